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

#define TR_PI 3.14159265358979323846
#define MV_STEPS 30
#define MV_TARGET 10000
#define MV_TARGET_PLATES 4000
#define ST_TARGET 20000
#define ST_SEED 12345u
#define TR_GAP 0.3    /* gap / h */
#define TR_MARGIN 0.2 /* margin / h */
#define WQ_PAIRS 100000
#define SAFETY_PHASES 32

enum { K_SEARCH, K_FILTER, K_MARGIN, K_QUAD, K_PREC, K_ASM, K_STIFF, K_SAFETY };
enum { ASM_COLOUR, ASM_COLOUR_B1, ASM_ATOMIC, ASM_THREADBUF, ASM_GATHER, ASM_SERIAL, ASM_N };
static const char *const asm_name[ASM_N] = {"colour", "colour-b1", "atomic",
                                            "threadbuf", "gather", "serial"};
static const double margins[4] = {0.05, 0.1, 0.2, 0.4};
static const double stfacs[4] = {0.1, 1, 10, 100};
static const double factors[4] = {0.5, 0.7, 0.9, 1.0};

typedef struct tdesc {
    int knob, sub, variant; /* variant: quad case 0 crumpled, 1 warped */
    struct tdesc *next;
} tdesc;

static tdesc *descs;
static ctb_search_config cfg;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static const char *prec_name(void) { return sizeof(ct_real) == 4 ? "single" : "double"; }

/* ---- Narrow-phase output buffers ---------------------------------------- */

typedef struct geobuf {
    ct_idx cap;
    ct_real *r[13];
    uint8_t *flag;
    ct_contact_geo g;
} geobuf;

static void geo_free(geobuf *b)
{
    for (int i = 0; i < 13; i++)
        ct_free(b->r[i]);
    ct_free(b->flag);
    memset(b, 0, sizeof *b);
}

