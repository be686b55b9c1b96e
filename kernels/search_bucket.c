/*
 * search_bucket.c -- the bucket (uniform voxel grid) candidate search.
 *
 * Direction: main SEGMENTS are binned into every cell their box, inflated
 * by d = gap + margin, covers; each secondary node then tests the segments
 * of its own cell. A cell's list is in increasing segment order (a stable
 * counting sort over blocks of consecutive segments) and holds a segment at
 * most once, so a node's accepted segments come out sorted and unique.
 *
 * Passes (all parallel, none allocates once the sizes are stable):
 *  1. per segment: index and finiteness checks, the box of its corners
 *     (exact, kept for CT_FILTER_BOX) and that box inflated by d as the
 *     predicate computes it, rounded outward to float (a 32-byte record for
 *     a one-instruction vector pre-test); the box of all segments
 *     (search_bucket_grid.c);
 *  2. the grid over the main box inflated by d: cells per unit length from
 *     the Radioss sizing times cell_factor, total capped (nodes outside it
 *     can pair with nothing);
 *  3. ranges and count: every segment's cell range, packed, in one vector
 *     loop that also sums the entries (conservative: see below); then per
 *     block of consecutive segments, per cell, the segments covering it
 *     (counters of its own per block), from the packed ranges;
 *  4. offsets: one two-pass parallel scan over the cells;
 *  5. scatter the segment numbers into the cells;
 *  6. query (search_bucket_query.c), in one of two orders chosen per
 *     input by sampling whether consecutive secondaries lie in neighbouring
 *     cells
 *     (cti_bucket_local):
 *     - secondary order (ordered numberings): blocks of consecutive
 *       positions (up to BK_QUERY_BLOCKS per thread, handed out
 *       dynamically); block 0 writes straight into the output and the
 *       other blocks into buffers of their own, copied after it in
 *       parallel: the output is canonical as written, with no collector
 *       and no sort;
 *     - cell order (scattered numberings, where a node's cell, its list and
 *       its segments' records would all be random accesses): the
 *       secondaries counting-sorted by cell, visited with prefetching, and
 *       the collector (pairs.c) restores the secondary order.
 *     Two nodes of one cell that come one after the other (in either
 *     order) read the cell's entries and float boxes once for both.
 *     Per candidate: the float pre-test, then CT_FILTER_HULL: the shared
 *     predicate (cti_pair_test_f); CT_FILTER_BOX: the predicate's first
 *     step exactly, its sum of squares, and the predicate itself
 *     (ct_pair_box_near on the exact box, whose minima and maxima are the
 *     corners') whenever that sum is within rounding of d^2.
 *
 * Conservative cells: the cell of a coordinate is a monotone function of it
 * (subtract, multiply by a positive factor, clamp, truncate), the same for
 * nodes and for the ends of a segment's range, and those ends are the float
 * box, which contains the predicate's own fl(lo - d), fl(hi + d): a node
 * the predicate does not reject by its first step lies in a cell of the
 * range. If the entries would exceed a bound linear in the input (segments
 * far larger than the cells), the grid is coarsened and the count redone,
 * so memory stays O(N).
 *
 * Measured on "plates" 10^6 (1 and 2 threads; see the change's report):
 * versus the previous design (nodes binned, segments scanning cells, pairs
 * counting-sorted by position and each node's list sorted) this removes the
 * node binning, the 96-byte corner records, the pair transposition and the
 * per-node sorts on ordered numberings; the hull filter stays bound by the
 * predicate itself (about 4 calls and 1300 instructions per node).
 */
#include <stdlib.h>

#include "ct_internal.h"
#include "search_bucket_internal.h"

static void bk_free(void *v)
{
    bk_state *st = v;
    if (!st)
        return;
    ct_free(st->box);
    ct_free(st->fbox);
    ct_free(st->rng);
    ct_free(st->srec);
    ct_free(st->xyzw);
    ct_free(st->cnt);
    ct_free(st->start);
    ct_free(st->ent);
    ct_free(st->ncl);
    ct_free(st->ord);
    ct_free(st->ordc);
    ct_free(st->auto_scr);
    for (int b = 0; b < st->maxblk; b++) {
        ct_free(st->buf[b].node);
        ct_free(st->buf[b].seg);
    }
    ct_free(st->buf);
    free(st);
}

