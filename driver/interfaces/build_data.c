/*
 * build_data.c -- the per-model inputs the interfaces need, computed once
 * from a model (build.h): segment and node stiffness inputs, node gaps from
 * shell thickness or rod section, and each node's element stiffness for the
 * nodal contact time step.
 *
 * Stiffness inputs (DESIGN.md section 7):
 *  - a segment of a shell element, or of a rigid part's surface element with
 *    a thickness, is a shell: E and t of its part;
 *  - a brick face is a brick segment: B = E / (3 (1 - 2 nu)) of its part,
 *    A its reference area, V its brick's reference volume; a face of a rigid
 *    brick part has no element volume, and V = A^(3/2) (the cube on that
 *    face) stands in for it;
 *  - a node's B and V_node = sum of V / 8 over the hexahedra (deformable or
 *    rigid) that use it, and the mean E t of the shell segments that use it.
 *
 * Node gaps: half the thickness of the thickest shell segment at the node,
 * or the radius sqrt(A / pi) of a truss or rigid line part with a section
 * area; 0 elsewhere.
 *
 * Element stiffness per node (kelem): shells give their nodal stiffness
 * (ctd_shell node_k); a brick adds 2 (rho V / 8) / dt_e^2 to each of its
 * nodes (dt_e its stable step), so that sqrt(2 m / kelem) is the element
 * step; a truss or spring adds its axial stiffness to both nodes.
 */
#include "build.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model_internal.h"

static double part_bulk(const ctd_scene_part *p)
{
    double nu = p->material.nu;
    return p->material.E / (3.0 * (1.0 - 2.0 * nu));
}

static double quad_area(const ct_nodes *nd, ct_idx a, ct_idx b, ct_idx c, ct_idx d)
{
    double ax = nd->x[c] - nd->x[a], ay = nd->y[c] - nd->y[a], az = nd->z[c] - nd->z[a];
    double bx = nd->x[d] - nd->x[b], by = nd->y[d] - nd->y[b], bz = nd->z[d] - nd->z[b];
    if (d == c) { /* triangle: half the cross product of two edges */
        ax = nd->x[b] - nd->x[a];
        ay = nd->y[b] - nd->y[a];
        az = nd->z[b] - nd->z[a];
        bx = nd->x[c] - nd->x[a];
        by = nd->y[c] - nd->y[a];
        bz = nd->z[c] - nd->z[a];
    }
    double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    return 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
}

/* Volume of a hexahedron (VTK node order) as six tetrahedra around the
 * diagonal 0-6: exact for planar faces. */
