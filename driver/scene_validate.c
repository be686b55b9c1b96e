/*
 * scene_validate.c -- the checks after a scene's typed load: defaults for
 * absent fields, enum names, ranges of numbers, and references between
 * parts, meshes, bodies, selections and imported decks (see scene.h).
 */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"
#include "scene_internal.h"

const char *const cti_elem_names[CTD_ELEM_NKIND] = {"brick", "shell", "truss", "spring",
                                                       "rigid"};
const char *const cti_gen_names[CTD_GEN_NKIND] = {"plate", "block", "sphere", "ball",
                                                  "tube",  "folded", "net",  "rod"};
const char *const cti_bc_names[CTD_BC_NKIND] = {"fixed", "velocity", "initial_velocity",
                                                "gravity", "force", "pressure"};

typedef struct vctx {
    ctd_scene *sc;
    cti_errs *e;
    int deck_failed; /* an import failed: references into decks are not checked */
    int64_t refine;  /* > 0: replaces the file's refine */
    char p[160];     /* scratch path */
} vctx;

/* The path built from a format (into v->p). */
static const char *P(vctx *v, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static const char *P(vctx *v, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->p, sizeof v->p, fmt, ap);
    va_end(ap);
    return v->p;
}

static int has(vctx *v, const char *path) { return cti_ynode_at(v->e->root, path) != NULL; }

/* A number: finite and, unless NaN bounds, in [lo, hi] or (lo, hi) when
 * open. `expect` words the range. Returns 1 when fine. */
static int num(vctx *v, const char *path, double x, double lo, int lo_open, double hi,
               int hi_open, const char *expect)
{
    if (!isfinite(x)) {
        cti_err(v->e, CT_ERR_NONFINITE, 0, path, "expected a finite number (%s), got %g", expect,
                x);
        return 0;
    }
    int ok = (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
    if (!ok)
        cti_err(v->e, CT_ERR_ARG, 0, path, "expected %s, got %.17g", expect, x);
    return ok;
}

static int name_index(const char *s, const char *const *names, int n)
{
    for (int i = 0; s && i < n; i++)
        if (strcmp(s, names[i]) == 0)
            return i;
    return -1;
}

static void join(char *buf, size_t len, const char *const *names, int n)
{
    size_t off = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && off < len; i++)
        off += (size_t)snprintf(buf + off, len - off, "%s%s", i ? ", " : "", names[i]);
}

static int enum_field(vctx *v, const char *path, const char *s, const char *const *names, int n)
{
    int k = name_index(s, names, n);
    if (k < 0) {
        char all[256];
        join(all, sizeof all, names, n);
        cti_err(v->e, CT_ERR_ARG, 0, path, "expected one of %s, got '%s'", all, s ? s : "");
    }
    return k;
}

/* ---- where filters -------------------------------------------------------- */

static int parse_where(const char *s, ctd_where *w)
{
    w->n = 0;
    const char *p = s;
    for (;;) {
        while (isspace((unsigned char)*p))
            p++;
        if (w->n == CTD_WHERE_MAX || (*p != 'x' && *p != 'y' && *p != 'z'))
            return -1;
        w->axis[w->n] = *p - 'x';
        p++;
        while (isspace((unsigned char)*p))
            p++;
        int op;
        if (p[0] == '<' && p[1] == '=')
            op = CTD_WHERE_LE, p += 2;
        else if (p[0] == '>' && p[1] == '=')
            op = CTD_WHERE_GE, p += 2;
        else if (p[0] == '<')
            op = CTD_WHERE_LT, p += 1;
        else if (p[0] == '>')
            op = CTD_WHERE_GT, p += 1;
        else
            return -1;
        w->op[w->n] = op;
        char *end;
        double val = strtod(p, &end);
        if (end == p || !isfinite(val))
            return -1;
        w->value[w->n++] = val;
        p = end;
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            return 0;
        if (strncmp(p, "and", 3) == 0 && isspace((unsigned char)p[3]))
            p += 3;
        else if (strncmp(p, "&&", 2) == 0)
            p += 2;
        else
            return -1;
    }
}

/* ---- References ----------------------------------------------------------- */

static const ctd_deck *deck_of(const ctd_scene *sc, unsigned i)
{
    return sc->mesh[i].import ? sc->mesh[i].import->deck : NULL;
}

static int node_exists(const ctd_scene *sc, int64_t id)
{
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        const ctd_scene_mesh *m = &sc->mesh[i];
        if (m->generate) {
            if (id >= m->first_id && (m->nnode < 0 || id < m->first_id + m->nnode))
                return 1;
        } else if (deck_of(sc, i) && ctd_deck_node(deck_of(sc, i), id) >= 0) {
            return 1;
        }
    }
    return 0;
}

static int part_ref(vctx *v, const char *path, int64_t id)
{
    if (ctd_scene_part_by_id(v->sc, id))
        return 1;
    cti_err(v->e, CT_ERR_RANGE, 0, path, "part %lld does not exist (expected an id listed in parts)",
            (long long)id);
    return 0;
}

