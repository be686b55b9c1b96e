/*
 * narrow_quad.h -- what the node-quadrangle kernels share (project_quad.c:
 * four triangles and the closed form; project_newton.c: Newton): small
 * 3-vectors and the bilinear quadrangle's helpers.
 *
 * Boundary rule shared by Newton and the closed form: the four edges of a
 * bilinear quadrangle are straight, so the closest point of the boundary is
 * analytic; the interior candidate x(s, t) is kept when (s, t) lies in
 * [-1,1]^2 and it is not farther than the boundary's closest point. On a
 * flat parallelogram both methods are then exact, inside and outside.
 *
 * 3-vectors are small structs passed by value, which the compiler splits
 * into scalars.
 */
#ifndef NARROW_QUAD_H
#define NARROW_QUAD_H

#include "narrow_internal.h"

typedef struct cti_v3 {
    ct_real x, y, z;
} cti_v3;

static inline cti_v3 v3(ct_real x, ct_real y, ct_real z)
{
    cti_v3 r = {x, y, z};
    return r;
}
static inline cti_v3 v3_sub(cti_v3 a, cti_v3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline cti_v3 v3_add(cti_v3 a, cti_v3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline cti_v3 v3_scale(ct_real s, cti_v3 a) { return v3(s * a.x, s * a.y, s * a.z); }
static inline ct_real v3_dot(cti_v3 a, cti_v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline cti_v3 v3_cross(cti_v3 a, cti_v3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline cti_v3 v3_sel(cti_nr_int c, cti_v3 a, cti_v3 b)
{
    return v3(c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z);
}


/* ---- Bilinear quadrangle ------------------------------------------------- */

/* x(s,t) = x0 + s a1 + t a2 + s t a3 with x0 = (X1+X2+X3+X4)/4,
 * a1 = (-X1+X2+X3-X4)/4, a2 = (-X1-X2+X3+X4)/4, a3 = (X1-X2+X3-X4)/4, which
 * is sum H_i X_i with the shape functions of DESIGN.md section 6. The
 * corners are relative to X1 (X1 = 0), as loaded by CTI_NR_LOAD.
 *
 * The helpers take the quadrangle as 3-vectors passed by value (a struct
 * holding all of them would stay in memory and stop the vectorisation): the
 * corners X2, X3, X4, the node P, and x0, a1, a2, a3. */
#define CTI_QPARAMS                                                                       \
    cti_v3 X2, cti_v3 X3, cti_v3 X4, cti_v3 P, cti_v3 x0, cti_v3 a1, cti_v3 a2, cti_v3 a3
#define CTI_QARGS X2, X3, X4, P, x0, a1, a2, a3
#define CTI_QUNUSED (void)X2, (void)X3, (void)X4, (void)P, (void)x0, (void)a1, (void)a2, (void)a3

/* Declare x0, a1, a2, a3 of the corners X2, X3, X4 (X1 = 0). */
#define CTI_QUAD_MAKE(X2, X3, X4)                                                         \
    const ct_real c4_ = (ct_real)0.25;                                                    \
    cti_v3 x0 = v3(c4_ * (X2.x + (X3.x + X4.x)), c4_ * (X2.y + (X3.y + X4.y)),             \
                   c4_ * (X2.z + (X3.z + X4.z)));                                         \
    cti_v3 a1 = v3(c4_ * (X2.x + (X3.x - X4.x)), c4_ * (X2.y + (X3.y - X4.y)),             \
                   c4_ * (X2.z + (X3.z - X4.z)));                                         \
    cti_v3 a2 = v3(c4_ * (X4.x + (X3.x - X2.x)), c4_ * (X4.y + (X3.y - X2.y)),             \
                   c4_ * (X4.z + (X3.z - X2.z)));                                         \
    cti_v3 a3 = v3(c4_ * ((X3.x - X4.x) - X2.x), c4_ * ((X3.y - X4.y) - X2.y),             \
                   c4_ * ((X3.z - X4.z) - X2.z))

/* x(s, t). */
static inline cti_v3 cti_quad_x(cti_v3 x0, cti_v3 a1, cti_v3 a2, cti_v3 a3, ct_real s,
                                ct_real t)
{
    ct_real st = s * t;
    return v3(x0.x + s * a1.x + t * a2.x + st * a3.x, x0.y + s * a1.y + t * a2.y + st * a3.y,
              x0.z + s * a1.z + t * a2.z + st * a3.z);
}

/* Closest point of the straight edge P0 -> P0 + e to p, given 1/|e|^2:
 * parameter *u in [0, 1]; returns the squared distance. */
static inline ct_real cti_quad_edge(cti_v3 P0, cti_v3 e, ct_real inv_ee, cti_v3 p, ct_real *u)
{
    cti_v3 w = v3_sub(p, P0);
    ct_real uu = cti_nr_clamp01(v3_dot(w, e) * inv_ee);
    cti_v3 r = v3_sub(w, v3_scale(uu, e));
    *u = uu;
    return v3_dot(r, r);
}

/* The closest point of the quadrangle's boundary (four straight edges):
 * its (s, t) and squared distance. Ties keep the first edge in the order
 * 1-2, 2-3, 4-3, 1-4. Two divisions give the four 1/|e|^2. */
CTI_NR_INLINE void cti_quad_boundary(CTI_QPARAMS, ct_real *s, ct_real *t, ct_real *q)
{
    CTI_QUNUSED;
    cti_v3 Z = v3(0, 0, 0);
    cti_v3 e12 = X2, e23 = v3_sub(X3, X2), e43 = v3_sub(X3, X4), e14 = X4;
    ct_real l12 = v3_dot(e12, e12), l23 = v3_dot(e23, e23);
    ct_real l43 = v3_dot(e43, e43), l14 = v3_dot(e14, e14);
    l12 = l12 > 0 ? l12 : 1;
    l23 = l23 > 0 ? l23 : 1;
    l43 = l43 > 0 ? l43 : 1;
    l14 = l14 > 0 ? l14 : 1;
    ct_real ia = 1 / (l12 * l23), ib = 1 / (l43 * l14);
    ct_real u, qe;
    qe = cti_quad_edge(Z, e12, l23 * ia, P, &u);
    ct_real bs = 2 * u - 1, bt = -1, bq = qe;
    qe = cti_quad_edge(X2, e23, l12 * ia, P, &u);
    cti_nr_int take = qe < bq;
    bs = take ? 1 : bs;
    bt = take ? 2 * u - 1 : bt;
    bq = take ? qe : bq;
    qe = cti_quad_edge(X4, e43, l14 * ib, P, &u);
    take = qe < bq;
    bs = take ? 2 * u - 1 : bs;
    bt = take ? 1 : bt;
    bq = take ? qe : bq;
    qe = cti_quad_edge(Z, e14, l43 * ib, P, &u);
    take = qe < bq;
    bs = take ? -1 : bs;
    bt = take ? 2 * u - 1 : bt;
    bq = take ? qe : bq;
    *s = bs;
    *t = bt;
    *q = bq;
}

/* Squared distance from p to the triangle (A, B, C) (cti_nr_tri_k's q). */
CTI_NR_INLINE ct_real cti_quad_tri_q(cti_v3 A, cti_v3 B, cti_v3 C, cti_v3 p)
{
    cti_v3 ab = v3_sub(B, A), ac = v3_sub(C, A), ap = v3_sub(p, A);
    cti_v3 kb = v3_cross(ab, ap), kc = v3_cross(ac, ap);
    ct_real q, u, v, w, nx, ny, nz, nn, l2;
    cti_nr_int in;
    cti_nr_tri_k(ab.x, ab.y, ab.z, ac.x, ac.y, ac.z, ap.x, ap.y, ap.z, kb.x, kb.y, kb.z, kc.x,
                 kc.y, kc.z, &q, &u, &v, &w, &nx, &ny, &nz, &nn, &l2, &in);
    return q;
}

/* Whether p lies strictly on the other side of the plane of face (A, B, C)
 * than the tetrahedron's fourth corner D, or off that plane when D is in it
 * (a flat tetrahedron). */
CTI_NR_INLINE cti_nr_int cti_quad_face_out(cti_v3 A, cti_v3 B, cti_v3 C, cti_v3 D, cti_v3 p)
{
    cti_v3 n = v3_cross(v3_sub(B, A), v3_sub(C, A));
    ct_real o = v3_dot(n, v3_sub(D, A)), w = v3_dot(n, v3_sub(p, A));
    return ((o > 0) & (w < 0)) | ((o < 0) & (w > 0)) | ((o == 0) & (w != 0));
}

/*
 * A lower bound of the squared distance from P to the quadrangle: the
 * squared distance to the tetrahedron of its corners, which holds the
 * bilinear surface (every point of it is a mean of the corners with the
 * weights H1..H4 >= 0): the least over its four faces when P is outside
 * it, 0 when P is inside (or the test cannot tell). Newton uses it to end
 * the iterations of a node off the quadrangle: when this bound reaches the
 * boundary's squared distance, no point inside beats the boundary.
 */
CTI_NR_INLINE ct_real cti_quad_hull_q(CTI_QPARAMS)
{
    CTI_QUNUSED;
    cti_v3 A = v3(0, 0, 0);
    cti_nr_int out = cti_quad_face_out(A, X2, X3, X4, P) | cti_quad_face_out(A, X3, X4, X2, P) |
                     cti_quad_face_out(A, X2, X4, X3, P) | cti_quad_face_out(X2, X3, X4, A, P);
    ct_real q1 = cti_quad_tri_q(A, X2, X3, P), q2 = cti_quad_tri_q(A, X3, X4, P);
    ct_real q3 = cti_quad_tri_q(A, X2, X4, P), q4 = cti_quad_tri_q(X2, X3, X4, P);
    ct_real q12 = q1 < q2 ? q1 : q2, q34 = q3 < q4 ? q3 : q4;
    ct_real q = q12 < q34 ? q12 : q34;
    return out ? q : 0;
}

/* Corner triangle A, B, D (relative vectors e = B - A, f = D - A): keep the
 * smallest squared |e x f| and the longest squared edge |e|^2. */
static inline void cti_quad_corner(cti_v3 e, cti_v3 f, ct_real *amin, ct_real *lmax)
{
    cti_v3 c = v3_cross(e, f);
    ct_real a2 = v3_dot(c, c), l2 = v3_dot(e, e);
    *amin = a2 < *amin ? a2 : *amin;
    *lmax = l2 > *lmax ? l2 : *lmax;
}

/*
 * The common end of Newton and the closed form: choose the interior
 * candidate (s, t) or the boundary, then compute the outputs: the point
 * x(s,t), the shape weights H1..H4, the normal x_s x x_t (the mean normal
 * (X3-X1) x (X4-X2) where the Jacobian vanishes), the degeneracy test on
 * the four corner triangles, and the sidedness rule. `trusted` says (s, t)
 * is a stationary point (or the fallback iterate). The contact point is
 * relative to X1.
 */
CTI_NR_INLINE void cti_quad_end(CTI_QPARAMS, ct_real s, ct_real t, cti_nr_int trusted,
                                ct_real g, int two, ct_real *cx, ct_real *cy, ct_real *cz,
                                ct_real *h1, ct_real *h2,
                                ct_real *h3, ct_real *h4, ct_real *dist,
                                ct_real *pen, ct_real *nx, ct_real *ny, ct_real *nz,
                                cti_nr_int *degen,
                                cti_nr_int *flag)
{
    ct_real bs, bt, bq;
    cti_quad_boundary(CTI_QARGS, &bs, &bt, &bq);
    ct_real as = CTI_FABS(s), at = CTI_FABS(t);
    ct_real am = as > at ? as : at;
    cti_nr_int interior = trusted & (am <= 1);
    ct_real si = interior ? s : 0, ti = interior ? t : 0;
    cti_v3 ri = v3_sub(cti_quad_x(x0, a1, a2, a3, si, ti), P);
    ct_real qi = v3_dot(ri, ri);
    cti_nr_int take = interior & (qi <= bq);
    cti_nr_int near = trusted & (am <= 1 + CTI_NR_IN_TOL);
    cti_nr_int in = take | (near & !interior);
    ct_real fs = take ? si : bs, ft = take ? ti : bt;
    /* Outputs at (fs, ft). */
    cti_v3 c = cti_quad_x(x0, a1, a2, a3, fs, ft);
    cti_v3 xs = v3_add(a1, v3_scale(ft, a3)), xt = v3_add(a2, v3_scale(fs, a3));
    *h1 = (ct_real)0.25 * (1 - fs) * (1 - ft);
    *h2 = (ct_real)0.25 * (1 + fs) * (1 - ft);
    *h3 = (ct_real)0.25 * (1 + fs) * (1 + ft);
    *h4 = (ct_real)0.25 * (1 - fs) * (1 + ft);
    cti_v3 nv = v3_cross(xs, xt);
    cti_v3 m = v3_cross(X3, v3_sub(X4, X2));
    ct_real nn = v3_dot(nv, nv), mm = v3_dot(m, m);
    /* Corner triangles: corner i with its two neighbours. */
    ct_real lmax = 0, amin = CTI_HUGE;
    cti_v3 e12 = X2, e23 = v3_sub(X3, X2), e34 = v3_sub(X4, X3), e41 = X4;
    cti_quad_corner(e12, e41, &amin, &lmax);
    cti_quad_corner(e23, v3_scale(-1, e12), &amin, &lmax);
    cti_quad_corner(e34, v3_scale(-1, e23), &amin, &lmax);
    cti_quad_corner(v3_scale(-1, e41), v3_scale(-1, e34), &amin, &lmax);
    /* Corner triangle area |e x f|/2 <= tol * lmax. */
    ct_real lim = 2 * CTI_NR_AREA_TOL * lmax;
    *degen = !(amin > lim * lim);
    cti_nr_int usen = nn > (ct_real)1e-6 * mm;
    cti_v3 N = v3_sel(usen, nv, m);
    cti_nr_finish(P.x, P.y, P.z, c.x, c.y, c.z, N.x, N.y, N.z, usen ? nn : mm, lmax, in, g,
                  two, dist, pen, nx, ny, nz, flag);
    *cx = c.x;
    *cy = c.y;
    *cz = c.z;
}


/* Pair j of a block as the bilinear quadrangle's helpers take it: the
 * scalars of CTI_NR_LOAD(j), the corners X2..X4 and the node P as
 * 3-vectors, and x0, a1, a2, a3 (CTI_QUAD_MAKE). */
#define CTI_QUAD_LOAD(j)                                                                   \
    CTI_NR_LOAD(j);                                                                       \
    cti_v3 X2 = v3(x2, y2, z2), X3 = v3(x3, y3, z3), X4 = v3(x4, y4, z4),                 \
           P = v3(px, py, pz);                                                            \
    CTI_QUAD_MAKE(X2, X3, X4)

/* The outputs of pair j at (s, t) by cti_quad_end, with `extra` added to its
 * flag, stored by CTI_NR_STORE: in a block loop after CTI_NR_LOAD(j) and
 * CTI_QUAD_MAKE, with `two` (two-sided) in scope. */
#define CTI_QUAD_STORE(j, s, t, trusted, extra)                                            \
    do {                                                                                  \
        ct_real cx_, cy_, cz_, nx_, ny_, nz_, h1_, h2_, h3_, h4_, dist_, pen_;             \
        cti_nr_int degen_, flag_;                                                         \
        cti_quad_end(CTI_QARGS, s, t, trusted, g, two, &cx_, &cy_, &cz_, &h1_, &h2_, &h3_, \
                     &h4_, &dist_, &pen_, &nx_, &ny_, &nz_, &degen_, &flag_);             \
        cti_nr_int bad_ =                                                                 \
            nonfin ? CTI_NR_F(NONFINITE) : (degen_ ? CTI_NR_F(DEGENERATE) : 0);           \
        flag_ |= (extra);                                                                 \
        CTI_NR_STORE(j, bad_, dist_, pen_, nx_, ny_, nz_, cx_, cy_, cz_, h1_, h2_, h3_, h4_, \
                     g, flag_);                                                           \
    } while (0)

#endif /* NARROW_QUAD_H */
