/*
 * test_bench_report.c -- the JSON-to-Markdown script of the benchmarks
 * (bench/report.py) on a fixed file, tests/data/bench_sample.json: a real
 * `make bench` output (plates, 1000 and 10000 target nodes, 1 and 2
 * threads, 3 repetitions), trimmed (its 2-thread bucket row at 1000 given
 * the cell_factor and renumbered counters by hand), and two full contact
 * cycle medians
 * (cycle/folded/t1/100000 from a real run, its t2 row made up), and three
 * paired medians and two efficiency medians of a real run (bench_paired.c,
 * bench_eff.c), and two shell element medians of a real run
 * (bench_elements.c), and three cv aggregates added by hand (the bucket
 * 1000 row, the 1-thread cycle and shell rows); with
 * tests/data/interleaved_sample.json, a real bench/interleave.py output. The
 * expected numbers are worked out by hand from the JSON values and written
 * next to each check.
 *
 * The tests run the script with python3 from the repository's top
 * directory (where `make test` runs them).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test_cli.h"
#include "test_run.h"
#include "test_util.h"

#define REPORT "bench/report.py"
#define SAMPLE "tests/data/bench_sample.json"
#define INTER "tests/data/interleaved_sample.json"

/* Run `python3 bench/report.py <arg>`; returns its output (free it) and
 * its exit status in *status. */
static char *run_report(const char *arg, int *status)
{
    cr_assert(access(REPORT, R_OK) == 0,
              "%s not found: run the tests from the repository's top directory", REPORT);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "python3 %s %s 2>&1", REPORT, arg);
    return ctt_run_cmd(cmd, status);
}

/* The report of the sample file plus `more` (other files, or ""), which
 * must succeed. */
static char *sample_report(const char *more)
{
    cr_assert(access(SAMPLE, R_OK) == 0, "%s not found", SAMPLE);
    char arg[256];
    snprintf(arg, sizeof arg, "%s %s", SAMPLE, more);
    int status = -1;
    char *out = run_report(arg, &status);
    cr_assert_eq(status, 0, "report.py failed:\n%s", out);
    return out;
}

static void expect_line(const char *out, const char *line)
{
    cr_expect(strstr(out, line) != NULL, "missing line:\n%s\nin the report:\n%s", line, out);
}

Test(bench_report, tables_from_sample)
{
    cr_assert(access(SAMPLE, R_OK) == 0, "%s not found", SAMPLE);
    int status = -1;
    char *out = run_report(SAMPLE, &status);
    cr_assert_eq(status, 0, "report.py failed:\n%s", out);

    /* Provenance: the context keys the benchmark program stores. */
    expect_line(out, "- build: compiler=gcc 12.2.0");
    expect_line(out, "- topology: packages=1 numa=1 cores=2 pus=2");
    expect_line(out, "- binding: spread (2 threads: t0:PU0 t1:PU1)");

    /* Per family, one row per size / numbering / threads / algorithm. By
     * hand from the sample: direct, 1 thread, 1000: median real_time
     * 6597055.29 ns / nsec 1024 = 6442.4 ns/node (the mean row, 11102694.6
     * ns = 10842.5 ns/node, must not be used); bucket 278054.10 / 1024 =
     * 271.54 ns/node; ratio 6442.44 / 271.54 = 23.73; bytes/node 36.3125
     * and 230.65625. */
    expect_line(out, "| 1000 | natural | 1 | direct | 6.6 ms | 6442 | 23.73 | 3008 | 36.3 | - |  |");
    expect_line(out, "| 1000 | natural | 1 | bucket | 278 µs | 271.5 | 1.00 | 3008 | 230.7 | - |  |");
    cr_expect(strstr(out, "10842") == NULL, "the mean was used instead of the median:\n%s", out);
    /* 2 threads: 14855035.86 / 1024 = 14506.9; 647743.21 / 1024 = 632.56;
     * ratio 22.93; bytes/node 44.355 and 239.30. The bucket row's
     * cell_factor (0.7) and renumbered (1) counters, added to the sample by
     * hand, make its note. */
    expect_line(out, "| 1000 | natural | 2 | direct | 14.9 ms | 14507 | 22.93 | 3008 | 44.4 | - |  |");
    expect_line(out, "| 1000 | natural | 2 | bucket | 648 µs | 632.6 | 1.00 | 3008 | 239.3 | - | "
                     "cells ×0.7 renumbered |");
    /* A failed search is shown with its message. */
    expect_line(out, "| 1000 | natural | 1 | topological | - | - | - | - | - | - | "
                     "search topological: invalid argument |");
    /* Direct skipped at 10000 (nsec = nseg = 10000), extrapolated from the
     * 1000 run: 6597055.29 ns / (1024 * 1024) * 10^8 = 629.1 ms, i.e.
     * 62914 ns/node. */
    expect_line(out, "| 10000 | natural | 1 | direct | 629 ms (extrap.) | 62914 (extrap.) | - "
                     "| - | - | - | skipped: over budget");
    /* Bucket at 10000: 2471139.17 / 10^4 = 247.11 ns/node, 29800 pairs. */
    expect_line(out, "| 10000 | natural | 1 | bucket | 2.47 ms | 247.1 | 1.00 | 29800 | 181.1 | - |  |");
    /* Headline: plates at its largest measured size. */
    expect_line(out, "## Headline: plates, 10000 nodes");
    expect_line(out, "| natural | bucket | 1 | 2.47 ms | 247.1 | 29800 |");
    /* Scaling exponent of bucket with 2 threads: ln(6490199.50 / 647743.21)
     * / ln(10000 / 1024) = 1.011. */
    expect_line(out, "| plates | bucket | 1.01 | 1024 – 10000 |");
    /* Speed-up 1 -> 2 threads at 10000: 2471139.17 / 6490199.50 = 0.381,
     * efficiency 0.381 / 2 = 19%. */
    expect_line(out, "| plates | bucket | natural | 10000 | 2.47 ms | 6.49 ms | 0.38 | 19% |");

    free(out);
}

