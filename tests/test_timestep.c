/*
 * test_timestep.c -- contact time steps against hand values; minimum and
 * its index (ties: the smallest index) for 1 and 2 threads.
 */
#include "test_util.h"

#define TOL CTT_TOL(1e-14, 1e-6)

Test(timestep, nodal_hand_values)
{
    /* sqrt(2 m/(K_elem + K_contact)): m = 2, 100 + 300: sqrt(4/400) = 0.1;
     * m = 1, TYPE7 tangent at p = g/2 (K0 = 100: K0/r^2 = 400), no element:
     * sqrt(2/400) = 0.07071067811865475; entry 2 has no stiffness: no limit. */
    ct_real m[3] = {2, 1, 5}, ke[3] = {100, 0, 0};
    ct_real kc[3] = {300, ct_type7_tangent(100, 1, 0.5), 0}, dt[3], dmin;
    ct_idx imin;
    cr_assert_eq(ct_dt_nodal(3, NULL, m, ke, kc, dt, &dmin, &imin), CT_OK);
    cr_assert_leq(ctt_rel(dt[0], 0.1), TOL);
    cr_assert_leq(ctt_rel(dt[1], 0.07071067811865475), TOL);
    cr_assert_eq(dt[2], CT_DT_NONE);
    cr_assert_eq(imin, 1);
    cr_assert_eq(dmin, dt[1]);
    /* Per pair through node indices: pairs on nodes 0, 0, 2 with contact
     * stiffness 300, 700, 10: sqrt(4/400) = 0.1, sqrt(4/800) =
     * 0.07071067811865475, sqrt(10/10) = 1. */
    ct_idx idx[3] = {0, 0, 2};
    ct_real kp[3] = {300, 700, 10};
    cr_assert_eq(ct_dt_nodal(3, idx, m, ke, kp, dt, &dmin, &imin), CT_OK);
    cr_assert_leq(ctt_rel(dt[2], 1.0), TOL);
    cr_assert_eq(imin, 1);
    cr_assert_leq(ctt_rel(dmin, 0.07071067811865475), TOL);
    /* Nothing limits: CT_DT_NONE and -1. */
    ct_real z[3] = {0, 0, 0};
    cr_assert_eq(ct_dt_nodal(3, NULL, m, NULL, z, NULL, &dmin, &imin), CT_OK);
    cr_assert(dmin == CT_DT_NONE && imin == -1);
    /* NaN: error with the smallest index. */
    ct_real kn[3] = {1, NAN, NAN};
    cr_assert_eq(ct_dt_nodal(3, NULL, m, NULL, kn, NULL, &dmin, &imin), CT_ERR_NONFINITE);
    cr_assert_eq(imin, 1);
}

/* The nodal step of entry i by hand, the kernel's operations in its order:
 * the element stiffness (0 without) plus the contact stiffness, then
 * sqrt(2 m / k). */
static ct_real nodal_by_hand(const ct_idx *idx, const ct_real *m, const ct_real *ke,
                             const ct_real *kc, ct_idx i)
{
    ct_idx j = idx ? idx[i] : i;
    ct_real k = ke ? ke[j] + kc[i] : kc[i];
    return (m[j] > 0 && k > 0) ? (ct_real)sqrt((ct_real)2 * m[j] / k) : CT_DT_NONE;
}

