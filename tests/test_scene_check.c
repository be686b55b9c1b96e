/*
 * test_scene_check.c -- `contact check` and the run's report on scene files
 * (suite scene): the summary and first time step (against the bar's
 * analytic step), the initial penetrations, --file-only, the output
 * directory, the bench's scene and the self-contact gap note. The scene
 * files are in tests/data/scenes/ and data/scenes/.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "output.h"
#include "run.h"
#include "scene.h"
#include "solver.h"
#include "test_util.h"

#include <criterion/redirect.h>

#include "test_scene.h"

/* `contact check` on a scene (relative to tests/data/scenes) prints its
 * path followed by `line`, then the first time step: positive, and the
 * cycles it announces are end_time / step. Returns the step. */
static double expect_check_line(const char *name, const char *line)
{
    char p[1024];
    scene_path(p, sizeof p, name);
    cr_assert_eq(ctd_check_main(p, 0, NULL), CTD_EXIT_OK);
    fflush(stdout);
    char want[1200], got[1200], got2[1200];
    FILE *f = cr_get_redirected_stdout();
    cr_assert_not_null(fgets(got, sizeof got, f));
    snprintf(want, sizeof want, "%s: %s\n", p, line);
    cr_assert_str_eq(got, want);
    cr_assert_not_null(fgets(got2, sizeof got2, f));
    size_t n = strlen(p);
    cr_assert_eq(strncmp(got2, p, n), 0, "%s", got2);
    double dt, cycles, end;
    long long limit;
    char why[160];
    cr_assert_eq(sscanf(got2 + n, ": first time step %lg s (%159[^)]), about %lg cycles to "
                        "end_time %lg (cycle_limit %lld)", &dt, why, &cycles, &end, &limit),
                 5, "%s", got2);
    cr_assert(!strcmp(why, "output.every") || !strncmp(why, "the stable step x dt_scale ", 27),
              "%s", got2);
    cr_assert(dt > 0 && dt < end, "%s", got2);
    cr_assert_float_eq(cycles, end / dt, 1e-3 * cycles, "%s", got2);
    cr_assert_eq(limit, CTD_CYCLE_LIMIT);
    /* Then one line per interface and the initial penetrations. */
    int ninterface = 0;
    while (fgets(got2, sizeof got2, f) && strstr(got2, ": interface "))
        ninterface++;
    if (ninterface)
        cr_assert_not_null(strstr(got2, ": initial penetration: "), "%s", got2);
    cr_assert_null(fgets(got2, sizeof got2, f), "one line too many: %s", got2);
    return dt;
}

/* The check reports the nodes that start within their gap: the block's
 * bottom face, 0.4 mm over the plate, with a 1 mm gap: 4 nodes at 0.6 mm
 * (by hand). Lifted to 1.1 mm, none. */
Test(scene, check_reports_initial_penetration, .init = cr_redirect_stdout)
{
    char p[1024];
    scene_path(p, sizeof p, "check_initial_pen.yaml");
    cr_assert_eq(ctd_check_main(p, 0, NULL), CTD_EXIT_OK);
    fflush(stdout);
    FILE *f = cr_get_redirected_stdout();
    char line[1200];
    for (int k = 0; k < 2; k++)
        cr_assert_not_null(fgets(line, sizeof line, f));
    size_t n = strlen(p);
    cr_assert_not_null(fgets(line, sizeof line, f));
    cr_assert_eq(strncmp(line, p, n), 0, "%s", line);
    const char *iface = ": interface drop (type 24): 4 pairs in contact at t = 0, stable step ";
    cr_assert_eq(strncmp(line + n, iface, strlen(iface)), 0, "%s", line);
    cr_assert_not_null(fgets(line, sizeof line, f));
    long long count, node;
    double pmax;
    int part;
    cr_assert_eq(sscanf(line + n, ": initial penetration: %lld nodes within the gap at t = 0, "
                        "the deepest %lg at node %lld (part %d)", &count, &pmax, &node, &part),
                 4, "%s", line);
    cr_assert_eq(count, 4);
    cr_assert_float_eq(pmax, 0.0006, 1e-4 * 0.0006, "%s", line);
    cr_assert(node >= 5 && node <= 12 && part == 2, "%s", line);
}

