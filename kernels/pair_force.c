/*
 * pair_force.c -- the fused per-pair contact force: linear penalty with
 * normal damping and the Coulomb friction step, in one pass over the pairs
 * (DESIGN.md section 7; the formulas are those of ct_normal_force and
 * ct_friction_step, documented in ct_force.h and ct_friction.h). The
 * relative velocity these kernels read is kinematics.c's.
 *
 * The two-kernel composition reads the normals twice and writes fn only for
 * the friction pass to read it back; at 10^6 pairs both passes stream from
 * memory, so the fused pass moves fewer bytes. The per-pair arithmetic is
 * that of pair_force_body.h, shared with penalty.c and friction.c, so the
 * results are bit-identical to the composition by construction
 * (tests/test_friction.c checks this with memcmp).
 */
#include "pair_force_body.h"

/* Pairs per block. A thread keeps 7 stack arrays of this length: the
 * per-pair stiffness, friction coefficient and tangential stiffness filled
 * with the scalar when no array is given, and sinks for the optional
 * outputs not asked for, so that one loop serves every combination (28 KB
 * in double; they stay in L1). */
#define CTI_PF_BLOCK 512

/* One block of n pairs; every pointer already points at the block's first
 * pair. has_vn, has_mm and filt are constants after inlining. Returns 1
 * when a checked value of the block is NaN or infinite: the union of
 * ct_normal_force's and ct_friction_step's checks (the stiffness, friction
 * coefficient and tangential stiffness per pair, the scalars having been
 * checked once as those kernels check them). */
static inline __attribute__((always_inline)) int
cti_pair_force_block(int64_t n, const ct_real *restrict pp, const ct_real *restrict ax,
                     const ct_real *restrict ay, const ct_real *restrict az,
                     const ct_real *restrict ux, const ct_real *restrict uy,
                     const ct_real *restrict uz, const ct_real *restrict vnp,
                     const ct_real *restrict kk, const ct_real *restrict m1,
                     const ct_real *restrict m2, ct_real vs, const ct_real *restrict m_,
                     const ct_real *restrict k_, ct_real dt, ct_real alpha,
                     ct_real *restrict ox, ct_real *restrict oy, ct_real *restrict oz,
                     ct_real *restrict ofn, ct_real *restrict oe, ct_real *restrict od,
                     ct_real *restrict hx, ct_real *restrict hy, ct_real *restrict hz,
                     ct_real *restrict otd, const int has_vn, const int has_mm,
                     const int filt)
{
    ct_real bad = 0;
CTI_SIMD_SQRT_BAD
    for (int64_t i = 0; i < n; i++) {
        ct_real n0 = ax[i], n1 = ay[i], n2 = az[i];
        ct_real v0 = ux[i], v1 = uy[i], v2 = uz[i];
        ct_real w = has_vn ? vnp[i] : v0 * n0 + v1 * n1 + v2 * n2;
        ct_real m = has_mm ? cti_reduced_mass(m1[i], m2[i]) : m1[i];
        ct_real k = kk[i];
        ct_real e, d;
        ct_real ft = cti_normal_pair(pp[i], k, m, vs, w, dt, &e, &d);
        ct_real fx = ft * n0, fy = ft * n1, fz = ft * n2;
        ox[i] = fx;
        oy[i] = fy;
        oz[i] = fz;
        ofn[i] = ft;
        oe[i] = e;
        od[i] = d;
        /* The terms in short chains (see cti_normal_block): the inputs'
         * (cti_normal_pair says what they cover), continued by the
         * friction step's; the normal force's. Of the force vector fn n,
         * only the first component: it covers fn; the normal is covered by
         * the friction trial, which every component of it reaches; and
         * with a unit normal, as the conventions require, |fn n_i| <= fn
         * cannot overflow where fn does not. (The two other terms cost 7 %
         * at 10^4 pairs.) */
        ct_real in = cti_nf_add(cti_nf_add(CTI_NF(m), w), k);
        if (has_mm)
            in = cti_nf_add(in, m2[i]);
        /* Friction on the normal force just computed. */
        ct_real g0 = hx[i], g1 = hy[i], g2 = hz[i];
        otd[i] = cti_friction_pair(n0, n1, n2, v0, v1, v2, ft, m_[i], k_[i], dt, alpha, filt,
                                   &g0, &g1, &g2, &in);
        hx[i] = g0;
        hy[i] = g1;
        hz[i] = g2;
        bad += in + CTI_NF(fx);
    }
    return !(bad == 0);
}

