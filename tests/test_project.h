/*
 * test_project.h -- helpers of the node-segment narrow-phase tests
 * (test_project.c, test_project_determinism.c): a small deterministic
 * random generator, the bilinear quadrangle and its derivatives, and random
 * warped quadrangles.
 */
#ifndef TEST_PROJECT_H
#define TEST_PROJECT_H

#include "test_util.h"

static unsigned rng_state = 12345u;
static inline double urand(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (rng_state >> 8) / 16777216.0;
}

/* The bilinear quadrangle X at (s, t): the point x and its derivatives
 * xs, xt. */
static inline void bil(const double X[4][3], double s, double t, double x[3],
                       double xs[3], double xt[3])
{
    double H[4] = {(1 - s) * (1 - t) / 4, (1 + s) * (1 - t) / 4, (1 + s) * (1 + t) / 4,
                   (1 - s) * (1 + t) / 4};
    double Hs[4] = {-(1 - t) / 4, (1 - t) / 4, (1 + t) / 4, -(1 + t) / 4};
    double Ht[4] = {-(1 - s) / 4, -(1 + s) / 4, (1 + s) / 4, (1 - s) / 4};
    for (int d = 0; d < 3; d++) {
        x[d] = xs[d] = xt[d] = 0;
        for (int i = 0; i < 4; i++) {
            x[d] += H[i] * X[i][d];
            xs[d] += Hs[i] * X[i][d];
            xt[d] += Ht[i] * X[i][d];
        }
    }
}

/* A random warped quad around the unit square [-1,1]^2 scaled by L. */
static inline void rand_quad(double X[4][3], double warp, double L)
{
    double base[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int i = 0; i < 4; i++) {
        X[i][0] = L * (base[i][0] + 0.3 * (urand() - 0.5));
        X[i][1] = L * (base[i][1] + 0.3 * (urand() - 0.5));
        X[i][2] = L * warp * (i & 1 ? 1 : -1) * (0.5 + 0.5 * urand());
    }
}

#endif
