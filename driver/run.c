/*
 * run.c -- `contact run` and `contact check` (run.h): options, scene,
 * model, interfaces, solver.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "output.h"
#include "run.h"
#include "scene.h"
#include "solver.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: contact run SCENE [--out DIR] [--threads N] [--search ALGO] [--end T]\n"
            "                         [--dt-scale S] [--refine N] [--cycle-limit N] [--quiet]\n"
            "Runs a scene (YAML, see `contact check`) with the explicit solver and writes\n"
            "a VTU/PVD series, history.csv, summary.json and energies.png.\n"
            "  --out DIR       output directory, created if missing (default: the scene's\n"
            "                  output.dir)\n"
            "  --threads N     OpenMP threads (default: solver.threads or OpenMP's default)\n"
            "  --search ALGO   direct | topological | bucket | bsp: every interface's search\n"
            "                  (self contact keeps its own under topological; TYPE11 runs\n"
            "                  bucket for any but direct)\n"
            "  --end T         end time in seconds (default: the scene's end_time)\n"
            "  --refine N      multiply every generated mesh's cells by N (1..1000),\n"
            "                  replacing the scene's refine\n"
            "  --dt-scale S    safety factor on the stable time step (default: the scene's;\n"
            "                  values above 1 are allowed here, for experiments)\n"
            "  --cycle-limit N the most cycles the run may need (default: the scene's\n"
            "                  solver.cycle_limit, 1e8): a step too small to reach the end\n"
            "                  within it is an error (exit 2), not a run of days\n"
            "  --quiet         no progress line and no report\n"
            "Exit codes: 0 success, 1 bad usage, 2 bad input, 4 the run went unstable,\n"
            "5 an output file could not be written, or out of memory.\n");
}

static int parse_pos(const char *s, double *v)
{
    char *e;
    errno = 0;
    double x = strtod(s, &e);
    if (errno || e == s || *e || !(x > 0) || x > 1e300)
        return -1;
    *v = x;
    return 0;
}

/* What `run` and `check` both build: the scene, its model, the interfaces
 * and the solver (loads resolved; the output directory opened unless
 * o->no_output). */
typedef struct run_setup {
    ctd_scene *sc;
    ctd_model model;
    int have_model, have_solver;
    ctd_solver s;
} run_setup;

/* Load the scene (refine 0: the file's); print its errors on stderr.
 * Returns CTD_EXIT_OK, CTD_EXIT_BADINPUT or CTD_EXIT_OUTPUT (no memory). */
static int load_scene(const char *who, const char *scene, int64_t refine, ctd_scene **sc)
{
    *sc = NULL;
    ctd_scene_err *se = calloc(1, sizeof *se);
    if (!se) {
        fprintf(stderr, "%s: out of memory\n", who);
        return CTD_EXIT_OUTPUT;
    }
    int rc = ctd_scene_load_refined(scene, refine, sc, se);
    if (rc != CT_OK)
        ctd_scene_print_errors(stderr, scene, se);
    free(se);
    /* A scene too large for the memory is exit 5, as a model or a solver
     * that cannot have its arrays: the file is not wrong. */
    return rc == CT_OK ? CTD_EXIT_OK : rc == CT_ERR_NOMEM ? CTD_EXIT_OUTPUT : CTD_EXIT_BADINPUT;
}

/* Build everything; print what fails on stderr after `who`. Returns
 * CTD_EXIT_OK or the exit code (2 bad input, 5 an unusable output
 * directory or no memory). setup_close is due in every case. */
