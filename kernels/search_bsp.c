/*
 * search_bsp.c -- the quick-sort search: a binary space partition of the
 * secondary nodes and main segments (DESIGN.md section 5, seed 002 "Quick
 * Sort").
 *
 * A box holds a range of nodes and a sorted list of segments. It is split in
 * two halves at the middle of the nodes' tight bounding box along its
 * longest side (a flat sheet has no extent across itself, so X, Y, Z in turn
 * would waste every third split; the longest side always halves the
 * occupied space). Nodes go left (coordinate below the pivot) or right; a
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
 *
 * Parallelism: OpenMP tasks. Boxes above a size cutoff partition their
 * nodes in place and write their children's segment lists into a shared
 * arena by an atomic bump (the arena grows and the search is redone if it
 * overflows: only on the first calls). Below the cutoff a task runs its
 * whole subtree on one thread with a private stack of segment lists.
 * Every buffer is kept in the workspace between calls.
 */
#include <stdlib.h>

#include "ct_internal.h"

#define BSP_MAX_DEPTH 96

/*
 * The tree works in float, in coordinates relative to an origin o: a node's
 * tree coordinate is fl32(fl64(x - o)) (rounded to nearest), a segment
 * bound is fl64(lo - o) rounded down to float (upper bounds up). Each step
 * is monotone, so x >= lo implies tree(x) >= tree(lo): a node inside a
 * segment's inflated box is inside it in tree coordinates too, and the
 * partition stays conservative while it moves half the bytes of double.
 * The exact decision is always the shared predicate on the input arrays.
 */
typedef float bsp_f;

static inline bsp_f bsp_down(double v)
{
    bsp_f f = (bsp_f)v;
    return (double)f > v ? nextafterf(f, -INFINITY) : f;
}

static inline bsp_f bsp_up(double v)
{
    bsp_f f = (bsp_f)v;
    return (double)f < v ? nextafterf(f, INFINITY) : f;
}
#define BSP_BLOCKS 64
#ifndef BSP_TASKS_PER_THREAD
#define BSP_TASKS_PER_THREAD 16
#endif

typedef struct bsp_box {
    bsp_f lo[3], hi[3];
} bsp_box;

/* A thread's private stack of segment lists (offsets, not pointers, since
 * it may move when it grows). Padded so two threads never share a line. */
typedef struct bsp_stack {
    ct_idx *a;
    size_t cap;
    bsp_f *lb;       /* a leaf's segment boxes, 6 arrays of lbcap */
    unsigned char *hit; /* a node's box-test results, lbcap + 8 */
    size_t lbcap;
    char pad[64 - 2 * sizeof(size_t) - 3 * sizeof(void *)];
} bsp_stack;

typedef struct bsp_state {
    size_t nodecap, segcap, arenacap;
    bsp_f *nx, *ny, *nz; /* coordinates of the nodes in tree order */
    ct_idx *nid;           /* their positions in in->sec */
    bsp_f *sb;           /* per segment: inflated box lo[3], hi[3] */
    ct_idx *arena;         /* segment lists of the boxes above the cutoff */
    int64_t arenatop;
    int nthr;
    bsp_stack *stk;
    int64_t blk[2 * BSP_BLOCKS + 2];
} bsp_state;

typedef struct bsp_ctx {
    const ct_search_input *in;
    bsp_state *st;
    cti_collect *col;
    ct_real d;
    bsp_f minbox;
    double o[3]; /* origin of the tree coordinates */
    int64_t leaf, task_min;
    int err;      /* CT_ERR_NOMEM when a buffer could not grow */
    int overflow; /* the shared arena was too small */
} bsp_ctx;

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
        ct_free(st->stk[t].lb);
        ct_free(st->stk[t].hit);
    }
    free(st->stk);
    free(st);
}

