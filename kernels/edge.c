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

/* The end points A1, A2, B1, B2 of n pairs into C, two values to an entry
 * (CTI_PUT2): (x, y) of each in turn, then (z of A1, z of A2), (z of B1,
 * z of B2); loads scalar (see cti_nr_fetch). */
CTI_NOVEC static void cti_ee_fetch(const ct_idx *restrict ea, const ct_idx *restrict eb,
                                      const ct_idx *restrict e1, const ct_idx *restrict e2,
                                      const ct_real *restrict x, const ct_real *restrict y,
                                      const ct_real *restrict z, ct_idx n,
                                      ct_real (*restrict C)[2 * CTI_EE_BLOCK])
{
    ct_real *const d[6] = {C[0], C[1], C[2], C[3], C[4], C[5]};
    CTI_NOVEC_LOOP
    for (ct_idx j = 0; j < n; j++) {
        ct_idx ia = ea[j], ib = eb[j];
        cti_put4(d, j, x, y, z, e1[ia], e2[ia], e1[ib], e2[ib]);
    }
}

int ct_narrow_edge_edge(ct_idx npair, const ct_idx *restrict ea, const ct_idx *restrict eb,
                        const ct_idx *restrict e1, const ct_idx *restrict e2,
                        const ct_real *restrict x, const ct_real *restrict y,
                        const ct_real *restrict z, const ct_real *restrict gap_edge,
                        ct_real gap, ct_real gap_max, const ct_edge_geo *out,
                        ct_narrow_stats *stats)
{
    /* The scalar gap: finite and >= 0 (as the node-segment phase); a NaN
     * cap is not "no cap". */
    if (npair < 0 || !out || !(gap >= 0) || !(gap <= CTI_HUGE) || gap_max != gap_max)
        return CT_ERR_ARG;
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (npair == 0)
        return CT_OK;
    const int npts = !out->pax + !out->pay + !out->paz + !out->pbx + !out->pby + !out->pbz;
    if (!ea || !eb || !e1 || !e2 || !x || !y || !z || !out->dist || !out->pen || !out->nx ||
        !out->ny || !out->nz || !out->sa || !out->sb || (npts != 0 && npts != 6) ||
        !out->gap || !out->flag)
        return CT_ERR_ARG;
    const ct_real *restrict open = out->pen;
    uint8_t *restrict oflag = out->flag;
    ct_idx nblock = (ct_idx)((npair + CTI_EE_BLOCK - 1) / CTI_EE_BLOCK);
    /* A call of one block runs without a thread team (cheaper). */
    CTI_PAR_FOR(nblock > 1, (schedule(static)),
    for (ct_idx bi = 0; bi < nblock; bi++) {
        ct_idx k0 = bi * CTI_EE_BLOCK, nb = CTI_MIN(npair - k0, CTI_EE_BLOCK);
        /* The block's gaps, and its end points copied by a scalar loop into
         * contiguous arrays (cheaper than vector gathers, and it keeps the
         * 32-bit indices out of the vector loop: see narrow_internal.h). */
        _Alignas(64) ct_real G[CTI_EE_BLOCK];
        _Alignas(64) cti_nr_int F[CTI_EE_BLOCK];
        _Alignas(64) ct_real C[6][2 * CTI_EE_BLOCK];
        cti_ee_fetch(ea + k0, eb + k0, e1, e2, x, y, z, nb, C);
        for (ct_idx j = 0; j < nb; j++) {
            ct_real ga = gap, gb = gap;
            if (gap_edge) {
                ga = gap_edge[ea[k0 + j]];
                gb = gap_edge[eb[k0 + j]];
                ga = (gap_max > 0 && ga > gap_max) ? gap_max : ga;
                gb = (gap_max > 0 && gb > gap_max) ? gap_max : gb;
            }
            G[j] = ga + gb;
        }
        cti_ee_block(nb, G, C, out, k0, F);
        cti_nr_flags_out(F, oflag + k0, nb);
    });
    if (stats) {
        int64_t act = 0, dg = 0, nf = 0, os = 0;
        CTI_PAR_FOR(nblock > 1, (schedule(static) reduction(+ : act, dg, nf, os)),
        for (ct_idx k = 0; k < npair; k++) {
            act += open[k] > 0;
            dg += (oflag[k] & CT_NARROW_DEGENERATE) != 0;
            nf += (oflag[k] & CT_NARROW_NONFINITE) != 0;
            os += (oflag[k] & CT_NARROW_OUTSIDE) != 0;
        });
        stats->active = act;
        stats->degenerate = dg;
        stats->nonfinite = nf;
        stats->outside = os;
    }
    return CT_OK;
}

