/*
 * test_errors_scene.c -- checks of a scene file that no other test makes
 * fail (driver/scene_validate.c, scene_validate_iface.c,
 * scene_validate_mesh.c), suite "errors_scene". Each case is a small scene
 * loaded with ctd_scene_load: the load must fail with CT_ERR_ARG and its
 * first message must have the line and the field of the mistake and read
 * "FILE:LINE: FIELD: what" (scene.h), with the words given.
 *
 * Two cases showed a defect of the scene checks when written (fixed since,
 * see each one).
 */
#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "test_errors.h"

/* A brick block (part 1, mesh line 3) and a rigid plate above it (part 2,
 * line 4); the parts on lines 6 and 7; the case's text from line 8 on. */
static const char BASE[] =
    "end_time: 1.0e-3\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
    "  - generate: {kind: plate, part: 2, cells: [1, 1], size: [0.02, 0.02], origin: [0, 0, "
    "0.02]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "  - {id: 2, element: rigid, thickness: 0.001, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n";

/* One shell part (line 5) after a mesh entry given by the case (line 3). */
static const char MESH_HEAD[] = "end_time: 1.0e-3\nmesh:\n";
static const char MESH_TAIL[] =
    "parts:\n"
    "  - {id: 1, element: shell, thickness: 0.001, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n";

typedef struct scase {
    const char *text; /* after BASE, the mesh entry when mesh is 1, the file when 2 */
    int mesh;
    int line;
    const char *field, *what;
} scase;

/* Load the case's scene from dir and expect its first error. */
static void expect_scene_error(const char *dir, const scase *c)
{
    char text[2048], path[128];
    if (c->mesh == 2)
        snprintf(text, sizeof text, "%s", c->text);
    else if (c->mesh)
        snprintf(text, sizeof text, "%s%s%s", MESH_HEAD, c->text, MESH_TAIL);
    else
        snprintf(text, sizeof text, "%s%s", BASE, c->text);
    ctt_write_file(dir, "case.yaml", text);
    snprintf(path, sizeof path, "%s/case.yaml", dir);
    ctd_scene *sc = NULL;
    ctd_scene_err e;
    memset(&e, 0, sizeof e);
    int rc = ctd_scene_load(path, &sc, &e);
    cr_expect_eq(rc, CT_ERR_ARG, "%s: expected a refusal, got %d", c->text, rc);
    cr_expect_null(sc);
    if (rc == CT_OK) {
        ctd_scene_free(sc);
        return;
    }
    cr_assert(e.count >= 1);
    const ctd_scene_msg *m = &e.msg[0];
    cr_expect_eq(m->line, c->line, "%s: line %d, expected %d: %s", c->text, m->line, c->line,
                 m->text);
    cr_expect_str_eq(m->field, c->field, "%s: %s", c->text, m->text);
    char want[700];
    snprintf(want, sizeof want, "case.yaml:%d: %s: %s", c->line, c->field, c->what);
    cr_expect(strstr(m->text, want) != NULL, "message \"%s\" lacks \"%s\"", m->text, want);
}

static void run_cases(const scase *c, size_t n)
{
    char dir[64];
    ctt_tmpdir(dir, "errv");
    for (size_t i = 0; i < n; i++)
        expect_scene_error(dir, &c[i]);
    ctt_rmtree(dir);
}

Test(errors_scene, top_level_and_rigid_bodies)
{
    static const scase c[] = {
        {"refine: 0\n", 0, 8, "refine", "expected an integer in 1..1000, got 0"},
        {"output: {dir: \"\"}\n", 0, 8, "output.dir", "expected a directory name, got ''"},
        {"solver: {threads: -1}\n", 0, 8, "solver.threads",
         "expected an integer in 0..4096 (0: OpenMP's default), got -1"},
        {"rigid_bodies: [{id: 0, part: 2}]\n", 0, 8, "rigid_bodies[0].id",
         "expected an integer > 0, got 0"},
        {"rigid_bodies:\n  - {id: 1, part: 2}\n  - {id: 1, part: 2}\n", 0, 10,
         "rigid_bodies[1].id", "rigid body 1 is defined twice (first at line 9)"},
        {"rigid_bodies:\n  - {id: 1, part: 2}\n  - {id: 3, part: 2}\n", 0, 10,
         "rigid_bodies[1].part", "part 2 already belongs to rigid body 1"},
        {"rigid_bodies: [{id: 3, part: 1}]\n", 0, 8, "rigid_bodies[0].part",
         "part 1 has element brick, expected a part with element rigid"},
    };
    run_cases(c, sizeof c / sizeof c[0]);
}

Test(errors_scene, boundary_conditions)
{
    static const scase c[] = {
        {"boundary:\n  - {kind: fixed, nodes: {part: 1}, surface: {part: 1}}\n", 0, 9,
         "boundary[0].surface", "only used by kind pressure"},
        {"boundary:\n  - {kind: fixed, nodes: {part: 1}, pressure: 5}\n", 0, 9,
         "boundary[0].pressure", "only used by kind pressure"},
        {"boundary:\n  - {kind: fixed, nodes: {part: 1}, curve: [[0, 1], [1, 1]]}\n", 0, 9,
         "boundary[0].curve", "only used by kinds force and pressure"},
        {"boundary:\n  - {kind: fixed}\n", 0, 9, "boundary[0].nodes",
         "required field missing for kind fixed (expected a node selection)"},
        {"boundary:\n  - {kind: gravity, nodes: {part: 1}, value: [0, 0, -9.81]}\n", 0, 9,
         "boundary[0].nodes", "not used by gravity (it acts on every node)"},
        {"boundary:\n  - {kind: velocity, nodes: {part: 1}}\n", 0, 9, "boundary[0].value",
         "required field missing for kind velocity (expected a list of 3 numbers)"},
        {"boundary:\n  - {kind: fixed, nodes: {part: 1}, value: [0, 0, 1]}\n", 0, 9,
         "boundary[0].value", "not used by kind fixed"},
        {"boundary:\n  - {kind: initial_velocity, nodes: {part: 1}, value: [0, 0, 1], dofs: x}\n",
         0, 9, "boundary[0].dofs", "only used by kinds fixed and velocity"},
        {"boundary:\n  - {kind: fixed, nodes: {part: 1}, dofs: xq}\n", 0, 9, "boundary[0].dofs",
         "expected some of the letters x, y, z (each once), got 'xq'"},
        {"boundary:\n  - {kind: pressure, surface: {part: 1, surf: 3}, pressure: 1}\n", 0, 9,
         "boundary[0].surface", "expected exactly one of part, parts, surf"},
        {"boundary:\n  - {kind: fixed, nodes: {}}\n", 0, 9, "boundary[0].nodes",
         "empty selection, expected one of part, parts, group, ids, where"},
    };
    run_cases(c, sizeof c / sizeof c[0]);
}

Test(errors_scene, interfaces)
{
    static const scase c[] = {
        {"interfaces:\n  - {type: 5, main: {part: 2}}\n", 0, 9, "interfaces[0].secondary",
         "required field missing for type 5 (expected a node selection)"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, grnd_IDs: {part: 1}}\n", 0, 9,
         "interfaces[0].grnd_IDs", "only used by type 24"},
        {"interfaces:\n  - {type: 6, main: {part: 2}, secondary: {part: 1}}\n", 0, 9,
         "interfaces[0].secondary",
         "part 1 has element brick; type 6 expects a part with element rigid"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, curve: [[0, 0], [1, 1]]}\n", 0, 9,
         "interfaces[0].curve", "only used by type 6"},
        {"interfaces:\n  - {type: 6, main: {part: 2}, secondary: {part: 2}, "
         "curve: [[0, 0]]}\n",
         0, 9, "interfaces[0].curve", "expected at least 2 points, got 1"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Istf: 7}\n", 0, 9, "interfaces[0].Istf",
         "expected one of 0, 1, 2, 3, 4, 5, 1000, got 7"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Igap0: 2}\n", 0, 9, "interfaces[0].Igap0",
         "expected 0 or 1, got 2"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ipen0: 2}\n", 0, 9, "interfaces[0].Ipen0",
         "expected 0 or 1, got 2"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Inacti: 9}\n", 0, 9,
         "interfaces[0].Inacti", "expected one of -1, 0, 1, 2, 3, 5, 6, 1000, got 9"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifric: 9}\n", 0, 9, "interfaces[0].Ifric",
         "expected an integer in 0..4, got 9"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifiltr: 9}\n", 0, 9,
         "interfaces[0].Ifiltr", "expected an integer in 0..3, got 9"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, search: topological}\n", 0, 9,
         "interfaces[0].search", "topological cannot find self contact (a node's closest main "
         "node is itself): expected direct, bucket or bsp for type 7"},
        {"interfaces:\n  - {type: 11, main: {part: 2}, search: bsp}\n", 0, 9,
         "interfaces[0].search", "type 11's edge search is direct or bucket, got bsp"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, margin: -1}\n", 0, 9,
         "interfaces[0].margin",
         "expected a length >= 0 (0: 0.2 times the mean main edge length), got -1"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, margin: .inf}\n", 0, 9,
         "interfaces[0].margin", "expected a number, got '.inf'"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Irem_gap: 3}\n", 0, 9,
         "interfaces[0].Irem_gap", "expected an integer in 0..2, got 3"},
        {"interfaces:\n  - {type: 5, main: {part: 2}, secondary: {part: 2}, Irem_gap: 2}\n", 0,
         9, "interfaces[0].Irem_gap",
         "2 is only used by self contact: types 7, 11, and 24 without secondary, got type 5"},
        {"interfaces:\n  - {type: 24, main: {part: 2}, secondary: {part: 2}, Irem_gap: 2}\n", 0,
         9, "interfaces[0].Irem_gap",
         "2 is only used by self contact: types 7, 11, and 24 without secondary, got type 24 "
         "with a secondary side"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Stmin: 5, Stmax: 1}\n", 0, 9,
         "interfaces[0].Stmax", "expected a number >= Stmin (5), got 1"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifric: 3, C5: 2, C6: 1}\n", 0, 9,
         "interfaces[0].C5", "Renard friction (Ifric 3) expects 0 < C5 < C6, got C5 = 2, C6 = 1"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifric: 4, C2: -1}\n", 0, 9,
         "interfaces[0].C2", "Ifric 4 expects a decay rate C2 >= 0, got -1"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifiltr: 2, Xfreq: 1}\n", 0, 9,
         "interfaces[0].Xfreq", "expected a number >= 2 pi for Ifiltr 2, got 1"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifiltr: 3, Xfreq: 0}\n", 0, 9,
         "interfaces[0].Xfreq", "expected a number > 0 for Ifiltr 3, got 0"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Tstart: 2, Tstop: 1}\n", 0, 9,
         "interfaces[0].Tstop", "expected a time > Tstart (2), got 1"},
    };
    run_cases(c, sizeof c / sizeof c[0]);
}

