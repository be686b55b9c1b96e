/*
 * test_search_bucket.c -- the bucket search returns exactly the pairs of the
 * direct (all pairs) search, byte for byte, for 1 and 2 threads, on the
 * geometric cases: plates, self contact, one cell, coplanar and collinear
 * nodes, huge and long segments, offsets and scales, random soups, both
 * filters, the baseline variant. Orders and bad input:
 * test_search_bucket_input.c.
 */
#include "test_search_bucket.h"

Test(search_bucket, plates_several_gaps)
{
    ctt_scene s;
    two_plates(&s, 20, 0.3, 0, 1, 0);
    const double gaps[] = {0.05, 0.25, 0.3, 0.5, 1.0, 2.5};
    ct_idx prev = 0;
    for (int g = 0; g < 6; g++) {
        ct_search_input in = ctt_scene_input(&s, gaps[g] * 0.6, gaps[g] * 0.4, 0);
        ct_idx n = check_same(&in);
        cr_assert_geq(n, prev, "pairs must grow with the gap");
        prev = n;
    }
    /* At 0.5 each interior node sees exactly 3 quads (by hand: the corner
     * quad's box is sqrt(0.25^2 + 0.35^2 + 0.3^2) > 0.5 away). */
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    cr_assert_eq(check_same(&in), 3 * 20 * 20 - 2 * 20);
    ctt_scene_free(&s);
}

Test(search_bucket, triangles)
{
    ctt_scene s;
    two_plates(&s, 16, 0.2, 0, 1, 1);
    for (int g = 0; g < 3; g++) {
        ct_search_input in = ctt_scene_input(&s, 0.2 + 0.3 * g, 0.05, 0);
        cr_assert_gt(check_same(&in), 0);
    }
    ctt_scene_free(&s);
}

/* A sheet folded over itself: the upper half lies 0.4 above the lower. */
Test(search_bucket, self_contact_folded_sheet)
{
    const int nx = 24, ny = 6;
    ctt_scene s;
    sc_init(&s, nx * ny, nx * ny, nx * ny);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double u = i * 0.5, half = (nx - 1) * 0.25, r = 0.2;
            double x = u <= half ? u : 2 * half - u, z = u <= half ? 0 : 2 * r;
            ctt_scene_node(&s, x + 0.01 * (i % 3), j * 0.5, z);
        }
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            ct_idx a = j * nx + i;
            ctt_scene_seg(&s, a, a + 1, a + nx + 1, a + nx);
        }
    for (ct_idx i = 0; i < s.nn; i++)
        s.sec[i] = i;
    s.nsec = s.nn;
    for (int g = 0; g < 3; g++) {
        ct_search_input in = ctt_scene_input(&s, 0.35 + 0.2 * g, 0.1, 1);
        cr_assert_gt(check_same(&in), 0);
        in.self = 0;
        cr_assert_gt(check_same(&in), 0);
    }
    ctt_scene_free(&s);
}

/* A tiny cloud against one big segment and a few small ones: every node
 * falls in one cell. */
Test(search_bucket, all_nodes_in_one_cell)
{
    ctt_scene s;
    sc_init(&s, 300, 10, 300);
    ct_idx a = ctt_scene_node(&s, -50, -50, 0), b = ctt_scene_node(&s, 50, -50, 0);
    ct_idx c = ctt_scene_node(&s, 50, 50, 0), d = ctt_scene_node(&s, -50, 50, 0);
    ctt_scene_seg(&s, a, b, c, d);
    ct_idx e = ctt_scene_node(&s, 0, 0, 1e-3), f = ctt_scene_node(&s, 1e-3, 0, 1e-3);
    ct_idx g = ctt_scene_node(&s, 0, 1e-3, 1e-3);
    ctt_scene_seg(&s, e, f, g, g);
    uint64_t r = 12345;
    for (int i = 0; i < 200; i++) {
        double u = rnd(&r), v = rnd(&r);
        s.sec[s.nsec++] = ctt_scene_node(&s, 1e-3 * u, 1e-3 * v, 1e-3 * (u - v));
    }
    ct_search_input in = ctt_scene_input(&s, 1e-3, 5e-4, 0);
    cr_assert_geq(check_same(&in), 200);
    ctt_scene_free(&s);
}

