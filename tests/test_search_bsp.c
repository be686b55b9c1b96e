/*
 * test_search_bsp.c -- the quick-sort (binary space partition) search
 * returns exactly the pairs of the direct (all pairs) search, byte for byte,
 * on hard geometry, for any leaf size, box threshold and thread count.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "search_bsp_internal.h"
#include "test_search_scene.h"

/* The classic two plates: main quads (or triangles) at z = 0, a node plate
 * at z = dz shifted in-plane by (0.25, 0.35) element. */
static void bs_two_plates(ctt_scene *s, int n, double dz, int tri)
{
    ctt_scene_init(s, 2 * n * n, 2 * n * n);
    ctt_scene_plate(s, n, n, 0, 0, 0, 1.0, 1, tri);
    ct_idx b = ctt_scene_plate(s, n, n, 0.25, 0.35, dz, 1.0, 0, 0);
    for (ct_idx i = 0; i < n * n; i++)
        ctt_scene_sec(s, b + i);
}

static uint64_t rng_state;
static double rnd(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* bsp (default parameters and a few leaf sizes / box thresholds) against
 * direct; returns the number of pairs. */
static ct_idx check_bsp(const ct_search_input *in, const char *what)
{
    ct_pairs ref, got;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&got, 0);
    ctt_search_tuned(CT_SEARCH_DIRECT, 0, 0, in, &ref);
    const int leaves[] = {0, 1, 7, 1000};
    const double boxes[] = {0, 1e-3, 0.7};
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 3; b++) {
            if (a > 0 && b > 0 && a != b)
                continue; /* a representative set of combinations */
            ctt_search_tuned(CT_SEARCH_BSP, leaves[a], boxes[b], in, &got);
            cr_assert(ctt_same_pairs(&ref, &got),
                      "%s: bsp (leaf %d, min_box %g) gives %d pairs, direct %d (or a different "
                      "list)",
                      what, leaves[a], boxes[b], got.n, ref.n);
        }
    /* Every leaf on the dense path (search_bsp_dense.c), and none. */
    for (int dense = -1; dense <= 1; dense += 2) {
        ct_search_params p = ct_search_default_params(CT_SEARCH_BSP);
        p.dense = dense;
        ctt_search_with(&p, in, &got);
        cr_assert(ctt_same_pairs(&ref, &got), "%s: bsp with dense %d gives %d pairs, direct %d",
                  what, dense, got.n, ref.n);
    }
    ct_idx n = ref.n;
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&got);
    return n;
}

static int small(void) { return ctt_checking(); }

Test(search_bsp, two_plates_several_gaps)
{
    ctt_scene s;
    int n = small() ? 14 : 40;
    bs_two_plates(&s, n, 0.3, 0);
    const double gaps[] = {0.0, 0.1, 0.25, 0.45, 1.0, 2.6};
    for (int g = 0; g < 6; g++) {
        ct_search_input in = ctt_scene_input(&s, gaps[g], 0.05, 0);
        ct_idx np = check_bsp(&in, "two plates");
        /* Not vacuous: from gap + margin 0.3 on every node has its quad. */
        if (gaps[g] + 0.05 >= 0.3)
            cr_assert_geq(np, (n - 1) * (n - 1), "gap %g: only %d pairs", gaps[g], np);
        else
            cr_assert_eq(np, 0);
    }
    ctt_scene_free(&s);
}

Test(search_bsp, triangles)
{
    ctt_scene s;
    bs_two_plates(&s, small() ? 12 : 35, 0.2, 1);
    for (int g = 0; g < 3; g++) {
        ct_search_input in = ctt_scene_input(&s, 0.15 + 0.3 * g, 0.1, 0);
        cr_assert_gt(check_bsp(&in, "triangles"), 0);
    }
    ctt_scene_free(&s);
}

/* A sheet folded back over itself (z = 0 going out, z = 0.3 coming back):
 * self contact, every node a secondary of the same surface. */
