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
 */
#include "narrow_internal.h"

/* One sub-triangle candidate of the 4-triangle method. */
#define CTI_NR_4TRI_CAND(k, kk)                                                           \
    do {                                                                                  \
        ct_real q, u, v, w, nx, ny, nz, nn, l2;                                           \
        int in;                                                                           \
        cti_nr_tri(o##k[0], o##k[1], o##k[2], o##kk[0], o##kk[1], o##kk[2], op[0], op[1], \
                   op[2], &q, &u, &v, &w, &nx, &ny, &nz, &nn, &l2, &in);                  \
        int take = ((k) == 0) | (q < bq);                                                    \
        bq = take ? q : bq;                                                               \
        bk = take ? (k) : bk;                                                             \
        bu = take ? u : bu;                                                               \
        bv = take ? v : bv;                                                               \
        bw = take ? w : bw;                                                               \
        bnx = take ? nx : bnx;                                                            \
        bny = take ? ny : bny;                                                            \
        bnz = take ? nz : bnz;                                                            \
        bnn = take ? nn : bnn;                                                            \
        e0[0] = take ? o##k[0] : e0[0];                                                   \
        e0[1] = take ? o##k[1] : e0[1];                                                   \
        e0[2] = take ? o##k[2] : e0[2];                                                   \
        e1[0] = take ? o##kk[0] : e1[0];                                                  \
        e1[1] = take ? o##kk[1] : e1[1];                                                  \
        e1[2] = take ? o##kk[2] : e1[2];                                                  \
        nnmin = nn < nnmin ? nn : nnmin;                                                  \
        lmax = l2 > lmax ? l2 : lmax;                                                     \
        inside = inside | in;                                                             \
    } while (0)

/* Four triangles (O, X_k, X_k+1) around the centroid O; the closest point of
 * their union. Weights: H_i = u/4 + v [i == k] + w [i == k+1]. */
void cti_nr_block_4tri(const cti_nr_args *a, ct_idx k0, ct_idx n, const cti_nr_blk *blk)
{
    CTI_NR_OUTPTRS(a, k0);
    int two = a->two_sided;
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        ct_real p[3], X1[3], X2[3], X3[3], X4[3], g, org[3];
        ct_real zs = cti_nr_get(blk, j, p, X1, X2, X3, X4, &g, org);
        int nonfin = cti_nr_nonfinite(zs);
        ct_real O[3], o0[3], o1[3], o2[3], o3[3], op[3], e0[3] = {0, 0, 0}, e1[3] = {0, 0, 0};
        _Pragma("GCC unroll 4")
        for (int d = 0; d < 3; d++) {
            O[d] = (ct_real)0.25 * ((X1[d] + X2[d]) + (X3[d] + X4[d]));
            o0[d] = X1[d] - O[d];
            o1[d] = X2[d] - O[d];
            o2[d] = X3[d] - O[d];
            o3[d] = X4[d] - O[d];
            op[d] = p[d] - O[d];
        }
        ct_real bq = 0, bu = 0, bv = 0, bw = 0, bnx = 0, bny = 0, bnz = 0, bnn = 0;
        ct_real nnmin = CTI_HUGE, lmax = 0;
        int bk = 0, inside = 0;
        CTI_NR_4TRI_CAND(0, 1);
        CTI_NR_4TRI_CAND(1, 2);
        CTI_NR_4TRI_CAND(2, 3);
        CTI_NR_4TRI_CAND(3, 0);
        (void)bq;
        ct_real lim = 2 * CTI_NR_AREA_TOL * lmax;
        int degen = !(nnmin > lim * lim);
        int bad = nonfin ? CT_NARROW_NONFINITE : (degen ? CT_NARROW_DEGENERATE : 0);
        ct_real cx = O[0] + bv * e0[0] + bw * e1[0];
        ct_real cy = O[1] + bv * e0[1] + bw * e1[1];
        ct_real cz = O[2] + bv * e0[2] + bw * e1[2];
        ct_real hu = (ct_real)0.25 * bu;
        ct_real h1 = hu + (bk == 0 ? bv : 0) + (bk == 3 ? bw : 0);
        ct_real h2 = hu + (bk == 1 ? bv : 0) + (bk == 0 ? bw : 0);
        ct_real h3 = hu + (bk == 2 ? bv : 0) + (bk == 1 ? bw : 0);
        ct_real h4 = hu + (bk == 3 ? bv : 0) + (bk == 2 ? bw : 0);
        ct_real inv = 1 / CTI_SQRT(bnn > 0 ? bnn : 1);
        ct_real dist, pen, mx, my, mz;
        int flag;
        cti_nr_finish(p[0], p[1], p[2], cx, cy, cz, bnx * inv, bny * inv, bnz * inv,
                      CTI_SQRT(lmax), inside, g, two, &dist, &pen, &mx, &my, &mz, &flag);
        CTI_NR_STORE(j, bad, dist, pen, mx, my, mz, cx, cy, cz, h1, h2, h3, h4, g, flag);
    }
}

