/*
 * test_cli_run.c -- the `contact` program's command line (driver/main.c,
 * driver/run.c) run as a program, suite "cli": here `contact run` and `contact check`
 * (the other commands in tests/test_cli*.c). Each run small, its exit
 * code and output checked against expectations found independently of the program:
 *
 *  - run: --threads 1 and 2, and --search with each algorithm, give the same
 *    files byte for byte (history.csv, state.pvd, state_*.vtu; the summary
 *    names the threads and the search); --cycle-limit N accepts a run of
 *    exactly N cycles (the output interval caps the step, so the count is
 *    end_time / every) and refuses N - 1 (exit 2, naming the limit); --end,
 *    --refine (node counts (n+1)^3 by hand), --dt-scale (half the scale,
 *    twice the cycles), --quiet, --out and the default output directory;
 *    an unstable step exits 4, an unwritable directory 5.
 *  - check: a good scene's summary and first step (end_time / every
 *    cycles), the initial penetration of a block placed inside the gap
 *    (gap - height by hand), --file-only against the full check, --out,
 *    the run's options that change its answer (--refine, --end, --dt-scale,
 *    --cycle-limit, --search) and the errors' FILE:LINE: FIELD.
 */
#include <errno.h>
#include <hwloc.h>
#include <omp.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "meshgen.h"
#include "test_cli.h"
#include "test_util.h"

/* ---- Scenes ------------------------------------------------------------ */

/* A steel block of 2 x 2 x 2 bricks flying at 1 m/s. The output interval
 * (1e-7 s) is below the stable step (about 5e-7 s), so every step is the
 * interval and the run takes end_time / every = 50 cycles. */
static const char FLY[] =
    "title: cli fly\n"
    "end_time: 5.0e-6\n"
    "output: {every: 1.0e-7, vtu: false, csv: false}\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [2, 2, 2], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "boundary:\n"
    "  - {kind: initial_velocity, nodes: {part: 1}, value: [1, 0, 0]}\n";

/* The same with refine 2 and a cycle limit of 10 in the file. */
static const char FLY2[] =
    "title: cli fly refined\n"
    "end_time: 5.0e-6\n"
    "refine: 2\n"
    "output: {every: 1.0e-7, vtu: false, csv: false}\n"
    "solver: {cycle_limit: 10}\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [2, 2, 2], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "boundary:\n"
    "  - {kind: initial_velocity, nodes: {part: 1}, value: [1, 0, 0]}\n";

/* A soft block dropped at 1 m/s onto a clamped shell plate, 0.2 mm above
 * the TYPE24 gap: it touches, bounces and leaves in 0.6 ms (338 cycles),
 * with four output steps (t = 0, 2, 4, 6 x 1e-4 s). */
static const char DROP[] =
    "title: cli drop\n"
    "end_time: 6.0e-4\n"
    "output: {every: 2.0e-4, vtu: true, csv: true}\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [4, 4], size: [0.04, 0.04],"
    " origin: [-0.02, -0.02, 0]}\n"
    "  - generate: {kind: block, part: 2, cells: [2, 2, 2], size: [0.01, 0.01, 0.01],"
    " origin: [-0.005, -0.005, 0.0007]}\n"
    "parts:\n"
    "  - {id: 1, element: shell, thickness: 0.002, material: {E: 2.1e9, nu: 0.3, rho: 7800}}\n"
    "  - {id: 2, element: brick, material: {E: 1.0e7, nu: 0.3, rho: 1000}}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {part: 1}}\n"
    "  - {kind: initial_velocity, nodes: {part: 2}, value: [0, 0, -1]}\n"
    "interfaces:\n"
    "  - {type: 24, name: drop, main: {part: 1}, secondary: {part: 2}, gap: 0.0005}\n";

/* A steel block whose x = 0.01 face is thrown at 1 m/s (it vibrates); the
 * output interval is the end time, so the stable step sets the cycles. */
static const char WOBBLE[] =
    "title: cli wobble\n"
    "end_time: 2.0e-5\n"
    "output: {every: 2.0e-5, vtu: true, csv: true}\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [2, 2, 2], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "boundary:\n"
    "  - {kind: initial_velocity, nodes: {part: 1, where: \"x > 0.009\"}, value: [1, 0, 0]}\n";

/* A one-brick block whose bottom face is 0.4 mm above a rigid plate, inside
 * the interface's 1 mm gap: four nodes start 0.6 mm deep. */
