/*
 * test_alloc_fail.c -- what the library and the driver do when memory runs
 * out, suite "alloc_fail": every allocation of a sequence of calls made to
 * fail in turn (tests/alloc_fail.h: the k-th and all after it), k = 0, 1,
 * ... up to the number the sequence makes when nothing fails. Each time,
 * every call must answer CT_OK or CT_ERR_NOMEM (never another code, a
 * crash or a hang), the sequence stops at the first failure as a caller
 * would, the objects are then destroyed, and everything allocated in the
 * window must have been freed (no leak on any failure path). A refused
 * allocation must show as CT_ERR_NOMEM somewhere in the sequence: a call
 * that answers CT_OK after one of its allocations failed has lost it.
 *
 * Under make check (AddressSanitizer) the sweeps take a sample of the
 * allocations (see sweep). The sweeps run on 1 thread (the allocation order is then the same in
 * every run, so each k fails a different allocation) and again on 2 for
 * the paths of the parallel regions (where the k-th allocation may differ
 * from run to run; the claims hold for any).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "alloc_fail.h"
#include "contact_cycle.h"
#include "meshgen.h"
#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_cli.h"
#include "test_search_scene.h"

typedef struct run_case {
    const char *path;
    int load_only; /* 1: stop after the load (the importer's test scene) */
    const char *out; /* the output directory, or NULL for no files */
    char err[1024];
} run_case;

/* A sequence of calls under test: returns the first code other than CT_OK
 * (and stops there), or CT_OK; cleans up after itself either way. */
typedef int (*ctt_seq)(void *ctx);

/* Run seq with allocations failing from number k on; checks the claims
 * above and returns the number of allocations the run asked for. */
/* The allocation failing in the current run (-1: none), for messages. */
static int64_t cur_k = -1;

/* Set by a sequence whose run succeeded without an optional product (the
 * energy plot, which a run skips with a note when it cannot make it): a
 * refused allocation there is not lost. */
static int optional_skipped;

static int64_t run_failing(ctt_seq seq, void *ctx, int64_t k, const char *what)
{
    cur_k = k;
    optional_skipped = 0;
    ctt_alloc_begin(k);
    int rc = seq(ctx);
    int64_t n = ctt_alloc_end();
    int64_t refused = ctt_alloc_refused(), live = ctt_alloc_live();
    cr_assert(rc == CT_OK || rc == CT_ERR_NOMEM,
              "%s, allocation %lld failing: returned %d (%s), expected CT_OK or CT_ERR_NOMEM",
              what, (long long)k, rc, ct_strerror(rc));
    cr_assert(refused == 0 || rc == CT_ERR_NOMEM || optional_skipped,
              "%s, allocation %lld failing: %lld refused, yet the sequence answered CT_OK",
              what, (long long)k, (long long)refused);
    cr_assert_eq(live, 0, "%s, allocation %lld failing: %lld blocks not freed", what,
                 (long long)k, (long long)live);
    return n;
}

/* The sweep: a clean run counts the allocations (and must succeed), then
 * each is failed in turn, on 1 and on 2 threads. Under the sanitizers
 * (make check, where a run is 20 to 50 times slower) every fifth, from an
 * offset that changes from one sweep to the next, and all of the first 64:
 * there the point is what the normal build cannot see (a use after free,
 * a double free on a failure path). Returns the count of the 1-thread
 * clean run. */
static int64_t sweep(ctt_seq seq, void *ctx, const char *what)
{
    static int64_t offset;
    const int64_t stride = ctt_checking() ? 5 : 1;
    offset = (offset + 1) % stride;
    int64_t n1 = 0;
    for (int t = 1; t <= 2; t++) {
        ctt_threads(t);
        cur_k = -1;
        ctt_alloc_begin(-1);
        int rc = seq(ctx);
        int64_t n = ctt_alloc_end();
        cr_assert_eq(rc, CT_OK, "%s: the run without failures failed: %s", what,
                     ct_strerror(rc));
        cr_assert_eq(ctt_alloc_live(), 0, "%s: %lld blocks not freed without failures", what,
                     (long long)ctt_alloc_live());
        cr_assert_gt(n, 0, "%s: no allocation seen (are the wrappers linked?)", what);
        if (t == 1)
            n1 = n;
        for (int64_t k = 0; k < n; k++)
            if (k < 64 || k % stride == offset)
                run_failing(seq, ctx, k, what);
    }
    ctt_threads(1);
    return n1;
}

/* ---- The searches ------------------------------------------------------- */

typedef struct search_case {
    ctt_scene sc;
    ct_search_algo algo;
    int self;
} search_case;

