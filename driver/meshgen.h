/*
 * meshgen.h -- synthetic meshes (prefix ctd_): low-level generators that
 * write one body into a ct_mesh, and the "search cases" (families) the
 * benchmark and the tests build from them.
 *
 * Every generator takes a ct_mesh that holds nothing (it is initialised
 * here; release it with ct_mesh_destroy) and returns CT_OK or a negative
 * CT_ERR_* code. Solids' outer surfaces are oriented outward by the
 * right-hand rule n1 -> n2 -> n3. Only positions are set (velocities,
 * forces and masses are zero); the topology is not built.
 */
#ifndef CTD_MESHGEN_H
#define CTD_MESHGEN_H

#include <stdint.h>

#include "contact.h"

/* ---- Low-level generators ---------------------------------------------- */

/* Plate of nx x ny cells in the plane z = origin[2]: node (i, j) is number
 * i + (nx + 1) j at origin + (i hx, j hy, 0). Cell (i, j) is the quad
 * (i,j) (i+1,j) (i+1,j+1) (i,j+1), normal +z, numbered i + nx j; with
 * `tri` it is two triangles (i,j) (i+1,j) (i+1,j+1) and (i,j) (i+1,j+1)
 * (i,j+1), numbered 2 (i + nx j) and 2 (i + nx j) + 1. */
int ctd_plate(ct_mesh *m, int nx, int ny, double hx, double hy, const double origin[3],
              int tri);

/* The same with node coordinates xs[0..nx], ys[0..ny] (increasing) at z. */
int ctd_plate_coords(ct_mesh *m, int nx, int ny, const double *xs, const double *ys,
                     double z, int tri);

/* Hexahedral block of nx x ny x nz cells of size h[0..2] from origin: all
 * (nx+1)(ny+1)(nz+1) nodes, node (i, j, k) numbered i + (nx+1)(j + (ny+1) k),
 * and its 2 (nx ny + ny nz + nz nx) outer surface quads (outward normals).
 * When hex8 is not NULL, *hex8 receives 8 nx ny nz node numbers (free with
 * ct_free): element (i, j, k), numbered i + nx (j + ny k), lists its bottom
 * face (z = k) counter-clockwise seen from +z, (i,j) (i+1,j) (i+1,j+1)
 * (i,j+1), then the top face (z = k+1) in the same order (the usual hex8
 * ordering: nodes 4-7 above nodes 0-3; positive Jacobian). */
int ctd_block(ct_mesh *m, int nx, int ny, int nz, const double h[3], const double origin[3],
              ct_idx **hex8);

/* Cube-sphere: the surface of a cube of n x n quads per face projected on
 * the sphere of the given radius (equal-angle mapping), 6 n^2 + 2 nodes
 * (shared nodes merged), 6 n^2 quads, outward normals. */
int ctd_sphere(ct_mesh *m, int n, double radius, const double centre[3]);

/* Extrusion of a profile (px[i], py[i]), i < np, along z from z0 over
 * length in nl cells: node (i, l) numbered i + np l. closed: the profile is
 * a loop (np quads per layer); otherwise np - 1 quads per layer. Quad
 * (i,l) (i+1,l) (i+1,l+1) (i,l+1): a counter-clockwise loop gives outward
 * normals. */
int ctd_extrude(ct_mesh *m, int np, const double *px, const double *py, int closed, int nl,
                double length, double z0);

/* Round tube along z: nr quads around, nl along (an extrusion). */
int ctd_tube(ct_mesh *m, int nr, int nl, double radius, double length);

/* Accordion (zigzag) sheet: nlayer flat layers of nflat cells of size h,
 * stacked at distance `spacing` in y and joined by half-circle bends,
 * extruded along z over nw cells of size h. Facing layers are `spacing`
 * apart: self contact on every layer. */
int ctd_folded(ct_mesh *m, int nlayer, int nflat, int nw, double h, double spacing);

/* The number of nodes ctd_folded makes with these arguments, without
 * making them: -1 for arguments it rejects, INT64_MAX when the count does
 * not fit in 64 bits. */
int64_t ctd_folded_nodes(int nlayer, int nflat, int nw, double h, double spacing);

/* Plate of nx x ny cells of size h displaced in x, y and z by a smooth
 * random field (8 Fourier modes per component, wavelength ~ 12 h) of the
 * given amplitude; amplitudes of a few h fold the surface over itself
 * (it may self-intersect). */
int ctd_crumpled(ct_mesh *m, int nx, int ny, double h, double amplitude, uint64_t seed);

/* nplate plates of k x k quads of size h at random positions (inside a cube
 * of side `box` from the origin) and random orientations. */
