/*
 * test_iface_type6.c -- the TYPE6 interface (seed 000's user curve) under
 * prescribed positions, against truths computed here by hand: the total
 * force from the curve, its spread over the penetrating nodes, the stored
 * energy as the curve's integral, the time step, and Coulomb friction on
 * each pair's share of the force.
 */
#include "interfaces/iface_internal.h"
#include "test_iface_type356.h"

#include "meshgen.h"

/* ---- TYPE6: the user curve ----------------------------------------------- */

Test(iface_type356, type6_curve_force_energy_timestep)
{
    /* Main face 2 x 2 unit quads on [0,2]^2, z = 0, facing +z (nodes 0..8,
     * mass 1). Secondary: a tilted flat face of 2 x 1 quads, nodes at
     * x = 0.2, 1.0, 1.8 and y = 0.3, 1.7 (nodes 9..14) with z = -0.03,
     * -0.01, +0.01, plus node 15 at (1.5, 0.5, -0.02) given in sec; mass 2. */
    ct_real cp[4] = {0, 0.01, 0.025, 0.05}, cf[4] = {0, 100, 400, 500};
    ct_idx m[4][4], s1[2] = {9, 10}, s2[2] = {12, 13}, s3[2] = {13, 14}, s4[2] = {10, 11};
    ct_idx *qm[4] = {m[0], m[1], m[2], m[3]};
    const ct_idx sec[1] = {15};
    grid_segments(2, 2, 0, 0, qm);
    tnodes tn;
    tn_init(&tn, 16);
    for (int j = 0; j <= 2; j++)
        for (int i = 0; i <= 2; i++)
            tn_set(&tn, j * 3 + i, i, j, 0);
    const double xs[3] = {0.2, 1.0, 1.8}, zs[3] = {-0.03, -0.01, 0.01};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 3; i++) {
            tn_set(&tn, 9 + j * 3 + i, xs[i], j ? 1.7 : 0.3, zs[i]);
            tn.m[9 + j * 3 + i] = 2;
        }
    tn_set(&tn, 15, 1.5, 0.5, -0.02);
    tn.m[15] = 2;
    ctd_iface_cfg cfg = ctd_iface_default_cfg(6);
    cfg.ncurve = 4;
    cfg.curve_p = cp;
    cfg.curve_f = cf;
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 16;
    d.nseg = 4;
    d.n1 = m[0];
    d.n2 = m[1];
    d.n3 = m[2];
    d.n4 = m[3];
    d.nsec = 1;
    d.sec = sec;
    d.nsseg = 2;
    d.s1 = s1;
    d.s2 = s2;
    d.s3 = s3;
    d.s4 = s4;
    ctd_iface *it = make_iface(&cfg, &d);
    /* The interface owns a copy of the curve. */
    for (int i = 0; i < 4; i++)
        cp[i] = cf[i] = (ct_real)-1;
    /* Two patterns: p_max 0.03 inside the table, then everything 0.03
     * deeper, p_max 0.06 beyond it (the last interval extrapolated). By
     * hand: f(0.03) = 400 + 4000 * 0.005 = 420, slope 4000, f/p = 14000;
     * integral 0.5 + 3.75 + 2.05 = 6.3. f(0.06) = 540, f/p = 9000;
     * integral 0.5 + 3.75 + 11.25 + 5.2 = 20.7. Masses: main 9, secondary
     * 7 x 2 = 14, so M_min = 9. */
    const double Fexp[2] = {420, 540}, Eexp[2] = {6.3, 20.7}, Kexp[2] = {14000, 9000};
    const double tol = CTT_TOL(1e-9, 1e-3);
    for (int c = 0; c < 2; c++) {
        const double sh = 0.03 * c;
        if (c)
            for (ct_idx k = 9; k < 16; k++)
                tn.z[k] -= (ct_real)sh;
        double pk[16] = {0}, psum = 0;
        for (ct_idx k = 9; k < 16; k++) {
            pk[k] = -(double)tn.z[k] > 0 ? -(double)tn.z[k] : 0;
            psum += pk[k];
        }
        ctd_iface_report rep;
        tstep(it, &tn, c * 1e-3, 1e-3, &rep);
        cr_assert_eq(rep.nactive, c ? 7 : 5, "pattern %d: %d active", c, (int)rep.nactive);
        double fsec = 0, fmain = 0;
        for (ct_idx k = 0; k < 16; k++) {
            cr_assert(fabs(tn.fx[k]) <= tol * Fexp[c] && fabs(tn.fy[k]) <= tol * Fexp[c]);
            if (k < 9)
                fmain += tn.fz[k];
            else
                fsec += tn.fz[k];
        }
        for (ct_idx k = 9; k < 16; k++) {
            double want = Fexp[c] * pk[k] / psum;
            cr_assert(fabs(tn.fz[k] - want) <= tol * Fexp[c],
                      "pattern %d node %d: %g expected %g", c, (int)k, (double)tn.fz[k], want);
        }
        cr_assert(fabs(fsec - Fexp[c]) <= tol * Fexp[c], "pattern %d: total %g expected %g", c,
                  fsec, Fexp[c]);
        cr_assert(fabs(fsec + fmain) <= tol * Fexp[c]);
        cr_assert(fabs(rep.force[2] - Fexp[c]) <= tol * Fexp[c]);
        cr_assert(fabs(rep.e_contact - Eexp[c]) <= tol * Eexp[c], "pattern %d: energy %.12g",
                  c, rep.e_contact);
        cr_assert(fabs((double)rep.kmax - Kexp[c]) <= tol * Kexp[c]);
        const double dtw = 0.1 * sqrt(9 / Kexp[c]);
        cr_assert(fabs((double)rep.dt_curve - dtw) <= tol * dtw, "pattern %d: dt %g expected %g",
                  c, (double)rep.dt_curve, dtw);
        cr_assert(rep.dt == rep.dt_curve && rep.dt_nodal == CT_DT_NONE);
    }
    ctd_iface_destroy(it);
    /* A given mass_min wins over the nodal sums. */
    for (int i = 0; i < 4; i++) {
        cp[i] = (ct_real)(i == 0 ? 0 : i == 1 ? 0.01 : i == 2 ? 0.025 : 0.05);
        cf[i] = (ct_real)(i == 0 ? 0 : i == 1 ? 100 : i == 2 ? 400 : 500);
    }
    d.mass_min = 3;
    it = make_iface(&cfg, &d);
    ctd_iface_report rep;
    tstep(it, &tn, 0, 1e-3, &rep);
    const double dtw = 0.1 * sqrt(3 / 9000.0);
    cr_assert(fabs((double)rep.dt - dtw) <= tol * dtw, "dt %g expected %g", (double)rep.dt, dtw);
    /* Lifted clear of the face: nothing penetrates, and the step is the
     * curve's at its first point beyond 0, not unbounded: at p = 0.01,
     * f/p = 10000 and the slope of the interval starting there is 20000
     * (ct_curve_eval takes the interval a breakpoint starts). */
    for (ct_idx k = 9; k < 16; k++)
        tn.z[k] += (ct_real)0.5;
    tstep(it, &tn, 2e-3, 1e-3, &rep);
    cr_assert_eq(rep.nactive, 0);
    const double dt0 = 0.1 * sqrt(3 / 20000.0);
    cr_assert(fabs((double)rep.dt_curve - dt0) <= tol * dt0, "dt before contact %g, expected %g",
              (double)rep.dt_curve, dt0);
    ctd_iface_destroy(it);
    tn_free(&tn);
}

