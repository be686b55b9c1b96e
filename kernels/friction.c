/*
 * friction.c -- friction coefficient laws, tangential force by elastic
 * predictor and return to the Coulomb cone, the tangential filter, and the
 * carrying of per-pair history across re-sorts (DESIGN.md section 7).
 */
#include "math_vec.h"
#include "pair_force_body.h"

/* Block of new pairs one binary search serves in ct_pair_match. */
#define CTI_MATCH_BLOCK 4096

#define CTI_TWO_PI ((ct_real)6.283185307179586476925286766559)

int ct_friction_check(int law, const ct_real coef[7], ct_diag *diag)
{
    if (law < 0 || law >= CT_FRIC_NLAW || !coef)
        return cti_fail(diag, CT_ERR_ARG, -1, "Unknown friction law %d.", law);
    static const char *const name[7] = {"Fric", "C1", "C2", "C3", "C4", "C5", "C6"};
    for (int i = 0; i < 7; i++)
        if (!(CTI_FABS(coef[i]) <= CTI_HUGE))
            return cti_fail(diag, CT_ERR_ARG, i,
                            "Friction coefficient %d (%s) = %g is not finite or above %g.", i,
                            name[i], (double)coef[i], (double)CTI_HUGE);
    if (law == CT_FRIC_RENARD) {
        if (!(coef[5] > 0))
            return cti_fail(diag, CT_ERR_ARG, 5, "Renard needs C5 = Vcr1 > 0.");
        if (!(coef[6] > coef[5]))
            return cti_fail(diag, CT_ERR_ARG, 6, "Renard needs C6 = Vcr2 > C5 = Vcr1.");
        if (!(coef[2] >= coef[4]))
            return cti_fail(diag, CT_ERR_ARG, 4, "Renard needs C4 = mu_min <= C2 = mu_d.");
    }
    if (law == CT_FRIC_EXPDECAY && !(coef[2] >= 0))
        return cti_fail(diag, CT_ERR_ARG, 2, "The decay rate C2 must be >= 0.");
    return CT_OK;
}

/* The laws, written once for the scalar and the array entry points, before
 * the clamp to mu >= 0. The denominators are guarded so that unchecked
 * coefficients give a finite value rather than a NaN. Always inlined: with
 * three exponentials clang would call it, and the loop over pairs would
 * not vectorise. */
static inline __attribute__((always_inline)) ct_real
cti_mu_raw(int law, const ct_real *restrict c, ct_real p, ct_real v)
{
    ct_real mu;
    v = CTI_FABS(v);
    switch (law) {
    case CT_FRIC_COULOMB: mu = c[0]; break;
    case CT_FRIC_POLY:
        mu = c[0] + c[1] * p + c[2] * v + c[3] * p * v + c[4] * p * p + c[5] * v * v;
        break;
    case CT_FRIC_DARMSTAD:
        mu = c[1] * cti_exp(c[2] * v) * p * p + c[3] * cti_exp(c[4] * v) * p +
             c[5] * cti_exp(c[6] * v);
        break;
    case CT_FRIC_RENARD: {
        /* The three branches' values by selects and one division: each
         * branch divides once (u = v / v1, xi = (v - C5) / w, a / den), so
         * the division takes the branch's operands. The same bits as
         * branches, but no branch on the speed (which a scalar loop
         * mispredicted on most pairs) and a loop that vectorises. */
        ct_real v1 = c[5] > 0 ? c[5] : 1, w = c[6] - c[5];
        w = w > 0 ? w : 1;
        ct_real d = v - c[6], a = c[2] - c[4];
        ct_real den = (ct_real)1 + a * d * d;
        den = den > 0 ? den : 1;
        ct_real num = v < c[6] ? v - c[5] : a, dv = v < c[6] ? w : den;
        num = v <= c[5] ? v : num;
        dv = v <= c[5] ? v1 : dv;
        ct_real t = num / dv;
        ct_real m1 = c[1] + (c[3] - c[1]) * t * ((ct_real)2 - t);
        ct_real m2 = c[3] + (c[4] - c[3]) * t * t * ((ct_real)3 - (ct_real)2 * t);
        mu = v < c[6] ? m2 : c[2] - t;
        mu = v <= c[5] ? m1 : mu;
        break;
    }
    case CT_FRIC_EXPDECAY: mu = c[1] + (c[0] - c[1]) * cti_exp(-c[2] * v); break;
    default: mu = 0;
    }
    return mu;
}

