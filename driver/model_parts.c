/*
 * model_parts.c -- the element sets of a model (bricks, shells, trusses)
 * and the masses of its rigid parts, from the scene's parts (model.h).
 *
 * The elements are sorted to their parts in one pass, and the faces of
 * all bricks are classed once (faces with the same corners share a class),
 * so each part costs its own elements: a pass over every element per part,
 * and the outer faces of each part's bricks counted over every node of the
 * model, cost parts x (elements + nodes).
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

/* The elements of each scene part, by kind (0 bricks, 1 shells, 2 lines):
 * idx[k][off[k][p] .. off[k][p + 1]) in element order; and the classes of
 * the faces of all bricks (cls NULL: each part's bricks go through
 * ctd_brick_outer_faces, for an input it must check or too large for the
 * classes' index) with a stamp per class and each brick's place in its
 * part (loc). */
typedef struct part_index {
    ct_idx *off[3], *idx[3];
    ct_idx *conn, *cls, *loc;
    int32_t *stamp, gen;
} part_index;

typedef struct part_id {
    int64_t id;
    ct_idx p;
} part_id;

static int cmp_part_id(const void *a, const void *b)
{
    int64_t x = ((const part_id *)a)->id, y = ((const part_id *)b)->id;
    return (x > y) - (x < y);
}

/* The scene part (index) of part id `id`, or -1. */
static ct_idx part_of(const part_id *ids, size_t n, int64_t id)
{
    part_id key = {id, 0};
    const part_id *f = bsearch(&key, ids, n, sizeof *ids, cmp_part_id);
    return f ? f->p : -1;
}

/* CSR of the n elements (their part id at byte offset `at` of each
 * `stride`-byte record of data) over the np scene parts. */
static int csr_by_part(const void *data, size_t n, size_t stride, size_t at, const part_id *ids,
                       size_t np, ct_idx **off, ct_idx **idx)
{
    *off = calloc(np + 2, sizeof **off);
    *idx = malloc((n + 1) * sizeof **idx);
    ct_idx *q = malloc((n + 1) * sizeof *q);
    if (!*off || !*idx || !q) {
        free(q);
        return CT_ERR_NOMEM;
    }
    for (size_t e = 0; e < n; e++) {
        int64_t id;
        memcpy(&id, (const char *)data + e * stride + at, sizeof id);
        q[e] = part_of(ids, np, id);
        if (q[e] >= 0)
            (*off)[q[e] + 1]++;
    }
    for (size_t p = 0; p < np; p++)
        (*off)[p + 1] += (*off)[p];
    ct_idx *fill = malloc((np + 1) * sizeof *fill);
    if (!fill) {
        free(q);
        return CT_ERR_NOMEM;
    }
    memcpy(fill, *off, np * sizeof *fill);
    for (size_t e = 0; e < n; e++)
        if (q[e] >= 0)
            (*idx)[fill[q[e]]++] = (ct_idx)e;
    free(fill);
    free(q);
    return CT_OK;
}

static void index_free(part_index *ix)
{
    for (int k = 0; k < 3; k++) {
        free(ix->off[k]);
        free(ix->idx[k]);
    }
    free(ix->conn);
    free(ix->cls);
    free(ix->loc);
    free(ix->stamp);
    memset(ix, 0, sizeof *ix);
}

