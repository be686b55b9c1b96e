/*
 * bench_paired.h -- ratios of two searches measured in interleaved rounds
 * (bench_paired.c).
 */
#ifndef BENCH_PAIRED_H
#define BENCH_PAIRED_H

#include "bench_search.h"

/* Register the paired benchmarks; returns how many, or -1 on allocation
 * failure. The configuration is copied. */
int ctb_paired_register(const ctb_search_config *c);

/* Free the cached meshes and the registrations (after gb_run). */
void ctb_paired_cleanup(void);

#endif /* BENCH_PAIRED_H */
