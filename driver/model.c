/*
 * model.c -- the model of a scene: nodes, element sets, masses, rigid
 * bodies, boundary conditions, surface segments and VTU cells (model.h).
 * The generators not in meshgen.h (ball, net, rod) are in model_gen.c;
 * the selections are in model_select.c; the element sets and the parts'
 * masses in model_parts.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"
#include "model.h"
#include "model_internal.h"
#include "output.h"

/* ---- Growable arrays ----------------------------------------------------- */

int cti_vec_push(cti_vec *v, const void *item, size_t size)
{
    if (v->n == v->cap) {
        size_t cap = v->cap ? 2 * v->cap : 64;
        void *p = realloc(v->data, cap * size);
        if (!p)
            return CT_ERR_NOMEM;
        v->data = p;
        v->cap = cap;
    }
    memcpy((char *)v->data + v->n * size, item, size);
    v->n++;
    return CT_OK;
}

void cti_vec_free(cti_vec *v)
{
    free(v->data);
    memset(v, 0, sizeof *v);
}


/* ---- Collecting the meshes ------------------------------------------------ */


static void collect_free(cti_mcollect *c)
{
    cti_vec_free(&c->x); cti_vec_free(&c->y); cti_vec_free(&c->z); cti_vec_free(&c->id);
    cti_vec_free(&c->hex); cti_vec_free(&c->quad); cti_vec_free(&c->line);
    cti_vec_free(&c->dface);
}

static int push_node(cti_mcollect *c, double x, double y, double z, int64_t id)
{
    int rc = cti_vec_push(&c->x, &x, sizeof x);
    if (!rc) rc = cti_vec_push(&c->y, &y, sizeof y);
    if (!rc) rc = cti_vec_push(&c->z, &z, sizeof z);
    if (!rc) rc = cti_vec_push(&c->id, &id, sizeof id);
    return rc;
}

/* One generated mesh entry: its nodes and elements appended to c. */
static int collect_generate(cti_mcollect *c, const ctd_scene *sc, unsigned i, char *err, size_t len)
{
    const ctd_scene_mesh *me = &sc->mesh[i];
    const ctd_scene_generate *g = me->generate;
    const int64_t *ce = g->cells_eff;
    ct_idx off = (ct_idx)c->x.n;
    cti_gen gen;
    int rc = cti_generate(&gen, g);
    if (rc != CT_OK)
        return ctd_errf(err, len, rc, "%s:%d: mesh[%u]: cannot generate the %s mesh: %s",
                             sc->path, me->line, i, g->kind_name, ct_strerror(rc));
    if (me->nnode >= 0 && gen.mesh.nodes.n != me->nnode) {
        rc = ctd_errf(err, len, CT_ERR_ARG,
                           "%s:%d: mesh[%u]: the %s generator made %d nodes, the scene's "
                           "numbering expects %lld", sc->path, me->line, i, g->kind_name,
                           gen.mesh.nodes.n, (long long)me->nnode);
        goto done;
    }
    for (ct_idx k = 0; k < gen.mesh.nodes.n && !rc; k++)
        rc = push_node(c, gen.mesh.nodes.x[k], gen.mesh.nodes.y[k], gen.mesh.nodes.z[k],
                       me->first_id + k);
    if (gen.hex8) {
        int64_t nh = ce[0] * (g->kind == CTD_GEN_BALL ? ce[0] * ce[0] : ce[1] * ce[2]);
        for (int64_t e = 0; e < nh && !rc; e++) {
            cti_hex h;
            for (int a = 0; a < 8; a++)
                h.n[a] = off + gen.hex8[8 * e + a];
            h.part = g->part;
            h.mesh = (int32_t)i;
            h.deck = -1;
            rc = cti_vec_push(&c->hex, &h, sizeof h);
        }
    } else if (gen.nline) {
        for (ct_idx e = 0; e < gen.nline && !rc; e++) {
            cti_line l = {{off + gen.l1[e], off + gen.l2[e]}, g->part};
            rc = cti_vec_push(&c->line, &l, sizeof l);
        }
    } else {
        for (ct_idx s = 0; s < gen.mesh.nseg && !rc; s++) {
            cti_quad q = {{off + gen.mesh.n1[s], off + gen.mesh.n2[s], off + gen.mesh.n3[s],
                           off + gen.mesh.n4[s]}, g->part, (int32_t)i, -1};
            rc = cti_vec_push(&c->quad, &q, sizeof q);
        }
    }
    if (rc)
        rc = ctd_errf(err, len, rc, "out of memory");
done:
    cti_gen_destroy(&gen);
    return rc;
}

