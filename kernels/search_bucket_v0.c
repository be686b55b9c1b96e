/*
 * search_bucket_v0.c -- the baseline bucket search (variant 0, the first
 * design), kept for comparison with the default (search_bucket.c): nodes
 * binned into cells, segments scanning the cells their inflated box covers,
 * pairs transposed to the canonical order by a counting sort on the
 * position and a sort of each node's few segments. Selected in
 * search_bucket.c when ct_search_params.variant is 0, or called directly (tests).
 *
 * Direction chosen: secondary nodes are counting-sorted into the cells
 * (one entry per node), and each main segment scans the cells its box,
 * inflated by gap + margin, covers. The alternative (segments binned into
 * every cell they cover, nodes looking up their own cell) writes one entry
 * per segment and covered cell: on the plates case with the Radioss sizing
 * (cell about 1.33 segment lengths, inflated box 2 long) that is about 6
 * entries per segment against 1 per node here, for the same number of box
 * tests, and the cost of turning segment-major pairs into node-major output
 * (one counting sort of the pairs by secondary position) is below the cost
 * of writing and reading those extra entries (reasoned, not measured: only
 * this direction was built). On the plates case (10^6 nodes, 3 accepted
 * pairs per node) the time is dominated by the exact predicate (about
 * 20 ns a call) and, with a shuffled numbering, by memory latency.
 *
 * Passes (all parallel, none allocates once the sizes are stable):
 *  1. bounding boxes of the secondaries and of the main segments, with a
 *     finiteness and index-range check folded in;
 *  2. the grid: the secondaries' box intersected with the main box inflated
 *     by d = gap + margin, cells per unit length from the Radioss sizing,
 *     total capped;
 *  3. nodes into cells: count per (cell, block), prefix sum, scatter of the
 *     node coordinates into cell-ordered arrays (a stable counting sort);
 *  3b. segments counting-sorted by the cell of their box centre, so the
 *     scan below runs in spatial order whatever the numbering;
 *  4. segments scan their cells: the nodes of one row of cells are
 *     contiguous, a box test that is exactly the predicate's first step and
 *     a provably conservative version of its second reject most nodes, the
 *     shared predicate decides the rest; pairs go to per-thread buffers;
 *  5. pairs to canonical order: count per (secondary, thread), prefix sum,
 *     scatter into the output, then each node's few segments are sorted
 *     (the set is fixed by the predicate and the order by the sort, so the
 *     bytes do not depend on the thread count or the schedule).
 *
 * Conservative cells: the cell of a coordinate is a monotone function of it
 * (subtract, multiply by a positive factor, clamp, truncate), the same
 * function for nodes and for segment boxes, and the segment range is taken
 * from its inflated box widened by a few ulps of the coordinates' magnitude;
 * a node inside the inflated box is therefore always in a scanned cell.
 */
#include <stdlib.h>

#include "search_bucket_grid.h"

int cti_search_bucket_v0(ct_search *s, const ct_search_input *in, ct_pairs *out);

/* A thread's pair buffer: secondary positions and segments. */
typedef struct bk_buf {
    ct_idx *pos, *seg;
    size_t n, cap;
} bk_buf;

typedef struct bk_state {
    int64_t max_pairs; /* this search's pair limit (cti_search_max_pairs) */
    int maxthr;
    ct_idx *cell;          /* per secondary position: its cell, or -1 */
    size_t cell_cap;
    ct_real *px, *py, *pz; /* binned nodes, cell order */
    ct_idx *ppos;          /* their secondary positions */
    size_t px_cap, py_cap, pz_cap, ppos_cap;
    ct_idx *hist; /* node binning: count per (cell, block), then offsets */
    size_t hist_cap;
    ct_idx *phist; /* pair transposition: per (secondary, thread) */
    size_t phist_cap;
    ct_real *srec; /* per segment: its 4 corners, 12 values, segment order */
    size_t srec_cap;
    ct_idx *skey, *sorder, *shist; /* segments sorted by the cell of their centre */
    size_t skey_cap, sorder_cap, shist_cap;
    bk_buf *buf;   /* thread t uses buf[4 * t], on lines of its own */
} bk_state;

