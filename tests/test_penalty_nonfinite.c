/*
 * test_penalty_nonfinite.c -- the normal force laws and the damping finish
 * against NaN and infinite inputs and overflows (suite "penalty",
 * docs/fuzz F15): every input array, one bad entry at a time (the harness
 * of test_nonfinite.h), the scalars, results that overflow from finite
 * inputs, and finite extreme inputs that must still pass.
 *
 * Each "each_input" test failed before F15 on its first +inf: the kernels
 * returned CT_OK whatever their inputs (an infinite force, a NaN one, or,
 * worse, none: a NaN stiffness or mass counted as 0, an infinite gap or
 * stiffness of TYPE7 gave no force, an infinite penetration the capped
 * TYPE7 force).
 */
#include "test_nonfinite.h"

#define DT ((ct_real)1e-4)
#define VISS ((ct_real)0.3)

/* ---- ct_penalty_linear, with every state (blending, Inacti subtract) ---- */

enum { LI_P, LI_VN, LI_K, LI_P0, LI_PPREV, LI_FCAP, LI_QJ, LI_N };

static void fill_linear(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        in[LI_P][i] = ntf_pen(i);
        in[LI_VN][i] = ntf_val(i, 1, -1, 1);
        in[LI_K][i] = ntf_val(i, 2, 1e3, 2e3);
        in[LI_P0][i] = ntf_val(i, 3, 0, 0.2e-3);
        in[LI_PPREV][i] = ntf_val(i, 4, 0, 1e-3);
        /* Some pairs blended: a plateau of 0.1 from a jump to 2e-3. */
        in[LI_FCAP][i] = i % 5 == 0 ? (ct_real)0.1 : (ct_real)CT_BLEND_NONE;
        in[LI_QJ][i] = i % 5 == 0 ? (ct_real)2e-3 : 0;
    }
}

static int call_linear(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_penalty_linear(n, in[LI_P], in[LI_VN], in[LI_K], DT, in[LI_P0], in[LI_PPREV],
                             in[LI_FCAP], in[LI_QJ], out[0], out[1]);
}

static int zero2(ct_real **in, ct_real **out, ct_idx k)
{
    (void)in;
    return ntf_all_zero(out, 2, 1, k);
}

Test(penalty, nonfinite_linear_each_input)
{
    const ntf_case c = {"ct_penalty_linear", LI_N, 2, 1,
                        {"p", "vn", "K", "p0", "p_prev", "fcap", "qjump"},
                        1u << LI_P, 1u << LI_P, 0, fill_linear, call_linear, zero2};
    ntf_run(&c);
}

/* ---- ct_penalty_type7 ---------------------------------------------------- */

static int32_t flag7[NTF_LONG];

static void fill_type7(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        in[0][i] = ntf_pen(i);
        in[1][i] = ntf_val(i, 5, 2e-3, 3e-3); /* gap */
        in[2][i] = ntf_val(i, 6, 1e3, 2e3);   /* K0 */
    }
}

static int call_type7(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_penalty_type7(n, in[0], in[1], in[2], out[0], out[1], out[2], flag7);
}

static int zero3(ct_real **in, ct_real **out, ct_idx k)
{
    (void)in;
    return ntf_all_zero(out, 3, 1, k);
}

/* A NaN or negative penetration or gap is no contact (the header); -inf
 * too. An infinite p, which the law capped at F_max with CT_OK, is an
 * error; a penetration beyond the gap is not (the finite cap). */
Test(penalty, nonfinite_type7_each_input)
{
    const ntf_case c = {"ct_penalty_type7", 3, 3, 1, {"p", "g", "K0"}, 3u, 3u, 0,
                        fill_type7, call_type7, zero3};
    ntf_run(&c);
    ct_real p = 5, g = 1, K0 = 10, f, kt, e;
    int32_t fl;
    cr_assert_eq(ct_penalty_type7(1, &p, &g, &K0, &f, &kt, &e, &fl), CT_OK);
    cr_assert(fl == 1 && isfinite(f) && isfinite(e));
}

