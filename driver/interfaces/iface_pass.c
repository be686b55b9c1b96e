/*
 * iface_pass.c -- one node-segment pass of an interface (TYPE3, TYPE5,
 * TYPE6, TYPE7 and TYPE24): the re-sort criterion and the search, the
 * per-pair states carried across re-sorts (friction force, initial
 * penetration, blending, Ipen_max deactivation), the narrow phase, then the
 * per-pair stages of iface_pass_force.c (normal law: linear with blending,
 * TYPE7, or TYPE6's curve, whose law and step live in type6.c; damping;
 * friction; time-step limits), and race-free assembly with the shape
 * weights (segment node i gets -h_i times the node's force).
 */
#include "iface_internal.h"

#include "ct_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Fill values of the states for pairs new after a re-sort. */
static ct_real state_fill(int s)
{
    if (s == CTDI_ST_FCAP)
        return (ct_real)CT_BLEND_NONE;
    if (s == CTDI_ST_ACT)
        return 1;
    return 0;
}

static void free_scratch(ctdi_pass *p)
{
    for (int i = 0; i < 4; i++)
        ct_free(p->s[i]);
    ct_free(p->o2n);
    for (int i = 0; i < 13; i++)
        ct_free(p->g[i]);
    ct_free(p->flag);
    ct_free(p->iflag);
    ct_free(p->carry);
    ct_free(p->handoff);
    for (int i = 0; i < CTDI_R_N; i++)
        ct_free(p->r[i]);
    memset(p->s, 0, sizeof p->s);
    memset(p->g, 0, sizeof p->g);
    memset(p->r, 0, sizeof p->r);
    p->o2n = NULL;
    p->flag = NULL;
    p->iflag = NULL;
    p->carry = NULL;
    p->handoff = NULL;
    p->cap = 0;
}

