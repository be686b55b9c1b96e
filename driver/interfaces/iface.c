/*
 * iface.c -- the interface object (iface.h): parameter checks, the data
 * shared by every type (node stiffness, node gaps), the pass builder of the
 * node-to-surface types, the step dispatch with Tstart/Tstop and the
 * report, and small helpers of iface_internal.h.
 */
#include "iface_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


int ctdi_fail(ct_diag *diag, int code, int64_t index, const char *msg)
{
    if (diag) {
        diag->code = code;
        diag->index = index;
        snprintf(diag->msg, sizeof diag->msg, "%s", msg);
    }
    return code;
}

/* True for the types of the seed 000 family (3, 5, 6). */
static int family356(int type) { return type == 3 || type == 5 || type == 6; }

ctd_iface_cfg ctd_iface_default_cfg(int type)
{
    ctd_iface_cfg c;
    memset(&c, 0, sizeof c);
    c.type = type;
    c.algo = CT_SEARCH_BUCKET;
    c.filter = CT_FILTER_HULL;
    c.quad = CT_QUAD_4TRI;
    c.asm_variant = CT_ASM_COLOUR;
    c.Stfac = 1;
    c.VisS = type == 24 ? (ct_real)1.0 : (ct_real)0.05;
    c.two_sided = type == 7 || type == 11;
    c.self = type == 7 || type == 11;
    c.kt_scale = 1;
    if (family356(type)) {
        /* Radioss TYPE3/5/6: the engine's topological search (TYPE6 keeps
         * the bucket search: rigid bodies may move far in one step), the
         * closed-form projection, the seed's series scale 0.2, no damping. */
        c.algo = type == 6 ? CT_SEARCH_BUCKET : CT_SEARCH_TOPO;
        c.quad = CT_QUAD_CLOSED;
        c.Stfac = (ct_real)CT_STIFF_SCALE_DEFAULT;
        c.VisS = 0;
    }
    return c;
}

ct_idx *ctdi_copy_idx(ct_idx n, const ct_idx *a)
{
    ct_idx *c = ct_calloc((size_t)(n > 0 ? n : 1), sizeof(ct_idx));
    if (c && n > 0)
        memcpy(c, a, (size_t)n * sizeof(ct_idx));
    return c;
}

int64_t ctdi_unique_nodes(ct_idx nnode, const ct_idx *const lists[6], const ct_idx counts[6],
                          ct_idx **out)
{
    *out = NULL;
    int64_t tot = 0;
    for (int l = 0; l < 6; l++)
        if (lists[l] && counts[l] > 0)
            tot += counts[l];
    if (tot > INT32_MAX)
        return CT_ERR_TOOBIG;
    /* A mark per node, then the marked nodes in increasing order into an
     * array of their exact count (the lists hold each node several times:
     * 4 nseg entries for about nseg nodes; a sorted copy of them all, kept
     * whole, held three times the memory the result needs). */
    uint8_t *mark = ct_calloc((size_t)(nnode > 0 ? nnode : 1), 1);
    if (!mark)
        return CT_ERR_NOMEM;
    for (int l = 0; l < 6; l++) {
        if (!lists[l])
            continue;
        for (ct_idx i = 0; i < counts[l]; i++) {
            ct_idx v = lists[l][i];
            if (v < 0 || v >= nnode) {
                ct_free(mark);
                return CT_ERR_RANGE;
            }
            mark[v] = 1;
        }
    }
    int64_t u = 0;
    for (ct_idx v = 0; v < nnode; v++)
        u += mark[v];
    ct_idx *a = ct_calloc((size_t)(u > 0 ? u : 1), sizeof(ct_idx));
    if (!a) {
        ct_free(mark);
        return CT_ERR_NOMEM;
    }
    int64_t k = 0;
    for (ct_idx v = 0; v < nnode; v++)
        if (mark[v])
            a[k++] = v;
    ct_free(mark);
    *out = a;
    return u;
}

