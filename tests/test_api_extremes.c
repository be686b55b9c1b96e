/*
 * test_api_extremes.c -- the public API at the edges of its input range
 * (suite "api_extremes"): each test is a case that a fuzzing campaign of
 * the C API (2026-12-01) found mishandled, checked against an answer
 * computed here (the direct search, a closest point in long double, the
 * closed form of an energy) or against the documented error code.
 */
#include <float.h>
#include <stdint.h>
#include <string.h>

#include "test_util.h"

/* ---- Allocation ---------------------------------------------------------- */

/* A count near SIZE_MAX (a negative int converted) is an overflow: NULL,
 * not a buffer of a few bytes (the rounding to CT_PAD wrapped). */
Test(api_extremes, calloc_near_size_max_is_null)
{
    const size_t counts[] = {SIZE_MAX, SIZE_MAX - 1, SIZE_MAX - 15, SIZE_MAX - 70,
                             (size_t)-1 / 8 + 1};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++)
        cr_assert_null(ct_calloc(counts[i], 8), "count %zu", counts[i]);
    cr_assert_null(ct_calloc(SIZE_MAX - 3, 1));
    void *p = ct_calloc(100, 8);
    cr_assert_not_null(p);
    ct_free(p);
}

/* ---- Searches on extreme extents ----------------------------------------- */

/* One unit quad scaled by s (corners 0..3), a node above its centre at
 * height 0.3 s (node 4); every algorithm's pairs against the direct
 * search's, and the workspace's size. */
static void quad_case(double s, ct_search_algo algo, int variant, int64_t max_cells,
                      ct_idx *npairs, size_t *memory)
{
    ct_real x[5] = {0, (ct_real)s, (ct_real)s, 0, (ct_real)(0.5 * s)};
    ct_real y[5] = {0, 0, (ct_real)s, (ct_real)s, (ct_real)(0.5 * s)};
    ct_real z[5] = {0, 0, 0, 0, (ct_real)(0.3 * s)};
    ct_idx n1 = 0, n2 = 1, n3 = 2, n4 = 3, sec = 4;
    ct_search_input in = {.nnode = 5, .x = x, .y = y, .z = z, .nsec = 1, .sec = &sec,
                          .nseg = 1, .n1 = &n1, .n2 = &n2, .n3 = &n3, .n4 = &n4,
                          .gap = (ct_real)(0.5 * s), .margin = 0};
    ct_search_params p = ct_search_default_params(algo);
    p.variant = variant;
    p.max_cells = max_cells;
    ct_search *sr;
    ct_pairs out;
    cr_assert_eq(ct_search_init(&sr, &p), CT_OK);
    cr_assert_eq(ct_pairs_init(&out, 0), CT_OK);
    cr_assert_eq(ct_search_run(sr, &in, &out), CT_OK, "%s, scale %g",
                 ct_search_algo_name(algo), s);
    *npairs = out.n;
    if (out.n == 1)
        cr_assert(out.node[0] == 4 && out.seg[0] == 0);
    *memory = ct_search_memory(sr);
    ct_pairs_destroy(&out);
    ct_search_destroy(sr);
}

/* The topological search's grid was sized from products of the extent's
 * sides: near 1e300 they overflowed (an int64_t cell count overflowed,
 * undefined behaviour, then no pair), on a subnormal extent 1 / h was
 * infinite (a NaN cell index). Now every algorithm finds the pair the
 * direct search finds, at every scale the search accepts. */
Test(api_extremes, searches_on_huge_and_subnormal_extents)
{
    const double scales[] = {1, CTT_SINGLE ? 1e18 : 1e160, CTT_SINGLE ? 1e36 : 1e299,
                             CTT_SINGLE ? 1e-40 : 1e-320, CTT_SINGLE ? 1e-30 : 1e-300};
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        ct_idx nd, n;
        size_t mem;
        quad_case(scales[i], CT_SEARCH_DIRECT, 1, 0, &nd, &mem);
        cr_assert_eq(nd, 1, "direct at scale %g", scales[i]);
        for (int a = 1; a < CT_SEARCH_NALGO; a++) {
            quad_case(scales[i], (ct_search_algo)a, 1, 0, &n, &mem);
            cr_assert_eq(n, nd, "%s at scale %g: %ld pairs, direct %ld",
                         ct_search_algo_name((ct_search_algo)a), scales[i], (long)n, (long)nd);
        }
    }
}

/* A cap on the bucket grid's cells of INT64_MAX on a subnormal extent
 * (whose face areas make every cell size tiny) took the whole cap: 2^30
 * cells, 8 GB. The cap is now bounded by 32 (nsec + nseg) + 2^20. */
