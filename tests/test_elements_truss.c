/*
 * test_elements_truss.c -- truss and spring elements against hand values,
 * a 1-D wave front, momentum conservation and thread independence.
 */
#include <string.h>

#include "elements/elements.h"
#include "test_util.h"

/* A two-node bar along the unit vector (1, 2, 2) / 3. */
static void bar_nodes(ct_nodes *nd, double L)
{
    cr_assert_eq(ct_nodes_init(nd, 2), CT_OK);
    nd->x[0] = 1;
    nd->y[0] = -1;
    nd->z[0] = 0.5;
    nd->x[1] = 1 + L / 3;
    nd->y[1] = -1 + 2 * L / 3;
    nd->z[1] = 0.5 + 2 * L / 3;
}

Test(elements_truss, stretched_bar_by_hand)
{
    ct_nodes nd;
    bar_nodes(&nd, 2.0);
    ct_idx n1 = 0, n2 = 1;
    ctd_truss t;
    cr_assert_eq(ctd_truss_init(&t, 1, &n1, &n2, 2, nd.x, nd.y, nd.z, NULL), CT_OK);
    /* A = 0.5, E = 200, rho = 8: k = 200 * 0.5 / 2 = 50, mass 8. */
    cr_assert_eq(ctd_truss_set_truss(&t, 0, 1, 0.5, 200, 8), CT_OK);
    ct_real m[2] = {0, 0};
    ctd_truss_mass(&t, m);
    cr_assert_float_eq(m[0], 4.0, 1e-12);
    cr_assert_float_eq(m[1], 4.0, 1e-12);
    /* Stretch to L = 2.3: N = 50 * 0.3 = 15, energy 50 * 0.09 / 2 = 2.25. */
    ct_nodes_destroy(&nd);
    bar_nodes(&nd, 2.3);
    cr_assert_eq(ctd_truss_forces(&t, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL), CT_OK);
    const double tol = CTT_TOL(1e-12, 2e-5);
    double u[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
    /* Tension pulls node 0 towards node 1 (+u) and node 1 back (-u). */
    cr_assert(fabs(nd.fx[0] - 15 * u[0]) < tol * 15, "fx0 %g", (double)nd.fx[0]);
    cr_assert(fabs(nd.fy[0] - 15 * u[1]) < tol * 15);
    cr_assert(fabs(nd.fz[0] - 15 * u[2]) < tol * 15);
    cr_assert(fabs(nd.fx[1] + 15 * u[0]) < tol * 15);
    cr_assert(fabs(nd.fy[1] + 15 * u[1]) < tol * 15);
    cr_assert(fabs(nd.fz[1] + 15 * u[2]) < tol * 15);
    cr_assert(ctt_rel(ctd_truss_energy(&t), 2.25) < CTT_TOL(1e-10, 1e-3));
    /* Stable step L / c = 2.3 / sqrt(200 / 8) = 0.46. */
    ct_idx imin;
    ct_real dt = ctd_truss_dt(&t, nd.x, nd.y, nd.z, m, &imin);
    cr_assert(ctt_rel(dt, 0.46) < CTT_TOL(1e-12, 1e-5));
    cr_assert_eq(imin, 0);
    /* As a spring of k = 7: N = 7 * 0.3 = 2.1, dt = sqrt(min m / k). */
    cr_assert_eq(ctd_truss_set_spring(&t, 0, 1, 7), CT_OK);
    memset(nd.fx, 0, 2 * sizeof *nd.fx);
    memset(nd.fy, 0, 2 * sizeof *nd.fy);
    memset(nd.fz, 0, 2 * sizeof *nd.fz);
    cr_assert_eq(ctd_truss_forces(&t, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL), CT_OK);
    cr_assert(fabs(nd.fz[1] + 2.1 * u[2]) < tol * 2.1);
    cr_assert(ctt_rel(ctd_truss_energy(&t), 7 * 0.09 / 2) < CTT_TOL(1e-10, 1e-3));
    m[1] = 3;
    dt = ctd_truss_dt(&t, nd.x, nd.y, nd.z, m, NULL);
    cr_assert(ctt_rel(dt, sqrt(3.0 / 7)) < CTT_TOL(1e-12, 1e-6));
    /* A collapsed element is reported. */
    nd.x[1] = nd.x[0];
    nd.y[1] = nd.y[0];
    nd.z[1] = nd.z[0];
    ct_diag dg;
    cr_assert_eq(ctd_truss_forces(&t, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, &dg),
                 CT_ERR_DEGENERATE);
    cr_assert_eq(dg.index, 0);
    ctd_truss_destroy(&t);
    ct_nodes_destroy(&nd);
}

/* A chain of n unit trusses along x (E = A = rho = 1, so c = 1). */
static void chain(ct_nodes *nd, ctd_truss *t, int n)
{
    cr_assert_eq(ct_nodes_init(nd, n + 1), CT_OK);
    ct_idx *a = malloc(sizeof *a * n), *b = malloc(sizeof *b * n);
    for (int i = 0; i <= n; i++)
        nd->x[i] = i;
    for (int i = 0; i < n; i++) {
        a[i] = i;
        b[i] = i + 1;
    }
    cr_assert_eq(ctd_truss_init(t, n, a, b, n + 1, nd->x, nd->y, nd->z, NULL), CT_OK);
    cr_assert_eq(ctd_truss_set_truss(t, 0, n, 1, 1, 1), CT_OK);
    ctd_truss_mass(t, nd->m);
    free(a);
    free(b);
}

static void cd_step(ct_nodes *nd, ctd_truss *t, double dt, int first)
{
    int n = nd->n;
    memset(nd->fx, 0, n * sizeof *nd->fx);
    memset(nd->fy, 0, n * sizeof *nd->fy);
    memset(nd->fz, 0, n * sizeof *nd->fz);
    cr_assert_eq(ctd_truss_forces(t, nd->x, nd->y, nd->z, nd->fx, nd->fy, nd->fz, NULL), CT_OK);
    for (int i = first; i < n; i++) {
        nd->vx[i] += dt * nd->fx[i] / nd->m[i];
        nd->vy[i] += dt * nd->fy[i] / nd->m[i];
        nd->vz[i] += dt * nd->fz[i] / nd->m[i];
    }
    for (int i = 0; i < n; i++) {
        nd->x[i] += dt * nd->vx[i];
        nd->y[i] += dt * nd->vy[i];
        nd->z[i] += dt * nd->vz[i];
    }
}

Test(elements_truss, wave_front_at_ct)
{
    const int n = ctt_checking() ? 100 : 300;
    ct_nodes nd;
    ctd_truss t;
    chain(&nd, &t, n);
    /* The solver's usual safety factor 0.9 on L / c = 1. */
    const double v0 = 1e-2, dt = 0.9 * ctd_truss_dt(&t, nd.x, nd.y, nd.z, nd.m, NULL);
    cr_assert(ctt_rel(dt, 0.9) < 1e-6, "dt %g", dt);
    nd.vx[0] = v0; /* node 0 is driven at constant velocity */
    const int steps = (int)(n / 2 / dt); /* the front reaches mid-chain */
    for (int s = 0; s < steps; s++)
        cd_step(&nd, &t, dt, 1);
    /* Velocities are at the half step: time (steps - 1/2) dt. */
    const double time = (steps - 0.5) * dt;
    /* The front: where the velocity crosses v0 / 2 (linear interpolation
     * between nodes). Dispersion of the discrete chain spreads it over a
     * few elements around c t. */
    int i = 0;
    for (int k = 0; k <= n; k++)
        if (nd.vx[k] > v0 / 2)
            i = k;
    cr_assert(i < n);
    double front = i + (nd.vx[i] - v0 / 2) / (nd.vx[i] - nd.vx[i + 1]);
    cr_assert(fabs(front - time) <= 1.0, "front at %g, c t = %g", front, time);
    /* The impulse of the driven end, rho A c v0 t, equals the momentum
     * rho A v0 x_f of the moving part: the momentum front is at c t
     * (within 3e-4 element here: the start-up transient of the driven
     * end). */
    double p = 0;
    for (int k = 0; k <= n; k++)
        p += nd.m[k] * nd.vx[k];
    cr_assert(fabs(p / v0 - time) < CTT_TOL(0.01, 0.1), "momentum front %.9g, c t %.9g",
              p / v0, time);
    /* Behind the front the particle velocity is v0. */
    cr_assert(fabs(nd.vx[(int)(time / 2)] - v0) < 0.05 * v0);
    ctd_truss_destroy(&t);
    ct_nodes_destroy(&nd);
}

Test(elements_truss, free_chain_conserves_momentum)
{
    const int n = 64;
    ct_nodes nd;
    ctd_truss t;
    chain(&nd, &t, n);
    /* Give it a transverse zig-zag too, so forces are 3-D. */
    uint64_t s = 12345;
    double p0[3] = {0, 0, 0}, scale = 0;
    for (int i = 0; i <= n; i++) {
        ct_real *v[3] = {nd.vx, nd.vy, nd.vz};
        for (int d = 0; d < 3; d++) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            v[d][i] = (ct_real)(((double)(s >> 11) / 9007199254740992.0 - 0.5) * 0.1);
            p0[d] += nd.m[i] * v[d][i];
            scale += fabs(nd.m[i] * v[d][i]);
        }
        nd.y[i] = 0.1 * (i % 2);
    }
    const double dt = 0.5;
    for (int k = 0; k < 2000; k++)
        cd_step(&nd, &t, dt, 0);
    double p[3] = {0, 0, 0};
    for (int i = 0; i <= n; i++) {
        p[0] += nd.m[i] * nd.vx[i];
        p[1] += nd.m[i] * nd.vy[i];
        p[2] += nd.m[i] * nd.vz[i];
    }
    for (int d = 0; d < 3; d++)
        cr_assert(fabs(p[d] - p0[d]) < CTT_TOL(1e-13, 1e-5) * scale, "p%d %g vs %g", d, p[d],
                  p0[d]);
    ctd_truss_destroy(&t);
    ct_nodes_destroy(&nd);
}

