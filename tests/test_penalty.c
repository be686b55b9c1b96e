/*
 * test_penalty.c -- normal force laws: linear penalty, TYPE24 stiffness
 * blending and initial penetration, TYPE7 (energy by quadrature, no NaN),
 * TYPE6 curve, damping, the fused fast path and thread independence; the
 * relative velocity at the contact point.
 */
#include "test_util.h"

#define TOL CTT_TOL(1e-14, 1e-6)

Test(penalty, linear_hand_values)
{
    /* K = 1000, p = 0.002: F = 2, E = 0.5 * 1000 * 4e-6 = 0.002. p <= 0 and
     * NaN give nothing. */
    ct_real p[4] = {0.002, 0, -1, NAN}, K[4] = {1000, 1000, 1000, 1000}, f[4], e[4];
    cr_assert_eq(ct_penalty_linear(4, p, NULL, K, 0, NULL, NULL, NULL, NULL, f, e), CT_OK);
    cr_assert_leq(ctt_rel(f[0], 2.0), TOL);
    cr_assert_leq(ctt_rel(e[0], 0.002), TOL);
    for (int i = 1; i < 4; i++)
        cr_assert(f[i] == 0 && e[i] == 0);
    /* Partial blending state is an argument error. */
    ct_real a[4] = {0}, b[4] = {0};
    cr_assert_eq(ct_penalty_linear(4, p, p, K, 0, NULL, a, b, NULL, f, e), CT_ERR_ARG);
    cr_assert_eq(ct_penalty_linear(4, p, NULL, K, 0, NULL, a, b, a, f, e), CT_ERR_ARG);
}

Test(penalty, inacti_subtract_and_ipen_max)
{
    /* Initial penetrations 0, 0.01, 0.5 with Ipen_max = 0.3: the third pair
     * is deactivated. */
    ct_real pi[3] = {0, 0.01, 0.5}, p0[3];
    int32_t act[3];
    cr_assert_eq(ct_initial_penetration(3, CT_INACTI_SUBTRACT, pi, 0.3, p0, act), 1);
    cr_assert(act[0] == 1 && act[1] == 1 && act[2] == 0);
    cr_assert(p0[0] == 0 && p0[1] == pi[1] && p0[2] == 0);
    cr_assert_eq(ct_initial_penetration(3, CT_INACTI_IGNORE, pi, 0, p0, act), 0);
    cr_assert(p0[0] == 0 && p0[1] == 0 && p0[2] == 0 && act[2] == 1);
    /* One pair, K = 100, p0 = 0.01, through p = 0.012, 0.008, 0.009, -0.1:
     *   0.012: q = 0.002, F = 0.2;
     *   0.008: p0 -> 0.008, q = 0, F = 0;
     *   0.009: p0 stays 0.008, q = 0.001, F = 0.1;
     *  -0.1:   p0 -> 0 (forgotten), F = 0. */
    ct_real K = 100, q0 = 0.01, f, e;
    const ct_real seq[4] = {0.012, 0.008, 0.009, -0.1};
    const double wf[4] = {0.2, 0, 0.1, 0}, wp0[4] = {0.01, 0.008, 0.008, 0};
    for (int s = 0; s < 4; s++) {
        cr_assert_eq(ct_penalty_linear(1, &seq[s], NULL, &K, 0, &q0, NULL, NULL, NULL, &f, &e), CT_OK);
        cr_assert_leq(fabs(f - wf[s]), CTT_TOL(1e-14, 1e-6), "step %d f=%g", s, (double)f);
        cr_assert_leq(fabs(q0 - wp0[s]), CTT_TOL(1e-16, 1e-8), "step %d p0=%g", s, (double)q0);
    }
}

