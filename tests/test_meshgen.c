/*
 * test_meshgen.c -- the synthetic mesh generators and search cases: valid
 * meshes, node counts near the target, outward normals, exact geometry
 * (sphere radius, plate gap, unit spacing), topology of closed and open
 * surfaces, numbering variants that keep the geometry, determinism.
 */
#include <stdint.h>
#include <string.h>

#include "meshgen.h"
#include "test_util.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define TARGET 2000

static void make(ctd_case *c, const char *fam, int64_t target, ctd_numbering num, uint64_t seed)
{
    ct_diag d;
    memset(&d, 0, sizeof d);
    int rc = ctd_case_make(c, fam, target, num, seed, &d);
    cr_assert_eq(rc, CT_OK, "%s: %s", fam, d.msg);
}

/* Segment normal by the right-hand rule (diagonals' cross product) and
 * centroid (mean of the corners), in double. */
static void seg_geom(const ct_mesh *m, ct_idx s, double cen[3], double nrm[3])
{
    ct_idx v[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
    double p[4][3];
    for (int k = 0; k < 4; k++) {
        p[k][0] = m->nodes.x[v[k]];
        p[k][1] = m->nodes.y[v[k]];
        p[k][2] = m->nodes.z[v[k]];
    }
    double a[3], b[3];
    for (int i = 0; i < 3; i++) {
        cen[i] = (p[0][i] + p[1][i] + p[2][i] + p[3][i]) / 4;
        a[i] = p[2][i] - p[0][i];
        b[i] = p[3][i] - p[1][i];
    }
    if (v[2] == v[3]) /* triangle: (n2 - n1) x (n3 - n1) */
        for (int i = 0; i < 3; i++) {
            a[i] = p[1][i] - p[0][i];
            b[i] = p[2][i] - p[0][i];
        }
    nrm[0] = a[1] * b[2] - a[2] * b[1];
    nrm[1] = a[2] * b[0] - a[0] * b[2];
    nrm[2] = a[0] * b[1] - a[1] * b[0];
}

static void assert_outward(const ct_mesh *m, const double ctr[3])
{
    for (ct_idx s = 0; s < m->nseg; s++) {
        double c[3], n[3];
        seg_geom(m, s, c, n);
        double dot = (c[0] - ctr[0]) * n[0] + (c[1] - ctr[1]) * n[1] + (c[2] - ctr[2]) * n[2];
        cr_assert_gt(dot, 0, "segment %d points inward", s);
    }
}

/* ---- Every family ------------------------------------------------------ */

Test(meshgen, families_valid_and_sized)
{
    int nf;
    const char *const *fam = ctd_case_families(&nf);
    cr_assert_eq(nf, 10);
    for (int f = 0; f < nf; f++) {
        ctd_case c;
        make(&c, fam[f], TARGET, CTD_NUM_NATURAL, 7);
        ct_diag d;
        cr_assert_eq(ct_mesh_validate(&c.mesh, &d), CT_OK, "%s: %s", fam[f], d.msg);
        cr_assert_str_eq(c.name, fam[f]);
        cr_assert_gt(c.main.n, 0);
        cr_assert_gt(c.h_mean, 0);
        /* Target = secondary node count (block: the upper block's nodes,
         * i.e. those above z = 0.1), within 10%. */
        int64_t n = c.sec.n;
        if (!strcmp(fam[f], "block")) {
            n = 0;
            for (ct_idx i = 0; i < c.mesh.nodes.n; i++)
                n += c.mesh.nodes.z[i] > 0.1;
        }
        cr_assert(n >= 0.9 * TARGET && n <= 1.1 * TARGET, "%s: %ld nodes for target %d",
                  fam[f], (long)n, TARGET);
        /* sec sorted, unique, in range; main likewise; gathered nodes match. */
        for (ct_idx k = 1; k < c.sec.n; k++)
            cr_assert_lt(c.sec.node[k - 1], c.sec.node[k]);
        cr_assert_lt(c.sec.node[c.sec.n - 1], c.mesh.nodes.n);
        for (ct_idx k = 1; k < c.main.n; k++)
            cr_assert_lt(c.main.seg[k - 1], c.main.seg[k]);
        for (ct_idx k = 0; k < c.main.n; k++) {
            ct_idx s = c.main.seg[k];
            cr_assert(c.mn1[k] == c.mesh.n1[s] && c.mn2[k] == c.mesh.n2[s] &&
                      c.mn3[k] == c.mesh.n3[s] && c.mn4[k] == c.mesh.n4[s]);
        }
        ct_search_input in;
        ctd_case_input(&c, (ct_real)0.1, (ct_real)0.2, &in);
        cr_assert(in.nsec == c.sec.n && in.sec == c.sec.node && in.nseg == c.main.n &&
                  in.n1 == c.mn1 && in.x == c.mesh.nodes.x && in.self == c.self &&
                  in.gap == (ct_real)0.1 && in.margin == (ct_real)0.2);
        ctd_case_destroy(&c);
    }
}

Test(meshgen, self_and_two_body_cases)
{
    static const char *const self_fam[] = {"tube", "folded", "crumpled", "soup"};
    static const char *const two_fam[] = {"plates", "plates-tri", "block", "sphere",
                                          "graded", "ball-plate"};
    for (int f = 0; f < 4; f++) {
        ctd_case c;
        make(&c, self_fam[f], TARGET, CTD_NUM_SHUFFLED, 3);
        cr_assert_eq(c.self, 1, "%s", self_fam[f]);
        cr_assert_eq(c.main.n, c.mesh.nseg); /* main = every segment */
        /* sec = all nodes of the surface (every node is on it here). */
        cr_assert_eq(c.sec.n, c.mesh.nodes.n, "%s", self_fam[f]);
        for (ct_idx k = 0; k < c.sec.n; k++)
            cr_assert_eq(c.sec.node[k], k);
        ctd_case_destroy(&c);
    }
    for (int f = 0; f < 6; f++) {
        ctd_case c;
        make(&c, two_fam[f], TARGET, CTD_NUM_NATURAL, 3);
        cr_assert_eq(c.self, 0, "%s", two_fam[f]);
        /* No secondary node belongs to a main segment. */
        unsigned char *is_sec = calloc((size_t)c.mesh.nodes.n, 1);
        for (ct_idx k = 0; k < c.sec.n; k++)
            is_sec[c.sec.node[k]] = 1;
        for (ct_idx k = 0; k < c.main.n; k++)
            cr_assert(!is_sec[c.mn1[k]] && !is_sec[c.mn2[k]] && !is_sec[c.mn3[k]] &&
                          !is_sec[c.mn4[k]],
                      "%s", two_fam[f]);
        free(is_sec);
        ctd_case_destroy(&c);
    }
}

Test(meshgen, plates_geometry)
{
    for (int tri = 0; tri < 2; tri++) {
        ctd_case c;
        make(&c, tri ? "plates-tri" : "plates", 2500, CTD_NUM_NATURAL, 1);
        cr_assert_eq(c.sec.n, 2500);                 /* 50 x 50 nodes */
        cr_assert_eq(c.main.n, tri ? 5000 : 2500);   /* 50 x 50 cells */
        for (ct_idx k = 0; k < c.sec.n; k++) {
            ct_idx i = c.sec.node[k];
            cr_assert_float_eq(c.mesh.nodes.z[i], 0.3, CTT_TOL(1e-15, 1e-7));
            /* Shifted by (0.25, 0.35) from the unit grid. */
            double fx = c.mesh.nodes.x[i] - floor(c.mesh.nodes.x[i]);
            double fy = c.mesh.nodes.y[i] - floor(c.mesh.nodes.y[i]);
            cr_assert_float_eq(fx, 0.25, CTT_TOL(1e-12, 1e-4));
            cr_assert_float_eq(fy, 0.35, CTT_TOL(1e-12, 1e-4));
        }
        for (ct_idx k = 0; k < c.main.n; k++)
            cr_assert_eq(c.mesh.nodes.z[c.mn1[k]], 0);
        /* Unit quads: every edge 1; two triangles per cell: edges 1, 1, sqrt 2. */
        double h = tri ? (2 + sqrt(2.0)) / 3 : 1.0;
        cr_assert_float_eq(c.h_mean, h, CTT_TOL(1e-12, 1e-6));
        ctd_case_destroy(&c);
    }
}

/* ---- Low-level generators ---------------------------------------------- */

Test(meshgen, block_outward_hex8_and_closed)
{
    int nx = 4, ny = 3, nz = 2;
    double h[3] = {1, 0.5, 2}, o[3] = {1, 2, 3};
    ct_mesh m;
    ct_idx *hex = NULL;
    cr_assert_eq(ctd_block(&m, nx, ny, nz, h, o, &hex), CT_OK);
    cr_assert_eq(m.nodes.n, 5 * 4 * 3);
    cr_assert_eq(m.nseg, 2 * (12 + 6 + 8));
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    double ctr[3] = {1 + 2, 2 + 0.75, 3 + 2};
    assert_outward(&m, ctr);
    /* Every surface quad lies on the box's boundary (one coordinate at a
     * face of the box for all four corners). */
    /* hex8: nodes 4..7 are 0..3 one layer up; (n1-n0) x (n3-n0) . (n4-n0) > 0. */
    for (int e = 0; e < nx * ny * nz; e++) {
        ct_idx *q = hex + 8 * e;
        double p[8][3];
        for (int k = 0; k < 8; k++) {
            p[k][0] = m.nodes.x[q[k]];
            p[k][1] = m.nodes.y[q[k]];
            p[k][2] = m.nodes.z[q[k]];
        }
        for (int k = 0; k < 4; k++) {
            cr_assert_float_eq(p[k + 4][2] - p[k][2], 2.0, 1e-12);
            cr_assert_float_eq(p[k + 4][0], p[k][0], 1e-12);
        }
        double a[3], b[3], cc[3];
        for (int i = 0; i < 3; i++) {
            a[i] = p[1][i] - p[0][i];
            b[i] = p[3][i] - p[0][i];
            cc[i] = p[4][i] - p[0][i];
        }
        double vol = (a[1] * b[2] - a[2] * b[1]) * cc[0] + (a[2] * b[0] - a[0] * b[2]) * cc[1] +
                     (a[0] * b[1] - a[1] * b[0]) * cc[2];
        cr_assert_float_eq(vol, 1 * 0.5 * 2, CTT_TOL(1e-12, 1e-5));
        /* Bottom face counter-clockwise from +z: (n1-n0) x (n2-n1) has +z. */
        double z = (p[1][0] - p[0][0]) * (p[2][1] - p[1][1]) -
                   (p[1][1] - p[0][1]) * (p[2][0] - p[1][0]);
        cr_assert_gt(z, 0);
    }
    ct_free(hex);
    /* The surface is closed: every edge in two quads; Euler 2 over the
     * surface nodes. */
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    for (ct_idx e = 0; e < m.nedge; e++)
        cr_assert_eq(m.edge_seg_off[e + 1] - m.edge_seg_off[e], 2);
    ct_surface all = {m.nseg, malloc(sizeof(ct_idx) * (size_t)m.nseg)};
    for (ct_idx s = 0; s < m.nseg; s++)
        all.seg[s] = s;
    ct_nodeset sn;
    cr_assert_eq(ct_surface_nodes(&m, &all, &sn), CT_OK);
    cr_assert_eq(sn.n, 5 * 4 * 3 - 3 * 2 * 1); /* minus the interior nodes */
    cr_assert_eq(sn.n - m.nedge + m.nseg, 2);
    ct_nodeset_destroy(&sn);
    free(all.seg);
    ct_mesh_destroy(&m);
}

Test(meshgen, sphere_radius_outward_closed)
{
    double ctr[3] = {0.5, -1, 2}, R = 3;
    ct_mesh m;
    int n = 5;
    cr_assert_eq(ctd_sphere(&m, n, R, ctr), CT_OK);
    cr_assert_eq(m.nodes.n, 6 * n * n + 2);
    cr_assert_eq(m.nseg, 6 * n * n);
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    for (ct_idx i = 0; i < m.nodes.n; i++) {
        double dx = m.nodes.x[i] - ctr[0], dy = m.nodes.y[i] - ctr[1],
               dz = m.nodes.z[i] - ctr[2];
        cr_assert_float_eq(sqrt(dx * dx + dy * dy + dz * dz), R, CTT_TOL(1e-14, 1e-6) * R);
    }
    assert_outward(&m, ctr);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    for (ct_idx e = 0; e < m.nedge; e++)
        cr_assert_eq(m.edge_seg_off[e + 1] - m.edge_seg_off[e], 2);
    cr_assert_eq(m.nodes.n - m.nedge + m.nseg, 2);
    /* Shared nodes merged: no two nodes at the same place. */
    double dmin = 1e300;
    for (ct_idx i = 0; i < m.nodes.n; i++)
        for (ct_idx j = i + 1; j < m.nodes.n; j++) {
            double dx = m.nodes.x[i] - m.nodes.x[j], dy = m.nodes.y[i] - m.nodes.y[j],
                   dz = m.nodes.z[i] - m.nodes.z[j];
            double d = sqrt(dx * dx + dy * dy + dz * dz);
            dmin = d < dmin ? d : dmin;
        }
    cr_assert_gt(dmin, 0.1 * R / n);
    ct_mesh_destroy(&m);
}

Test(meshgen, tube_and_folded_topology)
{
    ct_mesh m;
    cr_assert_eq(ctd_tube(&m, 12, 5, 2.0, 10.0), CT_OK);
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    assert_outward(&m, (double[3]){0, 0, 0}); /* radial component only matters */
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nodes.n - m.nedge + m.nseg, 0);
    ct_mesh_destroy(&m);

    /* Folded: an open sheet (a disk topologically); facing layers 0.4
     * apart, so every node of an inner layer has a node of another layer
     * within 0.4 + h in y. */
    cr_assert_eq(ctd_folded(&m, 4, 10, 3, 1.0, 0.4), CT_OK);
    cr_assert_eq(ct_mesh_validate(&m, NULL), CT_OK);
    cr_assert_eq(ct_mesh_build_topology(&m, NULL), CT_OK);
    cr_assert_eq(m.nodes.n - m.nedge + m.nseg, 1);
    double ymax = 0;
    for (ct_idx i = 0; i < m.nodes.n; i++)
        ymax = m.nodes.y[i] > ymax ? m.nodes.y[i] : ymax;
    cr_assert_float_eq(ymax, 3 * 0.4, CTT_TOL(1e-12, 1e-6));
    ct_mesh_destroy(&m);
}

