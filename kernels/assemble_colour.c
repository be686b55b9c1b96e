/*
 * assemble_colour.c -- the default assembly: greedy colouring of blocks of
 * consecutive pairs, then one parallel loop per colour without atomics.
 *
 * Why blocks: the pair list comes in node order, so the pairs of one block
 * touch neighbouring nodes and share many of them. Coloured one by one,
 * pairs of a colour are scattered over the whole list and every colour
 * sweeps every cache line of the pair and node arrays; coloured by blocks,
 * each block is processed sequentially by one thread (its pairs may share
 * nodes freely), the arrays are streamed once per cycle, and few colours are
 * needed. block == 1 gives the plain pair colouring, whose colour loops are
 * `omp for simd` loops (no two lanes share a node).
 *
 * Determinism: a node receives its contributions in the order (colour,
 * block, pair, slot), fixed by the colouring, which depends on the map only.
 */
#include "assemble_body.h"

/* The pairs of block b, lo..hi-1: blocks of ws->block pairs, or the
 * caller's (ws->block == 0, ct_colour_pair_blocks). */
static inline void cti_block_range(const ct_assemble_ws *ws, ct_idx b, ct_idx npair, ct_idx *lo,
                                   ct_idx *hi)
{
    const ct_idx B = ws->block;
    if (B > 0) {
        *lo = b * B;
        *hi = (npair - *lo > B) ? *lo + B : npair;
    } else {
        *lo = ws->bstart[b];
        *hi = ws->bstart[b + 1];
    }
}

#define CTI_GROW(ws, field, capf, need)                                                 \
    cti_grow((void **)&(ws)->field, &(ws)->capf, (size_t)(need), sizeof *(ws)->field, 0)

/*
 * One pass of the greedy colouring over the blocks todo[0..ntodo-1] (in
 * increasing order): colours base .. base + 64 W - 1, W mask words per node
 * (local[n] is node n's mask row, or n itself when local is NULL). A block
 * takes the smallest colour of the pass that no node of it carries; blocks
 * that find them all taken go to next[] (returned count). Since all colours
 * below `base` were taken for those blocks in earlier passes, and the masks
 * hold exactly the colours of this pass given to earlier blocks, each block
 * gets the colour of the one-by-one greedy. full[l] counts node l's leading
 * full words, which no block containing it can use (a hub node's many
 * colours are skipped in O(1)).
 */
static ct_idx cti_colour_pass(ct_assemble_ws *ws, const ct_asm_map *map, const ct_idx *todo,
                              ct_idx ntodo, ct_idx *next,
                              const int64_t *local, int W, ct_idx base, ct_idx *maxc)
{
    uint64_t *restrict mask = ws->mask;
    ct_idx *restrict full = ws->full;
    const int ns = map->nslot;
    const ct_idx npair = map->npair;
    ct_idx nnext = 0;
#define CTI_ROW(n) (local ? local[n] : (int64_t)(n))
    for (ct_idx i = 0; i < ntodo; i++) {
        ct_idx b = todo[i], lo, hi;
        cti_block_range(ws, b, npair, &lo, &hi);
        int start = 0;
        if (W > 1)
            for (int s = 0; s < ns; s++)
                for (ct_idx k = lo; k < hi; k++) {
                    int f = full[CTI_ROW(map->slot[s][k])];
                    start = f > start ? f : start;
                }
        int word = -1, c = 0;
        for (int q = start; q < W; q++) {
            uint64_t m = 0;
            for (int s = 0; s < ns; s++) {
                const ct_idx *restrict sl = map->slot[s];
                for (ct_idx k = lo; k < hi; k++)
                    m |= mask[CTI_ROW(sl[k]) * W + q];
            }
            if (m != ~(uint64_t)0) {
                word = q;
                c = __builtin_ctzll(~m);
                break;
            }
        }
        if (word < 0) {
            next[nnext++] = b;
            continue;
        }
        uint64_t bit = (uint64_t)1 << c;
        for (int s = 0; s < ns; s++) {
            const ct_idx *restrict sl = map->slot[s];
            for (ct_idx k = lo; k < hi; k++) {
                int64_t row = CTI_ROW(sl[k]);
                mask[row * W + word] |= bit;
                if (W > 1)
                    while (full[row] < W && mask[row * W + full[row]] == ~(uint64_t)0)
                        full[row]++;
            }
        }
        ct_idx col = base + 64 * (ct_idx)word + c;
        ws->colour[b] = col;
        if (col > *maxc)
            *maxc = col;
    }
#undef CTI_ROW
    return nnext;
}

