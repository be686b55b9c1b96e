/*
 * test_loads.c -- the external loads of a scene (driver/loads.c, suite
 * "loads"): the time function, a step force on a bar against the wave
 * solution, a ramped pressure on a free block against the impulse it must
 * give, and the energy balance with the loads' work.
 */
#include <math.h>
#include <string.h>

#include "loads.h"
#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_util.h"

static void load_path(char *buf, size_t n, const char *name)
{
    const char *f = __FILE__, *slash = strrchr(f, '/');
    snprintf(buf, n, "%.*s/data/scenes/%s", slash ? (int)(slash - f) : 1, slash ? f : ".", name);
}

typedef struct lrun {
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
} lrun;

static void lrun_init(lrun *r, const char *name, ctd_solver_opts *o)
{
    char p[1024], err[1024] = "";
    load_path(p, sizeof p, name);
    static ctd_scene_err se;
    cr_assert_eq(ctd_scene_load(p, &r->sc, &se), CT_OK, "%s: %s", p,
                 se.count ? se.msg[0].text : "?");
    cr_assert_eq(ctd_model_build(&r->m, r->sc, err, sizeof err), CT_OK, "%s", err);
    o->no_output = 1;
    o->quiet = 1;
    cr_assert_eq(ctd_solver_init(&r->s, &r->m, o, NULL, 0, err, sizeof err), CT_OK, "%s", err);
}

static void lrun_free(lrun *r)
{
    ctd_solver_destroy(&r->s);
    ctd_model_destroy(&r->m);
    ctd_scene_free(r->sc);
}

Test(loads, factor_of_time)
{
    const double c[3][2] = {{1, 0}, {2, 4}, {4, 0}};
    cr_expect_eq(ctd_loads_factor(c, 0, 7), 1.0);
    cr_expect_eq(ctd_loads_factor(c, 3, -5), 0.0);   /* before: the first value */
    cr_expect_eq(ctd_loads_factor(c, 3, 1.5), 2.0);  /* linear in between */
    cr_expect_eq(ctd_loads_factor(c, 3, 2), 4.0);
    cr_expect_eq(ctd_loads_factor(c, 3, 3.5), 1.0);
    cr_expect_eq(ctd_loads_factor(c, 3, 9), 0.0);    /* after: the last value */
    const double one[1][2] = {{0, 2.5}};
    cr_expect_eq(ctd_loads_factor(one, 1, 3), 2.5);
}

/* The end of the bar, the time it reaches its largest displacement. */
typedef struct bar_obs {
    ct_idx end;
    double x0, umax, tmax;
} bar_obs;

static void bar_observe(void *ctx, const ctd_solver *s)
{
    bar_obs *o = ctx;
    double u = (double)s->x[o->end] - o->x0;
    if (u > o->umax) {
        o->umax = u;
        o->tmax = s->time;
    }
}

/* A step force F on the free end of a held bar: the end displacement peaks
 * at 2 F L / (E A) at t = 2 L / c (the stress wave's round trip), and the
 * work of the load balances the energies. */
