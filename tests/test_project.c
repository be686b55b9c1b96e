/*
 * test_project.c -- node-segment narrow phase (suite "project") against
 * independent answers: dense sampling plus a local minimisation written
 * here (coordinate descent, each 1-D step a bisection on the analytic
 * derivative), brute-force sampling of triangles, and hand-computed cases.
 * The reference computations are in double in both builds.
 */
#include <stdio.h>
#include <string.h>

#include "test_geo.h"
#include "test_project.h"

/* ---- A small harness: one segment set, many pairs ---------------------- */

/* One pair: node 0 at p against the segment of nodes 1..4 (a triangle when
 * tri != 0, using n4 = n3). */
static void one(ct_quad_method m, int two, const double X[4][3], const double p[3],
                double gap, int tri, ctt_geo *o)
{
    ct_real x[5], y[5], z[5];
    x[0] = (ct_real)p[0]; y[0] = (ct_real)p[1]; z[0] = (ct_real)p[2];
    for (int i = 0; i < 4; i++) {
        x[i + 1] = (ct_real)X[i][0];
        y[i + 1] = (ct_real)X[i][1];
        z[i + 1] = (ct_real)X[i][2];
    }
    ct_idx node = 0, seg = 0, n1 = 1, n2 = 2, n3 = 3, n4 = tri ? 3 : 4;
    int rc = ct_narrow_node_segment(1, &node, &seg, &n1, &n2, &n3, &n4, x, y, z, NULL, NULL,
                                    (ct_real)gap, 0, 0, m, two, &o->g, NULL);
    cr_assert_eq(rc, CT_OK);
}

/* A point near the quad: (s, t) in [-1.6, 1.6]^2, then off the surface
 * along its normal by h in [-0.4, 0.4] L (above, below, beyond edges and
 * corners). */
static void rand_point(const double X[4][3], double L, double p[3])
{
    double s = 3.2 * urand() - 1.6, t = 3.2 * urand() - 1.6, x[3], a[3], b[3];
    bil(X, s, t, x, a, b);
    double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                   a[0] * b[1] - a[1] * b[0]};
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double h = L * (0.8 * urand() - 0.4);
    for (int d = 0; d < 3; d++)
        p[d] = x[d] + h * n[d] / nl;
}

static double dist3(const double a[3], double bx, double by, double bz)
{
    return sqrt((a[0] - bx) * (a[0] - bx) + (a[1] - by) * (a[1] - by) +
                (a[2] - bz) * (a[2] - bz));
}

/* Outputs always finite, weights summing to 1 and reproducing the point. */
static void check_consistent(const ctt_geo *o, const double X[4][3], const double p[3], int tri)
{
    const ct_contact_geo *g = &o->g;
    double h[4] = {g->h1[0], g->h2[0], g->h3[0], g->h4[0]};
    cr_assert(isfinite(g->dist[0]) && isfinite(g->pen[0]) && isfinite(g->nx[0]) &&
              isfinite(g->ny[0]) && isfinite(g->nz[0]));
    cr_assert_float_eq(h[0] + h[1] + h[2] + h[3], 1.0, CTT_TOL(1e-13, 1e-5));
    if (tri)
        cr_assert_eq(h[3], 0);
    for (int d = 0; d < 3; d++) {
        double c = h[0] * X[0][d] + h[1] * X[1][d] + h[2] * X[2][d] + h[3] * X[3][d];
        double cd = d == 0 ? g->cx[0] : (d == 1 ? g->cy[0] : g->cz[0]);
        cr_assert_float_eq(c, cd, CTT_TOL(1e-12, 1e-5));
    }
    double nl = sqrt(g->nx[0] * g->nx[0] + g->ny[0] * g->ny[0] + g->nz[0] * g->nz[0]);
    cr_assert_float_eq(nl, 1.0, CTT_TOL(1e-13, 1e-6));
    cr_assert_float_eq(fabs(g->dist[0]), dist3(p, g->cx[0], g->cy[0], g->cz[0]),
                       CTT_TOL(1e-13, 1e-6));
}

