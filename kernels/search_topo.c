/*
 * search_topo.c -- the topologically limited search, the engine search of
 * Radioss TYPE3/TYPE5 (seed 000 "Detection of Closest Main Node", seed 002
 * "Topologically Limited Search", DESIGN.md section 5).
 *
 * Each secondary node keeps its closest main node M from the last call.
 * A call moves M to the closest of the nodes of the segments attached to M
 * (M stays when none is closer; one hop per call), then reports the
 * segments attached to the new M that pass the shared predicate, in
 * increasing segment order. The cost is O(secondaries x node degree).
 *
 * The first call, a call after ct_search_reset(), and a call whose topology
 * (nnode, the secondaries, the segment corners) differs from the last one's
 * do a full search instead: the exact closest main node of every secondary
 * (Euclidean, ties to the smaller node index, the same answer as trying
 * every main node), found with a uniform grid and expanding rings of cells.
 * The topology is compared in full with a kept copy (search_key.c), not by
 * its pointers: a caller that rewrites its arrays in place would otherwise
 * get hops along a stale node -> segment map.
 *
 * On a scattered numbering the search runs on a spatially renumbered copy
 * (search_renumber.c, as the bucket and bsp searches). Ties are then broken
 * by the original node numbers (ct_search.tie), and when the copy's
 * numbering is made again the history is carried over to it
 * (cti_topo_history_export / import), so the pairs are those of the plain
 * search, bit for bit.
 *
 * Known weakness (the seed's Figure 4, "Undetected Impact"): a node that
 * moves more than about one element per call, or onto a part of the surface
 * not connected to its closest node through one hop, is not paired with the
 * segment it hits; the search may miss pairs, it never reports a pair that
 * fails the predicate.
 */
#include <stdlib.h>

#include "ct_internal.h"

typedef struct topo_state {
    /* What the history belongs to. */
    cti_topo_key key;
    int valid;
    /* Main node -> segments (CSR over global node indices, segments in
     * increasing order), built once per key. */
    ct_idx *off, *adj;
    size_t offcap, adjcap;
    /* Main node -> the other nodes of its segments, each once (CSR): the
     * candidates of a hop. */
    ct_idx *noff, *nbr;
    size_t noffcap, nbrcap;
    /* Scratch of that list's build (one mark per node), kept: the build
     * runs again whenever a renumbered copy is made anew. */
    ct_idx *seen;
    size_t seencap;
    /* Closest main node per secondary position, -1 when none. */
    ct_idx *closest;
    size_t clcap;
} topo_state;

static void topo_free(void *p)
{
    topo_state *st = p;
    if (!st)
        return;
    ct_free(st->off);
    ct_free(st->adj);
    ct_free(st->noff);
    ct_free(st->nbr);
    ct_free(st->seen);
    ct_free(st->closest);
    cti_topo_key_free(&st->key);
    free(st);
}

static size_t topo_memory(const void *p)
{
    const topo_state *st = p;
    return (st->offcap + st->adjcap + st->noffcap + st->nbrcap + st->seencap + st->clcap) *
               sizeof(ct_idx) +
           cti_topo_key_memory(&st->key);
}

/* Whether node a precedes node b in the tie-break order: the original
 * numbers (tie, new -> original, on a renumbered copy) or the numbers. */
static inline int topo_before(const ct_idx *tie, ct_idx a, ct_idx b)
{
    return tie ? tie[a] < tie[b] : a < b;
}

static inline ct_real topo_d2(const ct_real *restrict x, const ct_real *restrict y,
                              const ct_real *restrict z, ct_idx m, ct_real px, ct_real py,
                              ct_real pz)
{
    ct_real dx = x[m] - px, dy = y[m] - py, dz = z[m] - pz;
    return dx * dx + dy * dy + dz * dz;
}

/* Build the node -> segment CSR (a node repeated in a segment, as n3 == n4
 * in a triangle, is counted once). */
