/*
 * bench_cycle.c -- the full contact cycle of a self-contact sheet, in ns per
 * node per cycle for each phase (issue 5 item 6; DESIGN.md section 4). The
 * cycle itself is driver/contact_cycle.c; this file is the scene, the
 * motion and the Google Benchmark glue.
 *
 * Names (Google Benchmark appends "/<nodes>/real_time"):
 *   cycle/<folded|crumpled>/t<T>
 * at 10^5 and 10^6 nodes for folded and 10^5 for crumpled (CT_BENCH_FULL
 * adds crumpled at 10^6), 1 thread and all threads.
 *
 * The scene: the meshgen case (self contact, natural numbering, unit mass
 * per node), gap 0.3 h (two-sided shells: 0.15 h of sheet thickness per
 * side), margin 0.2 h, TYPE7 law with K0 = 1, damping 0.05, Coulomb 0.2,
 * bucket search with the hull filter, 4-triangle quads, colouring assembly,
 * the narrow phase's skip of the pairs proved out of contact
 * (ctd_cycle_default_params). It moves under the prescribed motion of
 * ctd_motion: the stacking axis (y for folded, z for crumpled) is scaled
 * about the middle by s0 - s1 (1 - cos phi)/2 (folded: s0 = 0.72, so the
 * layers 0.4 h apart start 0.288 h apart, already in contact, and close to
 * 0.248 h; crumpled: s0 = 0.9), neighbouring layers slide against each
 * other by 0.5 h sin phi along z (folded) or x (crumpled), and the period
 * is chosen so that no node moves more than 0.008 h in a cycle.
 *
 * What one Google Benchmark iteration is: a block of C = 8 cycles
 * preceded by one forced search, with the scene
 * (its mesh, candidates and friction history) kept from one iteration
 * and one benchmark to the next; the iteration count is fixed at 1, so every repetition is one
 * block. Each benchmark restarts the motion at the same cycle (its r-th
 * repetition runs cycles 1 + r C .. (r + 1) C), so the 1-thread and the
 * all-threads rows time the same states of the motion and their ratio is
 * the speed-up. The positions and velocities of each cycle are computed with the
 * timer paused. The phases are timed inside the cycle (omp_get_wtime).
 * Re-sorts are rare (every ~10-25 cycles), so a short block cannot
 * amortise them by itself: the search figure is
 *     ns_search = check per cycle + (cost of one search) / interval,
 * the cost of one search being the mean over the block's searches (the
 * forced one included: there is always at least one), and the interval the
 * mean number of cycles between re-sorts of the criterion over a whole
 * period of the motion, computed exactly from the motion's displacement
 * field (the bound ct_resort_needed evaluates: the smaller of twice the
 * largest node displacement since the last sort and the relative bound per
 * axis, against the margin). The interval the
 * interface itself saw (re-sorts fired by the criterion, over its life) is
 * reported too when there was one (resort_interval_seen; blocks are
 * usually shorter than an interval, so it rarely is).
 *
 * Counters (per node and cycle): ns_search, ns_narrow, ns_force (relative
 * velocity, TYPE7 law, damping, friction, pair force), ns_assemble (zeroing
 * the nodal forces and ct_assemble), ns_timestep, ns_total, and
 * ns_total_x_threads (ns_total times the threads: the "per thread" figure
 * the target of 15 ns is stated in); ns_per_sort (one search, per node),
 * resort_interval, ns_check, cand_per_node, eval_per_node (candidates
 * through the narrow phase: the others the skip proved out of contact),
 * active_per_node,
 * threads, nodes.
 */
#include "bench_cycle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "bench_topology.h"
#include "contact.h"
#include "contact_cycle.h"
#include "gbench.h"
#include "meshgen.h"

/* Largest node displacement per cycle, in mesh sizes h. */
#define CB_STEP 0.008
/* Memory per node at the peak, for the skip test (measured: about 2.7 kB
 * per node for the folded sheet in double, with the mesh and the arrays). */
#define CB_BYTES_PER_NODE 4000.0
#define CB_DT 1e-3

typedef struct cdesc {
    const char *family;
    int64_t nodes;
    int threads;
    int cycles; /* per iteration */
    int64_t calls; /* repetitions run so far (each is one block) */
    struct cdesc *next;
} cdesc;

static cdesc *descs;
static ctb_search_config cfg;

