/*
 * search_bucket_grid.c -- the bucket search's first pass (bounding boxes,
 * index and finiteness checks, the segments' corner records) and the sizing
 * of its grid. The search itself is in search_bucket.c.
 */
#include <stdlib.h>

#include "ct_internal.h"

/* In search_bucket_grid.c: pass 1 (boxes, checks, segment records) and
 * the grid's sizing. */
int cti_bucket_boxes(const ct_search_input *in, ct_real *restrict srec, ct_real sb[6],
                     ct_real mb[6]);
void cti_bucket_size(const ct_real lo[3], const ct_real hi[3], ct_idx nseg, double factor,
                     int64_t maxc, ct_idx n[3], ct_real inv[3], ct_real *tol);

/* Pass 1: the boxes of the secondaries (sb) and of the segments' nodes
 * (mb), as lo[3] hi[3]; checks indices and finiteness, and copies the
 * segments' corners into srec (12 values per segment, contiguous). */
int cti_bucket_boxes(const ct_search_input *in, ct_real *restrict srec, ct_real sb[6],
                     ct_real mb[6])
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict sec = in->sec;
    const ct_idx nnode = in->nnode;
    ct_real s0 = CTI_HUGE, s1 = CTI_HUGE, s2 = CTI_HUGE;
    ct_real t0 = -CTI_HUGE, t1 = -CTI_HUGE, t2 = -CTI_HUGE;
    int bad = 0, range = 0;
#pragma omp parallel for schedule(static) reduction(min : s0, s1, s2) \
    reduction(max : t0, t1, t2) reduction(| : bad, range)
    for (ct_idx i = 0; i < in->nsec; i++) {
        ct_idx k = sec[i];
        if ((uint32_t)k >= (uint32_t)nnode) {
            range = 1;
            continue;
        }
        ct_real X = x[k], Y = y[k], Z = z[k];
        /* v - v is 0 for a finite v, NaN for NaN and infinities. */
        bad |= !(X - X == 0) | !(Y - Y == 0) | !(Z - Z == 0);
        s0 = CTI_MIN(s0, X);
        s1 = CTI_MIN(s1, Y);
        s2 = CTI_MIN(s2, Z);
        t0 = CTI_MAX(t0, X);
        t1 = CTI_MAX(t1, Y);
        t2 = CTI_MAX(t2, Z);
    }
    sb[0] = s0, sb[1] = s1, sb[2] = s2, sb[3] = t0, sb[4] = t1, sb[5] = t2;
    s0 = s1 = s2 = CTI_HUGE;
    t0 = t1 = t2 = -CTI_HUGE;
    const ct_idx *nn[4] = {in->n1, in->n2, in->n3, in->n4};
#pragma omp parallel for schedule(static) reduction(min : s0, s1, s2) \
    reduction(max : t0, t1, t2) reduction(| : bad, range)
    for (ct_idx j = 0; j < in->nseg; j++) {
        ct_real *restrict r = srec + (size_t)12 * j;
        for (int q = 0; q < 4; q++) {
            ct_idx k = nn[q][j];
            if ((uint32_t)k >= (uint32_t)nnode) {
                range = 1;
                r[3 * q] = r[3 * q + 1] = r[3 * q + 2] = 0;
                continue;
            }
            ct_real X = x[k], Y = y[k], Z = z[k];
            r[3 * q] = X;
            r[3 * q + 1] = Y;
            r[3 * q + 2] = Z;
            bad |= !(X - X == 0) | !(Y - Y == 0) | !(Z - Z == 0);
            s0 = CTI_MIN(s0, X);
            s1 = CTI_MIN(s1, Y);
            s2 = CTI_MIN(s2, Z);
            t0 = CTI_MAX(t0, X);
            t1 = CTI_MAX(t1, Y);
            t2 = CTI_MAX(t2, Z);
        }
    }
    mb[0] = s0, mb[1] = s1, mb[2] = s2, mb[3] = t0, mb[4] = t1, mb[5] = t2;
    if (range)
        return CT_ERR_RANGE;
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

/* Cells per axis from the Radioss sizing, capped at maxc in total. */
void cti_bucket_size(const ct_real lo[3], const ct_real hi[3], ct_idx nseg, double factor,
                     int64_t maxc, ct_idx n_out[3], ct_real inv[3], ct_real *tol)
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
    double mag = 0;
    for (int k = 0; k < 3; k++) {
        n_out[k] = (ct_idx)n[k];
        inv[k] = L[k] > 0 ? (ct_real)(n[k] / L[k]) : 0;
        mag = CTI_MAX(mag, CTI_MAX(fabs((double)lo[k]), fabs((double)hi[k])));
    }
    *tol = (ct_real)(8.0 * CTI_EPS * mag);
}
