/*
 * iface_reach.c -- an interface's gaps against the extent of its nodes
 * (ctd_iface_check_reach). A gap as large as the model makes every node a
 * contact of every segment: the search's candidates grow as nsec x nseg
 * (a 10^4-node sheet with a 10 m gap exhausted 24 GiB) and the penalty
 * pushes across the whole model. It is an input mistake, told before the
 * run starts.
 */
#include <math.h>
#include <stdio.h>

#include "type11_internal.h"

/* The box around the listed nodes of two lists, grown into lo, hi. */
static void box_of(ct_idx n, const ct_idx *v, const ct_real *x, const ct_real *y,
                   const ct_real *z, double lo[3], double hi[3])
{
    for (ct_idx i = 0; i < n; i++) {
        double c[3] = {x[v[i]], y[v[i]], z[v[i]]};
        for (int d = 0; d < 3; d++) {
            lo[d] = c[d] < lo[d] ? c[d] : lo[d];
            hi[d] = c[d] > hi[d] ? c[d] : hi[d];
        }
    }
}

/* The diagonal of the box around the nodes of lists a and b. */
static double extent(ct_idx na, const ct_idx *a, ct_idx nb, const ct_idx *b, const ct_real *x,
                     const ct_real *y, const ct_real *z)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    box_of(na, a, x, y, z, lo, hi);
    box_of(nb, b, x, y, z, lo, hi);
    if (!(hi[0] >= lo[0]))
        return INFINITY; /* no node: nothing to span */
    double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

static int too_far(char *msg, size_t len, const char *what, double gap, double diag, double h)
{
    if (!(gap >= diag))
        return CT_OK;
    char hs[64] = "";
    if (h > 0)
        snprintf(hs, sizeof hs, ", %.3g here", h);
    snprintf(msg, len,
             "its %s gap %g reaches the diagonal %g of the box around its nodes, so every "
             "node would be in contact with every %s (expected a gap below the element "
             "size%s)",
             what, gap, diag, what[0] == 'e' ? "edge" : "segment", hs);
    return CT_ERR_ARG;
}

int ctd_iface_check_reach(const ctd_iface *it, const ct_real *x, const ct_real *y,
                          const ct_real *z, char *msg, size_t len)
{
    if (!it || !x || !y || !z)
        return CT_ERR_ARG;
    for (int i = 0; i < it->npass; i++) {
        const ctdi_pass *p = &it->pass[i];
        if (p->nsec == 0 || p->nseg == 0)
            continue;
        double d = extent(p->nsec, p->sec, p->nmain, p->mainn, x, y, z);
        double h = ctdi_mean_seg_edge(p->nseg, p->n1, p->n2, p->n3, p->n4, x, y, z);
        int rc = too_far(msg, len, "node-segment", p->reach, d, h);
        if (rc != CT_OK)
            return rc;
    }
    const ctdi_epass *e = it->ep;
    if (e && e->ne > 0) {
        /* sgap is the sum of two edge gaps: the distance of two edges' axes
         * in contact. */
        double d = extent(e->nan, e->an, e->nbn, e->bn, x, y, z);
        return too_far(msg, len, "edge-edge", e->sgap, d, 0);
    }
    return CT_OK;
}