Test(errors_scene, generated_meshes)
{
    static const scase c[] = {
        {"  - generate: {kind: plate, part: 1, cells: [1], size: [1, 1]}\n", 1, 3,
         "mesh[0].generate.cells", "expected a list of 2 integers for kind plate, got 1"},
        {"  - generate: {kind: plate, part: 1, cells: [0, 1], size: [1, 1]}\n", 1, 3,
         "mesh[0].generate.cells[0]", "expected an integer in 1 .. 1e8, got 0"},
        {"  - generate: {kind: plate, part: 1, cells: [1, 1], size: [1]}\n", 1, 3,
         "mesh[0].generate.size", "expected a list of 2 numbers for kind plate, got another count"},
        {"  - generate: {kind: sphere, part: 1, cells: [2], radius: 1, size: [1, 1]}\n", 1, 3,
         "mesh[0].generate.size", "not used by kind sphere"},
        {"  - generate: {kind: tube, part: 1, cells: [4, 2], radius: 1}\n", 1, 3,
         "mesh[0].generate.length", "required field missing for kind tube (expected a number > 0)"},
        {"  - generate: {kind: plate, part: 1, cells: [1, 1], size: [1, 1], radius: 2}\n", 1, 3,
         "mesh[0].generate.radius", "not used by kind plate"},
        {"  - generate: {kind: folded, part: 1, cells: [2, 2], size: [0.1], spacing: 0.1}\n", 1,
         3, "mesh[0].generate.layers", "expected an integer >= 1 for kind folded, got nothing"},
        {"  - generate: {kind: sphere, part: 1, cells: [2], radius: 1, tri: true}\n", 1, 3,
         "mesh[0].generate.tri", "only used by kind plate"},
        {"  - generate: {kind: plate, part: 1, cells: [5000000, 5000000], size: [1, 1]}\n", 1, 3,
         "mesh[0].generate.cells", "the mesh would have more than 2147483583 nodes"},
    };
    run_cases(c, sizeof c / sizeof c[0]);
}

