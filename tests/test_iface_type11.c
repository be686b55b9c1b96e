/*
 * test_iface_type11.c -- TYPE11 edge-to-edge details beyond
 * test_iface.c's crossed rods (suite iface_type11): the nodal contact step
 * over the four edge nodes; the pair budget.
 */
#include <math.h>
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
    uint64_t st = 99;
    ct_idx e1[NE], e2[NE];
    ct_real gn[2 * NE];
    for (int e = 0; e < NE; e++) {
        double c[3], d[3], n2 = 0;
        for (int k = 0; k < 3; k++) {
            c[k] = 4 * ((double)(ctd_splitmix64(&st) >> 11) / 9007199254740992.0);
            d[k] = 2 * ((double)(ctd_splitmix64(&st) >> 11) / 9007199254740992.0) - 1;
            n2 += d[k] * d[k];
        }
        double s = 0.5 / sqrt(n2);
        tn_set(&t, 2 * e, c[0] - s * d[0], c[1] - s * d[1], c[2] - s * d[2]);
        tn_set(&t, 2 * e + 1, c[0] + s * d[0], c[1] + s * d[1], c[2] + s * d[2]);
        e1[e] = 2 * e;
        e2[e] = 2 * e + 1;
        gn[2 * e] = gn[2 * e + 1] = (ct_real)g;
    }
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
        ctd_iface_data d;
        memset(&d, 0, sizeof d);
        d.nnode = 2 * NE;
        d.nea = NE;
        d.ea1 = e1;
        d.ea2 = e2;
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
        tstep(it, &t, 0, 1e-6, &rep);
        const ctdi_epass *e = it->ep;
        static int got[NE][NE];
        memset(got, 0, sizeof got);
        for (ct_idx k = 0; k < e->n; k++) {
            cr_assert_lt(e->pa[k], e->pb[k]);
            if (k > 0)
                cr_assert(e->pa[k - 1] < e->pa[k] ||
                              (e->pa[k - 1] == e->pa[k] && e->pb[k - 1] < e->pb[k]),
                          "pair %d out of order", (int)k);
            got[e->pa[k]][e->pb[k]] = 1;
        }
        for (int a = 0; a < NE; a++)
            for (int b = a + 1; b < NE; b++)
                if (want[a][b] >= 0)
                    cr_expect_eq(got[a][b], want[a][b], "%s: edges %d %d", algo ? "bucket" :
                                 "direct", a, b);
        ctd_iface_destroy(it);
    }
    tn_free(&t);
}
