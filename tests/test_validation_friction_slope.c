/*
 * test_validation_friction_slope.c -- validation case 5b (issue 6, suite
 * validation_friction), after the NAFEMS contact benchmark CGS-4 (NAFEMS
 * R0081, Benchmark Tests for Finite Element Modelling of Contact, Gapping
 * and Sliding, 2001): a block on a slope of angle alpha under a vertical
 * load G, pushed up the slope by a horizontal force F that grows. Along the
 * slope F cos(alpha) - G sin(alpha) pushes up, the normal force is
 * N = G cos(alpha) + F sin(alpha), and Coulomb's law holds the block while
 * F cos(alpha) - G sin(alpha) <= mu N: sliding starts at
 *   F / G = (tan(alpha) + mu) / (1 - mu tan(alpha)).
 *
 * Scene tests/data/validation/friction_slope.yaml: a rigid block on a rigid
 * slope (TYPE24, Ifric 0, Fric = mu 0.3, Istf 1000: K = 1e5 N/m per node,
 * Kt = K, 9 nodes: Kt_total = 9e5 N/m), the loads on the block's bottom
 * nodes (no moment about the contact). G = 100 N is raised over 30 ms,
 * then F rises linearly over 200 ms to 1.2 times the analytic onset. The
 * ramp is quasi-static: the block's period on its tangential springs is
 * 2 pi sqrt(M / Kt_total) = 0.83 ms, 240 times shorter than the ramp; the
 * oscillation it leaves is (dF/dt) / (Kt_total omega), 8e-4 of the onset
 * deflection.
 *
 * Onset of sliding: the elastic predictor holds the block at the
 * tangential deflection u = (F cos(alpha) - G sin(alpha)) / Kt_total
 * (negative while G pulls it down the slope: the friction force turns
 * round during the ramp), at most the cone's mu N / Kt_total. The onset is
 * the first time u exceeds mu N(t) / Kt_total (N the interface's normal
 * force): past it the block slips. F / G there is asserted within 0.5 % of
 * the formula for alpha = 0, 8 and 16 degrees (tan 16 deg = 0.287, just
 * under mu: before F comes, the friction holds 96 % of the cone).
 */
#include "test_validation_friction.h"

#define SL_G 100.0
#define SL_MU 0.3
#define SL_KT (9 * 1.0e5)
#define SL_T0 0.03
#define SL_T1 0.23

typedef struct sl_obs {
    int body;
    double x0;
    vf_rec rec; /* t, u, N */
} sl_obs;

static void sl_observe(void *ctx, const ctd_solver *s)
{
    sl_obs *o = ctx;
    const ctd_rigid *r = &s->model->body[o->body].rigid;
    if (o->rec.n == 0)
        o->x0 = r->xc[0];
    double *row = vf_rec_add(&o->rec);
    row[0] = s->time;
    row[1] = r->xc[0] - o->x0;
    row[2] = s->rep[0].fvec[2];
}

/* The force entries of the scene: G first, then F. */
static void sl_loads(ctd_scene *sc, ctd_scene_bc **G, ctd_scene_bc **F)
{
    *G = *F = NULL;
    for (unsigned i = 0; i < sc->boundary_count; i++)
        if (sc->boundary[i].kind == CTD_BC_FORCE) {
            if (!*G)
                *G = &sc->boundary[i];
            else
                *F = &sc->boundary[i];
        }
    cr_assert(*G && *F);
}

