/*
 * test_validation_friction_laws.c -- validation case 5d (suite
 * validation_friction_laws): the friction laws other than Coulomb (TYPE24,
 * Ifric 1 polynomial, 2 Darmstad, 3 Renard, 4 exponential decay) through
 * the whole driver: the scene, the interface's per-pair slip speed and
 * contact pressure (driver/interfaces/iface_pass_force.c), the law, the
 * return to the cone and the filter.
 *
 * Truth: while a contact slides, its friction force sits on the cone,
 * |Ft| = mu(p, v) fn, so a block dragged at a constant speed v under a
 * constant load N carries Ft / N = mu(p, v), with mu the law's published
 * formula, computed here by hand (fl_mu below, written from DESIGN.md
 * section 7 and the header kernels/ct_friction.h; the test never calls the
 * library's law):
 *   Ifric 1: mu = Fric + C1 p + C2 v + C3 p v + C4 p^2 + C5 v^2;
 *   Ifric 2: mu = C1 e^(C2 v) p^2 + C3 e^(C4 v) p + C5 e^(C6 v);
 *   Ifric 3 (Renard, C1 mu_s, C2 mu_d, C3 mu_max, C4 mu_min, C5 Vcr1,
 *            C6 Vcr2, xi = (v - C5) / (C6 - C5)):
 *            v <= C5: mu = C1 + (C3 - C1) (v / C5) (2 - v / C5),
 *            C5 < v < C6: mu = C3 + (C4 - C3) xi^2 (3 - 2 xi),
 *            v >= C6: mu = C2 - (C2 - C4) / (1 + (C2 - C4) (v - C6)^2);
 *   Ifric 4: mu = C1 + (Fric - C1) e^(-C2 v).
 * The contact pressure of a pair is its normal force over the area of the
 * main segment it presses on (the interface computes it from the
 * segment's diagonals, or from two edges of a triangle).
 *
 * Scene tests/data/validation/friction_laws.yaml: a rigid block with a
 * 20 mm x 20 mm bottom face, its 4 corners the secondary nodes (one
 * node-to-surface pass), driven at v in x and held in y (a driven rigid
 * body does not spin, so the corners press alike) over a fixed rigid plate
 * of 10 mm square cells; 1 N down on each corner: N = 4 N on 4e-4 m^2, a
 * pressure of 1e4 Pa. Each main segment (1e-4 m^2) has the area one
 * corner stands for, so the pressure the interface should use,
 * 1 N / 1e-4 m^2, is that same 1e4 Pa. The coefficients make the pressure
 * terms a large part of mu (half the pressure changes mu by 42 % to 49 %),
 * and each law runs at two or three speeds where its mu differs by 26 % to
 * 54 % (Renard at one speed in each of its three branches): a wrong speed,
 * a wrong pressure or an ignored Ifric fails. TYPE24 with Istf 1000 gives
 * K = Kt = 1e5 N/m per corner; the step is 2e-5 s; a run lasts 30 ms.
 *
 * Checks, in double and in single precision:
 *  - over the steady window (the second half of the run), the mean Ft / N
 *    against mu(p_load, v), p_load = (N / 4) / A_seg from the load, and
 *    the mean N against the load: within CTT_TOL(1e-6, 1e-4);
 *  - every step from the first contact, Ft against the tangential law
 *    written out by hand for one corner from the recorded N (fl_measure:
 *    elastic trial, return to the cone mu(fn / A_seg, v) fn, filter):
 *    within CTT_TOL(1e-9, 2e-4) relative;
 *  - no force across the drag: |Fy| / N within CTT_TOL(1e-9, 1e-5).
 * Why these tolerances. The normal penalty springs (4 x 1e5 N/m on the
 * 31 g block, 570 Hz) start from the load applied at once; VisS 1 damps
 * the oscillation as about e^(-1.2e3 t), to 1e-7 of N at the window's
 * start and 1e-14 at its end: the window's mean N is off the load by
 * 8e-9 (measured), and the mean Ft / N by as much through the pressure
 * terms (2.4e-8 at most with a filter, which lags N's last wiggles). The tangential spring's elastic lag (the trial gains Kt v dt =
 * 0.1 N to 1 N a step) and the filter's (alpha = 0.05: about 3 ms) are
 * over long before the window, and the step-by-step check follows both
 * exactly anyway. What is left is round-off: double agrees to 1e-12
 * (measured). In single the corners' penetrations, 10 um measured from
 * positions near z = 1 mm (float spacing 1.2e-10 m there), carry a
 * relative round-off of 1e-5 per corner, which goes into each corner's fn
 * and pressure, and a filtered force clipped to a corner's own cone
 * remembers it over 1 / alpha steps: measured 1e-5 on the means, 5e-5 per
 * step at worst (the filtered start).
 *
 * A triangulated plate (two triangles per cell, 5e-5 m^2 each) doubles the
 * pressure the interface uses to 2e4 Pa for the same load: the case checks
 * the area of triangles against that. It is the convention's price (the
 * pressure follows the main segments' size, not the contact's area),
 * stated, not hidden: the true mean pressure is still 1e4 Pa.
 *
 * The tangential filter (Ifiltr 2, alpha = 2 pi / Xfreq, and Ifiltr 3,
 * alpha = 2 pi Xfreq dt, both 0.05 here) only smooths: in steady sliding
 * the filtered force stays on the cone and the same mu holds. The filter
 * shows in the rise of Ft at the start, which the step-by-step check
 * follows with alpha, and which is asserted to take 30 steps or more
 * (against at most 5 without it): an ignored filter fails.
 */