static int collect_import(cti_mcollect *c, const ctd_scene *sc, unsigned i, char *err, size_t len)
{
    const ctd_deck *d = sc->mesh[i].import->deck;
    ct_idx off = (ct_idx)c->x.n;
    int rc = CT_OK;
    for (ct_idx k = 0; k < d->mesh.nodes.n && !rc; k++)
        rc = push_node(c, d->mesh.nodes.x[k], d->mesh.nodes.y[k], d->mesh.nodes.z[k],
                       d->node_id[k]);
    for (ct_idx s = 0; s < d->mesh.nseg && !rc; s++) {
        cti_quad q = {{off + d->mesh.n1[s], off + d->mesh.n2[s], off + d->mesh.n3[s],
                       off + d->mesh.n4[s]}, d->seg_part[s], (int32_t)i, s};
        rc = cti_vec_push(s < d->nelemseg ? &c->quad : &c->dface, &q, sizeof q);
    }
    for (ct_idx b = 0; b < d->nbrick && !rc; b++) {
        cti_hex h;
        for (int a = 0; a < 8; a++)
            h.n[a] = off + d->brick_node[8 * b + a];
        h.part = d->brick_part[b];
        h.mesh = (int32_t)i;
        h.deck = b;
        rc = cti_vec_push(&c->hex, &h, sizeof h);
    }
    return rc ? ctd_errf(err, len, rc, "out of memory") : CT_OK;
}

/* ---- Building ---------------------------------------------------------------- */

void ctd_model_destroy(ctd_model *m)
{
    if (!m)
        return;
    for (int s = 0; s < m->nset; s++) {
        ctd_model_set *st = &m->set[s];
        if (st->element == CTD_ELEM_BRICK)
            ctd_brick_destroy(&st->brick);
        else if (st->element == CTD_ELEM_SHELL)
            ctd_shell_destroy(&st->shell);
        else
            ctd_truss_destroy(&st->truss);
    }
    free(m->set);
    for (int b = 0; b < m->nbody; b++)
        ctd_rigid_destroy(&m->body[b].rigid);
    free(m->body);
    ct_mesh_destroy(&m->mesh);
    free(m->node_id); free(m->mesh_node_off); free(m->node_part); free(m->node_body);
    free(m->seg_part); free(m->seg_src); free(m->seg_shell); free(m->seg_thick);
    free(m->seg_deck); free(m->seg_mesh); free(m->seg_brick); free(m->seg_set);
    free(m->l1); free(m->l2); free(m->line_part);
    free(m->bc_mask);
    for (int d = 0; d < 3; d++)
        ct_free(m->bc_v[d]);
    free(m->cell_type); free(m->cell_off); free(m->cell_node); free(m->cell_part);
    memset(m, 0, sizeof *m);
}