Test(bench_report, cycle_table_from_sample)
{
    cr_assert(access(SAMPLE, R_OK) == 0, "%s not found", SAMPLE);
    int status = -1;
    char *out = run_report(SAMPLE, &status);
    cr_assert_eq(status, 0, "report.py failed:\n%s", out);

    expect_line(out, "## Full contact cycle");
    /* No label on the aggregates: the precision is the file's (ct_build's
     * precision=double). */
    expect_line(out, "### double precision");
    expect_line(out, "| family | nodes | threads | candidates/node | evaluated/node | active/node "
                     "| re-sort interval (cycles) | search (amortised) | narrow | force | assembly "
                     "| time step | total ns/node/cycle | × threads (per thread) "
                     "| vs target 15 | speed-up |");
    /* 1 thread, the real run's median: cand_per_node 6.7979 and
     * active_per_node 2.0834 to 2 decimals (the sample predates
     * eval_per_node: "-"); resort_interval 19 (no
     * resort_interval_seen); phases 34.07, 259.71, 226.42, 83.52, 29.90;
     * total 633.63, times 1 thread 633.63; vs target 633.63 / 15 = 42.24;
     * no speed-up on the 1-thread row. */
    expect_line(out, "| folded | 100000 | 1 | 6.80 | - | 2.08 | 19 | 34.1 | 259.7 | 226.4 | 83.5 "
                     "| 29.9 | 633.6 | 633.6 | 42.2× | - |");
    /* 2 threads: search 1.83 + 334.9 / 19 = 19.456, then 141.27, 122.64,
     * 48.31, 16.04; total 347.716, times 2 threads 695.433; vs target
     * 695.433 / 15 = 46.36 (the total alone would give 23.2); interval 19,
     * seen 17.5; speed-up 633.634 / 347.716 = 1.822 (the wall times would
     * give 539.2 / 305.1 = 1.77). */
    expect_line(out, "| folded | 100000 | 2 | 6.80 | - | 2.08 | 19 (seen 17.5) | 19.5 | 141.3 | "
                     "122.6 | 48.3 | 16.0 | 347.7 | 695.4 | 46.4× | 1.82 |");
    /* The cycle rows are in their own table, not in the "other" one (which
     * would list them by name with their median time). */
    cr_expect(strstr(out, "| cycle/folded/") == NULL,
              "cycle rows left in the \"other\" table:\n%s", out);
    cr_expect(strstr(out, "## Other benchmarks") == NULL,
              "the sample has no other benchmarks, but the table is there:\n%s", out);

    free(out);
}

