/*
 * test_search_renumber_reuse.c -- a renumbering kept by the workspace
 * (ct_search_params.renumber_keep, kernels/search_renumber.c) serves the
 * searches that follow while the topology is the same: the pairs stay the
 * direct search's after the nodes move (even when the motion destroys the
 * numbering's locality), a changed corner or secondary list is noticed and
 * a new numbering made, the kept numbering expires after renumber_keep
 * searches and on ct_search_reset, and 1 and 2 threads give the same bytes
 * on one workspace.
 */
#include "test_search_scene.h"

#include <math.h>

#include "ct_internal.h"
#include "meshgen.h"

/* A mutable copy of a case's search input. */
typedef struct rcopy {
    ct_search_input in;
    ct_real *x, *y, *z;
    ct_idx *sec, *n[4];
} rcopy;

static void *dup_array(const void *src, size_t n, size_t size)
{
    void *p = ct_calloc(n, size);
    cr_assert(p);
    memcpy(p, src, n * size);
    return p;
}

static void rcopy_make(rcopy *r, const ct_search_input *in)
{
    r->in = *in;
    r->in.x = r->x = dup_array(in->x, (size_t)in->nnode, sizeof(ct_real));
    r->in.y = r->y = dup_array(in->y, (size_t)in->nnode, sizeof(ct_real));
    r->in.z = r->z = dup_array(in->z, (size_t)in->nnode, sizeof(ct_real));
    r->in.sec = r->sec = dup_array(in->sec, (size_t)in->nsec, sizeof(ct_idx));
    const ct_idx *c[4] = {in->n1, in->n2, in->n3, in->n4};
    for (int k = 0; k < 4; k++)
        r->n[k] = dup_array(c[k], (size_t)in->nseg, sizeof(ct_idx));
    r->in.n1 = r->n[0], r->in.n2 = r->n[1], r->in.n3 = r->n[2], r->in.n4 = r->n[3];
}

static void rcopy_free(rcopy *r)
{
    ct_free(r->x);
    ct_free(r->y);
    ct_free(r->z);
    ct_free(r->sec);
    for (int k = 0; k < 4; k++)
        ct_free(r->n[k]);
}

/* Search with the kept workspace w and check the pairs against the direct
 * search of the same input; returns the kept numbering's use count. */
static int check_step(ct_search *w, const ct_search_input *in, ct_pairs *got, ct_pairs *ref,
                      const char *what)
{
    ctt_search(CT_SEARCH_DIRECT, in, ref);
    cr_assert_gt(ref->n, 0, "%s: no pairs", what);
    cr_assert_eq(ct_search_run(w, in, got), CT_OK, "%s", what);
    cr_assert(ctt_same_pairs(ref, got), "%s: %d pairs, direct %d (or the order differs)", what,
              got->n, ref->n);
    return cti_renum_uses(w->rn);
}

