/*
 * search_bsp.c -- the quick-sort search: a binary space partition of the
 * secondary nodes and main segments (DESIGN.md section 5, seed 002 "Quick
 * Sort").
 *
 * A box holds a range of nodes and a sorted list of segments. It is split in
 * two halves at the middle of the nodes' tight bounding box along its
 * longest side (a flat sheet has no extent across itself, so X, Y, Z in turn
 * would waste every third split; the longest side always halves the
 * occupied space). A box above the task cutoff is split at the sampled
 * median of its nodes instead, so that the tasks' work is halved too
 * (bsp_sample_median). Nodes go left (coordinate below the pivot) or right; a
 * segment goes to every half whose nodes' tight box meets the segment's box
 * inflated by gap + margin, so a segment astride the pivot goes to both and
 * one far from every node of a half goes to neither. A box stops splitting
 * (and tests all its couples) when
 *  - it has no node or no segment (nothing to do),
 *  - nodes * segments <= leaf_size * (nodes + segments), i.e. testing all
 *    couples costs about as much as one more split (so leaf_size bounds
 *    the smaller of the two counts at about 2 * leaf_size; measured on the
 *    10^6-node plates, leaf sizes 16 to 64 are within a few percent),
 *  - the nodes' box is smaller than min_box (0 -> gap + margin), below
 *    which every segment in reach is astride every pivot,
 *  - no split along any axis reduces the segment count (segments much
 *    larger than the box), or the depth reaches BSP_MAX_DEPTH.
 *
 * Exactness: the predicate accepts a pair only when the node lies in the
 * segment's inflated box, computed here with the same operations, widened
 * by a few ulps and rounded outward into the tree's float coordinates (see
 * below), and a node always lies in its box's tight box, so the segment
 * reaches the node's leaf. A leaf tests each of its nodes
 * against its segments in increasing order with the shared predicate; each
 * node is in exactly one leaf, so its list is the direct search's list, and
 * the collector writes the canonical order whatever thread did the work.
 * A leaf whose nodes pass the box test of most of its segments decides the
 * predicate's first steps in SIMD lanes over its segments
 * (search_bsp_dense.c); the others batch their candidates
 * (predicate_batch.c). Both give the one-pair predicate's answers.
 *
 * Parallelism: OpenMP tasks. Boxes above a size cutoff partition their
 * nodes in place and write their children's segment lists into a shared
 * arena by an atomic bump (the arena grows and the search is redone if it
 * overflows: only on the first calls); those lists hold segment numbers.
 * Below the cutoff a task runs its whole subtree on one thread with a
 * private stack of lists of segment records (search_bsp_internal.h), which
 * its splits and leaves read with unit stride. Every buffer is kept in the
 * workspace between calls.
 */
#include <stdlib.h>

#include "search_bsp_internal.h"

static void bsp_free(void *p)
{
    bsp_state *st = p;
    if (!st)
        return;
    ct_free(st->nx);
    ct_free(st->ny);
    ct_free(st->nz);
    ct_free(st->nid);
    ct_free(st->sb);
    ct_free(st->arena);
    for (int t = 0; t < st->nthr; t++) {
        ct_free(st->stk[t].a);
        ct_free(st->stk[t].rec);
        ct_free(st->stk[t].lb);
        ct_free(st->stk[t].lid);
        ct_free(st->stk[t].lc);
        ct_free(st->stk[t].lcn);
        ct_free(st->stk[t].lr);
        ct_free(st->stk[t].part);
    }
    free(st->stk);
    free(st);
}

