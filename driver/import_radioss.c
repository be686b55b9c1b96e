/*
 * import_radioss.c -- the Radioss block-format reader (see import_radioss.h):
 * ctd_deck_read runs the passes (the scan of import_radioss_scan.c, the
 * resolution of import_radioss_resolve.c and import_radioss_sets.c), moves
 * the results into the deck and checks the mesh, reporting a bad segment by
 * its element and line; also ctd_deck_destroy, the warning and the lookups.
 * The whole read is O(file size); errors name the file, the line and the
 * field (the outer faces of bricks are in import_radioss_bricks.c).
 */
#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ct_internal.h"
#include "import_radioss_internal.h"

/* The warning string from the unsupported keywords. */
static char *make_warning(const ctd_rad_reader *r)
{
    size_t len = 64;
    for (int i = 0; i < r->nun; i++)
        len += strlen(r->un[i]) + 24;
    char *w = malloc(len);
    if (!w)
        return NULL;
    w[0] = 0;
    size_t k = 0;
    if (r->nun > 0)
        k += (size_t)snprintf(w, len, "unsupported keywords ignored:");
    for (int i = 0; i < r->nun; i++)
        k += (size_t)snprintf(w + k, len - k, "%s %s (%d)", i ? "," : "", r->un[i],
                              r->uncount[i]);
    return w;
}

/* Move what the passes built into the deck (the reader and the resolution
 * keep what is left to free). CT_ERR_NOMEM when a title, the warning or
 * the node map cannot be allocated. */
static int fill_deck(ctd_rad_reader *r, ctd_rad_res *z, ctd_deck *deck)
{
    int rc = CT_OK;
    ct_idx nseg = (ct_idx)z->nseg;
    if ((rc = ct_mesh_init(&deck->mesh, 0, nseg)) != CT_OK)
        return rc;
    /* The mesh: nodes from the resolution, the segments copied. */
    ct_nodes_destroy(&deck->mesh.nodes);
    deck->mesh.nodes = z->nd;
    memset(&z->nd, 0, sizeof z->nd);
    for (ct_idx s = 0; s < nseg; s++) {
        deck->mesh.n1[s] = z->sn[4 * (size_t)s];
        deck->mesh.n2[s] = z->sn[4 * (size_t)s + 1];
        deck->mesh.n3[s] = z->sn[4 * (size_t)s + 2];
        deck->mesh.n4[s] = z->sn[4 * (size_t)s + 3];
    }
    deck->node_id = r->nid;
    deck->node_line = r->nline;
    r->nid = NULL;
    r->nline = NULL;
    deck->nelemseg = (ct_idx)r->ns;
    deck->seg_elem = z->selem;
    deck->seg_part = z->spart;
    deck->seg_kind = z->skind;
    deck->seg_face = z->sface;
    deck->seg_line = z->sline;
    z->selem = z->spart = NULL;
    z->skind = z->sface = NULL;
    z->sline = NULL;
    deck->nbrick = (ct_idx)r->nb;
    deck->brick_id = r->bid;
    deck->brick_part = r->bpart;
    deck->brick_line = r->bline;
    deck->brick_node = z->bnode;
    r->bid = r->bpart = NULL;
    r->bline = NULL;
    z->bnode = NULL;
    deck->npart = (int)r->np;
    deck->part = r->part;
    for (size_t p = 0; p < r->np; p++)
        if (!(deck->part[p].title = ctd_rad_or_empty(deck->part[p].title)))
            rc = CT_ERR_NOMEM;
    r->part = NULL;
    r->np = 0;
    for (int i = 0; i < deck->nsurf; i++)
        if (!(deck->surf[i].title = ctd_rad_or_empty(deck->surf[i].title)))
            rc = CT_ERR_NOMEM;
    for (int i = 0; i < deck->ngroup; i++)
        if (!(deck->group[i].title = ctd_rad_or_empty(deck->group[i].title)))
            rc = CT_ERR_NOMEM;
    deck->title = ctd_rad_or_empty(r->title);
    r->title = NULL;
    deck->warning = make_warning(r);
    deck->nwarn = r->nun;
    deck->unsupported = r->un;
    deck->unsupported_count = r->uncount;
    r->un = NULL;
    r->uncount = NULL;
    r->nun = 0;
    ctd_rad_map *nm = malloc(sizeof *nm);
    if (nm) {
        *nm = z->nodes;
        memset(&z->nodes, 0, sizeof z->nodes);
        deck->node_map = nm;
    }
    return rc != CT_OK || !deck->title || !deck->warning || !nm ? CT_ERR_NOMEM : CT_OK;
}

/* The mesh check, reported in the deck's terms. */
static int check_mesh(ctd_rad_reader *r, const ctd_deck *deck)
{
    ct_diag md;
    memset(&md, 0, sizeof md);
    int rc = ct_mesh_validate(&deck->mesh, &md);
    if (rc == CT_OK)
        return CT_OK;
    int64_t s = md.index;
    if (s < 0 || s >= deck->mesh.nseg)
        return ctd_rad_fail(r, rc, -1, "%s", md.msg);
    int kind = deck->seg_kind[s];
    if (kind == CTD_SEG_BRICK_FACE)
        return ctd_rad_fail(r, rc, deck->seg_line[s], "face %d of /BRICK/%lld element %lld: %s",
                            deck->seg_face[s], (long long)deck->seg_part[s],
                            (long long)deck->seg_elem[s], md.msg);
    return ctd_rad_fail(r, rc, deck->seg_line[s], "%s/%lld element %lld: %s",
                        ctd_rad_kind_kw(kind), (long long)deck->seg_part[s],
                        (long long)deck->seg_elem[s], md.msg);
}

