/*
 * predicate.c -- the pair predicate shared by all four searches: may node p
 * be within distance d of a segment? (See ct_search.h for the contract.)
 *
 * The hull test (CT_FILTER_HULL) runs from cheap to exact so the common
 * cases cost little:
 *  1. the node is outside the segment's box inflated by d   -> no;
 *  2. the Euclidean distance to the segment's box exceeds d -> no;
 *  2b. a corner is within d                                  -> yes;
 *  3. the node lies over the segment, within d of every corner's height
 *     (the prism test below)                                -> yes;
 *  4. a point of an edge the node is outside of is within d -> yes;
 *  4b. a lower bound of the hull distance, from the slab of the corners'
 *     heights and the planes through the edges, exceeds d    -> no;
 *  5. otherwise the exact distance to the convex hull of the corners.
 * Steps 2b, 3 and 4 only accept, and only when a point of the hull is truly
 * within d (up to rounding); step 4b only rejects, and only when every
 * point of the hull is farther than d: they are shortcuts, not
 * approximations. On a smooth surface they decide almost every pair
 * without step 5, which costs up to four point-triangle distances.
 * The box test (CT_FILTER_BOX) stops after step 2: looser (a superset of
 * the hull set) and several times cheaper.
 * Every step is a true bound of the distance to the hull, so the answer is
 * that of step 4 up to rounding, and it is the same function for every
 * search, which is what makes their pair sets identical.
 */
#include "ct_internal.h"
#include "predicate_steps.h"

static inline ct_real dot3(const ct_real a[3], const ct_real b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void sub3(ct_real r[3], const ct_real a[3], const ct_real b[3])
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

ct_real cti_dist2_point_edge(const ct_real p[3], const ct_real a[3], const ct_real b[3])
{
    const cti_pv P = {p[0], p[1], p[2]}, A = {a[0], a[1], a[2]}, B = {b[0], b[1], b[2]};
    return cti_step_edge2(P, A, B);
}

/* Closest point of a triangle by its Voronoi regions (vertex, edge, face),
 * after the classic formulation in Ericson, Real-Time Collision Detection,
 * section 5.1.5. */
ct_real cti_dist2_point_triangle(const ct_real p[3], const ct_real a[3],
                                 const ct_real b[3], const ct_real c[3])
{
    ct_real ab[3], ac[3], ap[3], bp[3], cp[3], r[3];
    sub3(ab, b, a);
    sub3(ac, c, a);
    sub3(ap, p, a);
    ct_real d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return dot3(ap, ap);
    sub3(bp, p, b);
    ct_real d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return dot3(bp, bp);
    sub3(cp, p, c);
    ct_real d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return dot3(cp, cp);
    ct_real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0)
        return cti_dist2_point_edge(p, a, b);
    ct_real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0)
        return cti_dist2_point_edge(p, a, c);
    ct_real va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0)
        return cti_dist2_point_edge(p, b, c);
    ct_real den = va + vb + vc;
    if (!(den > 0)) {
        /* Degenerate (collinear or coincident corners): the triangle is
         * covered by its edges. */
        ct_real e1 = cti_dist2_point_edge(p, a, b);
        ct_real e2 = cti_dist2_point_edge(p, a, c);
        ct_real e3 = cti_dist2_point_edge(p, b, c);
        return CTI_MIN(e1, CTI_MIN(e2, e3));
    }
    ct_real v = vb / den, w = vc / den;
    for (int k = 0; k < 3; k++)
        r[k] = ap[k] - v * ab[k] - w * ac[k];
    return dot3(r, r);
}

/* (u x v) . w */
static inline ct_real triple(const ct_real u[3], const ct_real v[3], const ct_real w[3])
{
    return w[0] * (u[1] * v[2] - u[2] * v[1]) + w[1] * (u[2] * v[0] - u[0] * v[2]) +
           w[2] * (u[0] * v[1] - u[1] * v[0]);
}

