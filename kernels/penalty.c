/*
 * penalty.c -- normal contact force laws: linear penalty with TYPE24
 * stiffness blending and initial-penetration handling, the TYPE7 nonlinear
 * law, the TYPE6 user curve, normal damping, and the fused linear fast path
 * (DESIGN.md section 7). The formulas are documented in ct_force.h.
 */
#include "pair_force_body.h"

/* Blocks of the deterministic sums (fixed: the order depends on n only). */
#define CTI_SUM_BLOCKS 64

/* The sum of a[lo, hi) (of its positive values only). The vector
 * reduction order is fixed by the compiled code, not by the thread count. */
static double cti_sum_block(const ct_real *restrict a, int64_t lo, int64_t hi,
                            int positive_only)
{
    double s = 0;
    if (positive_only) {
#pragma omp simd reduction(+ : s)
        for (int64_t i = lo; i < hi; i++)
            s += a[i] > 0 ? (double)a[i] : 0.0;
    } else {
#pragma omp simd reduction(+ : s)
        for (int64_t i = lo; i < hi; i++)
            s += (double)a[i];
    }
    return s;
}

static double cti_sum_blocks(ct_idx n, const ct_real *restrict a, int positive_only)
{
    double part[CTI_SUM_BLOCKS];
    CTI_PAR_FOR(n > CTI_PAR_MIN, (schedule(static)),
    for (int b = 0; b < CTI_SUM_BLOCKS; b++) {
        int64_t lo = (int64_t)n * b / CTI_SUM_BLOCKS, hi = (int64_t)n * (b + 1) / CTI_SUM_BLOCKS;
        part[b] = cti_sum_block(a, lo, hi, positive_only);
    });
    double s = 0;
    for (int b = 0; b < CTI_SUM_BLOCKS; b++)
        s += part[b];
    return s;
}

double ct_sum_ordered(ct_idx n, const ct_real *a)
{
    if (n <= 0 || !a)
        return 0;
    return cti_sum_blocks(n, a, 0);
}

/* ---- Linear law with blending and initial penetration ------------------- */

/* The blended law with cap Fc >= 0 set at the jump penetration qj
 * (ct_force.h): F = K q up to qc = Fc/K, then Fc up to qj, then
 * Fc + K (q - qj). Force and stored energy at q >= 0, K > 0; c < 0 means
 * not blended (F = K q). */
static inline void cti_blend_law(ct_real q, ct_real K, ct_real c, ct_real qj, ct_real *f,
                                 ct_real *e)
{
    ct_real lin_f = K * q, lin_e = (ct_real)0.5 * K * q * q;
    ct_real qc = c / K;
    ct_real ej = c * qj - c * qc * (ct_real)0.5; /* E(qj) = Fc qj - Fc^2/(2K) */
    ct_real dq = q - qj;
    if (c < 0 || q <= qc) {
        *f = lin_f;
        *e = lin_e;
    } else if (dq <= 0) {
        *f = c;
        *e = c * q - c * qc * (ct_real)0.5;
    } else {
        *f = c + K * dq;
        *e = ej + c * dq + (ct_real)0.5 * K * dq * dq;
    }
}

