/*
 * bench_paired.c -- the ratio targets of the search, measured in
 * interleaved rounds.
 *
 * Three targets of the search are ratios of two runs: bsp against bucket
 * on a uniform mesh (within 2x), bsp against bucket on the graded mesh
 * (below 1), and a shuffled against the natural numbering (within 1.5x);
 * and, with no target, the topological search's shuffled against natural.
 * Taken from two rows of the search table, such a ratio compares two runs
 * made up to minutes apart, and on a shared host their conditions differ:
 * bsp/bucket on the plates read 1.6x to 2.2x in runs of the same code.
 * Here one benchmark times both searches, one whole search each per round,
 * alternating which runs first, so a slow spell of the host lands on both,
 * and reports the median of the rounds' ratios with their range.
 *
 * Names: paired/<family>/<B>-vs-<A>/t<threads>/<target nodes>; A is the
 * reference (the denominator). Counters: ns_a and ns_b (median ns per
 * secondary node), ratio (median of the rounds' B / A), ratio_min,
 * ratio_max, rounds, pairs_a and pairs_b; same_pairs = 1 when the two
 * searches returned the same list (searches of one mesh; the numberings'
 * rows compare counts only, since their lists are numbered differently).
 */
#include "bench_paired.h"

#include "bench_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_topology.h"
#include "contact.h"
#include "gbench.h"
#include "meshgen.h"

/* Rounds per repetition (each repetition of Google Benchmark runs them
 * all; the rounds alternate which search runs first). */
#define PAIRED_ROUNDS 5

typedef struct paired_desc {
    char family[32];
    int64_t target;
    ct_search_algo algo_a, algo_b;
    int num_a, num_b;
    int threads;
    struct paired_desc *next;
} paired_desc;

static paired_desc *descs;
static ctb_search_config cfg;

/* ---- Meshes: the two last used are kept -------------------------------- */

typedef struct paired_mesh {
    int valid, rc;
    char err[300];
    char family[32];
    int64_t target;
    int numbering;
    ctb_mesh m;
    double h_mean;
    unsigned long used; /* clock of the last use */
} paired_mesh;

static paired_mesh cache[2];
static unsigned long clock_use;

static void mesh_clear(paired_mesh *m)
{
    ctb_mesh_clear(&m->m);
    memset(m, 0, sizeof *m);
}

static paired_mesh *mesh_get(const char *family, int64_t target, int numbering,
                             const paired_mesh *keep)
{
    for (int i = 0; i < 2; i++) {
        paired_mesh *c = &cache[i];
        if (c->valid && c->target == target && c->numbering == numbering &&
            strcmp(c->family, family) == 0) {
            c->used = ++clock_use;
            return c;
        }
    }
    /* Replace the older entry, never the one the caller still holds. */
    paired_mesh *c = &cache[0];
    if (c == keep || (cache[1].used < c->used && &cache[1] != keep))
        c = &cache[1];
    mesh_clear(c);
    c->valid = 1;
    c->used = ++clock_use;
    snprintf(c->family, sizeof c->family, "%s", family);
    c->target = target;
    c->numbering = numbering;
    c->rc = ctb_mesh_case(&c->m, family, target, numbering, &cfg, &c->h_mean, c->err,
                          sizeof c->err);
    return c;
}

/* ---- The benchmark ------------------------------------------------------- */


/* One whole search of in, its wall time in *t. */
static int time_search(ct_search *s, const ct_search_input *in, ct_pairs *out, double *t)
{
    double t0 = ctb_now_s();
    int rc = ct_search_run(s, in, out);
    *t = ctb_now_s() - t0;
    return rc;
}

static int same_list(const ct_pairs *a, const ct_pairs *b)
{
    if (a->n != b->n)
        return 0;
    return memcmp(a->node, b->node, (size_t)a->n * sizeof(ct_idx)) == 0 &&
           memcmp(a->seg, b->seg, (size_t)a->n * sizeof(ct_idx)) == 0;
}

