/*
 * bench_cycle.h -- the full contact cycle, measured per phase
 * (bench_cycle.c; issue 5 item 6).
 */
#ifndef BENCH_CYCLE_H
#define BENCH_CYCLE_H

#include "bench_search.h"

/* Register the cycle benchmarks (the configuration is copied); returns how
 * many, or -1 on allocation failure. */
int ctb_cycle_register(const ctb_search_config *c);

/* Free the cached scene and the registrations (after gb_run). */
void ctb_cycle_cleanup(void);

#endif /* BENCH_CYCLE_H */