#include "test_validation_friction.h"

#include "interfaces/iface.h"

#define FL_NSEC 4              /* the block's bottom corners */
#define FL_LOAD 4.0            /* N, 1 N on each corner */
#define FL_AB (0.02 * 0.02)    /* m^2, the block's bottom face */
#define FL_H 0.01              /* m, the plate's cell */
#define FL_DT 2.0e-5           /* s, the step (capped by the output interval) */
#define FL_T 0.03              /* s, the run */
#define FL_K 1.0e5             /* N/m, K = Kt per corner: Stfac E t of the plate */

/* A law's card: Ifric, Fric, C1..C6. */
typedef struct fl_law {
    const char *name;
    int ifric;
    double fric, c[6];
} fl_law;

/* The laws' published formulas, by hand (see the header). c[0] is C1. */
static double fl_mu(const fl_law *L, double p, double v)
{
    const double *c = L->c, F = L->fric;
    double mu = 0;
    switch (L->ifric) {
    case 1:
        mu = F + c[0] * p + c[1] * v + c[2] * p * v + c[3] * p * p + c[4] * v * v;
        break;
    case 2:
        mu = c[0] * exp(c[1] * v) * p * p + c[2] * exp(c[3] * v) * p + c[4] * exp(c[5] * v);
        break;
    case 3: {
        const double ms = c[0], md = c[1], mmax = c[2], mmin = c[3], v1 = c[4], v2 = c[5];
        if (v <= v1) {
            mu = ms + (mmax - ms) * (v / v1) * (2 - v / v1);
        } else if (v < v2) {
            double xi = (v - v1) / (v2 - v1);
            mu = mmax + (mmin - mmax) * xi * xi * (3 - 2 * xi);
        } else {
            mu = md - (md - mmin) / (1 + (md - mmin) * (v - v2) * (v - v2));
        }
        break;
    }
    case 4: mu = c[0] + (F - c[0]) * exp(-c[1] * v); break;
    default: cr_assert_fail("no such law %d", L->ifric);
    }
    return mu;
}

/* The laws of the case, for pressures near 1e4 Pa (2e4 on triangles) and
 * speeds 0.05 to 0.5 m/s (mu stays positive there: the library clamps a
 * negative mu to 0, which the formulas above do not). */