static int setup_open(run_setup *r, const char *who, const char *scene, int64_t refine,
                      const char *search, const ctd_solver_opts *o)
{
    memset(r, 0, sizeof *r);
    int code = load_scene(who, scene, refine, &r->sc);
    if (code != CTD_EXIT_OK)
        return code;
    if (search) {
        /* Every interface's search, but the topological search on self
         * contact: it would find nothing there (a node's closest main node
         * is itself), so those keep the scene's, and the run says so. */
        int algo = ct_search_algo_from_name(search);
        for (unsigned i = 0; i < r->sc->interfaces_count; i++) {
            ctd_scene_interface *f = &r->sc->interfaces[i];
            if (algo == CT_SEARCH_TOPO && (f->type == 7 || (f->type == 24 && f->self))) {
                if (!o->quiet)
                    printf("%s: --search topological: interface %s (type %lld) is self contact, "
                           "which the topological search cannot find; it keeps its %s search\n",
                           scene, f->label, (long long)f->type,
                           ct_search_algo_name((ct_search_algo)f->search));
                continue;
            }
            f->search = algo;
        }
    }
    /* Out of memory is exit 5, as for the scene and the solver's arrays
     * (a model too large for the machine is not a mistake in the file). */
    char err[1024] = "";
    int rc = ctd_model_build(&r->model, r->sc, err, sizeof err);
    if (rc != CT_OK) {
        fprintf(stderr, "%s: %s\n", who, err);
        return rc == CT_ERR_NOMEM ? CTD_EXIT_OUTPUT : CTD_EXIT_BADINPUT;
    }
    r->have_model = 1;
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    if (r->sc->interfaces_count &&
        (rc = ctd_interfaces_build(&r->model, r->sc, &hooks, &nhook, err, sizeof err)) != CT_OK) {
        fprintf(stderr, "%s: %s\n", who, err);
        return rc == CT_ERR_NOMEM ? CTD_EXIT_OUTPUT : CTD_EXIT_BADINPUT;
    }
    r->have_solver = 1; /* the solver owns the hooks from here, even on failure */
    if (ctd_solver_init(&r->s, &r->model, o, hooks, nhook, err, sizeof err)) {
        fprintf(stderr, "%s: %s\n", who, err);
        return r->s.exit_code == CTD_EXIT_BADINPUT ? CTD_EXIT_BADINPUT : CTD_EXIT_OUTPUT;
    }
    return CTD_EXIT_OK;
}

static void setup_close(run_setup *r)
{
    if (r->have_solver)
        ctd_solver_destroy(&r->s);
    if (r->have_model)
        ctd_model_destroy(&r->model);
    ctd_scene_free(r->sc);
}

/* The options `run` and `check` share, with the scene. */
typedef struct run_cli {
    const char *scene, *out, *search;
    double end, dts;
    int threads, quiet, file_only;
    int64_t refine, cycle_limit;
} run_cli;

/* Which options a command takes. */
enum { OPT_RUN = 1, OPT_CHECK = 2 };

/* Parse argv (the words after the command) into c for the command `who`
 * (mode OPT_RUN or OPT_CHECK; help prints its usage). Returns -1 to go on,
 * or the exit code: 0 after --help, CTD_EXIT_USAGE with the reason on
 * stderr. */
static int parse_cli(const char *who, int mode, int argc, char **argv, run_cli *c,
                     void (*help)(FILE *))
{
    memset(c, 0, sizeof *c);
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            help(stdout);
            return 0;
        }
        if (mode == OPT_RUN && !strcmp(a, "--quiet")) {
            c->quiet = 1;
            continue;
        }
        if (mode == OPT_CHECK && !strcmp(a, "--file-only")) {
            c->file_only = 1;
            continue;
        }
        if (a[0] != '-' || !a[1]) {
            if (c->scene) {
                fprintf(stderr, "%s: one scene expected, got '%s' and '%s'\n", who, c->scene, a);
                return CTD_EXIT_USAGE;
            }
            c->scene = a;
            continue;
        }
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) {
            fprintf(stderr, "%s: option %s needs a value (try --help)\n", who, a);
            return CTD_EXIT_USAGE;
        }
        i++;
        double x;
        if (!strcmp(a, "--out")) {
            c->out = v;
        } else if (!strcmp(a, "--search")) {
            if (ct_search_algo_from_name(v) < 0) {
                fprintf(stderr, "%s: --search expects direct, topological, bucket or bsp, got "
                                "'%s'\n", who, v);
                return CTD_EXIT_USAGE;
            }
            c->search = v;
        } else if (!strcmp(a, "--end")) {
            if (parse_pos(v, &c->end)) {
                fprintf(stderr, "%s: --end expects a time > 0, got '%s'\n", who, v);
                return CTD_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--dt-scale")) {
            if (parse_pos(v, &c->dts)) {
                fprintf(stderr, "%s: --dt-scale expects a number > 0, got '%s'\n", who, v);
                return CTD_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--refine")) {
            if (parse_pos(v, &x) || x != (int)x || x > 1000) {
                fprintf(stderr, "%s: --refine expects an integer in 1..1000, got '%s'\n", who,
                        v);
                return CTD_EXIT_USAGE;
            }
            c->refine = (int64_t)x;
        } else if (!strcmp(a, "--cycle-limit")) {
            if (parse_pos(v, &x) || x > 1e15 || x != (double)(int64_t)x) {
                fprintf(stderr, "%s: --cycle-limit expects an integer in 1..1e15, got '%s'\n",
                        who, v);
                return CTD_EXIT_USAGE;
            }
            c->cycle_limit = (int64_t)x;
        } else if (mode == OPT_RUN && !strcmp(a, "--threads")) {
            if (parse_pos(v, &x) || x != (int)x || x > 4096) {
                fprintf(stderr, "%s: --threads expects an integer in 1..4096, got '%s'\n", who,
                        v);
                return CTD_EXIT_USAGE;
            }
            c->threads = (int)x;
        } else {
            fprintf(stderr, "%s: unknown option '%s' (try --help)\n", who, a);
            return CTD_EXIT_USAGE;
        }
    }
    if (!c->scene) {
        help(stderr);
        return CTD_EXIT_USAGE;
    }
    return -1;
}

