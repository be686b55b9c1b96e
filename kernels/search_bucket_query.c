/*
 * search_bucket_query.c -- pass 6 of the bucket search (search_bucket.c):
 * the query of the secondary nodes against the segments of their cells, in
 * secondary order (cti_bucket_query_direct) or in cell order
 * (cti_bucket_query_cells), with the candidate test they share.
 */
#include <stdlib.h>

#include "ct_internal.h"
#include "search_bucket_internal.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

/* A batch with fewer free lanes than this is decided before more entries
 * are tested (see bk_cands_batch). */
enum { BK_BATCH_SLACK = 16 };

/* What the candidate test needs. */
typedef struct bk_ctx {
    const ct_real *x, *y, *z;
    const ct_idx *n1, *n2, *n3, *n4;
    const ct_real *box, *srec;
    const float *fbox;
    const ct_idx *start, *ent;
    ct_real d, d2lo, d2hi;
    int self, boxf;
} bk_ctx;

static void bk_ctx_init(bk_ctx *k, const bk_state *st, const ct_search_input *in)
{
    k->x = in->x, k->y = in->y, k->z = in->z;
    k->n1 = in->n1, k->n2 = in->n2, k->n3 = in->n3, k->n4 = in->n4;
    k->box = st->box;
    k->srec = st->srec_on ? st->srec : NULL;
    k->fbox = st->fbox;
    k->start = st->start;
    k->ent = st->ent;
    const ct_real d = in->gap + in->margin, d2 = d * d;
    /* The predicate's sum of squares (CT_FILTER_BOX) is ours: the same
     * expressions on the same minima and maxima, up to the order of a few
     * roundings (at most about 3 ulps relatively, every term being
     * nonnegative, plus underflow). Outside [d2lo, d2hi] our answer is
     * therefore the predicate's; inside, the predicate is asked. */
    k->d = d;
    k->d2hi = d2 + d2 * (16 * CTI_EPS) + (ct_real)1e-30;
    k->d2lo = d2 - d2 * (16 * CTI_EPS) - (ct_real)1e-30;
    k->self = in->self;
    k->boxf = in->filter == CT_FILTER_BOX;
}

/* The float pre-test, branch-free: 1 when node `node` at the float point
 * pv (x y z 0 -x -y -z 0) may pair with segment j (and, for self contact,
 * j is not one of the node's own segments). Rounding is monotone and the
 * float box is rounded outward, so a node that passes the predicate's
 * first step passes it; with AVX, one compare of 8 lanes. */
#if defined(__AVX__)
typedef __m256 bk_fpoint;
static inline bk_fpoint bk_fpoint_of(ct_real X, ct_real Y, ct_real Z)
{
    const float fx = (float)X, fy = (float)Y, fz = (float)Z;
    return _mm256_setr_ps(fx, fy, fz, 0, -fx, -fy, -fz, 0);
}
#else
typedef struct bk_fpoint {
    float x, y, z;
} bk_fpoint;
static inline bk_fpoint bk_fpoint_of(ct_real X, ct_real Y, ct_real Z)
{
    bk_fpoint p = {(float)X, (float)Y, (float)Z};
    return p;
}
#endif

static inline int bk_pretest_box(const bk_ctx *restrict k, bk_fpoint pv, ct_idx j)
{
#if defined(__AVX__)
    const __m256 fb = _mm256_loadu_ps(k->fbox + (size_t)8 * j);
    return !_mm256_movemask_ps(_mm256_cmp_ps(pv, fb, _CMP_LT_OQ));
#else
    const float *restrict f = k->fbox + (size_t)8 * j;
    return !(pv.x < f[0] || pv.y < f[1] || pv.z < f[2] || -pv.x < f[4] || -pv.y < f[5] ||
             -pv.z < f[6]);
#endif
}

/* For self contact: 1 when j is not one of the node's own segments (no
 * branch: about one entry in four is, which a branch would mispredict). */
