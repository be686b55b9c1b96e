/*
 * bench_trade.c -- the speed/accuracy trade (issue 5 item 7, DESIGN.md
 * section 10): one benchmark per knob setting, each with a cost counter and
 * the accuracy figure that knob changes (see bench_trade.h for the names,
 * counters and label).
 *
 * Knobs and what is measured:
 *  search     direct, topological, bucket, bsp on the moving sheet (below)
 *             and on two sliding plates ("plates" of meshgen.h, ~4000
 *             secondary nodes, the secondary plate moved rigidly by
 *             s(k) (3 h, 1.5 h, 0), s(k) as below), a search every step:
 *             cost ns per node per search; accuracy the pairs missed
 *             against the direct search, summed over the 30 steps (the
 *             topological search misses, the others must show 0).
 *  filter     CT_FILTER_HULL vs CT_FILTER_BOX (bucket) on the moving
 *             sheet: cost ns per node per step of search + narrow phase
 *             (4 triangles) over the candidates; accuracy the candidate
 *             pairs per node (the extra narrow-phase work); x_active the
 *             active pairs per node (must be equal).
 *  margin     re-sort margin 0.05, 0.1, 0.2, 0.4 h on the moving sheet: each
 *             step ct_resort_needed, a bucket search (gap + margin) when it
 *             says so, the narrow phase over the stored candidates: cost
 *             amortised ns per node per step; accuracy the pairs within
 *             the gap missing from the stored candidates (must be 0);
 *             x_pairs_per_node, x_resorts_per_100.
 *  renumber   "off", "auto" and "fresh" (ct_search_params.renumber; fresh:
 *             auto with renumber_keep -1, a new numbering every search
 *             instead of the kept one) for the topological, bucket and
 *             bsp searches on shuffled plates (RN_TARGET secondaries,
 *             static, gap 0.3 h + margin 0.2 h): cost ns per node per
 *             search; accuracy the pairs that differ from the bucket
 *             search with renumbering off (must be 0: the renumbering
 *             returns the same list, bit for bit).
 *  dense      "off", "auto" and "on" (ct_search_params.dense) for the bsp
 *             search on the graded mesh (DN_TARGET secondaries, natural
 *             numbering, gap 0.3 h + margin 0.2 h): cost ns per node per
 *             search; accuracy the pairs that differ from the search with
 *             no dense leaf (must be 0).
 *  quad       4tri, newton, closed on the candidate pairs of the static
 *             sheet (the crumpled case, ~2 10^4 nodes, seed 12345, not
 *             moved; bucket candidates at gap 0.3 h + margin 0.2 h;
 *             two-sided, gap 0.3 h) and on random warped quads: cost ns per
 *             pair; accuracy the largest |D - D_newton| / h over the pairs
 *             (x_mean_err the mean).
 *  precision  the narrow phase (Newton) of the precision case in the
 *             binary's precision: cost ns per pair (report.py merges the
 *             double and single runs); the accuracy comes from
 *             bench/trade_precision.py on the two --dump-narrow files.
 *  assembly   colour, colour-b1, atomic, threadbuf, gather, serial on the
 *             static sheet's pairs with the most threads: cost ns per pair;
 *             accuracy the largest difference from the serial sum relative
 *             to the largest nodal force; x_bitwise_1v<T> = 1 when the
 *             result with 1 thread and with T threads are bit-identical.
 *  stiffness  Stfac 0.1, 1, 10, 100 on a linear penalty, an elastic bar of
 *             10 elements pressed by sigma on a penalty wall (K = Stfac E A
 *             / h), integrated explicitly to rest with mass-proportional
 *             damping: cost the steps per unit time 1 / dt_stable
 *             (ct_dt_nodal with the element stiffness; time unit h / c);
 *             accuracy the penetration at rest over the element
 *             deformation u = sigma h / E (seed 003: d / u = 1 / Stfac).
 *  safety     factor 0.5, 0.7, 0.9, 1.0 on two scenes, 32 phases of the
 *             contact's start against the step grid each: "mass", a mass
 *             hits a linear penalty wall with dt = factor x 2 sqrt(m / K)
 *             (the central-difference limit of a mass on a spring): cost
 *             steps per unit time sqrt(m / K), accuracy the largest
 *             |e^2 - 1| (e the restitution: the energy error after release;
 *             exact answer e = 1); "bar", the bar of the stiffness knob
 *             (undamped, Stfac 10) flies onto the wall with dt = factor x
 *             ct_dt_nodal's step: cost steps per unit time h / c, accuracy
 *             the largest |E_after / E_before - 1|.
 *
 * The moving sheet: the "crumpled" case of meshgen.h (~10^4 nodes, self
 * contact) moved by the smooth displacement field
 *   u = A s(k) (sin(w (y + z/2) + 0.3), sin(w (z + x/2) + 1.1),
 *               sin(w (x + y/2) + 2.3)),
 * w = 2 pi / (16 h), A = 1.5 h, s(k) = (1 - cos(pi k / 29)) / 2 over the
 * 30 steps k = 0..29 (the largest node displacement in a step is about
 * 0.14 h). The reference pairs of every step (direct, gap 0.3 h + margin
 * 0.2 h) are computed once. Accuracy passes run the 30 steps forward from
 * a fresh workspace (untimed); the timed loops continue the motion back and
 * forth (0..29..0), one step per iteration, so histories stay continuous.
 */
