/*
 * test_validation_extreme_scale.c -- validation extremes (issue 6) of the
 * number scales, end to end through the interface object (TYPE24):
 *  d. coordinates offset by 1e0 .. 1e6: the penetration and force error
 *     against the un-offset case, in this build's precision, and with the
 *     coordinates rounded to single precision (a single build stores
 *     them so): where single precision stops being accurate;
 *  e. elements of size 1e-6 and 1e3 in one model: the bucket and BSP
 *     searches find exactly the direct search's pairs, the interface gives
 *     the same forces with each, and they are K p on both scales.
 */
#include "test_util.h"
#include "test_validation.h"

#include <stdint.h>
#include <string.h>

#include "test_validation_extreme.h"

/* ---- d. Offset coordinates ---------------------------------------------------- */

static const ct_idx Q1[1] = {0}, Q2[1] = {1}, Q3[1] = {2}, Q4[1] = {3}, S4[1] = {4};

/* The unit plate [X0, X0+1]^2 at z = X0 (an oriented face, normal +z) and a
 * node at (X0+0.3, X0+0.4, X0-p): TYPE24 one-sided, gap 0, K. to_float:
 * round every coordinate through float first. Returns the force K q (its
 * z component) and the penetration q in *pen. */
static double offset_force(double X0, double p, double K, int to_float, double *pen)
{
    const double c[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.3, 0.4, -p}};
    nodes nd;
    nodes_init(&nd, 5);
    for (int i = 0; i < 5; i++) {
        double v[3];
        for (int a = 0; a < 3; a++) {
            v[a] = X0 + c[i][a];
            if (to_float)
                v[a] = (double)(float)v[a];
        }
        nd.x[i] = (ct_real)v[0];
        nd.y[i] = (ct_real)v[1];
        nd.z[i] = (ct_real)v[2];
    }
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 5;
    d.nseg = 1;
    d.n1 = Q1;
    d.n2 = Q2;
    d.n3 = Q3;
    d.n4 = Q4;
    d.nsec = 1;
    d.sec = S4;
    d.K = (ct_real)K;
    ctd_iface_cfg cfg = ctd_iface_default_cfg(24);
    cfg.two_sided = 0;
    cfg.gap = 0;
    cfg.VisS = 0;
    cfg.algo = CT_SEARCH_DIRECT;
    ctd_iface *it = make(&cfg, &d);
    ctd_iface_report rep;
    nodes_step(it, &nd, 0, 1e-6, &rep);
    double F = nd.fz[4];
    *pen = nd.pen[4];
    ctd_iface_destroy(it);
    nodes_free(&nd);
    return F;
}

/*
 * Offsets 10^(k/4), k = 0..24, plus the un-offset reference 0. The error is
 * |F(X0) - F(0)| / F(0) (and the same for the penetration). A coordinate
 * near X0 stored in float carries an absolute rounding of up to
 * X0 2^-24 ~ 6e-8 X0: against a penetration of 1e-3 that reaches 1 % at
 * X0 ~ 170, so single precision must lose 1 % between 30 and 1000 (the
 * rounding model) while double stays below 1e-6 up to 1e6 (2e-16 x 1e6 /
 * 1e-3 = 2e-7).
 */
Test(validation_extreme, offset_coordinates)
{
    const double p = 1e-3, K = 1e3;
    double pen0, penf0;
    const double F0 = offset_force(0, p, K, 0, &pen0);
    const double Ff0 = offset_force(0, p, K, 1, &penf0);
    cr_assert(fabs(F0 - K * p) <= CTT_TOL(1e-12, 1e-6) * K * p, "un-offset force %g", F0);
    cr_assert(fabs(pen0 - p) <= CTT_TOL(1e-12, 1e-6) * p);
    FILE *f = ctv_csv("extreme_offset", "offset,err_force_this_build,err_pen_this_build,"
                                        "err_force_float_coords,rounding_model");
    double worst = 0, cross_native = -1, cross_float = -1;
    for (int k = 0; k <= 24; k++) {
        double X0 = pow(10.0, k / 4.0), pen, penf;
        double F = offset_force(X0, p, K, 0, &pen);
        double Ff = offset_force(X0, p, K, 1, &penf);
        cr_assert(isfinite(F) && isfinite(Ff) && isfinite(pen));
        double e = fabs(F - F0) / F0, ep = fabs(pen - pen0) / pen0, ef = fabs(Ff - Ff0) / Ff0;
        double model = X0 * 5.96e-8 / p; /* half an ulp of X0 in float, over p */
        worst = fmax(worst, fmax(e, ep));
        if (cross_native < 0 && e > 0.01)
            cross_native = X0;
        if (cross_float < 0 && ef > 0.01)
            cross_float = X0;
        ctv_row(f, 5, X0, e, ep, ef, model);
    }
    if (f)
        fclose(f);
#ifdef CT_SINGLE
    /* Single: accurate near the origin, fails where rounding predicts. */
    cr_assert(cross_native >= 30 && cross_native <= 1000, "single loses 1 %% at %g",
              cross_native);
#else
    cr_assert(worst <= 1e-6, "double: worst offset error %g", worst);
    cr_assert(cross_native < 0);
#endif
    cr_assert(cross_float >= 30 && cross_float <= 1000, "float coordinates lose 1 %% at %g",
              cross_float);
    ctv_plot("extreme_offset",
             "Force of a 1e-3 penetration with every coordinate offset by X0",
             "offset X0", "relative error against X0 = 0",
             "1,2,linespoints,force (" CT_PRECISION_NAME " build);1,3,points,penetration ("
             CT_PRECISION_NAME " build);1,4,linespoints,force (coordinates rounded to float);"
             "1,5,dashed,rounding model X0 2^-24 / p",
             "logx logy");
    const char *note = "TYPE24 one-sided gap 0, unit quad, node 1e-3 behind it, "
                       "offsets 10^(k/4), k = 0..24; " CT_PRECISION_NAME " build";
    ctv_result("d. offset 1e6", "worst force/pen error up to 1e6, this build", worst, 0,
               CTT_SINGLE ? 0 : 1e-6, note);
    ctv_result("d. offset 1e6", "offset where float coordinates pass 1 % error", cross_float,
               170, 0, "reference: the rounding model 0.01 p / 2^-24 = 168");
    if (CTT_SINGLE)
        ctv_result("d. offset 1e6", "offset where the single build passes 1 % error",
                   cross_native, 170, 0, note);
}

