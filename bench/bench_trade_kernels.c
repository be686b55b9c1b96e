/*
 * bench_trade_kernels.c -- the kernel-side knobs of the speed/accuracy trade
 * (see bench_trade.c for what each measures): the quad projection (on the
 * static sheet and on random warped quads), the precision and the assembly
 * variant.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_trade_internal.h"

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

void ctbt_wq_free(void)
{
    ct_real *r[3] = {wq.x, wq.y, wq.z};
    ct_idx *ix[6] = {wq.n1, wq.n2, wq.n3, wq.n4, wq.node, wq.seg};
    for (int i = 0; i < 3; i++)
        ct_free(r[i]);
    for (int i = 0; i < 6; i++)
        ct_free(ix[i]);
    ctbt_geo_free(&wq.ref);
    memset(&wq, 0, sizeof wq);
}

static double u01(uint64_t k, uint64_t stream)
{
    uint64_t s = ctbt_cfg.seed ^ (k * 0x9E3779B97F4A7C15ull) ^ (stream << 56);
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
    int rc = ctbt_geo_reserve(&wq.ref, n);
    if (rc == CT_OK)
        rc = ct_narrow_node_segment(n, wq.node, wq.seg, wq.n1, wq.n2, wq.n3, wq.n4, wq.x, wq.y,
                                    wq.z, NULL, NULL, (ct_real)0.3, 0, 0, CT_QUAD_NEWTON, 1,
                                    &wq.ref.g, NULL);
    if (rc == CT_OK)
        wq.state = 1;
    return rc;
}

/* ---- Knob: quad projection ------------------------------------------------ */

void ctbt_bm_quad(gb_state *st, const tdesc *d)
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
        statcase *s = ctbt_sc_get();
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
                 (long)s->c.sec.n, (long)npair, ctbt_cfg.max_threads);
    } else {
        int rc = wq_get();
        if (rc != CT_OK) {
            ctbt_set_skip(st, "warped quads", rc);
            return;
        }
        npair = wq.npair, node = wq.node, seg = wq.seg, n1 = wq.n1, n2 = wq.n2, n3 = wq.n3;
        n4 = wq.n4, x = wq.x, y = wq.y, z = wq.z, ref = &wq.ref, h = 1, gap = (ct_real)0.3;
        snprintf(note, sizeof note,
                 "%ld random warped unit quads (corners +-0.15 h out of plane), a node each, "
                 "two-sided, gap 0.3 h, %d threads",
                 (long)npair, ctbt_cfg.max_threads);
    }
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    geobuf gb;
    memset(&gb, 0, sizeof gb);
    int rc = ctbt_geo_reserve(&gb, npair);
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
    double t0 = ctbt_now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        rc = ct_narrow_node_segment(npair, node, seg, n1, n2, n3, n4, x, y, z, NULL, NULL, gap,
                                    0, 0, meth, 1, &gb.g, NULL);
        it++;
    }
    double dt = ctbt_now_s() - t0;
    ctbt_geo_free(&gb);
    char name[48];
    snprintf(name, sizeof name, "%s@%s", ct_quad_method_name(meth),
             d->variant ? "warped" : "crumpled");
    if (rc != CT_OK) {
        ctbt_set_skip(st, name, rc);
        return;
    }
    ctbt_cost_accuracy(st, dt, it, (double)npair, emax);
    gb_set_counter(st, "x_mean_err", cnt ? esum / (double)cnt : 0, GB_PLAIN);
    gb_set_counter(st, "x_active", (double)ns.active / (double)(npair ? npair : 1), GB_PLAIN);
    if (meth == CT_QUAD_NEWTON)
        gb_set_counter(st, "x_fallbacks", (double)ns.fallbacks, GB_PLAIN);
    ctbt_label(st, "quad", name, "ns/pair", "max |D - D_newton| / h (x_mean_err: mean)", note);
}

/* ---- Knob: precision (cost; the accuracy is trade_precision.py's) --------- */