static inline int bk_not_own(const bk_ctx *restrict k, ct_idx node, ct_idx j)
{
    return !((node == k->n1[j]) | (node == k->n2[j]) | (node == k->n3[j]) |
             (node == k->n4[j]));
}

static inline int bk_pretest(const bk_ctx *restrict k, bk_fpoint pv, ct_idx node, ct_idx j)
{
    int pass = bk_pretest_box(k, pv, j);
    if (k->self)
        pass &= bk_not_own(k, node, j);
    return pass;
}

/* The box filter (CT_FILTER_BOX): node `node` at (X, Y, Z) against the
 * segments of its cell, entries e0 to e1 - 1: writes the accepted ones, in
 * increasing order, to out and returns their number. */
static inline ct_idx bk_cands_box(const bk_ctx *restrict k, ct_idx node, ct_real X, ct_real Y,
                                  ct_real Z, ct_idx e0, ct_idx e1, ct_idx *restrict out)
{
    const ct_idx *restrict ent = k->ent;
    const ct_real d = k->d;
    const bk_fpoint pv = bk_fpoint_of(X, Y, Z);
    ct_idx n = 0;
    for (ct_idx e = e0; e < e1; e++) {
        const ct_idx j = ent[e];
        if (!bk_pretest(k, pv, node, j))
            continue;
        const ct_real *restrict r = k->box + (size_t)6 * j;
        /* The predicate's first step, exactly, then its sum. */
        if (X < r[0] - d || X > r[3] + d || Y < r[1] - d || Y > r[4] + d || Z < r[2] - d ||
            Z > r[5] + d)
            continue;
        ct_real ex = X < r[0] ? r[0] - X : (X > r[3] ? X - r[3] : 0);
        ct_real ey = Y < r[1] ? r[1] - Y : (Y > r[4] ? Y - r[4] : 0);
        ct_real ez = Z < r[2] ? r[2] - Z : (Z > r[5] ? Z - r[5] : 0);
        ct_real e2 = ex * ex + ey * ey + ez * ez;
        if (e2 > k->d2hi)
            continue;
        const ct_real p[3] = {X, Y, Z};
        /* The box's minima and maxima are the corners': the predicate on
         * (lo, hi, lo, hi) is the predicate. */
        const int ok = e2 <= k->d2lo || ct_pair_box_near(p, r, r + 3, r, r + 3, d);
        out[n] = j;
        n += ok != 0;
    }
    return n;
}

/* The hull filter in batches: decide the pending candidates of pb
 * (cti_pair_batch_test) and append the accepted ones, in their order, to
 * w, which has room for all of them. */
static void bk_flush(const bk_ctx *restrict k, const ct_search_input *in,
                     cti_pair_batch *restrict pb, bk_out *restrict w)
{
    cti_pair_batch_decide(pb, in, k->srec, k->d);
    size_t n = w->n;
    ct_idx *restrict on = w->node, *restrict os = w->seg;
    const cti_lane *restrict ok = pb->ok;
    for (int q = 0; q < pb->n; q++) {
        on[n] = pb->node[q];
        os[n] = pb->seg[q];
        n += (size_t)ok[q];
    }
    w->n = n;
    pb->n = 0;
}

/* Where a batch's accepted pairs go: the block output w (secondary order),
 * or, when w is NULL, thread t's collector (cell order; the pairs' secondary
 * positions in bpos, *last the open record). */
typedef struct bk_sink {
    bk_out *w;
    ct_idx *bpos;
    const ct_search_input *in;
    cti_collect *col;
    int t;
    ct_idx last;
} bk_sink;

static void bk_sink_flush(const bk_ctx *restrict k, cti_pair_batch *restrict pb, bk_sink *o)
{
    if (o->w) {
        bk_flush(k, o->in, pb, o->w);
        return;
    }
    size_t len = o->col->len[o->t];
    cti_pair_batch_collect(pb, o->bpos, o->in, k->srec, k->d, o->col, o->t, &len, &o->last);
    o->col->len[o->t] = len;
}