Test(api_extremes, bucket_cells_bounded_by_the_input)
{
    for (int variant = 0; variant <= 1; variant++) {
        ct_idx n;
        size_t mem;
        quad_case(CTT_SINGLE ? 1e-40 : 1e-320, CT_SEARCH_BUCKET, variant, INT64_MAX, &n, &mem);
        cr_assert_eq(n, 1, "variant %d", variant);
        cr_assert_lt(mem, (size_t)64 << 20, "variant %d: workspace %zu bytes", variant, mem);
    }
}

/* ---- Narrow phase ---------------------------------------------------------- */

/* One pair: node 4 against the segment of corners 0..3 (a triangle when
 * c[3] repeats c[2]). */
typedef struct one_pair {
    ct_real d, pen, nx, ny, nz, cx, cy, cz, h1, h2, h3, h4, g;
    uint8_t fl;
    ct_contact_geo o;
} one_pair;

static int narrow_one(const double c[5][3], int tri, ct_real gap, ct_real cap,
                      ct_quad_method m, int two, one_pair *r)
{
    ct_real x[5], y[5], z[5];
    for (int i = 0; i < 5; i++) {
        x[i] = (ct_real)c[i][0];
        y[i] = (ct_real)c[i][1];
        z[i] = (ct_real)c[i][2];
    }
    ct_idx n1 = 0, n2 = 1, n3 = 2, n4 = tri ? 2 : 3, node = 4, seg = 0;
    ct_contact_geo o = {&r->d,  &r->pen, &r->nx, &r->ny, &r->nz, &r->cx, &r->cy,
                        &r->cz, &r->h1,  &r->h2, &r->h3, &r->h4, &r->g,  &r->fl};
    r->o = o;
    ct_real gn[5] = {0.1f, 0.1f, 0.1f, 0.1f, 0.1f};
    return ct_narrow_node_segment(1, &node, &seg, &n1, &n2, &n3, &n4, x, y, z,
                                  cap != 0 ? gn : NULL, NULL, gap, cap, 0, m, two, &r->o, NULL);
}

/* A node whose distance to the segment overflows when squared (finite
 * coordinates near 1e154 and beyond) got dist = +inf and a zero normal;
 * now the documented skip: flag NONFINITE, dist CT_NARROW_FAR, normal
 * (0, 0, 1), pen 0. */
Test(api_extremes, narrow_overflowing_distance_is_skipped)
{
    const double big[] = {CTT_SINGLE ? 1e20 : 1e160, CTT_SINGLE ? 1e30 : 1e200,
                          CTT_SINGLE ? 1e37 : 1e300};
    for (size_t b = 0; b < sizeof big / sizeof big[0]; b++)
        for (int m = 0; m < CT_QUAD_NMETHOD; m++)
            for (int two = 0; two <= 1; two++) {
                const double c[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                        {big[b], big[b], 1}};
                one_pair r;
                cr_assert_eq(narrow_one(c, 0, (ct_real)0.1, 0, (ct_quad_method)m, two, &r),
                             CT_OK);
                cr_assert(r.fl & CT_NARROW_NONFINITE, "coordinate %g, method %d: flag %d",
                          big[b], m, r.fl);
                cr_assert(r.d == CT_NARROW_FAR && r.pen == 0 && r.nx == 0 && r.ny == 0 &&
                          r.nz == 1);
            }
    /* At 1e3 the same pair is an ordinary one. */
    const double c[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1e3, 1e3, 1}};
    one_pair r;
    cr_assert_eq(narrow_one(c, 0, (ct_real)0.1, 0, CT_QUAD_4TRI, 1, &r), CT_OK);
    cr_assert(!(r.fl & CT_NARROW_NONFINITE));
    cr_assert_lt(ctt_rel(r.d, sqrt(2.0 * 999.0 * 999.0 + 1.0)), CTT_TOL(1e-12, 1e-5));
}

/* The scalar gap and the caps are parameters: a NaN gap was dropped by the
 * max with per-node gaps, a negative one gave negative penetrations, a NaN
 * cap acted as no cap. Now CT_ERR_ARG, as ct_search_run for its gap. */
