/*
 * project.c -- node-segment narrow phase: the entry point, the work split,
 * and each block's gaps and coordinates. The block kernels, the vector
 * loops, live in project_tri.c (node-triangle: closest point, clamped
 * barycentric coordinates), project_quad.c and project_newton.c (the
 * quadrangle methods).
 *
 * Work split: pairs are cut into blocks of CTI_NR_BLOCK; blocks are shared
 * among threads (static schedule). Inside a block, each maximal run of
 * pairs of one kind (triangle or quadrangle) goes to that kind's kernel, a
 * `#pragma omp simd` loop. Every pair's arithmetic is the same whichever
 * lane or thread computes it, so the results do not depend on the thread
 * count.
 */
#include "narrow_internal.h"

const char *ct_quad_method_name(ct_quad_method m)
{
    switch (m) {
    case CT_QUAD_4TRI: return "4tri";
    case CT_QUAD_NEWTON: return "newton";
    case CT_QUAD_CLOSED: return "closed";
    default: return "unknown";
    }
}

int ct_quad_method_from_name(const char *name)
{
    if (!name)
        return -1;
    for (int m = 0; m < CT_QUAD_NMETHOD; m++)
        if (strcmp(name, ct_quad_method_name((ct_quad_method)m)) == 0)
            return m;
    return -1;
}

/* The pair gaps of a block (see ct_narrow.h) into b->g. */
void cti_nr_gather(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b)
{
    const ct_real *restrict gn = a->gap_node, *restrict gs = a->gap_seg;
    ct_real gap = a->gap, cs = a->gap_max_s, cm = a->gap_max_m;
    if (!gn && !gs) { /* always, with ct_narrow_node_slots */
        for (ct_idx j = 0; j < n; j++)
            b->g[j] = gap;
        return;
    }
    const ct_idx *restrict node = a->node + k0, *restrict seg = a->seg + k0;
    for (ct_idx j = 0; j < n; j++) {
        ct_real vs = gn ? gn[node[j]] : 0, vm = gs ? gs[seg[j]] : 0;
        vs = (cs > 0 && vs > cs) ? cs : vs;
        vm = (cm > 0 && vm > cm) ? cm : vm;
        ct_real g = vs + vm;
        /* A NaN gap stays NaN (and the pair is skipped). */
        b->g[j] = g < gap ? gap : g;
    }
}

/* The coordinates of a block's pairs, loaded one by one and stored two at
 * a time; from packed coordinates, a node's (x, y, z, w) in one vector load
 * (the same stores and values). The loops are kept scalar: vectorised,
 * they would be the vector gathers this copy exists to avoid. Each loop
 * stops at the first pair whose segment is not of its kind (a triangle has
 * n3 == n4): it finds the run of one kind as it copies, from the indices
 * it loads anyway, where a separate scan loaded them once more (5 % of the
 * node-triangle kernel's time). */
CTI_NOVEC ct_idx cti_nr_fetch(const cti_nr_args *a, ct_idx k0, ct_idx n, int quad,
                                 cti_nr_blk *b)
{
    const ct_idx *restrict seg = a->seg + k0;
    const ct_idx *restrict n1 = a->n1, *restrict n2 = a->n2;
    const ct_idx *restrict n3 = a->n3, *restrict n4 = a->n4;
    const ct_real *restrict X = a->x, *restrict Y = a->y, *restrict Z = a->z;
    /* The node of pair j: node[j], or with ct_narrow_node_slots node_sel[s]
     * (through the selection, as the corners). */
    const int by_sel = a->node_sel != NULL;
    const ct_idx *restrict node = by_sel ? a->node_sel : a->node + k0;
    const ct_real *restrict W = a->xyzw;
    ct_idx j = 0;
    if (!quad) {
        ct_real *const d[6] = {b->pxy, b->xy1, b->xy2, b->xy3, b->z01, b->z23};
        if (W) {
            CTI_NOVEC_LOOP
            for (; j < n; j++) {
                ct_idx s = seg[j], i3 = n3[s];
                if (i3 != n4[s])
                    break;
                cti_put4_packed(d, j, W, node[by_sel ? s : j], n1[s], n2[s], i3);
            }
            return j;
        }
        CTI_NOVEC_LOOP
        for (; j < n; j++) {
            ct_idx s = seg[j], i3 = n3[s];
            if (i3 != n4[s])
                break;
            cti_put4(d, j, X, Y, Z, node[by_sel ? s : j], n1[s], n2[s], i3);
        }
        return j;
    }
    ct_real *const d[8] = {b->pxy, b->xy1, b->xy2, b->xy3, b->xy4, b->z01, b->z23, b->z4};
    if (W) {
        CTI_NOVEC_LOOP
        for (; j < n; j++) {
            ct_idx s = seg[j], i3 = n3[s], i4 = n4[s];
            if (i3 == i4)
                break;
            cti_put5_packed(d, j, W, node[by_sel ? s : j], n1[s], n2[s], i3, i4);
        }
        return j;
    }
    CTI_NOVEC_LOOP
    for (; j < n; j++) {
        ct_idx s = seg[j], i3 = n3[s], i4 = n4[s];
        if (i3 == i4)
            break;
        cti_put5(d, j, X, Y, Z, node[by_sel ? s : j], n1[s], n2[s], i3, i4);
    }
    return j;
}

