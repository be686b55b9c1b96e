/*
 * scene.c -- loading a scene file: the libyaml tree (lines), the typed load
 * through libcyaml, then the checks (scene_validate.c); `contact check`.
 */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scene_internal.h"

/* ---- Names --------------------------------------------------------------- */

const char *ctd_element_name(int e) { return e >= 0 && e < CTD_ELEM_NKIND ? cti_elem_names[e] : "?"; }
const char *ctd_gen_kind_name(int k) { return k >= 0 && k < CTD_GEN_NKIND ? cti_gen_names[k] : "?"; }
const char *ctd_bc_kind_name(int k) { return k >= 0 && k < CTD_BC_NKIND ? cti_bc_names[k] : "?"; }

const ctd_scene_part *ctd_scene_part_by_id(const ctd_scene *sc, int64_t id)
{
    for (unsigned i = 0; sc && i < sc->parts_count; i++)
        if (sc->parts[i].id == id)
            return &sc->parts[i];
    return NULL;
}

int ctd_where_eval(const ctd_where *w, double x, double y, double z)
{
    const double c[3] = {x, y, z};
    for (int i = 0; i < w->n; i++) {
        double v = c[w->axis[i]], r = w->value[i];
        int ok = 0;
        switch (w->op[i]) {
        case CTD_WHERE_LT: ok = v < r; break;
        case CTD_WHERE_LE: ok = v <= r; break;
        case CTD_WHERE_GT: ok = v > r; break;
        default: ok = v >= r; break;
        }
        if (!ok)
            return 0;
    }
    return 1;
}

/* ---- libcyaml configuration with a captured log ---------------------------- */

typedef struct logbuf {
    char text[8192];
    size_t len;
} logbuf;

static void log_capture(cyaml_log_t level, void *ctx, const char *fmt, va_list args)
{
    (void)level;
    logbuf *b = ctx;
    if (b && b->len < sizeof b->text - 1) {
        int n = vsnprintf(b->text + b->len, sizeof b->text - b->len, fmt, args);
        if (n > 0)
            b->len += (size_t)n;
        if (b->len >= sizeof b->text)
            b->len = sizeof b->text - 1;
    }
}

/* libcyaml's allocator (cyaml_mem's contract: size 0 frees), in the
 * project's code so that the tests' allocation wrappers see libcyaml's
 * allocations too (tests/alloc_fail.h). */
static void *scene_mem(void *ctx, void *ptr, size_t size)
{
    (void)ctx;
    if (size == 0) {
        free(ptr);
        return NULL;
    }
    return realloc(ptr, size);
}

static cyaml_config_t config(logbuf *b)
{
    cyaml_config_t c;
    memset(&c, 0, sizeof c);
    c.log_fn = b ? log_capture : NULL;
    c.log_ctx = b;
    c.mem_fn = scene_mem;
    c.log_level = CYAML_LOG_ERROR;
    /* Aliases are allowed: the YAML tree (scene_yaml_read.c) has checked them
     * (each names an anchor before it, no cycle, a bounded number of
     * copies) before libcyaml reads the file. */
    c.flags = 0;
    return c;
}

/* ---- Numbers and booleans read in full ---------------------------------------- */

/* libcyaml (1.3.1) reads a number with strtoll(base 0)/strtod and ignores
 * whatever follows it: `part: 1e3` loads as 1, `cells: [2.5]` as 2,
 * `part: 010` as 8, `E: 2.1e11 7800` as 2.1e11. Re-read every scalar that the
 * schema types as a number, in full, and report the ones that are not. */
static int int_text_ok(const char *s)
{
    const char *p = s + (*s == '+' || *s == '-');
    if (!isdigit((unsigned char)*p))
        return 0;
    if (p[0] == '0' && p[1])
        return 0; /* 010 would be octal, 0x10 hexadecimal */
    while (isdigit((unsigned char)*p))
        p++;
    return *p == '\0';
}

