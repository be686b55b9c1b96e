/*
 * test_deck_select.c -- a scene that imports a Radioss deck and selects
 * from it (suite "deck_select"): `{surf: N}` and `{group: N}` selections
 * (driver/model_select.c), the deck's shells and surface faces entering the
 * model (driver/model.c), unknown ids refused, and a contact run against a
 * deck surface.
 *
 * The deck is written here (deck_write): a 3 x 2 grid of 10 mm cells at
 * z = 0 whose left four cells are /SHELL quads (part 1) and whose right
 * column is four /SH3N triangles (part 2), one /BRICK (part 3) away from
 * it, and the sets /SURF/PART (one part, two parts), /SURF/GRSHEL,
 * /SURF/PART/EXT (the brick's faces), /GRNOD/NODE, /GRNOD/PART (shells,
 * brick) and /GRNOD/GRSHEL. Every expectation below (node ids of each
 * segment and of each group, segment counts of each kind, which faces a
 * `where` keeps) is read by hand from that text, not from the reader.
 *
 * Checked:
 *  - the model: 20 deck nodes then 8 generated ones; 26 segments: the 8
 *    shells as shell elements of parts 1 and 2, the outer faces of the two
 *    brick parts (6 + 6), and the 6 faces /SURF/PART/EXT made (seg_src
 *    CTD_SEGSRC_DECK), outward;
 *  - each surface and node group selects exactly the deck's segments and
 *    nodes (as sets of node ids), with and without a `where` filter; the
 *    scene's own `{surf: 1}` and `{group: 10}` reach the interface and the
 *    boundary condition;
 *  - an unknown surface or group id, and a surface id where nodes are
 *    expected (and the reverse), fail the load (CT_ERR_RANGE, CT_ERR_ARG)
 *    and `contact check` (exit 2) naming the file, the line and the field;
 *    the model's own selection refuses an unknown id naming file and line;
 *  - a block dropped at 1 m/s on the deck surface (TYPE24, main {surf: 1})
 *    stops above it and bounces, where with the brick's far surface as
 *    main it falls through (free flight to z = 0.0007 - 0.002 m).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_cli.h"
#include "test_util.h"

/* ---- The deck ------------------------------------------------------------ */

static void node(FILE *f, int id, double x, double y, double z)
{
    fprintf(f, "%10d%20.6f%20.6f%20.6f\n", id, x, y, z);
}

/* One line of 10-column integer fields (n of them). */
static void row(FILE *f, int n, const int *v)
{
    for (int i = 0; i < n; i++)
        fprintf(f, "%10d", v[i]);
    fputc('\n', f);
}
#define ROW(f, ...)                                                                        \
    row((f), (int)(sizeof((int[]){__VA_ARGS__}) / sizeof(int)), (int[]){__VA_ARGS__})

/* Nodes 1-12: the grid, row by row (y = 0, 0.01, 0.02), x = 0 .. 0.03:
 *      9  10  11  12
 *      5   6   7   8
 *      1   2   3   4
 * Nodes 21-28: the brick, 21-24 at z = 0 and 25-28 above them at z = 0.01,
 * over x 0.10 .. 0.11, y 0 .. 0.01. */
