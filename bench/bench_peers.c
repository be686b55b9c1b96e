/*
 * bench_peers.c -- the peers in the same run (bench/peers/peers.h):
 * nanoflann, CGAL box_intersection_d and Bullet's btDbvt (and the textbook
 * grid of grid_peer.cc, as a reference) on the meshes and
 * the query of the search benchmarks, checked against our search.
 *
 * Names: peer/<family>/<peer>/t<threads>/<target nodes> with the tuned
 * setting (in the label), and, with CT_BENCH_FULL=1 or CT_BENCH_PEER_TUNE=1,
 * the tuning variants peer/<family>/<peer>@<setting>/t<threads>/<nodes>.
 * Reduced set: plates at 10^4, 10^5, 10^6 and folded (self contact) at
 * 10^5; cgal on 1 thread (it is sequential), nanoflann and bullet on all
 * threads (and on 1 too in the full set).
 *
 * Each run: the mesh (cached, first-touched as in bench_search.c), our
 * bucket search's pairs as the reference (canonical order, computed once
 * per mesh), one untimed peer run whose pairs, put in canonical order, must
 * equal the reference (else the run fails with gb_skip_with_error and
 * counts as a failure: ctb_peers_cleanup returns the count); then the timed
 * loop of whole peer runs (build + query + exact filter + output). Counters:
 * ns_per_node (build + query per secondary node), build_ns_per_node,
 * query_ns_per_node, pairs, candidates (box-level, before the filter),
 * threads, nsec, nseg.
 *
 * Tuned settings (ctp_default_setting), from the tuning variants on plates
 * at 10^5 nodes, 2 threads (2-core machine, loaded, so +-50%; ns per node,
 * build + query):
 *  - nanoflann leaf_max_size 20: leaf 10 / 20 / 50 gave 1028 / 1001 / 1045
 *    (within noise; 20 is the middle of the README's 10-50 range);
 *  - CGAL cutoff 1000, axes "auto": the axis order dominates (cutoff 1000:
 *    xzy 400, yzx 832, xyz 3915, yxz 2746, zxy 4691, zyx 6226; scanning on
 *    the flat axis z is the worst), then the cutoff (xzy: 10 -> 768,
 *    1000 -> 400, 3000 -> 975); "auto" picks xzy on plates;
 *  - Bullet: leaves inserted in shuffled order, no optimisation: 4206,
 *    against 51226 for mesh-order insertion (a deep, list-like tree) and
 *    14308 for shuffled + optimizeTopDown (its build alone 12500).
 */
#include "bench_peers.h"

#include "bench_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_topology.h"
#include "contact.h"
#include "gbench.h"
#include "meshgen.h"
#include "peers/peers.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- The peers' C side (peers.h) ----------------------------------------- */

static const char *const peer_names[CTP_NPEERS] = {"nanoflann", "cgal", "bullet", "grid"};

const char *ctp_peer_name(ctp_peer p)
{
    return p >= 0 && p < CTP_NPEERS ? peer_names[p] : "unknown";
}

int ctp_peer_from_name(const char *name)
{
    for (int p = 0; name && p < CTP_NPEERS; p++)
        if (strcmp(name, peer_names[p]) == 0)
            return p;
    return -1;
}

