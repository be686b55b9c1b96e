/*
 * search_bsp_leaf.c -- the float tree coordinates of the quick-sort search
 * and its leaf scan (search_bsp.c describes the algorithm; the types are in
 * search_bsp_internal.h).
 */
#include <stdlib.h>

#include "search_bsp_internal.h"

/* Inflated, slightly widened segment boxes in tree coordinates. The bounds
 * are computed as the predicate computes them, then shifted by the origin
 * and rounded outward to float; a NaN bound becomes infinite so such a
 * segment reaches every leaf and the predicate decides. */
static void bsp_seg_boxes(const ct_search_input *in, ct_real d, const double o[3],
                          bsp_f *restrict sb)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_real w = 8 * CTI_EPS;
#pragma omp parallel for schedule(static)
    for (ct_idx j = 0; j < in->nseg; j++) {
        const ct_real *cc[3] = {x, y, z};
        ct_idx i1 = in->n1[j], i2 = in->n2[j], i3 = in->n3[j], i4 = in->n4[j];
        for (int k = 0; k < 3; k++) {
            const ct_real *v = cc[k];
            ct_real a = v[i1], b = v[i2], e = v[i3], f = v[i4];
            ct_real lo = CTI_MIN(CTI_MIN(a, b), CTI_MIN(e, f));
            ct_real hi = CTI_MAX(CTI_MAX(a, b), CTI_MAX(e, f));
            ct_real l = lo - d, h = hi + d;
            l -= w * (CTI_FABS(lo) + d);
            h += w * (CTI_FABS(hi) + d);
            sb[6 * (size_t)j + k] = l == l ? bsp_down((double)l - o[k]) : -(bsp_f)INFINITY;
            sb[6 * (size_t)j + 3 + k] = h == h ? bsp_up((double)h - o[k]) : (bsp_f)INFINITY;
        }
    }
}

ct_idx cti_bsp_tree_coords(bsp_ctx *c, bsp_box *root)
{
    const ct_search_input *in = c->in;
    bsp_state *st = c->st;
    const ct_idx nsec = in->nsec, nseg = in->nseg;
    /* Tree coordinates are float, relative to an origin inside the model
     * (a corner of the first segment) so that they keep their precision
     * whatever the offset of the model. */
    c->o[0] = c->o[1] = c->o[2] = 0;
    if (nseg > 0) {
        ct_idx a = in->n1[0];
        double q[3] = {(double)in->x[a], (double)in->y[a], (double)in->z[a]};
        if (isfinite(q[0]) && isfinite(q[1]) && isfinite(q[2]))
            c->o[0] = q[0], c->o[1] = q[1], c->o[2] = q[2];
    }
    bsp_seg_boxes(in, c->d, c->o, st->sb);

    /* The union of the segment boxes (per fixed block, so the result does
     * not depend on the thread count; min and max are exact anyway). */
    bsp_box ub[BSP_BLOCKS], nbx[BSP_BLOCKS];
    const int64_t sbl = ((int64_t)nseg + BSP_BLOCKS - 1) / BSP_BLOCKS;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < BSP_BLOCKS; b++) {
        box_empty(&ub[b]);
        int64_t lo = b * sbl, hi = CTI_MIN((int64_t)nseg, lo + sbl);
        for (int64_t j = lo; j < hi; j++) {
            const bsp_f *q = st->sb + 6 * j;
            box_add(&ub[b], q[0], q[1], q[2]);
            box_add(&ub[b], q[3], q[4], q[5]);
        }
    }
    bsp_box u;
    box_empty(&u);
    for (int b = 0; b < BSP_BLOCKS; b++) {
        box_add(&u, ub[b].lo[0], ub[b].lo[1], ub[b].lo[2]);
        box_add(&u, ub[b].hi[0], ub[b].hi[1], ub[b].hi[2]);
    }

    /* Keep the nodes inside that union (the others cannot pair), in block
     * order: count, prefix, scatter. NaN coordinates fail the test. */
    int64_t *cnt = st->blk;
    const int64_t nbl = ((int64_t)nsec + BSP_BLOCKS - 1) / BSP_BLOCKS;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
#define BSP_INSIDE(p, q, r)                                                                \
    ((p) >= u.lo[0] && (p) <= u.hi[0] && (q) >= u.lo[1] && (q) <= u.hi[1] &&              \
     (r) >= u.lo[2] && (r) <= u.hi[2])
#pragma omp parallel for schedule(static)
    for (int b = 0; b < BSP_BLOCKS; b++) {
        int64_t lo = b * nbl, hi = CTI_MIN((int64_t)nsec, lo + nbl), n = 0;
        for (int64_t i = lo; i < hi; i++) {
            ct_idx k = in->sec[i];
            bsp_f p = (bsp_f)((double)x[k] - c->o[0]), q = (bsp_f)((double)y[k] - c->o[1]);
            bsp_f r = (bsp_f)((double)z[k] - c->o[2]);
            n += BSP_INSIDE(p, q, r);
        }
        cnt[b] = n;
    }
    int64_t run = 0;
    for (int b = 0; b < BSP_BLOCKS; b++) {
        int64_t t = cnt[b];
        cnt[b] = run;
        run += t;
    }
    const ct_idx nkeep = (ct_idx)run;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < BSP_BLOCKS; b++) {
        int64_t lo = b * nbl, hi = CTI_MIN((int64_t)nsec, lo + nbl), o = cnt[b];
        box_empty(&nbx[b]);
        for (int64_t i = lo; i < hi; i++) {
            ct_idx k = in->sec[i];
            bsp_f p = (bsp_f)((double)x[k] - c->o[0]), q = (bsp_f)((double)y[k] - c->o[1]);
            bsp_f r = (bsp_f)((double)z[k] - c->o[2]);
            if (BSP_INSIDE(p, q, r)) {
                st->nx[o] = p;
                st->ny[o] = q;
                st->nz[o] = r;
                st->nid[o] = (ct_idx)i;
                o++;
                box_add(&nbx[b], p, q, r);
            }
        }
    }
