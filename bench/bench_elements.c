/*
 * bench_elements.c -- the cost of the driver's thin shell (driver/elements/
 * shell.h), the part of a `contact run` that is not contact: on the scenes
 * of data/scenes the shells take most of the wall time.
 *
 * Names (Google Benchmark appends "/<nodes>/real_time"):
 *   elements/shell/plate/t<T>   at about 10^5 and 10^6 nodes
 *   elements/brick/block/t<T>   at about 10^5 nodes
 * 1 thread and all threads. The shell mesh is a square plate of unit quads
 * (each split both ways: four triangles, and eight hinges per quad inside
 * the plate), bent out of its plane by a smooth wave of amplitude 0.3 cell
 * and stretched by 1 %, so that every triangle and every hinge carries a
 * force; one iteration is one call of ctd_shell_forces. The brick mesh is
 * a cube of unit hexahedra (8 Gauss points each) under a smooth
 * displacement of 2 % of a cell; one iteration is what the solver does
 * with a brick set each cycle: ctd_brick_forces and the set's stable step.
 * The forces are added to arrays that are not cleared: their values do not
 * change the work.
 *
 * Counters: ns_per_elem (per input element and call), ns_per_node,
 * elements, triangles and hinges (shells), threads, nodes.
 */
#include "bench_elements.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "bench_topology.h"
#include "contact.h"
#include "ct_internal.h"
#include "gbench.h"
#include "meshgen.h"
#include "elements/elements.h"
#include "elements/shell.h"

static ctb_search_config cfg;

enum { EL_SHELL = 0, EL_BRICK = 1 };

typedef struct edesc {
    int kind;
    int64_t nodes;
    int threads;
    struct edesc *next;
} edesc;

static edesc *descs;

/* The elements kept between the benchmarks of one kind and size. */
static struct {
    int kind;
    int64_t nodes; /* target of the kept set, 0: none */
    ctd_shell s;
    ctd_brick b;
    ct_mesh m;
    ct_idx *hex;
    ct_idx nelem;
    ct_real *x, *y, *z, *f[3];
    char err[160];
} sh;

static void set_free(void)
{
    if (sh.nodes) {
        if (sh.kind == EL_SHELL)
            ctd_shell_destroy(&sh.s);
        else
            ctd_brick_destroy(&sh.b);
        ct_mesh_destroy(&sh.m);
    }
    ct_free(sh.hex);
    ct_free(sh.x);
    ct_free(sh.y);
    ct_free(sh.z);
    for (int k = 0; k < 3; k++)
        ct_free(sh.f[k]);
    memset(&sh, 0, sizeof sh);
}

/* The mesh and its element set (reference positions from the mesh). */
static int set_make(int kind, int64_t nodes)
{
    const double o[3] = {0, 0, 0};
    int rc;
    if (kind == EL_SHELL) {
        int nc = (int)floor(sqrt((double)nodes)) - 1;
        rc = ctd_plate(&sh.m, nc, nc, 1.0, 1.0, o, 0);
    } else {
        int nc = (int)floor(cbrt((double)nodes)) - 1;
        const double h[3] = {1, 1, 1};
        rc = ctd_block(&sh.m, nc, nc, nc, h, o, &sh.hex);
        sh.nelem = (ct_idx)nc * nc * nc;
    }
    if (rc != CT_OK) {
        snprintf(sh.err, sizeof sh.err, "mesh: %s", ct_strerror(rc));
        return rc;
    }
    const ct_nodes *nd = &sh.m.nodes;
    if (kind == EL_SHELL) {
        rc = ctd_shell_init(&sh.s, nd->n, nd->x, nd->y, nd->z, sh.m.nseg, sh.m.n1, sh.m.n2,
                            sh.m.n3, sh.m.n4, NULL, 2.1e11, 0.3, 7800, 0.05);
        sh.nelem = sh.s.nelem;
    } else {
        rc = ctd_brick_init(&sh.b, sh.nelem, sh.hex, nd->n, nd->x, nd->y, nd->z, 2.1e11, 0.3,
                            7800, NULL);
    }
    if (rc != CT_OK) {
        ct_mesh_destroy(&sh.m);
        snprintf(sh.err, sizeof sh.err, "element set: %s", ct_strerror(rc));
        return rc;
    }
    return CT_OK;
}

