/*
 * import_radioss.h -- a reader for a subset of the Radioss block format
 * (prefix ctd_): nodes, shells, triangles, bricks, parts, surfaces and node
 * groups, turned into a ct_mesh with the deck's ids kept alongside.
 *
 * Supported keywords (the rest are skipped with their data lines and listed
 * once in a warning, never an error):
 *   /NODE                 id x y z (id in 10 columns, coordinates in 20)
 *   /SHELL/part_id        id n1 n2 n3 n4 (10 columns each; n4 == n3 is a
 *                         triangle)
 *   /SH3N/part_id         id n1 n2 n3
 *   /BRICK/part_id        id n1 ... n8 (nodes 5-8 above nodes 1-4)
 *   /PART/part_id         a title line, then prop_id mat_id
 *   /SURF/PART/id         a title line, then part ids (also /SURF/PART/EXT/id):
 *                         the shells of shell parts, the outer faces of the
 *                         bricks of brick parts
 *   /SURF/GRSHEL/id       a title line, then /GRSHEL ids: their shells
 *   /GRNOD/NODE/id        a title line, then node ids
 *   /GRNOD/PART/id        a title line, then part ids: the nodes of their
 *                         elements
 *   /GRNOD/GRSHEL/id      a title line, then /GRSHEL ids: their shells' nodes
 *   /GRSHEL/SHEL/id       a title line, then shell ids
 *   /TITLE, /BEGIN        read (the title kept) or skipped silently
 *   /END                  the end of the deck (later lines are ignored)
 * Lines starting with '#' or '$' are comments (an "#include" line is listed
 * as unsupported: included files are not read). Fields may be left- or
 * right-justified inside their columns; a blank field is 0 (a blank
 * coordinate is 0.0; a blank node or element id is a missing field); list
 * lines hold any number of 10-column fields, zeros skipped. Numbers may be
 * written 1.5E+01, -.5, 1.D0, 2.5d-1 or 1.5+01 (the Fortran forms). Lines
 * may end in CRLF; a line longer than 4096 characters is an error.
 *
 * Ids are positive integers; any keyword may appear several times and in
 * any order (references are resolved after the whole file is read).
 */
#ifndef CTD_IMPORT_RADIOSS_H
#define CTD_IMPORT_RADIOSS_H

#include <stdint.h>

#include "contact.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The longest line accepted, in characters (without the line end). */
#define CTD_DECK_MAXLINE 4096

/* What a mesh segment comes from. */
enum ctd_seg_kind { CTD_SEG_SHELL = 0, CTD_SEG_SH3N = 1, CTD_SEG_BRICK_FACE = 2 };

typedef struct ctd_part {
    int64_t id, prop, mat;
    char *title;
    int32_t line; /* the line of the /PART keyword */
} ctd_part;

typedef struct ctd_surf {
    int64_t id;
    char *title;
    int32_t line;  /* the line of the /SURF keyword */
    ct_surface s;  /* segment indices into mesh, increasing (ct_calloc'd) */
} ctd_surf;

typedef struct ctd_group {
    int64_t id;
    char *title;
    int32_t line;  /* the line of the /GRNOD keyword */
    ct_nodeset s;  /* node indices, sorted and unique (ct_calloc'd) */
} ctd_group;

typedef struct ctd_deck {
    /* Nodes (positions only) and segments: first one segment per /SHELL
     * and /SH3N element in file order (nelemseg of them), then the brick
     * faces that surfaces use, each face created once. The topology is not
     * built. */
    ct_mesh mesh;
    int64_t *node_id;   /* [mesh.nodes.n] the deck's id of each node */
    int32_t *node_line; /* [mesh.nodes.n] its line */
    ct_idx nelemseg;
    int64_t *seg_elem;  /* [mesh.nseg] element id (the brick's id for a face) */
    int64_t *seg_part;  /* [mesh.nseg] part id */
    int8_t *seg_kind;   /* [mesh.nseg] enum ctd_seg_kind */
    int8_t *seg_face;   /* [mesh.nseg] local face 0..5 of a brick face, else -1 */
    int32_t *seg_line;  /* [mesh.nseg] line of the element */
    /* Bricks: 8 node indices each, in the deck's order. */
    ct_idx nbrick;
    int64_t *brick_id, *brick_part;
    ct_idx *brick_node; /* [8 nbrick] */
    int32_t *brick_line;
    /* Parts (/PART cards), surfaces, node groups, in file order. */
    int npart, nsurf, ngroup;
    ctd_part *part;
    ctd_surf *surf;
    ctd_group *group;
    char *title; /* /TITLE's line, or "" */
    /* Warnings: the distinct unsupported keywords (numeric ids removed, e.g.
     * "/MAT/PLAS_JOHNS"), in order of first appearance, with their counts. */
    int nwarn;
    char **unsupported;
    int *unsupported_count;
    char *warning; /* "unsupported keywords ignored: /X (2), /Y (1)", or "" */
    void *node_map; /* internal: node id -> index */
} ctd_deck;