/* Segments: elements of surface parts, outer faces, deck faces. */
static int build_segments(cti_mbuild *b)
{
    ctd_model *m = b->m;
    const ctd_scene *sc = b->sc;
    cti_quad *quad = b->c.quad.data, *df = b->c.dface.data;
    int64_t nseg = (int64_t)b->c.quad.n + (int64_t)b->c.dface.n;
    for (unsigned p = 0; p < sc->parts_count; p++)
        nseg += b->faces[p].n;
    if (nseg > INT32_MAX / 2)
        return ctd_errf(b->err, b->len, CT_ERR_TOOBIG, "too many segments");
    /* The mesh holds the nodes already: move them into a new one. */
    ct_mesh nm;
    int rc = ct_mesh_init(&nm, 0, (ct_idx)nseg);
    if (rc)
        return ctd_errf(b->err, b->len, rc, "out of memory");
    ct_nodes keep = m->mesh.nodes;
    memset(&m->mesh.nodes, 0, sizeof m->mesh.nodes);
    ct_mesh_destroy(&m->mesh);
    ct_nodes_destroy(&nm.nodes);
    m->mesh = nm;
    m->mesh.nodes = keep;
    size_t ns = (size_t)nseg + 1;
    m->seg_part = calloc(ns, sizeof *m->seg_part);
    m->seg_src = calloc(ns, sizeof *m->seg_src);
    m->seg_shell = calloc(ns, sizeof *m->seg_shell);
    m->seg_thick = calloc(ns, sizeof *m->seg_thick);
    m->seg_deck = calloc(ns, sizeof *m->seg_deck);
    m->seg_mesh = calloc(ns, sizeof *m->seg_mesh);
    m->seg_brick = calloc(ns, sizeof *m->seg_brick);
    m->seg_set = calloc(ns, sizeof *m->seg_set);
    if (!m->seg_part || !m->seg_src || !m->seg_shell || !m->seg_thick || !m->seg_deck ||
        !m->seg_mesh || !m->seg_brick || !m->seg_set)
        return ctd_errf(b->err, b->len, CT_ERR_NOMEM, "out of memory");
    ct_idx k = 0;
    for (size_t e = 0; e < b->c.quad.n; e++, k++) {
        const ctd_scene_part *pt = ctd_scene_part_by_id(sc, quad[e].part);
        m->mesh.n1[k] = quad[e].n[0];
        m->mesh.n2[k] = quad[e].n[1];
        m->mesh.n3[k] = quad[e].n[2];
        m->mesh.n4[k] = quad[e].n[3];
        m->seg_part[k] = (int32_t)quad[e].part;
        m->seg_src[k] = CTD_SEGSRC_ELEMENT;
        m->seg_shell[k] = pt && pt->element == CTD_ELEM_SHELL;
        m->seg_thick[k] = pt ? (ct_real)pt->thickness : 0;
        m->seg_deck[k] = quad[e].deck;
        m->seg_mesh[k] = quad[e].mesh;
        m->seg_brick[k] = -1;
        m->seg_set[k] = -1;
        for (int s = 0; pt && s < m->nset; s++)
            if (m->set[s].part == pt->id)
                m->seg_set[k] = s;
    }
    for (unsigned p = 0; p < sc->parts_count; p++)
        for (ct_idx f = 0; f < b->faces[p].n; f++, k++) {
            const ct_idx *q = b->faces[p].node + 4 * (int64_t)f;
            m->mesh.n1[k] = q[0];
            m->mesh.n2[k] = q[1];
            m->mesh.n3[k] = q[2];
            m->mesh.n4[k] = q[3];
            m->seg_part[k] = (int32_t)sc->parts[p].id;
            m->seg_src[k] = CTD_SEGSRC_FACE;
            m->seg_deck[k] = -1;
            m->seg_mesh[k] = -1;
            m->seg_brick[k] = b->faces[p].brick[f];
            m->seg_set[k] = b->face_set[p];
        }
    for (size_t e = 0; e < b->c.dface.n; e++, k++) {
        m->mesh.n1[k] = df[e].n[0];
        m->mesh.n2[k] = df[e].n[1];
        m->mesh.n3[k] = df[e].n[2];
        m->mesh.n4[k] = df[e].n[3];
        m->seg_part[k] = (int32_t)df[e].part;
        m->seg_src[k] = CTD_SEGSRC_DECK;
        m->seg_deck[k] = df[e].deck;
        m->seg_mesh[k] = df[e].mesh;
        m->seg_brick[k] = -1;
        m->seg_set[k] = -1;
    }
    return CT_OK;
}