/* The cached scene. */
static struct {
    int valid, rc;
    char err[300];
    const char *family;
    int64_t target;
    ctd_case c;
    int have_case;
    ct_idx nnode;
    double h;
    ct_real *ref[3], *pos[3], *vel[3], *f[3], *m;
    ctd_motion mo;
    double interval; /* predicted mean re-sort interval */
    int64_t cycle;   /* cycles run on the scene (the motion's clock) */
    ctd_cycle *cy;
} sc;

static void scene_free(void)
{
    ctd_cycle_destroy(sc.cy);
    for (int a = 0; a < 3; a++) {
        ctb_free(sc.ref[a]);
        ctb_free(sc.pos[a]);
        ctb_free(sc.vel[a]);
        ctb_free(sc.f[a]);
    }
    ctb_free(sc.m);
    if (sc.have_case)
        ctd_case_destroy(&sc.c);
    memset(&sc, 0, sizeof sc);
}

static int scene_fail(int rc, const char *what)
{
    sc.rc = rc;
    snprintf(sc.err, sizeof sc.err, "%s: %s", what, ct_strerror(rc));
    return rc;
}

/* One node of the motion's displacement field, (d^2, cos^2). */
typedef struct { double a, b; } cpoint;

static int cmp_a_desc(const void *p, const void *q)
{
    double x = ((const cpoint *)p)->a, y = ((const cpoint *)q)->a;
    return x < y ? 1 : x > y ? -1 : 0;
}

/*
 * The mean re-sort interval of the criterion under the motion, over one
 * period. Between cycles i and j a node moves by sqrt(a df^2 + b dsl^2)
 * (a = d^2 its squared distance to the centre along the compression axis,
 * b = cos^2 of its slide wave, df and dsl the changes of the scale and of
 * the slide amplitude), so the largest displacement is a maximum over the
 * Pareto front of the points (a, b): a few nodes. The criterion's bound is
 * the smaller of twice it (secondary and main are the same nodes) and the
 * relative bound per axis, the length of the vector of the displacements'
 * ranges along the axes ((max d - min d) df and (max cos - min cos) dsl).
 */
static double predict_interval(const ctd_motion *mo, ct_idx n, const ct_real *rc,
                               double margin)
{
    cpoint *pt = malloc(sizeof *pt * (size_t)(n > 0 ? n : 1));
    if (!pt || n <= 0) {
        free(pt);
        return 0;
    }
    double kw = 2 * 3.141592653589793 / mo->wavelength;
    double dlo = 1e300, dhi = -1e300, clo = 1e300, chi = -1e300;
    for (ct_idx i = 0; i < n; i++) {
        double d = (double)rc[i] - mo->centre, cw = cos(kw * (double)rc[i]);
        pt[i].a = d * d;
        pt[i].b = cw * cw;
        dlo = d < dlo ? d : dlo;
        dhi = d > dhi ? d : dhi;
        clo = cw < clo ? cw : clo;
        chi = cw > chi ? cw : chi;
    }
    qsort(pt, (size_t)n, sizeof *pt, cmp_a_desc);
    int nf = 0;
    double bmax = -1;
    for (ct_idx i = 0; i < n; i++) /* a descending: keep b records */
        if (pt[i].b > bmax) {
            bmax = pt[i].b;
            pt[nf++] = pt[i];
        }
    const double pi2 = 2 * 3.141592653589793;
    int64_t ncyc = (int64_t)ceil(mo->period) + 1, last = 0, sorts = 0, sum = 0;
    double f0 = mo->s0, s0 = 0;
    for (int64_t c = 1; c <= 4 * ncyc && (c <= ncyc || sorts < 2); c++) {
        double phi = pi2 * (double)c / mo->period;
        double f = mo->s0 - mo->s1 * (1 - cos(phi)) / 2, s = mo->slide * sin(phi);
        double df2 = (f - f0) * (f - f0), ds2 = (s - s0) * (s - s0), m2 = 0;
        for (int k = 0; k < nf; k++) {
            double v = pt[k].a * df2 + pt[k].b * ds2;
            m2 = v > m2 ? v : m2;
        }
        /* The relative bound per axis: the ranges of the displacements
         * along the compression and the slide axes (the third is 0). */
        double rcx = (dhi - dlo) * fabs(f - f0), rsl = (chi - clo) * fabs(s - s0);
        double rel = sqrt(rcx * rcx + rsl * rsl), abs2 = 2 * sqrt(m2);
        if ((rel < abs2 ? rel : abs2) > margin) {
            sorts++;
            sum += c - last;
            last = c;
            f0 = f;
            s0 = s;
        }
    }
    free(pt);
    return sorts > 0 ? (double)sum / (double)sorts : (double)ncyc;
}

