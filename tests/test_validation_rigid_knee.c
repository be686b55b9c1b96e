/*
 * test_validation_rigid_knee.c -- validation case 11 (issue 6): TYPE6 on the
 * knee-bolster scene (data/scenes/knee-bolster.yaml, loaded as it is): a
 * rigid knee (cube-sphere, 5.5 kg) strikes a held rigid bolster plate at
 * 5 m/s; the interface force is the user curve of the largest penetration
 * (Radioss TYPE6, seed 004: F = f(max p)).
 *
 * Checked at every cycle in contact, loading and unloading: the force the
 * interface reports (s->rep[0].fvec) against the input curve at the knee's
 * penetration read from the positions (the knee's lowest node, its pole,
 * below the plate's plane z = 0: TYPE6 takes the card's gap, 0 here, and
 * the plate's shell thickness only gives the plate its mass). Also the
 * crush depth, where the curve's integral equals the initial kinetic
 * energy, and the rebound speed (the curve is elastic: restitution 1).
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "test_validation_rigid.h"

/* The tolerance on the force-penetration path: 1 % of the curve's
 * force, in double and in single (the penetration is read from float
 * positions in single: about 1e-8 m of round-off on 34 mm of crush). */
#define TOL CTT_TOL(1e-2, 1e-2)

static double curve_at(const ctd_scene_interface *f, double p)
{
    unsigned k = 0;
    while (k + 2 < f->curve_count && p >= f->curve[k + 1][0])
        k++;
    const double *a = f->curve[k], *b = f->curve[k + 1];
    double v = a[1] + (b[1] - a[1]) * (p - a[0]) / (b[0] - a[0]);
    return v > 0 ? v : 0;
}

/* The integral of the curve from 0 to p. */
static double curve_work(const ctd_scene_interface *f, double p)
{
    double w = 0, lo = 0;
    while (lo < p) {
        unsigned k = 0;
        while (k + 2 < f->curve_count && lo >= f->curve[k + 1][0])
            k++;
        double hi = k + 2 < f->curve_count && f->curve[k + 1][0] < p ? f->curve[k + 1][0] : p;
        w += 0.5 * (curve_at(f, lo) + curve_at(f, hi)) * (hi - lo);
        lo = hi;
    }
    return w;
}

/* The scene at a refine (1: as it is), the knee thrown with an extra
 * sideways speed vx (its pole stays its lowest node: no friction, no
 * turn); csv names the plot's data (NULL: none). */
