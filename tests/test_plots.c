/*
 * test_plots.c -- the plot script of the benchmarks (bench/plots.py): it is
 * run on the fixed file tests/data/bench_sample.json and on a small file
 * written here (floor and trade records), into a temporary folder. The
 * tests check that the PNG files exist, are PNG images of the size the
 * script sets (1200 x 750) and are not trivial, that plots without records
 * are skipped (not failed), and that the numbers plotted are the ones
 * worked out by hand from the JSON (the script keeps its gnuplot data files
 * with --data). Skipped when gnuplot or python3 is absent.
 *
 * The tests run from the repository's top directory (where `make test`
 * runs them).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test_run.h"
#include "test_util.h"

#define PLOTS "bench/plots.py"
#define SAMPLE "tests/data/bench_sample.json"

typedef struct plot_dir {
    char root[64];  /* the temporary folder */
    char out[96];   /* root/out: the PNG files */
    char data[96];  /* root/data: the gnuplot scripts and data files */
} plot_dir;

static void need_tools(void)
{
    if (system("command -v gnuplot >/dev/null 2>&1") != 0)
        cr_skip_test("gnuplot is not installed (Debian gnuplot-nox: make deps)");
    if (system("command -v python3 >/dev/null 2>&1") != 0)
        cr_skip_test("python3 is not installed");
    cr_assert(access(PLOTS, R_OK) == 0,
              "%s not found: run the tests from the repository's top directory", PLOTS);
}

static void dir_make(plot_dir *d)
{
    snprintf(d->root, sizeof d->root, "/tmp/ct-test-plots-XXXXXX");
    cr_assert(mkdtemp(d->root) != NULL, "mkdtemp failed");
    snprintf(d->out, sizeof d->out, "%s/out", d->root);
    snprintf(d->data, sizeof d->data, "%s/data", d->root);
}

static void dir_remove(const plot_dir *d)
{
    char cmd[160];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", d->root);
    cr_expect(system(cmd) == 0, "could not remove %s", d->root);
}

/* Run `python3 bench/plots.py <files> --out D/out --data D/data`; returns
 * its output, stdout and stderr together (free it), and its exit status. */
static char *run_plots(const plot_dir *d, const char *files, int *status)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "python3 %s %s --out '%s' --data '%s' 2>&1", PLOTS, files, d->out,
             d->data);
    return ctt_run_cmd(cmd, status);
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    cr_assert(f != NULL, "cannot open %s", path);
    char *buf = calloc(1 << 16, 1);
    cr_assert(buf != NULL);
    size_t n = fread(buf, 1, (1 << 16) - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static int exists(const char *folder, const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    return access(path, F_OK) == 0;
}

static unsigned be32(const unsigned char *p)
{
    return (unsigned)p[0] << 24 | (unsigned)p[1] << 16 | (unsigned)p[2] << 8 | (unsigned)p[3];
}

/* The file is a PNG: the 8-byte signature, then the IHDR chunk with the
 * script's size (1200 x 750), and at least min_bytes long (an empty plot
 * area with axes alone is already several kilobytes; a plot with curves,
 * key and labels more). */
static void expect_png(const char *folder, const char *name, long min_bytes)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    struct stat sb;
    cr_assert(stat(path, &sb) == 0, "%s was not written", path);
    cr_expect(sb.st_size >= min_bytes, "%s: %ld bytes, expected at least %ld", path,
              (long)sb.st_size, min_bytes);
    FILE *f = fopen(path, "rb");
    cr_assert(f != NULL);
    unsigned char h[24];
    size_t n = fread(h, 1, sizeof h, f);
    fclose(f);
    cr_assert_eq(n, sizeof h, "%s: shorter than a PNG header", path);
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    cr_expect(memcmp(h, sig, 8) == 0, "%s: no PNG signature", path);
    cr_expect(memcmp(h + 12, "IHDR", 4) == 0, "%s: the first chunk is not IHDR", path);
    cr_expect_eq(be32(h + 16), 1200u, "%s: width %u", path, be32(h + 16));
    cr_expect_eq(be32(h + 20), 750u, "%s: height %u", path, be32(h + 20));
}

