/*
 * test_iface_type11.c -- TYPE11 edge-to-edge details beyond
 * test_iface.c's crossed rods (suite iface_type11): the nodal contact step
 * over the four edge nodes; the pair budget; the filter against the test's
 * own distances; the bucket grid's pairs against the direct search's.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test_iface_util.h"
#include "interfaces/type11_internal.h"
#include "meshgen.h"

/* Edge A from (-1, 0, 0) to (1, 0, 0) and edge B across it at x = 0.5 from
 * (0.5, -1, h) to (0.5, 1, h), with the node gaps g: t gets the nodes, the
 * data is returned. */
static ctd_iface_data one_pair(tnodes *t, double h, const ct_real g[4])
{
    tn_init(t, 4);
    tn_set(t, 0, -1, 0, 0);
    tn_set(t, 1, 1, 0, 0);
    tn_set(t, 2, 0.5, -1, h);
    tn_set(t, 3, 0.5, 1, h);
    return edge_pair_data(g);
}

/* One pair: A from (-1, 0, 0) to (1, 0, 0), B across it at x = 0.5 from
 * (0.5, -1, h) to (0.5, 1, h), so the contact points are at sa = 0.75 and
 * sb = 0.5 and the weights are w = (0.25, 0.75, 0.5, 0.5). With masses
 * m = (1, 4, 2, 0.5) and no element stiffness, the rank-one contact
 * stiffness K w w^T has the largest frequency omega^2 = K sum w_i^2 / m_i
 * (= 0.828125 K), so the step is sqrt(2 / (0.828125 K)), limited by node 3
 * (the largest w_i^2 / m_i). The former estimate, sqrt(2 m_A1 / K) at A's
 * first node, was 1.29 times too long here. */
Test(iface_type11, nodal_step_over_the_four_edge_nodes)
{
    const double r = 0.1, h = 0.15, K0 = 1e3;
    tnodes t;
    ct_real g[4] = {(ct_real)r, (ct_real)r, (ct_real)r, (ct_real)r};
    ctd_iface_data d = one_pair(&t, h, g);
    const double mass[4] = {1, 4, 2, 0.5};
    for (int i = 0; i < 4; i++)
        t.m[i] = (ct_real)mass[i];
    ctd_iface_cfg cfg = ctd_iface_default_cfg(11);
    cfg.Istf = 1;
    cfg.Stfac = (ct_real)K0;
    cfg.VisS = 0;
    cfg.algo = CT_SEARCH_DIRECT;
    ctd_iface *it = NULL;
    ct_diag diag;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
    ctd_iface_report rep;
    tstep(it, &t, 0, 1e-4, &rep);
    cr_assert_eq(rep.nactive, 1);
    cr_assert(rep.kmax > 0);
    const double w[4] = {0.25, 0.75, 0.5, 0.5};
    double s = 0;
    for (int i = 0; i < 4; i++)
        s += w[i] * w[i] / mass[i];
    cr_assert(fabs(s - 0.828125) < 1e-15);
    double want = sqrt(2.0 / ((double)rep.kmax * s));
    cr_expect(fabs((double)rep.dt_nodal - want) <= CTT_TOL(1e-12, 1e-6) * want,
              "dt_nodal %.9g, expected %.9g", (double)rep.dt_nodal, want);
    cr_expect_eq(rep.dt_node, 3, "limiting node %lld", (long long)rep.dt_node);
    ctd_iface_destroy(it);
    tn_free(&t);
}

/* The pair budget (iface_reach.c) of the edge pass: the same single pair
 * fits a limit of exactly its arrays' bytes (1.5 x CTDI_EPAIR_BYTES) and
 * fails the step one byte below, with a message that says why. */
