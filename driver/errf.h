/*
 * errf.h -- the driver's one way to report a failure into a caller's
 * message buffer (internal to the driver).
 */
#ifndef CTD_ERRF_H
#define CTD_ERRF_H

#include <stddef.h>

/* Format a message into err (when err is not NULL and len > 0, truncated
 * to len) and return code, so that a failing path reads
 * `return ctd_errf(err, len, CT_ERR_ARG, "...", ...)`. */
int ctd_errf(char *err, size_t len, int code, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#endif
