/*
 * floor.h -- the hardware floor of the contact search: the minimum number of
 * bytes any search must move, and the time that takes at a measured memory
 * bandwidth. Pure functions (header only, so the tests use them without the
 * benchmark program); the bandwidth itself is measured by bench_floor.c.
 *
 * The byte model counts what ANY search algorithm must move for one search,
 * not the passes of a particular one (the bucket sort's binning, counting
 * and scatter passes come on top): every input it cannot do without is read
 * once, every output is written once.
 *
 *   sec_list = nsec * sizeof(ct_idx)       the list of secondary nodes
 *                                          (global indices) is read;
 *   coords   = 3 * nnode * sizeof(ct_real) x, y, z of every node the search
 *                                          touches, once: the secondary
 *                                          nodes and the corners of the main
 *                                          segments (nnode counts the union;
 *                                          a node that is both is read once);
 *   conn     = 4 * nseg * sizeof(ct_idx)   the main segments' connectivity
 *                                          n1..n4 (a triangle repeats n3, so
 *                                          it has 4 entries too);
 *   pairs    = 2 * npair * sizeof(ct_idx)  the output (node, seg) pairs are
 *                                          written.
 *
 * Writes are counted once, as STREAM counts them (its triad a = b + s c
 * moves 3 arrays: 2 read, 1 written; the extra read of a write-allocate
 * cache is counted in neither), so the ratio measured / floor compares like
 * with like. Everything else (grids, sort keys, scratch) is the algorithm's
 * own overhead and is what the ratio measures.
 */
#ifndef CTB_FLOOR_H
#define CTB_FLOOR_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "contact.h"

typedef struct ctb_floor_terms {
    double sec_list, coords, conn, pairs; /* bytes, as documented above */
    double total;                         /* their sum; -1 for invalid input */
} ctb_floor_terms;

/* The minimum bytes of one search (see the top of this file). A negative
 * count or a zero element size gives total = -1 and every term 0. */
static inline ctb_floor_terms ctb_floor_search_bytes(int64_t nsec, int64_t nseg, int64_t nnode,
                                                     int64_t npair, size_t real_size,
                                                     size_t idx_size)
{
    ctb_floor_terms t = {0, 0, 0, 0, -1};
    if (nsec < 0 || nseg < 0 || nnode < 0 || npair < 0 || real_size == 0 || idx_size == 0)
        return t;
    t.sec_list = (double)nsec * (double)idx_size;
    t.coords = 3.0 * (double)nnode * (double)real_size;
    t.conn = 4.0 * (double)nseg * (double)idx_size;
    t.pairs = 2.0 * (double)npair * (double)idx_size;
    t.total = t.sec_list + t.coords + t.conn + t.pairs;
    return t;
}

/* The lower bound in ns per secondary node: bytes / bandwidth / nsec, with
 * the bandwidth in GB/s (1e9 bytes per second): bytes / (gbps * 1e9) s is
 * bytes / gbps ns. -1 when an argument is not positive. */
static inline double ctb_floor_ns_per_node(double bytes, int64_t nsec, double gbps)
{
    if (!(bytes > 0) || nsec <= 0 || !(gbps > 0))
        return -1;
    return bytes / gbps / (double)nsec;
}

/* Bytes one triad a[i] = b[i] + s c[i] over n elements of elem_size bytes
 * moves, counted as STREAM does: 3 n elem_size. */
static inline double ctb_triad_bytes(int64_t n, size_t elem_size)
{
    return 3.0 * (double)n * (double)elem_size;
}

/* GB/s (1e9 bytes per second); -1 when seconds is not positive. */
static inline double ctb_gbps(double bytes, double seconds)
{
    return seconds > 0 ? bytes / seconds / 1e9 : -1;
}

/* Mark index v in seen[0..n-1], counting it in *count the first time;
 * 1 when v is out of range (nothing marked). */
static inline int ctb_floor_mark(unsigned char *seen, int64_t n, ct_idx v, int64_t *count)
{
    if (v < 0 || v >= n)
        return 1;
    *count += !seen[v];
    seen[v] = 1;
    return 0;
}

/*
 * The nodes a search over this input touches: the union of the secondary
 * nodes sec[0..nsec-1] and the corners n1..n4 of the nseg main segments
 * (indices in [0, nnode_all)), each counted once. This is the nnode of the
 * byte model. -1 on allocation failure or an index out of range.
 */
