/*
 * test_import_radioss.c -- the Radioss deck reader: the shared decks load
 * with the node, segment, surface and group figures found by an independent
 * scan of the files (and those stated in their NOTICE); each kind of bad
 * input gives its code and a message naming the file, the line and the
 * field; lenient number formats; speed. The outer surface of bricks:
 * test_import_radioss_bricks.c.
 *
 * The shared decks are read from $CT_SHARED/data/radioss/ (never copied
 * into the repository); the tests that need them skip when it is absent.
 * The small decks of the error tests are in tests/data/radioss/.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "test_import_radioss.h"

/* ---- Helpers ----------------------------------------------------------- */

/* $CT_SHARED/data/radioss/NAME, or skip the test. */
static void shared_path(char *buf, size_t n, const char *name)
{
    const char *s = ctt_shared();
    if (!s)
        cr_skip_test("CT_SHARED is not set: the shared Radioss decks are not available");
    snprintf(buf, n, "%s/data/radioss/%s", s, name);
    if (access(buf, R_OK) != 0)
        cr_skip_test("%s is absent: the shared Radioss decks are not available", buf);
}

/* Expect a failure with this code and a message holding the file name,
 * ":LINE:" (line > 0) and each of the given words. */
static void expect_error(const char *path, int code, int line, const char *w1, const char *w2)
{
    ctd_deck d;
    ct_diag g;
    memset(&g, 0, sizeof g);
    int rc = ctd_deck_read(path, &d, &g);
    cr_assert_eq(rc, code, "%s: expected %s, got %s: %s", path, ct_strerror(code),
                 ct_strerror(rc), g.msg);
    cr_assert_eq(g.code, code);
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    cr_assert(strstr(g.msg, base), "message \"%s\" lacks the file name %s", g.msg, base);
    if (line > 0) {
        char tag[32];
        snprintf(tag, sizeof tag, ":%d: ", line);
        cr_assert(strstr(g.msg, tag), "message \"%s\" lacks the line \"%s\"", g.msg, tag);
        cr_assert_eq(g.index, line, "diag index %ld, expected line %d", (long)g.index, line);
    }
    if (w1)
        cr_assert(strstr(g.msg, w1), "message \"%s\" lacks \"%s\"", g.msg, w1);
    if (w2)
        cr_assert(strstr(g.msg, w2), "message \"%s\" lacks \"%s\"", g.msg, w2);
    /* The deck holds nothing after a failure. */
    cr_assert_null(d.node_id);
    cr_assert_eq(d.mesh.nseg, 0);
}

/* An independent scan of a deck: the data lines under /NODE, /SHELL/,
 * /SH3N/, /BRICK/ (up to /END), the first and last node lines, the
 * distinct node ids used by each element kind's lines, and the 10-column
 * ids listed under a given list keyword. */
typedef struct scan {
    long nnode, nshell, nsh3n, nbrick;
    char first[128], last[128];
    long maxid;
    unsigned char *used_sh3n, *used_shell; /* [maxid + 1] */
    long shell_nodes[4096][5];             /* id n1..n4 of the first shells */
} scan;

static int is_kw(const char *line, const char *kw) { return !strncmp(line, kw, strlen(kw)); }