static int topo_build_csr(topo_state *st, const ct_search_input *in)
{
    const ct_idx nn = in->nnode, ns = in->nseg;
    void *p = st->off;
    if (cti_grow(&p, &st->offcap, (size_t)nn + 1, sizeof(ct_idx), 0))
        return CT_ERR_NOMEM;
    st->off = p;
    ct_idx *off = st->off;
    memset(off, 0, ((size_t)nn + 1) * sizeof *off);
    for (ct_idx j = 0; j < ns; j++) {
        ct_idx v[4] = {in->n1[j], in->n2[j], in->n3[j], in->n4[j]};
        for (int k = 0; k < 4; k++) {
            if (v[k] < 0 || v[k] >= nn)
                return CT_ERR_RANGE;
            int dup = 0;
            for (int q = 0; q < k; q++)
                dup |= v[q] == v[k];
            if (!dup)
                off[v[k] + 1]++;
        }
    }
    for (ct_idx i = 0; i < nn; i++)
        off[i + 1] += off[i];
    p = st->adj;
    if (cti_grow(&p, &st->adjcap, (size_t)off[nn] + 1, sizeof(ct_idx), 0))
        return CT_ERR_NOMEM;
    st->adj = p;
    /* Fill in segment order with a moving cursor (off[i] shifted down by
     * one node, then restored), so each node's list ascends. */
    for (ct_idx j = 0; j < ns; j++) {
        ct_idx v[4] = {in->n1[j], in->n2[j], in->n3[j], in->n4[j]};
        for (int k = 0; k < 4; k++) {
            int dup = 0;
            for (int q = 0; q < k; q++)
                dup |= v[q] == v[k];
            if (!dup)
                st->adj[off[v[k]]++] = j;
        }
    }
    for (ct_idx i = nn; i > 0; i--)
        off[i] = off[i - 1];
    off[0] = 0;
    /* The other nodes of each node's segments, each once, in the order
     * first met: counted, then written (seen[v] == i + 1, then -(i + 1):
     * v is already in node i's list; a hub node costs its degree, not its
     * square). */
    p = st->noff;
    if (cti_grow(&p, &st->noffcap, (size_t)nn + 1, sizeof(ct_idx), 0))
        return CT_ERR_NOMEM;
    st->noff = p;
    p = st->seen;
    if (cti_grow(&p, &st->seencap, (size_t)nn + 1, sizeof(ct_idx), 0))
        return CT_ERR_NOMEM;
    st->seen = p;
    ct_idx *restrict seen = st->seen;
    memset(seen, 0, ((size_t)nn + 1) * sizeof *seen);
    ct_idx *restrict noff = st->noff, cnt = 0;
    for (int pass = 0; pass < 2; pass++) {
        ct_idx *restrict nbr = st->nbr;
        cnt = 0;
        for (ct_idx i = 0; i < nn; i++) {
            const ct_idx mark = pass ? -(i + 1) : i + 1;
            noff[i] = cnt;
            seen[i] = mark;
            for (ct_idx q = off[i]; q < off[i + 1]; q++) {
                const ct_idx j = st->adj[q];
                const ct_idx v[4] = {in->n1[j], in->n2[j], in->n3[j], in->n4[j]};
                for (int k = 0; k < 4; k++) {
                    if (seen[v[k]] == mark)
                        continue;
                    seen[v[k]] = mark;
                    if (pass)
                        nbr[cnt] = v[k];
                    cnt++;
                }
            }
        }
        if (!pass) {
            p = st->nbr;
            if (cti_grow(&p, &st->nbrcap, (size_t)cnt + 1, sizeof(ct_idx), 0))
                return CT_ERR_NOMEM;
            st->nbr = p;
        }
    }
    noff[nn] = cnt;
    return CT_OK;
}

/* The exact closest main node of every secondary (full search). Main nodes
 * with finite coordinates are counting-sorted into a uniform grid; each
 * secondary scans rings of cells around its own until no unvisited cell
 * can hold a closer node. Scratch is allocated here: this runs on the
 * first call only. */
/* In self contact a node's own segments are excluded, so the node itself
 * and the nodes it shares a segment with can never be its useful closest
 * main node: they are skipped, and the search looks across the fold. */
static inline int topo_excluded(const ct_search_input *in, const ct_idx *restrict off,
                                const ct_idx *restrict adj, ct_idx node, ct_idx m)
{
    if (!in->self)
        return 0;
    if (m == node)
        return 1;
    for (ct_idx q = off[node]; q < off[node + 1]; q++) {
        ct_idx j = adj[q];
        if (in->n1[j] == m || in->n2[j] == m || in->n3[j] == m || in->n4[j] == m)
            return 1;
    }
    return 0;
}

/* The cell of coordinate v along one axis, clamped to [0, nmax] (a NaN
 * product, 0 * inf on a single cell, to 0). */
static inline int64_t topo_cell1(double v, double lo, double inv, int64_t nmax)
{
    double t = (v - lo) * inv;
    t = t > 0 ? t : 0;
    return t < (double)nmax ? (int64_t)t : nmax;
}

