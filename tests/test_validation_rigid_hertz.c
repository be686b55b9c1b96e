/*
 * test_validation_rigid_hertz.c -- validation case 1 (issue 6): Hertz
 * impact of a rigid ball on a rigid plane through TYPE6, whose force curve
 * is the Hertz law F = (4/3) E* sqrt(R) d^1.5 tabulated finely.
 *
 * Reference (Johnson, Contact Mechanics, CUP 1985, section 11.4; the
 * quasi-static Hertz impact of a sphere of mass m at speed v):
 *   d_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5),
 *   t_c   = 2 (d_max / v) int_0^1 dx / sqrt(1 - x^(5/2))
 *         = 2 (d_max / v) (2/5) B(2/5, 1/2) = 2.9432 d_max / v,
 *   F_max = (4/3) E* sqrt(R) d_max^(3/2), restitution 1.
 * The ball is a rigid cube-sphere whose pole is a node, so the deepest node's
 * penetration is the ball's indentation d, and TYPE6 makes the total force
 * the curve at that penetration whatever the other nodes do.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "test_validation_rigid.h"

#define ESTAR 1.0e8 /* effective modulus E* (Pa) */

/* The case's tolerance on every figure: 0.5 % in double and in single
 * (single stores positions in float: the indentation, about 1.2 mm, carries
 * a few 1e-9 m of round-off, far below it). */
#define TOL CTT_TOL(5e-3, 5e-3)

/* The integral of the piecewise-linear table (p, f) of n points from 0 to
 * b (b within the table). */
static double table_integral(double (*c)[2], int n, double b)
{
    double s = 0;
    for (int k = 0; k + 1 < n && c[k][0] < b; k++) {
        double hi = c[k + 1][0] < b ? c[k + 1][0] : b;
        double fh = c[k][1] + (c[k + 1][1] - c[k][1]) * (hi - c[k][0]) / (c[k + 1][0] - c[k][0]);
        s += 0.5 * (c[k][1] + fh) * (hi - c[k][0]);
    }
    return s;
}

static double table_eval(double (*c)[2], int n, double p)
{
    int k = 0;
    while (k + 2 < n && p >= c[k + 1][0])
        k++;
    return c[k][1] + (c[k + 1][1] - c[k][1]) * (p - c[k][0]) / (c[k + 1][0] - c[k][0]);
}

/* The Hertz impact ODE m d'' = -C d^1.5 (d > 0), d(0) = 0, d'(0) = v,
 * integrated by RK4 in steps of at most h: the reference force history for
 * the plot (the figures themselves are checked against the closed forms). */
typedef struct hertz_ode {
    double t, d, u, C, m, h;
} hertz_ode;

static double hertz_acc(const hertz_ode *o, double d)
{
    return d > 0 ? -o->C * d * sqrt(d) / o->m : 0;
}

static void hertz_advance(hertz_ode *o, double t_to)
{
    while (o->t < t_to) {
        double h = t_to - o->t < o->h ? t_to - o->t : o->h;
        double k1d = o->u, k1u = hertz_acc(o, o->d);
        double k2d = o->u + 0.5 * h * k1u, k2u = hertz_acc(o, o->d + 0.5 * h * k1d);
        double k3d = o->u + 0.5 * h * k2u, k3u = hertz_acc(o, o->d + 0.5 * h * k2d);
        double k4d = o->u + h * k3u, k4u = hertz_acc(o, o->d + h * k3d);
        o->d += h / 6 * (k1d + 2 * k2d + 2 * k3d + k4d);
        o->u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
        o->t += h;
    }
}

