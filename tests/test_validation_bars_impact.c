/*
 * test_validation_bars_impact.c -- validation case 3 (issue 6, suite
 * validation_bars): the longitudinal impact of elastic bars, against
 * St Venant's one-dimensional wave solution (Timoshenko & Goodier, Theory
 * of Elasticity, 3rd ed. 1970, chapter 15, longitudinal impact of bars;
 * Goldsmith, Impact, 1960, chapter 2):
 *  - a bar of length L striking a rigid wall at v0 stays in contact for
 *    exactly 2L/c (c = sqrt(E/rho)) under the force Z v0 (Z = A sqrt(E
 *    rho)) and leaves at v0;
 *  - two identical bars, the striker at v0 and the struck bar at rest,
 *    touch for 2L/c under Z v0 / 2; then the striker is at rest and the
 *    struck bar moves at v0; the momentum is conserved.
 * The bars are rows of 40 brick cubes with Poisson's ratio 0 (a bar in one
 * dimension); the contact is TYPE24, nodes to surface, with the stiffness
 * of the main face alone (Istf 1000) and no damping (VisS 0): the scenes
 * tests/data/validation/bars_wall.yaml and bars_two.yaml say why.
 *
 * The penalty spring lengthens the contact. With a total contact stiffness
 * k in front of a bar of impedance Z, the end force rises as
 * Z v0 (1 - exp(-t/tau)), tau = Z/k, and the release comes at
 * 2L/c + x tau, x solving (2 - eps + 2x) exp(-x) = 1 (x = 1.68 for
 * eps = exp(-2L/(c tau)) -> 0): the characteristic solution of the bar
 * with a spring at its end (derived in docs/validation/sections/bars.md).
 * Two bars: by symmetry each sees a wall behind the spring 2k.
 */
#include "test_validation_bars.h"

/* Bar and material of the scenes. */
#define B_E 2.1e11
#define B_RHO 7800.0
#define B_H 0.005
#define B_L 0.2
#define B_V0 1.0

static double bar_c(void) { return sqrt(B_E / B_RHO); }
static double bar_T(void) { return 2 * B_L / bar_c(); }
static double bar_Z(void) { return B_H * B_H * sqrt(B_E * B_RHO); }

/* The release of a bar with a spring of time constant tau at its end,
 * after 2L/c (see the top comment): x tau with (2 - eps + 2x) e^-x = 1. */
static double spring_delay(double tau)
{
    double eps = exp(-bar_T() / tau), x = 1.7;
    for (int k = 0; k < 50; k++) {
        double f = (2 - eps + 2 * x) * exp(-x) - 1, df = (2 - 2 + eps - 2 * x) * exp(-x);
        x -= f / df;
    }
    return x * tau;
}

/* The end force of the bar with the spring (normalised by its rigid-wall
 * value), s the time since the first contact. */
static double spring_force(double s, double tau)
{
    double T = bar_T();
    if (s < 0)
        return 0;
    if (s <= T)
        return 1 - exp(-s / tau);
    double u = s - T, eps = exp(-T / tau);
    double f = -1 + (2 - eps + 2 * u / tau) * exp(-u / tau);
    return f > 0 && u < spring_delay(tau) ? f : 0;
}

/* What the observer gathers. */
typedef struct imp_obs {
    int two;                /* 1: two bars, 0: bar on the wall */
    vb_nodes sec, face;     /* the bar end nodes, the face they strike */
    vb_nodes a, b;          /* striker (or the bar), struck bar */
    double t_prev, g_prev;
    int have_prev;
    double t_first, t_last; /* first closing, last opening of the gap */
    int closings, openings;
    int force_gaps;         /* cycles inside the impact with no force */
    int in_contact_cycles;
    double p0, dp_max;      /* momentum along x: initial, largest change */
    double dt_min, dt_max;  /* the steps taken during the contact */
    double fscale, tau;
    int record;             /* 1: keep the rows below for the CSV */
    int nrow, cap;
    double (*row)[8];
} imp_obs;