enum { SEL_NODES = 1, SEL_SURF = 2 };

/* Check a selection; `allow` is SEL_NODES, SEL_SURF or both. */
static void check_sel(vctx *v, const char *base, ctd_scene_sel *s, int allow)
{
    char path[160];
    snprintf(path, sizeof path, "%s", base);
    s->line = cti_path_line(v->e->root, path);
    int nparts = (s->part != 0) + (s->parts_count > 0);
    int nnodes = (s->group != 0) + (s->ids_count > 0);
    int nsurf = s->surf != 0;
    if (!(allow & SEL_NODES) && nnodes) {
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.%s", path, s->group ? "group" : "ids"),
                "a surface is expected here: use part, parts or surf");
    } else if (!(allow & SEL_SURF) && nsurf) {
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.surf", path),
                "nodes are expected here: use part, parts, group, ids or where");
    } else if (allow == SEL_SURF && nparts + nsurf != 1) {
        cti_err(v->e, CT_ERR_ARG, 0, path, "expected exactly one of part, parts, surf");
    } else if (nparts + nnodes + nsurf == 0 && !s->where_text) {
        cti_err(v->e, CT_ERR_ARG, 0, path, "empty selection, expected one of %s",
                allow == SEL_NODES ? "part, parts, group, ids, where"
                                   : "part, parts, surf, group, ids");
    } else if (nparts + nnodes + nsurf > 1) {
        cti_err(v->e, CT_ERR_ARG, 0, path, "expected only one of part, parts, surf, group, ids");
    }
    if (s->part)
        part_ref(v, P(v, "%s.part", path), s->part);
    for (unsigned k = 0; k < s->parts_count; k++)
        part_ref(v, P(v, "%s.parts[%u]", path, k), s->parts[k]);
    if ((s->surf || s->group) && !v->deck_failed) {
        int found = 0;
        for (unsigned i = 0; i < v->sc->mesh_count; i++) {
            const ctd_deck *d = deck_of(v->sc, i);
            if (d && (s->surf ? ctd_deck_surf(d, s->surf) != NULL
                              : ctd_deck_group(d, s->group) != NULL))
                found = 1;
        }
        if (!found)
            cti_err(v->e, CT_ERR_RANGE, 0, P(v, "%s.%s", path, s->surf ? "surf" : "group"),
                    "%s %lld does not exist (expected the id of a %s in an imported deck)",
                    s->surf ? "surface" : "node group", (long long)(s->surf ? s->surf : s->group),
                    s->surf ? "/SURF" : "/GRNOD");
    }
    for (unsigned k = 0; k < s->ids_count && !v->deck_failed; k++)
        if (!node_exists(v->sc, s->ids[k]))
            cti_err(v->e, CT_ERR_RANGE, 0, P(v, "%s.ids[%u]", path, k),
                    "node %lld does not exist (expected a node id of the meshes)",
                    (long long)s->ids[k]);
    memset(&s->where, 0, sizeof s->where);
    if (s->where_text && parse_where(s->where_text, &s->where) != 0)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.where", path),
                "expected at most %d clauses like 'z < 0.001' (x|y|z, <|<=|>|>=, a number) "
                "joined by 'and', got '%s'",
                CTD_WHERE_MAX, s->where_text);
}

/* ---- Meshes ---------------------------------------------------------------- */

/* Cells per kind, and which other fields each kind needs. */
static const struct {
    int ncells, nsize, radius, length, to, folded, elem_mask;
} kind_spec[CTD_GEN_NKIND] = {
#define SURF ((1 << CTD_ELEM_SHELL) | (1 << CTD_ELEM_RIGID))
#define SOLID ((1 << CTD_ELEM_BRICK) | (1 << CTD_ELEM_RIGID))
#define LINE ((1 << CTD_ELEM_TRUSS) | (1 << CTD_ELEM_SPRING) | (1 << CTD_ELEM_RIGID))
    [CTD_GEN_PLATE] = {2, 2, 0, 0, 0, 0, SURF},  [CTD_GEN_BLOCK] = {3, 3, 0, 0, 0, 0, SOLID},
    [CTD_GEN_SPHERE] = {1, 0, 1, 0, 0, 0, SURF}, [CTD_GEN_BALL] = {1, 0, 1, 0, 0, 0, SOLID},
    [CTD_GEN_TUBE] = {2, 0, 1, 1, 0, 0, SURF},   [CTD_GEN_FOLDED] = {2, 1, 0, 0, 0, 1, SURF},
    [CTD_GEN_NET] = {2, 2, 0, 0, 0, 0, LINE},    [CTD_GEN_ROD] = {1, 0, 0, 0, 1, 0, LINE},
};