/* Init, two runs (the nodes moved between them: the topological search's
 * history and the kept renumbering are used), destroy. */
static int search_seq(void *ctx)
{
    search_case *c = ctx;
    ct_search_params p = ct_search_default_params(c->algo);
    ct_search *s = NULL;
    ct_pairs out;
    int rc = ct_pairs_init(&out, 0);
    if (rc != CT_OK)
        return rc;
    rc = ct_search_init(&s, &p);
    ct_search_input in = ctt_scene_input(&c->sc, 0.3, 0.2, c->self);
    for (int r = 0; r < 2 && rc == CT_OK; r++) {
        rc = ct_search_run(s, &in, &out);
        for (ct_idx i = 0; i < c->sc.nn; i++)
            c->sc.z[i] += (ct_real)(i % 2 ? 0.01 : -0.01);
    }
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
    return rc;
}

Test(alloc_fail, searches)
{
    for (int a = 0; a < CT_SEARCH_NALGO; a++) {
        for (int self = 0; self <= 1; self++) {
            search_case c;
            c.algo = (ct_search_algo)a;
            c.self = self;
            /* Two 12 x 12 plates 0.4 apart (the second's nodes are the
             * secondaries), or one crumpled-like bent plate against
             * itself. */
            ctt_scene_init(&c.sc, 400, 400);
            ctt_scene_plate(&c.sc, 12, 12, 0, 0, 0, 1, 1, 0);
            ct_idx b = ctt_scene_plate(&c.sc, 12, 12, 0.3, 0.2, self ? 0.5 : 0.4, 1, self, 1);
            for (ct_idx i = self ? 0 : b; i < c.sc.nn; i++)
                ctt_scene_sec(&c.sc, i);
            char what[64];
            snprintf(what, sizeof what, "%s search%s", ct_search_algo_name(c.algo),
                     self ? " (self)" : "");
            sweep(search_seq, &c, what);
            ctt_scene_free(&c.sc);
        }
    }
}

/* ---- The assembly ------------------------------------------------------- */

typedef struct asm_case {
    ct_idx npair, nnode;
    ct_idx *slot[5];
    ct_real *f[3], *fn[3];
} asm_case;

/* Each variant prepared and run, in one workspace (a variant's preparation
 * after another's, as a caller switching variants does), then destroyed;
 * and the colouring of single pairs. */
static int asm_seq(void *ctx)
{
    asm_case *c = ctx;
    ct_assemble_ws ws;
    int rc = ct_assemble_ws_init(&ws);
    if (rc != CT_OK)
        return rc;
    const ct_asm_map map =
        ct_asm_map_nodeseg(c->npair, c->slot[0], c->slot[1], c->slot[2], c->slot[3], c->slot[4]);
    const ct_real *const w[5] = {NULL, NULL, NULL, NULL, NULL};
    for (int v = 0; v < CT_ASM_NVARIANT && rc == CT_OK; v++) {
        rc = ct_assemble_prepare(&ws, (ct_assemble_variant)v, &map, c->nnode);
        if (rc == CT_OK)
            rc = ct_assemble(&ws, (ct_assemble_variant)v, &map, w, c->f[0], c->f[1], c->f[2],
                             c->nnode, c->fn[0], c->fn[1], c->fn[2]);
    }
    if (rc == CT_OK)
        rc = ct_colour_pairs(&ws, &map, c->nnode, 1);
    ct_assemble_ws_destroy(&ws);
    return rc;
}

Test(alloc_fail, assembly)
{
    /* 3000 pairs over 400 nodes: each node in many pairs, many colours. */
    asm_case c;
    c.npair = 3000;
    c.nnode = 400;
    for (int s = 0; s < 5; s++) {
        c.slot[s] = malloc(sizeof(ct_idx) * (size_t)c.npair);
        cr_assert_not_null(c.slot[s]);
        for (ct_idx k = 0; k < c.npair; k++)
            c.slot[s][k] = (ct_idx)((k * 7 + s * 53 + (k / 13) * s) % c.nnode);
    }
    for (int d = 0; d < 3; d++) {
        c.f[d] = malloc(sizeof(ct_real) * (size_t)c.npair);
        c.fn[d] = calloc((size_t)c.nnode, sizeof(ct_real));
        cr_assert(c.f[d] && c.fn[d]);
        for (ct_idx k = 0; k < c.npair; k++)
            c.f[d][k] = (ct_real)(d + 1);
    }
    sweep(asm_seq, &c, "assembly");
    for (int s = 0; s < 5; s++)
        free(c.slot[s]);
    for (int d = 0; d < 3; d++) {
        free(c.f[d]);
        free(c.fn[d]);
    }
}

