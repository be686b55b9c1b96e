/*
 * test_search_renumber.c -- the spatial renumbering of scattered inputs
 * (ct_search_params.renumber, kernels/search_renumber.c): forced on, the
 * bucket and bsp searches return exactly the direct search's pairs on every
 * family, natural and shuffled, self contact included, with the same bytes
 * for 1 and 2 threads; "auto" renumbers a large shuffled case and not an
 * ordered one, and for the bucket a numbering local only in short pieces
 * (told from rows and space-filling curves); a secondary list out of order and a secondary listed twice
 * give what the plain search gives; every algorithm reports an index out of
 * range and a non-finite node it uses with the same code.
 */
#include "test_search_scene.h"

#include <math.h>

#include "ct_internal.h"
#include "meshgen.h"

static void search_rn(ct_search_algo a, int renumber, const ct_search_input *in, ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(a);
    p.renumber = renumber;
    ctt_search_with(&p, in, out);
}

static void check_family(const char *family, int64_t n, ctd_numbering num)
{
    ctd_case c;
    ct_diag d = {0};
    cr_assert_eq(ctd_case_make(&c, family, n, num, 11, &d), CT_OK, "%s: %s", family, d.msg);
    ct_search_input in;
    ctd_case_input(&c, (ct_real)(0.4 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in);
    ct_pairs ref, got, got2;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&got, 0);
    ct_pairs_init(&got2, 0);
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    for (int a = CT_SEARCH_BUCKET; a <= CT_SEARCH_BSP; a++) {
        ctt_threads(1);
        search_rn((ct_search_algo)a, 1, &in, &got);
        ctt_threads(2);
        search_rn((ct_search_algo)a, 1, &in, &got2);
        cr_assert(ctt_same_pairs(&ref, &got), "%s n=%lld %s: renumbered %s gives %d pairs, direct %d",
                  family, (long long)n, ctd_numbering_name(num), ct_search_algo_name(a), got.n,
                  ref.n);
        cr_assert(ctt_same_pairs(&got, &got2), "%s %s: 1 and 2 threads differ", family,
                  ct_search_algo_name(a));
    }
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&got);
    ct_pairs_destroy(&got2);
    ctd_case_destroy(&c);
}

Test(search_renumber, forced_on_matches_direct_on_every_family, .timeout = 240)
{
    int nf = 0;
    const char *const *fam = ctd_case_families(&nf);
    cr_assert_geq(nf, 8);
    for (int f = 0; f < nf; f++) {
        check_family(fam[f], 400, CTD_NUM_SHUFFLED);
        check_family(fam[f], ctt_checking() ? 1000 : 3000, CTD_NUM_SHUFFLED);
        check_family(fam[f], 1000, CTD_NUM_NATURAL);
    }
}

/* Whether a search of algorithm a with renumber r on in made the renumbered
 * copy (the workspace creates its renumbering state on first use; the test
 * reads the library's internal struct for that one fact). Asserts the
 * pairs equal ref. */
static int renumbered(ct_search_algo a, int r, const ct_search_input *in, const ct_pairs *ref)
{
    ct_search_params p = ct_search_default_params(a);
    p.renumber = r;
    ct_search *s;
    ct_pairs got;
    ct_pairs_init(&got, 0);
    cr_assert_eq(ct_search_init(&s, &p), CT_OK);
    cr_assert_eq(ct_search_run(s, in, &got), CT_OK);
    const int made = s->rn != NULL;
    ct_search_destroy(s);
    cr_assert(ctt_same_pairs(ref, &got), "%s, renumber %d: the pairs differ",
              ct_search_algo_name(a), r);
    ct_pairs_destroy(&got);
    return made;
}

/* "auto": a shuffled case above the sampling threshold is renumbered for
 * the bsp search, an ordered one is not, nor is a shuffled one below 2^19
 * nodes for the bucket (its own scattered path is as fast there); "on"
 * always renumbers, "off" never; the pairs are the plain bucket search's
 * in every case. */
