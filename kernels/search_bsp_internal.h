/*
 * search_bsp_internal.h -- the types and box helpers shared by the files of
 * the quick-sort search (private to kernels/search_bsp*.c): search_bsp.c
 * builds the partition, search_bsp_leaf.c computes the tree coordinates and
 * scans the leaves, search_bsp_dense.c decides the dense leaves.
 */
#ifndef CT_SEARCH_BSP_INTERNAL_H
#define CT_SEARCH_BSP_INTERNAL_H

#include "ct_internal.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

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
    bsp_f f = (bsp_f)v, d = cti_next_down_f(f);
    return (double)f > v ? d : f;
}

static inline bsp_f bsp_up(double v)
{
    bsp_f f = (bsp_f)v, u = cti_next_up_f(f);
    return (double)f < v ? u : f;
}

/* Blocks of the deterministic per-block loops over nodes and segments. */
#define BSP_BLOCKS 64
#ifndef BSP_TASKS_PER_THREAD
#define BSP_TASKS_PER_THREAD 16
#endif

typedef struct bsp_box {
    bsp_f lo[3], hi[3];
} bsp_box;

/* Arrays of a dense leaf's corner scratch (search_bsp_dense.c). */
#define BSP_LC 25

/* A thread's private scratch:
 *  - a: the two index lists of a split above the task cutoff, before they
 *    move to the shared arena;
 *  - rec: the segment lists of the subtree it runs below the cutoff, as
 *    records (BSP_REC floats, the segment's number in lane 3), so that a
 *    split and a leaf read their list with unit stride instead of
 *    gathering one record per index; offsets, not pointers, since it may
 *    move when it grows (rcap in records);
 *  - lb, lid: a leaf's segment boxes (6 arrays, upper bounds negated as in
 *    the records) and numbers, of lbcap, a multiple of 8;
 *  - lc, lcn: a dense leaf's segments' corners and box bounds (BSP_LC
 *    arrays of lccap, search_bsp_dense.c) and their node numbers (4 arrays
 *    of lccap);
 *  - lr, lrcap: a dense leaf's answers, a byte per node and 8 segments;
 *  - part, partcap: the partition's scratch (search_bsp_partition.c), the
 *    four arrays of a box's right part, in floats. */
typedef struct bsp_stack {
    ct_idx *a;
    size_t cap;
    bsp_f *rec;
    size_t rcap;
    bsp_f *lb;
    ct_idx *lid;
    size_t lbcap;
    ct_real *lc;
    ct_idx *lcn;
    size_t lccap;
    uint8_t *lr;
    size_t lrcap;
    bsp_f *part;
    size_t partcap;
    char pad[128 - 6 * sizeof(size_t) - 8 * sizeof(void *)];
} bsp_stack;
_Static_assert(sizeof(bsp_stack) % 64 == 0, "a thread's scratch fills whole cache lines");

typedef struct bsp_state {
    size_t nodecap, segcap, arenacap;
    bsp_f *nx, *ny, *nz; /* coordinates of the nodes in tree order */
    ct_idx *nid;           /* their positions in in->sec */
    bsp_f *sb;           /* per segment: inflated box, a BSP_REC record */
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
    int dense;    /* ct_search_params.dense */
    int err;      /* CT_ERR_NOMEM when a buffer could not grow */
    int overflow; /* the shared arena was too small */
} bsp_ctx;

/* A segment's inflated box is one 32-byte record of 8 floats,
 * lo[0..2], 0, -hi[0..2], 0: with the key of a box x, (x.hi[0..2], +inf,
 * -x.lo[0..2], +inf), the segment meets x exactly when every lane of the
 * record is <= the key's (negation is exact; lanes 3 and 7 are not
 * compared), one 8-lane compare. NaN bounds never reach a record (they become
 * infinite). */
#define BSP_REC 8

_Static_assert(sizeof(ct_idx) == sizeof(bsp_f), "a segment number fits a record's lane 3");

/* A list record: segment j's record with j's bits in lane 3. */
static inline void bsp_rec_put(bsp_f *restrict dst, const bsp_f *restrict sbrec, ct_idx j)
{
    memcpy(dst, sbrec, BSP_REC * sizeof *dst);
    memcpy(dst + 3, &j, sizeof j);
}

static inline ct_idx bsp_rec_id(const bsp_f *r)
{
    ct_idx j;
    memcpy(&j, r + 3, sizeof j);
    return j;
}

#if defined(__AVX__)
typedef __m256 bsp_key;
static inline bsp_key bsp_key_of(const bsp_box *x)
{
    return _mm256_setr_ps(x->hi[0], x->hi[1], x->hi[2], (bsp_f)INFINITY, -x->lo[0], -x->lo[1],
                          -x->lo[2], (bsp_f)INFINITY);
}
static inline int rec_meets(const bsp_f *restrict r, bsp_key k)
{
    /* Lane 3 of a list record holds a number, not a bound: left out. */
    return (_mm256_movemask_ps(_mm256_cmp_ps(_mm256_load_ps(r), k, _CMP_LE_OQ)) & 0x77) == 0x77;
}
#else
typedef bsp_box bsp_key;
static inline bsp_key bsp_key_of(const bsp_box *x)
{
    return *x;
}
static inline int rec_meets(const bsp_f *restrict r, bsp_key k)
{
    /* Bitwise and: no branch to mispredict. */
    return (r[0] <= k.hi[0]) & (r[1] <= k.hi[1]) & (r[2] <= k.hi[2]) & (r[4] <= -k.lo[0]) &
           (r[5] <= -k.lo[1]) & (r[6] <= -k.lo[2]);
}
#endif

