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

#include "errf.h"
#include "meshgen.h"
#include "output.h"
#include "scene_validate_internal.h"

const char *const cti_elem_names[CTD_ELEM_NKIND] = {"brick", "shell", "truss", "spring", "rigid"};
const char *const cti_gen_names[CTD_GEN_NKIND] = {"plate", "block",  "sphere", "ball",
                                                  "tube",  "folded", "net",    "rod"};
const char *const cti_bc_names[CTD_BC_NKIND] = {"fixed",   "velocity", "initial_velocity",
                                                "gravity", "force",    "pressure"};

/* The path built from a format (into v->p). */
const char *cti_vpath(vctx *v, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
const char *cti_vpath(vctx *v, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->p, sizeof v->p, fmt, ap);
    va_end(ap);
    return v->p;
}

int cti_vhas(vctx *v, const char *path) { return cti_ynode_at(v->e->root, path) != NULL; }

/* A number: finite and, unless NaN bounds, in [lo, hi] or (lo, hi) when
 * open. `expect` words the range. Returns 1 when fine. */
int cti_vnum(vctx *v, const char *path, double x, double lo, int lo_open, double hi, int hi_open,
             const char *expect)
{
    if (!isfinite(x)) {
        if (strcmp(expect, "a finite number") == 0)
            cti_err(v->e, CT_ERR_NONFINITE, 0, path, "expected a finite number, got %s",
                    ctd_num(x).s);
        else
            cti_err(v->e, CT_ERR_NONFINITE, 0, path, "expected a finite number (%s), got %s",
                    expect, ctd_num(x).s);
        return 0;
    }
    int ok = (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
    if (!ok)
        cti_err(v->e, CT_ERR_ARG, 0, path, "expected %s, got %s", expect, ctd_num(x).s);
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

int cti_venum(vctx *v, const char *path, const char *s, const char *const *names, int n)
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

const ctd_deck *cti_vdeck(const ctd_scene *sc, unsigned i)
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
        } else if (cti_vdeck(sc, i) && ctd_deck_node(cti_vdeck(sc, i), id) >= 0) {
            return 1;
        }
    }
    return 0;
}

int cti_vpart_ref(vctx *v, const char *path, int64_t id)
{
    if (ctd_scene_part_by_id(v->sc, id))
        return 1;
    cti_err(v->e, CT_ERR_RANGE, 0, path,
            "part %lld does not exist (expected an id listed in parts)", (long long)id);
    return 0;
}

/* Check a selection; `allow` is SEL_NODES, SEL_SURF or both. */
void cti_vsel(vctx *v, const char *base, ctd_scene_sel *s, int allow)
{
    char path[160];
    snprintf(path, sizeof path, "%s", base);
    s->line = cti_path_line(v->e->root, path);
    int nparts = (s->part != 0) + (s->parts_count > 0);
    int nnodes = (s->group != 0) + (s->ids_count > 0);
    int nsurf = s->surf != 0;
    if (!(allow & SEL_NODES) && nnodes) {
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.%s", path, s->group ? "group" : "ids"),
                "a surface is expected here: use part, parts or surf");
    } else if (!(allow & SEL_SURF) && nsurf) {
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.surf", path),
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
        cti_vpart_ref(v, cti_vpath(v, "%s.part", path), s->part);
    for (unsigned k = 0; k < s->parts_count; k++)
        cti_vpart_ref(v, cti_vpath(v, "%s.parts[%u]", path, k), s->parts[k]);
    if ((s->surf || s->group) && !v->deck_failed) {
        int found = 0;
        for (unsigned i = 0; i < v->sc->mesh_count; i++) {
            const ctd_deck *d = cti_vdeck(v->sc, i);
            if (d &&
                (s->surf ? ctd_deck_surf(d, s->surf) != NULL : ctd_deck_group(d, s->group) != NULL))
                found = 1;
        }
        if (!found)
            cti_err(v->e, CT_ERR_RANGE, 0, cti_vpath(v, "%s.%s", path, s->surf ? "surf" : "group"),
                    "%s %lld does not exist (expected the id of a %s in an imported deck)",
                    s->surf ? "surface" : "node group", (long long)(s->surf ? s->surf : s->group),
                    s->surf ? "/SURF" : "/GRNOD");
    }
    for (unsigned k = 0; k < s->ids_count && !v->deck_failed; k++)
        if (!node_exists(v->sc, s->ids[k]))
            cti_err(v->e, CT_ERR_RANGE, 0, cti_vpath(v, "%s.ids[%u]", path, k),
                    "node %lld does not exist (expected a node id of the meshes)",
                    (long long)s->ids[k]);
    memset(&s->where, 0, sizeof s->where);
    if (s->where_text && parse_where(s->where_text, &s->where) != 0)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.where", path),
                "expected at most %d clauses like 'z < 0.001' (x|y|z, <|<=|>|>=, a number) "
                "joined by 'and', got '%s'",
                CTD_WHERE_MAX, s->where_text);
}