Test(project, newton_matches_dense_search_on_warped_quads)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    double err[3] = {0, 0, 0};
    int nq = ctt_checking() ? 8 : 40, np = 12;
    for (int q = 0; q < nq; q++) {
        double X[4][3];
        rand_quad(X, 0.12, 1.0 + q * 0.1);
        for (int k = 0; k < np; k++) {
            double p[3], c[3], d;
            rand_point(X, 1.0, p);
            truth_quad(X, p, c, &d);
            for (int m = 0; m < 3; m++) {
                one((ct_quad_method)m, 1, X, p, 0.01, 0, &o);
                check_consistent(&o, X, p, 0);
                double e = fabs(o.g.dist[0] - d);
                if (m == CT_QUAD_NEWTON) {
                    /* Newton: the exact answer (single: the rounding of the
                     * inputs and of the iteration). */
                    cr_assert_float_eq(o.g.dist[0], d, CTT_TOL(1e-10, 5e-5), "q %d k %d", q, k);
                    cr_assert(dist3(c, o.g.cx[0], o.g.cy[0], o.g.cz[0]) <= CTT_TOL(1e-10, 5e-4),
                              "q %d k %d: point off by %g", q, k,
                              dist3(c, o.g.cx[0], o.g.cy[0], o.g.cz[0]));
                    cr_assert_eq(o.g.flag[0] & CT_NARROW_FALLBACK, 0);
                }
                /* Every method's surface is never closer than the true one
                 * by more than the warp allows; the error is reported. */
                err[m] = fmax(err[m], e);
            }
        }
    }
    cr_log_info("max |D - D_true| on warped quads (warp 0.12 L): 4tri %.3e newton %.3e closed %.3e",
                err[0], err[1], err[2]);
    printf("project: max |D - D_true| on warped quads: 4tri %.3e newton %.3e closed %.3e\n",
           err[0], err[1], err[2]);
    cr_assert(isfinite(err[0]) && isfinite(err[2]));
    ctt_geo_free(&o);
}

/* Newton over a batch of pairs, as the vector loop sees them: warped quads
 * and nodes up to 1.2 L off the surface, far beyond the edges too, so that
 * some pairs need more than the vector loop's fixed number of iterations
 * and are finished by the further rounds (newton_redo), a few hitting the
 * cap. Every pair against the dense
 * search. */
