/*
 * bench_scene.h -- whole runs of the driver's scenes (bench_scene.c).
 */
#ifndef BENCH_SCENE_H
#define BENCH_SCENE_H

#include "bench_search.h"

/* Register the benchmarks (the configuration is copied); returns how many,
 * or -1 on allocation failure. */
int ctb_scene_register(const ctb_search_config *c);

/* Free the registrations (after gb_run). */
void ctb_scene_cleanup(void);

#endif /* BENCH_SCENE_H */
