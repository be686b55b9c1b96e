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

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

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
    int valid;   /* 1: built (or failed: rc != 0) for the key below */
    int rc;      /* CT_OK or the build error */
    char err[300];
    char family[32];
    int64_t target;
    int numbering;
    /* First-touched copies of the search input arrays. */
    ct_real *x, *y, *z;
    ct_idx *sec, *n1, *n2, *n3, *n4;
    ct_search_input in;
    double h_mean;
    double build_s;
    /* Reference pairs for the topological search's misses (computed once,
     * by direct when affordable, else by bucket, else bsp). */
    int ref_state; /* 0: not yet, 1: done, -1: failed */
    ct_search_algo ref_algo;
    ct_pairs ref;
    ct_idx *pos; /* node -> position in sec, for comparing pair lists */
} bench_mesh;

static bench_mesh cur;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void mesh_clear(bench_mesh *m)
{
    ctb_free(m->x);
    ctb_free(m->y);
    ctb_free(m->z);
    ctb_free(m->sec);
    ctb_free(m->n1);
    ctb_free(m->n2);
    ctb_free(m->n3);
    ctb_free(m->n4);
    if (m->ref_state == 1)
        ct_pairs_destroy(&m->ref);
    free(m->pos);
    memset(m, 0, sizeof *m);
}

/*
 * The search distance of each family, relative to the mean main edge
 * length h (DESIGN.md section 5: margin = 0.2 h, search distance =
 * gap + margin). gap = 0.3 h everywhere, so gap + margin = 0.5 h; on the
 * plates family (unit spacing, plates 0.3 apart) that is the issue's
 * "0.3 apart, gap + margin 0.5". Every family of meshgen.h puts its
 * facing surfaces 0.3 h apart (folded: 0.4 h), inside that distance.
 */
static void family_gap(const char *family, double h, double *gap, double *margin)
{
    (void)family;
    *gap = 0.3 * h;
    *margin = 0.2 * h;
}

/* Build the mesh for d (or keep it when it is the current one). */
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

    double t0 = now_s();
    ctd_case c;
    ct_diag diag;
    memset(&c, 0, sizeof c);
    memset(&diag, 0, sizeof diag);
    int rc = ctd_case_make(&c, d->family, d->target, (ctd_numbering)d->numbering, cfg.seed, &diag);
    if (rc != CT_OK) {
        cur.rc = rc;
        snprintf(cur.err, sizeof cur.err, "mesh: %s: %s", ct_strerror(rc), diag.msg);
        return &cur;
    }
    ct_search_input in;
    memset(&in, 0, sizeof in);
    /* The gap does not change the arrays; it is set below from h. */
    ctd_case_input(&c, 0, 0, &in);
    /* First-touch copies made by the largest team the run uses; the case
     * itself is released once copied. */
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    cur.x = ctb_first_touch_copy_real(in.x, (size_t)in.nnode);
    cur.y = ctb_first_touch_copy_real(in.y, (size_t)in.nnode);
    cur.z = ctb_first_touch_copy_real(in.z, (size_t)in.nnode);
    cur.sec = ctb_first_touch_copy_idx(in.sec, (size_t)in.nsec);
    cur.n1 = ctb_first_touch_copy_idx(in.n1, (size_t)in.nseg);
    cur.n2 = ctb_first_touch_copy_idx(in.n2, (size_t)in.nseg);
    cur.n3 = ctb_first_touch_copy_idx(in.n3, (size_t)in.nseg);
    cur.n4 = ctb_first_touch_copy_idx(in.n4, (size_t)in.nseg);
    if (!cur.x || !cur.y || !cur.z || !cur.sec || !cur.n1 || !cur.n2 || !cur.n3 || !cur.n4) {
        ctd_case_destroy(&c);
        cur.rc = CT_ERR_NOMEM;
        snprintf(cur.err, sizeof cur.err, "mesh input: %s", ct_strerror(cur.rc));
        return &cur;
    }
    cur.in = in;
    cur.in.x = cur.x;
    cur.in.y = cur.y;
    cur.in.z = cur.z;
    cur.in.sec = cur.sec;
    cur.in.n1 = cur.n1;
    cur.in.n2 = cur.n2;
    cur.in.n3 = cur.n3;
    cur.in.n4 = cur.n4;
    cur.h_mean = c.h_mean;
    ctd_case_destroy(&c);
    double gap, margin;
    family_gap(d->family, cur.h_mean, &gap, &margin);
    cur.in.gap = (ct_real)gap;
    cur.in.margin = (ct_real)margin;
    cur.build_s = now_s() - t0;
    return &cur;
}

static double pair_tests(const ct_search_input *in) { return (double)in->nsec * (double)in->nseg; }

