/*
 * test_stiffness.c -- contact stiffness: segment (shell, brick face), node,
 * combinations and clamping, against hand-computed values.
 */
#include <float.h>

#include "test_util.h"

/* Relative tolerance of a few roundings: double, single. */
#define TOL CTT_TOL(1e-14, 1e-6)

Test(stiffness, segment_scalar_hand_values)
{
    /* Shell: Stfac E t = 0.1 * 210000 * 2 = 42000. */
    cr_assert_leq(ctt_rel(ct_seg_stiffness_shell(0.1, 210000, 2), 42000), TOL);
    /* Bulk modulus: E/(3(1 - 2 nu)) = 1000/(3 * 0.5) = 2000/3. */
    cr_assert_leq(ctt_rel(ct_bulk_modulus(1000, 0.25), 2000.0 / 3.0), TOL);
    /* Brick face: Stfac B A^2 / V = 0.5 * (2000/3) * 16 / 8 = 2000/3. */
    cr_assert_leq(ctt_rel(ct_seg_stiffness_brick(0.5, 2000.0 / 3.0, 4, 8), 2000.0 / 3.0), TOL);
    cr_assert_eq(ct_seg_stiffness_brick(0.5, 100, 4, 0), 0);
    /* Incompressible: a huge but finite bulk modulus. */
    cr_assert(isfinite(ct_bulk_modulus(1000, 0.5)) && ct_bulk_modulus(1000, 0.5) > 1e30);
}

