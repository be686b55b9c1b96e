/*
 * test_errors_scene_yaml.c -- the scene loader on YAML that is not a
 * scene's mapping, and on the YAML features around it (driver/scene_yaml.c,
 * scene_yaml_read.c, scene.c), suite "errors_scene_yaml": files without
 * content, a list or a scalar at the top, anchors and aliases, keys that
 * are not names, a second document, values of the wrong shape, booleans,
 * more errors than are shown, and a scene too large for the memory. Each
 * case is loaded twice: with ctd_scene_load (the code, the line and the
 * field of the first message) and by `contact check` (the exit code and
 * the same "FILE:LINE: FIELD: what" on its error stream).
 *
 * Defects these found (fixed in driver/scene_yaml_read.c, scene.c and
 * run.c, see each case): a file of only "---" blamed a line after its end;
 * a valid alias was refused as "got '*alias'"; a list as a key made the
 * tree read the key's entries as values ("nested deeper than 64 levels"
 * under a path of "?"); a second document was dropped without a word; a
 * misspelt boolean (`csv: flase`) was read as true; a scene too large for
 * the memory exited 2 (bad input).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "test_errors.h"

/* A scene that loads: a brick block (part 1, line 3) and its part (line
 * 5). Cases append lines 6 on. */
static const char OK_HEAD[] =
    "end_time: 1.0e-5\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n";

/* The keys of the top-level mapping, as the messages list them. */
#define TOP_KEYS "title, end_time, refine, output, solver, mesh, parts, rigid_bodies, boundary, interfaces"

typedef struct ycase {
    const char *text; /* the whole file */
    int code;         /* the load's code */
    int line;
    const char *field; /* "" when the message names none */
    const char *what;
} ycase;

/* The first message of a failed load of DIR/case.yaml holding c->text is
 * "case.yaml:LINE: FIELD: what" (no FIELD when ""), in-process and from
 * `contact check` (exit 2). */
static void expect_yaml_error(const char *dir, const ycase *c)
{
    char path[128], want[900];
    ctt_write_file(dir, "case.yaml", c->text);
    snprintf(path, sizeof path, "%s/case.yaml", dir);
    if (c->field[0])
        snprintf(want, sizeof want, "case.yaml:%d: %s: %s", c->line, c->field, c->what);
    else
        snprintf(want, sizeof want, "case.yaml:%d: %s", c->line, c->what);
    ctd_scene *sc = (ctd_scene *)1;
    ctd_scene_err e;
    memset(&e, 0, sizeof e);
    int rc = ctd_scene_load(path, &sc, &e);
    cr_expect_eq(rc, c->code, "%s: code %d, expected %d (%s)", c->text, rc, c->code,
                 e.count ? e.msg[0].text : "no message");
    cr_expect_null(sc, "%s", c->text);
    if (rc == CT_OK) {
        ctd_scene_free(sc);
        return;
    }
    cr_assert_geq(e.count, 1);
    cr_expect_eq(e.msg[0].line, c->line, "%s: %s", c->text, e.msg[0].text);
    cr_expect_str_eq(e.msg[0].field, c->field, "%s: %s", c->text, e.msg[0].text);
    cr_expect(strstr(e.msg[0].text, want) != NULL, "\"%s\" lacks \"%s\"", e.msg[0].text, want);
    ctt_cli r = {0};
    cte_run(&r, dir, "", "check case.yaml");
    CTE_EXPECT(&r, CTD_EXIT_BADINPUT, want, "case.yaml: invalid scene (");
    ctt_cli_free(&r);
}

static void run_ycases(const ycase *c, size_t n)
{
    char dir[64];
    ctt_tmpdir(dir, "erry");
    for (size_t i = 0; i < n; i++)
        expect_yaml_error(dir, &c[i]);
    ctt_rmtree(dir);
}

#define NO_CONTENT                                                                            \
    "the file holds no YAML content (it is empty, or only comments, blank lines and '---'), " \
    "expected a mapping with end_time, mesh, parts"

/* An empty file, one of comments and blanks, and documents without
 * content: one message on line 1. A file of "# c\n---\n# c\n" was blamed
 * on its line 4 (after its end) as "got an empty value". */