/* One Newton step on f(s,t) = |x(s,t) - p|^2 / 2: the full Hessian when it
 * is safely positive definite, Gauss-Newton otherwise. Iterates are kept in
 * [-3, 3]^2 so a wandering iteration stays finite. *step = |ds| + |dt|. */
static inline void cti_nr_newton_step(const cti_bilin *b, const ct_real p[3], ct_real *s,
                                      ct_real *t, ct_real *step)
{
    ct_real S = *s, T = *t;
    ct_real g1 = 0, g2 = 0, h11 = 0, h22 = 0, h12 = 0, ra3 = 0;
    _Pragma("GCC unroll 4")
    for (int i = 0; i < 3; i++) {
        ct_real xs = b->a1[i] + T * b->a3[i];
        ct_real xt = b->a2[i] + S * b->a3[i];
        ct_real r = b->x0[i] + S * b->a1[i] + T * b->a2[i] + S * T * b->a3[i] - p[i];
        g1 += r * xs;
        g2 += r * xt;
        h11 += xs * xs;
        h22 += xt * xt;
        h12 += xs * xt;
        ra3 += r * b->a3[i];
    }
    ct_real hf = h12 + ra3;
    ct_real detf = h11 * h22 - hf * hf;
    ct_real detg = h11 * h22 - h12 * h12;
    int full = detf > (ct_real)1e-6 * h11 * h22;
    ct_real m12 = full ? hf : h12;
    ct_real det = full ? detf : detg;
    det = det > 0 ? det : 1;
    ct_real ds = -(h22 * g1 - m12 * g2) / det;
    ct_real dt = -(h11 * g2 - m12 * g1) / det;
    S += ds;
    T += dt;
    S = S < -3 ? -3 : (S > 3 ? 3 : S);
    T = T < -3 ? -3 : (T > 3 ? 3 : T);
    *s = S;
    *t = T;
    *step = CTI_FABS(ds) + CTI_FABS(dt);
}

/* The common end of Newton and the closed form: choose the interior
 * candidate (s, t) or the boundary, then compute the outputs. `trusted`
 * says (s, t) is a stationary point (or the fallback iterate). */
static inline void cti_nr_quad_end(const cti_bilin *b, const ct_real p[3], const ct_real X1[3],
                                   const ct_real X2[3], const ct_real X3[3],
                                   const ct_real X4[3], ct_real s, ct_real t, int trusted,
                                   ct_real g, int two, ct_real c[3], ct_real h[4],
                                   ct_real *dist, ct_real *pen, ct_real nrm[3], int *degen,
                                   int *flag)
{
    ct_real bs, bt, bq;
    cti_nr_quad_boundary(X1, X2, X3, X4, p, &bs, &bt, &bq);
    int interior = trusted & (CTI_FABS(s) <= 1) & (CTI_FABS(t) <= 1);
    ct_real si = interior ? s : 0, ti = interior ? t : 0;
    ct_real qi = cti_bilin_dist2(b, si, ti, p);
    int take = interior & (qi <= bq);
    int near = trusted & (CTI_FABS(s) <= 1 + CTI_NR_IN_TOL) & (CTI_FABS(t) <= 1 + CTI_NR_IN_TOL);
    int in = take | (near & !interior);
    ct_real fs = take ? si : bs, ft = take ? ti : bt;
    ct_real N[3], size;
    cti_nr_quad_out(b, X1, X2, X3, X4, fs, ft, c, h, N, &size, degen);
    cti_nr_finish(p[0], p[1], p[2], c[0], c[1], c[2], N[0], N[1], N[2], size, in, g, two,
                  dist, pen, &nrm[0], &nrm[1], &nrm[2], flag);
}

/* Bilinear projection by Newton: a fixed number of steps for every pair in
 * a vector loop, the pairs not yet converged continue in a scalar loop,
 * then a vector loop chooses interior or boundary and writes the outputs. */
