/*
 * type7.c -- TYPE7 auto contact (seed 002): one surface against itself,
 * both sides, the gap from the shell thickness (at least cfg.gap), the
 * nonlinear law K = K0 g/(g - p), damping, friction, the kinematic time
 * step; the pass engine is iface_pass.c.
 */
#include "iface_internal.h"

int ctdi_type7_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag)
{
    const ctd_iface_cfg *c = &it->cfg;
    if (d->nseg <= 0 || !d->n1 || !d->n2 || !d->n3 || !d->n4)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE7 needs a surface.");
    ct_real *kseg = NULL;
    if (it->kconst == 0 && c->Istf != 1) {
        int rc = ctdi_seg_stiffness(c->Stfac, d->nseg, d->seg_E, d->seg_t, d->seg_B, d->seg_A,
                                    d->seg_V, &kseg, diag);
        if (rc != CT_OK)
            return rc;
        if (!kseg)
            return ctdi_fail(diag, CT_ERR_ARG, -1,
                             "TYPE7 needs Istf = 1, a stiffness K or segment inputs.");
    }
    /* The surface's nodes, plus any extra secondary nodes given. */
    const ct_idx ns = d->nseg;
    const ct_idx *l[6] = {d->n1, d->n2, d->n3, d->n4, d->sec, d->grnd};
    const ct_idx k[6] = {ns, ns, ns, ns, d->nsec, d->ngrnd};
    ct_idx *sec = NULL;
    int64_t nsec = ctdi_unique_nodes(it->nnode, l, k, &sec);
    if (nsec < 0) {
        ct_free(kseg);
        return ctdi_fail(diag, (int)nsec, -1, "A TYPE7 node index is out of range.");
    }
    it->npass = 1;
    int rc = ctdi_pass_setup(it, &it->pass[0], (ct_idx)nsec, sec, d->nseg, d->n1, d->n2,
                             d->n3, d->n4, kseg, 1, 1, CTDI_LAW_TYPE7);
    return rc == CT_OK ? CT_OK : ctdi_pass_setup_fail(diag, rc, "TYPE7 setup failed");
}
