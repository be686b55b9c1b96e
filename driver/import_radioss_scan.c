/*
 * import_radioss_scan.c -- the first pass of the Radioss reader: the text
 * is scanned once, line by line; keyword lines choose the current block
 * (unsupported keywords are counted for the warning) and each data line is
 * parsed in fixed columns into the reader's growing arrays, which keep the
 * deck's raw ids and the line numbers for the resolution that follows.
 */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "import_radioss_internal.h"

const char *const ctd_rad_corner[8] = {"n1", "n2", "n3", "n4", "n5", "n6", "n7", "n8"};
const char *const ctd_rad_list_kw[6] = {"/SURF/PART",  "/SURF/GRSHEL",  "/GRNOD/NODE",
                                        "/GRNOD/PART", "/GRNOD/GRSHEL", "/GRSHEL/SHEL"};
const char *const ctd_rad_list_field[6] = {"part_id", "grshel_id", "node_id",
                                           "part_id", "grshel_id", "shell_id"};

/* The blocks (the kinds of data lines under a keyword). */
enum blk { B_NONE, B_SKIP, B_NODE, B_SHELL, B_SH3N, B_BRICK, B_PART, B_LIST, B_TITLE };

/* ---- Data lines -------------------------------------------------------- */

static int line_node(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    if (r->nn == r->capn) {
        size_t c = ctd_rad_next_cap(r->capn);
        if (ctd_rad_regrow(&r->nid, c, sizeof *r->nid) ||
            ctd_rad_regrow(&r->xyz, 3 * c, sizeof *r->xyz) ||
            ctd_rad_regrow(&r->nline, c, sizeof *r->nline))
            return ctd_rad_nomem(r, ln);
        r->capn = c;
    }
    size_t i = r->nn;
    int rc;
    static const char *const xyz[3] = {"x", "y", "z"};
    if ((rc = ctd_rad_need_id(r, ln, s, len, 0, "node_id", &r->nid[i])) != CT_OK)
        return rc;
    for (int k = 0; k < 3; k++)
        if ((rc = ctd_rad_opt_real(r, ln, s, len, 10 + 20 * k, xyz[k], &r->xyz[3 * i + k])) !=
            CT_OK)
            return rc;
    r->nline[i] = ln;
    r->nn++;
    return CT_OK;
}

/* An element line: its id, then n node ids in 10 columns each. */
static int elem_ids(ctd_rad_reader *r, int32_t ln, const char *s, int len, const char *idname,
                    int64_t *id, int n, int64_t *raw)
{
    int rc = ctd_rad_need_id(r, ln, s, len, 0, idname, id);
    for (int k = 0; k < n && rc == CT_OK; k++)
        rc = ctd_rad_need_id(r, ln, s, len, 10 + 10 * k, ctd_rad_corner[k], &raw[k]);
    return rc;
}

static int line_brick(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    if (r->nb == r->capb) {
        size_t c = ctd_rad_next_cap(r->capb);
        if (ctd_rad_regrow(&r->bid, c, sizeof *r->bid) ||
            ctd_rad_regrow(&r->bpart, c, sizeof *r->bpart) ||
            ctd_rad_regrow(&r->braw, 8 * c, sizeof *r->braw) ||
            ctd_rad_regrow(&r->bline, c, sizeof *r->bline))
            return ctd_rad_nomem(r, ln);
        r->capb = c;
    }
    size_t b = r->nb;
    int rc = elem_ids(r, ln, s, len, "brick_id", &r->bid[b], 8, r->braw + 8 * b);
    if (rc != CT_OK)
        return rc;
    r->bpart[b] = r->blk_id;
    r->bline[b] = ln;
    r->nb++;
    return CT_OK;
}

/* A /SHELL or /SH3N line (a triangle's n4 is its n3). */
static int line_shell(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    if (r->ns == r->caps) {
        size_t c = ctd_rad_next_cap(r->caps);
        if (ctd_rad_regrow(&r->sid, c, sizeof *r->sid) ||
            ctd_rad_regrow(&r->spart, c, sizeof *r->spart) ||
            ctd_rad_regrow(&r->sraw, 4 * c, sizeof *r->sraw) ||
            ctd_rad_regrow(&r->sline, c, sizeof *r->sline) ||
            ctd_rad_regrow(&r->skind, c, sizeof *r->skind))
            return ctd_rad_nomem(r, ln);
        r->caps = c;
    }
    size_t e = r->ns;
    int tri = r->blk == B_SH3N;
    int rc = elem_ids(r, ln, s, len, tri ? "sh3n_id" : "shell_id", &r->sid[e], tri ? 3 : 4,
                      r->sraw + 4 * e);
    if (rc != CT_OK)
        return rc;
    if (tri)
        r->sraw[4 * e + 3] = r->sraw[4 * e + 2];
    r->spart[e] = r->blk_id;
    r->sline[e] = ln;
    r->skind[e] = (int8_t)(tri ? CTD_SEG_SH3N : CTD_SEG_SHELL);
    r->ns++;
    return CT_OK;
}