/* The run's report says it too (from its cycle 0). */
Test(scene, run_reports_initial_penetration, .init = cr_redirect_stdout)
{
    char p[1024], out[256];
    scene_path(p, sizeof p, "check_initial_pen.yaml");
    snprintf(out, sizeof out, "/tmp/ct_pen_run_%ld", (long)getpid());
    char *argv[] = {p, "--out", out, "--end", "1e-7"};
    cr_assert_eq(ctd_run_main(5, argv), CTD_EXIT_OK);
    fflush(stdout);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", out);
    cr_assert_eq(system(cmd), 0);
    FILE *f = cr_get_redirected_stdout();
    char line[1200];
    const char *want = "  initial penetration: 4 nodes within the gap at t = 0, the deepest "
                       "0.0006 at node ";
    int found = 0;
    while (fgets(line, sizeof line, f))
        found += strncmp(line, want, strlen(want)) == 0;
    cr_assert_eq(found, 1);
}

Test(scene, check_reports_no_initial_penetration, .init = cr_redirect_stdout)
{
    static const char *text =
        "end_time: 2.0e-6\nmesh:\n"
        "  - generate: {kind: plate, part: 1, cells: [1, 1], size: [0.04, 0.04], origin: [-0.02, -0.02, 0]}\n"
        "  - generate: {kind: block, part: 2, cells: [1, 1, 1], size: [0.01, 0.01, 0.01], origin: [-0.005, -0.005, 0.0011]}\n"
        "parts:\n"
        "  - {id: 1, element: rigid, thickness: 0.002, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
        "  - {id: 2, element: brick, material: {E: 1.0e8, nu: 0.3, rho: 2000}}\n"
        "interfaces:\n"
        "  - {type: 24, name: drop, main: {part: 1}, secondary: {part: 2}, gap: 0.001}\n";
    char p[256];
    write_scene_text(p, sizeof p, "nopen", text);
    int rc = ctd_check_main(p, 0, NULL);
    unlink(p);
    cr_assert_eq(rc, CTD_EXIT_OK);
    fflush(stdout);
    FILE *f = cr_get_redirected_stdout();
    char line[1200], want[1200];
    for (int k = 0; k < 4; k++)
        cr_assert_not_null(fgets(line, sizeof line, f));
    snprintf(want, sizeof want, "%s: initial penetration: none (no node within its gap at t = 0)\n",
             p);
    cr_assert_str_eq(line, want);
}

/* --file-only reads the file and nothing more: a scene whose interface
 * selects nothing passes it (one line, the summary) and fails the full
 * check. */
Test(scene, check_file_only_reads_the_file_only, .init = cr_redirect_stdout)
{
    char p[1024];
    scene_path(p, sizeof p, "iface_empty_main.yaml");
    cr_assert_eq(ctd_check_main(p, 1, NULL), CTD_EXIT_OK);
    fflush(stdout);
    char want[1200];
    snprintf(want, sizeof want, "%s: ok: \"empty main\", end_time 1e-05, 2 meshes (36 nodes), "
             "2 parts, 0 rigid bodies, 0 boundary conditions, 1 interface, output to "
             "out/iface_empty_main\n", p);
    cr_assert_stdout_eq_str(want);
}

/* The check refuses the output directories the run would refuse (exit 5,
 * the run's message), creating nothing: --out naming a file, --out under a
 * file, the scene's output.dir naming a file; and passes a missing
 * directory two levels below an existing one (the run creates both),
 * creating neither. */
Test(scene, check_refuses_an_unusable_output_directory, .init = cr_redirect_stderr)
{
    char bar[1024], file[256], missing[256], deep[300], p[256], text[600];
    scene_path(bar, sizeof bar, "../../../data/scenes/bar-wave.yaml");
    snprintf(file, sizeof file, "/tmp/ct_outfile_%ld", (long)getpid());
    snprintf(missing, sizeof missing, "/tmp/ct_outdir_%ld", (long)getpid());
    snprintf(deep, sizeof deep, "%s/sub", file);
    FILE *f = fopen(file, "w");
    cr_assert_not_null(f);
    fclose(f);
    rmdir(missing);
    FILE *o = freopen("/dev/null", "w", stdout);
    cr_assert_not_null(o);
    int rc_file = ctd_check_main(bar, 0, file);
    int rc_deep = ctd_check_main(bar, 0, deep);
    char two[300];
    snprintf(two, sizeof two, "%s/sub", missing);
    int rc_new = ctd_check_main(bar, 0, two);
    struct stat st;
    int created = stat(missing, &st) == 0;
    snprintf(text, sizeof text,
             "end_time: 1.0e-5\noutput: {dir: %s}\nmesh:\n"
             "  - generate: {kind: block, part: 1, cells: [1, 1, 1], size: [0.1, 0.1, 0.1]}\n"
             "parts:\n  - {id: 1, element: brick, material: {E: 1.0e6, nu: 0.3, rho: 1000}}\n",
             file);
    write_scene_text(p, sizeof p, "outfile", text);
    int rc_scene = ctd_check_main(p, 0, NULL);
    int rc_scene_out = ctd_check_main(p, 0, missing); /* --out wins */
    unlink(p);
    unlink(file);
    rmdir(missing);
    cr_assert_eq(rc_file, CTD_EXIT_OUTPUT);
    cr_assert_eq(rc_deep, CTD_EXIT_OUTPUT);
    cr_assert_eq(rc_new, CTD_EXIT_OK);
    cr_assert_not(created, "the check created %s", missing);
    cr_assert_eq(rc_scene, CTD_EXIT_OUTPUT);
    cr_assert_eq(rc_scene_out, CTD_EXIT_OK);
    fflush(stderr);
    char want[1400];
    snprintf(want, sizeof want,
             "contact check: output path is not a directory '%s': Not a directory\n"
             "contact check: cannot use output directory '%s': Not a directory\n"
             "contact check: output path is not a directory '%s': Not a directory\n",
             file, deep, file);
    cr_assert_stderr_eq_str(want);
}

