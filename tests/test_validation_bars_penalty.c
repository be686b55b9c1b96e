/*
 * test_validation_bars_penalty.c -- validation case 7 (issue 6, suite
 * validation_bars): the physical meaning of the penalty parameter, after
 * Munjiza, The Combined Finite-Discrete Element Method (Wiley 2004),
 * section 2.6.3 (seed 003): two elements of size h pressed together by the
 * pressure sigma deform by u = sigma h / E (eq. 2.56) and penetrate each
 * other by d = sigma h / p (eq. 2.57) for the penalty p; with p = alpha E
 * the penetration is u / alpha, and the contact's frequency is sqrt(alpha)
 * times the element's, so the stable step shrinks by that factor.
 *
 * Munjiza's p is a pressure per unit of relative penetration d / h (units
 * of E, Pa): the contact pressure is p d / h. Our TYPE24 works with a
 * stiffness per node (N/m); on a node with the tributary area A_node the
 * same law is K = p A_node / h. With Istf 1000 the interface gives each
 * node K = Stfac B A_seg^2 / V = Stfac B A_seg / h (B the bulk modulus of
 * the face's brick, V its volume): Stfac = alpha E A_node / (B A_seg) =
 * 3 alpha (1 - 2 nu) A_node / A_seg, here 3 alpha / 4 (nu = 0, one face of
 * four nodes). The nodal step of the contact, sqrt(2 m / (k_e + K)) with
 * the brick's nodal stiffness k_e = 2 m / dt_e^2 = E h / 4, is then
 * dt_e / sqrt(1 + alpha): exactly the factor sqrt(1 + alpha).
 *
 * Scene: tests/data/validation/bars_penalty.yaml (the pressure ramped
 * smoothly over ten periods of the lowest mode and held; the figures are
 * the means over the last 100 us, their spread the dynamic residual).
 */
#include "test_validation_bars.h"

#define P_E 2.1e11
#define P_RHO 7800.0
#define P_H 0.01
#define P_SIGMA 2.1e8
#define P_T_AVG 2.0e-4 /* the window of the means: [P_T_AVG, end] */

typedef struct pen_obs {
    vb_nodes sec, face, top;
    const ctd_scene_bc *load;
    double alpha;
    /* Sums over the window. */
    int n;
    double d_sum, u_sum, d_min, d_max;
    FILE *csv;
    int every, cycle;
} pen_obs;

static int z_above(double x, double y, double z, const void *arg)
{
    (void)x, (void)y;
    return z > *(const double *)arg;
}

static int z_below(double x, double y, double z, const void *arg)
{
    (void)x, (void)y;
    return z < *(const double *)arg;
}

static void pen_observe(void *ctx, const ctd_solver *s)
{
    pen_obs *o = ctx;
    /* Penetration: the lower brick's top face above the upper brick's
     * bottom nodes; the upper brick's shortening. */
    double zs = vb_mean(&o->sec, s->z), zf = vb_mean(&o->face, s->z);
    double d = zf - zs, u = P_H - (vb_mean(&o->top, s->z) - zs);
    double f = ctd_loads_factor(o->load->curve, o->load->curve_count, s->time);
    double d_exact = P_SIGMA * P_H / (o->alpha * P_E), u_exact = P_SIGMA * P_H / P_E;
    if (o->csv && o->cycle++ % o->every == 0)
        ctv_row(o->csv, 5, s->time * 1e6, d / d_exact, f, u / u_exact, f);
    if (s->time >= P_T_AVG) {
        o->n++;
        o->d_sum += d;
        o->u_sum += u;
        o->d_min = fmin(o->d_min, d);
        o->d_max = fmax(o->d_max, d);
    }
}

typedef struct pen_res {
    double d, u, spread, dt_ratio;
} pen_res;

static pen_res run_penalty(double alpha, const char *csvname)
{
    vb_run r;
    vb_load(&r, "bars_penalty.yaml");
    r.sc->interfaces[0].Stfac = 0.75 * alpha;
    pen_obs o;
    memset(&o, 0, sizeof o);
    o.alpha = alpha;
    o.d_min = INFINITY;
    o.d_max = -INFINITY;
    o.load = &r.sc->boundary[2];
    cr_assert_eq(o.load->kind, CTD_BC_PRESSURE);
    vb_start(&r, pen_observe, &o);
    double cut_face = -1e-6, cut_sec = 1e-6, cut_top = 0.5 * P_H;
    o.face = vb_mesh_nodes(&r.m, 0, z_above, &cut_face);
    o.sec = vb_mesh_nodes(&r.m, 1, z_below, &cut_sec);
    o.top = vb_mesh_nodes(&r.m, 1, z_above, &cut_top);
    cr_assert(o.face.n == 4 && o.sec.n == 4 && o.top.n == 4);
    if (csvname) {
        o.csv = ctv_csv(csvname, "t_us,d_over_exact,d_quasistatic,u_over_exact,u_quasistatic");
        o.every = 2;
    }
    vb_go(&r);
    if (o.csv)
        fclose(o.csv);
    pen_res x;
    x.d = o.d_sum / o.n;
    x.u = o.u_sum / o.n;
    x.spread = (o.d_max - o.d_min) / 2 / x.d;
    /* The step of the run (the contact's, scaled) against the brick's step
     * h / c (nu = 0: c_b = sqrt(E/rho)). */
    double dte = P_H / sqrt(P_E / P_RHO);
    x.dt_ratio = r.s.dt / (r.s.dt_scale * dte);
    free(o.sec.i);
    free(o.face.i);
    free(o.top.i);
    vb_free(&r);
    return x;
}

