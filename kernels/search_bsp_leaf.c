/*
 * search_bsp_leaf.c -- the float tree coordinates of the quick-sort search
 * and its leaf scan (search_bsp.c describes the algorithm; the types are in
 * search_bsp_internal.h).
 */
#include <stdlib.h>

#include "search_bsp_internal.h"

/* Inflated, slightly widened segment boxes in tree coordinates, as records
 * (search_bsp_internal.h: lo, 0, -hi, 0). The bounds
 * are computed as the predicate computes them, then shifted by the origin
 * and rounded outward to float; a NaN bound becomes infinite so such a
 * segment reaches every leaf and the predicate decides. */
/* The coordinates of the corners of segments [j0, j0 + n), n <= 64:
 * c[axis][corner][segment]. */
CTI_NOVEC static void bsp_fetch_corners(const ct_search_input *in, ct_idx j0, int n,
                                        ct_real c[3][4][64])
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *const cn[4] = {in->n1 + j0, in->n2 + j0, in->n3 + j0, in->n4 + j0};
    CTI_NOVEC_LOOP
    for (int q = 0; q < n; q++) {
        for (int e = 0; e < 4; e++) {
            const ct_idx i = cn[e][q];
            c[0][e][q] = x[i];
            c[1][e][q] = y[i];
            c[2][e][q] = z[i];
        }
    }
}

/* The inflated boxes of the segments as records in sb, and their union in
 * *u (the box of every record's two corners). */
static void bsp_seg_boxes(const ct_search_input *in, ct_real d, const double o[3],
                          bsp_f *restrict sb, bsp_box *u)
{
    const ct_real w = 8 * CTI_EPS;
    const ct_idx nseg = in->nseg;
    /* In blocks: the corners are first copied with scalar loads (gathers
     * are slow here), then the bounds of a block are computed in SIMD
     * lanes, axis by axis, and stored as records. The union is taken here,
     * from the block's bounds while they are in cache: a pass of its own
     * read the records back from memory (32 MB at 10^6 segments), 8 ms of
     * the 10^6-node plates' 250 on 1 thread. Min and max are exact, so the
     * union is the same whatever the blocks and the threads (up to the
     * sign of a zero bound, which no comparison sees). */
    enum { B = 64 };
    const ct_idx nblk = (nseg + B - 1) / B;
    bsp_f l0 = (bsp_f)INFINITY, l1 = (bsp_f)INFINITY, l2 = (bsp_f)INFINITY;
    bsp_f h0 = -(bsp_f)INFINITY, h1 = -(bsp_f)INFINITY, h2 = -(bsp_f)INFINITY;
#pragma omp parallel for schedule(static) reduction(min : l0, l1, l2) reduction(max : h0, h1, h2)
    for (ct_idx bi = 0; bi < nblk; bi++) {
        const ct_idx j0 = bi * B;
        const int n = (int)CTI_MIN((ct_idx)B, nseg - j0);
        _Alignas(64) ct_real cr[3][4][B];
        _Alignas(64) bsp_f lo_[3][B], hi_[3][B];
        bsp_fetch_corners(in, j0, n, cr);
        for (int k = 0; k < 3; k++) {
            const double ok = o[k];
            const ct_real *restrict ca = cr[k][0], *restrict cb = cr[k][1];
            const ct_real *restrict ce = cr[k][2], *restrict cf = cr[k][3];
            bsp_f *restrict lk = lo_[k], *restrict hk = hi_[k];
#pragma omp simd
            for (int q = 0; q < n; q++) {
                ct_real a = ca[q], b = cb[q], e = ce[q], f = cf[q];
                ct_real lo = CTI_MIN(CTI_MIN(a, b), CTI_MIN(e, f));
                ct_real hi = CTI_MAX(CTI_MAX(a, b), CTI_MAX(e, f));
                ct_real l = lo - d, h = hi + d;
                l -= w * (CTI_FABS(lo) + d);
                h += w * (CTI_FABS(hi) + d);
                lk[q] = l == l ? bsp_down((double)l - ok) : -(bsp_f)INFINITY;
                hk[q] = -(h == h ? bsp_up((double)h - ok) : (bsp_f)INFINITY);
            }
        }
        bsp_box bu;
        box_empty(&bu);
        for (int q = 0; q < n; q++) {
            bsp_f *r = sb + BSP_REC * (size_t)(j0 + q);
            r[0] = lo_[0][q], r[1] = lo_[1][q], r[2] = lo_[2][q], r[3] = 0;
            r[4] = hi_[0][q], r[5] = hi_[1][q], r[6] = hi_[2][q], r[7] = 0;
            box_add(&bu, lo_[0][q], lo_[1][q], lo_[2][q]);
            box_add(&bu, -hi_[0][q], -hi_[1][q], -hi_[2][q]);
        }
        l0 = bu.lo[0] < l0 ? bu.lo[0] : l0;
        l1 = bu.lo[1] < l1 ? bu.lo[1] : l1;
        l2 = bu.lo[2] < l2 ? bu.lo[2] : l2;
        h0 = bu.hi[0] > h0 ? bu.hi[0] : h0;
        h1 = bu.hi[1] > h1 ? bu.hi[1] : h1;
        h2 = bu.hi[2] > h2 ? bu.hi[2] : h2;
    }
    u->lo[0] = l0, u->lo[1] = l1, u->lo[2] = l2;
    u->hi[0] = h0, u->hi[1] = h1, u->hi[2] = h2;
}

