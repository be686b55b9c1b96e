/*
 * test_irem_gap.c -- Irem_gap 2 in whole runs (TYPE7 and TYPE11): a fine
 * sheet whose cells are smaller than the gap, stretched so that it is
 * searched again and again, never touches itself with the neighbour
 * exclusion (TYPE7 and TYPE11, TYPE24 on one surface) and does without it; a
 * fine accordion fold still stops its thrown layer on the clamped one (the
 * facing layer is no neighbour); the field's bad values are refused with
 * their line.
 */
#include "test_scene_features.h"

#include "interfaces/iface.h"
#include "meshgen.h"
#include "run.h"
#include "test_scene.h"

#include <criterion/redirect.h>

/* A steel shell sheet of 26 x 26 cells of 0.4 mm, its x edges pulled apart
 * at 10 m/s; the gap (1 mm, 2.5 cells) takes in the neighbours of every
 * node; %s is the extra field of both interfaces. */
#define STRETCHED_SHEET                                                                        \
    "title: stretched fine sheet\n"                                                             \
    "end_time: %s\n"                                                                            \
    "mesh:\n"                                                                                   \
    "  - generate: {kind: plate, part: 1, cells: [26, 26], size: [0.0104, 0.0104]}\n"          \
    "parts:\n"                                                                                  \
    "  - {id: 1, element: shell, thickness: 0.001, " STEEL "}\n"                               \
    "boundary:\n"                                                                               \
    "  - {kind: velocity, nodes: {part: 1, where: \"x < 0.0001\"}, value: [-10, 0, 0], "       \
    "dofs: x}\n"                                                                                \
    "  - {kind: velocity, nodes: {part: 1, where: \"x > 0.0103\"}, value: [10, 0, 0], "        \
    "dofs: x}\n"                                                                                \
    "interfaces:\n"
static const char *stretched_sheet =
    STRETCHED_SHEET "  - {type: 7, name: self, main: {part: 1}, gap: 0.001%s}\n"
                    "  - {type: 11, name: edges, main: {part: 1}, gap: 0.001%s}\n";
/* TYPE24 on one surface: its gap is the shells' half thicknesses, 1 mm. */
static const char *stretched_sheet_24 =
    STRETCHED_SHEET "  - {type: 24, name: self, main: {part: 1}%s}\n%s";

typedef struct contact_watch {
    int64_t active_max[2];
} contact_watch;

static void watch_contact(void *ctx, const ctd_solver *s)
{
    contact_watch *w = ctx;
    for (int i = 0; i < s->nhook && i < 2; i++)
        if (s->rep[i].active > w->active_max[i])
            w->active_max[i] = s->rep[i].active;
}

static void run_stretched(const char *scene, const char *end, const char *extra,
                          contact_watch *w, int64_t resorts[2], int64_t excluded[2])
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml, scene, end, extra, scene == stretched_sheet ? extra : "");
    sf_run r;
    sf_load(&r, yaml);
    memset(w, 0, sizeof *w);
    resorts[1] = excluded[1] = 0;
    sf_solve(&r, watch_contact, w, 2);
    for (int i = 0; i < r.s.nhook; i++) {
        resorts[i] = r.s.rep[i].resorts;
        excluded[i] = r.s.rep[i].excluded;
    }
    sf_free(&r);
}

Test(irem_gap, stretched_fine_sheet_never_touches_itself)
{
    contact_watch with, without;
    int64_t rs[2], ex[2], rs0[2], ex0[2];
    run_stretched(stretched_sheet, "5.0e-5", ", Irem_gap: 2", &with, rs, ex);
    /* Without: a few cycles (the neighbours' contact soon drives the step
     * down to nothing). */
    run_stretched(stretched_sheet, "1.0e-6", "", &without, rs0, ex0);
    for (int i = 0; i < 2; i++) {
        /* Searched again as the sheet stretched: the exclusion holds
         * across re-sorts. */
        cr_assert_gt(rs[i], 2, "interface %d: %lld searches", i, (long long)rs[i]);
        cr_assert_eq(with.active_max[i], 0, "interface %d: %lld pairs in contact", i,
                     (long long)with.active_max[i]);
        cr_assert_gt(ex[i], 0);
        /* Without it, every node is within the gap of its neighbours. */
        cr_assert_gt(without.active_max[i], 0, "interface %d", i);
        cr_assert_eq(ex0[i], 0);
    }
}

Test(irem_gap, stretched_fine_sheet_type24)
{
    contact_watch with, without;
    int64_t rs[2], ex[2], rs0[2], ex0[2];
    run_stretched(stretched_sheet_24, "5.0e-5", ", Irem_gap: 2", &with, rs, ex);
    run_stretched(stretched_sheet_24, "1.0e-6", "", &without, rs0, ex0);
    cr_assert_gt(rs[0], 2, "%lld searches", (long long)rs[0]);
    cr_assert_eq(with.active_max[0], 0, "%lld pairs in contact", (long long)with.active_max[0]);
    cr_assert_gt(ex[0], 0);
    cr_assert_gt(without.active_max[0], 0);
    cr_assert_eq(ex0[0], 0);
}

