/*
 * build.c -- ctd_interfaces_build (solver.h): each interface of a scene
 * resolved on the model into a ctd_iface (build.h says how), wrapped as a
 * contact hook of the solver.
 */
#include "build.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errf.h"
#include "iface_internal.h"

/* One hook's context: the interface and the element stiffness it borrows
 * (shared by the hooks of a run: the first hook owns it). */
typedef struct hook_ctx {
    ctd_iface *it;
    ct_real *kelem; /* owned when own_kelem */
    int own_kelem;
    ct_idx nnode; /* kelem's length */
} hook_ctx;

static int hook_step(void *ctx, const ctd_state *s, ct_real *fx, ct_real *fy, ct_real *fz,
                     ctd_contact_report *rep)
{
    hook_ctx *h = ctx;
    ctd_iface_report r;
    ctd_iface_set_dt_max(h->it, (ct_real)s->dt_max);
    int rc = ctd_iface_step(h->it, s->time, (ct_real)s->dt, s->x, s->y, s->z, s->vx, s->vy,
                            s->vz, s->m, fx, fy, fz, &r);
    if (rc == CT_OK && !(r.dt > 0)) {
        /* A stable step of 0 or NaN comes from a contact stiffness that
         * overflowed (Stfac 1e308, or Istf 1 with a huge Stfac): read below
         * as "no limit", it let the run finish with NaN contact energies, or
         * fail later as an unstable step. */
        rc = CT_ERR_ARG;
        snprintf(r.msg, sizeof r.msg,
                 "its stable time step is %g: the contact stiffness overflows (expected a "
                 "smaller Stfac, or a finite Stmax)", (double)r.dt);
    }
    rep->energy = r.e_contact;
    rep->damping = r.e_damp;
    rep->friction = r.e_fric;
    rep->dt_limit = r.dt < CT_DT_NONE ? (double)r.dt : 0.0;
    rep->dt_kin = r.dt_kin < CT_DT_NONE ? (double)r.dt_kin : 0.0;
    rep->force = sqrt(r.force[0] * r.force[0] + r.force[1] * r.force[1] +
                      r.force[2] * r.force[2]);
    for (int d = 0; d < 3; d++)
        rep->fvec[d] = r.force[d];
    rep->active = r.nactive;
    rep->resorts = r.resorts;
    rep->margin = (double)r.margin;
    rep->excluded = r.excluded;
    rep->t_search = r.t[CTD_IT_SEARCH];
    rep->t_narrow = r.t[CTD_IT_NARROW];
    rep->t_force = r.t[CTD_IT_FORCE];
    rep->t_assembly = r.t[CTD_IT_ASSEMBLE];
    if (rc != CT_OK) {
        rep->bad_node = r.dt_node;
        /* The solver names the code; the interface's own words, if any,
         * follow it. */
        snprintf(rep->msg, sizeof rep->msg, "%s", r.msg);
        return rc;
    }
    if (rep->want_fields && rep->pen && rep->node_active)
        ctd_iface_fields(h->it, rep->pen, rep->node_active);
    return CT_OK;
}

static void hook_destroy(void *ctx)
{
    hook_ctx *h = ctx;
    if (!h)
        return;
    ctd_iface_destroy(h->it);
    if (h->own_kelem)
        ct_free(h->kelem);
    free(h);
}

static size_t hook_memory(const void *ctx)
{
    const hook_ctx *h = ctx;
    if (!h)
        return 0;
    /* The element stiffness is counted by the hook that owns it. */
    size_t b = sizeof *h + ctd_iface_memory(h->it);
    return b + (h->own_kelem ? (size_t)h->nnode * sizeof(ct_real) : 0);
}

/* Segment connectivity of a selection (ct_calloc'ed, 4 arrays). */
typedef struct segs {
    ct_idx n;
    ct_idx *q[4];
} segs;

static void segs_free(segs *s)
{
    for (int a = 0; a < 4; a++)
        ct_free(s->q[a]);
    memset(s, 0, sizeof *s);
}