/* The data line of a /PART after its title: prop_id mat_id. */
static int line_part(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    ctd_part *p = &r->part[r->np - 1];
    if (r->sub > 1)
        return CT_OK;
    static const char *const nm[2] = {"prop_id", "mat_id"};
    int64_t *v[2] = {&p->prop, &p->mat};
    for (int k = 0; k < 2; k++) {
        ctd_rad_fld f = ctd_rad_field(s, len, 10 * k, 10);
        if (ctd_rad_parse_int(f, v[k]) < 0 || *v[k] < 0)
            return ctd_rad_bad_field(r, ln, nm[k], 0, "a non-negative integer", f);
    }
    return CT_OK;
}

/* A line of ids of a list card after its title (zeros skipped). */
static int line_list(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    ctd_rad_list *l = &r->list[r->nl - 1];
    for (int k = 0; 10 * k < len; k++) {
        ctd_rad_fld f = ctd_rad_field(s, len, 10 * k, 10);
        int64_t v;
        int rc = ctd_rad_parse_int(f, &v);
        if (rc < 0 || v < 0)
            return ctd_rad_bad_field(r, ln, ctd_rad_list_field[l->type], k + 1,
                                     "a positive integer", f);
        if (v == 0)
            continue;
        if (l->n == l->cap) {
            size_t c = ctd_rad_next_cap(l->cap);
            if (ctd_rad_regrow(&l->ids, c, sizeof *l->ids) ||
                ctd_rad_regrow(&l->lines, c, sizeof *l->lines) ||
                ctd_rad_regrow(&l->fld, c, sizeof *l->fld))
                return ctd_rad_nomem(r, ln);
            l->cap = c;
        }
        l->ids[l->n] = v;
        l->lines[l->n] = ln;
        l->fld[l->n] = (int16_t)(k + 1);
        l->n++;
    }
    return CT_OK;
}

/* ---- Keywords ---------------------------------------------------------- */

static int add_unsupported(ctd_rad_reader *r, const char *name, int n)
{
    for (int i = 0; i < r->nun; i++)
        if ((int)strlen(r->un[i]) == n && !strncmp(r->un[i], name, (size_t)n)) {
            r->uncount[i]++;
            return CT_OK;
        }
    if (r->nun == r->capun) {
        int c = r->capun ? 2 * r->capun : 16;
        if (ctd_rad_regrow(&r->un, (size_t)c, sizeof *r->un) ||
            ctd_rad_regrow(&r->uncount, (size_t)c, sizeof *r->uncount))
            return CT_ERR_NOMEM;
        r->capun = c;
    }
    r->un[r->nun] = ctd_rad_dup_trim(name, n);
    if (!r->un[r->nun])
        return CT_ERR_NOMEM;
    r->uncount[r->nun++] = 1;
    return CT_OK;
}

/* Split "/A/B/12" into upper-case tokens; returns the count (at most 8). */
static int tokens(const char *s, int len, char tok[8][24])
{
    int nt = 0, i = 1;
    while (i <= len && nt < 8) {
        int j = i;
        while (j < len && s[j] != '/')
            j++;
        int n = j - i < 23 ? j - i : 23;
        for (int k = 0; k < n; k++)
            tok[nt][k] = (char)toupper((unsigned char)s[i + k]);
        tok[nt][n] = 0;
        nt++;
        i = j + 1;
    }
    return nt;
}

/* Room for one more element in the array *pp of n (capacity *cap). */
static int room_for_one(void *pp, size_t *cap, size_t n, size_t size)
{
    if (n < *cap)
        return CT_OK;
    size_t c = ctd_rad_next_cap(*cap);
    if (ctd_rad_regrow(pp, c, size))
        return CT_ERR_NOMEM;
    *cap = c;
    return CT_OK;
}

/* The block of a keyword from its tokens; *lt is the list type of a list
 * card, *nfix the number of tokens before the keyword's id (-1: /BEGIN). */
