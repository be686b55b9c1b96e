/*
 * select.c -- which of a secondary node's candidate pairs carry its contact
 * (ct_select_pairs, ct_narrow.h), after the narrow phase.
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
 *    surface; ties go to the first pair in list order, so the choice is the
 *    same for any thread count) carries the node's penetration;
 *  - one-sided: if that pair is behind its segment but outside the
 *    footprint (the dent case), its penetration is gap + r, provided the
 *    node lies within 60 degrees of the inward normal (-r.n >= r/2); a node
 *    beside or under the free edge of a surface, further off the normal,
 *    gets none;
 *  - two-sided (shells, self contact): a second pair may act, the closest
 *    among the penetrating ones whose normal opposes the first one's
 *    (n1.n2 < 0): a node pinched between two layers of a fold is pushed by
 *    both;
 *  - every other pair of the node gets penetration 0.
 *
 * Each node's run of pairs is decided alone, so the runs are shared among
 * threads with no effect on the result.
 */
#include "ct_internal.h"

#include <math.h>

/* Pairs below which the runs are decided by the calling thread alone (a
 * team costs more than a few thousand runs). */
#define CTI_SELECT_PAR_MIN 2048

/* Pairs the narrow phase skipped: never carriers. */
#define CTI_SELECT_SKIP (CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE)

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

static ct_real dot_normals(const ct_contact_geo *g, ct_idx a, ct_idx b)
{
    return g->nx[a] * g->nx[b] + g->ny[a] * g->ny[b] + g->nz[a] * g->nz[b];
}

/* The run of one node: pairs [a, b). Returns the carrying pairs that
 * penetrate. The closest pair is found without a branch on the data (a
 * node's pairs come in no useful order), and the search for a second
 * carrier is left out when no other pair penetrates. */
static inline int select_run(ct_idx a, ct_idx b, ct_real px, ct_real py, ct_real pz,
                             int two_sided, const ct_contact_geo *g, const ct_real *p_prev,
                             uint8_t *carry, ct_idx *handoff)
{
    const uint8_t skip = CTI_SELECT_SKIP;
    ct_idx best = -1, second = -1;
    ct_real bd = 0;
    int npen = 0, nprev = 0;
    for (ct_idx k = a; k < b; k++) {
        const ct_real d = CTI_FABS(g->dist[k]);
        const int ok = !(g->flag[k] & skip);
        const int take = ok & ((best < 0) | (d < bd));
        best = take ? k : best;
        bd = take ? d : bd;
        npen += g->pen[k] > 0;
    }
    if (handoff)
        for (ct_idx k = a; k < b; k++) {
            handoff[k] = -1;
            nprev += p_prev && p_prev[k] > 0;
        }
    if (best < 0) {
        for (ct_idx k = a; k < b; k++) {
            g->pen[k] = 0;
            carry[k] = 0;
        }
        return 0;
    }
    if (two_sided && npen > (g->pen[best] > 0))
        for (ct_idx k = a; k < b; k++) {
            if (k == best || (g->flag[k] & skip) || !(g->pen[k] > 0))
                continue;
            if (dot_normals(g, k, best) < 0 &&
                (second < 0 || CTI_FABS(g->dist[k]) < CTI_FABS(g->dist[second])))
                second = k;
        }
    const ct_real pb = carried_pen(g, best, two_sided, px, py, pz);
    const ct_real ps = second >= 0 ? g->pen[second] : 0;
    /* A pair that carried the node last step and carries it no more hands
     * its states to the new carrier on its side, the first such pair in
     * list order, when that carrier did not carry last step itself (none
     * to look for when only the carriers carried last step). */
    if (nprev > (p_prev && p_prev[best] > 0) + (second >= 0 && p_prev && p_prev[second] > 0)) {
        for (ct_idx k = a; k < b; k++) {
            if (k == best || k == second || !(p_prev[k] > 0))
                continue;
            const ct_idx to = second >= 0 && dot_normals(g, k, second) > 0 ? second : best;
            if (!(p_prev[to] > 0) && handoff[to] < 0)
                handoff[to] = k;
        }
    }
    for (ct_idx k = a; k < b; k++) {
        g->pen[k] = 0;
        carry[k] = 0;
    }
    g->pen[best] = pb;
    carry[best] = 1;
    if (second >= 0) {
        g->pen[second] = ps;
        carry[second] = 1;
    }
    return (pb > 0) + (ps > 0);
}

int ct_select_pairs(ct_idx npair, const ct_idx *node, const ct_real *x, const ct_real *y,
                    const ct_real *z, int two_sided, const ct_contact_geo *geo,
                    const ct_real *p_prev, uint8_t *carry, ct_idx *handoff, int64_t *active)
{
    if (active)
        *active = 0;
    if (npair < 0 || (npair > 0 && (!node || !x || !y || !z || !geo || !carry)))
        return CT_ERR_ARG;
    if (npair > 0 && (!geo->dist || !geo->pen || !geo->nx || !geo->ny || !geo->nz ||
                      !geo->cx || !geo->cy || !geo->cz || !geo->gap || !geo->flag))
        return CT_ERR_ARG;
    int64_t act = 0;
    int unsorted = 0;
    CTI_PAR_FOR(npair > CTI_SELECT_PAR_MIN,
                (schedule(static) reduction(+ : act) reduction(| : unsorted)),
    for (ct_idx k = 0; k < npair; k++) {
        unsorted |= k > 0 && node[k - 1] > node[k];
        if (k > 0 && node[k - 1] == node[k])
            continue; /* inside a run another iteration decides */
        ct_idx e = k + 1;
        while (e < npair && node[e] == node[k])
            e++;
        const ct_idx nd = node[k];
        if (e == k + 1 && (two_sided || geo->pen[k] > 0)) {
            /* A node with one pair (the common case): it carries unless
             * skipped, and keeps its penetration (select_run's answer,
             * without the calls; the dent rule needs one-sided pen 0). */
            const int ok = !(geo->flag[k] & CTI_SELECT_SKIP);
            carry[k] = (uint8_t)ok;
            if (handoff)
                handoff[k] = -1;
            if (!ok)
                geo->pen[k] = 0;
            act += ok && geo->pen[k] > 0;
            continue;
        }
        act += select_run(k, e, x[nd], y[nd], z[nd], two_sided, geo, p_prev, carry, handoff);
    });
    if (active)
        *active = unsorted ? 0 : act;
    /* A node in two runs would have been given a carrier in each. */
    return unsorted ? CT_ERR_ARG : CT_OK;
}