ct_real ct_friction_mu1(int law, const ct_real coef[7], ct_real pressure, ct_real speed)
{
    if (!coef)
        return 0;
    ct_real mu = cti_mu_raw(law, coef, pressure, speed);
    return mu > 0 ? mu : 0;
}

/* Pairs [i0, i1) of ct_friction_mu for one law (a constant after
 * inlining), one vector loop: the law's arithmetic is the same in a
 * vector lane (Renard's branches are selects around one division, the
 * exponential is cti_exp's arithmetic: math_vec.h), so ct_friction_mu1 gives
 * the same bits. 1 when a checked value is NaN or infinite: the speed
 * (every law but Coulomb), the pressure (the polynomial and Darmstad laws),
 * and the law's value before the clamp to >= 0 (an overflow, which the
 * clamp made 0, or let through as +inf). */
static inline __attribute__((always_inline)) int
cti_mu_block(int64_t i0, int64_t i1, const int law, const ct_real *restrict c,
             const ct_real *restrict pressure, const ct_real *restrict speed,
             ct_real *restrict mu)
{
    const int usep = law == CT_FRIC_POLY || law == CT_FRIC_DARMSTAD;
    const int usev = law != CT_FRIC_COULOMB;
    ct_real bad = 0;
#pragma omp simd reduction(+ : bad)
    for (int64_t i = i0; i < i1; i++) {
        ct_real pr = usep ? pressure[i] : 0, v = usev ? speed[i] : 0;
        ct_real m = cti_mu_raw(law, c, pr, v);
        mu[i] = m > 0 ? m : 0;
        ct_real nf = usev ? cti_nf_add(CTI_NF(m), v) : CTI_NF(m);
        bad += usep ? cti_nf_add(nf, pr) : nf;
    }
    return !(bad == 0);
}

/* Pairs per block of the friction-law loop. */
#define CTI_MU_BLOCK 512

int ct_friction_mu(ct_idx npair, int law, const ct_real coef[7], const ct_real *pressure,
                   const ct_real *speed, ct_real *mu)
{
    const int usep = law == CT_FRIC_POLY || law == CT_FRIC_DARMSTAD;
    if (npair < 0 || !coef || !speed || !mu || law < 0 || law >= CT_FRIC_NLAW ||
        (!pressure && usep))
        return CT_ERR_ARG;
    ct_real c[7];
    for (int i = 0; i < 7; i++) {
        c[i] = coef[i];
        if (CTI_NONFINITE(c[i]))
            return CT_ERR_ARG; /* as ct_friction_check */
    }
    const int64_t nblk = ((int64_t)npair + CTI_MU_BLOCK - 1) / CTI_MU_BLOCK;
    int bad = 0;
#define CTI_MU_CASE(L)                                                                     \
    case L: bad |= cti_mu_block(i0, i1, L, c, pressure, speed, mu); break;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(| : bad)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_MU_BLOCK, npair, &i0, &i1);
        switch (law) {
        CTI_MU_CASE(CT_FRIC_COULOMB)
        CTI_MU_CASE(CT_FRIC_POLY)
        CTI_MU_CASE(CT_FRIC_DARMSTAD)
        CTI_MU_CASE(CT_FRIC_RENARD)
        default: bad |= cti_mu_block(i0, i1, CT_FRIC_EXPDECAY, c, pressure, speed, mu);
        }
    });
#undef CTI_MU_CASE
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

ct_real ct_filter_alpha(int ifiltr, ct_real xfreq, ct_real dt)
{
    ct_real a;
    switch (ifiltr) {
    case 1: a = xfreq; break;
    case 2: a = xfreq > 0 ? CTI_TWO_PI / xfreq : 0; break;
    case 3: a = CTI_TWO_PI * xfreq * dt; break;
    default: a = 1;
    }
    if (!(a > 0))
        return 1; /* not positive or NaN: the filter is off */
    return a < 1 ? a : 1;
}

