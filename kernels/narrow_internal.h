/*
 * narrow_internal.h -- helpers shared by the narrow-phase kernels
 * (project.c, project_quad.c, edge.c). Every helper is a branch-free inline
 * function of scalars, so a `#pragma omp simd` loop over pairs that calls
 * them vectorises, and a pair gives bit-identical results whether it lands
 * in a vector lane or in a scalar remainder loop (only +, -, *, /, sqrt and
 * selects are used; no libm call that could differ between the two).
 */
#ifndef NARROW_INTERNAL_H
#define NARROW_INTERNAL_H

#include "ct_internal.h"

/* Pairs per block: the unit of work of the parallel loops (so the split of
 * the work among threads never changes which code path a pair takes). */
#define CTI_NR_BLOCK 128

#ifdef CT_SINGLE
#define CTI_NR_AREA_TOL 1.0e-6f  /* degenerate: area <= tol * longest edge^2 */
#define CTI_NR_IN_TOL 1.0e-5f    /* footprint tolerance in parameter space */
#define CTI_NR_ON_TOL 1.0e-6f    /* on the surface: D <= tol * segment size */
#define CTI_NR_NEWTON_TOL 1.0e-5f
#define CTI_NR_EDGE_TOL 1.0e-6f  /* edge-edge: degenerate edge length ratio */
#else
#define CTI_NR_AREA_TOL 1.0e-12
#define CTI_NR_IN_TOL 1.0e-10
#define CTI_NR_ON_TOL 1.0e-14
#define CTI_NR_NEWTON_TOL 1.0e-12
#define CTI_NR_EDGE_TOL 1.0e-12
#endif

/* `#pragma omp simd` on the pair loops (gcc). Neither compiler vectorises
 * sqrt while it may set errno: the loops vectorise only in a build with
 * -fno-math-errno (same, correctly rounded results). clang 14 does not
 * vectorise these loops even then, and a forced loop that fails is an
 * error under -Werror, so clang gets no pragma. */
#if defined(__clang__)
#define CTI_NR_SIMD
#else
#define CTI_NR_SIMD _Pragma("omp simd")
#endif

/* Newton: iterations done for every pair in the vector loop, then the cap
 * for the pairs that have not converged yet (scalar loop). */
#define CTI_NR_NEWTON_VEC_IT 5
#define CTI_NR_NEWTON_MAX_IT 30

/* Everything a node-segment block kernel needs (internal; the public API
 * takes the arrays one by one). */
typedef struct cti_nr_args {
    const ct_idx *node, *seg, *n1, *n2, *n3, *n4;
    const ct_real *x, *y, *z;
    const ct_real *gap_node, *gap_seg;
    ct_real gap, gap_max_s, gap_max_m;
    int two_sided;
    const ct_contact_geo *out;
} cti_nr_args;

/* A block's inputs gathered into contiguous arrays (pairs k0 + j): the
 * node p, the corners X1..X4 and the pair gap. The compute loops then read
 * only these, which keeps them free of indirect and conditional loads. */
typedef struct cti_nr_blk {
    ct_real p[3][CTI_NR_BLOCK];
    ct_real X[4][3][CTI_NR_BLOCK];
    ct_real g[CTI_NR_BLOCK];
} cti_nr_blk;

void cti_nr_gather(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b);

/* Block kernels: pairs [k0, k0 + n), n <= CTI_NR_BLOCK, all triangles or all
 * quadrangles, inputs gathered in b. */
void cti_nr_block_tri(const cti_nr_args *a, ct_idx k0, ct_idx n, const cti_nr_blk *b);
void cti_nr_block_4tri(const cti_nr_args *a, ct_idx k0, ct_idx n, const cti_nr_blk *b);
void cti_nr_block_newton(const cti_nr_args *a, ct_idx k0, ct_idx n, const cti_nr_blk *b);
void cti_nr_block_closed(const cti_nr_args *a, ct_idx k0, ct_idx n, const cti_nr_blk *b);

