/*
 * test_search_families.c -- every search against the direct search on every
 * synthetic family, at several sizes, gaps and numberings, and the same
 * bytes for 1 and 2 threads.
 */
#include "test_search_scene.h"

#include <string.h>

#include "meshgen.h"

/* Pairs of `sub` not in `all`, both canonical (secondary order = node order
 * because the case's secondary list is sorted). */
static int64_t missing(const ct_pairs *sub, const ct_pairs *all)
{
    int64_t miss = 0, j = 0;
    for (ct_idx i = 0; i < sub->n; i++) {
        while (j < all->n && (all->node[j] < sub->node[i] ||
                              (all->node[j] == sub->node[i] && all->seg[j] < sub->seg[i])))
            j++;
        if (!(j < all->n && all->node[j] == sub->node[i] && all->seg[j] == sub->seg[i]))
            miss++;
    }
    return miss;
}

/* expect_pairs: the search distance reaches across the case's spacing (the
 * plates are 0.3 h apart, the folded layers 0.4 h), so the direct search
 * must find pairs. */
static void check_case(const char *family, int64_t n, ctd_numbering num, double gap_h,
                       double margin_h, int expect_pairs)
{
    ctd_case c;
    ct_diag d = {0};
    int rc = ctd_case_make(&c, family, n, num, 7, &d);
    cr_assert_eq(rc, CT_OK, "case %s: %s", family, d.msg);
    double h = c.h_mean;
    ct_search_input in;
    ctd_case_input(&c, (ct_real)(gap_h * h), (ct_real)(margin_h * h), &in);
    ct_pairs ref, got;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&got, 0);
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    if (expect_pairs)
        cr_assert_gt(ref.n, 0, "%s (n=%lld): the case has no contact candidates", family,
                     (long long)n);
    for (int a = CT_SEARCH_BUCKET; a <= CT_SEARCH_BSP; a++) {
        ctt_search((ct_search_algo)a, &in, &got);
        cr_assert(ctt_same_pairs(&ref, &got),
                  "%s, n=%lld, numbering %s, gap %g h: %s gives %d pairs (missing %lld, extra %lld), "
                  "direct %d",
                  family, (long long)n, ctd_numbering_name(num), gap_h, ct_search_algo_name(a),
                  got.n, (long long)missing(&ref, &got), (long long)missing(&got, &ref), ref.n);
    }
    /* The bsp search with every leaf on the dense path, and with none. */
    for (int dense = -1; dense <= 1; dense += 2) {
        ct_search_params p = ct_search_default_params(CT_SEARCH_BSP);
        p.dense = dense;
        ctt_search_with(&p, &in, &got);
        cr_assert(ctt_same_pairs(&ref, &got),
                  "%s, n=%lld, numbering %s, gap %g h: bsp with dense %d gives %d pairs (missing "
                  "%lld, extra %lld), direct %d",
                  family, (long long)n, ctd_numbering_name(num), gap_h, dense, got.n,
                  (long long)missing(&ref, &got), (long long)missing(&got, &ref), ref.n);
    }
    /* The topological search may miss pairs; it never reports one that the
     * direct search rejects. */
    ctt_search(CT_SEARCH_TOPO, &in, &got);
    cr_assert_eq(missing(&got, &ref), 0, "%s: topological reported pairs direct rejects", family);
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&got);
    ctd_case_destroy(&c);
}

Test(search_families, all_families_match_direct, .timeout = 240)
{
    int nf = 0;
    const char *const *fam = ctd_case_families(&nf);
    cr_assert_geq(nf, 8);
    int64_t sizes[] = {300, 3000};
    int nsize = ctt_checking() ? 1 : 2;
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < nsize; k++) {
            check_case(fam[f], sizes[k], CTD_NUM_NATURAL, 0.4, 0.1, 1);
            check_case(fam[f], sizes[k], CTD_NUM_SHUFFLED, 0.1, 0.05, 0);
        }
}

Test(search_families, gaps_and_numberings, .timeout = 240)
{
    const double gaps[] = {0.0, 0.05, 0.3, 1.0, 2.5};
    const ctd_numbering nums[] = {CTD_NUM_NATURAL, CTD_NUM_SHUFFLED, CTD_NUM_SFC};
    int64_t n = ctt_checking() ? 500 : 4000;
    for (int g = 0; g < 5; g++)
        for (int k = 0; k < 3; k++) {
            check_case("plates", n, nums[k], gaps[g], 0.1, gaps[g] >= 0.3);
            check_case("folded", n, nums[k], gaps[g], 0.1, gaps[g] >= 0.3);
        }
}

/* The same output bytes with 1 and 2 threads, for every algorithm. */
Test(search_families, thread_count_does_not_change_bytes, .timeout = 240)
{
    const char *fams[] = {"plates", "folded", "soup", "graded"};
    int64_t n = ctt_checking() ? 2000 : 20000;
    for (int f = 0; f < 4; f++) {
        ctd_case c;
        ct_diag d = {0};
        cr_assert_eq(ctd_case_make(&c, fams[f], n, CTD_NUM_SHUFFLED, 3, &d), CT_OK, "%s", d.msg);
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.3 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in);
        for (int a = 0; a < CT_SEARCH_NALGO; a++) {
            if (a == CT_SEARCH_DIRECT && (double)c.sec.n * c.main.n > 1e8)
                continue;
            ct_pairs p1, p2;
            ct_pairs_init(&p1, 0);
            ct_pairs_init(&p2, 0);
            ctt_threads(1);
            ctt_search((ct_search_algo)a, &in, &p1);
            ctt_threads(2);
            ctt_search((ct_search_algo)a, &in, &p2);
            cr_assert(ctt_same_pairs(&p1, &p2), "%s on %s: 1 and 2 threads differ (%d vs %d pairs)",
                      ct_search_algo_name(a), fams[f], p1.n, p2.n);
            ct_pairs_destroy(&p1);
            ct_pairs_destroy(&p2);
        }
        ctd_case_destroy(&c);
    }
}

