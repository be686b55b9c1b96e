/*
 * ct_narrow.h -- narrow phase, part of contact.h: node-to-segment projection
 * (triangles; quadrangles by three methods) and edge-to-edge closest points.
 * DESIGN.md section 6; seed "Auto Contacts", Contact Detection.
 *
 * Every kernel works on a list of candidate pairs (structure of arrays) and
 * writes one result per pair into caller-allocated arrays (ct_calloc, at
 * least npair elements each). Results do not depend on the thread count.
 * Indices must be valid (the search produced them); they are not checked.
 *
 * Node-segment conventions:
 *  - A segment is n1 n2 n3 n4, a triangle when n4 == n3 (always projected by
 *    the analytic triangle method, whatever the quad method).
 *  - Gap of a pair: with no per-node and no per-segment gap (both NULL) it is
 *    the scalar `gap`. Otherwise it is max(gap, g_s + g_m), where
 *    g_s = min(gap_node[node], gap_max_s) (0 when gap_node is NULL) and
 *    g_m = min(gap_seg[seg], gap_max_m) (0 when gap_seg is NULL); a cap <= 0
 *    means no cap. The scalar then plays the part of TYPE7's Gapmin.
 *  - Two-sided (shells): D = |p - c| >= 0, normal (p - c)/D, pen = max(0,
 *    gap - D); a node on the mid-surface (D below 1e-14, single 1e-6, times
 *    the segment size) gets the segment normal.
 *  - One-sided (oriented solid surfaces): the side is the sign of
 *    (p - c).N, N the segment's unit normal at c (the sign of the
 *    tetrahedron volume of seed 000). In front: as two-sided. Behind, with
 *    the node's projection inside the segment's footprint: D = -|p - c|,
 *    normal N, pen = gap + |p - c| (flag CT_NARROW_BEHIND). Behind but
 *    outside the footprint (the closest point is on the boundary): no
 *    contact through this segment, pen = 0, normal N, D = -|p - c| (flags
 *    BEHIND | OUTSIDE); the neighbouring segment whose footprint holds the
 *    node reports it. "Inside" tolerates 1e-10 (single 1e-5) in the
 *    segment's parameters, so a node under a shared edge is inside both.
 *  - The normal points from the segment towards the node: the force on the
 *    node is +pen*K*n and the segment node i receives -h_i*pen*K*n.
 *  - Skipped pairs (degenerate segment, or a NaN/Inf coordinate or gap):
 *    flag set, pen = 0, dist = CT_NARROW_FAR, normal (0, 0, 1), contact point
 *    (0, 0, 0), weights 0. A segment is degenerate when one of its triangles
 *    (a triangle itself; for quads the four corner triangles, or the four
 *    centroid triangles of CT_QUAD_4TRI) has an area at most 1e-12 (single
 *    1e-6) times the square of the segment's longest edge: zero area,
 *    needles, coincident nodes.
 *  - Needles short of that: a node's closest point on a triangle of longest
 *    edge L and height h is found to about eps L^2 / h on its face (eps
 *    the precision's; measured within 1e-6 h at L/h = 1e6 in double, 1e-4 h
 *    at 1e2 in single) and to eps L beside its short edge
 *    (tests/test_api_extremes.c). Mesh needles finer than that.
 */
#ifndef CT_NARROW_H
#define CT_NARROW_H

