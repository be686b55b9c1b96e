/*
 * test_exclusion.c -- the neighbour exclusion of self contact (Irem_gap = 2,
 * kernels/exclude.c) against the test's own geometry: on a flat sheet the
 * excluded segments of a node are every segment within r but its own; on a
 * strip folded into a U they are those within r joined to the node along
 * the strip through segments within r, never the facing leg's. The
 * removal from a search's pairs, thread independence and bad input.
 */
#include "test_util.h"

#include "meshgen.h"

#include <string.h>

/* A U-shaped strip: leg A from x = L to 0 at y = 0, a half circle of radius
 * R around (0, R, .), leg B from x = 0 to L at y = 2R; columns along the
 * strip, rows z = 0 .. nz h. Column i's point is (px[i], py[i]). */
typedef struct ustrip {
    ct_mesh m;
    int ncol, nz;
    double px[128], py[128];
} ustrip;

static void ustrip_make(ustrip *u, double L, double R, double h, int nz)
{
    int nleg = (int)(L / h + 0.5), nb = (int)(3.14159265358979 * R / h + 0.5);
    int c = 0;
    for (int i = 0; i < nleg; i++, c++) { /* leg A, x = L .. h */
        u->px[c] = L - i * h;
        u->py[c] = 0;
    }
    for (int i = 0; i <= nb; i++, c++) { /* the bend, x <= 0 */
        double t = 3.14159265358979323846 * i / nb;
        u->px[c] = -R * sin(t);
        u->py[c] = R - R * cos(t);
    }
    for (int i = 1; i <= nleg; i++, c++) { /* leg B, x = h .. L */
        u->px[c] = i * h;
        u->py[c] = 2 * R;
    }
    u->ncol = c;
    u->nz = nz;
    cr_assert_lt(c, 128);
    cr_assert_eq(ct_mesh_init(&u->m, (ct_idx)(c * (nz + 1)), (ct_idx)((c - 1) * nz)), CT_OK);
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i < c; i++) {
            ct_idx v = (ct_idx)(i + c * j);
            u->m.nodes.x[v] = (ct_real)u->px[i];
            u->m.nodes.y[v] = (ct_real)u->py[i];
            u->m.nodes.z[v] = (ct_real)(j * h);
        }
    for (int j = 0; j < nz; j++)
        for (int i = 0; i + 1 < c; i++) {
            ct_idx s = (ct_idx)(i + (c - 1) * j);
            u->m.n1[s] = (ct_idx)(i + c * j);
            u->m.n2[s] = (ct_idx)(i + 1 + c * j);
            u->m.n3[s] = (ct_idx)(i + 1 + c * (j + 1));
            u->m.n4[s] = (ct_idx)(i + c * (j + 1));
        }
}

/* Distance from p to the rectangle a + s (b - a) + t (d - a), s, t in [0, 1]
 * (b - a orthogonal to d - a: every segment of these tests). */
static double rect_dist(const double p[3], const double a[3], const double b[3],
                        const double d[3])
{
    double u[3], v[3], w[3], uu = 0, vv = 0, pu = 0, pv = 0;
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = d[k] - a[k];
        w[k] = p[k] - a[k];
        uu += u[k] * u[k];
        vv += v[k] * v[k];
        pu += w[k] * u[k];
        pv += w[k] * v[k];
    }
    double s = pu / uu, t = pv / vv;
    s = s < 0 ? 0 : (s > 1 ? 1 : s);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double d2 = 0;
    for (int k = 0; k < 3; k++) {
        double e = w[k] - s * u[k] - t * v[k];
        d2 += e * e;
    }
    return sqrt(d2);
}

static double node_seg_dist(const ct_mesh *m, ct_idx g, ct_idx s)
{
    const ct_nodes *nd = &m->nodes;
    double p[3] = {nd->x[g], nd->y[g], nd->z[g]};
    double a[3] = {nd->x[m->n1[s]], nd->y[m->n1[s]], nd->z[m->n1[s]]};
    double b[3] = {nd->x[m->n2[s]], nd->y[m->n2[s]], nd->z[m->n2[s]]};
    double d[3] = {nd->x[m->n4[s]], nd->y[m->n4[s]], nd->z[m->n4[s]]};
    return rect_dist(p, a, b, d);
}

static int holds(const ct_mesh *m, ct_idx s, ct_idx g)
{
    return m->n1[s] == g || m->n2[s] == g || m->n3[s] == g || m->n4[s] == g;
}