static int scene_get(const char *family, int64_t target)
{
    if (sc.valid && sc.family == family && sc.target == target)
        return sc.rc;
    scene_free();
    sc.valid = 1;
    sc.family = family;
    sc.target = target;
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    ct_diag diag;
    int rc = ctd_case_make(&sc.c, family, target, CTD_NUM_NATURAL, cfg.seed, &diag);
    if (rc != CT_OK) {
        sc.rc = rc;
        snprintf(sc.err, sizeof sc.err, "%.250s", diag.msg);
        return rc;
    }
    sc.have_case = 1;
    ct_idx n = sc.nnode = sc.c.mesh.nodes.n;
    sc.h = sc.c.h_mean > 0 ? sc.c.h_mean : 1;
    const ct_real *src[3] = {sc.c.mesh.nodes.x, sc.c.mesh.nodes.y, sc.c.mesh.nodes.z};
    int ok = 1;
    for (int a = 0; a < 3; a++) {
        ok &= (sc.ref[a] = ctb_first_touch_copy_real(src[a], (size_t)n)) != NULL;
        ok &= (sc.pos[a] = ctb_first_touch_alloc((size_t)n, sizeof(ct_real))) != NULL;
        ok &= (sc.vel[a] = ctb_first_touch_alloc((size_t)n, sizeof(ct_real))) != NULL;
        ok &= (sc.f[a] = ctb_first_touch_alloc((size_t)n, sizeof(ct_real))) != NULL;
    }
    ok &= (sc.m = ctb_first_touch_alloc((size_t)n, sizeof(ct_real))) != NULL;
    if (!ok)
        return scene_fail(CT_ERR_NOMEM, "scene arrays");
    for (ct_idx i = 0; i < n; i++)
        sc.m[i] = 1;
    /* The motion (see the top of the file). */
    int folded = strcmp(family, "folded") == 0;
    ctd_motion *mo = &sc.mo;
    mo->axis_c = folded ? 1 : 2;
    mo->axis_s = folded ? 2 : 0;
    double lo = 1e300, hi = -1e300;
    for (ct_idx i = 0; i < n; i++) {
        double v = (double)sc.ref[mo->axis_c][i];
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    mo->centre = 0.5 * (lo + hi);
    mo->s0 = folded ? 0.72 : 0.9;
    mo->s1 = 0.1;
    mo->slide = 0.5 * sc.h;
    mo->wavelength = folded ? 0.8 * sc.h : 4 * sc.h; /* folded: layers 0.4 h apart */
    mo->period = 1;
    mo->period = ctd_motion_max_step(mo, 0.5 * (hi - lo)) / (CB_STEP * sc.h);
    ctd_cycle_params p = ctd_cycle_default_params(sc.h);
    sc.interval = predict_interval(mo, n, sc.ref[mo->axis_c], (double)p.margin);
    rc = ctd_cycle_init(&sc.cy, &p, n, sc.m, sc.c.sec.n, sc.c.sec.node, sc.c.sec.n,
                        sc.c.sec.node, sc.c.main.n, sc.c.mn1, sc.c.mn2, sc.c.mn3, sc.c.mn4,
                        sc.c.self);
    if (rc != CT_OK)
        return scene_fail(rc, "cycle init");
    /* The first cycle (the initial search, the arrays' first touch), then
     * room for 1.5 times its pairs (the motion's most compressed state has
     * up to ~1.35 times the first one's), so the timed cycles do not
     * allocate. */
    ctd_motion_eval(mo, n, (const ct_real *const *)sc.ref, 0, CB_DT, sc.pos, sc.vel);
    rc = ctd_cycle_step(sc.cy, sc.pos[0], sc.pos[1], sc.pos[2], sc.vel[0], sc.vel[1],
                        sc.vel[2], (ct_real)CB_DT, sc.f[0], sc.f[1], sc.f[2]);
    if (rc != CT_OK)
        return scene_fail(rc, "first cycle");
    sc.cycle = 1;
    int64_t want = 3 * (int64_t)ctd_cycle_pairs(sc.cy)->n / 2;
    rc = ctd_cycle_reserve(sc.cy, (ct_idx)(want < INT32_MAX / 2 ? want : INT32_MAX / 2));
    if (rc != CT_OK)
        return scene_fail(rc, "reserve");
    return CT_OK;
}

static void bm_cycle(gb_state *st, void *arg)
{
    cdesc *d = arg;
    char where[256], msg[700];
    if ((double)d->nodes * CB_BYTES_PER_NODE > cfg.mem_limit) {
        gb_skip_with_error(st, "skipped: not enough memory");
        return;
    }
    if (scene_get(d->family, d->nodes) != CT_OK) {
        snprintf(msg, sizeof msg, "setup: %.300s", sc.err);
        gb_skip_with_error(st, msg);
        return;
    }
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);
    ctd_cycle_stats_reset(sc.cy);
    /* Every benchmark (1 thread, all threads) runs the same stretch of the
     * motion: repetition r is the block of cycles starting at cycle
     * 1 + r * C, whichever benchmark ran on the scene before, so their
     * rows time the same states and the speed-up between them is a real
     * one. The forced search at the block's start makes the jump back in
     * the motion harmless to the candidates. */
    sc.cycle = 1 + d->calls * (int64_t)d->cycles;
    d->calls++;
    int rc = CT_OK;
    while (rc == CT_OK && gb_keep_running(st)) {
        ctd_cycle_force_resort(sc.cy); /* one search per block, timed */
        for (int k = 0; k < d->cycles && rc == CT_OK; k++) {
            gb_pause_timing(st);
            ctd_motion_eval(&sc.mo, sc.nnode, (const ct_real *const *)sc.ref,
                            (double)sc.cycle, CB_DT, sc.pos, sc.vel);
            sc.cycle++;
            gb_resume_timing(st);
            rc = ctd_cycle_step(sc.cy, sc.pos[0], sc.pos[1], sc.pos[2], sc.vel[0], sc.vel[1],
                                sc.vel[2], (ct_real)CB_DT, sc.f[0], sc.f[1], sc.f[2]);
        }
    }
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "cycle: %s", ct_strerror(rc));
        sc.rc = rc; /* the interface is unusable now */
        snprintf(sc.err, sizeof sc.err, "cycle: %s", ct_strerror(rc));
        gb_skip_with_error(st, msg);
        return;
    }
    const ctd_cycle_stats *s = ctd_cycle_get_stats(sc.cy);
    if (s->cycles <= 0 || s->resorts <= 0)
        return;
    double per = 1e9 / ((double)s->cycles * (double)sc.nnode);
    double sort_ns = 1e9 * s->t_sort / (double)s->resorts / (double)sc.nnode;
    double check_ns = (s->t[CTD_PH_SEARCH] - s->t_sort) * per;
    double search_ns = check_ns + (sc.interval > 0 ? sort_ns / sc.interval : sort_ns);
    double ph[CTD_PH_N] = {search_ns, s->t[CTD_PH_NARROW] * per, s->t[CTD_PH_FORCE] * per,
                           s->t[CTD_PH_ASSEMBLE] * per, s->t[CTD_PH_TIMESTEP] * per};
    static const char *const ph_name[CTD_PH_N] = {"ns_search", "ns_narrow", "ns_force",
                                                  "ns_assemble", "ns_timestep"};
    double total = 0;
    for (int i = 0; i < CTD_PH_N; i++) {
        gb_set_counter(st, ph_name[i], ph[i], GB_PLAIN);
        total += ph[i];
    }
    gb_set_counter(st, "ns_total", total, GB_PLAIN);
    gb_set_counter(st, "ns_total_x_threads", total * d->threads, GB_PLAIN);
    gb_set_counter(st, "ns_per_sort", sort_ns, GB_PLAIN);
    gb_set_counter(st, "ns_check", check_ns, GB_PLAIN);
    gb_set_counter(st, "resort_interval", sc.interval, GB_PLAIN);
    if (s->natural_sorts > 0)
        gb_set_counter(st, "resort_interval_seen",
                       (double)s->interval_sum / (double)s->natural_sorts, GB_PLAIN);
    gb_set_counter(st, "cand_per_node", (double)s->cand_sum / (double)s->cycles / sc.nnode,
                   GB_PLAIN);
    gb_set_counter(st, "eval_per_node", (double)s->eval_sum / (double)s->cycles / sc.nnode,
                   GB_PLAIN);
    gb_set_counter(st, "active_per_node",
                   (double)s->active_sum / (double)s->cycles / sc.nnode, GB_PLAIN);
    gb_set_counter(st, "threads", (double)d->threads, GB_PLAIN);
    gb_set_counter(st, "nodes", (double)sc.nnode, GB_PLAIN);
    snprintf(msg, sizeof msg,
             "prec=%s %s self contact, bucket+hull, 4tri, skip, TYPE7, Coulomb 0.2, colour; "
             "%d cycles + 1 forced search per iteration; %.1f ns/node/cycle x %d thr = %.1f "
             "(target <= 15); %s[%s]",
             sizeof(ct_real) == 4 ? "single" : "double", d->family, d->cycles, total,
             d->threads, total * d->threads, ctb_bind_name(cfg.bind), where);
    gb_set_label(st, msg);
}