int ct_penalty_linear(ct_idx npair, const ct_real *p, const ct_real *vn, const ct_real *K,
                      ct_real dt, ct_real *p0, ct_real *p_prev, ct_real *fcap,
                      ct_real *qjump, ct_real *fel, ct_real *energy)
{
    int blend = p_prev != NULL;
    if (npair < 0 || !p || !K || !fel || (!p_prev) != (!fcap) || (!p_prev) != (!qjump) ||
        (blend && !vn) || !cti_step_ok(dt))
        return CT_ERR_ARG;
    const ct_real *restrict pp_ = p, *restrict v = vn, *restrict kk_ = K;
    ct_real *restrict q0 = p0, *restrict pprev = p_prev, *restrict fc = fcap,
                      *restrict qj_ = qjump, *restrict f = fel, *restrict en = energy;
    int bad = 0;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(| : bad)),
    for (ct_idx i = 0; i < npair; i++) {
        /* The witness sum of the pair's checked values (ct_internal.h):
         * K and the states read NaN or infinite, the force and the states
         * written NaN or infinite (which a p of +inf makes so: K p is
         * infinite, or NaN for K = 0; a NaN or negative p, -inf too, is no
         * contact). */
        ct_real nf = CTI_NF(kk_[i]);
        ct_real kk = kk_[i] > 0 ? kk_[i] : 0; /* negative: no force */
        ct_real q = pp_[i] > 0 ? pp_[i] : 0;
        if (q0) {
            /* Inacti "subtract": p0 = min(p0, p), force on p - p0. */
            nf += CTI_NF(q0[i]);
            ct_real a = q0[i] < q ? q0[i] : q;
            a = a > 0 ? a : 0;
            q0[i] = a;
            q -= a;
        }
        ct_real fi = kk * q, ei = (ct_real)0.5 * kk * q * q;
        if (blend) {
            nf += (CTI_NF(fc[i]) + CTI_NF(qj_[i])) + (CTI_NF(pprev[i]) + CTI_NF(v[i]));
            ct_real c = fc[i], qj = qj_[i], prev = pprev[i] > 0 ? pprev[i] : 0;
            ct_real d = CTI_FABS(v[i]) * dt;
            d = d > 0 ? d : 0;
            if (q > 0 && kk > 0) {
                if (q - prev > (ct_real)CT_BLEND_SLACK * d) {
                    /* A jump: the stored energy may not exceed what the law
                     * held at the motion-explained penetration prev + d. */
                    ct_real fa, ea;
                    cti_blend_law(prev + d, kk, c, qj, &fa, &ea);
                    ct_real rest = q * q - (ct_real)2 * ea / kk;
                    if (rest > 0) {
                        c = (ct_real)2 * ea / (q + CTI_SQRT(rest));
                        qj = q;
                    } else {
                        c = CT_BLEND_NONE;
                    }
                }
                if (c >= 0 && kk * q <= c)
                    c = CT_BLEND_NONE; /* back on the linear branch */
            } else {
                c = CT_BLEND_NONE; /* separated: the full stiffness returns */
            }
            if (c >= 0)
                cti_blend_law(q, kk, c, qj, &fi, &ei);
            nf += CTI_NF(c) + CTI_NF(d);
            fc[i] = c;
            qj_[i] = c >= 0 ? qj : 0;
            pprev[i] = q;
        }
        f[i] = fi;
        if (en)
            en[i] = ei;
        nf += CTI_NF(fi); /* the energy is not checked (ct_force.h) */
        bad |= CTI_NONFINITE(nf);
    });
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

int ct_initial_penetration(ct_idx npair, int mode, const ct_real *p_init, ct_real pen_max,
                           ct_real *p0, int32_t *active)
{
    if (npair < 0 || !p_init || !p0 || !active ||
        (mode != CT_INACTI_IGNORE && mode != CT_INACTI_SUBTRACT))
        return CT_ERR_ARG;
    int ndead = 0;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(+ : ndead)),
    for (ct_idx i = 0; i < npair; i++) {
        ct_real q = p_init[i] > 0 ? p_init[i] : 0;
        int dead = pen_max > 0 && q > pen_max;
        active[i] = !dead;
        p0[i] = (mode == CT_INACTI_SUBTRACT && !dead) ? q : 0;
        ndead += dead;
    });
    return ndead;
}

/* ---- TYPE7 ---------------------------------------------------------------- */

/* r - 1 - ln r with r = 1 - x, 0 <= x < 1: the series sum_{n>=2} x^n/n for
 * small x (the closed form cancels there), -x - log1p(-x) otherwise. */
static inline ct_real cti_type7_series(ct_real x)
{
    ct_real s = (ct_real)(1.0 / 15);
    for (int k = 14; k >= 2; k--)
        s = (ct_real)1 / (ct_real)k + x * s;
    return s;
}

static inline ct_real cti_type7_phi(ct_real x)
{
    if (x < (ct_real)(1.0 / 32))
        return x * x * cti_type7_series(x);
    return -x - CTI_LOG1P(-x);
}