static int classify(char t[8][24], int nt, int *lt, int *nfix)
{
    *lt = -1;
    *nfix = 1;
    if (nt >= 1 && !strcmp(t[0], "NODE") && nt <= 2) {
        *nfix = nt; /* /NODE or /NODE/unit_id: no id required */
        return B_NODE;
    }
    if (nt >= 1 && !strcmp(t[0], "SHELL"))
        return B_SHELL;
    if (nt >= 1 && !strcmp(t[0], "SH3N"))
        return B_SH3N;
    if (nt >= 1 && !strcmp(t[0], "BRICK"))
        return B_BRICK;
    if (nt >= 1 && !strcmp(t[0], "PART"))
        return B_PART;
    *nfix = 2;
    if (nt >= 2 && !strcmp(t[0], "SURF") && !strcmp(t[1], "PART")) {
        *lt = CTD_RAD_L_SURF_PART;
        *nfix = nt >= 3 && !strcmp(t[2], "EXT") ? 3 : 2;
        return B_LIST;
    }
    if (nt >= 2 && !strcmp(t[0], "SURF") && !strcmp(t[1], "GRSHEL")) {
        *lt = CTD_RAD_L_SURF_GRSHEL;
        return B_LIST;
    }
    if (nt >= 2 && !strcmp(t[0], "GRNOD") &&
        (!strcmp(t[1], "NODE") || !strcmp(t[1], "PART") || !strcmp(t[1], "GRSHEL"))) {
        *lt = !strcmp(t[1], "NODE")   ? CTD_RAD_L_GRNOD_NODE
              : !strcmp(t[1], "PART") ? CTD_RAD_L_GRNOD_PART
                                      : CTD_RAD_L_GRNOD_GRSHEL;
        return B_LIST;
    }
    if (nt >= 2 && !strcmp(t[0], "GRSHEL") && !strcmp(t[1], "SHEL")) {
        *lt = CTD_RAD_L_GRSHEL_SHEL;
        return B_LIST;
    }
    *nfix = 1;
    if (nt == 1 && !strcmp(t[0], "TITLE"))
        return B_TITLE;
    *nfix = nt == 1 && !strcmp(t[0], "BEGIN") ? -1 : 0;
    return B_SKIP;
}

/* An unsupported keyword, counted under its name without the trailing
 * numeric ids: /MAT/PLAS_JOHNS/2 -> /MAT/PLAS_JOHNS. */
static int unsupported(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    int n = len;
    for (;;) {
        int j = n;
        while (j > 1 && isdigit((unsigned char)s[j - 1]))
            j--;
        if (j < n && j > 1 && s[j - 1] == '/')
            n = j - 1;
        else
            break;
    }
    return add_unsupported(r, s, n) == CT_OK ? CT_OK : ctd_rad_nomem(r, ln);
}

static int keyword(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    while (len > 0 && isspace((unsigned char)s[len - 1]))
        len--;
    snprintf(r->kw, sizeof r->kw, "%.*s", len, s);
    char t[8][24];
    int nt = tokens(s, len, t), lt, nfix;
    int blk = classify(t, nt, &lt, &nfix);
    r->blk = blk;
    r->sub = 0;
    r->blk_id = 0;
    if (blk == B_SKIP)
        return nfix == -1 ? CT_OK : unsupported(r, ln, s, len);
    if (blk == B_NODE) {
        r->saw_node = 1;
        return CT_OK;
    }
    if (blk == B_TITLE)
        return CT_OK;
    /* The keyword's own id: exactly one more token, a positive integer. */
    ctd_rad_fld f = {"", 0};
    if (nt == nfix + 1) {
        f.p = s + 1;
        for (int k = 0; k < nfix; k++)
            f.p = strchr(f.p, '/') + 1;
        f.n = (int)(s + len - f.p);
    }
    int64_t id = 0;
    if (nt != nfix + 1 || ctd_rad_parse_int(f, &id) != 0 || id <= 0)
        return ctd_rad_fail(r, CT_ERR_ARG, ln, "keyword %s: expected a positive id after %s/",
                            r->kw,
                            blk == B_LIST    ? ctd_rad_list_kw[lt]
                            : blk == B_PART  ? "/PART"
                            : blk == B_SHELL ? "/SHELL"
                            : blk == B_SH3N  ? "/SH3N"
                                             : "/BRICK");
    r->blk_id = id;
    if (blk == B_PART) {
        if (room_for_one(&r->part, &r->capp, r->np, sizeof *r->part))
            return ctd_rad_nomem(r, ln);
        ctd_part *p = &r->part[r->np++];
        memset(p, 0, sizeof *p);
        p->id = id;
        p->line = ln;
    } else if (blk == B_LIST) {
        if (room_for_one(&r->list, &r->capl, r->nl, sizeof *r->list))
            return ctd_rad_nomem(r, ln);
        ctd_rad_list *l = &r->list[r->nl++];
        memset(l, 0, sizeof *l);
        l->type = lt;
        l->id = id;
        l->line = ln;
    }
    return CT_OK;
}

