/*
 * ct_internal.h -- internal helpers of libcontact (prefix cti_). Not part of
 * the public API; kernels include it after contact.h.
 */
#ifndef CT_INTERNAL_H
#define CT_INTERNAL_H

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact.h"

#ifdef _OPENMP
#include <omp.h>
static inline int cti_num_threads(void) { return omp_get_max_threads(); }
static inline int cti_thread_id(void) { return omp_get_thread_num(); }
/* Inside a caller's parallel region a kernel opens no team of its own (a
 * nested region would run on one thread anyway, at the cost of making it). */
static inline int cti_in_parallel(void) { return omp_in_parallel(); }
static inline int cti_team_size(void) { return omp_get_num_threads(); }
#else
static inline int cti_num_threads(void) { return 1; }
static inline int cti_thread_id(void) { return 0; }
static inline int cti_in_parallel(void) { return 0; }
static inline int cti_team_size(void) { return 1; }
#endif

/* Parallel loops that run serially below a size. A `#pragma omp parallel
 * for if (c)` whose c is false still enters the OpenMP runtime: gcc's
 * libgomp then builds, allocates and frees a one-thread team and makes a
 * futex system call at its closing barrier, a microsecond or more on a
 * virtual machine. A small model ran about 70 such regions per cycle in its
 * contact and node loops (the showcase: a third of its contact time).
 * CTI_PAR_FOR runs the loop, written once, as a parallel loop when c holds
 * outside a parallel region (inside one, a team would be of one thread:
 * the cycle's blocks call kernels on up to a few thousand pairs) and as a
 * plain loop (vectorised by the compiler as it can) otherwise;
 * CTI_PAR_FOR_SIMD the same with `simd`, the plain loop under `omp simd`.
 * Each iteration does the same arithmetic on either branch, and the
 * reductions these loops use (min, max, |, integer +) are exact, so the
 * results do not depend on the branch. The loop may hold no #pragma (a
 * directive inside a macro argument is undefined): a loop that needs one
 * calls a function; CTI_PAR_FOR_SIMD takes no reduction clause. Usage:
 *   CTI_PAR_FOR(n > CTI_PAR_MIN, (schedule(static) reduction(min : d)),
 *   for (ct_idx k = 0; k < n; k++) {
 *       ...
 *   });
 */
#define CTI_PRAGMA_(x) _Pragma(#x)
#define CTI_PRAGMA(x) CTI_PRAGMA_(x)
#define CTI_UNPAREN(...) __VA_ARGS__
#define CTI_PAR_FOR(cond, clauses, ...)                                                        \
    do {                                                                                       \
        if ((cond) && !cti_in_parallel()) {                                                    \
            CTI_PRAGMA(omp parallel for CTI_UNPAREN clauses)                                  \
            __VA_ARGS__                                                                        \
        } else {                                                                               \
            __VA_ARGS__                                                                        \
        }                                                                                      \
    } while (0)
#define CTI_PAR_FOR_SIMD(cond, clauses, ...)                                                   \
    do {                                                                                       \
        if ((cond) && !cti_in_parallel()) {                                                    \
            CTI_PRAGMA(omp parallel for simd CTI_UNPAREN clauses)                             \
            __VA_ARGS__                                                                        \
        } else {                                                                               \
            _Pragma("omp simd") __VA_ARGS__                                                    \
        }                                                                                      \
    } while (0)

/* A function, and a loop in it, that the compiler must not vectorise: the
 * copies of indexed coordinates or velocities into unit-stride block arrays
 * (narrow phase, batch predicate, relative velocity). Vectorised, their
 * indexed loads become vector gathers, which AMD Zen 4 runs several times
 * slower than the scalar loads. gcc has no loop pragma for it before gcc 14,
 * so the function's optimisation options say it; clang has the pragma. */