/* ---- Parts, bodies, boundary conditions ------------------------------------ */

static void check_parts(vctx *v)
{
    ctd_scene *sc = v->sc;
    for (unsigned i = 0; i < sc->parts_count; i++) {
        ctd_scene_part *p = &sc->parts[i];
        p->line = cti_path_line(v->e->root, cti_vpath(v, "parts[%u]", i));
        /* The model keeps part ids in int32_t (cell_part, node_part, the VTU
         * part_id array): 4294967297 was written as part 1. */
        if (p->id <= 0 || p->id > INT32_MAX)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "parts[%u].id", i),
                    "expected an integer in 1 .. 2147483647, got %lld", (long long)p->id);
        for (unsigned j = 0; j < i; j++)
            if (sc->parts[j].id == p->id) {
                cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "parts[%u].id", i),
                        "part %lld is defined twice (first at line %d), expected a new id",
                        (long long)p->id, sc->parts[j].line);
                break;
            }
        p->element = cti_venum(v, cti_vpath(v, "parts[%u].element", i), p->element_name,
                               cti_elem_names, CTD_ELEM_NKIND);
        int okE = cti_vnum(v, cti_vpath(v, "parts[%u].material.E", i), p->material.E, 0, 1,
                           INFINITY, 0, "a number > 0");
        cti_vnum(v, cti_vpath(v, "parts[%u].material.nu", i), p->material.nu, -1, 1, 0.5, 1,
                 "a number in (-1, 0.5)");
        int okr = cti_vnum(v, cti_vpath(v, "parts[%u].material.rho", i), p->material.rho, 0, 1,
                           INFINITY, 0, "a number > 0");
        /* Each > 0 and finite is not enough: rho 4.9e-324 gave nodes a mass
         * of 0 ("only springs attach it"), rho 1e-300 or E 1e308 a wave speed
         * sqrt(E/rho) of inf and a stable step of 0 ("unstable" at cycle 0).
         * Any consistent unit system (SI, mm-ms-kg, mm-s-t) is far inside. */
        if (okE && okr && !(p->material.rho >= 1e-100 && p->material.E <= 1e100 &&
                            p->material.E / p->material.rho >= 1e-60 &&
                            p->material.E / p->material.rho <= 1e60))
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "parts[%u].material", i),
                    "E %g and rho %g give a wave speed squared E/rho of %g: expected rho >= "
                    "1e-100, E <= 1e100 and E/rho in 1e-60 .. 1e60 (check the units)",
                    p->material.E, p->material.rho, p->material.E / p->material.rho);
        static const char *const keys[3] = {"thickness", "area", "stiffness"};
        const int need[3] = {CTD_ELEM_SHELL, CTD_ELEM_TRUSS, CTD_ELEM_SPRING};
        const double val[3] = {p->thickness, p->area, p->stiffness};
        for (int k = 0; k < 3; k++) {
            const char *pth = cti_vpath(v, "parts[%u].%s", i, keys[k]);
            if (p->element == need[k] && !cti_vhas(v, pth))
                cti_err(v->e, CT_ERR_ARG, 0, pth,
                        "required field missing for element %s (expected a number > 0)",
                        p->element_name);
            else if (cti_vhas(v, pth))
                cti_vnum(v, pth, val[k], 0, 1, INFINITY, 0, "a number > 0");
        }
    }
}

