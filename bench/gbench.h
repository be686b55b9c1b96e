/*
 * gbench.h -- a small C API over Google Benchmark (bench/gbench_shim.cc).
 *
 * Benchmarks are written in C: a benchmark is a function gb_fn that
 * prepares its data (untimed), then loops `while (gb_keep_running(st))`
 * around the code to time, and finally sets counters and a label. The
 * shim registers it with Google Benchmark, which chooses the iteration
 * count, repeats, aggregates (mean, median, ...) and writes the console
 * table and the JSON file.
 */
#ifndef GBENCH_H
#define GBENCH_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Wraps benchmark::State. */
typedef struct gb_state gb_state;
typedef void (*gb_fn)(gb_state *st, void *arg);

/* Counter flags, mapped onto benchmark::Counter::Flags by the shim.
 * GB_RATE: divide by the measured time; GB_ITER_INVARIANT: multiply by the
 * iteration count; GB_AVG_ITERATIONS: divide by the iteration count;
 * GB_INVERT: take the reciprocal after the above. */
enum {
    GB_PLAIN = 0,
    GB_RATE = 1 << 0,
    GB_AVG_THREADS = 1 << 1,
    GB_ITER_INVARIANT = 1 << 2,
    GB_AVG_ITERATIONS = 1 << 3,
    GB_INVERT = 1 << 4
};

/*
 * Register benchmark `name` calling fn(st, arg). arg must stay valid until
 * gb_run returns. Options: range0 >= 0 appends "/<range0>" to the name and
 * is read back with gb_range(st, 0) (negative: no argument);
 * use_real_time != 0 measures wall-clock time (use it for OpenMP code);
 * iterations > 0 fixes the iteration count (0: Google Benchmark decides);
 * min_time_s > 0 sets this benchmark's minimum time (it then overrides
 * --benchmark_min_time; 0: the command-line value). Returns 0, or -1 when
 * name or fn is NULL.
 */
int gb_register(const char *name, gb_fn fn, void *arg, int64_t range0, int use_real_time,
                int64_t iterations, double min_time_s);

/* The timed loop: `while (gb_keep_running(st)) { ... }`. */
int gb_keep_running(gb_state *st);

/* Argument i (only i == 0 is set by gb_register). */
int64_t gb_range(gb_state *st, int i);

/* Iterations run so far (after the loop: the total). */
int64_t gb_iterations(gb_state *st);

/* A user counter (shown as a column, stored in the JSON). */
void gb_set_counter(gb_state *st, const char *name, double value, int flags);

void gb_set_label(gb_state *st, const char *label);

/* Mark the run as failed with a message; call it before the loop (the loop
 * then does not run) or inside it and `break`. */
void gb_skip_with_error(gb_state *st, const char *msg);

/* Exclude a part of an iteration from the measured time. */
void gb_pause_timing(gb_state *st);
void gb_resume_timing(gb_state *st);

void gb_set_items_processed(gb_state *st, int64_t n);

/* A probe of the host's speed (bench_host.c) that the shim runs after
 * every call of a benchmark function that did not fail, untimed: it fills
 * out[0..GB_HOST_N-1] and returns 0, and the shim sets them as the
 * counters GB_HOST_THREADS, GB_HOST_CHAIN, GB_HOST_BARRIER (when above 0)
 * and GB_HOST_READ of the run. NULL (the default): no probe. Call before
 * gb_run. */
#define GB_HOST_N 4
typedef int (*gb_probe_fn)(double out[GB_HOST_N]);
#define GB_HOST_THREADS "host_threads"
#define GB_HOST_CHAIN "host_chain_us"
#define GB_HOST_BARRIER "host_barrier_us"
#define GB_HOST_READ "host_read_GBps"
void gb_set_host_probe(gb_probe_fn fn);
/* A key/value pair for the context block of every report (console and
 * JSON "context"). Call before gb_run. */
void gb_add_context(const char *key, const char *value);

/*
 * Initialize (consumes the --benchmark_* flags of argv), reject unknown
 * arguments, run the benchmarks that match --benchmark_filter, shut down.
 * Returns 0, 1 for unrecognized arguments, 2 when no benchmark matched
 * the filter, 3 on an internal exception.
 */
int gb_run(int *argc, char **argv);

#ifdef __cplusplus
}
#endif

#endif /* GBENCH_H */
