/*
 * test_project_slots.c -- ct_narrow_node_slots (suite "project"): a
 * selection of a pair list, the segments' nodes given per pair, gives for
 * each selected pair the bytes ct_narrow_node_segment gives that pair in
 * the whole list, for every method, one- and two-sided, with triangles and
 * quadrangles mixed, on 1 and 2 threads; and it rejects bad arguments.
 * (ct_narrow_node_segment itself is checked against independent answers in
 * test_project.c.)
 */
#include <string.h>

#include "test_geo.h"
#include "test_util.h"

#include "meshgen.h"

Test(project, slots_selection_equals_whole_list)
{
    /* A row of warped segments (every third a triangle, n4 == n3), nodes
     * scattered above and below them, pairs in a scrambled order. */
    const int ns = 150, nn = 500;
    const ct_idx np = ctt_checking() ? 2000 : 9000;
    const int nnode = 4 * ns + nn;
    ct_real *x = ct_calloc((size_t)nnode, sizeof(ct_real));
    ct_real *y = ct_calloc((size_t)nnode, sizeof(ct_real));
    ct_real *z = ct_calloc((size_t)nnode, sizeof(ct_real));
    ct_idx *n[4], *sl[4];
    for (int d = 0; d < 4; d++) {
        n[d] = ct_calloc((size_t)ns, sizeof(ct_idx));
        sl[d] = ct_calloc((size_t)np, sizeof(ct_idx));
        cr_assert(n[d] && sl[d]);
    }
    cr_assert(x && y && z);
    uint64_t st = 7;
    for (int s = 0; s < ns; s++) {
        const double cx = 2.0 * (s % 15), cy = 2.0 * (s / 15);
        const double X[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int i = 0; i < 4; i++) {
            x[4 * s + i] = (ct_real)(cx + X[i][0] + 0.1 * ctd_u01(ctd_splitmix64(&st)));
            y[4 * s + i] = (ct_real)(cy + X[i][1] + 0.1 * ctd_u01(ctd_splitmix64(&st)));
            z[4 * s + i] = (ct_real)(0.2 * ctd_u01(ctd_splitmix64(&st)) - 0.1);
            n[i][s] = 4 * s + i;
        }
        if (s % 3 == 0)
            n[3][s] = n[2][s];
    }
    for (int i = 0; i < nn; i++) {
        x[4 * ns + i] = (ct_real)(30 * ctd_u01(ctd_splitmix64(&st)) - 0.5);
        y[4 * ns + i] = (ct_real)(20 * ctd_u01(ctd_splitmix64(&st)) - 0.5);
        z[4 * ns + i] = (ct_real)(0.8 * ctd_u01(ctd_splitmix64(&st)) - 0.4);
    }
    ct_idx *node = ct_calloc((size_t)np, sizeof(ct_idx));
    ct_idx *seg = ct_calloc((size_t)np, sizeof(ct_idx));
    ct_idx *sel = ct_calloc((size_t)np, sizeof(ct_idx));
    cr_assert(node && seg && sel);
    for (ct_idx k = 0; k < np; k++) {
        node[k] = 4 * ns + (ct_idx)(ctd_splitmix64(&st) % (uint64_t)nn);
        seg[k] = (ct_idx)(ctd_splitmix64(&st) % (uint64_t)ns);
    }
    cr_assert_eq(ct_asm_seg_slots(np, seg, ns, n[0], n[1], n[2], n[3], sl[0], sl[1], sl[2],
                                  sl[3]),
                 CT_OK);
    /* The selection: about two pairs in five, increasing, in runs and gaps
     * (as a contact cycle's skip leaves them). */
    ct_idx nsel = 0;
    for (ct_idx k = 0; k < np; k++)
        if (ctd_splitmix64(&st) % 5 < 2 || (k / 64) % 7 == 0)
            sel[nsel++] = k;
    cr_assert_gt(nsel, np / 4);
    cr_assert_lt(nsel, np);
    ctt_geo whole, part;
    ctt_geo_init(&whole, np);
    ctt_geo_init(&part, nsel);
    int64_t active = 0;
    for (int m = 0; m < CT_QUAD_NMETHOD; m++)
        for (int two = 0; two < 2; two++)
            for (int thr = 1; thr <= 2; thr++) {
                ctt_threads(thr);
                ct_narrow_stats sw, sp;
                cr_assert_eq(ct_narrow_node_segment(np, node, seg, n[0], n[1], n[2], n[3], x, y,
                                                    z, NULL, NULL, (ct_real)0.3, 0, 0,
                                                    (ct_quad_method)m, two, &whole.g, &sw),
                             CT_OK);
                cr_assert_eq(ct_narrow_node_slots(nsel, sel, node, sl[0], sl[1], sl[2], sl[3], x,
                                                  y, z, (ct_real)0.3, (ct_quad_method)m, two,
                                                  &part.g, &sp),
                             CT_OK);
                for (ct_idx j = 0; j < nsel; j++) {
                    const ct_idx k = sel[j];
                    for (int i = 0; i < CTT_GEO_NF; i++)
                        cr_assert(memcmp(&part.f[i][j], &whole.f[i][k], sizeof(ct_real)) == 0,
                                  "method %d two %d: selected pair %d (pair %d), field %d: %g "
                                  "against %g",
                                  m, two, (int)j, (int)k, i, (double)part.f[i][j],
                                  (double)whole.f[i][k]);
                    cr_assert_eq(part.g.flag[j], whole.g.flag[k]);
                }
                active += sp.active;
                cr_assert_leq(sp.active, sw.active);
            }
    /* Contact and its absence both occur. */
    cr_assert_gt(active, 0);
    cr_assert_lt(active, (int64_t)CT_QUAD_NMETHOD * 4 * nsel);
    ctt_geo_free(&whole);
    ctt_geo_free(&part);
    for (int d = 0; d < 4; d++) {
        ct_free(n[d]);
        ct_free(sl[d]);
    }
    ct_free(x);
    ct_free(y);
    ct_free(z);
    ct_free(node);
    ct_free(seg);
    ct_free(sel);
}

Test(project, slots_bad_arguments)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    ct_idx i = 0;
    ct_real v = 0;
    cr_assert_eq(ct_narrow_node_slots(-1, &i, &i, &i, &i, &i, &i, &v, &v, &v, 0, CT_QUAD_4TRI, 0,
                                      &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_slots(1, NULL, &i, &i, &i, &i, &i, &v, &v, &v, 0, CT_QUAD_4TRI, 0,
                                      &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_slots(1, &i, &i, &i, &i, NULL, &i, &v, &v, &v, 0, CT_QUAD_4TRI, 0,
                                      &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_slots(1, &i, &i, &i, &i, &i, &i, &v, &v, &v, 0, CT_QUAD_NMETHOD,
                                      0, &o.g, NULL),
                 CT_ERR_ARG);
    /* Nothing to do: no array is read. */
    cr_assert_eq(ct_narrow_node_slots(0, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0,
                                      CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_OK);
    ctt_geo_free(&o);
}
