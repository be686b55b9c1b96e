/*
 * test_mesh.c -- node arrays, mesh validation (each kind of bad input with
 * its code and message) and the derived topology against hand counts,
 * Euler characteristics and brute force.
 */
#include <stdint.h>
#include <string.h>

#include "test_util.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A plate of nx x ny unit cells built here (not by the generators): node
 * (i, j) = i + (nx+1) j; quads, or two triangles per cell with n4 == n3. */
static void plate(ct_mesh *m, int nx, int ny, int tri)
{
    cr_assert_eq(ct_mesh_init(m, (nx + 1) * (ny + 1), nx * ny * (tri ? 2 : 1)), CT_OK);
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            m->nodes.x[i + (nx + 1) * j] = (ct_real)i;
            m->nodes.y[i + (nx + 1) * j] = (ct_real)j;
        }
    int s = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            ct_idx a = i + (nx + 1) * j, b = a + 1, d = a + nx + 1, c = d + 1;
            if (tri) {
                m->n1[s] = a; m->n2[s] = b; m->n3[s] = c; m->n4[s] = c; s++;
                m->n1[s] = a; m->n2[s] = c; m->n3[s] = d; m->n4[s] = d; s++;
            } else {
                m->n1[s] = a; m->n2[s] = b; m->n3[s] = c; m->n4[s] = d; s++;
            }
        }
}

static void expect_fail(const ct_mesh *m, int code, int64_t index, const char *w1,
                        const char *w2)
{
    ct_diag d;
    memset(&d, 0, sizeof d);
    int rc = ct_mesh_validate(m, &d);
    cr_assert_eq(rc, code, "expected %s, got %s (%s)", ct_strerror(code), ct_strerror(rc),
                 d.msg);
    cr_assert_eq(d.code, code);
    cr_assert_eq(d.index, index, "index %ld, expected %ld: %s", (long)d.index, (long)index,
                 d.msg);
    cr_assert(strstr(d.msg, w1), "message \"%s\" lacks \"%s\"", d.msg, w1);
    cr_assert(strstr(d.msg, w2), "message \"%s\" lacks \"%s\"", d.msg, w2);
}

Test(mesh, nodes_aligned_and_zeroed)
{
    ct_nodes nd;
    cr_assert_eq(ct_nodes_init(&nd, 37), CT_OK);
    ct_real *f[10] = {nd.x, nd.y, nd.z, nd.vx, nd.vy, nd.vz, nd.fx, nd.fy, nd.fz, nd.m};
    for (int k = 0; k < 10; k++) {
        cr_assert_not_null(f[k]);
        cr_assert_eq((uintptr_t)f[k] % CT_ALIGN, 0);
        for (int i = 0; i < 48; i++) /* padded to a multiple of CT_PAD */
            cr_assert_eq(f[k][i], 0);
    }
    cr_assert_eq(nd.n, 37);
    ct_nodes_destroy(&nd);
    cr_assert_null(nd.x);
    cr_assert_eq(ct_nodes_init(&nd, -1), CT_ERR_ARG);
}

Test(mesh, valid_plates_accepted)
{
    ct_mesh m;
    plate(&m, 3, 2, 0);
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    ct_mesh_destroy(&m);
    plate(&m, 3, 2, 1); /* triangles with n4 == n3 */
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    ct_mesh_destroy(&m);
}

Test(mesh, rejects_out_of_range)
{
    ct_mesh m;
    plate(&m, 5, 5, 0); /* 36 nodes */
    m.n3[12] = 99;
    expect_fail(&m, CT_ERR_RANGE, 12, "segment 12: node n3 = 99", "out of range [0, 36)");
    m.n3[12] = m.n4[12] + 1;
    m.n1[4] = -1; /* the first bad segment is reported */
    m.n2[20] = 36;
    expect_fail(&m, CT_ERR_RANGE, 4, "segment 4", "n1 = -1");
    ct_mesh_destroy(&m);
}

