/*
 * project_tri.c -- the node-triangle block kernel: closest point, clamped
 * barycentric coordinates (cti_nr_tri in narrow_internal.h), one
 * `#pragma omp simd` loop over a block's pairs. Like the other block
 * kernels it uses no OpenMP construct but simd, so the build may compile
 * it with another compiler than the rest (see NARROW_CC in the Makefile).
 */
#include "narrow_internal.h"

/* Node-triangle over a block whose segments are all triangles: as
 * CTI_NR_LOAD, but only the three corners are read (n4 == n3). */
void cti_nr_block_tri(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b)
{
    CTI_NR_OUTPTRS(a, k0);
    int two = a->two_sided;
    const ct_real *restrict P = b->pxy, *restrict A1 = b->xy1;
    const ct_real *restrict A2 = b->xy2, *restrict A3 = b->xy3;
    const ct_real *restrict Z01 = b->z01, *restrict Z23 = b->z23;
    const ct_real *restrict G = b->g;
    CTI_NR_SIMD
    for (ct_idx j = 0; j < n; j++) {
        const ct_real ox = A1[2 * j], oy = A1[2 * j + 1], oz = Z01[2 * j + 1];
        const ct_real px = P[2 * j] - ox, py = P[2 * j + 1] - oy, pz = Z01[2 * j] - oz;
        const ct_real x2 = A2[2 * j] - ox, y2 = A2[2 * j + 1] - oy, z2 = Z23[2 * j] - oz;
        const ct_real x3 = A3[2 * j] - ox, y3 = A3[2 * j + 1] - oy, z3 = Z23[2 * j + 1] - oz;
        const ct_real g = G[j];
        const ct_real zsum_ = (((px + py) + (pz + x2)) + ((y2 + z2) + (x3 + y3))) + (z3 + g);
        const cti_nr_int nonfin = !(zsum_ - zsum_ == 0);
        ct_real q, u, v, w, nx, ny, nz, nn, l2;
        cti_nr_int in;
        cti_nr_tri(x2, y2, z2, x3, y3, z3, px, py, pz, &q, &u, &v, &w, &nx, &ny, &nz, &nn, &l2,
                   &in);
        (void)q;
        /* Area |n|/2 <= tol * l2. */
        ct_real lim = 2 * CTI_NR_AREA_TOL * l2;
        cti_nr_int degen = !(nn > lim * lim);
        cti_nr_int bad = nonfin ? CTI_NR_F(NONFINITE) : (degen ? CTI_NR_F(DEGENERATE) : 0);
        ct_real cx = v * x2 + w * x3;
        ct_real cy = v * y2 + w * y3;
        ct_real cz = v * z2 + w * z3;
        ct_real dist, pen, mx, my, mz;
        cti_nr_int flag;
        cti_nr_finish(px, py, pz, cx, cy, cz, nx, ny, nz, nn, l2, in, g, two, &dist, &pen,
                      &mx, &my, &mz, &flag);
        CTI_NR_STORE(j, bad, dist, pen, mx, my, mz, cx, cy, cz, u, v, w, 0, g, flag);
    }
    cti_nr_flags_out(b->flag, a->out->flag + k0, n);
}
