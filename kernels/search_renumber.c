/*
 * search_renumber.c -- a spatial renumbering of the search input, run
 * around the bucket and bsp searches when the numbering is scattered
 * (ct_search_params.renumber).
 *
 * With a random node numbering every segment corner and every secondary is
 * a random cache line in every pass of a search, and the bucket's counting
 * passes write to random cells. Here, instead:
 *  1. the nodes are counting-sorted by the cell of a grid over their box
 *     (row-major cells of about CTI_RN_CELL nodes; non-finite nodes last):
 *     Q maps an old number to the new one;
 *  2. the coordinates are copied in the new order (by the sort itself);
 *  3. the segments are counting-sorted by the new number of their first
 *     corner and their corners renumbered (the corner order is kept);
 *  4. the secondaries are counting-sorted by their new number;
 *  5. the search runs on that copy, whose numbering is local;
 *  6. its pairs are mapped back: each secondary's list moves to the
 *     secondary's original position, its segments get their original
 *     numbers and are sorted (up to four by a branch-free network, more by
 *     insertion).
 * The passes whose reads or writes land at random places (the scatter of
 * step 1, the corner and secondary lookups of steps 3 and 4, step 6)
 * prefetch the lines of later iterations, so that their misses overlap.
 * The predicate sees the same coordinates in the same corner order, so the
 * result is the canonical pair list of the original input, bit for bit.
 * Every sort is a stable counting sort over contiguous blocks of the input
 * (a stable sort has one result), so nothing depends on the thread count.
 *
 * The copy costs per node 3 numbers (Q, key, rank) and 7 coordinates (the
 * new x, y, z, and x y z 0 packed by the sort), per segment 10 numbers and
 * 4 more for the kept topology, per secondary 4 numbers and 2 offsets, plus
 * the inner pair list and the counting sorts' counters (at most
 * CTI_RN_MAXBLK blocks of one counter per CTI_RN_CELL nodes): O(N), about
 * 260 bytes per secondary on two plates (two mesh nodes and one segment per
 * secondary; measured with contact search).
 *
 * Reuse: steps 1 to 4 depend on the topology (the secondaries and the
 * segments' corners) and, for locality only, on the positions. Explicit
 * dynamics searches the same mesh again every few cycles, and continuum
 * motion keeps neighbours neighbours, so the renumbering made for one
 * search stays local for many. It is kept with a copy of the topology it
 * was made for; a later search whose topology is equal (compared in full,
 * one streaming pass) only copies the coordinates through the kept
 * numbers (the scatter of step 2) and maps its pairs back, for up to
 * ct_search_params.renumber_keep searches (default CTI_RN_KEEP), after
 * which the numbering is made again from the current positions. Any
 * numbering gives the same canonical list, so reuse changes the cost,
 * never the pairs. ct_search_reset forgets the numbering.
 *
 * Cases left to the plain search, which handles or reports them: a
 * secondary listed twice, an empty input.
 */
#include <stdlib.h>

#include "ct_internal.h"
#include "search_bucket_internal.h"

/* Blocks of the counting sorts at most (counters: blocks x keys). */
#define CTI_RN_MAXBLK 8
/* Nodes per cell of the renumbering grid, and per key of the segment sort
 * (new node numbers >> CTI_RN_SHIFT), about. The counters' stride relies on
 * CTI_RN_CELL == 1 << CTI_RN_SHIFT (cells <= nnode >> CTI_RN_SHIFT).
 * Smaller cells make the order of the copy closer to a row-by-row
 * numbering: the search on the copy of shuffled plates 10^6 took 1.07-1.14
 * times the search of the natural numbering with cells of 8 nodes, and
 * 0.99-1.04 with cells of 4 (2 threads, alternating in one process). */
#define CTI_RN_SHIFT 2
#define CTI_RN_CELL (1 << CTI_RN_SHIFT)

/* Searches a renumbering serves, by default, while the topology is the
 * same (ct_search_params.renumber_keep == 0). */