/* Nodes on a line and in the segments' plane, and repeated coordinates. */
Test(search_bucket, coplanar_collinear_duplicates)
{
    ctt_scene s;
    sc_init(&s, 600, 200, 400);
    ctt_scene_plate(&s, 8, 8, 0, 0, 0, 1, 1, 0);
    for (int i = 0; i < 60; i++) /* collinear, in the plane */
        s.sec[s.nsec++] = ctt_scene_node(&s, -1 + 0.15 * i, 3.5, 0);
    for (int i = 0; i < 60; i++) /* duplicates of the main nodes */
        s.sec[s.nsec++] = ctt_scene_node(&s, s.x[i], s.y[i], s.z[i]);
    for (int i = 0; i < 40; i++) /* many at one point on a cell boundary */
        s.sec[s.nsec++] = ctt_scene_node(&s, 3, 3, 0.5);
    for (int i = 0; i < 64; i++) /* the main nodes themselves */
        s.sec[s.nsec++] = i;
    for (int g = 0; g < 3; g++) {
        ct_search_input in = ctt_scene_input(&s, 0.25 * g, 0.25, 0);
        cr_assert_gt(check_same(&in), 0);
        in.self = 1;
        check_same(&in);
    }
    /* All on one line: main segments degenerate to a line too. */
    ctt_scene l;
    sc_init(&l, 100, 40, 50);
    for (int i = 0; i < 40; i++) {
        ct_idx a = ctt_scene_node(&l, i, 0, 0), b = ctt_scene_node(&l, i + 1, 0, 0);
        ctt_scene_seg(&l, a, b, b, b);
    }
    for (int i = 0; i < 20; i++)
        l.sec[l.nsec++] = ctt_scene_node(&l, 0.37 * i * 2, 0, 0);
    ct_search_input in = ctt_scene_input(&l, 0.3, 0.1, 0);
    cr_assert_gt(check_same(&in), 0);
    ctt_scene_free(&l);
    ctt_scene_free(&s);
}

/* One huge quad among small ones: it covers every cell. */
Test(search_bucket, huge_segment)
{
    ctt_scene s;
    two_plates(&s, 16, 0.3, 0, 1, 0);
    ct_idx a = ctt_scene_node(&s, -5, -5, 0.1), b = ctt_scene_node(&s, 25, -5, 0.1);
    ct_idx c = ctt_scene_node(&s, 25, 25, 0.5), d = ctt_scene_node(&s, -5, 25, 0.5);
    ctt_scene_seg(&s, a, b, c, d);
    ct_search_input in = ctt_scene_input(&s, 0.2, 0.1, 0);
    cr_assert_gt(check_same(&in), s.nsec);
    /* With very few cells, and with one cell. */
    cr_assert_gt(check_same_cells(&in, 7), s.nsec);
    cr_assert_gt(check_same_cells(&in, 1), s.nsec);
    ctt_scene_free(&s);
}

/* Offset by 1e6, and scaled by 1e-6 (gap scaled too). */
Test(search_bucket, offset_and_scale)
{
    ctt_scene s;
    two_plates(&s, 12, 0.3, 1e6, 1, 0);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    cr_assert_gt(check_same(&in), 0);
    ctt_scene_free(&s);
    two_plates(&s, 12, 0.3, 0, 1e-6, 0);
    in = ctt_scene_input(&s, 0.3e-6, 0.2e-6, 0);
    cr_assert_eq(check_same(&in), 3 * 12 * 12 - 2 * 12);
    ctt_scene_free(&s);
}

Test(search_bucket, empty_sets)
{
    ctt_scene s;
    two_plates(&s, 4, 0.3, 0, 1, 0);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    in.nsec = 0;
    cr_assert_eq(check_same(&in), 0);
    in = ctt_scene_input(&s, 0.3, 0.2, 0);
    in.nseg = 0;
    cr_assert_eq(check_same(&in), 0);
    /* Far apart: the grid region is empty. */
    for (ct_idx i = 0; i < s.nsec; i++)
        s.z[s.sec[i]] += 100;
    in = ctt_scene_input(&s, 0.3, 0.2, 0);
    cr_assert_eq(check_same(&in), 0);
    ctt_scene_free(&s);
}

