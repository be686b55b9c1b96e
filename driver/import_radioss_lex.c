/*
 * import_radioss_lex.c -- the text level of the Radioss reader: reading the
 * file, the error messages that name the file, the line and the field,
 * fixed-width fields and the Radioss number formats (1.5E+01, -.5, 1.D0,
 * 2.5d-1, 1.5+01), and the growing arrays and strings the scan fills.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "ct_internal.h"
#include "import_radioss_internal.h"

/* ---- Growing arrays and strings ---------------------------------------- */

int ctd_rad_regrow(void *pp, size_t cap, size_t size)
{
    void **p = pp;
    void *q = realloc(*p, cap * size);
    if (!q)
        return CT_ERR_NOMEM;
    *p = q;
    return CT_OK;
}

size_t ctd_rad_next_cap(size_t cap) { return cap ? cap + cap / 2 + 16 : 256; }

char *ctd_rad_dup_trim(const char *s, int n)
{
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        n--;
    while (n > 0 && isspace((unsigned char)*s)) {
        s++;
        n--;
    }
    char *t = malloc((size_t)n + 1);
    if (t) {
        memcpy(t, s, (size_t)n);
        t[n] = 0;
    }
    return t;
}

char *ctd_rad_or_empty(char *s)
{
    if (s)
        return s;
    s = malloc(1);
    if (s)
        *s = 0;
    return s;
}

/* ---- The file ---------------------------------------------------------- */

char *ctd_rad_slurp(const char *path, size_t *size)
{
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    /* A regular file past the limit is refused before any read (the loop
     * below stops a stream only after reading 1 GiB of it). */
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) &&
        (uint64_t)st.st_size > (uint64_t)CTD_DECK_MAXBYTES) {
        fclose(f);
        *size = (size_t)st.st_size;
        errno = EFBIG;
        return NULL;
    }
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        if (n == cap) {
            char *q = realloc(buf, 2 * cap);
            if (!q) {
                free(buf);
                buf = NULL;
                errno = ENOMEM;
                break;
            }
            buf = q;
            cap *= 2;
        }
        size_t k = fread(buf + n, 1, cap - n, f);
        n += k;
        /* Not a text deck (/dev/zero, a binary file): stop at the first
         * chunk with a NUL byte, which the scan reports with its line,
         * instead of reading on (import: {file: /dev/zero} grew without end). */
        if (k > 0 && memchr(buf + n - k, '\0', k))
            break;
        if (n > CTD_DECK_MAXBYTES) {
            free(buf);
            buf = NULL;
            errno = EFBIG;
            break;
        }
        if (k == 0) {
            if (ferror(f)) {
                free(buf);
                buf = NULL;
                errno = EIO;
            }
            break;
        }
    }
    int e = errno;
    fclose(f);
    errno = e;
    *size = buf ? n : 0;
    return buf;
}

/* ---- Messages ---------------------------------------------------------- */

/* The last 100 characters of a path at most. */
static const char *short_path(const char *p)
{
    size_t n = strlen(p);
    return n > 100 ? p + n - 100 : p;
}

int ctd_rad_fail(ctd_rad_reader *r, int code, int64_t line, const char *fmt, ...)
{
    char what[224];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (line > 0)
        return cti_fail(r->diag, code, line, "%s:%lld: %s", short_path(r->path),
                        (long long)line, what);
    return cti_fail(r->diag, code, line, "%s: %s", short_path(r->path), what);
}

int ctd_rad_nomem(ctd_rad_reader *r, int64_t line)
{
    return ctd_rad_fail(r, CT_ERR_NOMEM, line, "out of memory");
}

int ctd_rad_bad_field(ctd_rad_reader *r, int32_t line, const char *name, int k,
                      const char *what, ctd_rad_fld f)
{
    char num[24] = "";
    if (k > 0)
        snprintf(num, sizeof num, " (number %d)", k);
    return ctd_rad_fail(r, CT_ERR_ARG, line, "field '%s'%s of %s: expected %s, got '%.*s'", name,
                        num, r->kw, what, CTI_MIN(f.n, 40), f.p);
}

/* ---- Fields ------------------------------------------------------------ */

