/*
 * test_friction_nonfinite.c -- the friction step, the fused pair force and
 * the friction laws against NaN and infinite inputs and overflows (suite
 * "friction", docs/fuzz F15): every input array, one bad entry at a time
 * (test_nonfinite.h), the scalars, results that overflow from finite
 * inputs, and finite extreme inputs that must still pass.
 *
 * Each "each_input" test failed before F15 on its first +inf: the kernels
 * returned CT_OK whatever their inputs (the friction step gave no force for
 * a NaN or infinite trial, infinite or NaN forces otherwise; the friction
 * laws clamped a NaN to 0 and let +inf through).
 */
#include "test_nonfinite.h"

#define DT ((ct_real)1e-4)

/* ---- ct_friction_step ------------------------------------------------------ */

enum { FR_NX, FR_NY, FR_NZ, FR_VX, FR_VY, FR_VZ, FR_FTX, FR_FTY, FR_FTZ, FR_FN, FR_MU, FR_KT,
       FR_N };

static void fill_friction(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        ntf_normal(i, 20, &in[FR_NX][i], &in[FR_NY][i], &in[FR_NZ][i]);
        in[FR_VX][i] = ntf_val(i, 23, -1, 1);
        in[FR_VY][i] = ntf_val(i, 24, -1, 1);
        in[FR_VZ][i] = ntf_val(i, 25, -1, 1);
        /* Old forces within and beyond the cone: stick and slip. */
        in[FR_FTX][i] = ntf_val(i, 26, -0.3, 0.3);
        in[FR_FTY][i] = ntf_val(i, 27, -0.3, 0.3);
        in[FR_FTZ][i] = ntf_val(i, 28, -0.3, 0.3);
        in[FR_FN][i] = ntf_contact(i) ? ntf_val(i, 29, 0.5, 1.5) : 0;
        in[FR_MU][i] = ntf_val(i, 30, 0.1, 0.5);
        in[FR_KT][i] = ntf_val(i, 31, 1e3, 2e3);
    }
}

static int call_friction(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_friction_step(n, in[FR_NX], in[FR_NY], in[FR_NZ], in[FR_VX], in[FR_VY],
                            in[FR_VZ], in[FR_FN], in[FR_MU], 0, in[FR_KT], 0, DT, 1, in[FR_FTX],
                            in[FR_FTY], in[FR_FTZ], out[0]);
}

/* The filter, the scalars mu0 and kt0, no dissipation. */
static int call_friction_filt(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    (void)out;
    return ct_friction_step(n, in[FR_NX], in[FR_NY], in[FR_NZ], in[FR_VX], in[FR_VY],
                            in[FR_VZ], in[FR_FN], NULL, (ct_real)0.3, NULL, (ct_real)1.5e3, DT,
                            (ct_real)0.5, in[FR_FTX], in[FR_FTY], in[FR_FTZ], NULL);
}

/* The new tangential force (the history) and the friction work. */
static int zero_friction(ct_real **in, ct_real **out, ct_idx k)
{
    return in[FR_FTX][k] == 0 && in[FR_FTY][k] == 0 && in[FR_FTZ][k] == 0 && out[0][k] == 0;
}

/* fn, mu and kt NaN or negative (-inf too) count as 0 (the header): no
 * friction force for fn or mu; kt = 0 keeps the old force, capped. */
Test(friction, nonfinite_step_each_input)
{
    const ntf_case c = {"ct_friction_step", FR_N, 1, 1,
                        {"nx", "ny", "nz", "vx", "vy", "vz", "ftx", "fty", "ftz", "fn", "mu",
                         "kt"},
                        7u << FR_FN, 3u << FR_FN, 0, fill_friction, call_friction,
                        zero_friction};
    ntf_run(&c);
    const ntf_case c2 = {"ct_friction_step (filter, scalars)", FR_MU, 0, 1,
                         {"nx", "ny", "nz", "vx", "vy", "vz", "ftx", "fty", "ftz", "fn"},
                         1u << FR_FN, 0, 0, fill_friction, call_friction_filt, NULL};
    ntf_run(&c2);
}

/* ---- ct_pair_force_linear_coulomb ------------------------------------------- */

enum { PF_P, PF_NX, PF_NY, PF_NZ, PF_VX, PF_VY, PF_VZ, PF_FTX, PF_FTY, PF_FTZ, PF_MS, PF_VN,
       PF_K, PF_MM, PF_MU, PF_KT, PF_N };

