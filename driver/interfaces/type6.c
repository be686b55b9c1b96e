/*
 * type6.c -- TYPE6 (seed 004): contact between two rigid bodies whose
 * normal force is a user curve of the largest penetration. One pass of the
 * pass engine (iface_pass.c) takes the secondary nodes (data.sec and the
 * nodes of the secondary segments s1..s4) against the main segments,
 * one-sided unless cfg.two_sided, with the gap cfg.gap (0 by default: the
 * penetration is minus the signed distance).
 *
 * The law (CTDI_LAW_TYPE6, ct_penalty_type6): with p_max the largest
 * penetration of the pass, the total normal force is F = max(0, f(p_max)),
 * shared by the penetrating pairs in proportion to their penetration,
 * F_k = F p_k / sum(p), so the forces sum to F (the seed's formula for one
 * pass). The stored energy is the integral of max(0, f) from 0 to p_max
 * (the curve read as an elastic loading curve), computed exactly for the
 * piecewise-linear table by ctdi_curve_integral. The curve's stiffness
 * K = max(f'(p_max), f(p_max)/p_max) tunes the damper of every penetrating
 * pair (C = VisS sqrt(2 K m), VisS 0 by default) and sets the step
 * 0.1 sqrt(M_min / K) (ct_dt_type6), M_min the smaller rigid-body mass
 * (data.mass_min, or the smaller of the two sides' nodal mass sums at the
 * first active step); before any penetration, K is the curve's at its
 * first point beyond zero. The nodal step is not used: the nodes move with
 * their bodies. Friction sees each pair's share of K, K F_k / F, as its
 * tangential stiffness, so the tangential springs of the pass add up to K.
 */
#include "iface_internal.h"

#include "ct_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The integral over a width w of the positive part of the linear function
 * going from f0 to f1. */
static double positive_trapezoid(double f0, double f1, double w)
{
    if (f0 >= 0 && f1 >= 0)
        return 0.5 * (f0 + f1) * w;
    if (f0 <= 0 && f1 <= 0)
        return 0;
    /* One sign change: the triangle on the positive side of the root. */
    double fp = f0 > 0 ? f0 : f1, fm = f0 > 0 ? f1 : f0;
    return 0.5 * fp * (w * fp / (fp - fm));
}

double ctdi_curve_integral(ct_idx n, const ct_real *x, const ct_real *y, double a, double b)
{
    if (n < 2 || !(b > a))
        return 0;
    double sum = 0;
    /* Interval i is [x[i], x[i+1]], the first one extended to the left and
     * the last one to the right (the extrapolation of ct_curve_eval). */
    for (ct_idx i = 0; i + 1 < n; i++) {
        double lo = i == 0 ? a : (double)x[i], hi = i + 2 == n ? b : (double)x[i + 1];
        double u0 = a > lo ? a : lo, u1 = b < hi ? b : hi;
        if (!(u1 > u0))
            continue;
        double s = ((double)y[i + 1] - (double)y[i]) / ((double)x[i + 1] - (double)x[i]);
        double f0 = (double)y[i] + s * (u0 - (double)x[i]);
        double f1 = (double)y[i] + s * (u1 - (double)x[i]);
        sum += positive_trapezoid(f0, f1, u1 - u0);
    }
    return sum;
}

