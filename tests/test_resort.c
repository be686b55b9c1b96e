/*
 * test_resort.c -- the shared pair predicate against a sampled convex hull,
 * and the re-sort criterion against the direct search.
 */
#include "test_util.h"

#include <string.h>

static uint64_t rng_state = 88172645463325252ull;

static double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

/* Smallest distance from p to a dense sample of convex combinations of the
 * four corners (the hull), an independent estimate from above. */
static double sampled_hull_dist(const double p[3], double c[4][3], int m)
{
    double best = 1e300;
    for (int i = 0; i <= m; i++)
        for (int j = 0; j <= m - i; j++)
            for (int k = 0; k <= m - i - j; k++) {
                double w[4] = {(double)i / m, (double)j / m, (double)k / m, 0};
                w[3] = 1 - w[0] - w[1] - w[2];
                double q[3] = {0, 0, 0};
                for (int v = 0; v < 4; v++)
                    for (int a = 0; a < 3; a++)
                        q[a] += w[v] * c[v][a];
                double d2 = 0;
                for (int a = 0; a < 3; a++)
                    d2 += (p[a] - q[a]) * (p[a] - q[a]);
                if (d2 < best)
                    best = d2;
            }
    return sqrt(best);
}

Test(resort, predicate_matches_sampled_hull)
{
    /* The sample is within h of the true hull distance: with m = 40 the
     * sampling step on a unit-size tetrahedron is 1/40, so the sampled
     * distance exceeds the true one by at most about 0.05. Pairs decided
     * with more than that slack must agree with the predicate. */
    int ntrial = ctt_checking() ? 150 : 600, decided = 0;
    const double slack = 0.05;
    for (int t = 0; t < ntrial; t++) {
        double c[4][3];
        for (int v = 0; v < 4; v++)
            for (int a = 0; a < 3; a++)
                c[v][a] = urand();
        if (t % 3 == 0) /* flat quads too */
            for (int v = 0; v < 4; v++)
                c[v][2] = 0.5;
        double p[3] = {3 * urand() - 1, 3 * urand() - 1, 3 * urand() - 1};
        double d = 0.6 * urand();
        ct_real P[3], A[4][3];
        for (int a = 0; a < 3; a++) {
            P[a] = (ct_real)p[a];
            for (int v = 0; v < 4; v++)
                A[v][a] = (ct_real)c[v][a];
        }
        int got = ct_pair_may_touch(P, A[0], A[1], A[2], A[3], (ct_real)d);
        double ds = sampled_hull_dist(p, c, 40);
        if (ds <= d) {
            cr_assert(got, "trial %d: a hull point at %g <= d = %g but the predicate said no", t, ds, d);
            decided++;
        } else if (ds > d + slack) {
            cr_assert(!got, "trial %d: hull distance >= %g > d = %g but the predicate said yes", t,
                      ds - slack, d);
            decided++;
        }
    }
    cr_assert_gt(decided, ntrial * 3 / 4);
}

/* Flat quads with the point in their plane: every orientation of a flat
 * tetrahedron and a coplanar point is rounding noise, so an inside test
 * must not decide. Random planes, points in the plane outside the quad. */
Test(resort, predicate_coplanar_points)
{
    int ntrial = ctt_checking() ? 300 : 2000, checked = 0;
    for (int t = 0; t < ntrial; t++) {
        double o[3], u[3], v[3], c2[4][2], c[4][3];
        for (int a = 0; a < 3; a++) {
            o[a] = 20 * urand();
            u[a] = urand() - 0.5;
            v[a] = urand() - 0.5;
        }
        /* A convex quad in the (u, v) plane: a jittered unit square. */
        double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int k = 0; k < 4; k++)
            for (int a = 0; a < 2; a++)
                c2[k][a] = sq[k][a] + 0.2 * (urand() - 0.5);
        for (int k = 0; k < 4; k++)
            for (int a = 0; a < 3; a++)
                c[k][a] = o[a] + c2[k][0] * u[a] + c2[k][1] * v[a];
        double s0 = 1.5 + 2 * urand(), s1 = 3 * urand() - 1;
        double p[3];
        for (int a = 0; a < 3; a++)
            p[a] = o[a] + s0 * u[a] + s1 * v[a];
        double ds = sampled_hull_dist(p, c, 40), d = 0.3 * ds;
        ct_real P[3], A[4][3];
        for (int a = 0; a < 3; a++) {
            P[a] = (ct_real)p[a];
            for (int k = 0; k < 4; k++)
                A[k][a] = (ct_real)c[k][a];
        }
        /* The point is at least 0.3 (in plane units) beyond the quad; the
         * sampled distance exceeds d by far more than the sampling error. */
        cr_assert(!ct_pair_may_touch(P, A[0], A[1], A[2], A[3], (ct_real)d),
                  "trial %d: coplanar point at %g accepted for d = %g", t, ds, d);
        checked++;
    }
    cr_assert_eq(checked, ntrial);
}

