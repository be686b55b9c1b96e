/*
 * search_bucket_grid.c -- the bucket search's first pass (bounding boxes,
 * index and finiteness checks, the segments' boxes) and the sizing of its
 * grid. The search itself is in search_bucket.c.
 */
#include <stdlib.h>

#include "search_bucket_grid.h"

/* v rounded to a float not above it (round_down) or not below it, with
 * selects, so that pass 1's loop vectorises. */
static inline float bk_float_out(ct_real v, int round_down)
{
    float f = (float)v;
#ifndef CT_SINGLE
    if (round_down)
        f = (ct_real)f > v ? cti_next_down_f(f) : f;
    else
        f = (ct_real)f < v ? cti_next_up_f(f) : f;
#else
    (void)round_down;
#endif
    return f;
}

/* What pass 1 reads and writes, for the body its loops share. */
typedef struct bk_boxes_out {
    const ct_real *x, *y, *z, *xyzw;
    const ct_idx *n1, *n2, *n3, *n4;
    ct_real *box, *srec;
    float *fbox;
    uint32_t nnode;
    ct_real d;
} bk_boxes_out;

/* A segment's box for the reduction and its flags (bk_box_one). */
typedef struct bk_box_res {
    ct_real lx, ly, lz, hx, hy, hz;
    int flags;
} bk_box_res;

/* Segment j: writes its records and returns its box for the reduction
 * (empty when an index is out of range: its corners are then read at node
 * 0, which exists, and ignored) with flags 1 (an index out of range) and 2
 * (a corner not finite). No branch, so that the ordered loops vectorise;
 * `scattered` (corners from xyzw, corner records) and `with_box` are
 * constants at each call: a box store under a test of the pointer made gcc
 * keep a scalar copy of the loop, which is the one that ran. */
static inline __attribute__((always_inline)) bk_box_res
bk_box_one(const bk_boxes_out ov, ct_idx j, const int scattered, const int with_box)
{
    const bk_boxes_out *o = &ov;
    ct_idx a = o->n1[j], b = o->n2[j], c = o->n3[j], e = o->n4[j];
    const uint32_t nn = o->nnode;
    const int out = ((uint32_t)a >= nn) | ((uint32_t)b >= nn) | ((uint32_t)c >= nn) |
                    ((uint32_t)e >= nn);
    const ct_idx keep = -(ct_idx)!out; /* all ones, or 0: node 0 */
    a &= keep, b &= keep, c &= keep, e &= keep;
    ct_real xa, xb, xc, xe, ya, yb, yc, ye, za, zb, zc, ze;
    if (scattered && o->xyzw) {
        const ct_real *pa = o->xyzw + 4 * (size_t)a, *pb = o->xyzw + 4 * (size_t)b;
        const ct_real *pc = o->xyzw + 4 * (size_t)c, *pe = o->xyzw + 4 * (size_t)e;
        xa = pa[0], ya = pa[1], za = pa[2], xb = pb[0], yb = pb[1], zb = pb[2];
        xc = pc[0], yc = pc[1], zc = pc[2], xe = pe[0], ye = pe[1], ze = pe[2];
    } else {
        const ct_real *restrict x = o->x, *restrict y = o->y, *restrict z = o->z;
        xa = x[a], xb = x[b], xc = x[c], xe = x[e];
        ya = y[a], yb = y[b], yc = y[c], ye = y[e];
        za = z[a], zb = z[b], zc = z[c], ze = z[e];
    }
    /* Each v - v is 0, or NaN for NaN and infinities (min and max may
     * drop a NaN, so the check is on the corners). */
    ct_real fin = ((xa - xa) + (xb - xb) + (xc - xc) + (xe - xe)) +
                  ((ya - ya) + (yb - yb) + (yc - yc) + (ye - ye)) +
                  ((za - za) + (zb - zb) + (zc - zc) + (ze - ze));
    /* The predicate's own expressions: the same minima and maxima. */
    ct_real lx = CTI_MIN(CTI_MIN(xa, xb), CTI_MIN(xc, xe));
    ct_real hx = CTI_MAX(CTI_MAX(xa, xb), CTI_MAX(xc, xe));
    ct_real ly = CTI_MIN(CTI_MIN(ya, yb), CTI_MIN(yc, ye));
    ct_real hy = CTI_MAX(CTI_MAX(ya, yb), CTI_MAX(yc, ye));
    ct_real lz = CTI_MIN(CTI_MIN(za, zb), CTI_MIN(zc, ze));
    ct_real hz = CTI_MAX(CTI_MAX(za, zb), CTI_MAX(zc, ze));
    if (scattered && o->srec) {
        ct_real *restrict q = o->srec + (size_t)12 * j;
        q[0] = xa, q[1] = ya, q[2] = za, q[3] = xb, q[4] = yb, q[5] = zb;
        q[6] = xc, q[7] = yc, q[8] = zc, q[9] = xe, q[10] = ye, q[11] = ze;
    }
    if (with_box) {
        ct_real *restrict r = o->box + (size_t)6 * j;
        r[0] = lx, r[1] = ly, r[2] = lz, r[3] = hx, r[4] = hy, r[5] = hz;
    }
    float *restrict f = o->fbox + (size_t)8 * j;
    const ct_real d = o->d;
    f[0] = bk_float_out(lx - d, 1);
    f[1] = bk_float_out(ly - d, 1);
    f[2] = bk_float_out(lz - d, 1);
    f[3] = 0;
    f[4] = -bk_float_out(hx + d, 0);
    f[5] = -bk_float_out(hy + d, 0);
    f[6] = -bk_float_out(hz + d, 0);
    f[7] = 0;
    const bk_box_res r = {out ? CTI_HUGE : lx,  out ? CTI_HUGE : ly,  out ? CTI_HUGE : lz,
                          out ? -CTI_HUGE : hx, out ? -CTI_HUGE : hy, out ? -CTI_HUGE : hz,
                          out | ((!(fin == 0) & !out) << 1)};
    return r;
}

