/*
 * type24.c -- TYPE24 (seed 001): nodes to surface, surface to surface
 * (both passes) or a single surface, with a constant penalty stiffness
 * (Istf, Stfac, Stmin, Stmax), the linear law with stiffness blending,
 * Igap0 gaps, Inacti / Ipen0 / Ipen_max, grnd_IDs, VisS and friction; the
 * pass engine is iface_pass.c.
 */
#include "iface_internal.h"

/* Istf of the card -> ct_stiff_combine (0 and 2 mean, 3 max, 4 min,
 * 5 series, 1 and 1000 main only); -1 when unknown. */
static int istf_mode(int istf)
{
    switch (istf) {
    case 0:
    case 2:
        return CT_STIFF_MEAN;
    case 3:
        return CT_STIFF_MAX;
    case 4:
        return CT_STIFF_MIN;
    case 5:
        return CT_STIFF_SERIES;
    case 1:
    case 1000:
        return CT_STIFF_MAIN;
    default:
        return -1;
    }
}

int ctdi_type24_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag)
{
    const ctd_iface_cfg *c = &it->cfg;
    it->stiff_mode = istf_mode(c->Istf);
    if (it->stiff_mode < 0)
        return ctdi_fail(diag, CT_ERR_ARG, c->Istf, "TYPE24 Istf must be 0..5 or 1000.");
    if (d->nseg <= 0 || !d->n1 || !d->n2 || !d->n3 || !d->n4)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE24 needs main segments.");
    if (!c->self && !c->symmetric && (d->nsec <= 0 || !d->sec) && d->nsseg <= 0 &&
        d->ngrnd <= 0)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE24 needs secondary nodes or segments.");
    if (c->symmetric && (d->nsseg <= 0 || !d->s1 || !d->s2 || !d->s3 || !d->s4))
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "TYPE24 surface to surface needs secondary segments.");
    ct_real *kseg = NULL, *kseg2 = NULL;
    int rc = CT_OK;
    if (it->kconst == 0) {
        rc = ctdi_seg_stiffness(c->Stfac, d->nseg, d->seg_E, d->seg_t, d->seg_B, d->seg_A,
                                d->seg_V, &kseg, diag);
        if (rc == CT_OK && c->symmetric)
            rc = ctdi_seg_stiffness(c->Stfac, d->nsseg, d->ssg_E, d->ssg_t, d->ssg_B,
                                    d->ssg_A, d->ssg_V, &kseg2, diag);
        if (rc == CT_OK && (!kseg || (c->symmetric && !kseg2)))
            rc = ctdi_fail(diag, CT_ERR_ARG, -1,
                           "TYPE24 needs a stiffness K or segment stiffness inputs.");
        if (rc != CT_OK) {
            ct_free(kseg);
            ct_free(kseg2);
            return rc;
        }
    }
    int two = c->two_sided != 0;
    const ct_idx ns = d->nseg, nss = d->nsseg;
    ct_idx *sec = NULL;
    int64_t nsec;
    if (c->self) {
        const ct_idx *l[6] = {d->n1, d->n2, d->n3, d->n4, d->grnd, d->sec};
        const ct_idx k[6] = {ns, ns, ns, ns, d->ngrnd, d->nsec};
        nsec = ctdi_unique_nodes(it->nnode, l, k, &sec);
    } else {
        const ct_idx *l[6] = {d->sec, d->grnd, d->s1, d->s2, d->s3, d->s4};
        const ct_idx k[6] = {d->nsec, d->ngrnd, nss, nss, nss, nss};
        nsec = ctdi_unique_nodes(it->nnode, l, k, &sec);
    }
    if (nsec < 0) {
        ct_free(kseg);
        ct_free(kseg2);
        return ctdi_fail(diag, (int)nsec, -1, "A TYPE24 node index is out of range.");
    }
    it->npass = 1;
    rc = ctdi_pass_setup(it, &it->pass[0], (ct_idx)nsec, sec, d->nseg, d->n1, d->n2, d->n3,
                         d->n4, kseg, c->self != 0, two, CTDI_LAW_LINEAR);
    if (rc != CT_OK) {
        ct_free(kseg2);
        return ctdi_pass_setup_fail(diag, rc, "TYPE24 setup failed");
    }
    if (!c->symmetric || c->self) {
        ct_free(kseg2);
        return CT_OK;
    }
    /* Second pass: the main surface's nodes against the secondary segments. */
    const ct_idx *l[6] = {d->n1, d->n2, d->n3, d->n4, NULL, NULL};
    const ct_idx k[6] = {ns, ns, ns, ns, 0, 0};
    ct_idx *sec2 = NULL;
    int64_t n2 = ctdi_unique_nodes(it->nnode, l, k, &sec2);
    if (n2 < 0) {
        ct_free(kseg2);
        return (int)n2;
    }
    it->npass = 2;
    rc = ctdi_pass_setup(it, &it->pass[1], (ct_idx)n2, sec2, d->nsseg, d->s1, d->s2, d->s3,
                         d->s4, kseg2, 0, two, CTDI_LAW_LINEAR);
    if (rc != CT_OK)
        return ctdi_pass_setup_fail(diag, rc, "TYPE24 setup of its second pass failed");
    /* Its nodes are the main side's: the report counts its force negative,
     * so that the total is the force on the secondary surface. */
    it->pass[1].reverse = 1;
    return CT_OK;
}
