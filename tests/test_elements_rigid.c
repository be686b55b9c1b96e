/*
 * test_elements_rigid.c -- rigid bodies: mass properties and force/moment
 * assembly by hand, steady spin about a principal axis, and conservation
 * of energy, angular momentum and shape by a torque-free asymmetric body.
 */
#include <string.h>

#include "elements/elements.h"
#include "test_util.h"

/* 8 point masses of 2 at the corners (+-1, +-2, +-3) around (1, 2, 3). */
static void box8(ct_nodes *nd)
{
    cr_assert_eq(ct_nodes_init(nd, 8), CT_OK);
    for (int a = 0; a < 8; a++) {
        nd->x[a] = 1 + ((a & 1) ? 1 : -1);
        nd->y[a] = 2 + ((a & 2) ? 2 : -2);
        nd->z[a] = 3 + ((a & 4) ? 3 : -3);
        nd->m[a] = 2;
    }
}

static const ct_idx ALL8[8] = {0, 1, 2, 3, 4, 5, 6, 7};

Test(elements_rigid, mass_centre_inertia_by_hand)
{
    ct_nodes nd;
    box8(&nd);
    ctd_rigid r;
    cr_assert_eq(ctd_rigid_init(&r, 8, ALL8, 8, nd.m, nd.x, nd.y, nd.z, NULL, NULL, NULL),
                 CT_OK);
    cr_assert(ctt_rel(r.mass, 16) < 1e-15);
    cr_assert(fabs(r.xc[0] - 1) < 1e-14 && fabs(r.xc[1] - 2) < 1e-14 &&
              fabs(r.xc[2] - 3) < 1e-14);
    /* Ixx = 16 (2^2 + 3^2) = 208, Iyy = 16 (1 + 9) = 160, Izz = 16 (1 + 4)
     * = 80, no products of inertia. */
    double J[9], want[9] = {208, 0, 0, 0, 160, 0, 0, 0, 80};
    ctd_rigid_inertia_world(&r, J);
    for (int k = 0; k < 9; k++)
        cr_assert(fabs(J[k] - want[k]) < 1e-12 * 208, "J[%d] = %g", k, J[k]);
    ctd_rigid_destroy(&r);
    /* The same box turned by 90 degrees about z: (x, y) -> (-y, x) about the
     * centre, so Ixx and Iyy swap. Plus one extra mass of 4 at the centre
     * + (1, 1, 0): the centre moves by (4/20)(1, 1, 0) and the tensor
     * gains products of inertia; compute the parallel-axis sums by hand:
     * M = 20, c = (1.2, 2.2, 3). */
    ct_nodes nd2;
    cr_assert_eq(ct_nodes_init(&nd2, 9), CT_OK);
    for (int a = 0; a < 8; a++) {
        nd2.x[a] = 1 - (nd.y[a] - 2);
        nd2.y[a] = 2 + (nd.x[a] - 1);
        nd2.z[a] = nd.z[a];
        nd2.m[a] = 2;
    }
    nd2.x[8] = 2, nd2.y[8] = 3, nd2.z[8] = 3, nd2.m[8] = 4;
    ct_idx all9[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    cr_assert_eq(ctd_rigid_init(&r, 9, all9, 9, nd2.m, nd2.x, nd2.y, nd2.z, NULL, NULL, NULL),
                 CT_OK);
    cr_assert(fabs(r.xc[0] - 1.2) < 1e-14 && fabs(r.xc[1] - 2.2) < 1e-14);
    /* About the old centre: box diag(160, 208, 80) plus the point mass
     * 4 (|d|^2 I - d d^T), d = (1, 1, 0): +(4, 4, 8), xy -4. Shift to the
     * new centre: minus M (|s|^2 I - s s^T), s = (0.2, 0.2, 0):
     * -20 (0.04, 0.04, 0.08), xy +0.8. */
    double w2[9] = {160 + 4 - 0.8, -4 + 0.8, 0, -4 + 0.8, 208 + 4 - 0.8, 0, 0, 0, 80 + 8 - 1.6};
    ctd_rigid_inertia_world(&r, J);
    for (int k = 0; k < 9; k++)
        cr_assert(fabs(J[k] - w2[k]) < 1e-12 * 212, "J[%d] = %.15g vs %.15g", k, J[k], w2[k]);
    ctd_rigid_destroy(&r);
    ct_nodes_destroy(&nd2);
    ct_nodes_destroy(&nd);
}

Test(elements_rigid, force_and_moment_by_hand)
{
    ct_nodes nd;
    box8(&nd);
    ctd_rigid r;
    cr_assert_eq(ctd_rigid_init(&r, 8, ALL8, 8, nd.m, nd.x, nd.y, nd.z, NULL, NULL, NULL),
                 CT_OK);
    /* Node 7 at c + (1, 2, 3) gets (0, 0, 1): moment (2, -1, 0).
     * Node 4 at c + (-1, -2, 3) gets (1, 0, 0): moment (0, 3, 2). */
    nd.fz[7] = 1;
    nd.fx[4] = 1;
    ctd_rigid_clear(&r);
    ctd_rigid_accumulate(&r, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz);
    const double F[3] = {1, 0, 1}, T[3] = {2, 2, 2};
    for (int d = 0; d < 3; d++) {
        cr_assert(fabs(r.F[d] - F[d]) < 1e-14);
        cr_assert(fabs(r.tau[d] - T[d]) < 1e-14, "tau%d %g", d, r.tau[d]);
    }
    /* One step from rest: v = dt F / M, L = dt tau. */
    cr_assert_eq(ctd_rigid_advance(&r, 0.5), CT_OK);
    for (int d = 0; d < 3; d++) {
        cr_assert(fabs(r.vc[d] - 0.5 * F[d] / 16) < 1e-15);
        cr_assert(fabs(r.L[d] - 0.5 * T[d]) < 1e-15);
        cr_assert(fabs(r.xc[d] - (1 + d) - 0.25 * F[d] / 16) < 1e-14);
    }
    ctd_rigid_destroy(&r);
    ct_nodes_destroy(&nd);
}

/* Largest relative change of the pairwise node distances. */
static double shape_error(const ct_nodes *a, const ct_nodes *b)
{
    double e = 0;
    for (int i = 0; i < a->n; i++)
        for (int j = i + 1; j < a->n; j++) {
            double d0 = hypot(hypot(a->x[i] - a->x[j], a->y[i] - a->y[j]), a->z[i] - a->z[j]);
            double d1 = hypot(hypot(b->x[i] - b->x[j], b->y[i] - b->y[j]), b->z[i] - b->z[j]);
            e = fmax(e, fabs(d1 - d0) / d0);
        }
    return e;
}

Test(elements_rigid, spin_about_principal_axis)
{
    ct_nodes nd;
    box8(&nd);
    ctd_rigid r;
    cr_assert_eq(ctd_rigid_init(&r, 8, ALL8, 8, nd.m, nd.x, nd.y, nd.z, NULL, NULL, NULL),
                 CT_OK);
    const double v[3] = {0.5, 0, -1}, w[3] = {0, 0, 5}; /* z is principal (Izz = 80) */
    ctd_rigid_set_velocity(&r, v, w);
    const double dt = 1e-3;
    const int steps = 1000;
    for (int s = 0; s < steps; s++) {
        ctd_rigid_clear(&r);
        cr_assert_eq(ctd_rigid_advance(&r, dt), CT_OK);
    }
    for (int d = 0; d < 3; d++)
        cr_assert(fabs(r.omega[d] - w[d]) < 1e-12 * 5, "omega%d %.17g", d, r.omega[d]);
    /* Node kinematics: positions rigid, velocities v + w x r. */
    ct_nodes moved;
    cr_assert_eq(ct_nodes_init(&moved, 8), CT_OK);
    ctd_rigid_set_nodes(&r, moved.x, moved.y, moved.z, moved.vx, moved.vy, moved.vz);
    cr_assert(shape_error(&nd, &moved) < CTT_TOL(1e-13, 1e-6));
    /* The angle turned: each step is the Cayley rotation of angle
     * 2 atan(w dt / 2) about z, within (w dt)^3 / 12 of w dt. Node 7's
     * offset (1, 2, 3) from the centre has turned by it. */
    double rx = moved.x[7] - r.xc[0], ry = moved.y[7] - r.xc[1];
    double ang = atan2(1 * ry - 2 * rx, 1 * rx + 2 * ry);
    double want = remainder(steps * 2 * atan(5 * dt / 2), 2 * 3.14159265358979323846);
    cr_assert(fabs(ang - want) < CTT_TOL(1e-12, 1e-5), "angle %.15g vs %.15g", ang, want);
    cr_assert(fabs(steps * 2 * atan(5 * dt / 2) - 5.0) < 2e-5); /* 1000 (w dt)^3 / 12 = 1.04e-5 */
    cr_assert(fabs(moved.z[7] - r.xc[2] - 3) < CTT_TOL(1e-12, 1e-5));
    for (int a = 0; a < 8; a++) {
        double rx = moved.x[a] - r.xc[0], ry = moved.y[a] - r.xc[1];
        cr_assert(fabs(moved.vx[a] - (v[0] - 5 * ry)) < CTT_TOL(1e-12, 1e-5));
        cr_assert(fabs(moved.vy[a] - (v[1] + 5 * rx)) < CTT_TOL(1e-12, 1e-5));
        cr_assert(fabs(moved.vz[a] - v[2]) < CTT_TOL(1e-12, 1e-5));
    }
    cr_assert(fabs(r.xc[2] - (3 - steps * dt)) < 1e-12);
    ct_nodes_destroy(&moved);
    ctd_rigid_destroy(&r);
    ct_nodes_destroy(&nd);
}

Test(elements_rigid, torque_free_asymmetric_body_conserves)
{
    /* Seven unequal masses at irregular positions: all three principal
     * moments differ; spin mostly about the intermediate axis plus a
     * perturbation (the tumbling case). */
    const double P[7][4] = {{1.0, 0.3, -0.2, 0.1},  {2.0, -1.1, 0.4, 0.7},
                            {0.5, 0.9, 1.3, -0.4},  {1.5, 0.2, -1.0, -0.9},
                            {3.0, -0.5, -0.6, 0.2}, {0.7, 1.4, 0.1, 0.8},
                            {1.2, -0.3, 0.9, -1.2}};
    ct_nodes nd;
    cr_assert_eq(ct_nodes_init(&nd, 7), CT_OK);
    for (int a = 0; a < 7; a++) {
        nd.m[a] = P[a][0];
        nd.x[a] = P[a][1];
        nd.y[a] = P[a][2];
        nd.z[a] = P[a][3];
        /* Initial velocities from a spin plus noise (made rigid by the
         * body's own projection: L from the nodes). */
        nd.vx[a] = 0.3 - 2.0 * nd.z[a] + 0.5 * nd.y[a];
        nd.vy[a] = -0.1 + 1.0 * nd.z[a];
        nd.vz[a] = 0.2 + 2.0 * nd.x[a] - 1.0 * nd.x[a] * 0.3;
    }
    ct_idx all[7] = {0, 1, 2, 3, 4, 5, 6};
    ctd_rigid r;
    cr_assert_eq(ctd_rigid_init(&r, 7, all, 7, nd.m, nd.x, nd.y, nd.z, nd.vx, nd.vy, nd.vz),
                 CT_OK);
    cr_assert(fabs(r.I[0] - r.I[1]) > 0.1 && fabs(r.I[1] - r.I[2]) > 0.1 &&
              fabs(r.I[0] - r.I[2]) > 0.1);
    double e0 = ctd_rigid_kinetic(&r), p0[3], L0[3];
    ctd_rigid_momentum(&r, p0, L0);
    double wn = sqrt(r.omega[0] * r.omega[0] + r.omega[1] * r.omega[1] +
                     r.omega[2] * r.omega[2]);
    const double dt = 2e-3 / wn; /* |omega| dt = 2e-3 */
    const int steps = ctt_checking() ? 2000 : 10000;
    double emax = 0, lmax = 0, Lnorm = sqrt(L0[0] * L0[0] + L0[1] * L0[1] + L0[2] * L0[2]);
    int maxit = 0;
    for (int s = 0; s < steps; s++) {
        ctd_rigid_clear(&r);
        cr_assert_eq(ctd_rigid_advance(&r, dt), CT_OK);
        maxit = r.iters > maxit ? r.iters : maxit;
        double L[3];
        ctd_rigid_momentum(&r, NULL, L);
        emax = fmax(emax, fabs(ctd_rigid_kinetic(&r) - e0) / e0);
        for (int d = 0; d < 3; d++)
            lmax = fmax(lmax, fabs(L[d] - L0[d]) / Lnorm);
    }
    cr_log_info("rigid torque-free: %d steps, energy %.3g, L %.3g, iterations <= %d", steps,
                emax, lmax, maxit);
    cr_assert(emax < 1e-9, "energy drift %g", emax);
    cr_assert(lmax < 1e-9, "angular momentum drift %g", lmax);
    /* It did tumble: the body-frame angular velocity changed direction. */
    ct_nodes moved;
    cr_assert_eq(ct_nodes_init(&moved, 7), CT_OK);
    ctd_rigid_set_nodes(&r, moved.x, moved.y, moved.z, moved.vx, moved.vy, moved.vz);
    double se = shape_error(&nd, &moved);
    cr_assert(se < CTT_TOL(1e-12, 1e-6), "shape error %g", se);
    /* The nodes' momentum equals the body's. */
    double p[3] = {0, 0, 0};
    for (int a = 0; a < 7; a++) {
        p[0] += nd.m[a] * moved.vx[a];
        p[1] += nd.m[a] * moved.vy[a];
        p[2] += nd.m[a] * moved.vz[a];
    }
    for (int d = 0; d < 3; d++)
        cr_assert(fabs(p[d] - p0[d]) < CTT_TOL(1e-12, 1e-5) * (1 + fabs(p0[d])));
    ct_nodes_destroy(&moved);
    ctd_rigid_destroy(&r);
    ct_nodes_destroy(&nd);
}
