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
            /* A x op and B x op: triangle k + 1's A is this B, and the
             * compiler forms each corner's product once for both. (Handed
             * on from one triangle to the next in a variable, or kept in a
             * second array, they stop gcc from vectorising the loop.) */
            const cti_v3 KA = v3_cross(A, op), KB = v3_cross(B, op);
            cti_nr_tri_k(A.x, A.y, A.z, B.x, B.y, B.z, op.x, op.y, op.z, KA.x, KA.y, KA.z, KB.x,
                         KB.y, KB.z, &q, &u, &v, &w, &nx, &ny, &nz, &nn, &l2, &in);
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