Test(bench_report, elements_table_from_sample)
{
    char *out = sample_report("");
    expect_line(out, "## Element forces (the driver)");
    expect_line(out, "| element | mesh | nodes | elements | triangles | hinges | threads "
                     "| ns/element | ns/node | speed-up |");
    /* 1 thread: ns_per_elem 411.338, ns_per_node 408.739; no speed-up. */
    expect_line(out, "| shell | plate | 100000 | 99225 | 396900 | 791280 | 1 | 411.3 | 408.7 "
                     "| - |");
    /* 2 threads: 272.423 and 270.701; speed-up 411.338 / 272.423 = 1.510
     * (the wall times give 40.80 / 27.03 = 1.51 too). */
    expect_line(out, "| shell | plate | 100000 | 99225 | 396900 | 791280 | 2 | 272.4 | 270.7 "
                     "| 1.51 |");
    cr_expect(strstr(out, "| elements/shell/") == NULL,
              "element rows left in the \"other\" table:\n%s", out);
    free(out);
}

Test(bench_report, scenes_table_from_sample)
{
    char *out = sample_report("");
    expect_line(out, "## Whole runs (the driver)");
    expect_line(out, "| scene | nodes | cycles | threads | µs/cycle | ns/node/cycle | elements "
                     "| contact | other | speed-up |");
    /* 1 thread: us_per_cycle 127.708, ns_per_node_cycle 174.942, shares
     * 0.869, 0.0528, 0.0782. */
    expect_line(out, "| showcase | 730 | 3000 | 1 | 127.7 | 174.9 | 87 % | 5 % | 8 % | - |");
    /* 2 threads: 130.515 and 178.788; speed-up 174.942 / 178.788 = 0.978. */
    expect_line(out, "| showcase | 730 | 3000 | 2 | 130.5 | 178.8 | 82 % | 7 % | 11 % | 0.98 |");
    cr_expect(strstr(out, "| scene/") == NULL, "scene rows left in the \"other\" table:\n%s",
              out);
    free(out);
}

Test(bench_report, missing_file_fails)
{
    int status = 0;
    char *out = run_report("tests/data/no_such_file.json", &status);
    cr_expect_neq(status, 0, "report.py accepted a missing file:\n%s", out);
    cr_expect(strstr(out, "cannot read") != NULL, "no error message:\n%s", out);
    free(out);
}

Test(bench_report, paired_ratio_table_from_sample)
{
    char *out = sample_report("");

    expect_line(out, "## Ratio targets, measured in interleaved rounds");
    expect_line(out, "| family | nodes | threads | b vs a | a ns/node | b ns/node | ratio b/a "
                     "| range | same pairs | target | met? |");
    /* The sample's medians: ns_a 73.983, ns_b 140.264, ratio 1.8025 (at
     * most 2: met), ratio_min 1.7364, ratio_max 1.8671, same_pairs 1. */
    expect_line(out, "| plates | 1000000 | 2 | bsp-vs-bucket | 74.0 | 140.3 | 1.80 | 1.74-1.87 "
                     "| yes | ≤ 2 (issue 2: bsp within 2× of bucket, uniform mesh) | yes |");
    /* Two numberings: no same_pairs counter ("-"); ratio 1.9596 > 1.5. */
    expect_line(out, "| plates | 1000000 | 2 | bucket-shuffled-vs-natural | 75.4 | 140.2 | 1.96 "
                     "| 1.90-2.19 | - | ≤ 1.5 (issue 2: shuffled within 1.5× of ordered) "
                     "| **no** |");
    /* Graded: 0.7658 < 1, met. */
    expect_line(out, "| graded | 100000 | 2 | bsp-vs-bucket | 308.2 | 234.3 | 0.77 | 0.75-0.77 "
                     "| yes | < 1 (issue 2: bsp faster than bucket, graded mesh) | yes |");
    /* Sorted by family: graded before plates. */
    const char *g = strstr(out, "| graded | 100000 | 2 | bsp-vs-bucket");
    const char *p = strstr(out, "| plates | 1000000 | 2 | bsp-vs-bucket");
    cr_expect(g && p && g < p, "rows not sorted by family:\n%s", out);
    cr_expect(strstr(out, "| paired/") == NULL, "paired rows left in the \"other\" table:\n%s",
              out);

    free(out);
}