static void fill_pair(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        in[PF_P][i] = ntf_pen(i);
        ntf_normal(i, 40, &in[PF_NX][i], &in[PF_NY][i], &in[PF_NZ][i]);
        in[PF_VX][i] = ntf_val(i, 43, -1, 1);
        in[PF_VY][i] = ntf_val(i, 44, -1, 1);
        in[PF_VZ][i] = ntf_val(i, 45, -1, 1);
        in[PF_FTX][i] = ntf_val(i, 46, -0.3, 0.3);
        in[PF_FTY][i] = ntf_val(i, 47, -0.3, 0.3);
        in[PF_FTZ][i] = ntf_val(i, 48, -0.3, 0.3);
        in[PF_MS][i] = ntf_val(i, 49, 0.5, 1.5);
        in[PF_VN][i] = in[PF_VX][i] * in[PF_NX][i] + in[PF_VY][i] * in[PF_NY][i] +
                       in[PF_VZ][i] * in[PF_NZ][i];
        in[PF_K][i] = ntf_val(i, 50, 1e3, 2e3);
        in[PF_MM][i] = ntf_val(i, 51, 0.5, 1.5);
        in[PF_MU][i] = ntf_val(i, 52, 0.1, 0.5);
        in[PF_KT][i] = ntf_val(i, 53, 1e3, 2e3);
    }
}

static int call_pair(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_pair_force_linear_coulomb(
        n, in[PF_P], in[PF_NX], in[PF_NY], in[PF_NZ], in[PF_VX], in[PF_VY], in[PF_VZ],
        in[PF_VN], in[PF_K], 0, in[PF_MS], in[PF_MM], (ct_real)0.3, in[PF_MU], 0, in[PF_KT], 0,
        DT, 1, out[0], out[1], out[2], out[3], out[4], out[5], in[PF_FTX], in[PF_FTY],
        in[PF_FTZ], out[6]);
}

/* Without vn (v . n instead), K, mm, mu, kt (their scalars), with the
 * filter, without the energy and the friction work. */
static int call_pair_lean(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_pair_force_linear_coulomb(
        n, in[PF_P], in[PF_NX], in[PF_NY], in[PF_NZ], in[PF_VX], in[PF_VY], in[PF_VZ], NULL,
        NULL, (ct_real)1.5e3, in[PF_MS], NULL, (ct_real)0.3, NULL, (ct_real)0.3, NULL,
        (ct_real)1.5e3, DT, (ct_real)0.5, out[0], out[1], out[2], out[3], NULL, out[5],
        in[PF_FTX], in[PF_FTY], in[PF_FTZ], NULL);
}

static int zero_pair(ct_real **in, ct_real **out, ct_idx k)
{
    return ntf_all_zero(out, 7, 1, k) && in[PF_FTX][k] == 0 && in[PF_FTY][k] == 0 &&
           in[PF_FTZ][k] == 0;
}

/* The union of the two kernels' checks. A NaN or negative p is no contact
 * (no force at all); mu and kt as in ct_friction_step (the normal force
 * stays). */
Test(friction, nonfinite_pair_force_each_input)
{
    const ntf_case c = {"ct_pair_force_linear_coulomb", PF_N, 7, 1,
                        {"p", "nx", "ny", "nz", "vx", "vy", "vz", "ftx", "fty", "ftz", "ms",
                         "vn", "K", "mm", "mu", "kt"},
                        1u << PF_P | 1u << PF_MU | 1u << PF_KT, 1u << PF_P, 0, fill_pair,
                        call_pair, zero_pair};
    ntf_run(&c);
    const ntf_case c2 = {"ct_pair_force_linear_coulomb (lean)", PF_VN, 7, 1,
                         {"p", "nx", "ny", "nz", "vx", "vy", "vz", "ftx", "fty", "ftz", "ms"},
                         1u << PF_P, 0, 0, fill_pair, call_pair_lean, NULL};
    ntf_run(&c2);
}

/* ---- ct_friction_mu ------------------------------------------------------- */

static const ct_real law_c[CT_FRIC_NLAW][7] = {
    {0.3, 0, 0, 0, 0, 0, 0},
    {0.3, 0.01, 0.02, 0.001, 0.0001, 0.001, 0},
    {0, 0.001, -0.1, 0.01, -0.2, 0.2, -0.05},
    {0, 0.3, 0.2, 0.5, 0.15, 0.1, 0.5},
    {0.4, 0.2, 3, 0, 0, 0, 0}};
static int mu_law;

/* in[0] the speed, in[1] the pressure. */
static void fill_mu(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        in[0][i] = ntf_val(i, 60, 0, 1);
        in[1][i] = ntf_val(i, 61, 0, 10);
    }
}

