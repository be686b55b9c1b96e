/*
 * test_scene_features.h -- what the two files of suite scene_features
 * share (tests/test_scene_features.c, test_scene_features_iface.c): a scene
 * written by the test, loaded, solved and freed; the rigid bodies of a
 * model; an observer of bodies approaching a fixed plane.
 */
#ifndef TEST_SCENE_FEATURES_H
#define TEST_SCENE_FEATURES_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_solve.h"
#include "test_util.h"

#define PI 3.14159265358979323846
#define STEEL "material: {E: 2.1e11, nu: 0.3, rho: 7800}"
#define RHO 7800.0
#define E_STEEL 2.1e11

/* Momentum "to round-off" over the few thousand steps of a run, with the
 * positions and velocities in ct_real (test_scenes.c uses the same). */
#define MOMENTUM_TOL CTT_TOL(1e-12, 1e-6)

/* ---- Running a scene written by the test --------------------------------- */

typedef struct sf_run {
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
    int solver;
} sf_run;

/* Write the scene text into a fresh temporary directory, load it at the
 * given refine (0: the file's) and build its model; the file is removed
 * once loaded. */
static inline void sf_load_refined(sf_run *r, const char *yaml, int64_t refine)
{
    memset(r, 0, sizeof *r);
    char dir[] = "/tmp/ct_features_XXXXXX", path[64];
    cr_assert(mkdtemp(dir) != NULL, "cannot make a temporary directory");
    snprintf(path, sizeof path, "%s/scene.yaml", dir);
    FILE *f = fopen(path, "w");
    cr_assert(f != NULL, "cannot write %s", path);
    fputs(yaml, f);
    fclose(f);
    static ctd_scene_err se;
    int rc = ctd_scene_load_refined(path, refine, &r->sc, &se);
    remove(path);
    rmdir(dir);
    cr_assert_eq(rc, CT_OK, "scene: %s\n%s", se.count ? se.msg[0].text : "?", yaml);
    char err[1024] = "";
    cr_assert_eq(ctd_model_build(&r->m, r->sc, err, sizeof err), CT_OK, "model: %s", err);
}

static inline void sf_load(sf_run *r, const char *yaml) { sf_load_refined(r, yaml, 0); }

/* Build the interfaces and the solver (no files, quiet) with an observer
 * and `threads` threads, run to the end and assert that it ended "ok". */
static inline void sf_solve(sf_run *r, void (*observe)(void *, const ctd_solver *), void *ctx,
                            int threads)
{
    cr_assert_eq(ctt_solve(&r->m, r->sc, &r->s, observe, ctx, threads, &r->solver), CTD_EXIT_OK,
                 "run: %s", r->s.message);
}

static inline void sf_free(sf_run *r)
{
    if (r->solver)
        ctd_solver_destroy(&r->s);
    ctd_model_destroy(&r->m);
    ctd_scene_free(r->sc);
    memset(r, 0, sizeof *r);
}

/* The index of the rigid body of a part, or -1. */
static inline int sf_body_index(const ctd_model *m, int64_t part)
{
    for (int b = 0; b < m->nbody; b++)
        if (m->body[b].part == part)
            return b;
    return -1;
}

/* The rigid body of a part (asserted). */
static inline const ctd_rigid *sf_body(const ctd_model *m, int64_t part)
{
    int b = sf_body_index(m, part);
    cr_assert(b >= 0, "part %lld is no rigid body", (long long)part);
    return &m->body[b].rigid;
}

/* Whether the final states of two runs are the same bit for bit. */
static inline int sf_same_state(const ctd_solver *a, const ctd_solver *b)
{
    if (a->nnode != b->nnode || a->cycle != b->cycle)
        return 0;
    size_t bytes = sizeof(ct_real) * (size_t)a->nnode;
    const ct_real *fa[6] = {a->x, a->y, a->z, a->vx, a->vy, a->vz};
    const ct_real *fb[6] = {b->x, b->y, b->z, b->vx, b->vy, b->vz};
    for (int f = 0; f < 6; f++)
        if (memcmp(fa[f], fb[f], bytes) != 0)
            return 0;
    return 1;
}

/* ---- An observer of bodies approaching a fixed plane ---------------------- */

/* For up to SF_NG parts: the distance d = dir (c - plane) of the part's
 * nearest node to the plane c = `plane` along `axis` (dir +1 for a part
 * above it, -1 below), its smallest value over the run, and its value at
 * the contact onset: for a rigid part the first cycle whose centre
 * velocity v(n+1/2) differs from the initial one (the contact force at
 * x(n) acted; its nodes get their velocities at the drift, one cycle
 * later), for a deformable part the first cycle at which interface 0
 * stores energy (in single precision the elements' round-off moves the
 * nodes' velocities by more than 1e-6 before any contact). Also the
 * largest contact energy of interface 0 and the largest step. */