Test(penalty, blending_hand_value)
{
    /* K = 100, a new pair found at q = 0.05 while the motion explains
     * d = |vn| dt = 1 * 0.01 = 0.01: E_a = 0.5 * 100 * 0.01^2 = 0.005. The
     * plateau solves Fc q - Fc^2/(2K) = E_a: Fc = K q - sqrt(K^2 q^2 - 2 K
     * E_a) = 5 - sqrt(25 - 1) = 5 - 4.898979485566356 = 0.10102051443364
     * (the kernel uses the cancellation-free form). */
    ct_real p = 0.05, vn = -1, K = 100, pp = 0, fc = CT_BLEND_NONE, qj = 0, f, e;
    cr_assert_eq(ct_penalty_linear(1, &p, &vn, &K, 0.01, NULL, &pp, &fc, &qj, &f, &e), CT_OK);
    cr_assert_leq(ctt_rel(f, 5.0 - sqrt(24.0)), CTT_TOL(1e-13, 1e-5));
    cr_assert_leq(ctt_rel(e, 0.005), CTT_TOL(1e-13, 1e-5));
    cr_assert(fc >= 0 && qj == p && pp == p);
    /* Loading on: full stiffness beyond the jump, F = Fc + K (q - qj):
     * q = 0.055 (motion 0.005 < d): F = 0.10102 + 100 * 0.005 = 0.60102. */
    p = 0.055;
    cr_assert_eq(ct_penalty_linear(1, &p, &vn, &K, 0.01, NULL, &pp, &fc, &qj, &f, &e), CT_OK);
    cr_assert_leq(ctt_rel(f, 5.0 - sqrt(24.0) + 0.5), CTT_TOL(1e-13, 1e-5));
    /* Unloading to 0.02: on the plateau, F = Fc. */
    p = 0.02;
    cr_assert_eq(ct_penalty_linear(1, &p, &vn, &K, 0.01, NULL, &pp, &fc, &qj, &f, &e), CT_OK);
    cr_assert_leq(ctt_rel(f, 5.0 - sqrt(24.0)), CTT_TOL(1e-13, 1e-5));
    /* Down to q = 0.001 < Fc/K = 0.00101: back on the linear branch, the
     * blending ends: F = K q = 0.1. */
    p = 0.001;
    cr_assert_eq(ct_penalty_linear(1, &p, &vn, &K, 0.01, NULL, &pp, &fc, &qj, &f, &e), CT_OK);
    cr_assert_leq(ctt_rel(f, 0.1), CTT_TOL(1e-13, 1e-5));
    cr_assert_eq(fc, CT_BLEND_NONE);
    /* A move explained by the motion never blends: 0.001 -> 0.009 with
     * d = 0.01 gives F = K q = 0.9. */
    p = 0.009;
    cr_assert_eq(ct_penalty_linear(1, &p, &vn, &K, 0.01, NULL, &pp, &fc, &qj, &f, &e), CT_OK);
    cr_assert_leq(ctt_rel(f, 0.9), CTT_TOL(1e-13, 1e-5));
}

/* A unit mass moving into a wall at speed v0 appears at penetration qjump
 * (a late detection); central differences until it has left. Returns the
 * final kinetic energy. */
static double jump_run(int blend, double qjump, double v0, double K, double dt)
{
    ct_real q = (ct_real)qjump, u = (ct_real)v0; /* u = dq/dt, inward */
    ct_real pp = 0, fc = CT_BLEND_NONE, qj = 0, f, e, kk = (ct_real)K;
    for (int step = 0; step < 2000000; step++) {
        ct_real vn = -u;
        if (blend)
            ct_penalty_linear(1, &q, &vn, &kk, (ct_real)dt, NULL, &pp, &fc, &qj, &f, &e);
        else
            ct_penalty_linear(1, &q, &vn, &kk, (ct_real)dt, NULL, NULL, NULL, NULL, &f, &e);
        u -= f * (ct_real)dt; /* m = 1 */
        q += u * (ct_real)dt;
        if (q < 0 && u < 0)
            break;
    }
    return 0.5 * (double)u * (double)u;
}

Test(penalty, blending_creates_no_energy)
{
    /* v0 = 1, K = 1e4, dt = 1e-4 (omega dt = 0.01), found at q = 0.05.
     * Initial kinetic energy 0.5. Without blending the spring holds
     * 0.5 K q^2 = 12.5 from nowhere and the mass leaves with ~13. With
     * blending the stored energy at the jump is the energy of the explained
     * motion, 0.5 K (v0 dt)^2 = 5e-5, and the law is conservative: the mass
     * leaves with 0.5 + 5e-5 up to the O((omega dt)^2) error of central
     * differences on the stiff branch (bounded here by 1e-3 relative). */
    double ke_plain = jump_run(0, 0.05, 1.0, 1e4, 1e-4);
    double ke_blend = jump_run(1, 0.05, 1.0, 1e4, 1e-4);
    cr_assert_gt(ke_plain, 12.0, "plain %g", ke_plain);
    cr_assert_leq(ke_blend, (0.5 + 5e-5) * (1 + 1e-3), "blended %g", ke_blend);
    cr_assert_geq(ke_blend, 0.5 * (1 - 1e-3), "blended %g", ke_blend);
}

/* ---- TYPE7 ---------------------------------------------------------------- */

static double t7_force(double K0, double g, double q) { return K0 * g * q / (g - q); }

/* Adaptive Simpson on F, in double. */
static double simpson(double a, double b, double fa, double fm, double fb, double whole,
                      double K0, double g, double tol, int depth)
{
    double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    double flm = t7_force(K0, g, lm), frm = t7_force(K0, g, rm);
    double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth <= 0 || fabs(left + right - whole) <= 15 * tol)
        return left + right + (left + right - whole) / 15;
    return simpson(a, m, fa, flm, fm, left, K0, g, tol / 2, depth - 1) +
           simpson(m, b, fm, frm, fb, right, K0, g, tol / 2, depth - 1);
}

