/*
 * bench_elements.c -- the cost of the driver's thin shell (driver/elements/
 * shell.h), the part of a `contact run` that is not contact: on the scenes
 * of data/scenes the shells take most of the wall time.
 *
 * Names (Google Benchmark appends "/<nodes>/real_time"):
 *   elements/shell/plate/t<T>
 * at about 10^5 and 10^6 nodes, 1 thread and all threads. The mesh is a
 * square plate of unit quads (each split both ways: four triangles, and
 * eight hinges per quad inside the plate), bent out of its plane by a
 * smooth wave of amplitude 0.3 cell and stretched by 1 % so that every
 * triangle and every hinge carries a force. One iteration is one call of
 * ctd_shell_forces (the forces are added to arrays that are not cleared:
 * their values do not change the work).
 *
 * Counters: ns_per_elem (per input element and call), ns_per_node,
 * elements, triangles, hinges, threads, nodes.
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
#include "elements/shell.h"

static ctb_search_config cfg;

typedef struct edesc {
    int64_t nodes;
    int threads;
    struct edesc *next;
} edesc;

static edesc *descs;

/* The shell kept between the benchmarks of one size. */
static struct {
    int64_t nodes; /* target of the kept shell, 0: none */
    ctd_shell s;
    ct_mesh m;
    ct_real *x, *y, *z, *f[3];
    char err[160];
} sh;

static void shell_free(void)
{
    if (sh.nodes) {
        ctd_shell_destroy(&sh.s);
        ct_mesh_destroy(&sh.m);
    }
    ct_free(sh.x);
    ct_free(sh.y);
    ct_free(sh.z);
    for (int k = 0; k < 3; k++)
        ct_free(sh.f[k]);
    memset(&sh, 0, sizeof sh);
}

static int shell_get(int64_t nodes)
{
    if (sh.nodes == nodes)
        return CT_OK;
    shell_free();
    int nc = (int)floor(sqrt((double)nodes)) - 1;
    const double o[3] = {0, 0, 0};
    int rc = ctd_plate(&sh.m, nc, nc, 1.0, 1.0, o, 0);
    if (rc != CT_OK) {
        snprintf(sh.err, sizeof sh.err, "plate: %s", ct_strerror(rc));
        return rc;
    }
    const ct_nodes *nd = &sh.m.nodes;
    rc = ctd_shell_init(&sh.s, nd->n, nd->x, nd->y, nd->z, sh.m.nseg, sh.m.n1, sh.m.n2,
                        sh.m.n3, sh.m.n4, NULL, 2.1e11, 0.3, 7800, 0.05);
    if (rc != CT_OK) {
        ct_mesh_destroy(&sh.m);
        snprintf(sh.err, sizeof sh.err, "shell: %s", ct_strerror(rc));
        return rc;
    }
    sh.nodes = nodes;
    size_t n = (size_t)nd->n;
    sh.x = ct_calloc(n, sizeof(ct_real));
    sh.y = ct_calloc(n, sizeof(ct_real));
    sh.z = ct_calloc(n, sizeof(ct_real));
    for (int k = 0; k < 3; k++)
        sh.f[k] = ct_calloc(n, sizeof(ct_real));
    if (!sh.x || !sh.y || !sh.z || !sh.f[0] || !sh.f[1] || !sh.f[2]) {
        shell_free();
        snprintf(sh.err, sizeof sh.err, "out of memory");
        return CT_ERR_NOMEM;
    }
    for (size_t i = 0; i < n; i++) {
        double p = nd->x[i], q = nd->y[i];
        sh.x[i] = (ct_real)(1.01 * p);
        sh.y[i] = (ct_real)q;
        sh.z[i] = (ct_real)(0.3 * sin(0.37 * p) * cos(0.23 * q));
    }
    return CT_OK;
}

static void bm_shell(gb_state *st, void *arg)
{
    edesc *d = arg;
    char where[256], msg[400];
    if (shell_get(d->nodes) != CT_OK) {
        snprintf(msg, sizeof msg, "setup: %s", sh.err);
        gb_skip_with_error(st, msg);
        return;
    }
    ctb_bind_threads(cfg.bind, d->threads, where, sizeof where);
    /* A warm-up call, untimed (first touch of the slots by this team). */
    int rc = ctd_shell_forces(&sh.s, sh.x, sh.y, sh.z, sh.f[0], sh.f[1], sh.f[2], NULL);
    double t0 = ctb_now_s();
    while (rc == CT_OK && gb_keep_running(st))
        if ((rc = ctd_shell_forces(&sh.s, sh.x, sh.y, sh.z, sh.f[0], sh.f[1], sh.f[2], NULL)) !=
            CT_OK)
            break;
    double dt = ctb_now_s() - t0;
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "shell forces: %s", ct_strerror(rc));
        gb_skip_with_error(st, msg);
        return;
    }
    double it = (double)gb_iterations(st);
    if (!(it > 0))
        return;
    gb_set_counter(st, "ns_per_elem", dt * 1e9 / (it * (double)sh.s.nelem), GB_PLAIN);
    gb_set_counter(st, "ns_per_node", dt * 1e9 / (it * (double)sh.m.nodes.n), GB_PLAIN);
    gb_set_counter(st, "elements", (double)sh.s.nelem, GB_PLAIN);
    gb_set_counter(st, "triangles", (double)sh.s.ntri, GB_PLAIN);
    gb_set_counter(st, "hinges", (double)sh.s.nhinge, GB_PLAIN);
    gb_set_counter(st, "threads", d->threads, GB_PLAIN);
    gb_set_counter(st, "nodes", (double)sh.m.nodes.n, GB_PLAIN);
    snprintf(msg, sizeof msg, "prec=%s plate of %d quads, bent; %s",
             sizeof(ct_real) == 4 ? "single" : "double", (int)sh.s.nelem, where);
    gb_set_label(st, msg);
}

void ctb_elements_cleanup(void)
{
    shell_free();
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
    static const int64_t sizes[2] = {100000, 1000000};
    int tlist[2] = {1, cfg.max_threads};
    int nt = cfg.max_threads > 1 ? 2 : 1, count = 0;
    for (int i = 0; i < 2; i++)
        for (int t = 0; t < nt; t++) {
            edesc *d = calloc(1, sizeof *d);
            if (!d)
                return -1;
            d->nodes = sizes[i];
            d->threads = tlist[t];
            d->next = descs;
            descs = d;
            char name[64];
            snprintf(name, sizeof name, "elements/shell/plate/t%d", tlist[t]);
            if (gb_register(name, bm_shell, d, sizes[i], 1, 0, 0) != 0)
                return -1;
            count++;
        }
    return count;
}
