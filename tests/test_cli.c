/*
 * test_cli.c -- the `contact` program's command line (driver/main.c,
 * driver/run.c), run as a program (suite "cli"): every command and every
 * option at least once, each run small (a few hundred cycles, a thousand
 * nodes), its exit code and output checked against expectations found
 * independently of the program:
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
 *  - search: with each algorithm and every option, the pair count printed
 *    is that of a direct search run here on the same case (ctd_case_make
 *    with the same family, size, numbering and seed; gap, margin and filter
 *    as given), and the case line names the nodes, numbering, gap, margin
 *    and filter asked for.
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
 *    and the errors' FILE:LINE: FIELD.
 *  - demo: its first case (the folded sheet) runs, each search checked
 *    against direct, the pair count that of a search run here; the demo is
 *    then stopped (its other cases take minutes).
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

/* Expect exit code `code`, and `what` (when not NULL) in the error stream. */
#define EXPECT_FAIL(r, code, what)                                                            \
    do {                                                                                      \
        cr_expect_eq((r)->status, (code), "exit %d, expected %d; stderr: %s", (r)->status,    \
                     (code), (r)->err);                                                       \
        if ((what) != NULL)                                                                   \
            cr_expect(strstr((r)->err, (what)) != NULL, "stderr lacks \"%s\": %s",            \
                      (const char *)(what), (r)->err);                                        \
    } while (0)

/* The number of lines of s. */
static int count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
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
    cr_expect(strstr(r.out, "usage: contact check [--file-only] [--out DIR] SCENE") != NULL);
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

/* ---- search -------------------------------------------------------------- */

/* A case as this test builds it, and its direct pair count. */
typedef struct ref_case {
    int nodes, sec, main;
    long pairs;
} ref_case;

/* The direct search on ctd_case_make(family, n, num, seed) with gap and
 * margin (< 0: 0.4 h and 0.1 h, h the mean main edge, as documented) and the
 * filter. */
static ref_case direct_ref(const char *family, int64_t n, ctd_numbering num, uint64_t seed,
                           double gap, double margin, ct_search_filter filter)
{
    ctd_case c;
    ct_diag d;
    memset(&d, 0, sizeof d);
    cr_assert_eq(ctd_case_make(&c, family, n, num, seed, &d), CT_OK, "%s", d.msg);
    double h = c.h_mean > 0 ? c.h_mean : 1.0;
    ct_search_input in;
    ctd_case_input(&c, (ct_real)(gap >= 0 ? gap : 0.4 * h),
                   (ct_real)(margin >= 0 ? margin : 0.1 * h), &in);
    in.filter = filter;
    ct_search_params p = ct_search_default_params(CT_SEARCH_DIRECT);
    ct_search *s;
    ct_pairs pr;
    ct_pairs_init(&pr, 0);
    cr_assert_eq(ct_search_init(&s, &p), CT_OK);
    cr_assert_eq(ct_search_run(s, &in, &pr), CT_OK);
    ref_case r = {c.mesh.nodes.n, c.sec.n, c.main.n, (long)pr.n};
    ct_search_destroy(s);
    ct_pairs_destroy(&pr);
    ctd_case_destroy(&c);
    return r;
}

/* The pair count on the line of search `name` in the output (-1 when no line
 * names it); *line (when not NULL) receives that line. */
static long search_pairs(const char *out, const char *name, const char **line)
{
    char key[40];
    snprintf(key, sizeof key, "\n  %s ", name);
    const char *p = strstr(out, key);
    if (!p)
        return -1;
    long n = -1;
    double t;
    char nm[32];
    if (sscanf(p + 1, " %31s %lf ns/node %ld pairs", nm, &t, &n) != 3)
        return -1;
    if (line)
        *line = p + 1;
    return n;
}

/* The number of timed (non-reference) search lines: each shows B/node. */
static int timed_lines(const char *out)
{
    int n = 0;
    for (const char *p = out; (p = strstr(p, " B/node")) != NULL; p++)
        n++;
    return n;
}

/* `name`'s line says "identical to direct (missed 0, extra 0)". */
static int identical(const char *out, const char *name)
{
    const char *line;
    if (search_pairs(out, name, &line) < 0)
        return 0;
    const char *end = strchr(line, '\n');
    const char *id = strstr(line, "identical to direct (missed 0, extra 0)");
    return id && end && id < end;
}