static const fl_law FL_POLY = {"Ifric 1 polynomial", 1, 0.1,
                               {2e-5, 0.3, -2e-5, 1e-9, -0.6, 0}};
static const fl_law FL_DARM = {"Ifric 2 Darmstad", 2, 0, {1e-9, -2, 2e-5, -1, 0.1, -3}};
static const fl_law FL_RENARD = {"Ifric 3 Renard", 3, 0, {0.3, 0.25, 0.5, 0.15, 0.1, 0.3}};
static const fl_law FL_EXP = {"Ifric 4 exponential decay", 4, 0.6, {0.2, 5, 0, 0, 0, 0}};

typedef struct fl_obs {
    vf_rec rec; /* t, N, Ft (against the drag), Fy */
} fl_obs;

static void fl_observe(void *ctx, const ctd_solver *s)
{
    fl_obs *o = ctx;
    double *row = vf_rec_add(&o->rec);
    row[0] = s->time;
    row[1] = s->rep[0].fvec[2];
    row[2] = -s->rep[0].fvec[0];
    row[3] = s->rep[0].fvec[1];
}

/* How a run differs from the scene besides the law: the triangulated
 * plate, the pressure's area (CTD_PAREA_*), the block's part as the
 * secondary side (TYPE24's two passes). */
typedef struct fl_setup {
    int tri, parea, two_pass;
} fl_setup;

/* One run of the scene with law L at speed v, the filter (ifiltr, xfreq)
 * and the setup u. */
static void fl_run_setup(const fl_law *L, double v, int ifiltr, double xfreq, fl_setup u,
                         fl_obs *o)
{
    vf_run r;
    vf_load(&r, "friction_laws.yaml");
    ctd_scene_interface *f = &r.sc->interfaces[0];
    f->pressure_area = u.parea;
    if (u.two_pass) {
        f->secondary->part = 2;
        f->secondary->where.n = 0;
    }
    const int tri = u.tri;
    f->Ifric = L->ifric;
    f->Fric = L->fric;
    f->C1 = L->c[0];
    f->C2 = L->c[1];
    f->C3 = L->c[2];
    f->C4 = L->c[3];
    f->C5 = L->c[4];
    f->C6 = L->c[5];
    f->Ifiltr = ifiltr;
    f->Xfreq = xfreq;
    vf_bc(r.sc, CTD_BC_VELOCITY)->value[0] = v;
    cr_assert(r.sc->mesh[0].generate != NULL);
    r.sc->mesh[0].generate->tri = tri != 0;
    vf_build(&r);
    memset(o, 0, sizeof *o);
    vf_rec_init(&o->rec, 4);
    vf_solve(&r, fl_observe, o, 1);
    vf_free(&r);
}

static void fl_run(const fl_law *L, double v, int ifiltr, double xfreq, int tri, fl_obs *o)
{
    fl_setup u = {tri, CTD_PAREA_MAIN, 0};
    fl_run_setup(L, v, ifiltr, xfreq, u, o);
}

/* What a run measured. */
typedef struct fl_meas {
    double mu;      /* steady window: mean Ft / mean N */
    double N;       /* steady window: mean N */
    double step;    /* steady window: largest relative |Ft - Ft_hand| per step */
    double rise;    /* the same from the first contact to the window */
    double fy;      /* largest |Fy| / N in contact */
    double t_rise;  /* first time Ft >= 0.99 mu(p, v) N, from the first contact */
} fl_meas;

/* The filter's alpha by hand (ct_friction.h): Ifiltr 0 none, 2 2 pi /
 * Xfreq, 3 2 pi Xfreq dt, kept in (0, 1]. */
static double fl_alpha(int ifiltr, double xfreq, double dt)
{
    double a = ifiltr == 2 ? 2 * VF_PI / xfreq : ifiltr == 3 ? 2 * VF_PI * xfreq * dt : 1;
    return a > 0 && a < 1 ? a : 1;
}

