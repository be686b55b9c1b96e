/*
 * iface_fields.c -- the per-node output fields of an interface (for the
 * VTU series): the largest penetration of the pairs that touch a node and
 * their count, from the pairs of the last step.
 */
#include "build.h"
#include "iface_internal.h"

void ctd_iface_fields(const ctd_iface *it, ct_real *pen, int32_t *nact)
{
    if (!it || !pen || !nact)
        return;
    for (int i = 0; i < it->npass; i++) {
        const ctdi_pass *p = &it->pass[i];
        if (p->nsec == 0 || p->nseg == 0 || !p->geo.pen)
            continue;
        const ct_pairs *pp = &p->pairs[p->cur];
        for (ct_idx k = 0; k < pp->n; k++) {
            ct_real v = p->geo.pen[k];
            if (!(v > 0))
                continue;
            ct_idx a = pp->node[k];
            if (v > pen[a])
                pen[a] = v;
            nact[a]++;
        }
    }
    if (it->ep)
        ctdi_type11_fields(it->ep, pen, nact);
}