Test(project, newton_batch_with_far_nodes_matches_dense_search)
{
    int nq = ctt_checking() ? 6 : 24, np = 16, npair = nq * np;
    ct_real *x = ct_calloc((size_t)(5 * npair), sizeof(ct_real));
    ct_real *y = ct_calloc((size_t)(5 * npair), sizeof(ct_real));
    ct_real *z = ct_calloc((size_t)(5 * npair), sizeof(ct_real));
    ct_idx *node = ct_calloc((size_t)npair, sizeof(ct_idx)), *seg = ct_calloc((size_t)npair, sizeof(ct_idx));
    ct_idx *n1 = ct_calloc((size_t)nq, sizeof(ct_idx)), *n2 = ct_calloc((size_t)nq, sizeof(ct_idx));
    ct_idx *n3 = ct_calloc((size_t)nq, sizeof(ct_idx)), *n4 = ct_calloc((size_t)nq, sizeof(ct_idx));
    double (*X)[4][3] = malloc(sizeof(double[4][3]) * (size_t)nq);
    double (*P)[3] = malloc(sizeof(double[3]) * (size_t)npair);
    for (int q = 0; q < nq; q++) {
        rand_quad(X[q], 0.2, 1.0 + 0.05 * q);
        for (int i = 0; i < 4; i++) {
            x[4 * q + i] = (ct_real)X[q][i][0];
            y[4 * q + i] = (ct_real)X[q][i][1];
            z[4 * q + i] = (ct_real)X[q][i][2];
        }
        n1[q] = 4 * q;
        n2[q] = 4 * q + 1;
        n3[q] = 4 * q + 2;
        n4[q] = 4 * q + 3;
    }
    for (int k = 0; k < npair; k++) {
        int q = k / np;
        double s = 6 * urand() - 3, t = 6 * urand() - 3, c[3], a[3], b[3];
        bil(X[q], s, t, c, a, b);
        double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
        double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double h = 2.4 * urand() - 1.2;
        for (int d = 0; d < 3; d++)
            P[k][d] = c[d] + h * n[d] / nl;
        ct_idx i = 4 * nq + k;
        x[i] = (ct_real)P[k][0];
        y[i] = (ct_real)P[k][1];
        z[i] = (ct_real)P[k][2];
        node[k] = i;
        seg[k] = (ct_idx)q;
    }
    ctt_geo o;
    ctt_geo_init(&o, npair);
    cr_assert_eq(ct_narrow_node_segment(npair, node, seg, n1, n2, n3, n4, x, y, z, NULL, NULL,
                                        (ct_real)0.01, 0, 0, CT_QUAD_NEWTON, 1, &o.g, NULL),
                 CT_OK);
    for (int k = 0; k < npair; k++) {
        /* The reference takes the rounded inputs of the single build. */
        double Xr[4][3], pr[3] = {x[node[k]], y[node[k]], z[node[k]]}, c[3], d;
        int q = k / np;
        for (int i = 0; i < 4; i++) {
            Xr[i][0] = x[4 * q + i];
            Xr[i][1] = y[4 * q + i];
            Xr[i][2] = z[4 * q + i];
        }
        truth_quad(Xr, pr, c, &d);
        cr_assert_float_eq(o.g.dist[k], d, CTT_TOL(1e-10, 5e-5), "pair %d", k);
        cr_assert(dist3(c, o.g.cx[k], o.g.cy[k], o.g.cz[k]) <= CTT_TOL(1e-10, 5e-4),
                  "pair %d: point off by %g", k, dist3(c, o.g.cx[k], o.g.cy[k], o.g.cz[k]));
        cr_assert_eq(o.g.flag[k] & (CT_NARROW_FALLBACK | CT_NARROW_DEGENERATE), 0);
    }
    ctt_geo_free(&o);
    free(X);
    free(P);
    ct_free(x); ct_free(y); ct_free(z); ct_free(node); ct_free(seg);
    ct_free(n1); ct_free(n2); ct_free(n3); ct_free(n4);
}

/* Nodes whose Newton iterate leaves the square by more than
 * CTI_NR_NEWTON_FAR (kernels/narrow_internal.h) and comes back to the
 * nearest point, inside: strongly warped quadrangles (a corner lifted by
 * about the quadrangle's size), found by a random search. The iterations
 * of a far iterate may end only where the interior cannot beat the
 * boundary; ending them on the distance alone gave the boundary here,
 * 0.0004 to 0.04 farther. Each case alone (its block takes the second
 * fixed loop) and in a block of nodes that converge at once (it goes to the
 * rounds from step 2), against the dense search. */