static size_t bk_memory(const void *v)
{
    const bk_state *st = v;
    size_t b = sizeof *st + (size_t)st->maxblk * sizeof(bk_out);
    b += st->box_cap * sizeof(ct_real) + st->fbox_cap * sizeof(float);
    b += st->rng_cap * sizeof(uint64_t) + (st->srec_cap + st->xyzw_cap) * sizeof(ct_real);
    b += (st->cnt_cap + st->start_cap + st->ent_cap) * sizeof(ct_idx);
    b += (st->ncl_cap + st->ord_cap + st->ordc_cap ) * sizeof(ct_idx);
    b += st->auto_scr_cap * sizeof(ct_real);
    for (int k = 0; k < st->maxblk; k++)
        b += 2 * st->buf[k].cap * sizeof(ct_idx);
    return b;
}

/* The workspace's state, created on first use and grown to nb blocks. */
static bk_state *bk_get(ct_search *s, int nb)
{
    bk_state *st = cti_search_state(s, sizeof *st, bk_free, bk_memory);
    if (!st)
        return NULL;
    if (nb > st->maxblk) {
        bk_out *nw = ct_calloc((size_t)nb, sizeof *nw);
        if (!nw)
            return NULL;
        for (int b = 0; b < st->maxblk; b++)
            nw[b] = st->buf[b];
        ct_free(st->buf);
        st->buf = nw;
        st->maxblk = nb;
    }
    return st;
}

static int bk_grow(void *pp, size_t *cap, size_t need, size_t size)
{
    void **p = pp;
    return cti_grow(p, cap, need, size, 0);
}

/* Grow a block's output to hold at least `need` pairs, keeping its content;
 * 0, or -1 when out of memory or beyond ct_idx. */
int cti_bucket_out_grow(bk_out *o, size_t need)
{
    if (need <= o->cap)
        return 0;
    size_t ncap = need + need / 2 + 4096;
    if (ncap > (size_t)INT32_MAX)
        ncap = (size_t)INT32_MAX;
    if (need > ncap)
        return -1;
    if (cti_renew_two(&o->node, &o->seg, o->n, ncap) != CT_OK)
        return -1;
    o->cap = ncap;
    return 0;
}

/* A segment's cell range packed in 64 bits: first cell (bits 0-31), spans
 * minus one along x, y, z (10 bits each, from bit 32); BK_SKIP: misses the
 * grid; BK_WIDE: a span too long to pack (the range is recomputed). */
#define BK_SKIP (UINT64_C(1) << 63)
#define BK_WIDE (UINT64_C(1) << 62)

/* Pass 3a: every segment's packed cell range, in one vector loop (the same
 * bk_cell1 as the nodes', on the float box's ends widened to ct_real, which
 * is exact); returns the number of entries the ranges make. */