static void deck_write(const char *dir)
{
    char p[256];
    snprintf(p, sizeof p, "%s/deck.rad", dir);
    FILE *f = fopen(p, "w");
    cr_assert_not_null(f);
    fprintf(f, "# test_deck_select: shells, triangles, a brick and their sets\n/NODE\n");
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 4; i++)
            node(f, 1 + i + 4 * j, 0.01 * i, 0.01 * j, 0);
    const double bx[4][2] = {{0.10, 0}, {0.11, 0}, {0.11, 0.01}, {0.10, 0.01}};
    for (int k = 0; k < 8; k++)
        node(f, 21 + k, bx[k % 4][0], bx[k % 4][1], k < 4 ? 0 : 0.01);
    fprintf(f, "/PART/1\nquads\n");
    ROW(f, 1, 1);
    fprintf(f, "/PART/2\ntriangles\n");
    ROW(f, 1, 1);
    fprintf(f, "/PART/3\nbrick\n");
    ROW(f, 1, 1);
    fprintf(f, "/SHELL/1\n");
    ROW(f, 101, 1, 2, 6, 5);
    ROW(f, 102, 2, 3, 7, 6);
    ROW(f, 103, 5, 6, 10, 9);
    ROW(f, 104, 6, 7, 11, 10);
    fprintf(f, "/SH3N/2\n");
    ROW(f, 201, 3, 4, 8);
    ROW(f, 202, 3, 8, 7);
    ROW(f, 203, 7, 8, 12);
    ROW(f, 204, 7, 12, 11);
    fprintf(f, "/BRICK/3\n");
    ROW(f, 301, 21, 22, 23, 24, 25, 26, 27, 28);
    fprintf(f, "/GRSHEL/SHEL/5\ntwo opposite quads\n");
    ROW(f, 101, 104);
    fprintf(f, "/SURF/PART/1\nthe quads\n");
    ROW(f, 1);
    fprintf(f, "/SURF/PART/2\nall shells\n");
    ROW(f, 1, 2);
    fprintf(f, "/SURF/GRSHEL/3\nthe two quads of grshel 5\n");
    ROW(f, 5);
    fprintf(f, "/SURF/PART/EXT/4\nthe brick's faces\n");
    ROW(f, 3);
    fprintf(f, "/GRNOD/NODE/7\nfour nodes\n");
    ROW(f, 1, 5, 9, 12);
    fprintf(f, "/GRNOD/PART/8\nthe triangles' nodes\n");
    ROW(f, 2);
    fprintf(f, "/GRNOD/GRSHEL/9\nthe nodes of grshel 5\n");
    ROW(f, 5);
    fprintf(f, "/GRNOD/PART/10\nthe brick's nodes\n");
    ROW(f, 3);
    fprintf(f, "/END\n");
    cr_assert_eq(fclose(f), 0);
}

/* The scene: the deck, then a generated one-brick block 8 mm wide over the
 * quads, its bottom 0.7 mm above them (0.2 mm above the 0.5 mm gap),
 * dropped at 1 m/s. NODES is the selection of the second fixed condition
 * (line 14), MAIN the interface's main surface (line 17). */
static const char SCENE[] =
    "title: deck select\n"
    "end_time: 2.0e-3\n"
    "output: {every: 2.0e-4, vtu: false, csv: false}\n"
    "mesh:\n"
    "  - import: {file: deck.rad}\n"
    "  - generate: {kind: block, part: 20, cells: [1, 1, 1], size: [0.008, 0.008, 0.008],"
    " origin: [0.006, 0.006, 0.0007]}\n"
    "parts:\n"
    "  - {id: 1, element: shell, thickness: 0.002, material: {E: 1.0e7, nu: 0.3, rho: 1000}}\n"
    "  - {id: 2, element: shell, thickness: 0.002, material: {E: 1.0e7, nu: 0.3, rho: 1000}}\n"
    "  - {id: 3, element: brick, material: {E: 1.0e7, nu: 0.3, rho: 1000}}\n"
    "  - {id: 20, element: brick, material: {E: 1.0e7, nu: 0.3, rho: 1000}}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {parts: [1, 2]}}\n"
    "  - {kind: fixed, nodes: %s}\n"
    "  - {kind: initial_velocity, nodes: {part: 20}, value: [0, 0, -1]}\n"
    "interfaces:\n"
    "  - {type: 24, name: deck, main: %s, secondary: {part: 20}, gap: 0.0005}\n";

/* Write the deck and DIR/NAME with these two selections. */
static void scene_write(const char *dir, const char *name, const char *nodes, const char *main)
{
    char text[2048];
    snprintf(text, sizeof text, SCENE, nodes, main);
    ctt_write_file(dir, name, text);
}