static void bk_free(void *v)
{
    bk_state *st = v;
    if (!st)
        return;
    ct_free(st->cell);
    ct_free(st->px);
    ct_free(st->py);
    ct_free(st->pz);
    ct_free(st->ppos);
    ct_free(st->hist);
    ct_free(st->phist);
    ct_free(st->srec);
    ct_free(st->skey);
    ct_free(st->sorder);
    ct_free(st->shist);
    for (int t = 0; t < st->maxthr; t++) {
        ct_free(st->buf[4 * t].pos);
        ct_free(st->buf[4 * t].seg);
    }
    ct_free(st->buf);
    free(st);
}

static size_t bk_memory(const void *v)
{
    const bk_state *st = v;
    size_t b = sizeof *st;
    b += (st->cell_cap + st->ppos_cap + st->hist_cap + st->phist_cap) * sizeof(ct_idx);
    b += (st->skey_cap + st->sorder_cap + st->shist_cap) * sizeof(ct_idx);
    b += (st->px_cap + st->py_cap + st->pz_cap + st->srec_cap) * sizeof(ct_real);
    for (int t = 0; t < st->maxthr; t++)
        b += 2 * st->buf[4 * t].cap * sizeof(ct_idx);
    return b;
}

/* The workspace's state, created on first use and grown to nt threads. */
static bk_state *bk_get(ct_search *s, int nt)
{
    bk_state *st = cti_search_state(s, sizeof *st, bk_free, bk_memory);
    if (!st)
        return NULL;
    if (nt > st->maxthr) {
        /* One 64-byte slot per thread: a thread's buffer header never
         * shares a cache line with another's. */
        bk_buf *nb = ct_calloc((size_t)nt * 4, sizeof *nb);
        if (!nb)
            return NULL;
        for (int t = 0; t < st->maxthr; t++)
            nb[4 * t] = st->buf[4 * t];
        ct_free(st->buf);
        st->buf = nb;
        st->maxthr = nt;
    }
    return st;
}

static int bk_grow(void *pp, size_t *cap, size_t need, size_t size)
{
    void **p = pp;
    return cti_grow(p, cap, need, size, 0);
}

/* Make room for one more pair in buffer b; 0, or -1 when out of memory. */
static int bk_room(bk_buf *b)
{
    if (b->n < b->cap)
        return 0;
    size_t ncap = b->cap + b->cap / 2 + 1024;
    if (cti_renew_two(&b->pos, &b->seg, b->n, ncap) != CT_OK)
        return -1;
    b->cap = ncap;
    return 0;
}

/* The grid: origin, cells per axis, cells per unit length. */
typedef struct bk_grid {
    ct_real lo[3], hi[3]; /* the region where a node may pair at all */
    ct_real inv[3];       /* cells per unit length (0 on a flat axis) */
    ct_idx n[3];          /* cells per axis */
    ct_real tol;          /* widening of segment ranges, a few ulps */
} bk_grid;

/* Cell of coordinate v along one axis: monotone in v. */
static inline ct_idx bk_cell1(ct_real v, ct_real o, ct_real inv, ct_idx nmax)
{
    ct_real t = (v - o) * inv;
    t = t > 0 ? t : 0;
    return t < (ct_real)nmax ? (ct_idx)t : nmax;
}

/* Pass 1: the boxes of the secondaries (sb) and of the segments' nodes
 * (mb), as lo[3] hi[3]; checks indices and finiteness, and copies the
 * segments' corners into srec (12 values per segment, contiguous). */
static int v0_boxes(const ct_search_input *in, ct_real *restrict srec, ct_real sb[6],
                     ct_real mb[6])
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict sec = in->sec;
    const ct_idx nnode = in->nnode;
    ct_real s0 = CTI_HUGE, s1 = CTI_HUGE, s2 = CTI_HUGE;
    ct_real t0 = -CTI_HUGE, t1 = -CTI_HUGE, t2 = -CTI_HUGE;
    int bad = 0, range = 0;