typedef void (*cti_nr_kernel)(const cti_nr_args *, ct_idx, ct_idx, cti_nr_blk *);

/* Block bi of the pairs, in runs of one segment kind. */
static void cti_nr_one_block(const cti_nr_args *a, cti_nr_kernel quad, ct_idx npair,
                             ct_idx bi, cti_nr_blk *blk)
{
    const ct_idx *seg = a->seg, *n3 = a->n3, *n4 = a->n4;
    ct_idx k0 = bi * CTI_NR_BLOCK;
    ct_idx k1 = CTI_MIN(npair, k0 + CTI_NR_BLOCK);
    while (k0 < k1) {
        int tri = n3[seg[k0]] == n4[seg[k0]];
        ct_idx m = cti_nr_fetch(a, k0, k1 - k0, !tri, blk);
        cti_nr_gather(a, k0, m, blk);
        (tri ? cti_nr_block_tri : quad)(a, k0, m, blk);
        k0 += m;
    }
}

/* The narrow phase of npair pairs described by a, after the checks every
 * entry point makes. */
static int cti_narrow_run(const cti_nr_args *ap, ct_idx npair, ct_quad_method method,
                          ct_narrow_stats *stats)
{
    const cti_nr_args a = *ap;
    const ct_contact_geo *out = a.out;
    if (npair < 0 || (int)method < 0 || method >= CT_QUAD_NMETHOD || !out)
        return CT_ERR_ARG;
    /* The scalar gap is a parameter (finite, >= 0, as ct_search_run asks):
     * with per-node or per-segment gaps a NaN one would be dropped by the
     * max, and a negative one gave negative penetrations. A NaN cap is not
     * "no cap". */
    if (!(a.gap >= 0) || !(a.gap <= CTI_HUGE) || a.gap_max_s != a.gap_max_s ||
        a.gap_max_m != a.gap_max_m)
        return CT_ERR_ARG;
    /* Packed coordinates are loaded as aligned vectors. */
    if (a.xyzw && (uintptr_t)a.xyzw % (4 * sizeof(ct_real)) != 0)
        return CT_ERR_ARG;
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (npair == 0)
        return CT_OK;
    if (!(a.node || a.node_sel) || !a.seg || !a.n1 || !a.n2 || !a.n3 || !a.n4 ||
        !(a.xyzw || (a.x && a.y && a.z)) || !out->dist || !out->pen || !out->nx || !out->ny || !out->nz ||
        !out->cx || !out->cy || !out->cz || !out->h1 || !out->h2 || !out->h3 || !out->h4 ||
        !out->gap || !out->flag)
        return CT_ERR_ARG;
    cti_nr_kernel quad = method == CT_QUAD_4TRI     ? cti_nr_block_4tri
                         : method == CT_QUAD_NEWTON ? cti_nr_block_newton
                                                    : cti_nr_block_closed;
    ct_idx nblock = (ct_idx)((npair + CTI_NR_BLOCK - 1) / CTI_NR_BLOCK);
    /* A call of up to 128 pairs (two blocks) runs without a thread team:
     * opening one costs more than the work. (The threshold was one block
     * when blocks were 128 pairs; the results do not depend on it.) Nor
     * does a call from inside the caller's own parallel region. */
    const int team = npair > 128 && !cti_in_parallel();
    if (team) {
#pragma omp parallel
        {
            /* One block scratch per thread, on its stack. */
            cti_nr_blk blk;
            blk.newton_more = 0;
#pragma omp for schedule(static)
            for (ct_idx bi = 0; bi < nblock; bi++)
                cti_nr_one_block(&a, quad, npair, bi, &blk);
        }
    } else { /* no team at all (see CTI_PAR_FOR) */
        cti_nr_blk blk;
        blk.newton_more = 0;
        for (ct_idx bi = 0; bi < nblock; bi++)
            cti_nr_one_block(&a, quad, npair, bi, &blk);
    }
    if (stats) {
        int64_t act = 0, fb = 0, dg = 0, nf = 0, bh = 0, os = 0;
        const ct_real *restrict pen = out->pen;
        const uint8_t *restrict fl = out->flag;
        CTI_PAR_FOR(team, (schedule(static) reduction(+ : act, fb, dg, nf, bh, os)),
        for (ct_idx k = 0; k < npair; k++) {
            act += pen[k] > 0;
            fb += (fl[k] & CT_NARROW_FALLBACK) != 0;
            dg += (fl[k] & CT_NARROW_DEGENERATE) != 0;
            nf += (fl[k] & CT_NARROW_NONFINITE) != 0;
            bh += (fl[k] & CT_NARROW_BEHIND) != 0;
            os += (fl[k] & CT_NARROW_OUTSIDE) != 0;
        });
        stats->active = act;
        stats->fallbacks = fb;
        stats->degenerate = dg;
        stats->nonfinite = nf;
        stats->behind = bh;
        stats->outside = os;
    }
    return CT_OK;
}

