/*
 * import_radioss_internal.h -- what the files of the Radioss reader share
 * (prefix ctd_rad_); not part of the public API (see import_radioss.h).
 *
 * The reader works in two passes. The scan (import_radioss_scan.c) reads
 * the text into a ctd_rad_reader: growing arrays of raw ids, each with its
 * line, using the field and number parsers of import_radioss_lex.c. The
 * resolution then turns ids into indices through id maps: nodes, elements
 * and parts (import_radioss_resolve.c), then /GRSHEL lists, surfaces and
 * node groups (import_radioss_sets.c), the latter using the outer faces of
 * bricks (import_radioss_bricks.c). import_radioss.c runs the passes and
 * moves the results into the ctd_deck.
 */
#ifndef CTD_IMPORT_RADIOSS_INTERNAL_H
#define CTD_IMPORT_RADIOSS_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "import_radioss.h"

/* ---- Growing arrays and strings (import_radioss_lex.c) ----------------- */

/* Grow the malloc'd array *pp to hold `cap` elements (contents kept). */
int ctd_rad_regrow(void *pp, size_t cap, size_t size);

/* The capacity after `cap` (256 to start, then half as much again). */
size_t ctd_rad_next_cap(size_t cap);

/* A malloc'd copy of s[0..n) without leading and trailing blanks. */
char *ctd_rad_dup_trim(const char *s, int n);

/* A malloc'd "" when s is NULL, else s; NULL only when out of memory. */
char *ctd_rad_or_empty(char *s);

/* The largest deck read, in bytes (1 GiB: an endless stream, a FIFO fed
 * forever, would otherwise take all the memory). */
#define CTD_DECK_MAXBYTES ((size_t)1 << 30)

/* Read a whole file; NULL (errno set) on failure: EFBIG for a file past
 * CTD_DECK_MAXBYTES (*size: its size when known, else 0). */
char *ctd_rad_slurp(const char *path, size_t *size);

/* ---- Id maps (import_radioss_resolve.c) -------------------------------- */

/* An open-addressing map from positive 64-bit ids to indices. */
typedef struct ctd_rad_map {
    size_t mask;
    int64_t *key; /* 0 = empty */
    ct_idx *val;
} ctd_rad_map;

/* Size the map for n insertions. */
int ctd_rad_map_init(ctd_rad_map *m, size_t n);
void ctd_rad_map_free(ctd_rad_map *m);
/* Insert k -> v; returns the earlier value when k is already present, else
 * -1. The map must have been sized for all insertions. */
ct_idx ctd_rad_map_put(ctd_rad_map *m, int64_t k, ct_idx v);
/* The value of k, or -1 (also for a NULL or empty map). */
ct_idx ctd_rad_map_get(const ctd_rad_map *m, int64_t k);

/* ---- Reader state (filled by the scan) --------------------------------- */

/* The list cards, in this order: surfaces first, then node groups, then
 * /GRSHEL. */
enum ctd_rad_lst { CTD_RAD_L_SURF_PART, CTD_RAD_L_SURF_GRSHEL, CTD_RAD_L_GRNOD_NODE,
                   CTD_RAD_L_GRNOD_PART, CTD_RAD_L_GRNOD_GRSHEL, CTD_RAD_L_GRSHEL_SHEL };

/* The keyword of each list type ("/SURF/PART", ...), and the name of its
 * fields ("part_id", ...); the field names of element corners ("n1", ...). */
extern const char *const ctd_rad_list_kw[6];
extern const char *const ctd_rad_list_field[6];
extern const char *const ctd_rad_corner[8];

/* A list card as read: its ids, each with its line and field number. */
typedef struct ctd_rad_list {
    int type; /* enum ctd_rad_lst */
    int64_t id;
    char *title;
    int32_t line;
    size_t n, cap;
    int64_t *ids;
    int32_t *lines;
    int16_t *fld;
} ctd_rad_list;

typedef struct ctd_rad_reader {
    const char *path;
    ct_diag *diag;
    char kw[48];  /* the current keyword, for messages */
    int blk, sub; /* the current block (private to the scan) and its data
                   * lines so far */
    int64_t blk_id;
    int saw_node;
    /* Nodes. */
    size_t nn, capn;
    int64_t *nid;
    double *xyz;
    int32_t *nline;
    /* Shell and triangle elements (raw node ids, 4 per element). */
    size_t ns, caps;
    int64_t *sid, *spart, *sraw;
    int32_t *sline;
    int8_t *skind;
    /* Bricks (raw node ids, 8 per brick). */
    size_t nb, capb;
    int64_t *bid, *bpart, *braw;
    int32_t *bline;
    /* Parts and lists. */
    size_t np, capp;
    ctd_part *part;
    size_t nl, capl;
    ctd_rad_list *list;
    /* Unsupported keywords. */
    int nun, capun;
    char **un;
    int *uncount;
    char *title;
} ctd_rad_reader;

/* Fill the reader's diag with "FILE:LINE: what" ("FILE: what" when line
 * <= 0), diag->index = line; returns code. */
