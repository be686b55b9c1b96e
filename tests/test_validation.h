/*
 * test_validation.h -- what the validation cases (issue 6, suites named
 * validation_*) record besides their assertions.
 *
 * With CT_VALIDATION_OUT=DIR in the environment (`make validation` sets it),
 * a case writes
 *  - DIR/<name>.csv: its curves, one row per sample, a header line of
 *    column names (ctv_csv);
 *  - DIR/<name>.plot: how to draw them (ctv_plot), read by
 *    tests/validation_plots.py, which makes docs/validation/<name>.png;
 *  - one line per measured figure in DIR/results.tsv (ctv_result): case,
 *    quantity, measured, reference, relative error, tolerance, verdict.
 * Without it nothing is written and the calls cost nothing, so `make test`
 * runs the same cases with the same assertions.
 *
 * Criterion forks one process per test (and may run them in parallel with
 * --jobs), so every file is opened in append mode or written whole by one
 * test.
 */
#ifndef TEST_VALIDATION_H
#define TEST_VALIDATION_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The output folder, or NULL when nothing is to be written. */
static inline const char *ctv_dir(void)
{
    const char *d = getenv("CT_VALIDATION_OUT");
    return d && d[0] ? d : NULL;
}

/* Open DIR/<name>.csv for writing with the header line (comma-separated
 * column names); NULL when CT_VALIDATION_OUT is not set or the file cannot
 * be opened. Close with fclose. */
static inline FILE *ctv_csv(const char *name, const char *header)
{
    const char *d = ctv_dir();
    if (!d)
        return NULL;
    char p[1024];
    snprintf(p, sizeof p, "%s/%s.csv", d, name);
    FILE *f = fopen(p, "w");
    if (f)
        fprintf(f, "%s\n", header);
    return f;
}

/* One CSV row of n numbers (f may be NULL: nothing happens). */
static inline void ctv_row(FILE *f, int n, ...)
{
    if (!f)
        return;
    va_list ap;
    va_start(ap, n);
    for (int i = 0; i < n; i++)
        fprintf(f, "%s%.9g", i ? "," : "", va_arg(ap, double));
    va_end(ap);
    fputc('\n', f);
}

/*
 * How to draw DIR/<name>.csv: a title, the axis labels, and `series`, a
 * string of entries separated by ';', each "XCOL,YCOL,STYLE,LEGEND" with
 * columns counted from 1, STYLE lines | points | linespoints | dashed, e.g.
 *   "1,2,lines,simulated;1,3,dashed,Hertz (analytic)".
 * `options` is "" or a space-separated list of logx, logy.
 */
static inline void ctv_plot(const char *name, const char *title, const char *xlabel,
                            const char *ylabel, const char *series, const char *options)
{
    const char *d = ctv_dir();
    if (!d)
        return;
    char p[1024];
    snprintf(p, sizeof p, "%s/%s.plot", d, name);
    FILE *f = fopen(p, "w");
    if (!f)
        return;
    fprintf(f, "title\t%s\nxlabel\t%s\nylabel\t%s\nseries\t%s\noptions\t%s\n", title, xlabel,
            ylabel, series, options ? options : "");
    fclose(f);
}

/*
 * One measured figure of a case: `measured` against `reference` (the
 * analytic or published value), the relative error |m - r| / |r| (or the
 * absolute one when the reference is 0), the tolerance the test asserts
 * (0: reported only, not asserted) and a short note (the mesh, the
 * settings, what failed). Returns the error, so a test can assert on it.
 */
static inline double ctv_result(const char *casename, const char *quantity, double measured,
                                double reference, double tol, const char *note)
{
    double err = reference != 0 ? fabs(measured - reference) / fabs(reference)
                                : fabs(measured - reference);
    const char *d = ctv_dir();
    if (!d)
        return err;
    char p[1024];
    snprintf(p, sizeof p, "%s/results.tsv", d);
    FILE *f = fopen(p, "a");
    if (!f)
        return err;
    const char *verdict = tol > 0 ? (err <= tol ? "pass" : "FAIL") : "reported";
    fprintf(f, "%s\t%s\t%.6g\t%.6g\t%.3g\t%.3g\t%s\t%s\n", casename, quantity, measured,
            reference, err, tol, verdict, note ? note : "");
    fclose(f);
    return err;
}

#endif /* TEST_VALIDATION_H */
