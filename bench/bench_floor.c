/*
 * bench_floor.c -- the hardware floor, measured in the same run as the
 * searches (issue 5, item 3).
 *
 * Benchmarks (Google Benchmark appends "/real_time"):
 *   floor/triad/dram/t<T>/<n>   a[i] = b[i] + s c[i] over three arrays of n
 *                               doubles, together 4 times the last-level
 *                               cache (each at most 1/12 of the memory,
 *                               at least 64 MiB): the memory
 *                               bandwidth (counter GBps, bytes counted as
 *                               STREAM does, 24 per element);
 *   floor/triad/ws/t<T>/<n>     the same over arrays holding together the
 *                               byte model of the bucket search on plates at
 *                               10^6 nodes: the bandwidth at the search's
 *                               own working-set size (on a machine whose
 *                               last-level cache holds that working set, this
 *                               is the cache's bandwidth, not DRAM's);
 *   floor/bucket/plates/t<T>/<nodes>  the bucket search on plates (as in
 *                               the search benchmarks: gap 0.3 h, margin
 *                               0.2 h), its time per node, the byte model
 *                               of floor.h, and the floor and ratio
 *                               measured / floor for both bandwidths;
 *   efficiency/triad/dram/t<T>/<n> and efficiency/compute/t<T>/<n>  the
 *                               machine's own 2-thread efficiency on a loop
 *                               that only streams memory and on one that
 *                               only computes (bench_eff.c): the ceilings of
 *                               the kernels' efficiency rows;
 *   floor/sync/region|barrier/t<T>/<R>  what one parallel region and one
 *                               barrier cost (bench_sync.c).
 * The arrays are allocated and first touched by the team that runs the
 * kernel (static schedule, the same as the kernel's), and kept while the
 * thread count stays the same. The bandwidth used for the floor is the best
 * triad of this run with the same thread count (STREAM reports the best
 * time); when the triad benchmarks were filtered out it is measured inside
 * the floor benchmark, untimed (the label says so).
 */
#include "bench_floor.h"

#include "bench_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_eff.h"
#include "bench_sync.h"
#include "bench_topology.h"
#include "contact.h"
#include "floor.h"
#include "gbench.h"
#include "meshgen.h"

static ctb_search_config cfg;

enum { TRIAD_DRAM = 0, TRIAD_WS = 1 };
static const char *const triad_kind_name[2] = {"dram", "ws"};

typedef struct floor_desc {
    int kind;      /* benchmark: 0 triad, 1 bucket, 2 triad efficiency, 3 compute
                      efficiency */
    int triad;     /* TRIAD_DRAM or TRIAD_WS */
    int64_t n;     /* triad elements per array, or target nodes */
    int threads;
    struct floor_desc *next;
} floor_desc;

static floor_desc *descs;

/* Best bandwidth (GB/s) of this run per triad kind and thread slot (0: one
 * thread, 1: all threads); 0 while not measured. */
static double best_bw[2][2];

/* The triad arrays of the last run. */
static struct {
    double *a, *b, *c;
    int64_t n;
    int threads;
} tri;

/* The plates mesh of the bucket benchmarks. */
static struct {
    int valid, rc;
    char err[300];
    int64_t target;
    ctb_mesh m;      /* first-touched copies of the search input */
    int64_t touched; /* nnode of the byte model */
} pm;

static const char *prec_name(void) { return sizeof(ct_real) == 4 ? "single" : "double"; }

static int slot_of(int threads) { return threads > 1 ? 1 : 0; }

/* The largest cache of cpu0 in bytes (sysfs), 32 MiB when unknown. */
static double llc_bytes(void)
{
    double best = 0;
    for (int i = 0; i < 8; i++) {
        char path[96];
        snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/size", i);
        FILE *f = fopen(path, "r");
        if (!f)
            continue;
        double v = 0;
        char unit = 0;
        if (fscanf(f, "%lf%c", &v, &unit) >= 1) {
            if (unit == 'K')
                v *= 1024;
            else if (unit == 'M')
                v *= 1024 * 1024;
            if (v > best)
                best = v;
        }
        fclose(f);
    }
    return best > 0 ? best : 32.0 * 1024 * 1024;
}

