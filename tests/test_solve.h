/*
 * test_solve.h -- run a built model to its end from a test: the scene's
 * interfaces, the solver with no files and no report, an observer called
 * every cycle, `threads` threads. Shared by the scene-feature and the
 * validation helpers (test_scene_features.h, test_validation_friction.h).
 */
#ifndef TEST_SOLVE_H
#define TEST_SOLVE_H

#include <criterion/criterion.h>

#include "model.h"
#include "scene.h"
#include "solver.h"

/* Build the interfaces of m (from scene sc) and solver s, set *built once
 * s holds them (its destroy is then due), run to the end; returns the
 * run's exit code (s->message says why when it is not CTD_EXIT_OK). */
static inline int ctt_solve(ctd_model *m, const ctd_scene *sc, ctd_solver *s,
                            void (*observe)(void *, const ctd_solver *), void *ctx, int threads,
                            int *built)
{
    char err[1024] = "";
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    cr_assert_eq(ctd_interfaces_build(m, sc, &hooks, &nhook, err, sizeof err), CT_OK,
                 "interfaces: %s", err);
    ctd_solver_opts o = ctd_solver_default_opts();
    o.no_output = 1;
    o.quiet = 1;
    o.threads = threads;
    o.observe = observe;
    o.observe_ctx = ctx;
    cr_assert_eq(ctd_solver_init(s, m, &o, hooks, nhook, err, sizeof err), CT_OK,
                 "solver: %s", err);
    *built = 1;
    return ctd_solver_run(s);
}

#endif /* TEST_SOLVE_H */