Test(timestep, every_path_several_chunks)
{
    /* Nodal: every combination of node list and element stiffness, over 1000
     * entries (chunks of 256 and a remainder), 1 and 2 threads: each step
     * the hand formula's bits, the minimum and its index a plain scan's.
     * The list repeats and jumps (i * 37 mod 613). A NaN mass through the
     * list is found at the first entry naming it. */
    enum { N = 1000, NN = 613 };
    /* Masses and element stiffnesses of N nodes: without the list, item i
     * is node i; the list names the first NN. */
    ct_real m[N], ke[N], kc[N], dt[N];
    ct_idx idx[N];
    for (ct_idx j = 0; j < N; j++) {
        m[j] = (ct_real)(1 + (j * 7919) % 1000) / 64;
        ke[j] = (ct_real)(50 + (j * 104729) % 977);
    }
    for (ct_idx i = 0; i < N; i++) {
        idx[i] = (ct_idx)((i * 37) % NN);
        kc[i] = (i % 11 == 0) ? 0 : (ct_real)(10 + (i * 31) % 500);
    }
    m[5] = 0; /* no mass: no limit */
    for (int th = 1; th <= 2; th++) {
        ctt_threads(th);
        for (int c = 0; c < 4; c++) {
            const ct_idx *ix = (c & 1) ? idx : NULL;
            const ct_real *kk = (c & 2) ? ke : NULL;
            ct_real dmin;
            ct_idx imin;
            cr_assert_eq(ct_dt_nodal(N, ix, m, kk, kc, dt, &dmin, &imin), CT_OK);
            ct_real best = CT_DT_NONE;
            ct_idx bi = -1;
            for (ct_idx i = 0; i < N; i++) {
                ct_real h = nodal_by_hand(ix, m, kk, kc, i);
                cr_assert_eq(dt[i], h, "entry %d, list %d, element %d: %.17g, by hand %.17g",
                             (int)i, c & 1, c >> 1, (double)dt[i], (double)h);
                if (h < best) {
                    best = h;
                    bi = i;
                }
            }
            cr_assert(dmin == best && imin == bi, "list %d element %d", c & 1, c >> 1);
        }
    }
    /* The TYPE7 kinematic step over the same 1000 entries: (g - p) / (2 (-vn))
     * where 0 < p < g (1 - RMIN) and vn < 0, by hand, bit for bit. */
    ct_real p[N], g[N], vn[N];
    for (ct_idx i = 0; i < N; i++) {
        g[i] = (ct_real)(1 + i % 7) / 8;
        p[i] = g[i] * (ct_real)((i * 13) % 17) / 16; /* 0 to g (deactivated) */
        vn[i] = (ct_real)((int)((i * 29) % 41) - 30) / 4;
    }
    for (int th = 1; th <= 2; th++) {
        ctt_threads(th);
        ct_real dmin;
        ct_idx imin;
        cr_assert_eq(ct_dt_type7_kinematic(N, p, g, vn, dt, &dmin, &imin), CT_OK);
        const ct_real xc = (ct_real)1 - (ct_real)CT_TYPE7_RMIN;
        ct_real best = CT_DT_NONE;
        ct_idx bi = -1;
        for (ct_idx i = 0; i < N; i++) {
            int lim = p[i] > 0 && g[i] > 0 && p[i] < g[i] * xc && vn[i] < 0;
            ct_real h = lim ? (g[i] - p[i]) / ((ct_real)2 * -vn[i]) : CT_DT_NONE;
            cr_assert_eq(dt[i], h, "TYPE7 entry %d", (int)i);
            if (h < best) {
                best = h;
                bi = i;
            }
        }
        cr_assert(bi >= 0 && dmin == best && imin == bi);
    }
    /* The first entry naming node 600 is the error's index. */
    ct_idx first = -1;
    for (ct_idx i = 0; i < N && first < 0; i++)
        if (idx[i] == 600)
            first = i;
    cr_assert(first >= 0);
    m[600] = NAN;
    ct_real dmin;
    ct_idx imin;
    cr_assert_eq(ct_dt_nodal(N, idx, m, NULL, kc, NULL, &dmin, &imin), CT_ERR_NONFINITE);
    cr_assert_eq(imin, first);
    cr_assert_eq(ct_dt_nodal(N, idx, m, ke, kc, NULL, &dmin, &imin), CT_ERR_NONFINITE);
    cr_assert_eq(imin, first);
}

