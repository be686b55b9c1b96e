/*
 * bench_kernels.c -- the contact kernels in ns per pair (issue 3 "Figures
 * for the benchmark", issue 5 item 5), at 10^4, 10^5 and 10^6 pairs (10^7
 * with CT_BENCH_FULL), 1 thread and all threads.
 *
 * Names (Google Benchmark appends "/<pairs>/real_time"):
 *   kernels/narrow/<tri|4tri|newton|closed|edge>/t<T>
 *   kernels/force/<penalty+coulomb|penalty+coulomb-fused|type7|mu-<law>>/t<T>
 *   kernels/assemble/<colour|colour-b1|atomic|threadbuf|gather|serial>/t<T>
 *   kernels/prepare/<slots|colour|colour-b1|gather>/t<T>  (once per pair list:
 *       the segment slots, the colourings, the gather map; the thread
 *       buffers' ranges cost nothing measurable and are not listed)
 * Counters: ns_per_pair, threads, npair (and per kernel: active, fallbacks,
 * ncolour). The label starts with "prec=<double|single>" and names the
 * setting; the context gets ct_precision.
 *
 * The pairs are realistic and in node order: the plates case of meshgen.h
 * ("plates" for quads, "plates-tri" for triangles) searched by the bucket
 * search with gap 0.35 h and margin 0.15 h (the search benchmarks' distance
 * gap + margin = 0.5 h; the secondary plate lies 0.3 h above the main one,
 * so about a third of the pairs penetrate), the list cut to the wanted
 * count. The mesh size is chosen from the pairs per node (3.0 on quads, 6.0
 * on triangles). Narrow phase: one-sided, scalar gap. Forces, friction and
 * assembly use the Newton narrow-phase result of the quad case, with
 * velocities, stiffnesses and masses drawn once from a fixed seed.
 * Edge-edge: synthetic pairs of crossing edges (edge A along x, edge B along
 * y 0.2 above, random offsets so about 40% of the pairs clamp a parameter),
 * gap 0.15 per edge, the four nodes of a pair consecutive.
 *
 * Everything is built once per (mesh, pairs) outside the timed loop, copied
 * into arrays first touched by the largest team, and kept while the
 * benchmarks on it run (they are registered next to each other).
 */
#include "bench_kernels.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_eff.h"
#include "bench_topology.h"
#include "contact.h"
#include "gbench.h"
#include "meshgen.h"

enum { G_NARROW, G_EDGE, G_FORCE, G_TYPE7, G_MU, G_ASM, G_PREP };
enum { F_PENALTY_COULOMB = 0, F_PAIR_FUSED = 1 };
enum { A_COLOUR, A_COLOUR_B1, A_ATOMIC, A_THREADBUF, A_GATHER, A_SERIAL, A_N };
enum { P_SLOTS, P_COLOUR, P_COLOUR_B1, P_GATHER, P_N };
static const char *const asm_name[A_N] = {"colour", "colour-b1", "atomic",
                                          "threadbuf", "gather", "serial"};
static const char *const prep_name[P_N] = {"slots", "colour", "colour-b1", "gather"};
static const char *const law_name[CT_FRIC_NLAW] = {"coulomb", "poly", "darmstad", "renard",
                                                   "expdecay"};
/* Coefficients Fric, C1..C6 per law (each passes ct_friction_check). */
static const double law_coef[CT_FRIC_NLAW][7] = {
    {0.2, 0, 0, 0, 0, 0, 0},
    {0.2, 1e-4, 0.01, 1e-5, 1e-8, 1e-3, 0},
    {0, 1e-8, -0.1, 1e-4, -0.2, 0.2, -0.05},
    {0, 0.3, 0.2, 0.4, 0.15, 0.1, 0.5},
    {0.3, 0.2, 2.0, 0, 0, 0, 0}};

/* Physical constants of the force benchmarks. */
#define KB_VISS 0.05
#define KB_DT 1e-4
#define KB_MU0 0.2
#define KB_KT0 1e3

typedef struct kdesc {
    int group, sub;
    int64_t npair;
    int threads;
    int eff; /* 1: efficiency/<kernel>: 1 thread against `threads` (bench_eff.c) */
    struct kdesc *next;
} kdesc;

static kdesc *descs;
static ctb_search_config cfg;

/* ---- Node-segment pair data ---------------------------------------------- */