/* K0 g^2 phi(x), x = p / g < 1 - RMIN: as K0 g g phi(x), and where g^2
 * overflows (g above about 1.3e154, single 1.8e19) while the energy does
 * not, as K0 p^2 s(x) (phi(x) = x^2 s(x) below x = 1/32; above it p is as
 * large as g / 32 and the energy overflows itself). */
static inline ct_real cti_type7_e(ct_real K0, ct_real g, ct_real p, ct_real x)
{
    ct_real e = K0 * g * g * cti_type7_phi(x);
    if (!(e <= CTI_HUGE) && x < (ct_real)(1.0 / 32))
        e = K0 * (p * p) * cti_type7_series(x);
    return e;
}

ct_real ct_type7_energy(ct_real K0, ct_real g, ct_real p)
{
    if (!(K0 > 0) || !(g > 0) || !(p > 0) || !(g <= CTI_HUGE) || !(K0 <= CTI_HUGE))
        return 0;
    ct_real x = p / g, xc = (ct_real)1 - (ct_real)CT_TYPE7_RMIN;
    if (x < xc)
        return cti_type7_e(K0, g, p, x);
    /* The capped force as ct_penalty_type7 computes it (1 - xc is not
     * RMIN in single precision: 4.7e-5 apart), so the energy past the
     * point is the work of the force the kernel gives. */
    ct_real fmax = K0 * g * xc / ((ct_real)1 - xc);
    ct_real xe = x < 1 ? x : 1;
    return K0 * g * g * cti_type7_phi(xc) + fmax * g * (xe - xc);
}

/* One block [i0, i1) of ct_penalty_type7, inlined with constant has_*
 * flags: force, tangent and flag in a branch-free SIMD loop; then, when
 * asked for, the energy in a scalar loop (gcc cannot vectorise its series
 * and log1p) over the pairs in contact only: the others' energy is an
 * exact zero, as the formula gives them. Returns 1 when a checked value of
 * the block is NaN or infinite (ct_internal.h): p or g infinite, K0 NaN or
 * infinite, or an output. */
static inline __attribute__((always_inline)) int
cti_type7_block(int64_t i0, int64_t i1, const ct_real *restrict p, const ct_real *restrict g,
                const ct_real *restrict K0, ct_real *restrict fel, ct_real *restrict ktan,
                ct_real *restrict energy, int32_t *restrict flag, const int has_kt,
                const int has_e, const int has_flag)
{
    const ct_real xc = (ct_real)1 - (ct_real)CT_TYPE7_RMIN;
    ct_real bad = 0;
#pragma omp simd reduction(+ : bad)
    for (int64_t i = i0; i < i1; i++) {
        ct_real gi = g[i], k0 = K0[i], q = p[i];
        /* Selects on floating compares (no int flag: see pair_force_body.h).
         * An infinite g or K0 is the check's business (it gave no force). */
        ct_real ok = gi > 0 ? (ct_real)1 : 0;
        ok = k0 > 0 ? ok : 0;
        ok = q > 0 ? ok : 0;
        ct_real gs = ok > 0 ? gi : 1, ks = ok > 0 ? k0 : 0;
        ct_real x = ok > 0 ? q / gs : 0;
        ct_real xs = x >= xc ? xc : x, r = (ct_real)1 - xs;
        ct_real f = ks * gs * xs / r;
        fel[i] = f;
        /* The terms of K0, p and g (+inf only: NaN or <= 0, -inf too, is
         * no contact; the compares are ok's), then of the outputs (short
         * chains: see cti_normal_block). */
        ct_real nf = cti_nf_add(cti_nf_add(CTI_NF(k0), q > 0 ? q : 0), gi > 0 ? gi : 0);
        ct_real out = CTI_NF(f);
        if (has_kt) {
            ct_real kt = ks / (r * r);
            ktan[i] = kt;
            out = cti_nf_add(out, kt);
        }
        nf += out;
        if (has_flag)
            flag[i] = x >= xc ? 1 : 0;
        bad += nf;
    }
    /* The energy is not checked (from finite inputs it is finite or +inf:
     * ct_force.h); its scalar loop is left out after a failure. */
    int nonfinite = !(bad == 0);
    if (!has_e || nonfinite)
        return nonfinite;
    for (int64_t i = i0; i < i1; i++) {
        ct_real gi = g[i], k0 = K0[i], q = p[i];
        if (!(gi > 0 && k0 > 0 && q > 0)) {
            energy[i] = 0;
            continue;
        }
        ct_real x = q / gi;
        ct_real xs = x >= xc ? xc : x;
        ct_real e = cti_type7_e(k0, gi, q, xs);
        if (x >= xc)
            e += fel[i] * gi * ((x < 1 ? x : 1) - xc);
        energy[i] = e;
    }
    return 0;
}