/* One block [i0, i1) of ct_friction_step. Inlined with constant has_*
 * flags so that every variant is a branch-free SIMD loop. Returns 1 when a
 * checked value of the block is NaN or infinite (pair_force_body.h). */
static inline __attribute__((always_inline)) int
cti_friction_block(int64_t i0, int64_t i1, const ct_real *restrict ax,
                   const ct_real *restrict ay, const ct_real *restrict az,
                   const ct_real *restrict ux, const ct_real *restrict uy,
                   const ct_real *restrict uz, const ct_real *restrict f_n,
                   const ct_real *restrict m_, ct_real mu0, const ct_real *restrict k_,
                   ct_real kt0, ct_real dt, ct_real alpha, ct_real *restrict hx,
                   ct_real *restrict hy, ct_real *restrict hz, ct_real *restrict od,
                   const int has_mu, const int has_kt, const int has_d, const int filt)
{
    ct_real bad = 0;
CTI_SIMD_SQRT_BAD
    for (int64_t i = i0; i < i1; i++) {
        ct_real g0 = hx[i], g1 = hy[i], g2 = hz[i], nf = 0;
        ct_real d = cti_friction_pair(ax[i], ay[i], az[i], ux[i], uy[i], uz[i], f_n[i],
                                      has_mu ? m_[i] : mu0, has_kt ? k_[i] : kt0, dt, alpha,
                                      filt, &g0, &g1, &g2, &nf);
        hx[i] = g0;
        hy[i] = g1;
        hz[i] = g2;
        if (has_d)
            od[i] = d;
        bad += nf;
    }
    return !(bad == 0);
}

/* Pairs per block of the friction loop. */
#define CTI_FRIC_BLOCK 2048

int ct_friction_step(ct_idx npair, const ct_real *nx, const ct_real *ny, const ct_real *nz,
                     const ct_real *vx, const ct_real *vy, const ct_real *vz,
                     const ct_real *fn, const ct_real *mu, ct_real mu0, const ct_real *kt,
                     ct_real kt0, ct_real dt, ct_real alpha, ct_real *ftx, ct_real *fty,
                     ct_real *ftz, ct_real *dissip)
{
    if (npair < 0 || !nx || !ny || !nz || !vx || !vy || !vz || !fn || !ftx || !fty || !ftz ||
        !cti_step_ok(dt) || !(alpha > 0 && alpha <= 1))
        return CT_ERR_ARG;
    /* The scalars that stand for per-pair arrays: NaN and -inf count as 0,
     * as in the arrays; +inf is refused here, once. */
    if ((!mu && mu0 > CTI_REAL_MAX) || (!kt && kt0 > CTI_REAL_MAX))
        return CT_ERR_NONFINITE;
    const int variant = (mu != NULL) | (kt != NULL) << 1 | (dissip != NULL) << 2 |
                        (alpha < 1) << 3;
    const int64_t nblk = ((int64_t)npair + CTI_FRIC_BLOCK - 1) / CTI_FRIC_BLOCK;
    int bad = 0;
#define CTI_FRIC_CASE(V)                                                                   \
    case V:                                                                                \
        bad |= cti_friction_block(i0, i1, nx, ny, nz, vx, vy, vz, fn, mu, mu0, kt, kt0, dt, \
                                  alpha, ftx, fty, ftz, dissip, (V)&1, ((V) >> 1) & 1,     \
                                  ((V) >> 2) & 1, ((V) >> 3) & 1);                         \
        break;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(| : bad)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_FRIC_BLOCK, npair, &i0, &i1);
        switch (variant) { CTI_CASES16(CTI_FRIC_CASE) }
    });
#undef CTI_FRIC_CASE
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

/* Block [i0, i1) of ct_friction_work, inlined with constant flags (the kt
 * array or kt0, adding to dissip or not, the energy or not): a load or a
 * store under a condition does not vectorise under clang, nor an outlined
 * parallel loop over pointers it cannot bound. */