Test(errors_scene_yaml, files_without_content)
{
    static const ycase c[] = {
        {"", CT_ERR_ARG, 1, "", NO_CONTENT},
        {"# only a comment\n\n   \n# and another\n", CT_ERR_ARG, 1, "", NO_CONTENT},
        {"---\n", CT_ERR_ARG, 1, "", NO_CONTENT},
        {"# c\n---\n# c\n", CT_ERR_ARG, 1, "", NO_CONTENT},
        {"---\n...\n", CT_ERR_ARG, 1, "", NO_CONTENT},
    };
    run_ycases(c, sizeof c / sizeof c[0]);
}

/* A list, a scalar, a null or an empty quoted string at the top: the
 * line of the value, what was expected and what was found. */
Test(errors_scene_yaml, top_level_not_a_mapping)
{
    static const ycase c[] = {
        {"- end_time: 1\n- mesh: []\n", CT_ERR_ARG, 1, "",
         "expected a mapping with keys " TOP_KEYS ", got a list"},
        {"# a scene\n[end_time, 1]\n", CT_ERR_ARG, 2, "",
         "expected a mapping with keys " TOP_KEYS ", got a list"},
        {"end_time 1\n", CT_ERR_ARG, 1, "",
         "expected a mapping with keys " TOP_KEYS ", got 'end_time 1'"},
        {"\n\n~\n", CT_ERR_ARG, 3, "", "expected a mapping with keys " TOP_KEYS ", got '~'"},
        {"''\n", CT_ERR_ARG, 1, "",
         "expected a mapping with keys " TOP_KEYS ", got an empty value"},
    };
    run_ycases(c, sizeof c / sizeof c[0]);
}

/* A key that is a list or a mapping (YAML allows it; the scene's keys are
 * names): one error at the key, under the path of its mapping. The tree
 * used to read the key's own entries as the value and blamed a nesting
 * "deeper than 64 levels" under a path of "?.?.?...". */
Test(errors_scene_yaml, keys_that_are_not_names)
{
    static const ycase c[] = {
        {"? [a, b]\n: 1\nend_time: 1\n", CT_ERR_ARG, 1, "",
         "expected a name as the key of a mapping entry, got a list"},
        {"end_time: 1\n? {a: 1}\n: 2\n", CT_ERR_ARG, 2, "",
         "expected a name as the key of a mapping entry, got a mapping"},
        {"end_time: 1\nmesh:\n  - {[x]: 1}\n", CT_ERR_ARG, 3, "mesh[0]",
         "expected a name as the key of a mapping entry, got a list"},
        {"end_time: 1\nk: &k [a]\n*k : 2\n", CT_ERR_ARG, 3, "",
         "expected a name as the key of a mapping entry, got an alias of a list or mapping"},
    };
    run_ycases(c, sizeof c / sizeof c[0]);
}

/* A second document after a complete scene: libcyaml reads the first
 * only, and the scene below loaded with its second half (and its mistake)
 * ignored. */
Test(errors_scene_yaml, second_document_is_refused)
{
    char text[1024];
    snprintf(text, sizeof text, "%s---\nend_time: oops\n", OK_HEAD);
    const ycase c[] = {
        {text, CT_ERR_ARG, 6, "", "a second YAML document (after '---' or '...'): expected one "
                                  "scene per file"},
    };
    run_ycases(c, 1);
}

/* A key given twice and values of the wrong shape: what the schema
 * expects there (each phrase of scene_schema.c's description) and what
 * was found. */