#define CTI_RN_KEEP 64

/* Loops of random reads prefetch this many iterations ahead. */
#define CTI_RN_AHEAD 16
#define CTI_RN_AHEAD_W 32
/* A compare-exchange of two indices, by min and max (no branch). */
#define CTI_RN_IDX_MAX ((ct_idx)INT32_MAX)
#define CTI_RN_CSWAP(a, b)                       \
    do {                                         \
        const ct_idx lo_ = (a) < (b) ? (a) : (b); \
        const ct_idx hi_ = (a) < (b) ? (b) : (a); \
        (a) = lo_;                               \
        (b) = hi_;                               \
    } while (0)
#if defined(__GNUC__)
#define CTI_RN_PREFETCH(p) __builtin_prefetch(p)
#define CTI_RN_PREFETCHW(p) __builtin_prefetch(p, 1)
#else
#define CTI_RN_PREFETCHW(p) ((void)(p))
#define CTI_RN_PREFETCH(p) ((void)(p))
#endif

struct cti_renum {
    size_t cap_node, cap_seg, cap_sec, cap_cnt;
    ct_idx *Q, *key, *rank;       /* per node: old->new number, sort key, sec rank */
    ct_real *x, *y, *z;           /* coordinates in the new order */
    ct_real *w4;                  /* x y z 0 per node, new order (the sort's output) */
    ct_idx *smap, *n1, *n2, *n3, *n4; /* per new segment: old number, corners */
    ct_idx *skey, *c4;            /* per segment: sort key; new corners, packed */
    ct_idx *spos, *sec, *gcnt;    /* per new secondary: old position, new node, pairs */
    int64_t *gstart, *off;        /* inner group starts (nsec + 1); output offsets */
    ct_idx *cnt;                  /* counting sort counters */
    ct_pairs inner;
    int inner_ok;
    /* The topology the numbering was made for (a copy of the input's
     * lists), whether Q .. rank hold that numbering, and how many
     * searches have used it. */
    cti_topo_key tk;
    int valid, uses;
    /* Topological search only: per new node its original number (P), per
     * secondary the history carried to a new numbering (hist). */
    ct_idx *P, *hist;
    size_t cap_P, cap_hist;
};

void cti_renum_forget(cti_renum *r)
{
    if (r)
        r->valid = 0;
}

int cti_renum_uses(const cti_renum *r)
{
    return r && r->valid ? r->uses : 0;
}

void cti_renum_free(cti_renum *r)
{
    if (!r)
        return;
    ct_idx *ip[] = {r->Q,  r->key,  r->rank, r->smap, r->n1, r->n2, r->n3, r->n4,
                    r->skey, r->c4, r->spos, r->sec, r->gcnt, r->cnt, r->P, r->hist};
    for (size_t i = 0; i < sizeof ip / sizeof ip[0]; i++)
        ct_free(ip[i]);
    ct_free(r->x);
    ct_free(r->y);
    ct_free(r->z);
    ct_free(r->w4);
    ct_free(r->gstart);
    ct_free(r->off);
    if (r->inner_ok)
        ct_pairs_destroy(&r->inner);
    cti_topo_key_free(&r->tk);
    free(r);
}

size_t cti_renum_memory(const cti_renum *r)
{
    if (!r)
        return 0;
    return r->cap_node * (3 * sizeof(ct_idx) + 7 * sizeof(ct_real)) +
           r->cap_seg * 10 * sizeof(ct_idx) +
           r->cap_sec * (3 * sizeof(ct_idx) + 2 * sizeof(int64_t)) +
           r->cap_cnt * sizeof(ct_idx) + (size_t)r->inner.cap * 2 * sizeof(ct_idx) +
           cti_topo_key_memory(&r->tk) + (r->cap_P + r->cap_hist) * sizeof(ct_idx);
}

/* Grow the arrays to n nodes, m segments, s secondaries and c counters
 * (contents not kept). */
