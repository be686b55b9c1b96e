/*
 * test_resort.c -- the shared pair predicate against a sampled convex hull
 * and an exact hull distance of the test's own, and the re-sort criterion
 * against the direct search.
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

/* An exact hull distance written independently of predicate.c: the point's
 * projection onto a face's plane when it falls inside the face (signed
 * areas), else the nearest of the face's edges (clamped parameter); zero
 * inside the tetrahedron (four orientations of one sign). */
static void cross(const double u[3], const double v[3], double w[3])
{
    w[0] = u[1] * v[2] - u[2] * v[1];
    w[1] = u[2] * v[0] - u[0] * v[2];
    w[2] = u[0] * v[1] - u[1] * v[0];
}

static double tri_dist(const double p[3], const double a[3], const double b[3],
                       const double c[3])
{
    double ab[3], ac[3], n[3], nn = 0, h = 0;
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ac[k] = c[k] - a[k];
    }
    cross(ab, ac, n);
    for (int k = 0; k < 3; k++) {
        nn += n[k] * n[k];
        h += (p[k] - a[k]) * n[k];
    }
    double best = fmin(ctt_point_seg_dist(p, a, b),
                       fmin(ctt_point_seg_dist(p, b, c), ctt_point_seg_dist(p, c, a)));
    if (nn > 0) {
        double q[3];
        for (int k = 0; k < 3; k++)
            q[k] = p[k] - h / nn * n[k];
        const double *v[3] = {a, b, c};
        int inside = 1;
        for (int e = 0; e < 3; e++) {
            double u[3], w[3], x[3], s = 0;
            for (int k = 0; k < 3; k++) {
                u[k] = v[(e + 1) % 3][k] - v[e][k];
                w[k] = q[k] - v[e][k];
            }
            cross(u, w, x);
            for (int k = 0; k < 3; k++)
                s += x[k] * n[k];
            inside &= s >= 0;
        }
        if (inside)
            best = fmin(best, fabs(h) / sqrt(nn));
    }
    return best;
}

static double orient(const double a[3], const double b[3], const double c[3], const double p[3])
{
    double u[3], v[3], w[3], x[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = p[k] - a[k];
    }
    cross(u, v, x);
    return x[0] * w[0] + x[1] * w[1] + x[2] * w[2];
}

static double hull_dist(const double p[3], double c[4][3])
{
    double s1 = orient(c[0], c[1], c[2], p), s2 = orient(c[0], c[2], c[3], p);
    double s3 = orient(c[0], c[3], c[1], p), s4 = orient(c[1], c[3], c[2], p);
    if ((s1 > 0 && s2 > 0 && s3 > 0 && s4 > 0) || (s1 < 0 && s2 < 0 && s3 < 0 && s4 < 0))
        return 0;
    return fmin(fmin(tri_dist(p, c[0], c[1], c[2]), tri_dist(p, c[0], c[2], c[3])),
                fmin(tri_dist(p, c[0], c[1], c[3]), tri_dist(p, c[1], c[2], c[3])));
}

/* Warped quads in random planes, as on a curved or crumpled surface
 * (convex, and one in three a dart), and points all around them at distances near d: the cases
 * where the predicate's slab-and-edge-plane reject (after the prism and
 * edge accepts) decides. Every pair whose exact hull distance is more
 * than 1e-9 away from d must be decided as that distance says. */