/* Lines, VTU cells and the part of each node. */
static int build_cells(cti_mbuild *b)
{
    ctd_model *m = b->m;
    cti_hex *hex = b->c.hex.data;
    cti_quad *quad = b->c.quad.data;
    cti_line *line = b->c.line.data;
    size_t nh = b->c.hex.n, nq = b->c.quad.n, nl = b->c.line.n;
    m->nline = (ct_idx)nl;
    m->l1 = malloc(sizeof(ct_idx) * (nl + 1));
    m->l2 = malloc(sizeof(ct_idx) * (nl + 1));
    m->line_part = malloc(sizeof(int32_t) * (nl + 1));
    m->ncell = (ct_idx)(nh + nq + nl);
    m->nelem = (int64_t)(nh + nq + nl);
    m->cell_type = malloc(nh + nq + nl + 1);
    m->cell_off = malloc(sizeof(ct_idx) * (nh + nq + nl + 1));
    m->cell_node = malloc(sizeof(ct_idx) * (8 * nh + 4 * nq + 2 * nl + 1));
    m->cell_part = malloc(sizeof(int32_t) * (nh + nq + nl + 1));
    if (!m->l1 || !m->l2 || !m->line_part || !m->cell_type || !m->cell_off || !m->cell_node ||
        !m->cell_part)
        return ctd_errf(b->err, b->len, CT_ERR_NOMEM, "out of memory");
    ct_idx c = 0, o = 0;
    m->cell_off[0] = 0;
    for (size_t e = 0; e < nh; e++, c++) {
        m->cell_type[c] = CTD_VTK_HEXAHEDRON;
        for (int a = 0; a < 8; a++)
            m->cell_node[o++] = hex[e].n[a];
        m->cell_part[c] = (int32_t)hex[e].part;
        m->cell_off[c + 1] = o;
    }
    for (size_t e = 0; e < nq; e++, c++) {
        int tri = quad[e].n[3] == quad[e].n[2];
        m->cell_type[c] = tri ? CTD_VTK_TRIANGLE : CTD_VTK_QUAD;
        for (int a = 0; a < (tri ? 3 : 4); a++)
            m->cell_node[o++] = quad[e].n[a];
        m->cell_part[c] = (int32_t)quad[e].part;
        m->cell_off[c + 1] = o;
    }
    for (size_t e = 0; e < nl; e++, c++) {
        m->cell_type[c] = CTD_VTK_LINE;
        m->cell_node[o++] = m->l1[e] = line[e].n[0];
        m->cell_node[o++] = m->l2[e] = line[e].n[1];
        m->cell_part[c] = m->line_part[e] = (int32_t)line[e].part;
        m->cell_off[c + 1] = o;
    }
    for (ct_idx k = 0; k < m->ncell; k++)
        for (ct_idx j = m->cell_off[k]; j < m->cell_off[k + 1]; j++)
            if (m->node_part[m->cell_node[j]] == 0)
                m->node_part[m->cell_node[j]] = m->cell_part[k];
    return CT_OK;
}

/* Boundary conditions: masks, imposed and initial velocities, gravity. */
static int build_bcs(cti_mbuild *b)
{
    ctd_model *m = b->m;
    const ctd_scene *sc = b->sc;
    for (unsigned i = 0; i < sc->boundary_count; i++) {
        const ctd_scene_bc *bc = &sc->boundary[i];
        if (bc->kind == CTD_BC_GRAVITY) {
            m->has_gravity = 1;
            for (int d = 0; d < 3; d++)
                m->gravity[d] = bc->value[d];
            continue;
        }
        if (bc->kind == CTD_BC_FORCE || bc->kind == CTD_BC_PRESSURE)
            continue; /* loads: the solver's (loads.c) */
        ct_nodeset ns = {0, NULL};
        int rc = ctd_model_select_nodes(m, bc->nodes, &ns, b->err, b->len);
        if (rc)
            return rc;
        /* A condition on no node is a mistake in the selection (a `where`
         * that misses the mesh by a tolerance): the run would go on
         * without it. As loads.c tells an empty load. */
        if (ns.n == 0) {
            ct_nodeset_destroy(&ns);
            return ctd_errf(b->err, b->len, CT_ERR_ARG,
                                 "%s:%d: boundary[%u].nodes: selects no node (kind %s)",
                                 sc->path, bc->line, i, bc->kind_name);
        }
        for (ct_idx k = 0; k < ns.n; k++) {
            ct_idx n = ns.node[k];
            if (bc->kind == CTD_BC_INITIAL_VELOCITY) {
                m->mesh.nodes.vx[n] = (ct_real)bc->value[0];
                m->mesh.nodes.vy[n] = (ct_real)bc->value[1];
                m->mesh.nodes.vz[n] = (ct_real)bc->value[2];
                continue;
            }
            for (int d = 0; d < 3; d++)
                if (bc->dof[d]) {
                    m->bc_mask[n] |= (uint8_t)(1u << d);
                    m->bc_v[d][n] = bc->kind == CTD_BC_VELOCITY ? (ct_real)bc->value[d] : 0;
                }
        }
        ct_nodeset_destroy(&ns);
    }
    return CT_OK;
}

