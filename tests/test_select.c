/*
 * test_select.c -- ct_select_pairs (suite "select"): which of a node's
 * pairs carry its contact after the narrow phase. Hand cases whose answer
 * is geometry: a node over a vertex shared by four segments (one carrier,
 * the penetration of the surface, not four), a node below the bottom of a
 * dent (a penetration where every pair reports none), a node pinched
 * between two layers (two carriers, two-sided), the hand-over of states
 * when the contact moves to the next segment, and bad arguments.
 */
#include <math.h>
#include <string.h>

#include "test_util.h"

enum { MAXP = 8, NF = 13 };

/* A node-segment case: up to MAXP pairs of node 0 with segments given by
 * their corners, run through the narrow phase (4 triangles). */
typedef struct sel_case {
    ct_real x[64], y[64], z[64];
    ct_idx n1[MAXP], n2[MAXP], n3[MAXP], n4[MAXP];
    ct_idx node[MAXP], seg[MAXP];
    ct_idx np, nn;
    ct_real f[NF][MAXP];
    uint8_t flag[MAXP], carry[MAXP];
    ct_idx handoff[MAXP];
    ct_contact_geo g;
} sel_case;

static void sel_init(sel_case *c, ct_real px, ct_real py, ct_real pz)
{
    memset(c, 0, sizeof *c);
    c->x[0] = px, c->y[0] = py, c->z[0] = pz;
    c->nn = 1;
    ct_real *const *f = (ct_real *const[NF]){c->f[0], c->f[1], c->f[2],  c->f[3],  c->f[4],
                                             c->f[5], c->f[6], c->f[7],  c->f[8],  c->f[9],
                                             c->f[10], c->f[11], c->f[12]};
    ct_contact_geo g = {f[0], f[1], f[2], f[3],  f[4],  f[5],  f[6],
                        f[7], f[8], f[9], f[10], f[11], f[12], c->flag};
    c->g = g;
}

static ct_idx sel_node(sel_case *c, ct_real x, ct_real y, ct_real z)
{
    c->x[c->nn] = x, c->y[c->nn] = y, c->z[c->nn] = z;
    return c->nn++;
}

/* A quad a b c d (counter-clockwise seen from its normal's side). */
static void sel_quad(sel_case *c, const ct_real a[3], const ct_real b[3], const ct_real d3[3],
                     const ct_real e[3])
{
    ct_idx k = c->np++;
    c->n1[k] = sel_node(c, a[0], a[1], a[2]);
    c->n2[k] = sel_node(c, b[0], b[1], b[2]);
    c->n3[k] = sel_node(c, d3[0], d3[1], d3[2]);
    c->n4[k] = sel_node(c, e[0], e[1], e[2]);
    c->node[k] = 0;
    c->seg[k] = k;
}

static void sel_narrow(sel_case *c, ct_real gap, int two_sided)
{
    int rc = ct_narrow_node_segment(c->np, c->node, c->seg, c->n1, c->n2, c->n3, c->n4, c->x,
                                    c->y, c->z, NULL, NULL, gap, 0, 0, CT_QUAD_4TRI, two_sided,
                                    &c->g, NULL);
    cr_assert_eq(rc, CT_OK);
}

/* The four unit quads of [-1, 1]^2 at z = 0, normal +z. */
static void four_quads(sel_case *c)
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            ct_real x0 = (ct_real)(i - 1), y0 = (ct_real)(j - 1);
            const ct_real a[3] = {x0, y0, 0}, b[3] = {x0 + 1, y0, 0}, d[3] = {x0 + 1, y0 + 1, 0},
                          e[3] = {x0, y0 + 1, 0};
            sel_quad(c, a, b, d, e);
        }
}

/* Over the shared vertex every pair sees the same penetration; one pair
 * carries it (the first in list order: the ties' rule), the others get 0.
 * Four pairs would push four times as hard. Two-sided too: the other
 * pairs are on the same side (their normals agree), not a second layer. */
