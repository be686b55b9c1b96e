/*
 * cgal_peer.cc -- the CGAL peer (Debian libcgal-dev 5.5, header-only):
 * CGAL::box_intersection_d, the segment-tree algorithm of Zomorodian and
 * Edelsbrunner, between the secondary nodes' point boxes and the main
 * segments' boxes inflated by d.
 *
 * Configuration, as the package's manual describes it for this use:
 *  - topology CLOSED: a node is a degenerate box [p, p], which the default
 *    HALF_OPEN topology would treat as empty (and a node exactly at the
 *    inflated boundary must still be reported);
 *  - setting BIPARTITE: nodes against segments, never nodes against nodes;
 *  - our own box type (min_coord, max_coord, id, dimension: the Box_traits_d
 *    requirements) with ids unique over both sequences (nodes 0..nsec-1,
 *    segments nsec..), which the algorithm uses to break ties;
 *  - the knobs: `cutoff` (below it a subproblem is solved by scanning
 *    instead of splitting further; default 10) and the order of the box
 *    axes: the segment tree splits on the last dimension first and scans on
 *    the first, so which coordinate goes where changes the cost (on plates
 *    flat in z, 8x between the best and the worst order). "auto" (the
 *    tuned choice) scans on the longest extent of the nodes' bounding box,
 *    splits first on the second longest and puts the shortest in the
 *    middle; computing it is part of the build time.
 * The random-access version of box_intersection_d reorders the two box
 * sequences in place; they are rebuilt every run (the build time). The
 * algorithm is sequential (CGAL's Parallel_tag needs TBB): one thread.
 */
#include <CGAL/box_intersection_d.h>

#include <chrono>
#include <cstdint>
#include <new>
#include <vector>

#include "peers.h"

namespace {

struct Box {
    typedef double NT;
    typedef std::size_t ID;
    double lo[3], hi[3];
    std::size_t ident;
    static int dimension() { return 3; }
    double min_coord(int k) const { return lo[k]; }
    double max_coord(int k) const { return hi[k]; }
    std::size_t id() const { return ident; }
};

double seconds()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

ctp::Buffers buffers;

} // namespace

extern "C" int ctp_cgal_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                            ctp_times *t)
{
    if (!in || !s || !out || !t || in->nsec < 0 || in->nseg < 0 || s->cutoff < 1 ||
        s->axis_order < -1 || s->axis_order > 5)
        return CT_ERR_ARG;
    t->build_s = t->query_s = 0;
    t->candidates = 0;
    const ct_real d = in->gap + in->margin;
    const double pad = ctp_pad((double)d, ctp_coord_scale(in));
    int rc = CT_OK;
    ctp::guarded(out, rc, [&] {
        double t0 = seconds();
        const int *ax = ctp_axis_order(s->axis_order >= 0 ? s->axis_order
                                                          : ctp_auto_axis_order(in));
        std::vector<Box> nodes((size_t)in->nsec), segs((size_t)in->nseg);
        const ct_real *xyz[3] = {in->x, in->y, in->z};
        for (ct_idx i = 0; i < in->nsec; i++) {
            Box &b = nodes[(size_t)i];
            ct_idx k = in->sec[i];
            for (int c = 0; c < 3; c++)
                b.lo[c] = b.hi[c] = (double)xyz[ax[c]][k];
            b.ident = (std::size_t)i;
        }
        for (ct_idx j = 0; j < in->nseg; j++) {
            double lo[3], hi[3];
            ctp_seg_box(in, j, lo, hi);
            Box &b = segs[(size_t)j];
            for (int c = 0; c < 3; c++) {
                b.lo[c] = lo[ax[c]] - pad;
                b.hi[c] = hi[ax[c]] + pad;
            }
            b.ident = (std::size_t)in->nsec + (std::size_t)j;
        }
        double t1 = seconds();
        t->build_s = t1 - t0;

        buffers.prepare(1);
        std::vector<ct_idx> &buf = buffers.buf[0];
        buf.clear();
        int64_t cand = 0;
        const std::size_t nsec = (std::size_t)in->nsec;
        auto callback = [&](const Box &a, const Box &b) {
            /* BIPARTITE: a comes from the first sequence (the nodes); the
             * ids say so in any case. */
            const Box &nb = a.ident < nsec ? a : b;
            const Box &sb = a.ident < nsec ? b : a;
            cand++;
            ct_idx node = in->sec[nb.ident];
            ct_idx j = (ct_idx)(sb.ident - nsec);
            ctp::keep_if_accepted(buf, in, node, j, d);
        };
        CGAL::box_intersection_d(nodes.begin(), nodes.end(), segs.begin(), segs.end(), callback,
                                 (std::ptrdiff_t)s->cutoff, CGAL::Box_intersection_d::CLOSED,
                                 CGAL::Box_intersection_d::BIPARTITE);
        ctp::gather(buffers, out, 0, 1, &rc);
        t->candidates = cand;
        t->query_s = seconds() - t1;
    });
    return rc;
}
