/*
 * model_parts.c -- the element sets of a model (bricks, shells, trusses)
 * and the masses of its rigid parts, from the scene's parts (model.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "model_internal.h"

static const char *elem_name(int kind)
{
    const char *n = ctd_element_name(kind);
    return n ? n : "?";
}

/* Quad (or triangle, n4 == n3) area. */
static double quad_area(const ct_real *x, const ct_real *y, const ct_real *z, const ct_idx *n)
{
    double a[3] = {x[n[2]] - x[n[0]], y[n[2]] - y[n[0]], z[n[2]] - z[n[0]]};
    double b[3] = {x[n[3]] - x[n[1]], y[n[3]] - y[n[1]], z[n[3]] - z[n[1]]};
    if (n[3] == n[2]) {
        b[0] = x[n[1]] - x[n[0]];
        b[1] = y[n[1]] - y[n[0]];
        b[2] = z[n[1]] - z[n[0]];
    }
    double c0 = a[1] * b[2] - a[2] * b[1], c1 = a[2] * b[0] - a[0] * b[2],
           c2 = a[0] * b[1] - a[1] * b[0];
    return 0.5 * sqrt(c0 * c0 + c1 * c1 + c2 * c2);
}

/* The element sets and the rigid parts' masses. */
int cti_model_parts(cti_mbuild *b)
{
    ctd_model *m = b->m;
    const ctd_scene *sc = b->sc;
    ct_idx nn = m->mesh.nodes.n;
    const ct_real *x = m->mesh.nodes.x, *y = m->mesh.nodes.y, *z = m->mesh.nodes.z;
    cti_hex *hex = b->c.hex.data;
    cti_quad *quad = b->c.quad.data;
    cti_line *line = b->c.line.data;
    m->set = calloc(sc->parts_count + 1, sizeof *m->set);
    b->faces = calloc(sc->parts_count + 1, sizeof *b->faces);
    b->face_set = calloc(sc->parts_count + 1, sizeof *b->face_set);
    if (!m->set || !b->faces || !b->face_set)
        return cti_model_err(b->err, b->len, CT_ERR_NOMEM, "out of memory");
    int rc = CT_OK;
    for (unsigned p = 0; p < sc->parts_count && !rc; p++) {
        const ctd_scene_part *pt = &sc->parts[p];
        b->face_set[p] = -1;
        ct_idx nh = 0, nq = 0, nl = 0;
        for (size_t e = 0; e < b->c.hex.n; e++)
            nh += hex[e].part == pt->id;
        for (size_t e = 0; e < b->c.quad.n; e++)
            nq += quad[e].part == pt->id;
        for (size_t e = 0; e < b->c.line.n; e++)
            nl += line[e].part == pt->id;
        if (nh + nq + nl == 0)
            continue;
        int el = pt->element;
        const char *bad = NULL;
        if (el == CTD_ELEM_BRICK && nq + nl)
            bad = nq ? "shells" : "lines";
        else if (el == CTD_ELEM_SHELL && nh + nl)
            bad = nh ? "bricks" : "lines";
        else if ((el == CTD_ELEM_TRUSS || el == CTD_ELEM_SPRING) && nh + nq)
            bad = nh ? "bricks" : "shells";
        if (bad)
            return cti_model_err(b->err, b->len, CT_ERR_ARG,
                                 "%s:%d: parts[%u]: part %lld has element %s but its meshes "
                                 "give it %s (expected %s elements only)", sc->path, pt->line,
                                 p, (long long)pt->id, elem_name(el), bad, elem_name(el));
        double rho = pt->material.rho;
        /* Gather the part's connectivity. */
        ct_idx *conn = malloc(sizeof(ct_idx) * (size_t)(8 * (int64_t)nh + 4 * (int64_t)nq +
                                                        2 * (int64_t)nl + 1));
        if (!conn)
            return cti_model_err(b->err, b->len, CT_ERR_NOMEM, "out of memory");
        ct_idx *hc = conn, *qc = conn + 8 * (int64_t)nh, *lc = qc + 4 * (int64_t)nq;
        ct_idx kh = 0, kq = 0, kl = 0;
        for (size_t e = 0; e < b->c.hex.n; e++)
            if (hex[e].part == pt->id)
                memcpy(hc + 8 * (int64_t)kh++, hex[e].n, 8 * sizeof(ct_idx));
        for (size_t e = 0; e < b->c.quad.n; e++)
            if (quad[e].part == pt->id)
                memcpy(qc + 4 * (int64_t)kq++, quad[e].n, 4 * sizeof(ct_idx));
        for (size_t e = 0; e < b->c.line.n; e++)
            if (line[e].part == pt->id)
                memcpy(lc + 2 * (int64_t)kl++, line[e].n, 2 * sizeof(ct_idx));
        ct_diag d = {0};
        if (nh) {
            d.msg[0] = 0;
            rc = ctd_brick_outer_faces(nn, x, y, z, nh, hc, NULL, &b->faces[p], &d);
            if (rc)
                goto part_err;
        }
        if (el == CTD_ELEM_RIGID) {
            /* Masses only: the body is made once every mass is known. */
            if (nh) {
                ctd_brick tmp;
                rc = ctd_brick_init(&tmp, nh, hc, nn, x, y, z, (ct_real)pt->material.E,
                                    (ct_real)pt->material.nu, (ct_real)rho, &d);
                if (rc)
                    goto part_err;
                ctd_brick_mass(&tmp, m->mesh.nodes.m);
                ctd_brick_destroy(&tmp);
            }
            if (nq && !(pt->thickness > 0)) {
                free(conn);
                return cti_model_err(b->err, b->len, CT_ERR_ARG,
                                     "%s:%d: parts[%u].thickness: rigid part %lld has surface "
                                     "elements, whose mass is rho A t: expected a thickness > 0",
                                     sc->path, pt->line, p, (long long)pt->id);
            }
            if (nl && !(pt->area > 0)) {
                free(conn);
                return cti_model_err(b->err, b->len, CT_ERR_ARG,
                                     "%s:%d: parts[%u].area: rigid part %lld has line elements, "
                                     "whose mass is rho A L: expected an area > 0", sc->path,
                                     pt->line, p, (long long)pt->id);
            }
            for (ct_idx e = 0; e < nq; e++) {
                const ct_idx *q = qc + 4 * (int64_t)e;
                int nv = q[3] == q[2] ? 3 : 4;
                double me = rho * pt->thickness * quad_area(x, y, z, q) / nv;
                for (int a = 0; a < nv; a++)
                    m->mesh.nodes.m[q[a]] += (ct_real)me;
            }
            for (ct_idx e = 0; e < nl; e++) {
                const ct_idx *l = lc + 2 * (int64_t)e;
                double dx = x[l[1]] - x[l[0]], dy = y[l[1]] - y[l[0]], dz = z[l[1]] - z[l[0]];
                double me = 0.5 * rho * pt->area * sqrt(dx * dx + dy * dy + dz * dz);
                m->mesh.nodes.m[l[0]] += (ct_real)me;
                m->mesh.nodes.m[l[1]] += (ct_real)me;
            }
            free(conn);
            continue;
        }
        ctd_model_set *st = &m->set[m->nset];
        st->element = el;
        st->part = pt->id;
        if (el == CTD_ELEM_BRICK) {
            rc = ctd_brick_init(&st->brick, nh, hc, nn, x, y, z, (ct_real)pt->material.E,
                                (ct_real)pt->material.nu, (ct_real)rho, &d);
            if (!rc) {
                ctd_brick_mass(&st->brick, m->mesh.nodes.m);
                st->nelem = nh;
                b->face_set[p] = m->nset;
            }
        } else if (el == CTD_ELEM_SHELL) {
            ct_idx *n1 = malloc(sizeof(ct_idx) * 4 * (size_t)nq);
            if (!n1) {
                free(conn);
                return cti_model_err(b->err, b->len, CT_ERR_NOMEM, "out of memory");
            }
            for (ct_idx e = 0; e < nq; e++)
                for (int a = 0; a < 4; a++)
                    n1[a * (int64_t)nq + e] = qc[4 * (int64_t)e + a];
            rc = ctd_shell_init(&st->shell, nn, x, y, z, nq, n1, n1 + nq, n1 + 2 * (int64_t)nq,
                                n1 + 3 * (int64_t)nq, NULL, pt->material.E, pt->material.nu,
                                rho, pt->thickness);
            free(n1);
            if (!rc) {
                ctd_shell_masses(&st->shell, m->mesh.nodes.m);
                st->nelem = nq;
            }
        } else {
            ct_idx *n1 = malloc(sizeof(ct_idx) * 2 * (size_t)nl);
            if (!n1) {
                free(conn);
                return cti_model_err(b->err, b->len, CT_ERR_NOMEM, "out of memory");
            }
            for (ct_idx e = 0; e < nl; e++) {
                n1[e] = lc[2 * (int64_t)e];
                n1[nl + e] = lc[2 * (int64_t)e + 1];
            }
            rc = ctd_truss_init(&st->truss, nl, n1, n1 + nl, nn, x, y, z, &d);
            free(n1);
            if (!rc) {
                rc = el == CTD_ELEM_TRUSS
                         ? ctd_truss_set_truss(&st->truss, 0, nl, (ct_real)pt->area,
                                               (ct_real)pt->material.E, (ct_real)rho)
                         : ctd_truss_set_spring(&st->truss, 0, nl, (ct_real)pt->stiffness);
                if (rc)
                    ctd_truss_destroy(&st->truss);
            }
            if (!rc) {
                ctd_truss_mass(&st->truss, m->mesh.nodes.m);
                st->nelem = nl;
            }
        }
        if (!rc) {
            m->nset++;
            free(conn);
            continue;
        }
    part_err:
        free(conn);
        return cti_model_err(b->err, b->len, rc,
                             "%s:%d: parts[%u]: cannot build the %s elements of part %lld: %s%s%s",
                             sc->path, pt->line, p, elem_name(el), (long long)pt->id,
                             ct_strerror(rc), d.msg[0] ? ": " : "", d.msg);
    }
    return rc;
}
