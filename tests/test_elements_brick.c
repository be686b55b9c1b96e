/*
 * test_elements_brick.c -- the total Lagrangian St Venant-Kirchhoff brick:
 * patch test, objectivity, Hooke's law, energy against work, equilibrium,
 * thread independence, volume and stable step against hand values.
 */
#include <string.h>

#include "elements/elements.h"
#include "meshgen.h"
#include "test_util.h"

/* E = 1000, nu = 0.25: lambda = mu = 400, lambda + 2 mu = 1200; rho = 3:
 * c = 20. */
#define EY 1000.0
#define NU 0.25
#define RHO 3.0

static uint64_t rng = 2024;
static double urand(void) /* in [-1, 1) */
{
    rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(rng >> 11) / 4503599627370496.0 - 1.0;
}

/* Block of n^3 unit cells; node (i, j, k) at i + (n+1)(j + (n+1) k). */
static ct_idx *block(ct_mesh *m, int n)
{
    ct_idx *hex = NULL;
    const double h[3] = {1, 1, 1};
    cr_assert_eq(ctd_block(m, n, n, n, h, NULL, &hex), CT_OK);
    return hex;
}

/* The n x n x n block as bricks of the test material in b. */
static ct_idx *block_bricks(ct_mesh *m, int n, ctd_brick *b)
{
    ct_idx *hex = block(m, n);
    ct_nodes *nd = &m->nodes;
    cr_assert_eq(ctd_brick_init(b, n * n * n, hex, nd->n, nd->x, nd->y, nd->z, EY, NU, RHO, NULL),
                 CT_OK);
    return hex;
}

static ct_idx nid(int n, int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); }

/* SVK first Piola-Kirchhoff stress and energy density of F = I + H. */
static double svk(const double H[3][3], double P[3][3])
{
    double lam, mu;
    {
        ct_real l, m;
        ctd_lame(EY, NU, &l, &m);
        lam = l;
        mu = m;
    }
    double E[3][3], S[3][3], tr = 0, ee = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double c = 0;
            for (int k = 0; k < 3; k++)
                c += (H[k][i] + (k == i)) * (H[k][j] + (k == j));
            E[i][j] = (c - (i == j)) / 2;
        }
    for (int i = 0; i < 3; i++)
        tr += E[i][i];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            S[i][j] = 2 * mu * E[i][j] + (i == j) * lam * tr;
            ee += E[i][j] * E[i][j];
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            P[i][j] = 0;
            for (int k = 0; k < 3; k++)
                P[i][j] += (H[i][k] + (i == k)) * S[k][j];
        }
    return lam / 2 * tr * tr + mu * ee;
}

static void zero_forces(ct_nodes *nd)
{
    memset(nd->fx, 0, nd->n * sizeof *nd->fx);
    memset(nd->fy, 0, nd->n * sizeof *nd->fy);
    memset(nd->fz, 0, nd->n * sizeof *nd->fz);
}

/* The 2 x 2 x 2 block with its interior node and some face and edge nodes
 * moved (faces stay planar, the outer box stays [0, 2]^3). */
static ct_idx *distorted_block(ct_mesh *m)
{
    ct_idx *hex = block(m, 2);
    ct_nodes *nd = &m->nodes;
    ct_idx c = nid(2, 1, 1, 1);
    nd->x[c] = 1.15, nd->y[c] = 0.9, nd->z[c] = 1.1;
    c = nid(2, 1, 1, 0); /* bottom face centre, moved in its plane */
    nd->x[c] = 1.1, nd->y[c] = 0.85;
    c = nid(2, 2, 1, 1); /* x = 2 face centre */
    nd->y[c] = 1.1, nd->z[c] = 0.9;
    c = nid(2, 1, 0, 0); /* an edge midpoint, along its edge */
    nd->x[c] = 0.8;
    c = nid(2, 0, 1, 2);
    nd->y[c] = 1.2;
    return hex;
}