ct_idx ct_asm_default_block(ct_idx npair)
{
    return (ct_idx)CTI_MIN((int64_t)CT_ASM_BLOCK_MAX,
                           CTI_MAX((int64_t)CT_ASM_BLOCK_MIN, (int64_t)npair / 32));
}

/* The colouring of ws->nblock blocks (ws->block and, when it is 0,
 * ws->bstart already set). */
static int cti_colour_blocks(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode)
{
    const ct_idx npair = map->npair, nblock = ws->nblock;
    const int ns = map->nslot;
    if (CTI_GROW(ws, colour, cap_colour, nblock) || CTI_GROW(ws, bperm, cap_bperm, nblock) ||
        CTI_GROW(ws, todo, cap_todo, nblock) || CTI_GROW(ws, next, cap_next, nblock) ||
        CTI_GROW(ws, mask, cap_mask, nnode))
        return CT_ERR_NOMEM;
    memset(ws->mask, 0, (size_t)nnode * sizeof *ws->mask);
    ct_idx *todo = ws->todo, *next = ws->next, ntodo = nblock, maxc = -1;
    for (ct_idx b = 0; b < nblock; b++)
        todo[b] = b;
    /* Pass 0: one 64-bit mask per node (colours 0..63). */
    ct_idx nnext = cti_colour_pass(ws, map, todo, nblock, next, NULL, 1, 0, &maxc);
    /* Later passes, for the blocks that found 64 colours taken: the nodes
     * of those blocks get compact local numbers and W-word masks. */
    for (ct_idx base = 64; nnext > 0;) {
        ct_idx *t = todo;
        todo = next;
        next = t;
        ntodo = nnext;
        int64_t *local = ws->cnt;
        ct_idx nloc = 0;
        if (cti_grow((void **)&ws->cnt, &ws->cap_cnt, (size_t)nnode + 1, sizeof *ws->cnt, 0))
            return CT_ERR_NOMEM;
        local = ws->cnt;
        for (ct_idx n = 0; n < nnode; n++)
            local[n] = -1;
        for (ct_idx i = 0; i < ntodo; i++) {
            ct_idx lo, hi;
            cti_block_range(ws, todo[i], npair, &lo, &hi);
            for (int s = 0; s < ns; s++)
                for (ct_idx k = lo; k < hi; k++)
                    if (local[map->slot[s][k]] < 0)
                        local[map->slot[s][k]] = nloc++;
        }
        /* Words per node: as many as keep the masks within the size of the
         * per-node mask array of pass 0 (or 2^20 words), at most 64. */
        int64_t budget = CTI_MAX((int64_t)nnode, (int64_t)1 << 20);
        int W = 1;
        while (W < 64 && (int64_t)nloc * W * 2 <= budget)
            W *= 2;
        if (CTI_GROW(ws, mask, cap_mask, (size_t)nloc * W) ||
            CTI_GROW(ws, full, cap_full, nloc))
            return CT_ERR_NOMEM;
        memset(ws->mask, 0, (size_t)nloc * W * sizeof *ws->mask);
        memset(ws->full, 0, (size_t)nloc * sizeof *ws->full);
        nnext = cti_colour_pass(ws, map, todo, ntodo, next, local, W, base, &maxc);
        base += 64 * (ct_idx)W;
    }

    /* Group the blocks by colour (counting sort, stable: increasing inside
     * a colour). */
    ct_idx ncol = maxc + 1;
    if (CTI_GROW(ws, col_off, cap_off, (size_t)ncol + 1))
        return CT_ERR_NOMEM;
    ct_idx *off = ws->col_off;
    memset(off, 0, ((size_t)ncol + 1) * sizeof *off);
    for (ct_idx b = 0; b < nblock; b++)
        off[ws->colour[b] + 1]++;
    for (ct_idx c = 0; c < ncol; c++)
        off[c + 1] += off[c];
    /* Scatter with cursors kept in `todo` (free now). */
    ct_idx *cur = ws->todo;
    if ((size_t)ncol > ws->cap_todo) { /* more colours than blocks cannot happen */
        return CT_ERR_ARG;
    }
    memcpy(cur, off, (size_t)ncol * sizeof *cur);
    for (ct_idx b = 0; b < nblock; b++)
        ws->bperm[cur[ws->colour[b]]++] = b;

    ws->ncolour = ncol;
    ws->col_nslot = ns;
    ws->col_npair = npair;
    ws->col_nnode = nnode;
    ws->max_degree = -1;
    return CT_OK;
}

