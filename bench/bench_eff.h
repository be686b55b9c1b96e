/*
 * bench_eff.h -- parallel efficiency measured in interleaved rounds
 * (bench_eff.c), for the kernel and triad benchmarks.
 */
#ifndef BENCH_EFF_H
#define BENCH_EFF_H

#include "bench_topology.h"
#include "gbench.h"

/* One call of the code to time; returns 0 (CT_OK) or an error code. */
typedef int (*ctb_eff_call)(void *arg);

/*
 * Time `call` with 1 thread and with `nthreads` threads in alternating
 * rounds (which goes first alternates too), inside one Google Benchmark run
 * of one iteration (register it with iterations = 1). The threads are bound
 * once for nthreads by `bind`; a 1-thread call runs on the team's first
 * thread. Counters: ns_t1 and ns_tn (median ns per unit over the rounds,
 * `units` per call), eff (median of the rounds' t1 / (nthreads tn)),
 * eff_min, eff_max, eff_best (from the best 1-thread and all-threads
 * times), rounds, calls, threads (nthreads). Returns the first error of
 * a call (the benchmark is then marked failed) or 0. `where` receives the
 * binding (for the label).
 */
int ctb_eff_run(gb_state *st, ctb_eff_call call, void *arg, double units, int nthreads,
                ctb_bind_policy bind, char *where, size_t wlen);

#endif /* BENCH_EFF_H */