#pragma omp parallel for schedule(static) reduction(min : s0, s1, s2) \
    reduction(max : t0, t1, t2) reduction(| : bad, range)
    for (ct_idx i = 0; i < in->nsec; i++) {
        ct_idx k = sec[i];
        if ((uint32_t)k >= (uint32_t)nnode) {
            range = 1;
            continue;
        }
        ct_real X = x[k], Y = y[k], Z = z[k];
        /* v - v is 0 for a finite v, NaN for NaN and infinities. */
        bad |= !(X - X == 0) | !(Y - Y == 0) | !(Z - Z == 0);
        s0 = CTI_MIN(s0, X);
        s1 = CTI_MIN(s1, Y);
        s2 = CTI_MIN(s2, Z);
        t0 = CTI_MAX(t0, X);
        t1 = CTI_MAX(t1, Y);
        t2 = CTI_MAX(t2, Z);
    }
    sb[0] = s0, sb[1] = s1, sb[2] = s2, sb[3] = t0, sb[4] = t1, sb[5] = t2;
    s0 = s1 = s2 = CTI_HUGE;
    t0 = t1 = t2 = -CTI_HUGE;
    const ct_idx *nn[4] = {in->n1, in->n2, in->n3, in->n4};
#pragma omp parallel for schedule(static) reduction(min : s0, s1, s2) \
    reduction(max : t0, t1, t2) reduction(| : bad, range)
    for (ct_idx j = 0; j < in->nseg; j++) {
        ct_real *restrict r = srec + (size_t)12 * j;
        for (int q = 0; q < 4; q++) {
            ct_idx k = nn[q][j];
            if ((uint32_t)k >= (uint32_t)nnode) {
                range = 1;
                r[3 * q] = r[3 * q + 1] = r[3 * q + 2] = 0;
                continue;
            }
            ct_real X = x[k], Y = y[k], Z = z[k];
            r[3 * q] = X;
            r[3 * q + 1] = Y;
            r[3 * q + 2] = Z;
            bad |= !(X - X == 0) | !(Y - Y == 0) | !(Z - Z == 0);
            s0 = CTI_MIN(s0, X);
            s1 = CTI_MIN(s1, Y);
            s2 = CTI_MIN(s2, Z);
            t0 = CTI_MAX(t0, X);
            t1 = CTI_MAX(t1, Y);
            t2 = CTI_MAX(t2, Z);
        }
    }
    mb[0] = s0, mb[1] = s1, mb[2] = s2, mb[3] = t0, mb[4] = t1, mb[5] = t2;
    if (range)
        return CT_ERR_RANGE;
    return bad ? CT_ERR_NONFINITE : CT_OK;
}

/* Cells per axis as the default search sizes them (cti_bucket_size), and
 * the tolerance of the cell coordinates: 8 machine epsilons of the largest
 * coordinate magnitude of the grid's box. */
static void v0_size(const ct_real lo[3], const ct_real hi[3], ct_idx nseg, double factor,
                    int64_t maxc, ct_idx n_out[3], ct_real inv[3], ct_real *tol)
{
    cti_bucket_size(lo, hi, nseg, factor, maxc, n_out, inv);
    double mag = 0;
    for (int k = 0; k < 3; k++)
        mag = CTI_MAX(mag, CTI_MAX(fabs((double)lo[k]), fabs((double)hi[k])));
    *tol = (ct_real)(8.0 * CTI_EPS * mag);
}

/* Sort a node's segment list (short: insertion; long: qsort). */
static int bk_cmp(const void *a, const void *b)
{
    ct_idx x = *(const ct_idx *)a, y = *(const ct_idx *)b;
    return (x > y) - (x < y);
}

static void bk_sort(ct_idx *v, ct_idx n)
{
    if (n > 32) {
        qsort(v, (size_t)n, sizeof *v, bk_cmp);
        return;
    }
    for (ct_idx i = 1; i < n; i++) {
        ct_idx x = v[i], j = i;
        while (j > 0 && v[j - 1] > x) {
            v[j] = v[j - 1];
            j--;
        }
        v[j] = x;
    }
}