Test(search_bsp, folded_sheet_self_contact)
{
    ctt_scene s;
    int n = small() ? 10 : 24, w = small() ? 6 : 12;
    int nu = 2 * n + 1;
    ctt_scene_init(&s, nu * w, nu * w);
    for (int j = 0; j < w; j++)
        for (int i = 0; i < nu; i++) {
            double u = i <= n ? i : 2 * n - i + 0.5;
            double z = i <= n ? 0 : 0.3;
            ctt_scene_node(&s, u * 0.5, j * 0.5, z);
        }
    for (int j = 0; j + 1 < w; j++)
        for (int i = 0; i + 1 < nu; i++) {
            ct_idx a = j * nu + i;
            ctt_scene_seg(&s, a, a + 1, a + nu + 1, a + nu);
        }
    for (ct_idx i = 0; i < s.nn; i++)
        ctt_scene_sec(&s, i);
    ct_search_input in = ctt_scene_input(&s, 0.25, 0.1, 1);
    ct_idx np = check_bsp(&in, "folded self");
    cr_assert_gt(np, 0);
    ctt_scene_free(&s);
}

/* Every secondary in one tiny box (1e-9 wide), and all at one point. */
Test(search_bsp, all_nodes_in_one_tiny_box)
{
    ctt_scene s;
    ctt_scene_init(&s, 2000, 400);
    ctt_scene_plate(&s, 12, 12, -5, -5, 0, 1.0, 1, 0);
    rng_state = 7;
    for (int i = 0; i < 500; i++)
        ctt_scene_sec(&s, ctt_scene_node(&s, 0.3 + 1e-9 * rnd(), 0.2 + 1e-9 * rnd(),
                                         0.1 + 1e-9 * rnd()));
    for (int i = 0; i < 500; i++)
        ctt_scene_sec(&s, ctt_scene_node(&s, 1.5, 1.5, 0.2));
    ct_search_input in = ctt_scene_input(&s, 0.2, 0.05, 0);
    ct_idx np = check_bsp(&in, "tiny box");
    cr_assert_geq(np, 1000); /* every node is over a quad at 0.1 or 0.2 */
    in.margin = 0;
    in.gap = 0;
    check_bsp(&in, "tiny box, zero gap");
    ctt_scene_free(&s);
}

/* Coplanar (nodes in the plane of the segments) and collinear nodes. */
Test(search_bsp, coplanar_and_collinear)
{
    ctt_scene s;
    ctt_scene_init(&s, 2000, 400);
    ctt_scene_plate(&s, 15, 15, 0, 0, 0, 1.0, 1, 0);
    rng_state = 11;
    for (int i = 0; i < 300; i++)
        /* coplanar */
        ctt_scene_sec(&s, ctt_scene_node(&s, 16 * rnd() - 0.5, 16 * rnd() - 0.5, 0.0));
    for (int i = 0; i < 300; i++)
        ctt_scene_sec(&s, ctt_scene_node(&s, 0.05 * i - 0.5, 3.5, 0.2)); /* collinear along x */
    for (int i = 0; i < 100; i++)
        ctt_scene_sec(&s, ctt_scene_node(&s, 7.0, 7.0, 0.01 * i)); /* collinear along z */
    ct_search_input in = ctt_scene_input(&s, 0.1, 0.1, 0);
    cr_assert_gt(check_bsp(&in, "coplanar/collinear"), 300);
    /* Main nodes on one line too: degenerate (zero-area) segments. */
    ctt_scene t;
    ctt_scene_init(&t, 500, 100);
    for (int i = 0; i < 40; i++)
        ctt_scene_node(&t, 0.5 * i, 0, 0);
    for (int i = 0; i + 3 < 40; i += 2)
        ctt_scene_seg(&t, i, i + 1, i + 2, i + 3);
    for (int i = 0; i < 200; i++)
        ctt_scene_sec(&t, ctt_scene_node(&t, 0.1 * i - 0.5, 0.05 * (i % 7), 0));
    ct_search_input it = ctt_scene_input(&t, 0.1, 0.05, 0);
    cr_assert_gt(check_bsp(&it, "collinear main"), 0);
    ctt_scene_free(&s);
    ctt_scene_free(&t);
}