double ctdi_mean_seg_edge(ct_idx nseg, const ct_idx *n1, const ct_idx *n2, const ct_idx *n3,
                          const ct_idx *n4, const ct_real *x, const ct_real *y,
                          const ct_real *z)
{
    double sum = 0;
    int64_t cnt = 0;
    for (ct_idx j = 0; j < nseg; j++) {
        ct_idx v[4] = {n1[j], n2[j], n3[j], n4[j]};
        int nv = v[3] == v[2] ? 3 : 4;
        for (int a = 0; a < nv; a++) {
            ct_idx p = v[a], q = v[(a + 1) % nv];
            double dx = (double)x[p] - (double)x[q], dy = (double)y[p] - (double)y[q],
                   dz = (double)z[p] - (double)z[q];
            sum += sqrt(dx * dx + dy * dy + dz * dz);
            cnt++;
        }
    }
    return cnt ? sum / (double)cnt : 0.0;
}

int ctdi_seg_stiffness(ct_real stfac, ct_idx nseg, const ct_real *E, const ct_real *t,
                       const ct_real *B, const ct_real *A, const ct_real *V, ct_real **out,
                       ct_diag *diag)
{
    *out = NULL;
    if (!E && !t && !B && !A && !V)
        return CT_OK;
    if ((!E) != (!t) || (!B) != (!A) || (!B) != (!V))
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "Segment stiffness inputs must come as E with t, and B with A and V.");
    ct_real *k = ct_calloc((size_t)(nseg > 0 ? nseg : 1), sizeof(ct_real));
    if (!k)
        return CT_ERR_NOMEM;
    int rc = ct_seg_stiffness(nseg, stfac, E, t, B, A, V, k, diag);
    if (rc != CT_OK) {
        ct_free(k);
        return rc;
    }
    *out = k;
    return CT_OK;
}

ct_real *ctdi_seg_gap(const ct_real *gnode, ct_idx nseg, const ct_idx *n1, const ct_idx *n2,
                      const ct_idx *n3, const ct_idx *n4)
{
    if (!gnode)
        return NULL;
    ct_real *g = ct_calloc((size_t)(nseg > 0 ? nseg : 1), sizeof(ct_real));
    if (!g)
        return NULL;
    for (ct_idx j = 0; j < nseg; j++) {
        ct_real a = gnode[n1[j]], b = gnode[n2[j]], c = gnode[n3[j]], d = gnode[n4[j]];
        ct_real v = a > b ? a : b;
        v = v > c ? v : c;
        g[j] = v > d ? v : d;
    }
    return g;
}

int ctdi_add_pass(ctd_iface *it, const ct_idx *const lists[6], const ct_idx counts[6],
                  const ctdi_surf *s, int need_k, int reverse, int law, const char *what,
                  ct_diag *diag)
{
    const ctd_iface_cfg *c = &it->cfg;
    char msg[200];
    if (it->npass >= 2)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "An interface has at most two passes.");
    if (s->nseg <= 0 || !s->q1 || !s->q2 || !s->q3 || !s->q4) {
        snprintf(msg, sizeof msg, "TYPE%d needs %s.", c->type, what);
        return ctdi_fail(diag, CT_ERR_ARG, -1, msg);
    }
    if (c->two_sided && !(c->gap > 0)) {
        snprintf(msg, sizeof msg, "TYPE%d two-sided (shell) contact needs a gap > 0.", c->type);
        return ctdi_fail(diag, CT_ERR_ARG, -1, msg);
    }
    ct_real *kseg = NULL;
    if (need_k && it->kconst == 0) {
        int rc = ctdi_seg_stiffness(c->Stfac, s->nseg, s->E, s->t, s->B, s->A, s->V, &kseg,
                                    diag);
        if (rc != CT_OK)
            return rc;
        if (!kseg) {
            snprintf(msg, sizeof msg,
                     "TYPE%d needs a stiffness K or the stiffness inputs of its %s (E with t, "
                     "or B with A and V).",
                     c->type, what);
            return ctdi_fail(diag, CT_ERR_ARG, -1, msg);
        }
    }
    ct_idx *sec = NULL;
    int64_t ns = ctdi_unique_nodes(it->nnode, lists, counts, &sec);
    if (ns < 0) {
        ct_free(kseg);
        snprintf(msg, sizeof msg, "A TYPE%d secondary node index is out of range.", c->type);
        return ctdi_fail(diag, (int)ns, -1, msg);
    }
    /* The pass owns sec and kseg from here, even when the setup fails. */
    ctdi_pass *p = &it->pass[it->npass++];
    int rc = ctdi_pass_setup(it, p, (ct_idx)ns, sec, s->nseg, s->q1, s->q2, s->q3, s->q4, kseg,
                             1, c->two_sided != 0, law);
    if (rc != CT_OK) {
        snprintf(msg, sizeof msg, "TYPE%d setup failed against its %s", c->type, what);
        return ctdi_pass_setup_fail(diag, rc, msg);
    }
    p->reverse = reverse;
    return CT_OK;
}

