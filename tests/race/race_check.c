/*
 * race_check.c -- the race check run by `make check-tsan`.
 *
 * Criterion cannot run under ThreadSanitizer (its arena allocator fails to
 * map beside TSan's shadow memory), so this program drives every parallel
 * kernel itself, with the OpenMP thread count set to 2, on inputs large
 * enough that every thread gets work, and verifies each result against a
 * serial or direct reference. Built with clang -fsanitize=thread and run
 * with LLVM's Archer tool (OMP_TOOL_LIBRARIES), which tells TSan about
 * OpenMP's barriers, tasks and reductions: a reported race is a real one.
 * Exit code: 0 when every check passed, 1 otherwise.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "meshgen.h"

#ifdef _OPENMP
#include <omp.h>
#define SET_THREADS(n) omp_set_num_threads(n)
#else
#define SET_THREADS(n) ((void)(n))
#endif

static int failures = 0;

#define CHECK(cond, ...)                                                                       \
    do {                                                                                       \
        if (!(cond)) {                                                                         \
            failures++;                                                                        \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);                                        \
            printf(__VA_ARGS__);                                                               \
            printf("\n");                                                                      \
        }                                                                                      \
    } while (0)

static int same_pairs(const ct_pairs *a, const ct_pairs *b)
{
    return a->n == b->n && memcmp(a->node, b->node, sizeof(ct_idx) * (size_t)a->n) == 0 &&
           memcmp(a->seg, b->seg, sizeof(ct_idx) * (size_t)a->n) == 0;
}

/* Search a with the bsp search's dense-leaf knob set to dense. */
static int search_dense(ct_search_algo a, int dense, const ct_search_input *in, ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(a);
    p.dense = dense;
    ct_search *s;
    int rc = ct_search_init(&s, &p);
    if (rc == CT_OK)
        rc = ct_search_run(s, in, out);
    if (rc == CT_OK && a == CT_SEARCH_TOPO)
        rc = ct_search_run(s, in, out); /* the incremental path too */
    ct_search_destroy(s);
    return rc;
}

static int search(ct_search_algo a, const ct_search_input *in, ct_pairs *out)
{
    return search_dense(a, 0, in, out);
}

/* Mesh generation, topology and the four searches on a few families, with
 * shuffled numbering (the bucket's cell-order query) and natural numbering
 * (its secondary-order query). */
static void check_searches(void)
{
    const char *fams[] = {"plates", "folded", "soup", "graded", "sphere"};
    for (int f = 0; f < 10; f++) {
        ctd_case c;
        ct_diag d = {0};
        int rc = ctd_case_make(&c, fams[f % 5], 3000, f < 5 ? CTD_NUM_SHUFFLED : CTD_NUM_NATURAL,
                               5, &d);
        CHECK(rc == CT_OK, "case %s: %s", fams[f % 5], d.msg);
        if (rc)
            continue;
        rc = ct_mesh_build_topology(&c.mesh, &d);
        CHECK(rc == CT_OK, "topology of %s: %s", fams[f % 5], d.msg);
        for (int filt = 0; filt < 2; filt++) {
            ct_search_input in;
            ctd_case_input(&c, (ct_real)(0.3 * c.h_mean), (ct_real)(0.1 * c.h_mean), &in);
            in.filter = (ct_search_filter)filt;
            ct_pairs ref, got;
            ct_pairs_init(&ref, 0);
            ct_pairs_init(&got, 0);
            rc = search(CT_SEARCH_DIRECT, &in, &ref);
            CHECK(rc == CT_OK, "direct on %s: %s", fams[f % 5], ct_strerror(rc));
            for (int a = CT_SEARCH_BUCKET; a <= CT_SEARCH_BSP; a++) {
                rc = search((ct_search_algo)a, &in, &got);
                CHECK(rc == CT_OK && same_pairs(&ref, &got), "%s on %s (filter %d): rc %d, %d vs %d pairs",
                      ct_search_algo_name(a), fams[f % 5], filt, rc, got.n, ref.n);
            }
            /* bsp with every leaf dense (its per-thread scratch in tasks). */
            rc = search_dense(CT_SEARCH_BSP, 1, &in, &got);
            CHECK(rc == CT_OK && same_pairs(&ref, &got), "bsp dense on %s (filter %d): rc %d",
                  fams[f % 5], filt, rc);
            rc = search(CT_SEARCH_TOPO, &in, &got);
            CHECK(rc == CT_OK, "topological on %s: %s", fams[f % 5], ct_strerror(rc));
            /* A forced renumbering, searched twice by one workspace: the
             * second search reuses the kept numbering (its comparison of
             * the topology and its coordinate scatter in parallel). */
            for (int a = CT_SEARCH_BUCKET; a <= CT_SEARCH_BSP; a++) {
                ct_search_params p = ct_search_default_params((ct_search_algo)a);
                p.renumber = 1;
                ct_search *w;
                rc = ct_search_init(&w, &p);
                for (int k = 0; k < 2 && rc == CT_OK; k++) {
                    rc = ct_search_run(w, &in, &got);
                    CHECK(rc == CT_OK && same_pairs(&ref, &got),
                          "renumbered %s on %s, search %d: rc %d", ct_search_algo_name(a),
                          fams[f % 5], k, rc);
                }
                ct_search_destroy(w);
            }
            /* The topological search on a copy made anew every search (its
             * history carried over, in parallel), against the plain one. */
            {
                ct_search_params p = ct_search_default_params(CT_SEARCH_TOPO);
                ct_search *w[2] = {NULL, NULL};
                p.renumber = -1;
                rc = ct_search_init(&w[0], &p);
                p.renumber = 1;
                p.renumber_keep = -1;
                if (rc == CT_OK)
                    rc = ct_search_init(&w[1], &p);
                ct_pairs tp;
                ct_pairs_init(&tp, 0);
                for (int k = 0; k < 3 && rc == CT_OK; k++) {
                    rc = ct_search_run(w[0], &in, &tp);
                    if (rc == CT_OK)
                        rc = ct_search_run(w[1], &in, &got);
                    CHECK(rc == CT_OK && same_pairs(&tp, &got),
                          "renumbered topological on %s, search %d: rc %d", fams[f % 5], k, rc);
                }
                ct_pairs_destroy(&tp);
                ct_search_destroy(w[0]);
                ct_search_destroy(w[1]);
            }
            ct_pairs_destroy(&ref);
            ct_pairs_destroy(&got);
        }
        ctd_case_destroy(&c);
    }
}