typedef struct pdata {
    int valid, rc, tri;
    char err[300];
    int64_t want;
    ct_idx npair, nnode, nseg, nsec;
    double gap;
    ct_real *x, *y, *z;
    ct_idx *n1, *n2, *n3, *n4, *node, *seg;
    ct_real *g[13]; /* dist pen nx ny nz cx cy cz h1 h2 h3 h4 gap */
    uint8_t *flag;
    ct_contact_geo geo;
    /* Force and assembly inputs (quads; made on first use). */
    int force_ready;
    ct_real *p, *nx, *ny, *nz, *vn, *vx, *vy, *vz, *K, *ms, *speed, *press, *h[4];
    ct_real *fx, *fy, *fz, *fn, *energy, *dissip, *ftx, *fty, *ftz, *fdis, *mu;
    ct_real *fel, *ktan, *ptx, *pty, *ptz;
    int32_t *flag7;
    ct_idx *s[4];
    ct_real *fxn, *fyn, *fzn;
    ct_assemble_ws ws;
    int ws_ready;
} pdata;

static pdata pd;

/* All allocations of pd and ed go through this list so one call frees them. */
#define KB_MAXALLOC 96
static void *allocs[KB_MAXALLOC];
static int nalloc;

static void *ft_alloc(size_t n, size_t size)
{
    if (nalloc >= KB_MAXALLOC)
        return NULL;
    void *p = ctb_first_touch_alloc(n, size);
    if (p)
        allocs[nalloc++] = p;
    return p;
}

