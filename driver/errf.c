/*
 * errf.c -- ctd_errf and ctd_num (errf.h).
 */
#include "errf.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

int ctd_errf(char *err, size_t len, int code, const char *fmt, ...)
{
    if (err && len) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, len, fmt, ap);
        va_end(ap);
    }
    return code;
}

ctd_num_text ctd_num(double x)
{
    ctd_num_text t;
    /* 17 significant digits always read back (IEEE double); fewer often
     * do. Infinities print as %g does ("inf") and read back at once; a NaN
     * never compares equal, so it stops the loop at once ("nan"). */
    for (int p = 1; p <= 17; p++) {
        snprintf(t.s, sizeof t.s, "%.*g", p, x);
        if (x != x || strtod(t.s, NULL) == x)
            break;
    }
    return t;
}
