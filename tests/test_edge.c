/*
 * test_edge.c -- edge-to-edge narrow phase and nodal forces (suite "edge"),
 * against brute-force sampled distances and hand-computed cases; the nodal
 * forces' non-finite inputs (test_nonfinite.h).
 */
#include <string.h>

#include "test_nonfinite.h"

typedef struct egeo {
    ct_edge_geo g;
    ct_real *buf;
} egeo;

static void egeo_init(egeo *o, ct_idx n)
{
    size_t stride = (size_t)n + CT_PAD;
    o->buf = ct_calloc(stride * 14, sizeof(ct_real));
    cr_assert_not_null(o->buf);
    ct_real **f[] = {&o->g.dist, &o->g.pen, &o->g.nx,  &o->g.ny,  &o->g.nz,
                     &o->g.sa,   &o->g.sb,  &o->g.pax, &o->g.pay, &o->g.paz,
                     &o->g.pbx,  &o->g.pby, &o->g.pbz, &o->g.gap};
    for (int i = 0; i < 14; i++)
        *f[i] = o->buf + stride * (size_t)i;
    o->g.flag = ct_calloc((size_t)n, 1);
}

static void egeo_free(egeo *o)
{
    ct_free(o->buf);
    ct_free(o->g.flag);
}

/* Edge A = nodes 0-1, edge B = nodes 2-3. */
static void one(const double P[4][3], double gap, egeo *o)
{
    ct_real x[4], y[4], z[4];
    for (int i = 0; i < 4; i++) {
        x[i] = (ct_real)P[i][0];
        y[i] = (ct_real)P[i][1];
        z[i] = (ct_real)P[i][2];
    }
    ct_idx ea = 0, eb = 1, e1[2] = {0, 2}, e2[2] = {1, 3};
    cr_assert_eq(ct_narrow_edge_edge(1, &ea, &eb, e1, e2, x, y, z, NULL, (ct_real)gap, 0, &o->g,
                                     NULL),
                 CT_OK);
}

static unsigned rng_state = 777u;
static double urand(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (rng_state >> 8) / 16777216.0;
}

static double d3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

Test(edge, random_pairs_against_sampling)
{
    egeo o;
    egeo_init(&o, 1);
    int N = ctt_checking() ? 300 : 1000, npair = ctt_checking() ? 8 : 25;
    for (int q = 0; q < npair; q++) {
        double P[4][3];
        for (int i = 0; i < 4; i++)
            for (int d = 0; d < 3; d++)
                P[i][d] = 2 * urand() - 1;
        double best = 1e300, la = d3(P[0], P[1]), lb = d3(P[2], P[3]);
        for (int i = 0; i <= N; i++)
            for (int j = 0; j <= N; j++) {
                double a[3], b[3], s = (double)i / N, t = (double)j / N;
                for (int d = 0; d < 3; d++) {
                    a[d] = P[0][d] + s * (P[1][d] - P[0][d]);
                    b[d] = P[2][d] + t * (P[3][d] - P[2][d]);
                }
                double dd = d3(a, b);
                best = dd < best ? dd : best;
            }
        one(P, 0.1, &o);
        double D = o.g.dist[0];
        cr_assert(D <= best + CTT_TOL(1e-12, 1e-5), "pair %d: %g > sampled %g", q, D, best);
        cr_assert(D >= best - (la + lb) / N, "pair %d: %g << sampled %g", q, D, best);
        /* The points are on the edges at the reported parameters. */
        double sa = o.g.sa[0], sb = o.g.sb[0];
        cr_assert(sa >= 0 && sa <= 1 && sb >= 0 && sb <= 1);
        double pa[3] = {o.g.pax[0], o.g.pay[0], o.g.paz[0]};
        double pb[3] = {o.g.pbx[0], o.g.pby[0], o.g.pbz[0]};
        for (int d = 0; d < 3; d++) {
            cr_assert_float_eq(pa[d], P[0][d] + sa * (P[1][d] - P[0][d]), CTT_TOL(1e-14, 1e-6));
            cr_assert_float_eq(pb[d], P[2][d] + sb * (P[3][d] - P[2][d]), CTT_TOL(1e-14, 1e-6));
        }
        cr_assert_float_eq(D, d3(pa, pb), CTT_TOL(1e-14, 1e-6));
        cr_assert_float_eq(o.g.pen[0], fmax(0, 0.2 - D), CTT_TOL(1e-14, 1e-6));
        /* Normal along Pa - Pb. */
        if (D > 1e-6)
            for (int d = 0; d < 3; d++) {
                double n = d == 0 ? o.g.nx[0] : (d == 1 ? o.g.ny[0] : o.g.nz[0]);
                cr_assert_float_eq(n, (pa[d] - pb[d]) / D, CTT_TOL(1e-12, 1e-5));
            }
    }
    egeo_free(&o);
}

