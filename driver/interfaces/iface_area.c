/*
 * iface_area.c -- the secondary node's area for the contact pressure of the
 * pressure-dependent friction laws (Ifric 1 and 2), with pressure_area
 * CTD_PAREA_SECONDARY.
 *
 * The Radioss definition divides a pair's normal force by the area of the
 * main segment the node touches (the default, CTD_PAREA_MAIN). It is the
 * pressure only while the secondary nodes are about as dense as the main
 * segments: a coarse main surface under a fine secondary one divides each
 * node's share of the load by a segment that carries many nodes. Where
 * TYPE24 runs its two passes, the load goes to the pass of the stiffer
 * side, and on the validation block of docs/VALIDATION.md (case 5d) the
 * pass whose main segment is the block's 20 mm face saw a quarter of the
 * pressure.
 *
 * With CTD_PAREA_SECONDARY a pair's pressure is its normal force over the
 * area its secondary node stands for: the sum, over the model's surface
 * segments the node is a corner of, of the segment's area over its number
 * of corners (3 or 4), counting only the segments that face the contact,
 * whose unit normal a satisfies |a . n| >= 1/2 (within 60 degrees of the
 * pair's normal n, either side: shells have no outside). The side faces of
 * a block meet its bottom corners edge-on, and a corner node would
 * otherwise count them too. A node none of whose segments faces the
 * contact (it touches with an edge or a corner) takes all of them. Both
 * from the current geometry, evaluated for the pairs in contact only.
 * Segments with the same corners as another (a shell glued on a brick's
 * face on the same nodes: the model's surface holds both) count once: a
 * node stands for the area of the surface, not of each part that covers
 * it.
 */
#include "iface_internal.h"

#include "ct_internal.h"

#include <stdlib.h>
#include <string.h>

void ctdi_area_free(ctd_iface *it)
{
    ct_free(it->area_q);
    ct_free(it->area_off);
    ct_free(it->area_seg);
    it->area_q = it->area_off = it->area_seg = NULL;
    it->narea_seg = it->narea_ent = 0;
}

size_t ctdi_area_memory(const ctd_iface *it)
{
    if (!it->area_off)
        return 0;
    return ((size_t)it->nnode + 2 + (size_t)it->narea_ent + 1 + 4 * (size_t)it->narea_seg + 1) *
           sizeof(ct_idx);
}

/* A segment's corners, sorted (a triangle's third once, then -1), and the
 * segment: the key that finds segments repeating another's corners. */
typedef struct area_key {
    ct_idx c[4], s;
} area_key;

static int area_key_cmp(const void *pa, const void *pb)
{
    const area_key *a = pa, *b = pb;
    for (int i = 0; i < 4; i++)
        if (a->c[i] != b->c[i])
            return a->c[i] < b->c[i] ? -1 : 1;
    return (a->s > b->s) - (a->s < b->s);
}

/* rep[s] = 1 for each segment among the ns with a corner marked whose
 * corners (in any order) are those of an earlier segment; 0 otherwise.
 * Corners are in range (checked by the caller). */
static int area_mark_repeats(ct_idx ns, const ct_idx *const q[4], const uint8_t *mark,
                             uint8_t *rep)
{
    ct_idx nk = 0;
    for (ct_idx s = 0; s < ns; s++)
        nk += mark[q[0][s]] | mark[q[1][s]] | mark[q[2][s]] | mark[q[3][s]];
    area_key *k = ct_calloc((size_t)nk + 1, sizeof *k);
    if (!k)
        return CT_ERR_NOMEM;
    ct_idx n = 0;
    for (ct_idx s = 0; s < ns; s++) {
        if (!(mark[q[0][s]] | mark[q[1][s]] | mark[q[2][s]] | mark[q[3][s]]))
            continue;
        const int tri = q[3][s] == q[2][s];
        ct_idx c[4] = {q[0][s], q[1][s], q[2][s], tri ? -1 : q[3][s]};
        const int m = tri ? 3 : 4;
        for (int i = 1; i < m; i++) /* insertion sort of 3 or 4 */
            for (int j = i; j > 0 && c[j - 1] > c[j]; j--) {
                const ct_idx t = c[j];
                c[j] = c[j - 1];
                c[j - 1] = t;
            }
        memcpy(k[n].c, c, sizeof c);
        k[n++].s = s;
    }
    qsort(k, (size_t)n, sizeof *k, area_key_cmp);
    for (ct_idx i = 1; i < n; i++)
        rep[k[i].s] = memcmp(k[i].c, k[i - 1].c, sizeof k[i].c) == 0;
    ct_free(k);
    return CT_OK;
}

