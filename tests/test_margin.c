/*
 * test_margin.c -- the scene's re-sort margin (interfaces[i].margin): the
 * value the interfaces use, and what a larger one changes (how often they
 * search) and does not change (the contacts they find).
 */
#include "test_scene_features.h"

#include <math.h>

/* A block of bricks 0.05 above a held plate of 10 x 10 shells 0.1 wide,
 * TYPE24 between them, `extra` inside the interface's mapping. */
static void plate_block_scene(char *buf, size_t n, const char *extra)
{
    snprintf(buf, n,
             "end_time: 2.0e-6\n"
             "mesh:\n"
             "  - generate: {kind: plate, part: 1, cells: [10, 10], size: [1, 1]}\n"
             "  - generate: {kind: block, part: 2, cells: [2, 2, 1], size: [0.2, 0.2, 0.1],\n"
             "               origin: [0.4, 0.4, 0.05]}\n"
             "parts:\n"
             "  - {id: 1, element: shell, thickness: 0.01,\n"
             "     material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
             "  - {id: 2, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}\n"
             "boundary:\n"
             "  - {kind: fixed, nodes: {part: 1}}\n"
             "interfaces:\n"
             "  - {type: 24, main: {part: 1}, secondary: {part: 2}%s}\n",
             extra);
}

static double margin_used(const char *extra)
{
    char yaml[2048];
    plate_block_scene(yaml, sizeof yaml, extra);
    sf_run r;
    sf_load(&r, yaml);
    sf_solve(&r, NULL, NULL, 1);
    cr_assert_eq(r.s.nhook, 1);
    double m = r.s.rep[0].margin;
    sf_free(&r);
    return m;
}

Test(margin, the_field_is_the_margin_used)
{
    /* Without the field: 0.2 times the mean main edge, every edge of the
     * plate 1/10 long. */
    double d = margin_used("");
    cr_expect(fabs(d - 0.02) <= CTT_TOL(1e-12, 1e-6) * 0.02,
              "default margin %.17g, expected 0.2 x 0.1", d);
    cr_expect_eq(margin_used(", margin: 0"), d, "margin 0 is the default");
    double g = margin_used(", margin: 0.05");
    cr_expect_eq(g, (double)(ct_real)0.05, "margin 0.05 given, %.17g used", g);
}

/* The scene file data/scenes/NAME with `margin: m, ` put at the head of
 * every interface's mapping (m < 0: as written). */
static void scene_with_margin(char *buf, size_t n, const char *name, double m)
{
    char path[512], rel[256];
    snprintf(rel, sizeof rel, "../data/scenes/%s", name);
    ctt_tests_path(path, sizeof path, rel);
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f, "cannot read %s", path);
    char text[1 << 14];
    size_t len = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[len] = 0;
    const char *key = "{type: ", *p = text;
    size_t used = 0;
    int found = 0;
    for (const char *at = strstr(p, key); at; at = strstr(p, key)) {
        at += strlen("{");
        used += (size_t)snprintf(buf + used, n - used, "%.*s", (int)(at - p), p);
        if (m >= 0)
            used += (size_t)snprintf(buf + used, n - used, "margin: %.17g, ", m);
        p = at;
        found++;
    }
    cr_assert(found > 0, "%s has no interface", name);
    snprintf(buf + used, n - used, "%s", p);
}

/* Run the scene at margin m (< 0: as written) on 2 threads. */
static void run_at(sf_run *r, const char *name, double m)
{
    static char yaml[1 << 14];
    scene_with_margin(yaml, sizeof yaml, name, m);
    sf_load(r, yaml);
    sf_solve(r, NULL, NULL, 2);
}

/* The largest difference of the two runs' final positions over the
 * model's extent. */