/* A defect these two found (driver/scene_validate_mesh.c): `to` was
 * checked only for kind rod, and `layers` only for kind folded; on any
 * other kind they were accepted and ignored, where radius, length,
 * spacing, size and tri are refused as "not used by kind X" (scene.h: an
 * unknown key is an error, typos are caught). A plate with
 * `to: [1, 1, 1]` or `layers: 2` loaded as if they were not there. */
Test(errors_scene, to_of_another_kind_is_refused)
{
    static const scase c[] = {
        {"  - generate: {kind: plate, part: 1, cells: [1, 1], size: [1, 1], to: [1, 1, 1]}\n", 1,
         3, "mesh[0].generate.to", "not used by kind plate"},
    };
    run_cases(c, 1);
}

/* The same defect for `layers` (see above). */
Test(errors_scene, layers_of_another_kind_are_refused)
{
    static const scase c[] = {
        {"  - generate: {kind: plate, part: 1, cells: [1, 1], size: [1, 1], layers: 2}\n", 1, 3,
         "mesh[0].generate.layers", "not used by kind plate"},
    };
    run_cases(c, 1);
}

#define WHERE_EXPECT                                                                         \
    "expected at most 6 clauses like 'z < 0.001' (x|y|z, <|<=|>|>=, a number) joined by 'and', " \
    "got "

