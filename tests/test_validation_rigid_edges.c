/*
 * test_validation_rigid_edges.c -- validation case 10 (issue 6): edge to
 * edge contact (TYPE11) of two crossed rigid rods of unequal masses
 * (tests/data/validation/rigid_rods.yaml: rods along e1 = x and e2 = (0,
 * cos 30, sin 30), meeting at their midpoints along n = e1 x e2 / |e1 x e2|,
 * the upper one moving along -n at 2 m/s).
 *
 * References:
 *  - the edge-edge force acts along e1 x e2 (seed 002, Figure 9: the
 *    closest points of two crossing segments differ along their common
 *    normal);
 *  - the TYPE7 law of TYPE11 with Istf 1 (K0 = Stfac): F = K0 g p / (g - p),
 *    stored energy K0 g^2 phi(x), phi(x) = -x - ln(1 - x), x = p / g,
 *    g = r1 + r2 (the rods' radii sqrt(A / pi), their node gaps);
 *  - so the deepest penetration p_max solves m* V^2 / 2 = K0 g^2 phi(p/g)
 *    (m* the reduced mass, V the normal approach speed), and the distance
 *    of the rods' axes never goes below g - p, with p = F g / (K0 g + F)
 *    the penetration the force implies;
 *  - undamped (VisS 0): restitution 1; with the force through both centres
 *    of mass the normal velocities follow the 1D impact of two masses and
 *    the tangential ones are unchanged; momentum is conserved exactly.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "test_validation_rigid.h"

#define PI 3.14159265358979323846

/* Velocities, restitution and the crush depth: 0.5 % in double and single.
 * The force's direction, and its distance from the law at the penetration
 * read from the positions (against the peak force): 1e-9 in double
 * (round-off), 1e-3 in single (float positions carry about 4e-9 m of
 * round-off: 5e-4 N of force at the law's stiffness, 2e-5 of the peak).
 * Momentum: 1e-12 relative in double, 1e-6 in single. */
#define TOL CTT_TOL(5e-3, 5e-3)
#define TOL_LAW CTT_TOL(1e-9, 1e-3)
#define MOM_TOL CTT_TOL(1e-12, 1e-6)

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void unit(double a[3])
{
    double l = sqrt(dot(a, a));
    for (int d = 0; d < 3; d++)
        a[d] /= l;
}

/* The common normal of the rods at sample q (from the lower rod to the
 * upper one) and the distance of their axes along it. */
static double rods_normal(const rv_sample *q, double n[3])
{
    double e1[3], e2[3], c[3];
    for (int d = 0; d < 3; d++) {
        e1[d] = q->xn[0][d] - q->xc[0][d];
        e2[d] = q->xn[1][d] - q->xc[1][d];
        c[d] = q->xc[1][d] - q->xc[0][d];
    }
    cross(e1, e2, n);
    unit(n);
    double s = dot(c, n);
    if (s < 0) {
        for (int d = 0; d < 3; d++)
            n[d] = -n[d];
        s = -s;
    }
    return s;
}

static double phi7(double x)
{
    return -x - log1p(-x);
}

