/*
 * bench_sync.h -- the cost of a parallel region and of a barrier with the
 * OpenMP runtime the programs link (bench_sync.c).
 */
#ifndef BENCH_SYNC_H
#define BENCH_SYNC_H

#include "bench_topology.h"

/* Register floor/sync/region and floor/sync/barrier with 1 and max_threads
 * threads bound by `bind`; returns how many, or -1 on allocation failure. */
int ctb_sync_register(ctb_bind_policy bind, int max_threads);

/* Free the benchmarks' descriptions (after gb_run). */
void ctb_sync_cleanup(void);

#endif /* BENCH_SYNC_H */