static const char PEN[] =
    "end_time: 2.0e-6\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [1, 1], size: [0.04, 0.04],"
    " origin: [-0.02, -0.02, 0]}\n"
    "  - generate: {kind: block, part: 2, cells: [1, 1, 1], size: [0.01, 0.01, 0.01],"
    " origin: [-0.005, -0.005, 0.0004]}\n"
    "parts:\n"
    "  - {id: 1, element: rigid, thickness: 0.002, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
    "  - {id: 2, element: brick, material: {E: 1.0e8, nu: 0.3, rho: 2000}}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {part: 1}}\n"
    "interfaces:\n"
    "  - {type: 24, name: pen, main: {part: 1}, secondary: {part: 2}, gap: 0.001}\n";

/* A valid file whose model cannot be built: a rigid plate without the
 * thickness its mass needs (line 6). */
static const char RIGID[] =
    "title: rigid plate without thickness\n"
    "end_time: 0.01\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [2, 2], size: [0.1, 0.1]}\n"
    "parts:\n"
    "  - {id: 1, element: rigid, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n";

/* A file with a word where a number belongs (line 6, parts[0].material.E). */
static const char BAD[] =
    "title: broken\n"
    "end_time: 1.0e-3\n"
    "mesh:\n"
    "  - generate: {kind: block, part: 1, cells: [2, 2, 2], size: [0.01, 0.01, 0.01]}\n"
    "parts:\n"
    "  - {id: 1, element: brick, material: {E: stiff, nu: 0.3, rho: 7800}}\n";

/* A new temporary directory holding every scene above. */
static void scenes_dir(char *dir)
{
    ctt_tmpdir(dir, "cli");
    ctt_write_file(dir, "fly.yaml", FLY);
    ctt_write_file(dir, "fly2.yaml", FLY2);
    ctt_write_file(dir, "drop.yaml", DROP);
    ctt_write_file(dir, "wobble.yaml", WOBBLE);
    ctt_write_file(dir, "pen.yaml", PEN);
    ctt_write_file(dir, "rigid.yaml", RIGID);
    ctt_write_file(dir, "bad.yaml", BAD);
    ctt_write_file(dir, "plain.txt", "a regular file, not a directory\n");
}

/* 1 when the files DIR_A/NAME and DIR_B/NAME hold the same bytes (the
 * VTU files are binary: compared byte by byte to the end of both). */
static int same_file(const char *da, const char *db, const char *name)
{
    char pa[1200], pb[1200];
    snprintf(pa, sizeof pa, "%s/%s", da, name);
    snprintf(pb, sizeof pb, "%s/%s", db, name);
    FILE *fa = fopen(pa, "rb"), *fb = fopen(pb, "rb");
    cr_assert(fa && fb, "%s or %s missing", pa, pb);
    int ca, cb;
    long n = 0;
    do {
        ca = fgetc(fa);
        cb = fgetc(fb);
        n++;
    } while (ca == cb && ca != EOF);
    fclose(fa);
    fclose(fb);
    return ca == cb && n > 1;
}

/* The summary of a run in DIR/SUB (free it). */
static char *summary_of(const char *dir, const char *sub)
{
    char p[1200];
    snprintf(p, sizeof p, "%s/%s/summary.json", dir, sub);
    char *s = ctt_slurp(p);
    cr_assert_not_null(s, "%s missing", p);
    return s;
}


/* ---- run ----------------------------------------------------------------- */

/* The files of a run that do not depend on the threads or the search. */
static const char *const RESULT_FILES[] = {"history.csv", "state.pvd", "state_000000.vtu",
                                           "state_000001.vtu", "state_000002.vtu",
                                           "state_000003.vtu"};
#define NRESULT (sizeof RESULT_FILES / sizeof RESULT_FILES[0])