static void scan_deck(const char *path, scan *s)
{
    memset(s, 0, sizeof *s);
    s->maxid = 1 << 20;
    s->used_sh3n = calloc((size_t)s->maxid + 1, 1);
    s->used_shell = calloc((size_t)s->maxid + 1, 1);
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f);
    char line[8192];
    int blk = 0; /* 1 node, 2 shell, 3 sh3n, 4 brick */
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#')
            continue;
        if (line[0] == '/') {
            if (is_kw(line, "/END"))
                break;
            blk = is_kw(line, "/NODE") ? 1 : is_kw(line, "/SHELL/") ? 2
                  : is_kw(line, "/SH3N/")                           ? 3
                  : is_kw(line, "/BRICK/")                          ? 4
                                                                    : 0;
            continue;
        }
        if (strspn(line, " \r\n") == strlen(line) || blk == 0)
            continue;
        long v[5] = {0, 0, 0, 0, 0};
        if (blk == 1) {
            if (s->nnode == 0)
                snprintf(s->first, sizeof s->first, "%.127s", line);
            snprintf(s->last, sizeof s->last, "%.127s", line);
            s->nnode++;
        } else if (blk == 2 || blk == 3) {
            int nv = sscanf(line, "%ld %ld %ld %ld %ld", &v[0], &v[1], &v[2], &v[3], &v[4]);
            cr_assert_geq(nv, blk == 2 ? 5 : 4);
            for (int k = 1; k < (blk == 2 ? 5 : 4); k++) {
                cr_assert(v[k] > 0 && v[k] <= s->maxid);
                (blk == 2 ? s->used_shell : s->used_sh3n)[v[k]] = 1;
            }
            if (blk == 2 && s->nshell < 4096)
                memcpy(s->shell_nodes[s->nshell], v, sizeof v);
            *(blk == 2 ? &s->nshell : &s->nsh3n) += 1;
        } else {
            s->nbrick++;
        }
    }
    fclose(f);
}

static void scan_free(scan *s)
{
    free(s->used_sh3n);
    free(s->used_shell);
}

static long count_used(const unsigned char *u, long maxid)
{
    long n = 0;
    for (long i = 0; i <= maxid; i++)
        n += u[i];
    return n;
}

/* The ids listed under the first keyword line equal to `kw` (after its
 * title line), in 10-column fields. Returns the count. */
static long list_ids(const char *path, const char *kw, long *ids, long cap)
{
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f);
    char line[8192];
    long n = 0;
    int state = 0; /* 0 looking, 1 title next, 2 in list */
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = 0;
        if (line[0] == '#')
            continue;
        if (line[0] == '/') {
            if (state == 2)
                break;
            state = !strcmp(line, kw) ? 1 : 0;
            continue;
        }
        if (state == 1) {
            state = 2;
            continue;
        }
        if (state == 2)
            for (size_t c = 0; c < strlen(line); c += 10) {
                char fld[11] = {0};
                memcpy(fld, line + c, strlen(line + c) < 10 ? strlen(line + c) : 10);
                long v = 0;
                if (sscanf(fld, "%ld", &v) == 1 && v != 0 && n < cap)
                    ids[n++] = v;
            }
    }
    fclose(f);
    return n;
}

/* Columns [a, a + w) of a line as a number. */
static double col(const char *line, int a, int w)
{
    char b[32] = {0};
    memcpy(b, line + a, (size_t)w);
    double v = 0;
    cr_assert_eq(sscanf(b, "%lf", &v), 1, "no number in columns %d-%d of \"%s\"", a, a + w, line);
    return v;
}

static void check_node_line(const ctd_deck *d, ct_idx i, const char *line)
{
    cr_assert_eq(d->node_id[i], (int64_t)col(line, 0, 10));
    cr_assert_eq(d->mesh.nodes.x[i], (ct_real)col(line, 10, 20), "x of node %ld", (long)i);
    cr_assert_eq(d->mesh.nodes.y[i], (ct_real)col(line, 30, 20), "y of node %ld", (long)i);
    cr_assert_eq(d->mesh.nodes.z[i], (ct_real)col(line, 50, 20), "z of node %ld", (long)i);
}

/* Counts, first and last nodes, and a valid mesh, against the scan. */
static void check_counts(const char *path, const ctd_deck *d, const scan *s)
{
    cr_assert_eq(d->mesh.nodes.n, s->nnode, "%s: %ld nodes, the file has %ld", path,
                 (long)d->mesh.nodes.n, s->nnode);
    cr_assert_eq(d->nelemseg, s->nshell + s->nsh3n);
    cr_assert_eq(d->nbrick, s->nbrick);
    check_node_line(d, 0, s->first);
    check_node_line(d, d->mesh.nodes.n - 1, s->last);
    long nsh = 0, ntri = 0;
    for (ct_idx k = 0; k < d->nelemseg; k++) {
        nsh += d->seg_kind[k] == CTD_SEG_SHELL;
        ntri += d->seg_kind[k] == CTD_SEG_SH3N;
        if (d->seg_kind[k] == CTD_SEG_SH3N)
            cr_assert_eq(d->mesh.n4[k], d->mesh.n3[k]);
    }
    cr_assert_eq(nsh, s->nshell);
    cr_assert_eq(ntri, s->nsh3n);
    ct_diag g;
    cr_assert_eq(ct_mesh_validate(&d->mesh, &g), CT_OK);
}