/* Nodes repeated at the same coordinates (main and secondary). */
Test(search_bsp, duplicate_coordinates)
{
    ctt_scene s;
    ctt_scene_init(&s, 3000, 600);
    ctt_scene_plate(&s, 10, 10, 0, 0, 0, 1.0, 1, 0);
    ctt_scene_plate(&s, 10, 10, 0, 0, 0, 1.0, 1, 1); /* the same plate again, as triangles */
    for (int k = 0; k < 3; k++) {
        ct_idx b = ctt_scene_plate(&s, 10, 10, 0.5, 0.5, 0.2, 1.0, 0, 0);
        for (ct_idx i = 0; i < 100; i++)
            ctt_scene_sec(&s, b + i);
    }
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.1, 0);
    cr_assert_gt(check_bsp(&in, "duplicates"), 300);
    ctt_scene_free(&s);
}

/* One segment 1000 times larger than the others. */
Test(search_bsp, one_huge_segment)
{
    ctt_scene s;
    ctt_scene_init(&s, 3000, 1000);
    ctt_scene_plate(&s, 20, 20, 0, 0, 0, 0.1, 1, 0);
    ct_idx a = ctt_scene_node(&s, -50, -50, 0.5), b = ctt_scene_node(&s, 50, -50, 0.5);
    ct_idx c = ctt_scene_node(&s, 50, 50, 0.5), d = ctt_scene_node(&s, -50, 50, 0.5);
    ctt_scene_seg(&s, a, b, c, d);
    ct_idx p = ctt_scene_plate(&s, 30, 30, -0.5, -0.5, 0.3, 0.1, 0, 0);
    for (ct_idx i = 0; i < 900; i++)
        ctt_scene_sec(&s, p + i);
    ct_search_input in = ctt_scene_input(&s, 0.2, 0.05, 0);
    ct_idx np = check_bsp(&in, "huge segment");
    cr_assert_geq(np, 900); /* every node is 0.2 below the huge quad */
    ctt_scene_free(&s);
}

/* The same scene offset by 1e6 (and 1e9) and scaled by 1e-6 (gap scaled
 * alike). The tree works in float relative to an origin: these check that
 * it stays conservative. In double, a second cluster at 1e40 (beyond the
 * float range) is added to the 1e9 scene. */
Test(search_bsp, offset_and_scaled_coordinates)
{
    const double off[3] = {1e6, 0, 1e9}, sc[3] = {1, 1e-6, 1};
    for (int v = 0; v < 3; v++) {
        ctt_scene s;
        ctt_scene_init(&s, 2000, 2000);
        rng_state = 99 + (uint64_t)v;
        int n = 16;
        double *xs = malloc(sizeof(double) * n);
        for (int i = 0; i < n; i++)
            xs[i] = off[v] + sc[v] * i;
        ctt_scene_grid(&s, n, n, xs, xs, off[v], 1, 0);
        for (int i = 0; i < 600; i++)
            ctt_scene_sec(&s, ctt_scene_node(&s, off[v] + sc[v] * (n * rnd() - 0.5),
                                             off[v] + sc[v] * (n * rnd() - 0.5),
                                             off[v] + sc[v] * (0.6 * rnd() - 0.3)));
        if (v == 2 && !CTT_SINGLE) {
            ct_idx a = ctt_scene_node(&s, 1e40, 1e40, 1e40),
                   b = ctt_scene_node(&s, 1e40 + 1, 1e40, 1e40);
            ct_idx c = ctt_scene_node(&s, 1e40, 1e40 + 1, 1e40);
            ctt_scene_seg(&s, a, b, c, c);
            ctt_scene_sec(&s, ctt_scene_node(&s, 1e40, 1e40, 1e40));
        }
        ct_search_input in = ctt_scene_input(&s, 0.2 * sc[v], 0.05 * sc[v], 0);
        const char *name[3] = {"offset 1e6", "scaled 1e-6", "offset 1e9"};
        cr_assert_gt(check_bsp(&in, name[v]), 100);
        free(xs);
        ctt_scene_free(&s);
    }
}