Test(validation_friction, slope_push_onset)
{
    const double alphas[] = {0.0, 8.0, 16.0};
    const int na = (int)(sizeof alphas / sizeof alphas[0]);
    double sim[sizeof alphas / sizeof alphas[0]];
    FILE *fo = ctv_csv("friction_slope_onset", "alpha (deg),F/G simulated,F/G analytic");
    FILE *fc = ctv_csv("friction_slope_u",
                       "F/G,u simulated,stick (F cos - G sin) / Kt,cone mu N / Kt");
    for (int k = 0; k < na; k++) {
        const double al = alphas[k] * VF_PI / 180, ta = tan(al);
        const double ratio = (ta + SL_MU) / (1 - SL_MU * ta), Fend = 1.2 * ratio * SL_G;
        vf_run r;
        vf_load(&r, "friction_slope.yaml");
        ctd_scene_bc *G, *F;
        sl_loads(r.sc, &G, &F);
        /* Per node: vertical (down) G and horizontal F towards the slope,
         * in the slope's frame (x up the slope, z its normal). */
        G->value[0] = -SL_G * sin(al) / 9;
        G->value[2] = -SL_G * cos(al) / 9;
        F->value[0] = Fend * cos(al) / 9;
        F->value[2] = -Fend * sin(al) / 9;
        r.sc->interfaces[0].Fric = SL_MU;
        vf_build(&r);
        sl_obs o;
        memset(&o, 0, sizeof o);
        vf_rec_init(&o.rec, 3);
        o.body = vf_body(&r, 2);
        vf_solve(&r, sl_observe, &o, 1);
        vf_free(&r);
        /* The onset: the first sample past the ramp's start whose
         * deflection exceeds the cone's. */
        double fg_on = -1, umin = 0;
        for (size_t i = 0; i < o.rec.n; i++) {
            const double *w = vf_rec_row(&o.rec, i);
            umin = fmin(umin, w[1]);
            if (w[0] > SL_T0 && w[1] > SL_MU * w[2] / SL_KT) {
                fg_on = Fend * (w[0] - SL_T0) / (SL_T1 - SL_T0) / SL_G;
                break;
            }
        }
        cr_assert(fg_on > 0, "alpha %g: the block never slid", alphas[k]);
        char q[96], note[256];
        snprintf(q, sizeof q, "alpha %g deg, mu 0.3: F/G at the onset of sliding", alphas[k]);
        snprintf(note, sizeof note,
                 "rigid block, TYPE24 Kt_total 9e5 N/m, G 100 N, F ramp 0 to %.4g N over 0.2 s; "
                 "onset: u > mu N / Kt",
                 Fend);
        double e = ctv_result("5b slope push", q, fg_on, ratio, CTT_TOL(0.005, 0.005), note);
        cr_expect(e <= CTT_TOL(0.005, 0.005), "alpha %g: F/G %.6g at onset, expected %.6g",
                  alphas[k], fg_on, ratio);
        /* Before F: held down the slope at -G sin(alpha) / Kt. */
        if (alphas[k] > 0) {
            double ud = -SL_G * sin(al) / SL_KT;
            snprintf(q, sizeof q, "alpha %g deg: deflection under G alone (m)", alphas[k]);
            double eu = ctv_result("5b slope push", q, umin, ud, CTT_TOL(0.03, 0.03),
                                   "the friction holds G sin(alpha) before F comes");
            cr_expect(eu <= CTT_TOL(0.03, 0.03), "alpha %g: held at %.4g, expected %.4g",
                      alphas[k], umin, ud);
        }
        sim[k] = fg_on;
        if (k == na - 1)
            for (size_t i = 0; i < o.rec.n; i += 25) {
                const double *w = vf_rec_row(&o.rec, i);
                if (w[0] < SL_T0)
                    continue;
                double f = Fend * (w[0] - SL_T0) / (SL_T1 - SL_T0);
                double N = SL_G * cos(al) + f * sin(al);
                if (w[1] > 3 * SL_MU * N / SL_KT)
                    break; /* sliding away: the plot shows the onset */
                ctv_row(fc, 4, f / SL_G, w[1], (f * cos(al) - SL_G * sin(al)) / SL_KT,
                        SL_MU * N / SL_KT);
            }
        vf_rec_free(&o.rec);
    }
    /* The formula every degree, the simulated onsets at their angles. */
    for (int deg = 0; deg <= 16; deg++) {
        double ta = tan(deg * VF_PI / 180), fs = NAN;
        for (int k = 0; k < na; k++)
            if (alphas[k] == deg)
                fs = sim[k];
        ctv_row(fo, 3, (double)deg, fs, (ta + SL_MU) / (1 - SL_MU * ta));
    }
    if (fo)
        fclose(fo);
    if (fc)
        fclose(fc);
    ctv_plot("friction_slope_onset", "5b: block pushed up a slope, onset of sliding (mu 0.3)",
             "slope angle alpha (deg)", "F / G at the onset",
             "1,3,lines,(tan alpha + mu) / (1 - mu tan alpha);1,2,points,simulated (TYPE24)", "");
    ctv_plot("friction_slope_u", "5b: tangential deflection during the push (alpha 16 deg)",
             "F / G", "displacement up the slope (m)",
             "1,2,lines,simulated;1,3,dashed,stick: (F cos - G sin) / Kt;"
             "1,4,dashed,cone: mu N / Kt",
             "");
}