/* The node ids of a group, as a 0/1 table over ids. */
static void group_ids(const ctd_deck *d, const ctd_group *g, unsigned char *tab, long maxid)
{
    memset(tab, 0, (size_t)maxid + 1);
    for (ct_idx k = 0; k < g->s.n; k++) {
        if (k > 0)
            cr_assert_lt(g->s.node[k - 1], g->s.node[k], "group nodes sorted and unique");
        int64_t id = d->node_id[g->s.node[k]];
        cr_assert(id > 0 && id <= maxid);
        tab[id] = 1;
    }
}

/* ---- The shared decks -------------------------------------------------- */

Test(import_radioss, tritubv4)
{
    char path[1024];
    shared_path(path, sizeof path, "TRITUBV4_0000.rad");
    scan s;
    scan_deck(path, &s);
    ctd_deck d;
    load(path, &d);
    check_counts(path, &d, &s);
    /* The figures of NOTICE.md. */
    cr_assert_eq(d.mesh.nodes.n, 498);
    cr_assert_eq(d.mesh.nseg, 900);
    cr_assert_eq(s.nsh3n, 900);
    /* /SURF/PART/3 = part 1 = all the triangles; /GRNOD/PART/2 = part 1's
     * nodes (the scan's distinct node ids of the /SH3N lines). */
    const ctd_surf *sf = ctd_deck_surf(&d, 3);
    cr_assert_not_null(sf);
    cr_assert_eq(sf->s.n, 900);
    for (ct_idx k = 0; k < sf->s.n; k++)
        cr_assert_eq(sf->s.seg[k], k);
    const ctd_group *g = ctd_deck_group(&d, 2);
    cr_assert_not_null(g);
    cr_assert_eq(g->s.n, count_used(s.used_sh3n, s.maxid));
    unsigned char *tab = calloc((size_t)s.maxid + 1, 1);
    group_ids(&d, g, tab, s.maxid);
    cr_assert_eq(memcmp(tab, s.used_sh3n, (size_t)s.maxid + 1), 0);
    free(tab);
    const ctd_part *p = ctd_deck_part(&d, 1);
    cr_assert_not_null(p);
    cr_assert_str_eq(p->title, "PID_FLUI");
    cr_assert_eq(p->prop, 1);
    cr_assert_eq(p->mat, 1);
    /* Unsupported keywords: listed once each with their counts. */
    const char *w = ctd_deck_warning(&d);
    cr_assert(!strncmp(w, "unsupported keywords ignored: ", 30), "%s", w);
    cr_assert(strstr(w, "/MAT/PLAS_JOHNS (1)"), "%s", w);
    cr_assert(strstr(w, "/INTER/TYPE7 (1)"), "%s", w);
    cr_assert(strstr(w, "/RWALL/PLANE (2)"), "%s", w);
    int found = 0;
    for (int i = 0; i < d.nwarn; i++) {
        found |= !strcmp(d.unsupported[i], "/MAT/PLAS_JOHNS") && d.unsupported_count[i] == 1;
        const char *supported[] = {"/NODE", "/SH3N", "/PART", "/SURF/PART", "/GRNOD/PART",
                                   "/TITLE", "/BEGIN", "/END"};
        for (size_t k = 0; k < sizeof supported / sizeof supported[0]; k++)
            cr_assert_str_neq(d.unsupported[i], supported[k]);
        for (int j = 0; j < i; j++)
            cr_assert_str_neq(d.unsupported[i], d.unsupported[j], "listed once");
    }
    cr_assert(found);
    cr_assert_str_eq(d.title, "TRITUBV4");
    scan_free(&s);
    ctd_deck_destroy(&d);
}