static int rn_grow(cti_renum *r, size_t n, size_t m, size_t s, size_t c)
{
    int ok = 1;
    if (n > r->cap_node || m > r->cap_seg || s > r->cap_sec)
        r->valid = 0; /* the kept numbering is lost */
    if (n > r->cap_node) {
        ct_idx **ip[] = {&r->Q, &r->key, &r->rank};
        ct_real **rp[] = {&r->x, &r->y, &r->z};
        for (int i = 0; i < 3; i++) {
            ct_free(*ip[i]);
            ok &= (*ip[i] = ct_calloc(n, sizeof(ct_idx))) != NULL;
        }
        for (int i = 0; i < 3; i++) {
            ct_free(*rp[i]);
            ok &= (*rp[i] = ct_calloc(n, sizeof(ct_real))) != NULL;
        }
        ct_free(r->w4);
        ok &= (r->w4 = ct_calloc(4 * n, sizeof(ct_real))) != NULL;
        r->cap_node = ok ? n : 0;
    }
    if (ok && m > r->cap_seg) {
        ct_idx **ip[] = {&r->smap, &r->n1, &r->n2, &r->n3, &r->n4, &r->skey};
        for (int i = 0; i < 6; i++) {
            ct_free(*ip[i]);
            ok &= (*ip[i] = ct_calloc(m, sizeof(ct_idx))) != NULL;
        }
        ct_free(r->c4);
        ok &= (r->c4 = ct_calloc(4 * m, sizeof(ct_idx))) != NULL;
        r->cap_seg = ok ? m : 0;
    }
    if (ok && s > r->cap_sec) {
        ct_idx **ip[] = {&r->spos, &r->sec, &r->gcnt};
        for (int i = 0; i < 3; i++) {
            ct_free(*ip[i]);
            ok &= (*ip[i] = ct_calloc(s, sizeof(ct_idx))) != NULL;
        }
        ct_free(r->gstart);
        ct_free(r->off);
        ok &= (r->gstart = ct_calloc(s + 1, sizeof(int64_t))) != NULL;
        ok &= (r->off = ct_calloc(s + 1, sizeof(int64_t))) != NULL;
        r->cap_sec = ok ? s : 0;
    }
    if (ok && c > r->cap_cnt) {
        ct_free(r->cnt);
        ok &= (r->cnt = ct_calloc(c, sizeof(ct_idx))) != NULL;
        r->cap_cnt = ok ? c : 0;
    }
    if (ok && !r->inner_ok)
        r->inner_ok = ok = ct_pairs_init(&r->inner, 0) == CT_OK;
    return ok ? CT_OK : CT_ERR_NOMEM;
}

/* Items [*lo, *hi) of block b of nb over n items. */
static inline void rn_block(ct_idx n, int nb, int b, ct_idx *lo, ct_idx *hi)
{
    *lo = (ct_idx)((int64_t)n * b / nb);
    *hi = (ct_idx)((int64_t)n * (b + 1) / nb);
}

/* The counting pass of a stable counting sort of the items 0 .. n-1 by
 * key[i] in [0, nkey): nb blocks of consecutive items count in their own
 * counters (nb x stride, stride >= nkey), which then hold each block's
 * first slot per key (cti_bucket_offsets). */
static void rn_count(ct_idx n, const ct_idx *restrict key, int64_t nkey, int nb, size_t stride,
                     ct_idx *restrict cnt)
{
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx *restrict c = cnt + (size_t)b * stride;
        memset(c, 0, (size_t)nkey * sizeof *c);
        ct_idx lo, hi;
        rn_block(n, nb, b, &lo, &hi);
        for (ct_idx i = lo; i < hi; i++)
            c[key[i]]++;
    }
    cti_bucket_offsets(cnt, nb, stride, nkey, NULL);
}

/* The whole sort: ord[k] is the k-th item in key order, ties in index
 * order (a stable sort has one result, whatever nb). */