Test(mesh, rejects_repeated_node)
{
    ct_mesh m;
    plate(&m, 3, 3, 0);
    m.n4[7] = m.n2[7];
    expect_fail(&m, CT_ERR_DUPNODE, 7, "segment 7", "n4");
    m.n4[7] = m.n3[7]; /* now a (valid) triangle */
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    m.n2[2] = m.n1[2];
    expect_fail(&m, CT_ERR_DUPNODE, 2, "segment 2", "n2");
    ct_mesh_destroy(&m);
    /* A triangle with n4 == n1 is not the convention: rejected. */
    plate(&m, 1, 1, 1);
    m.n4[0] = m.n1[0];
    expect_fail(&m, CT_ERR_DUPNODE, 0, "segment 0", "n4");
    ct_mesh_destroy(&m);
}

Test(mesh, rejects_nan_and_inf)
{
    ct_mesh m;
    plate(&m, 2, 2, 0);
    m.nodes.y[4] = NAN;
    expect_fail(&m, CT_ERR_NONFINITE, 4, "node 4", "y is NaN");
    m.nodes.y[4] = 1;
    m.nodes.z[7] = -INFINITY;
    expect_fail(&m, CT_ERR_NONFINITE, 7, "node 7", "z is infinite");
    /* Segments are checked before nodes. */
    m.n2[3] = 100;
    expect_fail(&m, CT_ERR_RANGE, 3, "segment 3", "n2 = 100");
    ct_mesh_destroy(&m);
}

Test(mesh, rejects_zero_area)
{
    ct_mesh m;
    plate(&m, 2, 2, 0);
    /* Quad 1 (nodes 1 2 5 4) squashed onto a line: every corner on y = x. */
    ct_idx q[4] = {m.n1[1], m.n2[1], m.n3[1], m.n4[1]};
    for (int k = 0; k < 4; k++) {
        m.nodes.x[q[k]] = (ct_real)(k + 1);
        m.nodes.y[q[k]] = (ct_real)(k + 1);
    }
    /* Segment 0 (nodes 0 1 4 3) shares nodes 1 and 4 but keeps its area
     * (node 3 is off the line): the first zero-area segment is 1. */
    expect_fail(&m, CT_ERR_DEGENERATE, 1, "segment 1 has zero area", "longest edge");
    ct_mesh_destroy(&m);

    /* A clean case: one quad whose n3 sits on n1 (the quad folds flat). */
    cr_assert_eq(ct_mesh_init(&m, 4, 1), CT_OK);
    ct_real xs[4] = {0, 1, 0, 1}, ys[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; k++) {
        m.nodes.x[k] = xs[k];
        m.nodes.y[k] = ys[k];
    }
    m.n1[0] = 0; m.n2[0] = 1; m.n3[0] = 2; m.n4[0] = 3;
    expect_fail(&m, CT_ERR_DEGENERATE, 0, "segment 0 has zero area", "longest edge");
    /* Just above the threshold (area 1e-9 x edge^2 in double, 1e-4 in
     * single) it is accepted. */
    m.nodes.y[2] = m.nodes.y[3] = (ct_real)CTT_TOL(1e-9, 1e-4);
    m.nodes.x[2] = 1; m.nodes.x[3] = 0;
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    ct_mesh_destroy(&m);

    /* A triangle (n4 == n3) with collinear corners. */
    cr_assert_eq(ct_mesh_init(&m, 3, 1), CT_OK);
    m.nodes.x[1] = 1; m.nodes.x[2] = 2;
    m.n1[0] = 0; m.n2[0] = 1; m.n3[0] = 2; m.n4[0] = 2;
    expect_fail(&m, CT_ERR_DEGENERATE, 0, "segment 0", "zero area");
    m.nodes.y[2] = 1; /* a proper triangle now */
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    ct_mesh_destroy(&m);
}

/* Finite coordinates whose segment is too large for the arithmetic (found
 * while fuzzing: 1e200 in double gave "zero area: its area inf") are named
 * as such; the same shape scaled down to the largest size accepted passes. */
