/*
 * test_import_radioss_bricks.c -- the Radioss reader's bricks: the outer
 * surface of a brick block (every face once, outward, none inside),
 * degenerate bricks, the surfaces of brick parts and of their unions
 * against a brute-force count, and the time of many such surfaces.
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

/* ---- Surfaces of many brick parts -------------------------------------- */

/* The part of brick (i, j, k) of a block, and whether it is numbered
 * inside out. */
typedef int (*brick_fn)(int i, int j, int k);

/* Write the nodes of a block of nx x ny x nz unit bricks (node (i, j, k) has
 * id 1 + i + (nx + 1) (j + (ny + 1) k)) and its bricks, i fastest, brick
 * number e (0-based) with id e + 1, under a /BRICK/P keyword each time the
 * part changes (so the parts' bricks interleave in the deck's order); a
 * brick numbered inside out lists its top face first. */
static void write_block(FILE *f, int nx, int ny, int nz, brick_fn part, brick_fn inside_out)
{
    fprintf(f, "/NODE\n");
    for (int k = 0; k <= nz; k++)
        for (int j = 0; j <= ny; j++)
            for (int i = 0; i <= nx; i++)
                fprintf(f, "%10d%20d%20d%20d\n", 1 + i + (nx + 1) * (j + (ny + 1) * k), i, j, k);
    long e = 0;
    int prev = -1;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++, e++) {
                int p = part(i, j, k);
                if (p != prev)
                    fprintf(f, "/BRICK/%d\n", p);
                prev = p;
                long n[8];
                for (int c = 0; c < 8; c++) {
                    int di = (c & 3) == 1 || (c & 3) == 2, dj = (c & 3) >= 2, dk = c >= 4;
                    if (inside_out && inside_out(i, j, k))
                        dk = !dk;
                    n[c] = 1 + (i + di) + (long)(nx + 1) * ((j + dj) + (long)(ny + 1) * (k + dk));
                }
                fprintf(f, "%10ld%10ld%10ld%10ld%10ld%10ld%10ld%10ld%10ld\n", e + 1, n[0], n[1],
                        n[2], n[3], n[4], n[5], n[6], n[7]);
            }
}

/* The block of the equality test: 2 x 2 x 1 tiles given to parts 1..4 in
 * turn, so each part touches the others, and a third of the bricks inside
 * out. */
static int tile_part(int i, int j, int k) { return 1 + (i / 2 + 3 * (j / 2) + k) % 4; }
static int tile_inverted(int i, int j, int k) { return (i + 2 * j + k) % 3 == 0; }

/* The corners of local face l (0-based, from the contract in
 * import_radioss.h: 1 4 3 2, 5 6 7 8, 1 2 6 5, 2 3 7 6, 3 4 8 7, 4 1 5 8),
 * sorted. */