/* Pairs per block of the TYPE7 loop. */
#define CTI_TYPE7_BLOCK 2048

int ct_penalty_type7(ct_idx npair, const ct_real *p, const ct_real *g, const ct_real *K0,
                     ct_real *fel, ct_real *ktan, ct_real *energy, int32_t *flag)
{
    if (npair < 0 || !p || !g || !K0 || !fel)
        return CT_ERR_ARG;
    const int variant = (ktan != NULL) | (energy != NULL) << 1 | (flag != NULL) << 2;
    const int64_t nblk = ((int64_t)npair + CTI_TYPE7_BLOCK - 1) / CTI_TYPE7_BLOCK;
    int bad = 0;
#define CTI_T7_CASE(V)                                                                     \
    case V:                                                                                \
        bad |= cti_type7_block(i0, i1, p, g, K0, fel, ktan, energy, flag, (V)&1,           \
                               ((V) >> 1) & 1, ((V) >> 2) & 1);                            \
        break;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(| : bad)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_TYPE7_BLOCK, npair, &i0, &i1);
        switch (variant) { CTI_CASES8(CTI_T7_CASE) }
    });
#undef CTI_T7_CASE
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

/* ---- TYPE6 user curve ----------------------------------------------------- */

int ct_curve_check(ct_idx n, const ct_real *x, const ct_real *y, ct_diag *diag)
{
    if (!x || !y || n < 2)
        return cti_fail(diag, CT_ERR_ARG, -1, "A curve needs at least 2 points (it has %ld).",
                        (long)n);
    for (ct_idx i = 0; i < n; i++) {
        if (!(CTI_FABS(x[i]) <= CTI_HUGE) || !(CTI_FABS(y[i]) <= CTI_HUGE))
            return cti_fail(diag, CT_ERR_ARG, i, "Curve point %ld is not finite.", (long)i);
        if (i > 0 && !(x[i] > x[i - 1]))
            return cti_fail(diag, CT_ERR_ARG, i,
                            "Curve abscissa %ld is not above the previous one.", (long)i);
    }
    return CT_OK;
}

ct_real ct_curve_eval(ct_idx n, const ct_real *x, const ct_real *y, ct_real p,
                      ct_real *slope)
{
    if (p != p || n < 2) {
        if (slope)
            *slope = 0;
        return 0;
    }
    /* The interval [x[lo], x[lo+1]] with x[lo] <= p < x[lo+1], clamped to
     * the first and last intervals (extrapolation). */
    ct_idx lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        ct_idx mid = lo + (hi - lo) / 2;
        if (p >= x[mid])
            lo = mid;
        else
            hi = mid;
    }
    ct_real s = (y[lo + 1] - y[lo]) / (x[lo + 1] - x[lo]);
    if (slope)
        *slope = s;
    return y[lo] + s * (p - x[lo]);
}