/*
 * Pass 1, over the segments: checks indices and finiteness, reduces the box
 * of the segments' corners into mb (lo[3] hi[3]), and writes per segment
 *  - fbox[8 j ..]: the box inflated by d = gap + margin as the predicate
 *    computes it, fl(lo - d) and fl(hi + d), rounded outward to float and
 *    stored as lo x y z 0, -hi x y z 0 (one 32-byte vector);
 *  - box[6 j ..] (when box is not NULL): the exact box, lo x y z hi x y z,
 *    the very minima and maxima the predicate computes;
 *  - srec[12 j ..] (when srec is not NULL): the four corners' coordinates.
 * When xyzw is not NULL (scattered numberings), the node coordinates are
 * first packed into it, x y z 0 per node, in one streaming pass: a corner
 * is then one cache line, not three random ones (the x, y and z arrays).
 * An ordered numbering runs a vector loop (one for each filter: see
 * bk_box_one); a scattered one a loop that prefetches the corners a few
 * segments ahead, with the same body.
 */
int cti_bucket_boxes(const ct_search_input *in, ct_real *restrict xyzw, ct_real *restrict box,
                     float *restrict fbox, ct_real *restrict srec, ct_real mb[6])
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    if (xyzw) {
#pragma omp parallel for simd schedule(static)
        for (ct_idx i = 0; i < in->nnode; i++) {
            xyzw[4 * (size_t)i] = x[i];
            xyzw[4 * (size_t)i + 1] = y[i];
            xyzw[4 * (size_t)i + 2] = z[i];
            xyzw[4 * (size_t)i + 3] = 0;
        }
    }
    const ct_idx nseg = in->nseg;
    if (nseg > 0 && in->nnode <= 0)
        return CT_ERR_RANGE; /* every index is out of range */
    const ct_idx *restrict n1 = in->n1, *restrict n2 = in->n2, *restrict n3 = in->n3,
                 *restrict n4 = in->n4;
    const uint32_t nnode = (uint32_t)in->nnode;
    const ct_real d = in->gap + in->margin;
    ct_real u0 = CTI_HUGE, u1 = CTI_HUGE, u2 = CTI_HUGE;
    ct_real v0 = -CTI_HUGE, v1 = -CTI_HUGE, v2 = -CTI_HUGE;
    int bad = 0, range = 0;