#define SF_NG 2
typedef struct sf_obs {
    int axis;
    double plane;
    int ng;
    int64_t part[SF_NG];
    int dir[SF_NG], body[SF_NG], on[SF_NG];
    double v0[SF_NG], dmin[SF_NG], don[SF_NG];
    double emax, dtmax;
} sf_obs;

static inline void sf_obs_init(sf_obs *o, int axis, double plane)
{
    memset(o, 0, sizeof *o);
    o->axis = axis;
    o->plane = plane;
    for (int g = 0; g < SF_NG; g++) {
        o->dmin[g] = INFINITY;
        o->don[g] = NAN;
    }
}

/* Watch `part` (dir +1 above the plane, -1 below), whose initial velocity
 * along the axis is v0. */
static inline void sf_obs_add(sf_obs *o, const ctd_model *m, int64_t part, int dir, double v0)
{
    cr_assert_lt(o->ng, SF_NG);
    o->part[o->ng] = part;
    o->dir[o->ng] = dir;
    o->v0[o->ng] = v0;
    o->body[o->ng] = sf_body_index(m, part);
    o->ng++;
}

static inline void sf_observe(void *ctx, const ctd_solver *s)
{
    sf_obs *o = ctx;
    const int a = o->axis;
    const ct_real *c = a == 0 ? s->x : a == 1 ? s->y : s->z;
    const int32_t *np = s->model->node_part;
    for (int g = 0; g < o->ng; g++) {
        double d = INFINITY;
        for (ct_idx i = 0; i < s->nnode; i++)
            if (np[i] == o->part[g])
                d = fmin(d, o->dir[g] * ((double)c[i] - o->plane));
        int moved = o->body[g] >= 0
                        ? fabs(s->model->body[o->body[g]].rigid.vc[a] - o->v0[g]) >
                              1e-6 * fabs(o->v0[g])
                        : s->nhook > 0 && s->rep[0].energy > 0;
        o->dmin[g] = fmin(o->dmin[g], d);
        if (moved && !o->on[g]) {
            o->on[g] = 1;
            o->don[g] = d;
        }
    }
    if (s->nhook > 0)
        o->emax = fmax(o->emax, s->rep[0].energy);
    o->dtmax = fmax(o->dtmax, s->dt);
}

/* A rigid body that met linear springs of total stiffness nK at speed v
 * (the contact opening at `gap` from the plane): it began to slow within
 * one step of crossing the gap (v dt_max, with a round-off's slack), came
 * no nearer than gap - v sqrt(M / nK) (within `tol` of that depth: the
 * central difference's error in the amplitude of a spring it resolves
 * with several hundred steps, and the fraction of a step at the onset),
 * and left at speed v (the undamped law stores and returns the energy;
 * the same tolerance). */
static inline void sf_expect_bounce(const sf_obs *o, int g, const ctd_model *m, double gap, double M,
                             double nK, double v, double tol, const char *what)
{
    double p = v * sqrt(M / nK), slack = CTT_TOL(1e-12, 1e-9);
    double vend = sf_body(m, o->part[g])->vc[o->axis];
    cr_log_info("%s: onset %.9g (gap %.9g), closest %.9g (hand %.9g, %.2e of the depth), "
                "final speed %.9g", what, o->don[g], gap, o->dmin[g], gap - p,
                fabs(o->dmin[g] - (gap - p)) / p, vend);
    cr_expect(o->on[g], "%s: never slowed", what);
    cr_expect(o->don[g] <= gap + slack && o->don[g] >= gap - v * o->dtmax - slack,
              "%s: the contact began at %.9g from the plane, expected the gap %.9g (within one "
              "step, %.3g)", what, o->don[g], gap, v * o->dtmax);
    cr_expect(fabs(o->dmin[g] - (gap - p)) <= tol * p,
              "%s: closest approach %.9g, expected gap - v sqrt(M / nK) = %.9g within %.1e "
              "of the depth %.6g", what, o->dmin[g], gap - p, tol, p);
    cr_expect(fabs(fabs(vend) - v) <= tol * v && vend * o->v0[g] < 0,
              "%s: left at %.9g, expected %.9g back", what, vend, -o->v0[g]);
}


/* Depth, rebound speed and peak force against the hand values: 2e-4 in
 * double and single. Measured at most 3.6e-6 of the depth (3.3e-6 in
 * single) and 1.4e-6 of the speed: the central difference resolves each
 * contact with about 600 steps, its amplitude error goes as (omega dt)^2,
 * and the onset falls within a step. */
#define BOUNCE_TOL CTT_TOL(2e-4, 2e-4)

#endif /* TEST_SCENE_FEATURES_H */
