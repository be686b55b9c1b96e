/*
 * test_search_topo.c -- the topologically limited search (TYPE3/5 engine):
 * it follows a smoothly sliding sheet exactly, its first search finds the
 * brute-force closest main node, it misses the impact of seed 000's
 * "Undetected Impact" figure (which the bucket search finds), and a reset
 * forces a full search, as does a changed topology (secondaries or
 * corners, in new arrays or rewritten in place; the same contents in a new
 * array keep the history).
 */
#include <stdint.h>
#include <string.h>

#include "test_search_scene.h"

/* Main surface: an (nx+1) x (ny+1) grid of unit quads, z = f(x); node (i, j)
 * is number j*(nx+1) + i and quad (i, j) is number j*nx + i. */
static double curve_a;
static double surf(double x) { return curve_a * (x - 10) * (x - 10); }

static void ts_main(ctt_scene *s, int nx, int ny)
{
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++)
            ctt_scene_node(s, i, j, surf(i));
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            ct_idx a = j * (nx + 1) + i;
            ctt_scene_seg(s, a, a + 1, a + nx + 2, a + nx + 1);
        }
}


static int has_pair(const ct_pairs *p, ct_idx node, ct_idx seg)
{
    for (ct_idx k = 0; k < p->n; k++)
        if (p->node[k] == node && p->seg[k] == seg)
            return 1;
    return 0;
}

/* Every pair of a is in b (both canonical: the secondary list ascends). */
static int subset(const ct_pairs *a, const ct_pairs *b)
{
    ct_idx j = 0;
    for (ct_idx i = 0; i < a->n; i++) {
        while (j < b->n && (b->node[j] < a->node[i] ||
                            (b->node[j] == a->node[i] && b->seg[j] < a->seg[i])))
            j++;
        if (!(j < b->n && b->node[j] == a->node[i] && b->seg[j] == a->seg[i]))
            return 0;
    }
    return 1;
}

/*
 * A 10 x 10 sheet of nodes 0.3 above a 20 x 20 unit-quad surface slides by
 * (0.17, 0.09) per call over 30 calls (less than a fifth of an element).
 * Flat surface, gap + margin 0.5: the pairs within 0.5 of a node 0.3 above
 * the plane reach 0.4 in-plane, so they all touch the node's closest grid
 * node and topo must equal direct byte for byte at every call. Curved
 * surface (z = 0.02 (x - 10)^2, the sheet following it): asserted is
 * direct(0.35) subset of topo(0.5) subset of direct(0.5) at every call, i.e.
 * nothing within 0.35 is missed and nothing false is reported. Both for 1
 * and 2 threads, with identical bytes.
 */
static void sliding(double a, int exact)
{
    curve_a = a;
    ctt_scene s;
    ctt_scene_init(&s, 600, 400);
    ts_main(&s, 20, 20);
    ct_idx base = s.nn;
    for (int j = 0; j < 10; j++)
        for (int i = 0; i < 10; i++) {
            ct_idx k = ctt_scene_node(&s, 0, 0, 0);
            s.sec[s.nsec++] = k;
        }
    ct_pairs got[2], ref, inner;
    ct_pairs_init(&got[0], 0);
    ct_pairs_init(&got[1], 0);
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&inner, 0);
    ct_search *w[2];
    ct_search_params p = ct_search_default_params(CT_SEARCH_TOPO);
    cr_assert_eq(ct_search_init(&w[0], &p), CT_OK);
    cr_assert_eq(ct_search_init(&w[1], &p), CT_OK);
    ct_search_input in = ctt_scene_input(&s, 0.3, 0.2, 0);
    int64_t total = 0;
    for (int step = 0; step < 30; step++) {
        for (int j = 0; j < 10; j++)
            for (int i = 0; i < 10; i++) {
                ct_idx k = base + j * 10 + i;
                double x = 4.13 + i + 0.17 * step, y = 4.27 + j + 0.09 * step;
                s.x[k] = (ct_real)x, s.y[k] = (ct_real)y, s.z[k] = (ct_real)(surf(x) + 0.3);
            }
        for (int t = 0; t < 2; t++) {
            ctt_threads(t + 1);
            cr_assert_eq(ct_search_run(w[t], &in, &got[t]), CT_OK);
        }
        cr_assert(ctt_same_pairs(&got[0], &got[1]), "step %d: 1 and 2 threads differ", step);
        ctt_search(CT_SEARCH_DIRECT, &in, &ref);
        cr_assert(subset(&got[0], &ref), "step %d: topo reports a pair direct rejects", step);
        if (exact) {
            cr_assert(ctt_same_pairs(&got[0], &ref), "step %d: topo %d pairs, direct %d", step,
                      got[0].n, ref.n);
        } else {
            ct_search_input in2 = in;
            in2.margin = (ct_real)0.05;
            ctt_search(CT_SEARCH_DIRECT, &in2, &inner);
            cr_assert(subset(&inner, &got[0]), "step %d: topo misses a pair within 0.35", step);
        }
        total += got[0].n;
    }
    cr_assert_gt(total, 30 * 100, "not vacuous: every node has its quad at every call");
    ct_search_destroy(w[0]);
    ct_search_destroy(w[1]);
    ct_pairs_destroy(&got[0]);
    ct_pairs_destroy(&got[1]);
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&inner);
    ctt_scene_free(&s);
}