static int64_t gen_nodes(const ctd_scene_generate *g)
{
    const int64_t *c = g->cells_eff;
    switch (g->kind) {
    case CTD_GEN_PLATE:
    case CTD_GEN_NET: return (c[0] + 1) * (c[1] + 1);
    case CTD_GEN_BLOCK: return (c[0] + 1) * (c[1] + 1) * (c[2] + 1);
    case CTD_GEN_SPHERE: return 6 * c[0] * c[0] + 2;
    case CTD_GEN_BALL: return (c[0] + 1) * (c[0] + 1) * (c[0] + 1);
    case CTD_GEN_TUBE: return c[0] * (c[1] + 1);
    case CTD_GEN_ROD: return c[0] + 1;
    case CTD_GEN_FOLDED: {
        ct_mesh m;
        double h = g->size[0];
        if (ctd_folded(&m, (int)g->layers, (int)c[0], (int)c[1], h, g->spacing) != CT_OK)
            return -1;
        int64_t n = m.nodes.n;
        ct_mesh_destroy(&m);
        return n;
    }
    default: return -1;
    }
}

static void check_generate(vctx *v, unsigned i, ctd_scene_generate *g)
{
    char b[96];
    snprintf(b, sizeof b, "mesh[%u].generate", i);
    g->kind = enum_field(v, P(v, "%s.kind", b), g->kind_name, cti_gen_names, CTD_GEN_NKIND);
    memset(g->cells_eff, 0, sizeof g->cells_eff);
    if (g->kind < 0)
        return;
    int nerr = v->e->count;
    int k = g->kind;
    const ctd_scene_part *part = ctd_scene_part_by_id(v->sc, g->part);
    if (part_ref(v, P(v, "%s.part", b), g->part) && !(kind_spec[k].elem_mask >> part->element & 1))
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.part", b),
                "part %lld has element %s, which a %s mesh cannot have (expected %s)",
                (long long)g->part, part->element_name, g->kind_name,
                kind_spec[k].elem_mask == SURF    ? "shell or rigid"
                : kind_spec[k].elem_mask == SOLID ? "brick or rigid"
                                                  : "truss, spring or rigid");
    if ((int)g->cells_count != kind_spec[k].ncells)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.cells", b),
                "expected a list of %d integers for kind %s, got %u", kind_spec[k].ncells,
                g->kind_name, g->cells_count);
    for (unsigned j = 0; j < g->cells_count && j < 3; j++) {
        if (g->cells[j] < 1 || g->cells[j] > 100000000)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.cells[%u]", b, j),
                    "expected an integer in 1 .. 1e8, got %lld", (long long)g->cells[j]);
        else if (g->cells[j] * v->sc->refine > 100000000)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.cells[%u]", b, j),
                    "cells times refine is %lld, expected at most 1e8",
                    (long long)(g->cells[j] * v->sc->refine));
        else
            g->cells_eff[j] = g->cells[j] * v->sc->refine;
    }
    if (kind_spec[k].nsize && (int)g->size_count != kind_spec[k].nsize)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.size", b),
                "expected a list of %d numbers for kind %s, got %s", kind_spec[k].nsize,
                g->kind_name, g->size ? "another count" : "nothing");
    else if (!kind_spec[k].nsize && g->size)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.size", b), "not used by kind %s", g->kind_name);
    for (unsigned j = 0; j < g->size_count; j++)
        num(v, P(v, "%s.size[%u]", b, j), g->size[j], 0, 1, INFINITY, 0, "a number > 0");
    for (int j = 0; j < 3; j++)
        num(v, P(v, "%s.origin[%d]", b, j), g->origin[j], -INFINITY, 0, INFINITY, 0,
            "a finite number");
    struct {
        const char *key;
        int need;
        double val;
    } opt[] = {{"radius", kind_spec[k].radius, g->radius},
               {"length", kind_spec[k].length, g->length},
               {"spacing", kind_spec[k].folded, g->spacing}};
    for (int j = 0; j < 3; j++) {
        const char *pth = P(v, "%s.%s", b, opt[j].key);
        if (opt[j].need && !has(v, pth))
            cti_err(v->e, CT_ERR_ARG, 0, pth, "required field missing for kind %s (expected a "
                    "number > 0)", g->kind_name);
        else if (opt[j].need)
            num(v, pth, opt[j].val, 0, 1, INFINITY, 0, "a number > 0");
        else if (has(v, pth))
            cti_err(v->e, CT_ERR_ARG, 0, pth, "not used by kind %s", g->kind_name);
    }
    const char *pl = P(v, "%s.layers", b);
    if (kind_spec[k].folded && (!has(v, pl) || g->layers < 1))
        cti_err(v->e, CT_ERR_ARG, 0, pl, "expected an integer >= 1 for kind folded, got %s",
                has(v, pl) ? "less" : "nothing");
    const char *pt = P(v, "%s.to", b);
    if (kind_spec[k].to && !has(v, pt))
        cti_err(v->e, CT_ERR_ARG, 0, pt, "required field missing for kind rod (expected a list "
                "of 3 numbers)");
    else if (kind_spec[k].to && g->to[0] == g->origin[0] && g->to[1] == g->origin[1] &&
             g->to[2] == g->origin[2])
        cti_err(v->e, CT_ERR_ARG, 0, pt, "expected a point other than origin");
    if (g->tri && k != CTD_GEN_PLATE)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.tri", b), "only used by kind plate");
    v->sc->mesh[i].nnode = v->e->count == nerr ? gen_nodes(g) : -1;
}