Test(cli, run_threads_and_search_give_identical_files)
{
    char dir[64];
    scenes_dir(dir);
    ctt_cli r = {0};
    /* The reference: two threads, the scene's search (bucket for TYPE24). */
    ctt_cli_run(&r, dir, 1, "run drop.yaml --out t2 --threads 2");
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    cr_expect(strncmp(r.out, "drop.yaml: ok after ", 20) == 0, "%s", r.out);
    cr_expect(strstr(r.out, " 2 threads)\n") != NULL, "%s", r.out);
    cr_expect(strstr(r.out, "  interface drop (type 24, bucket search)") != NULL, "%s", r.out);
    /* drop.yaml asks for both (the plot needs gnuplot: not checked). */
    cr_expect(strstr(r.out, "  files: t2/ (state.pvd + state_*.vtu for ParaView, history.csv, "
                            "summary.json") != NULL,
              "%s", r.out);
    char *s2 = summary_of(dir, "t2");
    cr_expect_eq(ctt_json_num(s2, "threads"), 2);
    /* Four output steps (t = 0, 2, 4, 6 x 1e-4 s) and no fifth file. */
    cr_expect_eq(ctt_json_num(s2, "output_steps"), 4);
    cr_expect(!ctt_exists(dir, "t2/state_000004.vtu"));
    /* The block touched the plate. */
    cr_expect_gt(ctt_json_num(s2, "max_active"), 0, "%s", s2);
    double cycles = ctt_json_num(s2, "cycles");
    cr_expect_gt(cycles, 100);
    free(s2);

    ctt_cli_run(&r, dir, 2, "run drop.yaml --out t1 --threads 1 --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect_str_empty(r.out, "--quiet printed: %s", r.out);
    char *s1 = summary_of(dir, "t1");
    cr_expect_eq(ctt_json_num(s1, "threads"), 1, "%s", s1);
    cr_expect_eq(ctt_json_num(s1, "cycles"), cycles);
    free(s1);
    char d1[128], d2[128];
    snprintf(d1, sizeof d1, "%s/t1", dir);
    snprintf(d2, sizeof d2, "%s/t2", dir);
    for (size_t f = 0; f < NRESULT; f++)
        cr_expect(same_file(d1, d2, RESULT_FILES[f]), "%s differs between 1 and 2 threads",
                  RESULT_FILES[f]);

    static const char *const algo[] = {"direct", "topological", "bucket", "bsp"};
    for (int k = 0; k < 4; k++) {
        char sub[32], ds[128];
        snprintf(sub, sizeof sub, "s_%s", algo[k]);
        snprintf(ds, sizeof ds, "%s/%s", dir, sub);
        ctt_cli_run(&r, dir, 2, "run drop.yaml --out %s --search %s --quiet", sub, algo[k]);
        cr_assert_eq(r.status, 0, "%s: %s", algo[k], r.err);
        char *s = summary_of(dir, sub);
        char name[64];
        snprintf(name, sizeof name, "\"search\": \"%s\"", algo[k]);
        cr_expect(strstr(s, name) != NULL, "--search %s not applied: %s", algo[k], s);
        free(s);
        for (size_t f = 0; f < NRESULT; f++)
            cr_expect(same_file(d2, ds, RESULT_FILES[f]), "%s differs with --search %s",
                      RESULT_FILES[f], algo[k]);
    }
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

Test(cli, run_cycle_limit_end_refine)
{
    char dir[64];
    scenes_dir(dir);
    ctt_cli r = {0};
    /* 5e-6 s in steps of 1e-7 s: 50 cycles, which a limit of 50 allows. */
    ctt_cli_run(&r, dir, 2, "run fly.yaml --out c50 --cycle-limit 50");
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    cr_expect(strncmp(r.out, "fly.yaml: ok after 50 cycles, t = 5e-06 of 5e-06 s", 50) == 0,
              "%s", r.out);
    char *s = summary_of(dir, "c50");
    cr_expect_eq(ctt_json_num(s, "cycles"), 50, "%s", s);
    free(s);
    /* One less is refused at once, naming the limit and the cycles needed. */
    ctt_cli_run(&r, dir, 2, "run fly.yaml --out c49 --cycle-limit 49 --quiet");
    EXPECT_FAIL(&r, 2, "would need 50 more cycles to reach end_time 5e-06, more than "
                       "solver.cycle_limit (49) allows");
    cr_expect(strstr(r.err, "contact run: error: cycle 0 (t = 0)") != NULL, "%s", r.err);
    /* The report lists the files the run wrote: fly.yaml asks for no
     * states and no history, so summary.json alone, refused or not (the
     * report listed the states, the history and the plot every time). */
    ctt_cli_run(&r, dir, 2, "run fly.yaml --out c49r --cycle-limit 49");
    cr_expect(strstr(r.out, "  files: c49r/ (summary.json)\n") != NULL, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "run fly.yaml --out c50r --cycle-limit 50");
    cr_expect(strstr(r.out, "  files: c50r/ (summary.json)\n") != NULL, "%s", r.out);
    /* The option replaces the file's limit (10), in both directions. */
    ctt_cli_run(&r, dir, 2, "run fly2.yaml --out l10 --quiet --refine 1");
    EXPECT_FAIL(&r, 2, "solver.cycle_limit (10)");
    ctt_cli_run(&r, dir, 2, "run fly2.yaml --out l50 --quiet --refine 1 --cycle-limit 50");
    cr_expect_eq(r.status, 0, "%s", r.err);

    /* --end: 2e-6 s is 20 steps of 1e-7 s. */
    ctt_cli_run(&r, dir, 2, "run fly.yaml --out end --end 2e-6 --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    s = summary_of(dir, "end");
    cr_expect_eq(ctt_json_num(s, "cycles"), 20, "%s", s);
    cr_expect(fabs(ctt_json_num(s, "end_time") - 2e-6) < 1e-18, "%s", s);
    cr_expect(fabs(ctt_json_num(s, "time_reached") - 2e-6) < 1e-18, "%s", s);
    free(s);

    /* --refine: 2 x 2 x 2 bricks become 4 x 4 x 4 (5^3 nodes, 64 bricks); on
     * a file with refine 2, --refine 1 gives back 3^3 nodes and 8 bricks. */
    ctt_cli_run(&r, dir, 2, "run fly.yaml --out r2 --refine 2 --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    s = summary_of(dir, "r2");
    cr_expect_eq(ctt_json_num(s, "nodes"), 125, "%s", s);
    cr_expect_eq(ctt_json_num(s, "elements"), 64, "%s", s);
    free(s);
    s = summary_of(dir, "l50");
    cr_expect_eq(ctt_json_num(s, "nodes"), 27, "%s", s);
    cr_expect_eq(ctt_json_num(s, "elements"), 8, "%s", s);
    free(s);
    ctt_cli_run(&r, dir, 2, "run fly2.yaml --out f2 --cycle-limit 100 --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    s = summary_of(dir, "f2");
    cr_expect_eq(ctt_json_num(s, "nodes"), 125, "the file's refine 2 not applied: %s", s);
    free(s);

    /* Without --out: the scene's default directory, out/<scene name>,
     * under the working directory; nothing else written there. */
    ctt_cli_run(&r, dir, 2, "run fly.yaml --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(ctt_exists(dir, "out/fly/summary.json"));
    /* The scene writes neither VTU nor CSV. */
    cr_expect(!ctt_exists(dir, "out/fly/history.csv") && !ctt_exists(dir, "out/fly/state.pvd"));
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

Test(cli, run_dt_scale_and_unstable)
{
    char dir[64];
    scenes_dir(dir);
    ctt_cli r = {0};
    /* The scene's dt_scale is the default 0.9; half of it takes twice the
     * cycles, give or take the rounding of end_time / step up. */
    ctt_cli_run(&r, dir, 2, "run wobble.yaml --out w90 --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    ctt_cli_run(&r, dir, 2, "run wobble.yaml --out w45 --dt-scale 0.45 --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    char *a = summary_of(dir, "w90"), *b = summary_of(dir, "w45");
    double n90 = ctt_json_num(a, "cycles"), n45 = ctt_json_num(b, "cycles");
    cr_expect(n90 >= 20 && fabs(n45 - 2 * n90) <= 2, "%g cycles at 0.45, %g at 0.9", n45, n90);
    free(a);
    free(b);
    /* Three times the stable step: unstable, exit 4, the last good state
     * written. */
    ctt_cli_run(&r, dir, 2, "run wobble.yaml --out w300 --dt-scale 3");
    EXPECT_FAIL(&r, 4, "contact run: unstable: cycle ");
    cr_expect(strstr(r.out, "wobble.yaml: unstable after ") == r.out, "%s", r.out);
    cr_expect(ctt_exists(dir, "w300/last_good.vtu"));
    char *s = summary_of(dir, "w300");
    cr_expect(strstr(s, "\"status\": \"unstable\"") != NULL, "%s", s);
    cr_expect_eq(ctt_json_num(s, "exit_code"), 4, "%s", s);
    free(s);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* Options refused with exit 1, the reason on stderr and nothing on stdout:
 * `contact <cmd> <args> fly.yaml` (before: options that take a value see
 * the scene's name as theirs) for each row. */
typedef struct bad_opt {
    const char *args, *msg;
} bad_opt;

static void expect_refused(ctt_cli *r, const char *dir, const char *cmd, const bad_opt *bad,
                           size_t n, int before)
{
    for (size_t k = 0; k < n; k++) {
        if (before)
            ctt_cli_run(r, dir, 2, "%s %s fly.yaml", cmd, bad[k].args);
        else
            ctt_cli_run(r, dir, 2, "%s fly.yaml %s", cmd, bad[k].args);
        EXPECT_FAIL(r, 1, bad[k].msg);
        cr_expect_str_empty(r->out, "%s %s printed: %s", cmd, bad[k].args, r->out);
    }
}

Test(cli, run_bad_usage_and_input)
{
    char dir[64];
    scenes_dir(dir);
    ctt_cli r = {0};
    ctt_cli_run(&r, dir, 2, "run");
    EXPECT_FAIL(&r, 1, "usage: contact run SCENE");
    ctt_cli_run(&r, dir, 2, "run --quiet");
    EXPECT_FAIL(&r, 1, "usage: contact run SCENE");
    ctt_cli_run(&r, dir, 2, "run fly.yaml drop.yaml");
    EXPECT_FAIL(&r, 1, "contact run: one scene expected, got 'fly.yaml' and 'drop.yaml'");
    static const bad_opt bad[] = {
        {"--fast", "contact run: option --fast needs a value"},
        {"--fast 1", "contact run: unknown option '--fast' (try --help)"},
        {"--out", "contact run: option --out needs a value"},
        {"--search quick", "--search expects direct, topological, bucket or bsp, got 'quick'"},
        {"--end 0", "--end expects a time > 0, got '0'"},
        {"--end -1e-3", "--end expects a time > 0, got '-1e-3'"},
        {"--end soon", "--end expects a time > 0, got 'soon'"},
        {"--dt-scale 0", "--dt-scale expects a number > 0, got '0'"},
        {"--dt-scale nan", "--dt-scale expects a number > 0, got 'nan'"},
        {"--refine 0", "--refine expects an integer in 1..1000, got '0'"},
        {"--refine 2.5", "--refine expects an integer in 1..1000, got '2.5'"},
        {"--refine 1001", "--refine expects an integer in 1..1000, got '1001'"},
        {"--cycle-limit 0", "--cycle-limit expects an integer in 1..1e15, got '0'"},
        {"--cycle-limit 1.5", "--cycle-limit expects an integer in 1..1e15, got '1.5'"},
        {"--cycle-limit 2e15", "--cycle-limit expects an integer in 1..1e15, got '2e15'"},
        {"--threads 0", "--threads expects an integer in 1..4096, got '0'"},
        {"--threads 1.5", "--threads expects an integer in 1..4096, got '1.5'"},
        {"--threads 4097", "--threads expects an integer in 1..4096, got '4097'"},
    };
    expect_refused(&r, dir, "run", bad, sizeof bad / sizeof bad[0], 0);
    cr_expect(!ctt_exists(dir, "out"), "a refused run wrote its output");
    /* Bad input: a missing file, a malformed field (file, line and field
     * named), a model that cannot be built. */
    ctt_cli_run(&r, dir, 2, "run nosuch.yaml");
    EXPECT_FAIL(&r, 2, "nosuch.yaml");
    ctt_cli_run(&r, dir, 2, "run bad.yaml");
    EXPECT_FAIL(&r, 2, "bad.yaml:6: parts[0].material.E: expected a number, got 'stiff'");
    ctt_cli_run(&r, dir, 2, "run rigid.yaml");
    EXPECT_FAIL(&r, 2, "contact run: rigid.yaml:6: parts[0].thickness");
    /* An output directory that cannot be made (under a regular file). */
    ctt_cli_run(&r, dir, 2, "run fly.yaml --out plain.txt/out --quiet");
    EXPECT_FAIL(&r, 5, "plain.txt/out");
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* ---- check --------------------------------------------------------------- */

/* The first number after `key` in text (0 when absent). */
static double number_after(const char *text, const char *key)
{
    const char *p = strstr(text, key);
    return p ? strtod(p + strlen(key), NULL) : 0;
}

/* check answers for the run the same options would make: --refine (the
 * node count (n+1)^3 by hand), --end (end / every cycles), --dt-scale (the
 * step in proportion), --cycle-limit (the run's refusal), --search; and
 * refuses the options it has no use for and bad values as run does. */
Test(cli, check_takes_the_runs_options)
{
    char dir[64];
    scenes_dir(dir);
    ctt_cli r = {0};
    ctt_cli_run(&r, dir, 2, "check fly.yaml --refine 2");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(strstr(r.out, "1 mesh (125 nodes)") != NULL, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "check --file-only fly.yaml --refine 3");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(strstr(r.out, "1 mesh (343 nodes)") != NULL, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "check fly2.yaml --refine 1 --cycle-limit 50");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(strstr(r.out, "1 mesh (27 nodes)") != NULL, "%s", r.out);
    cr_expect(strstr(r.out, "about 50 cycles to end_time 5e-06 (cycle_limit 50)") != NULL, "%s",
              r.out);
    /* --end: 2e-6 s in steps of 1e-7 s. */
    ctt_cli_run(&r, dir, 2, "check fly.yaml --end 2e-6");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(strstr(r.out, "about 20 cycles to end_time 2e-06") != NULL, "%s", r.out);
    /* --cycle-limit: refused as the run refuses it. */
    ctt_cli_run(&r, dir, 2, "check fly.yaml --cycle-limit 49");
    EXPECT_FAIL(&r, 2, "would need 50 more cycles to reach end_time 5e-06, more than "
                       "solver.cycle_limit (49) allows");
    /* --dt-scale: half the scale, twice the cycles (give or take the
     * rounding of end_time / step up, as for the run). */
    ctt_cli_run(&r, dir, 2, "check wobble.yaml");
    cr_assert_eq(r.status, 0, "%s", r.err);
    double n90 = number_after(r.out, "about ");
    cr_expect(strstr(r.out, "(the stable step x dt_scale 0.9") != NULL, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "check wobble.yaml --dt-scale 0.45");
    cr_assert_eq(r.status, 0, "%s", r.err);
    double n45 = number_after(r.out, "about ");
    cr_expect(strstr(r.out, "(the stable step x dt_scale 0.45") != NULL, "%s", r.out);
    /* The step is end_time / cycles, at most the stable step x scale (when
     * it is less, the line gives that one too). */
    double d45 = number_after(r.out, "first time step "), m45 = number_after(r.out, "0.45 = ");
    cr_expect(fabs(d45 * n45 / 2e-5 - 1) < 1e-3, "%g cycles of %g s", n45, d45);
    cr_expect(m45 == 0 || (m45 >= d45 && m45 * (n45 - 1) < 2e-5), "%s", r.out);
    cr_expect(n90 >= 20 && fabs(n45 - 2 * n90) <= 2, "%g cycles at 0.45, %g at 0.9", n45, n90);
    /* The cycles check announces are those the run makes. */
    ctt_cli_run(&r, dir, 2, "run wobble.yaml --out w45 --dt-scale 0.45 --quiet");
    cr_assert_eq(r.status, 0, "%s", r.err);
    char *js = summary_of(dir, "w45");
    cr_expect_eq(ctt_json_num(js, "cycles"), n45, "check said %g cycles: %s", n45, js);
    free(js);
    /* --search: a complete search finds the initial contact the default does. */
    ctt_cli_run(&r, dir, 2, "check pen.yaml --search direct");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(strstr(r.out, "pen.yaml: interface pen (type 24): 4 pairs in contact at t = 0") !=
                  NULL, "%s", r.out);
    /* Bad values and options check has no use for. */
    static const bad_opt bad[] = {
        {"--refine 0", "contact check: --refine expects an integer in 1..1000, got '0'"},
        {"--end soon", "contact check: --end expects a time > 0, got 'soon'"},
        {"--dt-scale -1", "contact check: --dt-scale expects a number > 0, got '-1'"},
        {"--cycle-limit 1.5", "contact check: --cycle-limit expects an integer in 1..1e15"},
        {"--search quick", "contact check: --search expects direct, topological, bucket or bsp"},
        {"--threads 2", "contact check: unknown option '--threads' (try --help)"},
        {"--quiet", "contact check: unknown option '--quiet' (try --help)"},
    };
    expect_refused(&r, dir, "check", bad, sizeof bad / sizeof bad[0], 1);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

Test(cli, check_scenes)
{
    char dir[64];
    scenes_dir(dir);
    ctt_cli r = {0};
    ctt_cli_run(&r, dir, 2, "check fly.yaml");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect_str_eq(r.out,
                     "fly.yaml: ok: \"cli fly\", end_time 5e-06, 1 mesh (27 nodes), 1 part, 0 "
                     "rigid bodies, 1 boundary condition, 0 interfaces, output to out/fly\n"
                     "fly.yaml: first time step 1e-07 s (output.every), about 50 cycles to "
                     "end_time 5e-06 (cycle_limit 100000000)\n");
    cr_expect_str_empty(r.err);
    /* Nothing written: not the default directory, not --out's. */
    ctt_cli_run(&r, dir, 2, "check --out new/deeper fly.yaml");
    cr_expect_eq(r.status, 0, "%s", r.err);
    cr_expect(!ctt_exists(dir, "out") && !ctt_exists(dir, "new"), "check created a directory");
    ctt_cli_run(&r, dir, 2, "check fly.yaml --out plain.txt/out");
    EXPECT_FAIL(&r, 5, "plain.txt/out");

    /* Contact at the start: none for the dropped block, four nodes 0.6 mm
     * deep (gap 1 mm - height 0.4 mm) for the block placed in the gap. */
    ctt_cli_run(&r, dir, 2, "check drop.yaml");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(strstr(r.out, "drop.yaml: interface drop (type 24): 0 pairs in contact at t = 0, "
                            "stable step ") != NULL, "%s", r.out);
    cr_expect(strstr(r.out, "drop.yaml: initial penetration: none") != NULL, "%s", r.out);
    /* The margin the interface chose (0.2 x its mean main edge), which the
     * run's report prints too. */
    cr_expect(strstr(r.out, ", re-sort margin ") != NULL, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "check pen.yaml");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect(strstr(r.out, "pen.yaml: interface pen (type 24): 4 pairs in contact at t = 0") !=
                  NULL, "%s", r.out);
    cr_expect(strstr(r.out, "pen.yaml: initial penetration: 4 nodes within the gap at t = 0, "
                            "the deepest 0.0006 at node ") != NULL, "%s", r.out);

    /* --file-only reads the file alone: the rigid plate without thickness
     * passes it (one summary line), the full check refuses the model. */
    ctt_cli_run(&r, dir, 2, "check --file-only rigid.yaml");
    cr_expect_eq(r.status, 0, "%s", r.err);
    cr_expect(strncmp(r.out, "rigid.yaml: ok: ", 16) == 0 && count_lines(r.out) == 1, "%s",
              r.out);
    ctt_cli_run(&r, dir, 2, "check rigid.yaml");
    EXPECT_FAIL(&r, 2, "contact check: rigid.yaml:6: parts[0].thickness: rigid part 1");
    cr_expect_str_empty(r.out);
    ctt_cli_run(&r, dir, 2, "check bad.yaml");
    EXPECT_FAIL(&r, 2, "bad.yaml:6: parts[0].material.E: expected a number, got 'stiff'");
    cr_expect(strstr(r.err, "bad.yaml: invalid scene (1 error)") != NULL, "%s", r.err);
    ctt_cli_run(&r, dir, 2, "check --file-only bad.yaml");
    EXPECT_FAIL(&r, 2, "bad.yaml:6: parts[0].material.E");
    ctt_cli_run(&r, dir, 2, "check nosuch.yaml");
    EXPECT_FAIL(&r, 2, "nosuch.yaml");

    /* Bad usage. */
    ctt_cli_run(&r, dir, 2, "check");
    EXPECT_FAIL(&r, 1, "usage: contact check");
    ctt_cli_run(&r, dir, 2, "check fly.yaml drop.yaml");
    EXPECT_FAIL(&r, 1, "contact check: one scene expected, got 'fly.yaml' and 'drop.yaml'");
    ctt_cli_run(&r, dir, 2, "check --strict fly.yaml");
    EXPECT_FAIL(&r, 1, "contact check: unknown option '--strict'");
    ctt_cli_run(&r, dir, 2, "check fly.yaml --out");
    EXPECT_FAIL(&r, 1, "contact check: option --out needs a value");
    cr_expect_str_empty(r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}


/* `--search topological` sets every interface's search but self contact's,
 * which it cannot find (a node's closest main node is itself): the
 * showcase's TYPE7 keeps its bucket search, says so, and still catches the
 * folding layers; TYPE11's edge search names what it runs (bucket for any
 * choice but direct). */
/* The repository's scene `name` by an absolute path (the runs are in a
 * directory of their own). */
static void repo_scene(char *scene, size_t n, const char *name)
{
    char rel[1024], cwd[512];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    ctt_tests_path(rel, sizeof rel, "../data/scenes/");
    const char *base = rel[0] == '/' ? "" : cwd, *sep = rel[0] == '/' ? "" : "/";
    snprintf(scene, n, "%s%s%s%s", base, sep, rel, name);
}

Test(cli, run_search_override_keeps_self_contact)
{
    char dir[64], scene[2048];
    ctt_tmpdir(dir, "cli");
    repo_scene(scene, sizeof scene, "showcase.yaml");
    ctt_cli r = {0};
    ctt_cli_run(&r, dir, 2, "run %s --out o --search topological", scene);
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    cr_expect(strstr(r.out, "--search topological: interface sheet-self (type 7) is self contact, "
                            "which the topological search cannot find; it keeps its bucket "
                            "search\n") != NULL,
              "%s", r.out);
    cr_expect(strstr(r.out, "interface ball-sheet (type 24, topological search)") != NULL, "%s",
              r.out);
    const char *t7 = strstr(r.out, "interface sheet-self (type 7, bucket search): max force ");
    cr_assert_not_null(t7, "%s", r.out);
    const char *act = strstr(t7, "max active pairs ");
    cr_assert_not_null(act);
    cr_expect_gt(atol(act + strlen("max active pairs ")), 0, "%s", r.out);
    repo_scene(scene, sizeof scene, "folding-sheet.yaml");
    ctt_cli_run(&r, dir, 2, "run %s --out o --search bsp --end 1e-5", scene);
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    cr_expect(strstr(r.out, "interface self (type 7, bsp search)") != NULL, "%s", r.out);
    cr_expect(strstr(r.out, "interface edges (type 11, bucket search)") != NULL, "%s", r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* The threads of a run nobody gave a count (no --threads, no
 * solver.threads, OMP_NUM_THREADS unset): one per CTD_NODES_PER_THREAD
 * nodes at most, OpenMP's count above that; any count given wins. */
Test(cli, run_threads_follow_the_model_size_unless_given)
{
    char dir[64], scene[2048];
    ctt_tmpdir(dir, "cli");
    repo_scene(scene, sizeof scene, "showcase.yaml");
    const int cores = omp_get_num_procs();
    ctt_cli r = {0};
    /* 730 nodes: one thread. */
    ctt_cli_run(&r, dir, 0, "run %s --out o --end 1e-5", scene);
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    cr_expect(strstr(r.out, "730 nodes") != NULL, "%s", r.out);
    cr_expect(strstr(r.out, " s wall, 1 thread)") != NULL, "%s", r.out);
    /* Given, by the option or the environment: two. */
    ctt_cli_run(&r, dir, 0, "run %s --out o --end 1e-5 --threads 2", scene);
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    cr_expect(strstr(r.out, " s wall, 2 threads)") != NULL, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "run %s --out o --end 1e-5", scene);
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    cr_expect(strstr(r.out, " s wall, 2 threads)") != NULL, "%s", r.out);
    /* Above one node per thread's worth, two where the machine has them:
     * the folding sheet at refine 3 (1144 nodes, 1.14x faster on two than
     * on one on this project's host) and the showcase at refine 2 (3659). */
    const struct {
        const char *file;
        int refine;
        const char *nodes;
    } big[] = {{"folding-sheet.yaml", 3, "1144 nodes"}, {"showcase.yaml", 2, "3659 nodes"}};
    for (size_t k = 0; k < sizeof big / sizeof big[0]; k++) {
        repo_scene(scene, sizeof scene, big[k].file);
        ctt_cli_run(&r, dir, 0, "run %s --out o --end 1e-6 --refine %d", scene, big[k].refine);
        cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
        cr_expect(strstr(r.out, big[k].nodes) != NULL, "%s", r.out);
        cr_expect(strstr(r.out, cores >= 2 ? " s wall, 2 threads)" : " s wall, 1 thread)") !=
                      NULL,
                  "%s", r.out);
    }
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}
