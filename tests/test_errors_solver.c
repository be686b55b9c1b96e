/*
 * test_errors_solver.c -- the solver's diagnostics (driver/solver.c,
 * solver_report.c), suite "errors_solver": how a run that cannot go on
 * stops, with which exit code and which words. Interfaces that misbehave
 * on purpose are plugged into the solver through its hook (solver.h), on
 * a model built from a scene file as `contact run` builds it; the other
 * cases run the `contact` program on a scene file:
 *
 *  - an interface failing mid-run: an unstable code (exit 4, "unstable",
 *    the interface, the cycle and the node named) and any other code
 *    (exit 2, "error": a search too large for the machine is the input's
 *    fault);
 *  - a non-finite contact force (exit 4, the node named); a finite force
 *    whose kick overflows the velocity, found as a non-finite position at
 *    the next cycle; a stable step that underflows to 0;
 *  - a hook without its step function, a solver without a model;
 *  - from scene files: two loads of 1e308 on one node (a non-finite force
 *    before the first step, which no time step explains); a spinning
 *    rigid body stepped 10 times past its rotation's limit; an unstable
 *    run whose last good state cannot be written.
 *
 * Coverage of driver/ (the C files in driver/ and driver/elements/;
 * driver/interfaces/ excluded), gcov 12 over the whole suite run from a build
 * made with  make CC=gcc OPT=-O1 SAN_SUFFIX=-cov SAN_FLAGS="--coverage -g"
 * build-tests  (the `contact` runs of the tests counted too):
 *   before the tests of tests/test_errors_*.c (2c87307): lines 6923 / 7550
 *     (91.7 %), functions 407 / 415 (98.1 %);
 *   after them: lines 7147 / 7582 (94.3 %), functions 411 / 416 (98.8 %).
 * Of which the solver, run, loads, model, Radioss reader and output files:
 * lines 3392 / 3711 (91.4 %) -> 3562 / 3743 (95.2 %), functions 190 / 195
 * -> 194 / 196. solver.c alone: 430 / 461 -> 459 / 463 lines.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_errors.h"

/* ---- A model and a misbehaving interface --------------------------------- */

/* A soft, light block (E = rho = 1000: the wave speed is 1 m/s, the stable
 * step about 3e-3 s, a node's mass 1.25e-4 kg) that runs for about 300
 * cycles with one output step at each end. */
static const char SOFT[] =
    "title: soft block\n"
    "end_time: 1.0\n"
    "output: {every: 1.0, vtu: false, csv: false}\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 1000, nu: 0.3, rho: 1000}}\n";

enum fake_mode { FAKE_UNSTABLE, FAKE_TOOBIG, FAKE_INF_FORCE, FAKE_HUGE_FORCE, FAKE_TINY_STEP };

/* What the fake interface does, from cycle `at` on, at node index `node`. */
typedef struct fake {
    int mode;
    int64_t at;
    ct_idx node;
} fake;

static int fake_step(void *ctx, const ctd_state *st, ct_real *fx, ct_real *fy, ct_real *fz,
                     ctd_contact_report *rep)
{
    (void)fy;
    (void)fz;
    const fake *f = ctx;
    if (f->mode == FAKE_TINY_STEP)
        rep->dt_limit = 5e-324; /* the least double: times a dt_scale < 0.5 it is 0 */
    if (st->step < f->at)
        return CT_OK;
    switch (f->mode) {
    case FAKE_UNSTABLE:
        rep->bad_node = f->node;
        snprintf(rep->msg, sizeof rep->msg, "the fake interface gave up.");
        return CT_ERR_NONFINITE;
    case FAKE_TOOBIG:
        snprintf(rep->msg, sizeof rep->msg, "more pairs than an index holds.");
        return CT_ERR_TOOBIG;
    case FAKE_INF_FORCE:
        fx[f->node] += (ct_real)INFINITY;
        break;
    case FAKE_HUGE_FORCE:
        /* Finite in the build's precision: 1e308, or 1e38 in single. */
        fx[f->node] += (ct_real)(sizeof(ct_real) == sizeof(float) ? 1e38 : 1e308);
        break;
    default:
        break;
    }
    return CT_OK;
}

typedef struct fake_run {
    char dir[64];
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
    fake f;
    int rc_init;
    char err[1024];
} fake_run;

/* Load SOFT, build its model and a solver with one fake interface named
 * "fake" (type 7); opts as given (no output, quiet) with dt_scale. */