static int float_text_ok(const char *s)
{
    char *end;
    (void)strtod(s, &end);
    return end != s && *end == '\0';
}

/* libcyaml reads a boolean as false when it is one of false, no, off,
 * disable or 0 (in any case) and as true otherwise: `csv: flase` wrote the
 * history. Only YAML's words are taken. */
static int bool_text_ok(const char *s)
{
    static const char *const words[] = {"true", "false", "yes", "no", "on", "off"};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        if (strcasecmp(s, words[i]) == 0)
            return 1;
    return 0;
}

static void check_numbers(cti_errs *e, const cti_ynode *n, const cyaml_schema_value_t *v,
                          char *path, size_t plen, size_t cap)
{
    if (!n || !v || plen >= cap)
        return;
    switch (v->type) {
    case CYAML_BOOL:
        if (n->kind == CTI_Y_SCALAR && !bool_text_ok(n->value)) {
            char q[80];
            cti_quote_value(n->value, q, sizeof q);
            cti_err(e, CT_ERR_ARG, n->line, path, "expected true or false, got %s", q);
        }
        return;
    case CYAML_INT:
    case CYAML_UINT:
    case CYAML_FLOAT:
        /* A list or a mapping here has been reported by libcyaml already. */
        if (n->kind == CTI_Y_SCALAR &&
            !(v->type == CYAML_FLOAT ? float_text_ok(n->value) : int_text_ok(n->value))) {
            char q[80];
            cti_quote_value(n->value, q, sizeof q);
            cti_err(e, CT_ERR_ARG, n->line, path, "expected %s, got %s",
                    v->type == CYAML_FLOAT ? "a number" : "a decimal integer", q);
        }
        return;
    case CYAML_MAPPING:
        if (n->kind != CTI_Y_MAP)
            return;
        for (int i = 0; i < n->n; i++) {
            const cyaml_schema_field_t *f = v->mapping.fields;
            while (f->key && !(n->key[i] && strcmp(f->key, n->key[i]) == 0))
                f++;
            if (!f->key)
                continue;
            int k = snprintf(path + plen, cap - plen, "%s%s", plen ? "." : "", f->key);
            if (k > 0)
                check_numbers(e, n->child[i], &f->value, path, plen + (size_t)k, cap);
            path[plen] = '\0';
        }
        return;
    case CYAML_SEQUENCE:
    case CYAML_SEQUENCE_FIXED:
        if (n->kind != CTI_Y_SEQ)
            return;
        for (int i = 0; i < n->n; i++) {
            int k = snprintf(path + plen, cap - plen, "[%d]", i);
            if (k > 0)
                check_numbers(e, n->child[i], v->sequence.entry, path, plen + (size_t)k, cap);
            path[plen] = '\0';
        }
        return;
    default:
        return;
    }
}

/* ---- Load / free ----------------------------------------------------------- */

void ctd_scene_free(ctd_scene *sc)
{
    if (!sc)
        return;
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        ctd_scene_import *im = sc->mesh[i].import;
        if (im) {
            free(im->path);
            im->path = NULL;
            if (im->deck) {
                ctd_deck_destroy(im->deck);
                free(im->deck);
                im->deck = NULL;
            }
        }
    }
    free(sc->path);
    free(sc->dir);
    free(sc->out_dir);
    cti_ynode_free(sc->internal);
    sc->path = sc->dir = sc->out_dir = NULL;
    sc->internal = NULL;
    cyaml_config_t c = config(NULL);
    cyaml_free(&c, &cti_scene_schema, sc, 0);
}

/* ---- A Radioss deck given as a scene ------------------------------------- */

/* The line of the first Radioss keyword of the file at path ('/' then a
 * capital letter at the start of a line, as /BEGIN or /NODE; no line of a
 * scene starts so, since a scene's top-level keys are lower case), with the
 * keyword in kw; 0 when the first CTI_DECK_SNIFF lines hold none. Called
 * only when the file failed to read as a scene: a deck reads as malformed
 * YAML or as a string, and libyaml's message for either says nothing of
 * what the file is. */