static size_t bsp_memory(const void *p)
{
    const bsp_state *st = p;
    size_t b = st->nodecap * (3 * sizeof(bsp_f) + sizeof(ct_idx)) +
               st->segcap * 6 * sizeof(bsp_f) + st->arenacap * sizeof(ct_idx);
    for (int t = 0; t < st->nthr; t++)
        b += st->stk[t].cap * sizeof(ct_idx) + st->stk[t].lbcap * (6 * sizeof(bsp_f) + 1);
    return b;
}

/* The workspace's state, created (or taken over from another algorithm)
 * and grown to the sizes of this call. */
static int bsp_prepare(ct_search *s, const ct_search_input *in, bsp_state **out)
{
    if (s->algo_state && s->algo_free != bsp_free)
        ct_search_reset(s);
    bsp_state *st = s->algo_state;
    if (!st) {
        st = calloc(1, sizeof *st);
        if (!st)
            return CT_ERR_NOMEM;
        s->algo_state = st;
        s->algo_free = bsp_free;
        s->algo_memory = bsp_memory;
    }
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
        size_t c = st->segcap * 6;
        void *a = st->sb;
        if (cti_grow(&a, &c, 6 * ns, sizeof(bsp_f), 0))
            return CT_ERR_NOMEM;
        st->sb = a;
        st->segcap = c / 6;
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

static inline int box_meets(const bsp_f *restrict b, const bsp_box *restrict x)
{
    /* Bitwise and: no branch to mispredict. */
    return (b[0] <= x->hi[0]) & (b[3] >= x->lo[0]) & (b[1] <= x->hi[1]) & (b[4] >= x->lo[1]) &
           (b[2] <= x->hi[2]) & (b[5] >= x->lo[2]);
}

static inline void box_empty(bsp_box *b)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = (bsp_f)INFINITY;
        b->hi[k] = -(bsp_f)INFINITY;
    }
}

static inline void box_add(bsp_box *b, bsp_f x, bsp_f y, bsp_f z)
{
    /* NaN compares false and leaves the box alone. */
    b->lo[0] = x < b->lo[0] ? x : b->lo[0];
    b->hi[0] = x > b->hi[0] ? x : b->hi[0];
    b->lo[1] = y < b->lo[1] ? y : b->lo[1];
    b->hi[1] = y > b->hi[1] ? y : b->hi[1];
    b->lo[2] = z < b->lo[2] ? z : b->lo[2];
    b->hi[2] = z > b->hi[2] ? z : b->hi[2];
}

/* Test every node of [n0, n1) against the sorted segment list. The
 * segment boxes are gathered into arrays so the box test of one node
 * against all segments is a vector loop; the few that pass go to the shared
 * predicate in increasing segment order. A node's candidates go straight
 * into this thread's collector buffer; the shared length is written once
 * per leaf. */
