/*
 * contact_cycle_skip.c -- the skip of the contact cycle's narrow phase (see
 * contact_cycle.h for why it is exact): the motion bound (the re-sort
 * criterion's, from one cycle to the next) summed cycle after cycle, each
 * pair's expiry (the value of that sum up to which its last distance
 * proves it out of contact), carried across a re-sort, and the selection
 * of the pairs whose expiry has passed.
 *
 * The expiry of a pair evaluated when the sum was M, at distance D with gap
 * g, is M + (D - g - slack) / (1 + 1e-6); the pair is skipped while the sum
 * is below it. A pair whose segment was skipped by the kernel (degenerate,
 * or a NaN/Inf coordinate) gets -1: it is evaluated every cycle, as is every
 * pair when the sum or the expiry is NaN (the comparison is false).
 */
#include "contact_cycle_internal.h"

#include <float.h>

#ifdef CT_SINGLE
#define CY_EPS FLT_EPSILON
#else
#define CY_EPS DBL_EPSILON
#endif

/* Keep the positions of the listed nodes, and return their largest
 * coordinate magnitude (NaN: infinite), in one pass. */
static double list_keep(ct_idx n, const ct_idx *restrict list, const ct_real *restrict x,
                        const ct_real *restrict y, const ct_real *restrict z,
                        ct_real *restrict xp, ct_real *restrict yp, ct_real *restrict zp)
{
    double L = 0;
#pragma omp parallel for schedule(static) reduction(max : L)
    for (ct_idx i = 0; i < n; i++) {
        const ct_idx k = list[i];
        xp[k] = x[k];
        yp[k] = y[k];
        zp[k] = z[k];
        /* Selects, not fmax: a libm call per coordinate (gcc does not
         * inline fmax, whose NaN rule differs from a select's), and fmax
         * would drop a NaN coordinate where the bound must be infinite. */
        const double ax = fabs((double)x[k]), ay = fabs((double)y[k]), az = fabs((double)z[k]);
        double a = ax > ay ? ax : ay;
        a = az > a ? az : a;
        a = ((ax != ax) | (ay != ay) | (az != az)) ? INFINITY : a;
        L = a > L ? a : L;
    }
    return L;
}

void cti_skip_motion(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z)
{
    /* The first cycle has no previous positions: its pairs are all new
     * (expiry -1), so the sum does not matter; it stays 0. Otherwise the
     * step's bound is the re-sort criterion's, from the last cycle's
     * positions: the smaller of the two largest steps' sum and the
     * relative bound per axis (0 for a rigid motion). */
    if (cy->have_prev) {
        ct_real b = 0;
        ct_resort_needed(cy->nsec, cy->sec, cy->nmain, cy->mainn, cy->xp, cy->yp, cy->zp, x, y,
                         z, 0, &b);
        cy->motion += b == b ? (double)b : INFINITY;
    }
    double L = list_keep(cy->nsec, cy->sec, x, y, z, cy->xp, cy->yp, cy->zp);
    if (!cy->self) {
        const double Lm = list_keep(cy->nmain, cy->mainn, x, y, z, cy->xp, cy->yp, cy->zp);
        L = Lm > L ? Lm : L; /* neither is NaN */
    }
    cy->have_prev = 1;
    cy->slack = 1024 * CY_EPS * (L + (double)cy->p.gap);
}

void cti_skip_remap(ctd_cycle *cy, ct_idx n, int old, int now)
{
    const ct_idx *restrict o = cy->old_of_new;
    const ct_real *restrict src = cy->ex[old];
    ct_real *restrict dst = cy->ex[now], *restrict pen = cy->geo.pen;
    const double M = cy->motion;
    /* The narrow-phase results are indexed by pair and not carried: a pair
     * the skip leaves out would find another pair's there. Its penetration
     * must read 0 (the force pass packs the pairs with p > 0). */
#pragma omp parallel for schedule(static)
    for (ct_idx k = 0; k < n; k++) {
        dst[k] = o[k] >= 0 ? (ct_real)((double)src[o[k]] - M) : (ct_real)-1;
        pen[k] = 0;
    }
    cy->motion = 0;
}

ct_idx cti_skip_select(ctd_cycle *cy, ct_idx k0, ct_idx k1, ct_idx *restrict act)
{
    const ct_real *restrict ex = cy->ex[cy->cur] + k0;
    uint8_t *restrict ev = cy->evald + k0;
    const double M = cy->motion;
    /* Every index is written, the count advances by the test: no branch. */
    ct_idx ne = 0;
    for (ct_idx k = 0; k < k1 - k0; k++) {
        const int need = !(M < (double)ex[k]);
        act[ne] = k;
        ne += need;
        ev[k] = (uint8_t)need;
    }
    return ne;
}

void cti_skip_expiry(ctd_cycle *cy, ct_idx k0, ct_idx ne, const ct_idx *restrict act,
                     const ct_real *restrict dist, const ct_real *restrict gap,
                     const uint8_t *restrict flag)
{
    ct_real *restrict ex = cy->ex[cy->cur] + k0;
    const double M = cy->motion, slack = cy->slack, inv = 1 / (1 + 1e-6);
    const uint8_t bad = CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE;
    for (ct_idx j = 0; j < ne; j++) {
        double e = (flag[j] & bad) ? -1 : M + ((double)dist[j] - (double)gap[j] - slack) * inv;
        ex[act[j]] = (ct_real)e;
    }
}