Test(search_renumber, auto_renumbers_scattered_only, .timeout = 120)
{
    const ctd_numbering nums[2] = {CTD_NUM_SHUFFLED, CTD_NUM_NATURAL};
    for (int k = 0; k < 2; k++) {
        ctd_case c;
        ct_diag d = {0};
        cr_assert_eq(ctd_case_make(&c, "plates", 20000, nums[k], 5, &d), CT_OK, "%s", d.msg);
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.4 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in);
        cr_assert_lt(in.nnode, 1 << 19);
        ct_pairs ref;
        ct_pairs_init(&ref, 0);
        search_rn(CT_SEARCH_BUCKET, -1, &in, &ref);
        cr_assert_gt(ref.n, 0);
        const int shuffled = nums[k] == CTD_NUM_SHUFFLED;
        cr_assert_eq(renumbered(CT_SEARCH_BSP, 0, &in, &ref), shuffled,
                     "bsp, auto, %s numbering", ctd_numbering_name(nums[k]));
        cr_assert_eq(renumbered(CT_SEARCH_BUCKET, 0, &in, &ref), 0, "bucket, auto, %s numbering",
                     ctd_numbering_name(nums[k]));
        for (int a = CT_SEARCH_BUCKET; a <= CT_SEARCH_BSP; a++) {
            cr_assert(renumbered((ct_search_algo)a, 1, &in, &ref));
            cr_assert(!renumbered((ct_search_algo)a, -1, &in, &ref));
        }
        ct_pairs_destroy(&ref);
        ctd_case_destroy(&c);
    }
}

/* A numbering local only in short pieces scattered in space (the soup: 9
 * quads per plate, plates in random places) is told from ordered ones,
 * whose rows jump back once per row (the folded sheet's rows of 1532
 * segments, which a sampling stride of nseg / 256 hit every fourth time)
 * and from a space-filling curve's, which jumps far only at its coarsest
 * levels. */
Test(search_renumber, pieces_told_from_rows_and_curves, .timeout = 120)
{
    const struct {
        const char *family;
        ctd_numbering num;
        int pieces;
    } cases[] = {{"soup", CTD_NUM_NATURAL, 1},    {"soup", CTD_NUM_SHUFFLED, 1},
                 {"plates", CTD_NUM_SHUFFLED, 1}, {"plates", CTD_NUM_NATURAL, 0},
                 {"plates", CTD_NUM_SFC, 0},      {"folded", CTD_NUM_NATURAL, 0},
                 {"folded", CTD_NUM_SFC, 0},      {"crumpled", CTD_NUM_SFC, 0},
                 {"tube", CTD_NUM_NATURAL, 0},    {"sphere", CTD_NUM_SFC, 0},
                 {"graded", CTD_NUM_NATURAL, 0},  {"block", CTD_NUM_SFC, 0}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        ctd_case c;
        ct_diag d = {0};
        cr_assert_eq(ctd_case_make(&c, cases[k].family, 100000, cases[k].num, 5, &d), CT_OK,
                     "%s", d.msg);
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.3 * c.h_mean), (ct_real)(0.2 * c.h_mean), &in);
        cr_assert_eq(cti_search_pieces(&in), cases[k].pieces, "%s, %s numbering",
                     cases[k].family, ctd_numbering_name(cases[k].num));
        ctd_case_destroy(&c);
    }
}

/* "auto" renumbers the soup's pieces for the bucket search from 2^16 nodes
 * and the topological one from 2^17 (not below; never for bsp, which
 * sorts space itself), with the plain search's pairs. */
Test(search_renumber, auto_renumbers_pieces_for_bucket_and_topo, .timeout = 120)
{
    const int64_t sizes[3] = {30000, 70000, 140000};
    for (int k = 0; k < 3; k++) {
        ctd_case c;
        ct_diag d = {0};
        cr_assert_eq(ctd_case_make(&c, "soup", sizes[k], CTD_NUM_NATURAL, 5, &d), CT_OK, "%s",
                     d.msg);
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.3 * c.h_mean), (ct_real)(0.2 * c.h_mean), &in);
        cr_assert(cti_search_pieces(&in));
        ct_pairs ref;
        ct_pairs_init(&ref, 0);
        search_rn(CT_SEARCH_BUCKET, -1, &in, &ref);
        cr_assert_gt(ref.n, 0);
        const int big = in.nnode >= (1 << 16), bigger = in.nnode >= (1 << 17);
        cr_assert_eq(big, k >= 1);
        cr_assert_eq(bigger, k == 2);
        cr_assert_eq(renumbered(CT_SEARCH_BUCKET, 0, &in, &ref), big, "bucket, auto, %d nodes",
                     (int)in.nnode);
        /* The topological search's own pairs, without renumbering. */
        ct_pairs topo;
        ct_pairs_init(&topo, 0);
        search_rn(CT_SEARCH_TOPO, -1, &in, &topo);
        cr_assert_eq(renumbered(CT_SEARCH_TOPO, 0, &in, &topo), bigger,
                     "topological, auto, %d nodes", (int)in.nnode);
        ct_pairs_destroy(&topo);
        cr_assert(!renumbered(CT_SEARCH_BSP, 0, &in, &ref), "bsp, auto, %d nodes",
                  (int)in.nnode);
        ct_pairs_destroy(&ref);
        ctd_case_destroy(&c);
    }
}

