/*
 * narrow_bits.c -- prints a hash of every output of the narrow-phase
 * kernels (node-triangle, the three node-quadrangle methods, one- and
 * two-sided, edge-edge) over a fixed set of random pairs: near contact,
 * far, on edges and corners, warped, degenerate, with NaN and Inf
 * coordinates. `make check-narrow-cc` builds it twice, with the block
 * kernels compiled by NARROW_CC and by CC, and requires the same output:
 * the two compilers' code must give the same bits (see NARROW_VEC_SRC in
 * the Makefile). Not a Criterion test: the comparison is between two
 * programs.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"

#define NNODE 60000
#define NPAIR 200000

static uint64_t rng_state = 0x9e3779b97f4a7c15u;

static uint64_t rng_next(void)
{
    uint64_t x = rng_state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return rng_state = x;
}

/* Uniform in [-1, 1). */
static double rng_sym(void) { return (double)(rng_next() >> 11) * 0x1p-52 - 1; }

static ct_idx rng_below(ct_idx n) { return (ct_idx)(rng_next() % (uint64_t)n); }

/* FNV-1a over the bytes of n elements of size s. */
static uint64_t hash_bytes(uint64_t h, const void *p, size_t bytes)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < bytes; i++) {
        h ^= c[i];
        h *= 0x100000001b3u;
    }
    return h;
}

/* The mesh: NNODE / 5 segments of 4 corners each and a node per segment
 * placed about it (nodes 4 s .. 4 s + 3 the corners of segment s, node
 * 4 NSEG + s its node). */
#define NSEG (NNODE / 5)

static ct_real X[NNODE], Y[NNODE], Z[NNODE], GN[NNODE];
static ct_idx N1[NSEG], N2[NSEG], N3[NSEG], N4[NSEG];
static ct_real GS[NSEG];
static ct_idx PNODE[NPAIR], PSEG[NPAIR];

static void make_mesh(void)
{
    for (ct_idx s = 0; s < NSEG; s++) {
        ct_idx b = 4 * s;
        int kind = (int)rng_below(16);
        double ox = 10 * rng_sym(), oy = 10 * rng_sym(), oz = 10 * rng_sym();
        double ax = rng_sym(), ay = rng_sym(), az = 0.3 * rng_sym();
        double bx = rng_sym(), by = rng_sym(), bz = 0.3 * rng_sym();
        double w = kind < 8 ? 0.3 * rng_sym() : 0; /* warp of the fourth corner */
        double c[4][3] = {{ox, oy, oz},
                          {ox + ax, oy + ay, oz + az},
                          {ox + ax + bx, oy + ay + by, oz + az + bz + w},
                          {ox + bx, oy + by, oz + bz}};
        if (kind == 8) /* zero area: all corners on a line */
            for (int k = 1; k < 4; k++)
                for (int d = 0; d < 3; d++)
                    c[k][d] = c[0][d] + k * (c[1][d] - c[0][d]);
        if (kind == 9) /* a needle: one side 1e-7 long */
            for (int d = 0; d < 3; d++) {
                c[3][d] = c[0][d] + 1e-7 * (c[3][d] - c[0][d]);
                c[2][d] = c[1][d] + 1e-7 * (c[2][d] - c[1][d]);
            }
        if (kind == 10) /* two coincident corners */
            for (int d = 0; d < 3; d++)
                c[2][d] = c[1][d];
        for (int k = 0; k < 4; k++) {
            X[b + k] = (ct_real)c[k][0];
            Y[b + k] = (ct_real)c[k][1];
            Z[b + k] = (ct_real)c[k][2];
        }
        if (kind == 11) /* a NaN or an infinite corner */
            X[b + (ct_idx)rng_below(4)] = (rng_next() & 1) ? NAN : INFINITY;
        N1[s] = b;
        N2[s] = b + 1;
        N3[s] = b + 2;
        N4[s] = (kind & 1) ? b + 2 : b + 3; /* odd kinds: triangles */
        GS[s] = (ct_real)(0.05 + 0.1 * fabs(rng_sym()));
        /* The segment's node: a point of its plane (inside, on an edge or a
         * corner, or outside) lifted by a small signed height. */
        double u = 1.4 * rng_sym() + 0.5, v = 1.4 * rng_sym() + 0.5;
        int where = (int)rng_below(8);
        if (where == 0)
            u = 0;
        if (where == 1)
            u = v = 1;
        double h = (where == 2) ? 0 : 0.4 * rng_sym();
        double nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
        double nl = sqrt(nx * nx + ny * ny + nz * nz);
        nl = nl > 0 ? nl : 1;
        ct_idx p = 4 * NSEG + s;
        X[p] = (ct_real)(ox + u * ax + v * bx + h * nx / nl);
        Y[p] = (ct_real)(oy + u * ay + v * by + h * ny / nl);
        Z[p] = (ct_real)(oz + u * az + v * bz + h * nz / nl);
        if (where == 3 && kind == 12)
            Z[p] = NAN;
        GN[p] = (ct_real)(0.05 + 0.1 * fabs(rng_sym()));
    }
    /* Pairs: mostly a segment's own node, some another segment's (far);
     * kinds of segment come in runs of random length, as in a pair list. */
    for (ct_idx k = 0; k < NPAIR; k++) {
        ct_idx s = rng_below(NSEG);
        PSEG[k] = s;
        PNODE[k] = 4 * NSEG + ((rng_next() & 7) ? s : rng_below(NSEG));
    }
}

