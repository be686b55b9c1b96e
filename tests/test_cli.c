/*
 * test_cli.c -- the `contact` program's command line (driver/main.c,
 * driver/run.c) run as a program, suite "cli": here help, bad usage and info
 * (the other commands in tests/test_cli*.c). Each run small, its exit
 * code and output checked against expectations found independently of the program:
 *
 *  - help: `contact --help` lists the five commands; each command's --help
 *    lists each of its options; the search families listed are those of
 *    ctd_case_families().
 *  - bad usage: no command, an unknown command, an unknown option, an
 *    option without its value and each option with a value out of its
 *    documented range exit 1 with a message naming it (exit codes: 0
 *    success, 1 bad usage, 2 bad input, 4 unstable, 5 output).
 *  - info: the build line is ct_build_info() of the library this test links
 *    (the compiler named by this file's own compiler macros, the precision
 *    of this build, a 12-digit commit); the machine line's counts are
 *    hwloc's, asked here; the thread count is OMP_NUM_THREADS.
 */
#include <errno.h>
#include <hwloc.h>
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

/* ---- help and bad usage -------------------------------------------------- */

Test(cli, help_lists_every_command_and_option)
{
    char dir[64];
    ctt_tmpdir(dir, "cli");
    ctt_cli r = {0};
    static const char *const cmds[] = {"info", "search", "demo", "run", "check"};
    static const char *const helps[] = {"--help", "-h", "help"};
    for (int h = 0; h < 3; h++) {
        ctt_cli_run(&r, dir, 2, "%s", helps[h]);
        cr_expect_eq(r.status, 0, "contact %s: exit %d", helps[h], r.status);
        cr_expect(strstr(r.out, "usage: contact <command>") != NULL, "%s", r.out);
        for (int c = 0; c < 5; c++) {
            char line[32];
            snprintf(line, sizeof line, "\n  %s ", cmds[c]);
            cr_expect(strstr(r.out, line) != NULL, "contact %s does not list %s:\n%s", helps[h],
                      cmds[c], r.out);
        }
        cr_expect_str_empty(r.err);
    }
    /* No command, and an unknown one: usage on the error stream, exit 1. */
    ctt_cli_run(&r, dir, 2, "");
    EXPECT_FAIL(&r, 1, "usage: contact <command>");
    cr_expect_str_empty(r.out);
    ctt_cli_run(&r, dir, 2, "frobnicate");
    EXPECT_FAIL(&r, 1, "unknown command 'frobnicate'");

    /* Each command's own help, with each of its options. */
    static const char *const run_opts[] = {"--out DIR", "--threads N", "--search ALGO",
                                           "--end T", "--dt-scale S", "--refine N",
                                           "--cycle-limit N", "--quiet"};
    ctt_cli_run(&r, dir, 2, "run --help");
    cr_expect_eq(r.status, 0);
    for (size_t k = 0; k < sizeof run_opts / sizeof run_opts[0]; k++)
        cr_expect(strstr(r.out, run_opts[k]) != NULL, "run --help lacks %s", run_opts[k]);
    cr_expect(strstr(r.out, "Exit codes: 0 success, 1 bad usage, 2 bad input, 4 the run went "
                            "unstable,\n5 an output file could not be written") != NULL,
              "%s", r.out);
    ctt_cli_run(&r, dir, 2, "run -h");
    cr_expect_eq(r.status, 0);
    cr_expect(strstr(r.out, "usage: contact run SCENE") != NULL);

    ctt_cli_run(&r, dir, 2, "check --help");
    cr_expect_eq(r.status, 0);
    cr_expect(strstr(r.out, "usage: contact check [--file-only] [--out DIR] [--search ALGO]") !=
              NULL);
    cr_expect(strstr(r.out, "  --file-only") != NULL && strstr(r.out, "  --out DIR") != NULL);

    static const char *const search_opts[] = {
        "--family F", "--n NODES", "--algo direct|topological|bucket|bsp|all",
        "--numbering natural|shuffled|sfc", "--gap G", "--margin M", "--filter hull|box",
        "--repeat R", "--seed S", "--threads T", "--check auto|off", "--renumber auto|on|off",
        "--renumber-keep K|fresh", "--dense auto|on|off", "--cells auto|F"};
    ctt_cli_run(&r, dir, 2, "search --help");
    cr_expect_eq(r.status, 0);
    for (size_t k = 0; k < sizeof search_opts / sizeof search_opts[0]; k++)
        cr_expect(strstr(r.out, search_opts[k]) != NULL, "search --help lacks %s",
                  search_opts[k]);
    /* The families line: exactly the generator's families, in its order. */
    int nf = 0;
    const char *const *fam = ctd_case_families(&nf);
    char want[512] = "\nFamilies:";
    for (int i = 0; i < nf; i++) {
        strcat(want, " ");
        strcat(want, fam[i]);
    }
    strcat(want, "\n");
    cr_expect(nf >= 10 && strstr(r.out, want) != NULL, "expected \"%s\" in:\n%s", want, r.out);
    ctt_cli_run(&r, dir, 2, "search -h");
    cr_expect_eq(r.status, 0);
    cr_expect(strstr(r.out, "usage: contact search") != NULL);

    /* info and demo take --help (or -h) and nothing else. */
    ctt_cli_run(&r, dir, 2, "info --help");
    cr_expect_eq(r.status, 0);
    cr_expect_str_eq(r.out, "usage: contact info\nPrints build provenance and the hwloc machine "
                            "summary.\n");
    ctt_cli_run(&r, dir, 2, "demo -h");
    cr_expect_eq(r.status, 0);
    cr_expect(strstr(r.out, "usage: contact demo\n") == r.out);
    cr_expect(strstr(r.out, "folded sheet") && strstr(r.out, "two plates") &&
              strstr(r.out, "graded mesh"), "%s", r.out);
    ctt_cli_run(&r, dir, 2, "info --verbose");
    EXPECT_FAIL(&r, 1, "contact info: unknown option '--verbose'");
    cr_expect_str_empty(r.out);
    ctt_cli_run(&r, dir, 2, "info now");
    EXPECT_FAIL(&r, 1, "contact info: unknown argument 'now'");
    /* Without the check the demo's minutes-long run started here. */
    ctt_cli_run(&r, dir, 2, "demo --quick");
    EXPECT_FAIL(&r, 1, "contact demo: unknown option '--quick'");
    cr_expect_str_empty(r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* ---- info ---------------------------------------------------------------- */

Test(cli, info_prints_provenance)
{
    char dir[64];
    ctt_tmpdir(dir, "cli");
    /* The machine as hwloc describes it, asked here. */
    hwloc_topology_t topo;
    cr_assert_eq(hwloc_topology_init(&topo), 0);
    cr_assert_eq(hwloc_topology_load(topo), 0);
    char machine[160];
    snprintf(machine, sizeof machine, "machine: packages=%d cores=%d pus=%d numa=%d",
             hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PACKAGE),
             hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_CORE),
             hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PU),
             hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_NUMANODE));
    hwloc_topology_destroy(topo);
    /* The compiler that built this file built the library too. */