typedef struct loaded {
    char path[128];
    ctd_scene *sc;
    ctd_model m;
} loaded;

static void load_build(loaded *l, const char *dir, const char *name)
{
    static ctd_scene_err se;
    char err[1024] = "";
    snprintf(l->path, sizeof l->path, "%s/%s", dir, name);
    int rc = ctd_scene_load(l->path, &l->sc, &se);
    cr_assert_eq(rc, CT_OK, "%s", se.count ? se.msg[0].text : "?");
    rc = ctd_model_build(&l->m, l->sc, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "model: %s", err);
}

static void loaded_free(loaded *l)
{
    ctd_model_destroy(&l->m);
    ctd_scene_free(l->sc);
}

/* ---- Sets of node ids ------------------------------------------------------ */

/* A segment as its distinct corner ids, sorted, in 4 slots (0 after a
 * triangle's third). */
typedef struct corners {
    long id[4];
} corners;

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

static int cmp_corners(const void *a, const void *b)
{
    const corners *x = a, *y = b;
    for (int k = 0; k < 4; k++)
        if (x->id[k] != y->id[k])
            return x->id[k] < y->id[k] ? -1 : 1;
    return 0;
}

static corners corners_of(const long *v, int n)
{
    corners c = {{0, 0, 0, 0}};
    long t[4];
    memcpy(t, v, sizeof(long) * (size_t)n);
    qsort(t, (size_t)n, sizeof *t, cmp_long);
    for (int k = 0; k < n; k++)
        c.id[k] = t[k];
    return c;
}

/* The corners of model segment s, by scene node id. */
static corners seg_corners(const ctd_model *m, ct_idx s)
{
    const ct_idx q[4] = {m->mesh.n1[s], m->mesh.n2[s], m->mesh.n3[s], m->mesh.n4[s]};
    long v[4];
    int n = 0;
    for (int a = 0; a < 4; a++) {
        long id = (long)m->node_id[q[a]];
        int dup = 0;
        for (int b = 0; b < n; b++)
            dup |= v[b] == id;
        if (!dup)
            v[n++] = id;
    }
    return corners_of(v, n);
}

/* Expected segments: n lists of 3 or 4 corner ids (a 0 in the fourth slot:
 * a triangle). */
static void expect_surface(const ctd_model *m, const ct_surface *got, int n, const long (*want)[4],
                           const char *what)
{
    cr_assert_eq(got->n, n, "%s: %d segments, expected %d", what, got->n, n);
    corners *g = malloc(sizeof *g * (size_t)(n + 1)), *w = malloc(sizeof *w * (size_t)(n + 1));
    cr_assert(g && w);
    for (int k = 0; k < n; k++) {
        g[k] = seg_corners(m, got->seg[k]);
        w[k] = corners_of(want[k], want[k][3] ? 4 : 3);
    }
    qsort(g, (size_t)n, sizeof *g, cmp_corners);
    qsort(w, (size_t)n, sizeof *w, cmp_corners);
    for (int k = 0; k < n; k++)
        cr_expect(cmp_corners(&g[k], &w[k]) == 0,
                  "%s: segment %d is %ld %ld %ld %ld, expected %ld %ld %ld %ld", what, k,
                  g[k].id[0], g[k].id[1], g[k].id[2], g[k].id[3], w[k].id[0], w[k].id[1],
                  w[k].id[2], w[k].id[3]);
    free(g);
    free(w);
}

static void expect_nodes(const ctd_model *m, const ct_nodeset *got, int n, const long *want,
                         const char *what)
{
    cr_assert_eq(got->n, n, "%s: %d nodes, expected %d", what, got->n, n);
    long *g = malloc(sizeof *g * (size_t)(n + 1));
    cr_assert_not_null(g);
    for (int k = 0; k < n; k++)
        g[k] = (long)m->node_id[got->node[k]];
    qsort(g, (size_t)n, sizeof *g, cmp_long);
    for (int k = 0; k < n; k++)
        cr_expect_eq(g[k], want[k], "%s: node %d is %ld, expected %ld", what, k, g[k], want[k]);
    free(g);
}