Test(project, newton_iterate_that_leaves_the_square_and_comes_back)
{
    static const double C[][5][3] = {
        {{0.095535358503886211, 0.075940254107380298, -0.12709048314133087},
         {0.9432114134866717, -0.053684904353022443, 0.066025454120059446},
         {1.143430745470793, 0.93845457275885946, -1.1716514811737087},
         {0.10166635061036507, 0.85415904039853474, 1.1982012986497257},
         {0.54742219113944746, 0.18824097892477654, -0.67050196965546061}},
        {{-0.11929564336333531, 0.072910077514325614, 1.2720425791730006},
         {1.12876205648529, -0.07698065676039581, 0.8722685811282489},
         {0.90497914541440438, 0.88511742023922679, 1.0376501277349799},
         {0.093798577339251815, 1.096440996233327, -1.0007884921022114},
         {0.031411838053859498, 0.93096221042418126, 0.035529970189610571}},
        {{0.1462625289345679, 0.034907960791679446, -1.159375342814337},
         {0.96754098540480338, -0.10458492326078912, 0.53216539106064664},
         {0.9412475761280279, 0.8503252051895881, -0.81822718031181374},
         {-0.10811372026423043, 1.0217110735232411, 0.12183820687900115},
         {0.29072753882573688, 0.8015765209883845, -0.67859326393972563}},
        {{0.147717171558332, -0.072565698879427334, -0.42992519689276176},
         {1.1308220641073345, 0.1316471341908185, 0.49474629481094712},
         {0.94298346973353586, 0.89689041459639429, -0.45850476245496929},
         {-0.1470452903872205, 0.95817195964053015, 0.16235308924869596},
         {0.61431593046553146, 0.74184721968753409, 0.76950789647029927}},
        {{-0.032549415743435513, -0.082005082327190351, 0.47404262479023507},
         {0.89526963184397379, -0.083259134057116116, -0.43243873743299155},
         {1.0243351147336028, 0.9426524483427221, 0.31967039294574229},
         {0.071250615505703788, 0.99851397654779184, -0.10010803591265427},
         {-0.020880460587320737, 0.22875872356439975, -0.72764241053690992}},
    };
    enum { NB = 64, AT = 5 };
    ctt_geo o;
    ctt_geo_init(&o, NB);
    for (size_t c = 0; c < sizeof C / sizeof C[0]; c++) {
        /* Nodes 0-3 the warped quadrangle, 4-7 a flat one, 8.. the nodes. */
        ct_real x[8 + NB], y[8 + NB], z[8 + NB];
        double Xr[4][3], pr[3], cp[3], d;
        for (int i = 0; i < 4; i++) {
            x[i] = (ct_real)C[c][i][0], y[i] = (ct_real)C[c][i][1], z[i] = (ct_real)C[c][i][2];
            Xr[i][0] = x[i], Xr[i][1] = y[i], Xr[i][2] = z[i];
            x[4 + i] = (ct_real)(i == 1 || i == 2), y[4 + i] = (ct_real)(i >= 2), z[4 + i] = 0;
        }
        ct_idx n1[2] = {0, 4}, n2[2] = {1, 5}, n3[2] = {2, 6}, n4[2] = {3, 7};
        ct_idx node[NB], seg[NB];
        for (int k = 0; k < NB; k++) {
            x[8 + k] = (ct_real)(0.1 + 0.8 * urand()), y[8 + k] = (ct_real)(0.1 + 0.8 * urand());
            z[8 + k] = (ct_real)0.05;
            node[k] = 8 + k;
            seg[k] = 1;
        }
        x[8 + AT] = (ct_real)C[c][4][0], y[8 + AT] = (ct_real)C[c][4][1];
        z[8 + AT] = (ct_real)C[c][4][2];
        seg[AT] = 0;
        pr[0] = x[8 + AT], pr[1] = y[8 + AT], pr[2] = z[8 + AT];
        truth_quad(Xr, pr, cp, &d);
        for (int alone = 0; alone < 2; alone++) {
            ct_idx np = alone ? 1 : NB;
            ct_idx *nd = alone ? node + AT : node, *sg = alone ? seg + AT : seg;
            int k = alone ? 0 : AT;
            cr_assert_eq(ct_narrow_node_segment(np, nd, sg, n1, n2, n3, n4, x, y, z, NULL, NULL,
                                                (ct_real)0.01, 0, 0, CT_QUAD_NEWTON, 1, &o.g,
                                                NULL),
                         CT_OK);
            cr_assert_float_eq(fabs(o.g.dist[k]), d, CTT_TOL(1e-10, 5e-5),
                               "case %zu (alone %d): D %.12g, the dense search %.12g", c, alone,
                               (double)o.g.dist[k], d);
            cr_assert(dist3(cp, o.g.cx[k], o.g.cy[k], o.g.cz[k]) <= CTT_TOL(1e-9, 5e-4),
                      "case %zu (alone %d): point off by %g", c, alone,
                      dist3(cp, o.g.cx[k], o.g.cy[k], o.g.cz[k]));
        }
    }
    ctt_geo_free(&o);
}


