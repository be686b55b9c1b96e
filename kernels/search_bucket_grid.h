/*
 * search_bucket_grid.h -- the passes of search_bucket_grid.c that both
 * bucket searches use (the default, search_bucket.c, and the baseline,
 * search_bucket_v0.c): bounding boxes and checks, the grid's size, the
 * counting sort's offsets and the binning of the nodes. Not part of any API.
 */
#ifndef CT_SEARCH_BUCKET_GRID_H
#define CT_SEARCH_BUCKET_GRID_H

#include "ct_internal.h"

/* The bucket passes' parallel loops that gcc vectorises (clauses in
 * parentheses). clang 14 gets the plain loop: it cannot vectorise pass 1's
 * gathers (and warns, an error under -Werror), and it vectorised the range
 * pass with a wrong sum of entries, one vector lane's share of it (7783 for
 * 60516 on a 10^4 plate with 8 lanes; 1/2 and 1/4 with SSE2 and AVX2),
 * which overran the entry array. The same loop sums right as `omp simd`
 * alone or with a 64-bit loop index: a fault of clang 14.0.6's combined
 * `parallel for simd` with a reduction, found here (reproduced apart from
 * this code, not reduced to a few lines). */
#ifdef __clang__
#define BK_PAR_FOR_SIMD(clauses) CTI_PRAGMA(omp parallel for CTI_UNPAREN clauses)
#else
#define BK_PAR_FOR_SIMD(clauses) CTI_PRAGMA(omp parallel for simd CTI_UNPAREN clauses)
#endif

/* The cap on a bucket grid's cells: ct_search_params.max_cells, 0 for
 * 2 (nsec + nseg) + 1024, and never above 32 (nsec + nseg) + 2^20: more
 * cells than that only cost memory (a cap such as INT64_MAX on a
 * degenerate extent took a billion cells, 8 GB). */
static inline int64_t cti_bucket_max_cells(int64_t max_cells, const ct_search_input *in)
{
    const int64_t items = (int64_t)in->nsec + (int64_t)in->nseg;
    const int64_t top = 32 * items + (INT64_C(1) << 20);
    const int64_t m = max_cells > 0 ? max_cells : 2 * items + 1024;
    return m < top ? m : top;
}

int cti_bucket_boxes(const ct_search_input *in, ct_real *restrict xyzw, ct_real *restrict box,
                     float *restrict fbox, ct_real *restrict srec, ct_real mb[6]);
int cti_bucket_scattered(const ct_search_input *in);
int cti_bucket_check_sec(const ct_search_input *in);
int64_t cti_bucket_offsets(ct_idx *cnt, int nb, size_t stride, int64_t ncell, ct_idx *start);
int cti_bucket_bin_nodes(const ct_search_input *in, const ct_real lo[3], const ct_real hi[3],
                         const ct_real inv[3], const ct_idx n[3], int nb, ct_idx *cnt,
                         size_t stride, ct_idx *ncl, ct_idx *ord, ct_idx *ordc,
                         ct_idx *nbinned);
int cti_bucket_local(const ct_search_input *in, const ct_real lo[3], const ct_real hi[3],
                     const ct_real inv[3], const ct_idx n[3]);
void cti_bucket_size(const ct_real lo[3], const ct_real hi[3], ct_idx nseg, double factor,
                     int64_t maxc, ct_idx n[3], ct_real inv[3]);

#endif /* CT_SEARCH_BUCKET_GRID_H */