/* ---- ct_penalty_type6 ---------------------------------------------------- */

static const ct_real cx6[3] = {0, (ct_real)1e-3, (ct_real)2e-3};
static const ct_real cy6[3] = {0, 10, 50};

static void fill_type6(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++)
        in[0][i] = ntf_pen(i);
}

static int call_type6(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    ct_real pm, ft, kc;
    return ct_penalty_type6(n, in[0], 3, cx6, cy6, out[0], &pm, &ft, &kc, d);
}

static int zero1(ct_real **in, ct_real **out, ct_idx k)
{
    (void)in;
    return ntf_all_zero(out, 1, 1, k);
}

/* +inf, which made p_max infinite (forces of infinity times 0, NaN), names
 * its pair. */
Test(penalty, nonfinite_type6_each_input)
{
    const ntf_case c = {"ct_penalty_type6", 1, 1, 1, {"p"}, 1u, 1u, 1,
                        fill_type6, call_type6, zero1};
    ntf_run(&c);
}

/* ---- ct_normal_finish ---------------------------------------------------- */

enum { FI_P, FI_FEL, FI_KD, FI_VN, FI_MS, FI_MM, FI_NX, FI_NY, FI_NZ, FI_N };

static void fill_finish(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        ct_real p = ntf_pen(i), k = ntf_val(i, 7, 1e3, 2e3);
        in[FI_P][i] = p;
        in[FI_FEL][i] = p > 0 ? k * p : 0;
        in[FI_KD][i] = k;
        in[FI_VN][i] = ntf_val(i, 8, -1, 1);
        in[FI_MS][i] = ntf_val(i, 9, 0.5, 1.5);
        in[FI_MM][i] = ntf_val(i, 10, 0.5, 1.5);
        ntf_normal(i, 11, &in[FI_NX][i], &in[FI_NY][i], &in[FI_NZ][i]);
    }
}

static int call_finish(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_normal_finish(n, in[FI_P], in[FI_FEL], in[FI_KD], in[FI_VN], in[FI_MS],
                            in[FI_MM], VISS, DT, in[FI_NX], in[FI_NY], in[FI_NZ], out[0],
                            out[1], out[2], out[3], out[4]);
}

/* The contact cycle's call: no segment mass, no dissipation. */
static int call_finish_cycle(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_normal_finish(n, in[FI_P], in[FI_FEL], in[FI_KD], in[FI_VN], in[FI_MS], NULL,
                            VISS, DT, in[FI_NX], in[FI_NY], in[FI_NZ], out[0], out[1], out[2],
                            out[3], NULL);
}

static int zero5(ct_real **in, ct_real **out, ct_idx k)
{
    (void)in;
    return ntf_all_zero(out, 5, 1, k);
}

Test(penalty, nonfinite_finish_each_input)
{
    const ntf_case c = {"ct_normal_finish", FI_N, 5, 1,
                        {"p", "fel", "kd", "vn", "ms", "mm", "nx", "ny", "nz"},
                        1u << FI_P, 1u << FI_P, 0, fill_finish, call_finish, zero5};
    ntf_run(&c);
    /* Without mm, which is then not read: the last input left out. */
    const ntf_case c2 = {"ct_normal_finish (cycle)", FI_MM, 4, 1,
                         {"p", "fel", "kd", "vn", "ms"}, 1u << FI_P, 1u << FI_P, 0,
                         fill_finish, call_finish_cycle, zero5};
    ntf_run(&c2);
}

/* ---- ct_normal_force ----------------------------------------------------- */

enum { NF_P, NF_NX, NF_NY, NF_NZ, NF_VN, NF_MS, NF_K, NF_MM, NF_N };