/* ---- e. Elements of size 1e-6 and 1e3 in one model -------------------------------- */

/* A plate of n x n quads of size h with its corner at (ox, 0, 0), z = 0,
 * normal +z, appended at node `*nn` and segment `*ns`. */
static void add_plate(nodes *p, ct_idx *q[4], ct_idx *nn, ct_idx *ns, int n, double h,
                      double ox)
{
    ct_idx base = *nn;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            p->x[*nn] = (ct_real)(ox + i * h);
            p->y[*nn] = (ct_real)(j * h);
            p->z[*nn] = 0;
            (*nn)++;
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            ct_idx a = base + (ct_idx)(j * (n + 1) + i);
            q[0][*ns] = a;
            q[1][*ns] = a + 1;
            q[2][*ns] = a + 1 + (ct_idx)(n + 1);
            q[3][*ns] = a + (ct_idx)(n + 1);
            (*ns)++;
        }
}

/*
 * Two plates of 6 x 6 quads in one surface: cells of 1e-6 at the origin and
 * cells of 1e3 from x = 10. Secondary nodes over each plate (every cell
 * centre and corner at a fixed fraction of the cell): half 1e-3 cell
 * behind the face (penetration 1e-3 h), half 1e-3 cell in front (none).
 * The three complete searches must return identical pairs; the interface
 * must give the same forces with each, K p on both scales.
 */