Test(select, vertex_of_four_segments_carries_once)
{
    static sel_case c;
    int64_t active = -1;
    for (int two = 0; two < 2; two++) {
        sel_init(&c, 0, 0, (ct_real)0.3);
        four_quads(&c);
        sel_narrow(&c, (ct_real)0.5, two);
        for (int k = 0; k < 4; k++)
            cr_assert_float_eq(c.g.pen[k], 0.2, CTT_TOL(1e-14, 1e-6), "pair %d before: %g", k,
                               c.g.pen[k]);
        cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, two, &c.g, NULL, c.carry,
                                     NULL, &active),
                     CT_OK);
        cr_assert_eq(active, 1, "two-sided %d: %lld carriers", two, (long long)active);
        cr_assert_float_eq(c.g.pen[0], 0.2, CTT_TOL(1e-14, 1e-6));
        cr_assert_eq(c.carry[0], 1);
        for (int k = 1; k < 4; k++) {
            cr_assert_eq(c.g.pen[k], 0, "pair %d keeps %g", k, c.g.pen[k]);
            cr_assert_eq(c.carry[k], 0);
        }
    }
    /* Off the vertex, over the third quad: that one carries. */
    sel_init(&c, (ct_real)0.4, (ct_real)-0.3, (ct_real)0.1);
    four_quads(&c);
    sel_narrow(&c, (ct_real)0.5, 0);
    cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, 0, &c.g, NULL, c.carry, NULL,
                                 &active),
                 CT_OK);
    cr_assert_eq(active, 1);
    for (int k = 0; k < 4; k++)
        cr_assert_eq(c.carry[k], k == 2, "pair %d", k);
    cr_assert_float_eq(c.g.pen[2], 0.4, CTT_TOL(1e-14, 1e-6));
}

/* Skipped pairs (flagged degenerate or non-finite by the narrow phase)
 * never carry: over the shared vertex with pairs 0 and 1 flagged, the
 * first of the others carries; with every pair of the node flagged, none
 * does and every penetration is rewritten to 0 (here stale values put
 * there on purpose), carry 0, no active pair. */
Test(select, skipped_pairs_never_carry)
{
    static sel_case c;
    int64_t active = -1;
    for (int all = 0; all < 2; all++) {
        sel_init(&c, 0, 0, (ct_real)0.3);
        four_quads(&c);
        sel_narrow(&c, (ct_real)0.5, 0);
        for (int k = 0; k < 4; k++) {
            if (all || k < 2)
                c.flag[k] = k % 2 ? CT_NARROW_NONFINITE : CT_NARROW_DEGENERATE;
            c.g.pen[k] = (ct_real)0.2;
            c.carry[k] = 7;
        }
        cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, 0, &c.g, NULL, c.carry,
                                     NULL, &active),
                     CT_OK);
        cr_assert_eq(active, all ? 0 : 1);
        for (int k = 0; k < 4; k++) {
            int carrier = !all && k == 2;
            cr_assert_eq(c.carry[k], carrier, "all %d pair %d", all, k);
            cr_assert_eq(c.g.pen[k], carrier ? (ct_real)0.2 : 0, "all %d pair %d", all, k);
        }
    }
}

/* A valley along y: two faces meeting at x = 0, z = 0, normals up and
 * inward. A node 0.1 below the bottom line lies behind both faces and
 * outside both footprints: no pair reports a penetration, yet the node is
 * 0.1 inside the solid. The carrier gets gap + 0.1. */
Test(select, bottom_of_a_dent_penetrates)
{
    static sel_case c;
    sel_init(&c, 0, (ct_real)0.5, (ct_real)-0.1);
    const ct_real a[3] = {-1, 0, 1}, b[3] = {0, 0, 0}, d[3] = {0, 1, 0}, e[3] = {-1, 1, 1};
    sel_quad(&c, a, b, d, e);
    const ct_real a2[3] = {0, 0, 0}, b2[3] = {1, 0, 1}, d2[3] = {1, 1, 1}, e2[3] = {0, 1, 0};
    sel_quad(&c, a2, b2, d2, e2);
    const ct_real gap = (ct_real)0.05;
    sel_narrow(&c, gap, 0);
    for (int k = 0; k < 2; k++) {
        cr_assert(c.g.nz[k] > 0, "pair %d: normal z %g (faces must face up)", k, c.g.nz[k]);
        cr_assert_eq(c.g.pen[k], 0, "pair %d: pen %g", k, c.g.pen[k]);
        cr_assert(c.g.flag[k] & CT_NARROW_BEHIND);
        cr_assert(c.g.flag[k] & CT_NARROW_OUTSIDE);
    }
    int64_t active = 0;
    cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, 0, &c.g, NULL, c.carry, NULL,
                                 &active),
                 CT_OK);
    cr_assert_eq(active, 1);
    cr_assert_eq(c.carry[0] + c.carry[1], 1);
    ct_real p = c.g.pen[0] + c.g.pen[1];
    cr_assert_float_eq(p, gap + 0.1, CTT_TOL(1e-12, 1e-6), "pen %g", p);
    /* Beside the surface's free edge instead (off the inward normal by
     * more than 60 degrees): nothing. */
    sel_init(&c, (ct_real)1.5, (ct_real)0.5, (ct_real)1.2);
    sel_quad(&c, a2, b2, d2, e2);
    sel_narrow(&c, gap, 0);
    cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, 0, &c.g, NULL, c.carry, NULL,
                                 &active),
                 CT_OK);
    cr_assert_eq(active, 0);
    cr_assert_eq(c.g.pen[0], 0);
}