static void check_import(vctx *v, unsigned i, ctd_scene_import *im)
{
    const char *pf = P(v, "mesh[%u].import.file", i);
    char pfile[96];
    snprintf(pfile, sizeof pfile, "%s", pf);
    const char *dir = im->file[0] == '/' ? "" : v->sc->dir;
    size_t len = strlen(dir) + strlen(im->file) + 1;
    im->path = malloc(len);
    im->deck = calloc(1, sizeof *im->deck);
    if (!im->path || !im->deck) {
        cti_err(v->e, CT_ERR_NOMEM, 0, pfile, "out of memory");
        return;
    }
    snprintf(im->path, len, "%s%s", dir, im->file);
    ct_diag d = {0};
    int rc = ctd_deck_read(im->path, im->deck, &d);
    if (rc != CT_OK) {
        free(im->deck);
        im->deck = NULL;
        v->deck_failed = 1;
        cti_err(v->e, rc, 0, pfile, "cannot load the Radioss deck: %s", d.msg);
        return;
    }
    /* Every part with elements must be described in `parts`. */
    const ctd_deck *dk = im->deck;
    for (int64_t s = 0; s < (int64_t)dk->nelemseg + dk->nbrick; s++) {
        int64_t id = s < dk->nelemseg ? dk->seg_part[s] : dk->brick_part[s - dk->nelemseg];
        int line = s < dk->nelemseg ? dk->seg_line[s] : dk->brick_line[s - dk->nelemseg];
        if (!ctd_scene_part_by_id(v->sc, id)) {
            cti_err(v->e, CT_ERR_RANGE, 0, pfile,
                    "the deck's part %lld (used at %s:%d) is not in parts (expected an "
                    "entry {id: %lld, element: ..., material: ...})",
                    (long long)id, im->path, line, (long long)id);
            break;
        }
    }
}

static void check_meshes(vctx *v)
{
    ctd_scene *sc = v->sc;
    int64_t next_id = 1;
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        ctd_scene_mesh *m = &sc->mesh[i];
        m->line = cti_path_line(v->e->root, P(v, "mesh[%u]", i));
        m->first_id = next_id;
        m->nnode = -1;
        if (!m->generate == !m->import) {
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "mesh[%u]", i),
                    m->generate ? "expected only one of generate, import, got both"
                                : "expected one of generate, import, got neither");
            continue;
        }
        if (m->generate) {
            check_generate(v, i, m->generate);
            if (m->nnode > 0)
                next_id = m->first_id + m->nnode;
        } else {
            check_import(v, i, m->import);
            const ctd_deck *d = m->import->deck;
            for (ct_idx k = 0; d && k < d->mesh.nodes.n; k++) {
                int64_t id = d->node_id[k];
                int clash = -1;
                for (unsigned j = 0; j < i && clash < 0; j++) {
                    const ctd_scene_mesh *o = &sc->mesh[j];
                    if (o->generate ? (o->nnode > 0 && id >= o->first_id &&
                                       id < o->first_id + o->nnode)
                                    : (deck_of(sc, j) && ctd_deck_node(deck_of(sc, j), id) >= 0))
                        clash = (int)j;
                }
                if (clash >= 0) {
                    cti_err(v->e, CT_ERR_ARG, 0, P(v, "mesh[%u].import.file", i),
                            "node id %lld of the deck (line %d) is already used by mesh[%d] "
                            "(expected distinct node ids; list imports before generated meshes)",
                            (long long)id, d->node_line[k], clash);
                    break;
                }
            }
            for (ct_idx k = 0; d && k < d->mesh.nodes.n; k++)
                if (d->node_id[k] >= next_id)
                    next_id = d->node_id[k] + 1;
            m->first_id = 0;
            m->nnode = d ? d->mesh.nodes.n : -1;
        }
    }
}

/* ---- Parts, bodies, boundary conditions ------------------------------------ */