static int segs_of(const ctd_model *m, const ct_surface *su, segs *out)
{
    memset(out, 0, sizeof *out);
    const ct_idx *src[4] = {m->mesh.n1, m->mesh.n2, m->mesh.n3, m->mesh.n4};
    for (int a = 0; a < 4; a++) {
        out->q[a] = ct_calloc((size_t)su->n + 1, sizeof(ct_idx));
        if (!out->q[a]) {
            segs_free(out);
            return CT_ERR_NOMEM;
        }
        for (ct_idx k = 0; k < su->n; k++)
            out->q[a][k] = src[a][su->seg[k]];
    }
    out->n = su->n;
    return CT_OK;
}

/* Lines of the selection's parts whose nodes pass its `where` filter. */
static int lines_of(const ctd_model *m, const ctd_scene_sel *sel, ct_idx **e1, ct_idx **e2,
                    ct_idx *n)
{
    *n = 0;
    *e1 = ct_calloc((size_t)m->nline + 1, sizeof(ct_idx));
    *e2 = ct_calloc((size_t)m->nline + 1, sizeof(ct_idx));
    if (!*e1 || !*e2)
        return CT_ERR_NOMEM;
    const ct_nodes *nd = &m->mesh.nodes;
    for (ct_idx l = 0; l < m->nline; l++) {
        int in = sel->part && sel->part == m->line_part[l];
        for (unsigned k = 0; k < sel->parts_count; k++)
            in |= sel->parts[k] == m->line_part[l];
        ct_idx a = m->l1[l], b = m->l2[l];
        if (!in || !ctd_where_eval(&sel->where, nd->x[a], nd->y[a], nd->z[a]) ||
            !ctd_where_eval(&sel->where, nd->x[b], nd->y[b], nd->z[b]))
            continue;
        (*e1)[*n] = a;
        (*e2)[*n] = b;
        (*n)++;
    }
    return CT_OK;
}

/* Everything resolved for one interface; freed by resolved_free. */
typedef struct resolved {
    segs main, sec_segs;
    ct_nodeset sec, grnd;
    ct_idx *ea1, *ea2, *eb1, *eb2;
    ct_idx nea, neb;
} resolved;

static void resolved_free(resolved *r)
{
    segs_free(&r->main);
    segs_free(&r->sec_segs);
    ct_nodeset_destroy(&r->sec);
    ct_nodeset_destroy(&r->grnd);
    ct_free(r->ea1);
    ct_free(r->ea2);
    ct_free(r->eb1);
    ct_free(r->eb2);
    memset(r, 0, sizeof *r);
}

/* The unique edges of segments (type11.c does the work). */
static int surface_edges(const segs *s, ct_idx **e1, ct_idx **e2, ct_idx *n)
{
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nseg = s->n;
    d.n1 = s->q[0];
    d.n2 = s->q[1];
    d.n3 = s->q[2];
    d.n4 = s->q[3];
    return ctdi_seg_edges(&d, e1, e2, n);
}

static int select_surface(const ctd_model *m, const ctd_scene_sel *sel, segs *out, char *err,
                          size_t len)
{
    ct_surface su;
    int rc = ctd_model_select_surface(m, sel, &su, err, len);
    if (rc != CT_OK)
        return rc;
    rc = segs_of(m, &su, out);
    ct_free(su.seg);
    return rc;
}