static int geo_reserve(geobuf *b, ct_idx n)
{
    if (n <= b->cap && b->flag)
        return CT_OK;
    geo_free(b);
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
static int narrow(const ct_search_input *in, const ct_pairs *p, ct_quad_method m, ct_real gap,
                  geobuf *b, ct_narrow_stats *st)
{
    int rc = geo_reserve(b, p->n);
    if (rc != CT_OK)
        return rc;
    return ct_narrow_node_segment(p->n, p->node, p->seg, in->n1, in->n2, in->n3, in->n4, in->x,
                                  in->y, in->z, NULL, NULL, gap, 0, 0, m, 1, &b->g, st);
}

/* Pairs of ref (rn pairs) missing from got; both in canonical order
 * (secondary position, then segment). *extra (may be NULL) gets the pairs
 * of got absent from ref. */
static int64_t count_missing(const ct_idx *pos, ct_idx rn, const ct_idx *rnode,
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

/* MV_SHEET: the crumpled sheet in self contact (every knob of the moving
 * scenes); MV_PLATES: two plates sliding (the search knob only: a scene
 * without self contact, where the topological search's history means what
 * it was made for). */
enum { MV_SHEET, MV_PLATES, MV_NSCENE };
static const char *const mv_name[MV_NSCENE] = {"crumpled", "plates"};
static const int64_t mv_target[MV_NSCENE] = {MV_TARGET, MV_TARGET_PLATES};

typedef struct movecase {
    int state; /* 0: not built, 1: ready, -1: failed */
    int scene;
    char err[256];
    ctd_case c;
    ct_idx nnode;
    double h, maxstep;
    ct_real *xs, *ys, *zs; /* MV_STEPS * nnode positions */
    ct_pairs ref[MV_STEPS];
    ct_idx *pos;
    double ref_s;
} movecase;

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
static void mv_input(const movecase *m, int k, ct_search_input *in)
{
    ctd_case_input(&m->c, (ct_real)(TR_GAP * m->h), (ct_real)(TR_MARGIN * m->h), in);
    size_t off = (size_t)k * (size_t)m->nnode;
    in->x = m->xs + off;
    in->y = m->ys + off;
    in->z = m->zs + off;
}

/* Step of timed iteration `it`: back and forth 0..29..1, 0..., so the
 * motion stays continuous (the forward accuracy pass ends at 29). */
static int pingpong(int64_t it)
{
    int64_t period = 2 * (MV_STEPS - 1), j = (it + MV_STEPS - 1) % period;
    return (int)(j < MV_STEPS ? j : period - j);
}

static movecase *mv_fail(movecase *m, int rc, const char *what)
{
    m->state = -1;
    snprintf(m->err, sizeof m->err, "moving %s, %s: %s", mv_name[m->scene], what,
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

static movecase *mv_get(int scene)
{
    movecase *m = &mvs[scene];
    if (m->state != 0)
        return m;
    m->scene = scene;
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    ct_diag diag;
    int rc = ctd_case_make(&m->c, mv_name[scene], mv_target[scene], CTD_NUM_NATURAL, cfg.seed,
                           &diag);
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
    double t0 = now_s();
    for (int k = 0; k < MV_STEPS && rc == CT_OK; k++) {
        ct_search_input in;
        mv_input(m, k, &in);
        rc = ct_pairs_init(&m->ref[k], 0);
        if (rc == CT_OK)
            rc = ct_search_run(s, &in, &m->ref[k]);
    }
    m->ref_s = now_s() - t0;
    ct_search_destroy(s);
    if (rc != CT_OK)
        return mv_fail(m, rc, "direct reference");
    return m;
}

static double mv_ref_pairs(const movecase *m)
{
    double t = 0;
    for (int k = 0; k < MV_STEPS; k++)
        t += m->ref[k].n;
    return t;
}

/* ---- The static sheet (quad, precision, assembly, the dump) -------------- */

typedef struct statcase {
    int state;
    char err[256];
    ctd_case c;
    ct_search_input in;
    ct_pairs pairs;
    double h;
    geobuf ref; /* Newton */
} statcase;

static statcase sc;

static void sc_free(statcase *s)
{
    if (s->state != 0) {
        ctd_case_destroy(&s->c);
        ct_pairs_destroy(&s->pairs);
    }
    geo_free(&s->ref);
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
        rc = narrow(&s->in, &s->pairs, CT_QUAD_NEWTON, (ct_real)(TR_GAP * s->h), &s->ref, NULL);
    if (rc != CT_OK) {
        s->state = -1;
        snprintf(s->err, sizeof s->err, "static sheet: %s", ct_strerror(rc));
    }
    return rc;
}

static statcase *sc_get(void)
{
    if (sc.state == 0) {
        ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
        sc_build(&sc);
    }
    return &sc;
}

/* ---- Random warped quads --------------------------------------------------- */

/* WQ_PAIRS pairs, each with its own quad: the unit square's corners jittered
 * by up to 0.1 in-plane and raised alternately by +-0.15 out of plane (a
 * saddle: warped), and a node above a random point of [-0.1, 1.1]^2 at a
 * height in [-0.3, 0.3]. Nodes 5k..5k+3 are the quad, 5k+4 the node. */
static struct {
    int state;
    ct_idx npair;
    ct_real *x, *y, *z;
    ct_idx *n1, *n2, *n3, *n4, *node, *seg;
    geobuf ref;
} wq;

static void wq_free(void)
{
    ct_real *r[3] = {wq.x, wq.y, wq.z};
    ct_idx *ix[6] = {wq.n1, wq.n2, wq.n3, wq.n4, wq.node, wq.seg};
    for (int i = 0; i < 3; i++)
        ct_free(r[i]);
    for (int i = 0; i < 6; i++)
        ct_free(ix[i]);
    geo_free(&wq.ref);
    memset(&wq, 0, sizeof wq);
}

static double u01(uint64_t k, uint64_t stream)
{
    uint64_t s = cfg.seed ^ (k * 0x9E3779B97F4A7C15ull) ^ (stream << 56);
    return ctd_u01(ctd_splitmix64(&s));
}

static int wq_get(void)
{
    if (wq.state != 0)
        return wq.state > 0 ? CT_OK : CT_ERR_NOMEM;
    wq.state = -1;
    ct_idx n = WQ_PAIRS;
    wq.npair = n;
    wq.x = ct_calloc((size_t)(5 * n), sizeof(ct_real));
    wq.y = ct_calloc((size_t)(5 * n), sizeof(ct_real));
    wq.z = ct_calloc((size_t)(5 * n), sizeof(ct_real));
    wq.n1 = ct_calloc((size_t)n, sizeof(ct_idx));
    wq.n2 = ct_calloc((size_t)n, sizeof(ct_idx));
    wq.n3 = ct_calloc((size_t)n, sizeof(ct_idx));
    wq.n4 = ct_calloc((size_t)n, sizeof(ct_idx));
    wq.node = ct_calloc((size_t)n, sizeof(ct_idx));
    wq.seg = ct_calloc((size_t)n, sizeof(ct_idx));
    if (!wq.x || !wq.y || !wq.z || !wq.n1 || !wq.n2 || !wq.n3 || !wq.n4 || !wq.node ||
        !wq.seg)
        return CT_ERR_NOMEM;
    static const double cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1}, cz[4] = {1, -1, 1, -1};
    for (ct_idx k = 0; k < n; k++) {
        int64_t b = 5 * (int64_t)k;
        for (int c = 0; c < 4; c++) {
            wq.x[b + c] = (ct_real)(cx[c] + 0.2 * (u01((uint64_t)b + c, 1) - 0.5));
            wq.y[b + c] = (ct_real)(cy[c] + 0.2 * (u01((uint64_t)b + c, 2) - 0.5));
            wq.z[b + c] = (ct_real)(0.15 * cz[c]);
        }
        wq.x[b + 4] = (ct_real)(-0.1 + 1.2 * u01((uint64_t)k, 3));
        wq.y[b + 4] = (ct_real)(-0.1 + 1.2 * u01((uint64_t)k, 4));
        wq.z[b + 4] = (ct_real)(-0.3 + 0.6 * u01((uint64_t)k, 5));
        wq.n1[k] = (ct_idx)b, wq.n2[k] = (ct_idx)(b + 1);
        wq.n3[k] = (ct_idx)(b + 2), wq.n4[k] = (ct_idx)(b + 3);
        wq.node[k] = (ct_idx)(b + 4), wq.seg[k] = k;
    }
    int rc = geo_reserve(&wq.ref, n);
    if (rc == CT_OK)
        rc = ct_narrow_node_segment(n, wq.node, wq.seg, wq.n1, wq.n2, wq.n3, wq.n4, wq.x, wq.y,
                                    wq.z, NULL, NULL, (ct_real)0.3, 0, 0, CT_QUAD_NEWTON, 1,
                                    &wq.ref.g, NULL);
    if (rc == CT_OK)
        wq.state = 1;
    return rc;
}

/* ---- Knob: search algorithm --------------------------------------------- */

static void set_skip(gb_state *st, const char *what, int rc)
{
    char msg[400];
    snprintf(msg, sizeof msg, "%.300s: %s", what, ct_strerror(rc));
    gb_skip_with_error(st, msg);
}

static void label(gb_state *st, const char *knob, const char *setting, const char *cost,
                  const char *acc, const char *note)
{
    char msg[800];
    snprintf(msg, sizeof msg, "knob=%s setting=%s; cost: %s; accuracy: %s; prec=%s %s", knob,
             setting, cost, acc, prec_name(), note);
    gb_set_label(st, msg);
}

static void bm_search(gb_state *st, const tdesc *d)
{
    movecase *m = mv_get(d->variant);
    if (m->state < 0) {
        gb_skip_with_error(st, m->err);
        return;
    }
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    ct_search_algo algo = (ct_search_algo)d->sub;
    char name[64];
    snprintf(name, sizeof name, "%s@%s", ct_search_algo_name(algo), mv_name[d->variant]);
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
        found = (int64_t)mv_ref_pairs(m);
    for (int k = 0; k < MV_STEPS && rc == CT_OK && algo != CT_SEARCH_DIRECT; k++) {
        mv_input(m, k, &in);
        rc = ct_search_run(s, &in, &out);
        int64_t e = 0;
        if (rc == CT_OK)
            miss += count_missing(m->pos, m->ref[k].n, m->ref[k].node, m->ref[k].seg, &out, &e);
        extra += e;
        found += out.n;
    }
    int64_t it = 0;
    double t0 = now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        mv_input(m, pingpong(it++), &in);
        rc = ct_search_run(s, &in, &out);
    }
    double dt = now_s() - t0;
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
    if (rc != CT_OK) {
        set_skip(st, name, rc);
        return;
    }
    double nsec = m->c.sec.n;
    gb_set_counter(st, "cost", it ? dt * 1e9 / ((double)it * nsec) : 0, GB_PLAIN);
    gb_set_counter(st, "accuracy", (double)miss, GB_PLAIN);
    gb_set_counter(st, "x_extra", (double)extra, GB_PLAIN);
    gb_set_counter(st, "x_ref_pairs_per_node", mv_ref_pairs(m) / (MV_STEPS * nsec), GB_PLAIN);
    gb_set_counter(st, "x_pairs_per_node", (double)found / (MV_STEPS * nsec), GB_PLAIN);
    gb_set_counter(st, "x_ref_pairs", mv_ref_pairs(m), GB_PLAIN);
    char note[300];
    snprintf(note, sizeof note,
             "%s, %ld secondary nodes, %d steps (max node step %.2f h), a search every step, "
             "gap 0.3 h + margin 0.2 h, %d threads",
             d->variant == MV_SHEET ? "moving crumpled sheet (self contact)"
                                    : "plates sliding (secondary plate moved rigidly)",
             (long)m->c.sec.n, MV_STEPS, m->maxstep, cfg.max_threads);
    label(st, "search", name, "ns/node per search",
          "pairs missed vs direct, summed over the steps", note);
}

/* ---- Knob: search filter ------------------------------------------------- */

static void bm_filter(gb_state *st, const tdesc *d)
{
    movecase *m = mv_get(MV_SHEET);
    if (m->state < 0) {
        gb_skip_with_error(st, m->err);
        return;
    }
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
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
        mv_input(m, k, &in);
        in.filter = (ct_search_filter)d->sub;
        ct_narrow_stats ns;
        rc = ct_search_run(s, &in, &out);
        if (rc == CT_OK)
            rc = narrow(&in, &out, CT_QUAD_4TRI, gap, &gb, &ns);
        pairs += out.n;
        active += (double)ns.active;
    }
    int64_t it = 0;
    double tsearch = 0, t0 = now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        mv_input(m, pingpong(it++), &in);
        in.filter = (ct_search_filter)d->sub;
        double ta = now_s();
        rc = ct_search_run(s, &in, &out);
        tsearch += now_s() - ta;
        if (rc == CT_OK)
            rc = narrow(&in, &out, CT_QUAD_4TRI, gap, &gb, NULL);
    }
    double dt = now_s() - t0;
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
    geo_free(&gb);
    const char *name = d->sub == CT_FILTER_BOX ? "box" : "hull";
    if (rc != CT_OK) {
        set_skip(st, name, rc);
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
             (long)m->c.sec.n, cfg.max_threads);
    label(st, "filter", name, "ns/node per step (search + narrow phase)",
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
    mv_input(m, k, &in);
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
        rc = narrow(&in, cand, CT_QUAD_4TRI, in.gap, gb, NULL);
    return rc;
}

static void bm_margin(gb_state *st, const tdesc *d)
{
    movecase *m = mv_get(MV_SHEET);
    if (m->state < 0) {
        gb_skip_with_error(st, m->err);
        return;
    }
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    ct_real margin = (ct_real)(margins[d->sub] * m->h), gap = (ct_real)(TR_GAP * m->h);
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
        mv_input(m, k, &in);
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
            miss += count_missing(m->pos, within.n, within.node, within.seg, &cand, NULL);
    }
    int64_t it = 0;
    double t0 = now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        int sorted = 0;
        rc = margin_step(m, pingpong(it++), margin, s, &cand, x0, y0, z0, 0, &gb, &sorted);
    }
    double dt = now_s() - t0;
    ct_search_destroy(s);
    ct_pairs_destroy(&cand);
    ct_pairs_destroy(&within);
    geo_free(&gb);
    ct_free(x0);
    ct_free(y0);
    ct_free(z0);
    char name[32];
    snprintf(name, sizeof name, "%gh", margins[d->sub]);
    if (rc != CT_OK) {
        set_skip(st, name, rc);
        return;
    }
    double nsec = m->c.sec.n;
    gb_set_counter(st, "cost", it ? dt * 1e9 / ((double)it * nsec) : 0, GB_PLAIN);
    gb_set_counter(st, "accuracy", (double)miss, GB_PLAIN);
    gb_set_counter(st, "x_pairs_per_node", pairs / (MV_STEPS * nsec), GB_PLAIN);
    gb_set_counter(st, "x_resorts_per_100", 100.0 * (double)resorts / (MV_STEPS - 1),
                   GB_PLAIN);
    char note[300];
    snprintf(note, sizeof note,
             "each step: ct_resort_needed, bucket search (gap + margin) when needed, "
             "4-triangle narrow phase over the stored candidates; moving crumpled sheet, %ld "
             "nodes, max step %.2f h, gap 0.3 h, %d threads",
             (long)m->c.sec.n, m->maxstep, cfg.max_threads);
    label(st, "margin", name, "amortised ns/node per step",
          "pairs within the gap missing from the candidates (summed over the steps)", note);
}

