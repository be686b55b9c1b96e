/*
 * test_scene_features.c -- driver features that no other test ran (a
 * coverage run found them), each exercised by a small scene that the test
 * writes into a temporary directory and runs through the scene reader, the
 * model, the interfaces and the solver (suite scene_features). Every truth
 * is independent of the code under test: a hand formula, a run of the same
 * scene without the feature, or the geometry the generator promises.
 *
 * Most contacts below are linear penalty springs of a known stiffness K
 * (Stmin = Stmax = K pins the pair stiffness, whatever the law's inputs)
 * or TYPE11's TYPE7 law with a known K0, hit by rigid bodies, so that the
 * impact is a mass on a spring: a body of mass M arriving at speed v on n
 * equal springs goes p = v sqrt(M / (n K)) deep, stays pi sqrt(M / (n K))
 * in contact, pushes at most v sqrt(n K M), and leaves at speed v
 * (undamped). The masses are rho V by hand, but the ball's (its bricks
 * are mapped onto the ball), which comes from the model.
 * This file: meshes, generators and options (4 to 7); the interfaces in
 * test_scene_features_iface.c.
 *
 *  4. triangles_give_the_quads_response (ball dropped on a plate of
 *     triangles and on one of quads: peak force, contact time, depth and
 *     rebound agree with each other and with the hand values; triangle run
 *     bit-identical with 1 and 2 threads) and
 *     pressure_on_triangles_pushes_a_rigid_tile (a free rigid tile of
 *     triangles: mass rho A t, centre at the rectangle's centre, the
 *     pressure's impulse p A t and no rotation). The triangle branches of
 *     the area formulas (model_parts.c, loads.c, build_data.c) compute
 *     what their quad formula gives for n4 == n3 (a degenerate quad's
 *     diagonals are two of its edges): these checks catch a wrong
 *     triangle area or share, not the branches' removal; build_data.c's
 *     area is used for brick faces only, never for a triangle of a
 *     generated scene.
 *  5. tube_generator: node count nr (nl + 1), every node on the cylinder
 *     of the given radius about the axis through origin, the rings at
 *     origin z + l length / nl, the mass rho t (polygon perimeter) length;
 *     dropped on a plate, the tube bounces back with its momentum reversed
 *     and goes no deeper than a rigid tube would.
 *  6. gap_caps_set_the_contact_distance: a rigid thick tile (node gaps
 *     t/2) dropped on a thick clamped shell plate (segment gaps t/2),
 *     TYPE24. Truth: the contact begins at, and the tile bounces from,
 *     min(g_s, Gap_max_s) + min(g_m, Gap_max_m), for each cap alone and
 *     both; and the search follows the caps: shells so thick that the
 *     gap spans the model without both caps are refused, with both
 *     accepted.
 *  7. where_selections_with_le_and_and: the node and segment sets chosen
 *     by `<=` and `&&` (also mixed with `and`) equal the sets computed from
 *     the grid indices; the fixed components follow them. (The ball of 4
 *     picks its lowest node with `&&` and `<=` too.)
 */
#include "test_scene_features.h"

/* ---- 4. Triangles ---------------------------------------------------------- */

/* A rigid steel ball (radius 8 mm, 4^3 bricks: one lowest node) dropped at
 * 1 m/s on a clamped shell plate (t = 2 mm, 10 mm cells) of quads or of
 * triangles, its lowest node over the point (3, 1) mm of a cell, inside
 * the triangle (a, b, c) away from the diagonal. TYPE24 with that node
 * alone as secondary (where: z in (1, 1.7] mm; its neighbours are 0.5 mm
 * higher, beyond the depth), K = 4e5 N/m: one spring, the segment's K is
 * the same E t for a triangle as for a quad. */
