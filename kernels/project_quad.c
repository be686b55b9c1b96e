/*
 * project_quad.c -- node-quadrangle projection by the three methods of
 * DESIGN.md section 6 (see ct_quad_method in ct_narrow.h for the formulas):
 * four triangles around the centroid, Newton on the bilinear (s, t), and
 * the closed form from distance ratios.
 *
 * Boundary rule shared by Newton and the closed form: the four edges of a
 * bilinear quadrangle are straight, so the closest point of the boundary is
 * analytic; the interior candidate x(s, t) is kept when (s, t) lies in
 * [-1,1]^2 and it is not farther than the boundary's closest point. On a
 * flat parallelogram both methods are then exact, inside and outside.
 *
 * Every block kernel is one `#pragma omp simd` loop over the block's pairs
 * written with scalars and selects (narrow_internal.h). 3-vectors are small
 * structs passed by value, which the compiler splits into scalars.
 */
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

/* ---- Four triangles around the centroid -------------------------------- */

/* Four triangles (O, X_k, X_k+1) around the centroid O; the closest point of
 * their union (ties keep the first). Weights: H_i = u/4 + v [i == k] +
 * w [i == k+1]. */
void cti_nr_block_4tri(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b)
{
    CTI_NR_OUTPTRS(a, k0);
    CTI_NR_INPTRS(a, k0);
    int two = a->two_sided;
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        CTI_NR_LOAD(j);
        /* X1 is the origin. */
        cti_v3 O = v3((ct_real)0.25 * (x2 + (x3 + x4)), (ct_real)0.25 * (y2 + (y3 + y4)),
                      (ct_real)0.25 * (z2 + (z3 + z4)));
        cti_v3 o[4] = {v3(-O.x, -O.y, -O.z), v3(x2 - O.x, y2 - O.y, z2 - O.z),
                       v3(x3 - O.x, y3 - O.y, z3 - O.z), v3(x4 - O.x, y4 - O.y, z4 - O.z)};
        cti_v3 op = v3(px - O.x, py - O.y, pz - O.z);
        ct_real bq = 0, bv = 0, bw = 0, bnn = 0, nnmin = CTI_HUGE, lmax = 0;
        ct_real h[4] = {0, 0, 0, 0};
        cti_v3 bn = v3(0, 0, 0), bc = v3(0, 0, 0);
        cti_nr_int inside = 0;
        _Pragma("GCC unroll 4")
        for (int k = 0; k < 4; k++) {
            cti_v3 A = o[k], B = o[(k + 1) & 3];
            ct_real q, u, v, w, nx, ny, nz, nn, l2;
            cti_nr_int in;
            cti_nr_tri(A.x, A.y, A.z, B.x, B.y, B.z, op.x, op.y, op.z, &q, &u, &v, &w, &nx, &ny,
                       &nz, &nn, &l2, &in);
            cti_nr_int take = (k == 0) | (q < bq);
            bq = take ? q : bq;
            bv = take ? v : bv;
            bw = take ? w : bw;
            bn = v3_sel(take, v3(nx, ny, nz), bn);
            bnn = take ? nn : bnn;
            bc = v3_sel(take, v3_add(v3_scale(v, A), v3_scale(w, B)), bc);
            /* Corner weights of this candidate. */
            ct_real hu = (ct_real)0.25 * u;
            _Pragma("GCC unroll 4")
            for (int i = 0; i < 4; i++) {
                ct_real hi = hu + (i == k ? v : 0) + (i == ((k + 1) & 3) ? w : 0);
                h[i] = take ? hi : h[i];
            }
            nnmin = nn < nnmin ? nn : nnmin;
            lmax = l2 > lmax ? l2 : lmax;
            inside = inside | in;
        }
        ct_real lim = 2 * CTI_NR_AREA_TOL * lmax;
        cti_nr_int degen = !(nnmin > lim * lim);
        cti_nr_int bad = nonfin ? CTI_NR_F(NONFINITE) : (degen ? CTI_NR_F(DEGENERATE) : 0);
        ct_real cx = O.x + bc.x, cy = O.y + bc.y, cz = O.z + bc.z;
        ct_real dist, pen, mx, my, mz;
        cti_nr_int flag;
        cti_nr_finish(px, py, pz, cx, cy, cz, bn.x, bn.y, bn.z, bnn, lmax, inside, g, two,
                      &dist, &pen, &mx, &my, &mz, &flag);
        CTI_NR_STORE(j, bad, dist, pen, mx, my, mz, cx, cy, cz, h[0], h[1], h[2], h[3], g,
                     flag);
    }
    cti_nr_flags_out(b->flag, a->out->flag + k0, n);
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

/* ---- Newton ---------------------------------------------------------------- */

/* One Newton step on f(s,t) = |x(s,t) - p|^2 / 2: the full Hessian when it
 * is safely positive definite, Gauss-Newton otherwise. Iterates are kept in
 * [-3, 3]^2 so a wandering iteration stays finite. *step = |ds| + |dt|. */