/* ---- Knob: quad projection ------------------------------------------------ */

static void bm_quad(gb_state *st, const tdesc *d)
{
    ct_quad_method meth = (ct_quad_method)d->sub;
    ct_idx npair;
    const ct_idx *node, *seg, *n1, *n2, *n3, *n4;
    const ct_real *x, *y, *z;
    const geobuf *ref;
    ct_real gap;
    double h;
    char note[300];
    if (d->variant == 0) {
        statcase *s = sc_get();
        if (s->state < 0) {
            gb_skip_with_error(st, s->err);
            return;
        }
        npair = s->pairs.n, node = s->pairs.node, seg = s->pairs.seg;
        n1 = s->in.n1, n2 = s->in.n2, n3 = s->in.n3, n4 = s->in.n4;
        x = s->in.x, y = s->in.y, z = s->in.z, ref = &s->ref, h = s->h;
        gap = (ct_real)(TR_GAP * h);
        snprintf(note, sizeof note,
                 "crumpled sheet, %ld nodes, its %ld bucket candidates (gap 0.3 h + margin "
                 "0.2 h), two-sided, %d threads",
                 (long)s->c.sec.n, (long)npair, cfg.max_threads);
    } else {
        int rc = wq_get();
        if (rc != CT_OK) {
            set_skip(st, "warped quads", rc);
            return;
        }
        npair = wq.npair, node = wq.node, seg = wq.seg, n1 = wq.n1, n2 = wq.n2, n3 = wq.n3;
        n4 = wq.n4, x = wq.x, y = wq.y, z = wq.z, ref = &wq.ref, h = 1, gap = (ct_real)0.3;
        snprintf(note, sizeof note,
                 "%ld random warped unit quads (corners +-0.15 h out of plane), a node each, "
                 "two-sided, gap 0.3 h, %d threads",
                 (long)npair, cfg.max_threads);
    }
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    geobuf gb;
    memset(&gb, 0, sizeof gb);
    int rc = geo_reserve(&gb, npair);
    ct_narrow_stats ns;
    memset(&ns, 0, sizeof ns);
    if (rc == CT_OK)
        rc = ct_narrow_node_segment(npair, node, seg, n1, n2, n3, n4, x, y, z, NULL, NULL, gap, 0,
                                    0, meth, 1, &gb.g, &ns);
    double emax = 0, esum = 0;
    int64_t cnt = 0;
    for (ct_idx k = 0; k < npair && rc == CT_OK; k++) {
        if (gb.g.flag[k] & (CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE))
            continue;
        double e = fabs((double)gb.g.dist[k] - (double)ref->g.dist[k]) / h;
        emax = e > emax ? e : emax;
        esum += e;
        cnt++;
    }
    int64_t it = 0;
    double t0 = now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        rc = ct_narrow_node_segment(npair, node, seg, n1, n2, n3, n4, x, y, z, NULL, NULL, gap,
                                    0, 0, meth, 1, &gb.g, NULL);
        it++;
    }
    double dt = now_s() - t0;
    geo_free(&gb);
    char name[48];
    snprintf(name, sizeof name, "%s@%s", ct_quad_method_name(meth),
             d->variant ? "warped" : "crumpled");
    if (rc != CT_OK) {
        set_skip(st, name, rc);
        return;
    }
    gb_set_counter(st, "cost", it ? dt * 1e9 / ((double)it * npair) : 0, GB_PLAIN);
    gb_set_counter(st, "accuracy", emax, GB_PLAIN);
    gb_set_counter(st, "x_mean_err", cnt ? esum / (double)cnt : 0, GB_PLAIN);
    gb_set_counter(st, "x_active", (double)ns.active / (double)(npair ? npair : 1), GB_PLAIN);
    if (meth == CT_QUAD_NEWTON)
        gb_set_counter(st, "x_fallbacks", (double)ns.fallbacks, GB_PLAIN);
    label(st, "quad", name, "ns/pair", "max |D - D_newton| / h (x_mean_err: mean)", note);
}