static const char *ball_scene =
    "title: ball on %s\n"
    "end_time: 1.6e-3\n"
    "output: {every: 1.0e-5}\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [4, 4], size: [0.04, 0.04],\n"
    "               origin: [-0.02, -0.02, 0], tri: %s}\n"
    "  - generate: {kind: ball, part: 2, cells: [4], radius: 0.008,\n"
    "               origin: [0.003, 0.001, 0.0095]}\n"
    "parts:\n"
    "  - {id: 1, name: plate, element: shell, thickness: 0.002, " STEEL "}\n"
    "  - {id: 2, name: ball, element: rigid, " STEEL "}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {part: 1}}\n"
    "  - {kind: initial_velocity, nodes: {part: 2}, value: [0, 0, -1]}\n"
    "interfaces:\n"
    "  - {type: 24, name: drop, main: {part: 1}, secondary: {where: \"z > 0.001 && z <= "
    "0.0017\"},\n"
    "     VisS: 0, Stmin: 4.0e5, Stmax: 4.0e5}\n";

typedef struct ball_result {
    double fmax, ton, toff, dtmax;
    sf_obs o;
} ball_result;

static void ball_observe(void *ctx, const ctd_solver *s)
{
    ball_result *q = ctx;
    sf_observe(&q->o, s);
    double f = s->rep[0].force;
    q->fmax = fmax(q->fmax, f);
    if (f > 0 && !(q->ton >= 0))
        q->ton = s->time;
    if (f > 0)
        q->toff = s->time;
    q->dtmax = fmax(q->dtmax, s->dt);
}

static void ball_run(sf_run *r, int tri, int threads, ball_result *q)
{
    char yaml[4096];
    snprintf(yaml, sizeof yaml, ball_scene, tri ? "triangles" : "quads",
             tri ? "true" : "false");
    sf_load(r, yaml);
    /* 16 cells: 16 quads or 32 triangles, then the ball's 96 faces. */
    cr_assert_eq(r->m.mesh.nseg, (tri ? 32 : 16) + 96);
    memset(q, 0, sizeof *q);
    q->ton = -1;
    sf_obs_init(&q->o, 2, 0.0);
    sf_obs_add(&q->o, &r->m, 2, +1, -1.0);
    sf_solve(r, ball_observe, q, threads);
}

Test(scene_features, triangles_give_the_quads_response)
{
    const double v = 1, K = 4e5, gap = 0.001;
    sf_run rq, rt;
    ball_result q, t;
    ball_run(&rq, 0, 1, &q);
    ball_run(&rt, 1, 2, &t);
    double M = sf_body(&rt.m, 2)->mass;
    double F = v * sqrt(M * K), T = PI * sqrt(M / K);
    const ball_result *res[2] = {&q, &t};
    const sf_run *run[2] = {&rq, &rt};
    for (int k = 0; k < 2; k++) {
        const ball_result *b = res[k];
        const char *what = k ? "triangles" : "quads";
        cr_log_info("%s: peak force %.9g (hand %.9g), contact time %.9g (hand %.9g)", what,
                    b->fmax, F, b->toff - b->ton, T);
        sf_expect_bounce(&b->o, 0, &run[k]->m, gap, M, K, v, BOUNCE_TOL, what);
        /* Peak force: the depth's tolerance. The contact time is sampled at
         * the steps: one step at each end. */
        cr_expect(fabs(b->fmax - F) <= BOUNCE_TOL * F, "%s: peak force %.9g, expected "
                  "v sqrt(M K) = %.9g", what, b->fmax, F);
        cr_expect(fabs(b->toff - b->ton - T) <= 2 * b->dtmax + BOUNCE_TOL * T, "%s: in contact "
                  "for %.9g s, expected pi sqrt(M / K) = %.9g", what, b->toff - b->ton, T);
    }
    /* The two plates give the same response: peak force and depth to
     * 1e-4 (measured 3e-6 in double), contact time within two steps. */
    cr_expect(ctt_rel(t.fmax, q.fmax) <= 1e-4, "peak force %.9g on triangles, %.9g on quads",
              t.fmax, q.fmax);
    cr_expect(fabs(t.o.dmin[0] - q.o.dmin[0]) <= 1e-4 * (gap - q.o.dmin[0]),
              "closest approach %.9g on triangles, %.9g on quads", t.o.dmin[0], q.o.dmin[0]);
    cr_expect(fabs((t.toff - t.ton) - (q.toff - q.ton)) <= 2 * fmax(t.dtmax, q.dtmax),
              "contact time %.9g on triangles, %.9g on quads", t.toff - t.ton, q.toff - q.ton);
    /* The run on triangles with one thread: the same bits (not under the
     * sanitizers, which keep the two-thread run). */
    if (!ctt_checking()) {
        sf_run rt1;
        ball_result t1;
        ball_run(&rt1, 1, 1, &t1);
        cr_expect(sf_same_state(&rt.s, &rt1.s), "triangles: 1 and 2 threads differ");
        sf_free(&rt1);
    }
    sf_free(&rq);
    sf_free(&rt);
}

