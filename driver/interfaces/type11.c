/*
 * type11.c -- TYPE11 edge-to-edge contact (seed 002, Figure 9): the edges
 * of set A against themselves (self) or against set B; a search over edge
 * boxes (direct, or a bucket grid), the re-sort criterion, the edge-edge
 * narrow phase, the TYPE7 law with damping, and the forces on the four edge
 * nodes with the weights of the contact points (force and moment balanced),
 * assembled race-free (ct_asm_map_edge, colouring by default).
 *
 * The search and the re-sort criterion are in type11_search.c; the
 * names "topological" and "bsp" select its bucket grid.
 */
#include "type11_internal.h"

#include "ct_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void free_pairs(ctdi_epass *e)
{
    for (int i = 0; i < 4; i++)
        ct_free(e->sl[i]);
    for (int i = 0; i < E_N; i++)
        ct_free(e->r[i]);
    ct_free(e->flag);
    ct_free(e->iflag);
    memset(e->sl, 0, sizeof e->sl);
    memset(e->r, 0, sizeof e->r);
    e->flag = NULL;
    e->iflag = NULL;
    e->cap = 0;
}

int ctdi_epass_grow_ids(ctdi_epass *e, size_t n)
{
    if (n <= e->cap_ids && e->pa)
        return CT_OK;
    ct_free(e->pa);
    ct_free(e->pb);
    size_t c = n + n / 2 + 64;
    e->pa = ct_calloc(c, sizeof(ct_idx));
    e->pb = ct_calloc(c, sizeof(ct_idx));
    e->cap_ids = e->pa && e->pb ? c : 0;
    return e->cap_ids ? CT_OK : CT_ERR_NOMEM;
}