/* A three-layer accordion (the folding-sheet scene one cell wide; at
 * refine 3, cells of 1.67 mm under a 2 mm gap), the bottom layer clamped,
 * the top one (16 mm up) thrown down at 20 m/s onto the middle one. The
 * step is a quarter of the stable one, so that the scheme's own energy
 * error (second order: -0.78 %, -0.26 %, -0.05 % at dt_scale 0.5, 0.25,
 * 0.125, most of it the edge contact's stiffening law) stays well under
 * the bound the exclusion is held to. (At 0.5 the bound held only while
 * TYPE11 booked 10 % more damping than its forces did, which hid that
 * error: -0.11 %.) */
static const char *fine_fold =
    "title: fine fold\n"
    "end_time: 1.0e-3\n"
    "solver: {dt_scale: 0.25}\n"
    "mesh:\n"
    "  - generate: {kind: folded, part: 1, cells: [8, 1], size: [0.005], layers: 3, "
    "spacing: 0.008}\n"
    "parts:\n"
    "  - {id: 1, element: shell, thickness: 0.001, " STEEL "}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {part: 1, where: \"y < 0.0001\"}}\n"
    "  - {kind: initial_velocity, nodes: {part: 1, where: \"y > 0.0159\"}, "
    "value: [0, -20, 0]}\n"
    "interfaces:\n"
    "  - {type: 7, name: self, main: {part: 1}, gap: 0.002, Irem_gap: 2}\n"
    "  - {type: 11, name: edges, main: {part: 1}, gap: 0.002, Irem_gap: 2}\n";

typedef struct fold_watch {
    /* Per node of the thrown layer's flat part, the middle layer's two
     * nodes of the same z whose x bracket its x (-1: not such a node). */
    const ct_idx *b0, *b1;
    double sep; /* the least height over the middle layer, over the run */
    int64_t active_max;
} fold_watch;

static void watch_fold(void *ctx, const ctd_solver *s)
{
    fold_watch *w = ctx;
    for (int i = 0; i < s->nnode; i++) {
        const ct_idx j0 = w->b0[i], j1 = w->b1[i];
        if (j0 < 0)
            continue;
        double t = (s->x[i] - s->x[j0]) / (s->x[j1] - s->x[j0]);
        double d = s->y[i] - (s->y[j0] + t * (s->y[j1] - s->y[j0]));
        w->sep = d < w->sep ? d : w->sep;
    }
    if (s->rep[0].active > w->active_max)
        w->active_max = s->rep[0].active;
}

Test(irem_gap, fine_fold_still_stops_the_thrown_layer)
{
    sf_run r;
    sf_load_refined(&r, fine_fold, 3);
    const ct_nodes *nd = &r.m.mesh.nodes;
    ct_idx *b0 = malloc(sizeof *b0 * (size_t)nd->n), *b1 = malloc(sizeof *b1 * (size_t)nd->n);
    cr_assert(b0 && b1);
    /* The top layer's nodes above the middle layer's flat part, each with
     * the middle layer's nodes of the same z around its x (the layers'
     * nodes are spread evenly along the folded sheet, not above each
     * other). */
    int ntop = 0;
    for (ct_idx i = 0; i < nd->n; i++) {
        b0[i] = b1[i] = -1;
        if (!(nd->y[i] > 0.016 - 1e-9))
            continue;
        double lo = -1e300, hi = 1e300;
        for (ct_idx j = 0; j < nd->n; j++) {
            if (!(fabs(nd->y[j] - 0.008) < 1e-9 && fabs(nd->z[j] - nd->z[i]) < 1e-9))
                continue;
            if (nd->x[j] <= nd->x[i] && nd->x[j] > lo) {
                lo = nd->x[j];
                b0[i] = j;
            }
            if (nd->x[j] > nd->x[i] && nd->x[j] < hi) {
                hi = nd->x[j];
                b1[i] = j;
            }
        }
        if (b0[i] < 0 || b1[i] < 0)
            b0[i] = b1[i] = -1;
        else
            ntop++;
    }
    cr_assert_gt(ntop, 0);
    fold_watch w = {b0, b1, 1e300, 0};
    sf_solve(&r, watch_fold, &w, 2);
    /* The layers met: pairs across the fold carried force, and the thrown
     * layer never crossed the middle one. Were the facing layer's pairs
     * excluded, it would pass through: 20 m/s over 1 ms is 20 mm, more
     * than twice the spacing. */
    cr_assert_gt(w.active_max, 0);
    cr_assert_gt(w.sep, 0.0, "the thrown layer crossed the middle one (%g)", w.sep);
    /* And it came down from 8 mm to about the gap (the contact is made at
     * the distance along the normal, of tilted layers here). */
    cr_assert_lt(w.sep, 0.003, "the layers did not meet (closest %g)", w.sep);
    cr_assert_gt(r.s.rep[0].excluded, 0);
    cr_assert_gt(r.s.rep[1].excluded, 0);
    cr_assert_lt(fabs(r.s.error_max), 5e-3, "energy error %g", r.s.error_max);
    free(b0);
    free(b1);
    sf_free(&r);
}

