/*
 * predicate_batch.c -- the hull predicate (predicate.c) over a batch of
 * candidate pairs at once.
 *
 * A search that tests many pairs one by one pays, per pair, a call, twelve
 * indexed loads and the branches of the predicate's early exits, which
 * vary from pair to pair and defeat the branch predictor. Here a batch is
 * decided in three loops:
 *  1. load: the node's and the four corners' coordinates into the batch's
 *     unit-stride arrays (scalar loads, which this hardware issues several
 *     per cycle, where vector gathers are slow);
 *  2. decide, in SIMD lanes and without branches, in two stages: first
 *     steps 1 and 2 (the box) reject and step 2b (a corner) accepts, then,
 *     on the lanes left (packed to the front when they are few), step 3
 *     (the prism) and step 4 (the edges) accept and step 4b (a lower
 *     bound of the distance) rejects; after a batch where step 2b left
 *     most lanes open, the next PB_SKIP batches run steps 1, 3 and 4 in one
 *     loop instead, and the second stage, with step 2b, on the lanes that
 *     loop leaves open; a lane still undecided, or with a coordinate that
 *     is not finite, goes to
 *  3. the one-pair predicate, ct_pair_may_touch, on that pair alone.
 * Steps 1 to 4b are the inline functions of predicate_steps.h, the very
 * ones ct_pair_may_touch runs, on the same values and in its order: each
 * lane's answer is the one-pair answer, bit for bit, so the batch changes
 * no search's pair set. On smooth surfaces the lanes decide every pair. On
 * the graded mesh (10^5) the corners accept 76 % of the candidates and
 * the box rejects 14 %, so the costly second stage runs on a tenth of
 * them; on the plates no corner is within d, and the batches run as one
 * stage. On self contact (a crumpled or folded sheet, a sphere) the box
 * keeps many segments of a node's neighbourhood that lie just farther than
 * d: step 4b rejects them in the lanes (before it moved here from the
 * one-pair predicate, those pairs were 2 per node on the crumpled sheet,
 * all sent to the one-pair predicate).
 *
 * Threads: a batch belongs to one thread (it lives on that thread's stack)
 * and is appended to that thread's own output (a query block's buffer or
 * the collector's per-thread buffer), so batching adds no shared write.
 */
#include "ct_internal.h"
#include "predicate_steps.h"

/* The answer of a lane that the vector loop leaves to ct_pair_may_touch. */
enum { PB_UNDECIDED = 2 };

/* Batches run as one stage, without step 2b, after one where step 2b left
 * most lanes open. The switch changes no answer (see pb_one_stage), so it
 * may follow each thread's own batches. */
enum { PB_SKIP = 15 };

/* The copy loops below are scalar on purpose (CTI_NOVEC): vectorised, they
 * become gathers, which measured slower here (gcc: 17 % of the bucket search
 * on plates 10^6, against 14 % scalar). */

CTI_NOVEC void cti_pair_batch_load(cti_pair_batch *restrict b, const ct_real *restrict x,
                         const ct_real *restrict y, const ct_real *restrict z,
                         const ct_idx *restrict n1, const ct_idx *restrict n2,
                         const ct_idx *restrict n3, const ct_idx *restrict n4)
{
    const int n = b->n;
    ct_real *const dst[8] = {b->pxy, b->axy, b->bxy, b->cxy, b->exy, b->paz, b->bcz, b->ez};
    CTI_NOVEC_LOOP
    for (int k = 0; k < n; k++) {
        const ct_idx j = b->seg[k];
        cti_put5(dst, k, x, y, z, b->node[k], n1[j], n2[j], n3[j], n4[j]);
    }
}

CTI_NOVEC void cti_pair_batch_load_rec(cti_pair_batch *restrict b, const ct_real *restrict x,
                             const ct_real *restrict y, const ct_real *restrict z,
                             const ct_real *restrict rec)
{
    const int n = b->n;
    CTI_NOVEC_LOOP
    for (int k = 0; k < n; k++) {
        const ct_idx i = b->node[k];
        const ct_real *restrict r = rec + (size_t)12 * (size_t)b->seg[k];
        CTI_PUT2(b->pxy, k, x[i], y[i]);
        CTI_PUT2(b->axy, k, r[0], r[1]);
        CTI_PUT2(b->bxy, k, r[3], r[4]);
        CTI_PUT2(b->cxy, k, r[6], r[7]);
        CTI_PUT2(b->exy, k, r[9], r[10]);
        CTI_PUT2(b->paz, k, z[i], r[2]);
        CTI_PUT2(b->bcz, k, r[5], r[8]);
        b->ez[k] = r[11];
    }
}