static int64_t bk_ranges(bk_state *st, const ct_search_input *in, const bk_grid *g)
{
    const ct_idx nseg = in->nseg, nx = g->n[0], ny = g->n[1], nz = g->n[2];
    const ct_real lo0 = g->lo[0], lo1 = g->lo[1], lo2 = g->lo[2];
    const ct_real hi0 = g->hi[0], hi1 = g->hi[1], hi2 = g->hi[2];
    const ct_real iv0 = g->inv[0], iv1 = g->inv[1], iv2 = g->inv[2];
    const float *restrict fbox = st->fbox;
    uint64_t *restrict rng = st->rng;
    int64_t total = 0;
    BK_PAR_FOR_SIMD((schedule(static) reduction(+ : total)))
    for (ct_idx j = 0; j < nseg; j++) {
        const float *restrict f = fbox + (size_t)8 * j;
        const ct_real l0 = f[0], l1 = f[1], l2 = f[2];
        const ct_real h0 = -(ct_real)f[4], h1 = -(ct_real)f[5], h2 = -(ct_real)f[6];
        const int inside = !(h0 < lo0) & !(l0 > hi0) & !(h1 < lo1) & !(l1 > hi1) &
                           !(h2 < lo2) & !(l2 > hi2);
        const ct_idx a0 = bk_cell1(l0, lo0, iv0, nx - 1), b0 = bk_cell1(h0, lo0, iv0, nx - 1);
        const ct_idx a1 = bk_cell1(l1, lo1, iv1, ny - 1), b1 = bk_cell1(h1, lo1, iv1, ny - 1);
        const ct_idx a2 = bk_cell1(l2, lo2, iv2, nz - 1), b2 = bk_cell1(h2, lo2, iv2, nz - 1);
        const ct_idx sx = b0 - a0, sy = b1 - a1, sz = b2 - a2;
        const int narrow = (sx < 1024) & (sy < 1024) & (sz < 1024);
        const uint64_t packed =
            (uint64_t)(((int64_t)a2 * ny + a1) * nx + a0) | ((uint64_t)sx << 32) |
            ((uint64_t)sy << 42) | ((uint64_t)sz << 52);
        rng[j] = !inside ? BK_SKIP : (narrow ? packed : BK_WIDE);
        /* At most ncell, which fits a ct_idx. */
        total += inside ? (int64_t)((sx + 1) * (sy + 1) * (sz + 1)) : 0;
    }
    return total;
}

/* Segment j's range from its packed form r: the first cell (c) and the
 * spans minus one (s); 0 when it misses the grid. */
static inline int bk_unpack(uint64_t r, const float *restrict f, const bk_grid *g,
                            size_t *c, ct_idx s[3])
{
    if (r & BK_SKIP)
        return 0;
    if (!(r & BK_WIDE)) {
        *c = (size_t)(r & 0xffffffffu);
        s[0] = (ct_idx)((r >> 32) & 1023);
        s[1] = (ct_idx)((r >> 42) & 1023);
        s[2] = (ct_idx)((r >> 52) & 1023);
        return 1;
    }
    ct_idx c0[3], c1[3];
    for (int k = 0; k < 3; k++) {
        c0[k] = bk_cell1((ct_real)f[k], g->lo[k], g->inv[k], g->n[k] - 1);
        c1[k] = bk_cell1(-(ct_real)f[4 + k], g->lo[k], g->inv[k], g->n[k] - 1);
        s[k] = c1[k] - c0[k];
    }
    *c = ((size_t)c0[2] * (size_t)g->n[1] + (size_t)c0[1]) * (size_t)g->n[0] + (size_t)c0[0];
    return 1;
}

/* Pass 3b: count, per block of consecutive segments, per cell, the
 * segments covering it (counters of its own per block). */
static void bk_count(bk_state *st, const ct_search_input *in, const bk_grid *g, int nb,
                     size_t stride)
{
    const ct_idx nseg = in->nseg, nx = g->n[0], ny = g->n[1];
    const int64_t ncell = g->ncell;
    const float *restrict fbox = st->fbox;
    const uint64_t *restrict rng = st->rng;
    ct_idx *restrict cnt = st->cnt;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx *restrict cb = cnt + (size_t)b * stride;
        memset(cb, 0, (size_t)ncell * sizeof *cb);
        ct_idx lo = (ct_idx)((int64_t)nseg * b / nb);
        ct_idx hi = (ct_idx)((int64_t)nseg * (b + 1) / nb);
        for (ct_idx j = lo; j < hi; j++) {
            size_t c;
            ct_idx s[3];
            if (!bk_unpack(rng[j], fbox + (size_t)8 * j, g, &c, s))
                continue;
            for (ct_idx iz = 0; iz <= s[2]; iz++)
                for (ct_idx iy = 0; iy <= s[1]; iy++) {
                    ct_idx *restrict row = cb + c + ((size_t)iz * ny + iy) * nx;
                    for (ct_idx ix = 0; ix <= s[0]; ix++)
                        row[ix]++;
                }
        }
    }
}

