/*
 * pair_force_body.h -- the per-pair arithmetic of the normal force and of the
 * Coulomb friction step (private to kernels/penalty.c, friction.c and
 * pair_force.c; the formulas are documented in ct_force.h and ct_friction.h).
 *
 * ct_normal_force, ct_friction_step and the fused ct_pair_force_linear_coulomb
 * all call these functions, so the fused kernel is bit-identical to the
 * two-kernel composition by construction (tests/test_friction.c checks it
 * with memcmp). The functions are always inlined into branch-free SIMD
 * loops: every select is written as a ternary on a floating-point compare,
 * and divisions and square roots take safe arguments, so that gcc and clang
 * if-convert and vectorise the loops that call them.
 */
#ifndef CT_PAIR_FORCE_BODY_H
#define CT_PAIR_FORCE_BODY_H

#include "ct_internal.h"

/* "omp simd" on loops that call sqrt: they vectorise only when sqrt need
 * not set errno (-fno-math-errno, which defines __NO_MATH_ERRNO__); with
 * errno semantics gcc and clang cannot vectorise them and clang would warn
 * that the requested vectorisation failed. */
#if defined(__NO_MATH_ERRNO__)
#define CTI_SIMD_SQRT _Pragma("omp simd")
#define CTI_SIMD_SQRT_BAD _Pragma("omp simd reduction(+ : bad)")
#else
#define CTI_SIMD_SQRT
#define CTI_SIMD_SQRT_BAD
#endif
/* CTI_SIMD_SQRT_BAD: the same, with the witness sum `bad` of the block's
 * non-finite check (ct_internal.h) as a reduction. */

/* Loops shorter than this run on one thread. */
#define CTI_PAR_MIN 8192

/* The case labels 0 .. 2^k - 1 of a switch over a variant number, each
 * expanded by the caller's macro C(V). */
#define CTI_CASES4(C, o) C((o) + 0) C((o) + 1) C((o) + 2) C((o) + 3)
#define CTI_CASES8(C) CTI_CASES4(C, 0) CTI_CASES4(C, 4)
#define CTI_CASES16(C) CTI_CASES8(C) CTI_CASES4(C, 8) CTI_CASES4(C, 12)
#define CTI_CASES32(C) CTI_CASES16(C) CTI_CASES4(C, 16) CTI_CASES4(C, 20) \
    CTI_CASES4(C, 24) CTI_CASES4(C, 28)

/* Block b of blocks of bs pairs out of n: the range [*i0, *i1). */
static inline void cti_block_range(int64_t b, int64_t bs, int64_t n, int64_t *i0, int64_t *i1)
{
    int64_t lo = b * bs, hi = lo + bs;
    *i0 = lo;
    *i1 = hi < n ? hi : n;
}

/* The scalar parameters of the force and friction kernels: a step dt
 * finite and >= 0, a damping ratio finite (<= 0: no damping). NaN or
 * infinite ones are argument errors (CT_ERR_ARG), as a negative step was. */
static inline int cti_step_ok(ct_real dt) { return dt >= 0 && dt <= CTI_REAL_MAX; }
static inline int cti_viss_ok(ct_real viss) { return !CTI_NONFINITE(viss); }

/* The reduced mass of the damper: without a segment mass (mm <= 0),
 * ms / (1 + ms/inf) = ms (branch-free). */
static inline ct_real cti_reduced_mass(ct_real ms, ct_real mm)
{
    ct_real m2 = mm > 0 ? mm : (ct_real)INFINITY;
    return ms / ((ct_real)1 + ms / m2);
}

/* The linear penalty with normal damping for one pair: penetration p,
 * stiffness k, (reduced) mass m, damping ratio vs >= 0, normal velocity w,
 * step dt. Returns the normal force fn >= 0 (zero out of contact); *e gets
 * the stored energy and *d the damping dissipation of the step (>= 0).
 * Non-finite check (ct_internal.h): the callers' witness sums take the
 * force vector fn n, which is NaN or infinite whenever a NaN or an
 * overflow reaches fn (the clamp to >= 0 keeps a NaN) and whenever p is
 * +inf (k p is infinite, or NaN for k = 0; a NaN or negative p, -inf too,
 * is no contact by the convention of ct_force.h); and the terms of what
 * may not reach it (a pair out of contact, a damper that pushes fn to 0):
 * k (when per pair: a scalar is checked once), m and w. The energy and the
 * dissipation are not checked: from finite inputs they are finite or
 * +inf, never NaN. */
static inline __attribute__((always_inline)) ct_real
cti_normal_pair(ct_real p, ct_real k, ct_real m, ct_real vs, ct_real w, ct_real dt,
                ct_real *e, ct_real *d)
{
    ct_real q = p > 0 ? p : 0;
    k = k > 0 ? k : 0;
    ct_real fe = k * q;
    ct_real a = (ct_real)2 * k * m;
    a = a > 0 ? a : 0;
    /* Without damping c is 0 even where 2 k m overflows (0 times its
     * infinite root was NaN, and the force with it). */
    ct_real c = vs * CTI_SQRT(a);
    c = vs > 0 ? c : 0;
    ct_real ft = fe - c * w;
    /* Two selects, not (ft > 0 && q > 0): gcc 12 turns the && into a
     * select on a bool that it cannot vectorise. The first keeps a NaN
     * (ft is never -0: fe >= +0), so that an overflow is seen. */
    ft = ft < 0 ? 0 : ft;
    ft = q > 0 ? ft : 0;
    *e = (ct_real)0.5 * fe * q;
    ct_real dd = (fe - ft) * w * dt;
    *d = dd > 0 ? dd : 0;
    return ft;
}

