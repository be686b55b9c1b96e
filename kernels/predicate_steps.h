/*
 * predicate_steps.h -- the steps of the hull predicate (predicate.c) as
 * branch-free inline functions on scalars, shared by the one-pair predicate
 * (ct_pair_may_touch) and the batch predicate (predicate_batch.c), which
 * runs them in SIMD lanes. Both compile the very same expressions, so a
 * step decides a pair identically in either; that is what lets a search
 * use the batch and still return the pair set of the direct search bit for
 * bit. Not part of any API.
 */
#ifndef CT_PREDICATE_STEPS_H
#define CT_PREDICATE_STEPS_H

#include "ct_internal.h"

/* Always inlined: a step called from a vector loop must be inlined for the
 * loop to vectorise, and clang keeps a static function out of line once a
 * file calls it from two loops (then fails the build under -Werror, since
 * the loops ask for SIMD). */
#if defined(__GNUC__)
#define CTI_STEP static inline __attribute__((always_inline))
#else
#define CTI_STEP static inline
#endif

/* CTI_FMA (ct_internal.h): the steps are mostly dot and cross products,
 * which the fused form runs in fewer operations. */

/* A point or vector, passed by value (the compiler splits it into
 * scalars, in a vector loop into lanes). */
typedef struct cti_pv {
    ct_real x, y, z;
} cti_pv;

CTI_STEP cti_pv cti_pv_sub(cti_pv a, cti_pv b)
{
    cti_pv r = {a.x - b.x, a.y - b.y, a.z - b.z};
    return r;
}

CTI_STEP ct_real cti_pv_dot(cti_pv a, cti_pv b)
{
    return CTI_FMA(a.x, b.x, CTI_FMA(a.y, b.y, a.z * b.z));
}

/* u x v */
CTI_STEP cti_pv cti_pv_cross(cti_pv u, cti_pv v)
{
    cti_pv r = {CTI_FMA(u.y, v.z, -(u.z * v.y)), CTI_FMA(u.z, v.x, -(u.x * v.z)),
                CTI_FMA(u.x, v.y, -(u.y * v.x))};
    return r;
}

/* (u x v) . w */
CTI_STEP ct_real cti_pv_triple(cti_pv u, cti_pv v, cti_pv w)
{
    return cti_pv_dot(cti_pv_cross(u, v), w);
}

/* Squared distance from p to the segment a b. */
CTI_STEP ct_real cti_step_edge2(cti_pv p, cti_pv a, cti_pv b)
{
    cti_pv ab = cti_pv_sub(b, a), ap = cti_pv_sub(p, a);
    ct_real l2 = cti_pv_dot(ab, ab);
    ct_real t = cti_pv_dot(ap, ab) / l2;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    t = l2 > 0 ? t : 0;
    cti_pv r = {CTI_FMA(-t, ab.x, ap.x), CTI_FMA(-t, ab.y, ap.y), CTI_FMA(-t, ab.z, ap.z)};
    return cti_pv_dot(r, r);
}

/* One axis of steps 1 and 2, from the bounds of the corners' box: lo, hi,
 * and lod = lo - d, hid = hi + d; *out set when v is outside [lod, hid];
 * returns the squared distance from v to [lo, hi]. */
CTI_STEP ct_real cti_step_axis_lh(ct_real v, ct_real lo, ct_real hi, ct_real lod, ct_real hid,
                                  cti_lane *out)
{
    *out |= (v < lod) | (v > hid);
    ct_real ex = v < lo ? lo - v : (v > hi ? v - hi : 0);
    return ex * ex;
}

/* The bounds [lo, hi] of the four corners' coordinates on one axis. */
CTI_STEP ct_real cti_step_lo(ct_real a, ct_real b, ct_real c, ct_real e)
{
    return CTI_MIN(CTI_MIN(a, b), CTI_MIN(c, e));
}

CTI_STEP ct_real cti_step_hi(ct_real a, ct_real b, ct_real c, ct_real e)
{
    return CTI_MAX(CTI_MAX(a, b), CTI_MAX(c, e));
}

/* One axis of steps 1 and 2: the box [lo, hi] of the four corners'
 * coordinates; *out set when v is outside it inflated by d; returns the
 * squared distance from v to it. */
