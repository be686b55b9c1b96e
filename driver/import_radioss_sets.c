/*
 * import_radioss_sets.c -- the sets of the Radioss reader, resolved after
 * the nodes, elements and parts: /GRSHEL/SHEL lists (shells), surfaces
 * (/SURF/PART: the shells of shell parts and the outer faces of the bricks
 * of brick parts, each face made a segment once; /SURF/GRSHEL) and node
 * groups (/GRNOD/NODE, /GRNOD/PART, /GRNOD/GRSHEL). Unknown ids are
 * CT_ERR_RANGE, named by line and field number.
 */
#include <stdlib.h>
#include <string.h>

#include "import_radioss_internal.h"

static int cmp_idx(const void *a, const void *b)
{
    ct_idx x = *(const ct_idx *)a, y = *(const ct_idx *)b;
    return (x > y) - (x < y);
}

/* A growing ct_idx list (ct_calloc'd: it becomes a ct_surface or a
 * ct_nodeset). */
typedef struct ilist {
    size_t n, cap;
    ct_idx *v;
} ilist;

/* Append v unless stamped already in this generation. */
static int push(ctd_rad_res *z, ilist *o, ct_idx v)
{
    if (z->stamp[v] == z->gen)
        return CT_OK;
    z->stamp[v] = z->gen;
    if (o->n == o->cap) {
        size_t c = ctd_rad_next_cap(o->cap);
        ct_idx *q = ct_calloc(c, sizeof *q);
        if (!q)
            return CT_ERR_NOMEM;
        if (o->n)
            memcpy(q, o->v, o->n * sizeof *q);
        ct_free(o->v);
        o->v = q;
        o->cap = c;
    }
    o->v[o->n++] = v;
    return CT_OK;
}

/* 1 the first time the part or /GRSHEL index k is met since the last
 * z->idgen++ (one list's pass over its ids), else 0: a repeated id adds
 * nothing, and without this check a list that repeats the id of a large
 * part n times would cost n times the part. */
static int first_use(ctd_rad_res *z, ct_idx k)
{
    if (z->idstamp[k] == z->idgen)
        return 0;
    z->idstamp[k] = z->idgen;
    return 1;
}

/* The index (in map m) of the id of entry i of list l; an unknown id is
 * CT_ERR_RANGE, "field 'F' (number K) of KW/ID: unknown WHAT ID". */
static int list_ref(ctd_rad_reader *r, const ctd_rad_map *m, const ctd_rad_list *l, size_t i,
                    const char *what, ct_idx *v)
{
    *v = ctd_rad_map_get(m, l->ids[i]);
    if (*v < 0)
        return ctd_rad_fail(r, CT_ERR_RANGE, l->lines[i],
                            "field '%s' (number %d) of %s/%lld: unknown %s %lld",
                            ctd_rad_list_field[l->type], l->fld[i], ctd_rad_list_kw[l->type],
                            (long long)l->id, what, (long long)l->ids[i]);
    return CT_OK;
}

/* ---- /GRSHEL ----------------------------------------------------------- */

int ctd_rad_res_grshel(ctd_rad_reader *r, ctd_rad_res *z)
{
    if (ctd_rad_map_init(&z->grshel, r->nl) || !(z->gseg = calloc(r->nl + 1, sizeof *z->gseg)) ||
        !(z->gsegn = calloc(r->nl + 1, sizeof *z->gsegn)))
        return ctd_rad_nomem(r, -1);
    for (size_t g = 0; g < r->nl; g++) {
        const ctd_rad_list *l = &r->list[g];
        if (l->type != CTD_RAD_L_GRSHEL_SHEL)
            continue;
        ct_idx prev = ctd_rad_map_put(&z->grshel, l->id, (ct_idx)g);
        if (prev >= 0)
            return ctd_rad_fail(r, CT_ERR_ARG, l->line,
                                "keyword /GRSHEL/SHEL/%lld: id %lld is defined twice (first on "
                                "line %ld)",
                                (long long)l->id, (long long)l->id, (long)r->list[prev].line);
        if (!(z->gseg[g] = malloc((l->n + 1) * sizeof **z->gseg)))
            return ctd_rad_nomem(r, -1);
        for (size_t i = 0; i < l->n; i++) {
            int rc = list_ref(r, &z->shells, l, i, "shell", &z->gseg[g][i]);
            if (rc != CT_OK)
                return rc;
        }
        z->gsegn[g] = (ct_idx)l->n;
    }
    return CT_OK;
}

