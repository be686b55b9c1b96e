/*
 * bench_host.c -- a probe of the host's speed, run after the calls of the
 * benchmark functions (the shim calls it; gbench.h, gb_set_host_probe).
 *
 * The machines we measure on are virtual and shared. Two whole `make
 * bench` runs on one machine read the same rows up to 2.5 times apart,
 * each row steady within its run (so the spread of its repetitions, the
 * report's cv, does not show it). A probe on one thread (a chain of
 * integer operations, loads along a random cycle, a streaming read) moved
 * by a few per cent between such runs. What moved was where the host put
 * the two virtual CPUs: in one run a barrier of the two took 0.19 us, in
 * the next 0.8 (the region and barrier rows 4 times apart, small searches
 * on two threads 1.4 to 2 times slower, while the memory-bound kernels on
 * two threads ran 1.4 to 2 times faster and the one-thread searches 1.4
 * times faster: two virtual CPUs on one core's two hardware threads, then
 * on two cores, by every sign). So the probe, right after a benchmark:
 *  - chain: dependent integer multiply-adds on each thread the benchmark
 *    used (no memory: the cores' clock and the share of it the host gives
 *    each virtual CPU), the slowest thread's time;
 *  - barrier: one barrier of a team on every processor (how far apart the
 *    host placed the virtual CPUs), whatever the benchmark's threads;
 *  - read: one streaming read of 64 MiB shared among the benchmark's
 *    threads, as a bandwidth.
 * The barrier and the read are timed until two timings in a row agree
 * within HOST_AGREE (see there), the chain's fastest of three is kept, and
 * a probe less than HOST_EVERY_S after the last one on as many threads
 * returns the last one's figures: this keeps the probe's cost near 1 % of
 * a run. The report (bench/report_noise.py) compares each row's figures
 * with the run's usual ones. The probe runs outside the timed loop, after
 * the benchmark's own clean-up.
 */
#include "bench_host.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "bench_common.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* Multiply-adds in the chain: at 4 cycles each (a 64-bit multiply's
 * latency plus an add), about 80 us at 3.4 GHz. */
#define HOST_CHAIN 65536
/* Barriers per timing. */
#define HOST_BARRIERS 256
/* The read buffer, bytes: larger than the last-level caches we run on. */
#define HOST_READ_BYTES ((size_t)64 << 20)
/* The barrier and the read are timed until two timings in a row agree
 * within HOST_AGREE (at most HOST_TRIES times), and the last is kept.
 * After a benchmark that freed a few hundred megabytes, every page of the
 * process is slow to touch again for a while: loads along a random cycle
 * through 32 MiB took 2900, 1200, 560, 300, 210 ns in successive timings
 * before settling at 160, and a first read of this buffer 68 ms instead of
 * 2, with no page fault the guest sees (a small program that wrote and
 * freed 400 MB saw the same after one of its two frees; this host's kernel
 * runs paravirtualised, its page tables shadowed by the host). The settled
 * figure is the host's speed, not that transient. */
#define HOST_TRIES 16
#define HOST_AGREE 1.05
/* A probe this soon after the last one returns its figures. */
#define HOST_EVERY_S 0.5
/* Threads the probe's slots can hold. */
#define HOST_MAX_THREADS 256

static double *rbuf;
static double last_at = -HUGE_VAL, last[GB_HOST_N];
static volatile uint64_t host_seed = 0x9e3779b97f4a7c15ull;
static volatile double host_sink;

static uint64_t chain(uint64_t a)
{
    for (int k = 0; k < HOST_CHAIN; k++)
        a = a * 6364136223846793005ull + 1442695040888963407ull;
    return a;
}

/* The read buffer, once, filled with ones. */
static int buffer_ready(void)
{
    if (rbuf)
        return 0;
    rbuf = aligned_alloc(64, HOST_READ_BYTES);
    if (!rbuf)
        return -1;
    const int64_t n = (int64_t)(HOST_READ_BYTES / sizeof *rbuf);
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < n; i++)
        rbuf[i] = 1.0;
    return 0;
}

/* Whether timing b agrees with the one before it, a, within HOST_AGREE. */
static int settled(double a, double b)
{
    return b <= HOST_AGREE * a && a <= HOST_AGREE * b;
}