Test(project, all_methods_exact_on_flat_parallelograms)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    for (int q = 0; q < 20; q++) {
        /* A skewed, rotated, flat parallelogram. */
        double u[3] = {1 + urand(), 0.3 * urand(), 0.2 * urand()};
        double v[3] = {0.6 * urand() - 0.3, 0.8 + urand(), 0.3 * urand() - 0.15};
        double o0[3] = {urand(), urand(), urand()};
        double X[4][3];
        for (int d = 0; d < 3; d++) {
            X[0][d] = o0[d] - u[d] - v[d];
            X[1][d] = o0[d] + u[d] - v[d];
            X[2][d] = o0[d] + u[d] + v[d];
            X[3][d] = o0[d] - u[d] + v[d];
        }
        for (int k = 0; k < 15; k++) {
            double p[3], c[3], d;
            rand_point(X, 1.0, p);
            truth_quad(X, p, c, &d);
            for (int m = 0; m < 3; m++) {
                one((ct_quad_method)m, 1, X, p, 0.01, 0, &o);
                cr_assert_float_eq(o.g.dist[0], d, CTT_TOL(1e-12, 2e-5), "m %d q %d k %d", m, q,
                                   k);
                cr_assert(dist3(c, o.g.cx[0], o.g.cy[0], o.g.cz[0]) <= CTT_TOL(1e-11, 2e-4),
                          "m %d q %d k %d: point off by %g", m, q, k,
                          dist3(c, o.g.cx[0], o.g.cy[0], o.g.cz[0]));
            }
        }
    }
    ctt_geo_free(&o);
}

Test(project, triangle_against_brute_force_sampling)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    int N = ctt_checking() ? 150 : 400;
    for (int q = 0; q < 12; q++) {
        double X[4][3];
        for (int i = 0; i < 3; i++)
            for (int d = 0; d < 3; d++)
                X[i][d] = 2 * urand() - 1;
        X[3][0] = X[2][0]; X[3][1] = X[2][1]; X[3][2] = X[2][2];
        for (int k = 0; k < 6; k++) {
            double p[3] = {3 * urand() - 1.5, 3 * urand() - 1.5, 3 * urand() - 1.5};
            double best = 1e300;
            for (int i = 0; i <= N; i++)
                for (int j = 0; i + j <= N; j++) {
                    double a = (double)i / N, b = (double)j / N, x[3];
                    for (int d = 0; d < 3; d++)
                        x[d] = X[0][d] + a * (X[1][d] - X[0][d]) + b * (X[2][d] - X[0][d]);
                    double dd = dist3(p, x[0], x[1], x[2]);
                    best = dd < best ? dd : best;
                }
            /* Covering radius of the sample grid: half the longest grid
             * cell diagonal. */
            double L = 0;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    L = fmax(L, dist3(X[i], X[j][0], X[j][1], X[j][2]));
            one(CT_QUAD_4TRI, 1, X, p, 0.0, 1, &o);
            check_consistent(&o, X, p, 1);
            double D = o.g.dist[0];
            cr_assert(D <= best + CTT_TOL(1e-12, 1e-5), "q %d: D %g > sampled %g", q, D, best);
            cr_assert(D >= best - 2 * L / N, "q %d: D %g << sampled %g", q, D, best);
            cr_assert(o.g.h1[0] >= 0 && o.g.h2[0] >= 0 && o.g.h3[0] >= 0);
        }
    }
    ctt_geo_free(&o);
}

/* Two segments sharing the edge x = 0, flat or folded into a ridge; a node
 * whose closest point is on the shared edge or at its end vertex (above the
 * ridge; below only when flat: under a fold each segment has its own foot,
 * and a node on the surface gets each segment's own normal). */