static size_t bsp_memory(const void *p)
{
    const bsp_state *st = p;
    size_t b = st->nodecap * (3 * sizeof(bsp_f) + sizeof(ct_idx)) +
               st->segcap * BSP_REC * sizeof(bsp_f) + st->arenacap * sizeof(ct_idx);
    for (int t = 0; t < st->nthr; t++)
        b += st->stk[t].cap * sizeof(ct_idx) + st->stk[t].rcap * BSP_REC * sizeof(bsp_f) +
             st->stk[t].lbcap * (6 * sizeof(bsp_f) + sizeof(ct_idx)) +
             st->stk[t].lccap * (BSP_LC * sizeof(ct_real) + 4 * sizeof(ct_idx)) +
             st->stk[t].lrcap + st->stk[t].partcap * sizeof(bsp_f);
    return b;
}

/* The workspace's state, created (or taken over from another algorithm)
 * and grown to the sizes of this call. */
static int bsp_prepare(ct_search *s, const ct_search_input *in, bsp_state **out)
{
    bsp_state *st = cti_search_state(s, sizeof *st, bsp_free, bsp_memory);
    if (!st)
        return CT_ERR_NOMEM;
    int nt = cti_num_threads();
    if (nt > st->nthr) {
        bsp_stack *ns = calloc((size_t)nt, sizeof *ns);
        if (!ns)
            return CT_ERR_NOMEM;
        for (int t = 0; t < st->nthr; t++)
            ns[t] = st->stk[t];
        free(st->stk);
        st->stk = ns;
        st->nthr = nt;
    }
    size_t nn = (size_t)in->nsec, ns = (size_t)in->nseg;
    if (nn > st->nodecap || !st->nid) {
        size_t c = st->nodecap;
        void *a = NULL, *b = NULL, *cc = NULL, *dd = NULL;
        int rc = cti_grow(&a, &c, nn, sizeof(bsp_f), 0);
        c = st->nodecap;
        rc |= cti_grow(&b, &c, nn, sizeof(bsp_f), 0);
        c = st->nodecap;
        rc |= cti_grow(&cc, &c, nn, sizeof(bsp_f), 0);
        c = st->nodecap;
        rc |= cti_grow(&dd, &c, nn, sizeof(ct_idx), 0);
        if (rc) {
            ct_free(a);
            ct_free(b);
            ct_free(cc);
            ct_free(dd);
            return CT_ERR_NOMEM;
        }
        ct_free(st->nx);
        ct_free(st->ny);
        ct_free(st->nz);
        ct_free(st->nid);
        st->nx = a;
        st->ny = b;
        st->nz = cc;
        st->nid = dd;
        st->nodecap = c;
    }
    if (ns > st->segcap || !st->sb) {
        size_t c = st->segcap * BSP_REC;
        void *a = st->sb;
        if (cti_grow(&a, &c, BSP_REC * ns, sizeof(bsp_f), 0))
            return CT_ERR_NOMEM;
        st->sb = a;
        st->segcap = c / BSP_REC;
    }
    size_t want = 6 * ns + 4096;
    if (want > st->arenacap || !st->arena) {
        void *a = st->arena;
        if (cti_grow(&a, &st->arenacap, want, sizeof(ct_idx), 0))
            return CT_ERR_NOMEM;
        st->arena = a;
    }
    *out = st;
    return CT_OK;
}

/* Partition nodes [n0, n1) about `mid` on axis `ax` (below: left), and
 * return the split index with the children's tight boxes. With a scratch
 * (part, see cti_bsp_partition) the partition is stable; without one (a
 * box above BSP_PART_MAX nodes), Hoare's, in place. */