/* Move the coordinates of the undecided lanes (ok[k] >= PB_UNDECIDED) to
 * the front of the batch's arrays, in order, and their lane numbers to idx;
 * returns how many. In place: lane k moves to m <= k. */
CTI_NOVEC static int pb_compact(cti_pair_batch *restrict b, int *restrict idx)
{
    int m = 0;
    CTI_NOVEC_LOOP
    for (int k = 0; k < b->n; k++) {
        if (b->ok[k] < PB_UNDECIDED)
            continue;
        idx[m] = k;
        for (int h = 0; h < 2; h++) {
            b->pxy[2 * m + h] = b->pxy[2 * k + h], b->axy[2 * m + h] = b->axy[2 * k + h];
            b->bxy[2 * m + h] = b->bxy[2 * k + h], b->cxy[2 * m + h] = b->cxy[2 * k + h];
            b->exy[2 * m + h] = b->exy[2 * k + h], b->paz[2 * m + h] = b->paz[2 * k + h];
            b->bcz[2 * m + h] = b->bcz[2 * k + h];
        }
        b->ez[m] = b->ez[k];
        m++;
    }
    return m;
}

/* The batch's coordinate arrays, read-only, for the loops over its lanes
 * (in place, or on the lanes packed to the front). */
#define PB_ARRAYS(b)                                                                    \
    const ct_real *restrict pxy = (b)->pxy, *restrict axy = (b)->axy;                   \
    const ct_real *restrict bxy = (b)->bxy, *restrict cxy = (b)->cxy;                   \
    const ct_real *restrict exy = (b)->exy, *restrict paz = (b)->paz;                   \
    const ct_real *restrict bcz = (b)->bcz, *restrict ez = (b)->ez

/* Lane k's node P and corners A, B, C, E, from the batch's arrays (in
 * scope through PB_ARRAYS). */
#define PB_LANE(k)                                                                      \
    const cti_pv P = {pxy[2 * (k)], pxy[2 * (k) + 1], paz[2 * (k)]},                   \
                 A = {axy[2 * (k)], axy[2 * (k) + 1], paz[2 * (k) + 1]},               \
                 B = {bxy[2 * (k)], bxy[2 * (k) + 1], bcz[2 * (k)]},                   \
                 C = {cxy[2 * (k)], cxy[2 * (k) + 1], bcz[2 * (k) + 1]},               \
                 E = {exy[2 * (k)], exy[2 * (k) + 1], ez[k]}

/* Steps 1 and 2 reject, on every lane; what accepts is step 2b (`one` =
 * 0: stage 1 of two) or steps 3 and 4 (`one` = 1: the one-stage test).
 * ok[k] = 0 reject, 1 accept, 2 undecided, 3 not finite (undecided to the
 * end). Returns the number of lanes undecided. Called with a constant
 * `one`, so it compiles as two loops. */
CTI_STEP cti_lane pb_open(cti_pair_batch *restrict b, ct_real d, ct_real d2, const int one)
{
    const int n = b->n;
    cti_lane *restrict ok = b->ok;
    PB_ARRAYS(b);
    cti_lane nund = 0;
#pragma omp simd reduction(+ : nund)
    for (int k = 0; k < n; k++) {
        PB_LANE(k);
        /* v - v is 0 for a finite v, NaN otherwise. */
        const ct_real fin = ((P.x - P.x) + (P.y - P.y) + (P.z - P.z)) +
                            ((A.x - A.x) + (A.y - A.y) + (A.z - A.z)) +
                            ((B.x - B.x) + (B.y - B.y) + (B.z - B.z)) +
                            ((C.x - C.x) + (C.y - C.y) + (C.z - C.z)) +
                            ((E.x - E.x) + (E.y - E.y) + (E.z - E.z));
        const ct_real box2 = cti_step_box(P, A, B, C, E, d);
        const cti_lane reject = (box2 < 0) | (box2 > d2);
        cti_lane accept;
        if (one) {
            const cti_prism q = cti_step_prism(P, A, B, C, E, d2);
            accept = q.accept | cti_step_edges(P, A, B, C, E, d2, q);
        } else {
            accept = cti_step_corners(P, A, B, C, E, d2);
        }
        /* In integer operations (selects between truth values of different
         * origins do not vectorise): (reject - 1) is 0 or all ones. A lane
         * with a coordinate that is not finite is 3 whatever the steps say
         * (a NaN fails every comparison, but an infinity can pass step 4b's):
         * the one-pair predicate decides it. */
        const cti_lane nf = !(fin == 0);
        const cti_lane r = ((reject - 1) & (2 - accept)) | (nf * 3);
        ok[k] = r;
        nund += r >> 1;
    }
    return nund;
}

