/*
 * test_errors_model.c -- the errors of building a model from a valid scene
 * file (driver/model.c, model_parts.c, model_select.c), suite
 * "errors_model": each scene below passes the file's checks and fails the
 * model, run as `contact check` or `contact run` in a directory of its own.
 * Every case asserts the exit code, the message's "FILE:LINE: FIELD:"
 * prefix (the line of the part or mesh entry at fault) and what it says;
 * the runs write nothing.
 *
 *  - masses: a node held by springs only; a brick part whose nodes' masses
 *    underflow to 0 (rho at its lower bound on a tiny block); a rigid part
 *    with no mass at all; a rigid net without the area its mass needs;
 *  - element kinds: a deck's shells in a brick or spring part, its bricks
 *    in a shell or truss part;
 *  - geometry: an inverted deck brick in a deformable and in a rigid part,
 *    named by its deck element id and line;
 *  - rigid bodies: a node shared by two rigid parts;
 *  - memory: a generated block too large for the address space the run is
 *    given (exit 5, as every out-of-memory failure of `contact run`).
 *
 * Unreachable from a scene (the scene checks refuse the input first, see
 * docs in the report): a brick or shell part given lines (only generators
 * make lines, and their part's element is checked), a selection naming a
 * missing node or group, and a generator whose node count differs from
 * the loader's formula.
 */
#include <stdio.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "test_errors.h"

/* Ten nodes and a shell (element 1 of part 1, line 13) on nodes 2, 9, 10
 * and 3; the decks below add a brick of part 2 on line 15. */
#define DECK_NODES_SHELL \
    "/NODE\n" \
    "         1                   0                   0                   0\n" \
    "         2                   1                   0                   0\n" \
    "         3                   1                   1                   0\n" \
    "         4                   0                   1                   0\n" \
    "         5                   0                   0                   1\n" \
    "         6                   1                   0                   1\n" \
    "         7                   1                   1                   1\n" \
    "         8                   0                   1                   1\n" \
    "         9                   2                   0                   0\n" \
    "        10                   2                   1                   0\n" \
    "/SHELL/1\n" \
    "         1         2         9        10         3\n"

/* A unit brick (nodes 1-8, element 7 of part 2 on line 15) sharing the
 * shell's edge 2-3. */
static const char DECK[] =
    DECK_NODES_SHELL
    "/BRICK/2\n"
    "         7         1         2         3         4         5         6         7         8\n";

/* The same brick numbered inside out (its bottom face 1 4 3 2): the deck
 * reader accepts it, the element's Jacobian is negative. */
static const char DECK_INVERTED[] =
    DECK_NODES_SHELL
    "/BRICK/2\n"
    "         7         1         4         3         2         5         8         7         6\n";

/* A scene importing DECK_FILE with parts 1 and 2 given as P1 and P2 (the
 * parts are on lines 5 and 6). */
static void deck_scene(const char *dir, const char *name, const char *deck_file, const char *p1,
                       const char *p2)
{
    char text[1024];
    snprintf(text, sizeof text,
             "end_time: 1.0e-4\n"
             "mesh:\n"
             "  - import: {file: %s}\n"
             "parts:\n"
             "  - {id: 1, %s, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
             "  - {id: 2, %s, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n",
             deck_file, p1, p2);
    ctt_write_file(dir, name, text);
}

/* A scene of one generated mesh (line 3) and one part (line 5). */
static void gen_scene(const char *dir, const char *name, const char *gen, const char *part)
{
    char text[1024];
    snprintf(text, sizeof text,
             "end_time: 1.0e-4\n"
             "mesh:\n"
             "  - generate: {%s}\n"
             "parts:\n"
             "  - {id: 1, %s}\n",
             gen, part);
    ctt_write_file(dir, name, text);
}

static const char STEEL[] = "material: {E: 2.1e11, nu: 0.3, rho: 7800}";

/* `contact run NAME --out out` fails with `code` and `want`, and creates no
 * output directory. */
static void expect_run_fails(const char *dir, const char *name, int code, const char *want,
                             const char *also)
{
    ctt_cli r = {0};
    cte_run(&r, dir, "", "run %s --out out --quiet", name);
    CTE_EXPECT(&r, code, want, also);
    cr_expect(!ctt_exists(dir, "out"), "%s: the failed run created its output directory", name);
    ctt_cli_free(&r);
}

/* A node with elements but no mass: springs alone, masses that underflow,
 * a rigid body of no mass, a rigid net without its area. */