/* Checks no other case reached (a coverage run of the test suite found
 * them unexecuted): each is one error on its line and field. */
Test(errors_scene, checks_found_unexecuted)
{
    static const scase c[] = {
        {"  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n", 0, 8,
         "parts[2].id", "part 1 is defined twice (first at line 6), expected a new id"},
        {"boundary:\n  - {kind: fixed, nodes: {part: 1, ids: [1]}}\n", 0, 9, "boundary[0].nodes",
         "expected only one of part, parts, surf, group, ids"},
        {"boundary:\n  - {kind: pressure, surface: {part: 1}}\n", 0, 9, "boundary[0].pressure",
         "required field missing for kind pressure (expected a finite number, Pa)"},
        {"boundary:\n  - {kind: clamp, nodes: {part: 1}}\n", 0, 9, "boundary[0].kind",
         "expected one of fixed, velocity, initial_velocity, gravity, force, pressure, got "
         "'clamp'"},
        {"boundary:\n  - {kind: fixed, nodes: {part: 1, where: \"z = 1\"}}\n", 0, 9,
         "boundary[0].nodes.where", WHERE_EXPECT "'z = 1'"},
        {"boundary:\n  - {kind: fixed, nodes: {part: 1, where: \"z < 1 or x > 0\"}}\n", 0, 9,
         "boundary[0].nodes.where", WHERE_EXPECT "'z < 1 or x > 0'"},
        {"  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [1, 1, 1]}\n", 1, 3,
         "mesh[0].generate.part",
         "part 1 has element shell, which a block mesh cannot have (expected brick or rigid)"},
        {"  - generate: {kind: plate, part: 1, cells: [200000, 1], size: [1, 1]}\n"
         "refine: 1000\n",
         1, 3, "mesh[0].generate.cells[0]",
         "cells times refine is 200000000, expected at most 1e8"},
        {"  - {}\n", 1, 3, "mesh[0]", "expected one of generate, import, got neither"},
        {"  - {import: {file: a.rad}, generate: {kind: plate, part: 1, cells: [1, 1],"
         " size: [1, 1]}}\n",
         1, 3, "mesh[0]", "expected only one of generate, import, got both"},
        {"end_time: 1\nmesh:\n  - generate: {kind: rod, part: 1, cells: [2]}\nparts:\n"
         "  - {id: 1, element: truss, area: 1.0e-4, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n",
         2, 3, "mesh[0].generate.to",
         "required field missing for kind rod (expected a list of 3 numbers)"},
        {"end_time: 1\nmesh:\n  - generate: {kind: rod, part: 1, cells: [2], origin: [1, 2, 3],"
         " to: [1, 2, 3]}\nparts:\n"
         "  - {id: 1, element: truss, area: 1.0e-4, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n",
         2, 3, "mesh[0].generate.to", "expected a point other than origin"},
    };
    run_cases(c, sizeof c / sizeof c[0]);
}

