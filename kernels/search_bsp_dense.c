/*
 * search_bsp_dense.c -- the dense leaf of the quick-sort search.
 *
 * A node's candidates all lie in its leaf. Where elements are small
 * against the search distance (the fine region of a graded mesh), a node
 * passes the box test of most of the leaf's segments it meets, and the
 * batch predicate (predicate_batch.c) spends most of its time copying
 * fifteen coordinates per pair into its lanes. A dense leaf instead copies
 * its segments' corners once, with the bounds of their boxes, into SoA
 * arrays, and runs the predicate's cheap steps (1 and 2, the box; 2b, a
 * corner within d) on 8 segments at a time in SIMD lanes, the node's
 * coordinates broadcast. The pairs those steps leave undecided (about one
 * in ten on the graded mesh) go to the batch predicate, whose answer is
 * the one-pair predicate's; its lanes rerun steps 1 to 2b on the same
 * values, so they are undecided there too. The steps are predicate_steps.h's
 * inline functions and the box bounds are their min, max, lo - d and
 * hi + d, computed once instead of per pair: every answer is bit for bit
 * that of ct_pair_may_touch, and the pair set is the direct search's.
 *
 * A leaf is dense when its first nodes' box tests pass at least half of
 * the lanes of the groups of 8 that they touch; otherwise (a coarse
 * region, the plates) the lanes would mostly compute pairs the box test
 * already rejected, and the leaf takes the batch path of search_bsp_leaf.c.
 *
 * Threads: a leaf belongs to one task, and everything here is that
 * thread's scratch (its bsp_stack) and its collector buffer.
 */
#include "predicate_steps.h"
#include "search_bsp_internal.h"

/* The array of the leaf's corner scratch (BSP_LC arrays, lccap apart):
 * corner e's axis a, then the box's lo, hi, lo - d and hi + d on axis a,
 * then the sum of (v - v) over the corners' coordinates (0 when they are
 * finite). */
#define LC_CORNER(e, a) (3 * (e) + (a))
#define LC_LO(a) (12 + (a))
#define LC_HI(a) (15 + (a))
#define LC_LOD(a) (18 + (a))
#define LC_HID(a) (21 + (a))
#define LC_FIN 24
_Static_assert(LC_FIN + 1 == BSP_LC, "the dense leaf's arrays");

/* BSP_DENSE_SAMPLE (search_bsp_internal.h): the nodes whose box tests
 * choose the leaf's path; BSP_DENSE_MAX_SEGS: the most segments a dense
 * leaf may have (a leaf made by the box-size rule can hold any number; the
 * corner scratch costs 216 bytes a segment). DENSE_NODES: the nodes decided
 * between two emissions (the answer bytes then take at most 256 x 256). */
enum { DENSE_NODES = 256 };

int cti_bsp_leaf_is_dense(const bsp_ctx *c, const bsp_stack *sk, ct_idx n0, ct_idx n1,
                          ct_idx ns, bsp_sample *smp)
{
    smp->n = 0;
    smp->ng = ((ns + 7) & ~(ct_idx)7) / 8;
    if (ns > BSP_DENSE_MAX_SEGS)
        return 0;
    if (c->dense != 0)
        return c->dense > 0;
    const bsp_state *st = c->st;
    const size_t w = sk->lbcap;
    const bsp_f *restrict lb = sk->lb;
    const ct_idx ke = CTI_MIN(n1, n0 + BSP_DENSE_SAMPLE), ng = smp->ng;
    int64_t bits = 0, groups = 0;
    for (ct_idx k = n0; k < ke; k++) {
        const bsp_pt pt = bsp_pt_of(st->nx[k], st->ny[k], st->nz[k]);
        uint8_t *restrict mk = smp->m + (size_t)(k - n0) * (size_t)ng;
        for (ct_idx g = 0; g < ng; g++) {
            const unsigned m = bsp_mask_of(NULL, 0, ng, k - n0, g, lb, w, &pt);
            mk[g] = (uint8_t)m;
            bits += __builtin_popcount(m);
            groups += m != 0;
        }
    }
    smp->n = ke - n0;
    return 2 * bits >= 8 * groups && groups > 0;
}

/* The corners of the leaf's segments segs[0..ns), their node numbers and
 * their boxes' bounds into this thread's scratch; the padding lanes up to
 * a multiple of 8 get zeros and no node (no node's box test passes them). */