Test(iface_type356, type6_coulomb_friction_uses_the_pair_share)
{
    /* One quad [-1,1]^2 at z = 0 (nodes 0..3) and two nodes sliding along
     * x at depths 0.02 and 0.01; f(p) = 1000 p, so F = 20 shared 2:1 and
     * K = 1000. Each pair's tangential spring is its share of K (2/3 and
     * 1/3 of 1000), so the friction force grows by share K v dt per step
     * until it reaches mu F_k, then slides at mu F_k. */
    const ct_real cp[2] = {0, 0.1}, cf[2] = {0, 100};
    const ct_idx q1[1] = {0}, q2[1] = {1}, q3[1] = {2}, q4[1] = {3}, sec[2] = {4, 5};
    const double mu = 0.3, v = 1, dt = 1e-3, pz[2] = {0.02, 0.01};
    const double Fk[2] = {20 * 2 / 3.0, 20 / 3.0}, kt[2] = {1000 * 2 / 3.0, 1000 / 3.0};
    const double tol = CTT_TOL(1e-9, 1e-3);
    tnodes tn;
    tn_init(&tn, 6);
    tn_set(&tn, 0, -1, -1, 0);
    tn_set(&tn, 1, 1, -1, 0);
    tn_set(&tn, 2, 1, 1, 0);
    tn_set(&tn, 3, -1, 1, 0);
    ctd_iface_cfg cfg = ctd_iface_default_cfg(6);
    cfg.ncurve = 2;
    cfg.curve_p = cp;
    cfg.curve_f = cf;
    cfg.Fric = (ct_real)mu;
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 6;
    d.nseg = 1;
    d.n1 = q1;
    d.n2 = q2;
    d.n3 = q3;
    d.n4 = q4;
    d.nsec = 2;
    d.sec = sec;
    ctd_iface *it = make_iface(&cfg, &d);
    for (int j = 0; j < 15; j++) {
        for (int k = 0; k < 2; k++) {
            tn_set(&tn, 4 + k, -0.5 + v * dt * j, 0.3 * k - 0.2, -pz[k]);
            tn.vx[4 + k] = (ct_real)v;
        }
        ctd_iface_report rep;
        tstep(it, &tn, j * dt, dt, &rep);
        double work = 0;
        for (int k = 0; k < 2; k++) {
            double el = (j + 1) * kt[k] * v * dt, cap = mu * Fk[k];
            double want = -(el < cap ? el : cap);
            cr_assert(fabs(tn.fz[4 + k] - Fk[k]) <= tol * Fk[k]);
            cr_assert(fabs(tn.fx[4 + k] - want) <= tol * Fk[k], "step %d node %d: %g expected %g",
                      j, k, (double)tn.fx[4 + k], want);
            work += el >= cap ? cap * v * dt : 0;
        }
        if (j >= 6) /* both sliding: the dissipation is mu F v dt */
            cr_assert(fabs(rep.e_fric - work) <= tol * work, "step %d: %g expected %g", j,
                      rep.e_fric, work);
        cr_assert(fabs(tn.fx[0] + tn.fx[1] + tn.fx[2] + tn.fx[3] + tn.fx[4] + tn.fx[5]) <=
                  tol * 20);
    }
    ctd_iface_destroy(it);
    tn_free(&tn);
}