/* ---- Knob: precision (cost; the accuracy is trade_precision.py's) --------- */

static void bm_prec(gb_state *st, const tdesc *d)
{
    (void)d;
    statcase *s = sc_get();
    if (s->state < 0) {
        gb_skip_with_error(st, s->err);
        return;
    }
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    geobuf gb;
    memset(&gb, 0, sizeof gb);
    ct_real gap = (ct_real)(TR_GAP * s->h);
    ct_narrow_stats ns;
    memset(&ns, 0, sizeof ns);
    int rc = narrow(&s->in, &s->pairs, CT_QUAD_NEWTON, gap, &gb, &ns); /* warm-up */
    int64_t it = 0;
    double t0 = now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        rc = narrow(&s->in, &s->pairs, CT_QUAD_NEWTON, gap, &gb, NULL);
        it++;
    }
    double dt = now_s() - t0;
    geo_free(&gb);
    if (rc != CT_OK) {
        set_skip(st, "precision", rc);
        return;
    }
    gb_set_counter(st, "cost", it ? dt * 1e9 / ((double)it * s->pairs.n) : 0, GB_PLAIN);
    gb_set_counter(st, "x_pairs", (double)s->pairs.n, GB_PLAIN);
    gb_set_counter(st, "x_fallbacks", (double)ns.fallbacks, GB_PLAIN);
    char note[300];
    snprintf(note, sizeof note,
             "Newton narrow phase of the --dump-narrow case (crumpled, %ld nodes, seed %u, %ld "
             "pairs), two-sided, %d threads",
             (long)s->c.sec.n, ST_SEED, (long)s->pairs.n, cfg.max_threads);
    label(st, "precision", prec_name(), "ns/pair",
          "max relative difference from the double run (bench/trade_precision.py)", note);
}

