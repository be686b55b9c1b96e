/*
 * test_import_radioss_bricks.c -- the Radioss reader's bricks: the outer
 * surface of a brick block (every face once, outward, none inside) and
 * degenerate bricks.
 */
#include <math.h>
#include <stdint.h>

#include "test_import_radioss.h"

/* ---- Bricks ------------------------------------------------------------ */

/* Centroid and right-hand normal (diagonals' cross product for a quad, edge
 * cross product for a triangle) of a face, and whether all its corners lie
 * in the plane x = 1. */
static void face_geom(const ct_nodes *nd, const ct_idx v[4], double c[3], double nrm[3],
                      int *on_x1)
{
    double p[4][3];
    int m = v[3] == v[2] ? 3 : 4;
    *on_x1 = 1;
    c[0] = c[1] = c[2] = 0;
    for (int k = 0; k < 4; k++) {
        p[k][0] = nd->x[v[k]];
        p[k][1] = nd->y[v[k]];
        p[k][2] = nd->z[v[k]];
        if (k < m) {
            for (int i = 0; i < 3; i++)
                c[i] += p[k][i] / m;
            *on_x1 &= p[k][0] == 1.0;
        }
    }
    double a[3], b[3];
    for (int i = 0; i < 3; i++) {
        a[i] = m == 4 ? p[2][i] - p[0][i] : p[1][i] - p[0][i];
        b[i] = m == 4 ? p[3][i] - p[1][i] : p[2][i] - p[0][i];
    }
    nrm[0] = a[1] * b[2] - a[2] * b[1];
    nrm[1] = a[2] * b[0] - a[0] * b[2];
    nrm[2] = a[0] * b[1] - a[1] * b[0];
}

/* The faces (4 corners each) all point away from `centre`, none lies in
 * x = 1 (the shared face), and their unit normals sum to zero (closed). */
static void check_outer(const ct_nodes *nd, const ct_idx *corners, ct_idx n,
                        const double centre[3])
{
    double sum[3] = {0, 0, 0};
    for (ct_idx f = 0; f < n; f++) {
        double c[3], nrm[3];
        int on_x1;
        face_geom(nd, corners + 4 * (size_t)f, c, nrm, &on_x1);
        double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        cr_assert_gt(len, 0);
        double dot = (nrm[0] * (c[0] - centre[0]) + nrm[1] * (c[1] - centre[1]) +
                      nrm[2] * (c[2] - centre[2])) /
                     len;
        cr_assert_gt(dot, 0.1, "face %ld points inward", (long)f);
        cr_assert(!on_x1, "face %ld is the shared face x = 1", (long)f);
        for (int i = 0; i < 3; i++)
            sum[i] += nrm[i] / len;
    }
    for (int i = 0; i < 3; i++)
        cr_assert_lt(fabs(sum[i]), 1e-12);
}

Test(import_radioss, brick_block_outer_surface)
{
    char path[1024];
    data_path(path, sizeof path, "bricks.rad");
    ctd_deck d;
    load(path, &d);
    cr_assert_eq(d.mesh.nodes.n, 16);
    cr_assert_eq(d.nbrick, 3);
    cr_assert_eq(d.nelemseg, 0);
    /* /SURF/PART/1: the 2x1x1 block of part 2 (brick 2 numbered inside
     * out): 12 faces minus the shared one counted twice = 10, outward. */
    const ctd_surf *sf = ctd_deck_surf(&d, 1);
    cr_assert_not_null(sf);
    cr_assert_eq(sf->s.n, 10);
    ct_idx corners[4 * 16];
    for (ct_idx k = 0; k < sf->s.n; k++) {
        ct_idx s = sf->s.seg[k];
        cr_assert_eq(d.seg_kind[s], CTD_SEG_BRICK_FACE);
        cr_assert_eq(d.seg_part[s], 2);
        corners[4 * k] = d.mesh.n1[s];
        corners[4 * k + 1] = d.mesh.n2[s];
        corners[4 * k + 2] = d.mesh.n3[s];
        corners[4 * k + 3] = d.mesh.n4[s];
    }
    const double centre[3] = {1, 0.5, 0.5};
    check_outer(&d.mesh.nodes, corners, sf->s.n, centre);
    /* /SURF/PART/EXT/2: with part 3's brick on top of brick 1: 18 - 2 x 2
     * = 14 faces; the 9 faces both surfaces share are one segment each, so
     * the mesh holds 10 + 14 - 9 = 15 face segments. */
    sf = ctd_deck_surf(&d, 2);
    cr_assert_not_null(sf);
    cr_assert_eq(sf->s.n, 14);
    cr_assert_eq(d.mesh.nseg, 15);
    /* The same through ctd_deck_brick_surface and the low-level function. */
    ctd_faces f;
    ct_diag g;
    const int64_t p2 = 2;
    cr_assert_eq(ctd_deck_brick_surface(&d, &p2, 1, &f, &g), CT_OK);
    cr_assert_eq(f.n, 10);
    check_outer(&d.mesh.nodes, f.node, f.n, centre);
    for (ct_idx k = 0; k < f.n; k++)
        cr_assert(f.brick[k] == 0 || f.brick[k] == 1);
    ctd_faces_destroy(&f);
    cr_assert_eq(ctd_brick_outer_faces(d.mesh.nodes.n, d.mesh.nodes.x, d.mesh.nodes.y,
                                       d.mesh.nodes.z, d.nbrick, d.brick_node, NULL, &f, &g),
                 CT_OK);
    cr_assert_eq(f.n, 14);
    ctd_faces_destroy(&f);
    const int64_t p9 = 9;
    cr_assert_eq(ctd_deck_brick_surface(&d, &p9, 1, &f, &g), CT_ERR_RANGE);
    /* /GRNOD/PART/3: the 8 nodes of brick 3 (ids 7, 8, 10, 11, 13-16). */
    const ctd_group *gr = ctd_deck_group(&d, 3);
    cr_assert_not_null(gr);
    cr_assert_eq(gr->s.n, 8);
    const int64_t want[8] = {7, 8, 10, 11, 13, 14, 15, 16};
    for (int k = 0; k < 8; k++)
        cr_assert_eq(d.node_id[gr->s.node[k]], want[k]);
    ctd_deck_destroy(&d);
}

