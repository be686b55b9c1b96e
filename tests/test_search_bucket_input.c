/*
 * test_search_bucket_input.c -- the bucket search on inputs in any order
 * (secondaries shuffled, nodes and segments renumbered: still direct's
 * pairs, in secondary-list order) and on bad input (indices out of range,
 * NaN and infinite coordinates: an error code, never a crash).
 */
#include <math.h>

#include "test_search_bucket.h"

Test(search_bucket, nan_input)
{
    ctt_scene s;
    two_plates(&s, 4, 0.3, 0, 1, 0);
    ct_pairs out;
    ct_pairs_init(&out, 0);
    s.x[s.sec[3]] = (ct_real)NAN;
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_ERR_NONFINITE);
    s.x[s.sec[3]] = 1;
    s.z[s.n3[5]] = (ct_real)INFINITY;
    cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_ERR_NONFINITE);
    ct_pairs_destroy(&out);
    ctt_scene_free(&s);
}

Test(search_bucket, shuffled_secondaries_cell_order, .timeout = 120)
{
    const int n = ctt_checking() ? 66 : 80;
    ctt_scene s;
    two_plates(&s, n, 0.3, 0, 1, 0);
    shuffle_sec(&s, 4242);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    /* Every node sees 3 quads but the last row's and column's (by hand, as
     * in plates_several_gaps). */
    cr_assert_eq(check_same(&in), 3 * n * n - 2 * n);
    in.filter = CT_FILTER_BOX;
    cr_assert_geq(check_same(&in), 3 * n * n - 2 * n);
    ctt_scene_free(&s);
}

Test(search_bucket, bad_indices_and_coordinates)
{
    for (int big = 0; big < 2; big++) {
        int n = big ? 66 : 5;
        ctt_scene s;
        two_plates(&s, n, 0.3, 0, 1, 0);
        if (big)
            shuffle_sec(&s, 99);
        ct_pairs out;
        ct_pairs_init(&out, 0);
        ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
        ct_idx keep = s.sec[s.nsec / 2];
        s.sec[s.nsec / 2] = s.nn; /* one past the last node */
        cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_ERR_RANGE);
        s.sec[s.nsec / 2] = -1;
        cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 1, 0), CT_ERR_RANGE);
        s.sec[s.nsec / 2] = keep;
        ct_idx k4 = s.n4[s.ns - 1];
        s.n4[s.ns - 1] = s.nn + 7;
        cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_ERR_RANGE);
        s.n4[s.ns - 1] = k4;
        s.z[s.sec[s.nsec - 1]] = (ct_real)NAN;
        cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_ERR_NONFINITE);
        s.z[s.sec[s.nsec - 1]] = (ct_real)-INFINITY;
        cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 1, 0), CT_ERR_NONFINITE);
        s.z[s.sec[s.nsec - 1]] = (ct_real)0.3;
        /* Repaired: it runs again. */
        cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_OK);
        cr_assert_eq(out.n, 3 * n * n - 2 * n);
        ct_pairs_destroy(&out);
        ctt_scene_free(&s);
    }
}