static inline void box_empty(bsp_box *b)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = (bsp_f)INFINITY;
        b->hi[k] = -(bsp_f)INFINITY;
    }
}

/* The min/max reductions of bsp_box_of as a simd loop: gcc vectorises them
 * only when told (they are not fast-math min/max); clang 14 cannot
 * vectorise this select form at all and, asked to, fails the build
 * (-Wpass-failed), so it gets the plain loop. The result is the same
 * either way: min and max do not depend on the order. */
#if defined(__clang__)
#define BSP_SIMD_MINMAX
#else
#define BSP_SIMD_MINMAX                                                                    \
    _Pragma("omp simd reduction(min : l0, l1, l2) reduction(max : h0, h1, h2)")
#endif

/* The tight box of the tree coordinates [i0, i1) (NaN compares false and
 * is left out, as in box_add). */
static inline void bsp_box_of(const bsp_f *restrict x, const bsp_f *restrict y,
                              const bsp_f *restrict z, ct_idx i0, ct_idx i1, bsp_box *b)
{
    bsp_f l0 = (bsp_f)INFINITY, l1 = (bsp_f)INFINITY, l2 = (bsp_f)INFINITY;
    bsp_f h0 = -(bsp_f)INFINITY, h1 = -(bsp_f)INFINITY, h2 = -(bsp_f)INFINITY;
    BSP_SIMD_MINMAX
    for (ct_idx i = i0; i < i1; i++) {
        l0 = x[i] < l0 ? x[i] : l0;
        h0 = x[i] > h0 ? x[i] : h0;
        l1 = y[i] < l1 ? y[i] : l1;
        h1 = y[i] > h1 ? y[i] : h1;
        l2 = z[i] < l2 ? z[i] : l2;
        h2 = z[i] > h2 ? z[i] : h2;
    }
    b->lo[0] = l0, b->lo[1] = l1, b->lo[2] = l2;
    b->hi[0] = h0, b->hi[1] = h1, b->hi[2] = h2;
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

/* The box test of a node (px, py, pz) against 8 segments of a leaf, from
 * box q of the leaf's arrays (l0.. lower bounds, m0.. negated upper
 * bounds): bit e of the result is set when the node is in box q + e. With
 * AVX, six 8-lane compares and a mask. */
#if defined(__AVX__)
typedef struct bsp_pt {
    __m256 x, y, z, mx, my, mz;
} bsp_pt;
static inline bsp_pt bsp_pt_of(bsp_f px, bsp_f py, bsp_f pz)
{
    bsp_pt p = {_mm256_set1_ps(px),  _mm256_set1_ps(py),  _mm256_set1_ps(pz),
                _mm256_set1_ps(-px), _mm256_set1_ps(-py), _mm256_set1_ps(-pz)};
    return p;
}
static inline unsigned bsp_leaf_mask8(const bsp_f *restrict l0, const bsp_f *restrict l1,
                                      const bsp_f *restrict l2, const bsp_f *restrict m0,
                                      const bsp_f *restrict m1, const bsp_f *restrict m2,
                                      const bsp_pt *p)
{
    __m256 c = _mm256_cmp_ps(_mm256_load_ps(l0), p->x, _CMP_LE_OQ);
    c = _mm256_and_ps(c, _mm256_cmp_ps(_mm256_load_ps(m0), p->mx, _CMP_LE_OQ));
    c = _mm256_and_ps(c, _mm256_cmp_ps(_mm256_load_ps(l1), p->y, _CMP_LE_OQ));
    c = _mm256_and_ps(c, _mm256_cmp_ps(_mm256_load_ps(m1), p->my, _CMP_LE_OQ));
    c = _mm256_and_ps(c, _mm256_cmp_ps(_mm256_load_ps(l2), p->z, _CMP_LE_OQ));
    c = _mm256_and_ps(c, _mm256_cmp_ps(_mm256_load_ps(m2), p->mz, _CMP_LE_OQ));
    return (unsigned)_mm256_movemask_ps(c);
}
#else
typedef struct bsp_pt {
    bsp_f x, y, z, mx, my, mz;
} bsp_pt;
static inline bsp_pt bsp_pt_of(bsp_f px, bsp_f py, bsp_f pz)
{
    bsp_pt p = {px, py, pz, -px, -py, -pz};
    return p;
}
static inline unsigned bsp_leaf_mask8(const bsp_f *restrict l0, const bsp_f *restrict l1,
                                      const bsp_f *restrict l2, const bsp_f *restrict m0,
                                      const bsp_f *restrict m1, const bsp_f *restrict m2,
                                      const bsp_pt *p)
{
    unsigned m = 0;
    for (int e = 0; e < 8; e++)
        m |= (unsigned)((l0[e] <= p->x) & (m0[e] <= p->mx) & (l1[e] <= p->y) &
                        (m1[e] <= p->my) & (l2[e] <= p->z) & (m2[e] <= p->mz))
             << e;
    return m;
}
#endif

/* Boxes of at most this many nodes are partitioned stably, through the
 * thread's scratch (cti_bsp_partition); larger ones, the few splits at the
 * top of the tree, in place by Hoare's partition, so the scratch stays
 * within 1 MiB a thread. Which one runs depends on the box alone, never on
 * the thread count. */
#define BSP_PART_MAX 65536

/* Partition the tree order [n0, n1) about `mid` on axis ax (0: nx, 1: ny,
 * 2: nz): the nodes with coordinate < mid first, then the others, each
 * part in its previous order (search_bsp_partition.c); returns the split
 * index. scratch holds 4 * (n1 - n0) floats: the two parts' vector stores
 * never reach past the nodes read so far. */
ct_idx cti_bsp_partition(bsp_f *restrict nx, bsp_f *restrict ny, bsp_f *restrict nz,
                         ct_idx *restrict nid, ct_idx n0, ct_idx n1, int ax, bsp_f mid,
                         bsp_f *restrict scratch);

/* The tree coordinates of a search (search_bsp_leaf.c): the origin c->o,
 * the inflated segment boxes st->sb, and the nodes inside the union of the
 * segment boxes in st->nx, ny, nz, nid (block order), with their tight box
 * in *root. Returns the number of nodes kept. */
ct_idx cti_bsp_tree_coords(bsp_ctx *c, bsp_box *root);

/* Test every node of [n0, n1) of the tree order against the sorted segment
 * list of ns segments and collect the pairs (search_bsp_leaf.c): a list of
 * numbers segs, or (cti_bsp_leaf_rec) a list of records. */
void cti_bsp_leaf(bsp_ctx *c, ct_idx n0, ct_idx n1, const ct_idx *restrict segs, ct_idx ns);
void cti_bsp_leaf_rec(bsp_ctx *c, ct_idx n0, ct_idx n1, const bsp_f *restrict recs, ct_idx ns);

/* n new zeroed buffers of bytes[i] each into q[i], all or none; 0 (and the
 * error flag) when one cannot be allocated (search_bsp_leaf.c). */
int cti_bsp_alloc(bsp_ctx *c, int n, const size_t *bytes, void **q);

/* A dense leaf (search_bsp_dense.c): with the hull filter, when the first
 * nodes of [n0, n1) pass the box test of most of the segments they meet in
 * their groups of 8 (cti_bsp_leaf_is_dense), the leaf is decided by
 * cti_bsp_leaf_dense: the predicate's first steps in SIMD lanes over the
 * leaf's segments with the node broadcast, the rest in a batch. The leaf's
 * boxes are in sk->lb (padded to a multiple of 8). */
enum { BSP_DENSE_SAMPLE = 8, BSP_DENSE_MAX_SEGS = 2048 };

/* The box-test masks of a leaf's first n nodes (one byte per node and group
 * of 8 segments, ng groups a node), computed once to choose the path and
 * read again by the path chosen. */
typedef struct bsp_sample {
    ct_idx n, ng;
    uint8_t m[BSP_DENSE_SAMPLE * (BSP_DENSE_MAX_SEGS / 8)];
} bsp_sample;

/* The mask of the leaf's node i (counted from the leaf's first) against
 * group g: the sample's when i < nsmp (sm: the sample's bytes, ng groups a
 * node), else computed from the leaf's boxes lb (w apart). Callers pass the
 * sample's count and bytes as locals, which the collector's stores cannot
 * alias. */
static inline unsigned bsp_mask_of(const uint8_t *restrict sm, ct_idx nsmp, ct_idx ng, ct_idx i,
                                   ct_idx g, const bsp_f *restrict lb, size_t w,
                                   const bsp_pt *pt)
{
    if (i < nsmp)
        return sm[(size_t)i * (size_t)ng + (size_t)g];
    const size_t q0 = 8 * (size_t)g;
    return bsp_leaf_mask8(lb + q0, lb + w + q0, lb + 2 * w + q0, lb + 3 * w + q0,
                          lb + 4 * w + q0, lb + 5 * w + q0, pt);
}

int cti_bsp_leaf_is_dense(const bsp_ctx *c, const bsp_stack *sk, ct_idx n0, ct_idx n1,
                          ct_idx ns, bsp_sample *smp);
void cti_bsp_leaf_dense(bsp_ctx *c, bsp_stack *sk, ct_idx n0, ct_idx n1,
                        const ct_idx *restrict segs, ct_idx ns, const bsp_sample *smp);

#endif /* CT_SEARCH_BSP_INTERNAL_H */
