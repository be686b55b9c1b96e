/*
 * kinematics.c -- the relative velocity at the contact point, which the
 * damping, the friction and the time step read: of a node against a segment
 * (ct_relative_velocity) and of two edges at their closest points
 * (ct_relative_velocity_edge). Both copy the velocities of a sub-block's
 * nodes into stack arrays with scalar loads, then run one vector loop over
 * them with unit stride (the reason is the comment on CTI_RELVEL_SUB).
 */
#include "pair_force_body.h"

/* Pairs per sub-block of the relative velocity: the velocities of its
 * pairs' five nodes are first copied into stack arrays (15 of them, 23 KB
 * in double, in L1) with scalar loads, then one vector loop reads them with
 * unit stride. Vectorised directly, the loop's 15 indexed loads a pair
 * become vector gathers, which this hardware (AMD Zen 4) runs several times
 * slower than the scalar loads they replace (the narrow phase, see
 * narrow_internal.h, measured the same). */
#define CTI_RELVEL_SUB 192

/* The velocities of pairs [i0, i1) (i1 - i0 <= CTI_RELVEL_SUB) into w,
 * two to an entry (CTI_PUT2), j = k - i0: w[c][2 j], w[c][2 j + 1] the x
 * and y components of node c of pair k (c = 0: the secondary node, 1..4
 * the segment's corners), w[5] the z components of nodes 0 and 1, w[6]
 * of nodes 2 and 3, w[7][j] of node 4. Loads scalar on purpose. */
CTI_NOVEC static void cti_relvel_fetch(int64_t i0, int64_t i1, const ct_idx *restrict node,
                                       const ct_idx *restrict s1, const ct_idx *restrict s2,
                                       const ct_idx *restrict s3, const ct_idx *restrict s4,
                                       const ct_real *restrict vx, const ct_real *restrict vy,
                                       const ct_real *restrict vz,
                                       ct_real (*restrict w)[2 * CTI_RELVEL_SUB])
{
    ct_real *const d[8] = {w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7]};
    CTI_NOVEC_LOOP
    for (int64_t k = i0; k < i1; k++)
        cti_put5(d, (ct_idx)(k - i0), vx, vy, vz, node[k], s1[k], s2[k], s3[k], s4[k]);
}

/* One block [i0, i1) of ct_relative_velocity, in sub-blocks; has_m
 * constant after inlining. */
static inline __attribute__((always_inline)) void
cti_relvel_block(int64_t i0, int64_t i1, const ct_idx *restrict node,
                 const ct_idx *restrict s1, const ct_idx *restrict s2,
                 const ct_idx *restrict s3, const ct_idx *restrict s4,
                 const ct_real *restrict h1, const ct_real *restrict h2,
                 const ct_real *restrict h3, const ct_real *restrict h4,
                 const ct_real *restrict nx, const ct_real *restrict ny,
                 const ct_real *restrict nz, const ct_real *restrict vx,
                 const ct_real *restrict vy, const ct_real *restrict vz,
                 const ct_real *restrict m, ct_real *restrict rx, ct_real *restrict ry,
                 ct_real *restrict rz, ct_real *restrict vn, ct_real *restrict mm,
                 const int has_m)
{
    /* The velocities two to an entry (CTI_PUT2): (x, y) of the node and
     * of the four corners, (z of the node, z of corner 1), (z2, z3); z4
     * alone in w[7]. */
    _Alignas(64) ct_real w[8][2 * CTI_RELVEL_SUB];
    for (int64_t b0 = i0; b0 < i1; b0 += CTI_RELVEL_SUB) {
        const int64_t b1 = i1 - b0 < CTI_RELVEL_SUB ? i1 : b0 + CTI_RELVEL_SUB;
        cti_relvel_fetch(b0, b1, node, s1, s2, s3, s4, vx, vy, vz, w);
        const ct_real *restrict p2 = w[0], *restrict a2 = w[1], *restrict b2 = w[2];
        const ct_real *restrict c2 = w[3], *restrict e2 = w[4], *restrict z01 = w[5];
        const ct_real *restrict z23 = w[6], *restrict ez = w[7];
#pragma omp simd
        for (int64_t k = b0; k < b1; k++) {
            const int64_t j = k - b0, x = 2 * j, y = 2 * j + 1;
            ct_real ux = p2[x] - (h1[k] * a2[x] + h2[k] * b2[x] + h3[k] * c2[x] + h4[k] * e2[x]);
            ct_real uy = p2[y] - (h1[k] * a2[y] + h2[k] * b2[y] + h3[k] * c2[y] + h4[k] * e2[y]);
            ct_real uz = z01[x] -
                         (h1[k] * z01[y] + h2[k] * z23[x] + h3[k] * z23[y] + h4[k] * ez[j]);
            rx[k] = ux;
            ry[k] = uy;
            rz[k] = uz;
            vn[k] = ux * nx[k] + uy * ny[k] + uz * nz[k];
        }
        if (has_m) {
#pragma omp simd
            for (int64_t k = b0; k < b1; k++)
                mm[k] = h1[k] * m[s1[k]] + h2[k] * m[s2[k]] + h3[k] * m[s3[k]] +
                        h4[k] * m[s4[k]];
        }
    }
}