/* A small scene: two rows of quads, a node above each corner region. */
static void build_scene(ctt_scene *s)
{
    ctt_scene_init(s, 64, 16);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 5; i++)
            ctt_scene_node(s, i, j, 0);
    for (int i = 0; i < 4; i++)
        ctt_scene_seg(s, i, i + 1, i + 6, i + 5);
    for (int i = 0; i < 8; i++)
        ctt_scene_sec(s, ctt_scene_node(s, 0.3 + 0.5 * i, 0.4, 0.2 + 0.05 * i));
}

/* The secondary list in reverse order: canonical order is by position in
 * the list, so the renumbered result must follow the list, as the plain
 * one does. A secondary listed twice: the plain search's result (the
 * renumbering steps aside). */
Test(search_renumber, secondary_order_and_duplicates)
{
    ctt_scene s;
    build_scene(&s);
    for (int i = 0; i < s.nsec / 2; i++) {
        ct_idx t = s.sec[i];
        s.sec[i] = s.sec[s.nsec - 1 - i];
        s.sec[s.nsec - 1 - i] = t;
    }
    ct_search_input in = ctt_scene_input(&s, 0.5, 0.1, 0);
    ct_pairs a, b;
    ct_pairs_init(&a, 0);
    ct_pairs_init(&b, 0);
    for (int alg = CT_SEARCH_BUCKET; alg <= CT_SEARCH_BSP; alg++) {
        search_rn((ct_search_algo)alg, -1, &in, &a);
        search_rn((ct_search_algo)alg, 1, &in, &b);
        cr_assert_gt(a.n, 4);
        cr_assert_eq(a.node[0], s.sec[0], "the first pair is not the first listed secondary's");
        cr_assert(ctt_same_pairs(&a, &b), "%s: the renumbered pairs differ (reversed list)",
                  ct_search_algo_name(alg));
    }
    ctt_scene_sec(&s, s.sec[2]); /* listed twice */
    in = ctt_scene_input(&s, 0.5, 0.1, 0);
    for (int alg = CT_SEARCH_BUCKET; alg <= CT_SEARCH_BSP; alg++) {
        search_rn((ct_search_algo)alg, -1, &in, &a);
        search_rn((ct_search_algo)alg, 1, &in, &b);
        cr_assert(ctt_same_pairs(&a, &b), "%s: the renumbered pairs differ (duplicate)",
                  ct_search_algo_name(alg));
    }
    ct_pairs_destroy(&a);
    ct_pairs_destroy(&b);
    ctt_scene_free(&s);
}

/* Bad input: every algorithm, with renumbering on and off, reports an
 * index out of range (a corner, a secondary) and a non-finite secondary or
 * corner with the same code. */
