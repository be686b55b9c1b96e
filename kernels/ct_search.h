/*
 * ct_search.h -- candidate search (broad phase), part of contact.h.
 *
 * One contract for the four algorithms: given secondary nodes, main
 * segments, a gap and a margin, return every pair (node, segment) whose
 * distance can be below gap + margin, in canonical order (by position in the
 * secondary list, then by segment index), bit-identical for any thread
 * count. "Can be below" is decided by one predicate shared by all four,
 * chosen in the input (ct_search_filter):
 *  - CT_FILTER_HULL (default): the node's distance to the convex hull of
 *    the segment's corners is at most gap + margin. The hull contains the
 *    segment's surface for every projection method (bilinear, 4 triangles,
 *    2 triangles), so no pair any narrow phase would find is dropped.
 *  - CT_FILTER_BOX: the node's distance to the segment's axis-aligned box
 *    is at most gap + margin; a superset of the hull set (the narrow phase
 *    then rejects the extra pairs every cycle), several times cheaper.
 */
#ifndef CT_SEARCH_H
#define CT_SEARCH_H

#ifdef __cplusplus
extern "C" {
#endif

/* Candidate pairs, structure of arrays: node[k] is a global node index,
 * seg[k] an index into the segment arrays the search was given. */
typedef struct ct_pairs {
    ct_idx n, cap;
    ct_idx *node, *seg;
} ct_pairs;

int ct_pairs_init(ct_pairs *p, ct_idx cap);
int ct_pairs_reserve(ct_pairs *p, ct_idx cap); /* keeps content */
void ct_pairs_destroy(ct_pairs *p);

/* Which shared predicate decides "may touch" (the same for every search). */
typedef enum ct_search_filter {
    CT_FILTER_HULL = 0, /* distance to the convex hull of the corners <= d */
    CT_FILTER_BOX = 1   /* distance to the segment's axis-aligned box <= d:
                           a superset of the hull set, much cheaper */
} ct_search_filter;

typedef struct ct_search_input {
    ct_idx nnode;                  /* length of x, y, z */
    const ct_real *x, *y, *z;      /* current node positions */
    ct_idx nsec;                   /* secondary nodes ... */
    const ct_idx *sec;             /* ... as global node indices */
    ct_idx nseg;                   /* main segments ... */
    const ct_idx *n1, *n2, *n3, *n4; /* ... by global node indices */
    ct_real gap, margin;           /* search distance = gap + margin */
    int self; /* 1: one surface against itself; a node never pairs with a
                 segment it belongs to */
    ct_search_filter filter; /* 0 (CT_FILTER_HULL) when zero-initialised */
} ct_search_input;

typedef enum ct_search_algo {
    CT_SEARCH_DIRECT = 0, /* all pairs; the reference */
    CT_SEARCH_TOPO,       /* topologically limited (TYPE3/5 engine): may miss
                             impacts; not meant for self contact (a node's
                             closest main node is itself) */
    CT_SEARCH_BUCKET,     /* uniform voxel grid, counting sort */
    CT_SEARCH_BSP,        /* quick sort: binary space partition */
    CT_SEARCH_NALGO
} ct_search_algo;

/* Name ("direct", "topological", "bucket", "bsp") and its inverse (-1 when
 * the name is unknown). */
const char *ct_search_algo_name(ct_search_algo a);
int ct_search_algo_from_name(const char *name);

typedef struct ct_search_params {
    ct_search_algo algo;
    /* bucket: 1 (default) the lean design (segments binned per cell, nodes
     * query their cell, cell order for scattered numbering); 0 the baseline
     * (nodes binned, segments scan; kept to measure against). Both give
     * the same pairs. */
    int variant;
    /* bucket: cells per unit length = cell_factor * 0.75 *
     * sqrt(nseg / (LxLy + LyLz + LzLx)) (cell_factor 1: the Radioss
     * sizing), total cells capped at max_cells (0 -> 2 * (nsec + nseg) +
     * 1024). cell_factor 0 (default): chosen per input among 0.1 to 3, by
     * the cost of binning and testing counted on a sample of the input,
     * kept for up to 16 searches while the input's counts and extent stay
     * (kernels/search_bucket_auto.c). The pairs are the same for any
     * factor; variant 0 takes 0 as 1. */
    double cell_factor;
    int64_t max_cells;
    /* bsp: a box becomes a leaf, tested all against all, when it holds no
     * node or no segment, when nodes x segments <= leaf_size x (nodes +
     * segments) (leaf_size 0 -> 32), or when its longest side is below
     * min_box (0 -> gap + margin). */
    int leaf_size;
    double min_box;
    /* bsp with the hull filter: 0 (default) a leaf of up to 2048 segments
     * whose first nodes pass the box test of at least half the segments in
     * the groups of 8 they touch is decided by the dense path (the
     * predicate's first steps in SIMD lanes over the leaf's segments;
     * kernels/search_bsp_dense.c), the others by the batch path; 1 every
     * leaf of up to 2048 segments dense, -1 none. The same pairs, bit for
     * bit; a knob for tests and measurements. */
    int dense;
    /* bucket, bsp and topological: 0 (default) renumber the input
     * spatially when its numbering is scattered (segment corners far apart
     * in number) and the interface uses a fair share of the node arrays
     * (nnode <= 4 x (nsec + 4 nseg): the copy's cost grows with nnode), for
     * the bucket only from 2^19 nodes (below, its own scattered path is as
     * fast); also when the numbering is local only in short pieces
     * scattered in space (a soup of small parts: consecutive segments
     * often far apart), for the bucket from 2^16 nodes and the topological
     * search from 2^17; 1 always, -1 never. The search then runs on a renumbered copy (nodes by grid cell, segments
     * by their first corner, secondaries by number) and its pairs are
     * mapped back: the same canonical list, bit for bit, for about 260
     * bytes of workspace per secondary on two plates. The topological
     * search breaks its ties by the original node numbers and carries its
     * history to each new numbering: its pairs too are those of the plain
     * search. */
    int renumber;
    /* With renumbering: a numbering is reused by the searches that follow
     * while the topology (secondaries, segment corners; compared in full
     * every search) is unchanged, for up to renumber_keep searches (0 ->
     * 64), then made again from the current positions; -1 makes it anew
     * every search. Only the cost changes, never the pairs. Adds 4 bytes
     * per secondary and 16 per segment (the copy of the topology; the
     * topological search always keeps it, and 4 bytes per node and per
     * secondary more for its ties and history). */
    int renumber_keep;
    /* The most pairs a search may return (0 or above 2^31 - 1: 2^31 - 1,
     * what a ct_idx counts). A search that would return more fails with
     * CT_ERR_TOOBIG, for every algorithm and thread count alike, having
     * held at most about max_pairs pairs per thread (or per query block of
     * the bucket) on the way: the caller sizes it from the memory its own
     * per-pair arrays would need. */
    int64_t max_pairs;
} ct_search_params;

/* The defaults above for one algorithm. */
ct_search_params ct_search_default_params(ct_search_algo algo);

/* An opaque search workspace: scratch arrays grown on demand and kept, and
 * the topological search's history (closest main node per secondary). */
typedef struct ct_search ct_search;

/* A workspace for the searches of params p (NULL: the bucket search's
 * defaults). CT_ERR_ARG for a parameter out of its range: an unknown
 * algorithm or variant, a cell_factor that is negative, NaN or above 1e6,
 * a negative max_cells, leaf_size, min_box or max_pairs, dense or
 * renumber outside -1..1, renumber_keep below -1. */
int ct_search_init(ct_search **s, const ct_search_params *p);
void ct_search_destroy(ct_search *s);

/* Run the search; out is grown as needed and overwritten. Returns CT_OK;
 * CT_ERR_ARG for a missing array, a negative count or a gap or margin that
 * is negative or not finite; CT_ERR_RANGE when a secondary or a segment
 * corner is not a node index (0 <= i < nnode); CT_ERR_NONFINITE when one of
 * those nodes has a NaN or infinite coordinate, or one beyond 1e300
 * (single precision 3e38), whose arithmetic would overflow (other nodes
 * are not read);
 * CT_ERR_NOMEM. The same for every algorithm. */
int ct_search_run(ct_search *s, const ct_search_input *in, ct_pairs *out);

/* Forget the history: the next topological search is a full search, and
 * the next renumbered search makes its numbering anew. */
void ct_search_reset(ct_search *s);

/* Bytes of scratch currently held by the workspace. */
size_t ct_search_memory(const ct_search *s);

/* What the last successful ct_search_run on s chose by itself: whether it
 * ran on a renumbered copy (ct_search_params.renumber), and for the bucket
 * search the cell factor of its grid (the chosen one when cell_factor is
 * 0; 0 for the other algorithms). For reports: the pairs do not depend on
 * either. CT_ERR_ARG when s or info is NULL. */
typedef struct ct_search_info {
    int renumbered;
    double cell_factor;
} ct_search_info;
int ct_search_get_info(const ct_search *s, ct_search_info *info);

/* The shared predicates (see the top of this file): 1 when the point p may
 * be within d of the segment a b c dd (dd == c for a triangle): by the
 * distance to the corners' convex hull (CT_FILTER_HULL), or by the distance
 * to the corners' axis-aligned box (CT_FILTER_BOX). */
int ct_pair_box_near(const ct_real p[3], const ct_real a[3], const ct_real b[3],
                     const ct_real c[3], const ct_real dd[3], ct_real d);
int ct_pair_may_touch(const ct_real p[3], const ct_real a[3], const ct_real b[3],
                      const ct_real c[3], const ct_real dd[3], ct_real d);

/*
 * Re-sort criterion (DESIGN.md section 5). x0/y0/z0 are the positions at
 * the last sort, x/y/z the current ones. The bound on how much any
 * node-segment distance can have shrunk since the sort is the smaller of
 *  - the largest displacement of a secondary node plus the largest of a
 *    main node, and
 *  - the relative displacement bound per axis: a point of a segment moves
 *    by a convex combination of its corners' displacements, so along each
 *    axis the secondary-minus-main displacement lies in [min_s - max_m,
 *    max_s - min_m]; the bound is the length of the vector of the larger
 *    ends. A rigid motion of both sets together (a dropped body in self
 *    contact, sheets moving as one) gives 0: no re-sort.
 * While the bound is at most `margin`, every pair now within `gap` was
 * within gap + margin at the sort, so the stored candidates are complete.
 * A NaN position gives an infinite bound. Returns 1 when a re-sort is
 * needed, 0 when not; *bound (may be NULL) receives the bound. Passing the
 * same array for sec and main_nodes (self contact, one node list) reads
 * the nodes once. The node lists are not range-checked (no node count is
 * passed): they are the lists the search was given, which it checks.
 */
int ct_resort_needed(ct_idx nsec, const ct_idx *sec, ct_idx nmain,
                     const ct_idx *main_nodes, const ct_real *x0, const ct_real *y0,
                     const ct_real *z0, const ct_real *x, const ct_real *y,
                     const ct_real *z, ct_real margin, ct_real *bound);

/*
 * The re-sort criterion against two references in one pass over the
 * nodes, for a code that also bounds each step (the contact cycle's skip
 * of the narrow phase, driver/contact_cycle.h): the return value and
 * *bound are ct_resort_needed's against x0/y0/z0 (the positions at the last
 * sort), *step the same bound against xp/yp/zp (the previous positions: how
 * much any distance can have shrunk since them), bit for bit. When xk is
 * not NULL, xk/yk/zk receive the current positions of the listed nodes
 * (the next call's xp; they must not alias x or xp: keep two arrays and
 * swap them). *amax receives the largest coordinate magnitude of the listed
 * nodes, infinite if one is NaN. bound, step, amax may be NULL. The node
 * lists are not range-checked (as ct_resort_needed's), and xk/yk/zk are
 * written at the listed nodes' indices: they hold as many entries as the
 * position arrays. One pass
 * reads the 9 coordinates of a node where ct_resort_needed twice and a copy
 * read 15.
 */
int ct_resort_track(ct_idx nsec, const ct_idx *sec, ct_idx nmain, const ct_idx *main_nodes,
                    const ct_real *x0, const ct_real *y0, const ct_real *z0, const ct_real *xp,
                    const ct_real *yp, const ct_real *zp, const ct_real *x, const ct_real *y,
                    const ct_real *z, ct_real *xk, ct_real *yk, ct_real *zk, ct_real margin,
                    ct_real *bound, ct_real *step, double *amax);

/*
 * Neighbour exclusion for self contact on a fine mesh (Radioss's
 * Irem_gap = 2). When the gap is more than half the shortest edge, a node
 * starts within the gap of the segments next to its own and a flat sheet
 * pushes itself apart. The exclusion of a query (a node, or an edge) is the
 * set of items (segments, or edges) within distance r of it at the start
 * that are joined to it through items all within r: the set grows from the
 * items that hold one of the query's nodes (never paired in self contact)
 * by shared nodes, and admits only the query's candidates, the items within
 * r. An item within r joined only through farther ones (the other layer of
 * a fold, a part that is not connected) is kept: the exclusion removes the
 * surface around the query, not what lies near it.
 *
 * ct_exclusion_build takes the candidates (query, item) within r in any
 * order; repeated ones count once. The items holding a query node join the
 * growth whether candidates or not (they touch the query), and are
 * excluded when they are candidates (a self search never pairs them).
 * ex is overwritten (not freed). Items have nper nodes (4: segments,
 * n4 == n3 for a triangle; 2: edges); query q's nodes are q1[q] and q2[q]
 * (q2 NULL: q1 alone; q1 NULL: query q is node q, nq <= nnode). The result
 * lists, per query, its excluded items ascending, the same for any thread
 * count. CT_ERR_ARG for a missing array or a negative count, CT_ERR_RANGE
 * for an index out of range, CT_ERR_NOMEM.
 *
 * ct_exclusion_build_nodeseg: the exclusion of every node (queries are
 * global node indices) against the segments of a search input, the
 * candidates being the pairs within r by the hull predicate (a bucket
 * search with gap r, no margin, self contact). CT_ERR_ARG for r negative
 * or not finite; the search's errors otherwise.
 *
 * ct_pairs_exclude removes from p the pairs (node, seg) the exclusion of
 * node holds (its queries are global node indices), keeping the order;
 * *removed (may be NULL) the count. CT_ERR_RANGE for a node beyond nq.
 */
typedef struct ct_exclusion {
    ct_idx nq;    /* queries */
    ct_idx *off;  /* nq + 1: query q's items are item[off[q] .. off[q+1]-1] */
    ct_idx *item; /* ascending within each query */
} ct_exclusion;

typedef struct ct_exclusion_input {
    ct_idx nnode;
    ct_idx nitem;
    int nper;                    /* 2 or 4 nodes per item */
    const ct_idx *in[4];         /* item t's nodes in[0][t] .. in[nper-1][t] */
    ct_idx nq;
    const ct_idx *q1, *q2;       /* query nodes (see above) */
    ct_idx ncand;
    const ct_idx *cq, *ci;       /* candidate k: query cq[k], item ci[k] */
} ct_exclusion_input;

int ct_exclusion_build(ct_exclusion *ex, const ct_exclusion_input *in);
int ct_exclusion_build_nodeseg(ct_exclusion *ex, const ct_search_input *in, ct_real r);
void ct_exclusion_destroy(ct_exclusion *ex);
/* 1 when query q excludes item (0 for q out of range). */
int ct_exclusion_has(const ct_exclusion *ex, ct_idx q, ct_idx item);
int ct_pairs_exclude(ct_pairs *p, const ct_exclusion *ex, int64_t *removed);

#ifdef __cplusplus
}
#endif

#endif /* CT_SEARCH_H */
