/*
 * import_radioss_resolve.c -- the second pass of the Radioss reader for
 * nodes, elements and parts: the open-addressing id maps, node ids turned
 * into node indices (repeated ids and unknown or repeated element nodes are
 * errors), the element segments, the bricks, and each part's segments and
 * bricks (dense part indices, CSR lists) for the sets that follow.
 */
#include <stdlib.h>
#include <string.h>

#include "import_radioss_internal.h"

/* ---- Id maps ----------------------------------------------------------- */

int ctd_rad_map_init(ctd_rad_map *m, size_t n)
{
    size_t cap = 64;
    while (cap < 2 * n + 16)
        cap *= 2;
    m->mask = cap - 1;
    m->key = calloc(cap, sizeof *m->key);
    m->val = malloc(cap * sizeof *m->val);
    return m->key && m->val ? CT_OK : CT_ERR_NOMEM;
}

void ctd_rad_map_free(ctd_rad_map *m)
{
    if (!m)
        return;
    free(m->key);
    free(m->val);
    m->key = NULL;
    m->val = NULL;
}

/* The slot of k: where it is, or the empty slot where it would go. */
static size_t map_slot(const ctd_rad_map *m, int64_t k)
{
    uint64_t h = (uint64_t)k;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    h ^= h >> 33;
    size_t i = (size_t)h & m->mask;
    while (m->key[i] != 0 && m->key[i] != k)
        i = (i + 1) & m->mask;
    return i;
}

ct_idx ctd_rad_map_put(ctd_rad_map *m, int64_t k, ct_idx v)
{
    size_t i = map_slot(m, k);
    if (m->key[i] == k)
        return m->val[i];
    m->key[i] = k;
    m->val[i] = v;
    return -1;
}

ct_idx ctd_rad_map_get(const ctd_rad_map *m, int64_t k)
{
    if (!m || !m->key || k == 0)
        return -1;
    size_t i = map_slot(m, k);
    return m->key[i] == k ? m->val[i] : -1;
}

/* ---- Resolution state -------------------------------------------------- */

void ctd_rad_res_free(ctd_rad_res *z, size_t nl)
{
    ctd_rad_map_free(&z->nodes);
    ctd_rad_map_free(&z->shells);
    ctd_rad_map_free(&z->parts);
    ctd_rad_map_free(&z->grshel);
    ct_nodes_destroy(&z->nd);
    free(z->sn); free(z->selem); free(z->spart); free(z->skind); free(z->sface);
    free(z->sline); free(z->spk); free(z->bnode); free(z->bpk); free(z->faceseg);
    free(z->pk_id); free(z->pk_brick);
    free(z->pk_soff); free(z->pk_seg); free(z->pk_boff); free(z->pk_brk); free(z->stamp);
    free(z->idstamp); free(z->fcls); free(z->fstamp); free(z->fbrk);
    if (z->gseg)
        for (size_t i = 0; i < nl; i++)
            free(z->gseg[i]);
    free(z->gseg);
    free(z->gsegn);
}

int ctd_rad_seg_room(ctd_rad_res *z, size_t need)
{
    if (need <= z->capseg)
        return CT_OK;
    size_t c = z->capseg;
    while (c < need)
        c = ctd_rad_next_cap(c);
    if (ctd_rad_regrow(&z->sn, 4 * c, sizeof *z->sn) ||
        ctd_rad_regrow(&z->selem, c, sizeof *z->selem) ||
        ctd_rad_regrow(&z->spart, c, sizeof *z->spart) ||
        ctd_rad_regrow(&z->skind, c, sizeof *z->skind) ||
        ctd_rad_regrow(&z->sface, c, sizeof *z->sface) ||
        ctd_rad_regrow(&z->sline, c, sizeof *z->sline))
        return CT_ERR_NOMEM;
    z->capseg = c;
    return CT_OK;
}

const char *ctd_rad_kind_kw(int kind)
{
    return kind == CTD_SEG_SHELL ? "/SHELL" : kind == CTD_SEG_SH3N ? "/SH3N" : "/BRICK";
}

/* ---- Nodes ------------------------------------------------------------- */

int ctd_rad_res_nodes(ctd_rad_reader *r, ctd_rad_res *z)
{
    if (r->nn > (size_t)INT32_MAX - CT_PAD)
        return ctd_rad_fail(r, CT_ERR_TOOBIG, r->nline[r->nn - 1], "more than %d nodes",
                            INT32_MAX - CT_PAD);
    if (ctd_rad_map_init(&z->nodes, r->nn) || ct_nodes_init(&z->nd, (ct_idx)r->nn))
        return ctd_rad_nomem(r, -1);
    for (size_t i = 0; i < r->nn; i++) {
        ct_idx prev = ctd_rad_map_put(&z->nodes, r->nid[i], (ct_idx)i);
        if (prev >= 0)
            return ctd_rad_fail(r, CT_ERR_ARG, r->nline[i],
                                "field 'node_id' of /NODE: node id %lld is defined twice "
                                "(first on line %ld)",
                                (long long)r->nid[i], (long)r->nline[prev]);
        z->nd.x[i] = (ct_real)r->xyz[3 * i];
        z->nd.y[i] = (ct_real)r->xyz[3 * i + 1];
        z->nd.z[i] = (ct_real)r->xyz[3 * i + 2];
    }
    return CT_OK;
}