/* The folded sheet's node count, known without making the mesh (a scene's
 * check counted nodes by making it: 10^9 nodes for layers 1000 of cells
 * [1000, 1000]), is the count the mesh has, for spacings that round the
 * section's length either way; and absurd sizes give INT64_MAX, not a
 * wrapped count. */
Test(meshgen, folded_node_count_without_the_mesh)
{
    const struct {
        int layers, nflat, nw;
        double h, spacing;
    } c[] = {{1, 1, 1, 1.0, 0.5}, {4, 10, 3, 1.0, 0.4},  {7, 13, 2, 0.3, 0.17},
             {3, 5, 4, 0.1, 0.0637}, {2, 9, 1, 2.0, 7.3}, {20, 3, 5, 0.5, 0.011}};
    for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
        ct_mesh m;
        cr_assert_eq(ctd_folded(&m, c[k].layers, c[k].nflat, c[k].nw, c[k].h, c[k].spacing),
                     CT_OK);
        cr_assert_eq(ctd_folded_nodes(c[k].layers, c[k].nflat, c[k].nw, c[k].h, c[k].spacing),
                     (int64_t)m.nodes.n, "case %zu", k);
        ct_mesh_destroy(&m);
    }
    cr_assert_eq(ctd_folded_nodes(0, 1, 1, 1.0, 1.0), -1);
    cr_assert_eq(ctd_folded_nodes(1, 1, 1, 1.0, 0.0), -1);
    cr_assert_eq(ctd_folded_nodes(100000000, 100000000, 100000000, 1e-300, 1e300), INT64_MAX);
    cr_assert_eq(ctd_folded_nodes(1000, 1000, 1000, 1.0, 2.0),
                 (int64_t)1001 * (int64_t)llround((1000 * 1000.0 + 999 * M_PI) / 1.0 + 1));
}