int ctdi_type6_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag)
{
    const ctd_iface_cfg *c = &it->cfg;
    ct_diag cd;
    memset(&cd, 0, sizeof cd);
    if (ct_curve_check(c->ncurve, c->curve_p, c->curve_f, &cd) != CT_OK) {
        char msg[400];
        snprintf(msg, sizeof msg,
                 "TYPE6 needs a valid force curve (ncurve >= 2 points, curve_p strictly "
                 "ascending, finite values): %s",
                 cd.msg);
        return ctdi_fail(diag, CT_ERR_ARG, cd.index, msg);
    }
    if (!(d->mass_min >= 0) || !(d->mass_min < (ct_real)1e30))
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "TYPE6 mass_min must be finite and >= 0 (0: from the nodal masses).");
    const ct_idx ns = d->nsseg;
    const int has_sec = d->nsec > 0 && d->sec;
    const int has_seg = ns > 0 && d->s1 && d->s2 && d->s3 && d->s4;
    if (!has_sec && !has_seg)
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "TYPE6 needs secondary nodes (data.sec) or secondary segments "
                         "(data.s1..s4).");
    /* Own the table: the caller's arrays may go away after init. */
    size_t nc = (size_t)c->ncurve;
    it->curve_p = ct_calloc(nc, sizeof(ct_real));
    it->curve_f = ct_calloc(nc, sizeof(ct_real));
    if (!it->curve_p || !it->curve_f)
        return CT_ERR_NOMEM;
    memcpy(it->curve_p, c->curve_p, nc * sizeof(ct_real));
    memcpy(it->curve_f, c->curve_f, nc * sizeof(ct_real));
    it->ncurve = c->ncurve;
    it->cfg.curve_p = it->curve_p;
    it->cfg.curve_f = it->curve_f;
    it->mass_min = d->mass_min;
    it->mass_set = d->mass_min > 0;
    const ct_idx *l[6] = {has_sec ? d->sec : NULL, has_seg ? d->s1 : NULL,
                          has_seg ? d->s2 : NULL,  has_seg ? d->s3 : NULL,
                          has_seg ? d->s4 : NULL,  NULL};
    const ct_idx k[6] = {d->nsec, ns, ns, ns, ns, 0};
    const ctdi_surf m = ctdi_main_surf(d);
    return ctdi_add_pass(it, l, k, &m, 0, 0, CTDI_LAW_TYPE6, "main segments", diag);
}

int ctdi_type6_prune(const ctd_iface *it, ctdi_pass *p, ct_pairs *pp, const ct_real *x,
                     const ct_real *y, const ct_real *z)
{
    /* The carrier of a node is its pair of smallest |distance| (select.c;
     * a pinch's second carrier penetrates, so is within the gap). A pair's
     * distance changes by at most the motion bound of the re-sort
     * criterion, below a margin until the next search, whatever the bodies
     * do (turning included): a pair farther than the node's closest by more
     * than two margins, and beyond the gap by as much, cannot carry the node
     * before then. The distance here is to the two triangles a b c, a c d;
     * the narrow phase's surface over the same corners (4 triangles around
     * the centroid, or bilinear) is within twice the warp w (the corners'
     * largest distance to their mean plane) of it, hence the 2 w on either
     * side. A NaN distance (a NaN corner) keeps its pair, for the narrow
     * phase to report. The search's order is kept: a node's pairs are
     * consecutive. */
    const ct_idx n = pp->n;
    if (2 * (size_t)n > p->prune_cap || !p->prune) {
        size_t cap = 2 * (size_t)n + (size_t)n / 2 + 64;
        ct_free(p->prune);
        p->prune = ct_calloc(cap, sizeof *p->prune);
        p->prune_cap = p->prune ? cap : 0;
        if (!p->prune)
            return CT_ERR_NOMEM;
    }
    double *restrict dk = p->prune, *restrict wk = p->prune + n;
    CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++) {
        const ct_idx j = pp->seg[k], s = pp->node[k];
        const ct_idx v[4] = {p->n1[j], p->n2[j], p->n3[j], p->n4[j]};
        double c[4][3], q[3] = {0, 0, 0};
        for (int a = 0; a < 4; a++) {
            c[a][0] = x[v[a]];
            c[a][1] = y[v[a]];
            c[a][2] = z[v[a]];
            for (int d = 0; d < 3; d++)
                q[d] += 0.25 * c[a][d];
        }
        /* The search's own point-triangle distance (predicate.c). */
        ct_real ps[3] = {x[s], y[s], z[s]}, cr[4][3];
        for (int a = 0; a < 4; a++)
            for (int d = 0; d < 3; d++)
                cr[a][d] = (ct_real)c[a][d];
        double d2 = (double)cti_dist2_point_triangle(ps, cr[0], cr[1], cr[2]);
        if (v[3] != v[2])
            d2 = fmin(d2, (double)cti_dist2_point_triangle(ps, cr[0], cr[2], cr[3]));
        /* The warp: the corners' largest distance to the plane through their
         * mean normal to the diagonals' cross product (0 for a triangle). */
        double warp = 0;
        if (v[3] != v[2]) {
            double e[3], f[3], nv[3];
            for (int d = 0; d < 3; d++) {
                e[d] = c[2][d] - c[0][d];
                f[d] = c[3][d] - c[1][d];
            }
            nv[0] = e[1] * f[2] - e[2] * f[1];
            nv[1] = e[2] * f[0] - e[0] * f[2];
            nv[2] = e[0] * f[1] - e[1] * f[0];
            const double len = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
            for (int a = 0; a < 4 && len > 0; a++)
                warp = fmax(warp, fabs(((c[a][0] - q[0]) * nv[0] + (c[a][1] - q[1]) * nv[1] +
                                        (c[a][2] - q[2]) * nv[2]) / len));
        }
        dk[k] = sqrt(d2);
        wk[k] = 2 * warp;
    });
    const double two_m = 2 * (double)it->margin, gap = (double)p->reach;
    ct_idx w = 0;
    for (ct_idx a = 0; a < n;) {
        ct_idx b = a;
        double dmin = INFINITY;
        while (b < n && pp->node[b] == pp->node[a]) {
            dmin = fmin(dmin, dk[b] + wk[b]);
            b++;
        }
        const double keep = (gap > dmin ? gap : dmin) + two_m;
        for (ct_idx k = a; k < b; k++) {
            if (dk[k] - wk[k] > keep)
                continue;
            pp->node[w] = pp->node[k];
            pp->seg[w] = pp->seg[k];
            w++;
        }
        a = b;
    }
    pp->n = w;
    return CT_OK;
}

