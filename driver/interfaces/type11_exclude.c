/*
 * type11_exclude.c -- Irem_gap 2 for TYPE11: the edges within the gap of an
 * edge at the start and joined to it through edges within the gap (its
 * neighbours on the surface, ct_exclusion of ct_search.h) are taken out of
 * its pairs, so that a mesh finer than the gap does not push itself apart.
 *
 * The first search's pairs hold every pair within the search distance
 * (gap + margin) by their inflated boxes; the narrow phase measures them,
 * and those within the largest pair gap, in both orders (the search lists a
 * self pair once), are the candidates of the exclusion. A pair is removed
 * when either edge excludes the other: the rule is then symmetric.
 */
#include "type11_internal.h"

#include "ct_internal.h"

#include <stdlib.h>

static int build(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                 const ct_real *z)
{
    const ct_idx n = e->n;
    int rc = ct_narrow_edge_edge(n, e->pa, e->pb, e->e1, e->e2, x, y, z, e->gedge, 0,
                                 it->cfg.Gap_max_s, &e->geo, NULL);
    if (rc != CT_OK)
        return rc;
    const ct_real *dist = e->geo.dist;
    ct_idx nc = 0;
    for (ct_idx k = 0; k < n; k++)
        nc += dist[k] <= e->sgap;
    ct_idx *cq = ct_calloc(2 * (size_t)nc + 1, sizeof *cq);
    ct_idx *ci = ct_calloc(2 * (size_t)nc + 1, sizeof *ci);
    if (!cq || !ci) {
        ct_free(cq);
        ct_free(ci);
        return CT_ERR_NOMEM;
    }
    ct_idx w = 0;
    for (ct_idx k = 0; k < n; k++)
        if (dist[k] <= e->sgap) {
            cq[w] = e->pa[k];
            ci[w++] = e->pb[k];
            cq[w] = e->pb[k];
            ci[w++] = e->pa[k];
        }
    ct_exclusion_input in;
    memset(&in, 0, sizeof in);
    in.nnode = it->nnode;
    in.nitem = e->ne;
    in.nper = 2;
    in.in[0] = e->e1;
    in.in[1] = e->e2;
    in.nq = e->ne;
    in.q1 = e->e1;
    in.q2 = e->e2;
    in.ncand = w;
    in.cq = cq;
    in.ci = ci;
    rc = ct_exclusion_build(&e->excl, &in);
    ct_free(cq);
    ct_free(ci);
    return rc;
}

int ctdi_type11_exclude(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                        const ct_real *z)
{
    if (e->excl_state == 0)
        return CT_OK;
    const int first = e->excl_state == 1;
    if (first) {
        int rc = build(it, e, x, y, z);
        if (rc != CT_OK)
            return rc;
        e->excl_state = 2;
    }
    /* In order: the pairs keep their canonical order. */
    ct_idx *pa = e->pa, *pb = e->pb, w = 0;
    for (ct_idx k = 0; k < e->n; k++) {
        if (ct_exclusion_has(&e->excl, pa[k], pb[k]) || ct_exclusion_has(&e->excl, pb[k], pa[k]))
            continue;
        pa[w] = pa[k];
        pb[w] = pb[k];
        w++;
    }
    if (first)
        it->excluded += e->n - w;
    e->n = w;
    return CT_OK;
}