/* ---- Triad ---------------------------------------------------------------- */

static void triad(int64_t n, double *restrict a, const double *restrict b,
                  const double *restrict c, double s)
{
#pragma omp parallel for simd schedule(static)
    for (int64_t i = 0; i < n; i++)
        a[i] = b[i] + s * c[i];
}

static void triad_free(void)
{
    ctb_free(tri.a);
    ctb_free(tri.b);
    ctb_free(tri.c);
    memset(&tri, 0, sizeof tri);
}

/* Arrays of n doubles first touched by the current team (the caller has set
 * the thread count); kept while n and the thread count stay. */
static int triad_arrays(int64_t n, int threads)
{
    if (tri.a && tri.n == n && tri.threads == threads)
        return 0;
    triad_free();
    tri.a = ctb_first_touch_alloc((size_t)n, sizeof(double));
    tri.b = ctb_first_touch_alloc((size_t)n, sizeof(double));
    tri.c = ctb_first_touch_alloc((size_t)n, sizeof(double));
    if (!tri.a || !tri.b || !tri.c) {
        triad_free();
        return -1;
    }
    double *restrict b = tri.b, *restrict c = tri.c;
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < n; i++) {
        b[i] = 1.0 + 1e-9 * (double)(i & 1023);
        c[i] = 2.0 - 1e-9 * (double)(i & 511);
    }
    tri.n = n;
    tri.threads = threads;
    return 0;
}

/* Elements per array of each kind. */
static int64_t triad_n(int kind)
{
    if (kind == TRIAD_WS) {
        /* The model of plates at 10^6 nodes: nsec = nseg = 10^6, about 2 10^6
         * touched nodes and 3 10^6 pairs (measured: 2.94 pairs per node). */
        ctb_floor_terms t = ctb_floor_search_bytes(1000000, 1000000, 2002001, 3000000,
                                                   sizeof(ct_real), sizeof(ct_idx));
        return (int64_t)(t.total / 24.0);
    }
    /* The three arrays together are 4 times the last-level cache. STREAM
     * asks for 4 times per array, which is 6 GB here (480 MiB of L3); a
     * cyclic sweep over a footprint several times an LRU-like cache's size
     * finds nothing of it left in the cache, so 4 times in total suffices
     * and keeps the run short. */
    double want = 4.0 / 3.0 * llc_bytes();
    long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGESIZE);
    double mem = pages > 0 && psize > 0 ? (double)pages * (double)psize : 8e9;
    if (want > mem / 12)
        want = mem / 12;
    if (want < 64.0 * 1024 * 1024)
        want = 64.0 * 1024 * 1024;
    return (int64_t)(want / sizeof(double));
}

/* Measure the best of `passes` triads (untimed by Google Benchmark). */
static double triad_measure(int kind, int threads, int passes)
{
    ctb_bind_threads(cfg.bind, threads, NULL, 0);
    int64_t n = triad_n(kind);
    if (triad_arrays(n, threads) != 0)
        return -1;
    double best = 0;
    triad(n, tri.a, tri.b, tri.c, 3.0);
    for (int p = 0; p < passes; p++) {
        double t0 = ctb_now_s();
        triad(n, tri.a, tri.b, tri.c, 3.0);
        double g = ctb_gbps(ctb_triad_bytes(n, sizeof(double)), ctb_now_s() - t0);
        if (g > best)
            best = g;
    }
    return best;
}

/* Bind d's threads and make its arrays (first touched by them); 0, or -1
 * with the benchmark marked failed. */
static int triad_ready(gb_state *st, const floor_desc *d, char *where, size_t len)
{
    ctb_bind_threads(cfg.bind, d->threads, where, len);
    if (triad_arrays(d->n, d->threads) != 0) {
        gb_skip_with_error(st, "triad: out of memory");
        return -1;
    }
    return 0;
}