/* The case found in the contact cycle: a vertical quad of the folded sheet
 * and a node in its plane, 0.51 away, accepted for d = 0.297 by an inside
 * test fooled by rounding. */
Test(resort, predicate_vertical_quad_regression)
{
    ct_real P[3] = {(ct_real)0x1.5a34c0bac34cp-2, (ct_real)0x1.c3851a1049a72p+0,
                    (ct_real)0x1.0a5a581f4a09ep+4};
    ct_real A[4][3] = {{(ct_real)0x1.5a34c0bac34cp-2, (ct_real)0x1.c3851a1049a72p+0,
                        (ct_real)0x1.d4b4b03e9413cp+3},
                       {(ct_real)0x1.0568635f824p-5, (ct_real)0x1.05d706bf6a709p+1,
                        (ct_real)0x1.eb3d86547f53ep+3},
                       {(ct_real)0x1.0568635f824p-5, (ct_real)0x1.05d706bf6a709p+1,
                        (ct_real)0x1.059ec32a3fa9fp+4},
                       {(ct_real)0x1.5a34c0bac34cp-2, (ct_real)0x1.c3851a1049a72p+0,
                        (ct_real)0x1.f4b4b03e9413cp+3}};
    cr_assert(!ct_pair_may_touch(P, A[0], A[1], A[2], A[3], (ct_real)0.2972));
    cr_assert(ct_pair_may_touch(P, A[0], A[1], A[2], A[3], (ct_real)0.52));
}

Test(resort, predicate_triangle_and_degenerate)
{
    ct_real a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    ct_real p1[3] = {0.25, 0.25, 0.3}, p2[3] = {1.0, 1.0, 0.0};
    /* p1 is 0.3 above the triangle's interior; p2 is sqrt(2)/2 from edge bc. */
    cr_assert(ct_pair_may_touch(p1, a, b, c, c, (ct_real)0.31));
    cr_assert(!ct_pair_may_touch(p1, a, b, c, c, (ct_real)0.29));
    cr_assert(ct_pair_may_touch(p2, a, b, c, c, (ct_real)0.71));
    cr_assert(!ct_pair_may_touch(p2, a, b, c, c, (ct_real)0.70));
    /* A needle (all corners collinear) is handled as its edges. */
    ct_real e[3] = {2, 0, 0}, p3[3] = {1.5, 0.4, 0};
    cr_assert(ct_pair_may_touch(p3, a, b, e, e, (ct_real)0.41));
    cr_assert(!ct_pair_may_touch(p3, a, b, e, e, (ct_real)0.39));
}

/* A plate of nq x nq unit quads at z = 0 (main) and a cloud of nodes above
 * it (secondary), in one node array. */
typedef struct scene {
    ct_idx nnode, nsec, nseg;
    ct_real *x, *y, *z, *x0, *y0, *z0;
    ct_idx *sec, *n1, *n2, *n3, *n4, *mainn;
    ct_idx nmain;
} scene;

