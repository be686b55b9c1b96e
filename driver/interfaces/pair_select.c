/*
 * pair_select.c -- which of a secondary node's candidate pairs carry its
 * contact (the pass engine calls it after the narrow phase).
 *
 * The narrow phase judges each (node, segment) pair alone. Left at that, a
 * node above a vertex shared by four segments of a flat surface gets four
 * full penalty forces, and one that moves off the vertex loses three of them
 * in one step: the force is not a function of the position, and energy is
 * made or lost. Below the bottom vertex of a dent (a concave corner seen
 * from the node), every projection falls outside its segment's footprint
 * and no pair reports a penetration at all: the node passes through. So a
 * node's contact is carried by one pair per side:
 *
 *  - the pair with the smallest |distance| (the closest point of the
 *    surface; ties go to the first pair in canonical order, so the choice
 *    is the same for any thread count) carries the node's penetration;
 *  - one-sided: if that pair is behind its segment but outside the
 *    footprint (the dent case), its penetration is gap + r, provided the
 *    node lies within 60 degrees of the inward normal (-r.n >= r/2); a node
 *    beside or under the free edge of a surface, further off the normal,
 *    gets none, as before;
 *  - two-sided (shells, self contact): a second pair may act, the closest
 *    among those whose normal opposes the first one's (n1.n2 < 0): a node
 *    pinched between two layers of a fold is pushed by both;
 *  - every other pair of the node gets penetration 0;
 *  - the carrying pairs are marked (p->carry), penetrating or not: their
 *    springs set the nodal time step (iface_pass.c).
 *
 * When a node's contact moves from one segment to the next (its carrying
 * pair changes, on the same side), the pair states move with it: the last
 * penetration and the blending of the linear law, the tangential friction
 * force and the initial penetration. Otherwise the new pair would start
 * from nothing: the stiffness blending would take the continuous move for
 * a jump and drop the force, and the friction history would be lost.
 */
#include "iface_internal.h"

#include "ct_internal.h"

#include <math.h>

/* States that follow the node's contact from pair to pair. */
static const int moved_states[] = {CTDI_ST_FTX,  CTDI_ST_FTY,   CTDI_ST_FTZ,
                                   CTDI_ST_P0,   CTDI_ST_PPREV, CTDI_ST_FCAP,
                                   CTDI_ST_QJUMP, CTDI_ST_FDAMP};
#define NMOVED ((int)(sizeof moved_states / sizeof moved_states[0]))

/* The penetration the carrying pair k gets (one-sided dead zone included). */
static ct_real carried_pen(const ct_contact_geo *g, ct_idx k, int two_sided, ct_real px,
                           ct_real py, ct_real pz)
{
    ct_real pen = g->pen[k];
    uint8_t f = g->flag[k];
    if (two_sided || pen > 0 || !(f & CT_NARROW_BEHIND) || !(f & CT_NARROW_OUTSIDE))
        return pen;
    ct_real rx = px - g->cx[k], ry = py - g->cy[k], rz = pz - g->cz[k];
    ct_real r = CTI_SQRT(rx * rx + ry * ry + rz * rz);
    ct_real along = -(rx * g->nx[k] + ry * g->ny[k] + rz * g->nz[k]);
    return along >= (ct_real)0.5 * r ? g->gap[k] + r : 0;
}

/* Move the states of pair `from` to pair `to` and reset `from`'s. */
static void move_states(ct_real *const st[CTDI_ST_N], ct_idx from, ct_idx to)
{
    for (int i = 0; i < NMOVED; i++) {
        int s = moved_states[i];
        st[s][to] = st[s][from];
        st[s][from] = s == CTDI_ST_FCAP ? (ct_real)CT_BLEND_NONE : 0;
    }
}

/* The run of one node: pairs [a, b). Returns the active pairs it keeps. */
static int select_run(ctdi_pass *p, ct_idx a, ct_idx b, const ct_real *x,
                      const ct_real *y, const ct_real *z, ct_real *const st[CTDI_ST_N])
{
    const ct_contact_geo *g = &p->geo;
    const ct_idx nd = p->pairs[p->cur].node[a];
    const uint8_t skip = CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE;
    ct_idx best = -1, second = -1;
    for (ct_idx k = a; k < b; k++)
        p->carry[k] = 0;
    for (ct_idx k = a; k < b; k++)
        if (!(g->flag[k] & skip) && (best < 0 || fabs(g->dist[k]) < fabs(g->dist[best])))
            best = k;
    if (best < 0) {
        for (ct_idx k = a; k < b; k++)
            g->pen[k] = 0;
        return 0;
    }
    if (p->two_sided)
        for (ct_idx k = a; k < b; k++) {
            if (k == best || (g->flag[k] & skip) || !(g->pen[k] > 0))
                continue;
            ct_real c = g->nx[k] * g->nx[best] + g->ny[k] * g->ny[best] +
                        g->nz[k] * g->nz[best];
            if (c < 0 && (second < 0 || fabs(g->dist[k]) < fabs(g->dist[second])))
                second = k;
        }
    ct_real pb = carried_pen(g, best, p->two_sided, x[nd], y[nd], z[nd]);
    ct_real ps = second >= 0 ? g->pen[second] : 0;
    /* States follow the contact: a pair that carried the node last step
     * (p_prev > 0) and carries it no more hands its states to the new
     * carrier on its side. */
    for (ct_idx k = a; k < b; k++) {
        if (k == best || k == second || !(st[CTDI_ST_PPREV][k] > 0))
            continue;
        ct_idx to = best;
        if (second >= 0) {
            ct_real c = g->nx[k] * g->nx[second] + g->ny[k] * g->ny[second] +
                        g->nz[k] * g->nz[second];
            if (c > 0)
                to = second;
        }
        if (!(st[CTDI_ST_PPREV][to] > 0))
            move_states(st, k, to);
    }
    for (ct_idx k = a; k < b; k++)
        g->pen[k] = 0;
    g->pen[best] = pb;
    p->carry[best] = 1;
    if (second >= 0) {
        g->pen[second] = ps;
        p->carry[second] = 1;
    }
    return (pb > 0) + (ps > 0);
}

int64_t ctdi_pass_select(ctdi_pass *p, const ct_real *x, const ct_real *y, const ct_real *z)
{
    const ct_pairs *pp = &p->pairs[p->cur];
    const ct_idx n = pp->n, *restrict node = pp->node;
    ct_real *const *st = p->st[p->cur];
    int64_t active = 0;
    CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static) reduction(+ : active)),
    for (ct_idx k = 0; k < n; k++) {
        if (k > 0 && node[k - 1] == node[k])
            continue;
        ct_idx e = k + 1;
        while (e < n && node[e] == node[k])
            e++;
        active += select_run(p, k, e, x, y, z, st);
    });
    return active;
}
