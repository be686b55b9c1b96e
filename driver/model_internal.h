/*
 * model_internal.h -- helpers shared by model.c, model_parts.c,
 * model_gen.c and model_select.c (prefix cti_). Not part of the driver's
 * API.
 */
#ifndef CTD_MODEL_INTERNAL_H
#define CTD_MODEL_INTERNAL_H

#include <stddef.h>

#include "contact.h"
#include "errf.h"
#include "import_radioss.h"
#include "model.h"
#include "scene.h"

/* A growable array of fixed-size items. */
typedef struct cti_vec {
    void *data;
    size_t n, cap;
} cti_vec;

int cti_vec_push(cti_vec *v, const void *item, size_t size);
void cti_vec_free(cti_vec *v);

/* One generated mesh entry: nodes (mesh.nodes) and either surface segments
 * (mesh.n1..n4), bricks (hex8, 8 per element, ctd_block's order) or lines
 * (l1, l2), numbered as scene.h defines. */
typedef struct cti_gen {
    ct_mesh mesh;
    ct_idx *hex8;       /* ct_calloc'd, or NULL */
    ct_idx nline;
    ct_idx *l1, *l2;    /* malloc'd, or NULL */
} cti_gen;

int cti_generate(cti_gen *g, const ctd_scene_generate *sg);
void cti_gen_destroy(cti_gen *g);

/* ---- Building a model (model.c, model_parts.c) ---------------------------- */

/* The meshes of a scene collected into one numbering. */
/* A brick remembers where it comes from (scene mesh entry, and its index
 * in that deck's bricks or -1 for a generated one) so that an element the
 * model refuses is named as the user wrote it. */
typedef struct cti_hex { ct_idx n[8]; int64_t part; int32_t mesh; ct_idx deck; } cti_hex;
typedef struct cti_quad { ct_idx n[4]; int64_t part; int32_t mesh, deck; } cti_quad;
typedef struct cti_line { ct_idx n[2]; int64_t part; } cti_line;

typedef struct cti_mcollect {
    cti_vec x, y, z;          /* double */
    cti_vec id;               /* int64_t */
    cti_vec hex, quad, line;  /* elements */
    cti_vec dface;            /* cti_quad: deck faces of /SURF surfaces */
} cti_mcollect;

/* The state of ctd_model_build. */
typedef struct cti_mbuild {
    ctd_model *m;
    const ctd_scene *sc;
    cti_mcollect c;
    ctd_faces *faces;   /* per part (parts_count), outer faces of its bricks */
    int32_t *face_set;  /* per part: element set index or -1 */
    char *err;
    size_t len;
} cti_mbuild;

/* The element sets and the rigid parts' masses (model_parts.c). */
int cti_model_parts(cti_mbuild *b);

#endif