ct_idx cti_bsp_tree_coords(bsp_ctx *c, bsp_box *root)
{
    const ct_search_input *in = c->in;
    bsp_state *st = c->st;
    const ct_idx nsec = in->nsec, nseg = in->nseg;
    /* Tree coordinates are float, relative to an origin inside the model
     * (a corner of the first segment) so that they keep their precision
     * whatever the offset of the model. */
    c->o[0] = c->o[1] = c->o[2] = 0;
    if (nseg > 0) {
        ct_idx a = in->n1[0];
        double q[3] = {(double)in->x[a], (double)in->y[a], (double)in->z[a]};
        if (isfinite(q[0]) && isfinite(q[1]) && isfinite(q[2]))
            c->o[0] = q[0], c->o[1] = q[1], c->o[2] = q[2];
    }
    /* The segment boxes and their union. */
    bsp_box u, nbx[BSP_BLOCKS];
    bsp_seg_boxes(in, c->d, c->o, st->sb, &u);

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
            bsp_f p = (bsp_f)((double)x[k] - c->o[0]), q = (bsp_f)((double)y[k] - c->o[1]);
            bsp_f r = (bsp_f)((double)z[k] - c->o[2]);
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
            bsp_f p = (bsp_f)((double)x[k] - c->o[0]), q = (bsp_f)((double)y[k] - c->o[1]);
            bsp_f r = (bsp_f)((double)z[k] - c->o[2]);
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
    box_empty(root);
    for (int b = 0; b < BSP_BLOCKS; b++) {
        box_add(root, nbx[b].lo[0], nbx[b].lo[1], nbx[b].lo[2]);
        box_add(root, nbx[b].hi[0], nbx[b].hi[1], nbx[b].hi[2]);
    }
    return nkeep;
}

/* Room for a leaf of ns segments in this thread's leaf scratch; 0 (and the
 * error flag) when it cannot grow. */
static int bsp_leaf_room(bsp_ctx *c, bsp_stack *sk, ct_idx ns)
{
    if ((size_t)ns + 8 <= sk->lbcap)
        return 1;
    const size_t cap = ((size_t)ns + (size_t)ns / 2 + 64) & ~(size_t)7;
    const size_t bytes[2] = {6 * cap * sizeof(bsp_f), cap * sizeof(ct_idx)};
    void *q[2];
    if (!cti_bsp_alloc(c, 2, bytes, q))
        return 0;
    ct_free(sk->lb);
    ct_free(sk->lid);
    sk->lb = q[0];
    sk->lid = q[1];
    sk->lbcap = cap;
    return 1;
}

int cti_bsp_alloc(bsp_ctx *c, int n, const size_t *bytes, void **q)
{
    int ok = 1;
    for (int i = 0; i < n; i++)
        ok &= (q[i] = ct_calloc(bytes[i], 1)) != NULL;
    if (ok)
        return 1;
    for (int i = 0; i < n; i++)
        ct_free(q[i]);
#pragma omp atomic write
    c->err = CT_ERR_NOMEM;
    return 0;
}

/* Test every node of [n0, n1) against the ns segments whose boxes are in
 * this thread's leaf scratch (sk->lb, lbcap apart; upper bounds negated as
 * in the records) and numbers in segs, in increasing order. The box test of
 * one node against all segments is a vector loop; the few that pass go to
 * the shared predicate in increasing segment order. A node's candidates go
 * straight into this thread's collector buffer; the shared length is
 * written once per leaf. */