static const int axis_orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                      {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
static const char *const axis_order_names[6] = {"xyz", "xzy", "yxz", "yzx", "zxy", "zyx"};

const char *ctp_axis_order_name(int k)
{
    return k >= 0 && k < 6 ? axis_order_names[k] : k == -1 ? "auto" : "?";
}
const int *ctp_axis_order(int k) { return axis_orders[k >= 0 && k < 6 ? k : 0]; }

int ctp_auto_axis_order(const ct_search_input *in)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const ct_real *xyz[3] = {in->x, in->y, in->z};
    for (ct_idx i = 0; i < in->nsec; i++)
        for (int k = 0; k < 3; k++) {
            double v = (double)xyz[k][in->sec[i]];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    /* Axes by decreasing extent (ties: x before y before z). */
    int a[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (hi[a[j]] - lo[a[j]] > hi[a[i]] - lo[a[i]]) {
                int t = a[i];
                a[i] = a[j];
                a[j] = t;
            }
    /* Dimension 0 (scanned) = longest, 2 (split first) = second, 1 = the
     * shortest. */
    int want[3] = {a[0], a[2], a[1]};
    for (int k = 0; k < 6; k++)
        if (axis_orders[k][0] == want[0] && axis_orders[k][1] == want[1])
            return k;
    return 0;
}

static const char *const tree_names[3] = {"incremental", "shuffled", "topdown"};

ctp_setting ctp_default_setting(ctp_peer p, int threads)
{
    ctp_setting s;
    memset(&s, 0, sizeof s);
    s.threads = p == CTP_CGAL ? 1 : (threads > 0 ? threads : 1);
    s.leaf_size = 20;
    s.cutoff = 1000;
    s.axis_order = -1;
    s.tree = CTP_DBVT_SHUFFLED;
    return s;
}

const char *ctp_setting_name(ctp_peer p, const ctp_setting *s, char *buf, size_t len)
{
    switch (p) {
    case CTP_NANOFLANN: snprintf(buf, len, "leaf%d", s->leaf_size); break;
    case CTP_CGAL:
        snprintf(buf, len, "cut%ld-%s", s->cutoff, ctp_axis_order_name(s->axis_order));
        break;
    case CTP_BULLET:
        snprintf(buf, len, "%s", tree_names[s->tree >= 0 && s->tree < 3 ? s->tree : 0]);
        break;
    case CTP_GRID: snprintf(buf, len, "textbook"); break;
    default: snprintf(buf, len, "?"); break;
    }
    return buf;
}

int ctp_run(ctp_peer p, const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
            ctp_times *t)
{
    switch (p) {
    case CTP_NANOFLANN: return ctp_nanoflann_run(in, s, out, t);
    case CTP_CGAL: return ctp_cgal_run(in, s, out, t);
    case CTP_BULLET: return ctp_bullet_run(in, s, out, t);
    case CTP_GRID: return ctp_grid_run(in, s, out, t);
    default: return CT_ERR_ARG;
    }
}

double ctp_coord_scale(const ct_search_input *in)
{
    double m = 0;
#pragma omp parallel for schedule(static) reduction(max : m)
    for (ct_idx k = 0; k < in->nnode; k++) {
        double a = fabs((double)in->x[k]), b = fabs((double)in->y[k]);
        double c = fabs((double)in->z[k]);
        double v = a > b ? a : b;
        v = v > c ? v : c;
        m = v > m ? v : m;
    }
    return m;
}

/* ---- Comparing pair sets ------------------------------------------------- */

typedef struct pair_diff {
    int64_t missing, extra; /* reference pairs not found; found pairs not in
                               the reference (duplicates included) */
    int rc;                 /* CT_OK or an allocation failure */
} pair_diff;

/* Keys (position in sec << 32 | segment) of p, sorted. */
static uint64_t *sorted_keys(const ct_idx *pos, const ct_pairs *p, int *rc)
{
    size_t n = (size_t)p->n;
    uint64_t *key = malloc((n ? n : 1) * sizeof *key);
    ct_idx *val = malloc((n ? n : 1) * sizeof *val);
    if (!key || !val) {
        free(key);
        free(val);
        *rc = CT_ERR_NOMEM;
        return NULL;
    }
    for (size_t k = 0; k < n; k++) {
        key[k] = (uint64_t)(uint32_t)pos[p->node[k]] << 32 | (uint64_t)(uint32_t)p->seg[k];
        val[k] = 0;
    }
    *rc = ctd_radix_sort(key, val, (int64_t)n);
    free(val);
    if (*rc != CT_OK) {
        free(key);
        return NULL;
    }
    return key;
}

/* The difference between the reference set ref and got (any order). pos
 * maps a global node index to its position in the secondary list. */
static pair_diff compare_sets(const ct_idx *pos, const ct_pairs *ref, const ct_pairs *got)
{
    pair_diff r = {0, 0, CT_OK};
    uint64_t *a = sorted_keys(pos, ref, &r.rc);
    uint64_t *b = a ? sorted_keys(pos, got, &r.rc) : NULL;
    if (!a || !b) {
        free(a);
        free(b);
        return r;
    }
    int64_t i = 0, j = 0, na = ref->n, nb = got->n;
    while (i < na || j < nb) {
        if (j >= nb) {
            r.missing += na - i;
            break;
        }
        if (i >= na) {
            r.extra += nb - j;
            break;
        }
        if (j > 0 && b[j] == b[j - 1]) { /* a pair reported twice */
            r.extra++;
            j++;
        } else if (a[i] == b[j]) {
            i++;
            j++;
        } else if (a[i] < b[j]) {
            r.missing++;
            i++;
        } else {
            r.extra++;
            j++;
        }
    }
    free(a);
    free(b);
    return r;
}

/* ---- What a benchmark is ------------------------------------------------- */

typedef struct peer_desc {
    char family[32];
    int64_t target;
    ctp_peer peer;
    ctp_setting set;
    int variant; /* 1: a tuning variant (its setting in the name) */
    struct peer_desc *next;
} peer_desc;

static peer_desc *descs;
static ctb_search_config cfg;
static int failures;

/* ---- The mesh cache (one mesh at a time) ---------------------------------- */

typedef struct peer_mesh {
    int valid, rc;
    char err[300];
    char family[32];
    int64_t target;
    ctb_mesh m; /* first-touched copies of the search input; ref: our bucket
                 * search's pairs (ref_state -1: failed, rc in ref_rc) */
    double h_mean;
    int ref_rc;
} peer_mesh;

static peer_mesh cur;

static void mesh_clear(peer_mesh *m)
{
    ctb_mesh_clear(&m->m);
    memset(m, 0, sizeof *m);
}

/* The mesh of (family, target), natural numbering (or the current one). */
static peer_mesh *mesh_get(const char *family, int64_t target)
{
    if (cur.valid && cur.target == target && strcmp(cur.family, family) == 0)
        return &cur;
    mesh_clear(&cur);
    cur.valid = 1;
    snprintf(cur.family, sizeof cur.family, "%s", family);
    cur.target = target;
    cur.rc = ctb_mesh_case(&cur.m, family, target, CTD_NUM_NATURAL, &cfg, &cur.h_mean, cur.err,
                           sizeof cur.err);
    return &cur;
}

/* Our bucket search's pairs on the current mesh (computed once). */
static const ct_pairs *mesh_reference(peer_mesh *pm)
{
    ctb_mesh *m = &pm->m;
    if (m->ref_state)
        return m->ref_state == 1 ? &m->ref : NULL;
    m->ref_state = -1;
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    m->pos = ctb_position_map(&m->in);
    if (!m->pos) {
        pm->ref_rc = CT_ERR_NOMEM;
        return NULL;
    }
    ct_pairs out;
    memset(&out, 0, sizeof out);
    pm->ref_rc = ctb_search_once(CT_SEARCH_BUCKET, &m->in, &out);
    if (pm->ref_rc != CT_OK) {
        ct_pairs_destroy(&out);
        return NULL;
    }
    m->ref = out;
    m->ref_algo = CT_SEARCH_BUCKET;
    m->ref_state = 1;
    return &m->ref;
}

/* ---- The benchmark ------------------------------------------------------- */

static void bm_peer(gb_state *st, void *arg)
{
    const peer_desc *d = arg;
    char msg[512], sname[64];
    ctp_setting_name(d->peer, &d->set, sname, sizeof sname);

    double need = (double)d->target * (cfg.bytes_per_node + 300.0);
    if (need > cfg.mem_limit) {
        snprintf(msg, sizeof msg, "skipped: not enough memory (need about %.1f GB)", need / 1e9);
        gb_skip_with_error(st, msg);
        return;
    }
    peer_mesh *m = mesh_get(d->family, d->target);
    if (m->rc != CT_OK) {
        gb_skip_with_error(st, m->err);
        return;
    }
    const ct_search_input *in = &m->m.in;
    const ct_pairs *ref = mesh_reference(m);
    if (!ref) {
        snprintf(msg, sizeof msg, "reference (bucket search): %s", ct_strerror(m->ref_rc));
        failures++;
        gb_skip_with_error(st, msg);
        return;
    }

    char where[256];
    ctb_bind_threads(cfg.bind, d->set.threads, where, sizeof where);
    ct_pairs out;
    ctp_times t;
    int rc = ct_pairs_init(&out, 0);
    /* Untimed: the peer's buffers grow; its pairs are checked. */
    if (rc == CT_OK)
        rc = ctp_run(d->peer, in, &d->set, &out, &t);
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "peer %s (%s): %s", ctp_peer_name(d->peer), sname,
                 ct_strerror(rc));
        failures++;
        gb_skip_with_error(st, msg);
        ct_pairs_destroy(&out);
        return;
    }
    pair_diff diff = compare_sets(m->m.pos, ref, &out);
    if (diff.rc != CT_OK || diff.missing || diff.extra) {
        snprintf(msg, sizeof msg,
                 "MISMATCH: peer %s (%s) against bucket: %ld pairs, %ld missing, %ld extra%s",
                 ctp_peer_name(d->peer), sname, (long)out.n, (long)diff.missing,
                 (long)diff.extra, diff.rc != CT_OK ? " (comparison out of memory)" : "");
        failures++;
        gb_skip_with_error(st, msg);
        ct_pairs_destroy(&out);
        return;
    }

    double build = 0, query = 0, cand = 0;
    while (gb_keep_running(st)) {
        rc = ctp_run(d->peer, in, &d->set, &out, &t);
        if (rc != CT_OK) {
            snprintf(msg, sizeof msg, "peer %s: %s", ctp_peer_name(d->peer), ct_strerror(rc));
            failures++;
            gb_skip_with_error(st, msg);
            break;
        }
        build += t.build_s;
        query += t.query_s;
        cand += (double)t.candidates;
    }
    int64_t iters = gb_iterations(st);
    if (rc == CT_OK && iters > 0) {
        double per = 1e9 / ((double)iters * (double)in->nsec);
        gb_set_counter(st, "ns_per_node", (build + query) * per, GB_PLAIN);
        gb_set_counter(st, "build_ns_per_node", build * per, GB_PLAIN);
        gb_set_counter(st, "query_ns_per_node", query * per, GB_PLAIN);
        gb_set_counter(st, "pairs", (double)out.n, GB_PLAIN);
        gb_set_counter(st, "candidates", cand / (double)iters, GB_PLAIN);
        gb_set_counter(st, "nsec", (double)in->nsec, GB_PLAIN);
        gb_set_counter(st, "nseg", (double)in->nseg, GB_PLAIN);
        gb_set_counter(st, "threads", (double)d->set.threads, GB_PLAIN);
        gb_set_items_processed(st, iters * (int64_t)in->nsec);
        snprintf(msg, sizeof msg, "%s%s same_as=bucket h=%.4g gap=%.4g margin=%.4g %s[%s]",
                 sname, d->variant ? "" : " (tuned)", m->h_mean, (double)in->gap,
                 (double)in->margin, ctb_bind_name(cfg.bind), where);
        gb_set_label(st, msg);
    }
    ct_pairs_destroy(&out);
}