int ctdi_epass_grow(ctdi_epass *e, size_t n)
{
    if (n <= e->cap && e->flag)
        return CT_OK;
    free_pairs(e);
    size_t c = n + n / 2 + 64;
    int ok = 1;
    for (int i = 0; i < 4; i++)
        ok &= (e->sl[i] = ct_calloc(c, sizeof(ct_idx))) != NULL;
    for (int i = 0; i < E_N; i++)
        ok &= (e->r[i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    ok &= (e->flag = ct_calloc(c, 1)) != NULL;
    ok &= (e->iflag = ct_calloc(c, sizeof(int32_t))) != NULL;
    if (!ok) {
        free_pairs(e);
        return CT_ERR_NOMEM;
    }
    e->cap = c;
    ct_real **r = e->r;
    ct_edge_geo g = {r[E_DIST], r[E_PEN], r[E_NX], r[E_NY], r[E_NZ], r[E_SA], r[E_SB],
                     NULL,      NULL,     NULL,    NULL,    NULL,    NULL,    r[E_GAP],
                     e->flag};
    e->geo = g;
    return CT_OK;
}

void ctdi_type11_free(ctdi_epass *e)
{
    if (!e)
        return;
    free_pairs(e);
    ct_free(e->pa);
    ct_free(e->pb);
    for (int i = 0; i < CTDI_FGEO_N; i++)
        ct_free(e->fr[i]);
    ct_free(e->fflag);
    ct_exclusion_destroy(&e->excl);
    ct_free(e->e1);
    ct_free(e->e2);
    ct_free(e->gedge);
    ct_free(e->an);
    ct_free(e->bn);
    ct_free(e->x0);
    ct_free(e->y0);
    ct_free(e->z0);
    ct_free(e->box);
    ct_free(e->cnt);
    ct_free(e->cell_off);
    ct_free(e->cell_edge);
    ct_free(e->tmp_a);
    ct_free(e->cellr);
    ct_free(e->qoff);
    ct_free(e->qbuf);
    ct_free(e->fd[0]);
    ct_free(e->fd[1]);
    ct_free(e->kpa);
    ct_free(e->kpb);
    ct_free(e->o2n);
    if (e->ws_ok)
        ct_assemble_ws_destroy(&e->ws);
    free(e);
}

size_t ctdi_type11_memory(const ctdi_epass *e, ct_idx nnode)
{
    size_t b = sizeof *e + e->cap * (4 * sizeof(ct_idx) + E_N * sizeof(ct_real) + 5);
    b += e->cap_ids * 2 * sizeof(ct_idx);
    b += (size_t)CTDI_FCHUNK * (CTDI_FGEO_N * sizeof(ct_real) + 1);
    b += (size_t)e->ne * (2 * sizeof(ct_idx) + 7 * sizeof(ct_real));
    b += (e->cap_cell + e->cap_ce + e->cap_tmp + e->cap_qbuf) * sizeof(ct_idx);
    b += e->cap_cellr * sizeof(int32_t) + e->cap_qoff * sizeof(int64_t);
    b += (e->cap_fd[0] + e->cap_fd[1]) * sizeof(ct_real) +
         (e->cap_kpa + e->cap_kpb + e->cap_o2n) * sizeof(ct_idx);
    /* The unique nodes of each side, the pair counts per A edge, the
     * positions at the last sort (nnode + 1 each). */
    b += ((size_t)e->nan + (size_t)e->nbn + (size_t)e->na + 2) * sizeof(ct_idx);
    b += 3 * ((size_t)nnode + 1) * sizeof(ct_real);
    if (e->excl.off)
        b += ((size_t)e->excl.nq + 1 + (size_t)e->excl.off[e->excl.nq]) * sizeof(ct_idx);
    return b + ct_assemble_ws_memory(&e->ws);
}

void ctdi_type11_force_resort(ctdi_epass *e) { e->need_sort = 1; }

void *ctdi_grow_fresh(void *a, size_t *cap, size_t n, size_t size)
{
    if (n <= *cap && a)
        return a;
    ct_free(a);
    size_t c = n + n / 2 + 64;
    a = ct_calloc(c, size);
    *cap = a ? c : 0;
    return a;
}

int ctdi_type11_carry_damping(ctdi_epass *e)
{
    const size_t n = (size_t)e->n;
    const int old = e->fcur, now = 1 - e->fcur;
    int rc;
    e->fd[now] = ctdi_grow_fresh(e->fd[now], &e->cap_fd[now], n, sizeof(ct_real));
    e->o2n = ctdi_grow_fresh(e->o2n, &e->cap_o2n, n, sizeof(ct_idx));
    if (!e->fd[now] || !e->o2n)
        return CT_ERR_NOMEM;
    /* The new list's forces from the old one's (the first list: none). */
    if (e->nkey > 0 &&
        ((rc = ct_pair_match(e->nkey, e->kpa, e->kpb, e->n, e->pa, e->pb, e->o2n, NULL)) !=
             CT_OK ||
         (rc = ct_pair_remap(e->n, e->o2n, e->fd[old], 0, e->fd[now])) != CT_OK))
        return rc;
    if (e->nkey == 0)
        memset(e->fd[now], 0, n * sizeof(ct_real));
    /* Then its keys, for the next search (the old ones are no longer read). */
    e->fcur = now;
    e->nkey = 0;
    e->kpa = ctdi_grow_fresh(e->kpa, &e->cap_kpa, n, sizeof(ct_idx));
    e->kpb = ctdi_grow_fresh(e->kpb, &e->cap_kpb, n, sizeof(ct_idx));
    if (!e->kpa || !e->kpb)
        return CT_ERR_NOMEM;
    memcpy(e->kpa, e->pa, n * sizeof(ct_idx));
    memcpy(e->kpb, e->pb, n * sizeof(ct_idx));
    e->nkey = e->n;
    return CT_OK;
}

ct_idx ctd_iface_nsec(const ctd_iface *it)
{
    if (it->ep)
        return it->ep->na;
    return it->npass > 0 ? it->pass[0].nsec : 0;
}

static int cmp_edge(const void *a, const void *b)
{
    const ct_idx *u = a, *v = b;
    if (u[0] != v[0])
        return (u[0] > v[0]) - (u[0] < v[0]);
    return (u[1] > v[1]) - (u[1] < v[1]);
}

int ctdi_seg_edges(const ctd_iface_data *d, ct_idx **e1, ct_idx **e2, ct_idx *ne)
{
    size_t cap = 4 * (size_t)d->nseg + 1;
    ct_idx *t = malloc(2 * cap * sizeof(ct_idx));
    if (!t)
        return CT_ERR_NOMEM;
    size_t k = 0;
    for (ct_idx j = 0; j < d->nseg; j++) {
        ct_idx v[4] = {d->n1[j], d->n2[j], d->n3[j], d->n4[j]};
        int nv = v[3] == v[2] ? 3 : 4;
        for (int a = 0; a < nv; a++) {
            ct_idx p = v[a], q = v[(a + 1) % nv];
            t[2 * k] = p < q ? p : q;
            t[2 * k + 1] = p < q ? q : p;
            k++;
        }
    }
    qsort(t, k, 2 * sizeof(ct_idx), cmp_edge);
    size_t u = 0;
    for (size_t i = 0; i < k; i++)
        if (u == 0 || t[2 * u - 2] != t[2 * i] || t[2 * u - 1] != t[2 * i + 1]) {
            t[2 * u] = t[2 * i];
            t[2 * u + 1] = t[2 * i + 1];
            u++;
        }
    *e1 = ct_calloc(u + 1, sizeof(ct_idx));
    *e2 = ct_calloc(u + 1, sizeof(ct_idx));
    if (!*e1 || !*e2) {
        free(t);
        return CT_ERR_NOMEM;
    }
    for (size_t i = 0; i < u; i++) {
        (*e1)[i] = t[2 * i];
        (*e2)[i] = t[2 * i + 1];
    }
    *ne = (ct_idx)u;
    free(t);
    return CT_OK;
}

int ctdi_type11_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag)
{
    const ctd_iface_cfg *c = &it->cfg;
    if (!(c->Istf == 1 || it->kconst > 0))
        return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE11 needs Istf = 1 or a stiffness K.");
    ctdi_epass *e = calloc(1, sizeof *e);
    if (!e)
        return CT_ERR_NOMEM;
    it->ep = e;
    e->need_sort = 1;
    e->excl_state = c->Irem_gap == 2;
    e->bucket = c->algo != CT_SEARCH_DIRECT;
    ct_real k0 = c->Istf == 1 ? c->Stfac : c->Stfac * it->kconst / 2;
    if (k0 < c->Stmin)
        k0 = c->Stmin;
    if (c->Stmax > 0 && k0 > c->Stmax)
        k0 = c->Stmax;
    e->k0 = k0;
    int rc = CT_OK;
    if (d->nea > 0) {
        if (!d->ea1 || !d->ea2 || (d->neb > 0 && (!d->eb1 || !d->eb2)))
            return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE11 edge arrays missing.");
        e->na = d->nea;
        e->nb = d->neb > 0 ? d->neb : 0;
        e->ne = e->na + e->nb;
        e->e1 = ct_calloc((size_t)e->ne + 1, sizeof(ct_idx));
        e->e2 = ct_calloc((size_t)e->ne + 1, sizeof(ct_idx));
        if (!e->e1 || !e->e2)
            return CT_ERR_NOMEM;
        for (ct_idx i = 0; i < e->na; i++) {
            e->e1[i] = d->ea1[i];
            e->e2[i] = d->ea2[i];
        }
        for (ct_idx i = 0; i < e->nb; i++) {
            e->e1[e->na + i] = d->eb1[i];
            e->e2[e->na + i] = d->eb2[i];
        }
    } else {
        if (d->nseg <= 0 || !d->n1 || !d->n2 || !d->n3 || !d->n4)
            return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE11 needs edges or a surface.");
        for (ct_idx j = 0; j < d->nseg; j++)
            if (d->n1[j] < 0 || d->n1[j] >= it->nnode || d->n2[j] < 0 ||
                d->n2[j] >= it->nnode || d->n3[j] < 0 || d->n3[j] >= it->nnode ||
                d->n4[j] < 0 || d->n4[j] >= it->nnode)
                return ctdi_fail(diag, CT_ERR_RANGE, j, "A TYPE11 segment node is out of range.");
        rc = ctdi_seg_edges(d, &e->e1, &e->e2, &e->na);
        if (rc != CT_OK)
            return rc;
        e->nb = 0;
        e->ne = e->na;
    }
    e->self = e->nb == 0;
    for (ct_idx i = 0; i < e->ne; i++)
        if (e->e1[i] < 0 || e->e1[i] >= it->nnode || e->e2[i] < 0 || e->e2[i] >= it->nnode ||
            e->e1[i] == e->e2[i])
            return ctdi_fail(diag, CT_ERR_RANGE, i, "A TYPE11 edge node is out of range or "
                                                    "repeated.");
    /* Edge gaps: the larger node gap of the edge, at least gap / 2. */
    e->gedge = ct_calloc((size_t)e->ne + 1, sizeof(ct_real));
    if (!e->gedge)
        return CT_ERR_NOMEM;
    ct_real gmax = 0;
    for (ct_idx i = 0; i < e->ne; i++) {
        ct_real g = c->gap / 2;
        if (it->gnode) {
            ct_real a = it->gnode[e->e1[i]], b = it->gnode[e->e2[i]];
            g = a > g ? a : g;
            g = b > g ? b : g;
        }
        e->gedge[i] = g;
        ct_real gc = c->Gap_max_s > 0 && g > c->Gap_max_s ? c->Gap_max_s : g;
        gmax = gc > gmax ? gc : gmax;
    }
    e->sgap = 2 * gmax;
    if (!(e->sgap > 0))
        return ctdi_fail(diag, CT_ERR_ARG, -1, "TYPE11 needs a positive gap.");
    const ct_idx *la[6] = {e->e1, e->e2, NULL, NULL, NULL, NULL};
    const ct_idx ka[6] = {e->na, e->na, 0, 0, 0, 0};
    int64_t n = ctdi_unique_nodes(it->nnode, la, ka, &e->an);
    if (n < 0)
        return (int)n;
    e->nan = (ct_idx)n;
    if (e->self) {
        e->bn = ctdi_copy_idx(e->nan, e->an);
        e->nbn = e->nan;
        if (!e->bn)
            return CT_ERR_NOMEM;
    } else {
        const ct_idx *lb[6] = {e->e1 + e->na, e->e2 + e->na, NULL, NULL, NULL, NULL};
        const ct_idx kb[6] = {e->nb, e->nb, 0, 0, 0, 0};
        n = ctdi_unique_nodes(it->nnode, lb, kb, &e->bn);
        if (n < 0)
            return (int)n;
        e->nbn = (ct_idx)n;
    }
    size_t nn = (size_t)it->nnode + 1;
    e->x0 = ct_calloc(nn, sizeof(ct_real));
    e->y0 = ct_calloc(nn, sizeof(ct_real));
    e->z0 = ct_calloc(nn, sizeof(ct_real));
    e->box = ct_calloc(6 * (size_t)e->ne + 6, sizeof(ct_real));
    e->cnt = ct_calloc((size_t)e->na + 2, sizeof(ct_idx));
    if (!e->x0 || !e->y0 || !e->z0 || !e->box || !e->cnt)
        return CT_ERR_NOMEM;
    if ((rc = ctdi_epass_grow(e, 0)) != CT_OK || (rc = ctdi_epass_grow_ids(e, 0)) != CT_OK)
        return rc;
    /* The filter's chunk of measured pairs (type11_filter.c). */
    for (int i = 0; i < CTDI_FGEO_N; i++)
        if (!(e->fr[i] = ct_calloc(CTDI_FCHUNK, sizeof(ct_real))))
            return CT_ERR_NOMEM;
    if (!(e->fflag = ct_calloc(CTDI_FCHUNK, 1)))
        return CT_ERR_NOMEM;
    ct_real **f = e->fr;
    ct_edge_geo fg = {f[0], f[1], f[2], f[3], f[4], f[5], f[6], NULL,
                      NULL, NULL, NULL, NULL, NULL, f[7], e->fflag};
    e->fgeo = fg;
    rc = ct_assemble_ws_init(&e->ws);
    e->ws_ok = rc == CT_OK;
    return rc;
}

/*
 * The nodal step of the edge pairs. A pair's spring K acts on the gap
 * w . u of its four nodes (weights w = (1 - sa, sa, 1 - sb, sb), the
 * force on node i being w_i F), a rank-one stiffness K w w^T whose largest
 * frequency on the lumped masses is omega^2 = K sum_i w_i^2 / m_i. With
 * the element stiffness (the largest kelem_i / m_i of the four nodes)
 * added, the step is sqrt(2 / (max_i kelem_i / m_i + K sum_i w_i^2 / m_i)),
 * which is the node-segment formula sqrt(2 m / (kelem + K)) when one node
 * carries the whole weight. Nodes without mass are left out. *node gets
 * the node of the limiting pair with the largest w_i^2 / m_i (-1: no
 * active pair). The maximum is a parallel reduction; the limiting pair is
 * then the first one that reaches it, the same for any thread count.
 */
static double edge_pair_lambda(const ctdi_epass *e, ct_idx k, const ct_real *m,
                               const ct_real *kelem)
{
    const ct_real *w[4] = {e->r[E_W1], e->r[E_W2], e->r[E_W3], e->r[E_W4]};
    double le = 0, lc = 0;
    for (int a = 0; a < 4; a++) {
        const ct_idx i = e->sl[a][k];
        if (!(m[i] > 0))
            continue;
        double ke = kelem ? (double)kelem[i] / m[i] : 0;
        le = ke > le ? ke : le;
        lc += (double)w[a][k] * w[a][k] / m[i];
    }
    return le + (double)e->r[E_KTAN][k] * lc;
}

static void edge_dt_nodal(const ctdi_epass *e, ct_idx n, const ct_real *m, const ct_real *kelem,
                          ct_real *dt, ct_idx *node)
{
    const ct_real *restrict kt = e->r[E_KTAN], *w[4] = {e->r[E_W1], e->r[E_W2], e->r[E_W3],
                                                        e->r[E_W4]};
    double lmax = 0;
    CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static) reduction(max : lmax)),
    for (ct_idx k = 0; k < n; k++)
        if (kt[k] > 0) {
            double l = edge_pair_lambda(e, k, m, kelem);
            lmax = l > lmax ? l : lmax;
        });
    ct_idx kmax = -1;
    for (ct_idx k = 0; lmax > 0 && k < n && kmax < 0; k++)
        if (kt[k] > 0 && edge_pair_lambda(e, k, m, kelem) == lmax)
            kmax = k;
    *dt = lmax > 0 ? (ct_real)sqrt(2.0 / lmax) : CT_DT_NONE;
    *node = -1;
    double best = -1;
    for (int a = 0; kmax >= 0 && a < 4; a++) {
        const ct_idx i = e->sl[a][kmax];
        double r = m[i] > 0 ? (double)w[a][kmax] * w[a][kmax] / m[i] : -1;
        if (r > best) {
            best = r;
            *node = i;
        }
    }
}