Test(meshgen, plate_numbering_documented)
{
    ct_mesh m;
    double o[3] = {1, 2, 3};
    cr_assert_eq(ctd_plate(&m, 3, 2, 0.5, 2.0, o, 1), CT_OK);
    cr_assert_eq(m.nseg, 12);
    /* node (i, j) = i + 4 j at origin + (0.5 i, 2 j, 0). */
    cr_assert_float_eq(m.nodes.x[2 + 4 * 1], 2.0, 1e-12);
    cr_assert_float_eq(m.nodes.y[2 + 4 * 1], 4.0, 1e-12);
    cr_assert_float_eq(m.nodes.z[2 + 4 * 1], 3.0, 1e-12);
    /* cell (1, 1) -> triangles 2 (1 + 3) and 2 (1 + 3) + 1. */
    cr_assert(m.n1[8] == 5 && m.n2[8] == 6 && m.n3[8] == 10 && m.n4[8] == 10);
    cr_assert(m.n1[9] == 5 && m.n2[9] == 10 && m.n3[9] == 9 && m.n4[9] == 9);
    assert_outward(&m, (double[3]){0, 0, -1e3}); /* normals +z */
    ct_mesh_destroy(&m);
}

/* ---- Numbering --------------------------------------------------------- */

static int cmp3(const void *a, const void *b)
{
    const double *p = a, *q = b;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k])
            return p[k] < q[k] ? -1 : 1;
    return 0;
}

