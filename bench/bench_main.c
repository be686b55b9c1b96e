/*
 * bench_main.c -- the benchmark program (make bench).
 *
 * Prints the provenance (build, machine, threads), the hwloc topology and
 * the thread binding, stores them in the report's context, registers the
 * benchmarks and runs them through Google Benchmark.
 *
 * Own options (removed before Google Benchmark sees the arguments):
 *   --bind=compact|spread|none   thread placement (default: CT_BENCH_BIND,
 *                                else spread)
 *   --full                       the full set (same as CT_BENCH_FULL=1)
 *   --direct-budget=X            direct search only while nsec*nseg <= X
 *                                (default 2e8, 4e9 with --full;
 *                                CT_BENCH_DIRECT_BUDGET)
 *   --no-host-probe              no probe of the host after the
 *                                benchmarks (bench_host.c; no host_*
 *                                counters)
 * Defaults added unless given: --benchmark_repetitions=3
 * --benchmark_report_aggregates_only=true --benchmark_min_time=0.05
 * --benchmark_out=build/bench.json --benchmark_out_format=json.
 * Every other --benchmark_* flag (e.g. --benchmark_filter=REGEX) passes
 * through.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench_cycle.h"
#include "bench_elements.h"
#include "bench_scene.h"
#include "bench_host.h"
#include "bench_paired.h"
#include "bench_floor.h"
#include "bench_kernels.h"
#include "bench_peers.h"
#include "bench_real.h"
#include "bench_search.h"
#include "bench_trade.h"
#include "bench_topology.h"
#include "contact.h"
#include "gbench.h"
#include "provenance.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static int has_flag(int argc, char **argv, const char *prefix)
{
    size_t n = strlen(prefix);
    for (int i = 1; i < argc; i++)
        if (strncmp(argv[i], prefix, n) == 0)
            return 1;
    return 0;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: bench [--bind=compact|spread|none] [--full] [--direct-budget=X]\n"
               "             [--no-host-probe]\n"
               "             [--benchmark_* flags of Google Benchmark, e.g.\n"
               "              --benchmark_filter=REGEX --benchmark_min_time=S]\n"
               "names: search/<family>/<algo>/<numbering>/t<threads>/<nodes>/real_time\n"
               "       kernels/<group>/<kernel>/t<threads>/<pairs>/real_time\n"
               "       floor/<triad/dram|triad/ws|bucket/plates>/t<threads>/<n>/real_time\n"
               "       real/<deck>/<algo>/t<threads>/real_time\n"
               "       cycle/<folded|crumpled>/t<threads>/<nodes>/real_time\n"
               "       paired/<family>/<b>-vs-<a>/t<threads>/<nodes>/real_time\n"
               "       efficiency/<kernel|triad/dram>/t<threads>/<n>/real_time\n"
               "       elements/<shell/plate|brick/block>/t<threads>/<nodes>/real_time\n"
               "       scene/<showcase|folding-sheet-wide>/t<threads>/<cycles>/real_time\n"
               "env: CT_BENCH_FULL=1, CT_BENCH_BIND, CT_BENCH_DIRECT_BUDGET,\n"
               "     CT_SHARED (the Radioss decks), CT_BENCH_MESH=deck.rad\n");
}

int main(int argc, char **argv)
{
    int vrc = ctb_peers_verify_main(argc, argv); /* bench --verify-peers */
    if (vrc >= 0)
        return vrc;
    vrc = ctb_trade_dump_main(argc, argv); /* bench --dump-narrow FILE */
    if (vrc >= 0)
        return vrc;
    ctb_search_config cfg;
    memset(&cfg, 0, sizeof cfg);
    const char *e = getenv("CT_BENCH_FULL");
    cfg.full = e && *e && strcmp(e, "0") != 0;
    int bind = ctb_bind_from_env();
    if (bind < 0) {
        fprintf(stderr, "bench: CT_BENCH_BIND must be compact, spread or none\n");
        return 2;
    }
    e = getenv("CT_BENCH_DIRECT_BUDGET");
    /* The reduced set keeps `make bench` under 10 minutes on 2 cores: the
     * direct search runs while nsec*nseg <= 2e8 and is extrapolated
     * beyond; the full set runs it to 4e9. */
    cfg.direct_budget = e && *e ? strtod(e, NULL) : -1;
    cfg.seed = 12345;
    int probe = 1;

    /* Our own options out, defaults in, Google Benchmark's flags kept. */
    char **args = calloc((size_t)argc + 8, sizeof *args);
    if (!args)
        return 1;
    int nargs = 0;
    args[nargs++] = argv[0];
    for (int i = 1; i < argc; i++) {
        if (strncmp(argv[i], "--bind=", 7) == 0) {
            bind = ctb_bind_from_name(argv[i] + 7);
            if (bind < 0) {
                fprintf(stderr, "bench: unknown binding '%s'\n", argv[i] + 7);
                usage(stderr);
                free(args);
                return 2;
            }
        } else if (strcmp(argv[i], "--full") == 0) {
            cfg.full = 1;
        } else if (strcmp(argv[i], "--no-host-probe") == 0) {
            probe = 0;
        } else if (strncmp(argv[i], "--direct-budget=", 16) == 0) {
            cfg.direct_budget = strtod(argv[i] + 16, NULL);
        } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            free(args);
            return 0;
        } else {
            args[nargs++] = argv[i];
        }
    }
    if (!(cfg.direct_budget >= 0))
        cfg.direct_budget = cfg.full ? 4e9 : 2e8;
    if (!has_flag(argc, argv, "--benchmark_repetitions"))
        args[nargs++] = "--benchmark_repetitions=3";
    if (!has_flag(argc, argv, "--benchmark_report_aggregates_only") &&
        !has_flag(argc, argv, "--benchmark_display_aggregates_only"))
        args[nargs++] = "--benchmark_report_aggregates_only=true";
    if (!has_flag(argc, argv, "--benchmark_min_time"))
        args[nargs++] = "--benchmark_min_time=0.05";
    if (!has_flag(argc, argv, "--benchmark_out=")) {
        if (mkdir("build", 0777) != 0 && errno != EEXIST)
            fprintf(stderr, "bench: cannot create build/: %s\n", strerror(errno));
        args[nargs++] = "--benchmark_out=build/bench.json";
        if (!has_flag(argc, argv, "--benchmark_out_format"))
            args[nargs++] = "--benchmark_out_format=json";
    }
    args[nargs] = NULL;
    cfg.bind = (ctb_bind_policy)bind;