static void rn_sort(ct_idx n, const ct_idx *restrict key, int64_t nkey, int nb, size_t stride,
                    ct_idx *restrict cnt, ct_idx *restrict ord)
{
    rn_count(n, key, nkey, nb, stride, cnt);
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx *restrict c = cnt + (size_t)b * stride;
        ct_idx lo, hi;
        rn_block(n, nb, b, &lo, &hi);
        for (ct_idx i = lo; i < hi; i++)
            ord[c[key[i]]++] = i;
    }
}

/* The packed coordinates (x y z 0 per node, new order) into the new
 * x, y, z arrays, in sequence. */
static void rn_unpack(cti_renum *r, ct_idx nn)
{
    const ct_real *restrict w4 = r->w4;
    ct_real *restrict X = r->x, *restrict Y = r->y, *restrict Z = r->z;
#pragma omp parallel for schedule(static)
    for (ct_idx k = 0; k < nn; k++) {
        X[k] = w4[4 * (size_t)k];
        Y[k] = w4[4 * (size_t)k + 1];
        Z[k] = w4[4 * (size_t)k + 2];
    }
}

/* Steps 1 and 2: the node order by grid cell, and the coordinates in it;
 * with P, also each new node's original number. */
static void rn_nodes(cti_renum *r, const ct_search_input *in, int nb, size_t stride,
                     ct_idx *restrict P)
{
    const ct_idx nn = in->nnode;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    ct_real u0 = CTI_HUGE, u1 = CTI_HUGE, u2 = CTI_HUGE;
    ct_real v0 = -CTI_HUGE, v1 = -CTI_HUGE, v2 = -CTI_HUGE;
#pragma omp parallel for schedule(static) reduction(min : u0, u1, u2) reduction(max : v0, v1, v2)
    for (ct_idx i = 0; i < nn; i++) {
        ct_real a = x[i], b = y[i], c = z[i];
        if (!(CTI_FABS(a) <= CTI_HUGE && CTI_FABS(b) <= CTI_HUGE && CTI_FABS(c) <= CTI_HUGE))
            continue;
        u0 = a < u0 ? a : u0;
        u1 = b < u1 ? b : u1;
        u2 = c < u2 ? c : u2;
        v0 = a > v0 ? a : v0;
        v1 = b > v1 ? b : v1;
        v2 = c > v2 ? c : v2;
    }
    ct_real lo[3] = {u0, u1, u2}, hi[3] = {v0, v1, v2}, inv[3];
    ct_idx g[3] = {1, 1, 1};
    /* Cells of about CTI_RN_CELL nodes: the nodes of a cell are a few cache
     * lines apart whatever their order. */
    const ct_idx target = CTI_MAX(1, nn / CTI_RN_CELL);
    if (u0 <= v0) /* some finite node */
        cti_bucket_size(lo, hi, target, 1.0, target, g, inv);
    else
        inv[0] = inv[1] = inv[2] = 0, lo[0] = lo[1] = lo[2] = 0;
    const int64_t ncell = (int64_t)g[0] * g[1] * g[2];
    ct_idx *restrict key = r->key;
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < nn; i++) {
        ct_real a = x[i], b = y[i], c = z[i];
        int fin = CTI_FABS(a) <= CTI_HUGE && CTI_FABS(b) <= CTI_HUGE && CTI_FABS(c) <= CTI_HUGE;
        ct_idx ix = bk_cell1(a, lo[0], inv[0], g[0] - 1), iy = bk_cell1(b, lo[1], inv[1], g[1] - 1),
               iz = bk_cell1(c, lo[2], inv[2], g[2] - 1);
        key[i] = fin ? (ct_idx)(((int64_t)iz * g[1] + iy) * g[0] + ix) : (ct_idx)ncell;
    }
    /* The counting sort of rn_sort, whose scatter writes, instead of the
     * order, each node's new number (Q, in sequence) and its coordinates,
     * packed x y z 0 at their new place (one random line per node), which
     * a last pass unpacks in sequence. */
    ct_idx *restrict cnt = r->cnt, *restrict Q = r->Q;
    ct_real *restrict w4 = r->w4;
    rn_count(nn, key, ncell + 1, nb, stride, cnt);
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx *restrict c = cnt + (size_t)b * stride;
        ct_idx lo_, hi_;
        rn_block(nn, nb, b, &lo_, &hi_);
        for (ct_idx i = lo_; i < hi_; i++) {
            if (i + CTI_RN_AHEAD_W < hi_)
                CTI_RN_PREFETCHW(w4 + 4 * (size_t)c[key[i + CTI_RN_AHEAD_W]]);
            const ct_idx k = c[key[i]]++;
            Q[i] = k;
            if (P)
                P[k] = i;
            ct_real *restrict w = w4 + 4 * (size_t)k;
            w[0] = x[i];
            w[1] = y[i];
            w[2] = z[i];
            w[3] = 0;
        }
    }
    rn_unpack(r, nn);
}