Test(search_bsp, empty_inputs)
{
    ctt_scene s;
    bs_two_plates(&s, 5, 0.1, 0);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.1, 0);
    ct_pairs got;
    ct_pairs_init(&got, 0);
    in.nsec = 0;
    ctt_search_tuned(CT_SEARCH_BSP, 0, 0, &in, &got);
    cr_assert_eq(got.n, 0);
    in.nsec = s.nsec;
    in.nseg = 0;
    ctt_search_tuned(CT_SEARCH_BSP, 0, 0, &in, &got);
    cr_assert_eq(got.n, 0);
    in.nsec = 0;
    ctt_search_tuned(CT_SEARCH_BSP, 0, 0, &in, &got);
    cr_assert_eq(got.n, 0);
    ct_pairs_destroy(&got);
    ctt_scene_free(&s);
}

/* Element sizes growing geometrically by 100x across the plate in x and y. */
Test(search_bsp, strongly_graded_mesh)
{
    ctt_scene s;
    int n = small() ? 20 : 45;
    ctt_scene_init(&s, 2 * n * n, n * n);
    double *xs = malloc(sizeof(double) * n);
    double r = pow(100.0, 1.0 / (n - 2)), h = 0.01;
    xs[0] = 0;
    for (int i = 1; i < n; i++, h *= r)
        xs[i] = xs[i - 1] + h;
    ctt_scene_grid(&s, n, n, xs, xs, 0, 1, 0);
    double *ys = malloc(sizeof(double) * n);
    for (int i = 0; i < n; i++)
        ys[i] = xs[i] * 0.97 + 0.003;
    ct_idx b = ctt_scene_grid(&s, n, n, ys, ys, 0.02, 0, 0);
    for (ct_idx i = 0; i < n * n; i++)
        ctt_scene_sec(&s, b + i);
    ct_search_input in = ctt_scene_input(&s, 0.02, 0.01, 0);
    cr_assert_gt(check_bsp(&in, "graded"), n * n / 2);
    in.gap = 0.5;
    check_bsp(&in, "graded, large gap");
    free(xs);
    free(ys);
    ctt_scene_free(&s);
}

/* Random soups: quads and triangles of random sizes and orientations,
 * random secondaries, random gaps, self contact or not, random parameters. */
Test(search_bsp, random_soups_many_seeds, .timeout = 120)
{
    int nseed = small() ? 15 : 60;
    for (int seed = 1; seed <= nseed; seed++) {
        rng_state = 1000 + (uint64_t)seed * 7919;
        int nseg = 20 + (int)(rnd() * 300), nfree = (int)(rnd() * 400);
        int self = seed % 3 == 0;
        double box = 1 + 9 * rnd();
        ctt_scene s;
        ctt_scene_init(&s, 4 * nseg + nfree, nseg);
        for (int k = 0; k < nseg; k++) {
            double c[3] = {box * rnd(), box * rnd(), box * rnd() * (seed % 4 == 1 ? 0 : 1)};
            double size = exp(log(0.01) + rnd() * log(200.0)) * (seed % 5 == 0 ? 10 : 1);
            ct_idx v[4];
            for (int q = 0; q < 4; q++)
                v[q] = ctt_scene_node(&s, c[0] + size * (rnd() - 0.5),
                                      c[1] + size * (rnd() - 0.5),
                                      c[2] + size * (rnd() - 0.5) * (seed % 4 == 1 ? 0 : 1));
            if (rnd() < 0.4)
                ctt_scene_seg(&s, v[0], v[1], v[2], v[2]);
            else
                ctt_scene_seg(&s, v[0], v[1], v[2], v[3]);
        }
        for (int k = 0; k < nfree; k++)
            ctt_scene_node(&s, box * rnd(), box * rnd(), box * rnd());
        for (ct_idx i = 0; i < s.nn; i++)
            if (self || i >= 4 * nseg || rnd() < 0.2)
                ctt_scene_sec(&s, i);
        double gap = rnd() < 0.2 ? 0 : box * 0.1 * rnd();
        ct_search_input in = ctt_scene_input(&s, gap, rnd() < 0.5 ? 0 : gap * 0.3, self);
        ct_pairs ref, got;
        ct_pairs_init(&ref, 0);
        ct_pairs_init(&got, 0);
        ctt_search_tuned(CT_SEARCH_DIRECT, 0, 0, &in, &ref);
        int leaf = (int)(rnd() * 40);
        double mb = rnd() < 0.5 ? 0 : box * 0.2 * rnd();
        ct_search_params p = ct_search_default_params(CT_SEARCH_BSP);
        p.leaf_size = leaf;
        p.min_box = mb;
        p.dense = (seed / 3) % 3 - 1; /* independent of self (seed % 3) */
        ctt_search_with(&p, &in, &got);
        cr_assert(ctt_same_pairs(&ref, &got),
                  "seed %d (self %d, leaf %d, min_box %g, dense %d): %d vs %d", seed, self, leaf,
                  mb, p.dense, got.n, ref.n);
        ct_pairs_destroy(&ref);
        ct_pairs_destroy(&got);
        ctt_scene_free(&s);
    }
}