/* Common checks of the card. */
static int check_cfg(const ctd_iface_cfg *c, ct_diag *diag)
{
    if (c->type != 7 && c->type != 11 && c->type != 24 && !family356(c->type))
        return ctdi_fail(diag, CT_ERR_ARG, c->type,
                         "Interface type must be 3, 5, 6, 7, 11 or 24.");
    if (c->algo < 0 || c->algo >= CT_SEARCH_NALGO || c->quad < 0 ||
        c->quad >= CT_QUAD_NMETHOD || c->asm_variant < 0 || c->asm_variant >= CT_ASM_NVARIANT)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "Unknown search, projection or assembly.");
    if (c->algo == CT_SEARCH_TOPO && (c->type == 7 || (c->type == 24 && c->self)))
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "The topological search cannot find self contact (TYPE7, TYPE24 on "
                         "one surface): a node's closest main node is itself.");
    if (!(c->Stfac > 0) || !(c->Stmin >= 0) || !(c->Stmax >= 0) ||
        (c->Stmax > 0 && c->Stmax < c->Stmin))
        return ctdi_fail(diag, CT_ERR_ARG, -1, "Stfac must be > 0 and 0 <= Stmin <= Stmax.");
    if (!(c->gap >= 0) || !(c->Gap_max_s >= 0) || !(c->Gap_max_m >= 0) ||
        !(c->Ipen_max >= 0) || !(c->VisS >= 0) || !(c->margin >= 0) ||
        !(c->kt_scale >= 0))
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "gap, Gap_max_s, Gap_max_m, Ipen_max, VisS, margin and kt_scale "
                         "must be >= 0.");
    if (c->Ifric < 0 || c->Ifric >= CT_FRIC_NLAW || c->Ifiltr < 0 || c->Ifiltr > 3)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "Ifric must be 0..4 and Ifiltr 0..3.");
    if (c->Irem_gap < 0 || c->Irem_gap > 2 ||
        (c->Irem_gap == 2 && c->type != 7 && c->type != 11 && !(c->type == 24 && c->self)))
        return ctdi_fail(diag, CT_ERR_ARG, c->Irem_gap,
                         "Irem_gap must be 0, 1 or 2, and 2 only for types 7, 11 and 24 on one "
                         "surface (self contact).");
    if (!(c->Tstart >= 0) || !(c->Tstop >= 0) || (c->Tstop > 0 && c->Tstop <= c->Tstart))
        return ctdi_fail(diag, CT_ERR_ARG, -1, "Need Tstart >= 0 and Tstop > Tstart when set.");
    if (c->pressure_area != CTD_PAREA_MAIN &&
        (c->pressure_area != CTD_PAREA_SECONDARY || c->type == 11))
        return ctdi_fail(diag, CT_ERR_ARG, c->pressure_area,
                         "pressure_area must be main, or secondary for the node-segment "
                         "types (3, 5, 6, 7, 24).");
    return CT_OK;
}

