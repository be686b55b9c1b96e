/*
 * bench_trade_search.c -- the search-side knobs of the speed/accuracy trade
 * (see bench_trade.c for what each measures): the search algorithm, the
 * search filter and the re-sort margin, all on the moving scenes, the
 * renumbering of scattered inputs on shuffled plates and the dense leaves of
 * the bsp search on the graded mesh.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_trade_internal.h"

/* ---- Knob: search algorithm --------------------------------------------- */

void ctbt_bm_search(gb_state *st, const tdesc *d)
{
    movecase *m = ctbt_mv_get(d->variant);
    if (m->state < 0) {
        gb_skip_with_error(st, m->err);
        return;
    }
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    ct_search_algo algo = (ct_search_algo)d->sub;
    char name[64];
    snprintf(name, sizeof name, "%s@%s", ct_search_algo_name(algo), ctbt_mv_name[d->variant]);
    ct_search_params p = ct_search_default_params(algo);
    ct_search *s = NULL;
    ct_pairs out;
    memset(&out, 0, sizeof out);
    int rc = ct_search_init(&s, &p);
    if (rc == CT_OK)
        rc = ct_pairs_init(&out, 0);
    int64_t miss = 0, extra = 0, found = 0;
    ct_search_input in;
    /* Accuracy: the 30 steps forward from a fresh workspace (direct is the
     * reference itself: 0 misses by construction, not run again). */
    if (algo == CT_SEARCH_DIRECT)
        found = (int64_t)ctbt_mv_ref_pairs(m);
    for (int k = 0; k < MV_STEPS && rc == CT_OK && algo != CT_SEARCH_DIRECT; k++) {
        ctbt_mv_input(m, k, &in);
        rc = ct_search_run(s, &in, &out);
        int64_t e = 0;
        if (rc == CT_OK)
            miss += ctbt_count_missing(m->pos, m->ref[k].n, m->ref[k].node, m->ref[k].seg, &out,
                                       &e);
        extra += e;
        found += out.n;
    }
    int64_t it = 0;
    double t0 = ctbt_now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        ctbt_mv_input(m, ctbt_pingpong(it++), &in);
        rc = ct_search_run(s, &in, &out);
    }
    double dt = ctbt_now_s() - t0;
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
    if (rc != CT_OK) {
        ctbt_set_skip(st, name, rc);
        return;
    }
    double nsec = m->c.sec.n;
    ctbt_cost_accuracy(st, dt, it, (double)nsec, (double)miss);
    gb_set_counter(st, "x_extra", (double)extra, GB_PLAIN);
    gb_set_counter(st, "x_ref_pairs_per_node", ctbt_mv_ref_pairs(m) / (MV_STEPS * nsec), GB_PLAIN);
    gb_set_counter(st, "x_pairs_per_node", (double)found / (MV_STEPS * nsec), GB_PLAIN);
    gb_set_counter(st, "x_ref_pairs", ctbt_mv_ref_pairs(m), GB_PLAIN);
    char note[300];
    snprintf(note, sizeof note,
             "%s, %ld secondary nodes, %d steps (max node step %.2f h), a search every step, "
             "gap 0.3 h + margin 0.2 h, %d threads",
             d->variant == MV_SHEET ? "moving crumpled sheet (self contact)"
                                    : "plates sliding (secondary plate moved rigidly)",
             (long)m->c.sec.n, MV_STEPS, m->maxstep, ctbt_cfg.max_threads);
    ctbt_label(st, "search", name, "ns/node per search",
               "pairs missed vs direct, summed over the steps", note);
}

/* ---- Knob: search filter ------------------------------------------------- */