/* Sorted coordinates of the given nodes (all when list is NULL). */
static double *node_multiset(const ctd_case *c, const ct_idx *list, ct_idx n)
{
    double *v = malloc(sizeof(double) * 3 * (size_t)n);
    for (ct_idx k = 0; k < n; k++) {
        ct_idx i = list ? list[k] : k;
        v[3 * k] = c->mesh.nodes.x[i];
        v[3 * k + 1] = c->mesh.nodes.y[i];
        v[3 * k + 2] = c->mesh.nodes.z[i];
    }
    qsort(v, (size_t)n, 3 * sizeof(double), cmp3);
    return v;
}

static int cmp6(const void *a, const void *b)
{
    const double *p = a, *q = b;
    for (int k = 0; k < 6; k++)
        if (p[k] != q[k])
            return p[k] < q[k] ? -1 : 1;
    return 0;
}

/* Sorted (centroid, normal) of the main segments (all segments when
 * all != 0): the geometry and the orientation. */
static double *seg_multiset(const ctd_case *c, int all, ct_idx *count)
{
    ct_idx n = all ? c->mesh.nseg : c->main.n;
    double *v = malloc(sizeof(double) * 6 * (size_t)n);
    for (ct_idx k = 0; k < n; k++)
        seg_geom(&c->mesh, all ? k : c->main.seg[k], v + 6 * k, v + 6 * k + 3);
    qsort(v, (size_t)n, 6 * sizeof(double), cmp6);
    *count = n;
    return v;
}