/* ---- Elements ---------------------------------------------------------- */

/* Resolve n node ids of an element; check repeats (allowed: n4 == n3 of a
 * /SHELL when `tri_ok`, and any repeat when `rep_ok`). */
static int res_corners(ctd_rad_reader *r, ctd_rad_res *z, const int64_t *raw, int n,
                       ct_idx *out, int32_t ln, const char *kw, int64_t part, int tri_ok,
                       int rep_ok)
{
    const char *const *corner = ctd_rad_corner;
    for (int k = 0; k < n; k++) {
        out[k] = ctd_rad_map_get(&z->nodes, raw[k]);
        if (out[k] < 0)
            return ctd_rad_fail(r, CT_ERR_RANGE, ln,
                                "field '%s' of %s/%lld: unknown node id %lld", corner[k], kw,
                                (long long)part, (long long)raw[k]);
        for (int j = 0; j < k && !rep_ok; j++)
            if (out[k] == out[j] && !(tri_ok && k == 3 && j == 2))
                return ctd_rad_fail(r, CT_ERR_DUPNODE, ln,
                                    "field '%s' of %s/%lld: node id %lld repeats field '%s'",
                                    corner[k], kw, (long long)part, (long long)raw[k],
                                    corner[j]);
    }
    return CT_OK;
}

/* Put an element id in its map; a repeated id is an error. */
static int elem_id(ctd_rad_reader *r, ctd_rad_map *m, int64_t id, ct_idx i,
                   const int32_t *lines, const char *name, const char *kw, int64_t part)
{
    ct_idx prev = ctd_rad_map_put(m, id, i);
    if (prev < 0)
        return CT_OK;
    return ctd_rad_fail(r, CT_ERR_ARG, lines[i],
                        "field '%s' of %s/%lld: element id %lld is defined twice (first on "
                        "line %ld)",
                        name, kw, (long long)part, (long long)id, (long)lines[prev]);
}

/* Shells and triangles: their segments, the shell id map. */
static int res_shells(ctd_rad_reader *r, ctd_rad_res *z, ctd_rad_map *tri)
{
    for (size_t s = 0; s < r->ns; s++) {
        int kind = r->skind[s], shell = kind == CTD_SEG_SHELL;
        const char *kw = ctd_rad_kind_kw(kind);
        int rc = res_corners(r, z, r->sraw + 4 * s, shell ? 4 : 3, z->sn + 4 * s, r->sline[s],
                             kw, r->spart[s], 1, 0);
        if (rc == CT_OK)
            rc = elem_id(r, shell ? &z->shells : tri, r->sid[s], (ct_idx)s, r->sline,
                         shell ? "shell_id" : "sh3n_id", kw, r->spart[s]);
        if (rc != CT_OK)
            return rc;
        if (!shell)
            z->sn[4 * s + 3] = z->sn[4 * s + 2];
        z->selem[s] = r->sid[s];
        z->spart[s] = r->spart[s];
        z->skind[s] = r->skind[s];
        z->sface[s] = -1;
        z->sline[s] = r->sline[s];
    }
    z->nseg = r->ns;
    return CT_OK;
}

/* Bricks: their nodes (at least 4 distinct), the brick ids unique. */
static int res_bricks(ctd_rad_reader *r, ctd_rad_res *z, ctd_rad_map *bricks)
{
    for (size_t b = 0; b < r->nb; b++) {
        ct_idx *c = z->bnode + 8 * b;
        int rc = res_corners(r, z, r->braw + 8 * b, 8, c, r->bline[b], "/BRICK", r->bpart[b],
                             0, 1);
        if (rc != CT_OK)
            return rc;
        int distinct = 0;
        for (int k = 0; k < 8; k++) {
            int seen = 0;
            for (int j = 0; j < k; j++)
                seen |= c[j] == c[k];
            distinct += !seen;
        }
        if (distinct < 4)
            return ctd_rad_fail(r, CT_ERR_DUPNODE, r->bline[b],
                                "/BRICK/%lld element %lld has only %d distinct nodes (at "
                                "least 4 needed)",
                                (long long)r->bpart[b], (long long)r->bid[b], distinct);
        rc = elem_id(r, bricks, r->bid[b], (ct_idx)b, r->bline, "brick_id", "/BRICK",
                     r->bpart[b]);
        if (rc != CT_OK)
            return rc;
    }
    return CT_OK;
}