/* A free rigid steel tile (30 x 20 mm, t = 1 mm, 3 x 2 cells, as 12
 * triangles or 6 quads) under a pressure of 1e4 Pa on its upper face. */
static const char *press_scene =
    "title: pressed tile\n"
    "end_time: 2.0e-4\n"
    "output: {every: 1.0e-5}\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [3, 2], size: [0.03, 0.02],\n"
    "               origin: [0.001, 0.002, 0.003], tri: %s}\n"
    "parts:\n"
    "  - {id: 1, name: tile, element: rigid, thickness: 0.001, " STEEL "}\n"
    "boundary:\n"
    "  - {kind: pressure, surface: {part: 1}, pressure: 1.0e4}\n";

Test(scene_features, pressure_on_triangles_pushes_a_rigid_tile)
{
    const double A = 0.03 * 0.02, t = 0.001, p = 1e4, M = RHO * A * t;
    for (int tri = 0; tri < 2; tri++) {
        const char *what = tri ? "triangles" : "quads";
        char yaml[2048];
        snprintf(yaml, sizeof yaml, press_scene, tri ? "true" : "false");
        sf_run r;
        sf_load(&r, yaml);
        cr_assert_eq(r.m.mesh.nseg, tri ? 12 : 6);
        const ctd_rigid *b = sf_body(&r.m, 1);
        /* The rigid body's mass and centre, from the elements' areas. */
        cr_expect(ctt_rel(b->mass, M) < CTT_TOL(1e-12, 1e-6), "%s: mass %.9g, expected "
                  "rho A t = %.9g", what, b->mass, M);
        cr_expect(fabs(b->xc[0] - 0.016) < CTT_TOL(1e-14, 1e-8) &&
                      fabs(b->xc[1] - 0.012) < CTT_TOL(1e-14, 1e-8),
                  "%s: centre (%.9g, %.9g), expected the rectangle's (0.016, 0.012)", what,
                  b->xc[0], b->xc[1]);
        sf_solve(&r, NULL, NULL, 1);
        /* The impulse of the force p A along -z (the segments' normal is
         * +z) up to the last kick, half a step past the end; no moment
         * about the centre: the body neither spins nor moves sideways. */
        double P[3], time = r.s.time + 0.5 * r.s.dt, J = -p * A * time;
        ctd_solver_momentum(&r.s, P);
        double L = sqrt(b->L[0] * b->L[0] + b->L[1] * b->L[1] + b->L[2] * b->L[2]);
        cr_log_info("%s: momentum %.9g (hand %.9g), angular momentum %.3g", what, P[2], J, L);
        cr_expect(ctt_rel(P[2], J) < CTT_TOL(1e-9, 1e-5), "%s: momentum %.9g, expected "
                  "-p A t = %.9g", what, P[2], J);
        cr_expect(fabs(P[0]) + fabs(P[1]) < CTT_TOL(1e-12, 1e-6) * fabs(J), "%s: sideways "
                  "momentum %.3g, %.3g", what, P[0], P[1]);
        /* A moment of one corner's share of the force about the centre,
         * over the run, would be |J| x 1 cm / 3; round-off is far below. */
        cr_expect(L < CTT_TOL(1e-9, 1e-5) * fabs(J) * 0.01, "%s: angular momentum %.3g", what,
                  L);
        sf_free(&r);
    }
}

/* ---- 5. The tube generator ------------------------------------------------ */

/* A steel tube of shells (radius 10 mm, length 40 mm, t = 1 mm, 8 around,
 * 4 along) from origin (1, -2, 1.5) mm along z, dropped at 1 m/s on a
 * clamped shell plate (t = 2 mm) through TYPE5 (K = 6e4 N/m on each of
 * the 8 rim nodes; none over a grid line of the plate). */