static ct_real *col(void) { return ct_calloc(NPAIR, sizeof(ct_real)); }

int main(void)
{
    make_mesh();
    ct_contact_geo g = {col(), col(), col(), col(), col(), col(), col(), col(), col(),
                        col(), col(), col(), col(), ct_calloc(NPAIR, 1)};
    ct_real *const arr[13] = {g.dist, g.pen, g.nx, g.ny, g.nz, g.cx, g.cy,
                              g.cz, g.h1, g.h2, g.h3, g.h4, g.gap};
    for (int a = 0; a < 13; a++)
        if (!arr[a] || !g.flag) {
            fprintf(stderr, "narrow_bits: out of memory\n");
            return 1;
        }
    int status = 0;
    for (int m = 0; m < CT_QUAD_NMETHOD; m++)
        for (int two = 0; two < 2; two++)
            for (int var = 0; var < 2; var++) {
                ct_narrow_stats st;
                int rc = ct_narrow_node_segment(
                    NPAIR, PNODE, PSEG, N1, N2, N3, N4, X, Y, Z, var ? GN : NULL,
                    var ? GS : NULL, (ct_real)0.1, (ct_real)0.12, (ct_real)0.08,
                    (ct_quad_method)m, two, &g, &st);
                uint64_t h = 0xcbf29ce484222325u;
                for (int a = 0; a < 13; a++)
                    h = hash_bytes(h, arr[a], NPAIR * sizeof(ct_real));
                h = hash_bytes(h, g.flag, NPAIR);
                printf("node-segment %-6s %s gaps=%s rc=%d active=%lld fallbacks=%lld "
                       "degenerate=%lld nonfinite=%lld hash=%016llx\n",
                       ct_quad_method_name((ct_quad_method)m), two ? "two-sided" : "one-sided",
                       var ? "per-node+segment" : "uniform", rc, (long long)st.active,
                       (long long)st.fallbacks, (long long)st.degenerate,
                       (long long)st.nonfinite, (unsigned long long)h);
                status |= rc != CT_OK;
            }
    /* Edge-edge: the segments' sides as edges, random pairs of them. */
    const ct_idx ne = 4 * NSEG;
    ct_idx *e1 = ct_calloc((size_t)ne, sizeof(ct_idx)), *e2 = ct_calloc((size_t)ne, sizeof(ct_idx));
    ct_idx *ea = ct_calloc(NPAIR, sizeof(ct_idx)), *eb = ct_calloc(NPAIR, sizeof(ct_idx));
    ct_real *ge = ct_calloc((size_t)ne, sizeof(ct_real));
    if (!e1 || !e2 || !ea || !eb || !ge) {
        fprintf(stderr, "narrow_bits: out of memory\n");
        return 1;
    }
    for (ct_idx e = 0; e < ne; e++) {
        e1[e] = e;
        e2[e] = (e % 4 == 3) ? e - 3 : e + 1;
        ge[e] = (ct_real)(0.05 + 0.2 * fabs(rng_sym()));
    }
    for (ct_idx k = 0; k < NPAIR; k++) {
        ea[k] = rng_below(ne);
        /* Mostly a nearby edge (same or next segment), some far. */
        ct_idx s = ea[k] / 4 + ((rng_next() & 3) ? 0 : 1);
        eb[k] = (rng_next() & 7) ? (4 * (s % NSEG) + (ct_idx)rng_below(4)) : rng_below(ne);
    }
    ct_edge_geo eg = {g.dist, g.pen, g.nx, g.ny, g.nz, g.cx, g.cy, g.cz, g.h1, g.h2, g.h3,
                      g.h4, col(), g.gap, g.flag};
    if (!eg.pbz) {
        fprintf(stderr, "narrow_bits: out of memory\n");
        return 1;
    }
    for (int var = 0; var < 2; var++) {
        ct_narrow_stats st;
        int rc = ct_narrow_edge_edge(NPAIR, ea, eb, e1, e2, X, Y, Z, var ? ge : NULL,
                                     (ct_real)0.1, (ct_real)0.15, &eg, &st);
        uint64_t h = 0xcbf29ce484222325u;
        ct_real *const ea_[15] = {eg.dist, eg.pen, eg.nx, eg.ny, eg.nz, eg.sa, eg.sb, eg.pax,
                                  eg.pay, eg.paz, eg.pbx, eg.pby, eg.pbz, eg.gap, NULL};
        for (int a = 0; ea_[a]; a++)
            h = hash_bytes(h, ea_[a], NPAIR * sizeof(ct_real));
        h = hash_bytes(h, eg.flag, NPAIR);
        printf("edge-edge gaps=%s rc=%d active=%lld degenerate=%lld nonfinite=%lld "
               "hash=%016llx\n",
               var ? "per-edge" : "uniform", rc, (long long)st.active,
               (long long)st.degenerate, (long long)st.nonfinite, (unsigned long long)h);
        status |= rc != CT_OK;
    }
    /* Provenance on stderr: it differs between the two builds compared. */
    fprintf(stderr, "%s\n", ct_build_info());
    return status;
}