static void fake_open(fake_run *r, fake f, double dt_scale, int with_step)
{
    memset(r, 0, sizeof *r);
    ctt_tmpdir(r->dir, "errs");
    ctt_write_file(r->dir, "soft.yaml", SOFT);
    char path[128];
    snprintf(path, sizeof path, "%s/soft.yaml", r->dir);
    ctd_scene_err se;
    cr_assert_eq(ctd_scene_load(path, &r->sc, &se), CT_OK, "%s", se.msg[0].text);
    cr_assert_eq(ctd_model_build(&r->m, r->sc, r->err, sizeof r->err), CT_OK, "%s", r->err);
    r->f = f;
    ctd_contact_hook *h = calloc(1, sizeof *h);
    cr_assert_not_null(h);
    h->name = "fake";
    h->type = 7;
    h->search = "none";
    h->ctx = &r->f;
    h->contact_step = with_step ? fake_step : NULL;
    ctd_solver_opts o = ctd_solver_default_opts();
    o.no_output = 1;
    o.quiet = 1;
    o.progress = 0;
    o.threads = 1;
    o.dt_scale = dt_scale;
    r->rc_init = ctd_solver_init(&r->s, &r->m, &o, h, 1, r->err, sizeof r->err);
}

static void fake_close(fake_run *r)
{
    ctd_solver_destroy(&r->s);
    ctd_model_destroy(&r->m);
    ctd_scene_free(r->sc);
    ctt_rmtree(r->dir);
}

/* Run to the end; expect exit `code`, status `status` and `want` in the
 * message (and `also` when not NULL). */
static void expect_run(fake_run *r, int code, const char *status, const char *want,
                       const char *also)
{
    cr_assert_eq(r->rc_init, CT_OK, "%s", r->err);
    int rc = ctd_solver_run(&r->s);
    cr_expect_eq(rc, code, "exit %d, expected %d: %s", rc, code, r->s.message);
    cr_expect_eq(r->s.exit_code, code);
    cr_expect_str_eq(r->s.status, status);
    cr_expect(strstr(r->s.message, want) != NULL, "message lacks \"%s\": %s", want, r->s.message);
    if (also)
        cr_expect(strstr(r->s.message, also) != NULL, "message lacks \"%s\": %s", also,
                  r->s.message);
    cr_expect(r->s.time < r->s.end_time, "the run went on to t = %g", r->s.time);
}

/* ---- Interfaces that fail ---------------------------------------------- */

/* An unstable code names the interface, its type, the cycle and the node
 * (by its scene id, index + 1 for a generated mesh), and stops at once. */
Test(errors_solver, interface_unstable_mid_run)
{
    fake_run r;
    fake_open(&r, (fake){FAKE_UNSTABLE, 5, 3}, 0, 1);
    expect_run(&r, CTD_EXIT_UNSTABLE, "unstable", "cycle 5 (t = ",
               "): interface fake (type 7) failed at node 4: ");
    cr_expect(strstr(r.s.message, "the fake interface gave up.") != NULL, "%s", r.s.message);
    cr_expect_eq(r.s.cycle, 5);
    fake_close(&r);
}

/* Any other code is the input's (exit 2, "error"). */
Test(errors_solver, interface_error_mid_run)
{
    fake_run r;
    fake_open(&r, (fake){FAKE_TOOBIG, 2, 0}, 0, 1);
    expect_run(&r, CTD_EXIT_BADINPUT, "error", "cycle 2 (t = ",
               "): interface fake (type 7) failed: ");
    cr_expect(strstr(r.s.message, "more pairs than an index holds.") != NULL, "%s", r.s.message);
    cr_expect(strstr(r.s.message, "at node") == NULL, "no node to name: %s", r.s.message);
    fake_close(&r);
}

/* ---- Non-finite states --------------------------------------------------- */

/* An infinite contact force at cycle 3: the node is named with its part and
 * the step that is likely the cause. */
Test(errors_solver, nonfinite_force)
{
    fake_run r;
    fake_open(&r, (fake){FAKE_INF_FORCE, 3, 6}, 0, 1);
    expect_run(&r, CTD_EXIT_UNSTABLE, "unstable",
               "cycle 3 (t = ", "): node 7 (part 1) has a non-finite force; the time step (dt = ");
    fake_close(&r);
}

/* A force of 1e308 (1e38 in single) on a node of 1.25e-4 kg gives it an infinite velocity
 * at cycle 1 (which checks no energy): the position after the drift is
 * what is found, at cycle 2. */
Test(errors_solver, nonfinite_position)
{
    fake_run r;
    fake_open(&r, (fake){FAKE_HUGE_FORCE, 1, 0}, 0, 1);
    expect_run(&r, CTD_EXIT_UNSTABLE, "unstable", "cycle 2 (t = ",
               "): node 1 (part 1) has a non-finite position; the time step (dt = ");
    fake_close(&r);
}

/* An interface whose stable step is the least double, times dt_scale 0.4:
 * a step of 0 is refused before the first kick. */
Test(errors_solver, stable_step_of_zero)
{
    fake_run r;
    fake_open(&r, (fake){FAKE_TINY_STEP, 1000000, 0}, 0.4, 1);
    expect_run(&r, CTD_EXIT_UNSTABLE, "unstable", "cycle 0 (t = 0): the stable time step is 0",
               NULL);
    cr_expect_eq(r.s.cycle, 0);
    fake_close(&r);
}