static void check_rigid(vctx *v)
{
    ctd_scene *sc = v->sc;
    for (unsigned i = 0; i < sc->rigid_bodies_count; i++) {
        ctd_scene_rigid *r = &sc->rigid_bodies[i];
        r->line = cti_path_line(v->e->root, cti_vpath(v, "rigid_bodies[%u]", i));
        if (r->id <= 0)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "rigid_bodies[%u].id", i),
                    "expected an integer > 0, got %lld", (long long)r->id);
        for (unsigned j = 0; j < i; j++) {
            if (sc->rigid_bodies[j].id == r->id)
                cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "rigid_bodies[%u].id", i),
                        "rigid body %lld is defined twice (first at line %d)", (long long)r->id,
                        sc->rigid_bodies[j].line);
            if (sc->rigid_bodies[j].part == r->part)
                cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "rigid_bodies[%u].part", i),
                        "part %lld already belongs to rigid body %lld", (long long)r->part,
                        (long long)sc->rigid_bodies[j].id);
        }
        const ctd_scene_part *p = ctd_scene_part_by_id(sc, r->part);
        if (cti_vpart_ref(v, cti_vpath(v, "rigid_bodies[%u].part", i), r->part) &&
            p->element != CTD_ELEM_RIGID)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "rigid_bodies[%u].part", i),
                    "part %lld has element %s, expected a part with element rigid",
                    (long long)r->part, p->element_name);
    }
}

/* The fields of the loads (force, pressure): surface, pressure, curve. */
static void check_load(vctx *v, unsigned i, ctd_scene_bc *b)
{
    const int pres = b->kind == CTD_BC_PRESSURE, load = pres || b->kind == CTD_BC_FORCE;
    const char *ps = cti_vpath(v, "boundary[%u].surface", i);
    if (pres && !b->surface)
        cti_err(v->e, CT_ERR_ARG, 0, ps,
                "required field missing for kind pressure (expected a surface selection)");
    else if (!pres && b->surface)
        cti_err(v->e, CT_ERR_ARG, 0, ps, "only used by kind pressure");
    else if (b->surface)
        cti_vsel(v, ps, b->surface, SEL_SURF);
    const char *pp = cti_vpath(v, "boundary[%u].pressure", i);
    if (pres && !cti_vhas(v, pp))
        cti_err(v->e, CT_ERR_ARG, 0, pp,
                "required field missing for kind pressure (expected a finite number, Pa)");
    else if (!pres && cti_vhas(v, pp))
        cti_err(v->e, CT_ERR_ARG, 0, pp, "only used by kind pressure");
    else if (pres)
        cti_vnum(v, pp, b->pressure, -INFINITY, 0, INFINITY, 0, "a finite number");
    if (b->curve && !load) {
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "boundary[%u].curve", i),
                "only used by kinds force and pressure");
        return;
    }
    for (unsigned k = 0; b->curve && k < b->curve_count; k++) {
        cti_vnum(v, cti_vpath(v, "boundary[%u].curve[%u][0]", i, k), b->curve[k][0], -INFINITY, 0,
                 INFINITY, 0, "a finite time");
        cti_vnum(v, cti_vpath(v, "boundary[%u].curve[%u][1]", i, k), b->curve[k][1], -INFINITY, 0,
                 INFINITY, 0, "a finite factor");
        if (k > 0 && !(b->curve[k][0] > b->curve[k - 1][0]))
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "boundary[%u].curve[%u][0]", i, k),
                    "expected times in strictly ascending order, got %s after %s",
                    ctd_num(b->curve[k][0]).s, ctd_num(b->curve[k - 1][0]).s);
    }
}