void ctbt_bm_filter(gb_state *st, const tdesc *d)
{
    movecase *m = ctbt_mv_get(MV_SHEET);
    if (m->state < 0) {
        gb_skip_with_error(st, m->err);
        return;
    }
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *s = NULL;
    ct_pairs out;
    memset(&out, 0, sizeof out);
    geobuf gb;
    memset(&gb, 0, sizeof gb);
    int rc = ct_search_init(&s, &p);
    if (rc == CT_OK)
        rc = ct_pairs_init(&out, 0);
    ct_real gap = (ct_real)(TR_GAP * m->h);
    double pairs = 0, active = 0;
    ct_search_input in;
    for (int k = 0; k < MV_STEPS && rc == CT_OK; k++) {
        ctbt_mv_input(m, k, &in);
        in.filter = (ct_search_filter)d->sub;
        ct_narrow_stats ns;
        rc = ct_search_run(s, &in, &out);
        if (rc == CT_OK)
            rc = ctbt_narrow(&in, &out, CT_QUAD_4TRI, gap, &gb, &ns);
        pairs += out.n;
        active += (double)ns.active;
    }
    int64_t it = 0;
    double tsearch = 0, t0 = ctbt_now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        ctbt_mv_input(m, ctbt_pingpong(it++), &in);
        in.filter = (ct_search_filter)d->sub;
        double ta = ctbt_now_s();
        rc = ct_search_run(s, &in, &out);
        tsearch += ctbt_now_s() - ta;
        if (rc == CT_OK)
            rc = ctbt_narrow(&in, &out, CT_QUAD_4TRI, gap, &gb, NULL);
    }
    double dt = ctbt_now_s() - t0;
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
    ctbt_geo_free(&gb);
    const char *name = d->sub == CT_FILTER_BOX ? "box" : "hull";
    if (rc != CT_OK) {
        ctbt_set_skip(st, name, rc);
        return;
    }
    double nsec = m->c.sec.n, div = (double)(it ? it : 1) * nsec;
    gb_set_counter(st, "cost", dt * 1e9 / div, GB_PLAIN);
    gb_set_counter(st, "accuracy", pairs / (MV_STEPS * nsec), GB_PLAIN);
    gb_set_counter(st, "x_search_ns_per_node", tsearch * 1e9 / div, GB_PLAIN);
    gb_set_counter(st, "x_active_per_node", active / (MV_STEPS * nsec), GB_PLAIN);
    char note[300];
    snprintf(note, sizeof note,
             "bucket search + 4-triangle narrow phase every step, moving crumpled sheet, %ld "
             "nodes, gap 0.3 h + margin 0.2 h, %d threads",
             (long)m->c.sec.n, ctbt_cfg.max_threads);
    ctbt_label(st, "filter", name, "ns/node per step (search + narrow phase)",
               "candidate pairs per node", note);
}

/* ---- Knob: re-sort margin ------------------------------------------------ */

/* One step of the re-sort scheme at step k: re-sort when needed (x0 keeps
 * the positions of the last sort), then the narrow phase over the stored
 * candidates. *sorted = 1 when it searched. */
static int margin_step(const movecase *m, int k, ct_real margin, ct_search *s,
                       ct_pairs *cand, ct_real *x0, ct_real *y0, ct_real *z0, int force,
                       geobuf *gb, int *sorted)
{
    ct_search_input in;
    ctbt_mv_input(m, k, &in);
    in.margin = margin;
    *sorted = force || ct_resort_needed(in.nsec, in.sec, in.nsec, in.sec, x0, y0, z0, in.x,
                                        in.y, in.z, margin, NULL);
    int rc = CT_OK;
    if (*sorted) {
        rc = ct_search_run(s, &in, cand);
        size_t bytes = (size_t)m->nnode * sizeof(ct_real);
        memcpy(x0, in.x, bytes);
        memcpy(y0, in.y, bytes);
        memcpy(z0, in.z, bytes);
    }
    if (rc == CT_OK)
        rc = ctbt_narrow(&in, cand, CT_QUAD_4TRI, in.gap, gb, NULL);
    return rc;
}

