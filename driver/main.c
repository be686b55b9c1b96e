/*
 * main.c -- the `contact` command.
 *
 *   contact info                 build provenance and machine topology
 *   contact search [options]     run the contact searches on a synthetic case,
 *                                check each against the direct search, time them
 *   contact demo                 the search comparison, each checked against direct: on
 *                                a self-contact sheet and on two plates
 *   contact run SCENE [options]  run a scene (explicit dynamics)
 *   contact check SCENE          validate a scene (file, model, first step) without running it
 *
 * Exit codes: 0 success, 1 bad usage, 2 bad input (scene), 3 a verification
 * failed, 4 the run went unstable, 5 output failure or out of memory.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "contact.h"
#include "meshgen.h"
#include "provenance.h"
#include "run.h"
#include "scene.h"
#include "wtime.h"

#ifdef _OPENMP
#include <omp.h>
#endif

enum { EXIT_USAGE = 1, EXIT_VERIFY = 3, EXIT_NOMEM = 5 };

typedef struct search_opts {
    const char *family;
    int64_t n;
    int algo; /* -1: all */
    ctd_numbering num;
    double gap, margin; /* < 0: from the case's mean edge length */
    int repeat;
    uint64_t seed;
    ct_search_filter filter;
    int check; /* 0: no direct reference, even when affordable */
    int renumber; /* ct_search_params.renumber: 0 auto, 1 on, -1 off */
    int renumber_keep; /* ct_search_params.renumber_keep: 0 default, -1 fresh */
    int dense;    /* ct_search_params.dense: 0 auto, 1 on, -1 off */
    double cells; /* ct_search_params.cell_factor: 0 chosen per input */
} search_opts;