#if defined(__clang__)
#define CTI_NOVEC
#define CTI_NOVEC_LOOP _Pragma("clang loop vectorize(disable) interleave(disable)")
#elif defined(__GNUC__)
#define CTI_NOVEC __attribute__((optimize("no-tree-vectorize")))
#define CTI_NOVEC_LOOP
#else
#define CTI_NOVEC
#define CTI_NOVEC_LOOP
#endif

/* The float next below f (f not NaN), as nextafterf(f, -INFINITY) but
 * inline: the libm call was 2 % of the quick-sort search, which rounds six
 * box bounds per segment outward. -INFINITY stays; both zeros go to the
 * smallest negative subnormal. */
static inline float cti_next_down_f(float f)
{
    /* Selects, not branches: a caller rounding bounds outward decides at
     * random whether to step at all, and a branch there mispredicts. */
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    uint32_t r = f > 0 ? u - 1 : u + 1;     /* away from +0 on the bits */
    r = (u & 0x7fffffffu) == 0 ? 0x80000001u : r; /* +-0 -> -0x1p-149 */
    r = f == -INFINITY ? u : r;
    memcpy(&f, &r, sizeof f);
    return f;
}

/* The float next above f (f not NaN): nextafterf(f, INFINITY). */
static inline float cti_next_up_f(float f) { return -cti_next_down_f(-f); }

/* The m-th position of a sample of [0, n), stream `stream`, n > 0: drawn
 * by a 64-bit mix (SplitMix64's finaliser), with replacement. The samples
 * that decide how to search use it rather than a regular stride, which
 * aliases with a structured mesh's rows (a stride of nseg / 256 fell on
 * every fourth row end of the folded sheet). */
static inline ct_idx cti_sample_index(uint64_t m, uint64_t stream, ct_idx n)
{
    uint64_t z = (stream << 32) + (m + 1) * UINT64_C(0x9e3779b97f4a7c15);
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    z ^= z >> 31;
    return (ct_idx)(z % (uint64_t)n);
}

/* ---- Precision-generic maths ------------------------------------------ */

#ifdef CT_SINGLE
#define CTI_SQRT sqrtf
#define CTI_FABS fabsf
#define CTI_LOG logf
#define CTI_LOG1P log1pf
#define CTI_FMIN fminf
#define CTI_FMAX fmaxf
#define CTI_EPS 1.1920929e-07f
#define CTI_HUGE 3.0e38f
#define CTI_REAL_MAX FLT_MAX /* the largest finite ct_real */
#else
#define CTI_SQRT sqrt
#define CTI_FABS fabs
#define CTI_LOG log
#define CTI_LOG1P log1p
#define CTI_FMIN fmin
#define CTI_FMAX fmax
#define CTI_EPS 2.220446049250313e-16
#define CTI_HUGE 1.0e300
#define CTI_REAL_MAX DBL_MAX
#endif

/* a * b + c with one rounding where the processor fuses them (FMA).
 * Written out (the build does not contract on its own, -ffp-contract=off),
 * so a scalar call and a vector lane compute the same roundings; a build
 * without FMA rounds twice, the same way in both. */
#if defined(__FMA__) && defined(CT_SINGLE)
#define CTI_FMA(a, b, c) fmaf(a, b, c)
#elif defined(__FMA__)
#define CTI_FMA(a, b, c) fma(a, b, c)
#else
#define CTI_FMA(a, b, c) ((a) * (b) + (c))
#endif

#define CTI_MIN(a, b) ((a) < (b) ? (a) : (b))
#define CTI_MAX(a, b) ((a) > (b) ? (a) : (b))

/* ---- Non-finite values -------------------------------------------------- */

/* x - x is 0 for a finite x and NaN for an infinite or NaN one: exact, since
 * the build uses -fno-math-errno -fno-trapping-math but not -ffast-math
 * (which would let the compiler fold it to 0). */
#define CTI_NONFINITE(x) (!((x) - (x) == 0))