CTI_NR_INLINE void cti_newton_step(CTI_QPARAMS, ct_real *s, ct_real *t, ct_real *step)
{
    CTI_QUNUSED;
    ct_real S = *s, T = *t;
    cti_v3 xs = v3_add(a1, v3_scale(T, a3));
    cti_v3 xt = v3_add(a2, v3_scale(S, a3));
    cti_v3 r = v3_sub(cti_quad_x(x0, a1, a2, a3, S, T), P);
    ct_real g1 = v3_dot(r, xs), g2 = v3_dot(r, xt);
    ct_real h11 = v3_dot(xs, xs), h22 = v3_dot(xt, xt), h12 = v3_dot(xs, xt);
    ct_real hf = h12 + v3_dot(r, a3);
    ct_real detf = h11 * h22 - hf * hf;
    ct_real detg = h11 * h22 - h12 * h12;
    cti_nr_int full = detf > (ct_real)1e-6 * h11 * h22;
    ct_real m12 = full ? hf : h12;
    ct_real det = full ? detf : detg;
    ct_real inv = 1 / (det > 0 ? det : 1);
    ct_real ds = -(h22 * g1 - m12 * g2) * inv;
    ct_real dt = -(h11 * g2 - m12 * g1) * inv;
    S += ds;
    T += dt;
    S = S < -3 ? -3 : (S > 3 ? 3 : S);
    T = T < -3 ? -3 : (T > 3 ? 3 : T);
    *s = S;
    *t = T;
    *step = CTI_FABS(ds) + CTI_FABS(dt);
}

/* Start of Newton: the least-squares (s, t) of the quadrangle's affine part
 * x0 + s a1 + t a2 (exact for a parallelogram), kept in [-3, 3]^2. */
static inline void cti_newton_start(CTI_QPARAMS, ct_real *s, ct_real *t)
{
    CTI_QUNUSED;
    cti_v3 r = v3_sub(P, x0);
    ct_real h11 = v3_dot(a1, a1), h22 = v3_dot(a2, a2), h12 = v3_dot(a1, a2);
    ct_real g1 = v3_dot(r, a1), g2 = v3_dot(r, a2);
    cti_v3 c = v3_cross(a1, a2);
    ct_real det = v3_dot(c, c);
    ct_real inv = 1 / (det > 0 ? det : 1);
    ct_real S = (h22 * g1 - h12 * g2) * inv, T = (h11 * g2 - h12 * g1) * inv;
    *s = S < -3 ? -3 : (S > 3 ? 3 : S);
    *t = T < -3 ? -3 : (T > 3 ? 3 : T);
}

/* Bilinear projection by Newton: one vector loop does a fixed number of
 * steps for every pair and writes the outputs; pairs not converged then
 * (last step above the tolerance, NaN included) are redone by a scalar loop
 * that continues to the cap. Which pairs are redone depends on the pair
 * only, so the results do not depend on lanes or threads. */
void cti_nr_block_newton(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b)
{
    CTI_NR_OUTPTRS(a, k0);
    CTI_NR_INPTRS(a, k0);
    int two = a->two_sided;
    ct_real sv[CTI_NR_BLOCK], tv[CTI_NR_BLOCK];
    cti_nr_int redo[CTI_NR_BLOCK];
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        CTI_NR_LOAD(j);
        cti_v3 X2 = v3(x2, y2, z2), X3 = v3(x3, y3, z3), X4 = v3(x4, y4, z4),
               P = v3(px, py, pz);
        CTI_QUAD_MAKE(X2, X3, X4);
        ct_real s, t, st = 0;
        cti_newton_start(CTI_QARGS, &s, &t);
        _Pragma("GCC unroll 8")
        for (int it = 0; it < CTI_NR_NEWTON_VEC_IT; it++)
            cti_newton_step(CTI_QARGS, &s, &t, &st);
        cti_nr_int conv = st <= CTI_NR_NEWTON_TOL;
        sv[j] = s;
        tv[j] = t;
        redo[j] = !conv;
        ct_real cx, cy, cz, nx, ny, nz;
        ct_real h1, h2, h3, h4, dist, pen;
        cti_nr_int degen, flag;
        cti_quad_end(CTI_QARGS, s, t, 1, g, two, &cx, &cy, &cz, &h1, &h2, &h3, &h4, &dist, &pen, &nx, &ny, &nz, &degen, &flag);
        cti_nr_int bad = nonfin ? CTI_NR_F(NONFINITE) : (degen ? CTI_NR_F(DEGENERATE) : 0);
        CTI_NR_STORE(j, bad, dist, pen, nx, ny, nz, cx, cy, cz, h1, h2, h3, h4,
                     g, flag);
    }
    for (ct_idx j = 0; j < n; j++) {
        if (!redo[j])
            continue;
        CTI_NR_LOAD(j);
        cti_v3 X2 = v3(x2, y2, z2), X3 = v3(x3, y3, z3), X4 = v3(x4, y4, z4),
               P = v3(px, py, pz);
        CTI_QUAD_MAKE(X2, X3, X4);
        ct_real s = sv[j], t = tv[j], st = 1;
        for (int it = CTI_NR_NEWTON_VEC_IT; it < CTI_NR_NEWTON_MAX_IT; it++) {
            cti_newton_step(CTI_QARGS, &s, &t, &st);
            if (st <= CTI_NR_NEWTON_TOL)
                break;
        }
        cti_nr_int conv = st <= CTI_NR_NEWTON_TOL;
        /* Not converged inside the square: keep the best of the iterate and
         * the boundary, and say so. Not converged outside: the boundary. */
        cti_nr_int fb = (!conv) & (CTI_FABS(s) <= 1) & (CTI_FABS(t) <= 1);
        ct_real cx, cy, cz, nx, ny, nz;
        ct_real h1, h2, h3, h4, dist, pen;
        cti_nr_int degen, flag;
        cti_quad_end(CTI_QARGS, s, t, conv | fb, g, two, &cx, &cy, &cz, &h1, &h2, &h3, &h4, &dist, &pen, &nx, &ny, &nz, &degen, &flag);
        cti_nr_int bad = nonfin ? CTI_NR_F(NONFINITE) : (degen ? CTI_NR_F(DEGENERATE) : 0);
        flag |= fb ? CTI_NR_F(FALLBACK) : 0;
        CTI_NR_STORE(j, bad, dist, pen, nx, ny, nz, cx, cy, cz, h1, h2, h3, h4,
                     g, flag);
    }
    cti_nr_flags_out(b->flag, a->out->flag + k0, n);
}