/* ---- TYPE6: the stored energy where the curve is negative ---------------- */

/* The stored energy of TYPE6 is the integral of the force the law applies,
 * max(0, f(p)), from 0 to p_max (the kernel clamps the curve's value to be
 * compressive). A curve that starts above p = 0 is extrapolated to the
 * left by its first interval and can be negative there, so the integral
 * takes the positive part of each interval; checked by hand on three
 * intervals with a sign change either way, and against a midpoint sum of
 * max(0, ct_curve_eval) on a curve with several. */
Test(iface_type356, type6_energy_positive_part_of_the_curve)
{
    const double tol = CTT_TOL(1e-12, 1e-5);
    /* (0.01, 100), (0.02, 400): f(p) = 100 + 30000 (p - 0.01), zero at
     * p = 1/150; over [0, 0.015] the triangle from 1/150 to 0.015, height
     * 250: 0.5 * (0.015 - 1/150) * 250. */
    const ct_real p1[2] = {(ct_real)0.01, (ct_real)0.02}, f1[2] = {100, 400};
    double e = ctdi_curve_integral(2, p1, f1, 0, 0.015);
    double want = 0.5 * (0.015 - 1.0 / 150) * 250;
    cr_assert(fabs(e - want) <= tol * want, "rising through zero: %.12g expected %.12g", e, want);
    /* Wholly below the root: nothing stored. */
    cr_assert(ctdi_curve_integral(2, p1, f1, 0, 0.006) == 0);
    /* Falling through zero, (0, 100), (0.01, -100): the triangle from 0 to
     * the root 0.005, height 100. */
    const ct_real p2[2] = {0, (ct_real)0.01}, f2[2] = {100, -100};
    e = ctdi_curve_integral(2, p2, f2, 0, 0.01);
    want = 0.5 * 0.005 * 100;
    cr_assert(fabs(e - want) <= tol * want, "falling through zero: %.12g expected %.12g", e, want);
    /* A curve that crosses zero three times, against a midpoint sum of the
     * clamped curve over [0, 0.05] (10^6 intervals: its error is far below
     * the tolerance for a piecewise-linear integrand). */
    const ct_real p3[5] = {(ct_real)0.005, (ct_real)0.01, (ct_real)0.02, (ct_real)0.03,
                           (ct_real)0.04};
    const ct_real f3[5] = {-50, 80, -20, 300, 100};
    const double b = 0.05;
    e = ctdi_curve_integral(5, p3, f3, 0, b);
    const int nq = 1000000;
    double sum = 0;
    for (int i = 0; i < nq; i++) {
        ct_real slope;
        const double f = (double)ct_curve_eval(5, p3, f3, (ct_real)((i + 0.5) * b / nq), &slope);
        sum += f > 0 ? f : 0;
    }
    sum *= b / nq;
    cr_assert(fabs(e - sum) <= CTT_TOL(1e-8, 1e-4) * sum, "three crossings: %.12g, quadrature %.12g",
              e, sum);
}