/* Pass 3: counting sort of the secondaries into the cells, in nb blocks of
 * consecutive positions (a stable sort: a cell's nodes are in secondary
 * order). Returns the number of binned nodes. Afterwards the nodes of cell
 * c are px[cend(c-1) .. cend(c)-1] with cend(c) = hist[c * nb + nb - 1]. */
static ct_idx bk_bin_nodes(bk_state *st, const ct_search_input *in, const bk_grid *g,
                           int nb)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict sec = in->sec;
    const ct_idx nsec = in->nsec, nx = g->n[0], ny = g->n[1];
    const int64_t nh = (int64_t)nx * ny * g->n[2] * nb;
    ct_idx *restrict hist = st->hist, *restrict cell = st->cell;
#pragma omp parallel for schedule(static)
    for (int64_t c = 0; c <= nh; c++)
        hist[c] = 0;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx lo = (ct_idx)((int64_t)nsec * b / nb), hi = (ct_idx)((int64_t)nsec * (b + 1) / nb);
        for (ct_idx i = lo; i < hi; i++) {
            ct_idx k = sec[i];
            ct_real X = x[k], Y = y[k], Z = z[k];
            if (X < g->lo[0] || X > g->hi[0] || Y < g->lo[1] || Y > g->hi[1] ||
                Z < g->lo[2] || Z > g->hi[2]) {
                cell[i] = -1;
                continue;
            }
            ct_idx ix = bk_cell1(X, g->lo[0], g->inv[0], nx - 1);
            ct_idx iy = bk_cell1(Y, g->lo[1], g->inv[1], ny - 1);
            ct_idx iz = bk_cell1(Z, g->lo[2], g->inv[2], g->n[2] - 1);
            ct_idx c = (iz * ny + iy) * nx + ix;
            cell[i] = c;
            hist[(int64_t)c * nb + b]++;
        }
    }
    ct_idx nbin = cti_prefix_sum_idx(hist, hist, (ct_idx)nh);
    ct_real *restrict px = st->px, *restrict py = st->py, *restrict pz = st->pz;
    ct_idx *restrict ppos = st->ppos;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx lo = (ct_idx)((int64_t)nsec * b / nb), hi = (ct_idx)((int64_t)nsec * (b + 1) / nb);
        for (ct_idx i = lo; i < hi; i++) {
            ct_idx c = cell[i];
            if (c < 0)
                continue;
            ct_idx k = sec[i], o = hist[(int64_t)c * nb + b]++;
            px[o] = x[k];
            py[o] = y[k];
            pz[o] = z[k];
            ppos[o] = i;
        }
    }
    return nbin;
}

/* Pass 3b: counting sort of the segments by the cell of their box's centre,
 * so that the scan visits the cells, the binned nodes and the segment
 * records in spatial order whatever the numbering. */
static void bk_bin_segs(bk_state *st, ct_idx nseg, const bk_grid *g, int nb)
{
    const ct_idx nx = g->n[0], ny = g->n[1];
    const int64_t nh = (int64_t)nx * ny * g->n[2] * nb;
    const ct_real *restrict srec = st->srec;
    ct_idx *restrict hist = st->shist, *restrict key = st->skey, *restrict ord = st->sorder;
#pragma omp parallel for schedule(static)
    for (int64_t c = 0; c <= nh; c++)
        hist[c] = 0;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx lo = (ct_idx)((int64_t)nseg * b / nb), hi = (ct_idx)((int64_t)nseg * (b + 1) / nb);
        for (ct_idx j = lo; j < hi; j++) {
            const ct_real *r = srec + (size_t)12 * j;
            ct_idx ic[3];
            for (int k = 0; k < 3; k++) {
                ct_real l = CTI_MIN(CTI_MIN(r[k], r[3 + k]), CTI_MIN(r[6 + k], r[9 + k]));
                ct_real h = CTI_MAX(CTI_MAX(r[k], r[3 + k]), CTI_MAX(r[6 + k], r[9 + k]));
                ic[k] = bk_cell1(l + (h - l) / 2, g->lo[k], g->inv[k], g->n[k] - 1);
            }
            ct_idx c = (ic[2] * ny + ic[1]) * nx + ic[0];
            key[j] = c;
            hist[(int64_t)c * nb + b]++;
        }
    }
    cti_prefix_sum_idx(hist, hist, (ct_idx)nh);