/* ---- Knob: assembly variant ---------------------------------------------- */

static struct {
    int state;
    ct_idx npair, nnode;
    ct_idx *s[4];
    ct_real *fx, *fy, *fz, *ser[3], *a[3], *b[3];
} as;

static void as_free(void)
{
    for (int i = 0; i < 4; i++)
        ct_free(as.s[i]);
    ct_free(as.fx);
    ct_free(as.fy);
    ct_free(as.fz);
    for (int i = 0; i < 3; i++) {
        ct_free(as.ser[i]);
        ct_free(as.a[i]);
        ct_free(as.b[i]);
    }
    memset(&as, 0, sizeof as);
}

/* Pair forces f = (0.5 + pen / gap) n for every pair of the static sheet
 * (none zero, so every node sums many terms), their slots, and the serial
 * sum. */
static int as_get(statcase *s)
{
    if (as.state != 0)
        return as.state > 0 ? CT_OK : CT_ERR_NOMEM;
    as.state = -1;
    ct_idx np = s->pairs.n, nn = s->in.nnode;
    as.npair = np;
    as.nnode = nn;
    int ok = 1;
    for (int i = 0; i < 4; i++)
        ok &= (as.s[i] = ct_calloc((size_t)np, sizeof(ct_idx))) != NULL;
    ok &= (as.fx = ct_calloc((size_t)np, sizeof(ct_real))) != NULL;
    ok &= (as.fy = ct_calloc((size_t)np, sizeof(ct_real))) != NULL;
    ok &= (as.fz = ct_calloc((size_t)np, sizeof(ct_real))) != NULL;
    for (int i = 0; i < 3; i++) {
        ok &= (as.ser[i] = ct_calloc((size_t)nn, sizeof(ct_real))) != NULL;
        ok &= (as.a[i] = ct_calloc((size_t)nn, sizeof(ct_real))) != NULL;
        ok &= (as.b[i] = ct_calloc((size_t)nn, sizeof(ct_real))) != NULL;
    }
    if (!ok)
        return CT_ERR_NOMEM;
    const ct_contact_geo *g = &s->ref.g;
    ct_real gap = (ct_real)(TR_GAP * s->h);
    for (ct_idx k = 0; k < np; k++) {
        ct_real f = (ct_real)0.5 + g->pen[k] / gap;
        as.fx[k] = f * g->nx[k];
        as.fy[k] = f * g->ny[k];
        as.fz[k] = f * g->nz[k];
    }
    int rc = ct_asm_seg_slots(np, s->pairs.seg, s->in.nseg, s->in.n1, s->in.n2, s->in.n3,
                              s->in.n4, as.s[0], as.s[1], as.s[2], as.s[3]);
    if (rc != CT_OK)
        return rc;
    ct_asm_map map = ct_asm_map_nodeseg(np, s->pairs.node, as.s[0], as.s[1], as.s[2], as.s[3]);
    const ct_real *const w[5] = {NULL, g->h1, g->h2, g->h3, g->h4};
    rc = ct_assemble_serial(&map, w, as.fx, as.fy, as.fz, nn, as.ser[0], as.ser[1], as.ser[2]);
    if (rc == CT_OK)
        as.state = 1;
    return rc;
}

static int as_run(ct_assemble_ws *ws, ct_assemble_variant v, statcase *s, ct_real *out[3])
{
    ct_asm_map map =
        ct_asm_map_nodeseg(as.npair, s->pairs.node, as.s[0], as.s[1], as.s[2], as.s[3]);
    const ct_contact_geo *g = &s->ref.g;
    const ct_real *const w[5] = {NULL, g->h1, g->h2, g->h3, g->h4};
    memset(out[0], 0, (size_t)as.nnode * sizeof(ct_real));
    memset(out[1], 0, (size_t)as.nnode * sizeof(ct_real));
    memset(out[2], 0, (size_t)as.nnode * sizeof(ct_real));
    return ct_assemble(ws, v, &map, w, as.fx, as.fy, as.fz, as.nnode, out[0], out[1], out[2]);
}