/* Pairs per block of the relative velocity loop. */
#define CTI_RELVEL_BLOCK 2048

int ct_relative_velocity(ct_idx npair, const ct_idx *node, const ct_idx *s1, const ct_idx *s2,
                         const ct_idx *s3, const ct_idx *s4, const ct_real *h1,
                         const ct_real *h2, const ct_real *h3, const ct_real *h4,
                         const ct_real *nx, const ct_real *ny, const ct_real *nz,
                         const ct_real *vx, const ct_real *vy, const ct_real *vz,
                         const ct_real *m, ct_real *rx, ct_real *ry, ct_real *rz, ct_real *vn,
                         ct_real *mm)
{
    if (npair < 0 || (!m) != (!mm))
        return CT_ERR_ARG;
    if (npair > 0 && (!node || !s1 || !s2 || !s3 || !s4 || !h1 || !h2 || !h3 || !h4 || !nx ||
                      !ny || !nz || !vx || !vy || !vz || !rx || !ry || !rz || !vn))
        return CT_ERR_ARG;
    const int64_t nblk = ((int64_t)npair + CTI_RELVEL_BLOCK - 1) / CTI_RELVEL_BLOCK;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_RELVEL_BLOCK, npair, &i0, &i1);
        if (m)
            cti_relvel_block(i0, i1, node, s1, s2, s3, s4, h1, h2, h3, h4, nx, ny, nz, vx, vy,
                             vz, m, rx, ry, rz, vn, mm, 1);
        else
            cti_relvel_block(i0, i1, node, s1, s2, s3, s4, h1, h2, h3, h4, nx, ny, nz, vx, vy,
                             vz, NULL, rx, ry, rz, vn, NULL, 0);
    });
    return CT_OK;
}

/* The velocities (and masses) of edge pairs [i0, i1) into w, in
 * cti_put4's layout, j = k - i0: w[c][2 j], w[c][2 j + 1] the x and y
 * components of node c (0, 1 the first edge's ends, 2, 3 the second's),
 * w[4] the z components of nodes 0 and 1, w[5] of nodes 2 and 3; with m,
 * w[6] the masses of nodes 0 and 1, w[7] of nodes 2 and 3. */
CTI_NOVEC static void cti_relvel_edge_fetch(int64_t i0, int64_t i1, const ct_idx *restrict a1,
                                            const ct_idx *restrict a2,
                                            const ct_idx *restrict b1,
                                            const ct_idx *restrict b2,
                                            const ct_real *restrict vx,
                                            const ct_real *restrict vy,
                                            const ct_real *restrict vz,
                                            const ct_real *restrict m,
                                            ct_real (*restrict w)[2 * CTI_RELVEL_SUB])
{
    ct_real *const d[6] = {w[0], w[1], w[2], w[3], w[4], w[5]};
    CTI_NOVEC_LOOP
    for (int64_t k = i0; k < i1; k++)
        cti_put4(d, (ct_idx)(k - i0), vx, vy, vz, a1[k], a2[k], b1[k], b2[k]);
    if (m) {
        CTI_NOVEC_LOOP
        for (int64_t k = i0; k < i1; k++) {
            CTI_PUT2(w[6], k - i0, m[a1[k]], m[a2[k]]);
            CTI_PUT2(w[7], k - i0, m[b1[k]], m[b2[k]]);
        }
    }
}

/* One block [i0, i1) of ct_relative_velocity_edge, in sub-blocks. has_r,
 * has_u2 and has_m are constants after inlining. The sums are formed in
 * the order ((1 - sa) v(a1) + sa v(a2)) - (1 - sb) v(b1) - sb v(b2). */
