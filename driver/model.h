/*
 * model.h -- the model a scene describes, built once before a run (prefix
 * ctd_model_): one node array, the element sets, lumped masses, rigid
 * bodies, boundary conditions, the surface segments the interfaces select
 * from, and the cells the VTU output shows.
 *
 * Nodes. Meshes are laid out in the order of the scene's `mesh` list: the
 * nodes of mesh 0 first (an imported deck in the deck's order, a generated
 * mesh in its generator's order), then mesh 1, ... node_id[i] is the
 * scene's id of node i (scene.h: a deck's id, or first_id + local number
 * for a generated mesh). Reference positions, initial velocities and lumped
 * masses are in mesh.nodes (x, y, z, vx, vy, vz, m; fx, fy, fz unused).
 *
 * Generated kinds not in meshgen.h (numbering as scene.h defines it):
 *  - ball: ctd_block's n x n x n bricks on [-1, 1]^3 (node (i, j, k) =
 *    i + (n+1)(j + (n+1) k)), each node p mapped onto the unit ball by the
 *    smooth cube-to-ball map x' = x sqrt(1 - y^2/2 - z^2/2 + y^2 z^2/3)
 *    (and cyclically), then scaled by radius and moved to origin;
 *  - net: the plate's nodes (node (i, j) = i + (nx+1) j); trusses first
 *    along x, (i,j)-(i+1,j) for j then i, then along y, (i,j)-(i,j+1);
 *  - rod: node k at origin + (k / n)(to - origin), truss k joins k, k+1.
 * A generated tube or folded sheet is moved by origin (the generators
 * build them at the coordinate origin).
 *
 * Elements. One element set per part: bricks (hex8 of block, ball and deck
 * /BRICK), shells (quads and triangles of plate, sphere, tube, folded and
 * deck /SHELL, /SH3N), truss or spring (lines of net and rod). A part with
 * element `rigid` is a rigid body (its scene body id from rigid_bodies, or
 * the part id); its nodes' masses are rho V for its bricks, rho A t for its
 * surface elements (thickness required) and rho A L for its lines (area
 * required), lumped equally on the element's nodes. A node with elements
 * but no mass (only springs attached) is an error.
 *
 * Surface segments (mesh.n1..n4, for the interfaces): the shell and rigid
 * surface elements (seg_src CTD_SEGSRC_ELEMENT), the outer faces of each
 * brick or rigid-brick part's bricks (CTD_SEGSRC_FACE, ctd_brick_outer_faces
 * per part), then the faces of imported /SURF surfaces made of brick faces
 * (CTD_SEGSRC_DECK, used only by `surf:` selections).
 *
 * Boundary conditions. Per node: bc_mask bit d set when component d is
 * imposed (fixed: velocity 0; velocity: bc_v); a later entry overrides an
 * earlier one on the same component. Initial velocities are written into
 * mesh.nodes.vx.. (later entries override earlier ones). A rigid body with
 * a constrained node is driven: its centre's constrained components follow
 * that node's imposed velocity (the first such node in node order) and it
 * does not rotate.
 */
#ifndef CTD_MODEL_H
#define CTD_MODEL_H

#include <stddef.h>
#include <stdint.h>

#include "contact.h"
#include "elements/elements.h"
#include "scene.h"
#include "elements/shell.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { CTD_SEGSRC_ELEMENT = 0, CTD_SEGSRC_FACE = 1, CTD_SEGSRC_DECK = 2 };

/* One element set: the elements of one deformable part. */
typedef struct ctd_model_set {
    int element;          /* CTD_ELEM_BRICK, SHELL, TRUSS or SPRING */
    int64_t part;         /* scene part id */
    ctd_brick brick;      /* when element is BRICK */
    ctd_shell shell;      /* when SHELL */
    ctd_truss truss;      /* when TRUSS or SPRING */
    ct_idx nelem;
} ctd_model_set;

typedef struct ctd_model_body {
    int64_t id, part;     /* scene body id and its part */
    ctd_rigid rigid;
    int driven;           /* 1: a node of the body is constrained */
    int dof[3];           /* driven components */
    double v[3];          /* their imposed velocity */
} ctd_model_body;

typedef struct ctd_model {
    const ctd_scene *scene;
    ct_mesh mesh;             /* nodes (reference state, masses), segments */
    int64_t *node_id;         /* [nnode] scene id */
    ct_idx *mesh_node_off;    /* [mesh_count + 1] first node of each scene mesh entry */
    int32_t *node_part;       /* [nnode] part id of the first element using it (0: none) */
    int32_t *node_body;       /* [nnode] rigid body index, or -1 */
    int32_t *seg_part;        /* [nseg] part id */
    int8_t *seg_src;          /* [nseg] CTD_SEGSRC_* */
    int8_t *seg_shell;        /* [nseg] 1: a deformable shell element */
    ct_real *seg_thick;       /* [nseg] shell thickness (0 otherwise) */
    int32_t *seg_deck;        /* [nseg] deck mesh index (CTD_SEGSRC_DECK, ELEMENT of a deck), or -1 */
    int32_t *seg_mesh;        /* [nseg] scene mesh entry it comes from */
    int32_t *seg_brick;       /* [nseg] brick (set-local) of a face, or -1 */
    int32_t *seg_set;         /* [nseg] element set of its element or brick, or -1 */
    /* Lines (trusses, springs, rigid lines): for VTU and edge contact. */
    ct_idx nline;
    ct_idx *l1, *l2;
    int32_t *line_part;
    /* Element sets and rigid bodies. */
    int nset;
    ctd_model_set *set;
    int nbody;
    ctd_model_body *body;
    /* Boundary conditions. */
    uint8_t *bc_mask;         /* [nnode] bit d: component d imposed */
    ct_real *bc_v[3];         /* [nnode] imposed velocity components */
    int has_gravity;
    double gravity[3];
    /* Cells for the VTU output. */
    ct_idx ncell;
    uint8_t *cell_type;
    ct_idx *cell_off, *cell_node;
    int32_t *cell_part;
    int64_t nelem;            /* elements of every kind (rigid ones included) */
    double mass;              /* total mass */
} ctd_model;

/*
 * Build the model of a loaded scene (which must outlive it). On failure
 * returns a negative CT_ERR_* code and err holds a message naming the
 * scene file, the part, node or mesh entry and what is wrong; the model is
 * then empty (ctd_model_destroy is still safe).
 */
int ctd_model_build(ctd_model *m, const ctd_scene *sc, char *err, size_t errlen);
void ctd_model_destroy(ctd_model *m);

/* Nodes of a node selection (scene.h): sorted, unique indices (release with
 * ct_nodeset_destroy). An empty result is not an error. */
int ctd_model_select_nodes(const ctd_model *m, const ctd_scene_sel *sel, ct_nodeset *out,
                           char *err, size_t errlen);

/* Segments of a surface selection: increasing indices into m->mesh
 * (out->seg from ct_calloc; release with ct_free). `part`/`parts` take the
 * part's element and outer-face segments, `surf` the deck surface's
 * segments; `where` keeps the segments whose nodes all satisfy it. */
int ctd_model_select_surface(const ctd_model *m, const ctd_scene_sel *sel, ct_surface *out,
                             char *err, size_t errlen);

/* The node index of a scene node id, or -1. */
ct_idx ctd_model_node(const ctd_model *m, int64_t id);

#ifdef __cplusplus
}
#endif

#endif /* CTD_MODEL_H */