int ct_colour_pairs(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode, ct_idx block)
{
    if (!ws || !cti_asm_map_ok(map) || nnode < 0)
        return CT_ERR_ARG;
    ws->col_npair = ws->col_nnode = -1; /* invalid until finished */
    int rc = cti_asm_nodes_in_range(map, nnode);
    if (rc != CT_OK)
        return rc;
    const ct_idx B = block > 0 ? block : ct_asm_default_block(map->npair);
    ws->block = B;
    ws->nblock = (ct_idx)(((int64_t)map->npair + B - 1) / B);
    return cti_colour_blocks(ws, map, nnode);
}

int ct_colour_pair_blocks(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode,
                          ct_idx nblock, const ct_idx *bstart)
{
    if (!ws || !cti_asm_map_ok(map) || nnode < 0 || nblock < 0 || !bstart)
        return CT_ERR_ARG;
    ws->col_npair = ws->col_nnode = -1; /* invalid until finished */
    const ct_idx npair = map->npair;
    int bad = bstart[0] != 0 || bstart[nblock] != npair || (nblock == 0) != (npair == 0);
    for (ct_idx b = 0; b < nblock && !bad; b++)
        bad = !(bstart[b + 1] > bstart[b]);
    if (bad)
        return CT_ERR_ARG;
    int rc = cti_asm_nodes_in_range(map, nnode);
    if (rc != CT_OK)
        return rc;
    if (CTI_GROW(ws, bstart, cap_bstart, (size_t)nblock + 1))
        return CT_ERR_NOMEM;
    memcpy(ws->bstart, bstart, ((size_t)nblock + 1) * sizeof *bstart);
    ws->block = 0;
    ws->nblock = nblock;
    return cti_colour_blocks(ws, map, nnode);
}

ct_idx ct_pair_node_blocks(ct_idx npair, const ct_idx *node, ct_idx block, ct_idx *bstart)
{
    if (npair < 0 || block < 1 || !bstart || (npair > 0 && !node))
        return CT_ERR_ARG;
    /* The order check reads the whole list (the block cuts only their
     * ends): a reduction, on a team for a long list. */
    int down = 0;
    CTI_PAR_FOR(npair > 65536, (schedule(static) reduction(| : down)),
    for (ct_idx k = 1; k < npair; k++) {
        down |= node[k] < node[k - 1];
    });
    if (down)
        return CT_ERR_ARG;
    ct_idx nb = 0, k = 0;
    while (k < npair) {
        bstart[nb++] = k;
        /* At least `block` pairs, then to the end of the last node's run. */
        k = npair - k > block ? k + block : npair;
        while (k < npair && node[k] == node[k - 1])
            k++;
    }
    bstart[nb] = npair;
    return nb;
}

