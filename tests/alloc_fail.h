/*
 * alloc_fail.h -- allocation failure on demand, for the tests of what the
 * library and the driver do when memory runs out (tests/test_alloc_fail.c).
 *
 * The test program is linked with -Wl,--wrap for malloc, calloc, realloc,
 * aligned_alloc, strdup, strndup and free (the Makefile), so every call to
 * them from the project's own code (kernels/, driver/, tests/) goes through
 * tests/alloc_fail.c. Calls made inside shared libraries (libc itself,
 * libyaml, libgomp, Criterion) are not seen, except libcyaml's, which
 * allocate through the scene loader's mem_fn (driver/scene.c) and so from
 * the project's code.
 *
 * Between ctt_alloc_begin() and ctt_alloc_end(), allocations are counted,
 * and the one numbered fail_at (0: the first) and every one after it fail
 * when fail_at >= 0 (a program that goes on after a failure meets more; one
 * failure alone would let a later allocation succeed and hide a path that
 * ignores the first). Outside such a window the wrappers only pass through.
 */
#ifndef CTT_ALLOC_FAIL_H
#define CTT_ALLOC_FAIL_H

#include <stdint.h>

/* Start a window: counters zeroed; allocations from number fail_at on
 * fail (fail_at < 0: none fails). */
void ctt_alloc_begin(int64_t fail_at);

/* End the window; returns the number of allocations it asked for. */
int64_t ctt_alloc_end(void);

/* Within or after a window: the blocks allocated in it, successfully, and
 * not freed in it (0 when everything the window allocated was freed). */
int64_t ctt_alloc_live(void);

/* The allocations refused in the last window. */
int64_t ctt_alloc_refused(void);

#endif
