/*
 * search.c -- the search workspace, the dispatcher over the four
 * algorithms and the direct (all pairs) reference search. The re-sort
 * criterion is in resort.c.
 */
#include <stdlib.h>

#include "ct_internal.h"

static const char *const algo_names[CT_SEARCH_NALGO] = {"direct", "topological", "bucket",
                                                        "bsp"};

const char *ct_search_algo_name(ct_search_algo a)
{
    return (a >= 0 && a < CT_SEARCH_NALGO) ? algo_names[a] : "unknown";
}

int ct_search_algo_from_name(const char *name)
{
    for (int a = 0; name && a < CT_SEARCH_NALGO; a++)
        if (strcmp(name, algo_names[a]) == 0)
            return a;
    if (name && (strcmp(name, "topo") == 0))
        return CT_SEARCH_TOPO;
    return -1;
}

ct_search_params ct_search_default_params(ct_search_algo algo)
{
    ct_search_params p;
    memset(&p, 0, sizeof p);
    p.algo = algo;
    p.variant = 1;
    p.cell_factor = 0; /* chosen per input */
    p.max_cells = 0;
    p.leaf_size = 32;
    p.min_box = 0;
    return p;
}

int ct_search_init(ct_search **s, const ct_search_params *p)
{
    if (!s)
        return CT_ERR_ARG;
    *s = NULL;
    if (p && (p->algo < 0 || p->algo >= CT_SEARCH_NALGO || p->variant < 0 || p->variant > 1 ||
              !(p->cell_factor >= 0) || !(p->cell_factor <= 1e6) || p->max_pairs < 0 ||
              p->max_cells < 0 || p->leaf_size < 0 || !(p->min_box >= 0) || p->dense < -1 || p->dense > 1 ||
              p->renumber < -1 || p->renumber > 1 || p->renumber_keep < -1))
        return CT_ERR_ARG;
    ct_search *w = calloc(1, sizeof *w);
    if (!w)
        return CT_ERR_NOMEM;
    w->p = p ? *p : ct_search_default_params(CT_SEARCH_BUCKET);
    *s = w;
    return CT_OK;
}

void *cti_search_state(ct_search *s, size_t size, void (*fr)(void *),
                       size_t (*mem)(const void *))
{
    if (s->algo_state && s->algo_free != fr)
        ct_search_reset(s);
    if (!s->algo_state) {
        void *st = calloc(1, size);
        if (!st)
            return NULL;
        s->algo_state = st;
        s->algo_free = fr;
        s->algo_memory = mem;
    }
    return s->algo_state;
}

void ct_search_reset(ct_search *s)
{
    if (s)
        cti_renum_forget(s->rn);
    if (s && s->algo_free && s->algo_state)
        s->algo_free(s->algo_state);
    if (s) {
        s->algo_state = NULL;
        s->algo_free = NULL;
        s->algo_memory = NULL;
    }
}

void ct_search_destroy(ct_search *s)
{
    if (!s)
        return;
    ct_search_reset(s);
    cti_collect_free(&s->col);
    cti_renum_free(s->rn);
    free(s);
}

size_t ct_search_memory(const ct_search *s)
{
    if (!s)
        return 0;
    size_t b = cti_collect_memory(&s->col) + cti_renum_memory(s->rn);
    if (s->algo_memory && s->algo_state)
        b += s->algo_memory(s->algo_state);
    return b;
}

int ct_search_get_info(const ct_search *s, ct_search_info *info)
{
    if (!s || !info)
        return CT_ERR_ARG;
    info->renumbered = s->last_renumbered;
    info->cell_factor = s->last_cell_factor;
    return CT_OK;
}

/* Nodes from which "auto" renumbers a scattered input for the bucket
 * search (see ct_search_run). */
#define CTI_RN_BUCKET_MIN (1 << 19)
/* Nodes from which "auto" renumbers a numbering local in short pieces
 * only (cti_search_pieces), for the bucket and the topological searches. */
