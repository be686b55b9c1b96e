/*
 * exclude.c -- the neighbour exclusion of self contact (Radioss's
 * Irem_gap = 2; ct_search.h states the rule): which items (segments or
 * edges) near a query (a node or an edge) at the start are its surface
 * neighbours, and the removal of those pairs from a search's list.
 *
 * The build takes the candidates within the distance (any order), sorts
 * them into one list per query (counting sort, then each list ascending),
 * and grows, per query, the set reached from the items that hold one of its
 * nodes: an item is reached when it shares a node with a reached item and is
 * a candidate of the query. Each query's growth reads only its own list and
 * writes only its own marks, so the queries run in parallel and the result
 * is the same for any thread count. The scratch of one growth (a queue and
 * the list's marks) is per thread, sized by the longest list.
 */
#include <stdlib.h>

#include "ct_internal.h"

/* 1 when v is in the ascending list a[0..n-1], its position in *at. */
static int find_sorted(const ct_idx *a, ct_idx n, ct_idx v, ct_idx *at)
{
    ct_idx lo = 0, hi = n;
    while (lo < hi) {
        ct_idx mid = lo + (hi - lo) / 2;
        if (a[mid] < v)
            lo = mid + 1;
        else
            hi = mid;
    }
    *at = lo;
    return lo < n && a[lo] == v;
}

static int cmp_idx(const void *a, const void *b)
{
    ct_idx x = *(const ct_idx *)a, y = *(const ct_idx *)b;
    return (x > y) - (x < y);
}

/* The nodes of item t (duplicates, a triangle's n4 == n3, kept). */
static inline ct_idx item_node(const ct_exclusion_input *in, ct_idx t, int j)
{
    return in->in[j][t];
}

/* 1 when item t's node j is not one of its nodes before j. */
static int first_at(const ct_exclusion_input *in, ct_idx t, int j)
{
    for (int i = 0; i < j; i++)
        if (item_node(in, t, i) == item_node(in, t, j))
            return 0;
    return 1;
}

static int check_input(const ct_exclusion_input *in)
{
    if (!in || in->nnode < 0 || in->nitem < 0 || in->nq < 0 || in->ncand < 0 ||
        (in->nper != 2 && in->nper != 4))
        return CT_ERR_ARG;
    for (int j = 0; j < in->nper; j++)
        if (in->nitem > 0 && !in->in[j])
            return CT_ERR_ARG;
    if (in->ncand > 0 && (!in->cq || !in->ci))
        return CT_ERR_ARG;
    if (!in->q1 && in->nq > in->nnode)
        return CT_ERR_RANGE;
    for (int j = 0; j < in->nper; j++)
        for (ct_idx t = 0; t < in->nitem; t++)
            if (in->in[j][t] < 0 || in->in[j][t] >= in->nnode)
                return CT_ERR_RANGE;
    for (ct_idx q = 0; in->q1 && q < in->nq; q++) {
        ct_idx b = in->q2 ? in->q2[q] : in->q1[q];
        if (in->q1[q] < 0 || in->q1[q] >= in->nnode || b < 0 || b >= in->nnode)
            return CT_ERR_RANGE;
    }
    for (ct_idx k = 0; k < in->ncand; k++)
        if (in->cq[k] < 0 || in->cq[k] >= in->nq || in->ci[k] < 0 || in->ci[k] >= in->nitem)
            return CT_ERR_RANGE;
    return CT_OK;
}

/* Node -> item adjacency (CSR, items ascending, an item once per node). */
static int node_items(const ct_exclusion_input *in, ct_idx **off_out, ct_idx **adj_out)
{
    ct_idx *off = ct_calloc((size_t)in->nnode + 1, sizeof *off);
    if (!off)
        return CT_ERR_NOMEM;
    for (ct_idx t = 0; t < in->nitem; t++)
        for (int j = 0; j < in->nper; j++)
            if (first_at(in, t, j))
                off[item_node(in, t, j) + 1]++;
    for (ct_idx v = 0; v < in->nnode; v++)
        off[v + 1] += off[v];
    ct_idx *adj = ct_calloc((size_t)off[in->nnode] + 1, sizeof *adj);
    ct_idx *fill = ct_calloc((size_t)in->nnode + 1, sizeof *fill);
    if (!adj || !fill) {
        ct_free(off);
        ct_free(adj);
        ct_free(fill);
        return CT_ERR_NOMEM;
    }
    for (ct_idx t = 0; t < in->nitem; t++)
        for (int j = 0; j < in->nper; j++)
            if (first_at(in, t, j)) {
                ct_idx v = item_node(in, t, j);
                adj[off[v] + fill[v]++] = t;
            }
    ct_free(fill);
    *off_out = off;
    *adj_out = adj;
    return CT_OK;
}

/* The candidates as one ascending list per query (CSR); a repeated
 * candidate is kept once. */
