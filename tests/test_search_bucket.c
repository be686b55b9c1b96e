/*
 * test_search_bucket.c -- the bucket search returns exactly the pairs of the
 * direct (all pairs) search, byte for byte, for 1 and 2 threads.
 */
#include <stdint.h>
#include <string.h>

#include "test_util.h"

/* A small scene: nodes, segments, secondary list. */
typedef struct scene {
    ct_idx nn, ns, nsec;
    ct_real *x, *y, *z;
    ct_idx *n1, *n2, *n3, *n4, *sec;
} scene;

static void sc_init(scene *s, ct_idx nn, ct_idx ns, ct_idx nsec)
{
    memset(s, 0, sizeof *s);
    s->x = calloc((size_t)nn + 1, sizeof(ct_real));
    s->y = calloc((size_t)nn + 1, sizeof(ct_real));
    s->z = calloc((size_t)nn + 1, sizeof(ct_real));
    s->n1 = calloc((size_t)ns + 1, sizeof(ct_idx));
    s->n2 = calloc((size_t)ns + 1, sizeof(ct_idx));
    s->n3 = calloc((size_t)ns + 1, sizeof(ct_idx));
    s->n4 = calloc((size_t)ns + 1, sizeof(ct_idx));
    s->sec = calloc((size_t)nsec + 1, sizeof(ct_idx));
}

static void sc_free(scene *s)
{
    free(s->x), free(s->y), free(s->z);
    free(s->n1), free(s->n2), free(s->n3), free(s->n4), free(s->sec);
}

static ct_idx sc_node(scene *s, double x, double y, double z)
{
    s->x[s->nn] = (ct_real)x, s->y[s->nn] = (ct_real)y, s->z[s->nn] = (ct_real)z;
    return s->nn++;
}

static void sc_seg(scene *s, ct_idx a, ct_idx b, ct_idx c, ct_idx d)
{
    s->n1[s->ns] = a, s->n2[s->ns] = b, s->n3[s->ns] = c, s->n4[s->ns] = d;
    s->ns++;
}

/* An nx by ny grid of nodes at height z with spacing h, origin (ox, oy);
 * returns the first node. With quads (or 2 triangles per cell) when segs. */
static ct_idx sc_plate(scene *s, int nx, int ny, double ox, double oy, double z, double h,
                       int segs, int tri)
{
    ct_idx base = s->nn;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            sc_node(s, ox + h * i, oy + h * j, z);
    for (int j = 0; segs && j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            ct_idx a = base + j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
            if (tri) {
                sc_seg(s, a, b, c, c);
                sc_seg(s, a, c, d, d);
            } else {
                sc_seg(s, a, b, c, d);
            }
        }
    return base;
}

static double rnd(uint64_t *r)
{
    *r = *r * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*r >> 11) / 9007199254740992.0;
}

static ct_search_input sc_input(const scene *s, double gap, double margin, int self)
{
    ct_search_input in = {s->nn, s->x, s->y, s->z, s->nsec, s->sec, s->ns, s->n1, s->n2,
                          s->n3, s->n4, (ct_real)gap, (ct_real)margin, self, CT_FILTER_HULL};
    return in;
}