/* The output arrays of a block as restrict locals o_*, offset by k0. */
#define CTI_NR_OUTPTRS(a, k0)                                                             \
    const ct_contact_geo *o_ = (a)->out;                                                  \
    ct_real *restrict o_dist = o_->dist + (k0), *restrict o_pen = o_->pen + (k0);         \
    ct_real *restrict o_nx = o_->nx + (k0), *restrict o_ny = o_->ny + (k0);               \
    ct_real *restrict o_nz = o_->nz + (k0), *restrict o_cx = o_->cx + (k0);               \
    ct_real *restrict o_cy = o_->cy + (k0), *restrict o_cz = o_->cz + (k0);               \
    ct_real *restrict o_h1 = o_->h1 + (k0), *restrict o_h2 = o_->h2 + (k0);               \
    ct_real *restrict o_h3 = o_->h3 + (k0), *restrict o_h4 = o_->h4 + (k0);               \
    ct_real *restrict o_gap = o_->gap + (k0);                                             \
    uint8_t *restrict o_flag = o_->flag + (k0)

/* Write pair j of the block, or the documented skip values when bad != 0;
 * the contact point (cx, cy, cz) is relative to org (see cti_nr_get). */
#define CTI_NR_STORE(j, bad, dist, pen, nx, ny, nz, cx, cy, cz, h1, h2, h3, h4, g, flag)  \
    do {                                                                                  \
        o_dist[j] = (bad) ? CT_NARROW_FAR : (dist);                                       \
        o_pen[j] = (bad) ? 0 : (pen);                                                     \
        o_nx[j] = (bad) ? 0 : (nx);                                                       \
        o_ny[j] = (bad) ? 0 : (ny);                                                       \
        o_nz[j] = (bad) ? 1 : (nz);                                                       \
        o_cx[j] = (bad) ? 0 : (cx) + org[0];                                              \
        o_cy[j] = (bad) ? 0 : (cy) + org[1];                                              \
        o_cz[j] = (bad) ? 0 : (cz) + org[2];                                              \
        o_h1[j] = (bad) ? 0 : (h1);                                                       \
        o_h2[j] = (bad) ? 0 : (h2);                                                       \
        o_h3[j] = (bad) ? 0 : (h3);                                                       \
        o_h4[j] = (bad) ? 0 : (h4);                                                       \
        o_gap[j] = ((bad) & CT_NARROW_NONFINITE) ? 0 : (g);                               \
        o_flag[j] = (uint8_t)((bad) ? (bad) : (flag));                                    \
    } while (0)

/* Load pair j of a block, translated so that X1 is at the origin (o gets
 * X1); returns the non-finite test sum (gap included). */
static inline ct_real cti_nr_get(const cti_nr_blk *b, ct_idx j, ct_real p[3], ct_real X1[3],
                                 ct_real X2[3], ct_real X3[3], ct_real X4[3], ct_real *g,
                                 ct_real o[3])
{
#define CTI_NR_GET1(d)                                                                    \
    p[d] = b->p[d][j];                                                                    \
    X1[d] = b->X[0][d][j];                                                                \
    X2[d] = b->X[1][d][j];                                                                \
    X3[d] = b->X[2][d][j];                                                                \
    X4[d] = b->X[3][d][j]
    CTI_NR_GET1(0);
    CTI_NR_GET1(1);
    CTI_NR_GET1(2);
#undef CTI_NR_GET1
    ct_real z = 0;
    for (int d = 0; d < 3; d++)
        z += (p[d] - p[d]) + (X1[d] - X1[d]) + (X2[d] - X2[d]) + (X3[d] - X3[d]) +
             (X4[d] - X4[d]);
    /* Work relative to X1 (o receives it): differences of nearby
     * coordinates keep their accuracy far from the origin, which single
     * precision needs. */
    for (int d = 0; d < 3; d++) {
        o[d] = X1[d];
        p[d] -= o[d];
        X2[d] -= o[d];
        X3[d] -= o[d];
        X4[d] -= o[d];
        X1[d] = 0;
    }
    *g = b->g[j];
    return z + (*g - *g);
}

static inline ct_real cti_nr_clamp01(ct_real u)
{
    u = u > 0 ? u : 0;
    return u < 1 ? u : 1;
}

/* 0 when every argument is finite (x - x is 0 for a finite x, NaN else). */
static inline int cti_nr_nonfinite(ct_real s)
{
    return !(s == 0);
}

/*
 * Closest point of triangle (a, a + ab, a + ac) to a + ap, branch-free:
 * the face projection when it falls inside, else the nearest of the three
 * edges (each with an explicitly formed residual, so the comparison is
 * accurate near vertices). Outputs: squared distance *q, barycentric
 * weights of a, b, c (*u, *v, *w), the unnormalised normal ab x ac and its
 * squared length *nn, the squared longest edge *l2, and *in = 1 when the
 * unclamped projection lies inside within CTI_NR_IN_TOL.
 */