ctd_rad_fld ctd_rad_field(const char *s, int len, int start, int width)
{
    ctd_rad_fld f = {s, 0};
    if (start >= len)
        return f;
    int a = start, b = start + width < len ? start + width : len;
    while (a < b && isspace((unsigned char)s[a]))
        a++;
    while (b > a && isspace((unsigned char)s[b - 1]))
        b--;
    f.p = s + a;
    f.n = b - a;
    return f;
}

/* ---- Numbers ----------------------------------------------------------- */

int ctd_rad_parse_int(ctd_rad_fld f, int64_t *v)
{
    *v = 0;
    if (f.n == 0)
        return 1;
    int i = 0, neg = 0;
    if (f.p[0] == '+' || f.p[0] == '-') {
        neg = f.p[0] == '-';
        i = 1;
    }
    if (i == f.n || f.n - i > 18)
        return -1;
    int64_t x = 0;
    for (; i < f.n; i++) {
        if (f.p[i] < '0' || f.p[i] > '9')
            return -1;
        x = 10 * x + (f.p[i] - '0');
    }
    *v = neg ? -x : x;
    return 0;
}

int ctd_rad_parse_real(ctd_rad_fld f, double *v)
{
    *v = 0;
    if (f.n == 0)
        return 1;
    if (f.n > 64)
        return -1;
    char b[80];
    int k = 0, expo = 0, i = 0;
    if (f.p[0] == '+' || f.p[0] == '-')
        b[k++] = f.p[i++];
    int rest = f.n - i;
    if ((rest == 3 && !strncasecmp(f.p + i, "nan", 3)) ||
        (rest == 3 && !strncasecmp(f.p + i, "inf", 3)) ||
        (rest == 8 && !strncasecmp(f.p + i, "infinity", 8)))
        return -2;
    for (; i < f.n; i++) {
        char c = f.p[i];
        if ((c >= '0' && c <= '9') || c == '.') {
            b[k++] = c;
        } else if (c == '+' || c == '-') {
            /* 1.5+01 is 1.5E+01 (a sign after a digit starts an exponent). */
            if (k > 0 && !expo && (isdigit((unsigned char)b[k - 1]) || b[k - 1] == '.')) {
                b[k++] = 'e';
                expo = 1;
            }
            b[k++] = c;
        } else if (c == 'e' || c == 'E' || c == 'd' || c == 'D') {
            if (expo)
                return -1;
            b[k++] = 'e';
            expo = 1;
        } else {
            return -1;
        }
    }
    b[k] = 0;
    char *end;
    errno = 0;
    double d = strtod(b, &end);
    if (end != b + k || k == 0)
        return -1;
    if (!isfinite(d) || !isfinite((ct_real)d))
        return -2;
    *v = d;
    return 0;
}

/* ---- Required and optional fields -------------------------------------- */

int ctd_rad_need_id(ctd_rad_reader *r, int32_t line, const char *s, int len, int start,
                    const char *name, int64_t *v)
{
    ctd_rad_fld f = ctd_rad_field(s, len, start, 10);
    int rc = ctd_rad_parse_int(f, v);
    if (rc == 1)
        return ctd_rad_fail(r, CT_ERR_ARG, line,
                            "field '%s' of %s: missing (columns %d-%d are blank)", name, r->kw,
                            start + 1, start + 10);
    if (rc < 0 || *v <= 0)
        return ctd_rad_bad_field(r, line, name, 0, "a positive integer", f);
    return CT_OK;
}

int ctd_rad_opt_real(ctd_rad_reader *r, int32_t line, const char *s, int len, int start,
                     const char *name, double *v)
{
    ctd_rad_fld f = ctd_rad_field(s, len, start, 20);
    int rc = ctd_rad_parse_real(f, v);
    if (rc == -1)
        return ctd_rad_bad_field(r, line, name, 0, "a number", f);
    if (rc == -2)
        return ctd_rad_fail(r, CT_ERR_NONFINITE, line,
                            "field '%s' of %s: the coordinate '%.*s' is not finite", name, r->kw,
                            CTI_MIN(f.n, 40), f.p);
    return CT_OK;
}
