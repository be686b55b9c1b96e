/*
 * bench_kernels.c -- the contact kernels in ns per pair (issue 3 "Figures
 * for the benchmark", issue 5 item 5), at 10^4, 10^5 and 10^6 pairs (10^7
 * with CT_BENCH_FULL), 1 thread and all threads.
 *
 * Names (Google Benchmark appends "/<pairs>/real_time"):
 *   kernels/narrow/<tri|4tri|newton|closed|edge>/t<T>
 *   kernels/narrow/<tri|4tri|newton>-packed/t<T>  (the same pairs from packed
 *       coordinates, ct_narrow_node_segment_packed; the pack, a pass over the
 *       nodes once per step in a code, is not in the timed call: its cost is
 *       the counters pack_ns_per_node and pack_ns_per_pair, the latter at
 *       this benchmark's 1.4-2.9 pairs per node)
 *   kernels/force/<penalty+coulomb|penalty+coulomb-fused|type7|mu-<law>>/t<T>
 *   kernels/assemble/<colour|colour-b1|atomic|threadbuf|gather|serial>/t<T>
 *   kernels/prepare/<slots|colour|colour-b1|gather>/t<T>  (once per pair list:
 *       the segment slots, the colourings, the gather map; the thread
 *       buffers' ranges cost nothing measurable and are not listed)
 * Counters: ns_per_pair, threads, npair; bytes_per_pair and
 * stream_bytes_per_pair (the byte model of floor.h for the call's arrays,
 * and for its per-pair arrays alone: the report divides them by the triad
 * bandwidth of the same thread count); per kernel: active, fallbacks,
 * ncolour. The label starts with "prec=<double|single>" and names the
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

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "bench_eff.h"
#include "bench_kernels_data.h"
#include "bench_topology.h"
#include "contact.h"
#include "floor.h"
#include "gbench.h"
#include "meshgen.h"

enum { G_NARROW, G_NARROW_PACKED, G_EDGE, G_FORCE, G_TYPE7, G_MU, G_ASM, G_PREP };
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

typedef struct kdesc {
    int group, sub;
    int64_t npair;
    int threads;
    int eff; /* 1: efficiency/<kernel>: 1 thread against `threads` (bench_eff.c) */
    struct kdesc *next;
} kdesc;

static kdesc *descs;
static ctb_search_config cfg;

static const char *prec_name(void) { return sizeof(ct_real) == 4 ? "single" : "double"; }

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
    case G_NARROW_PACKED:
        return ct_narrow_node_segment_packed(
            p->npair, p->node, p->seg, p->n1, p->n2, p->n3, p->n4, p->xyzw, NULL, NULL,
            (ct_real)p->gap, 0, 0, d->sub < 0 ? CT_QUAD_4TRI : (ct_quad_method)d->sub, 0, &p->geo,
            stats);
    case G_EDGE:
    {
        const ctb_kb_edges *e = ctb_kb_edges_get(d->npair);
        return ct_narrow_edge_edge((ct_idx)e->npair, e->ea, e->eb, e->e1, e->e2, e->x, e->y,
                                   e->z, NULL, (ct_real)0.15, 0, &e->geo, stats);
    }
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

/* The arrays the call of d reads and writes (floor.h): 0 when d has no
 * floor (the colourings' and the gather map's preparation, whose work is a
 * sort, not a stream). */
static int kernel_streams(const kdesc *d, ctb_kernel_streams *s)
{
    memset(s, 0, sizeof *s);
    switch (d->group) {
    case G_NARROW: /* node, seg; the 13 results and the flag; n1..n4; x, y, z */
        *s = (ctb_kernel_streams){.pair_idx_in = 2, .pair_real_out = 13, .pair_b1_out = 1,
                                  .seg_idx_in = 4, .node_real_in = 3};
        return 1;
    case G_NARROW_PACKED: /* the same, x, y, z, w in one array */
        *s = (ctb_kernel_streams){.pair_idx_in = 2, .pair_real_out = 13, .pair_b1_out = 1,
                                  .seg_idx_in = 4, .node_real_in = 4};
        return 1;
    case G_EDGE: /* ea, eb; the 14 results and the flag; e1, e2; x, y, z */
        *s = (ctb_kernel_streams){.pair_idx_in = 2, .pair_real_out = 14, .pair_b1_out = 1,
                                  .seg_idx_in = 2, .node_real_in = 3};
        return 1;
    case G_FORCE:
        if (d->sub == F_PAIR_FUSED) {
            /* In: p, n (3), v (3), vn, K, ms, the tangential force (3); out:
             * the normal force (3), fn, energy, damping work, the tangential
             * force (3), friction work. */
            s->pair_real_in = 13;
            s->pair_real_out = 10;
        } else {
            /* ct_normal_force: in p, n, vn, K, ms; out f, fn, energy, damping
             * work. ct_friction_step: in n, v, fn, the tangential force;
             * out the tangential force, friction work. */
            s->pair_real_in = 7 + 10;
            s->pair_real_out = 6 + 4;
        }
        return 1;
    case G_TYPE7: /* in p, gap, K; out force, tangent, energy, flag */
        *s = (ctb_kernel_streams){.pair_real_in = 3, .pair_real_out = 3, .pair_b4_out = 1};
        return 1;
    case G_MU: /* mu out; pressure and speed in as the law uses them */
        s->pair_real_out = 1;
        s->pair_real_in = d->sub == CT_FRIC_COULOMB                                  ? 0
                          : (d->sub == CT_FRIC_POLY || d->sub == CT_FRIC_DARMSTAD) ? 2
                                                                                   : 1;
        return 1;
    case G_ASM: /* node, s1..s4; f (3), h1..h4; the nodal forces read and written */
        *s = (ctb_kernel_streams){.pair_idx_in = 5, .pair_real_in = 7, .node_real_in = 3,
                                  .node_real_out = 3};
        return 1;
    default:
        if (d->sub != P_SLOTS)
            return 0;
        /* seg in; n1..n4 per segment; s1..s4 out */
        *s = (ctb_kernel_streams){.pair_idx_in = 1, .pair_idx_out = 4, .seg_idx_in = 4};
        return 1;
    }
}