Test(irem_gap, library_refuses_impossible_values)
{
    ct_mesh m;
    const double org[3] = {0, 0, 0};
    cr_assert_eq(ctd_plate(&m, 3, 3, 1.0, 1.0, org, 0), CT_OK);
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = m.nodes.n;
    d.nseg = m.nseg;
    d.n1 = m.n1;
    d.n2 = m.n2;
    d.n3 = m.n3;
    d.n4 = m.n4;
    d.K = (ct_real)1e6; /* a given stiffness: TYPE24 has no segment inputs here */
    /* TYPE24 on one surface (self 1) takes it, as Radioss's TYPE25 Igap 2;
     * with a secondary side (self 0) it has no neighbours to exclude. */
    const int type[6] = {7, 7, 24, 7, 24, 11}, irem[6] = {3, -1, 2, 2, 2, 2},
              self[6] = {1, 1, 0, 1, 1, 1};
    const int want[6] = {CT_ERR_ARG, CT_ERR_ARG, CT_ERR_ARG, CT_OK, CT_OK, CT_OK};
    for (int k = 0; k < 6; k++) {
        ctd_iface_cfg cfg = ctd_iface_default_cfg(type[k]);
        cfg.Istf = 1;
        cfg.gap = (ct_real)0.5;
        cfg.self = self[k];
        cfg.two_sided = 1;
        cfg.Irem_gap = irem[k];
        ctd_iface *it = NULL;
        ct_diag diag;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), want[k], "type %d Irem_gap %d",
                     type[k], irem[k]);
        if (want[k] != CT_OK)
            cr_assert(strstr(diag.msg, "Irem_gap") != NULL, "%s", diag.msg);
        ctd_iface_destroy(it);
    }
    ct_mesh_destroy(&m);
}

/* Distance from p to the axis-aligned square [x0, x0 + h] x [y0, y0 + h]
 * in the plane z = 0 (p in it too). */
static double square_dist(double px, double py, double x0, double y0, double h)
{
    double dx = px < x0 ? x0 - px : (px > x0 + h ? px - x0 - h : 0);
    double dy = py < y0 ? y0 - py : (py > y0 + h ? py - y0 - h : 0);
    return sqrt(dx * dx + dy * dy);
}

Test(irem_gap, check_counts_the_pairs_it_takes_out, .init = cr_redirect_stdout)
{
    /* The stretched sheet at rest: every pair (node, cell not its own)
     * within the gap (1 mm; cells of 0.4 mm, no distance within 1e-3 of
     * it) is a candidate of the first search and leaves it. */
    char yaml[2048], path[256];
    snprintf(yaml, sizeof yaml, stretched_sheet, "1.0e-6", ", Irem_gap: 2", ", Irem_gap: 2");
    write_scene_text(path, sizeof path, "irem", yaml);
    char *argv[] = {path, "--out", "/tmp"};
    cr_assert_eq(ctd_check_cli(3, argv), CTD_EXIT_OK);
    remove(path);
    fflush(stdout);
    const int n = 26;
    const double h = 0.0104 / n, gap = 0.001;
    int64_t want = 0;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            for (int cj = 0; cj < n; cj++)
                for (int ci = 0; ci < n; ci++) {
                    int own = (ci == i || ci == i - 1) && (cj == j || cj == j - 1);
                    double d = square_dist(i * h, j * h, ci * h, cj * h, h);
                    cr_assert_gt(fabs(d - gap), 1e-3 * gap);
                    want += !own && d <= gap;
                }
    char wanted[128];
    snprintf(wanted, sizeof wanted,
             "interface self (type 7): 0 pairs in contact at t = 0, no step limit, %lld "
             "neighbour pairs excluded (Irem_gap 2)",
             (long long)want);
    FILE *f = cr_get_redirected_stdout();
    char line[2048];
    int found = 0, edges = 0, note = 0, clean = 0;
    while (fgets(line, sizeof line, f)) {
        found += strstr(line, wanted) != NULL;
        edges += strstr(line, "interface edges (type 11): 0 pairs in contact") != NULL &&
                 strstr(line, "neighbour pairs excluded (Irem_gap 2)") != NULL;
        /* The shortest edge, 0.0004, prints 0.000399999 in single. */
        note += strstr(line, "note: self contact with a gap of 0.001, more than half the "
                             "shortest edge (") != NULL &&
                strstr(line, "): Irem_gap 2 takes") != NULL;
        clean += strstr(line, "initial penetration: none") != NULL;
    }
    cr_expect_eq(found, 1, "no line \"%s\"", wanted);
    cr_expect_eq(edges, 1);
    cr_expect_eq(note, 1);
    cr_expect_eq(clean, 1);
}