static void fill_normal(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        in[NF_P][i] = ntf_pen(i);
        ntf_normal(i, 12, &in[NF_NX][i], &in[NF_NY][i], &in[NF_NZ][i]);
        in[NF_VN][i] = ntf_val(i, 15, -1, 1);
        in[NF_MS][i] = ntf_val(i, 16, 0.5, 1.5);
        in[NF_K][i] = ntf_val(i, 17, 1e3, 2e3);
        in[NF_MM][i] = ntf_val(i, 18, 0.5, 1.5);
    }
}

static int call_normal(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_normal_force(n, in[NF_P], in[NF_NX], in[NF_NY], in[NF_NZ], in[NF_VN], in[NF_K],
                           0, in[NF_MS], in[NF_MM], VISS, DT, out[0], out[1], out[2], out[3],
                           out[4], out[5]);
}

/* The contact cycle's linear call: the scalar K0, no segment mass, no
 * energy, no dissipation. */
static int call_normal_cycle(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_normal_force(n, in[NF_P], in[NF_NX], in[NF_NY], in[NF_NZ], in[NF_VN], NULL,
                           (ct_real)1.5e3, in[NF_MS], NULL, VISS, DT, out[0], out[1], out[2],
                           out[3], NULL, NULL);
}

static int zero6(ct_real **in, ct_real **out, ct_idx k)
{
    (void)in;
    return ntf_all_zero(out, 6, 1, k);
}

static int zero4(ct_real **in, ct_real **out, ct_idx k)
{
    (void)in;
    return ntf_all_zero(out, 4, 1, k);
}

Test(penalty, nonfinite_normal_force_each_input)
{
    const ntf_case c = {"ct_normal_force", NF_N, 6, 1,
                        {"p", "nx", "ny", "nz", "vn", "ms", "K", "mm"},
                        1u << NF_P, 1u << NF_P, 0, fill_normal, call_normal, zero6};
    ntf_run(&c);
    const ntf_case c2 = {"ct_normal_force (cycle)", NF_K, 4, 1,
                         {"p", "nx", "ny", "nz", "vn", "ms"}, 1u << NF_P, 1u << NF_P, 0,
                         fill_normal, call_normal_cycle, zero4};
    ntf_run(&c2);
}

/* ---- Scalars -------------------------------------------------------------- */

/* dt and viss NaN or infinite are argument errors, K0 (standing for K) a
 * non-finite value: an infinite dt, and a NaN or infinite viss or K0, were
 * accepted (NaN viss as no damping, +inf K0 gave infinite forces). */
Test(penalty, nonfinite_scalars)
{
    ct_real p[2] = {1e-3, 2e-3}, nx[2] = {0, 0}, ny[2] = {0, 0}, nz[2] = {1, 1};
    ct_real vn[2] = {-1, 1}, ms[2] = {1, 1}, K[2] = {1e3, 1e3}, fel[2] = {1, 2};
    ct_real fx[2], fy[2], fz[2], fn[2];
    const ct_real inf = (ct_real)INFINITY, nan = (ct_real)NAN;
    for (int t = 1; t <= 2; t++) {
        ctt_threads(t);
        cr_assert_eq(ct_normal_force(2, p, nx, ny, nz, vn, K, 0, ms, NULL, VISS, inf, fx, fy,
                                     fz, fn, NULL, NULL),
                     CT_ERR_ARG);
        cr_assert_eq(ct_normal_force(2, p, nx, ny, nz, vn, K, 0, ms, NULL, nan, DT, fx, fy,
                                     fz, fn, NULL, NULL),
                     CT_ERR_ARG);
        cr_assert_eq(ct_normal_force(2, p, nx, ny, nz, vn, K, 0, ms, NULL, inf, DT, fx, fy,
                                     fz, fn, NULL, NULL),
                     CT_ERR_ARG);
        cr_assert_eq(ct_normal_force(2, p, nx, ny, nz, vn, NULL, inf, ms, NULL, VISS, DT, fx,
                                     fy, fz, fn, NULL, NULL),
                     CT_ERR_NONFINITE);
        cr_assert_eq(ct_normal_force(2, p, nx, ny, nz, vn, NULL, -inf, ms, NULL, VISS, DT, fx,
                                     fy, fz, fn, NULL, NULL),
                     CT_ERR_NONFINITE);
        cr_assert_eq(ct_normal_force(2, p, nx, ny, nz, vn, NULL, nan, ms, NULL, VISS, DT, fx,
                                     fy, fz, fn, NULL, NULL),
                     CT_ERR_NONFINITE);
        /* K0 is not read when K is given; a negative viss is no damping. */
        cr_assert_eq(ct_normal_force(2, p, nx, ny, nz, vn, K, nan, ms, NULL, -1, DT, fx, fy,
                                     fz, fn, NULL, NULL),
                     CT_OK);
        cr_assert_eq(ct_normal_finish(2, p, fel, K, vn, ms, NULL, VISS, inf, nx, ny, nz, fn,
                                      fx, fy, fz, NULL),
                     CT_ERR_ARG);
        cr_assert_eq(ct_normal_finish(2, p, fel, K, vn, ms, NULL, nan, DT, nx, ny, nz, fn, fx,
                                      fy, fz, NULL),
                     CT_ERR_ARG);
        cr_assert_eq(ct_penalty_linear(2, p, NULL, K, inf, NULL, NULL, NULL, NULL, fel, NULL),
                     CT_ERR_ARG);
        /* Without blending, vn is not read. */
        ct_real vbad[2] = {nan, inf};
        cr_assert_eq(ct_penalty_linear(2, p, vbad, K, DT, NULL, NULL, NULL, NULL, fel, NULL),
                     CT_OK);
    }
}