ct_idx ct_colour_degree(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode)
{
    if (!ws || !cti_asm_map_ok(map) || ws->col_npair != map->npair ||
        ws->col_nnode != nnode || ws->col_nslot != map->nslot)
        return -1;
    /* The map may have changed since the colouring (same sizes): its nodes
     * index the counters below. */
    if (cti_asm_nodes_in_range(map, nnode) != CT_OK)
        return -1;
    /* cnt[n]: distinct blocks touching node n; mask[n]: last block seen + 1. */
    if (cti_grow((void **)&ws->cnt, &ws->cap_cnt, (size_t)nnode, sizeof *ws->cnt, 0) ||
        cti_grow((void **)&ws->mask, &ws->cap_mask, (size_t)nnode, sizeof *ws->mask, 0))
        return -1;
    memset(ws->cnt, 0, (size_t)nnode * sizeof *ws->cnt);
    memset(ws->mask, 0, (size_t)nnode * sizeof *ws->mask);
    const ct_idx npair = map->npair;
    for (ct_idx b = 0; b < ws->nblock; b++) {
        ct_idx lo, hi;
        cti_block_range(ws, b, npair, &lo, &hi);
        for (int s = 0; s < map->nslot; s++)
            for (ct_idx k = lo; k < hi; k++) {
                ct_idx n = map->slot[s][k];
                if (ws->mask[n] != (uint64_t)b + 1) {
                    ws->mask[n] = (uint64_t)b + 1;
                    ws->cnt[n]++;
                }
            }
    }
    memset(ws->mask, 0, (size_t)nnode * sizeof *ws->mask);
    int64_t best = 0;
    for (ct_idx b = 0; b < ws->nblock; b++) {
        ct_idx lo, hi;
        cti_block_range(ws, b, npair, &lo, &hi);
        int64_t d = 0;
        for (int s = 0; s < map->nslot; s++)
            for (ct_idx k = lo; k < hi; k++) {
                ct_idx n = map->slot[s][k];
                if (ws->mask[n] != (uint64_t)b + 1) {
                    ws->mask[n] = (uint64_t)b + 1;
                    d += ws->cnt[n] - 1;
                }
            }
        if (d > best)
            best = d;
    }
    ws->max_degree = best > INT32_MAX ? INT32_MAX : (ct_idx)best;
    return ws->max_degree;
}

/* Block b's pairs onto the nodes, in order: all of them, or the first
 * count[b] when count is given. */
static void colour_block(const ct_assemble_ws *ws, ct_idx b, ct_idx npair, const ct_idx *count,
                         int ns,
                         int mode, const ct_idx *const slot[], const ct_real *const w[],
                         const ct_real *sign, const ct_real *fx, const ct_real *fy,
                         const ct_real *fz, ct_real *fxn, ct_real *fyn, ct_real *fzn)
{
    ct_idx lo, hi;
    cti_block_range(ws, b, npair, &lo, &hi);
    if (count)
        hi = lo + CTI_MAX(0, CTI_MIN(count[b], hi - lo));
    cti_asm_range(lo, hi, ns, mode, slot, w, sign, fx, fy, fz, fxn, fyn, fzn, count != NULL);
}

int ct_assemble_coloured(const ct_assemble_ws *ws, const ct_asm_map *map,
                         const ct_real *const w[], const ct_real *restrict fx,
                         const ct_real *restrict fy, const ct_real *restrict fz,
                         ct_idx nnode, ct_real *restrict fxn, ct_real *restrict fyn,
                         ct_real *restrict fzn)
{
    return ct_assemble_coloured_prefix(ws, map, NULL, w, fx, fy, fz, nnode, fxn, fyn, fzn);
}

int ct_assemble_coloured_prefix(const ct_assemble_ws *ws, const ct_asm_map *map,
                                const ct_idx *count, const ct_real *const w[],
                                const ct_real *restrict fx, const ct_real *restrict fy,
                                const ct_real *restrict fz, ct_idx nnode,
                                ct_real *restrict fxn, ct_real *restrict fyn,
                                ct_real *restrict fzn)
{
    if (!ws || !cti_asm_map_ok(map) || !w || ws->col_npair != map->npair ||
        ws->col_nslot != map->nslot || ws->col_nnode != nnode)
        return CT_ERR_ARG;
    if (map->npair == 0)
        return CT_OK;
    const int ns = map->nslot;
    const ct_idx B = ws->block, npair = map->npair, ncol = ws->ncolour;
    const ct_idx *restrict off = ws->col_off, *restrict bperm = ws->bperm;
    const ct_idx *const *slot = map->slot;
    const ct_real *sign = map->sign;
    const int mode = cti_asm_mode(ns, w);
    if (B == 1 && !count) {
        /* One pair per block: within a colour no two pairs share a node, so
         * the lanes of a SIMD loop never collide. */
#define CTI_COLOUR_SIMD(NS, MODE)                                                        \
    for (ct_idx c = 0; c < ncol; c++) {                                                 \
        CTI_ASM_FOR_SIMD                                                                \
        for (ct_idx j = off[c]; j < off[c + 1]; j++)                                    \
            cti_asm_pair(bperm[j], NS, MODE, slot, w, sign, fx, fy, fz, fxn, fyn, fzn); \
    }
#pragma omp parallel
        {
            if (ns == 5 && mode == 1) {
                CTI_COLOUR_SIMD(5, 1)
            } else if (ns == 4 && mode == 2) {
                CTI_COLOUR_SIMD(4, 2)
            } else {
                CTI_COLOUR_SIMD(ns, 0)
            }
        }
#undef CTI_COLOUR_SIMD
    } else if (npair > 4096) {
#pragma omp parallel
        for (ct_idx c = 0; c < ncol; c++) {
#pragma omp for schedule(static)
            for (ct_idx j = off[c]; j < off[c + 1]; j++)
                colour_block(ws, bperm[j], npair, count, ns, mode, slot, w, sign, fx, fy, fz,
                             fxn, fyn, fzn);
        }
    } else {
        /* A small list on one thread, without a team (see CTI_PAR_FOR):
         * colour by colour, the blocks of a colour in order, so each node
         * receives its additions in the order the threads make them. */
        for (ct_idx c = 0; c < ncol; c++)
            for (ct_idx j = off[c]; j < off[c + 1]; j++)
                colour_block(ws, bperm[j], npair, count, ns, mode, slot, w, sign, fx, fy, fz,
                             fxn, fyn, fzn);
    }
    return CT_OK;
}