Test(search_renumber, bad_input_every_algorithm)
{
    const int want[4] = {CT_ERR_RANGE, CT_ERR_RANGE, CT_ERR_NONFINITE, CT_ERR_NONFINITE};
    for (int bad = 0; bad < 4; bad++) {
        ctt_scene s;
        build_scene(&s);
        if (bad == 0)
            s.n3[1] = s.nn + 7; /* corner out of range */
        else if (bad == 1)
            s.sec[3] = -2; /* secondary out of range */
        else if (bad == 2)
            s.x[s.sec[5]] = (ct_real)NAN; /* non-finite secondary */
        else
            s.z[s.n2[3]] = (ct_real)INFINITY; /* non-finite corner */
        ct_search_input in = ctt_scene_input(&s, 0.5, 0.1, 0);
        for (int alg = 0; alg < CT_SEARCH_NALGO; alg++)
            for (int r = -1; r <= 1; r += 2) {
                ct_search_params p = ct_search_default_params((ct_search_algo)alg);
                p.renumber = r;
                ct_search *w;
                ct_pairs o;
                ct_pairs_init(&o, 0);
                cr_assert_eq(ct_search_init(&w, &p), CT_OK);
                int rc = ct_search_run(w, &in, &o);
                ct_search_destroy(w);
                ct_pairs_destroy(&o);
                cr_assert_eq(rc, want[bad], "case %d, %s, renumber %d: %s, want %s", bad,
                             ct_search_algo_name(alg), r, ct_strerror(rc),
                             ct_strerror(want[bad]));
            }
        ctt_scene_free(&s);
    }
    /* A non-finite node no segment and no secondary uses is not read. */
    ctt_scene s;
    build_scene(&s);
    ctt_scene_node(&s, (double)NAN, 0, 0);
    ct_search_input in = ctt_scene_input(&s, 0.5, 0.1, 0);
    ct_pairs a, b;
    ct_pairs_init(&a, 0);
    ct_pairs_init(&b, 0);
    ctt_search(CT_SEARCH_DIRECT, &in, &a);
    search_rn(CT_SEARCH_BUCKET, 1, &in, &b);
    cr_assert(ctt_same_pairs(&a, &b));
    ct_pairs_destroy(&a);
    ct_pairs_destroy(&b);
    ctt_scene_free(&s);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    p.renumber = 2;
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_ERR_ARG);
}

/* A small interface in a large model (node arrays far longer than what the
 * interface uses): "auto" does not renumber (the copy's cost grows with all
 * the nodes), a NaN in a node the interface does not use is not read, and
 * one in a secondary is still reported. */
Test(search_renumber, small_interface_in_large_model, .timeout = 120)
{
    ctd_case c;
    ct_diag d = {0};
    cr_assert_eq(ctd_case_make(&c, "plates", 20000, CTD_NUM_SHUFFLED, 5, &d), CT_OK, "%s", d.msg);
    ct_search_input in;
    ctd_case_input(&c, (ct_real)(0.4 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in);
    const ct_idx n0 = in.nnode, n = n0 + 400000;
    ct_real *xyz[3];
    const ct_real *src[3] = {in.x, in.y, in.z};
    for (int a = 0; a < 3; a++) {
        xyz[a] = ct_calloc((size_t)n, sizeof(ct_real));
        cr_assert(xyz[a]);
        memcpy(xyz[a], src[a], sizeof(ct_real) * (size_t)n0);
        for (ct_idx i = n0; i < n; i++)
            xyz[a][i] = (ct_real)(1e4 + i); /* far away, unused */
    }
    xyz[0][n - 7] = (ct_real)NAN; /* unused */
    ct_search_input big = in;
    big.nnode = n;
    big.x = xyz[0], big.y = xyz[1], big.z = xyz[2];
    ct_pairs ref, got;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&got, 0);
    search_rn(CT_SEARCH_BUCKET, -1, &in, &ref);
    cr_assert(!renumbered(CT_SEARCH_BSP, 0, &big, &ref), "auto renumbered a small interface");
    cr_assert(!renumbered(CT_SEARCH_BSP, -1, &big, &ref));
    /* The same input at its own size is renumbered by "auto". */
    cr_assert(renumbered(CT_SEARCH_BSP, 0, &in, &ref));
    xyz[2][in.sec[17]] = (ct_real)INFINITY;
    for (int alg = 0; alg < CT_SEARCH_NALGO; alg++) {
        if (alg == CT_SEARCH_DIRECT)
            continue; /* 20000 x 20000 pairs: too slow for a bad-input check */
        ct_search_params p = ct_search_default_params((ct_search_algo)alg);
        ct_search *s;
        cr_assert_eq(ct_search_init(&s, &p), CT_OK);
        cr_assert_eq(ct_search_run(s, &big, &got), CT_ERR_NONFINITE, "%s",
                     ct_search_algo_name(alg));
        ct_search_destroy(s);
    }
    for (int a = 0; a < 3; a++)
        ct_free(xyz[a]);
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&got);
    ctd_case_destroy(&c);
}
