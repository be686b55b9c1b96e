/*
 * stiffness.c -- contact stiffness: main segment stiffness (shell, brick
 * face), secondary node stiffness, and their combination per pair
 * (DESIGN.md section 7, seeds TYPE5 and TYPE24).
 */
#include "ct_internal.h"

#ifdef CT_SINGLE
#define CTI_CBRT cbrtf
#else
#define CTI_CBRT cbrt
#endif

/* Loops shorter than this run on one thread (the parallel start-up would
 * cost more than the work). */
#define CTI_PAR_MIN 8192

ct_real ct_bulk_modulus(ct_real E, ct_real nu)
{
    ct_real d = (ct_real)3 * ((ct_real)1 - (ct_real)2 * nu);
    if (!(E > 0))
        return 0;
    if (!(d > 0))
        return CTI_HUGE;
    return E / d;
}

ct_real ct_seg_stiffness_shell(ct_real stfac, ct_real E, ct_real t) { return stfac * E * t; }

ct_real ct_seg_stiffness_brick(ct_real stfac, ct_real B, ct_real A, ct_real V)
{
    return V > 0 ? stfac * B * (A * A / V) : 0;
}

ct_real ct_node_stiffness1(ct_real B, ct_real vnode, ct_real et_mean)
{
    ct_real ks = 0;
    if (vnode > 0 && B > 0)
        ks = B * CTI_CBRT((ct_real)2 * vnode);
    if (et_mean > 0)
        ks += et_mean;
    return ks;
}

/* 0 when v is usable as a non-negative physical quantity, else the error
 * code it deserves. */
static inline int cti_check_nonneg(ct_real v)
{
    if (v != v)
        return CT_ERR_NONFINITE;
    return v < 0 ? CT_ERR_ARG : CT_OK;
}

int ct_seg_stiffness(ct_idx nseg, ct_real stfac, const ct_real *E, const ct_real *t,
                     const ct_real *B, const ct_real *A, const ct_real *V, ct_real *K,
                     ct_diag *diag)
{
    if (nseg < 0 || !K || (!E) != (!t) || !((!B) == (!A) && (!A) == (!V)))
        return cti_fail(diag, CT_ERR_ARG, -1, "Bad segment stiffness arguments.");
    if (!(stfac >= 0))
        return cti_fail(diag, CT_ERR_ARG, -1, "The stiffness factor must be >= 0.");
    /* Validation first (serial, in index order: the first offender is
     * reported); this runs once per model, not per cycle. */
    for (ct_idx i = 0; i < nseg; i++) {
        int shell = t && t[i] > 0;
        int code = CT_OK;
        if (t && t[i] != t[i])
            code = CT_ERR_NONFINITE;
        else if (shell)
            code = cti_check_nonneg(E[i]);
        else if (V && V[i] > 0) {
            code = cti_check_nonneg(B[i]);
            if (code == CT_OK)
                code = cti_check_nonneg(A[i]);
        } else if (V && V[i] != V[i])
            code = CT_ERR_NONFINITE;
        if (code != CT_OK)
            return cti_fail(diag, code, i,
                            "Segment %ld has a NaN or negative stiffness input.", (long)i);
    }
    const ct_real *restrict e = E, *restrict th = t, *restrict b = B, *restrict a = A,
                            *restrict v = V;
    ct_real *restrict k = K;
    CTI_PAR_FOR(nseg > CTI_PAR_MIN, (schedule(static)),
    for (ct_idx i = 0; i < nseg; i++) {
        ct_real ksh = 0, kbr = 0;
        int shell = 0;
        if (th) {
            shell = th[i] > 0;
            ksh = stfac * e[i] * th[i];
        }
        if (v && v[i] > 0)
            kbr = stfac * b[i] * (a[i] * a[i] / v[i]);
        k[i] = shell ? ksh : kbr;
    });
    return CT_OK;
}