static void expect_file(const plot_dir *d, const char *name, const char *want)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", d->data, name);
    char *got = read_text(path);
    cr_expect_str_eq(got, want, "%s:\n%s\nexpected:\n%s", path, got, want);
    free(got);
}

Test(plots, sample_pngs)
{
    need_tools();
    plot_dir d;
    dir_make(&d);
    int status = -1;
    char *out = run_plots(&d, SAMPLE, &status);
    cr_expect_eq(status, 0, "plots.py failed:\n%s", out);
    expect_png(d.out, "search_cost.png", 10000);
    expect_png(d.out, "speedup.png", 10000);
    /* The sample has no real-mesh, floor or trade records: those plots are
     * skipped with a message, not failed. */
    cr_expect(!exists(d.out, "real_meshes.png") && !exists(d.out, "trade.png"),
              "a plot without records was written");
    cr_expect(strstr(out, "trade.png skipped") != NULL, "no skip message:\n%s", out);
    cr_expect(strstr(out, "the floor line is omitted") != NULL, "no floor message:\n%s", out);
    free(out);
    dir_remove(&d);
}

Test(plots, sample_numbers)
{
    need_tools();
    plot_dir d;
    dir_make(&d);
    int status = -1;
    char *out = run_plots(&d, SAMPLE, &status);
    cr_expect_eq(status, 0, "plots.py failed:\n%s", out);
    free(out);
    /* Time per search in seconds against nsec, from the median aggregates:
     * bucket, 1 thread: 278054.09999928094 ns at nsec 1024 and
     * 2471139.166674321 ns at nsec 10000. */
    expect_file(&d, "cost_bucket_t1.dat", "1024 0.000278054\n10000 0.00247114\n");
    /* Direct over budget at 10000 nodes (nsec = nseg = 10000), extrapolated
     * from the 1-thread run at nsec = nseg = 1024 (6597055.28570547 ns):
     * 6597055.28570547e-9 * 1e8 / 1024^2 = 0.629144 s. */
    expect_file(&d, "cost_direct_t1_extrap.dat", "1024 0.00659706\n10000 0.629144\n");
    /* Speed-up of bucket at the largest N with 1 and 2 threads (10000):
     * 2471139.166674321 / 6490199.4999900125 = 0.380749. */
    expect_file(&d, "speedup_bucket.dat", "1 1\n2 0.380749\n");
    dir_remove(&d);
}

/* A small run: bucket on plates at two sizes, the floor at one, and three
 * trade records of two knobs: "search" with generic counter names, "quad"
 * with bench_trade.c's label and counters (cost, accuracy), one error 0. */