Test(stiffness, node_hand_value)
{
    /* Two bricks of volume 8 attached: Vnode = 2 * 8/8 = 2, (2 Vnode)^(1/3)
     * = 4^(1/3) = 1.5874010519681994; B = 2000/3 gives 1058.2673679787996;
     * plus the mean E t of two shells (100 * 1, 200 * 2): (100 + 400)/2 =
     * 250; total 1308.2673679787996. */
    double want = 2000.0 / 3.0 * 1.5874010519681994 + 250.0;
    cr_assert_leq(ctt_rel(ct_node_stiffness1(2000.0 / 3.0, 2, 250), want), CTT_TOL(1e-14, 1e-6));
    ct_real B[3] = {2000.0 / 3.0, 0, 10}, V[3] = {2, 0, 0.5}, Et[3] = {250, 30, 0}, K[3];
    cr_assert_eq(ct_node_stiffness(3, B, V, Et, K, NULL), CT_OK);
    cr_assert_leq(ctt_rel(K[0], want), CTT_TOL(1e-14, 1e-6));
    cr_assert_eq(K[1], 30); /* shells only */
    cr_assert_leq(ctt_rel(K[2], 10.0), CTT_TOL(1e-15, 1e-6)); /* 10 * (2*0.5)^(1/3) = 10 */
    B[1] = NAN;
    ct_diag d;
    cr_assert_eq(ct_node_stiffness(3, B, V, Et, K, &d), CT_ERR_NONFINITE);
    cr_assert_eq(d.index, 1);
    B[1] = 0;
    Et[2] = -1;
    cr_assert_eq(ct_node_stiffness(3, B, V, Et, K, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 2);
}

Test(stiffness, segment_array_shell_wins)
{
    /* 0: shell only, 1: brick only, 2: both (shell wins), 3: neither. */
    ct_real E[4] = {210000, 0, 1000, 0}, t[4] = {2, 0, 3, 0};
    ct_real B[4] = {0, 2000.0 / 3.0, 5000, 0}, A[4] = {0, 4, 4, 0}, V[4] = {0, 8, 8, 0};
    ct_real K[4];
    cr_assert_eq(ct_seg_stiffness(4, 0.1, E, t, B, A, V, K, NULL), CT_OK);
    cr_assert_leq(ctt_rel(K[0], 42000), TOL);          /* 0.1 * 210000 * 2 */
    cr_assert_leq(ctt_rel(K[1], 400.0 / 3.0), TOL);    /* 0.1 * 2000/3 * 16/8 */
    cr_assert_leq(ctt_rel(K[2], 300), TOL);            /* 0.1 * 1000 * 3, not the brick */
    cr_assert_eq(K[3], 0);
    /* Shells only, bricks only. */
    cr_assert_eq(ct_seg_stiffness(4, 0.1, E, t, NULL, NULL, NULL, K, NULL), CT_OK);
    cr_assert_eq(K[1], 0);
    cr_assert_eq(ct_seg_stiffness(4, 0.1, NULL, NULL, B, A, V, K, NULL), CT_OK);
    cr_assert_leq(ctt_rel(K[2], 0.1 * 5000 * 2), TOL);
    /* Errors: NaN thickness at 2; negative bulk modulus of a brick at 1. */
    ct_diag d;
    t[2] = NAN;
    cr_assert_eq(ct_seg_stiffness(4, 0.1, E, t, B, A, V, K, &d), CT_ERR_NONFINITE);
    cr_assert_eq(d.index, 2);
    t[2] = 3;
    B[1] = -1;
    cr_assert_eq(ct_seg_stiffness(4, 0.1, E, t, B, A, V, K, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 1);
    cr_assert_eq(ct_seg_stiffness(4, -1, E, t, NULL, NULL, NULL, K, NULL), CT_ERR_ARG);
}

Test(stiffness, combinations_hand_values)
{
    /* Km = 3, Ks = 6: main 3, mean 4.5, max 6, min 3, series 18/9 = 2,
     * scaled series 0.2 * 2 = 0.4. */
    const double want[CT_STIFF_NCOMBINE] = {3, 4.5, 6, 3, 2, 0.4};
    for (int m = 0; m < CT_STIFF_NCOMBINE; m++)
        cr_assert_leq(ctt_rel(ct_stiffness_combine1(m, 3, 6, 0.2, 0, 0), want[m]), TOL,
                      "mode %d", m);
    /* TYPE5 example of the seed: K1 = K2/10 -> K = s K2/11 = 10 s K1/11. */
    cr_assert_leq(ctt_rel(ct_stiffness_combine1(CT_STIFF_SCALED_SERIES, 1, 10, 0.2, 0, 0),
                          0.2 * 10.0 / 11.0),
                  TOL);
    /* Clamping to [2.5, 4]: series 2 -> 2.5, max 6 -> 4, mean 4.5 -> 4,
     * main 3 unchanged; stmax = 0 means no upper bound. */
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_SERIES, 3, 6, 0.2, 2.5, 4), 2.5);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_MAX, 3, 6, 0.2, 2.5, 4), 4);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_MEAN, 3, 6, 0.2, 2.5, 4), 4);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_MAIN, 3, 6, 0.2, 2.5, 4), 3);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_MAX, 3, 6, 0.2, 0, 0), 6);
    cr_assert_eq(ct_stiffness_combine1(99, 3, 6, 0.2, 0, 0), 0);
}