/* ---- Parts ------------------------------------------------------------- */

/* Dense part indices: the /PART cards first, then parts that only have
 * elements; then each part's segments and bricks, in file order (counting
 * sorts), so that part-based sets cost what the parts hold. */
static int res_parts(ctd_rad_reader *r, ctd_rad_res *z)
{
    size_t maxp = r->np + r->ns + r->nb;
    if (ctd_rad_map_init(&z->parts, maxp) ||
        !(z->pk_id = malloc((maxp + 1) * sizeof *z->pk_id)) ||
        !(z->pk_brick = calloc(maxp + 1, 1)))
        return ctd_rad_nomem(r, -1);
    for (size_t p = 0; p < r->np; p++) {
        ct_idx prev = ctd_rad_map_put(&z->parts, r->part[p].id, (ct_idx)z->npk);
        if (prev >= 0)
            return ctd_rad_fail(r, CT_ERR_ARG, r->part[p].line,
                                "keyword /PART/%lld: part id %lld is defined twice (first on "
                                "line %ld)",
                                (long long)r->part[p].id, (long long)r->part[p].id,
                                (long)r->part[prev].line);
        z->pk_id[z->npk++] = r->part[p].id;
    }
    for (size_t e = 0; e < r->ns + r->nb; e++) {
        int64_t id = e < r->ns ? r->spart[e] : r->bpart[e - r->ns];
        ct_idx k = ctd_rad_map_get(&z->parts, id);
        if (k < 0) {
            k = (ct_idx)z->npk;
            ctd_rad_map_put(&z->parts, id, k);
            z->pk_id[z->npk++] = id;
        }
        if (e < r->ns) {
            z->spk[e] = k;
        } else {
            z->bpk[e - r->ns] = k;
            z->pk_brick[k] = 1;
        }
    }
    if (!(z->pk_soff = calloc(z->npk + 2, sizeof *z->pk_soff)) ||
        !(z->pk_boff = calloc(z->npk + 2, sizeof *z->pk_boff)) ||
        !(z->pk_seg = malloc((r->ns + 1) * sizeof *z->pk_seg)) ||
        !(z->pk_brk = malloc((r->nb + 1) * sizeof *z->pk_brk)))
        return ctd_rad_nomem(r, -1);
    for (size_t s = 0; s < r->ns; s++)
        z->pk_soff[z->spk[s] + 2]++;
    for (size_t b = 0; b < r->nb; b++)
        z->pk_boff[z->bpk[b] + 2]++;
    for (size_t k = 2; k < z->npk + 2; k++) {
        z->pk_soff[k] += z->pk_soff[k - 1];
        z->pk_boff[k] += z->pk_boff[k - 1];
    }
    for (size_t s = 0; s < r->ns; s++)
        z->pk_seg[z->pk_soff[z->spk[s] + 1]++] = (ct_idx)s;
    for (size_t b = 0; b < r->nb; b++)
        z->pk_brk[z->pk_boff[z->bpk[b] + 1]++] = (ct_idx)b;
    return CT_OK;
}

int ctd_rad_res_elems(ctd_rad_reader *r, ctd_rad_res *z)
{
    if (r->ns > (size_t)INT32_MAX / 4 || r->nb > (size_t)INT32_MAX / 8)
        return ctd_rad_fail(r, CT_ERR_TOOBIG, -1, "too many elements for 32-bit indices");
    if (ctd_rad_seg_room(z, r->ns) || ctd_rad_map_init(&z->shells, r->ns) ||
        !(z->spk = malloc((r->ns + 1) * sizeof *z->spk)) ||
        !(z->bnode = malloc((8 * r->nb + 1) * sizeof *z->bnode)) ||
        !(z->bpk = malloc((r->nb + 1) * sizeof *z->bpk)))
        return ctd_rad_nomem(r, -1);
    /* The triangle and brick ids are only checked for repeats. */
    ctd_rad_map tri, bricks;
    memset(&tri, 0, sizeof tri);
    memset(&bricks, 0, sizeof bricks);
    int rc;
    if (ctd_rad_map_init(&tri, r->ns) || ctd_rad_map_init(&bricks, r->nb))
        rc = ctd_rad_nomem(r, -1);
    else if ((rc = res_shells(r, z, &tri)) == CT_OK && (rc = res_bricks(r, z, &bricks)) == CT_OK)
        rc = res_parts(r, z);
    ctd_rad_map_free(&tri);
    ctd_rad_map_free(&bricks);
    return rc;
}
