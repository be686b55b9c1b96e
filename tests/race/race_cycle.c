/*
 * race_cycle.c -- the race check of the contact cycle (driver/contact_cycle*.c):
 * its fused block pass, the skip's motion bound, selection and expiries,
 * the re-sorts and the assembly, on a folded sheet of several blocks of
 * pairs under the fold-and-slide motion (race_check.c runs it). The run
 * with 2 threads is watched by ThreadSanitizer; its nodal forces must equal
 * those of the run with 1 thread bit for bit, and the skip must have left
 * pairs out (or the check would not exercise it).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact_cycle.h"
#include "meshgen.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#define RC_CYCLES 12

/* Run the cycles with `threads`; the last cycle's forces into f (3 n),
 * the candidates evaluated and listed over the run into *ev and *cand. 0
 * when it ran. */
static int run(const ctd_case *c, int threads, ct_real *f, int64_t *ev, int64_t *cand)
{
#ifdef _OPENMP
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    const ct_idx n = c->mesh.nodes.n;
    const double h = c->h_mean;
    ct_real *ref[3] = {c->mesh.nodes.x, c->mesh.nodes.y, c->mesh.nodes.z};
    ct_real *pos[3], *vel[3], *m = ct_calloc((size_t)n, sizeof(ct_real));
    int ok = m != NULL;
    for (int a = 0; a < 3; a++) {
        pos[a] = ct_calloc((size_t)n, sizeof(ct_real));
        vel[a] = ct_calloc((size_t)n, sizeof(ct_real));
        ok &= pos[a] && vel[a];
    }
    double lo = 1e300, hi = -1e300;
    for (ct_idx i = 0; ok && i < n; i++) {
        m[i] = 1;
        lo = fmin(lo, (double)ref[1][i]);
        hi = fmax(hi, (double)ref[1][i]);
    }
    /* The motion of tests/test_cycle.c, steps up to 0.03 h. */
    ctd_motion mo = {1, 2, 0.5 * (lo + hi), 0.72, 0.1, 0.5 * h, 0.8 * h, 1};
    mo.period = ctd_motion_max_step(&mo, 0.5 * (hi - lo)) / (0.03 * h);
    ctd_cycle_params p = ctd_cycle_default_params(h);
    ctd_cycle *cy = NULL;
    int rc = ok ? ctd_cycle_init(&cy, &p, n, m, c->sec.n, c->sec.node, c->sec.n, c->sec.node,
                                 c->main.n, c->mn1, c->mn2, c->mn3, c->mn4, 1)
                : CT_ERR_NOMEM;
    for (int k = 0; k < RC_CYCLES && rc == CT_OK; k++) {
        ctd_motion_eval(&mo, n, (const ct_real *const *)ref, k, 1e-3, pos, vel);
        rc = ctd_cycle_step(cy, pos[0], pos[1], pos[2], vel[0], vel[1], vel[2], (ct_real)1e-3,
                            f, f + n, f + 2 * (size_t)n);
    }
    if (rc == CT_OK) {
        *ev = ctd_cycle_get_stats(cy)->eval_sum;
        *cand = ctd_cycle_get_stats(cy)->cand_sum;
    }
    ctd_cycle_destroy(cy);
    for (int a = 0; a < 3; a++) {
        ct_free(pos[a]);
        ct_free(vel[a]);
    }
    ct_free(m);
    return rc;
}

void race_check_cycle(int *failures)
{
    ctd_case c;
    ct_diag diag;
    if (ctd_case_make(&c, "folded", 2500, CTD_NUM_NATURAL, 1, &diag) != CT_OK) {
        printf("FAIL contact cycle: %s\n", diag.msg);
        (*failures)++;
        return;
    }
    const size_t len = 3 * (size_t)c.mesh.nodes.n;
    ct_real *f2 = ct_calloc(len, sizeof(ct_real)), *f1 = ct_calloc(len, sizeof(ct_real));
    int64_t ev2 = 0, ev1 = 0, cand = 0;
    int rc2 = f2 && f1 ? run(&c, 2, f2, &ev2, &cand) : CT_ERR_NOMEM;
    int rc1 = rc2 == CT_OK ? run(&c, 1, f1, &ev1, &cand) : rc2;
    if (rc2 != CT_OK || rc1 != CT_OK) {
        printf("FAIL contact cycle: %s\n", ct_strerror(rc2 != CT_OK ? rc2 : rc1));
        (*failures)++;
    } else if (memcmp(f1, f2, sizeof(ct_real) * len) != 0) {
        printf("FAIL contact cycle: the forces differ between 1 and 2 threads\n");
        (*failures)++;
    } else if (!(ev2 < cand) || ev1 != ev2) {
        printf("FAIL contact cycle: %ld of %ld candidates evaluated (1 thread: %ld)\n",
               (long)ev2, (long)cand, (long)ev1);
        (*failures)++;
    } else {
        printf("ok   contact cycle (folded, %d nodes, %d cycles, %ld of %ld candidates "
               "evaluated): 1 and 2 threads agree\n",
               (int)c.mesh.nodes.n, RC_CYCLES, (long)ev2, (long)cand);
    }
#ifdef _OPENMP
    omp_set_num_threads(2);
#endif
    ct_free(f1);
    ct_free(f2);
    ctd_case_destroy(&c);
}
