/*
 * pair_select.c -- which of a secondary node's candidate pairs carry its
 * contact (the pass engine calls it after the narrow phase): libcontact's
 * ct_select_pairs (kernels/select.c says why and how: one pair per side,
 * the dent, the pinch), then the pair states follow the node's contact.
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

/* States that follow the node's contact from pair to pair. */
static const int moved_states[] = {CTDI_ST_FTX,  CTDI_ST_FTY,   CTDI_ST_FTZ,
                                   CTDI_ST_P0,   CTDI_ST_PPREV, CTDI_ST_FCAP,
                                   CTDI_ST_QJUMP, CTDI_ST_FDAMP};
#define NMOVED ((int)(sizeof moved_states / sizeof moved_states[0]))

int64_t ctdi_pass_select(ctdi_pass *p, const ct_real *x, const ct_real *y, const ct_real *z)
{
    const ct_pairs *pp = &p->pairs[p->cur];
    const ct_idx n = pp->n;
    ct_real *const *st = p->st[p->cur];
    int64_t active = 0;
    /* The pass's arrays are sized for its pair list: no argument error. */
    (void)ct_select_pairs(n, pp->node, x, y, z, p->two_sided, &p->geo, st[CTDI_ST_PPREV],
                          p->carry, p->handoff, &active);
    /* Each pair hands over to one carrier at most: the moves touch
     * disjoint pairs. The pair handed from is reset. */
    const ct_idx *restrict ho = p->handoff;
    CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++) {
        const ct_idx from = ho[k];
        if (from < 0)
            continue;
        for (int i = 0; i < NMOVED; i++) {
            const int s = moved_states[i];
            st[s][k] = st[s][from];
            st[s][from] = s == CTDI_ST_FCAP ? (ct_real)CT_BLEND_NONE : 0;
        }
    });
    return active;
}
