/*
 * test_scene.c -- scene files: a valid scene loads with the values written
 * in it (and the documented defaults); each broken file is rejected with
 * exit code 2 and a message naming the file, the right line and the field.
 * The scene files are in tests/data/scenes/ (their line numbers are quoted
 * below; the broken ones are base_ok.yaml or valid.yaml with one change).
 * `contact check` on scene files is in test_scene_check.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "output.h"
#include "run.h"
#include "scene.h"
#include "solver.h"
#include "test_util.h"

#include <criterion/redirect.h>

#include "test_scene.h"

static ctd_scene *load_ok(const char *name)
{
    char p[1024];
    scene_path(p, sizeof p, name);
    static ctd_scene_err err;
    ctd_scene *sc = NULL;
    int rc = ctd_scene_load(p, &sc, &err);
    cr_assert_eq(rc, CT_OK, "%s: %s", name, err.count ? err.msg[0].text : "?");
    cr_assert_not_null(sc);
    return sc;
}

Test(scene, valid_scene_values)
{
    ctd_scene *sc = load_ok("valid.yaml");
    cr_assert_str_eq(sc->title, "ball on plate");
    cr_assert_eq(sc->end_time, 0.01);
    cr_assert_eq(sc->refine, 2);
    cr_assert_str_eq(sc->out_dir, "out/valid");
    cr_assert_eq(sc->output->every, 1.0e-4);
    cr_assert(sc->output->vtu && !sc->output->csv);
    cr_assert_eq(sc->output->format, CTD_VTU_ASCII);
    cr_assert_eq(sc->solver->dt_scale, 0.8);
    cr_assert_eq(sc->solver->threads, 2);

    /* Meshes: cells doubled by refine; node counts by the formulas of
     * scene.h: block (8+1)(8+1)(2+1) = 243, ball (6+1)^3 = 343, plate 5x5. */
    cr_assert_eq(sc->mesh_count, 3);
    const ctd_scene_generate *b = sc->mesh[0].generate, *ball = sc->mesh[1].generate;
    cr_assert_eq(b->kind, CTD_GEN_BLOCK);
    cr_assert(b->cells_eff[0] == 8 && b->cells_eff[1] == 8 && b->cells_eff[2] == 2);
    cr_assert(b->size_count == 3 && b->size[2] == 0.02);
    cr_assert(b->origin[0] == 0 && b->origin[1] == 0 && b->origin[2] == 0);
    cr_assert_eq(ball->kind, CTD_GEN_BALL);
    cr_assert_eq(ball->radius, 0.03);
    cr_assert(ball->origin[0] == 0.1 && ball->origin[2] == 0.06);
    cr_assert_eq(ball->cells_eff[0], 6);
    cr_assert_eq(sc->mesh[0].nnode, 243);
    cr_assert_eq(sc->mesh[1].nnode, 343);
    cr_assert_eq(sc->mesh[2].nnode, 25);
    cr_assert_eq(sc->mesh[0].first_id, 1);
    cr_assert_eq(sc->mesh[1].first_id, 244);
    cr_assert_eq(sc->mesh[2].first_id, 587);
    cr_assert_eq(sc->mesh[1].line, 9);

    /* Parts. */
    cr_assert_eq(sc->parts_count, 3);
    cr_assert_eq(sc->parts[1].element, CTD_ELEM_BRICK);
    cr_assert_eq(sc->parts[1].material.E, 7.0e10);
    cr_assert_eq(sc->parts[1].material.nu, 0.33);
    cr_assert_eq(sc->parts[1].material.rho, 2700);
    cr_assert_str_eq(sc->parts[2].name, "lid");
    cr_assert_eq(sc->parts[2].element, CTD_ELEM_RIGID);
    cr_assert_eq(sc->parts[2].line, 19);
    cr_assert_eq(sc->parts[2].thickness, 0.005);
    cr_assert_eq(ctd_scene_part_by_id(sc, 2), &sc->parts[1]);
    cr_assert_null(ctd_scene_part_by_id(sc, 4));
    cr_assert(sc->rigid_bodies_count == 1 && sc->rigid_bodies[0].part == 3);

    /* Boundary conditions. */
    cr_assert_eq(sc->boundary_count, 4);
    const ctd_scene_bc *fx = &sc->boundary[0];
    cr_assert_eq(fx->kind, CTD_BC_FIXED);
    cr_assert(fx->dof[0] == 1 && fx->dof[1] == 0 && fx->dof[2] == 1);
    cr_assert_eq(fx->nodes->part, 1);
    cr_assert_eq(fx->nodes->where.n, 2);
    cr_assert(ctd_where_eval(&fx->nodes->where, 0.0, 5.0, 0.0005));
    cr_assert(!ctd_where_eval(&fx->nodes->where, 0.0, 0.0, 0.001)); /* z < 0.001 is strict */
    cr_assert(!ctd_where_eval(&fx->nodes->where, -1e-9, 0.0, 0.0)); /* x >= 0 */
    cr_assert_eq(sc->boundary[1].kind, CTD_BC_INITIAL_VELOCITY);
    cr_assert(sc->boundary[1].value_count == 3 && sc->boundary[1].value[2] == -5);
    cr_assert(sc->boundary[2].nodes->ids_count == 3 && sc->boundary[2].nodes->ids[2] == 451);
    cr_assert_eq(sc->boundary[3].kind, CTD_BC_GRAVITY);
    cr_assert_null(sc->boundary[3].nodes);
    cr_assert_eq(sc->boundary[3].value[2], -9.81);

    /* Interfaces: given values and the type-dependent defaults. */
    cr_assert_eq(sc->interfaces_count, 4);
    const ctd_scene_interface *i24 = &sc->interfaces[0], *i7 = &sc->interfaces[1],
                              *i3 = &sc->interfaces[2], *i6 = &sc->interfaces[3];
    cr_assert_eq(i24->type, 24);
    cr_assert_str_eq(i24->label, "ball-plate");
    cr_assert(i24->Istf == 2 && i24->Stfac == 1.5 && i24->gap == 0.001 && i24->Fric == 0.2);
    cr_assert(i24->Ifiltr == 1 && i24->Xfreq == 0.5);
    cr_assert_eq(i24->search, CT_SEARCH_BSP);
    cr_assert_eq(i24->VisS, 1.0);
    cr_assert_eq(i24->self, 0);
    cr_assert_eq(i24->line, 31);
    cr_assert_eq(i7->self, 1);
    cr_assert_str_eq(i7->label, "if1");
    cr_assert(i7->Stfac == 1.0 && i7->VisS == 0.05);
    cr_assert_eq(i7->search, CT_SEARCH_BUCKET);
    cr_assert_eq(i7->line, 34);
    cr_assert_eq(i7->gap, 0.001);
    cr_assert(i3->Stfac == 0.2 && i3->VisS == 0.0);
    cr_assert_eq(i3->search, CT_SEARCH_TOPO);
    cr_assert_eq(i6->curve_count, 3);
    cr_assert(i6->curve[1][0] == 0.01 && i6->curve[1][1] == 1000 && i6->curve[2][1] == 5000);
    ctd_scene_free(sc);
}

