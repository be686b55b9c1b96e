/*
 * test_newton_bound.c -- the bound by which Newton ends a node far off the
 * quadrangle (cti_quad_hull_q, kernels/narrow_quad.h; suite "project"):
 * never above the squared distance to the bilinear surface, found by the
 * dense search of test_project.h, for nodes inside the tetrahedron of the
 * corners as well as outside it; and tight enough beyond the edges that it
 * ends most of those nodes' iterations.
 */
#include "narrow_quad.h"
#include "test_project.h"

/* cti_quad_hull_q and the boundary's nearest squared distance of node p
 * and quadrangle X, in the kernels' precision and frame (X1 the origin). */
static void hull_and_boundary(const double X[4][3], const double p[3], double *hq,
                              double *bq)
{
    ct_real r[5][3];
    for (int d = 0; d < 3; d++) {
        for (int i = 0; i < 4; i++)
            r[i][d] = (ct_real)X[i][d];
        r[4][d] = (ct_real)p[d];
    }
    cti_v3 X2 = v3(r[1][0] - r[0][0], r[1][1] - r[0][1], r[1][2] - r[0][2]);
    cti_v3 X3 = v3(r[2][0] - r[0][0], r[2][1] - r[0][1], r[2][2] - r[0][2]);
    cti_v3 X4 = v3(r[3][0] - r[0][0], r[3][1] - r[0][1], r[3][2] - r[0][2]);
    cti_v3 P = v3(r[4][0] - r[0][0], r[4][1] - r[0][1], r[4][2] - r[0][2]);
    CTI_QUAD_MAKE(X2, X3, X4);
    ct_real bs, bt, q;
    cti_quad_boundary(CTI_QARGS, &bs, &bt, &q);
    *bq = q;
    *hq = cti_quad_hull_q(CTI_QARGS);
}

Test(project, newton_hull_bound_is_below_the_distance)
{
    const double warps[4] = {0.05, 0.3, 1.0, 2.0};
    int nq = ctt_checking() ? 8 : 40, np = 40, inside = 0, beyond = 0, ended = 0;
    for (int q = 0; q < nq; q++) {
        double X[4][3];
        rand_quad(X, warps[q % 4], 1.0);
        for (int k = 0; k < np; k++) {
            double p[3], c[3], d, hq, bq;
            if (k % 2 == 0) {
                /* Inside the tetrahedron: a mean of the corners. */
                double w[4], sw = 0;
                for (int i = 0; i < 4; i++)
                    sw += w[i] = urand() + 1e-3;
                for (int e = 0; e < 3; e++)
                    p[e] = (w[0] * X[0][e] + w[1] * X[1][e] + w[2] * X[2][e] + w[3] * X[3][e]) /
                           sw;
                inside++;
            } else {
                /* Beyond an edge, in or near the plane, or anywhere around. */
                double s = 5 * urand() - 2.5, t = 5 * urand() - 2.5, a[3], b[3];
                bil(X, s, t, p, a, b);
                p[2] += (k % 4 == 1 ? 0.2 : 2.0) * (2 * urand() - 1);
            }
            truth_quad(X, p, c, &d);
            hull_and_boundary(X, p, &hq, &bq);
            /* A lower bound (the tetrahedron holds the surface), up to
             * rounding relative to the coordinates. */
            cr_assert(hq <= d * d + CTT_TOL(1e-12, 1e-5),
                      "quad %d node %d: bound %.17g above %.17g", q, k, hq, d * d);
            if (k % 4 == 1) {
                int off = !(fabs(p[0]) <= 1.3 && fabs(p[1]) <= 1.3);
                beyond += off;
                ended += off && hq >= bq * (1 - CTI_NR_NEWTON_OFF_TOL);
            }
        }
    }
    cr_log_info("newton hull bound: %d nodes inside, %d beyond an edge near the plane, "
                "%d of them ended", inside, beyond, ended);
    /* Nodes near the plane beyond an edge: the bound is the boundary's
     * distance for most of them, so their iterations end. */
    cr_assert(beyond > 0 && 2 * ended > beyond, "%d of %d nodes beyond an edge ended", ended,
              beyond);
}