CTI_NOVEC static void dense_corners(const ct_search_input *in, bsp_stack *sk,
                                    const ct_idx *restrict segs, ct_idx ns, ct_real d)
{
    const size_t w = sk->lccap;
    ct_real *restrict lc = sk->lc;
    ct_idx *restrict lcn = sk->lcn;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *const cn[4] = {in->n1, in->n2, in->n3, in->n4};
    const ct_idx ns8 = (ns + 7) & ~(ct_idx)7;
    CTI_NOVEC_LOOP
    for (ct_idx q = 0; q < ns; q++) {
        const ct_idx j = segs[q];
        for (int e = 0; e < 4; e++) {
            const ct_idx i = cn[e][j];
            lcn[(size_t)e * w + (size_t)q] = i;
            lc[(size_t)LC_CORNER(e, 0) * w + (size_t)q] = x[i];
            lc[(size_t)LC_CORNER(e, 1) * w + (size_t)q] = y[i];
            lc[(size_t)LC_CORNER(e, 2) * w + (size_t)q] = z[i];
        }
    }
    for (ct_idx q = ns; q < ns8; q++) {
        for (int e = 0; e < 4; e++)
            lcn[(size_t)e * w + (size_t)q] = -1;
        for (int a = 0; a < 12; a++)
            lc[(size_t)a * w + (size_t)q] = 0;
    }
    for (int a = 0; a < 3; a++) {
        const ct_real *restrict ca = lc + (size_t)LC_CORNER(0, a) * w;
        const ct_real *restrict cb = lc + (size_t)LC_CORNER(1, a) * w;
        const ct_real *restrict cc = lc + (size_t)LC_CORNER(2, a) * w;
        const ct_real *restrict ce = lc + (size_t)LC_CORNER(3, a) * w;
        ct_real *restrict lo = lc + (size_t)LC_LO(a) * w, *restrict hi = lc + (size_t)LC_HI(a) * w;
        ct_real *restrict lod = lc + (size_t)LC_LOD(a) * w;
        ct_real *restrict hid = lc + (size_t)LC_HID(a) * w;
#pragma omp simd
        for (ct_idx q = 0; q < ns8; q++) {
            const ct_real l = cti_step_lo(ca[q], cb[q], cc[q], ce[q]);
            const ct_real h = cti_step_hi(ca[q], cb[q], cc[q], ce[q]);
            lo[q] = l, hi[q] = h, lod[q] = l - d, hid[q] = h + d;
        }
    }
    /* 0 when the corners are finite, NaN otherwise (v - v is 0 for a
     * finite v, NaN for NaN and infinities), whatever the order of the sum. */
    ct_real *restrict fin = lc + (size_t)LC_FIN * w;
    for (ct_idx q = 0; q < ns8; q++)
        fin[q] = 0;
    for (int a = 0; a < 12; a++) {
        const ct_real *restrict v = lc + (size_t)a * w;
#pragma omp simd
        for (ct_idx q = 0; q < ns8; q++)
            fin[q] += v[q] - v[q];
    }
}

/* Steps 1, 2 and 2b of point P (pfin: the sum of (v - v) over its
 * coordinates) against the 8 segments at lane q0 of the scratch: the lanes
 * of m they accept in *acc, those they leave undecided (or that have a
 * coordinate that is not finite) in *und. */