CTI_STEP ct_real cti_step_axis(ct_real v, ct_real a, ct_real b, ct_real c, ct_real e,
                                    ct_real d, cti_lane *out)
{
    ct_real lo = cti_step_lo(a, b, c, e), hi = cti_step_hi(a, b, c, e);
    return cti_step_axis_lh(v, lo, hi, lo - d, hi + d, out);
}

/* The three axes' squared distances into the result of steps 1 and 2. */
CTI_STEP ct_real cti_step_box_sum(ct_real bx, ct_real by, ct_real bz, cti_lane out)
{
    ct_real box2 = (bx + by) + bz;
    return out ? -1 : box2;
}

/* Steps 1 and 2: the squared Euclidean distance from p to the corners' box,
 * or -1 when p is outside the box inflated by d (then surely farther). */
CTI_STEP ct_real cti_step_box(cti_pv p, cti_pv a, cti_pv b, cti_pv c, cti_pv e, ct_real d)
{
    cti_lane out = 0;
    ct_real bx = cti_step_axis(p.x, a.x, b.x, c.x, e.x, d, &out);
    ct_real by = cti_step_axis(p.y, a.y, b.y, c.y, e.y, d, &out);
    ct_real bz = cti_step_axis(p.z, a.z, b.z, c.z, e.z, d, &out);
    return cti_step_box_sum(bx, by, bz, out);
}

/* Step 2b: 1 when a corner is within d of p (then the hull is too). The
 * cheapest accept: on a mesh whose elements are small against d (a graded
 * mesh's fine region, a folded sheet) it decides most kept pairs. */
CTI_STEP cti_lane cti_step_corners(cti_pv p, cti_pv a, cti_pv b, cti_pv c, cti_pv e,
                                        ct_real d2)
{
    cti_pv pa = cti_pv_sub(p, a), pb = cti_pv_sub(p, b), pc = cti_pv_sub(p, c),
           pe = cti_pv_sub(p, e);
    const cti_lane ca = cti_pv_dot(pa, pa) <= d2, cb = cti_pv_dot(pb, pb) <= d2;
    const cti_lane cc = cti_pv_dot(pc, pc) <= d2, ce = cti_pv_dot(pe, pe) <= d2;
    return (ca | cb) | (cc | ce);
}

/* What the prism test finds: accept (1 when p lies over the segment within
 * d of every corner's height); the four edge sides s0..s3 (which count only
 * when ok: otherwise p is taken to be outside every edge); and, for the reject step, n (the
 * diagonals' normal), |n|^2 and h = how far p lies outside the slab of the
 * corners' heights along n, times |n|; ok = 0 when n was not usable.
 * Returned by value, so that the compiler keeps it in registers (in a
 * vector loop, in lanes). */
typedef struct cti_prism {
    ct_real s0, s1, s2, s3;
    cti_pv n;
    ct_real nn, h;
    cti_lane ok, accept;
} cti_prism;

/* Step 3, the prism test (the argument is at its use in predicate.c). */
CTI_STEP cti_prism cti_step_prism(cti_pv p, cti_pv a, cti_pv b, cti_pv c, cti_pv e,
                                       ct_real d2)
{
    cti_prism q;
    cti_pv ac = cti_pv_sub(c, a), be = cti_pv_sub(e, b);
    cti_pv n = cti_pv_cross(ac, be);
    ct_real nn = cti_pv_dot(n, n);
    cti_lane ok = nn > (ct_real)1e-2 * cti_pv_dot(ac, ac) * cti_pv_dot(be, be);
    cti_pv pa = cti_pv_sub(p, a), pb = cti_pv_sub(p, b), pc = cti_pv_sub(p, c),
           pe = cti_pv_sub(p, e);
    cti_pv ab = cti_pv_sub(b, a), bc = cti_pv_sub(c, b), ce = cti_pv_sub(e, c),
           ea = cti_pv_sub(a, e);
    ct_real s0 = cti_pv_triple(ab, pa, n), s1 = cti_pv_triple(bc, pb, n);
    ct_real s2 = cti_pv_triple(ce, pc, n), s3 = cti_pv_triple(ea, pe, n);
    ct_real h1 = cti_pv_dot(pa, n), h2 = cti_pv_dot(pb, n), h3 = cti_pv_dot(pc, n),
            h4 = cti_pv_dot(pe, n);
    ct_real hmax = CTI_MAX(CTI_MAX(h1 * h1, h2 * h2), CTI_MAX(h3 * h3, h4 * h4));
    ct_real lo = CTI_MIN(CTI_MIN(h1, h2), CTI_MIN(h3, h4));
    ct_real hi = CTI_MAX(CTI_MAX(h1, h2), CTI_MAX(h3, h4));
    q.h = lo > 0 ? lo : (hi < 0 ? -hi : 0);
    q.nn = nn;
    q.n = n;
    q.ok = ok;
    q.s0 = s0, q.s1 = s1, q.s2 = s2, q.s3 = s3;
    q.accept = ok & (s0 >= 0) & (s1 >= 0) & (s2 >= 0) & (s3 >= 0) & (hmax <= d2 * nn);
    return q;
}