Test(iface_type11, pair_budget_stops_the_step)
{
    tnodes t;
    ct_real g[4] = {0.1, 0.1, 0.1, 0.1};
    ctd_iface_data d = one_pair(&t, 0.15, g);
    const double need = 1.5 * (double)CTDI_EPAIR_BYTES;
    for (int k = 0; k < 2; k++) {
        ctd_iface_cfg cfg = ctd_iface_default_cfg(11);
        cfg.Istf = 1;
        cfg.Stfac = 1e3;
        cfg.mem_limit = k == 0 ? need : need - 1;
        ctd_iface *it = NULL;
        ct_diag diag;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
        ctd_iface_report rep;
        int rc = ctd_iface_step(it, 0, 1e-4, t.x, t.y, t.z, t.vx, t.vy, t.vz, t.m, t.fx, t.fy,
                                t.fz, &rep);
        if (k == 0) {
            cr_assert_eq(rc, CT_OK, "%s", rep.msg);
            cr_assert_eq(rep.nactive, 1);
            cr_assert_eq(rep.msg[0], 0);
        } else {
            cr_assert_eq(rc, CT_ERR_NOMEM);
            cr_assert(strstr(rep.msg, "found 1 candidate pairs") &&
                          strstr(rep.msg, "the interface's memory limit"),
                      "%s", rep.msg);
        }
        ctd_iface_destroy(it);
    }
    tn_free(&t);
}

/* The distance of segments a0 a1 and b0 b1 by a golden-section search on
 * s of the distance from a(s) to segment b (convex in s): the test's own. */
static double seg_seg(const double a0[3], const double a1[3], const double b0[3],
                      const double b1[3])
{
    double lo = 0, hi = 1;
    const double g = 0.5 * (sqrt(5.0) - 1);
    for (int it = 0; it < 80; it++) {
        double s1 = hi - g * (hi - lo), s2 = lo + g * (hi - lo), p1[3], p2[3];
        for (int k = 0; k < 3; k++) {
            p1[k] = a0[k] + s1 * (a1[k] - a0[k]);
            p2[k] = a0[k] + s2 * (a1[k] - a0[k]);
        }
        if (ctt_point_seg_dist(p1, b0, b1) < ctt_point_seg_dist(p2, b0, b1))
            hi = s2;
        else
            lo = s1;
    }
    double p[3];
    for (int k = 0; k < 3; k++)
        p[k] = a0[k] + 0.5 * (lo + hi) * (a1[k] - a0[k]);
    return fmin(ctt_point_seg_dist(p, b0, b1),
                fmin(ctt_point_seg_dist(a0, b0, b1), ctt_point_seg_dist(a1, b0, b1)));
}

/* The candidate pairs of one step of a TYPE11 interface over the edges
 * ea (and eb unless neb is 0: self), with the direct search (algo 0) or the
 * bucket grid (1): n and the pairs (a, b), after the filter. The caller
 * frees *pa and *pb. qbuf receives whether the bucket query took its
 * one-pass way (room for its candidates in qbuf) rather than two passes. */
static ct_idx edge_pairs(tnodes *t, const ct_real *gn, ct_idx nea, const ct_idx *ea1,
                         const ct_idx *ea2, ct_idx neb, const ct_idx *eb1, const ct_idx *eb2,
                         double margin, int algo, ct_idx **pa, ct_idx **pb, int *qbuf)
{
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = t->n;
    d.nea = nea;
    d.ea1 = ea1;
    d.ea2 = ea2;
    d.neb = neb;
    d.eb1 = eb1;
    d.eb2 = eb2;
    d.gap_node = gn;
    ctd_iface_cfg cfg = ctd_iface_default_cfg(11);
    cfg.Istf = 1;
    cfg.Stfac = 1e3;
    cfg.margin = (ct_real)margin;
    cfg.algo = algo ? CT_SEARCH_BUCKET : CT_SEARCH_DIRECT;
    ctd_iface *it = NULL;
    ct_diag diag;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
    ctd_iface_report rep;
    tstep(it, t, 0, 1e-6, &rep);
    const ctdi_epass *e = it->ep;
    const ct_idx n = e->n;
    *pa = malloc(sizeof(ct_idx) * ((size_t)n + 1));
    *pb = malloc(sizeof(ct_idx) * ((size_t)n + 1));
    cr_assert(*pa && *pb);
    memcpy(*pa, e->pa, sizeof(ct_idx) * (size_t)n);
    memcpy(*pb, e->pb, sizeof(ct_idx) * (size_t)n);
    *qbuf = e->cap_qbuf > 0;
    ctd_iface_destroy(it);
    return n;
}