#undef BSP_INSIDE
    box_empty(root);
    for (int b = 0; b < BSP_BLOCKS; b++) {
        box_add(root, nbx[b].lo[0], nbx[b].lo[1], nbx[b].lo[2]);
        box_add(root, nbx[b].hi[0], nbx[b].hi[1], nbx[b].hi[2]);
    }
    return nkeep;
}

/* Test every node of [n0, n1) against the sorted segment list. The
 * segment boxes are gathered into arrays so the box test of one node
 * against all segments is a vector loop; the few that pass go to the shared
 * predicate in increasing segment order. A node's candidates go straight
 * into this thread's collector buffer; the shared length is written once
 * per leaf. */
void cti_bsp_leaf(bsp_ctx *c, ct_idx n0, ct_idx n1, const ct_idx *restrict segs, ct_idx ns)
{
    const ct_search_input *in = c->in;
    const bsp_state *st = c->st;
    cti_collect *col = c->col;
    const int t = cti_thread_id();
    bsp_stack *sk = &st->stk[t];
    if ((size_t)ns + 16 > sk->lbcap) {
        size_t cap = (size_t)ns + (size_t)ns / 2 + 64;
        bsp_f *lb = ct_calloc(6 * cap, sizeof *lb);
        unsigned char *hit = ct_calloc(cap + 8, 1);
        if (!lb || !hit) {
            ct_free(lb);
            ct_free(hit);
#pragma omp atomic write
            c->err = CT_ERR_NOMEM;
            return;
        }
        ct_free(sk->lb);
        ct_free(sk->hit);
        sk->lb = lb;
        sk->hit = hit;
        sk->lbcap = cap;
    }
    const size_t w = sk->lbcap;
    bsp_f *restrict l0 = sk->lb, *restrict l1 = l0 + w, *restrict l2 = l1 + w;
    bsp_f *restrict h0 = l2 + w, *restrict h1 = h0 + w, *restrict h2 = h1 + w;
    unsigned char *restrict hit = sk->hit;
    const bsp_f *restrict sb = st->sb;
    for (ct_idx q = 0; q < ns; q++) {
        const bsp_f *b = sb + 6 * (size_t)segs[q];
        l0[q] = b[0];
        l1[q] = b[1];
        l2[q] = b[2];
        h0[q] = b[3];
        h1[q] = b[4];
        h2[q] = b[5];
    }
    /* Pad to a multiple of 16 with empty boxes so the vector loop has no
     * scalar remainder (the capacity is at least ns + 16). */
    const ct_idx ns16 = (ns + 15) & ~(ct_idx)15;
    for (ct_idx q = ns; q < ns16; q++) {
        l0[q] = l1[q] = l2[q] = (bsp_f)INFINITY;
        h0[q] = h1[q] = h2[q] = -(bsp_f)INFINITY;
    }
    for (ct_idx q = ns16; q < ns16 + 8; q++)
        hit[q] = 0;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    size_t len = col->len[t];
    /* Hull filter: the candidates that pass the box test go through the
     * batch predicate; the box filter decides them here, one by one. */
    const int batch = in->filter != CT_FILTER_BOX;
    cti_pair_batch pb;
    ct_idx bpos[CTI_PAIR_BATCH], last = -1;
    cti_pair_batch_init(&pb);
    for (ct_idx k = n0; k < n1; k++) {
        if (len + (size_t)pb.n + (size_t)ns > col->cap[t]) {
            col->len[t] = len;
            if (cti_collect_room(col, t, (size_t)pb.n + (size_t)ns) != CT_OK)
                return;
        }
        ct_idx *restrict buf = col->buf[t];
        const bsp_f px = st->nx[k], py = st->ny[k], pz = st->nz[k];
        const ct_idx pos = st->nid[k], node = in->sec[pos];
        /* Sixteen lanes at a time with a constant trip count: a loop over
         * ns16 left most leaves (a few dozen segments) to gcc's scalar
         * epilogue. */
        for (ct_idx q0 = 0; q0 < ns16; q0 += 16) {
#pragma omp simd
            for (ct_idx q = q0; q < q0 + 16; q++)
                hit[q] = (unsigned char)((px >= l0[q]) & (px <= h0[q]) & (py >= l1[q]) &
                                         (py <= h1[q]) & (pz >= l2[q]) & (pz <= h2[q]));
        }
        size_t start = len;
        for (ct_idx q0 = 0; q0 < ns16; q0 += 8) {
            uint64_t m;
            memcpy(&m, hit + q0, sizeof m);
            while (m) {
                ct_idx q = q0 + (ct_idx)(__builtin_ctzll(m) >> 3);
                m &= m - 1;
                ct_idx j = segs[q];
                if (batch) {
                    if (cti_pair_batch_push(&pb, bpos, in, node, pos, j))
                        cti_pair_batch_collect(&pb, bpos, in, NULL, c->d, col, t, &len, &last);
                    continue;
                }
                if (cti_pair_test_f(x, y, z, node, in->n1[j], in->n2[j], in->n3[j], in->n4[j],
                                    c->d, in->self, in->filter))
                    buf[len++] = j;
            }
        }
        if (!batch && len > start) {
            col->owner[pos] = t;
            col->start[pos] = (int64_t)start;
            col->count[pos] = (ct_idx)(len - start);
        }
    }
    if (pb.n > 0)
        cti_pair_batch_collect(&pb, bpos, in, NULL, c->d, col, t, &len, &last);
    col->len[t] = len;
}