static const char *const FIXTURE =
    "{\"context\": {\"ct_build\": \"precision=double\"}, \"benchmarks\": [\n"
    "{\"name\": \"search/plates/bucket/natural/t1/1000/real_time\", \"run_name\": "
    "\"search/plates/bucket/natural/t1/1000/real_time\", \"run_type\": \"iteration\", "
    "\"real_time\": 100000, \"time_unit\": \"ns\", \"nsec\": 1000, \"ns_per_node\": 100},\n"
    "{\"name\": \"search/plates/bucket/natural/t1/100000/real_time\", \"run_name\": "
    "\"search/plates/bucket/natural/t1/100000/real_time\", \"run_type\": \"iteration\", "
    "\"real_time\": 5, \"time_unit\": \"ms\", \"nsec\": 100000, \"ns_per_node\": 50},\n"
    "{\"name\": \"floor/bucket/plates/t1/100000/real_time\", \"run_name\": "
    "\"floor/bucket/plates/t1/100000/real_time\", \"run_type\": \"iteration\", "
    "\"real_time\": 5, \"time_unit\": \"ms\", \"floor_bytes_per_node\": 92, \"GBps_dram\": 10,"
    " \"GBps_ws\": 40, \"floor_ns_dram\": 9.2, \"floor_ns_ws\": 2.3},\n"
    "{\"name\": \"trade/search/bucket\", \"run_name\": \"trade/search/bucket\", \"run_type\": "
    "\"iteration\", \"real_time\": 1, \"time_unit\": \"ms\", \"label\": \"knob=search "
    "setting=bucket\", \"ns_per_node\": 50, \"misses\": 0},\n"
    "{\"name\": \"trade/search/topological\", \"run_name\": \"trade/search/topological\", "
    "\"run_type\": \"iteration\", \"real_time\": 1, \"time_unit\": \"ms\", \"label\": "
    "\"knob=search setting=topological\", \"ns_per_node\": 20, \"misses\": 12},\n"
    "{\"name\": \"trade/quad/newton\", \"run_name\": \"trade/quad/newton\", \"run_type\": "
    "\"iteration\", \"real_time\": 1, \"time_unit\": \"ms\", \"label\": \"knob=quad "
    "setting=newton; cost: ns per pair; accuracy: max |D - D_newton| / h; prec=double\", "
    "\"cost\": 30, \"accuracy\": 0, \"x_mean_err\": 5},\n"
    "{\"name\": \"trade/quad/4tri\", \"run_name\": \"trade/quad/4tri\", \"run_type\": "
    "\"iteration\", \"real_time\": 1, \"time_unit\": \"ms\", \"label\": \"knob=quad "
    "setting=4tri; cost: ns per pair; accuracy: max |D - D_newton| / h; prec=double\", "
    "\"cost\": 10, \"accuracy\": 0.01, \"x_mean_err\": 5},\n"
    "{\"name\": \"trade/quad/closed\", \"run_name\": \"trade/quad/closed\", \"run_type\": "
    "\"iteration\", \"real_time\": 1, \"time_unit\": \"ms\", \"label\": \"knob=quad "
    "setting=closed; cost: ns per pair; accuracy: max |D - D_newton| / h; prec=double\", "
    "\"cost\": 20, \"accuracy\": 1e-6, \"x_mean_err\": 5}\n"
    "]}\n";

Test(plots, floor_and_trade)
{
    need_tools();
    plot_dir d;
    dir_make(&d);
    char path[128];
    snprintf(path, sizeof path, "%s/fixture.json", d.root);
    FILE *f = fopen(path, "w");
    cr_assert(f != NULL);
    fputs(FIXTURE, f);
    fclose(f);
    int status = -1;
    char *out = run_plots(&d, path, &status);
    cr_expect_eq(status, 0, "plots.py failed:\n%s", out);
    free(out);
    expect_png(d.out, "search_cost.png", 10000);
    expect_png(d.out, "trade.png", 10000);
    /* One thread only: no speed-up plot. */
    cr_expect(!exists(d.out, "speedup.png"), "a speed-up plot from one thread count");
    /* The floor line: 92 bytes per node at 10 GB/s is 9.2 ns per node, so
     * 9.2e-9 s times N; at the working-set bandwidth 40 GB/s, 2.3e-9 N. */
    snprintf(path, sizeof path, "%s/search_cost.gp", d.data);
    char *gp = read_text(path);
    cr_expect(strstr(gp, "9.2e-09*x") != NULL, "no DRAM floor line 9.2e-09*x in:\n%s", gp);
    cr_expect(strstr(gp, "2.3e-09*x") != NULL, "no working-set floor line 2.3e-09*x in:\n%s",
              gp);
    free(gp);
    /* The trade points (cost, error, setting), one panel per knob. Knob
     * "search" (no cost/accuracy counters): ns_per_node and misses, on a
     * linear error axis (0 and 12). Knob "quad" (bench_trade.c's counters
     * cost and accuracy; x_mean_err is not the accuracy): errors 1e-2 and
     * 1e-6 span more than 100x, so a log axis, the 0 of newton drawn at a
     * tenth of the smallest positive error, 1e-7. */
    expect_file(&d, "trade_0.dat", "50 0 bucket\n20 12 topological\n");
    expect_file(&d, "trade_1.dat", "30 1e-07 newton\n10 0.01 4tri\n20 1e-06 closed\n");
    snprintf(path, sizeof path, "%s/trade.gp", d.data);
    gp = read_text(path);
    cr_expect(strstr(gp, "accuracy: max |D - D_newton| / h") != NULL,
              "the label's accuracy description is not the axis label:\n%s", gp);
    free(gp);
    dir_remove(&d);
}