int ct_pair_force_linear_coulomb(
    ct_idx npair, const ct_real *p, const ct_real *nx, const ct_real *ny, const ct_real *nz,
    const ct_real *vx, const ct_real *vy, const ct_real *vz, const ct_real *vn,
    const ct_real *K, ct_real K0, const ct_real *ms, const ct_real *mm, ct_real viss,
    const ct_real *mu, ct_real mu0, const ct_real *kt, ct_real kt0, ct_real dt,
    ct_real alpha, ct_real *fx, ct_real *fy, ct_real *fz, ct_real *fn, ct_real *energy,
    ct_real *dissip, ct_real *ftx, ct_real *fty, ct_real *ftz, ct_real *fdissip)
{
    if (npair < 0 || !p || !nx || !ny || !nz || !vx || !vy || !vz || !ms || !fx || !fy ||
        !fz || !ftx || !fty || !ftz || !cti_step_ok(dt) || !cti_viss_ok(viss) ||
        !(alpha > 0 && alpha <= 1))
        return CT_ERR_ARG;
    /* The scalars standing for per-pair arrays, as the two kernels check
     * them (K0 finite; mu0 and kt0 not +inf, NaN and -inf counting as 0). */
    if ((!K && CTI_NONFINITE(K0)) || (!mu && mu0 > CTI_REAL_MAX) || (!kt && kt0 > CTI_REAL_MAX))
        return CT_ERR_NONFINITE;
    const ct_real vs = viss > 0 ? viss : 0;
    const int variant = (vn != NULL) | (mm != NULL) << 1 | (alpha < 1) << 2;
    const int64_t nblk = ((int64_t)npair + CTI_PF_BLOCK - 1) / CTI_PF_BLOCK;
    int bad = 0;
#pragma omp parallel if (npair > CTI_PAR_MIN) reduction(| : bad)
    {
        /* Per-thread scalar broadcasts and output sinks (see CTI_PF_BLOCK). */
        ct_real bk[CTI_PF_BLOCK], bmu[CTI_PF_BLOCK], bkt[CTI_PF_BLOCK];
        ct_real sink_fn[CTI_PF_BLOCK], sink_e[CTI_PF_BLOCK], sink_d[CTI_PF_BLOCK],
            sink_td[CTI_PF_BLOCK];
        for (int j = 0; j < CTI_PF_BLOCK; j++) {
            bk[j] = K0;
            bmu[j] = mu0;
            bkt[j] = kt0;
        }
#pragma omp for schedule(static)
        for (int64_t b = 0; b < nblk; b++) {
            int64_t i0, i1;
            cti_block_range(b, CTI_PF_BLOCK, npair, &i0, &i1);
            int64_t len = i1 - i0;
            const ct_real *kb = K ? K + i0 : bk, *mub = mu ? mu + i0 : bmu,
                          *ktb = kt ? kt + i0 : bkt, *vnb = vn ? vn + i0 : NULL,
                          *mmb = mm ? mm + i0 : NULL;
            ct_real *fnb = fn ? fn + i0 : sink_fn, *eb = energy ? energy + i0 : sink_e,
                    *db = dissip ? dissip + i0 : sink_d, *tdb = fdissip ? fdissip + i0 : sink_td;
#define CTI_PF_CASE(V)                                                                     \
    case V:                                                                                \
        bad |= cti_pair_force_block(len, p + i0, nx + i0, ny + i0, nz + i0, vx + i0,        \
                                    vy + i0, vz + i0, vnb, kb, ms + i0, mmb, vs, mub, ktb,  \
                                    dt, alpha, fx + i0, fy + i0, fz + i0, fnb, eb, db,      \
                                    ftx + i0, fty + i0, ftz + i0, tdb, (V)&1, ((V) >> 1) & 1, \
                                    ((V) >> 2) & 1);                                        \
        break;
            switch (variant) { CTI_CASES8(CTI_PF_CASE) }
#undef CTI_PF_CASE
        }
    }
    return bad ? CT_ERR_NONFINITE : CT_OK;
}