static void bsp_leaf(bsp_ctx *c, ct_idx n0, ct_idx n1, const ct_idx *restrict segs,
                     ct_idx ns)
{
    const ct_search_input *in = c->in;
    const bsp_state *st = c->st;
    cti_collect *col = c->col;
    const int t = cti_thread_id();
    bsp_stack *sk = &st->stk[t];
    if ((size_t)ns + 16 > sk->lbcap) {
        size_t cap = (size_t)ns + (size_t)ns / 2 + 64;
        bsp_f *lb = ct_calloc(6 * cap, sizeof *lb);
        unsigned char *hit = ct_calloc(cap + 8, 1);
        if (!lb || !hit) {
            ct_free(lb);
            ct_free(hit);
#pragma omp atomic write
            c->err = CT_ERR_NOMEM;
            return;
        }
        ct_free(sk->lb);
        ct_free(sk->hit);
        sk->lb = lb;
        sk->hit = hit;
        sk->lbcap = cap;
    }
    const size_t w = sk->lbcap;
    bsp_f *restrict l0 = sk->lb, *restrict l1 = l0 + w, *restrict l2 = l1 + w;
    bsp_f *restrict h0 = l2 + w, *restrict h1 = h0 + w, *restrict h2 = h1 + w;
    unsigned char *restrict hit = sk->hit;
    const bsp_f *restrict sb = st->sb;
    for (ct_idx q = 0; q < ns; q++) {
        const bsp_f *b = sb + 6 * (size_t)segs[q];
        l0[q] = b[0];
        l1[q] = b[1];
        l2[q] = b[2];
        h0[q] = b[3];
        h1[q] = b[4];
        h2[q] = b[5];
    }
    /* Pad to a multiple of 16 with empty boxes so the vector loop has no
     * scalar remainder (the capacity is at least ns + 16). */
    const ct_idx ns16 = (ns + 15) & ~(ct_idx)15;
    for (ct_idx q = ns; q < ns16; q++) {
        l0[q] = l1[q] = l2[q] = (bsp_f)INFINITY;
        h0[q] = h1[q] = h2[q] = -(bsp_f)INFINITY;
    }
    for (ct_idx q = ns16; q < ns16 + 8; q++)
        hit[q] = 0;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    size_t len = col->len[t];
    for (ct_idx k = n0; k < n1; k++) {
        if (len + (size_t)ns > col->cap[t]) {
            col->len[t] = len;
            if (cti_collect_room(col, t, (size_t)ns) != CT_OK)
                return;
        }
        ct_idx *restrict buf = col->buf[t];
        const bsp_f px = st->nx[k], py = st->ny[k], pz = st->nz[k];
        const ct_idx pos = st->nid[k], node = in->sec[pos];
#pragma omp simd
        for (ct_idx q = 0; q < ns16; q++)
            hit[q] = (unsigned char)((px >= l0[q]) & (px <= h0[q]) & (py >= l1[q]) &
                                     (py <= h1[q]) & (pz >= l2[q]) & (pz <= h2[q]));
        size_t start = len;
        for (ct_idx q0 = 0; q0 < ns16; q0 += 8) {
            uint64_t m;
            memcpy(&m, hit + q0, sizeof m);
            while (m) {
                ct_idx q = q0 + (ct_idx)(__builtin_ctzll(m) >> 3);
                m &= m - 1;
                ct_idx j = segs[q];
                if (cti_pair_test_f(x, y, z, node, in->n1[j], in->n2[j], in->n3[j], in->n4[j],
                                    c->d, in->self, in->filter))
                    buf[len++] = j;
            }
        }
        if (len > start) {
            col->owner[pos] = t;
            col->start[pos] = (int64_t)start;
            col->count[pos] = (ct_idx)(len - start);
        }
    }
    col->len[t] = len;
}

/* Partition nodes [n0, n1) in place about `mid` on axis `ax` (below: left),
 * and return the split index with the children's tight boxes. */
static ct_idx bsp_split_nodes(bsp_state *st, ct_idx n0, ct_idx n1, int ax, bsp_f mid,
                              bsp_box *bl, bsp_box *br)
{
    bsp_f *restrict nx = st->nx, *restrict ny = st->ny, *restrict nz = st->nz;
    ct_idx *restrict nid = st->nid;
    const bsp_f *a = ax == 0 ? nx : (ax == 1 ? ny : nz);
    /* The children's boxes in locals (registers), not through pointers. */
    bsp_box L, R;
    box_empty(&L);
    box_empty(&R);
    ct_idx i = n0, j = n1 - 1;
    for (;;) {
        while (i <= j && a[i] < mid) {
            box_add(&L, nx[i], ny[i], nz[i]);
            i++;
        }
        while (i <= j && !(a[j] < mid)) {
            box_add(&R, nx[j], ny[j], nz[j]);
            j--;
        }
        if (i >= j)
            break;
        bsp_f tx = nx[i], ty = ny[i], tz = nz[i];
        ct_idx ti = nid[i];
        nx[i] = nx[j]; ny[i] = ny[j]; nz[i] = nz[j]; nid[i] = nid[j];
        nx[j] = tx; ny[j] = ty; nz[j] = tz; nid[j] = ti;
    }
    *bl = L;
    *br = R;
    return i;
}

/* Stable split of a sorted segment list into the lists of the two halves
 * (written to l and r); returns the counts. */
