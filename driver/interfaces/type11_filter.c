/*
 * type11_filter.c -- what TYPE11 keeps of its search's pairs. The search
 * (type11_search.c) lists the pairs of edges whose boxes, inflated by half
 * the search distance (the largest pair gap + the margin), overlap: a
 * superset of the pairs within that distance (a box's corner reaches sqrt(3)
 * times further than its face). The narrow phase measures them once per
 * search, in chunks into arrays of the filter's own (the per-pair arrays of
 * the step are sized for the pairs kept), and a pair stays when its edges
 * are within its gap and the margin: its distance shrinks by less than the
 * margin until the re-sort criterion asks for a new search, so no pair that
 * comes within its gap before then is lost. Pairs the narrow phase skipped
 * (a degenerate or non-finite edge) stay, for the step to report them.
 *
 * Irem_gap 2: at the first search, the edges within the largest pair gap of
 * an edge and joined to it through edges within it (its neighbours on the
 * surface, ct_exclusion of ct_search.h; candidates in both orders, as the
 * search lists a self pair once) are taken out of its pairs, so that a mesh
 * finer than the gap does not push itself apart. A pair is removed when
 * either edge excludes the other: the rule is then symmetric.
 */
#include "type11_internal.h"

#include "ct_internal.h"

#include <stdlib.h>

/* Measure pairs k0 .. k1-1 of the search's list into the filter's chunk
 * (index k - k0). */
static int measure(ctd_iface *it, ctdi_epass *e, ct_idx k0, ct_idx k1, const ct_real *x,
                   const ct_real *y, const ct_real *z)
{
    return ct_narrow_edge_edge(k1 - k0, e->pa + k0, e->pb + k0, e->e1, e->e2, x, y, z, e->gedge,
                               0, it->cfg.Gap_max_s, &e->fgeo, NULL);
}

/* The exclusion from the search's pairs within the largest pair gap. */
static int build_exclusion(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                           const ct_real *z)
{
    const ct_idx n = e->n;
    size_t cap = 1024, w = 0;
    ct_idx *cq = malloc(cap * sizeof *cq), *ci = malloc(cap * sizeof *ci);
    int rc = cq && ci ? CT_OK : CT_ERR_NOMEM;
    for (ct_idx k0 = 0; k0 < n && rc == CT_OK; k0 += CTDI_FCHUNK) {
        const ct_idx k1 = n - k0 > CTDI_FCHUNK ? k0 + CTDI_FCHUNK : n;
        if ((rc = measure(it, e, k0, k1, x, y, z)) != CT_OK)
            break;
        for (ct_idx k = k0; k < k1 && rc == CT_OK; k++) {
            if (!(e->fgeo.dist[k - k0] <= e->sgap))
                continue;
            if (w + 2 > cap) {
                ct_idx *a = realloc(cq, 2 * cap * sizeof *cq);
                ct_idx *b = a ? realloc(ci, 2 * cap * sizeof *ci) : NULL;
                if (a)
                    cq = a;
                if (b)
                    ci = b;
                if (!a || !b) {
                    rc = CT_ERR_NOMEM;
                    break;
                }
                cap *= 2;
            }
            cq[w] = e->pa[k];
            ci[w++] = e->pb[k];
            cq[w] = e->pb[k];
            ci[w++] = e->pa[k];
        }
    }
    if (rc == CT_OK) {
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
        in.ncand = (ct_idx)w;
        in.cq = cq;
        in.ci = ci;
        rc = ct_exclusion_build(&e->excl, &in);
    }
    free(cq);
    free(ci);
    return rc;
}

int ctdi_type11_filter(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                       const ct_real *z)
{
    int rc;
    const int first = e->excl_state == 1;
    if (first) {
        if ((rc = build_exclusion(it, e, x, y, z)) != CT_OK)
            return rc;
        e->excl_state = 2;
    }
    /* In order, chunk by chunk: a pair is written at or before where it was
     * read, after its chunk was measured, so the list keeps its canonical
     * order. */
    const ct_real margin = it->margin;
    const ct_idx n = e->n;
    ct_idx *pa = e->pa, *pb = e->pb, w = 0;
    int64_t excluded = 0;
    for (ct_idx k0 = 0; k0 < n; k0 += CTDI_FCHUNK) {
        const ct_idx k1 = n - k0 > CTDI_FCHUNK ? k0 + CTDI_FCHUNK : n;
        if ((rc = measure(it, e, k0, k1, x, y, z)) != CT_OK)
            return rc;
        const ct_real *restrict dist = e->fgeo.dist, *restrict gap = e->fgeo.gap;
        const uint8_t *restrict flag = e->fgeo.flag;
        for (ct_idx k = k0; k < k1; k++) {
            const ct_idx c = k - k0;
            const int skipped = (flag[c] & (CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE)) != 0;
            if (!skipped && !(dist[c] <= gap[c] + margin))
                continue;
            if (e->excl_state == 2 && (ct_exclusion_has(&e->excl, pa[k], pb[k]) ||
                                       ct_exclusion_has(&e->excl, pb[k], pa[k]))) {
                excluded++;
                continue;
            }
            pa[w] = pa[k];
            pb[w] = pb[k];
            w++;
        }
    }
    if (first)
        it->excluded += excluded;
    e->n = w;
    return CT_OK;
}