Test(meshgen, numbering_keeps_geometry)
{
    static const char *const fam[] = {"plates", "graded", "soup", "sphere", "block"};
    for (int f = 0; f < 5; f++) {
        ctd_case nat;
        make(&nat, fam[f], 1500, CTD_NUM_NATURAL, 11);
        ct_idx nsn, nmn;
        double *nodes0 = node_multiset(&nat, NULL, nat.mesh.nodes.n);
        double *sec0 = node_multiset(&nat, nat.sec.node, nat.sec.n);
        double *segs0 = seg_multiset(&nat, 1, &nsn);
        double *main0 = seg_multiset(&nat, 0, &nmn);
        for (int num = CTD_NUM_SHUFFLED; num <= CTD_NUM_SFC; num++) {
            ctd_case c;
            make(&c, fam[f], 1500, (ctd_numbering)num, 11);
            cr_assert_eq(c.mesh.nodes.n, nat.mesh.nodes.n);
            cr_assert_eq(c.sec.n, nat.sec.n);
            cr_assert_eq(c.main.n, nat.main.n);
            cr_assert_eq(c.self, nat.self);
            ct_idx ns2, nm2;
            double *nodes1 = node_multiset(&c, NULL, c.mesh.nodes.n);
            double *sec1 = node_multiset(&c, c.sec.node, c.sec.n);
            double *segs1 = seg_multiset(&c, 1, &ns2);
            double *main1 = seg_multiset(&c, 0, &nm2);
            const char *nm = ctd_numbering_name((ctd_numbering)num);
            cr_assert_arr_eq(nodes1, nodes0, 3 * sizeof(double) * (size_t)c.mesh.nodes.n,
                             "%s %s", fam[f], nm);
            cr_assert_arr_eq(sec1, sec0, 3 * sizeof(double) * (size_t)c.sec.n, "%s %s",
                             fam[f], nm);
            cr_assert_arr_eq(segs1, segs0, 6 * sizeof(double) * (size_t)nsn, "%s %s", fam[f],
                             nm);
            cr_assert_arr_eq(main1, main0, 6 * sizeof(double) * (size_t)nmn, "%s %s", fam[f],
                             nm);
            cr_assert_float_eq(c.h_mean, nat.h_mean, CTT_TOL(1e-12, 1e-5) * nat.h_mean);
            cr_assert_eq(ct_mesh_validate(&c.mesh, NULL), CT_OK);
            free(nodes1);
            free(sec1);
            free(segs1);
            free(main1);
            ctd_case_destroy(&c);
        }
        free(nodes0);
        free(sec0);
        free(segs0);
        free(main0);
        ctd_case_destroy(&nat);
    }
}