int ctdi_area_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag)
{
    const int law = it->fric_law;
    if (it->cfg.pressure_area != CTD_PAREA_SECONDARY || !it->fric_on ||
        (law != CT_FRIC_POLY && law != CT_FRIC_DARMSTAD))
        return CT_OK;
    const ct_idx nn = it->nnode, ns = d->nmseg;
    if (ns < 0 || (ns > 0 && (!d->m1 || !d->m2 || !d->m3 || !d->m4)))
        return ctdi_fail(diag, CT_ERR_ARG, -1,
                         "pressure_area secondary needs the model's surface segments.");
    const ct_idx *const q[4] = {d->m1, d->m2, d->m3, d->m4};
    /* Mark the secondary nodes of the passes, then count, per marked node,
     * the segments it is a corner of (a triangle's n3 == n4 once). */
    ct_idx *off = ct_calloc((size_t)nn + 2, sizeof(ct_idx));
    uint8_t *mark = ct_calloc((size_t)nn + 1, 1);
    if (!off || !mark) {
        ct_free(off);
        ct_free(mark);
        return CT_ERR_NOMEM;
    }
    for (int i = 0; i < it->npass; i++)
        for (ct_idx k = 0; k < it->pass[i].nsec; k++)
            mark[it->pass[i].sec[k]] = 1;
    int rc = CT_OK;
    for (ct_idx s = 0; s < ns && rc == CT_OK; s++)
        for (int c = 0; c < 4; c++)
            if ((uint32_t)q[c][s] >= (uint32_t)nn) {
                rc = ctdi_fail(diag, CT_ERR_RANGE, s, "A model segment's node is out of range.");
                break;
            }
    uint8_t *rep = rc == CT_OK ? ct_calloc((size_t)ns + 1, 1) : NULL;
    if (rc == CT_OK && !rep)
        rc = CT_ERR_NOMEM;
    if (rc == CT_OK)
        rc = area_mark_repeats(ns, q, mark, rep);
    ct_idx nkeep = 0;
    int64_t nent = 0;
    for (ct_idx s = 0; s < ns && rc == CT_OK; s++) {
        int keep = 0;
        for (int c = 0; c < 4 && !rep[s]; c++) {
            const ct_idx v = q[c][s];
            if (c == 3 && v == q[2][s])
                continue;
            if (mark[v]) {
                off[v + 1]++;
                nent++;
                keep = 1;
            }
        }
        nkeep += keep;
    }
    for (ct_idx v = 0; v < nn && rc == CT_OK; v++)
        if (mark[v] && off[v + 1] == 0)
            rc = ctdi_fail(diag, CT_ERR_ARG, v,
                           "pressure_area secondary: a secondary node is a corner of no "
                           "surface segment (a node of a beam, a spring or a node list "
                           "alone), so it has no area.");
    if (rc == CT_OK && (nent > INT32_MAX || nkeep > INT32_MAX / 4))
        rc = CT_ERR_NOMEM;
    ct_idx *seg = NULL, *cq = NULL;
    if (rc == CT_OK) {
        seg = ct_calloc((size_t)nent + 1, sizeof(ct_idx));
        cq = ct_calloc((size_t)4 * (size_t)nkeep + 1, sizeof(ct_idx));
        if (!seg || !cq)
            rc = CT_ERR_NOMEM;
    }
    if (rc != CT_OK) {
        ct_free(off);
        ct_free(mark);
        ct_free(rep);
        ct_free(seg);
        ct_free(cq);
        return rc;
    }
    for (ct_idx v = 0; v < nn; v++)
        off[v + 1] += off[v];
    /* Fill: the kept segments in model order, each node's list in that
     * order too (off[v] walks up to off[v + 1], then is moved back). */
    ct_idx local = 0;
    for (ct_idx s = 0; s < ns; s++) {
        int keep = 0;
        for (int c = 0; c < 4 && !rep[s]; c++) {
            const ct_idx v = q[c][s];
            if ((c == 3 && v == q[2][s]) || !mark[v])
                continue;
            seg[off[v]++] = local;
            keep = 1;
        }
        if (keep) {
            for (int c = 0; c < 4; c++)
                cq[4 * (size_t)local + (size_t)c] = q[c][s];
            local++;
        }
    }
    for (ct_idx v = nn; v > 0; v--)
        off[v] = off[v - 1];
    off[0] = 0;
    ct_free(mark);
    ct_free(rep);
    it->area_off = off;
    it->area_seg = seg;
    it->area_q = cq;
    it->narea_seg = nkeep;
    it->narea_ent = (ct_idx)nent;
    return CT_OK;
}

void ctdi_area_of_pairs(const ctd_iface *it, ct_idx n, const ct_idx *restrict node,
                        const ct_real *restrict pen, const ct_real *restrict nx,
                        const ct_real *restrict ny, const ct_real *restrict nz,
                        const ct_real *restrict x, const ct_real *restrict y,
                        const ct_real *restrict z, ct_real *restrict area)
{
    const ct_idx *restrict off = it->area_off, *restrict seg = it->area_seg,
                           *restrict q = it->area_q;
    CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++) {
        if (!(pen[k] > 0)) {
            area[k] = 0;
            continue;
        }
        const ct_idx v = node[k];
        double facing = 0, all = 0;
        for (ct_idx e = off[v]; e < off[v + 1]; e++) {
            const ct_idx *c = q + 4 * (size_t)seg[e];
            const ct_idx i1 = c[0], i2 = c[1], i3 = c[2], i4 = c[3];
            const int tri = i4 == i3;
            /* Twice the vector area: (X3 - X1) x (X4 - X2) for a
             * quadrangle, (X2 - X1) x (X3 - X1) for a triangle. */
            const double ax = tri ? x[i2] - x[i1] : x[i3] - x[i1];
            const double ay = tri ? y[i2] - y[i1] : y[i3] - y[i1];
            const double az = tri ? z[i2] - z[i1] : z[i3] - z[i1];
            const double bx = tri ? x[i3] - x[i1] : x[i4] - x[i2];
            const double by = tri ? y[i3] - y[i1] : y[i4] - y[i2];
            const double bz = tri ? z[i3] - z[i1] : z[i4] - z[i2];
            const double cx = ay * bz - az * by, cy = az * bx - ax * bz,
                         cz = ax * by - ay * bx;
            const double a2 = sqrt(cx * cx + cy * cy + cz * cz);
            const double share = 0.5 * a2 / (tri ? 3.0 : 4.0);
            const double dn = cx * (double)nx[k] + cy * (double)ny[k] + cz * (double)nz[k];
            all += share;
            facing += 2 * fabs(dn) >= a2 ? share : 0;
        }
        area[k] = (ct_real)(facing > 0 ? facing : all);
    });
}