int ct_penalty_type6(ct_idx npair, const ct_real *p, ct_idx ncurve, const ct_real *cx,
                     const ct_real *cy, ct_real *fel, ct_real *pmax, ct_real *ftotal,
                     ct_real *kcurve, ct_diag *diag)
{
    if (npair < 0 || !p || !fel)
        return cti_fail(diag, CT_ERR_ARG, -1, "Bad TYPE6 arguments.");
    int rc = ct_curve_check(ncurve, cx, cy, diag);
    if (rc != CT_OK)
        return rc;
    /* The largest penetration (NaN compares false: ignored, as any p <= 0,
     * -inf too). An infinite p_max is an error, reported at the lowest
     * index holding it (a second pass, on failure only). */
    ct_real pm = 0;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(max : pm)),
    for (ct_idx i = 0; i < npair; i++)
        pm = p[i] > pm ? p[i] : pm;
    );
    if (pm > CTI_REAL_MAX) {
        ct_idx i = 0;
        while (!(p[i] > CTI_REAL_MAX))
            i++;
        return cti_fail(diag, CT_ERR_NONFINITE, i, "TYPE6: penetration %ld is infinite.",
                        (long)i);
    }
    ct_real slope = 0, F = 0, kc = 0;
    if (pm > 0) {
        F = ct_curve_eval(ncurve, cx, cy, pm, &slope);
        F = F > 0 ? F : 0;
        ct_real sec = F / pm;
        kc = slope > sec ? slope : sec;
    }
    double sum = npair > 0 ? cti_sum_blocks(npair, p, 1) : 0;
    ct_real scale = sum > 0 ? (ct_real)((double)F / sum) : 0;
    /* Overflows of finite inputs: the curve's force or stiffness at p_max
     * (a steep extrapolation), the sum of the penetrations, or the largest
     * force scale p_max (the other forces are below it). Reported at the
     * first pair of the largest penetration, or -1 for the sum. */
    if (!(sum <= DBL_MAX))
        return cti_fail(diag, CT_ERR_NONFINITE, -1, "TYPE6: the sum of the penetrations "
                                                    "overflows.");
    if (CTI_NONFINITE(F) || CTI_NONFINITE(scale * pm) || (kcurve && CTI_NONFINITE(kc))) {
        ct_idx i = 0;
        while (!(p[i] == pm))
            i++;
        return cti_fail(diag, CT_ERR_NONFINITE, i,
                        "TYPE6: the curve's force or stiffness at the largest penetration "
                        "(pair %ld, %g) overflows.",
                        (long)i, (double)pm);
    }
    CTI_PAR_FOR_SIMD(npair > CTI_PAR_MIN, (schedule(static)),
    for (ct_idx i = 0; i < npair; i++)
        fel[i] = p[i] > 0 ? scale * p[i] : 0;
    );
    if (pmax)
        *pmax = pm;
    if (ftotal)
        *ftotal = F;
    if (kcurve)
        *kcurve = kc;
    return CT_OK;
}

/* ---- Damping and the force vector ----------------------------------------- */

ct_real ct_damping_coef(ct_real viss, ct_real K, ct_real ms, ct_real mm)
{
    ct_real m = cti_reduced_mass(ms, mm);
    ct_real a = (ct_real)2 * K * m;
    return (viss > 0 && a > 0) ? viss * CTI_SQRT(a) : 0;
}

/* One block [i0, i1) of ct_normal_finish, inlined with constant has_*
 * flags: a branch-free SIMD loop. Returns 1 when a checked value of the
 * block is NaN or infinite (ct_internal.h): p infinite, fel, kd, vn, the
 * masses NaN or infinite, and the outputs (the force vector's check covers
 * the normal and fn, which it multiplies). */
