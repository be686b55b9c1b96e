/*
 * project_quad.c -- node-quadrangle projection by two of the three methods
 * of DESIGN.md section 6 (see ct_quad_method in ct_narrow.h for the
 * formulas): four triangles around the centroid, and the closed form from
 * distance ratios. Newton on the bilinear (s, t) is in project_newton.c;
 * the helpers they share in narrow_quad.h.
 *
 * Every block kernel is one `#pragma omp simd` loop over the block's pairs
 * written with scalars and selects (narrow_internal.h).
 */
#include "narrow_quad.h"

/* ---- Four triangles around the centroid -------------------------------- */

/* Four triangles (O, X_k, X_k+1) around the centroid O; the closest point of
 * their union (ties keep the first). Weights: H_i = u/4 + v [i == k] +
 * w [i == k+1].
 *
 * The block runs as separate SIMD loops: one forms the centroid and the
 * corners relative to it, one per triangle folds that triangle's closest
 * point into the best so far (kept in the block's arrays, in L1), and one
 * finishes. Written as one loop over the four triangles, a pair's live
 * values (the four corners, the best point, normal and weights, and one
 * triangle's own) did not fit the 16 vector registers of AVX2 and spilled;
 * split, each loop holds one triangle's values: 0.63-0.76 of the single
 * loop's time on plates, 0.86-0.90 on the folded sheet (10^4 and 6 10^5
 * pairs, 1 thread, alternating in one process). The arithmetic of every
 * pair is that of the single loop, operation for operation: the same
 * results, bit for bit. (Two sets of best arrays, read from one and written
 * to the other, avoid gcc's masked stores of `cond ? new : old` but made
 * masked loads instead, and the working set outgrew L1: slower.) */
typedef struct cti_4tri_scr {
    _Alignas(64) ct_real O[3][CTI_NR_BLOCK];    /* centroid, relative to X1 */
    _Alignas(64) ct_real op[3][CTI_NR_BLOCK];   /* node - O */
    _Alignas(64) ct_real o[4][3][CTI_NR_BLOCK]; /* X_k - O */
    /* The best so far: squared distance, normal and its squared length,
     * contact point (relative to O), weights; over all four triangles, the
     * smallest squared normal, the longest squared edge, the footprint. */
    _Alignas(64) ct_real q[CTI_NR_BLOCK], nn[CTI_NR_BLOCK], nnmin[CTI_NR_BLOCK];
    _Alignas(64) ct_real lmax[CTI_NR_BLOCK];
    _Alignas(64) ct_real n[3][CTI_NR_BLOCK], c[3][CTI_NR_BLOCK], h[4][CTI_NR_BLOCK];
    _Alignas(64) cti_nr_int inside[CTI_NR_BLOCK];
} cti_4tri_scr;

/* Triangle k of every pair of the block folded into the best (k == 0
 * starts it). */
static inline __attribute__((always_inline)) void cti_4tri_fold(cti_4tri_scr *restrict S,
                                                                 const int k, ct_idx n)
{
    const int k1 = (k + 1) & 3;
    const ct_real *restrict ax = S->o[k][0], *restrict ay = S->o[k][1], *restrict az = S->o[k][2];
    const ct_real *restrict bx = S->o[k1][0], *restrict by = S->o[k1][1],
                            *restrict bz = S->o[k1][2];
    const ct_real *restrict qx = S->op[0], *restrict qy = S->op[1], *restrict qz = S->op[2];
    ct_real *restrict Bq = S->q, *restrict Bnn = S->nn, *restrict Nmin = S->nnmin;
    ct_real *restrict Lmax = S->lmax;
    ct_real *restrict Nx = S->n[0], *restrict Ny = S->n[1], *restrict Nz = S->n[2];
    ct_real *restrict Cx = S->c[0], *restrict Cy = S->c[1], *restrict Cz = S->c[2];
    ct_real *restrict H0 = S->h[0], *restrict H1 = S->h[1], *restrict H2 = S->h[2],
                      *restrict H3 = S->h[3];
    cti_nr_int *restrict In = S->inside;
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        const ct_real Ax = ax[j], Ay = ay[j], Az = az[j], Bx = bx[j], By = by[j], Bz = bz[j];
        ct_real q, u, v, w, nx, ny, nz, nn, l2;
        cti_nr_int in;
        cti_nr_tri(Ax, Ay, Az, Bx, By, Bz, qx[j], qy[j], qz[j], &q, &u, &v, &w, &nx, &ny, &nz,
                   &nn, &l2, &in);
        /* The best so far, read whole (k == 0: nothing to read). */
        const ct_real oq = k == 0 ? 0 : Bq[j], onx = k == 0 ? 0 : Nx[j],
                      ony = k == 0 ? 0 : Ny[j], onz = k == 0 ? 0 : Nz[j],
                      onn = k == 0 ? 0 : Bnn[j], ocx = k == 0 ? 0 : Cx[j],
                      ocy = k == 0 ? 0 : Cy[j], ocz = k == 0 ? 0 : Cz[j],
                      oh0 = k == 0 ? 0 : H0[j], oh1 = k == 0 ? 0 : H1[j],
                      oh2 = k == 0 ? 0 : H2[j], oh3 = k == 0 ? 0 : H3[j];
        const ct_real nmin = k == 0 ? CTI_HUGE : Nmin[j], lm = k == 0 ? 0 : Lmax[j];
        const cti_nr_int oin = k == 0 ? 0 : In[j];
        const cti_nr_int take = k == 0 ? 1 : q < oq;
        Bq[j] = take ? q : oq;
        Nx[j] = take ? nx : onx;
        Ny[j] = take ? ny : ony;
        Nz[j] = take ? nz : onz;
        Bnn[j] = take ? nn : onn;
        Cx[j] = take ? v * Ax + w * Bx : ocx;
        Cy[j] = take ? v * Ay + w * By : ocy;
        Cz[j] = take ? v * Az + w * Bz : ocz;
        /* Corner weights of this candidate. */
        const ct_real hu = (ct_real)0.25 * u;
        const ct_real h0 = hu + (0 == k ? v : 0) + (0 == k1 ? w : 0);
        const ct_real h1 = hu + (1 == k ? v : 0) + (1 == k1 ? w : 0);
        const ct_real h2 = hu + (2 == k ? v : 0) + (2 == k1 ? w : 0);
        const ct_real h3 = hu + (3 == k ? v : 0) + (3 == k1 ? w : 0);
        H0[j] = take ? h0 : oh0;
        H1[j] = take ? h1 : oh1;
        H2[j] = take ? h2 : oh2;
        H3[j] = take ? h3 : oh3;
        Nmin[j] = nn < nmin ? nn : nmin;
        Lmax[j] = l2 > lm ? l2 : lm;
        In[j] = oin | in;
    }
}