Test(plots, unreadable_file)
{
    need_tools();
    plot_dir d;
    dir_make(&d);
    int status = -1;
    char *out = run_plots(&d, "tests/data/no_such_file.json", &status);
    cr_expect_eq(status, 1, "exit status %d for a missing file:\n%s", status, out);
    cr_expect(strstr(out, "cannot read") != NULL, "no error message:\n%s", out);
    cr_expect(!exists(d.out, "search_cost.png"), "a plot from a missing file");
    free(out);
    dir_remove(&d);
}

/* The validation script (tests/validation_plots.py, `make validation`): one
 * case's curve and figure, written as tests/test_validation.h writes them,
 * give a PNG of the script's size (800 x 520) and the results table between
 * the markers of the page. (Its gnuplot commands must all be valid: a bad
 * one fails every plot.) */
Test(plots, validation_script_draws_and_tabulates)
{
    need_tools();
    plot_dir d;
    dir_make(&d);
    char path[256], cmd[768];
    cr_assert(mkdir(d.data, 0700) == 0);
    snprintf(path, sizeof path, "%s/case.csv", d.data);
    FILE *f = fopen(path, "w");
    cr_assert(f != NULL);
    fputs("t,F_sim,F_ref\n0,0,0\n1,1.5,1.4\n2,0.5,nan\n", f);
    fclose(f);
    snprintf(path, sizeof path, "%s/case.plot", d.data);
    f = fopen(path, "w");
    cr_assert(f != NULL);
    fputs("title\tA case\nxlabel\tt\nylabel\tF\nseries\t1,2,points,simulated;1,3,lines,"
          "analytic\noptions\t\n",
          f);
    fclose(f);
    snprintf(path, sizeof path, "%s/results.tsv", d.data);
    f = fopen(path, "w");
    cr_assert(f != NULL);
    fputs("case_a\tpeak force (N)\t1.5\t1.4\t0.0714\t0.1\tpass\ta note\n", f);
    fclose(f);
    snprintf(path, sizeof path, "%s/page.md", d.root);
    f = fopen(path, "w");
    cr_assert(f != NULL);
    fputs("# Page\n<!-- results:begin -->\nold\n<!-- results:end -->\ntail\n", f);
    fclose(f);
    snprintf(cmd, sizeof cmd, "python3 tests/validation_plots.py '%s' --out '%s' --page '%s' 2>&1",
             d.data, d.out, path);
    int status = -1;
    char *out = ctt_run_cmd(cmd, &status);
    cr_expect_eq(status, 0, "validation_plots.py failed:\n%s", out);
    free(out);
    char png[256];
    snprintf(png, sizeof png, "%s/case.png", d.out);
    FILE *p = fopen(png, "rb");
    cr_assert(p != NULL, "%s was not written", png);
    unsigned char h[24];
    size_t n = fread(h, 1, sizeof h, p);
    fclose(p);
    cr_assert_eq(n, sizeof h, "%s: shorter than a PNG header", png);
    cr_expect(memcmp(h + 1, "PNG", 3) == 0 && memcmp(h + 12, "IHDR", 4) == 0, "not a PNG");
    cr_expect(be32(h + 16) == 800u && be32(h + 20) == 520u, "size %u x %u", be32(h + 16),
              be32(h + 20));
    char *page = read_text(path);
    const char *row = "| case_a | peak force (N) | 1.5 | 1.4 | 0.0714 | 0.1 | pass | a note |";
    cr_expect(strstr(page, row) != NULL && strstr(page, "old") == NULL &&
                  strstr(page, "tail") != NULL,
              "page:\n%s", page);
    free(page);
    dir_remove(&d);
}