Test(project, shared_edge_and_vertex_same_answer)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    for (int fold = 0; fold < 3; fold++) {
        double f = 0.3 * fold;
        double A[4][3] = {{-1, -1, -f}, {0, -1, 0}, {0, 1, 0}, {-1, 1, -f}};
        double B[4][3] = {{0, -1, 0}, {1, -1, -f}, {1, 1, -f}, {0, 1, 0}};
        double pts[3][3] = {{0, 0.3, 0.2}, {0, -1, 0.15}, {0, 1, -0.1}};
        for (int m = 0; m < 3; m++)
            for (int two = 0; two < 2; two++)
                for (int k = 0; k < 3; k++) {
                    if (k == 2 && fold > 0)
                        continue;
                    one((ct_quad_method)m, two, A, pts[k], 0.25, 0, &o);
                    double da = o.g.dist[0], pa = o.g.pen[0];
                    double na[3] = {o.g.nx[0], o.g.ny[0], o.g.nz[0]};
                    one((ct_quad_method)m, two, B, pts[k], 0.25, 0, &o);
                    cr_assert_float_eq(da, o.g.dist[0], CTT_TOL(1e-14, 1e-6), "m %d k %d", m, k);
                    cr_assert_float_eq(pa, o.g.pen[0], CTT_TOL(1e-14, 1e-6));
                    cr_assert_float_eq(na[0], o.g.nx[0], CTT_TOL(1e-12, 1e-5));
                    cr_assert_float_eq(na[1], o.g.ny[0], CTT_TOL(1e-12, 1e-5));
                    cr_assert_float_eq(na[2], o.g.nz[0], CTT_TOL(1e-12, 1e-5));
                }
        /* The same with triangles: A = (X1 X2 X3), B = (X2 X4 X3). */
        double T1[4][3] = {{-1, 0, -f}, {0, -1, 0}, {0, 1, 0}, {0, 1, 0}};
        double T2[4][3] = {{0, -1, 0}, {1, 0, -f}, {0, 1, 0}, {0, 1, 0}};
        for (int k = 0; k < (fold > 0 ? 2 : 3); k++) {
            one(CT_QUAD_4TRI, 1, T1, pts[k], 0.25, 1, &o);
            double da = o.g.dist[0], nz = o.g.nz[0];
            one(CT_QUAD_4TRI, 1, T2, pts[k], 0.25, 1, &o);
            cr_assert_float_eq(da, o.g.dist[0], CTT_TOL(1e-14, 1e-6));
            cr_assert_float_eq(nz, o.g.nz[0], CTT_TOL(1e-12, 1e-5));
        }
    }
    ctt_geo_free(&o);
}

/* A node sliding across the shared edge: its penetration (the largest over
 * the two segments) is 1-Lipschitz in its position, so between samples h
 * apart it changes by at most h (times 1 + 1e-9). */
Test(project, sliding_across_edge_is_continuous)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    double A[4][3] = {{-1, -1, 0.2}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0.2}};
    double B[4][3] = {{0, -1, 0}, {1, -1, -0.1}, {1, 1, -0.1}, {0, 1, 0}};
    int n = 2001;
    double h = 1.0 / (n - 1);
    for (int m = 0; m < 3; m++)
        for (int two = 0; two < 2; two++) {
            double prev = -1, maxjump = 0;
            for (int i = 0; i < n; i++) {
                double p[3] = {-0.5 + i * h, 0.1, 0.05};
                one((ct_quad_method)m, two, A, p, 0.2, 0, &o);
                double pen = o.g.pen[0];
                one((ct_quad_method)m, two, B, p, 0.2, 0, &o);
                pen = fmax(pen, o.g.pen[0]);
                if (prev >= 0)
                    maxjump = fmax(maxjump, fabs(pen - prev));
                prev = pen;
            }
            cr_assert(maxjump <= h * (1 + 1e-9) + CTT_TOL(1e-14, 1e-6),
                      "method %d two %d: jump %g > step %g", m, two, maxjump, h);
        }
    ctt_geo_free(&o);
}