void cti_nr_block_newton(const cti_nr_args *a, ct_idx k0, ct_idx n, const cti_nr_blk *blk)
{
    CTI_NR_OUTPTRS(a, k0);
    int two = a->two_sided;
    ct_real sv[CTI_NR_BLOCK], tv[CTI_NR_BLOCK], stv[CTI_NR_BLOCK];
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        ct_real p[3], X1[3], X2[3], X3[3], X4[3], g, org[3];
        cti_nr_get(blk, j, p, X1, X2, X3, X4, &g, org);
        cti_bilin b;
        cti_bilin_make(&b, X1, X2, X3, X4);
        ct_real s = 0, t = 0, st = 0;
        _Pragma("GCC unroll 8")
        for (int it = 0; it < CTI_NR_NEWTON_VEC_IT; it++)
            cti_nr_newton_step(&b, p, &s, &t, &st);
        sv[j] = s;
        tv[j] = t;
        stv[j] = st;
    }
    for (ct_idx j = 0; j < n; j++) {
        /* NaN steps never compare <= tol: such pairs iterate to the cap and
         * are skipped as non-finite at the end. */
        if (stv[j] <= CTI_NR_NEWTON_TOL)
            continue;
        ct_real p[3], X1[3], X2[3], X3[3], X4[3], g, org[3];
        cti_nr_get(blk, j, p, X1, X2, X3, X4, &g, org);
        cti_bilin b;
        cti_bilin_make(&b, X1, X2, X3, X4);
        ct_real s = sv[j], t = tv[j], st = stv[j];
        for (int it = CTI_NR_NEWTON_VEC_IT;
             it < CTI_NR_NEWTON_MAX_IT && !(st <= CTI_NR_NEWTON_TOL); it++)
            cti_nr_newton_step(&b, p, &s, &t, &st);
        sv[j] = s;
        tv[j] = t;
        stv[j] = st;
    }
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        ct_real p[3], X1[3], X2[3], X3[3], X4[3], g, org[3];
        ct_real zs = cti_nr_get(blk, j, p, X1, X2, X3, X4, &g, org);
        int nonfin = cti_nr_nonfinite(zs);
        cti_bilin b;
        cti_bilin_make(&b, X1, X2, X3, X4);
        ct_real s = sv[j], t = tv[j];
        int conv = stv[j] <= CTI_NR_NEWTON_TOL;
        /* Not converged inside the square: keep the best of the iterate and
         * the boundary, and say so. Not converged outside: the boundary. */
        int fb = (!conv) & (CTI_FABS(s) <= 1) & (CTI_FABS(t) <= 1);
        ct_real c[3], h[4], dist, pen, nrm[3];
        int degen, flag;
        cti_nr_quad_end(&b, p, X1, X2, X3, X4, s, t, conv | fb, g, two, c, h, &dist, &pen,
                        nrm, &degen, &flag);
        int bad = nonfin ? CT_NARROW_NONFINITE : (degen ? CT_NARROW_DEGENERATE : 0);
        flag |= fb ? CT_NARROW_FALLBACK : 0;
        CTI_NR_STORE(j, bad, dist, pen, nrm[0], nrm[1], nrm[2], c[0], c[1], c[2], h[0], h[1],
                     h[2], h[3], g, flag);
    }
}

/* Signed in-plane distance (times |m|) of p to the line A -> B, positive on
 * the inner side: ((B - A) x (p - A)).m / |B - A|. */
static inline ct_real cti_nr_line_dist(const ct_real A[3], const ct_real B[3],
                                       const ct_real p[3], const ct_real m[3])
{
    ct_real u[3], w[3];
    _Pragma("GCC unroll 4")
    for (int i = 0; i < 3; i++) {
        u[i] = B[i] - A[i];
        w[i] = p[i] - A[i];
    }
    ct_real cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2],
            cz = u[0] * w[1] - u[1] * w[0];
    ct_real l2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    return (cx * m[0] + cy * m[1] + cz * m[2]) / CTI_SQRT(l2 > 0 ? l2 : 1);
}

/* Closed-form (s, t) from the in-plane distances to the four edge lines. */
void cti_nr_block_closed(const cti_nr_args *a, ct_idx k0, ct_idx n, const cti_nr_blk *blk)
{
    CTI_NR_OUTPTRS(a, k0);
    int two = a->two_sided;
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        ct_real p[3], X1[3], X2[3], X3[3], X4[3], g, org[3];
        ct_real zs = cti_nr_get(blk, j, p, X1, X2, X3, X4, &g, org);
        int nonfin = cti_nr_nonfinite(zs);
        cti_bilin b;
        cti_bilin_make(&b, X1, X2, X3, X4);
        /* Mean normal m = (X3 - X1) x (X4 - X2); its length cancels in the
         * ratios, so it is not normalised. */
        ct_real d1[3], d2[3];
        _Pragma("GCC unroll 4")
        for (int i = 0; i < 3; i++) {
            d1[i] = X3[i] - X1[i];
            d2[i] = X4[i] - X2[i];
        }
        ct_real m[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                        d1[0] * d2[1] - d1[1] * d2[0]};
        ct_real d41 = cti_nr_line_dist(X4, X1, p, m), d23 = cti_nr_line_dist(X2, X3, p, m);
        ct_real d12 = cti_nr_line_dist(X1, X2, p, m), d34 = cti_nr_line_dist(X3, X4, p, m);
        ct_real dens = d41 + d23, dent = d12 + d34;
        ct_real s = (d41 - d23) / (dens > 0 ? dens : 1);
        ct_real t = (d12 - d34) / (dent > 0 ? dent : 1);
        s = dens > 0 ? s : 2;
        t = dent > 0 ? t : 2;
        s = s < -2 ? -2 : (s > 2 ? 2 : s);
        t = t < -2 ? -2 : (t > 2 ? 2 : t);
        ct_real c[3], h[4], dist, pen, nrm[3];
        int degen, flag;
        cti_nr_quad_end(&b, p, X1, X2, X3, X4, s, t, 1, g, two, c, h, &dist, &pen, nrm,
                        &degen, &flag);
        int bad = nonfin ? CT_NARROW_NONFINITE : (degen ? CT_NARROW_DEGENERATE : 0);
        CTI_NR_STORE(j, bad, dist, pen, nrm[0], nrm[1], nrm[2], c[0], c[1], c[2], h[0], h[1],
                     h[2], h[3], g, flag);
    }
}
