/*
 * test_errors_output.c -- output failures of a run (driver/output_*.c and
 * how solver.c, solver_report.c and run.c report them), suite
 * "errors_output". The tests run as root, for whom permission bits stop
 * nothing, so a file of the output is made unwritable in ways that stop
 * root too: a directory in its place (it cannot be opened for writing),
 * a symbolic link to /dev/full (every write fails with ENOSPC), or a
 * file-size limit (ulimit -f, writes past it fail with EFBIG). Each case
 * asserts exit 5, a message that names the file and the reason, and what
 * the run wrote or did not write; for a failure mid-run, the cycle.
 *
 *  - history.csv at the start (create, write) and mid-run (the size limit);
 *  - a VTU step (create; write, raw and ASCII), the PVD collection (its
 *    temporary file, the rename onto it);
 *  - summary.json at the end (create, write): the run's status is then
 *    "error" with the reason (it was "ok" with an empty message);
 *  - the energy plot's script: a warning, the run's results stand (exit 0);
 *  - the writers' own refusals of what no caller should pass.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "output.h"
#include "test_errors.h"

/* A steel block flying at 1 m/s for 4 steps with an output at each, in
 * FORMAT; vtu and csv as given. */
static void fly_scene(const char *dir, const char *name, int vtu, int csv, const char *format)
{
    char text[1024];
    snprintf(text, sizeof text,
             "title: fly\n"
             "end_time: 1.0e-6\n"
             "output: {every: 2.5e-7, vtu: %s, csv: %s, format: %s}\n"
             "mesh:\n"
             "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, 0.01]}\n"
             "parts:\n"
             "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
             "boundary:\n"
             "  - {kind: initial_velocity, nodes: {part: 1}, value: [1, 0, 0]}\n",
             vtu ? "true" : "false", csv ? "true" : "false", format);
    ctt_write_file(dir, name, text);
}

/* Make DIR/o/NAME a directory ("dir") or a link to /dev/full ("full"). */
static void spoil(const char *dir, const char *name, const char *how)
{
    char cmd[512];
    if (!strcmp(how, "dir"))
        snprintf(cmd, sizeof cmd, "mkdir -p '%s/o/%s'", dir, name);
    else
        snprintf(cmd, sizeof cmd, "mkdir -p '%s/o' && ln -s /dev/full '%s/o/%s'", dir, dir, name);
    cr_assert_eq(system(cmd), 0, "%s", cmd);
}

/* A fresh directory with the scenes, its output directory o/ spoilt. */
static void fresh(char *dir, const char *name, const char *how)
{
    ctt_tmpdir(dir, "erro");
    fly_scene(dir, "both.yaml", 1, 1, "binary");
    fly_scene(dir, "vtu.yaml", 1, 0, "binary");
    fly_scene(dir, "ascii.yaml", 1, 0, "ascii");
    fly_scene(dir, "csv.yaml", 0, 1, "binary");
    fly_scene(dir, "none.yaml", 0, 0, "binary");
    if (name)
        spoil(dir, name, how);
}

/* The status and exit code summary.json records, when it exists. */
static void expect_summary(const char *dir, const char *status, int code)
{
    char *s = cte_slurp_in(dir, "o/summary.json");
    cr_assert_not_null(s, "no o/summary.json");
    char want[64];
    snprintf(want, sizeof want, "\"status\": \"%s\"", status);
    cr_expect(strstr(s, want) != NULL, "summary lacks %s: %s", want, s);
    snprintf(want, sizeof want, "\"exit_code\": %d", code);
    cr_expect(strstr(s, want) != NULL, "summary lacks %s: %s", want, s);
    free(s);
}

/* history.csv cannot be created or written: the run stops before its
 * first step (the solver's set-up), nothing else is written. */
Test(errors_output, history_at_the_start)
{
    static const char *const how[2] = {"dir", "full"};
    static const char *const want[2] = {
        "contact run: cannot create CSV file 'o/history.csv': Is a directory",
        "contact run: cannot write CSV file 'o/history.csv': No space left on device"};
    for (int k = 0; k < 2; k++) {
        char dir[64];
        fresh(dir, "history.csv", how[k]);
        ctt_cli r = {0};
        cte_run(&r, dir, "", "run both.yaml --out o --quiet");
        CTE_EXPECT(&r, CTD_EXIT_OUTPUT, want[k], NULL);
        cr_expect(!ctt_exists(dir, "o/state_000000.vtu") && !ctt_exists(dir, "o/summary.json"),
                  "a run refused at its start wrote files");
        ctt_cli_free(&r);
        ctt_rmtree(dir);
    }
}

/* The history fills its 4 KiB (ulimit -f 8: 8 blocks of 512 bytes, the
 * output directory's probe just fits) at cycle 33: the run stops there
 * with exit 5 and says so in its summary; the rows before it are whole. */