/* Step 2 alone, with the kept numbers Q (a search that reuses the
 * numbering): the coordinates scattered to their new places, packed, and
 * unpacked. */
static void rn_coords(cti_renum *r, const ct_search_input *in)
{
    const ct_idx nn = in->nnode;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict Q = r->Q;
    ct_real *restrict w4 = r->w4;
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < nn; i++) {
        if (i + CTI_RN_AHEAD_W < nn)
            CTI_RN_PREFETCHW(w4 + 4 * (size_t)Q[i + CTI_RN_AHEAD_W]);
        ct_real *restrict w = w4 + 4 * (size_t)Q[i];
        w[0] = x[i];
        w[1] = y[i];
        w[2] = z[i];
        w[3] = 0;
    }
    rn_unpack(r, nn);
}

/* Whether the input's topology is the one the kept numbering was made for
 * (one streaming pass). */
static int rn_same_topology(const cti_renum *r, const ct_search_input *in)
{
    return r->valid && cti_topo_key_same(&r->tk, in);
}

/* Steps 3 and 4: segments by the new number of their first corner (to
 * CTI_RN_SHIFT bits), secondaries by their new number (marks in rank[],
 * then one ordered pass). Returns 0 when a secondary is listed twice. */
static int rn_lists(cti_renum *r, const ct_search_input *in, int nb, size_t stride)
{
    const ct_idx nn = in->nnode, ng = in->nseg, ns = in->nsec;
    const ct_idx *restrict Q = r->Q;
    /* The renumbered corners, packed in the old segment order (read in
     * sequence here; the reordering below then reads one 16-byte record
     * per segment, not four arrays). */
    ct_idx *restrict skey = r->skey, *restrict c4 = r->c4;
#pragma omp parallel for schedule(static)
    for (ct_idx j = 0; j < ng; j++) {
        if (j + CTI_RN_AHEAD < ng) {
            const size_t a = (size_t)j + CTI_RN_AHEAD;
            CTI_RN_PREFETCH(Q + in->n1[a]);
            CTI_RN_PREFETCH(Q + in->n2[a]);
            CTI_RN_PREFETCH(Q + in->n3[a]);
            CTI_RN_PREFETCH(Q + in->n4[a]);
        }
        const ct_idx q1 = Q[in->n1[j]];
        skey[j] = q1 >> CTI_RN_SHIFT;
        c4[4 * (size_t)j] = q1;
        c4[4 * (size_t)j + 1] = Q[in->n2[j]];
        c4[4 * (size_t)j + 2] = Q[in->n3[j]];
        c4[4 * (size_t)j + 3] = Q[in->n4[j]];
    }
    rn_sort(ng, skey, ((int64_t)nn >> CTI_RN_SHIFT) + 1, nb, stride, r->cnt, r->smap);
    const ct_idx *restrict smap = r->smap;
    ct_idx *restrict a = r->n1, *restrict b = r->n2, *restrict c = r->n3, *restrict d = r->n4;
#pragma omp parallel for schedule(static)
    for (ct_idx k = 0; k < ng; k++) {
        if (k + CTI_RN_AHEAD < ng)
            CTI_RN_PREFETCH(c4 + 4 * (size_t)smap[k + CTI_RN_AHEAD]);
        const ct_idx *restrict e = c4 + 4 * (size_t)smap[k];
        a[k] = e[0];
        b[k] = e[1];
        c[k] = e[2];
        d[k] = e[3];
    }
    /* Secondaries: rank[new number] = original position (a secondary listed
     * twice leaves fewer marks than secondaries: the marks are counted,
     * which does not depend on which write won). */
    ct_idx *restrict rank = r->rank;
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < nn; i++)
        rank[i] = -1;
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < ns; i++) {
        if (i + 2 * CTI_RN_AHEAD < ns)
            CTI_RN_PREFETCH(Q + in->sec[i + 2 * CTI_RN_AHEAD]);
        if (i + CTI_RN_AHEAD < ns)
            CTI_RN_PREFETCHW(rank + Q[in->sec[i + CTI_RN_AHEAD]]);
        /* Atomic: a twice-listed secondary's two writes may meet. */
#pragma omp atomic write
        rank[Q[in->sec[i]]] = i;
    }
    /* Marks per block of new numbers, their offsets, then the lists in
     * new-number order: sec (new numbers), spos (original positions),
     * kpos (the inverse of spos) and rank (new number -> new position). */
    enum { NB = 64 };
    int64_t bo[NB + 1];