int ctd_deck_read(const char *path, ctd_deck *deck, ct_diag *diag)
{
    if (!deck || !path)
        return cti_fail(diag, CT_ERR_ARG, -1, "ctd_deck_read: NULL path or deck.");
    memset(deck, 0, sizeof *deck);
    ctd_rad_reader r;
    memset(&r, 0, sizeof r);
    r.path = path;
    r.diag = diag;
    ctd_rad_res z;
    memset(&z, 0, sizeof z);
    size_t size = 0;
    char *buf = ctd_rad_slurp(path, &size);
    if (!buf && errno == EFBIG && size > 0)
        return ctd_rad_fail(&r, CT_ERR_ARG, -1,
                            "the file has %llu bytes, more than the %llu (%g GiB) a deck "
                            "may have", (unsigned long long)size,
                            (unsigned long long)CTD_DECK_MAXBYTES,
                            (double)CTD_DECK_MAXBYTES / (double)((size_t)1 << 30));
    if (!buf && errno == EFBIG)
        return ctd_rad_fail(&r, CT_ERR_ARG, -1,
                            "the stream passed the %g GiB a deck may have before its end",
                            (double)CTD_DECK_MAXBYTES / (double)((size_t)1 << 30));
    /* Out of memory for the file's bytes is not the input's fault: the
     * caller (the scene, `contact`) tells it by the code (exit 5). */
    if (!buf && errno == ENOMEM)
        return ctd_rad_fail(&r, CT_ERR_NOMEM, -1, "out of memory reading the file");
    if (!buf)
        return ctd_rad_fail(&r, CT_ERR_ARG, -1, "cannot open or read the file: %s",
                            strerror(errno));
    int32_t nlines = 0;
    int rc = size == 0 ? ctd_rad_fail(&r, CT_ERR_ARG, -1, "the file is empty")
                       : ctd_rad_scan(&r, buf, size, &nlines);
    if (rc == CT_OK && (!r.saw_node || r.nn == 0))
        rc = ctd_rad_fail(&r, CT_ERR_ARG, nlines,
                          r.saw_node ? "no node lines under /NODE (end of file)"
                                     : "no /NODE keyword in the deck (end of file)");
    if (rc == CT_OK)
        rc = ctd_rad_res_nodes(&r, &z);
    if (rc == CT_OK)
        rc = ctd_rad_res_elems(&r, &z);
    if (rc == CT_OK)
        rc = ctd_rad_res_grshel(&r, &z);
    if (rc == CT_OK)
        rc = ctd_rad_res_sets(&r, &z, deck);
    if (rc == CT_OK && (rc = fill_deck(&r, &z, deck)) != CT_OK)
        rc = ctd_rad_fail(&r, rc, -1, "out of memory");
    if (rc == CT_OK)
        rc = check_mesh(&r, deck);
    free(buf);
    ctd_rad_res_free(&z, r.nl);
    ctd_rad_reader_free(&r);
    if (rc != CT_OK)
        ctd_deck_destroy(deck);
    return rc;
}

void ctd_deck_destroy(ctd_deck *d)
{
    if (!d)
        return;
    ct_mesh_destroy(&d->mesh);
    free(d->node_id); free(d->node_line);
    free(d->seg_elem); free(d->seg_part); free(d->seg_kind); free(d->seg_face);
    free(d->seg_line);
    free(d->brick_id); free(d->brick_part); free(d->brick_node); free(d->brick_line);
    for (int i = 0; i < d->npart; i++)
        free(d->part[i].title);
    free(d->part);
    for (int i = 0; i < d->nsurf; i++) {
        free(d->surf[i].title);
        ct_free(d->surf[i].s.seg);
    }
    free(d->surf);
    for (int i = 0; i < d->ngroup; i++) {
        free(d->group[i].title);
        ct_free(d->group[i].s.node);
    }
    free(d->group);
    free(d->title);
    for (int i = 0; i < d->nwarn; i++)
        free(d->unsupported[i]);
    free(d->unsupported);
    free(d->unsupported_count);
    free(d->warning);
    ctd_rad_map_free(d->node_map);
    free(d->node_map);
    memset(d, 0, sizeof *d);
}

const char *ctd_deck_warning(const ctd_deck *d)
{
    return d && d->warning ? d->warning : "";
}

ct_idx ctd_deck_node(const ctd_deck *d, int64_t id)
{
    return d && id > 0 ? ctd_rad_map_get(d->node_map, id) : -1;
}

/* The first of n records of `size` bytes, each starting with its int64_t
 * id (ctd_part, ctd_surf, ctd_group), whose id is `id`; or NULL. */
static const void *find_id(const void *rec, int n, size_t size, int64_t id)
{
    _Static_assert(offsetof(ctd_part, id) == 0 && offsetof(ctd_surf, id) == 0 &&
                       offsetof(ctd_group, id) == 0,
                   "find_id reads the id at the start of the record");
    for (int i = 0; i < n; i++) {
        const char *p = (const char *)rec + (size_t)i * size;
        if (*(const int64_t *)(const void *)p == id)
            return p;
    }
    return NULL;
}

const ctd_part *ctd_deck_part(const ctd_deck *d, int64_t id)
{
    return d ? find_id(d->part, d->npart, sizeof *d->part, id) : NULL;
}

const ctd_surf *ctd_deck_surf(const ctd_deck *d, int64_t id)
{
    return d ? find_id(d->surf, d->nsurf, sizeof *d->surf, id) : NULL;
}

const ctd_group *ctd_deck_group(const ctd_deck *d, int64_t id)
{
    return d ? find_id(d->group, d->ngroup, sizeof *d->group, id) : NULL;
}
