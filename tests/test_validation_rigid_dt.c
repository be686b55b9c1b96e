/*
 * test_validation_rigid_dt.c -- validation case 8 (issue 6): the energy of a
 * penalty contact against omega dt. A rigid ball (mass M) hits a held wall
 * through a linear penalty, F = k p (TYPE6 with a linear curve, undamped;
 * tests/data/validation/rigid_wall.yaml), and the restitution e = u_out /
 * u_in is measured for omega dt = sqrt(k / M) dt from 0.02 to 1.98 (the
 * central difference's stability limit is 2), each at 16 entry phases.
 *
 * It runs the driver's solver (central difference, rigid body, the TYPE6
 * interface), with the step set through the output interval, which caps
 * it: TYPE6 sets no step before contact (it has no penetration to judge)
 * and its own step 0.1 sqrt(M / k) is omega dt = 0.1 dt_scale; dt_scale is
 * raised to 100 so that it never binds, and the step is the chosen one,
 * constant from start to end.
 *
 * Reference. The figure: e within 0.5 % for omega dt <= 0.2. And
 * the exact discrete theory (Belytschko, Liu, Moran, Nonlinear Finite
 * Elements for Continua and Structures, Wiley 2000, section 6.2: the
 * central difference conserves a modified energy of a linear system):
 * with u the velocity into the wall at half steps and p the penetration,
 *   H = u(n-1/2) u(n+1/2) / 2 + omega^2 p(n)^2 / 2
 * is exactly constant while the spring acts. At the first step in contact,
 * p0 = s u_in dt (0 < s <= 1), H = u_in^2 (1 - (omega dt)^2 s (1 - s)) / 2;
 * at the last one, pN = s' |u_out| dt, H = u_out^2 (1 - (omega dt)^2 s' (1 -
 * s')) / 2. So
 *   e^2 = (1 - (omega dt)^2 s (1 - s)) / (1 - (omega dt)^2 s' (1 - s')),
 * and e lies in [sqrt(1 - (omega dt)^2 / 4), 1 / sqrt(1 - (omega dt)^2 / 4)]:
 * the error grows as (omega dt)^2 / 8 and the energy gain is unbounded as
 * omega dt reaches 2. The test checks each run's e against this formula
 * with its own s and s' (the library's force and the integrator, exactly)
 * and the envelope.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "test_validation_rigid.h"

#define KCURVE 1.0e6 /* the curve's slope (N/m) */
#define NPHASE 16

/* The tolerance for omega dt <= 0.2: 0.5 % (double and single).
 * Each run's e against the discrete formula with its s, s': 1e-9 in double
 * (round-off), 1e-3 in single (s and s' come from float positions: the
 * penetration, about 5e-5 m, carries about 2e-9 m of round-off). */
#define TOL CTT_TOL(5e-3, 5e-3)
#define TOL_FORMULA CTT_TOL(1e-9, 1e-3)
/* How far the pole's penetration read from the positions may be from the
 * interface's own verdict (contact or not): the narrow phase counts a node
 * within 1e-14 (double) or 1e-6 (single) of the segment size (30 mm here)
 * as on the surface, not in it (kernels/narrow_internal.h, CTI_NR_ON_TOL). */
#define POS_TOL CTT_TOL(1e-15, 1e-7)

typedef struct impact {
    double e, s_in, s_out, e_formula;
    double dt, omega_dt;
} impact;

/* Entry phase j: the fractional parts of j times the golden ratio, spread
 * evenly over (0, 1) for any count. */
static double phase(int j)
{
    double g = 0.5 + 0.6180339887498949 * j;
    return g - floor(g);
}

/* One impact at omega dt = W and entry phase phi in (0, 1). */
static impact one_impact(rv_run *r, double M, double W, double phi)
{
    const double v = -r->sc->boundary[1].value[2];
    const double R = r->sc->mesh[1].generate->radius;
    const double w = sqrt(KCURVE / M), dt = W / w;
    /* The pole (R below the centre) starts (3 + phi) steps' travel above
     * the wall. */
    const double d0 = (3 + phi) * v * dt;
    r->sc->mesh[1].generate->origin[2] = R + d0;
    rv_build(r);
    const int ball = rv_body_of_part(r, 2);
    const ct_idx pole = rv_extreme_node(r, 2, 2, -1);
    double steps_in = ceil(3.1415926535897932 / acos(1 - W * W / 2)) + 1;
    ctd_solver_opts o = ctd_solver_default_opts();
    o.every = dt;
    o.dt_scale = 100;
    o.end_time = (4 + steps_in + 3) * dt;
    r->nb = 1;
    r->body[0] = ball;
    r->track[0] = pole;
    rv_run_solver(r, o);

    /* The contact as the interface saw it (active pairs), and the pole's
     * penetration read from the positions: they agree to the narrow
     * phase's round-off (POS_TOL). */
    impact q = {0};
    size_t first = 0, last = 0;
    for (size_t k = 0; k < r->n; k++) {
        double p = -r->h[k].xn[0][2];
        cr_assert(r->h[k].active <= 1, "W %g: %lld pairs active", W, (long long)r->h[k].active);
        cr_assert(r->h[k].active ? p > -POS_TOL : p < POS_TOL,
                  "W %g: %lld pairs active at a penetration of %g m", W,
                  (long long)r->h[k].active, p);
        if (r->h[k].active) {
            first = first ? first : k;
            last = k;
        }
    }
    cr_assert(first > 0 && last + 1 < r->n, "W %g phi %g: no complete contact", W, phi);
    for (size_t k = first; k <= last; k++)
        cr_assert_eq(r->h[k].active, 1, "W %g: the ball left and came back", W);
    double u_in = -r->h[first - 1].vc[0][2];    /* v(n-1/2) before the first contact */
    double u_out = r->h[r->n - 1].vc[0][2];     /* after */
    q.dt = r->h[first].dt;
    q.omega_dt = w * q.dt;
    q.e = u_out / u_in;
    q.s_in = -r->h[first].xn[0][2] / (u_in * q.dt);
    q.s_out = -r->h[last].xn[0][2] / (u_out * q.dt);
    double W2 = q.omega_dt * q.omega_dt;
    q.e_formula =
        sqrt((1 - W2 * q.s_in * (1 - q.s_in)) / (1 - W2 * q.s_out * (1 - q.s_out)));
    rv_reset(r);
    return q;
}

