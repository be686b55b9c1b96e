/*
 * test_validation_rigid_balls.c -- validation case 4 (issue 6): two free
 * rigid balls of unequal masses (0.27 kg and 0.98 kg) collide, head on and
 * obliquely, through TYPE6 with a linear curve F = k p (k = 1e6 N/m,
 * undamped). The scene (tests/data/validation/rigid_balls.yaml) is built so
 * that the effective stiffness is k exactly: TYPE6's total force is the
 * curve at the largest penetration, and the only node that touches is A's
 * pole, on B's flat top quad (normal +z, through A's centre).
 *
 * Reference (smooth spheres, Newton's impact law; e.g. Goldsmith, Impact,
 * Arnold 1960, chapter 2; with a linear spring the impact is a half period
 * of the two-body oscillator):
 *   along the normal n = +z, with u = v.n:
 *     u_A' = ((m_A - m_B) u_A + (1 + e) m_B u_B) / (m_A + m_B), e = 1,
 *     u_B' = ((m_B - m_A) u_B + (1 + e) m_A u_A) / (m_A + m_B);
 *   tangential components unchanged (no friction, the force is along n);
 *   contact duration t_c = pi sqrt(m* / k), m* = m_A m_B / (m_A + m_B);
 *   total momentum conserved exactly (no external force).
 * In the oblique impact A slides 1.2 mm across B's top quad during the
 * contact; its start is placed so that the contact point passes B's axis at
 * mid-contact, and B's rotation (from the off-axis force) is measured.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "test_validation_rigid.h"

#define KCURVE 1.0e6 /* the curve's slope (N/m) */
#define PI 3.14159265358979323846

/* Post-impact velocities and contact time: 0.5 % (of the approach speed
 * for velocities) in double and single. Momentum: 1e-12 relative in
 * double (round-off over a few hundred steps), 1e-6 in single (the nodal
 * forces are float there: each step's action and reaction differ by a
 * float rounding of the shape-function split). */
#define TOL CTT_TOL(5e-3, 5e-3)
#define MOM_TOL CTT_TOL(1e-12, 1e-6)

/* The contact gap: A's pole above the plane of B's top quad, the plane
 * turned with B (R R0^T e_z) and z_top above B's centre. */
static double contact_gap(const rv_sample *q, const double R0[9], double z_top)
{
    /* n = R R0^T e_z: R0^T e_z is R0's third row. */
    double a[3] = {R0[6], R0[7], R0[8]}, n[3];
    for (int i = 0; i < 3; i++)
        n[i] = q->R[1][3 * i] * a[0] + q->R[1][3 * i + 1] * a[1] + q->R[1][3 * i + 2] * a[2];
    double g = 0;
    for (int d = 0; d < 3; d++)
        g += (q->xn[0][d] - q->xc[1][d]) * n[d];
    return g - z_top;
}

