/*
 * test_cli_search.c -- the `contact` program's command line (driver/main.c,
 * driver/run.c) run as a program, suite "cli": here `contact search` and `contact demo`
 * (the other commands in tests/test_cli*.c). Each run small, its exit
 * code and output checked against expectations found independently of the program:
 *
 *  - search: with each algorithm and every option, the pair count printed
 *    is that of a direct search run here on the same case (ctd_case_make
 *    with the same family, size, numbering and seed; gap, margin and filter
 *    as given), and the case line names the nodes, numbering, gap, margin
 *    and filter asked for.
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
    /* Its line says the misses are the method's (and no exact search's
     * line says so). */
    cr_expect(topo < soup.pairs && strstr(tl, "[allowed: the topological search looks only near "
                                              "each node's last closest main node]") != NULL,
              "%s", r.out);
    const char *allowed = strstr(r.out, "[allowed"), *eol = strchr(tl, '\n');
    cr_expect(allowed && allowed > tl && (!eol || allowed < eol) &&
                  strstr(allowed + 1, "[allowed") == NULL,
              "%s", r.out);

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
 * direct search alone is the reference line and nothing else, or its timed
 * line with --check off. */
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
    /* Asked for alone without a reference, the direct search is timed: its
     * line is a timed one, with the pair count of the direct search run
     * here (it printed nothing at all before). */
    ctt_cli_run(&r, dir, 2, "search --n 800 --repeat 1 --algo direct --check off");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect_eq(timed_lines(r.out), 1, "%s", r.out);
    cr_expect_eq(search_pairs(r.out, "direct", NULL), ref.pairs, "%s", r.out);
    cr_expect(strstr(r.out, "skipped") == NULL, "%s", r.out);
    ctt_cli_run(&r, dir, 2, "search --n 800 --repeat 1 --algo all");
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_expect_eq(timed_lines(r.out), 3, "%s", r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}

/* A case too large for the memory the process may have exits 5 (out of
 * memory, as `contact run` does), not 1 (bad usage: the options are
 * valid). The limit is set by the shell (ulimit -v), which the sanitizers'
 * shadow memory cannot run under. */
Test(cli, search_out_of_memory_exit_5)
{
    if (ctt_checking())
        cr_skip_test("the sanitizers' shadow memory does not fit under ulimit -v");
    char dir[64];
    ctt_tmpdir(dir, "cli");
    ctt_cli r = {0};
    ctt_cli_run_prefix(&r, dir, "ulimit -v 400000 &&", 1,
                       "search --n 20000000 --algo bucket --check off --repeat 1");
    cr_expect_eq(r.status, 5, "%s", r.err);
    cr_expect(strstr(r.err, "out of memory") != NULL, "%s", r.err);
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
