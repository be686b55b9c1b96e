/*
 * import_radioss_bricks.c -- the outer surface of bricks (see
 * import_radioss.h): the faces not shared by two selected bricks. The
 * faces' corner keys are sorted (a counting sort on the largest corner,
 * then a small sort in each bucket) into classes of equal keys; a face is
 * outer when its class occurs once among the selected bricks' faces; each
 * is turned to point away from its brick's centroid. The same for the
 * brick parts of a deck.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ct_internal.h"
#include "import_radioss_internal.h"

/* The corners of the local faces 0..5 (0-based). */
static const int8_t hexface[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

/* The corners of a face with repeated corners collapsed; returns how many
 * distinct corners remain (3 or 4), or 0 when it is no face. */
static int face_corners(const ct_idx *c8, int l, ct_idx w[4])
{
    int m = 0;
    for (int i = 0; i < 4; i++) {
        ct_idx v = c8[hexface[l][i]];
        if (m == 0 || w[m - 1] != v)
            w[m++] = v;
    }
    if (m > 1 && w[m - 1] == w[0])
        m--;
    for (int i = 1; i < m; i++)
        for (int j = 0; j < i; j++)
            if (w[i] == w[j])
                return 0;
    if (m < 3)
        return 0;
    if (m == 3)
        w[3] = w[2];
    return m;
}

static int key_less(const ct_idx *a, const ct_idx *b)
{
    for (int i = 0; i < 4; i++)
        if (a[i] != b[i])
            return a[i] < b[i];
    return 0;
}

/* The key of face l of a brick: its corners sorted (a triangle's first
 * entry is -1); k[3] = -1 when it is no face or is not selected. */
static void face_key(const ct_idx *c8, int l, int selected, ct_idx k[4])
{
    ct_idx w[4];
    int m = selected ? face_corners(c8, l, w) : 0;
    if (m == 0) {
        k[3] = -1;
        return;
    }
    k[0] = m == 3 ? -1 : w[3];
    k[1] = w[0];
    k[2] = w[1];
    k[3] = w[2];
    for (int i = 1; i < 4; i++)
        for (int j = i; j > 0 && k[j] < k[j - 1]; j--) {
            ct_idx t = k[j];
            k[j] = k[j - 1];
            k[j - 1] = t;
        }
}

/* Give each of the nslot face slots its class (cls[f]): the faces whose
 * keys are equal share one class id, numbered from 0; a slot without a face
 * gets -1. The keys are bucketed by their largest node (cnt: nnode + 2
 * zeros, order: nslot), each bucket sorted (few faces share a largest
 * node). */
static void mark_classes(ct_idx nnode, ct_idx nslot, const ct_idx *key, ct_idx *cnt,
                         ct_idx *order, ct_idx *cls)
{
    for (ct_idx f = 0; f < nslot; f++) {
        cls[f] = -1;
        if (key[4 * f + 3] >= 0)
            cnt[key[4 * f + 3] + 1]++;
    }
    for (ct_idx i = 0; i < nnode; i++)
        cnt[i + 1] += cnt[i];
    for (ct_idx f = 0; f < nslot; f++)
        if (key[4 * f + 3] >= 0)
            order[cnt[key[4 * f + 3]]++] = f;
    /* cnt[i] is now the end of bucket i. */
    ct_idx lo = 0, ncls = 0;
    for (ct_idx i = 0; i < nnode; i++) {
        ct_idx hi = cnt[i];
        for (ct_idx a = lo + 1; a < hi; a++)
            for (ct_idx j = a; j > lo && key_less(key + 4 * order[j], key + 4 * order[j - 1]);
                 j--) {
                ct_idx t = order[j];
                order[j] = order[j - 1];
                order[j - 1] = t;
            }
        for (ct_idx a = lo; a < hi; a++) {
            if (a > lo && memcmp(key + 4 * order[a], key + 4 * order[a - 1], 4 * sizeof *key))
                ncls++;
            cls[order[a]] = ncls;
        }
        ncls += hi > lo;
        lo = hi;
    }
}

int ctd_brick_face_classes(ct_idx nnode, ct_idx nbrick, const ct_idx *conn,
                           const unsigned char *sel, ct_idx *cls)
{
    ct_idx nslot = 6 * nbrick;
    ct_idx *key = malloc(((size_t)nslot * 4 + 1) * sizeof *key);
    ct_idx *cnt = calloc((size_t)nnode + 2, sizeof *cnt);
    ct_idx *order = malloc(((size_t)nslot + 1) * sizeof *order);
    int rc = key && cnt && order ? CT_OK : CT_ERR_NOMEM;
    if (rc == CT_OK) {
        for (ct_idx b = 0; b < nbrick; b++)
            for (int l = 0; l < 6; l++)
                face_key(conn + 8 * (int64_t)b, l, !sel || sel[b], key + 4 * (6 * b + l));
        mark_classes(nnode, nslot, key, cnt, order, cls);
    }
    free(key);
    free(cnt);
    free(order);
    return rc;
}

/* Turn the m corners w of a face of the brick c8 so that its normal points
 * away from the brick's centroid. */
static void orient_face(const ct_real *x, const ct_real *y, const ct_real *z, const ct_idx *c8,
                        int m, ct_idx w[4])
{
    double c[3] = {0, 0, 0}, fc[3] = {0, 0, 0}, p[4][3];
    for (int i = 0; i < 8; i++) {
        ct_idx v = c8[i];
        c[0] += x[v] / 8;
        c[1] += y[v] / 8;
        c[2] += z[v] / 8;
    }
    for (int i = 0; i < 4; i++) {
        p[i][0] = x[w[i]];
        p[i][1] = y[w[i]];
        p[i][2] = z[w[i]];
        for (int d = 0; d < 3 && i < m; d++)
            fc[d] += p[i][d] / m;
    }
    double u[3], v[3];
    for (int d = 0; d < 3; d++) {
        u[d] = m == 4 ? p[2][d] - p[0][d] : p[1][d] - p[0][d];
        v[d] = m == 4 ? p[3][d] - p[1][d] : p[2][d] - p[0][d];
    }
    double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2],
           nz = u[0] * v[1] - u[1] * v[0];
    if (nx * (fc[0] - c[0]) + ny * (fc[1] - c[1]) + nz * (fc[2] - c[2]) < 0) {
        ct_idx t = w[1];
        w[1] = w[m - 1];
        w[m - 1] = t;
        if (m == 3)
            w[3] = w[2];
    }
}