/* The box filter (a node's distance to a segment's axis-aligned box, the
 * cheaper superset of the hull filter): bsp gives direct's pairs with it
 * too, at every leaf size and on both leaf paths (check_bsp), on two
 * plates at several gaps, quads and triangles, a self-contact fold and
 * random soups; and the box pairs include the hull pairs. The leaf's box
 * loop (search_bsp_leaf.c) ran in no test before. */
Test(search_bsp, box_filter_matches_direct)
{
    const double gaps[] = {0.05, 0.3, 0.6, 1.5};
    for (int tri = 0; tri < 2; tri++)
        for (int g = 0; g < 4; g++) {
            ctt_scene s;
            bs_two_plates(&s, small() ? 8 : 16, 0.3, tri);
            ct_search_input in = ctt_scene_input(&s, gaps[g] * 0.6, gaps[g] * 0.4, 0);
            char what[64];
            snprintf(what, sizeof what, "plates (tri %d, gap %g), hull", tri, gaps[g]);
            const ct_idx hull = check_bsp(&in, what);
            in.filter = CT_FILTER_BOX;
            snprintf(what, sizeof what, "plates (tri %d, gap %g), box", tri, gaps[g]);
            cr_assert_geq(check_bsp(&in, what), hull, "%s: fewer pairs than the hull", what);
            ctt_scene_free(&s);
        }
    for (int seed = 1; seed <= (small() ? 6 : 24); seed++) {
        rng_state = 777 + (uint64_t)seed * 104729;
        int nseg = 10 + (int)(rnd() * 150), nfree = (int)(rnd() * 200), self = seed % 2;
        double box = 1 + 5 * rnd();
        ctt_scene s;
        ctt_scene_init(&s, 4 * nseg + nfree, nseg);
        for (int k = 0; k < nseg; k++) {
            double c[3] = {box * rnd(), box * rnd(), box * rnd()};
            double size = 0.05 + rnd() * 1.5;
            ct_idx v[4];
            for (int q = 0; q < 4; q++)
                v[q] = ctt_scene_node(&s, c[0] + size * (rnd() - 0.5),
                                      c[1] + size * (rnd() - 0.5),
                                      c[2] + 0.3 * size * (rnd() - 0.5));
            ctt_scene_seg(&s, v[0], v[1], v[2], rnd() < 0.3 ? v[2] : v[3]);
        }
        for (int k = 0; k < nfree; k++)
            ctt_scene_node(&s, box * rnd(), box * rnd(), box * rnd());
        for (ct_idx i = 0; i < s.nn; i++)
            if (self || i >= 4 * nseg || rnd() < 0.3)
                ctt_scene_sec(&s, i);
        ct_search_input in = ctt_scene_input(&s, box * 0.05 * rnd(), box * 0.02 * rnd(), self);
        in.filter = CT_FILTER_BOX;
        char what[64];
        snprintf(what, sizeof what, "soup seed %d (self %d), box", seed, self);
        check_bsp(&in, what);
        ctt_scene_free(&s);
    }
}