Test(edge, parallel_edges)
{
    egeo o;
    egeo_init(&o, 1);
    /* Overlapping parallel edges 0.3 apart: distance 0.3, sa at the middle
     * of the overlap [0.5, 1] of A, normal +z. */
    double P[4][3] = {{0, 0, 0.3}, {2, 0, 0.3}, {1, 0, 0}, {3, 0, 0}};
    one(P, 0.2, &o);
    cr_assert_float_eq(o.g.dist[0], 0.3, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.sa[0], 0.75, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.sb[0], 0.25, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.nz[0], 1.0, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.pen[0], 0.1, CTT_TOL(1e-15, 1e-7));
    cr_assert(o.g.flag[0] & CT_NARROW_PARALLEL);
    /* Anti-parallel, disjoint: ends 1 apart along x, 0.3 in z. */
    double Q[4][3] = {{0, 0, 0.3}, {1, 0, 0.3}, {3, 0, 0}, {2, 0, 0}};
    one(Q, 0.2, &o);
    cr_assert_float_eq(o.g.dist[0], sqrt(1.09), CTT_TOL(1e-15, 1e-7));
    cr_assert_eq(o.g.sa[0], 1);
    cr_assert_eq(o.g.sb[0], 1);
    /* Nearly parallel (1e-9 rad): the closest pair is B1 = (1, 0, 0) and A
     * at x = 1, z = 0.3 + 1e-9 (to 1e-18); finite. */
    double R[4][3] = {{0, 0, 0.3}, {2, 0, 0.3 + 2e-9}, {1, 0, 0}, {3, 0, 0}};
    one(R, 0.2, &o);
    cr_assert_float_eq(o.g.dist[0], 0.3 + 1e-9, CTT_TOL(1e-14, 1e-6));
    cr_assert(isfinite(o.g.sa[0]) && isfinite(o.g.nx[0]));
    /* Collinear overlapping (touching): a unit normal perpendicular to A. */
    double S[4][3] = {{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {3, 0, 0}};
    one(S, 0.2, &o);
    cr_assert_float_eq(o.g.dist[0], 0, CTT_TOL(1e-15, 1e-7));
    double nl = o.g.nx[0] * o.g.nx[0] + o.g.ny[0] * o.g.ny[0] + o.g.nz[0] * o.g.nz[0];
    cr_assert_float_eq(nl, 1.0, CTT_TOL(1e-14, 1e-6));
    cr_assert_float_eq(o.g.nx[0], 0, CTT_TOL(1e-15, 1e-7));
    egeo_free(&o);
}

Test(edge, crossing_edges)
{
    egeo o;
    egeo_init(&o, 1);
    /* A along x through the origin, B along y through it: they intersect;
     * normal = +-(x cross y) = +-z, oriented from B's midpoint (0, 0.5, 0)
     * to A's (0.5, 0, 0)... whose z component is 0: the largest component
     * of x cross y = +z is made positive. */
    double P[4][3] = {{-0.5, 0, 0}, {1.5, 0, 0}, {0, -0.5, 0}, {0, 1.5, 0}};
    one(P, 0.1, &o);
    cr_assert_float_eq(o.g.dist[0], 0, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.sa[0], 0.25, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.sb[0], 0.25, CTT_TOL(1e-15, 1e-7));
    cr_assert_eq(o.g.nz[0], 1);
    cr_assert_float_eq(o.g.pen[0], 0.2, CTT_TOL(1e-15, 1e-7));
    /* Lifted A by 0.05: normal +z, distance 0.05; lowered: -z. */
    P[0][2] = P[1][2] = 0.05;
    one(P, 0.1, &o);
    cr_assert_float_eq(o.g.dist[0], 0.05, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.nz[0], 1, CTT_TOL(1e-15, 1e-7));
    P[0][2] = P[1][2] = -0.05;
    one(P, 0.1, &o);
    cr_assert_float_eq(o.g.nz[0], -1, CTT_TOL(1e-15, 1e-7));
    /* Crossing, A's midpoint above B's: the normal points up. */
    double Q[4][3] = {{-1, 0, 0.5}, {1, 0, -0.5}, {0, -1, -0.5}, {0, 1, 0.5}};
    one(Q, 0.1, &o);
    cr_assert_float_eq(o.g.dist[0], 0, CTT_TOL(1e-15, 1e-7));
    double nl = o.g.nx[0] * o.g.nx[0] + o.g.ny[0] * o.g.ny[0] + o.g.nz[0] * o.g.nz[0];
    cr_assert_float_eq(nl, 1.0, CTT_TOL(1e-14, 1e-6));
    egeo_free(&o);
}

Test(edge, forces_conserve_force_and_moment)
{
    int n = 64;
    egeo o;
    egeo_init(&o, n);
    ct_real x[256], y[256], z[256];
    ct_idx ea[64], eb[64], e1[128], e2[128];
    for (int k = 0; k < n; k++) {
        for (int i = 0; i < 4; i++) {
            x[4 * k + i] = (ct_real)(2 * urand() - 1 + 5);
            y[4 * k + i] = (ct_real)(2 * urand() - 1 - 3);
            z[4 * k + i] = (ct_real)(2 * urand() - 1);
        }
        ea[k] = 2 * k;
        eb[k] = 2 * k + 1;
        e1[2 * k] = 4 * k;
        e2[2 * k] = 4 * k + 1;
        e1[2 * k + 1] = 4 * k + 2;
        e2[2 * k + 1] = 4 * k + 3;
    }
    cr_assert_eq(ct_narrow_edge_edge(n, ea, eb, e1, e2, x, y, z, NULL, (ct_real)0.5, 0, &o.g,
                                     NULL),
                 CT_OK);
    ct_real F[64], fx[256], fy[256], fz[256];
    for (int k = 0; k < n; k++)
        F[k] = (ct_real)(1 + 10 * urand());
    cr_assert_eq(ct_edge_edge_forces(n, F, o.g.nx, o.g.ny, o.g.nz, o.g.sa, o.g.sb, fx, fy, fz),
                 CT_OK);
    for (int k = 0; k < n; k++) {
        double sf[3] = {0, 0, 0}, mo[3] = {0, 0, 0}, scale = 0;
        for (int i = 0; i < 4; i++) {
            double r[3] = {x[4 * k + i], y[4 * k + i], z[4 * k + i]};
            double f[3] = {fx[4 * k + i], fy[4 * k + i], fz[4 * k + i]};
            sf[0] += f[0]; sf[1] += f[1]; sf[2] += f[2];
            mo[0] += r[1] * f[2] - r[2] * f[1];
            mo[1] += r[2] * f[0] - r[0] * f[2];
            mo[2] += r[0] * f[1] - r[1] * f[0];
            scale = fmax(scale, sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) * F[k]);
        }
        for (int d = 0; d < 3; d++) {
            cr_assert(fabs(sf[d]) <= CTT_TOL(1e-14, 1e-6) * F[k], "pair %d sum %g", k, sf[d]);
            cr_assert(fabs(mo[d]) <= CTT_TOL(1e-13, 2e-5) * scale, "pair %d moment %g", k,
                      mo[d]);
        }
        /* A gets +F n in total. */
        double fa = fx[4 * k] + fx[4 * k + 1];
        cr_assert_float_eq(fa, F[k] * o.g.nx[k], CTT_TOL(1e-13, 1e-5));
    }
    egeo_free(&o);
}