static void scene_make(scene *s, int nq, int ncloud)
{
    int np = (nq + 1) * (nq + 1);
    s->nnode = np + ncloud;
    s->nseg = nq * nq;
    s->nsec = ncloud;
    s->nmain = np;
    s->x = ct_calloc((size_t)s->nnode, sizeof(ct_real));
    s->y = ct_calloc((size_t)s->nnode, sizeof(ct_real));
    s->z = ct_calloc((size_t)s->nnode, sizeof(ct_real));
    s->x0 = ct_calloc((size_t)s->nnode, sizeof(ct_real));
    s->y0 = ct_calloc((size_t)s->nnode, sizeof(ct_real));
    s->z0 = ct_calloc((size_t)s->nnode, sizeof(ct_real));
    s->sec = ct_calloc((size_t)ncloud, sizeof(ct_idx));
    s->mainn = ct_calloc((size_t)np, sizeof(ct_idx));
    s->n1 = ct_calloc((size_t)s->nseg, sizeof(ct_idx));
    s->n2 = ct_calloc((size_t)s->nseg, sizeof(ct_idx));
    s->n3 = ct_calloc((size_t)s->nseg, sizeof(ct_idx));
    s->n4 = ct_calloc((size_t)s->nseg, sizeof(ct_idx));
    cr_assert(s->x && s->y && s->z && s->sec && s->n1 && s->n4 && s->mainn);
    for (int j = 0; j <= nq; j++)
        for (int i = 0; i <= nq; i++) {
            int k = j * (nq + 1) + i;
            s->x[k] = (ct_real)i;
            s->y[k] = (ct_real)j;
            s->z[k] = (ct_real)(0.05 * sin(0.7 * i + 0.3 * j)); /* a little warp */
            s->mainn[k] = k;
        }
    for (int j = 0; j < nq; j++)
        for (int i = 0; i < nq; i++) {
            int e = j * nq + i, k = j * (nq + 1) + i;
            s->n1[e] = k;
            s->n2[e] = k + 1;
            s->n3[e] = k + nq + 2;
            s->n4[e] = k + nq + 1;
        }
    for (int c = 0; c < ncloud; c++) {
        int k = np + c;
        s->sec[c] = k;
        s->x[k] = (ct_real)(nq * urand());
        s->y[k] = (ct_real)(nq * urand());
        s->z[k] = (ct_real)(-0.6 + 1.2 * urand());
    }
}

static void scene_free(scene *s)
{
    ct_real *r[] = {s->x, s->y, s->z, s->x0, s->y0, s->z0};
    ct_idx *i[] = {s->sec, s->n1, s->n2, s->n3, s->n4, s->mainn};
    for (int k = 0; k < 6; k++) {
        ct_free(r[k]);
        ct_free(i[k]);
    }
}

static void run_direct(const scene *s, ct_real gap, ct_real margin, ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(CT_SEARCH_DIRECT);
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    ct_search_input in = {s->nnode, s->x, s->y, s->z, s->nsec, s->sec, s->nseg,
                          s->n1, s->n2, s->n3, s->n4, gap, margin, 0, CT_FILTER_HULL};
    cr_assert_eq(ct_search_run(w, &in, out), CT_OK);
    ct_search_destroy(w);
}

/* 1 when (node, seg) is in the canonical list p (secondary order is node
 * order here because sec is ascending). */
static int has_pair(const ct_pairs *p, ct_idx node, ct_idx seg)
{
    ct_idx lo = 0, hi = p->n;
    while (lo < hi) {
        ct_idx mid = lo + (hi - lo) / 2;
        if (p->node[mid] < node || (p->node[mid] == node && p->seg[mid] < seg))
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < p->n && p->node[lo] == node && p->seg[lo] == seg;
}

static void move_all(scene *s, double amp_sec, double amp_main)
{
    /* Random directions, each node moved by at most its amplitude. */
    for (ct_idx k = 0; k < s->nnode; k++) {
        double amp = k < s->nmain ? amp_main : amp_sec;
        double u[3] = {urand() - 0.5, urand() - 0.5, urand() - 0.5};
        double nrm = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) + 1e-300;
        double r = amp * urand();
        s->x[k] = s->x0[k] + (ct_real)(r * u[0] / nrm);
        s->y[k] = s->y0[k] + (ct_real)(r * u[1] / nrm);
        s->z[k] = s->z0[k] + (ct_real)(r * u[2] / nrm);
    }
}