/*
 * The force and friction kernels check their values by a witness sum: one
 * term per checked value, +-0 for a finite value and NaN for an infinite or
 * NaN one, summed per pair and added into one accumulator per block inside
 * the vector loop that computes the pairs (an `omp simd` reduction: no
 * branch, no extra pass over memory). The sum stays +-0 while every term
 * is and is NaN as soon as one is, in any order of the additions, so the
 * verdict depends neither on the vector width nor on the thread count; on
 * failure the kernels that report an index find it by a second pass.
 *  - CTI_NF(x): x's term, x - x;
 *  - cti_nf_add(acc, x): acc plus x's term in one operation where the
 *    processor fuses a multiply and an add: x * 0 + acc, exact (x * 0 is
 *    +-0 for a finite x, NaN otherwise; the build does not contract on its
 *    own, -ffp-contract=off, so it is written out); without FMA, the
 *    subtraction and the addition.
 * A value whose NaN or negative values have a meaning (a penetration: no
 * contact) enters as its select (p > 0 ? p : 0), whose term is NaN for +inf
 * only. A pair's terms go into short chains of their own, added to the
 * loop's accumulator once: a long chain runs at the fused operation's
 * latency, and chained into the accumulator every iteration would wait for
 * the one before. Each term costs an operation a pair, which in cache is
 * 4 % of the lean normal-force loop: the kernels check the fewest values
 * that cover their inputs (an input that always reaches an output is
 * covered by that output's term).
 */
#define CTI_NF(x) ((x) - (x))
static inline ct_real cti_nf_add(ct_real acc, ct_real x)
{
#if defined(__FMA__) && defined(CT_SINGLE)
    return fmaf(x, 0.0f, acc);
#elif defined(__FMA__)
    return fma(x, 0.0, acc);
#else
    return acc + CTI_NF(x);
#endif
}

