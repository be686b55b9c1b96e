/*
 * scene_schema.c -- the libcyaml schema of a scene file (see scene.h for
 * the format) and what it expects at a field path, for error messages.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

#define OPT CYAML_FLAG_OPTIONAL
#define REQ CYAML_FLAG_DEFAULT
#define PTR CYAML_FLAG_POINTER

static const cyaml_schema_value_t v_float = {CYAML_VALUE_FLOAT(REQ, double)};
static const cyaml_schema_value_t v_int64 = {CYAML_VALUE_INT(REQ, int64_t)};
static const cyaml_schema_value_t v_point = {
    CYAML_VALUE_SEQUENCE_FIXED(REQ, double, &v_float, 2)};

#define STR(key, flags, st, m) CYAML_FIELD_STRING_PTR(key, (flags) | PTR, st, m, 0, CYAML_UNLIMITED)
#define NUM(key, flags, st, m) CYAML_FIELD_FLOAT(key, flags, st, m)
#define INT(key, flags, st, m) CYAML_FIELD_INT(key, flags, st, m)

/* ---- Selections ---------------------------------------------------------- */

static const cyaml_schema_field_t f_sel[] = {
    INT("part", OPT, ctd_scene_sel, part),
    CYAML_FIELD_SEQUENCE("parts", OPT | PTR, ctd_scene_sel, parts, &v_int64, 1, CYAML_UNLIMITED),
    INT("surf", OPT, ctd_scene_sel, surf),
    INT("group", OPT, ctd_scene_sel, group),
    CYAML_FIELD_SEQUENCE("ids", OPT | PTR, ctd_scene_sel, ids, &v_int64, 1, CYAML_UNLIMITED),
    STR("where", OPT, ctd_scene_sel, where_text),
    CYAML_FIELD_END};

/* ---- Mesh ---------------------------------------------------------------- */

static const cyaml_schema_field_t f_generate[] = {
    STR("kind", REQ, ctd_scene_generate, kind_name),
    INT("part", REQ, ctd_scene_generate, part),
    CYAML_FIELD_SEQUENCE("cells", REQ | PTR, ctd_scene_generate, cells, &v_int64, 1, 3),
    CYAML_FIELD_SEQUENCE("size", OPT | PTR, ctd_scene_generate, size, &v_float, 1, 3),
    CYAML_FIELD_SEQUENCE_FIXED("origin", OPT, ctd_scene_generate, origin, &v_float, 3),
    CYAML_FIELD_SEQUENCE_FIXED("to", OPT, ctd_scene_generate, to, &v_float, 3),
    NUM("radius", OPT, ctd_scene_generate, radius),
    NUM("length", OPT, ctd_scene_generate, length),
    NUM("spacing", OPT, ctd_scene_generate, spacing),
    INT("layers", OPT, ctd_scene_generate, layers),
    CYAML_FIELD_BOOL("tri", OPT, ctd_scene_generate, tri),
    CYAML_FIELD_END};

static const cyaml_schema_field_t f_import[] = {
    STR("file", REQ, ctd_scene_import, file),
    CYAML_FIELD_END};

static const cyaml_schema_field_t f_mesh[] = {
    CYAML_FIELD_MAPPING_PTR("generate", OPT, ctd_scene_mesh, generate, f_generate),
    CYAML_FIELD_MAPPING_PTR("import", OPT, ctd_scene_mesh, import, f_import),
    CYAML_FIELD_END};
static const cyaml_schema_value_t v_mesh = {CYAML_VALUE_MAPPING(REQ, ctd_scene_mesh, f_mesh)};

/* ---- Parts, bodies, boundary conditions ---------------------------------- */

static const cyaml_schema_field_t f_material[] = {
    NUM("E", REQ, ctd_scene_material, E),
    NUM("nu", REQ, ctd_scene_material, nu),
    NUM("rho", REQ, ctd_scene_material, rho),
    CYAML_FIELD_END};

static const cyaml_schema_field_t f_part[] = {
    INT("id", REQ, ctd_scene_part, id),
    STR("name", OPT, ctd_scene_part, name),
    STR("element", REQ, ctd_scene_part, element_name),
    CYAML_FIELD_MAPPING("material", REQ, ctd_scene_part, material, f_material),
    NUM("thickness", OPT, ctd_scene_part, thickness),
    NUM("area", OPT, ctd_scene_part, area),
    NUM("stiffness", OPT, ctd_scene_part, stiffness),
    CYAML_FIELD_END};
static const cyaml_schema_value_t v_part = {CYAML_VALUE_MAPPING(REQ, ctd_scene_part, f_part)};

static const cyaml_schema_field_t f_rigid[] = {
    INT("id", REQ, ctd_scene_rigid, id),
    INT("part", REQ, ctd_scene_rigid, part),
    CYAML_FIELD_END};