#define BK_BOX_REDUCE(j, SCATTERED, WITH_BOX)                                           \
    do {                                                                                \
        const bk_boxes_out o = {x,   y,    z,    xyzw,  n1, n2, n3, n4,                  \
                                box, srec, fbox, nnode, d};                             \
        const bk_box_res r = bk_box_one(o, (j), (SCATTERED), (WITH_BOX));               \
        range |= r.flags & 1, bad |= r.flags >> 1;                                      \
        u0 = CTI_MIN(u0, r.lx), u1 = CTI_MIN(u1, r.ly), u2 = CTI_MIN(u2, r.lz);         \
        v0 = CTI_MAX(v0, r.hx), v1 = CTI_MAX(v1, r.hy), v2 = CTI_MAX(v2, r.hz);         \
    } while (0)
    const int pf = cti_bucket_scattered(in);
    if (!pf && !xyzw && !srec && !box) {
        BK_PAR_FOR_SIMD((schedule(static) reduction(min : u0, u1, u2)
                             reduction(max : v0, v1, v2) reduction(| : bad, range)))
        for (ct_idx j = 0; j < nseg; j++)
            BK_BOX_REDUCE(j, 0, 0);
    } else if (!pf && !xyzw && !srec) {
        BK_PAR_FOR_SIMD((schedule(static) reduction(min : u0, u1, u2)
                             reduction(max : v0, v1, v2) reduction(| : bad, range)))
        for (ct_idx j = 0; j < nseg; j++)
            BK_BOX_REDUCE(j, 0, 1);
    } else {
        enum { AHEAD = 8 };
#pragma omp parallel for schedule(static) reduction(min : u0, u1, u2) \
    reduction(max : v0, v1, v2) reduction(| : bad, range)
        for (ct_idx j = 0; j < nseg; j++) {
#if defined(__GNUC__)
            if (j + AHEAD < nseg) {
                const ct_idx q[4] = {n1[j + AHEAD], n2[j + AHEAD], n3[j + AHEAD],
                                     n4[j + AHEAD]};
                for (int k = 0; k < 4; k++)
                    if ((uint32_t)q[k] < nnode) {
                        if (xyzw) {
                            __builtin_prefetch(xyzw + 4 * (size_t)q[k]);
                        } else {
                            __builtin_prefetch(x + q[k]);
                            __builtin_prefetch(y + q[k]);
                            __builtin_prefetch(z + q[k]);
                        }
                    }
            }
#endif
            BK_BOX_REDUCE(j, 1, box != NULL);
        }
    }
#undef BK_BOX_REDUCE
    mb[0] = u0, mb[1] = u1, mb[2] = u2, mb[3] = v0, mb[4] = v1, mb[5] = v2;
    if (range)
        return CT_ERR_RANGE;
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

/* Whether the segments' numbering is scattered: consecutive segments'
 * first nodes far apart in memory in most of 256 samples (drawn at random
 * positions, cti_sample_index). Corner gathers
 * are then random accesses (prefetched, or replaced by corner records);
 * only speed depends on this. */
int cti_bucket_scattered(const ct_search_input *in)
{
    const ct_idx nseg = in->nseg;
    int far = 0;
    for (int q = 0; nseg > 4096 && q < 256; q++) {
        const ct_idx j = cti_sample_index((uint64_t)q, 1, nseg - 1);
        far += abs(in->n1[j + 1] - in->n1[j]) > 4096;
    }
    return far > 128;
}

int cti_search_pieces(const ct_search_input *in)
{
    const ct_idx nseg = in->nseg;
    if (nseg <= 4096)
        return 0;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    ct_real d2[256], lo[3], hi[3];
    for (int q = 0; q < 256; q++) {
        const ct_idx j = cti_sample_index((uint64_t)q, 0, nseg - 1);
        const ct_idx a = in->n1[j], b = in->n1[j + 1];
        const ct_real p[3] = {x[a], y[a], z[a]};
        const ct_real dx = x[b] - p[0], dy = y[b] - p[1], dz = z[b] - p[2];
        d2[q] = dx * dx + dy * dy + dz * dz;
        for (int k = 0; k < 3; k++) {
            lo[k] = q ? CTI_MIN(lo[k], p[k]) : p[k];
            hi[k] = q ? CTI_MAX(hi[k], p[k]) : p[k];
        }
    }
    const ct_real ex = hi[0] - lo[0], ey = hi[1] - lo[1], ez = hi[2] - lo[2];
    const ct_real far2 = (ex * ex + ey * ey + ez * ez) / 64;
    int jumps = 0;
    for (int q = 0; q < 256; q++)
        jumps += d2[q] > far2;
    return jumps > 16;
}

/* The secondaries' index and finiteness checks alone (the query does them
 * otherwise), for the calls that skip the query. */
int cti_bucket_check_sec(const ct_search_input *in)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict sec = in->sec;
    const uint32_t nnode = (uint32_t)in->nnode;
    int bad = 0, range = 0;
#pragma omp parallel for schedule(static) reduction(| : bad, range)
    for (ct_idx i = 0; i < in->nsec; i++) {
        ct_idx k = sec[i];
        if ((uint32_t)k >= nnode) {
            range = 1;
            continue;
        }
        ct_real fin = (x[k] - x[k]) + (y[k] - y[k]) + (z[k] - z[k]);
        bad |= !(fin == 0);
    }
    if (range)
        return CT_ERR_RANGE;
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