/* 2 ne nodes and ne edges of length 1 (edge e from node 2 e to 2 e + 1),
 * centred at random in [0, side]^3 and turned at random (seed), node gaps
 * gap. */
static void random_edges(tnodes *t, int ne, double side, uint64_t seed, double gap, ct_idx *e1,
                         ct_idx *e2, ct_real *gn)
{
    uint64_t st = seed;
    for (int e = 0; e < ne; e++) {
        double c[3], d[3], n2 = 0;
        for (int k = 0; k < 3; k++) {
            c[k] = side * ((double)(ctd_splitmix64(&st) >> 11) / 9007199254740992.0);
            d[k] = 2 * ((double)(ctd_splitmix64(&st) >> 11) / 9007199254740992.0) - 1;
            n2 += d[k] * d[k];
        }
        const double s = 0.5 / sqrt(n2);
        tn_set(t, 2 * e, c[0] - s * d[0], c[1] - s * d[1], c[2] - s * d[2]);
        tn_set(t, 2 * e + 1, c[0] + s * d[0], c[1] + s * d[1], c[2] + s * d[2]);
        e1[e] = 2 * e;
        e2[e] = 2 * e + 1;
        gn[2 * e] = gn[2 * e + 1] = (ct_real)gap;
    }
}

/* The search lists the pairs whose inflated boxes overlap, a superset; the
 * filter (type11_filter.c) keeps exactly the pairs within their gap and the
 * margin. Random unconnected edges: the kept pairs against the test's own
 * distances, for the direct and the bucket search. */
Test(iface_type11, filter_keeps_the_pairs_within_gap_and_margin)
{
    enum { NE = 160 };
    const double g = 0.1, margin = 0.15, reach = 2 * g + margin;
    tnodes t;
    tn_init(&t, 2 * NE);
    ct_idx e1[NE], e2[NE];
    ct_real gn[2 * NE];
    random_edges(&t, NE, 4, 99, g, e1, e2, gn);
    /* The truth, leaving out the pairs within 1e-6 of the reach. */
    static int want[NE][NE];
    int nwant = 0;
    for (int a = 0; a < NE; a++)
        for (int b = a + 1; b < NE; b++) {
            double a0[3] = {t.x[e1[a]], t.y[e1[a]], t.z[e1[a]]};
            double a1[3] = {t.x[e2[a]], t.y[e2[a]], t.z[e2[a]]};
            double b0[3] = {t.x[e1[b]], t.y[e1[b]], t.z[e1[b]]};
            double b1[3] = {t.x[e2[b]], t.y[e2[b]], t.z[e2[b]]};
            double d = seg_seg(a0, a1, b0, b1);
            want[a][b] = fabs(d - reach) < 1e-6 ? -1 : d <= reach;
            nwant += want[a][b] == 1;
        }
    cr_assert_gt(nwant, 20);
    for (int algo = 0; algo < 2; algo++) {
        ct_idx *pa, *pb;
        int qb;
        const ct_idx n = edge_pairs(&t, gn, NE, e1, e2, 0, NULL, NULL, margin, algo, &pa, &pb, &qb);
        static int got[NE][NE];
        memset(got, 0, sizeof got);
        for (ct_idx k = 0; k < n; k++) {
            cr_assert_lt(pa[k], pb[k]);
            if (k > 0)
                cr_assert(pa[k - 1] < pa[k] || (pa[k - 1] == pa[k] && pb[k - 1] < pb[k]),
                          "pair %d out of order", (int)k);
            got[pa[k]][pb[k]] = 1;
        }
        for (int a = 0; a < NE; a++)
            for (int b = a + 1; b < NE; b++)
                if (want[a][b] >= 0)
                    cr_expect_eq(got[a][b], want[a][b], "%s: edges %d %d", algo ? "bucket" :
                                 "direct", a, b);
        free(pa);
        free(pb);
    }
    tn_free(&t);
}