#ifdef __clang__
    const char *compiler = "build: compiler=clang " __clang_version__ " flags=";
#else
    const char *compiler = "build: compiler=gcc " __VERSION__ " flags=";
#endif
    const char *precision = CTT_SINGLE ? " precision=single commit=" : " precision=double commit=";
    ctt_cli r = {0};
    for (int threads = 1; threads <= 2; threads++) {
        ctt_cli_run(&r, dir, threads, "info");
        cr_assert_eq(r.status, 0, "%s", r.err);
        cr_expect_str_empty(r.err);
        cr_assert_eq(count_lines(r.out), 3, "expected three lines:\n%s", r.out);
        const char *l2 = strchr(r.out, '\n') + 1, *l3 = strchr(l2, '\n') + 1;
        char build[2048];
        snprintf(build, sizeof build, "build: %s\n", ct_build_info());
        cr_expect(strncmp(r.out, build, strlen(build)) == 0, "line 1: %.*s, expected %s",
                  (int)(l2 - r.out), r.out, build);
        cr_expect(strncmp(r.out, compiler, strlen(compiler)) == 0, "expected %s...: %s",
                  compiler, r.out);
        const char *pc = strstr(r.out, precision);
        cr_assert_not_null(pc, "no \"%s\" in %s", precision, r.out);
        const char *commit = pc + strlen(precision);
        size_t hex = strspn(commit, "0123456789abcdef");
        cr_expect((hex == 12 && (commit[12] == '\n' || !strncmp(commit + 12, "-dirty\n", 7))) ||
                      !strncmp(commit, "none", 4),
                  "commit: %.20s", commit);
        cr_expect(strncmp(l2, machine, strlen(machine)) == 0, "line 2: %.*s, expected %s...",
                  (int)(l3 - l2), l2, machine);
        char th[32];
        snprintf(th, sizeof th, "threads: %d\n", threads);
        cr_expect_str_eq(l3, th);
    }
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