Test(meshgen, shuffled_differs_and_is_deterministic)
{
    ctd_case a, b, n, d;
    make(&n, "plates", 1000, CTD_NUM_NATURAL, 5);
    make(&a, "plates", 1000, CTD_NUM_SHUFFLED, 5);
    make(&b, "plates", 1000, CTD_NUM_SHUFFLED, 5);
    make(&d, "plates", 1000, CTD_NUM_SHUFFLED, 6);
    size_t nb = sizeof(ct_real) * (size_t)n.mesh.nodes.n,
           sb = sizeof(ct_idx) * (size_t)n.mesh.nseg;
    cr_assert_neq(memcmp(a.mesh.nodes.x, n.mesh.nodes.x, nb), 0);
    cr_assert_neq(memcmp(a.mesh.n1, n.mesh.n1, sb), 0);
    cr_assert_neq(memcmp(a.mesh.nodes.x, d.mesh.nodes.x, nb), 0);
    cr_assert_arr_eq(a.mesh.nodes.x, b.mesh.nodes.x, nb);
    cr_assert_arr_eq(a.mesh.nodes.z, b.mesh.nodes.z, nb);
    cr_assert_arr_eq(a.mesh.n1, b.mesh.n1, sb);
    cr_assert_arr_eq(a.mesh.n4, b.mesh.n4, sb);
    cr_assert_arr_eq(a.sec.node, b.sec.node, sizeof(ct_idx) * (size_t)a.sec.n);
    cr_assert_arr_eq(a.mn2, b.mn2, sizeof(ct_idx) * (size_t)a.main.n);
    /* The secondary nodes are scattered over the numbering, not a range. */
    cr_assert_gt(a.sec.node[a.sec.n - 1] - a.sec.node[0], a.sec.n);
    ctd_case_destroy(&a);
    ctd_case_destroy(&b);
    ctd_case_destroy(&d);
    ctd_case_destroy(&n);

    /* Random families: same seed, same bytes, at 1 and 2 threads. */
    ctt_threads(1);
    make(&a, "crumpled", 1000, CTD_NUM_SFC, 9);
    ctt_threads(2);
    make(&b, "crumpled", 1000, CTD_NUM_SFC, 9);
    cr_assert_arr_eq(a.mesh.nodes.y, b.mesh.nodes.y, sizeof(ct_real) * (size_t)a.mesh.nodes.n);
    cr_assert_arr_eq(a.mesh.n3, b.mesh.n3, sizeof(ct_idx) * (size_t)a.mesh.nseg);
    cr_assert_eq(a.h_mean, b.h_mean);
    ctd_case_destroy(&a);
    ctd_case_destroy(&b);
    make(&a, "soup", 1000, CTD_NUM_NATURAL, 1);
    make(&b, "soup", 1000, CTD_NUM_NATURAL, 2);
    cr_assert_neq(memcmp(a.mesh.nodes.x, b.mesh.nodes.x, sizeof(ct_real) * 16), 0);
    ctd_case_destroy(&a);
    ctd_case_destroy(&b);
}