#include "bench_trade.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_topology.h"
#include "contact.h"
#include "gbench.h"
#include "meshgen.h"
#include "bench_trade_internal.h"

const char *const ctbt_asm_name[ASM_N] = {"colour", "colour-b1", "atomic",
                                            "threadbuf", "gather", "serial"};
const double ctbt_margins[4] = {0.05, 0.1, 0.2, 0.4};
const double ctbt_stfacs[4] = {0.1, 1, 10, 100};
const double ctbt_factors[4] = {0.5, 0.7, 0.9, 1.0};

static tdesc *descs;
ctb_search_config ctbt_cfg;

double ctbt_now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

const char *ctbt_prec_name(void) { return sizeof(ct_real) == 4 ? "single" : "double"; }

/* ---- Narrow-phase output buffers ---------------------------------------- */

void ctbt_geo_free(geobuf *b)
{
    for (int i = 0; i < 13; i++)
        ct_free(b->r[i]);
    ct_free(b->flag);
    memset(b, 0, sizeof *b);
}

int ctbt_geo_reserve(geobuf *b, ct_idx n)
{
    if (n <= b->cap && b->flag)
        return CT_OK;
    ctbt_geo_free(b);
    ct_idx cap = n + n / 4 + 64;
    for (int i = 0; i < 13; i++)
        if (!(b->r[i] = ct_calloc((size_t)cap, sizeof(ct_real))))
            return CT_ERR_NOMEM;
    if (!(b->flag = ct_calloc((size_t)cap, 1)))
        return CT_ERR_NOMEM;
    b->cap = cap;
    ct_contact_geo g = {b->r[0], b->r[1], b->r[2], b->r[3], b->r[4], b->r[5], b->r[6],
                        b->r[7], b->r[8], b->r[9], b->r[10], b->r[11], b->r[12], b->flag};
    b->g = g;
    return CT_OK;
}

/* Node-segment narrow phase of a pair list on the positions of in. */
int ctbt_narrow(const ct_search_input *in, const ct_pairs *p, ct_quad_method m, ct_real gap,
                geobuf *b, ct_narrow_stats *st)
{
    int rc = ctbt_geo_reserve(b, p->n);
    if (rc != CT_OK)
        return rc;
    return ct_narrow_node_segment(p->n, p->node, p->seg, in->n1, in->n2, in->n3, in->n4, in->x,
                                  in->y, in->z, NULL, NULL, gap, 0, 0, m, 1, &b->g, st);
}

/* Pairs of ref (rn pairs) missing from got; both in canonical order
 * (secondary position, then segment). *extra (may be NULL) gets the pairs
 * of got absent from ref. */
