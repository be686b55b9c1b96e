/*
 * test_validation_hertz.h -- the mesh and the analytic solution of the
 * Hertz validation cases (suite validation_hertz, case 2 of issue 6).
 *
 * The mesh is a quarter of a ball (x >= 0, y >= 0; the planes x = 0 and
 * y = 0 are symmetry planes) of radius R centred at (0, 0, R), so that its
 * south pole, where it touches the plane, is the origin (there the nodes'
 * coordinates are small, and so is their rounding in single precision:
 * the cells near the pole are 1.4 % of R, and a step moves a node by a
 * few 1e-9 m), from the pole up to z = (1 + ctop) R (ctop 0: a hemisphere,
 * 1: the whole quarter ball), graded towards the pole. It is the map the scene
 * generator `ball` uses (model.h: the smooth cube-to-ball map
 * x' = x sqrt(1 - y^2/2 - z^2/2 + y^2 z^2/3), cyclically) applied to the
 * parameter box [0, 1] x [0, 1] x [-1, ctop] with geometric spacings that
 * are finest at a = b = 0 and c = -1: near the pole a cell is about
 * h_a R / sqrt(2) wide and h_c R deep. The parameter planes a = 0, b = 0
 * map onto x = 0, y = 0, the plane c = 0 onto z = R, and the faces a = 1,
 * b = 1, c = -1 onto the sphere.
 *
 * The test writes it as a Radioss deck (/NODE, /BRICK/1) next to a scene
 * file that imports it, in a temporary folder.
 */
#ifndef TEST_VALIDATION_HERTZ_H
#define TEST_VALIDATION_HERTZ_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_validation_friction.h"

typedef struct hz_mesh {
    int na, nua;      /* cells along a and b; the first nua of them uniform */
    double ha;        /* their size (parameter units) */
    int nc, nuc;      /* cells along c; the first nuc uniform, of size hc */
    double hc;
    double sig;       /* the reach of the graded layers (see hz_c) */
    double ctop;      /* the top of the parameter box (0 or 1) */
    double R;
} hz_mesh;

/* Node id of parameter node (i, j, k). */
static inline int hz_id(const hz_mesh *h, int i, int j, int k)
{
    return 1 + i + (h->na + 1) * (j + (h->na + 1) * k);
}

/* Node i of n cells over [0, L]: nu cells of size h, then cells growing
 * by a constant ratio q (found by bisection) to reach L. */
static inline double hz_grade(int i, int n, int nu, double h, double L)
{
    if (i <= nu)
        return i * h;
    int m = n - nu;
    double rest = L - nu * h, lo = 1, hi = 10;
    for (int it = 0; it < 200; it++) {
        double q = 0.5 * (lo + hi), sum = 0, c = h;
        for (int k = 0; k < m; k++) {
            c *= q;
            sum += c;
        }
        if (sum > rest)
            hi = q;
        else
            lo = q;
    }
    double q = 0.5 * (lo + hi), x = nu * h, c = h;
    for (int k = nu; k < i; k++) {
        c *= q;
        x += c;
    }
    return i == n ? L : x;
}

static inline void hz_map(double a, double b, double c, double out[3])
{
    out[0] = a * sqrt(1 - b * b / 2 - c * c / 2 + b * b * c * c / 3);
    out[1] = b * sqrt(1 - c * c / 2 - a * a / 2 + c * c * a * a / 3);
    out[2] = c * sqrt(1 - a * a / 2 - b * b / 2 + a * a * b * b / 3);
}

static inline double hz_a(const hz_mesh *h, int i) { return hz_grade(i, h->na, h->nua, h->ha, 1); }

/* The parameter c of layer k at (a, b): the graded layers near the pole,
 * blended towards uniform layers away from it (weight exp(-(a^2 + b^2) /
 * sig^2)), so that the thin bottom layers do not run out to the cube's
 * corner, where the map squeezes them further and they would set the time
 * step. */
static inline double hz_c(const hz_mesh *h, double a, double b, int k)
{
    if (k == h->nc)
        return h->ctop;
    double g = -1 + hz_grade(k, h->nc, h->nuc, h->hc, h->ctop + 1);
    double u = -1 + (h->ctop + 1) * k / h->nc, w = exp(-(a * a + b * b) / (h->sig * h->sig));
    return w * g + (1 - w) * u;
}

/* The position of node (i, j, k). */
static inline void hz_node(const hz_mesh *h, int i, int j, int k, double p[3])
{
    double a = hz_a(h, i), b = hz_a(h, j), c = hz_c(h, a, b, k);
    hz_map(a, b, c, p);
    /* Exact zeros on the symmetry planes and the flat top. */
    p[0] = i == 0 ? 0.0 : h->R * p[0];
    p[1] = j == 0 ? 0.0 : h->R * p[1];
    p[2] = h->R + (c == 0 ? 0.0 : h->R * p[2]);
}