/* Random soups of small quads and points, random gaps, self or not. */
Test(search_bucket, random_soups)
{
    uint64_t r = 987654321;
    int nseed = ctt_checking() ? 20 : 60;
    for (int seed = 0; seed < nseed; seed++) {
        int nq = 1 + (int)(rnd(&r) * 120), np = (int)(rnd(&r) * 150);
        double box = 0.5 + rnd(&r) * 8, sz = 0.05 + rnd(&r) * 1.5;
        double zf = seed % 3 != 0; /* every third soup is flat */
        ctt_scene s;
        sc_init(&s, 4 * nq + np, nq, 4 * nq + np);
        for (int q = 0; q < nq; q++) {
            double cx = rnd(&r) * box, cy = rnd(&r) * box, cz = rnd(&r) * box * zf;
            ct_idx n[4];
            for (int k = 0; k < 4; k++) {
                double dx = (rnd(&r) - 0.5) * sz, dy = (rnd(&r) - 0.5) * sz;
                double dz = (rnd(&r) - 0.5) * sz * 0.3 * zf;
                n[k] = ctt_scene_node(&s, cx + dx, cy + dy, cz + dz);
            }
            ctt_scene_seg(&s, n[0], n[1], n[2], rnd(&r) < 0.3 ? n[2] : n[3]);
        }
        for (int i = 0; i < np; i++) {
            double px = rnd(&r) * box, py = rnd(&r) * box, pz = rnd(&r) * box * zf;
            ctt_scene_node(&s, px, py, pz);
        }
        int self = seed % 2;
        for (ct_idx i = 0; i < s.nn; i++)
            if (self || i >= 4 * nq || rnd(&r) < 0.2)
                s.sec[s.nsec++] = i;
        double gap = rnd(&r) * sz, margin = rnd(&r) * 0.5 * sz;
        ct_search_input in = ctt_scene_input(&s, gap, margin, self);
        check_same_cells(&in, seed % 5 == 4 ? 1 + (int64_t)(rnd(&r) * 50) : 0);
        ctt_scene_free(&s);
    }
}

/* One workspace through growing and shrinking sizes. */
Test(search_bucket, workspace_reuse)
{
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    const int sizes[] = {5, 30, 3, 30, 12};
    ct_pairs out, ref;
    ct_pairs_init(&out, 0);
    ct_pairs_init(&ref, 0);
    size_t mem_first = 0;
    for (int k = 0; k < 5; k++) {
        ctt_scene s;
        two_plates(&s, sizes[k], 0.3 + 0.05 * k, 0, 1, k % 2);
        ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
        /* Calls 1 to 3 on one thread: the per-thread pair buffers then see
         * the same fill at calls 1 and 3 (with two threads it depends on
         * the schedule). */
        ctt_threads(k >= 1 && k <= 3 ? 1 : 2);
        cr_assert_eq(ct_search_run(w, &in, &out), CT_OK);
        cr_assert_eq(run(CT_SEARCH_DIRECT, &in, &ref, 2, 0), CT_OK);
        cr_assert_eq(out.n, ref.n);
        size_t bytes = (size_t)ref.n * sizeof(ct_idx);
        cr_assert(memcmp(out.node, ref.node, bytes) == 0 && memcmp(out.seg, ref.seg, bytes) == 0);
        if (k == 1)
            mem_first = ct_search_memory(w);
        if (k == 3) /* the same size again allocates nothing more */
            cr_assert_eq(ct_search_memory(w), mem_first);
        ctt_scene_free(&s);
    }
    cr_assert_gt(mem_first, 0);
    ct_pairs_destroy(&out);
    ct_pairs_destroy(&ref);
    ct_search_destroy(w);
}

/* A secondary list in random order (at least 4096 nodes, so that the
 * search visits the nodes in cell order and restores the order through the
 * collector): still exactly direct's pairs, in secondary-list order. */
/* The box filter (the node's distance to the segment's box) equals direct
 * on plates, a self-contact fold, offset and scaled plates and soups, and
 * is a superset of the hull filter's pairs. */