static void two_balls(const char *casename, double vx, double vz)
{
    rv_run r;
    rv_load(&r, "tests/data/validation/rigid_balls.yaml");
    rv_build(&r);
    int A = rv_body_of_part(&r, 2), B = rv_body_of_part(&r, 1);
    const double mA = r.m.body[A].rigid.mass, mB = r.m.body[B].rigid.mass;
    const double ms = mA * mB / (mA + mB);
    const double tc = PI * sqrt(ms / KCURVE);
    ct_idx poleA = rv_extreme_node(&r, 2, 2, -1), topB = rv_extreme_node(&r, 1, 2, +1);
    const double z_top = r.m.mesh.nodes.z[topB] - r.m.body[B].rigid.xc[2];
    const double d0 = r.m.mesh.nodes.z[poleA] - r.m.mesh.nodes.z[topB];
    cr_assert(d0 > 0 && fabs(r.m.mesh.nodes.x[poleA]) < 1e-12);
    ctd_model_destroy(&r.m);
    r.built = 0;
    /* A's start: moved sideways so that its pole passes B's axis at
     * mid-contact; its velocity (vx, 0, -vz). */
    r.sc->mesh[1].generate->origin[0] = -vx * (d0 / vz + tc / 2);
    double *v = r.sc->boundary[0].value;
    v[0] = vx;
    v[1] = 0;
    v[2] = -vz;
    rv_build(&r);

    /* The step: TYPE6's own, 0.9 x 0.1 sqrt(M_min / K), from the start (the
     * output interval caps it before contact, where TYPE6 sets none). */
    ctd_solver_opts o = ctd_solver_default_opts();
    o.every = r.sc->solver->dt_scale * 0.1 * sqrt(fmin(mA, mB) / KCURVE);
    o.end_time = d0 / vz + 1.5 * tc;
    r.nb = 2;
    r.body[0] = A;
    r.body[1] = B;
    r.track[0] = poleA;
    r.track[1] = -1;
    rv_run_solver(&r, o);

    /* Contact from the gap's crossings. */
    size_t n = r.n;
    double *t = malloc(n * sizeof *t), *g = malloc(n * sizeof *g);
    cr_assert(t && g);
    for (size_t k = 0; k < n; k++) {
        t[k] = r.h[k].t;
        g[k] = -contact_gap(&r.h[k], r.h[0].R[1], z_top);
    }
    size_t k_in = 0, k_out = 0;
    double t_in = rv_crossing(t, g, n, 0, +1, &k_in);
    double t_out = t_in >= 0 ? rv_crossing(t, g, n, k_in, -1, &k_out) : -1;
    cr_assert(t_in >= 0 && t_out > t_in, "no complete contact");
    double tc_sim = t_out - t_in;
    int64_t act = 0;
    for (size_t k = 0; k < n; k++)
        act = r.h[k].active > act ? r.h[k].active : act;
    cr_expect_eq(act, 1, "%s: %lld pairs active at once: the stiffness is not k", casename,
                 (long long)act);

    /* The references. */
    const double uA = -vz, uB = 0;
    const double vA_ref[3] = {vx, 0, ((mA - mB) * uA + 2 * mB * uB) / (mA + mB)};
    const double vB_ref[3] = {0, 0, ((mB - mA) * uB + 2 * mA * uA) / (mA + mB)};
    const rv_sample *end = &r.h[n - 1];
    double eA = 0, eB = 0;
    for (int d = 0; d < 3; d++) {
        eA = fmax(eA, fabs(end->vc[0][d] - vA_ref[d]) / vz);
        eB = fmax(eB, fabs(end->vc[1][d] - vB_ref[d]) / vz);
    }
    /* Restitution along n from the bodies' normal velocities. */
    double e_sim = (end->vc[1][2] - end->vc[0][2]) / (uA - uB);
    double p1[3], pref = 0, perr = 0;
    ctd_solver_momentum(&r.s, p1);
    for (int d = 0; d < 3; d++) {
        pref = fmax(pref, fabs(r.p0[d]));
        perr = fmax(perr, fabs(p1[d] - r.p0[d]));
    }
    perr /= pref;
    /* B's spin after the impact, as a surface speed against the approach
     * speed. */
    const double *om = r.m.body[B].rigid.omega;
    double spin = sqrt(om[0] * om[0] + om[1] * om[1] + om[2] * om[2]) *
                  r.sc->mesh[0].generate->radius / vz;

    /* Curves: the normal force with the linear-spring half sine. */
    char name[64];
    snprintf(name, sizeof name, "rigid_balls_%s", casename);
    FILE *f = ctv_csv(name, "t_ms,F_sim,F_ref,vAz_sim,vBz_sim");
    const double w = sqrt(KCURVE / ms);
    for (size_t k = 0; k < n; k++) {
        double s = t[k] - t_in;
        double fr = s > 0 && s < tc ? ms * vz * w * sin(w * s) : 0;
        ctv_row(f, 5, 1e3 * t[k], r.h[k].f[2], fr, r.h[k].vc[0][2], r.h[k].vc[1][2]);
    }
    if (f)
        fclose(f);
    char title[160];
    snprintf(title, sizeof title, "Two rigid balls, %s impact (TYPE6, linear curve): normal force",
             casename);
    ctv_plot(name, title, "time (ms)", "contact force on A, z (N)",
             "1,2,points,simulated;1,3,lines,k p of the two-body spring (half sine)", "");

    char note[256], q[96];
    snprintf(note, sizeof note,
             "m_A %.4g kg, m_B %.4g kg, k %.3g N/m, v_A (%.3g, 0, %.3g) m/s, dt %.3g "
             "(omega dt %.3f)",
             mA, mB, KCURVE, vx, -vz, r.h[k_in].dt, w * r.h[k_in].dt);
    char cn[64];
    snprintf(cn, sizeof cn, "two_balls_%s", casename);
    snprintf(q, sizeof q, "velocity of A after (error / approach speed)");
    ctv_result(cn, q, eA, 0, TOL, note);
    snprintf(q, sizeof q, "velocity of B after (error / approach speed)");
    ctv_result(cn, q, eB, 0, TOL, note);
    double e1 = ctv_result(cn, "restitution along n", e_sim, 1.0, TOL, note);
    double e2 = ctv_result(cn, "contact time (s)", tc_sim, tc, TOL, note);
    ctv_result(cn, "momentum change / |p0|", perr, 0, MOM_TOL, note);
    ctv_result(cn, "spin of B after: omega R / v", spin, 0, 0, note);
    cr_expect(eA <= TOL, "%s: A leaves at (%.6g, %.6g, %.6g), expected (%.6g, %.6g, %.6g)",
              casename, end->vc[0][0], end->vc[0][1], end->vc[0][2], vA_ref[0], vA_ref[1],
              vA_ref[2]);
    cr_expect(eB <= TOL, "%s: B leaves at (%.6g, %.6g, %.6g), expected (%.6g, %.6g, %.6g)",
              casename, end->vc[1][0], end->vc[1][1], end->vc[1][2], vB_ref[0], vB_ref[1],
              vB_ref[2]);
    cr_expect(e1 <= TOL, "%s: restitution %.6g", casename, e_sim);
    cr_expect(e2 <= TOL, "%s: contact time %.6g s against %.6g s", casename, tc_sim, tc);
    cr_expect(perr <= MOM_TOL, "%s: momentum changed by %.3e of |p0|", casename, perr);
    free(t);
    free(g);
    rv_free(&r);
}

Test(validation_rigid, two_balls_head_on)
{
    two_balls("head_on", 0, 0.5);
}

Test(validation_rigid, two_balls_oblique)
{
    two_balls("oblique", 1.0, 0.5);
}
