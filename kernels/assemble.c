/*
 * assemble.c -- contact force assembly: pair maps, the workspace, the
 * sequential reference, the one entry point over the variants, and the
 * fixed-order sum used for energies. The variants live in
 * assemble_colour.c and assemble_variants.c; docs/RACES.md explains them.
 */
#include <stdlib.h>

#include "assemble_body.h"

ct_asm_map ct_asm_map_nodeseg(ct_idx npair, const ct_idx *node, const ct_idx *s1,
                              const ct_idx *s2, const ct_idx *s3, const ct_idx *s4)
{
    ct_asm_map m;
    memset(&m, 0, sizeof m);
    m.npair = npair;
    m.nslot = 5;
    m.slot[0] = node;
    m.slot[1] = s1;
    m.slot[2] = s2;
    m.slot[3] = s3;
    m.slot[4] = s4;
    m.sign[0] = 1;
    for (int s = 1; s < 5; s++)
        m.sign[s] = -1;
    return m;
}

ct_asm_map ct_asm_map_edge(ct_idx npair, const ct_idx *a1, const ct_idx *a2,
                           const ct_idx *b1, const ct_idx *b2)
{
    ct_asm_map m;
    memset(&m, 0, sizeof m);
    m.npair = npair;
    m.nslot = 4;
    m.slot[0] = a1;
    m.slot[1] = a2;
    m.slot[2] = b1;
    m.slot[3] = b2;
    m.sign[0] = m.sign[1] = 1;
    m.sign[2] = m.sign[3] = -1;
    return m;
}

int ct_asm_seg_slots(ct_idx npair, const ct_idx *restrict seg, ct_idx nseg,
                     const ct_idx *restrict n1, const ct_idx *restrict n2,
                     const ct_idx *restrict n3, const ct_idx *restrict n4,
                     ct_idx *restrict s1, ct_idx *restrict s2, ct_idx *restrict s3,
                     ct_idx *restrict s4)
{
    if (npair < 0 || nseg < 0)
        return CT_ERR_ARG;
    if (npair == 0)
        return CT_OK;
    if (!seg || !n1 || !n2 || !n3 || !n4 || !s1 || !s2 || !s3 || !s4)
        return CT_ERR_ARG;
    int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad)
    for (ct_idx k = 0; k < npair; k++) {
        ct_idx g = seg[k];
        if (g < 0 || g >= nseg) {
            bad = 1;
            s1[k] = s2[k] = s3[k] = s4[k] = 0;
            continue;
        }
        s1[k] = n1[g];
        s2[k] = n2[g];
        s3[k] = n3[g];
        s4[k] = n4[g];
    }
    return bad ? CT_ERR_RANGE : CT_OK;
}

static const char *const cti_asm_names[CT_ASM_NVARIANT] = {"colour", "atomic", "threadbuf",
                                                           "gather", "serial"};

const char *ct_assemble_variant_name(ct_assemble_variant v)
{
    return (v >= 0 && v < CT_ASM_NVARIANT) ? cti_asm_names[v] : "unknown";
}

int ct_assemble_variant_from_name(const char *name)
{
    if (!name)
        return -1;
    for (int v = 0; v < CT_ASM_NVARIANT; v++)
        if (strcmp(name, cti_asm_names[v]) == 0)
            return v;
    return -1;
}

int ct_assemble_ws_init(ct_assemble_ws *ws)
{
    if (!ws)
        return CT_ERR_ARG;
    memset(ws, 0, sizeof *ws);
    ws->col_npair = ws->col_nnode = -1;
    ws->g_npair = ws->g_nnode = -1;
    ws->tb_npair = ws->tb_nnode = -1;
    return CT_OK;
}

void ct_assemble_ws_destroy(ct_assemble_ws *ws)
{
    if (!ws)
        return;
    ct_free(ws->colour);
    ct_free(ws->col_off);
    ct_free(ws->bperm);
    ct_free(ws->bstart);
    ct_free(ws->g_node);
    ct_free(ws->g_off);
    ct_free(ws->g_slot);
    ct_free(ws->g_cx);
    ct_free(ws->g_cy);
    ct_free(ws->g_cz);
    ct_free(ws->tb_lo);
    ct_free(ws->tb_hi);
    if (ws->tb_buf)
        for (int t = 0; t < ws->tb_maxthr; t++)
            ct_free(ws->tb_buf[t]);
    free(ws->tb_buf);
    free(ws->tb_cap);
    ct_free(ws->mask);
    ct_free(ws->todo);
    ct_free(ws->next);
    ct_free(ws->full);
    ct_free(ws->cnt);
    memset(ws, 0, sizeof *ws);
    ws->col_npair = ws->col_nnode = -1;
    ws->g_npair = ws->g_nnode = -1;
    ws->tb_npair = ws->tb_nnode = -1;
}