#define CTI_DECK_SNIFF 2000

static int deck_keyword_line(const char *path, char *kw, size_t kwlen)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    char buf[256];
    int line = 1, at_start = 1, found = 0;
    while (!found && line <= CTI_DECK_SNIFF && fgets(buf, sizeof buf, f)) {
        if (at_start && buf[0] == '/' && buf[1] >= 'A' && buf[1] <= 'Z') {
            size_t n = strcspn(buf, " \t\r\n");
            snprintf(kw, kwlen, "%.*s", (int)(n < 48 ? n : 48), buf);
            found = line;
        }
        at_start = strchr(buf, '\n') != NULL;
        line += at_start;
    }
    fclose(f);
    return found;
}

/* When path is a Radioss deck, replaces the read error of e by one that
 * says so and how a scene uses a deck. */
static void explain_deck(cti_errs *e, const char *path)
{
    char kw[64];
    int line = deck_keyword_line(path, kw, sizeof kw);
    if (!line || !e->out || e->out->count < 1)
        return;
    e->out->count = 0;
    e->count = 0;
    e->root = NULL; /* the tree, if any, is freed */
    cti_err(e, CT_ERR_ARG, line, "",
            "this is a Radioss deck (%s), not a scene: a scene reads a deck's mesh with "
            "`mesh: [{import: {file: DECK}}]` and gives the parts' materials, the boundary "
            "conditions and the interfaces (the format: driver/scene.h)",
            kw);
}

int ctd_scene_load(const char *path, ctd_scene **out, ctd_scene_err *err)
{
    return ctd_scene_load_refined(path, 0, out, err);
}

int ctd_scene_load_refined(const char *path, int64_t refine, ctd_scene **out,
                           ctd_scene_err *err)
{
    if (err)
        memset(err, 0, sizeof *err);
    if (out)
        *out = NULL;
    cti_errs e = {.file = path ? path : "(null)", .root = NULL, .out = err};
    if (!path || !out)
        return cti_err(&e, CT_ERR_ARG, 0, "", "no scene file given");
    int line, code;
    char field[256], msg[512];
    cti_ynode *root = cti_yaml_read(path, &code, &line, field, sizeof field, msg, sizeof msg);
    if (!root) {
        cti_err(&e, code, line, field, "%s", msg);
        if (code == CT_ERR_ARG && line > 0)
            explain_deck(&e, path);
        return e.code;
    }
    e.root = root;
    if (root->kind != CTI_Y_MAP) {
        char got[96], keys[400];
        cti_ynode_describe(root, got, sizeof got);
        cti_schema_expect("", 1, keys, sizeof keys);
        cti_err(&e, CT_ERR_ARG, root->line, "", "expected a mapping with keys %s, got %s", keys,
                got);
        cti_ynode_free(root);
        explain_deck(&e, path);
        return e.code;
    }
    logbuf *lb = calloc(1, sizeof *lb);
    if (!lb) {
        cti_ynode_free(root);
        return cti_err(&e, CT_ERR_NOMEM, 0, "", "out of memory");
    }
    cyaml_config_t c = config(lb);
    ctd_scene *sc = NULL;
    cyaml_err_t rc = cyaml_load_file(path, &c, &cti_scene_schema, (cyaml_data_t **)&sc, NULL);
    if (rc != CYAML_OK) {
        if (rc == CYAML_ERR_OOM)
            cti_err(&e, CT_ERR_NOMEM, 0, "", "out of memory");
        else
            cti_cyaml_error(&e, rc, lb->text);
        free(lb);
        if (sc) {
            cyaml_config_t c0 = config(NULL);
            cyaml_free(&c0, &cti_scene_schema, sc, 0);
        }
        cti_ynode_free(root);
        return e.code;
    }
    free(lb);
    {
        char npath[256] = "";
        check_numbers(&e, root, &cti_scene_schema, npath, 0, sizeof npath);
        if (e.count > 0) {
            cyaml_config_t c0 = config(NULL);
            cyaml_free(&c0, &cti_scene_schema, sc, 0);
            cti_ynode_free(root);
            return e.code;
        }
    }
    sc->internal = root;
    sc->path = strdup(path);
    const char *slash = strrchr(path, '/');
    sc->dir = slash ? strndup(path, (size_t)(slash - path + 1)) : strdup("");
    if (!sc->path || !sc->dir) {
        ctd_scene_free(sc);
        return cti_err(&e, CT_ERR_NOMEM, 0, "", "out of memory");
    }
    int rcv = cti_scene_validate(sc, &e, refine);
    if (rcv != CT_OK || e.count > 0) {
        ctd_scene_free(sc);
        return e.code ? e.code : rcv;
    }
    *out = sc;
    return CT_OK;
}

