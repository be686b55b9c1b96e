/*
 * edge.c -- edge-to-edge narrow phase (TYPE11; seed "Auto Contacts",
 * Figure 9; DESIGN.md section 6) and the four nodal forces of a pair.
 *
 * Closest points of Pa(sa) = A1 + sa u and Pb(sb) = B1 + sb v, u = A2 - A1,
 * v = B2 - B1, w = A1 - B1: minimise |w + sa u - sb v|^2. With a = u.u,
 * b = u.v, c = v.v, d = u.w, e = v.w the normal equations give
 *   sa = (b e - c d) / den,  sb = (a e - b d) / den,  den = a c - b^2,
 * where den is taken as |u x v|^2 (no cancellation). Then sa is clamped to
 * [0, 1], sb recomputed as the minimiser for that sa, (b sa + e) / c, and
 * clamped, and sa recomputed for that sb, (b sb - d) / a, and clamped: the
 * constrained minimum of this convex problem. Parallel edges (den <= 16 eps
 * a c) start instead from the middle of the overlap of B's projection on
 * A's line with [0, 1] (A's end nearest to B when they do not overlap), so
 * the point is consistent and slides continuously. Last, the projections
 * of the four end points on the other edge are compared with that answer
 * and a strictly closer one is taken: rounding in nearly parallel cases
 * cannot then cost distance.
 */
#include "narrow_internal.h"

#define CTI_EE_PAR_TOL (16 * CTI_EPS)

/* |w + s u - t v|^2, the squared distance of Pa(s) and Pb(t). */
static inline ct_real cti_ee_q(const ct_real u[3], const ct_real v[3], const ct_real w[3],
                               ct_real s, ct_real t)
{
    ct_real rx = w[0] + s * u[0] - t * v[0];
    ct_real ry = w[1] + s * u[1] - t * v[1];
    ct_real rz = w[2] + s * u[2] - t * v[2];
    return rx * rx + ry * ry + rz * rz;
}

static inline void cti_ee_cand(const ct_real u[3], const ct_real v[3], const ct_real w[3],
                               ct_real s, ct_real t, ct_real *bs, ct_real *bt, ct_real *bq)
{
    ct_real q = cti_ee_q(u, v, w, s, t);
    int take = q < *bq;
    *bs = take ? s : *bs;
    *bt = take ? t : *bt;
    *bq = take ? q : *bq;
}

static inline void cti_ee_closest(const ct_real A1[3], const ct_real A2[3],
                                  const ct_real B1[3], const ct_real B2[3], ct_real *psa,
                                  ct_real *psb, int *par, ct_real *pa, ct_real *pc,
                                  ct_real ucv[3])
{
    ct_real u[3], v[3], w[3];
    _Pragma("GCC unroll 4")
    for (int i = 0; i < 3; i++) {
        u[i] = A2[i] - A1[i];
        v[i] = B2[i] - B1[i];
        w[i] = A1[i] - B1[i];
    }
    ct_real a = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    ct_real b = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    ct_real c = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    ct_real d = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    ct_real e = v[0] * w[0] + v[1] * w[1] + v[2] * w[2];
    ucv[0] = u[1] * v[2] - u[2] * v[1];
    ucv[1] = u[2] * v[0] - u[0] * v[2];
    ucv[2] = u[0] * v[1] - u[1] * v[0];
    ct_real den = ucv[0] * ucv[0] + ucv[1] * ucv[1] + ucv[2] * ucv[2];
    int parallel = !(den > CTI_EE_PAR_TOL * a * c);
    ct_real ai = 1 / (a > 0 ? a : 1), ci = 1 / (c > 0 ? c : 1);
    /* General case. */
    ct_real sg = (b * e - c * d) / (parallel ? 1 : den);
    /* Parallel: B1 and B2 on A's line are at -d/a and (b - d)/a. */
    ct_real q1 = -d * ai, q2 = (b - d) * ai;
    ct_real lo = q1 < q2 ? q1 : q2, hi = q1 < q2 ? q2 : q1;
    ct_real olo = lo > 0 ? lo : 0, ohi = hi < 1 ? hi : 1;
    ct_real sp = olo <= ohi ? (ct_real)0.5 * (olo + ohi) : (hi < 0 ? 0 : 1);
    ct_real s = cti_nr_clamp01(parallel ? sp : sg);
    ct_real t = cti_nr_clamp01((b * s + e) * ci);
    s = cti_nr_clamp01((b * t - d) * ai);
    /* The minimum is interior to both edges (found above) or has an end
     * point: the four end-point projections are candidates too, which
     * makes nearly parallel edges exact. Ties keep the earlier one. */
    ct_real bs = s, bt = t, bq = cti_ee_q(u, v, w, s, t);
    cti_ee_cand(u, v, w, 0, cti_nr_clamp01(e * ci), &bs, &bt, &bq);
    cti_ee_cand(u, v, w, 1, cti_nr_clamp01((e + b) * ci), &bs, &bt, &bq);
    cti_ee_cand(u, v, w, cti_nr_clamp01(-d * ai), 0, &bs, &bt, &bq);
    cti_ee_cand(u, v, w, cti_nr_clamp01((b - d) * ai), 1, &bs, &bt, &bq);
    *psa = bs;
    *psb = bt;
    *par = parallel;
    *pa = a;
    *pc = c;
}