void ctbt_bm_prec(gb_state *st, const tdesc *d)
{
    (void)d;
    statcase *s = ctbt_sc_get();
    if (s->state < 0) {
        gb_skip_with_error(st, s->err);
        return;
    }
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    geobuf gb;
    memset(&gb, 0, sizeof gb);
    ct_real gap = (ct_real)(TR_GAP * s->h);
    ct_narrow_stats ns;
    memset(&ns, 0, sizeof ns);
    int rc = ctbt_narrow(&s->in, &s->pairs, CT_QUAD_NEWTON, gap, &gb, &ns); /* warm-up */
    int64_t it = 0;
    double t0 = ctbt_now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        rc = ctbt_narrow(&s->in, &s->pairs, CT_QUAD_NEWTON, gap, &gb, NULL);
        it++;
    }
    double dt = ctbt_now_s() - t0;
    ctbt_geo_free(&gb);
    if (rc != CT_OK) {
        ctbt_set_skip(st, "precision", rc);
        return;
    }
    gb_set_counter(st, "cost", it ? dt * 1e9 / ((double)it * s->pairs.n) : 0, GB_PLAIN);
    gb_set_counter(st, "x_pairs", (double)s->pairs.n, GB_PLAIN);
    gb_set_counter(st, "x_fallbacks", (double)ns.fallbacks, GB_PLAIN);
    char note[300];
    snprintf(note, sizeof note,
             "Newton narrow phase of the --dump-narrow case (crumpled, %ld nodes, seed %u, %ld "
             "pairs), two-sided, %d threads",
             (long)s->c.sec.n, ST_SEED, (long)s->pairs.n, ctbt_cfg.max_threads);
    ctbt_label(st, "precision", ctbt_prec_name(), "ns/pair",
               "max relative difference from the double run (bench/trade_precision.py)", note);
}

/* ---- Knob: assembly variant ---------------------------------------------- */

static struct {
    int state;
    ct_idx npair, nnode;
    ct_idx *s[4];
    ct_real *fx, *fy, *fz, *ser[3], *a[3], *b[3];
} as;

void ctbt_as_free(void)
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

void ctbt_bm_asm(gb_state *st, const tdesc *d)
{
    statcase *s = ctbt_sc_get();
    if (s->state < 0) {
        gb_skip_with_error(st, s->err);
        return;
    }
    int rc = as_get(s);
    if (rc != CT_OK) {
        ctbt_set_skip(st, "assembly data", rc);
        return;
    }
    static const ct_assemble_variant var[ASM_N] = {CT_ASM_COLOUR, CT_ASM_COLOUR, CT_ASM_ATOMIC,
                                                   CT_ASM_THREADBUF, CT_ASM_GATHER,
                                                   CT_ASM_SERIAL};
    ct_assemble_variant v = var[d->sub];
    ct_assemble_ws ws;
    rc = ct_assemble_ws_init(&ws);
    if (rc != CT_OK) {
        ctbt_set_skip(st, "assembly workspace", rc);
        return;
    }
    ct_asm_map map =
        ct_asm_map_nodeseg(as.npair, s->pairs.node, as.s[0], as.s[1], as.s[2], as.s[3]);
    if (d->sub == ASM_COLOUR_B1)
        rc = ct_colour_pairs(&ws, &map, as.nnode, 1);
    else
        rc = ct_assemble_prepare(&ws, v, &map, as.nnode);
    int tmax = d->sub == ASM_SERIAL ? 1 : ctbt_cfg.max_threads;
    /* Accuracy: 1 thread, then the most threads; the difference from the
     * serial sum of the latter. */
    ctb_bind_threads(ctbt_cfg.bind, 1, NULL, 0);
    if (rc == CT_OK)
        rc = as_run(&ws, v, s, as.a);
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
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
    ctb_bind_threads(ctbt_cfg.bind, tmax, NULL, 0);
    const ct_real *const w[5] = {NULL, s->ref.g.h1, s->ref.g.h2, s->ref.g.h3, s->ref.g.h4};
    int64_t it = 0;
    double t0 = ctbt_now_s();
    while (rc == CT_OK && gb_keep_running(st)) {
        rc = ct_assemble(&ws, v, &map, w, as.fx, as.fy, as.fz, as.nnode, as.b[0], as.b[1],
                         as.b[2]);
        it++;
    }
    double dt = ctbt_now_s() - t0;
    ct_idx ncol = ws.ncolour;
    ct_assemble_ws_destroy(&ws);
    ctb_bind_threads(ctbt_cfg.bind, ctbt_cfg.max_threads, NULL, 0);
    if (rc != CT_OK) {
        ctbt_set_skip(st, ctbt_asm_name[d->sub], rc);
        return;
    }
    char key[48], note[300];
    ctbt_cost_accuracy(st, dt, it, (double)as.npair, fmax > 0 ? dmax / fmax : 0);
    snprintf(key, sizeof key, "x_bitwise_1v%d", ctbt_cfg.max_threads);
    gb_set_counter(st, key, same, GB_PLAIN);
    if (d->sub == ASM_COLOUR || d->sub == ASM_COLOUR_B1)
        gb_set_counter(st, "x_ncolour", (double)ncol, GB_PLAIN);
    snprintf(note, sizeof note,
             "%ld pairs of the crumpled sheet (%ld nodes), 5 slots each, timed with %d "
             "thread(s); x_bitwise_1v%d: 1 thread vs %d threads bit-identical",
             (long)as.npair, (long)as.nnode, tmax, ctbt_cfg.max_threads, ctbt_cfg.max_threads);
    ctbt_label(st, "assembly", ctbt_asm_name[d->sub], "ns/pair",
               "max |F - F_serial| / max |F_serial| over nodal components", note);
}