static void input_of(const ct_mesh *m, ct_idx *all, ct_search_input *in)
{
    memset(in, 0, sizeof *in);
    for (ct_idx i = 0; i < m->nodes.n; i++)
        all[i] = i;
    in->nnode = m->nodes.n;
    in->x = m->nodes.x;
    in->y = m->nodes.y;
    in->z = m->nodes.z;
    in->nsec = m->nodes.n;
    in->sec = all;
    in->nseg = m->nseg;
    in->n1 = m->n1;
    in->n2 = m->n2;
    in->n3 = m->n3;
    in->n4 = m->n4;
    in->self = 1;
}

/* The smallest |distance - r| over all node-segment pairs: the test's
 * truth and the kernel's predicate may differ only at a tie. */
static double closest_tie(const ct_mesh *m, double r)
{
    double t = 1e300;
    for (ct_idx g = 0; g < m->nodes.n; g++)
        for (ct_idx s = 0; s < m->nseg; s++)
            t = fmin(t, fabs(node_seg_dist(m, g, s) - r));
    return t;
}

Test(exclusion, flat_sheet_excludes_every_segment_within_r)
{
    /* On a flat sheet the segments within r of a node make a connected
     * patch around it (the cells meeting a disc): all are excluded. */
    ct_mesh m;
    const double org[3] = {0, 0, 0};
    cr_assert_eq(ctd_plate(&m, 16, 12, 1.0, 1.0, org, 0), CT_OK);
    const double r = 2.37;
    cr_assert_gt(closest_tie(&m, r), 1e-6);
    ct_idx *all = ct_calloc((size_t)m.nodes.n, sizeof *all);
    ct_search_input in;
    input_of(&m, all, &in);
    ct_exclusion ex;
    cr_assert_eq(ct_exclusion_build_nodeseg(&ex, &in, (ct_real)r), CT_OK);
    cr_assert_eq(ex.nq, m.nodes.n);
    int64_t total = 0;
    for (ct_idx g = 0; g < m.nodes.n; g++) {
        ct_idx k = ex.off[g];
        for (ct_idx s = 0; s < m.nseg; s++) {
            int want = !holds(&m, s, g) && node_seg_dist(&m, g, s) <= r;
            if (want) {
                cr_assert_lt(k, ex.off[g + 1], "node %d: segment %d missing", (int)g, (int)s);
                cr_assert_eq(ex.item[k], s, "node %d: %d excluded, %d expected", (int)g,
                             (int)ex.item[k], (int)s);
                k++;
                total++;
            }
        }
        cr_assert_eq(k, ex.off[g + 1], "node %d: more segments excluded than within r", (int)g);
    }
    /* An interior node: the 6 x 6 cells within 2 cells of it in x and in
     * y, but its own 4 and the 4 corner cells (at sqrt(2^2 + 2^2) = 2.83
     * > r). */
    ct_idx mid = 8 + 17 * 6;
    cr_assert_eq(ex.off[mid + 1] - ex.off[mid], 36 - 4 - 4);
    cr_assert_gt(total, 0);
    ct_exclusion_destroy(&ex);
    ct_free(all);
    ct_mesh_destroy(&m);
}

/* Truth on the U strip: segment (column c, row j) is excluded for node
 * (cg, jg) when it is within r, not its own, and every column between the
 * node's own columns (cg - 1, cg) and c holds a segment within r (segments
 * of neighbouring columns share a node in any rows). */
static int ustrip_truth(const ustrip *u, ct_idx g, ct_idx s, double r)
{
    const ct_mesh *m = &u->m;
    if (holds(m, s, g) || node_seg_dist(m, g, s) > r)
        return 0;
    int cg = (int)(g % u->ncol), c = (int)(s % (u->ncol - 1));
    int from = c > cg ? cg + 1 : c, to = c > cg ? c : cg - 2;
    for (int cc = from; cc <= to; cc++) {
        int any = 0;
        for (int j = 0; j < u->nz; j++)
            any |= node_seg_dist(m, g, (ct_idx)(cc + (u->ncol - 1) * j)) <= r;
        if (!any)
            return 0;
    }
    return 1;
}