static void bsp_split_segs(const bsp_f *restrict sb, const ct_idx *restrict segs, ct_idx ns,
                           const bsp_box *bl, const bsp_box *br, ct_idx *restrict l,
                           ct_idx *restrict r, ct_idx *nl, ct_idx *nr)
{
    ct_idx a = 0, b = 0;
    for (ct_idx q = 0; q < ns; q++) {
        ct_idx j = segs[q];
        const bsp_f *bx = sb + 6 * (size_t)j;
        l[a] = j;
        a += box_meets(bx, bl);
        r[b] = j;
        b += box_meets(bx, br);
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

/* Subtree below the task cutoff, on this thread: the segment list is at
 * offset `off` of this thread's stack and `base` is the stack's first free
 * entry (lists of the enclosing boxes live below it). */
static void bsp_serial(bsp_ctx *c, bsp_stack *sk, ct_idx n0, ct_idx n1, const bsp_box *box,
                       size_t off, ct_idx ns, size_t base, int depth)
{
    if (n1 <= n0 || ns == 0)
        return;
    if (bsp_is_leaf(c, n1 - n0, ns, depth)) {
        bsp_leaf(c, n0, n1, sk->a + off, ns);
        return;
    }
    if (base + 2 * (size_t)ns > sk->cap) {
        void *p = sk->a;
        if (cti_grow(&p, &sk->cap, base + 2 * (size_t)ns, sizeof(ct_idx), base) != CT_OK) {
#pragma omp atomic write
            c->err = CT_ERR_NOMEM;
            return;
        }
        sk->a = p;
    }
    int tried = 0;
    for (;;) {
        bsp_f mid;
        int ax = bsp_axis(c, box, tried, &mid);
        if (ax < 0)
            break;
        tried |= 1 << ax;
        bsp_box bl, br;
        ct_idx m = bsp_split_nodes(c->st, n0, n1, ax, mid, &bl, &br);
        ct_idx nl, nr;
        ct_idx *l = sk->a + base;
        bsp_split_segs(c->st->sb, sk->a + off, ns, &bl, &br, l, l + ns, &nl, &nr);
        if (nl == ns && nr == ns)
            continue; /* no reduction: try another axis */
        /* Pack the right list after the left one. */
        memmove(l + nl, l + ns, (size_t)nr * sizeof *l);
        size_t nb = base + (size_t)nl + (size_t)nr;
        bsp_serial(c, sk, n0, m, &bl, base, nl, nb, depth + 1);
        bsp_serial(c, sk, m, n1, &br, base + (size_t)nl, nr, nb, depth + 1);
        return;
    }
    bsp_leaf(c, n0, n1, sk->a + off, ns);
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
        /* Run the subtree here: copy the list to this thread's stack. */
        bsp_stack *sk = &c->st->stk[cti_thread_id()];
        if ((size_t)ns > sk->cap) {
            void *p = sk->a;
            if (cti_grow(&p, &sk->cap, (size_t)ns, sizeof(ct_idx), 0) != CT_OK) {
#pragma omp atomic write
                c->err = CT_ERR_NOMEM;
                return;
            }
            sk->a = p;
        }
        memcpy(sk->a, segs, (size_t)ns * sizeof *segs);
        bsp_serial(c, sk, n0, n1, &box, 0, ns, (size_t)ns, depth);
        return;
    }
    if (bsp_is_leaf(c, n1 - n0, ns, depth)) {
        bsp_leaf(c, n0, n1, segs, ns);
        return;
    }
    /* Split into this thread's stack (no task switch can happen until the
     * lists are copied), then move the exact lists into the shared arena. */
    bsp_stack *sk = &c->st->stk[cti_thread_id()];
    if (2 * (size_t)ns > sk->cap) {
        void *p = sk->a;
        if (cti_grow(&p, &sk->cap, 2 * (size_t)ns, sizeof(ct_idx), 0) != CT_OK) {
#pragma omp atomic write
            c->err = CT_ERR_NOMEM;
            return;
        }
        sk->a = p;
    }
    int tried = 0;
    for (;;) {
        bsp_f mid;
        int ax = bsp_axis(c, &box, tried, &mid);
        if (ax < 0)
            break;
        tried |= 1 << ax;
        bsp_box bl, br;
        ct_idx m = bsp_split_nodes(c->st, n0, n1, ax, mid, &bl, &br);
        ct_idx nl, nr;
        bsp_split_segs(c->st->sb, segs, ns, &bl, &br, sk->a, sk->a + ns, &nl, &nr);
        if (nl == ns && nr == ns)
            continue;
        ct_idx *l = bsp_arena(c, (size_t)nl + (size_t)nr);
        if (!l)
            return;
        memcpy(l, sk->a, (size_t)nl * sizeof *l);
        memcpy(l + nl, sk->a + ns, (size_t)nr * sizeof *l);
        const ct_idx *r = l + nl;
#pragma omp task default(none) firstprivate(c, n0, m, bl, l, nl, depth)
        bsp_task(c, n0, m, bl, l, nl, depth + 1);
#pragma omp task default(none) firstprivate(c, m, n1, br, r, nr, depth)
        bsp_task(c, m, n1, br, r, nr, depth + 1);
#pragma omp taskwait
        return;
    }
    bsp_leaf(c, n0, n1, segs, ns);
}

/* Inflated, slightly widened segment boxes in tree coordinates. The bounds
 * are computed as the predicate computes them, then shifted by the origin
 * and rounded outward to float; a NaN bound becomes infinite so such a
 * segment reaches every leaf and the predicate decides. */
static void bsp_seg_boxes(const ct_search_input *in, ct_real d, const double o[3],
                          bsp_f *restrict sb)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_real w = 8 * CTI_EPS;
#pragma omp parallel for schedule(static)
    for (ct_idx j = 0; j < in->nseg; j++) {
        const ct_real *cc[3] = {x, y, z};
        ct_idx i1 = in->n1[j], i2 = in->n2[j], i3 = in->n3[j], i4 = in->n4[j];
        for (int k = 0; k < 3; k++) {
            const ct_real *v = cc[k];
            ct_real a = v[i1], b = v[i2], e = v[i3], f = v[i4];
            ct_real lo = CTI_MIN(CTI_MIN(a, b), CTI_MIN(e, f));
            ct_real hi = CTI_MAX(CTI_MAX(a, b), CTI_MAX(e, f));
            ct_real l = lo - d, h = hi + d;
            l -= w * (CTI_FABS(lo) + d);
            h += w * (CTI_FABS(hi) + d);
            sb[6 * (size_t)j + k] = l == l ? bsp_down((double)l - o[k]) : -(bsp_f)INFINITY;
            sb[6 * (size_t)j + 3 + k] = h == h ? bsp_up((double)h - o[k]) : (bsp_f)INFINITY;
        }
    }
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
    const ct_idx nsec = in->nsec, nseg = in->nseg;
    const int nt = cti_num_threads();
    /* Subtrees of at most this many nodes + segments run on one thread:
     * about BSP_TASKS_PER_THREAD of them per thread. */
    c.task_min =
        CTI_MAX((int64_t)4096, ((int64_t)nsec + nseg) / (BSP_TASKS_PER_THREAD * (int64_t)nt));

    /* Tree coordinates are float, relative to an origin inside the model
     * (a corner of the first segment) so that they keep their precision
     * whatever the offset of the model. */
    c.o[0] = c.o[1] = c.o[2] = 0;
    if (nseg > 0) {
        ct_idx a = in->n1[0];
        double q[3] = {(double)in->x[a], (double)in->y[a], (double)in->z[a]};
        if (isfinite(q[0]) && isfinite(q[1]) && isfinite(q[2]))
            c.o[0] = q[0], c.o[1] = q[1], c.o[2] = q[2];
    }
    bsp_seg_boxes(in, c.d, c.o, st->sb);

    /* The union of the segment boxes (per fixed block, so the result does
     * not depend on the thread count; min and max are exact anyway). */
    bsp_box ub[BSP_BLOCKS], nbx[BSP_BLOCKS];
    const int64_t sbl = ((int64_t)nseg + BSP_BLOCKS - 1) / BSP_BLOCKS;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < BSP_BLOCKS; b++) {
        box_empty(&ub[b]);
        int64_t lo = b * sbl, hi = CTI_MIN((int64_t)nseg, lo + sbl);
        for (int64_t j = lo; j < hi; j++) {
            const bsp_f *q = st->sb + 6 * j;
            box_add(&ub[b], q[0], q[1], q[2]);
            box_add(&ub[b], q[3], q[4], q[5]);
        }
    }
    bsp_box u;
    box_empty(&u);
    for (int b = 0; b < BSP_BLOCKS; b++) {
        box_add(&u, ub[b].lo[0], ub[b].lo[1], ub[b].lo[2]);
        box_add(&u, ub[b].hi[0], ub[b].hi[1], ub[b].hi[2]);
    }

    /* Keep the nodes inside that union (the others cannot pair), in block
     * order: count, prefix, scatter. NaN coordinates fail the test. */
    int64_t *cnt = st->blk;
    const int64_t nbl = ((int64_t)nsec + BSP_BLOCKS - 1) / BSP_BLOCKS;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