Test(bench_report, interleaved_table_from_sample)
{
    cr_assert(access(INTER, R_OK) == 0, "%s not found", INTER);
    char *out = sample_report(INTER);

    expect_line(out, "## Single-precision speed-up, measured in interleaved rounds");
    expect_line(out, "| benchmark | a (double) | b (single) | speed-up a/b | range | ≥ 1.6? |");
    /* The file's row: a 16.256, b 10.271, ratio 1.5526 (< 1.6), range
     * 1.4648-1.5943. */
    expect_line(out, "| kernels/narrow/tri/t1/1000000 | 16.3 | 10.3 | 1.55 | 1.46-1.59 "
                     "| **no** |");
    /* Newton 10^6: a 37.228, b 19.652, ratio 1.8930 >= 1.6, range
     * 1.6184-1.9544. */
    expect_line(out, "| kernels/narrow/newton/t1/1000000 | 37.2 | 19.7 | 1.89 | 1.62-1.95 "
                     "| yes |");
    /* The probe's barrier over the rounds: tri 0.19-0.81 µs (4.3x: the host
     * moved its CPUs), Newton 0.78-0.82 (within 1.25x: not named). */
    expect_line(out, "The host moved its CPUs between the rounds of kernels/narrow/tri/t1/1000000 "
                     "(the probe's barrier of both CPUs, bench/bench_host.c, from 0.19 to 0.81 "
                     "µs): their range holds rounds under both placements.");
    /* Without the file, no such table. */
    free(out);
    out = sample_report("");
    cr_expect(strstr(out, "Single-precision speed-up, measured") == NULL,
              "interleaved table without its file:\n%s", out);
    free(out);
}

/* A fake benchmark program (a shell script) for bench/interleave.py: it
 * appends its tag to LOG, counts its calls in CNT, and writes a Google
 * Benchmark JSON with one run whose ns_per_pair is `first` on odd calls
 * and `second` on even ones, and whose host probe's barrier is `bar`. */
/* Write the shell script text to path, executable. */
static void write_script(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    cr_assert(f, "cannot write %s", path);
    fputs(text, f);
    fclose(f);
    cr_assert(chmod(path, 0755) == 0, "chmod %s", path);
}

static void write_fake(const char *path, const char *tag, const char *log, const char *cnt,
                       const char *first, const char *second, const char *bar)
{
    char text[2048];
    snprintf(text, sizeof text,
            "#!/bin/sh\n"
            "echo %s >> %s\n"
            "n=$(cat %s 2>/dev/null || echo 0); n=$((n + 1)); echo $n > %s\n"
            "v=%s; [ $((n %% 2)) -eq 0 ] && v=%s\n"
            "for a in \"$@\"; do case $a in --benchmark_out=*) out=${a#--benchmark_out=};; "
            "esac; done\n"
            "printf '{\"context\": {\"ct_build\": \"%s\"}, \"benchmarks\": [{\"name\": "
            "\"kernels/x/t1/10/real_time\", \"run_name\": \"kernels/x/t1/10/real_time\", "
            "\"run_type\": \"iteration\", \"host_barrier_us\": %s, \"ns_per_pair\": %%s}]}' "
            "$v > $out\n",
            tag, log, cnt, cnt, first, second, tag, bar);
    write_script(path, text);
}