Test(import_radioss, int357)
{
    char path[1024];
    shared_path(path, sizeof path, "INT357_0000.rad");
    scan s;
    scan_deck(path, &s);
    ctd_deck d;
    load(path, &d);
    check_counts(path, &d, &s);
    cr_assert_eq(d.mesh.nodes.n, 36);
    cr_assert_eq(d.npart, 9);
    /* Each /SURF/PART names one part of one shell: surface -> shell id. */
    const int64_t surf_shell[4][2] = {{9, 31}, {10, 51}, {12, 122}, {14, 193}};
    for (int i = 0; i < 4; i++) {
        const ctd_surf *sf = ctd_deck_surf(&d, surf_shell[i][0]);
        cr_assert_not_null(sf);
        cr_assert_eq(sf->s.n, 1);
        cr_assert_eq(d.seg_elem[sf->s.seg[0]], surf_shell[i][1]);
        cr_assert_eq(d.seg_kind[sf->s.seg[0]], CTD_SEG_SHELL);
    }
    /* /GRNOD/PART/11 = part 4 = shell 102 on nodes 105-108; /GRNOD/NODE/3
     * lists 31-34 and 71-74 (the ids of the file, checked by the scan). */
    long ids[64];
    cr_assert_eq(list_ids(path, "/GRNOD/NODE/3", ids, 64), 8);
    const ctd_group *g = ctd_deck_group(&d, 3);
    cr_assert_not_null(g);
    cr_assert_eq(g->s.n, 8);
    unsigned char tab[256];
    group_ids(&d, g, tab, 255);
    for (int k = 0; k < 8; k++)
        cr_assert(tab[ids[k]], "node %ld missing from group 3", ids[k]);
    g = ctd_deck_group(&d, 11);
    cr_assert_not_null(g);
    cr_assert_eq(g->s.n, 4);
    group_ids(&d, g, tab, 255);
    for (int id = 105; id <= 108; id++)
        cr_assert(tab[id]);
    cr_assert(strstr(ctd_deck_warning(&d), "/INTER/TYPE3 (1)"));
    cr_assert(strstr(ctd_deck_warning(&d), "/PROP/TYPE1 (9)"));
    scan_free(&s);
    ctd_deck_destroy(&d);
}