int64_t ctbt_count_missing(const ct_idx *pos, ct_idx rn, const ct_idx *rnode,
                           const ct_idx *rseg, const ct_pairs *got, int64_t *extra)
{
    int64_t a = 0, b = 0, miss = 0, more = 0;
    while (a < rn || b < got->n) {
        if (b >= got->n) {
            miss += rn - a;
            break;
        }
        if (a >= rn) {
            more += got->n - b;
            break;
        }
        ct_idx pa = pos[rnode[a]], pb = pos[got->node[b]];
        if (pa == pb && rseg[a] == got->seg[b]) {
            a++;
            b++;
        } else if (pa < pb || (pa == pb && rseg[a] < got->seg[b])) {
            miss++;
            a++;
        } else {
            more++;
            b++;
        }
    }
    if (extra)
        *extra = more;
    return miss;
}

/* ---- The moving scenes ---------------------------------------------------- */

const char *const ctbt_mv_name[MV_NSCENE] = {"crumpled", "plates"};
static const int64_t mv_target[MV_NSCENE] = {MV_TARGET, MV_TARGET_PLATES};

static movecase mvs[MV_NSCENE];

static void mv_free(movecase *m)
{
    if (m->state != 0) {
        ctd_case_destroy(&m->c);
        for (int k = 0; k < MV_STEPS; k++)
            ct_pairs_destroy(&m->ref[k]);
    }
    ct_free(m->xs);
    ct_free(m->ys);
    ct_free(m->zs);
    free(m->pos);
    memset(m, 0, sizeof *m);
}

/* The search input of step k (gap 0.3 h, margin 0.2 h unless changed). */
void ctbt_mv_input(const movecase *m, int k, ct_search_input *in)
{
    ctd_case_input(&m->c, (ct_real)(TR_GAP * m->h), (ct_real)(TR_MARGIN * m->h), in);
    size_t off = (size_t)k * (size_t)m->nnode;
    in->x = m->xs + off;
    in->y = m->ys + off;
    in->z = m->zs + off;
}

/* Step of timed iteration `it`: back and forth 0..29..1, 0..., so the
 * motion stays continuous (the forward accuracy pass ends at 29). */
int ctbt_pingpong(int64_t it)
{
    int64_t period = 2 * (MV_STEPS - 1), j = (it + MV_STEPS - 1) % period;
    return (int)(j < MV_STEPS ? j : period - j);
}

static movecase *mv_fail(movecase *m, int rc, const char *what)
{
    m->state = -1;
    snprintf(m->err, sizeof m->err, "moving %s, %s: %s", ctbt_mv_name[m->scene], what,
             ct_strerror(rc));
    return m;
}

/* Positions of step k. Sheet: every node moves by the smooth field of the
 * file's header. Plates: the secondary plate slides rigidly by
 * s(k) (3 h, 1.5 h, 0) over the fixed main plate. */
static void mv_move(movecase *m, int k, const uint8_t *is_sec)
{
    const ct_nodes *nd = &m->c.mesh.nodes;
    size_t n = (size_t)m->nnode;
    double s = 0.5 * (1.0 - cos(TR_PI * k / (MV_STEPS - 1)));
    double w = 2.0 * TR_PI / (16.0 * m->h), amp = 1.5 * m->h * s;
    for (size_t i = 0; i < n; i++) {
        double x = nd->x[i], y = nd->y[i], z = nd->z[i];
        size_t o = (size_t)k * n + i;
        if (m->scene == MV_SHEET) {
            x += amp * sin(w * (y + 0.5 * nd->z[i]) + 0.3);
            y += amp * sin(w * (nd->z[i] + 0.5 * nd->x[i]) + 1.1);
            z += amp * sin(w * (nd->x[i] + 0.5 * nd->y[i]) + 2.3);
        } else if (is_sec[i]) {
            x += 3.0 * m->h * s;
            y += 1.5 * m->h * s;
        }
        m->xs[o] = (ct_real)x;
        m->ys[o] = (ct_real)y;
        m->zs[o] = (ct_real)z;
    }
}

