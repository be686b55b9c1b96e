/*
 * test_trade.c -- the scripts of the speed/accuracy trade (issue 5 item 7):
 * bench/trade_precision.py on two small hand-written narrow-phase dumps, and
 * the "Speed/accuracy trade" table of bench/report.py on small hand-written
 * benchmark files. Every expected number is worked out by hand next to its
 * check. The benchmarks themselves (bench/bench_trade.c) are not linked into
 * the test binary.
 *
 * The tests run the scripts with python3 from the repository's top
 * directory (where `make test` runs them); the inputs are written to a
 * fresh directory under /tmp.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.h"

/* A fresh temporary directory (removed by cleanup_dir). */
static void make_dir(char *dir, size_t len)
{
    snprintf(dir, len, "/tmp/ct_test_trade_XXXXXX");
    cr_assert(mkdtemp(dir) != NULL, "mkdtemp failed");
}

static void cleanup_dir(const char *dir)
{
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect(system(cmd) == 0);
}

static void write_file(const char *dir, const char *name, const char *text)
{
    char path[300];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    cr_assert(f != NULL, "cannot write %s", path);
    fputs(text, f);
    cr_assert(fclose(f) == 0);
}

/* Run a shell command; returns its output (free it), status in *status. */
static char *run(const char *cmd, int *status)
{
    FILE *p = popen(cmd, "r");
    cr_assert(p != NULL, "popen(%s) failed", cmd);
    size_t cap = 1 << 16, len = 0, got;
    char *buf = malloc(cap);
    cr_assert(buf != NULL);
    while ((got = fread(buf + len, 1, cap - 1 - len, p)) > 0) {
        len += got;
        if (len + 1 == cap) {
            cap *= 2;
            buf = realloc(buf, cap);
            cr_assert(buf != NULL);
        }
    }
    buf[len] = '\0';
    int st = pclose(p);
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return buf;
}

static void expect_line(const char *out, const char *line)
{
    cr_expect(strstr(out, line) != NULL, "missing line:\n%s\nin the output:\n%s", line, out);
}

static void need_scripts(void)
{
    cr_assert(access("bench/report.py", R_OK) == 0 &&
                  access("bench/trade_precision.py", R_OK) == 0,
              "bench/*.py not found: run the tests from the repository's top directory");
}

/* ---- trade_precision.py --------------------------------------------------- */

/* Double: h = 1, gap = 0.5. Pairs (node seg flag dist pen nx ny nz):
 * (0,1) active, (2,3) active, (4,5) inactive, (6,7) degenerate (skipped),
 * (8,9) only here. */
static const char dump_double[] =
    "# contact --dump-narrow: precision=double case=test h=1 gap=0.5\n"
    "# node seg flag dist pen nx ny nz\n"
    "0 1 0 0.3 0.2 0 0 1\n"
    "2 3 0 0.45 0.05 1 0 0\n"
    "4 5 0 0.6 0 0 1 0\n"
    "6 7 1 1e30 0 0 0 1\n"
    "8 9 0 0.4 0.1 0 0 1\n";
/* Single: (0,1) pen 0.198 (|dp| = 0.002, relative 0.01, /gap 0.004), normal
 * (0, 0.006, 0.999982) (|dn| = sqrt(0.006^2 + 0.000018^2) = 0.0060000),
 * dist 0.302; (2,3) pen 0.0501 (relative 0.002); (4,5) now active with pen
 * 0.001 (below the 1% floor of the relative figure: not counted there; one
 * active mismatch), dist 0.499 (|dD| / h = 0.101, the largest); (6,7)
 * degenerate with garbage values that must be ignored; (10,11) only here. */
static const char dump_single[] =
    "# contact --dump-narrow: precision=single case=test h=1 gap=0.5\n"
    "# node seg flag dist pen nx ny nz\n"
    "0 1 0 0.302 0.198 0 0.006 0.999982\n"
    "2 3 0 0.45 0.0501 1 0 0\n"
    "4 5 0 0.499 0.001 0 1 0\n"
    "6 7 1 5 3 1 1 1\n"
    "10 11 0 0.4 0.1 0 0 1\n";