static void check_parts(vctx *v)
{
    ctd_scene *sc = v->sc;
    for (unsigned i = 0; i < sc->parts_count; i++) {
        ctd_scene_part *p = &sc->parts[i];
        p->line = cti_path_line(v->e->root, P(v, "parts[%u]", i));
        if (p->id <= 0)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "parts[%u].id", i), "expected an integer > 0, got %lld",
                    (long long)p->id);
        for (unsigned j = 0; j < i; j++)
            if (sc->parts[j].id == p->id) {
                cti_err(v->e, CT_ERR_ARG, 0, P(v, "parts[%u].id", i),
                        "part %lld is defined twice (first at line %d), expected a new id",
                        (long long)p->id, sc->parts[j].line);
                break;
            }
        p->element = enum_field(v, P(v, "parts[%u].element", i), p->element_name, cti_elem_names,
                                CTD_ELEM_NKIND);
        num(v, P(v, "parts[%u].material.E", i), p->material.E, 0, 1, INFINITY, 0,
            "a number > 0");
        num(v, P(v, "parts[%u].material.nu", i), p->material.nu, -1, 1, 0.5, 1,
            "a number in (-1, 0.5)");
        num(v, P(v, "parts[%u].material.rho", i), p->material.rho, 0, 1, INFINITY, 0,
            "a number > 0");
        static const char *const keys[3] = {"thickness", "area", "stiffness"};
        const int need[3] = {CTD_ELEM_SHELL, CTD_ELEM_TRUSS, CTD_ELEM_SPRING};
        const double val[3] = {p->thickness, p->area, p->stiffness};
        for (int k = 0; k < 3; k++) {
            const char *pth = P(v, "parts[%u].%s", i, keys[k]);
            if (p->element == need[k] && !has(v, pth))
                cti_err(v->e, CT_ERR_ARG, 0, pth,
                        "required field missing for element %s (expected a number > 0)",
                        p->element_name);
            else if (has(v, pth))
                num(v, pth, val[k], 0, 1, INFINITY, 0, "a number > 0");
        }
    }
}

static void check_rigid(vctx *v)
{
    ctd_scene *sc = v->sc;
    for (unsigned i = 0; i < sc->rigid_bodies_count; i++) {
        ctd_scene_rigid *r = &sc->rigid_bodies[i];
        r->line = cti_path_line(v->e->root, P(v, "rigid_bodies[%u]", i));
        if (r->id <= 0)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "rigid_bodies[%u].id", i),
                    "expected an integer > 0, got %lld", (long long)r->id);
        for (unsigned j = 0; j < i; j++) {
            if (sc->rigid_bodies[j].id == r->id)
                cti_err(v->e, CT_ERR_ARG, 0, P(v, "rigid_bodies[%u].id", i),
                        "rigid body %lld is defined twice (first at line %d)", (long long)r->id,
                        sc->rigid_bodies[j].line);
            if (sc->rigid_bodies[j].part == r->part)
                cti_err(v->e, CT_ERR_ARG, 0, P(v, "rigid_bodies[%u].part", i),
                        "part %lld already belongs to rigid body %lld", (long long)r->part,
                        (long long)sc->rigid_bodies[j].id);
        }
        const ctd_scene_part *p = ctd_scene_part_by_id(sc, r->part);
        if (part_ref(v, P(v, "rigid_bodies[%u].part", i), r->part) && p->element != CTD_ELEM_RIGID)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "rigid_bodies[%u].part", i),
                    "part %lld has element %s, expected a part with element rigid",
                    (long long)r->part, p->element_name);
    }
}

/* The fields of the loads (force, pressure): surface, pressure, curve. */
static void check_load(vctx *v, unsigned i, ctd_scene_bc *b)
{
    const int pres = b->kind == CTD_BC_PRESSURE, load = pres || b->kind == CTD_BC_FORCE;
    const char *ps = P(v, "boundary[%u].surface", i);
    if (pres && !b->surface)
        cti_err(v->e, CT_ERR_ARG, 0, ps,
                "required field missing for kind pressure (expected a surface selection)");
    else if (!pres && b->surface)
        cti_err(v->e, CT_ERR_ARG, 0, ps, "only used by kind pressure");
    else if (b->surface)
        check_sel(v, ps, b->surface, SEL_SURF);
    const char *pp = P(v, "boundary[%u].pressure", i);
    if (pres && !has(v, pp))
        cti_err(v->e, CT_ERR_ARG, 0, pp,
                "required field missing for kind pressure (expected a finite number, Pa)");
    else if (!pres && has(v, pp))
        cti_err(v->e, CT_ERR_ARG, 0, pp, "only used by kind pressure");
    else if (pres)
        num(v, pp, b->pressure, -INFINITY, 0, INFINITY, 0, "a finite number");
    if (b->curve && !load) {
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "boundary[%u].curve", i),
                "only used by kinds force and pressure");
        return;
    }
    for (unsigned k = 0; b->curve && k < b->curve_count; k++) {
        num(v, P(v, "boundary[%u].curve[%u][0]", i, k), b->curve[k][0], -INFINITY, 0, INFINITY,
            0, "a finite time");
        num(v, P(v, "boundary[%u].curve[%u][1]", i, k), b->curve[k][1], -INFINITY, 0, INFINITY,
            0, "a finite factor");
        if (k > 0 && !(b->curve[k][0] > b->curve[k - 1][0]))
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "boundary[%u].curve[%u][0]", i, k),
                    "expected times in strictly ascending order, got %g after %g",
                    b->curve[k][0], b->curve[k - 1][0]);
    }
}

