/*
 * bench_common.c -- helpers shared by the search benchmarks (bench_common.h).
 */
#include "bench_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_topology.h"
#include "meshgen.h"

double ctb_now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double ctb_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void ctb_minmax(const double *v, int n, double *lo, double *hi)
{
    double a = v[0], b = v[0];
    for (int i = 1; i < n; i++) {
        a = v[i] < a ? v[i] : a;
        b = v[i] > b ? v[i] : b;
    }
    *lo = a;
    *hi = b;
}

void ctb_mesh_clear(ctb_mesh *m)
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

int ctb_mesh_copy(ctb_mesh *m, const ct_search_input *src, ctb_bind_policy bind, int threads)
{
    ctb_bind_threads(bind, threads, NULL, 0);
    m->x = ctb_first_touch_copy_real(src->x, (size_t)src->nnode);
    m->y = ctb_first_touch_copy_real(src->y, (size_t)src->nnode);
    m->z = ctb_first_touch_copy_real(src->z, (size_t)src->nnode);
    m->sec = ctb_first_touch_copy_idx(src->sec, (size_t)src->nsec);
    m->n1 = ctb_first_touch_copy_idx(src->n1, (size_t)src->nseg);
    m->n2 = ctb_first_touch_copy_idx(src->n2, (size_t)src->nseg);
    m->n3 = ctb_first_touch_copy_idx(src->n3, (size_t)src->nseg);
    m->n4 = ctb_first_touch_copy_idx(src->n4, (size_t)src->nseg);
    if (!m->x || !m->y || !m->z || !m->sec || !m->n1 || !m->n2 || !m->n3 || !m->n4)
        return CT_ERR_NOMEM;
    m->in = *src;
    m->in.x = m->x;
    m->in.y = m->y;
    m->in.z = m->z;
    m->in.sec = m->sec;
    m->in.n1 = m->n1;
    m->in.n2 = m->n2;
    m->in.n3 = m->n3;
    m->in.n4 = m->n4;
    return CT_OK;
}

void ctb_search_gap(double h, double *gap, double *margin)
{
    *gap = 0.3 * h;
    *margin = 0.2 * h;
}

int ctb_mesh_case(ctb_mesh *m, const char *family, int64_t target, int numbering,
                  const ctb_search_config *cfg, double *h_mean, char *err, size_t errlen)
{
    ctd_case c;
    ct_diag diag;
    memset(&c, 0, sizeof c);
    memset(&diag, 0, sizeof diag);
    int rc = ctd_case_make(&c, family, target, (ctd_numbering)numbering, cfg->seed, &diag);
    if (rc != CT_OK) {
        snprintf(err, errlen, "mesh: %s: %s", ct_strerror(rc), diag.msg);
        return rc;
    }
    const double h = c.h_mean;
    double gap, margin;
    ctb_search_gap(h, &gap, &margin);
    ct_search_input in;
    ctd_case_input(&c, (ct_real)gap, (ct_real)margin, &in);
    /* The case itself is released once copied. */
    rc = ctb_mesh_copy(m, &in, cfg->bind, cfg->max_threads);
    ctd_case_destroy(&c);
    if (rc != CT_OK) {
        snprintf(err, errlen, "mesh input: %s", ct_strerror(rc));
        return rc;
    }
    *h_mean = h;
    return CT_OK;
}

ct_idx *ctb_position_map(const ct_search_input *in)
{
    ct_idx *pos = malloc(((size_t)in->nnode + 1) * sizeof *pos);
    if (!pos)
        return NULL;
    for (ct_idx k = 0; k < in->nnode; k++)
        pos[k] = -1;
    for (ct_idx i = 0; i < in->nsec; i++)
        pos[in->sec[i]] = i;
    return pos;
}

int ctb_search_once(ct_search_algo algo, const ct_search_input *in, ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(algo);
    ct_search *s = NULL;
    int rc = ct_search_init(&s, &p);
    if (rc == CT_OK)
        rc = ct_pairs_init(out, 0);
    if (rc == CT_OK)
        rc = ct_search_run(s, in, out);
    ct_search_destroy(s);
    return rc;
}

double ctb_pair_tests(const ct_search_input *in)
{
    return (double)in->nsec * (double)in->nseg;
}

const ct_pairs *ctb_mesh_reference(ctb_mesh *m, const ctb_search_config *cfg)
{
    if (m->ref_state)
        return m->ref_state == 1 ? &m->ref : NULL;
    m->ref_state = -1;
    const ct_search_algo order[] = {CT_SEARCH_DIRECT, CT_SEARCH_BUCKET, CT_SEARCH_BSP};
    ctb_bind_threads(cfg->bind, cfg->max_threads, NULL, 0);
    for (int k = 0; k < 3; k++) {
        if (order[k] == CT_SEARCH_DIRECT && ctb_pair_tests(&m->in) > cfg->direct_budget)
            continue;
        ct_pairs out;
        memset(&out, 0, sizeof out);
        if (ctb_search_once(order[k], &m->in, &out) != CT_OK) {
            ct_pairs_destroy(&out);
            continue;
        }
        m->pos = ctb_position_map(&m->in);
        if (!m->pos) {
            ct_pairs_destroy(&out);
            return NULL;
        }
        m->ref = out;
        m->ref_algo = order[k];
        m->ref_state = 1;
        return &m->ref;
    }
    return NULL;
}