int ctd_soup(ct_mesh *m, int nplate, int k, double h, double box, uint64_t seed);

/* A new mesh holding a's nodes and segments followed by b's (b's node
 * numbers shifted by a's node count). */
int ctd_mesh_concat(ct_mesh *out, const ct_mesh *a, const ct_mesh *b);

/* ---- Search cases ------------------------------------------------------ */

typedef enum ctd_numbering { CTD_NUM_NATURAL = 0, CTD_NUM_SHUFFLED, CTD_NUM_SFC } ctd_numbering;

typedef struct ctd_case {
    char name[64];                 /* family name */
    ct_mesh mesh;                  /* all nodes; all segments of the case */
    ct_surface main;               /* main segments (sorted mesh segment indices) */
    ct_nodeset sec;                /* secondary nodes (global indices), sorted */
    int self;                      /* 1: main and secondary are one surface */
    ct_idx *mn1, *mn2, *mn3, *mn4; /* main segments' nodes, gathered (main.n) */
    double h_mean;                 /* mean edge length of the main segments */
} ctd_case;

/*
 * Build a case of `family` (see ctd_case_families) of about target_nodes
 * secondary nodes (family by family below); seed drives the random
 * families and the shuffled numbering. Unit mesh size h = 1 unless said.
 *
 *  plates      plate A (secondary, ~target nodes, s x s with s = round(sqrt(
 *              target))) 0.3 above plate B (main, s x s quads, (s+1)^2
 *              nodes), A shifted in-plane by (0.25, 0.35). Total ~2 target.
 *  plates-tri  the same with two triangles per cell (B: 2 s^2 segments).
 *  block       two hex blocks nx x nx x nz (nx ~ 4 nz), A 0.3 above B and
 *              shifted by (0.25, 0.35); main = B's outer surface, sec = A's
 *              surface nodes. target = A's node count (interior included).
 *  sphere      a ball in a socket: inner cube-sphere (secondary, ~target
 *              nodes, n quads per cube edge, quads ~1 wide) inside an outer
 *              one (main, n + 1 per edge) of radius 0.3 larger.
 *  tube        a crushed tube (self): stadium cross-section whose flat walls
 *              are 0.3 apart, ~target nodes.
 *  folded      an accordion sheet (self), layers 0.4 apart, ~target nodes.
 *  crumpled    a plate displaced by ctd_crumpled with amplitude 5 (self),
 *              ~target nodes; about a quarter of its nodes lie within 0.5
 *              of a segment not their own.
 *  soup        3 x 3-quad plates at random in a box (self), ~target nodes.
 *  graded      a plate with geometric grading (cell sizes 1 .. 100 in x and
 *              y) as main, and a copy 0.3 above, shifted by (0.25, 0.35)
 *              cells, as secondary (~target nodes).
 *  ball-plate  a sphere (secondary, ~target nodes) 0.3 above a plate (main)
 *              that covers its shadow.
 * Node counts are within 10% of target for target >= 1000 (tests check).
 * The mesh passes ct_mesh_validate (not run here; the tests check every
 * family). The topology is not built. Cost: O(N) plus an O(N) radix sort
 * for sfc; 10^6 target nodes take 0.1-0.6 s with 2 threads here.
 */
int ctd_case_make(ctd_case *c, const char *family, int64_t target_nodes, ctd_numbering num,
                  uint64_t seed, ct_diag *diag);
void ctd_case_destroy(ctd_case *c);

/* A search input over this case (pointers into c). */
void ctd_case_input(const ctd_case *c, ct_real gap, ct_real margin, ct_search_input *in);

const char *const *ctd_case_families(int *count);
const char *ctd_numbering_name(ctd_numbering n); /* "natural", "shuffled", "sfc" */
int ctd_numbering_from_name(const char *name);   /* -1 when unknown */

/* Renumber the case's nodes and segments (natural: nothing). Every index
 * (segments, main, sec, gathered nodes) follows. */
int ctd_case_renumber(ctd_case *c, ctd_numbering num, uint64_t seed);

/* ---- Helpers shared by the generators ---------------------------------- */

/* splitmix64 step, and a uniform double in [0, 1) from one 64-bit value. */
uint64_t ctd_splitmix64(uint64_t *state);
static inline double ctd_u01(uint64_t r) { return (double)(r >> 11) * 0x1.0p-53; }

/* Sort key[0..n-1] ascending, carrying val; ties keep their input order
 * (LSD radix sort, O(n)). */
int ctd_radix_sort(uint64_t *key, ct_idx *val, int64_t n);

#endif