/* As bk_cands_box for the hull filter, in batches: node `node`'s (at
 * secondary position pos) candidates of entries e0 to e1 - 1 that pass the
 * pre-test join the batch pb, which is decided when it is (nearly) full;
 * the sink has room for pb's pending pairs and e1 - e0 more. The loop over
 * the entries takes at most as many as the batch has room for, so it does
 * not test the batch's count per entry, and writes only the segment per
 * entry: the node and its position are filled in after it, once per run of
 * accepted entries. */
static inline void bk_cands_batch(const bk_ctx *restrict k, ct_idx node, ct_idx pos, ct_real X,
                                  ct_real Y, ct_real Z, ct_idx e0, ct_idx e1,
                                  cti_pair_batch *restrict pb, bk_sink *o)
{
    const ct_idx *restrict ent = k->ent;
    const bk_fpoint pv = bk_fpoint_of(X, Y, Z);
    const int self = k->self;
    ct_idx *restrict sg = pb->seg, *restrict nd = pb->node, *restrict bp = o->bpos;
    ct_idx e = e0;
    while (e < e1) {
        int m = pb->n;
        const int m0 = m;
        const ct_idx ec = e1 - e < CTI_PAIR_BATCH - m ? e1 : e + (CTI_PAIR_BATCH - m);
        if (self) {
            for (; e < ec; e++) {
                const ct_idx j = ent[e];
                sg[m] = j;
                m += bk_pretest_box(k, pv, j);
            }
            /* The node's own segments are only among the entries that
             * passed the box (a fraction on a sheet): tested there, their
             * connectivity is read for those alone. */
            int w = m0;
            for (int q = m0; q < m; q++) {
                const ct_idx j = sg[q];
                sg[w] = j;
                w += bk_not_own(k, node, j);
            }
            m = w;
        } else {
            for (; e < ec; e++) {
                const ct_idx j = ent[e];
                sg[m] = j;
                m += bk_pretest_box(k, pv, j);
            }
        }
        for (int q = m0; q < m; q++) {
            nd[q] = node;
            bp[q] = pos;
        }
        pb->n = m;
        /* Decide the batch when it is full, or nearly: a batch left with
         * little room would make the loop above take few entries a time. */
        if (m > CTI_PAIR_BATCH - BK_BATCH_SLACK)
            bk_sink_flush(k, pb, o);
    }
}

/* The most entries a cell may have for its nodes to be queried in twos
 * (bk_cands_batch2's buffer). */
enum { BK_PAIR_MAX = 256 };

/* Two secondaries A and B (at secondary positions pa_ and pb_) of one
 * cell, entries e0 to e1 - 1 (at most BK_PAIR_MAX), into the batch pb as
 * bk_cands_batch would put them node after node: each entry's segment
 * number and float box are read once for both nodes. A's candidates join
 * the batch as they are found (decided whenever it fills), B's are kept in
 * a buffer and join it after A's; the sink has room for pb's pending pairs
 * and twice the entries. */