Test(elements_brick, patch_uniform_stretch)
{
    ct_mesh m;
    ct_idx *hex = distorted_block(&m);
    ct_nodes *nd = &m.nodes;
    ctd_brick b;
    cr_assert_eq(ctd_brick_init(&b, 8, hex, nd->n, nd->x, nd->y, nd->z, EY, NU, RHO, NULL),
                 CT_OK);
    const double H[3][3] = {{0.05, 0.02, -0.03}, {0.01, -0.04, 0.02}, {0.0, 0.03, 0.06}};
    ct_real *X[3] = {malloc(27 * sizeof(ct_real)), malloc(27 * sizeof(ct_real)),
                     malloc(27 * sizeof(ct_real))};
    memcpy(X[0], nd->x, 27 * sizeof(ct_real));
    memcpy(X[1], nd->y, 27 * sizeof(ct_real));
    memcpy(X[2], nd->z, 27 * sizeof(ct_real));
    for (int a = 0; a < 27; a++) {
        double p[3] = {X[0][a], X[1][a], X[2][a]};
        nd->x[a] = p[0] + H[0][0] * p[0] + H[0][1] * p[1] + H[0][2] * p[2];
        nd->y[a] = p[1] + H[1][0] * p[0] + H[1][1] * p[1] + H[1][2] * p[2];
        nd->z[a] = p[2] + H[2][0] * p[0] + H[2][1] * p[1] + H[2][2] * p[2];
    }
    zero_forces(nd);
    cr_assert_eq(ctd_brick_forces(&b, nd->x, nd->y, nd->z, nd->fx, nd->fy, nd->fz, NULL), CT_OK);
    double P[3][3], W = svk(H, P);
    double fbig = 0;
    for (int a = 0; a < 27; a++)
        fbig = fmax(fbig, fabs(nd->fx[a]) + fabs(nd->fy[a]) + fabs(nd->fz[a]));
    cr_assert(fbig > 1);
    const double tol = CTT_TOL(1e-12, 1e-5);
    ct_idx c = nid(2, 1, 1, 1);
    cr_assert(fabs(nd->fx[c]) + fabs(nd->fy[c]) + fabs(nd->fz[c]) < tol * fbig,
              "interior force %g %g %g (max %g)", (double)nd->fx[c], (double)nd->fy[c],
              (double)nd->fz[c], fbig);
    /* Uniform stress: the energy is W V0 (V0 = 8), and for every linear
     * field w = e_i X_j the virtual work of the nodal forces is -V0 P_ij. */
    cr_assert(ctt_rel(ctd_brick_energy(&b), 8 * W) < CTT_TOL(1e-12, 1e-4));
    const ct_real *f[3] = {nd->fx, nd->fy, nd->fz};
    double pmax = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            pmax = fmax(pmax, fabs(P[i][j]));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double vw = 0;
            for (int a = 0; a < 27; a++)
                vw += f[i][a] * X[j][a];
            cr_assert(fabs(-vw - 8 * P[i][j]) < tol * 8 * pmax, "P%d%d %g vs %g", i, j, -vw / 8,
                      P[i][j]);
        }
    /* Lumped mass: rho V0 in total (the box is [0, 2]^3). */
    ct_real *mass = calloc(27, sizeof *mass);
    ctd_brick_mass(&b, mass);
    double mt = 0;
    for (int a = 0; a < 27; a++)
        mt += mass[a];
    cr_assert(ctt_rel(mt, RHO * 8) < CTT_TOL(1e-13, 1e-6));
    free(mass);
    for (int d = 0; d < 3; d++)
        free(X[d]);
    ctd_brick_destroy(&b);
    ct_free(hex);
    ct_mesh_destroy(&m);
}