static inline void cti_nr_tri(ct_real abx, ct_real aby, ct_real abz, ct_real acx,
                              ct_real acy, ct_real acz, ct_real apx, ct_real apy,
                              ct_real apz, ct_real *q, ct_real *u, ct_real *v, ct_real *w,
                              ct_real *nx, ct_real *ny, ct_real *nz, ct_real *nn,
                              ct_real *l2, int *in)
{
    ct_real cx = aby * acz - abz * acy;
    ct_real cy = abz * acx - abx * acz;
    ct_real cz = abx * acy - aby * acx;
    ct_real n2 = cx * cx + cy * cy + cz * cz;
    ct_real aa = abx * abx + aby * aby + abz * abz;
    ct_real cc = acx * acx + acy * acy + acz * acz;
    ct_real ac = abx * acx + aby * acy + abz * acz;
    ct_real d1 = abx * apx + aby * apy + abz * apz;
    ct_real d2 = acx * apx + acy * apy + acz * apz;
    ct_real bcx = acx - abx, bcy = acy - aby, bcz = acz - abz;
    ct_real bpx = apx - abx, bpy = apy - aby, bpz = apz - abz;
    ct_real bb = bcx * bcx + bcy * bcy + bcz * bcz;
    ct_real d3 = bcx * bpx + bcy * bpy + bcz * bpz;
    ct_real lm = aa > cc ? aa : cc;
    lm = lm > bb ? lm : bb;
    /* Face: barycentric coordinates from the normal equations, with the
     * determinant taken as |ab x ac|^2 (no cancellation). */
    ct_real inv = 1 / (n2 > 0 ? n2 : 1);
    ct_real fv = (cc * d1 - ac * d2) * inv;
    ct_real fw = (aa * d2 - ac * d1) * inv;
    ct_real fu = 1 - fv - fw;
    ct_real h = apx * cx + apy * cy + apz * cz;
    ct_real qf = h * h * inv;
    int face = (fv >= 0) & (fw >= 0) & (fu >= 0);
    *in = (fv >= -CTI_NR_IN_TOL) & (fw >= -CTI_NR_IN_TOL) & (fu >= -CTI_NR_IN_TOL);
    /* Edges a-b, a-c, b-c. */
    ct_real t1 = cti_nr_clamp01(d1 / (aa > 0 ? aa : 1));
    ct_real t2 = cti_nr_clamp01(d2 / (cc > 0 ? cc : 1));
    ct_real t3 = cti_nr_clamp01(d3 / (bb > 0 ? bb : 1));
    ct_real rx = apx - t1 * abx, ry = apy - t1 * aby, rz = apz - t1 * abz;
    ct_real q1 = rx * rx + ry * ry + rz * rz;
    rx = apx - t2 * acx; ry = apy - t2 * acy; rz = apz - t2 * acz;
    ct_real q2 = rx * rx + ry * ry + rz * rz;
    rx = bpx - t3 * bcx; ry = bpy - t3 * bcy; rz = bpz - t3 * bcz;
    ct_real q3 = rx * rx + ry * ry + rz * rz;
    ct_real eu = 1 - t1, ev = t1, ew = 0, eq = q1;
    if (q2 < eq) { eu = 1 - t2; ev = 0; ew = t2; eq = q2; }
    if (q3 < eq) { eu = 0; ev = 1 - t3; ew = t3; eq = q3; }
    *q = face ? qf : eq;
    *u = face ? fu : eu;
    *v = face ? fv : ev;
    *w = face ? fw : ew;
    *nx = cx; *ny = cy; *nz = cz;
    *nn = n2;
    *l2 = lm;
}

/*
 * The sidedness rule and the outputs common to every node-segment method
 * (see ct_narrow.h): r = p - c, N the unit segment normal at c, size the
 * segment's size, in the footprint test, g the pair's gap.
 */