Test(timestep, type7_kinematic_type6_tunnel)
{
    /* (g - p)/(2 (-vn)): g = 1, p = 0.2, vn = -2: 0.8/4 = 0.2; separating
     * (vn = 1), out of contact (p = 0) and deactivated (p = 0.9995) set no
     * limit; p = 0.9, vn = -0.1: 0.1/0.2 = 0.5. */
    ct_real p[5] = {0.2, 0.2, 0, 0.9995, 0.9}, g[5] = {1, 1, 1, 1, 1};
    ct_real vn[5] = {-2, 1, -5, -5, -0.1}, dt[5], dmin;
    ct_idx imin;
    cr_assert_eq(ct_dt_type7_kinematic(5, p, g, vn, dt, &dmin, &imin), CT_OK);
    cr_assert_leq(ctt_rel(dt[0], 0.2), TOL);
    cr_assert(dt[1] == CT_DT_NONE && dt[2] == CT_DT_NONE && dt[3] == CT_DT_NONE);
    cr_assert_leq(ctt_rel(dt[4], 0.5), TOL);
    cr_assert(imin == 0 && dmin == dt[0]);
    /* TYPE6: x = {0, 1, 3}, y = {0, 10, 50}, M_min = 4. At p = 2:
     * K = max(f' = 20, f/p = 15) = 20, 0.1 sqrt(4/20) = 0.044721359549995794;
     * at p = 0.5: K = max(10, 10), 0.1 sqrt(0.4) = 0.06324555320336758. */
    ct_real x[3] = {0, 1, 3}, y[3] = {0, 10, 50};
    cr_assert_leq(ctt_rel(ct_dt_type6(4, 2, 3, x, y), 0.044721359549995794), TOL);
    cr_assert_leq(ctt_rel(ct_dt_type6(4, 0.5, 3, x, y), 0.06324555320336758), TOL);
    cr_assert_eq(ct_dt_type6(4, 0, 3, x, y), CT_DT_NONE);
    /* Tunnelling: 0.9 * 0.01/3 = 0.003 (either sign of v). */
    cr_assert_leq(ctt_rel(ct_dt_tunnel(0.01, 3), 0.003), TOL);
    cr_assert_leq(ctt_rel(ct_dt_tunnel(0.01, -3), 0.003), TOL);
    cr_assert_eq(ct_dt_tunnel(0.01, 0), CT_DT_NONE);
    cr_assert_eq(ct_dt_tunnel(0, 3), CT_DT_NONE);
}

Test(timestep, minimum_index_threads_and_ties)
{
    const ct_idx n = ctt_checking() ? 40000 : 400000;
    ct_real *m = malloc(n * sizeof *m), *k = malloc(n * sizeof *k);
    for (ct_idx i = 0; i < n; i++) {
        m[i] = (ct_real)(1 + ((int64_t)i * 7919) % 1000);
        k[i] = 1000;
    }
    /* Ties: the smallest mass 1 occurs many times; the first is the answer.
     * Plant an exact tie far apart (different threads' halves). */
    ct_idx first = -1;
    for (ct_idx i = 0; i < n && first < 0; i++)
        if (m[i] == 1)
            first = i;
    ct_real dmin1, dmin2;
    ct_idx i1, i2;
    ctt_threads(1);
    cr_assert_eq(ct_dt_nodal(n, NULL, m, NULL, k, NULL, &dmin1, &i1), CT_OK);
    ctt_threads(2);
    cr_assert_eq(ct_dt_nodal(n, NULL, m, NULL, k, NULL, &dmin2, &i2), CT_OK);
    cr_assert_eq(i1, first);
    cr_assert_eq(i2, first);
    cr_assert_eq(dmin1, dmin2);
    cr_assert_leq(ctt_rel(dmin1, sqrt(2.0 / 1000)), TOL);
    /* A unique smaller one in the second half wins for both counts. */
    m[n - 3] = 0.5;
    ctt_threads(1);
    ct_dt_nodal(n, NULL, m, NULL, k, NULL, &dmin1, &i1);
    ctt_threads(2);
    ct_dt_nodal(n, NULL, m, NULL, k, NULL, &dmin2, &i2);
    cr_assert(i1 == n - 3 && i2 == n - 3 && dmin1 == dmin2);
    free(m);
    free(k);
}

/* Infinite inputs: an infinite stiffness (or a sum of two finite ones that
 * overflows) gave a nodal step of exactly 0 with CT_OK, an infinite approach
 * speed a TYPE7 step of 0: a solver that takes the minimum then cannot
 * advance, and nothing said why. Both are CT_ERR_NONFINITE now, with the
 * first such entry, on the threaded path (20000 entries, 1 and 2 threads)
 * as on the short one, through a node list as without; finite entries
 * around them keep their steps. */