/* The case line: "case FAMILY: N nodes, S secondary, M main segments". */
static void expect_case_line(const char *out, const char *family, const ref_case *rc,
                             const char *rest)
{
    char want[256];
    snprintf(want, sizeof want, "case %s: %d nodes, %d secondary, %d main segments, ", family,
             rc->nodes, rc->sec, rc->main);
    const char *p = strstr(out, want);
    cr_expect_not_null(p, "expected \"%s\" in:\n%s", want, out);
    if (p && rest) {
        const char *end = strchr(p, '\n');
        const char *q = strstr(p, rest);
        cr_expect(q && q < end, "the case line lacks \"%s\": %.*s", rest, (int)(end - p), p);
    }
}

/* Every option with its effect visible in the output: numbering, gap,
 * margin, filter, cells, renumbering and threads; the counts are those of the
 * direct search run here. */
Test(cli, search_options_against_direct)
{
    char dir[64];
    ctt_tmpdir(dir, "cli");
    ctt_cli r = {0};

    /* Defaults but the size: the soup (self contact) of seed 11, where the
     * topological search misses pairs (its documented weakness). */
    ctt_cli_run(&r, dir, 2, "search --family soup --n 1500 --seed 11 --repeat 1 --threads 1");
    cr_assert_eq(r.status, 0, "%s%s", r.out, r.err);
    ref_case soup = direct_ref("soup", 1500, CTD_NUM_NATURAL, 11, -1, -1, CT_FILTER_HULL);
    cr_assert_gt(soup.pairs, 100);
    expect_case_line(r.out, "soup", &soup, "self=1, numbering natural, h=1 gap=0.4 margin=0.1 "
                                           "filter hull");
    cr_expect(strstr(r.out, "# threads: 1\n") != NULL, "--threads 1 not applied:\n%s", r.out);
    cr_expect_eq(search_pairs(r.out, "direct", NULL), soup.pairs, "%s", r.out);
    cr_expect_eq(timed_lines(r.out), 3, "%s", r.out);
    static const char *const exact[] = {"bucket", "bsp"};
    for (int k = 0; k < 2; k++) {
        cr_expect_eq(search_pairs(r.out, exact[k], NULL), soup.pairs, "%s:\n%s", exact[k], r.out);
        cr_expect(identical(r.out, exact[k]), "%s:\n%s", exact[k], r.out);
    }
    /* The topological search: a subset, its misses counted. */
    const char *tl = "";
    long topo = search_pairs(r.out, "topological", &tl);
    char miss[64];
    snprintf(miss, sizeof miss, "(missed %ld, extra 0)", soup.pairs - topo);
    cr_expect(topo > 0 && topo <= soup.pairs && strstr(tl, miss) != NULL,
              "topological %ld pairs of %ld, expected \"%s\":\n%s", topo, soup.pairs, miss, r.out);

    /* Another seed is another soup. */
    ctt_cli_run(&r, dir, 2, "search --family soup --n 1500 --seed 12 --repeat 1 --algo bucket");
    cr_assert_eq(r.status, 0, "%s", r.err);
    ref_case soup12 = direct_ref("soup", 1500, CTD_NUM_NATURAL, 12, -1, -1, CT_FILTER_HULL);
    cr_expect_neq(soup12.pairs, soup.pairs, "seeds 11 and 12 give the same soup");
    cr_expect_eq(search_pairs(r.out, "bucket", NULL), soup12.pairs, "%s", r.out);

    /* Gap, margin, box filter, shuffled numbering, renumbering on and fresh,
     * dense on, cells x2, two repetitions, on the ball in its socket: the
     * box filter keeps more pairs than the hull there (not on flat plates,
     * where the two agree). */
    ctt_cli_run(&r, dir, 2,
                "search --family sphere --n 900 --gap 0.5 --margin 0.05 --filter box "
                "--numbering shuffled --seed 3 --renumber on --renumber-keep fresh --dense on "
                "--cells 2 --repeat 2");
    cr_assert_eq(r.status, 0, "%s", r.err);
    ref_case box = direct_ref("sphere", 900, CTD_NUM_SHUFFLED, 3, 0.5, 0.05, CT_FILTER_BOX);
    ref_case hull = direct_ref("sphere", 900, CTD_NUM_SHUFFLED, 3, 0.5, 0.05, CT_FILTER_HULL);
    cr_assert_gt(box.pairs, hull.pairs);
    expect_case_line(r.out, "sphere", &box, "self=0, numbering shuffled, ");
    expect_case_line(r.out, "sphere", &box, " gap=0.5 margin=0.05 filter box");
    static const char *const exact3[] = {"direct", "bucket", "bsp"};
    for (int k = 0; k < 3; k++)
        cr_expect_eq(search_pairs(r.out, exact3[k], NULL), box.pairs, "%s: expected %ld:\n%s",
                     exact3[k], box.pairs, r.out);
    for (int k = 1; k < 3; k++)
        cr_expect(identical(r.out, exact3[k]), "%s:\n%s", exact3[k], r.out);
    topo = search_pairs(r.out, "topological", &tl);
    snprintf(miss, sizeof miss, "(missed %ld, extra 0)", box.pairs - topo);
    cr_expect(topo > 0 && strstr(tl, miss) != NULL, "expected \"%s\":\n%s", miss, r.out);
    /* Renumbered (on), the bucket grid at twice Radioss's cells. */
    const char *bl = "";
    search_pairs(r.out, "bucket", &bl);
    cr_expect(strstr(bl, "  cells x2  renumbered  identical") != NULL, "%s", r.out);
    cr_expect(strstr(tl, "  renumbered  DIFFERS") != NULL || strstr(tl, "  renumbered  identical"),
              "%s", r.out);
    /* The same with the hull filter: the count follows the filter. */
    ctt_cli_run(&r, dir, 2,
                "search --family sphere --n 900 --gap 0.5 --margin 0.05 --filter hull "
                "--numbering shuffled --seed 3 --algo bsp --repeat 1");
    cr_assert_eq(r.status, 0, "%s", r.err);
    expect_case_line(r.out, "sphere", &hull, " gap=0.5 margin=0.05 filter hull");
    cr_expect_eq(search_pairs(r.out, "direct", NULL), hull.pairs, "%s", r.out);
    cr_expect_eq(search_pairs(r.out, "bsp", NULL), hull.pairs, "%s", r.out);

    /* Check off: no reference, one search; space-filling-curve numbering,
     * renumbering and the dense index off, a kept numbering, cells auto. */
    ctt_cli_run(&r, dir, 2,
                "search --family plates --n 900 --algo bsp --check off --numbering sfc "
                "--renumber off --dense off --renumber-keep 5 --cells auto --repeat 1");
    cr_assert_eq(r.status, 0, "%s", r.err);
    ref_case sfc = direct_ref("plates", 900, CTD_NUM_SFC, 1, -1, -1, CT_FILTER_HULL);
    expect_case_line(r.out, "plates", &sfc, "numbering sfc, h=1 gap=0.4 margin=0.1 filter hull");
    cr_expect(strstr(r.out, "\n  direct: skipped (--check off)\n") != NULL, "%s", r.out);
    cr_expect_eq(search_pairs(r.out, "direct", NULL), -1);
    cr_expect_eq(timed_lines(r.out), 1, "%s", r.out);
    cr_expect_eq(search_pairs(r.out, "bsp", NULL), sfc.pairs, "%s", r.out);
    cr_expect(strstr(r.out, "identical to direct") == NULL, "compared without a reference");

    /* Renumbering auto and dense auto (their defaults, spelled out). */
    ctt_cli_run(&r, dir, 2,
                "search --family plates-tri --n 700 --renumber auto --dense auto --repeat 1 "
                "--algo topological");
    cr_assert_eq(r.status, 0, "%s", r.err);
    ref_case tri = direct_ref("plates-tri", 700, CTD_NUM_NATURAL, 1, -1, -1, CT_FILTER_HULL);
    cr_expect_eq(search_pairs(r.out, "topological", NULL), tri.pairs, "%s", r.out);
    cr_expect(identical(r.out, "topological"), "%s", r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* Each algorithm alone (--algo) reports the direct search's pair count; the
 * direct search alone is the reference line and nothing else. */
Test(cli, search_each_algorithm_alone)
{
    char dir[64];
    ctt_tmpdir(dir, "cli");
    ctt_cli r = {0};
    ref_case ref = direct_ref("plates", 800, CTD_NUM_NATURAL, 1, -1, -1, CT_FILTER_HULL);
    cr_assert_gt(ref.pairs, 0);
    static const char *const algo[] = {"topological", "bucket", "bsp"};
    for (int k = 0; k < 3; k++) {
        ctt_cli_run(&r, dir, 2, "search --n 800 --repeat 1 --algo %s", algo[k]);
        cr_assert_eq(r.status, 0, "%s: %s", algo[k], r.err);
        expect_case_line(r.out, "plates", &ref, "numbering natural");
        cr_expect_eq(timed_lines(r.out), 1, "%s:\n%s", algo[k], r.out);
        cr_expect_eq(search_pairs(r.out, "direct", NULL), ref.pairs, "%s", r.out);
        cr_expect_eq(search_pairs(r.out, algo[k], NULL), ref.pairs, "%s:\n%s", algo[k], r.out);
        cr_expect(identical(r.out, algo[k]), "%s:\n%s", algo[k], r.out);
    }
    ctt_cli_run(&r, dir, 2, "search --n 800 --repeat 1 --algo direct");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect_eq(search_pairs(r.out, "direct", NULL), ref.pairs, "%s", r.out);
    cr_expect_eq(timed_lines(r.out), 0, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "search --n 800 --repeat 1 --algo all");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect_eq(timed_lines(r.out), 3, "%s", r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

Test(cli, search_bad_options_exit_1)
{
    char dir[64];
    ctt_tmpdir(dir, "cli");
    ctt_cli r = {0};
    static const struct {
        const char *args, *msg;
    } bad[] = {
        {"--n 0", "--n expects a node count in [1, 2e8], got '0'"},
        {"--n 300000000", "--n expects a node count in [1, 2e8], got '300000000'"},
        {"--n ten", "got 'ten'"},
        {"--algo quick", "--algo expects direct, topological, bucket, bsp or all, got 'quick'"},
        {"--numbering random", "--numbering expects natural, shuffled or sfc, got 'random'"},
        {"--gap -1", "--gap expects a finite number >= 0, got '-1'"},
        {"--margin nan", "--margin expects a finite number >= 0, got 'nan'"},
        {"--gap inf", "--gap expects a finite number >= 0, got 'inf'"},
        {"--filter sphere", "--filter expects hull or box, got 'sphere'"},
        {"--check on", "--check expects auto or off, got 'on'"},
        {"--renumber maybe", "--renumber expects auto, on or off, got 'maybe'"},
        {"--dense yes", "--dense expects auto, on or off, got 'yes'"},
        {"--cells 0", "--cells expects auto or a factor in (0, 100], got '0'"},
        {"--cells 101", "--cells expects auto or a factor in (0, 100], got '101'"},
        {"--renumber-keep 0", "--renumber-keep expects 1..1000000 or fresh, got '0'"},
        {"--renumber-keep stale", "got 'stale'"},
        {"--repeat 0", "--repeat expects 1..1000, got '0'"},
        {"--repeat 1001", "--repeat expects 1..1000, got '1001'"},
        {"--seed -3", "--seed expects an integer >= 0, got '-3'"},
        {"--threads 0", "--threads expects 1..4096, got '0'"},
        {"--threads 4097", "--threads expects 1..4096, got '4097'"},
        {"--n", "option --n needs a value"},
        {"--n 10 --gap", "option --gap needs a value"},
        {"--fast 1", "unknown option '--fast' (try --help)"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        ctt_cli_run(&r, dir, 2, "search %s", bad[k].args);
        EXPECT_FAIL(&r, 1, bad[k].msg);
        /* Refused before anything runs: not even the provenance header. */
        cr_expect_str_empty(r.out, "search %s printed: %s", bad[k].args, r.out);
    }
    /* A family that does not exist is found when the case is built. */
    ctt_cli_run(&r, dir, 2, "search --family lattice --n 100");
    EXPECT_FAIL(&r, 1, "contact search: cannot build case 'lattice'");
    ctt_cli_free(&r);
    ctt_rmtree(dir);
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
    static const struct {
        const char *args, *msg;
    } bad[] = {
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
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        ctt_cli_run(&r, dir, 2, "run fly.yaml %s", bad[k].args);
        EXPECT_FAIL(&r, 1, bad[k].msg);
        cr_expect_str_empty(r.out, "run %s printed: %s", bad[k].args, r.out);
    }
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
    EXPECT_FAIL(&r, 1, "contact check: more than one scene 'drop.yaml'");
    ctt_cli_run(&r, dir, 2, "check --strict fly.yaml");
    EXPECT_FAIL(&r, 1, "contact check: unknown option '--strict'");
    ctt_cli_run(&r, dir, 2, "check fly.yaml --out");
    EXPECT_FAIL(&r, 1, "contact check: option --out needs a value");
    cr_expect_str_empty(r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* ---- demo ---------------------------------------------------------------- */

/* The demo's first case, the folded sheet of 20000 nodes: each search
 * checked against direct, whose count is that of the bucket search run here
 * on the same case (the bucket search equals direct: suite search_bucket;
 * a direct search here would double the test's time). The demo is stopped
 * once that case is done. */
Test(cli, demo_first_case, .timeout = 300)
{
    /* Under the sanitizers (make check) the direct search of 20000 nodes
     * takes minutes, and ASan refuses stdbuf's preloaded library. */
    if (ctt_checking())
        cr_skip_test("the demo's first case is too slow under the sanitizers");
    char bin[1100];
    ctt_contact_path(bin, sizeof bin);
    int fd[2];
    cr_assert_eq(pipe(fd), 0);
    pid_t pid = fork();
    cr_assert(pid >= 0);
    if (pid == 0) {
        dup2(fd[1], STDOUT_FILENO);
        close(fd[0]);
        close(fd[1]);
        setenv("OMP_NUM_THREADS", "2", 1);
        /* Line-buffered output (stdbuf, coreutils): into a pipe the
         * program's stdout is block-buffered, and the first case's lines
         * would come only with the second case's, minutes later. */
        execlp("stdbuf", "stdbuf", "-oL", bin, "demo", (char *)NULL);
        _exit(127);
    }
    close(fd[1]);
    FILE *f = fdopen(fd[0], "r");
    cr_assert_not_null(f);
    size_t cap = 1 << 14, len = 0;
    char *out = calloc(cap, 1), line[1024];
    cr_assert_not_null(out);
    int in_case = 0, searches = 0;
    while (searches < 4 && fgets(line, sizeof line, f)) {
        size_t l = strlen(line);
        if (len + l + 1 > cap)
            break;
        memcpy(out + len, line, l + 1);
        len += l;
        in_case |= strncmp(line, "case folded:", 12) == 0;
        searches += in_case && strstr(line, " ns/node ") != NULL;
    }
    kill(pid, SIGTERM);
    int st;
    waitpid(pid, &st, 0);
    fclose(f);
    cr_assert_eq(searches, 4, "the demo's first case did not finish:\n%s", out);

    char build[2048];
    snprintf(build, sizeof build, "# build: %s\n", ct_build_info());
    cr_expect(strncmp(out, build, strlen(build)) == 0, "%s", out);
    cr_expect(strstr(out, "\n# threads: 2\n") != NULL, "%s", out);
    cr_expect(strstr(out, "every search is checked pair for pair against\nthe direct") != NULL,
              "%s", out);
    /* The case, and its pair count from the bucket search here. */
    ctd_case c;
    ct_diag d;
    memset(&d, 0, sizeof d);
    cr_assert_eq(ctd_case_make(&c, "folded", 20000, CTD_NUM_NATURAL, 1, &d), CT_OK, "%s", d.msg);
    ct_search_input in;
    ctd_case_input(&c, (ct_real)(0.4 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *s;
    ct_pairs pr;
    ct_pairs_init(&pr, 0);
    cr_assert_eq(ct_search_init(&s, &p), CT_OK);
    cr_assert_eq(ct_search_run(s, &in, &pr), CT_OK);
    ref_case ref = {c.mesh.nodes.n, c.sec.n, c.main.n, (long)pr.n};
    ct_search_destroy(s);
    ct_pairs_destroy(&pr);
    ctd_case_destroy(&c);
    expect_case_line(out, "folded", &ref, "self=1, numbering natural");
    cr_expect_eq(search_pairs(out, "direct", NULL), ref.pairs, "%s", out);
    cr_expect(identical(out, "bucket") && identical(out, "bsp"), "%s", out);
    const char *tl = "";
    long topo = search_pairs(out, "topological", &tl);
    char miss[64];
    snprintf(miss, sizeof miss, "(missed %ld, extra 0)", ref.pairs - topo);
    cr_expect(topo > 0 && strstr(tl, miss) != NULL, "%s", out);
    free(out);
}