#pragma omp parallel for schedule(static)
    for (int b = 0; b < nb; b++) {
        ct_idx lo = (ct_idx)((int64_t)nseg * b / nb), hi = (ct_idx)((int64_t)nseg * (b + 1) / nb);
        for (ct_idx j = lo; j < hi; j++)
            ord[hist[(int64_t)key[j] * nb + b]++] = j;
    }
}

/* Pass 4: every segment scans the cells its inflated box covers; accepted
 * pairs (secondary position, segment) go to the threads' buffers. */
static int bk_scan(bk_state *st, const ct_search_input *in, const bk_grid *g, int nb)
{
    const ct_real *restrict srec = st->srec;
    const ct_idx *restrict sorder = st->sorder;
    const ct_idx *restrict sec = in->sec;
    const ct_idx *restrict n1 = in->n1, *restrict n2 = in->n2, *restrict n3 = in->n3,
                 *restrict n4 = in->n4;
    const ct_real *restrict px = st->px, *restrict py = st->py, *restrict pz = st->pz;
    const ct_idx *restrict ppos = st->ppos, *restrict hist = st->hist;
    const ct_real d = in->gap + in->margin, d2 = d * d;
    /* The predicate rejects when its sum of squares exceeds d2; ours may
     * differ from it by a few roundings (at most about 3 ulps, relatively,
     * as every term is nonnegative, plus underflow), so we reject only
     * above this bound. */
    const ct_real d2hi = d2 + d2 * (16 * CTI_EPS) + (ct_real)1e-30;
    const ct_idx nx = g->n[0], ny = g->n[1];
    const int self = in->self;
    const int filter = in->filter;
    int err = 0;
    for (int t = 0; t < st->maxthr; t++)
        st->buf[4 * t].n = 0;
#pragma omp parallel reduction(| : err)
    {
        bk_buf b = st->buf[4 * cti_thread_id()];
#pragma omp for schedule(dynamic, 256)
        for (ct_idx q = 0; q < in->nseg; q++) {
            if (err)
                continue;
            const ct_idx j = sorder[q];
            const ct_real *r = srec + (size_t)12 * j;
#if defined(__GNUC__)
            /* The records are read in cell order, i.e. at random for a
             * shuffled numbering: fetch a few segments ahead. */
            if (q + 8 < in->nseg) {
                const ct_real *rn = srec + (size_t)12 * sorder[q + 8];
                __builtin_prefetch(rn);
                __builtin_prefetch(rn + 11);
            }
#endif
            ct_real A[3], B[3], C[3], E[3], lo[3], hi[3], lod[3], hid[3];
            for (int k = 0; k < 3; k++) {
                A[k] = r[k];
                B[k] = r[3 + k];
                C[k] = r[6 + k];
                E[k] = r[9 + k];
            }
            int out = 0;
            ct_idx c0[3], c1[3];
            for (int k = 0; k < 3; k++) {
                /* Exactly the predicate's bounds: nodes outside them are
                 * rejected by it. */
                lo[k] = CTI_MIN(CTI_MIN(A[k], B[k]), CTI_MIN(C[k], E[k]));
                hi[k] = CTI_MAX(CTI_MAX(A[k], B[k]), CTI_MAX(C[k], E[k]));
                lod[k] = lo[k] - d;
                hid[k] = hi[k] + d;
                out |= hid[k] < g->lo[k] || lod[k] > g->hi[k];
                c0[k] = bk_cell1(lod[k] - g->tol, g->lo[k], g->inv[k], g->n[k] - 1);
                c1[k] = bk_cell1(hid[k] + g->tol, g->lo[k], g->inv[k], g->n[k] - 1);
            }
            if (out)
                continue;
            for (ct_idx iz = c0[2]; iz <= c1[2] && !err; iz++) {
                for (ct_idx iy = c0[1]; iy <= c1[1]; iy++) {
                    /* Cells c0[0] .. c1[0] of this row hold consecutive nodes. */
                    int64_t row = ((int64_t)iz * ny + iy) * nx;
                    int64_t ca = row + c0[0], cb = row + c1[0];
                    ct_idx k0 = ca > 0 ? hist[(ca - 1) * nb + nb - 1] : 0;
                    ct_idx k1 = hist[cb * nb + nb - 1];
                    for (ct_idx k = k0; k < k1; k++) {
                        ct_real X = px[k], Y = py[k], Z = pz[k];
                        if (X < lod[0] || X > hid[0] || Y < lod[1] || Y > hid[1] ||
                            Z < lod[2] || Z > hid[2])
                            continue;
                        ct_real ex = X < lo[0] ? lo[0] - X : (X > hi[0] ? X - hi[0] : 0);
                        ct_real ey = Y < lo[1] ? lo[1] - Y : (Y > hi[1] ? Y - hi[1] : 0);
                        ct_real ez = Z < lo[2] ? lo[2] - Z : (Z > hi[2] ? Z - hi[2] : 0);
                        if (ex * ex + ey * ey + ez * ez > d2hi)
                            continue;
                        ct_idx pos = ppos[k];
                        if (self) {
                            ct_idx node = sec[pos];
                            if (node == n1[j] || node == n2[j] || node == n3[j] ||
                                node == n4[j])
                                continue;
                        }
                        ct_real p[3] = {X, Y, Z};
                        if (filter == CT_FILTER_BOX ? !ct_pair_box_near(p, A, B, C, E, d)
                                                    : !ct_pair_may_touch(p, A, B, C, E, d))
                            continue;
                        /* Beyond the pair limit (err 2): so is the total. */
                        if (b.n == b.cap && (int64_t)b.n > st->max_pairs) {
                            err |= 2;
                            break;
                        }
                        if (b.n == b.cap && bk_room(&b)) {
                            err |= 1;
                            break;
                        }
                        b.pos[b.n] = pos;
                        b.seg[b.n] = j;
                        b.n++;
                    }
                    if (err)
                        break;
                }
            }
        }
        st->buf[4 * cti_thread_id()] = b;
    }
    return (err & 2) ? CT_ERR_TOOBIG : err ? CT_ERR_NOMEM : CT_OK;
}

