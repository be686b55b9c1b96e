/*
 * type11_search.c -- the broad phase of TYPE11 (type11.c): edge boxes
 * inflated by half the search distance, the direct search or a bucket grid
 * over set B's boxes, and the re-sort criterion.
 *
 * Each edge's box is inflated by half the search distance
 * d = (largest pair gap) + margin, so two boxes overlap when the edges may
 * be within d. The bucket grid sorts set B's boxes into cells (counting
 * sort in edge order); each A edge visits the cells its box covers and
 * keeps a B edge only in the first cell of the two boxes' intersection (no
 * duplicates, no marks), then sorts its list: pairs come out ordered by
 * (a, b), the same for any thread count and equal to the direct search's.
 *
 * The cells of every box are found once per search (cellr), so the first
 * cell of an intersection is a maximum of integers; with self contact an
 * A edge starts each cell's list at its first edge after itself (a search
 * in the sorted list); and the candidates are found in one query pass
 * into a scratch of the visited entries' size (bucket_one_pass), not
 * counted in one and written in another. On the folding sheet at
 * --refine 8 (15 112 edges) the search took 40 % less time than with the
 * cells computed per test, every entry tested and two passes.
 */
#include "type11_internal.h"

#include "ct_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static inline int boxes_overlap(const ct_real *a, const ct_real *b)
{
    return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] &&
           b[2] <= a[5];
}

/* 1 when edges a and b may pair (self: b > a and no shared node). */
static inline int admissible(const ctdi_epass *e, ct_idx a, ct_idx b)
{
    if (!e->self)
        return 1;
    if (b <= a)
        return 0;
    return e->e1[a] != e->e1[b] && e->e1[a] != e->e2[b] && e->e2[a] != e->e1[b] &&
           e->e2[a] != e->e2[b];
}

/* The grid: origin, cell size, dimensions. */
typedef struct grid {
    double o[3], h;
    int64_t n[3];
} grid;

static inline int64_t cell_of(const grid *g, int ax, double v)
{
    int64_t c = (int64_t)floor((v - g->o[ax]) / g->h);
    return c < 0 ? 0 : (c >= g->n[ax] ? g->n[ax] - 1 : c);
}

static void insertion_sort(ct_idx *a, ct_idx n)
{
    for (ct_idx i = 1; i < n; i++) {
        ct_idx v = a[i], j = i - 1;
        while (j >= 0 && a[j] > v) {
            a[j + 1] = a[j];
            j--;
        }
        a[j + 1] = v;
    }
}

/* Candidates of A edge a (count only when out is NULL). The bucket grid's
 * cells of each box are in e->cellr (first and last per axis). A pair of
 * boxes is counted in the first cell of their intersection only, which
 * per axis is the larger of the two boxes' first cells (the cell of a
 * coordinate does not decrease with it, so the cell of the larger lower
 * bound is the larger of the cells): integer comparisons, no division. */