static void reuse_case(ct_search_algo algo)
{
    ctd_case c;
    ct_diag d = {0};
    cr_assert_eq(ctd_case_make(&c, "plates", 2500, CTD_NUM_SHUFFLED, 21, &d), CT_OK, "%s", d.msg);
    ct_search_input in0;
    ctd_case_input(&c, (ct_real)(0.4 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in0);
    rcopy r;
    rcopy_make(&r, &in0);
    ct_search_input *in = &r.in;
    ct_search_params p = ct_search_default_params(algo);
    p.renumber = 1;
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    ct_pairs got, ref, prev;
    ct_pairs_init(&got, 0);
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&prev, 0);
    const char *an = ct_search_algo_name(algo);

    ctt_threads(2);
    cr_assert_eq(check_step(w, in, &got, &ref, an), 1, "%s: first search", an);
    cr_assert_eq(check_step(w, in, &got, &ref, an), 2, "%s: the same input again", an);

    /* A smooth motion: a rotation about z and a bend of plate A. */
    const ct_real cs = (ct_real)cos(0.3), sn = (ct_real)sin(0.3);
    for (ct_idx i = 0; i < in->nnode; i++) {
        const ct_real x = r.x[i], y = r.y[i];
        r.x[i] = cs * x - sn * y;
        r.y[i] = sn * x + cs * y;
    }
    for (ct_idx k = 0; k < in->nsec; k++)
        r.z[r.sec[k]] -= (ct_real)(0.002 * r.x[r.sec[k]]);
    cr_assert_eq(check_step(w, in, &got, &ref, "rotated and bent"), 3, "%s", an);

    /* The positions of plate A's nodes exchanged at random among them: the
     * kept numbering is no longer local at all, the pairs must not care. */
    uint64_t seed = 99;
    for (ct_idx k = in->nsec - 1; k > 0; k--) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const ct_idx j = (ct_idx)((seed >> 33) % (uint64_t)(k + 1));
        const ct_idx a = r.sec[k], b = r.sec[j];
        ct_real t = r.x[a];
        r.x[a] = r.x[b], r.x[b] = t;
        t = r.y[a];
        r.y[a] = r.y[b], r.y[b] = t;
        t = r.z[a];
        r.z[a] = r.z[b], r.z[b] = t;
    }
    cr_assert_eq(check_step(w, in, &got, &ref, "positions exchanged"), 4, "%s", an);

    /* One corner of one segment moved to a far node (same counts): the
     * pairs change, and the kept numbering must be dropped. */
    cr_assert_eq(ct_pairs_reserve(&prev, ref.n), CT_OK);
    memcpy(prev.node, ref.node, sizeof(ct_idx) * (size_t)ref.n);
    memcpy(prev.seg, ref.seg, sizeof(ct_idx) * (size_t)ref.n);
    prev.n = ref.n;
    const ct_idx j0 = in->nseg / 2;
    r.n[2][j0] = r.n[2][in->nseg - 1];
    cr_assert_eq(check_step(w, in, &got, &ref, "a corner changed"), 1, "%s", an);
    cr_assert(!ctt_same_pairs(&prev, &ref), "the changed corner did not change the pairs");

    /* Two secondaries exchanged in the list (the same set): canonical order
     * follows the list, so the output changes. */
    memcpy(prev.node, ref.node, sizeof(ct_idx) * (size_t)ref.n);
    memcpy(prev.seg, ref.seg, sizeof(ct_idx) * (size_t)ref.n);
    prev.n = ref.n;
    const ct_idx t = r.sec[0];
    r.sec[0] = r.sec[in->nsec / 3];
    r.sec[in->nsec / 3] = t;
    cr_assert_eq(check_step(w, in, &got, &ref, "secondaries exchanged"), 1, "%s", an);
    cr_assert(!ctt_same_pairs(&prev, &ref), "the exchange did not change the output");

    /* The same workspace with 1 thread: the same bytes. */
    ctt_threads(1);
    cr_assert_eq(check_step(w, in, &got, &ref, "1 thread"), 2, "%s", an);
    ctt_threads(2);

    /* ct_search_reset forgets the numbering. */
    ct_search_reset(w);
    cr_assert_eq(check_step(w, in, &got, &ref, "after reset"), 1, "%s", an);
    ct_search_destroy(w);

    /* renumber_keep = 2: a new numbering every other search; -1: none kept. */
    p.renumber_keep = 2;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    for (int k = 0; k < 5; k++) {
        r.z[r.sec[k]] += (ct_real)0.01;
        cr_assert_eq(check_step(w, in, &got, &ref, "keep 2"), 1 + k % 2, "%s, search %d", an, k);
    }
    ct_search_destroy(w);
    p.renumber_keep = -1;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    for (int k = 0; k < 2; k++)
        cr_assert_eq(check_step(w, in, &got, &ref, "keep -1"), 0, "%s", an);
    ct_search_destroy(w);

    ct_pairs_destroy(&got);
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&prev);
    rcopy_free(&r);
    ctd_case_destroy(&c);
}

Test(search_renumber_reuse, bucket, .timeout = 120) { reuse_case(CT_SEARCH_BUCKET); }

Test(search_renumber_reuse, bsp, .timeout = 120) { reuse_case(CT_SEARCH_BSP); }

Test(search_renumber_reuse, bad_keep_rejected)
{
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    p.renumber_keep = -2;
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_ERR_ARG);
}