/* Passes 4 and 5: offsets and scatter. */
static void bk_place(bk_state *st, const ct_search_input *in, const bk_grid *g, int nb,
                     size_t stride)
{
    const ct_idx nseg = in->nseg, nx = g->n[0], ny = g->n[1];
    const float *restrict fbox = st->fbox;
    const uint64_t *restrict rng = st->rng;
    ct_idx *restrict cnt = st->cnt;
    /* Pass 4: offsets. */
    cti_bucket_offsets(cnt, nb, stride, g->ncell, st->start);
    /* Pass 5: scatter; block b's segments go, in increasing order, after
     * those of blocks before it in every cell. */
    ct_idx *restrict ent = st->ent;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx *restrict cb = cnt + (size_t)b * stride;
        ct_idx lo = (ct_idx)((int64_t)nseg * b / nb);
        ct_idx hi = (ct_idx)((int64_t)nseg * (b + 1) / nb);
        for (ct_idx j = lo; j < hi; j++) {
            size_t c;
            ct_idx s[3];
            if (!bk_unpack(rng[j], fbox + (size_t)8 * j, g, &c, s))
                continue;
            for (ct_idx iz = 0; iz <= s[2]; iz++)
                for (ct_idx iy = 0; iy <= s[1]; iy++) {
                    ct_idx *restrict row = cb + c + ((size_t)iz * ny + iy) * nx;
                    for (ct_idx ix = 0; ix <= s[0]; ix++)
                        ent[row[ix]++] = j;
                }
        }
    }
}

/* The cell factor when cell_factor is 0: the one chosen before, unless it
 * is BK_AUTO_EVERY searches old or the input changed (counts, or a side
 * of the region by more than BK_AUTO_DRIFT); then a new choice. */
static int bk_auto(bk_state *st, const ct_search_input *in, const bk_grid *g, int64_t maxc,
                   int64_t limit, int nb)
{
    int fresh = st->auto_f > 0 && st->auto_age < BK_AUTO_EVERY && st->auto_nsec == in->nsec &&
                st->auto_nseg == in->nseg;
    for (int k = 0; k < 3 && fresh; k++) {
        const ct_real len = g->hi[k] - g->lo[k], was = st->auto_len[k];
        fresh = !(len - was > BK_AUTO_DRIFT * was || was - len > BK_AUTO_DRIFT * was);
    }
    if (fresh) {
        st->auto_age++;
        return CT_OK;
    }
    if (bk_grow(&st->auto_scr, &st->auto_scr_cap,
                cti_bucket_auto_scratch(in->nsec, in->nseg) / sizeof(ct_real) + 1,
                sizeof(ct_real)))
        return CT_ERR_NOMEM;
    st->auto_f =
        cti_bucket_auto_factor(in, st->fbox, g->lo, g->hi, maxc, limit, nb, st->auto_scr, NULL);
    st->auto_age = 1;
    st->auto_nsec = in->nsec;
    st->auto_nseg = in->nseg;
    for (int k = 0; k < 3; k++)
        st->auto_len[k] = g->hi[k] - g->lo[k];
    return CT_OK;
}

/* Variant: 1 (default) this file's design, 0 the baseline of
 * search_bucket_v0.c, chosen by ct_search_params.variant. */
int cti_search_bucket_v0(ct_search *s, const ct_search_input *in, ct_pairs *out);

/* Query blocks per thread at most, and secondaries per block at least
 * (secondary order). */
#ifndef BK_QUERY_BLOCKS
#define BK_QUERY_BLOCKS 8
#endif
#define BK_QUERY_MIN 4096

/* Query order: 0 chooses per input (cti_bucket_local), 1 secondary order,
 * 2 cell order. */
#ifndef BK_ORDER
#define BK_ORDER 0
#endif