static ct_idx query(const ctdi_epass *e, const grid *g, ct_idx a, ct_idx b0, ct_idx *out)
{
    const ct_real *ba = e->box + 6 * (size_t)a;
    ct_idx k = 0;
    if (!e->bucket) {
        ct_idx bend = e->self ? e->na : e->ne;
        for (ct_idx b = b0; b < bend; b++)
            if (admissible(e, a, b) && boxes_overlap(ba, e->box + 6 * (size_t)b)) {
                if (out)
                    out[k] = b;
                k++;
            }
        return k;
    }
    const int32_t *ca = e->cellr + 6 * (size_t)a;
    const int32_t *restrict cr = e->cellr;
    const ct_idx *restrict off = e->cell_off, *restrict ce = e->cell_edge;
    for (int64_t cz = ca[2]; cz <= ca[5]; cz++)
        for (int64_t cy = ca[1]; cy <= ca[4]; cy++)
            for (int64_t cx = ca[0]; cx <= ca[3]; cx++) {
                const int64_t cell = (cz * g->n[1] + cy) * g->n[0] + cx;
                ct_idx s = off[cell];
                const ct_idx s1 = off[cell + 1];
                if (e->self) {
                    /* A cell's list is in edge order: start at its first
                     * edge after a (a search without branches on the
                     * data), where the loop below tested them all. */
                    ct_idx n = s1 - s;
                    while (n > 1) {
                        const ct_idx h = n / 2;
                        s = ce[s + h - 1] <= a ? s + h : s;
                        n -= h;
                    }
                    s += n == 1 && ce[s] <= a;
                }
                for (; s < s1; s++) {
                    const ct_idx b = ce[s];
                    const int32_t *cb = cr + 6 * (size_t)b;
                    /* The first cell of the intersection is this one. */
                    if ((ca[0] > cb[0] ? ca[0] : cb[0]) != cx ||
                        (ca[1] > cb[1] ? ca[1] : cb[1]) != cy ||
                        (ca[2] > cb[2] ? ca[2] : cb[2]) != cz)
                        continue;
                    if (!admissible(e, a, b) || !boxes_overlap(ba, e->box + 6 * (size_t)b))
                        continue;
                    if (out)
                        out[k] = b;
                    k++;
                }
            }
    if (out)
        insertion_sort(out, k);
    return k;
}

static int grow_idx(ct_idx **p, size_t *cap, size_t n)
{
    *p = ctdi_grow_fresh(*p, cap, n, sizeof(ct_idx));
    return *p ? CT_OK : CT_ERR_NOMEM;
}

/* The A edges' candidate counts (cnt[a + 1]) into offsets (cnt[0] = 0), the
 * total into *tot, and room for that many pairs (within the budget). */
static int counts_to_offsets(ctd_iface *it, ctdi_epass *e, int64_t *tot)
{
    ct_idx *cnt = e->cnt;
    cnt[0] = 0;
    int64_t t = 0;
    for (ct_idx a = 0; a < e->na; a++) {
        t += cnt[a + 1];
        if (t > INT32_MAX)
            return CT_ERR_TOOBIG;
        cnt[a + 1] = (ct_idx)t;
    }
    *tot = t;
    int rc = ctdi_pair_budget(it, t, e->na, CTDI_EPAIR_ID_BYTES, e->sgap);
    return rc == CT_OK ? ctdi_epass_grow_ids(e, (size_t)t) : rc;
}

/* The bucket query in one pass: each A edge's candidates into its own
 * stretch of qbuf, as long as the entries of the cells it visits (a
 * bound of its count), then counted, and copied in order into pa, pb; the
 * two-pass way (count, then query again to fill) did the query twice.
 * QUERY_TWO_PASSES, and nothing done, when the bounds add up past
 * QBUF_MAX_PER_EDGE entries an edge (2 KiB; many edges in few cells) or
 * past the interface's memory for pairs: the caller then takes the two
 * passes, which need no such room. The folding sheet's edges visit 111
 * entries each at --refine 4, 260 at 8 and 414 at 12 (its gap does not
 * shrink with the cells). */
enum { QBUF_MAX_PER_EDGE = 512, QUERY_TWO_PASSES = 1 };