static ct_idx bsp_split_nodes(bsp_state *st, ct_idx n0, ct_idx n1, int ax, bsp_f mid,
                              bsp_f *part, bsp_box *bl, bsp_box *br)
{
    bsp_f *restrict nx = st->nx, *restrict ny = st->ny, *restrict nz = st->nz;
    ct_idx *restrict nid = st->nid;
    ct_idx i;
    if (part) {
        i = cti_bsp_partition(nx, ny, nz, nid, n0, n1, ax, mid, part);
    } else {
        const bsp_f *a = ax == 0 ? nx : (ax == 1 ? ny : nz);
        ct_idx j = n1 - 1;
        i = n0;
        for (;;) {
            while (i <= j && a[i] < mid)
                i++;
            while (i <= j && !(a[j] < mid))
                j--;
            if (i >= j)
                break;
            bsp_f tx = nx[i], ty = ny[i], tz = nz[i];
            ct_idx ti = nid[i];
            nx[i] = nx[j]; ny[i] = ny[j]; nz[i] = nz[j]; nid[i] = nid[j];
            nx[j] = tx; ny[j] = ty; nz[j] = tz; nid[j] = ti;
        }
    }
    /* The children's tight boxes in loops of their own, which vectorise
     * (Hoare's loops above cannot). */
    bsp_box_of(nx, ny, nz, n0, i, bl);
    bsp_box_of(nx, ny, nz, i, n1, br);
    return i;
}

/* How many entries ahead a loop over a list of segment numbers asks for
 * the record it will gather (one 32-byte record, half a line, per entry).
 * The lists of the boxes above the task cutoff hold up to all the
 * segments, whose records (32 MB at 10^6) are far from any cache, and the
 * gathers waited for memory one after another: on the 10^6-node plates,
 * 1 thread, the split of such a list took 6-7 ns a segment below the
 * root, 4-5 with the prefetch. */
#define BSP_PREFETCH 32

/* Stable split of a sorted segment list into the lists of the two halves;
 * returns the counts. A list of numbers (segs, written to l and r) gathers
 * one record per segment, prefetched BSP_PREFETCH entries ahead; a list of
 * records (recs, written to lr and rr) is read with unit stride. Either way
 * a segment costs one compare per half (rec_meets) and branch-free
 * appends. */
static void bsp_split_segs(const bsp_f *restrict sb, const ct_idx *restrict segs, ct_idx ns,
                           const bsp_box *bl, const bsp_box *br, ct_idx *restrict l,
                           ct_idx *restrict r, ct_idx *nl, ct_idx *nr)
{
    const bsp_key kl = bsp_key_of(bl), kr = bsp_key_of(br);
    ct_idx a = 0, b = 0;
    for (ct_idx q = 0; q < ns; q++) {
        const ct_idx j = segs[q];
        const bsp_f *rec = sb + BSP_REC * (size_t)j;
        if (q + BSP_PREFETCH < ns)
            __builtin_prefetch(sb + BSP_REC * (size_t)segs[q + BSP_PREFETCH]);
        l[a] = j;
        a += rec_meets(rec, kl);
        r[b] = j;
        b += rec_meets(rec, kr);
    }
    *nl = a;
    *nr = b;
}

static void bsp_split_recs(const bsp_f *restrict recs, ct_idx ns, const bsp_box *bl,
                           const bsp_box *br, bsp_f *restrict lr, bsp_f *restrict rr,
                           ct_idx *nl, ct_idx *nr)
{
    const bsp_key kl = bsp_key_of(bl), kr = bsp_key_of(br);
    ct_idx a = 0, b = 0;
    for (ct_idx q = 0; q < ns; q++) {
        const bsp_f *rec = recs + BSP_REC * (size_t)q;
        memcpy(lr + BSP_REC * (size_t)a, rec, BSP_REC * sizeof *rec);
        a += rec_meets(rec, kl);
        memcpy(rr + BSP_REC * (size_t)b, rec, BSP_REC * sizeof *rec);
        b += rec_meets(rec, kr);
    }
    *nl = a;
    *nr = b;
}

/* The pivot of a box along its longest usable axis, or -1 when the box
 * must be a leaf by the size rules. `tried` marks axes already tried. */