void ctd_faces_destroy(ctd_faces *f)
{
    if (!f)
        return;
    ct_free(f->node);
    ct_free(f->brick);
    ct_free(f->local);
    memset(f, 0, sizeof *f);
}

/* Whether face slot f is outer in the selection counted with generation gen
 * (see ctd_brick_select_outer). */
static int slot_outer(const ct_idx *cls, const int32_t *stamp, int32_t gen, int64_t f)
{
    return cls[f] >= 0 && stamp[cls[f]] == gen;
}

int ctd_brick_select_outer(const ct_real *x, const ct_real *y, const ct_real *z,
                           const ct_idx *conn, const ct_idx *cls, ct_idx nsel, const ct_idx *brk,
                           int32_t *stamp, int32_t gen, ctd_faces *out)
{
    memset(out, 0, sizeof *out);
    /* A class seen once in this selection holds gen, seen more often -gen. */
    for (ct_idx i = 0; i < nsel; i++)
        for (int l = 0; l < 6; l++) {
            ct_idx c = cls[6 * (int64_t)brk[i] + l];
            if (c >= 0)
                stamp[c] = (stamp[c] == gen || stamp[c] == -gen) ? -gen : gen;
        }
    ct_idx n = 0;
    for (ct_idx i = 0; i < nsel; i++)
        for (int l = 0; l < 6; l++)
            n += slot_outer(cls, stamp, gen, 6 * (int64_t)brk[i] + l);
    out->node = ct_calloc(4 * (size_t)n, sizeof(ct_idx));
    out->brick = ct_calloc((size_t)n, sizeof(ct_idx));
    out->local = ct_calloc((size_t)n, sizeof(int8_t));
    if (!out->node || !out->brick || !out->local) {
        ctd_faces_destroy(out);
        return CT_ERR_NOMEM;
    }
    ct_idx j = 0;
    for (ct_idx i = 0; i < nsel; i++)
        for (int l = 0; l < 6; l++) {
            ct_idx b = brk[i], w[4];
            if (!slot_outer(cls, stamp, gen, 6 * (int64_t)b + l))
                continue;
            const ct_idx *c8 = conn + 8 * (int64_t)b;
            orient_face(x, y, z, c8, face_corners(c8, l, w), w);
            memcpy(out->node + 4 * j, w, sizeof w);
            out->brick[j] = b;
            out->local[j] = (int8_t)l;
            j++;
        }
    out->n = n;
    return CT_OK;
}