Test(errors_scene_yaml, values_of_the_wrong_shape)
{
    static const struct {
        const char *line6, *field, *what;
    } w[] = {
        {"end_time: 2\n", "end_time", "field given twice"},
        {"refine: [2]\n", "refine", "expected an integer, got a list"},
        {"refine:\n", "refine", "expected an integer, got an empty value"},
        {"title: {a: 1}\n", "title", "expected a string, got a mapping"},
        {"solver: 5\n", "solver", "expected a mapping with keys dt_scale, threads, cycle_limit, "
                                  "got '5'"},
        {"boundary: 5\n", "boundary", "expected a list of mappings with keys kind, nodes, value, "
                                      "dofs, surface, pressure, curve, got '5'"},
        {"boundary: [{kind: force, nodes: {part: 1}, value: 5}]\n", "boundary[0].value",
         "expected a list of 3 numbers, got '5'"},
        {"boundary: [{kind: fixed, nodes: {ids: 5}}]\n", "boundary[0].nodes.ids",
         "expected a list (at least 1) of integers, got '5'"},
        {"interfaces: [{type: 7, main: {part: 1}, curve: 5}]\n", "interfaces[0].curve",
         "expected a list (at least 1) of [2 numbers], got '5'"},
        {"rigid_bodies: [{id: 1, part: \" 1\"}]\n", "rigid_bodies[0].part",
         "expected a decimal integer, got ' 1'"},
    };
    char dir[64];
    ctt_tmpdir(dir, "erry");
    for (size_t k = 0; k < sizeof w / sizeof w[0]; k++) {
        char text[1024];
        snprintf(text, sizeof text, "%s%s", OK_HEAD, w[k].line6);
        const ycase c = {text, CT_ERR_ARG, 6, w[k].field, w[k].what};
        expect_yaml_error(dir, &c);
    }
    /* The mesh entry's fields, on line 3. */
    static const struct {
        const char *gen, *field, *what;
    } g[] = {
        {"kind: rod, part: 1, cells: 5", "mesh[0].generate.cells",
         "expected a list (1 to 3) of integers, got '5'"},
        {"kind: rod, part: 1, cells: [5], origin: 5", "mesh[0].generate.origin",
         "expected a list of 3 numbers, got '5'"},
        {"kind: rod, part: 1, cells: [5], tri: [1]", "mesh[0].generate.tri",
         "expected true or false, got a list"},
        {"kind: [rod], part: 1, cells: [5]", "mesh[0].generate.kind",
         "expected a string, got a list"},
    };
    for (size_t k = 0; k < sizeof g / sizeof g[0]; k++) {
        char text[1024];
        snprintf(text, sizeof text, "end_time: 1\nmesh:\n  - generate: {%s}\n", g[k].gen);
        const ycase c = {text, CT_ERR_ARG, 3, g[k].field, g[k].what};
        expect_yaml_error(dir, &c);
    }
    const ycase m = {"end_time: 1\nmesh: 5\n", CT_ERR_ARG, 2, "mesh",
                     "expected a list (at least 1) of mappings with keys generate, import, got '5'"};
    expect_yaml_error(dir, &m);
    ctt_rmtree(dir);
}

/* ---- Anchors and aliases ---------------------------------------------------- */

/* Aliases repeat a material, a whole part, a boundary condition and a
 * number: the scene loads (it was refused: libcyaml ran with
 * CYAML_CFG_NO_ALIAS and the message read "expected a mapping with keys
 * E, nu, rho, got '*alias'"), each alias with its anchor's values, and
 * `contact check` passes it. */