/* Pairs [k0, k1) of ct_edge_edge_forces; 1 when one of the twelve nodal
 * forces is NaN or infinite (ct_internal.h): every input reaches them (0
 * times an infinite value is NaN), but a NaN or negative magnitude, -inf
 * too, which gives no force. */
static int cti_ee_forces_block(ct_idx k0, ct_idx k1, const ct_real *restrict fmag,
                               const ct_real *restrict nx, const ct_real *restrict ny,
                               const ct_real *restrict nz, const ct_real *restrict sa,
                               const ct_real *restrict sb, ct_real *restrict fx,
                               ct_real *restrict fy, ct_real *restrict fz)
{
    ct_real bad = 0;
#pragma omp simd reduction(+ : bad)
    for (ct_idx k = k0; k < k1; k++) {
        const ct_real F0 = fmag[k];
        ct_real F = F0 > 0 ? F0 : 0;
        ct_real wa2 = sa[k], wa1 = 1 - wa2, wb2 = sb[k], wb1 = 1 - wb2;
        ct_real Fx = F * nx[k], Fy = F * ny[k], Fz = F * nz[k];
        ct_real x0 = wa1 * Fx, x1 = wa2 * Fx, x2 = -(wb1 * Fx), x3 = -(wb2 * Fx);
        ct_real y0 = wa1 * Fy, y1 = wa2 * Fy, y2 = -(wb1 * Fy), y3 = -(wb2 * Fy);
        ct_real z0 = wa1 * Fz, z1 = wa2 * Fz, z2 = -(wb1 * Fz), z3 = -(wb2 * Fz);
        fx[4 * k + 0] = x0;
        fx[4 * k + 1] = x1;
        fx[4 * k + 2] = x2;
        fx[4 * k + 3] = x3;
        fy[4 * k + 0] = y0;
        fy[4 * k + 1] = y1;
        fy[4 * k + 2] = y2;
        fy[4 * k + 3] = y3;
        fz[4 * k + 0] = z0;
        fz[4 * k + 1] = z1;
        fz[4 * k + 2] = z2;
        fz[4 * k + 3] = z3;
        bad += (((CTI_NF(x0) + CTI_NF(x1)) + (CTI_NF(x2) + CTI_NF(x3))) +
                ((CTI_NF(y0) + CTI_NF(y1)) + (CTI_NF(y2) + CTI_NF(y3))) +
                ((CTI_NF(z0) + CTI_NF(z1)) + (CTI_NF(z2) + CTI_NF(z3))));
    }
    return !(bad == 0);
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
    ct_idx nblock = (ct_idx)((npair + CTI_EE_BLOCK - 1) / CTI_EE_BLOCK);
    int bad = 0;
    CTI_PAR_FOR(nblock > 1, (schedule(static) reduction(| : bad)),
    for (ct_idx bi = 0; bi < nblock; bi++)
        bad |= cti_ee_forces_block(bi * CTI_EE_BLOCK, CTI_MIN(npair, (bi + 1) * CTI_EE_BLOCK),
                                   fmag, nx, ny, nz, sa, sb, fx, fy, fz);
    );
    return bad ? CT_ERR_NONFINITE : CT_OK;
}