static int topo_full(topo_state *st, const ct_search_input *in, const ct_idx *tie)
{
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx nn = in->nnode;
    const ct_idx *off = st->off;
    ct_idx nm = 0;
    ct_real lo[3] = {CTI_HUGE, CTI_HUGE, CTI_HUGE}, hi[3] = {-CTI_HUGE, -CTI_HUGE, -CTI_HUGE};
    for (ct_idx i = 0; i < nn; i++) {
        if (off[i + 1] == off[i])
            continue;
        ct_real c[3] = {x[i], y[i], z[i]};
        if (!isfinite((double)c[0]) || !isfinite((double)c[1]) || !isfinite((double)c[2]))
            continue;
        nm++;
        for (int k = 0; k < 3; k++) {
            lo[k] = CTI_MIN(lo[k], c[k]);
            hi[k] = CTI_MAX(hi[k], c[k]);
        }
    }
    if (nm == 0) {
#pragma omp parallel for schedule(static)
        for (ct_idx i = 0; i < in->nsec; i++)
            st->closest[i] = -1;
        return CT_OK;
    }
    /* Cubic cells, about one per main node, at most 4 per main node,
     * sized relative to the longest side of the main nodes' box (its
     * products with the other sides overflow for coordinates near 1e300
     * and underflow for a subnormal extent, and a cell count from them
     * overflowed an int64_t). An extent too small for a finite 1 / h (or
     * zero, or overflowing) gets one cell: the rings then try every main
     * node. */
    double L[3], Lmax = 0;
    for (int k = 0; k < 3; k++) {
        L[k] = (double)hi[k] - (double)lo[k];
        Lmax = CTI_MAX(Lmax, L[k]);
    }
    int64_t dim[3] = {1, 1, 1}, ncell = 1;
    double h = 1, inv = 0;
    if (Lmax > 0 && isfinite(Lmax)) {
        double l[3];
        for (int k = 0; k < 3; k++)
            l[k] = L[k] / Lmax;
        const double S = l[0] * l[1] + l[1] * l[2] + l[2] * l[0], V = l[0] * l[1] * l[2];
        /* hr >= 1 / nm, so no side has more than nm + 1 cells. */
        double hr = CTI_MAX(CTI_MAX(cbrt(V / nm), sqrt(S / nm)), 1.0 / nm);
        for (;;) {
            ncell = 1;
            for (int k = 0; k < 3; k++) {
                dim[k] = (int64_t)(l[k] / hr) + 1;
                ncell *= dim[k];
            }
            if (ncell <= 4 * (int64_t)nm + 64)
                break;
            hr *= 1.26;
        }
        h = hr * Lmax;
        inv = 1.0 / h;
        if (!(h > 0) || !isfinite(inv) || !isfinite(inv * Lmax)) {
            dim[0] = dim[1] = dim[2] = 1;
            ncell = 1;
            h = 1;
            inv = 0;
        }
    }
    ct_idx *cnt = calloc((size_t)ncell + 1, sizeof *cnt);
    ct_idx *item = malloc((size_t)nm * sizeof *item);
    if (!cnt || !item) {
        free(cnt);
        free(item);
        return CT_ERR_NOMEM;
    }
#define TOPO_CELL(v, k) topo_cell1((double)(v), (double)lo[k], inv, dim[k] - 1)
    for (int pass = 0; pass < 2; pass++) {
        for (ct_idx i = 0; i < nn; i++) {
            if (off[i + 1] == off[i] || !isfinite((double)x[i]) || !isfinite((double)y[i]) ||
                !isfinite((double)z[i]))
                continue;
            int64_t c = (TOPO_CELL(z[i], 2) * dim[1] + TOPO_CELL(y[i], 1)) * dim[0] +
                        TOPO_CELL(x[i], 0);
            if (pass == 0)
                cnt[c + 1]++;
            else
                item[cnt[c]++] = i;
        }
        if (pass == 0)
            for (int64_t c = 0; c < ncell; c++)
                cnt[c + 1] += cnt[c];
    }
    /* cnt[c] now ends cell c; cell c is item[c ? cnt[c-1] : 0 .. cnt[c]). */
    const int64_t rmax = CTI_MAX(dim[0], CTI_MAX(dim[1], dim[2]));
#pragma omp parallel for schedule(dynamic, 256)
    for (ct_idx i = 0; i < in->nsec; i++) {
        ct_idx node = in->sec[i];
        ct_real px = x[node], py = y[node], pz = z[node];
        ct_idx best = -1;
        ct_real bd = 0;
        if (!isfinite((double)px) || !isfinite((double)py) || !isfinite((double)pz)) {
            st->closest[i] = -1;
            continue;
        }
        int64_t c0[3] = {TOPO_CELL(px, 0), TOPO_CELL(py, 1), TOPO_CELL(pz, 2)};
        /* The squared distance from the node to the main nodes' box: every
         * main node is at least that far away. */
        double E = 0;
        {
            const double pc[3] = {(double)px, (double)py, (double)pz};
            for (int k = 0; k < 3; k++) {
                double e = CTI_MAX(0.0, CTI_MAX((double)lo[k] - pc[k], pc[k] - (double)hi[k]));
                E += e * e;
            }
        }
        for (int64_t r = 0; r <= rmax; r++) {
            int64_t a[3], b[3];
            for (int k = 0; k < 3; k++) {
                a[k] = CTI_MAX(0, c0[k] - r);
                b[k] = CTI_MIN(dim[k] - 1, c0[k] + r);
            }
            for (int64_t cz = a[2]; cz <= b[2]; cz++)
                for (int64_t cy = a[1]; cy <= b[1]; cy++) {
                    /* Only the ring: rows strictly inside it in y and z
                     * contribute their two end cells. */
                    int inner = (cz > c0[2] - r && cz < c0[2] + r && cy > c0[1] - r &&
                                 cy < c0[1] + r);
                    int64_t ends[2] = {c0[0] - r, c0[0] + r};
                    int64_t ncx = inner ? (r > 0 ? 2 : 1) : b[0] - a[0] + 1;
                    for (int64_t u = 0; u < ncx; u++) {
                        int64_t cx = inner ? ends[u] : a[0] + u;
                        if (cx < a[0] || cx > b[0])
                            continue;
                        int64_t c = (cz * dim[1] + cy) * dim[0] + cx;
                        for (ct_idx q = c ? cnt[c - 1] : 0; q < cnt[c]; q++) {
                            ct_idx m = item[q];
                            ct_real d2 = topo_d2(x, y, z, m, px, py, pz);
                            if ((best < 0 || d2 < bd || (d2 == bd && topo_before(tie, m, best))) &&
                                !topo_excluded(in, off, st->adj, node, m)) {
                                best = m;
                                bd = d2;
                            }
                        }
                    }
                }
            /* A node in a cell beyond ring r lies, along some axis, at
             * least about r*h beyond the node's own cell (half a cell of
             * slack covers the rounding of the binning), and along every
             * axis at least the node's distance to the main box: its
             * squared distance is at least E + reach^2 (shrunk by a few
             * roundings of that sum). Without E, a node far from the main
             * surface (a ball dropped from a height onto a plate) scanned
             * every cell within its height: a first search of 10^5 nodes
             * took 40 s. */
            double reach = ((double)r - 0.5) * h;
            if (best >= 0 && reach > 0 &&
                (double)bd < (E + reach * reach) * (1 - 64 * (double)CTI_EPS))
                break;
        }
        st->closest[i] = best;
    }
#undef TOPO_CELL
    free(cnt);
    free(item);
    return CT_OK;
}