/* Pass 5: the threads' pairs into canonical order (secondary position, then
 * segment), by a counting sort on the position and a sort of each node's
 * few segments. */
static int bk_output(bk_state *st, const ct_search_input *in, int nt, ct_pairs *out)
{
    const ct_idx nsec = in->nsec;
    const ct_idx *restrict sec = in->sec;
    size_t total = 0;
    for (int t = 0; t < nt; t++)
        total += st->buf[4 * t].n;
    if ((int64_t)total > st->max_pairs)
        return CT_ERR_TOOBIG;
    int rc = ct_pairs_reserve(out, (ct_idx)total);
    if (rc)
        return rc;
    ct_idx *restrict ph = st->phist;
    const int64_t nh = (int64_t)nsec * nt;
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i <= nh; i++)
        ph[i] = 0;
#pragma omp parallel for schedule(static)
    for (int t = 0; t < nt; t++) {
        const bk_buf *b = &st->buf[4 * t];
        for (size_t q = 0; q < b->n; q++)
            ph[(int64_t)b->pos[q] * nt + t]++;
    }
    cti_prefix_sum_idx(ph, ph, (ct_idx)nh);
    ct_idx *restrict on = out->node, *restrict os = out->seg;
#pragma omp parallel for schedule(static)
    for (int t = 0; t < nt; t++) {
        const bk_buf *b = &st->buf[4 * t];
        for (size_t q = 0; q < b->n; q++) {
            ct_idx pos = b->pos[q], o = ph[(int64_t)pos * nt + t]++;
            on[o] = sec[pos];
            os[o] = b->seg[q];
        }
    }
    /* The segments were visited in cell order: sort each node's few. */
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < nsec; i++) {
        ct_idx a = i > 0 ? ph[(int64_t)i * nt - 1] : 0, e = ph[(int64_t)i * nt + nt - 1];
        if (e - a > 1)
            bk_sort(os + a, e - a);
    }
    out->n = (ct_idx)total;
    return CT_OK;
}