Test(bench_report, interleave_alternates_and_takes_medians)
{
    char dir[] = "/tmp/ct_interleave_XXXXXX";
    cr_assert(mkdtemp(dir), "mkdtemp");
    char a[300], b[300], log[300], ca[300], cb[300], js[300], cmd[1600];
    snprintf(a, sizeof a, "%s/a.sh", dir);
    snprintf(b, sizeof b, "%s/b.sh", dir);
    snprintf(log, sizeof log, "%s/log", dir);
    snprintf(ca, sizeof ca, "%s/ca", dir);
    snprintf(cb, sizeof cb, "%s/cb", dir);
    snprintf(js, sizeof js, "%s/out.json", dir);
    /* a: always 10; b: 4 on its odd calls, 5 on its even ones. Three
     * rounds: ratios 10/4, 10/5, 10/4 = 2.5, 2, 2.5: median 2.5, range 2 to
     * 2.5; b's median 4. The probe's barrier: 0.2 us in a's runs, 0.8 in
     * b's: the row's range 0.2-0.8, the host moved its CPUs. */
    write_fake(a, "A", log, ca, "10", "10", "0.2");
    write_fake(b, "B", log, cb, "4", "5", "0.8");
    snprintf(cmd, sizeof cmd,
             "python3 bench/interleave.py %s %s --filter x --rounds 3 --json %s 2>&1", a, b, js);
    int status = -1;
    char *out = ctt_run_cmd(cmd, &status);
    cr_assert_eq(status, 0, "interleave.py failed:\n%s", out);
    cr_expect(strstr(out, "barrier 0.20-0.80 us: the host moved its CPUs between rounds") != NULL,
              "the moved CPUs not said:\n%s", out);
    free(out);
    /* The order of the calls: A B, then B A, then A B. */
    snprintf(cmd, sizeof cmd, "tr -d '\\n' < %s", log);
    out = ctt_run_cmd(cmd, &status);
    cr_expect_str_eq(out, "ABBAAB", "calls not alternated: %s", out);
    free(out);
    snprintf(cmd, sizeof cmd,
             "python3 -c \"import json; r = json.load(open('%s'))['interleaved']['rows'][0]; "
             "print('%%s %%g %%g %%g %%g %%g %%d %%g %%g' %% (r['name'], r['a'], r['b'], "
             "r['ratio'], r['ratio_min'], r['ratio_max'], r['rounds'], r['barrier_min'], "
             "r['barrier_max']))\"", js);
    out = ctt_run_cmd(cmd, &status);
    cr_expect_str_eq(out, "kernels/x/t1/10 10 4 2.5 2 2.5 3 0.2 0.8\n", "rows: %s", out);
    free(out);
    /* A program that fails is reported, not averaged away. */
    snprintf(cmd, sizeof cmd, "python3 bench/interleave.py /bin/false %s --filter x 2>&1", b);
    out = ctt_run_cmd(cmd, &status);
    cr_expect_neq(status, 0, "a failing program was accepted:\n%s", out);
    free(out);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    cr_expect(system(cmd) == 0);
}

/* Run cmd and expect its output to be want. */
static void expect_cmd_output(const char *cmd, const char *want, const char *what)
{
    int status = -1;
    char *out = ctt_run_cmd(cmd, &status);
    cr_expect_str_eq(out, want, "%s: %s", what, out);
    free(out);
}

/* A fake benchmark program that answers every call with two repetitions of
 * one run, ns_per_pair `first` then `second`, and appends its arguments to
 * LOG. */
static void write_fake_reps(const char *path, const char *log, const char *first,
                            const char *second)
{
    char text[2048];
    snprintf(text, sizeof text,
            "#!/bin/sh\n"
            "echo \"$@\" >> %s\n"
            "for a in \"$@\"; do case $a in --benchmark_out=*) out=${a#--benchmark_out=};; "
            "esac; done\n"
            "r='\"name\": \"kernels/x/t1/10/real_time\", \"run_name\": "
            "\"kernels/x/t1/10/real_time\", \"run_type\": \"iteration\"'\n"
            "printf '{\"context\": {}, \"benchmarks\": [{%%s, \"ns_per_pair\": %s}, "
            "{%%s, \"ns_per_pair\": %s}, {\"name\": \"kernels/x/t1/10/real_time_median\", "
            "\"run_name\": \"kernels/x/t1/10/real_time\", \"run_type\": \"aggregate\", "
            "\"ns_per_pair\": 1}]}' \"$r\" \"$r\" > $out\n",
            log, first, second);
    write_script(path, text);
}