Test(resort, predicate_matches_exact_hull_on_warped_quads)
{
    int ntrial = ctt_checking() ? 2000 : 20000, near = 0, far = 0;
    for (int t = 0; t < ntrial; t++) {
        double o[3], u[3], v[3], w[3];
        for (int a = 0; a < 3; a++) {
            o[a] = 10 * urand();
            u[a] = urand() - 0.5;
            v[a] = urand() - 0.5;
        }
        cross(u, v, w);
        double wl = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        if (!(wl > 0.05))
            continue;
        double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, warp = (t % 4) ? 0.3 * urand() : 0;
        /* One trial in three a dart: corner 3 pushed in past the diagonal
         * (a reflex outline, whose edge planes do not all bound the hull). */
        if (t % 3 == 1)
            sq[2][0] = sq[2][1] = 0.35;
        double c[4][3];
        for (int k = 0; k < 4; k++) {
            double s0 = sq[k][0] + 0.2 * (urand() - 0.5), s1 = sq[k][1] + 0.2 * (urand() - 0.5);
            double hgt = warp * (urand() - 0.5);
            for (int a = 0; a < 3; a++)
                c[k][a] = o[a] + s0 * u[a] + s1 * v[a] + hgt * w[a] / wl;
        }
        double q0 = 3 * urand() - 1, q1 = 3 * urand() - 1, q2 = 1.6 * urand() - 0.8, p[3];
        for (int a = 0; a < 3; a++)
            p[a] = o[a] + q0 * u[a] + q1 * v[a] + q2 * w[a] / wl;
        double dt = hull_dist(p, c), d = 0.05 + 0.6 * urand();
        if (fabs(dt - d) <= 1e-9 * (1 + d))
            continue;
        ct_real P[3], A[4][3];
        for (int a = 0; a < 3; a++) {
            P[a] = (ct_real)p[a];
            for (int k = 0; k < 4; k++)
                A[k][a] = (ct_real)c[k][a];
        }
        int got = ct_pair_may_touch(P, A[0], A[1], A[2], A[3], (ct_real)d);
#ifdef CT_SINGLE
        /* Single precision: the corners and the point are rounded to float,
         * which moves the distance by about 1e-6 of the coordinates. */
        if (fabs(dt - d) <= 1e-5 * (1 + o[0] + o[1] + o[2]))
            continue;
#endif
        cr_assert_eq(got, dt <= d, "trial %d: exact hull distance %.17g, d = %.17g, predicate %d",
                     t, dt, d, got);
        near += dt <= d;
        far += dt > d;
    }
    /* Both outcomes are exercised in numbers. */
    cr_assert_gt(near, ntrial / 10);
    cr_assert_gt(far, ntrial / 10);
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

/* Every pair the direct search finds within the gap at the current
 * positions (into now, not empty) is among the stored candidates. */
static void expect_complete(const scene *s, ct_real gap, const ct_pairs *cand, ct_pairs *now,
                            int round)
{
    run_direct(s, gap, 0, now);
    cr_assert_gt(now->n, 0);
    for (ct_idx k = 0; k < now->n; k++)
        cr_assert(has_pair(cand, now->node[k], now->seg[k]),
                  "round %d: pair (%d, %d) within the gap is not among the stored candidates",
                  round, (int)now->node[k], (int)now->seg[k]);
}

/* The positions at the sort: x0, y0, z0 = x, y, z. */
static void keep_sort_positions(scene *s)
{
    memcpy(s->x0, s->x, sizeof(ct_real) * (size_t)s->nnode);
    memcpy(s->y0, s->y, sizeof(ct_real) * (size_t)s->nnode);
    memcpy(s->z0, s->z, sizeof(ct_real) * (size_t)s->nnode);
}

/* A scene of nq x nq quads and ncloud secondary nodes, sorted: its
 * candidates within gap + margin by the direct search in cand, its
 * positions at the sort kept; now initialised (empty). */
static void sorted_scene(scene *s, int nq, int ncloud, ct_real gap, ct_real margin,
                         ct_pairs *cand, ct_pairs *now)
{
    scene_make(s, nq, ncloud);
    ct_pairs_init(cand, 0);
    ct_pairs_init(now, 0);
    run_direct(s, gap, margin, cand);
    keep_sort_positions(s);
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
    const ct_real gap = (ct_real)0.2, margin = (ct_real)0.15;
    ct_pairs cand, now;
    sorted_scene(&s, 24, ctt_checking() ? 1500 : 6000, gap, margin, &cand, &now);
    for (int round = 0; round < 5; round++) {
        /* Secondary nodes move up to 0.09, main nodes up to 0.05: the bound
         * is at most 0.14 < margin. */
        move_all(&s, 0.09, 0.05);
        ct_real bound;
        int need = ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y,
                                    s.z, margin, &bound);
        cr_assert_eq(need, 0, "bound %g should be below the margin %g", (double)bound, (double)margin);
        cr_assert_leq(bound, (ct_real)0.14 + (ct_real)1e-6);
        expect_complete(&s, gap, &cand, &now, round);
    }
    ct_pairs_destroy(&cand);
    ct_pairs_destroy(&now);
    scene_free(&s);
}

