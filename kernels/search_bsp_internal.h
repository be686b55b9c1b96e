/*
 * search_bsp_internal.h -- the types and box helpers shared by the files of
 * the quick-sort search (private to kernels/search_bsp*.c): search_bsp.c
 * builds the partition, search_bsp_leaf.c computes the tree coordinates and
 * scans the leaves.
 */
#ifndef CT_SEARCH_BSP_INTERNAL_H
#define CT_SEARCH_BSP_INTERNAL_H

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
    return (double)f > v ? cti_next_down_f(f) : f;
}

static inline bsp_f bsp_up(double v)
{
    bsp_f f = (bsp_f)v;
    return (double)f < v ? cti_next_up_f(f) : f;
}

/* Blocks of the deterministic per-block loops over nodes and segments. */
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

/* The tree coordinates of a search (search_bsp_leaf.c): the origin c->o,
 * the inflated segment boxes st->sb, and the nodes inside the union of the
 * segment boxes in st->nx, ny, nz, nid (block order), with their tight box
 * in *root. Returns the number of nodes kept. */
ct_idx cti_bsp_tree_coords(bsp_ctx *c, bsp_box *root);

/* Test every node of [n0, n1) of the tree order against the sorted segment
 * list segs[0..ns-1] and collect the pairs (search_bsp_leaf.c). */
void cti_bsp_leaf(bsp_ctx *c, ct_idx n0, ct_idx n1, const ct_idx *restrict segs, ct_idx ns);

#endif /* CT_SEARCH_BSP_INTERNAL_H */