Test(bench_report, interleave_keeps_the_fastest_repetition)
{
    char dir[] = "/tmp/ct_interleave_XXXXXX";
    cr_assert(mkdtemp(dir), "mkdtemp");
    char a[300], b[300], log[300], js[300], cmd[1600];
    snprintf(a, sizeof a, "%s/a.sh", dir);
    snprintf(b, sizeof b, "%s/b.sh", dir);
    snprintf(log, sizeof log, "%s/log", dir);
    snprintf(js, sizeof js, "%s/out.json", dir);
    /* a's repetitions read 12 then 9, b's 3 then 6: the fastest of each, 9
     * and 3, give the ratio 3 (the last ones would give 1.5, the first 4;
     * the aggregate row, 1, is not a repetition). */
    write_fake_reps(a, log, "12", "9");
    write_fake_reps(b, log, "3", "6");
    snprintf(cmd, sizeof cmd,
             "python3 bench/interleave.py %s %s --filter x --rounds 2 --repetitions 2 "
             "--json %s 2>&1",
             a, b, js);
    int status = -1;
    char *out = ctt_run_cmd(cmd, &status);
    cr_assert_eq(status, 0, "interleave.py failed:\n%s", out);
    free(out);
    snprintf(cmd, sizeof cmd,
             "python3 -c \"import json; d = json.load(open('%s'))['interleaved']; "
             "r = d['rows'][0]; print('%%g %%g %%g %%d %%d' %% (r['a'], r['b'], r['ratio'], "
             "r['rounds'], d['repetitions']))\"",
             js);
    expect_cmd_output(cmd, "9 3 3 2 2\n", "rows");
    /* Every call asked for the repetitions. */
    snprintf(cmd, sizeof cmd, "grep -c -- '--benchmark_repetitions=2' %s", log);
    expect_cmd_output(cmd, "4\n", "calls with --benchmark_repetitions=2");
    snprintf(cmd, sizeof cmd,
             "python3 bench/interleave.py %s %s --filter x --repetitions 0 2>&1", a, b);
    out = ctt_run_cmd(cmd, &status);
    cr_expect_neq(status, 0, "--repetitions 0 was accepted:\n%s", out);
    free(out);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    cr_expect(system(cmd) == 0);
}

Test(bench_report, efficiency_table_from_sample)
{
    char *out = sample_report("");

    expect_line(out, "## Parallel efficiency, measured in interleaved rounds");
    expect_line(out, "| benchmark | size | threads | 1 thread | all threads | efficiency | range "
                     "| best | ≥ 90 %? |");
    /* The sample's medians: ns_t1 35.972, ns_tn 24.617, eff 0.8656 (86.6 %,
     * below 90: not met), eff_min 0.6956, eff_max 1.0245, eff_best 0.9759. */
    expect_line(out, "| narrow/4tri | 1000000 | 2 | 36.0 ns/pair | 24.6 ns/pair | 87 % "
                     "| 70 %-102 % | 98 % | **no** |");
    /* The triad in GB/s: 1 / 0.043893 ns per byte = 22.78, 1 / 0.033042 =
     * 30.26; eff 0.6647; no verdict, it is the ceiling. Listed after the
     * kernels. */
    expect_line(out, "| triad/dram | 8388608 | 2 | 22.8 GB/s | 30.3 GB/s | 66 % | 63 %-72 % "
                     "| 66 % | (ceiling) |");
    /* The compute ceiling: 1 / 0.0655 = 15.27 and 1 / 0.0330 = 30.30 G
     * multiply-adds per second, eff 0.9810, range 0.7338-1.0062, best
     * 0.9969; a ceiling, no verdict, listed before the triad (sorted by
     * name among the ceilings). */
    expect_line(out, "| compute | 536870912 | 2 | 15.3 G mul-add/s | 30.3 G mul-add/s "
                     "| 98 % | 73 %-101 % | 100 % | (ceiling) |");
    const char *k = strstr(out, "| narrow/4tri | 1000000 | 2 | 36.0");
    const char *cc = strstr(out, "| compute | 536870912");
    cr_expect(k && cc && k < cc, "the compute ceiling is not after the kernels:\n%s", out);
    const char *t = strstr(out, "| triad/dram | 8388608");
    cr_expect(k && t && k < t, "the triad is not after the kernels:\n%s", out);
    cr_expect(strstr(out, "| efficiency/") == NULL,
              "efficiency rows left in the \"other\" table:\n%s", out);
    free(out);
}

