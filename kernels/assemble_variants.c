/*
 * assemble_variants.c -- the benchmark alternatives to colouring: atomic
 * adds, per-thread force buffers with a reduction, and the two-phase gather
 * through a node->slot CSR map. See docs/RACES.md for what each costs and
 * guarantees.
 */
#include <stdlib.h>

#include "assemble_body.h"

/* ---- Atomics ------------------------------------------------------------ */

int ct_assemble_atomic(const ct_asm_map *map, const ct_real *const w[],
                       const ct_real *restrict fx, const ct_real *restrict fy,
                       const ct_real *restrict fz, ct_idx nnode, ct_real *restrict fxn,
                       ct_real *restrict fyn, ct_real *restrict fzn)
{
    if (!cti_asm_map_ok(map) || !w || nnode < 0)
        return CT_ERR_ARG;
    const int rc = cti_asm_nodes_in_range(map, nnode);
    if (rc != CT_OK)
        return rc;
    const int ns = map->nslot;
    const ct_idx *const *slot = map->slot;
    const ct_real *sign = map->sign;
    const int mode = cti_asm_mode(ns, w);
    /* Not deterministic: which thread adds first to a shared node varies. */
#pragma omp parallel for schedule(static)
    for (ct_idx k = 0; k < map->npair; k++) {
        ct_real f0 = fx[k], f1 = fy[k], f2 = fz[k];
        for (int s = 0; s < ns; s++) {
            ct_idx n = slot[s][k];
            ct_real ww = cti_asm_weight(w, sign, s, k, mode);
            ct_real cx = ww * f0, cy = ww * f1, cz = ww * f2;
#pragma omp atomic update
            fxn[n] += cx;
#pragma omp atomic update
            fyn[n] += cy;
#pragma omp atomic update
            fzn[n] += cz;
        }
    }
    return CT_OK;
}

/* ---- Per-thread buffers -------------------------------------------------- */

/* Thread t of nt owns pairs [k0(t), k0(t+1)). */
static inline ct_idx cti_tb_first(ct_idx npair, int t, int nt)
{
    return (ct_idx)((int64_t)npair * t / nt);
}

/* The node range [lo, hi) each thread's pairs touch, and buffers of
 * 3 * (hi - lo) values per thread. Redone when sizes or threads change. */
static int cti_tb_prepare(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode, int nt)
{
    if (nt > ws->tb_maxthr) {
        ct_real **nb = calloc((size_t)nt, sizeof *nb);
        size_t *nc = calloc((size_t)nt, sizeof *nc);
        ct_idx *lo = ct_calloc((size_t)nt, sizeof *lo), *hi = ct_calloc((size_t)nt, sizeof *hi);
        if (!nb || !nc || !lo || !hi) {
            free(nb);
            free(nc);
            ct_free(lo);
            ct_free(hi);
            return CT_ERR_NOMEM;
        }
        for (int t = 0; t < ws->tb_maxthr; t++) {
            nb[t] = ws->tb_buf[t];
            nc[t] = ws->tb_cap[t];
        }
        free(ws->tb_buf);
        free(ws->tb_cap);
        ct_free(ws->tb_lo);
        ct_free(ws->tb_hi);
        ws->tb_buf = nb;
        ws->tb_cap = nc;
        ws->tb_lo = lo;
        ws->tb_hi = hi;
        ws->tb_maxthr = nt;
    }
    const ct_idx npair = map->npair;
    const int ns = map->nslot;
    int bad = 0;
#pragma omp parallel for schedule(static, 1) num_threads(nt) reduction(| : bad)
    for (int t = 0; t < nt; t++) {
        ct_idx k0 = cti_tb_first(npair, t, nt), k1 = cti_tb_first(npair, t + 1, nt);
        ct_idx lo = nnode, hi = 0;
        for (int s = 0; s < ns; s++)
            for (ct_idx k = k0; k < k1; k++) {
                ct_idx n = map->slot[s][k];
                lo = n < lo ? n : lo;
                hi = n + 1 > hi ? n + 1 : hi;
            }
        if (k1 > k0 && (lo < 0 || hi > nnode))
            bad = 1;
        if (hi < lo)
            lo = hi = 0;
        ws->tb_lo[t] = lo;
        ws->tb_hi[t] = hi;
    }
    if (bad)
        return CT_ERR_RANGE;
    for (int t = 0; t < nt; t++)
        if (cti_grow((void **)&ws->tb_buf[t], &ws->tb_cap[t],
                     3 * (size_t)(ws->tb_hi[t] - ws->tb_lo[t]) + 1, sizeof(ct_real), 0))
            return CT_ERR_NOMEM;
    ws->tb_nthr = nt;
    ws->tb_npair = npair;
    ws->tb_nnode = nnode;
    return CT_OK;
}

