/*
 * type5.c -- TYPE5 (seed 000): a group of secondary nodes (beam, truss,
 * spring or solid nodes) against a main surface, in one pass of the pass
 * engine (iface_pass.c).
 *
 * The penalty law is linear, F = K p, with the two springs of the seed in
 * series, K = Stfac Km Ks/(Km + Ks): Km is the main segment's stiffness
 * (ct_seg_stiffness: E t for a shell, B A^2/V for a brick face) and Ks the
 * secondary node's (ct_node_stiffness: B (2 Vnode)^(1/3) plus the mean E t
 * of the attached shells). Both arrive already scaled by Stfac (iface.c
 * scales the node stiffness, ctdi_seg_stiffness the segment one), and
 * series(s Km, s Ks) = s Km Ks/(Km + Ks), so the pass combines them with
 * CT_STIFF_SERIES and nothing more. Without node stiffness inputs, or for a
 * node whose stiffness is 0 (a beam or spring node, which the inputs do
 * not cover), the spring is the main one alone, K = Stfac Km; a constant
 * data.K > 0 gives K = Stfac K.
 *
 * The surface is oriented (one-sided, the side from the sign of the
 * tetrahedron volume, seed Figure 6) unless cfg.two_sided. The contact point
 * comes from the closed-form (s, t) of the seed (CT_QUAD_CLOSED by default)
 * and the reaction goes to the main nodes with the shape functions,
 * F_i = N_i(s_c, t_c) F: the engine assembles -h_i F on segment node i, and
 * the narrow phase's h_i are the bilinear N_i at the contact point, so the
 * four reactions sum to -F and their moment about the contact point is zero.
 * The search is the engine's topological one by default (it may miss an
 * impact, seed Figure 4); damping and friction are the engine's (Ifric 0 to
 * 4, with the filter).
 */
#include "iface_internal.h"

int ctdi_type5_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag)
{
    if (d->nsec <= 0 || !d->sec)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE5 needs secondary nodes (data.sec).");
    it->stiff_mode = CT_STIFF_SERIES;
    it->ks_fallback = 1;
    const ct_idx *l[6] = {d->sec, NULL, NULL, NULL, NULL, NULL};
    const ct_idx k[6] = {d->nsec, 0, 0, 0, 0, 0};
    const ctdi_surf m = ctdi_main_surf(d);
    return ctdi_add_pass(it, l, k, &m, 1, 0, CTDI_LAW_LINEAR, "main segments", diag);
}