static void check_boundary(vctx *v)
{
    ctd_scene *sc = v->sc;
    for (unsigned i = 0; i < sc->boundary_count; i++) {
        ctd_scene_bc *b = &sc->boundary[i];
        b->line = cti_path_line(v->e->root, P(v, "boundary[%u]", i));
        b->kind = enum_field(v, P(v, "boundary[%u].kind", i), b->kind_name, cti_bc_names,
                             CTD_BC_NKIND);
        b->dof[0] = b->dof[1] = b->dof[2] = 1;
        if (b->kind < 0)
            continue;
        const int pres = b->kind == CTD_BC_PRESSURE;
        if ((b->kind == CTD_BC_GRAVITY || pres) && b->nodes)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "boundary[%u].nodes", i),
                    pres ? "not used by pressure (it loads a surface: give surface)"
                         : "not used by gravity (it acts on every node)");
        else if (b->kind != CTD_BC_GRAVITY && !pres && !b->nodes)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "boundary[%u].nodes", i),
                    "required field missing for kind %s (expected a node selection)", b->kind_name);
        else if (b->nodes)
            check_sel(v, P(v, "boundary[%u].nodes", i), b->nodes, SEL_NODES);
        check_load(v, i, b);
        int want_value = b->kind != CTD_BC_FIXED && !pres;
        if (want_value && !b->value)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "boundary[%u].value", i),
                    "required field missing for kind %s (expected a list of 3 numbers)",
                    b->kind_name);
        else if (!want_value && b->value)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "boundary[%u].value", i), "not used by kind %s%s",
                    b->kind_name, pres ? " (give pressure)" : "");
        for (unsigned k = 0; k < b->value_count; k++)
            num(v, P(v, "boundary[%u].value[%u]", i, k), b->value[k], -INFINITY, 0, INFINITY, 0,
                "a finite number");
        if (b->dofs) {
            const char *pd = P(v, "boundary[%u].dofs", i);
            int bad = b->kind != CTD_BC_FIXED && b->kind != CTD_BC_VELOCITY;
            if (bad) {
                cti_err(v->e, CT_ERR_ARG, 0, pd, "only used by kinds fixed and velocity");
                continue;
            }
            b->dof[0] = b->dof[1] = b->dof[2] = 0;
            for (const char *c = b->dofs; *c; c++) {
                int a = *c - 'x';
                if (a < 0 || a > 2 || b->dof[a])
                    bad = 1;
                else
                    b->dof[a] = 1;
            }
            if (bad || !b->dofs[0])
                cti_err(v->e, CT_ERR_ARG, 0, pd,
                        "expected some of the letters x, y, z (each once), got '%s'", b->dofs);
        }
    }
}

/* ---- Interfaces ------------------------------------------------------------ */