static inline __attribute__((always_inline)) int
cti_finish_block(int64_t i0, int64_t i1, const ct_real *restrict pp,
                 const ct_real *restrict fe_, const ct_real *restrict k,
                 const ct_real *restrict v, const ct_real *restrict m1,
                 const ct_real *restrict m2, ct_real vs, ct_real dt,
                 const ct_real *restrict ax, const ct_real *restrict ay,
                 const ct_real *restrict az, ct_real *restrict ofn, ct_real *restrict ox,
                 ct_real *restrict oy, ct_real *restrict oz, ct_real *restrict od,
                 const int has_mm, const int has_fn, const int has_d)
{
    ct_real bad = 0;
CTI_SIMD_SQRT_BAD
    for (int64_t i = i0; i < i1; i++) {
        ct_real q = pp[i], f0 = fe_[i], k0 = k[i], w = v[i];
        ct_real fe = f0 > 0 ? f0 : 0;
        ct_real m = has_mm ? cti_reduced_mass(m1[i], m2[i]) : m1[i];
        ct_real a = (ct_real)2 * k0 * m;
        a = a > 0 ? a : 0;
        /* No damping: c = 0 even where 2 kd m overflows (cti_normal_pair). */
        ct_real c = vs * CTI_SQRT(a);
        c = vs > 0 ? c : 0;
        ct_real ft = fe - c * w;
        ft = ft < 0 ? 0 : ft; /* keeps a NaN (ft is never -0) */
        ft = q > 0 ? ft : 0;
        fe = q > 0 ? fe : 0;
        ct_real d = (fe - ft) * w * dt;
        d = d > 0 ? d : 0;
        if (has_fn)
            ofn[i] = ft;
        ct_real fx = ft * ax[i], fy = ft * ay[i], fz = ft * az[i];
        ox[i] = fx;
        oy[i] = fy;
        oz[i] = fz;
        if (has_d)
            od[i] = d;
        /* The terms: fel, kd, m, w, p (+inf only: a NaN or negative p,
         * -inf too, is no contact; the compare is the selects') in the
         * inputs' chain; the force vector (which covers the normal and fn)
         * in the outputs' (short chains: see cti_normal_block). The
         * dissipation is not checked (cti_normal_pair). */
        ct_real in = cti_nf_add(cti_nf_add(CTI_NF(f0), k0), m);
        in = cti_nf_add(cti_nf_add(in, w), q > 0 ? q : 0);
        if (has_mm)
            in = cti_nf_add(in, m2[i]);
        bad += in + cti_nf_add(cti_nf_add(CTI_NF(fx), fy), fz);
    }
    return !(bad == 0);
}

/* Pairs per block of the damping loop. */
#define CTI_FINISH_BLOCK 2048

int ct_damping_work(ct_idx npair, const ct_real *p, const ct_real *fn, const ct_real *fel,
                    const ct_real *vn, ct_real dt, ct_real *fprev, ct_real *dissip)
{
    if (npair < 0 || !p || !fn || !fel || !vn || !fprev || !dissip || !cti_step_ok(dt))
        return CT_ERR_ARG;
    const ct_real *restrict pp = p, *restrict f = fn, *restrict fe = fel, *restrict v = vn;
    ct_real *restrict fo = fprev, *restrict d = dissip;
    CTI_PAR_FOR_SIMD(npair > CTI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < npair; k++) {
        ct_real fd = pp[k] > 0 ? f[k] - fe[k] : 0;
        d[k] = -(ct_real)0.5 * (fo[k] + fd) * v[k] * dt;
        fo[k] = fd;
    });
    return CT_OK;
}

int ct_normal_finish(ct_idx npair, const ct_real *p, const ct_real *fel, const ct_real *kd,
                     const ct_real *vn, const ct_real *ms, const ct_real *mm, ct_real viss,
                     ct_real dt, const ct_real *nx, const ct_real *ny, const ct_real *nz,
                     ct_real *fn, ct_real *fx, ct_real *fy, ct_real *fz, ct_real *dissip)
{
    if (npair < 0 || !p || !fel || !kd || !vn || !ms || !nx || !ny || !nz || !fx || !fy ||
        !fz || !cti_step_ok(dt) || !cti_viss_ok(viss))
        return CT_ERR_ARG;
    const ct_real vs = viss > 0 ? viss : 0;
    const int variant = (mm != NULL) | (fn != NULL) << 1 | (dissip != NULL) << 2;
    const int64_t nblk = ((int64_t)npair + CTI_FINISH_BLOCK - 1) / CTI_FINISH_BLOCK;
    int bad = 0;
#define CTI_NFIN_CASE(V)                                                                   \
    case V:                                                                                \
        bad |= cti_finish_block(i0, i1, p, fel, kd, vn, ms, mm, vs, dt, nx, ny, nz, fn, fx,  \
                                fy, fz, dissip, (V)&1, ((V) >> 1) & 1, ((V) >> 2) & 1);    \
        break;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(| : bad)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_FINISH_BLOCK, npair, &i0, &i1);
        switch (variant) { CTI_CASES8(CTI_NFIN_CASE) }
    });
#undef CTI_NFIN_CASE
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