static inline void cti_nr_finish(ct_real px, ct_real py, ct_real pz, ct_real cx, ct_real cy,
                                 ct_real cz, ct_real Nx, ct_real Ny, ct_real Nz,
                                 ct_real size, int in, ct_real g, int two_sided,
                                 ct_real *dist, ct_real *pen, ct_real *nx, ct_real *ny,
                                 ct_real *nz, int *flag)
{
    ct_real rx = px - cx, ry = py - cy, rz = pz - cz;
    ct_real r = CTI_SQRT(rx * rx + ry * ry + rz * rz);
    int on = r <= CTI_NR_ON_TOL * size;
    ct_real inv = 1 / (on ? 1 : r);
    ct_real side = rx * Nx + ry * Ny + rz * Nz;
    int behind = (!two_sided) & (!on) & (side < 0);
    ct_real gr = g - r;
    *dist = behind ? -r : r;
    *pen = behind ? (in ? g + r : 0) : (gr > 0 ? gr : 0);
    *nx = (behind | on) ? Nx : rx * inv;
    *ny = (behind | on) ? Ny : ry * inv;
    *nz = (behind | on) ? Nz : rz * inv;
    *flag = (behind ? CT_NARROW_BEHIND : 0) | (in ? 0 : CT_NARROW_OUTSIDE);
}

/*
 * Bilinear quadrangle helpers. x(s,t) = x0 + s a1 + t a2 + s t a3 with
 * x0 = (X1+X2+X3+X4)/4, a1 = (-X1+X2+X3-X4)/4, a2 = (-X1-X2+X3+X4)/4,
 * a3 = (X1-X2+X3-X4)/4, which is sum H_i X_i with the shape functions of
 * DESIGN.md section 6.
 */
typedef struct cti_bilin {
    ct_real x0[3], a1[3], a2[3], a3[3];
} cti_bilin;

static inline void cti_bilin_make(cti_bilin *b, const ct_real X1[3], const ct_real X2[3],
                                  const ct_real X3[3], const ct_real X4[3])
{
    _Pragma("GCC unroll 4")
    for (int i = 0; i < 3; i++) {
        b->x0[i] = (ct_real)0.25 * ((X1[i] + X2[i]) + (X3[i] + X4[i]));
        b->a1[i] = (ct_real)0.25 * ((X2[i] - X1[i]) + (X3[i] - X4[i]));
        b->a2[i] = (ct_real)0.25 * ((X4[i] - X1[i]) + (X3[i] - X2[i]));
        b->a3[i] = (ct_real)0.25 * ((X1[i] - X2[i]) + (X3[i] - X4[i]));
    }
}

/* Closest point of the straight edge P0 -> P1 to p: parameter u in [0, 1]
 * and squared distance. */
static inline void cti_nr_edge(const ct_real P0[3], const ct_real P1[3], const ct_real p[3],
                               ct_real *u, ct_real *q)
{
    ct_real ex = P1[0] - P0[0], ey = P1[1] - P0[1], ez = P1[2] - P0[2];
    ct_real wx = p[0] - P0[0], wy = p[1] - P0[1], wz = p[2] - P0[2];
    ct_real ee = ex * ex + ey * ey + ez * ez;
    ct_real uu = cti_nr_clamp01((wx * ex + wy * ey + wz * ez) / (ee > 0 ? ee : 1));
    ct_real rx = wx - uu * ex, ry = wy - uu * ey, rz = wz - uu * ez;
    *u = uu;
    *q = rx * rx + ry * ry + rz * rz;
}

/* The closest point of the quadrangle's boundary (four straight edges):
 * its (s, t) and squared distance. Ties keep the first edge in the order
 * 1-2, 2-3, 4-3, 1-4. */
static inline void cti_nr_quad_boundary(const ct_real X1[3], const ct_real X2[3],
                                        const ct_real X3[3], const ct_real X4[3],
                                        const ct_real p[3], ct_real *s, ct_real *t,
                                        ct_real *q)
{
    ct_real u, qe;
    cti_nr_edge(X1, X2, p, &u, &qe);
    ct_real bs = 2 * u - 1, bt = -1, bq = qe;
    cti_nr_edge(X2, X3, p, &u, &qe);
    int take = qe < bq;
    bs = take ? 1 : bs;
    bt = take ? 2 * u - 1 : bt;
    bq = take ? qe : bq;
    cti_nr_edge(X4, X3, p, &u, &qe);
    take = qe < bq;
    bs = take ? 2 * u - 1 : bs;
    bt = take ? 1 : bt;
    bq = take ? qe : bq;
    cti_nr_edge(X1, X4, p, &u, &qe);
    take = qe < bq;
    bs = take ? -1 : bs;
    bt = take ? 2 * u - 1 : bt;
    bq = take ? qe : bq;
    *s = bs;
    *t = bt;
    *q = bq;
}