int ctdi_type6_normal(ctd_iface *it, ctdi_pass *p, ct_idx n)
{
    ct_real **r = p->r;
    ct_real F = 0, kc = 0, pm = 0;
    int rc = ct_penalty_type6(n, p->geo.pen, it->ncurve, it->curve_p, it->curve_f,
                              r[CTDI_R_FEL], &pm, &F, &kc, NULL);
    if (rc != CT_OK)
        return rc;
    p->pmax = pm;
    p->kcurve = kc;
    /* Deeper than the last search's pairs hold for certain: search again
     * next step, with the reach this depth asks for. */
    if (pm > p->plimit)
        p->need_sort = 1;
    p->e_law = pm > 0 ? ctdi_curve_integral(it->ncurve, it->curve_p, it->curve_f, 0, pm) : 0;
    const ct_real *restrict pen = p->geo.pen, *restrict fel = r[CTDI_R_FEL];
    ct_real *restrict kt = r[CTDI_R_KTAN], *restrict K = r[CTDI_R_K], *restrict en = r[CTDI_R_EN],
                      *restrict pp = p->st[p->cur][CTDI_ST_PPREV];
    const ct_real share = F > 0 ? kc / F : 0;
    CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++) {
        const int on = pen[k] > 0;
        kt[k] = on ? kc : 0;
        K[k] = fel[k] * share;
        en[k] = 0;
        /* The pair carried the node this step: its states follow the
         * contact to the next segment (pair_select.c). */
        pp[k] = on ? pen[k] : 0;
    });
    return CT_OK;
}

ct_real ctdi_type6_dt(ctd_iface *it, const ctdi_pass *p, const ct_real *m)
{
    if (!it->mass_set) {
        double ms = 0, mm = 0;
        for (ct_idx i = 0; i < p->nsec; i++)
            ms += (double)m[p->sec[i]];
        for (ct_idx i = 0; i < p->nmain; i++)
            mm += (double)m[p->mainn[i]];
        it->mass_min = (ct_real)(ms < mm ? ms : mm);
        it->mass_set = 1;
    }
    /* Before the first contact (nothing penetrates) the step is that of
     * the curve's first point beyond zero: otherwise nothing bounds the
     * step until the bodies are already in, and the first contact cycle
     * finds them deep inside. */
    ct_real pe = p->pmax;
    for (ct_idx k = 0; !(pe > 0) && k < it->ncurve; k++)
        pe = it->curve_p[k];
    return ct_dt_type6(it->mass_min, pe, it->ncurve, it->curve_p, it->curve_f);
}
