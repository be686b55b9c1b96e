/*
 * test_project.h -- helpers of the node-segment narrow-phase tests
 * (test_project.c, test_project_determinism.c, test_newton_bound.c): a
 * small deterministic random generator, the bilinear quadrangle and its
 * derivatives, random warped quadrangles, and the independent reference
 * for the nearest point of a bilinear quadrangle (dense search).
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

/* ---- Independent reference for the bilinear quad ----------------------- */

static inline double f2(const double X[4][3], const double p[3], double s, double t)
{
    double x[3], a[3], b[3];
    bil(X, s, t, x, a, b);
    return (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) +
           (x[2] - p[2]) * (x[2] - p[2]);
}

/* d f / d s (dir 0) or d f / d t (dir 1), f = |x - p|^2 / 2. */
static inline double df(const double X[4][3], const double p[3], double s, double t,
                        int dir)
{
    double x[3], a[3], b[3];
    bil(X, s, t, x, a, b);
    const double *e = dir ? b : a;
    return (x[0] - p[0]) * e[0] + (x[1] - p[1]) * e[1] + (x[2] - p[2]) * e[2];
}

/* 1-D minimisation on [-1, 1] of f along one coordinate: f is a quadratic
 * in each coordinate with a positive leading term (a1 + t a3 != 0), so its
 * derivative is increasing: bisection on the sign of the derivative. */
static inline double line_min(const double X[4][3], const double p[3], double s, double t,
                              int dir)
{
    double lo = -1, hi = 1;
    double dlo = df(X, p, dir ? s : lo, dir ? lo : t, dir);
    double dhi = df(X, p, dir ? s : hi, dir ? hi : t, dir);
    if (dlo >= 0)
        return -1;
    if (dhi <= 0)
        return 1;
    for (int it = 0; it < 200 && hi - lo > 0; it++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;
        double dm = df(X, p, dir ? s : mid, dir ? mid : t, dir);
        if (dm > 0)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

/* Closest point of the bilinear quad: best of a 81 x 81 grid, then
 * coordinate descent to a fixed point. */
static inline void truth_quad(const double X[4][3], const double p[3], double c[3],
                              double *dist)
{
    double bs = 0, bt = 0, bf = 1e300;
    for (int i = 0; i <= 80; i++)
        for (int j = 0; j <= 80; j++) {
            double s = -1 + i / 40.0, t = -1 + j / 40.0, f = f2(X, p, s, t);
            if (f < bf) {
                bf = f;
                bs = s;
                bt = t;
            }
        }
    for (int sweep = 0; sweep < 5000; sweep++) {
        double s0 = bs, t0 = bt;
        bs = line_min(X, p, bs, bt, 0);
        bt = line_min(X, p, bs, bt, 1);
        if (fabs(bs - s0) + fabs(bt - t0) < 1e-16)
            break;
    }
    double a[3], b[3];
    bil(X, bs, bt, c, a, b);
    *dist = sqrt(f2(X, p, bs, bt));
}

#endif