#pragma omp parallel for schedule(static)
    for (int q = 0; q < NB; q++) {
        const ct_idx lo = (ct_idx)((int64_t)nn * q / NB), hi = (ct_idx)((int64_t)nn * (q + 1) / NB);
        int64_t m = 0;
        for (ct_idx i = lo; i < hi; i++)
            m += rank[i] >= 0;
        bo[q + 1] = m;
    }
    bo[0] = 0;
    for (int q = 0; q < NB; q++)
        bo[q + 1] += bo[q];
    if (bo[NB] != ns)
        return 0;
    ct_idx *restrict sec = r->sec, *restrict spos = r->spos, *restrict kpos = r->key;
#pragma omp parallel for schedule(static)
    for (int q = 0; q < NB; q++) {
        const ct_idx lo = (ct_idx)((int64_t)nn * q / NB), hi = (ct_idx)((int64_t)nn * (q + 1) / NB);
        ct_idx k = (ct_idx)bo[q];
        for (ct_idx i = lo; i < hi; i++) {
            ct_idx o = rank[i];
            if (o < 0)
                continue;
            sec[k] = i;
            spos[k] = o;
            kpos[o] = k;
            rank[i] = k++;
        }
    }
    return 1;
}

/* Step 6: the inner pairs (by new secondary position, then new segment)
 * into out in the original canonical order, written in that order. */