static int bsp_axis(const bsp_ctx *c, const bsp_box *b, int tried, bsp_f *mid)
{
    int ax = -1;
    bsp_f best = 0;
    for (int k = 0; k < 3; k++) {
        bsp_f e = b->hi[k] - b->lo[k];
        if (!(tried & (1 << k)) && e > best) {
            best = e;
            ax = k;
        }
    }
    if (ax < 0 || !(best >= c->minbox))
        return -1;
    bsp_f m = b->lo[ax] + 0.5f * best;
    /* Keep the pivot strictly inside (lo, hi] so both halves get a node. */
    if (!(m > b->lo[ax]) || !(m <= b->hi[ax]))
        m = b->hi[ax];
    *mid = m;
    return ax;
}

static int bsp_is_leaf(const bsp_ctx *c, int64_t nn, int64_t ns, int depth)
{
    return nn * ns <= c->leaf * (nn + ns) || depth >= BSP_MAX_DEPTH;
}

/* A split of a box: nodes [n0, m) go left, [m, n1) right, with their tight
 * boxes and the counts of the two segment lists. */
typedef struct bsp_cut {
    ct_idx m, nl, nr;
    bsp_box bl, br;
} bsp_cut;

/* A box's segment list: numbers (segs, split into l and r) or records
 * (recs, split into lr and rr), each output with room for ns. */
typedef struct bsp_list {
    const ct_idx *segs;
    ct_idx *l, *r;
    const bsp_f *recs;
    bsp_f *lr, *rr;
} bsp_list;

/* The median of a sample of the nodes' coordinates a[n0..n1) (BSP_SAMPLE
 * of them at fixed strides), as the pivot of a box above the task cutoff
 * when it lies inside (lo, hi]: there the split at the middle of the box
 * left one child most of the nodes on a graded mesh (85 % at each of the
 * first levels of the 10^5 mesh), so one thread split a chain of big
 * boxes while the other waited; the median halves the work instead. */
#define BSP_SAMPLE 63
static bsp_f bsp_sample_median(const bsp_f *a, ct_idx n0, ct_idx n1, bsp_f lo, bsp_f hi,
                               bsp_f mid)
{
    const int64_t n = (int64_t)n1 - n0;
    if (n < 2 * BSP_SAMPLE)
        return mid;
    bsp_f s[BSP_SAMPLE];
    for (int i = 0; i < BSP_SAMPLE; i++) {
        const bsp_f v = a[n0 + (ct_idx)(n * (2 * i + 1) / (2 * BSP_SAMPLE))];
        int j = i;
        for (; j > 0 && s[j - 1] > v; j--)
            s[j] = s[j - 1];
        s[j] = v;
    }
    const bsp_f m = s[BSP_SAMPLE / 2];
    return m > lo && m <= hi ? m : mid;
}

/* Split the box of nodes [n0, n1) with its list of ns segments: the axes
 * are tried from the longest until one reduces the segment count (the
 * nodes are partitioned in place, the two lists written). With `median`,
 * the pivot is the nodes' sampled median (bsp_sample_median), else the
 * middle of the box. part: the partition's scratch, NULL above
 * BSP_PART_MAX nodes (bsp_part_of). Returns 1 with the split in *k, or 0
 * when the box must be a leaf. */
static int bsp_split(const bsp_ctx *c, ct_idx n0, ct_idx n1, const bsp_box *box,
                     const bsp_list *li, ct_idx ns, int median, bsp_f *part, bsp_cut *k)
{
    int tried = 0;
    for (;;) {
        bsp_f mid;
        int ax = bsp_axis(c, box, tried, &mid);
        if (ax < 0)
            return 0;
        tried |= 1 << ax;
        if (median) {
            const bsp_f *a = ax == 0 ? c->st->nx : (ax == 1 ? c->st->ny : c->st->nz);
            mid = bsp_sample_median(a, n0, n1, box->lo[ax], box->hi[ax], mid);
        }
        k->m = bsp_split_nodes(c->st, n0, n1, ax, mid, part, &k->bl, &k->br);
        if (li->recs)
            bsp_split_recs(li->recs, ns, &k->bl, &k->br, li->lr, li->rr, &k->nl, &k->nr);
        else
            bsp_split_segs(c->st->sb, li->segs, ns, &k->bl, &k->br, li->l, li->r, &k->nl,
                           &k->nr);
        if (!(k->nl == ns && k->nr == ns))
            return 1; /* else no reduction: try another axis */
    }
}

