/*
 * test_cycle.c -- the full contact cycle (driver/contact_cycle.c) on a
 * small folded sheet under the prescribed fold-and-slide motion: the stored
 * candidates stay complete against the direct search while re-sorts are
 * skipped, the nodal forces balance, 1 and 2 threads agree to the bit,
 * nothing is NaN, and the fused block pass gives what whole-list kernel
 * calls give.
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

/* The cycle's law and friction for crun_make_opts (the defaults unless a
 * test sets them before making its run). */
static ctd_cycle_law crun_law = CTD_LAW_TYPE7;
static int crun_frictionless = 0;

static ctd_cycle_params crun_params(double h)
{
    ctd_cycle_params p = ctd_cycle_default_params(h);
    p.law = crun_law;
    if (crun_frictionless)
        p.mu = 0;
    return p;
}

static void crun_make_opts(crun *r, int64_t nodes, double step, int skip,
                           ct_assemble_variant variant)
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
    ctd_cycle_params p = crun_params(r->h);
    p.skip = skip;
    p.asm_variant = variant;
    cr_assert_eq(ctd_cycle_init(&r->cy, &p, r->n, r->m, r->c.sec.n, r->c.sec.node, r->c.sec.n,
                                r->c.sec.node, r->c.main.n, r->c.mn1, r->c.mn2, r->c.mn3,
                                r->c.mn4, 1),
                 CT_OK);
}

static void crun_make_skip(crun *r, int64_t nodes, double step, int skip)
{
    crun_make_opts(r, nodes, step, skip, CT_ASM_COLOUR);
}

static void crun_make(crun *r, int64_t nodes, double step)
{
    crun_make_skip(r, nodes, step, 1);
}

static void crun_step(crun *r, int cycle)
{
    const double dt = 1e-3;
    ctd_motion_eval(&r->mo, r->n, (const ct_real *const *)r->ref, cycle, dt, r->pos, r->vel);
    int rc = ctd_cycle_step(r->cy, r->pos[0], r->pos[1], r->pos[2], r->vel[0], r->vel[1],
                            r->vel[2], (ct_real)dt, r->f[0], r->f[1], r->f[2]);
    cr_assert_eq(rc, CT_OK, "cycle %d: %s", cycle, ct_strerror(rc));
}

/* The motion of crun_step plus a rigid drift of `drift` (a vector, in
 * units of h) per cycle. */