Test(scene, defaults)
{
    ctd_scene *sc = load_ok("base_ok.yaml");
    cr_assert_str_eq(sc->out_dir, "out/base_ok");
    cr_assert_eq(sc->output->every, 0.01 / 100);
    cr_assert(sc->output->vtu && sc->output->csv);
    cr_assert_eq(sc->output->format, CTD_VTU_RAW); /* binary unless asked */
    cr_assert_eq(sc->solver->dt_scale, 0.9);
    cr_assert_eq(sc->solver->threads, 0);
    cr_assert_eq(sc->refine, 1);
    cr_assert_eq(sc->boundary[0].nodes->where.n, 1);
    cr_assert(sc->boundary[0].dof[0] && sc->boundary[0].dof[1] && sc->boundary[0].dof[2]);
    const ctd_scene_interface *f = &sc->interfaces[0];
    cr_assert(f->Istf == 0 && f->Stfac == 1.0 && f->VisS == 1.0 && f->gap == 0 && f->Tstop == 0);
    cr_assert_eq(f->search, CT_SEARCH_BUCKET);
    cr_assert_eq(sc->mesh[1].first_id, 19); /* block 3 x 3 x 2 = 18 nodes first */
    ctd_scene_free(sc);
}

Test(scene, import_deck)
{
    ctd_scene *sc = load_ok("import.yaml");
    const ctd_deck *d = sc->mesh[0].import->deck;
    cr_assert_not_null(d);
    cr_assert_eq(d->mesh.nodes.n, 16); /* tests/data/radioss/bricks.rad */
    cr_assert_eq(d->nbrick, 3);
    cr_assert_eq(sc->mesh[0].nnode, 16);
    /* The generated plate's nodes follow the deck's largest id (16). */
    cr_assert_eq(sc->mesh[1].first_id, 17);
    cr_assert_eq(sc->mesh[1].nnode, 9);
    cr_assert_not_null(strstr(sc->mesh[0].import->path, "radioss/bricks.rad"));
    ctd_scene_free(sc);
}