/* What no caller should pass: a hook without its step, no model. */
Test(errors_solver, init_arguments)
{
    fake_run r;
    fake_open(&r, (fake){FAKE_UNSTABLE, 0, 0}, 0, 0);
    cr_expect_eq(r.rc_init, CT_ERR_ARG);
    cr_expect_str_eq(r.err, "interface 0 has no contact_step");
    fake_close(&r);
    ctd_solver s;
    char err[128] = "";
    cr_expect_eq(ctd_solver_init(&s, NULL, NULL, NULL, 0, err, sizeof err), CT_ERR_ARG);
    cr_expect_str_eq(err, "no model to run");
    ctd_solver_destroy(&s);
    cr_expect_eq(ctd_solver_init(NULL, NULL, NULL, NULL, 0, err, sizeof err), CT_ERR_ARG);
    ctd_solver_destroy(NULL);
}

/* ---- From scene files ---------------------------------------------------- */

/* Two forces of 1e308 on node 1 add up to infinity before any step: the
 * message blames the input, not a time step (it read "the time step
 * (dt = 0) is likely above the stable limit"). */
static const char TWO_LOADS[] =
    "end_time: 1.0e-6\n"
    "output: {vtu: false, csv: false}\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "boundary:\n"
    "  - {kind: force, nodes: {ids: [1]}, value: [1e308, 0, 0]}\n"
    "  - {kind: force, nodes: {ids: [1]}, value: [1e308, 0, 0]}\n";

/* A flat rigid plate spinning about a skew axis: its rotation's limit
 * (0.25 / |omega|) sets the step, and 10 times it leaves the rotation's
 * iteration without convergence. */
static const char SPIN[] =
    "end_time: 1.0e-1\n"
    "output: {every: 1.0e-1, vtu: false, csv: false}\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.2, 0.05, 0.02]}\n"
    "parts:\n"
    "  - {id: 1, element: rigid, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "boundary:\n"
    "  - {kind: initial_velocity, nodes: {part: 1, where: \"z > 0.01\"}, value: [10, 3, 0]}\n"
    "  - {kind: initial_velocity, nodes: {part: 1, where: \"z < 0.01\"}, value: [-10, 0, 5]}\n";

/* A steel block whose x = 0.01 face is thrown: with 3 times its stable step
 * it inverts a brick within a few cycles. */
static const char WOBBLE[] =
    "end_time: 2.0e-4\n"
    "output: {every: 2.0e-4, vtu: false, csv: false}\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [2, 2, 2], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "boundary:\n"
    "  - {kind: initial_velocity, nodes: {part: 1, where: \"x > 0.009\"}, value: [1, 0, 0]}\n";

Test(errors_solver, scene_runs_that_stop)
{
    char dir[64];
    ctt_tmpdir(dir, "errs");
    ctt_write_file(dir, "two_loads.yaml", TWO_LOADS);
    ctt_write_file(dir, "spin.yaml", SPIN);
    ctt_write_file(dir, "wobble.yaml", WOBBLE);
    ctt_cli r = {0};
    cte_run(&r, dir, "", "run two_loads.yaml --out o1 --quiet");
    CTE_EXPECT(&r, CTD_EXIT_UNSTABLE,
               "contact run: unstable: cycle 0 (t = 0): node 1 (part 1) has a non-finite force "
               "before the first step: expected loads, gravity and initial state whose forces "
               "are finite",
               "; no state passed the checks");
    cr_expect(strstr(r.err, "dt = 0") == NULL, "%s", r.err);
    cte_run(&r, dir, "", "run spin.yaml --out o2 --quiet --dt-scale 10");
    CTE_EXPECT(&r, CTD_EXIT_UNSTABLE,
               "contact run: unstable: cycle 0 (t = 0): rigid body 1 (part 1) failed to "
               "advance: ",
               "; the time step (dt = ");
    cr_expect(strstr(r.err, "is likely above the stable limit of its rotation") != NULL, "%s",
              r.err);
    cr_expect(strstr(r.err, "last good state (cycle 0, t = 0) written to o2/last_good.vtu") !=
                  NULL, "%s", r.err);
    /* The same step on the same scene within its limit runs. */
    cte_run(&r, dir, "", "run spin.yaml --out o2 --quiet");
    cr_expect_eq(r.status, 0, "%s", r.err);
    /* The last good state cannot be written: said, and the run still
     * exits 4 with its own diagnosis first. */
    char p[128];
    snprintf(p, sizeof p, "%s/o3/last_good.vtu", dir);
    char mk[256];
    snprintf(mk, sizeof mk, "mkdir -p '%s'", p);
    cr_assert_eq(system(mk), 0);
    cte_run(&r, dir, "", "run wobble.yaml --out o3 --quiet --dt-scale 3");
    CTE_EXPECT(&r, CTD_EXIT_UNSTABLE, "contact run: unstable: cycle ",
               "; the last good state could not be written: cannot create VTU file "
               "'o3/last_good.vtu': Is a directory");
    char *sum = cte_slurp_in(dir, "o3/summary.json");
    cr_assert_not_null(sum, "no summary.json");
    cr_expect(strstr(sum, "\"status\": \"unstable\"") && strstr(sum, "\"exit_code\": 4"), "%s",
              sum);
    free(sum);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}