/* Room for n elements of `size` bytes in the buffer *p of capacity *cap,
 * keeping its first `keep`; 0 (and the error flag) when it cannot grow. */
static int bsp_room(bsp_ctx *c, void **p, size_t *cap, size_t n, size_t size, size_t keep)
{
    if (n <= *cap)
        return 1;
    if (cti_grow(p, cap, n, size, keep) != CT_OK) {
#pragma omp atomic write
        c->err = CT_ERR_NOMEM;
        return 0;
    }
    return 1;
}

/* Room for n numbers in a thread's index scratch. */
static int bsp_stack_room(bsp_ctx *c, bsp_stack *sk, size_t n)
{
    void *p = sk->a;
    const int ok = bsp_room(c, &p, &sk->cap, n, sizeof(ct_idx), 0);
    sk->a = p;
    return ok;
}

/* Room for n records in a thread's record stack, keeping its first `keep`. */
static int bsp_rec_room(bsp_ctx *c, bsp_stack *sk, size_t n, size_t keep)
{
    void *p = sk->rec;
    const int ok = bsp_room(c, &p, &sk->rcap, n, BSP_REC * sizeof(bsp_f), keep);
    sk->rec = p;
    return ok;
}

/* The partition's scratch for a box of nodes [n0, n1) in this thread's
 * stack, or NULL when the box is above BSP_PART_MAX (Hoare's partition in
 * place); *ok = 0 (and the error flag) when it cannot grow. */
static bsp_f *bsp_part_of(bsp_ctx *c, bsp_stack *sk, ct_idx n0, ct_idx n1, int *ok)
{
    *ok = 1;
    const size_t n = (size_t)(n1 - n0);
    if (n > BSP_PART_MAX)
        return NULL;
    void *p = sk->part;
    *ok = bsp_room(c, &p, &sk->partcap, 4 * n, sizeof(bsp_f), 0);
    sk->part = p;
    return *ok ? sk->part : NULL;
}

/* Subtree below the task cutoff, on this thread: the segment list is ns
 * records at offset `off` of this thread's record stack and `base` is the
 * stack's first free record (lists of the enclosing boxes live below it).
 * A split writes the left list at base and the right one at base + ns, so
 * neither moves. */
static void bsp_serial(bsp_ctx *c, bsp_stack *sk, ct_idx n0, ct_idx n1, const bsp_box *box,
                       size_t off, ct_idx ns, size_t base, int depth)
{
    if (n1 <= n0 || ns == 0)
        return;
    if (bsp_is_leaf(c, n1 - n0, ns, depth)) {
        cti_bsp_leaf_rec(c, n0, n1, sk->rec + BSP_REC * off, ns);
        return;
    }
    if (!bsp_rec_room(c, sk, base + 2 * (size_t)ns, base))
        return;
    bsp_f *l = sk->rec + BSP_REC * base;
    bsp_list li = {NULL, NULL, NULL, sk->rec + BSP_REC * off, l, l + BSP_REC * (size_t)ns};
    int ok;
    bsp_f *part = bsp_part_of(c, sk, n0, n1, &ok);
    if (!ok)
        return;
    bsp_cut k;
    if (!bsp_split(c, n0, n1, box, &li, ns, 0, part, &k)) {
        cti_bsp_leaf_rec(c, n0, n1, sk->rec + BSP_REC * off, ns);
        return;
    }
    size_t nb = base + (size_t)ns + (size_t)k.nr;
    bsp_serial(c, sk, n0, k.m, &k.bl, base, k.nl, nb, depth + 1);
    bsp_serial(c, sk, k.m, n1, &k.br, base + (size_t)ns, k.nr, nb, depth + 1);
}

