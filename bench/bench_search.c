/*
 * bench_search.c -- the search benchmarks: the four algorithms (direct,
 * topological, bucket, bsp) on every synthetic mesh family, sizes 10^3 to
 * 10^6 (10^7 with CT_BENCH_FULL), node numberings natural, shuffled and
 * space-filling curve, 1 thread and all threads.
 *
 * Names: search/<family>/<algo>/<numbering>/t<threads>/<target nodes>
 * (Google Benchmark appends "/real_time").
 * Each benchmark builds nothing inside the timed loop: the mesh is built
 * once per (family, size, numbering), copied into first-touched arrays and
 * kept while the benchmarks on it run (they are registered next to each
 * other); each run binds its threads, creates its workspace, runs one
 * untimed search (workspace growth; the topological search's full first
 * search), then times whole searches (binning + query + output).
 */
#include "bench_search.h"

#include "bench_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_topology.h"
#include "contact.h"
#include "gbench.h"
#include "meshgen.h"

/* ---- What a benchmark is ------------------------------------------------ */

typedef struct bench_desc {
    char family[32];
    int64_t target;
    int numbering;
    ct_search_algo algo;
    int threads;
    struct bench_desc *next; /* registration list, freed at the end */
} bench_desc;

static bench_desc *descs;
static ctb_search_config cfg;

/* ---- The mesh cache (one mesh at a time) --------------------------------- */

typedef struct bench_mesh {
    int valid; /* 1: built (or failed: rc != 0) for the key below */
    int rc;    /* CT_OK or the build error */
    char err[300];
    char family[32];
    int64_t target;
    int numbering;
    ctb_mesh m; /* first-touched copies of the search input, the reference */
    double h_mean;
} bench_mesh;

static bench_mesh cur;

static void mesh_clear(bench_mesh *m)
{
    ctb_mesh_clear(&m->m);
    memset(m, 0, sizeof *m);
}

/* Build the mesh for d (or keep it when it is the current one); the search
 * distance is gap = 0.3 h, margin = 0.2 h (ctb_mesh_case). */
static bench_mesh *mesh_get(const bench_desc *d)
{
    if (cur.valid && cur.target == d->target && cur.numbering == d->numbering &&
        strcmp(cur.family, d->family) == 0)
        return &cur;
    mesh_clear(&cur);
    cur.valid = 1;
    snprintf(cur.family, sizeof cur.family, "%s", d->family);
    cur.target = d->target;
    cur.numbering = d->numbering;
    cur.rc = ctb_mesh_case(&cur.m, d->family, d->target, d->numbering, &cfg, &cur.h_mean,
                           cur.err, sizeof cur.err);
    return &cur;
}

/* ---- The benchmark ------------------------------------------------------- */

static void bm_search(gb_state *st, void *arg)
{
    const bench_desc *d = arg;
    char msg[400];

    if ((double)d->target * cfg.bytes_per_node > cfg.mem_limit) {
        snprintf(msg, sizeof msg, "skipped: not enough memory (need about %.1f GB)",
                 (double)d->target * cfg.bytes_per_node / 1e9);
        gb_skip_with_error(st, msg);
        return;
    }
    bench_mesh *m = mesh_get(d);
    if (m->rc != CT_OK) {
        gb_skip_with_error(st, m->err);
        return;
    }
    if (m->m.in.nsec <= 0) {
        gb_skip_with_error(st, "mesh: no secondary nodes");
        return;
    }
    ctb_search_bench(st, &m->m, &cfg, d->algo, d->threads, m->h_mean, "");
}

/* ---- Registration -------------------------------------------------------- */

static int is_self_family(const char *f)
{
    return strstr(f, "fold") || strstr(f, "crump");
}

static int add(const char *family, int64_t n, int numbering, ct_search_algo algo, int threads)
{
    bench_desc *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    snprintf(d->family, sizeof d->family, "%s", family);
    d->target = n;
    d->numbering = numbering;
    d->algo = algo;
    d->threads = threads;
    d->next = descs;
    descs = d;
    char name[160];
    snprintf(name, sizeof name, "search/%s/%s/%s/t%d", family, ct_search_algo_name(algo),
             ctd_numbering_name((ctd_numbering)numbering), threads);
    return gb_register(name, bm_search, d, n, 1, 0, 0);
}

int ctb_search_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    int self_done = 0;
    int count = 0;
    int nfam = 0;
    const char *const *families = ctd_case_families(&nfam);
    for (int f = 0; f < nfam; f++) {
        const char *fam = families[f];
        int plates = strcmp(fam, "plates") == 0;
        /* The reduced set: plates and the first self-contact family go to
         * 10^6 nodes, the others to 10^5, all threads only except on
         * plates (1 and all); full: every family to 10^7, 1 and all
         * threads. */
        int big = plates || (is_self_family(fam) && !self_done);
        if (is_self_family(fam))
            self_done = 1;
        int64_t nmax = cfg.full ? 10000000 : big ? 1000000 : 100000;
        /* Numberings: all three on plates (and, in the full set, on the
         * self-contact family too), natural elsewhere. */
        int nnum = (plates || (cfg.full && big)) ? 3 : 1;
        int tlist[2] = {1, cfg.max_threads};
        int nt = cfg.max_threads > 1 ? 2 : 1;
        int tfirst = (plates || cfg.full) ? 0 : nt - 1;
        for (int64_t n = 1000; n <= nmax; n *= 10)
            for (int num = 0; num < nnum; num++)
                for (int a = 0; a < CT_SEARCH_NALGO; a++)
                    for (int t = tfirst; t < nt; t++) {
                        /* The direct search reads every pair whatever the
                         * numbering: in the reduced set its other
                         * numberings stop at 10^3 nodes (at 10^4 they
                         * took half a minute of `make bench`). */
                        if (!cfg.full && a == CT_SEARCH_DIRECT && num != CTD_NUM_NATURAL &&
                            n > 1000)
                            continue;
                        if (add(fam, n, num, (ct_search_algo)a, tlist[t]) != 0)
                            return -1;
                        count++;
                    }
    }
    return count;
}

void ctb_search_cleanup(void)
{
    mesh_clear(&cur);
    while (descs) {
        bench_desc *n = descs->next;
        free(descs);
        descs = n;
    }
}