/* ---- The scan ---------------------------------------------------------- */

/* Where the title line of the current block goes (/PART, list cards and
 * /TITLE have one, the first line under the keyword, kept even if blank). */
static char **title_slot(ctd_rad_reader *r)
{
    switch (r->blk) {
    case B_PART: return &r->part[r->np - 1].title;
    case B_LIST: return &r->list[r->nl - 1].title;
    case B_TITLE: return &r->title;
    default: return NULL;
    }
}

/* One data line of the current block. */
static int data_line(ctd_rad_reader *r, int32_t ln, const char *s, int len)
{
    char **title = r->sub == 0 ? title_slot(r) : NULL;
    if (title) {
        free(*title);
        *title = ctd_rad_dup_trim(s, len);
        return *title ? CT_OK : ctd_rad_nomem(r, ln);
    }
    switch (r->blk) {
    case B_NODE: return line_node(r, ln, s, len);
    case B_SHELL:
    case B_SH3N: return line_shell(r, ln, s, len);
    case B_BRICK: return line_brick(r, ln, s, len);
    case B_PART: return line_part(r, ln, s, len);
    case B_LIST: return line_list(r, ln, s, len);
    default: return CT_OK;
    }
}

int ctd_rad_scan(ctd_rad_reader *r, const char *buf, size_t size, int32_t *nlines)
{
    const char *p = buf, *end = buf + size;
    int64_t ln = 0;
    while (p < end) {
        const char *q = memchr(p, '\n', (size_t)(end - p));
        if (!q)
            q = end;
        ln++;
        if (ln >= INT32_MAX)
            return ctd_rad_fail(r, CT_ERR_TOOBIG, -1, "more than %d lines", INT32_MAX - 1);
        size_t n = (size_t)(q - p);
        if (n > 0 && p[n - 1] == '\r')
            n--;
        if (n > CTD_DECK_MAXLINE)
            return ctd_rad_fail(r, CT_ERR_ARG, ln,
                                "line of %zu characters, longer than the %d allowed", n,
                                CTD_DECK_MAXLINE);
        /* A NUL byte is not text: the keyword and title code works on C
         * strings, which would end there (and a keyword's id would then be
         * looked for past its end). */
        const char *nul = memchr(p, '\0', n);
        if (nul)
            return ctd_rad_fail(r, CT_ERR_ARG, ln,
                                "a NUL byte in column %d (not a text deck)",
                                (int)(nul - p) + 1);
        const char *s = p;
        int len = (int)n, rc;
        p = q + 1;
        if (len > 0 && (s[0] == '#' || s[0] == '$')) {
            if (len >= 8 && !strncasecmp(s, "#include", 8) &&
                add_unsupported(r, "#include", 8) != CT_OK)
                return ctd_rad_nomem(r, ln);
            continue;
        }
        if (len > 0 && s[0] == '/') {
            int e = len;
            while (e > 0 && isspace((unsigned char)s[e - 1]))
                e--;
            if (e == 4 && !strncasecmp(s, "/END", 4))
                break;
            if ((rc = keyword(r, (int32_t)ln, s, len)) != CT_OK)
                return rc;
            continue;
        }
        int blank = 1;
        for (int i = 0; i < len && blank; i++)
            blank = isspace((unsigned char)s[i]) != 0;
        int titled = r->blk == B_PART || r->blk == B_LIST || r->blk == B_TITLE;
        if (blank && !(titled && r->sub == 0))
            continue;
        if ((rc = data_line(r, (int32_t)ln, s, len)) != CT_OK)
            return rc;
        r->sub++;
    }
    *nlines = (int32_t)ln;
    return CT_OK;
}

void ctd_rad_reader_free(ctd_rad_reader *r)
{
    free(r->nid); free(r->xyz); free(r->nline);
    free(r->sid); free(r->spart); free(r->sraw); free(r->sline); free(r->skind);
    free(r->bid); free(r->bpart); free(r->braw); free(r->bline);
    for (size_t p = 0; p < r->np; p++)
        free(r->part[p].title);
    free(r->part);
    for (size_t i = 0; i < r->nl; i++) {
        free(r->list[i].title);
        free(r->list[i].ids);
        free(r->list[i].lines);
        free(r->list[i].fld);
    }
    free(r->list);
    for (int i = 0; i < r->nun; i++)
        free(r->un[i]);
    free(r->un);
    free(r->uncount);
    free(r->title);
}
