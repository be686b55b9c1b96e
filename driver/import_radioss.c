/*
 * import_radioss.c -- the Radioss block-format reader (see import_radioss.h).
 *
 * The file is read into memory and scanned once, line by line; each data
 * line is parsed in fixed columns into growing arrays that keep the deck's
 * ids and the line numbers. References (element nodes, parts, shells,
 * groups) are resolved afterwards through open-addressing hash maps, so the
 * whole read is O(file size). Errors name the file, the line and the field.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "import_radioss.h"

/* ---- Small tools ------------------------------------------------------- */

/* Grow a malloc'd array to hold `cap` elements (contents kept). */
static int regrow(void *pp, size_t cap, size_t size)
{
    void **p = pp;
    void *q = realloc(*p, cap * size);
    if (!q)
        return CT_ERR_NOMEM;
    *p = q;
    return CT_OK;
}

static size_t next_cap(size_t cap) { return cap ? cap + cap / 2 + 16 : 256; }

static char *dup_trim(const char *s, int n)
{
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        n--;
    while (n > 0 && isspace((unsigned char)*s)) {
        s++;
        n--;
    }
    char *t = malloc((size_t)n + 1);
    if (t) {
        memcpy(t, s, (size_t)n);
        t[n] = 0;
    }
    return t;
}

static int cmp_idx(const void *a, const void *b)
{
    ct_idx x = *(const ct_idx *)a, y = *(const ct_idx *)b;
    return (x > y) - (x < y);
}

/* An open-addressing map from positive 64-bit ids to indices. */
typedef struct idmap {
    size_t mask;
    int64_t *key; /* 0 = empty */
    ct_idx *val;
} idmap;

static int map_init(idmap *m, size_t n)
{
    size_t cap = 64;
    while (cap < 2 * n + 16)
        cap *= 2;
    m->mask = cap - 1;
    m->key = calloc(cap, sizeof *m->key);
    m->val = malloc(cap * sizeof *m->val);
    return m->key && m->val ? CT_OK : CT_ERR_NOMEM;
}

static void map_free(idmap *m)
{
    if (!m)
        return;
    free(m->key);
    free(m->val);
    m->key = NULL;
    m->val = NULL;
}

static size_t map_slot(const idmap *m, int64_t k)
{
    uint64_t h = (uint64_t)k;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    h ^= h >> 33;
    size_t i = (size_t)h & m->mask;
    while (m->key[i] != 0 && m->key[i] != k)
        i = (i + 1) & m->mask;
    return i;
}

/* Insert k -> v; returns the earlier value when k is already present, else
 * -1. The map must have been sized for all insertions. */
static ct_idx map_put(idmap *m, int64_t k, ct_idx v)
{
    size_t i = map_slot(m, k);
    if (m->key[i] == k)
        return m->val[i];
    m->key[i] = k;
    m->val[i] = v;
    return -1;
}

static ct_idx map_get(const idmap *m, int64_t k)
{
    if (!m || !m->key || k == 0)
        return -1;
    size_t i = map_slot(m, k);
    return m->key[i] == k ? m->val[i] : -1;
}

/* ---- Reader state ------------------------------------------------------ */

enum blk { B_NONE, B_SKIP, B_NODE, B_SHELL, B_SH3N, B_BRICK, B_PART, B_LIST, B_TITLE };
enum lst { L_SURF_PART, L_SURF_GRSHEL, L_GRNOD_NODE, L_GRNOD_PART, L_GRNOD_GRSHEL,
           L_GRSHEL_SHEL };
static const char *const list_kw[] = {"/SURF/PART", "/SURF/GRSHEL", "/GRNOD/NODE",
                                      "/GRNOD/PART", "/GRNOD/GRSHEL", "/GRSHEL/SHEL"};
static const char *const list_field[] = {"part_id", "grshel_id", "node_id",
                                         "part_id", "grshel_id", "shell_id"};

/* A list card as read: its ids, each with its line and field number. */
typedef struct rlist {
    int type;
    int64_t id;
    char *title;
    int32_t line;
    size_t n, cap;
    int64_t *ids;
    int32_t *lines;
    int16_t *fld;
} rlist;

typedef struct rd {
    const char *path;
    ct_diag *diag;
    char kw[48];  /* the current keyword, for messages */
    int blk, sub; /* the current block and its data lines so far */
    int64_t blk_id;
    int saw_node;
    /* Nodes. */
    size_t nn, capn;
    int64_t *nid;
    double *xyz;
    int32_t *nline;
    /* Shell and triangle elements (raw node ids, 4 per element). */
    size_t ns, caps;
    int64_t *sid, *spart, *sraw;
    int32_t *sline;
    int8_t *skind;
    /* Bricks (raw node ids, 8 per brick). */
    size_t nb, capb;
    int64_t *bid, *bpart, *braw;
    int32_t *bline;
    /* Parts and lists. */
    size_t np, capp;
    ctd_part *part;
    size_t nl, capl;
    rlist *list;
    /* Unsupported keywords. */
    int nun, capun;
    char **un;
    int *uncount;
    char *title;
} rd;

static const char *short_path(const char *p)
{
    size_t n = strlen(p);
    return n > 100 ? p + n - 100 : p;
}