/* 6 x signed volume of tetrahedron (a, b, c, p). */
static inline ct_real orient3(const ct_real a[3], const ct_real b[3], const ct_real c[3],
                              const ct_real p[3])
{
    ct_real ab[3], ac[3], ap[3];
    sub3(ab, b, a);
    sub3(ac, c, a);
    sub3(ap, p, a);
    return triple(ab, ac, ap);
}

static inline cti_pv pv_of(const ct_real v[3])
{
    cti_pv r = {v[0], v[1], v[2]};
    return r;
}

/* Steps 1 and 2 as cti_step_box computes them, axis by axis with an early
 * exit: the same values, so the same answer; one pair at a time (the
 * direct search rejects almost every pair at its first axis) the branches
 * are cheaper than all three axes. */
static inline ct_real box_early(cti_pv p, cti_pv a, cti_pv b, cti_pv c, cti_pv e, ct_real d)
{
    cti_lane out = 0;
    const ct_real bx = cti_step_axis(p.x, a.x, b.x, c.x, e.x, d, &out);
    if (out)
        return -1;
    const ct_real by = cti_step_axis(p.y, a.y, b.y, c.y, e.y, d, &out);
    if (out)
        return -1;
    const ct_real bz = cti_step_axis(p.z, a.z, b.z, c.z, e.z, d, &out);
    return out ? -1 : (bx + by) + bz;
}

int ct_pair_box_near(const ct_real p[3], const ct_real a[3], const ct_real b[3],
                     const ct_real c[3], const ct_real e[3], ct_real d)
{
    ct_real box2 = box_early(pv_of(p), pv_of(a), pv_of(b), pv_of(c), pv_of(e), d);
    return box2 >= 0 && box2 <= d * d;
}

/*
 * Step 3, the prism test (cti_step_prism). n = (c - a) x (e - b), the
 * diagonals' normal, is the quad's vector area times 2 (for a triangle,
 * e == c, it is the triangle's normal), so the corners projected along n
 * form a polygon of positive area about n. When p is on the inner side
 * (about n) of all four edges, the angle each edge subtends from p is in
 * [0, pi] and they add up to 2 pi times the winding number, which is then
 * at least 1: p projects into the polygon, hence into the projected hull,
 * and the hull point q straight along n from p has a height between the
 * corners' heights, so |p - q| <= max_k |(p - P_k) . n| / |n|. Accept when
 * that is <= d. A triangle's zero edge e - c gives 0, which the test
 * allows. When the diagonals are within about 6 degrees of parallel (a
 * collapsed or needle quad) the rounding of n would tilt it: not decided
 * there.
 */

/*
 * Step 4b (cti_step_far, predicate_steps.h), a reject: a lower bound of the
 * distance to the hull, from the slab of the corners' heights along n and the
 * planes through the edges along n. The hull lies in the slab, so its distance
 * is at least q.h / |n|. Edge k's plane has the normal m = n x (P_k+1 - P_k),
 * which points inward when the corners wind positively about n (as n, twice the
 * vector area, makes them do); s[k] = m . (p - P_k), so p is -s[k] / |m|
 * outside it. When the two other corners are on the inner side too (a convex
 * outline, checked), the whole hull is, and since m is orthogonal to n the
 * distance to the slab cut by that half-space is the root of the sum of the
 * squares. Reject when the bound exceeds d by more than rounding (the
 * factor 1 + 64 eps): only pairs truly farther than d are rejected, where
 * step 5 would have cost up to four point-triangle distances. The vector
 * lanes of the batch predicate run this step too (predicate_batch.c).
 */
#if defined(__GNUC__)
#define PRED_NOINLINE __attribute__((noinline))
#else
#define PRED_NOINLINE
#endif

PRED_NOINLINE static int may_touch_past_box(const ct_real p[3], const ct_real a[3],
                                            const ct_real b[3], const ct_real c[3],
                                            const ct_real e[3], ct_real d2);