Test(api_extremes, narrow_bad_scalar_gap_is_refused)
{
    const double c[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0.05}};
    one_pair r;
    cr_assert_eq(narrow_one(c, 0, (ct_real)0.1, 0, CT_QUAD_4TRI, 0, &r), CT_OK);
    cr_assert_eq(narrow_one(c, 0, (ct_real)0.1, (ct_real)0.2, CT_QUAD_4TRI, 0, &r), CT_OK);
    const ct_real bad_gap[] = {(ct_real)NAN, (ct_real)INFINITY, -1, (ct_real)-1e-30};
    for (size_t i = 0; i < sizeof bad_gap / sizeof bad_gap[0]; i++)
        for (int cap = 0; cap <= 1; cap++)
            cr_assert_eq(narrow_one(c, 0, bad_gap[i], cap ? (ct_real)0.2 : 0, CT_QUAD_4TRI, 0,
                                    &r),
                         CT_ERR_ARG, "gap %g, per-node gaps %d", (double)bad_gap[i], cap);
    cr_assert_eq(narrow_one(c, 0, (ct_real)0.1, (ct_real)NAN, CT_QUAD_4TRI, 0, &r),
                 CT_ERR_ARG);
    /* ct_narrow_node_slots and the edge-edge phase alike. */
    ct_real x[5] = {0, 1, 1, 0, 0.5f}, y[5] = {0, 0, 1, 1, 0.5f}, z[5] = {0, 0, 0, 0, 0.05f};
    ct_idx sel = 0, node = 4, s1 = 0, s2 = 1, s3 = 2, s4 = 3;
    cr_assert_eq(ct_narrow_node_slots(1, &sel, &node, &s1, &s2, &s3, &s4, x, y, z, -1,
                                      CT_QUAD_4TRI, 0, &r.o, NULL),
                 CT_ERR_ARG);
    ct_real ed, ep, enx, eny, enz, esa, esb, pax, pay, paz, pbx, pby, pbz, eg;
    uint8_t efl;
    ct_edge_geo eo = {&ed, &ep, &enx, &eny, &enz, &esa, &esb, &pax,
                      &pay, &paz, &pbx, &pby, &pbz, &eg, &efl};
    ct_idx ea = 0, eb = 1, e1[2] = {0, 2}, e2[2] = {1, 3};
    cr_assert_eq(ct_narrow_edge_edge(1, &ea, &eb, e1, e2, x, y, z, NULL, (ct_real)0.1, 0, &eo,
                                     NULL),
                 CT_OK);
    cr_assert_eq(ct_narrow_edge_edge(1, &ea, &eb, e1, e2, x, y, z, NULL, (ct_real)NAN, 0, &eo,
                                     NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_edge_edge(1, &ea, &eb, e1, e2, x, y, z, NULL, -1, 0, &eo, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_edge_edge(1, &ea, &eb, e1, e2, x, y, z, NULL, (ct_real)0.1,
                                     (ct_real)NAN, &eo, NULL),
                 CT_ERR_ARG);
}

/* The closest point of triangle abc to p in long double: the projection on
 * the plane when it falls inside, else the closest of the three edges. */
static long double ref_edge2(const long double p[3], const long double a[3],
                             const long double b[3])
{
    long double ab[3], ap[3], t = 0, l = 0, d = 0;
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ap[k] = p[k] - a[k];
        t += ab[k] * ap[k];
        l += ab[k] * ab[k];
    }
    t = l > 0 ? t / l : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    for (int k = 0; k < 3; k++) {
        long double q = ap[k] - t * ab[k];
        d += q * q;
    }
    return d;
}