/* ---- TYPE6: the prune of the search's pairs ------------------------------ */

/* The distance from p to the triangle a b c, by dense sampling refined
 * around the best sample: an estimate of the test's own (from above, to
 * about 1e-6 of the triangle's size). */
static double tri_dist_sampled(const double p[3], const double a[3], const double b[3],
                               const double c[3])
{
    double best = 1e300, bu = 0, bv = 0, step = 1.0 / 64;
    for (int pass = 0; pass < 4; pass++) {
        double u0 = bu, v0 = bv;
        for (int i = -64; i <= 64; i++)
            for (int j = -64; j <= 64; j++) {
                double u = (pass ? u0 : 0.5) + i * step, v = (pass ? v0 : 0.5) + j * step;
                if (u < 0 || v < 0 || u + v > 1)
                    continue;
                double d2 = 0;
                for (int k = 0; k < 3; k++) {
                    double q = a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]);
                    d2 += (p[k] - q) * (p[k] - q);
                }
                if (d2 < best) {
                    best = d2;
                    bu = u;
                    bv = v;
                }
            }
        step /= 32;
    }
    return sqrt(best);
}

/* A uniform number in [0, 1). */
static double unit(uint64_t *st) { return (double)(ctd_splitmix64(st) >> 11) / 9007199254740992.0; }