static double hex_volume(const ct_nodes *nd, const ct_idx *q)
{
    static const int tet[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
    /* Tetrahedra (0, a, b, 6) around the diagonal; the sum of |det| / 6 is
     * the volume of a convex hexahedron whatever the orientation. */
    double v = 0;
    double ox = nd->x[q[0]], oy = nd->y[q[0]], oz = nd->z[q[0]];
    double dx = nd->x[q[6]] - ox, dy = nd->y[q[6]] - oy, dz = nd->z[q[6]] - oz;
    for (int t = 0; t < 6; t++) {
        ct_idx a = q[tet[t][0]], b = q[tet[t][1]];
        double ax = nd->x[a] - ox, ay = nd->y[a] - oy, az = nd->z[a] - oz;
        double bx = nd->x[b] - ox, by = nd->y[b] - oy, bz = nd->z[b] - oz;
        double det = dx * (ay * bz - az * by) - dy * (ax * bz - az * bx) + dz * (ax * by - ay * bx);
        v += fabs(det) / 6.0;
    }
    return v;
}

void ctd_build_data_destroy(ctd_build_data *d)
{
    if (!d)
        return;
    ct_free(d->seg_E);
    ct_free(d->seg_t);
    ct_free(d->seg_B);
    ct_free(d->seg_A);
    ct_free(d->seg_V);
    ct_free(d->node_B);
    ct_free(d->node_vnode);
    ct_free(d->node_et);
    ct_free(d->gap_node);
    ct_free(d->kelem);
    memset(d, 0, sizeof *d);
}

static int seg_inputs(const ctd_model *m, ctd_build_data *d)
{
    const ct_mesh *me = &m->mesh;
    const ctd_scene *sc = m->scene;
    for (ct_idx s = 0; s < me->nseg; s++) {
        const ctd_scene_part *p = ctd_scene_part_by_id(sc, m->seg_part[s]);
        if (!p)
            continue;
        double A = quad_area(&me->nodes, me->n1[s], me->n2[s], me->n3[s], me->n4[s]);
        if (m->seg_src[s] == CTD_SEGSRC_ELEMENT && m->seg_thick[s] > 0) {
            d->seg_E[s] = (ct_real)p->material.E;
            d->seg_t[s] = m->seg_thick[s];
            continue;
        }
        if (m->seg_src[s] == CTD_SEGSRC_ELEMENT)
            continue; /* a rigid surface element without thickness: no input */
        double V = 0;
        int st = m->seg_set[s], b = m->seg_brick[s];
        if (st >= 0 && st < m->nset && m->set[st].element == CTD_ELEM_BRICK && b >= 0 &&
            b < m->set[st].brick.n)
            V = m->set[st].brick.vol0[b];
        if (!(V > 0))
            V = A * sqrt(A);
        d->seg_B[s] = (ct_real)part_bulk(p);
        d->seg_A[s] = (ct_real)A;
        d->seg_V[s] = (ct_real)V;
    }
    return CT_OK;
}

static int node_inputs(const ctd_model *m, ctd_build_data *d)
{
    const ct_mesh *me = &m->mesh;
    const ctd_scene *sc = m->scene;
    ct_idx nn = me->nodes.n;
    ct_real *cnt = ct_calloc((size_t)nn + 1, sizeof(ct_real));
    if (!cnt)
        return CT_ERR_NOMEM;
    for (ct_idx c = 0; c < m->ncell; c++) {
        const ct_idx *q = m->cell_node + m->cell_off[c];
        ct_idx nq = m->cell_off[c + 1] - m->cell_off[c];
        const ctd_scene_part *p = ctd_scene_part_by_id(sc, m->cell_part[c]);
        if (!p)
            continue;
        if (m->cell_type[c] == CTD_VTK_HEXAHEDRON && nq == 8) {
            double v = hex_volume(&me->nodes, q);
            ct_real B = (ct_real)part_bulk(p);
            for (int a = 0; a < 8; a++) {
                d->node_vnode[q[a]] += (ct_real)(v / 8);
                if (B > d->node_B[q[a]])
                    d->node_B[q[a]] = B;
            }
        } else if (m->cell_type[c] == CTD_VTK_LINE && nq == 2 && p->area > 0) {
            ct_real r = (ct_real)sqrt(p->area / 3.14159265358979323846);
            for (int a = 0; a < 2; a++)
                if (r > d->gap_node[q[a]])
                    d->gap_node[q[a]] = r;
        }
    }
    for (ct_idx s = 0; s < me->nseg; s++) {
        if (!(d->seg_t[s] > 0))
            continue;
        ct_idx q[4] = {me->n1[s], me->n2[s], me->n3[s], me->n4[s]};
        int nv = q[3] == q[2] ? 3 : 4;
        for (int a = 0; a < nv; a++) {
            d->node_et[q[a]] += d->seg_E[s] * d->seg_t[s];
            cnt[q[a]] += 1;
            if (d->seg_t[s] / 2 > d->gap_node[q[a]])
                d->gap_node[q[a]] = d->seg_t[s] / 2;
        }
    }
    for (ct_idx i = 0; i < nn; i++)
        if (cnt[i] > 0)
            d->node_et[i] /= cnt[i];
    ct_free(cnt);
    return CT_OK;
}

static void element_stiffness(const ctd_model *m, ct_real *k)
{
    const ct_nodes *nd = &m->mesh.nodes;
    for (int s = 0; s < m->nset; s++) {
        const ctd_model_set *st = &m->set[s];
        if (st->element == CTD_ELEM_SHELL) {
            ctd_shell_node_stiffness(&st->shell, k);
        } else if (st->element == CTD_ELEM_BRICK) {
            const ctd_brick *b = &st->brick;
            ctd_brick_dt(b, nd->x, nd->y, nd->z, NULL); /* fills b->dte */
            for (ct_idx e = 0; e < b->n; e++) {
                double dte = b->dte[e];
                if (!(dte > 0))
                    continue;
                double ke = 2.0 * (b->rho * b->vol0[e] / 8.0) / (dte * dte);
                for (int a = 0; a < 8; a++)
                    k[b->conn[8 * (int64_t)e + a]] += (ct_real)ke;
            }
        } else {
            const ctd_truss *t = &st->truss;
            for (ct_idx e = 0; e < t->n; e++) {
                k[t->n1[e]] += t->k[e];
                k[t->n2[e]] += t->k[e];
            }
        }
    }
}

int ctd_build_data_init(ctd_build_data *d, const ctd_model *m)
{
    memset(d, 0, sizeof *d);
    size_t ns = (size_t)m->mesh.nseg + 1, nn = (size_t)m->mesh.nodes.n + 1;
    ct_real **seg[5] = {&d->seg_E, &d->seg_t, &d->seg_B, &d->seg_A, &d->seg_V};
    ct_real **node[5] = {&d->node_B, &d->node_vnode, &d->node_et, &d->gap_node, &d->kelem};
    int ok = 1;
    for (int i = 0; i < 5; i++) {
        ok &= (*seg[i] = ct_calloc(ns, sizeof(ct_real))) != NULL;
        ok &= (*node[i] = ct_calloc(nn, sizeof(ct_real))) != NULL;
    }
    if (!ok) {
        ctd_build_data_destroy(d);
        return CT_ERR_NOMEM;
    }
    int rc = seg_inputs(m, d);
    if (rc == CT_OK)
        rc = node_inputs(m, d);
    if (rc != CT_OK) {
        ctd_build_data_destroy(d);
        return rc;
    }
    element_stiffness(m, d->kelem);
    return CT_OK;
}