static void bm_asm(gb_state *st, const tdesc *d)
{
    statcase *s = sc_get();
    if (s->state < 0) {
        gb_skip_with_error(st, s->err);
        return;
    }
    int rc = as_get(s);
    if (rc != CT_OK) {
        set_skip(st, "assembly data", rc);
        return;
    }
    static const ct_assemble_variant var[ASM_N] = {CT_ASM_COLOUR, CT_ASM_COLOUR, CT_ASM_ATOMIC,
                                                   CT_ASM_THREADBUF, CT_ASM_GATHER,
                                                   CT_ASM_SERIAL};
    ct_assemble_variant v = var[d->sub];
    ct_assemble_ws ws;
    rc = ct_assemble_ws_init(&ws);
    if (rc != CT_OK) {
        set_skip(st, "assembly workspace", rc);
        return;
    }
    ct_asm_map map =
        ct_asm_map_nodeseg(as.npair, s->pairs.node, as.s[0], as.s[1], as.s[2], as.s[3]);
    if (d->sub == ASM_COLOUR_B1)
        rc = ct_colour_pairs(&ws, &map, as.nnode, 1);
    else
        rc = ct_assemble_prepare(&ws, v, &map, as.nnode);
    int tmax = d->sub == ASM_SERIAL ? 1 : cfg.max_threads;
    /* Accuracy: 1 thread, then the most threads; the difference from the
     * serial sum of the latter. */
    ctb_bind_threads(cfg.bind, 1, NULL, 0);
    if (rc == CT_OK)
        rc = as_run(&ws, v, s, as.a);
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    if (rc == CT_OK)
        rc = as_run(&ws, v, s, as.b);
    double dmax = 0, fmax = 0;
    int same = 1;
    for (int c = 0; c < 3 && rc == CT_OK; c++) {
        same &= memcmp(as.a[c], as.b[c], (size_t)as.nnode * sizeof(ct_real)) == 0;
        for (ct_idx i = 0; i < as.nnode; i++) {
            double e = fabs((double)as.b[c][i] - (double)as.ser[c][i]);
            double f = fabs((double)as.ser[c][i]);
            dmax = e > dmax ? e : dmax;
            fmax = f > fmax ? f : fmax;
        }
    }
    ctb_bind_threads(cfg.bind, tmax, NULL, 0);
    const ct_real *const w[5] = {NULL, s->ref.g.h1, s->ref.g.h2, s->ref.g.h3, s->ref.g.h4};
    int64_t it = 0;
    double t0 = now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        rc = ct_assemble(&ws, v, &map, w, as.fx, as.fy, as.fz, as.nnode, as.b[0], as.b[1],
                         as.b[2]);
        it++;
    }
    double dt = now_s() - t0;
    ct_idx ncol = ws.ncolour;
    ct_assemble_ws_destroy(&ws);
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    if (rc != CT_OK) {
        set_skip(st, asm_name[d->sub], rc);
        return;
    }
    char key[48], note[300];
    gb_set_counter(st, "cost", it ? dt * 1e9 / ((double)it * as.npair) : 0, GB_PLAIN);
    gb_set_counter(st, "accuracy", fmax > 0 ? dmax / fmax : 0, GB_PLAIN);
    snprintf(key, sizeof key, "x_bitwise_1v%d", cfg.max_threads);
    gb_set_counter(st, key, same, GB_PLAIN);
    if (d->sub == ASM_COLOUR || d->sub == ASM_COLOUR_B1)
        gb_set_counter(st, "x_ncolour", (double)ncol, GB_PLAIN);
    snprintf(note, sizeof note,
             "%ld pairs of the crumpled sheet (%ld nodes), 5 slots each, timed with %d "
             "thread(s); x_bitwise_1v%d: 1 thread vs %d threads bit-identical",
             (long)as.npair, (long)as.nnode, tmax, cfg.max_threads, cfg.max_threads);
    label(st, "assembly", asm_name[d->sub], "ns/pair",
          "max |F - F_serial| / max |F_serial| over nodal components", note);
}

/* ---- Knob: contact stiffness scale (1-D bar on a penalty wall) ------------ */

/*
 * An elastic bar of nel elements (E = rho = A = h = 1, so the wave speed
 * c = 1 and the time unit is h / c), node 0 on a penalty wall at x = 0 (the
 * linear law of ct_normal_force, K = Stfac E A / h, no contact damping),
 * the top node pushed down by sigma A. Lumped masses (rho A h, halved at
 * the ends), central difference at 0.9 x the stable step of ct_dt_nodal
 * (element stiffness: 2 E A / h inside, E A / h at the ends; K added at node
 * 0), mass-proportional damping c = 2 omega_1 (omega_1 = pi c / (2 L), the
 * first mode of the bar on a rigid wall), from rest at zero strain until
 * every speed is below 1e-9 sigma / (rho c). Returns CT_OK and the
 * penetration at rest, the stable step and the step count.
 */
static int bar_rest(double stfac, int nel, double sigma, double *pen, double *dtst,
                    int64_t *steps)
{
    int nn = nel + 1;
    ct_real m[64], ke[64], kc[64], u[64], v[64], f[64];
    if (nn > 64)
        return CT_ERR_ARG;
    for (int i = 0; i < nn; i++) {
        int ends = i == 0 || i == nel;
        m[i] = (ct_real)(ends ? 0.5 : 1.0);
        ke[i] = (ct_real)(ends ? 1.0 : 2.0);
        kc[i] = 0;
        u[i] = v[i] = f[i] = 0;
    }
    kc[0] = (ct_real)stfac;
    ct_real dtmin;
    ct_idx imin;
    int rc = ct_dt_nodal(nn, NULL, m, ke, kc, NULL, &dtmin, &imin);
    if (rc != CT_OK)
        return rc;
    *dtst = dtmin;
    double dt = 0.9 * dtmin, damp = 2.0 * TR_PI / (2.0 * nel);
    int64_t k = 0, kmax = 10000000;
    ct_real one = 1, zero = 0, Kc = (ct_real)stfac;
    for (; k < kmax; k++) {
        for (int i = 0; i < nn; i++)
            f[i] = 0;
        for (int e = 0; e < nel; e++) {
            ct_real nf = u[e + 1] - u[e]; /* E A strain */
            f[e] += nf;
            f[e + 1] -= nf;
        }
        f[nel] -= (ct_real)sigma;
        ct_real p = -u[0], vn = v[0], fx, fy, fz, fn;
        rc = ct_normal_force(1, &p, &one, &zero, &zero, &vn, &Kc, 0, &m[0], NULL, 0,
                             (ct_real)dt, &fx, &fy, &fz, &fn, NULL, NULL);
        if (rc != CT_OK)
            return rc;
        f[0] += fx;
        double vmax = 0;
        for (int i = 0; i < nn; i++) {
            v[i] = (ct_real)((double)v[i] + dt * ((double)f[i] / (double)m[i] - damp * v[i]));
            u[i] = (ct_real)((double)u[i] + dt * (double)v[i]);
            vmax = fabs((double)v[i]) > vmax ? fabs((double)v[i]) : vmax;
        }
        if (k > 100 && vmax < 1e-9 * sigma)
            break;
    }
    *pen = -(double)u[0];
    *steps = k;
    return k < kmax ? CT_OK : CT_ERR_NOCONV;
}

