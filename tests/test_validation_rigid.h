/*
 * test_validation_rigid.h -- what the rigid-body validation cases (suite
 * validation_rigid, issue 6 cases 1, 4, 8, 10 and 11) share: loading a scene
 * file, changing it in memory before the model is built (positions,
 * velocities, the TYPE6 curve), running the driver's solver with an observer
 * that records every cycle, and small helpers (the rigid body of a part, a
 * part's lowest node, a crossing time).
 *
 * The histories come from ctd_solver_opts.observe: it is called once per
 * cycle after the kick with the positions x(n), the velocities v(n+1/2),
 * the step s->dt that led to x(n), the bodies' centres and centre
 * velocities (double) and each interface's report of x(n) (s->rep[i].fvec).
 */
#ifndef TEST_VALIDATION_RIGID_H
#define TEST_VALIDATION_RIGID_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_util.h"
#include "test_validation.h"

/* Path of a file of the project: `rel` relative to the repository root
 * (found from this file's path, tests/...). */
static inline void rv_path(char *buf, size_t n, const char *rel)
{
    const char *f = __FILE__, *slash = strrchr(f, '/');
    int len = slash ? (int)(slash - f) : 1;
    snprintf(buf, n, "%.*s/../%s", len, slash ? f : ".", rel);
}

/* One sample of a run: time, the step that led to it, the first
 * interface's force on the secondary side and active pairs, and for up to two rigid bodies
 * their centre (x(n)), centre velocity (v(n+1/2)) and rotation, and one
 * tracked node's position per body. */
#define RV_NB 2
typedef struct rv_sample {
    double t, dt;
    double f[3];
    int64_t active; /* the first interface's active pairs */
    double xc[RV_NB][3], vc[RV_NB][3];
    double xn[RV_NB][3];
    double R[RV_NB][9]; /* the bodies' rotation matrices (body -> world) */
} rv_sample;

typedef struct rv_run {
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
    int built, started;
    /* The TYPE6 curve of interface 0 replaced for this run (restored
     * before the scene is freed: the scene owns the original). */
    double (*curve_saved)[2];
    unsigned curve_count_saved, curve_iface;
    int curve_swapped;
    /* What the observer records: bodies body[0..nb-1], node track[b]. */
    int nb;
    int body[RV_NB];
    ct_idx track[RV_NB];
    rv_sample *h;
    size_t n, cap;
    double p0[3];
} rv_run;

/* Load the scene at `rel` (relative to the repository root). The caller
 * may change r->sc before rv_build. */
static inline void rv_load(rv_run *r, const char *rel)
{
    memset(r, 0, sizeof *r);
    char p[1024];
    rv_path(p, sizeof p, rel);
    static ctd_scene_err se;
    int rc = ctd_scene_load(p, &r->sc, &se);
    cr_assert_eq(rc, CT_OK, "%s: %s", p, se.count ? se.msg[0].text : "?");
}

/* Replace interface i's curve by n points (p[k], f[k]) for this run; the
 * array `pts` must live until rv_free. */
static inline void rv_set_curve(rv_run *r, unsigned i, double (*pts)[2], unsigned n)
{
    cr_assert(i < r->sc->interfaces_count);
    cr_assert(!r->curve_swapped);
    r->curve_saved = r->sc->interfaces[i].curve;
    r->curve_count_saved = r->sc->interfaces[i].curve_count;
    r->curve_iface = i;
    r->sc->interfaces[i].curve = pts;
    r->sc->interfaces[i].curve_count = n;
    r->curve_swapped = 1;
}

/* Build the model. */
static inline void rv_build(rv_run *r)
{
    char err[1024] = "";
    int rc = ctd_model_build(&r->m, r->sc, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "model: %s", err);
    r->built = 1;
}

/* The index of the rigid body made of part `part`. */
static inline int rv_body_of_part(const rv_run *r, int64_t part)
{
    for (int b = 0; b < r->m.nbody; b++)
        if (r->m.body[b].part == part)
            return b;
    cr_assert_fail("no rigid body of part %lld", (long long)part);
    return -1;
}

/* The node of part `part` with the smallest (dir = -1) or largest (+1)
 * coordinate along axis `ax` in the reference state. */