/* ---- What `contact check` and `contact run` print -------------------------- */

void ctd_scene_print_errors(FILE *f, const char *path, const ctd_scene_err *err)
{
    const char *p = path ? path : "(null)";
    int shown = err->count < CTD_SCENE_MAXERR ? err->count : CTD_SCENE_MAXERR;
    for (int i = 0; i < shown; i++)
        fprintf(f, "%s\n", err->msg[i].text); /* "FILE:LINE: FIELD: what" */
    if (err->count > shown)
        fprintf(f, "%s: %d more errors not shown\n", p, err->count - shown);
    if (err->code == CT_ERR_NOMEM)
        fprintf(f, "%s: scene not loaded: out of memory\n", p);
    else
        fprintf(f, "%s: invalid scene (%d error%s)\n", p, err->count, err->count == 1 ? "" : "s");
}

void ctd_scene_print_summary(FILE *f, const char *path, const ctd_scene *sc)
{
    int64_t nnode = 0;
    int known = 1;
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        if (sc->mesh[i].import)
            nnode += sc->mesh[i].import->deck->mesh.nodes.n;
        else if (sc->mesh[i].nnode >= 0)
            nnode += sc->mesh[i].nnode;
        else
            known = 0;
    }
    /* Rigid bodies as the model builds them: the listed ones, and each
     * rigid part listed in none (a body of its own). */
    unsigned nbody = sc->rigid_bodies_count;
    for (unsigned i = 0; i < sc->parts_count; i++) {
        if (sc->parts[i].element != CTD_ELEM_RIGID)
            continue;
        int listed = 0;
        for (unsigned b = 0; b < sc->rigid_bodies_count; b++)
            listed |= sc->rigid_bodies[b].part == sc->parts[i].id;
        nbody += !listed;
    }
    fprintf(f, "%s: ok: \"%s\", end_time %g, %u mesh%s (%s%lld nodes), %u part%s, %u rigid "
            "bod%s, %u boundary condition%s, %u interface%s, output to %s\n",
            path, sc->title ? sc->title : "", sc->end_time, sc->mesh_count,
            sc->mesh_count == 1 ? "" : "es", known ? "" : ">= ", (long long)nnode,
            sc->parts_count, sc->parts_count == 1 ? "" : "s", nbody, nbody == 1 ? "y" : "ies",
            sc->boundary_count, sc->boundary_count == 1 ? "" : "s", sc->interfaces_count,
            sc->interfaces_count == 1 ? "" : "s", sc->out_dir);
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        const ctd_deck *d = sc->mesh[i].import ? sc->mesh[i].import->deck : NULL;
        if (d && ctd_deck_warning(d)[0])
            fprintf(f, "%s: warning: %s: %s\n", path, sc->mesh[i].import->path,
                    ctd_deck_warning(d));
    }
}