int ct_narrow_edge_edge(ct_idx npair, const ct_idx *restrict ea, const ct_idx *restrict eb,
                        const ct_idx *restrict e1, const ct_idx *restrict e2,
                        const ct_real *restrict x, const ct_real *restrict y,
                        const ct_real *restrict z, const ct_real *restrict gap_edge,
                        ct_real gap, ct_real gap_max, const ct_edge_geo *out,
                        ct_narrow_stats *stats)
{
    if (npair < 0 || !out)
        return CT_ERR_ARG;
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (npair == 0)
        return CT_OK;
    if (!ea || !eb || !e1 || !e2 || !x || !y || !z || !out->dist || !out->pen || !out->nx ||
        !out->ny || !out->nz || !out->sa || !out->sb || !out->pax || !out->pay || !out->paz ||
        !out->pbx || !out->pby || !out->pbz || !out->gap || !out->flag)
        return CT_ERR_ARG;
    ct_real *restrict odist = out->dist, *restrict open = out->pen;
    ct_real *restrict onx = out->nx, *restrict ony = out->ny, *restrict onz = out->nz;
    ct_real *restrict osa = out->sa, *restrict osb = out->sb;
    ct_real *restrict opax = out->pax, *restrict opay = out->pay, *restrict opaz = out->paz;
    ct_real *restrict opbx = out->pbx, *restrict opby = out->pby, *restrict opbz = out->pbz;
    ct_real *restrict ogap = out->gap;
    uint8_t *restrict oflag = out->flag;
    ct_idx nblock = (ct_idx)((npair + CTI_NR_BLOCK - 1) / CTI_NR_BLOCK);
#pragma omp parallel for schedule(static)
    for (ct_idx bi = 0; bi < nblock; bi++) {
        ct_idx k0 = bi * CTI_NR_BLOCK, nb = CTI_MIN(npair - k0, CTI_NR_BLOCK);
        /* Gather the block's end points and gaps. */
        ct_real P[4][3][CTI_NR_BLOCK], G[CTI_NR_BLOCK];
        for (ct_idx j = 0; j < nb; j++) {
            ct_idx ia = ea[k0 + j], ib = eb[k0 + j];
            ct_idx v[4] = {e1[ia], e2[ia], e1[ib], e2[ib]};
            _Pragma("GCC unroll 4")
            for (int q = 0; q < 4; q++) {
                P[q][0][j] = x[v[q]];
                P[q][1][j] = y[v[q]];
                P[q][2][j] = z[v[q]];
            }
            ct_real ga = gap, gb = gap;
            if (gap_edge) {
                ga = gap_edge[ia];
                gb = gap_edge[ib];
                ga = (gap_max > 0 && ga > gap_max) ? gap_max : ga;
                gb = (gap_max > 0 && gb > gap_max) ? gap_max : gb;
            }
            G[j] = ga + gb;
        }
        CTI_NR_SIMD
        for (ct_idx j = 0; j < nb; j++) {
        ct_idx k = k0 + j;
        ct_real A1[3], A2[3], B1[3], B2[3];
        _Pragma("GCC unroll 4")
        for (int i = 0; i < 3; i++) {
            A1[i] = P[0][i][j];
            A2[i] = P[1][i][j];
            B1[i] = P[2][i][j];
            B2[i] = P[3][i][j];
        }
        ct_real g = G[j];
        ct_real zs = g - g;
        _Pragma("GCC unroll 4")
        for (int i = 0; i < 3; i++)
            zs += (A1[i] - A1[i]) + (A2[i] - A2[i]) + (B1[i] - B1[i]) + (B2[i] - B2[i]);
        /* Relative to A1 (accuracy far from the origin). */
        ct_real org[3];
        for (int i = 0; i < 3; i++) {
            org[i] = A1[i];
            A2[i] -= org[i];
            B1[i] -= org[i];
            B2[i] -= org[i];
            A1[i] = 0;
        }
        int nonfin = cti_nr_nonfinite(zs);
        ct_real s, t, aa, cc, ucv[3];
        int par;
        cti_ee_closest(A1, A2, B1, B2, &s, &t, &par, &aa, &cc, ucv);
        ct_real lm = aa > cc ? aa : cc, ls = aa < cc ? aa : cc;
        int degen = !(ls > CTI_NR_EDGE_TOL * CTI_NR_EDGE_TOL * lm);
        int bad = nonfin ? CT_NARROW_NONFINITE : (degen ? CT_NARROW_DEGENERATE : 0);
        ct_real Pa[3], Pb[3], r[3], ma[3];
        _Pragma("GCC unroll 4")
        for (int i = 0; i < 3; i++) {
            Pa[i] = A1[i] + s * (A2[i] - A1[i]);
            Pb[i] = B1[i] + t * (B2[i] - B1[i]);
            r[i] = Pa[i] - Pb[i];
            ma[i] = (ct_real)0.5 * ((A1[i] + A2[i]) - (B1[i] + B2[i]));
        }
        ct_real dist = CTI_SQRT(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        int touch = dist <= CTI_NR_ON_TOL * CTI_SQRT(lm);
        /* Touching: u x v, or for parallel edges u x (the axis along which u
         * is smallest), then oriented from B's midpoint towards A's. */
        ct_real u[3] = {A2[0] - A1[0], A2[1] - A1[1], A2[2] - A1[2]};
        ct_real ax = CTI_FABS(u[0]), ay = CTI_FABS(u[1]), az = CTI_FABS(u[2]);
        int kx = (ax <= ay) & (ax <= az), ky = (!kx) & (ay <= az);
        ct_real pcv[3] = {kx ? 0 : (ky ? -u[2] : u[1]), kx ? u[2] : (ky ? 0 : -u[0]),
                          kx ? -u[1] : (ky ? u[0] : 0)};
        ct_real tn[3];
        _Pragma("GCC unroll 4")
        for (int i = 0; i < 3; i++)
            tn[i] = par ? pcv[i] : ucv[i];
        ct_real tl = CTI_SQRT(tn[0] * tn[0] + tn[1] * tn[1] + tn[2] * tn[2]);
        ct_real ti = 1 / (tl > 0 ? tl : 1);
        ct_real om = tn[0] * ma[0] + tn[1] * ma[1] + tn[2] * ma[2];
        ct_real big = ((CTI_FABS(tn[0]) >= CTI_FABS(tn[1])) & (CTI_FABS(tn[0]) >= CTI_FABS(tn[2])))
                          ? tn[0]
                          : (CTI_FABS(tn[1]) >= CTI_FABS(tn[2]) ? tn[1] : tn[2]);
        ct_real sg = ((om < 0) | ((om == 0) & (big < 0))) ? -ti : ti;
        ct_real di = 1 / (touch ? 1 : dist);
        ct_real n[3];
        _Pragma("GCC unroll 4")
        for (int i = 0; i < 3; i++)
            n[i] = touch ? tn[i] * sg : r[i] * di;
        ct_real pen = g - dist;
        int clamped = (s <= 0) | (s >= 1) | (t <= 0) | (t >= 1);
        odist[k] = bad ? CT_NARROW_FAR : dist;
        open[k] = bad ? 0 : (pen > 0 ? pen : 0);
        onx[k] = bad ? 0 : n[0];
        ony[k] = bad ? 0 : n[1];
        onz[k] = bad ? 1 : n[2];
        osa[k] = bad ? 0 : s;
        osb[k] = bad ? 0 : t;
        opax[k] = bad ? 0 : Pa[0] + org[0];
        opay[k] = bad ? 0 : Pa[1] + org[1];
        opaz[k] = bad ? 0 : Pa[2] + org[2];
        opbx[k] = bad ? 0 : Pb[0] + org[0];
        opby[k] = bad ? 0 : Pb[1] + org[1];
        opbz[k] = bad ? 0 : Pb[2] + org[2];
        ogap[k] = nonfin ? 0 : g;
        oflag[k] = (uint8_t)(bad ? bad
                                 : ((clamped ? CT_NARROW_OUTSIDE : 0) |
                                    (par ? CT_NARROW_PARALLEL : 0)));
        }
    }
    if (stats) {
        int64_t act = 0, dg = 0, nf = 0, os = 0;
#pragma omp parallel for schedule(static) reduction(+ : act, dg, nf, os)
        for (ct_idx k = 0; k < npair; k++) {
            act += open[k] > 0;
            dg += (oflag[k] & CT_NARROW_DEGENERATE) != 0;
            nf += (oflag[k] & CT_NARROW_NONFINITE) != 0;
            os += (oflag[k] & CT_NARROW_OUTSIDE) != 0;
        }
        stats->active = act;
        stats->degenerate = dg;
        stats->nonfinite = nf;
        stats->outside = os;
    }
    return CT_OK;
}

int ct_edge_edge_forces(ct_idx npair, const ct_real *restrict fmag,
                        const ct_real *restrict nx, const ct_real *restrict ny,
                        const ct_real *restrict nz, const ct_real *restrict sa,
                        const ct_real *restrict sb, ct_real *restrict fx,
                        ct_real *restrict fy, ct_real *restrict fz)
{
    if (npair < 0)
        return CT_ERR_ARG;
    if (npair == 0)
        return CT_OK;
    if (!fmag || !nx || !ny || !nz || !sa || !sb || !fx || !fy || !fz)
        return CT_ERR_ARG;
    ct_idx nblock = (ct_idx)((npair + CTI_NR_BLOCK - 1) / CTI_NR_BLOCK);
#pragma omp parallel for schedule(static)
    for (ct_idx bi = 0; bi < nblock; bi++) {
        ct_idx k0 = bi * CTI_NR_BLOCK, k1 = CTI_MIN(npair, k0 + CTI_NR_BLOCK);
        CTI_NR_SIMD
        for (ct_idx k = k0; k < k1; k++) {
            ct_real F = fmag[k];
            ct_real wa2 = sa[k], wa1 = 1 - wa2, wb2 = sb[k], wb1 = 1 - wb2;
            ct_real Fx = F * nx[k], Fy = F * ny[k], Fz = F * nz[k];
            fx[4 * k + 0] = wa1 * Fx;
            fx[4 * k + 1] = wa2 * Fx;
            fx[4 * k + 2] = -(wb1 * Fx);
            fx[4 * k + 3] = -(wb2 * Fx);
            fy[4 * k + 0] = wa1 * Fy;
            fy[4 * k + 1] = wa2 * Fy;
            fy[4 * k + 2] = -(wb1 * Fy);
            fy[4 * k + 3] = -(wb2 * Fy);
            fz[4 * k + 0] = wa1 * Fz;
            fz[4 * k + 1] = wa2 * Fz;
            fz[4 * k + 2] = -(wb1 * Fz);
            fz[4 * k + 3] = -(wb2 * Fz);
        }
    }
    return CT_OK;
}