static const char *tube_scene =
    "title: tube drop\n"
    "end_time: 2.0e-3\n"
    "output: {every: 1.0e-5}\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [4, 4], size: [0.04, 0.04],\n"
    "               origin: [-0.02, -0.02, 0]}\n"
    "  - generate: {kind: tube, part: 2, cells: [8, 4], radius: 0.01, length: 0.04,\n"
    "               origin: [0.001, -0.002, 0.0015]}\n"
    "parts:\n"
    "  - {id: 1, name: plate, element: shell, thickness: 0.002, " STEEL "}\n"
    "  - {id: 2, name: tube, element: shell, thickness: 0.001, " STEEL "}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {part: 1}}\n"
    "  - {kind: initial_velocity, nodes: {part: 2}, value: [0, 0, -1]}\n"
    "interfaces:\n"
    "  - {type: 5, name: rim, main: {part: 1}, secondary: {part: 2}, Stmin: 6.0e4, "
    "Stmax: 6.0e4}\n";

Test(scene_features, tube_generator)
{
    const int nr = 8, nl = 4;
    const double R = 0.01, L = 0.04, o[3] = {0.001, -0.002, 0.0015}, t = 0.001;
    sf_run r;
    sf_load(&r, tube_scene);
    const ct_nodes *nd = &r.m.mesh.nodes;
    /* The tube's nodes follow the plate's 25 in the generator's order,
     * (i, l) at i + nr l. */
    const ct_idx off = 25;
    cr_assert_eq(nd->n, off + nr * (nl + 1));
    double M = 0, worst_r = 0, worst_z = 0;
    for (int l = 0; l <= nl; l++)
        for (int i = 0; i < nr; i++) {
            ct_idx k = off + i + nr * l;
            cr_assert_eq(r.m.node_part[k], 2);
            double dx = nd->x[k] - o[0], dy = nd->y[k] - o[1];
            worst_r = fmax(worst_r, fabs(sqrt(dx * dx + dy * dy) - R));
            worst_z = fmax(worst_z, fabs(nd->z[k] - (o[2] + L * l / nl)));
            M += nd->m[k];
        }
    /* The cylinder and the rings: to the coordinates' round-off. */
    cr_expect(worst_r < CTT_TOL(1e-15, 1e-8), "a node is %.3g off the radius", worst_r);
    cr_expect(worst_z < CTT_TOL(1e-15, 1e-8), "a ring is %.3g off its height", worst_z);
    /* Shell masses: rho t times the area of the 8-sided prism. */
    double Mh = RHO * t * L * nr * 2 * R * sin(PI / nr);
    cr_expect(ctt_rel(M, Mh) < CTT_TOL(1e-12, 1e-6), "tube mass %.9g, expected %.9g", M, Mh);
    sf_obs ob;
    sf_obs_init(&ob, 2, 0.0);
    sf_obs_add(&ob, &r.m, 2, +1, -1.0);
    sf_solve(&r, sf_observe, &ob, 1);
    /* It runs, touches at the gap t_plate / 2, goes no deeper than the
     * rigid tube would (the elastic one's rim meets the springs with less
     * than the whole mass behind it; 1 % for the central difference), and
     * leaves with its momentum reversed. */
    const double v = 1, gap = 0.001, K = 6e4, prigid = v * sqrt(Mh / (nr * K));
    double P[3];
    ctd_solver_momentum(&r.s, P);
    cr_log_info("tube: onset %.9g, closest %.9g (rigid %.9g), momentum %.9g of %.9g, energy "
                "error %.3g", ob.don[0], ob.dmin[0], gap - prigid, P[2], Mh * v, r.s.e.error);
    cr_expect(ob.don[0] <= gap && ob.don[0] >= gap - v * ob.dtmax - 1e-9,
              "the tube touched at %.9g, expected the gap %.9g", ob.don[0], gap);
    cr_expect(ob.dmin[0] >= gap - 1.01 * prigid && ob.dmin[0] < gap, "the tube came within "
              "%.9g, the rigid bound is %.9g", ob.dmin[0], gap - prigid);
    cr_expect(fabs(P[2] - Mh * v) <= 0.01 * Mh * v, "final momentum %.9g, expected +M v = %.9g",
              P[2], Mh * v);
    /* Measured -4.8e-7 in double; 7.3e-4 in single, the round-off of the
     * float shells' strains in the internal energy. */
    cr_expect(fabs(r.s.e.error) < CTT_TOL(1e-5, 3e-3), "energy error %.3g", r.s.e.error);
    sf_free(&r);
}