/* The check's first step against the bar's analytic one: 100 trusses of
 * 1 cm, c = sqrt(E/rho), the stable step 0.9 L/c, evened out as the run
 * does to reach end_time in whole steps: end / ceil(end / (0.9 L/c))
 * (printed to 4 digits, 0.13 % below the stable step here). */
Test(scene, check_step_is_the_bars_analytic_step, .init = cr_redirect_stdout)
{
    double dt = expect_check_line("../../../data/scenes/bar-wave.yaml", "ok: \"bar wave\", end_time 0.00015417, 1 mesh (101 nodes), 1 part, 0 rigid bodies, 1 boundary condition, 0 interfaces, output to out/bar-wave");
    const double end = 1.5417e-4, stable = 0.9 * 0.01 / sqrt(2.1e11 / 7800);
    double want = end / ceil(end / stable);
    cr_assert_float_eq(dt, want, 4e-4 * want, "step %g, expected %g", dt, want);
}

/* The bench's wide folding sheet (bench/bench_scene.c) starts with no node
 * within its gap, as the scene it widens; refining that scene ten times
 * instead makes cells of 0.5 mm under the 1 mm gap, and the check says that
 * every node starts within the gap of its neighbours' segments. */
Test(scene, bench_scene_starts_out_of_contact, .init = cr_redirect_stdout)
{
    char p[1024], q[1024], q0[256];
    scene_path(p, sizeof p, "../../../bench/scenes/folding-sheet-wide.yaml");
    scene_path(q, sizeof q, "../../../data/scenes/folding-sheet.yaml");
    write_scene_without_irem(q0, sizeof q0, "no_irem", q);
    cr_assert_eq(ctd_check_main(p, 0, "/tmp"), CTD_EXIT_OK);
    char *argv[] = {q0, "--refine", "10", "--out", "/tmp"};
    cr_assert_eq(ctd_check_cli(5, argv), CTD_EXIT_OK);
    argv[0] = q;
    cr_assert_eq(ctd_check_cli(5, argv), CTD_EXIT_OK);
    remove(q0);
    fflush(stdout);
    FILE *f = cr_get_redirected_stdout();
    char line[1400], want[1200];
    int summary = 0, none = 0, all = 0, irem = 0;
    snprintf(want, sizeof want, "%s: ok: \"folding sheet, wide\", end_time 0.001, 1 mesh (10086 nodes)", p);
    while (fgets(line, sizeof line, f)) {
        summary += !strncmp(line, want, strlen(want));
        none += strstr(line, "initial penetration: none") == line + strlen(p) + 2;
        all += strstr(line, ": initial penetration: 11931 nodes within the gap at t = 0") ==
               line + strlen(q0);
        irem += strstr(line, ": initial penetration: none") == line + strlen(q);
    }
    cr_expect_eq(summary, 1, "no summary line \"%s\"", want);
    cr_expect_eq(none, 1, "the wide sheet starts in contact");
    /* Without Irem_gap, the sheet refined 10 times starts with every node
     * in the gap of its neighbours; the scene's Irem_gap 2 takes them out. */
    cr_expect_eq(all, 1, "the sheet refined 10 times does not start with every node in its gap");
    cr_expect_eq(irem, 1, "with Irem_gap 2 the sheet refined 10 times starts in contact");
}

/* The bench's contact-heavy sheet (bench/scenes/folding-sheet-contact.yaml,
 * layers 1.5 mm apart under a 1 mm gap) checks out and starts with no node
 * within its gap: its rows time contact, not an initial overlap. */