static void imp_observe(void *ctx, const ctd_solver *s)
{
    imp_obs *o = ctx;
    /* The gap along x between the face and the end nodes (positive: apart). */
    double g = o->two ? vb_mean(&o->face, s->x) - vb_mean(&o->sec, s->x)
                      : vb_mean(&o->sec, s->x) - vb_mean(&o->face, s->x);
    double t = s->time;
    if (o->have_prev) {
        if (o->g_prev > 0 && g <= 0) {
            double tc = vb_cross(o->t_prev, o->g_prev, t, g);
            if (o->closings == 0)
                o->t_first = tc;
            o->closings++;
        } else if (o->g_prev <= 0 && g > 0) {
            o->t_last = vb_cross(o->t_prev, o->g_prev, t, g);
            o->openings++;
        }
    }
    double F = s->rep[0].force;
    if (o->closings > 0 && g <= 0) {
        o->in_contact_cycles++;
        o->force_gaps += !(F > 0);
        o->dt_min = fmin(o->dt_min, s->dt);
        o->dt_max = fmax(o->dt_max, s->dt);
    }
    double p[3];
    ctd_solver_momentum(s, p);
    double dp = fabs(p[0] - o->p0) + fabs(p[1]) + fabs(p[2]);
    o->dp_max = fmax(o->dp_max, dp);
    o->t_prev = t;
    o->g_prev = g;
    o->have_prev = 1;
    if (o->record && o->closings > 0) {
        if (o->nrow == o->cap) {
            o->cap = o->cap ? 2 * o->cap : 512;
            o->row = realloc(o->row, sizeof *o->row * (size_t)o->cap);
            cr_assert(o->row != NULL);
        }
        double T = bar_T(), sr = t - o->t_first;
        double va = vb_mean_mass(s->model, &o->a, s->vx) / B_V0;
        double vb = o->two ? vb_mean_mass(s->model, &o->b, s->vx) / B_V0 : 0;
        double ra = o->two ? fmax(0, 1 - fmin(sr / T, 1)) : (sr < T ? -1 + 2 * sr / T : 1);
        double rb = o->two ? fmin(sr / T, 1) : 0;
        double *w = o->row[o->nrow++];
        w[0] = sr / T;
        w[1] = F / o->fscale;
        w[2] = sr < T ? 1.0 : 0.0;
        w[3] = spring_force(sr, o->tau);
        w[4] = va;
        w[5] = ra;
        w[6] = vb;
        w[7] = rb;
    }
}

/* Write the rows, with the force also averaged over 9 cycles around each
 * (two periods of the ringing of the end nodes on the contact spring). */
static void imp_write(const imp_obs *o, const char *name)
{
    FILE *f = ctv_csv(name, "t_over_T,F_sim,F_rigid,F_spring,va_sim,va_exact,vb_sim,vb_exact,"
                            "F_sim_mean9");
    if (!f)
        return;
    for (int k = 0; k < o->nrow; k++) {
        double sum = 0;
        int cnt = 0;
        for (int j = k - 4; j <= k + 4; j++)
            if (j >= 0 && j < o->nrow) {
                sum += o->row[j][1];
                cnt++;
            }
        const double *w = o->row[k];
        ctv_row(f, 9, w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], sum / cnt);
    }
    fclose(f);
}

static int end_x_max(double x, double y, double z, const void *arg)
{
    (void)y, (void)z;
    return x > *(const double *)arg;
}

static int end_x_min(double x, double y, double z, const void *arg)
{
    (void)y, (void)z;
    return x < *(const double *)arg;
}

/* The figures of one impact run. */
typedef struct imp_res {
    double duration, delay_spring, v_a, v_b, dp_rel, dt_ratio;
    int chatter, force_gaps, cycles;
} imp_res;

/* Run scene `file` (two bars or the wall) with TYPE24 Stfac `stfac`;
 * `csvname` (may be NULL) records the curves. */
static imp_res run_impact(const char *file, int two, double stfac, const char *csvname)
{
    vb_run r;
    vb_load(&r, file);
    r.sc->interfaces[0].Stfac = stfac;
    imp_obs o;
    memset(&o, 0, sizeof o);
    o.two = two;
    o.dt_min = INFINITY;
    vb_start(&r, imp_observe, &o);
    const ctd_model *m = &r.m;
    /* Two bars: mesh 0 the striker (x < 0), mesh 1 the struck bar; the wall
     * case: mesh 0 the wall (face at x = 0), mesh 1 the bar. */
    double cut_hi = -2e-6, cut_lo = 1e-7, cut_bar = 2e-6, cut_face = -1e-7;
    o.a = vb_mesh_nodes(m, two ? 0 : 1, NULL, NULL);
    o.b = vb_mesh_nodes(m, two ? 1 : 0, NULL, NULL);
    o.sec = two ? vb_mesh_nodes(m, 0, end_x_max, &cut_hi) : vb_mesh_nodes(m, 1, end_x_min, &cut_bar);
    o.face = two ? vb_mesh_nodes(m, 1, end_x_min, &cut_lo) : vb_mesh_nodes(m, 0, end_x_max, &cut_face);
    cr_assert_eq(o.sec.n, 4);
    cr_assert_eq(o.face.n, 4);
    double p[3];
    ctd_solver_momentum(&r.s, p);
    o.p0 = p[0];
    /* Contact stiffness: Istf 1000, K = Stfac B A^2 / V = Stfac (E/3) h per
     * end node (nu = 0), four nodes. */
    double k = 4 * stfac * (B_E / 3) * B_H;
    o.tau = two ? bar_Z() / (2 * k) : bar_Z() / k;
    o.fscale = (two ? 0.5 : 1.0) * bar_Z() * B_V0;
    o.record = csvname != NULL;
    vb_go(&r);
    if (csvname)
        imp_write(&o, csvname);
    free(o.row);
    imp_res res;
    res.duration = o.t_last - o.t_first;
    res.delay_spring = spring_delay(o.tau);
    res.v_a = vb_mean_mass(m, &o.a, r.s.vx);
    res.v_b = two ? vb_mean_mass(m, &o.b, r.s.vx) : 0;
    res.dp_rel = o.dp_max / fabs(o.p0);
    res.chatter = o.openings - 1;
    res.force_gaps = o.force_gaps;
    res.cycles = o.in_contact_cycles;
    /* The step in contact against the bricks' own (h / c, nu = 0). */
    res.dt_ratio = o.dt_max / (r.s.dt_scale * B_H / bar_c());
    cr_assert(o.closings >= 1 && o.openings == o.closings, "%s: %d closings, %d openings", file,
              o.closings, o.openings);
    cr_assert(o.dt_max - o.dt_min <= 1e-9 * o.dt_max, "%s: the step changed in contact", file);
    free(o.a.i);
    free(o.b.i);
    free(o.sec.i);
    free(o.face.i);
    vb_free(&r);
    return res;
}