/* One block [i0, i1) of ct_normal_force, inlined with constant has_* flags
 * so that every variant is a branch-free SIMD loop. Returns 1 when a
 * checked value of the block is NaN or infinite (cti_normal_pair; the
 * force vector's check covers the normal and fn). */
static inline __attribute__((always_inline)) int
cti_normal_block(int64_t i0, int64_t i1, const ct_real *restrict pp,
                 const ct_real *restrict ax, const ct_real *restrict ay,
                 const ct_real *restrict az, const ct_real *restrict v,
                 const ct_real *restrict kk, ct_real K0, const ct_real *restrict m1,
                 const ct_real *restrict m2, ct_real vs, ct_real dt, ct_real *restrict ox,
                 ct_real *restrict oy, ct_real *restrict oz, ct_real *restrict ofn,
                 ct_real *restrict oe, ct_real *restrict od, const int has_k,
                 const int has_mm, const int has_fn, const int has_e, const int has_d)
{
    ct_real bad = 0;
CTI_SIMD_SQRT_BAD
    for (int64_t i = i0; i < i1; i++) {
        ct_real m = has_mm ? cti_reduced_mass(m1[i], m2[i]) : m1[i];
        ct_real k = has_k ? kk[i] : K0;
        ct_real e, d;
        ct_real ft = cti_normal_pair(pp[i], k, m, vs, v[i], dt, &e, &d);
        ct_real fx = ft * ax[i], fy = ft * ay[i], fz = ft * az[i];
        ox[i] = fx;
        oy[i] = fy;
        oz[i] = fz;
        if (has_fn)
            ofn[i] = ft;
        if (has_e)
            oe[i] = e;
        if (has_d)
            od[i] = d;
        /* The terms (cti_normal_pair says what they cover) in short
         * chains, the inputs' apart: a chain runs at the latency of its
         * fused operations, and the outputs' come last. */
        ct_real in = cti_nf_add(CTI_NF(m), v[i]);
        if (has_k)
            in = cti_nf_add(in, k);
        if (has_mm)
            in = cti_nf_add(in, m2[i]);
        bad += in + cti_nf_add(cti_nf_add(CTI_NF(fx), fy), fz);
    }
    return !(bad == 0);
}

/* Pairs per block of the fused normal-force loop. */
#define CTI_NORMAL_BLOCK 2048

int ct_normal_force(ct_idx npair, const ct_real *p, const ct_real *nx, const ct_real *ny,
                    const ct_real *nz, const ct_real *vn, const ct_real *K, ct_real K0,
                    const ct_real *ms, const ct_real *mm, ct_real viss, ct_real dt,
                    ct_real *fx, ct_real *fy, ct_real *fz, ct_real *fn, ct_real *energy,
                    ct_real *dissip)
{
    if (npair < 0 || !p || !nx || !ny || !nz || !vn || !ms || !fx || !fy || !fz ||
        !cti_step_ok(dt) || !cti_viss_ok(viss))
        return CT_ERR_ARG;
    if (!K && CTI_NONFINITE(K0))
        return CT_ERR_NONFINITE; /* the scalar stands for a per-pair K: checked once */
    const ct_real vs = viss > 0 ? viss : 0;
    const int variant = (K != NULL) | (mm != NULL) << 1 | (fn != NULL) << 2 |
                        (energy != NULL) << 3 | (dissip != NULL) << 4;
    const int64_t nblk = ((int64_t)npair + CTI_NORMAL_BLOCK - 1) / CTI_NORMAL_BLOCK;
    int bad = 0;
#define CTI_NF_CASE(V)                                                                     \
    case V:                                                                                \
        bad |= cti_normal_block(i0, i1, p, nx, ny, nz, vn, K, K0, ms, mm, vs, dt, fx, fy,   \
                                fz, fn, energy, dissip, (V)&1, ((V) >> 1) & 1,             \
                                ((V) >> 2) & 1, ((V) >> 3) & 1, ((V) >> 4) & 1);           \
        break;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(| : bad)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_NORMAL_BLOCK, npair, &i0, &i1);
        switch (variant) { CTI_CASES32(CTI_NF_CASE) }
    });
#undef CTI_NF_CASE
    return bad ? CT_ERR_NONFINITE : CT_OK;
}
