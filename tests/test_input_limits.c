/*
 * test_input_limits.c -- the input a fuzzing campaign (docs/fuzz/REPORT.md)
 * found accepted with wrong values, or run without end: each case is now an
 * error naming the file's line and the field (exit 2).
 */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "run.h"
#include "scene.h"
#include "solver.h"
#include "test_util.h"

#include <criterion/redirect.h>

static void write_text(char *p, size_t n, const char *text)
{
    snprintf(p, n, "/tmp/ct_limits_%ld.yaml", (long)getpid());
    FILE *f = fopen(p, "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
}

/* The scene `text` is refused; its first error is on `line`, `field`, and
 * says `what`. */
static void expect_refused(const char *text, int line, const char *field, const char *what)
{
    static ctd_scene_err err;
    char p[256];
    write_text(p, sizeof p, text);
    ctd_scene *sc = (ctd_scene *)1;
    int rc = ctd_scene_load(p, &sc, &err);
    unlink(p);
    cr_assert_neq(rc, CT_OK, "accepted:\n%s", text);
    cr_assert_null(sc);
    cr_assert_geq(err.count, 1);
    cr_assert_eq(err.msg[0].line, line, "%s", err.msg[0].text);
    cr_assert_str_eq(err.msg[0].field, field, "%s", err.msg[0].text);
    cr_assert_not_null(strstr(err.msg[0].text, what), "%s", err.msg[0].text);
}

#define BRICK_PART "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
#define BLOCK "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"

/* libcyaml reads a number up to its first bad character: `part: 1e3` was
 * part 1, `cells: [2.5]` 2 cells, `cells: [010]` 8 (octal), `E: 2.1e11 7800`
 * 2.1e11. Every number is now read whole. */
Test(input_limits, numbers_are_read_whole)
{
    expect_refused("end_time: 1\nmesh:\n"
                   "  - generate: {kind: block, part: 1e3, cells: [1, 1, 1], size: [1, 1, 1]}\n"
                   "parts:\n" BRICK_PART,
                   3, "mesh[0].generate.part", "expected a decimal integer, got '1e3'");
    expect_refused("end_time: 1\nmesh:\n"
                   "  - generate: {kind: block, part: 1, cells: [1, 2.5, 1], size: [1, 1, 1]}\n"
                   "parts:\n" BRICK_PART,
                   3, "mesh[0].generate.cells[1]", "got '2.5'");
    expect_refused("end_time: 1\nmesh:\n"
                   "  - generate: {kind: block, part: 1, cells: [010, 1, 1], size: [1, 1, 1]}\n"
                   "parts:\n" BRICK_PART,
                   3, "mesh[0].generate.cells[0]", "got '010'");
    expect_refused("end_time: 1\nmesh:\n" BLOCK "parts:\n"
                   "  - {id: 1, element: brick, material: {E: 2.1e11 7800, nu: 0.3, rho: 1}}\n",
                   5, "parts[0].material.E", "expected a number, got '2.1e11 7800'");
    /* What is whole still loads, with its value. */
    static ctd_scene_err err;
    char p[256];
    write_text(p, sizeof p,
               "end_time: +2.5e-3\nsolver: {threads: 0, cycle_limit: 1000}\nmesh:\n" BLOCK
               "parts:\n"
               "  - {id: 1, element: brick, material: {E: 2.1E+11, nu: .3, rho: 7800.}}\n");
    ctd_scene *sc = NULL;
    cr_assert_eq(ctd_scene_load(p, &sc, &err), CT_OK, "%s", err.msg[0].text);
    unlink(p);
    cr_assert_eq(sc->end_time, 2.5e-3);
    cr_assert_eq(sc->parts[0].material.E, 2.1e11);
    cr_assert_eq(sc->parts[0].material.nu, 0.3);
    cr_assert_eq(sc->solver->cycle_limit, 1000);
    ctd_scene_free(sc);
}

/* A long value is quoted to 60 bytes; the cut fell inside a two-byte
 * character and left half of it in the message. "x" and 40 e-acutes: the
 * 60th byte is the first half of the 30th, so 29 are kept, then "...". */
Test(input_limits, long_values_are_cut_between_characters)
{
    char text[512], want[128];
    int k = snprintf(text, sizeof text, "end_time: 1\nmesh:\n  - generate: {kind: block, part: 1, "
                     "cells: [1, 1, 1], size: [x");
    for (int i = 0; i < 40; i++)
        k += snprintf(text + k, sizeof text - (size_t)k, "\xc3\xa9");
    snprintf(text + k, sizeof text - (size_t)k, ", 1, 1]}\nparts:\n" BRICK_PART);
    k = snprintf(want, sizeof want, "got 'x");
    for (int i = 0; i < 29; i++)
        k += snprintf(want + k, sizeof want - (size_t)k, "\xc3\xa9");
    snprintf(want + k, sizeof want - (size_t)k, "...'");
    expect_refused(text, 3, "mesh[0].generate.size[0]", want);
}

/* A generated mesh's `to` is checked finite, and no generated coordinate
 * may pass 1e74 (a rod from -1e308 overflowed the TYPE11 edge search). */
Test(input_limits, generated_coordinates_are_bounded)
{
    const char *rod = "  - {id: 1, element: truss, area: 1.0e-6,"
                      " material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n";
    char t[1024];
    snprintf(t, sizeof t, "end_time: 1\nmesh:\n"
             "  - generate: {kind: rod, part: 1, cells: [2], to: [nan, 0, 0]}\nparts:\n%s", rod);
    expect_refused(t, 3, "mesh[0].generate.to[0]", "expected a finite number, got nan");
    snprintf(t, sizeof t, "end_time: 1\nmesh:\n"
             "  - generate: {kind: rod, part: 1, cells: [2], origin: [-1e308, 0, 0],"
             " to: [1e308, 0, 0]}\nparts:\n%s", rod);
    expect_refused(t, 3, "mesh[0].generate", "expected at most 1e+74");
    expect_refused("end_time: 1\nmesh:\n"
                   "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [1e75, 1, 1]}\n"
                   "parts:\n" BRICK_PART,
                   3, "mesh[0].generate", "expected at most 1e+74");
}

/* Part ids are int32 in the model: 4294967297 was written as part 1. */
Test(input_limits, part_ids_fit_the_model)
{
    expect_refused("end_time: 1\nmesh:\n"
                   "  - generate: {kind: block, part: 4294967297, cells: [1, 1, 1],"
                   " size: [1, 1, 1]}\nparts:\n"
                   "  - {id: 4294967297, element: brick, material: {E: 1, nu: 0.3, rho: 1}}\n",
                   5, "parts[0].id", "expected an integer in 1 .. 2147483647");
}

/* `contact check` agreed to friction coefficients `contact run` refused,
 * and the kernel's message called 1e308 "not finite". */
Test(input_limits, friction_coefficients_checked_in_the_scene)
{
    const char *head = "end_time: 1\nmesh:\n" BLOCK
                       "  - generate: {kind: block, part: 2, cells: [1, 1, 1], size: [1, 1, 1],"
                       " origin: [0, 0, 0.02]}\nparts:\n" BRICK_PART
                       "  - {id: 2, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
                       "interfaces:\n";
    char t[2048];
    snprintf(t, sizeof t, "%s  - {type: 24, main: {part: 1}, secondary: {part: 2}, Fric: 1e308}\n",
             head);
    expect_refused(t, 9, "interfaces[0].Fric", "expected a number in [0, ");
    snprintf(t, sizeof t, "%s  - {type: 24, main: {part: 1}, secondary: {part: 2}, Ifric: 3,"
             " C2: 0.1, C4: 0.5, C5: 0.01, C6: 0.1}\n", head);
    expect_refused(t, 9, "interfaces[0].C4", "expects C4 = mu_min <= C2 = mu_d");
    /* Finite, above the kernels' bound (1e300 in double, 3e38 in single). */
    volatile double big = sizeof(ct_real) == 8 ? 1e308 : 3.3e38;
    ct_real c[7] = {(ct_real)big, 0, 0, 0, 0, 0, 0};
    ct_diag d = {0};
    cr_assert_eq(ct_friction_check(CT_FRIC_COULOMB, c, &d), CT_ERR_ARG);
    cr_assert_not_null(strstr(d.msg, "(Fric)"), "%s", d.msg);
}

/* E and rho each finite and > 0 were not enough: rho 4.9e-324 gave no
 * mass ("only springs attach it"), E 1e308 a step of 0 ("unstable"). */
Test(input_limits, material_units_are_bounded)
{
    expect_refused("end_time: 1\nmesh:\n" BLOCK "parts:\n"
                   "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 4.9e-324}}\n",
                   5, "parts[0].material", "check the units");
    expect_refused("end_time: 1\nmesh:\n" BLOCK "parts:\n"
                   "  - {id: 1, element: brick, material: {E: 1e308, nu: 0.3, rho: 7800}}\n",
                   5, "parts[0].material", "check the units");
}

/* Times too small for the arithmetic: end_time 4.9e-324 ran one step and
 * ended "ok" with a NaN external work. */
Test(input_limits, times_are_bounded)
{
    expect_refused("end_time: 4.9e-324\nmesh:\n" BLOCK "parts:\n" BRICK_PART, 1, "end_time",
                   "expected a number >= 1e-20");
    expect_refused("end_time: 1\nsolver: {dt_scale: 1e-30}\nmesh:\n" BLOCK "parts:\n" BRICK_PART,
                   2, "solver.dt_scale", "expected a number in [1e-6, 1]");
    expect_refused("end_time: 1\nsolver: {cycle_limit: 0}\nmesh:\n" BLOCK "parts:\n" BRICK_PART,
                   2, "solver.cycle_limit", "expected an integer in 1 .. 1e15");
}

/* Run `text` as `contact run SCENE --quiet [extra]`; returns the exit code. */
static int run_text(const char *text, const char *extra, const char *extra_value)
{
    char p[256], out[300];
    write_text(p, sizeof p, text);
    snprintf(out, sizeof out, "%s.out", p);
    char *argv[] = {p, "--out", out, "--quiet", (char *)extra, (char *)extra_value};
    int rc = ctd_run_main(extra ? 6 : 4, argv);
    unlink(p);
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", out);
    cr_assert_eq(system(cmd), 0);
    return rc;
}

/* Check `text` as `contact check SCENE`; returns the exit code. */
static int check_text(const char *text)
{
    char p[256];
    write_text(p, sizeof p, text);
    int rc = ctd_check_main(p, 0, NULL);
    unlink(p);
    return rc;
}

#define DROP                                                                                     \
    "mesh:\n"                                                                                    \
    "  - generate: {kind: plate, part: 1, cells: [1, 1], size: [0.04, 0.04],"                   \
    " origin: [-0.02, -0.02, 0]}\n"                                                              \
    "  - generate: {kind: block, part: 2, cells: [1, 1, 1], size: [0.01, 0.01, 0.01],"          \
    " origin: [-0.005, -0.005, 0.0011]}\n"                                                       \
    "parts:\n"                                                                                   \
    "  - {id: 1, element: rigid, thickness: 0.002, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n" \
    "  - {id: 2, element: brick, material: {E: 1.0e8, nu: 0.3, rho: 2000}}\n"                   \
    "boundary:\n"                                                                                \
    "  - {kind: fixed, nodes: {part: 1}}\n"

/* A contact stiffness that overflows gave a stable step of 0, read as "no
 * limit": the run ended "ok" with NaN contact energies. A run whose step
 * cannot reach end_time within solver.cycle_limit cycles ran for days. */
Test(input_limits, runs_that_cannot_end_well_stop_at_once, .init = cr_redirect_stderr)
{
    char t[2048];
    snprintf(t, sizeof t, "end_time: 2.0e-6\n%sinterfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}, Istf: 1, Stfac: 1.0e308}\n",
             DROP);
    cr_assert_eq(run_text(t, NULL, NULL), CTD_EXIT_BADINPUT);
    /* Stfac 1e20: a step of 7e-17 s, 3e10 cycles for 2 us. */
    snprintf(t, sizeof t, "end_time: 2.0e-6\n%sinterfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}, Istf: 1, Stfac: 1.0e20}\n",
             DROP);
    cr_assert_eq(run_text(t, NULL, NULL), CTD_EXIT_BADINPUT);
    /* The same scene with a sane stiffness runs; a cycle limit below what
     * it needs stops it, one above lets it finish. */
    snprintf(t, sizeof t, "end_time: 2.0e-6\n%sinterfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}}\n", DROP);
    cr_assert_eq(run_text(t, NULL, NULL), CTD_EXIT_OK);
    cr_assert_eq(run_text(t, "--cycle-limit", "3"), CTD_EXIT_BADINPUT);
    cr_assert_eq(run_text(t, "--cycle-limit", "100000"), CTD_EXIT_OK);
    cr_assert_eq(run_text(t, "--end", "9e18"), CTD_EXIT_BADINPUT);
}

/* `contact check` computes the first cycle's step as the run does: it
 * refuses the overflowing stiffness and the step that cannot reach
 * end_time within the cycle limit, without running (it read the file
 * only and said "ok"). */
static void quiet_both(void)
{
    cr_redirect_stdout();
    cr_redirect_stderr();
}

Test(input_limits, check_finds_what_the_first_cycle_finds, .init = quiet_both)
{
    char t[2048];
    snprintf(t, sizeof t, "end_time: 2.0e-6\n%sinterfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}, Istf: 1, Stfac: 1.0e308}\n",
             DROP);
    cr_assert_eq(check_text(t), CTD_EXIT_BADINPUT);
    snprintf(t, sizeof t, "end_time: 2.0e-6\n%sinterfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}, Istf: 1, Stfac: 1.0e20}\n",
             DROP);
    cr_assert_eq(check_text(t), CTD_EXIT_BADINPUT);
    snprintf(t, sizeof t, "end_time: 2.0e-6\n%sinterfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}}\n", DROP);
    cr_assert_eq(check_text(t), CTD_EXIT_OK);
    snprintf(t, sizeof t, "end_time: 2.0e-6\nsolver: {cycle_limit: 3}\n%sinterfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}}\n", DROP);
    cr_assert_eq(check_text(t), CTD_EXIT_BADINPUT);
    cr_assert_eq(run_text(t, NULL, NULL), CTD_EXIT_BADINPUT);
}

/* Finite velocities whose kinetic energy overflows: the energies are inf,
 * the runaway test (live > 100 ref) compares inf with inf and passed, and
 * the run ended "ok". It is unstable at cycle 0, and the check says so. */
Test(input_limits, infinite_energy_fails_the_run, .init = quiet_both)
{
    const char *t = "end_time: 1.0e-6\nmesh:\n"
                    "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
                    "parts:\n"
                    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
                    "boundary:\n"
                    "  - {kind: initial_velocity, nodes: {part: 1}, value: [0, 0, -1.0e200]}\n";
    cr_assert_eq(run_text(t, NULL, NULL), CTD_EXIT_UNSTABLE);
    cr_assert_eq(check_text(t), CTD_EXIT_UNSTABLE);
}

/* A deck that never ends (/dev/zero, a FIFO fed forever) was read until
 * the memory ran out; the reader stops at the first chunk holding a NUL
 * byte, and the scan names the line (without the stop it reads 1 GiB and
 * fails on the size instead). */
Test(input_limits, an_endless_deck_stops_at_its_first_chunk)
{
    expect_refused("end_time: 1.0e-6\nmesh:\n  - import: {file: /dev/zero}\nparts:\n" BRICK_PART,
                   3, "mesh[0].import.file", "/dev/zero:1: line of 65536 characters");
}

/* A deck file past 1 GiB is refused from its size, before any read (it
 * was read whole, 1 GiB of memory, before the limit fired). The file is
 * sparse: no disk, and a read of it would find NUL bytes at once, a
 * different message. */
Test(input_limits, a_deck_past_1_gib_is_refused_by_its_size)
{
    char deck[128], text[400];
    snprintf(deck, sizeof deck, "/tmp/ct_big_deck_%ld.rad", (long)getpid());
    FILE *f = fopen(deck, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(ftruncate(fileno(f), ((off_t)1 << 30) + 1), 0);
    fclose(f);
    snprintf(text, sizeof text,
             "end_time: 1.0e-6\nmesh:\n  - import: {file: %s}\nparts:\n" BRICK_PART, deck);
    char want[300];
    snprintf(want, sizeof want,
             "%s: the file has 1073741825 bytes, more than the 1073741824 (1 GiB) a deck may have",
             deck);
    expect_refused(text, 3, "mesh[0].import.file", want);
    unlink(deck);
}

/* A load that selects nothing is bad input (2), not "output" (5). */
Test(input_limits, empty_load_selection_is_bad_input, .init = cr_redirect_stderr)
{
    cr_assert_eq(run_text("end_time: 1.0e-6\nmesh:\n"
                          "  - generate: {kind: plate, part: 1, cells: [1, 1], size: [0.01, 0.01]}\n"
                          "parts:\n"
                          "  - {id: 1, element: shell, thickness: 0.001,"
                          " material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
                          "boundary:\n"
                          "  - {kind: fixed, nodes: {part: 1, where: \"x < 0.001\"}}\n"
                          "  - {kind: pressure, surface: {part: 1, where: \"z > 1e9\"},"
                          " pressure: 1}\n",
                          NULL, NULL),
                 CTD_EXIT_BADINPUT);
}
