/*
 * test_friction.c -- friction laws against hand values, the filter
 * coefficient, stick / slip / cone, dissipation, history remap, threads.
 */
#include "test_util.h"

#define TOL CTT_TOL(1e-14, 1e-6)

Test(friction, law_hand_values)
{
    /* Coulomb: Fric. */
    ct_real c0[7] = {0.3, 0, 0, 0, 0, 0, 0};
    cr_assert_leq(ctt_rel(ct_friction_mu1(CT_FRIC_COULOMB, c0, 5, 5), 0.3), TOL);
    /* Ifric 1, Fric = 0.1, C1..C5 = 0.01, 0.02, 0.001, 0.0001, 0.002 at
     * p = 10, v = 2: 0.1 + 0.1 + 0.04 + 0.02 + 0.01 + 0.008 = 0.278. */
    ct_real c1[7] = {0.1, 0.01, 0.02, 0.001, 0.0001, 0.002, 0};
    cr_assert_leq(ctt_rel(ct_friction_mu1(CT_FRIC_POLY, c1, 10, 2), 0.278), TOL);
    /* Darmstad, C1..C6 = 0.001, -0.5, 0.01, -1, 0.2, -0.1 at p = 3, v = 2:
     * 0.001 e^-1 9 + 0.01 e^-2 3 + 0.2 e^-0.2 = 0.0033109150 + 0.0040600585
     * + 0.1637461506 = 0.17111712408323776. */
    ct_real c2[7] = {0, 0.001, -0.5, 0.01, -1, 0.2, -0.1};
    cr_assert_leq(ctt_rel(ct_friction_mu1(CT_FRIC_DARMSTAD, c2, 3, 2), 0.17111712408323776),
                  CTT_TOL(1e-14, 1e-6));
    /* Ifric 4, mu_s = 0.5, mu_d = 0.2, c = 2 at v = 0.5:
     * 0.2 + 0.3 e^-1 = 0.3103638323514327; at v = 0: mu_s. */
    ct_real c4[7] = {0.5, 0.2, 2, 0, 0, 0, 0};
    cr_assert_leq(ctt_rel(ct_friction_mu1(CT_FRIC_EXPDECAY, c4, 0, 0.5), 0.3103638323514327), TOL);
    cr_assert_leq(ctt_rel(ct_friction_mu1(CT_FRIC_EXPDECAY, c4, 0, 0), 0.5), TOL);
    /* Negative results clamp to 0. */
    ct_real cn[7] = {-1, 0, 0, 0, 0, 0, 0};
    cr_assert_eq(ct_friction_mu1(CT_FRIC_POLY, cn, 0, 0), 0);
    /* Array form equals the scalar form. */
    ct_real p[3] = {3, 1, 0}, v[3] = {2, 0.1, 7}, mu[3];
    cr_assert_eq(ct_friction_mu(3, CT_FRIC_DARMSTAD, c2, p, v, mu), CT_OK);
    for (int i = 0; i < 3; i++)
        cr_assert_eq(mu[i], ct_friction_mu1(CT_FRIC_DARMSTAD, c2, p[i], v[i]));
    cr_assert_eq(ct_friction_mu(3, CT_FRIC_DARMSTAD, c2, NULL, v, mu), CT_ERR_ARG);
}