/* Between two layers 0.2 apart, gap 0.15 each: two-sided, both push (the
 * closer first); one-sided the same geometry gives one carrier. */
Test(select, pinched_node_has_two_carriers)
{
    static sel_case c;
    for (int two = 0; two < 2; two++) {
        sel_init(&c, (ct_real)0.5, (ct_real)0.5, (ct_real)0.08);
        const ct_real a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, d[3] = {1, 1, 0}, e[3] = {0, 1, 0};
        sel_quad(&c, a, b, d, e);
        const ct_real a2[3] = {0, 0, (ct_real)0.2}, b2[3] = {0, 1, (ct_real)0.2},
                      d2[3] = {1, 1, (ct_real)0.2}, e2[3] = {1, 0, (ct_real)0.2};
        sel_quad(&c, a2, b2, d2, e2);
        sel_narrow(&c, (ct_real)0.15, two);
        int64_t active = 0;
        cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, two, &c.g, NULL, c.carry,
                                     NULL, &active),
                     CT_OK);
        cr_assert_eq(c.carry[0], 1);
        cr_assert_float_eq(c.g.pen[0], 0.07, CTT_TOL(1e-14, 1e-6));
        if (two) {
            cr_assert_eq(active, 2);
            cr_assert_eq(c.carry[1], 1);
            cr_assert_float_eq(c.g.pen[1], 0.03, CTT_TOL(1e-14, 1e-6));
        } else {
            cr_assert_eq(active, 1);
            cr_assert_eq(c.carry[1], 0);
            cr_assert_eq(c.g.pen[1], 0);
        }
    }
}

/* The contact moves from quad 0 to quad 1 (the node crossed x = 0): quad
 * 1's pair did not carry last step, quad 0's did, so its states go to
 * quad 1's pair. When quad 1's pair carried already, nothing moves. Two
 * nodes in one list: each run is decided alone. */
Test(select, handoff_follows_the_contact)
{
    static sel_case c;
    sel_init(&c, (ct_real)0.1, (ct_real)0.5, (ct_real)0.1);
    const ct_real a[3] = {-1, 0, 0}, b[3] = {0, 0, 0}, d[3] = {0, 1, 0}, e[3] = {-1, 1, 0};
    sel_quad(&c, a, b, d, e);
    const ct_real a2[3] = {0, 0, 0}, b2[3] = {1, 0, 0}, d2[3] = {1, 1, 0}, e2[3] = {0, 1, 0};
    sel_quad(&c, a2, b2, d2, e2);
    /* Node 1 (a second secondary node) over quad 0, pairs 2 and 3. */
    ct_idx n2 = sel_node(&c, (ct_real)-0.5, (ct_real)0.5, (ct_real)0.2);
    for (int k = 2; k < 4; k++) {
        c.node[k] = n2;
        c.seg[k] = k - 2;
        c.n1[k] = c.n1[k - 2], c.n2[k] = c.n2[k - 2], c.n3[k] = c.n3[k - 2],
        c.n4[k] = c.n4[k - 2];
    }
    c.np = 4;
    sel_narrow(&c, (ct_real)0.3, 0);
    const ct_real p_prev[4] = {(ct_real)0.25, 0, (ct_real)0.1, 0};
    int64_t active = 0;
    cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, 0, &c.g, p_prev, c.carry,
                                 c.handoff, &active),
                 CT_OK);
    cr_assert_eq(active, 2);
    cr_assert_eq(c.carry[1], 1);
    cr_assert_eq(c.handoff[1], 0, "handoff %d", c.handoff[1]);
    cr_assert_eq(c.handoff[0], -1);
    /* Node 1 stays on quad 0, which carried already: no move. */
    cr_assert_eq(c.carry[2], 1);
    cr_assert_eq(c.handoff[2], -1);
    cr_assert_eq(c.handoff[3], -1);
    /* Had the new carrier carried last step too, it keeps its own. */
    const ct_real p_both[4] = {(ct_real)0.25, (ct_real)0.05, 0, 0};
    sel_narrow(&c, (ct_real)0.3, 0);
    cr_assert_eq(ct_select_pairs(c.np, c.node, c.x, c.y, c.z, 0, &c.g, p_both, c.carry,
                                 c.handoff, NULL),
                 CT_OK);
    cr_assert_eq(c.handoff[1], -1);
}

