/*
 * test_cycle.c -- the full contact cycle (driver/contact_cycle.c) on a
 * small folded sheet under the prescribed fold-and-slide motion: the stored
 * candidates stay complete against the direct search while re-sorts are
 * skipped, the nodal forces balance, 1 and 2 threads agree to the bit, and
 * nothing is NaN.
 */
#include "test_util.h"

#include <string.h>

#include "contact_cycle.h"
#include "meshgen.h"

/* A folded sheet, its motion (largest node step `step` h per cycle) and the
 * arrays of one run. */
typedef struct crun {
    ctd_case c;
    ct_idx n;
    double h;
    ct_real *ref[3], *pos[3], *vel[3], *f[3], *m;
    ctd_motion mo;
    ctd_cycle *cy;
} crun;

static void crun_make(crun *r, int64_t nodes, double step)
{
    memset(r, 0, sizeof *r);
    ct_diag diag;
    cr_assert_eq(ctd_case_make(&r->c, "folded", nodes, CTD_NUM_NATURAL, 1, &diag), CT_OK, "%s",
                 diag.msg);
    r->n = r->c.mesh.nodes.n;
    r->h = r->c.h_mean;
    const ct_real *src[3] = {r->c.mesh.nodes.x, r->c.mesh.nodes.y, r->c.mesh.nodes.z};
    for (int a = 0; a < 3; a++) {
        r->ref[a] = ct_calloc((size_t)r->n, sizeof(ct_real));
        r->pos[a] = ct_calloc((size_t)r->n, sizeof(ct_real));
        r->vel[a] = ct_calloc((size_t)r->n, sizeof(ct_real));
        r->f[a] = ct_calloc((size_t)r->n, sizeof(ct_real));
        cr_assert(r->ref[a] && r->pos[a] && r->vel[a] && r->f[a]);
        memcpy(r->ref[a], src[a], sizeof(ct_real) * (size_t)r->n);
    }
    r->m = ct_calloc((size_t)r->n, sizeof(ct_real));
    cr_assert(r->m);
    for (ct_idx i = 0; i < r->n; i++)
        r->m[i] = 1;
    double lo = 1e300, hi = -1e300;
    for (ct_idx i = 0; i < r->n; i++) {
        lo = fmin(lo, (double)r->ref[1][i]);
        hi = fmax(hi, (double)r->ref[1][i]);
    }
    /* Layers 0.4 h apart, compressed to 0.288 h (gap 0.3 h: in contact)
     * and on to 0.248 h, neighbouring layers sliding along z. */
    ctd_motion mo = {1, 2, 0.5 * (lo + hi), 0.72, 0.1, 0.5 * r->h, 0.8 * r->h, 1};
    mo.period = ctd_motion_max_step(&mo, 0.5 * (hi - lo)) / (step * r->h);
    r->mo = mo;
    ctd_cycle_params p = ctd_cycle_default_params(r->h);
    cr_assert_eq(ctd_cycle_init(&r->cy, &p, r->n, r->m, r->c.sec.n, r->c.sec.node, r->c.sec.n,
                                r->c.sec.node, r->c.main.n, r->c.mn1, r->c.mn2, r->c.mn3,
                                r->c.mn4, 1),
                 CT_OK);
}

static void crun_step(crun *r, int cycle)
{
    const double dt = 1e-3;
    ctd_motion_eval(&r->mo, r->n, (const ct_real *const *)r->ref, cycle, dt, r->pos, r->vel);
    int rc = ctd_cycle_step(r->cy, r->pos[0], r->pos[1], r->pos[2], r->vel[0], r->vel[1],
                            r->vel[2], (ct_real)dt, r->f[0], r->f[1], r->f[2]);
    cr_assert_eq(rc, CT_OK, "cycle %d: %s", cycle, ct_strerror(rc));
}

static void crun_free(crun *r)
{
    ctd_cycle_destroy(r->cy);
    for (int a = 0; a < 3; a++) {
        ct_free(r->ref[a]);
        ct_free(r->pos[a]);
        ct_free(r->vel[a]);
        ct_free(r->f[a]);
    }
    ct_free(r->m);
    ctd_case_destroy(&r->c);
}

static int64_t nodes_for_test(void) { return ctt_checking() ? 1000 : 2500; }
static int cycles_for_test(void) { return ctt_checking() ? 30 : 40; }

/* (a) At every cycle the stored candidates hold every pair the direct
 * search finds within the gap (margin 0) at the current positions; the
 * criterion re-sorts now and then, not every cycle. (d) No NaN. */