static double state_difference(const ctd_solver *a, const ctd_solver *b)
{
    cr_assert_eq(a->nnode, b->nnode);
    double d = 0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const ct_real *pa[3] = {a->x, a->y, a->z}, *pb[3] = {b->x, b->y, b->z};
    for (int c = 0; c < 3; c++)
        for (ct_idx i = 0; i < a->nnode; i++) {
            d = fmax(d, fabs((double)pa[c][i] - (double)pb[c][i]));
            lo[c] = fmin(lo[c], (double)pa[c][i]);
            hi[c] = fmax(hi[c], (double)pa[c][i]);
        }
    double L = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    return d / L;
}

/* The interfaces' largest default margin (each from its own mean edge). */
static double default_margin(const sf_run *r)
{
    double m = 0;
    for (int i = 0; i < r->s.nhook; i++) {
        cr_assert(r->s.rep[i].margin > 0, "interface %d chose no margin", i);
        m = fmax(m, r->s.rep[i].margin);
    }
    return m;
}

/* A search at a larger margin holds every pair a smaller one holds; the
 * pairs it adds are out of contact and add nothing to a force, and the
 * interfaces' stable step counts an open pair only within 0.2 mean edges
 * (the default margin) plus two steps' approach of contact, whatever the
 * margin (ctdi_dt_counts). So the run is the same, to the rounding of the
 * additions the longer lists reorder, with fewer searches. */
static void same_run_fewer_searches(const char *name, double factor, int fewer)
{
    sf_run a, b;
    run_at(&a, name, -1);
    const double m0 = default_margin(&a);
    run_at(&b, name, factor * m0);
    for (int i = 0; i < a.s.nhook; i++) {
        cr_log_info("%s, %s: re-sorts %lld at margin %.4g, %lld at %.4g; cycles %lld, %lld",
                    name, a.s.hooks[i].name, (long long)a.s.rep[i].resorts, a.s.rep[i].margin,
                    (long long)b.s.rep[i].resorts, b.s.rep[i].margin, (long long)a.s.cycle,
                    (long long)b.s.cycle);
        cr_expect_eq(b.s.rep[i].margin, (double)(ct_real)(factor * m0));
        if (fewer)
            cr_expect(b.s.rep[i].resorts < a.s.rep[i].resorts,
                      "%s: interface %d searched %lld times at %g x the margin, %lld at the "
                      "default", name, i, (long long)b.s.rep[i].resorts, factor,
                      (long long)a.s.rep[i].resorts);
    }
    cr_expect_eq(b.s.cycle, a.s.cycle, "%s: %lld cycles at %g x the margin, %lld at the "
                 "default: the stable step moved with the margin", name, (long long)b.s.cycle,
                 factor, (long long)a.s.cycle);
    double d = state_difference(&a.s, &b.s);
    cr_expect(d <= CTT_TOL(1e-12, 1e-5), "%s: final positions %.3g (of the extent) apart", name,
              d);
    sf_free(&a);
    sf_free(&b);
}

Test(margin, folding_sheet_searches_less_at_a_larger_margin)
{
    /* TYPE7 and TYPE11 with friction: 27 searches at the default margin
     * (0.000995), 6 at 4 times it. */
    same_run_fewer_searches("folding-sheet.yaml", 4, 1);
}

Test(margin, sliding_block_step_does_not_move_with_the_margin)
{
    /* TYPE24 with friction, a block resting 1 mm from a slope: its nodes
     * are candidates from the start, open, at rest. Counted as the margin
     * made them candidates, the interface's step before any contact was
     * 4.94e-6 s at the default margin and 4.11e-6 at 3 times it (8997 and
     * 10816 cycles). */
    same_run_fewer_searches("sliding-block.yaml", 3, 0);
}

Test(margin, showcase_searches_less_at_a_larger_margin)
{
    /* TYPE24 (ball on sheet) and TYPE7 (the sheet on itself): 72 and 55
     * searches at the default margin, 16 and 12 at 3 times it. */
    same_run_fewer_searches("showcase.yaml", 3, 1);
}