Test(exclusion, folded_strip_keeps_the_facing_leg)
{
    ustrip u;
    ustrip_make(&u, 12.0, 1.5, 1.0, 2);
    const double r = 3.41; /* more than the legs' spacing 3, less than the bend pi R */
    cr_assert_gt(closest_tie(&u.m, r), 1e-6);
    ct_idx *all = ct_calloc((size_t)u.m.nodes.n, sizeof *all);
    ct_search_input in;
    input_of(&u.m, all, &in);
    ct_exclusion ex;
    cr_assert_eq(ct_exclusion_build_nodeseg(&ex, &in, (ct_real)r), CT_OK);
    int64_t kept_facing = 0, excluded = 0;
    for (ct_idx g = 0; g < u.m.nodes.n; g++)
        for (ct_idx s = 0; s < u.m.nseg; s++) {
            int want = ustrip_truth(&u, g, s, r), got = ct_exclusion_has(&ex, g, s);
            cr_assert_eq(got, want, "node %d segment %d: excluded %d, expected %d", (int)g,
                         (int)s, got, want);
            excluded += got;
            kept_facing += !got && !holds(&u.m, s, g) && node_seg_dist(&u.m, g, s) <= r;
        }
    /* Node in the middle of leg A (x = 6): the facing leg's segments
     * within r stay, its own leg's go. */
    ct_idx g = 6;
    int facing = 0, own_leg = 0;
    for (ct_idx s = 0; s < u.m.nseg; s++) {
        if (holds(&u.m, s, g) || node_seg_dist(&u.m, g, s) > r)
            continue;
        int on_b = u.py[s % (u.ncol - 1)] > 2.9;
        if (on_b)
            facing += !ct_exclusion_has(&ex, g, s);
        else
            own_leg += ct_exclusion_has(&ex, g, s);
    }
    cr_assert_gt(facing, 0);
    cr_assert_gt(own_leg, 0);
    cr_assert_gt(kept_facing, 0);
    cr_assert_gt(excluded, 0);
    ct_exclusion_destroy(&ex);
    ct_free(all);
    ct_mesh_destroy(&u.m);
}

Test(exclusion, pairs_lose_exactly_the_excluded_and_keep_their_order)
{
    ustrip u;
    ustrip_make(&u, 10.0, 1.2, 0.5, 3);
    const double r = 2.9;
    ct_idx *all = ct_calloc((size_t)u.m.nodes.n, sizeof *all);
    ct_search_input in;
    input_of(&u.m, all, &in);
    in.gap = (ct_real)r;
    in.margin = (ct_real)0.3;
    ct_search_params sp;
    memset(&sp, 0, sizeof sp);
    sp.algo = CT_SEARCH_DIRECT;
    ct_search *s;
    cr_assert_eq(ct_search_init(&s, &sp), CT_OK);
    ct_pairs p, q;
    cr_assert_eq(ct_pairs_init(&p, 0), CT_OK);
    cr_assert_eq(ct_pairs_init(&q, 0), CT_OK);
    cr_assert_eq(ct_search_run(s, &in, &p), CT_OK);
    cr_assert_eq(ct_search_run(s, &in, &q), CT_OK);
    /* Thread independence of the build. */
    ct_exclusion ex1, ex2;
    ctt_threads(1);
    cr_assert_eq(ct_exclusion_build_nodeseg(&ex1, &in, (ct_real)r), CT_OK);
    ctt_threads(2);
    cr_assert_eq(ct_exclusion_build_nodeseg(&ex2, &in, (ct_real)r), CT_OK);
    cr_assert_eq(ex1.off[ex1.nq], ex2.off[ex2.nq]);
    cr_assert_eq(memcmp(ex1.off, ex2.off, sizeof *ex1.off * ((size_t)ex1.nq + 1)), 0);
    cr_assert_eq(memcmp(ex1.item, ex2.item, sizeof *ex1.item * (size_t)ex1.off[ex1.nq]), 0);
    int64_t removed = -1;
    cr_assert_eq(ct_pairs_exclude(&q, &ex1, &removed), CT_OK);
    /* q is p without the excluded pairs, in p's order. */
    ct_idx w = 0;
    int64_t want_removed = 0;
    for (ct_idx k = 0; k < p.n; k++) {
        if (ct_exclusion_has(&ex1, p.node[k], p.seg[k])) {
            want_removed++;
            continue;
        }
        cr_assert_lt(w, q.n);
        cr_assert(q.node[w] == p.node[k] && q.seg[w] == p.seg[k], "pair %d out of place",
                  (int)w);
        w++;
    }
    cr_assert_eq(w, q.n);
    cr_assert_eq(removed, want_removed);
    cr_assert_gt(removed, 0);
    cr_assert_gt(q.n, 0); /* the facing leg's pairs */
    /* Every excluded item is within r, so every one is among p's pairs. */
    cr_assert_eq(removed, (int64_t)ex1.off[ex1.nq]);
    ct_exclusion_destroy(&ex1);
    ct_exclusion_destroy(&ex2);
    ct_pairs_destroy(&p);
    ct_pairs_destroy(&q);
    ct_search_destroy(s);
    ct_free(all);
    ct_mesh_destroy(&u.m);
}