Test(search_bucket, box_filter_matches_direct)
{
    ctt_scene s;
    two_plates(&s, 20, 0.3, 0, 1, 0);
    const double gaps[] = {0.05, 0.3, 0.5, 1.0, 2.5};
    for (int g = 0; g < 5; g++) {
        ct_search_input in = ctt_scene_input(&s, gaps[g] * 0.6, gaps[g] * 0.4, 0);
        ct_idx hull = check_same(&in);
        in.filter = CT_FILTER_BOX;
        cr_assert_geq(check_same(&in), hull, "the box filter keeps every hull pair");
    }
    ctt_scene_free(&s);
    two_plates(&s, 12, 0.3, 1e6, 1, 1);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    in.filter = CT_FILTER_BOX;
    cr_assert_gt(check_same(&in), 0);
    ctt_scene_free(&s);
    two_plates(&s, 12, 0.3, 0, 1e-6, 0);
    in = ctt_scene_input(&s, 0.3e-6, 0.2e-6, 0);
    in.filter = CT_FILTER_BOX;
    cr_assert_gt(check_same(&in), 0);
    ctt_scene_free(&s);
    /* Soups, self or not, the last few on very coarse grids. */
    uint64_t r = 1357911;
    for (int seed = 0; seed < 20; seed++) {
        int nq = 1 + (int)(rnd(&r) * 80), np = (int)(rnd(&r) * 100);
        double box = 0.5 + rnd(&r) * 6, sz = 0.05 + rnd(&r) * 1.5;
        ctt_scene u;
        sc_init(&u, 4 * nq + np, nq, 4 * nq + np);
        for (int q = 0; q < nq; q++) {
            double cx = rnd(&r) * box, cy = rnd(&r) * box, cz = rnd(&r) * box;
            ct_idx v[4];
            for (int k = 0; k < 4; k++)
                v[k] = ctt_scene_node(&u, cx + (rnd(&r) - 0.5) * sz, cy + (rnd(&r) - 0.5) * sz,
                               cz + (rnd(&r) - 0.5) * sz * 0.3);
            ctt_scene_seg(&u, v[0], v[1], v[2], rnd(&r) < 0.3 ? v[2] : v[3]);
        }
        for (int i = 0; i < np; i++)
            ctt_scene_node(&u, rnd(&r) * box, rnd(&r) * box, rnd(&r) * box);
        for (ct_idx i = 0; i < u.nn; i++)
            u.sec[u.nsec++] = i;
        ct_search_input iu = ctt_scene_input(&u, rnd(&r) * sz, rnd(&r) * 0.5 * sz, seed % 2);
        iu.filter = CT_FILTER_BOX;
        check_same_cells(&iu, seed >= 16 ? 1 + seed % 4 : 0);
        ctt_scene_free(&u);
    }
}

/* A segment whose cell range is longer than the packed form holds (1024
 * cells along an axis): a strip of 3000 unit quads along x makes about
 * 2250 cells along x, and a long thin segment above it covers them all.
 * Its range is recomputed from its box; the nodes near its far end pair
 * with it as in the direct search. */
Test(search_bucket, segment_wider_than_the_packed_range)
{
    enum { L = 3000 };
    ctt_scene s;
    sc_init(&s, 2 * (L + 1) + 4 + 4 * L, L + 1, 4 * L);
    ctt_scene_plate(&s, L + 1, 2, 0, 0, 0, 1, 1, 0);
    ct_idx a = ctt_scene_node(&s, 0, 0.25, 0.2), b = ctt_scene_node(&s, L, 0.25, 0.2);
    ct_idx c = ctt_scene_node(&s, L, 0.75, 0.2), d = ctt_scene_node(&s, 0, 0.75, 0.2);
    const ct_idx wide = s.ns;
    ctt_scene_seg(&s, a, b, c, d);
    for (int i = 0; i < 2 * L; i++) {
        s.sec[s.nsec++] = ctt_scene_node(&s, 0.5 * i + 0.25, 0.5, 0.1);
        s.sec[s.nsec++] = ctt_scene_node(&s, 0.5 * i + 0.25, 0.5, 0.45);
    }
    ct_search_input in = ctt_scene_input(&s, 0.2, 0.1, 0);
    cr_assert_gt(check_same(&in), 0);
    /* Independently of direct: every node at z = 0.1 or 0.45 lies within
     * 0.3 of the long segment, those at the far end included. */
    ct_pairs p;
    ct_pairs_init(&p, 0);
    cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &p, 2, 0), CT_OK);
    ct_idx with_wide = 0, far_end = 0;
    for (ct_idx k = 0; k < p.n; k++)
        if (p.seg[k] == wide) {
            with_wide++;
            far_end += s.x[p.node[k]] > L - 10;
        }
    cr_assert_eq(with_wide, s.nsec);
    cr_assert_eq(far_end, 2 * 20);
    ct_pairs_destroy(&p);
    ctt_scene_free(&s);
}

/* Huge segments on a grid asked to be very fine: the entries (segments x
 * covered cells) would pass 10^8; the search coarsens the grid instead,
 * keeps its memory linear, and still returns direct's pairs. */
