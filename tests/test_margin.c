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

/* The folding-sheet scene's text with `margin: m` in both interfaces
 * (m < 0: as written). */
static void folding_sheet(char *buf, size_t n, double m)
{
    char path[512];
    ctt_tests_path(path, sizeof path, "../data/scenes/folding-sheet.yaml");
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f, "cannot read %s", path);
    char text[1 << 14];
    size_t len = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[len] = 0;
    buf[0] = 0;
    const char *keys[2] = {"name: self, ", "name: edges, "};
    const char *p = text;
    size_t used = 0;
    for (int k = 0; k < 2; k++) {
        const char *at = strstr(p, keys[k]);
        cr_assert_not_null(at, "the scene no longer has '%s'", keys[k]);
        at += strlen(keys[k]);
        used += (size_t)snprintf(buf + used, n - used, "%.*s", (int)(at - p), p);
        if (m >= 0)
            used += (size_t)snprintf(buf + used, n - used, "margin: %.17g, ", m);
        p = at;
    }
    snprintf(buf + used, n - used, "%s", p);
}

Test(margin, larger_margin_searches_less_and_finds_the_same_contacts)
{
    /* Self contact of a folding sheet (TYPE7 and TYPE11, friction). A
     * search at a larger margin holds every pair a smaller one holds, and
     * the pairs it adds are out of contact: they add nothing to a force. So
     * the run's states are the same bits, with fewer searches (measured:
     * 27 at the default 0.000995, 6 at 4 times that). This holds where the
     * elements' step governs, as here: the interfaces' own step counts the
     * stiffness of open candidates, which a larger margin can add
     * (scene.h). */
    static char yaml[1 << 14];
    folding_sheet(yaml, sizeof yaml, -1);
    sf_run a, b;
    sf_load(&a, yaml);
    sf_solve(&a, NULL, NULL, 2);
    cr_assert_eq(a.s.nhook, 2);
    /* Each interface's default from its own mean edge (segments, edges). */
    const double m0 = fmax(a.s.rep[0].margin, a.s.rep[1].margin);
    cr_assert(a.s.rep[0].margin > 0 && a.s.rep[1].margin > 0, "margins %g, %g",
              a.s.rep[0].margin, a.s.rep[1].margin);
    folding_sheet(yaml, sizeof yaml, 4 * m0);
    sf_load(&b, yaml);
    sf_solve(&b, NULL, NULL, 2);
    for (int i = 0; i < 2; i++) {
        cr_log_info("%s: re-sorts %lld at margin %.4g, %lld at %.4g", a.s.hooks[i].name,
                    (long long)a.s.rep[i].resorts, a.s.rep[i].margin,
                    (long long)b.s.rep[i].resorts,
                    b.s.rep[i].margin);
        cr_expect_eq(b.s.rep[i].margin, (double)(ct_real)(4 * m0));
        cr_expect(b.s.rep[i].resorts < a.s.rep[i].resorts,
                  "interface %d searched %lld times at 4 x the margin, %lld at the default", i,
                  (long long)b.s.rep[i].resorts, (long long)a.s.rep[i].resorts);
    }
    cr_expect(a.s.e.friction > 0, "the sheet never slid on itself: nothing was tested");
    cr_expect(sf_same_state(&a.s, &b.s),
              "the final states differ: the larger margin changed a contact");
    sf_free(&a);
    sf_free(&b);
}