/* Squared distance from p to x(s, t). */
static inline ct_real cti_bilin_dist2(const cti_bilin *b, ct_real s, ct_real t,
                                      const ct_real p[3])
{
    ct_real q = 0;
    _Pragma("GCC unroll 4")
    for (int i = 0; i < 3; i++) {
        ct_real r = b->x0[i] + s * b->a1[i] + t * b->a2[i] + s * t * b->a3[i] - p[i];
        q += r * r;
    }
    return q;
}

/* Corner triangle A, B, D: keep the smallest squared |AB x AD| and the
 * longest squared edge AB. */
static inline void cti_nr_corner(const ct_real A[3], const ct_real B[3], const ct_real D[3],
                                 ct_real *amin, ct_real *lmax)
{
    ct_real e[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    ct_real f[3] = {D[0] - A[0], D[1] - A[1], D[2] - A[2]};
    ct_real gx = e[1] * f[2] - e[2] * f[1], gy = e[2] * f[0] - e[0] * f[2],
            gz = e[0] * f[1] - e[1] * f[0];
    ct_real a2 = gx * gx + gy * gy + gz * gz;
    ct_real l2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    *amin = a2 < *amin ? a2 : *amin;
    *lmax = l2 > *lmax ? l2 : *lmax;
}

/*
 * Final outputs of a bilinear quad at (s, t): point x(s,t), shape weights
 * H1..H4, unit normal x_s x x_t (the mean normal (X3-X1) x (X4-X2) where the
 * Jacobian vanishes), the degeneracy test on the four corner triangles and
 * the longest edge.
 */
static inline void cti_nr_quad_out(const cti_bilin *b, const ct_real X1[3],
                                   const ct_real X2[3], const ct_real X3[3],
                                   const ct_real X4[3], ct_real s, ct_real t, ct_real c[3],
                                   ct_real h[4], ct_real N[3], ct_real *size, int *degen)
{
    ct_real xs[3], xt[3], n[3], m[3], d1[3], d2[3];
    _Pragma("GCC unroll 4")
    for (int i = 0; i < 3; i++) {
        c[i] = b->x0[i] + s * b->a1[i] + t * b->a2[i] + s * t * b->a3[i];
        xs[i] = b->a1[i] + t * b->a3[i];
        xt[i] = b->a2[i] + s * b->a3[i];
        d1[i] = X3[i] - X1[i];
        d2[i] = X4[i] - X2[i];
    }
    h[0] = (ct_real)0.25 * (1 - s) * (1 - t);
    h[1] = (ct_real)0.25 * (1 + s) * (1 - t);
    h[2] = (ct_real)0.25 * (1 + s) * (1 + t);
    h[3] = (ct_real)0.25 * (1 - s) * (1 + t);
    n[0] = xs[1] * xt[2] - xs[2] * xt[1];
    n[1] = xs[2] * xt[0] - xs[0] * xt[2];
    n[2] = xs[0] * xt[1] - xs[1] * xt[0];
    m[0] = d1[1] * d2[2] - d1[2] * d2[1];
    m[1] = d1[2] * d2[0] - d1[0] * d2[2];
    m[2] = d1[0] * d2[1] - d1[1] * d2[0];
    ct_real nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    ct_real mm = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
    /* Corner triangles: corner i with its two neighbours. */
    ct_real lmax = 0, amin = CTI_HUGE;
    cti_nr_corner(X1, X2, X4, &amin, &lmax);
    cti_nr_corner(X2, X3, X1, &amin, &lmax);
    cti_nr_corner(X3, X4, X2, &amin, &lmax);
    cti_nr_corner(X4, X1, X3, &amin, &lmax);
    /* Corner triangle area |e x f|/2 <= tol * lmax. */
    ct_real lim = 2 * CTI_NR_AREA_TOL * lmax;
    *degen = !(amin > lim * lim);
    int usen = nn > (ct_real)1e-6 * mm;
    ct_real inv = 1 / CTI_SQRT(usen ? nn : (mm > 0 ? mm : 1));
    N[0] = (usen ? n[0] : m[0]) * inv;
    N[1] = (usen ? n[1] : m[1]) * inv;
    N[2] = (usen ? n[2] : m[2]) * inv;
    *size = CTI_SQRT(lmax);
}

#endif /* NARROW_INTERNAL_H */