/* A broken file: the load fails with `code`, and the first message names
 * the file, ":LINE:", the field, and contains `what`. */
typedef struct broken {
    const char *file;
    int line;
    const char *field;
    const char *what;
    int code;
} broken;

static const broken broken_files[] = {
    {"missing_field.yaml", 8, "parts[1].material", "required field missing (expected a mapping with keys E, nu, rho)", CT_ERR_ARG},
    {"missing_thickness.yaml", 8, "parts[1].thickness", "required field missing for element shell", CT_ERR_ARG},
    {"missing_end_time.yaml", 1, "end_time", "required field missing (expected a number)", CT_ERR_ARG},
    {"wrong_type.yaml", 12, "interfaces[0].Fric", "expected a number, got 'rough'", CT_ERR_ARG},
    {"bad_block.yaml", 13, "mesh[1].generate.radius", "expected a number, got 'big'", CT_ERR_ARG},
    {"unknown_interface.yaml", 12, "interfaces[0].type", "expected one of 3, 5, 6, 7, 11, 24, got 9", CT_ERR_ARG},
    {"unknown_key.yaml", 12, "interfaces[0].Frik", "unknown field, expected one of type, name, main", CT_ERR_ARG},
    {"bad_search.yaml", 12, "interfaces[0].search", "expected one of direct, topological, bucket, bsp, got 'octree'", CT_ERR_ARG},
    {"bad_pressure_area.yaml", 12, "interfaces[0].pressure_area", "expected one of main, secondary, got 'nodal'", CT_ERR_ARG},
    {"bad_pressure_area_type11.yaml", 12, "interfaces[0].pressure_area", "expected main for type 11 (edge to edge: its nodes have no area), got secondary", CT_ERR_ARG},
    {"bad_output_format.yaml", 4, "output.format", "expected one of binary, ascii, got 'hdf5'", CT_ERR_ARG},
    {"bad_part_ref.yaml", 12, "interfaces[0].secondary.part", "part 7 does not exist", CT_ERR_RANGE},
    {"bad_node_ref.yaml", 10, "boundary[0].nodes.ids[2]", "node 9999 does not exist", CT_ERR_RANGE},
    {"impossible_param.yaml", 7, "parts[0].material.nu", "expected a number in (-1, 0.5), got 0.5", CT_ERR_ARG},
    {"nan_end_time.yaml", 2, "end_time", "expected a finite number", CT_ERR_NONFINITE},
    {"negative_gap.yaml", 13, "interfaces[0].gap", "expected a number >= 0", CT_ERR_ARG},
    {"bad_xfreq.yaml", 12, "interfaces[0].Xfreq", "expected a number in (0, 1] for Ifiltr 1, got 1.5", CT_ERR_ARG},
    {"bad_curve.yaml", 15, "interfaces[0].curve[2][0]", "strictly ascending order, got 0.01 after 0.02", CT_ERR_ARG},
    {"bad_where.yaml", 10, "boundary[0].nodes.where", "got 'z << 0.001'", CT_ERR_ARG},
    {"malformed.yaml", 5, "mesh[1].generate.origin", "malformed YAML: did not find expected ',' or ']'", CT_ERR_ARG},
    {"import_bad_deck.yaml", 4, "mesh[0].import.file", "bad_number.rad:5: field 'y' of /NODE", CT_ERR_ARG},
    {"import_missing_part.yaml", 4, "mesh[0].import.file", "the deck's part 3", CT_ERR_RANGE},
    {"bad_load_surface.yaml", 10, "boundary[1].surface", "required field missing for kind pressure", CT_ERR_ARG},
    {"bad_load_curve.yaml", 11, "boundary[0].curve[2][0]", "strictly ascending order, got 1e-05 after 2e-05", CT_ERR_ARG},
};