int ctd_rad_fail(ctd_rad_reader *r, int code, int64_t line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* The same for CT_ERR_NOMEM: "out of memory". */
int ctd_rad_nomem(ctd_rad_reader *r, int64_t line);

/* ---- Fields and numbers (import_radioss_lex.c) ------------------------- */

/* A field: columns of a line, trimmed of blanks (n == 0: blank). */
typedef struct ctd_rad_fld {
    const char *p;
    int n;
} ctd_rad_fld;

/* Columns [start, start + width) of a line of len characters. */
ctd_rad_fld ctd_rad_field(const char *s, int len, int start, int width);

/* An integer: 0 read, 1 blank (v = 0), -1 malformed. */
int ctd_rad_parse_int(ctd_rad_fld f, int64_t *v);

/* A real in Fortran forms: 0 read, 1 blank (v = 0), -1 malformed, -2 NaN
 * or infinite (written so, or overflowing). */
int ctd_rad_parse_real(ctd_rad_fld f, double *v);

/* A required positive id in columns [start, start + 10) of line `line`. */
int ctd_rad_need_id(ctd_rad_reader *r, int32_t line, const char *s, int len, int start,
                    const char *name, int64_t *v);

/* An optional real in columns [start, start + 20) (blank = 0). */
int ctd_rad_opt_real(ctd_rad_reader *r, int32_t line, const char *s, int len, int start,
                     const char *name, double *v);

/* A field that does not read as it should, CT_ERR_ARG: "field 'NAME' of
 * KW: expected WHAT, got 'TEXT'" ("field 'NAME' (number K) of ..." when
 * k > 0; TEXT cut at 40 characters). */
int ctd_rad_bad_field(ctd_rad_reader *r, int32_t line, const char *name, int k,
                      const char *what, ctd_rad_fld f);

/* ---- The scan (import_radioss_scan.c) ---------------------------------- */

/* Scan the text buf[0..size) into r; *nlines is the number of lines read
 * (up to /END). */
int ctd_rad_scan(ctd_rad_reader *r, const char *buf, size_t size, int32_t *nlines);

/* Release what the scan allocated (and is still owned by r). */
void ctd_rad_reader_free(ctd_rad_reader *r);

/* ---- Resolution state (import_radioss_resolve.c, _sets.c) -------------- */

/* The maps and the arrays being built. */
typedef struct ctd_rad_res {
    ctd_rad_map nodes, shells, parts, grshel;
    ct_nodes nd;
    /* Segments (element segments, then brick faces). */
    size_t nseg, capseg;
    ct_idx *sn; /* 4 per segment */
    int64_t *selem, *spart;
    int8_t *skind, *sface;
    int32_t *sline;
    ct_idx *spk;        /* dense part index of each element segment */
    ct_idx *bnode;      /* resolved brick nodes */
    ct_idx *bpk;        /* dense part index of each brick */
    ct_idx *faceseg;    /* [6 nb] segment of a brick face, or -1 */
    int64_t *pk_id;     /* dense part ids */
    ct_idx *pk_soff, *pk_seg; /* element segments of each dense part (CSR) */
    ct_idx *pk_boff, *pk_brk; /* bricks of each dense part (CSR) */
    unsigned char *pk_brick;
    size_t npk;
    ct_idx **gseg;      /* resolved /GRSHEL lists (segments) */
    ct_idx *gsegn;
    int32_t *stamp;      /* per node or segment */
    int32_t gen;
    /* Per dense part or /GRSHEL index: the last list that used it (a list
     * that repeats an id goes through its elements once). */
    int32_t *idstamp;
    int32_t idgen;
    /* The outer faces of brick parts' surfaces, made at the first /SURF/PART
     * card that names a brick part: the class of each face slot (see
     * ctd_brick_face_classes), a stamp per class and its generation, and
     * room for one card's bricks. */
    ct_idx *fcls;    /* [6 nb] */
    int32_t *fstamp; /* [6 nb] */
    int32_t fgen;
    ct_idx *fbrk;    /* [nb] */
} ctd_rad_res;

/* Release the resolution state (nl: the number of list cards). */
void ctd_rad_res_free(ctd_rad_res *z, size_t nl);

/* Room for `need` segments in the segment arrays. */
int ctd_rad_seg_room(ctd_rad_res *z, size_t need);

/* "/SHELL", "/SH3N" or "/BRICK" for an enum ctd_seg_kind. */
const char *ctd_rad_kind_kw(int kind);

/* Nodes: the id map (a repeated id is an error) and the ct_nodes. */
int ctd_rad_res_nodes(ctd_rad_reader *r, ctd_rad_res *z);

/* Elements: segments, bricks, element id maps, dense part indices. */
int ctd_rad_res_elems(ctd_rad_reader *r, ctd_rad_res *z);

/* ---- Outer faces of bricks (import_radioss_bricks.c) ------------------ */

/* ctd_brick_face_classes and ctd_brick_select_outer: import_radioss.h. */

/* ---- Sets (import_radioss_sets.c) -------------------------------------- */

/* The /GRSHEL lists resolved to segment indices. */
int ctd_rad_res_grshel(ctd_rad_reader *r, ctd_rad_res *z);

/* Surfaces and groups into d, in file order; ids unique per kind. */
int ctd_rad_res_sets(ctd_rad_reader *r, ctd_rad_res *z, ctd_deck *d);

#endif /* CTD_IMPORT_RADIOSS_INTERNAL_H */