/*
 * Compare the recorded force with the tangential law written out by hand
 * for one corner (fn = N / 4, the four alike), step by step from the first
 * contact: the elastic trial F* = F_old + Kt v dt (everything lies along
 * the drag), the return to the cone Fc = min(F*, mu fn), the filter
 * F = alpha Fc + (1 - alpha) F_old, again at most mu fn, with
 * mu = mu(fn / A_seg, v) (DESIGN.md section 7 and ct_friction.h). Once the
 * trial is past the cone at every step (without a filter: from the first
 * steps on) this is Ft = mu(p, v) N.
 */
static fl_meas fl_measure(const fl_obs *o, const fl_law *L, double v, double aseg, int ifiltr,
                          double xfreq)
{
    fl_meas m = {0, 0, 0, 0, 0, -1};
    double sn = 0, sf = 0, t0 = -1, F = 0, tprev = 0;
    size_t cnt = 0;
    for (size_t i = 0; i < o->rec.n; i++) {
        const double *w = vf_rec_row(&o->rec, i);
        const double t = w[0], N = w[1], Ft = w[2], dt = i ? t - tprev : FL_DT;
        tprev = t;
        if (!(N > 0)) {
            F = 0; /* out of contact: the pair's force is reset */
            continue;
        }
        if (t0 < 0)
            t0 = t;
        const double fn = N / FL_NSEC, mu = fl_mu(L, fn / aseg, v), c = mu * fn;
        const double al = fl_alpha(ifiltr, xfreq, dt);
        const double Fs = F + FL_K * v * dt, Fc = Fs < c ? Fs : c;
        const double Fa = al * Fc + (1 - al) * F;
        F = Fa < c ? Fa : c;
        const double err = fabs(Ft - FL_NSEC * F) / (FL_NSEC * F);
        if (m.t_rise < 0 && Ft >= 0.99 * mu * N)
            m.t_rise = t - t0;
        m.fy = fmax(m.fy, fabs(w[3]) / N);
        if (t < 0.5 * FL_T) {
            m.rise = fmax(m.rise, err);
            continue;
        }
        m.step = fmax(m.step, err);
        sn += N;
        sf += Ft;
        cnt++;
    }
    cr_assert(cnt > 100, "only %zu samples in the steady window", cnt);
    m.N = sn / (double)cnt;
    m.mu = sf / sn;
    return m;
}

/* Run law L at speed v (filter and plate as in fl_run), check the figures
 * of the header and return what was measured. */
static fl_meas fl_case(const fl_law *L, double v, int ifiltr, double xfreq, int tri,
                       const char *what)
{
    const double aseg = tri ? 0.5 * FL_H * FL_H : FL_H * FL_H;
    /* The pressure the interface should use: the load per corner over a
     * main segment's area (1e4 Pa on the quads, 2e4 on the triangles). */
    const double p = FL_LOAD / FL_NSEC / aseg;
    const double mu = fl_mu(L, p, v);
    cr_assert(mu > 0, "%s: mu(%g, %g) = %g; the case needs mu > 0", L->name, p, v, mu);
    fl_obs o;
    fl_run(L, v, ifiltr, xfreq, tri, &o);
    fl_meas m = fl_measure(&o, L, v, aseg, ifiltr, xfreq);
    vf_rec_free(&o.rec);
    char cs[128], q[160], note[200];
    snprintf(cs, sizeof cs, "5d friction laws%s", what);
    snprintf(note, sizeof note,
             "rigid block dragged over a rigid plate (%s), N = 4 N, p = %g Pa, TYPE24 "
             "K = Kt = 1e5 N/m x 4 corners, Ifiltr %d; means over 15..30 ms",
             tri ? "triangles" : "quads", p, ifiltr);
    const double tol = CTT_TOL(1e-6, 1e-4), tol_step = CTT_TOL(1e-9, 2e-4);
    snprintf(q, sizeof q, "%s at v = %g m/s: Ft / N", L->name, v);
    double e = ctv_result(cs, q, m.mu, mu, tol, note);
    cr_expect(e <= tol, "%s, v = %g, p = %g Pa%s: Ft / N = %.9g, the law gives %.9g (%.3g)",
              L->name, v, p, what, m.mu, mu, e);
    snprintf(q, sizeof q, "%s at v = %g m/s: mean N (N)", L->name, v);
    double en = ctv_result(cs, q, m.N, FL_LOAD, tol, note);
    cr_expect(en <= tol, "%s, v = %g%s: mean N = %.9g, the load is %g", L->name, v, what, m.N,
              FL_LOAD);
    snprintf(q, sizeof q, "%s at v = %g m/s: worst step of Ft against the law by hand",
             L->name, v);
    double es = fmax(m.step, m.rise);
    ctv_result(cs, q, es, 0, tol_step, note);
    cr_expect(es <= tol_step,
              "%s, v = %g%s: a step's Ft is off the law by hand by %.3g (steady window) and "
              "%.3g (before it)",
              L->name, v, what, m.step, m.rise);
    /* The drag is along x: no force across it. */
    cr_expect(m.fy <= CTT_TOL(1e-9, 1e-5), "%s, v = %g%s: |Fy| / N up to %.3g", L->name, v,
              what, m.fy);
    return m;
}