static void usage_search(FILE *f)
{
    fprintf(f, "usage: contact search [--family F] [--n NODES] [--algo direct|topological|bucket|bsp|all]\n"
               "                      [--numbering natural|shuffled|sfc] [--gap G] [--margin M]\n"
               "                      [--filter hull|box] [--repeat R] [--seed S] [--threads T]\n"
               "                      [--check auto|off] [--renumber auto|on|off]\n"
               "                      [--renumber-keep K|fresh] [--dense auto|on|off]\n"
               "                      [--cells auto|F]\n"
               "Runs each search on a synthetic case, checks its pair set against the direct\n"
               "search (when affordable; --check off skips it, for timing runs) and prints\n"
               "the median time per secondary node (--algo direct times the direct search\n"
               "itself with --check off, and otherwise prints its reference run).\n"
               "Families:");
    int nf = 0;
    const char *const *fam = ctd_case_families(&nf);
    for (int i = 0; i < nf; i++)
        fprintf(f, " %s", fam[i]);
    fprintf(f, "\nDefaults: --family plates --n 100000 --algo all --numbering natural,\n"
               "gap 0.4 h and margin 0.1 h (h: mean main edge length), filter hull\n"
               "(hull: exact distance to the segment's corners' hull; box: distance to its\n"
               "bounding box, looser and cheaper). A renumbered search (scattered numbering)\n"
               "reuses its numbering for --renumber-keep searches of the same topology\n"
               "(default 64; fresh: a new numbering every search). The bucket grid's cells:\n"
               "auto (chosen per input by the cost of binning and testing, counted on a\n"
               "sample) or F times the Radioss sizing (1: Radioss's, from the bounding box's\n"
               "faces); the line shows the factor used and whether the input was renumbered.\n");
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Pairs of `a` missing from `b` (both in canonical order). */
static int64_t count_missing(const ct_pairs *a, const ct_pairs *b, const ct_idx *secpos)
{
    int64_t miss = 0, j = 0;
    for (int64_t i = 0; i < a->n; i++) {
        while (j < b->n && (secpos[b->node[j]] < secpos[a->node[i]] ||
                            (b->node[j] == a->node[i] && b->seg[j] < a->seg[i])))
            j++;
        if (!(j < b->n && b->node[j] == a->node[i] && b->seg[j] == a->seg[i]))
            miss++;
    }
    return miss;
}

static int run_search(const search_opts *o)
{
    ctd_case c;
    ct_diag d = {0};
    double t0 = ctd_wtime();
    int rc = ctd_case_make(&c, o->family, o->n, o->num, o->seed, &d);
    if (rc) {
        fprintf(stderr, "contact search: cannot build case '%s': %s\n", o->family,
                d.msg[0] ? d.msg : ct_strerror(rc));
        return rc == CT_ERR_NOMEM ? EXIT_NOMEM : EXIT_USAGE;
    }
    double tgen = ctd_wtime() - t0;
    double h = c.h_mean > 0 ? c.h_mean : 1.0;
    ct_real gap = (ct_real)(o->gap >= 0 ? o->gap : 0.4 * h);
    ct_real margin = (ct_real)(o->margin >= 0 ? o->margin : 0.1 * h);
    ct_search_input in;
    ctd_case_input(&c, gap, margin, &in);
    in.filter = o->filter;
    printf("case %s: %d nodes, %d secondary, %d main segments, self=%d, numbering %s, "
           "h=%.4g gap=%.4g margin=%.4g filter %s (built in %.3f s)\n",
           c.name, c.mesh.nodes.n, c.sec.n, c.main.n, c.self, ctd_numbering_name(o->num), h,
           (double)gap, (double)margin, o->filter == CT_FILTER_BOX ? "box" : "hull", tgen);

    /* The direct search is run (as the reference, or timed when it is the
     * one asked for with --check off) only below a budget of node-segment
     * tests: above it, it would run for hours. */
    const int affordable = (double)c.sec.n * (double)c.main.n <= 2e10;
    /* The secondary position of each node, to compare canonical lists. */
    ct_idx *secpos = ct_calloc((size_t)c.mesh.nodes.n, sizeof *secpos);
    ct_pairs ref, got;
    ct_pairs_init(&ref, 0);
    ct_pairs_init(&got, 0);
    int have_ref = 0, failed = 0;
    if (!secpos) {
        rc = CT_ERR_NOMEM;
        fprintf(stderr, "contact search: out of memory (%d nodes)\n", c.mesh.nodes.n);
        goto done;
    }
    for (ct_idx i = 0; i < c.sec.n; i++)
        secpos[c.sec.node[i]] = i;
    const int time_direct = o->algo == CT_SEARCH_DIRECT && !o->check;
    if (!o->check) {
        if (!time_direct)
            printf("  direct: skipped (--check off)\n");
    } else if (affordable) {
        ct_search_params p = ct_search_default_params(CT_SEARCH_DIRECT);
        ct_search *s;
        if ((rc = ct_search_init(&s, &p)) == CT_OK) {
            t0 = ctd_wtime();
            rc = ct_search_run(s, &in, &ref);
            printf("  %-12s %10.2f ns/node  %10d pairs  (reference, %.3f s)\n", "direct",
                   1e9 * (ctd_wtime() - t0) / (c.sec.n ? c.sec.n : 1), ref.n, ctd_wtime() - t0);
            ct_search_destroy(s);
        }
        if (rc) {
            fprintf(stderr, "contact search: direct search failed: %s\n", ct_strerror(rc));
            goto done;
        }
        have_ref = 1;
    } else {
        printf("  direct: skipped (%.2g node-segment tests is over the budget)\n",
               (double)c.sec.n * (double)c.main.n);
    }
    /* The direct search is timed here only when it is the one asked for and
     * was not run as the reference (--check off); otherwise its line is the
     * reference's above. */
    for (int a = time_direct ? 0 : 1; a < CT_SEARCH_NALGO; a++) {
        if (o->algo >= 0 && a != o->algo)
            continue;
        if (a == CT_SEARCH_DIRECT && !affordable) {
            printf("  direct: skipped (%.2g node-segment tests is over the budget)\n",
                   (double)c.sec.n * (double)c.main.n);
            continue;
        }
        ct_search_params p = ct_search_default_params((ct_search_algo)a);
        p.renumber = o->renumber;
        p.renumber_keep = o->renumber_keep;
        p.dense = o->dense;
        p.cell_factor = o->cells;
        ct_search *s;
        if ((rc = ct_search_init(&s, &p)) != CT_OK) {
            fprintf(stderr, "contact search: %s: cannot set up the search: %s\n",
                    ct_search_algo_name(a), ct_strerror(rc));
            goto done;
        }
        int reps = o->repeat > 0 ? o->repeat : 5;
        double *ts = calloc((size_t)reps, sizeof *ts);
        if (!ts) {
            /* The timings' array: without it nothing can be timed. */
            rc = CT_ERR_NOMEM;
            fprintf(stderr, "contact search: %s: out of memory (%d timings)\n",
                    ct_search_algo_name(a), reps);
            ct_search_destroy(s);
            goto done;
        }
        for (int r = 0; r < reps && rc == CT_OK; r++) {
            if (a == CT_SEARCH_TOPO)
                ct_search_reset(s); /* time the full first search each time */
            t0 = ctd_wtime();
            rc = ct_search_run(s, &in, &got);
            ts[r] = ctd_wtime() - t0;
        }
        if (rc) {
            fprintf(stderr, "contact search: %s failed: %s\n", ct_search_algo_name(a),
                    ct_strerror(rc));
            free(ts);
            ct_search_destroy(s);
            goto done;
        }
        qsort(ts, (size_t)reps, sizeof *ts, cmp_double);
        printf("  %-12s %10.2f ns/node  %10d pairs  %8.1f B/node", ct_search_algo_name(a),
               1e9 * ts[reps / 2] / (c.sec.n ? c.sec.n : 1), got.n,
               (double)ct_search_memory(s) / (c.sec.n ? c.sec.n : 1));
        ct_search_info si;
        if (ct_search_get_info(s, &si) == CT_OK) {
            if (si.cell_factor > 0)
                printf("  cells x%g", si.cell_factor);
            if (si.renumbered)
                printf("  renumbered");
        }
        if (have_ref) {
            int64_t miss = count_missing(&ref, &got, secpos);
            int64_t extra = count_missing(&got, &ref, secpos);
            int same = got.n == ref.n && memcmp(got.node, ref.node, sizeof(ct_idx) * (size_t)ref.n) == 0 &&
                       memcmp(got.seg, ref.seg, sizeof(ct_idx) * (size_t)ref.n) == 0;
            printf("  %s (missed %lld, extra %lld)", same ? "identical to direct" : "DIFFERS",
                   (long long)miss, (long long)extra);
            /* Say so where a difference is the method's, not a defect. */
            if (!same && extra == 0 && a == CT_SEARCH_TOPO)
                printf("  [allowed: the topological search looks only near each node's last "
                       "closest main node]");
            /* The topological search may miss pairs (its known weakness);
             * nothing may report a pair the direct search rejects. */
            if (extra > 0 || (!same && a != CT_SEARCH_TOPO))
                failed = 1;
        }
        printf("\n");
        free(ts);
        ct_search_destroy(s);
    }
done:
    ct_pairs_destroy(&ref);
    ct_pairs_destroy(&got);
    ct_free(secpos);
    ctd_case_destroy(&c);
    if (rc)
        return rc == CT_ERR_NOMEM ? EXIT_NOMEM : EXIT_USAGE;
    if (failed) {
        fprintf(stderr, "contact search: VERIFICATION FAILED: a search differs from direct\n");
        return EXIT_VERIFY;
    }
    return 0;
}

static int parse_i64(const char *s, int64_t *v)
{
    char *e;
    errno = 0;
    long long x = strtoll(s, &e, 10);
    if (errno || e == s || *e || x < 0)
        return -1;
    *v = x;
    return 0;
}

static int parse_dbl(const char *s, double *v)
{
    char *e;
    errno = 0;
    double x = strtod(s, &e);
    if (errno || e == s || *e || !(x >= 0) || x > 1e300)
        return -1;
    *v = x;
    return 0;
}

static int cmd_search(int argc, char **argv)
{
    search_opts o = {"plates", 100000, -1, CTD_NUM_NATURAL, -1, -1, 5, 1, CT_FILTER_HULL, 1, 0, 0, 0, 0};
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int64_t iv;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage_search(stdout);
            return 0;
        }
        if (!v) {
            fprintf(stderr, "contact search: option %s needs a value\n", a);
            return EXIT_USAGE;
        }
        i++;
        if (!strcmp(a, "--family")) {
            o.family = v;
        } else if (!strcmp(a, "--n")) {
            if (parse_i64(v, &o.n) || o.n < 1 || o.n > 200000000) {
                fprintf(stderr, "contact search: --n expects a node count in [1, 2e8], got '%s'\n", v);
                return EXIT_USAGE;
            }
        } else if (!strcmp(a, "--algo")) {
            o.algo = strcmp(v, "all") ? ct_search_algo_from_name(v) : -1;
            if (strcmp(v, "all") && o.algo < 0) {
                fprintf(stderr, "contact search: --algo expects direct, topological, bucket, bsp or all, got '%s'\n", v);
                return EXIT_USAGE;
            }
        } else if (!strcmp(a, "--numbering")) {
            if (!strcmp(v, "natural"))
                o.num = CTD_NUM_NATURAL;
            else if (!strcmp(v, "shuffled"))
                o.num = CTD_NUM_SHUFFLED;
            else if (!strcmp(v, "sfc"))
                o.num = CTD_NUM_SFC;
            else {
                fprintf(stderr, "contact search: --numbering expects natural, shuffled or sfc, got '%s'\n", v);
                return EXIT_USAGE;
            }
        } else if (!strcmp(a, "--gap") || !strcmp(a, "--margin")) {
            if (parse_dbl(v, !strcmp(a, "--gap") ? &o.gap : &o.margin)) {
                fprintf(stderr, "contact search: %s expects a finite number >= 0, got '%s'\n", a, v);
                return EXIT_USAGE;
            }
        } else if (!strcmp(a, "--filter")) {
            if (strcmp(v, "hull") && strcmp(v, "box")) {
                fprintf(stderr, "contact search: --filter expects hull or box, got '%s'\n", v);
                return EXIT_USAGE;
            }
            o.filter = strcmp(v, "box") ? CT_FILTER_HULL : CT_FILTER_BOX;
        } else if (!strcmp(a, "--check")) {
            if (strcmp(v, "auto") && strcmp(v, "off")) {
                fprintf(stderr, "contact search: --check expects auto or off, got '%s'\n", v);
                return EXIT_USAGE;
            }
            o.check = !strcmp(v, "auto");
        } else if (!strcmp(a, "--renumber")) {
            if (strcmp(v, "auto") && strcmp(v, "on") && strcmp(v, "off")) {
                fprintf(stderr, "contact search: --renumber expects auto, on or off, got '%s'\n",
                        v);
                return EXIT_USAGE;
            }
            o.renumber = !strcmp(v, "on") ? 1 : !strcmp(v, "off") ? -1 : 0;
        } else if (!strcmp(a, "--dense")) {
            if (strcmp(v, "auto") && strcmp(v, "on") && strcmp(v, "off")) {
                fprintf(stderr, "contact search: --dense expects auto, on or off, got '%s'\n", v);
                return EXIT_USAGE;
            }
            o.dense = !strcmp(v, "on") ? 1 : !strcmp(v, "off") ? -1 : 0;
        } else if (!strcmp(a, "--cells")) {
            if (!strcmp(v, "auto"))
                o.cells = 0;
            else if (parse_dbl(v, &o.cells) || !(o.cells > 0) || o.cells > 100) {
                fprintf(stderr, "contact search: --cells expects auto or a factor in (0, 100], got '%s'\n",
                        v);
                return EXIT_USAGE;
            }
        } else if (!strcmp(a, "--renumber-keep")) {
            if (!strcmp(v, "fresh"))
                o.renumber_keep = -1;
            else if (parse_i64(v, &iv) || iv < 1 || iv > 1000000) {
                fprintf(stderr,
                        "contact search: --renumber-keep expects 1..1000000 or fresh, got '%s'\n",
                        v);
                return EXIT_USAGE;
            } else
                o.renumber_keep = (int)iv;
        } else if (!strcmp(a, "--repeat")) {
            if (parse_i64(v, &iv) || iv < 1 || iv > 1000) {
                fprintf(stderr, "contact search: --repeat expects 1..1000, got '%s'\n", v);
                return EXIT_USAGE;
            }
            o.repeat = (int)iv;
        } else if (!strcmp(a, "--seed")) {
            if (parse_i64(v, &iv)) {
                fprintf(stderr, "contact search: --seed expects an integer >= 0, got '%s'\n", v);
                return EXIT_USAGE;
            }
            o.seed = (uint64_t)iv;
        } else if (!strcmp(a, "--threads")) {
            if (parse_i64(v, &iv) || iv < 1 || iv > 4096) {
                fprintf(stderr, "contact search: --threads expects 1..4096, got '%s'\n", v);
                return EXIT_USAGE;
            }
#ifdef _OPENMP
            omp_set_num_threads((int)iv);
#endif
        } else {
            fprintf(stderr, "contact search: unknown option '%s' (try --help)\n", a);
            return EXIT_USAGE;
        }
    }
    ctd_print_provenance(stdout, "# ");
    return run_search(&o);
}

