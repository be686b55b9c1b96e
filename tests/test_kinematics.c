/*
 * test_kinematics.c -- ct_relative_velocity_edge (suite kinematics): the
 * relative velocity of two edges at their closest points, against a hand
 * case and against a rigid rotation, where it must be w x (Pa - Pb); its
 * optional outputs, thread independence and argument checks. (The
 * node-segment kernel's tests are in test_penalty.c.)
 */
#include <stdint.h>

#include "test_util.h"

static double kin_rand01(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * 0x1p-53;
}

Test(kinematics, edge_hand_case_and_arguments)
{
    /* Edge A = nodes 0-1 at sa = 0.25, edge B = nodes 2-3 at sb = 0.5.
     * v(Pa) = 0.75 (1, 0, 2) + 0.25 (5, 4, -2) = (2, 1, 1);
     * v(Pb) = 0.5 (0, 2, 0) + 0.5 (-2, 0, 4) = (-1, 1, 2);
     * u = (3, 0, -1); n = (0.6, 0, 0.8): vn = 1.8 - 0.8 = 1; u.u = 10;
     * masses 0.75 * 1 + 0.25 * 3 = 1.5 and 0.5 * 2 + 0.5 * 6 = 4. */
    ct_real vx[4] = {1, 5, 0, -2}, vy[4] = {0, 4, 2, 0}, vz[4] = {2, -2, 0, 4};
    ct_real m[4] = {1, 3, 2, 6};
    ct_idx a1[1] = {0}, a2[1] = {1}, b1[1] = {2}, b2[1] = {3};
    ct_real sa[1] = {0.25}, sb[1] = {0.5}, nx[1] = {0.6}, ny[1] = {0}, nz[1] = {0.8};
    ct_real rx[1], ry[1], rz[1], vn[1], u2[1], ma[1], mb[1];
    cr_assert_eq(ct_relative_velocity_edge(1, a1, a2, b1, b2, sa, sb, nx, ny, nz, vx, vy, vz, m,
                                           rx, ry, rz, vn, u2, ma, mb),
                 CT_OK);
    const double tol = CTT_TOL(1e-15, 1e-6);
    cr_assert_leq(fabs(rx[0] - 3) + fabs(ry[0]) + fabs(rz[0] + 1), 8 * tol);
    cr_assert_leq(fabs(vn[0] - 1), 8 * tol);
    cr_assert_leq(fabs(u2[0] - 10), 32 * tol);
    cr_assert_leq(fabs(ma[0] - 1.5) + fabs(mb[0] - 4), 8 * tol);
    /* The optional outputs left out: vn the same bits. */
    ct_real vn2[1];
    cr_assert_eq(ct_relative_velocity_edge(1, a1, a2, b1, b2, sa, sb, nx, ny, nz, vx, vy, vz,
                                           NULL, NULL, NULL, NULL, vn2, NULL, NULL, NULL),
                 CT_OK);
    cr_assert(memcmp(vn, vn2, sizeof vn) == 0);
    /* Mismatched groups, a negative count, a missing required array. */
    cr_assert_eq(ct_relative_velocity_edge(1, a1, a2, b1, b2, sa, sb, nx, ny, nz, vx, vy, vz, m,
                                           NULL, NULL, NULL, vn, NULL, ma, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_relative_velocity_edge(1, a1, a2, b1, b2, sa, sb, nx, ny, nz, vx, vy, vz,
                                           NULL, rx, NULL, rz, vn, NULL, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_relative_velocity_edge(-1, a1, a2, b1, b2, sa, sb, nx, ny, nz, vx, vy, vz,
                                           NULL, NULL, NULL, NULL, vn, NULL, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_relative_velocity_edge(1, a1, a2, b1, b2, sa, NULL, nx, ny, nz, vx, vy, vz,
                                           NULL, NULL, NULL, NULL, vn, NULL, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_relative_velocity_edge(0, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                                           NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                                           NULL, NULL, NULL),
                 CT_OK);
}

/* A rigid rotation v = w x x: the relative velocity of the closest points
 * is w x (Pa - Pb), for 5 x 10^4 random edge pairs (many blocks, both the
 * sub-block copies and their remainders), on 1 and 2 threads with the same
 * bits; the masses against a plain loop in double. */
Test(kinematics, edge_rigid_rotation_and_threads)
{
    const ct_idx nn = 30000, np = 50000;
    ct_real *X[3], *V[3], *R[2][3], *N[3], *vn[2], *u2[2], *ma[2], *mb[2], *S[2], *m;
    ct_idx *E[4];
    m = ct_calloc(nn, sizeof(ct_real));
    for (int a = 0; a < 3; a++) {
        X[a] = ct_calloc(nn, sizeof(ct_real));
        V[a] = ct_calloc(nn, sizeof(ct_real));
        N[a] = ct_calloc(np, sizeof(ct_real));
        for (int t = 0; t < 2; t++)
            R[t][a] = ct_calloc(np, sizeof(ct_real));
    }
    for (int t = 0; t < 2; t++) {
        vn[t] = ct_calloc(np, sizeof(ct_real));
        u2[t] = ct_calloc(np, sizeof(ct_real));
        ma[t] = ct_calloc(np, sizeof(ct_real));
        mb[t] = ct_calloc(np, sizeof(ct_real));
        S[t] = ct_calloc(np, sizeof(ct_real));
    }
    for (int j = 0; j < 4; j++)
        E[j] = ct_calloc(np, sizeof(ct_idx));
    const double w[3] = {-0.4, 0.9, 1.3};
    uint64_t st = 4242;
    for (ct_idx i = 0; i < nn; i++) {
        for (int a = 0; a < 3; a++)
            X[a][i] = (ct_real)(4 * kin_rand01(&st) - 2);
        V[0][i] = (ct_real)(w[1] * X[2][i] - w[2] * X[1][i]);
        V[1][i] = (ct_real)(w[2] * X[0][i] - w[0] * X[2][i]);
        V[2][i] = (ct_real)(w[0] * X[1][i] - w[1] * X[0][i]);
        m[i] = (ct_real)(0.5 + kin_rand01(&st));
    }
    for (ct_idx k = 0; k < np; k++) {
        for (int j = 0; j < 4; j++)
            E[j][k] = (ct_idx)(kin_rand01(&st) * nn) % nn;
        S[0][k] = (ct_real)kin_rand01(&st);
        S[1][k] = (ct_real)kin_rand01(&st);
        double n[3] = {kin_rand01(&st) - 0.5, kin_rand01(&st) - 0.5, kin_rand01(&st) - 0.5};
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int a = 0; a < 3; a++)
            N[a][k] = (ct_real)(n[a] / l);
    }
    for (int t = 0; t < 2; t++) {
        ctt_threads(t + 1);
        cr_assert_eq(ct_relative_velocity_edge(np, E[0], E[1], E[2], E[3], S[0], S[1], N[0],
                                               N[1], N[2], V[0], V[1], V[2], m, R[t][0],
                                               R[t][1], R[t][2], vn[t], u2[t], ma[t], mb[t]),
                     CT_OK);
    }
    const size_t bytes = (size_t)np * sizeof(ct_real);
    for (int a = 0; a < 3; a++)
        cr_assert(memcmp(R[0][a], R[1][a], bytes) == 0, "u component %d: threads differ", a);
    cr_assert(memcmp(vn[0], vn[1], bytes) == 0 && memcmp(u2[0], u2[1], bytes) == 0 &&
                  memcmp(ma[0], ma[1], bytes) == 0 && memcmp(mb[0], mb[1], bytes) == 0,
              "1 and 2 threads differ");
    double err = 0, em = 0;
    for (ct_idx k = 0; k < np; k++) {
        const double s = S[0][k], t = S[1][k];
        double d[3];
        for (int a = 0; a < 3; a++)
            d[a] = (1 - s) * X[a][E[0][k]] + s * X[a][E[1][k]] -
                   ((1 - t) * X[a][E[2][k]] + t * X[a][E[3][k]]);
        const double u[3] = {w[1] * d[2] - w[2] * d[1], w[2] * d[0] - w[0] * d[2],
                             w[0] * d[1] - w[1] * d[0]};
        double un = 0, uu = 0;
        for (int a = 0; a < 3; a++) {
            err = fmax(err, fabs(R[0][a][k] - u[a]));
            un += u[a] * N[a][k];
            uu += u[a] * u[a];
        }
        err = fmax(err, fabs(vn[0][k] - un));
        err = fmax(err, fabs(u2[0][k] - uu) / 10);
        em = fmax(em, fabs(ma[0][k] - ((1 - s) * m[E[0][k]] + s * m[E[1][k]])));
        em = fmax(em, fabs(mb[0][k] - ((1 - t) * m[E[2][k]] + t * m[E[3][k]])));
    }
    /* |u| <= 2 sqrt(3) 4 |w|: a few roundings of that. */
    cr_assert_leq(err, CTT_TOL(1e-13, 2e-5), "max error %g against w x (Pa - Pb)", err);
    cr_assert_leq(em, CTT_TOL(1e-15, 1e-6), "max mass error %g", em);
    for (int a = 0; a < 3; a++) {
        ct_free(X[a]);
        ct_free(V[a]);
        ct_free(N[a]);
        for (int t = 0; t < 2; t++)
            ct_free(R[t][a]);
    }
    for (int t = 0; t < 2; t++) {
        ct_free(vn[t]);
        ct_free(u2[t]);
        ct_free(ma[t]);
        ct_free(mb[t]);
        ct_free(S[t]);
    }
    for (int j = 0; j < 4; j++)
        ct_free(E[j]);
    ct_free(m);
}