static void sorted_face(const ct_idx *c8, int l, ct_idx k[4])
{
    static const int fc[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                                 {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
    for (int c = 0; c < 4; c++)
        k[c] = c8[fc[l][c] - 1];
    for (int a = 1; a < 4; a++)
        for (int b = a; b > 0 && k[b] < k[b - 1]; b--) {
            ct_idx t = k[b];
            k[b] = k[b - 1];
            k[b - 1] = t;
        }
}

/* Each /SURF/PART card over brick parts (single parts and unions of parts
 * that touch, in an order that makes later cards reuse earlier cards'
 * faces) holds exactly the faces of its bricks that no other face of its
 * bricks matches (brute force over all pairs), each once, outward; a face
 * is one segment whatever the number of surfaces that use it. */
Test(import_radioss, brick_part_surfaces_match_brute_force)
{
    enum { NX = 6, NY = 4, NZ = 3, NB = NX * NY * NZ, NCARD = 8 };
    const int card[NCARD][5] = {/* id, then up to 4 parts (0: none) */
                                {7, 2, 3, 4, 2}, {1, 1, 0, 0, 0}, {5, 1, 2, 0, 0},
                                {8, 1, 2, 3, 4}, {2, 2, 0, 0, 0}, {6, 3, 1, 0, 0},
                                {3, 3, 0, 0, 0}, {4, 4, 0, 0, 0}};
    char path[256];
    tmp_path(path, sizeof path, "brick_parts.rad");
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    write_block(f, NX, NY, NZ, tile_part, tile_inverted);
    for (int c = 0; c < NCARD; c++) {
        fprintf(f, "/SURF/PART/%d\ncard %d\n", card[c][0], c);
        for (int q = 1; q < 5 && card[c][q]; q++)
            fprintf(f, "%10d", card[c][q]);
        fprintf(f, "\n");
    }
    fclose(f);
    ctd_deck d;
    load(path, &d);
    unlink(path);
    cr_assert_eq(d.nbrick, NB);
    cr_assert_eq(d.nelemseg, 0);
    static ct_idx slotseg[6 * NB], key[6 * NB][4];
    for (int s = 0; s < 6 * NB; s++) {
        slotseg[s] = -1;
        sorted_face(d.brick_node + 8 * (s / 6), s % 6, key[s]);
    }
    ct_idx nused = 0;
    for (int c = 0; c < NCARD; c++) {
        unsigned char want[6 * NB] = {0};
        int sel[NB] = {0}, nwant = 0;
        for (int b = 0; b < NB; b++)
            for (int q = 1; q < 5; q++)
                sel[b] |= d.brick_part[b] == card[c][q];
        for (int s = 0; s < 6 * NB; s++) {
            int alone = sel[s / 6];
            for (int t = 0; t < 6 * NB && alone; t++)
                alone = t == s || !sel[t / 6] || memcmp(key[s], key[t], sizeof key[s]);
            want[s] = (unsigned char)alone;
            nwant += alone;
        }
        const ctd_surf *sf = ctd_deck_surf(&d, card[c][0]);
        cr_assert_not_null(sf);
        cr_assert_eq(sf->s.n, nwant, "card %d: %ld faces, brute force %d", card[c][0],
                     (long)sf->s.n, nwant);
        for (ct_idx k = 0; k < sf->s.n; k++) {
            ct_idx s = sf->s.seg[k];
            cr_assert(k == 0 || s > sf->s.seg[k - 1], "segments increasing");
            cr_assert_eq(d.seg_kind[s], CTD_SEG_BRICK_FACE);
            ct_idx b = (ct_idx)d.seg_elem[s] - 1;
            int slot = 6 * b + d.seg_face[s];
            cr_assert(want[slot], "card %d: face %d of brick %ld is not outer", card[c][0],
                      d.seg_face[s], (long)b + 1);
            cr_assert_eq(d.seg_part[s], d.brick_part[b]);
            if (slotseg[slot] < 0)
                slotseg[slot] = s, nused++;
            cr_assert_eq(slotseg[slot], s, "one segment per face");
            ct_idx v[4] = {d.mesh.n1[s], d.mesh.n2[s], d.mesh.n3[s], d.mesh.n4[s]}, sk[4];
            double fc[3], nrm[3], bc[3] = {0, 0, 0};
            int on;
            face_geom(&d.mesh.nodes, v, fc, nrm, &on);
            for (int q = 0; q < 8; q++) {
                ct_idx n = d.brick_node[8 * b + q];
                bc[0] += d.mesh.nodes.x[n] / 8;
                bc[1] += d.mesh.nodes.y[n] / 8;
                bc[2] += d.mesh.nodes.z[n] / 8;
            }
            cr_assert_gt(nrm[0] * (fc[0] - bc[0]) + nrm[1] * (fc[1] - bc[1]) +
                             nrm[2] * (fc[2] - bc[2]),
                         0.1, "card %d: segment %ld points inward", card[c][0], (long)s);
            memcpy(sk, v, sizeof sk);
            for (int a = 1; a < 4; a++)
                for (int q = a; q > 0 && sk[q] < sk[q - 1]; q--) {
                    ct_idx t = sk[q];
                    sk[q] = sk[q - 1];
                    sk[q - 1] = t;
                }
            cr_assert(!memcmp(sk, key[slot], sizeof sk), "segment %ld's corners", (long)s);
        }
    }
    /* The whole block's card: its 2 (6 x 4 + 6 x 3 + 4 x 3) boundary faces. */
    cr_assert_eq(ctd_deck_surf(&d, 8)->s.n, 108);
    cr_assert_eq(d.mesh.nseg, nused);
    ctd_deck_destroy(&d);
}

/* The part of brick (i, j, k) of the guard's layer: 10 x 5 tiles. */
static int layer_part(int i, int j, int k)
{
    (void)k;
    return 1 + i / 10 + 40 * (j / 5);
}

/* Many brick parts, each with its own /SURF/PART card: each card used to
 * find the outer faces of all the deck's bricks, so the cost grew as the
 * square of the deck (15.4 s for these 2560 cards over 128000 bricks; 0.34 s
 * once the faces' classes are found once for the deck). */
Test(import_radioss, many_brick_part_surfaces_linear_time, .timeout = 120)
{
    int ny = ctt_checking() ? 50 : 320, np = 8 * ny; /* parts of 10 x 5 bricks */
    char path[256];
    tmp_path(path, sizeof path, "brick_part_surfaces.rad");
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    write_block(f, 400, ny, 1, layer_part, NULL);
    for (int p = 1; p <= np; p++)
        fprintf(f, "/SURF/PART/%d\npart %d\n%10d\n", p, p, p);
    fclose(f);
    ctd_deck d;
    double sec = load_timed(path, &d);
    unlink(path);
    cr_assert_eq(d.nbrick, 400 * ny);
    cr_assert_eq(d.nsurf, np);
    /* A 10 x 5 x 1 tile: 50 + 50 + 2 (10 + 5) faces. */
    for (int p = 1; p <= np; p++)
        cr_assert_eq(ctd_deck_surf(&d, p)->s.n, 130);
    cr_assert_eq(d.mesh.nseg, 130 * np);
    ctd_deck_destroy(&d);
    cr_log_info("import_radioss: %d /SURF/PART cards over %d bricks read in %.3f s", np,
                400 * ny, sec);
    cr_assert_lt(sec, ctt_checking() ? 20.0 : 5.0, "%.2f s", sec);
}
