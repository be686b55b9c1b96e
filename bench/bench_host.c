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
 *  - chain: dependent integer shift-xor-multiplies on each thread the benchmark
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
#include "ct_internal.h"

/* Steps of the chain: each a shift, an exclusive or and a 64-bit multiply
 * on the result of the one before (about 5 cycles: some 95 us at 3.4 GHz).
 * A plain multiply-add chain would not do: clang folds eight of its steps
 * into one (the composition of affine maps is affine) and ran it in 9 us. */
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

static uint64_t *rbuf;
static double last_at = -HUGE_VAL, last[GB_HOST_N];
static volatile uint64_t host_seed = 0x9e3779b97f4a7c15ull;
static volatile uint64_t host_sink;

static uint64_t chain(uint64_t a)
{
    for (int k = 0; k < HOST_CHAIN; k++)
        a = (a ^ (a >> 29)) * 0xbf58476d1ce4e5b9ull;
    return a;
}

/* The read buffer, once, filled (first touch by the team that reads it). */
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
        rbuf[i] = (uint64_t)i;
    return 0;
}

/* One barrier of a team of np threads, timed by thread 0 over
 * HOST_BARRIERS of them (s; 0 for one thread). */
static double barrier_once(int np)
{
    double bar = 0;
#pragma omp parallel num_threads(np)
    {
        const int team = cti_team_size();
#pragma omp barrier
        const double t0 = ctb_now_s();
        for (int b = 0; b < HOST_BARRIERS && team > 1; b++) {
#pragma omp barrier
        }
        if (cti_thread_id() == 0 && team > 1)
            bar = (ctb_now_s() - t0) / HOST_BARRIERS;
    }
    return bar;
}

/* One read of the buffer shared among a team of nt threads (s). */
static double read_once(int nt)
{
    const int64_t n = (int64_t)(HOST_READ_BYTES / sizeof *rbuf);
    uint64_t s = 0; /* an exclusive or: exact in any order, so the compilers vectorise it */
    const double t0 = ctb_now_s();
#pragma omp parallel for schedule(static) num_threads(nt) reduction(^ : s)
    for (int64_t i = 0; i < n; i++)
        s ^= rbuf[i];
    const double dt = ctb_now_s() - t0;
    host_sink = s; /* keeps the read */
    return dt;
}

/* f(n) timed until two timings in a row agree within HOST_AGREE (at most
 * HOST_TRIES times): the last. */
static double settled(double (*f)(int), int n)
{
    double prev = HUGE_VAL, dt = HUGE_VAL;
    for (int k = 0; k < HOST_TRIES; k++) {
        dt = f(n);
        if (dt <= HOST_AGREE * prev && prev <= HOST_AGREE * dt)
            break;
        prev = dt;
    }
    return dt;
}

/* The slowest thread's fastest of three chains on a team of nt (s); *size
 * the team's size. */
static double chain_time(int nt, int *size)
{
    double chain_s[HOST_MAX_THREADS * 8]; /* a cache line apart */
    const uint64_t seed = host_seed;
    int team = 1;
#pragma omp parallel num_threads(nt)
    {
        const int t = cti_thread_id();
        if (t == 0)
            team = cti_team_size();
        double best = HUGE_VAL;
        for (int k = 0; k < 3; k++) {
            const double t0 = ctb_now_s();
            const uint64_t a = chain(seed + (uint64_t)t);
            const double dt = ctb_now_s() - t0;
            best = dt < best ? dt : best;
            if (a == 0) /* almost never: keeps the chain */
                host_sink = (uint64_t)t;
        }
        chain_s[8 * t] = best;
    }
    double c = 0;
    for (int t = 0; t < team; t++)
        c = chain_s[8 * t] > c ? chain_s[8 * t] : c;
    *size = team;
    return c;
}

int ctb_host_probe(double out[GB_HOST_N])
{
    int nt = cti_num_threads();
    if (nt > HOST_MAX_THREADS)
        nt = HOST_MAX_THREADS;
    if (!(ctb_now_s() - last_at < HOST_EVERY_S && (int)last[0] == nt)) {
        if (buffer_ready())
            return -1;
        int size = 1, np = 1;
#ifdef _OPENMP
        np = omp_get_num_procs();
#endif
        const double c = chain_time(nt, &size);
        last[0] = size;
        last[1] = 1e6 * c;
        last[2] = 1e6 * settled(barrier_once, np < HOST_MAX_THREADS ? np : HOST_MAX_THREADS);
        last[3] = (double)HOST_READ_BYTES / settled(read_once, nt) * 1e-9;
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
