/*
 * errf.c -- ctd_errf (errf.h).
 */
#include "errf.h"

#include <stdarg.h>
#include <stdio.h>

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
