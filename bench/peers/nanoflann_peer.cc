/*
 * nanoflann_peer.cc -- the nanoflann peer (Debian libnanoflann-dev 1.4,
 * header-only): a kd-tree over the secondary nodes, one radius search per
 * main segment.
 *
 * Why this way round: nanoflann indexes points and answers "which indexed
 * points lie within r of a query point" (radiusSearch; with the L2 metrics
 * r and the distances are squared, as its README warns). The nodes are
 * points, so they go into the tree exactly; a segment is a box, which a
 * ball around its centre of radius (half-diagonal + d) contains together
 * with everything within d of it, so one radius search per segment with
 * that segment's own radius finds a superset of its pairs. The other way
 * round (segment centres in the tree, one search per node) would need the
 * largest segment's half-diagonal as every query's radius. The README
 * recommends L2_Simple_Adaptor for 2-D and 3-D points and a leaf size of
 * 10 to 50 (smaller: faster queries, slower build); the bench tunes it.
 *
 * The radius search goes through findNeighbors with a result set of our
 * own that keeps only the indices (no distance pairs, no sorting), and the
 * exact filter is applied to each hit. Queries run on OpenMP threads.
 */
#include <nanoflann.hpp>

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <new>
#include <vector>

#include "peers.h"

namespace {

/* The secondary nodes, copied into one interleaved array (the adaptor
 * nanoflann reads during the build and at the leaves). */
struct Cloud {
    std::vector<ct_real> p;
    size_t kdtree_get_point_count() const { return p.size() / 3; }
    ct_real kdtree_get_pt(size_t i, size_t dim) const { return p[3 * i + dim]; }
    template <class Bbox> bool kdtree_get_bbox(Bbox &) const { return false; }
};

typedef nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<ct_real, Cloud>, Cloud,
                                            3, uint32_t>
    Tree;

/* A radius result set that appends the indices of the points within
 * sqrt(r2) to hits. */
struct Hits {
    ct_real r2;
    std::vector<uint32_t> *hits;
    size_t size() const { return hits->size(); }
    bool full() const { return true; }
    bool addPoint(ct_real dist2, uint32_t index)
    {
        if (dist2 <= r2)
            hits->push_back(index);
        return true;
    }
    ct_real worstDist() const { return r2; }
};

double seconds()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

ctp::Buffers buffers;
std::vector<std::vector<uint32_t>> hit_lists;

} // namespace

extern "C" int ctp_nanoflann_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                                 ctp_times *t)
{
    if (!in || !s || !out || !t || in->nsec < 0 || in->nseg < 0 || s->leaf_size < 1)
        return CT_ERR_ARG;
    t->build_s = t->query_s = 0;
    t->candidates = 0;
    const int nt = s->threads > 0 ? s->threads : omp_get_max_threads();
    const ct_real d = in->gap + in->margin;
    const double pad = ctp_pad((double)d, ctp_coord_scale(in));
    int rc = CT_OK;
    ctp::guarded(out, rc, [&] {
        /* Build: the points, then the index. */
        double t0 = seconds();
        Cloud cloud;
        cloud.p.resize(3 * (size_t)in->nsec);
        for (ct_idx i = 0; i < in->nsec; i++) {
            ct_idx k = in->sec[i];
            cloud.p[3 * (size_t)i] = in->x[k];
            cloud.p[3 * (size_t)i + 1] = in->y[k];
            cloud.p[3 * (size_t)i + 2] = in->z[k];
        }
        Tree tree(3, cloud,
                  nanoflann::KDTreeSingleIndexAdaptorParams(
                      (size_t)s->leaf_size, nanoflann::KDTreeSingleIndexAdaptorFlags::None));
        if (in->nsec > 0)
            tree.buildIndex();
        double t1 = seconds();
        t->build_s = t1 - t0;

        /* Query: one radius search per segment, the exact filter on each
         * hit, per-thread buffers gathered into out. */
        if ((int)hit_lists.size() < nt)
            hit_lists.resize((size_t)nt);
        const nanoflann::SearchParams sp(32, 0.0f, false);
        auto query = [&](int tid, std::vector<ct_idx> &buf) {
            std::vector<uint32_t> &hits = hit_lists[(size_t)tid];
            int64_t cand = 0;
#pragma omp for schedule(dynamic, 1024) nowait
            for (ct_idx j = 0; j < in->nseg; j++) {
                if (in->nsec == 0)
                    continue;
                double lo[3], hi[3];
                ctp_seg_box(in, j, lo, hi);
                ct_real q[3];
                double h2 = 0;
                for (int k = 0; k < 3; k++) {
                    q[k] = (ct_real)(0.5 * (lo[k] + hi[k]));
                    /* Half the extent, measured from the rounded centre. */
                    double e = std::fmax(hi[k] - (double)q[k], (double)q[k] - lo[k]);
                    h2 += e * e;
                }
                double r = std::sqrt(h2) + pad;
                /* Squared radius, rounded up by a relative margin so the
                 * search cannot lose a point on its boundary. */
                Hits res{(ct_real)(r * r * (1.0 + 1e-5)), &hits};
                hits.clear();
                tree.findNeighbors(res, q, sp);
                cand += (int64_t)hits.size();
                for (uint32_t k : hits) {
                    ct_idx node = in->sec[k];
                    ctp::keep_if_accepted(buf, in, node, j, d);
                }
            }
            return cand;
        };
        t->candidates = ctp::parallel_query(buffers, nt, out, rc, query);
        t->query_s = seconds() - t1;
    });
    return rc;
}