Test(search_bucket, huge_segments_coarsen_the_grid, .timeout = 60)
{
    ctt_scene s;
    two_plates(&s, 16, 0.3, 0, 1, 0);
    ctt_scene t;
    sc_init(&t, s.nn + 200, s.ns + 50, s.nsec);
    for (ct_idx i = 0; i < s.nn; i++)
        ctt_scene_node(&t, s.x[i], s.y[i], s.z[i]);
    for (ct_idx j = 0; j < s.ns; j++)
        ctt_scene_seg(&t, s.n1[j], s.n2[j], s.n3[j], s.n4[j]);
    for (int q = 0; q < 50; q++) {
        double z0 = 0.05 + 0.005 * q;
        ct_idx a = ctt_scene_node(&t, -5, -5, z0), b = ctt_scene_node(&t, 25, -5, z0);
        ct_idx c = ctt_scene_node(&t, 25, 25, z0 + 0.2), d = ctt_scene_node(&t, -5, 25, z0 + 0.2);
        ctt_scene_seg(&t, a, b, c, d);
    }
    for (ct_idx i = 0; i < s.nsec; i++)
        t.sec[t.nsec++] = s.sec[i];
    ct_search_input in = ctt_scene_input(&t, 0.2, 0.1, 0);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    p.cell_factor = 500;
    p.max_cells = 2000000;
    ct_pairs ref, b1, b2;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&b1, 0);
    ct_pairs_init(&b2, 0);
    cr_assert_eq(run(CT_SEARCH_DIRECT, &in, &ref, 2, 0), CT_OK);
    size_t mem = 0;
    cr_assert_eq(run_params(&p, &in, &b1, 1, &mem), CT_OK);
    cr_assert_eq(run_params(&p, &in, &b2, 2, NULL), CT_OK);
    cr_assert_gt(ref.n, 50 * t.nsec / 2);
    cr_assert_eq(b1.n, ref.n);
    cr_assert_eq(b2.n, ref.n);
    size_t bytes = (size_t)ref.n * sizeof(ct_idx);
    cr_assert(memcmp(b1.node, ref.node, bytes) == 0 && memcmp(b1.seg, ref.seg, bytes) == 0);
    cr_assert(memcmp(b2.node, ref.node, bytes) == 0 && memcmp(b2.seg, ref.seg, bytes) == 0);
    /* 10^8 entries would be 400 MB. */
    cr_assert_lt(mem, (size_t)64 << 20, "workspace %zu bytes", mem);
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&b1);
    ct_pairs_destroy(&b2);
    ctt_scene_free(&t);
    ctt_scene_free(&s);
}

/* Bad indices and coordinates, on small inputs and on a large shuffled one
 * (the cell-order path). */
/* Nodes, segments and secondaries all randomly renumbered (more than 4096
 * segments whose nodes lie far apart in memory: the search then keeps the
 * corners in records and visits the nodes in cell order): still direct's
 * pairs, byte for byte. */
/* The baseline variant (search_bucket_v0.c), called directly: the same
 * bytes as direct on plates, a shuffled secondary list and soups. */
int cti_search_bucket_v0(ct_search *s, const ct_search_input *in, ct_pairs *out);

static void check_v0(const ct_search_input *in)
{
    ct_pairs ref, got;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&got, 0);
    cr_assert_eq(run(CT_SEARCH_DIRECT, in, &ref, 2, 0), CT_OK);
    for (int th = 1; th <= 2; th++) {
        ctt_threads(th);
        ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
        ct_search *s;
        cr_assert_eq(ct_search_init(&s, &p), CT_OK);
        cr_assert_eq(cti_search_bucket_v0(s, in, &got), CT_OK);
        ct_search_destroy(s);
        size_t bytes = (size_t)ref.n * sizeof(ct_idx);
        cr_assert_eq(got.n, ref.n);
        cr_assert(memcmp(got.node, ref.node, bytes) == 0 && memcmp(got.seg, ref.seg, bytes) == 0);
    }
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&got);
}

Test(search_bucket, baseline_variant_matches_direct)
{
    ctt_scene s;
    two_plates(&s, 30, 0.3, 0, 1, 0);
    shuffle_sec(&s, 5);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    check_v0(&in);
    in.filter = CT_FILTER_BOX;
    check_v0(&in);
    ctt_scene_free(&s);
    two_plates(&s, 12, 0.3, 1e6, 1, 1);
    in = ctt_scene_input(&s, 0.3, 0.2, 0);
    check_v0(&in);
    ctt_scene_free(&s);
}
