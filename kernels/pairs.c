/*
 * pairs.c -- candidate pair lists, and the collector that turns per-thread,
 * per-node candidate lists into the canonical pair order.
 */
#include <stdlib.h>

#include "ct_internal.h"

int ct_pairs_init(ct_pairs *p, ct_idx cap)
{
    if (!p || cap < 0)
        return CT_ERR_ARG;
    memset(p, 0, sizeof *p);
    return ct_pairs_reserve(p, cap > 0 ? cap : 16);
}

int ct_pairs_reserve(ct_pairs *p, ct_idx cap)
{
    if (!p || cap < 0)
        return CT_ERR_ARG;
    if (cap <= p->cap && p->node)
        return CT_OK;
    size_t ncap = (size_t)cap + (size_t)cap / 4 + 16;
    if (ncap > (size_t)INT32_MAX)
        ncap = (size_t)INT32_MAX;
    if ((size_t)cap > ncap)
        return CT_ERR_TOOBIG;
    if (cti_renew_two(&p->node, &p->seg, p->n > 0 ? (size_t)p->n : 0, ncap) != CT_OK)
        return CT_ERR_NOMEM;
    p->cap = (ct_idx)ncap;
    return CT_OK;
}

void ct_pairs_destroy(ct_pairs *p)
{
    if (!p)
        return;
    ct_free(p->node);
    ct_free(p->seg);
    memset(p, 0, sizeof *p);
}

int cti_collect_begin(cti_collect *c, ct_idx nsec)
{
    int nt = cti_num_threads();
    if (nt > c->maxthr) {
        ct_idx **nb = calloc((size_t)nt, sizeof *nb);
        size_t *nl = calloc((size_t)nt, sizeof *nl), *nc = calloc((size_t)nt, sizeof *nc);
        if (!nb || !nl || !nc) {
            free(nb);
            free(nl);
            free(nc);
            return CT_ERR_NOMEM;
        }
        for (int t = 0; t < c->maxthr; t++) {
            nb[t] = c->buf[t];
            nc[t] = c->cap[t];
        }
        free(c->buf);
        free(c->len);
        free(c->cap);
        c->buf = nb;
        c->len = nl;
        c->cap = nc;
        c->maxthr = nt;
    }
    c->nthr = nt;
    for (int t = 0; t < nt; t++)
        c->len[t] = 0;
    if (nsec > c->seccap || !c->owner) {
        ct_free(c->owner);
        ct_free(c->start);
        ct_free(c->count);
        ct_free(c->off);
        c->owner = ct_calloc((size_t)nsec, sizeof *c->owner);
        c->start = ct_calloc((size_t)nsec, sizeof *c->start);
        c->count = ct_calloc((size_t)nsec, sizeof *c->count);
        c->off = ct_calloc((size_t)nsec + 1, sizeof *c->off);
        c->seccap = nsec;
        if (!c->owner || !c->start || !c->count || !c->off)
            return CT_ERR_NOMEM;
    }
    c->nsec = nsec;
    c->err = 0;
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < nsec; i++)
        c->count[i] = 0;
    return CT_OK;
}

/* The collector's pair limit (c->max, 0: 2^31 - 1). */
static int64_t collect_max(const cti_collect *c)
{
    return c->max > 0 ? c->max : INT32_MAX;
}

int cti_collect_room(cti_collect *c, int t, size_t extra)
{
    size_t need = c->len[t] + extra;
    if (need <= c->cap[t])
        return CT_OK;
    /* Pairs this thread kept beyond the limit: the total is beyond it
     * too, whatever the other threads hold (stop before growing). */
    if ((int64_t)c->len[t] > collect_max(c)) {
#pragma omp atomic write
        c->err = CT_ERR_TOOBIG;
        return CT_ERR_TOOBIG;
    }
    void *p = c->buf[t];
    if (cti_grow(&p, &c->cap[t], need, sizeof(ct_idx), c->len[t]) != CT_OK) {
#pragma omp atomic write
        c->err = CT_ERR_NOMEM;
        return CT_ERR_NOMEM;
    }
    c->buf[t] = p;
    return CT_OK;
}

/* The first node i in [0, n] whose first pair is at or after q (off is
 * nondecreasing, off[n] = the total). */
static ct_idx collect_first_at(const int64_t *off, ct_idx n, int64_t q)
{
    ct_idx a = 0, b = n;
    while (a < b) {
        ct_idx m = a + (b - a) / 2;
        if (off[m] < q)
            a = m + 1;
        else
            b = m;
    }
    return a;
}

int cti_collect_finish(cti_collect *c, const ct_idx *sec, ct_pairs *out)
{
    if (c->err)
        return c->err;
    int64_t total = cti_prefix_sum(c->count, c->off, c->nsec);
    if (total > collect_max(c))
        return CT_ERR_TOOBIG;
    int rc = ct_pairs_reserve(out, (ct_idx)total);
    if (rc)
        return rc;
    ct_idx *restrict on = out->node, *restrict os = out->seg;
    const int64_t *restrict off = c->off;
    const ct_idx nsec = c->nsec;
    /* Each thread writes an equal share of the pairs, not of the nodes: on
     * a graded mesh the pairs per node vary tenfold along the numbering.
     * Its nodes are those whose first pair falls in its share (found by
     * bisection of the offsets); every pair is written once, at the same
     * place, whatever the thread count. */
#pragma omp parallel
    {
        const int nt = cti_team_size(), t = cti_thread_id();
        ct_idx lo = collect_first_at(off, nsec, total * t / nt);
        ct_idx hi = collect_first_at(off, nsec, total * (t + 1) / nt);
        for (ct_idx i = lo; i < hi; i++) {
            ct_idx n = c->count[i];
            if (n == 0)
                continue;
            int64_t o = off[i];
            const ct_idx *src = c->buf[c->owner[i]] + c->start[i];
            for (ct_idx k = 0; k < n; k++) {
                on[o + k] = sec[i];
                os[o + k] = src[k];
            }
        }
    }
    out->n = (ct_idx)total;
    return CT_OK;
}

void cti_collect_free(cti_collect *c)
{
    for (int t = 0; t < c->maxthr; t++)
        ct_free(c->buf[t]);
    free(c->buf);
    free(c->len);
    free(c->cap);
    ct_free(c->owner);
    ct_free(c->start);
    ct_free(c->count);
    ct_free(c->off);
    memset(c, 0, sizeof *c);
}

size_t cti_collect_memory(const cti_collect *c)
{
    size_t b = (size_t)c->seccap * (sizeof *c->owner + sizeof *c->start + sizeof *c->count +
                                   sizeof *c->off);
    for (int t = 0; t < c->maxthr; t++)
        b += c->cap[t] * sizeof(ct_idx);
    return b;
}