/* Room for n entries in the shared arena, or NULL (and the overflow flag). */
static ct_idx *bsp_arena(bsp_ctx *c, size_t n)
{
    int64_t o;
#pragma omp atomic capture
    {
        o = c->st->arenatop;
        c->st->arenatop += (int64_t)n;
    }
    if ((size_t)o + n > c->st->arenacap) {
#pragma omp atomic write
        c->overflow = 1;
        return NULL;
    }
    return c->st->arena + o;
}

/* A box at or above the task cutoff; its segment list is in the shared
 * arena (read only). */
static void bsp_task(bsp_ctx *c, ct_idx n0, ct_idx n1, bsp_box box, const ct_idx *segs,
                     ct_idx ns, int depth)
{
    if (n1 <= n0 || ns == 0)
        return;
    if ((int64_t)(n1 - n0) + ns < c->task_min) {
        /* Run the subtree here, on its list as records in this thread's
         * record stack. */
        bsp_stack *sk = &c->st->stk[cti_thread_id()];
        if (!bsp_rec_room(c, sk, (size_t)ns, 0))
            return;
        const bsp_f *restrict sb = c->st->sb;
        for (ct_idx q = 0; q < ns; q++) {
            if (q + BSP_PREFETCH < ns)
                __builtin_prefetch(sb + BSP_REC * (size_t)segs[q + BSP_PREFETCH]);
            bsp_rec_put(sk->rec + BSP_REC * (size_t)q, sb + BSP_REC * (size_t)segs[q], segs[q]);
        }
        bsp_serial(c, sk, n0, n1, &box, 0, ns, (size_t)ns, depth);
        return;
    }
    if (bsp_is_leaf(c, n1 - n0, ns, depth)) {
        cti_bsp_leaf(c, n0, n1, segs, ns);
        return;
    }
    /* Split into this thread's stack (no task switch can happen until the
     * lists are copied), then move the exact lists into the shared arena. */
    bsp_stack *sk = &c->st->stk[cti_thread_id()];
    if (!bsp_stack_room(c, sk, 2 * (size_t)ns))
        return;
    bsp_list li = {segs, sk->a, sk->a + ns, NULL, NULL, NULL};
    int ok;
    bsp_f *part = bsp_part_of(c, sk, n0, n1, &ok);
    if (!ok)
        return;
    bsp_cut k;
    if (!bsp_split(c, n0, n1, &box, &li, ns, 1, part, &k)) {
        cti_bsp_leaf(c, n0, n1, segs, ns);
        return;
    }
    const ct_idx m = k.m, nl = k.nl, nr = k.nr;
    const bsp_box bl = k.bl, br = k.br;
    ct_idx *l = bsp_arena(c, (size_t)nl + (size_t)nr);
    if (!l)
        return;
    memcpy(l, sk->a, (size_t)nl * sizeof *l);
    memcpy(l + nl, sk->a + ns, (size_t)nr * sizeof *l);
    const ct_idx *r = l + nl;
    /* No taskwait: a child needs nothing from its parent once its list is
     * in the arena, and the barrier closing the parallel region waits for
     * every task. A taskwait here let a waiting thread run only its own
     * children (libgomp), so on a graded mesh, where one child holds most
     * of the work, the other thread sat idle in it (1.0x on 2 threads). */
#pragma omp task default(none) firstprivate(c, n0, m, bl, l, nl, depth)
    bsp_task(c, n0, m, bl, l, nl, depth + 1);
#pragma omp task default(none) firstprivate(c, m, n1, br, r, nr, depth)
    bsp_task(c, m, n1, br, r, nr, depth + 1);
}