/* ---- Registration -------------------------------------------------------- */

static int add(const char *family, int64_t n, ctp_peer peer, const ctp_setting *set,
               int variant)
{
    peer_desc *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    snprintf(d->family, sizeof d->family, "%s", family);
    d->target = n;
    d->peer = peer;
    d->set = *set;
    d->variant = variant;
    d->next = descs;
    descs = d;
    char name[192], sname[64] = "";
    if (variant) {
        sname[0] = '@';
        ctp_setting_name(peer, set, sname + 1, sizeof sname - 1);
    }
    snprintf(name, sizeof name, "peer/%s/%s%s/t%d", family, ctp_peer_name(peer), sname,
             set->threads);
    return gb_register(name, bm_peer, d, n, 1, 0, 0);
}

/* The tuned setting of each peer on 1 thread and on all threads. */
static int add_tuned(const char *family, int64_t n, int *count)
{
    for (int p = 0; p < CTP_NPEERS; p++) {
        int tl[2] = {cfg.max_threads, 1};
        int nt = (p == CTP_CGAL || cfg.max_threads == 1) ? 1 : (cfg.full ? 2 : 1);
        for (int k = 0; k < nt; k++) {
            ctp_setting s = ctp_default_setting((ctp_peer)p, p == CTP_CGAL ? 1 : tl[k]);
            if (add(family, n, (ctp_peer)p, &s, 0) != 0)
                return -1;
            (*count)++;
        }
    }
    return 0;
}