Test(import_radioss, boxbeam)
{
    char path[1024];
    shared_path(path, sizeof path, "BOXBEAM_0000.rad");
    scan s;
    scan_deck(path, &s);
    ctd_deck d;
    load(path, &d);
    check_counts(path, &d, &s);
    /* "About 1k nodes" (NOTICE.md), quads. */
    cr_assert(d.mesh.nodes.n > 900 && d.mesh.nodes.n < 1100);
    cr_assert_eq(s.nsh3n, 0);
    for (ct_idx k = 0; k < d.mesh.nseg; k++)
        cr_assert_eq(d.seg_kind[k], CTD_SEG_SHELL);
    /* /SURF/PART/4 = part 2 = shell 897. */
    const ctd_surf *sf = ctd_deck_surf(&d, 4);
    cr_assert_not_null(sf);
    cr_assert_eq(sf->s.n, 1);
    cr_assert_eq(d.seg_elem[sf->s.seg[0]], 897);
    /* /SURF/GRSHEL/1 = /GRSHEL/SHEL/2: exactly the listed shells. */
    static long ids[4096];
    long n = list_ids(path, "/GRSHEL/SHEL/2", ids, 4096);
    cr_assert_gt(n, 100);
    sf = ctd_deck_surf(&d, 1);
    cr_assert_not_null(sf);
    cr_assert_eq(sf->s.n, n);
    for (long k = 0; k < n; k++) {
        int hit = 0;
        for (ct_idx j = 0; j < sf->s.n && !hit; j++)
            hit = d.seg_elem[sf->s.seg[j]] == ids[k];
        cr_assert(hit, "shell %ld missing from surface 1", ids[k]);
    }
    /* /GRNOD/PART/15 = part 1: the nodes of /SHELL/1 (the scan's table,
     * without shell 897 of part 2, the last one). */
    unsigned char *want = calloc((size_t)s.maxid + 1, 1), *tab = calloc((size_t)s.maxid + 1, 1);
    cr_assert_eq(s.shell_nodes[s.nshell - 1][0], 897);
    for (long e = 0; e < s.nshell - 1; e++)
        for (int k = 1; k < 5; k++)
            want[s.shell_nodes[e][k]] = 1;
    const ctd_group *g = ctd_deck_group(&d, 15);
    cr_assert_not_null(g);
    group_ids(&d, g, tab, s.maxid);
    cr_assert_eq(memcmp(tab, want, (size_t)s.maxid + 1), 0);
    /* /GRNOD/GRSHEL/5 = the nodes of the shells of /GRSHEL/SHEL/1. */
    n = list_ids(path, "/GRSHEL/SHEL/1", ids, 4096);
    memset(want, 0, (size_t)s.maxid + 1);
    for (long k = 0; k < n; k++) {
        long e = 0;
        while (e < s.nshell && s.shell_nodes[e][0] != ids[k])
            e++;
        cr_assert_lt(e, s.nshell);
        for (int c = 1; c < 5; c++)
            want[s.shell_nodes[e][c]] = 1;
    }
    g = ctd_deck_group(&d, 5);
    cr_assert_not_null(g);
    group_ids(&d, g, tab, s.maxid);
    cr_assert_eq(memcmp(tab, want, (size_t)s.maxid + 1), 0);
    cr_assert(strstr(ctd_deck_warning(&d), "/INTER/TYPE7 (2)"));
    cr_assert(strstr(ctd_deck_warning(&d), "#include (1)"));
    free(want);
    free(tab);
    scan_free(&s);
    ctd_deck_destroy(&d);
}

/* ---- Errors ------------------------------------------------------------ */

Test(import_radioss, error_decks)
{
    struct {
        const char *file;
        int code, line;
        const char *w1, *w2;
    } c[] = {
        {"bad_number.rad", CT_ERR_ARG, 5, "field 'y' of /NODE", "expected a number, got '1.0x2'"},
        {"missing_field.rad", CT_ERR_ARG, 9, "field 'n4' of /SHELL/1", "missing"},
        {"nan_coord.rad", CT_ERR_NONFINITE, 6, "field 'z' of /NODE", "NaN"},
        {"dup_node.rad", CT_ERR_ARG, 7, "node id 2", "first on line 4"},
        {"unknown_node.rad", CT_ERR_RANGE, 8, "field 'n3' of /SH3N/4", "unknown node id 99"},
        {"repeated_node.rad", CT_ERR_DUPNODE, 9, "field 'n3' of /SHELL/1", "repeats field 'n2'"},
        {"unknown_part.rad", CT_ERR_RANGE, 14, "/SURF/PART/5", "unknown part 7"},
        {"no_node.rad", CT_ERR_ARG, 6, "no /NODE", NULL},
        {"zero_area.rad", CT_ERR_DEGENERATE, 11, "/SHELL/3 element 21", "zero area"},
        {"bad_keyword.rad", CT_ERR_ARG, 4, "/SHELL/", "positive id"},
        {"unknown_grshel.rad", CT_ERR_RANGE, 16, "/SURF/GRSHEL/2", "unknown /GRSHEL/SHEL 9"},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        char path[1024];
        data_path(path, sizeof path, c[i].file);
        cr_assert_eq(access(path, R_OK), 0, "%s not found", path);
        expect_error(path, c[i].code, c[i].line, c[i].w1, c[i].w2);
    }
}

Test(import_radioss, missing_and_empty_file)
{
    expect_error("/nonexistent-dir/none.rad", CT_ERR_ARG, 0, "/nonexistent-dir/none.rad",
                 "cannot open");
    char path[256];
    tmp_path(path, sizeof path, "empty.rad");
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fclose(f);
    expect_error(path, CT_ERR_ARG, 0, "empty", NULL);
    unlink(path);
}