Test(cycle, candidates_complete_against_direct)
{
    ctt_threads(2);
    crun r;
    crun_make(&r, nodes_for_test(), 0.015);
    ct_search_params sp = ct_search_default_params(CT_SEARCH_DIRECT);
    ct_search *ds = NULL;
    cr_assert_eq(ct_search_init(&ds, &sp), CT_OK);
    ct_pairs ref;
    cr_assert_eq(ct_pairs_init(&ref, 0), CT_OK);
    int ncyc = cycles_for_test();
    int64_t touched = 0;
    for (int k = 0; k < ncyc; k++) {
        crun_step(&r, k);
        ct_search_input in;
        memset(&in, 0, sizeof in);
        in.nnode = r.n;
        in.x = r.pos[0];
        in.y = r.pos[1];
        in.z = r.pos[2];
        in.nsec = r.c.sec.n;
        in.sec = r.c.sec.node;
        in.nseg = r.c.main.n;
        in.n1 = r.c.mn1;
        in.n2 = r.c.mn2;
        in.n3 = r.c.mn3;
        in.n4 = r.c.mn4;
        in.gap = ctd_cycle_default_params(r.h).gap;
        in.margin = 0;
        in.self = 1;
        cr_assert_eq(ct_search_run(ds, &in, &ref), CT_OK);
        touched += ref.n;
        /* Both lists ascend by (node, seg): merge. */
        const ct_pairs *cand = ctd_cycle_pairs(r.cy);
        ct_idx j = 0;
        for (ct_idx i = 0; i < ref.n; i++) {
            while (j < cand->n && (cand->node[j] < ref.node[i] ||
                                   (cand->node[j] == ref.node[i] && cand->seg[j] < ref.seg[i])))
                j++;
            cr_assert(j < cand->n && cand->node[j] == ref.node[i] && cand->seg[j] == ref.seg[i],
                      "cycle %d: direct pair (%d, %d) is not among the %d stored candidates", k,
                      (int)ref.node[i], (int)ref.seg[i], (int)cand->n);
        }
        /* (d) No NaN in the forces, the geometry or the steps. */
        for (ct_idx i = 0; i < r.n; i++)
            cr_assert(isfinite(r.f[0][i]) && isfinite(r.f[1][i]) && isfinite(r.f[2][i]),
                      "cycle %d: node %d force is not finite", k, (int)i);
        const ct_contact_geo *g = ctd_cycle_geo(r.cy);
        for (ct_idx q = 0; q < cand->n; q++)
            cr_assert(isfinite(g->pen[q]) && isfinite(g->nx[q]) && isfinite(g->ny[q]) &&
                      isfinite(g->nz[q]) && isfinite(g->h1[q]) && isfinite(g->h4[q]),
                      "cycle %d: pair %d has a non-finite narrow-phase result", k, (int)q);
        const ctd_cycle_stats *s = ctd_cycle_get_stats(r.cy);
        cr_assert(isfinite(s->dt_kin) && s->dt_kin > 0 && isfinite(s->dt_nodal) &&
                  s->dt_nodal > 0);
    }
    const ctd_cycle_stats *s = ctd_cycle_get_stats(r.cy);
    /* Contact throughout (the sheet starts compressed into the gap), and
     * the criterion both skipped and fired. */
    cr_assert_gt(touched, (int64_t)ncyc * r.n / 2, "only %ld direct pairs in all", (long)touched);
    cr_assert_gt(s->active_sum, 0);
    cr_assert_geq(s->natural_sorts, 2, "the criterion fired %ld times", (long)s->natural_sorts);
    cr_assert_lt(s->resorts, ncyc / 3, "%ld searches in %d cycles", (long)s->resorts, ncyc);
    ct_pairs_destroy(&ref);
    ct_search_destroy(ds);
    crun_free(&r);
}

/* (b) Every pair's forces sum to zero (the node gets +f, the segment nodes
 * -h_i f with sum h_i = 1), so the nodal contact forces sum to zero up to
 * round-off, at every cycle. */
Test(cycle, nodal_forces_balance)
{
    ctt_threads(2);
    crun r;
    crun_make(&r, nodes_for_test(), 0.015);
    int ncyc = cycles_for_test();
    double tol = CTT_TOL(1e-12, 1e-5);
    for (int k = 0; k < ncyc; k++) {
        crun_step(&r, k);
        for (int a = 0; a < 3; a++) {
            double sum = 0, mag = 0;
            for (ct_idx i = 0; i < r.n; i++) {
                sum += (double)r.f[a][i];
                mag += fabs((double)r.f[a][i]);
            }
            if (a == 1)
                cr_assert_gt(mag, 0, "cycle %d: no force across the layers", k);
            cr_assert_leq(fabs(sum), tol * mag, "cycle %d axis %d: sum %g of |f| %g", k, a,
                          sum, mag);
        }
    }
    crun_free(&r);
}

/* (c) The whole cycle (search, colouring, remap, kernels, assembly) gives
 * bit-identical nodal forces with 1 and 2 threads. */
Test(cycle, threads_bit_identical)
{
    crun r1, r2;
    int ncyc = cycles_for_test();
    ctt_threads(1);
    crun_make(&r1, nodes_for_test(), 0.015);
    for (int k = 0; k < ncyc; k++)
        crun_step(&r1, k);
    ctt_threads(2);
    crun_make(&r2, nodes_for_test(), 0.015);
    for (int k = 0; k < ncyc; k++)
        crun_step(&r2, k);
    cr_assert_eq(r1.n, r2.n);
    cr_assert_eq(ctd_cycle_pairs(r1.cy)->n, ctd_cycle_pairs(r2.cy)->n);
    for (int a = 0; a < 3; a++)
        cr_assert(memcmp(r1.f[a], r2.f[a], sizeof(ct_real) * (size_t)r1.n) == 0,
                  "axis %d: the forces differ between 1 and 2 threads", a);
    double mag = 0;
    for (ct_idx i = 0; i < r1.n; i++)
        mag += fabs((double)r1.f[1][i]);
    cr_assert_gt(mag, 0);
    crun_free(&r1);
    crun_free(&r2);
}