/* The sides of interface f: surfaces, nodes, edges, per its type. */
static int resolve(const ctd_model *m, const ctd_scene_interface *f, resolved *r,
                   const char *where, char *err, size_t len)
{
    memset(r, 0, sizeof *r);
    int t = (int)f->type, rc;
    if ((rc = select_surface(m, f->main, &r->main, err, len)) != CT_OK)
        return rc;
    if (t == 11 && r->main.n == 0 &&
        (rc = lines_of(m, f->main, &r->ea1, &r->ea2, &r->nea)) != CT_OK)
        return rc;
    if (t != 11 && r->main.n == 0)
        return ctd_errf(err, len, CT_ERR_ARG, "%s: main selects no surface segment", where);
    if (t == 11 && r->main.n == 0 && r->nea == 0)
        return ctd_errf(err, len, CT_ERR_ARG, "%s: main selects no segment and no line", where);
    if (f->secondary) {
        int surf = t == 3 || t == 6 || t == 11 || t == 24;
        if (surf && (rc = select_surface(m, f->secondary, &r->sec_segs, err, len)) != CT_OK)
            return rc;
        if (t == 11 && r->sec_segs.n == 0 &&
            (rc = lines_of(m, f->secondary, &r->eb1, &r->eb2, &r->neb)) != CT_OK)
            return rc;
        if (t == 3 && r->sec_segs.n == 0)
            return ctd_errf(err, len, CT_ERR_ARG, "%s: secondary selects no surface segment",
                        where);
        if ((t == 5 || t == 7 || t == 6 || t == 24) && (t != 24 || r->sec_segs.n == 0) &&
            (rc = ctd_model_select_nodes(m, f->secondary, &r->sec, err, len)) != CT_OK)
            return rc;
        if ((t == 5 || t == 6 || t == 24) && r->sec_segs.n == 0 && r->sec.n == 0)
            return ctd_errf(err, len, CT_ERR_ARG, "%s: secondary selects no node", where);
        if (t == 11 && r->sec_segs.n == 0 && r->neb == 0)
            return ctd_errf(err, len, CT_ERR_ARG, "%s: secondary selects no segment and no line",
                        where);
    }
    if (f->grnd_IDs &&
        (rc = ctd_model_select_nodes(m, f->grnd_IDs, &r->grnd, err, len)) != CT_OK)
        return rc;
    /* TYPE11 of two sets: the unique edges of each side's segments. */
    if (t == 11 && f->secondary && r->main.n > 0 &&
        (rc = surface_edges(&r->main, &r->ea1, &r->ea2, &r->nea)) != CT_OK)
        return rc;
    if (t == 11 && r->sec_segs.n > 0 &&
        (rc = surface_edges(&r->sec_segs, &r->eb1, &r->eb2, &r->neb)) != CT_OK)
        return rc;
    return CT_OK;
}

/* Gather per-segment inputs of the selected segments (su indices into the
 * model) into arrays of the selection. */
typedef struct seg_inputs {
    ct_real *E, *t, *B, *A, *V;
} seg_inputs;

static void seg_inputs_free(seg_inputs *g)
{
    ct_free(g->E);
    ct_free(g->t);
    ct_free(g->B);
    ct_free(g->A);
    ct_free(g->V);
    memset(g, 0, sizeof *g);
}

static int seg_inputs_of(const ctd_build_data *bd, const ct_idx *sel, ct_idx n, seg_inputs *g)
{
    memset(g, 0, sizeof *g);
    ct_real **dst[5] = {&g->E, &g->t, &g->B, &g->A, &g->V};
    const ct_real *src[5] = {bd->seg_E, bd->seg_t, bd->seg_B, bd->seg_A, bd->seg_V};
    for (int i = 0; i < 5; i++) {
        if (!(*dst[i] = ct_calloc((size_t)n + 1, sizeof(ct_real)))) {
            seg_inputs_free(g);
            return CT_ERR_NOMEM;
        }
        for (ct_idx k = 0; k < n; k++)
            (*dst[i])[k] = src[i][sel[k]];
    }
    return CT_OK;
}