static int candidate_lists(const ct_exclusion_input *in, ct_idx **off_out, ct_idx **item_out)
{
    ct_idx *off = ct_calloc((size_t)in->nq + 1, sizeof *off);
    ct_idx *item = ct_calloc((size_t)in->ncand + 1, sizeof *item);
    if (!off || !item) {
        ct_free(off);
        ct_free(item);
        return CT_ERR_NOMEM;
    }
    for (ct_idx k = 0; k < in->ncand; k++)
        off[in->cq[k] + 1]++;
    for (ct_idx q = 0; q < in->nq; q++)
        off[q + 1] += off[q];
    ct_idx *fill = ct_calloc((size_t)in->nq + 1, sizeof *fill);
    if (!fill) {
        ct_free(off);
        ct_free(item);
        return CT_ERR_NOMEM;
    }
    for (ct_idx k = 0; k < in->ncand; k++)
        item[off[in->cq[k]] + fill[in->cq[k]]++] = in->ci[k];
    /* Sort each list (a search's lists are already ascending) and drop
     * repeats; the lists shrink in place, fill[q] their new lengths. */
    for (ct_idx q = 0; q < in->nq; q++) {
        ct_idx *a = item + off[q], n = off[q + 1] - off[q];
        int sorted = 1;
        for (ct_idx i = 1; i < n && sorted; i++)
            sorted = a[i - 1] < a[i];
        if (!sorted)
            qsort(a, (size_t)n, sizeof *a, cmp_idx);
        ct_idx u = 0;
        for (ct_idx i = 0; i < n; i++)
            if (u == 0 || a[i] != a[u - 1])
                a[u++] = a[i];
        fill[q] = u;
    }
    ct_idx w = 0;
    for (ct_idx q = 0; q < in->nq; q++) {
        ct_idx s = off[q];
        off[q] = w;
        memmove(item + w, item + s, (size_t)fill[q] * sizeof *item);
        w += fill[q];
    }
    off[in->nq] = w;
    ct_free(fill);
    *off_out = off;
    *item_out = item;
    return CT_OK;
}

/* Grow query q's reached set over its list c[0..n-1] (marks in mark[]);
 * queue holds at most n + the seed items. */
static void grow_query(const ct_exclusion_input *in, const ct_idx *noff, const ct_idx *nadj,
                       ct_idx q, const ct_idx *c, ct_idx n, uint8_t *mark, ct_idx *queue)
{
    ct_idx head = 0, tail = 0;
    const ct_idx a = in->q1 ? in->q1[q] : q;
    const ct_idx b = in->q1 ? (in->q2 ? in->q2[q] : a) : q;
    /* Seeds: the items holding one of the query's nodes. */
    for (int s = 0; s < (a == b ? 1 : 2); s++) {
        const ct_idx v = s == 0 ? a : b;
        for (ct_idx j = noff[v]; j < noff[v + 1]; j++) {
            ct_idx t = nadj[j], at;
            if (find_sorted(c, n, t, &at)) {
                if (mark[at])
                    continue;
                mark[at] = 1;
            }
            queue[tail++] = t;
        }
    }
    while (head < tail) {
        const ct_idx t = queue[head++];
        for (int j = 0; j < in->nper; j++) {
            const ct_idx v = item_node(in, t, j);
            for (ct_idx i = noff[v]; i < noff[v + 1]; i++) {
                ct_idx u = nadj[i], at;
                if (find_sorted(c, n, u, &at) && !mark[at]) {
                    mark[at] = 1;
                    queue[tail++] = u;
                }
            }
        }
    }
}

void ct_exclusion_destroy(ct_exclusion *ex)
{
    if (!ex)
        return;
    ct_free(ex->off);
    ct_free(ex->item);
    memset(ex, 0, sizeof *ex);
}

