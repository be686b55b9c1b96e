/*
 * test_util.h -- helpers shared by the Criterion tests.
 */
#ifndef TEST_UTIL_H
#define TEST_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

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

#endif