/* The floor's bytes of one call of d over npair pairs of p (-1: none);
 * with pairs_only, of its per-pair arrays alone. */
static double kernel_bytes(const kdesc *d, const pdata *p, int64_t npair, int pairs_only)
{
    ctb_kernel_streams s;
    if (!kernel_streams(d, &s))
        return -1;
    if (pairs_only)
        return ctb_floor_kernel_bytes(&s, npair, 0, 0, sizeof(ct_real), sizeof(ct_idx));
    int64_t nseg = 0, nnode = 0;
    if (d->group == G_EDGE) { /* each pair its own two edges and four nodes */
        nseg = 2 * npair;
        nnode = 4 * npair;
    } else if (d->group == G_NARROW || d->group == G_NARROW_PACKED || d->group == G_ASM ||
               d->group == G_PREP) {
        if (ctb_floor_pairs_touched(p->nnode, p->nseg, npair, p->node, p->seg, p->n1, p->n2,
                                    p->n3, p->n4, &nseg, &nnode) != 0)
            return -1;
    }
    return ctb_floor_kernel_bytes(&s, npair, nseg, nnode, sizeof(ct_real), sizeof(ct_idx));
}

static const char *setting(const kdesc *d, char *buf, size_t len)
{
    switch (d->group) {
    case G_NARROW:
    case G_NARROW_PACKED:
        if (d->sub < 0)
            snprintf(buf, len, "node-triangle (plates-tri), one-sided%s",
                     d->group == G_NARROW_PACKED ? ", packed coordinates" : "");
        else
            snprintf(buf, len, "node-quad %s (plates), one-sided%s",
                     ct_quad_method_name((ct_quad_method)d->sub),
                     d->group == G_NARROW_PACKED ? ", packed coordinates" : "");
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
        rc = ctb_kb_edges_get(d->npair)->rc;
    } else {
        const int narrow = d->group == G_NARROW || d->group == G_NARROW_PACKED;
        p = ctb_kb_pairs(narrow && d->sub < 0, d->npair);
        rc = p->rc;
        if (rc == CT_OK && !narrow)
            rc = ctb_kb_force_prepare(p);
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
    double t0 = ctb_now_s();
    while (rc == CT_OK && gb_keep_running(st))
        rc = run_once(d, p, NULL);
    double dt = ctb_now_s() - t0;
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
    double bytes = kernel_bytes(d, p, npair, 0), sbytes = kernel_bytes(d, p, npair, 1);
    if (bytes > 0 && sbytes > 0) {
        gb_set_counter(st, "bytes_per_pair", bytes / (double)npair, GB_PLAIN);
        gb_set_counter(st, "stream_bytes_per_pair", sbytes / (double)npair, GB_PLAIN);
    }
    char extra[160] = "";
    if (d->group == G_NARROW_PACKED) {
        /* The pack: rounds of calls over about 10 ms, after the timed loop. */
        const ct_idx nn = p->nnode;
        int64_t calls = 0;
        double p0 = ctb_now_s(), pt = 0;
        do {
            rc = ct_coords_pack(nn, p->x, p->y, p->z, p->xyzw);
            calls++;
            pt = ctb_now_s() - p0;
        } while (rc == CT_OK && pt < 0.01);
        gb_set_counter(st, "pack_ns_per_node", pt * 1e9 / ((double)calls * (double)nn),
                       GB_PLAIN);
        gb_set_counter(st, "pack_ns_per_pair", pt * 1e9 / ((double)calls * (double)npair),
                       GB_PLAIN);
    }
    if (d->group == G_NARROW || d->group == G_NARROW_PACKED || d->group == G_EDGE) {
        gb_set_counter(st, "active", (double)stats.active / (double)npair, GB_PLAIN);
        if (d->group != G_EDGE && d->sub == CT_QUAD_NEWTON)
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
    ctb_kb_data_init(c);
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
        ADD(G_NARROW_PACKED, -1, "narrow/tri-packed");
        for (int m = 0; m < CT_QUAD_NMETHOD; m++) {
            snprintf(what, sizeof what, "narrow/%s", ct_quad_method_name((ct_quad_method)m));
            ADD(G_NARROW, m, what);
            if (m == CT_QUAD_CLOSED)
                continue;
            snprintf(what, sizeof what, "narrow/%s-packed",
                     ct_quad_method_name((ct_quad_method)m));
            ADD(G_NARROW_PACKED, m, what);
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
    ctb_kb_data_free();
    while (descs) {
        kdesc *n = descs->next;
        free(descs);
        descs = n;
    }
}