Test(import_radioss, long_line)
{
    char path[256];
    tmp_path(path, sizeof path, "long_line.rad");
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "/NODE\n         1                   0                   0                   0\n");
    fprintf(f, "         2");
    for (int i = 0; i < 5000; i++)
        fputc(' ', f);
    fprintf(f, "1\n         3                   0                   0                   0\n");
    fclose(f);
    expect_error(path, CT_ERR_ARG, 3, "4096", NULL);
    /* A line of exactly 4096 characters is accepted (a list line of zeros). */
    f = fopen(path, "w");
    fprintf(f, "/NODE\n         1                   0                   0                   0\n");
    fprintf(f, "/GRNOD/NODE/1\ntitle\n");
    for (int i = 0; i < 4095; i++)
        fputc(' ', f);
    fprintf(f, "1\n");
    fclose(f);
    ctd_deck d;
    load(path, &d);
    cr_assert_eq(d.ngroup, 1);
    cr_assert_eq(d.group[0].s.n, 1);
    ctd_deck_destroy(&d);
    unlink(path);
}

/* A NUL byte inside a keyword (found by fuzzing: the keyword's id was
 * looked for with strchr, which stopped at the NUL and returned NULL) is an
 * error naming the line and the column, not a crash; so is one in a data
 * line (an error before too, but one that did not say why). */
Test(import_radioss, nul_byte)
{
    char path[256];
    tmp_path(path, sizeof path, "nul_byte.rad");
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    static const char kw[] = "/GRNOD/GRSHEL\0/9\n";
    fwrite(kw, 1, sizeof kw - 1, f);
    fclose(f);
    expect_error(path, CT_ERR_ARG, 1, "NUL byte", "column 14");
    f = fopen(path, "wb");
    cr_assert_not_null(f);
    static const char node[] = "/NODE\n         1                 1.5\0"
                               "                   0                   0\n";
    fwrite(node, 1, sizeof node - 1, f);
    fclose(f);
    expect_error(path, CT_ERR_ARG, 2, "NUL byte", "column 31");
    unlink(path);
}

/* ---- Formats ----------------------------------------------------------- */

static void check_formats(const ctd_deck *d)
{
    /* Node values as written in the deck (see tests/data/radioss/formats.rad). */
    const double want[5][4] = {{1, 15, -0.5, 1},
                               {2, 0.25, 0, 15},
                               {3, 3, 4, -0.25},
                               {4, 1, 1, 1},
                               {5, -0.0125, 2, 0}};
    cr_assert_eq(d->mesh.nodes.n, 5);
    for (int i = 0; i < 5; i++) {
        cr_assert_eq(d->node_id[i], (int64_t)want[i][0]);
        cr_assert_eq(d->mesh.nodes.x[i], (ct_real)want[i][1], "x of node %d", i + 1);
        cr_assert_eq(d->mesh.nodes.y[i], (ct_real)want[i][2], "y of node %d", i + 1);
        cr_assert_eq(d->mesh.nodes.z[i], (ct_real)want[i][3], "z of node %d", i + 1);
    }
    cr_assert_eq(ctd_deck_node(d, 4), 3);
    cr_assert_eq(ctd_deck_node(d, 6), -1);
    /* Shell 7 (left-justified id) 1 2 3 4; shell 8 a triangle 4 3 5 5. */
    cr_assert_eq(d->mesh.nseg, 2);
    cr_assert_eq(d->seg_elem[0], 7);
    cr_assert_eq(d->seg_elem[1], 8);
    cr_assert_eq(d->seg_part[1], 12);
    const ct_idx s0[4] = {0, 1, 2, 3}, s1[4] = {3, 2, 4, 4};
    const ct_idx *n[4] = {d->mesh.n1, d->mesh.n2, d->mesh.n3, d->mesh.n4};
    for (int k = 0; k < 4; k++) {
        cr_assert_eq(n[k][0], s0[k]);
        cr_assert_eq(n[k][1], s1[k]);
    }
    cr_assert_eq(d->seg_line[0], 19);
    cr_assert_eq(d->seg_line[1], 20);
    /* /PART/12 with a blank title line. */
    cr_assert_eq(d->npart, 1);
    cr_assert_str_eq(d->part[0].title, "");
    cr_assert_eq(d->part[0].prop, 5);
    cr_assert_eq(d->part[0].mat, 6);
    cr_assert_str_eq(d->title, "formats test deck");
    /* Groups: a list over two lines with a blank field; a forward reference
     * to /GRSHEL/SHEL/3 (shells 7 and 8: all five nodes); part 12. */
    const ctd_group *g = ctd_deck_group(d, 4);
    cr_assert_not_null(g);
    cr_assert_eq(g->s.n, 3);
    for (int k = 0; k < 3; k++)
        cr_assert_eq(g->s.node[k], k);
    cr_assert_eq(ctd_deck_group(d, 9)->s.n, 5);
    cr_assert_eq(ctd_deck_group(d, 10)->s.n, 5);
    cr_assert_eq(ctd_deck_surf(d, 6)->s.n, 2);
    cr_assert_eq(ctd_deck_surf(d, 11)->s.n, 2);
    /* The unsupported blocks (garbage data lines included) are skipped,
     * /BEGIN silently, the rest listed; lines after /END are not read. */
    cr_assert_str_eq(ctd_deck_warning(d),
                     "unsupported keywords ignored: /MAT/PLAS_JOHNS (1), /INTER/TYPE7 (2)");
    cr_assert_eq(d->nwarn, 2);
}