static const cyaml_schema_value_t v_rigid = {CYAML_VALUE_MAPPING(REQ, ctd_scene_rigid, f_rigid)};

static const cyaml_schema_field_t f_bc[] = {
    STR("kind", REQ, ctd_scene_bc, kind_name),
    CYAML_FIELD_MAPPING_PTR("nodes", OPT, ctd_scene_bc, nodes, f_sel),
    CYAML_FIELD_SEQUENCE("value", OPT | PTR, ctd_scene_bc, value, &v_float, 3, 3),
    STR("dofs", OPT, ctd_scene_bc, dofs),
    CYAML_FIELD_MAPPING_PTR("surface", OPT, ctd_scene_bc, surface, f_sel),
    NUM("pressure", OPT, ctd_scene_bc, pressure),
    CYAML_FIELD_SEQUENCE("curve", OPT | PTR, ctd_scene_bc, curve, &v_point, 1, CYAML_UNLIMITED),
    CYAML_FIELD_END};
static const cyaml_schema_value_t v_bc = {CYAML_VALUE_MAPPING(REQ, ctd_scene_bc, f_bc)};

/* ---- Interfaces ---------------------------------------------------------- */

#define IF_NUM(k) NUM(#k, OPT, ctd_scene_interface, k)
#define IF_INT(k) INT(#k, OPT, ctd_scene_interface, k)

static const cyaml_schema_field_t f_interface[] = {
    INT("type", REQ, ctd_scene_interface, type),
    STR("name", OPT, ctd_scene_interface, name),
    CYAML_FIELD_MAPPING_PTR("main", REQ, ctd_scene_interface, main, f_sel),
    CYAML_FIELD_MAPPING_PTR("secondary", OPT, ctd_scene_interface, secondary, f_sel),
    CYAML_FIELD_MAPPING_PTR("grnd_IDs", OPT, ctd_scene_interface, grnd_IDs, f_sel),
    STR("search", OPT, ctd_scene_interface, search_name),
    STR("pressure_area", OPT, ctd_scene_interface, pressure_area_name),
    IF_INT(Istf), IF_INT(Igap0), IF_INT(Ipen0), IF_INT(Inacti), IF_INT(Ifric), IF_INT(Ifiltr),
    IF_INT(Irem_gap),
    IF_NUM(Stfac), IF_NUM(Stmin), IF_NUM(Stmax), IF_NUM(gap), IF_NUM(Gap_max_s),
    IF_NUM(Gap_max_m), IF_NUM(Ipen_max), IF_NUM(VisS), IF_NUM(Fric), IF_NUM(C1), IF_NUM(C2),
    IF_NUM(C3), IF_NUM(C4), IF_NUM(C5), IF_NUM(C6), IF_NUM(Xfreq), IF_NUM(Tstart),
    IF_NUM(Tstop), IF_NUM(margin),
    CYAML_FIELD_SEQUENCE("curve", OPT | PTR, ctd_scene_interface, curve, &v_point, 1,
                         CYAML_UNLIMITED),
    CYAML_FIELD_END};
static const cyaml_schema_value_t v_interface = {
    CYAML_VALUE_MAPPING(REQ, ctd_scene_interface, f_interface)};

/* ---- Top level ------------------------------------------------------------ */

static const cyaml_schema_field_t f_output[] = {
    STR("dir", OPT, ctd_scene_output, dir),
    NUM("every", OPT, ctd_scene_output, every),
    CYAML_FIELD_BOOL("vtu", OPT, ctd_scene_output, vtu),
    CYAML_FIELD_BOOL("csv", OPT, ctd_scene_output, csv),
    STR("format", OPT, ctd_scene_output, format_name),
    CYAML_FIELD_END};

static const cyaml_schema_field_t f_solver[] = {
    NUM("dt_scale", OPT, ctd_scene_solver, dt_scale),
    INT("threads", OPT, ctd_scene_solver, threads),
    INT("cycle_limit", OPT, ctd_scene_solver, cycle_limit),
    CYAML_FIELD_END};