Test(stiffness, series_extreme_ratios)
{
    /* Ratios 1e-6 .. 1e6 (half decades), at several magnitudes: finite and
     * within 1e-12 (double) / 1e-6 (single) of the exact value, computed
     * here in long double from the textbook formula. */
    const double mags[] = {1e-3, 1.0, 1e6, CTT_SINGLE ? 1e15 : 1e150};
    for (int im = 0; im < 4; im++)
        for (int k = -12; k <= 12; k++) {
            long double a = mags[im], b = a * powl(10.0L, k / 2.0L);
            long double exact = a * b / (a + b);
            ct_real got = ct_stiffness_combine1(CT_STIFF_SERIES, (ct_real)a, (ct_real)b, 0.2, 0, 0);
            /* Compare against the exact value of the rounded inputs. */
            long double ar = (ct_real)a, br = (ct_real)b, ex = ar * br / (ar + br);
            (void)exact;
            cr_assert(isfinite(got));
            cr_assert_leq(fabsl(got - ex) / ex, CTT_TOL(1e-12, 1e-6), "a=%Lg b=%Lg got=%g want=%Lg",
                          a, b, (double)got, ex);
            /* Symmetric. */
            cr_assert_eq(got, ct_stiffness_combine1(CT_STIFF_SERIES, (ct_real)b, (ct_real)a, 0.2, 0, 0));
        }
    /* Where the naive K1 K2 overflows: 1e300 with 1e300 is 5e299 (double);
     * 3e38 with 3e38 is 1.5e38 (single). */
    ct_real big = CTT_SINGLE ? (ct_real)3e38 : (ct_real)1e300;
    cr_assert_leq(ctt_rel(ct_stiffness_combine1(CT_STIFF_SERIES, big, big, 0.2, 0, 0), big / 2), TOL);
    /* Zeros and infinities. */
    ct_real inf = (ct_real)INFINITY;
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_SERIES, 0, 5, 0.2, 0, 0), 0);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_SERIES, 0, 0, 0.2, 0, 0), 0);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_SERIES, inf, 5, 0.2, 0, 0), 5);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_SERIES, 0, inf, 0.2, 0, 0), 0);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_SERIES, inf, inf, 0.2, 0, 0), inf);
    cr_assert_eq(ct_stiffness_combine1(CT_STIFF_SERIES, inf, inf, 0.2, 0, 7), 7);
    cr_assert_leq(ctt_rel(ct_stiffness_combine1(CT_STIFF_SCALED_SERIES, inf, 5, 0.2, 0, 0), 1.0), TOL);
}

Test(stiffness, pairs_gather_errors_threads)
{
    /* Per-pair gather: pair k = (node k % 7, seg k % 5). */
    const ct_idx n = ctt_checking() ? 20000 : 200000;
    ct_idx *node = malloc(n * sizeof *node), *seg = malloc(n * sizeof *seg);
    ct_real *K1 = malloc(n * sizeof *K1), *K2 = malloc(n * sizeof *K2);
    ct_real Kn[7] = {1, 2, 3, 4, 5, 6, 7}, Ks[5] = {10, 20, 30, 40, 50};
    for (ct_idx k = 0; k < n; k++) {
        node[k] = k % 7;
        seg[k] = k % 5;
    }
    ctt_threads(1);
    cr_assert_eq(ct_stiffness_pairs(n, CT_STIFF_SERIES, node, seg, Kn, Ks, 0.2, 0, 0, K1, NULL), CT_OK);
    ctt_threads(2);
    cr_assert_eq(ct_stiffness_pairs(n, CT_STIFF_SERIES, node, seg, Kn, Ks, 0.2, 0, 0, K2, NULL), CT_OK);
    cr_assert_eq(memcmp(K1, K2, n * sizeof *K1), 0);
    /* Pair 12: node 5 (Ks = 6), seg 2 (Km = 30): 180/36 = 5. */
    cr_assert_leq(ctt_rel(K1[12], 5.0), TOL);
    /* Errors report the smallest offending pair, whatever the threads. */
    Kn[3] = NAN; /* first pair with node 3 is pair 3 */
    Ks[4] = -1;  /* first pair with seg 4 is pair 4 */
    ct_diag d;
    cr_assert_eq(ct_stiffness_pairs(n, CT_STIFF_MEAN, node, seg, Kn, Ks, 0.2, 0, 0, K1, &d),
                 CT_ERR_NONFINITE);
    cr_assert_eq(d.index, 3);
    Kn[3] = 4;
    cr_assert_eq(ct_stiffness_pairs(n, CT_STIFF_MEAN, node, seg, Kn, Ks, 0.2, 0, 0, K1, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 4);
    cr_assert_eq(ct_stiffness_pairs(n, 42, node, seg, Kn, Ks, 0.2, 0, 0, K1, &d), CT_ERR_ARG);
    free(node);
    free(seg);
    free(K1);
    free(K2);
}
