/*
 * scene_validate_internal.h -- what the files of the scene checks share
 * (private to driver/scene_validate*.c): scene_validate.c holds the
 * helpers, references, parts, loads and the top level, scene_validate_mesh.c
 * the meshes, scene_validate_iface.c the interfaces.
 */
#ifndef CT_SCENE_VALIDATE_INTERNAL_H
#define CT_SCENE_VALIDATE_INTERNAL_H

#include "scene_internal.h"

typedef struct vctx {
    ctd_scene *sc;
    cti_errs *e;
    int deck_failed; /* an import failed: references into decks are not checked */
    int64_t refine;  /* > 0: replaces the file's refine */
    char p[160];     /* scratch path */
} vctx;

/* The path built from a format (into v->p). */
const char *cti_vpath(vctx *v, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Whether the file has the key at path. */
int cti_vhas(vctx *v, const char *path);
/* A number: finite and, unless NaN bounds, in [lo, hi] or (lo, hi) when
 * open. `expect` words the range. Returns 1 when fine. */
int cti_vnum(vctx *v, const char *path, double x, double lo, int lo_open, double hi, int hi_open,
             const char *expect);
/* The index of s among names, or -1 with an error listing them. */
int cti_venum(vctx *v, const char *path, const char *s, const char *const *names, int n);
/* The deck imported by mesh i, or NULL. */
const ctd_deck *cti_vdeck(const ctd_scene *sc, unsigned i);
/* Whether part id exists (else an error at path). */
int cti_vpart_ref(vctx *v, const char *path, int64_t id);
/* What a selection may hold (the allow argument of cti_vsel). */
enum { SEL_NODES = 1, SEL_SURF = 2 };
/* Check a selection; `allow` is SEL_NODES, SEL_SURF or both. */
void cti_vsel(vctx *v, const char *base, ctd_scene_sel *s, int allow);

/* The meshes (scene_validate_mesh.c) and one interface (scene_validate_iface.c). */
void cti_vcheck_meshes(vctx *v);
void cti_vcheck_interface(vctx *v, unsigned i, ctd_scene_interface *f);

#endif /* CT_SCENE_VALIDATE_INTERNAL_H */