Test(trade, precision_compare_by_hand)
{
    need_scripts();
    char dir[64], cmd[512];
    make_dir(dir, sizeof dir);
    write_file(dir, "d.txt", dump_double);
    write_file(dir, "s.txt", dump_single);
    snprintf(cmd, sizeof cmd,
             "python3 bench/trade_precision.py %s/d.txt %s/s.txt --json %s/tp.json 2>&1", dir,
             dir, dir);
    int status = -1;
    char *out = run(cmd, &status);
    cr_assert_eq(status, 0, "trade_precision.py failed:\n%s", out);
    expect_line(out, "narrow phase, single against double:");
    /* 3 matched pairs (the degenerate one left out), one only on each side,
     * (4,5) active in single only. */
    expect_line(out, "pairs: 3 common, 1 only in double, 1 only in single, "
                     "1 active in one only");
    expect_line(out, "max relative penetration difference (p >= 0.01 gap): 0.01\n");
    expect_line(out, "max penetration difference / gap: 0.004\n");
    expect_line(out, "max normal difference |n_s - n_d|: 0.006\n");
    expect_line(out, "max distance difference / h: 0.101\n");
    free(out);

    /* The JSON holds the same figures under "trade_precision". */
    snprintf(cmd, sizeof cmd,
             "python3 -c \"import json; d = json.load(open('%s/tp.json'))['trade_precision']; "
             "print('%%d %%d %%d %%.6f %%.6f %%.7f' %% (d['pairs_common'], d['only_reference'], "
             "d['active_mismatch'], d['max_rel_pen'], d['max_pen_err_gap'], "
             "d['max_normal_diff']))\" 2>&1",
             dir);
    out = run(cmd, &status);
    cr_assert_eq(status, 0, "%s", out);
    expect_line(out, "3 1 1 0.010000 0.004000 0.0060000");
    free(out);
    cleanup_dir(dir);
}

Test(trade, precision_bad_input_fails)
{
    need_scripts();
    char dir[64], cmd[512];
    make_dir(dir, sizeof dir);
    write_file(dir, "d.txt", dump_double);
    write_file(dir, "bad.txt", "# h=1 gap=0.5\n0 1 0 0.3\n"); /* too few fields */
    snprintf(cmd, sizeof cmd, "python3 bench/trade_precision.py %s/d.txt %s/bad.txt 2>&1", dir,
             dir);
    int status = 0;
    char *out = run(cmd, &status);
    cr_expect_neq(status, 0, "a malformed dump was accepted:\n%s", out);
    cr_expect(strstr(out, "cannot read") != NULL, "no error message:\n%s", out);
    free(out);
    cleanup_dir(dir);
}

/* ---- report.py's trade table ------------------------------------------------ */

/* A double-precision file: the median row must be used, not the mean; a
 * precision row; a failed run; a search row listed after the precision
 * row (the table orders by knob: search first). */
static const char bench_double[] =
    "{\"context\": {\"ct_precision\": \"double\"}, \"benchmarks\": [\n"
    "{\"name\": \"trade/precision/double/real_time_mean\", \"run_name\": "
    "\"trade/precision/double/real_time\", \"run_type\": \"aggregate\", \"aggregate_name\": "
    "\"mean\", \"real_time\": 5, \"time_unit\": \"ms\", \"cost\": 1500, \"label\": "
    "\"knob=precision setting=double; cost: ns/pair; accuracy: max relative difference; "
    "prec=double dump case\"},\n"
    "{\"name\": \"trade/precision/double/real_time_median\", \"run_name\": "
    "\"trade/precision/double/real_time\", \"run_type\": \"aggregate\", \"aggregate_name\": "
    "\"median\", \"real_time\": 4, \"time_unit\": \"ms\", \"cost\": 1000, \"x_pairs\": 200, "
    "\"label\": \"knob=precision setting=double; cost: ns/pair; accuracy: max relative "
    "difference; prec=double dump case\"},\n"
    "{\"name\": \"trade/quad/closed@warped/real_time\", \"run_name\": "
    "\"trade/quad/closed@warped/real_time\", \"run_type\": \"iteration\", \"error_occurred\": "
    "true, \"error_message\": \"warped quads: out of memory\"},\n"
    "{\"name\": \"trade/search/topological/real_time_mean\", \"run_name\": "
    "\"trade/search/topological/real_time\", \"run_type\": \"aggregate\", \"aggregate_name\": "
    "\"mean\", \"real_time\": 9, \"time_unit\": \"ms\", \"cost\": 999, \"accuracy\": 7, "
    "\"label\": \"knob=search setting=topological; cost: ns/node per search; accuracy: pairs "
    "missed vs direct; prec=double moving sheet\"},\n"
    "{\"name\": \"trade/search/topological/real_time_median\", \"run_name\": "
    "\"trade/search/topological/real_time\", \"run_type\": \"aggregate\", \"aggregate_name\": "
    "\"median\", \"real_time\": 6, \"time_unit\": \"ms\", \"cost\": 579.5, \"accuracy\": 12, "
    "\"x_pairs_per_node\": 0.5, \"label\": \"knob=search setting=topological; cost: ns/node "
    "per search; accuracy: pairs missed vs direct; prec=double moving sheet\"}\n"
    "]}\n";
/* A single-precision file with its precision row, three repetitions and no
 * aggregate: the median of 700, 800, 900 is 800. */