Test(mesh, rejects_segment_too_large_for_the_precision)
{
    ct_mesh m;
    cr_assert_eq(ct_mesh_init(&m, 3, 1), CT_OK);
    double big = CTT_TOL(1e200, 1e30);
    m.nodes.x[1] = (ct_real)big;
    m.nodes.y[2] = (ct_real)big;
    m.n1[0] = 0; m.n2[0] = 1; m.n3[0] = 2; m.n4[0] = 2;
    expect_fail(&m, CT_ERR_NONFINITE, 0, "segment 0 is too large for", "scale the model");
    /* Longest edge squared 2 L^2 with L^4 well below the limit. */
    double ok = CTT_TOL(1e70, 1e9);
    m.nodes.x[1] = (ct_real)ok;
    m.nodes.y[2] = (ct_real)ok;
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    ct_mesh_destroy(&m);
}

/* ---- Topology ---------------------------------------------------------- */

static void check_sorted_edges(const ct_mesh *m)
{
    for (ct_idx e = 0; e < m->nedge; e++) {
        cr_assert_lt(m->e1[e], m->e2[e]);
        if (e > 0)
            cr_assert(m->e1[e - 1] < m->e1[e] ||
                      (m->e1[e - 1] == m->e1[e] && m->e2[e - 1] < m->e2[e]));
    }
}

Test(mesh, topology_quad_plate_2x2)
{
    ct_mesh m;
    plate(&m, 2, 2, 0);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nedge, 12);
    check_sorted_edges(&m);
    for (ct_idx e = 0; e < 12; e++) {
        int interior = (m.e1[e] == 4 || m.e2[e] == 4); /* the centre node's edges */
        ct_idx cnt = m.edge_seg_off[e + 1] - m.edge_seg_off[e];
        cr_assert_eq(cnt, interior ? 2 : 1, "edge %d-%d", m.e1[e], m.e2[e]);
    }
    cr_assert_eq(m.node_seg_off[5] - m.node_seg_off[4], 4);
    for (int k = 0; k < 4; k++)
        cr_assert_eq(m.node_seg[m.node_seg_off[4] + k], k);
    cr_assert_eq(m.node_seg_off[1] - m.node_seg_off[0], 1);
    cr_assert_eq(m.node_seg[m.node_seg_off[0]], 0);
    cr_assert_eq(m.node_seg_off[2] - m.node_seg_off[1], 2); /* node 1: segments 0, 1 */
    cr_assert_eq(m.node_seg[m.node_seg_off[1]], 0);
    cr_assert_eq(m.node_seg[m.node_seg_off[1] + 1], 1);
    /* Rebuilding replaces the old arrays (no leak, same result). */
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nedge, 12);
    ct_mesh_destroy(&m);
}

Test(mesh, topology_triangle_plate)
{
    ct_mesh m;
    plate(&m, 2, 2, 1);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nedge, 16); /* 12 grid edges + 4 diagonals */
    check_sorted_edges(&m);
    cr_assert_eq(9 - m.nedge + m.nseg, 1); /* a disk */
    /* A triangle lists each node once. Cells 0..3 hold triangles (a b c),
     * (a c d): node 2 (corner (2,0)) is only in triangle 2 = (1 2 5), node 0
     * in both triangles of cell 0; the centre node 4 in 0, 1, 3, 4, 6, 7. */
    cr_assert_eq(m.node_seg_off[3] - m.node_seg_off[2], 1);
    cr_assert_eq(m.node_seg[m.node_seg_off[2]], 2);
    cr_assert_eq(m.node_seg_off[1] - m.node_seg_off[0], 2);
    ct_idx centre[6] = {0, 1, 3, 4, 6, 7};
    cr_assert_eq(m.node_seg_off[5] - m.node_seg_off[4], 6);
    cr_assert_arr_eq(m.node_seg + m.node_seg_off[4], centre, sizeof centre);
    ct_mesh_destroy(&m);
}

/* The surface of the unit cube, 6 quads, outward by the right-hand rule. */
static void cube(ct_mesh *m)
{
    cr_assert_eq(ct_mesh_init(m, 8, 6), CT_OK);
    for (int k = 0; k < 8; k++) {
        m->nodes.x[k] = (ct_real)(k & 1);
        m->nodes.y[k] = (ct_real)((k >> 1) & 1);
        m->nodes.z[k] = (ct_real)((k >> 2) & 1);
    }
    static const ct_idx f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int s = 0; s < 6; s++) {
        m->n1[s] = f[s][0]; m->n2[s] = f[s][1]; m->n3[s] = f[s][2]; m->n4[s] = f[s][3];
    }
}