static ct_surface select_surf(const ctd_model *m, int64_t id, const ctd_where *w)
{
    ctd_scene_sel sel;
    memset(&sel, 0, sizeof sel);
    sel.surf = id;
    if (w)
        sel.where = *w;
    ct_surface s;
    char err[512] = "";
    cr_assert_eq(ctd_model_select_surface(m, &sel, &s, err, sizeof err), CT_OK, "%s", err);
    return s;
}

static ct_nodeset select_group(const ctd_model *m, int64_t id, const ctd_where *w)
{
    ctd_scene_sel sel;
    memset(&sel, 0, sizeof sel);
    sel.group = id;
    if (w)
        sel.where = *w;
    ct_nodeset s;
    char err[512] = "";
    cr_assert_eq(ctd_model_select_nodes(m, &sel, &s, err, sizeof err), CT_OK, "%s", err);
    return s;
}

/* The deck's segments, by hand from deck_write. */
static const long QUADS[4][4] = {{1, 2, 6, 5}, {2, 3, 7, 6}, {5, 6, 10, 9}, {6, 7, 11, 10}};
static const long SHELLS[8][4] = {{1, 2, 6, 5}, {2, 3, 7, 6}, {5, 6, 10, 9}, {6, 7, 11, 10},
                                  {3, 4, 8, 0}, {3, 8, 7, 0},  {7, 8, 12, 0}, {7, 12, 11, 0}};
static const long GRSHEL5[2][4] = {{1, 2, 6, 5}, {6, 7, 11, 10}};
/* The brick's local faces (import_radioss.h): 1 4 3 2, 5 6 7 8, 1 2 6 5,
 * 2 3 7 6, 3 4 8 7, 4 1 5 8 of its corners 21 .. 28. */
static const long BRICK_FACES[6][4] = {{21, 24, 23, 22}, {25, 26, 27, 28}, {21, 22, 26, 25},
                                       {22, 23, 27, 26}, {23, 24, 28, 27}, {24, 21, 25, 28}};

Test(deck_select, model_holds_the_deck)
{
    char dir[64];
    ctt_tmpdir(dir, "deck");
    deck_write(dir);
    scene_write(dir, "scene.yaml", "{group: 10}", "{surf: 1}");
    loaded l;
    load_build(&l, dir, "scene.yaml");
    const ctd_model *m = &l.m;
    /* Nodes: the deck's 20 in its order (ids 1-12, 21-28), then the
     * block's 8 numbered from the largest deck id + 1 (29-36). */
    cr_assert_eq(m->mesh.nodes.n, 28);
    cr_expect(m->mesh_node_off[0] == 0 && m->mesh_node_off[1] == 20 && m->mesh_node_off[2] == 28);
    for (int k = 0; k < 28; k++) {
        long want = k < 12 ? k + 1 : k + 9;
        cr_expect_eq((long)m->node_id[k], want, "node %d has id %ld", k, (long)m->node_id[k]);
    }
    /* Segments: 8 deck shells, 6 + 6 outer brick faces, 6 deck faces. */
    cr_assert_eq(m->mesh.nseg, 26);
    int nel = 0, nface = 0, ndeck = 0;
    for (ct_idx s = 0; s < m->mesh.nseg; s++) {
        if (m->seg_src[s] == CTD_SEGSRC_ELEMENT) {
            nel++;
            cr_expect(m->seg_part[s] == 1 || m->seg_part[s] == 2);
            cr_expect_eq(m->seg_shell[s], 1, "deck shell %d is no shell element", s);
            cr_expect_eq(m->seg_mesh[s], 0);
            cr_expect(m->seg_deck[s] >= 0 && m->seg_deck[s] < 8, "segment %d: deck index %d", s,
                      m->seg_deck[s]);
            cr_expect(fabs((double)m->seg_thick[s] - 0.002) < 1e-9);
        } else if (m->seg_src[s] == CTD_SEGSRC_FACE) {
            nface++;
            cr_expect(m->seg_part[s] == 3 || m->seg_part[s] == 20);
        } else {
            cr_expect_eq(m->seg_src[s], CTD_SEGSRC_DECK);
            ndeck++;
            cr_expect_eq(m->seg_part[s], 3);
            cr_expect_eq(m->seg_mesh[s], 0);
            cr_expect_geq(m->seg_deck[s], 8, "a deck face indexes the deck's faces, after its "
                                             "8 shells");
        }
    }
    cr_expect(nel == 8 && nface == 12 && ndeck == 6, "%d element, %d face, %d deck segments", nel,
              nface, ndeck);
    /* Element sets: parts 1 and 2 hold the deck's 4 quads and 4 triangles
     * as shells; part 3 its brick. */
    int seen = 0;
    for (int s = 0; s < m->nset; s++) {
        const ctd_model_set *st = &m->set[s];
        if (st->part == 1 || st->part == 2) {
            cr_expect_eq(st->element, CTD_ELEM_SHELL, "part %lld", (long long)st->part);
            cr_expect_eq(st->nelem, 4, "part %lld has %d elements", (long long)st->part,
                         st->nelem);
            seen++;
        } else if (st->part == 3) {
            cr_expect_eq(st->element, CTD_ELEM_BRICK);
            cr_expect_eq(st->nelem, 1);
            seen++;
        }
    }
    cr_expect_eq(seen, 3);
    loaded_free(&l);
    ctt_rmtree(dir);
}

