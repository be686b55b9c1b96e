/*
 * search_bucket_auto.c -- the bucket grid's cell size chosen per input
 * (ct_search_params.cell_factor == 0, the default).
 *
 * The Radioss sizing (cells per unit length from the number of segments
 * over the faces of the bounding box) suits a surface spread over its box:
 * two plates, a tube. It is too fine where the segments fill a volume (a
 * soup of small plates, a crumpled sheet): a segment's box then covers
 * tens of cells, and the binning writes tens of entries per segment. It is
 * too coarse where element sizes vary (a graded mesh): a node's cell then
 * holds hundreds of segments to test. The best factor measured on the
 * synthetic families ranged from 0.25 to 2 times the Radioss sizing, and
 * the search at the Radioss sizing was up to 2.3x slower than at the best.
 *
 * The chooser prices every candidate grid with what the search will do on
 * it, counted on a sample of the input:
 *   E  the entries the binning writes (cells covered, per segment);
 *   T  the entries the nodes test (the entries of a node's cell);
 *   C  the cells, whose counters every block clears and scans;
 * cost = BK_AUTO_E E + T + BK_AUTO_C nb C, nb the counting blocks (one per
 * thread, each with counters of its own). The weights are fitted to the
 * searches' times on ten families (1 thread, 10^5 and 10^6 nodes, factors
 * 0.1 to 3; docs/DESIGN-CHANGES.md section 5): with them the chosen grid
 * was within 7 % of the best of the ten factors on every family but one
 * (the soup at 10^6 nodes, 14 %, measured before such inputs were
 * renumbered), and entry weights of 1.5 to 4 with cell weights of 4 to 10
 * did no better beyond the noise of the times. The pairs are the same on
 * every grid (search_bucket.c): the choice changes the cost, never the
 * result.
 *
 * Sampling: up to BK_AUTO_SEGS segments and BK_AUTO_NODES secondary nodes,
 * drawn over the numbering (auto_pick) and gathered once into a compact
 * scratch, with a small hash table (the passes over the candidates then
 * stay in cache, and the memory does not grow with the grid). E = (nseg /
 * segments sampled) x the sampled segments' spans. For T, the sampled
 * nodes are counted by cell in the table and every sampled segment sums
 * the counts over its range: the sampled (node, entry) couples, scaled by
 * both sampling ratios; both estimates are unbiased. The candidates go
 * from coarse to fine; once the part of a candidate's cost that only grows
 * with finer grids (entries and cells) exceeds the best cost so far, the
 * finer ones are not priced.
 * Serial and in a fixed order: the choice depends on the input and the
 * number of counting blocks only.
 */
#include <string.h>

#include "ct_internal.h"
#include "search_bucket_internal.h"

const double cti_bucket_auto_factors[BK_AUTO_NF] = {0.1, 0.15, 0.25, 0.35, 0.5,
                                                   0.7, 1.0,  1.4,  2.0,  3.0};

/* The m-th of s samples out of n, stream `seed`: m itself when all are
 * taken, otherwise cti_sample_index's draw (with replacement, which keeps
 * the estimates unbiased). Node and segment samples draw from different
 * streams: one sequence for both aliases on a regular mesh (two plates
 * numbered alike put the k-th sampled node over the k-th sampled segment,
 * which doubled T in a first version). */
static inline ct_idx auto_pick(ct_idx m, ct_idx s, ct_idx n, uint64_t seed)
{
    return s == n ? m : cti_sample_index((uint64_t)m, seed, n);
}

/* Sampled segment box f's cell range on grid g (as bk_ranges computes
 * it); 0 when it misses the grid. */
static int auto_range(const float *restrict f, const bk_grid *g, ct_idx a[3], ct_idx b[3])
{
    for (int k = 0; k < 3; k++) {
        const ct_real l = f[k], h = -(ct_real)f[4 + k];
        if (h < g->lo[k] || l > g->hi[k])
            return 0;
        a[k] = bk_cell1(l, g->lo[k], g->inv[k], g->n[k] - 1);
        b[k] = bk_cell1(h, g->lo[k], g->inv[k], g->n[k] - 1);
    }
    return 1;
}

