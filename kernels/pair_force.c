/*
 * pair_force.c -- the fused per-pair contact force: linear penalty with
 * normal damping and the Coulomb friction step, in one pass over the pairs
 * (DESIGN.md section 7; the formulas are those of ct_normal_force and
 * ct_friction_step, documented in ct_force.h and ct_friction.h).
 *
 * The two-kernel composition reads the normals twice and writes fn only for
 * the friction pass to read it back; at 10^6 pairs both passes stream from
 * memory, so the fused pass moves fewer bytes. Each expression below is
 * written exactly as in penalty.c and friction.c, in the same order, so the
 * results are bit-identical to the composition (tests/test_friction.c
 * checks this with memcmp); a change to either kernel's arithmetic must be
 * made here too.
 */
#include "ct_internal.h"

/* "omp simd" on loops that call sqrt: they vectorise only when sqrt need
 * not set errno (-fno-math-errno, which defines __NO_MATH_ERRNO__). */
#if defined(__NO_MATH_ERRNO__)
#define CTI_SIMD_SQRT _Pragma("omp simd")
#else
#define CTI_SIMD_SQRT
#endif

/* Loops shorter than this run on one thread. */
#define CTI_PAR_MIN 8192

/* Pairs per block. A thread keeps 7 stack arrays of this length: the
 * per-pair stiffness, friction coefficient and tangential stiffness filled
 * with the scalar when no array is given, and sinks for the optional
 * outputs not asked for, so that one loop serves every combination (28 KB
 * in double; they stay in L1). */
#define CTI_PF_BLOCK 512

/* The reduced mass as in penalty.c: without a segment mass,
 * ms / (1 + ms/inf) = ms. */
static inline ct_real cti_pf_reduced_mass(ct_real ms, ct_real mm)
{
    ct_real m2 = mm > 0 ? mm : (ct_real)INFINITY;
    return ms / ((ct_real)1 + ms / m2);
}

/* One block of n pairs; every pointer already points at the block's first
 * pair. has_vn, has_mm and filt are constants after inlining. */
static inline __attribute__((always_inline)) void
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
    const ct_real beta = (ct_real)1 - alpha;
