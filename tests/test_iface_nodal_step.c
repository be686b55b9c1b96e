/*
 * test_iface_nodal_step.c -- the nodal contact step of the node-segment
 * interfaces (suite iface_nodal_step): each carrying pair's stiffness is
 * spread onto its nodes with the weights |w| (1 on the secondary node, h_i
 * on the segment's nodes), summed per node, and the step is the smallest
 * sqrt(2 m / (kelem + kc)): the Gershgorin bound of the contact springs on
 * the lumped masses.
 */
#include <math.h>
#include <string.h>

#include "test_iface_util.h"

/* One quad [-1, 1]^2 at z = 0 (nodes 0..3) and secondary nodes from 4. */
static ctd_iface *quad_iface(ct_idx nnode, ct_idx nsec, const ct_idx *sec, ct_real K)
{
    static const ct_idx q1[1] = {0}, q2[1] = {1}, q3[1] = {2}, q4[1] = {3};
    ctd_iface_cfg c = ctd_iface_default_cfg(24);
    c.gap = 0;
    c.VisS = 0;
    c.quad = CT_QUAD_NEWTON;
    c.margin = (ct_real)0.1;
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = nnode;
    d.nseg = 1;
    d.n1 = q1;
    d.n2 = q2;
    d.n3 = q3;
    d.n4 = q4;
    d.nsec = nsec;
    d.sec = sec;
    d.K = K;
    ctd_iface *it = NULL;
    ct_diag diag;
    cr_assert_eq(ctd_iface_init(&it, &c, &d, &diag), CT_OK, "%s", diag.msg);
    return it;
}

static void quad_nodes(tnodes *t, ct_idx n)
{
    tn_init(t, n);
    tn_set(t, 0, -1, -1, 0);
    tn_set(t, 1, 1, -1, 0);
    tn_set(t, 2, 1, 1, 0);
    tn_set(t, 3, -1, 1, 0);
}

/* Two nodes (mass 1) press on the centre of a quad whose corners are light
 * (mass 1/4): each corner carries h = 1/4 of both springs, kc = K/2, and
 * its step sqrt(2 (1/4) / (K/2)) = sqrt(1/K) is below the secondary nodes'
 * sqrt(2/K). Counting the secondary nodes alone (as the step did before)
 * would give a step sqrt(2) too long for the corners. */
Test(iface_nodal_step, light_segment_nodes_set_the_step)
{
    const double K = 1e4;
    tnodes t;
    quad_nodes(&t, 6);
    for (int i = 0; i < 4; i++)
        t.m[i] = (ct_real)0.25;
    tn_set(&t, 4, 0, 0, -0.01);
    tn_set(&t, 5, 0, 0, -0.02);
    const ct_idx sec[2] = {4, 5};
    ctd_iface *it = quad_iface(6, 2, sec, (ct_real)K);
    ctd_iface_report rep;
    tstep(it, &t, 0, 1e-4, &rep);
    cr_assert_eq(rep.nactive, 2);
    const double want = sqrt(1.0 / K), tol = CTT_TOL(1e-12, 1e-6);
    cr_expect(fabs((double)rep.dt_nodal - want) <= tol * want, "dt_nodal %.9g, expected %.9g",
              (double)rep.dt_nodal, want);
    cr_expect(rep.dt_node >= 0 && rep.dt_node < 4, "limiting node %lld, expected a corner",
              (long long)rep.dt_node);
    ctd_iface_destroy(it);
    tn_free(&t);
}

/* The 2 x 2 grid of quads on [-1, 1]^2 (nodes 0..8, mean edge 1) and one
 * secondary node 9 (t: 10 nodes, mass 1), TYPE24 with K, no damping. */