static void knee_bolster_curve(int64_t refine, double vx, const char *csv_name)
{
    rv_run r;
    memset(&r, 0, sizeof r);
    char path[1024];
    rv_path(path, sizeof path, "data/scenes/knee-bolster.yaml");
    static ctd_scene_err se;
    cr_assert_eq(ctd_scene_load_refined(path, refine, &r.sc, &se), CT_OK, "%s: %s", path,
                 se.count ? se.msg[0].text : "?");
    for (unsigned b = 0; b < r.sc->boundary_count; b++)
        if (r.sc->boundary[b].kind == CTD_BC_INITIAL_VELOCITY)
            r.sc->boundary[b].value[0] = vx;
    rv_build(&r);
    const ctd_scene_interface *f = &r.sc->interfaces[0];
    cr_assert_eq(f->type, 6);
    cr_assert_eq(f->gap, 0, "the scene's card gap is expected to be 0");
    const int knee = rv_body_of_part(&r, 2);
    const ct_idx pole = rv_extreme_node(&r, 2, 2, -1);
    const double M = r.m.body[knee].rigid.mass;
    const double v0 = -r.m.body[knee].rigid.vc[2];
    cr_assert(v0 > 0);

    r.nb = 1;
    r.body[0] = knee;
    r.track[0] = pole;
    rv_run_solver(&r, ctd_solver_default_opts());

    /* The path: every sample with the pole below z = 0. */
    FILE *csv = csv_name ? ctv_csv(csv_name, "p_mm,F_loading,F_unloading,F_curve") : NULL;
    double err_max = 0, pmax = 0, pmax_err = 0;
    int nload = 0, nunload = 0;
    for (size_t k = 0; k < r.n; k++) {
        double p = -r.h[k].xn[0][2];
        double F = r.h[k].f[2]; /* the bolster pushes the knee up */
        if (!(p > 0)) {
            cr_expect(fabs(F) == 0, "force %g at t = %g with no penetration", F, r.h[k].t);
            continue;
        }
        double fc = curve_at(f, p);
        double e = fabs(F - fc) / fc;
        /* Loading while the knee still moves down over the next step. */
        int loading = r.h[k].vc[0][2] < 0;
        nload += loading;
        nunload += !loading;
        if (e > err_max) {
            err_max = e;
            pmax_err = p;
        }
        pmax = fmax(pmax, p);
        ctv_row(csv, 4, 1e3 * p, loading ? F : NAN, loading ? NAN : F, NAN);
    }
    for (unsigned k = 0; k < f->curve_count && csv; k++)
        if (f->curve[k][0] <= 1.2 * pmax)
            ctv_row(csv, 4, 1e3 * f->curve[k][0], NAN, NAN, f->curve[k][1]);
    if (csv)
        fclose(csv);
    if (csv_name)
        ctv_plot(csv_name, "TYPE6 knee bolster: force against penetration",
             "knee penetration (mm)", "interface force (N)",
             "1,2,points,loading (simulated);1,3,points,unloading (simulated);"
             "1,4,linespoints,input curve",
             "");

    /* The crush depth where the curve's work equals M v0^2 / 2 (bisection
     * on the exact integral of the table). */
    double ek = 0.5 * M * v0 * v0, lo = 0, hi = f->curve[f->curve_count - 1][0];
    cr_assert(curve_work(f, hi) > ek, "the curve ends before the knee stops");
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (curve_work(f, mid) < ek)
            lo = mid;
        else
            hi = mid;
    }
    double pstop = 0.5 * (lo + hi);
    double e_rest = r.h[r.n - 1].vc[0][2] / v0;

    double e2 = fabs(pmax - pstop) / pstop, e3 = fabs(e_rest - 1.0);
    if (csv_name) {
        char note[200];
        snprintf(note, sizeof note,
                 "data/scenes/knee-bolster.yaml as is: %d loading and %d unloading samples, "
                 "largest error at p = %.3g mm",
                 nload, nunload, 1e3 * pmax_err);
        ctv_result("type6_knee", "largest |F - f(p)| / f(p) on the path", err_max, 0, TOL,
                   note);
        e2 = ctv_result("type6_knee", "crush depth (m)", pmax, pstop, TOL,
                        "where the curve's work is M v0^2 / 2");
        e3 = ctv_result("type6_knee", "restitution", e_rest, 1.0, TOL,
                        "elastic curve: the knee leaves at its impact speed");
    }
    cr_expect(nload >= 5 && nunload >= 5, "%d loading and %d unloading samples", nload,
              nunload);
    cr_expect(err_max <= TOL, "the path leaves the curve by %.3e at p = %.4g m", err_max,
              pmax_err);
    cr_expect(e2 <= TOL, "crush %.5g m against %.5g m", pmax, pstop);
    cr_expect(e3 <= TOL, "restitution %.6f", e_rest);
    rv_free(&r);
}

Test(validation_rigid, type6_knee_bolster_curve) { knee_bolster_curve(1, 0, "rigid_knee"); }

/* Refined 3 times (4083 nodes): the search reaches only the largest
 * penetration of the last step and two margins, and keeps a node's pairs
 * within two margins of its closest (iface_pass.c, type6.c); the pairs must
 * still hold the pole at every step, or the force would leave the curve.
 * Thrown sideways too (3 m/s, some 40 mm over the plate's cells during the
 * crush): the nodes' closest segments change between searches. */
Test(validation_rigid, type6_knee_bolster_curve_refined)
{
    knee_bolster_curve(3, 0, NULL);
    knee_bolster_curve(3, 3.0, NULL);
}
