/*
 * scene_validate_mesh.c -- the checks of a scene's meshes: generated
 * shapes and their sizes, imported decks (scene_validate.c has the rest).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"
#include "scene_validate_internal.h"

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

/* The largest coordinate a generated mesh may reach: edges below 2e74, so
 * that an edge squared, squared, stays below 1e300 (kernels/mesh.c). */
#define GEN_MAXCOORD 1e74

/* The most nodes a generated mesh may have (meshgen's limit, ct_idx). */
#define GEN_MAXNODES ((int64_t)INT32_MAX - 64)

/* a b c, or INT64_MAX when it does not fit (cells are at most 1e8, so the
 * product of two factors does). */
static int64_t mul3(int64_t a, int64_t b, int64_t c)
{
    return a * b > INT64_MAX / c ? INT64_MAX : a * b * c;
}

static int64_t gen_nodes(const ctd_scene_generate *g)
{
    const int64_t *c = g->cells_eff;
    switch (g->kind) {
    case CTD_GEN_PLATE:
    case CTD_GEN_NET: return (c[0] + 1) * (c[1] + 1);
    case CTD_GEN_BLOCK: return mul3(c[0] + 1, c[1] + 1, c[2] + 1);
    case CTD_GEN_SPHERE: return 6 * c[0] * c[0] + 2;
    case CTD_GEN_BALL: return mul3(c[0] + 1, c[0] + 1, c[0] + 1);
    case CTD_GEN_TUBE: return c[0] * (c[1] + 1);
    case CTD_GEN_ROD: return c[0] + 1;
    case CTD_GEN_FOLDED:
        return ctd_folded_nodes((int)g->layers, (int)c[0], (int)c[1], g->h_eff, g->spacing);
    default: return -1;
    }
}