/* The tuning variants: nanoflann's leaf size, CGAL's cutoff and axis
 * order, Bullet's tree variant. */
static int add_variants(const char *family, int64_t n, int *count)
{
    static const int leaves[] = {10, 20, 50};
    static const long cutoffs[] = {10, 1000, 3000};
    for (int k = 0; k < 3; k++) {
        ctp_setting s = ctp_default_setting(CTP_NANOFLANN, cfg.max_threads);
        s.leaf_size = leaves[k];
        if (add(family, n, CTP_NANOFLANN, &s, 1) != 0)
            return -1;
        (*count)++;
    }
    for (int k = 0; k < 3; k++)
        for (int a = -1; a < 6; a++) {
            ctp_setting s = ctp_default_setting(CTP_CGAL, 1);
            s.cutoff = cutoffs[k];
            s.axis_order = a;
            if (add(family, n, CTP_CGAL, &s, 1) != 0)
                return -1;
            (*count)++;
        }
    for (int k = 0; k < 3; k++) {
        ctp_setting s = ctp_default_setting(CTP_BULLET, cfg.max_threads);
        s.tree = k;
        if (add(family, n, CTP_BULLET, &s, 1) != 0)
            return -1;
        (*count)++;
    }
    return 0;
}

int ctb_peers_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    const char *e = getenv("CT_BENCH_PEER_TUNE");
    int tune = cfg.full || (e && *e && strcmp(e, "0") != 0);
    int count = 0;
    int64_t nmax = cfg.full ? 10000000 : 1000000;
    /* Registered size by size so each mesh is built once. */
    for (int64_t n = 10000; n <= nmax; n *= 10) {
        if (add_tuned("plates", n, &count) != 0)
            return -1;
        if (tune && (n == 100000 || (cfg.full && n == 1000000)) &&
            add_variants("plates", n, &count) != 0)
            return -1;
    }
    if (add_tuned("folded", 100000, &count) != 0)
        return -1;
    if (cfg.full && add_tuned("folded", 1000000, &count) != 0)
        return -1;
    return count;
}