Test(deck_select, surfaces_and_groups_are_the_decks)
{
    char dir[64];
    ctt_tmpdir(dir, "deck");
    deck_write(dir);
    scene_write(dir, "scene.yaml", "{group: 10}", "{surf: 1}");
    loaded l;
    load_build(&l, dir, "scene.yaml");
    const ctd_model *m = &l.m;

    ct_surface s = select_surf(m, 1, NULL);
    expect_surface(m, &s, 4, QUADS, "surf 1 (part 1)");
    ct_free(s.seg);
    s = select_surf(m, 2, NULL);
    expect_surface(m, &s, 8, SHELLS, "surf 2 (parts 1, 2)");
    ct_free(s.seg);
    s = select_surf(m, 3, NULL);
    expect_surface(m, &s, 2, GRSHEL5, "surf 3 (grshel 5)");
    ct_free(s.seg);
    /* The brick's six faces: the deck's own segments, each facing out of
     * the brick (its centre at (0.105, 0.005, 0.005)). */
    s = select_surf(m, 4, NULL);
    expect_surface(m, &s, 6, BRICK_FACES, "surf 4 (the brick's faces)");
    const ct_nodes *nd = &m->mesh.nodes;
    for (ct_idx k = 0; k < s.n; k++) {
        ct_idx g = s.seg[k];
        cr_expect_eq(m->seg_src[g], CTD_SEGSRC_DECK, "surf 4 segment %d", g);
        const ct_idx q[4] = {m->mesh.n1[g], m->mesh.n2[g], m->mesh.n3[g], m->mesh.n4[g]};
        double d1[3] = {nd->x[q[2]] - nd->x[q[0]], nd->y[q[2]] - nd->y[q[0]],
                        nd->z[q[2]] - nd->z[q[0]]};
        double d2[3] = {nd->x[q[3]] - nd->x[q[1]], nd->y[q[3]] - nd->y[q[1]],
                        nd->z[q[3]] - nd->z[q[1]]};
        double n[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                       d1[0] * d2[1] - d1[1] * d2[0]};
        double c[3] = {0, 0, 0};
        for (int a = 0; a < 4; a++) {
            c[0] += 0.25 * nd->x[q[a]];
            c[1] += 0.25 * nd->y[q[a]];
            c[2] += 0.25 * nd->z[q[a]];
        }
        double out = n[0] * (c[0] - 0.105) + n[1] * (c[1] - 0.005) + n[2] * (c[2] - 0.005);
        cr_expect_gt(out, 0, "surf 4 segment %d faces into the brick", g);
    }
    ct_free(s.seg);
    /* A where filter: x < 0.025 keeps the quads (every triangle has a corner
     * at x = 0.03). */
    ctd_where w = {1, {0}, {CTD_WHERE_LT}, {0.025}};
    s = select_surf(m, 2, &w);
    expect_surface(m, &s, 4, QUADS, "surf 2 where x < 0.025");
    ct_free(s.seg);

    static const long g7[] = {1, 5, 9, 12}, g8[] = {3, 4, 7, 8, 11, 12},
                      g9[] = {1, 2, 5, 6, 7, 10, 11}, g10[] = {21, 22, 23, 24, 25, 26, 27, 28},
                      g8y[] = {7, 8, 11, 12};
    ct_nodeset ns = select_group(m, 7, NULL);
    expect_nodes(m, &ns, 4, g7, "group 7 (/GRNOD/NODE)");
    ct_nodeset_destroy(&ns);
    ns = select_group(m, 8, NULL);
    expect_nodes(m, &ns, 6, g8, "group 8 (/GRNOD/PART of the triangles)");
    ct_nodeset_destroy(&ns);
    ns = select_group(m, 9, NULL);
    expect_nodes(m, &ns, 7, g9, "group 9 (/GRNOD/GRSHEL)");
    ct_nodeset_destroy(&ns);
    ns = select_group(m, 10, NULL);
    expect_nodes(m, &ns, 8, g10, "group 10 (/GRNOD/PART of the brick)");
    ct_nodeset_destroy(&ns);
    ctd_where wy = {1, {1}, {CTD_WHERE_GT}, {0.005}};
    ns = select_group(m, 8, &wy);
    expect_nodes(m, &ns, 4, g8y, "group 8 where y > 0.005");
    ct_nodeset_destroy(&ns);

    /* The scene's own selections: {surf: 1} is the interface's main
     * surface, {group: 10} holds the brick fixed (and nothing else but the
     * shells, fixed by the first condition). */
    const ctd_scene *sc = l.sc;
    cr_assert_eq(sc->interfaces_count, 1);
    cr_expect_eq(sc->interfaces[0].main->surf, 1);
    cr_expect_eq(sc->interfaces[0].main->line, 17);
    char err[512] = "";
    cr_assert_eq(ctd_model_select_surface(m, sc->interfaces[0].main, &s, err, sizeof err), CT_OK,
                 "%s", err);
    expect_surface(m, &s, 4, QUADS, "interfaces[0].main");
    ct_free(s.seg);
    cr_expect_eq(sc->boundary[1].nodes->group, 10);
    cr_expect_eq(sc->boundary[1].nodes->line, 14);
    for (ct_idx k = 0; k < m->mesh.nodes.n; k++) {
        long id = (long)m->node_id[k];
        int fixed = id <= 12 || (id >= 21 && id <= 28);
        cr_expect_eq(m->bc_mask[k], fixed ? 7 : 0, "node %ld: mask %d", id, m->bc_mask[k]);
    }

    /* The model's selection refuses what the deck does not define, naming
     * the scene file and the selection's line. */
    ctd_scene_sel bad;
    memset(&bad, 0, sizeof bad);
    bad.surf = 99;
    bad.line = 17;
    cr_expect_eq(ctd_model_select_surface(m, &bad, &s, err, sizeof err), CT_ERR_RANGE);
    cr_expect(strstr(err, "scene.yaml:17: surface 99 is in no imported deck") != NULL, "%s", err);
    memset(&bad, 0, sizeof bad);
    bad.group = 98;
    bad.line = 14;
    cr_expect_eq(ctd_model_select_nodes(m, &bad, &ns, err, sizeof err), CT_ERR_RANGE);
    cr_expect(strstr(err, "scene.yaml:14: node group 98 is in no imported deck") != NULL, "%s",
              err);
    loaded_free(&l);
    ctt_rmtree(dir);
}