/* Fill a ct_diag (when not NULL) and return the code. */
int cti_fail(ct_diag *d, int code, int64_t index, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Grow an aligned array to hold at least `need` elements of `size` bytes,
 * keeping the first `keep` elements. *cap is in elements. */
int cti_grow(void **p, size_t *cap, size_t need, size_t size, size_t keep);

/* Replace the index arrays *a and *b by new ones of ncap entries (zeroed
 * past the first n, which are copied): both or, when out of memory
 * (CT_ERR_NOMEM), neither. The pair lists' growth (their node and segment
 * columns). */
int cti_renew_two(ct_idx **a, ct_idx **b, size_t n, size_t ncap);

/* Exclusive prefix sum of cnt[0..n-1] into off[0..n] (off[n] = total), in
 * parallel (two passes over per-thread blocks). cnt and off may alias.
 * The result does not depend on the thread count. Must be called outside a
 * parallel region. */
int64_t cti_prefix_sum(const ct_idx *cnt, int64_t *off, int64_t n);
ct_idx cti_prefix_sum_idx(const ct_idx *cnt, ct_idx *off, ct_idx n);

/* ---- The shared pair predicate ----------------------------------------- */

/* Squared distance from p to triangle a b c (closest point by Voronoi
 * regions; degenerate triangles fall back to their edges). */
ct_real cti_dist2_point_triangle(const ct_real p[3], const ct_real a[3],
                                 const ct_real b[3], const ct_real c[3]);

/* Squared distance from p to segment a b. */
ct_real cti_dist2_point_edge(const ct_real p[3], const ct_real a[3], const ct_real b[3]);

/* Load the four corners of segment s. */
static inline void cti_load_seg(const ct_real *restrict x, const ct_real *restrict y,
                                const ct_real *restrict z, ct_idx i1, ct_idx i2,
                                ct_idx i3, ct_idx i4, ct_real a[3], ct_real b[3],
                                ct_real c[3], ct_real d[3])
{
    a[0] = x[i1]; a[1] = y[i1]; a[2] = z[i1];
    b[0] = x[i2]; b[1] = y[i2]; b[2] = z[i2];
    c[0] = x[i3]; c[1] = y[i3]; c[2] = z[i3];
    d[0] = x[i4]; d[1] = y[i4]; d[2] = z[i4];
}

/* The predicate every search applies to every pair it reports, by global
 * indices. `self` excludes a node's own segments; `filter` is the input's
 * ct_search_filter. */
static inline int cti_pair_test_f(const ct_real *restrict x, const ct_real *restrict y,
                                  const ct_real *restrict z, ct_idx node, ct_idx i1,
                                  ct_idx i2, ct_idx i3, ct_idx i4, ct_real d, int self,
                                  int filter)
{
    if (self && (node == i1 || node == i2 || node == i3 || node == i4))
        return 0;
    ct_real p[3] = {x[node], y[node], z[node]};
    ct_real a[3], b[3], c[3], e[3];
    cti_load_seg(x, y, z, i1, i2, i3, i4, a, b, c, e);
    return filter == CT_FILTER_BOX ? ct_pair_box_near(p, a, b, c, e, d)
                                   : ct_pair_may_touch(p, a, b, c, e, d);
}

/* ---- The hull predicate over a batch of pairs (predicate_batch.c) ------ */

/* An integer as wide as ct_real: truth values computed in vector lanes
 * next to ct_real values (a narrower type would need conversions that
 * the compiler does not vectorise). */
#ifdef CT_SINGLE
typedef int32_t cti_lane;
#else
typedef int64_t cti_lane;
#endif

/* Pairs per batch: the batch's coordinates (15 arrays) stay in L1. */
#ifndef CTI_PAIR_BATCH
#define CTI_PAIR_BATCH 128
#endif

/* Two reals stored together: a GNU vector of two, which gcc and clang
 * store at once from two scalar loads (a load, a load-and-insert, one
 * store). The block copies of the batch predicate and the narrow phase
 * store their coordinates this way, two to an entry, arr[2 k] and
 * arr[2 k + 1] for lane k, which halves their stores; the vector loops
 * that read them separate the two with permutes. */
typedef ct_real cti_two __attribute__((vector_size(2 * sizeof(ct_real))));
#define CTI_PUT2(arr, k, u, v) (*(cti_two *)(void *)&(arr)[2 * (k)] = (cti_two){(u), (v)})

/* The coordinates (x, y, z) of nodes i0..i3 as entry k of that layout: d[v]
 * receives (x, y) of node v, d[4] (z of nodes 0 and 1), d[5] (z of nodes 2
 * and 3). Loads scalar, 6 stores. */
static inline __attribute__((always_inline)) void
cti_put4(ct_real *const d[6], ct_idx k, const ct_real *restrict x, const ct_real *restrict y,
         const ct_real *restrict z, ct_idx i0, ct_idx i1, ct_idx i2, ct_idx i3)
{
    CTI_PUT2(d[0], k, x[i0], y[i0]);
    CTI_PUT2(d[1], k, x[i1], y[i1]);
    CTI_PUT2(d[2], k, x[i2], y[i2]);
    CTI_PUT2(d[3], k, x[i3], y[i3]);
    CTI_PUT2(d[4], k, z[i0], z[i1]);
    CTI_PUT2(d[5], k, z[i2], z[i3]);
}

/* Packed coordinates (ct_coords_pack): node i's (x, y, z, w) at
 * xyzw[4 i..4 i + 3], aligned to their size, loaded as one vector. The
 * copies from them store the same layout as cti_put4 / cti_put5: (x, y) is
 * the vector's low half, and the z of two nodes one shuffle of theirs. */
typedef ct_real cti_four __attribute__((vector_size(4 * sizeof(ct_real))));
#define CTI_XYZW(w, i) (*(const cti_four *)(const void *)&(w)[4 * (size_t)(i)])
#define CTI_PUT2V(arr, k, v) (*(cti_two *)(void *)&(arr)[2 * (k)] = (v))
#define CTI_LO2(a) __builtin_shufflevector((a), (a), 0, 1)
#define CTI_ZZ(a, b) __builtin_shufflevector((a), (b), 2, 6)

/* cti_put4 from packed coordinates: the same stores, 4 vector loads. */
static inline __attribute__((always_inline)) void
cti_put4_packed(ct_real *const d[6], ct_idx k, const ct_real *restrict w, ct_idx i0, ct_idx i1,
                ct_idx i2, ct_idx i3)
{
    const cti_four v0 = CTI_XYZW(w, i0), v1 = CTI_XYZW(w, i1);
    const cti_four v2 = CTI_XYZW(w, i2), v3 = CTI_XYZW(w, i3);
    CTI_PUT2V(d[0], k, CTI_LO2(v0));
    CTI_PUT2V(d[1], k, CTI_LO2(v1));
    CTI_PUT2V(d[2], k, CTI_LO2(v2));
    CTI_PUT2V(d[3], k, CTI_LO2(v3));
    CTI_PUT2V(d[4], k, CTI_ZZ(v0, v1));
    CTI_PUT2V(d[5], k, CTI_ZZ(v2, v3));
}

/* The same for five nodes: d[v] (x, y) of node v for v < 5, d[5] and d[6]
 * the z of nodes 0, 1 and 2, 3, d[7][k] the z of node 4. 8 stores. */
static inline __attribute__((always_inline)) void
cti_put5(ct_real *const d[8], ct_idx k, const ct_real *restrict x, const ct_real *restrict y,
         const ct_real *restrict z, ct_idx i0, ct_idx i1, ct_idx i2, ct_idx i3, ct_idx i4)
{
    ct_real *const d4[6] = {d[0], d[1], d[2], d[3], d[5], d[6]};
    cti_put4(d4, k, x, y, z, i0, i1, i2, i3);
    CTI_PUT2(d[4], k, x[i4], y[i4]);
    d[7][k] = z[i4];
}

/* cti_put5 from packed coordinates. */
static inline __attribute__((always_inline)) void
cti_put5_packed(ct_real *const d[8], ct_idx k, const ct_real *restrict w, ct_idx i0, ct_idx i1,
                ct_idx i2, ct_idx i3, ct_idx i4)
{
    ct_real *const d4[6] = {d[0], d[1], d[2], d[3], d[5], d[6]};
    cti_put4_packed(d4, k, w, i0, i1, i2, i3);
    const cti_four v4 = CTI_XYZW(w, i4);
    CTI_PUT2V(d[4], k, CTI_LO2(v4));
    d[7][k] = v4[2];
}

/* A batch of candidate pairs and, once loaded, their coordinates. A caller
 * fills node[], seg[] and n, loads, tests, and reads ok[] (0 or 1). Lives on
 * the caller's stack or in its workspace: no allocation. The coordinates
 * are two to an entry (CTI_PUT2): (x, y) of the node P and of the corners
 * A, B, C, E, then (Pz, Az), (Bz, Cz); Ez alone. */
typedef struct cti_pair_batch {
    _Alignas(64) ct_real pxy[2 * CTI_PAIR_BATCH];
    ct_real axy[2 * CTI_PAIR_BATCH], bxy[2 * CTI_PAIR_BATCH];
    ct_real cxy[2 * CTI_PAIR_BATCH], exy[2 * CTI_PAIR_BATCH];
    ct_real paz[2 * CTI_PAIR_BATCH], bcz[2 * CTI_PAIR_BATCH], ez[CTI_PAIR_BATCH];
    ct_idx node[CTI_PAIR_BATCH], seg[CTI_PAIR_BATCH];
    cti_lane ok[CTI_PAIR_BATCH];
    int n;
    int skip;        /* batches still to run without the corner step */
    int64_t nscalar; /* pairs left to the one-pair predicate, summed */
} cti_pair_batch;

/* Lane k's coordinates: the node p and the corners a, b, c, e. */
static inline void cti_pair_batch_set(cti_pair_batch *restrict pb, int k, const ct_real p[3],
                                      const ct_real a[3], const ct_real b[3],
                                      const ct_real c[3], const ct_real e[3])
{
    ct_real *const d[8] = {pb->pxy, pb->axy, pb->bxy, pb->cxy,
                           pb->exy, pb->paz, pb->bcz, pb->ez};
    const ct_real x[5] = {p[0], a[0], b[0], c[0], e[0]}, y[5] = {p[1], a[1], b[1], c[1], e[1]},
                  z[5] = {p[2], a[2], b[2], c[2], e[2]};
    cti_put5(d, k, x, y, z, 0, 1, 2, 3, 4);
}

/* An empty batch (its coordinates are loaded later). */
static inline void cti_pair_batch_init(cti_pair_batch *pb)
{
    pb->n = 0;
    pb->skip = 0;
    pb->nscalar = 0;
}

/* Load the coordinates of the batch's pairs: the corners by the segments'
 * node indices, or (_rec) from 12-value corner records per segment. The
 * indices must be valid (the caller checked them). */
void cti_pair_batch_load(cti_pair_batch *restrict b, const ct_real *restrict x,
                         const ct_real *restrict y, const ct_real *restrict z,
                         const ct_idx *restrict n1, const ct_idx *restrict n2,
                         const ct_idx *restrict n3, const ct_idx *restrict n4);
void cti_pair_batch_load_rec(cti_pair_batch *restrict b, const ct_real *restrict x,
                             const ct_real *restrict y, const ct_real *restrict z,
                             const ct_real *restrict rec);

/* ok[k] = ct_pair_may_touch of pair k at distance d, for k < n: the same
 * answer, bit for bit, decided mostly in vector lanes. */
void cti_pair_batch_test(cti_pair_batch *restrict b, ct_real d);

/* The hull predicate (kept for callers that do not choose a filter). */
static inline int cti_pair_test(const ct_real *restrict x, const ct_real *restrict y,
                                const ct_real *restrict z, ct_idx node, ct_idx i1,
                                ct_idx i2, ct_idx i3, ct_idx i4, ct_real d, int self)
{
    return cti_pair_test_f(x, y, z, node, i1, i2, i3, i4, d, self, CT_FILTER_HULL);
}

/* ---- Candidate collection ---------------------------------------------- */

/*
 * Searches that visit secondary nodes in an order of their own (cell order,
 * tree order) store each node's candidate segments, in increasing segment
 * order, in a per-thread buffer and record where: owner[i] (thread), start[i]
 * and count[i] for secondary position i (a count of 0 needs no record). cti_collect_finish() then writes the
 * canonical pair list (secondary order, then segment) in parallel; the
 * result does not depend on which thread found what.
 */
typedef struct cti_collect {
    int nthr;           /* buffers in use */
    int maxthr;         /* buffers allocated */
    ct_idx **buf;       /* per-thread segment buffers */
    size_t *len, *cap;  /* per-thread fill and capacity (elements) */
    ct_idx nsec, seccap;
    int32_t *owner;     /* per secondary */
    int64_t *start;     /* per secondary */
    ct_idx *count;      /* per secondary */
    int64_t *off;       /* scratch: output offsets (nsec + 1) */
    int err;            /* set by a thread whose buffer could not grow */
    int64_t max;        /* the pair limit (cti_search_max_pairs; 0: 2^31 - 1) */
} cti_collect;

/* Prepare for nsec secondaries and the current thread count (outside a
 * parallel region). Counts are zeroed. */
int cti_collect_begin(cti_collect *c, ct_idx nsec);

/* Grow thread t's buffer to hold `extra` more entries beyond c->len[t]
 * (inside the parallel region; sets c->err on failure). A thread records a
 * node's list by writing owner[i], start[i] and count[i] for its secondary
 * position i; segments in increasing order. */
int cti_collect_room(cti_collect *c, int t, size_t extra);

/* Convenience for callers without a local fill: append one segment for
 * thread t, and record a node's list as everything appended since `start`
 * (c->len[t] before its first push). */
static inline int cti_collect_push(cti_collect *c, int t, ct_idx seg)
{
    if (c->len[t] == c->cap[t] && cti_collect_room(c, t, 1) != CT_OK)
        return CT_ERR_NOMEM;
    c->buf[t][c->len[t]++] = seg;
    return CT_OK;
}

static inline void cti_collect_mark(cti_collect *c, int t, ct_idx secpos, size_t start)
{
    c->owner[secpos] = t;
    c->start[secpos] = (int64_t)start;
    c->count[secpos] = (ct_idx)(c->len[t] - start);
}

/* Load the batch pb's coordinates (by the segments' indices, or from the
 * corner records rec when not NULL) and decide it: pb->ok. */
void cti_pair_batch_decide(cti_pair_batch *restrict pb, const ct_search_input *in,
                           const ct_real *rec, ct_real d);

/* Decide the batch pb (cti_pair_batch_decide; the secondary position of
 * each pair in pos[]) and append the accepted segments to thread t's
 * collector buffer from *len on, which must have room for pb->n more. A
 * node's pairs must be consecutive in the batches; they may span two:
 * *last is the position whose record is open (-1 before the first). */
void cti_pair_batch_collect(cti_pair_batch *restrict pb, const ct_idx *restrict pos,
                            const ct_search_input *in, const ct_real *rec, ct_real d,
                            cti_collect *col, int t, size_t *len, ct_idx *last);

/* Append the candidate (node, segment j), of secondary position p, to the
 * batch pb (positions in pos[]), unless self contact excludes it (j is one
 * of the node's own segments); 1 when the batch is then full. */
static inline int cti_pair_batch_push(cti_pair_batch *restrict pb, ct_idx *restrict pos,
                                      const ct_search_input *in, ct_idx node, ct_idx p,
                                      ct_idx j)
{
    if (in->self && (node == in->n1[j] || node == in->n2[j] || node == in->n3[j] ||
                     node == in->n4[j]))
        return 0;
    pb->node[pb->n] = node;
    pb->seg[pb->n] = j;
    pos[pb->n++] = p;
    return pb->n == CTI_PAIR_BATCH;
}

/* Write the canonical pairs. */
int cti_collect_finish(cti_collect *c, const ct_idx *sec, ct_pairs *out);

void cti_collect_free(cti_collect *c);
size_t cti_collect_memory(const cti_collect *c);

/* ---- Per-algorithm entry points (search.c dispatches) ------------------ */

/* A kept copy of a search input's topology: the secondaries, the segment
 * corners and the counts (search_key.c). Zero-initialised: empty. */
typedef struct cti_topo_key {
    ct_idx *sec, *n1, *n2, *n3, *n4;
    size_t cap_sec, cap_seg;
    ct_idx nnode, nsec, nseg;
    int valid;
} cti_topo_key;
void cti_topo_key_free(cti_topo_key *k);
size_t cti_topo_key_memory(const cti_topo_key *k);
/* 1 when k holds a copy of in's topology (compared in full). */
int cti_topo_key_same(const cti_topo_key *k, const ct_search_input *in);
/* Copy in's topology into k (k is invalid on CT_ERR_NOMEM). */
int cti_topo_key_store(cti_topo_key *k, const ct_search_input *in);

/* The spatial renumbering of scattered inputs (search_renumber.c). */
typedef struct cti_renum cti_renum;
void cti_renum_free(cti_renum *r);
size_t cti_renum_memory(const cti_renum *r);
/* The next renumbered search makes its numbering again. */
void cti_renum_forget(cti_renum *r);
/* The searches that have used the kept numbering, 0 when none is kept (for
 * the tests). */
int cti_renum_uses(const cti_renum *r);

struct ct_search {
    ct_search_params p;
    cti_collect col;
    cti_renum *rn; /* created on first use */
    /* During a search on a renumbered copy: the original number of each
     * node of the copy, by which the topological search breaks ties (NULL
     * otherwise). */
    const ct_idx *tie;
    /* What the last search chose (ct_search_get_info). */
    int last_renumbered;
    double last_cell_factor;
    void *algo_state; /* owned by the algorithm */
    void (*algo_free)(void *state);
    size_t (*algo_memory)(const void *state);
};

/* The algorithm state of s whose free function is fr: the one kept from
 * the last call, or a new zeroed one of size bytes (with fr and mem
 * installed) when there is none or it belongs to another algorithm (the
 * parameters changed; that one is dropped with ct_search_reset). NULL when
 * out of memory. */
void *cti_search_state(ct_search *s, size_t size, void (*fr)(void *),
                       size_t (*mem)(const void *));

/* The search's pair limit: ct_search_params.max_pairs within (0, 2^31 - 1]. */
static inline int64_t cti_search_max_pairs(const ct_search *s)
{
    int64_t m = s->p.max_pairs;
    return m > 0 && m < INT32_MAX ? m : INT32_MAX;
}

int cti_search_direct(ct_search *s, const ct_search_input *in, ct_pairs *out);
int cti_search_topo(ct_search *s, const ct_search_input *in, ct_pairs *out);
/* The topological history across a new numbering of the same topology
 * (search_topo.c, used by search_renumber.c). Export: when the workspace
 * holds a history for the renumbered input in, hist[o] = the original
 * number of the closest main node of the secondary at original position o
 * (kpos: original position -> position in in; old_of_new: node of in ->
 * original node), and returns 1; 0 when there is none. Import: the history
 * of the new renumbered input in from hist (new_of_old: original node ->
 * node of in). Forget: the next topological search is a full one. */
int cti_topo_history_export(ct_search *s, const ct_search_input *in, const ct_idx *kpos,
                            const ct_idx *old_of_new, ct_idx *hist);
int cti_topo_history_import(ct_search *s, const ct_search_input *in, const ct_idx *kpos,
                            const ct_idx *new_of_old, const ct_idx *hist);
void cti_topo_forget(ct_search *s);
int cti_search_bucket(ct_search *s, const ct_search_input *in, ct_pairs *out);
int cti_search_bsp(ct_search *s, const ct_search_input *in, ct_pairs *out);

/* Run `run` on a spatially renumbered copy of the input (every index
 * checked) and map its pairs back (search_renumber.c). *done = 0 (and
 * nothing written) when the input is left to the plain search: empty, or a
 * secondary listed twice. */
int cti_search_renumbered(ct_search *s, const ct_search_input *in, ct_pairs *out,
                          int (*run)(ct_search *, const ct_search_input *, ct_pairs *),
                          int *done);
int cti_bucket_scattered(const ct_search_input *in);
/* 1 when the numbering is local only in short pieces scattered in space
 * (a soup of small parts, each numbered in order): of 256 sampled
 * consecutive segments, more than 16 (1 in 16) whose first corners lie
 * farther apart than an eighth of the samples' box diagonal. A structured
 * mesh jumps that far once per row, a space-filling curve at its few
 * coarsest levels. Indices must have been checked (search_bucket_grid.c). */
int cti_search_pieces(const ct_search_input *in);
/* 1 when the node arrays are much larger than what the interface uses
 * (more than 4 x (secondaries + 4 x segments)): passes over all nodes would
 * then cost more than the search (search.c). */
int cti_search_small_share(const ct_search_input *in);

#endif /* CT_INTERNAL_H */