/* The sizes keep the direct references affordable: with two plates of
 * 10^5 nodes they took two minutes of the demo on 2 cores (the shuffled
 * one 90 s: the all-pairs loop reads the nodes at random); `contact
 * search` runs any size. */
static int cmd_demo(void)
{
    ctd_print_provenance(stdout, "# ");
    printf("\nContact search comparison: every search is checked pair for pair against\n"
           "the direct (all pairs) search; times are medians of 5 runs. Larger cases:\n"
           "contact search --family F --n N (--check off to skip the direct search).\n\n");
    search_opts cases[] = {
        {"folded", 20000, -1, CTD_NUM_NATURAL, -1, -1, 5, 1, CT_FILTER_HULL, 1, 0, 0, 0, 0},
        {"plates", 40000, -1, CTD_NUM_NATURAL, -1, -1, 5, 1, CT_FILTER_HULL, 1, 0, 0, 0, 0},
        {"plates", 40000, -1, CTD_NUM_SHUFFLED, -1, -1, 5, 1, CT_FILTER_HULL, 1, 0, 0, 0, 0},
        {"graded", 50000, -1, CTD_NUM_NATURAL, -1, -1, 5, 1, CT_FILTER_HULL, 1, 0, 0, 0, 0},
    };
    int worst = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int rc = run_search(&cases[i]);
        if (rc > worst)
            worst = rc;
        printf("\n");
    }
    return worst;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: contact <command> [options]\n"
               "  info      build provenance and machine topology\n"
               "  search    run and verify the contact searches on a synthetic case\n"
               "  demo      the search comparison on a self-contact sheet and two plates\n"
               "  run       run a scene: contact run SCENE [--out DIR] [--threads N] ...\n"
               "  check     validate a scene (file, model, first step) without running it\n"
               "Run `contact <command> --help` for a command's options.\n");
}