/* Fill diag with "FILE:LINE: what". */
static int rfail(rd *r, int code, int64_t line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int rfail(rd *r, int code, int64_t line, const char *fmt, ...)
{
    if (r->diag) {
        char what[224];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(what, sizeof what, fmt, ap);
        va_end(ap);
        r->diag->code = code;
        r->diag->index = line;
        if (line > 0)
            snprintf(r->diag->msg, sizeof r->diag->msg, "%s:%lld: %s", short_path(r->path),
                     (long long)line, what);
        else
            snprintf(r->diag->msg, sizeof r->diag->msg, "%s: %s", short_path(r->path), what);
    }
    return code;
}

/* ---- Fields ------------------------------------------------------------ */

typedef struct fld {
    const char *p;
    int n;
} fld;

/* Columns [start, start + width) of a line, trimmed of blanks. */
static fld field(const char *s, int len, int start, int width)
{
    fld f = {s, 0};
    if (start >= len)
        return f;
    int a = start, b = start + width < len ? start + width : len;
    while (a < b && isspace((unsigned char)s[a]))
        a++;
    while (b > a && isspace((unsigned char)s[b - 1]))
        b--;
    f.p = s + a;
    f.n = b - a;
    return f;
}

/* An integer: 0 read, 1 blank (v = 0), -1 malformed. */
static int parse_int(fld f, int64_t *v)
{
    *v = 0;
    if (f.n == 0)
        return 1;
    int i = 0, neg = 0;
    if (f.p[0] == '+' || f.p[0] == '-') {
        neg = f.p[0] == '-';
        i = 1;
    }
    if (i == f.n || f.n - i > 18)
        return -1;
    int64_t x = 0;
    for (; i < f.n; i++) {
        if (f.p[i] < '0' || f.p[i] > '9')
            return -1;
        x = 10 * x + (f.p[i] - '0');
    }
    *v = neg ? -x : x;
    return 0;
}

/* A real in Fortran forms: 0 read, 1 blank (v = 0), -1 malformed, -2 NaN or
 * infinite (written so, or overflowing). */
static int parse_real(fld f, double *v)
{
    *v = 0;
    if (f.n == 0)
        return 1;
    if (f.n > 64)
        return -1;
    char b[80];
    int k = 0, expo = 0, i = 0;
    if (f.p[0] == '+' || f.p[0] == '-')
        b[k++] = f.p[i++];
    int rest = f.n - i;
    if ((rest == 3 && !strncasecmp(f.p + i, "nan", 3)) ||
        (rest == 3 && !strncasecmp(f.p + i, "inf", 3)) ||
        (rest == 8 && !strncasecmp(f.p + i, "infinity", 8)))
        return -2;
    for (; i < f.n; i++) {
        char c = f.p[i];
        if ((c >= '0' && c <= '9') || c == '.') {
            b[k++] = c;
        } else if (c == '+' || c == '-') {
            /* 1.5+01 is 1.5E+01 (a sign after a digit starts an exponent). */
            if (k > 0 && !expo && (isdigit((unsigned char)b[k - 1]) || b[k - 1] == '.')) {
                b[k++] = 'e';
                expo = 1;
            }
            b[k++] = c;
        } else if (c == 'e' || c == 'E' || c == 'd' || c == 'D') {
            if (expo)
                return -1;
            b[k++] = 'e';
            expo = 1;
        } else {
            return -1;
        }
    }
    b[k] = 0;
    char *end;
    errno = 0;
    double d = strtod(b, &end);
    if (end != b + k || k == 0)
        return -1;
    if (!isfinite(d) || !isfinite((ct_real)d))
        return -2;
    *v = d;
    return 0;
}

/* A required positive id in columns [start, start + 10). */
static int need_id(rd *r, int32_t line, const char *s, int len, int start, const char *name,
                   int64_t *v)
{
    fld f = field(s, len, start, 10);
    int rc = parse_int(f, v);
    if (rc == 1)
        return rfail(r, CT_ERR_ARG, line, "field '%s' of %s: missing (columns %d-%d are blank)",
                     name, r->kw, start + 1, start + 10);
    if (rc < 0 || *v <= 0)
        return rfail(r, CT_ERR_ARG, line, "field '%s' of %s: expected a positive integer, got '%.*s'",
                     name, r->kw, f.n > 40 ? 40 : f.n, f.p);
    return CT_OK;
}

/* An optional real in columns [start, start + 20) (blank = 0). */
static int opt_real(rd *r, int32_t line, const char *s, int len, int start, const char *name,
                    double *v)
{
    fld f = field(s, len, start, 20);
    int rc = parse_real(f, v);
    if (rc == -1)
        return rfail(r, CT_ERR_ARG, line, "field '%s' of %s: expected a number, got '%.*s'",
                     name, r->kw, f.n > 40 ? 40 : f.n, f.p);
    if (rc == -2)
        return rfail(r, CT_ERR_NONFINITE, line,
                     "field '%s' of %s: the coordinate '%.*s' is not finite", name, r->kw,
                     f.n > 40 ? 40 : f.n, f.p);
    return CT_OK;
}

/* ---- Block lines ------------------------------------------------------- */

static const char *const corner[8] = {"n1", "n2", "n3", "n4", "n5", "n6", "n7", "n8"};

static int line_node(rd *r, int32_t ln, const char *s, int len)
{
    if (r->nn == r->capn) {
        size_t c = next_cap(r->capn);
        if (regrow(&r->nid, c, sizeof *r->nid) || regrow(&r->xyz, 3 * c, sizeof *r->xyz) ||
            regrow(&r->nline, c, sizeof *r->nline))
            return rfail(r, CT_ERR_NOMEM, ln, "out of memory");
        r->capn = c;
    }
    size_t i = r->nn;
    int rc;
    static const char *const xyz[3] = {"x", "y", "z"};
    if ((rc = need_id(r, ln, s, len, 0, "node_id", &r->nid[i])) != CT_OK)
        return rc;
    for (int k = 0; k < 3; k++)
        if ((rc = opt_real(r, ln, s, len, 10 + 20 * k, xyz[k], &r->xyz[3 * i + k])) != CT_OK)
            return rc;
    r->nline[i] = ln;
    r->nn++;
    return CT_OK;
}

static int line_elem(rd *r, int32_t ln, const char *s, int len)
{
    static const char *const idname[3] = {"shell_id", "sh3n_id", "brick_id"};
    if (r->blk == B_BRICK) {
        if (r->nb == r->capb) {
            size_t c = next_cap(r->capb);
            if (regrow(&r->bid, c, sizeof *r->bid) || regrow(&r->bpart, c, sizeof *r->bpart) ||
                regrow(&r->braw, 8 * c, sizeof *r->braw) ||
                regrow(&r->bline, c, sizeof *r->bline))
                return rfail(r, CT_ERR_NOMEM, ln, "out of memory");
            r->capb = c;
        }
        size_t b = r->nb;
        int rc = need_id(r, ln, s, len, 0, idname[2], &r->bid[b]);
        for (int k = 0; k < 8 && rc == CT_OK; k++)
            rc = need_id(r, ln, s, len, 10 + 10 * k, corner[k], &r->braw[8 * b + k]);
        if (rc != CT_OK)
            return rc;
        r->bpart[b] = r->blk_id;
        r->bline[b] = ln;
        r->nb++;
        return CT_OK;
    }
    if (r->ns == r->caps) {
        size_t c = next_cap(r->caps);
        if (regrow(&r->sid, c, sizeof *r->sid) || regrow(&r->spart, c, sizeof *r->spart) ||
            regrow(&r->sraw, 4 * c, sizeof *r->sraw) || regrow(&r->sline, c, sizeof *r->sline) ||
            regrow(&r->skind, c, sizeof *r->skind))
            return rfail(r, CT_ERR_NOMEM, ln, "out of memory");
        r->caps = c;
    }
    size_t e = r->ns;
    int tri = r->blk == B_SH3N;
    int rc = need_id(r, ln, s, len, 0, idname[tri], &r->sid[e]);
    for (int k = 0; k < (tri ? 3 : 4) && rc == CT_OK; k++)
        rc = need_id(r, ln, s, len, 10 + 10 * k, corner[k], &r->sraw[4 * e + k]);
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

static int line_part(rd *r, int32_t ln, const char *s, int len)
{
    ctd_part *p = &r->part[r->np - 1];
    if (r->sub == 0) {
        p->title = dup_trim(s, len);
        return p->title ? CT_OK : rfail(r, CT_ERR_NOMEM, ln, "out of memory");
    }
    if (r->sub > 1)
        return CT_OK;
    static const char *const nm[2] = {"prop_id", "mat_id"};
    int64_t *v[2] = {&p->prop, &p->mat};
    for (int k = 0; k < 2; k++) {
        fld f = field(s, len, 10 * k, 10);
        if (parse_int(f, v[k]) < 0 || *v[k] < 0)
            return rfail(r, CT_ERR_ARG, ln,
                         "field '%s' of %s: expected a non-negative integer, got '%.*s'", nm[k],
                         r->kw, f.n > 40 ? 40 : f.n, f.p);
    }
    return CT_OK;
}

static int line_list(rd *r, int32_t ln, const char *s, int len)
{
    rlist *l = &r->list[r->nl - 1];
    if (r->sub == 0) {
        l->title = dup_trim(s, len);
        return l->title ? CT_OK : rfail(r, CT_ERR_NOMEM, ln, "out of memory");
    }
    for (int k = 0; 10 * k < len; k++) {
        fld f = field(s, len, 10 * k, 10);
        int64_t v;
        int rc = parse_int(f, &v);
        if (rc < 0 || v < 0)
            return rfail(r, CT_ERR_ARG, ln,
                         "field '%s' (number %d) of %s: expected a positive integer, got '%.*s'",
                         list_field[l->type], k + 1, r->kw, f.n > 40 ? 40 : f.n, f.p);
        if (v == 0)
            continue;
        if (l->n == l->cap) {
            size_t c = next_cap(l->cap);
            if (regrow(&l->ids, c, sizeof *l->ids) || regrow(&l->lines, c, sizeof *l->lines) ||
                regrow(&l->fld, c, sizeof *l->fld))
                return rfail(r, CT_ERR_NOMEM, ln, "out of memory");
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

static int add_unsupported(rd *r, const char *name, int n)
{
    for (int i = 0; i < r->nun; i++)
        if ((int)strlen(r->un[i]) == n && !strncmp(r->un[i], name, (size_t)n)) {
            r->uncount[i]++;
            return CT_OK;
        }
    if (r->nun == r->capun) {
        int c = r->capun ? 2 * r->capun : 16;
        if (regrow(&r->un, (size_t)c, sizeof *r->un) ||
            regrow(&r->uncount, (size_t)c, sizeof *r->uncount))
            return CT_ERR_NOMEM;
        r->capun = c;
    }
    r->un[r->nun] = dup_trim(name, n);
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

static int keyword(rd *r, int32_t ln, const char *s, int len)
{
    while (len > 0 && isspace((unsigned char)s[len - 1]))
        len--;
    snprintf(r->kw, sizeof r->kw, "%.*s", len, s);
    char t[8][24];
    int nt = tokens(s, len, t);
    int blk = B_SKIP, lt = -1, nfix = 0;
    if (nt >= 1 && !strcmp(t[0], "NODE") && nt <= 2) {
        blk = B_NODE;
        nfix = nt; /* /NODE or /NODE/unit_id: no id required */
    } else if (nt >= 1 && !strcmp(t[0], "SHELL")) {
        blk = B_SHELL;
        nfix = 1;
    } else if (nt >= 1 && !strcmp(t[0], "SH3N")) {
        blk = B_SH3N;
        nfix = 1;
    } else if (nt >= 1 && !strcmp(t[0], "BRICK")) {
        blk = B_BRICK;
        nfix = 1;
    } else if (nt >= 1 && !strcmp(t[0], "PART")) {
        blk = B_PART;
        nfix = 1;
    } else if (nt >= 2 && !strcmp(t[0], "SURF") && !strcmp(t[1], "PART")) {
        blk = B_LIST;
        lt = L_SURF_PART;
        nfix = nt >= 3 && !strcmp(t[2], "EXT") ? 3 : 2;
    } else if (nt >= 2 && !strcmp(t[0], "SURF") && !strcmp(t[1], "GRSHEL")) {
        blk = B_LIST;
        lt = L_SURF_GRSHEL;
        nfix = 2;
    } else if (nt >= 2 && !strcmp(t[0], "GRNOD") &&
               (!strcmp(t[1], "NODE") || !strcmp(t[1], "PART") || !strcmp(t[1], "GRSHEL"))) {
        blk = B_LIST;
        lt = !strcmp(t[1], "NODE") ? L_GRNOD_NODE
             : !strcmp(t[1], "PART") ? L_GRNOD_PART
                                     : L_GRNOD_GRSHEL;
        nfix = 2;
    } else if (nt >= 2 && !strcmp(t[0], "GRSHEL") && !strcmp(t[1], "SHEL")) {
        blk = B_LIST;
        lt = L_GRSHEL_SHEL;
        nfix = 2;
    } else if (nt == 1 && !strcmp(t[0], "TITLE")) {
        blk = B_TITLE;
        nfix = 1;
    } else if (nt == 1 && !strcmp(t[0], "BEGIN")) {
        blk = B_SKIP;
        nfix = -1;
    }
    r->blk = blk;
    r->sub = 0;
    r->blk_id = 0;
    if (blk == B_SKIP) {
        if (nfix == -1)
            return CT_OK;
        /* The name without its trailing numeric ids: /MAT/PLAS_JOHNS/2 ->
         * /MAT/PLAS_JOHNS. */
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
        return add_unsupported(r, s, n) == CT_OK ? CT_OK
                                                  : rfail(r, CT_ERR_NOMEM, ln, "out of memory");
    }
    if (blk == B_NODE) {
        r->saw_node = 1;
        return CT_OK;
    }
    if (blk == B_TITLE)
        return CT_OK;
    /* The keyword's own id: exactly one more token, a positive integer. */
    fld f = {"", 0};
    if (nt == nfix + 1) {
        f.p = s + 1;
        for (int k = 0; k < nfix; k++)
            f.p = strchr(f.p, '/') + 1;
        f.n = (int)(s + len - f.p);
    }
    int64_t id = 0;
    if (nt != nfix + 1 || parse_int(f, &id) != 0 || id <= 0)
        return rfail(r, CT_ERR_ARG, ln, "keyword %s: expected a positive id after %s/", r->kw,
                     blk == B_LIST ? list_kw[lt] : blk == B_PART ? "/PART"
                                                 : blk == B_SHELL ? "/SHELL"
                                                 : blk == B_SH3N ? "/SH3N"
                                                                 : "/BRICK");
    r->blk_id = id;
    if (blk == B_PART) {
        if (r->np == r->capp) {
            size_t c = next_cap(r->capp);
            if (regrow(&r->part, c, sizeof *r->part))
                return rfail(r, CT_ERR_NOMEM, ln, "out of memory");
            r->capp = c;
        }
        ctd_part *p = &r->part[r->np++];
        memset(p, 0, sizeof *p);
        p->id = id;
        p->line = ln;
    } else if (blk == B_LIST) {
        if (r->nl == r->capl) {
            size_t c = next_cap(r->capl);
            if (regrow(&r->list, c, sizeof *r->list))
                return rfail(r, CT_ERR_NOMEM, ln, "out of memory");
            r->capl = c;
        }
        rlist *l = &r->list[r->nl++];
        memset(l, 0, sizeof *l);
        l->type = lt;
        l->id = id;
        l->line = ln;
    }
    return CT_OK;
}

/* ---- The scan ---------------------------------------------------------- */

static int scan(rd *r, const char *buf, size_t size, int32_t *nlines)
{
    const char *p = buf, *end = buf + size;
    int64_t ln = 0;
    while (p < end) {
        const char *q = memchr(p, '\n', (size_t)(end - p));
        if (!q)
            q = end;
        ln++;
        if (ln >= INT32_MAX)
            return rfail(r, CT_ERR_TOOBIG, -1, "more than %d lines", INT32_MAX - 1);
        size_t n = (size_t)(q - p);
        if (n > 0 && p[n - 1] == '\r')
            n--;
        if (n > CTD_DECK_MAXLINE)
            return rfail(r, CT_ERR_ARG, ln, "line of %zu characters, longer than the %d allowed",
                         n, CTD_DECK_MAXLINE);
        const char *s = p;
        int len = (int)n;
        p = q + 1;
        int rc = CT_OK;
        if (len > 0 && (s[0] == '#' || s[0] == '$')) {
            if (len >= 8 && !strncasecmp(s, "#include", 8) &&
                add_unsupported(r, "#include", 8) != CT_OK)
                return rfail(r, CT_ERR_NOMEM, ln, "out of memory");
            continue;
        }
        if (len > 0 && s[0] == '/') {
            int e = len;
            while (e > 0 && isspace((unsigned char)s[e - 1]))
                e--;
            if (e == 4 && !strncasecmp(s, "/END", 4))
                break;
            rc = keyword(r, (int32_t)ln, s, len);
            if (rc != CT_OK)
                return rc;
            continue;
        }
        int blank = 1;
        for (int i = 0; i < len && blank; i++)
            blank = isspace((unsigned char)s[i]) != 0;
        int titled = r->blk == B_PART || r->blk == B_LIST || r->blk == B_TITLE;
        if (blank && !(titled && r->sub == 0))
            continue;
        switch (r->blk) {
        case B_NODE: rc = line_node(r, (int32_t)ln, s, len); break;
        case B_SHELL:
        case B_SH3N:
        case B_BRICK: rc = line_elem(r, (int32_t)ln, s, len); break;
        case B_PART: rc = line_part(r, (int32_t)ln, s, len); break;
        case B_LIST: rc = line_list(r, (int32_t)ln, s, len); break;
        case B_TITLE:
            if (r->sub == 0) {
                free(r->title);
                r->title = dup_trim(s, len);
                if (!r->title)
                    rc = rfail(r, CT_ERR_NOMEM, ln, "out of memory");
            }
            break;
        default: break;
        }
        if (rc != CT_OK)
            return rc;
        r->sub++;
    }
    *nlines = (int32_t)ln;
    return CT_OK;
}

/* ---- Outer faces of bricks --------------------------------------------- */

static const int8_t hexface[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

/* The corners of a face with repeated corners collapsed; returns how many
 * distinct corners remain (3 or 4), or 0 when it is no face. */
static int face_corners(const ct_idx *c8, int l, ct_idx w[4])
{
    int m = 0;
    for (int i = 0; i < 4; i++) {
        ct_idx v = c8[hexface[l][i]];
        if (m == 0 || w[m - 1] != v)
            w[m++] = v;
    }
    if (m > 1 && w[m - 1] == w[0])
        m--;
    for (int i = 1; i < m; i++)
        for (int j = 0; j < i; j++)
            if (w[i] == w[j])
                return 0;
    if (m < 3)
        return 0;
    if (m == 3)
        w[3] = w[2];
    return m;
}

static int key_less(const ct_idx *a, const ct_idx *b)
{
    for (int i = 0; i < 4; i++)
        if (a[i] != b[i])
            return a[i] < b[i];
    return 0;
}

void ctd_faces_destroy(ctd_faces *f)
{
    if (!f)
        return;
    ct_free(f->node);
    ct_free(f->brick);
    ct_free(f->local);
    memset(f, 0, sizeof *f);
}

int ctd_brick_outer_faces(ct_idx nnode, const ct_real *x, const ct_real *y, const ct_real *z,
                          ct_idx nbrick, const ct_idx *conn, const unsigned char *sel,
                          ctd_faces *out, ct_diag *diag)
{
    ct_diag dummy;
    if (!diag)
        diag = &dummy;
    if (!out || nnode < 0 || nbrick < 0 || (nbrick > 0 && (!conn || !x || !y || !z))) {
        diag->code = CT_ERR_ARG;
        diag->index = -1;
        snprintf(diag->msg, sizeof diag->msg, "ctd_brick_outer_faces: a NULL array or a negative count.");
        return CT_ERR_ARG;
    }
    memset(out, 0, sizeof *out);
    if ((int64_t)nbrick * 6 > INT32_MAX) {
        diag->code = CT_ERR_TOOBIG;
        diag->index = -1;
        snprintf(diag->msg, sizeof diag->msg, "%ld bricks have too many faces for a 32-bit index.",
                 (long)nbrick);
        return CT_ERR_TOOBIG;
    }
    for (int64_t k = 0; k < 8 * (int64_t)nbrick; k++)
        if (conn[k] < 0 || conn[k] >= nnode) {
            diag->code = CT_ERR_RANGE;
            diag->index = k / 8;
            snprintf(diag->msg, sizeof diag->msg, "brick %ld: node %d = %ld is out of range [0, %ld).",
                     (long)(k / 8), (int)(k % 8) + 1, (long)conn[k], (long)nnode);
            return CT_ERR_RANGE;
        }
    ct_idx nslot = 6 * nbrick;
    ct_idx *key = malloc(((size_t)nslot * 4 + 1) * sizeof *key);
    ct_idx *cnt = calloc((size_t)nnode + 2, sizeof *cnt);
    ct_idx *order = malloc(((size_t)nslot + 1) * sizeof *order);
    unsigned char *outer = calloc((size_t)nslot + 1, 1);
    int rc = CT_ERR_NOMEM;
    if (!key || !cnt || !order || !outer)
        goto done;
    /* Sorted keys of the faces (a triangle's first entry is -1), bucketed by
     * their largest node with a counting sort. */
    for (ct_idx b = 0; b < nbrick; b++)
        for (int l = 0; l < 6; l++) {
            ct_idx *k = key + 4 * (6 * b + l), w[4];
            int m = (!sel || sel[b]) ? face_corners(conn + 8 * (int64_t)b, l, w) : 0;
            if (m == 0) {
                k[3] = -1;
                continue;
            }
            k[0] = m == 3 ? -1 : w[3];
            k[1] = w[0];
            k[2] = w[1];
            k[3] = w[2];
            for (int i = 1; i < 4; i++)
                for (int j = i; j > 0 && k[j] < k[j - 1]; j--) {
                    ct_idx t = k[j];
                    k[j] = k[j - 1];
                    k[j - 1] = t;
                }
            cnt[k[3] + 1]++;
        }
    for (ct_idx i = 0; i < nnode; i++)
        cnt[i + 1] += cnt[i];
    for (ct_idx f = 0; f < nslot; f++)
        if (key[4 * f + 3] >= 0)
            order[cnt[key[4 * f + 3]]++] = f;
    /* cnt[i] is now the end of bucket i; sort each bucket (few faces share
     * a largest node) and mark the keys that occur once. */
    ct_idx lo = 0;
    for (ct_idx i = 0; i < nnode; i++) {
        ct_idx hi = cnt[i];
        for (ct_idx a = lo + 1; a < hi; a++)
            for (ct_idx j = a; j > lo && key_less(key + 4 * order[j], key + 4 * order[j - 1]);
                 j--) {
                ct_idx t = order[j];
                order[j] = order[j - 1];
                order[j - 1] = t;
            }
        for (ct_idx a = lo; a < hi;) {
            ct_idx e = a + 1;
            while (e < hi && !memcmp(key + 4 * order[e], key + 4 * order[a], 4 * sizeof *key))
                e++;
            if (e == a + 1)
                outer[order[a]] = 1;
            a = e;
        }
        lo = hi;
    }
    ct_idx n = 0;
    for (ct_idx f = 0; f < nslot; f++)
        n += outer[f];
    out->node = ct_calloc(4 * (size_t)n, sizeof(ct_idx));
    out->brick = ct_calloc((size_t)n, sizeof(ct_idx));
    out->local = ct_calloc((size_t)n, sizeof(int8_t));
    if (!out->node || !out->brick || !out->local) {
        ctd_faces_destroy(out);
        goto done;
    }
    ct_idx j = 0;
    for (ct_idx f = 0; f < nslot; f++) {
        if (!outer[f])
            continue;
        ct_idx b = f / 6, w[4];
        int l = f % 6, m = face_corners(conn + 8 * (int64_t)b, l, w);
        /* Outward: the normal points away from the brick's centroid. */
        double c[3] = {0, 0, 0}, fc[3] = {0, 0, 0}, p[4][3];
        for (int i = 0; i < 8; i++) {
            ct_idx v = conn[8 * (int64_t)b + i];
            c[0] += x[v] / 8;
            c[1] += y[v] / 8;
            c[2] += z[v] / 8;
        }
        for (int i = 0; i < 4; i++) {
            p[i][0] = x[w[i]];
            p[i][1] = y[w[i]];
            p[i][2] = z[w[i]];
            for (int d = 0; d < 3 && i < m; d++)
                fc[d] += p[i][d] / m;
        }
        double u[3], v[3];
        for (int d = 0; d < 3; d++) {
            u[d] = m == 4 ? p[2][d] - p[0][d] : p[1][d] - p[0][d];
            v[d] = m == 4 ? p[3][d] - p[1][d] : p[2][d] - p[0][d];
        }
        double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2],
               nz = u[0] * v[1] - u[1] * v[0];
        if (nx * (fc[0] - c[0]) + ny * (fc[1] - c[1]) + nz * (fc[2] - c[2]) < 0) {
            ct_idx t = w[1];
            w[1] = w[m - 1];
            w[m - 1] = t;
            if (m == 3)
                w[3] = w[2];
        }
        memcpy(out->node + 4 * j, w, sizeof w);
        out->brick[j] = b;
        out->local[j] = (int8_t)l;
        j++;
    }
    out->n = n;
    rc = CT_OK;
done:
    free(key);
    free(cnt);
    free(order);
    free(outer);
    if (rc == CT_ERR_NOMEM) {
        diag->code = rc;
        diag->index = -1;
        snprintf(diag->msg, sizeof diag->msg, "Out of memory in ctd_brick_outer_faces.");
    }
    return rc;
}

/* ---- Resolution -------------------------------------------------------- */

/* Resolution state: the maps and the arrays being built. */
typedef struct res {
    idmap nodes, shells, parts, grshel;
    ct_nodes nd;
    /* Segments (element segments, then brick faces). */
    size_t nseg, capseg;
    ct_idx *sn; /* 4 per segment */
    int64_t *selem, *spart;
    int8_t *skind, *sface;
    int32_t *sline;
    ct_idx *spk;        /* dense part index of each element segment */
    ct_idx *bnode;      /* resolved brick nodes */
    ct_idx *bpk;        /* dense part index of each brick */
    ct_idx *faceseg;    /* [6 nb] segment of a brick face, or -1 */
    int64_t *pk_id;     /* dense part ids */
    ct_idx *pk_soff, *pk_seg; /* element segments of each dense part (CSR) */
    ct_idx *pk_boff, *pk_brk; /* bricks of each dense part (CSR) */
    unsigned char *pk_brick;
    size_t npk;
    ct_idx **gseg;      /* resolved /GRSHEL lists (segments) */
    ct_idx *gsegn;
    unsigned char *mark; /* per dense part */
    int32_t *stamp;      /* per node or segment */
    int32_t gen;
} res;

static void res_free(res *z, size_t nl)
{
    map_free(&z->nodes);
    map_free(&z->shells);
    map_free(&z->parts);
    map_free(&z->grshel);
    ct_nodes_destroy(&z->nd);
    free(z->sn); free(z->selem); free(z->spart); free(z->skind); free(z->sface);
    free(z->sline); free(z->spk); free(z->bnode); free(z->bpk); free(z->faceseg);
    free(z->pk_id); free(z->pk_brick);
    free(z->pk_soff); free(z->pk_seg); free(z->pk_boff); free(z->pk_brk); free(z->mark); free(z->stamp);
    if (z->gseg)
        for (size_t i = 0; i < nl; i++)
            free(z->gseg[i]);
    free(z->gseg);
    free(z->gsegn);
}

static int seg_room(res *z, size_t need)
{
    if (need <= z->capseg)
        return CT_OK;
    size_t c = z->capseg;
    while (c < need)
        c = next_cap(c);
    if (regrow(&z->sn, 4 * c, sizeof *z->sn) || regrow(&z->selem, c, sizeof *z->selem) ||
        regrow(&z->spart, c, sizeof *z->spart) || regrow(&z->skind, c, sizeof *z->skind) ||
        regrow(&z->sface, c, sizeof *z->sface) || regrow(&z->sline, c, sizeof *z->sline))
        return CT_ERR_NOMEM;
    z->capseg = c;
    return CT_OK;
}

static const char *kind_kw(int kind)
{
    return kind == CTD_SEG_SHELL ? "/SHELL" : kind == CTD_SEG_SH3N ? "/SH3N" : "/BRICK";
}

/* Nodes: the id map (a repeated id is an error) and the ct_nodes. */
static int res_nodes(rd *r, res *z)
{
    if (r->nn > (size_t)INT32_MAX - CT_PAD)
        return rfail(r, CT_ERR_TOOBIG, r->nline[r->nn - 1], "more than %d nodes", INT32_MAX - CT_PAD);
    if (map_init(&z->nodes, r->nn) || ct_nodes_init(&z->nd, (ct_idx)r->nn))
        return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    for (size_t i = 0; i < r->nn; i++) {
        ct_idx prev = map_put(&z->nodes, r->nid[i], (ct_idx)i);
        if (prev >= 0)
            return rfail(r, CT_ERR_ARG, r->nline[i],
                         "field 'node_id' of /NODE: node id %lld is defined twice (first on "
                         "line %ld)",
                         (long long)r->nid[i], (long)r->nline[prev]);
        z->nd.x[i] = (ct_real)r->xyz[3 * i];
        z->nd.y[i] = (ct_real)r->xyz[3 * i + 1];
        z->nd.z[i] = (ct_real)r->xyz[3 * i + 2];
    }
    return CT_OK;
}

/* Resolve n node ids of an element; check repeats (allowed: n4 == n3 of a
 * /SHELL when `tri_ok`, and any repeat when `rep_ok`). */
static int res_corners(rd *r, res *z, const int64_t *raw, int n, ct_idx *out, int32_t ln,
                       const char *kw, int64_t part, int tri_ok, int rep_ok)
{
    for (int k = 0; k < n; k++) {
        out[k] = map_get(&z->nodes, raw[k]);
        if (out[k] < 0)
            return rfail(r, CT_ERR_RANGE, ln, "field '%s' of %s/%lld: unknown node id %lld",
                         corner[k], kw, (long long)part, (long long)raw[k]);
        for (int j = 0; j < k && !rep_ok; j++)
            if (out[k] == out[j] && !(tri_ok && k == 3 && j == 2))
                return rfail(r, CT_ERR_DUPNODE, ln,
                             "field '%s' of %s/%lld: node id %lld repeats field '%s'", corner[k],
                             kw, (long long)part, (long long)raw[k], corner[j]);
    }
    return CT_OK;
}

/* Elements: segments, bricks, element id maps, dense part indices. */
static int res_elems(rd *r, res *z)
{
    if (r->ns > (size_t)INT32_MAX / 4 || r->nb > (size_t)INT32_MAX / 8)
        return rfail(r, CT_ERR_TOOBIG, -1, "too many elements for 32-bit indices");
    if (seg_room(z, r->ns) || map_init(&z->shells, r->ns) ||
        !(z->spk = malloc((r->ns + 1) * sizeof *z->spk)) ||
        !(z->bnode = malloc((8 * r->nb + 1) * sizeof *z->bnode)) ||
        !(z->bpk = malloc((r->nb + 1) * sizeof *z->bpk)))
        return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    idmap tri, bricks;
    memset(&tri, 0, sizeof tri);
    memset(&bricks, 0, sizeof bricks);
    int rc = CT_OK;
    if (map_init(&tri, r->ns) || map_init(&bricks, r->nb)) {
        rc = rfail(r, CT_ERR_NOMEM, -1, "out of memory");
        goto out;
    }
    for (size_t s = 0; s < r->ns; s++) {
        int kind = r->skind[s];
        rc = res_corners(r, z, r->sraw + 4 * s, kind == CTD_SEG_SH3N ? 3 : 4, z->sn + 4 * s,
                         r->sline[s], kind_kw(kind), r->spart[s], 1, 0);
        if (rc != CT_OK)
            goto out;
        if (kind == CTD_SEG_SH3N)
            z->sn[4 * s + 3] = z->sn[4 * s + 2];
        ct_idx prev = map_put(kind == CTD_SEG_SHELL ? &z->shells : &tri, r->sid[s], (ct_idx)s);
        if (prev >= 0) {
            rc = rfail(r, CT_ERR_ARG, r->sline[s],
                       "field '%s' of %s/%lld: element id %lld is defined twice (first on line "
                       "%ld)",
                       kind == CTD_SEG_SHELL ? "shell_id" : "sh3n_id", kind_kw(kind),
                       (long long)r->spart[s], (long long)r->sid[s], (long)r->sline[prev]);
            goto out;
        }
        z->selem[s] = r->sid[s];
        z->spart[s] = r->spart[s];
        z->skind[s] = r->skind[s];
        z->sface[s] = -1;
        z->sline[s] = r->sline[s];
    }
    z->nseg = r->ns;
    for (size_t b = 0; b < r->nb; b++) {
        ct_idx *c = z->bnode + 8 * b;
        rc = res_corners(r, z, r->braw + 8 * b, 8, c, r->bline[b], "/BRICK", r->bpart[b], 0, 1);
        if (rc != CT_OK)
            goto out;
        int distinct = 0;
        for (int k = 0; k < 8; k++) {
            int seen = 0;
            for (int j = 0; j < k; j++)
                seen |= c[j] == c[k];
            distinct += !seen;
        }
        if (distinct < 4) {
            rc = rfail(r, CT_ERR_DUPNODE, r->bline[b],
                       "/BRICK/%lld element %lld has only %d distinct nodes (at least 4 needed)",
                       (long long)r->bpart[b], (long long)r->bid[b], distinct);
            goto out;
        }
        ct_idx prev = map_put(&bricks, r->bid[b], (ct_idx)b);
        if (prev >= 0) {
            rc = rfail(r, CT_ERR_ARG, r->bline[b],
                       "field 'brick_id' of /BRICK/%lld: element id %lld is defined twice "
                       "(first on line %ld)",
                       (long long)r->bpart[b], (long long)r->bid[b], (long)r->bline[prev]);
            goto out;
        }
    }
    /* Dense part indices: the /PART cards first, then parts that only have
     * elements. */
    size_t maxp = r->np + r->ns + r->nb;
    if (map_init(&z->parts, maxp) || !(z->pk_id = malloc((maxp + 1) * sizeof *z->pk_id)) ||
        !(z->pk_brick = calloc(maxp + 1, 1)) || !(z->mark = calloc(maxp + 1, 1))) {
        rc = rfail(r, CT_ERR_NOMEM, -1, "out of memory");
        goto out;
    }
    for (size_t p = 0; p < r->np; p++) {
        ct_idx prev = map_put(&z->parts, r->part[p].id, (ct_idx)z->npk);
        if (prev >= 0) {
            rc = rfail(r, CT_ERR_ARG, r->part[p].line,
                       "keyword /PART/%lld: part id %lld is defined twice (first on line %ld)",
                       (long long)r->part[p].id, (long long)r->part[p].id,
                       (long)r->part[prev].line);
            goto out;
        }
        z->pk_id[z->npk++] = r->part[p].id;
    }
    for (size_t e = 0; e < r->ns + r->nb; e++) {
        int64_t id = e < r->ns ? r->spart[e] : r->bpart[e - r->ns];
        ct_idx k = map_get(&z->parts, id);
        if (k < 0) {
            k = (ct_idx)z->npk;
            map_put(&z->parts, id, k);
            z->pk_id[z->npk++] = id;
        }
        if (e < r->ns) {
            z->spk[e] = k;
        } else {
            z->bpk[e - r->ns] = k;
            z->pk_brick[k] = 1;
        }
    }
    /* Each part's segments and bricks, in file order (counting sorts), so
     * that part-based sets cost what the parts hold. */
    if (!(z->pk_soff = calloc(z->npk + 2, sizeof *z->pk_soff)) ||
        !(z->pk_boff = calloc(z->npk + 2, sizeof *z->pk_boff)) ||
        !(z->pk_seg = malloc((r->ns + 1) * sizeof *z->pk_seg)) ||
        !(z->pk_brk = malloc((r->nb + 1) * sizeof *z->pk_brk))) {
        rc = rfail(r, CT_ERR_NOMEM, -1, "out of memory");
        goto out;
    }
    for (size_t s = 0; s < r->ns; s++)
        z->pk_soff[z->spk[s] + 2]++;
    for (size_t b = 0; b < r->nb; b++)
        z->pk_boff[z->bpk[b] + 2]++;
    for (size_t k = 2; k < z->npk + 2; k++) {
        z->pk_soff[k] += z->pk_soff[k - 1];
        z->pk_boff[k] += z->pk_boff[k - 1];
    }
    for (size_t s = 0; s < r->ns; s++)
        z->pk_seg[z->pk_soff[z->spk[s] + 1]++] = (ct_idx)s;
    for (size_t b = 0; b < r->nb; b++)
        z->pk_brk[z->pk_boff[z->bpk[b] + 1]++] = (ct_idx)b;
out:
    map_free(&tri);
    map_free(&bricks);
    return rc;
}

/* Mark the parts listed in l; an unknown id is an error. */
static int mark_parts(rd *r, res *z, const rlist *l, int *any_brick)
{
    memset(z->mark, 0, z->npk + 1);
    *any_brick = 0;
    for (size_t i = 0; i < l->n; i++) {
        ct_idx k = map_get(&z->parts, l->ids[i]);
        if (k < 0)
            return rfail(r, CT_ERR_RANGE, l->lines[i],
                         "field 'part_id' (number %d) of %s/%lld: unknown part %lld", l->fld[i],
                         list_kw[l->type], (long long)l->id, (long long)l->ids[i]);
        z->mark[k] = 1;
        *any_brick |= z->pk_brick[k];
    }
    return CT_OK;
}

/* The /GRSHEL lists resolved to segment indices. */
static int res_grshel(rd *r, res *z)
{
    if (map_init(&z->grshel, r->nl) || !(z->gseg = calloc(r->nl + 1, sizeof *z->gseg)) ||
        !(z->gsegn = calloc(r->nl + 1, sizeof *z->gsegn)))
        return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    for (size_t g = 0; g < r->nl; g++) {
        const rlist *l = &r->list[g];
        if (l->type != L_GRSHEL_SHEL)
            continue;
        ct_idx prev = map_put(&z->grshel, l->id, (ct_idx)g);
        if (prev >= 0)
            return rfail(r, CT_ERR_ARG, l->line, "keyword /GRSHEL/SHEL/%lld: id %lld is defined twice (first on line %ld)",
                         (long long)l->id, (long long)l->id, (long)r->list[prev].line);
        if (!(z->gseg[g] = malloc((l->n + 1) * sizeof **z->gseg)))
            return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
        for (size_t i = 0; i < l->n; i++) {
            ct_idx s = map_get(&z->shells, l->ids[i]);
            if (s < 0)
                return rfail(r, CT_ERR_RANGE, l->lines[i],
                             "field 'shell_id' (number %d) of /GRSHEL/SHEL/%lld: unknown shell %lld",
                             l->fld[i], (long long)l->id, (long long)l->ids[i]);
            z->gseg[g][i] = s;
        }
        z->gsegn[g] = (ct_idx)l->n;
    }
    return CT_OK;
}

/* Look up a /GRSHEL id of list l, entry i. */
static int grshel_of(rd *r, res *z, const rlist *l, size_t i, ct_idx *g)
{
    *g = map_get(&z->grshel, l->ids[i]);
    if (*g < 0)
        return rfail(r, CT_ERR_RANGE, l->lines[i],
                     "field 'grshel_id' (number %d) of %s/%lld: unknown /GRSHEL/SHEL %lld",
                     l->fld[i], list_kw[l->type], (long long)l->id, (long long)l->ids[i]);
    return CT_OK;
}

/* Append v to a growing ct_idx list unless stamped already. */
typedef struct ilist {
    size_t n, cap;
    ct_idx *v;
} ilist;

static int push(res *z, ilist *o, ct_idx v)
{
    if (z->stamp[v] == z->gen)
        return CT_OK;
    z->stamp[v] = z->gen;
    if (o->n == o->cap) {
        size_t c = next_cap(o->cap);
        ct_idx *q = ct_calloc(c, sizeof *q);
        if (!q)
            return CT_ERR_NOMEM;
        if (o->n)
            memcpy(q, o->v, o->n * sizeof *q);
        ct_free(o->v);
        o->v = q;
        o->cap = c;
    }
    o->v[o->n++] = v;
    return CT_OK;
}

/* The segments of one surface card. */
static int res_surf(rd *r, res *z, const rlist *l, ilist *o)
{
    z->gen++;
    if (l->type == L_SURF_GRSHEL) {
        for (size_t i = 0; i < l->n; i++) {
            ct_idx g;
            int rc = grshel_of(r, z, l, i, &g);
            if (rc != CT_OK)
                return rc;
            for (ct_idx k = 0; k < z->gsegn[g]; k++)
                if (push(z, o, z->gseg[g][k]))
                    return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
        }
        return CT_OK;
    }
    int any_brick, rc = mark_parts(r, z, l, &any_brick);
    if (rc != CT_OK)
        return rc;
    for (size_t i = 0; i < l->n; i++) {
        ct_idx k = map_get(&z->parts, l->ids[i]);
        for (ct_idx j = z->pk_soff[k]; j < z->pk_soff[k + 1]; j++)
            if (push(z, o, z->pk_seg[j]))
                return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    }
    if (!any_brick)
        return CT_OK;
    unsigned char *sel = calloc(r->nb + 1, 1);
    if (!sel)
        return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    for (size_t i = 0; i < l->n; i++) {
        ct_idx k = map_get(&z->parts, l->ids[i]);
        for (ct_idx j = z->pk_boff[k]; j < z->pk_boff[k + 1]; j++)
            sel[z->pk_brk[j]] = 1;
    }
    ctd_faces f;
    ct_diag d;
    rc = ctd_brick_outer_faces(z->nd.n, z->nd.x, z->nd.y, z->nd.z, (ct_idx)r->nb, z->bnode, sel,
                               &f, &d);
    free(sel);
    if (rc != CT_OK)
        return rfail(r, rc, l->line, "%s/%lld: %s", list_kw[l->type], (long long)l->id, d.msg);
    for (ct_idx j = 0; j < f.n && rc == CT_OK; j++) {
        size_t slot = 6 * (size_t)f.brick[j] + (size_t)f.local[j];
        if (z->faceseg[slot] < 0) {
            if (z->nseg >= (size_t)INT32_MAX - CT_PAD || seg_room(z, z->nseg + 1)) {
                rc = rfail(r, CT_ERR_NOMEM, -1, "out of memory");
                break;
            }
            size_t s = z->nseg++;
            memcpy(z->sn + 4 * s, f.node + 4 * (size_t)j, 4 * sizeof *z->sn);
            z->selem[s] = r->bid[f.brick[j]];
            z->spart[s] = r->bpart[f.brick[j]];
            z->skind[s] = CTD_SEG_BRICK_FACE;
            z->sface[s] = f.local[j];
            z->sline[s] = r->bline[f.brick[j]];
            z->faceseg[slot] = (ct_idx)s;
            /* The stamp array covers the segments that can exist. */
        }
        if (push(z, o, z->faceseg[slot]))
            rc = rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    }
    ctd_faces_destroy(&f);
    return rc;
}

/* The nodes of one node-group card. */
static int res_group(rd *r, res *z, const rlist *l, ilist *o)
{
    z->gen++;
    int nomem = 0;
    if (l->type == L_GRNOD_NODE) {
        for (size_t i = 0; i < l->n && !nomem; i++) {
            ct_idx v = map_get(&z->nodes, l->ids[i]);
            if (v < 0)
                return rfail(r, CT_ERR_RANGE, l->lines[i],
                             "field 'node_id' (number %d) of /GRNOD/NODE/%lld: unknown node id %lld",
                             l->fld[i], (long long)l->id, (long long)l->ids[i]);
            nomem = push(z, o, v) != CT_OK;
        }
    } else if (l->type == L_GRNOD_GRSHEL) {
        for (size_t i = 0; i < l->n && !nomem; i++) {
            ct_idx g;
            int rc = grshel_of(r, z, l, i, &g);
            if (rc != CT_OK)
                return rc;
            for (ct_idx k = 0; k < z->gsegn[g] && !nomem; k++)
                for (int c = 0; c < 4 && !nomem; c++)
                    nomem = push(z, o, z->sn[4 * (size_t)z->gseg[g][k] + c]) != CT_OK;
        }
    } else {
        int any_brick, rc = mark_parts(r, z, l, &any_brick);
        if (rc != CT_OK)
            return rc;
        for (size_t i = 0; i < l->n && !nomem; i++) {
            ct_idx k = map_get(&z->parts, l->ids[i]);
            for (ct_idx j = z->pk_soff[k]; j < z->pk_soff[k + 1] && !nomem; j++)
                for (int c = 0; c < 4 && !nomem; c++)
                    nomem = push(z, o, z->sn[4 * (size_t)z->pk_seg[j] + c]) != CT_OK;
            for (ct_idx j = z->pk_boff[k]; j < z->pk_boff[k + 1] && !nomem; j++)
                for (int c = 0; c < 8 && !nomem; c++)
                    nomem = push(z, o, z->bnode[8 * (size_t)z->pk_brk[j] + c]) != CT_OK;
        }
    }
    if (nomem)
        return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    if (o->n > 1)
        qsort(o->v, o->n, sizeof *o->v, cmp_idx);
    return CT_OK;
}

/* Surfaces and groups, in file order; ids unique per kind. */
static int res_sets(rd *r, res *z, ctd_deck *d)
{
    size_t nsurf = 0, ngroup = 0;
    for (size_t i = 0; i < r->nl; i++) {
        nsurf += r->list[i].type <= L_SURF_GRSHEL;
        ngroup += r->list[i].type >= L_GRNOD_NODE && r->list[i].type <= L_GRNOD_GRSHEL;
    }
    /* Stamps cover nodes and every segment there can be (6 faces a brick). */
    size_t nstamp = r->nn + r->ns + 6 * r->nb + 1;
    d->surf = calloc(nsurf + 1, sizeof *d->surf);
    d->group = calloc(ngroup + 1, sizeof *d->group);
    z->stamp = calloc(nstamp, sizeof *z->stamp);
    z->faceseg = malloc((6 * r->nb + 1) * sizeof *z->faceseg);
    if (!d->surf || !d->group || !z->stamp || !z->faceseg)
        return rfail(r, CT_ERR_NOMEM, -1, "out of memory");
    for (size_t i = 0; i < 6 * r->nb; i++)
        z->faceseg[i] = -1;
    idmap sid, gid;
    memset(&sid, 0, sizeof sid);
    memset(&gid, 0, sizeof gid);
    int rc = CT_OK;
    if (map_init(&sid, nsurf) || map_init(&gid, ngroup)) {
        rc = rfail(r, CT_ERR_NOMEM, -1, "out of memory");
        goto out;
    }
    for (size_t i = 0; i < r->nl && rc == CT_OK; i++) {
        rlist *l = &r->list[i];
        if (l->type == L_GRSHEL_SHEL)
            continue;
        int surf = l->type <= L_SURF_GRSHEL;
        idmap *m = surf ? &sid : &gid;
        int *cnt = surf ? &d->nsurf : &d->ngroup;
        ct_idx prev = map_put(m, l->id, (ct_idx)i);
        if (prev >= 0) {
            rc = rfail(r, CT_ERR_ARG, l->line, "keyword %s/%lld: id %lld is already used by %s/%lld on line %ld",
                       list_kw[l->type], (long long)l->id, (long long)l->id,
                       list_kw[r->list[prev].type], (long long)l->id, (long)r->list[prev].line);
            break;
        }
        ilist o = {0, 0, NULL};
        rc = surf ? res_surf(r, z, l, &o) : res_group(r, z, l, &o);
        if (rc != CT_OK) {
            ct_free(o.v);
            break;
        }
        if (surf && o.n > 1)
            qsort(o.v, o.n, sizeof *o.v, cmp_idx);
        if (!o.v && !(o.v = ct_calloc(1, sizeof *o.v))) {
            rc = rfail(r, CT_ERR_NOMEM, -1, "out of memory");
            break;
        }
        if (surf) {
            ctd_surf *s = &d->surf[(*cnt)++];
            s->id = l->id;
            s->title = l->title;
            s->line = l->line;
            s->s.n = (ct_idx)o.n;
            s->s.seg = o.v;
        } else {
            ctd_group *g = &d->group[(*cnt)++];
            g->id = l->id;
            g->title = l->title;
            g->line = l->line;
            g->s.n = (ct_idx)o.n;
            g->s.node = o.v;
        }
        l->title = NULL;
    }
out:
    map_free(&sid);
    map_free(&gid);
    return rc;
}

/* ---- The public functions ---------------------------------------------- */

static void rd_free(rd *r)
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

/* Read a whole file; NULL (errno set) on failure. */
static char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        if (n == cap) {
            char *q = realloc(buf, 2 * cap);
            if (!q) {
                free(buf);
                buf = NULL;
                errno = ENOMEM;
                break;
            }
            buf = q;
            cap *= 2;
        }
        size_t k = fread(buf + n, 1, cap - n, f);
        n += k;
        if (k == 0) {
            if (ferror(f)) {
                free(buf);
                buf = NULL;
                errno = EIO;
            }
            break;
        }
    }
    fclose(f);
    *size = n;
    return buf;
}

/* The warning string from the unsupported keywords. */
static char *make_warning(const rd *r)
{
    size_t len = 64;
    for (int i = 0; i < r->nun; i++)
        len += strlen(r->un[i]) + 24;
    char *w = malloc(len);
    if (!w)
        return NULL;
    w[0] = 0;
    size_t k = 0;
    if (r->nun > 0)
        k += (size_t)snprintf(w, len, "unsupported keywords ignored:");
    for (int i = 0; i < r->nun; i++)
        k += (size_t)snprintf(w + k, len - k, "%s %s (%d)", i ? "," : "", r->un[i],
                              r->uncount[i]);
    return w;
}

static char *or_empty(char *s)
{
    if (s)
        return s;
    s = malloc(1);
    if (s)
        *s = 0;
    return s;
}

int ctd_deck_read(const char *path, ctd_deck *deck, ct_diag *diag)
{
    ct_diag dummy;
    if (!diag)
        diag = &dummy;
    if (!deck || !path) {
        diag->code = CT_ERR_ARG;
        diag->index = -1;
        snprintf(diag->msg, sizeof diag->msg, "ctd_deck_read: NULL path or deck.");
        return CT_ERR_ARG;
    }
    memset(deck, 0, sizeof *deck);
    rd r;
    memset(&r, 0, sizeof r);
    r.path = path;
    r.diag = diag;
    res z;
    memset(&z, 0, sizeof z);
    int rc;
    size_t size = 0;
    char *buf = slurp(path, &size);
    if (!buf)
        return rfail(&r, CT_ERR_ARG, -1, "cannot open or read the file: %s", strerror(errno));
    int32_t nlines = 0;
    if (size == 0) {
        rc = rfail(&r, CT_ERR_ARG, -1, "the file is empty");
        goto fail;
    }
    rc = scan(&r, buf, size, &nlines);
    if (rc != CT_OK)
        goto fail;
    if (!r.saw_node || r.nn == 0) {
        rc = rfail(&r, CT_ERR_ARG, nlines, r.saw_node ? "no node lines under /NODE (end of file)"
                                                      : "no /NODE keyword in the deck (end of file)");
        goto fail;
    }
    if ((rc = res_nodes(&r, &z)) != CT_OK || (rc = res_elems(&r, &z)) != CT_OK ||
        (rc = res_grshel(&r, &z)) != CT_OK || (rc = res_sets(&r, &z, deck)) != CT_OK)
        goto fail;
    /* The mesh: nodes from the resolution, the segments copied. */
    ct_idx nseg = (ct_idx)z.nseg;
    if ((rc = ct_mesh_init(&deck->mesh, 0, nseg)) != CT_OK) {
        rc = rfail(&r, rc, -1, "out of memory");
        goto fail;
    }
    ct_nodes_destroy(&deck->mesh.nodes);
    deck->mesh.nodes = z.nd;
    memset(&z.nd, 0, sizeof z.nd);
    for (ct_idx s = 0; s < nseg; s++) {
        deck->mesh.n1[s] = z.sn[4 * (size_t)s];
        deck->mesh.n2[s] = z.sn[4 * (size_t)s + 1];
        deck->mesh.n3[s] = z.sn[4 * (size_t)s + 2];
        deck->mesh.n4[s] = z.sn[4 * (size_t)s + 3];
    }
    /* Move the arrays into the deck. */
    deck->node_id = r.nid;
    deck->node_line = r.nline;
    r.nid = NULL;
    r.nline = NULL;
    deck->nelemseg = (ct_idx)r.ns;
    deck->seg_elem = z.selem;
    deck->seg_part = z.spart;
    deck->seg_kind = z.skind;
    deck->seg_face = z.sface;
    deck->seg_line = z.sline;
    z.selem = z.spart = NULL;
    z.skind = z.sface = NULL;
    z.sline = NULL;
    deck->nbrick = (ct_idx)r.nb;
    deck->brick_id = r.bid;
    deck->brick_part = r.bpart;
    deck->brick_line = r.bline;
    deck->brick_node = z.bnode;
    r.bid = r.bpart = NULL;
    r.bline = NULL;
    z.bnode = NULL;
    deck->npart = (int)r.np;
    deck->part = r.part;
    for (size_t p = 0; p < r.np; p++)
        if (!(deck->part[p].title = or_empty(deck->part[p].title)))
            rc = CT_ERR_NOMEM;
    r.part = NULL;
    r.np = 0;
    for (int i = 0; i < deck->nsurf; i++)
        if (!(deck->surf[i].title = or_empty(deck->surf[i].title)))
            rc = CT_ERR_NOMEM;
    for (int i = 0; i < deck->ngroup; i++)
        if (!(deck->group[i].title = or_empty(deck->group[i].title)))
            rc = CT_ERR_NOMEM;
    deck->title = or_empty(r.title);
    r.title = NULL;
    deck->warning = make_warning(&r);
    deck->nwarn = r.nun;
    deck->unsupported = r.un;
    deck->unsupported_count = r.uncount;
    r.un = NULL;
    r.uncount = NULL;
    r.nun = 0;
    idmap *nm = malloc(sizeof *nm);
    if (nm) {
        *nm = z.nodes;
        memset(&z.nodes, 0, sizeof z.nodes);
        deck->node_map = nm;
    }
    if (rc != CT_OK || !deck->title || !deck->warning || !nm) {
        rc = rfail(&r, CT_ERR_NOMEM, -1, "out of memory");
        goto fail;
    }
    /* The mesh check, reported in the deck's terms. */
    ct_diag md;
    memset(&md, 0, sizeof md);
    rc = ct_mesh_validate(&deck->mesh, &md);
    if (rc != CT_OK) {
        int64_t s = md.index;
        if (s >= 0 && s < nseg) {
            int kind = deck->seg_kind[s];
            if (kind == CTD_SEG_BRICK_FACE)
                rfail(&r, rc, deck->seg_line[s], "face %d of /BRICK/%lld element %lld: %s",
                      deck->seg_face[s], (long long)deck->seg_part[s],
                      (long long)deck->seg_elem[s], md.msg);
            else
                rfail(&r, rc, deck->seg_line[s], "%s/%lld element %lld: %s", kind_kw(kind),
                      (long long)deck->seg_part[s], (long long)deck->seg_elem[s], md.msg);
        } else {
            rfail(&r, rc, -1, "%s", md.msg);
        }
        goto fail;
    }
    free(buf);
    rd_free(&r);
    res_free(&z, r.nl);
    return CT_OK;
fail:
    free(buf);
    res_free(&z, r.nl);
    rd_free(&r);
    ctd_deck_destroy(deck);
    return rc;
}

void ctd_deck_destroy(ctd_deck *d)
{
    if (!d)
        return;
    ct_mesh_destroy(&d->mesh);
    free(d->node_id); free(d->node_line);
    free(d->seg_elem); free(d->seg_part); free(d->seg_kind); free(d->seg_face);
    free(d->seg_line);
    free(d->brick_id); free(d->brick_part); free(d->brick_node); free(d->brick_line);
    for (int i = 0; i < d->npart; i++)
        free(d->part[i].title);
    free(d->part);
    for (int i = 0; i < d->nsurf; i++) {
        free(d->surf[i].title);
        ct_free(d->surf[i].s.seg);
    }
    free(d->surf);
    for (int i = 0; i < d->ngroup; i++) {
        free(d->group[i].title);
        ct_free(d->group[i].s.node);
    }
    free(d->group);
    free(d->title);
    for (int i = 0; i < d->nwarn; i++)
        free(d->unsupported[i]);
    free(d->unsupported);
    free(d->unsupported_count);
    free(d->warning);
    map_free(d->node_map);
    free(d->node_map);
    memset(d, 0, sizeof *d);
}

const char *ctd_deck_warning(const ctd_deck *d)
{
    return d && d->warning ? d->warning : "";
}

ct_idx ctd_deck_node(const ctd_deck *d, int64_t id)
{
    return d && id > 0 ? map_get(d->node_map, id) : -1;
}

const ctd_part *ctd_deck_part(const ctd_deck *d, int64_t id)
{
    for (int i = 0; d && i < d->npart; i++)
        if (d->part[i].id == id)
            return &d->part[i];
    return NULL;
}

const ctd_surf *ctd_deck_surf(const ctd_deck *d, int64_t id)
{
    for (int i = 0; d && i < d->nsurf; i++)
        if (d->surf[i].id == id)
            return &d->surf[i];
    return NULL;
}

const ctd_group *ctd_deck_group(const ctd_deck *d, int64_t id)
{
    for (int i = 0; d && i < d->ngroup; i++)
        if (d->group[i].id == id)
            return &d->group[i];
    return NULL;
}

int ctd_deck_brick_surface(const ctd_deck *d, const int64_t *part_ids, int nparts,
                           ctd_faces *out, ct_diag *diag)
{
    if (!d || !out || nparts < 0 || (nparts > 0 && !part_ids)) {
        if (diag) {
            diag->code = CT_ERR_ARG;
            diag->index = -1;
            snprintf(diag->msg, sizeof diag->msg, "ctd_deck_brick_surface: NULL argument.");
        }
        return CT_ERR_ARG;
    }
    unsigned char *sel = NULL;
    if (nparts > 0) {
        sel = calloc((size_t)d->nbrick + 1, 1);
        if (!sel)
            return CT_ERR_NOMEM;
        for (int p = 0; p < nparts; p++) {
            int found = 0;
            for (ct_idx b = 0; b < d->nbrick; b++)
                if (d->brick_part[b] == part_ids[p])
                    sel[b] = 1, found = 1;
            if (!found) {
                free(sel);
                if (diag) {
                    diag->code = CT_ERR_RANGE;
                    diag->index = p;
                    snprintf(diag->msg, sizeof diag->msg, "part %lld has no /BRICK elements.",
                             (long long)part_ids[p]);
                }
                return CT_ERR_RANGE;
            }
        }
    }
    int rc = ctd_brick_outer_faces(d->mesh.nodes.n, d->mesh.nodes.x, d->mesh.nodes.y,
                                   d->mesh.nodes.z, d->nbrick, d->brick_node, sel, out, diag);
    free(sel);
    return rc;
}