Test(scene, bench_contact_scene_checks_out, .init = cr_redirect_stdout)
{
    char p[1024];
    scene_path(p, sizeof p, "../../../bench/scenes/folding-sheet-contact.yaml");
    cr_assert_eq(ctd_check_main(p, 0, "/tmp"), CTD_EXIT_OK);
    fflush(stdout);
    FILE *f = cr_get_redirected_stdout();
    char line[1400];
    int none = 0, nodes = 0;
    while (fgets(line, sizeof line, f)) {
        none += strstr(line, ": initial penetration: none") != NULL;
        nodes += strstr(line, "1 mesh (9922 nodes)") != NULL;
    }
    cr_expect_eq(nodes, 1, "not the 9922 nodes of the sheet (its folds closer)");
    cr_expect_eq(none, 1, "the contact-heavy sheet starts with nodes within its gap");
}

/* A self-contact gap above half the shortest segment edge gets a note in
 * the check and in the run's report (Radioss's warning 94): the folding
 * sheet (gap 1 mm, cells of 5 mm / refine; without its Irem_gap, whose
 * note tests/test_irem_gap.c reads) has none at refine 2, one at refine 3
 * (its shortest edge a bend's chord, 2 r sin(du / 2 r) with du the
 * section's spacing: 1.656 mm), and at refine 5 its cells (1 mm) are under
 * the gap: neighbours are in contact from the start. */
Test(scene, self_contact_gap_note, .init = cr_redirect_stdout)
{
    char q0[1024], q[256];
    scene_path(q0, sizeof q0, "../../../data/scenes/folding-sheet.yaml");
    write_scene_without_irem(q, sizeof q, "note", q0);
    const char *refine[3] = {"2", "3", "5"};
    for (int k = 0; k < 3; k++) {
        char *argv[] = {q, "--refine", (char *)refine[k], "--out", "/tmp"};
        cr_assert_eq(ctd_check_cli(5, argv), CTD_EXIT_OK);
    }
    char dir[] = "/tmp/ct_scene_note_XXXXXX", out[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(out, sizeof out, "%s/out", dir);
    char *argv[] = {q, "--refine", "5", "--end", "1e-7", "--out", out};
    cr_assert_eq(ctd_run_main(7, argv), CTD_EXIT_OK);
    fflush(stdout);
    /* The section: 3 flat layers of 8 cells and 2 half-circle bends of
     * radius 4 mm, its points round(length / h) + 1 evenly spaced. */
    const double r = 0.004, len = 3 * 8 * 0.005 + 2 * 3.14159265358979323846 * r;
    const double h3 = 0.005 / 3, du = len / round(len / h3), chord = 2 * r * sin(du / (2 * r));
    char want3[128];
    snprintf(want3, sizeof want3, "shortest edge (%g): a node comes", chord);
    FILE *f = cr_get_redirected_stdout();
    char line[2048];
    int notes = 0, compressed = 0, start = 0, edges = 0, report = 0, shortest = 0;
    while (fgets(line, sizeof line, f)) {
        if (!strstr(line, "note: "))
            continue;
        notes++;
        compressed += strstr(line, "when the segments between are compressed") != NULL;
        start += strstr(line, "from the start") != NULL;
        edges += strstr(line, "interface edges (type 11): note: self contact of edges with a "
                              "gap of 0.001, more than half the shortest edge") != NULL;
        report += !strncmp(line, "    note: self contact with a gap of 0.001", 42);
        shortest += strstr(line, want3) != NULL;
    }
    /* refine 3 and 5: TYPE7 and TYPE11 each, in the check; refine 5 in
     * the run's report too. */
    cr_expect_eq(notes, 6, "%d notes", notes);
    cr_expect_eq(compressed, 2);
    cr_expect_eq(start, 4);
    cr_expect_eq(edges, 2);
    cr_expect_eq(report, 1);
    cr_expect_eq(shortest, 1, "no note with \"%s\"", want3);
    remove(q);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0);
}

Test(scene, check_main_valid, .init = cr_redirect_stdout)
{
    expect_check_line("valid.yaml", "ok: \"ball on plate\", end_time 0.01, 3 meshes (611 nodes), 3 parts, 1 rigid body, 4 boundary conditions, 4 interfaces, output to out/valid");
}

/* A rigid part listed in no rigid_bodies entry is a body of its own, and
 * the check counts it as the model will (the knee-bolster scene has two
 * such parts and no list). */
Test(scene, check_main_counts_unlisted_rigid_parts, .init = cr_redirect_stdout)
{
    expect_check_line("../../../data/scenes/knee-bolster.yaml", "ok: \"knee bolster\", end_time 0.045, 2 meshes (467 nodes), 2 parts, 2 rigid bodies, 2 boundary conditions, 1 interface, output to out/knee-bolster");
}