Test(validation_bars, bar_on_rigid_wall)
{
    imp_res x = run_impact("bars_wall.yaml", 0, 1.0, "bars_wall_impact");
    double T = bar_T();
    char note[256];
    snprintf(note, sizeof note,
             "40 brick cubes (h 5 mm, nu 0), TYPE24 Istf 1000 Stfac 1, VisS 0; %d reopenings "
             "(chatter), %d cycles of %d without force",
             x.chatter, x.force_gaps, x.cycles);
    double e_dur = ctv_result("3 bar on rigid wall", "contact duration / (2L/c)", x.duration / T,
                              1.0, 0.05, note);
    ctv_result("3 bar on rigid wall", "contact duration / (2L/c + 1.68 Z/k)",
               x.duration / (T + x.delay_spring), 1.0, 0, "the bar with the spring at its end");
    double e_v = ctv_result("3 bar on rigid wall", "rebound velocity / v0", x.v_a / B_V0, 1.0,
                            0.02, note);
    ctv_plot("bars_wall_impact", "Bar on a rigid wall: end force (40 bricks, TYPE24 Stfac 1)",
             "time since first contact / (2L/c)", "force / (Z v0)",
             "1,2,lines,simulated;1,9,lines,simulated (mean over 9 cycles);"
             "1,3,dashed,St Venant (rigid contact);"
             "1,4,dashed,bar with the contact spring (analytic)",
             "");
    cr_expect(e_dur < 0.05, "duration %.4g us against 2L/c = %.4g us", x.duration * 1e6, T * 1e6);
    cr_expect(e_v < 0.02, "rebound at %.5g m/s", x.v_a);
    /* The spring model explains the lengthening: what is left is the mesh's
     * dispersion. */
    cr_expect(fabs(x.duration - T - x.delay_spring) < 0.02 * T,
              "duration %.4g us, bar with spring %.4g us", x.duration * 1e6,
              (T + x.delay_spring) * 1e6);
}

Test(validation_bars, two_bars_colliding)
{
    imp_res x = run_impact("bars_two.yaml", 1, 1.0, "bars_two_impact");
    double T = bar_T();
    char note[256];
    snprintf(note, sizeof note,
             "2 x 40 brick cubes (h 5 mm, nu 0), TYPE24 Istf 1000 Stfac 1, VisS 0; %d reopenings "
             "(chatter), %d cycles of %d without force",
             x.chatter, x.force_gaps, x.cycles);
    const char *cs = "3 two bars colliding";
    double e_dur = ctv_result(cs, "contact duration / (2L/c)", x.duration / T, 1.0, 0.05, note);
    ctv_result(cs, "contact duration / (2L/c + 1.68 Z/(2k))", x.duration / (T + x.delay_spring),
               1.0, 0, "the bar with the spring at its end, by symmetry");
    /* The striker's velocity against v0 (reference 0: the error is
     * absolute, in units of v0). */
    double e_a = ctv_result(cs, "striker velocity after / v0", x.v_a / B_V0, 0.0, 0.02, note);
    double e_b = ctv_result(cs, "struck bar velocity after / v0", x.v_b / B_V0, 1.0, 0.02, note);
    const double ptol = CTT_TOL(1e-12, 1e-5);
    ctv_result(cs, "momentum change / initial momentum", x.dp_rel, 0.0, ptol,
               "largest over the run, all nodes");
    ctv_plot("bars_two_impact", "Two bars colliding: contact force and bar velocities",
             "time since first contact / (2L/c)", "force / (Z v0 / 2), velocity / v0",
             "1,2,lines,force (simulated);1,9,lines,force (mean over 9 cycles);"
             "1,3,dashed,force (St Venant);"
             "1,5,lines,striker velocity;1,6,dashed,striker (St Venant);"
             "1,7,lines,struck bar velocity;1,8,dashed,struck bar (St Venant)",
             "");
    cr_expect(e_dur < 0.05, "duration %.4g us against 2L/c = %.4g us", x.duration * 1e6, T * 1e6);
    cr_expect(e_a < 0.02, "striker at %.5g m/s after the impact", x.v_a);
    cr_expect(e_b < 0.02, "struck bar at %.5g m/s after the impact", x.v_b);
    cr_expect(x.dp_rel <= ptol, "momentum changed by %.3g (relative)", x.dp_rel);
}