static int run(ct_search_algo a, const ct_search_input *in, ct_pairs *out, int threads,
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
static ct_idx check_same_cells(const ct_search_input *in, int64_t max_cells)
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

static ct_idx check_same(const ct_search_input *in) { return check_same_cells(in, 0); }

/* Plate A (secondary) above plate B (main), shifted in plane. */
static void two_plates(scene *s, int n, double h, double off, double scale, int tri)
{
    sc_init(s, 2 * (n + 1) * (n + 1), 2 * n * n, (n + 1) * (n + 1));
    sc_plate(s, n + 1, n + 1, off, off, off, scale, 1, tri);
    ct_idx a = sc_plate(s, n, n, off + 0.25 * scale, off + 0.35 * scale, off + h * scale, scale,
                        0, 0);
    for (ct_idx i = 0; i < n * n; i++)
        s->sec[i] = a + i;
    s->nsec = n * n;
}

Test(search_bucket, plates_several_gaps)
{
    scene s;
    two_plates(&s, 20, 0.3, 0, 1, 0);
    const double gaps[] = {0.05, 0.25, 0.3, 0.5, 1.0, 2.5};
    ct_idx prev = 0;
    for (int g = 0; g < 6; g++) {
        ct_search_input in = sc_input(&s, gaps[g] * 0.6, gaps[g] * 0.4, 0);
        ct_idx n = check_same(&in);
        cr_assert_geq(n, prev, "pairs must grow with the gap");
        prev = n;
    }
    /* At 0.5 each interior node sees exactly 3 quads (by hand: the corner
     * quad's box is sqrt(0.25^2 + 0.35^2 + 0.3^2) > 0.5 away). */
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
    cr_assert_eq(check_same(&in), 3 * 20 * 20 - 2 * 20);
    sc_free(&s);
}

Test(search_bucket, triangles)
{
    scene s;
    two_plates(&s, 16, 0.2, 0, 1, 1);
    for (int g = 0; g < 3; g++) {
        ct_search_input in = sc_input(&s, 0.2 + 0.3 * g, 0.05, 0);
        cr_assert_gt(check_same(&in), 0);
    }
    sc_free(&s);
}

/* A sheet folded over itself: the upper half lies 0.4 above the lower. */
Test(search_bucket, self_contact_folded_sheet)
{
    const int nx = 24, ny = 6;
    scene s;
    sc_init(&s, nx * ny, nx * ny, nx * ny);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double u = i * 0.5, half = (nx - 1) * 0.25, r = 0.2;
            double x = u <= half ? u : 2 * half - u, z = u <= half ? 0 : 2 * r;
            sc_node(&s, x + 0.01 * (i % 3), j * 0.5, z);
        }
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            ct_idx a = j * nx + i;
            sc_seg(&s, a, a + 1, a + nx + 1, a + nx);
        }
    for (ct_idx i = 0; i < s.nn; i++)
        s.sec[i] = i;
    s.nsec = s.nn;
    for (int g = 0; g < 3; g++) {
        ct_search_input in = sc_input(&s, 0.35 + 0.2 * g, 0.1, 1);
        cr_assert_gt(check_same(&in), 0);
        in.self = 0;
        cr_assert_gt(check_same(&in), 0);
    }
    sc_free(&s);
}

/* A tiny cloud against one big segment and a few small ones: every node
 * falls in one cell. */
Test(search_bucket, all_nodes_in_one_cell)
{
    scene s;
    sc_init(&s, 300, 10, 300);
    ct_idx a = sc_node(&s, -50, -50, 0), b = sc_node(&s, 50, -50, 0);
    ct_idx c = sc_node(&s, 50, 50, 0), d = sc_node(&s, -50, 50, 0);
    sc_seg(&s, a, b, c, d);
    ct_idx e = sc_node(&s, 0, 0, 1e-3), f = sc_node(&s, 1e-3, 0, 1e-3);
    ct_idx g = sc_node(&s, 0, 1e-3, 1e-3);
    sc_seg(&s, e, f, g, g);
    uint64_t r = 12345;
    for (int i = 0; i < 200; i++) {
        double u = rnd(&r), v = rnd(&r);
        s.sec[s.nsec++] = sc_node(&s, 1e-3 * u, 1e-3 * v, 1e-3 * (u - v));
    }
    ct_search_input in = sc_input(&s, 1e-3, 5e-4, 0);
    cr_assert_geq(check_same(&in), 200);
    sc_free(&s);
}

/* Nodes on a line and in the segments' plane, and repeated coordinates. */
Test(search_bucket, coplanar_collinear_duplicates)
{
    scene s;
    sc_init(&s, 600, 200, 400);
    sc_plate(&s, 8, 8, 0, 0, 0, 1, 1, 0);
    for (int i = 0; i < 60; i++) /* collinear, in the plane */
        s.sec[s.nsec++] = sc_node(&s, -1 + 0.15 * i, 3.5, 0);
    for (int i = 0; i < 60; i++) /* duplicates of the main nodes */
        s.sec[s.nsec++] = sc_node(&s, s.x[i], s.y[i], s.z[i]);
    for (int i = 0; i < 40; i++) /* many at one point on a cell boundary */
        s.sec[s.nsec++] = sc_node(&s, 3, 3, 0.5);
    for (int i = 0; i < 64; i++) /* the main nodes themselves */
        s.sec[s.nsec++] = i;
    for (int g = 0; g < 3; g++) {
        ct_search_input in = sc_input(&s, 0.25 * g, 0.25, 0);
        cr_assert_gt(check_same(&in), 0);
        in.self = 1;
        check_same(&in);
    }
    /* All on one line: main segments degenerate to a line too. */
    scene l;
    sc_init(&l, 100, 40, 50);
    for (int i = 0; i < 40; i++) {
        ct_idx a = sc_node(&l, i, 0, 0), b = sc_node(&l, i + 1, 0, 0);
        sc_seg(&l, a, b, b, b);
    }
    for (int i = 0; i < 20; i++)
        l.sec[l.nsec++] = sc_node(&l, 0.37 * i * 2, 0, 0);
    ct_search_input in = sc_input(&l, 0.3, 0.1, 0);
    cr_assert_gt(check_same(&in), 0);
    sc_free(&l);
    sc_free(&s);
}