int ctd_iface_init(ctd_iface **out, const ctd_iface_cfg *cfg, const ctd_iface_data *d,
                   ct_diag *diag)
{
    if (!out)
        return CT_ERR_ARG;
    *out = NULL;
    if (!cfg || !d || d->nnode < 0)
        return ctdi_fail(diag, CT_ERR_ARG, -1, "Missing configuration or data.");
    int rc = check_cfg(cfg, diag);
    if (rc != CT_OK)
        return rc;
    ctd_iface *it = calloc(1, sizeof *it);
    if (!it)
        return CT_ERR_NOMEM;
    it->cfg = *cfg;
    /* The curve is TYPE6's (its setup swaps in owned copies); no other
     * type keeps the caller's pointers. */
    if (cfg->type != 6) {
        it->cfg.ncurve = 0;
        it->cfg.curve_p = it->cfg.curve_f = NULL;
    }
    if (!(it->cfg.kt_scale > 0))
        it->cfg.kt_scale = 1;
    it->nnode = d->nnode;
    it->kconst = d->K > 0 ? d->K : 0;
    it->margin = cfg->margin;
    it->coef[0] = cfg->Fric;
    for (int i = 0; i < 6; i++)
        it->coef[i + 1] = cfg->C[i];
    it->fric_law = cfg->Ifric;
    it->fric_on = cfg->Ifric != CT_FRIC_COULOMB || cfg->Fric > 0;
    if (it->fric_on)
        rc = ct_friction_check(it->fric_law, it->coef, diag);
    /* Per-node data. */
    if (rc == CT_OK && d->gap_node) {
        it->gnode = ct_calloc((size_t)(d->nnode > 0 ? d->nnode : 1), sizeof(ct_real));
        if (!it->gnode)
            rc = CT_ERR_NOMEM;
        else
            for (ct_idx i = 0; i < d->nnode; i++) {
                if (!(d->gap_node[i] >= 0)) {
                    rc = ctdi_fail(diag, CT_ERR_ARG, i, "A node gap is negative or NaN.");
                    break;
                }
                it->gnode[i] = d->gap_node[i];
            }
    }
    if (rc == CT_OK && it->kconst == 0 && (d->node_B || d->node_et)) {
        it->knode = ct_calloc((size_t)(d->nnode > 0 ? d->nnode : 1), sizeof(ct_real));
        if (!it->knode)
            rc = CT_ERR_NOMEM;
        else
            rc = ct_node_stiffness(d->nnode, d->node_B, d->node_vnode, d->node_et, it->knode,
                                   diag);
        for (ct_idx i = 0; rc == CT_OK && i < d->nnode; i++)
            it->knode[i] *= cfg->Stfac;
    }
    if (rc == CT_OK && cfg->type != 6 && cfg->type != 11 &&
        !(it->kc = ct_calloc((size_t)(d->nnode > 0 ? d->nnode : 1), sizeof(ct_real))))
        rc = CT_ERR_NOMEM;
    if (rc == CT_OK) {
        switch (cfg->type) {
        case 3: rc = ctdi_type3_setup(it, d, diag); break;
        case 5: rc = ctdi_type5_setup(it, d, diag); break;
        case 6: rc = ctdi_type6_setup(it, d, diag); break;
        case 7: rc = ctdi_type7_setup(it, d, diag); break;
        case 24: rc = ctdi_type24_setup(it, d, diag); break;
        default: rc = ctdi_type11_setup(it, d, diag); break;
        }
    }
    if (rc == CT_OK)
        rc = ctdi_area_setup(it, d, diag);
    if (rc != CT_OK) {
        ctd_iface_destroy(it);
        return rc;
    }
    *out = it;
    return CT_OK;
}

void ctd_iface_destroy(ctd_iface *it)
{
    if (!it)
        return;
    for (int i = 0; i < 2; i++)
        ctdi_pass_free(&it->pass[i]);
    ctdi_type11_free(it->ep);
    ct_free(it->curve_p);
    ct_free(it->curve_f);
    ct_free(it->knode);
    ct_free(it->gnode);
    ct_free(it->kc);
    ctdi_area_free(it);
    free(it);
}