static void check_interface(vctx *v, unsigned i, ctd_scene_interface *f)
{
    char b[64];
    snprintf(b, sizeof b, "interfaces[%u]", i);
    f->line = cti_path_line(v->e->root, b);
    snprintf(f->label, sizeof f->label, "%s", f->name ? f->name : "");
    if (!f->name)
        snprintf(f->label, sizeof f->label, "if%u", i);
    const int64_t t = f->type;
    if (t != 3 && t != 5 && t != 6 && t != 7 && t != 11 && t != 24) {
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.type", b),
                "expected one of 3, 5, 6, 7, 11, 24, got %lld", (long long)t);
        return;
    }
    /* Selections: main is a surface; secondary per type. */
    check_sel(v, P(v, "%s.main", b), f->main, SEL_SURF);
    f->self = f->secondary == NULL;
    if (f->self && (t == 3 || t == 5 || t == 6))
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.secondary", b),
                "required field missing for type %lld (expected a %s selection)", (long long)t,
                t == 5 ? "node" : "surface");
    else if (f->secondary)
        check_sel(v, P(v, "%s.secondary", b), f->secondary,
                  (t == 3 || t == 6 || t == 11) ? SEL_SURF
                  : (t == 5 || t == 7)          ? SEL_NODES
                                                : SEL_NODES | SEL_SURF);
    if (f->grnd_IDs && t != 24)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.grnd_IDs", b), "only used by type 24");
    else if (f->grnd_IDs)
        check_sel(v, P(v, "%s.grnd_IDs", b), f->grnd_IDs, SEL_NODES);
    /* TYPE6: both sides on rigid parts, and the force curve. */
    if (t == 6) {
        ctd_scene_sel *side[2] = {f->main, f->secondary};
        for (int s = 0; s < 2; s++) {
            if (!side[s])
                continue;
            int64_t pid = side[s]->part ? side[s]->part
                          : side[s]->parts_count ? side[s]->parts[0]
                                                 : 0;
            const ctd_scene_part *p = pid ? ctd_scene_part_by_id(v->sc, pid) : NULL;
            if (p && p->element != CTD_ELEM_RIGID)
                cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.%s", b, s ? "secondary" : "main"),
                        "part %lld has element %s; type 6 expects a part with element rigid",
                        (long long)pid, p->element_name);
        }
        if (!f->curve)
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.curve", b),
                    "required field missing for type 6 (expected [[p0, F0], [p1, F1], ...])");
    } else if (f->curve) {
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.curve", b), "only used by type 6");
    }
    if (f->curve && f->curve_count < 2)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.curve", b), "expected at least 2 points, got %u",
                f->curve_count);
    for (unsigned k = 0; f->curve && k < f->curve_count; k++) {
        num(v, P(v, "%s.curve[%u][0]", b, k), f->curve[k][0], 0, 0, INFINITY, 0,
            "a penetration >= 0");
        num(v, P(v, "%s.curve[%u][1]", b, k), f->curve[k][1], 0, 0, INFINITY, 0, "a force >= 0");
        if (k > 0 && !(f->curve[k][0] > f->curve[k - 1][0]))
            cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.curve[%u][0]", b, k),
                    "expected penetrations in strictly ascending order, got %g after %g",
                    f->curve[k][0], f->curve[k - 1][0]);
    }
    /* Search. */
    static const char *const search_names[] = {"direct", "topological", "bucket", "bsp"};
    if (f->search_name)
        f->search = enum_field(v, P(v, "%s.search", b), f->search_name, search_names, 4);
    else
        f->search = (t == 3 || t == 5) ? CT_SEARCH_TOPO : CT_SEARCH_BUCKET;
    /* Defaults of the card fields that are not zero. */
    if (!has(v, P(v, "%s.Stfac", b)))
        f->Stfac = (t == 3 || t == 5 || t == 6) ? 0.2 : 1.0;
    if (!has(v, P(v, "%s.VisS", b)))
        f->VisS = (t == 7 || t == 11) ? 0.05 : t == 24 ? 1.0 : 0.0;
    /* Integer flags. */
    if (!(f->Istf >= 0 && f->Istf <= 5) && f->Istf != 1000)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Istf", b),
                "expected one of 0, 1, 2, 3, 4, 5, 1000, got %lld", (long long)f->Istf);
    if (f->Igap0 < 0 || f->Igap0 > 1)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Igap0", b), "expected 0 or 1, got %lld",
                (long long)f->Igap0);
    if (f->Ipen0 < 0 || f->Ipen0 > 1)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Ipen0", b), "expected 0 or 1, got %lld",
                (long long)f->Ipen0);
    if (f->Inacti < -1 || (f->Inacti > 6 && f->Inacti != 1000) || f->Inacti == 4)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Inacti", b),
                "expected one of -1, 0, 1, 2, 3, 5, 6, 1000, got %lld", (long long)f->Inacti);
    if (f->Ifric < 0 || f->Ifric > 4)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Ifric", b), "expected an integer in 0..4, got %lld",
                (long long)f->Ifric);
    if (f->Ifiltr < 0 || f->Ifiltr > 3)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Ifiltr", b),
                "expected an integer in 0..3, got %lld", (long long)f->Ifiltr);
    /* Numbers. */
    num(v, P(v, "%s.Stfac", b), f->Stfac, 0, 1, INFINITY, 0, "a number > 0");
    num(v, P(v, "%s.Stmin", b), f->Stmin, 0, 0, INFINITY, 0, "a number >= 0");
    if (num(v, P(v, "%s.Stmax", b), f->Stmax, 0, 0, INFINITY, 0, "a number >= 0 (0: no limit)") &&
        f->Stmax > 0 && f->Stmax < f->Stmin)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Stmax", b), "expected a number >= Stmin (%g), got %g",
                f->Stmin, f->Stmax);
    num(v, P(v, "%s.gap", b), f->gap, 0, 0, INFINITY, 0, "a number >= 0 (0: automatic)");
    num(v, P(v, "%s.Gap_max_s", b), f->Gap_max_s, 0, 0, INFINITY, 0, "a number >= 0");
    num(v, P(v, "%s.Gap_max_m", b), f->Gap_max_m, 0, 0, INFINITY, 0, "a number >= 0");
    num(v, P(v, "%s.Ipen_max", b), f->Ipen_max, 0, 0, INFINITY, 0, "a number >= 0");
    num(v, P(v, "%s.VisS", b), f->VisS, 0, 0, INFINITY, 0, "a number >= 0");
    num(v, P(v, "%s.Fric", b), f->Fric, 0, 0, INFINITY, 0, "a number >= 0");
    const double C[6] = {f->C1, f->C2, f->C3, f->C4, f->C5, f->C6};
    for (int k = 0; k < 6; k++)
        num(v, P(v, "%s.C%d", b, k + 1), C[k], -INFINITY, 0, INFINITY, 0, "a finite number");
    if (f->Ifric == 3 && !(f->C5 > 0 && f->C6 > f->C5))
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.C5", b),
                "Renard friction (Ifric 3) expects 0 < C5 < C6, got C5 = %g, C6 = %g", f->C5, f->C6);
    if (f->Ifric == 4 && f->C2 < 0)
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.C2", b),
                "Ifric 4 expects a decay rate C2 >= 0, got %g", f->C2);
    const char *px = P(v, "%s.Xfreq", b);
    char pxs[96];
    snprintf(pxs, sizeof pxs, "%s", px);
    if (f->Ifiltr == 1)
        num(v, pxs, f->Xfreq, 0, 1, 1, 0, "a number in (0, 1] for Ifiltr 1");
    else if (f->Ifiltr == 2)
        num(v, pxs, f->Xfreq, 6.283185307179586, 0, INFINITY, 0, "a number >= 2 pi for Ifiltr 2");
    else if (f->Ifiltr == 3)
        num(v, pxs, f->Xfreq, 0, 1, INFINITY, 0, "a number > 0 for Ifiltr 3");
    else
        num(v, pxs, f->Xfreq, -INFINITY, 0, INFINITY, 0, "a finite number");
    num(v, P(v, "%s.Tstart", b), f->Tstart, 0, 0, INFINITY, 0, "a time >= 0");
    if (num(v, P(v, "%s.Tstop", b), f->Tstop, 0, 0, INFINITY, 0, "a time >= 0 (0: never)") &&
        f->Tstop > 0 && !(f->Tstop > f->Tstart))
        cti_err(v->e, CT_ERR_ARG, 0, P(v, "%s.Tstop", b), "expected a time > Tstart (%g), got %g",
                f->Tstart, f->Tstop);
}