int ct_assemble_threadbuf(ct_assemble_ws *ws, const ct_asm_map *map,
                          const ct_real *const w[], const ct_real *restrict fx,
                          const ct_real *restrict fy, const ct_real *restrict fz,
                          ct_idx nnode, ct_real *restrict fxn, ct_real *restrict fyn,
                          ct_real *restrict fzn)
{
    if (!ws || !cti_asm_map_ok(map) || !w || nnode < 0)
        return CT_ERR_ARG;
    const int nt = cti_num_threads();
    if (ws->tb_nthr != nt || ws->tb_npair != map->npair || ws->tb_nnode != nnode) {
        int rc = cti_tb_prepare(ws, map, nnode, nt);
        if (rc != CT_OK)
            return rc;
    }
    const ct_idx npair = map->npair;
    const int ns = map->nslot;
    const ct_idx *const *slot = map->slot;
    const ct_real *sign = map->sign;
    const int mode = cti_asm_mode(ns, w);
    ct_idx glo = nnode, ghi = 0;
    for (int t = 0; t < nt; t++)
        if (ws->tb_hi[t] > ws->tb_lo[t]) {
            glo = CTI_MIN(glo, ws->tb_lo[t]);
            ghi = CTI_MAX(ghi, ws->tb_hi[t]);
        }
    int bad = 0;
#pragma omp parallel num_threads(nt) reduction(| : bad)
    {
        /* Phase 1: each buffer block is accumulated by one thread, in pair
         * order. A team smaller than nt (never with dynamic threads off)
         * still covers every block. */
        for (int t = cti_thread_id(); t < nt; t += cti_asm_team()) {
            ct_idx lo = ws->tb_lo[t], len = ws->tb_hi[t] - lo;
            ct_real *restrict bx = ws->tb_buf[t], *restrict by = bx + len, *restrict bz = by + len;
            memset(bx, 0, 3 * (size_t)len * sizeof *bx);
            ct_idx k0 = cti_tb_first(npair, t, nt), k1 = cti_tb_first(npair, t + 1, nt);
            for (ct_idx k = k0; k < k1; k++) {
                ct_real f0 = fx[k], f1 = fy[k], f2 = fz[k];
                for (int s = 0; s < ns; s++) {
                    ct_idx i = slot[s][k] - lo;
                    if ((uint32_t)i >= (uint32_t)len) { /* stale ranges: refuse */
                        bad = 1;
                        continue;
                    }
                    ct_real ww = cti_asm_weight(w, sign, s, k, mode);
                    ct_real cx = ww * f0, cy = ww * f1, cz = ww * f2;
                    bx[i] += cx;
                    by[i] += cy;
                    bz[i] += cz;
                }
            }
        }
#pragma omp barrier
        /* Phase 2: node-parallel sum of the buffers in thread order. */
#pragma omp for schedule(static)
        for (ct_idx n = glo; n < ghi; n++) {
            ct_real sx = fxn[n], sy = fyn[n], sz = fzn[n];
            for (int t = 0; t < nt; t++) {
                ct_idx lo = ws->tb_lo[t], len = ws->tb_hi[t] - lo, i = n - lo;
                if ((uint32_t)i < (uint32_t)len) {
                    const ct_real *b = ws->tb_buf[t];
                    sx += b[i];
                    sy += b[len + i];
                    sz += b[2 * (size_t)len + i];
                }
            }
            fxn[n] = sx;
            fyn[n] = sy;
            fzn[n] = sz;
        }
    }
    if (bad) {
        ws->tb_npair = -1;
        return CT_ERR_RANGE;
    }
    return CT_OK;
}

/* ---- Two-phase gather ---------------------------------------------------- */