/* Rigid bodies: one per rigid part with elements. */
static int build_bodies(cti_mbuild *b)
{
    ctd_model *m = b->m;
    const ctd_scene *sc = b->sc;
    ct_idx nn = m->mesh.nodes.n;
    m->body = calloc(sc->parts_count + 1, sizeof *m->body);
    ct_idx *list = malloc(sizeof(ct_idx) * ((size_t)nn + 1));
    int32_t *mark = malloc(sizeof(int32_t) * ((size_t)nn + 1));
    if (!m->body || !list || !mark) {
        free(list);
        free(mark);
        return ctd_errf(b->err, b->len, CT_ERR_NOMEM, "out of memory");
    }
    int rc = CT_OK;
    for (unsigned p = 0; p < sc->parts_count && !rc; p++) {
        const ctd_scene_part *pt = &sc->parts[p];
        if (pt->element != CTD_ELEM_RIGID)
            continue;
        for (ct_idx i = 0; i < nn; i++)
            mark[i] = 0;
        for (ct_idx c = 0; c < m->ncell; c++)
            if (m->cell_part[c] == pt->id)
                for (ct_idx j = m->cell_off[c]; j < m->cell_off[c + 1]; j++)
                    mark[m->cell_node[j]] = 1;
        ct_idx n = 0;
        for (ct_idx i = 0; i < nn; i++)
            if (mark[i]) {
                if (m->node_body[i] >= 0) {
                    rc = ctd_errf(b->err, b->len, CT_ERR_ARG,
                                       "%s:%d: parts[%u]: node %lld belongs to two rigid parts "
                                       "(%lld and %lld); expected each node in one rigid body "
                                       "at most", sc->path, pt->line, p, (long long)m->node_id[i],
                                       (long long)m->body[m->node_body[i]].part,
                                       (long long)pt->id);
                    break;
                }
                list[n++] = i;
            }
        if (rc || n == 0)
            continue;
        ctd_model_body *bd = &m->body[m->nbody];
        bd->part = pt->id;
        bd->id = pt->id;
        for (unsigned r = 0; r < sc->rigid_bodies_count; r++)
            if (sc->rigid_bodies[r].part == pt->id)
                bd->id = sc->rigid_bodies[r].id;
        const ct_nodes *nd = &m->mesh.nodes;
        /* A body whose masses all underflowed (a tiny rho on tiny
         * elements) has none: say so in the file's terms (ctd_rigid_init
         * would only refuse an invalid argument). */
        double mass = 0;
        for (ct_idx k = 0; k < n; k++)
            mass += nd->m[list[k]];
        if (!(mass > 0)) {
            rc = ctd_errf(b->err, b->len, CT_ERR_ARG,
                               "%s:%d: parts[%u].material.rho: rigid part %lld has a mass of %g "
                               "(rho %g is too small for its elements); expected a rho that "
                               "gives its elements a mass > 0", sc->path, pt->line, p,
                               (long long)pt->id, mass, pt->material.rho);
            break;
        }
        rc = ctd_rigid_init(&bd->rigid, n, list, nn, nd->m, nd->x, nd->y, nd->z, nd->vx, nd->vy,
                            nd->vz);
        if (rc) {
            rc = ctd_errf(b->err, b->len, rc, "%s:%d: parts[%u]: cannot make the rigid "
                               "body of part %lld: %s", sc->path, pt->line, p,
                               (long long)pt->id, ct_strerror(rc));
            break;
        }
        for (ct_idx k = 0; k < n; k++) {
            ct_idx i = list[k];
            m->node_body[i] = m->nbody;
            if (m->bc_mask[i] && !bd->driven) {
                bd->driven = 1;
                for (int d = 0; d < 3; d++) {
                    bd->dof[d] = m->bc_mask[i] >> d & 1;
                    bd->v[d] = bd->dof[d] ? m->bc_v[d][i] : 0;
                }
            }
        }
        m->nbody++;
    }
    free(list);
    free(mark);
    return rc;
}