static int thread_id(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

static int team_size(void)
{
#ifdef _OPENMP
    return omp_get_num_threads();
#else
    return 1;
#endif
}

/* The settled time of one barrier of a team of np threads (s; 0 for one
 * thread). */
static double barrier_time(int np)
{
    double bar = 0;
    int stop = 0; /* written by thread 0 between barriers */
#pragma omp parallel num_threads(np)
    {
        /* Thread 0 times the barriers and decides, for all, when to stop
         * (each thread reads the flag after a barrier that follows its
         * write, and it is written again only after the next barrier). */
        const int t = thread_id();
        int done = team_size() == 1;
        double prev = HUGE_VAL;
        for (int k = 0; !done; k++) {
#pragma omp barrier
            const double t0 = ctb_now_s();
            for (int b = 0; b < HOST_BARRIERS; b++) {
#pragma omp barrier
            }
            if (t == 0) {
                bar = (ctb_now_s() - t0) / HOST_BARRIERS;
                stop = k + 1 >= HOST_TRIES || settled(prev, bar);
                prev = bar;
            }
#pragma omp barrier
            done = stop;
        }
    }
    return bar;
}

/* On a team of nt: out[1] the slowest thread's fastest chain (s), out[3]
 * the settled read's time (s); out[0] the team's size. */
static void probe_team(int nt, double out[GB_HOST_N])
{
    double chain_s[HOST_MAX_THREADS * 8]; /* a cache line apart */
    const uint64_t seed = host_seed;
    const int64_t n = (int64_t)(HOST_READ_BYTES / sizeof *rbuf);
    double rd = HUGE_VAL;
    int size = 1, stop = 0; /* written by thread 0 between barriers */
#pragma omp parallel num_threads(nt)
    {
        const int t = thread_id(), team = team_size();
        double best = HUGE_VAL;
        for (int k = 0; k < 3; k++) {
            const double t0 = ctb_now_s();
            const uint64_t a = chain(seed + (uint64_t)t);
            const double dt = ctb_now_s() - t0;
            best = dt < best ? dt : best;
            if (a == 0) /* almost never: keeps the chain */
                host_sink = (double)t;
        }
        chain_s[8 * t] = best;
        if (t == 0)
            size = team;
        /* The read, each thread its static share, timed by thread 0
         * between barriers. */
        const int64_t lo = n * t / team, hi = n * (t + 1) / team;
        double prev = HUGE_VAL;
        int done = 0;
        for (int k = 0; !done; k++) {
#pragma omp barrier
            const double t0 = ctb_now_s();
            double s = 0;
#pragma omp simd reduction(+ : s)
            for (int64_t i = lo; i < hi; i++)
                s += rbuf[i];
            if (s < 0) /* never: keeps the sum */
                host_sink = s;
#pragma omp barrier
            if (t == 0) {
                rd = ctb_now_s() - t0;
                stop = k + 1 >= HOST_TRIES || settled(prev, rd);
                prev = rd;
            }
#pragma omp barrier
            done = stop;
        }
    }
    double c = 0;
    for (int t = 0; t < size; t++)
        c = chain_s[8 * t] > c ? chain_s[8 * t] : c;
    out[0] = size;
    out[1] = c;
    out[3] = rd;
}

int ctb_host_probe(double out[GB_HOST_N])
{
    int nt = 1;
#ifdef _OPENMP
    nt = omp_get_max_threads();
#endif
    if (nt > HOST_MAX_THREADS)
        nt = HOST_MAX_THREADS;
    if (!(ctb_now_s() - last_at < HOST_EVERY_S && (int)last[0] == nt)) {
        if (buffer_ready())
            return -1;
        double v[GB_HOST_N];
        probe_team(nt, v);
        int np = 1;
#ifdef _OPENMP
        np = omp_get_num_procs();
#endif
        v[2] = barrier_time(np < HOST_MAX_THREADS ? np : HOST_MAX_THREADS);
        last[0] = v[0];
        last[1] = 1e6 * v[1];
        last[2] = 1e6 * v[2];
        last[3] = (double)HOST_READ_BYTES / v[3] * 1e-9;
        last_at = ctb_now_s();
    }
    for (int k = 0; k < GB_HOST_N; k++)
        out[k] = last[k];
    return 0;
}

void ctb_host_cleanup(void)
{
    free(rbuf);
    rbuf = NULL;
}