/*
 * Read a deck. On success the deck owns everything (release with
 * ctd_deck_destroy); on failure it holds nothing, the return value is a
 * negative CT_ERR_* code and diag->msg reads "FILE:LINE: what" (for a field:
 * "FILE:LINE: field 'x' of /NODE: expected a number, got 'abc'"), with
 * diag->index the line number (-1 when the file could not be read). Codes:
 *   CT_ERR_ARG        the file cannot be opened or read, is empty or has no
 *                     /NODE; a malformed number or id; a missing field; a
 *                     line too long; a bad keyword id; a duplicate id
 *                     (node, element of one kind, part, surface, group)
 *   CT_ERR_NONFINITE  a NaN or infinite coordinate
 *   CT_ERR_RANGE      an unknown node, part, shell or /GRSHEL id
 *   CT_ERR_DUPNODE    an element with a repeated node (a /SHELL may have
 *                     n4 == n3, a triangle)
 *   CT_ERR_DEGENERATE a zero-area segment (from ct_mesh_validate, named by
 *                     element id and line)
 *   CT_ERR_TOOBIG     more nodes or segments than ct_idx holds
 *   CT_ERR_NOMEM      out of memory
 */
int ctd_deck_read(const char *path, ctd_deck *deck, ct_diag *diag);
void ctd_deck_destroy(ctd_deck *deck);

/* The warning string (never NULL; "" when there is nothing to say). */
const char *ctd_deck_warning(const ctd_deck *deck);

/* The index of the node with the deck id `id`, or -1. */
ct_idx ctd_deck_node(const ctd_deck *deck, int64_t id);

/* The part, surface or node group with this id, or NULL. */
const ctd_part *ctd_deck_part(const ctd_deck *deck, int64_t id);
const ctd_surf *ctd_deck_surf(const ctd_deck *deck, int64_t id);
const ctd_group *ctd_deck_group(const ctd_deck *deck, int64_t id);

/* ---- Outer surface of bricks ------------------------------------------- */

typedef struct ctd_faces {
    ct_idx n;
    ct_idx *node;  /* [4 n] n1 n2 n3 n4 of each face (n4 == n3: triangle) */
    ct_idx *brick; /* [n] the brick each face belongs to */
    int8_t *local; /* [n] its local face number (see below) */
} ctd_faces;

/*
 * The outer faces of the selected bricks (sel[b] != 0; all when sel is
 * NULL): faces not shared by two selected bricks, each oriented outward
 * (its right-hand normal points away from its brick's centroid; a face is
 * reversed where the brick's numbering is inverted). Brick b's nodes are
 * conn[8b .. 8b+7] (0-based, < nnode); its local faces are 0: 1 4 3 2,
 * 1: 5 6 7 8, 2: 1 2 6 5, 3: 2 3 7 6, 4: 3 4 8 7, 5: 4 1 5 8 (1-based
 * corners). A face of a degenerate brick with three distinct corners is a
 * triangle; with fewer it is dropped. Faces come in brick order, then local
 * order. O(nnode + nbrick). out is overwritten (free with ctd_faces_destroy).
 */
int ctd_brick_outer_faces(ct_idx nnode, const ct_real *x, const ct_real *y, const ct_real *z,
                          ct_idx nbrick, const ct_idx *conn, const unsigned char *sel,
                          ctd_faces *out, ct_diag *diag);
void ctd_faces_destroy(ctd_faces *f);

/* The class of each face slot f = 6 b + l (local face l of brick b, as in
 * ctd_brick_outer_faces) into cls[6 nbrick]: faces with the same corners
 * (in any order) share one class id, in [0, 6 nbrick); a slot that is no
 * face (fewer than three distinct corners), or whose brick is not selected
 * (sel[b] == 0; sel NULL selects all), gets -1. The input must be valid
 * (checked by the caller). O(nnode + nbrick); CT_OK or CT_ERR_NOMEM. */
int ctd_brick_face_classes(ct_idx nnode, ct_idx nbrick, const ct_idx *conn,
                           const unsigned char *sel, ct_idx *cls);

/* The outer faces of the nsel bricks brk[] (in increasing order, each
 * once), given the classes cls of all face slots: the faces whose class
 * occurs once among these bricks' faces, oriented and ordered as by
 * ctd_brick_outer_faces. stamp holds one entry per class, each different
 * from gen and -gen (zeros and a gen greater than all earlier ones do), and
 * is left so for the next selection. O(nsel) whatever the number of
 * bricks; out is overwritten; CT_OK or CT_ERR_NOMEM. */
int ctd_brick_select_outer(const ct_real *x, const ct_real *y, const ct_real *z,
                           const ct_idx *conn, const ct_idx *cls, ct_idx nsel, const ct_idx *brk,
                           int32_t *stamp, int32_t gen, ctd_faces *out);

/* The outer faces of the bricks of the given parts of a deck (all bricks
 * when nparts == 0). An id that names no brick part is CT_ERR_RANGE. */
int ctd_deck_brick_surface(const ctd_deck *deck, const int64_t *part_ids, int nparts,
                           ctd_faces *out, ct_diag *diag);

#ifdef __cplusplus
}
#endif

#endif /* CTD_IMPORT_RADIOSS_H */