static void free_all(void)
{
    for (int i = 0; i < nalloc; i++)
        ctb_free(allocs[i]);
    nalloc = 0;
    if (pd.ws_ready)
        ct_assemble_ws_destroy(&pd.ws);
    memset(&pd, 0, sizeof pd);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static const char *prec_name(void) { return sizeof(ct_real) == 4 ? "single" : "double"; }

static ct_real *ft_real(int64_t n) { return ft_alloc((size_t)n, sizeof(ct_real)); }
static ct_idx *ft_idx(int64_t n) { return ft_alloc((size_t)n, sizeof(ct_idx)); }

static int fail(pdata *d, int rc, const char *what)
{
    d->rc = rc;
    snprintf(d->err, sizeof d->err, "%s: %s", what, ct_strerror(rc));
    return rc;
}

/* Search the plates case with about `target` secondary nodes. */
static int search_case(ctd_case *c, int tri, int64_t target, ct_pairs *out, double *h)
{
    ct_diag diag;
    memset(c, 0, sizeof *c);
    int rc = ctd_case_make(c, tri ? "plates-tri" : "plates", target, CTD_NUM_NATURAL,
                           cfg.seed, &diag);
    if (rc != CT_OK)
        return rc;
    *h = c->h_mean;
    ct_search_input in;
    ctd_case_input(c, (ct_real)(0.35 * c->h_mean), (ct_real)(0.15 * c->h_mean), &in);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *s = NULL;
    rc = ct_search_init(&s, &p);
    if (rc == CT_OK)
        rc = ct_pairs_init(out, 0);
    if (rc == CT_OK)
        rc = ct_search_run(s, &in, out);
    ct_search_destroy(s);
    return rc;
}

static pdata *pairs_get(int tri, int64_t want)
{
    if (pd.valid && pd.tri == tri && pd.want == want)
        return &pd;
    free_all();
    pd.valid = 1;
    pd.tri = tri;
    pd.want = want;
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    double per_node = tri ? 6.0 : 3.0, h = 1;
    int64_t target = (int64_t)((double)want / per_node * 1.03) + 16;
    if (target < 1000)
        target = 1000;
    ctd_case c;
    ct_pairs out;
    memset(&out, 0, sizeof out);
    int rc = search_case(&c, tri, target, &out, &h);
    if (rc == CT_OK && out.n < want) { /* once more, larger */
        target = (int64_t)((double)target * (double)want / (double)(out.n + 1) * 1.05) + 16;
        ctd_case_destroy(&c);
        ct_pairs_destroy(&out);
        memset(&out, 0, sizeof out);
        rc = search_case(&c, tri, target, &out, &h);
    }
    if (rc == CT_OK && out.n < want)
        rc = CT_ERR_RANGE;
    if (rc != CT_OK) {
        ctd_case_destroy(&c);
        ct_pairs_destroy(&out);
        fail(&pd, rc, "pair list");
        return &pd;
    }
    ct_search_input in;
    ctd_case_input(&c, 0, 0, &in);
    pd.npair = (ct_idx)want;
    pd.nnode = in.nnode;
    pd.nseg = in.nseg;
    pd.nsec = in.nsec;
    pd.gap = 0.35 * h;
    pd.x = ctb_first_touch_copy_real(in.x, (size_t)in.nnode);
    pd.y = ctb_first_touch_copy_real(in.y, (size_t)in.nnode);
    pd.z = ctb_first_touch_copy_real(in.z, (size_t)in.nnode);
    pd.n1 = ctb_first_touch_copy_idx(in.n1, (size_t)in.nseg);
    pd.n2 = ctb_first_touch_copy_idx(in.n2, (size_t)in.nseg);
    pd.n3 = ctb_first_touch_copy_idx(in.n3, (size_t)in.nseg);
    pd.n4 = ctb_first_touch_copy_idx(in.n4, (size_t)in.nseg);
    pd.node = ctb_first_touch_copy_idx(out.node, (size_t)want);
    pd.seg = ctb_first_touch_copy_idx(out.seg, (size_t)want);
    void *copies[9] = {pd.x, pd.y, pd.z, pd.n1, pd.n2, pd.n3, pd.n4, pd.node, pd.seg};
    for (int i = 0; i < 9; i++)
        if (copies[i] && nalloc < KB_MAXALLOC)
            allocs[nalloc++] = copies[i];
    ctd_case_destroy(&c);
    ct_pairs_destroy(&out);
    int ok = 1;
    for (int i = 0; i < 9; i++)
        ok &= copies[i] != NULL;
    for (int i = 0; i < 13; i++)
        ok &= (pd.g[i] = ft_real(want)) != NULL;
    ok &= (pd.flag = ft_alloc((size_t)want, 1)) != NULL;
    if (!ok) {
        fail(&pd, CT_ERR_NOMEM, "pair data");
        return &pd;
    }
    ct_contact_geo g = {pd.g[0], pd.g[1], pd.g[2], pd.g[3], pd.g[4], pd.g[5], pd.g[6],
                        pd.g[7], pd.g[8], pd.g[9], pd.g[10], pd.g[11], pd.g[12], pd.flag};
    pd.geo = g;
    return &pd;
}

/* A uniform number in [0, 1) from (k, stream), fixed by the seed. */
static double u01(uint64_t k, uint64_t stream)
{
    uint64_t s = cfg.seed ^ (k * 0x9E3779B97F4A7C15ull) ^ (stream << 56);
    return ctd_u01(ctd_splitmix64(&s));
}

/* The force and assembly inputs of the quad case. */
static int force_prepare(pdata *d)
{
    if (d->force_ready)
        return d->rc;
    d->force_ready = 1;
    int64_t n = d->npair;
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    ct_real **reals[] = {&d->p, &d->nx, &d->ny, &d->nz, &d->vn, &d->vx, &d->vy, &d->vz,
                         &d->K, &d->ms, &d->speed, &d->press, &d->h[0], &d->h[1], &d->h[2],
                         &d->h[3], &d->fx, &d->fy, &d->fz, &d->fn, &d->energy, &d->dissip,
                         &d->ftx, &d->fty, &d->ftz, &d->fdis, &d->mu, &d->fel, &d->ktan,
                         &d->ptx, &d->pty, &d->ptz};
    int ok = 1;
    for (size_t i = 0; i < sizeof reals / sizeof *reals; i++)
        ok &= (*reals[i] = ft_real(n)) != NULL;
    for (int i = 0; i < 4; i++)
        ok &= (d->s[i] = ft_idx(n)) != NULL;
    ok &= (d->flag7 = ft_alloc((size_t)n, sizeof(int32_t))) != NULL;
    ok &= (d->fxn = ft_real(d->nnode)) != NULL;
    ok &= (d->fyn = ft_real(d->nnode)) != NULL;
    ok &= (d->fzn = ft_real(d->nnode)) != NULL;
    if (!ok)
        return fail(d, CT_ERR_NOMEM, "force data");
    int rc = ct_narrow_node_segment(d->npair, d->node, d->seg, d->n1, d->n2, d->n3, d->n4,
                                    d->x, d->y, d->z, NULL, NULL, (ct_real)d->gap, 0, 0,
                                    CT_QUAD_NEWTON, 0, &d->geo, NULL);
    if (rc != CT_OK)
        return fail(d, rc, "narrow phase");
    const ct_contact_geo *g = &d->geo;
    for (int64_t k = 0; k < n; k++) {
        d->p[k] = g->pen[k];
        d->nx[k] = g->nx[k];
        d->ny[k] = g->ny[k];
        d->nz[k] = g->nz[k];
        d->h[0][k] = g->h1[k];
        d->h[1][k] = g->h2[k];
        d->h[2][k] = g->h3[k];
        d->h[3][k] = g->h4[k];
        /* Relative velocity: normal part in [-1, 0.5) (mostly approaching),
         * tangential slip up to 1 in a random direction of the plane. */
        double vn = -1.0 + 1.5 * u01((uint64_t)k, 1);
        double vt = u01((uint64_t)k, 2), a = 6.283185307179586 * u01((uint64_t)k, 3);
        d->vn[k] = (ct_real)vn;
        d->vx[k] = (ct_real)(vt * cos(a) + vn * g->nx[k]);
        d->vy[k] = (ct_real)(vt * sin(a) + vn * g->ny[k]);
        d->vz[k] = (ct_real)(vn * g->nz[k]);
        d->speed[k] = (ct_real)vt;
        d->K[k] = (ct_real)(1e3 * (1.0 + u01((uint64_t)k, 4)));
        d->ms[k] = (ct_real)(1e-3 * (1.0 + u01((uint64_t)k, 5)));
    }
    rc = ct_normal_force(d->npair, d->p, d->nx, d->ny, d->nz, d->vn, d->K, 0, d->ms, NULL,
                         (ct_real)KB_VISS, (ct_real)KB_DT, d->fx, d->fy, d->fz, d->fn,
                         d->energy, d->dissip);
    if (rc != CT_OK)
        return fail(d, rc, "normal force");
    for (int64_t k = 0; k < n; k++)
        d->press[k] = d->fn[k]; /* unit contact area */
    rc = ct_asm_seg_slots(d->npair, d->seg, d->nseg, d->n1, d->n2, d->n3, d->n4, d->s[0],
                          d->s[1], d->s[2], d->s[3]);
    if (rc != CT_OK)
        return fail(d, rc, "segment slots");
    rc = ct_assemble_ws_init(&d->ws);
    if (rc != CT_OK)
        return fail(d, rc, "assembly workspace");
    d->ws_ready = 1;
    return CT_OK;
}

/* ---- Edge-edge pair data ------------------------------------------------- */

static struct {
    int valid, rc;
    int64_t npair;
    ct_idx *ea, *eb, *e1, *e2;
    ct_real *x, *y, *z, *o[14];
    uint8_t *flag;
    ct_edge_geo geo;
} ed;

static void edge_free(void)
{
    ctb_free(ed.ea);
    ctb_free(ed.eb);
    ctb_free(ed.e1);
    ctb_free(ed.e2);
    ctb_free(ed.x);
    ctb_free(ed.y);
    ctb_free(ed.z);
    for (int i = 0; i < 14; i++)
        ctb_free(ed.o[i]);
    ctb_free(ed.flag);
    memset(&ed, 0, sizeof ed);
}

static int edge_get(int64_t n)
{
    if (ed.valid && ed.npair == n)
        return ed.rc;
    edge_free();
    ed.valid = 1;
    ed.npair = n;
    ctb_bind_threads(cfg.bind, cfg.max_threads, NULL, 0);
    ed.ea = ctb_first_touch_alloc((size_t)n, sizeof(ct_idx));
    ed.eb = ctb_first_touch_alloc((size_t)n, sizeof(ct_idx));
    ed.e1 = ctb_first_touch_alloc((size_t)(2 * n), sizeof(ct_idx));
    ed.e2 = ctb_first_touch_alloc((size_t)(2 * n), sizeof(ct_idx));
    ed.x = ctb_first_touch_alloc((size_t)(4 * n), sizeof(ct_real));
    ed.y = ctb_first_touch_alloc((size_t)(4 * n), sizeof(ct_real));
    ed.z = ctb_first_touch_alloc((size_t)(4 * n), sizeof(ct_real));
    int ok = ed.ea && ed.eb && ed.e1 && ed.e2 && ed.x && ed.y && ed.z;
    for (int i = 0; i < 14; i++)
        ok &= (ed.o[i] = ctb_first_touch_alloc((size_t)n, sizeof(ct_real))) != NULL;
    ok &= (ed.flag = ctb_first_touch_alloc((size_t)n, 1)) != NULL;
    if (!ok)
        return ed.rc = CT_ERR_NOMEM;
    int64_t row = 1000;
    for (int64_t k = 0; k < n; k++) {
        double cx = 2.0 * (double)(k % row), cy = 2.0 * (double)(k / row);
        double dx = -0.9 + 1.8 * u01((uint64_t)k, 11), dy = -0.4 + 0.8 * u01((uint64_t)k, 12);
        double tz = -0.05 + 0.1 * u01((uint64_t)k, 13);
        int64_t b = 4 * k;
        /* Edge A along x through (cx, cy + dy, 0); edge B along y through
         * (cx + dx, cy, 0.2), slightly tilted. */
        ed.x[b] = (ct_real)(cx - 0.5), ed.y[b] = (ct_real)(cy + dy), ed.z[b] = (ct_real)(-tz);
        ed.x[b + 1] = (ct_real)(cx + 0.5), ed.y[b + 1] = (ct_real)(cy + dy);
        ed.z[b + 1] = (ct_real)tz;
        ed.x[b + 2] = (ct_real)(cx + dx), ed.y[b + 2] = (ct_real)(cy - 0.5);
        ed.z[b + 2] = (ct_real)(0.2 + tz);
        ed.x[b + 3] = (ct_real)(cx + dx), ed.y[b + 3] = (ct_real)(cy + 0.5);
        ed.z[b + 3] = (ct_real)(0.2 - tz);
        ed.e1[2 * k] = (ct_idx)b, ed.e2[2 * k] = (ct_idx)(b + 1);
        ed.e1[2 * k + 1] = (ct_idx)(b + 2), ed.e2[2 * k + 1] = (ct_idx)(b + 3);
        ed.ea[k] = (ct_idx)(2 * k), ed.eb[k] = (ct_idx)(2 * k + 1);
    }
    ct_edge_geo g = {ed.o[0], ed.o[1], ed.o[2], ed.o[3], ed.o[4], ed.o[5], ed.o[6], ed.o[7],
                     ed.o[8], ed.o[9], ed.o[10], ed.o[11], ed.o[12], ed.o[13], ed.flag};
    ed.geo = g;
    return ed.rc = CT_OK;
}

/* ---- The benchmark ------------------------------------------------------- */

/* The fused pair force on the same inputs and outputs as the composition
 * ct_normal_force + ct_friction_step of G_FORCE (bit-identical results). */
static int run_pair_force(const pdata *p)
{
    return ct_pair_force_linear_coulomb(p->npair, p->p, p->nx, p->ny, p->nz, p->vx, p->vy,
                                        p->vz, p->vn, p->K, 0, p->ms, NULL, (ct_real)KB_VISS,
                                        NULL, (ct_real)KB_MU0, NULL, (ct_real)KB_KT0,
                                        (ct_real)KB_DT, 1, p->fx, p->fy, p->fz, p->fn,
                                        p->energy, p->dissip, p->ftx, p->fty, p->ftz, p->fdis);
}

/* One call of the kernel of d (the timed body). stats/aux receive extras. */
static int run_once(const kdesc *d, pdata *p, ct_narrow_stats *stats)
{
    ct_asm_map map;
    switch (d->group) {
    case G_NARROW:
        return ct_narrow_node_segment(p->npair, p->node, p->seg, p->n1, p->n2, p->n3, p->n4,
                                      p->x, p->y, p->z, NULL, NULL, (ct_real)p->gap, 0, 0,
                                      d->sub < 0 ? CT_QUAD_4TRI : (ct_quad_method)d->sub, 0,
                                      &p->geo, stats);
    case G_EDGE:
        return ct_narrow_edge_edge((ct_idx)ed.npair, ed.ea, ed.eb, ed.e1, ed.e2, ed.x, ed.y,
                                   ed.z, NULL, (ct_real)0.15, 0, &ed.geo, stats);
    case G_FORCE: {
        if (d->sub == F_PAIR_FUSED)
            return run_pair_force(p);
        int rc = ct_normal_force(p->npair, p->p, p->nx, p->ny, p->nz, p->vn, p->K, 0, p->ms,
                                 NULL, (ct_real)KB_VISS, (ct_real)KB_DT, p->fx, p->fy, p->fz,
                                 p->fn, p->energy, p->dissip);
        if (rc == CT_OK)
            rc = ct_friction_step(p->npair, p->nx, p->ny, p->nz, p->vx, p->vy, p->vz, p->fn,
                                  NULL, (ct_real)KB_MU0, NULL, (ct_real)KB_KT0,
                                  (ct_real)KB_DT, 1, p->ftx, p->fty, p->ftz, p->fdis);
        return rc;
    }
    case G_TYPE7:
        return ct_penalty_type7(p->npair, p->p, p->geo.gap, p->K, p->fel, p->ktan, p->energy,
                                p->flag7);
    case G_MU: {
        ct_real coef[7];
        for (int i = 0; i < 7; i++)
            coef[i] = (ct_real)law_coef[d->sub][i];
        return ct_friction_mu(p->npair, d->sub, coef, p->press, p->speed, p->mu);
    }
    case G_ASM: {
        map = ct_asm_map_nodeseg(p->npair, p->node, p->s[0], p->s[1], p->s[2], p->s[3]);
        const ct_real *const w[5] = {NULL, p->h[0], p->h[1], p->h[2], p->h[3]};
        static const ct_assemble_variant var[A_N] = {CT_ASM_COLOUR, CT_ASM_COLOUR,
                                                     CT_ASM_ATOMIC, CT_ASM_THREADBUF,
                                                     CT_ASM_GATHER, CT_ASM_SERIAL};
        return ct_assemble(&p->ws, var[d->sub], &map, w, p->fx, p->fy, p->fz, p->nnode,
                           p->fxn, p->fyn, p->fzn);
    }
    case G_PREP:
        map = ct_asm_map_nodeseg(p->npair, p->node, p->s[0], p->s[1], p->s[2], p->s[3]);
        switch (d->sub) {
        case P_SLOTS:
            return ct_asm_seg_slots(p->npair, p->seg, p->nseg, p->n1, p->n2, p->n3, p->n4,
                                    p->s[0], p->s[1], p->s[2], p->s[3]);
        case P_COLOUR:
            return ct_colour_pairs(&p->ws, &map, p->nnode, 0);
        case P_COLOUR_B1:
            return ct_colour_pairs(&p->ws, &map, p->nnode, 1);
        default:
            return ct_gather_prepare(&p->ws, &map, p->nnode);
        }
    }
    return CT_ERR_ARG;
}

/* The efficiency rows' call (bench_eff.c). */
typedef struct eff_ctx {
    const kdesc *d;
    pdata *p;
} eff_ctx;

static int eff_call(void *arg)
{
    eff_ctx *c = arg;
    return run_once(c->d, c->p, NULL);
}

/* Untimed preparation of the assembly variant of d on p's workspace. */
static int asm_prepare(const kdesc *d, pdata *p)
{
    ct_asm_map map = ct_asm_map_nodeseg(p->npair, p->node, p->s[0], p->s[1], p->s[2], p->s[3]);
    switch (d->sub) {
    case A_COLOUR:
        return ct_colour_pairs(&p->ws, &map, p->nnode, 0);
    case A_COLOUR_B1:
        return ct_colour_pairs(&p->ws, &map, p->nnode, 1);
    case A_GATHER:
        return ct_gather_prepare(&p->ws, &map, p->nnode);
    case A_THREADBUF:
        return ct_assemble_prepare(&p->ws, CT_ASM_THREADBUF, &map, p->nnode);
    default:
        return CT_OK;
    }
}

static const char *setting(const kdesc *d, char *buf, size_t len)
{
    switch (d->group) {
    case G_NARROW:
        if (d->sub < 0)
            snprintf(buf, len, "node-triangle (plates-tri), one-sided");
        else
            snprintf(buf, len, "node-quad %s (plates), one-sided",
                     ct_quad_method_name((ct_quad_method)d->sub));
        break;
    case G_EDGE:
        snprintf(buf, len, "edge-edge, synthetic crossing edges");
        break;
    case G_FORCE:
        if (d->sub == F_PAIR_FUSED)
            snprintf(buf, len, "ct_pair_force_linear_coulomb (fused: linear, damping, Coulomb)");
        else
            snprintf(buf, len, "ct_normal_force (linear, damping) + ct_friction_step (Coulomb)");
        break;
    case G_TYPE7:
        snprintf(buf, len, "ct_penalty_type7");
        break;
    case G_MU:
        snprintf(buf, len, "ct_friction_mu %s", law_name[d->sub]);
        break;
    case G_ASM:
        snprintf(buf, len, "ct_assemble %s", asm_name[d->sub]);
        break;
    default:
        snprintf(buf, len, "prepare %s", prep_name[d->sub]);
    }
    return buf;
}

static void bm_kernel(gb_state *st, void *arg)
{
    const kdesc *d = arg;
    char where[256], msg[600], set[128];
    if ((double)d->npair * 600.0 > cfg.mem_limit) {
        gb_skip_with_error(st, "skipped: not enough memory");
        return;
    }
    pdata *p = NULL;
    ct_idx npair = (ct_idx)d->npair;
    int rc = CT_OK;
    if (d->group == G_EDGE) {
        rc = edge_get(d->npair);
    } else {
        p = pairs_get(d->group == G_NARROW && d->sub < 0, d->npair);
        rc = p->rc;
        if (rc == CT_OK && d->group != G_NARROW)
            rc = force_prepare(p);
    }
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "setup: %.200s", p ? p->err : ct_strerror(rc));
        gb_skip_with_error(st, msg);
        return;
    }
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);
    if (d->group == G_ASM)
        rc = asm_prepare(d, p);
    if (d->eff && rc == CT_OK) {
        eff_ctx c = {d, p};
        rc = ctb_eff_run(st, eff_call, &c, (double)npair, d->threads, cfg.bind, where,
                         sizeof where);
        if (rc != CT_OK) {
            snprintf(msg, sizeof msg, "%s: %s", setting(d, set, sizeof set), ct_strerror(rc));
            gb_skip_with_error(st, msg);
            return;
        }
        snprintf(msg, sizeof msg, "prec=%s %s; %ld pairs; 1 against %d threads; %s[%s]",
                 prec_name(), setting(d, set, sizeof set), (long)npair, d->threads,
                 ctb_bind_name(cfg.bind), where);
        gb_set_label(st, msg);
        return;
    }
    ct_narrow_stats stats;
    memset(&stats, 0, sizeof stats);
    if (rc == CT_OK)
        rc = run_once(d, p, &stats); /* warm-up, untimed */
    double t0 = now_s();
    while (rc == CT_OK && gb_keep_running(st))
        rc = run_once(d, p, NULL);
    double dt = now_s() - t0;
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "%s: %s", setting(d, set, sizeof set), ct_strerror(rc));
        gb_skip_with_error(st, msg);
        return;
    }
    int64_t it = gb_iterations(st);
    if (it <= 0)
        return;
    gb_set_counter(st, "ns_per_pair", dt * 1e9 / ((double)it * (double)npair), GB_PLAIN);
    gb_set_counter(st, "threads", (double)d->threads, GB_PLAIN);
    gb_set_counter(st, "npair", (double)npair, GB_PLAIN);
    char extra[160] = "";
    if (d->group == G_NARROW || d->group == G_EDGE) {
        gb_set_counter(st, "active", (double)stats.active / (double)npair, GB_PLAIN);
        if (d->group == G_NARROW && d->sub == CT_QUAD_NEWTON)
            gb_set_counter(st, "fallbacks", (double)stats.fallbacks, GB_PLAIN);
        snprintf(extra, sizeof extra, ", %.0f%% active", 100.0 * (double)stats.active / npair);
    }
    if ((d->group == G_ASM && (d->sub == A_COLOUR || d->sub == A_COLOUR_B1)) ||
        (d->group == G_PREP && (d->sub == P_COLOUR || d->sub == P_COLOUR_B1))) {
        gb_set_counter(st, "ncolour", (double)p->ws.ncolour, GB_PLAIN);
        snprintf(extra, sizeof extra, ", block %ld, %ld colours", (long)p->ws.block,
                 (long)p->ws.ncolour);
    }
    if (p)
        snprintf(msg, sizeof msg, "prec=%s %s%s; %ld pairs on %ld nodes; %s[%s]", prec_name(),
                 setting(d, set, sizeof set), extra, (long)npair, (long)p->nnode,
                 ctb_bind_name(cfg.bind), where);
    else
        snprintf(msg, sizeof msg, "prec=%s %s%s; %ld pairs; %s[%s]", prec_name(),
                 setting(d, set, sizeof set), extra, (long)npair, ctb_bind_name(cfg.bind),
                 where);
    gb_set_label(st, msg);
}