static double t7_integral(double K0, double g, double p)
{
    double fa = 0, fb = t7_force(K0, g, p), fm = t7_force(K0, g, p / 2);
    double whole = p / 6 * (fa + 4 * fm + fb);
    /* Tolerance: 1e-13 of a bound on the integral (p * F(p)). */
    return simpson(0, p, fa, fm, fb, whole, K0, g, 1e-13 * p * fb, 50);
}

Test(penalty, type7_hand_values)
{
    /* K0 = 100, g = 1, p = 0.5: K = 100/0.5 = 200, F = 100, tangent
     * K0/r^2 = 400, E = 100 (0.5 - 1 - ln 0.5) = 19.314718055994531. */
    ct_real p = 0.5, g = 1, K0 = 100, f, kt, e;
    int32_t flag;
    cr_assert_eq(ct_penalty_type7(1, &p, &g, &K0, &f, &kt, &e, &flag), CT_OK);
    cr_assert_leq(ctt_rel(f, 100), TOL);
    cr_assert_leq(ctt_rel(kt, 400), TOL);
    cr_assert_leq(ctt_rel(e, 19.314718055994531), CTT_TOL(1e-14, 1e-6));
    cr_assert_eq(flag, 0);
    cr_assert_leq(ctt_rel(ct_type7_tangent(100, 1, 0.5), 400), TOL);
}

Test(penalty, type7_energy_is_integral_of_force)
{
    /* E(p) against adaptive Simpson of F = K0 g q/(g - q) over [0, p], at
     * p/g from 1e-6 to 0.9989 (just below deactivation at 0.999), for two
     * (K0, g). 1e-8 relative in double; 1e-4 in single (p/g itself carries a
     * 6e-8 rounding, amplified by 1/r = 1000 near the mid-surface). */
    const double xs[] = {1e-6, 1e-3, 0.02, 0.1, 0.3, 0.5, 0.9, 0.99, 0.999 - 1.1e-4};
    const double K0s[] = {100, 3e5}, gs[] = {1, 0.004};
    for (int c = 0; c < 2; c++)
        for (unsigned i = 0; i < sizeof xs / sizeof xs[0]; i++) {
            double g = gs[c], K0 = K0s[c], p = xs[i] * g;
            ct_real pr = (ct_real)p, gr = (ct_real)g, kr = (ct_real)K0, f, e;
            ct_penalty_type7(1, &pr, &gr, &kr, &f, NULL, &e, NULL);
            double want = t7_integral(K0, g, (double)pr);
            cr_assert_leq(ctt_rel(e, want), CTT_TOL(1e-8, 1e-4), "x=%g e=%.17g want=%.17g",
                          xs[i], (double)e, want);
            cr_assert_leq(ctt_rel(ct_type7_energy(kr, gr, pr), want), CTT_TOL(1e-8, 1e-4));
        }
}

Test(penalty, type7_monotone_finite_and_deactivation)
{
    /* F finite and non-decreasing for p/g from 0 to 1.5; flag set from
     * 1 - RMIN on, where F stays at K0 g (1 - RMIN)/RMIN = 999 K0 g. */
    const int n = 3000;
    ct_real g = 2, K0 = 50, prev = -1;
    for (int i = 0; i <= n; i++) {
        ct_real p = (ct_real)(1.5 * g * i / n), f, kt, e;
        int32_t flag;
        ct_penalty_type7(1, &p, &g, &K0, &f, &kt, &e, &flag);
        cr_assert(isfinite(f) && isfinite(kt) && isfinite(e));
        cr_assert_geq(f, prev, "p=%g", (double)p);
        prev = f;
        double x = (double)p / (double)g;
        if (x < 0.999 - 1e-6)
            cr_assert_eq(flag, 0, "x=%g", x);
        if (x >= 0.999 + 1e-6) {
            cr_assert_eq(flag, 1, "x=%g", x);
            cr_assert_leq(ctt_rel(f, 999.0 * 50 * 2), CTT_TOL(1e-12, 1e-4));
        }
    }
}

Test(penalty, type7_never_nan)
{
    /* p in {-1, 0, g/2, g, 2g, inf, nan} with g = 1, and g = 0, -1, nan,
     * inf: every output finite, or CT_ERR_NONFINITE for an infinite p or g
     * (they gave finite outputs with CT_OK: the force at the cap, or none;
     * test_penalty_nonfinite.c). */
    const ct_real ps[7] = {-1, 0, 0.5, 1, 2, INFINITY, NAN};
    const ct_real gsv[5] = {1, 0, -1, NAN, INFINITY};
    for (int a = 0; a < 7; a++)
        for (int b = 0; b < 5; b++) {
            ct_real p = ps[a], g = gsv[b], K0 = 10, f, kt, e;
            int32_t flag;
            /* The scalar functions have no error code: finite always. */
            cr_assert(isfinite(ct_type7_energy(10, g, p)));
            cr_assert(isfinite(ct_type7_tangent(10, g, p)));
            int rc = ct_penalty_type7(1, &p, &g, &K0, &f, &kt, &e, &flag);
            if (isinf(p) || isinf(g)) {
                cr_assert_eq(rc, CT_ERR_NONFINITE, "p=%g g=%g", (double)p, (double)g);
                continue;
            }
            cr_assert_eq(rc, CT_OK);
            cr_assert(isfinite(f) && isfinite(kt) && isfinite(e) && f >= 0 && e >= 0,
                      "p=%g g=%g f=%g kt=%g e=%g", (double)p, (double)g, (double)f,
                      (double)kt, (double)e);
        }
}