static inline void dense_steps(cti_pv P, ct_real pfin, const ct_real *restrict lc, size_t w,
                               ct_idx q0, ct_real d2, unsigned m, unsigned *acc, unsigned *und)
{
    const ct_real *restrict v[BSP_LC];
    for (int a = 0; a < BSP_LC; a++)
        v[a] = lc + (size_t)a * w + (size_t)q0;
    _Alignas(64) cti_lane r8[8];
#pragma omp simd
    for (int k = 0; k < 8; k++) {
        const cti_pv A = {v[0][k], v[1][k], v[2][k]}, B = {v[3][k], v[4][k], v[5][k]},
                     C = {v[6][k], v[7][k], v[8][k]}, E = {v[9][k], v[10][k], v[11][k]};
        cti_lane out = 0;
        const ct_real bx = cti_step_axis_lh(P.x, v[LC_LO(0)][k], v[LC_HI(0)][k],
                                            v[LC_LOD(0)][k], v[LC_HID(0)][k], &out);
        const ct_real by = cti_step_axis_lh(P.y, v[LC_LO(1)][k], v[LC_HI(1)][k],
                                            v[LC_LOD(1)][k], v[LC_HID(1)][k], &out);
        const ct_real bz = cti_step_axis_lh(P.z, v[LC_LO(2)][k], v[LC_HI(2)][k],
                                            v[LC_LOD(2)][k], v[LC_HID(2)][k], &out);
        const ct_real box2 = cti_step_box_sum(bx, by, bz, out);
        const cti_lane reject = (box2 < 0) | (box2 > d2);
        const cti_lane accept = cti_step_corners(P, A, B, C, E, d2);
        const cti_lane nf = !(pfin + v[LC_FIN][k] == 0);
        /* 0 reject, 1 accept, 2 undecided, 3 not finite (as the batch). */
        r8[k] = ((reject - 1) & (2 - accept)) | (nf << 1);
    }
    /* The answers as bit masks: with AVX-512, two compares into mask
     * registers (gcc turned the loop below into a lane-by-lane extraction,
     * about 15 % of the dense leaf's samples). */
    unsigned a = 0, u = 0;
#if defined(__AVX512F__) && !defined(CT_SINGLE)
    const __m512i rv = _mm512_load_si512((const void *)r8);
    a = _mm512_cmpeq_epi64_mask(rv, _mm512_set1_epi64(1));
    u = _mm512_cmpge_epi64_mask(rv, _mm512_set1_epi64(2));
#elif defined(__AVX512VL__) && defined(CT_SINGLE)
    const __m256i rv = _mm256_load_si256((const void *)r8);
    a = _mm256_cmpeq_epi32_mask(rv, _mm256_set1_epi32(1));
    u = _mm256_cmpge_epi32_mask(rv, _mm256_set1_epi32(2));
#else
    for (int k = 0; k < 8; k++) {
        a |= (unsigned)(r8[k] == 1) << k;
        u |= (unsigned)(r8[k] >> 1) << k;
    }
#endif
    *acc = a & m;
    *und = u & m;
}

/* Room for a leaf of ns8 segments (a multiple of 8) in this thread's corner
 * scratch and for DENSE_NODES nodes' answer bytes; 0 (and the error flag)
 * when it cannot grow. */
static int dense_room(bsp_ctx *c, bsp_stack *sk, ct_idx ns8)
{
    const size_t nb = (size_t)DENSE_NODES * (size_t)(ns8 / 8);
    if ((size_t)ns8 <= sk->lccap && nb <= sk->lrcap)
        return 1;
    const size_t cap = CTI_MAX(sk->lccap, ((size_t)ns8 + (size_t)ns8 / 2 + 64) & ~(size_t)7);
    const size_t rcap = (size_t)DENSE_NODES * (cap / 8);
    const size_t bytes[3] = {BSP_LC * cap * sizeof(ct_real), 4 * cap * sizeof(ct_idx), rcap};
    void *q[3];
    if (!cti_bsp_alloc(c, 3, bytes, q))
        return 0;
    ct_free(sk->lc);
    ct_free(sk->lcn);
    ct_free(sk->lr);
    sk->lc = q[0];
    sk->lcn = q[1];
    sk->lr = q[2];
    sk->lccap = cap;
    sk->lrcap = rcap;
    return 1;
}

/* Decide the batch's pairs and set the answer bit of each accepted one
 * (bit at[i] of lr). */
static void dense_flush(cti_pair_batch *restrict pb, const int64_t *restrict at,
                        uint8_t *restrict lr, ct_real d)
{
    cti_pair_batch_test(pb, d);
    for (int i = 0; i < pb->n; i++)
        lr[at[i] >> 3] |= (uint8_t)((pb->ok[i] != 0) << (at[i] & 7));
    pb->n = 0;
}

/* The bits of m (lanes q0.. of the leaf) whose segment is not one of
 * node's own (self contact excludes those). */
static inline unsigned dense_not_own(const ct_idx *restrict lcn, size_t w, ct_idx q0,
                                     unsigned m, ct_idx node)
{
    unsigned own = 0;
    for (unsigned r = m; r; r &= r - 1) {
        const int e = __builtin_ctz(r);
        const size_t q = (size_t)(q0 + e);
        own |= (unsigned)((lcn[q] == node) | (lcn[w + q] == node) | (lcn[2 * w + q] == node) |
                          (lcn[3 * w + q] == node))
               << e;
    }
    return m & ~own;
}

/* Nodes [n0, n1) (at most DENSE_NODES) of a dense leaf: steps 1 to 2b per
 * node and group of 8 into the answer bytes, the undecided pairs through
 * the batch, then each node's accepted segments, in increasing order, into
 * this thread's collector buffer at *len. */
