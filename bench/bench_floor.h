/*
 * bench_floor.h -- the hardware floor benchmarks (bench_floor.c): the
 * measured memory bandwidth (a STREAM-triad-like kernel) and, from the byte
 * model of floor.h, the lower bound of the bucket search on plates and the
 * ratio measured / floor.
 */
#ifndef BENCH_FLOOR_H
#define BENCH_FLOOR_H

#include "bench_search.h"

/* Register the floor benchmarks (the configuration is copied); returns how
 * many, or -1 on allocation failure. */
int ctb_floor_register(const ctb_search_config *c);

/* Free the arrays and the mesh kept between runs (after gb_run). */
void ctb_floor_cleanup(void);

#endif /* BENCH_FLOOR_H */