/* ---- The skip as a trade-table knob -----------------------------------
 *
 * trade/skip/<off|on>@folded: the folded sheet of 10^5 nodes, a fresh
 * interface (skip off or on) run for TS_CYCLES cycles of the motion from
 * cycle 1 (its first search and the natural re-sorts included), with all
 * threads: cost ns per node per cycle; accuracy the largest difference of
 * a nodal force from the run without the skip, relative to the largest
 * nodal force, over those cycles (must be 0: the skip is exact).
 * x_eval_per_node the candidates through the narrow phase. */
#define TS_NODES 100000
#define TS_CYCLES 24

/* Run the stretch with skip setting `skip` into a fresh interface; when
 * cmp is given (the other run's forces, TS_CYCLES x 3 x nnode), fold the
 * largest difference into *diff and the largest |f| into *fmax; when keep
 * is given, store the forces there. Timed by the caller's state unless st
 * is NULL. */
static int skip_stretch(gb_state *st, int skip, const ct_real *cmp, ct_real *keep,
                        double *diff, double *fmax, int64_t *eval_sum, int64_t *cycles,
                        double *tstep)
{
    ctd_cycle_params p = ctd_cycle_default_params(sc.h);
    p.skip = skip;
    ctd_cycle *cy = NULL;
    int rc = ctd_cycle_init(&cy, &p, sc.nnode, sc.m, sc.c.sec.n, sc.c.sec.node, sc.c.sec.n,
                            sc.c.sec.node, sc.c.main.n, sc.c.mn1, sc.c.mn2, sc.c.mn3, sc.c.mn4,
                            sc.c.self);
    if (rc == CT_OK)
        rc = ctd_cycle_reserve(cy, (ct_idx)(ctd_cycle_pairs(sc.cy)->n * 3 / 2));
    const size_t nn = (size_t)sc.nnode;
    for (int k = 0; k < TS_CYCLES && rc == CT_OK; k++) {
        if (st)
            gb_pause_timing(st);
        ctd_motion_eval(&sc.mo, sc.nnode, (const ct_real *const *)sc.ref, (double)(1 + k),
                        CB_DT, sc.pos, sc.vel);
        if (st)
            gb_resume_timing(st);
        double t0 = omp_get_wtime();
        rc = ctd_cycle_step(cy, sc.pos[0], sc.pos[1], sc.pos[2], sc.vel[0], sc.vel[1],
                            sc.vel[2], (ct_real)CB_DT, sc.f[0], sc.f[1], sc.f[2]);
        *tstep += omp_get_wtime() - t0;
        if (rc != CT_OK || st)
            continue;
        for (int a = 0; a < 3; a++) {
            const ct_real *f = sc.f[a];
            size_t off = ((size_t)k * 3 + (size_t)a) * nn;
            if (keep)
                memcpy(keep + off, f, sizeof(ct_real) * nn);
            for (size_t i = 0; cmp && i < nn; i++) {
                double v = fabs((double)f[i] - (double)cmp[off + i]);
                *diff = v > *diff ? v : *diff;
                double m = fabs((double)cmp[off + i]);
                *fmax = m > *fmax ? m : *fmax;
            }
        }
    }
    if (rc == CT_OK) {
        *eval_sum += ctd_cycle_get_stats(cy)->eval_sum;
        *cycles += ctd_cycle_get_stats(cy)->cycles;
    }
    if (st)
        gb_pause_timing(st);
    ctd_cycle_destroy(cy);
    if (st)
        gb_resume_timing(st);
    return rc;
}