Test(validation_bars, penalty_meaning_munjiza)
{
    /* Single precision runs alpha 1 and 10 only: at alpha 100 (and already
     * at 27) the float run goes unstable. In a quasi-static contact the
     * normal speed is about zero, and the rounding noise of the
     * penetration (float epsilon times the coordinates, 6e-10 m here)
     * exceeds the jump the motion explains, |v_n| dt, so the linear law's
     * stiffness blending (ct_penalty_linear) switches on at every step; with
     * a stiff spring the run then runs away. A limit found here, reported,
     * not fixed (see the section text). */
    const double alphas[3] = {1, 10, 100};
    const int nalpha = CTT_SINGLE ? 2 : 3;
    const char *cs = "7 penalty meaning (Munjiza 2.6.3)";
    /* Double and single precision alike: the contact plane is at z = 0,
     * where float positions resolve the 1e-7 m penetration of alpha 100. */
    const double tol_d = CTT_TOL(0.02, 0.02), tol_dt = 0.02;
    FILE *f = ctv_csv("bars_penalty_alpha", "alpha,d_over_u_sim,d_over_u_exact,dt_ratio_sim,"
                                            "dt_ratio_exact");
    for (int i = 0; i < nalpha; i++) {
        double a = alphas[i];
        pen_res x = run_penalty(a, a == 10 ? "bars_penalty_history" : NULL);
        double d_exact = P_SIGMA * P_H / (a * P_E), u_exact = P_SIGMA * P_H / P_E;
        double dt_exact = 1 / sqrt(1 + a);
        ctv_row(f, 5, a, x.d / u_exact, 1 / a, x.dt_ratio, dt_exact);
        char q[128], note[200];
        snprintf(note, sizeof note,
                 "2 bricks h 10 mm, nu 0, sigma/E 1e-3; TYPE24 Istf 1000 Stfac %g (p = %g E); "
                 "mean over the hold, dynamic spread +-%.2g", 0.75 * a, a, x.spread);
        snprintf(q, sizeof q, "alpha %g: penetration d / (sigma h / p)", a);
        double e_d = ctv_result(cs, q, x.d / d_exact, 1.0, tol_d, note);
        snprintf(q, sizeof q, "alpha %g: element shortening u / (sigma h / E)", a);
        ctv_result(cs, q, x.u / u_exact, 1.0, 0, "St Venant-Kirchhoff brick at strain 1e-3");
        snprintf(q, sizeof q, "alpha %g: step / element step", a);
        double e_dt = ctv_result(cs, q, x.dt_ratio, dt_exact, tol_dt, "1 / sqrt(1 + alpha)");
        cr_expect(e_d < tol_d, "alpha %g: d = %.5g m, sigma h / p = %.5g m", a, x.d, d_exact);
        cr_expect(e_dt < tol_dt, "alpha %g: step ratio %.4f, expected %.4f", a, x.dt_ratio,
                  dt_exact);
        /* The element deformation does not depend on the penalty. */
        cr_expect(fabs(x.u / u_exact - 1) < 0.01, "alpha %g: u = %.5g m, sigma h / E = %.5g m",
                  a, x.u, u_exact);
    }
    if (f)
        fclose(f);
    ctv_plot("bars_penalty_alpha", "Two elements pressed together: penetration and step",
             "alpha (penalty p = alpha E)", "ratio",
             "1,2,linespoints,penetration d / (sigma h / E) (simulated);"
             "1,3,dashed,1 / alpha (Munjiza eqs. 2.56-2.57);"
             "1,4,linespoints,step / element step (simulated);"
             "1,5,dashed,1 / sqrt(1 + alpha)",
             "logx logy");
    ctv_plot("bars_penalty_history", "Two elements pressed together, alpha 10: the load history",
             "time (us)", "value / its exact static value at the full load",
             "1,2,lines,penetration d (simulated);1,3,dashed,sigma(t) h / p (quasi-static);"
             "1,4,lines,shortening u (simulated);1,5,dashed,sigma(t) h / E (quasi-static)",
             "");
}
