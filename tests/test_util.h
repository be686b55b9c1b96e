/*
 * test_util.h -- helpers shared by the Criterion tests.
 */
#ifndef TEST_UTIL_H
#define TEST_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"

#ifdef _OPENMP
#include <omp.h>
static inline void ctt_threads(int n) { omp_set_num_threads(n); }
#else
static inline void ctt_threads(int n) { (void)n; }
#endif

/* A tolerance stated for each precision: the double one, and the one the
 * single-precision build uses (each test states both where it asserts). */
#ifdef CT_SINGLE
#define CTT_TOL(dbl, sgl) (sgl)
#define CTT_SINGLE 1
#else
#define CTT_TOL(dbl, sgl) (dbl)
#define CTT_SINGLE 0
#endif

/* 1 when running under a sanitizer (make check): tests may shrink sizes. */
static inline int ctt_checking(void) { return getenv("CT_CHECK") != NULL; }

/* Path of ../shared (set by the Makefile), or NULL. */
static inline const char *ctt_shared(void) { return getenv("CT_SHARED"); }

/* Relative difference, safe at zero. */
static inline double ctt_rel(double a, double b)
{
    double s = fabs(a) > fabs(b) ? fabs(a) : fabs(b);
    return s > 0 ? fabs(a - b) / s : 0.0;
}

/* tests/REL (a path below the tests' folder), found from this file's path:
 * relative to the working directory when the build named the file so. */
static inline void ctt_tests_path(char *buf, size_t n, const char *rel)
{
    const char *f = __FILE__, *slash = strrchr(f, '/');
    if (slash)
        snprintf(buf, n, "%.*s/%s", (int)(slash - f), f, rel);
    else
        snprintf(buf, n, "%s", rel);
}

/* The distance from point p to the segment a b (the tests' own, written
 * apart from the kernels). */
static inline double ctt_point_seg_dist(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], l2 = 0, t = 0;
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ap[k] = p[k] - a[k];
        l2 += ab[k] * ab[k];
        t += ap[k] * ab[k];
    }
    t = l2 > 0 ? t / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double r2 = 0;
    for (int k = 0; k < 3; k++)
        r2 += (ap[k] - t * ab[k]) * (ap[k] - t * ab[k]);
    return sqrt(r2);
}

#endif