static int bucket_one_pass(ctd_iface *it, ctdi_epass *e, const grid *g)
{
    const ct_idx na = e->na;
    const ct_idx bstart = e->self ? 0 : na;
    e->qoff = ctdi_grow_fresh(e->qoff, &e->cap_qoff, (size_t)na + 1, sizeof(int64_t));
    if (!e->qoff)
        return CT_ERR_NOMEM;
    int64_t *restrict qo = e->qoff;
    const ct_idx *restrict off = e->cell_off;
    const int32_t *restrict cr = e->cellr;
#pragma omp parallel for schedule(static) if (na > CTDI_PAR_MIN)
    for (ct_idx a = 0; a < na; a++) {
        const int32_t *ca = cr + 6 * (size_t)a;
        int64_t nv = 0;
        for (int64_t cz = ca[2]; cz <= ca[5]; cz++)
            for (int64_t cy = ca[1]; cy <= ca[4]; cy++)
                for (int64_t cx = ca[0]; cx <= ca[3]; cx++) {
                    const int64_t cell = (cz * g->n[1] + cy) * g->n[0] + cx;
                    nv += off[cell + 1] - off[cell];
                }
        qo[a + 1] = nv;
    }
    qo[0] = 0;
    for (ct_idx a = 0; a < na; a++)
        qo[a + 1] += qo[a];
    if (qo[na] > (int64_t)QBUF_MAX_PER_EDGE * na + 65536 ||
        qo[na] > ctdi_pair_limit(it, sizeof(ct_idx)))
        return QUERY_TWO_PASSES;
    e->qbuf = ctdi_grow_fresh(e->qbuf, &e->cap_qbuf, (size_t)qo[na] + 1, sizeof(ct_idx));
    if (!e->qbuf)
        return CT_ERR_NOMEM;
    ct_idx *cnt = e->cnt, *qb = e->qbuf;
#pragma omp parallel for schedule(dynamic, 64) if (na > CTDI_PAR_MIN)
    for (ct_idx a = 0; a < na; a++)
        cnt[a + 1] = query(e, g, a, bstart, qb + qo[a]);
    int64_t tot;
    int rc = counts_to_offsets(it, e, &tot);
    if (rc != CT_OK)
        return rc;
    ct_idx *pa = e->pa, *pb = e->pb;
#pragma omp parallel for schedule(static) if (na > CTDI_PAR_MIN)
    for (ct_idx a = 0; a < na; a++) {
        const ct_idx k0 = cnt[a], k1 = cnt[a + 1];
        memcpy(pb + k0, qb + qo[a], (size_t)(k1 - k0) * sizeof *pb);
        for (ct_idx k = k0; k < k1; k++)
            pa[k] = a;
    }
    e->n = (ct_idx)tot;
    return CT_OK;
}