Test(validation_friction_laws, laws_against_hand_formulas)
{
    const struct {
        const fl_law *law;
        int nv;
        double v[3];
    } cases[] = {
        {&FL_POLY, 2, {0.05, 0.5}},
        {&FL_DARM, 2, {0.05, 0.5}},
        {&FL_RENARD, 3, {0.05, 0.2, 0.5}},
        {&FL_EXP, 2, {0.05, 0.5}},
    };
    const int nc = (int)(sizeof cases / sizeof cases[0]);
    const double p = FL_LOAD / FL_AB;
    FILE *f = ctv_csv("friction_laws_mu",
                      "v (m/s),poly,Darmstad,Renard,exp decay,poly sim,Darmstad sim,"
                      "Renard sim,exp decay sim");
    for (int k = 0; k < nc; k++) {
        const fl_law *L = cases[k].law;
        /* The speeds must tell the law apart: their mu differ by far more
         * than the tolerance (26 % at least); and where the law reads the
         * pressure, half of it must change mu as much (42 % at least). */
        for (int j = 1; j < cases[k].nv; j++) {
            double a = fl_mu(L, p, cases[k].v[j - 1]), b = fl_mu(L, p, cases[k].v[j]);
            cr_assert(ctt_rel(a, b) > 0.25, "%s: mu %g and %g are too close", L->name, a, b);
        }
        for (int j = 0; j < cases[k].nv; j++) {
            double a = fl_mu(L, p, cases[k].v[j]), b = fl_mu(L, 0.5 * p, cases[k].v[j]);
            cr_assert(L->ifric > 2 || ctt_rel(a, b) > 0.4, "%s: mu %g and %g at half the "
                      "pressure are too close", L->name, a, b);
        }
        for (int j = 0; j < cases[k].nv; j++) {
            fl_meas m = fl_case(L, cases[k].v[j], 0, 0, 0, "");
            double row[9];
            for (int c = 0; c < 9; c++)
                row[c] = NAN;
            row[0] = cases[k].v[j];
            row[5 + k] = m.mu;
            ctv_row(f, 9, row[0], row[1], row[2], row[3], row[4], row[5], row[6], row[7],
                    row[8]);
        }
    }
    /* The laws' curves at p = 1e4 Pa. */
    for (int i = 0; i <= 100; i++) {
        double v = 0.006 * i;
        ctv_row(f, 9, v, fl_mu(&FL_POLY, p, v), fl_mu(&FL_DARM, p, v), fl_mu(&FL_RENARD, p, v),
                fl_mu(&FL_EXP, p, v), NAN, NAN, NAN, NAN);
    }
    if (f)
        fclose(f);
    ctv_plot("friction_laws_mu",
             "5d: block dragged at speed v under 1e4 Pa, Ft / N against the laws",
             "sliding speed v (m/s)", "friction coefficient Ft / N",
             "1,2,lines,Ifric 1 polynomial;1,3,lines,Ifric 2 Darmstad;1,4,lines,Ifric 3 Renard;"
             "1,5,lines,Ifric 4 exponential decay;1,6,points,simulated Ifric 1;"
             "1,7,points,simulated Ifric 2;1,8,points,simulated Ifric 3;"
             "1,9,points,simulated Ifric 4",
             "");
}