Test(mesh, topology_cube_closed)
{
    ct_mesh m;
    cube(&m);
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nedge, 12);
    check_sorted_edges(&m);
    for (ct_idx e = 0; e < m.nedge; e++)
        cr_assert_eq(m.edge_seg_off[e + 1] - m.edge_seg_off[e], 2);
    cr_assert_eq(8 - m.nedge + 6, 2);
    for (int i = 0; i < 8; i++)
        cr_assert_eq(m.node_seg_off[i + 1] - m.node_seg_off[i], 3);
    ct_mesh_destroy(&m);
}

Test(mesh, topology_tube)
{
    int nr = 6, nl = 3;
    ct_mesh m;
    cr_assert_eq(ct_mesh_init(&m, nr * (nl + 1), nr * nl), CT_OK);
    for (int l = 0; l <= nl; l++)
        for (int i = 0; i < nr; i++) {
            m.nodes.x[i + nr * l] = (ct_real)cos(2 * M_PI * i / nr);
            m.nodes.y[i + nr * l] = (ct_real)sin(2 * M_PI * i / nr);
            m.nodes.z[i + nr * l] = (ct_real)l;
        }
    for (int l = 0; l < nl; l++)
        for (int i = 0; i < nr; i++) {
            int s = i + nr * l, a = i + nr * l, b = (i + 1) % nr + nr * l;
            m.n1[s] = a; m.n2[s] = b; m.n3[s] = b + nr; m.n4[s] = a + nr;
        }
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nedge, nr * (nl + 1) + nr * nl);
    cr_assert_eq(m.nodes.n - m.nedge + m.nseg, 0);
    int one = 0;
    for (ct_idx e = 0; e < m.nedge; e++)
        one += (m.edge_seg_off[e + 1] - m.edge_seg_off[e]) == 1;
    cr_assert_eq(one, 2 * nr); /* the two end rings */
    ct_mesh_destroy(&m);
}

Test(mesh, topology_non_manifold)
{
    /* Three quads sharing the edge 0-1 (a "book" of three pages). */
    ct_mesh m;
    cr_assert_eq(ct_mesh_init(&m, 8, 3), CT_OK);
    m.nodes.y[1] = 1;
    for (int p = 0; p < 3; p++) {
        double a = 2 * M_PI * p / 3;
        for (int k = 0; k < 2; k++) {
            m.nodes.x[2 + 2 * p + k] = (ct_real)cos(a);
            m.nodes.z[2 + 2 * p + k] = (ct_real)sin(a);
            m.nodes.y[2 + 2 * p + k] = (ct_real)k;
        }
        m.n1[p] = 0; m.n2[p] = 2 + 2 * p; m.n3[p] = 3 + 2 * p; m.n4[p] = 1;
    }
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nedge, 1 + 3 * 3);
    cr_assert_eq(m.e1[0], 0);
    cr_assert_eq(m.e2[0], 1);
    cr_assert_eq(m.edge_seg_off[1] - m.edge_seg_off[0], 3);
    for (int p = 0; p < 3; p++)
        cr_assert_eq(m.edge_seg[m.edge_seg_off[0] + p], p);
    ct_mesh_destroy(&m);
}

/* A plate whose node numbers are randomly permuted and whose cells are a
 * mix of quads and triangles, against brute force, at 1 and 2 threads. */