static ctd_iface *grid_iface(tnodes *t, double K, double margin)
{
    static const ct_idx g1[4] = {0, 1, 3, 4}, g2[4] = {1, 2, 4, 5}, g3[4] = {4, 5, 7, 8},
                        g4[4] = {3, 4, 6, 7}, sec[1] = {9};
    tn_init(t, 10);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++)
            tn_set(t, (ct_idx)(3 * j + i), i - 1, j - 1, 0);
    ctd_iface_cfg c = ctd_iface_default_cfg(24);
    c.gap = 0;
    c.VisS = 0;
    c.margin = (ct_real)margin;
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 10;
    d.nseg = 4;
    d.n1 = g1;
    d.n2 = g2;
    d.n3 = g3;
    d.n4 = g4;
    d.nsec = 1;
    d.sec = sec;
    d.K = (ct_real)K;
    ctd_iface *it = NULL;
    ct_diag diag;
    cr_assert_eq(ctd_iface_init(&it, &c, &d, &diag), CT_OK, "%s", diag.msg);
    return it;
}

/* A node above the vertex shared by four quads has four candidate pairs but
 * one carrier (pair_select.c): its spring counts once, the step is
 * sqrt(2 m / K), not sqrt(2 m / (4 K)). The carrier's stiffness counts
 * while the pair is open too (the node lifted a little above the surface,
 * within the search distance), so the step does not jump back up in a
 * cycle of chatter. */
Test(iface_nodal_step, one_carrier_per_node_open_or_closed)
{
    const double K = 1e4;
    tnodes t;
    ctd_iface *it = grid_iface(&t, K, 0.1);
    const double want = sqrt(2.0 / K), tol = CTT_TOL(1e-12, 1e-6);
    const double z[2] = {-0.01, 0.02};
    for (int k = 0; k < 2; k++) {
        tn_set(&t, 9, 0, 0, z[k]);
        ctd_iface_report rep;
        tstep(it, &t, k * 1e-4, 1e-4, &rep);
        cr_assert_eq(rep.ncand, 4, "z = %g: %d candidates", z[k], (int)rep.ncand);
        cr_assert_eq(rep.nactive, k == 0 ? 1 : 0);
        cr_expect(fabs((double)rep.dt_nodal - want) <= tol * want,
                  "z = %g: dt_nodal %.9g, expected %.9g", z[k], (double)rep.dt_nodal, want);
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}

/* With the caller's largest next step (ctd_iface_set_dt_max), an open
 * carrier enters the step within band + 2 |v| dtmax of contact, band =
 * 0.2 mean edges = 0.2 here, whatever the margin (1.5: every position
 * below is a candidate). Without it every carrier does. */
Test(iface_nodal_step, open_carrier_counts_near_contact_whatever_the_margin)
{
    const double K = 1e4, dtmax = 1e-4;
    tnodes t;
    ctd_iface *it = grid_iface(&t, K, 1.5);
    const double want = sqrt(2.0 / K), tol = CTT_TOL(1e-12, 1e-6);
    /* z, vz, whether dtmax is given, whether the spring counts. At z = 0.5
     * the clearance beyond the band is 0.3: the node at rest does not
     * count; at 1000 it closes 0.2 in two steps, not enough; at 2000,
     * 0.4. */
    static const struct { double z, vz; int given, counts; } c[] = {
        {0.15, 0, 1, 1}, {0.5, 0, 1, 0}, {0.5, -1000, 1, 0}, {0.5, -2000, 1, 1},
        {0.5, 0, 0, 1},  {1.2, 0, 0, 1}};
    for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
        tn_set(&t, 9, 0, 0, c[k].z);
        t.vz[9] = (ct_real)c[k].vz;
        ctd_iface_set_dt_max(it, c[k].given ? (ct_real)dtmax : 0);
        ctd_iface_report rep;
        tstep(it, &t, (double)k * 1e-6, 1e-6, &rep);
        cr_assert_eq(rep.ncand, 4, "z = %g: %d candidates", c[k].z, (int)rep.ncand);
        cr_assert_eq(rep.nactive, 0);
        if (c[k].counts)
            cr_expect(fabs((double)rep.dt_nodal - want) <= tol * want,
                      "z = %g, vz = %g: dt_nodal %.9g, expected %.9g", c[k].z, c[k].vz,
                      (double)rep.dt_nodal, want);
        else
            cr_expect(!(rep.dt_nodal < CT_DT_NONE), "z = %g, vz = %g: dt_nodal %.9g, expected "
                      "no limit", c[k].z, c[k].vz, (double)rep.dt_nodal);
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}