int ctd_brick_outer_faces(ct_idx nnode, const ct_real *x, const ct_real *y, const ct_real *z,
                          ct_idx nbrick, const ct_idx *conn, const unsigned char *sel,
                          ctd_faces *out, ct_diag *diag)
{
    if (!out || nnode < 0 || nbrick < 0 || (nbrick > 0 && (!conn || !x || !y || !z)))
        return cti_fail(diag, CT_ERR_ARG, -1,
                        "ctd_brick_outer_faces: a NULL array or a negative count.");
    memset(out, 0, sizeof *out);
    if ((int64_t)nbrick * 6 > INT32_MAX)
        return cti_fail(diag, CT_ERR_TOOBIG, -1,
                        "%ld bricks have too many faces for a 32-bit index.", (long)nbrick);
    for (int64_t k = 0; k < 8 * (int64_t)nbrick; k++)
        if (conn[k] < 0 || conn[k] >= nnode)
            return cti_fail(diag, CT_ERR_RANGE, k / 8,
                            "brick %ld: node %d = %ld is out of range [0, %ld).", (long)(k / 8),
                            (int)(k % 8) + 1, (long)conn[k], (long)nnode);
    ct_idx nslot = 6 * nbrick, n = 0;
    ct_idx *cls = malloc(((size_t)nslot + 1) * sizeof *cls);
    ct_idx *brk = malloc(((size_t)nbrick + 1) * sizeof *brk);
    int32_t *stamp = calloc((size_t)nslot + 1, sizeof *stamp);
    int rc = CT_ERR_NOMEM;
    if (cls && brk && stamp && ctd_brick_face_classes(nnode, nbrick, conn, sel, cls) == CT_OK) {
        for (ct_idx b = 0; b < nbrick; b++)
            if (!sel || sel[b])
                brk[n++] = b;
        rc = ctd_brick_select_outer(x, y, z, conn, cls, n, brk, stamp, 1, out);
    }
    free(cls);
    free(brk);
    free(stamp);
    if (rc == CT_ERR_NOMEM)
        cti_fail(diag, rc, -1, "Out of memory in ctd_brick_outer_faces.");
    return rc;
}

int ctd_deck_brick_surface(const ctd_deck *d, const int64_t *part_ids, int nparts,
                           ctd_faces *out, ct_diag *diag)
{
    if (!d || !out || nparts < 0 || (nparts > 0 && !part_ids))
        return cti_fail(diag, CT_ERR_ARG, -1, "ctd_deck_brick_surface: NULL argument.");
    unsigned char *sel = NULL;
    if (nparts > 0) {
        sel = calloc((size_t)d->nbrick + 1, 1);
        if (!sel)
            return CT_ERR_NOMEM;
        for (int p = 0; p < nparts; p++) {
            int found = 0;
            for (ct_idx b = 0; b < d->nbrick; b++)
                if (d->brick_part[b] == part_ids[p])
                    sel[b] = 1, found = 1;
            if (!found) {
                free(sel);
                return cti_fail(diag, CT_ERR_RANGE, p, "part %lld has no /BRICK elements.",
                                (long long)part_ids[p]);
            }
        }
    }
    int rc = ctd_brick_outer_faces(d->mesh.nodes.n, d->mesh.nodes.x, d->mesh.nodes.y,
                                   d->mesh.nodes.z, d->nbrick, d->brick_node, sel, out, diag);
    free(sel);
    return rc;
}