/* The sampled nodes' cells, counted in an open-addressing table of a power
 * of two of slots at least twice the sampled nodes (so at most half full:
 * one distinct cell per node at most): per slot the cell number plus one
 * (0: empty) and its count. A table the size of the grid would cost 4
 * bytes per cell, held for one choice every few searches, and its sparse
 * lookups would miss the caches. The slots' placement depends on the
 * table's size, the counts do not. */
typedef struct auto_slot {
    uint32_t cell1, count;
} auto_slot;

/* The table's slots for s sampled nodes. */
static size_t auto_slots(ct_idx s)
{
    size_t n = 16;
    while (n < (size_t)2 * (size_t)s)
        n *= 2;
    return n;
}

static inline uint32_t auto_hash(uint32_t cell1, uint32_t mask)
{
    return (uint32_t)(cell1 * UINT32_C(0x9e3779b1)) & mask;
}

static void auto_count(auto_slot *restrict tab, uint32_t mask, uint32_t cell1)
{
    uint32_t h = auto_hash(cell1, mask);
    while (tab[h].cell1 && tab[h].cell1 != cell1)
        h = (h + 1) & mask;
    tab[h].cell1 = cell1;
    tab[h].count++;
}

static uint32_t auto_lookup(const auto_slot *restrict tab, uint32_t mask, uint32_t cell1)
{
    uint32_t h = auto_hash(cell1, mask);
    while (tab[h].cell1) {
        if (tab[h].cell1 == cell1)
            return tab[h].count;
        h = (h + 1) & mask;
    }
    return 0;
}

/* Count the nv sampled nodes (xyz) by their cell of grid g. */
static void auto_nodes(const ct_real *restrict xyz, ct_idx nv, const bk_grid *g,
                       auto_slot *restrict tab, uint32_t mask)
{
    memset(tab, 0, ((size_t)mask + 1) * sizeof *tab);
    const size_t nx = (size_t)g->n[0], ny = (size_t)g->n[1];
    for (ct_idx m = 0; m < nv; m++) {
        const ct_real *p = xyz + (size_t)3 * m;
        const size_t cx = (size_t)bk_cell1(p[0], g->lo[0], g->inv[0], g->n[0] - 1);
        const size_t cy = (size_t)bk_cell1(p[1], g->lo[1], g->inv[1], g->n[1] - 1);
        const size_t cz = (size_t)bk_cell1(p[2], g->lo[2], g->inv[2], g->n[2] - 1);
        auto_count(tab, mask, (uint32_t)((cz * ny + cy) * nx + cx) + 1);
    }
}

/* The samples of an input of nsec nodes and nseg segments. */
static void auto_samples(ct_idx nsec, ct_idx nseg, ct_idx *sn, ct_idx *ss)
{
    *sn = CTI_MIN(nsec > 0 ? nsec : 0, BK_AUTO_NODES);
    *ss = CTI_MIN(nseg > 0 ? nseg : 0, BK_AUTO_SEGS);
}

size_t cti_bucket_auto_scratch(ct_idx nsec, ct_idx nseg)
{
    ct_idx sn, ss;
    auto_samples(nsec, nseg, &sn, &ss);
    return (size_t)3 * (size_t)sn * sizeof(ct_real) + (size_t)8 * (size_t)ss * sizeof(float) +
           auto_slots(sn) * sizeof(auto_slot);
}