int cti_search_bucket(ct_search *s, const ct_search_input *in, ct_pairs *out)
{
    if (s->p.variant == 0)
        return cti_search_bucket_v0(s, in, out);
    const int nb = cti_num_threads();
    /* Query blocks: up to BK_QUERY_BLOCKS per thread, handed out
     * dynamically, so a region dense in candidates (a graded mesh's fine
     * corner) does not hold one thread while the others wait; at least
     * BK_QUERY_MIN secondaries each (a small mesh: one block per thread).
     * One thread: one block, which writes the output directly. */
    const int64_t nqw =
        CTI_MAX((int64_t)nb, CTI_MIN((int64_t)BK_QUERY_BLOCKS * nb, in->nsec / BK_QUERY_MIN));
    const int nq = nb > 1 ? (int)nqw : 1;
    bk_state *st = bk_get(s, nq);
    if (!st)
        return CT_ERR_NOMEM;
    st->max_pairs = cti_search_max_pairs(s);
    out->n = 0;
    int rc = ct_pairs_reserve(out, 0);
    if (rc)
        return rc;
    const int boxf = in->filter == CT_FILTER_BOX;
    if ((boxf && bk_grow(&st->box, &st->box_cap, (size_t)6 * (size_t)in->nseg,
                         sizeof(ct_real))) ||
        bk_grow(&st->fbox, &st->fbox_cap, (size_t)8 * (size_t)in->nseg, sizeof(float)) ||
        bk_grow(&st->rng, &st->rng_cap, (size_t)in->nseg, sizeof(uint64_t)))
        return CT_ERR_NOMEM;
    /* Scattered numberings, hull filter: corner records, so that a
     * candidate's corners are two cache lines, not twelve random ones. */
    st->srec_on = !boxf && cti_bucket_scattered(in);
    if (st->srec_on &&
        (bk_grow(&st->srec, &st->srec_cap, (size_t)12 * (size_t)in->nseg, sizeof(ct_real)) ||
         bk_grow(&st->xyzw, &st->xyzw_cap, (size_t)4 * (size_t)in->nnode, sizeof(ct_real))))
        return CT_ERR_NOMEM;
    ct_real mb[6];
    rc = cti_bucket_boxes(in, st->srec_on ? st->xyzw : NULL, boxf ? st->box : NULL, st->fbox,
                          st->srec_on ? st->srec : NULL, mb);
    if (rc)
        return rc;
    if (in->nsec == 0 || in->nseg == 0)
        return cti_bucket_check_sec(in);
    const ct_real d = in->gap + in->margin;
    bk_grid g;
    for (int k = 0; k < 3; k++) {
        /* Nodes outside the main box inflated by d (the predicate's own
         * fl(lo - d), fl(hi + d)) can pair with no segment. */
        g.lo[k] = mb[k] - d;
        g.hi[k] = mb[3 + k] + d;
    }
    int64_t maxc = cti_bucket_max_cells(s->p.max_cells, in);
    /* Entries, and counters per (cell, block), must fit a ct_idx; entries
     * beyond a bound linear in the input coarsen the grid. */
    maxc = CTI_MIN(maxc, (int64_t)(INT32_MAX / 4) / nb);
    const int64_t limit =
        CTI_MIN((int64_t)INT32_MAX - 1, 32 * ((int64_t)in->nsec + in->nseg) + (1 << 20));
    double factor = s->p.cell_factor;
    if (!(factor > 0)) {
        rc = bk_auto(st, in, &g, maxc, limit, nb);
        if (rc)
            return rc;
        factor = st->auto_f;
    }
    s->last_cell_factor = factor;
    for (;;) {
        cti_bucket_size(g.lo, g.hi, in->nseg, factor, maxc, g.n, g.inv);
        g.ncell = (int64_t)g.n[0] * g.n[1] * g.n[2];
        size_t stride = ((size_t)g.ncell + 15) & ~(size_t)15;
        if (bk_grow(&st->cnt, &st->cnt_cap, stride * (size_t)nb, sizeof(ct_idx)) ||
            bk_grow(&st->start, &st->start_cap, (size_t)g.ncell + 1, sizeof(ct_idx)))
            return CT_ERR_NOMEM;
        const int64_t nent = bk_ranges(st, in, &g);
        if (nent <= limit) {
            if (bk_grow(&st->ent, &st->ent_cap, (size_t)nent + 1, sizeof(ct_idx)))
                return CT_ERR_NOMEM;
            bk_count(st, in, &g, nb, stride);
            bk_place(st, in, &g, nb, stride);
            break;
        }
        /* Segments far larger than the cells: a coarser grid. */
        if (g.ncell == 1)
            return CT_ERR_TOOBIG; /* cannot happen: one cell holds nseg */
        maxc = CTI_MAX(1, g.ncell / 8);
    }
    /* Pass 6. Secondary order when it is spatially local (the output is
     * then canonical as written); otherwise cell order and the collector. */
    int order = BK_ORDER;
    if (order == 0)
        order = cti_bucket_local(in, g.lo, g.hi, g.inv, g.n) ? 1 : 2;
    if (order == 2) {
        size_t ns = (size_t)in->nsec;
        size_t stride = ((size_t)g.ncell + 15) & ~(size_t)15;
        if (bk_grow(&st->ncl, &st->ncl_cap, ns, sizeof(ct_idx)) ||
            bk_grow(&st->ord, &st->ord_cap, ns, sizeof(ct_idx)) ||
            bk_grow(&st->ordc, &st->ordc_cap, ns, sizeof(ct_idx)))
            return CT_ERR_NOMEM;
        ct_idx nbinned = 0;
        rc = cti_bucket_bin_nodes(in, g.lo, g.hi, g.inv, g.n, nb, st->cnt, stride, st->ncl,
                                  st->ord, st->ordc, &nbinned);
        if (rc)
            return rc;
        cti_collect *col = &s->col;
        rc = cti_collect_begin(col, in->nsec);
        if (rc)
            return rc;
        int qerr = cti_bucket_query_cells(st, in, nq, nbinned, col);
        if (qerr)
            return col->err ? col->err : CT_ERR_NOMEM;
        rc = cti_collect_finish(col, in->sec, out);
        return rc;
    }
    bk_out *o = st->buf;
    o[0].node = out->node;
    o[0].seg = out->seg;
    o[0].cap = (size_t)out->cap;
    o[0].n = 0;
    int qerr = cti_bucket_query_direct(st, in, &g, nq, o);
    out->node = o[0].node;
    out->seg = o[0].seg;
    out->cap = (ct_idx)o[0].cap;
    out->n = (ct_idx)o[0].n;
    o[0].node = o[0].seg = NULL;
    o[0].cap = o[0].n = 0;
    if (qerr) {
        out->n = 0;
        return (qerr & BK_ERANGE)       ? CT_ERR_RANGE
               : (qerr & BK_ENONFINITE) ? CT_ERR_NONFINITE
               : (qerr & BK_ETOOBIG)    ? CT_ERR_TOOBIG
                                        : CT_ERR_NOMEM;
    }
    /* Concatenate the other blocks after block 0, in parallel. */
    size_t total = out->n;
    for (int b = 1; b < nq; b++)
        total += o[b].n;
    if ((int64_t)total > st->max_pairs)
        return CT_ERR_TOOBIG;
    rc = ct_pairs_reserve(out, (ct_idx)total);
    if (rc)
        return rc;
    size_t off = out->n;
    for (int b = 1; b < nq; b++) {
        o[b].off = off;
        off += o[b].n;
    }
    ct_idx *restrict on = out->node, *restrict os = out->seg;
    /* One team for all the copies; the blocks' ranges are disjoint, so
     * their loops need no barrier between them. */
#pragma omp parallel if (nq > 1)
    for (int b = 1; b < nq; b++) {
        const ct_idx *restrict bn = o[b].node, *restrict bs = o[b].seg;
        const int64_t n = (int64_t)o[b].n;
        const size_t ob = o[b].off;
#pragma omp for schedule(static) nowait
        for (int64_t k = 0; k < n; k++) {
            on[ob + (size_t)k] = bn[k];
            os[ob + (size_t)k] = bs[k];
        }
    }
    out->n = (ct_idx)total;
    return CT_OK;
}
