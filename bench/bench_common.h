/*
 * bench_common.h -- helpers shared by the search benchmarks (bench_search.c,
 * bench_real.c, bench_peers.c, bench_floor.c): the clock, a mesh's search
 * input as first-touch copies, the reference pairs and their comparison,
 * and the timed search benchmark itself.
 */
#ifndef BENCH_COMMON_H
#define BENCH_COMMON_H

#include <stddef.h>
#include <stdint.h>

#include "bench_search.h"
#include "contact.h"
#include "gbench.h"

/* A monotonic clock, in seconds. */
double ctb_now_s(void);

/* The median of v[0..n-1] (n >= 1; v is sorted in place). */
double ctb_median(double *v, int n);

/* The smallest and largest of v[0..n-1] (n >= 1). */
void ctb_minmax(const double *v, int n, double *lo, double *hi);

/* The search input of a mesh, its arrays first-touch copies (ctb_free),
 * and the reference pairs of the topological search's misses. */
typedef struct ctb_mesh {
    ct_real *x, *y, *z;
    ct_idx *sec, *n1, *n2, *n3, *n4;
    ct_search_input in; /* points at the copies above */
    int ref_state;      /* 0: not computed yet, 1: done, -1: failed */
    ct_search_algo ref_algo;
    ct_pairs ref;
    ct_idx *pos; /* node -> position in sec (-1: not secondary) */
} ctb_mesh;

/* Free the copies, the reference and the position map; zero *m. */
void ctb_mesh_clear(ctb_mesh *m);

/* m->in = *src with its arrays replaced by first-touch copies made by
 * `threads` threads placed by `bind` (the largest team the runs use).
 * CT_OK or CT_ERR_NOMEM (the copies made are freed by ctb_mesh_clear). */
int ctb_mesh_copy(ctb_mesh *m, const ct_search_input *src, ctb_bind_policy bind, int threads);

/*
 * The search distance of every benchmark, relative to the mean main edge
 * length h (DESIGN.md section 5: margin = 0.2 h, search distance = gap +
 * margin): gap = 0.3 h, so gap + margin = 0.5 h; on the plates family (unit
 * spacing, plates 0.3 apart) that is the "0.3 apart, gap + margin
 * 0.5". Every family of meshgen.h puts its facing surfaces 0.3 h apart
 * (folded: 0.4 h), inside that distance.
 */
void ctb_search_gap(double h, double *gap, double *margin);

/* The synthetic case `family` of about `target` nodes (meshgen.h) with
 * `numbering` and cfg->seed, its search distance from ctb_search_gap,
 * copied as above by cfg->max_threads threads; *h_mean gets its mean main
 * edge length. On failure returns the error and writes a message to err. */
int ctb_mesh_case(ctb_mesh *m, const char *family, int64_t target, int numbering,
                  const ctb_search_config *cfg, double *h_mean, char *err, size_t errlen);

/* node -> position in in->sec (-1 for the other nodes), malloc'd; NULL when
 * out of memory. */
ct_idx *ctb_position_map(const ct_search_input *in);

/* Our search `algo` with default parameters on in, into out (initialised
 * here; the caller destroys it whatever the result). */
int ctb_search_once(ct_search_algo algo, const ct_search_input *in, ct_pairs *out);

/* nsec * nseg, the direct search's pair tests. */
double ctb_pair_tests(const ct_search_input *in);

/* The reference pairs of m, computed once by the largest team: direct when
 * nsec * nseg is within cfg->direct_budget, else bucket, else bsp (all three
 * report the same set); also fills m->pos. NULL when none succeeded. */
const ct_pairs *ctb_mesh_reference(ctb_mesh *m, const ctb_search_config *cfg);

/* Count the pairs of ref absent from got (*missing) and the pairs of got
 * absent from ref (*extra); both lists are in the searches' canonical order
 * (secondary position, then segment), so one merge pass. */
void ctb_compare_pairs(const ct_idx *pos, const ct_pairs *ref, const ct_pairs *got,
                       int64_t *missing, int64_t *extra);

/* A workspace for algo and an output list, after one untimed search of in
 * (workspace and output growth; the topological search's full first
 * search). On failure returns the error; *s and *out are then released. */
int ctb_search_start(ct_search_algo algo, const ct_search_input *in, ct_search **s,
                     ct_pairs *out);

/* Whole searches of in while the benchmark runs; *seconds gets their time.
 * Returns the first error (the loop stops there) or CT_OK. */
int ctb_search_timed(gb_state *st, ct_search *s, const ct_search_input *in, ct_pairs *out,
                     double *seconds);

/*
 * One search benchmark of `algo` with `threads` threads on m: skipped when
 * the direct search is over its budget; the topological search's reference
 * (computed first, by the largest team); one untimed search, then whole
 * searches timed. Counters ns_per_node, nsec, nseg, pairs, bytes_per_node
 * (workspace / secondary nodes), threads and, for the topological search,
 * misses (and extra, pairs the reference does not have); the label is
 * "<prefix>h=<h_mean> gap=.. margin=.. <bind>[<cpus>] misses_vs=<ref>".
 */
void ctb_search_bench(gb_state *st, ctb_mesh *m, const ctb_search_config *cfg,
                      ct_search_algo algo, int threads, double h_mean, const char *prefix);

#endif /* BENCH_COMMON_H */