static int rn_map_back(cti_renum *r, const ct_search_input *in, ct_pairs *out)
{
    const ct_idx ns = in->nsec;
    ct_pairs *ip = &r->inner;
    const int64_t np = ip->n;
    const ct_idx *restrict rank = r->rank, *restrict kpos = r->key;
    /* Group sizes by new position: every thread counts the groups that
     * start in its share of the pairs (a group is one secondary's run). */
    ct_idx *restrict gcnt = r->gcnt;
    const ct_idx *restrict pn = ip->node;
#pragma omp parallel for schedule(static)
    for (ct_idx k = 0; k < ns; k++)
        gcnt[k] = 0;
#pragma omp parallel
    {
        const int nt = cti_team_size(), t = cti_thread_id();
        int64_t lo = np * t / nt, hi = np * (t + 1) / nt;
        /* Both ends move to the next group boundary, so the shares stay
         * disjoint and cover every group once. */
        while (lo > 0 && lo < np && pn[lo] == pn[lo - 1])
            lo++;
        while (hi > 0 && hi < np && pn[hi] == pn[hi - 1])
            hi++;
        for (int64_t q = lo; q < hi;) {
            int64_t e = q + 1;
            while (e < np && pn[e] == pn[q])
                e++;
            gcnt[rank[pn[q]]] = (ct_idx)(e - q);
            q = e;
        }
    }
    /* Inner group starts (new positions); counts and output offsets by
     * original position (spos's array is free: its scratch). */
    int64_t *restrict gstart = r->gstart, *restrict off = r->off;
    ct_idx *restrict ocnt = r->spos;
    int64_t total = cti_prefix_sum(gcnt, gstart, ns);
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < ns; i++)
        ocnt[i] = gcnt[kpos[i]];
    cti_prefix_sum(ocnt, off, ns);
    if (total != np)
        return CT_ERR_ARG; /* cannot happen: the groups partition the pairs */
    int rc = ct_pairs_reserve(out, (ct_idx)np);
    if (rc)
        return rc;
    /* The segments' original numbers, in the inner order: there the new
     * numbers are local, so smap is read almost in sequence (in the loop
     * below, by original position, each read would be a cache miss). */
    ct_idx *restrict ps = ip->seg;
    const ct_idx *restrict smap = r->smap, *restrict sec = in->sec;
#pragma omp parallel for simd schedule(static)
    for (int64_t q = 0; q < np; q++)
        ps[q] = smap[ps[q]];
    ct_idx *restrict on = out->node, *restrict os = out->seg;
#pragma omp parallel
    {
        /* Each thread's secondaries [lo, hi) write the output [off[lo],
         * off[hi]). */
        const int nt = cti_team_size(), t = cti_thread_id();
        const ct_idx lo = (ct_idx)((int64_t)ns * t / nt), hi = (ct_idx)((int64_t)ns * (t + 1) / nt);
        const int64_t end = off[hi];
        for (ct_idx i = lo; i < hi; i++) {
            /* Two random reads per secondary (its group's start, the
             * group): prefetched ahead, two levels deep, so that they
             * overlap. */
            if (i + 2 * CTI_RN_AHEAD < ns)
                CTI_RN_PREFETCH(gstart + kpos[i + 2 * CTI_RN_AHEAD]);
            if (i + CTI_RN_AHEAD < ns)
                CTI_RN_PREFETCH(ps + gstart[kpos[i + CTI_RN_AHEAD]]);
            const ct_idx n = ocnt[i], node = sec[i];
            if (n == 0)
                continue;
            const int64_t src = gstart[kpos[i]], dst = off[i];
            if (n <= 4 && dst + 4 <= end) {
                /* Up to four segments (most secondaries): sorted by a
                 * network of min and max, without a branch, padded with
                 * the largest number, and all four slots written; those
                 * past the group are this thread's next groups' slots,
                 * written again when their turn comes. (An insertion
                 * sort's branches were mispredicted about once per
                 * segment.) */
                ct_idx v[4];
                for (int q = 0; q < 4; q++) {
                    /* (A load inside the group in every case, so that
                     * the choice needs no branch.) */
                    const ct_idx e = ps[src + (q < n ? q : n - 1)];
                    v[q] = q < n ? e : CTI_RN_IDX_MAX;
                }
                CTI_RN_CSWAP(v[0], v[1]);
                CTI_RN_CSWAP(v[2], v[3]);
                CTI_RN_CSWAP(v[0], v[2]);
                CTI_RN_CSWAP(v[1], v[3]);
                CTI_RN_CSWAP(v[1], v[2]);
                for (int q = 0; q < 4; q++) {
                    os[dst + q] = v[q];
                    on[dst + q] = node;
                }
                continue;
            }
            for (ct_idx q = 0; q < n; q++) {
                /* Insertion by original segment number. */
                ct_idx sg = ps[src + q], w = q;
                while (w > 0 && os[dst + w - 1] > sg) {
                    os[dst + w] = os[dst + w - 1];
                    w--;
                }
                os[dst + w] = sg;
                on[dst + q] = node;
            }
        }
    }
    out->n = (ct_idx)np;
    return CT_OK;
}