/* Step 4: 1 when a point of an edge that p is outside of (side < 0) is
 * within d. All four edges are measured (no early exit, so that the step
 * runs in vector lanes); the answer is the same. */
CTI_STEP cti_lane cti_step_edges(cti_pv p, cti_pv a, cti_pv b, cti_pv c, cti_pv e, ct_real d2,
                                 const cti_prism q)
{
    const cti_lane all = q.ok - 1; /* all ones when n is not usable */
    cti_lane e0 = ((q.s0 < 0) | all) & (cti_step_edge2(p, a, b) <= d2);
    cti_lane e1 = ((q.s1 < 0) | all) & (cti_step_edge2(p, b, c) <= d2);
    cti_lane e2 = ((q.s2 < 0) | all) & (cti_step_edge2(p, c, e) <= d2);
    cti_lane e3 = ((q.s3 < 0) | all) & (cti_step_edge2(p, e, a) <= d2);
    return (e0 | e1 | e2 | e3) & 1;
}

/* One edge's term of step 4b: edge P -> R of the outline, whose plane along
 * n has the normal m = n x (R - P), inward when the corners wind positively
 * about n; s = m . (p - P) (the prism test's side). When p is outside that
 * plane (s < 0) and the two other corners U and V are inside it (so the
 * whole hull is), p is at least |s| / |m| from the hull laterally: returns
 * the larger of lat and s^2 / |m|^2 then, lat otherwise. */
CTI_STEP ct_real cti_step_far_edge(cti_pv n, cti_pv P, cti_pv R, cti_pv U, cti_pv V, ct_real s,
                                   ct_real lat)
{
    const cti_pv ek = cti_pv_sub(R, P);
    const cti_pv m = cti_pv_cross(n, ek);
    const ct_real mm = cti_pv_dot(m, m);
    const cti_pv u = cti_pv_sub(U, P), v = cti_pv_sub(V, P);
    const ct_real mu = cti_pv_dot(m, u), mv = cti_pv_dot(m, v);
    const cti_lane use = (s < 0) & (mm > 0) & !(mu < 0) & !(mv < 0);
    const ct_real l2 = s * s / (mm > 0 ? mm : 1);
    return (use & (l2 > lat)) ? l2 : lat;
}

/* Step 4b, a reject (the argument is at its use in predicate.c): 1 when the
 * lower bound of the hull distance from the slab of the corners' heights
 * and the edges' planes exceeds d by more than rounding. Every term is
 * computed (no early exit, so that the step runs in vector lanes); the
 * answer is that of stopping at the slab alone when it suffices, since
 * adding the lateral term (>= 0) cannot lower the sum. */
CTI_STEP cti_lane cti_step_far(cti_pv a, cti_pv b, cti_pv c, cti_pv e, const cti_prism q,
                               ct_real d2)
{
    const ct_real lim = d2 * (1 + 64 * CTI_EPS);
    const ct_real hh = q.h * q.h / (q.ok ? q.nn : 1);
    ct_real lat = 0;
    lat = cti_step_far_edge(q.n, a, b, c, e, q.s0, lat);
    lat = cti_step_far_edge(q.n, b, c, e, a, q.s1, lat);
    lat = cti_step_far_edge(q.n, c, e, a, b, q.s2, lat);
    lat = cti_step_far_edge(q.n, e, a, b, c, q.s3, lat);
    return q.ok & (lat + hh > lim);
}

#endif