static void bm_triad(gb_state *st, void *arg)
{
    const floor_desc *d = arg;
    char where[256], msg[400];
    if (triad_ready(st, d, where, sizeof where) != 0)
        return;
    triad(d->n, tri.a, tri.b, tri.c, 3.0); /* warm-up */
    double t0 = ctb_now_s();
    while (gb_keep_running(st))
        triad(d->n, tri.a, tri.b, tri.c, 3.0);
    double dt = ctb_now_s() - t0;
    int64_t it = gb_iterations(st);
    if (it <= 0)
        return;
    /* Keep the result alive (a[i] = 1 + 3 * 2 = 7 about). */
    if (tri.a[d->n / 2] < 0)
        gb_set_label(st, "impossible");
    double bytes = ctb_triad_bytes(d->n, sizeof(double));
    double g = ctb_gbps(bytes * (double)it, dt);
    double *best = &best_bw[d->triad][slot_of(d->threads)];
    if (g > *best)
        *best = g;
    gb_set_counter(st, "GBps", g, GB_PLAIN);
    gb_set_counter(st, "array_MiB", (double)d->n * 8.0 / 1048576.0, GB_PLAIN);
    gb_set_counter(st, "threads", (double)d->threads, GB_PLAIN);
    snprintf(msg, sizeof msg, "prec=%s triad %s: 3 arrays x %.0f MiB (LLC %.0f MiB) %s[%s]",
             prec_name(), triad_kind_name[d->triad], (double)d->n * 8.0 / 1048576.0,
             llc_bytes() / 1048576.0, ctb_bind_name(cfg.bind), where);
    gb_set_label(st, msg);
}

/* ---- The bucket search against its floor --------------------------------- */

static void plates_clear(void)
{
    ctb_mesh_clear(&pm.m);
    memset(&pm, 0, sizeof pm);
}

/* The plates case of `target` nodes as the search benchmarks build it
 * (ctb_mesh_case: gap 0.3 h, margin 0.2 h), or the current one. */
static void plates_get(int64_t target)
{
    if (pm.valid && pm.target == target)
        return;
    plates_clear();
    pm.valid = 1;
    pm.target = target;
    double h;
    pm.rc = ctb_mesh_case(&pm.m, "plates", target, CTD_NUM_NATURAL, &cfg, &h, pm.err,
                          sizeof pm.err);
    if (pm.rc != CT_OK)
        return;
    const ct_search_input *in = &pm.m.in;
    pm.touched = ctb_floor_touched_nodes(in->nnode, in->nsec, in->sec, in->nseg, in->n1, in->n2,
                                         in->n3, in->n4);
    if (pm.touched < 0) {
        pm.rc = CT_ERR_NOMEM;
        snprintf(pm.err, sizeof pm.err, "mesh input: %s", ct_strerror(pm.rc));
    }
}