int ctb_peers_cleanup(void)
{
    mesh_clear(&cur);
    while (descs) {
        peer_desc *n = descs->next;
        free(descs);
        descs = n;
    }
    int f = failures;
    failures = 0;
    return f;
}

/* ---- The verification mode ----------------------------------------------- */

/* Every setting the verification runs: each peer's tuned one, and the knob
 * values at their extremes (nanoflann leaf 1 and 50; CGAL cutoff 1, which
 * splits down to single boxes, and 1000, with all six axis orders; every
 * Bullet tree variant). */
static int verify_settings(ctp_peer p, int threads, ctp_setting *s)
{
    int n = 0;
    s[n++] = ctp_default_setting(p, threads);
    if (p == CTP_NANOFLANN) {
        static const int leaves[] = {1, 10, 50};
        for (int k = 0; k < 3; k++) {
            s[n] = ctp_default_setting(p, threads);
            s[n++].leaf_size = leaves[k];
        }
    } else if (p == CTP_CGAL) {
        static const long cutoffs[] = {1, 1000};
        for (int k = 0; k < 2; k++)
            for (int a = -1; a < 6; a++) {
                s[n] = ctp_default_setting(p, 1);
                s[n].cutoff = cutoffs[k];
                s[n++].axis_order = a;
            }
    } else if (p == CTP_BULLET) {
        for (int k = 0; k < 3; k++) {
            s[n] = ctp_default_setting(p, threads);
            s[n++].tree = k;
        }
    }
    return n;
}