/* Big enough for tasks (more than 4096 nodes + segments): the bytes are
 * the same for 1 and 2 threads and equal to direct's. With 1 thread a
 * repeated call must not grow the workspace (with 2 threads the per-thread
 * buffers may still grow on later calls, as the task schedule varies). */
Test(search_bsp, one_and_two_threads_identical)
{
    ctt_scene s;
    int n = small() ? 50 : 80;
    bs_two_plates(&s, n, 0.3, 0);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    ct_pairs p1, p2, ref;
    ct_pairs_init(&p1, 0);
    ct_pairs_init(&p2, 0);
    ct_pairs_init(&ref, 0);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BSP);
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    ctt_threads(1);
    cr_assert_eq(ct_search_run(w, &in, &p1), CT_OK);
    size_t mem = ct_search_memory(w);
    cr_assert_eq(ct_search_run(w, &in, &p1), CT_OK);
    cr_assert_eq(ct_search_memory(w), mem, "the workspace grew on a repeated call");
    ctt_threads(2);
    for (int rep = 0; rep < 3; rep++) {
        cr_assert_eq(ct_search_run(w, &in, &p2), CT_OK);
        cr_assert(ctt_same_pairs(&p1, &p2), "1 thread %d pairs, 2 threads %d", p1.n, p2.n);
    }
    ctt_search_tuned(CT_SEARCH_DIRECT, 0, 0, &in, &ref);
    cr_assert(ctt_same_pairs(&ref, &p1));
    ct_search_destroy(w);
    ct_pairs_destroy(&p1);
    ct_pairs_destroy(&p2);
    ct_pairs_destroy(&ref);
    ctt_scene_free(&s);
}

/* The dense-leaf knob takes -1, 0 and 1 only. */
Test(search_bsp, dense_knob_range)
{
    ct_search_params p = ct_search_default_params(CT_SEARCH_BSP);
    ct_search *w;
    for (int v = -2; v <= 2; v++) {
        p.dense = v;
        const int rc = ct_search_init(&w, &p);
        cr_assert_eq(rc, v >= -1 && v <= 1 ? CT_OK : CT_ERR_ARG, "dense %d: %d", v, rc);
        if (rc == CT_OK)
            ct_search_destroy(w);
    }
}

/* One leaf (every node and segment in a box far below gap + margin) with
 * more nodes than a dense leaf decides between two emissions (256), and
 * segments just under and over the most a dense leaf takes (2048): every
 * node meets every segment, and both paths, forced and chosen, give the
 * direct search's pairs. */
Test(search_bsp, dense_leaf_large)
{
    const int nsegs[] = {2000, 2100};
    for (int c = 0; c < 2; c++) {
        ctt_scene s;
        const int nseg = nsegs[c], nsec = small() ? 300 : 600;
        ctt_scene_init(&s, 3 * nseg + nsec, nseg);
        rng_state = 99 + (uint64_t)c;
        for (int k = 0; k < nseg; k++) {
            ct_idx v[3];
            for (int q = 0; q < 3; q++)
                v[q] = ctt_scene_node(&s, 1e-3 * rnd(), 1e-3 * rnd(), 1e-3 * rnd());
            ctt_scene_seg(&s, v[0], v[1], v[2], v[2]);
        }
        for (int i = 0; i < nsec; i++)
            ctt_scene_sec(&s, ctt_scene_node(&s, 1e-3 * rnd(), 1e-3 * rnd(), 1e-3 * rnd()));
        ct_search_input in = ctt_scene_input(&s, 0.05, 0.01, 0);
        ct_idx np = check_bsp(&in, "one large leaf");
        cr_assert_eq(np, (ct_idx)nseg * nsec, "%d segments: %d pairs", nseg, np);
        ctt_scene_free(&s);
    }
}

/* The partition of a box's nodes (search_bsp_partition.c) against the
 * stable partition written out plainly: nodes below the pivot first, then
 * the others, each part in its order, a NaN coordinate on the right; on
 * every axis, over counts that end inside and on a 16-lane vector, with
 * ties at the pivot, from an offset into the arrays (the nodes before n0
 * and from n1 on are left alone). */