Test(loads, bar_step_force_doubles_the_static_displacement)
{
    bar_obs o = {-1, 0, 0, 0};
    ctd_solver_opts opt = ctd_solver_default_opts();
    opt.observe = bar_observe;
    opt.observe_ctx = &o;
    lrun r;
    lrun_init(&r, "loads_bar_step.yaml", &opt);
    for (ct_idx i = 0; i < r.m.mesh.nodes.n; i++)
        if (r.m.mesh.nodes.x[i] > 0.999)
            o.end = i;
    cr_assert_geq(o.end, 0);
    o.x0 = r.m.mesh.nodes.x[o.end];
    cr_assert_eq(ctd_solver_run(&r.s), CTD_EXIT_OK, "%s", r.s.message);
    const double F = 1e5, L = 1, E = 2.1e11, A = 1e-4, rho = 7800, c = sqrt(E / rho);
    const double ust = F * L / (E * A);
    cr_expect(fabs(o.umax - 2 * ust) <= 0.01 * 2 * ust, "peak %.6g, expected 2 F L/(E A) = %.6g",
              o.umax, 2 * ust);
    cr_expect(fabs(o.tmax - 2 * L / c) <= 0.03 * 2 * L / c, "peak at %.4g s, expected 2L/c = %.4g",
              o.tmax, 2 * L / c);
    /* The load's work is F times the end displacement, and the balance
     * closes with it. */
    double u_end = (double)r.s.x[o.end] - o.x0;
    cr_expect(ctt_rel(r.s.e.external, F * u_end) < CTT_TOL(1e-9, 1e-4), "work %.9g, F u = %.9g",
              r.s.e.external, F * u_end);
    cr_expect(fabs(r.s.e.error) < CTT_TOL(1e-3, 1e-3), "energy error %.3e", r.s.e.error);
    lrun_free(&r);
}

/* A pressure ramped to p over T on the top face of a free block: the total
 * force is -p A e_z (the face's area A), so the momentum at time t > T is
 * -p A (t - T/2) e_z, with nothing along x or y; the energy balance holds
 * with the pressure's work. */
Test(loads, block_pressure_ramp_gives_its_impulse)
{
    ctd_solver_opts opt = ctd_solver_default_opts();
    lrun r;
    lrun_init(&r, "loads_block_pressure.yaml", &opt);
    cr_assert_eq(ctd_solver_run(&r.s), CTD_EXIT_OK, "%s", r.s.message);
    double P[3];
    ctd_solver_momentum(&r.s, P);
    const double p = 1e6, A = 0.01, T = 1e-4;
    /* The last kick spans half a step past the end time (velocities are
     * at half steps). */
    double t = r.s.time + 0.5 * r.s.dt;
    double J = -p * A * (t - T / 2);
    /* The kicks sum F(t_k) dt: for the ramp's slope a = p A / T this falls
     * short of the integral by a dt^2 / 8 at the start, and by at most as
     * much again at the ramp's end. */
    double a = p * A / T, dt = r.s.dt, tol = a * dt * dt / 4 + CTT_TOL(1e-9, 1e-5) * fabs(J);
    cr_expect(fabs(P[2] - J) <= tol, "momentum z %.9g, expected %.9g within %.3g", P[2], J, tol);
    cr_expect(fabs(P[0]) < CTT_TOL(1e-9, 1e-4) * fabs(J) && fabs(P[1]) < CTT_TOL(1e-9, 1e-4) * fabs(J),
              "momentum x %.3g, y %.3g", P[0], P[1]);
    cr_expect(fabs(r.s.e.error) < CTT_TOL(1e-4, 1e-3), "energy error %.3e", r.s.e.error);
    cr_expect(r.s.e.external > 0, "the pressure did work %.3g", r.s.e.external);
    lrun_free(&r);
}

/* A load whose selection is empty is bad input naming file, line, entry. */
Test(loads, empty_selection_is_an_error)
{
    char p[1024], err[512] = "";
    load_path(p, sizeof p, "loads_block_pressure.yaml");
    static ctd_scene_err se;
    ctd_scene *sc;
    cr_assert_eq(ctd_scene_load(p, &sc, &se), CT_OK);
    sc->boundary[0].surface->where.value[0] = 5; /* z > 5: nothing */
    ctd_model m;
    cr_assert_eq(ctd_model_build(&m, sc, err, sizeof err), CT_OK, "%s", err);
    ctd_loads L;
    int rc = ctd_loads_init(&L, &m, err, sizeof err);
    cr_expect_neq(rc, CT_OK);
    cr_expect(strstr(err, "loads_block_pressure.yaml:12: boundary[0].surface: selects no "
                          "segment (kind pressure)") != NULL,
              "message: %s", err);
    ctd_model_destroy(&m);
    ctd_scene_free(sc);
}