static inline __attribute__((always_inline)) void
cti_relvel_edge_block(int64_t i0, int64_t i1, const ct_idx *restrict a1,
                      const ct_idx *restrict a2, const ct_idx *restrict b1,
                      const ct_idx *restrict b2, const ct_real *restrict sa,
                      const ct_real *restrict sb, const ct_real *restrict nx,
                      const ct_real *restrict ny, const ct_real *restrict nz,
                      const ct_real *restrict vx, const ct_real *restrict vy,
                      const ct_real *restrict vz, const ct_real *restrict m,
                      ct_real *restrict rx, ct_real *restrict ry, ct_real *restrict rz,
                      ct_real *restrict vn, ct_real *restrict u2, ct_real *restrict ma,
                      ct_real *restrict mb, const int has_r, const int has_u2, const int has_m)
{
    _Alignas(64) ct_real w[8][2 * CTI_RELVEL_SUB];
    for (int64_t b0 = i0; b0 < i1; b0 += CTI_RELVEL_SUB) {
        const int64_t b1e = i1 - b0 < CTI_RELVEL_SUB ? i1 : b0 + CTI_RELVEL_SUB;
        cti_relvel_edge_fetch(b0, b1e, a1, a2, b1, b2, vx, vy, vz, has_m ? m : NULL, w);
        const ct_real *restrict p2 = w[0], *restrict q2 = w[1], *restrict r2 = w[2];
        const ct_real *restrict s2 = w[3], *restrict z01 = w[4], *restrict z23 = w[5];
        const ct_real *restrict m01 = w[6], *restrict m23 = w[7];
#pragma omp simd
        for (int64_t k = b0; k < b1e; k++) {
            const int64_t j = k - b0, x = 2 * j, y = 2 * j + 1;
            const ct_real ua = 1 - sa[k], ub = 1 - sb[k];
            ct_real ux = ua * p2[x] + sa[k] * q2[x] - ub * r2[x] - sb[k] * s2[x];
            ct_real uy = ua * p2[y] + sa[k] * q2[y] - ub * r2[y] - sb[k] * s2[y];
            ct_real uz = ua * z01[x] + sa[k] * z01[y] - ub * z23[x] - sb[k] * z23[y];
            vn[k] = ux * nx[k] + uy * ny[k] + uz * nz[k];
            if (has_r) {
                rx[k] = ux;
                ry[k] = uy;
                rz[k] = uz;
            }
            if (has_u2)
                u2[k] = ux * ux + uy * uy + uz * uz;
            if (has_m) {
                ma[k] = ua * m01[x] + sa[k] * m01[y];
                mb[k] = ub * m23[x] + sb[k] * m23[y];
            }
        }
    }
}

/* One block of ct_relative_velocity_edge, its loop chosen by variant: bit 0
 * (rx, ry, rz) asked, bit 1 u2, bit 2 the masses. */
static void cti_relvel_edge_range(int variant, int64_t i0, int64_t i1, const ct_idx *a1,
                                  const ct_idx *a2, const ct_idx *b1, const ct_idx *b2,
                                  const ct_real *sa, const ct_real *sb, const ct_real *nx,
                                  const ct_real *ny, const ct_real *nz, const ct_real *vx,
                                  const ct_real *vy, const ct_real *vz, const ct_real *m,
                                  ct_real *rx, ct_real *ry, ct_real *rz, ct_real *vn,
                                  ct_real *u2, ct_real *ma, ct_real *mb)
{
#define CTI_RVE_CASE(V)                                                                        \
    case V:                                                                                    \
        cti_relvel_edge_block(i0, i1, a1, a2, b1, b2, sa, sb, nx, ny, nz, vx, vy, vz, m, rx,  \
                              ry, rz, vn, u2, ma, mb, (V)&1, ((V) >> 1) & 1, ((V) >> 2) & 1);  \
        break;
    switch (variant) { CTI_CASES8(CTI_RVE_CASE) }
#undef CTI_RVE_CASE
}

int ct_relative_velocity_edge(ct_idx npair, const ct_idx *a1, const ct_idx *a2,
                              const ct_idx *b1, const ct_idx *b2, const ct_real *sa,
                              const ct_real *sb, const ct_real *nx, const ct_real *ny,
                              const ct_real *nz, const ct_real *vx, const ct_real *vy,
                              const ct_real *vz, const ct_real *m, ct_real *rx, ct_real *ry,
                              ct_real *rz, ct_real *vn, ct_real *u2, ct_real *ma, ct_real *mb)
{
    if (npair < 0 || (!m) != (!ma) || (!m) != (!mb) || (!rx) != (!ry) || (!rx) != (!rz))
        return CT_ERR_ARG;
    if (npair > 0 && (!a1 || !a2 || !b1 || !b2 || !sa || !sb || !nx || !ny || !nz || !vx ||
                      !vy || !vz || !vn))
        return CT_ERR_ARG;
    const int variant = (rx != NULL) | (u2 != NULL) << 1 | (m != NULL) << 2;
    const int64_t nblk = ((int64_t)npair + CTI_RELVEL_BLOCK - 1) / CTI_RELVEL_BLOCK;
    CTI_PAR_FOR(npair > CTI_PAR_MIN, (schedule(static)),
    for (int64_t b = 0; b < nblk; b++) {
        int64_t i0, i1;
        cti_block_range(b, CTI_RELVEL_BLOCK, npair, &i0, &i1);
        cti_relvel_edge_range(variant, i0, i1, a1, a2, b1, b2, sa, sb, nx, ny, nz, vx, vy, vz,
                              m, rx, ry, rz, vn, u2, ma, mb);
    });
    return CT_OK;
}