Test(project, one_sided_and_two_sided)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    double Q[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    for (int m = 0; m < 3; m++) {
        double below[3] = {0.2, 0.3, -0.1}, above[3] = {0.2, 0.3, 0.05};
        /* One-sided, behind: penetrating, pen = gap + depth, normal +z. */
        one((ct_quad_method)m, 0, Q, below, 0.1, 0, &o);
        cr_assert_float_eq(o.g.dist[0], -0.1, CTT_TOL(1e-14, 1e-6));
        cr_assert_float_eq(o.g.pen[0], 0.2, CTT_TOL(1e-14, 1e-6));
        cr_assert_float_eq(o.g.nz[0], 1.0, CTT_TOL(1e-14, 1e-6));
        cr_assert(o.g.flag[0] & CT_NARROW_BEHIND);
        /* One-sided, in front within the gap. */
        one((ct_quad_method)m, 0, Q, above, 0.1, 0, &o);
        cr_assert_float_eq(o.g.pen[0], 0.05, CTT_TOL(1e-14, 1e-6));
        cr_assert_float_eq(o.g.nz[0], 1.0, CTT_TOL(1e-14, 1e-6));
        /* Two-sided: symmetric on both faces. */
        double lo[3] = {0.2, 0.3, -0.05};
        one((ct_quad_method)m, 1, Q, above, 0.1, 0, &o);
        double pa = o.g.pen[0], na = o.g.nz[0];
        one((ct_quad_method)m, 1, Q, lo, 0.1, 0, &o);
        cr_assert_float_eq(o.g.pen[0], pa, CTT_TOL(1e-14, 1e-6));
        cr_assert_float_eq(o.g.nz[0], -na, CTT_TOL(1e-14, 1e-6));
        cr_assert_float_eq(o.g.dist[0], 0.05, CTT_TOL(1e-14, 1e-6));
        /* On the mid-surface: the segment normal, pen = gap, no NaN. */
        double on[3] = {0.2, 0.3, 0};
        for (int two = 0; two < 2; two++) {
            one((ct_quad_method)m, two, Q, on, 0.1, 0, &o);
            cr_assert_eq(o.g.nz[0], 1.0);
            cr_assert_float_eq(o.g.pen[0], 0.1, CTT_TOL(1e-14, 1e-6));
            cr_assert(fabs(o.g.dist[0]) <= CTT_TOL(1e-15, 1e-7));
        }
        /* One-sided, behind and outside the footprint: no contact here. */
        double out[3] = {1.3, 0.0, -0.05};
        one((ct_quad_method)m, 0, Q, out, 0.5, 0, &o);
        cr_assert_eq(o.g.pen[0], 0);
        cr_assert_eq(o.g.flag[0] & (CT_NARROW_BEHIND | CT_NARROW_OUTSIDE),
                     CT_NARROW_BEHIND | CT_NARROW_OUTSIDE);
        /* Two-sided, same point: distance to the edge x = 1. */
        one((ct_quad_method)m, 1, Q, out, 0.5, 0, &o);
        cr_assert_float_eq(o.g.dist[0], sqrt(0.09 + 0.0025), CTT_TOL(1e-14, 1e-6));
    }
    /* A triangle, one-sided, behind. */
    double T[4][3] = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0, 1, 1}};
    double p[3] = {0.2, 0.2, 0.9};
    one(CT_QUAD_4TRI, 0, T, p, 0.05, 1, &o);
    cr_assert_float_eq(o.g.pen[0], 0.15, CTT_TOL(1e-14, 1e-6));
    cr_assert_float_eq(o.g.dist[0], -0.1, CTT_TOL(1e-14, 1e-6));
    ctt_geo_free(&o);
}

Test(project, gap_per_node_and_segment_with_caps)
{
    ctt_geo o;
    ctt_geo_init(&o, 3);
    ct_real x[6] = {0.2, 0.2, 0.2, -1, 1, 0}, y[6] = {0.1, 0.1, 0.1, -1, -1, 1},
            z[6] = {0.3, 0.3, 0.3, 0, 0, 0};
    ct_idx node[3] = {0, 1, 2}, seg[3] = {0, 1, 0};
    ct_idx n1[2] = {3, 3}, n2[2] = {4, 4}, n3[2] = {5, 5}, n4[2] = {5, 5};
    ct_real gn[3] = {0.3, 0.1, 0.05}, gs[2] = {0.2, 0.02};
    /* Caps 0.25 (node) and 0.15 (segment); Gapmin 0.1. */
    int rc = ct_narrow_node_segment(3, node, seg, n1, n2, n3, n4, x, y, z, gn, gs,
                                    (ct_real)0.1, (ct_real)0.25, (ct_real)0.15, CT_QUAD_4TRI,
                                    1, &o.g, NULL);
    cr_assert_eq(rc, CT_OK);
    cr_assert_float_eq(o.g.gap[0], 0.25 + 0.15, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.gap[1], 0.1 + 0.02, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.gap[2], 0.05 + 0.15, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.pen[0], 0.4 - 0.3, CTT_TOL(1e-14, 1e-6));
    cr_assert_eq(o.g.pen[1], 0);
    /* Node gaps only, no caps: Gapmin wins where larger. */
    rc = ct_narrow_node_segment(3, node, seg, n1, n2, n3, n4, x, y, z, gn, NULL, (ct_real)0.2,
                                0, 0, CT_QUAD_4TRI, 1, &o.g, NULL);
    cr_assert_float_eq(o.g.gap[0], 0.3, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.gap[1], 0.2, CTT_TOL(1e-15, 1e-7));
    /* Neither: the scalar. */
    rc = ct_narrow_node_segment(3, node, seg, n1, n2, n3, n4, x, y, z, NULL, NULL,
                                (ct_real)0.35, 0, 0, CT_QUAD_4TRI, 1, &o.g, NULL);
    cr_assert_float_eq(o.g.gap[2], 0.35, CTT_TOL(1e-15, 1e-7));
    cr_assert_float_eq(o.g.pen[2], 0.05, CTT_TOL(1e-14, 1e-6));
    ctt_geo_free(&o);
}

