/*
 * test_iface_plate.c -- the driver's contact interfaces (driver/interfaces/)
 * with one node against a rigid plate under prescribed motions, no solver:
 * the TYPE24 penalty force and its distribution, the blending and the kept
 * time step, the stiffness combinations, initial penetration, Coulomb
 * friction and its dissipation, Tstart/Tstop, and bad input. The meshed
 * cases (TYPE7, TYPE11, threads, searches) are in test_iface.c.
 */
#include "test_util.h"

#include <string.h>

#include "interfaces/iface.h"
#include "test_iface_util.h"

/* ---- A node against a rigid plate (TYPE24) -------------------------------- */

/* Plate [-L, L]^2 at z = 0 (nodes 0..3, normal +z), node 4 secondary. */
static const ct_idx P1[1] = {0}, P2[1] = {1}, P3[1] = {2}, P4[1] = {3}, SEC4[1] = {4};

static void plate_nodes(tnodes *t, double L)
{
    tn_init(t, 5);
    tn_set(t, 0, -L, -L, 0);
    tn_set(t, 1, L, -L, 0);
    tn_set(t, 2, L, L, 0);
    tn_set(t, 3, -L, L, 0);
}

static ctd_iface *plate_iface(ctd_iface_cfg *c, ct_real K)
{
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 5;
    d.nseg = 1;
    d.n1 = P1;
    d.n2 = P2;
    d.n3 = P3;
    d.n4 = P4;
    d.nsec = 1;
    d.sec = SEC4;
    d.K = K;
    ctd_iface *it = NULL;
    ct_diag diag;
    int rc = ctd_iface_init(&it, c, &d, &diag);
    cr_assert_eq(rc, CT_OK, "init: %s", diag.msg);
    return it;
}

static ctd_iface_cfg plate_cfg(void)
{
    ctd_iface_cfg c = ctd_iface_default_cfg(24);
    c.two_sided = 0; /* an oriented solid face, gap 0 */
    c.gap = 0;
    c.quad = CT_QUAD_NEWTON; /* bilinear shape functions */
    c.VisS = 0;
    c.margin = (ct_real)0.1;
    return c;
}

Test(iface, type24_penalty_force_and_distribution)
{
    const double K = 1000, s = 0.3, tt = -0.4, tol = CTT_TOL(1e-12, 2e-5);
    const double H[4] = {(1 - s) * (1 - tt) / 4, (1 + s) * (1 - tt) / 4, (1 + s) * (1 + tt) / 4,
                         (1 - s) * (1 + tt) / 4};
    const double pens[3] = {1e-3, 0.01, 0.05};
    for (int c = 0; c < 3; c++) {
        tnodes t;
        plate_nodes(&t, 1);
        double p = pens[c];
        tn_set(&t, 4, s, tt, -p);
        ctd_iface_cfg cfg = plate_cfg();
        ctd_iface *it = plate_iface(&cfg, (ct_real)K);
        ctd_iface_report rep;
        tstep(it, &t, 0, 1e-3, &rep);
        double F = K * p;
        cr_assert_eq(rep.nactive, 1);
        cr_assert(fabs(t.fz[4] - F) <= tol * F, "fz %g expected %g", (double)t.fz[4], F);
        cr_assert(fabs(t.fx[4]) <= tol * F && fabs(t.fy[4]) <= tol * F);
        for (int i = 0; i < 4; i++)
            cr_assert(fabs(t.fz[i] + H[i] * F) <= tol * F, "node %d: %g expected %g", i,
                      (double)t.fz[i], -H[i] * F);
        cr_assert(fabs(fsum(t.fz, 5)) <= tol * F && fabs(fsum(t.fx, 5)) <= tol * F);
        cr_assert(fabs(rep.force[2] - F) <= tol * F);
        cr_assert(fabs(rep.e_contact - 0.5 * K * p * p) <= tol * 0.5 * K * p * p);
        /* Constant stiffness: the nodal step sqrt(2 m / K) (m = 1). */
        cr_assert(fabs(rep.dt_nodal - sqrt(2.0 / K)) <= tol * sqrt(2.0 / K));
        ctd_iface_destroy(it);
        tn_free(&t);
    }
}

