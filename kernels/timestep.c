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

/* The inputs of the per-item limits. */
struct cti_dt_nodal_in {
    const ct_idx *idx;
    const ct_real *m, *kelem, *kcont;
};
struct cti_dt_type7_in {
    const ct_real *p, *g, *vn;
};
enum { CTI_DT_NODAL, CTI_DT_TYPE7 };
struct cti_dt_in {
    int kind; /* CTI_DT_NODAL or CTI_DT_TYPE7: which of the two is read */
    struct cti_dt_nodal_in nodal;
    struct cti_dt_type7_in type7;
};

/* The nodal step of a node of mass mi and stiffness k (element plus
 * contact); *nan is set if an input is NaN or infinite (an infinite
 * stiffness, or a sum of two that overflows, would give a zero step, on
 * which a solver cannot advance; an infinite mass an infinite one). */
static inline ct_real cti_dt_nodal_step(ct_real mi, ct_real k, int *nan)
{
    *nan = CTI_NONFINITE(mi) | CTI_NONFINITE(k);
    return (mi > 0 && k > 0) ? CTI_SQRT((ct_real)2 * mi / k) : CT_DT_NONE;
}

/* The TYPE7 kinematic step of a pair of penetration pi, gap gi and normal
 * velocity v (ct_dt_type7_kinematic); *nan is set if an input is NaN or
 * infinite (an infinite approach speed would give a zero step). */
static inline ct_real cti_dt_type7_step(ct_real pi, ct_real gi, ct_real v, int *nan)
{
    const ct_real xc = (ct_real)1 - (ct_real)CT_TYPE7_RMIN;
    int lim = pi > 0 && gi > 0 && pi < gi * xc && v < 0;
    *nan = CTI_NONFINITE(pi) | CTI_NONFINITE(gi) | CTI_NONFINITE(v);
    return lim ? (gi - pi) / ((ct_real)2 * -v) : CT_DT_NONE;
}

/* Items per chunk of the scan. */
#define CTI_DT_CHUNK 256

/* The chunk's minimum as a vector reduction: gcc vectorises it; clang 14
 * does not without -ffast-math (a compare-and-select minimum of doubles
 * that may be NaN) and, asked to, fails the build under -Werror, so it
 * gets the plain loop. */
#ifdef __clang__
#define CTI_DT_MIN_SIMD
#else
#define CTI_DT_MIN_SIMD _Pragma("omp simd reduction(min : cm)")
#endif

/* mc[k] = m[ix[k]] and, when ke is given, kc[k] = ke[ix[k]], k < n: scalar
 * loads (not vector gathers). */
CTI_NOVEC static void cti_dt_fetch(const ct_idx *restrict ix, const ct_real *restrict m,
                                   const ct_real *restrict ke, int n, ct_real *restrict mc,
                                   ct_real *restrict kc)
{
    CTI_NOVEC_LOOP
    for (int k = 0; k < n; k++)
        mc[k] = m[ix[k]];
    if (!ke)
        return;
    CTI_NOVEC_LOOP
    for (int k = 0; k < n; k++)
        kc[k] = ke[ix[k]];
}

/* Element stiffness zero, for the calls without one (a chunk's worth). */
static const ct_real cti_dt_zero[CTI_DT_CHUNK];

/* The steps of items [i0, i0 + n) (n <= CTI_DT_CHUNK) into d, their
 * non-finite flags into nan; returns whether any is set. One vector loop per kind. */
static int cti_dt_chunk(const struct cti_dt_in *in, ct_idx i0, int n, ct_real *restrict d,
                        cti_lane *restrict nan)
{
    cti_lane any = 0;
    if (in->kind == CTI_DT_NODAL) {
        /* Through a node list, the chunk's masses (and element
         * stiffnesses) are copied first by scalar loads; the vector loops
         * then read contiguous arrays only (a chunk of zeros standing for
         * absent element stiffnesses), so that no lane selects a pointer.
         * With the list and the NULL test inside the loop (and the TYPE7
         * loop's pointers read through the struct, below), gcc 12 loaded
         * every input with vector gathers, which AMD Zen 4 and 5 microcode:
         * the two steps of the folded sheet's contact cycle (10^5 nodes,
         * 1 thread) took 12.9 ns per node and cycle, now 5.8. */
        _Alignas(64) ct_real mc[CTI_DT_CHUNK], kc[CTI_DT_CHUNK];
        const struct cti_dt_nodal_in *nd = &in->nodal;
        const ct_real *restrict mp = nd->m + i0, *restrict kp = cti_dt_zero;
        if (nd->idx) {
            cti_dt_fetch(nd->idx + i0, nd->m, nd->kelem, n, mc, kc);
            mp = mc;
            kp = nd->kelem ? kc : kp;
        } else if (nd->kelem) {
            kp = nd->kelem + i0;
        }
        const ct_real *restrict kq = nd->kcont + i0;
#pragma omp simd reduction(| : any)
        for (int k = 0; k < n; k++) {
            int f = 0;
            d[k] = cti_dt_nodal_step(mp[k], kp[k] + kq[k], &f);
            nan[k] = f;
            any |= f;
        }
    } else {
        /* The arrays as restrict pointers to the chunk (see above). */
        const ct_real *restrict pp = in->type7.p + i0, *restrict gp = in->type7.g + i0;
        const ct_real *restrict vp = in->type7.vn + i0;
#pragma omp simd reduction(| : any)
        for (int k = 0; k < n; k++) {
            int f = 0;
            d[k] = cti_dt_type7_step(pp[k], gp[k], vp[k], &f);
            nan[k] = f;
            any |= f;
        }
    }
    return any != 0;
}

