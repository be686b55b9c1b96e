/*
 * common.c -- error names, aligned allocation, build provenance and the
 * parallel prefix sum shared by the kernels.
 */
#include <stdarg.h>
#include <stdlib.h>

#include "ct_internal.h"

const char *ct_strerror(int code)
{
    switch (code) {
    case CT_OK: return "success";
    case CT_ERR_NOMEM: return "out of memory";
    case CT_ERR_ARG: return "invalid argument";
    case CT_ERR_RANGE: return "index out of range";
    case CT_ERR_DUPNODE: return "node repeated in a segment";
    case CT_ERR_NONFINITE: return "NaN or infinite value";
    case CT_ERR_DEGENERATE: return "degenerate (zero-area) entity";
    case CT_ERR_NOCONV: return "iteration did not converge";
    case CT_ERR_TOOBIG: return "count too large for a 32-bit index";
    default: return "unknown error";
    }
}

int cti_fail(ct_diag *d, int code, int64_t index, const char *fmt, ...)
{
    if (d) {
        d->code = code;
        d->index = index;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(d->msg, sizeof d->msg, fmt, ap);
        va_end(ap);
    }
    return code;
}

void *ct_calloc(size_t count, size_t size)
{
    if (size == 0)
        size = 1;
    /* The roundings up below must not wrap: a count near SIZE_MAX (a
     * negative int count converted) is an overflow, not a small buffer. */
    if (count > SIZE_MAX - CT_PAD)
        return NULL;
    size_t padded = (count + CT_PAD - 1) / CT_PAD * CT_PAD;
    if (padded == 0)
        padded = CT_PAD;
    if (padded > (SIZE_MAX - CT_ALIGN) / size)
        return NULL;
    size_t bytes = padded * size;
    bytes = (bytes + CT_ALIGN - 1) / CT_ALIGN * CT_ALIGN;
    void *p = aligned_alloc(CT_ALIGN, bytes);
    if (p)
        memset(p, 0, bytes);
    return p;
}

void ct_free(void *p) { free(p); }

int cti_renew_two(ct_idx **a, ct_idx **b, size_t n, size_t ncap)
{
    ct_idx *na = ct_calloc(ncap, sizeof *na), *nb = ct_calloc(ncap, sizeof *nb);
    if (!na || !nb) {
        ct_free(na);
        ct_free(nb);
        return CT_ERR_NOMEM;
    }
    if (n) {
        memcpy(na, *a, n * sizeof *na);
        memcpy(nb, *b, n * sizeof *nb);
    }
    ct_free(*a);
    ct_free(*b);
    *a = na;
    *b = nb;
    return CT_OK;
}

int cti_grow(void **p, size_t *cap, size_t need, size_t size, size_t keep)
{
    if (need <= *cap && *p)
        return CT_OK;
    /* Room beyond a quarter of the address space is not there (and the
     * growth below would wrap). */
    if (need > (SIZE_MAX / 4) / (size ? size : 1))
        return CT_ERR_NOMEM;
    size_t ncap = *cap ? *cap : 64;
    while (ncap < need)
        ncap = ncap + ncap / 2 + 64;
    void *q = ct_calloc(ncap, size);
    if (!q)
        return CT_ERR_NOMEM;
    if (*p && keep)
        memcpy(q, *p, keep * size);
    ct_free(*p);
    *p = q;
    *cap = ncap;
    return CT_OK;
}

#ifndef CT_BUILD_CFLAGS
#define CT_BUILD_CFLAGS "unknown"
#endif
#ifndef CT_BUILD_COMMIT
#define CT_BUILD_COMMIT "unknown"
#endif
#ifdef __clang__
#define CTI_COMPILER "clang " __clang_version__
#elif defined(__GNUC__)
#define CTI_COMPILER "gcc " __VERSION__
#else
#define CTI_COMPILER "unknown compiler"
#endif

/* See contact.h: the precision this library was built with, by name. */
const int CT_PRECISION_GUARD = 1;

const char *ct_build_info(void)
{
    return "compiler=" CTI_COMPILER " flags=" CT_BUILD_CFLAGS
           " precision=" CT_PRECISION_NAME " commit=" CT_BUILD_COMMIT;
}

/* Blocks of the scan are fixed by n alone (not by the thread count), so the
 * 64-bit integer sums are identical whatever the number of threads. */
#define CTI_SCAN_BLOCKS 64

#define CTI_DEFINE_SCAN(NAME, OUT)                                                 \
    OUT NAME(const ct_idx *cnt, OUT *off, OUT n)                                 \
    {                                                                            \
        int64_t bsum[CTI_SCAN_BLOCKS + 1];                                       \
        int64_t nb = n < 4096 ? 1 : CTI_SCAN_BLOCKS;                             \
        int64_t bl = ((int64_t)n + nb - 1) / nb;                                 \
        _Pragma("omp parallel for schedule(static) if (nb > 1)")                 \
        for (int64_t b = 0; b < nb; b++) {                                       \
            int64_t lo = b * bl, hi = CTI_MIN((int64_t)n, lo + bl), s = 0;       \
            for (int64_t i = lo; i < hi; i++)                                    \
                s += cnt[i];                                                     \
            bsum[b] = s;                                                         \
        }                                                                        \
        int64_t run = 0;                                                         \
        for (int64_t b = 0; b < nb; b++) {                                       \
            int64_t t = bsum[b];                                                 \
            bsum[b] = run;                                                       \
            run += t;                                                            \
        }                                                                        \
        _Pragma("omp parallel for schedule(static) if (nb > 1)")                 \
        for (int64_t b = 0; b < nb; b++) {                                       \
            int64_t lo = b * bl, hi = CTI_MIN((int64_t)n, lo + bl), s = bsum[b]; \
            for (int64_t i = lo; i < hi; i++) {                                  \
                int64_t c = cnt[i];                                              \
                off[i] = (OUT)s;                                                 \
                s += c;                                                          \
            }                                                                    \
        }                                                                        \
        off[n] = (OUT)run;                                                       \
        return (OUT)run;                                                         \
    }

CTI_DEFINE_SCAN(cti_prefix_sum, int64_t)
CTI_DEFINE_SCAN(cti_prefix_sum_idx, ct_idx)