static void bsp_leaf_scan(bsp_ctx *c, bsp_stack *sk, ct_idx n0, ct_idx n1,
                          const ct_idx *restrict segs, ct_idx ns)
{
    const ct_search_input *in = c->in;
    const bsp_state *st = c->st;
    cti_collect *col = c->col;
    const int t = cti_thread_id();
    const size_t w = sk->lbcap;
    bsp_f *restrict l0 = sk->lb, *restrict l1 = l0 + w, *restrict l2 = l1 + w;
    bsp_f *restrict m0 = l2 + w, *restrict m1 = m0 + w, *restrict m2 = m1 + w;
    /* Pad to a multiple of 8 with empty boxes (the capacity is at least
     * ns + 8). */
    const ct_idx ns8 = (ns + 7) & ~(ct_idx)7;
    for (ct_idx q = ns; q < ns8; q++) {
        l0[q] = l1[q] = l2[q] = (bsp_f)INFINITY;
        m0[q] = m1[q] = m2[q] = (bsp_f)INFINITY;
    }
    /* Hull filter: the candidates that pass the box test go through the
     * batch predicate, or, in a dense leaf, its steps run over the leaf's
     * segments (search_bsp_dense.c); the box filter decides them here, one
     * by one. */
    const int batch = in->filter != CT_FILTER_BOX;
    bsp_sample smp;
    smp.n = 0;
    smp.ng = ns8 / 8;
    if (batch && cti_bsp_leaf_is_dense(c, sk, n0, n1, ns, &smp)) {
        cti_bsp_leaf_dense(c, sk, n0, n1, segs, ns, &smp);
        return;
    }
    /* The sampled nodes' masks, read back (bsp_mask_of). */
    const ct_idx nsmp = smp.n;
    const uint8_t *restrict sm = smp.m;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    size_t len = col->len[t];
    cti_pair_batch pb;
    ct_idx bpos[CTI_PAIR_BATCH], last = -1;
    cti_pair_batch_init(&pb);
    /* The leaf's node numbers, in chunks, each gathered in a loop of its
     * own: their loads are independent there and overlap (read one per
     * node in the loop below, each was a cache miss in the way of the
     * next node). */
    enum { CHUNK = 64 };
    ct_idx lnode[CHUNK];
    for (ct_idx k = n0; k < n1; k++) {
        if ((k - n0) % CHUNK == 0) {
            const ct_idx kend = CTI_MIN(n1, k + CHUNK);
            for (ct_idx e = k; e < kend; e++)
                lnode[e - k] = in->sec[st->nid[e]];
        }
        if (len + (size_t)pb.n + (size_t)ns > col->cap[t]) {
            col->len[t] = len;
            if (cti_collect_room(col, t, (size_t)pb.n + (size_t)ns) != CT_OK)
                return;
        }
        ct_idx *restrict buf = col->buf[t];
        const bsp_pt pt = bsp_pt_of(st->nx[k], st->ny[k], st->nz[k]);
        const ct_idx pos = st->nid[k], node = lnode[(k - n0) % CHUNK];
        size_t start = len;
        for (ct_idx q0 = 0; q0 < ns8; q0 += 8) {
            unsigned m = bsp_mask_of(sm, nsmp, ns8 / 8, k - n0, q0 / 8, l0, w, &pt);
            while (m) {
                ct_idx q = q0 + (ct_idx)__builtin_ctz(m);
                m &= m - 1;
                ct_idx j = segs[q];
                if (batch) {
                    if (cti_pair_batch_push(&pb, bpos, in, node, pos, j))
                        cti_pair_batch_collect(&pb, bpos, in, NULL, c->d, col, t, &len, &last);
                    continue;
                }
                if (cti_pair_test_f(x, y, z, node, in->n1[j], in->n2[j], in->n3[j], in->n4[j],
                                    c->d, in->self, in->filter))
                    buf[len++] = j;
            }
        }
        if (!batch && len > start) {
            col->owner[pos] = t;
            col->start[pos] = (int64_t)start;
            col->count[pos] = (ct_idx)(len - start);
        }
    }
    if (pb.n > 0)
        cti_pair_batch_collect(&pb, bpos, in, NULL, c->d, col, t, &len, &last);
    col->len[t] = len;
}

/* Segment record b into slot q of this thread's leaf arrays. */
static inline void bsp_leaf_put(bsp_stack *sk, ct_idx q, const bsp_f *restrict b)
{
    bsp_f *restrict lb = sk->lb;
    const size_t w = sk->lbcap;
    for (int e = 0; e < 3; e++) {
        lb[e * w + (size_t)q] = b[e];
        lb[(3 + e) * w + (size_t)q] = b[4 + e];
    }
}

/* The leaf of a list of numbers: their records are gathered. */
void cti_bsp_leaf(bsp_ctx *c, ct_idx n0, ct_idx n1, const ct_idx *restrict segs, ct_idx ns)
{
    bsp_stack *sk = &c->st->stk[cti_thread_id()];
    if (!bsp_leaf_room(c, sk, ns))
        return;
    const bsp_f *restrict sb = c->st->sb;
    for (ct_idx q = 0; q < ns; q++)
        bsp_leaf_put(sk, q, sb + BSP_REC * (size_t)segs[q]);
    bsp_leaf_scan(c, sk, n0, n1, segs, ns);
}

/* The leaf of a list of records: read with unit stride, numbers from lane 3. */
void cti_bsp_leaf_rec(bsp_ctx *c, ct_idx n0, ct_idx n1, const bsp_f *restrict recs, ct_idx ns)
{
    bsp_stack *sk = &c->st->stk[cti_thread_id()];
    if (!bsp_leaf_room(c, sk, ns))
        return;
    ct_idx *restrict lid = sk->lid;
    for (ct_idx q = 0; q < ns; q++) {
        const bsp_f *b = recs + BSP_REC * (size_t)q;
        bsp_leaf_put(sk, q, b);
        lid[q] = bsp_rec_id(b);
    }
    bsp_leaf_scan(c, sk, n0, n1, lid, ns);
}