/* Check the part ids of list l (an unknown id is an error); *any_brick
 * tells whether one of them has bricks. */
static int check_parts(ctd_rad_reader *r, ctd_rad_res *z, const ctd_rad_list *l, int *any_brick)
{
    *any_brick = 0;
    for (size_t i = 0; i < l->n; i++) {
        ct_idx k;
        int rc = list_ref(r, &z->parts, l, i, "part", &k);
        if (rc != CT_OK)
            return rc;
        *any_brick |= z->pk_brick[k];
    }
    return CT_OK;
}

/* ---- Surfaces ---------------------------------------------------------- */

/* The face classes of all the deck's bricks and the arrays of the cards'
 * selections, made once (at the first card that needs them). */
static int brick_classes(ctd_rad_reader *r, ctd_rad_res *z)
{
    if (z->fbrk)
        return CT_OK;
    z->fcls = malloc((6 * r->nb + 1) * sizeof *z->fcls);
    z->fstamp = calloc(6 * r->nb + 1, sizeof *z->fstamp);
    if (!z->fcls || !z->fstamp ||
        ctd_brick_face_classes(z->nd.n, (ct_idx)r->nb, z->bnode, NULL, z->fcls) != CT_OK ||
        !(z->fbrk = malloc((r->nb + 1) * sizeof *z->fbrk)))
        return ctd_rad_nomem(r, -1);
    return CT_OK;
}

/* The outer faces of the bricks of the parts of list l, made segments
 * (once each, whatever the number of surfaces that use them). The cost is
 * that of the parts' bricks: their faces' classes, found once for the
 * deck, are counted among them. */
static int surf_brick_faces(ctd_rad_reader *r, ctd_rad_res *z, const ctd_rad_list *l, ilist *o)
{
    int rc = brick_classes(r, z), nparts = 0;
    if (rc != CT_OK)
        return rc;
    /* The bricks, in increasing order (each part's list is), as when the
     * faces of all bricks were scanned: this order numbers new segments. */
    ct_idx nsel = 0;
    z->idgen++;
    for (size_t i = 0; i < l->n; i++) {
        ct_idx k = ctd_rad_map_get(&z->parts, l->ids[i]), nk = z->pk_boff[k + 1] - z->pk_boff[k];
        if (!first_use(z, k) || nk == 0)
            continue;
        memcpy(z->fbrk + nsel, z->pk_brk + z->pk_boff[k], (size_t)nk * sizeof *z->fbrk);
        nsel += nk;
        nparts++;
    }
    if (nparts > 1)
        qsort(z->fbrk, (size_t)nsel, sizeof *z->fbrk, cmp_idx);
    ctd_faces f;
    if (ctd_brick_select_outer(z->nd.x, z->nd.y, z->nd.z, z->bnode, z->fcls, nsel, z->fbrk,
                               z->fstamp, ++z->fgen, &f) != CT_OK)
        return ctd_rad_nomem(r, -1);
    for (ct_idx j = 0; j < f.n && rc == CT_OK; j++) {
        size_t slot = 6 * (size_t)f.brick[j] + (size_t)f.local[j];
        if (z->faceseg[slot] < 0) {
            if (z->nseg >= (size_t)INT32_MAX - CT_PAD || ctd_rad_seg_room(z, z->nseg + 1)) {
                rc = ctd_rad_nomem(r, -1);
                break;
            }
            /* The stamp array covers the segments that can exist. */
            size_t s = z->nseg++;
            memcpy(z->sn + 4 * s, f.node + 4 * (size_t)j, 4 * sizeof *z->sn);
            z->selem[s] = r->bid[f.brick[j]];
            z->spart[s] = r->bpart[f.brick[j]];
            z->skind[s] = CTD_SEG_BRICK_FACE;
            z->sface[s] = f.local[j];
            z->sline[s] = r->bline[f.brick[j]];
            z->faceseg[slot] = (ct_idx)s;
        }
        if (push(z, o, z->faceseg[slot]))
            rc = ctd_rad_nomem(r, -1);
    }
    ctd_faces_destroy(&f);
    return rc;
}