int cti_search_bsp(ct_search *s, const ct_search_input *in, ct_pairs *out)
{
    bsp_state *st;
    int rc = bsp_prepare(s, in, &st);
    if (rc)
        return rc;
    bsp_ctx c;
    c.in = in;
    c.st = st;
    c.col = &s->col;
    c.d = in->gap + in->margin;
    c.minbox = (bsp_f)(s->p.min_box > 0 ? s->p.min_box : (double)c.d);
    c.leaf = s->p.leaf_size > 0 ? s->p.leaf_size : 32;
    c.dense = s->p.dense;
    const ct_idx nsec = in->nsec, nseg = in->nseg;
    const int nt = cti_num_threads();
    /* Subtrees of at most this many nodes + segments run on one thread:
     * about BSP_TASKS_PER_THREAD of them per thread, and none below 512
     * (a floor of 4096 left a 10^3-node search in one task, on one
     * thread: 150 ns/node on 2 threads against 105 with 512). */
    c.task_min =
        CTI_MAX((int64_t)512, ((int64_t)nsec + nseg) / (BSP_TASKS_PER_THREAD * (int64_t)nt));

    /* Tree coordinates (search_bsp_leaf.c): the segment boxes, and the
     * nodes that can pair with their tight box, the root. */
    bsp_box root;
    const ct_idx nkeep = cti_bsp_tree_coords(&c, &root);
    const int64_t sbl = ((int64_t)nseg + BSP_BLOCKS - 1) / BSP_BLOCKS;

    for (;;) {
        rc = cti_collect_begin(c.col, nsec);
        if (rc)
            return rc;
        c.err = 0;
        c.overflow = 0;
        st->arenatop = 0;
        /* The root's segments: those meeting the nodes' box, in order. */
        ct_idx *segs = st->arena;
        ct_idx nroot = 0;
        if (nkeep > 0) {
            const bsp_key kroot = bsp_key_of(&root);
            int64_t *sc = st->blk + BSP_BLOCKS + 1;
#pragma omp parallel for schedule(static)
            for (int b = 0; b < BSP_BLOCKS; b++) {
                int64_t lo = b * sbl, hi = CTI_MIN((int64_t)nseg, lo + sbl), n = 0;
                for (int64_t j = lo; j < hi; j++)
                    n += rec_meets(st->sb + BSP_REC * j, kroot);
                sc[b] = n;
            }
            int64_t r2 = 0;
            for (int b = 0; b < BSP_BLOCKS; b++) {
                int64_t t = sc[b];
                sc[b] = r2;
                r2 += t;
            }
            nroot = (ct_idx)r2;
            if ((size_t)nroot > st->arenacap) {
                void *a = st->arena;
                if (cti_grow(&a, &st->arenacap, 4 * (size_t)nroot, sizeof(ct_idx), 0))
                    return CT_ERR_NOMEM;
                st->arena = a;
                segs = st->arena;
            }
#pragma omp parallel for schedule(static)
            for (int b = 0; b < BSP_BLOCKS; b++) {
                int64_t lo = b * sbl, hi = CTI_MIN((int64_t)nseg, lo + sbl), o = sc[b];
                for (int64_t j = lo; j < hi; j++)
                    if (rec_meets(st->sb + BSP_REC * j, kroot))
                        segs[o++] = (ct_idx)j;
            }
            st->arenatop = nroot;
        }
        if (nkeep > 0 && nroot > 0) {
#pragma omp parallel
#pragma omp single
            bsp_task(&c, 0, nkeep, root, segs, nroot, 0);
        }
        if (c.err)
            return c.err;
        if (c.col->err)
            return c.col->err;
        if (!c.overflow)
            break;
        /* The shared arena was too small: grow it and search again. The
         * node order left by the aborted pass is as good as any. */
        void *a = st->arena;
        size_t need = CTI_MAX((size_t)st->arenatop, 2 * st->arenacap);
        ct_free(a);
        st->arena = NULL;
        st->arenacap = 0;
        a = NULL;
        if (cti_grow(&a, &st->arenacap, need, sizeof(ct_idx), 0))
            return CT_ERR_NOMEM;
        st->arena = a;
    }
    return cti_collect_finish(c.col, in->sec, out);
}