static int dense_nodes(bsp_ctx *c, bsp_stack *sk, ct_idx n0, ct_idx n1,
                       const ct_idx *restrict segs, ct_idx ns, const bsp_sample *smp,
                       ct_idx leaf0, size_t *len)
{
    const ct_search_input *in = c->in;
    const bsp_state *st = c->st;
    cti_collect *col = c->col;
    const int t = cti_thread_id();
    const ct_idx ng = ((ns + 7) & ~(ct_idx)7) / 8;
    const size_t wb = sk->lbcap, w = sk->lccap;
    const bsp_f *restrict lb = sk->lb;
    const ct_real *restrict lc = sk->lc;
    const ct_idx *restrict lcn = sk->lcn;
    uint8_t *restrict lr = sk->lr;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_real d = c->d, d2 = d * d;
    const int self = in->self;
    const ct_idx nsmp = smp->n;
    const uint8_t *restrict sm = smp->m;
    cti_pair_batch pb;
    int64_t at[CTI_PAIR_BATCH];
    cti_pair_batch_init(&pb);

    for (ct_idx k = n0; k < n1; k++) {
        const ct_idx node = in->sec[st->nid[k]];
        const bsp_pt pt = bsp_pt_of(st->nx[k], st->ny[k], st->nz[k]);
        const cti_pv P = {x[node], y[node], z[node]};
        const ct_real pfin = (P.x - P.x) + (P.y - P.y) + (P.z - P.z);
        uint8_t *restrict rk = lr + (size_t)(k - n0) * (size_t)ng;
        for (ct_idx g = 0; g < ng; g++) {
            const ct_idx q0 = 8 * g;
            unsigned m = bsp_mask_of(sm, nsmp, ng, k - leaf0, g, lb, wb, &pt);
            if (m && self)
                m = dense_not_own(lcn, w, q0, m, node);
            if (!m) {
                rk[g] = 0;
                continue;
            }
            unsigned acc, und;
            dense_steps(P, pfin, lc, w, q0, d2, m, &acc, &und);
            rk[g] = (uint8_t)acc;
            for (; und; und &= und - 1) {
                const int e = __builtin_ctz(und);
                const size_t q = (size_t)(q0 + e);
                const int i = pb.n;
                ct_real cn[4][3];
                for (int v = 0; v < 4; v++)
                    for (int a = 0; a < 3; a++)
                        cn[v][a] = lc[LC_CORNER(v, a) * w + q];
                const ct_real pp[3] = {P.x, P.y, P.z};
                cti_pair_batch_set(&pb, i, pp, cn[0], cn[1], cn[2], cn[3]);
                at[i] = ((int64_t)(k - n0) * ng + g) * 8 + e;
                if (++pb.n == CTI_PAIR_BATCH)
                    dense_flush(&pb, at, lr, d);
            }
        }
    }
    if (pb.n > 0)
        dense_flush(&pb, at, lr, d);

    size_t l = *len;
    for (ct_idx k = n0; k < n1; k++) {
        if (l + (size_t)ns > col->cap[t]) {
            col->len[t] = l;
            if (cti_collect_room(col, t, (size_t)ns) != CT_OK)
                return 0;
        }
        ct_idx *restrict buf = col->buf[t];
        const uint8_t *restrict rk = lr + (size_t)(k - n0) * (size_t)ng;
        const size_t start = l;
        for (ct_idx g = 0; g < ng; g++)
            for (unsigned r = rk[g]; r; r &= r - 1)
                buf[l++] = segs[8 * g + __builtin_ctz(r)];
        if (l > start) {
            const ct_idx pos = st->nid[k];
            col->owner[pos] = t;
            col->start[pos] = (int64_t)start;
            col->count[pos] = (ct_idx)(l - start);
        }
    }
    *len = l;
    return 1;
}

void cti_bsp_leaf_dense(bsp_ctx *c, bsp_stack *sk, ct_idx n0, ct_idx n1,
                        const ct_idx *restrict segs, ct_idx ns, const bsp_sample *smp)
{
    const ct_idx ns8 = (ns + 7) & ~(ct_idx)7;
    if (!dense_room(c, sk, ns8))
        return;
    dense_corners(c->in, sk, segs, ns, c->d);
    cti_collect *col = c->col;
    const int t = cti_thread_id();
    size_t len = col->len[t];
    for (ct_idx k = n0; k < n1; k += DENSE_NODES)
        if (!dense_nodes(c, sk, k, CTI_MIN(n1, k + DENSE_NODES), segs, ns, smp, n0, &len))
            return;
    col->len[t] = len;
}
