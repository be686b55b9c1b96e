/*
 * model_select.c -- node and surface selections of a scene (scene.h) turned
 * into node indices and segment indices of a model.
 */
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "model_internal.h"

ct_idx ctd_model_node(const ctd_model *m, int64_t id)
{
    const ctd_scene *sc = m->scene;
    for (unsigned i = 0; i < sc->mesh_count; i++) {
        const ctd_scene_mesh *me = &sc->mesh[i];
        ct_idx off = m->mesh_node_off[i], n = m->mesh_node_off[i + 1] - off;
        if (me->generate) {
            if (id >= me->first_id && id < me->first_id + n)
                return off + (ct_idx)(id - me->first_id);
        } else if (me->import && me->import->deck) {
            ct_idx k = ctd_deck_node(me->import->deck, id);
            if (k >= 0)
                return off + k;
        }
    }
    return -1;
}

static int in_parts(const ctd_scene_sel *s, int64_t part)
{
    if (s->part && s->part == part)
        return 1;
    for (unsigned k = 0; k < s->parts_count; k++)
        if (s->parts[k] == part)
            return 1;
    return 0;
}

static int where_ok(const ctd_model *m, const ctd_scene_sel *s, ct_idx n)
{
    const ct_nodes *nd = &m->mesh.nodes;
    return ctd_where_eval(&s->where, nd->x[n], nd->y[n], nd->z[n]);
}

int ctd_model_select_nodes(const ctd_model *m, const ctd_scene_sel *sel, ct_nodeset *out,
                           char *err, size_t errlen)
{
    out->n = 0;
    out->node = NULL;
    if (!m || !sel)
        return CT_ERR_ARG;
    const ctd_scene *sc = m->scene;
    ct_idx nn = m->mesh.nodes.n;
    unsigned char *mark = calloc((size_t)nn + 1, 1);
    if (!mark)
        return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    int any = 0;
    if (sel->part || sel->parts_count) {
        any = 1;
        for (ct_idx c = 0; c < m->ncell; c++)
            if (in_parts(sel, m->cell_part[c]))
                for (ct_idx j = m->cell_off[c]; j < m->cell_off[c + 1]; j++)
                    mark[m->cell_node[j]] = 1;
    }
    if (sel->group) {
        any = 1;
        int found = 0;
        for (unsigned i = 0; i < sc->mesh_count; i++) {
            const ctd_deck *d = sc->mesh[i].import ? sc->mesh[i].import->deck : NULL;
            const ctd_group *g = d ? ctd_deck_group(d, sel->group) : NULL;
            if (!g)
                continue;
            found = 1;
            for (ct_idx k = 0; k < g->s.n; k++)
                mark[m->mesh_node_off[i] + g->s.node[k]] = 1;
        }
        if (!found) {
            free(mark);
            return ctd_errf(err, errlen, CT_ERR_RANGE, "%s:%d: node group %lld is in no "
                                 "imported deck", sc->path, sel->line, (long long)sel->group);
        }
    }
    for (unsigned k = 0; k < sel->ids_count; k++) {
        any = 1;
        ct_idx n = ctd_model_node(m, sel->ids[k]);
        if (n < 0) {
            free(mark);
            return ctd_errf(err, errlen, CT_ERR_RANGE, "%s:%d: node %lld does not exist",
                                 sc->path, sel->line, (long long)sel->ids[k]);
        }
        mark[n] = 1;
    }
    if (!any)
        memset(mark, 1, (size_t)nn);
    ct_idx cnt = 0;
    for (ct_idx i = 0; i < nn; i++) {
        mark[i] = mark[i] && where_ok(m, sel, i);
        cnt += mark[i];
    }
    out->node = ct_calloc((size_t)cnt + 1, sizeof(ct_idx));
    if (!out->node) {
        free(mark);
        return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    }
    for (ct_idx i = 0; i < nn; i++)
        if (mark[i])
            out->node[out->n++] = i;
    free(mark);
    return CT_OK;
}

int ctd_model_select_surface(const ctd_model *m, const ctd_scene_sel *sel, ct_surface *out,
                             char *err, size_t errlen)
{
    out->n = 0;
    out->seg = NULL;
    if (!m || !sel)
        return CT_ERR_ARG;
    const ctd_scene *sc = m->scene;
    const ct_mesh *me = &m->mesh;
    ct_idx ns = me->nseg;
    unsigned char *mark = calloc((size_t)ns + 1, 1);
    if (!mark)
        return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    if (sel->part || sel->parts_count) {
        for (ct_idx s = 0; s < ns; s++)
            mark[s] = m->seg_src[s] != CTD_SEGSRC_DECK && in_parts(sel, m->seg_part[s]);
    } else if (sel->surf) {
        int found = 0;
        for (unsigned i = 0; i < sc->mesh_count; i++) {
            const ctd_deck *d = sc->mesh[i].import ? sc->mesh[i].import->deck : NULL;
            const ctd_surf *su = d ? ctd_deck_surf(d, sel->surf) : NULL;
            if (!su)
                continue;
            found = 1;
            /* Deck segment index -> model segment, for this deck. */
            unsigned char *want = calloc((size_t)d->mesh.nseg + 1, 1);
            if (!want) {
                free(mark);
                return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
            }
            for (ct_idx k = 0; k < su->s.n; k++)
                want[su->s.seg[k]] = 1;
            for (ct_idx s = 0; s < ns; s++)
                if (m->seg_mesh[s] == (int32_t)i && m->seg_deck[s] >= 0 && want[m->seg_deck[s]])
                    mark[s] = 1;
            free(want);
        }
        if (!found) {
            free(mark);
            return ctd_errf(err, errlen, CT_ERR_RANGE, "%s:%d: surface %lld is in no "
                                 "imported deck", sc->path, sel->line, (long long)sel->surf);
        }
    }
    ct_idx cnt = 0;
    for (ct_idx s = 0; s < ns; s++) {
        if (mark[s] && sel->where.n) {
            const ct_idx q[4] = {me->n1[s], me->n2[s], me->n3[s], me->n4[s]};
            for (int a = 0; a < 4; a++)
                if (!where_ok(m, sel, q[a]))
                    mark[s] = 0;
        }
        cnt += mark[s];
    }
    out->seg = ct_calloc((size_t)cnt + 1, sizeof(ct_idx));
    if (!out->seg) {
        free(mark);
        return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    }
    for (ct_idx s = 0; s < ns; s++)
        if (mark[s])
            out->seg[out->n++] = s;
    free(mark);
    return CT_OK;
}