static int index_parts(const cti_mbuild *b, part_index *ix)
{
    memset(ix, 0, sizeof *ix);
    const ctd_scene *sc = b->sc;
    size_t np = sc->parts_count;
    part_id *ids = malloc((np + 1) * sizeof *ids);
    if (!ids)
        return CT_ERR_NOMEM;
    for (size_t p = 0; p < np; p++)
        ids[p] = (part_id){sc->parts[p].id, (ct_idx)p};
    qsort(ids, np, sizeof *ids, cmp_part_id);
    int rc = csr_by_part(b->c.hex.data, b->c.hex.n, sizeof(cti_hex), offsetof(cti_hex, part),
                         ids, np, &ix->off[0], &ix->idx[0]);
    if (!rc)
        rc = csr_by_part(b->c.quad.data, b->c.quad.n, sizeof(cti_quad),
                         offsetof(cti_quad, part), ids, np, &ix->off[1], &ix->idx[1]);
    if (!rc)
        rc = csr_by_part(b->c.line.data, b->c.line.n, sizeof(cti_line),
                         offsetof(cti_line, part), ids, np, &ix->off[2], &ix->idx[2]);
    free(ids);
    if (rc)
        return rc;
    /* The face classes of all bricks, for an input the classes take. */
    const cti_hex *hex = b->c.hex.data;
    const size_t nh = b->c.hex.n;
    const ct_idx nn = b->m->mesh.nodes.n;
    int ok = nh > 0 && nh <= (size_t)INT32_MAX / 6;
    for (size_t e = 0; e < nh && ok; e++)
        for (int a = 0; a < 8; a++)
            ok &= hex[e].n[a] >= 0 && hex[e].n[a] < nn;
    if (!ok)
        return CT_OK;
    ix->conn = malloc(8 * nh * sizeof *ix->conn);
    ix->cls = malloc(6 * nh * sizeof *ix->cls);
    ix->stamp = calloc(6 * nh, sizeof *ix->stamp);
    ix->loc = malloc(nh * sizeof *ix->loc);
    if (!ix->conn || !ix->cls || !ix->stamp || !ix->loc)
        return CT_ERR_NOMEM;
    for (size_t e = 0; e < nh; e++)
        memcpy(ix->conn + 8 * e, hex[e].n, 8 * sizeof(ct_idx));
    return ctd_brick_face_classes(nn, (ct_idx)nh, ix->conn, NULL, ix->cls);
}

/* The outer faces of scene part p's nh bricks (hc: their nodes, in the
 * part's order) into *out, the brick of each face numbered in the part. */
static int part_faces(part_index *ix, unsigned p, ct_idx nn, const ct_real *x,
                      const ct_real *y, const ct_real *z, ct_idx nh, const ct_idx *hc,
                      ctd_faces *out, ct_diag *d)
{
    if (!ix->cls)
        return ctd_brick_outer_faces(nn, x, y, z, nh, hc, NULL, out, d);
    const ct_idx *brk = ix->idx[0] + ix->off[0][p];
    for (ct_idx k = 0; k < nh; k++)
        ix->loc[brk[k]] = k;
    int rc = ctd_brick_select_outer(x, y, z, ix->conn, ix->cls, nh, brk, ix->stamp, ++ix->gen,
                                    out);
    if (rc) {
        snprintf(d->msg, sizeof d->msg, "Out of memory for the outer faces.");
        return rc;
    }
    for (ct_idx f = 0; f < out->n; f++)
        out->brick[f] = ix->loc[out->brick[f]];
    return CT_OK;
}

/* " (/BRICK/2 element 7, deck.rad:15)" for brick e of the model (an
 * index into b->c.hex) when it comes from a deck, "" for a generated one:
 * the brick as the user can find it (the element sets number bricks
 * within their part). */
static void brick_origin(const cti_mbuild *b, ct_idx e, char *buf, size_t len)
{
    const cti_hex *h = (const cti_hex *)b->c.hex.data + e;
    const ctd_scene_mesh *me = &b->sc->mesh[h->mesh];
    if (h->deck < 0 || !me->import || !me->import->deck)
        return;
    const ctd_deck *d = me->import->deck;
    snprintf(buf, len, " (/BRICK/%lld element %lld, %s:%d)", (long long)d->brick_part[h->deck],
             (long long)d->brick_id[h->deck], me->import->file, (int)d->brick_line[h->deck]);
}