static void bm_stiff(gb_state *st, const tdesc *d)
{
    double stfac = stfacs[d->sub], sigma = 1e-3, pen = 0, dtst = 0;
    int64_t steps = 0;
    int rc = CT_OK;
    while (rc == CT_OK && gb_keep_running(st))
        rc = bar_rest(stfac, 10, sigma, &pen, &dtst, &steps);
    char name[32];
    snprintf(name, sizeof name, "%g", stfac);
    if (rc != CT_OK) {
        set_skip(st, name, rc);
        return;
    }
    double u = sigma; /* sigma h / E */
    gb_set_counter(st, "cost", 1.0 / dtst, GB_PLAIN);
    gb_set_counter(st, "accuracy", pen / u, GB_PLAIN);
    gb_set_counter(st, "x_analytic", 1.0 / stfac, GB_PLAIN);
    gb_set_counter(st, "x_dt_stable", dtst, GB_PLAIN);
    gb_set_counter(st, "x_steps_to_rest", (double)steps, GB_PLAIN);
    label(st, "stiffness", name, "steps per unit time h/c (1 / dt_stable, ct_dt_nodal)",
          "penetration at rest / element deformation sigma h / E (x_analytic: 1/Stfac)",
          "elastic bar, 10 elements, on a linear penalty wall K = Stfac E A / h, sigma = "
          "1e-3 E, central difference at 0.9 dt_stable, damped to rest");
}

/* ---- Knob: time-step safety factor ---------------------------------------- */

/*
 * Scene "mass": a mass m = 1 moving at v = -1 towards a linear penalty wall
 * K = 1 at x = 0 (ct_normal_force, no damping), central difference with
 * dt = factor x 2 sqrt(m / K) (the stability limit of the central
 * difference for a mass on a spring, omega dt <= 2). The mass starts at
 * x = (1 + phase) |v| dt, phase = j / SAFETY_PHASES, so the contact starts
 * at every point of a step. The restitution e = v_out / |v_in| after
 * release; the exact answer is e = 1, and e^2 - 1 is the relative energy
 * error. (At factor 0.5, omega dt = 1: the discrete half period is exactly
 * 3 steps, cos(Omega dt) = 1 - (omega dt)^2 / 2 = 1/2, and e = 1 for every
 * phase: a coincidence of this scene.)
 */
static int bounce_mass(double factor, double phase, double *err)
{
    ct_real one = 1, zero = 0, K = 1, ms = 1;
    double dt = factor * 2.0, x = (1.0 + phase) * dt, v = -1.0;
    for (int k = 0; k < 100000; k++) {
        ct_real p = (ct_real)(-x), vn = (ct_real)v, fx, fy, fz, fn;
        int rc = ct_normal_force(1, &p, &one, &zero, &zero, &vn, &K, 0, &ms, NULL, 0,
                                 (ct_real)dt, &fx, &fy, &fz, &fn, NULL, NULL);
        if (rc != CT_OK)
            return rc;
        v += dt * (double)fx;
        x += dt * v;
        if (x > 0 && v > 0 && k > 0) {
            *err = v * v - 1.0;
            return CT_OK;
        }
    }
    return CT_ERR_NOCONV;
}

/*
 * Scene "bar": the elastic bar of bar_rest (10 elements, E = rho = A = h =
 * 1), undamped, flying at v0 = -1e-3 c onto the penalty wall K = 10 E A / h,
 * dt = factor x the stable step of ct_dt_nodal (sqrt(2 m / (K_elem +
 * K_contact)), the minimum over nodes), node 0 starting (1 + phase) |v0| dt
 * above the wall. Out of contact the central difference conserves exactly
 * E_n = sum 1/2 m_i v_i(n - 1/2) v_i(n + 1/2) + sum_e 1/2 (E A / h) (u_e+1 -
 * u_e)^2 (positions at n); before contact E = 1/2 M v0^2. The error is
 * E / E0 - 1 at the first step out of contact after t = 200 h / c (about
 * ten contact durations 2 L / c).
 */