Test(edge, gaps_per_edge_and_cap)
{
    egeo o;
    egeo_init(&o, 1);
    ct_real x[4] = {0, 1, 0.5, 0.5}, y[4] = {0, 0, -1, 1}, z[4] = {0.3, 0.3, 0, 0};
    ct_idx ea = 0, eb = 1, e1[2] = {0, 2}, e2[2] = {1, 3};
    ct_real ge[2] = {0.5, 0.1};
    cr_assert_eq(ct_narrow_edge_edge(1, &ea, &eb, e1, e2, x, y, z, ge, 0, (ct_real)0.25, &o.g,
                                     NULL),
                 CT_OK);
    cr_assert_float_eq(o.g.gap[0], 0.35, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.pen[0], 0.05, CTT_TOL(1e-14, 1e-6));
    egeo_free(&o);
}

Test(edge, degenerate_and_nonfinite)
{
    egeo o;
    egeo_init(&o, 1);
    double P[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, -1, 0.1}, {0, 1, 0.1}};
    one(P, 0.2, &o);
    cr_assert(o.g.flag[0] & CT_NARROW_DEGENERATE);
    cr_assert_eq(o.g.pen[0], 0);
    double Q[4][3] = {{0, 0, 0}, {1, 0, 0}, {NAN, -1, 0.1}, {0, 1, 0.1}};
    one(Q, 0.2, &o);
    cr_assert(o.g.flag[0] & CT_NARROW_NONFINITE);
    cr_assert_eq(o.g.pen[0], 0);
    ct_real v[] = {o.g.dist[0], o.g.nx[0], o.g.ny[0], o.g.nz[0], o.g.sa[0], o.g.sb[0],
                   o.g.pax[0],  o.g.pbx[0], o.g.gap[0]};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        cr_assert(isfinite(v[i]));
    egeo_free(&o);
}

