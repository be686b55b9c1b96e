/*
 * bench_scene.c -- whole runs of the driver: what `contact run` costs per
 * node and cycle on scenes (data/scenes, bench/scenes), elements, interfaces and
 * solver together, no output written.
 *
 * Names (Google Benchmark appends "/<cycles>/real_time"):
 *   scene/showcase/t<T>            the scene `make run` runs (730 nodes:
 *                                  a small model, where the per-cycle
 *                                  overheads of each phase show)
 *   scene/folding-sheet-wide/t<T>  the folding sheet with ten times its
 *                                  cells along and across at the same cell
 *                                  size (bench/scenes/folding-sheet-wide.yaml:
 *                                  10086 nodes, TYPE7 + TYPE11 self contact;
 *                                  its 300 cycles end before the layers meet)
 *   scene/folding-sheet-contact/t<T>  the same sheet with its layers 1.5 mm
 *                                  apart (bench/scenes/folding-sheet-contact.yaml):
 *                                  9922 nodes, thousands of candidates from the
 *                                  start, of pairs in contact from about
 *                                  cycle 90
 * 1 thread and all threads. One iteration is a run of the scene from its
 * start for the fixed number of cycles (the solver's max_cycles); the
 * scene's load, the model, interfaces and solver set-up are outside the
 * timing. The scene files' paths are relative to the project's top (the
 * working directory of `make bench`).
 *
 * Counters: ns_per_node_cycle (run wall time / (cycles x nodes)),
 * us_per_cycle, nodes, cycles, and the run's own split (the solver's
 * timers, as a share of its wall time): elements_share, contact_share
 * (search, narrow phase, force, assembly), other_share; threads.
 */
#include "bench_scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "bench_topology.h"
#include "gbench.h"
#include "model.h"
#include "scene.h"
#include "solver.h"

static ctb_search_config cfg;

typedef struct sdesc {
    const char *file;
    int64_t refine, cycles;
    int threads;
    struct sdesc *next;
} sdesc;

static sdesc *descs;

/* One run's set-up, or its error in err. */
typedef struct srun {
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
    int have_model, have_solver;
} srun;

static void srun_free(srun *r)
{
    if (r->have_solver)
        ctd_solver_destroy(&r->s);
    if (r->have_model)
        ctd_model_destroy(&r->m);
    if (r->sc)
        ctd_scene_free(r->sc);
    memset(r, 0, sizeof *r);
}

static int srun_make(srun *r, const sdesc *d, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    const char *path = d->file;
    static ctd_scene_err se;
    if (ctd_scene_load_refined(path, d->refine, &r->sc, &se) != CT_OK) {
        snprintf(err, errlen, "%.400s", se.count ? se.msg[0].text : path);
        return -1;
    }
    if (ctd_model_build(&r->m, r->sc, err, errlen) != CT_OK)
        return -1;
    r->have_model = 1;
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    if (ctd_interfaces_build(&r->m, r->sc, &hooks, &nhook, err, errlen) != CT_OK)
        return -1;
    ctd_solver_opts o = ctd_solver_default_opts();
    o.no_output = 1;
    o.quiet = 1;
    o.threads = d->threads;
    o.max_cycles = d->cycles;
    if (ctd_solver_init(&r->s, &r->m, &o, hooks, nhook, err, errlen) != CT_OK)
        return -1;
    r->have_solver = 1;
    return 0;
}

static void bm_scene(gb_state *st, void *arg)
{
    const sdesc *d = arg;
    char where[256], msg[512];
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);
    double wall = 0, tel = 0, tct = 0, tall = 0;
    int64_t cycles = 0;
    ct_idx nodes = 0;
    while (gb_keep_running(st)) {
        srun r;
        if (srun_make(&r, d, msg, sizeof msg) != 0) {
            srun_free(&r);
            char e[600];
            snprintf(e, sizeof e, "setup of %s: %s", d->file, msg);
            gb_skip_with_error(st, e);
            return;
        }
        double t0 = ctb_now_s();
        int rc = ctd_solver_run(&r.s);
        wall += ctb_now_s() - t0;
        if (rc != CTD_EXIT_OK) {
            snprintf(msg, sizeof msg, "%s: %.400s", d->file, r.s.message);
            srun_free(&r);
            gb_skip_with_error(st, msg);
            return;
        }
        const ctd_timers *t = &r.s.timers;
        tel += t->elements;
        tct += t->search + t->narrow + t->force + t->assembly;
        tall += t->total;
        cycles += r.s.cycle;
        nodes = r.s.nnode;
        srun_free(&r);
    }
    double it = (double)gb_iterations(st);
    if (!(it > 0) || cycles <= 0 || nodes <= 0)
        return;
    gb_set_counter(st, "ns_per_node_cycle", wall * 1e9 / ((double)cycles * (double)nodes),
                   GB_PLAIN);
    gb_set_counter(st, "us_per_cycle", wall * 1e6 / (double)cycles, GB_PLAIN);
    gb_set_counter(st, "nodes", (double)nodes, GB_PLAIN);
    gb_set_counter(st, "cycles", (double)cycles / it, GB_PLAIN);
    if (tall > 0) {
        gb_set_counter(st, "elements_share", tel / tall, GB_PLAIN);
        gb_set_counter(st, "contact_share", tct / tall, GB_PLAIN);
        gb_set_counter(st, "other_share", (tall - tel - tct) / tall, GB_PLAIN);
    }
    gb_set_counter(st, "threads", d->threads, GB_PLAIN);
    snprintf(msg, sizeof msg, "prec=%s %s refine %lld, %lld cycles from the start; %s",
             sizeof(ct_real) == 4 ? "single" : "double", d->file, (long long)d->refine,
             (long long)d->cycles, where);
    gb_set_label(st, msg);
}

void ctb_scene_cleanup(void)
{
    while (descs) {
        sdesc *n = descs->next;
        free(descs);
        descs = n;
    }
}

int ctb_scene_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    static const struct {
        const char *name, *file;
        int64_t refine, cycles;
    } set[] = {{"showcase", "data/scenes/showcase.yaml", 1, 3000},
               {"folding-sheet-wide", "bench/scenes/folding-sheet-wide.yaml", 1, 300},
               {"folding-sheet-contact", "bench/scenes/folding-sheet-contact.yaml", 1, 300}};
    int tlist[2] = {1, cfg.max_threads};
    int nt = cfg.max_threads > 1 ? 2 : 1, count = 0;
    for (size_t i = 0; i < sizeof set / sizeof *set; i++)
        for (int t = 0; t < nt; t++) {
            sdesc *d = calloc(1, sizeof *d);
            if (!d)
                return -1;
            d->file = set[i].file;
            d->refine = set[i].refine;
            d->cycles = set[i].cycles;
            d->threads = tlist[t];
            d->next = descs;
            descs = d;
            char name[96];
            snprintf(name, sizeof name, "scene/%s/t%d", set[i].name, tlist[t]);
            if (gb_register(name, bm_scene, d, set[i].cycles, 1, 1, 0) != 0)
                return -1;
            count++;
        }
    return count;
}