Test(bench_report, sync_table_from_sample)
{
    char *out = sample_report("");
    expect_line(out, "## Hardware floor");
    expect_line(out, "| precision | threads | µs per region | µs per barrier |");
    /* The sample's medians: regions 0.0977 and 1.0643 µs, barriers 0.0227
     * and 0.4714 µs, one row per thread count. */
    expect_line(out, "| double | 1 | 0.10 | 0.02 |");
    expect_line(out, "| double | 2 | 1.06 | 0.47 |");
    cr_expect(strstr(out, "| floor/sync/") == NULL,
              "sync rows left in the \"other\" table:\n%s", out);
    free(out);
}

/* The host probe's table from the sample's five probed rows (by hand).
 * Medians per team size: 1 thread, chains 70, 80, 140 -> 80, reads 36, 38,
 * 40 -> 38; 2 threads, chains 72, 75 -> 73.5, reads 78, 80 -> 79; the
 * barriers (every processor: one median for the file) 0.8, 1.2, 1.6 ->
 * 1.2. Off by more than 1.25 either way: shell t1's chain 140/80 = 1.75,
 * shell t2's barrier 0.8/1.2 = 0.67, the folded cycle t2's barrier 1.6/1.2
 * = 1.33 (named in that order, the farthest first); the direct search
 * (chain 0.875) and the showcase are not. The targets table notes the
 * cycle row's (targets_table_from_sample). */
Test(bench_report, host_probe_from_sample)
{
    char *out = sample_report("");
    expect_line(out, "| precision | threads | rows | chain µs: median (lowest-highest) | "
                     "barrier µs: median (lowest-highest) | read GB/s: median (lowest-highest) | "
                     "rows off |");
    expect_line(out, "| double | 1 | 3 | 80.0 (70.0-140.0) | 1.20 (1.20-1.20) | 38.0 (36.0-40.0) "
                     "| 1 |");
    expect_line(out, "| double | 2 | 2 | 73.5 (72.0-75.0) | 1.20 (0.80-1.60) | 79.0 (78.0-80.0) "
                     "| 2 |");
    expect_line(out, "Rows measured while the host differed, double: "
                     "elements/shell/plate/t1/100000 (chain ×1.75), elements/shell/plate/t2/100000 "
                     "(barrier ×0.67), cycle/folded/t2/100000 (barrier ×1.33).");
    cr_expect(strstr(out, "scene/showcase/t1/3000 (") == NULL,
              "the showcase, at the medians, named:\n%s", out);
    cr_expect(strstr(out, "search/plates/direct/natural/t1/1000 (") == NULL,
              "the direct search, within 1.25 of the medians, named:\n%s", out);
    free(out);
}

/* The speed targets gathered from the sample and the interleaved sample, by
 * hand: the paired rows' ratios (graded 0.7658 < 1 met; plates bsp 1.8025
 * <= 2 met; shuffled 1.9596 > 1.5 not met); the single-precision rows at
 * 10^6 pairs span 1.5422 (edge) to 2.0061 (fused), under 1.6: not met; one
 * kernel efficiency row, 0.8656 (87 %, not met), with the machine's compute
 * 0.9810 (98 %) and triad 0.6647 (66 %); the cycle's per-thread totals
 * 633.6 and 695.4, over 15. No search or kernel at 10^6: those rows are
 * unmeasured. */
