/*
 * bench_kernels_data.c -- the data of the kernel benchmarks (see
 * bench_kernels_data.h and the head of bench_kernels.c).
 */
#include "bench_kernels_data.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_topology.h"
#include "meshgen.h"

static ctb_search_config cfg;

void ctb_kb_data_init(const ctb_search_config *c) { cfg = *c; }

/* ---- Node-segment pair data ---------------------------------------------- */


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

static void pairs_free(void)
{
    for (int i = 0; i < nalloc; i++)
        ctb_free(allocs[i]);
    nalloc = 0;
    if (pd.ws_ready)
        ct_assemble_ws_destroy(&pd.ws);
    memset(&pd, 0, sizeof pd);
}


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

pdata *ctb_kb_pairs(int tri, int64_t want)
{
    if (pd.valid && pd.tri == tri && pd.want == want)
        return &pd;
    pairs_free();
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
    ok &= (pd.xyzw = ft_real(4 * (int64_t)pd.nnode)) != NULL;
    if (!ok) {
        fail(&pd, CT_ERR_NOMEM, "pair data");
        return &pd;
    }
    rc = ct_coords_pack(pd.nnode, pd.x, pd.y, pd.z, pd.xyzw);
    if (rc != CT_OK) {
        fail(&pd, rc, "packed coordinates");
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
int ctb_kb_force_prepare(pdata *d)
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

static ctb_kb_edges ed;

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

const ctb_kb_edges *ctb_kb_edges_get(int64_t n)
{
    if (ed.valid && ed.npair == n)
        return &ed;
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
        return ed.rc = CT_ERR_NOMEM, &ed;
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
    ed.rc = CT_OK;
    return &ed;
}


void ctb_kb_data_free(void)
{
    pairs_free();
    edge_free();
}