void ctd_iface_set_kelem(ctd_iface *it, const ct_real *kelem)
{
    if (it)
        it->kelem = kelem;
}

void ctd_iface_set_dt_max(ctd_iface *it, ct_real dt_max)
{
    if (it)
        it->dt_max = dt_max > 0 && dt_max < CT_DT_NONE ? dt_max : 0;
}

void ctd_iface_force_resort(ctd_iface *it)
{
    if (!it)
        return;
    for (int i = 0; i < it->npass; i++)
        it->pass[i].need_sort = 1;
    if (it->ep)
        ctdi_type11_force_resort(it->ep);
}

int ctd_iface_type(const ctd_iface *it) { return it->cfg.type; }


size_t ctd_iface_memory(const ctd_iface *it)
{
    size_t b = sizeof *it;
    if (it->knode)
        b += (size_t)it->nnode * sizeof(ct_real);
    if (it->gnode)
        b += (size_t)it->nnode * sizeof(ct_real);
    if (it->kc)
        b += (size_t)it->nnode * sizeof(ct_real);
    b += 2 * (size_t)it->ncurve * sizeof(ct_real);
    for (int i = 0; i < it->npass; i++)
        b += ctdi_pass_memory(&it->pass[i], it->nnode);
    if (it->ep)
        b += ctdi_type11_memory(it->ep, it->nnode);
    return b + ctdi_area_memory(it);
}

static void report_zero(ctd_iface_report *rep)
{
    memset(rep, 0, sizeof *rep);
    rep->dt_nodal = rep->dt_kin = rep->dt_tunnel = rep->dt_curve = rep->dt = CT_DT_NONE;
    rep->dt_node = -1;
}

int ctd_iface_step(ctd_iface *it, double time, ct_real dt, const ct_real *x, const ct_real *y,
                   const ct_real *z, const ct_real *vx, const ct_real *vy, const ct_real *vz,
                   const ct_real *m, ct_real *fx, ct_real *fy, ct_real *fz,
                   ctd_iface_report *rep)
{
    ctd_iface_report local;
    if (!rep)
        rep = &local;
    report_zero(rep);
    if (!it || !x || !y || !z || !vx || !vy || !vz || !m || !fx || !fy || !fz ||
        !(dt >= 0))
        return CT_ERR_ARG;
    int on = time >= it->cfg.Tstart && (!(it->cfg.Tstop > 0) || time <= it->cfg.Tstop);
    rep->resorts = it->resorts;
    rep->margin = it->margin;
    rep->deactivated = it->deactivated;
    rep->excluded = it->excluded;
    if (!on) {
        if (it->was_on)
            ctd_iface_force_resort(it);
        it->was_on = 0;
        return CT_OK;
    }
    it->was_on = 1;
    rep->on = 1;
    int rc = CT_OK;
    it->msg[0] = 0;
    ctdi_nodal_begin(it);
    for (int i = 0; i < it->npass && rc == CT_OK; i++)
        rc = ctdi_pass_step(it, &it->pass[i], dt, x, y, z, vx, vy, vz, m, fx, fy, fz, rep);
    if (rc == CT_OK)
        ctdi_nodal_finish(it, m, rep);
    if (rc == CT_OK && it->ep)
        rc = ctdi_type11_step(it, dt, x, y, z, vx, vy, vz, m, fx, fy, fz, rep);
    rep->dt = rep->dt_nodal;
    if (rep->dt_kin < rep->dt)
        rep->dt = rep->dt_kin;
    if (rep->dt_tunnel < rep->dt)
        rep->dt = rep->dt_tunnel;
    if (rep->dt_curve < rep->dt)
        rep->dt = rep->dt_curve;
    rep->resorts = it->resorts;
    rep->margin = it->margin;
    rep->deactivated = it->deactivated;
    rep->excluded = it->excluded;
    if (rc != CT_OK)
        snprintf(rep->msg, sizeof rep->msg, "%s", it->msg);
    return rc;
}
