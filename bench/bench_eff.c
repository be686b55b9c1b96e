/*
 * bench_eff.c -- the 2-thread efficiency target of issue 3 measured in
 * interleaved rounds.
 *
 * The kernel table's efficiency divides the 1-thread row by the all-threads
 * row, two runs made one after the other; on a shared host their
 * conditions differ (the kernel rows read 59 % to 110 % across runs of the
 * same code).
 * Here one benchmark times the same call with 1 thread and with all
 * threads, round after round, alternating which goes first, and reports
 * the median of the rounds' efficiencies with their range. Each timing is
 * the median of a few calls, enough to last about 20 ms.
 */
#include "bench_eff.h"

#include <stdlib.h>

#include "bench_common.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* Rounds per run; calls per timing so that it lasts at least EFF_MIN_S. */
#define EFF_ROUNDS 7
#define EFF_MIN_S 0.02
#define EFF_MAX_CALLS 64

static void set_threads(int n)
{
#ifdef _OPENMP
    omp_set_num_threads(n);
#else
    (void)n;
#endif
}


/* The median seconds of k calls with n threads. */
static int timed(ctb_eff_call call, void *arg, int n, int k, double *sec)
{
    double t[EFF_MAX_CALLS];
    set_threads(n);
    for (int i = 0; i < k; i++) {
        double t0 = ctb_now_s();
        int rc = call(arg);
        t[i] = ctb_now_s() - t0;
        if (rc != 0)
            return rc;
    }
    *sec = ctb_median(t, k);
    return 0;
}

int ctb_eff_run(gb_state *st, ctb_eff_call call, void *arg, double units, int nthreads,
                ctb_bind_policy bind, char *where, size_t wlen)
{
    ctb_bind_threads(bind, nthreads, where, wlen);
    /* Warm-up with both team sizes; the first timing sizes the calls. */
    double w1 = 0, wn = 0;
    int rc = timed(call, arg, 1, 1, &w1);
    if (rc == 0)
        rc = timed(call, arg, nthreads, 1, &wn);
    int k = 1;
    if (rc == 0 && wn > 0)
        while (k < EFF_MAX_CALLS && (double)k * wn < EFF_MIN_S)
            k++;
    double t1[EFF_ROUNDS], tn[EFF_ROUNDS], e[EFF_ROUNDS];
    int r = 0;
    while (rc == 0 && gb_keep_running(st)) {
        for (r = 0; r < EFF_ROUNDS && rc == 0; r++) {
            if (r % 2 == 0) {
                rc = timed(call, arg, 1, k, &t1[r]);
                if (rc == 0)
                    rc = timed(call, arg, nthreads, k, &tn[r]);
            } else {
                rc = timed(call, arg, nthreads, k, &tn[r]);
                if (rc == 0)
                    rc = timed(call, arg, 1, k, &t1[r]);
            }
            e[r] = t1[r] / ((double)nthreads * tn[r]);
        }
    }
    set_threads(nthreads);
    if (rc != 0 || r != EFF_ROUNDS)
        return rc;
    double emin, emax, b1, bn, unused;
    ctb_minmax(e, r, &emin, &emax);
    ctb_minmax(t1, r, &b1, &unused);
    ctb_minmax(tn, r, &bn, &unused);
    /* From the best times (a busy host only ever adds time, STREAM's
     * rule): the efficiency the machine gives when left alone. */
    gb_set_counter(st, "eff_best", b1 / ((double)nthreads * bn), GB_PLAIN);
    gb_set_counter(st, "ns_t1", ctb_median(t1, r) * 1e9 / units, GB_PLAIN);
    gb_set_counter(st, "ns_tn", ctb_median(tn, r) * 1e9 / units, GB_PLAIN);
    gb_set_counter(st, "eff", ctb_median(e, r), GB_PLAIN);
    gb_set_counter(st, "eff_min", emin, GB_PLAIN);
    gb_set_counter(st, "eff_max", emax, GB_PLAIN);
    gb_set_counter(st, "rounds", (double)r, GB_PLAIN);
    gb_set_counter(st, "calls", (double)k, GB_PLAIN);
    gb_set_counter(st, "threads", (double)nthreads, GB_PLAIN);
    return 0;
}
