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
 * penetrate. Two passes over the run: the first finds the closest pair
 * (without a branch on the data: a node's pairs come in no useful order),
 * counts the penetrating pairs and, for the hand-over, those that carried
 * last step, and clears the carry flags and hand-overs; the second looks for
 * the second carrier when another pair penetrates, clearing the
 * penetrations as it goes (the carriers' are set again after it). A run is
 * a few pairs: each pass's loop costs its exit's misprediction, so the
 * passes are as few as the decision allows. */
static inline int select_run(ct_idx a, ct_idx b, ct_real px, ct_real py, ct_real pz,
                             int two_sided, const ct_contact_geo *g, const ct_real *p_prev,
                             uint8_t *carry, ct_idx *handoff)
{
    const uint8_t skip = CTI_SELECT_SKIP;
    ct_idx best = -1, second = -1;
    ct_real bd = 0;
    int npen = 0, nprev = 0;
    const int count_prev = handoff && p_prev;
    for (ct_idx k = a; k < b; k++) {
        const ct_real d = CTI_FABS(g->dist[k]);
        const int ok = !(g->flag[k] & skip);
        const int take = ok & ((best < 0) | (d < bd));
        best = take ? k : best;
        bd = take ? d : bd;
        npen += g->pen[k] > 0;
        carry[k] = 0;
        if (handoff)
            handoff[k] = -1;
        if (count_prev)
            nprev += p_prev[k] > 0;
    }
    if (best < 0) {
        for (ct_idx k = a; k < b; k++)
            g->pen[k] = 0;
        return 0;
    }
    const ct_real pb = carried_pen(g, best, two_sided, px, py, pz);
    ct_real ps = 0;
    if (two_sided && npen > (g->pen[best] > 0)) {
        for (ct_idx k = a; k < b; k++) {
            const ct_real pk = g->pen[k];
            g->pen[k] = 0;
            if (k == best || (g->flag[k] & skip) || !(pk > 0))
                continue;
            if (dot_normals(g, k, best) < 0 &&
                (second < 0 || CTI_FABS(g->dist[k]) < CTI_FABS(g->dist[second]))) {
                second = k;
                ps = pk;
            }
        }
    } else {
        for (ct_idx k = a; k < b; k++)
            g->pen[k] = 0;
    }
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
    g->pen[best] = pb;
    carry[best] = 1;
    if (second >= 0) {
        g->pen[second] = ps;
        carry[second] = 1;
    }
    return (pb > 0) + (ps > 0);
}

/* The runs that start in [k0, k1) of the npair pairs, each decided whole
 * (it may end beyond k1): the carriers that penetrate, and in *unsorted
 * whether a run is followed by a smaller node number. The runs are walked
 * one after the other, not found by testing every pair for a run's start. */
static int64_t select_runs(ct_idx k0, ct_idx k1, ct_idx npair, const ct_idx *node,
                           const ct_real *x, const ct_real *y, const ct_real *z, int two_sided,
                           const ct_contact_geo *geo, const ct_real *p_prev, uint8_t *carry,
                           ct_idx *handoff, int *unsorted)
{
    int64_t act = 0;
    int uns = 0;
    ct_idx k = k0;
    while (k < k1 && k > 0 && node[k - 1] == node[k])
        k++; /* inside a run that started before k0 */
    while (k < k1) {
        const ct_idx nd = node[k];
        ct_idx e = k + 1;
        while (e < npair && node[e] == nd)
            e++;
        uns |= e < npair && node[e] < nd;
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
        } else {
            act += select_run(k, e, x[nd], y[nd], z[nd], two_sided, geo, p_prev, carry,
                              handoff);
        }
        k = e;
    }
    *unsorted |= uns;
    return act;
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
    if (npair > CTI_SELECT_PAR_MIN && !cti_in_parallel()) {
        /* Each thread decides the runs that start in its share of the list. */
#pragma omp parallel reduction(+ : act) reduction(| : unsorted)
        {
            const int64_t nt = cti_team_size(), t = cti_thread_id();
            const ct_idx k0 = (ct_idx)(npair * t / nt), k1 = (ct_idx)(npair * (t + 1) / nt);
            act += select_runs(k0, k1, npair, node, x, y, z, two_sided, geo, p_prev, carry,
                               handoff, &unsorted);
        }
    } else {
        act = select_runs(0, npair, npair, node, x, y, z, two_sided, geo, p_prev, carry,
                          handoff, &unsorted);
    }
    if (active)
        *active = unsorted ? 0 : act;
    /* A node in two runs would have been given a carrier in each. */
    return unsorted ? CT_ERR_ARG : CT_OK;
}