Test(import_radioss, number_formats)
{
    char path[1024];
    data_path(path, sizeof path, "formats.rad");
    ctd_deck d;
    load(path, &d);
    check_formats(&d);
    ctd_deck_destroy(&d);
}

Test(import_radioss, crlf_line_ends)
{
    char path[1024], tmp[256];
    data_path(path, sizeof path, "formats.rad");
    tmp_path(tmp, sizeof tmp, "crlf.rad");
    FILE *in = fopen(path, "r"), *out = fopen(tmp, "w");
    cr_assert(in && out);
    int ch;
    while ((ch = fgetc(in)) != EOF) {
        if (ch == '\n')
            fputc('\r', out);
        fputc(ch, out);
    }
    fclose(in);
    fclose(out);
    ctd_deck d;
    load(tmp, &d);
    check_formats(&d);
    ctd_deck_destroy(&d);
    unlink(tmp);
}

/* ---- Speed ------------------------------------------------------------- */

Test(import_radioss, large_deck_linear_time, .timeout = 120)
{
    int n = ctt_checking() ? 100 : 500; /* n x n quads, (n+1)^2 nodes */
    char path[256];
    tmp_path(path, sizeof path, "large.rad");
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "/NODE\n");
    /* Ids in a scattered order (a permutation of 1..N by a stride), so the
     * id -> index map is exercised beyond the identity. */
    long nn = (long)(n + 1) * (n + 1), stride = 7919;
    for (long i = 0; i < nn; i++)
        fprintf(f, "%10ld%20.6f%20.6f%20.6f\n", 1 + (i * stride) % nn, 0.1 * (double)(i % (n + 1)),
                0.1 * (double)(i / (n + 1)), 0.0);
    fprintf(f, "/SHELL/1\n");
    for (long j = 0, e = 1; j < n; j++)
        for (long i = 0; i < n; i++, e++) {
            long a = i + (n + 1) * j, b = a + 1, c = a + n + 2, d = a + n + 1;
            fprintf(f, "%10ld%10ld%10ld%10ld%10ld\n", e, 1 + (a * stride) % nn,
                    1 + (b * stride) % nn, 1 + (c * stride) % nn, 1 + (d * stride) % nn);
        }
    fprintf(f, "/SURF/PART/1\nall\n         1\n");
    fclose(f);
    ctd_deck d;
    double sec = load_timed(path, &d);
    cr_assert_eq(d.mesh.nodes.n, nn);
    cr_assert_eq(d.mesh.nseg, (ct_idx)n * n);
    cr_assert_eq(ctd_deck_surf(&d, 1)->s.n, (ct_idx)n * n);
    /* Segment 0's corners are the nodes written first for (0,0), (1,0),
     * (1,1), (0,1): check through their coordinates. */
    ct_idx c = d.mesh.n3[0];
    cr_assert_eq(d.mesh.nodes.x[c], (ct_real)0.1);
    cr_assert_eq(d.mesh.nodes.y[c], (ct_real)0.1);
    cr_assert_eq(d.node_id[c], 1 + ((long)(n + 2) * stride) % nn);
    ctd_deck_destroy(&d);
    unlink(path);
    cr_log_info("import_radioss: %ld nodes and %ld quads read in %.3f s", nn, (long)n * n, sec);
    /* Linear time: about 0.3 s here; a quadratic id lookup would take minutes. */
    cr_assert_lt(sec, ctt_checking() ? 20.0 : 5.0, "%.2f s", sec);
}

