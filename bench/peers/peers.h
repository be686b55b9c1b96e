/*
 * peers.h -- the general-purpose libraries our search is compared with
 * (the C++ files of bench/peers, built only by `make bench`), behind a C API
 * the C benchmarks call.
 *
 * Every peer answers the project's query (ct_search.h): the pairs
 * (secondary node, main segment) whose distance may be below d = gap +
 * margin. It finds box-level candidates its own way, then applies the
 * project's exact filter (in->filter: ct_pair_may_touch for CT_FILTER_HULL,
 * ct_pair_box_near for CT_FILTER_BOX) and, when in->self is set, drops a
 * node's own segments, exactly as the project's searches do. The pairs come
 * out in the peer's own order (not the canonical one); each pair once.
 *
 *  - nanoflann: a kd-tree (KDTreeSingleIndexAdaptor, L2_Simple_Adaptor) over
 *    the secondary nodes; one radius search per main segment, around its
 *    box centre, radius = half-diagonal of the box + d. Queries run on
 *    `threads` OpenMP threads (queries on a built index are thread-safe).
 *  - cgal: CGAL::box_intersection_d (segment tree, CLOSED topology,
 *    BIPARTITE setting) of the nodes' point boxes against the segments'
 *    boxes inflated by d; single-threaded.
 *  - bullet: btDbvt (Bullet's dynamic AABB tree) of the segments' boxes
 *    inflated by d, queried by each node's point box (collideTV); queries
 *    on `threads` OpenMP threads (the tree is not modified while queried).
 *  - grid: not a library but the textbook reference (grid_peer.cc): a
 *    straightforward single-pass uniform grid of the nodes, each segment's
 *    inflated box scanning its cells, unordered output; queries on
 *    `threads` OpenMP threads. It is what "a straightforward grid" costs
 *    on this machine, measured, not a peer to beat by a factor.
 *
 * The runs are not reentrant: each peer keeps per-thread candidate buffers
 * between calls (like our workspace), so only one run at a time.
 */
#ifndef CTB_PEERS_H
#define CTB_PEERS_H

#include <stddef.h>
#include <stdint.h>

#include "contact.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ctp_peer {
    CTP_NANOFLANN = 0,
    CTP_CGAL,
    CTP_BULLET,
    CTP_GRID, /* the textbook reference, not a library */
    CTP_NPEERS
} ctp_peer;

/* Bullet tree variants. */
enum {
    CTP_DBVT_INCREMENTAL = 0, /* leaves inserted one by one, mesh order */
    CTP_DBVT_SHUFFLED = 1,    /* inserted in a pseudo-random order */
    CTP_DBVT_TOPDOWN = 2      /* inserted shuffled, then optimizeTopDown() */
};

/* The knobs of each peer (the others are ignored). */
typedef struct ctp_setting {
    int threads;     /* query threads (nanoflann, bullet); cgal uses 1 */
    int leaf_size;   /* nanoflann: leaf_max_size */
    long cutoff;     /* cgal: below this many boxes, scan instead of split */
    int axis_order;  /* cgal: 0..5, index into ctp_axis_order: box
                        dimension k holds coordinate axis order[k]; CGAL's
                        segment tree splits on dimension 2 first and scans
                        on dimension 0. -1 (auto): from the nodes' bounding
                        box, dimension 0 = the longest extent, 2 = the
                        second longest, 1 = the shortest */
    int tree;        /* bullet: CTP_DBVT_* */
} ctp_setting;

/* Time of one run, seconds: building the peer's structure (boxes, points,
 * tree), and querying it (queries, exact filter, output). */
typedef struct ctp_times {
    double build_s, query_s;
    int64_t candidates; /* box-level candidates before the exact filter */
} ctp_times;

/* "nanoflann", "cgal", "bullet", "grid"; and the inverse (-1 when unknown). */
const char *ctp_peer_name(ctp_peer p);
int ctp_peer_from_name(const char *name);