Test(iface_type356, type6_prune_keeps_every_future_closest_pair)
{
    /* A bumpy surface of triangles (planar: no warp), nodes above and
     * below it, all pairs within reach. After the prune, move every node
     * and corner by at most half a margin (their relative motion below a
     * margin, as the re-sort criterion allows): each node's closest
     * triangle, found by sampling, must be among its kept pairs. */
    enum { NX = 6, NV = (NX + 1) * (NX + 1), NT = 2 * NX * NX, NS = 40 };
    const double M = 0.05;
    uint64_t st = 12345;
    ct_real x[NV + NS], y[NV + NS], z[NV + NS];
    for (int j = 0; j <= NX; j++)
        for (int i = 0; i <= NX; i++) {
            int v = i + (NX + 1) * j;
            x[v] = (ct_real)i;
            y[v] = (ct_real)j;
            z[v] = (ct_real)(0.3 * sin(1.3 * i) * cos(0.9 * j));
        }
    ct_idx n1[NT], n2[NT], n3[NT], n4[NT];
    for (int j = 0, t = 0; j < NX; j++)
        for (int i = 0; i < NX; i++) {
            ct_idx a = i + (NX + 1) * j, b = a + 1, c = a + NX + 2, d = a + NX + 1;
            n1[t] = a, n2[t] = b, n3[t] = c, n4[t++] = c;
            n1[t] = a, n2[t] = c, n3[t] = d, n4[t++] = d;
        }
    for (int k = 0; k < NS; k++) {
        x[NV + k] = (ct_real)(0.5 + 5 * unit(&st));
        y[NV + k] = (ct_real)(0.5 + 5 * unit(&st));
        z[NV + k] = (ct_real)(-1.0 + 2 * unit(&st));
    }
    ctd_iface it;
    ctdi_pass p;
    memset(&it, 0, sizeof it);
    memset(&p, 0, sizeof p);
    it.margin = (ct_real)M;
    p.n1 = n1, p.n2 = n2, p.n3 = n3, p.n4 = n4, p.nseg = NT;
    p.reach = (ct_real)0.02;
    ct_pairs pp;
    cr_assert_eq(ct_pairs_init(&pp, NS * NT), CT_OK);
    for (int k = 0; k < NS; k++)
        for (int t = 0; t < NT; t++) {
            pp.node[pp.n] = NV + k;
            pp.seg[pp.n++] = t;
        }
    cr_assert_eq(ctdi_type6_prune(&it, &p, &pp, x, y, z), CT_OK);
    cr_assert_lt(pp.n, NS * NT / 4, "the prune kept %d of %d pairs", (int)pp.n, NS * NT);
    /* Moves. */
    int checked = 0;
    const int ntrial = ctt_checking() ? 2 : 6;
    for (int trial = 0; trial < ntrial; trial++) {
        double X[NV + NS], Y[NV + NS], Z[NV + NS];
        for (int v = 0; v < NV + NS; v++) {
            double d[3], n2s = 0;
            for (int k = 0; k < 3; k++) {
                d[k] = 2 * unit(&st) - 1;
                n2s += d[k] * d[k];
            }
            double s = 0.5 * M * 0.999 / sqrt(n2s > 0 ? n2s : 1);
            X[v] = x[v] + s * d[0];
            Y[v] = y[v] + s * d[1];
            Z[v] = z[v] + s * d[2];
        }
        for (int k = 0; k < NS; k++) {
            const double q[3] = {X[NV + k], Y[NV + k], Z[NV + k]};
            double best = 1e300;
            int bt = -1;
            for (int t = 0; t < NT; t++) {
                const double a[3] = {X[n1[t]], Y[n1[t]], Z[n1[t]]};
                const double b[3] = {X[n2[t]], Y[n2[t]], Z[n2[t]]};
                const double c[3] = {X[n3[t]], Y[n3[t]], Z[n3[t]]};
                double d = tri_dist_sampled(q, a, b, c);
                if (d < best - 1e-9) {
                    best = d;
                    bt = t;
                }
            }
            int kept = 0;
            for (ct_idx m = 0; m < pp.n; m++)
                kept |= pp.node[m] == NV + k && pp.seg[m] == bt;
            cr_expect(kept, "trial %d: node %d's closest triangle %d was pruned", trial, k, bt);
            checked++;
        }
    }
    cr_assert_eq(checked, ntrial * NS);
    ct_free(p.prune);
    ct_pairs_destroy(&pp);
}
