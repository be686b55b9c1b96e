/*
 * bullet_peer.cc -- the Bullet peer (Debian libbullet-dev 3.24, the default
 * single-precision build): btDbvt, the dynamic AABB tree behind Bullet's
 * btDbvtBroadphase, holding the main segments' boxes inflated by d, queried
 * by each secondary node's point box with collideTV.
 *
 * btDbvtBroadphase itself would put nodes and segments in its trees and
 * report every overlapping proxy pair through its pair cache, one thread;
 * the tree it is made of, queried directly, is the faster way to ask "which
 * segment boxes contain this point" and its queries are read-only
 * (collideTV is const and keeps its stack on the caller's stack), so they
 * run on OpenMP threads. The knob is the tree variant: leaves inserted one
 * by one in the mesh's order (what the broadphase does), in a shuffled
 * order, or inserted shuffled and then rebuilt by optimizeTopDown (a
 * top-down split, bottom-up below 128 leaves). optimizeIncremental passes
 * were tried too: slower than either on every mesh here.
 *
 * btScalar is float here: boxes are rounded outward to float (segments'
 * boxes down/up, each node's point to a tiny float box around it), so the
 * tree's answer stays a superset; the exact filter decides in ct_real.
 */
#include "peers.h"

/* Bullet's headers live in /usr/include/bullet (the Makefile passes it
 * with -isystem, and links -lBulletCollision -lLinearMath). Without them
 * this file compiles to a stub that refuses to run (CT_ERR_ARG), so the
 * bench still builds and --verify-peers reports the missing peer. */
#if defined(__has_include)
#if __has_include(<btBulletCollisionCommon.h>)
#define CTP_HAVE_BULLET 1
#endif
#endif

#ifndef CTP_HAVE_BULLET
extern "C" int ctp_bullet_run(const ct_search_input *, const ctp_setting *, ct_pairs *out,
                              ctp_times *t)
{
    if (out)
        out->n = 0;
    if (t)
        t->build_s = t->query_s = 0;
    return CT_ERR_ARG;
}
#else

#include <btBulletCollisionCommon.h>

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <new>
#include <vector>

namespace {

double seconds()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

/* The largest btScalar <= v and the smallest >= v. */
btScalar down(double v)
{
    btScalar f = (btScalar)v;
    return (double)f > v ? std::nextafter(f, (btScalar)-INFINITY) : f;
}
btScalar up(double v)
{
    btScalar f = (btScalar)v;
    return (double)f < v ? std::nextafter(f, (btScalar)INFINITY) : f;
}

/* The collideTV policy: one per thread, for the node being queried. */
struct Collect : btDbvt::ICollide {
    const ct_search_input *in;
    ct_real d;
    ct_idx node;
    int64_t cand;
    std::vector<ct_idx> *buf;
    void Process(const btDbvtNode *leaf) override
    {
        ct_idx j = (ct_idx)(intptr_t)leaf->data;
        cand++;
        ctp::keep_if_accepted(*buf, in, node, j, d);
    }
};

ctp::Buffers buffers;

} // namespace

extern "C" int ctp_bullet_run(const ct_search_input *in, const ctp_setting *s, ct_pairs *out,
                              ctp_times *t)
{
    if (!in || !s || !out || !t || in->nsec < 0 || in->nseg < 0 || s->tree < 0 || s->tree > 2)
        return CT_ERR_ARG;
    t->build_s = t->query_s = 0;
    t->candidates = 0;
    const int nt = s->threads > 0 ? s->threads : omp_get_max_threads();
    const ct_real d = in->gap + in->margin;
    const double pad = ctp_pad((double)d, ctp_coord_scale(in));
    int rc = CT_OK;
    ctp::guarded(out, rc, [&] {
        double t0 = seconds();
        btDbvt tree;
        /* Insertion order: natural, or a fixed pseudo-random permutation
         * (an insertion-built tree of boxes inserted along a row degenerates
         * into a deep, list-like tree; random order keeps it shallow). */
        std::vector<ct_idx> order((size_t)in->nseg);
        for (ct_idx j = 0; j < in->nseg; j++)
            order[(size_t)j] = j;
        if (s->tree != CTP_DBVT_INCREMENTAL) {
            uint64_t r = 0x9E3779B97F4A7C15ull;
            for (ct_idx j = in->nseg - 1; j > 0; j--) {
                r ^= r << 13;
                r ^= r >> 7;
                r ^= r << 17;
                ct_idx k = (ct_idx)(r % (uint64_t)(j + 1));
                ct_idx tmp = order[(size_t)j];
                order[(size_t)j] = order[(size_t)k];
                order[(size_t)k] = tmp;
            }
        }
        for (ct_idx q = 0; q < in->nseg; q++) {
            ct_idx j = order[(size_t)q];
            double lo[3], hi[3];
            ctp_seg_box(in, j, lo, hi);
            btVector3 mi(down(lo[0] - pad), down(lo[1] - pad), down(lo[2] - pad));
            btVector3 mx(up(hi[0] + pad), up(hi[1] + pad), up(hi[2] + pad));
            tree.insert(btDbvtVolume::FromMM(mi, mx), (void *)(intptr_t)j);
        }
        if (s->tree == CTP_DBVT_TOPDOWN)
            tree.optimizeTopDown();
        double t1 = seconds();
        t->build_s = t1 - t0;

        auto query = [&](int, std::vector<ct_idx> &buf) {
            Collect col;
            col.in = in;
            col.d = d;
            col.node = 0;
            col.cand = 0;
            col.buf = &buf;
#pragma omp for schedule(dynamic, 1024) nowait
            for (ct_idx i = 0; i < in->nsec; i++) {
                ct_idx k = in->sec[i];
                double p[3] = {(double)in->x[k], (double)in->y[k], (double)in->z[k]};
                btVector3 mi(down(p[0]), down(p[1]), down(p[2]));
                btVector3 mx(up(p[0]), up(p[1]), up(p[2]));
                col.node = k;
                tree.collideTV(tree.m_root, btDbvtVolume::FromMM(mi, mx), col);
            }
            return col.cand;
        };
        t->candidates = ctp::parallel_query(buffers, nt, out, rc, query);
        t->query_s = seconds() - t1;
        /* The tree's destructor (not timed as either) frees its nodes. */
    });
    return rc;
}

#endif /* CTP_HAVE_BULLET */