/* The segments of one surface card. */
static int res_surf(ctd_rad_reader *r, ctd_rad_res *z, const ctd_rad_list *l, ilist *o)
{
    z->gen++;
    z->idgen++;
    if (l->type == CTD_RAD_L_SURF_GRSHEL) {
        for (size_t i = 0; i < l->n; i++) {
            ct_idx g;
            int rc = list_ref(r, &z->grshel, l, i, "/GRSHEL/SHEL", &g);
            if (rc != CT_OK)
                return rc;
            if (!first_use(z, g))
                continue;
            for (ct_idx k = 0; k < z->gsegn[g]; k++)
                if (push(z, o, z->gseg[g][k]))
                    return ctd_rad_nomem(r, -1);
        }
        return CT_OK;
    }
    int any_brick, rc = check_parts(r, z, l, &any_brick);
    if (rc != CT_OK)
        return rc;
    for (size_t i = 0; i < l->n; i++) {
        ct_idx k = ctd_rad_map_get(&z->parts, l->ids[i]);
        if (!first_use(z, k))
            continue;
        for (ct_idx j = z->pk_soff[k]; j < z->pk_soff[k + 1]; j++)
            if (push(z, o, z->pk_seg[j]))
                return ctd_rad_nomem(r, -1);
    }
    return any_brick ? surf_brick_faces(r, z, l, o) : CT_OK;
}

/* ---- Node groups ------------------------------------------------------- */

/* Push the first nc nodes of each of the n elements elem[0..n) of the
 * connectivity conn (stride `stride`). */
static int push_nodes(ctd_rad_res *z, ilist *o, const ct_idx *conn, int stride, int nc,
                      const ct_idx *elem, ct_idx n)
{
    for (ct_idx j = 0; j < n; j++)
        for (int c = 0; c < nc; c++)
            if (push(z, o, conn[(size_t)stride * (size_t)elem[j] + (size_t)c]))
                return CT_ERR_NOMEM;
    return CT_OK;
}

/* The nodes of one node-group card, sorted. */
static int res_group(ctd_rad_reader *r, ctd_rad_res *z, const ctd_rad_list *l, ilist *o)
{
    z->gen++;
    z->idgen++;
    int nomem = 0, any_brick, rc;
    if (l->type == CTD_RAD_L_GRNOD_PART && (rc = check_parts(r, z, l, &any_brick)) != CT_OK)
        return rc;
    for (size_t i = 0; i < l->n && !nomem; i++) {
        if (l->type == CTD_RAD_L_GRNOD_NODE) {
            ct_idx v;
            if ((rc = list_ref(r, &z->nodes, l, i, "node id", &v)) != CT_OK)
                return rc;
            nomem = push(z, o, v) != CT_OK;
        } else if (l->type == CTD_RAD_L_GRNOD_GRSHEL) {
            ct_idx g;
            if ((rc = list_ref(r, &z->grshel, l, i, "/GRSHEL/SHEL", &g)) != CT_OK)
                return rc;
            if (first_use(z, g))
                nomem = push_nodes(z, o, z->sn, 4, 4, z->gseg[g], z->gsegn[g]) != CT_OK;
        } else {
            ct_idx k = ctd_rad_map_get(&z->parts, l->ids[i]);
            if (!first_use(z, k))
                continue;
            nomem = push_nodes(z, o, z->sn, 4, 4, z->pk_seg + z->pk_soff[k],
                               z->pk_soff[k + 1] - z->pk_soff[k]) != CT_OK ||
                    push_nodes(z, o, z->bnode, 8, 8, z->pk_brk + z->pk_boff[k],
                               z->pk_boff[k + 1] - z->pk_boff[k]) != CT_OK;
        }
    }
    if (nomem)
        return ctd_rad_nomem(r, -1);
    if (o->n > 1)
        qsort(o->v, o->n, sizeof *o->v, cmp_idx);
    return CT_OK;
}