static void bm_paired(gb_state *st, void *arg)
{
    const paired_desc *d = arg;
    char msg[600];
    /* Two meshes of this size at most. */
    if (2.0 * (double)d->target * cfg.bytes_per_node > cfg.mem_limit) {
        gb_skip_with_error(st, "skipped: not enough memory for two meshes");
        return;
    }
    paired_mesh *ma = mesh_get(d->family, d->target, d->num_a, NULL);
    paired_mesh *mb = mesh_get(d->family, d->target, d->num_b, ma);
    if (ma->rc != CT_OK || mb->rc != CT_OK) {
        gb_skip_with_error(st, ma->rc != CT_OK ? ma->err : mb->err);
        return;
    }
    const ct_search_input *ia = &ma->m.in, *ib = &mb->m.in;
    if (ia->nsec <= 0 || ib->nsec <= 0) {
        gb_skip_with_error(st, "mesh: no secondary nodes");
        return;
    }
    char where[256];
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);
    ct_search *sa = NULL, *sb = NULL;
    ct_pairs pa, pb;
    int rc = ctb_search_start(d->algo_a, ia, &sa, &pa);
    if (rc == CT_OK) {
        rc = ctb_search_start(d->algo_b, ib, &sb, &pb);
        if (rc != CT_OK) {
            ct_search_destroy(sa);
            ct_pairs_destroy(&pa);
        }
    }
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "search: %s", ct_strerror(rc));
        gb_skip_with_error(st, msg);
        return;
    }
    double ta[PAIRED_ROUNDS], tb[PAIRED_ROUNDS], r[PAIRED_ROUNDS];
    int n = 0;
    while (gb_keep_running(st)) {
        for (n = 0; n < PAIRED_ROUNDS && rc == CT_OK; n++) {
            if (n % 2 == 0) {
                rc = time_search(sa, ia, &pa, &ta[n]);
                if (rc == CT_OK)
                    rc = time_search(sb, ib, &pb, &tb[n]);
            } else {
                rc = time_search(sb, ib, &pb, &tb[n]);
                if (rc == CT_OK)
                    rc = time_search(sa, ia, &pa, &ta[n]);
            }
            r[n] = tb[n] / ta[n];
        }
        if (rc != CT_OK) {
            snprintf(msg, sizeof msg, "search: %s", ct_strerror(rc));
            gb_skip_with_error(st, msg);
            break;
        }
    }
    if (rc == CT_OK && n == PAIRED_ROUNDS) {
        double rmin, rmax;
        ctb_minmax(r, n, &rmin, &rmax);
        const double na = (double)ia->nsec, nb = (double)ib->nsec;
        gb_set_counter(st, "ns_a", ctb_median(ta, n) * 1e9 / na, GB_PLAIN);
        gb_set_counter(st, "ns_b", ctb_median(tb, n) * 1e9 / nb, GB_PLAIN);
        gb_set_counter(st, "ratio", ctb_median(r, n), GB_PLAIN);
        gb_set_counter(st, "ratio_min", rmin, GB_PLAIN);
        gb_set_counter(st, "ratio_max", rmax, GB_PLAIN);
        gb_set_counter(st, "rounds", (double)n, GB_PLAIN);
        gb_set_counter(st, "pairs_a", (double)pa.n, GB_PLAIN);
        gb_set_counter(st, "pairs_b", (double)pb.n, GB_PLAIN);
        gb_set_counter(st, "threads", (double)d->threads, GB_PLAIN);
        if (d->num_a == d->num_b)
            gb_set_counter(st, "same_pairs", (double)same_list(&pa, &pb), GB_PLAIN);
        snprintf(msg, sizeof msg, "a=%s/%s b=%s/%s h=%.4g %s[%s]",
                 ct_search_algo_name(d->algo_a), ctd_numbering_name((ctd_numbering)d->num_a),
                 ct_search_algo_name(d->algo_b), ctd_numbering_name((ctd_numbering)d->num_b),
                 ma->h_mean, ctb_bind_name(cfg.bind), where);
        gb_set_label(st, msg);
    }
    ct_search_destroy(sa);
    ct_search_destroy(sb);
    ct_pairs_destroy(&pa);
    ct_pairs_destroy(&pb);
}

/* ---- Registration -------------------------------------------------------- */

static int add(const char *family, int64_t n, ct_search_algo a, int num_a, ct_search_algo b,
               int num_b, int threads)
{
    paired_desc *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    snprintf(d->family, sizeof d->family, "%s", family);
    d->target = n;
    d->algo_a = a;
    d->algo_b = b;
    d->num_a = num_a;
    d->num_b = num_b;
    d->threads = threads;
    d->next = descs;
    descs = d;
    char name[160];
    if (a == b)
        snprintf(name, sizeof name, "paired/%s/%s-%s-vs-%s/t%d", family, ct_search_algo_name(a),
                 ctd_numbering_name((ctd_numbering)num_b),
                 ctd_numbering_name((ctd_numbering)num_a), threads);
    else
        snprintf(name, sizeof name, "paired/%s/%s-vs-%s/t%d", family, ct_search_algo_name(b),
                 ct_search_algo_name(a), threads);
    /* One iteration: the function's rounds are the measurement. */
    return gb_register(name, bm_paired, d, n, 1, 1, 0);
}

int ctb_paired_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    /* The targets' sizes (the full set too). */
    const int64_t big = 1000000;
    int tl[2] = {1, cfg.max_threads}, nt = cfg.max_threads > 1 ? 2 : 1, count = 0;
    const ct_search_algo BK = CT_SEARCH_BUCKET, BSP = CT_SEARCH_BSP;
    const int NAT = CTD_NUM_NATURAL, SHUF = CTD_NUM_SHUFFLED;
    for (int t = 0; t < nt; t++) {
        if (add("plates", big, BK, NAT, BSP, NAT, tl[t]) != 0 ||
            add("plates", big, BK, NAT, BK, SHUF, tl[t]) != 0)
            return -1;
        count += 2;
    }
    if (add("graded", 100000, BK, NAT, BSP, NAT, tl[nt - 1]) != 0)
        return -1;
    /* Not a target of the issue: the topological search's cost of a
     * scattered numbering, now that it runs on a renumbered copy too. */
    if (add("plates", big, CT_SEARCH_TOPO, NAT, CT_SEARCH_TOPO, SHUF, tl[nt - 1]) != 0)
        return -1;
    return count + 2;
}

void ctb_paired_cleanup(void)
{
    for (int i = 0; i < 2; i++)
        mesh_clear(&cache[i]);
    while (descs) {
        paired_desc *n = descs->next;
        free(descs);
        descs = n;
    }
}