static inline __attribute__((always_inline)) void
cti_friction_work_block(int64_t i0, int64_t i1, const ct_real *restrict ux,
                        const ct_real *restrict uy, const ct_real *restrict uz,
                        const ct_real *restrict gx, const ct_real *restrict gy,
                        const ct_real *restrict gz, const ct_real *restrict kk, ct_real kt0,
                        ct_real dt, ct_real *restrict d, ct_real *restrict en, const int has_k,
                        const int after, const int has_e)
{
    const ct_real sgn = after ? -1 : 1;
#pragma omp simd
    for (int64_t k = i0; k < i1; k++) {
        const ct_real g2 = gx[k] * gx[k] + gy[k] * gy[k] + gz[k] * gz[k];
        const ct_real s = has_k ? kk[k] : kt0;
        const ct_real e = s > 0 ? g2 / (2 * s) : 0;
        const ct_real w = (ct_real)-0.5 * (gx[k] * ux[k] + gy[k] * uy[k] + gz[k] * uz[k]) * dt;
        if (after)
            d[k] += w + sgn * e;
        else
            d[k] = w + sgn * e;
        if (has_e)
            en[k] += e;
    }
}

/* Pairs per block of ct_friction_work. */
#define CTI_FWORK_BLOCK 2048

int ct_friction_work(ct_idx npair, const ct_real *vx, const ct_real *vy, const ct_real *vz,
                     const ct_real *ftx, const ct_real *fty, const ct_real *ftz,
                     const ct_real *kt, ct_real kt0, ct_real dt, int after, ct_real *dissip,
                     ct_real *energy)
{
    if (npair < 0 || !vx || !vy || !vz || !ftx || !fty || !ftz || !dissip ||
        !cti_step_ok(dt))
        return CT_ERR_ARG;
#define CTI_FW(K, A, E)                                                                       \
    cti_friction_work_block(i0, i1, vx, vy, vz, ftx, fty, ftz, kt, kt0, dt, dissip, energy, K,  \
                            A, E)
    const int kk = kt != NULL, e = after && energy != NULL;
    const int64_t nblk = ((int64_t)npair + CTI_FWORK_BLOCK - 1) / CTI_FWORK_BLOCK;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_FWORK_BLOCK, npair, &i0, &i1);
        if (!after)
            kk ? CTI_FW(1, 0, 0) : CTI_FW(0, 0, 0);
        else if (e)
            kk ? CTI_FW(1, 1, 1) : CTI_FW(0, 1, 1);
        else
            kk ? CTI_FW(1, 1, 0) : CTI_FW(0, 1, 0);
    });
#undef CTI_FW
    return CT_OK;
}

double ct_friction_dissipation(ct_idx npair, const ct_real *dissip)
{
    return ct_sum_ordered(npair, dissip);
}

/* One ordered 64-bit key per (node, seg): node major, seg minor (seg is
 * shifted so that negative values keep their order). */
static inline int64_t cti_key(ct_idx node, ct_idx seg)
{
    return (int64_t)node * ((int64_t)1 << 32) + ((int64_t)seg + ((int64_t)1 << 31));
}