/* Random edge pairs: nn nodes in the unit cube, edges (2 e, 2 e + 1), n
 * pairs over them (ct_free the six arrays). */
typedef struct epairs {
    ct_real *x, *y, *z;
    ct_idx *e1, *e2, *ea, *eb;
} epairs;

static epairs random_pairs(int n, int nn)
{
    epairs p;
    p.x = ct_calloc((size_t)nn, sizeof(ct_real));
    p.y = ct_calloc((size_t)nn, sizeof(ct_real));
    p.z = ct_calloc((size_t)nn, sizeof(ct_real));
    p.e1 = ct_calloc((size_t)nn / 2, sizeof(ct_idx));
    p.e2 = ct_calloc((size_t)nn / 2, sizeof(ct_idx));
    p.ea = ct_calloc((size_t)n, sizeof(ct_idx));
    p.eb = ct_calloc((size_t)n, sizeof(ct_idx));
    cr_assert(p.x && p.y && p.z && p.e1 && p.e2 && p.ea && p.eb);
    for (int i = 0; i < nn; i++) {
        p.x[i] = (ct_real)urand();
        p.y[i] = (ct_real)urand();
        p.z[i] = (ct_real)urand();
    }
    for (int e = 0; e < nn / 2; e++) {
        p.e1[e] = 2 * e;
        p.e2[e] = 2 * e + 1;
    }
    for (int k = 0; k < n; k++) {
        p.ea[k] = (ct_idx)(k % (nn / 2));
        p.eb[k] = (ct_idx)((k * 31 + 7) % (nn / 2));
    }
    return p;
}

static void epairs_free(epairs *p)
{
    ct_free(p->x);
    ct_free(p->y);
    ct_free(p->z);
    ct_free(p->e1);
    ct_free(p->e2);
    ct_free(p->ea);
    ct_free(p->eb);
}

Test(edge, threads_identical)
{
    int n = ctt_checking() ? 2000 : 20000, nn = 4000;
    epairs p = random_pairs(n, nn);
    ct_real *x = p.x, *y = p.y, *z = p.z;
    ct_idx *e1 = p.e1, *e2 = p.e2, *ea = p.ea, *eb = p.eb;
    egeo a, b;
    egeo_init(&a, n);
    egeo_init(&b, n);
    ctt_threads(1);
    ct_narrow_edge_edge(n, ea, eb, e1, e2, x, y, z, NULL, (ct_real)0.05, 0, &a.g, NULL);
    ctt_threads(2);
    ct_narrow_edge_edge(n, ea, eb, e1, e2, x, y, z, NULL, (ct_real)0.05, 0, &b.g, NULL);
    cr_assert_eq(memcmp(a.buf, b.buf, ((size_t)n + CT_PAD) * 14 * sizeof(ct_real)), 0);
    cr_assert_eq(memcmp(a.g.flag, b.g.flag, (size_t)n), 0);
    egeo_free(&a);
    egeo_free(&b);
    epairs_free(&p);
}

/* The closest points are optional: with all six arrays NULL the other
 * results are the same bits, and the points' memory is not written; one
 * NULL of the six is an argument error. */
