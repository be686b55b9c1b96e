/*
 * bench_host.h -- how fast the host ran while a benchmark ran
 * (bench_host.c): a short probe after every call of a benchmark, whose
 * figures go into that benchmark's row.
 */
#ifndef BENCH_HOST_H
#define BENCH_HOST_H

#include "gbench.h"

/* Runs the probe on the current OpenMP team size (the threads the
 * benchmark just used), or returns the last one's figures when it ran less
 * than half a second ago on as many threads: out[0] the team's size,
 * out[1] the time of a fixed chain of dependent integer operations on its
 * slowest thread, in microseconds, out[2] one barrier of a team on every
 * processor, in microseconds (0 with one processor), out[3] the bandwidth
 * of one read of 64 MiB shared among the team, in GB/s. Returns 0, or -1 (out untouched)
 * when the buffer cannot be allocated. The shim sets the four as the
 * counters GB_HOST_THREADS, GB_HOST_CHAIN, GB_HOST_BARRIER and GB_HOST_READ
 * (gbench.h). */
int ctb_host_probe(double out[GB_HOST_N]);

/* Free the probe's buffer (after gb_run). */
void ctb_host_cleanup(void);

#endif /* BENCH_HOST_H */