Test(select, bad_arguments)
{
    static sel_case c;
    sel_init(&c, 0, 0, 1);
    four_quads(&c);
    cr_assert_eq(ct_select_pairs(-1, c.node, c.x, c.y, c.z, 0, &c.g, NULL, c.carry, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_select_pairs(4, NULL, c.x, c.y, c.z, 0, &c.g, NULL, c.carry, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_select_pairs(4, c.node, c.x, c.y, c.z, 0, &c.g, NULL, NULL, NULL, NULL),
                 CT_ERR_ARG);
    ct_contact_geo g = c.g;
    g.flag = NULL;
    cr_assert_eq(ct_select_pairs(4, c.node, c.x, c.y, c.z, 0, &g, NULL, c.carry, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_select_pairs(0, NULL, NULL, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL),
                 CT_OK);
    /* Pairs not in ascending node order: a node in two runs would get two
     * carriers. */
    sel_narrow(&c, (ct_real)0.5, 0);
    ct_idx nodes[4] = {0, 1, 0, 1};
    int64_t active = -1;
    cr_assert_eq(ct_select_pairs(4, nodes, c.x, c.y, c.z, 0, &c.g, NULL, c.carry, NULL, &active),
                 CT_ERR_ARG);
    cr_assert_eq(active, 0);
}

/* A long list in runs of 1 to 12 pairs (synthetic narrow-phase results:
 * random distances with ties and NaNs, penetrations, normals facing,
 * opposing and across, skipped, behind and outside pairs, and last
 * penetrations), against the rule written out plainly in the test
 * (oracle_run): each run decided by a call of its own, and the whole list
 * by one call with 1, 2 and 3 threads. The threads split the list where
 * they like; each run must still be decided whole, once: a run cut at a
 * split, decided twice or not at all, changes the bytes. The same list
 * with one descent in node order right at a 2-thread split is refused. */
enum { LONG_N = 20000 };

typedef struct long_case {
    ct_real f[NF][LONG_N];
    uint8_t flag[LONG_N], carry[LONG_N];
    ct_idx node[LONG_N], handoff[LONG_N];
    ct_real p_prev[LONG_N];
    ct_contact_geo g;
} long_case;

static void long_geo(long_case *c)
{
    ct_contact_geo g = {c->f[0], c->f[1], c->f[2], c->f[3],  c->f[4],  c->f[5], c->f[6],
                        c->f[7], c->f[8], c->f[9], c->f[10], c->f[11], c->f[12], c->flag};
    c->g = g;
}

static void long_fill(long_case *c, uint64_t seed)
{
    uint64_t s = seed;
    ct_idx nd = 0;
    for (ct_idx k = 0; k < LONG_N;) {
        s = s * 6364136223846793005u + 1442695040888963407u;
        ct_idx len = 1 + (ct_idx)((s >> 33) % 12);
        for (ct_idx q = 0; q < len && k < LONG_N; q++, k++) {
            double r[6];
            for (int i = 0; i < 6; i++) {
                s = s * 6364136223846793005u + 1442695040888963407u;
                r[i] = (double)(s >> 11) / 9007199254740992.0;
            }
            c->node[k] = nd;
            /* dist, either side; in every third run on a coarse grid, so
             * that ties between a run's pairs occur (ties go to the first),
             * and now and then NaN (never the closest). */
            const int coarse = nd % 3 == 0;
            c->f[0][k] = (ct_real)(coarse ? floor(8 * r[0]) / 8 - 0.3 : r[0] - 0.3);
            if (r[0] < 0.01)
                c->f[0][k] = (ct_real)NAN;
            c->f[1][k] = r[1] < 0.5 ? (ct_real)(0.3 * r[1]) : 0; /* pen */
            /* Two layers facing each other, and some normals across them
             * (n1.n2 = 0 exactly: neither opposed nor along). */
            const ct_real nz = r[2] < 0.4 ? 1 : (r[2] < 0.8 ? -1 : 0);
            c->f[2][k] = nz == 0, c->f[3][k] = 0, c->f[4][k] = nz;
            for (int i = 5; i < NF; i++)
                c->f[i][k] = (ct_real)r[3];
            c->f[12][k] = (ct_real)0.3; /* gap */
            /* Skipped pairs of both kinds; behind and outside (the
             * one-sided dent rule), outside, behind, neither. */
            c->flag[k] = r[4] < 0.05   ? CT_NARROW_DEGENERATE
                         : r[4] < 0.1  ? CT_NARROW_NONFINITE
                         : r[4] < 0.3  ? CT_NARROW_BEHIND | CT_NARROW_OUTSIDE
                         : r[4] < 0.5  ? CT_NARROW_OUTSIDE
                         : r[4] < 0.6  ? CT_NARROW_BEHIND
                                       : 0;
            c->p_prev[k] = r[5] < 0.4 ? (ct_real)(0.2 * r[5]) : 0;
        }
        nd += 1 + (ct_idx)((s >> 40) % 3);
    }
    long_geo(c);
}

/* The end of the run of node[k] in node[0..n-1]. */
static ct_idx run_end_of(const ct_idx *node, ct_idx k, ct_idx n)
{
    ct_idx e = k + 1;
    while (e < n && node[e] == node[k])
        e++;
    return e;
}

/* The rule of ct_select_pairs (ct_narrow.h) for the run [a, e) of c,
 * written out plainly as the reference: the pen, carry and handoff it
 * gives, and the run's active count. */
static int64_t oracle_run(long_case *c, ct_idx a, ct_idx e, int two, ct_real *const xyz[3])
{
    const uint8_t skip = CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE;
    ct_real *dist = c->f[0], *pen = c->f[1], *nx = c->f[2], *ny = c->f[3], *nz = c->f[4];
    /* The closest pair not skipped; ties (and anything after a NaN first
     * pair, which no distance compares below) go to the first. */
    ct_idx best = -1;
    for (ct_idx k = a; k < e; k++)
        if (!(c->flag[k] & skip) && (best < 0 || fabs(dist[k]) < fabs(dist[best])))
            best = k;
    ct_idx second = -1;
    ct_real pb = 0, ps = 0;
    if (best >= 0) {
        pb = pen[best];
        const uint8_t f = c->flag[best];
        if (!two && !(pb > 0) && (f & CT_NARROW_BEHIND) && (f & CT_NARROW_OUTSIDE)) {
            /* The dent: gap + r within 60 degrees of the inward normal. */
            const ct_idx n = c->node[best];
            const ct_real rx = xyz[0][n] - c->f[5][best], ry = xyz[1][n] - c->f[6][best],
                          rz = xyz[2][n] - c->f[7][best];
            const ct_real r = sqrt(rx * rx + ry * ry + rz * rz);
            const ct_real along = -(rx * nx[best] + ry * ny[best] + rz * nz[best]);
            pb = along >= (ct_real)0.5 * r ? c->f[12][best] + r : 0;
        }
        for (ct_idx k = a; k < e && two; k++) {
            const ct_real dn = nx[k] * nx[best] + ny[k] * ny[best] + nz[k] * nz[best];
            if (k != best && !(c->flag[k] & skip) && pen[k] > 0 && dn < 0 &&
                (second < 0 || fabs(dist[k]) < fabs(dist[second])))
                second = k;
        }
        if (second >= 0)
            ps = pen[second];
    }
    ct_idx hb = -1, hs = -1;
    for (ct_idx k = a; k < e && best >= 0; k++) {
        if (k == best || k == second || !(c->p_prev[k] > 0))
            continue;
        const ct_real dn = second < 0 ? 0
                                      : nx[k] * nx[second] + ny[k] * ny[second] +
                                            nz[k] * nz[second];
        if (second >= 0 && dn > 0) {
            if (!(c->p_prev[second] > 0) && hs < 0)
                hs = k;
        } else if (!(c->p_prev[best] > 0) && hb < 0) {
            hb = k;
        }
    }
    for (ct_idx k = a; k < e; k++) {
        pen[k] = k == best ? pb : (k == second ? ps : 0);
        c->carry[k] = k == best || k == second;
        c->handoff[k] = k == best ? hb : (k == second ? hs : -1);
    }
    return (pb > 0) + (ps > 0);
}

Test(select, runs_decided_whole_for_any_thread_count)
{
    static long_case base, ref, got;
    /* Node coordinates (the one-sided dent rule reads them): node numbers
     * grow by 1 to 3 a run, so stay below 3 LONG_N. */
    static ct_real xyz[3][3 * LONG_N];
    uint64_t sx = 99;
    for (int i = 0; i < 3; i++)
        for (ct_idx n = 0; n < 3 * LONG_N; n++) {
            sx = sx * 6364136223846793005u + 1442695040888963407u;
            xyz[i][n] = (ct_real)((double)(sx >> 11) / 9007199254740992.0 - 0.5);
        }
    for (int two = 0; two < 2; two++) {
        long_fill(&base, 12345 + (uint64_t)two);
        /* Reference: the rule, run by run. */
        ref = base;
        long_geo(&ref);
        int64_t act_ref = 0;
        for (ct_idx k = 0; k < LONG_N;) {
            const ct_idx e = run_end_of(ref.node, k, LONG_N);
            act_ref += oracle_run(&ref, k, e, two, (ct_real *const[3]){xyz[0], xyz[1], xyz[2]});
            k = e;
        }
        /* Each run through a call of its own (below the threaded size). */
        got = base;
        long_geo(&got);
        int64_t act_own = 0;
        for (ct_idx k = 0; k < LONG_N;) {
            const ct_idx e = run_end_of(got.node, k, LONG_N);
            ct_contact_geo g = got.g;
            ct_real **fp[NF] = {&g.dist, &g.pen, &g.nx, &g.ny, &g.nz, &g.cx, &g.cy,
                                &g.cz,   &g.h1,  &g.h2, &g.h3, &g.h4, &g.gap};
            for (int i = 0; i < NF; i++)
                *fp[i] += k;
            g.flag += k;
            int64_t a = 0;
            cr_assert_eq(ct_select_pairs(e - k, got.node + k, xyz[0], xyz[1], xyz[2], two, &g,
                                         got.p_prev + k, got.carry + k, got.handoff + k, &a),
                         CT_OK);
            /* Hand-overs are indices within the call: back to the list's. */
            for (ct_idx q = k; q < e; q++)
                got.handoff[q] = got.handoff[q] >= 0 ? got.handoff[q] + k : -1;
            act_own += a;
            k = e;
        }
        cr_assert_gt(act_ref, LONG_N / 20, "active %lld", (long long)act_ref);
        cr_assert_eq(act_own, act_ref);
        cr_assert(memcmp(got.f[1], ref.f[1], sizeof got.f[1]) == 0, "pen, runs alone");
        cr_assert(memcmp(got.carry, ref.carry, sizeof got.carry) == 0, "carry, runs alone");
        cr_assert(memcmp(got.handoff, ref.handoff, sizeof got.handoff) == 0,
                  "handoff, runs alone");
        for (int t = 1; t <= 3; t++) {
            ctt_threads(t);
            got = base;
            long_geo(&got);
            int64_t act = -1;
            cr_assert_eq(ct_select_pairs(LONG_N, got.node, xyz[0], xyz[1], xyz[2], two, &got.g,
                                         got.p_prev, got.carry, got.handoff, &act),
                         CT_OK);
            cr_assert_eq(act, act_ref, "two-sided %d, %d threads: active %lld against %lld",
                         two, t, (long long)act, (long long)act_ref);
            cr_assert(memcmp(got.f[1], ref.f[1], sizeof got.f[1]) == 0, "pen, %d threads", t);
            cr_assert(memcmp(got.carry, ref.carry, sizeof got.carry) == 0, "carry, %d threads",
                      t);
            cr_assert(memcmp(got.handoff, ref.handoff, sizeof got.handoff) == 0,
                      "handoff, %d threads", t);
        }
        /* One descent, at the 2-thread split. */
        got = base;
        long_geo(&got);
        got.node[LONG_N / 2] = got.node[LONG_N / 2 - 1] - 1;
        ctt_threads(2);
        int64_t act = -1;
        cr_assert_eq(ct_select_pairs(LONG_N, got.node, xyz[0], xyz[1], xyz[2], two, &got.g,
                                     got.p_prev, got.carry, got.handoff, &act),
                     CT_ERR_ARG);
        cr_assert_eq(act, 0);
    }
    ctt_threads(2);
}