static inline void bk_cands_batch2(const bk_ctx *restrict k, ct_idx na, ct_idx pa_,
                                   bk_fpoint pa, ct_idx nb_, ct_idx pb_, bk_fpoint pvb,
                                   ct_idx e0, ct_idx e1, cti_pair_batch *restrict pb,
                                   bk_sink *o)
{
    const ct_idx *restrict ent = k->ent;
    ct_idx *restrict sg = pb->seg, *restrict nd = pb->node, *restrict bp = o->bpos;
    ct_idx sb[BK_PAIR_MAX];
    int mb = 0;
    ct_idx e = e0;
    while (e < e1) {
        int m = pb->n;
        const int m0 = m;
        const ct_idx ec = e1 - e < CTI_PAIR_BATCH - m ? e1 : e + (CTI_PAIR_BATCH - m);
        for (; e < ec; e++) {
            const ct_idx j = ent[e];
            sg[m] = j;
            sb[mb] = j;
            m += bk_pretest_box(k, pa, j);
            mb += bk_pretest_box(k, pvb, j);
        }
        if (k->self) {
            int w = m0;
            for (int q = m0; q < m; q++) {
                const ct_idx j = sg[q];
                sg[w] = j;
                w += bk_not_own(k, na, j);
            }
            m = w;
        }
        for (int q = m0; q < m; q++) {
            nd[q] = na;
            bp[q] = pa_;
        }
        pb->n = m;
        if (m > CTI_PAIR_BATCH - BK_BATCH_SLACK)
            bk_sink_flush(k, pb, o);
    }
    if (k->self) {
        int w = 0;
        for (int q = 0; q < mb; q++) {
            const ct_idx j = sb[q];
            sb[w] = j;
            w += bk_not_own(k, nb_, j);
        }
        mb = w;
    }
    for (int q = 0; q < mb;) {
        const int m = pb->n;
        const int c = mb - q < CTI_PAIR_BATCH - m ? mb - q : CTI_PAIR_BATCH - m;
        for (int t = 0; t < c; t++) {
            sg[m + t] = sb[q + t];
            nd[m + t] = nb_;
            bp[m + t] = pb_;
        }
        pb->n = m + c;
        q += c;
        if (pb->n > CTI_PAIR_BATCH - BK_BATCH_SLACK)
            bk_sink_flush(k, pb, o);
    }
}

/* A secondary located in the grid: its node, coordinates and cell. */
typedef struct bk_loc {
    ct_idx node;
    ct_real X, Y, Z;
    ct_idx ic[3];
} bk_loc;

/* bk_locate's answer for a node outside the grid (no error: it pairs with
 * nothing). */
enum { BK_OUTSIDE = 16 };

/* Locate node `node` (a secondary): 0 and *l filled when it is a valid
 * node inside the grid; otherwise BK_ERANGE, BK_ENONFINITE or
 * BK_OUTSIDE. */
static inline int bk_locate(const ct_real *restrict x, const ct_real *restrict y,
                            const ct_real *restrict z, ct_idx node, uint32_t nnode,
                            const bk_grid *g, bk_loc *l)
{
    if ((uint32_t)node >= nnode)
        return BK_ERANGE;
    const ct_real X = x[node], Y = y[node], Z = z[node];
    if (!((X - X) + (Y - Y) + (Z - Z) == 0))
        return BK_ENONFINITE;
    if (X < g->lo[0] || X > g->hi[0] || Y < g->lo[1] || Y > g->hi[1] || Z < g->lo[2] ||
        Z > g->hi[2])
        return BK_OUTSIDE;
    l->node = node;
    l->X = X, l->Y = Y, l->Z = Z;
    l->ic[0] = bk_cell1(X, g->lo[0], g->inv[0], g->n[0] - 1);
    l->ic[1] = bk_cell1(Y, g->lo[1], g->inv[1], g->n[1] - 1);
    l->ic[2] = bk_cell1(Z, g->lo[2], g->inv[2], g->n[2] - 1);
    return 0;
}

/* Pass 6, secondary order: blocks of consecutive positions; block 0 writes
 * into o[0] (the output's arrays), block b > 0 into o[b]. Also checks the
 * secondaries' indices and coordinates. Returns BK_E* bits. */