int ctd_model_build(ctd_model *m, const ctd_scene *sc, char *err, size_t errlen)
{
    if (!m)
        return CT_ERR_ARG;
    memset(m, 0, sizeof *m);
    if (!sc)
        return CT_ERR_ARG;
    m->scene = sc;
    cti_mbuild b;
    memset(&b, 0, sizeof b);
    b.m = m;
    b.sc = sc;
    b.err = err;
    b.len = errlen;
    int rc = CT_OK;
    m->mesh_node_off = calloc(sc->mesh_count + 1, sizeof *m->mesh_node_off);
    if (!m->mesh_node_off)
        rc = ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    for (unsigned i = 0; i < sc->mesh_count && !rc; i++) {
        m->mesh_node_off[i] = (ct_idx)b.c.x.n;
        rc = sc->mesh[i].generate ? collect_generate(&b.c, sc, i, err, errlen)
                                  : collect_import(&b.c, sc, i, err, errlen);
        if (!rc && b.c.x.n > (size_t)INT32_MAX / 2)
            rc = ctd_errf(err, errlen, CT_ERR_TOOBIG, "too many nodes");
    }
    if (rc)
        goto fail;
    ct_idx nn = (ct_idx)b.c.x.n;
    m->mesh_node_off[sc->mesh_count] = nn;
    if ((rc = ct_mesh_init(&m->mesh, nn, 0)) != CT_OK) {
        rc = ctd_errf(err, errlen, rc, "out of memory");
        goto fail;
    }
    const double *cx = b.c.x.data, *cy = b.c.y.data, *cz = b.c.z.data;
    for (ct_idx i = 0; i < nn; i++) {
        m->mesh.nodes.x[i] = (ct_real)cx[i];
        m->mesh.nodes.y[i] = (ct_real)cy[i];
        m->mesh.nodes.z[i] = (ct_real)cz[i];
    }
    m->node_id = malloc(sizeof(int64_t) * ((size_t)nn + 1));
    m->node_part = calloc((size_t)nn + 1, sizeof(int32_t));
    m->node_body = malloc(sizeof(int32_t) * ((size_t)nn + 1));
    m->bc_mask = calloc((size_t)nn + 1, 1);
    for (int d = 0; d < 3; d++)
        m->bc_v[d] = ct_calloc((size_t)nn + 1, sizeof(ct_real));
    if (!m->node_id || !m->node_part || !m->node_body || !m->bc_mask || !m->bc_v[0] ||
        !m->bc_v[1] || !m->bc_v[2]) {
        rc = ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
        goto fail;
    }
    if (nn)
        memcpy(m->node_id, b.c.id.data, sizeof(int64_t) * (size_t)nn);
    for (ct_idx i = 0; i < nn; i++)
        m->node_body[i] = -1;
    if ((rc = cti_model_parts(&b)) || (rc = build_segments(&b)) || (rc = build_cells(&b)) ||
        (rc = build_bcs(&b)) || (rc = build_bodies(&b)))
        goto fail;
    for (ct_idx i = 0; i < nn; i++) {
        if (m->node_part[i] && !(m->mesh.nodes.m[i] > 0)) {
            /* Name the part (its line): a massive element whose mass
             * underflowed (a tiny rho) is not "only springs". */
            unsigned p = 0;
            while (p < sc->parts_count && sc->parts[p].id != m->node_part[i])
                p++;
            const ctd_scene_part *pt = p < sc->parts_count ? &sc->parts[p] : NULL;
            if (pt && pt->element != CTD_ELEM_SPRING)
                rc = ctd_errf(err, errlen, CT_ERR_ARG,
                                   "%s:%d: parts[%u].material.rho: node %lld of part %lld has "
                                   "a mass of %g (rho %g is too small for its elements)",
                                   sc->path, pt->line, p, (long long)m->node_id[i],
                                   (long long)pt->id, (double)m->mesh.nodes.m[i],
                                   pt->material.rho);
            else
                rc = ctd_errf(err, errlen, CT_ERR_ARG,
                                   "%s:%d: parts[%u]: node %lld (part %d) has no mass: only "
                                   "springs attach it (expected a truss, brick, shell or rigid "
                                   "part on it)", sc->path, pt ? pt->line : 0, p,
                                   (long long)m->node_id[i], m->node_part[i]);
            goto fail;
        }
        m->mass += m->mesh.nodes.m[i];
    }
    goto done;
fail:
    ctd_model_destroy(m);
done:
    if (b.faces)
        for (unsigned p = 0; p < sc->parts_count; p++)
            ctd_faces_destroy(&b.faces[p]);
    free(b.faces);
    free(b.face_set);
    collect_free(&b.c);
    return rc;
}