Test(search_bucket, scattered_numbering, .timeout = 120)
{
    const int n = 100;
    ctt_scene s;
    two_plates(&s, n, 0.3, 0, 1, 0);
    uint64_t r = 77;
    /* A random node permutation perm (old -> new), applied everywhere. */
    ct_idx *perm = malloc(sizeof(ct_idx) * (size_t)s.nn);
    ct_real *t = malloc(sizeof(ct_real) * (size_t)s.nn);
    for (ct_idx i = 0; i < s.nn; i++)
        perm[i] = i;
    for (ct_idx i = s.nn - 1; i > 0; i--) {
        ct_idx j = (ct_idx)(rnd(&r) * (i + 1)), v = perm[i];
        perm[i] = perm[j];
        perm[j] = v;
    }
    ct_real *c[3] = {s.x, s.y, s.z};
    for (int k = 0; k < 3; k++) {
        for (ct_idx i = 0; i < s.nn; i++)
            t[perm[i]] = c[k][i];
        memcpy(c[k], t, sizeof(ct_real) * (size_t)s.nn);
    }
    for (ct_idx j = 0; j < s.ns; j++) {
        s.n1[j] = perm[s.n1[j]], s.n2[j] = perm[s.n2[j]];
        s.n3[j] = perm[s.n3[j]], s.n4[j] = perm[s.n4[j]];
    }
    for (ct_idx i = 0; i < s.nsec; i++)
        s.sec[i] = perm[s.sec[i]];
    /* Random segment order. */
    for (ct_idx j = s.ns - 1; j > 0; j--) {
        ct_idx q = (ct_idx)(rnd(&r) * (j + 1));
        ct_idx *a[4] = {s.n1, s.n2, s.n3, s.n4};
        for (int k = 0; k < 4; k++) {
            ct_idx v = a[k][j];
            a[k][j] = a[k][q];
            a[k][q] = v;
        }
    }
    shuffle_sec(&s, 31);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    cr_assert_eq(check_same(&in), 3 * n * n - 2 * n);
    /* One search reused across calls (its packed copy of the coordinates
     * must be made afresh by each): a NaN main corner is seen, then the
     * repaired input gives the pairs again, and a main node lifted out of
     * reach loses its segments' pairs. */
    {
        ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
        ct_search *bs;
        cr_assert_eq(ct_search_init(&bs, &p), CT_OK);
        ct_pairs o;
        ct_pairs_init(&o, 0);
        ctt_threads(2);
        const ct_idx m = s.n1[s.ns / 2];
        const ct_real zm = s.z[m];
        cr_assert_eq(ct_search_run(bs, &in, &o), CT_OK);
        cr_assert_eq(o.n, 3 * n * n - 2 * n);
        s.z[m] = (ct_real)NAN;
        cr_assert_eq(ct_search_run(bs, &in, &o), CT_ERR_NONFINITE);
        s.z[m] = zm;
        cr_assert_eq(ct_search_run(bs, &in, &o), CT_OK);
        cr_assert_eq(o.n, 3 * n * n - 2 * n);
        s.z[m] = zm - 100;
        cr_assert_eq(ct_search_run(bs, &in, &o), CT_OK);
        ct_idx moved = o.n;
        cr_assert_eq(check_same(&in), moved);
        cr_assert_lt(moved, 3 * n * n - 2 * n);
        s.z[m] = zm;
        ct_pairs_destroy(&o);
        ct_search_destroy(bs);
    }
    if (!ctt_checking()) {
        in.filter = CT_FILTER_BOX;
        cr_assert_geq(check_same(&in), 3 * n * n - 2 * n);
    }
    free(perm);
    free(t);
    ctt_scene_free(&s);
}

/* Two nodes of one cell are queried together (bk_cands_batch2): cells of
 * 36 to 289 entries (across the 256 of its buffer and the batch's 128), a
 * node's candidates filling the batch more than once, in secondary order,
 * in cell order (shuffled), and in self contact (own segments left out). */
Test(search_bucket, two_nodes_of_a_long_cell, .timeout = 120)
{
    const int sides[4] = {6, 12, 15, 17};
    for (int k = 0; k < 4; k++) {
        const int n = sides[k];
        for (int shuf = 0; shuf < 2; shuf++) {
            ctt_scene s;
            two_plates(&s, n, 0.05, 0, 0.1, 0);
            if (shuf)
                shuffle_sec(&s, 7 + (uint64_t)k);
            ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
            for (int64_t cells = 1; cells <= 8; cells *= 8)
                cr_assert_gt(check_same_cells(&in, cells), 0);
            ctt_scene_free(&s);
        }
        ctt_scene s;
        two_plates(&s, n, 0.05, 0, 0.1, 0);
        for (ct_idx i = 0; i < s.nn; i++)
            s.sec[i] = i;
        s.nsec = s.nn;
        ct_search_input in = ctt_scene_input(&s, 0.1, 0.05, 1);
        for (int64_t cells = 1; cells <= 8; cells *= 8)
            cr_assert_gt(check_same_cells(&in, cells), 0);
        ctt_scene_free(&s);
    }
}