Test(iface, type24_approach_no_blending)
{
    /* The node comes down at a speed consistent with its motion: every step
     * the force is K p (no blending, no damping with VisS = 0). */
    const double K = 500, v = 0.1, dt = 1e-3, tol = CTT_TOL(1e-9, 1e-3);
    tnodes t;
    plate_nodes(&t, 1);
    ctd_iface_cfg cfg = plate_cfg();
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    double z = 0.002;
    int seen = 0;
    for (int k = 0; k < 100; k++) {
        tn_set(&t, 4, 0.1, 0.2, z);
        t.vz[4] = (ct_real)-v;
        ctd_iface_report rep;
        tstep(it, &t, k * dt, dt, &rep);
        double p = z < 0 ? -z : 0;
        cr_assert(fabs(t.fz[4] - K * p) <= tol * K * 0.01, "step %d: fz %g expected %g", k,
                  (double)t.fz[4], K * p);
        seen += p > 0;
        z -= v * dt;
    }
    cr_assert(seen > 50);
    ctd_iface_destroy(it);
    tn_free(&t);
}

Test(iface, type24_step_kept_while_the_pair_is_open)
{
    /* A node just above the plate (a candidate, not in contact), then in
     * contact, then just above again (contact chatter): the nodal step stays
     * sqrt(2 m / K) throughout. It must not jump back to the element step
     * (no limit) while the pair is open, since the spring can act again at
     * the next cycle with that longer step (the two-bar impact of
     * validation_bars ran away that way). */
    const double K = 500, tol = CTT_TOL(1e-12, 2e-6);
    const double zs[3] = {1e-4, -1e-4, 2e-4};
    tnodes t;
    plate_nodes(&t, 1);
    ctd_iface_cfg cfg = plate_cfg();
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    for (int k = 0; k < 3; k++) {
        tn_set(&t, 4, 0.1, 0.2, zs[k]);
        ctd_iface_report rep;
        tstep(it, &t, k * 1e-3, 1e-3, &rep);
        cr_assert_eq(rep.nactive, zs[k] < 0, "step %d", k);
        cr_assert(fabs(rep.dt_nodal - sqrt(2.0 / K)) <= tol * sqrt(2.0 / K),
                  "step %d: dt_nodal %g expected %g", k, (double)rep.dt_nodal, sqrt(2.0 / K));
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}

Test(iface, type24_stiffness_modes)
{
    /* Km = Stfac E t = 2 * 100 * 1 = 200, Ks = Stfac * et = 2 * 40 = 80. */
    const ct_real E[1] = {100}, th[1] = {1};
    ct_real et[5] = {0, 0, 0, 0, 40};
    const int istf[6] = {2, 3, 4, 5, 1000, 0};
    const double Kexp[6] = {140, 200, 80, 200.0 * 80 / 280, 200, 140};
    const double p = 0.01, tol = CTT_TOL(1e-12, 2e-5);
    for (int c = 0; c < 6; c++) {
        tnodes t;
        plate_nodes(&t, 1);
        tn_set(&t, 4, 0, 0, -p);
        ctd_iface_cfg cfg = plate_cfg();
        cfg.Istf = istf[c];
        cfg.Stfac = 2;
        ctd_iface_data d;
        memset(&d, 0, sizeof d);
        d.nnode = 5;
        d.nseg = 1;
        d.n1 = P1;
        d.n2 = P2;
        d.n3 = P3;
        d.n4 = P4;
        d.nsec = 1;
        d.sec = SEC4;
        d.seg_E = E;
        d.seg_t = th;
        d.node_et = et;
        ctd_iface *it = NULL;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, NULL), CT_OK);
        ctd_iface_report rep;
        tstep(it, &t, 0, 1e-3, &rep);
        cr_assert(fabs(t.fz[4] - Kexp[c] * p) <= tol * Kexp[c] * p, "Istf %d: %g expected %g",
                  istf[c], (double)t.fz[4], Kexp[c] * p);
        ctd_iface_destroy(it);
        /* Stmax clamps. */
        cfg.Stmax = 50;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, NULL), CT_OK);
        tstep(it, &t, 0, 1e-3, &rep);
        cr_assert(fabs(t.fz[4] - 50 * p) <= tol * 50 * p);
        ctd_iface_destroy(it);
        tn_free(&t);
    }
}