Test(edge, closest_points_optional)
{
    const int n = 3000;
    epairs p = random_pairs(n, 400);
    egeo a, b;
    egeo_init(&a, n);
    egeo_init(&b, n);
    const size_t stride = (size_t)n + CT_PAD;
    for (size_t i = 0; i < 14 * stride; i++)
        b.buf[i] = 7; /* a sentinel the kernel must leave in the points */
    ct_real *pts[6] = {b.g.pax, b.g.pay, b.g.paz, b.g.pbx, b.g.pby, b.g.pbz};
    b.g.pax = b.g.pay = b.g.paz = b.g.pbx = b.g.pby = b.g.pbz = NULL;
    ct_narrow_stats sa, sb;
    cr_assert_eq(ct_narrow_edge_edge(n, p.ea, p.eb, p.e1, p.e2, p.x, p.y, p.z, NULL,
                                     (ct_real)0.05, 0, &a.g, &sa),
                 CT_OK);
    cr_assert_eq(ct_narrow_edge_edge(n, p.ea, p.eb, p.e1, p.e2, p.x, p.y, p.z, NULL,
                                     (ct_real)0.05, 0, &b.g, &sb),
                 CT_OK);
    cr_assert_gt(sa.active, 0);
    cr_assert_eq(sa.active, sb.active);
    const ct_real *ra[8] = {a.g.dist, a.g.pen, a.g.nx, a.g.ny, a.g.nz, a.g.sa, a.g.sb, a.g.gap};
    const ct_real *rb[8] = {b.g.dist, b.g.pen, b.g.nx, b.g.ny, b.g.nz, b.g.sa, b.g.sb, b.g.gap};
    for (int i = 0; i < 8; i++)
        cr_assert_eq(memcmp(ra[i], rb[i], (size_t)n * sizeof(ct_real)), 0, "array %d", i);
    cr_assert_eq(memcmp(a.g.flag, b.g.flag, (size_t)n), 0);
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < n; k++)
            cr_assert_eq(pts[i][k], 7, "point array %d written at pair %d", i, k);
    b.g.pbz = pts[5]; /* five NULL, one not */
    cr_assert_eq(ct_narrow_edge_edge(n, p.ea, p.eb, p.e1, p.e2, p.x, p.y, p.z, NULL,
                                     (ct_real)0.05, 0, &b.g, NULL),
                 CT_ERR_ARG);
    egeo_free(&a);
    egeo_free(&b);
    epairs_free(&p);
}

/* Lane independence: the same pairs shifted by one (so each lands in
 * another vector lane and block position, some in the scalar remainder)
 * give bit-identical results, nearly parallel and touching edges included. */
Test(edge, shifted_pairs_identical)
{
    int n = ctt_checking() ? 1000 : 5000, nn = 2000;
    ct_real *x = ct_calloc((size_t)nn, sizeof(ct_real)), *y = ct_calloc((size_t)nn, sizeof(ct_real)),
            *z = ct_calloc((size_t)nn, sizeof(ct_real));
    for (int i = 0; i < nn; i += 2) {
        x[i] = (ct_real)urand();
        y[i] = (ct_real)urand();
        z[i] = (ct_real)urand();
        /* Every fourth edge along x: parallel pairs among them. */
        int px = (i / 2) % 4 == 0;
        x[i + 1] = x[i] + (ct_real)(px ? 0.5 : urand() - 0.5);
        y[i + 1] = y[i] + (ct_real)(px ? 0 : urand() - 0.5);
        z[i + 1] = z[i] + (ct_real)(px ? 0 : urand() - 0.5);
    }
    ct_idx *e1 = ct_calloc((size_t)nn / 2, sizeof(ct_idx)), *e2 = ct_calloc((size_t)nn / 2, sizeof(ct_idx));
    for (int e = 0; e < nn / 2; e++) {
        e1[e] = 2 * e;
        e2[e] = 2 * e + 1;
    }
    ct_idx *ea = ct_calloc((size_t)n, sizeof(ct_idx)), *eb = ct_calloc((size_t)n, sizeof(ct_idx));
    for (int k = 0; k < n; k++) {
        ea[k] = (ct_idx)(k % (nn / 2));
        eb[k] = (ct_idx)((k * 13 + 5) % (nn / 2));
    }
    /* Some touching pairs: B's first end on A's middle. */
    for (int k = 0; k < n; k += 17) {
        ct_idx a = ea[k], b = eb[k];
        if (a == b)
            continue;
        x[e1[b]] = (ct_real)0.5 * (x[e1[a]] + x[e2[a]]);
        y[e1[b]] = (ct_real)0.5 * (y[e1[a]] + y[e2[a]]);
        z[e1[b]] = (ct_real)0.5 * (z[e1[a]] + z[e2[a]]);
    }
    egeo a, b;
    egeo_init(&a, n);
    egeo_init(&b, n);
    ct_narrow_stats st;
    cr_assert_eq(ct_narrow_edge_edge(n, ea, eb, e1, e2, x, y, z, NULL, (ct_real)0.05, 0, &a.g, &st),
                 CT_OK);
    cr_assert(st.active > 0);
    cr_assert_eq(ct_narrow_edge_edge(n - 1, ea + 1, eb + 1, e1, e2, x, y, z, NULL, (ct_real)0.05, 0,
                                     &b.g, NULL),
                 CT_OK);
    ct_real *fa[] = {a.g.dist, a.g.pen, a.g.nx, a.g.ny, a.g.nz, a.g.sa, a.g.sb,
                     a.g.pax, a.g.pay, a.g.paz, a.g.pbx, a.g.pby, a.g.pbz, a.g.gap};
    ct_real *fb[] = {b.g.dist, b.g.pen, b.g.nx, b.g.ny, b.g.nz, b.g.sa, b.g.sb,
                     b.g.pax, b.g.pay, b.g.paz, b.g.pbx, b.g.pby, b.g.pbz, b.g.gap};
    for (int f = 0; f < 14; f++)
        cr_assert_eq(memcmp(fa[f] + 1, fb[f], (size_t)(n - 1) * sizeof(ct_real)), 0, "field %d", f);
    cr_assert_eq(memcmp(a.g.flag + 1, b.g.flag, (size_t)(n - 1)), 0);
    egeo_free(&a);
    egeo_free(&b);
    ct_free(x); ct_free(y); ct_free(z); ct_free(e1); ct_free(e2); ct_free(ea); ct_free(eb);
}