/* Morton key built bit by bit (independent of the generator's magic
 * numbers), on the same quantisation: 2^21 - 1 steps over the box. */
static uint64_t morton_slow(const double p[3], const double lo[3], const double hi[3])
{
    uint64_t q[3], key = 0;
    for (int a = 0; a < 3; a++) {
        double t = hi[a] > lo[a] ? (p[a] - lo[a]) * (2097151.0 / (hi[a] - lo[a])) : 0;
        t = t < 0 ? 0 : t > 2097151.0 ? 2097151.0 : t;
        q[a] = (uint64_t)t;
    }
    for (int bit = 0; bit < 21; bit++)
        for (int a = 0; a < 3; a++)
            key |= ((q[a] >> bit) & 1) << (3 * bit + a);
    return key;
}

Test(meshgen, sfc_orders_nodes_along_the_curve)
{
    ctd_case c;
    make(&c, "ball-plate", 1500, CTD_NUM_SFC, 0);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    const ct_real *xyz[3] = {c.mesh.nodes.x, c.mesh.nodes.y, c.mesh.nodes.z};
    for (ct_idx i = 0; i < c.mesh.nodes.n; i++)
        for (int a = 0; a < 3; a++) {
            lo[a] = xyz[a][i] < lo[a] ? xyz[a][i] : lo[a];
            hi[a] = xyz[a][i] > hi[a] ? xyz[a][i] : hi[a];
        }
    uint64_t prev = 0;
    for (ct_idx i = 0; i < c.mesh.nodes.n; i++) {
        double p[3] = {xyz[0][i], xyz[1][i], xyz[2][i]};
        uint64_t k = morton_slow(p, lo, hi);
        cr_assert_geq(k, prev, "node %d out of curve order", i);
        prev = k;
    }
    ctd_case_destroy(&c);
}

Test(meshgen, bad_requests)
{
    ctd_case c;
    ct_diag d;
    cr_assert_eq(ctd_case_make(&c, "pancake", 1000, CTD_NUM_NATURAL, 0, &d), CT_ERR_ARG);
    cr_assert(strstr(d.msg, "pancake"), "%s", d.msg);
    cr_assert_eq(ctd_case_make(&c, "plates", 1, CTD_NUM_NATURAL, 0, &d), CT_ERR_ARG);
    cr_assert_eq(ctd_numbering_from_name("sfc"), CTD_NUM_SFC);
    cr_assert_eq(ctd_numbering_from_name("hilbert"), -1);
    cr_assert_str_eq(ctd_numbering_name(CTD_NUM_SHUFFLED), "shuffled");
}

/* ---- Large ------------------------------------------------------------- */

Test(meshgen, plates_million, .timeout = 60)
{
    if (ctt_checking())
        cr_skip_test("large case skipped under sanitizers");
    ctd_case c;
    make(&c, "plates", 1000000, CTD_NUM_SFC, 1);
    cr_assert_eq(c.sec.n, 1000000);
    cr_assert_eq(c.main.n, 1000000);
    cr_assert_eq(ct_mesh_validate(&c.mesh, NULL), CT_OK);
    cr_assert_eq(ct_mesh_build_topology(&c.mesh, NULL), CT_OK);
    /* Two disks: Euler characteristic 2; plate B has 2 * 1000 * 1001 edges,
     * plate A 2 * 999 * 1000. */
    cr_assert_eq(c.mesh.nedge, 2 * 1000 * 1001 + 2 * 999 * 1000);
    cr_assert_eq((int64_t)c.mesh.nodes.n - c.mesh.nedge + c.mesh.nseg, 2);
    ctd_case_destroy(&c);
}
