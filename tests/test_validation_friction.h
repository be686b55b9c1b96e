/*
 * test_validation_friction.h -- what the friction and Hertz validation cases
 * (suites validation_friction and validation_hertz) share: loading a scene
 * of tests/data/validation (or any path), letting the test change it before
 * the model is built, building the interfaces and running the solver with
 * an observer, and a growable record of samples.
 */
#ifndef TEST_VALIDATION_FRICTION_H
#define TEST_VALIDATION_FRICTION_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_solve.h"
#include "test_util.h"
#include "test_validation.h"

#define VF_PI 3.14159265358979323846

/* The path of tests/data/validation/<name>. */
static inline void vf_path(char *buf, size_t n, const char *name)
{
    const char *f = __FILE__, *slash = strrchr(f, '/');
    snprintf(buf, n, "%.*s/data/validation/%s", slash ? (int)(slash - f) : 1, slash ? f : ".",
             name);
}

typedef struct vf_run {
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
    int built;
} vf_run;

/* Load a scene (a full path); the caller may then change r->sc. */
static inline void vf_load_path(vf_run *r, const char *p)
{
    static ctd_scene_err se;
    memset(r, 0, sizeof *r);
    cr_assert_eq(ctd_scene_load(p, &r->sc, &se), CT_OK, "%s: %s", p,
                 se.count ? se.msg[0].text : "?");
}

/* Load tests/data/validation/<name>. */
static inline void vf_load(vf_run *r, const char *name)
{
    char p[1024];
    vf_path(p, sizeof p, name);
    vf_load_path(r, p);
}

/* Build the model of the (possibly changed) scene. */
static inline void vf_build(vf_run *r)
{
    char err[1024] = "";
    cr_assert_eq(ctd_model_build(&r->m, r->sc, err, sizeof err), CT_OK, "model: %s", err);
}

/* The index of the rigid body of a part (after vf_build), asserted. */
static inline int vf_body(const vf_run *r, int64_t part)
{
    for (int b = 0; b < r->m.nbody; b++)
        if (r->m.body[b].part == part)
            return b;
    cr_assert_fail("%s: part %lld is no rigid body", r->sc->path, (long long)part);
    return -1;
}

/* After vf_build: build the interfaces, prepare the solver (no files,
 * quiet) with the observer and `threads` threads (the small models of
 * these cases run on one: a cycle then costs microseconds, and a second
 * thread only adds its synchronisation), run to the end and assert that
 * the run ended "ok". */
static inline void vf_solve(vf_run *r, void (*observe)(void *, const ctd_solver *), void *ctx,
                            int threads)
{
    int rc = ctt_solve(&r->m, r->sc, &r->s, observe, ctx, threads, &r->built);
    cr_assert_eq(rc, CTD_EXIT_OK, "%s: %s", r->sc->path, r->s.message);
}

static inline void vf_free(vf_run *r)
{
    if (r->built)
        ctd_solver_destroy(&r->s);
    ctd_model_destroy(&r->m);
    ctd_scene_free(r->sc);
    memset(r, 0, sizeof *r);
}

/* The boundary entry of a kind (the first one), asserted to exist. */
static inline ctd_scene_bc *vf_bc(ctd_scene *sc, int kind)
{
    for (unsigned i = 0; i < sc->boundary_count; i++)
        if (sc->boundary[i].kind == kind)
            return &sc->boundary[i];
    cr_assert_fail("%s: no boundary entry of kind %s", sc->path, ctd_bc_kind_name(kind));
    return NULL;
}

/* A growable table of samples, ncol doubles per row. */
typedef struct vf_rec {
    int ncol;
    size_t n, cap;
    double *v;
} vf_rec;

static inline void vf_rec_init(vf_rec *t, int ncol)
{
    memset(t, 0, sizeof *t);
    t->ncol = ncol;
}

static inline double *vf_rec_add(vf_rec *t)
{
    if (t->n == t->cap) {
        t->cap = t->cap ? 2 * t->cap : 1024;
        t->v = realloc(t->v, t->cap * (size_t)t->ncol * sizeof(double));
        cr_assert(t->v != NULL);
    }
    return t->v + (t->n++) * (size_t)t->ncol;
}

static inline double *vf_rec_row(const vf_rec *t, size_t i)
{
    return t->v + i * (size_t)t->ncol;
}

static inline void vf_rec_free(vf_rec *t)
{
    free(t->v);
    memset(t, 0, sizeof *t);
}

#endif /* TEST_VALIDATION_FRICTION_H */