static void bm_trade_skip(gb_state *st, void *arg)
{
    const int skip = *(const int *)arg;
    char msg[700];
    static int acc_done;
    static double acc;
    if ((double)TS_NODES * CB_BYTES_PER_NODE > cfg.mem_limit) {
        gb_skip_with_error(st, "skipped: not enough memory");
        return;
    }
    if (scene_get("folded", TS_NODES) != CT_OK) {
        snprintf(msg, sizeof msg, "setup: %.300s", sc.err);
        gb_skip_with_error(st, msg);
        return;
    }
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    int rc = CT_OK;
    int64_t es = 0, nc = 0;
    double ts = 0;
    if (!acc_done) { /* both runs once, untimed: the accuracy */
        size_t len = (size_t)TS_CYCLES * 3 * (size_t)sc.nnode;
        ct_real *ref = malloc(sizeof(ct_real) * len);
        double diff = 0, fmax = 0;
        rc = ref ? CT_OK : CT_ERR_NOMEM;
        if (rc == CT_OK)
            rc = skip_stretch(NULL, 0, NULL, ref, &diff, &fmax, &es, &nc, &ts);
        if (rc == CT_OK)
            rc = skip_stretch(NULL, 1, ref, NULL, &diff, &fmax, &es, &nc, &ts);
        free(ref);
        if (rc == CT_OK && !(fmax > 0)) {
            gb_skip_with_error(st, "setup: no contact force in the stretch");
            return;
        }
        acc = diff / fmax;
        acc_done = rc == CT_OK;
    }
    es = nc = 0;
    ts = 0;
    while (rc == CT_OK && gb_keep_running(st))
        rc = skip_stretch(st, skip, NULL, NULL, NULL, NULL, &es, &nc, &ts);
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "skip stretch: %s", ct_strerror(rc));
        gb_skip_with_error(st, msg);
        return;
    }
    gb_set_counter(st, "cost", nc ? ts * 1e9 / (double)nc / sc.nnode : 0, GB_PLAIN);
    gb_set_counter(st, "accuracy", acc, GB_PLAIN);
    gb_set_counter(st, "x_eval_per_node", nc ? (double)es / (double)nc / sc.nnode : 0,
                   GB_PLAIN);
    snprintf(msg, sizeof msg,
             "knob=skip setting=%s@folded; cost: ns/node per cycle; accuracy: largest nodal "
             "force difference from the run without the skip / largest nodal force; prec=%s "
             "folded sheet %d nodes, %d cycles of the motion from a fresh interface, %d threads",
             skip ? "on" : "off", sizeof(ct_real) == 4 ? "single" : "double", (int)sc.nnode,
             TS_CYCLES, cfg.max_threads);
    gb_set_label(st, msg);
}