Test(friction, renard_values_and_continuity)
{
    /* mu_s = 0.3, mu_d = 0.2, mu_max = 0.5, mu_min = 0.1, Vcr1 = 1, Vcr2 = 3.
     *   v = 0:   0.3;
     *   v = 0.5: 0.3 + 0.2 * 0.5 * 1.5 = 0.45;
     *   v = 1:   0.3 + 0.2 * 1 * 1 = 0.5 (= mu_max);
     *   v = 2:   xi = 0.5: 0.5 - 0.4 * 0.25 * 2 = 0.3;
     *   v = 3:   0.1 (= mu_min);
     *   v = 4:   0.2 - 0.1/(1 + 0.1 * 1) = 0.10909090909090909;
     *   v -> inf: mu_d. */
    ct_real c[7] = {0, 0.3, 0.2, 0.5, 0.1, 1, 3};
    cr_assert_eq(ct_friction_check(CT_FRIC_RENARD, c, NULL), CT_OK);
    const double v[7] = {0, 0.5, 1, 2, 3, 4, 1e8};
    const double w[7] = {0.3, 0.45, 0.5, 0.3, 0.1, 0.10909090909090909, 0.2};
    for (int i = 0; i < 7; i++)
        cr_assert_leq(ctt_rel(ct_friction_mu1(CT_FRIC_RENARD, c, 0, v[i]), w[i]),
                      CTT_TOL(1e-14, 1e-6), "v=%g", v[i]);
    /* Continuity at C5 and C6: |mu(C +- h) - mu(C)| <= L h, with L a bound
     * on |mu'| near there (0.4 from the first branch at v -> C5 is 0, the
     * cubic's slope at its ends is 0, the last branch's is 0): take L = 1
     * and h = 1e-7 (1e-3 in single). */
    const double h = CTT_TOL(1e-7, 1e-3);
    for (int k = 5; k <= 6; k++) {
        double cv = c[k], mid = ct_friction_mu1(CT_FRIC_RENARD, c, 0, (ct_real)cv);
        double lo = ct_friction_mu1(CT_FRIC_RENARD, c, 0, (ct_real)(cv - h));
        double hi = ct_friction_mu1(CT_FRIC_RENARD, c, 0, (ct_real)(cv + h));
        cr_assert_leq(fabs(lo - mid), h * CTT_TOL(1.0, 2.0), "C%d", k);
        cr_assert_leq(fabs(hi - mid), h * CTT_TOL(1.0, 2.0), "C%d", k);
    }
    /* Bad Renard coefficients. */
    ct_diag d;
    ct_real b1[7] = {0, 0.3, 0.2, 0.5, 0.1, 0, 3};
    cr_assert_eq(ct_friction_check(CT_FRIC_RENARD, b1, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 5);
    ct_real b2[7] = {0, 0.3, 0.2, 0.5, 0.1, 3, 3};
    cr_assert_eq(ct_friction_check(CT_FRIC_RENARD, b2, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 6);
    ct_real b3[7] = {0, 0.3, 0.2, 0.5, NAN, 1, 3};
    cr_assert_eq(ct_friction_check(CT_FRIC_RENARD, b3, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 4);
    cr_assert_eq(ct_friction_check(9, c, &d), CT_ERR_ARG);
}

Test(friction, filter_alpha)
{
    /* Ifiltr 1: Xfreq; 2: 2 pi / Xfreq; 3: 2 pi Xfreq dt. */
    cr_assert_leq(ctt_rel(ct_filter_alpha(1, 0.3, 1e-3), 0.3), TOL);
    cr_assert_leq(ctt_rel(ct_filter_alpha(2, 100, 1e-3), 0.06283185307179587), TOL);
    cr_assert_leq(ctt_rel(ct_filter_alpha(3, 10, 1e-3), 0.06283185307179587), TOL);
    /* Kept in (0, 1]. */
    cr_assert_eq(ct_filter_alpha(1, 5, 1e-3), 1);
    cr_assert_eq(ct_filter_alpha(2, 1, 1e-3), 1);   /* 2 pi > 1 */
    cr_assert_eq(ct_filter_alpha(3, 1e6, 1), 1);
    cr_assert_eq(ct_filter_alpha(1, 0, 1e-3), 1);   /* off */
    cr_assert_eq(ct_filter_alpha(2, 0, 1e-3), 1);
    cr_assert_eq(ct_filter_alpha(1, -0.5, 1e-3), 1);
    cr_assert_eq(ct_filter_alpha(1, NAN, 1e-3), 1);
    cr_assert_eq(ct_filter_alpha(0, 0.3, 1e-3), 1);
}

/* One pair, normal z, fn = 10, mu = 0.5 (limit 5), kt = 1000, dt = 1e-3. */
static void one(ct_real vx, ct_real vy, ct_real vz, ct_real alpha, ct_real F[3], ct_real *dis)
{
    ct_real nx = 0, ny = 0, nz = 1, fn = 10;
    ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, NULL, 0.5, NULL, 1000, 1e-3, alpha,
                     &F[0], &F[1], &F[2], dis);
}

Test(friction, stick_slip_filter_hand_values)
{
    /* Stick: v = (1, 0, 7) (the normal part is ignored), old force (0, 0, 3)
     * (its normal part is dropped): trial -1000 * 1e-3 * (1, 0, 0) =
     * (-1, 0, 0), |trial| = 1 < 5: elastic, no dissipation. */
    ct_real F[3] = {0, 0, 3}, dis;
    one(1, 0, 7, 1, F, &dis);
    cr_assert(F[0] == -1 && F[1] == 0 && F[2] == 0 && dis == 0);
    /* Slip: v = (10, 0, 0) from rest: trial (-10, 0, 0) -> (-5, 0, 0) on
     * the cone, in the trial direction; slip (10 - 5)/1000 = 5e-3,
     * dissipation 5 * 5e-3 = 0.025. */
    F[0] = F[1] = F[2] = 0;
    one(10, 0, 0, 1, F, &dis);
    cr_assert_leq(fabs(F[0] + 5), TOL * 5);
    cr_assert(F[1] == 0 && F[2] == 0);
    cr_assert_leq(ctt_rel(dis, 0.025), CTT_TOL(1e-13, 1e-5));
    /* Filter alpha = 0.25: old (2, 0, 0), v = (1, 0, 0): trial (1, 0, 0)
     * (stick), filtered 0.25 * 1 + 0.75 * 2 = 1.75. */
    F[0] = 2;
    F[1] = F[2] = 0;
    one(1, 0, 0, 0.25, F, &dis);
    cr_assert_leq(ctt_rel(F[0], 1.75), TOL);
    /* The same with fn = 3 (limit 1.5): 1.75 is scaled back to the cone. */
    ct_real nx = 0, ny = 0, nz = 1, fn = 3, vx = 1, vy = 0, vz = 0;
    F[0] = 2;
    ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, NULL, 0.5, NULL, 1000, 1e-3, 0.25,
                     &F[0], &F[1], &F[2], &dis);
    cr_assert_leq(ctt_rel(F[0], 1.5), TOL);
    /* Filtered while slipping: fn = 1 (limit 0.5), kt dt = 1, old (-2, 0,
     * 0) (from a larger normal force), v = (1, 0, 0): trial (-3, 0, 0) ->
     * (-0.5, 0, 0) on the cone, slip (3 - 0.5)/100 = 0.025; filtered with
     * alpha = 0.5: -1.25, scaled back to the cone: -0.5. The dissipation
     * is the force on the cone times the slip, 0.5 * 0.025 = 0.0125 (not
     * the filtered force's 1.25 * 0.025). */
    fn = 1;
    F[0] = -2;
    F[1] = F[2] = 0;
    ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, NULL, 0.5, NULL, 100, 1e-2, 0.5,
                     &F[0], &F[1], &F[2], &dis);
    cr_assert_leq(ctt_rel(F[0], -0.5), TOL);
    cr_assert(F[1] == 0 && F[2] == 0);
    cr_assert_leq(ctt_rel(dis, 0.0125), CTT_TOL(1e-13, 1e-5));
    /* Out of contact: zero force, the history is cleared. */
    fn = 0;
    ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, NULL, 0.5, NULL, 1000, 1e-3, 1,
                     &F[0], &F[1], &F[2], &dis);
    cr_assert(F[0] == 0 && dis == 0);
    cr_assert_eq(ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, NULL, 0.5, NULL, 1000,
                                  1e-3, 0, &F[0], &F[1], &F[2], &dis),
                 CT_ERR_ARG);
}