Test(errors_scene_yaml, aliases_repeat_values)
{
    char dir[64], path[128];
    ctt_tmpdir(dir, "erry");
    ctt_write_file(dir, "alias.yaml",
                   "end_time: &t 2.0e-5\n"
                   "output: {every: *t}\n"
                   "mesh:\n"
                   "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
                   "  - generate: {kind: block, part: 2, cells: [1, 1, 1], size: [0.01, 0.01, 0.01],"
                   " origin: [0, 0, 0.02]}\n"
                   "  - generate: {kind: block, part: 3, cells: [1, 1, 1], size: [0.01, 0.01, 0.01],"
                   " origin: [0, 0, 0.04]}\n"
                   "parts:\n"
                   "  - &p1 {id: 1, element: brick, material: &steel {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
                   "  - {id: 2, element: brick, material: *steel}\n"
                   "  - {id: 3, element: brick, material: {E: 7.0e10, nu: 0.33, rho: 2700}}\n"
                   "boundary:\n"
                   "  - &fix {kind: fixed, nodes: {part: 1, where: \"z < 0.001\"}}\n"
                   "  - *fix\n");
    snprintf(path, sizeof path, "%s/alias.yaml", dir);
    ctd_scene *sc = NULL;
    ctd_scene_err e;
    int rc = ctd_scene_load(path, &sc, &e);
    cr_assert_eq(rc, CT_OK, "%s", e.count ? e.msg[0].text : "?");
    cr_expect_eq(sc->end_time, 2.0e-5);
    cr_expect_eq(sc->output->every, sc->end_time);
    cr_assert_eq(sc->parts_count, 3);
    const ctd_scene_material *m0 = &sc->parts[0].material, *m1 = &sc->parts[1].material;
    cr_expect(m1->E == m0->E && m1->nu == m0->nu && m1->rho == m0->rho,
              "part 2's material (%g, %g, %g) is not part 1's (%g, %g, %g)", m1->E, m1->nu,
              m1->rho, m0->E, m0->nu, m0->rho);
    cr_expect_eq(m0->E, 2.1e11);
    cr_expect_eq(sc->parts[2].material.E, 7.0e10, "the next part keeps its own material");
    cr_assert_eq(sc->boundary_count, 2);
    for (unsigned i = 0; i < 2; i++) {
        const ctd_scene_bc *b = &sc->boundary[i];
        cr_expect_eq(b->kind, CTD_BC_FIXED, "boundary[%u]", i);
        cr_assert_not_null(b->nodes, "boundary[%u]", i);
        cr_expect_eq(b->nodes->part, 1, "boundary[%u]", i);
        cr_expect_eq(b->nodes->where.n, 1, "boundary[%u]", i);
    }
    ctd_scene_free(sc);
    ctt_cli r = {0};
    cte_run(&r, dir, "", "check alias.yaml");
    cr_expect_eq(r.status, CTD_EXIT_OK, "%s", r.err);
    cr_expect(strstr(r.out, "alias.yaml: ok: \"\", end_time 2e-05, 3 meshes (24 nodes), 3 parts")
                  != NULL, "%s", r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* A mistake inside an aliased value is reported at each use, under each
 * use's path, on the line where the value is written (the anchor's). */
Test(errors_scene_yaml, error_inside_an_alias_at_each_use)
{
    char dir[64], path[128];
    ctt_tmpdir(dir, "erry");
    ctt_write_file(dir, "case.yaml",
                   "end_time: 1.0e-5\n"
                   "mesh:\n"
                   "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
                   "parts:\n"
                   "  - {id: 1, element: brick, material: &m {E: 2.1e11, nu: 0.7, rho: 7800}}\n"
                   "  - {id: 2, element: brick, material: *m}\n");
    snprintf(path, sizeof path, "%s/case.yaml", dir);
    ctd_scene *sc = NULL;
    ctd_scene_err e;
    cr_assert_eq(ctd_scene_load(path, &sc, &e), CT_ERR_ARG);
    cr_assert_eq(e.count, 2, "%d errors: %s", e.count, e.msg[0].text);
    for (int i = 0; i < 2; i++) {
        char field[64];
        snprintf(field, sizeof field, "parts[%d].material.nu", i);
        cr_expect_str_eq(e.msg[i].field, field);
        cr_expect_eq(e.msg[i].line, 5, "%s", e.msg[i].text);
    }
    ctt_rmtree(dir);
}

/* What an alias may not do: name no anchor, name an anchor whose node
 * contains it (a cycle: the anchor names its node once complete), nest
 * the tree deeper than 64 levels, or copy more than 100000 nodes in all
 * (ten levels of ten aliases: 10^7 nodes for the tree and again for
 * libcyaml). Each is one error at the alias, promptly. */
Test(errors_scene_yaml, alias_errors)
{
    static char deep[4096], bomb[2048];
    /* An anchor 40 levels deep used 30 levels down. */
    size_t off = (size_t)snprintf(deep, sizeof deep, "end_time: 1\na: &a ");
    for (int i = 0; i < 40; i++)
        deep[off++] = '[';
    for (int i = 0; i < 40; i++)
        deep[off++] = ']';
    off += (size_t)snprintf(deep + off, sizeof deep - off, "\nb: ");
    for (int i = 0; i < 30; i++)
        deep[off++] = '[';
    off += (size_t)snprintf(deep + off, sizeof deep - off, "*a");
    for (int i = 0; i < 30; i++)
        deep[off++] = ']';
    snprintf(deep + off, sizeof deep - off, "\n");
    /* The billion laughs, shortened. */
    off = (size_t)snprintf(bomb, sizeof bomb, "end_time: 1\nl0: &l0 [x, x, x, x, x, x, x, x, x, x]\n");
    for (int i = 1; i < 10; i++)
        off += (size_t)snprintf(bomb + off, sizeof bomb - off,
                                "l%d: &l%d [*l%d, *l%d, *l%d, *l%d, *l%d, *l%d, *l%d, *l%d, *l%d, "
                                "*l%d]\n",
                                i, i, i - 1, i - 1, i - 1, i - 1, i - 1, i - 1, i - 1, i - 1, i - 1,
                                i - 1);
    const ycase c[] = {
        {"end_time: 1\nmesh:\n  - generate: *g\n", CT_ERR_ARG, 3, "mesh[0].generate",
         "undefined alias *g: expected an anchor &g on a node that ends before it"},
        {"end_time: 1\nmesh: &m\n  - generate: {kind: rod, part: 1, cells: [1], to: [1, 0, 0]}\n"
         "  - *m\n",
         CT_ERR_ARG, 4, "mesh[1]", "undefined alias *m: expected an anchor &m on a node that ends"},
        {"end_time: 1\nsolver: &s {threads: *s}\n", CT_ERR_ARG, 2, "solver.threads",
         "undefined alias *s"},
        {"end_time: 1\nparts: [{id: 1, material: *later}]\nx: &later {E: 1}\n", CT_ERR_ARG, 2,
         "parts[0].material", "undefined alias *later"},
        {deep, CT_ERR_ARG, 3, "b[0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0]"
                              "[0][0][0][0][0][0][0][0]",
         "malformed YAML: lists and mappings nested deeper than 64 levels (through the alias *a)"},
        /* l(k) has 1 + 10 size(l(k-1)) nodes: 11, 111, 1111, 11111. The
         * copies for l1..l3 are 110 + 1110 + 11110 = 12330 nodes; seven
         * copies of l3 in l4 make 90107, the eighth, l4[7], 101218. */
        {bomb, CT_ERR_ARG, 6, "l4[7]",
         "the aliases copy more than 100000 nodes in all (at *l3), expected fewer or smaller "
         "aliases"},
    };
    run_ycases(c, sizeof c / sizeof c[0]);
}

/* ---- Booleans, many errors, no memory ---------------------------------------- */

/* libcyaml reads any word but false, no, off, disable and 0 as true: a
 * typo `csv: flase` wrote the history and exited 0. Only YAML's words
 * (true/false, yes/no, on/off, any case) are taken now. */
Test(errors_scene_yaml, booleans_are_words)
{
    static const char *const bad[] = {"flase", "3", "enable", "\"\""};
    char dir[64];
    ctt_tmpdir(dir, "erry");
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char text[1024], what[96];
        snprintf(text, sizeof text, "%soutput: {csv: %s}\n", OK_HEAD, bad[k]);
        snprintf(what, sizeof what, "expected true or false, got '%s'",
                 bad[k][0] == '"' ? "" : bad[k]);
        const ycase c = {text, CT_ERR_ARG, 6, "output.csv", what};
        expect_yaml_error(dir, &c);
    }
    /* The words themselves load, with their value. */
    static const struct {
        const char *word;
        bool value;
    } ok[] = {{"false", 0}, {"No", 0}, {"OFF", 0}, {"true", 1}, {"yes", 1}, {"On", 1}};
    for (size_t k = 0; k < sizeof ok / sizeof ok[0]; k++) {
        char text[1024], path[128];
        snprintf(text, sizeof text, "%soutput: {csv: %s}\n", OK_HEAD, ok[k].word);
        ctt_write_file(dir, "ok.yaml", text);
        snprintf(path, sizeof path, "%s/ok.yaml", dir);
        ctd_scene *sc = NULL;
        ctd_scene_err e;
        cr_assert_eq(ctd_scene_load(path, &sc, &e), CT_OK, "%s: %s", ok[k].word, e.msg[0].text);
        cr_expect_eq(sc->output->csv, ok[k].value, "%s", ok[k].word);
        ctd_scene_free(sc);
    }
    ctt_rmtree(dir);
}