void ctbt_bm_margin(gb_state *st, const tdesc *d)
{
    movecase *m = ctbt_mv_get(MV_SHEET);
    if (m->state < 0) {
        gb_skip_with_error(st, m->err);
        return;
    }
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    ct_real margin = (ct_real)(ctbt_margins[d->sub] * m->h), gap = (ct_real)(TR_GAP * m->h);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *s = NULL;
    ct_pairs cand, within;
    memset(&cand, 0, sizeof cand);
    memset(&within, 0, sizeof within);
    geobuf gb;
    memset(&gb, 0, sizeof gb);
    size_t n = (size_t)m->nnode;
    ct_real *x0 = ct_calloc(n, sizeof(ct_real)), *y0 = ct_calloc(n, sizeof(ct_real));
    ct_real *z0 = ct_calloc(n, sizeof(ct_real));
    int rc = x0 && y0 && z0 ? ct_search_init(&s, &p) : CT_ERR_NOMEM;
    if (rc == CT_OK)
        rc = ct_pairs_init(&cand, 0);
    if (rc == CT_OK)
        rc = ct_pairs_init(&within, 0);
    int64_t miss = 0, resorts = 0;
    double pairs = 0;
    for (int k = 0; k < MV_STEPS && rc == CT_OK; k++) {
        int sorted = 0;
        rc = margin_step(m, k, margin, s, &cand, x0, y0, z0, k == 0, &gb, &sorted);
        resorts += k > 0 && sorted;
        pairs += cand.n;
        if (rc != CT_OK)
            break;
        /* The pairs within the gap now: the direct reference (gap + 0.2 h)
         * filtered by the shared predicate at distance gap. */
        ct_search_input in;
        ctbt_mv_input(m, k, &in);
        rc = ct_pairs_reserve(&within, m->ref[k].n);
        within.n = 0;
        for (ct_idx q = 0; q < m->ref[k].n && rc == CT_OK; q++) {
            ct_idx nd = m->ref[k].node[q], sg = m->ref[k].seg[q];
            ct_real pp[3] = {in.x[nd], in.y[nd], in.z[nd]}, c[4][3];
            const ct_idx cn[4] = {in.n1[sg], in.n2[sg], in.n3[sg], in.n4[sg]};
            for (int j = 0; j < 4; j++) {
                c[j][0] = in.x[cn[j]];
                c[j][1] = in.y[cn[j]];
                c[j][2] = in.z[cn[j]];
            }
            if (ct_pair_may_touch(pp, c[0], c[1], c[2], c[3], gap)) {
                within.node[within.n] = nd;
                within.seg[within.n] = sg;
                within.n++;
            }
        }
        if (rc == CT_OK)
            miss += ctbt_count_missing(m->pos, within.n, within.node, within.seg, &cand, NULL);
    }
    int64_t it = 0;
    double t0 = ctbt_now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        int sorted = 0;
        rc = margin_step(m, ctbt_pingpong(it++), margin, s, &cand, x0, y0, z0, 0, &gb, &sorted);
    }
    double dt = ctbt_now_s() - t0;
    ct_search_destroy(s);
    ct_pairs_destroy(&cand);
    ct_pairs_destroy(&within);
    ctbt_geo_free(&gb);
    ct_free(x0);
    ct_free(y0);
    ct_free(z0);
    char name[32];
    snprintf(name, sizeof name, "%gh", ctbt_margins[d->sub]);
    if (rc != CT_OK) {
        ctbt_set_skip(st, name, rc);
        return;
    }
    double nsec = m->c.sec.n;
    ctbt_cost_accuracy(st, dt, it, (double)nsec, (double)miss);
    gb_set_counter(st, "x_pairs_per_node", pairs / (MV_STEPS * nsec), GB_PLAIN);
    gb_set_counter(st, "x_resorts_per_100", 100.0 * (double)resorts / (MV_STEPS - 1),
                   GB_PLAIN);
    char note[300];
    snprintf(note, sizeof note,
             "each step: ct_resort_needed, bucket search (gap + margin) when needed, "
             "4-triangle narrow phase over the stored candidates; moving crumpled sheet, %ld "
             "nodes, max step %.2f h, gap 0.3 h, %d threads",
             (long)m->c.sec.n, m->maxstep, ctbt_cfg.max_threads);
    ctbt_label(st, "margin", name, "amortised ns/node per step",
               "pairs within the gap missing from the candidates (summed over the steps)", note);
}

/* ---- Knobs on one static search case: renumbering, dense bsp leaves, cells */

/* The cases, built on first use with their reference pairs:
 *  SK_RENUM  shuffled plates (RN_TARGET secondaries), reference the bucket
 *            search with renumbering off;
 *  SK_DENSE  the graded mesh (DN_TARGET secondaries, natural numbering),
 *            reference the bsp search with no dense leaf (the batch path);
 *  SK_CELL + f  family ctbt_cell_families[f] (CL_TARGET secondaries,
 *            natural numbering), reference the bucket search with its
 *            default grid (chosen per input). The grid's size changes the
 *            cost only: the rows show how far the chosen grid ("auto") and
 *            the Radioss sizing (factor 1, from the bounding box's faces)
 *            are from the best factor on each kind of mesh. */