/* R = rotation by 90 degrees about the unit axis u: u u^T + [u]x. */
static void rot90(const double u[3], double R[3][3])
{
    const double W[3][3] = {{0, -u[2], u[1]}, {u[2], 0, -u[0]}, {-u[1], u[0], 0}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            R[i][j] = u[i] * u[j] + W[i][j];
}

Test(elements_brick, rigid_rotation_is_stress_free)
{
    ct_mesh m;
    ct_idx *hex = distorted_block(&m);
    ct_nodes *nd = &m.nodes;
    ctd_brick b;
    cr_assert_eq(ctd_brick_init(&b, 8, hex, nd->n, nd->x, nd->y, nd->z, EY, NU, RHO, NULL),
                 CT_OK);
    const double s3 = 1 / sqrt(3.0), u[3] = {s3, s3, s3}, t[3] = {5, -3, 2};
    double R[3][3];
    rot90(u, R);
    ct_real *x = calloc(27, sizeof *x), *y = calloc(27, sizeof *y), *z = calloc(27, sizeof *z);
    /* The stretched state of the patch test, then the same rotated. */
    const double H[3][3] = {{0.05, 0.02, -0.03}, {0.01, -0.04, 0.02}, {0.0, 0.03, 0.06}};
    ct_real *f0 = calloc(81, sizeof *f0), *f1 = calloc(81, sizeof *f1);
    for (int pass = 0; pass < 3; pass++) {
        for (int a = 0; a < 27; a++) {
            double p[3] = {nd->x[a], nd->y[a], nd->z[a]}, q[3];
            for (int i = 0; i < 3; i++)
                q[i] = p[i] + (pass > 0 ? H[i][0] * p[0] + H[i][1] * p[1] + H[i][2] * p[2] : 0);
            double r[3];
            for (int i = 0; i < 3; i++)
                r[i] = pass == 1 ? q[i] : R[i][0] * q[0] + R[i][1] * q[1] + R[i][2] * q[2] + t[i];
            x[a] = r[0], y[a] = r[1], z[a] = r[2];
        }
        ct_real *f = pass == 1 ? f0 : f1;
        memset(f, 0, 81 * sizeof *f);
        cr_assert_eq(ctd_brick_forces(&b, x, y, z, f, f + 27, f + 54, NULL), CT_OK);
        if (pass == 0) {
            /* Pure rotation: no strain, no force, no energy. The force scale
             * of a unit strain on a unit face is E. */
            double fm = 0;
            for (int k = 0; k < 81; k++)
                fm = fmax(fm, fabs(f[k]));
            cr_assert(fm < CTT_TOL(1e-12, 1e-4) * EY, "force %g after a rigid rotation", fm);
            cr_assert(ctd_brick_energy(&b) < CTT_TOL(1e-24, 1e-8) * EY * 8);
        }
    }
    /* Objectivity under strain: the rotated state's forces are R f. */
    double fm = 0;
    for (int k = 0; k < 81; k++)
        fm = fmax(fm, fabs(f0[k]));
    for (int a = 0; a < 27; a++)
        for (int i = 0; i < 3; i++) {
            double rf = R[i][0] * f0[a] + R[i][1] * f0[27 + a] + R[i][2] * f0[54 + a];
            cr_assert(fabs(f1[27 * i + a] - rf) < CTT_TOL(1e-12, 1e-5) * fm);
        }
    free(f0);
    free(f1);
    free(x);
    free(y);
    free(z);
    ctd_brick_destroy(&b);
    ct_free(hex);
    ct_mesh_destroy(&m);
}

/* A single unit cube (nodes in hex8 order) and its brick. */
static void unit_cube_nu(ct_nodes *nd, ctd_brick *b, double side, double nu)
{
    cr_assert_eq(ct_nodes_init(nd, 8), CT_OK);
    static const int cx[8] = {0, 1, 1, 0, 0, 1, 1, 0}, cy[8] = {0, 0, 1, 1, 0, 0, 1, 1};
    for (int a = 0; a < 8; a++) {
        nd->x[a] = side * cx[a];
        nd->y[a] = side * cy[a];
        nd->z[a] = side * (a >= 4);
    }
    ct_idx conn[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    cr_assert_eq(ctd_brick_init(b, 1, conn, 8, nd->x, nd->y, nd->z, EY, nu, RHO, NULL), CT_OK);
}

static void unit_cube(ct_nodes *nd, ctd_brick *b, double side) { unit_cube_nu(nd, b, side, NU); }

Test(elements_brick, uniaxial_hooke)
{
    ct_nodes nd;
    ctd_brick b;
    unit_cube(&nd, &b, 1.0);
    /* Uniaxial stress: u = (eps X, -nu eps Y, -nu eps Z); sigma_xx = E eps. */
    const double eps = CTT_TOL(1e-6, 1e-3), tol = CTT_TOL(1e-5, 5e-3);
    for (int a = 0; a < 8; a++) {
        nd.x[a] += eps * nd.x[a];
        nd.y[a] -= NU * eps * nd.y[a];
        nd.z[a] -= NU * eps * nd.z[a];
    }
    zero_forces(&nd);
    cr_assert_eq(ctd_brick_forces(&b, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL), CT_OK);
    double fx1 = 0, fy1 = 0, fz1 = 0;
    for (int a = 0; a < 8; a++) {
        if (a == 1 || a == 2 || a == 5 || a == 6) /* the x = 1 face */
            fx1 += nd.fx[a];
        if (a == 2 || a == 3 || a == 6 || a == 7) /* y = 1 */
            fy1 += nd.fy[a];
        if (a >= 4)
            fz1 += nd.fz[a];
    }
    /* The element pulls the x = 1 face back with sigma A = E eps. */
    cr_assert(ctt_rel(-fx1, EY * eps) < tol, "face force %g vs E eps %g", -fx1, EY * eps);
    cr_assert(fabs(fy1) < tol * EY * eps && fabs(fz1) < tol * EY * eps, "lateral %g %g", fy1,
              fz1);
    /* Energy E eps^2 / 2 per unit volume. */
    cr_assert(ctt_rel(ctd_brick_energy(&b), EY * eps * eps / 2) < CTT_TOL(1e-5, 1e-2));
    ctd_brick_destroy(&b);
    ct_nodes_destroy(&nd);
}

/* A distorted single element, deformed by a random displacement field. */
static void random_element(ct_nodes *nd, ctd_brick *b, double strain)
{
    unit_cube(nd, b, 1.0);
    ctd_brick_destroy(b);
    for (int a = 0; a < 8; a++) {
        nd->x[a] += 0.15 * urand();
        nd->y[a] += 0.15 * urand();
        nd->z[a] += 0.15 * urand();
    }
    ct_idx conn[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    cr_assert_eq(ctd_brick_init(b, 1, conn, 8, nd->x, nd->y, nd->z, EY, NU, RHO, NULL), CT_OK);
    for (int a = 0; a < 8; a++) {
        nd->x[a] += strain * urand();
        nd->y[a] += strain * urand();
        nd->z[a] += strain * urand();
    }
}

Test(elements_brick, energy_matches_work)
{
    ct_nodes nd;
    ctd_brick b;
    random_element(&nd, &b, 0.03);
    const double d = CTT_TOL(1e-5, 1e-3);
    double dv[24];
    for (int k = 0; k < 24; k++)
        dv[k] = d * urand();
    ct_real *c[3] = {nd.x, nd.y, nd.z};
    zero_forces(&nd);
    cr_assert_eq(ctd_brick_forces(&b, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL), CT_OK);
    double work = 0;
    const ct_real *f[3] = {nd.fx, nd.fy, nd.fz};
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++)
            work += f[i][a] * 2 * dv[3 * a + i];
    double Wpm[2];
    for (int s = 0; s < 2; s++) {
        for (int a = 0; a < 8; a++)
            for (int i = 0; i < 3; i++)
                c[i][a] += (s == 0 ? 1 : -2) * dv[3 * a + i];
        zero_forces(&nd);
        cr_assert_eq(ctd_brick_forces(&b, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL), CT_OK);
        Wpm[s] = ctd_brick_energy(&b);
    }
    /* W(x + d) - W(x - d) = -f . 2d + O(d^3): the forces are minus the
     * energy's gradient. */
    double dW = Wpm[0] - Wpm[1];
    cr_assert(fabs(dW) > 0);
    cr_assert(ctt_rel(dW, -work) < CTT_TOL(1e-6, 1e-2), "dW %.12g, work %.12g", dW, -work);
    ctd_brick_destroy(&b);
    ct_nodes_destroy(&nd);
}

Test(elements_brick, equilibrium_force_and_moment)
{
    ct_nodes nd;
    ctd_brick b;
    for (int trial = 0; trial < 5; trial++) {
        random_element(&nd, &b, 0.2);
        zero_forces(&nd);
        cr_assert_eq(ctd_brick_forces(&b, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL), CT_OK);
        double F[3] = {0, 0, 0}, M[3] = {0, 0, 0}, fs = 0, ms = 0;
        for (int a = 0; a < 8; a++) {
            double p[3] = {nd.x[a], nd.y[a], nd.z[a]}, f[3] = {nd.fx[a], nd.fy[a], nd.fz[a]};
            double mo[3] = {p[1] * f[2] - p[2] * f[1], p[2] * f[0] - p[0] * f[2],
                            p[0] * f[1] - p[1] * f[0]};
            for (int i = 0; i < 3; i++) {
                F[i] += f[i];
                M[i] += mo[i];
                fs += fabs(f[i]);
                ms += fabs(mo[i]);
            }
        }
        cr_assert(fs > 1);
        for (int i = 0; i < 3; i++) {
            cr_assert(fabs(F[i]) < CTT_TOL(1e-13, 1e-5) * fs, "F%d %g of %g", i, F[i], fs);
            cr_assert(fabs(M[i]) < CTT_TOL(1e-13, 1e-5) * ms, "M%d %g of %g", i, M[i], ms);
        }
        ctd_brick_destroy(&b);
        ct_nodes_destroy(&nd);
    }
}

Test(elements_brick, threads_bit_identical)
{
    const int n = ctt_checking() ? 5 : 10;
    ct_mesh m;
    ctd_brick b;
    ct_idx *hex = block_bricks(&m, n, &b);
    ct_nodes *nd = &m.nodes;
    for (int a = 0; a < nd->n; a++) {
        nd->x[a] += 0.05 * urand() + 0.1 * nd->y[a];
        nd->y[a] += 0.05 * urand();
        nd->z[a] += 0.05 * urand();
    }
    const size_t nn = (size_t)nd->n;
    ct_real *f1 = calloc(3 * nn, sizeof *f1), *f2 = calloc(3 * nn, sizeof *f2);
    ctt_threads(1);
    cr_assert_eq(ctd_brick_forces(&b, nd->x, nd->y, nd->z, f1, f1 + nn, f1 + 2 * nn, NULL),
                 CT_OK);
    double e1 = ctd_brick_energy(&b);
    ct_idx i1, i2;
    ct_real dt1 = ctd_brick_dt(&b, nd->x, nd->y, nd->z, &i1);
    ctt_threads(2);
    cr_assert_eq(ctd_brick_forces(&b, nd->x, nd->y, nd->z, f2, f2 + nn, f2 + 2 * nn, NULL),
                 CT_OK);
    double e2 = ctd_brick_energy(&b);
    ct_real dt2 = ctd_brick_dt(&b, nd->x, nd->y, nd->z, &i2);
    cr_assert(memcmp(f1, f2, 3 * nn * sizeof *f1) == 0);
    cr_assert(e1 == e2 && e1 > 0);
    cr_assert(dt1 == dt2 && i1 == i2);
    free(f1);
    free(f2);
    ctd_brick_destroy(&b);
    ct_free(hex);
    ct_mesh_destroy(&m);
}

/* The step the forces compute on the way (volume as sum_g det0 det F)
 * against ctd_brick_dt's (volume as sum_g det J), on a sheared, distorted
 * block: the same number to round-off, for 1 and 2 threads. */
Test(elements_brick, stable_step_of_forces_matches_dt)
{
    ct_mesh m;
    ctd_brick b;
    ct_idx *hex = block_bricks(&m, 6, &b);
    ct_nodes *nd = &m.nodes;
    cr_expect_eq(ctd_brick_dt_last(&b), CTD_DT_NONE);
    for (int a = 0; a < nd->n; a++) {
        nd->x[a] += 0.05 * urand() + 0.2 * nd->y[a];
        nd->y[a] += 0.05 * urand() - 0.1 * nd->z[a];
        nd->z[a] += 0.05 * urand();
    }
    const size_t nn = (size_t)nd->n;
    ct_real *f = calloc(3 * nn, sizeof *f);
    cr_assert_not_null(f);
    ct_real dt = ctd_brick_dt(&b, nd->x, nd->y, nd->z, NULL);
    cr_assert_gt(dt, 0);
    for (int t = 1; t <= 2; t++) {
        ctt_threads(t);
        cr_assert_eq(ctd_brick_forces(&b, nd->x, nd->y, nd->z, f, f + nn, f + 2 * nn, NULL),
                     CT_OK);
        double got = ctd_brick_dt_last(&b);
        cr_expect_lt(fabs(got - dt), CTT_TOL(1e-13, 1e-5) * dt, "%d threads: %.17g against %.17g",
                     t, got, (double)dt);
    }
    free(f);
    ctd_brick_destroy(&b);
    ct_free(hex);
    ct_mesh_destroy(&m);
}

Test(elements_brick, volume_by_hand)
{
    ct_nodes nd;
    ctd_brick b;
    unit_cube(&nd, &b, 1.0);
    cr_assert(ctt_rel(b.vol0[0], 1.0) < CTT_TOL(1e-14, 1e-6));
    /* Corner 6 = (1, 1, 1) raised by a: z = Z (1 + a X Y), V = 1 + a / 4. */
    nd.z[6] = 1.6;
    cr_assert(ctt_rel(ctd_brick_volume(&b, 0, nd.x, nd.y, nd.z), 1.15) < CTT_TOL(1e-14, 1e-6));
    /* An affine map: V = det A. */
    const double A[3][3] = {{1.2, 0.3, 0.0}, {-0.1, 0.9, 0.2}, {0.05, 0.0, 1.1}};
    double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                 A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    static const int cx[8] = {0, 1, 1, 0, 0, 1, 1, 0}, cy[8] = {0, 0, 1, 1, 0, 0, 1, 1};
    for (int a = 0; a < 8; a++) {
        double p[3] = {cx[a], cy[a], a >= 4};
        nd.x[a] = A[0][0] * p[0] + A[0][1] * p[1] + A[0][2] * p[2];
        nd.y[a] = A[1][0] * p[0] + A[1][1] * p[1] + A[1][2] * p[2];
        nd.z[a] = A[2][0] * p[0] + A[2][1] * p[1] + A[2][2] * p[2];
    }
    cr_assert(ctt_rel(ctd_brick_volume(&b, 0, nd.x, nd.y, nd.z), det) < CTT_TOL(1e-14, 1e-6));
    ctd_brick_destroy(&b);
    ct_nodes_destroy(&nd);
}

Test(elements_brick, stable_step_unit_cube)
{
    ct_nodes nd;
    ctd_brick b;
    unit_cube(&nd, &b, 1.0);
    /* max(lambda + 2 mu, 3 lambda + 2 mu) = 2000, rho = 3: c_b =
     * sqrt(2000 / 3); L = V / A_max = 1: dt = sqrt(3 / 2000). */
    const double dt_hand = sqrt(3.0 / 2000);
    ct_idx imin = -2;
    ct_real dt = ctd_brick_dt(&b, nd.x, nd.y, nd.z, &imin);
    cr_assert(ctt_rel(dt, dt_hand) < CTT_TOL(1e-14, 1e-6), "dt %g", (double)dt);
    cr_assert_eq(imin, 0);
    /* Lumped mass rho V0 / 8 per node. */
    ct_real mass[8] = {0};
    ctd_brick_mass(&b, mass);
    for (int a = 0; a < 8; a++)
        cr_assert(ctt_rel(mass[a], RHO / 8) < CTT_TOL(1e-14, 1e-6));
    /* The true limit 2 / omega_max of the free unit cube (lumped masses
     * rho / 8): power iteration on M^-1 K, K v from central differences
     * of the forces around the reference state. */
    ct_real *X[3] = {nd.x, nd.y, nd.z};
    double X0[24], v[24], lam = 0;
    for (int k = 0; k < 24; k++) {
        X0[k] = X[k % 3][k / 3];
        v[k] = urand();
    }
    const double s = CTT_TOL(1e-7, 1e-3), mnode = RHO / 8;
    for (int it = 0; it < 300; it++) {
        double nv = 0, kv[24] = {0};
        for (int k = 0; k < 24; k++)
            nv += v[k] * v[k];
        nv = sqrt(nv);
        for (int sg = -1; sg <= 1; sg += 2) {
            for (int k = 0; k < 24; k++)
                X[k % 3][k / 3] = X0[k] + sg * s * v[k] / nv;
            zero_forces(&nd);
            cr_assert_eq(ctd_brick_forces(&b, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL),
                         CT_OK);
            const ct_real *f[3] = {nd.fx, nd.fy, nd.fz};
            for (int k = 0; k < 24; k++)
                kv[k] -= sg * f[k % 3][k / 3] / (2 * s);
        }
        double nk = 0;
        for (int k = 0; k < 24; k++) {
            v[k] = kv[k] / mnode;
            nk += v[k] * v[k];
        }
        lam = sqrt(nk);
    }
    double dt_true = 2 / sqrt(lam);
    cr_log_info("brick unit cube: dt %g, 2/omega_max %g, h/c %g", (double)dt, dt_true,
                1 / sqrt(1200 / RHO));
    cr_assert(ctt_rel(dt_true, dt_hand) < CTT_TOL(1e-5, 1e-2), "2/omega_max %g", dt_true);
    /* A cube of side 2: twice the step. */
    for (int k = 0; k < 24; k++)
        X[k % 3][k / 3] = 2 * X0[k];
    cr_assert(ctt_rel(ctd_brick_dt(&b, nd.x, nd.y, nd.z, NULL), 2 * dt_hand) <
              CTT_TOL(1e-14, 1e-6));
    ctd_brick_destroy(&b);
    ct_nodes_destroy(&nd);
}

/* Central difference on a free element (nu = 0.45) from a tiny random
 * velocity, at `factor` times the element's step: the largest kinetic
 * energy over the run relative to the initial one. */
static double run_cd(double factor)
{
    ct_nodes nd;
    ctd_brick b;
    unit_cube_nu(&nd, &b, 1.0, 0.45);
    ct_real m[8] = {0};
    ctd_brick_mass(&b, m);
    const double dt = factor * ctd_brick_dt(&b, nd.x, nd.y, nd.z, NULL);
    double k0 = 0, kmax = 0;
    /* Small enough to stay linear, large enough for single precision
     * positions to resolve the motion. */
    const double amp = CTT_TOL(1e-6, 1e-3);
    for (int a = 0; a < 8; a++) {
        nd.vx[a] = amp * urand();
        nd.vy[a] = amp * urand();
        nd.vz[a] = amp * urand();
        k0 += m[a] * (nd.vx[a] * nd.vx[a] + nd.vy[a] * nd.vy[a] + nd.vz[a] * nd.vz[a]) / 2;
    }
    for (int step = 0; step < 400; step++) {
        zero_forces(&nd);
        if (ctd_brick_forces(&b, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, NULL) != CT_OK) {
            kmax = HUGE_VAL; /* it grew until the element turned inside out */
            break;
        }
        double k = 0;
        for (int a = 0; a < 8; a++) {
            nd.vx[a] += dt * nd.fx[a] / m[a];
            nd.vy[a] += dt * nd.fy[a] / m[a];
            nd.vz[a] += dt * nd.fz[a] / m[a];
            nd.x[a] += dt * nd.vx[a];
            nd.y[a] += dt * nd.vy[a];
            nd.z[a] += dt * nd.vz[a];
            k += m[a] * (nd.vx[a] * nd.vx[a] + nd.vy[a] * nd.vy[a] + nd.vz[a] * nd.vz[a]) / 2;
        }
        kmax = fmax(kmax, k);
    }
    ctd_brick_destroy(&b);
    ct_nodes_destroy(&nd);
    return kmax / k0;
}

Test(elements_brick, stable_step_is_sharp)
{
    /* Below the step the motion stays bounded; 3 % above, the dilatation
     * mode grows (amplification about 1.5 per step). */
    double below = run_cd(0.97), above = run_cd(1.03);
    cr_log_info("brick nu=0.45: KE growth %g at 0.97 dt, %g at 1.03 dt", below, above);
    cr_assert(below < 100, "KE grew %g times below the step", below);
    cr_assert(above > 1e6, "KE grew only %g times above the step", above);
}

Test(elements_brick, errors)
{
    ct_nodes nd;
    ctd_brick b;
    unit_cube(&nd, &b, 1.0);
    ctd_brick_destroy(&b);
    ct_diag dg;
    ct_idx bad[8] = {0, 3, 2, 1, 4, 7, 6, 5}; /* mirrored: negative Jacobian */
    cr_assert_eq(ctd_brick_init(&b, 1, bad, 8, nd.x, nd.y, nd.z, EY, NU, RHO, &dg),
                 CT_ERR_DEGENERATE);
    ct_idx out[8] = {0, 1, 2, 3, 4, 5, 6, 8};
    cr_assert_eq(ctd_brick_init(&b, 1, out, 8, nd.x, nd.y, nd.z, EY, NU, RHO, &dg),
                 CT_ERR_RANGE);
    ct_idx ok[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    cr_assert_eq(ctd_brick_init(&b, 1, ok, 8, nd.x, nd.y, nd.z, EY, 0.5, RHO, &dg), CT_ERR_ARG);
    cr_assert_eq(ctd_brick_init(&b, 1, ok, 8, nd.x, nd.y, nd.z, EY, NU, RHO, &dg), CT_OK);
    /* Turn the element inside out. */
    nd.z[4] = nd.z[5] = nd.z[6] = nd.z[7] = -1;
    zero_forces(&nd);
    cr_assert_eq(ctd_brick_forces(&b, nd.x, nd.y, nd.z, nd.fx, nd.fy, nd.fz, &dg),
                 CT_ERR_DEGENERATE);
    cr_assert_eq(dg.index, 0);
    ctd_brick_destroy(&b);
    ct_nodes_destroy(&nd);
}
