/*
 * grid_peer.cc -- the textbook reference: a straightforward single-pass
 * uniform grid, written the way one would write it first, to measure what
 * the engineering of our searches buys (and what it costs: canonical order,
 * input checks, determinism) on the same query.
 *
 * Build: the secondary nodes' bounding box, cut into cubic cells whose edge
 * is the mean largest extent of the main segments' boxes (at most
 * 2 nsec + 1024 cells: coarser when the box is large for the mesh), and a
 * counting sort of the nodes into the cells (count, prefix sum, place; one
 * thread). Query: the segments in parallel (OpenMP, dynamic chunks); each
 * inflates its box by d, scans the nodes of the cells the box covers, keeps
 * the nodes inside the box and applies the project's exact filter. No
 * re-sort of the output: pairs come out segment by segment, in the order the
 * threads finish (the harness compares them as sets). Its arrays are kept
 * from one run to the next, like our workspaces.
 */
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <new>
#include <vector>

#include "peers.h"

namespace {

double seconds()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

ctp::Buffers buffers;
std::vector<int64_t> start; /* per cell: first position in order */
std::vector<ct_idx> order;  /* positions in in->sec, cell by cell */
std::vector<int64_t> cell;  /* per position: its cell */
std::vector<int64_t> fill;  /* per cell: next free position (placing) */

} // namespace

extern "C" int ctp_grid_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                            ctp_times *t)
{
    if (!in || !s || !out || !t || in->nsec < 0 || in->nseg < 0)
        return CT_ERR_ARG;
    t->build_s = t->query_s = 0;
    t->candidates = 0;
    const int nt = s->threads > 0 ? s->threads : omp_get_max_threads();
    const ct_real d = in->gap + in->margin;
    const double pad = ctp_pad((double)d, ctp_coord_scale(in));
    int rc = CT_OK;
    ctp::guarded(out, rc, [&] {
        double t0 = seconds();
        const ct_real *xyz[3] = {in->x, in->y, in->z};
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (ct_idx i = 0; i < in->nsec; i++)
            for (int k = 0; k < 3; k++) {
                double v = (double)xyz[k][in->sec[i]];
                lo[k] = std::min(lo[k], v);
                hi[k] = std::max(hi[k], v);
            }
        double h = 0;
        for (ct_idx j = 0; j < in->nseg; j++) {
            double a[3], b[3];
            ctp_seg_box(in, j, a, b);
            h += std::max(b[0] - a[0], std::max(b[1] - a[1], b[2] - a[2]));
        }
        h = in->nseg > 0 ? h / in->nseg : 1;
        if (!(h > 0))
            h = 1;
        const int64_t maxc = 2 * (int64_t)in->nsec + 1024;
        int64_t n[3];
        double inv[3];
        for (;;) {
            int64_t prod = 1;
            for (int k = 0; k < 3; k++) {
                double e = in->nsec > 0 ? hi[k] - lo[k] : 0;
                n[k] = std::max<int64_t>(1, (int64_t)(e / h) + 1);
                inv[k] = e > 0 ? 1 / h : 0;
                prod *= n[k];
            }
            if (prod <= maxc)
                break;
            h *= 1.25;
        }
        const int64_t ncell = n[0] * n[1] * n[2];
        start.assign((size_t)ncell + 1, 0);
        order.resize((size_t)in->nsec);
        cell.resize((size_t)in->nsec);
        for (ct_idx i = 0; i < in->nsec; i++) {
            int64_t c[3];
            for (int k = 0; k < 3; k++)
                c[k] = std::min<int64_t>(n[k] - 1,
                                         (int64_t)(((double)xyz[k][in->sec[i]] - lo[k]) * inv[k]));
            int64_t cc = (c[2] * n[1] + c[1]) * n[0] + c[0];
            cell[(size_t)i] = cc;
            start[(size_t)cc + 1]++;
        }
        for (int64_t c = 0; c < ncell; c++)
            start[(size_t)c + 1] += start[(size_t)c];
        fill.assign(start.begin(), start.end() - 1);
        for (ct_idx i = 0; i < in->nsec; i++)
            order[(size_t)fill[(size_t)cell[(size_t)i]]++] = i;
        double t1 = seconds();
        t->build_s = t1 - t0;

        auto query = [&](int, std::vector<ct_idx> &buf) {
            int64_t cand = 0;
#pragma omp for schedule(dynamic, 1024) nowait
            for (ct_idx j = 0; j < in->nseg; j++) {
                if (in->nsec == 0)
                    continue;
                double a[3], b[3];
                ctp_seg_box(in, j, a, b);
                int64_t c0[3], c1[3];
                bool miss = false;
                for (int k = 0; k < 3; k++) {
                    a[k] -= pad;
                    b[k] += pad;
                    miss |= b[k] < lo[k] || a[k] > hi[k];
                    c0[k] = (int64_t)std::max(0.0, (a[k] - lo[k]) * inv[k]);
                    c1[k] = std::min<int64_t>(
                        n[k] - 1, (int64_t)std::max(0.0, (b[k] - lo[k]) * inv[k]));
                }
                if (miss)
                    continue;
                for (int64_t iz = c0[2]; iz <= c1[2]; iz++)
                    for (int64_t iy = c0[1]; iy <= c1[1]; iy++)
                        for (int64_t ix = c0[0]; ix <= c1[0]; ix++) {
                            int64_t cc = (iz * n[1] + iy) * n[0] + ix;
                            for (int64_t e = start[(size_t)cc]; e < start[(size_t)cc + 1];
                                 e++) {
                                ct_idx node = in->sec[order[(size_t)e]];
                                double p[3] = {(double)in->x[node], (double)in->y[node],
                                               (double)in->z[node]};
                                if (p[0] < a[0] || p[0] > b[0] || p[1] < a[1] ||
                                    p[1] > b[1] || p[2] < a[2] || p[2] > b[2])
                                    continue;
                                cand++;
                                ctp::keep_if_accepted(buf, in, node, j, d);
                            }
                        }
            }
            return cand;
        };
        t->candidates = ctp::parallel_query(buffers, nt, out, rc, query);
        t->query_s = seconds() - t1;
    });
    return rc;
}