movecase *ctbt_mv_get(int scene)
{
    movecase *m = &mvs[scene];
    if (m->state != 0)
        return m;
    m->scene = scene;
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    ct_diag diag;
    int rc = ctd_case_make(&m->c, ctbt_mv_name[scene], mv_target[scene], CTD_NUM_NATURAL,
                           ctbt_cfg.seed, &diag);
    m->state = 1;
    if (rc != CT_OK)
        return mv_fail(m, rc, "mesh");
    m->h = m->c.h_mean;
    m->nnode = m->c.mesh.nodes.n;
    size_t n = (size_t)m->nnode, tot = n * MV_STEPS;
    m->xs = ct_calloc(tot, sizeof(ct_real));
    m->ys = ct_calloc(tot, sizeof(ct_real));
    m->zs = ct_calloc(tot, sizeof(ct_real));
    m->pos = malloc(n * sizeof *m->pos);
    uint8_t *is_sec = calloc(n, 1);
    if (!m->xs || !m->ys || !m->zs || !m->pos || !is_sec) {
        free(is_sec);
        return mv_fail(m, CT_ERR_NOMEM, "positions");
    }
    for (size_t i = 0; i < n; i++)
        m->pos[i] = -1;
    for (ct_idx i = 0; i < m->c.sec.n; i++) {
        m->pos[m->c.sec.node[i]] = i;
        is_sec[m->c.sec.node[i]] = 1;
    }
    double maxd = 0;
    for (int k = 0; k < MV_STEPS; k++) {
        mv_move(m, k, is_sec);
        for (size_t i = 0; i < n && k > 0; i++) {
            size_t o = (size_t)k * n + i;
            double dx = m->xs[o] - m->xs[o - n], dy = m->ys[o] - m->ys[o - n];
            double dz = m->zs[o] - m->zs[o - n], d = sqrt(dx * dx + dy * dy + dz * dz);
            maxd = d > maxd ? d : maxd;
        }
    }
    free(is_sec);
    m->maxstep = maxd / m->h;
    ct_search_params p = ct_search_default_params(CT_SEARCH_DIRECT);
    ct_search *s = NULL;
    rc = ct_search_init(&s, &p);
    double t0 = ctbt_now_s();
    for (int k = 0; k < MV_STEPS && rc == CT_OK; k++) {
        ct_search_input in;
        ctbt_mv_input(m, k, &in);
        rc = ct_pairs_init(&m->ref[k], 0);
        if (rc == CT_OK)
            rc = ct_search_run(s, &in, &m->ref[k]);
    }
    m->ref_s = ctbt_now_s() - t0;
    ct_search_destroy(s);
    if (rc != CT_OK)
        return mv_fail(m, rc, "direct reference");
    return m;
}

double ctbt_mv_ref_pairs(const movecase *m)
{
    double t = 0;
    for (int k = 0; k < MV_STEPS; k++)
        t += m->ref[k].n;
    return t;
}

/* ---- The static sheet (quad, precision, assembly, the dump) -------------- */
static statcase sc;

static void sc_free(statcase *s)
{
    if (s->state != 0) {
        ctd_case_destroy(&s->c);
        ct_pairs_destroy(&s->pairs);
    }
    ctbt_geo_free(&s->ref);
    memset(s, 0, sizeof *s);
}

/* The crumpled sheet of ~ST_TARGET nodes (seed ST_SEED, natural
 * numbering), its bucket candidates at gap 0.3 h + margin 0.2 h and their
 * Newton narrow phase (two-sided, gap 0.3 h). The same in every binary. */
static int sc_build(statcase *s)
{
    ct_diag diag;
    s->state = 1;
    int rc = ctd_case_make(&s->c, "crumpled", ST_TARGET, CTD_NUM_NATURAL, ST_SEED, &diag);
    if (rc == CT_OK) {
        s->h = s->c.h_mean;
        ctd_case_input(&s->c, (ct_real)(TR_GAP * s->h), (ct_real)(TR_MARGIN * s->h), &s->in);
        rc = ct_pairs_init(&s->pairs, 0);
    }
    if (rc == CT_OK) {
        ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
        ct_search *se = NULL;
        rc = ct_search_init(&se, &p);
        if (rc == CT_OK)
            rc = ct_search_run(se, &s->in, &s->pairs);
        ct_search_destroy(se);
    }
    if (rc == CT_OK)
        rc = ctbt_narrow(&s->in, &s->pairs, CT_QUAD_NEWTON, (ct_real)(TR_GAP * s->h), &s->ref,
                         NULL);
    if (rc != CT_OK) {
        s->state = -1;
        snprintf(s->err, sizeof s->err, "static sheet: %s", ct_strerror(rc));
    }
    return rc;
}