/* The workspace's topological state, created on first use. */
static topo_state *topo_get(ct_search *s)
{
    return cti_search_state(s, sizeof(topo_state), topo_free, topo_memory);
}

/* The node -> segment map, the key and room for the history of input in
 * (the history's contents are left to the caller). */
static int topo_rebuild(topo_state *st, const ct_search_input *in)
{
    st->valid = 0;
    int rc = topo_build_csr(st, in);
    if (rc)
        return rc;
    void *p = st->closest;
    if (cti_grow(&p, &st->clcap, (size_t)in->nsec, sizeof(ct_idx), 0))
        return CT_ERR_NOMEM;
    st->closest = p;
    return cti_topo_key_store(&st->key, in);
}

void cti_topo_forget(ct_search *s)
{
    if (s->algo_state && s->algo_free == topo_free)
        ((topo_state *)s->algo_state)->valid = 0;
}

int cti_topo_history_export(ct_search *s, const ct_search_input *in, const ct_idx *kpos,
                            const ct_idx *old_of_new, ct_idx *hist)
{
    const topo_state *st =
        s->algo_state && s->algo_free == topo_free ? s->algo_state : NULL;
    if (!st || !st->valid || !cti_topo_key_same(&st->key, in))
        return 0;
    const ct_idx *restrict cl = st->closest;
#pragma omp parallel for schedule(static)
    for (ct_idx o = 0; o < in->nsec; o++) {
        const ct_idx m = cl[kpos[o]];
        hist[o] = m >= 0 ? old_of_new[m] : -1;
    }
    return 1;
}

