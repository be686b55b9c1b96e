/*
 * bench_kernels_data.h -- the data of the kernel benchmarks
 * (bench_kernels_data.c): realistic node-segment pairs of the plates case
 * with the force and assembly inputs, and synthetic edge-edge pairs, each
 * built once per size and first touched by the largest team.
 */
#ifndef BENCH_KERNELS_DATA_H
#define BENCH_KERNELS_DATA_H

#include <stdint.h>

#include "bench_search.h"
#include "contact.h"

/* Physical constants of the force benchmarks. */
#define KB_VISS 0.05
#define KB_DT 1e-4
#define KB_MU0 0.2
#define KB_KT0 1e3

/* Node-segment pairs (rc != CT_OK: err says why). */
typedef struct pdata {
    int valid, rc, tri;
    char err[300];
    int64_t want;
    ct_idx npair, nnode, nseg, nsec;
    double gap;
    ct_real *x, *y, *z;
    ct_real *xyzw; /* x, y, z packed by ct_coords_pack (the _packed rows) */
    ct_idx *n1, *n2, *n3, *n4, *node, *seg;
    ct_real *g[13]; /* dist pen nx ny nz cx cy cz h1 h2 h3 h4 gap */
    uint8_t *flag;
    ct_contact_geo geo;
    /* Force and assembly inputs (quads; made on first use). */
    int force_ready;
    ct_real *p, *nx, *ny, *nz, *vn, *vx, *vy, *vz, *K, *ms, *speed, *press, *h[4];
    ct_real *fx, *fy, *fz, *fn, *energy, *dissip, *ftx, *fty, *ftz, *fdis, *mu;
    ct_real *fel, *ktan, *ptx, *pty, *ptz;
    int32_t *flag7;
    ct_idx *s[4];
    ct_real *fxn, *fyn, *fzn;
    ct_assemble_ws ws;
    int ws_ready;
} pdata;

/* Synthetic edge-edge pairs (rc as above). */
typedef struct ctb_kb_edges {
    int valid, rc;
    int64_t npair;
    ct_idx *ea, *eb, *e1, *e2;
    ct_real *x, *y, *z, *o[14];
    uint8_t *flag;
    ct_edge_geo geo;
} ctb_kb_edges;

/* The configuration of the data (seed, binding, team). */
void ctb_kb_data_init(const ctb_search_config *c);

/* The first `want` pairs of the plates case (triangles when tri), in node
 * order; kept until the next call with another (tri, want). */
pdata *ctb_kb_pairs(int tri, int64_t want);

/* The force and assembly inputs of d (once); returns d->rc. */
int ctb_kb_force_prepare(pdata *d);

/* n edge-edge pairs; kept until the next call with another n. */
const ctb_kb_edges *ctb_kb_edges_get(int64_t n);

/* Free all the data. */
void ctb_kb_data_free(void);

#endif /* BENCH_KERNELS_DATA_H */
