/*
 * test_model_parts.c -- the element sets of a model of several parts hold
 * their own nodes only (a model of many parts held one copy of every node
 * per part: 4000 brick parts of 108k nodes took 10 GB and 28 s to build),
 * and their masses are the parts' (rho t A for a shell part, rho V for a
 * brick part, on the part's own nodes).
 */
#include "test_util.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "model.h"
#include "scene.h"

#define RHO 7800.0
#define THICK 0.002

/* Write `text` to a temporary scene file and build its model. */
static ctd_scene *build_text(const char *text, ctd_model *m)
{
    char p[256], err[1024] = "";
    snprintf(p, sizeof p, "/tmp/ct_model_parts_%ld.yaml", (long)getpid());
    FILE *f = fopen(p, "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
    static ctd_scene_err se;
    ctd_scene *sc = NULL;
    int rc = ctd_scene_load(p, &sc, &se);
    unlink(p);
    cr_assert_eq(rc, CT_OK, "%s", se.count ? se.msg[0].text : "?");
    cr_assert_eq(ctd_model_build(m, sc, err, sizeof err), CT_OK, "%s", err);
    return sc;
}

/* The mass on the nodes of mesh i. */
static double mesh_mass(const ctd_model *m, unsigned i)
{
    double s = 0;
    for (ct_idx k = m->mesh_node_off[i]; k < m->mesh_node_off[i + 1]; k++)
        s += (double)m->mesh.nodes.m[k];
    return s;
}

Test(model_parts, sets_hold_their_own_nodes)
{
    const char *text =
        "end_time: 1.0e-6\n"
        "mesh:\n"
        "  - generate: {kind: plate, part: 1, cells: [3, 2], size: [0.03, 0.02]}\n"
        "  - generate: {kind: block, part: 2, cells: [2, 2, 2], size: [0.02, 0.02, 0.02],"
        " origin: [0, 0, 0.1]}\n"
        "  - generate: {kind: plate, part: 3, cells: [4, 4], size: [0.04, 0.04],"
        " origin: [0, 0, 0.2]}\n"
        "parts:\n"
        "  - {id: 1, element: shell, thickness: 0.002, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
        "  - {id: 2, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
        "  - {id: 3, element: shell, thickness: 0.002, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n";
    ctd_model m;
    ctd_scene *sc = build_text(text, &m);
    cr_assert_eq(m.nset, 3);
    const ct_idx want_nodes[3] = {12, 27, 25};
    const double want_mass[3] = {RHO * THICK * 0.03 * 0.02, RHO * 0.02 * 0.02 * 0.02,
                                 RHO * THICK * 0.04 * 0.04};
    for (int k = 0; k < 3; k++) {
        const ctd_model_set *st = &m.set[k];
        cr_assert_eq(st->part, k + 1);
        ct_idx lo = m.mesh_node_off[k], hi = m.mesh_node_off[k + 1];
        cr_assert_eq(hi - lo, want_nodes[k]);
        if (st->element == CTD_ELEM_SHELL) {
            /* Its nodes, and only those: the arrays are per set node. */
            cr_assert_eq(st->shell.nsnode, want_nodes[k]);
            for (ct_idx j = 0; j < st->shell.nsnode; j++)
                cr_assert(st->shell.snode[j] >= lo && st->shell.snode[j] < hi &&
                          (j == 0 || st->shell.snode[j] > st->shell.snode[j - 1]));
        } else {
            cr_assert_eq(st->element, CTD_ELEM_BRICK);
            /* The model's reference positions, not a copy. */
            cr_assert(st->brick.X0 == m.mesh.nodes.x && st->brick.Y0 == m.mesh.nodes.y &&
                      st->brick.Z0 == m.mesh.nodes.z && st->brick.ref == NULL);
        }
        double got = mesh_mass(&m, (unsigned)k);
        cr_assert(fabs(got - want_mass[k]) <= 1e-12 * want_mass[k] + CTT_TOL(0, 1e-6 * want_mass[k]),
                  "part %d: mass %.15g, expected %.15g", k + 1, got, want_mass[k]);
    }
    ctd_model_destroy(&m);
    ctd_scene_free(sc);
}

/* Many parts: each of 300 one-cell shell parts holds its 4 nodes, whatever
 * the model's 1200; the total mass is the sum of the parts'. */
Test(model_parts, many_parts_each_hold_four_nodes)
{
    const int n = 300;
    size_t cap = (size_t)n * 300 + 256, len = 0;
    char *text = malloc(cap);
    cr_assert_not_null(text);
    len += (size_t)snprintf(text + len, cap - len, "end_time: 1.0e-6\nmesh:\n");
    for (int i = 0; i < n; i++)
        len += (size_t)snprintf(text + len, cap - len,
                                "  - generate: {kind: plate, part: %d, cells: [1, 1], size: "
                                "[0.01, 0.01], origin: [%g, 0, 0]}\n",
                                i + 1, 0.02 * i);
    len += (size_t)snprintf(text + len, cap - len, "parts:\n");
    for (int i = 0; i < n; i++)
        len += (size_t)snprintf(text + len, cap - len,
                                "  - {id: %d, element: shell, thickness: 0.002, material: "
                                "{E: 2.1e11, nu: 0.3, rho: 7800}}\n",
                                i + 1);
    cr_assert_lt(len, cap);
    ctd_model m;
    ctd_scene *sc = build_text(text, &m);
    free(text);
    cr_assert_eq(m.nset, n);
    cr_assert_eq(m.mesh.nodes.n, 4 * n);
    double total = 0;
    for (int k = 0; k < n; k++) {
        cr_assert_eq(m.set[k].shell.nsnode, 4);
        total += mesh_mass(&m, (unsigned)k);
    }
    double want = n * RHO * THICK * 1e-4;
    cr_assert(fabs(total - want) <= CTT_TOL(1e-12, 1e-5) * want, "%.15g vs %.15g", total, want);
    ctd_model_destroy(&m);
    ctd_scene_free(sc);
}