/* The reference pair list of the current mesh, computed once. */
static const ct_pairs *mesh_reference(bench_mesh *m)
{
    if (m->ref_state)
        return m->ref_state == 1 ? &m->ref : NULL;
    m->ref_state = -1;
    const ct_search_algo order[] = {CT_SEARCH_DIRECT, CT_SEARCH_BUCKET, CT_SEARCH_BSP};
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    for (int k = 0; k < 3; k++) {
        if (order[k] == CT_SEARCH_DIRECT && pair_tests(&m->in) > cfg.direct_budget)
            continue;
        ct_search_params p = ct_search_default_params(order[k]);
        ct_search *s = NULL;
        if (ct_search_init(&s, &p) != CT_OK)
            continue;
        ct_pairs out;
        int rc = ct_pairs_init(&out, 0);
        if (rc == CT_OK)
            rc = ct_search_run(s, &m->in, &out);
        ct_search_destroy(s);
        if (rc != CT_OK) {
            ct_pairs_destroy(&out);
            continue;
        }
        m->pos = malloc(((size_t)m->in.nnode + 1) * sizeof *m->pos);
        if (!m->pos) {
            ct_pairs_destroy(&out);
            return NULL;
        }
        for (ct_idx i = 0; i < m->in.nsec; i++)
            m->pos[m->in.sec[i]] = i;
        m->ref = out;
        m->ref_algo = order[k];
        m->ref_state = 1;
        return &m->ref;
    }
    return NULL;
}

/* Pairs of ref missing from got, and pairs of got absent from ref; both
 * lists are in canonical order (secondary position, then segment). */
static void compare_pairs(const ct_idx *pos, const ct_pairs *ref, const ct_pairs *got,
                          int64_t *missing, int64_t *extra)
{
    int64_t a = 0, b = 0, miss = 0, more = 0;
    while (a < ref->n || b < got->n) {
        if (b >= got->n) {
            miss += ref->n - a;
            break;
        }
        if (a >= ref->n) {
            more += got->n - b;
            break;
        }
        ct_idx pa = pos[ref->node[a]], pb = pos[got->node[b]];
        if (pa == pb && ref->seg[a] == got->seg[b]) {
            a++;
            b++;
        } else if (pa < pb || (pa == pb && ref->seg[a] < got->seg[b])) {
            miss++;
            a++;
        } else {
            more++;
            b++;
        }
    }
    *missing = miss;
    *extra = more;
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
    const ct_search_input *in = &m->in;
    if (in->nsec <= 0) {
        gb_skip_with_error(st, "mesh: no secondary nodes");
        return;
    }
    if (d->algo == CT_SEARCH_DIRECT && pair_tests(in) > cfg.direct_budget) {
        snprintf(msg, sizeof msg,
                 "skipped: over budget (nsec=%ld nseg=%ld, nsec*nseg=%.3g > %.3g)",
                 (long)in->nsec, (long)in->nseg, pair_tests(in), cfg.direct_budget);
        gb_skip_with_error(st, msg);
        return;
    }

    /* The topological search's reference is computed before binding this
     * run's threads (it binds the largest team itself). */
    const ct_pairs *ref = d->algo == CT_SEARCH_TOPO ? mesh_reference(m) : NULL;

    char where[256];
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);

    ct_search_params p = ct_search_default_params(d->algo);
    ct_search *s = NULL;
    ct_pairs out;
    memset(&out, 0, sizeof out);
    int rc = ct_search_init(&s, &p);
    if (rc == CT_OK)
        rc = ct_pairs_init(&out, 0);
    /* Untimed: grows the workspace and the output; for the topological
     * search this is the full first search, the timed ones use history. */
    if (rc == CT_OK)
        rc = ct_search_run(s, in, &out);
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "search %s: %s", ct_search_algo_name(d->algo), ct_strerror(rc));
        gb_skip_with_error(st, msg);
        ct_search_destroy(s);
        ct_pairs_destroy(&out);
        return;
    }

    double t0 = now_s();
    while (gb_keep_running(st)) {
        rc = ct_search_run(s, in, &out);
        if (rc != CT_OK) {
            snprintf(msg, sizeof msg, "search %s: %s", ct_search_algo_name(d->algo),
                     ct_strerror(rc));
            gb_skip_with_error(st, msg);
            break;
        }
    }
    double t1 = now_s();
    int64_t iters = gb_iterations(st);

    if (rc == CT_OK && iters > 0) {
        gb_set_counter(st, "ns_per_node", (t1 - t0) * 1e9 / ((double)iters * (double)in->nsec),
                       GB_PLAIN);
        gb_set_counter(st, "nsec", (double)in->nsec, GB_PLAIN);
        gb_set_counter(st, "nseg", (double)in->nseg, GB_PLAIN);
        gb_set_counter(st, "pairs", (double)out.n, GB_PLAIN);
        gb_set_counter(st, "bytes_per_node", (double)ct_search_memory(s) / (double)in->nsec,
                       GB_PLAIN);
        gb_set_counter(st, "threads", (double)d->threads, GB_PLAIN);
        gb_set_items_processed(st, iters * (int64_t)in->nsec);
        char mis[96] = "";
        if (d->algo == CT_SEARCH_TOPO && ref) {
            int64_t missing = 0, extra = 0;
            compare_pairs(m->pos, ref, &out, &missing, &extra);
            gb_set_counter(st, "misses", (double)missing, GB_PLAIN);
            snprintf(mis, sizeof mis, " misses_vs=%s%s", ct_search_algo_name(m->ref_algo),
                     extra ? " EXTRA_PAIRS" : "");
            if (extra)
                gb_set_counter(st, "extra", (double)extra, GB_PLAIN);
        } else if (d->algo == CT_SEARCH_TOPO) {
            snprintf(mis, sizeof mis, " misses_vs=none");
        }
        snprintf(msg, sizeof msg, "h=%.4g gap=%.4g margin=%.4g %s[%s]%s", m->h_mean,
                 (double)in->gap, (double)in->margin, ctb_bind_name(cfg.bind), where, mis);
        gb_set_label(st, msg);
    }
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
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