int ct_gather_prepare(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode)
{
    if (!ws || !cti_asm_map_ok(map) || nnode < 0)
        return CT_ERR_ARG;
    ws->g_npair = ws->g_nnode = -1;
    const ct_idx npair = map->npair;
    const int ns = map->nslot;
    const int64_t nsl = (int64_t)npair * ns;
    if (cti_grow((void **)&ws->cnt, &ws->cap_cnt, (size_t)nnode + 1, sizeof *ws->cnt, 0) ||
        cti_grow((void **)&ws->g_slot, &ws->cap_gslot, (size_t)nsl, sizeof *ws->g_slot, 0) ||
        cti_grow((void **)&ws->g_cx, &ws->cap_gc[0], (size_t)nsl, sizeof(ct_real), 0) ||
        cti_grow((void **)&ws->g_cy, &ws->cap_gc[1], (size_t)nsl, sizeof(ct_real), 0) ||
        cti_grow((void **)&ws->g_cz, &ws->cap_gc[2], (size_t)nsl, sizeof(ct_real), 0))
        return CT_ERR_NOMEM;
    int64_t *restrict cnt = ws->cnt;
    memset(cnt, 0, ((size_t)nnode + 1) * sizeof *cnt);
    for (ct_idx k = 0; k < npair; k++)
        for (int s = 0; s < ns; s++) {
            ct_idx n = map->slot[s][k];
            if (n < 0 || n >= nnode)
                return CT_ERR_RANGE;
            cnt[n]++;
        }
    ct_idx nt = 0;
    for (ct_idx n = 0; n < nnode; n++)
        nt += cnt[n] > 0;
    if (cti_grow((void **)&ws->g_node, &ws->cap_gnode, (size_t)nt, sizeof *ws->g_node, 0) ||
        cti_grow((void **)&ws->g_off, &ws->cap_goff, (size_t)nt + 1, sizeof *ws->g_off, 0))
        return CT_ERR_NOMEM;
    /* Touched nodes in increasing order; cnt becomes each node's cursor. */
    int64_t run = 0;
    ct_idx g = 0;
    for (ct_idx n = 0; n < nnode; n++)
        if (cnt[n] > 0) {
            ws->g_node[g] = n;
            ws->g_off[g++] = run;
            int64_t c = cnt[n];
            cnt[n] = run;
            run += c;
        }
    ws->g_off[g] = run;
    /* Slots in increasing index k * nslot + s, i.e. in pair order. */
    for (ct_idx k = 0; k < npair; k++)
        for (int s = 0; s < ns; s++)
            ws->g_slot[cnt[map->slot[s][k]]++] = (int64_t)k * ns + s;
    ws->g_ntouched = nt;
    ws->g_nslot = ns;
    ws->g_npair = npair;
    ws->g_nnode = nnode;
    return CT_OK;
}

int ct_assemble_gather(ct_assemble_ws *ws, const ct_asm_map *map,
                       const ct_real *const w[], const ct_real *restrict fx,
                       const ct_real *restrict fy, const ct_real *restrict fz,
                       ct_idx nnode, ct_real *restrict fxn, ct_real *restrict fyn,
                       ct_real *restrict fzn)
{
    if (!ws || !cti_asm_map_ok(map) || !w || ws->g_npair != map->npair ||
        ws->g_nslot != map->nslot || ws->g_nnode != nnode)
        return CT_ERR_ARG;
    const ct_idx npair = map->npair, ng = ws->g_ntouched;
    const int ns = map->nslot;
    const ct_real *sign = map->sign;
    const int mode = cti_asm_mode(ns, w);
    ct_real *restrict cx = ws->g_cx, *restrict cy = ws->g_cy, *restrict cz = ws->g_cz;
    const ct_idx *restrict gnode = ws->g_node;
    const int64_t *restrict goff = ws->g_off, *restrict gslot = ws->g_slot;
#pragma omp parallel
    {
        /* Phase 1: every pair writes its own slots (no sharing). */
        CTI_ASM_FOR_SIMD
        for (ct_idx k = 0; k < npair; k++) {
            ct_real f0 = fx[k], f1 = fy[k], f2 = fz[k];
            for (int s = 0; s < ns; s++) {
                int64_t i = (int64_t)k * ns + s;
                ct_real ww = cti_asm_weight(w, sign, s, k, mode);
                cx[i] = ww * f0;
                cy[i] = ww * f1;
                cz[i] = ww * f2;
            }
        }
        /* Phase 2: each touched node sums its slots in pair order. */
#pragma omp for schedule(static)
        for (ct_idx g = 0; g < ng; g++) {
            ct_idx n = gnode[g];
            ct_real sx = fxn[n], sy = fyn[n], sz = fzn[n];
            for (int64_t j = goff[g]; j < goff[g + 1]; j++) {
                int64_t i = gslot[j];
                sx += cx[i];
                sy += cy[i];
                sz += cz[i];
            }
            fxn[n] = sx;
            fyn[n] = sy;
            fzn[n] = sz;
        }
    }
    return CT_OK;
}