Test(errors_output, history_mid_run)
{
    char dir[64];
    ctt_tmpdir(dir, "erro");
    ctt_write_file(dir, "long.yaml",
                   "end_time: 5.0e-6\n"
                   "output: {every: 1.0e-7, vtu: false, csv: true}\n"
                   "mesh:\n"
                   "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.01, 0.01, "
                   "0.01]}\n"
                   "parts:\n"
                   "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
                   "boundary:\n"
                   "  - {kind: initial_velocity, nodes: {part: 1}, value: [1, 0, 0]}\n");
    ctt_cli r = {0};
    cte_run(&r, dir, "trap '' XFSZ; ulimit -f 8;", "run long.yaml --out o --quiet");
    CTE_EXPECT(&r, CTD_EXIT_OUTPUT, "contact run: error: cycle ",
               "): cannot write CSV file 'o/history.csv': File too large");
    expect_summary(dir, "error", CTD_EXIT_OUTPUT);
    char *csv = cte_slurp_in(dir, "o/history.csv");
    cr_assert_not_null(csv);
    int rows = count_lines(csv);
    cr_expect(rows > 5 && rows < 51, "%d lines in the history", rows);
    char cyc[64];
    snprintf(cyc, sizeof cyc, "error: cycle %d (t = ", rows - 1);
    cr_expect(strstr(r.err, cyc) != NULL, "the failing cycle is the row after %d: %s", rows - 1,
              r.err);
    free(csv);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* The first VTU step, and the PVD collection after it, cannot be written:
 * the run stops at cycle 0, its summary says "error" and exit 5. */
Test(errors_output, vtu_and_pvd)
{
    static const struct {
        const char *file, *how, *scene, *want;
    } c[] = {
        {"state_000000.vtu", "dir", "vtu.yaml",
         "contact run: error: cycle 0 (t = 0): cannot create VTU file 'o/state_000000.vtu': Is "
         "a directory"},
        {"state_000000.vtu", "full", "vtu.yaml",
         "contact run: error: cycle 0 (t = 0): cannot write VTU file 'o/state_000000.vtu': No "
         "space left on device"},
        {"state_000000.vtu", "dir", "ascii.yaml",
         "contact run: error: cycle 0 (t = 0): cannot create VTU file 'o/state_000000.vtu': Is "
         "a directory"},
        {"state_000000.vtu", "full", "ascii.yaml",
         "contact run: error: cycle 0 (t = 0): cannot write VTU file 'o/state_000000.vtu': No "
         "space left on device"},
        {"state.pvd.tmp", "dir", "vtu.yaml",
         "contact run: error: cycle 0 (t = 0): cannot create PVD file 'o/state.pvd.tmp': Is a "
         "directory"},
        {"state.pvd.tmp", "full", "vtu.yaml",
         "contact run: error: cycle 0 (t = 0): cannot write PVD file 'o/state.pvd.tmp': No "
         "space left on device"},
        {"state.pvd", "dir", "vtu.yaml",
         "contact run: error: cycle 0 (t = 0): cannot rename PVD file to 'o/state.pvd': Is a "
         "directory"},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        char dir[64];
        fresh(dir, c[i].file, c[i].how);
        ctt_cli r = {0};
        cte_run(&r, dir, "", "run %s --out o --quiet", c[i].scene);
        CTE_EXPECT(&r, CTD_EXIT_OUTPUT, c[i].want, NULL);
        expect_summary(dir, "error", CTD_EXIT_OUTPUT);
        cr_expect(!ctt_exists(dir, "o/state_000001.vtu"), "%s: the run went on", c[i].file);
        ctt_cli_free(&r);
        ctt_rmtree(dir);
    }
}

/* summary.json cannot be written at the end of a run that went well: exit
 * 5, status "error" and the reason, in the message and in the report (the
 * run said "contact run: ok: " and nothing else). */
Test(errors_output, summary_at_the_end)
{
    static const char *const how[2] = {"dir", "full"};
    static const char *const want[2] = {
        "contact run: error: cannot create summary file 'o/summary.json': Is a directory",
        "contact run: error: cannot write summary file 'o/summary.json': No space left on "
        "device"};
    for (int k = 0; k < 2; k++) {
        char dir[64];
        fresh(dir, "summary.json", how[k]);
        ctt_cli r = {0};
        cte_run(&r, dir, "", "run vtu.yaml --out o --quiet");
        CTE_EXPECT(&r, CTD_EXIT_OUTPUT, want[k], NULL);
        cr_expect(ctt_exists(dir, "o/state_000004.vtu"), "the run's steps were all written");
        /* Not quiet: the report's first line says "error" and why. */
        cte_run(&r, dir, "", "run vtu.yaml --out o");
        cr_expect_eq(r.status, CTD_EXIT_OUTPUT);
        cr_expect(strstr(r.out, "vtu.yaml: error after 4 cycles") != NULL, "%s", r.out);
        cr_expect(strstr(r.out, want[k] + strlen("contact run: error: ")) != NULL, "%s", r.out);
        cr_expect_eq(count_lines(r.err), 1, "one message on stderr: %s", r.err);
        ctt_cli_free(&r);
        ctt_rmtree(dir);
    }
}

/* A run that went unstable and cannot write its summary either: its own
 * status and exit code stay, the summary's failure is added. */
Test(errors_output, summary_of_an_unstable_run)
{
    char dir[64];
    fresh(dir, "summary.json", "dir");
    ctt_write_file(dir, "wobble.yaml",
                   "end_time: 2.0e-4\n"
                   "output: {every: 2.0e-4, vtu: false, csv: false}\n"
                   "mesh:\n"
                   "  - generate: {kind: block, part: 1, cells: [2, 2, 2], size: [0.01, 0.01, "
                   "0.01]}\n"
                   "parts:\n"
                   "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
                   "boundary:\n"
                   "  - {kind: initial_velocity, nodes: {part: 1, where: \"x > 0.009\"}, value: "
                   "[1, 0, 0]}\n");
    ctt_cli r = {0};
    cte_run(&r, dir, "", "run wobble.yaml --out o --quiet --dt-scale 3");
    CTE_EXPECT(&r, CTD_EXIT_UNSTABLE, "contact run: unstable: cycle ",
               "; cannot create summary file 'o/summary.json': Is a directory");
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* The energy plot is a picture of history.csv: when its script cannot be
 * written the run warns and its results stand (exit 0, summary "ok"). */
Test(errors_output, plot_script)
{
    static const char *const how[2] = {"dir", "full"};
    static const char *const want[2] = {
        "contact: energy plot: cannot create gnuplot script 'o/energies.gp': Is a directory",
        "contact: energy plot: cannot write gnuplot script 'o/energies.gp': No space left on "
        "device"};
    for (int k = 0; k < 2; k++) {
        char dir[64];
        fresh(dir, "energies.gp", how[k]);
        ctt_cli r = {0};
        cte_run(&r, dir, "", "run csv.yaml --out o");
        CTE_EXPECT(&r, 0, want[k], NULL);
        expect_summary(dir, "ok", 0);
        cr_expect(!ctt_exists(dir, "o/energies.png"));
        ctt_cli_free(&r);
        ctt_rmtree(dir);
    }
}

/* The writers refuse, with a message, what no caller should pass: rows
 * before the header or without their interface arrays, a mesh without
 * positions, no directory. */
Test(errors_output, api_refusals)
{
    char dir[64], err[512] = "";
    ctt_tmpdir(dir, "erro");
    ctd_output *o = NULL;
    ctd_output_opts oo = {dir, NULL, 1, 1, CTD_VTU_RAW};
    cr_assert_eq(ctd_output_open(&o, &oo, err, sizeof err), CT_OK, "%s", err);
    ctd_history_row row = {0};
    cr_expect_eq(ctd_output_csv_row(o, &row), CT_ERR_ARG);
    cr_expect_str_eq(ctd_output_error(o), "CSV row before ctd_output_csv_begin");
    const char *names[1] = {""};
    cr_expect_eq(ctd_output_csv_begin(o, 1, names), CT_OK, "%s", ctd_output_error(o));
    cr_expect_eq(ctd_output_csv_row(o, &row), CT_ERR_ARG);
    cr_expect_str_eq(ctd_output_error(o), "CSV row without its per-interface arrays");
    ctd_output_close(o);
    char *csv = cte_slurp_in(dir, "history.csv");
    cr_assert_not_null(csv);
    cr_expect(strstr(csv, ",if0_force,if0_active,if0_resorts\n") != NULL,
              "an unnamed interface's columns: %s", csv);
    cr_expect_eq(count_lines(csv), 1, "no row was written: %s", csv);
    free(csv);
    cr_expect_str_eq(ctd_output_error(NULL), "no output");
    ctd_out_mesh m = {0};
    char path[128];
    snprintf(path, sizeof path, "%s/x.vtu", dir);
    cr_expect_eq(ctd_vtu_write(path, &m, err, sizeof err), CT_ERR_ARG);
    cr_expect(strstr(err, "x.vtu': incomplete mesh (positions or cells missing)") != NULL, "%s",
              err);
    cr_expect(!ctt_exists(dir, "x.vtu"));
    oo.dir = "";
    cr_expect_eq(ctd_output_open(&o, &oo, err, sizeof err), CT_ERR_ARG);
    cr_expect_str_eq(err, "no output directory given");
    cr_expect_eq(ctd_output_check_dir(NULL, err, sizeof err), CT_ERR_ARG);
    cr_expect_str_eq(err, "no output directory given");
    ctt_rmtree(dir);
}