enum { SK_RENUM, SK_DENSE, SK_CELL, SK_N = SK_CELL + CL_NFAMILY };
/* 0: the grid the search chooses (the default); 1: the Radioss sizing. */
const double ctbt_cell_factors[CL_NFACTOR] = {0, 0.25, 0.35, 0.5, 0.7, 1.0, 2.0};
const char *const ctbt_cell_families[CL_NFAMILY] = {"crumpled", "folded", "soup", "graded"};
static struct skcase {
    int state; /* 0: not built, 1: ready, -1: failed */
    char err[256];
    ctd_case c;
    ct_search_input in;
    ct_pairs ref;
} sk[SK_N];

void ctbt_rn_free(void)
{
    for (int i = 0; i < SK_N; i++) {
        if (sk[i].state == 0)
            continue;
        ct_pairs_destroy(&sk[i].ref);
        ctd_case_destroy(&sk[i].c);
        memset(&sk[i], 0, sizeof sk[i]);
    }
}

/* A search of algorithm a with renumber, renumber_keep, dense and
 * cell_factor (0: the default) set. */
static int sk_run(ct_search_algo a, int renumber, int keep, int dense, double cell,
                  const ct_search_input *in, ct_search **s, ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(a);
    p.renumber = renumber;
    p.renumber_keep = keep;
    p.dense = dense;
    p.cell_factor = cell;
    int rc = ct_search_init(s, &p);
    return rc == CT_OK ? ct_search_run(*s, in, out) : rc;
}

/* Pairs of a not in b plus pairs of b not in a (both canonical). */
static int64_t sk_differ(const ct_pairs *a, const ct_pairs *b)
{
    int64_t d = 0;
    ct_idx i = 0, j = 0;
    while (i < a->n || j < b->n) {
        int c;
        if (i == a->n)
            c = 1;
        else if (j == b->n)
            c = -1;
        else
            c = a->node[i] != b->node[j] ? (a->node[i] < b->node[j] ? -1 : 1)
                : a->seg[i] != b->seg[j] ? (a->seg[i] < b->seg[j] ? -1 : 1)
                                         : 0;
        d += c != 0;
        i += c <= 0;
        j += c >= 0;
    }
    return d;
}

static struct skcase *sk_get(int which)
{
    struct skcase *k = &sk[which];
    if (k->state != 0)
        return k;
    ct_diag dg = {0};
    k->state = -1;
    int rc = which == SK_RENUM
                 ? ctd_case_make(&k->c, "plates", RN_TARGET, CTD_NUM_SHUFFLED, 3, &dg)
             : which == SK_DENSE
                 ? ctd_case_make(&k->c, "graded", DN_TARGET, CTD_NUM_NATURAL, 3, &dg)
                 : ctd_case_make(&k->c, ctbt_cell_families[which - SK_CELL], CL_TARGET,
                                 CTD_NUM_NATURAL, 3, &dg);
    ct_search *s = NULL;
    if (rc == CT_OK) {
        ctd_case_input(&k->c, (ct_real)(TR_GAP * k->c.h_mean), (ct_real)(TR_MARGIN * k->c.h_mean),
                       &k->in);
        rc = ct_pairs_init(&k->ref, 0);
        if (rc == CT_OK)
            rc = which == SK_RENUM   ? sk_run(CT_SEARCH_BUCKET, -1, 0, 0, 0, &k->in, &s, &k->ref)
                 : which == SK_DENSE ? sk_run(CT_SEARCH_BSP, 0, 0, -1, 0, &k->in, &s, &k->ref)
                                     : sk_run(CT_SEARCH_BUCKET, 0, 0, 0, 0, &k->in, &s, &k->ref);
        ct_search_destroy(s);
    }
    if (rc == CT_OK)
        k->state = 1;
    else
        snprintf(k->err, sizeof k->err, "%s case: %.200s",
                 which == SK_RENUM ? "renumbering" : which == SK_DENSE ? "dense-leaf" : "cell-size",
                 dg.msg[0] ? dg.msg : ct_strerror(rc));
    return k;
}