int ct_node_stiffness(ct_idx n, const ct_real *B, const ct_real *vnode,
                      const ct_real *et_mean, ct_real *K, ct_diag *diag)
{
    if (n < 0 || !K || (!B) != (!vnode))
        return cti_fail(diag, CT_ERR_ARG, -1, "Bad node stiffness arguments.");
    for (ct_idx i = 0; i < n; i++) {
        int code = CT_OK;
        if (B) {
            code = cti_check_nonneg(B[i]);
            if (code == CT_OK)
                code = cti_check_nonneg(vnode[i]);
        }
        if (code == CT_OK && et_mean)
            code = cti_check_nonneg(et_mean[i]);
        if (code != CT_OK)
            return cti_fail(diag, code, i, "Node %ld has a NaN or negative stiffness input.",
                            (long)i);
    }
    CTI_PAR_FOR(n > CTI_PAR_MIN, (schedule(static)),
    for (ct_idx i = 0; i < n; i++)
        K[i] = ct_node_stiffness1(B ? B[i] : 0, vnode ? vnode[i] : 0, et_mean ? et_mean[i] : 0);
    );
    return CT_OK;
}

/* Springs in series, lo / (1 + lo/hi): lo/hi <= 1 cannot overflow, an
 * infinite hi gives lo, a zero lo gives 0 (also when hi is 0), two
 * infinities give infinity. */
static inline ct_real cti_series(ct_real a, ct_real b)
{
    ct_real lo = a < b ? a : b, hi = a < b ? b : a;
    ct_real r = lo / ((ct_real)1 + lo / hi);
    r = (lo > 0) ? r : (ct_real)0;
    return (lo == (ct_real)INFINITY) ? lo : r;
}

static inline ct_real cti_combine(int mode, ct_real km, ct_real ks, ct_real s)
{
    switch (mode) {
    case CT_STIFF_MAIN: return km;
    case CT_STIFF_MEAN: return (ct_real)0.5 * km + (ct_real)0.5 * ks;
    case CT_STIFF_MAX: return km > ks ? km : ks;
    case CT_STIFF_MIN: return km < ks ? km : ks;
    case CT_STIFF_SERIES: return cti_series(km, ks);
    case CT_STIFF_SCALED_SERIES: return s * cti_series(km, ks);
    default: return 0;
    }
}

static inline ct_real cti_clamp_stiff(ct_real k, ct_real stmin, ct_real stmax)
{
    k = k < stmin ? stmin : k;
    return (stmax > 0 && k > stmax) ? stmax : k;
}

ct_real ct_stiffness_combine1(int mode, ct_real Km, ct_real Ks, ct_real s, ct_real stmin,
                              ct_real stmax)
{
    if (mode < 0 || mode >= CT_STIFF_NCOMBINE)
        return 0;
    return cti_clamp_stiff(cti_combine(mode, Km, Ks, s), stmin, stmax);
}

int ct_stiffness_pairs(ct_idx npair, int mode, const ct_idx *node, const ct_idx *seg,
                       const ct_real *Knode, const ct_real *Kseg, ct_real s, ct_real stmin,
                       ct_real stmax, ct_real *K, ct_diag *diag)
{
    if (npair < 0 || !node || !seg || !Knode || !Kseg || !K || mode < 0 ||
        mode >= CT_STIFF_NCOMBINE)
        return cti_fail(diag, CT_ERR_ARG, -1, "Bad pair stiffness arguments.");
    const ct_idx *restrict nd = node, *restrict sg = seg;
    const ct_real *restrict kn = Knode, *restrict ksg = Kseg;
    ct_real *restrict k = K;
    ct_idx bad = npair;
    /* The smallest offending index is a min-reduction: the same for any
     * thread count. */
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static) reduction(min : bad)),
    for (ct_idx i = 0; i < npair; i++) {
        ct_real km = ksg[sg[i]], ks = kn[nd[i]];
        if (!(km >= 0) || !(ks >= 0))
            bad = i < bad ? i : bad;
        k[i] = cti_clamp_stiff(cti_combine(mode, km, ks, s), stmin, stmax);
    });
    if (bad < npair) {
        ct_real km = Kseg[seg[bad]], ks = Knode[node[bad]];
        int code = (km != km || ks != ks) ? CT_ERR_NONFINITE : CT_ERR_ARG;
        return cti_fail(diag, code, bad, "Pair %ld has a NaN or negative stiffness.",
                        (long)bad);
    }
    return CT_OK;
}