#define BSP_INSIDE(p, q, r)                                                                \
    ((p) >= u.lo[0] && (p) <= u.hi[0] && (q) >= u.lo[1] && (q) <= u.hi[1] &&              \
     (r) >= u.lo[2] && (r) <= u.hi[2])
#pragma omp parallel for schedule(static)
    for (int b = 0; b < BSP_BLOCKS; b++) {
        int64_t lo = b * nbl, hi = CTI_MIN((int64_t)nsec, lo + nbl), n = 0;
        for (int64_t i = lo; i < hi; i++) {
            ct_idx k = in->sec[i];
            bsp_f p = (bsp_f)((double)x[k] - c.o[0]), q = (bsp_f)((double)y[k] - c.o[1]);
            bsp_f r = (bsp_f)((double)z[k] - c.o[2]);
            n += BSP_INSIDE(p, q, r);
        }
        cnt[b] = n;
    }
    int64_t run = 0;
    for (int b = 0; b < BSP_BLOCKS; b++) {
        int64_t t = cnt[b];
        cnt[b] = run;
        run += t;
    }
    const ct_idx nkeep = (ct_idx)run;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < BSP_BLOCKS; b++) {
        int64_t lo = b * nbl, hi = CTI_MIN((int64_t)nsec, lo + nbl), o = cnt[b];
        box_empty(&nbx[b]);
        for (int64_t i = lo; i < hi; i++) {
            ct_idx k = in->sec[i];
            bsp_f p = (bsp_f)((double)x[k] - c.o[0]), q = (bsp_f)((double)y[k] - c.o[1]);
            bsp_f r = (bsp_f)((double)z[k] - c.o[2]);
            if (BSP_INSIDE(p, q, r)) {
                st->nx[o] = p;
                st->ny[o] = q;
                st->nz[o] = r;
                st->nid[o] = (ct_idx)i;
                o++;
                box_add(&nbx[b], p, q, r);
            }
        }
    }
#undef BSP_INSIDE
    bsp_box root;
    box_empty(&root);
    for (int b = 0; b < BSP_BLOCKS; b++) {
        box_add(&root, nbx[b].lo[0], nbx[b].lo[1], nbx[b].lo[2]);
        box_add(&root, nbx[b].hi[0], nbx[b].hi[1], nbx[b].hi[2]);
    }

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
            int64_t *sc = st->blk + BSP_BLOCKS + 1;
#pragma omp parallel for schedule(static)
            for (int b = 0; b < BSP_BLOCKS; b++) {
                int64_t lo = b * sbl, hi = CTI_MIN((int64_t)nseg, lo + sbl), n = 0;
                for (int64_t j = lo; j < hi; j++)
                    n += box_meets(st->sb + 6 * j, &root);
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
                    if (box_meets(st->sb + 6 * j, &root))
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