static const cyaml_schema_field_t f_scene[] = {
    STR("title", OPT, ctd_scene, title),
    NUM("end_time", REQ, ctd_scene, end_time),
    INT("refine", OPT, ctd_scene, refine),
    CYAML_FIELD_MAPPING_PTR("output", OPT, ctd_scene, output, f_output),
    CYAML_FIELD_MAPPING_PTR("solver", OPT, ctd_scene, solver, f_solver),
    CYAML_FIELD_SEQUENCE("mesh", REQ | PTR, ctd_scene, mesh, &v_mesh, 1, CYAML_UNLIMITED),
    CYAML_FIELD_SEQUENCE("parts", REQ | PTR, ctd_scene, parts, &v_part, 1, CYAML_UNLIMITED),
    CYAML_FIELD_SEQUENCE("rigid_bodies", OPT | PTR, ctd_scene, rigid_bodies, &v_rigid, 0,
                         CYAML_UNLIMITED),
    CYAML_FIELD_SEQUENCE("boundary", OPT | PTR, ctd_scene, boundary, &v_bc, 0, CYAML_UNLIMITED),
    CYAML_FIELD_SEQUENCE("interfaces", OPT | PTR, ctd_scene, interfaces, &v_interface, 0,
                         CYAML_UNLIMITED),
    CYAML_FIELD_END};

const cyaml_schema_value_t cti_scene_schema = {CYAML_VALUE_MAPPING(PTR, ctd_scene, f_scene)};

/* ---- What the schema expects at a path ------------------------------------ */

static const char *type_phrase(const cyaml_schema_value_t *v, int plural)
{
    switch (v->type) {
    case CYAML_INT:
    case CYAML_UINT: return plural ? "integers" : "an integer";
    case CYAML_FLOAT: return plural ? "numbers" : "a number";
    case CYAML_BOOL: return plural ? "booleans" : "true or false";
    case CYAML_STRING: return plural ? "strings" : "a string";
    case CYAML_MAPPING: return plural ? "mappings" : "a mapping";
    case CYAML_SEQUENCE:
    case CYAML_SEQUENCE_FIXED: return plural ? "lists" : "a list";
    default: return plural ? "values" : "a value";
    }
}

static void keys_of(const cyaml_schema_value_t *v, char *buf, size_t len)
{
    size_t off = 0;
    buf[0] = '\0';
    for (const cyaml_schema_field_t *f = v->mapping.fields; f && f->key && off < len; f++)
        off += (size_t)snprintf(buf + off, len - off, "%s%s", off ? ", " : "", f->key);
}

void cti_schema_expect(const char *path, int keys_only, char *buf, size_t len)
{
    const cyaml_schema_value_t *v = &cti_scene_schema;
    const char *p = path;
    buf[0] = '\0';
    while (*p) {
        if (*p == '.')
            p++;
        if (*p == '[') {
            if (v->type != CYAML_SEQUENCE && v->type != CYAML_SEQUENCE_FIXED)
                return;
            const char *end = strchr(p, ']');
            if (!end)
                return;
            v = v->sequence.entry;
            p = end + 1;
        } else {
            size_t klen = strcspn(p, ".[");
            if (v->type != CYAML_MAPPING)
                return;
            const cyaml_schema_field_t *f = v->mapping.fields;
            while (f->key && !(strlen(f->key) == klen && strncmp(f->key, p, klen) == 0))
                f++;
            if (!f->key)
                return;
            v = &f->value;
            p += klen;
        }
    }
    char keys[400];
    if (v->type == CYAML_MAPPING) {
        keys_of(v, keys, sizeof keys);
        if (keys_only)
            snprintf(buf, len, "%s", keys);
        else
            snprintf(buf, len, "a mapping with keys %s", keys);
    } else if (v->type == CYAML_SEQUENCE_FIXED ||
               (v->type == CYAML_SEQUENCE && v->sequence.min == v->sequence.max)) {
        const cyaml_schema_value_t *e = v->sequence.entry;
        if (e->type == CYAML_SEQUENCE_FIXED)
            snprintf(buf, len, "a list of %u lists of %u %s", v->sequence.min, e->sequence.min,
                     type_phrase(e->sequence.entry, 1));
        else
            snprintf(buf, len, "a list of %u %s", v->sequence.min, type_phrase(e, 1));
    } else if (v->type == CYAML_SEQUENCE) {
        const cyaml_schema_value_t *e = v->sequence.entry;
        char extra[64] = "";
        if (v->sequence.max != CYAML_UNLIMITED)
            snprintf(extra, sizeof extra, " (%u to %u)", v->sequence.min, v->sequence.max);
        else if (v->sequence.min > 0)
            snprintf(extra, sizeof extra, " (at least %u)", v->sequence.min);
        if (e->type == CYAML_SEQUENCE_FIXED)
            snprintf(buf, len, "a list%s of [%u %s]", extra, e->sequence.min,
                     type_phrase(e->sequence.entry, 1));
        else if (e->type == CYAML_MAPPING) {
            keys_of(e, keys, sizeof keys);
            snprintf(buf, len, "a list%s of mappings with keys %s", extra, keys);
        } else
            snprintf(buf, len, "a list%s of %s", extra, type_phrase(e, 1));
    } else {
        snprintf(buf, len, "%s", type_phrase(v, 0));
    }
}