/* ---- Top level ------------------------------------------------------------- */

static int check_top(vctx *v)
{
    ctd_scene *sc = v->sc;
    num(v, "end_time", sc->end_time, 0, 1, INFINITY, 0, "a number > 0");
    if (!has(v, "refine"))
        sc->refine = 1;
    else if (sc->refine < 1 || sc->refine > 1000) {
        cti_err(v->e, CT_ERR_ARG, 0, "refine", "expected an integer in 1..1000, got %lld",
                (long long)sc->refine);
        sc->refine = 1;
    }
    if (v->refine > 1000)
        cti_err(v->e, CT_ERR_ARG, 0, "refine", "expected an integer in 1..1000 from the "
                "caller, got %lld", (long long)v->refine);
    else if (v->refine > 0)
        sc->refine = v->refine;
    if (!sc->output && !(sc->output = calloc(1, sizeof *sc->output)))
        return CT_ERR_NOMEM;
    if (!sc->solver && !(sc->solver = calloc(1, sizeof *sc->solver)))
        return CT_ERR_NOMEM;
    ctd_scene_output *o = sc->output;
    if (!has(v, "output.vtu"))
        o->vtu = true;
    if (!has(v, "output.csv"))
        o->csv = true;
    if (!has(v, "output.every"))
        o->every = isfinite(sc->end_time) && sc->end_time > 0 ? sc->end_time / 100 : 1.0;
    else
        num(v, "output.every", o->every, 0, 1, INFINITY, 0, "a number > 0");
    if (o->dir && !o->dir[0])
        cti_err(v->e, CT_ERR_ARG, 0, "output.dir", "expected a directory name, got ''");
    if (o->dir) {
        sc->out_dir = strdup(o->dir);
    } else {
        const char *base = strrchr(sc->path, '/');
        base = base ? base + 1 : sc->path;
        size_t n = strlen(base);
        if (n > 5 && strcmp(base + n - 5, ".yaml") == 0)
            n -= 5;
        else if (n > 4 && strcmp(base + n - 4, ".yml") == 0)
            n -= 4;
        sc->out_dir = malloc(n + 5);
        if (sc->out_dir)
            snprintf(sc->out_dir, n + 5, "out/%.*s", (int)n, base);
    }
    if (!sc->out_dir)
        return CT_ERR_NOMEM;
    if (!has(v, "solver.dt_scale"))
        sc->solver->dt_scale = 0.9;
    else
        num(v, "solver.dt_scale", sc->solver->dt_scale, 0, 1, 1, 0, "a number in (0, 1]");
    if (sc->solver->threads < 0 || sc->solver->threads > 4096)
        cti_err(v->e, CT_ERR_ARG, 0, "solver.threads",
                "expected an integer in 0..4096 (0: OpenMP's default), got %lld",
                (long long)sc->solver->threads);
    return CT_OK;
}

int cti_scene_validate(ctd_scene *sc, cti_errs *e, int64_t refine)
{
    vctx v = {.sc = sc, .e = e, .refine = refine};
    int rc = check_top(&v);
    if (rc != CT_OK)
        return cti_err(e, rc, 0, "", "out of memory");
    check_parts(&v);
    check_meshes(&v);
    check_rigid(&v);
    check_boundary(&v);
    for (unsigned i = 0; i < sc->interfaces_count; i++)
        check_interface(&v, i, &sc->interfaces[i]);
    return e->count ? e->code : CT_OK;
}