static void bm_bucket(gb_state *st, void *arg)
{
    const floor_desc *d = arg;
    char where[256], msg[512];
    if ((double)d->n * cfg.bytes_per_node > cfg.mem_limit) {
        gb_skip_with_error(st, "skipped: not enough memory");
        return;
    }
    /* Bandwidths of this thread count: from the triad benchmarks, or
     * measured here. */
    int slot = slot_of(d->threads);
    int measured_here = 0;
    for (int k = 0; k < 2; k++)
        if (best_bw[k][slot] <= 0) {
            double g = triad_measure(k, d->threads, k == TRIAD_DRAM ? 3 : 10);
            if (g > best_bw[k][slot])
                best_bw[k][slot] = g;
            measured_here = 1;
        }
    if (measured_here)
        triad_free();
    plates_get(d->n);
    if (pm.rc != CT_OK) {
        gb_skip_with_error(st, pm.err);
        return;
    }
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);
    const ct_search_input *in = &pm.m.in;
    ct_search *s;
    ct_pairs out;
    int rc = ctb_search_start(CT_SEARCH_BUCKET, in, &s, &out); /* untimed: workspace growth */
    double dt = 0;
    if (rc == CT_OK)
        rc = ctb_search_timed(st, s, in, &out, &dt);
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "bucket search: %s", ct_strerror(rc));
        gb_skip_with_error(st, msg);
    }
    int64_t it = gb_iterations(st);
    if (rc == CT_OK && it > 0) {
        double ns = dt * 1e9 / ((double)it * (double)in->nsec);
        ctb_floor_terms t = ctb_floor_search_bytes(in->nsec, in->nseg, pm.touched, out.n,
                                                   sizeof(ct_real), sizeof(ct_idx));
        double fd = ctb_floor_ns_per_node(t.total, in->nsec, best_bw[TRIAD_DRAM][slot]);
        double fw = ctb_floor_ns_per_node(t.total, in->nsec, best_bw[TRIAD_WS][slot]);
        gb_set_counter(st, "ns_per_node", ns, GB_PLAIN);
        gb_set_counter(st, "nsec", (double)in->nsec, GB_PLAIN);
        gb_set_counter(st, "nseg", (double)in->nseg, GB_PLAIN);
        gb_set_counter(st, "nnode", (double)pm.touched, GB_PLAIN);
        gb_set_counter(st, "pairs", (double)out.n, GB_PLAIN);
        gb_set_counter(st, "floor_bytes_per_node", t.total / (double)in->nsec, GB_PLAIN);
        gb_set_counter(st, "GBps_dram", best_bw[TRIAD_DRAM][slot], GB_PLAIN);
        gb_set_counter(st, "GBps_ws", best_bw[TRIAD_WS][slot], GB_PLAIN);
        gb_set_counter(st, "floor_ns_dram", fd, GB_PLAIN);
        gb_set_counter(st, "floor_ns_ws", fw, GB_PLAIN);
        gb_set_counter(st, "ratio_dram", fd > 0 ? ns / fd : -1, GB_PLAIN);
        gb_set_counter(st, "ratio_ws", fw > 0 ? ns / fw : -1, GB_PLAIN);
        gb_set_counter(st, "threads", (double)d->threads, GB_PLAIN);
        snprintf(msg, sizeof msg,
                 "prec=%s bytes/node: sec %.1f + coords %.1f + conn %.1f + pairs %.1f; "
                 "bandwidth %s %s[%s]",
                 prec_name(), t.sec_list / (double)in->nsec, t.coords / (double)in->nsec,
                 t.conn / (double)in->nsec, t.pairs / (double)in->nsec,
                 measured_here ? "measured here" : "from the triad benchmarks",
                 ctb_bind_name(cfg.bind), where);
        gb_set_label(st, msg);
    }
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
}

/* The machine's own 2-thread efficiency on a memory-bound loop: the DRAM
 * triad, 1 thread against all in interleaved rounds (bench_eff.c), the
 * ceiling of every kernel that streams from memory. */
static int triad_call(void *arg)
{
    const floor_desc *d = arg;
    triad(d->n, tri.a, tri.b, tri.c, 3.0);
    return 0;
}

static void bm_triad_eff(gb_state *st, void *arg)
{
    const floor_desc *d = arg;
    char where[256], msg[400];
    if (triad_ready(st, d, where, sizeof where) != 0)
        return;
    ctb_eff_run(st, triad_call, (void *)d, (double)ctb_triad_bytes(d->n, sizeof(double)),
                d->threads, cfg.bind, where, sizeof where);
    snprintf(msg, sizeof msg, "triad %s, %.0f MiB per array; ns_t1 and ns_tn per byte; "
             "1 against %d threads; %s[%s]", triad_kind_name[d->triad],
             (double)d->n * sizeof(double) / (1024.0 * 1024.0), d->threads,
             ctb_bind_name(cfg.bind), where);
    gb_set_label(st, msg);
}

/* The machine's own 2-thread efficiency on a loop that only computes: the
 * ceiling of the kernels bound by their arithmetic, as the triad is of
 * those bound by memory. Each block of COMPUTE_STEPS steps runs
 * COMPUTE_LANES independent multiply-adds per step on its own accumulators
 * (registers, no memory traffic); the blocks are shared among the team.
 * Below 90 % here, the host's second core was not all ours. */
#define COMPUTE_LANES 32
#define COMPUTE_STEPS 4096