Test(validation_extreme, mixed_scales)
{
    const int n = 6;
    const double hs = 1e-6, hb = 1e3, K = 1e3;
    const int nplate = (n + 1) * (n + 1), nsq = n * n;
    const ct_idx nsec = 2 * 2 * nsq;
    nodes p;
    nodes_init(&p, 2 * nplate + nsec);
    ct_idx *q[4];
    for (int a = 0; a < 4; a++)
        cr_assert((q[a] = ct_calloc((size_t)(2 * nsq), sizeof(ct_idx))) != NULL);
    ct_idx nn = 0, ns = 0;
    add_plate(&p, q, &nn, &ns, n, hs, 0);
    add_plate(&p, q, &nn, &ns, n, hb, 10);
    ct_idx *sec = ct_calloc((size_t)nsec, sizeof(ct_idx));
    double *pref = calloc((size_t)(2 * nplate + nsec), sizeof(double));
    cr_assert(sec && pref);
    ct_idx k = 0;
    for (int pl = 0; pl < 2; pl++) {
        double h = pl ? hb : hs, ox = pl ? 10 : 0;
        for (int c = 0; c < nsq; c++)
            for (int side = 0; side < 2; side++) {
                int i = c % n, j = c / n;
                double z = side ? 1e-3 * h : -1e-3 * h;
                p.x[nn] = (ct_real)(ox + (i + 0.37) * h);
                p.y[nn] = (ct_real)((j + 0.61) * h);
                p.z[nn] = (ct_real)z;
                pref[nn] = side ? 0 : -(double)p.z[nn];
                sec[k++] = nn++;
            }
    }
    /* The searches, pair for pair (no margin beyond the default 0.2 of the
     * mean edge, about 100 here, so every tiny node is a candidate of the
     * big plate's nearby segments as well). */
    ct_search_input in;
    memset(&in, 0, sizeof in);
    in.nnode = nn;
    in.x = p.x;
    in.y = p.y;
    in.z = p.z;
    in.nsec = nsec;
    in.sec = sec;
    in.nseg = ns;
    in.n1 = q[0];
    in.n2 = q[1];
    in.n3 = q[2];
    in.n4 = q[3];
    in.gap = 0;
    in.margin = (ct_real)(0.2 * (hs + hb) / 2);
    const ct_search_algo al[3] = {CT_SEARCH_DIRECT, CT_SEARCH_BUCKET, CT_SEARCH_BSP};
    ct_pairs pr[3];
    for (int a = 0; a < 3; a++) {
        ct_search *s = NULL;
        ct_search_params sp = ct_search_default_params(al[a]);
        cr_assert_eq(ct_search_init(&s, &sp), CT_OK);
        cr_assert_eq(ct_pairs_init(&pr[a], 0), CT_OK);
        cr_assert_eq(ct_search_run(s, &in, &pr[a]), CT_OK);
        ct_search_destroy(s);
    }
    cr_assert(pr[0].n > 0);
    for (int a = 1; a < 3; a++) {
        cr_assert_eq(pr[a].n, pr[0].n, "%s: %d pairs, direct %d", ct_search_algo_name(al[a]),
                     (int)pr[a].n, (int)pr[0].n);
        for (ct_idx i = 0; i < pr[0].n; i++)
            cr_assert(pr[a].node[i] == pr[0].node[i] && pr[a].seg[i] == pr[0].seg[i],
                      "%s: pair %d differs", ct_search_algo_name(al[a]), (int)i);
    }
    /* The interface with each search: identical forces, K p. */
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = nn;
    d.nseg = ns;
    d.n1 = q[0];
    d.n2 = q[1];
    d.n3 = q[2];
    d.n4 = q[3];
    d.nsec = nsec;
    d.sec = sec;
    d.K = (ct_real)K;
    ct_real *f0 = ct_calloc((size_t)nn, sizeof(ct_real));
    cr_assert(f0);
    double worst[2] = {0, 0};
    ct_idx act0 = 0;
    for (int a = 0; a < 3; a++) {
        ctd_iface_cfg c = ctd_iface_default_cfg(24);
        c.two_sided = 0;
        c.gap = 0;
        c.VisS = 0;
        c.algo = al[a];
        ctd_iface *it = make(&c, &d);
        ctd_iface_report rep;
        nodes_step(it, &p, 0, 1e-6, &rep);
        if (a == 0)
            act0 = rep.nactive;
        cr_assert_eq(rep.nactive, act0);
        cr_assert_eq(rep.nactive, 2 * nsq, "active %d, expected %d", (int)rep.nactive, 2 * nsq);
        for (ct_idx i = 0; i < nn; i++) {
            if (a == 0)
                f0[i] = p.fz[i];
            cr_assert(p.fz[i] == f0[i], "%s: node %d force differs from direct",
                      ct_search_algo_name(al[a]), (int)i);
        }
        for (ct_idx i = 2 * nplate; i < nn; i++) {
            double Fr = K * pref[i], e = fabs((double)p.fz[i] - Fr);
            cr_assert(p.fx[i] == 0 && p.fy[i] == 0);
            int big = i >= 2 * nplate + 2 * nsq;
            if (Fr > 0) {
                e /= Fr;
                worst[big] = fmax(worst[big], e);
                cr_assert(e <= CTT_TOL(1e-9, 1e-3), "node %d (%s cells): force %g, K p %g",
                          (int)i, big ? "1e3" : "1e-6", (double)p.fz[i], Fr);
            } else {
                cr_assert(p.fz[i] == 0, "node %d in front of its face has force %g", (int)i,
                          (double)p.fz[i]);
            }
        }
        ctd_iface_destroy(it);
    }
    const double npairs = (double)pr[0].n;
    for (int a = 0; a < 3; a++)
        ct_pairs_destroy(&pr[a]);
    const char *note = "TYPE24 one-sided gap 0, two 6x6 plates (cells 1e-6 and 1e3) in one "
                       "surface, 144 nodes, penetration 1e-3 cell; direct, bucket, bsp";
    ctv_result("e. sizes 1e-6 and 1e3", "bucket and bsp pairs = direct pairs (count)",
               npairs, npairs, 0, note);
    ctv_result("e. sizes 1e-6 and 1e3", "force vs K p, worst rel. error, 1e-6 cells", worst[0],
               0, CTT_TOL(1e-9, 1e-3), note);
    ctv_result("e. sizes 1e-6 and 1e3", "force vs K p, worst rel. error, 1e3 cells", worst[1],
               0, CTT_TOL(1e-9, 1e-3), note);
    ct_free(f0);
    ct_free(sec);
    free(pref);
    for (int a = 0; a < 4; a++)
        ct_free(q[a]);
    nodes_free(&p);
}