Test(iface, type24_initial_penetration)
{
    const double K = 1000, p0 = 0.02, tol = CTT_TOL(1e-10, 1e-4);
    /* Inacti: the initial penetration is subtracted; going 0.005 deeper
     * gives K * 0.005. */
    tnodes t;
    plate_nodes(&t, 1);
    tn_set(&t, 4, 0.2, 0.1, -p0);
    ctd_iface_cfg cfg = plate_cfg();
    cfg.Inacti = 5;
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    ctd_iface_report rep;
    tstep(it, &t, 0, 1e-3, &rep);
    cr_assert(fabs(t.fz[4]) <= tol * K * p0, "initial force %g", (double)t.fz[4]);
    for (int k = 1; k <= 5; k++) {
        tn_set(&t, 4, 0.2, 0.1, -p0 - 0.001 * k);
        t.vz[4] = -1; /* 1 per step of 1e-3: consistent, no blending */
        tstep(it, &t, k * 1e-3, 1e-3, &rep);
        cr_assert(fabs(t.fz[4] - K * 0.001 * k) <= tol * K * p0, "step %d: %g", k,
                  (double)t.fz[4]);
    }
    ctd_iface_destroy(it);
    /* Ipen_max: a pair deeper than it is deactivated for good. */
    tn_set(&t, 4, 0.2, 0.1, -p0);
    t.vz[4] = 0;
    cfg = plate_cfg();
    cfg.Ipen_max = (ct_real)0.01;
    it = plate_iface(&cfg, (ct_real)K);
    tstep(it, &t, 0, 1e-3, &rep);
    cr_assert_eq(rep.deactivated, 1);
    cr_assert(t.fz[4] == 0);
    tstep(it, &t, 1e-3, 1e-3, &rep);
    cr_assert(t.fz[4] == 0);
    ctd_iface_destroy(it);
    /* Default (Inacti 0): the full force on the initial penetration. */
    cfg = plate_cfg();
    it = plate_iface(&cfg, (ct_real)K);
    tstep(it, &t, 0, 1e-3, &rep);
    cr_assert(fabs(t.fz[4] - K * p0) <= tol * K * p0);
    ctd_iface_destroy(it);
    tn_free(&t);
}

/* ---- Friction (TYPE24, Coulomb) ------------------------------------------ */

Test(iface, type24_coulomb_sliding)
{
    const double K = 1000, p = 0.01, mu = 0.3, v = 1, dt = 1e-3;
    const double Fn = K * p, tol = CTT_TOL(1e-9, 1e-3);
    tnodes t;
    plate_nodes(&t, 10);
    ctd_iface_cfg cfg = plate_cfg();
    cfg.Fric = (ct_real)mu;
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    double x = -1;
    for (int k = 0; k < 30; k++) {
        tn_set(&t, 4, x, 0.5, -p);
        t.vx[4] = (ct_real)v;
        ctd_iface_report rep;
        tstep(it, &t, k * dt, dt, &rep);
        cr_assert(fabs(t.fz[4] - Fn) <= tol * Fn);
        if (k >= 5) { /* steady sliding (the stick phase lasts 3 steps) */
            cr_assert(fabs(t.fx[4] + mu * Fn) <= tol * mu * Fn, "step %d: ft %g expected %g",
                      k, (double)t.fx[4], -mu * Fn);
            cr_assert(fabs(t.fy[4]) <= tol * mu * Fn);
            double w = mu * Fn * v * dt;
            cr_assert(fabs(rep.e_fric - w) <= tol * w, "step %d: dissipation %g expected %g",
                      k, rep.e_fric, w);
        }
        cr_assert(fabs(fsum(t.fx, 5)) <= tol * Fn && fabs(fsum(t.fz, 5)) <= tol * Fn);
        x += v * dt;
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}
Test(iface, tstart_tstop)
{
    const double K = 1000, p = 0.01;
    tnodes t;
    plate_nodes(&t, 1);
    tn_set(&t, 4, 0.1, 0.1, -p);
    ctd_iface_cfg cfg = plate_cfg();
    cfg.Tstart = 1;
    cfg.Tstop = 2;
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    const double times[5] = {0.5, 1.0, 1.5, 2.0, 2.5};
    const int on[5] = {0, 1, 1, 1, 0};
    for (int k = 0; k < 5; k++) {
        ctd_iface_report rep;
        tstep(it, &t, times[k], 1e-3, &rep);
        cr_assert_eq(rep.on, on[k], "time %g", times[k]);
        double want = on[k] ? K * p : 0;
        cr_assert(fabs(t.fz[4] - want) <= CTT_TOL(1e-12, 2e-5) * K * p, "time %g: %g",
                  times[k], (double)t.fz[4]);
        cr_assert(on[k] || (rep.e_contact == 0 && rep.nactive == 0));
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}

Test(iface, bad_input)
{
    ctd_iface_cfg cfg = ctd_iface_default_cfg(24);
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    ctd_iface *it = NULL;
    ct_diag diag;
    cfg.type = 9;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_ERR_ARG);
    cr_assert_null(it);
    cfg = ctd_iface_default_cfg(24);
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_ERR_ARG); /* no segments */
    const ct_idx bad[1] = {7};
    d.nnode = 5;
    d.nseg = 1;
    d.n1 = P1;
    d.n2 = P2;
    d.n3 = P3;
    d.n4 = bad;
    d.nsec = 1;
    d.sec = SEC4;
    d.K = 1;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_ERR_RANGE);
    cr_assert_null(it);
}