/* Items of two nodes (edges e1[t] e2[t]) and ncand candidates. */
static ct_exclusion_input edge_input(ct_idx nnode, ct_idx nitem, const ct_idx *e1,
                                     const ct_idx *e2, ct_idx nq, ct_idx ncand, const ct_idx *cq,
                                     const ct_idx *ci)
{
    ct_exclusion_input e;
    memset(&e, 0, sizeof e);
    e.nnode = nnode;
    e.nitem = nitem;
    e.nper = 2;
    e.in[0] = e1;
    e.in[1] = e2;
    e.nq = nq;
    e.ncand = ncand;
    e.cq = cq;
    e.ci = ci;
    return e;
}

Test(exclusion, edges_grow_through_shared_nodes)
{
    /* Items of two nodes: a polyline 0-1-2-...-9 along x (h = 1) and a
     * separate one 10..19 at y = 0.5 above it. Query: the edge (4, 5).
     * Candidates within r = 2.2 (by hand): edges 2..6 of the first line
     * (edge i joins nodes i, i+1; edge 4 the query itself) and edges 2..6
     * of the second. The first line's reach the query through shared
     * nodes, the second's do not. */
    ct_idx e1[18], e2[18];
    for (int i = 0; i < 9; i++) {
        e1[i] = i;
        e2[i] = i + 1;
        e1[9 + i] = 10 + i;
        e2[9 + i] = 11 + i;
    }
    ct_idx q1[1] = {4}, q2[1] = {5};
    ct_idx cq[10], ci[10];
    for (int i = 0; i < 5; i++) {
        cq[i] = cq[5 + i] = 0;
        ci[i] = 2 + i;
        ci[5 + i] = 9 + 2 + i;
    }
    ct_exclusion_input e = edge_input(20, 18, e1, e2, 1, 10, cq, ci);
    e.q1 = q1;
    e.q2 = q2;
    ct_exclusion ex;
    cr_assert_eq(ct_exclusion_build(&ex, &e), CT_OK);
    ct_idx want[] = {2, 3, 4, 5, 6};
    cr_assert_eq(ex.off[1], 5);
    for (int i = 0; i < 5; i++)
        cr_assert_eq(ex.item[i], want[i]);
    ct_exclusion_destroy(&ex);
    /* A gap in the chain: edge 1 is a candidate, edge 2 not; the edges
     * holding a query node (3, 4, 5) join the growth whether candidates or
     * not (they touch the query), so edge 1 is cut off behind edge 2. */
    ct_idx ci2[4] = {1, 5, 6, 11}, cq2[4] = {0, 0, 0, 0};
    e.ncand = 4;
    e.cq = cq2;
    e.ci = ci2;
    cr_assert_eq(ct_exclusion_build(&ex, &e), CT_OK);
    cr_assert_eq(ex.off[1], 2);
    cr_assert_eq(ex.item[0], 5);
    cr_assert_eq(ex.item[1], 6);
    ct_exclusion_destroy(&ex);
}

Test(exclusion, bad_input_is_refused)
{
    ct_idx a[2] = {0, 1}, b[2] = {1, 2}, cq[1] = {0}, ci[1] = {5};
    ct_exclusion_input e = edge_input(3, 2, a, b, 3, 1, cq, ci);
    ct_exclusion ex;
    cr_assert_eq(ct_exclusion_build(&ex, &e), CT_ERR_RANGE); /* item 5 of 2 */
    cr_assert_null(ex.off);
    ci[0] = 1;
    e.nper = 3;
    cr_assert_eq(ct_exclusion_build(&ex, &e), CT_ERR_ARG);
    e.nper = 2;
    e.nq = 4; /* queries are nodes: no more than nnode */
    cr_assert_eq(ct_exclusion_build(&ex, &e), CT_ERR_RANGE);
    e.nq = 3;
    b[1] = 3; /* an item's node beyond nnode */
    cr_assert_eq(ct_exclusion_build(&ex, &e), CT_ERR_RANGE);
    b[1] = 2;
    cr_assert_eq(ct_exclusion_build(&ex, &e), CT_OK);
    ct_pairs p;
    cr_assert_eq(ct_pairs_init(&p, 1), CT_OK);
    p.n = 1;
    p.node[0] = 7; /* a node beyond the exclusion's queries */
    p.seg[0] = 0;
    cr_assert_eq(ct_pairs_exclude(&p, &ex, NULL), CT_ERR_RANGE);
    cr_assert_eq(p.n, 1);
    ct_exclusion_destroy(&ex);
    ct_search_input in;
    memset(&in, 0, sizeof in);
    cr_assert_eq(ct_exclusion_build_nodeseg(&ex, &in, (ct_real)NAN), CT_ERR_ARG);
    cr_assert_eq(ct_exclusion_build_nodeseg(&ex, &in, -1), CT_ERR_ARG);
    ct_pairs_destroy(&p);
    ct_exclusion_destroy(&ex);
}
