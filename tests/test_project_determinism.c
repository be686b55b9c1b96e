/*
 * test_project_determinism.c -- the node-segment narrow phase gives the
 * same bytes whatever computes a pair (suite "project"): 1 or 2 threads,
 * any SIMD lane (the pairs shifted by one), and for Newton any block (a
 * pair computed alone, whichever path its block took).
 */
#include <string.h>

#include "test_geo.h"
#include "test_project.h"

Test(project, threads_and_lanes_give_identical_results)
{
    int ns = 200, nn = 600, np = ctt_checking() ? 3000 : 20000;
    ct_real *x = ct_calloc((size_t)(4 * ns + nn), sizeof(ct_real));
    ct_real *y = ct_calloc((size_t)(4 * ns + nn), sizeof(ct_real));
    ct_real *z = ct_calloc((size_t)(4 * ns + nn), sizeof(ct_real));
    ct_idx *n1 = ct_calloc((size_t)ns, sizeof(ct_idx)), *n2 = ct_calloc((size_t)ns, sizeof(ct_idx));
    ct_idx *n3 = ct_calloc((size_t)ns, sizeof(ct_idx)), *n4 = ct_calloc((size_t)ns, sizeof(ct_idx));
    for (int s = 0; s < ns; s++) {
        double X[4][3];
        rand_quad(X, 0.1, 1.0);
        for (int i = 0; i < 4; i++) {
            x[4 * s + i] = (ct_real)(X[i][0] + 3 * (s % 10));
            y[4 * s + i] = (ct_real)X[i][1];
            z[4 * s + i] = (ct_real)X[i][2];
        }
        n1[s] = 4 * s;
        n2[s] = 4 * s + 1;
        n3[s] = 4 * s + 2;
        n4[s] = (s % 3 == 0) ? 4 * s + 2 : 4 * s + 3;
    }
    for (int i = 0; i < nn; i++) {
        x[4 * ns + i] = (ct_real)(30 * urand() - 1);
        y[4 * ns + i] = (ct_real)(3 * urand() - 1.5);
        z[4 * ns + i] = (ct_real)(urand() - 0.5);
    }
    ct_idx *node = ct_calloc((size_t)np + 1, sizeof(ct_idx));
    ct_idx *seg = ct_calloc((size_t)np + 1, sizeof(ct_idx));
    for (int k = 0; k < np; k++) {
        node[k] = 4 * ns + (ct_idx)(k / 7 % nn);
        seg[k] = (ct_idx)((k * 37 + k / 5) % ns);
    }
    ctt_geo a, b;
    ctt_geo_init(&a, np);
    ctt_geo_init(&b, np);
    for (int m = 0; m < 3; m++)
        for (int two = 0; two < 2; two++) {
            ct_narrow_stats sa, sb;
            ctt_threads(1);
            cr_assert_eq(ct_narrow_node_segment(np, node, seg, n1, n2, n3, n4, x, y, z, NULL,
                                                NULL, (ct_real)0.3, 0, 0, (ct_quad_method)m, two,
                                                &a.g, &sa),
                         CT_OK);
            ctt_threads(2);
            cr_assert_eq(ct_narrow_node_segment(np, node, seg, n1, n2, n3, n4, x, y, z, NULL,
                                                NULL, (ct_real)0.3, 0, 0, (ct_quad_method)m, two,
                                                &b.g, &sb),
                         CT_OK);
            for (int f = 0; f < CTT_GEO_NF; f++)
                cr_assert_eq(memcmp(a.f[f], b.f[f], (size_t)np * sizeof(ct_real)), 0,
                             "field %d", f);
            cr_assert_eq(memcmp(a.g.flag, b.g.flag, (size_t)np), 0);
            cr_assert_eq(memcmp(&sa, &sb, sizeof sa), 0);
            cr_assert(sa.active > 0);
            /* Shifted by one. */
            cr_assert_eq(ct_narrow_node_segment(np - 1, node + 1, seg + 1, n1, n2, n3, n4, x, y,
                                                z, NULL, NULL, (ct_real)0.3, 0, 0,
                                                (ct_quad_method)m, two, &b.g, NULL),
                         CT_OK);
            cr_assert_eq(memcmp(a.g.dist + 1, b.g.dist, (size_t)(np - 1) * sizeof(ct_real)), 0);
            cr_assert_eq(memcmp(a.g.nx + 1, b.g.nx, (size_t)(np - 1) * sizeof(ct_real)), 0);
            cr_assert_eq(memcmp(a.g.h3 + 1, b.g.h3, (size_t)(np - 1) * sizeof(ct_real)), 0);
        }
    ctt_geo_free(&a);
    ctt_geo_free(&b);
    ct_free(x); ct_free(y); ct_free(z);
    ct_free(n1); ct_free(n2); ct_free(n3); ct_free(n4);
    ct_free(node); ct_free(seg);
}