Test(scene, broken_files_name_file_line_field, .init = cr_redirect_stderr)
{
    static ctd_scene_err err;
    for (size_t k = 0; k < sizeof broken_files / sizeof broken_files[0]; k++) {
        const broken *b = &broken_files[k];
        char p[1024], want[1200];
        scene_path(p, sizeof p, b->file);
        ctd_scene *sc = (ctd_scene *)1;
        int rc = ctd_scene_load(p, &sc, &err);
        cr_assert_eq(rc, b->code, "%s: code %d, expected %d (%s)", b->file, rc, b->code,
                     err.msg[0].text);
        cr_assert_null(sc, "%s", b->file);
        cr_assert_geq(err.count, 1, "%s", b->file);
        const ctd_scene_msg *m = &err.msg[0];
        snprintf(want, sizeof want, "%s:%d: %s: ", p, b->line, b->field);
        cr_assert_eq(strncmp(m->text, want, strlen(want)), 0, "%s: got \"%s\", expected it to start \"%s\"",
                     b->file, m->text, want);
        cr_assert_not_null(strstr(m->text, b->what), "%s: \"%s\" lacks \"%s\"", b->file, m->text,
                           b->what);
        cr_assert_eq(m->line, b->line, "%s", b->file);
        cr_assert_str_eq(m->field, b->field, "%s", b->file);
        cr_assert_eq(ctd_check_main(p, 0, NULL), CTD_EXIT_BADINPUT, "%s", b->file);
    }
}

/* A Radioss deck given where a scene is expected: libyaml reads one as
 * malformed YAML (a '/' line after comments) or as one long string; either
 * way the error says what the file is, at its first keyword, and how a scene
 * reads a deck, and `contact check` exits 2. A malformed scene keeps its
 * own message (broken_files). */
Test(scene, radioss_deck_given_as_scene_is_named, .init = cr_redirect_stderr)
{
    static ctd_scene_err err;
    const struct {
        const char *file, *kw;
        int line;
    } decks[] = {{"../radioss/nan_coord.rad", "/NODE", 2},
                 {"../radioss/bricks.rad", "/NODE", 3},
                 {"../radioss/no_node.rad", "/PART/1", 2}};
    for (size_t k = 0; k < sizeof decks / sizeof decks[0]; k++) {
        char p[1024], want[1200];
        scene_path(p, sizeof p, decks[k].file);
        ctd_scene *sc = (ctd_scene *)1;
        cr_assert_eq(ctd_scene_load(p, &sc, &err), CT_ERR_ARG, "%s", decks[k].file);
        cr_assert_null(sc);
        cr_assert_eq(err.count, 1, "%s: %d errors", decks[k].file, err.count);
        snprintf(want, sizeof want, "%s:%d: this is a Radioss deck (%s), not a scene: ", p,
                 decks[k].line, decks[k].kw);
        cr_assert_eq(strncmp(err.msg[0].text, want, strlen(want)), 0,
                     "got \"%s\", expected it to start \"%s\"", err.msg[0].text, want);
        cr_assert_not_null(strstr(err.msg[0].text, "mesh: [{import: {file: DECK}}]"));
        cr_assert_eq(err.msg[0].line, decks[k].line);
        cr_assert_eq(ctd_check_main(p, 0, NULL), CTD_EXIT_BADINPUT);
    }
}

Test(scene, one_error_per_problem)
{
    /* Only the one changed line is wrong in each file: no cascade. */
    static ctd_scene_err err;
    const char *files[] = {"bad_part_ref.yaml", "import_bad_deck.yaml", "unknown_interface.yaml"};
    for (int k = 0; k < 3; k++) {
        char p[1024];
        scene_path(p, sizeof p, files[k]);
        ctd_scene *sc = NULL;
        ctd_scene_load(p, &sc, &err);
        cr_assert_eq(err.count, 1, "%s: %d errors, first %s", files[k], err.count, err.msg[0].text);
    }
}