static const char bench_single[] =
    "{\"context\": {\"ct_precision\": \"single\"}, \"benchmarks\": [\n"
    "{\"name\": \"trade/precision/single/real_time\", \"run_name\": "
    "\"trade/precision/single/real_time\", \"run_type\": \"iteration\", \"real_time\": 3, "
    "\"time_unit\": \"ms\", \"cost\": 900, \"label\": \"knob=precision setting=single; cost: "
    "ns/pair; accuracy: max relative difference; prec=single dump case\"},\n"
    "{\"name\": \"trade/precision/single/real_time\", \"run_name\": "
    "\"trade/precision/single/real_time\", \"run_type\": \"iteration\", \"real_time\": 3, "
    "\"time_unit\": \"ms\", \"cost\": 700, \"label\": \"knob=precision setting=single; cost: "
    "ns/pair; accuracy: max relative difference; prec=single dump case\"},\n"
    "{\"name\": \"trade/precision/single/real_time\", \"run_name\": "
    "\"trade/precision/single/real_time\", \"run_type\": \"iteration\", \"real_time\": 3, "
    "\"time_unit\": \"ms\", \"cost\": 800, \"label\": \"knob=precision setting=single; cost: "
    "ns/pair; accuracy: max relative difference; prec=single dump case\"}\n"
    "]}\n";
static const char compare_json[] =
    "{\"trade_precision\": {\"reference\": \"double\", \"other\": \"single\", "
    "\"max_rel_pen\": 0.00145, \"max_pen_err_gap\": 3.7e-05, \"max_normal_diff\": 0.000283, "
    "\"max_dist_err_h\": 1.1e-05, \"active_mismatch\": 2, \"only_reference\": 3, "
    "\"only_other\": 4}}\n";

Test(trade, report_table_by_hand)
{
    need_scripts();
    char dir[64], cmd[512];
    make_dir(dir, sizeof dir);
    write_file(dir, "d.json", bench_double);
    write_file(dir, "s.json", bench_single);
    write_file(dir, "c.json", compare_json);
    snprintf(cmd, sizeof cmd, "python3 bench/report.py %s/d.json %s/s.json %s/c.json 2>&1", dir,
             dir, dir);
    int status = -1;
    char *out = run(cmd, &status);
    cr_assert_eq(status, 0, "report.py failed:\n%s", out);
    expect_line(out, "## Speed/accuracy trade");
    /* Median row (cost 579.5, accuracy 12), not the mean (999, 7). */
    const char *search = "| search | topological | double | 579.5 | ns/node per search | 12 | "
                         "pairs missed vs direct | pairs_per_node=0.5 |";
    expect_line(out, search);
    cr_expect(strstr(out, "| 999 |") == NULL, "the mean was used:\n%s", out);
    /* The double precision row is the reference. */
    const char *pd = "| precision | double | double | 1000 | ns/pair | 0 (reference) | max "
                     "relative difference | pairs=200 |";
    expect_line(out, pd);
    /* Single: median cost 800; accuracy from the comparison file; cost
     * ratio 800 / 1000 = 0.80. */
    expect_line(out, "| precision | single | single | 800 | ns/pair | 0.00145 | max relative "
                     "difference | max_dpen_over_gap=3.70e-05, max_dnormal=2.83e-04, "
                     "max_ddist_over_h=1.10e-05, active_mismatch=2, unmatched=3+4, "
                     "cost_vs_double=0.80 |");
    /* A failed run shows its message. */
    expect_line(out, "| quad | closed@warped | double | - | - | - | - | "
                     "warped quads: out of memory |");
    /* Knob order: search, then quad, then precision. */
    const char *a = strstr(out, search), *b = strstr(out, "| quad | closed@warped"),
               *c = strstr(out, pd);
    cr_expect(a && b && c && a < b && b < c, "rows out of knob order:\n%s", out);
    /* The cases under the table. */
    expect_line(out, "- search: moving sheet");
    expect_line(out, "- precision: dump case");
    cr_expect(strstr(out, "## Other benchmarks") == NULL, "trade rows listed as other:\n%s",
              out);
    free(out);

    /* Without the comparison: the single row says how to get it. */
    snprintf(cmd, sizeof cmd, "python3 bench/report.py %s/d.json %s/s.json 2>&1", dir, dir);
    out = run(cmd, &status);
    cr_assert_eq(status, 0, "report.py failed:\n%s", out);
    expect_line(out, "| precision | single | single | 800 | ns/pair | - (run "
                     "bench/trade_precision.py) |");
    free(out);

    /* Only a comparison file: no benchmark to report. */
    snprintf(cmd, sizeof cmd, "python3 bench/report.py %s/c.json 2>&1", dir);
    out = run(cmd, &status);
    cr_expect_neq(status, 0, "report.py accepted no benchmark file:\n%s", out);
    free(out);
    cleanup_dir(dir);
}