Test(friction, steady_sliding_dissipation)
{
    /* v = (2, 1, 0) for 200 steps: the trial grows by kt dt |v| = sqrt(5)
     * = 2.236 a step, so steps 0 and 1 stick (2.236, 4.472 < 5, no
     * dissipation) and from step 2 on the force sits on the cone against the
     * slip, F = -5 (2, 1, 0)/sqrt(5), and each step
     * dissipates mu fn |v| dt = 5 * sqrt(5) * 1e-3 = 0.011180339887498949. */
    ct_real F[3] = {0, 0, 0}, dis;
    for (int s = 0; s < 200; s++) {
        one(2, 1, 0, 1, F, &dis);
        cr_assert_geq(dis, 0);
        if (s < 2)
            cr_assert_eq(dis, 0);
        if (s > 2) /* step 2 slips only partly: 6.708 - 5 */
            cr_assert_leq(ctt_rel(dis, 0.011180339887498949), CTT_TOL(1e-12, 1e-5), "step %d", s);
    }
    cr_assert_leq(fabs(F[0] + 10 / sqrt(5.0)), CTT_TOL(1e-13, 1e-5));
    cr_assert_leq(fabs(F[1] + 5 / sqrt(5.0)), CTT_TOL(1e-13, 1e-5));
}

static uint64_t rng = 88172645463325252ull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