/* The message of a failed load for `field`, or NULL. */
static const ctd_scene_msg *msg_for(const ctd_scene_err *e, const char *field)
{
    for (int k = 0; k < e->count && k < CTD_SCENE_MAXERR; k++)
        if (!strcmp(e->msg[k].field, field))
            return &e->msg[k];
    return NULL;
}

Test(deck_select, unknown_ids_refused)
{
    char dir[64];
    ctt_tmpdir(dir, "deck");
    deck_write(dir);
    scene_write(dir, "unknown.yaml", "{group: 98}", "{surf: 99}");
    scene_write(dir, "misused.yaml", "{surf: 1}", "{group: 7}");
    static ctd_scene_err se;
    ctd_scene *sc = NULL;
    char p[128];

    /* Ids no deck defines: CT_ERR_RANGE, one message each. */
    snprintf(p, sizeof p, "%s/unknown.yaml", dir);
    cr_expect_eq(ctd_scene_load(p, &sc, &se), CT_ERR_RANGE);
    cr_expect_null(sc);
    cr_expect_eq(se.count, 2, "%d errors: %s", se.count, se.msg[0].text);
    const ctd_scene_msg *g = msg_for(&se, "boundary[1].nodes.group");
    const ctd_scene_msg *s = msg_for(&se, "interfaces[0].main.surf");
    cr_assert(g && s, "fields: '%s', '%s'", se.msg[0].field, se.count > 1 ? se.msg[1].field : "");
    cr_expect_eq(g->line, 14);
    cr_expect_eq(s->line, 17);
    cr_expect(strstr(g->text, "unknown.yaml:14: boundary[1].nodes.group: node group 98 does not "
                              "exist") != NULL, "%s", g->text);
    cr_expect(strstr(s->text, "unknown.yaml:17: interfaces[0].main.surf: surface 99 does not "
                              "exist") != NULL, "%s", s->text);

    /* A surface where nodes are expected, a node group as a surface:
     * CT_ERR_ARG. */
    snprintf(p, sizeof p, "%s/misused.yaml", dir);
    cr_expect_eq(ctd_scene_load(p, &sc, &se), CT_ERR_ARG);
    cr_expect_null(sc);
    g = msg_for(&se, "boundary[1].nodes.surf");
    s = msg_for(&se, "interfaces[0].main.group");
    cr_assert(g && s, "fields: '%s', '%s'", se.msg[0].field, se.count > 1 ? se.msg[1].field : "");
    cr_expect_eq(g->line, 14);
    cr_expect_eq(s->line, 17);
    cr_expect(strstr(g->text, "nodes are expected here") != NULL, "%s", g->text);
    cr_expect(strstr(s->text, "a surface is expected here") != NULL, "%s", s->text);

    /* The command: bad input, exit 2, the same file:line: field. */
    ctt_cli r = {0};
    ctt_cli_run(&r, dir, 2, "check unknown.yaml");
    cr_expect_eq(r.status, 2, "exit %d: %s", r.status, r.err);
    cr_expect(strstr(r.err, "unknown.yaml:14: boundary[1].nodes.group: node group 98") != NULL,
              "%s", r.err);
    cr_expect(strstr(r.err, "unknown.yaml:17: interfaces[0].main.surf: surface 99") != NULL, "%s",
              r.err);
    cr_expect(strstr(r.err, "unknown.yaml: invalid scene (2 errors)") != NULL, "%s", r.err);
    ctt_cli_run(&r, dir, 2, "run misused.yaml --quiet");
    cr_expect_eq(r.status, 2, "exit %d: %s", r.status, r.err);
    cr_expect(strstr(r.err, "misused.yaml:17: interfaces[0].main.group") != NULL, "%s", r.err);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* ---- A contact run on the deck's surface ---------------------------------- */

typedef struct drop_obs {
    ct_idx lo, hi;   /* the block's nodes */
    double zmin;     /* the lowest z of its nodes over the run */
    int64_t active;  /* the most pairs in contact in a cycle */
} drop_obs;

static void observe(void *ctx, const ctd_solver *s)
{
    drop_obs *o = ctx;
    for (ct_idx i = o->lo; i < o->hi; i++)
        if ((double)s->z[i] < o->zmin)
            o->zmin = (double)s->z[i];
    if (s->nhook && s->rep[0].active > o->active)
        o->active = s->rep[0].active;
}

/* Run the scene DIR/NAME (2 ms); the block's mean vertical velocity at the
 * end into *vz. */
static drop_obs drop_run(const char *dir, const char *name, double *vz)
{
    loaded l;
    load_build(&l, dir, name);
    char err[1024] = "";
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    cr_assert_eq(ctd_interfaces_build(&l.m, l.sc, &hooks, &nhook, err, sizeof err), CT_OK, "%s",
                 err);
    cr_assert_eq(nhook, 1);
    drop_obs o = {l.m.mesh_node_off[1], l.m.mesh_node_off[2], INFINITY, 0};
    cr_assert_eq(o.hi - o.lo, 8);
    ctd_solver_opts opt = ctd_solver_default_opts();
    opt.no_output = 1;
    opt.quiet = 1;
    opt.threads = 2;
    opt.observe = observe;
    opt.observe_ctx = &o;
    ctd_solver s;
    cr_assert_eq(ctd_solver_init(&s, &l.m, &opt, hooks, nhook, err, sizeof err), CT_OK, "%s",
                 err);
    cr_assert_eq(ctd_solver_run(&s), CTD_EXIT_OK, "%s", s.message);
    cr_expect(fabs(s.time - 2e-3) < 1e-12, "t = %g", s.time);
    *vz = 0;
    for (ct_idx i = o.lo; i < o.hi; i++)
        *vz += (double)s.vz[i] / 8;
    ctd_solver_destroy(&s);
    loaded_free(&l);
    return o;
}

Test(deck_select, block_stopped_by_deck_surface)
{
    char dir[64];
    ctt_tmpdir(dir, "deck");
    deck_write(dir);
    scene_write(dir, "scene.yaml", "{group: 10}", "{surf: 1}");
    scene_write(dir, "control.yaml", "{group: 10}", "{surf: 4}");
    /* Main: the quads under the block. It touches them (pairs in contact),
     * never reaches z = 0 and leaves upward. */
    double vz;
    drop_obs o = drop_run(dir, "scene.yaml", &vz);
    cr_expect_gt(o.active, 0, "no pair in contact");
    cr_expect_gt(o.zmin, 0, "the block went through the deck surface (z %g)", o.zmin);
    cr_expect_lt(o.zmin, 0.0007, "the block never fell (z %g)", o.zmin);
    cr_expect_gt(vz, 0.1, "the block did not bounce (vz %g)", vz);
    /* Main: the brick's faces, far away: nothing stops the block, which
     * flies on to 0.0007 - 1 m/s x 2 ms = -0.0013 m. */
    double vz_free;
    drop_obs c = drop_run(dir, "control.yaml", &vz_free);
    cr_expect_eq(c.active, 0);
    cr_expect(fabs(c.zmin + 0.0013) < 1e-6, "free flight ends at %g", c.zmin);
    cr_expect(fabs(vz_free + 1) < 1e-6, "vz %g", vz_free);
    /* The same run through the command: exit 0, contact in the summary. */
    ctt_cli r = {0};
    ctt_cli_run(&r, dir, 2, "run scene.yaml --out out --quiet");
    cr_expect_eq(r.status, 0, "exit %d: %s", r.status, r.err);
    char p[128];
    snprintf(p, sizeof p, "%s/out/summary.json", dir);
    char *sum = ctt_slurp(p);
    cr_assert_not_null(sum);
    cr_expect_eq(ctt_json_num(sum, "max_active"), (double)o.active, "%s", sum);
    free(sum);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}