int cti_bucket_query_direct(const bk_state *st, const ct_search_input *in, const bk_grid *g,
                            int nb, bk_out *o)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict sec = in->sec;
    const ct_idx *restrict start = st->start;
    const ct_idx nx = g->n[0], ny = g->n[1];
    const ct_idx nsec = in->nsec;
    const uint32_t nnode = (uint32_t)in->nnode;
    bk_ctx k;
    bk_ctx_init(&k, st, in);
    const int batch = !k.boxf;
    int err = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(| : err)
    for (int b = 0; b < nb; b++) {
        bk_out w = o[b];
        w.n = 0;
        cti_pair_batch pb;
        ct_idx bpos[CTI_PAIR_BATCH];
        bk_sink sink = {&w, bpos, in, NULL, 0, -1};
        cti_pair_batch_init(&pb);
        ct_idx lo = (ct_idx)((int64_t)nsec * b / nb);
        ct_idx hi = (ct_idx)((int64_t)nsec * (b + 1) / nb);
        /* The next secondary, when the pair test below located it in
         * another cell. */
        int have = 0;
        bk_loc nl = {0, 0, 0, 0, {0, 0, 0}};
        for (ct_idx i = lo; i < hi; i++) {
            bk_loc l;
            if (have) {
                l = nl;
                have = 0;
            } else {
                const int r = bk_locate(x, y, z, sec[i], nnode, g, &l);
                if (r) {
                    err |= r & ~BK_OUTSIDE;
                    continue;
                }
            }
            const ct_idx node = l.node;
            const ct_real X = l.X, Y = l.Y, Z = l.Z;
            const size_t c = ((size_t)l.ic[2] * ny + l.ic[1]) * nx + l.ic[0];
            const ct_idx e0 = start[c], e1 = start[c + 1];
            /* Room for every candidate of this cell and the batch's (twice
             * the cell's when two nodes share it). */
            int two = 0;
            if (batch && i + 1 < hi && e1 - e0 <= BK_PAIR_MAX &&
                !bk_locate(x, y, z, sec[i + 1], nnode, g, &nl)) {
                two = nl.ic[0] == l.ic[0] && nl.ic[1] == l.ic[1] && nl.ic[2] == l.ic[2];
                have = !two;
            }
            const size_t need = w.n + (size_t)pb.n + (size_t)(1 + two) * (size_t)(e1 - e0);
            /* A block that kept more pairs than the limit: so does the
             * whole search (stop before growing). */
            if (need > w.cap && (int64_t)w.n > st->max_pairs) {
                err |= BK_ETOOBIG;
                break;
            }
            if (need > w.cap && cti_bucket_out_grow(&w, need)) {
                err |= BK_ENOMEM;
                break;
            }
            if (two) {
                bk_cands_batch2(&k, node, i, bk_fpoint_of(X, Y, Z), nl.node, i + 1,
                                bk_fpoint_of(nl.X, nl.Y, nl.Z), e0, e1, &pb, &sink);
                i++;
                continue;
            }
            if (batch) {
                bk_cands_batch(&k, node, i, X, Y, Z, e0, e1, &pb, &sink);
                continue;
            }
            ct_idx m = bk_cands_box(&k, node, X, Y, Z, e0, e1, w.seg + w.n);
            for (ct_idx q = 0; q < m; q++)
                w.node[w.n + q] = node;
            w.n += (size_t)m;
        }
        if (pb.n > 0 && !(err & (BK_ENOMEM | BK_ETOOBIG)))
            bk_sink_flush(&k, &pb, &sink);
        o[b] = w;
    }
    return err;
}

/* Pass 6, cell order: the secondaries binned by cell (ord, ordc), blocks of
 * consecutive binned nodes; the collector restores the secondary order. */