static void crun_step_drift(crun *r, int cycle, const double drift[3])
{
    const double dt = 1e-3;
    ctd_motion_eval(&r->mo, r->n, (const ct_real *const *)r->ref, cycle, dt, r->pos, r->vel);
    for (int a = 0; a < 3; a++) {
        const double d = drift[a] * r->h;
        for (ct_idx i = 0; i < r->n; i++) {
            r->pos[a][i] += (ct_real)(cycle * d);
            r->vel[a][i] += (ct_real)(d / dt);
        }
    }
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
            cr_assert(isfinite(g->pen[q]) &&
                          (!g->h1 || (isfinite(g->h1[q]) && isfinite(g->h2[q]) &&
                                      isfinite(g->h3[q]) && isfinite(g->h4[q]))),
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

/* One pair list through the public kernels called once on the whole list
 * (the composition the cycle's fused block pass must reproduce), assembled
 * by a plain serial loop: nodal forces into f, the two step limits into
 * dkin and dnod. ft is the friction history and pprev the last step's
 * penetrations (both updated); a node's new carrier takes the history of
 * the pair that carried it on that side last step, which loses it (the
 * driver's pair_select.c, written here for the list at once). *handed
 * counts the hand-overs. */
static void whole_list_reference(const crun *r, const ct_pairs *P, ct_real *const ft[3],
                                 ct_real *pprev, ct_real *const f[3], ct_real *dkin,
                                 ct_real *dnod, const ct_contact_geo *geo_out,
                                 const uint8_t *ev, int64_t *handed)
{
    const ct_idx n = P->n;
    const ctd_cycle_params p = crun_params(r->h);
    const ct_real dt = (ct_real)1e-3;
    enum { DIST, PEN, NX, NY, NZ, CX, CY, CZ, H1, H2, H3, H4, GAP, VX, VY, VZ, VN, K0, MS, FEL,
           KT, FN, PX, PY, PZ, NA };
    ct_real *a[NA];
    for (int i = 0; i < NA; i++) {
        a[i] = ct_calloc((size_t)n + 1, sizeof(ct_real));
        cr_assert(a[i]);
    }
    uint8_t *flag = ct_calloc((size_t)n + 1, 1);
    cr_assert(flag);
    ct_contact_geo g = {a[DIST], a[PEN], a[NX], a[NY], a[NZ], a[CX], a[CY],
                        a[CZ],   a[H1],  a[H2], a[H3], a[H4], a[GAP], flag};
    const ctd_case *c = &r->c;
    cr_assert_eq(ct_narrow_node_segment(n, P->node, P->seg, c->mn1, c->mn2, c->mn3, c->mn4,
                                        r->pos[0], r->pos[1], r->pos[2], NULL, NULL, p.gap, 0,
                                        0, p.quad, p.two_sided, &g, NULL),
                 CT_OK);
    /* The carrying pairs, decided on the whole list at once (the pass cuts
     * a node's pairs at its block boundaries). */
    uint8_t *carry = ct_calloc((size_t)n + 1, 1);
    ct_idx *from = ct_calloc((size_t)n + 1, sizeof(ct_idx));
    cr_assert(carry && from);
    cr_assert_eq(ct_select_pairs(n, P->node, r->pos[0], r->pos[1], r->pos[2], p.two_sided, &g,
                                 pprev, carry, from, NULL),
                 CT_OK);
    for (ct_idx k = 0; k < n; k++) {
        pprev[k] = a[PEN][k];
        if (from[k] < 0)
            continue;
        for (int d = 0; d < 3; d++) {
            ft[d][k] = ft[d][from[k]];
            ft[d][from[k]] = 0;
        }
        ++*handed;
    }
    ct_free(carry);
    ct_free(from);
    /* The narrow phase is per pair: the block pass must give its bytes for
     * what it keeps: p of every pair, the flag of every pair it evaluated,
     * the weights of every pair in contact. A pair the skip left out must
     * be out of contact by the whole-list call too (and read p = 0). The
     * other fields are not kept. */
    cr_assert(!geo_out->dist && !geo_out->nx && !geo_out->cx && !geo_out->gap);
    const int kept[4] = {H1, H2, H3, H4};
    ct_real *const mine[4] = {geo_out->h1, geo_out->h2, geo_out->h3, geo_out->h4};
    for (ct_idx k = 0; k < n; k++) {
        cr_assert(memcmp(&geo_out->pen[k], &a[PEN][k], sizeof(ct_real)) == 0,
                  "pair %d: p %g, the whole-list call %g", (int)k, (double)geo_out->pen[k],
                  (double)a[PEN][k]);
        if (ev && !ev[k])
            continue;
        cr_assert_eq(geo_out->flag[k], flag[k]);
        for (int i = 0; i < 4 && a[PEN][k] > 0 && geo_out->h1; i++)
            cr_assert(memcmp(&mine[i][k], &a[kept[i]][k], sizeof(ct_real)) == 0,
                      "pair %d: weight %d differs from the whole-list call", (int)k, i + 1);
    }
    for (ct_idx k = 0; k < n; k++) {
        ct_idx s = P->seg[k], q[4] = {c->mn1[s], c->mn2[s], c->mn3[s], c->mn4[s]};
        const ct_real *h[4] = {a[H1], a[H2], a[H3], a[H4]};
        for (int d = 0; d < 3; d++) {
            double u = r->vel[d][P->node[k]];
            for (int j = 0; j < 4; j++)
                u -= (double)h[j][k] * r->vel[d][q[j]];
            a[VX + d][k] = (ct_real)u;
        }
        a[VN][k] = a[VX][k] * a[NX][k] + a[VY][k] * a[NY][k] + a[VZ][k] * a[NZ][k];
        a[K0][k] = p.K0;
        a[MS][k] = r->m[P->node[k]];
    }
    if (p.law == CTD_LAW_TYPE7) {
        cr_assert_eq(ct_penalty_type7(n, a[PEN], a[GAP], a[K0], a[FEL], a[KT], NULL, NULL),
                     CT_OK);
        cr_assert_eq(ct_normal_finish(n, a[PEN], a[FEL], a[KT], a[VN], a[MS], NULL, p.viss, dt,
                                      a[NX], a[NY], a[NZ], a[FN], a[PX], a[PY], a[PZ], NULL),
                     CT_OK);
    } else {
        /* The linear law: F = K0 p with damping; its tangent is K0. */
        cr_assert_eq(ct_normal_force(n, a[PEN], a[NX], a[NY], a[NZ], a[VN], NULL, p.K0, a[MS],
                                     NULL, p.viss, dt, a[PX], a[PY], a[PZ], a[FN], NULL, NULL),
                     CT_OK);
        for (ct_idx k = 0; k < n; k++)
            a[KT][k] = a[PEN][k] > 0 ? p.K0 : 0;
    }
    if (p.mu > 0)
        cr_assert_eq(ct_friction_step(n, a[NX], a[NY], a[NZ], a[VX], a[VY], a[VZ], a[FN], NULL,
                                      p.mu, NULL, p.kt, dt, 1, ft[0], ft[1], ft[2], NULL),
                     CT_OK);
    for (int d = 0; d < 3; d++)
        memset(f[d], 0, sizeof(ct_real) * (size_t)r->n);
    for (ct_idx k = 0; k < n; k++) {
        ct_idx s = P->seg[k], q[4] = {c->mn1[s], c->mn2[s], c->mn3[s], c->mn4[s]};
        const ct_real *h[4] = {a[H1], a[H2], a[H3], a[H4]};
        for (int d = 0; d < 3; d++) {
            ct_real F = a[PX + d][k] + ft[d][k];
            f[d][P->node[k]] += F;
            for (int j = 0; j < 4; j++)
                f[d][q[j]] -= h[j][k] * F;
        }
    }
    ct_idx i;
    cr_assert_eq(ct_dt_type7_kinematic(n, a[PEN], a[GAP], a[VN], NULL, dkin, &i), CT_OK);
    cr_assert_eq(ct_dt_nodal(n, P->node, r->m, NULL, a[KT], NULL, dnod, &i), CT_OK);
    for (int k = 0; k < NA; k++)
        ct_free(a[k]);
    ct_free(flag);
}

/* (e) The narrow phase, force and step run fused in blocks of pairs; the
 * result must be that of each kernel called once on the whole list: the
 * same narrow-phase bytes for what the cycle keeps (p of every pair, out
 * of contact by the whole-list call too where the skip left it out; the
 * flag of every pair evaluated; the weights of the pairs in contact), the
 * same nodal step limit (the kinematic one and the nodal forces within
 * round-off: the reference sums the relative velocity in its own order),
 * and nodal forces equal to a serial assembly of the whole-list pair
 * forces within round-off (the colouring sums in another order). Checked
 * at the first cycle (friction history zero) and at the following cycles
 * while no re-sort moves the pairs, with the history carried by the
 * reference itself. Two threads, a list of several blocks. */
static void fused_pass_check(ct_assemble_variant variant)
{
    crun r;
    ctt_threads(2);
    /* 2500 nodes in every mode: about 17000 pairs, several blocks of the
     * fused pass (4096 pairs). */
    crun_make_opts(&r, 2500, 0.015, 1, variant);
    /* The colouring assembles the blocks' compact lists and keeps no
     * per-pair weights; the other variants keep them (and the reference
     * checks them). */
    cr_assert_eq(ctd_cycle_geo(r.cy)->h1 == NULL, variant == CT_ASM_COLOUR);
    ct_real *ft[3] = {NULL, NULL, NULL}, *f[3], *pprev = NULL;
    int64_t handed = 0;
    for (int d = 0; d < 3; d++) {
        f[d] = ct_calloc((size_t)r.n, sizeof(ct_real));
        cr_assert(f[d]);
    }
    int checked = 0;
    int64_t skipped = 0;
    for (int k = 0; k < 6; k++) {
        crun_step(&r, k);
        const ctd_cycle_stats *s = ctd_cycle_get_stats(r.cy);
        const ct_pairs *P = ctd_cycle_pairs(r.cy);
        if (k == 0) {
            cr_assert_gt(P->n, 3 * 4096, "%d pairs: too few for several blocks", (int)P->n);
            for (int d = 0; d < 3; d++) {
                ft[d] = ct_calloc((size_t)P->n, sizeof(ct_real));
                cr_assert(ft[d]);
            }
            pprev = ct_calloc((size_t)P->n, sizeof(ct_real));
            cr_assert(pprev);
        } else if (s->resorts > 1) {
            break; /* the pairs moved: the reference's history no longer applies */
        }
        ct_real dkin, dnod;
        const uint8_t *ev = ctd_cycle_evaluated(r.cy);
        whole_list_reference(&r, P, ft, pprev, f, &dkin, &dnod, ctd_cycle_geo(r.cy), ev,
                             &handed);
        for (ct_idx q = 0; q < P->n; q++)
            skipped += !ev[q];
        /* The friction history, pair by pair: the whole list's within
         * round-off (its relative velocity sums in another order), and
         * exactly zero out of contact. */
        const ct_real *pen = ctd_cycle_geo(r.cy)->pen;
        double hmag = 0, herr = 0;
        for (int d = 0; d < 3; d++) {
            const ct_real *h = ctd_cycle_friction(r.cy, d);
            for (ct_idx q = 0; q < P->n; q++) {
                if (!(pen[q] > 0))
                    cr_assert_eq(h[q], 0, "cycle %d: pair %d out of contact keeps a history", k,
                                 (int)q);
                hmag = fmax(hmag, fabs((double)ft[d][q]));
                herr = fmax(herr, fabs((double)h[q] - (double)ft[d][q]));
            }
        }
        cr_assert(crun_frictionless ? hmag == 0 : hmag > 0, "cycle %d: friction %g", k, hmag);
        cr_assert_leq(herr, CTT_TOL(1e-12, 1e-4) * hmag, "cycle %d: friction history %g of %g", k,
                      herr, hmag);
        double mag = 0, err = 0;
        for (int d = 0; d < 3; d++)
            for (ct_idx i = 0; i < r.n; i++) {
                mag = fmax(mag, fabs((double)f[d][i]));
                err = fmax(err, fabs((double)f[d][i] - (double)r.f[d][i]));
            }
        cr_assert_gt(mag, 0, "cycle %d: no force", k);
        cr_assert_leq(err, CTT_TOL(1e-12, 1e-4) * mag, "cycle %d: |f - f_ref| %g of max %g", k, err,
                      mag);
        /* The reference's relative velocity sums in another order. */
        cr_assert_leq(fabs((double)s->dt_kin - (double)dkin),
                      CTT_TOL(1e-12, 1e-4) * fabs((double)dkin),
                      "cycle %d: kinematic step %g, whole list %g", k, (double)s->dt_kin,
                      (double)dkin);
        cr_assert_eq(s->dt_nodal, dnod, "cycle %d: nodal step %g, whole list %g", k,
                     (double)s->dt_nodal, (double)dnod);
        checked++;
    }
    cr_assert_geq(checked, 2, "only %d cycles before the first re-sort", checked);
    cr_assert_gt(skipped, 0, "the skip left no pair out: the test does not exercise it");
    cr_assert_gt(handed, 0, "no node's contact moved to another pair: the hand-over untested");
    for (int d = 0; d < 3; d++) {
        ct_free(ft[d]);
        ct_free(f[d]);
    }
    ct_free(pprev);
    crun_free(&r);
}

/* The default assembly (colouring), fused with the pass: the blocks'
 * compact lists of pairs in contact. */
Test(cycle, fused_pass_equals_whole_list_kernels)
{
    fused_pass_check(CT_ASM_COLOUR);
}

/* A variant that assembles the per-pair forces after the pass (gather):
 * the same check, with the per-pair weights too. */
Test(cycle, fused_pass_equals_whole_list_kernels_per_pair_forces)
{
    fused_pass_check(CT_ASM_GATHER);
}

/* The same with the linear law (F = K0 p, the TYPE3/5/24 law) and without
 * friction: the cycle's other force path (ct_normal_force, no friction
 * step), which only the benchmark's trade table ran before. */
Test(cycle, fused_pass_equals_whole_list_kernels_linear_frictionless)
{
    crun_law = CTD_LAW_LINEAR;
    crun_frictionless = 1;
    fused_pass_check(CT_ASM_COLOUR);
}

/* The linear law with friction, the assembly after the pass. */
Test(cycle, fused_pass_equals_whole_list_kernels_linear_gather)
{
    crun_law = CTD_LAW_LINEAR;
    fused_pass_check(CT_ASM_GATHER);
}

/* (e2) One carrier per side: with the selection (the default), no node of
 * the folded sheet has more than two pairs in contact (one per side of
 * it), and fewer pairs are in contact than without it, where a node near a
 * segment's edge or vertex has one for each segment around it. */
Test(cycle, selection_keeps_one_pair_per_side)
{
    ctt_threads(2);
    int64_t active[2] = {0, 0};
    int most[2] = {0, 0};
    for (int sel = 0; sel < 2; sel++) {
        crun r;
        crun_make(&r, nodes_for_test(), 0.015);
        ctd_cycle_destroy(r.cy);
        ctd_cycle_params p = ctd_cycle_default_params(r.h);
        cr_assert_eq(p.select, 1, "the selection must be the default");
        p.select = sel;
        cr_assert_eq(ctd_cycle_init(&r.cy, &p, r.n, r.m, r.c.sec.n, r.c.sec.node, r.c.sec.n,
                                    r.c.sec.node, r.c.main.n, r.c.mn1, r.c.mn2, r.c.mn3,
                                    r.c.mn4, 1),
                     CT_OK);
        for (int k = 0; k < 5; k++) {
            crun_step(&r, k);
            const ct_pairs *P = ctd_cycle_pairs(r.cy);
            const ct_real *pen = ctd_cycle_geo(r.cy)->pen;
            int run = 0;
            for (ct_idx q = 0; q < P->n; q++) {
                run = (q > 0 && P->node[q] == P->node[q - 1] ? run : 0) + (pen[q] > 0);
                most[sel] = run > most[sel] ? run : most[sel];
            }
            active[sel] += ctd_cycle_get_stats(r.cy)->nactive;
        }
        crun_free(&r);
    }
    cr_assert_leq(most[1], 2, "a node has %d pairs in contact", most[1]);
    cr_assert_gt(most[0], 2, "without the selection no node had more than 2: the test shows "
                             "nothing");
    cr_assert_lt(active[1], active[0], "%ld pairs in contact with the selection, %ld without",
                 (long)active[1], (long)active[0]);
}

/* (f) A pair that leaves contact loses its friction history: a node pressed
 * into a quad and sliding (sticking friction) at cycle A, lifted out of the
 * gap but kept as a candidate at cycle B (no re-sort), and put back at A's
 * position and velocity at cycle C: at B its history is zero, and C gives
 * A's forces bit for bit (the predictor starts from zero both times). */
Test(cycle, friction_history_reset_out_of_contact)
{
    /* Nodes 0..3 the unit quad at z = 0, node 4 the secondary. */
    ct_real x[5] = {0, 1, 1, 0, 0.5}, y[5] = {0, 0, 1, 1, 0.5}, z[5] = {0, 0, 0, 0, 0.25};
    ct_real vx[5] = {0, 0, 0, 0, 1}, vy[5] = {0}, vz[5] = {0}, m[5] = {1, 1, 1, 1, 1};
    ct_idx sec[1] = {4}, mainn[4] = {0, 1, 2, 3}, n1[1] = {0}, n2[1] = {1}, n3[1] = {2},
           n4[1] = {3};
    ctd_cycle_params p = ctd_cycle_default_params(1);
    ctd_cycle *cy;
    cr_assert_eq(ctd_cycle_init(&cy, &p, 5, m, 1, sec, 4, mainn, 1, n1, n2, n3, n4, 0), CT_OK);
    ct_real fa[3][5], fb[3][5], fc[3][5];
    const ct_real dt = (ct_real)1e-3;
    /* A: p = 0.05 of the gap 0.3, sliding at 1 along x. */
    cr_assert_eq(ctd_cycle_step(cy, x, y, z, vx, vy, vz, dt, fa[0], fa[1], fa[2]), CT_OK);
    cr_assert_eq(ctd_cycle_pairs(cy)->n, 1);
    const ct_real ha = ctd_cycle_friction(cy, 0)[0];
    cr_assert_lt(ha, 0, "no friction force against the sliding (history %g)", (double)ha);
    cr_assert_gt(fa[2][4], 0);
    /* B: 0.35 above the quad, beyond the gap, within the margin. */
    z[4] = (ct_real)0.35;
    cr_assert_eq(ctd_cycle_step(cy, x, y, z, vx, vy, vz, dt, fb[0], fb[1], fb[2]), CT_OK);
    cr_assert_eq(ctd_cycle_get_stats(cy)->resorts, 1, "the lift must not trigger a re-sort");
    cr_assert_eq(ctd_cycle_pairs(cy)->n, 1);
    for (int a = 0; a < 3; a++)
        cr_assert_eq(ctd_cycle_friction(cy, a)[0], 0, "axis %d: history kept out of contact", a);
    for (int a = 0; a < 3; a++)
        for (int i = 0; i < 5; i++)
            cr_assert_eq(fb[a][i], 0);
    /* C: back to A. */
    z[4] = (ct_real)0.25;
    cr_assert_eq(ctd_cycle_step(cy, x, y, z, vx, vy, vz, dt, fc[0], fc[1], fc[2]), CT_OK);
    cr_assert(memcmp(fa, fc, sizeof fa) == 0, "cycle C differs from cycle A");
    cr_assert_eq(ctd_cycle_friction(cy, 0)[0], ha);
    cr_assert_null(ctd_cycle_friction(cy, 3));
    ctd_cycle_destroy(cy);
}

/* (g) The skip of the narrow phase changes no force, friction history or
 * step: the same motion run with the skip and without it gives the same
 * bytes at every cycle, re-sorts included, while the skip leaves out a
 * good share of the candidates. A faster motion than the other tests (up
 * to 0.03 h per cycle) makes the pairs' expiries run out often. */
Test(cycle, skip_equals_full_evaluation)
{
    ctt_threads(2);
    crun a, b;
    crun_make_skip(&a, nodes_for_test(), 0.03, 1);
    crun_make_skip(&b, nodes_for_test(), 0.03, 0);
    cr_assert_null(ctd_cycle_evaluated(b.cy));
    int ncyc = cycles_for_test();
    for (int k = 0; k < ncyc; k++) {
        crun_step(&a, k);
        crun_step(&b, k);
        const ct_pairs *pa = ctd_cycle_pairs(a.cy);
        cr_assert_eq(pa->n, ctd_cycle_pairs(b.cy)->n);
        for (int d = 0; d < 3; d++) {
            cr_assert(memcmp(a.f[d], b.f[d], sizeof(ct_real) * (size_t)a.n) == 0,
                      "cycle %d axis %d: the skip changed the nodal forces", k, d);
            cr_assert(memcmp(ctd_cycle_friction(a.cy, d), ctd_cycle_friction(b.cy, d),
                             sizeof(ct_real) * (size_t)pa->n) == 0,
                      "cycle %d axis %d: the skip changed the friction history", k, d);
        }
        const ctd_cycle_stats *sa = ctd_cycle_get_stats(a.cy), *sb = ctd_cycle_get_stats(b.cy);
        cr_assert_eq(sa->nactive, sb->nactive);
        cr_assert_eq(sa->dt_kin, sb->dt_kin);
        cr_assert_eq(sa->dt_nodal, sb->dt_nodal);
        cr_assert_eq(sb->neval, pa->n);
        /* A skipped pair's penetration is 0, as the full evaluation says. */
        const uint8_t *ev = ctd_cycle_evaluated(a.cy);
        const ct_real *pna = ctd_cycle_geo(a.cy)->pen, *pnb = ctd_cycle_geo(b.cy)->pen;
        ct_idx ne = 0;
        for (ct_idx q = 0; q < pa->n; q++) {
            ne += ev[q];
            cr_assert(ev[q] || (pna[q] == 0 && pnb[q] == 0),
                      "cycle %d: skipped pair %d has penetration %g", k, (int)q, (double)pnb[q]);
        }
        cr_assert_eq(ne, sa->neval);
    }
    const ctd_cycle_stats *sa = ctd_cycle_get_stats(a.cy), *sb = ctd_cycle_get_stats(b.cy);
    cr_assert_geq(sa->natural_sorts, 2, "the criterion fired %ld times", (long)sa->natural_sorts);
    cr_assert_gt(sa->active_sum, 0);
    cr_assert_lt(sa->eval_sum, sb->eval_sum * 3 / 4, "the skip left out only %ld of %ld pairs",
                 (long)(sb->eval_sum - sa->eval_sum), (long)sb->eval_sum);
    crun_free(&a);
    crun_free(&b);
}

/* (h) A rigid drift of the whole sheet, 0.5 h per cycle (2.5 margins),
 * on top of the fold-and-slide motion: the re-sort criterion and the skip
 * use the relative displacement, so the drifting sheet re-sorts as often
 * as the still one and the skip leaves out as many pairs; with the skip
 * off, the drifting sheet's forces are the same bytes. */
Test(cycle, rigid_drift_keeps_resorts_and_skip)
{
    ctt_threads(2);
    const double none[3] = {0, 0, 0}, drift[3] = {0.4, 0.2, -0.224};
    crun still, moving, full;
    crun_make_skip(&still, nodes_for_test(), 0.015, 1);
    crun_make_skip(&moving, nodes_for_test(), 0.015, 1);
    crun_make_skip(&full, nodes_for_test(), 0.015, 0);
    int ncyc = cycles_for_test();
    for (int k = 0; k < ncyc; k++) {
        crun_step_drift(&still, k, none);
        crun_step_drift(&moving, k, drift);
        crun_step_drift(&full, k, drift);
        for (int d = 0; d < 3; d++)
            cr_assert(memcmp(moving.f[d], full.f[d], sizeof(ct_real) * (size_t)moving.n) == 0,
                      "cycle %d axis %d: the skip changed the drifting sheet's forces", k, d);
    }
    const ctd_cycle_stats *ss = ctd_cycle_get_stats(still.cy);
    const ctd_cycle_stats *sm = ctd_cycle_get_stats(moving.cy);
    const ctd_cycle_stats *sf = ctd_cycle_get_stats(full.cy);
    cr_assert_eq(sm->resorts, ss->resorts, "%ld searches drifting, %ld still", (long)sm->resorts,
                 (long)ss->resorts);
    cr_assert_lt(sm->resorts, ncyc / 3);
    cr_assert_eq(sm->active_sum, sf->active_sum);
    cr_assert_gt(sm->active_sum, 0);
    /* The skip: within 5 % of the still sheet's evaluations, and a good
     * share of the candidates left out. */
    cr_assert_leq((double)sm->eval_sum, 1.05 * (double)ss->eval_sum,
                  "%ld pairs evaluated drifting, %ld still", (long)sm->eval_sum,
                  (long)ss->eval_sum);
    cr_assert_lt(sm->eval_sum, sf->eval_sum * 3 / 4);
    crun_free(&still);
    crun_free(&moving);
    crun_free(&full);
}
