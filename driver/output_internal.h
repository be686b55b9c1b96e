/*
 * output_internal.h -- the output state shared by output_vtu.c and
 * output_csv.c.
 */
#ifndef CTD_OUTPUT_INTERNAL_H
#define CTD_OUTPUT_INTERNAL_H

#include <stdio.h>

#include "output.h"

struct ctd_output {
    char *dir, *base;
    int vtu, csv, vtu_format;
    /* VTU series: the steps written so far (time, file name). */
    int nstep, capstep;
    double *step_time;
    FILE *csvf;
    int ninterface;
    char err[1024];
};

/* "<dir>/<name>" into a new string (NULL when out of memory). */
char *cti_out_path(const char *dir, const char *name);

/* Record "what 'path': strerror(errno)" in o->err; returns CT_ERR_ARG. */
int cti_out_fail(char *err, size_t len, const char *what, const char *path, int errnum);

/* "out of memory" into err (when err is not NULL and len > 0); returns
 * CT_ERR_NOMEM. */
int cti_out_nomem(char *err, size_t len);

/* The raw appended form of a checked mesh into an open file
 * (output_vtu_raw.c); 0, or -1 when a write or an allocation failed. */
int cti_vtu_write_raw(FILE *f, const ctd_out_mesh *m);

#endif
