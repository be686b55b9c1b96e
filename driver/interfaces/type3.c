/*
 * type3.c -- TYPE3 (seed 000, "the same as TYPE3" throughout TYPE5 and
 * TYPE6): contact between two oriented solid surfaces, in two passes of the
 * pass engine (iface_pass.c). The first pass takes the secondary surface's
 * nodes against the main segments, the second the main surface's nodes
 * against the secondary segments, so a corner of either surface that
 * enters the other is caught, and neither surface is the "master".
 *
 * Each pass is TYPE5's (type5.c): the linear law with the springs in series,
 * K = Stfac Km Ks/(Km + Ks), where Km is the stiffness of the segment that
 * is hit (main segments in the first pass, secondary in the second, each
 * from its own inputs) and Ks that of the node (the main stiffness alone
 * when the node has none); the closed-form projection, the topological
 * search, damping and friction by default as in Radioss. The surfaces are
 * one-sided unless cfg.two_sided (then a gap > 0 is needed). data.sec is not
 * read: TYPE3 is surface to surface.
 *
 * The report's force is the total on the secondary surface: the second
 * pass counts the reactions on the secondary segments, minus the force on
 * its (main) nodes.
 */
#include "iface_internal.h"

int ctdi_type3_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag)
{
    if (d->nsseg <= 0 || !d->s1 || !d->s2 || !d->s3 || !d->s4)
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "TYPE3 needs secondary segments (data.s1..s4): it is surface to "
                         "surface.");
    it->stiff_mode = CT_STIFF_SERIES;
    it->ks_fallback = 1;
    const ctdi_surf m = ctdi_main_surf(d), s = ctdi_sec_surf(d);
    const ct_idx ns = d->nsseg, nm = d->nseg;
    const ct_idx *l1[6] = {d->s1, d->s2, d->s3, d->s4, NULL, NULL};
    const ct_idx k1[6] = {ns, ns, ns, ns, 0, 0};
    int rc = ctdi_add_pass(it, l1, k1, &m, 1, 0, CTDI_LAW_LINEAR, "main segments", diag);
    if (rc != CT_OK)
        return rc;
    const ct_idx *l2[6] = {d->n1, d->n2, d->n3, d->n4, NULL, NULL};
    const ct_idx k2[6] = {nm, nm, nm, nm, 0, 0};
    return ctdi_add_pass(it, l2, k2, &s, 1, 1, CTDI_LAW_LINEAR, "secondary segments", diag);
}
