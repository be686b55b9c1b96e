/*
 * bench_sync.c -- what a parallel region and a barrier cost on this machine
 * with the OpenMP runtime the programs link (the floor of a cycle's fixed
 * cost; issue 5, item 3).
 *
 * Benchmarks (Google Benchmark appends "/real_time"):
 *   floor/sync/region/t<T>/<R>   R parallel regions, each a static loop of
 *                                one store per thread (no work to speak
 *                                of): counter us_per_region;
 *   floor/sync/barrier/t<T>/<R>  one parallel region whose threads meet at
 *                                R barriers: counter us_per_barrier.
 * A contact cycle of the driver runs some fifty of these (the kernels' and
 * the solver's loops, each a region or a work-sharing loop ending in a
 * barrier), whatever the model's size: on a small model they, not the
 * arithmetic, bound the cycle, and a second thread pays only when the
 * cycle's work outweighs them.
 */
#include "bench_sync.h"

#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* Regions or barriers per iteration. */
#define SYNC_REPEAT 2000

typedef struct sync_desc {
    int barrier; /* 0: regions, 1: barriers */
    int threads;
    ctb_bind_policy bind;
    struct sync_desc *next;
} sync_desc;

static sync_desc *descs;

/* r regions; sink holds one slot per thread, a cache line (8 doubles)
 * apart, for the regions' stores. */
static void regions(int64_t r, int threads, double *sink)
{
    for (int64_t k = 0; k < r; k++) {
#pragma omp parallel for schedule(static)
        for (int t = 0; t < threads; t++)
            sink[8 * t] += 1.0;
    }
}

static void barriers(int64_t r)
{
#pragma omp parallel
    {
        for (int64_t k = 0; k < r; k++) {
#pragma omp barrier
        }
    }
}

static void bm_sync(gb_state *st, void *arg)
{
    const sync_desc *d = arg;
    char where[256], msg[400];
    ctb_bind_threads(d->bind, d->threads, where, sizeof where);
    const int64_t r = gb_range(st, 0);
    double *sink = calloc(8 * (size_t)d->threads, sizeof *sink);
    if (!sink) {
        gb_skip_with_error(st, "sync: out of memory");
        return;
    }
    if (d->barrier) /* warm-up: the team is made */
        barriers(16);
    else
        regions(16, d->threads, sink);
    double t0 = ctb_now_s();
    while (gb_keep_running(st)) {
        if (d->barrier)
            barriers(r);
        else
            regions(r, d->threads, sink);
    }
    double dt = ctb_now_s() - t0;
    free(sink);
    int64_t it = gb_iterations(st);
    if (it <= 0)
        return;
    gb_set_counter(st, d->barrier ? "us_per_barrier" : "us_per_region",
                   dt / ((double)it * (double)r) * 1e6, GB_PLAIN);
    gb_set_counter(st, "threads", (double)d->threads, GB_PLAIN);
    snprintf(msg, sizeof msg, "prec=%s %s; %s[%s]", sizeof(ct_real) == 4 ? "single" : "double",
             d->barrier ? "barriers in one parallel region" : "parallel regions of a static loop",
             ctb_bind_name(d->bind), where);
    gb_set_label(st, msg);
}

int ctb_sync_register(ctb_bind_policy bind, int max_threads)
{
    int tlist[2] = {1, max_threads};
    int nt = max_threads > 1 ? 2 : 1;
    int count = 0;
    for (int b = 0; b < 2; b++)
        for (int t = 0; t < nt; t++) {
            sync_desc *d = calloc(1, sizeof *d);
            if (!d)
                return -1;
            d->barrier = b;
            d->threads = tlist[t];
            d->bind = bind;
            d->next = descs;
            descs = d;
            char name[96];
            snprintf(name, sizeof name, "floor/sync/%s/t%d", b ? "barrier" : "region",
                     tlist[t]);
            if (gb_register(name, bm_sync, d, SYNC_REPEAT, 1, 0, 0) != 0)
                return -1;
            count++;
        }
    return count;
}

void ctb_sync_cleanup(void)
{
    while (descs) {
        sync_desc *n = descs->next;
        free(descs);
        descs = n;
    }
}