double cti_bucket_auto_factor(const ct_search_input *in, const float *fbox,
                              const ct_real lo[3], const ct_real hi[3], int64_t maxc,
                              int64_t limit, int nb, void *scratch,
                              cti_bucket_auto_info *info)
{
    const ct_idx nseg = in->nseg, nsec = in->nsec;
    ct_idx sn, ss;
    auto_samples(nsec, nseg, &sn, &ss);
    const double ks = (double)nseg / (double)ss, kn = (double)nsec / (double)sn;
    /* The samples, gathered once: the nodes the query would look up (a
     * node out of range, refused there, or out of the region tests
     * nothing), and the segments' float boxes. */
    ct_real *restrict xyz = scratch;
    float *restrict sbox = (float *)(xyz + (size_t)3 * (size_t)sn);
    auto_slot *restrict tab = (auto_slot *)(sbox + (size_t)8 * (size_t)ss);
    const uint32_t mask = (uint32_t)(auto_slots(sn) - 1);
    ct_idx nv = 0;
    for (ct_idx m = 0; m < sn; m++) {
        const ct_idx p = in->sec[auto_pick(m, sn, nsec, 1)];
        if ((uint32_t)p >= (uint32_t)in->nnode)
            continue;
        const ct_real X = in->x[p], Y = in->y[p], Z = in->z[p];
        if (!(X >= lo[0] && X <= hi[0] && Y >= lo[1] && Y <= hi[1] && Z >= lo[2] && Z <= hi[2]))
            continue;
        xyz[3 * (size_t)nv] = X;
        xyz[3 * (size_t)nv + 1] = Y;
        xyz[3 * (size_t)nv + 2] = Z;
        nv++;
    }
    for (ct_idx m = 0; m < ss; m++)
        memcpy(sbox + (size_t)8 * m, fbox + (size_t)8 * auto_pick(m, ss, nseg, 2),
               8 * sizeof(float));
    double best = -1, best_f = 1.0;
    ct_idx prev[3] = {0, 0, 0};
    int priced = 0;
    for (int c = 0; c < BK_AUTO_NF; c++) {
        bk_grid g;
        for (int k = 0; k < 3; k++) {
            g.lo[k] = lo[k];
            g.hi[k] = hi[k];
        }
        cti_bucket_size(lo, hi, nseg, cti_bucket_auto_factors[c], maxc, g.n, g.inv);
        if (g.n[0] == prev[0] && g.n[1] == prev[1] && g.n[2] == prev[2])
            continue; /* the same grid as the coarser candidate (the cap) */
        for (int k = 0; k < 3; k++)
            prev[k] = g.n[k];
        g.ncell = (int64_t)g.n[0] * g.n[1] * g.n[2];
        /* Entries: the sampled spans, scaled. */
        double e = 0;
        for (ct_idx m = 0; m < ss; m++) {
            ct_idx a[3], b[3];
            if (auto_range(sbox + (size_t)8 * m, &g, a, b))
                e += (double)(b[0] - a[0] + 1) * (double)(b[1] - a[1] + 1) *
                     (double)(b[2] - a[2] + 1);
        }
        e *= ks;
        if (e > (double)limit)
            break; /* the search would coarsen it; finer ones too */
        const double floor_cost = BK_AUTO_E * e + BK_AUTO_C * nb * (double)g.ncell;
        if (best >= 0 && floor_cost >= best)
            break;
        /* Tests: the sampled nodes in the cells of the sampled segments'
         * ranges, counted from the segments' side (reads only). */
        auto_nodes(xyz, nv, &g, tab, mask);
        const size_t nx = (size_t)g.n[0], ny = (size_t)g.n[1];
        double t = 0;
        for (ct_idx m = 0; m < ss; m++) {
            ct_idx a[3], b[3];
            if (!auto_range(sbox + (size_t)8 * m, &g, a, b))
                continue;
            uint64_t sum = 0;
            for (ct_idx iz = a[2]; iz <= b[2]; iz++)
                for (ct_idx iy = a[1]; iy <= b[1]; iy++) {
                    const size_t row = ((size_t)iz * ny + (size_t)iy) * nx;
                    for (ct_idx ix = a[0]; ix <= b[0]; ix++)
                        sum += auto_lookup(tab, mask, (uint32_t)(row + (size_t)ix) + 1);
                }
            t += (double)sum;
        }
        t *= ks * kn;
        const double cost = floor_cost + t;
        priced++;
        if (best < 0 || cost < best) {
            best = cost;
            best_f = cti_bucket_auto_factors[c];
            if (info) {
                info->entries = e;
                info->tests = t;
                info->cells = (double)g.ncell;
            }
        }
    }
    if (info) {
        info->factor = best_f;
        info->priced = priced;
    }
    return best_f;
}