/* An imported deck whose node ids a generated mesh listed before it has
 * taken (the generated block's nodes are 1..8, the deck's 1..4): the
 * import is blamed, with the deck's line and the mesh it clashes with. */
Test(errors_scene, import_after_a_generated_mesh_clashes)
{
    char dir[64];
    ctt_tmpdir(dir, "errv");
    ctt_write_file(dir, "quad.rad",
                   "/NODE\n"
                   "         1                   0                   0                   0\n"
                   "         2                   1                   0                   0\n"
                   "         3                   1                   1                   0\n"
                   "         4                   0                   1                   0\n"
                   "/SHELL/1\n"
                   "         1         1         2         3         4\n");
    const scase c = {
        "end_time: 1\nmesh:\n"
        "  - generate: {kind: block, part: 2, cells: [1, 1, 1], size: [1, 1, 1]}\n"
        "  - import: {file: quad.rad}\n"
        "parts:\n"
        "  - {id: 1, element: shell, thickness: 0.001, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
        "  - {id: 2, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n",
        2, 4, "mesh[1].import.file",
        "node id 1 of the deck (line 2) is already used by mesh[0] (expected distinct node ids; "
        "list imports before generated meshes)"};
    expect_scene_error(dir, &c);
    ctt_rmtree(dir);
}

/* A number in a message reads as the shortest text that is the same
 * double: 1.1, not 1.1000000000000001 (%.17g, as range errors printed it
 * before); and a value just past a bound keeps the digits that show it is
 * past (%g printed both Tstart and Tstop below as 0.1). */
Test(errors_scene, numbers_in_messages_shortest_exact)
{
    static const scase c[] = {
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifiltr: 1, Xfreq: 1.1}\n", 0, 9,
         "interfaces[0].Xfreq", "expected a number in (0, 1] for Ifiltr 1, got 1.1"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Ifiltr: 1, Xfreq: 1.0000000000000002}\n", 0,
         9, "interfaces[0].Xfreq",
         "expected a number in (0, 1] for Ifiltr 1, got 1.0000000000000002"},
        {"interfaces:\n  - {type: 7, main: {part: 2}, Tstart: 0.1, Tstop: 0.09999999999999999}\n",
         0, 9, "interfaces[0].Tstop", "expected a time > Tstart (0.1), got 0.09999999999999999"},
        {"interfaces:\n  - {type: 6, main: {part: 2}, secondary: {part: 2},\n"
         "     curve: [[0, 0], [2e-3, 1], [1.9e-3, 2]]}\n",
         0, 10, "interfaces[0].curve[2][0]",
         "expected penetrations in strictly ascending order, got 0.0019 after 0.002"},
    };
    run_cases(c, sizeof c / sizeof c[0]);
}