static int parts_build(cti_mbuild *b, part_index *ix)
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
        return ctd_errf(b->err, b->len, CT_ERR_NOMEM, "out of memory");
    int rc = CT_OK;
    for (unsigned p = 0; p < sc->parts_count && !rc; p++) {
        const ctd_scene_part *pt = &sc->parts[p];
        b->face_set[p] = -1;
        const ct_idx *ih = ix->idx[0] + ix->off[0][p], *iq = ix->idx[1] + ix->off[1][p],
                     *il = ix->idx[2] + ix->off[2][p];
        ct_idx nh = ix->off[0][p + 1] - ix->off[0][p], nq = ix->off[1][p + 1] - ix->off[1][p],
               nl = ix->off[2][p + 1] - ix->off[2][p];
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
            return ctd_errf(b->err, b->len, CT_ERR_ARG,
                                 "%s:%d: parts[%u]: part %lld has element %s but its meshes "
                                 "give it %s (expected %s elements only)", sc->path, pt->line,
                                 p, (long long)pt->id, elem_name(el), bad, elem_name(el));
        double rho = pt->material.rho;
        /* Gather the part's connectivity. */
        ct_idx *conn = malloc(sizeof(ct_idx) * (size_t)(8 * (int64_t)nh + 4 * (int64_t)nq +
                                                        2 * (int64_t)nl + 1));
        if (!conn)
            return ctd_errf(b->err, b->len, CT_ERR_NOMEM, "out of memory");
        ct_idx *hc = conn, *qc = conn + 8 * (int64_t)nh, *lc = qc + 4 * (int64_t)nq;
        for (ct_idx k = 0; k < nh; k++)
            memcpy(hc + 8 * (int64_t)k, hex[ih[k]].n, 8 * sizeof(ct_idx));
        for (ct_idx k = 0; k < nq; k++)
            memcpy(qc + 4 * (int64_t)k, quad[iq[k]].n, 4 * sizeof(ct_idx));
        for (ct_idx k = 0; k < nl; k++)
            memcpy(lc + 2 * (int64_t)k, line[il[k]].n, 2 * sizeof(ct_idx));
        ct_diag d = {0};
        int bad_brick = 0; /* the brick elements refused one of their bricks */
        if (nh) {
            d.msg[0] = 0;
            rc = part_faces(ix, p, nn, x, y, z, nh, hc, &b->faces[p], &d);
            if (rc)
                goto part_err;
        }
        if (el == CTD_ELEM_RIGID) {
            /* Masses only: the body is made once every mass is known. */
            if (nh) {
                ctd_brick tmp;
                rc = ctd_brick_init_shared(&tmp, nh, hc, nn, x, y, z, (ct_real)pt->material.E,
                                           (ct_real)pt->material.nu, (ct_real)rho, &d);
                bad_brick = rc != CT_OK;
                if (rc)
                    goto part_err;
                ctd_brick_mass(&tmp, m->mesh.nodes.m);
                ctd_brick_destroy(&tmp);
            }
            if (nq && !(pt->thickness > 0)) {
                free(conn);
                return ctd_errf(b->err, b->len, CT_ERR_ARG,
                                     "%s:%d: parts[%u].thickness: rigid part %lld has surface "
                                     "elements, whose mass is rho A t: expected a thickness > 0",
                                     sc->path, pt->line, p, (long long)pt->id);
            }
            if (nl && !(pt->area > 0)) {
                free(conn);
                return ctd_errf(b->err, b->len, CT_ERR_ARG,
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
            /* The model's positions stay the reference ones (the solver
             * moves its own copy): shared by every brick part. */
            rc = ctd_brick_init_shared(&st->brick, nh, hc, nn, x, y, z, (ct_real)pt->material.E,
                                       (ct_real)pt->material.nu, (ct_real)rho, &d);
            bad_brick = rc != CT_OK;
            if (!rc) {
                ctd_brick_mass(&st->brick, m->mesh.nodes.m);
                st->nelem = nh;
                b->face_set[p] = m->nset;
            }
        } else if (el == CTD_ELEM_SHELL) {
            ct_idx *n1 = malloc(sizeof(ct_idx) * 4 * (size_t)nq);
            if (!n1) {
                free(conn);
                return ctd_errf(b->err, b->len, CT_ERR_NOMEM, "out of memory");
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
                return ctd_errf(b->err, b->len, CT_ERR_NOMEM, "out of memory");
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
        char origin[512] = "";
        if (bad_brick && d.index >= 0 && d.index < nh)
            brick_origin(b, ih[d.index], origin, sizeof origin);
        return ctd_errf(b->err, b->len, rc,
                             "%s:%d: parts[%u]: cannot build the %s elements of part %lld%s: "
                             "%s%s%s",
                             sc->path, pt->line, p, elem_name(el), (long long)pt->id, origin,
                             ct_strerror(rc), d.msg[0] ? ": " : "", d.msg);
    }
    return rc;
}

/* The element sets and the rigid parts' masses. */
int cti_model_parts(cti_mbuild *b)
{
    part_index ix;
    int rc = index_parts(b, &ix);
    if (rc == CT_OK)
        rc = parts_build(b, &ix);
    else
        rc = ctd_errf(b->err, b->len, rc, "out of memory");
    index_free(&ix);
    return rc;
}