static long double ref_tri_dist(const long double p[3], const long double v[3][3])
{
    long double e1[3], e2[3], n[3], w[3], nn = 0;
    for (int k = 0; k < 3; k++) {
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
        w[k] = p[k] - v[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    for (int k = 0; k < 3; k++)
        nn += n[k] * n[k];
    /* Inside when p's projection is on the inner side of every edge. */
    int inside = 1;
    for (int i = 0; i < 3; i++) {
        const long double *A = v[i], *B = v[(i + 1) % 3];
        long double ab[3], ap[3], c[3];
        for (int k = 0; k < 3; k++) {
            ab[k] = B[k] - A[k];
            ap[k] = p[k] - A[k];
        }
        c[0] = ab[1] * ap[2] - ab[2] * ap[1];
        c[1] = ab[2] * ap[0] - ab[0] * ap[2];
        c[2] = ab[0] * ap[1] - ab[1] * ap[0];
        inside &= c[0] * n[0] + c[1] * n[1] + c[2] * n[2] >= 0;
    }
    if (inside) {
        long double h = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
        return fabsl(h) / sqrtl(nn);
    }
    long double d = ref_edge2(p, v[0], v[1]);
    long double d2 = ref_edge2(p, v[1], v[2]), d3 = ref_edge2(p, v[2], v[0]);
    d = d2 < d ? d2 : d;
    d = d3 < d ? d3 : d;
    return sqrtl(d);
}

static double urand(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/* A needle triangle: corners b and c about 1 apart near the origin, the
 * third corner L away along a random direction (corner `far` of the
 * three), in long double as the kernel will see them (rounded to ct_real);
 * the node p, placed by `beyond`: 1 beyond the short edge, on the side away
 * from the far corner, within 1 of it; 0 anywhere in the cube of side 2
 * around the short edge. */
static void needle(uint64_t *seed, double L, int far, int beyond, long double v[3][3],
                   long double p[3], double c[5][3])
{
    double dir[3], nd = 0;
    for (int k = 0; k < 3; k++) {
        dir[k] = urand(seed) - 0.5;
        nd += dir[k] * dir[k];
    }
    nd = sqrt(nd);
    for (int i = 0, q = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++)
            v[i][k] = i == far ? (long double)(L * dir[k] / nd)
                               : (long double)(urand(seed) - 0.5 + (q ? 0.5 : -0.5) * (k == 0));
        q += i != far;
    }
    const long double *b = v[(far + 1) % 3], *cc = v[(far + 2) % 3], *a = v[far];
    if (beyond) {
        /* m + s u + t w + h n: u along the short edge, n the plane's
         * normal, w = n x u pointing away from the far corner. */
        long double m[3], u[3], e[3], n[3], w[3], lu = 0, ln = 0, lw = 0, side = 0;
        for (int k = 0; k < 3; k++) {
            m[k] = (b[k] + cc[k]) / 2;
            u[k] = cc[k] - b[k];
            e[k] = a[k] - b[k];
            lu += u[k] * u[k];
        }
        n[0] = u[1] * e[2] - u[2] * e[1];
        n[1] = u[2] * e[0] - u[0] * e[2];
        n[2] = u[0] * e[1] - u[1] * e[0];
        for (int k = 0; k < 3; k++)
            ln += n[k] * n[k];
        w[0] = n[1] * u[2] - n[2] * u[1];
        w[1] = n[2] * u[0] - n[0] * u[2];
        w[2] = n[0] * u[1] - n[1] * u[0];
        for (int k = 0; k < 3; k++) {
            lw += w[k] * w[k];
            side += w[k] * (a[k] - m[k]);
        }
        const long double su = (long double)(urand(seed) - 0.5) / sqrtl(lu);
        const long double tw = (side > 0 ? -1 : 1) * (long double)(0.05 + urand(seed)) / sqrtl(lw);
        const long double hn = (long double)(2 * urand(seed) - 1) / sqrtl(ln);
        for (int k = 0; k < 3; k++)
            p[k] = m[k] + su * u[k] + tw * w[k] + hn * n[k];
    } else {
        for (int k = 0; k < 3; k++)
            p[k] = (long double)(2 * urand(seed) - 1);
    }
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) {
            c[i][k] = (double)(ct_real)v[i][k];
            v[i][k] = (long double)c[i][k];
        }
    for (int k = 0; k < 3; k++) {
        c[4][k] = (double)(ct_real)p[k];
        p[k] = (long double)c[4][k];
        c[3][k] = c[2][k];
    }
}

/* Needles against the long double closest point. The triangle kernel's
 * vertex tests were differences of dot products with the edges from the
 * first corner: with that corner the far one they are of the order of L^2
 * and lost their sign beyond L ~ 1e7 (double): 11-17 % of the nodes beyond
 * the short edge went to a vertex up to 0.37 farther than the edge. Beyond
 * the short edge the answer is now within 16 eps L (the coordinates are
 * taken relative to the first corner, L away) up to L = 1e10 (single:
 * 3e4, its degenerate test's reach). Anywhere near the short edge, the
 * projection on the face itself is formed from products of the long edges
 * and loses about eps L^2 (the documented limit of needles in
 * ct_narrow.h): within 1e-6 up to L = 1e6 (single: 1e-4 up to 1e2). */
Test(api_extremes, needle_triangles_against_long_double)
{
    uint64_t seed = 12345;
    const double eps = CTT_SINGLE ? (double)FLT_EPSILON : DBL_EPSILON;
    for (int beyond = 1; beyond >= 0; beyond--) {
        const double lmin = 1e2, lmax = beyond ? CTT_TOL(1e10, 3e4) : CTT_TOL(1e6, 1e2);
        int tested = 0;
        double worst = 0;
        for (int it = 0; it < 3000; it++) {
            const double L = lmin * pow(lmax / lmin, urand(&seed));
            const int far = it % 3;
            long double v[3][3], p[3];
            double c[5][3];
            needle(&seed, L, far, beyond, v, p, c);
            one_pair r;
            cr_assert_eq(narrow_one(c, 1, 10, 0, CT_QUAD_4TRI, 1, &r), CT_OK);
            if (r.fl & CT_NARROW_DEGENERATE)
                continue;
            const double ref = (double)ref_tri_dist(p, v);
            const double err = fabs((double)r.d - ref);
            const double tol = beyond ? 16 * eps * L + 1e-12 : CTT_TOL(1e-6, 1e-4);
            worst = err > worst ? err : worst;
            cr_assert_leq(err, tol, "%s, L %g, far corner %d: dist %.9g, reference %.9g",
                          beyond ? "beyond the short edge" : "near it", L, far, (double)r.d,
                          ref);
            tested++;
        }
        cr_assert_geq(tested, 2900, "only %d of 3000 needles were projected", tested);
        cr_log_info("needles %s: %d projected, worst |dist - reference| %.3g",
                    beyond ? "beyond the short edge" : "near it", tested, worst);
    }
}

/* ---- Forces ---------------------------------------------------------------- */

/* The TYPE7 energy of a gap whose square overflows (above 1.3e154, single
 * 1.8e19) was inf times a vanishing series: NaN. It is K0 g^2 phi(p / g) =
 * K0 p^2 / 2 (1 + O(p / g)). */
Test(api_extremes, type7_energy_of_a_huge_gap)
{
    const ct_real g = (ct_real)(CTT_SINGLE ? 1e25 : 1e200), p = (ct_real)1e-3, K0 = 2;
    const ct_real e = ct_type7_energy(K0, g, p);
    cr_assert_lt(ctt_rel(e, 1e-6), CTT_TOL(1e-12, 1e-6), "energy %g", (double)e);
    ct_real fel, ktan, en;
    int32_t flag;
    cr_assert_eq(ct_penalty_type7(1, &p, &g, &K0, &fel, &ktan, &en, &flag), CT_OK);
    cr_assert_eq(en, e);
    cr_assert_lt(ctt_rel(fel, 2e-3), CTT_TOL(1e-12, 1e-6));
}

/* An edge-edge force magnitude that is NaN or negative gives no force (it
 * gave NaN or pulling nodal forces). An infinite one, which gave no force
 * too, is CT_ERR_NONFINITE now (test_edge_nonfinite.c); the third pair
 * has magnitude 0 instead. */
Test(api_extremes, edge_forces_of_bad_magnitudes_are_zero)
{
    const ct_real mags[4] = {(ct_real)NAN, -1, 0, 2};
    ct_real nx[4] = {0, 0, 0, 0}, ny[4] = {0, 0, 0, 0}, nz[4] = {1, 1, 1, 1};
    ct_real sa[4] = {0.25f, 0.25f, 0.25f, 0.25f}, sb[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    ct_real fx[16], fy[16], fz[16];
    cr_assert_eq(ct_edge_edge_forces(4, mags, nx, ny, nz, sa, sb, fx, fy, fz), CT_OK);
    for (int k = 0; k < 3; k++)
        for (int s = 0; s < 4; s++)
            cr_assert(fx[4 * k + s] == 0 && fy[4 * k + s] == 0 && fz[4 * k + s] == 0,
                      "pair %d slot %d", k, s);
    cr_assert_eq(fz[12], (ct_real)1.5);
    cr_assert_eq(fz[13], (ct_real)0.5);
    cr_assert_eq(fz[14], -1);
    cr_assert_eq(fz[15], -1);
}

/* ---- Parameters ------------------------------------------------------------ */

Test(api_extremes, search_init_refuses_out_of_range_params)
{
    ct_search *s = NULL;
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    const double bad_factor[] = {NAN, INFINITY, 2e6, -1};
    for (size_t i = 0; i < sizeof bad_factor / sizeof bad_factor[0]; i++) {
        p.cell_factor = bad_factor[i];
        cr_assert_eq(ct_search_init(&s, &p), CT_ERR_ARG, "cell_factor %g", bad_factor[i]);
        cr_assert_null(s);
    }
    p.cell_factor = 500;
    cr_assert_eq(ct_search_init(&s, &p), CT_OK);
    ct_search_destroy(s);
    p = ct_search_default_params(CT_SEARCH_BSP);
    p.max_pairs = -1;
    cr_assert_eq(ct_search_init(&s, &p), CT_ERR_ARG);
}