Test(validation_friction_laws, pressure_on_triangle_segments)
{
    /* The same load on half-area segments: the interface's pressure is
     * 2e4 Pa, and the pressure terms must follow it (mu changes by 57 %
     * and 56 % from its value at 1e4 Pa). */
    const double pq = FL_LOAD / FL_AB, pt = 2 * pq, v = 0.5;
    const fl_law *laws[] = {&FL_POLY, &FL_DARM};
    for (int k = 0; k < 2; k++) {
        cr_assert(ctt_rel(fl_mu(laws[k], pq, v), fl_mu(laws[k], pt, v)) > 0.5,
                  "%s: the pressure must matter", laws[k]->name);
        fl_case(laws[k], v, 0, 0, 1, " (triangulated plate)");
    }
}

Test(validation_friction_laws, filter_keeps_steady_mu)
{
    /* Ifiltr 2: alpha = 2 pi / Xfreq = 0.05; Ifiltr 3: alpha = 2 pi Xfreq
     * dt = 0.05 at the step of 2e-5 s. */
    const struct {
        const fl_law *law;
        double v;
        int ifiltr;
        double xfreq;
    } cases[] = {
        {&FL_EXP, 0.05, 3, 0.05 / (2 * VF_PI * FL_DT)},
        {&FL_POLY, 0.5, 2, 2 * VF_PI / 0.05},
    };
    for (int k = 0; k < 2; k++) {
        char what[64];
        snprintf(what, sizeof what, " (Ifiltr %d)", cases[k].ifiltr);
        fl_meas u = fl_case(cases[k].law, cases[k].v, 0, 0, 0, " (no filter)");
        fl_meas m = fl_case(cases[k].law, cases[k].v, cases[k].ifiltr, cases[k].xfreq, 0, what);
        /* Without the filter Ft is on the cone from the first contact
         * (fn is small then, the trial large); with alpha = 0.05 it closes
         * its distance to the cone by 5 % a step at most, while fn settles:
         * it reaches 99 % after 1.0 ms (50 steps) at 0.5 m/s and 2.9 ms at
         * 0.05 m/s (measured; the step-by-step check above follows it). */
        cr_expect(u.t_rise >= 0 && u.t_rise <= 5 * FL_DT, "%s: unfiltered rise %.3g s",
                  cases[k].law->name, u.t_rise);
        cr_expect(m.t_rise >= 30 * FL_DT, "%s%s: the force rose in %.3g s: no filter?",
                  cases[k].law->name, what, m.t_rise);
    }
}