/* Cells per axis from the Radioss sizing, capped at maxc in total. */
void cti_bucket_size(const ct_real lo[3], const ct_real hi[3], ct_idx nseg, double factor,
                     int64_t maxc, ct_idx n_out[3], ct_real inv[3])
{
    double L[3], n[3];
    for (int k = 0; k < 3; k++)
        L[k] = (double)hi[k] - (double)lo[k];
    double area = L[0] * L[1] + L[1] * L[2] + L[2] * L[0];
    double lmax = CTI_MAX(L[0], CTI_MAX(L[1], L[2]));
    double a;
    if (area > 0)
        a = factor * 0.75 * sqrt((double)nseg / area);
    else if (lmax > 0) /* all on a line: about one cell per segment */
        a = factor * 0.75 * (double)nseg / lmax;
    else
        a = 0;
    double prod = 1;
    for (int k = 0; k < 3; k++) {
        double c = floor(L[k] * a);
        n[k] = (c >= 1 && c == c) ? CTI_MIN(c, (double)maxc) : 1;
        prod *= n[k];
    }
    if (prod > (double)maxc) {
        int act = (n[0] > 1) + (n[1] > 1) + (n[2] > 1);
        double sc = pow((double)maxc / prod, 1.0 / act);
        prod = 1;
        for (int k = 0; k < 3; k++) {
            n[k] = CTI_MAX(1.0, floor(n[k] * sc));
            prod *= n[k];
        }
        while (prod > (double)maxc) { /* rounding left it a little high */
            int kk = (n[0] >= n[1] && n[0] >= n[2]) ? 0 : (n[1] >= n[2] ? 1 : 2);
            prod = prod / n[kk] * (n[kk] - 1);
            n[kk] -= 1;
        }
    }
    for (int k = 0; k < 3; k++) {
        n_out[k] = (ct_idx)n[k];
        inv[k] = L[k] > 0 ? (ct_real)(n[k] / L[k]) : 0;
    }
}

/*
 * Offsets of a counting sort with counters per block: cnt[b * stride + c]
 * holds block b's count for cell c; afterwards it holds the first slot of
 * block b in cell c (cell-major, then block), and start[c] (when not NULL)
 * the first slot of cell c, start[ncell] the total. A two-pass scan over 64
 * groups of cells: parallel, and independent of the thread count.
 */
int64_t cti_bucket_offsets(ct_idx *cnt, int nb, size_t stride, int64_t ncell, ct_idx *start)
{
    enum { NSB = 64 };
    int64_t bsum[NSB];
    const int64_t bl = (ncell + NSB - 1) / NSB;
#pragma omp parallel for schedule(static)
    for (int q = 0; q < NSB; q++) {
        int64_t c0 = q * bl, c1 = CTI_MIN(ncell, c0 + bl), s = 0;
        for (int b = 0; b < nb; b++) {
            const ct_idx *restrict cb = cnt + (size_t)b * stride;
            for (int64_t c = c0; c < c1; c++)
                s += cb[c];
        }
        bsum[q] = s;
    }
    int64_t run = 0;
    for (int q = 0; q < NSB; q++) {
        int64_t v = bsum[q];
        bsum[q] = run;
        run += v;
    }
#pragma omp parallel for schedule(static)
    for (int q = 0; q < NSB; q++) {
        int64_t c0 = q * bl, c1 = CTI_MIN(ncell, c0 + bl);
        ct_idx s = (ct_idx)bsum[q];
        for (int64_t c = c0; c < c1; c++) {
            if (start)
                start[c] = s;
            for (int b = 0; b < nb; b++) {
                ct_idx *restrict cb = cnt + (size_t)b * stride;
                ct_idx v = cb[c];
                cb[c] = s;
                s += v;
            }
        }
    }
    if (start)
        start[ncell] = (ct_idx)run;
    return run;
}

/* Cell of coordinate v along one axis: monotone in v (the search's own
 * function, repeated here for the node binning). */
static inline ct_idx bk_cell1(ct_real v, ct_real o, ct_real inv, ct_idx nmax)
{
    ct_real t = (v - o) * inv;
    t = t > 0 ? t : 0;
    return t < (ct_real)nmax ? (ct_idx)t : nmax;
}

/* The cell of a node inside [lo, hi], or -1 outside. */
static inline ct_idx bk_node_cell(ct_real X, ct_real Y, ct_real Z, const ct_real lo[3],
                                  const ct_real hi[3], const ct_real inv[3], const ct_idx n[3])
{
    if (X < lo[0] || X > hi[0] || Y < lo[1] || Y > hi[1] || Z < lo[2] || Z > hi[2])
        return -1;
    ct_idx ix = bk_cell1(X, lo[0], inv[0], n[0] - 1);
    ct_idx iy = bk_cell1(Y, lo[1], inv[1], n[1] - 1);
    ct_idx iz = bk_cell1(Z, lo[2], inv[2], n[2] - 1);
    return (iz * n[1] + iy) * n[0] + ix;
}