Test(friction, random_sweep_cone_stick_slip_threads)
{
    const ct_idx n = ctt_checking() ? 20000 : 200000;
    ct_real *a[20];
    for (int i = 0; i < 20; i++)
        a[i] = malloc(n * sizeof(ct_real));
    ct_real *nx = a[0], *ny = a[1], *nz = a[2], *vx = a[3], *vy = a[4], *vz = a[5], *fn = a[6],
            *mu = a[7], *kt = a[8], *hx = a[9], *hy = a[10], *hz = a[11], *d1 = a[12],
            *gx = a[13], *gy = a[14], *gz = a[15], *d2 = a[16];
    for (ct_idx i = 0; i < n; i++) {
        double x = urand() - 0.5, y = urand() - 0.5, z = urand() - 0.5;
        double l = sqrt(x * x + y * y + z * z) + 1e-300;
        nx[i] = (ct_real)(x / l);
        ny[i] = (ct_real)(y / l);
        nz[i] = (ct_real)(z / l);
        vx[i] = (ct_real)(10 * (urand() - 0.5));
        vy[i] = (ct_real)(10 * (urand() - 0.5));
        vz[i] = (ct_real)(10 * (urand() - 0.5));
        fn[i] = (ct_real)(i % 17 == 0 ? 0 : 100 * urand());
        mu[i] = (ct_real)urand();
        kt[i] = (ct_real)(1e4 * urand());
        hx[i] = gx[i] = (ct_real)(50 * (urand() - 0.5));
        hy[i] = gy[i] = (ct_real)(50 * (urand() - 0.5));
        hz[i] = gz[i] = (ct_real)(50 * (urand() - 0.5));
    }
    /* The trial, computed here independently in long double. */
    const double dt = 1e-3;
    long double *tx = malloc(n * 3 * sizeof *tx);
    for (ct_idx i = 0; i < n; i++) {
        long double N[3] = {nx[i], ny[i], nz[i]}, O[3] = {hx[i], hy[i], hz[i]},
                    V[3] = {vx[i], vy[i], vz[i]};
        long double on = O[0] * N[0] + O[1] * N[1] + O[2] * N[2];
        long double vn = V[0] * N[0] + V[1] * N[1] + V[2] * N[2];
        for (int c = 0; c < 3; c++)
            tx[3 * i + c] = (O[c] - on * N[c]) - kt[i] * dt * (V[c] - vn * N[c]);
    }
    ctt_threads(1);
    ct_friction_step(n, nx, ny, nz, vx, vy, vz, fn, mu, 0, kt, 0, (ct_real)dt, 1, hx, hy, hz, d1);
    ctt_threads(2);
    ct_friction_step(n, nx, ny, nz, vx, vy, vz, fn, mu, 0, kt, 0, (ct_real)dt, 1, gx, gy, gz, d2);
    cr_assert_eq(memcmp(hx, gx, n * sizeof *hx), 0);
    cr_assert_eq(memcmp(hz, gz, n * sizeof *hz), 0);
    cr_assert_eq(memcmp(d1, d2, n * sizeof *d1), 0);
    ctt_threads(1);
    double s1 = ct_friction_dissipation(n, d1);
    ctt_threads(2);
    double s2 = ct_friction_dissipation(n, d2);
    cr_assert_eq(memcmp(&s1, &s2, sizeof s1), 0);
    const double eps = CTT_TOL(1e-12, 1e-5);
    int nstick = 0, nslip = 0;
    for (ct_idx i = 0; i < n; i++) {
        double lim = (double)mu[i] * fn[i];
        double F = sqrt((double)hx[i] * hx[i] + (double)hy[i] * hy[i] + (double)hz[i] * hz[i]);
        double T = sqrtl(tx[3 * i] * tx[3 * i] + tx[3 * i + 1] * tx[3 * i + 1] +
                         tx[3 * i + 2] * tx[3 * i + 2]);
        cr_assert_leq(F, lim * (1 + eps), "pair %d: |Ft| %g > mu fn %g", i, F, lim);
        cr_assert_geq(d1[i], 0);
        /* Tangential: no normal component. */
        double fnrm = (double)hx[i] * nx[i] + (double)hy[i] * ny[i] + (double)hz[i] * nz[i];
        cr_assert_leq(fabs(fnrm), eps * (1 + F) * 10);
        if (fn[i] == 0) {
            cr_assert(F == 0 && d1[i] == 0);
            continue;
        }
        if (T < lim * (1 - 1e-6)) { /* stick: the elastic trial itself */
            nstick++;
            for (int c = 0; c < 3; c++) {
                double got = c == 0 ? hx[i] : c == 1 ? hy[i] : hz[i];
                cr_assert_leq(fabs(got - (double)tx[3 * i + c]), eps * (1 + T) * 10);
            }
            cr_assert_eq(d1[i], 0);
        } else if (T > lim * (1 + 1e-6)) { /* slip: on the cone, along the trial */
            nslip++;
            cr_assert_leq(fabs(F - lim), eps * (1 + lim) * 10);
            for (int c = 0; c < 3; c++) {
                double got = c == 0 ? hx[i] : c == 1 ? hy[i] : hz[i];
                cr_assert_leq(fabs(got - (double)(tx[3 * i + c] * lim / T)), eps * (1 + lim) * 10);
            }
            /* Dissipation = |F| (|trial| - limit)/kt. */
            cr_assert_leq(fabs(d1[i] - lim * (T - lim) / kt[i]),
                          eps * 100 * (1 + lim * T / kt[i]), "pair %d", i);
        }
    }
    cr_assert_gt(nstick, n / 20);
    cr_assert_gt(nslip, n / 20);
    free(tx);
    for (int i = 0; i < 20; i++)
        free(a[i]);
}