int cti_search_bucket_v0(ct_search *s, const ct_search_input *in, ct_pairs *out)
{
    int nt = cti_num_threads();
    bk_state *st = bk_get(s, nt);
    if (!st)
        return CT_ERR_NOMEM;
    st->max_pairs = cti_search_max_pairs(s);
    out->n = 0;
    int rc = ct_pairs_reserve(out, 0);
    if (rc)
        return rc;
    if (bk_grow(&st->srec, &st->srec_cap, (size_t)12 * (size_t)in->nseg, sizeof(ct_real)))
        return CT_ERR_NOMEM;
    ct_real sb[6], mb[6];
    rc = v0_boxes(in, st->srec, sb, mb);
    if (rc || in->nsec == 0 || in->nseg == 0)
        return rc;
    const ct_real d = in->gap + in->margin;
    bk_grid g;
    for (int k = 0; k < 3; k++) {
        /* Nodes outside the main box inflated by d (with the predicate's
         * rounding) can pair with no segment. */
        g.lo[k] = CTI_MAX(sb[k], mb[k] - d);
        g.hi[k] = CTI_MIN(sb[3 + k], mb[3 + k] + d);
        if (g.lo[k] > g.hi[k])
            return CT_OK;
    }
    int64_t maxc = cti_bucket_max_cells(s->p.max_cells, in);
    /* Offsets per (cell, block) must fit a ct_idx. */
    maxc = CTI_MIN(maxc, (int64_t)(INT32_MAX / 2) / nt);
    s->last_cell_factor = s->p.cell_factor > 0 ? s->p.cell_factor : 1.0;
    v0_size(g.lo, g.hi, in->nseg, s->last_cell_factor, maxc,
                    g.n, g.inv, &g.tol);
    int64_t ncell = (int64_t)g.n[0] * g.n[1] * g.n[2];
    if ((int64_t)in->nsec * nt >= INT32_MAX)
        return CT_ERR_TOOBIG;
    size_t ns = (size_t)in->nsec;
    if (bk_grow(&st->cell, &st->cell_cap, ns, sizeof(ct_idx)) ||
        bk_grow(&st->ppos, &st->ppos_cap, ns, sizeof(ct_idx)) ||
        bk_grow(&st->px, &st->px_cap, ns, sizeof(ct_real)) ||
        bk_grow(&st->py, &st->py_cap, ns, sizeof(ct_real)) ||
        bk_grow(&st->pz, &st->pz_cap, ns, sizeof(ct_real)) ||
        bk_grow(&st->hist, &st->hist_cap, (size_t)(ncell * nt + 1), sizeof(ct_idx)) ||
        bk_grow(&st->phist, &st->phist_cap, ns * (size_t)nt + 1, sizeof(ct_idx)) ||
        bk_grow(&st->shist, &st->shist_cap, (size_t)(ncell * nt + 1), sizeof(ct_idx)) ||
        bk_grow(&st->skey, &st->skey_cap, (size_t)in->nseg, sizeof(ct_idx)) ||
        bk_grow(&st->sorder, &st->sorder_cap, (size_t)in->nseg, sizeof(ct_idx)))
        return CT_ERR_NOMEM;
    if (bk_bin_nodes(st, in, &g, nt) == 0)
        return CT_OK;
    bk_bin_segs(st, in->nseg, &g, nt);
    rc = bk_scan(st, in, &g, nt);
    if (rc)
        return rc;
    return bk_output(st, in, nt, out);
}