/* The one-pair predicate for every lane of the arrays still undecided in
 * o[0..m-1]; lane k of the arrays is lane idx[k] of the batch (idx NULL:
 * k), whose ok it sets. */
static void pb_one_pair(cti_pair_batch *restrict b, const cti_lane *o, const int *idx, int m,
                        ct_real d)
{
    PB_ARRAYS(b);
    for (int k = 0; k < m; k++) {
        if (o[k] < PB_UNDECIDED)
            continue;
        b->nscalar++;
        PB_LANE(k);
        const ct_real p[3] = {P.x, P.y, P.z}, a[3] = {A.x, A.y, A.z}, bb[3] = {B.x, B.y, B.z},
                      c[3] = {C.x, C.y, C.z}, e[3] = {E.x, E.y, E.z};
        b->ok[idx ? idx[k] : k] = ct_pair_may_touch(p, a, bb, c, e, d);
    }
}

/* Stage 1 of the two-stage test (the box and the corners). */
__attribute__((noinline)) static cti_lane pb_stage1(cti_pair_batch *restrict b, ct_real d,
                                                    ct_real d2)
{
    return pb_open(b, d, d2, 0);
}

/* Steps 3 and 4 accept, on the undecided lanes (2) of o[0..m-1]; returns
 * whether any lane is left undecided or not finite. */
static cti_lane pb_accept(const cti_pair_batch *restrict b, cti_lane *restrict o, int m,
                          ct_real d2)
{
    PB_ARRAYS(b);
    cti_lane left = 0;
#pragma omp simd reduction(| : left)
    for (int k = 0; k < m; k++) {
        PB_LANE(k);
        const cti_prism q = cti_step_prism(P, A, B, C, E, d2);
        const cti_lane accept = q.accept | cti_step_edges(P, A, B, C, E, d2, q);
        /* An undecided lane (2) becomes 1 when accepted; 0, 1 and 3 stay. */
        const cti_lane r = o[k] - (o[k] == 2) * accept;
        o[k] = r;
        left |= r >> 1;
    }
    return left;
}

/* On the lanes of o[0..m-1] that steps 3 and 4 left undecided (2): step
 * 2b accepts when `corners` (the one-stage loop left it out), then step
 * 4b rejects; returns whether any lane is left undecided or not finite. */
static cti_lane pb_settle(const cti_pair_batch *restrict b, cti_lane *restrict o, int m,
                          ct_real d2, const int corners)
{
    PB_ARRAYS(b);
    cti_lane left = 0;
#pragma omp simd reduction(| : left)
    for (int k = 0; k < m; k++) {
        PB_LANE(k);
        const cti_lane accept = corners ? cti_step_corners(P, A, B, C, E, d2) : 0;
        const cti_prism q = cti_step_prism(P, A, B, C, E, d2);
        const cti_lane far = cti_step_far(A, B, C, E, q, d2);
        /* 2 becomes 1 when accepted, else 0 when step 4b rejects. */
        const cti_lane dec = accept | ((far & (1 - accept)) << 1);
        const cti_lane r = o[k] - (o[k] == 2) * dec;
        o[k] = r;
        left |= r >> 1;
    }
    return left;
}

/*
 * After the first loop left nund lanes undecided: steps 3 and 4 accept
 * (unless `one`: the one-stage loop ran them), then on the lanes still
 * open step 2b accepts (only if `one`: stage 1 ran it otherwise) and step
 * 4b rejects, which is the one-pair predicate's order, so its answer. Few
 * lanes left (a fine mesh, where the corners decide) are first packed to
 * the front so the vector loops run over them only; many are tested in
 * place, where packing would cost more than it saves. Whatever is still
 * undecided, and every lane with a coordinate that is not finite, goes to
 * the one-pair predicate. Step 4b's loop runs only when a lane is left
 * for it (on the plates and the graded mesh, never).
 */