/* The solver options of the command line's values (0: the scene's). */
static ctd_solver_opts cli_solver_opts(const run_cli *c)
{
    ctd_solver_opts o = ctd_solver_default_opts();
    o.end_time = c->end;
    o.dt_scale = c->dts;
    o.cycle_limit = c->cycle_limit;
    o.threads = c->threads;
    o.out_dir = c->out;
    o.quiet = c->quiet;
    return o;
}

int ctd_run_main(int argc, char **argv)
{
    run_cli c;
    int code = parse_cli("contact run", OPT_RUN, argc, argv, &c, usage);
    if (code >= 0)
        return code;
    ctd_solver_opts o = cli_solver_opts(&c);
    run_setup r;
    code = setup_open(&r, "contact run", c.scene, c.refine, c.search, &o);
    if (code == CTD_EXIT_OK) {
        code = ctd_solver_run(&r.s);
        if (code != CTD_EXIT_OK)
            fprintf(stderr, "contact run: %s: %s\n", r.s.status, r.s.message);
    }
    setup_close(&r);
    return code;
}

/* What the interfaces found in the dry cycle: per interface its pairs in
 * contact and its stable step; then the nodes within their gap at the
 * start (initial penetrations, the usual cause of a violent first cycle). */
static void print_contact_at_start(const char *scene, const ctd_solver *s)
{
    for (int i = 0; i < s->nhook; i++) {
        const ctd_contact_report *r = &s->rep[i];
        char step[64] = "no step limit";
        if (r->dt_limit > 0 && r->dt_limit < CTD_DT_NONE)
            snprintf(step, sizeof step, "stable step %.4g s", r->dt_limit);
        char excl[96] = "";
        if (r->excluded > 0)
            snprintf(excl, sizeof excl, ", %lld neighbour pair%s excluded (Irem_gap 2)",
                     (long long)r->excluded, r->excluded == 1 ? "" : "s");
        char margin[64] = "";
        if (r->margin > 0)
            snprintf(margin, sizeof margin, ", re-sort margin %.3g", r->margin);
        printf("%s: interface %s (type %d): %lld pair%s in contact at t = 0, %s%s%s\n", scene,
               s->hooks[i].name ? s->hooks[i].name : "?", s->hooks[i].type,
               (long long)r->active, r->active == 1 ? "" : "s", step, excl, margin);
        if (s->hooks[i].note[0])
            printf("%s: interface %s (type %d): note: %s\n", scene,
                   s->hooks[i].name ? s->hooks[i].name : "?", s->hooks[i].type,
                   s->hooks[i].note);
    }
    char prefix[1100];
    snprintf(prefix, sizeof prefix, "%s: ", scene);
    ctd_solver_print_penetration(stdout, prefix, s);
}