Test(timestep, infinite_inputs_are_errors_not_zero_steps)
{
    enum { N = 20000 };
    ct_real *m = malloc(N * sizeof *m), *k = malloc(N * sizeof *k);
    ct_real *ke = malloc(N * sizeof *ke), *p = malloc(N * sizeof *p);
    ct_real *g = malloc(N * sizeof *g), *vn = malloc(N * sizeof *vn);
    ct_idx *idx = malloc(N * sizeof *idx);
    cr_assert(m && k && ke && p && g && vn && idx);
    const ct_real big = (ct_real)(sizeof(ct_real) == 4 ? 3e38 : 1e308);
    const ct_idx at[3] = {5, 300, N - 7};
    for (int c = 0; c < 6; c++) {
        for (ct_idx i = 0; i < N; i++) {
            m[i] = 1;
            k[i] = 100;
            ke[i] = 0;
            p[i] = (ct_real)0.1;
            g[i] = 1;
            vn[i] = -1;
            idx[i] = (ct_idx)(((int64_t)i * 37) % N);
        }
        const ct_idx i0 = at[c % 3], i1 = at[(c + 1) % 3];
        const ct_idx first = i0 < i1 ? i0 : i1;
        switch (c) {
        case 0: k[i0] = INFINITY; k[i1] = INFINITY; break;
        case 1: m[i0] = INFINITY; m[i1] = -INFINITY; break;
        case 2: k[i0] = big; ke[i0] = big; k[i1] = big; ke[i1] = big; break; /* overflow */
        case 3: vn[i0] = -INFINITY; vn[i1] = -INFINITY; break;
        case 4: p[i0] = INFINITY; p[i1] = -INFINITY; break;
        default: g[i0] = INFINITY; g[i1] = INFINITY; break;
        }
        for (int t = 1; t <= 2; t++) {
            ctt_threads(t);
            for (ct_idx n = 400; n <= N; n += N - 400) {
                ct_real dmin = -1;
                ct_idx imin = -2;
                const ct_idx want = first < n ? first : (i0 < n ? i0 : (i1 < n ? i1 : -1));
                int rc = c < 3 ? ct_dt_nodal(n, NULL, m, c == 2 ? ke : NULL, k, NULL, &dmin,
                                             &imin)
                               : ct_dt_type7_kinematic(n, p, g, vn, NULL, &dmin, &imin);
                if (want < 0) {
                    /* No bad entry in the first n: the plain answer. */
                    cr_assert_eq(rc, CT_OK, "case %d, n %ld", c, (long)n);
                    cr_assert(dmin > 0 && dmin < CT_DT_NONE, "case %d: dmin %g", c,
                              (double)dmin);
                    continue;
                }
                cr_assert_eq(rc, CT_ERR_NONFINITE, "case %d, %d threads, n %ld: rc %d", c, t,
                             (long)n, rc);
                cr_assert_eq(imin, want, "case %d, %d threads: imin %ld, want %ld", c, t,
                             (long)imin, (long)want);
                cr_assert_eq(dmin, CT_DT_NONE);
            }
            if (c < 3) {
                /* Through a node list (mass and element stiffness of node
                 * idx[i], contact stiffness of entry i): the first entry
                 * whose mass or total stiffness is not finite, by a plain
                 * scan. */
                ct_idx want = -1;
                for (ct_idx i = 0; i < N && want < 0; i++) {
                    const double mi = m[idx[i]], ki = (c == 2 ? ke[idx[i]] : 0) + k[i];
                    if (!isfinite(mi) || !isfinite((ct_real)ki))
                        want = i;
                }
                ct_real dmin;
                ct_idx imin;
                const int rc = ct_dt_nodal(N, idx, m, c == 2 ? ke : NULL, k, NULL, &dmin, &imin);
                if (c == 2) {
                    /* The two big stiffnesses of node i0 now belong to two
                     * entries (i0's contact, the entry naming i0's element):
                     * no sum overflows, the step is finite. */
                    cr_assert_eq(want, -1);
                    cr_assert_eq(rc, CT_OK);
                    cr_assert(dmin > 0 && dmin < CT_DT_NONE);
                    continue;
                }
                cr_assert_eq(rc, CT_ERR_NONFINITE, "case %d through the list", c);
                cr_assert_eq(imin, want);
            }
        }
    }
    free(m);
    free(k);
    free(ke);
    free(p);
    free(g);
    free(vn);
    free(idx);
}
