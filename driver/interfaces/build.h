/*
 * build.h -- the scene's interfaces turned into the solver's contact hooks
 * (ctd_interfaces_build of solver.h is defined in build.c).
 *
 * How a scene interface (scene.h) becomes a ctd_iface (iface.h):
 *  - main: the segments of the surface selection; TYPE11 takes the edges of
 *    those segments, or, when the selection has none, the lines (trusses,
 *    springs, rigid lines) of the selected parts;
 *  - secondary: TYPE3 and TYPE11 a surface (TYPE11: edges as for main);
 *    TYPE5 and TYPE7 nodes; TYPE6 the nodes of the surface (or of the
 *    selection when it has no surface); TYPE24 a surface when the selection
 *    gives segments (surface to surface, both passes), nodes otherwise;
 *    absent for 7, 11 and 24 means self contact on main;
 *  - the card fields map one to one onto ctd_iface_cfg; `search` onto the
 *    broad phase;
 *  - stiffness inputs, node gaps and element stiffness come from the model
 *    (build_data.c);
 *  - TYPE24 on a shell surface (every main segment a surface element with a
 *    thickness) is two-sided, with the gap from the thickness when the card
 *    gives none (Igap0 = 1); on brick faces it is one-sided.
 */
#ifndef CTD_BUILD_H
#define CTD_BUILD_H

#include "contact.h"
#include "model.h"
#include "solver.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Model-wide inputs shared by every interface of a run (arrays of nseg or
 * nnode entries, ct_calloc'ed). */
typedef struct ctd_build_data {
    ct_real *seg_E, *seg_t, *seg_B, *seg_A, *seg_V;
    ct_real *node_B, *node_vnode, *node_et;
    ct_real *gap_node;
    ct_real *kelem;
} ctd_build_data;

int ctd_build_data_init(ctd_build_data *d, const ctd_model *m);
void ctd_build_data_destroy(ctd_build_data *d);

struct ctd_iface;

/* The output fields of an interface's last step (iface_fields.c): for
 * each node touched by an active pair, pen[node] = max(pen[node], p) and
 * nact[node] += 1 (node-segment pairs mark the secondary node, edge pairs
 * their four nodes). */
void ctd_iface_fields(const struct ctd_iface *it, ct_real *pen, int32_t *nact);

#ifdef __cplusplus
}
#endif

#endif /* CTD_BUILD_H */