Test(resort, candidates_complete_below_margin)
{
    scene s;
    scene_make(&s, 24, ctt_checking() ? 1500 : 6000);
    const ct_real gap = (ct_real)0.2, margin = (ct_real)0.15;
    ct_pairs cand, now;
    ct_pairs_init(&cand, 0);
    ct_pairs_init(&now, 0);
    run_direct(&s, gap, margin, &cand);
    memcpy(s.x0, s.x, sizeof(ct_real) * (size_t)s.nnode);
    memcpy(s.y0, s.y, sizeof(ct_real) * (size_t)s.nnode);
    memcpy(s.z0, s.z, sizeof(ct_real) * (size_t)s.nnode);
    for (int round = 0; round < 5; round++) {
        /* Secondary nodes move up to 0.09, main nodes up to 0.05: the bound
         * is at most 0.14 < margin. */
        move_all(&s, 0.09, 0.05);
        ct_real bound;
        int need = ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y,
                                    s.z, margin, &bound);
        cr_assert_eq(need, 0, "bound %g should be below the margin %g", (double)bound, (double)margin);
        cr_assert_leq(bound, (ct_real)0.14 + (ct_real)1e-6);
        run_direct(&s, gap, 0, &now);
        cr_assert_gt(now.n, 0);
        for (ct_idx k = 0; k < now.n; k++)
            cr_assert(has_pair(&cand, now.node[k], now.seg[k]),
                      "round %d: pair (%d, %d) within the gap is not among the stored candidates",
                      round, now.node[k], now.seg[k]);
    }
    ct_pairs_destroy(&cand);
    ct_pairs_destroy(&now);
    scene_free(&s);
}

Test(resort, asks_for_resort_above_margin)
{
    scene s;
    scene_make(&s, 8, 200);
    memcpy(s.x0, s.x, sizeof(ct_real) * (size_t)s.nnode);
    memcpy(s.y0, s.y, sizeof(ct_real) * (size_t)s.nnode);
    memcpy(s.z0, s.z, sizeof(ct_real) * (size_t)s.nnode);
    ct_real bound;
    /* Nothing moved: no re-sort. */
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)0.1, &bound), 0);
    cr_assert_eq(bound, 0);
    /* One secondary node moved by 0.07 and one main node by 0.05: 0.12 > 0.1. */
    s.z[s.sec[17]] += (ct_real)0.07;
    s.x[s.mainn[5]] += (ct_real)0.05;
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)0.1, &bound), 1);
    cr_assert_float_eq(bound, 0.12, CTT_TOL(1e-12, 1e-6));
    /* The same motion fits in a margin of 0.13. */
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)0.13, NULL), 0);
    /* A NaN position always asks for a re-sort. */
    s.y[s.sec[3]] = (ct_real)NAN;
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)1e30, NULL), 1);
    scene_free(&s);
}

Test(resort, motion_above_margin_can_break_completeness)
{
    /* Why the criterion matters: a node moved by more than the margin
     * towards the plate reaches pairs that were not stored. */
    scene s;
    scene_make(&s, 6, 1);
    ct_idx n = s.sec[0];
    s.x[n] = (ct_real)2.5;
    s.y[n] = (ct_real)2.5;
    s.z[n] = (ct_real)0.6;
    const ct_real gap = (ct_real)0.1, margin = (ct_real)0.2;
    ct_pairs cand, now;
    ct_pairs_init(&cand, 0);
    ct_pairs_init(&now, 0);
    run_direct(&s, gap, margin, &cand);
    cr_assert_eq(cand.n, 0, "the node starts 0.55 or more above the plate");
    memcpy(s.x0, s.x, sizeof(ct_real) * (size_t)s.nnode);
    memcpy(s.y0, s.y, sizeof(ct_real) * (size_t)s.nnode);
    memcpy(s.z0, s.z, sizeof(ct_real) * (size_t)s.nnode);
    s.z[n] = (ct_real)0.1; /* moved by 0.5 > margin */
    run_direct(&s, gap, 0, &now);
    cr_assert_gt(now.n, 0);
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  margin, NULL), 1);
    ct_pairs_destroy(&cand);
    ct_pairs_destroy(&now);
    scene_free(&s);
}