static inline int64_t ctb_floor_touched_nodes(int64_t nnode_all, int64_t nsec,
                                              const ct_idx *sec, int64_t nseg,
                                              const ct_idx *n1, const ct_idx *n2,
                                              const ct_idx *n3, const ct_idx *n4)
{
    if (nnode_all < 0 || nsec < 0 || nseg < 0)
        return -1;
    unsigned char *seen = calloc((size_t)nnode_all + 1, 1);
    if (!seen)
        return -1;
    int64_t count = 0;
    int bad = 0;
    for (int64_t i = 0; i < nsec && !bad; i++)
        bad = ctb_floor_mark(seen, nnode_all, sec[i], &count);
    const ct_idx *corner[4] = {n1, n2, n3, n4};
    for (int c = 0; c < 4 && !bad; c++)
        for (int64_t s = 0; s < nseg && !bad; s++)
            bad = ctb_floor_mark(seen, nnode_all, corner[c][s], &count);
    free(seen);
    return bad ? -1 : count;
}

/*
 * The floor of a kernel over candidate pairs, by the same convention: every
 * array the kernel's call reads is read once, every array it writes is
 * written once (an array read and written, like a friction history, counts
 * both ways), the extra read of a write-allocate cache counted nowhere.
 * Per-pair arrays count per pair; arrays indexed by segment (connectivity)
 * or by node (coordinates, nodal forces) count once per segment or node the
 * pairs touch, however many pairs share it. It is the least any
 * implementation of the call, with the same arrays in and out, must move:
 * a kernel at its floor is bound by memory, one far above it by its
 * arithmetic or its latency.
 */
typedef struct ctb_kernel_streams {
    int pair_real_in, pair_real_out; /* per-pair ct_real arrays read, written */
    int pair_idx_in, pair_idx_out;   /* per-pair ct_idx arrays read, written */
    int pair_b1_out, pair_b4_out;    /* per-pair 1-byte and 4-byte arrays written */
    int seg_idx_in;                  /* ct_idx arrays indexed by segment, read */
    int node_real_in, node_real_out; /* ct_real arrays indexed by node, read, written */
} ctb_kernel_streams;

/* The bytes of one call over npair pairs touching nseg segments and nnode
 * nodes; -1 when a count is negative or a size is zero. */
static inline double ctb_floor_kernel_bytes(const ctb_kernel_streams *s, int64_t npair,
                                            int64_t nseg, int64_t nnode, size_t real_size,
                                            size_t idx_size)
{
    if (!s || npair < 0 || nseg < 0 || nnode < 0 || real_size == 0 || idx_size == 0)
        return -1;
    const double r = (double)real_size, i = (double)idx_size;
    double per_pair = (s->pair_real_in + s->pair_real_out) * r +
                      (s->pair_idx_in + s->pair_idx_out) * i + s->pair_b1_out +
                      4.0 * s->pair_b4_out;
    return (double)npair * per_pair + (double)nseg * s->seg_idx_in * i +
           (double)nnode * (s->node_real_in + s->node_real_out) * r;
}

/*
 * The segments and nodes that npair pairs (node[k], seg[k]) touch: the
 * distinct segments, and the union of the pairs' nodes and their segments'
 * corners n1..n4 (nodes in [0, nnode_all), segments in [0, nseg_all)).
 * Returns 0, or -1 on allocation failure or an index out of range.
 */
static inline int ctb_floor_pairs_touched(int64_t nnode_all, int64_t nseg_all, int64_t npair,
                                          const ct_idx *node, const ct_idx *seg,
                                          const ct_idx *n1, const ct_idx *n2,
                                          const ct_idx *n3, const ct_idx *n4,
                                          int64_t *nseg_out, int64_t *nnode_out)
{
    if (nnode_all < 0 || nseg_all < 0 || npair < 0)
        return -1;
    unsigned char *seen = calloc((size_t)nnode_all + 1, 1);
    unsigned char *sseen = calloc((size_t)nseg_all + 1, 1);
    int bad = !seen || !sseen;
    int64_t nn = 0, ns = 0;
    const ct_idx *corner[4] = {n1, n2, n3, n4};
    for (int64_t k = 0; k < npair && !bad; k++) {
        const ct_idx e = seg[k];
        if (e < 0 || e >= nseg_all || ctb_floor_mark(seen, nnode_all, node[k], &nn)) {
            bad = 1;
            break;
        }
        if (sseen[e])
            continue;
        sseen[e] = 1;
        ns++;
        for (int c = 0; c < 4 && !bad; c++)
            bad = ctb_floor_mark(seen, nnode_all, corner[c][e], &nn);
    }
    free(seen);
    free(sseen);
    if (bad)
        return -1;
    *nseg_out = ns;
    *nnode_out = nn;
    return 0;
}

#endif /* CTB_FLOOR_H */