/* ---- TYPE6 ---------------------------------------------------------------- */

Test(penalty, type6_curve_eval_and_checks)
{
    /* x = {0, 1, 3}, y = {0, 10, 50}: slopes 10 then 20.
     * f(0.5) = 5, f'(0.5) = 10; f(2) = 10 + 20 = 30, f'(2) = 20;
     * f(1) = 10 (right interval: slope 20); f(4) = 50 + 20 = 70 (linear
     * extrapolation of the last interval); f(-1) = -10 (first interval). */
    ct_real x[3] = {0, 1, 3}, y[3] = {0, 10, 50}, s;
    cr_assert_eq(ct_curve_check(3, x, y, NULL), CT_OK);
    cr_assert_leq(fabs(ct_curve_eval(3, x, y, 0.5, &s) - 5), TOL);
    cr_assert_eq(s, 10);
    cr_assert_leq(fabs(ct_curve_eval(3, x, y, 2, &s) - 30), TOL * 30);
    cr_assert_eq(s, 20);
    cr_assert_leq(fabs(ct_curve_eval(3, x, y, 1, &s) - 10), TOL * 10);
    cr_assert_eq(s, 20);
    cr_assert_leq(fabs(ct_curve_eval(3, x, y, 4, &s) - 70), TOL * 70);
    cr_assert_leq(fabs(ct_curve_eval(3, x, y, -1, &s) + 10), TOL * 10);
    cr_assert_eq(ct_curve_eval(3, x, y, NAN, &s), 0);
    /* Bad tables, with the offending index. */
    ct_diag d;
    cr_assert_eq(ct_curve_check(1, x, y, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, -1);
    ct_real xb[3] = {0, 1, 1};
    cr_assert_eq(ct_curve_check(3, xb, y, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 2);
    ct_real xd[3] = {0, 2, 1};
    cr_assert_eq(ct_curve_check(3, xd, y, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 2);
    ct_real yn[3] = {0, NAN, 1};
    cr_assert_eq(ct_curve_check(3, x, yn, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 1);
    ct_real xi[3] = {0, 1, INFINITY};
    cr_assert_eq(ct_curve_check(3, xi, y, &d), CT_ERR_ARG);
    cr_assert_eq(d.index, 2);
    ct_real f[1];
    cr_assert_eq(ct_penalty_type6(1, x, 3, xb, y, f, NULL, NULL, NULL, &d), CT_ERR_ARG);
}

Test(penalty, type6_distribution)
{
    /* p = {0.5, 1, -0.2, 2, NaN}: p_max = 2, F = f(2) = 30, sum of positive
     * penetrations 3.5, so forces 30 * {0.5, 1, 0, 2, 0}/3.5 =
     * {4.285714.., 8.571428.., 0, 17.142857.., 0}, summing to 30;
     * K = max(f'(2), f(2)/2) = max(20, 15) = 20. */
    ct_real x[3] = {0, 1, 3}, y[3] = {0, 10, 50};
    ct_real p[5] = {0.5, 1, -0.2, 2, NAN}, f[5], pm, ft, kc;
    cr_assert_eq(ct_penalty_type6(5, p, 3, x, y, f, &pm, &ft, &kc, NULL), CT_OK);
    cr_assert_eq(pm, 2);
    cr_assert_leq(ctt_rel(ft, 30), TOL);
    cr_assert_leq(ctt_rel(kc, 20), TOL);
    const double w[5] = {30 * 0.5 / 3.5, 30 * 1 / 3.5, 0, 30 * 2 / 3.5, 0};
    double sum = 0;
    for (int i = 0; i < 5; i++) {
        cr_assert_leq(fabs(f[i] - w[i]), TOL * 30, "i=%d", i);
        sum += f[i];
    }
    cr_assert_leq(ctt_rel(sum, 30), TOL * 4);
    /* Many pairs, 1 and 2 threads: bit-identical, summing to f(p_max). */
    const ct_idx n = ctt_checking() ? 30000 : 300000;
    ct_real *pp = malloc(n * sizeof *pp), *f1 = malloc(n * sizeof *f1),
            *f2 = malloc(n * sizeof *f2);
    for (ct_idx i = 0; i < n; i++)
        pp[i] = (ct_real)((((int64_t)i * 7919) % 1000) / 500.0 - 0.5); /* -0.5 .. 1.498 */
    ctt_threads(1);
    cr_assert_eq(ct_penalty_type6(n, pp, 3, x, y, f1, &pm, &ft, NULL, NULL), CT_OK);
    ctt_threads(2);
    cr_assert_eq(ct_penalty_type6(n, pp, 3, x, y, f2, NULL, NULL, NULL, NULL), CT_OK);
    cr_assert_eq(memcmp(f1, f2, n * sizeof *f1), 0);
    /* f(1.498) = 10 + 20 * 0.498 = 19.96. */
    cr_assert_leq(ctt_rel(ft, 19.96), CTT_TOL(1e-13, 1e-5));
    long double s = 0;
    for (ct_idx i = 0; i < n; i++)
        s += f1[i];
    cr_assert_leq(ctt_rel((double)s, ft), CTT_TOL(1e-12, 1e-4));
    free(pp);
    free(f1);
    free(f2);
}

/* ---- Damping and the force vector ----------------------------------------- */

Test(penalty, damping_hand_values)
{
    /* C = VisS sqrt(2 K m): 0.1 sqrt(2 * 1e4 * 2) = 0.1 * 200 = 20; with the
     * reduced mass of 2 and 2 (m = 1): 0.1 sqrt(2e4) = 14.142135623730951. */
    cr_assert_leq(ctt_rel(ct_damping_coef(0.1, 1e4, 2, 0), 20), TOL);
    cr_assert_leq(ctt_rel(ct_damping_coef(0.1, 1e4, 2, 2), 14.142135623730951), TOL);
    cr_assert_eq(ct_damping_coef(0.1, -1, 2, 0), 0);
    /* Pair 0 approaching (vn = -0.1): fn = 5 + 20 * 0.1 = 7, dissipation
     * C vn^2 dt = 20 * 0.01 * 1e-3 = 2e-4. Pair 1 separating fast (vn = 1):
     * 5 - 20 < 0 is clamped to 0 (no tension), dissipation 5 * 1 * 1e-3.
     * Pair 2 out of contact: zeros. Normal n = (0, 0.6, 0.8). */
    ct_real p[3] = {0.1, 0.1, -1}, fel[3] = {5, 5, 5}, kd[3] = {1e4, 1e4, 1e4};
    ct_real vn[3] = {-0.1, 1, -1}, ms[3] = {2, 2, 2};
    ct_real nx[3] = {0, 0, 0}, ny[3] = {0.6, 0.6, 0.6}, nz[3] = {0.8, 0.8, 0.8};
    ct_real fn[3], fx[3], fy[3], fz[3], dis[3];
    cr_assert_eq(ct_normal_finish(3, p, fel, kd, vn, ms, NULL, 0.1, 1e-3, nx, ny, nz, fn, fx, fy,
                                  fz, dis),
                 CT_OK);
    cr_assert_leq(ctt_rel(fn[0], 7), TOL);
    cr_assert_leq(ctt_rel(fy[0], 4.2), TOL);
    cr_assert_leq(ctt_rel(fz[0], 5.6), TOL);
    cr_assert_eq(fx[0], 0);
    cr_assert_leq(ctt_rel(dis[0], 2e-4), CTT_TOL(1e-13, 1e-5));
    cr_assert_eq(fn[1], 0);
    cr_assert_leq(ctt_rel(dis[1], 5e-3), TOL);
    cr_assert(fn[2] == 0 && fy[2] == 0 && dis[2] == 0);
    /* The fused path: F = K p = 1e4 * 0.1 = 1000 plus 20 * 0.1 = 1002;
     * energy 0.5 * 1e4 * 0.01 = 50. */
    ct_real e[3];
    cr_assert_eq(ct_normal_force(3, p, nx, ny, nz, vn, kd, 0, ms, NULL, 0.1, 1e-3, fx, fy, fz,
                                 fn, e, dis),
                 CT_OK);
    cr_assert_leq(ctt_rel(fn[0], 1002), TOL);
    cr_assert_leq(ctt_rel(fz[0], 801.6), TOL);
    cr_assert_leq(ctt_rel(e[0], 50), TOL);
    cr_assert_leq(ctt_rel(dis[0], 2e-4), CTT_TOL(1e-12, 1e-4));
    cr_assert_leq(ctt_rel(fn[1], 1000 - 20), TOL);
    cr_assert(fn[2] == 0 && e[2] == 0 && dis[2] == 0);
}

Test(penalty, fused_matches_composed_and_threads)
{
    const ct_idx n = ctt_checking() ? 20000 : 200000;
    ct_real *a[16];
    for (int i = 0; i < 16; i++)
        a[i] = malloc(n * sizeof(ct_real));
    ct_real *p = a[0], *nx = a[1], *ny = a[2], *nz = a[3], *vn = a[4], *K = a[5], *ms = a[6],
            *mm = a[7];
    for (ct_idx i = 0; i < n; i++) {
        double t = 0.001 * i;
        p[i] = (ct_real)(0.01 * sin(t));
        nx[i] = (ct_real)cos(t);
        ny[i] = (ct_real)sin(t);
        nz[i] = 0;
        vn[i] = (ct_real)cos(3 * t);
        K[i] = (ct_real)(1e3 * (1.5 + sin(5 * t)));
        ms[i] = 1 + (ct_real)(i % 3);
        mm[i] = 2;
    }
    ct_real *fx = a[8], *fy = a[9], *fz = a[10], *fn = a[11], *gx = a[12], *gy = a[13],
            *gz = a[14], *fel = a[15];
    ctt_threads(1);
    ct_normal_force(n, p, nx, ny, nz, vn, K, 0, ms, mm, 0.05, 1e-4, fx, fy, fz, fn, NULL, NULL);
    ctt_threads(2);
    ct_normal_force(n, p, nx, ny, nz, vn, K, 0, ms, mm, 0.05, 1e-4, gx, gy, gz, NULL, NULL, NULL);
    cr_assert_eq(memcmp(fx, gx, n * sizeof *fx), 0);
    cr_assert_eq(memcmp(fz, gz, n * sizeof *fz), 0);
    /* The composed path (linear law, then damping) agrees to round-off. */
    ct_penalty_linear(n, p, NULL, K, 0, NULL, NULL, NULL, NULL, fel, NULL);
    ct_normal_finish(n, p, fel, K, vn, ms, mm, 0.05, 1e-4, nx, ny, nz, fn, gx, gy, gz, NULL);
    for (ct_idx i = 0; i < n; i++)
        cr_assert_leq(fabs(gx[i] - fx[i]), CTT_TOL(1e-12, 1e-4) * (1 + fabs(fx[i])));
    for (int i = 0; i < 16; i++)
        free(a[i]);
}

Test(penalty, ordered_sum_threads)
{
    const ct_idx n = ctt_checking() ? 50001 : 500001;
    ct_real *v = malloc(n * sizeof *v);
    for (ct_idx i = 0; i < n; i++)
        v[i] = (ct_real)(1.0 / (1 + i % 977));
    ctt_threads(1);
    double s1 = ct_sum_ordered(n, v);
    ctt_threads(2);
    double s2 = ct_sum_ordered(n, v);
    cr_assert_eq(memcmp(&s1, &s2, sizeof s1), 0);
    long double ref = 0;
    for (ct_idx i = 0; i < n; i++)
        ref += v[i];
    cr_assert_leq(ctt_rel(s1, (double)ref), 1e-13);
    free(v);
}

/* Uniform in [0, 1) from a 64-bit LCG (Knuth's MMIX constants). */
static double rv_rand01(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * 0x1p-53;
}

/* ct_relative_velocity: a hand case (a quad and a triangle), then a rigid
 * rotation v = w x x of many pairs, where the relative velocity must be
 * w x (p - c) for the node p and the contact point c = sum h_i x_i, and the
 * main mass at c the interpolated one; argument checks. */
Test(penalty, relative_velocity_hand_and_rigid_rotation)
{
    /* Nodes 0..3 a quad, 4 a triangle's third node, 5 the secondary. */
    ct_real vx[6] = {1, 2, 3, 4, 5, 10}, vy[6] = {0, 0, 0, 0, -2, 1}, vz[6] = {1, 1, 1, 1, 1, 4};
    ct_real m[6] = {1, 2, 3, 4, 5, 6};
    ct_idx node[2] = {5, 5}, s1[2] = {0, 0}, s2[2] = {1, 1}, s3[2] = {2, 4}, s4[2] = {3, 4};
    ct_real h1[2] = {0.1, 0.5}, h2[2] = {0.2, 0.25}, h3[2] = {0.3, 0.25}, h4[2] = {0.4, 0};
    ct_real nx[2] = {0, 0.6}, ny[2] = {0, 0.8}, nz[2] = {1, 0};
    ct_real rx[2], ry[2], rz[2], vn[2], mm[2];
    cr_assert_eq(ct_relative_velocity(2, node, s1, s2, s3, s4, h1, h2, h3, h4, nx, ny, nz, vx, vy,
                                      vz, m, rx, ry, rz, vn, mm),
                 CT_OK);
    /* Quad: contact point velocity (0.1 + 0.4 + 0.9 + 1.6, 0, 1) = (3, 0, 1);
     * u = (7, 1, 3), vn = 3; mass 0.1 + 0.4 + 0.9 + 1.6 = 3. */
    const double tol = CTT_TOL(1e-15, 1e-6);
    cr_assert_leq(fabs(rx[0] - 7) + fabs(ry[0] - 1) + fabs(rz[0] - 3), 4 * tol);
    cr_assert_leq(fabs(vn[0] - 3), 4 * tol);
    cr_assert_leq(fabs(mm[0] - 3), 4 * tol);
    /* Triangle (0, 1, 4): point velocity (0.5 + 0.5 + 1.25, -0.5, 1) =
     * (2.25, -0.5, 1); u = (7.75, 1.5, 3); vn = 4.65 + 1.2 = 5.85; mass
     * 0.5 + 0.5 + 1.25 = 2.25. */
    cr_assert_leq(fabs(rx[1] - 7.75) + fabs(ry[1] - 1.5) + fabs(rz[1] - 3), 16 * tol);
    cr_assert_leq(fabs(vn[1] - 5.85), 16 * tol);
    cr_assert_leq(fabs(mm[1] - 2.25), 4 * tol);
    /* Without masses: the same velocities. */
    ct_real r2[2];
    cr_assert_eq(ct_relative_velocity(2, node, s1, s2, s3, s4, h1, h2, h3, h4, nx, ny, nz, vx, vy,
                                      vz, NULL, r2, ry, rz, vn, NULL),
                 CT_OK);
    cr_assert(memcmp(r2, rx, sizeof r2) == 0);
    /* m without mm (or the reverse), a negative count, a missing array. */
    cr_assert_eq(ct_relative_velocity(2, node, s1, s2, s3, s4, h1, h2, h3, h4, nx, ny, nz, vx, vy,
                                      vz, m, rx, ry, rz, vn, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_relative_velocity(2, node, s1, s2, s3, s4, h1, h2, h3, h4, nx, ny, nz, vx, vy,
                                      vz, NULL, rx, ry, rz, vn, mm),
                 CT_ERR_ARG);
    cr_assert_eq(ct_relative_velocity(-1, node, s1, s2, s3, s4, h1, h2, h3, h4, nx, ny, nz, vx,
                                      vy, vz, NULL, rx, ry, rz, vn, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_relative_velocity(2, node, s1, s2, s3, s4, h1, h2, h3, NULL, nx, ny, nz, vx,
                                      vy, vz, NULL, rx, ry, rz, vn, NULL),
                 CT_ERR_ARG);

    /* Rigid rotation about w through the origin, 3 x 10^4 random pairs
     * (several blocks, two threads). */
    const ct_idx nn = 20000, np = 30000;
    ct_real *X[3], *V[3], *H[4], *R[3], *N[3], *vnr = ct_calloc(np, sizeof(ct_real));
    ct_idx *S[5];
    for (int a = 0; a < 3; a++) {
        X[a] = ct_calloc(nn, sizeof(ct_real));
        V[a] = ct_calloc(nn, sizeof(ct_real));
        R[a] = ct_calloc(np, sizeof(ct_real));
        N[a] = ct_calloc(np, sizeof(ct_real));
    }
    for (int j = 0; j < 4; j++)
        H[j] = ct_calloc(np, sizeof(ct_real));
    for (int j = 0; j < 5; j++)
        S[j] = ct_calloc(np, sizeof(ct_idx));
    const double w[3] = {0.3, -1.1, 0.7};
    uint64_t st = 12345;
    for (ct_idx i = 0; i < nn; i++) {
        for (int a = 0; a < 3; a++)
            X[a][i] = (ct_real)(4 * rv_rand01(&st) - 2);
        V[0][i] = (ct_real)(w[1] * X[2][i] - w[2] * X[1][i]);
        V[1][i] = (ct_real)(w[2] * X[0][i] - w[0] * X[2][i]);
        V[2][i] = (ct_real)(w[0] * X[1][i] - w[1] * X[0][i]);
    }
    for (ct_idx k = 0; k < np; k++) {
        double hs = 0, h[4];
        for (int j = 0; j < 5; j++)
            S[j][k] = (ct_idx)(rv_rand01(&st) * nn) % nn;
        for (int j = 0; j < 4; j++)
            hs += h[j] = rv_rand01(&st);
        for (int j = 0; j < 4; j++)
            H[j][k] = (ct_real)(h[j] / hs);
        N[0][k] = 0, N[1][k] = 0, N[2][k] = 1;
    }
    ctt_threads(2);
    cr_assert_eq(ct_relative_velocity(np, S[4], S[0], S[1], S[2], S[3], H[0], H[1], H[2], H[3],
                                      N[0], N[1], N[2], V[0], V[1], V[2], NULL, R[0], R[1], R[2],
                                      vnr, NULL),
                 CT_OK);
    double err = 0;
    for (ct_idx k = 0; k < np; k++) {
        double d[3];
        for (int a = 0; a < 3; a++) {
            double c = 0;
            for (int j = 0; j < 4; j++)
                c += (double)H[j][k] * X[a][S[j][k]];
            d[a] = X[a][S[4][k]] - c;
        }
        double u[3] = {w[1] * d[2] - w[2] * d[1], w[2] * d[0] - w[0] * d[2],
                       w[0] * d[1] - w[1] * d[0]};
        for (int a = 0; a < 3; a++)
            err = fmax(err, fabs(R[a][k] - u[a]));
        err = fmax(err, fabs(vnr[k] - u[2]));
    }
    /* |v| <= 2 sqrt(3) |w|: a few roundings of that. */
    cr_assert_leq(err, CTT_TOL(1e-13, 1e-5), "max error %g against w x (p - c)", err);
    for (int a = 0; a < 3; a++) {
        ct_free(X[a]);
        ct_free(V[a]);
        ct_free(R[a]);
        ct_free(N[a]);
    }
    for (int j = 0; j < 4; j++)
        ct_free(H[j]);
    for (int j = 0; j < 5; j++)
        ct_free(S[j]);
    ct_free(vnr);
}

/* A 64-bit xorshift step. */
static uint64_t t7_rand(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

#define T7_EPS (sizeof(ct_real) == 4 ? 1.1920929e-07 : 2.220446049250313e-16)

Test(penalty, type7_energy_array_equals_one_pair)
{
    /* TYPE7's energies from the array kernel and from ct_type7_energy
     * (one pair) for 1037 pairs: x over (0, 1.2),
     * both sides of 1/32 and of the deactivation point, pairs out of
     * contact; gaps over twelve decades. The same bits below the
     * deactivation point; past it the kernel adds its own force times the
     * rest of the way, within a few roundings of the one-pair form. */
    enum { N = 1037 };
    static ct_real p[N], g[N], k0[N], fel[N], e[N];
    uint64_t s = 777;
    for (int i = 0; i < N; i++) {
        g[i] = (ct_real)ldexp(1 + (double)(t7_rand(&s) % 1000) / 1000.0,
                              (int)(t7_rand(&s) % 40) - 30);
        k0[i] = (ct_real)ldexp(1, (int)(t7_rand(&s) % 30));
        double x = i % 3 == 0 ? (double)(t7_rand(&s) % 1000) / 1000.0 * 1.2
                              : (double)(t7_rand(&s) % 1000) / 1000.0 / 16;
        p[i] = (ct_real)(x * (double)g[i]);
        if (i % 11 == 0)
            p[i] = -p[i];
    }
    const ct_real xc = 1 - (ct_real)CT_TYPE7_RMIN;
    for (int t = 1; t <= 2; t++) {
        omp_set_num_threads(t);
        cr_assert_eq(ct_penalty_type7(N, p, g, k0, fel, NULL, e, NULL), CT_OK);
        for (int i = 0; i < N; i++) {
            ct_real one = ct_type7_energy(k0[i], g[i], p[i]);
            if (p[i] / g[i] < xc)
                cr_assert_eq(e[i], one, "pair %d: x = %g: %a against %a", i,
                             (double)(p[i] / g[i]), (double)e[i], (double)one);
            else
                cr_assert_leq(fabs((double)(e[i] - one)), 8 * T7_EPS * (double)one, "pair %d", i);
            if (!(p[i] > 0))
                cr_assert_eq(e[i], 0);
        }
    }
}

/* ct_damping_work's books against hand values (dt 0.1): pair 0 in contact,
 * damping part 5 - 4 = 1 after 1, approaching at 2: -(1 + 1)(-2)(0.1)/2 =
 * 0.2; pair 1, damping part 2 - 3 = -1 (the damper eases the spring while
 * the node leaves) after 0.5, leaving at 1: -(0.5 - 1)(1)(0.1)/2 = 0.025;
 * pair 2 out of contact, its last damping force 2 still books its second
 * half step: -(2 + 0)(3)(0.1)/2 = -0.3 (negative: the force did work on a
 * node it pushed away), and its state falls to 0. */
Test(penalty, damping_work_hand_values)
{
    ct_real p[3] = {0.1, 0.2, -0.1}, fn[3] = {5, 2, 0}, fel[3] = {4, 3, 1};
    ct_real vn[3] = {-2, 1, 3}, fo[3] = {1, 0.5, 2}, d[3] = {9, 9, 9};
    cr_assert_eq(ct_damping_work(3, p, fn, fel, vn, 0.1, fo, d), CT_OK);
    const double want[3] = {0.2, 0.025, -0.3}, wf[3] = {1, -1, 0};
    for (int k = 0; k < 3; k++) {
        cr_assert_leq(ctt_rel(d[k], want[k]), TOL, "%d: %.17g", k, (double)d[k]);
        cr_assert_eq(fo[k], (ct_real)wf[k], "%d: state %g", k, (double)fo[k]);
    }
    cr_assert_eq(ct_damping_work(-1, p, fn, fel, vn, 0.1, fo, d), CT_ERR_ARG);
    cr_assert_eq(ct_damping_work(3, p, fn, fel, NULL, 0.1, fo, d), CT_ERR_ARG);
    cr_assert_eq(ct_damping_work(3, p, fn, fel, vn, 0.1, NULL, d), CT_ERR_ARG);
    cr_assert_eq(ct_damping_work(3, p, fn, fel, vn, (ct_real)INFINITY, fo, d), CT_ERR_ARG);
}