static void assert_skipped(const ctt_geo *o, int bit)
{
    const ct_contact_geo *g = &o->g;
    cr_assert(g->flag[0] & bit, "flag %d lacks %d", g->flag[0], bit);
    cr_assert_eq(g->pen[0], 0);
    ct_real v[] = {g->dist[0], g->nx[0], g->ny[0], g->nz[0], g->cx[0], g->cy[0],
                   g->cz[0],   g->h1[0], g->h2[0], g->h3[0], g->h4[0], g->gap[0]};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        cr_assert(isfinite(v[i]), "output %zu not finite", i);
}

Test(project, degenerate_and_nonfinite_are_skipped)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    double p[3] = {0.1, 0.1, 0.05};
    double zero[4][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};       /* collinear */
    double needle[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1e-14, 0}, {0, 1e-14, 0}};
    double coinc[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}};      /* X4 = X3 */
    double same[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int m = 0; m < 3; m++)
        for (int two = 0; two < 2; two++) {
            one((ct_quad_method)m, two, zero, p, 0.1, 0, &o);
            assert_skipped(&o, CT_NARROW_DEGENERATE);
            one((ct_quad_method)m, two, needle, p, 0.1, 0, &o);
            assert_skipped(&o, CT_NARROW_DEGENERATE);
            one((ct_quad_method)m, two, coinc, p, 0.1, 0, &o);
            assert_skipped(&o, CT_NARROW_DEGENERATE);
            one((ct_quad_method)m, two, same, p, 0.1, 0, &o);
            assert_skipped(&o, CT_NARROW_DEGENERATE);
            one((ct_quad_method)m, two, zero, p, 0.1, 1, &o);
            assert_skipped(&o, CT_NARROW_DEGENERATE);
            double nanp[3] = {NAN, 0, 0};
            double Q[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
            one((ct_quad_method)m, two, Q, nanp, 0.1, 0, &o);
            assert_skipped(&o, CT_NARROW_NONFINITE);
            Q[2][1] = INFINITY;
            one((ct_quad_method)m, two, Q, p, 0.1, 0, &o);
            assert_skipped(&o, CT_NARROW_NONFINITE);
            one((ct_quad_method)m, two, Q, p, 0.1, 1, &o);
            assert_skipped(&o, CT_NARROW_NONFINITE);
        }
    ctt_geo_free(&o);
}

/* A mixed list of triangles and warped quads: identical outputs for 1 and
 * 2 threads, and for the list shifted by one pair (other vector lanes and
 * block boundaries). */
Test(project, bad_arguments)
{
    ctt_geo o;
    ctt_geo_init(&o, 1);
    ct_idx i = 0;
    ct_real v = 0;
    cr_assert_eq(ct_narrow_node_segment(-1, &i, &i, &i, &i, &i, &i, &v, &v, &v, NULL, NULL, 0, 0,
                                        0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment(1, NULL, &i, &i, &i, &i, &i, &v, &v, &v, NULL, NULL, 0,
                                        0, 0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment(1, &i, &i, &i, &i, &i, &i, &v, &v, &v, NULL, NULL, 0, 0,
                                        0, CT_QUAD_NMETHOD, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_quad_method_from_name("newton"), CT_QUAD_NEWTON);
    cr_assert_eq(ct_quad_method_from_name("nope"), -1);
    ctt_geo_free(&o);
}