/* Every assembly variant against the serial loop. */
static void check_assembly(void)
{
    ctd_case c;
    ct_diag d = {0};
    int rc = ctd_case_make(&c, "folded", 4000, CTD_NUM_NATURAL, 1, &d);
    CHECK(rc == CT_OK, "case: %s", d.msg);
    if (rc)
        return;
    ct_search_input in;
    ctd_case_input(&c, (ct_real)(0.4 * c.h_mean), 0, &in);
    ct_pairs pr;
    ct_pairs_init(&pr, 0);
    CHECK(search(CT_SEARCH_BUCKET, &in, &pr) == CT_OK, "search for assembly");
    ct_idx np = pr.n, nn = c.mesh.nodes.n;
    ct_idx *s[4];
    ct_real *w[5] = {NULL}, *f[3], *ref[3], *got[3];
    for (int k = 0; k < 4; k++)
        s[k] = ct_calloc((size_t)np, sizeof(ct_idx));
    for (int k = 1; k < 5; k++)
        w[k] = ct_calloc((size_t)np, sizeof(ct_real));
    for (int k = 0; k < 3; k++) {
        f[k] = ct_calloc((size_t)np, sizeof(ct_real));
        ref[k] = ct_calloc((size_t)nn, sizeof(ct_real));
        got[k] = ct_calloc((size_t)nn, sizeof(ct_real));
    }
    rc = ct_asm_seg_slots(np, pr.seg, c.main.n, c.mn1, c.mn2, c.mn3, c.mn4, s[0], s[1], s[2], s[3]);
    CHECK(rc == CT_OK, "seg slots: %s", ct_strerror(rc));
    for (ct_idx k = 0; k < np; k++) {
        w[1][k] = (ct_real)0.1;
        w[2][k] = (ct_real)0.2;
        w[3][k] = (ct_real)0.3;
        w[4][k] = (ct_real)0.4;
        f[0][k] = (ct_real)(k % 7);
        f[1][k] = (ct_real)(k % 5) - 2;
        f[2][k] = (ct_real)1;
    }
    ct_asm_map map = ct_asm_map_nodeseg(np, pr.node, s[0], s[1], s[2], s[3]);
    const ct_real *const *wc = (const ct_real *const *)w;
    CHECK(ct_assemble_serial(&map, wc, f[0], f[1], f[2], nn, ref[0], ref[1], ref[2]) == CT_OK,
          "serial assembly");
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    for (int v = 0; v < CT_ASM_NVARIANT; v++) {
        for (int k = 0; k < 3; k++)
            memset(got[k], 0, sizeof(ct_real) * (size_t)nn);
        rc = ct_assemble_prepare(&ws, (ct_assemble_variant)v, &map, nn);
        if (rc == CT_OK)
            rc = ct_assemble(&ws, (ct_assemble_variant)v, &map, wc, f[0], f[1], f[2], nn, got[0],
                             got[1], got[2]);
        double e = 0;
        for (ct_idx i = 0; i < nn; i++)
            for (int k = 0; k < 3; k++)
                e = fmax(e, fabs((double)got[k][i] - (double)ref[k][i]));
        CHECK(rc == CT_OK && e < 1e-3, "assembly %s: rc %d, max difference %g",
              ct_assemble_variant_name(v), rc, e);
    }
    ct_assemble_ws_destroy(&ws);
    for (int k = 0; k < 4; k++)
        ct_free(s[k]);
    for (int k = 1; k < 5; k++)
        ct_free(w[k]);
    for (int k = 0; k < 3; k++) {
        ct_free(f[k]);
        ct_free(ref[k]);
        ct_free(got[k]);
    }
    ct_pairs_destroy(&pr);
    ctd_case_destroy(&c);
}

int main(void)
{
    SET_THREADS(2);
    check_searches();
    check_assembly();
    extern void race_check_kernels(int *failures);
    race_check_kernels(&failures);
    extern void race_check_cycle(int *failures);
    race_check_cycle(&failures);
    extern void race_check_output(int *failures);
    race_check_output(&failures);
    /* The scenes of data/scenes, found from this file's path. */
    extern void race_check_scenes(const char *dir, int *failures);
    const char *f = __FILE__, *slash = strrchr(f, '/');
    char dir[1024];
    snprintf(dir, sizeof dir, "%.*s/../../data/scenes", slash ? (int)(slash - f) : 1,
             slash ? f : ".");
    race_check_scenes(dir, &failures);
    printf("race check: %s (%d failure%s)\n", failures ? "FAILED" : "passed", failures,
           failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
