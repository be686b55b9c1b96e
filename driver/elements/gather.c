/*
 * gather.c -- the node->slot map through which element sets sum their
 * private nodal force slots into the nodal arrays in a fixed order (see
 * elements.h). Built once per connectivity; the gather itself allocates
 * nothing.
 */
#include <stdlib.h>

#include "ct_internal.h"
#include "elements.h"

void ctd_gather_destroy(ctd_gather *g)
{
    if (!g)
        return;
    ct_free(g->node);
    ct_free(g->off);
    ct_free(g->slot);
    memset(g, 0, sizeof *g);
}

int ctd_gather_build(ctd_gather *g, ct_idx nelem, int nper, const ct_idx *const conn[],
                     int64_t estride, ct_idx nnode, ct_diag *diag)
{
    if (!g || nelem < 0 || nper < 1 || nnode < 0 || estride < 1 || (nelem > 0 && !conn))
        return CT_ERR_ARG;
    memset(g, 0, sizeof *g);
    int64_t nslot = (int64_t)nper * nelem;
    /* Count each node's slots (serial: this runs once per connectivity). */
    int64_t *cnt = ct_calloc((size_t)nnode + 1, sizeof *cnt);
    if (!cnt)
        return CT_ERR_NOMEM;
    for (int a = 0; a < nper; a++)
        for (ct_idx e = 0; e < nelem; e++) {
            ct_idx v = conn[a][(int64_t)e * estride];
            if (v < 0 || v >= nnode) {
                ct_free(cnt);
                return cti_fail(diag, CT_ERR_RANGE, e,
                                "Element %d refers to node %d, outside [0, %d).", (int)e,
                                (int)v, (int)nnode);
            }
            cnt[v]++;
        }
    ct_idx nt = 0;
    for (ct_idx v = 0; v < nnode; v++)
        nt += cnt[v] > 0;
    g->node = ct_calloc((size_t)nt + 1, sizeof *g->node);
    g->off = ct_calloc((size_t)nt + 1, sizeof *g->off);
    g->slot = ct_calloc((size_t)nslot + 1, sizeof *g->slot);
    if (!g->node || !g->off || !g->slot) {
        ct_free(cnt);
        ctd_gather_destroy(g);
        return CT_ERR_NOMEM;
    }
    /* cnt[v] becomes node v's cursor into slot[]. */
    int64_t pos = 0;
    ct_idx t = 0;
    for (ct_idx v = 0; v < nnode; v++) {
        if (cnt[v] == 0)
            continue;
        g->node[t] = v;
        g->off[t++] = pos;
        int64_t c = cnt[v];
        cnt[v] = pos;
        pos += c;
    }
    g->off[nt] = pos;
    /* Slots in increasing index order a * nelem + e. */
    for (int a = 0; a < nper; a++)
        for (ct_idx e = 0; e < nelem; e++) {
            ct_idx v = conn[a][(int64_t)e * estride];
            g->slot[cnt[v]++] = (int64_t)a * nelem + e;
        }
    ct_free(cnt);
    g->nelem = nelem;
    g->nnode = nnode;
    g->nper = nper;
    g->ntouched = nt;
    return CT_OK;
}

void ctd_gather_add(const ctd_gather *g, const ct_real *CT_RESTRICT sx,
                    const ct_real *CT_RESTRICT sy, const ct_real *CT_RESTRICT sz,
                    ct_real *CT_RESTRICT fx, ct_real *CT_RESTRICT fy,
                    ct_real *CT_RESTRICT fz)
{
    const ct_idx nt = g->ntouched;
    const ct_idx *node = g->node;
    const int64_t *off = g->off, *slot = g->slot;
    const int do_y = sy && fy, do_z = sz && fz;
    CTI_PAR_FOR(nt > CTD_PAR_MIN, (schedule(static)),
    for (ct_idx t = 0; t < nt; t++) {
        ct_real ax = 0, ay = 0, az = 0;
        for (int64_t k = off[t]; k < off[t + 1]; k++) {
            int64_t s = slot[k];
            ax += sx[s];
            if (do_y)
                ay += sy[s];
            if (do_z)
                az += sz[s];
        }
        ct_idx v = node[t];
        fx[v] += ax;
        if (do_y)
            fy[v] += ay;
        if (do_z)
            fz[v] += az;
    });
}