int cti_search_renumbered(ct_search *s, const ct_search_input *in, ct_pairs *out,
                          int (*run)(ct_search *, const ct_search_input *, ct_pairs *),
                          int *done)
{
    *done = 0;
    /* (ct_search_run has checked every index.) */
    if (in->nnode == 0 || in->nsec == 0 || in->nseg == 0)
        return CT_OK;
    if (!s->rn && !(s->rn = calloc(1, sizeof *s->rn)))
        return CT_ERR_NOMEM;
    cti_renum *r = s->rn;
    const int nb = CTI_MIN(cti_num_threads(), CTI_RN_MAXBLK);
    /* Keys: grid cells (at most nnode / CTI_RN_CELL, and a key for the
     * non-finite nodes) and first corners >> CTI_RN_SHIFT. */
    const size_t stride = ((size_t)(in->nnode >> CTI_RN_SHIFT) + 2 + 15) & ~(size_t)15;
    int rc = rn_grow(r, (size_t)in->nnode, (size_t)in->nseg, (size_t)in->nsec,
                     stride * (size_t)nb);
    if (rc)
        return rc;
    const int keep = s->p.renumber_keep == 0 ? CTI_RN_KEEP : s->p.renumber_keep;
    /* The topological search needs the original numbers (its ties) and,
     * when a numbering is made again for the same topology, its history
     * carried over (see below): it always keeps the topology. */
    const int topo = s->p.algo == CT_SEARCH_TOPO;
    if (topo && (cti_grow((void **)&r->P, &r->cap_P, (size_t)in->nnode, sizeof(ct_idx), 0) ||
                 cti_grow((void **)&r->hist, &r->cap_hist, (size_t)in->nsec, sizeof(ct_idx), 0)))
        return CT_ERR_NOMEM;
    const int same = rn_same_topology(r, in);
    /* The copy's input: its topology arrays here (their contents are the
     * kept numbering's until rn_nodes and rn_lists), its coordinates below. */
    ct_search_input in2 = *in;
    in2.sec = r->sec;
    in2.n1 = r->n1;
    in2.n2 = r->n2;
    in2.n3 = r->n3;
    in2.n4 = r->n4;
    if (keep > 0 && r->uses < keep && same) {
        rn_coords(r, in);
        r->uses++;
    } else {
        /* The old numbering's copy, for the history's export: the key
         * (r->key, original position -> position in the copy) and P are
         * intact until rn_nodes. */
        const int carry =
            topo && same && cti_topo_history_export(s, &in2, r->key, r->P, r->hist);
        r->valid = 0;
        rn_nodes(r, in, nb, stride, topo ? r->P : NULL);
        if (!rn_lists(r, in, nb, stride)) {
            if (topo)
                cti_topo_forget(s);
            return CT_OK; /* a secondary listed twice: the plain search */
        }
        if (keep > 0 || topo) {
            rc = cti_topo_key_store(&r->tk, in);
            if (rc)
                return rc;
            r->valid = 1;
        }
        r->uses = 1;
        if (topo) {
            if (carry)
                rc = cti_topo_history_import(s, &in2, r->key, r->Q, r->hist);
            else
                cti_topo_forget(s);
            if (rc)
                return rc;
        }
    }
    in2.x = r->x;
    in2.y = r->y;
    in2.z = r->z;
    *done = 1;
    s->tie = topo ? r->P : NULL;
    rc = run(s, &in2, &r->inner);
    s->tie = NULL;
    if (rc) {
        out->n = 0;
        return rc;
    }
    return rn_map_back(r, in, out);
}