/* The card of scene interface f as a ctd_iface_cfg. */
static ctd_iface_cfg card(const ctd_scene_interface *f)
{
    ctd_iface_cfg c = ctd_iface_default_cfg((int)f->type);
    c.algo = (ct_search_algo)f->search;
    c.Istf = (int)f->Istf;
    c.Stfac = (ct_real)f->Stfac;
    c.Stmin = (ct_real)f->Stmin;
    c.Stmax = (ct_real)f->Stmax;
    c.gap = (ct_real)f->gap;
    c.Igap0 = (int)f->Igap0;
    c.Gap_max_s = (ct_real)f->Gap_max_s;
    c.Gap_max_m = (ct_real)f->Gap_max_m;
    c.Ipen0 = (int)f->Ipen0;
    c.Inacti = (int)f->Inacti;
    c.Ipen_max = (ct_real)f->Ipen_max;
    c.VisS = (ct_real)f->VisS;
    c.Ifric = (int)f->Ifric;
    c.Fric = (ct_real)f->Fric;
    const double C[6] = {f->C1, f->C2, f->C3, f->C4, f->C5, f->C6};
    for (int i = 0; i < 6; i++)
        c.C[i] = (ct_real)C[i];
    c.Ifiltr = (int)f->Ifiltr;
    c.Irem_gap = (int)f->Irem_gap;
    c.Xfreq = (ct_real)f->Xfreq;
    c.Tstart = f->Tstart;
    c.Tstop = f->Tstop;
    c.margin = (ct_real)f->margin;
    c.pressure_area = f->pressure_area;
    return c;
}

/* Mean stiffness (Stfac not applied) of selected segments: the constant K
 * of a TYPE11 interface whose card does not give it (Istf != 1). */
static ct_real mean_seg_stiffness(const ctd_build_data *bd, const segs *s, const ct_idx *sel)
{
    double sum = 0;
    ct_idx cnt = 0;
    for (ct_idx k = 0; k < s->n; k++) {
        ct_idx j = sel[k];
        double v = bd->seg_t[j] > 0 ? (double)bd->seg_E[j] * bd->seg_t[j]
                   : bd->seg_V[j] > 0
                       ? (double)bd->seg_B[j] * bd->seg_A[j] * bd->seg_A[j] / bd->seg_V[j]
                       : 0;
        if (v > 0) {
            sum += v;
            cnt++;
        }
    }
    return cnt ? (ct_real)(sum / (double)cnt) : 0;
}

/* The TYPE6 force curve of the card (curve_count points [p, F]). */
static int curve_of(const ctd_scene_interface *f, ctd_iface_cfg *c, ct_real **p, ct_real **F)
{
    *p = ct_calloc((size_t)f->curve_count + 1, sizeof(ct_real));
    *F = ct_calloc((size_t)f->curve_count + 1, sizeof(ct_real));
    if (!*p || !*F)
        return CT_ERR_NOMEM;
    for (unsigned k = 0; k < f->curve_count; k++) {
        (*p)[k] = (ct_real)f->curve[k][0];
        (*F)[k] = (ct_real)f->curve[k][1];
    }
    c->ncurve = (ct_idx)f->curve_count;
    c->curve_p = *p;
    c->curve_f = *F;
    return CT_OK;
}

/* The mass of one side of a TYPE6 interface (the unique nodes of up to
 * four lists): the mass of the rigid body they all belong to, infinite
 * when that body is held in all three directions (it does not move, so it
 * sets no step), otherwise the sum of their nodal masses. */
static double side_mass(const ctd_model *m, const ct_idx *const l4[4], ct_idx cnt)
{
    const ct_idx *const lists[6] = {l4[0], l4[1], l4[2], l4[3], NULL, NULL};
    const ct_idx counts[6] = {cnt, l4[1] ? cnt : 0, l4[2] ? cnt : 0, l4[3] ? cnt : 0, 0, 0};
    ct_idx *u = NULL;
    int64_t n = ctdi_unique_nodes(m->mesh.nodes.n, lists, counts, &u);
    int body = -2;
    double sum = 0;
    for (int64_t k = 0; k < n; k++) {
        int b = m->node_body[u[k]];
        body = body == -2 || body == b ? b : -1;
        sum += (double)m->mesh.nodes.m[u[k]];
    }
    ct_free(u);
    if (body >= 0) {
        const ctd_model_body *bd = &m->body[body];
        if (bd->driven && bd->dof[0] && bd->dof[1] && bd->dof[2])
            return INFINITY;
        return bd->rigid.mass;
    }
    return sum;
}