static void check_generate(vctx *v, unsigned i, ctd_scene_generate *g)
{
    char b[96];
    snprintf(b, sizeof b, "mesh[%u].generate", i);
    g->kind = cti_venum(v, cti_vpath(v, "%s.kind", b), g->kind_name, cti_gen_names, CTD_GEN_NKIND);
    memset(g->cells_eff, 0, sizeof g->cells_eff);
    g->h_eff = 0;
    if (g->kind < 0)
        return;
    int nerr = v->e->count;
    int k = g->kind;
    const ctd_scene_part *part = ctd_scene_part_by_id(v->sc, g->part);
    /* A part whose element is unknown (-1) has its own error already. */
    if (cti_vpart_ref(v, cti_vpath(v, "%s.part", b), g->part) && part->element >= 0 &&
        !(kind_spec[k].elem_mask >> part->element & 1))
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.part", b),
                "part %lld has element %s, which a %s mesh cannot have (expected %s)",
                (long long)g->part, part->element_name, g->kind_name,
                kind_spec[k].elem_mask == SURF    ? "shell or rigid"
                : kind_spec[k].elem_mask == SOLID ? "brick or rigid"
                                                  : "truss, spring or rigid");
    if ((int)g->cells_count != kind_spec[k].ncells)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.cells", b),
                "expected a list of %d integers for kind %s, got %u", kind_spec[k].ncells,
                g->kind_name, g->cells_count);
    for (unsigned j = 0; j < g->cells_count && j < 3; j++) {
        if (g->cells[j] < 1 || g->cells[j] > 100000000)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.cells[%u]", b, j),
                    "expected an integer in 1 .. 1e8, got %lld", (long long)g->cells[j]);
        else if (g->cells[j] * v->sc->refine > 100000000)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.cells[%u]", b, j),
                    "cells times refine is %lld, expected at most 1e8",
                    (long long)(g->cells[j] * v->sc->refine));
        else
            g->cells_eff[j] = g->cells[j] * v->sc->refine;
    }
    if (kind_spec[k].nsize && (int)g->size_count != kind_spec[k].nsize)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.size", b),
                "expected a list of %d numbers for kind %s, got %s", kind_spec[k].nsize,
                g->kind_name, g->size ? "another count" : "nothing");
    else if (!kind_spec[k].nsize && g->size)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.size", b), "not used by kind %s",
                g->kind_name);
    for (unsigned j = 0; j < g->size_count; j++)
        cti_vnum(v, cti_vpath(v, "%s.size[%u]", b, j), g->size[j], 0, 1, INFINITY, 0,
                 "a number > 0");
    /* The folded sheet's size is one cell's: refine divides it, so that the
     * sheet keeps its extent, as every other mesh keeps its own. */
    if (k == CTD_GEN_FOLDED && g->size_count == 1)
        g->h_eff = g->size[0] / (double)v->sc->refine;
    for (int j = 0; j < 3; j++)
        cti_vnum(v, cti_vpath(v, "%s.origin[%d]", b, j), g->origin[j], -INFINITY, 0, INFINITY, 0,
                 "a finite number");
    struct {
        const char *key;
        int need;
        double val;
    } opt[] = {{"radius", kind_spec[k].radius, g->radius},
               {"length", kind_spec[k].length, g->length},
               {"spacing", kind_spec[k].folded, g->spacing}};
    for (int j = 0; j < 3; j++) {
        const char *pth = cti_vpath(v, "%s.%s", b, opt[j].key);
        if (opt[j].need && !cti_vhas(v, pth))
            cti_err(v->e, CT_ERR_ARG, 0, pth,
                    "required field missing for kind %s (expected a "
                    "number > 0)",
                    g->kind_name);
        else if (opt[j].need)
            cti_vnum(v, pth, opt[j].val, 0, 1, INFINITY, 0, "a number > 0");
        else if (cti_vhas(v, pth))
            cti_err(v->e, CT_ERR_ARG, 0, pth, "not used by kind %s", g->kind_name);
    }
    const char *pl = cti_vpath(v, "%s.layers", b);
    if (kind_spec[k].folded && (!cti_vhas(v, pl) || g->layers < 1))
        cti_err(v->e, CT_ERR_ARG, 0, pl, "expected an integer >= 1 for kind folded, got %s",
                cti_vhas(v, pl) ? "less" : "nothing");
    else if (kind_spec[k].folded && g->layers > 100000000)
        cti_err(v->e, CT_ERR_ARG, 0, pl, "expected an integer in 1 .. 1e8, got %lld",
                (long long)g->layers);
    else if (!kind_spec[k].folded && cti_vhas(v, pl))
        cti_err(v->e, CT_ERR_ARG, 0, pl, "not used by kind %s", g->kind_name);
    const char *pt = cti_vpath(v, "%s.to", b);
    char pts[96];
    snprintf(pts, sizeof pts, "%s", pt);
    if (kind_spec[k].to && !cti_vhas(v, pts))
        cti_err(v->e, CT_ERR_ARG, 0, pts,
                "required field missing for kind rod (expected a list "
                "of 3 numbers)");
    else if (kind_spec[k].to && cti_vhas(v, pts)) {
        int fin = 1;
        for (int j = 0; j < 3; j++)
            fin &= cti_vnum(v, cti_vpath(v, "%s[%d]", pts, j), g->to[j], -INFINITY, 0,
                            INFINITY, 0, "a finite number");
        if (fin && g->to[0] == g->origin[0] && g->to[1] == g->origin[1] &&
            g->to[2] == g->origin[2])
            cti_err(v->e, CT_ERR_ARG, 0, pts, "expected a point other than origin");
    } else if (cti_vhas(v, pts)) {
        cti_err(v->e, CT_ERR_ARG, 0, pts, "not used by kind %s", g->kind_name);
    }
    /* Finite inputs can still make coordinates the arithmetic cannot hold
     * (origin -1e308 with size 1e308 gives inf; a rod from -1e308 overflows
     * the edge search's boxes). Bound every coordinate the mesh can reach by
     * GEN_MAXCOORD, the limit the deck reader enforces on segments
     * (ct_mesh_validate: longest edge squared, squared, below 1e300). */
    if (v->e->count == nerr) {
        double reach = 0, span = 0;
        for (int j = 0; j < 3; j++) {
            reach = fmax(reach, fabs(g->origin[j]));
            if (kind_spec[k].to)
                reach = fmax(reach, fabs(g->to[j]));
        }
        /* folded: size [h] is one cell's size (of the mesh before refine) */
        const double per = k == CTD_GEN_FOLDED ? (double)(g->cells[0] + g->cells[1]) : 1;
        for (unsigned j = 0; j < g->size_count; j++)
            span += g->size[j] * per;
        span += 2 * g->radius + g->length;
        if (k == CTD_GEN_FOLDED)
            span += g->spacing * (double)g->layers;
        if (!(reach + span <= GEN_MAXCOORD))
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s", b),
                    "the mesh would reach coordinates of %g, expected at most %g (scale the "
                    "model's length unit)", reach + span, GEN_MAXCOORD);
    }
    if (g->tri && k != CTD_GEN_PLATE)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.tri", b), "only used by kind plate");
    v->sc->mesh[i].nnode = v->e->count == nerr ? gen_nodes(g) : -1;
    if (v->sc->mesh[i].nnode > GEN_MAXNODES) {
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.cells", b),
                "the mesh would have more than %lld nodes (expected fewer cells)",
                (long long)GEN_MAXNODES);
        v->sc->mesh[i].nnode = -1;
    }
}

static void check_import(vctx *v, unsigned i, ctd_scene_import *im)
{
    const char *pf = cti_vpath(v, "mesh[%u].import.file", i);
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

void cti_vcheck_meshes(vctx *v)
{
    ctd_scene *sc = v->sc;
    int64_t next_id = 1;
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        ctd_scene_mesh *m = &sc->mesh[i];
        m->line = cti_path_line(v->e->root, cti_vpath(v, "mesh[%u]", i));
        m->first_id = next_id;
        m->nnode = -1;
        if (!m->generate == !m->import) {
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "mesh[%u]", i),
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
                    if (o->generate
                            ? (o->nnode > 0 && id >= o->first_id && id < o->first_id + o->nnode)
                            : (cti_vdeck(sc, j) && ctd_deck_node(cti_vdeck(sc, j), id) >= 0))
                        clash = (int)j;
                }
                if (clash >= 0) {
                    cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "mesh[%u].import.file", i),
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