static int edge_search(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                       const ct_real *z)
{
    const ct_real half = (e->sgap + it->margin) / 2;
    const ct_idx ne = e->ne, na = e->na;
    ct_real *restrict box = e->box;
#pragma omp parallel for schedule(static) if (ne > CTDI_PAR_MIN)
    for (ct_idx i = 0; i < ne; i++) {
        ct_idx p = e->e1[i], q = e->e2[i];
        box[6 * i + 0] = (x[p] < x[q] ? x[p] : x[q]) - half;
        box[6 * i + 1] = (y[p] < y[q] ? y[p] : y[q]) - half;
        box[6 * i + 2] = (z[p] < z[q] ? z[p] : z[q]) - half;
        box[6 * i + 3] = (x[p] > x[q] ? x[p] : x[q]) + half;
        box[6 * i + 4] = (y[p] > y[q] ? y[p] : y[q]) + half;
        box[6 * i + 5] = (z[p] > z[q] ? z[p] : z[q]) + half;
    }
    const ct_idx b0 = e->self ? 0 : na, b1 = e->self ? na : ne;
    grid g;
    memset(&g, 0, sizeof g);
    int rc;
    if (e->bucket) {
        double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, ext = 0;
        for (ct_idx b = b0; b < b1; b++)
            for (int ax = 0; ax < 3; ax++) {
                /* Selects, as fmin and fmax answer here (lo and hi are never
                 * NaN) without their libm calls. */
                const double l = (double)box[6 * b + ax], h = (double)box[6 * b + 3 + ax];
                lo[ax] = l < lo[ax] ? l : lo[ax];
                hi[ax] = h > hi[ax] ? h : hi[ax];
                ext += (double)box[6 * b + 3 + ax] - (double)box[6 * b + ax];
            }
        int64_t nbox = b1 - b0;
        /* Boxes past the double range (huge coordinates or margins) would
         * make the cell counts below inf or NaN, whose conversion to int64_t
         * is undefined (it gave INT64_MIN, a signed overflow, then a bogus
         * "out of memory"). */
        if (nbox > 0 && !(isfinite(ext) && isfinite(hi[0] - lo[0]) &&
                          isfinite(hi[1] - lo[1]) && isfinite(hi[2] - lo[2])))
            return CT_ERR_NONFINITE;
        g.h = nbox > 0 ? ext / (3.0 * (double)nbox) : 1.0;
        if (!(g.h > 0))
            g.h = 1.0;
        int64_t maxc = 2 * (int64_t)ne + 1024;
        for (;;) {
            int64_t tot = 1;
            for (int ax = 0; ax < 3; ax++) {
                g.o[ax] = lo[ax];
                double span = nbox > 0 ? (hi[ax] - lo[ax]) / g.h : 0;
                /* Clamped before the conversion; a larger span grows h. */
                g.n[ax] = span < (double)maxc ? (int64_t)span + 1 : maxc + 1;
                tot = tot > maxc / g.n[ax] ? maxc + 1 : tot * g.n[ax];
            }
            if (tot <= maxc)
                break;
            g.h *= 1.5;
        }
        int64_t ncell = g.n[0] * g.n[1] * g.n[2];
        if (g.n[0] > INT32_MAX || g.n[1] > INT32_MAX || g.n[2] > INT32_MAX)
            return CT_ERR_TOOBIG;
        if ((rc = grow_idx(&e->cell_off, &e->cap_cell, (size_t)ncell + 1)) != CT_OK)
            return rc;
        e->cellr = ctdi_grow_fresh(e->cellr, &e->cap_cellr, 6 * (size_t)ne, sizeof(int32_t));
        if (!e->cellr)
            return CT_ERR_NOMEM;
        int32_t *restrict cr = e->cellr;
#pragma omp parallel for schedule(static) if (ne > CTDI_PAR_MIN)
        for (ct_idx i = 0; i < ne; i++)
            for (int ax = 0; ax < 3; ax++) {
                cr[6 * (size_t)i + ax] = (int32_t)cell_of(&g, ax, (double)box[6 * i + ax]);
                cr[6 * (size_t)i + 3 + ax] = (int32_t)cell_of(&g, ax, (double)box[6 * i + 3 + ax]);
            }
        memset(e->cell_off, 0, ((size_t)ncell + 1) * sizeof(ct_idx));
        int64_t total = 0;
        for (ct_idx b = b0; b < b1; b++) {
            const int32_t *c = cr + 6 * (size_t)b;
            for (int64_t cz = c[2]; cz <= c[5]; cz++)
                for (int64_t cy = c[1]; cy <= c[4]; cy++)
                    for (int64_t cx = c[0]; cx <= c[3]; cx++) {
                        e->cell_off[(cz * g.n[1] + cy) * g.n[0] + cx + 1]++;
                        total++;
                    }
        }
        if (total > INT32_MAX)
            return CT_ERR_TOOBIG;
        for (int64_t c = 0; c < ncell; c++)
            e->cell_off[c + 1] += e->cell_off[c];
        if ((rc = grow_idx(&e->cell_edge, &e->cap_ce, (size_t)total + 1)) != CT_OK ||
            (rc = grow_idx(&e->tmp_a, &e->cap_tmp, (size_t)ncell + 1)) != CT_OK)
            return rc;
        ct_idx *cur = e->tmp_a;
        memcpy(cur, e->cell_off, (size_t)ncell * sizeof(ct_idx));
        for (ct_idx b = b0; b < b1; b++) {
            const int32_t *c = cr + 6 * (size_t)b;
            for (int64_t cz = c[2]; cz <= c[5]; cz++)
                for (int64_t cy = c[1]; cy <= c[4]; cy++)
                    for (int64_t cx = c[0]; cx <= c[3]; cx++)
                        e->cell_edge[cur[(cz * g.n[1] + cy) * g.n[0] + cx]++] = b;
        }
    }
    ct_idx *cnt = e->cnt;
    const int64_t bstart = e->self ? 0 : na;
    if (e->bucket) {
        rc = bucket_one_pass(it, e, &g);
        if (rc != QUERY_TWO_PASSES)
            return rc;
    }
    /* Count, prefix, fill: canonical order (a, then b). */
#pragma omp parallel for schedule(dynamic, 64) if (na > CTDI_PAR_MIN)
    for (ct_idx a = 0; a < na; a++)
        cnt[a + 1] = query(e, &g, a, (ct_idx)bstart, NULL);
    int64_t tot;
    if ((rc = counts_to_offsets(it, e, &tot)) != CT_OK)
        return rc;
    ct_idx *pa = e->pa, *pb = e->pb;
#pragma omp parallel for schedule(dynamic, 64) if (na > CTDI_PAR_MIN)
    for (ct_idx a = 0; a < na; a++) {
        ct_idx k0 = cnt[a];
        query(e, &g, a, (ct_idx)bstart, pb + k0);
        for (ct_idx k = k0; k < cnt[a + 1]; k++)
            pa[k] = a;
    }
    e->n = (ct_idx)tot;
    return CT_OK;
}