int ct_narrow_node_segment(ct_idx npair, const ct_idx *restrict node,
                           const ct_idx *restrict seg, const ct_idx *restrict n1,
                           const ct_idx *restrict n2, const ct_idx *restrict n3,
                           const ct_idx *restrict n4, const ct_real *restrict x,
                           const ct_real *restrict y, const ct_real *restrict z,
                           const ct_real *restrict gap_node, const ct_real *restrict gap_seg,
                           ct_real gap, ct_real gap_max_s, ct_real gap_max_m,
                           ct_quad_method method, int two_sided, const ct_contact_geo *out,
                           ct_narrow_stats *stats)
{
    const cti_nr_args a = {node, seg, n1, n2, n3, n4, NULL, x, y, z, NULL, gap_node, gap_seg,
                           gap, gap_max_s, gap_max_m, two_sided, out};
    return cti_narrow_run(&a, npair, method, stats);
}

int ct_narrow_node_slots(ct_idx npair, const ct_idx *restrict sel, const ct_idx *restrict node,
                         const ct_idx *restrict s1, const ct_idx *restrict s2,
                         const ct_idx *restrict s3, const ct_idx *restrict s4,
                         const ct_real *restrict x, const ct_real *restrict y,
                         const ct_real *restrict z, ct_real gap, ct_quad_method method,
                         int two_sided, const ct_contact_geo *out, ct_narrow_stats *stats)
{
    /* The selection stands for the segment numbers, the slots for n1..n4. */
    const cti_nr_args a = {NULL, sel, s1, s2, s3, s4, node, x, y, z, NULL, NULL, NULL,
                           gap, 0, 0, two_sided, out};
    return cti_narrow_run(&a, npair, method, stats);
}

/* ---- Packed coordinates ------------------------------------------------ */

/* Nodes per thread below which the pack runs without a team. */
#define CTI_PACK_PAR 32768

int ct_coords_pack(ct_idx n, const ct_real *restrict x, const ct_real *restrict y,
                   const ct_real *restrict z, ct_real *restrict xyzw)
{
    if (n < 0)
        return CT_ERR_ARG;
    if (n == 0)
        return CT_OK;
    if (!x || !y || !z || !xyzw || (uintptr_t)xyzw % (4 * sizeof(ct_real)) != 0)
        return CT_ERR_ARG;
    CTI_PAR_FOR_SIMD(n > CTI_PACK_PAR, (schedule(static)),
    for (ct_idx i = 0; i < n; i++) {
        xyzw[4 * i] = x[i];
        xyzw[4 * i + 1] = y[i];
        xyzw[4 * i + 2] = z[i];
        xyzw[4 * i + 3] = 0;
    });
    return CT_OK;
}

int ct_narrow_node_segment_packed(ct_idx npair, const ct_idx *restrict node,
                                  const ct_idx *restrict seg, const ct_idx *restrict n1,
                                  const ct_idx *restrict n2, const ct_idx *restrict n3,
                                  const ct_idx *restrict n4, const ct_real *restrict xyzw,
                                  const ct_real *restrict gap_node,
                                  const ct_real *restrict gap_seg, ct_real gap,
                                  ct_real gap_max_s, ct_real gap_max_m, ct_quad_method method,
                                  int two_sided, const ct_contact_geo *out,
                                  ct_narrow_stats *stats)
{
    const cti_nr_args a = {node, seg, n1, n2, n3, n4, NULL, NULL, NULL, NULL, xyzw, gap_node,
                           gap_seg, gap, gap_max_s, gap_max_m, two_sided, out};
    return cti_narrow_run(&a, npair, method, stats);
}

int ct_narrow_node_slots_packed(ct_idx npair, const ct_idx *restrict sel,
                                const ct_idx *restrict node, const ct_idx *restrict s1,
                                const ct_idx *restrict s2, const ct_idx *restrict s3,
                                const ct_idx *restrict s4, const ct_real *restrict xyzw,
                                ct_real gap, ct_quad_method method, int two_sided,
                                const ct_contact_geo *out, ct_narrow_stats *stats)
{
    const cti_nr_args a = {NULL, sel, s1, s2, s3, s4, node, NULL, NULL, NULL, xyzw, NULL, NULL,
                           gap, 0, 0, two_sided, out};
    return cti_narrow_run(&a, npair, method, stats);
}