/* M_min of the TYPE6 step 0.1 sqrt(M_min / K): the smaller of the two
 * sides' masses; 0 (the interface then sums the nodal masses) when
 * neither side can move. */
static ct_real type6_mass_min(const ctd_model *m, const resolved *r)
{
    const ct_idx *const mn[4] = {r->main.q[0], r->main.q[1], r->main.q[2], r->main.q[3]};
    double mm = side_mass(m, mn, r->main.n), ms;
    if (r->sec_segs.n > 0) {
        const ct_idx *const sn[4] = {r->sec_segs.q[0], r->sec_segs.q[1], r->sec_segs.q[2],
                                     r->sec_segs.q[3]};
        ms = side_mass(m, sn, r->sec_segs.n);
    } else {
        const ct_idx *const sn[4] = {r->sec.node, NULL, NULL, NULL};
        ms = side_mass(m, sn, r->sec.n);
    }
    double v = mm < ms ? mm : ms;
    return isfinite(v) && v > 0 ? (ct_real)v : 0;
}

/* pressure_area secondary with a pressure-dependent law (Ifric 1, 2):
 * every secondary node needs an area, so every node of the secondary node
 * selection and of grnd_IDs must be a corner of a surface segment of the
 * model (the other secondary nodes are corners of the interface's own
 * segments). */
static int parea_check(const ctd_model *m, const ctd_scene_interface *f, unsigned idx,
                       const resolved *r, char *err, size_t len)
{
    if (f->pressure_area != CTD_PAREA_SECONDARY || (f->Ifric != 1 && f->Ifric != 2))
        return CT_OK;
    const ct_mesh *me = &m->mesh;
    uint8_t *on = calloc((size_t)me->nodes.n + 1, 1);
    if (!on)
        return ctd_errf(err, len, CT_ERR_NOMEM, "%s: out of memory", m->scene->path);
    const ct_idx *const q[4] = {me->n1, me->n2, me->n3, me->n4};
    for (ct_idx s = 0; s < me->nseg; s++)
        for (int c = 0; c < 4; c++)
            on[q[c][s]] = 1;
    const ct_nodeset *set[2] = {&r->sec, &r->grnd};
    static const char *const what[2] = {"secondary", "grnd_IDs"};
    int rc = CT_OK;
    for (int i = 0; i < 2 && rc == CT_OK; i++)
        for (ct_idx k = 0; k < set[i]->n; k++)
            if (!on[set[i]->node[k]]) {
                rc = ctd_errf(err, len, CT_ERR_ARG,
                          "%s:%d: interfaces[%u].pressure_area: node %lld of the %s "
                          "selection is a corner of no surface segment (shell or solid "
                          "face), so it has no area for the pressure; expected main, or "
                          "secondary nodes on surfaces",
                          m->scene->path, f->line, idx, (long long)m->node_id[set[i]->node[k]],
                          what[i]);
                break;
            }
    free(on);
    return rc;
}