Test(elements_truss, threads_bit_identical)
{
    /* A random net: many elements share each node. */
    const int nn = 3000, ne = 10000;
    ct_nodes nd;
    cr_assert_eq(ct_nodes_init(&nd, nn), CT_OK);
    ct_idx *a = malloc(sizeof *a * ne), *b = malloc(sizeof *b * ne);
    uint64_t s = 99;
    for (int i = 0; i < nn; i++) {
        ct_real *c[3] = {nd.x, nd.y, nd.z};
        for (int d = 0; d < 3; d++) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            c[d][i] = (ct_real)((s >> 11) % 100000) / 1000;
        }
    }
    for (int e = 0; e < ne; e++) {
        a[e] = e % nn;
        b[e] = (e * 7 + 1 + e / nn) % nn;
        if (b[e] == a[e])
            b[e] = (a[e] + 1) % nn;
    }
    ctd_truss t;
    cr_assert_eq(ctd_truss_init(&t, ne, a, b, nn, nd.x, nd.y, nd.z, NULL), CT_OK);
    cr_assert_eq(ctd_truss_set_truss(&t, 0, ne, 1, 1, 1), CT_OK);
    for (int i = 0; i < nn; i++)
        nd.x[i] *= (ct_real)1.01;
    ct_real *f1 = calloc(3 * nn, sizeof *f1), *f2 = calloc(3 * nn, sizeof *f2);
    ctt_threads(1);
    cr_assert_eq(ctd_truss_forces(&t, nd.x, nd.y, nd.z, f1, f1 + nn, f1 + 2 * nn, NULL), CT_OK);
    ctt_threads(2);
    cr_assert_eq(ctd_truss_forces(&t, nd.x, nd.y, nd.z, f2, f2 + nn, f2 + 2 * nn, NULL), CT_OK);
    cr_assert(memcmp(f1, f2, 3 * nn * sizeof *f1) == 0);
    double fsum = 0, fabs_sum = 0;
    for (int i = 0; i < 3 * nn; i++) {
        fsum += f1[i];
        fabs_sum += fabs(f1[i]);
    }
    cr_assert(fabs_sum > 0 && fabs(fsum) < CTT_TOL(1e-13, 1e-5) * fabs_sum);
    free(f1);
    free(f2);
    free(a);
    free(b);
    ctd_truss_destroy(&t);
    ct_nodes_destroy(&nd);
}