static int bounce_bar(double factor, double phase, double *err, double *dtst)
{
    enum { NEL = 10, NN = NEL + 1 };
    ct_real m[NN], ke[NN], kc[NN];
    double u[NN], v[NN], f[NN], vold[NN];
    for (int i = 0; i < NN; i++) {
        int ends = i == 0 || i == NEL;
        m[i] = (ct_real)(ends ? 0.5 : 1.0);
        ke[i] = (ct_real)(ends ? 1.0 : 2.0);
        kc[i] = 0;
    }
    kc[0] = 10;
    ct_real dtmin;
    ct_idx imin;
    int rc = ct_dt_nodal(NN, NULL, m, ke, kc, NULL, &dtmin, &imin);
    if (rc != CT_OK)
        return rc;
    *dtst = dtmin;
    double dt = factor * (double)dtmin, v0 = -1e-3, mtot = 0;
    for (int i = 0; i < NN; i++) {
        u[i] = (1.0 + phase) * (-v0) * dt; /* node 0's height above the wall */
        v[i] = v0;
        mtot += m[i];
    }
    double e0 = 0.5 * mtot * v0 * v0, t = 0;
    ct_real one = 1, zero = 0, Kc = kc[0];
    for (int64_t k = 0; k < 10000000; k++, t += dt) {
        for (int i = 0; i < NN; i++)
            f[i] = 0;
        double se = 0;
        for (int e = 0; e < NEL; e++) {
            double nf = u[e + 1] - u[e];
            f[e] += nf;
            f[e + 1] -= nf;
            se += 0.5 * nf * nf;
        }
        ct_real p = (ct_real)(-u[0]), vn = (ct_real)v[0], fx, fy, fz, fn;
        rc = ct_normal_force(1, &p, &one, &zero, &zero, &vn, &Kc, 0, &m[0], NULL, 0,
                             (ct_real)dt, &fx, &fy, &fz, &fn, NULL, NULL);
        if (rc != CT_OK)
            return rc;
        f[0] += (double)fx;
        double ke2 = 0;
        for (int i = 0; i < NN; i++) {
            vold[i] = v[i];
            v[i] += dt * f[i] / (double)m[i];
            ke2 += 0.5 * (double)m[i] * vold[i] * v[i];
        }
        if (t >= 200.0 && fx == 0) {
            *err = (ke2 + se) / e0 - 1.0;
            return CT_OK;
        }
        for (int i = 0; i < NN; i++)
            u[i] += dt * v[i];
    }
    return CT_ERR_NOCONV;
}

static void bm_safety(gb_state *st, const tdesc *d)
{
    double factor = factors[d->sub], emax = 0, esum = 0, dtst = 2.0;
    int rc = CT_OK;
    while (rc == CT_OK && gb_keep_running(st)) {
        emax = esum = 0;
        for (int j = 0; j < SAFETY_PHASES && rc == CT_OK; j++) {
            double err = 0, ph = (double)j / SAFETY_PHASES;
            rc = d->variant ? bounce_bar(factor, ph, &err, &dtst) : bounce_mass(factor, ph, &err);
            emax = fabs(err) > emax ? fabs(err) : emax;
            esum += err;
        }
    }
    char name[32];
    snprintf(name, sizeof name, "%g@%s", factor, d->variant ? "bar" : "mass");
    if (rc != CT_OK) {
        set_skip(st, name, rc);
        return;
    }
    gb_set_counter(st, "cost", 1.0 / (factor * dtst), GB_PLAIN);
    gb_set_counter(st, "accuracy", emax, GB_PLAIN);
    gb_set_counter(st, "x_mean_energy_err", esum / SAFETY_PHASES, GB_PLAIN);
    if (d->variant)
        label(st, "safety", name,
              "steps per unit time h/c (dt = factor x ct_dt_nodal's sqrt(2m/(K_elem+K)))",
              "max |E_after / E_before - 1| over 32 contact phases (x_mean_energy_err: mean)",
              "undamped elastic bar, 10 elements, v0 = -1e-3 c onto a linear penalty wall "
              "K = 10 E A / h, central difference, ct_normal_force");
    else
        label(st, "safety", name, "steps per unit time sqrt(m/K) (dt = factor x 2 sqrt(m/K))",
              "max |e^2 - 1| over 32 contact phases, e the restitution (x_mean_energy_err: "
              "mean)",
              "mass m on a linear penalty wall K, central difference, ct_normal_force; "
              "factor 0.5 is exact by coincidence (discrete half period = 3 steps)");
}

/* ---- Dispatch and registration ------------------------------------------ */

static void bm_trade(gb_state *st, void *arg)
{
    const tdesc *d = arg;
    switch (d->knob) {
    case K_SEARCH:
        bm_search(st, d);
        break;
    case K_FILTER:
        bm_filter(st, d);
        break;
    case K_MARGIN:
        bm_margin(st, d);
        break;
    case K_QUAD:
        bm_quad(st, d);
        break;
    case K_PREC:
        bm_prec(st, d);
        break;
    case K_ASM:
        bm_asm(st, d);
        break;
    case K_STIFF:
        bm_stiff(st, d);
        break;
    default:
        bm_safety(st, d);
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
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
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
                     mv_name[v]);
            ADD(K_SEARCH, a, v);
        }
    snprintf(name, sizeof name, "filter/hull");
    ADD(K_FILTER, CT_FILTER_HULL, 0);
    snprintf(name, sizeof name, "filter/box");
    ADD(K_FILTER, CT_FILTER_BOX, 0);
    for (int i = 0; i < 4; i++) {
        snprintf(name, sizeof name, "margin/%gh", margins[i]);
        ADD(K_MARGIN, i, 0);
    }
    for (int v = 0; v < 2; v++)
        for (int q = 0; q < CT_QUAD_NMETHOD; q++) {
            snprintf(name, sizeof name, "quad/%s@%s", ct_quad_method_name((ct_quad_method)q),
                     v ? "warped" : "crumpled");
            ADD(K_QUAD, q, v);
        }
    snprintf(name, sizeof name, "precision/%s", prec_name());
    ADD(K_PREC, 0, 0);
    for (int a = 0; a < ASM_N; a++) {
        snprintf(name, sizeof name, "assembly/%s", asm_name[a]);
        ADD(K_ASM, a, 0);
    }
    for (int i = 0; i < 4; i++) {
        snprintf(name, sizeof name, "stiffness/%g", stfacs[i]);
        ADD(K_STIFF, i, 0);
    }
    for (int v = 0; v < 2; v++)
        for (int i = 0; i < 4; i++) {
            snprintf(name, sizeof name, "safety/%g@%s", factors[i], v ? "bar" : "mass");
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
    wq_free();
    as_free();
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
            prec_name(), ST_TARGET, ST_SEED, (long)s.in.nnode, (long)s.pairs.n, s.h,
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
               prec_name(), path);
    sc_free(&s);
    return bad ? 1 : 0;
}