/* Write the deck: nodes, then the bricks of part 1. */
static inline void hz_write_deck(const hz_mesh *h, const char *path)
{
    FILE *f = fopen(path, "w");
    cr_assert(f != NULL, "cannot write %s", path);
    fprintf(f, "# A quarter of a ball graded towards its south pole (test_validation_hertz.h).\n");
    fprintf(f, "/NODE\n");
    for (int k = 0; k <= h->nc; k++)
        for (int j = 0; j <= h->na; j++)
            for (int i = 0; i <= h->na; i++) {
                double p[3];
                hz_node(h, i, j, k, p);
                fprintf(f, "%10d%20.13e%20.13e%20.13e\n", hz_id(h, i, j, k), p[0], p[1], p[2]);
            }
    fprintf(f, "/PART/1\nsphere\n         1         1\n/BRICK/1\n");
    int e = 1;
    for (int k = 0; k < h->nc; k++)
        for (int j = 0; j < h->na; j++)
            for (int i = 0; i < h->na; i++)
                fprintf(f, "%10d%10d%10d%10d%10d%10d%10d%10d%10d\n", e++, hz_id(h, i, j, k),
                        hz_id(h, i + 1, j, k), hz_id(h, i + 1, j + 1, k), hz_id(h, i, j + 1, k),
                        hz_id(h, i, j, k + 1), hz_id(h, i + 1, j, k + 1),
                        hz_id(h, i + 1, j + 1, k + 1), hz_id(h, i, j + 1, k + 1));
    fprintf(f, "/END\n");
    fclose(f);
}

/* A fresh temporary folder (the caller removes its files). */
static inline void hz_tmpdir(char *dir, size_t n)
{
    snprintf(dir, n, "/tmp/ct_hertz_XXXXXX");
    cr_assert(mkdtemp(dir) != NULL, "mkdtemp failed");
}

static inline void hz_rmdir(const char *dir, const char *const *files, int nfile)
{
    char p[1024];
    for (int i = 0; i < nfile; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, files[i]);
        remove(p);
    }
    remove(dir);
}

/* ---- Hertz: a sphere on a rigid plane (Johnson, Contact Mechanics, 1985,
 * chapter 4) ------------------------------------------------------------ */

typedef struct hz_mat {
    double E, nu, R;
} hz_mat;

/* E* of an elastic sphere on a rigid plane. */
static inline double hz_estar(const hz_mat *m) { return m->E / (1 - m->nu * m->nu); }

/* P = 4/3 E* sqrt(R) delta^3/2. */
static inline double hz_force(const hz_mat *m, double delta)
{
    return delta > 0 ? 4.0 / 3.0 * hz_estar(m) * sqrt(m->R) * pow(delta, 1.5) : 0;
}

/* The contact radius a = (3 P R / (4 E*))^1/3. */
static inline double hz_radius(const hz_mat *m, double P)
{
    return cbrt(3 * P * m->R / (4 * hz_estar(m)));
}

/* delta = a^2 / R. */
static inline double hz_delta(const hz_mat *m, double P)
{
    double a = hz_radius(m, P);
    return a * a / m->R;
}

/*
 * The displacement along the axis at depth z of the half-space under the
 * Hertz pressure p = p0 sqrt(1 - r^2/a^2) of total force P (p0 = 3 P /
 * (2 pi a^2)), towards the inside (positive), the far field at rest:
 * Boussinesq's point-load solution (Johnson, section 3.2: u_z = P (1 + nu)
 * / (2 pi E) (z^2 / rho^3 + 2 (1 - nu) / rho), rho the distance to the
 * load) summed over the pressure,
 *   u(z) = (1 + nu) / E int_0^a p(r) r [z^2 / (r^2 + z^2)^3/2
 *          + 2 (1 - nu) / (r^2 + z^2)^1/2] dr,
 * by Gauss-Legendre in r = a sin(phi) (smooth in phi). u(0) = delta: the
 * surface at the centre moves with the plane.
 */
static inline double hz_uz(const hz_mat *m, double P, double z)
{
    if (!(P > 0))
        return 0;
    static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                 -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                 0.7966664774136267,  0.9602898564975363};
    static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                 0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                 0.2223810344533745, 0.1012285362903763};
    const double a = hz_radius(m, P), p0 = 3 * P / (2 * VF_PI * a * a), nu = m->nu;
    /* 16 panels of 8 points over phi in [0, pi/2]. */
    const int np = 16;
    double sum = 0;
    for (int q = 0; q < np; q++) {
        double lo = q * (VF_PI / 2) / np, hi = (q + 1) * (VF_PI / 2) / np;
        for (int g = 0; g < 8; g++) {
            double ph = 0.5 * (lo + hi) + 0.5 * (hi - lo) * gx[g], w = 0.5 * (hi - lo) * gw[g];
            double r = a * sin(ph), dr = a * cos(ph), p = p0 * cos(ph);
            double s2 = r * r + z * z, s = sqrt(s2);
            double br = (s > 0 ? z * z / (s2 * s) : 0) + 2 * (1 - nu) / (s > 0 ? s : 1);
            sum += w * p * r * br * dr;
        }
    }
    return (1 + nu) / m->E * sum;
}

#endif /* TEST_VALIDATION_HERTZ_H */