/* One huge quad among small ones: it covers every cell. */
Test(search_bucket, huge_segment)
{
    scene s;
    two_plates(&s, 16, 0.3, 0, 1, 0);
    ct_idx a = sc_node(&s, -5, -5, 0.1), b = sc_node(&s, 25, -5, 0.1);
    ct_idx c = sc_node(&s, 25, 25, 0.5), d = sc_node(&s, -5, 25, 0.5);
    sc_seg(&s, a, b, c, d);
    ct_search_input in = sc_input(&s, 0.2, 0.1, 0);
    cr_assert_gt(check_same(&in), s.nsec);
    /* With very few cells, and with one cell. */
    cr_assert_gt(check_same_cells(&in, 7), s.nsec);
    cr_assert_gt(check_same_cells(&in, 1), s.nsec);
    sc_free(&s);
}

/* Offset by 1e6, and scaled by 1e-6 (gap scaled too). */
Test(search_bucket, offset_and_scale)
{
    scene s;
    two_plates(&s, 12, 0.3, 1e6, 1, 0);
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
    cr_assert_gt(check_same(&in), 0);
    sc_free(&s);
    two_plates(&s, 12, 0.3, 0, 1e-6, 0);
    in = sc_input(&s, 0.3e-6, 0.2e-6, 0);
    cr_assert_eq(check_same(&in), 3 * 12 * 12 - 2 * 12);
    sc_free(&s);
}

Test(search_bucket, empty_sets)
{
    scene s;
    two_plates(&s, 4, 0.3, 0, 1, 0);
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
    in.nsec = 0;
    cr_assert_eq(check_same(&in), 0);
    in = sc_input(&s, 0.3, 0.2, 0);
    in.nseg = 0;
    cr_assert_eq(check_same(&in), 0);
    /* Far apart: the grid region is empty. */
    for (ct_idx i = 0; i < s.nsec; i++)
        s.z[s.sec[i]] += 100;
    in = sc_input(&s, 0.3, 0.2, 0);
    cr_assert_eq(check_same(&in), 0);
    sc_free(&s);
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
        scene s;
        sc_init(&s, 4 * nq + np, nq, 4 * nq + np);
        for (int q = 0; q < nq; q++) {
            double cx = rnd(&r) * box, cy = rnd(&r) * box, cz = rnd(&r) * box * zf;
            ct_idx n[4];
            for (int k = 0; k < 4; k++) {
                double dx = (rnd(&r) - 0.5) * sz, dy = (rnd(&r) - 0.5) * sz;
                double dz = (rnd(&r) - 0.5) * sz * 0.3 * zf;
                n[k] = sc_node(&s, cx + dx, cy + dy, cz + dz);
            }
            sc_seg(&s, n[0], n[1], n[2], rnd(&r) < 0.3 ? n[2] : n[3]);
        }
        for (int i = 0; i < np; i++) {
            double px = rnd(&r) * box, py = rnd(&r) * box, pz = rnd(&r) * box * zf;
            sc_node(&s, px, py, pz);
        }
        int self = seed % 2;
        for (ct_idx i = 0; i < s.nn; i++)
            if (self || i >= 4 * nq || rnd(&r) < 0.2)
                s.sec[s.nsec++] = i;
        double gap = rnd(&r) * sz, margin = rnd(&r) * 0.5 * sz;
        ct_search_input in = sc_input(&s, gap, margin, self);
        check_same_cells(&in, seed % 5 == 4 ? 1 + (int64_t)(rnd(&r) * 50) : 0);
        sc_free(&s);
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
        scene s;
        two_plates(&s, sizes[k], 0.3 + 0.05 * k, 0, 1, k % 2);
        ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
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
        sc_free(&s);
    }
    cr_assert_gt(mem_first, 0);
    ct_pairs_destroy(&out);
    ct_pairs_destroy(&ref);
    ct_search_destroy(w);
}