int ct_pair_match(ct_idx nold, const ct_idx *old_node, const ct_idx *old_seg, ct_idx nnew,
                  const ct_idx *new_node, const ct_idx *new_seg, ct_idx *old_of_new,
                  ct_diag *diag)
{
    if (nold < 0 || nnew < 0 || (nold > 0 && (!old_node || !old_seg)) ||
        (nnew > 0 && (!new_node || !new_seg || !old_of_new)))
        return cti_fail(diag, CT_ERR_ARG, -1, "Bad pair match arguments.");
    /* Both lists must be strictly ascending (min-reductions: the first
     * offender, whatever the thread count). */
    ct_idx bad_old = nold, bad_new = nnew;
    CTI_PAR_FOR(nold > CTI_PAR_MIN, (schedule(static) reduction(min : bad_old)),
    for (ct_idx i = 1; i < nold; i++)
        if (!(cti_key(old_node[i - 1], old_seg[i - 1]) < cti_key(old_node[i], old_seg[i])))
            bad_old = i < bad_old ? i : bad_old;
    );
    CTI_PAR_FOR(nnew > CTI_PAR_MIN, (schedule(static) reduction(min : bad_new)),
    for (ct_idx i = 1; i < nnew; i++)
        if (!(cti_key(new_node[i - 1], new_seg[i - 1]) < cti_key(new_node[i], new_seg[i])))
            bad_new = i < bad_new ? i : bad_new;
    );
    if (bad_new < nnew)
        return cti_fail(diag, CT_ERR_ARG, bad_new,
                        "New pair %ld is not above the previous one in (node, seg) order.",
                        (long)bad_new);
    if (bad_old < nold)
        return cti_fail(diag, CT_ERR_ARG, -1 - (int64_t)bad_old,
                        "Old pair %ld is not above the previous one in (node, seg) order.",
                        (long)bad_old);
    ct_idx nblock = (ct_idx)(((int64_t)nnew + CTI_MATCH_BLOCK - 1) / CTI_MATCH_BLOCK);
    CTI_PAR_FOR(nblock > 1, (schedule(static)),
    for (ct_idx b = 0; b < nblock; b++) {
        int64_t k0 = (int64_t)b * CTI_MATCH_BLOCK, k1 = k0 + CTI_MATCH_BLOCK;
        k1 = k1 < nnew ? k1 : nnew;
        /* Lower bound of the block's first key in the old list. */
        int64_t first = cti_key(new_node[k0], new_seg[k0]);
        ct_idx lo = 0, hi = nold;
        while (lo < hi) {
            ct_idx mid = lo + (hi - lo) / 2;
            if (cti_key(old_node[mid], old_seg[mid]) < first)
                lo = mid + 1;
            else
                hi = mid;
        }
        ct_idx j = lo;
        for (int64_t k = k0; k < k1; k++) {
            int64_t key = cti_key(new_node[k], new_seg[k]);
            while (j < nold && cti_key(old_node[j], old_seg[j]) < key)
                j++;
            old_of_new[k] = (j < nold && cti_key(old_node[j], old_seg[j]) == key) ? j : -1;
        }
    });
    return CT_OK;
}

int ct_pair_remap(ct_idx nnew, const ct_idx *old_of_new, const ct_real *src, ct_real fill,
                  ct_real *dst)
{
    if (nnew < 0 || (nnew > 0 && (!old_of_new || !dst)))
        return CT_ERR_ARG;
    const ct_idx *restrict map = old_of_new;
    const ct_real *restrict s = src;
    ct_real *restrict d = dst;
    CTI_PAR_FOR(nnew > CTI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < nnew; k++)
        d[k] = (map[k] >= 0 && s) ? s[map[k]] : fill;
    );
    return CT_OK;
}

int ct_friction_remap(ct_idx nold, const ct_idx *old_node, const ct_idx *old_seg,
                      const ct_real *old_fx, const ct_real *old_fy, const ct_real *old_fz,
                      ct_idx nnew, const ct_idx *new_node, const ct_idx *new_seg,
                      ct_real *new_fx, ct_real *new_fy, ct_real *new_fz,
                      ct_idx *old_of_new, ct_diag *diag)
{
    if (nold > 0 && (!old_fx || !old_fy || !old_fz))
        return cti_fail(diag, CT_ERR_ARG, -1, "Missing old friction history.");
    if (nnew > 0 && (!new_fx || !new_fy || !new_fz))
        return cti_fail(diag, CT_ERR_ARG, -1, "Missing new friction history.");
    int rc = ct_pair_match(nold, old_node, old_seg, nnew, new_node, new_seg, old_of_new, diag);
    if (rc != CT_OK)
        return rc;
    ct_pair_remap(nnew, old_of_new, old_fx, 0, new_fx);
    ct_pair_remap(nnew, old_of_new, old_fy, 0, new_fy);
    ct_pair_remap(nnew, old_of_new, old_fz, 0, new_fz);
    return CT_OK;
}