Test(search_topo, sliding_flat_equals_direct) { sliding(0, 1); }

Test(search_topo, sliding_curved_keeps_close_pairs) { sliding(0.02, 0); }

/*
 * Seed 000, Figure 4: a strip of unit quads (10 x 2) at z = 0 and one node
 * that moves N(t0) = (2.3, 0.4, 1.5) -> N(t1) = (3.4, 0.4, 1.5) (parallel to
 * the surface, one element) -> N(t2) = (5.6, 0.4, 0.2) (2.2 elements and
 * down onto segment S = quad (5, 0), 0.2 away). Its closest main nodes at
 * t0 and t1 are M0 = (2, 0) and M1 = (3, 0) (brute force, checked here);
 * S's nodes are neither, and one hop from M1 reaches (4, 0) whose segments
 * do not include S: topo misses the pair that direct, bucket and bsp find
 * (gap + margin 0.3). After a reset the full search finds it.
 */
Test(search_topo, undetected_impact)
{
    curve_a = 0;
    ctt_scene s;
    ctt_scene_init(&s, 64, 32);
    ts_main(&s, 10, 2);
    ct_idx N = ctt_scene_node(&s, 2.3, 0.4, 1.5);
    s.sec[s.nsec++] = N;
    const ct_idx S = 5; /* quad (5, 0) */
    const double path[3][3] = {{2.3, 0.4, 1.5}, {3.4, 0.4, 1.5}, {5.6, 0.4, 0.2}};
    ct_search_params p = ct_search_default_params(CT_SEARCH_TOPO);
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    ct_search_input in = ctt_scene_input(&s, 0.2, 0.1, 0);
    ct_pairs got, ref;
    ct_pairs_init(&got, 0);
    ct_pairs_init(&ref, 0);
    const ct_idx expect_closest[2] = {2, 3}; /* nodes (2, 0) and (3, 0) */
    for (int t = 0; t < 3; t++) {
        s.x[N] = (ct_real)path[t][0], s.y[N] = (ct_real)path[t][1], s.z[N] = (ct_real)path[t][2];
        if (t < 2) {
            /* Brute-force closest main node, and it is not a node of S. */
            ct_idx best = -1;
            double bd = 1e300;
            for (ct_idx m = 0; m < N; m++) {
                double dx = s.x[m] - s.x[N], dy = s.y[m] - s.y[N], dz = s.z[m] - s.z[N];
                double d2 = dx * dx + dy * dy + dz * dz;
                if (d2 < bd)
                    bd = d2, best = m;
            }
            cr_assert_eq(best, expect_closest[t]);
            cr_assert(best != s.n1[S] && best != s.n2[S] && best != s.n3[S] && best != s.n4[S]);
        }
        cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
        ctt_search(CT_SEARCH_DIRECT, &in, &ref);
        cr_assert(subset(&got, &ref));
        if (t < 2)
            cr_assert_eq(ref.n, 0, "nothing is near at t%d", t);
    }
    /* t2: direct finds exactly (N, S); topo misses it. */
    cr_assert_eq(ref.n, 1);
    cr_assert(has_pair(&ref, N, S));
    cr_assert(!has_pair(&got, N, S), "topo was expected to miss the impact on S");
    cr_assert_eq(got.n, 0);
    /* The bucket and bsp searches find it. */
    ct_pairs other;
    ct_pairs_init(&other, 0);
    ctt_search(CT_SEARCH_BUCKET, &in, &other);
    cr_assert(has_pair(&other, N, S), "bucket misses the impact");
    ctt_search(CT_SEARCH_BSP, &in, &other);
    cr_assert(has_pair(&other, N, S), "bsp misses the impact");
    /* A reset forces a full search, which finds it. */
    ct_search_reset(w);
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    cr_assert(ctt_same_pairs(&got, &ref));
    ct_pairs_destroy(&other);
    ct_pairs_destroy(&got);
    ct_pairs_destroy(&ref);
    ct_search_destroy(w);
    ctt_scene_free(&s);
}