Test(scene, nonexistent_file, .init = cr_redirect_stderr)
{
    static ctd_scene_err err;
    ctd_scene *sc = NULL;
    const char *p = "/nonexistent/dir/scene.yaml";
    cr_assert_eq(ctd_scene_load(p, &sc, &err), CT_ERR_ARG);
    cr_assert_null(sc);
    cr_assert_str_eq(err.msg[0].text,
                     "/nonexistent/dir/scene.yaml: cannot open the scene file: No such file or "
                     "directory");
    cr_assert_eq(ctd_check_main(p, 0, NULL), CTD_EXIT_BADINPUT);
    cr_assert_eq(ctd_scene_load(NULL, &sc, &err), CT_ERR_ARG);
    /* A directory opens; libyaml then said "malformed YAML: input error". */
    cr_assert_eq(ctd_scene_load("/tmp", &sc, &err), CT_ERR_ARG);
    cr_assert_null(sc);
    cr_assert_str_eq(err.msg[0].text, "/tmp: cannot read the scene file: it is a directory");
}

Test(scene, names)
{
    cr_assert_str_eq(ctd_element_name(CTD_ELEM_SPRING), "spring");
    cr_assert_str_eq(ctd_gen_kind_name(CTD_GEN_FOLDED), "folded");
    cr_assert_str_eq(ctd_bc_kind_name(CTD_BC_INITIAL_VELOCITY), "initial_velocity");
    cr_assert_str_eq(ctd_element_name(99), "?");
}

/* ctd_scene_load_refined (contact run --refine N): the given refine
 * replaces the file's, multiplying every generated mesh's cells; 0 keeps
 * the file's; out of range is an error on the field "refine". */
Test(scene, refine_override)
{
    char p[1024];
    scene_path(p, sizeof p, "valid.yaml");
    static ctd_scene_err err;
    ctd_scene *base = NULL, *sc = NULL;
    cr_assert_eq(ctd_scene_load_refined(p, 0, &base, &err), CT_OK, "%s", err.msg[0].text);
    cr_assert_eq(ctd_scene_load_refined(p, 3, &sc, &err), CT_OK, "%s", err.msg[0].text);
    cr_expect_eq(sc->refine, 3);
    int generated = 0;
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        const ctd_scene_generate *g = sc->mesh[i].generate, *g0 = base->mesh[i].generate;
        if (!g)
            continue;
        generated++;
        for (int k = 0; k < 3; k++)
            cr_expect_eq(g->cells_eff[k], g0->cells_eff[k] / base->refine * 3,
                         "mesh %u axis %d: %lld cells", i, k, (long long)g->cells_eff[k]);
    }
    cr_expect_gt(generated, 0);
    ctd_scene_free(sc);
    ctd_scene_free(base);
    cr_expect_eq(ctd_scene_load_refined(p, 1001, &sc, &err), CT_ERR_ARG);
    cr_expect_null(sc);
    cr_expect_str_eq(err.msg[0].field, "refine");
}

/* Deeply nested lists (found by review while fuzzing: the YAML tree was
 * built by a recursion without a limit, and 200000 '[' overflowed the
 * stack) are an error naming the file, the line and the field, not a
 * crash. */
Test(scene, deep_nesting_is_an_error)
{
    char p[256];
    snprintf(p, sizeof p, "/tmp/ct_scene_%ld_deep.yaml", (long)getpid());
    FILE *f = fopen(p, "w");
    cr_assert_not_null(f);
    fprintf(f, "end_time: 1\nmesh: ");
    for (int i = 0; i < 200000; i++)
        fputc('[', f);
    fputc('\n', f);
    fclose(f);
    static ctd_scene_err err;
    ctd_scene *sc = (ctd_scene *)1;
    int rc = ctd_scene_load(p, &sc, &err);
    unlink(p);
    cr_assert_eq(rc, CT_ERR_ARG, "code %d (%s)", rc, err.msg[0].text);
    cr_assert_null(sc);
    const ctd_scene_msg *m = &err.msg[0];
    cr_assert_eq(m->line, 2, "%s", m->text);
    cr_assert_eq(strncmp(m->field, "mesh[0][0]", 10), 0, "%s", m->text);
    cr_assert_not_null(strstr(m->text, "nested deeper than 64 levels"), "%s", m->text);
    char want[300];
    snprintf(want, sizeof want, "%s:2: mesh[0][0]", p);
    cr_assert_eq(strncmp(m->text, want, strlen(want)), 0, "%s", m->text);
}

/* Load the scene `text` from a temporary file; the load must fail with
 * one error (err->msg[0]); returns its code. */