/* ---- Non-finite inputs of the nodal forces (docs/fuzz F15) ------------------- */

static void fill_edge(ct_real **in, ct_idx n)
{
    for (ct_idx i = 0; i < n; i++) {
        in[0][i] = ntf_contact(i) ? ntf_val(i, 70, 1, 2) : (i % 8 == 3 ? -1 : 0);
        ntf_normal(i, 71, &in[1][i], &in[2][i], &in[3][i]);
        in[4][i] = ntf_val(i, 74, 0, 1);
        in[5][i] = ntf_val(i, 75, 0, 1);
    }
}

static int call_edge(ct_real **in, ct_real **out, ct_idx n, ct_diag *d)
{
    (void)d;
    return ct_edge_edge_forces(n, in[0], in[1], in[2], in[3], in[4], in[5], out[0], out[1],
                               out[2]);
}

static int zero_edge(ct_real **in, ct_real **out, ct_idx k)
{
    (void)in;
    return ntf_all_zero(out, 3, 4, k);
}

/* Each input, one bad entry at a time (test_nonfinite.h). A NaN or
 * negative magnitude (-inf too) gives no force, as before; +inf, which gave
 * none with CT_OK, is an error (this failed first before F15), and so is a
 * NaN or infinite normal or parameter, which gave NaN forces with CT_OK. */
Test(edge, nonfinite_forces_each_input)
{
    const ntf_case c = {"ct_edge_edge_forces", 6, 3, 4, {"fmag", "nx", "ny", "nz", "sa", "sb"},
                        1u, 1u, 0, fill_edge, call_edge, zero_edge};
    ntf_run(&c);
    /* A magnitude above the old clamp of 1e300 (single 3e38), which gave
     * no force, is a force; one that overflows at a node is an error. */
    ct_real F = (ct_real)CTT_TOL(1e308, 3.2e38), nx = 0, ny = 0, nz = 1, sa = 0.5, sb = 0.25;
    ct_real fx[4], fy[4], fz[4];
    cr_assert_eq(ct_edge_edge_forces(1, &F, &nx, &ny, &nz, &sa, &sb, fx, fy, fz), CT_OK);
    cr_assert(fz[0] == F / 2 && fz[1] == F / 2 && fz[3] == -(F / 4));
    sa = 3; /* a weight of -2 at A1: -2 F */
    cr_assert_eq(ct_edge_edge_forces(1, &F, &nx, &ny, &nz, &sa, &sb, fx, fy, fz),
                 CT_ERR_NONFINITE);
}