/* ---- Registration -------------------------------------------------------- */

static int add_desc(int group, int sub, const char *what, int64_t npair, int threads,
                    int eff)
{
    kdesc *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    d->group = group;
    d->sub = sub;
    d->npair = npair;
    d->threads = threads;
    d->eff = eff;
    d->next = descs;
    descs = d;
    char name[160];
    snprintf(name, sizeof name, "%s/%s/t%d", eff ? "efficiency" : "kernels", what, threads);
    /* An efficiency row is one iteration: its rounds are the measurement. */
    return gb_register(name, bm_kernel, d, npair, 1, eff ? 1 : 0, 0);
}

static int add(int group, int sub, const char *what, int64_t npair, int threads)
{
    return add_desc(group, sub, what, npair, threads, 0);
}

int ctb_kernels_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    gb_add_context("ct_precision", prec_name());
    int tlist[2] = {1, cfg.max_threads};
    int nt = cfg.max_threads > 1 ? 2 : 1;
    int64_t nmax = cfg.full ? 10000000 : 1000000;
    int count = 0;
    char what[64];
#define ADD(g, s, w)                                                                          \
    do {                                                                                      \
        for (int t = 0; t < nt; t++) {                                                        \
            if (add(g, s, w, n, tlist[t]) != 0)                                               \
                return -1;                                                                    \
            count++;                                                                          \
        }                                                                                     \
    } while (0)
    /* Size-major, so the pair data built for a size serves every kernel:
     * triangles first (their own mesh), then everything on quads, then the
     * synthetic edges. */
    for (int64_t n = 10000; n <= nmax; n *= 10) {
        ADD(G_NARROW, -1, "narrow/tri");
        for (int m = 0; m < CT_QUAD_NMETHOD; m++) {
            snprintf(what, sizeof what, "narrow/%s", ct_quad_method_name((ct_quad_method)m));
            ADD(G_NARROW, m, what);
        }
        ADD(G_FORCE, F_PENALTY_COULOMB, "force/penalty+coulomb");
        ADD(G_FORCE, F_PAIR_FUSED, "force/penalty+coulomb-fused");
        ADD(G_TYPE7, 0, "force/type7");
        for (int l = 0; l < CT_FRIC_NLAW; l++) {
            snprintf(what, sizeof what, "force/mu-%s", law_name[l]);
            ADD(G_MU, l, what);
        }
        for (int pv = 0; pv < P_N; pv++) {
            snprintf(what, sizeof what, "prepare/%s", prep_name[pv]);
            ADD(G_PREP, pv, what);
        }
        for (int a = 0; a < A_N; a++) {
            snprintf(what, sizeof what, "assemble/%s", asm_name[a]);
            if (a == A_SERIAL) { /* sequential: one thread only */
                if (add(G_ASM, a, what, n, 1) != 0)
                    return -1;
                count++;
            } else {
                ADD(G_ASM, a, what);
            }
        }
        ADD(G_EDGE, 0, "narrow/edge");
    }
#undef ADD
    /* The 2-thread efficiency target at the largest size, 1 thread against
     * all in interleaved rounds: quads first (the pairs of the last size
     * are still built), then triangles. */
    if (cfg.max_threads > 1) {
        const struct {
            int g, s;
            const char *what;
        } eff[] = {{G_NARROW, CT_QUAD_4TRI, "narrow/4tri"},
                   {G_NARROW, CT_QUAD_NEWTON, "narrow/newton"},
                   {G_FORCE, F_PAIR_FUSED, "force/penalty+coulomb-fused"},
                   {G_TYPE7, 0, "force/type7"},
                   {G_ASM, A_COLOUR, "assemble/colour"},
                   {G_NARROW, -1, "narrow/tri"}};
        for (size_t i = 0; i < sizeof eff / sizeof eff[0]; i++) {
            if (add_desc(eff[i].g, eff[i].s, eff[i].what, nmax, cfg.max_threads, 1) != 0)
                return -1;
            count++;
        }
    }
    return count;
}

void ctb_kernels_cleanup(void)
{
    free_all();
    edge_free();
    while (descs) {
        kdesc *n = descs->next;
        free(descs);
        descs = n;
    }
}