static int set_get(int kind, int64_t nodes)
{
    if (sh.nodes == nodes && sh.kind == kind)
        return CT_OK;
    set_free();
    int rc = set_make(kind, nodes);
    if (rc != CT_OK)
        return rc;
    sh.kind = kind;
    sh.nodes = nodes;
    const ct_nodes *nd = &sh.m.nodes;
    size_t n = (size_t)nd->n;
    sh.x = ct_calloc(n, sizeof(ct_real));
    sh.y = ct_calloc(n, sizeof(ct_real));
    sh.z = ct_calloc(n, sizeof(ct_real));
    for (int k = 0; k < 3; k++)
        sh.f[k] = ct_calloc(n, sizeof(ct_real));
    if (!sh.x || !sh.y || !sh.z || !sh.f[0] || !sh.f[1] || !sh.f[2]) {
        set_free();
        snprintf(sh.err, sizeof sh.err, "out of memory");
        return CT_ERR_NOMEM;
    }
    for (size_t i = 0; i < n; i++) {
        double p = nd->x[i], q = nd->y[i], r = nd->z[i];
        if (kind == EL_SHELL) {
            sh.x[i] = (ct_real)(1.01 * p);
            sh.y[i] = (ct_real)q;
            sh.z[i] = (ct_real)(0.3 * sin(0.37 * p) * cos(0.23 * q));
        } else {
            sh.x[i] = (ct_real)(p + 0.02 * sin(0.3 * q + 0.2 * r));
            sh.y[i] = (ct_real)(q + 0.02 * cos(0.25 * p));
            sh.z[i] = (ct_real)(r + 0.02 * sin(0.21 * p + 0.17 * q));
        }
    }
    return CT_OK;
}

/* One call: the forces, and for bricks the stable step. */
static int set_call(void)
{
    if (sh.kind == EL_SHELL)
        return ctd_shell_forces(&sh.s, sh.x, sh.y, sh.z, sh.f[0], sh.f[1], sh.f[2], NULL);
    int rc = ctd_brick_forces(&sh.b, sh.x, sh.y, sh.z, sh.f[0], sh.f[1], sh.f[2], NULL);
    if (rc == CT_OK && !(ctd_brick_dt_last(&sh.b) > 0))
        rc = CT_ERR_DEGENERATE;
    return rc;
}

static void bm_elements(gb_state *st, void *arg)
{
    edesc *d = arg;
    char where[256], msg[400];
    if (set_get(d->kind, d->nodes) != CT_OK) {
        snprintf(msg, sizeof msg, "setup: %s", sh.err);
        gb_skip_with_error(st, msg);
        return;
    }
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);
    /* A warm-up call, untimed (first touch of the slots by this team). */
    int rc = set_call();
    double t0 = ctb_now_s();
    while (rc == CT_OK && gb_keep_running(st))
        rc = set_call();
    double dt = ctb_now_s() - t0;
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "element forces: %s", ct_strerror(rc));
        gb_skip_with_error(st, msg);
        return;
    }
    double it = (double)gb_iterations(st);
    if (!(it > 0))
        return;
    gb_set_counter(st, "ns_per_elem", dt * 1e9 / (it * (double)sh.nelem), GB_PLAIN);
    gb_set_counter(st, "ns_per_node", dt * 1e9 / (it * (double)sh.m.nodes.n), GB_PLAIN);
    gb_set_counter(st, "elements", (double)sh.nelem, GB_PLAIN);
    if (d->kind == EL_SHELL) {
        gb_set_counter(st, "triangles", (double)sh.s.ntri, GB_PLAIN);
        gb_set_counter(st, "hinges", (double)sh.s.nhinge, GB_PLAIN);
    }
    gb_set_counter(st, "threads", d->threads, GB_PLAIN);
    gb_set_counter(st, "nodes", (double)sh.m.nodes.n, GB_PLAIN);
    snprintf(msg, sizeof msg, "prec=%s %s of %d %s; %s",
             sizeof(ct_real) == 4 ? "single" : "double",
             d->kind == EL_SHELL ? "plate" : "block", (int)sh.nelem,
             d->kind == EL_SHELL ? "quads, bent" : "hexahedra, strained", where);
    gb_set_label(st, msg);
}

void ctb_elements_cleanup(void)
{
    set_free();
    while (descs) {
        edesc *n = descs->next;
        free(descs);
        descs = n;
    }
}

int ctb_elements_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    static const struct {
        int kind;
        const char *name;
        int64_t nodes;
    } set[] = {{EL_SHELL, "shell/plate", 100000},
               {EL_SHELL, "shell/plate", 1000000},
               {EL_BRICK, "brick/block", 100000}};
    int tlist[2] = {1, cfg.max_threads};
    int nt = cfg.max_threads > 1 ? 2 : 1, count = 0;
    for (size_t i = 0; i < sizeof set / sizeof *set; i++)
        for (int t = 0; t < nt; t++) {
            edesc *d = calloc(1, sizeof *d);
            if (!d)
                return -1;
            d->kind = set[i].kind;
            d->nodes = set[i].nodes;
            d->threads = tlist[t];
            d->next = descs;
            descs = d;
            char name[64];
            snprintf(name, sizeof name, "elements/%s/t%d", set[i].name, tlist[t]);
            if (gb_register(name, bm_elements, d, set[i].nodes, 1, 0, 0) != 0)
                return -1;
            count++;
        }
    return count;
}
