/*
 * wtime.h -- the driver's wall clock (internal to the driver).
 */
#ifndef CTD_WTIME_H
#define CTD_WTIME_H

/* Seconds since an arbitrary origin, monotonic: OpenMP's clock when built
 * with OpenMP (the one the kernels' phases are timed with), else
 * CLOCK_MONOTONIC. */
double ctd_wtime(void);

#endif