/* Degenerate bricks: a prism (nodes 3 = 4 and 7 = 8) has 2 triangles and
 * 3 quads; two tetrahedra (1 2 3 3 4 4 4 4) sharing a triangle have 6 outer
 * triangles; every face points away from the (convex) body's centre. */
Test(import_radioss, degenerate_bricks)
{
    ct_nodes nd;
    cr_assert_eq(ct_nodes_init(&nd, 8), CT_OK);
    const double p[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                            {1, 0, 1}, {0, 1, 1}, {0, 0, -1}, {-1, -1, 0}};
    for (int i = 0; i < 8; i++) {
        nd.x[i] = (ct_real)p[i][0];
        nd.y[i] = (ct_real)p[i][1];
        nd.z[i] = (ct_real)p[i][2];
    }
    const ct_idx prism[8] = {0, 1, 2, 2, 3, 4, 5, 5};
    ctd_faces f;
    ct_diag g;
    cr_assert_eq(ctd_brick_outer_faces(8, nd.x, nd.y, nd.z, 1, prism, NULL, &f, &g), CT_OK);
    cr_assert_eq(f.n, 5);
    int ntri = 0;
    for (ct_idx k = 0; k < f.n; k++)
        ntri += f.node[4 * k + 3] == f.node[4 * k + 2];
    cr_assert_eq(ntri, 2);
    const double pc[3] = {1.0 / 3, 1.0 / 3, 0.5};
    double sum[3] = {0, 0, 0};
    for (ct_idx k = 0; k < f.n; k++) {
        double c[3], nrm[3];
        int on;
        face_geom(&nd, f.node + 4 * k, c, nrm, &on);
        cr_assert_gt(nrm[0] * (c[0] - pc[0]) + nrm[1] * (c[1] - pc[1]) + nrm[2] * (c[2] - pc[2]),
                     0, "prism face %ld points inward", (long)k);
        for (int i = 0; i < 3; i++)
            sum[i] += nrm[i];
    }
    /* Closed: the area vectors (|nrm| = 2 area for a triangle, and for a
     * planar quad by its diagonals) sum to zero. */
    for (int i = 0; i < 3; i++)
        cr_assert_lt(fabs(sum[i]), 1e-12);
    ctd_faces_destroy(&f);
    /* Tetrahedra a b c d and a c b e, a = 1, b = 2, c = 7, d = 3, e = 6. */
    const ct_idx tets[16] = {1, 2, 7, 7, 3, 3, 3, 3, 1, 7, 2, 2, 6, 6, 6, 6};
    cr_assert_eq(ctd_brick_outer_faces(8, nd.x, nd.y, nd.z, 2, tets, NULL, &f, &g), CT_OK);
    cr_assert_eq(f.n, 6);
    for (ct_idx k = 0; k < f.n; k++) {
        cr_assert_eq(f.node[4 * k + 3], f.node[4 * k + 2]);
        double c[3], nrm[3];
        int on;
        face_geom(&nd, f.node + 4 * k, c, nrm, &on);
        cr_assert_gt(nrm[0] * c[0] + nrm[1] * c[1] + nrm[2] * c[2], 0, "tet face %ld", (long)k);
        cr_assert_neq(c[2], 0, "the shared face z = 0 is excluded");
    }
    ctd_faces_destroy(&f);
    /* A node index out of range is an error. */
    const ct_idx bad[8] = {0, 1, 2, 2, 3, 4, 5, 8};
    cr_assert_eq(ctd_brick_outer_faces(8, nd.x, nd.y, nd.z, 1, bad, NULL, &f, &g), CT_ERR_RANGE);
    ct_nodes_destroy(&nd);
}