static int add(const char *family, int64_t nodes, int threads)
{
    cdesc *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    d->family = family;
    d->nodes = nodes;
    d->threads = threads;
    /* Every size the same 8 cycles a repetition, so that every row times
     * the same stretch of the motion (cycles 1 to 24 with make bench's 3
     * repetitions): the skip evaluates more pairs in the motion's first
     * cycles (folded 10^6, 2 threads: 4.97 pairs per node over cycles 1-9,
     * 4.17 over 1-24, 2.98 over 1-48), and the 10^6 rows, with 3 cycles a
     * repetition, timed cycles 1-9 alone and read about 15 % above the
     * 10^5 rows for that. */
    d->cycles = 8;
    d->next = descs;
    descs = d;
    char name[128];
    snprintf(name, sizeof name, "cycle/%s/t%d", family, threads);
    return gb_register(name, bm_cycle, d, nodes, 1, 1, 0);
}

int ctb_cycle_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    gb_add_context("ct_cycle",
                   "self-contact sheet under a prescribed fold-and-slide motion; gap 0.3 h, "
                   "margin 0.2 h; search amortised over the predicted re-sort interval");
    static const struct {
        const char *family;
        int64_t nodes;
        int full_only;
    } set[] = {{"folded", 100000, 0},
               {"crumpled", 100000, 0},
               {"folded", 1000000, 0},
               {"crumpled", 1000000, 1}};
    static int skip_set[2] = {0, 1};
    for (int k = 0; k < 2; k++) {
        char name[64];
        snprintf(name, sizeof name, "trade/skip/%s@folded", skip_set[k] ? "on" : "off");
        if (gb_register(name, bm_trade_skip, &skip_set[k], -1, 1, 1, 0) != 0)
            return -1;
    }
    int tlist[2] = {1, cfg.max_threads};
    int nt = cfg.max_threads > 1 ? 2 : 1, count = 0;
    for (size_t i = 0; i < sizeof set / sizeof *set; i++) {
        if (set[i].full_only && !cfg.full)
            continue;
        for (int t = 0; t < nt; t++) {
            if (add(set[i].family, set[i].nodes, tlist[t]) != 0)
                return -1;
            count++;
        }
    }
    return count + 2;
}

void ctb_cycle_cleanup(void)
{
    scene_free();
    while (descs) {
        cdesc *n = descs->next;
        free(descs);
        descs = n;
    }
}