/* Lists that repeat one id (found by review while fuzzing): each
 * repetition of a part or /GRSHEL id used to go through all its elements
 * again, so a list naming a part of n elements n times took n^2 steps
 * (55 s for this 7 MB deck, minutes for larger ones). */
Test(import_radioss, repeated_list_ids_linear_time, .timeout = 120)
{
    int n = ctt_checking() ? 60 : 200; /* n x n quads of part 1 */
    long ne = (long)n * n, nn = (long)(n + 1) * (n + 1);
    char path[256];
    tmp_path(path, sizeof path, "repeated_ids.rad");
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "/NODE\n");
    for (long i = 0; i < nn; i++)
        fprintf(f, "%10ld%20.6f%20.6f%20.6f\n", i + 1, 0.1 * (double)(i % (n + 1)),
                0.1 * (double)(i / (n + 1)), 0.0);
    fprintf(f, "/SHELL/1\n");
    for (long j = 0, e = 1; j < n; j++)
        for (long i = 0; i < n; i++, e++) {
            long a = i + (n + 1) * j;
            fprintf(f, "%10ld%10ld%10ld%10ld%10ld\n", e, a + 1, a + 2, a + n + 3, a + n + 2);
        }
    fprintf(f, "/GRSHEL/SHEL/4\nall shells\n");
    for (long e = 1; e <= ne; e++)
        fprintf(f, "%10ld%s", e, e % 100 == 0 || e == ne ? "\n" : "");
    /* Each list names its part or /GRSHEL ne times, 100 to a line. */
    const char *lists[4][2] = {{"/GRNOD/PART/1", "1"},
                               {"/SURF/PART/2", "1"},
                               {"/SURF/GRSHEL/3", "4"},
                               {"/GRNOD/GRSHEL/5", "4"}};
    for (int k = 0; k < 4; k++) {
        fprintf(f, "%s\nrepeated\n", lists[k][0]);
        for (long e = 1; e <= ne; e++)
            fprintf(f, "%10s%s", lists[k][1], e % 100 == 0 || e == ne ? "\n" : "");
    }
    fclose(f);
    ctd_deck d;
    double sec = load_timed(path, &d);
    cr_assert_eq(ctd_deck_group(&d, 1)->s.n, (ct_idx)nn);
    cr_assert_eq(ctd_deck_surf(&d, 2)->s.n, (ct_idx)ne);
    cr_assert_eq(ctd_deck_surf(&d, 3)->s.n, (ct_idx)ne);
    cr_assert_eq(ctd_deck_group(&d, 5)->s.n, (ct_idx)nn);
    ctd_deck_destroy(&d);
    unlink(path);
    cr_log_info("import_radioss: 4 lists of %ld repeated ids read in %.3f s", ne, sec);
    /* Linear time: well under a second; the quadratic passes took minutes. */
    cr_assert_lt(sec, ctt_checking() ? 20.0 : 5.0, "%.2f s", sec);
}