/* Newton's path through a block (one or two steps in the first loop, the
 * second fixed loop for the whole block, or compacted rounds for its few
 * slow pairs) depends on the block's other pairs; a pair's result must not.
 * Blocks of 64 pairs: F with 60 fast pairs (nodes over a flat
 * parallelogram, where the start is exact and the first step converges)
 * and 4 slow ones (nodes off a warped quadrangle), S the other way round,
 * M with 60 medium pairs (over a parallelogram with a corner raised by
 * 1e-6: the second step converges) and 4 slow ones, in an order that takes
 * every path on one thread (the kernel guesses a block's path from the
 * block before: first loop of one step or two, writing the outputs or not,
 * second loop or not; traced, the order takes each of the six that occur);
 * every pair's outputs in the batch, on 1 and 2 threads, are compared byte
 * for byte with the pair computed alone. */
Test(project, newton_result_does_not_depend_on_the_block)
{
    /* Block b: S mostly slow, F mostly fast, M mostly medium. */
    const char *kind = "SFFSSFFSMMSMF";
    enum { NP = 13 * 64, NC = 12 };
    double F[4][3] = {{-1, -1, 0}, {1.2, -1, 0}, {1.5, 1, 0}, {-0.7, 1, 0}}, W[4][3];
    rand_quad(W, 0.4, 1.0);
    /* Medium: F with a corner raised by 1e-6, whose linear start is close
     * enough for the first step not to converge and the second to. */
    double M[4][3];
    memcpy(M, F, sizeof M);
    M[2][2] = 1e-6;
    ct_real x[NC + NP], y[NC + NP], z[NC + NP];
    for (int i = 0; i < 4; i++) {
        x[i] = (ct_real)F[i][0], y[i] = (ct_real)F[i][1], z[i] = (ct_real)F[i][2];
        x[4 + i] = (ct_real)W[i][0], y[4 + i] = (ct_real)W[i][1], z[4 + i] = (ct_real)W[i][2];
        x[8 + i] = (ct_real)M[i][0], y[8 + i] = (ct_real)M[i][1], z[8 + i] = (ct_real)M[i][2];
    }
    ct_idx n1[3] = {0, 4, 8}, n2[3] = {1, 5, 9}, n3[3] = {2, 6, 10}, n4[3] = {3, 7, 11};
    ct_idx node[NP], seg[NP];
    for (int k = 0; k < NP; k++) {
        const char kb = kind[k / 64];
        int few_slow = kb != 'S', slow = ((k % 16) == 5) == few_slow;
        double p[3];
        if (slow) {
            /* Off the quadrangle's extension, as in the batch test above. */
            double s = 6 * urand() - 3, t = 6 * urand() - 3, c[3], a[3], b[3];
            bil(W, s, t, c, a, b);
            double h = 2.4 * urand() - 1.2;
            for (int d = 0; d < 3; d++)
                p[d] = c[d] + h * (d == 2 ? 1 : 0.3);
        } else {
            p[0] = 2 * urand() - 1, p[1] = 2 * urand() - 1, p[2] = 0.2 * urand() - 0.1;
        }
        x[NC + k] = (ct_real)p[0], y[NC + k] = (ct_real)p[1], z[NC + k] = (ct_real)p[2];
        node[k] = NC + k;
        seg[k] = slow ? 1 : kb == 'M' ? 2 : 0;
    }
    ctt_geo a, b;
    ctt_geo_init(&a, NP);
    ctt_geo_init(&b, 1);
    for (int run = 0; run < 4; run++) {
        int two = run & 1;
        ctt_threads(1 + run / 2);
        cr_assert_eq(ct_narrow_node_segment(NP, node, seg, n1, n2, n3, n4, x, y, z, NULL, NULL,
                                            (ct_real)0.3, 0, 0, CT_QUAD_NEWTON, two, &a.g, NULL),
                     CT_OK);
        for (int k = 0; k < NP; k++) {
            cr_assert_eq(ct_narrow_node_segment(1, node + k, seg + k, n1, n2, n3, n4, x, y, z,
                                                NULL, NULL, (ct_real)0.3, 0, 0, CT_QUAD_NEWTON,
                                                two, &b.g, NULL),
                         CT_OK);
            for (int f = 0; f < CTT_GEO_NF; f++)
                cr_assert_eq(memcmp(a.f[f] + k, b.f[f], sizeof(ct_real)), 0,
                             "pair %d field %d: %.17g in the block, %.17g alone", k, f,
                             (double)a.f[f][k], (double)b.f[f][0]);
            cr_assert_eq(a.g.flag[k], b.g.flag[0], "pair %d", k);
        }
    }
    ctt_geo_free(&a);
    ctt_geo_free(&b);
}