static int build_one(const ctd_model *m, const ctd_scene_interface *f, unsigned idx,
                     const ctd_build_data *bd, ct_real *kelem, int own_kelem,
                     ctd_contact_hook *hook, char *err, size_t len)
{
    char where[256];
    snprintf(where, sizeof where, "%s:%d: interfaces[%u] (%s, type %lld)", m->scene->path,
             f->line, idx, f->label, (long long)f->type);
    int t = (int)f->type;
    resolved r;
    int rc = resolve(m, f, &r, where, err, len);
    if (rc == CT_OK)
        rc = parea_check(m, f, idx, &r, err, len);
    ct_surface msu = {0, NULL}, ssu = {0, NULL};
    seg_inputs gm, gs;
    memset(&gm, 0, sizeof gm);
    memset(&gs, 0, sizeof gs);
    /* The model segment indices of each side (for the stiffness inputs). */
    if (rc == CT_OK)
        rc = ctd_model_select_surface(m, f->main, &msu, err, len);
    if (rc == CT_OK && r.sec_segs.n > 0)
        rc = ctd_model_select_surface(m, f->secondary, &ssu, err, len);
    if (rc == CT_OK)
        rc = seg_inputs_of(bd, msu.seg, msu.n, &gm);
    if (rc == CT_OK)
        rc = seg_inputs_of(bd, ssu.seg, ssu.n, &gs);
    ctd_iface_cfg c = card(f);
    ct_real *curve_p = NULL, *curve_f = NULL;
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = m->mesh.nodes.n;
    d.nseg = r.main.n;
    d.n1 = r.main.q[0];
    d.n2 = r.main.q[1];
    d.n3 = r.main.q[2];
    d.n4 = r.main.q[3];
    d.nsec = r.sec.n;
    d.sec = r.sec.node;
    d.nsseg = r.sec_segs.n;
    d.s1 = r.sec_segs.q[0];
    d.s2 = r.sec_segs.q[1];
    d.s3 = r.sec_segs.q[2];
    d.s4 = r.sec_segs.q[3];
    d.ngrnd = r.grnd.n;
    d.grnd = r.grnd.node;
    d.nea = r.nea;
    d.ea1 = r.ea1;
    d.ea2 = r.ea2;
    d.neb = r.neb;
    d.eb1 = r.eb1;
    d.eb2 = r.eb2;
    d.seg_E = gm.E;
    d.seg_t = gm.t;
    d.seg_B = gm.B;
    d.seg_A = gm.A;
    d.seg_V = gm.V;
    d.ssg_E = gs.E;
    d.ssg_t = gs.t;
    d.ssg_B = gs.B;
    d.ssg_A = gs.A;
    d.ssg_V = gs.V;
    d.node_B = bd->node_B;
    d.node_vnode = bd->node_vnode;
    d.node_et = bd->node_et;
    d.gap_node = bd->gap_node;
    d.nmseg = m->mesh.nseg;
    d.m1 = m->mesh.n1;
    d.m2 = m->mesh.n2;
    d.m3 = m->mesh.n3;
    d.m4 = m->mesh.n4;
    if (rc == CT_OK) {
        /* Sides: self contact, surface to surface, shells two-sided. */
        c.self = f->self && t != 11;
        c.symmetric = t == 24 && r.sec_segs.n > 0;
        int shells = r.main.n > 0;
        for (ct_idx k = 0; k < msu.n; k++)
            shells &= bd->seg_t[msu.seg[k]] > 0;
        if (t == 24) {
            c.two_sided = shells;
            if (shells && c.gap == 0 && c.Igap0 == 0)
                c.Igap0 = 1;
        }
        if (t == 11 && c.Istf != 1) {
            d.K = mean_seg_stiffness(bd, &r.main, msu.seg);
            if (!(d.K > 0))
                rc = ctd_errf(err, len, CT_ERR_ARG,
                          "%s: edges of lines have no stiffness of their own: give Istf: 1 "
                          "and Stfac: the contact stiffness (N/m)", where);
        }
        if ((t == 3 || t == 5) && shells) {
            /* Shells: both faces, the gap half the largest thickness when
             * the card gives none. (TYPE6 stays one-sided whatever the
             * surface: its penetrations are the crush of the curve, far
             * deeper than any shell's half thickness.) */
            c.two_sided = 1;
            ct_real tmax = 0;
            for (ct_idx k = 0; k < msu.n; k++)
                tmax = bd->seg_t[msu.seg[k]] > tmax ? bd->seg_t[msu.seg[k]] : tmax;
            if (c.gap == 0)
                c.gap = tmax / 2;
        }
        if (t == 6) {
            d.mass_min = type6_mass_min(m, &r);
            rc = curve_of(f, &c, &curve_p, &curve_f);
            if (rc != CT_OK)
                ctd_errf(err, len, rc, "%s: out of memory", where);
        }
    }
    ctd_iface *it = NULL;
    if (rc == CT_OK) {
        ct_diag dg = {0, -1, ""};
        rc = ctd_iface_init(&it, &c, &d, &dg);
        /* The kernel's message, after the code unless it says it. */
        if (rc != CT_OK && strstr(dg.msg, ct_strerror(rc)))
            ctd_errf(err, len, rc, "%s: %s", where, dg.msg);
        else if (rc != CT_OK)
            ctd_errf(err, len, rc, "%s: %s%s%s", where, ct_strerror(rc), dg.msg[0] ? ": " : "",
                 dg.msg);
    }
    if (rc == CT_OK) {
        char msg[400];
        rc = ctd_iface_check_reach(it, m->mesh.nodes.x, m->mesh.nodes.y, m->mesh.nodes.z, msg,
                                   sizeof msg);
        if (rc != CT_OK) {
            ctd_errf(err, len, rc, "%s: %s", where, msg);
            ctd_iface_destroy(it);
        }
    }
    resolved_free(&r);
    ct_free(msu.seg);
    ct_free(ssu.seg);
    seg_inputs_free(&gm);
    seg_inputs_free(&gs);
    ct_free(curve_p);
    ct_free(curve_f);
    /* The steps that return a code alone (the selections, the per-segment
     * inputs, the edges, out of memory) are named by the interface. */
    if (rc != CT_OK && err && len > 0 && !err[0])
        ctd_errf(err, len, rc, "%s: %s", where, ct_strerror(rc));
    if (rc != CT_OK)
        return rc;
    hook_ctx *h = calloc(1, sizeof *h);
    if (!h) {
        ctd_iface_destroy(it);
        return ctd_errf(err, len, CT_ERR_NOMEM, "%s: out of memory", where);
    }
    h->it = it;
    h->kelem = kelem;
    h->own_kelem = own_kelem;
    h->nnode = m->mesh.nodes.n;
    ctd_iface_set_kelem(it, kelem);
    hook->name = f->label;
    hook->type = t;
    /* TYPE11's edge search is its own: direct, or a bucket grid for any
     * other choice (`--search` sets every interface's). */
    hook->search = ct_search_algo_name(t == 11 && f->search != CT_SEARCH_DIRECT
                                           ? CT_SEARCH_BUCKET
                                           : (ct_search_algo)f->search);
    hook->ctx = h;
    hook->contact_step = hook_step;
    hook->destroy = hook_destroy;
    hook->memory = hook_memory;
    ctd_iface_self_gap_note(it, m->mesh.nodes.x, m->mesh.nodes.y, m->mesh.nodes.z, hook->note,
                            sizeof hook->note);
    return CT_OK;
}