/* The six axis orders of the cgal peer ("xyz", "xzy", ...; -1: "auto"). */
const char *ctp_axis_order_name(int k);
const int *ctp_axis_order(int k);

/* The axis order (0..5) "auto" picks for in (see ctp_setting). */
int ctp_auto_axis_order(const ct_search_input *in);

/* The tuned setting of a peer (see bench_peers.c for the measurements),
 * with `threads` query threads. */
ctp_setting ctp_default_setting(ctp_peer p, int threads);

/* A short description of the setting ("leaf=10", "cutoff=1000 axes=xzy",
 * "tree=topdown") in buf; returns buf. */
const char *ctp_setting_name(ctp_peer p, const ctp_setting *s, char *buf, size_t len);

/* Run one peer on `in`; out (initialised by ct_pairs_init) is grown and
 * overwritten; *t receives the times. Returns CT_OK, CT_ERR_ARG,
 * CT_ERR_NOMEM (an allocation or C++ exception) or CT_ERR_TOOBIG. */
int ctp_nanoflann_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                      ctp_times *t);
int ctp_cgal_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                 ctp_times *t);
int ctp_bullet_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                   ctp_times *t);
int ctp_grid_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                 ctp_times *t);

/* The one that p names. */
int ctp_run(ctp_peer p, const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
            ctp_times *t);

/* ---- Helpers shared by the peers ---------------------------------------- */

/* The project's filter for one pair, by global indices: a node never pairs
 * with its own segment when in->self; then the shared predicate. */
static inline int ctp_pair_accept(const ct_search_input *in, ct_idx node, ct_idx j, ct_real d)
{
    ct_idx i1 = in->n1[j], i2 = in->n2[j], i3 = in->n3[j], i4 = in->n4[j];
    if (in->self && (node == i1 || node == i2 || node == i3 || node == i4))
        return 0;
    const ct_real *x = in->x, *y = in->y, *z = in->z;
    ct_real p[3] = {x[node], y[node], z[node]};
    ct_real a[3] = {x[i1], y[i1], z[i1]}, b[3] = {x[i2], y[i2], z[i2]};
    ct_real c[3] = {x[i3], y[i3], z[i3]}, e[3] = {x[i4], y[i4], z[i4]};
    return in->filter == CT_FILTER_BOX ? ct_pair_box_near(p, a, b, c, e, d)
                                       : ct_pair_may_touch(p, a, b, c, e, d);
}

/* Axis-aligned box of segment j (corners 1..4), in double. */
static inline void ctp_seg_box(const ct_search_input *in, ct_idx j, double lo[3], double hi[3])
{
    const ct_real *xyz[3] = {in->x, in->y, in->z};
    ct_idx n[4] = {in->n1[j], in->n2[j], in->n3[j], in->n4[j]};
    for (int k = 0; k < 3; k++) {
        double a = (double)xyz[k][n[0]], b = (double)xyz[k][n[1]];
        double c = (double)xyz[k][n[2]], e = (double)xyz[k][n[3]];
        double l0 = a < b ? a : b, l1 = c < e ? c : e;
        double h0 = a < b ? b : a, h1 = c < e ? e : c;
        lo[k] = l0 < l1 ? l0 : l1;
        hi[k] = h0 < h1 ? h1 : h0;
    }
}

/* The inflation used for the peers' boxes: d plus a few rounding units of
 * the largest coordinate magnitude `scale`, so that no pair the predicate
 * (evaluated in ct_real) accepts can fall outside a peer's box. The exact
 * filter decides afterwards. */
static inline double ctp_pad(double d, double scale)
{
#ifdef CT_SINGLE
    const double eps = 1.1920929e-07;
#else
    const double eps = 2.220446049250313e-16;
#endif
    return d + 16.0 * eps * (scale + d);
}

/* Largest |coordinate| of the secondary nodes and the segments' nodes. */
double ctp_coord_scale(const ct_search_input *in);

