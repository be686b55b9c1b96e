/*
 * timestep.c -- the contact contribution to the stable time step: nodal
 * (mass over element plus contact stiffness), TYPE7 kinematic, TYPE6 curve,
 * and the tunnelling limit (DESIGN.md sections 5 and 7).
 */
#include "ct_internal.h"

/* Loops shorter than this run on one thread. */
#define CTI_PAR_MIN 8192

/* Fold one thread's (minimum, index, first NaN) into the shared result.
 * The lexicographic minimum of (value, index) does not depend on the order
 * threads arrive in, so the answer is the same for any thread count. */
static inline void cti_dt_fold(ct_real lb, ct_idx li, ct_idx ln, ct_real *best, ct_idx *bi,
                               ct_idx *nan_idx)
{
    if (li >= 0 && (lb < *best || (lb == *best && (*bi < 0 || li < *bi)))) {
        *best = lb;
        *bi = li;
    }
    if (ln < *nan_idx)
        *nan_idx = ln;
}

static int cti_dt_result(ct_idx n, ct_real best, ct_idx bi, ct_idx nan_idx, ct_real *dtmin,
                         ct_idx *imin)
{
    if (nan_idx < n) {
        if (dtmin)
            *dtmin = CT_DT_NONE;
        if (imin)
            *imin = nan_idx;
        return CT_ERR_NONFINITE;
    }
    if (dtmin)
        *dtmin = best;
    if (imin)
        *imin = bi;
    return CT_OK;
}

int ct_dt_nodal(ct_idx n, const ct_idx *idx, const ct_real *m, const ct_real *kelem,
                const ct_real *kcont, ct_real *dt, ct_real *dtmin, ct_idx *imin)
{
    if (n < 0 || (n > 0 && (!m || !kcont)))
        return CT_ERR_ARG;
    ct_real best = CT_DT_NONE;
    ct_idx bi = -1, nan_idx = n;
#pragma omp parallel if (n > CTI_PAR_MIN)
    {
        ct_real lb = CT_DT_NONE;
        ct_idx li = -1, ln = n;
#pragma omp for schedule(static) nowait
        for (ct_idx i = 0; i < n; i++) {
            ct_idx j = idx ? idx[i] : i;
            ct_real mi = m[j], k = (kelem ? kelem[j] : 0) + kcont[i];
            ct_real d = (mi > 0 && k > 0) ? CTI_SQRT((ct_real)2 * mi / k) : CT_DT_NONE;
            if (mi != mi || k != k) {
                ln = i < ln ? i : ln;
                d = CT_DT_NONE;
            }
            if (dt)
                dt[i] = d;
            if (d < lb) {
                lb = d;
                li = i;
            }
        }
#pragma omp critical(cti_dt)
        cti_dt_fold(lb, li, ln, &best, &bi, &nan_idx);
    }
    return cti_dt_result(n, best, bi, nan_idx, dtmin, imin);
}

ct_real ct_type7_tangent(ct_real K0, ct_real g, ct_real p)
{
    if (!(K0 > 0) || !(g > 0))
        return 0;
    ct_real x = p / g, xc = (ct_real)1 - (ct_real)CT_TYPE7_RMIN;
    x = x > 0 ? x : 0;
    x = x < xc ? x : xc;
    ct_real r = (ct_real)1 - x;
    return K0 / (r * r);
}

int ct_dt_type7_kinematic(ct_idx npair, const ct_real *p, const ct_real *g,
                          const ct_real *vn, ct_real *dt, ct_real *dtmin, ct_idx *imin)
{
    if (npair < 0 || (npair > 0 && (!p || !g || !vn)))
        return CT_ERR_ARG;
    const ct_real xc = (ct_real)1 - (ct_real)CT_TYPE7_RMIN;
    ct_real best = CT_DT_NONE;
    ct_idx bi = -1, nan_idx = npair;
#pragma omp parallel if (npair > CTI_PAR_MIN)
    {
        ct_real lb = CT_DT_NONE;
        ct_idx li = -1, ln = npair;
#pragma omp for schedule(static) nowait
        for (ct_idx i = 0; i < npair; i++) {
            ct_real pi = p[i], gi = g[i], v = vn[i];
            int lim = pi > 0 && gi > 0 && pi < gi * xc && v < 0;
            ct_real d = lim ? (gi - pi) / ((ct_real)2 * -v) : CT_DT_NONE;
            if (pi != pi || gi != gi || v != v) {
                ln = i < ln ? i : ln;
                d = CT_DT_NONE;
            }
            if (dt)
                dt[i] = d;
            if (d < lb) {
                lb = d;
                li = i;
            }
        }
#pragma omp critical(cti_dt)
        cti_dt_fold(lb, li, ln, &best, &bi, &nan_idx);
    }
    return cti_dt_result(npair, best, bi, nan_idx, dtmin, imin);
}

ct_real ct_dt_type6(ct_real mmin, ct_real p, ct_idx ncurve, const ct_real *cx,
                    const ct_real *cy)
{
    if (!(p > 0) || !(mmin > 0) || ct_curve_check(ncurve, cx, cy, NULL) != CT_OK)
        return CT_DT_NONE;
    ct_real slope, f = ct_curve_eval(ncurve, cx, cy, p, &slope);
    ct_real sec = f / p;
    ct_real k = slope > sec ? slope : sec;
    if (!(k > 0))
        return CT_DT_NONE;
    ct_real d = (ct_real)0.1 * CTI_SQRT(mmin / k);
    return d < CT_DT_NONE ? d : CT_DT_NONE;
}

ct_real ct_dt_tunnel(ct_real gap_min, ct_real vrel_max)
{
    ct_real v = CTI_FABS(vrel_max);
    if (!(gap_min > 0) || !(v > 0))
        return CT_DT_NONE;
    ct_real d = (ct_real)0.9 * gap_min / v;
    return d < CT_DT_NONE ? d : CT_DT_NONE;
}