/* Pair k's scalar contributions, slot by slot; none for a zero value
 * (ct_assemble_scalar in ct_assemble.h). */
static inline void scalar_pair(ct_idx k, int ns, const ct_idx *const slot[],
                               const ct_real *const w[], const ct_real *sign,
                               const ct_real *restrict f, ct_real *restrict fn)
{
    if (f[k] == 0)
        return;
    for (int s = 0; s < ns; s++) {
        ct_real ww = cti_asm_weight(w, sign, s, k, 0);
        fn[slot[s][k]] += ww * f[k];
    }
}

/* Block b's pairs, in order. */
static void scalar_block(const ct_assemble_ws *ws, ct_idx b, ct_idx npair, int ns,
                         const ct_idx *const slot[],
                         const ct_real *const w[], const ct_real *sign,
                         const ct_real *restrict f, ct_real *restrict fn)
{
    ct_idx lo, hi;
    cti_block_range(ws, b, npair, &lo, &hi);
    for (ct_idx k = lo; k < hi; k++)
        scalar_pair(k, ns, slot, w, sign, f, fn);
}

int ct_assemble_scalar(const ct_assemble_ws *ws, ct_assemble_variant variant,
                       const ct_asm_map *map, const ct_real *const w[],
                       const ct_real *restrict f, ct_idx nnode, ct_real *restrict fn)
{
    if (!cti_asm_map_ok(map) || !w || !f || !fn || nnode < 0)
        return CT_ERR_ARG;
    const int ns = map->nslot;
    const ct_idx npair = map->npair;
    const ct_idx *const *slot = map->slot;
    const ct_real *sign = map->sign;
    if (variant != CT_ASM_COLOUR) {
        const int rc = cti_asm_nodes_in_range(map, nnode);
        if (rc != CT_OK)
            return rc;
        for (ct_idx k = 0; k < npair; k++)
            scalar_pair(k, ns, slot, w, sign, f, fn);
        return CT_OK;
    }
    if (!ws || ws->col_npair != npair || ws->col_nslot != ns || ws->col_nnode != nnode)
        return CT_ERR_ARG;
    const ct_idx ncol = ws->ncolour;
    const ct_idx *restrict off = ws->col_off, *restrict bperm = ws->bperm;
    /* Colour by colour, the blocks of a colour in order: on one thread (a
     * small list: no team, see CTI_PAR_FOR) the additions to each node come
     * in the order the threads make them. */
    if (npair > 4096) {
#pragma omp parallel
        for (ct_idx c = 0; c < ncol; c++) {
#pragma omp for schedule(static)
            for (ct_idx j = off[c]; j < off[c + 1]; j++)
                scalar_block(ws, bperm[j], npair, ns, slot, w, sign, f, fn);
        }
    } else {
        for (ct_idx c = 0; c < ncol; c++)
            for (ct_idx j = off[c]; j < off[c + 1]; j++)
                scalar_block(ws, bperm[j], npair, ns, slot, w, sign, f, fn);
    }
    return CT_OK;
}