/* ---- Overflows and extreme finite inputs ---------------------------------- */

/* The largest finite stiffness and penetration scales of each precision. */
#define BIGK CTT_TOL(1e300, 1e30)
#define TINYP CTT_TOL(1e-300, 1e-30)

/* A force that overflows from finite inputs is an error (CT_OK with +inf
 * before); extreme finite inputs whose results are finite pass, with the
 * right force. Without damping, 2 K m overflowing (K = 1e300, m = 1e10)
 * gave a zero force with CT_OK before (0 times its infinite root was NaN,
 * clamped to 0): that is what fails first on the old code. */
Test(penalty, nonfinite_overflow_and_extremes)
{
    ct_real nx = 0, ny = 0, nz = 1, vn = -1, m = (ct_real)1e10, fx, fy, fz, fn, e, d;
    /* K p = 1: finite, without damping, whatever 2 K m. */
    ct_real p = (ct_real)TINYP, K = (ct_real)BIGK;
    cr_assert_eq(ct_normal_force(1, &p, &nx, &ny, &nz, &vn, &K, 0, &m, NULL, 0, DT, &fx, &fy,
                                 &fz, &fn, &e, &d),
                 CT_OK);
    cr_assert_leq(ctt_rel(fn, (double)K * (double)p), CTT_TOL(1e-15, 1e-6));
    cr_assert_eq(fz, fn);
    /* K p beyond the largest real. */
    ct_real pbig = (ct_real)1e10;
    cr_assert_eq(ct_normal_force(1, &pbig, &nx, &ny, &nz, &vn, &K, 0, &m, NULL, 0, DT, &fx,
                                 &fy, &fz, &fn, NULL, NULL),
                 CT_ERR_NONFINITE);
    cr_assert_eq(ct_penalty_linear(1, &pbig, NULL, &K, DT, NULL, NULL, NULL, NULL, &fn, NULL),
                 CT_ERR_NONFINITE);
    /* p = +inf with K = 0: K p is NaN, which the clamp of the force to
     * >= 0 must keep (it made it 0). */
    ct_real pinf = (ct_real)INFINITY, K0z = 0;
    cr_assert_eq(ct_normal_force(1, &pinf, &nx, &ny, &nz, &vn, &K0z, 0, &m, NULL, VISS, DT, &fx,
                                 &fy, &fz, &fn, NULL, NULL),
                 CT_ERR_NONFINITE);
    /* A finite force whose energy K p^2 / 2 overflows: not an error, the
     * energy is +inf (diagnostics are not checked, ct_force.h). */
    ct_real K1 = 1, pe = (ct_real)CTT_TOL(1e200, 1e25);
    cr_assert_eq(ct_penalty_linear(1, &pe, NULL, &K1, DT, NULL, NULL, NULL, NULL, &fn, &e),
                 CT_OK);
    cr_assert(fn == pe && e == (ct_real)INFINITY);
    cr_assert_eq(ct_normal_force(1, &pe, &nx, &ny, &nz, &vn, &K1, 0, &m, NULL, 0, DT, &fx, &fy,
                                 &fz, &fn, &e, NULL),
                 CT_OK);
    cr_assert(fz == pe && e == (ct_real)INFINITY);
    /* TYPE7: K0 g x/(1 - x) = K0 g = 2 at x = 1/2; F_max = 999 K0 g
     * overflowing (CT_OK with +inf before). */
    ct_real g = (ct_real)(2 * TINYP), K0 = (ct_real)BIGK, f7, kt7;
    int32_t fl;
    cr_assert_eq(ct_penalty_type7(1, &p, &g, &K0, &f7, &kt7, NULL, &fl), CT_OK);
    cr_assert_leq(ctt_rel(f7, 2.0), CTT_TOL(1e-14, 1e-5));
    ct_real gb = (ct_real)1e10, pb = (ct_real)2e10;
    cr_assert_eq(ct_penalty_type7(1, &pb, &gb, &K0, &f7, NULL, NULL, &fl), CT_ERR_NONFINITE);
    /* The damping finish: a damper force c vn beyond the largest real on an
     * approaching node (c = viss sqrt(2 K m) about 4e149, vn = -1e300). */
    ct_real fel = 1, m1 = 1, vfast = -(ct_real)CTT_TOL(1e300, 1e36);
    cr_assert_eq(ct_normal_finish(1, &p, &fel, &K, &vfast, &m1, NULL, VISS, DT, &nx, &ny, &nz,
                                  &fn, &fx, &fy, &fz, NULL),
                 CT_ERR_NONFINITE);
}

