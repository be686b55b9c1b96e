/*
 * errf.h -- the driver's one way to report a failure into a caller's
 * message buffer, and to write a number in it (internal to the driver).
 */
#ifndef CTD_ERRF_H
#define CTD_ERRF_H

#include <stddef.h>

/* Format a message into err (when err is not NULL and len > 0, truncated
 * to len) and return code, so that a failing path reads
 * `return ctd_errf(err, len, CT_ERR_ARG, "...", ...)`. */
int ctd_errf(char *err, size_t len, int code, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* A number as a message shows it: the shortest %g form that reads back as
 * the same double (0.7, not 0.69999999999999996; 0.5000000000000001, not
 * 0.5, when the value is just above a bound of 0.5). */
typedef struct ctd_num_text {
    char s[32];
} ctd_num_text;

/* Used as `printf("%s", ctd_num(x).s)`: the struct is a temporary that
 * lives to the end of the full expression (C11 6.2.4p8), so several may
 * stand in one call. */
ctd_num_text ctd_num(double x);

#endif