int ctdi_type11_search(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                       const ct_real *z, int *did)
{
    *did = 0;
    if (!e->need_sort &&
        !ct_resort_needed(e->nan, e->an, e->nbn, e->bn, e->x0, e->y0, e->z0, x, y, z,
                          it->margin, NULL))
        return CT_OK;
    int rc = edge_search(it, e, x, y, z);
    if (rc == CT_OK)
        rc = ctdi_type11_filter(it, e, x, y, z);
    if (rc == CT_OK &&
        (rc = ctdi_pair_budget(it, e->n, e->na, CTDI_EPAIR_BYTES, e->sgap)) == CT_OK)
        rc = ctdi_epass_grow(e, (size_t)e->n);
    if (rc == CT_OK && it->cfg.VisS > 0)
        rc = ctdi_type11_carry_damping(e);
    if (rc != CT_OK)
        return rc;
    const ct_idx n = e->n;
    const ct_idx *restrict pa = e->pa, *restrict pb = e->pb, *restrict e1 = e->e1,
                           *restrict e2 = e->e2;
    ct_idx *restrict a1 = e->sl[0], *restrict a2 = e->sl[1], *restrict b1 = e->sl[2],
                     *restrict b2 = e->sl[3];
    ct_real *restrict k0 = e->r[E_K0];
    const ct_real K0 = e->k0;
#pragma omp parallel for schedule(static) if (n > CTDI_PAR_MIN)
    for (ct_idx k = 0; k < n; k++) {
        a1[k] = e1[pa[k]];
        a2[k] = e2[pa[k]];
        b1[k] = e1[pb[k]];
        b2[k] = e2[pb[k]];
        k0[k] = K0;
    }
    ct_asm_map map = ct_asm_map_edge(n, a1, a2, b1, b2);
    rc = ct_assemble_prepare(&e->ws, it->cfg.asm_variant, &map, it->nnode);
    if (rc != CT_OK)
        return rc;
    const ct_idx nn = it->nnode;
    ct_real *restrict X = e->x0, *restrict Y = e->y0, *restrict Z = e->z0;
#pragma omp parallel for simd schedule(static) if (nn > CTDI_PAR_MIN)
    for (ct_idx i = 0; i < nn; i++) {
        X[i] = x[i];
        Y[i] = y[i];
        Z[i] = z[i];
    }
    e->need_sort = 0;
    *did = 1;
    return CT_OK;
}