/* The trade of the penalty stiffness, on the bar and the wall: a stiffer
 * contact spring shortens the lengthening of the contact (1.68 Z/k, the
 * spring model) and shortens the step, dt / (h/c) = 1 / sqrt(1 + K/k_e)
 * with K/k_e = 4 Stfac / 3 (K = Stfac E h / 3 per end node against the
 * brick's nodal stiffness k_e = 2 m / dt_e^2 = E h / 4). */
Test(validation_bars, contact_stiffness_trade)
{
    /* Single precision stops at Stfac 3: at Stfac 10 the float run releases
     * 5 % before 2L/c (the penetration, 7e-8 m, is within a few hundred
     * rounding units of the coordinates: see the section text). */
    const double stfac[] = {0.1, 0.3, 1.0, 3.0, 10.0};
    const int ns = (int)(sizeof stfac / sizeof stfac[0]) - CTT_SINGLE;
    const double T = bar_T();
    FILE *f = ctv_csv("bars_stiffness_trade", "Stfac,excess_sim,excess_spring,dt_ratio_sim,"
                                              "dt_ratio_exact,rebound_error");
    double prev_excess = INFINITY, prev_dt = INFINITY;
    for (int i = 0; i < ns; i++) {
        imp_res x = run_impact("bars_wall.yaml", 0, stfac[i], NULL);
        double excess = x.duration / T - 1, model = x.delay_spring / T;
        double dt_exact = 1 / sqrt(1 + 4 * stfac[i] / 3);
        ctv_row(f, 6, stfac[i], excess, model, x.dt_ratio, dt_exact, fabs(x.v_a / B_V0 - 1));
        char q[128], note[160];
        snprintf(note, sizeof note, "bar on the wall, 40 bricks, TYPE24 Istf 1000 Stfac %g; "
                 "%d reopenings (chatter)", stfac[i], x.chatter);
        snprintf(q, sizeof q, "Stfac %g: contact duration / (2L/c)", stfac[i]);
        ctv_result("3 contact stiffness trade", q, x.duration / T, 1.0, 0, note);
        snprintf(q, sizeof q, "Stfac %g: contact step / element step", stfac[i]);
        double e_dt = ctv_result("3 contact stiffness trade", q, x.dt_ratio, dt_exact, 0.01,
                                 "1 / sqrt(1 + 4 Stfac / 3)");
        /* The spring model accounts for the lengthening to 2 % of 2L/c
         * (the rest: the mesh's dispersion), and the step is the nodal
         * step of the contact. */
        cr_expect(fabs(excess - model) < 0.02, "Stfac %g: duration excess %.4f, model %.4f",
                  stfac[i], excess, model);
        cr_expect(e_dt < 0.01, "Stfac %g: step ratio %.4f, expected %.4f", stfac[i], x.dt_ratio,
                  dt_exact);
        cr_expect(excess < prev_excess && x.dt_ratio < prev_dt, "Stfac %g: no trade", stfac[i]);
        prev_excess = excess;
        prev_dt = x.dt_ratio;
    }
    if (f)
        fclose(f);
    ctv_plot("bars_stiffness_trade", "Bar on a wall: contact stiffness against duration and step",
             "Stfac (TYPE24 Istf 1000; K = Stfac E h / 3 per end node)", "ratio",
             "1,2,linespoints,duration / (2L/c) - 1 (simulated);"
             "1,3,dashed,1.68 Z / (k 2L/c) (bar with spring);"
             "1,4,linespoints,contact step / element step (simulated);"
             "1,5,dashed,1 / sqrt(1 + 4 Stfac / 3)",
             "logx logy");
}