/* Speeds for Coulomb, which reads none (the harness gives it no array). */
static ct_real zero_speed[NTF_LONG];

static int call_mu(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    const int usep = mu_law == CT_FRIC_POLY || mu_law == CT_FRIC_DARMSTAD;
    return ct_friction_mu(n, mu_law, law_c[mu_law], usep ? in[1] : NULL,
                          mu_law == CT_FRIC_COULOMB ? zero_speed : in[0], out[0]);
}

/* Every law that reads the speed (all but Coulomb) and the pressure (the
 * polynomial and Darmstad laws): the vector loops of the first two, the
 * scalar loop and vector check of the others. Coulomb reads neither. */
Test(friction, nonfinite_mu_each_input)
{
    for (mu_law = 0; mu_law < CT_FRIC_NLAW; mu_law++) {
        const int np = mu_law == CT_FRIC_POLY || mu_law == CT_FRIC_DARMSTAD ? 2
                       : mu_law == CT_FRIC_COULOMB                          ? 0
                                                                            : 1;
        const ntf_case c = {"ct_friction_mu", np, 1, 1, {"speed", "pressure"}, 0, 0, 0,
                            fill_mu, call_mu, NULL};
        ntf_run(&c);
    }
    ct_real s[3] = {(ct_real)NAN, (ct_real)INFINITY, 1}, mu[3];
    cr_assert_eq(ct_friction_mu(3, CT_FRIC_COULOMB, law_c[0], s, s, mu), CT_OK);
    cr_assert(mu[0] == (ct_real)0.3 && mu[1] == (ct_real)0.3);
    cr_assert_eq(ct_friction_mu(1, CT_FRIC_RENARD, law_c[3], s, s + 2, mu), CT_OK);
}

/* A law's value that overflows from finite inputs (CT_OK before: +inf, or
 * NaN clamped to 0), and a non-finite coefficient (read as is before). */
Test(friction, nonfinite_mu_overflow)
{
    const ct_real big = (ct_real)CTT_TOL(1e200, 1e25);
    const ct_real poly[7] = {0, 0, 0, 0, 1, 0, 0}; /* C4 p^2 */
    ct_real p[2] = {1, big}, v[2] = {0, 0}, mu[2];
    cr_assert_eq(ct_friction_mu(1, CT_FRIC_POLY, poly, p, v, mu), CT_OK);
    cr_assert_eq(ct_friction_mu(2, CT_FRIC_POLY, poly, p, v, mu), CT_ERR_NONFINITE);
    /* Exponential decay with an unchecked negative rate: exp overflows,
     * times (Fric - C1) = 0 it is NaN (clamped to 0 before). */
    const ct_real dec[7] = {0.4, 0.4, -1, 0, 0, 0, 0};
    ct_real s[2] = {1, 1000};
    cr_assert_eq(ct_friction_mu(1, CT_FRIC_EXPDECAY, dec, NULL, s, mu), CT_OK);
    cr_assert_eq(ct_friction_mu(2, CT_FRIC_EXPDECAY, dec, NULL, s, mu), CT_ERR_NONFINITE);
    ct_real bad[7] = {0.3, 0, 0, 0, 0, 0, 0};
    bad[3] = (ct_real)NAN;
    cr_assert_eq(ct_friction_mu(1, CT_FRIC_COULOMB, bad, NULL, s, mu), CT_ERR_ARG);
    bad[3] = (ct_real)INFINITY;
    cr_assert_eq(ct_friction_mu(1, CT_FRIC_POLY, bad, p, s, mu), CT_ERR_ARG);
}

/* ---- Scalars, overflows, extremes ----------------------------------------- */

/* An infinite dt was accepted, mu0 or kt0 = +inf gave NaN or infinite
 * forces; NaN (as in the arrays) and -inf count as 0. */