int ct_exclusion_build(ct_exclusion *ex, const ct_exclusion_input *in)
{
    if (!ex)
        return CT_ERR_ARG;
    memset(ex, 0, sizeof *ex);
    int rc = check_input(in);
    if (rc != CT_OK)
        return rc;
    ct_idx *noff = NULL, *nadj = NULL, *coff = NULL, *citem = NULL, *scratch = NULL;
    uint8_t *mark = NULL;
    if ((rc = node_items(in, &noff, &nadj)) != CT_OK)
        return rc;
    if ((rc = candidate_lists(in, &coff, &citem)) != CT_OK)
        goto done;
    /* A queue holds the seeds (the items of two nodes) and the list. */
    ct_idx longest = 0, maxdeg = 0;
    for (ct_idx q = 0; q < in->nq; q++)
        longest = coff[q + 1] - coff[q] > longest ? coff[q + 1] - coff[q] : longest;
    for (ct_idx v = 0; v < in->nnode; v++)
        maxdeg = noff[v + 1] - noff[v] > maxdeg ? noff[v + 1] - noff[v] : maxdeg;
    const size_t per = (size_t)longest + 2 * (size_t)maxdeg + 1;
    const int nt = cti_num_threads();
    scratch = ct_calloc(per * (size_t)nt, sizeof *scratch);
    mark = ct_calloc((size_t)coff[in->nq] + 1, 1);
    ex->off = ct_calloc((size_t)in->nq + 1, sizeof *ex->off);
    if (!scratch || !mark || !ex->off) {
        rc = CT_ERR_NOMEM;
        goto done;
    }
    const ct_idx nq = in->nq;
    CTI_PAR_FOR(nq > 256, (schedule(dynamic, 64)),
    for (ct_idx q = 0; q < nq; q++) {
        ct_idx *queue = scratch + per * (size_t)cti_thread_id();
        grow_query(in, noff, nadj, q, citem + coff[q], coff[q + 1] - coff[q], mark + coff[q],
                   queue);
    });
    for (ct_idx q = 0; q < nq; q++) {
        ct_idx m = 0;
        for (ct_idx k = coff[q]; k < coff[q + 1]; k++)
            m += mark[k];
        ex->off[q + 1] = ex->off[q] + m;
    }
    ex->item = ct_calloc((size_t)ex->off[nq] + 1, sizeof *ex->item);
    if (!ex->item) {
        rc = CT_ERR_NOMEM;
        goto done;
    }
    for (ct_idx k = 0, w = 0; k < coff[nq]; k++)
        if (mark[k])
            ex->item[w++] = citem[k];
    ex->nq = nq;
done:
    ct_free(noff);
    ct_free(nadj);
    ct_free(coff);
    ct_free(citem);
    ct_free(scratch);
    ct_free(mark);
    if (rc != CT_OK)
        ct_exclusion_destroy(ex);
    return rc;
}

int ct_exclusion_has(const ct_exclusion *ex, ct_idx q, ct_idx item)
{
    if (!ex || !ex->off || q < 0 || q >= ex->nq)
        return 0;
    ct_idx at;
    return find_sorted(ex->item + ex->off[q], ex->off[q + 1] - ex->off[q], item, &at);
}

int ct_pairs_exclude(ct_pairs *p, const ct_exclusion *ex, int64_t *removed)
{
    if (removed)
        *removed = 0;
    if (!p || !ex || (p->n > 0 && (!p->node || !p->seg)))
        return CT_ERR_ARG;
    if (ex->nq == 0)
        return CT_OK;
    const ct_idx n = p->n;
    for (ct_idx k = 0; k < n; k++) {
        const ct_idx q = p->node[k];
        if (q < 0 || q >= ex->nq)
            return CT_ERR_RANGE;
    }
    /* One pass in order: the list keeps its canonical order. */
    ct_idx w = 0;
    for (ct_idx k = 0; k < n; k++) {
        const ct_idx q = p->node[k];
        const ct_idx lo = ex->off[q], len = ex->off[q + 1] - lo;
        ct_idx at;
        if (len > 0 && find_sorted(ex->item + lo, len, p->seg[k], &at))
            continue;
        p->node[w] = p->node[k];
        p->seg[w] = p->seg[k];
        w++;
    }
    if (removed)
        *removed = (int64_t)(n - w);
    p->n = w;
    return CT_OK;
}

int ct_exclusion_build_nodeseg(ct_exclusion *ex, const ct_search_input *in, ct_real r)
{
    if (!ex || !in || !(r >= 0) || CTI_NONFINITE(r))
        return CT_ERR_ARG;
    memset(ex, 0, sizeof *ex);
    ct_search_params sp;
    memset(&sp, 0, sizeof sp);
    sp.algo = CT_SEARCH_BUCKET;
    sp.variant = 1;
    ct_search *s = NULL;
    ct_pairs pr;
    int rc = ct_search_init(&s, &sp);
    if (rc != CT_OK)
        return rc;
    if ((rc = ct_pairs_init(&pr, 0)) != CT_OK) {
        ct_search_destroy(s);
        return rc;
    }
    ct_search_input w = *in;
    w.gap = r;
    w.margin = 0;
    w.self = 1;
    w.filter = CT_FILTER_HULL;
    rc = ct_search_run(s, &w, &pr);
    if (rc == CT_OK) {
        ct_exclusion_input e;
        memset(&e, 0, sizeof e);
        e.nnode = in->nnode;
        e.nitem = in->nseg;
        e.nper = 4;
        e.in[0] = in->n1;
        e.in[1] = in->n2;
        e.in[2] = in->n3;
        e.in[3] = in->n4;
        e.nq = in->nnode;
        e.ncand = pr.n;
        e.cq = pr.node;
        e.ci = pr.seg;
        rc = ct_exclusion_build(ex, &e);
    }
    ct_pairs_destroy(&pr);
    ct_search_destroy(s);
    return rc;
}