static void scrambled(ct_mesh *m, int n, uint64_t seed)
{
    ct_mesh p;
    plate(&p, n, n, 0);
    int nn = p.nodes.n, ns = 0;
    ct_idx *perm = malloc(sizeof(ct_idx) * (size_t)nn);
    for (int i = 0; i < nn; i++)
        perm[i] = i;
    for (int i = nn - 1; i > 0; i--) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        int j = (int)((seed >> 33) % (uint64_t)(i + 1));
        ct_idx t = perm[i]; perm[i] = perm[j]; perm[j] = t;
    }
    cr_assert_eq(ct_mesh_init(m, nn, 2 * p.nseg), CT_OK);
    for (int i = 0; i < nn; i++) {
        m->nodes.x[perm[i]] = p.nodes.x[i];
        m->nodes.y[perm[i]] = p.nodes.y[i];
    }
    for (int s = 0; s < p.nseg; s++) {
        ct_idx a = perm[p.n1[s]], b = perm[p.n2[s]], c = perm[p.n3[s]], d = perm[p.n4[s]];
        if (s % 3 == 0) {
            m->n1[ns] = a; m->n2[ns] = b; m->n3[ns] = c; m->n4[ns] = c; ns++;
            m->n1[ns] = a; m->n2[ns] = c; m->n3[ns] = d; m->n4[ns] = d; ns++;
        } else {
            m->n1[ns] = a; m->n2[ns] = b; m->n3[ns] = c; m->n4[ns] = d; ns++;
        }
    }
    m->nseg = ns;
    free(perm);
    ct_mesh_destroy(&p);
}

static int seg_has(const ct_mesh *m, ct_idx s, ct_idx v)
{
    return m->n1[s] == v || m->n2[s] == v || m->n3[s] == v || m->n4[s] == v;
}