static void pb_stage2(cti_pair_batch *restrict b, cti_lane nund, ct_real d, ct_real d2,
                      const int one)
{
    const int n = b->n;
    cti_lane *restrict ok = b->ok;
    int idx[CTI_PAIR_BATCH];
    cti_lane okc[CTI_PAIR_BATCH];
    cti_lane *restrict o = ok;
    int m = n;
    if (2 * nund <= n) {
        m = pb_compact(b, idx);
        for (int k = 0; k < m; k++)
            okc[k] = ok[idx[k]];
        o = okc;
    }
    cti_lane left = one ? 1 : pb_accept(b, o, m, d2);
    if (left)
        left = pb_settle(b, o, m, d2, one);
    if (o == okc)
        for (int k = 0; k < m; k++)
            ok[idx[k]] = okc[k];
    if (left)
        pb_one_pair(b, o, o == okc ? idx : NULL, m, d);
}

/* Steps 1, 3 and 4 in one vector loop, without step 2b, then step 2b and
 * step 4b on the lanes left: for batches where few corners are within d.
 * Leaving step 2b out of the first loop changes no answer: steps 2b, 3 and
 * 4 only accept and no reject comes between them, and step 2b runs before
 * step 4b rejects anything. */
__attribute__((noinline)) static void pb_one_stage(cti_pair_batch *restrict b, ct_real d,
                                                   ct_real d2)
{
    const cti_lane nund = pb_open(b, d, d2, 1);
    if (nund)
        pb_stage2(b, nund, d, d2, 1);
}

void cti_pair_batch_test(cti_pair_batch *restrict b, ct_real d)
{
    const int n = b->n;
    const ct_real d2 = d * d;
    /* Step 2b pays only where it lets stage 2 run on few lanes; where it
     * leaves most lanes open (no corner within d: elements large against
     * d), the next PB_SKIP batches run steps 1, 3 and 4 in one loop without
     * it, as one stage. */
    if (b->skip > 0) {
        b->skip--;
        pb_one_stage(b, d, d2);
        return;
    }
    const cti_lane nund = pb_stage1(b, d, d2);
    if (2 * nund > n)
        b->skip = PB_SKIP;
    if (nund)
        pb_stage2(b, nund, d, d2, 0);
}

void cti_pair_batch_decide(cti_pair_batch *restrict pb, const ct_search_input *in,
                           const ct_real *rec, ct_real d)
{
    if (rec)
        cti_pair_batch_load_rec(pb, in->x, in->y, in->z, rec);
    else
        cti_pair_batch_load(pb, in->x, in->y, in->z, in->n1, in->n2, in->n3, in->n4);
    cti_pair_batch_test(pb, d);
}

void cti_pair_batch_collect(cti_pair_batch *restrict pb, const ct_idx *restrict pos,
                            const ct_search_input *in, const ct_real *rec, ct_real d,
                            cti_collect *col, int t, size_t *len, ct_idx *last)
{
    cti_pair_batch_decide(pb, in, rec, d);
    ct_idx *restrict buf = col->buf[t];
    size_t l = *len;
    /* Every segment is written and the length advances by the answer (0
     * or 1): no branch on the answers, which a dense region makes
     * unpredictable. A node's record is opened at its first accepted pair
     * and its count is the length run since then, written when the next
     * record opens and at the end of the batch (the record stays open for
     * the next batch). */
    ct_idx lp = *last;
    int64_t ls = lp >= 0 ? col->start[lp] : 0;
    for (int q = 0; q < pb->n; q++) {
        const ct_idx p = pos[q];
        const size_t okq = (size_t)(pb->ok[q] != 0);
        if (okq & (p != lp)) {
            if (lp >= 0)
                col->count[lp] = (ct_idx)((int64_t)l - ls);
            col->owner[p] = t;
            col->start[p] = ls = (int64_t)l;
            lp = p;
        }
        buf[l] = pb->seg[q];
        l += okq;
    }
    if (lp >= 0)
        col->count[lp] = (ct_idx)((int64_t)l - ls);
    *last = lp;
    *len = l;
    pb->n = 0;
}
