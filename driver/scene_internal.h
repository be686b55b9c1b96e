/*
 * scene_internal.h -- shared by the scene loader's files: the light YAML
 * tree (built with libyaml) that maps field paths to lines, the libcyaml
 * schema, and the error list.
 */
#ifndef CTD_SCENE_INTERNAL_H
#define CTD_SCENE_INTERNAL_H

#include <cyaml/cyaml.h>

#include "scene.h"

/* A node of the YAML document: a scalar, a sequence or a mapping. */
enum { CTI_Y_SCALAR = 0, CTI_Y_SEQ, CTI_Y_MAP };

typedef struct cti_ynode {
    int kind;
    int line;                  /* 1-based line where the node starts */
    char *value;               /* scalar text (CTI_Y_SCALAR) */
    int n, cap;                /* children */
    char **key;                /* mapping keys (CTI_Y_MAP) */
    int *key_line;             /* the line of each key */
    struct cti_ynode **child;
} cti_ynode;

/* Parse a YAML file into a tree, aliases read as copies of their anchors'
 * nodes. On failure returns NULL with *code CT_ERR_NOMEM (out of memory,
 * line 0) or CT_ERR_ARG: for a syntax error, an undefined alias, a list as
 * a key or a second document, the 1-based line, the path of the innermost
 * field being read ("" at the top) and the description in msg; for an
 * unreadable file line 0 and strerror in msg; for a file without content
 * line 1. */
cti_ynode *cti_yaml_read(const char *path, int *code, int *line, char *field, size_t fieldlen,
                         char *msg, size_t msglen);
void cti_ynode_free(cti_ynode *n);

/* The node at a path such as "interfaces[0].main.part" (NULL if absent). */
const cti_ynode *cti_ynode_at(const cti_ynode *root, const char *path);

/* The line to blame for a path: the line of its key when present, else the
 * line of the deepest part of the path that exists (0 when nothing does). */
int cti_path_line(const cti_ynode *root, const char *path);

/* "'value'" for a message: at most 60 bytes of s, cut before a UTF-8
 * sequence rather than inside it, and "..." when cut. */
void cti_quote_value(const char *s, char *buf, size_t len);

/* A short description of a node for "got ..." ("'abc'", "a list", "a
 * mapping", "nothing"). */
void cti_ynode_describe(const cti_ynode *n, char *buf, size_t len);

/* The top-level schema (a pointer to ctd_scene). */
extern const cyaml_schema_value_t cti_scene_schema;

/* What the schema expects at a path ("a number", "an integer", "a list of
 * 3 numbers", "a mapping with keys a, b, c", ...), or "" when the path is
 * not in the schema. keys_only: for a mapping, only the list of its keys. */
void cti_schema_expect(const char *path, int keys_only, char *buf, size_t len);

/* Error collection of one load. */
typedef struct cti_errs {
    const char *file;
    const cti_ynode *root;
    ctd_scene_err *out;        /* may be NULL */
    int count;
    int code;
} cti_errs;

/* Add "FILE:LINE: FIELD: what" with LINE from the tree (or `line` when > 0
 * and the path is not found). Returns code. */
int cti_err(cti_errs *e, int code, int line, const char *field, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* Translate libcyaml's captured log (its error line and backtrace) into
 * one error. */
void cti_cyaml_error(cti_errs *e, cyaml_err_t rc, const char *log);

/* The names of the enum values as written in scene files. */
extern const char *const cti_elem_names[CTD_ELEM_NKIND];
extern const char *const cti_gen_names[CTD_GEN_NKIND];
extern const char *const cti_bc_names[CTD_BC_NKIND];

/* Checks after the typed load: defaults, enum names, ranges, references. */
int cti_scene_validate(ctd_scene *sc, cti_errs *e, int64_t refine);

#endif