/* ---- The mesh ----------------------------------------------------------- */

/* A crumpled-like mesh made, checked, its topology (edges, node ->
 * segment map) built, destroyed. */
static int mesh_seq(void *ctx)
{
    (void)ctx;
    ct_mesh m;
    const int nx = 30, ny = 20;
    int rc = ct_mesh_init(&m, (ct_idx)((nx + 1) * (ny + 1)), (ct_idx)(nx * ny));
    if (rc != CT_OK)
        return rc;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            ct_idx p = (ct_idx)(i + (nx + 1) * j);
            m.nodes.x[p] = (ct_real)i;
            m.nodes.y[p] = (ct_real)j;
            m.nodes.z[p] = (ct_real)(0.1 * ((i * 7 + j * 3) % 5));
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            ct_idx s = (ct_idx)(i + nx * j), a = (ct_idx)(i + (nx + 1) * j);
            m.n1[s] = a;
            m.n2[s] = a + 1;
            m.n3[s] = a + nx + 2;
            m.n4[s] = (i + j) % 3 ? a + nx + 1 : a + nx + 2; /* some triangles */
        }
    ct_diag dg = {0, -1, ""};
    rc = ct_mesh_validate(&m, &dg);
    if (rc == CT_OK)
        rc = ct_mesh_build_topology(&m, &dg);
    ct_mesh_destroy(&m);
    return rc;
}

Test(alloc_fail, mesh_topology) { sweep(mesh_seq, NULL, "mesh topology"); }

/* ---- The driver: a scene from its file to a few cycles ------------------- */


/* Load, build the model, the interfaces and the solver (no files), run 3
 * cycles, destroy. A run that fails must exit as `contact run` does when
 * memory runs out (CTD_EXIT_OUTPUT, 5): that is mapped back to
 * CT_ERR_NOMEM, any other exit to CT_ERR_ARG (which fails the sweep).
 * Every failure's message must say that memory ran out. */
/* Whether a message says that memory ran out: in the project's words, or
 * in the C library's (a file writer reports the errno of what failed). */
static int says_nomem(const char *msg)
{
    return strstr(msg, "out of memory") || strstr(msg, strerror(ENOMEM));
}

/* Every failure's code and message: out of memory, said so. */
static int run_verdict(const run_case *c, int rc)
{
    cr_assert(rc == CT_OK || rc == CT_ERR_NOMEM,
              "%s, allocation %lld failing: returned %d (%s): %s", c->path, (long long)cur_k,
              rc, ct_strerror(rc), c->err);
    cr_assert(rc != CT_ERR_NOMEM || says_nomem(c->err),
              "%s, allocation %lld failing: out of memory, but the message does not say so: "
              "'%s'", c->path, (long long)cur_k, c->err);
    return rc;
}

static int run_seq(void *ctx)
{
    run_case *c = ctx;
    c->err[0] = 0;
    char gp[128] = "";
    if (c->out) {
        snprintf(gp, sizeof gp, "%s/energies.gp", c->out);
        unlink(gp);
    }
    ctd_scene *sc = NULL;
    ctd_scene_err e;
    memset(&e, 0, sizeof e);
    int rc = ctd_scene_load(c->path, &sc, &e);
    if (rc != CT_OK || c->load_only) {
        if (rc != CT_OK && e.count > 0)
            snprintf(c->err, sizeof c->err, "%s", e.msg[0].text);
        ctd_scene_free(sc);
        return run_verdict(c, rc);
    }
    ctd_model m;
    rc = ctd_model_build(&m, sc, c->err, sizeof c->err);
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    if (rc == CT_OK)
        rc = ctd_interfaces_build(&m, sc, &hooks, &nhook, c->err, sizeof c->err);
    ctd_solver s;
    memset(&s, 0, sizeof s);
    int solver = 0;
    if (rc == CT_OK) {
        ctd_solver_opts o = ctd_solver_default_opts();
        o.no_output = c->out == NULL;
        o.out_dir = c->out;
        o.quiet = 1;
        o.max_cycles = 3;
        rc = ctd_solver_init(&s, &m, &o, hooks, nhook, c->err, sizeof c->err);
        hooks = NULL; /* the solver's now, whatever the outcome */
        solver = 1;
    } else {
        for (int i = 0; i < nhook; i++)
            hooks[i].destroy(hooks[i].ctx);
        free(hooks);
    }
    if (rc == CT_OK) {
        int x = ctd_solver_run(&s);
        if (x != CTD_EXIT_OK) {
            snprintf(c->err, sizeof c->err, "exit %d, status %s: %s", x, s.status, s.message);
            rc = x == CTD_EXIT_OUTPUT && says_nomem(s.message) ? CT_ERR_NOMEM : CT_ERR_ARG;
        }
        optional_skipped = x == CTD_EXIT_OK && gp[0] && access(gp, F_OK) != 0;
    }
    if (solver)
        ctd_solver_destroy(&s);
    ctd_model_destroy(&m);
    ctd_scene_free(sc);
    return run_verdict(c, rc);
}

