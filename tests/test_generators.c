/*
 * test_generators.c -- the scene's mesh generators under `refine` (suite
 * generators), against the geometry each generator promises:
 *
 *  - refine_keeps_every_mesh_in_place: a scene with one mesh of every
 *    kind, loaded at refine 1 and 2; each part's bounding box is the same
 *    (refine makes a mesh finer, not larger) and its node count is the
 *    generator's formula with the cells multiplied. The folded sheet's
 *    `size` is one cell's: refine 2 made a sheet twice as long and wide.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "model.h"
#include "scene.h"
#include "test_util.h"

#define PI 3.14159265358979323846
#define STEEL "material: {E: 2.1e11, nu: 0.3, rho: 7800}"

/* Load the scene text at the given refine (0: the file's) and build its
 * model. */
static void load_model(const char *yaml, int64_t refine, ctd_scene **sc, ctd_model *m)
{
    char dir[] = "/tmp/ct_generators_XXXXXX", path[64];
    cr_assert(mkdtemp(dir) != NULL, "cannot make a temporary directory");
    snprintf(path, sizeof path, "%s/scene.yaml", dir);
    FILE *f = fopen(path, "w");
    cr_assert(f != NULL, "cannot write %s", path);
    fputs(yaml, f);
    fclose(f);
    static ctd_scene_err se;
    int rc = ctd_scene_load_refined(path, refine, sc, &se);
    remove(path);
    rmdir(dir);
    cr_assert_eq(rc, CT_OK, "scene: %s", se.count ? se.msg[0].text : "?");
    char err[1024] = "";
    memset(m, 0, sizeof *m);
    cr_assert_eq(ctd_model_build(m, *sc, err, sizeof err), CT_OK, "model: %s", err);
}

/* ---- refine keeps every mesh in place ------------------------------------ */

static const char *all_kinds =
    "end_time: 1.0e-4\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [3, 2], size: [0.3, 0.2]}\n"
    "  - generate: {kind: block, part: 2, cells: [2, 3, 1], size: [0.2, 0.3, 0.1],"
    " origin: [1, 0, 0]}\n"
    "  - generate: {kind: ball, part: 3, cells: [3], radius: 0.1, origin: [2, 0, 0]}\n"
    "  - generate: {kind: sphere, part: 4, cells: [2], radius: 0.1, origin: [3, 0, 0]}\n"
    "  - generate: {kind: tube, part: 5, cells: [6, 2], radius: 0.1, length: 0.3,"
    " origin: [4, 0, 0]}\n"
    "  - generate: {kind: folded, part: 6, cells: [4, 3], size: [0.02], layers: 3,"
    " spacing: 0.04, origin: [5, 0, 0]}\n"
    "  - generate: {kind: net, part: 7, cells: [2, 2], size: [0.2, 0.2], origin: [6, 0, 0]}\n"
    "  - generate: {kind: rod, part: 8, cells: [3], origin: [7, 0, 0], to: [7.3, 0.1, 0]}\n"
    "parts:\n"
    "  - {id: 1, element: shell, thickness: 0.001, " STEEL "}\n"
    "  - {id: 2, element: brick, " STEEL "}\n"
    "  - {id: 3, element: brick, " STEEL "}\n"
    "  - {id: 4, element: shell, thickness: 0.001, " STEEL "}\n"
    "  - {id: 5, element: shell, thickness: 0.001, " STEEL "}\n"
    "  - {id: 6, element: shell, thickness: 0.001, " STEEL "}\n"
    "  - {id: 7, element: truss, area: 1.0e-6, " STEEL "}\n"
    "  - {id: 8, element: truss, area: 1.0e-6, " STEEL "}\n";

#define NKIND 8

typedef struct part_box {
    double lo[3], hi[3];
    long n;
} part_box;

static void part_boxes(const ctd_model *m, part_box b[NKIND + 1])
{
    for (int p = 0; p <= NKIND; p++) {
        b[p].n = 0;
        for (int d = 0; d < 3; d++) {
            b[p].lo[d] = INFINITY;
            b[p].hi[d] = -INFINITY;
        }
    }
    const ct_nodes *nd = &m->mesh.nodes;
    for (ct_idx k = 0; k < nd->n; k++) {
        int p = m->node_part[k];
        cr_assert(p >= 1 && p <= NKIND, "node %d in part %d", k, p);
        const double c[3] = {nd->x[k], nd->y[k], nd->z[k]};
        for (int d = 0; d < 3; d++) {
            b[p].lo[d] = fmin(b[p].lo[d], c[d]);
            b[p].hi[d] = fmax(b[p].hi[d], c[d]);
        }
        b[p].n++;
    }
}

Test(generators, refine_keeps_every_mesh_in_place)
{
    static const char *const kind[NKIND + 1] = {"",       "plate", "block",  "ball", "sphere",
                                                "tube",   "folded", "net", "rod"};
    part_box b1[NKIND + 1], b2[NKIND + 1];
    for (int r = 1; r <= 2; r++) {
        ctd_scene *sc;
        ctd_model m;
        load_model(all_kinds, r, &sc, &m);
        part_boxes(&m, r == 1 ? b1 : b2);
        ctd_model_destroy(&m);
        ctd_scene_free(sc);
    }
    /* The node counts by the generators' formulas: plate and net (nx+1)(ny+1),
     * block and ball the grid's, sphere 6 n^2 + 2, tube nr (nl+1), rod n+1;
     * the folded sheet's points along its section are round(length / h) + 1
     * with the section 3 layers of nflat h and 2 half-circle bends of radius
     * spacing / 2, times nw + 1 across. */
    const double lsec = 3 * 4 * 0.02 + 2 * PI * 0.02;
    const long want[2][NKIND + 1] = {
        {0, 4 * 3, 3 * 4 * 2, 4 * 4 * 4, 6 * 4 + 2, 6 * 3,
         (long)(round(lsec / 0.02) + 1) * 4, 3 * 3, 4},
        {0, 7 * 5, 5 * 7 * 3, 7 * 7 * 7, 6 * 16 + 2, 12 * 5,
         (long)(round(lsec / 0.01) + 1) * 7, 5 * 5, 7}};
    for (int p = 1; p <= NKIND; p++) {
        cr_expect_eq(b1[p].n, want[0][p], "%s: %ld nodes at refine 1, expected %ld", kind[p],
                     b1[p].n, want[0][p]);
        cr_expect_eq(b2[p].n, want[1][p], "%s: %ld nodes at refine 2, expected %ld", kind[p],
                     b2[p].n, want[1][p]);
        /* Straight meshes keep their box to round-off; the curved ones'
         * polygons approach their curves (a hexagon becomes a 12-gon: 15 %
         * of the tube's width; the folded sheet's bends 4 %), far from the
         * doubling a mesh made larger shows. */
        const int curved = p == 3 || p == 4 || p == 5 || p == 6;
        const double tol = curved ? 0.2 : CTT_TOL(1e-12, 1e-5);
        for (int d = 0; d < 3; d++) {
            const double span = fmax(b1[p].hi[d] - b1[p].lo[d], 0.1);
            cr_expect(fabs(b2[p].lo[d] - b1[p].lo[d]) <= tol * span &&
                          fabs(b2[p].hi[d] - b1[p].hi[d]) <= tol * span,
                      "%s, axis %d: [%.9g, %.9g] at refine 1, [%.9g, %.9g] at refine 2",
                      kind[p], d, b1[p].lo[d], b1[p].hi[d], b2[p].lo[d], b2[p].hi[d]);
        }
    }
}
