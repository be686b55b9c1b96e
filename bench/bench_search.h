/*
 * bench_search.h -- registration of the search benchmarks (bench_search.c).
 */
#ifndef BENCH_SEARCH_H
#define BENCH_SEARCH_H

#include <stdint.h>

#include "bench_topology.h"

typedef struct ctb_search_config {
    int full;             /* 1: every family and numbering, sizes to 10^7 */
    int max_threads;      /* "all threads" (the runs use 1 and this) */
    ctb_bind_policy bind; /* thread placement of every run */
    double direct_budget; /* direct runs only while nsec * nseg <= this */
    double bytes_per_node; /* memory estimate per target node ... */
    double mem_limit;      /* ... a size is skipped when it exceeds this */
    uint64_t seed;        /* mesh generator seed (shuffles, soups) */
} ctb_search_config;

/* Register the benchmarks; returns how many, or -1 on allocation failure.
 * The configuration is copied. */
int ctb_search_register(const ctb_search_config *c);

/* Free the cached mesh and the registrations (after gb_run). */
void ctb_search_cleanup(void);

#endif /* BENCH_SEARCH_H */