void ctb_compare_pairs(const ct_idx *pos, const ct_pairs *ref, const ct_pairs *got,
                       int64_t *missing, int64_t *extra)
{
    int64_t a = 0, b = 0, miss = 0, more = 0;
    while (a < ref->n && b < got->n) {
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
    *missing = miss + (ref->n - a);
    *extra = more + (got->n - b);
}

int ctb_search_start(ct_search_algo algo, const ct_search_input *in, ct_search **s,
                     ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(algo);
    *s = NULL;
    memset(out, 0, sizeof *out);
    int rc = ct_search_init(s, &p);
    if (rc == CT_OK)
        rc = ct_pairs_init(out, 0);
    if (rc == CT_OK)
        rc = ct_search_run(*s, in, out);
    if (rc != CT_OK) {
        ct_search_destroy(*s);
        *s = NULL;
        ct_pairs_destroy(out);
    }
    return rc;
}

int ctb_search_timed(gb_state *st, ct_search *s, const ct_search_input *in, ct_pairs *out,
                     double *seconds)
{
    int rc = CT_OK;
    double t0 = ctb_now_s();
    while (rc == CT_OK && gb_keep_running(st))
        rc = ct_search_run(s, in, out);
    *seconds = ctb_now_s() - t0;
    return rc;
}

void ctb_search_bench(gb_state *st, ctb_mesh *m, const ctb_search_config *cfg,
                      ct_search_algo algo, int threads, double h_mean, const char *prefix)
{
    const ct_search_input *in = &m->in;
    char msg[1400];
    if (algo == CT_SEARCH_DIRECT && ctb_pair_tests(in) > cfg->direct_budget) {
        snprintf(msg, sizeof msg,
                 "skipped: over budget (nsec=%ld nseg=%ld, nsec*nseg=%.3g > %.3g)",
                 (long)in->nsec, (long)in->nseg, ctb_pair_tests(in), cfg->direct_budget);
        gb_skip_with_error(st, msg);
        return;
    }
    /* The topological search's reference is computed before binding this
     * run's threads (it binds the largest team itself). */
    const ct_pairs *ref = algo == CT_SEARCH_TOPO ? ctb_mesh_reference(m, cfg) : NULL;

    char where[256];
    ctb_bind_threads(cfg->bind, threads, where, sizeof where);
    ct_search *s;
    ct_pairs out;
    int rc = ctb_search_start(algo, in, &s, &out);
    double secs = 0;
    if (rc == CT_OK)
        rc = ctb_search_timed(st, s, in, &out, &secs);
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "search %s: %s", ct_search_algo_name(algo), ct_strerror(rc));
        gb_skip_with_error(st, msg);
    }
    int64_t iters = gb_iterations(st);
    if (rc == CT_OK && iters > 0) {
        gb_set_counter(st, "ns_per_node", secs * 1e9 / ((double)iters * (double)in->nsec),
                       GB_PLAIN);
        gb_set_counter(st, "nsec", (double)in->nsec, GB_PLAIN);
        gb_set_counter(st, "nseg", (double)in->nseg, GB_PLAIN);
        gb_set_counter(st, "pairs", (double)out.n, GB_PLAIN);
        gb_set_counter(st, "bytes_per_node", (double)ct_search_memory(s) / (double)in->nsec,
                       GB_PLAIN);
        gb_set_counter(st, "threads", (double)threads, GB_PLAIN);
        /* What the search chose by itself (the bucket grid's cell factor,
         * a renumbered copy), for the tables' notes. */
        ct_search_info si;
        if (ct_search_get_info(s, &si) == CT_OK) {
            if (si.cell_factor > 0)
                gb_set_counter(st, "cell_factor", si.cell_factor, GB_PLAIN);
            gb_set_counter(st, "renumbered", (double)si.renumbered, GB_PLAIN);
        }
        gb_set_items_processed(st, iters * (int64_t)in->nsec);
        char mis[96] = "";
        if (algo == CT_SEARCH_TOPO && ref) {
            int64_t missing = 0, extra = 0;
            ctb_compare_pairs(m->pos, ref, &out, &missing, &extra);
            gb_set_counter(st, "misses", (double)missing, GB_PLAIN);
            if (extra)
                gb_set_counter(st, "extra", (double)extra, GB_PLAIN);
            snprintf(mis, sizeof mis, " misses_vs=%s%s", ct_search_algo_name(m->ref_algo),
                     extra ? " EXTRA_PAIRS" : "");
        } else if (algo == CT_SEARCH_TOPO) {
            snprintf(mis, sizeof mis, " misses_vs=none");
        }
        snprintf(msg, sizeof msg, "%sh=%.4g gap=%.4g margin=%.4g %s[%s]%s", prefix, h_mean,
                 (double)in->gap, (double)in->margin, ctb_bind_name(cfg->bind), where, mis);
        gb_set_label(st, msg);
    }
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
}