Test(friction, history_remap)
{
    /* Old (node, seg): (0,1) (0,3) (2,0) (5,5) (7,1), force x 10..50;
     * new: (0,3) (1,0) (2,0) (7,1) (8,0) -> old 1, -, 2, 4, -. */
    ct_idx on[5] = {0, 0, 2, 5, 7}, os[5] = {1, 3, 0, 5, 1};
    ct_idx nn[5] = {0, 1, 2, 7, 8}, ns[5] = {3, 0, 0, 1, 0};
    ct_real ox[5] = {10, 20, 30, 40, 50}, oy[5] = {1, 2, 3, 4, 5}, oz[5] = {0};
    ct_real fx[5], fy[5], fz[5];
    ct_idx map[5];
    cr_assert_eq(ct_friction_remap(5, on, os, ox, oy, oz, 5, nn, ns, fx, fy, fz, map, NULL), CT_OK);
    const ct_idx wm[5] = {1, -1, 2, 4, -1};
    const double wx[5] = {20, 0, 30, 50, 0}, wy[5] = {2, 0, 3, 5, 0};
    for (int i = 0; i < 5; i++) {
        cr_assert_eq(map[i], wm[i]);
        cr_assert(fx[i] == wx[i] && fy[i] == wy[i] && fz[i] == 0);
    }
    /* Any per-pair state: fill value for new pairs. */
    ct_real st[5];
    cr_assert_eq(ct_pair_remap(5, map, ox, -1, st), CT_OK);
    cr_assert(st[1] == -1 && st[3] == 50);
    /* Lists out of order are rejected with the index. */
    ct_diag d;
    ct_idx bad[5] = {0, 2, 1, 7, 8};
    cr_assert_eq(ct_pair_match(5, on, os, 5, bad, ns, map, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 2);
    ct_idx dup[5] = {0, 0, 2, 5, 7}, dups[5] = {1, 1, 0, 5, 1};
    cr_assert_eq(ct_pair_match(5, dup, dups, 5, nn, ns, map, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, -2);
    /* Large lists, several blocks: against a brute-force binary search, and
     * 1 vs 2 threads. Old: node i/3, seg 2 (i%3); new: node i/4, seg i%4. */
    const ct_idx no = ctt_checking() ? 30000 : 300000, nw = no * 4 / 3;
    ct_idx *a = malloc(no * sizeof *a), *b = malloc(no * sizeof *b);
    ct_idx *c = malloc(nw * sizeof *c), *e = malloc(nw * sizeof *e);
    ct_idx *m1 = malloc(nw * sizeof *m1), *m2 = malloc(nw * sizeof *m2);
    for (ct_idx i = 0; i < no; i++) {
        a[i] = i / 3;
        b[i] = 2 * (i % 3);
    }
    for (ct_idx i = 0; i < nw; i++) {
        c[i] = i / 4;
        e[i] = i % 4;
    }
    ctt_threads(1);
    cr_assert_eq(ct_pair_match(no, a, b, nw, c, e, m1, NULL), CT_OK);
    ctt_threads(2);
    cr_assert_eq(ct_pair_match(no, a, b, nw, c, e, m2, NULL), CT_OK);
    cr_assert_eq(memcmp(m1, m2, nw * sizeof *m1), 0);
    for (ct_idx i = 0; i < nw; i++) {
        /* Old index of (c, e) if present: node c, seg e in {0, 2, 4}. */
        ct_idx want = (e[i] % 2 == 0 && e[i] <= 4 && c[i] < no / 3) ? 3 * c[i] + e[i] / 2 : -1;
        cr_assert_eq(m1[i], want, "i=%d", i);
    }
    free(a);
    free(b);
    free(c);
    free(e);
    free(m1);
    free(m2);
}

/* ---- The fused pair force ------------------------------------------------ */

Test(friction, pair_force_hand_values)
{
    /* K = 1000, ms = 2 (no segment mass), viss = 0.1, dt = 1e-3, n = z,
     * mu0 = 0.5, kt0 = 1000; vn is taken as v . n (NULL).
     * C = 0.1 sqrt(2 * 1000 * 2) = 0.1 sqrt(4000).
     * Pair 0: p = 0.01, v = (1, 0, -0.5), no history: fel = 10, fn = 10 +
     * 0.5 C, energy 0.05, damping work (fel - fn) vn dt = 0.5 C * 0.5e-3;
     * friction trial -kt dt (1, 0, 0) = (-1, 0, 0) inside the cone
     * (limit fn / 2 > 5): stick, no friction work.
     * Pair 1: the same penetration and v = (2, 0, -0.5), history
     * (-6, 0, 3): its normal part 3 is dropped, the trial is (-6 - 2, 0, 0),
     * beyond the limit L = fn/2: slip, F = (-L, 0, 0), friction work
     * L (8 - L)/kt.
     * Pair 2: separated (p < 0): no force, the history is cleared. */
    const double C = 0.1 * sqrt(4000.0), fn0 = 10 + 0.5 * C, L = fn0 / 2;
    ct_real p[3] = {0.01, 0.01, -0.1}, nx[3] = {0, 0, 0}, ny[3] = {0, 0, 0}, nz[3] = {1, 1, 1};
    ct_real vx[3] = {1, 2, 1}, vy[3] = {0, 0, 1}, vz[3] = {-0.5, -0.5, -0.5}, ms[3] = {2, 2, 2};
    ct_real hx[3] = {0, -6, 4}, hy[3] = {0, 0, 4}, hz[3] = {0, 3, 0};
    ct_real fx[3], fy[3], fz[3], fn[3], e[3], dd[3], td[3];
    cr_assert_eq(ct_pair_force_linear_coulomb(3, p, nx, ny, nz, vx, vy, vz, NULL, NULL, 1000, ms,
                                              NULL, 0.1, NULL, 0.5, NULL, 1000, 1e-3, 1, fx,
                                              fy, fz, fn, e, dd, hx, hy, hz, td),
                 CT_OK);
    for (int i = 0; i < 2; i++) {
        cr_assert_leq(ctt_rel(fn[i], fn0), TOL, "pair %d", i);
        cr_assert_leq(ctt_rel(fz[i], fn0), TOL, "pair %d", i);
        cr_assert(fx[i] == 0 && fy[i] == 0, "pair %d", i);
        cr_assert_leq(ctt_rel(e[i], 0.05), TOL, "pair %d", i);
        cr_assert_leq(ctt_rel(dd[i], 0.25e-3 * C), CTT_TOL(1e-12, 1e-5), "pair %d", i);
    }
    cr_assert_leq(ctt_rel(hx[0], -1), CTT_TOL(1e-13, 1e-5));
    cr_assert(hy[0] == 0 && hz[0] == 0 && td[0] == 0);
    cr_assert_leq(ctt_rel(hx[1], -L), TOL);
    cr_assert(hy[1] == 0 && hz[1] == 0);
    cr_assert_leq(ctt_rel(td[1], L * (8 - L) / 1000), CTT_TOL(1e-12, 1e-5));
    cr_assert(fx[2] == 0 && fy[2] == 0 && fz[2] == 0 && fn[2] == 0 && e[2] == 0 && dd[2] == 0);
    cr_assert(hx[2] == 0 && hy[2] == 0 && hz[2] == 0 && td[2] == 0);
    /* Arguments. */
    cr_assert_eq(ct_pair_force_linear_coulomb(3, NULL, nx, ny, nz, vx, vy, vz, NULL, NULL, 1000,
                                              ms, NULL, 0.1, NULL, 0.5, NULL, 1000, 1e-3, 1, fx,
                                              fy, fz, NULL, NULL, NULL, hx, hy, hz, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_pair_force_linear_coulomb(3, p, nx, ny, nz, vx, vy, vz, NULL, NULL, 1000, ms,
                                              NULL, 0.1, NULL, 0.5, NULL, 1000, 1e-3, 0, fx, fy,
                                              fz, NULL, NULL, NULL, hx, hy, hz, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_pair_force_linear_coulomb(3, p, nx, ny, nz, vx, vy, vz, NULL, NULL, 1000, ms,
                                              NULL, 0.1, NULL, 0.5, NULL, 1000, -1, 1, fx, fy,
                                              fz, NULL, NULL, NULL, hx, hy, hz, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_pair_force_linear_coulomb(3, p, nx, ny, nz, vx, vy, vz, NULL, NULL, 1000, ms,
                                              NULL, 0.1, NULL, 0.5, NULL, 1000, 1e-3, 1, fx, fy,
                                              fz, NULL, NULL, NULL, NULL, hy, hz, NULL),
                 CT_ERR_ARG);
}

/* A value drawn in [lo, hi), now and then replaced by an awkward one
 * (0, a negative value, and NaN when `odd` is 1) when `odd` is set. NaN only
 * where it has a meaning (a penetration, a friction coefficient or
 * tangential stiffness counting as 0): elsewhere it is CT_ERR_NONFINITE
 * (test_nonfinite_force.c). */
static ct_real draw(double lo, double hi, int odd)
{
    double u = urand();
    if (odd == 1 && u < 0.02)
        return (ct_real)NAN;
    if (odd && u < 0.05)
        return 0;
    if (odd && u < 0.08)
        return (ct_real)-lo - (ct_real)1;
    return (ct_real)(lo + (hi - lo) * urand());
}

Test(friction, pair_force_fused_bit_identical_to_composition)
{
    /* Every combination of the optional inputs (K, mm, vn, mu, kt), the
     * filter and the optional outputs: the fused kernel, on 1 and on 2
     * threads, against ct_normal_force then ct_friction_step, bytewise.
     * n is above the parallel threshold. */
    const ct_idx n = ctt_checking() ? 9000 : 30000;
    enum { NA = 32 };
    ct_real *a[NA];
    for (int i = 0; i < NA; i++)
        a[i] = malloc(n * sizeof(ct_real));
    ct_real *p = a[0], *nx = a[1], *ny = a[2], *nz = a[3], *vx = a[4], *vy = a[5],
            *vz = a[6], *vn = a[7], *K = a[8], *ms = a[9], *mm = a[10], *mu = a[11],
            *kt = a[12], *h0x = a[13], *h0y = a[14], *h0z = a[15];
    for (ct_idx i = 0; i < n; i++) {
        double x = urand() - 0.5, y = urand() - 0.5, z = urand() - 0.5;
        double l = sqrt(x * x + y * y + z * z) + 1e-300;
        nx[i] = (ct_real)(x / l);
        ny[i] = (ct_real)(y / l);
        nz[i] = (ct_real)(z / l);
        p[i] = draw(-0.01, 0.02, 1);
        vx[i] = draw(-5, 5, 0);
        vy[i] = draw(-5, 5, 0);
        vz[i] = draw(-5, 5, i % 5 == 0 ? 2 : 0);
        vn[i] = draw(-2, 2, 2);
        K[i] = draw(1e2, 1e4, 2);
        ms[i] = draw(1e-3, 1, 2);
        mm[i] = draw(1e-3, 1, 2);
        mu[i] = draw(0, 0.6, 1);
        kt[i] = draw(1e2, 1e4, 1);
        h0x[i] = draw(-20, 20, 0);
        h0y[i] = draw(-20, 20, 0);
        h0z[i] = draw(-20, 20, 0);
    }
    /* Composition: R[0..9] = fx fy fz fn energy dissip ftx fty ftz fdissip;
     * fused on 1 thread: S[0..9]; on 2 threads: T[0..9]. */
    ct_real **R = a + 16, *S[10], *T[10];
    ct_real *vnc = malloc(n * sizeof(ct_real));
    for (int j = 0; j < 10; j++) {
        S[j] = malloc(n * sizeof(ct_real));
        T[j] = malloc(n * sizeof(ct_real));
    }
    const ct_real dt = (ct_real)1e-4;
    int ncase = 0;
    for (int v = 0; v < 128; v++) {
        const int hk = v & 1, hmm = v >> 1 & 1, hvn = v >> 2 & 1, hmu = v >> 3 & 1,
                  hkt = v >> 4 & 1, filt = v >> 5 & 1, outs = v >> 6 & 1;
        const ct_real alpha = filt ? (ct_real)0.3 : 1;
        /* Without vn the normal velocity is v . n, written as the kernel
         * documents it. */
        for (ct_idx i = 0; i < n; i++)
            vnc[i] = hvn ? vn[i] : vx[i] * nx[i] + vy[i] * ny[i] + vz[i] * nz[i];
        for (int j = 0; j < 10; j++) {
            memset(R[j], 0, n * sizeof(ct_real));
            memset(S[j], 0, n * sizeof(ct_real));
            memset(T[j], 0, n * sizeof(ct_real));
        }
        memcpy(R[6], h0x, n * sizeof(ct_real));
        memcpy(R[7], h0y, n * sizeof(ct_real));
        memcpy(R[8], h0z, n * sizeof(ct_real));
        for (int j = 6; j < 9; j++) {
            memcpy(S[j], R[j], n * sizeof(ct_real));
            memcpy(T[j], R[j], n * sizeof(ct_real));
        }
        ctt_threads(2);
        cr_assert_eq(ct_normal_force(n, p, nx, ny, nz, vnc, hk ? K : NULL, (ct_real)3e3, ms,
                                     hmm ? mm : NULL, (ct_real)0.07, dt, R[0], R[1], R[2], R[3],
                                     R[4], R[5]),
                     CT_OK);
        cr_assert_eq(ct_friction_step(n, nx, ny, nz, vx, vy, vz, R[3], hmu ? mu : NULL,
                                      (ct_real)0.3, hkt ? kt : NULL, (ct_real)5e3, dt, alpha,
                                      R[6], R[7], R[8], R[9]),
                     CT_OK);
        for (int t = 1; t <= 2; t++) {
            ct_real **O = t == 1 ? S : T;
            ctt_threads(t);
            cr_assert_eq(ct_pair_force_linear_coulomb(
                             n, p, nx, ny, nz, vx, vy, vz, hvn ? vn : NULL, hk ? K : NULL,
                             (ct_real)3e3, ms, hmm ? mm : NULL, (ct_real)0.07, hmu ? mu : NULL,
                             (ct_real)0.3, hkt ? kt : NULL, (ct_real)5e3, dt, alpha, O[0], O[1],
                             O[2], outs ? O[3] : NULL, outs ? O[4] : NULL, outs ? O[5] : NULL,
                             O[6], O[7], O[8], outs ? O[9] : NULL),
                         CT_OK);
        }
        for (int j = 0; j < 10; j++) {
            if (!outs && (j == 3 || j == 4 || j == 5 || j == 9))
                continue;
            cr_assert_eq(memcmp(S[j], R[j], n * sizeof(ct_real)), 0,
                         "case %d, output %d: fused differs from the composition", v, j);
            cr_assert_eq(memcmp(T[j], S[j], n * sizeof(ct_real)), 0,
                         "case %d, output %d: 2 threads differ from 1", v, j);
        }
        ncase++;
    }
    cr_assert_eq(ncase, 128);
    /* The inputs exercise both sides of each branch: contact and
     * separation, stick and slip (checked on the last case). */
    int ncontact = 0, nslip = 0;
    for (ct_idx i = 0; i < n; i++) {
        ncontact += R[3][i] > 0;
        nslip += R[9][i] > 0;
    }
    cr_assert_gt(ncontact, n / 10);
    cr_assert_gt(nslip, n / 20);
    cr_assert_lt(nslip, ncontact);
    for (int j = 0; j < 10; j++) {
        free(S[j]);
        free(T[j]);
    }
    free(vnc);
    for (int i = 0; i < NA; i++)
        free(a[i]);
}

/* ct_friction_work's books against hand values: pair 0 sticks on a spring
 * of 10 (its force -3 -> -2 along x while it moves at 1), pair 1 has no
 * spring (kt 0) and slides at 2 along y with a force -1. Before the step:
 * pair 0 books -(-3)(1)(0.1)/2 = 0.15 plus the spring's 9/20 given back;
 * after: -(-2)(1)(0.1)/2 = 0.1 less the spring's 4/20 now held, 0.5 in all,
 * which is minus the trapezoid of the force's work, 0.25, plus what the
 * spring gave back, 0.45 - 0.2. kt NULL with kt0 10 books pair 0 the same. */
Test(friction, work_books_hand_values)
{
    ct_real vx[2] = {1, 0}, vy[2] = {0, 2}, vz[2] = {0, 0};
    ct_real gx[2] = {-3, 0}, gy[2] = {0, 0}, gz[2] = {0, 0};
    ct_real kt[2] = {10, 0}, d[2] = {-7, -7}, en[2] = {0.7, 0};
    cr_assert_eq(ct_friction_work(2, vx, vy, vz, gx, gy, gz, kt, 0, 0.1, 0, d, en), CT_OK);
    cr_assert_leq(ctt_rel(d[0], 0.6), TOL, "%.17g", (double)d[0]);
    cr_assert_eq(d[1], 0);
    cr_assert(en[0] == (ct_real)0.7 && en[1] == 0, "energy untouched before the step");
    gx[0] = -2;
    gy[1] = -1;
    cr_assert_eq(ct_friction_work(2, vx, vy, vz, gx, gy, gz, kt, 0, 0.1, 1, d, en), CT_OK);
    cr_assert_leq(ctt_rel(d[0], 0.5), TOL, "%.17g", (double)d[0]);
    cr_assert_leq(ctt_rel(d[1], 0.1), TOL, "%.17g", (double)d[1]);
    cr_assert_leq(ctt_rel(en[0], 0.9), TOL, "%.17g", (double)en[0]);
    cr_assert_eq(en[1], 0);
    ct_real d1[1] = {0};
    cr_assert_eq(ct_friction_work(1, vx, vy, vz, gx, gy, gz, NULL, 10, 0.1, 1, d1, NULL), CT_OK);
    cr_assert_leq(ctt_rel(d1[0], 0.1 - 0.2), TOL, "%.17g", (double)d1[0]);
    /* Bad arguments. */
    cr_assert_eq(ct_friction_work(-1, vx, vy, vz, gx, gy, gz, kt, 0, 0.1, 0, d, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_friction_work(2, vx, vy, vz, NULL, gy, gz, kt, 0, 0.1, 0, d, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_friction_work(2, vx, vy, vz, gx, gy, gz, kt, 0, 0.1, 0, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_friction_work(2, vx, vy, vz, gx, gy, gz, kt, 0, -0.1, 0, d, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_friction_work(2, vx, vy, vz, gx, gy, gz, kt, 0, (ct_real)NAN, 0, d, NULL),
                 CT_ERR_ARG);
}