Test(resort, asks_for_resort_above_margin)
{
    scene s;
    scene_make(&s, 8, 200);
    keep_sort_positions(&s);
    ct_real bound;
    /* Nothing moved: no re-sort. */
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)0.1, &bound), 0);
    cr_assert_eq(bound, 0);
    /* One secondary node moved by 0.07 up and one main node by 0.05 down:
     * they approach by 0.12 > 0.1 (both bounds give 0.12). */
    s.z[s.sec[17]] += (ct_real)0.07;
    s.z[s.mainn[5]] -= (ct_real)0.05;
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)0.1, &bound), 1);
    cr_assert_float_eq(bound, 0.12, CTT_TOL(1e-12, 1e-6));
    /* The same motion fits in a margin of 0.13. */
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)0.13, NULL), 0);
    /* The main node moved sideways instead: the relative displacement is at
     * most |(-0.05, 0, 0.07)| = 0.086, below 0.1 (the sum of the two
     * largest displacements would say 0.12). */
    s.z[s.mainn[5]] = s.z0[s.mainn[5]];
    s.x[s.mainn[5]] += (ct_real)0.05;
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  (ct_real)0.1, &bound), 0);
    cr_assert_float_eq(bound, sqrt(0.07 * 0.07 + 0.05 * 0.05), CTT_TOL(1e-12, 1e-6));
    s.x[s.mainn[5]] = s.x0[s.mainn[5]];
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
    keep_sort_positions(&s);
    s.z[n] = (ct_real)0.1; /* moved by 0.5 > margin */
    run_direct(&s, gap, 0, &now);
    cr_assert_gt(now.n, 0);
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y, s.z,
                                  margin, NULL), 1);
    ct_pairs_destroy(&cand);
    ct_pairs_destroy(&now);
    scene_free(&s);
}

/* A rigid translation of both sets, 30 times the margin: the relative
 * bound is 0 (up to rounding), no re-sort is asked, and the stored
 * candidates still hold every pair the direct search finds within the gap
 * at the new positions; with the secondary nodes moved alone by the same
 * vector the criterion asks for a re-sort. */
Test(resort, rigid_translation_needs_no_resort)
{
    scene s;
    const ct_real gap = (ct_real)0.2, margin = (ct_real)0.15;
    ct_pairs cand, now;
    sorted_scene(&s, 16, ctt_checking() ? 800 : 3000, gap, margin, &cand, &now);
    const double t[3] = {3.0, -2.0, 1.5}; /* |t| = 3.9 = 26 margins */
    for (ct_idx k = 0; k < s.nnode; k++) {
        s.x[k] = s.x0[k] + (ct_real)t[0];
        s.y[k] = s.y0[k] + (ct_real)t[1];
        s.z[k] = s.z0[k] + (ct_real)t[2];
    }
    ct_real bound;
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y,
                                  s.z, margin, &bound), 0, "bound %g", (double)bound);
    cr_assert_leq(bound, CTT_TOL(1e-12, 1e-5));
    expect_complete(&s, gap, &cand, &now, 0);
    /* The plate left behind: the secondary nodes moved, the main ones not. */
    for (ct_idx k = 0; k < s.nmain; k++) {
        s.x[s.mainn[k]] = s.x0[s.mainn[k]];
        s.y[s.mainn[k]] = s.y0[s.mainn[k]];
        s.z[s.mainn[k]] = s.z0[s.mainn[k]];
    }
    cr_assert_eq(ct_resort_needed(s.nsec, s.sec, s.nmain, s.mainn, s.x0, s.y0, s.z0, s.x, s.y,
                                  s.z, margin, &bound), 1);
    cr_assert_float_eq(bound, sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]),
                       CTT_TOL(1e-12, 1e-5));
    ct_pairs_destroy(&cand);
    ct_pairs_destroy(&now);
    scene_free(&s);
}