#define CTI_RN_PIECES_MIN (1 << 16)
#define CTI_RN_PIECES_TOPO (1 << 17)

int cti_search_small_share(const ct_search_input *in)
{
    return (int64_t)in->nnode > 4 * ((int64_t)in->nsec + 4 * (int64_t)in->nseg);
}

static inline int node_finite(const ct_search_input *in, ct_idx i)
{
    return CTI_FABS(in->x[i]) <= CTI_HUGE && CTI_FABS(in->y[i]) <= CTI_HUGE &&
           CTI_FABS(in->z[i]) <= CTI_HUGE;
}

static int check_input(const ct_search_input *in)
{
    if (!in || in->nnode < 0 || in->nsec < 0 || in->nseg < 0)
        return CT_ERR_ARG;
    if ((in->nnode > 0 && (!in->x || !in->y || !in->z)) || (in->nsec > 0 && !in->sec) ||
        (in->nseg > 0 && (!in->n1 || !in->n2 || !in->n3 || !in->n4)))
        return CT_ERR_ARG;
    if (in->filter != CT_FILTER_HULL && in->filter != CT_FILTER_BOX)
        return CT_ERR_ARG;
    if (!(in->gap >= 0) || !(in->margin >= 0) || !isfinite((double)(in->gap + in->margin)))
        return CT_ERR_ARG;
    /* Every index in range, for every algorithm (one streaming pass). */
    const uint32_t nn = (uint32_t)in->nnode;
    int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad) if (in->nseg > 65536)
    for (ct_idx j = 0; j < in->nseg; j++)
        bad |= ((uint32_t)in->n1[j] >= nn) | ((uint32_t)in->n2[j] >= nn) |
               ((uint32_t)in->n3[j] >= nn) | ((uint32_t)in->n4[j] >= nn);
#pragma omp parallel for schedule(static) reduction(| : bad) if (in->nsec > 65536)
    for (ct_idx i = 0; i < in->nsec; i++)
        bad |= (uint32_t)in->sec[i] >= nn;
    if (bad)
        return CT_ERR_RANGE;
    /* Every node the search reads finite. When the interface uses a fair
     * share of the node arrays, all nodes in one stream first (the common
     * case ends there); otherwise (a small interface in a large model), or
     * when a node is not finite, the nodes used, one by one. */
    if (!cti_search_small_share(in)) {
        const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
        int nonfin = 0;
#pragma omp parallel for simd schedule(static) reduction(| : nonfin) if (in->nnode > 65536)
        for (ct_idx i = 0; i < in->nnode; i++)
            nonfin |= !(CTI_FABS(x[i]) <= CTI_HUGE) | !(CTI_FABS(y[i]) <= CTI_HUGE) |
                      !(CTI_FABS(z[i]) <= CTI_HUGE);
        if (!nonfin)
            return CT_OK;
    }
    int used = 0;
#pragma omp parallel for schedule(static) reduction(| : used) if (in->nsec > 65536)
    for (ct_idx i = 0; i < in->nsec; i++)
        used |= !node_finite(in, in->sec[i]);
#pragma omp parallel for schedule(static) reduction(| : used) if (in->nseg > 16384)
    for (ct_idx j = 0; j < in->nseg; j++)
        used |= !node_finite(in, in->n1[j]) || !node_finite(in, in->n2[j]) ||
                !node_finite(in, in->n3[j]) || !node_finite(in, in->n4[j]);
    return used ? CT_ERR_NONFINITE : CT_OK;
}