/* ---- 6. Gap caps Gap_max_s, Gap_max_m (TYPE24, shells on both sides) ------ */

/* A clamped steel shell plate (2 x 2 cells of 10 mm) and, inside one
 * cell's footprint, a rigid steel tile (8 mm square, one cell) 0.5 mm
 * beyond the expected gap, falling at 1 m/s; both of thickness t. Its
 * four nodes (where: z > 0.1 mm) are TYPE24's secondary nodes: node gap
 * g_s = t/2 (the tile's elements), segment gap g_m = t/2 (the plate's).
 * K = 12500 N/m: depth v sqrt(M / 4K) = 0.2 mm at t = 4 mm. */
static const char *gap_scene =
    "title: gap caps\n"
    "end_time: 1.5e-3\n"
    "output: {every: 1.0e-5}\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [2, 2], size: [0.02, 0.02],\n"
    "               origin: [-0.01, -0.01, 0]}\n"
    "  - generate: {kind: plate, part: 2, cells: [1, 1], size: [0.008, 0.008],\n"
    "               origin: [0.001, 0.001, %.17g]}\n"
    "parts:\n"
    "  - {id: 1, name: plate, element: shell, thickness: %g, " STEEL "}\n"
    "  - {id: 2, name: tile, element: rigid, thickness: %g, " STEEL "}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {part: 1}}\n"
    "  - {kind: initial_velocity, nodes: {part: 2}, value: [0, 0, -1]}\n"
    "interfaces:\n"
    "  - {type: 24, name: caps, main: {part: 1}, secondary: {where: \"z > 0.0001\"},\n"
    "     VisS: 0, Stmin: 12500, Stmax: 12500%s}\n";

Test(scene_features, gap_caps_set_the_contact_distance)
{
    const double t = 0.004, v = 1, K = 12500, M = RHO * 0.008 * 0.008 * t;
    /* The card's caps and the distance they leave: g_s + g_m uncapped,
     * then each cap alone, then both. */
    static const char *const caps[4] = {"", ", Gap_max_s: 0.0005", ", Gap_max_m: 0.001",
                                        ", Gap_max_s: 0.0005, Gap_max_m: 0.001"};
    const double gaps[4] = {t / 2 + t / 2, 0.0005 + t / 2, t / 2 + 0.001, 0.0005 + 0.001};
    for (int k = 0; k < 4; k++) {
        char yaml[4096], what[96];
        snprintf(yaml, sizeof yaml, gap_scene, gaps[k] + 0.0005, t, t, caps[k]);
        snprintf(what, sizeof what, "caps '%s'", caps[k]);
        sf_run r;
        sf_load(&r, yaml);
        sf_obs o;
        sf_obs_init(&o, 2, 0.0);
        sf_obs_add(&o, &r.m, 2, +1, -1.0);
        sf_solve(&r, sf_observe, &o, 1);
        cr_expect(ctt_rel(sf_body(&r.m, 2)->mass, M) < CTT_TOL(1e-12, 1e-6));
        sf_expect_bounce(&o, 0, &r.m, gaps[k], M, 4 * K, v, BOUNCE_TOL, what);
        sf_free(&r);
    }
    /* The search reaches the capped gap, not the raw one. Shells 60 mm
     * thick make the uncapped gap 60 mm, and either cap alone leaves 30.5
     * or 31 mm, above the 28.4 mm diagonal of the box around the nodes
     * (every node would touch every segment): the build refuses them. With
     * both caps the gap is 1.5 mm and the build passes. */
    const double reach[4] = {0.06, 0.0005 + 0.03, 0.03 + 0.001, 0.0015};
    for (int k = 0; k < 4; k++) {
        char yaml[4096], err[1024] = "", want[96];
        snprintf(yaml, sizeof yaml, gap_scene, 0.002, 0.06, 0.06, caps[k]);
        snprintf(want, sizeof want, "node-segment gap %g reaches the diagonal", reach[k]);
        sf_run r;
        sf_load(&r, yaml);
        ctd_contact_hook *hooks = NULL;
        int nhook = 0;
        int rc = ctd_interfaces_build(&r.m, r.sc, &hooks, &nhook, err, sizeof err);
        for (int i = 0; i < nhook; i++)
            hooks[i].destroy(hooks[i].ctx);
        free(hooks);
        if (k < 3)
            cr_expect(rc != CT_OK && strstr(err, want), "60 mm shells, caps '%s': expected "
                      "'%s', got %d, %s", caps[k], want, rc, err);
        else
            cr_expect(rc == CT_OK, "60 mm shells, caps '%s' refused: %s", caps[k], err);
        sf_free(&r);
    }
}