/* Self contact: a node's own neighbourhood cannot be its closest main node
 * (its segments are excluded), so the topological search must look across
 * the fold. On the crushed tube, whose facing walls are smooth, it must find
 * every pair the direct search finds; on the folded sheet it must find
 * pairs (it used to find none) and never one the direct search rejects. */
Test(search_families, topological_in_self_contact)
{
    const char *fams[] = {"tube", "folded"};
    for (int f = 0; f < 2; f++) {
        ctd_case c;
        ct_diag d = {0};
        cr_assert_eq(ctd_case_make(&c, fams[f], ctt_checking() ? 2000 : 6000, CTD_NUM_NATURAL, 1, &d),
                     CT_OK, "%s", d.msg);
        cr_assert_eq(c.self, 1);
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.4 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in);
        ct_pairs ref, got;
        ct_pairs_init(&ref, 0);
        ct_pairs_init(&got, 0);
        ctt_search(CT_SEARCH_DIRECT, &in, &ref);
        ctt_search(CT_SEARCH_TOPO, &in, &got);
        cr_assert_gt(ref.n, 0);
        cr_assert_eq(missing(&got, &ref), 0, "%s: topological reports pairs direct rejects", fams[f]);
        if (f == 0)
            cr_assert(ctt_same_pairs(&ref, &got), "tube: topological finds %d of %d pairs", got.n, ref.n);
        else
            cr_assert_gt(got.n, ref.n / 4, "folded: topological finds only %d of %d pairs", got.n,
                         ref.n);
        ct_pairs_destroy(&ref);
        ct_pairs_destroy(&got);
        ctd_case_destroy(&c);
    }
}

/* One search with parameters p; returns its code (out holds the pairs when
 * it is CT_OK). */
static int search_rc(const ct_search_params *p, const ct_search_input *in, ct_pairs *out)
{
    ct_search *s;
    cr_assert_eq(ct_search_init(&s, p), CT_OK);
    int rc = ct_search_run(s, in, out);
    ct_search_destroy(s);
    return rc;
}

/* The pair limit (ct_search_params.max_pairs): for every algorithm and
 * path (the bucket's direct and cell-order queries and its baseline, bsp's
 * dense and batch leaves, the renumbered copy), 1 and 2 threads, a limit
 * of exactly the pair count returns those pairs and one less fails with
 * CT_ERR_TOOBIG, as does a limit far below (where the search stops
 * early). */
Test(search_families, pair_limit_is_exact, .timeout = 240)
{
    const ctd_numbering nums[2] = {CTD_NUM_NATURAL, CTD_NUM_SHUFFLED};
    int64_t n = ctt_checking() ? 2000 : 5000;
    for (int u = 0; u < 2; u++) {
        ctd_case c;
        ct_diag d = {0};
        cr_assert_eq(ctd_case_make(&c, "folded", n, nums[u], 5, &d), CT_OK, "%s", d.msg);
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.3 * c.h_mean), (ct_real)(0.2 * c.h_mean), &in);
        struct {
            ct_search_algo a;
            int variant, renumber;
        } v[] = {{CT_SEARCH_DIRECT, 1, 0},  {CT_SEARCH_TOPO, 1, 0}, {CT_SEARCH_TOPO, 1, -1},
                 {CT_SEARCH_BUCKET, 1, 0},  {CT_SEARCH_BUCKET, 1, 1}, {CT_SEARCH_BUCKET, 0, -1},
                 {CT_SEARCH_BSP, 1, 0},     {CT_SEARCH_BSP, 1, -1}};
        for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
            ct_search_params p = ct_search_default_params(v[k].a);
            p.variant = v[k].variant;
            p.renumber = v[k].renumber;
            ct_pairs all, got;
            ct_pairs_init(&all, 0);
            ct_pairs_init(&got, 0);
            ctt_threads(1);
            cr_assert_eq(search_rc(&p, &in, &all), CT_OK);
            cr_assert_gt(all.n, 1000, "%s: too few pairs to test a limit", ct_search_algo_name(v[k].a));
            for (int t = 1; t <= 2; t++) {
                ctt_threads(t);
                p.max_pairs = all.n;
                cr_assert_eq(search_rc(&p, &in, &got), CT_OK, "%s case %zu, %d threads",
                             ctd_numbering_name(nums[u]), k, t);
                cr_assert(ctt_same_pairs(&all, &got));
                p.max_pairs = all.n - 1;
                cr_assert_eq(search_rc(&p, &in, &got), CT_ERR_TOOBIG, "%s case %zu, %d threads",
                             ctd_numbering_name(nums[u]), k, t);
                p.max_pairs = 10;
                cr_assert_eq(search_rc(&p, &in, &got), CT_ERR_TOOBIG, "%s case %zu, %d threads",
                             ctd_numbering_name(nums[u]), k, t);
            }
            ct_pairs_destroy(&all);
            ct_pairs_destroy(&got);
        }
        ctd_case_destroy(&c);
    }
}