void cti_nr_block_4tri(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b)
{
    CTI_NR_OUTPTRS(a, k0);
    CTI_NR_INPTRS(a, k0);
    int two = a->two_sided;
    cti_4tri_scr S;
    {
        ct_real *restrict Ox = S.O[0], *restrict Oy = S.O[1], *restrict Oz = S.O[2];
        ct_real *restrict qx = S.op[0], *restrict qy = S.op[1], *restrict qz = S.op[2];
        ct_real(*restrict o)[3][CTI_NR_BLOCK] = S.o;
        CTI_NR_SIMD
        for (ct_idx j = 0; j < n; j++) {
            CTI_NR_LOAD(j);
            (void)nonfin;
            /* X1 is the origin. */
            const ct_real Px = (ct_real)0.25 * (x2 + (x3 + x4));
            const ct_real Py = (ct_real)0.25 * (y2 + (y3 + y4));
            const ct_real Pz = (ct_real)0.25 * (z2 + (z3 + z4));
            Ox[j] = Px, Oy[j] = Py, Oz[j] = Pz;
            o[0][0][j] = -Px, o[0][1][j] = -Py, o[0][2][j] = -Pz;
            o[1][0][j] = x2 - Px, o[1][1][j] = y2 - Py, o[1][2][j] = z2 - Pz;
            o[2][0][j] = x3 - Px, o[2][1][j] = y3 - Py, o[2][2][j] = z3 - Pz;
            o[3][0][j] = x4 - Px, o[3][1][j] = y4 - Py, o[3][2][j] = z4 - Pz;
            qx[j] = px - Px, qy[j] = py - Py, qz[j] = pz - Pz;
        }
    }
    cti_4tri_fold(&S, 0, n);
    cti_4tri_fold(&S, 1, n);
    cti_4tri_fold(&S, 2, n);
    cti_4tri_fold(&S, 3, n);
    const ct_real *restrict Ox = S.O[0], *restrict Oy = S.O[1], *restrict Oz = S.O[2];
    const ct_real *restrict Nx = S.n[0], *restrict Ny = S.n[1], *restrict Nz = S.n[2];
    const ct_real *restrict Cx = S.c[0], *restrict Cy = S.c[1], *restrict Cz = S.c[2];
    const ct_real *restrict H0 = S.h[0], *restrict H1 = S.h[1], *restrict H2 = S.h[2],
                            *restrict H3 = S.h[3];
    const ct_real *restrict Bnn = S.nn, *restrict Nmin = S.nnmin, *restrict Lmax = S.lmax;
    const cti_nr_int *restrict In = S.inside;
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        CTI_NR_LOAD(j);
        const ct_real lmax = Lmax[j];
        ct_real lim = 2 * CTI_NR_AREA_TOL * lmax;
        cti_nr_int degen = !(Nmin[j] > lim * lim);
        cti_nr_int bad = nonfin ? CTI_NR_F(NONFINITE) : (degen ? CTI_NR_F(DEGENERATE) : 0);
        ct_real cx = Ox[j] + Cx[j], cy = Oy[j] + Cy[j], cz = Oz[j] + Cz[j];
        ct_real dist, pen, mx, my, mz;
        cti_nr_int flag;
        cti_nr_finish(px, py, pz, cx, cy, cz, Nx[j], Ny[j], Nz[j], Bnn[j], lmax, In[j], g, two,
                      &dist, &pen, &mx, &my, &mz, &flag);
        CTI_NR_STORE(j, bad, dist, pen, mx, my, mz, cx, cy, cz, H0[j], H1[j], H2[j], H3[j], g,
                     flag);
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
        CTI_QUAD_STORE(j, s, t, 1, 0);
    }
    cti_nr_flags_out(b->flag, a->out->flag + k0, n);
}