Test(validation_rigid, hertz_impact_rigid)
{
    rv_run r;
    rv_load(&r, "tests/data/validation/rigid_hertz.yaml");
    rv_build(&r);
    const int ball = rv_body_of_part(&r, 2);
    const ct_idx pole = rv_extreme_node(&r, 2, 2, -1);
    const double m = r.m.body[ball].rigid.mass;
    const double R = r.sc->mesh[1].generate->radius;
    const double v = -r.sc->boundary[1].value[2];
    const double z0 = r.m.mesh.nodes.z[pole];
    cr_assert(v > 0 && z0 > 0 && fabs(r.m.mesh.nodes.x[pole]) < 1e-12);

    /* The closed forms. */
    const double C = 4.0 / 3.0 * ESTAR * sqrt(R);
    const double dmax = pow(15.0 * m * v * v / (16.0 * ESTAR * sqrt(R)), 0.4);
    const double kt = 2.0 * 0.4 * tgamma(0.4) * tgamma(0.5) / tgamma(0.9); /* 2.9432 */
    const double tc = kt * dmax / v;
    const double f_max = C * dmax * sqrt(dmax);

    /* The curve: NT equal intervals up to 1.25 d_max (h = d_max / 320). */
    enum { NT = 400 };
    static double curve[NT + 1][2];
    for (int k = 0; k <= NT; k++) {
        double p = 1.25 * dmax * k / NT;
        curve[k][0] = p;
        curve[k][1] = C * p * sqrt(p);
    }
    /* The tabulation's own error: largest force error on [0, d_max] against
     * F(d_max), and the stored energy at d_max against 2/5 C d_max^2.5. */
    double tab_f = 0;
    for (int k = 0; k <= 20 * NT; k++) {
        double p = dmax * k / (20.0 * NT);
        tab_f = fmax(tab_f, fabs(table_eval(curve, NT + 1, p) - C * p * sqrt(p)) / f_max);
    }
    double w_ref = 0.4 * C * pow(dmax, 2.5);
    double tab_w = fabs(table_integral(curve, NT + 1, dmax) - w_ref) / w_ref;
    cr_expect(tab_f < 1e-4 && tab_w < 1e-4, "tabulation error %.2e (force), %.2e (energy)",
              tab_f, tab_w);
    rv_set_curve(&r, 0, curve, NT + 1);

    /* Run: the step is capped by the output interval at t_c / 400 (TYPE6
     * sets no step before contact, and its own step 0.1 sqrt(m / K) is
     * larger than that during most of the contact). */
    ctd_solver_opts o = ctd_solver_default_opts();
    o.every = tc / 400;
    o.end_time = z0 / v + 1.3 * tc;
    r.nb = 1;
    r.body[0] = ball;
    r.track[0] = pole;
    rv_run_solver(&r, o);

    size_t n = r.n;
    double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d);
    cr_assert(t && d);
    for (size_t k = 0; k < n; k++) {
        t[k] = r.h[k].t;
        d[k] = -r.h[k].xn[0][2]; /* the pole's penetration below z = 0 */
    }
    size_t k_in = 0, k_out = 0;
    double t_in = rv_crossing(t, d, n, 0, +1, &k_in);
    double t_out = t_in >= 0 ? rv_crossing(t, d, n, k_in, -1, &k_out) : -1;
    cr_assert(t_in >= 0 && t_out > t_in, "no complete contact (in %g, out %g)", t_in, t_out);
    double dmax_sim = 0, fmax_sim = 0, dt_max = 0;
    long long act = 0; /* nodes in contact: the pole first, then rings of nodes */
    for (size_t k = k_in; k < k_out; k++) {
        act = r.h[k].active > act ? (long long)r.h[k].active : act;
        dmax_sim = fmax(dmax_sim, d[k]);
        fmax_sim = fmax(fmax_sim, fabs(r.h[k].f[2]));
        dt_max = fmax(dt_max, r.h[k].dt);
    }
    dt_max = fmax(dt_max, r.h[k_out].dt);
    double e_sim = r.h[n - 1].vc[0][2] / v; /* v(n+1/2) after the contact */
    double tc_sim = t_out - t_in;

    /* Curves: the force against time with the Hertz ODE's history. */
    FILE *f = ctv_csv("rigid_hertz", "t_ms,F_sim,F_hertz,d_sim_mm");
    hertz_ode ode = {0, 0, v, C, m, tc / 20000};
    for (size_t k = 0; k < n; k++) {
        double fr = 0;
        if (t[k] >= t_in) {
            hertz_advance(&ode, t[k] - t_in);
            fr = ode.d > 0 ? C * ode.d * sqrt(ode.d) : 0;
        }
        ctv_row(f, 4, 1e3 * t[k], fabs(r.h[k].f[2]), fr, 1e3 * d[k]);
    }
    if (f)
        fclose(f);
    ctv_plot("rigid_hertz", "Hertz impact, rigid ball on rigid plane (TYPE6 Hertz curve)",
             "time (ms)", "contact force (N)",
             "1,2,points,simulated (TYPE6);1,3,lines,Hertz (RK4 of the Hertz ODE)", "");

    char note[256];
    snprintf(note, sizeof note,
             "cube-sphere 8x8/face R %.3g m, m %.4g kg, v %.3g m/s, E* %.3g Pa; curve %d "
             "intervals to 1.25 d_max; dt <= %.3g t_c; up to %lld nodes in contact",
             R, m, v, ESTAR, NT, dt_max / tc, act);
    double e1 = ctv_result("hertz_rigid", "peak indentation d_max (m)", dmax_sim, dmax, TOL, note);
    double e2 = ctv_result("hertz_rigid", "contact time t_c (s)", tc_sim, tc, TOL, note);
    double e3 = ctv_result("hertz_rigid", "peak force (N)", fmax_sim, f_max, TOL, note);
    double e4 = ctv_result("hertz_rigid", "restitution", e_sim, 1.0, TOL, note);
    ctv_result("hertz_rigid", "tabulation force error / F_max", tab_f, 0, 0, note);
    ctv_result("hertz_rigid", "tabulation energy error (relative)", tab_w, 0, 0, note);
    cr_expect(dt_max <= tc / 200, "step %.3g above t_c / 200 = %.3g", dt_max, tc / 200);
    cr_expect(e1 <= TOL, "d_max %.6g against %.6g (error %.2e)", dmax_sim, dmax, e1);
    cr_expect(e2 <= TOL, "t_c %.6g against %.6g (error %.2e)", tc_sim, tc, e2);
    cr_expect(e3 <= TOL, "F_max %.6g against %.6g (error %.2e)", fmax_sim, f_max, e3);
    cr_expect(e4 <= TOL, "restitution %.6g (error %.2e)", e_sim, e4);
    free(t);
    free(d);
    rv_free(&r);
}
