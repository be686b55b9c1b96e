/*
 * test_search_bucket.h -- what the bucket search's tests share
 * (test_search_bucket.c, test_search_bucket_input.c): plates on the shared
 * scene (test_search_scene.h), searches on 1 or 2 threads, and the check
 * that the bucket search returns direct's pairs byte for byte.
 */
#ifndef TEST_SEARCH_BUCKET_H
#define TEST_SEARCH_BUCKET_H

#include <stdint.h>
#include <string.h>

#include "test_search_scene.h"

/* A scene with room for nn nodes, ns segments and nsec secondaries
 * (test_search_scene.h). */
static inline void sc_init(ctt_scene *s, ct_idx nn, ct_idx ns, ct_idx nsec)
{
    ctt_scene_init(s, nn > nsec ? nn : nsec, ns);
}

static inline double rnd(uint64_t *r)
{
    *r = *r * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*r >> 11) / 9007199254740992.0;
}

static inline int run(ct_search_algo a, const ct_search_input *in, ct_pairs *out, int threads,
                      int64_t max_cells)
{
    ctt_threads(threads);
    ct_search_params p = ct_search_default_params(a);
    p.max_cells = max_cells;
    ct_search *s;
    cr_assert_eq(ct_search_init(&s, &p), CT_OK);
    int rc = ct_search_run(s, in, out);
    ct_search_destroy(s);
    return rc;
}

/* Bucket (1 and 2 threads) equals direct, byte for byte; returns the number
 * of pairs. */
static inline ct_idx check_same_cells(const ct_search_input *in, int64_t max_cells)
{
    ct_pairs ref, b1, b2;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&b1, 0);
    ct_pairs_init(&b2, 0);
    cr_assert_eq(run(CT_SEARCH_DIRECT, in, &ref, 2, 0), CT_OK);
    cr_assert_eq(run(CT_SEARCH_BUCKET, in, &b1, 1, max_cells), CT_OK);
    cr_assert_eq(run(CT_SEARCH_BUCKET, in, &b2, 2, max_cells), CT_OK);
    cr_assert_eq(b1.n, ref.n, "bucket found %d pairs, direct %d", (int)b1.n, (int)ref.n);
    cr_assert_eq(b2.n, ref.n);
    size_t bytes = (size_t)ref.n * sizeof(ct_idx);
    cr_assert(memcmp(b1.node, ref.node, bytes) == 0 && memcmp(b1.seg, ref.seg, bytes) == 0,
              "1-thread bucket pairs differ from direct");
    cr_assert(memcmp(b2.node, b1.node, bytes) == 0 && memcmp(b2.seg, b1.seg, bytes) == 0,
              "2-thread bucket pairs differ from 1-thread");
    ct_idx n = ref.n;
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&b1);
    ct_pairs_destroy(&b2);
    return n;
}

static inline ct_idx check_same(const ct_search_input *in)
{
    return check_same_cells(in, 0);
}

/* Plate A (secondary) above plate B (main), shifted in plane. */
static inline void two_plates(ctt_scene *s, int n, double h, double off, double scale, int tri)
{
    sc_init(s, 2 * (n + 1) * (n + 1), 2 * n * n, (n + 1) * (n + 1));
    ctt_scene_plate(s, n + 1, n + 1, off, off, off, scale, 1, tri);
    ct_idx a = ctt_scene_plate(s, n, n, off + 0.25 * scale, off + 0.35 * scale,
                               off + h * scale, scale, 0, 0);
    for (ct_idx i = 0; i < n * n; i++)
        s->sec[i] = a + i;
    s->nsec = n * n;
}

/* Search with explicit parameters on 1 or 2 threads. */
static inline int run_params(const ct_search_params *p, const ct_search_input *in,
                             ct_pairs *out, int threads, size_t *mem)
{
    ctt_threads(threads);
    ct_search *s;
    cr_assert_eq(ct_search_init(&s, p), CT_OK);
    int rc = ct_search_run(s, in, out);
    if (mem)
        *mem = ct_search_memory(s);
    ct_search_destroy(s);
    return rc;
}

/* Randomly permute the secondary list (Fisher-Yates). */
static inline void shuffle_sec(ctt_scene *s, uint64_t seed)
{
    uint64_t r = seed;
    for (ct_idx i = s->nsec - 1; i > 0; i--) {
        ct_idx j = (ct_idx)(rnd(&r) * (i + 1));
        ct_idx t = s->sec[i];
        s->sec[i] = s->sec[j];
        s->sec[j] = t;
    }
}

#endif /* TEST_SEARCH_BUCKET_H */