/* The Coulomb friction step for one pair: unit normal n, relative velocity
 * v, normal force fn, friction coefficient mu, tangential stiffness kt,
 * step dt, filter factor alpha in (0, 1] (applied when filt is set). On
 * entry (*g0, *g1, *g2) is the previous tangential force, on return the new
 * one (elastic predictor, return to the cone mu fn, optional filter).
 * Returns the friction dissipation of the step (>= 0).
 * Non-finite check (ct_internal.h): the step's terms are added to the
 * caller's witness sum *nf. Two terms cover every input: fn, mu and kt count as 0 when NaN or negative (-inf too), and
 * +inf in fn or mu makes the cone mu fn infinite or NaN (0 times
 * infinity); every other input (n, v, the old force) and +inf in kt reach
 * the squared trial tt whatever the stiffness and the step (0 times an
 * infinite slip is NaN), so tt's term covers them and the trial's
 * overflow. The filtered force's square has a term of its own (it may
 * overflow where the trial does not); the dissipation is not checked (from
 * finite inputs it is finite or +inf). */
static inline __attribute__((always_inline)) ct_real
cti_friction_pair(ct_real n0, ct_real n1, ct_real n2, ct_real v0, ct_real v1, ct_real v2,
                  ct_real fn, ct_real mu, ct_real kt, ct_real dt, ct_real alpha,
                  const int filt, ct_real *g0_, ct_real *g1_, ct_real *g2_, ct_real *nf)
{
    const ct_real beta = (ct_real)1 - alpha;
    ct_real f = fn > 0 ? fn : 0;
    ct_real m = mu > 0 ? mu : 0;
    ct_real k = kt > 0 ? kt : 0;
    ct_real lim = m * f;
    /* Old force, rotated into the current tangent plane by projection. */
    ct_real o0 = *g0_, o1 = *g1_, o2 = *g2_;
    ct_real on = o0 * n0 + o1 * n1 + o2 * n2;
    o0 -= on * n0;
    o1 -= on * n1;
    o2 -= on * n2;
    /* Tangential slip velocity and the elastic trial. */
    ct_real vnn = v0 * n0 + v1 * n1 + v2 * n2;
    ct_real kd = k * dt;
    ct_real t0 = o0 - kd * (v0 - vnn * n0);
    ct_real t1 = o1 - kd * (v1 - vnn * n1);
    ct_real t2 = o2 - kd * (v2 - vnn * n2);
    ct_real tt = t0 * t0 + t1 * t1 + t2 * t2;
    *nf = cti_nf_add(cti_nf_add(*nf, lim), tt);
    tt = tt > 0 ? tt : 0; /* lets the compiler drop the errno path of sqrt */
    ct_real tn = CTI_SQRT(tt);
    /* Return to the cone along the trial direction. (Divisions are
     * unconditional, on safe denominators, so that the loop if-converts and
     * vectorises.) */
    ct_real den = tn > lim ? tn : lim;
    ct_real rq = lim / (den > 0 ? den : (ct_real)1);
    ct_real r = den > 0 ? rq : (ct_real)1;
    ct_real g0 = r * t0, g1 = r * t1, g2 = r * t2;
    /* |g| = r |t| (r >= 0): its magnitude without a second square root
     * at the end of the pair's longest chain (sqrt of the trial, the
     * division, then that square root: the loop waited on it). */
    ct_real gm = r * tn;
    if (filt) {
        g0 = alpha * g0 + beta * o0;
        g1 = alpha * g1 + beta * o1;
        g2 = alpha * g2 + beta * o2;
        ct_real gg = g0 * g0 + g1 * g1 + g2 * g2;
        *nf = cti_nf_add(*nf, gg); /* the filtered force's square may overflow */
        gg = gg > 0 ? gg : 0;
        ct_real gn = CTI_SQRT(gg);
        ct_real gd = gn > lim ? gn : lim;
        ct_real sq = lim / (gd > 0 ? gd : (ct_real)1);
        ct_real s = gd > 0 ? sq : (ct_real)1;
        g0 *= s;
        g1 *= s;
        g2 *= s;
        gm = s * gn;
    }
    ct_real slip = tn - lim;
    ct_real slq = slip / (k > 0 ? k : (ct_real)1);
    slip = (slip > 0 && k > 0) ? slq : 0;
    /* Out of contact: no force. (A NaN or an overflow in the trial is the
     * check's business: it gave no force, with CT_OK.) */
    g0 = f > 0 ? g0 : 0;
    g1 = f > 0 ? g1 : 0;
    g2 = f > 0 ? g2 : 0;
    *g0_ = g0;
    *g1_ = g1;
    *g2_ = g2;
    gm = f > 0 ? gm : 0;
    ct_real d = gm * slip;
    return d > 0 ? d : 0;
}

#endif /* CT_PAIR_FORCE_BODY_H */