static void check_boundary(vctx *v)
{
    ctd_scene *sc = v->sc;
    for (unsigned i = 0; i < sc->boundary_count; i++) {
        ctd_scene_bc *b = &sc->boundary[i];
        b->line = cti_path_line(v->e->root, cti_vpath(v, "boundary[%u]", i));
        b->kind = cti_venum(v, cti_vpath(v, "boundary[%u].kind", i), b->kind_name, cti_bc_names,
                            CTD_BC_NKIND);
        b->dof[0] = b->dof[1] = b->dof[2] = 1;
        if (b->kind < 0)
            continue;
        const int pres = b->kind == CTD_BC_PRESSURE;
        if ((b->kind == CTD_BC_GRAVITY || pres) && b->nodes)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "boundary[%u].nodes", i),
                    pres ? "not used by pressure (it loads a surface: give surface)"
                         : "not used by gravity (it acts on every node)");
        else if (b->kind != CTD_BC_GRAVITY && !pres && !b->nodes)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "boundary[%u].nodes", i),
                    "required field missing for kind %s (expected a node selection)", b->kind_name);
        else if (b->nodes)
            cti_vsel(v, cti_vpath(v, "boundary[%u].nodes", i), b->nodes, SEL_NODES);
        check_load(v, i, b);
        int want_value = b->kind != CTD_BC_FIXED && !pres;
        if (want_value && !b->value)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "boundary[%u].value", i),
                    "required field missing for kind %s (expected a list of 3 numbers)",
                    b->kind_name);
        else if (!want_value && b->value)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "boundary[%u].value", i),
                    "not used by kind %s%s", b->kind_name, pres ? " (give pressure)" : "");
        for (unsigned k = 0; k < b->value_count; k++)
            cti_vnum(v, cti_vpath(v, "boundary[%u].value[%u]", i, k), b->value[k], -INFINITY, 0,
                     INFINITY, 0, "a finite number");
        if (b->dofs) {
            const char *pd = cti_vpath(v, "boundary[%u].dofs", i);
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

/* ---- Top level ------------------------------------------------------------- */

static int check_top(vctx *v)
{
    ctd_scene *sc = v->sc;
    /* > 0 alone let end_time 4.9e-324 through: one step of that size
     * divides into inf, and the run ended "ok" with NaN external work. */
    cti_vnum(v, "end_time", sc->end_time, 1e-20, 0, INFINITY, 0, "a number >= 1e-20");
    if (!cti_vhas(v, "refine"))
        sc->refine = 1;
    else if (sc->refine < 1 || sc->refine > 1000) {
        cti_err(v->e, CT_ERR_ARG, 0, "refine", "expected an integer in 1..1000, got %lld",
                (long long)sc->refine);
        sc->refine = 1;
    }
    if (v->refine > 1000)
        cti_err(v->e, CT_ERR_ARG, 0, "refine",
                "expected an integer in 1..1000 from the "
                "caller, got %lld",
                (long long)v->refine);
    else if (v->refine > 0)
        sc->refine = v->refine;
    if (!sc->output && !(sc->output = calloc(1, sizeof *sc->output)))
        return CT_ERR_NOMEM;
    if (!sc->solver && !(sc->solver = calloc(1, sizeof *sc->solver)))
        return CT_ERR_NOMEM;
    ctd_scene_output *o = sc->output;
    if (!cti_vhas(v, "output.vtu"))
        o->vtu = true;
    if (!cti_vhas(v, "output.csv"))
        o->csv = true;
    {
        static const char *const formats[] = {"binary", "ascii"};
        o->format = o->format_name && cti_venum(v, "output.format", o->format_name, formats,
                                                2) == 1
                        ? CTD_VTU_ASCII
                        : CTD_VTU_RAW;
    }
    if (!cti_vhas(v, "output.every"))
        o->every = isfinite(sc->end_time) && sc->end_time > 0 ? sc->end_time / 100 : 1.0;
    else
        cti_vnum(v, "output.every", o->every, 1e-20, 0, INFINITY, 0, "a number >= 1e-20");
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
    if (!cti_vhas(v, "solver.dt_scale"))
        sc->solver->dt_scale = 0.9;
    else
        cti_vnum(v, "solver.dt_scale", sc->solver->dt_scale, 1e-6, 0, 1, 0,
                 "a number in [1e-6, 1]");
    if (sc->solver->threads < 0 || sc->solver->threads > 4096)
        cti_err(v->e, CT_ERR_ARG, 0, "solver.threads",
                "expected an integer in 0..4096 (0: OpenMP's default), got %lld",
                (long long)sc->solver->threads);
    if (!cti_vhas(v, "solver.cycle_limit"))
        sc->solver->cycle_limit = CTD_CYCLE_LIMIT;
    else if (sc->solver->cycle_limit < 1 || sc->solver->cycle_limit > (int64_t)1000000000000000)
        cti_err(v->e, CT_ERR_ARG, 0, "solver.cycle_limit",
                "expected an integer in 1 .. 1e15, got %lld",
                (long long)sc->solver->cycle_limit);
    return CT_OK;
}

int cti_scene_validate(ctd_scene *sc, cti_errs *e, int64_t refine)
{
    vctx v = {.sc = sc, .e = e, .refine = refine};
    int rc = check_top(&v);
    if (rc != CT_OK)
        return cti_err(e, rc, 0, "", "out of memory");
    check_parts(&v);
    cti_vcheck_meshes(&v);
    check_rigid(&v);
    check_boundary(&v);
    for (unsigned i = 0; i < sc->interfaces_count; i++)
        cti_vcheck_interface(&v, i, &sc->interfaces[i]);
    return e->count ? e->code : CT_OK;
}