#ifdef __cplusplus
extern "C" {
#endif

/* How a quadrangle is projected on. */
typedef enum ct_quad_method {
    /* Four triangles around the centroid; the closest point of their union.
     * The centroid's weight is shared 1/4 to each corner. */
    CT_QUAD_4TRI = 0,
    /* Exact bilinear isoparametric projection: Newton on (s, t) minimising
     * |x(s,t) - p|^2 (full Hessian when positive definite, Gauss-Newton
     * otherwise), started from the least-squares (s, t) of the affine part
     * x0 + s a1 + t a2 (exact on a parallelogram), converged to 1e-12
     * (single 1e-5) in |ds| + |dt|; the closest
     * point of the four straight boundary edges is taken when it is closer
     * or the minimum lies outside [-1,1]^2. After 30 iterations without
     * convergence the best of the last iterate (clamped) and the boundary is
     * kept and CT_NARROW_FALLBACK set. Newton finds the minimum it starts
     * in: on quads whose bilinear map folds over itself (a corner pushed
     * across the opposite diagonal, far beyond any usable element) it may
     * stop at a local minimum, farther than the surface's closest point,
     * without the flag (seen only on such random quads, never on convex
     * ones warped up to twice their size). */
    CT_QUAD_NEWTON,
    /* Closed form (TYPE3/5 style): p is projected on the mean plane
     * (normal (x3-x1) x (x4-x2)); with d_41, d_23, d_12, d_34 the signed
     * in-plane distances of that point to the lines of the edges 4-1, 2-3,
     * 1-2, 3-4 (positive inside),
     *   s = (d_41 - d_23) / (d_41 + d_23),  t = (d_12 - d_34) / (d_12 + d_34),
     * the affine coordinates on a parallelogram, an approximation otherwise.
     * The point is x(s, t) on the bilinear surface when (s, t) is inside
     * [-1,1]^2, else the closest point of the four boundary edges. */
    CT_QUAD_CLOSED,
    CT_QUAD_NMETHOD
} ct_quad_method;

/* Name ("4tri", "newton", "closed") and inverse (-1 when unknown). */
const char *ct_quad_method_name(ct_quad_method m);
int ct_quad_method_from_name(const char *name);

/* Per-pair flags. */
enum ct_narrow_flag {
    CT_NARROW_DEGENERATE = 1, /* skipped: degenerate segment or edge */
    CT_NARROW_NONFINITE = 2,  /* skipped: NaN/Inf coordinate or gap */
    CT_NARROW_FALLBACK = 4,   /* Newton did not converge; fallback used */
    CT_NARROW_BEHIND = 8,     /* one-sided: the node is behind the segment */
    CT_NARROW_OUTSIDE = 16,   /* the closest point is on the segment's boundary
                                 (edge-edge: a parameter was clamped) */
    CT_NARROW_PARALLEL = 32   /* edge-edge: parallel edges */
};

/* Distance reported for skipped pairs. */
#ifdef CT_SINGLE
#define CT_NARROW_FAR 1.0e30f
#else
#define CT_NARROW_FAR 1.0e30
#endif

/* Node-segment results, one element per pair, caller-allocated. */
typedef struct ct_contact_geo {
    ct_real *dist, *pen;        /* distance D (signed when one-sided), penetration */
    ct_real *nx, *ny, *nz;      /* unit normal, from the segment towards the node */
    ct_real *cx, *cy, *cz;      /* contact point on the segment */
    ct_real *h1, *h2, *h3, *h4; /* weights of n1..n4 (h4 = 0 for a triangle), sum 1 */
    ct_real *gap;               /* the gap of the pair */
    uint8_t *flag;              /* CT_NARROW_* bits */
} ct_contact_geo;

/* Counts over one call (pairs with pen > 0 are active). */
typedef struct ct_narrow_stats {
    int64_t active, fallbacks, degenerate, nonfinite, behind, outside;
} ct_narrow_stats;

/*
 * Node-segment narrow phase over npair candidate pairs (node[k], seg[k]).
 * n1..n4 are indexed by segment, x/y/z by node. Returns CT_OK, or
 * CT_ERR_ARG for a NULL array, a negative count, a bad method, a scalar gap
 * that is negative, NaN or infinite, or a NaN cap. stats may be NULL.
 */
int ct_narrow_node_segment(ct_idx npair, const ct_idx *node,
                           const ct_idx *seg, const ct_idx *n1,
                           const ct_idx *n2, const ct_idx *n3,
                           const ct_idx *n4, const ct_real *x,
                           const ct_real *y, const ct_real *z,
                           const ct_real *gap_node, const ct_real *gap_seg,
                           ct_real gap, ct_real gap_max_s, ct_real gap_max_m,
                           ct_quad_method method, int two_sided, const ct_contact_geo *out,
                           ct_narrow_stats *stats);

/*
 * The same narrow phase over a selection of a pair list whose segment
 * nodes are given per pair (s1..s4[k] = n1..n4[seg[k]], as ct_asm_seg_slots
 * makes them once per list): pair j of the call is pair sel[j] of the list
 * (node node[sel[j]], corners s1..s4[sel[j]]) and its results go to element
 * j of out; one gap for every pair. For a contact cycle that evaluates part
 * of its candidates: the corners are read through one index instead of the
 * segment number, and the selected pairs need no copy. Returns as
 * ct_narrow_node_segment (sel must be given when npair > 0).
 */
int ct_narrow_node_slots(ct_idx npair, const ct_idx *sel, const ct_idx *node, const ct_idx *s1,
                         const ct_idx *s2, const ct_idx *s3, const ct_idx *s4,
                         const ct_real *x, const ct_real *y, const ct_real *z, ct_real gap,
                         ct_quad_method method, int two_sided, const ct_contact_geo *out,
                         ct_narrow_stats *stats);

/*
 * Packed node coordinates for the narrow phase: ct_coords_pack writes node
 * i's (x[i], y[i], z[i], 0) to xyzw[4 i..4 i + 3]; xyzw (4 n reals,
 * caller-allocated, e.g. ct_calloc(4 n, sizeof(ct_real))) must be aligned to 4 sizeof(ct_real)
 * bytes (32 in double, 16 in single). The _packed entry points take xyzw
 * in place of x, y, z (the fourth value is not read) and give the same
 * results, bit for bit, as ct_narrow_node_segment and ct_narrow_node_slots
 * on those x, y, z: they load a node's coordinates with one vector load
 * instead of three scalar loads from three arrays (DESIGN-CHANGES §6). A
 * code that keeps positions as x, y, z packs them once per step (a pass
 * over the nodes, about 1-2 ns a node) and hands xyzw to every narrow-phase
 * call of that step. CT_ERR_ARG for a negative count, a NULL array or a
 * misaligned xyzw (nothing is checked for n == 0 or npair == 0); the
 * _packed entry points otherwise return as the unpacked ones.
 */
int ct_coords_pack(ct_idx n, const ct_real *x, const ct_real *y, const ct_real *z,
                   ct_real *xyzw);
int ct_narrow_node_segment_packed(ct_idx npair, const ct_idx *node, const ct_idx *seg,
                                  const ct_idx *n1, const ct_idx *n2, const ct_idx *n3,
                                  const ct_idx *n4, const ct_real *xyzw,
                                  const ct_real *gap_node, const ct_real *gap_seg, ct_real gap,
                                  ct_real gap_max_s, ct_real gap_max_m, ct_quad_method method,
                                  int two_sided, const ct_contact_geo *out,
                                  ct_narrow_stats *stats);
int ct_narrow_node_slots_packed(ct_idx npair, const ct_idx *sel, const ct_idx *node,
                                const ct_idx *s1, const ct_idx *s2, const ct_idx *s3,
                                const ct_idx *s4, const ct_real *xyzw, ct_real gap,
                                ct_quad_method method, int two_sided,
                                const ct_contact_geo *out, ct_narrow_stats *stats);

/*
 * Which of each secondary node's candidate pairs carry its contact, after
 * the node-segment narrow phase; pairs in ascending node order (a search's
 * canonical order; CT_ERR_ARG otherwise, the results then unusable). Without it a node over a vertex shared by four
 * segments gets four penalty forces, and one in a dent none (select.c):
 *  - the pair with the smallest |dist| (skipping degenerate and non-finite
 *    ones; ties to the first in list order) carries the node; one-sided,
 *    behind its segment and outside its footprint, with the node within 60
 *    degrees of the inward normal (a dent), it gets pen = gap + r (r the
 *    distance to its contact point);
 *  - two_sided: also the closest penetrating pair whose normal opposes the
 *    first one's (a node pinched between two layers);
 *  - every other pair gets pen = 0 (geo->pen is rewritten).
 * carry[k] receives 1 for the carrying pairs (penetrating or not: their
 * springs set the nodal step), 0 for the others. A code that keeps
 * per-pair states (friction history, last penetration) gives p_prev, last
 * step's penetration of each pair of this list, and handoff: handoff[k] is
 * the pair of the same node and side that carried last step (p_prev > 0)
 * and carries no more, the first in list order, when carrier k did not
 * carry last step itself; else -1. Its states belong to k now (the node's
 * contact moved to the next segment). p_prev and handoff may be NULL;
 * *active (may be NULL) receives the carrying pairs with pen > 0. Node
 * indices are not range-checked (they come from a search). CT_ERR_ARG for
 * a NULL array or a negative count.
 */
int ct_select_pairs(ct_idx npair, const ct_idx *node, const ct_real *x, const ct_real *y,
                    const ct_real *z, int two_sided, const ct_contact_geo *geo,
                    const ct_real *p_prev, uint8_t *carry, ct_idx *handoff, int64_t *active);

/* Edge-edge results, one element per pair, caller-allocated. */
typedef struct ct_edge_geo {
    ct_real *dist, *pen;     /* |Pa - Pb|, max(0, gap - dist) */
    ct_real *nx, *ny, *nz;   /* unit normal along Pa - Pb (from edge B to edge A) */
    ct_real *sa, *sb;        /* Pa = (1-sa) A1 + sa A2, Pb = (1-sb) B1 + sb B2 */
    /* The closest points; all six NULL: not written (a code that needs
     * only sa and sb saves six stores a pair). */
    ct_real *pax, *pay, *paz, *pbx, *pby, *pbz;
    ct_real *gap;            /* the gap of the pair, g_a + g_b */
    uint8_t *flag;           /* CT_NARROW_* bits */
} ct_edge_geo;

/*
 * Edge-edge narrow phase (TYPE11, seed Figure 9) over npair pairs of edges
 * (ea[k], eb[k]); edge e runs from node e1[e] to node e2[e]. Closest points
 * by the 2x2 system, then clamp sa, recompute sb, clamp, recompute sa.
 * Parallel edges (sin^2 of the angle below 16 eps): sa is the middle of the
 * overlap of the two edges on A's line (or A's end nearest to B). Edges
 * that touch (dist at most 1e-14, single 1e-6, times the longer edge) get
 * the normal ea x eb, oriented so that it points from B's midpoint towards
 * A's (or, if that is 0, with a positive largest component); parallel
 * touching edges get a normal perpendicular to A.
 * Gap of an edge: min(gap_edge[e], gap_max) (cap <= 0: none), or `gap` when
 * gap_edge is NULL; the pair gap is the sum for the two edges. Skipped
 * pairs (an edge shorter than 1e-12, single 1e-6, times the longer one,
 * or NaN/Inf): flag, pen 0, dist CT_NARROW_FAR, normal (0,0,1), sa = sb = 0,
 * points 0. Returns CT_OK, or CT_ERR_ARG for a NULL array (but the six
 * closest-point arrays, which may all be NULL), a negative count, a scalar
 * gap that is negative, NaN or infinite, or a NaN cap.
 */
int ct_narrow_edge_edge(ct_idx npair, const ct_idx *ea, const ct_idx *eb,
                        const ct_idx *e1, const ct_idx *e2,
                        const ct_real *x, const ct_real *y,
                        const ct_real *z, const ct_real *gap_edge,
                        ct_real gap, ct_real gap_max, const ct_edge_geo *out,
                        ct_narrow_stats *stats);

/*
 * The four nodal forces of edge-edge pairs for a normal force magnitude
 * fmag[k] >= 0 (pushing the edges apart; a NaN or negative fmag[k], -inf
 * too, gives zero forces): A1 gets (1-sa) F n, A2 sa F n,
 * B1 -(1-sb) F n, B2 -sb F n. They sum to zero, and their moment is
 * (Pa - Pb) x F n = 0 since n is along Pa - Pb. Output slots 4k+0..3 are
 * A1, A2, B1, B2 (fx, fy, fz hold 4*npair elements). CT_ERR_NONFINITE
 * (docs/fuzz F15) for fmag = +inf (it gave zero forces), a NaN or infinite
 * n, sa or sb, or a nodal force that overflows, for any pair: no index is
 * reported, and the forces are then unspecified.
 */
int ct_edge_edge_forces(ct_idx npair, const ct_real *fmag,
                        const ct_real *nx, const ct_real *ny,
                        const ct_real *nz, const ct_real *sa,
                        const ct_real *sb, ct_real *fx,
                        ct_real *fy, ct_real *fz);

#ifdef __cplusplus
}
#endif

#endif /* CT_NARROW_H */