statcase *ctbt_sc_get(void)
{
    if (sc.state == 0) {
        ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
        sc_build(&sc);
    }
    return &sc;
}

/* ---- Skips and labels of every knob ------------------------------------ */

void ctbt_set_skip(gb_state *st, const char *what, int rc)
{
    char msg[400];
    snprintf(msg, sizeof msg, "%.300s: %s", what, ct_strerror(rc));
    gb_skip_with_error(st, msg);
}

void ctbt_cost_accuracy(gb_state *st, double dt, int64_t it, double n, double accuracy)
{
    gb_set_counter(st, "cost", it ? dt * 1e9 / ((double)it * n) : 0, GB_PLAIN);
    gb_set_counter(st, "accuracy", accuracy, GB_PLAIN);
}

void ctbt_label(gb_state *st, const char *knob, const char *setting, const char *cost,
                const char *acc, const char *note)
{
    char msg[800];
    snprintf(msg, sizeof msg, "knob=%s setting=%s; cost: %s; accuracy: %s; prec=%s %s", knob,
             setting, cost, acc, ctbt_prec_name(), note);
    gb_set_label(st, msg);
}

/* ---- Dispatch and registration ------------------------------------------ */

static void bm_trade(gb_state *st, void *arg)
{
    const tdesc *d = arg;
    switch (d->knob) {
    case K_SEARCH:
        ctbt_bm_search(st, d);
        break;
    case K_FILTER:
        ctbt_bm_filter(st, d);
        break;
    case K_MARGIN:
        ctbt_bm_margin(st, d);
        break;
    case K_RENUM:
    case K_DENSE:
    case K_CELL:
        ctbt_bm_static_search(st, d);
        break;
    case K_QUAD:
        ctbt_bm_quad(st, d);
        break;
    case K_PREC:
        ctbt_bm_prec(st, d);
        break;
    case K_ASM:
        ctbt_bm_asm(st, d);
        break;
    case K_STIFF:
        ctbt_bm_stiff(st, d);
        break;
    default:
        ctbt_bm_safety(st, d);
    }
}

static int add(int knob, int sub, int variant, const char *name)
{
    tdesc *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    d->knob = knob;
    d->sub = sub;
    d->variant = variant;
    d->next = descs;
    descs = d;
    char full[128];
    snprintf(full, sizeof full, "trade/%s", name);
    return gb_register(full, bm_trade, d, -1, 1, 0, 0);
}