/* `contact check` on the parsed command line. */
static int check_cli(const run_cli *c)
{
    const char *scene = c->scene;
    if (c->file_only) {
        ctd_scene *sc;
        int code = load_scene("contact check", scene, c->refine, &sc);
        if (code == CTD_EXIT_OK)
            ctd_scene_print_summary(stdout, scene, sc);
        ctd_scene_free(sc);
        return code;
    }
    ctd_solver_opts o = cli_solver_opts(c);
    o.out_dir = NULL;
    o.no_output = 1;
    o.quiet = 1;
    o.progress = 0;
    o.dry = 1;
    run_setup r;
    int code = setup_open(&r, "contact check", scene, c->refine, c->search, &o);
    if (code == CTD_EXIT_OK) {
        code = ctd_solver_run(&r.s);
        char err[1200];
        if (code != CTD_EXIT_OK) {
            fprintf(stderr, "contact check: %s: %s\n", r.s.status, r.s.message);
        } else if (ctd_output_check_dir(c->out ? c->out : r.sc->out_dir, err, sizeof err) !=
                   CT_OK) {
            /* What the run's first step would refuse, found creating nothing. */
            fprintf(stderr, "contact check: %s\n", err[0] ? err : "out of memory");
            code = CTD_EXIT_OUTPUT;
        } else {
            ctd_scene_print_summary(stdout, scene, r.sc);
            const ctd_solver *s = &r.s;
            char why[160];
            int n = s->dt_by_output
                        ? snprintf(why, sizeof why, "output.every")
                        : snprintf(why, sizeof why, "the stable step x dt_scale %g", s->dt_scale);
            /* The run evens the step out to land on end_time in equal
             * steps: said when it shows in the digits printed. */
            char a[32], b[32];
            snprintf(a, sizeof a, "%.4g", s->dt);
            snprintf(b, sizeof b, "%.4g", s->dt_max);
            if (strcmp(a, b) && n > 0 && (size_t)n < sizeof why)
                snprintf(why + n, sizeof why - (size_t)n, " = %s, evened out to end on end_time",
                         b);
            printf("%s: first time step %.4g s (%s), about %.4g cycles to end_time %g "
                   "(cycle_limit %lld)\n", scene, s->dt, why, s->end_time / s->dt, s->end_time,
                   (long long)s->cycle_limit);
            print_contact_at_start(scene, s);
        }
    }
    setup_close(&r);
    return code;
}

int ctd_check_main(const char *scene, int file_only, const char *out)
{
    run_cli c;
    memset(&c, 0, sizeof c);
    c.scene = scene;
    c.file_only = file_only;
    c.out = out;
    return check_cli(&c);
}

static void check_usage(FILE *f)
{
    fprintf(f,
            "usage: contact check [--file-only] [--out DIR] [--search ALGO] [--end T]\n"
            "                     [--dt-scale S] [--refine N] [--cycle-limit N] SCENE\n"
            "Validates a scene: reads the file (every error names the file, the line and the "
            "field),\nbuilds the model, the interfaces and the loads, and computes the first "
            "cycle's forces and\nstable step, as `contact run` would, without writing anything; "
            "then checks that the run\ncould create and write its output directory. Prints the "
            "step, the cycles the run would\nneed, each interface's pairs in contact at t = 0 "
            "and the nodes within their gap at t = 0\n(initial penetrations).\n"
            "  --file-only  read and validate the file only (no model, no output directory: "
            "quick on\n               any size)\n"
            "  --out DIR    the output directory `contact run --out DIR` would use (default: "
            "the\n               scene's output.dir)\n"
            "  --search, --end, --dt-scale, --refine, --cycle-limit: as for `contact run`, "
            "so that the\n               step, the cycles and the contact at t = 0 are those "
            "of that run\n"
            "Exit codes: 0 valid, 1 bad usage, 2 bad input, 4 the first cycle's forces or step "
            "are not\nfinite, 5 an output directory the run could not create or write, or out "
            "of memory.\n");
}

int ctd_check_cli(int argc, char **argv)
{
    run_cli c;
    int code = parse_cli("contact check", OPT_CHECK, argc, argv, &c, check_usage);
    return code >= 0 ? code : check_cli(&c);
}