static double compute_block(int64_t b)
{
    double acc[COMPUTE_LANES];
    for (int j = 0; j < COMPUTE_LANES; j++)
        acc[j] = 1.0 + 1e-3 * (double)(j + b % 7);
    const double m = 0.999999, c = 1e-6;
    for (int i = 0; i < COMPUTE_STEPS; i++) {
#pragma omp simd
        for (int j = 0; j < COMPUTE_LANES; j++)
            acc[j] = acc[j] * m + c;
    }
    double s = 0;
    for (int j = 0; j < COMPUTE_LANES; j++)
        s += acc[j];
    return s;
}

static double compute_sink;

static int compute_call(void *arg)
{
    const floor_desc *d = arg;
    const int64_t nblock = d->n / ((int64_t)COMPUTE_LANES * COMPUTE_STEPS);
    double s = 0;
#pragma omp parallel for schedule(static) reduction(+ : s)
    for (int64_t b = 0; b < nblock; b++)
        s += compute_block(b);
    compute_sink += s;
    return 0;
}

static void bm_compute_eff(gb_state *st, void *arg)
{
    const floor_desc *d = arg;
    char where[256], msg[400];
    ctb_eff_run(st, compute_call, (void *)d, (double)d->n, d->threads, cfg.bind, where,
                sizeof where);
    snprintf(msg, sizeof msg, "multiply-adds in registers, %d independent per step; ns_t1 "
             "and ns_tn per multiply-add; 1 against %d threads; %s[%s]", COMPUTE_LANES,
             d->threads, ctb_bind_name(cfg.bind), where);
    gb_set_label(st, msg);
}

/* ---- Registration -------------------------------------------------------- */

static int add(int kind, int triad_kind, int64_t n, int threads, int64_t iterations)
{
    floor_desc *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    d->kind = kind;
    d->triad = triad_kind;
    d->n = n;
    d->threads = threads;
    d->next = descs;
    descs = d;
    char name[128];
    if (kind == 3) {
        snprintf(name, sizeof name, "efficiency/compute/t%d", threads);
        return gb_register(name, bm_compute_eff, d, n, 1, 1, 0);
    }
    if (kind == 2) {
        snprintf(name, sizeof name, "efficiency/triad/%s/t%d", triad_kind_name[triad_kind],
                 threads);
        return gb_register(name, bm_triad_eff, d, n, 1, 1, 0);
    }
    if (kind == 0) {
        snprintf(name, sizeof name, "floor/triad/%s/t%d", triad_kind_name[triad_kind], threads);
        return gb_register(name, bm_triad, d, n, 1, iterations, 0);
    }
    snprintf(name, sizeof name, "floor/bucket/plates/t%d", threads);
    return gb_register(name, bm_bucket, d, n, 1, 0, 0);
}

int ctb_floor_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    memset(best_bw, 0, sizeof best_bw);
    int tlist[2] = {1, cfg.max_threads};
    int nt = cfg.max_threads > 1 ? 2 : 1;
    int count = 0;
    for (int t = 0; t < nt; t++) {
        /* The DRAM triad moves gigabytes per pass: 3 passes per repetition. */
        if (add(0, TRIAD_DRAM, triad_n(TRIAD_DRAM), tlist[t], 3) != 0 ||
            add(0, TRIAD_WS, triad_n(TRIAD_WS), tlist[t], 0) != 0)
            return -1;
        count += 2;
    }
    if (nt > 1) {
        /* 2^29 multiply-adds: about 35 ms on one core of this machine kind. */
        if (add(2, TRIAD_DRAM, triad_n(TRIAD_DRAM), cfg.max_threads, 0) != 0 ||
            add(3, 0, (int64_t)1 << 29, cfg.max_threads, 0) != 0)
            return -1;
        count += 2;
    }
    int ns = ctb_sync_register(cfg.bind, cfg.max_threads);
    if (ns < 0)
        return -1;
    count += ns;
    int64_t nmax = cfg.full ? 10000000 : 1000000;
    for (int64_t n = 1000000; n <= nmax; n *= 10)
        for (int t = 0; t < nt; t++) {
            if (add(1, 0, n, tlist[t], 0) != 0)
                return -1;
            count++;
        }
    return count;
}

void ctb_floor_cleanup(void)
{
    ctb_sync_cleanup();
    triad_free();
    plates_clear();
    while (descs) {
        floor_desc *n = descs->next;
        free(descs);
        descs = n;
    }
}