/*
 * Whether the secondary order is spatially local: 1 when at least half of
 * 1024 sampled consecutive pairs (sec[i], sec[i + 1]) lie in the same or
 * neighbouring cells. Reads 2048 nodes; only a choice of visiting order
 * depends on it, never the result.
 */
int cti_bucket_local(const ct_search_input *in, const ct_real lo[3], const ct_real hi[3],
                     const ct_real inv[3], const ct_idx n[3])
{
    const ct_idx nsec = in->nsec;
    if (nsec < 4096)
        return 1;
    const uint32_t nnode = (uint32_t)in->nnode;
    int near = 0, tot = 0;
    for (int s = 0; s < 1024; s++) {
        ct_idx i = (ct_idx)((int64_t)(nsec - 1) * s / 1024);
        ct_idx a = in->sec[i], b = in->sec[i + 1];
        if ((uint32_t)a >= nnode || (uint32_t)b >= nnode)
            continue;
        ct_idx ca = bk_node_cell(in->x[a], in->y[a], in->z[a], lo, hi, inv, n);
        ct_idx cb = bk_node_cell(in->x[b], in->y[b], in->z[b], lo, hi, inv, n);
        if (ca < 0 || cb < 0)
            continue;
        tot++;
        ct_idx ax = ca % n[0], bx = cb % n[0], ay = (ca / n[0]) % n[1], by = (cb / n[0]) % n[1];
        ct_idx az = ca / n[0] / n[1], bz = cb / n[0] / n[1];
        near += abs(ax - bx) <= 1 && abs(ay - by) <= 1 && abs(az - bz) <= 1;
    }
    return 2 * near >= tot;
}

/*
 * The secondaries in cell order (a stable counting sort by cell, blocks of
 * consecutive positions): ncl[i] receives the cell of position i (-1
 * outside [lo, hi]); ord[0 .. *nbinned - 1] the positions in cell order
 * and ordc[] their cells. Checks indices and coordinates (CT_ERR_RANGE,
 * CT_ERR_NONFINITE). cnt: nb * stride counters.
 */
int cti_bucket_bin_nodes(const ct_search_input *in, const ct_real lo[3], const ct_real hi[3],
                         const ct_real inv[3], const ct_idx n[3], int nb, ct_idx *cnt,
                         size_t stride, ct_idx *ncl, ct_idx *ord, ct_idx *ordc,
                         ct_idx *nbinned)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict sec = in->sec;
    const ct_idx nsec = in->nsec;
    const uint32_t nnode = (uint32_t)in->nnode;
    const int64_t ncell = (int64_t)n[0] * n[1] * n[2];
    int bad = 0, range = 0;
#pragma omp parallel for schedule(static) reduction(| : bad, range)
    for (int b = 0; b < nb; b++) {
        ct_idx *restrict cb = cnt + (size_t)b * stride;
        memset(cb, 0, (size_t)ncell * sizeof *cb);
        ct_idx i0 = (ct_idx)((int64_t)nsec * b / nb), i1 = (ct_idx)((int64_t)nsec * (b + 1) / nb);
        for (ct_idx i = i0; i < i1; i++) {
            ct_idx k = sec[i];
            if ((uint32_t)k >= nnode) {
                range = 1;
                ncl[i] = -1;
                continue;
            }
            ct_real X = x[k], Y = y[k], Z = z[k];
            bad |= !((X - X) + (Y - Y) + (Z - Z) == 0);
            ct_idx c = bk_node_cell(X, Y, Z, lo, hi, inv, n);
            ncl[i] = c;
            if (c >= 0)
                cb[c]++;
        }
    }
    if (range)
        return CT_ERR_RANGE;
    if (bad)
        return CT_ERR_NONFINITE;
    *nbinned = (ct_idx)cti_bucket_offsets(cnt, nb, stride, ncell, NULL);
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx *restrict cb = cnt + (size_t)b * stride;
        ct_idx i0 = (ct_idx)((int64_t)nsec * b / nb), i1 = (ct_idx)((int64_t)nsec * (b + 1) / nb);
        for (ct_idx i = i0; i < i1; i++) {
            ct_idx c = ncl[i];
            if (c < 0)
                continue;
            ct_idx o = cb[c]++;
            ord[o] = i;
            ordc[o] = c;
        }
    }
    return CT_OK;
}