/*
 * pressure_area: secondary (driver/interfaces/iface_area.c): a pair's
 * pressure is its normal force over the area its secondary node stands for
 * on the surface facing the contact. Each corner stands for a quarter of
 * the block's bottom face, 1e-4 m^2 (the block's side faces meet the
 * corners edge-on and do not count: counting them would make it 2e-4), so
 * the pressure is the true mean pressure, 1e4 Pa, on the quadrangle plate
 * and on the triangulated one alike, where the main segments' convention
 * gives 2e4 Pa on triangles (pressure_on_triangle_segments). Measured:
 * the mean Ft / N 2e-9 from mu(1e4 Pa, v), the steps 1.2e-12 from the law
 * by hand; asserted as laws_against_hand_formulas.
 *
 * With the block's part as the secondary side, TYPE24 runs two passes and
 * the plate's nodes under the block, against the block's stiffer face,
 * carry the load (the corners keep 3e-5 of it). With the main segments'
 * area, the block's face of 4e-4 m^2, their pressure is a quarter of the
 * true one and mu follows (0.131 against 0.300 for Ifric 1); with the
 * secondary nodes' area, 1e-4 m^2 each for the plate's nodes, it is the
 * true pressure. Not to round-off: the block's edges sweep over the
 * plate's nodes (15 mm over the run), each node taking up or giving back
 * its share over a few steps, and the corners' share presses at almost no
 * pressure: measured 5.2e-5 (Ifric 1) and 6.4e-5 (Ifric 2) from mu(p),
 * 1.7e-5 and 4.2e-5 from mu(p / 4) with the main area; asserted 2e-4
 * (the two mu differ by 56 % and 70 %). No step-by-step check here: the
 * plate's nodes take the block's stiffness, not the case's Kt. Nor in
 * single precision: that stiffness (Stfac B A^2 / V of the steel block,
 * 7e9 N/m) presses a plate node in by 1.4e-10 m, the float spacing at
 * z = 1 mm, and the pressures, made of those penetrations, are noise
 * (measured 1.6 % to 6 % off either way).
 */
Test(validation_friction_laws, secondary_area_is_the_contact_pressure)
{
    const double v = 0.5, p = FL_LOAD / FL_AB, acorner = FL_AB / FL_NSEC;
    const double tol = CTT_TOL(1e-6, 1e-4), tol_step = CTT_TOL(1e-9, 2e-4);
    const double tol2 = 2e-4;
    const fl_law *laws[] = {&FL_POLY, &FL_DARM};
    for (int k = 0; k < 2; k++) {
        const fl_law *L = laws[k];
        cr_assert(ctt_rel(fl_mu(L, p, v), fl_mu(L, p / 4, v)) > 0.5);
        for (int tri = 0; tri < 2; tri++) {
            fl_setup u = {tri, CTD_PAREA_SECONDARY, 0};
            fl_obs o;
            fl_run_setup(L, v, 0, 0, u, &o);
            fl_meas m = fl_measure(&o, L, v, acorner, 0, 0);
            vf_rec_free(&o.rec);
            const double e = ctt_rel(m.mu, fl_mu(L, p, v));
            cr_expect(e <= tol, "%s, %s, secondary area: Ft / N = %.9g, mu(%g Pa) = %.9g (%.3g)",
                      L->name, tri ? "triangles" : "quads", m.mu, p, fl_mu(L, p, v), e);
            cr_expect(fmax(m.step, m.rise) <= tol_step, "%s, %s: a step is off by %.3g",
                      L->name, tri ? "triangles" : "quads", fmax(m.step, m.rise));
        }
        for (int parea = 0; parea < 2 && sizeof(ct_real) == sizeof(double); parea++) {
            fl_setup u = {0, parea, 1};
            fl_obs o;
            fl_run_setup(L, v, 0, 0, u, &o);
            fl_meas m = fl_measure(&o, L, v, acorner, 0, 0);
            vf_rec_free(&o.rec);
            const double pw = parea == CTD_PAREA_SECONDARY ? p : p / 4;
            const double e = ctt_rel(m.mu, fl_mu(L, pw, v));
            cr_log_info("%s, two passes, %s area: Ft / N = %.9g, mu(%g Pa) = %.9g (%.3g)",
                        L->name, parea ? "secondary" : "main", m.mu, pw, fl_mu(L, pw, v), e);
            cr_expect(e <= tol2, "%s, two passes, %s area: Ft / N = %.9g, mu(%g Pa) = %.9g "
                      "(%.3g)", L->name, parea ? "secondary" : "main", m.mu, pw,
                      fl_mu(L, pw, v), e);
        }
    }
}