Test(search_bsp, node_partition_is_stable)
{
    enum { MAXN = 300, OFF = 5 };
    const int counts[] = {0, 1, 15, 16, 17, 31, 32, 33, 100, 257, MAXN};
    static float x[3][MAXN + 2 * OFF], ref[3][MAXN + 2 * OFF];
    static ct_idx id[MAXN + 2 * OFF], refid[MAXN + 2 * OFF];
    /* Exactly the scratch the partition may use for MAXN nodes (under
     * AddressSanitizer, `make check`, a store past it is an error). */
    static float scratch[4 * MAXN];
    rng_state = 7;
    for (int c = 0; c < (int)(sizeof counts / sizeof counts[0]); c++)
        for (int ax = 0; ax < 3; ax++) {
            const int n = counts[c], tot = n + 2 * OFF;
            for (int i = 0; i < tot; i++) {
                for (int a = 0; a < 3; a++) {
                    /* Quarters: ties at the pivot 0.5 are common. */
                    x[a][i] = (float)((int)(4 * rnd())) * 0.25f;
                    if (rnd() < 0.02)
                        x[a][i] = NAN;
                }
                id[i] = 1000 + i;
            }
            /* The reference: a plain stable partition into copies. */
            int m = OFF;
            for (int pass = 0; pass < 2; pass++)
                for (int i = OFF; i < OFF + n; i++) {
                    const int left = x[ax][i] < 0.5f;
                    if (left != (pass == 0))
                        continue;
                    for (int a = 0; a < 3; a++)
                        ref[a][m] = x[a][i];
                    refid[m++] = id[i];
                }
            int nleft = 0;
            for (int i = OFF; i < OFF + n; i++)
                nleft += x[ax][i] < 0.5f;
            for (int i = 0; i < OFF; i++) {
                for (int a = 0; a < 3; a++) {
                    ref[a][i] = x[a][i];
                    ref[a][OFF + n + i] = x[a][OFF + n + i];
                }
                refid[i] = id[i];
                refid[OFF + n + i] = id[OFF + n + i];
            }
            const ct_idx got = cti_bsp_partition(x[0], x[1], x[2], id, OFF, OFF + n, ax, 0.5f,
                                                 scratch);
            cr_assert_eq(got, OFF + nleft, "n %d axis %d: split at %d, want %d", n, ax, got,
                         OFF + nleft);
            for (int i = 0; i < tot; i++) {
                cr_assert_eq(id[i], refid[i], "n %d axis %d: position %d holds node %d, want %d",
                             n, ax, i, id[i], refid[i]);
                for (int a = 0; a < 3; a++)
                    cr_assert(memcmp(&x[a][i], &ref[a][i], sizeof(float)) == 0,
                              "n %d axis %d: coordinate %d of position %d moved apart from its "
                              "node", n, ax, a, i);
            }
        }
}

/* Boxes above BSP_PART_MAX nodes are split by Hoare's partition in place,
 * the others stably: plates with more nodes than that (so the first splits
 * take the first path, the rest the second) give the bucket search's pairs
 * (the bucket search is checked against direct in test_search_bucket.c;
 * direct itself would test 10^10 couples here), on 1 and 2 threads. */
Test(search_bsp, boxes_above_the_stable_partition_size, .timeout = 120)
{
    ctt_scene s;
    const int n = 300; /* 90000 nodes > BSP_PART_MAX */
    cr_assert_gt(n * n, BSP_PART_MAX);
    bs_two_plates(&s, n, 0.3, 0);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    ct_pairs ref, got;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&got, 0);
    ctt_search_tuned(CT_SEARCH_BUCKET, 0, 0, &in, &ref);
    cr_assert_gt(ref.n, 2 * n * n);
    for (int t = 1; t <= 2; t++) {
        ctt_threads(t);
        ctt_search_tuned(CT_SEARCH_BSP, 0, 0, &in, &got);
        cr_assert(ctt_same_pairs(&ref, &got), "%d threads: bsp %d pairs, bucket %d", t, got.n,
                  ref.n);
    }
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&got);
    ctt_scene_free(&s);
}