static uint64_t rng;
static int irnd(int n)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (int)((rng >> 33) % (uint64_t)n);
}

/*
 * The first (full) search finds the brute-force closest main node, ties to
 * the smaller node index. Main nodes and secondaries sit on an integer
 * lattice (many exact ties, duplicated coordinates); segments join random
 * main nodes. With gap + margin 1e6 every segment attached to the closest
 * node passes the predicate, so the pairs reported for a secondary are
 * exactly the segments of its closest node, which the test computes by
 * brute force. Seed 4: a flat main lattice and secondaries 10 to 40 units
 * above or below it, whose ring scan stops by their distance to the main
 * nodes' box (many exact ties there too: nodes straight above lattice
 * points have four or more equidistant neighbours).
 */
Test(search_topo, full_search_is_brute_force_closest)
{
    int nm = ctt_checking() ? 300 : 2000, nsec = ctt_checking() ? 400 : 3000;
    for (int seed = 1; seed <= 4; seed++) {
        rng = (uint64_t)seed * 1234567;
        ctt_scene s;
        ctt_scene_init(&s, nm + nsec + 4, nm);
        int spread = seed == 3 ? 4 : 30; /* seed 3: very many ties */
        for (int i = 0; i < nm; i++)
            ctt_scene_node(&s, irnd(spread), irnd(spread), seed == 2 || seed == 4 ? 0 : irnd(spread));
        for (int k = 0; k < nm / 2; k++) {
            ct_idx v[4];
            for (int q = 0; q < 4; q++) {
                int dup;
                do {
                    v[q] = irnd(nm);
                    dup = 0;
                    for (int r = 0; r < q; r++)
                        dup |= v[r] == v[q];
                } while (dup);
            }
            ctt_scene_seg(&s, v[0], v[1], v[2], k % 3 ? v[3] : v[2]);
        }
        for (int i = 0; i < nsec; i++) {
            double h = 0.5 * irnd(3);
            double zs = seed == 4 ? (irnd(2) ? 1 : -1) * (10 + irnd(31)) : irnd(spread + 10) - 5 - h;
            s.sec[s.nsec++] = ctt_scene_node(&s, irnd(spread + 10) - 5 + h,
                                             irnd(spread + 10) - 5, zs);
        }
        /* Which main nodes have segments. */
        char *used = calloc((size_t)s.nn, 1);
        for (ct_idx j = 0; j < s.ns; j++)
            used[s.n1[j]] = used[s.n2[j]] = used[s.n3[j]] = used[s.n4[j]] = 1;
        ct_pairs exp, got;
        ct_pairs_init(&exp, 0);
        ct_pairs_init(&got, 0);
        ct_pairs_reserve(&exp, nsec * 20);
        for (ct_idx i = 0; i < s.nsec; i++) {
            ct_idx node = s.sec[i], best = -1;
            ct_real bd = 0;
            for (ct_idx m = 0; m < nm; m++) {
                if (!used[m])
                    continue;
                ct_real dx = s.x[m] - s.x[node], dy = s.y[m] - s.y[node], dz = s.z[m] - s.z[node];
                ct_real d2 = dx * dx + dy * dy + dz * dz;
                if (best < 0 || d2 < bd)
                    best = m, bd = d2; /* ascending m: a tie keeps the smaller */
            }
            for (ct_idx j = 0; j < s.ns; j++)
                if (s.n1[j] == best || s.n2[j] == best || s.n3[j] == best || s.n4[j] == best) {
                    cr_assert_lt(exp.n, exp.cap);
                    exp.node[exp.n] = node;
                    exp.seg[exp.n] = j;
                    exp.n++;
                }
        }
        ct_search_input in = ctt_scene_input(&s, 1e6, 0, 0);
        ctt_search(CT_SEARCH_TOPO, &in, &got);
        cr_assert(ctt_same_pairs(&exp, &got), "seed %d: %d pairs, expected %d", seed, got.n, exp.n);
        free(used);
        ct_pairs_destroy(&exp);
        ct_pairs_destroy(&got);
        ctt_scene_free(&s);
    }
}