int ctd_interfaces_build(const ctd_model *m, const ctd_scene *sc, ctd_contact_hook **hooks,
                         int *nhook, char *err, size_t errlen)
{
    *hooks = NULL;
    *nhook = 0;
    if (err && errlen > 0)
        err[0] = 0;
    if (!m || !sc)
        return ctd_errf(err, errlen, CT_ERR_ARG, "no model or scene");
    unsigned n = sc->interfaces_count;
    if (n == 0)
        return CT_OK;
    ctd_contact_hook *h = calloc(n, sizeof *h);
    ctd_build_data bd;
    int rc = h ? ctd_build_data_init(&bd, m) : CT_ERR_NOMEM;
    if (rc != CT_OK) {
        free(h);
        return ctd_errf(err, errlen, rc, "%s: out of memory building the interfaces", sc->path);
    }
    /* The first hook owns the element stiffness; the others borrow it. */
    ct_real *kelem = bd.kelem;
    bd.kelem = NULL;
    unsigned built = 0;
    for (unsigned i = 0; i < n && rc == CT_OK; i++) {
        rc = build_one(m, &sc->interfaces[i], i, &bd, kelem, i == 0, &h[i], err, errlen);
        if (rc == CT_OK)
            built++;
    }
    ctd_build_data_destroy(&bd);
    if (rc != CT_OK) {
        for (unsigned i = 0; i < built; i++)
            h[i].destroy(h[i].ctx);
        if (built == 0)
            ct_free(kelem);
        free(h);
        return rc;
    }
    *hooks = h;
    *nhook = (int)n;
    return CT_OK;
}