const char *ctbt_renum_name(int variant)
{
    return variant == 0 ? "off" : variant == 1 ? "auto" : "fresh";
}

/* renumber: d->sub the algorithm, d->variant 0 off, 1 auto, 2 fresh (auto,
 * a new numbering every search). dense: bsp, d->variant -1 off, 0 auto,
 * 1 on. cell: bucket, d->sub the family, d->variant the factor's index. */
void ctbt_bm_static_search(gb_state *st, const tdesc *d)
{
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    const int which = d->knob == K_DENSE ? SK_DENSE
                      : d->knob == K_CELL ? SK_CELL + d->sub
                                          : SK_RENUM;
    struct skcase *k = sk_get(which);
    if (k->state < 0) {
        gb_skip_with_error(st, k->err);
        return;
    }
    const ct_search_algo a = which == SK_RENUM   ? (ct_search_algo)d->sub
                             : which == SK_DENSE ? CT_SEARCH_BSP
                                                 : CT_SEARCH_BUCKET;
    const int renumber = which == SK_RENUM ? (d->variant ? 0 : -1) : 0;
    const int keep = which == SK_RENUM && d->variant == 2 ? -1 : 0;
    const int dense = which == SK_DENSE ? d->variant : 0;
    const double cell = which >= SK_CELL ? ctbt_cell_factors[d->variant] : 0;
    char name[64];
    if (which == SK_RENUM)
        snprintf(name, sizeof name, "%s@%s", ctbt_renum_name(d->variant), ct_search_algo_name(a));
    else if (which == SK_DENSE)
        snprintf(name, sizeof name, "%s@graded", ctbt_dense_name(dense));
    else
        snprintf(name, sizeof name, "%s@%s", ctbt_cell_name(d->variant),
                 ctbt_cell_families[d->sub]);
    ct_search *s = NULL;
    ct_pairs out;
    memset(&out, 0, sizeof out);
    int rc = ct_pairs_init(&out, 0);
    if (rc == CT_OK)
        rc = sk_run(a, renumber, keep, dense, cell, &k->in, &s, &out); /* the untimed warm-up */
    const int64_t differ = rc == CT_OK ? sk_differ(&out, &k->ref) : 0;
    const double mem = (double)ct_search_memory(s);
    int64_t it = 0;
    double t0 = ctbt_now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        rc = ct_search_run(s, &k->in, &out);
        it++;
    }
    double dt = ctbt_now_s() - t0;
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
    if (rc != CT_OK) {
        ctbt_set_skip(st, name, rc);
        return;
    }
    const double nsec = k->c.sec.n;
    ctbt_cost_accuracy(st, dt, it, (double)nsec, (double)differ);
    gb_set_counter(st, "x_bytes_per_node", mem / nsec, GB_PLAIN);
    char note[300], mesh[96];
    if (which >= SK_CELL)
        snprintf(mesh, sizeof mesh, "%s, natural numbering", ctbt_cell_families[d->sub]);
    snprintf(note, sizeof note,
             "%s, %ld secondary nodes, gap 0.3 h + margin 0.2 h, %d threads",
             which == SK_RENUM   ? "plates, shuffled numbering"
             : which == SK_DENSE ? "graded mesh, natural numbering"
                                 : mesh,
             (long)k->c.sec.n, ctbt_cfg.max_threads);
    if (which == SK_RENUM)
        ctbt_label(st, "renumber", name, "ns/node per search",
                   "pairs differing from the bucket search with renumbering off", note);
    else if (which == SK_DENSE)
        ctbt_label(st, "dense", name, "ns/node per search",
                   "pairs differing from the bsp search without dense leaves", note);
    else
        ctbt_label(st, "bucket cells", name, "ns/node per search",
                   "pairs differing from the bucket search with its chosen grid (the default)",
                   note);
}

const char *ctbt_cell_name(int v)
{
    static char names[CL_NFACTOR][16];
    if (ctbt_cell_factors[v] == 0)
        return "auto";
    snprintf(names[v], sizeof names[v], "%g", ctbt_cell_factors[v]);
    return names[v];
}

const char *ctbt_dense_name(int dense)
{
    return dense < 0 ? "off" : dense > 0 ? "on" : "auto";
}