Test(bench_report, targets_table_from_sample)
{
    char *out = sample_report(INTER);
    expect_line(out, "## Speed targets of the issues, in this run");
    expect_line(out, "| 2 | bucket search ≤ 10 ns/node (plates 10^6, 2 threads) | - | - | - |");
    expect_line(out, "| 2 | bsp faster than bucket, graded mesh: b/a < 1 (graded 100000, "
                     "2 threads) | 0.77 (rounds 0.75-0.77) | - | yes |");
    expect_line(out, "| 2 | bsp within 2× of bucket, uniform mesh: b/a ≤ 2 (plates 1000000, "
                     "2 threads) | 1.80 (rounds 1.74-1.87) | - | yes |");
    expect_line(out, "| 2 | shuffled within 1.5× of ordered: b/a ≤ 1.5 (plates 1000000, "
                     "2 threads) | 1.96 (rounds 1.90-2.19) | - | **no** |");
    expect_line(out, "| 3 | node–triangle ≤ 5 ns/pair (10^6 pairs, 1 thread) | - | - | - |");
    expect_line(out, "| 3 | single precision ≥ 1.6× faster (interleaved, 10^6 pairs, 6 kernels) "
                     "| 1.54-2.01 (smallest: edge) | - | **no** |");
    expect_line(out, "| 3 | 2-thread efficiency ≥ 90 % (interleaved, 1 kernel) | 87 % "
                     "(narrow/4tri) | machine: compute 98 %, DRAM triad 66 % | **no** |");
    expect_line(out, "| 5 | full contact cycle ≤ 15 ns/node/cycle per thread | 633.6 (folded "
                     "100000, 1 thread) to 695.4 (folded 100000, 2 threads, host: barrier ×1.33) "
                     "| - | **no** |");
    /* The table comes before the search tables. */
    const char *t = strstr(out, "## Speed targets"), *h = strstr(out, "## Headline");
    cr_expect(t && h && t < h, "the targets are not before the headline:\n%s", out);
    free(out);
}

/* How steady the host was (bench/report_noise.py): the sample's three cv
 * aggregates, 4.12 % (bucket t1/1000), 12.16 % (cycle folded t1), 1.65 %
 * (shell elements t1). Sorted 0.0165, 0.0412, 0.1216: median 4.1 %; 90th
 * percentile at rank 0.9 * 2 = 1.8, 0.0412 + 0.8 * 0.0804 = 0.1055, 10.6 %;
 * largest 12.2 %; one row above 10 %, named. */
Test(bench_report, noise_table_from_sample)
{
    char *out = sample_report("");
    expect_line(out, "## How steady the host was during this run");
    expect_line(out, "| precision | rows | median cv | 90th percentile | largest | rows above "
                     "10 % |");
    expect_line(out, "| double | 3 | 4.1 % | 10.6 % | 12.2 % | 1 |");
    expect_line(out, "Noisiest rows, double: cycle/folded/t1/100000 (12.2 %).");
    cr_expect(strstr(out, "search/plates/bucket/natural/t1/1000 (") == NULL,
              "a row below 10 %% named as noisy:\n%s", out);
    free(out);
}

/* Without a cv aggregate (a run kept with its repetition rows), the cv is
 * that of the rows' times: 80, 100, 120 ns have mean 100 and sample
 * standard deviation 20, a cv of 20.0 %. */
Test(bench_report, noise_from_repetition_rows)
{
    char dir[64];
    ctt_tmpdir(dir, "noise");
    static const char row[] =
        "{\"name\": \"kernels/x/t1/10/real_time\", \"run_name\": \"kernels/x/t1/10/real_time\", "
        "\"run_type\": \"iteration\", \"repetitions\": 3, \"repetition_index\": %d, "
        "\"iterations\": 1, \"real_time\": %d, \"cpu_time\": %d, \"time_unit\": \"ns\"}";
    char rows[3][400], text[1400];
    const int t[3] = {80, 120, 100};
    for (int i = 0; i < 3; i++)
        snprintf(rows[i], sizeof rows[i], row, i, t[i], t[i]);
    snprintf(text, sizeof text,
             "{\"context\": {\"ct_precision\": \"single\"}, \"benchmarks\": [%s, %s, %s]}\n",
             rows[0], rows[1], rows[2]);
    ctt_write_file(dir, "reps.json", text);
    char arg[128];
    snprintf(arg, sizeof arg, "%s/reps.json", dir);
    int status = -1;
    char *out = run_report(arg, &status);
    cr_assert_eq(status, 0, "report.py failed:\n%s", out);
    expect_line(out, "| single | 1 | 20.0 % | 20.0 % | 20.0 % | 1 |");
    expect_line(out, "Noisiest rows, single: kernels/x/t1/10 (20.0 %).");
    free(out);
    ctt_rmtree(dir);
}