/* The bucket grid's pairs (after the filter) are the direct search's, in the
 * same order, and more than 100 (what: the case, for the messages).
 * Returns whether the bucket query took its one-pass way. */
static int bucket_equals_direct(tnodes *t, const ct_real *gn, ct_idx nea, const ct_idx *ea1,
                                const ct_idx *ea2, ct_idx neb, const ct_idx *eb1,
                                const ct_idx *eb2, double margin, const char *what)
{
    ct_idx *pa[2], *pb[2];
    int qb[2];
    ct_idx n[2];
    for (int algo = 0; algo < 2; algo++)
        n[algo] = edge_pairs(t, gn, nea, ea1, ea2, neb, eb1, eb2, margin, algo, &pa[algo],
                             &pb[algo], &qb[algo]);
    cr_assert_gt(n[0], 100, "%s: %d pairs", what, (int)n[0]);
    cr_assert_eq(n[1], n[0], "%s", what);
    cr_assert(memcmp(pa[1], pa[0], sizeof(ct_idx) * (size_t)n[0]) == 0, "%s", what);
    cr_assert(memcmp(pb[1], pb[0], sizeof(ct_idx) * (size_t)n[0]) == 0, "%s", what);
    for (int algo = 0; algo < 2; algo++)
        free(pa[algo]), free(pb[algo]);
    return qb[1];
}

/* The bucket grid's pairs are the direct search's, in the same order, on
 * three layers of a wavy grid of edges sharing their nodes (self contact,
 * and the top layer against the two below), and on a cluster of long
 * edges that puts hundreds in every cell (the query's two-pass way). */
Test(iface_type11, bucket_pairs_equal_direct_on_layers_and_a_cluster)
{
    enum { G = 24, L = 3, NN = G * G * L, NE = 2 * G * (G - 1) * L };
    const double h = 1, gap = 0.15 * h, margin = 0.2 * h;
    tnodes t;
    tn_init(&t, NN);
    static ct_real gn[NN];
    for (int l = 0; l < L; l++)
        for (int i = 0; i < G; i++)
            for (int j = 0; j < G; j++) {
                const ct_idx v = (l * G + i) * G + j;
                /* Layers 0.35 h apart, waved so that they cross the gap
                 * in places. */
                const double w = 0.12 * h * sin(0.7 * i + 1.3 * l) * cos(0.5 * j);
                tn_set(&t, v, i * h, j * h, 0.35 * h * l + w);
                gn[v] = (ct_real)gap;
            }
    static ct_idx e1[NE], e2[NE];
    ct_idx ne = 0, nlow = 0;
    for (int l = 0; l < L; l++) {
        for (int i = 0; i < G; i++)
            for (int j = 0; j < G; j++) {
                const ct_idx v = (l * G + i) * G + j;
                if (i + 1 < G)
                    e1[ne] = v, e2[ne++] = v + G;
                if (j + 1 < G)
                    e1[ne] = v, e2[ne++] = v + 1;
            }
        if (l == L - 2)
            nlow = ne;
    }
    cr_assert_eq(ne, NE);
    for (int sets = 0; sets < 2; sets++) {
        /* sets 0: all edges against themselves; 1: the two lower layers
         * (A) against the top one (B). */
        const ct_idx nea = sets ? nlow : NE, neb = sets ? NE - nlow : 0;
        cr_assert(bucket_equals_direct(&t, gn, nea, e1, e2, neb, e1 + nea, e2 + nea, margin,
                                       sets ? "two sets" : "self"),
                  "sets %d: the one-pass query", sets);
    }
    tn_free(&t);
    /* The cluster: 600 edges of length 1 in a box of side 1.5. */
    enum { NC = 600 };
    tn_init(&t, 2 * NC);
    static ct_real gc[2 * NC];
    static ct_idx c1[NC], c2[NC];
    random_edges(&t, NC, 1.5, 7, 0.01, c1, c2, gc);
    cr_assert(!bucket_equals_direct(&t, gc, NC, c1, c2, 0, NULL, NULL, 0.02, "cluster"),
              "cluster: the two-pass query");
    tn_free(&t);
}
