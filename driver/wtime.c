/*
 * wtime.c -- ctd_wtime (wtime.h).
 */
#include "wtime.h"

#ifdef _OPENMP
#include <omp.h>
double ctd_wtime(void) { return omp_get_wtime(); }
#else
#include <time.h>
double ctd_wtime(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
#endif