Test(friction, nonfinite_scalars)
{
    ct_real nx[2] = {0, 0}, ny[2] = {0, 0}, nz[2] = {1, 1}, vx[2] = {1, -1}, vy[2] = {0, 1},
            vz[2] = {0, 0}, fn[2] = {1, 2}, hx[2] = {0}, hy[2] = {0}, hz[2] = {0}, p[2] = {1e-3, 1e-3};
    const ct_real inf = (ct_real)INFINITY, nan = (ct_real)NAN;
    for (int t = 1; t <= 2; t++) {
        ctt_threads(t);
        hx[0] = hx[1] = hy[0] = hy[1] = hz[0] = hz[1] = 0;
        cr_assert_eq(ct_friction_step(2, nx, ny, nz, vx, vy, vz, fn, NULL, 0.3, NULL, 1e3, inf,
                                      1, hx, hy, hz, NULL),
                     CT_ERR_ARG);
        cr_assert_eq(ct_friction_step(2, nx, ny, nz, vx, vy, vz, fn, NULL, inf, NULL, 1e3, DT,
                                      1, hx, hy, hz, NULL),
                     CT_ERR_NONFINITE);
        cr_assert_eq(ct_friction_step(2, nx, ny, nz, vx, vy, vz, fn, NULL, 0.3, NULL, inf, DT,
                                      1, hx, hy, hz, NULL),
                     CT_ERR_NONFINITE);
        hx[0] = hx[1] = hy[0] = hy[1] = hz[0] = hz[1] = 0; /* unspecified after an error */
        cr_assert_eq(ct_friction_step(2, nx, ny, nz, vx, vy, vz, fn, NULL, nan, NULL, -inf, DT,
                                      1, hx, hy, hz, NULL),
                     CT_OK);
        cr_assert(hx[0] == 0 && hy[0] == 0 && hz[0] == 0);
        ct_real fx[2], fy[2], fz[2];
        cr_assert_eq(ct_pair_force_linear_coulomb(2, p, nx, ny, nz, vx, vy, vz, NULL, NULL,
                                                  nan, fn, NULL, 0.1, NULL, 0.3, NULL, 1e3, DT,
                                                  1, fx, fy, fz, NULL, NULL, NULL, hx, hy, hz,
                                                  NULL),
                     CT_ERR_NONFINITE);
        cr_assert_eq(ct_pair_force_linear_coulomb(2, p, nx, ny, nz, vx, vy, vz, NULL, NULL,
                                                  1e3, fn, NULL, inf, NULL, 0.3, NULL, 1e3, DT,
                                                  1, fx, fy, fz, NULL, NULL, NULL, hx, hy, hz,
                                                  NULL),
                     CT_ERR_ARG);
        cr_assert_eq(ct_pair_force_linear_coulomb(2, p, nx, ny, nz, vx, vy, vz, NULL, NULL,
                                                  1e3, fn, NULL, 0.1, NULL, inf, NULL, 1e3, DT,
                                                  1, fx, fy, fz, NULL, NULL, NULL, hx, hy, hz,
                                                  NULL),
                     CT_ERR_NONFINITE);
    }
}

/* The cone mu fn overflowing from finite inputs (NaN forces with CT_OK
 * before) is an error; a trial whose square lies between 1e300 and the
 * largest real, which gave no force before (its test was tt <= 1e300), now
 * sticks as it should; extreme finite stiffness and speed pass. */
Test(friction, nonfinite_overflow_and_extremes)
{
    ct_real nx = 0, ny = 0, nz = 1, vx = 0, vy = 0, vz = 0, hx, hy, hz, d;
    const ct_real big = (ct_real)CTT_TOL(1e200, 1e25);
    ct_real fn = big, mu = big, kt = 1;
    hx = 1, hy = hz = 0;
    cr_assert_eq(ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, &mu, 0, &kt, 0, DT, 1,
                                  &hx, &hy, &hz, &d),
                 CT_ERR_NONFINITE);
    /* |F_old| = 1e151 (single 1.8e19): its square 1e302 (3.2e38) is
     * finite, above the old test's 1e300 (3e38). */
    const ct_real h = (ct_real)CTT_TOL(1e151, 1.8e19);
    fn = h;
    mu = 2;
    hx = h;
    hy = hz = 0;
    cr_assert_eq(ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, &mu, 0, &kt, 0, DT, 1,
                                  &hx, &hy, &hz, &d),
                 CT_OK);
    cr_assert(hx == h && hy == 0 && hz == 0 && d == 0, "hx = %g", (double)hx);
    /* kt = 1e300 (single 1e30) on a slip of 1e-300 (1e-30) per unit time:
     * a trial of 1e-4, far inside the cone. */
    kt = (ct_real)CTT_TOL(1e300, 1e30);
    vx = (ct_real)CTT_TOL(1e-300, 1e-30);
    fn = 1;
    mu = (ct_real)0.5;
    hx = hy = hz = 0;
    cr_assert_eq(ct_friction_step(1, &nx, &ny, &nz, &vx, &vy, &vz, &fn, &mu, 0, &kt, 0, DT, 1,
                                  &hx, &hy, &hz, &d),
                 CT_OK);
    cr_assert_leq(ctt_rel(hx, -1e-4), CTT_TOL(1e-12, 1e-5));
}