/* Scratch for n pairs (contents not kept). */
static int grow_scratch(ctdi_pass *p, size_t n)
{
    if (n <= p->cap && p->flag)
        return CT_OK;
    free_scratch(p);
    size_t c = n + n / 2 + 64;
    int ok = 1;
    for (int i = 0; i < 4; i++)
        ok &= (p->s[i] = ct_calloc(c, sizeof(ct_idx))) != NULL;
    ok &= (p->o2n = ct_calloc(c, sizeof(ct_idx))) != NULL;
    for (int i = 0; i < 13; i++)
        ok &= (p->g[i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    ok &= (p->flag = ct_calloc(c, 1)) != NULL;
    ok &= (p->iflag = ct_calloc(c, sizeof(int32_t))) != NULL;
    ok &= (p->carry = ct_calloc(c, 1)) != NULL;
    ok &= (p->handoff = ct_calloc(c, sizeof(ct_idx))) != NULL;
    for (int i = 0; i < CTDI_R_N; i++)
        ok &= (p->r[i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    if (!ok) {
        free_scratch(p);
        return CT_ERR_NOMEM;
    }
    p->cap = c;
    ct_contact_geo g = {p->g[0], p->g[1], p->g[2], p->g[3],  p->g[4],  p->g[5],  p->g[6],
                        p->g[7], p->g[8], p->g[9], p->g[10], p->g[11], p->g[12], p->flag};
    p->geo = g;
    return CT_OK;
}

/* States of side b for n pairs (contents not kept). */
static int grow_states(ctdi_pass *p, int b, size_t n)
{
    if (n <= p->capst[b] && p->st[b][0])
        return CT_OK;
    size_t c = n + n / 2 + 64;
    int ok = 1;
    for (int i = 0; i < CTDI_ST_N; i++) {
        ct_free(p->st[b][i]);
        ok &= (p->st[b][i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    }
    p->capst[b] = ok ? c : 0;
    return ok ? CT_OK : CT_ERR_NOMEM;
}

void ctdi_pass_free(ctdi_pass *p)
{
    if (!p)
        return;
    ct_search_destroy(p->search);
    ct_pairs_destroy(&p->pairs[0]);
    ct_pairs_destroy(&p->pairs[1]);
    ct_exclusion_destroy(&p->excl);
    ct_free(p->prune);
    for (int b = 0; b < 2; b++)
        for (int i = 0; i < CTDI_ST_N; i++)
            ct_free(p->st[b][i]);
    free_scratch(p);
    if (p->ws_ok)
        ct_assemble_ws_destroy(&p->ws);
    ct_free(p->sec);
    ct_free(p->mainn);
    ct_free(p->n1);
    ct_free(p->n2);
    ct_free(p->n3);
    ct_free(p->n4);
    ct_free(p->kseg);
    ct_free(p->gseg);
    ct_free(p->x0);
    ct_free(p->y0);
    ct_free(p->z0);
    memset(p, 0, sizeof *p);
}

size_t ctdi_pass_memory(const ctdi_pass *p, ct_idx nnode)
{
    /* Per pair: s1..s4, o2n and handoff; the geometry and results; flag
     * and carry; iflag. */
    size_t b = p->cap * (6 * sizeof(ct_idx) + (13 + CTDI_R_N) * sizeof(ct_real) + 2 + 4);
    b += (p->capst[0] + p->capst[1]) * CTDI_ST_N * sizeof(ct_real);
    b += ((size_t)p->pairs[0].cap + (size_t)p->pairs[1].cap) * 2 * sizeof(ct_idx);
    b += ((size_t)p->nsec + (size_t)p->nmain + 4 * (size_t)p->nseg) * sizeof(ct_idx);
    b += ((p->kseg ? 1 : 0) + (p->gseg ? 1 : 0)) * (size_t)p->nseg * sizeof(ct_real);
    b += 3 * (size_t)nnode * sizeof(ct_real);
    b += ct_search_memory(p->search) + ct_assemble_ws_memory(&p->ws);
    b += p->prune_cap * sizeof(double);
    if (p->excl.off)
        b += ((size_t)p->excl.nq + 1 + (size_t)p->excl.off[p->excl.nq]) * sizeof(ct_idx);
    return b;
}

int ctdi_pass_setup_fail(ct_diag *diag, int rc, const char *what)
{
    const char *why = rc == CT_ERR_NOMEM   ? "out of memory"
                      : rc == CT_ERR_RANGE ? "a node index is out of range"
                      : rc == CT_ERR_ARG   ? "a two-sided surface needs a gap > 0: give the "
                                             "interface a gap (only shell parts carry a "
                                             "thickness to take it from)"
                                           : ct_strerror(rc);
    char msg[sizeof diag->msg];
    snprintf(msg, sizeof msg, "%s: %s.", what, why);
    return ctdi_fail(diag, rc, -1, msg);
}

int ctdi_pass_setup(ctd_iface *it, ctdi_pass *p, ct_idx nsec, ct_idx *sec_owned, ct_idx nseg,
                    const ct_idx *n1, const ct_idx *n2, const ct_idx *n3, const ct_idx *n4,
                    ct_real *kseg_owned, int self, int two_sided, int law)
{
    memset(p, 0, sizeof *p);
    p->nsec = nsec;
    p->sec = sec_owned;
    p->kseg = kseg_owned;
    p->nseg = nseg;
    p->self = self;
    p->two_sided = two_sided;
    p->law = law;
    p->need_sort = 1;
    p->first = 1;
    p->excl_state = self && it->cfg.Irem_gap == 2;
    if (!sec_owned)
        return CT_ERR_NOMEM;
    p->n1 = ctdi_copy_idx(nseg, n1);
    p->n2 = ctdi_copy_idx(nseg, n2);
    p->n3 = ctdi_copy_idx(nseg, n3);
    p->n4 = ctdi_copy_idx(nseg, n4);
    if (!p->n1 || !p->n2 || !p->n3 || !p->n4)
        return CT_ERR_NOMEM;
    const ct_idx *lists[6] = {n1, n2, n3, n4, NULL, NULL};
    const ct_idx counts[6] = {nseg, nseg, nseg, nseg, 0, 0};
    int64_t nm = ctdi_unique_nodes(it->nnode, lists, counts, &p->mainn);
    if (nm < 0)
        return (int)nm;
    p->nmain = (ct_idx)nm;
    p->mainn_rs = p->nmain == nsec && (nsec == 0 || !memcmp(p->mainn, sec_owned,
                                                            (size_t)nsec * sizeof *sec_owned))
                      ? sec_owned
                      : p->mainn;
    /* Gaps: per segment from the node gaps when the type uses them. */
    int var_gap = ctdi_var_gap(&it->cfg);
    ct_real gmax_s = 0, gmax_m = 0;
    if (var_gap && it->gnode) {
        p->gseg = ctdi_seg_gap(it->gnode, nseg, n1, n2, n3, n4);
        if (!p->gseg)
            return CT_ERR_NOMEM;
        for (ct_idx i = 0; i < nsec; i++)
            gmax_s = it->gnode[sec_owned[i]] > gmax_s ? it->gnode[sec_owned[i]] : gmax_s;
        for (ct_idx j = 0; j < nseg; j++)
            gmax_m = p->gseg[j] > gmax_m ? p->gseg[j] : gmax_m;
        if (it->cfg.Gap_max_s > 0 && gmax_s > it->cfg.Gap_max_s)
            gmax_s = it->cfg.Gap_max_s;
        if (it->cfg.Gap_max_m > 0 && gmax_m > it->cfg.Gap_max_m)
            gmax_m = it->cfg.Gap_max_m;
    }
    p->sgap = gmax_s + gmax_m > it->cfg.gap ? gmax_s + gmax_m : it->cfg.gap;
    p->reach = p->sgap;
    /* TYPE6: rigid bodies crush into each other as deep as the curve
     * goes, far beyond the gap; the search must still see a node that
     * deep (the search distance is unsigned), so it reaches the curve's
     * last penetration beyond the gap. */
    if (law == CTDI_LAW_TYPE6 && it->ncurve > 0)
        p->sgap += it->curve_p[it->ncurve - 1];
    if (two_sided && !(p->sgap > 0))
        return CT_ERR_ARG; /* a two-sided surface needs a positive gap */
    ct_search_params sp = ct_search_default_params(it->cfg.algo);
    sp.max_pairs = ctdi_pair_limit(it, CTDI_PAIR_BYTES);
    int rc = ct_search_init(&p->search, &sp);
    if (rc == CT_OK)
        rc = ct_pairs_init(&p->pairs[0], 0);
    if (rc == CT_OK)
        rc = ct_pairs_init(&p->pairs[1], 0);
    if (rc == CT_OK) {
        size_t nn = (size_t)(it->nnode > 0 ? it->nnode : 1);
        p->x0 = ct_calloc(nn, sizeof(ct_real));
        p->y0 = ct_calloc(nn, sizeof(ct_real));
        p->z0 = ct_calloc(nn, sizeof(ct_real));
        if (!p->x0 || !p->y0 || !p->z0)
            rc = CT_ERR_NOMEM;
    }
    if (rc == CT_OK)
        rc = grow_states(p, 0, 0);
    if (rc == CT_OK)
        rc = grow_states(p, 1, 0);
    if (rc == CT_OK)
        rc = grow_scratch(p, 0);
    if (rc == CT_OK) {
        rc = ct_assemble_ws_init(&p->ws);
        p->ws_ok = rc == CT_OK;
    }
    return rc;
}

/* The pair stiffness (with Stfac, clamped): the linear law's K or TYPE7's
 * K0 (TYPE6 sets its own every step). Both kseg and knode already carry
 * Stfac, and the series law is homogeneous of degree one, so for TYPE3/5
 * series(Stfac Km, Stfac Ks) = Stfac Km Ks/(Km + Ks), the seed's law. */
static void pair_stiffness(const ctd_iface *it, const ctdi_pass *p, ct_idx n,
                           const ct_idx *restrict node, const ct_idx *restrict seg,
                           ct_real *restrict K)
{
    const ctd_iface_cfg *c = &it->cfg;
    const ct_real *restrict ks = p->kseg, *restrict kn = it->knode;
    const int mode = kn ? it->stiff_mode : CT_STIFF_MAIN, t7 = p->law == CTDI_LAW_TYPE7;
    const int fb = it->ks_fallback;
    const ct_real stmin = c->Stmin, stmax = c->Stmax;
    ct_real kc = c->Stfac * it->kconst;
    if (t7)
        kc = c->Istf == 1 ? c->Stfac : kc / 2;
    CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++) {
        ct_real v;
        if (t7 && c->Istf == 1)
            v = kc;
        else if (!ks)
            v = kc;
        else if (t7)
            v = ks[seg[k]] / 2;
        else if (fb && !(kn && kn[node[k]] > 0))
            v = ks[seg[k]]; /* no node stiffness: the main one alone */
        else
            v = ct_stiffness_combine1(mode, ks[seg[k]], kn ? kn[node[k]] : 0, 1, 0, 0);
        if (v < stmin)
            v = stmin;
        if (stmax > 0 && v > stmax)
            v = stmax;
        K[k] = v;
    });
}

/* The gap of the search (its distance is this plus the margin). TYPE6's
 * rigid bodies crush into each other as deep as the curve goes, far beyond
 * the gap, and the search distance is unsigned: it reaches the largest
 * penetration of the last step and two margins beyond, so that it holds
 * every pair whose penetration can grow until the next re-sort (a pair's
 * penetration grows by at most the motion since the search, below the
 * margin until the criterion asks for a new one; the other margin covers
 * the step since the last narrow phase). The TYPE6 law asks for a re-sort
 * when the largest penetration passes p->plimit all the same. */
static ct_real search_gap(const ctd_iface *it, const ctdi_pass *p)
{
    if (p->law != CTDI_LAW_TYPE6)
        return p->sgap;
    return p->reach + (p->pmax > 0 ? p->pmax : 0) + 2 * it->margin;
}

/* Irem_gap 2: the neighbour exclusion, built at the first search from the
 * positions it searched (the largest contact gap as the distance), then
 * applied to every search's pairs. */
static int exclude_neighbours(ctd_iface *it, ctdi_pass *p, const ct_search_input *in,
                              ct_pairs *np)
{
    if (p->excl_state == 0)
        return CT_OK;
    const int first = p->excl_state == 1;
    int rc;
    if (first) {
        if ((rc = ct_exclusion_build_nodeseg(&p->excl, in, p->reach)) != CT_OK)
            return rc;
        p->excl_state = 2;
    }
    int64_t removed = 0;
    rc = ct_pairs_exclude(np, &p->excl, &removed);
    if (rc == CT_OK && first)
        it->excluded += removed;
    return rc;
}

/* The search and everything that depends on the pair list. */
static int pass_search(ctd_iface *it, ctdi_pass *p, const ct_real *x, const ct_real *y,
                       const ct_real *z, const ct_real *m, int *did)
{
    *did = 0;
    if (!p->need_sort &&
        !ct_resort_needed(p->nsec, p->sec, p->nmain, p->mainn_rs, p->x0, p->y0, p->z0, x, y, z,
                          it->margin, NULL))
        return CT_OK;
    int old = p->cur, now = 1 - p->cur;
    ct_search_input in;
    memset(&in, 0, sizeof in);
    in.nnode = it->nnode;
    in.x = x;
    in.y = y;
    in.z = z;
    in.nsec = p->nsec;
    in.sec = p->sec;
    in.nseg = p->nseg;
    in.n1 = p->n1;
    in.n2 = p->n2;
    in.n3 = p->n3;
    in.n4 = p->n4;
    in.gap = search_gap(it, p);
    in.margin = it->margin;
    in.self = p->self;
    in.filter = it->cfg.filter;
    ct_pairs *np = &p->pairs[now];
    const ct_pairs *op = &p->pairs[old];
    int rc = ct_search_run(p->search, &in, np);
    if (rc == CT_ERR_TOOBIG) /* beyond max_pairs: the memory or the index */
        return ctdi_pairs_too_many(it, ctdi_pair_limit(it, CTDI_PAIR_BYTES), 1, p->nsec,
                                   CTDI_PAIR_BYTES, p->sgap);
    if (rc != CT_OK)
        return rc;
    if ((rc = exclude_neighbours(it, p, &in, np)) != CT_OK)
        return rc;
    if (p->law == CTDI_LAW_TYPE6) {
        p->plimit = (p->pmax > 0 ? p->pmax : 0) + 2 * it->margin;
        if ((rc = ctdi_type6_prune(it, p, np, x, y, z)) != CT_OK)
            return rc;
    }
    ct_idx n = np->n;
    if ((rc = grow_scratch(p, (size_t)n)) != CT_OK || (rc = grow_states(p, now, (size_t)n)))
        return rc;
    rc = ct_asm_seg_slots(n, np->seg, p->nseg, p->n1, p->n2, p->n3, p->n4, p->s[0], p->s[1],
                          p->s[2], p->s[3]);
    if (rc != CT_OK)
        return rc;
    ct_asm_map map = ct_asm_map_nodeseg(n, np->node, p->s[0], p->s[1], p->s[2], p->s[3]);
    rc = ct_assemble_prepare(&p->ws, it->cfg.asm_variant, &map, it->nnode);
    if (rc != CT_OK)
        return rc;
    rc = ct_pair_match(op->n, op->node, op->seg, n, np->node, np->seg, p->o2n, NULL);
    for (int s = 0; s < CTDI_ST_N && rc == CT_OK; s++)
        rc = ct_pair_remap(n, p->o2n, p->st[old][s], state_fill(s), p->st[now][s]);
    if (rc != CT_OK)
        return rc;
    pair_stiffness(it, p, n, np->node, np->seg, p->r[CTDI_R_K]);
    const ct_idx *restrict nd = np->node;
    ct_real *restrict ms = p->r[CTDI_R_MS];
    CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++)
        ms[k] = m[nd[k]];
    );
    ct_real *restrict a = p->x0, *restrict b = p->y0, *restrict c = p->z0;
    const ct_idx nn = it->nnode;
    CTI_PAR_FOR_SIMD(nn > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx i = 0; i < nn; i++) {
        a[i] = x[i];
        b[i] = y[i];
        c[i] = z[i];
    });
    p->cur = now;
    p->need_sort = 0;
    *did = 1;
    return CT_OK;
}

/* After a search: a pair stiffness that overflowed (Stfac 1e308, or Istf 1
 * with a huge Stfac, and no Stmax) is the input's fault, said here with
 * the pair's node (CT_ERR_ARG). The force kernels would refuse it as a
 * non-finite value (the run "unstable"); before they did, its zero stable
 * step was caught by the solver's hook, with this advice. TYPE6 sets its
 * stiffness from the curve each step. */
static int pass_stiffness_finite(ctd_iface *it, const ctdi_pass *p, ctd_iface_report *rep)
{
    if (p->law == CTDI_LAW_TYPE6)
        return CT_OK;
    const ct_pairs *pp = &p->pairs[p->cur];
    const ct_real *restrict K = p->r[CTDI_R_K];
    for (ct_idx k = 0; k < pp->n; k++)
        if (CTI_NONFINITE(K[k])) {
            rep->dt_node = pp->node[k];
            snprintf(it->msg, sizeof it->msg,
                     "the contact stiffness overflows (expected a smaller Stfac, or a finite "
                     "Stmax)");
            return CT_ERR_ARG;
        }
    return CT_OK;
}

int ctdi_pass_step(ctd_iface *it, ctdi_pass *p, ct_real dt, const ct_real *x,
                   const ct_real *y, const ct_real *z, const ct_real *vx, const ct_real *vy,
                   const ct_real *vz, const ct_real *m, ct_real *fx, ct_real *fy,
                   ct_real *fz, ctd_iface_report *rep)
{
    if (p->nsec == 0 || p->nseg == 0)
        return CT_OK;
    if (!(it->band > 0)) {
        double h = ctdi_mean_seg_edge(p->nseg, p->n1, p->n2, p->n3, p->n4, x, y, z);
        ctdi_choose_band(it, h, p->sgap > 0 ? p->sgap : (ct_real)1e-3);
    }
    double t0 = ctd_wtime();
    int did;
    int rc = pass_search(it, p, x, y, z, m, &did);
    if (rc != CT_OK) {
        p->need_sort = 1;
        return rc;
    }
    if (did) {
        it->resorts++;
        rep->resorted++;
        if ((rc = pass_stiffness_finite(it, p, rep)) != CT_OK)
            return rc;
    }
    double t1 = ctd_wtime();
    const ct_pairs *pp = &p->pairs[p->cur];
    ct_idx n = pp->n;
    ct_narrow_stats ns;
    int var_gap = ctdi_var_gap(&it->cfg);
    const ct_real *gn = var_gap ? it->gnode : NULL, *gs = var_gap ? p->gseg : NULL;
    rc = ct_narrow_node_segment(n, pp->node, pp->seg, p->n1, p->n2, p->n3, p->n4, x, y, z, gn,
                                gs, it->cfg.gap, it->cfg.Gap_max_s, it->cfg.Gap_max_m,
                                it->cfg.quad, p->two_sided, &p->geo, &ns);
    if (rc != CT_OK)
        return rc;
    ns.active = ctdi_pass_select(p, x, y, z);
    if (p->first && p->law == CTDI_LAW_LINEAR)
        ctdi_pass_initial_state(it, p, n);
    p->first = 0;
    if (it->deactivated > 0) {
        ct_real *restrict pen = p->geo.pen;
        const ct_real *restrict act = p->st[p->cur][CTDI_ST_ACT];
        for (ct_idx k = 0; k < n; k++)
            if (act[k] == 0)
                pen[k] = 0;
    }
    double t2 = ctd_wtime();
    /* The pressure-dependent laws' area: the main segment's, or the
     * secondary node's (iface_area.c). */
    int wa = it->fric_on && (it->fric_law == CT_FRIC_POLY || it->fric_law == CT_FRIC_DARMSTAD);
    rc = ctdi_pass_kinematics(p, n, pp->node, x, y, z, vx, vy, vz, m, wa && !it->area_off);
    if (rc == CT_OK && wa && it->area_off)
        ctdi_area_of_pairs(it, n, pp->node, p->geo.pen, p->geo.nx, p->geo.ny, p->geo.nz, x, y,
                           z, p->r[CTDI_R_PRS]);
    if (rc == CT_OK)
        rc = ctdi_pass_normal_force(it, p, n, dt);
    ct_real *fd = p->r[CTDI_R_FD];
    if (rc == CT_OK && it->fric_on)
        rc = ctdi_pass_friction(it, p, n, dt);
    if (rc != CT_OK)
        return rc;
    rep->e_contact += ct_sum_ordered(n, p->r[CTDI_R_EN]) + p->e_law;
    rep->e_damp += ct_sum_ordered(n, p->r[CTDI_R_DD]);
    if (it->fric_on)
        rep->e_fric += ct_sum_ordered(n, fd);
    const double side = p->reverse ? -1.0 : 1.0;
    rep->force[0] += side * ct_sum_ordered(n, p->r[CTDI_R_FX]);
    rep->force[1] += side * ct_sum_ordered(n, p->r[CTDI_R_FY]);
    rep->force[2] += side * ct_sum_ordered(n, p->r[CTDI_R_FZ]);
    double t3 = ctd_wtime();
    ct_asm_map map = ct_asm_map_nodeseg(n, pp->node, p->s[0], p->s[1], p->s[2], p->s[3]);
    const ct_real *const w[5] = {NULL, p->geo.h1, p->geo.h2, p->geo.h3, p->geo.h4};
    rc = ct_assemble(&p->ws, it->cfg.asm_variant, &map, w, p->r[CTDI_R_FX], p->r[CTDI_R_FY],
                     p->r[CTDI_R_FZ], it->nnode, fx, fy, fz);
    double t4 = ctd_wtime();
    if (rc == CT_OK)
        rc = ctdi_pass_timestep(it, p, n, m, rep);
    double t5 = ctd_wtime();
    const double t[6] = {t0, t1, t2, t3, t4, t5};
    ctdi_report_pass(rep, t, n, ns.active);
    return rc;
}