Test(search_bucket, nan_input)
{
    scene s;
    two_plates(&s, 4, 0.3, 0, 1, 0);
    ct_pairs out;
    ct_pairs_init(&out, 0);
    s.x[s.sec[3]] = (ct_real)NAN;
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
    cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_ERR_NONFINITE);
    s.x[s.sec[3]] = 1;
    s.z[s.n3[5]] = (ct_real)INFINITY;
    cr_assert_eq(run(CT_SEARCH_BUCKET, &in, &out, 2, 0), CT_ERR_NONFINITE);
    ct_pairs_destroy(&out);
    sc_free(&s);
}

/* Search with explicit parameters on 1 or 2 threads. */
static int run_params(const ct_search_params *p, const ct_search_input *in, ct_pairs *out,
                      int threads, size_t *mem)
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
static void shuffle_sec(scene *s, uint64_t seed)
{
    uint64_t r = seed;
    for (ct_idx i = s->nsec - 1; i > 0; i--) {
        ct_idx j = (ct_idx)(rnd(&r) * (i + 1));
        ct_idx t = s->sec[i];
        s->sec[i] = s->sec[j];
        s->sec[j] = t;
    }
}

/* A secondary list in random order (at least 4096 nodes, so that the
 * search visits the nodes in cell order and restores the order through the
 * collector): still exactly direct's pairs, in secondary-list order. */
Test(search_bucket, shuffled_secondaries_cell_order, .timeout = 120)
{
    const int n = ctt_checking() ? 66 : 80;
    scene s;
    two_plates(&s, n, 0.3, 0, 1, 0);
    shuffle_sec(&s, 4242);
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
    /* Every node sees 3 quads but the last row's and column's (by hand, as
     * in plates_several_gaps). */
    cr_assert_eq(check_same(&in), 3 * n * n - 2 * n);
    in.filter = CT_FILTER_BOX;
    cr_assert_geq(check_same(&in), 3 * n * n - 2 * n);
    sc_free(&s);
}

/* The box filter (the node's distance to the segment's box) equals direct
 * on plates, a self-contact fold, offset and scaled plates and soups, and
 * is a superset of the hull filter's pairs. */