int cti_bucket_query_cells(const bk_state *st, const ct_search_input *in, int nb,
                           ct_idx nbinned, cti_collect *col)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict sec = in->sec;
    const ct_idx *restrict start = st->start;
    const ct_idx *restrict ord = st->ord, *restrict ordc = st->ordc;
    const ct_idx *restrict ent = st->ent;
    const float *restrict fbox = st->fbox;
    const ct_real *restrict box = st->box;
    const ct_real *restrict srec = st->srec_on ? st->srec : NULL;
    const ct_idx *restrict n1 = in->n1, *restrict n2 = in->n2, *restrict n3 = in->n3,
                 *restrict n4 = in->n4;
    const int boxf = in->filter == CT_FILTER_BOX, batch = !boxf;
    bk_ctx k;
    bk_ctx_init(&k, st, in);
    int err = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(| : err)
    for (int b = 0; b < nb; b++) {
        const int t = cti_thread_id();
        ct_idx lo = (ct_idx)((int64_t)nbinned * b / nb);
        ct_idx hi = (ct_idx)((int64_t)nbinned * (b + 1) / nb);
        ct_idx pfc = -1;
        cti_pair_batch pb;
        ct_idx bpos[CTI_PAIR_BATCH];
        bk_sink sink = {NULL, bpos, in, col, t, -1};
        cti_pair_batch_init(&pb);
        (void)ent, (void)fbox, (void)box, (void)srec, (void)n1, (void)n2, (void)n3, (void)n4;
        (void)boxf, (void)pfc;
        for (ct_idx q = lo; q < hi; q++) {
#if defined(__GNUC__)
            /* The segment numbers are random too: fetch the records of the
             * cell a few nodes ahead, once per cell. */
            if (q + 8 < hi && ordc[q + 8] != pfc) {
                pfc = ordc[q + 8];
                for (ct_idx e = start[pfc]; e < start[pfc + 1]; e++) {
                    const ct_idx j = ent[e];
                    __builtin_prefetch(fbox + (size_t)8 * j);
                    if (boxf) {
                        __builtin_prefetch(box + (size_t)6 * j);
                    } else if (srec) {
                        __builtin_prefetch(srec + (size_t)12 * j);
                        __builtin_prefetch(srec + (size_t)12 * j + 11);
                    } else {
                        __builtin_prefetch(n1 + j);
                        __builtin_prefetch(n2 + j);
                        __builtin_prefetch(n3 + j);
                        __builtin_prefetch(n4 + j);
                    }
                }
            }
            /* The positions are random: fetch a few nodes ahead. */
            if (q + 16 < hi) {
                ct_idx kn = sec[ord[q + 16]];
                __builtin_prefetch(x + kn);
                __builtin_prefetch(y + kn);
                __builtin_prefetch(z + kn);
            }
            if (q + 32 < hi)
                __builtin_prefetch(sec + ord[q + 32]);
#endif
            const ct_idx i = ord[q], node = sec[i];
            const size_t c = (size_t)ordc[q];
            const ct_idx e0 = start[c], e1 = start[c + 1];
            const size_t s0 = col->len[t];
            /* The cell's next node, if any, is queried with this one. */
            const int two =
                batch && q + 1 < hi && (size_t)ordc[q + 1] == c && e1 - e0 <= BK_PAIR_MAX;
            const size_t need = (size_t)pb.n + (size_t)(1 + two) * (size_t)(e1 - e0);
            if (col->cap[t] - s0 < need && cti_collect_room(col, t, need) != CT_OK) {
                err |= BK_ENOMEM;
                break;
            }
            if (two) {
                const ct_idx i2 = ord[q + 1], n2 = sec[i2];
                bk_cands_batch2(&k, node, i, bk_fpoint_of(x[node], y[node], z[node]), n2, i2,
                                bk_fpoint_of(x[n2], y[n2], z[n2]), e0, e1, &pb, &sink);
                q++;
                continue;
            }
            if (batch) {
                bk_cands_batch(&k, node, i, x[node], y[node], z[node], e0, e1, &pb, &sink);
                continue;
            }
            ct_idx m = bk_cands_box(&k, node, x[node], y[node], z[node], e0, e1, col->buf[t] + s0);
            if (m > 0) { /* a count of 0 is the collector's default */
                col->len[t] = s0 + (size_t)m;
                cti_collect_mark(col, t, i, s0);
            }
        }
        if (pb.n > 0 && !(err & BK_ENOMEM))
            bk_sink_flush(&k, &pb, &sink);
    }
    return err;
}
