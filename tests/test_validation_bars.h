/*
 * test_validation_bars.h -- what the validation cases of the group "bars"
 * (suites validation_bars and validation_patch: bar impact, the patch
 * test, the meaning of the penalty) share: loading a scene file of
 * tests/data/validation, changing it before the model is built, running
 * it with an observer, and a few small measures over node sets.
 */
#ifndef TEST_VALIDATION_BARS_H
#define TEST_VALIDATION_BARS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "solver.h"
#include "solver_internal.h"
#include "test_util.h"
#include "test_validation.h"

/* One run: the scene (editable between vb_load and vb_start), its model
 * and the solver. */
typedef struct vb_run {
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
    int started;
} vb_run;

/* Load tests/data/validation/<name>. */
static inline void vb_load(vb_run *r, const char *name)
{
    char p[1024];
    const char *f = __FILE__, *slash = strrchr(f, '/');
    snprintf(p, sizeof p, "%.*s/data/validation/%s", slash ? (int)(slash - f) : 1,
             slash ? f : ".", name);
    static ctd_scene_err se;
    memset(r, 0, sizeof *r);
    int rc = ctd_scene_load(p, &r->sc, &se);
    cr_assert_eq(rc, CT_OK, "%s: %s", p, se.count ? se.msg[0].text : "?");
}

/* Build the model and the interfaces of the (possibly edited) scene and
 * prepare the solver, with `observe` called every cycle (may be NULL). */
static inline void vb_start(vb_run *r, void (*observe)(void *, const ctd_solver *), void *ctx)
{
    char err[1024] = "";
    int rc = ctd_model_build(&r->m, r->sc, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "model: %s", err);
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    rc = ctd_interfaces_build(&r->m, r->sc, &hooks, &nhook, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "interfaces: %s", err);
    ctd_solver_opts o = ctd_solver_default_opts();
    o.no_output = 1;
    o.quiet = 1;
    o.threads = 1;
    o.observe = observe;
    o.observe_ctx = ctx;
    rc = ctd_solver_init(&r->s, &r->m, &o, hooks, nhook, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "solver: %s", err);
    r->started = 1;
}

/* Run to the end; the run must end "ok". */
static inline void vb_go(vb_run *r)
{
    int rc = ctd_solver_run(&r->s);
    cr_assert_eq(rc, CTD_EXIT_OK, "%s: %s", r->sc->path, r->s.message);
}

static inline void vb_free(vb_run *r)
{
    if (r->started) {
        ctd_solver_destroy(&r->s);
        ctd_model_destroy(&r->m);
    }
    ctd_scene_free(r->sc);
    memset(r, 0, sizeof *r);
}

/* A set of node indices (malloc'd). */
typedef struct vb_nodes {
    int n;
    ct_idx *i;
} vb_nodes;

/* The nodes of scene mesh entry `mesh` whose reference position passes
 * `keep` (NULL: all of them). */
static inline vb_nodes vb_mesh_nodes(const ctd_model *m, int mesh,
                                     int (*keep)(double x, double y, double z, const void *),
                                     const void *arg)
{
    ct_idx a = m->mesh_node_off[mesh], b = m->mesh_node_off[mesh + 1];
    vb_nodes s = {0, malloc(sizeof(ct_idx) * (size_t)(b - a + 1))};
    cr_assert(s.i != NULL);
    const ct_nodes *nd = &m->mesh.nodes;
    for (ct_idx k = a; k < b; k++)
        if (!keep || keep(nd->x[k], nd->y[k], nd->z[k], arg))
            s.i[s.n++] = k;
    return s;
}

/* Mass-weighted mean of a nodal array over a set (v: the velocity of the
 * set's centre of mass when the array is a velocity). */
static inline double vb_mean_mass(const ctd_model *m, const vb_nodes *s, const ct_real *v)
{
    double pm = 0, mm = 0;
    for (int k = 0; k < s->n; k++) {
        double mk = (double)m->mesh.nodes.m[s->i[k]];
        pm += mk * (double)v[s->i[k]];
        mm += mk;
    }
    return mm > 0 ? pm / mm : 0;
}

/* Plain mean of a nodal array over a set. */
static inline double vb_mean(const vb_nodes *s, const ct_real *v)
{
    double sum = 0;
    for (int k = 0; k < s->n; k++)
        sum += (double)v[s->i[k]];
    return s->n ? sum / s->n : 0;
}

/* The time where a quantity sampled at (t0, g0), (t1, g1) crosses zero
 * (linear between the samples). */
static inline double vb_cross(double t0, double g0, double t1, double g1)
{
    return g0 == g1 ? t1 : t0 + (t1 - t0) * g0 / (g0 - g1);
}

#endif /* TEST_VALIDATION_BARS_H */