Test(validation_rigid, edge_to_edge_crossed_rods)
{
    rv_run r;
    rv_load(&r, "tests/data/validation/rigid_rods.yaml");
    rv_build(&r);
    const int lo = rv_body_of_part(&r, 1), up = rv_body_of_part(&r, 2);
    const double m1 = r.m.body[lo].rigid.mass, m2 = r.m.body[up].rigid.mass;
    const double ms = m1 * m2 / (m1 + m2);
    const double g = sqrt(ctd_scene_part_by_id(r.sc, 1)->area / PI) +
                     sqrt(ctd_scene_part_by_id(r.sc, 2)->area / PI);
    const double K0 = r.sc->interfaces[0].Stfac;
    cr_assert_eq(r.sc->interfaces[0].Istf, 1);
    cr_assert_eq(r.sc->interfaces[0].VisS, 0);
    r.nb = 2;
    r.body[0] = lo;
    r.body[1] = up;
    r.track[0] = rv_extreme_node(&r, 1, 0, +1);
    r.track[1] = rv_extreme_node(&r, 2, 1, +1);
    double v1[3], v2[3];
    for (int d = 0; d < 3; d++) {
        v1[d] = r.m.body[lo].rigid.vc[d];
        v2[d] = r.m.body[up].rigid.vc[d];
    }
    rv_run_solver(&r, ctd_solver_default_opts());
    cr_assert(r.n > 2);

    /* The normal at the start, the approach speed, the references. */
    double n0[3];
    double d0 = rods_normal(&r.h[0], n0);
    cr_assert(d0 > g, "the rods start in contact");
    const double u1 = dot(v1, n0), u2 = dot(v2, n0), V = u1 - u2;
    cr_assert(V > 0);
    const double u1r = ((m1 - m2) * u1 + 2 * m2 * u2) / (m1 + m2);
    const double u2r = ((m2 - m1) * u2 + 2 * m1 * u1) / (m1 + m2);
    double v1r[3], v2r[3];
    for (int d = 0; d < 3; d++) {
        v1r[d] = v1[d] + (u1r - u1) * n0[d];
        v2r[d] = v2[d] + (u2r - u2) * n0[d];
    }
    /* p_max from the energy: bisection on phi(x) = m* V^2 / (2 K0 g^2). */
    double target = 0.5 * ms * V * V / (K0 * g * g), xa = 0, xb = 1 - 1e-12;
    for (int it = 0; it < 200; it++) {
        double xm = 0.5 * (xa + xb);
        if (phi7(xm) < target)
            xa = xm;
        else
            xb = xm;
    }
    const double pmax_ref = g * 0.5 * (xa + xb);

    /* The run, sample by sample. */
    FILE *ff = ctv_csv("rigid_rods_force", "p_mm,F_sim,F_law");
    FILE *fd = ctv_csv("rigid_rods_distance", "t_ms,d_mm,g_mm,g_minus_pmax_mm");
    double dmin = INFINITY, fmax_n = 0, dir_err = 0, law_err = 0;
    int ncontact = 0, pushes_apart = 1;
    for (size_t k = 0; k < r.n; k++) {
        const rv_sample *q = &r.h[k];
        double n[3];
        double d = rods_normal(q, n), p = g - d;
        double F = sqrt(dot(q->f, q->f));
        dmin = fmin(dmin, d);
        ctv_row(fd, 4, 1e3 * q->t, 1e3 * d, 1e3 * g, 1e3 * (g - pmax_ref));
        if (!(F > 0)) {
            cr_expect(p <= 0, "no force at t = %g with p = %g", q->t, p);
            continue;
        }
        ncontact++;
        double fn = dot(q->f, n), c[3];
        cross(q->f, n, c);
        dir_err = fmax(dir_err, sqrt(dot(c, c)) / F);
        pushes_apart &= fn < 0; /* the force on the lower rod (edge set A) */
        double Flaw = p > 0 ? K0 * g * p / (g - p) : 0;
        law_err = fmax(law_err, fabs(F - Flaw));
        fmax_n = fmax(fmax_n, F);
        ctv_row(ff, 3, 1e3 * p, F, Flaw);
    }
    /* The law's curve over the range, for the plot. */
    for (int i = 0; i <= 40 && ff; i++) {
        double p = 1.1 * pmax_ref * i / 40;
        ctv_row(ff, 3, 1e3 * p, NAN, K0 * g * p / (g - p));
    }
    if (ff)
        fclose(ff);
    if (fd)
        fclose(fd);
    ctv_plot("rigid_rods_force", "Crossed rigid rods (TYPE11): force against penetration",
             "penetration g - d (mm)", "edge-edge force (N)",
             "1,2,points,simulated;1,3,lines,TYPE7 law K0 g p / (g - p)", "");
    ctv_plot("rigid_rods_distance", "Crossed rigid rods (TYPE11): distance of the axes",
             "time (ms)", "distance (mm)",
             "1,2,lines,simulated;1,3,dashed,gap r1 + r2;1,4,dashed,gap - pmax (energy)", "");

    law_err /= fmax_n;
    const double p_F = fmax_n * g / (K0 * g + fmax_n);
    const rv_sample *end = &r.h[r.n - 1];
    double e1 = 0, e2 = 0;
    for (int d = 0; d < 3; d++) {
        e1 = fmax(e1, fabs(end->vc[0][d] - v1r[d]) / V);
        e2 = fmax(e2, fabs(end->vc[1][d] - v2r[d]) / V);
    }
    double restitution = (dot(end->vc[0], n0) - dot(end->vc[1], n0)) / -V;
    double p1[3], pref = 0, perr = 0;
    ctd_solver_momentum(&r.s, p1);
    for (int d = 0; d < 3; d++) {
        pref = fmax(pref, fabs(r.p0[d]));
        perr = fmax(perr, fabs(p1[d] - r.p0[d]));
    }
    perr /= pref;
    double spin = 0;
    for (int b = 0; b < 2; b++) {
        const double *om = r.m.body[r.body[b]].rigid.omega;
        spin = fmax(spin, sqrt(dot(om, om)) * 0.05 / V);
    }

    char note[256];
    snprintf(note, sizeof note,
             "rods of 9 segments, m %.4g and %.4g kg, g %.4g mm, K0 %.3g N/m, V %.3g m/s, "
             "dt %.3g s",
             m1, m2, 1e3 * g, K0, V, r.h[1].dt);
    ctv_result("rods_type11", "force direction: |F x n| / |F|", dir_err, 0, TOL_LAW, note);
    ctv_result("rods_type11", "|F - law(p)| / F_max at the measured p", law_err, 0, TOL_LAW,
               note);
    double ep = ctv_result("rods_type11", "deepest penetration (m)", g - dmin, pmax_ref, TOL,
                           note);
    ctv_result("rods_type11", "min distance - (g - p(F_max)) (m)", dmin - (g - p_F), 0, 0, note);
    double er = ctv_result("rods_type11", "restitution", restitution, 1.0, TOL, note);
    ctv_result("rods_type11", "velocity of the lower rod (error / V)", e1, 0, TOL, note);
    ctv_result("rods_type11", "velocity of the upper rod (error / V)", e2, 0, TOL, note);
    ctv_result("rods_type11", "momentum change / |p0|", perr, 0, MOM_TOL, note);
    ctv_result("rods_type11", "spin after: omega L/2 / V", spin, 0, 0, note);
    cr_expect(ncontact >= 10, "%d samples in contact", ncontact);
    cr_expect(dir_err <= TOL_LAW, "the force leaves e1 x e2 by %.3e", dir_err);
    cr_expect(pushes_apart, "the force does not push the rods apart");
    cr_expect(law_err <= TOL_LAW, "force off the law by %.3e", law_err);
    cr_expect(dmin >= g - p_F * (1 + TOL_LAW), "distance %.9g below g - p(F_max) = %.9g", dmin,
              g - p_F);
    cr_expect(ep <= TOL, "deepest penetration %.6g against %.6g", g - dmin, pmax_ref);
    cr_expect(er <= TOL, "restitution %.6g", restitution);
    cr_expect(e1 <= TOL && e2 <= TOL, "velocities off by %.3e and %.3e of V", e1, e2);
    cr_expect(perr <= MOM_TOL, "momentum changed by %.3e", perr);
    rv_free(&r);
}
