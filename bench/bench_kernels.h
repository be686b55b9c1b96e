/*
 * bench_kernels.h -- the contact kernel benchmarks (bench_kernels.c): narrow
 * phase, force laws and friction, assembly variants, in ns per pair.
 */
#ifndef BENCH_KERNELS_H
#define BENCH_KERNELS_H

#include "bench_search.h"

/* Register the kernel benchmarks (the configuration is copied) and add the
 * precision to the report's context; returns how many, or -1 on
 * allocation failure. */
int ctb_kernels_register(const ctb_search_config *c);

/* Free the cached pair lists and the registrations (after gb_run). */
void ctb_kernels_cleanup(void);

#endif /* BENCH_KERNELS_H */