#ifdef __cplusplus
}
#endif

#ifdef __cplusplus
#include <omp.h>

#include <new>
#include <vector>

namespace ctp {

/* Per-thread candidate buffers, kept between runs (each thread touches its
 * own first): pairs as (node, segment) interleaved. */
struct Buffers {
    std::vector<std::vector<ct_idx>> buf;
    std::vector<size_t> count;
    void prepare(int nt)
    {
        if ((int)buf.size() < nt)
            buf.resize((size_t)nt);
        count.assign((size_t)nt, 0);
    }
};

/* Runs a peer's body: an exception (an allocation failure inside the
 * library) becomes CT_ERR_NOMEM in rc, and on any error the output is
 * left empty. */
template <class F> inline void guarded(ct_pairs *out, int &rc, F &&body)
{
    try {
        body();
    } catch (const std::bad_alloc &) {
        rc = CT_ERR_NOMEM;
    } catch (...) {
        rc = CT_ERR_NOMEM;
    }
    if (rc != CT_OK)
        out->n = 0;
}

/* The project's exact filter on pair (node, j), and the pair appended to a
 * thread's buffer when it passes. */
inline void keep_if_accepted(std::vector<ct_idx> &buf, const ct_search_input *in, ct_idx node,
                             ct_idx j, ct_real d)
{
    if (ctp_pair_accept(in, node, j, d)) {
        buf.push_back(node);
        buf.push_back(j);
    }
}

/* Called by every thread t of a team of nt (or by the one thread of a
 * serial run) once its buffer is complete: sizes out, then each thread
 * copies its pairs to its offset. *rc (shared) carries the first error;
 * nothing is copied when it is set. */
inline void gather(Buffers &B, ct_pairs *out, int t, int nt, int *rc)
{
    B.count[(size_t)t] = B.buf[(size_t)t].size() / 2;
#pragma omp barrier
#pragma omp single
    {
        if (*rc == CT_OK) {
            size_t total = 0;
            for (int i = 0; i < nt; i++)
                total += B.count[(size_t)i];
            if (total > (size_t)INT32_MAX) {
                *rc = CT_ERR_TOOBIG;
            } else {
                int r = ct_pairs_reserve(out, (ct_idx)total);
                if (r != CT_OK)
                    *rc = r;
                else
                    out->n = (ct_idx)total;
            }
        }
    }
    if (*rc != CT_OK)
        return;
    size_t off = 0;
    for (int i = 0; i < t; i++)
        off += B.count[(size_t)i];
    const ct_idx *src = B.buf[(size_t)t].data();
    size_t n = B.count[(size_t)t];
    for (size_t k = 0; k < n; k++) {
        out->node[off + k] = src[2 * k];
        out->seg[off + k] = src[2 * k + 1];
    }
}

/* The parallel query every threaded peer runs: a team of nt threads, each
 * with its own cleared buffer; body(tid, buf) holds the peer's worksharing
 * loop (an orphaned `omp for ... nowait`) and returns the box-level
 * candidates it saw; an allocation failure sets rc; then the buffers are
 * gathered into out. Returns the candidates of all threads. */
template <class F>
inline int64_t parallel_query(Buffers &B, int nt, ct_pairs *out, int &rc, F &&body)
{
    B.prepare(nt);
    int64_t cand = 0;
#pragma omp parallel num_threads(nt) reduction(+ : cand)
    {
        int tid = omp_get_thread_num();
        std::vector<ct_idx> &buf = B.buf[(size_t)tid];
        buf.clear();
        try {
            cand += body(tid, buf);
        } catch (const std::bad_alloc &) {
#pragma omp atomic write
            rc = CT_ERR_NOMEM;
        }
        gather(B, out, tid, nt, &rc);
    }
    return cand;
}

} // namespace ctp
#endif

#endif /* CTB_PEERS_H */