Test(errors_model, masses)
{
    char dir[64], part[256];
    ctt_tmpdir(dir, "errm");
    gen_scene(dir, "springs.yaml", "kind: rod, part: 1, cells: [2], to: [0.1, 0, 0]",
              "element: spring, stiffness: 1000, material: {E: 2.1e11, nu: 0.3, rho: 7800}");
    /* rho 1e-100 (its lower bound) times a brick of 1e-240 m^3: 0. In
     * single precision, where 1e-80 and 1e-100 are 0 already (refused as
     * such), rho 1e-20 times a brick of 1e-30 m^3 (the float minimum is
     * 1.4e-45). */
    const int sp = sizeof(ct_real) == sizeof(float);
    const char *blk = sp ? "kind: block, part: 1, cells: [1, 1, 1], size: [1e-10, 1e-10, 1e-10]"
                         : "kind: block, part: 1, cells: [1, 1, 1], size: [1e-80, 1e-80, 1e-80]";
    const char *rho = sp ? "E: 1e-30, nu: 0.3, rho: 1e-20" : "E: 1e-45, nu: 0.3, rho: 1e-100";
    char mat[128];
    snprintf(mat, sizeof mat, "element: brick, material: {%s}", rho);
    gen_scene(dir, "tiny.yaml", blk, mat);
    snprintf(mat, sizeof mat, "element: rigid, material: {%s}", rho);
    gen_scene(dir, "tiny_rigid.yaml", blk, mat);
    snprintf(part, sizeof part, "element: rigid, %s", STEEL);
    gen_scene(dir, "rigid_net.yaml", "kind: net, part: 1, cells: [2, 2], size: [0.1, 0.1]", part);
    expect_run_fails(dir, "springs.yaml", CTD_EXIT_BADINPUT,
                     "contact run: springs.yaml:5: parts[0]: node 1 (part 1) has no mass: only "
                     "springs attach it",
                     "expected a truss, brick, shell or rigid part on it");
    expect_run_fails(dir, "tiny.yaml", CTD_EXIT_BADINPUT,
                     "contact run: tiny.yaml:5: parts[0].material.rho: node 1 of part 1 has a "
                     "mass of 0",
                     sp ? "(rho 1e-20 is too small for its elements)"
                        : "(rho 1e-100 is too small for its elements)");
    expect_run_fails(dir, "tiny_rigid.yaml", CTD_EXIT_BADINPUT,
                     "contact run: tiny_rigid.yaml:5: parts[0].material.rho: rigid part 1 has a "
                     "mass of 0",
                     "expected a rho that gives its elements a mass > 0");
    expect_run_fails(dir, "rigid_net.yaml", CTD_EXIT_BADINPUT,
                     "contact run: rigid_net.yaml:5: parts[0].area: rigid part 1 has line "
                     "elements, whose mass is rho A L: expected an area > 0",
                     NULL);
    ctt_rmtree(dir);
}

/* A part whose meshes give it elements of another kind than its own. */
Test(errors_model, element_kind_mismatch)
{
    char dir[64];
    ctt_tmpdir(dir, "errm");
    ctt_write_file(dir, "deck.rad", DECK);
    deck_scene(dir, "shells_in_brick.yaml", "deck.rad", "element: brick",
               "element: brick");
    deck_scene(dir, "bricks_in_shell.yaml", "deck.rad", "element: shell, thickness: 0.01",
               "element: shell, thickness: 0.01");
    deck_scene(dir, "bricks_in_truss.yaml", "deck.rad", "element: shell, thickness: 0.01",
               "element: truss, area: 1e-4");
    deck_scene(dir, "shells_in_spring.yaml", "deck.rad", "element: spring, stiffness: 10",
               "element: brick");
    static const struct {
        const char *file, *want;
    } c[] = {
        {"shells_in_brick.yaml", "shells_in_brick.yaml:5: parts[0]: part 1 has element brick but "
                                 "its meshes give it shells (expected brick elements only)"},
        {"bricks_in_shell.yaml", "bricks_in_shell.yaml:6: parts[1]: part 2 has element shell but "
                                 "its meshes give it bricks (expected shell elements only)"},
        {"bricks_in_truss.yaml", "bricks_in_truss.yaml:6: parts[1]: part 2 has element truss but "
                                 "its meshes give it bricks (expected truss elements only)"},
        {"shells_in_spring.yaml", "shells_in_spring.yaml:5: parts[0]: part 1 has element spring "
                                  "but its meshes give it shells (expected spring elements "
                                  "only)"},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        ctt_cli r = {0};
        cte_run(&r, dir, "", "check %s", c[i].file);
        CTE_EXPECT(&r, CTD_EXIT_BADINPUT, c[i].want, NULL);
        cr_expect_eq(count_lines(r.err), 1, "%s: one message expected: %s", c[i].file, r.err);
        cr_expect_str_empty(r.out, "%s: check printed a summary: %s", c[i].file, r.out);
        ctt_cli_free(&r);
    }
    ctt_rmtree(dir);
}

/* An inverted brick: the scene's part and line, and the deck's element id
 * and line, in a deformable part and in a rigid one (whose masses come
 * from the same brick elements). */