/*
 * History: a node jumping 12 elements in one call is lost by the one-hop
 * update (the pair direct finds is missing); ct_search_reset(), a changed
 * secondary list or a corner rewritten in place forces a full search that
 * finds it again; the same secondaries in a new array do not.
 */
Test(search_topo, reset_forces_full_search)
{
    curve_a = 0;
    ctt_scene s;
    ctt_scene_init(&s, 600, 400);
    ts_main(&s, 20, 20);
    ct_idx N = ctt_scene_node(&s, 2.3, 2.4, 0.2);
    s.sec[s.nsec++] = N;
    ct_idx M2 = ctt_scene_node(&s, 7.6, 3.5, 0.1); /* a secondary later */
    ct_search_params p = ct_search_default_params(CT_SEARCH_TOPO);
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    ct_search_input in = ctt_scene_input(&s, 0.2, 0.1, 0);
    ct_pairs got, ref;
    ct_pairs_init(&got, 0);
    ct_pairs_init(&ref, 0);
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    cr_assert(ctt_same_pairs(&got, &ref));
    cr_assert_gt(ref.n, 0);
    s.x[N] = 15.3, s.y[N] = 14.4; /* quad (15, 14) below */
    const ct_idx Q = 14 * 20 + 15;
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    cr_assert(has_pair(&ref, N, Q));
    cr_assert(!has_pair(&got, N, Q), "one hop cannot follow a 12-element jump");
    ct_search_reset(w);
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    cr_assert(ctt_same_pairs(&got, &ref), "after a reset: %d pairs, direct %d", got.n, ref.n);
    /* Jump back. A new secondary array with the same contents keeps the
     * history (it belongs to the topology, not to the array's address):
     * one hop cannot follow the jump. A different secondary list restarts
     * the search. */
    s.x[N] = 2.3, s.y[N] = 2.4;
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    ct_idx sec2[2] = {N, 0};
    in.sec = sec2;
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    cr_assert(!ctt_same_pairs(&got, &ref), "the same secondaries in a new array keep the history");
    sec2[1] = M2;
    in.nsec = 2;
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    cr_assert(ctt_same_pairs(&got, &ref), "a changed secondary list must force a full search");
    /* And a corner rewritten in place, in the same arrays: quad (7, 3) turned
     * (same nodes, another first corner) is a new topology. */
    s.x[N] = 15.3, s.y[N] = 14.4;
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    const ct_idx q73 = 3 * 20 + 7;
    ct_idx c1 = s.n1[q73];
    s.n1[q73] = s.n2[q73], s.n2[q73] = s.n3[q73], s.n3[q73] = s.n4[q73], s.n4[q73] = c1;
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    cr_assert(has_pair(&ref, N, Q));
    cr_assert(ctt_same_pairs(&got, &ref), "a corner rewritten in place must force a full search");
    ct_pairs_destroy(&got);
    ct_pairs_destroy(&ref);
    ct_search_destroy(w);
    ctt_scene_free(&s);
}

/*
 * An empty main side (no segment: the coverage run found the full
 * search's "no main node" branch unexecuted), then the surface given, in
 * one search object: no pair, then direct's pairs (the empty first call
 * leaves no history that hides them). And no secondary node.
 */
Test(search_topo, empty_main_side_then_full)
{
    curve_a = 0;
    ctt_scene s;
    ctt_scene_init(&s, 600, 400);
    ts_main(&s, 10, 10);
    for (int i = 0; i < 5; i++)
        s.sec[s.nsec++] = ctt_scene_node(&s, 1.3 + i, 2.4, 0.1);
    ct_search_params p = ct_search_default_params(CT_SEARCH_TOPO);
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    ct_search_input in = ctt_scene_input(&s, 0.2, 0.1, 0);
    ct_pairs got, ref;
    ct_pairs_init(&got, 0);
    ct_pairs_init(&ref, 0);
    const ct_idx nseg = in.nseg;
    in.nseg = 0;
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    cr_assert_eq(got.n, 0);
    in.nseg = nseg;
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    ctt_search(CT_SEARCH_DIRECT, &in, &ref);
    cr_assert_gt(ref.n, 0);
    cr_assert(ctt_same_pairs(&got, &ref), "%d pairs, direct %d", (int)got.n, (int)ref.n);
    in.nsec = 0;
    cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
    cr_assert_eq(got.n, 0);
    ct_pairs_destroy(&got);
    ct_pairs_destroy(&ref);
    ct_search_destroy(w);
    ctt_scene_free(&s);
}