Test(alloc_fail, scene_to_cycles)
{
    static const char *const scenes[] = {
        "data/scenes/showcase.yaml",      "data/scenes/ball-on-plate.yaml",
        "data/scenes/bar-wave.yaml",      "data/scenes/crossing-rods.yaml",
        "data/scenes/folding-sheet.yaml", "data/scenes/knee-bolster.yaml",
        "data/scenes/pressed-blocks.yaml", "data/scenes/sliding-block.yaml",
        "data/scenes/truss-net-drop.yaml", "tests/data/scenes/import.yaml"};
    const size_t nscene = sizeof scenes / sizeof *scenes;
    for (size_t i = 0; i < nscene; i++) {
        run_case c;
        c.path = scenes[i];
        c.out = NULL;
        /* The importer's scene (a Radioss deck read with the scene) is
         * loaded only: its deck is made for the reader's tests (one brick
         * is inverted on purpose). */
        c.load_only = i == nscene - 1;
        sweep(run_seq, &c, scenes[i]);
    }
}

/* The same with the files written (the series, history, summary, the
 * plot's script): the output's own allocations. gnuplot is kept off the
 * path (it would run some 2000 times). */
Test(alloc_fail, scene_with_output)
{
    const char *path0 = getenv("PATH");
    char *path = strdup(path0 ? path0 : "/usr/bin:/bin");
    cr_assert_not_null(path);
    cr_assert_eq(setenv("PATH", "/nonexistent", 1), 0);
    char dir[64];
    ctt_tmpdir(dir, "allocout");
    run_case c;
    c.path = "data/scenes/showcase.yaml";
    c.load_only = 0;
    c.out = dir;
    sweep(run_seq, &c, "showcase.yaml with output");
    cr_assert_eq(setenv("PATH", path, 1), 0);
    free(path);
    ctt_rmtree(dir);
}

/* ---- The contact cycle (driver/contact_cycle.h) --------------------------- */

/* A folded sheet squeezed so its layers touch: the cycle made, three steps
 * (a re-sort forced in the second by a jump of every node), destroyed. */
static int cycle_seq(void *ctx)
{
    (void)ctx;
    ctd_case c;
    ct_diag diag;
    int rc = ctd_case_make(&c, "folded", 1500, CTD_NUM_NATURAL, 1, &diag);
    if (rc != CT_OK)
        return rc;
    const ct_idx n = c.mesh.nodes.n;
    ct_real *a[10];
    int ok = 1;
    for (int i = 0; i < 10; i++)
        ok &= (a[i] = ct_calloc((size_t)n, sizeof(ct_real))) != NULL;
    ctd_cycle *cy = NULL;
    rc = ok ? CT_OK : CT_ERR_NOMEM;
    if (rc == CT_OK) {
        /* a[0..2] positions, a[3..5] velocities, a[6..8] forces, a[9] mass. */
        for (ct_idx i = 0; i < n; i++) {
            a[0][i] = c.mesh.nodes.x[i];
            a[1][i] = (ct_real)(0.72 * c.mesh.nodes.y[i]);
            a[2][i] = c.mesh.nodes.z[i];
            a[9][i] = 1;
        }
        ctd_cycle_params p = ctd_cycle_default_params(c.h_mean);
        rc = ctd_cycle_init(&cy, &p, n, a[9], c.sec.n, c.sec.node, c.sec.n, c.sec.node,
                            c.main.n, c.mn1, c.mn2, c.mn3, c.mn4, c.self);
    }
    for (int k = 0; k < 3 && rc == CT_OK; k++) {
        for (ct_idx i = 0; k == 1 && i < n; i++)
            a[2][i] += (ct_real)c.h_mean;
        rc = ctd_cycle_step(cy, a[0], a[1], a[2], a[3], a[4], a[5], (ct_real)1e-3, a[6], a[7],
                            a[8]);
    }
    ctd_cycle_destroy(cy);
    for (int i = 0; i < 10; i++)
        ct_free(a[i]);
    ctd_case_destroy(&c);
    return rc;
}

Test(alloc_fail, contact_cycle) { sweep(cycle_seq, NULL, "contact cycle"); }