/* ---- 7. where with <= and && ------------------------------------------------ */

/* A plate of 4 x 4 cells of 0.25 (coordinates exact in binary): node
 * (i, j) at (i/4, j/4), index i + 5 j; cell (i, j) is segment i + 4 j. */
static const char *where_scene =
    "title: where\n"
    "end_time: 1.0e-4\n"
    "mesh:\n"
    "  - generate: {kind: plate, part: 1, cells: [4, 4], size: [1.0, 1.0]}\n"
    "parts:\n"
    "  - {id: 1, name: plate, element: shell, thickness: 0.01, " STEEL "}\n"
    "boundary:\n"
    "  - {kind: fixed, nodes: {part: 1, where: \"x <= 0.5 && y <= 0.25\"}}\n"
    "  - {kind: fixed, nodes: {where: \"x >= 0.75&&y <= 0.5 and y > 0\"}, dofs: z}\n"
    "interfaces:\n"
    "  - {type: 7, name: corner, main: {part: 1, where: \"x<=0.5 && y<=0.5\"}}\n";

Test(scene_features, where_selections_with_le_and_and)
{
    sf_run r;
    sf_load(&r, where_scene);
    /* The first selection: i/4 <= 1/2 and j/4 <= 1/4, both boundaries in. */
    ct_nodeset ns;
    char err[256] = "";
    cr_assert_eq(ctd_model_select_nodes(&r.m, r.sc->boundary[0].nodes, &ns, err, sizeof err),
                 CT_OK, "%s", err);
    uint8_t want[25] = {0}, got[25] = {0};
    int nwant = 0;
    for (int j = 0; j <= 4; j++)
        for (int i = 0; i <= 4; i++)
            if (i <= 2 && j <= 1) {
                want[i + 5 * j] = 1;
                nwant++;
            }
    for (ct_idx k = 0; k < ns.n; k++)
        got[ns.node[k]] = 1;
    cr_expect_eq(ns.n, nwant, "%d nodes selected by 'x <= 0.5 && y <= 0.25', expected %d",
                 (int)ns.n, nwant);
    cr_expect(memcmp(got, want, sizeof want) == 0, "a different set of nodes");
    ct_nodeset_destroy(&ns);
    /* The fixed components: xyz on the first set; z on 3/4 <= x, 0 < y <=
     * 1/2 (i >= 3, j = 1 or 2), `&&` and `and` mixed. */
    for (int j = 0; j <= 4; j++)
        for (int i = 0; i <= 4; i++) {
            int mask = (i <= 2 && j <= 1 ? 7 : 0) | (i >= 3 && j >= 1 && j <= 2 ? 4 : 0);
            cr_expect_eq(r.m.bc_mask[i + 5 * j], mask, "node (%d, %d): fixed mask %d, "
                         "expected %d", i, j, r.m.bc_mask[i + 5 * j], mask);
        }
    /* The surface: the cells whose four corners have x, y <= 1/2. */
    ct_surface su;
    cr_assert_eq(ctd_model_select_surface(&r.m, r.sc->interfaces[0].main, &su, err,
                                          sizeof err), CT_OK, "%s", err);
    cr_expect_eq(su.n, 4, "%d segments selected, expected the 4 cells (i, j <= 1)", (int)su.n);
    for (ct_idx k = 0; k < su.n && k < 4; k++)
        cr_expect_eq(su.seg[k], (k % 2) + 4 * (k / 2), "segment %d is %d", (int)k,
                     (int)su.seg[k]);
    ct_free(su.seg);
    sf_free(&r);
}