int ctdi_type11_step(ctd_iface *it, ct_real dt, const ct_real *x, const ct_real *y,
                     const ct_real *z, const ct_real *vx, const ct_real *vy,
                     const ct_real *vz, const ct_real *m, ct_real *fx, ct_real *fy,
                     ct_real *fz, ctd_iface_report *rep)
{
    ctdi_epass *e = it->ep;
    if (e->na == 0)
        return CT_OK;
    if (!(it->band > 0)) {
        double s = 0;
        for (ct_idx i = 0; i < e->ne; i++) {
            ct_idx p = e->e1[i], q = e->e2[i];
            double dx = (double)x[p] - (double)x[q], dy = (double)y[p] - (double)y[q],
                   dz = (double)z[p] - (double)z[q];
            s += sqrt(dx * dx + dy * dy + dz * dz);
        }
        double h = e->ne > 0 ? s / (double)e->ne : 0;
        ctdi_choose_band(it, h, e->sgap);
    }
    double t0 = ctd_wtime();
    int did;
    int rc = ctdi_type11_search(it, e, x, y, z, &did);
    if (rc != CT_OK) {
        e->need_sort = 1;
        return rc;
    }
    if (did) {
        it->resorts++;
        rep->resorted++;
    }
    double t1 = ctd_wtime();
    const ct_idx n = e->n;
    ct_narrow_stats ns;
    rc = ct_narrow_edge_edge(n, e->pa, e->pb, e->e1, e->e2, x, y, z, e->gedge, 0,
                             it->cfg.Gap_max_s, &e->geo, &ns);
    if (rc != CT_OK)
        return rc;
    double t2 = ctd_wtime();
    ct_real **r = e->r;
    /* The relative velocity at the closest points (vn, and |u|^2 for the
     * tunnelling limit), the masses there, and the four nodes' weights. */
    rc = ct_relative_velocity_edge(n, e->sl[0], e->sl[1], e->sl[2], e->sl[3], r[E_SA],
                                   r[E_SB], r[E_NX], r[E_NY], r[E_NZ], vx, vy, vz, m, NULL,
                                   NULL, NULL, r[E_VN], r[E_VR2], r[E_MS], r[E_MM]);
    if (rc != CT_OK)
        return rc;
    {
        const ct_real *restrict sa = r[E_SA], *restrict sb = r[E_SB];
        ct_real *restrict w1 = r[E_W1], *restrict w2 = r[E_W2], *restrict w3 = r[E_W3],
                          *restrict w4 = r[E_W4];
        CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < n; k++) {
            w1[k] = 1 - sa[k];
            w2[k] = sa[k];
            w3[k] = 1 - sb[k];
            w4[k] = sb[k];
        });
    }
    rc = ct_penalty_type7(n, r[E_PEN], r[E_GAP], r[E_K0], r[E_FEL], r[E_KTAN], r[E_EN],
                          e->iflag);
    if (rc == CT_OK)
        rc = ct_normal_finish(n, r[E_PEN], r[E_FEL], r[E_KTAN], r[E_VN], r[E_MS], r[E_MM],
                              it->cfg.VisS, dt, r[E_NX], r[E_NY], r[E_NZ], r[E_FN], r[E_FX],
                              r[E_FY], r[E_FZ], it->cfg.VisS > 0 ? NULL : r[E_DD]);
    if (rc != CT_OK)
        return rc;
    if (it->cfg.VisS > 0 && /* the damper's books: its work by the trapezoidal rule */
        (rc = ct_damping_work(n, r[E_PEN], r[E_FN], r[E_FEL], r[E_VN], dt, e->fd[e->fcur],
                              r[E_DD])) != CT_OK)
        return rc;
    rep->e_contact += ct_sum_ordered(n, r[E_EN]);
    rep->e_damp += ct_sum_ordered(n, r[E_DD]);
    rep->force[0] += ct_sum_ordered(n, r[E_FX]);
    rep->force[1] += ct_sum_ordered(n, r[E_FY]);
    rep->force[2] += ct_sum_ordered(n, r[E_FZ]);
    double t3 = ctd_wtime();
    ct_asm_map map = ct_asm_map_edge(n, e->sl[0], e->sl[1], e->sl[2], e->sl[3]);
    const ct_real *const w[4] = {r[E_W1], r[E_W2], r[E_W3], r[E_W4]};
    rc = ct_assemble(&e->ws, it->cfg.asm_variant, &map, w, r[E_FX], r[E_FY], r[E_FZ],
                     it->nnode, fx, fy, fz);
    double t4 = ctd_wtime();
    if (rc != CT_OK)
        return rc;
    /* Time steps: nodal over the four edge nodes, kinematic, tunnelling. */
    ct_real dmin;
    ct_idx imin;
    edge_dt_nodal(e, n, m, it->kelem, &dmin, &imin);
    if (dmin < CT_DT_NONE)
        dmin *= (ct_real)ctdi_damped_dt_factor((double)it->cfg.VisS);
    if (dmin < rep->dt_nodal) {
        rep->dt_nodal = dmin;
        rep->dt_node = imin;
    }
    rc = ct_dt_type7_kinematic(n, r[E_PEN], r[E_GAP], r[E_VN], NULL, &dmin, &imin);
    if (rc != CT_OK)
        return rc;
    if (dmin < rep->dt_kin)
        rep->dt_kin = dmin;
    const ct_real *restrict gap = r[E_GAP], *restrict vr2 = r[E_VR2], *restrict kt = r[E_KTAN];
    const ct_real *restrict pen = r[E_PEN], *restrict dist = r[E_DIST];
    ct_real gmin = CT_DT_NONE, v2max = 0, kmax = 0;
    CTI_PAR_FOR(n > CTDI_PAR_MIN,
                (schedule(static) reduction(min : gmin) reduction(max : v2max, kmax)),
    for (ct_idx k = 0; k < n; k++) {
        if (!ctdi_dt_counts(pen[k], dist[k], gap[k], vr2[k], it->dt_max, it->band))
            continue;
        if (gap[k] > 0 && gap[k] < gmin)
            gmin = gap[k];
        if (vr2[k] > v2max)
            v2max = vr2[k];
        if (kt[k] > kmax)
            kmax = kt[k];
    });
    ctdi_report_limits(rep, kmax, gmin, v2max);
    double t5 = ctd_wtime();
    const double t[6] = {t0, t1, t2, t3, t4, t5};
    ctdi_report_pass(rep, t, n, ns.active);
    return CT_OK;
}

void ctdi_type11_fields(const ctdi_epass *e, ct_real *pen, int32_t *nact)
{
    for (ct_idx k = 0; k < e->n; k++) {
        ct_real p = e->geo.pen[k];
        if (!(p > 0))
            continue;
        const ct_idx q[4] = {e->e1[e->pa[k]], e->e2[e->pa[k]], e->e1[e->pb[k]],
                             e->e2[e->pb[k]]};
        for (int a = 0; a < 4; a++) {
            if (p > pen[q[a]])
                pen[q[a]] = p;
            nact[q[a]]++;
        }
    }
}