int ct_search_run(ct_search *s, const ct_search_input *in, ct_pairs *out)
{
    if (!s || !out)
        return CT_ERR_ARG;
    int rc = check_input(in);
    if (rc)
        return rc;
    s->col.max = cti_search_max_pairs(s);
    s->last_renumbered = 0;
    s->last_cell_factor = 0;
    int (*run)(ct_search *, const ct_search_input *, ct_pairs *) = NULL;
    switch (s->p.algo) {
    case CT_SEARCH_DIRECT: return cti_search_direct(s, in, out);
    case CT_SEARCH_TOPO: run = cti_search_topo; break;
    case CT_SEARCH_BUCKET: run = cti_search_bucket; break;
    case CT_SEARCH_BSP: run = cti_search_bsp; break;
    default: return CT_ERR_ARG;
    }
    /* Scattered numberings: the search on a renumbered copy (whose cost
     * grows with all the nodes: not for a small interface in a large
     * model, unless asked). The bucket has a scattered path of its own,
     * which is faster with 2 threads while the nodes fit the caches
     * (shuffled plates, 2 threads: 110-141 against 122-154 ns/node at
     * 10^5 secondaries, 147-158 against 129-139 at 3 10^5), so "auto"
     * renumbers its input from CTI_RN_BUCKET_MIN nodes only. */
    const int big = s->p.algo != CT_SEARCH_BUCKET || in->nnode >= CTI_RN_BUCKET_MIN;
    /* A numbering local only in short pieces scattered in space (a soup of
     * small parts) gets the bucket's secondary-order query, whose lists
     * then hold segments from everywhere in the arrays, and sends the
     * topological search's hops to random places: the renumbered copy is
     * faster from CTI_RN_PIECES_MIN nodes for the bucket (soup, 1 thread:
     * 1.18x at 10^5 nodes, 1.45x at 3 10^5, 2.6x at 10^6) and from
     * CTI_RN_PIECES_TOPO for the topological search (1.0x at 10^5, 2.1x
     * at 3 10^5, 3.1x at 10^6); the bsp search sorts space itself (1.0x at
     * 10^6). */
    const int pieces =
        (s->p.algo == CT_SEARCH_BUCKET && in->nnode >= CTI_RN_PIECES_MIN) ||
        (s->p.algo == CT_SEARCH_TOPO && in->nnode >= CTI_RN_PIECES_TOPO);
    if (s->p.renumber > 0 ||
        (s->p.renumber == 0 && !cti_search_small_share(in) &&
         ((big && cti_bucket_scattered(in)) || (pieces && cti_search_pieces(in))))) {
        int done = 0;
        rc = cti_search_renumbered(s, in, out, run, &done);
        s->last_renumbered = done && rc == CT_OK;
        if (rc || done)
            return rc;
    }
    return run(s, in, out);
}

/* Every secondary node against every segment: O(nsec * nseg). Threads take
 * blocks of secondary nodes; the collector restores the order. Each thread
 * keeps its fill in a local variable (the shared per-thread lengths sit on
 * one cache line). */
int cti_search_direct(ct_search *s, const ct_search_input *in, ct_pairs *out)
{
    cti_collect *c = &s->col;
    int rc = cti_collect_begin(c, in->nsec);
    if (rc)
        return rc;
    const ct_real d = in->gap + in->margin;
#pragma omp parallel
    {
        int t = cti_thread_id();
        size_t len = c->len[t];
#pragma omp for schedule(dynamic, 64)
        for (ct_idx i = 0; i < in->nsec; i++) {
            ct_idx node = in->sec[i];
            size_t start = len;
            for (ct_idx j = 0; j < in->nseg && !c->err; j++) {
                if (!cti_pair_test_f(in->x, in->y, in->z, node, in->n1[j], in->n2[j], in->n3[j],
                                     in->n4[j], d, in->self, in->filter))
                    continue;
                if (len == c->cap[t]) {
                    c->len[t] = len;
                    if (cti_collect_room(c, t, 1024) != CT_OK)
                        break;
                }
                c->buf[t][len++] = j;
            }
            c->owner[i] = t;
            c->start[i] = (int64_t)start;
            c->count[i] = (ct_idx)(len - start);
        }
        c->len[t] = len;
    }
    return cti_collect_finish(c, in->sec, out);
}