/* `contact check [options] SCENE` (run.c). */
static int cmd_check(int argc, char **argv) { return ctd_check_cli(argc, argv); }

/* The arguments of a command that takes none but --help (info, demo):
 * prints `help` and returns 0 for --help or -h anywhere, returns 1 (bad
 * usage) naming the first other argument, and -1 when there is none (run
 * the command). An unknown option used to be ignored: `contact demo
 * --quick` started the full demo, minutes long, and exited 0. */
static int no_options(const char *cmd, int argc, char **argv, const char *help)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(help, stdout);
            return 0;
        }
    if (argc > 0) {
        fprintf(stderr, "contact %s: unknown %s '%s' (try --help)\n", cmd,
                argv[0][0] == '-' ? "option" : "argument", argv[0]);
        return EXIT_USAGE;
    }
    return -1;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(cmd, "info")) {
        int code = no_options("info", argc - 2, argv + 2,
                              "usage: contact info\nPrints build provenance and the hwloc "
                              "machine summary.\n");
        if (code >= 0)
            return code;
        ctd_print_provenance(stdout, "");
        return 0;
    }
    if (!strcmp(cmd, "search"))
        return cmd_search(argc - 2, argv + 2);
    if (!strcmp(cmd, "run"))
        return ctd_run_main(argc - 2, argv + 2);
    if (!strcmp(cmd, "check"))
        return cmd_check(argc - 2, argv + 2);
    if (!strcmp(cmd, "demo")) {
        int code = no_options("demo", argc - 2, argv + 2,
                              "usage: contact demo\nRuns `contact search` on a folded sheet, "
                              "two plates (natural and shuffled numbering) and a graded "
                              "mesh.\n");
        if (code >= 0)
            return code;
        return cmd_demo();
    }
    fprintf(stderr, "contact: unknown command '%s'\n", cmd);
    usage(stderr);
    return EXIT_USAGE;
}