/* TYPE6: a curve steep enough that f(p_max) overflows (CT_OK with infinite
 * forces before), reported at the first pair of the largest penetration. */
Test(penalty, nonfinite_type6_overflow)
{
    const ct_real x[2] = {0, (ct_real)CTT_TOL(1e-200, 1e-20)};
    const ct_real y[2] = {0, (ct_real)CTT_TOL(1e200, 1e20)};
    ct_real p[5] = {0.5, 1, -0.2, 2, 2}, f[5], pm, ft, kc;
    ct_diag d;
    cr_assert_eq(ct_penalty_type6(5, p, 2, x, y, f, &pm, &ft, &kc, &d), CT_ERR_NONFINITE);
    cr_assert_eq(d.index, 3);
    /* A huge force on a tiny largest penetration: f / p_max, the scale of
     * the forces, overflows (the forces were +inf, or NaN). */
    const ct_real yb = (ct_real)CTT_TOL(1e300, 1e30);
    const ct_real x2[2] = {0, 1}, y2[2] = {yb, yb};
    ct_real q[3] = {-1, (ct_real)CTT_TOL(1e-300, 1e-30), (ct_real)CTT_TOL(1e-300, 1e-30)};
    cr_assert_eq(ct_penalty_type6(3, q, 2, x2, y2, f, &pm, &ft, NULL, &d), CT_ERR_NONFINITE);
    cr_assert_eq(d.index, 1);
    /* The same force on a penetration of 1: finite, the forces sum to it. */
    q[1] = q[2] = (ct_real)0.5;
    cr_assert_eq(ct_penalty_type6(3, q, 2, x2, y2, f, &pm, &ft, &kc, &d), CT_OK);
    cr_assert(f[1] == yb / 2 && f[2] == yb / 2 && kc == yb / (ct_real)0.5);
}