int ctb_peers_verify_main(int argc, char **argv)
{
    int found = 0;
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--verify-peers") == 0)
            found = 1;
    if (!found)
        return -1;
    static const char *const families[] = {"plates", "plates-tri", "sphere", "graded",
                                           "folded", "crumpled", "soup"};
    const int nfam = (int)(sizeof families / sizeof families[0]);
#ifdef _OPENMP
    int tmax = omp_get_max_threads();
#else
    int tmax = 1;
#endif
    int runs = 0, bad = 0;
    printf("verify-peers: every peer and setting against the direct search, %d thread(s)"
           " and 1\n", tmax);
    for (int f = 0; f < nfam; f++) {
        ctd_case c;
        ct_diag diag;
        memset(&c, 0, sizeof c);
        memset(&diag, 0, sizeof diag);
        int rc = ctd_case_make(&c, families[f], 1500, CTD_NUM_NATURAL, 12345, &diag);
        if (rc != CT_OK) {
            printf("FAIL %s: mesh: %s: %s\n", families[f], ct_strerror(rc), diag.msg);
            bad++;
            continue;
        }
        for (int filt = 0; filt < 2; filt++) {
            ct_search_input in;
            double gap, margin;
            ctb_search_gap(c.h_mean, &gap, &margin);
            ctd_case_input(&c, (ct_real)gap, (ct_real)margin, &in);
            in.filter = filt ? CT_FILTER_BOX : CT_FILTER_HULL;
            const char *fname = filt ? "box" : "hull";
            ct_pairs ref;
            memset(&ref, 0, sizeof ref);
            ct_idx *pos = ctb_position_map(&in);
            rc = pos ? ctb_search_once(CT_SEARCH_DIRECT, &in, &ref) : CT_ERR_NOMEM;
            if (rc != CT_OK || ref.n == 0) {
                printf("FAIL %s/%s: direct search: %s (%ld pairs)\n", families[f], fname,
                       ct_strerror(rc), (long)ref.n);
                bad++;
                ct_pairs_destroy(&ref);
                free(pos);
                continue;
            }
            for (int p = 0; p < CTP_NPEERS; p++) {
                int tl[2] = {tmax, 1};
                int nt = (p == CTP_CGAL || tmax == 1) ? 1 : 2;
                for (int k = 0; k < nt; k++) {
                    ctp_setting set[24];
                    int ns = verify_settings((ctp_peer)p, tl[k], set);
                    for (int q = 0; q < ns; q++) {
                        char sname[64];
                        ctp_setting_name((ctp_peer)p, &set[q], sname, sizeof sname);
                        ct_pairs out;
                        ctp_times t;
                        memset(&t, 0, sizeof t);
                        int r = ct_pairs_init(&out, 0);
                        if (r == CT_OK)
                            r = ctp_run((ctp_peer)p, &in, &set[q], &out, &t);
                        pair_diff df = {0, 0, CT_OK};
                        if (r == CT_OK)
                            df = compare_sets(pos, &ref, &out);
                        int ok = r == CT_OK && df.rc == CT_OK && !df.missing && !df.extra;
                        printf("%s %s/%s nsec=%ld nseg=%ld self=%d %s %s t%d: %ld pairs "
                               "(direct %ld), %ld candidates, %ld missing, %ld extra%s%s\n",
                               ok ? "ok  " : "FAIL", families[f], fname, (long)in.nsec,
                               (long)in.nseg, in.self, ctp_peer_name((ctp_peer)p), sname,
                               set[q].threads, (long)out.n, (long)ref.n, (long)t.candidates,
                               (long)df.missing, (long)df.extra, r ? ": " : "",
                               r ? ct_strerror(r) : "");
                        runs++;
                        bad += !ok;
                        ct_pairs_destroy(&out);
                    }
                }
            }
            ct_pairs_destroy(&ref);
            free(pos);
        }
        ctd_case_destroy(&c);
    }
    printf("verify-peers: %d runs, %d failed\n", runs, bad);
    fflush(stdout);
    return bad ? 1 : 0;
}