Test(errors_model, inverted_deck_brick)
{
    char dir[64];
    ctt_tmpdir(dir, "errm");
    ctt_write_file(dir, "inverted.rad", DECK_INVERTED);
    deck_scene(dir, "brick.yaml", "inverted.rad", "element: shell, thickness: 0.01",
               "element: brick");
    deck_scene(dir, "rigid.yaml", "inverted.rad", "element: shell, thickness: 0.01",
               "element: rigid");
    expect_run_fails(dir, "brick.yaml", CTD_EXIT_BADINPUT,
                     "contact run: brick.yaml:6: parts[1]: cannot build the brick elements of "
                     "part 2 (/BRICK/2 element 7, inverted.rad:15): ",
                     "non-positive Jacobian");
    expect_run_fails(dir, "rigid.yaml", CTD_EXIT_BADINPUT,
                     "contact run: rigid.yaml:6: parts[1]: cannot build the rigid elements of "
                     "part 2 (/BRICK/2 element 7, inverted.rad:15): ",
                     "non-positive Jacobian");
    /* `contact check` tells the same and prints no summary. */
    ctt_cli r = {0};
    cte_run(&r, dir, "", "check rigid.yaml");
    CTE_EXPECT(&r, CTD_EXIT_BADINPUT, "contact check: rigid.yaml:6: parts[1]: ",
               "(/BRICK/2 element 7, inverted.rad:15)");
    cr_expect_str_empty(r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* A node in two rigid parts: the second part is named, with both ids. */
Test(errors_model, node_in_two_rigid_parts)
{
    char dir[64];
    ctt_tmpdir(dir, "errm");
    ctt_write_file(dir, "deck.rad", DECK);
    deck_scene(dir, "two.yaml", "deck.rad", "element: rigid, thickness: 0.01", "element: rigid");
    expect_run_fails(dir, "two.yaml", CTD_EXIT_BADINPUT,
                     "contact run: two.yaml:6: parts[1]: node 2 belongs to two rigid parts (1 and "
                     "2); expected each node in one rigid body at most",
                     NULL);
    ctt_rmtree(dir);
}

/* A block of 8e6 bricks with 100 MB of address space: the generator's
 * arrays cannot be had. Exit 5 (out of memory, as a run that cannot hold
 * its scene or its solver's arrays), the mesh entry named, nothing
 * written. Skipped under the sanitizers, whose shadow memory needs more
 * address space than the limit. */
Test(errors_model, out_of_memory_building_the_model)
{
    if (ctt_checking())
        cr_skip_test("address-space limit under a sanitizer");
    char dir[64], part[256];
    ctt_tmpdir(dir, "errm");
    snprintf(part, sizeof part, "element: brick, %s", STEEL);
    gen_scene(dir, "big.yaml", "kind: block, part: 1, cells: [200, 200, 200], size: [1, 1, 1]",
              part);
    ctt_cli r = {0};
    cte_run(&r, dir, "ulimit -v 100000;", "run big.yaml --out out --quiet");
    CTE_EXPECT(&r, CTD_EXIT_OUTPUT,
               "contact run: big.yaml:3: mesh[0]: cannot generate the block mesh: out of memory",
               NULL);
    cr_expect(!ctt_exists(dir, "out"));
    cte_run(&r, dir, "ulimit -v 100000;", "check big.yaml");
    CTE_EXPECT(&r, CTD_EXIT_OUTPUT, "contact check: big.yaml:3: mesh[0]: ", "out of memory");
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* A force whose selection matches no node: the run would go on without
 * it, so it is refused (loads.c), with the condition's line. */
Test(errors_model, load_on_no_node)
{
    char dir[64];
    ctt_tmpdir(dir, "errm");
    ctt_write_file(dir, "deck.rad", DECK);
    ctt_write_file(dir, "load.yaml",
                   "end_time: 1.0e-4\n"
                   "mesh:\n"
                   "  - import: {file: deck.rad}\n"
                   "parts:\n"
                   "  - {id: 1, element: shell, thickness: 0.01, material: {E: 2.1e11, nu: 0.3, "
                   "rho: 7800}}\n"
                   "  - {id: 2, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
                   "boundary:\n"
                   "  - {kind: fixed, nodes: {part: 2}}\n"
                   "  - {kind: force, nodes: {part: 1, where: \"z > 5\"}, value: [1, 0, 0]}\n");
    expect_run_fails(dir, "load.yaml", CTD_EXIT_BADINPUT,
                     "contact run: load.yaml:9: boundary[1].nodes: selects no node (kind force)", NULL);
    ctt_rmtree(dir);
}

/* The model's entry points refuse what no caller should pass (a missing
 * model or scene, a missing selection), without touching anything. */
Test(errors_model, api_arguments)
{
    cr_expect_eq(ctd_model_build(NULL, NULL, NULL, 0), CT_ERR_ARG);
    ctd_model m;
    memset(&m, 0xff, sizeof m);
    cr_expect_eq(ctd_model_build(&m, NULL, NULL, 0), CT_ERR_ARG);
    cr_expect_eq(m.mesh.nodes.n, 0, "the model is left empty");
    ctd_model_destroy(&m);
    ctd_model_destroy(NULL);
    ct_nodeset ns;
    cr_expect_eq(ctd_model_select_nodes(NULL, NULL, &ns, NULL, 0), CT_ERR_ARG);
    cr_expect_eq(ns.n, 0);
    cr_expect_null(ns.node);
    ct_surface su;
    cr_expect_eq(ctd_model_select_surface(NULL, NULL, &su, NULL, 0), CT_ERR_ARG);
    cr_expect_eq(su.n, 0);
    cr_expect_null(su.seg);
}