/* Chunk c of the scan: its steps (into dt when given), and its minimum,
 * lowest index and first non-finite item folded into the running (lb, li, ln). */
static void cti_dt_scan_chunk(ct_idx n, const struct cti_dt_in *in, ct_idx c, ct_real *dt,
                              ct_real *lb, ct_idx *li, ct_idx *ln)
{
    _Alignas(64) ct_real d[CTI_DT_CHUNK];
    _Alignas(64) cti_lane nan[CTI_DT_CHUNK];
    const ct_idx i0 = c * CTI_DT_CHUNK;
    const int m = (int)(n - i0 < CTI_DT_CHUNK ? n - i0 : CTI_DT_CHUNK);
    if (cti_dt_chunk(in, i0, m, d, nan)) {
        for (int k = 0; k < m; k++)
            if (nan[k]) {
                d[k] = CT_DT_NONE;
                *ln = i0 + k < *ln ? i0 + k : *ln;
            }
    }
    if (dt)
        for (int k = 0; k < m; k++)
            dt[i0 + k] = d[k];
    ct_real cm = CT_DT_NONE;
    CTI_DT_MIN_SIMD
    for (int k = 0; k < m; k++)
        cm = d[k] < cm ? d[k] : cm;
    if (cm < *lb) {
        int k = 0;
        while (!(d[k] == cm))
            k++;
        *lb = d[k];
        *li = i0 + k;
    }
}

/* The scan shared by the per-item limits: dt[i] = the step of item i
 * (CT_DT_NONE where an input is NaN or infinite), the minimum and its
 * lowest index, or CT_ERR_NONFINITE with the first such item. In chunks: the steps of a
 * chunk in a vector loop, its minimum by a vector reduction (exact), then
 * the first index holding it, so the answer is the item-by-item scan's.
 * Below CTI_PAR_MIN items the chunks run without a thread team (see
 * CTI_PAR_FOR); the fold is the same. */
static int cti_dt_scan(ct_idx n, const struct cti_dt_in *in, ct_real *dt, ct_real *dtmin,
                       ct_idx *imin)
{
    ct_real best = CT_DT_NONE;
    ct_idx bi = -1, nan_idx = n;
    const ct_idx nch = (n + CTI_DT_CHUNK - 1) / CTI_DT_CHUNK;
    if (n > CTI_PAR_MIN) {
#pragma omp parallel
        {
            ct_real lb = CT_DT_NONE;
            ct_idx li = -1, ln = n;
#pragma omp for schedule(static) nowait
            for (ct_idx c = 0; c < nch; c++)
                cti_dt_scan_chunk(n, in, c, dt, &lb, &li, &ln);
#pragma omp critical(cti_dt)
            cti_dt_fold(lb, li, ln, &best, &bi, &nan_idx);
        }
    } else {
        ct_real lb = CT_DT_NONE;
        ct_idx li = -1, ln = n;
        for (ct_idx c = 0; c < nch; c++)
            cti_dt_scan_chunk(n, in, c, dt, &lb, &li, &ln);
        cti_dt_fold(lb, li, ln, &best, &bi, &nan_idx);
    }
    return cti_dt_result(n, best, bi, nan_idx, dtmin, imin);
}

int ct_dt_nodal(ct_idx n, const ct_idx *idx, const ct_real *m, const ct_real *kelem,
                const ct_real *kcont, ct_real *dt, ct_real *dtmin, ct_idx *imin)
{
    if (n < 0 || (n > 0 && (!m || !kcont)))
        return CT_ERR_ARG;
    const struct cti_dt_in in = {.kind = CTI_DT_NODAL, .nodal = {idx, m, kelem, kcont}};
    return cti_dt_scan(n, &in, dt, dtmin, imin);
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
    const struct cti_dt_in in = {.kind = CTI_DT_TYPE7, .type7 = {p, g, vn}};
    return cti_dt_scan(npair, &in, dt, dtmin, imin);
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