#ifdef _OPENMP
    cfg.max_threads = omp_get_max_threads();
#else
    cfg.max_threads = 1;
#endif
    /* Memory: about 500 bytes per target node at the peak (mesh generation,
     * first-touched copies, workspace, pairs, reference pairs; measured:
     * 430 MB for plates at 10^6); a size is skipped when that exceeds 70%
     * of the physical memory. */
    cfg.bytes_per_node = 500;
    long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGESIZE);
    cfg.mem_limit = pages > 0 && psize > 0 ? 0.7 * (double)pages * (double)psize : 4e9;

    /* Provenance, topology and binding: printed and put in the context. */
    char line[512], where[256];
    ctd_print_provenance(stdout, "# ");
    ctb_topology_print(stdout, "# ");
    int brc = ctb_bind_threads(cfg.bind, cfg.max_threads, where, sizeof where);
    printf("# binding: %s, %d threads: %s%s\n", ctb_bind_name(cfg.bind), cfg.max_threads,
           cfg.bind == CTB_BIND_NONE ? "left to the OpenMP runtime" : where,
           brc ? " (failed)" : "");
    printf("# set: %s (CT_BENCH_FULL=1 for the full set), direct budget nsec*nseg <= %.3g\n",
           cfg.full ? "full" : "reduced", cfg.direct_budget);
    fflush(stdout);

    gb_add_context("ct_build", ct_build_info());
    gb_add_context("ct_machine", ctd_machine_summary(line, sizeof line));
    gb_add_context("ct_topology", ctb_topology_line(line, sizeof line));
    snprintf(line, sizeof line, "%s (%d threads: %s)", ctb_bind_name(cfg.bind), cfg.max_threads,
             cfg.bind == CTB_BIND_NONE ? "runtime" : where);
    gb_add_context("ct_binding", line);
    snprintf(line, sizeof line, "%d", cfg.max_threads);
    gb_add_context("ct_threads", line);
    gb_add_context("ct_set", cfg.full ? "full" : "reduced");
    snprintf(line, sizeof line, "%.3g", cfg.direct_budget);
    gb_add_context("ct_direct_budget", line);
    gb_add_context("ct_search_distance", "gap = 0.3 h, margin = 0.2 h (h: mean main edge length)");

    int rc = 0;
    if (ctb_search_register(&cfg) < 0 || ctb_peers_register(&cfg) < 0 ||
        ctb_kernels_register(&cfg) < 0 || ctb_floor_register(&cfg) < 0 ||
        ctb_real_register(&cfg) < 0 || ctb_trade_register(&cfg) < 0 ||
        ctb_cycle_register(&cfg) < 0 || ctb_paired_register(&cfg) < 0 ||
        ctb_elements_register(&cfg) < 0 || ctb_scene_register(&cfg) < 0) {
        fprintf(stderr, "bench: out of memory registering benchmarks\n");
        rc = 1;
    } else {
        if (probe)
            gb_set_host_probe(ctb_host_probe);
        rc = gb_run(&nargs, args);
        if (rc == 1)
            usage(stderr);
        else if (rc == 2)
            fprintf(stderr, "bench: no benchmark matches the filter\n");
    }
    ctb_search_cleanup();
    if (ctb_peers_cleanup() > 0 && rc == 0)
        rc = 4; /* a peer's pairs differed from ours, or a peer failed */
    ctb_kernels_cleanup();
    ctb_floor_cleanup();
    ctb_real_cleanup();
    ctb_trade_cleanup();
    ctb_cycle_cleanup();
    ctb_paired_cleanup();
    ctb_elements_cleanup();
    ctb_scene_cleanup();
    ctb_host_cleanup();
    ctb_topology_close();
    free(args);
    return rc;
}