static int seg_has_edge(const ct_mesh *m, ct_idx s, ct_idx a, ct_idx b)
{
    ct_idx c[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
    for (int k = 0; k < 4; k++) {
        ct_idx p = c[k], q = c[(k + 1) & 3];
        if ((p == a && q == b) || (p == b && q == a))
            return 1;
    }
    return 0;
}

/* The topology of m against brute force: node -> segment lists exactly the
 * segments containing the node, ascending; edge -> segment the segments
 * having that edge, ascending; every segment edge listed. Returns the
 * number of edge -> segment entries. */
static int64_t check_topology_brute_force(const ct_mesh *m)
{
    check_sorted_edges(m);
    /* Node -> segment: exactly the segments containing the node, ascending. */
    for (ct_idx i = 0; i < m->nodes.n; i++) {
        ct_idx k = m->node_seg_off[i];
        for (ct_idx s = 0; s < m->nseg; s++)
            if (seg_has(m, s, i)) {
                cr_assert_lt(k, m->node_seg_off[i + 1]);
                cr_assert_eq(m->node_seg[k], s);
                k++;
            }
        cr_assert_eq(k, m->node_seg_off[i + 1]);
    }
    /* Edge -> segment: exactly the segments having that edge, ascending; and
     * every segment edge is listed. */
    int64_t total = 0;
    for (ct_idx e = 0; e < m->nedge; e++) {
        ct_idx k = m->edge_seg_off[e];
        for (ct_idx s = 0; s < m->nseg; s++)
            if (seg_has_edge(m, s, m->e1[e], m->e2[e])) {
                cr_assert_eq(m->edge_seg[k], s);
                k++;
            }
        cr_assert_eq(k, m->edge_seg_off[e + 1]);
        total += k - m->edge_seg_off[e];
    }
    int64_t expect = 0;
    for (ct_idx s = 0; s < m->nseg; s++)
        expect += (m->n3[s] == m->n4[s]) ? 3 : 4;
    cr_assert_eq(total, expect);
    return total;
}

Test(mesh, topology_brute_force_and_threads)
{
    ct_mesh m;
    scrambled(&m, 14, 12345);
    ctt_threads(1);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    int64_t total = check_topology_brute_force(&m);
    cr_assert_eq(m.nodes.n - m.nedge + m.nseg, 1); /* still a disk */

    /* The same bytes with 2 threads. */
    ct_mesh r;
    scrambled(&r, 14, 12345);
    ctt_threads(2);
    cr_assert_eq(ct_mesh_build_topology(&r, NULL), CT_OK);
    cr_assert_eq(r.nedge, m.nedge);
    cr_assert_arr_eq(r.e1, m.e1, sizeof(ct_idx) * (size_t)m.nedge);
    cr_assert_arr_eq(r.e2, m.e2, sizeof(ct_idx) * (size_t)m.nedge);
    cr_assert_arr_eq(r.edge_seg_off, m.edge_seg_off, sizeof(ct_idx) * (size_t)(m.nedge + 1));
    cr_assert_arr_eq(r.edge_seg, m.edge_seg, sizeof(ct_idx) * (size_t)total);
    cr_assert_arr_eq(r.node_seg_off, m.node_seg_off, sizeof(ct_idx) * (size_t)(m.nodes.n + 1));
    cr_assert_arr_eq(r.node_seg, m.node_seg,
                     sizeof(ct_idx) * (size_t)m.node_seg_off[m.nodes.n]);
    ct_mesh_destroy(&r);
    ct_mesh_destroy(&m);
}

Test(mesh, topology_fan_of_many_segments)
{
    /* A fan of 48 triangles around node 0, listed in a scrambled order: the
     * apex is in more than 32 segments and is the low node of 96 edge
     * entries, where the topology sorts its lists by qsort rather than by
     * insertion (at most 32). Against brute force, 1 and 2 threads. */
    enum { NT = 48 };
    for (int t = 1; t <= 2; t++) {
        ct_mesh m;
        cr_assert_eq(ct_mesh_init(&m, NT + 1, NT), CT_OK);
        for (int i = 0; i < NT; i++) {
            double a = 2 * M_PI * i / NT;
            m.nodes.x[1 + i] = (ct_real)cos(a);
            m.nodes.y[1 + i] = (ct_real)sin(a);
            m.nodes.z[1 + i] = (ct_real)0.2;
        }
        for (int k = 0; k < NT; k++) {
            int i = (k * 29) % NT; /* 29 is prime to 48: every triangle once */
            m.n1[k] = 0;
            m.n2[k] = 1 + i;
            m.n3[k] = m.n4[k] = 1 + (i + 1) % NT;
        }
        cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
        ctt_threads(t);
        cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
        cr_assert_eq(m.node_seg_off[1] - m.node_seg_off[0], NT);
        cr_assert_eq(m.nedge, 2 * NT); /* spokes and rim */
        int64_t total = check_topology_brute_force(&m);
        cr_assert_eq(total, 3 * NT);
        for (ct_idx e = 0; e < m.nedge; e++) /* spokes two segments, the rim one */
            cr_assert_eq(m.edge_seg_off[e + 1] - m.edge_seg_off[e], m.e1[e] == 0 ? 2 : 1,
                         "edge %d", (int)e);
        cr_assert_eq(m.nodes.n - m.nedge + m.nseg, 1); /* a disk */
        ct_mesh_destroy(&m);
    }
}

Test(mesh, topology_rejects_range)
{
    ct_mesh m;
    plate(&m, 2, 2, 0);
    m.n4[2] = 9;
    ct_diag d;
    cr_assert_eq(ct_mesh_build_topology(&m, &d), CT_ERR_RANGE);
    cr_assert_eq(d.index, 2);
    cr_assert(strstr(d.msg, "segment 2: node n4 = 9"), "%s", d.msg);
    ct_mesh_destroy(&m);
}

Test(mesh, surface_nodes)
{
    ct_mesh m;
    plate(&m, 3, 3, 0); /* 16 nodes, 9 quads */
    ct_idx segs[3] = {8, 0, 4}; /* the diagonal cells */
    ct_surface s = {3, segs};
    ct_nodeset ns;
    cr_assert_eq(ct_surface_nodes(&m, &s, &ns), CT_OK);
    ct_idx expect[10] = {0, 1, 4, 5, 6, 9, 10, 11, 14, 15}; /* 5 and 10 shared */
    cr_assert_eq(ns.n, 10);
    cr_assert_arr_eq(ns.node, expect, sizeof expect);
    ct_nodeset_destroy(&ns);
    cr_assert_null(ns.node);
    segs[1] = 9;
    cr_assert_eq(ct_surface_nodes(&m, &s, &ns), CT_ERR_RANGE);
    ct_mesh_destroy(&m);
}