CTI_SIMD_SQRT
    for (int64_t i = 0; i < n; i++) {
        ct_real n0 = ax[i], n1 = ay[i], n2 = az[i];
        ct_real v0 = ux[i], v1 = uy[i], v2 = uz[i];
        ct_real vnn = v0 * n0 + v1 * n1 + v2 * n2;
        ct_real w = has_vn ? vnp[i] : vnn;
        /* Normal force: F = K q with damping, clamped compressive. */
        ct_real q = pp[i] > 0 ? pp[i] : 0;
        ct_real k = kk[i];
        k = k > 0 ? k : 0;
        ct_real fe = k * q;
        ct_real m = has_mm ? cti_pf_reduced_mass(m1[i], m2[i]) : m1[i];
        ct_real a = (ct_real)2 * k * m;
        a = a > 0 ? a : 0;
        ct_real c = vs * CTI_SQRT(a);
        ct_real ft = fe - c * w;
        ft = ft > 0 ? ft : 0;
        ft = q > 0 ? ft : 0;
        ox[i] = ft * n0;
        oy[i] = ft * n1;
        oz[i] = ft * n2;
        ofn[i] = ft;
        oe[i] = (ct_real)0.5 * fe * q;
        ct_real dd = (fe - ft) * w * dt;
        od[i] = dd > 0 ? dd : 0;
        /* Friction: elastic predictor and return to the cone on fn = ft. */
        ct_real f = ft > 0 ? ft : 0;
        ct_real mu = m_[i];
        mu = mu > 0 ? mu : 0;
        ct_real kt = k_[i];
        kt = kt > 0 ? kt : 0;
        ct_real lim = mu * f;
        ct_real o0 = hx[i], o1 = hy[i], o2 = hz[i];
        ct_real on = o0 * n0 + o1 * n1 + o2 * n2;
        o0 -= on * n0;
        o1 -= on * n1;
        o2 -= on * n2;
        ct_real kd = kt * dt;
        ct_real t0 = o0 - kd * (v0 - vnn * n0);
        ct_real t1 = o1 - kd * (v1 - vnn * n1);
        ct_real t2 = o2 - kd * (v2 - vnn * n2);
        ct_real tt = t0 * t0 + t1 * t1 + t2 * t2;
        /* NaN or overflow in the trial: no force (a force-valued flag, as
         * in friction.c, so that gcc vectorises the selects). */
        ct_real fok = tt <= CTI_HUGE ? f : 0;
        tt = tt > 0 ? tt : 0;
        ct_real tn = CTI_SQRT(tt);
        ct_real den = tn > lim ? tn : lim;
        ct_real rq = lim / (den > 0 ? den : (ct_real)1);
        ct_real r = den > 0 ? rq : (ct_real)1;
        ct_real g0 = r * t0, g1 = r * t1, g2 = r * t2;
        if (filt) {
            g0 = alpha * g0 + beta * o0;
            g1 = alpha * g1 + beta * o1;
            g2 = alpha * g2 + beta * o2;
            ct_real gg = g0 * g0 + g1 * g1 + g2 * g2;
            gg = gg > 0 ? gg : 0;
            ct_real gn = CTI_SQRT(gg);
            ct_real gd = gn > lim ? gn : lim;
            ct_real sq = lim / (gd > 0 ? gd : (ct_real)1);
            ct_real s = gd > 0 ? sq : (ct_real)1;
            g0 *= s;
            g1 *= s;
            g2 *= s;
        }
        ct_real slip = tn - lim;
        ct_real slq = slip / (kt > 0 ? kt : (ct_real)1);
        slip = (slip > 0 && kt > 0) ? slq : 0;
        g0 = fok > 0 ? g0 : 0;
        g1 = fok > 0 ? g1 : 0;
        g2 = fok > 0 ? g2 : 0;
        hx[i] = g0;
        hy[i] = g1;
        hz[i] = g2;
        ct_real gg = g0 * g0 + g1 * g1 + g2 * g2;
        gg = gg > 0 ? gg : 0;
        ct_real d = CTI_SQRT(gg) * slip;
        otd[i] = d > 0 ? d : 0;
    }
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
        !fz || !ftx || !fty || !ftz || !(dt >= 0) || !(alpha > 0 && alpha <= 1))
        return CT_ERR_ARG;
    const ct_real vs = viss > 0 ? viss : 0;
    const int variant = (vn != NULL) | (mm != NULL) << 1 | (alpha < 1) << 2;
    const int64_t nblk = ((int64_t)npair + CTI_PF_BLOCK - 1) / CTI_PF_BLOCK;
#pragma omp parallel if (npair > CTI_PAR_MIN)
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
            int64_t i0 = b * CTI_PF_BLOCK, i1 = i0 + CTI_PF_BLOCK;
            i1 = i1 < npair ? i1 : npair;
            int64_t len = i1 - i0;
            const ct_real *kb = K ? K + i0 : bk, *mub = mu ? mu + i0 : bmu,
                          *ktb = kt ? kt + i0 : bkt, *vnb = vn ? vn + i0 : NULL,
                          *mmb = mm ? mm + i0 : NULL;
            ct_real *fnb = fn ? fn + i0 : sink_fn, *eb = energy ? energy + i0 : sink_e,
                    *db = dissip ? dissip + i0 : sink_d, *tdb = fdissip ? fdissip + i0 : sink_td;
#define CTI_PF_CASE(V)                                                                     \
    case V:                                                                                \
        cti_pair_force_block(len, p + i0, nx + i0, ny + i0, nz + i0, vx + i0, vy + i0,      \
                             vz + i0, vnb, kb, ms + i0, mmb, vs, mub, ktb, dt, alpha,      \
                             fx + i0, fy + i0, fz + i0, fnb, eb, db, ftx + i0, fty + i0,   \
                             ftz + i0, tdb, (V)&1, ((V) >> 1) & 1, ((V) >> 2) & 1);        \
        break;
            switch (variant) {
                CTI_PF_CASE(0) CTI_PF_CASE(1) CTI_PF_CASE(2) CTI_PF_CASE(3)
                CTI_PF_CASE(4) CTI_PF_CASE(5) CTI_PF_CASE(6) CTI_PF_CASE(7)
            }
#undef CTI_PF_CASE
        }
    }
    return CT_OK;
}