/* ---- All sets ---------------------------------------------------------- */

int ctd_rad_res_sets(ctd_rad_reader *r, ctd_rad_res *z, ctd_deck *d)
{
    size_t nsurf = 0, ngroup = 0;
    for (size_t i = 0; i < r->nl; i++) {
        nsurf += r->list[i].type <= CTD_RAD_L_SURF_GRSHEL;
        ngroup += r->list[i].type >= CTD_RAD_L_GRNOD_NODE &&
                  r->list[i].type <= CTD_RAD_L_GRNOD_GRSHEL;
    }
    /* Stamps cover nodes and every segment there can be (6 faces a brick). */
    size_t nstamp = r->nn + r->ns + 6 * r->nb + 1;
    d->surf = calloc(nsurf + 1, sizeof *d->surf);
    d->group = calloc(ngroup + 1, sizeof *d->group);
    z->stamp = calloc(nstamp, sizeof *z->stamp);
    z->idstamp = calloc((z->npk > r->nl ? z->npk : r->nl) + 1, sizeof *z->idstamp);
    z->faceseg = malloc((6 * r->nb + 1) * sizeof *z->faceseg);
    if (!d->surf || !d->group || !z->stamp || !z->idstamp || !z->faceseg)
        return ctd_rad_nomem(r, -1);
    for (size_t i = 0; i < 6 * r->nb; i++)
        z->faceseg[i] = -1;
    ctd_rad_map sid, gid;
    memset(&sid, 0, sizeof sid);
    memset(&gid, 0, sizeof gid);
    int rc = CT_OK;
    if (ctd_rad_map_init(&sid, nsurf) || ctd_rad_map_init(&gid, ngroup))
        rc = ctd_rad_nomem(r, -1);
    for (size_t i = 0; i < r->nl && rc == CT_OK; i++) {
        ctd_rad_list *l = &r->list[i];
        if (l->type == CTD_RAD_L_GRSHEL_SHEL)
            continue;
        int surf = l->type <= CTD_RAD_L_SURF_GRSHEL;
        ct_idx prev = ctd_rad_map_put(surf ? &sid : &gid, l->id, (ct_idx)i);
        if (prev >= 0) {
            rc = ctd_rad_fail(r, CT_ERR_ARG, l->line,
                              "keyword %s/%lld: id %lld is already used by %s/%lld on line %ld",
                              ctd_rad_list_kw[l->type], (long long)l->id, (long long)l->id,
                              ctd_rad_list_kw[r->list[prev].type], (long long)l->id,
                              (long)r->list[prev].line);
            break;
        }
        ilist o = {0, 0, NULL};
        rc = surf ? res_surf(r, z, l, &o) : res_group(r, z, l, &o);
        if (rc == CT_OK && surf && o.n > 1)
            qsort(o.v, o.n, sizeof *o.v, cmp_idx);
        if (rc == CT_OK && !o.v && !(o.v = ct_calloc(1, sizeof *o.v)))
            rc = ctd_rad_nomem(r, -1);
        if (rc != CT_OK) {
            ct_free(o.v);
            break;
        }
        if (surf) {
            ctd_surf *s = &d->surf[d->nsurf++];
            s->id = l->id;
            s->title = l->title;
            s->line = l->line;
            s->s.n = (ct_idx)o.n;
            s->s.seg = o.v;
        } else {
            ctd_group *g = &d->group[d->ngroup++];
            g->id = l->id;
            g->title = l->title;
            g->line = l->line;
            g->s.n = (ct_idx)o.n;
            g->s.node = o.v;
        }
        l->title = NULL;
    }
    ctd_rad_map_free(&sid);
    ctd_rad_map_free(&gid);
    return rc;
}