int ct_pair_may_touch(const ct_real p[3], const ct_real a[3], const ct_real b[3],
                      const ct_real c[3], const ct_real e[3], ct_real d)
{
    /* Steps 1 and 2 here, the rest in a function of its own: the direct
     * search rejects almost every pair here, and this function's frame
     * stays small. */
    ct_real d2 = d * d, box2 = box_early(pv_of(p), pv_of(a), pv_of(b), pv_of(c), pv_of(e), d);
    if (box2 < 0 || box2 > d2)
        return 0;
    return may_touch_past_box(p, a, b, c, e, d2);
}

/* Steps 3 to 5 of ct_pair_may_touch, for a pair that steps 1 and 2 kept
 * (not inlined, so that the first steps' frame stays small). */
PRED_NOINLINE static int may_touch_past_box(const ct_real p[3], const ct_real a[3],
                                            const ct_real b[3], const ct_real c[3],
                                            const ct_real e[3], ct_real d2)
{
    const cti_pv P = pv_of(p), A = pv_of(a), B = pv_of(b), C = pv_of(c), E = pv_of(e);
    if (cti_step_corners(P, A, B, C, E, d2))
        return 1;
    /* Step 3, then step 4: the edges lie in the hull. On a flat convex quad
     * the nearest hull point of an outside p is on an edge p is outside of;
     * the other edges belong to the faces step 5 tests. */
    const cti_prism q = cti_step_prism(P, A, B, C, E, d2);
    if (q.accept)
        return 1;
    /* Step 4 as cti_step_edges computes it, edge by edge with an early
     * exit (the same terms, so the same answer; one pair at a time the
     * branches are cheaper than measuring all four edges). */
    const cti_pv cv[4] = {A, B, C, E};
    const ct_real sv[4] = {q.s0, q.s1, q.s2, q.s3};
    for (int k = 0; k < 4; k++)
        if ((!q.ok || sv[k] < 0) && cti_step_edge2(P, cv[k], cv[(k + 1) & 3]) <= d2)
            return 1;
    if (cti_step_far(A, B, C, E, q, d2))
        return 0;
    int tri = (c[0] == e[0] && c[1] == e[1] && c[2] == e[2]);
    if (tri)
        return cti_dist2_point_triangle(p, a, b, c) <= d2;
    /* The hull of four points is the tetrahedron a b c e: inside it the
     * distance is zero, outside it is the distance to the nearest face. */
    if (cti_dist2_point_triangle(p, a, b, c) <= d2 || cti_dist2_point_triangle(p, a, c, e) <= d2 ||
        cti_dist2_point_triangle(p, a, b, e) <= d2 || cti_dist2_point_triangle(p, b, c, e) <= d2)
        return 1;
    /* The inside test is meaningful only for a tetrahedron whose volume is
     * clearly above the rounding error of orient3 (about eps |ab||ac||ae|):
     * for a flat one, all orientations of a coplanar point are noise. A
     * hull thinner than that is covered by its four faces to within its
     * thickness, which the faces' test above already used. */
    ct_real ab[3], ac[3], ae[3];
    sub3(ab, b, a);
    sub3(ac, c, a);
    sub3(ae, e, a);
    ct_real scale = CTI_SQRT(dot3(ab, ab) * dot3(ac, ac) * dot3(ae, ae));
    ct_real vol = orient3(a, b, c, e);
    if (!(CTI_FABS(vol) > 1024 * CTI_EPS * scale))
        return 0;
    ct_real s1 = orient3(a, b, c, p), s2 = orient3(a, c, e, p);
    ct_real s3 = orient3(a, e, b, p), s4 = orient3(b, e, c, p);
    /* Faces oriented so that all four are positive inside when vol > 0. */
    if (vol > 0)
        return s1 >= 0 && s2 >= 0 && s3 >= 0 && s4 >= 0;
    return s1 <= 0 && s2 <= 0 && s3 <= 0 && s4 <= 0;
}
