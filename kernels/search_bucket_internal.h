/*
 * search_bucket_internal.h -- private declarations of the bucket search,
 * shared by search_bucket.c (passes 1 to 5 and the driver of the search),
 * search_bucket_query.c (pass 6, the query) and defined partly in
 * search_bucket_grid.c. Not part of any API.
 */
#ifndef CT_SEARCH_BUCKET_INTERNAL_H
#define CT_SEARCH_BUCKET_INTERNAL_H

#include "search_bucket_grid.h"

/* One block's pair output (block 0's is the output's own arrays). Padded to
 * a cache line so that blocks never share one. */
typedef struct bk_out {
    ct_idx *node, *seg;
    size_t n, cap;
    size_t off; /* where the block's pairs go in the output */
    char pad[64 - 2 * sizeof(ct_idx *) - 3 * sizeof(size_t)];
} bk_out;

typedef struct bk_state {
    int maxblk;
    int64_t max_pairs; /* this search's pair limit (cti_search_max_pairs) */
    ct_real *box; /* per segment: lo x y z, hi x y z */
    size_t box_cap;
    float *fbox; /* per segment: fl(lo - d) rounded down (x y z 0), then
                    -fl(hi + d) rounded up (x y z 0): a float pre-test */
    size_t fbox_cap;
    uint64_t *rng; /* per segment: its cell range, packed (BK_SKIP, BK_WIDE) */
    size_t rng_cap;
    ct_real *srec; /* per segment: its 4 corners (hull filter, scattered
                      numberings only) */
    size_t srec_cap;
    ct_real *xyzw; /* per node: x y z 0 (scattered numberings only) */
    size_t xyzw_cap;
    ct_idx *cnt; /* per block: counters per cell, then offsets (stride cstride) */
    size_t cnt_cap;
    ct_idx *start; /* per cell: first entry; start[ncell] = entries */
    size_t start_cap;
    ct_idx *ent; /* segment numbers, cell by cell */
    size_t ent_cap;
    ct_idx *ncl, *ord, *ordc; /* cell order: node cells, positions, cells */
    size_t ncl_cap, ord_cap, ordc_cap;
    bk_out *buf; /* per block; buf[0] is unused (block 0 writes the output) */
    int srec_on;  /* srec holds this call's corners */
    /* The chosen cell factor (cell_factor 0): search_bucket_auto.c's
     * scratch, the factor, the searches since it was chosen, and the input
     * it was chosen on. */
    ct_real *auto_scr; /* cti_bucket_auto_scratch(nsec, nseg) bytes */
    size_t auto_scr_cap;
    double auto_f;
    int auto_age;
    ct_idx auto_nsec, auto_nseg;
    ct_real auto_len[3];
} bk_state;

/* The candidate cell factors, coarse to fine, and the cost weights per
 * entry binned (BK_AUTO_E) and per cell per counting block (BK_AUTO_C), a
 * node's test of one entry weighing 1 (search_bucket_auto.c). */
#define BK_AUTO_NF 10
extern const double cti_bucket_auto_factors[BK_AUTO_NF];
#define BK_AUTO_E 2.0
#define BK_AUTO_C 6.0
/* Segments and secondary nodes sampled, at most (all when fewer). */
#define BK_AUTO_SEGS 4096
#define BK_AUTO_NODES 8192

/* A choice of cell factor, for tests and reports: the factor, the
 * estimated entries binned and entries tested and the cells of its grid,
 * and the number of grids priced. */
typedef struct cti_bucket_auto_info {
    double factor, entries, tests, cells;
    int priced;
} cti_bucket_auto_info;

/* The cell factor for this input (search_bucket_auto.c): fbox the
 * segments' float boxes (pass 1), lo/hi the grid's region, maxc the cap on
 * cells, limit the entries beyond which the search coarsens the grid, nb
 * the counting blocks, scratch cti_bucket_auto_scratch(in->nsec, in->nseg) bytes,
 * ct_real-aligned; info may be NULL. */
double cti_bucket_auto_factor(const ct_search_input *in, const float *fbox,
                              const ct_real lo[3], const ct_real hi[3], int64_t maxc,
                              int64_t limit, int nb, void *scratch,
                              cti_bucket_auto_info *info);
/* The bytes of cti_bucket_auto_factor's scratch for an input of nsec
 * secondary nodes and nseg segments (the gathered samples and the table of
 * their cells: 460 KB at most, 0.5 KB for a few nodes). */
size_t cti_bucket_auto_scratch(ct_idx nsec, ct_idx nseg);

/* The chosen factor is kept for this many searches at most, and while the
 * counts stay the same and no side of the region changes by more than
 * BK_AUTO_DRIFT (relative). */
#define BK_AUTO_EVERY 16
#define BK_AUTO_DRIFT 0.1

/* The grid: the region where a node may pair at all, cells per axis and
 * per unit length. */
typedef struct bk_grid {
    ct_real lo[3], hi[3];
    ct_real inv[3]; /* 0 on a flat axis */
    ct_idx n[3];
    int64_t ncell;
} bk_grid;

/* Cell of coordinate v along one axis: monotone in v. */
static inline ct_idx bk_cell1(ct_real v, ct_real o, ct_real inv, ct_idx nmax)
{
    ct_real t = (v - o) * inv;
    t = t > 0 ? t : 0;
    return t < (ct_real)nmax ? (ct_idx)t : nmax;
}

/* Errors found by the query (or-ed). */
enum { BK_ENOMEM = 1, BK_ERANGE = 2, BK_ENONFINITE = 4, BK_ETOOBIG = 8 };

/* Grow a block's output to hold at least `need` pairs (search_bucket.c). */
int cti_bucket_out_grow(bk_out *o, size_t need);

/* Pass 6, secondary order (search_bucket_query.c): blocks of consecutive
 * positions, block 0 writing into o[0] (the output's arrays), block b > 0
 * into o[b]. Returns BK_E* bits. */
int cti_bucket_query_direct(const bk_state *st, const ct_search_input *in, const bk_grid *g,
                            int nb, bk_out *o);

/* Pass 6, cell order (search_bucket_query.c): the collector restores the
 * secondary order. Returns BK_E* bits. */
int cti_bucket_query_cells(const bk_state *st, const ct_search_input *in, int nb,
                           ct_idx nbinned, cti_collect *col);

#endif