/* ---- Closed form ----------------------------------------------------------- */

/* (B - A) x (p - A) . m: the signed in-plane distance of p to the line
 * A -> B times |m| |B - A|, positive on the inner side. */
static inline ct_real cti_closed_line(cti_v3 A, cti_v3 B, cti_v3 p, cti_v3 m)
{
    return v3_dot(v3_cross(v3_sub(B, A), v3_sub(p, A)), m);
}

static inline ct_real cti_closed_len(cti_v3 A, cti_v3 B)
{
    cti_v3 u = v3_sub(B, A);
    ct_real l2 = v3_dot(u, u);
    return CTI_SQRT(l2 > 0 ? l2 : 1);
}

/* Closed-form (s, t) from the in-plane distances to the four edge lines:
 * with d = c / L (c from cti_closed_line, L the edge length),
 * s = (d41 - d23) / (d41 + d23) = (c41 L23 - c23 L41) / (c41 L23 + c23 L41). */
void cti_nr_block_closed(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b)
{
    CTI_NR_OUTPTRS(a, k0);
    CTI_NR_INPTRS(a, k0);
    int two = a->two_sided;
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        CTI_NR_LOAD(j);
        cti_v3 X1 = v3(0, 0, 0), X2 = v3(x2, y2, z2), X3 = v3(x3, y3, z3),
               X4 = v3(x4, y4, z4), P = v3(px, py, pz), p = P;
        CTI_QUAD_MAKE(X2, X3, X4);
        /* Mean normal m = (X3 - X1) x (X4 - X2); its length cancels in the
         * ratios, so it is not normalised. */
        cti_v3 m = v3_cross(X3, v3_sub(X4, X2));
        ct_real c41 = cti_closed_line(X4, X1, p, m), c23 = cti_closed_line(X2, X3, p, m);
        ct_real c12 = cti_closed_line(X1, X2, p, m), c34 = cti_closed_line(X3, X4, p, m);
        ct_real L41 = cti_closed_len(X4, X1), L23 = cti_closed_len(X2, X3);
        ct_real L12 = cti_closed_len(X1, X2), L34 = cti_closed_len(X3, X4);
        ct_real ns = c41 * L23 - c23 * L41, dens = c41 * L23 + c23 * L41;
        ct_real nt = c12 * L34 - c34 * L12, dent = c12 * L34 + c34 * L12;
        ct_real s = ns / (dens > 0 ? dens : 1);
        ct_real t = nt / (dent > 0 ? dent : 1);
        s = dens > 0 ? s : 2;
        t = dent > 0 ? t : 2;
        s = s < -2 ? -2 : (s > 2 ? 2 : s);
        t = t < -2 ? -2 : (t > 2 ? 2 : t);
        ct_real cx, cy, cz, nx, ny, nz;
        ct_real h1, h2, h3, h4, dist, pen;
        cti_nr_int degen, flag;
        cti_quad_end(CTI_QARGS, s, t, 1, g, two, &cx, &cy, &cz, &h1, &h2, &h3, &h4, &dist, &pen, &nx, &ny, &nz, &degen, &flag);
        cti_nr_int bad = nonfin ? CTI_NR_F(NONFINITE) : (degen ? CTI_NR_F(DEGENERATE) : 0);
        CTI_NR_STORE(j, bad, dist, pen, nx, ny, nz, cx, cy, cz, h1, h2, h3, h4,
                     g, flag);
    }
    cti_nr_flags_out(b->flag, a->out->flag + k0, n);
}