Test(validation_rigid, restitution_against_omega_dt)
{
    static const double Ws[] = {0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.45, 0.6, 0.7, 0.9,
                                1.1,  1.2,  1.3, 1.5,  1.6, 1.7, 1.8,  1.9, 1.95, 1.98};
    const int nW = (int)(sizeof Ws / sizeof Ws[0]);
    rv_run r;
    rv_load(&r, "tests/data/validation/rigid_wall.yaml");
    rv_build(&r);
    const double M = r.m.body[rv_body_of_part(&r, 2)].rigid.mass;
    rv_reset(&r);
    FILE *f = ctv_csv("rigid_restitution_dt",
                      "omega_dt,gain_sim,loss_sim,gain_bound,loss_bound");
    double err_02 = 0, formula_err = 0, env_err = 0, W_formula = 0;
    double gain_max = 0, W_gain = 0;
    for (int i = 0; i < nW; i++) {
        double emin = INFINITY, emax = -INFINITY, wdt = 0;
        for (int j = 0; j < NPHASE; j++) {
            impact q = one_impact(&r, M, Ws[i], phase(j));
            wdt = q.omega_dt;
            emin = fmin(emin, q.e);
            emax = fmax(emax, q.e);
            double fe = fabs(q.e - q.e_formula) / q.e_formula;
            if (fe > formula_err) {
                formula_err = fe;
                W_formula = wdt;
            }
            double lo = sqrt(1 - wdt * wdt / 4), hi = 1 / lo;
            env_err = fmax(env_err, fmax(lo - q.e, q.e - hi) / q.e);
            if (wdt <= 0.2 + 1e-12)
                err_02 = fmax(err_02, fabs(q.e - 1));
        }
        if (emax - 1 > gain_max) {
            gain_max = emax - 1;
            W_gain = wdt;
        }
        double lo = sqrt(1 - wdt * wdt / 4);
        ctv_row(f, 5, wdt, emax - 1, 1 - emin, 1 / lo - 1, 1 - lo);
    }
    if (f)
        fclose(f);
    ctv_plot("rigid_restitution_dt",
             "Mass on a linear penalty wall: restitution error against omega dt (16 phases each)",
             "omega dt", "restitution error",
             "1,2,linespoints,gain: max e - 1 (simulated);1,3,linespoints,loss: 1 - min e "
             "(simulated);1,4,dashed,1/sqrt(1 - (omega dt)^2/4) - 1 (bound);1,5,dashed,"
             "1 - sqrt(1 - (omega dt)^2/4) (bound)",
             "logy");
    const char *note = "rigid ball on a held wall, TYPE6 linear curve k 1e6 N/m, v 0.1 m/s, "
                       "driver's solver, step set by the output interval";
    ctv_result("restitution_dt", "max |e - 1| for omega dt <= 0.2", err_02, 0, TOL, note);
    ctv_result("restitution_dt", "max |e - e_discrete(s, s')| / e", formula_err, 0,
               TOL_FORMULA, "every run against the central difference's modified energy");
    ctv_result("restitution_dt", "largest energy gain max(e) - 1 (at omega dt below 2)",
               gain_max, 0, 0, "grows without bound as omega dt reaches 2");
    cr_expect(err_02 <= TOL, "restitution error %.4e for omega dt <= 0.2", err_02);
    cr_expect(formula_err <= TOL_FORMULA, "e off the discrete formula by %.3e at omega dt %.3g",
              formula_err, W_formula);
    cr_expect(env_err <= TOL_FORMULA, "e outside its envelope by %.3e", env_err);
    cr_expect(gain_max > 1 && W_gain > 1.9,
              "the energy gain near the limit: max e - 1 = %.3g at omega dt %.3g", gain_max,
              W_gain);
    rv_free(&r);
}