static int load_text_fails(const char *text, ctd_scene_err *err)
{
    char p[256];
    write_scene_text(p, sizeof p, "text", text);
    ctd_scene *sc = (ctd_scene *)1;
    int rc = ctd_scene_load(p, &sc, err);
    unlink(p);
    cr_assert_neq(rc, CT_OK, "the scene was accepted:\n%s", text);
    cr_assert_null(sc);
    cr_assert_eq(err->count, 1, "%d errors: %s / %s", err->count, err->msg[0].text,
                 err->msg[1].text);
    return rc;
}

/* A generated mesh on a part whose element is unknown (found by fuzzing:
 * the element's -1 was used as a shift count, undefined behaviour that
 * UBSan reports) gets the one error on the element, nothing more. */
Test(scene, unknown_element_of_generated_part)
{
    static ctd_scene_err err;
    int rc = load_text_fails("end_time: 1\n"
                             "mesh:\n"
                             "  - generate: {kind: block, part: 1, cells: [1, 1, 1],"
                             " size: [1, 1, 1]}\n"
                             "parts:\n"
                             "  - {id: 1, element: bric, material: {E: 1, nu: 0.3, rho: 1}}\n",
                             &err);
    cr_assert_eq(rc, CT_ERR_ARG, "code %d (%s)", rc, err.msg[0].text);
    cr_assert_eq(err.msg[0].line, 5);
    cr_assert_str_eq(err.msg[0].field, "parts[0].element");
    cr_assert_not_null(strstr(err.msg[0].text, "got 'bric'"), "%s", err.msg[0].text);
}

/* Cells whose node count overflows (found by review while fuzzing: (n+1)^3
 * with n = 1e8 overflowed int64, undefined behaviour, and the scene was
 * accepted with a wrapped node count) or exceeds what a mesh can index are
 * an error on the cells; so are folded layers beyond int (they were
 * truncated: 4294967299 layers became 3). A folded sheet's count is known
 * without making it (it was made to be counted, and too large a one passed
 * the check with an unknown count). */
Test(scene, generated_sizes_out_of_range)
{
    static ctd_scene_err err;
    const char *parts = "parts:\n"
                        "  - {id: 1, element: brick, material: {E: 1, nu: 0.3, rho: 1}}\n"
                        "  - {id: 2, element: shell, thickness: 0.001,"
                        " material: {E: 1, nu: 0.3, rho: 1}}\n";
    const struct {
        const char *mesh, *field, *what;
    } c[] = {
        {"  - generate: {kind: block, part: 1, cells: [100000000, 100000000, 100000000],"
         " size: [1, 1, 1]}\n",
         "mesh[0].generate.cells", "more than 2147483583 nodes"},
        {"  - generate: {kind: ball, part: 1, cells: [100000000], radius: 1}\n",
         "mesh[0].generate.cells", "more than 2147483583 nodes"},
        {"  - generate: {kind: block, part: 1, cells: [2000, 2000, 1000], size: [1, 1, 1]}\n",
         "mesh[0].generate.cells", "more than 2147483583 nodes"},
        {"  - generate: {kind: folded, part: 2, cells: [1000, 1000], size: [0.005],"
         " layers: 100000, spacing: 0.008}\n",
         "mesh[0].generate.cells", "more than 2147483583 nodes"},
        {"  - generate: {kind: folded, part: 2, cells: [8, 4], size: [0.005],"
         " layers: 4294967299, spacing: 0.008}\n",
         "mesh[0].generate.layers", "expected an integer in 1 .. 1e8, got 4294967299"},
    };
    for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
        char text[1024];
        snprintf(text, sizeof text, "end_time: 1\nmesh:\n%s%s", c[k].mesh, parts);
        int rc = load_text_fails(text, &err);
        cr_assert_eq(rc, CT_ERR_ARG, "case %zu: code %d (%s)", k, rc, err.msg[0].text);
        cr_assert_eq(err.msg[0].line, 3, "case %zu: %s", k, err.msg[0].text);
        cr_assert_str_eq(err.msg[0].field, c[k].field, "case %zu: %s", k, err.msg[0].text);
        cr_assert_not_null(strstr(err.msg[0].text, c[k].what), "case %zu: %s", k,
                           err.msg[0].text);
    }
}