/* Twenty errors: the first CTD_SCENE_MAXERR (16) are printed, then how
 * many more there were, and the count; exit 2. */
Test(errors_scene_yaml, more_errors_than_shown)
{
    char dir[64], text[4096];
    size_t off = (size_t)snprintf(text, sizeof text,
                                  "end_time: 1.0e-5\n"
                                  "mesh:\n"
                                  "  - generate: {kind: block, part: 1, cells: [1, 1, 1],"
                                  " size: [0.01, 0.01, 0.01]}\n"
                                  "parts:\n");
    for (int i = 1; i <= 20; i++)
        off += (size_t)snprintf(text + off, sizeof text - off,
                                "  - {id: %d, element: brick, material: {E: 2.1e11, nu: 0.5,"
                                " rho: 7800}}\n",
                                i);
    ctt_tmpdir(dir, "erry");
    ctt_write_file(dir, "many.yaml", text);
    char path[128];
    snprintf(path, sizeof path, "%s/many.yaml", dir);
    ctd_scene *sc = NULL;
    ctd_scene_err e;
    cr_expect_eq(ctd_scene_load(path, &sc, &e), CT_ERR_ARG);
    cr_expect_eq(e.count, 20);
    cr_expect_str_eq(e.msg[CTD_SCENE_MAXERR - 1].field, "parts[15].material.nu");
    ctt_cli r = {0};
    cte_run(&r, dir, "", "check many.yaml");
    CTE_EXPECT(&r, CTD_EXIT_BADINPUT, "many.yaml: 4 more errors not shown\n",
               "many.yaml: invalid scene (20 errors)\n");
    /* Parts 0..15 on lines 5..20, in order, and none after. */
    const char *p = r.err;
    for (int i = 0; i < 16; i++) {
        char want[128];
        snprintf(want, sizeof want,
                 "many.yaml:%d: parts[%d].material.nu: expected a number in (-1, 0.5), got 0.5\n",
                 5 + i, i);
        const char *q = strstr(p, want);
        cr_expect(q != NULL, "lacks \"%s\" in order: %s", want, r.err);
        p = q ? q + strlen(want) : p;
    }
    cr_expect(strstr(r.err, "parts[16]") == NULL, "%s", r.err);
    cr_expect_eq(count_lines(r.err), 18, "%s", r.err);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* A scene whose YAML tree does not fit in 100 MB of address space: a
 * list of 1.5 million node ids (3 MB of text, about 150 MB of tree, by
 * experiment it loads with 200 MB). Exit 5 (out of memory, as for the
 * model and the solver), a message naming the file, nothing written. It
 * exited 2, as if the file were wrong (the tree's failure was reported
 * as CT_ERR_ARG, and any failed load was exit 2). Skipped under the
 * sanitizers, whose shadow memory needs more address space. */
Test(errors_scene_yaml, out_of_memory_reading_the_scene)
{
    if (ctt_checking())
        cr_skip_test("address-space limit under a sanitizer");
    char dir[64], path[128];
    ctt_tmpdir(dir, "erry");
    snprintf(path, sizeof path, "%s/big.yaml", dir);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "%sboundary:\n  - {kind: fixed, nodes: {ids: [1", OK_HEAD);
    for (int i = 1; i < 1500000; i++)
        fputs(",1", f);
    fputs("]}}\n", f);
    cr_assert_eq(fclose(f), 0);
    ctt_cli r = {0};
    cte_run(&r, dir, "ulimit -v 100000;", "run big.yaml --out out --quiet");
    CTE_EXPECT(&r, CTD_EXIT_OUTPUT, "big.yaml: out of memory",
               "big.yaml: scene not loaded: out of memory\n");
    cr_expect(!ctt_exists(dir, "out"));
    cte_run(&r, dir, "ulimit -v 100000;", "check big.yaml");
    CTE_EXPECT(&r, CTD_EXIT_OUTPUT, "big.yaml: out of memory", NULL);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}
