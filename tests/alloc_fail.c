/*
 * alloc_fail.c -- the allocation wrappers of alloc_fail.h. The counters are
 * atomic: the kernels allocate from inside parallel regions.
 */
#include "alloc_fail.h"

#include <errno.h>
#include <stdatomic.h>
#include <stddef.h>

void *__real_malloc(size_t n);
void *__real_calloc(size_t c, size_t n);
void *__real_realloc(void *p, size_t n);
void *__real_aligned_alloc(size_t a, size_t n);
char *__real_strdup(const char *s);
char *__real_strndup(const char *s, size_t n);
void __real_free(void *p);

void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t c, size_t n);
void *__wrap_realloc(void *p, size_t n);
void *__wrap_aligned_alloc(size_t a, size_t n);
char *__wrap_strdup(const char *s);
char *__wrap_strndup(const char *s, size_t n);
void __wrap_free(void *p);

static atomic_int on;
static atomic_llong fail_from, count, live, refused;

void ctt_alloc_begin(int64_t fail_at)
{
    atomic_store(&count, 0);
    atomic_store(&live, 0);
    atomic_store(&refused, 0);
    atomic_store(&fail_from, fail_at);
    atomic_store(&on, 1);
}

int64_t ctt_alloc_end(void)
{
    atomic_store(&on, 0);
    return atomic_load(&count);
}

int64_t ctt_alloc_live(void) { return atomic_load(&live); }

int64_t ctt_alloc_refused(void) { return atomic_load(&refused); }

/* Whether this allocation is refused (and counted). */
static int refuse(void)
{
    if (!atomic_load(&on))
        return 0;
    long long k = atomic_fetch_add(&count, 1);
    long long f = atomic_load(&fail_from);
    if (f >= 0 && k >= f) {
        atomic_fetch_add(&refused, 1);
        errno = ENOMEM;
        return 1;
    }
    return 0;
}

/* A block handed out (p not NULL) inside a window. */
static void *got(void *p)
{
    if (p && atomic_load(&on))
        atomic_fetch_add(&live, 1);
    return p;
}

void *__wrap_malloc(size_t n) { return refuse() ? NULL : got(__real_malloc(n)); }

void *__wrap_calloc(size_t c, size_t n) { return refuse() ? NULL : got(__real_calloc(c, n)); }

void *__wrap_aligned_alloc(size_t a, size_t n)
{
    return refuse() ? NULL : got(__real_aligned_alloc(a, n));
}

char *__wrap_strdup(const char *s) { return refuse() ? NULL : got(__real_strdup(s)); }

char *__wrap_strndup(const char *s, size_t n)
{
    return refuse() ? NULL : got(__real_strndup(s, n));
}

/* realloc(NULL, n) allocates a block; realloc(p, n) moves one (no change
 * in the live count, whether it succeeds or fails); realloc(p, 0) is not
 * used by the project (C23 makes it undefined). */
void *__wrap_realloc(void *p, size_t n)
{
    if (refuse())
        return NULL;
    void *q = __real_realloc(p, n);
    return p ? q : got(q);
}

void __wrap_free(void *p)
{
    if (p && atomic_load(&on))
        atomic_fetch_sub(&live, 1);
    __real_free(p);
}