size_t ct_assemble_ws_memory(const ct_assemble_ws *ws)
{
    if (!ws)
        return 0;
    size_t b = (ws->cap_colour + ws->cap_off + ws->cap_bperm + ws->cap_todo + ws->cap_next +
                ws->cap_full + ws->cap_bstart) *
               sizeof(ct_idx);
    b += ws->cap_mask * sizeof(uint64_t) + ws->cap_cnt * sizeof(int64_t);
    b += ws->cap_gnode * sizeof(ct_idx) + (ws->cap_goff + ws->cap_gslot) * sizeof(int64_t);
    b += (ws->cap_gc[0] + ws->cap_gc[1] + ws->cap_gc[2]) * sizeof(ct_real);
    b += 2 * (size_t)ws->tb_maxthr * sizeof(ct_idx);
    for (int t = 0; t < ws->tb_maxthr; t++)
        b += ws->tb_cap[t] * sizeof(ct_real);
    return b;
}

int ct_assemble_serial(const ct_asm_map *map, const ct_real *const w[],
                       const ct_real *restrict fx, const ct_real *restrict fy,
                       const ct_real *restrict fz, ct_idx nnode, ct_real *restrict fxn,
                       ct_real *restrict fyn, ct_real *restrict fzn)
{
    if (!cti_asm_map_ok(map) || !w || nnode < 0)
        return CT_ERR_ARG;
    const int bad = cti_asm_range_checked(0, map->npair, map->nslot,
                                          cti_asm_mode(map->nslot, w), map->slot, w, map->sign,
                                          fx, fy, fz, fxn, fyn, fzn, nnode);
    return bad ? CT_ERR_RANGE : CT_OK;
}

int ct_assemble_prepare(ct_assemble_ws *ws, ct_assemble_variant variant,
                        const ct_asm_map *map, ct_idx nnode)
{
    if (!ws || !cti_asm_map_ok(map) || nnode < 0)
        return CT_ERR_ARG;
    switch (variant) {
    case CT_ASM_COLOUR: return ct_colour_pairs(ws, map, nnode, 0);
    case CT_ASM_GATHER: return ct_gather_prepare(ws, map, nnode);
    case CT_ASM_THREADBUF: ws->tb_npair = -1; return CT_OK; /* redone at the next call */
    case CT_ASM_ATOMIC:
    case CT_ASM_SERIAL: return CT_OK;
    default: return CT_ERR_ARG;
    }
}

int ct_assemble(ct_assemble_ws *ws, ct_assemble_variant variant, const ct_asm_map *map,
                const ct_real *const w[], const ct_real *restrict fx,
                const ct_real *restrict fy, const ct_real *restrict fz, ct_idx nnode,
                ct_real *restrict fxn, ct_real *restrict fyn, ct_real *restrict fzn)
{
    switch (variant) {
    case CT_ASM_COLOUR:
        return ct_assemble_coloured(ws, map, w, fx, fy, fz, nnode, fxn, fyn, fzn);
    case CT_ASM_ATOMIC:
        return ct_assemble_atomic(map, w, fx, fy, fz, nnode, fxn, fyn, fzn);
    case CT_ASM_THREADBUF:
        return ct_assemble_threadbuf(ws, map, w, fx, fy, fz, nnode, fxn, fyn, fzn);
    case CT_ASM_GATHER:
        return ct_assemble_gather(ws, map, w, fx, fy, fz, nnode, fxn, fyn, fzn);
    case CT_ASM_SERIAL:
        return ct_assemble_serial(map, w, fx, fy, fz, nnode, fxn, fyn, fzn);
    default: return CT_ERR_ARG;
    }
}

#define CTI_SUM_MAXBLOCK 256
#define CTI_SUM_MINBLOCK 4096

double ct_sum_fixed(int64_t n, const ct_real *restrict v)
{
    if (n <= 0 || !v)
        return 0.0;
    double part[CTI_SUM_MAXBLOCK];
    int64_t nb = (n + CTI_SUM_MINBLOCK - 1) / CTI_SUM_MINBLOCK;
    if (nb > CTI_SUM_MAXBLOCK)
        nb = CTI_SUM_MAXBLOCK;
    int64_t bl = (n + nb - 1) / nb;
    CTI_PAR_FOR(nb > 1, (schedule(static)),
    for (int64_t b = 0; b < nb; b++) {
        int64_t lo = b * bl, hi = CTI_MIN(n, lo + bl);
        double s = 0.0;
        for (int64_t i = lo; i < hi; i++)
            s += (double)v[i];
        part[b] = s;
    });
    double s = 0.0;
    for (int64_t b = 0; b < nb; b++)
        s += part[b];
    return s;
}