static inline ct_idx rv_extreme_node(const rv_run *r, int64_t part, int ax, int dir)
{
    const ct_real *c[3] = {r->m.mesh.nodes.x, r->m.mesh.nodes.y, r->m.mesh.nodes.z};
    ct_idx best = -1;
    for (ct_idx i = 0; i < r->m.mesh.nodes.n; i++)
        if (r->m.node_part[i] == part &&
            (best < 0 || dir * (c[ax][i] - c[ax][best]) > 0))
            best = i;
    cr_assert(best >= 0, "part %lld has no node", (long long)part);
    return best;
}

static inline void rv_observe(void *ctx, const ctd_solver *s)
{
    rv_run *r = ctx;
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 4096;
        r->h = realloc(r->h, r->cap * sizeof *r->h);
        cr_assert(r->h != NULL);
    }
    rv_sample *q = &r->h[r->n++];
    memset(q, 0, sizeof *q);
    q->t = s->time;
    q->dt = s->dt;
    if (s->nhook > 0) {
        for (int d = 0; d < 3; d++)
            q->f[d] = s->rep[0].fvec[d];
        q->active = s->rep[0].active;
    }
    for (int b = 0; b < r->nb; b++) {
        const ctd_rigid *g = &s->model->body[r->body[b]].rigid;
        for (int d = 0; d < 3; d++) {
            q->xc[b][d] = g->xc[d];
            q->vc[b][d] = g->vc[d];
        }
        ctd_rigid_rotation(g, q->R[b]);
        ct_idx k = r->track[b];
        if (k >= 0) {
            q->xn[b][0] = s->x[k];
            q->xn[b][1] = s->y[k];
            q->xn[b][2] = s->z[k];
        }
    }
}

/* Build the interfaces and the solver with the options o (no files, quiet,
 * the observer set here), then run to the end. The bodies and tracked
 * nodes to record are r->nb, r->body[], r->track[] (set them before). */
static inline void rv_run_solver(rv_run *r, ctd_solver_opts o)
{
    char err[1024] = "";
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    int rc = ctd_interfaces_build(&r->m, r->sc, &hooks, &nhook, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "interfaces: %s", err);
    o.no_output = 1;
    o.quiet = 1;
    o.progress = 0;
    o.threads = 1; /* hundreds of nodes: one thread is fastest */
    o.observe = rv_observe;
    o.observe_ctx = r;
    rc = ctd_solver_init(&r->s, &r->m, &o, hooks, nhook, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "solver: %s", err);
    r->started = 1;
    ctd_solver_momentum(&r->s, r->p0);
    ctd_solver_run(&r->s);
    cr_assert_eq(r->s.exit_code, CTD_EXIT_OK, "run: %s", r->s.message);
}

/* Release the solver, the model and the history, keeping the scene (for
 * another run of it, changed). */
static inline void rv_reset(rv_run *r)
{
    if (r->started)
        ctd_solver_destroy(&r->s);
    if (r->built)
        ctd_model_destroy(&r->m);
    r->started = r->built = 0;
    r->n = 0;
}

static inline void rv_free(rv_run *r)
{
    if (r->started)
        ctd_solver_destroy(&r->s);
    if (r->built)
        ctd_model_destroy(&r->m);
    if (r->curve_swapped) {
        r->sc->interfaces[r->curve_iface].curve = r->curve_saved;
        r->sc->interfaces[r->curve_iface].curve_count = r->curve_count_saved;
    }
    ctd_scene_free(r->sc);
    free(r->h);
    memset(r, 0, sizeof *r);
}

/* The time at which g (sampled g[k] at t[k], k = 0..n-1, linear between
 * samples: exact for a position of the central difference, which moves
 * along straight lines between steps) first crosses 0 going in direction
 * dir (+1 upwards, -1 downwards) at or after sample k0; -1 when never. *at
 * (may be NULL) receives the sample after the crossing. */
static inline double rv_crossing(const double *t, const double *g, size_t n, size_t k0,
                                 int dir, size_t *at)
{
    for (size_t k = k0 > 0 ? k0 : 1; k < n; k++) {
        double a = dir * g[k - 1], b = dir * g[k];
        if (a < 0 && b >= 0) {
            if (at)
                *at = k;
            return t[k - 1] + (t[k] - t[k - 1]) * (-a) / (b - a);
        }
    }
    return -1;
}

#endif /* TEST_VALIDATION_RIGID_H */