int cti_topo_history_import(ct_search *s, const ct_search_input *in, const ct_idx *kpos,
                            const ct_idx *new_of_old, const ct_idx *hist)
{
    topo_state *st = topo_get(s);
    if (!st)
        return CT_ERR_NOMEM;
    int rc = topo_rebuild(st, in);
    if (rc)
        return rc;
    ct_idx *restrict cl = st->closest;
#pragma omp parallel for schedule(static)
    for (ct_idx o = 0; o < in->nsec; o++) {
        const ct_idx m = hist[o];
        cl[kpos[o]] = m >= 0 ? new_of_old[m] : -1;
    }
    st->valid = 1;
    return CT_OK;
}

int cti_search_topo(ct_search *s, const ct_search_input *in, ct_pairs *out)
{
    topo_state *st = topo_get(s);
    if (!st)
        return CT_ERR_NOMEM;
    const ct_idx *tie = s->tie;
    int full = !st->valid || !cti_topo_key_same(&st->key, in);
    int rc;
    if (full) {
        rc = topo_rebuild(st, in);
        if (rc)
            return rc;
        rc = topo_full(st, in, tie);
        if (rc)
            return rc;
        st->valid = 1;
    }
    cti_collect *col = &s->col;
    rc = cti_collect_begin(col, in->nsec);
    if (rc)
        return rc;
    const ct_real *restrict x = in->x, *restrict y = in->y, *restrict z = in->z;
    const ct_idx *restrict off = st->off, *restrict adj = st->adj;
    const ct_idx *restrict noff = st->noff, *restrict nbr = st->nbr;
    const ct_real d = in->gap + in->margin;
    /* Hull filter: a node's candidates go through the batch predicate. */
    const int batch = in->filter != CT_FILTER_BOX;
#pragma omp parallel
    {
        const int t = cti_thread_id();
        size_t len = col->len[t];
        cti_pair_batch pb;
        ct_idx bpos[CTI_PAIR_BATCH], last = -1;
        cti_pair_batch_init(&pb);
#pragma omp for schedule(static)
        for (ct_idx i = 0; i < in->nsec; i++) {
            ct_idx m = st->closest[i];
            if (m < 0)
                continue;
            const ct_idx node = in->sec[i];
            const ct_real px = x[node], py = y[node], pz = z[node];
            if (!full) {
                /* One hop: the closest of the nodes of M's segments (each
                 * once: the closest under (distance, tie order) does not
                 * depend on the order or on repeats, and M itself never
                 * beats itself). */
                ct_idx best = m;
                ct_real bd = topo_d2(x, y, z, m, px, py, pz);
                for (ct_idx q = noff[m]; q < noff[m + 1]; q++) {
                    const ct_idx v = nbr[q];
                    const ct_real d2 = topo_d2(x, y, z, v, px, py, pz);
                    if ((d2 < bd || (d2 == bd && topo_before(tie, v, best))) &&
                        !topo_excluded(in, off, adj, node, v)) {
                        best = v;
                        bd = d2;
                    }
                }
                m = best;
                st->closest[i] = m;
            }
            const ct_idx deg = off[m + 1] - off[m];
            if (len + (size_t)pb.n + (size_t)deg > col->cap[t]) {
                col->len[t] = len;
                if (cti_collect_room(col, t, (size_t)pb.n + (size_t)deg) != CT_OK)
                    continue; /* col->err is set */
            }
            if (batch) {
                for (ct_idx q = off[m]; q < off[m + 1]; q++)
                    if (cti_pair_batch_push(&pb, bpos, in, node, i, adj[q]))
                        cti_pair_batch_collect(&pb, bpos, in, NULL, d, col, t, &len, &last);
                continue;
            }
            ct_idx *restrict buf = col->buf[t];
            size_t start = len;
            for (ct_idx q = off[m]; q < off[m + 1]; q++) {
                ct_idx j = adj[q];
                if (cti_pair_test_f(x, y, z, node, in->n1[j], in->n2[j], in->n3[j], in->n4[j],
                                    d, in->self, in->filter))
                    buf[len++] = j;
            }
            if (len > start) {
                col->owner[i] = t;
                col->start[i] = (int64_t)start;
                col->count[i] = (ct_idx)(len - start);
            }
        }
        if (pb.n > 0)
            cti_pair_batch_collect(&pb, bpos, in, NULL, d, col, t, &len, &last);
        col->len[t] = len;
    }
    if (col->err) {
        st->valid = 0;
        return col->err;
    }
    return cti_collect_finish(col, in->sec, out);
}