int ctb_trade_register(const ctb_search_config *c)
{
    ctbt_cfg = *c;
    if (ctbt_cfg.max_threads < 1)
        ctbt_cfg.max_threads = 1;
    char name[96];
    int count = 0;
#define ADD(k, s, v)                                                                          \
    do {                                                                                      \
        if (add(k, s, v, name) != 0)                                                          \
            return -1;                                                                        \
        count++;                                                                              \
    } while (0)
    for (int v = 0; v < MV_NSCENE; v++)
        for (int a = 0; a < CT_SEARCH_NALGO; a++) {
            snprintf(name, sizeof name, "search/%s@%s", ct_search_algo_name((ct_search_algo)a),
                     ctbt_mv_name[v]);
            ADD(K_SEARCH, a, v);
        }
    snprintf(name, sizeof name, "filter/hull");
    ADD(K_FILTER, CT_FILTER_HULL, 0);
    snprintf(name, sizeof name, "filter/box");
    ADD(K_FILTER, CT_FILTER_BOX, 0);
    for (int i = 0; i < 4; i++) {
        snprintf(name, sizeof name, "margin/%gh", ctbt_margins[i]);
        ADD(K_MARGIN, i, 0);
    }
    for (int a = CT_SEARCH_TOPO; a <= CT_SEARCH_BSP; a++)
        for (int r = 0; r < 3; r++) {
            snprintf(name, sizeof name, "renumber/%s@%s", ctbt_renum_name(r),
                     ct_search_algo_name((ct_search_algo)a));
            ADD(K_RENUM, a, r);
        }
    for (int v = -1; v <= 1; v++) {
        snprintf(name, sizeof name, "dense/%s@graded", ctbt_dense_name(v));
        ADD(K_DENSE, 0, v);
    }
    for (int f = 0; f < CL_NFAMILY; f++)
        for (int v = 0; v < CL_NFACTOR; v++) {
            snprintf(name, sizeof name, "cells/%s@%s", ctbt_cell_name(v),
                     ctbt_cell_families[f]);
            ADD(K_CELL, f, v);
        }
    for (int v = 0; v < 2; v++)
        for (int q = 0; q < CT_QUAD_NMETHOD; q++) {
            snprintf(name, sizeof name, "quad/%s@%s", ct_quad_method_name((ct_quad_method)q),
                     v ? "warped" : "crumpled");
            ADD(K_QUAD, q, v);
        }
    snprintf(name, sizeof name, "precision/%s", ctbt_prec_name());
    ADD(K_PREC, 0, 0);
    for (int a = 0; a < ASM_N; a++) {
        snprintf(name, sizeof name, "assembly/%s", ctbt_asm_name[a]);
        ADD(K_ASM, a, 0);
    }
    for (int i = 0; i < 4; i++) {
        snprintf(name, sizeof name, "stiffness/%g", ctbt_stfacs[i]);
        ADD(K_STIFF, i, 0);
    }
    for (int v = 0; v < 2; v++)
        for (int i = 0; i < 4; i++) {
            snprintf(name, sizeof name, "safety/%g@%s", ctbt_factors[i], v ? "bar" : "mass");
            ADD(K_SAFETY, i, v);
        }
#undef ADD
    return count;
}

void ctb_trade_cleanup(void)
{
    for (int i = 0; i < MV_NSCENE; i++)
        mv_free(&mvs[i]);
    sc_free(&sc);
    ctbt_rn_free();
    ctbt_wq_free();
    ctbt_as_free();
    while (descs) {
        tdesc *n = descs->next;
        free(descs);
        descs = n;
    }
}

/* ---- bench --dump-narrow FILE --------------------------------------------- */

int ctb_trade_dump_main(int argc, char **argv)
{
    const char *path = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--dump-narrow") == 0) {
            if (i + 1 >= argc) {
                fprintf(stderr, "bench: --dump-narrow needs a file name\n");
                return 2;
            }
            path = argv[i + 1];
        } else if (strncmp(argv[i], "--dump-narrow=", 14) == 0) {
            path = argv[i] + 14;
        }
    }
    if (!path)
        return -1;
    statcase s;
    memset(&s, 0, sizeof s);
    if (sc_build(&s) != CT_OK) {
        fprintf(stderr, "bench: --dump-narrow: %s\n", s.err);
        sc_free(&s);
        return 1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        sc_free(&s);
        return 1;
    }
    const ct_contact_geo *g = &s.ref.g;
    fprintf(f, "# contact --dump-narrow: precision=%s case=crumpled target=%d seed=%u "
               "nodes=%ld pairs=%ld h=%.17g gap=%.17g method=newton two_sided=1\n",
            ctbt_prec_name(), ST_TARGET, ST_SEED, (long)s.in.nnode, (long)s.pairs.n, s.h,
            (double)(TR_GAP * s.h));
    fprintf(f, "# node seg flag dist pen nx ny nz\n");
    for (ct_idx k = 0; k < s.pairs.n; k++)
        fprintf(f, "%ld %ld %u %.17g %.17g %.17g %.17g %.17g\n", (long)s.pairs.node[k],
                (long)s.pairs.seg[k], (unsigned)g->flag[k], (double)g->dist[k],
                (double)g->pen[k], (double)g->nx[k], (double)g->ny[k], (double)g->nz[k]);
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    if (bad)
        fprintf(stderr, "bench: --dump-narrow: cannot write %s\n", path);
    else
        printf("bench: %ld pairs of the %s precision case written to %s\n", (long)s.pairs.n,
               ctbt_prec_name(), path);
    sc_free(&s);
    return bad ? 1 : 0;
}
