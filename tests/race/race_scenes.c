/*
 * race_scenes.c -- the race check of whole scenes: the solver, the elements
 * and every interface type through the scene glue (race_check.c runs it).
 *
 * The scenes of data/scenes are small enough that most of their loops stay
 * below the thresholds at which the interfaces and the solver go parallel
 * (CTDI_PAR_MIN, CTD_PAR_MIN). Each is therefore run refined (its
 * `refine` replaced, ctd_scene_load_refined) for a few cycles, with 2
 * threads and then with 1: ThreadSanitizer watches the first run, and the
 * two final states must be equal bit for bit.
 */
#include <stdio.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "solver.h"

/* A scene, the factor on its cells, the cycles to run. */
typedef struct race_scene {
    const char *file;
    int refine;
    int cycles;
} race_scene;

static const race_scene scenes[] = {
    {"showcase.yaml", 2, 6},       /* TYPE24 on shells, TYPE7 */
    {"folding-sheet.yaml", 5, 6},  /* TYPE7 + TYPE11 */
    {"pressed-blocks.yaml", 3, 6}, /* TYPE3, bricks, imposed velocity */
    {"truss-net-drop.yaml", 2, 6}, /* TYPE5, trusses */
    {"knee-bolster.yaml", 3, 6},   /* TYPE6, rigid bodies */
};

typedef struct final_state {
    ct_idx n;
    ct_real *v[6];
    int64_t cycle;
} final_state;

/* Run one scene with `threads`; keep its final state. 0 when it ran. */
static int run_one(const char *dir, const race_scene *rs, int threads, final_state *out)
{
    char path[1024], err[1024] = "";
    snprintf(path, sizeof path, "%s/%s", dir, rs->file);
    static ctd_scene_err se;
    ctd_scene *sc = NULL;
    if (ctd_scene_load_refined(path, rs->refine, &sc, &se) != CT_OK) {
        printf("FAIL %s: %s\n", path, se.count ? se.msg[0].text : "cannot load");
        return -1;
    }
    ctd_model m;
    ctd_solver s;
    ctd_contact_hook *hooks = NULL;
    int nhook = 0, rc = ctd_model_build(&m, sc, err, sizeof err);
    if (rc == CT_OK)
        rc = ctd_interfaces_build(&m, sc, &hooks, &nhook, err, sizeof err);
    if (rc != CT_OK) {
        printf("FAIL %s: %s\n", path, err);
        ctd_scene_free(sc);
        return -1;
    }
    ctd_solver_opts o = ctd_solver_default_opts();
    o.no_output = 1;
    o.quiet = 1;
    o.threads = threads;
    o.max_cycles = rs->cycles;
    rc = ctd_solver_init(&s, &m, &o, hooks, nhook, err, sizeof err);
    if (rc == CT_OK)
        rc = ctd_solver_run(&s) == CTD_EXIT_OK ? CT_OK : -1;
    if (rc != CT_OK)
        printf("FAIL %s (%d threads): %s%s\n", path, threads, err, s.message);
    out->n = s.nnode;
    out->cycle = s.cycle;
    const ct_real *src[6] = {s.x, s.y, s.z, s.vx, s.vy, s.vz};
    for (int f = 0; f < 6 && rc == CT_OK; f++) {
        out->v[f] = ct_calloc((size_t)s.nnode + 1, sizeof(ct_real));
        if (!out->v[f])
            rc = CT_ERR_NOMEM;
        else
            memcpy(out->v[f], src[f], sizeof(ct_real) * (size_t)s.nnode);
    }
    ctd_solver_destroy(&s);
    ctd_model_destroy(&m);
    ctd_scene_free(sc);
    return rc == CT_OK ? 0 : -1;
}

static void state_free(final_state *f)
{
    for (int k = 0; k < 6; k++)
        ct_free(f->v[k]);
}

void race_check_scenes(const char *dir, int *failures)
{
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        final_state two, one;
        memset(&two, 0, sizeof two);
        memset(&one, 0, sizeof one);
        if (run_one(dir, &scenes[i], 2, &two) || run_one(dir, &scenes[i], 1, &one)) {
            (*failures)++;
        } else if (one.n != two.n || one.cycle != two.cycle) {
            printf("FAIL %s: %lld nodes and %lld cycles with 1 thread, %lld and %lld with 2\n",
                   scenes[i].file, (long long)one.n, (long long)one.cycle, (long long)two.n,
                   (long long)two.cycle);
            (*failures)++;
        } else {
            int same = 1;
            for (int f = 0; f < 6; f++)
                same &= memcmp(one.v[f], two.v[f], sizeof(ct_real) * (size_t)one.n) == 0;
            if (!same) {
                printf("FAIL %s: the final state differs between 1 and 2 threads\n",
                       scenes[i].file);
                (*failures)++;
            } else {
                printf("ok   %s (x%d, %lld nodes, %lld cycles): 1 and 2 threads agree\n",
                       scenes[i].file, scenes[i].refine, (long long)one.n,
                       (long long)one.cycle);
            }
        }
        state_free(&two);
        state_free(&one);
    }
}