Test(search_bucket, box_filter_matches_direct)
{
    scene s;
    two_plates(&s, 20, 0.3, 0, 1, 0);
    const double gaps[] = {0.05, 0.3, 0.5, 1.0, 2.5};
    for (int g = 0; g < 5; g++) {
        ct_search_input in = sc_input(&s, gaps[g] * 0.6, gaps[g] * 0.4, 0);
        ct_idx hull = check_same(&in);
        in.filter = CT_FILTER_BOX;
        cr_assert_geq(check_same(&in), hull, "the box filter keeps every hull pair");
    }
    sc_free(&s);
    two_plates(&s, 12, 0.3, 1e6, 1, 1);
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
    in.filter = CT_FILTER_BOX;
    cr_assert_gt(check_same(&in), 0);
    sc_free(&s);
    two_plates(&s, 12, 0.3, 0, 1e-6, 0);
    in = sc_input(&s, 0.3e-6, 0.2e-6, 0);
    in.filter = CT_FILTER_BOX;
    cr_assert_gt(check_same(&in), 0);
    sc_free(&s);
    /* Soups, self or not, the last few on very coarse grids. */
    uint64_t r = 1357911;
    for (int seed = 0; seed < 20; seed++) {
        int nq = 1 + (int)(rnd(&r) * 80), np = (int)(rnd(&r) * 100);
        double box = 0.5 + rnd(&r) * 6, sz = 0.05 + rnd(&r) * 1.5;
        scene u;
        sc_init(&u, 4 * nq + np, nq, 4 * nq + np);
        for (int q = 0; q < nq; q++) {
            double cx = rnd(&r) * box, cy = rnd(&r) * box, cz = rnd(&r) * box;
            ct_idx v[4];
            for (int k = 0; k < 4; k++)
                v[k] = sc_node(&u, cx + (rnd(&r) - 0.5) * sz, cy + (rnd(&r) - 0.5) * sz,
                               cz + (rnd(&r) - 0.5) * sz * 0.3);
            sc_seg(&u, v[0], v[1], v[2], rnd(&r) < 0.3 ? v[2] : v[3]);
        }
        for (int i = 0; i < np; i++)
            sc_node(&u, rnd(&r) * box, rnd(&r) * box, rnd(&r) * box);
        for (ct_idx i = 0; i < u.nn; i++)
            u.sec[u.nsec++] = i;
        ct_search_input iu = sc_input(&u, rnd(&r) * sz, rnd(&r) * 0.5 * sz, seed % 2);
        iu.filter = CT_FILTER_BOX;
        check_same_cells(&iu, seed >= 16 ? 1 + seed % 4 : 0);
        sc_free(&u);
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
    scene s;
    sc_init(&s, 2 * (L + 1) + 4 + 4 * L, L + 1, 4 * L);
    sc_plate(&s, L + 1, 2, 0, 0, 0, 1, 1, 0);
    ct_idx a = sc_node(&s, 0, 0.25, 0.2), b = sc_node(&s, L, 0.25, 0.2);
    ct_idx c = sc_node(&s, L, 0.75, 0.2), d = sc_node(&s, 0, 0.75, 0.2);
    const ct_idx wide = s.ns;
    sc_seg(&s, a, b, c, d);
    for (int i = 0; i < 2 * L; i++) {
        s.sec[s.nsec++] = sc_node(&s, 0.5 * i + 0.25, 0.5, 0.1);
        s.sec[s.nsec++] = sc_node(&s, 0.5 * i + 0.25, 0.5, 0.45);
    }
    ct_search_input in = sc_input(&s, 0.2, 0.1, 0);
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
    sc_free(&s);
}

/* Huge segments on a grid asked to be very fine: the entries (segments x
 * covered cells) would pass 10^8; the search coarsens the grid instead,
 * keeps its memory linear, and still returns direct's pairs. */
Test(search_bucket, huge_segments_coarsen_the_grid, .timeout = 60)
{
    scene s;
    two_plates(&s, 16, 0.3, 0, 1, 0);
    scene t;
    sc_init(&t, s.nn + 200, s.ns + 50, s.nsec);
    for (ct_idx i = 0; i < s.nn; i++)
        sc_node(&t, s.x[i], s.y[i], s.z[i]);
    for (ct_idx j = 0; j < s.ns; j++)
        sc_seg(&t, s.n1[j], s.n2[j], s.n3[j], s.n4[j]);
    for (int q = 0; q < 50; q++) {
        double z0 = 0.05 + 0.005 * q;
        ct_idx a = sc_node(&t, -5, -5, z0), b = sc_node(&t, 25, -5, z0);
        ct_idx c = sc_node(&t, 25, 25, z0 + 0.2), d = sc_node(&t, -5, 25, z0 + 0.2);
        sc_seg(&t, a, b, c, d);
    }
    for (ct_idx i = 0; i < s.nsec; i++)
        t.sec[t.nsec++] = s.sec[i];
    ct_search_input in = sc_input(&t, 0.2, 0.1, 0);
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
    sc_free(&t);
    sc_free(&s);
}

/* Bad indices and coordinates, on small inputs and on a large shuffled one
 * (the cell-order path). */
Test(search_bucket, bad_indices_and_coordinates)
{
    for (int big = 0; big < 2; big++) {
        int n = big ? 66 : 5;
        scene s;
        two_plates(&s, n, 0.3, 0, 1, 0);
        if (big)
            shuffle_sec(&s, 99);
        ct_pairs out;
        ct_pairs_init(&out, 0);
        ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
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
        sc_free(&s);
    }
}

/* Nodes, segments and secondaries all randomly renumbered (more than 4096
 * segments whose nodes lie far apart in memory: the search then keeps the
 * corners in records and visits the nodes in cell order): still direct's
 * pairs, byte for byte. */
Test(search_bucket, scattered_numbering, .timeout = 120)
{
    const int n = 100;
    scene s;
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
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
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
    sc_free(&s);
}

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
    scene s;
    two_plates(&s, 30, 0.3, 0, 1, 0);
    shuffle_sec(&s, 5);
    ct_search_input in = sc_input(&s, 0.3, 0.2, 0);
    check_v0(&in);
    in.filter = CT_FILTER_BOX;
    check_v0(&in);
    sc_free(&s);
    two_plates(&s, 12, 0.3, 1e6, 1, 1);
    in = sc_input(&s, 0.3, 0.2, 0);
    check_v0(&in);
    sc_free(&s);
}
