/*
 * bench_elements.h -- the driver's shell element benchmarks
 * (bench_elements.c).
 */
#ifndef BENCH_ELEMENTS_H
#define BENCH_ELEMENTS_H

#include "bench_search.h"

/* Register the benchmarks (the configuration is copied); returns how many,
 * or -1 on allocation failure. */
int ctb_elements_register(const ctb_search_config *c);

/* Free the kept shell and the registrations (after gb_run). */
void ctb_elements_cleanup(void);

#endif /* BENCH_ELEMENTS_H */
