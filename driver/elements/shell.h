/*
 * shell.h -- thin elastic shell for the driver (prefix ctd_shell_).
 *
 * Mechanics (see shell.c for the formulas and their derivation):
 *  - membrane: constant-strain triangles, St Venant-Kirchhoff in plane
 *    stress on the Green strain of the triangle (large rotations exact);
 *  - bending: the "discrete shells" hinge energy on every interior edge,
 *    E_h = k_h (theta - theta0)^2 with k_h = w (D / 2) |e0|^2 / (A_A + A_B)
 *    (reference edge length and areas), D = E t^3 / (12 (1 - nu^2));
 *    theta is the signed dihedral angle between the two triangles.
 * Quadrangles (n4 != n3, the Radioss convention) are split both ways,
 * (n1 n2 n3) (n1 n3 n4) and (n1 n2 n4) (n2 n3 n4), each triangle weighted
 * 1/2 (w = product of the two triangles' weights): one split alone couples
 * bending and twist (a strip bent along a mesh axis is ~1.5 times too soft);
 * averaging both removes the coupling. The contact keeps seeing the quads.
 * Each input element has its own thickness t (the contact gap uses t / 2).
 *
 * A hinge's force on the nodes of each of its triangles lies along that
 * triangle's normal (it turns the triangle about the edge), so the forces
 * are computed in three passes: every triangle's unit normal; every
 * hinge's angle and its coefficient -2 k_h (theta - theta0); every
 * triangle's membrane force plus the coefficients of the hinges on its
 * three edges along its normal (shell_forces.c has the formula).
 * Forces are deterministic for any thread count: each triangle writes its
 * nodal forces into private slots, then a node-parallel pass sums each
 * node's slots in increasing slot order (a node->slot CSR map, as in
 * LULESH). Nothing is allocated after ctd_shell_init.
 */
#ifndef CTD_SHELL_H
#define CTD_SHELL_H

#include "contact.h"

/* Triangles or hinges per block of the forces' loops; each block sums its
 * energy, and the blocks' sums are added in block order, so the energy
 * does not depend on the thread count. */
#define CTD_SHELL_BLOCK 512

typedef struct ctd_shell {
    ct_idx nnode;    /* nodes of the model (arrays passed in are this long) */
    ct_idx nelem;    /* input elements (quads and triangles) */
    ct_idx ntri;     /* triangles after splitting quads */
    ct_idx nhinge;   /* interior edges shared by exactly two triangles */
    double E, nu, rho;

    /* Triangles: nodes, source element, reference data. */
    ct_idx *t1, *t2, *t3;
    ct_idx *tri_elem;       /* input element each triangle comes from */
    ct_real *tri_w;         /* weight: 1, or 1/2 for the four triangles of a quad */
    ct_real *tri_vol;       /* A0 t (reference area times thickness) */
    ct_real *b11, *b12, *b22; /* inverse of the reference edge matrix, local frame */
    ct_real *elem_t;        /* thickness per input element */

    /* Hinges: edge h1-h2, opposite nodes h3 (triangle A) and h4 (triangle B).
     * An edge between two quads has four hinges (each of the two triangles
     * of one quad holding the edge against each of the other's): those
     * come first, as ngroup groups of four, hinge j of group g being
     * h = j ngroup + g, its triangles A = hta[g] for j = 0, 1 and
     * hta[2 ngroup + g] for j = 2, 3, B = htb[g] for j = 0, 2 and
     * htb[ngroup + g] for j = 1, 3 (so the forces' loop over the groups reads
     * the edge once for four hinges, and each of its four triangles once
     * for two); the other hinges follow, from 4 ngroup on. */
    ct_idx *h1, *h2, *h3, *h4;
    ct_idx ngroup;
    ct_real *theta0; /* rest dihedral angle */
    ct_real *hk;     /* k_h = (D / 2) |e0|^2 / (A_A + A_B) */
    /* The hinge's triangles A and B, and the signs (+1 or -1) that turn
     * their unit normals into the hinge's nA = e x (h3 - h1) / |.| and
     * nB = (h4 - h1) x e / |.|, e = h2 - h1. */
    ct_idx *hta, *htb;
    ct_real *hsa, *hsb;

    /* Per-cycle scratch: each triangle's unit normal and 1 / (2 A); each
     * hinge's coefficient for its side A (hc[h]) and side B (hc[nhinge +
     * h]), the entry 2 nhinge always 0; and for each triangle edge k (corner k to
     * corner k + 1) the two entries of hc of the hinges on it (te[(2 k +
     * j) ntri + t], 2 nhinge when there are fewer). */
    ct_real *nx, *ny, *nz, *il;
    ct_real *hc;
    ct_idx *te;

    /* Private force slots: 3 per triangle, corner-major (slot c ntri + t
     * is corner c of triangle t). */
    ct_idx nslot;
    ct_real *sx, *sy, *sz;
    /* The set's nodes (those of its triangles), increasing: the arrays
     * below are per set node, not per model node, so that a model of many
     * shell parts holds and scans each part's nodes only. */
    ct_idx nsnode;
    ct_idx *snode;
    ct_idx *slot_off, *slot; /* set node -> its slots, increasing (CSR, nsnode + 1) */
    /* Energy per block of CTD_SHELL_BLOCK triangles, then of hinge groups,
     * then of the other hinges (ctd_shell_blocks). */
    double *e_blk;

    /* Results of the last ctd_shell_forces call. */
    double e_membrane, e_bending;

    /* Stability data from the reference configuration. */
    ct_real *node_k; /* per set node: nodal stiffness K_a (dt_a = sqrt(2 m_a / K_a)) */
    ct_real *node_m; /* per set node: lumped nodal mass */
    double dt_stable;
} ctd_shell;

/*
 * Build the shell from reference positions x, y, z (nnode each) and nelem
 * elements n1..n4 (n4 NULL: all triangles; n4[e] == n3[e]: a triangle).
 * thick: thickness per element, or NULL to use t for all. Material E > 0,
 * 0 <= nu < 0.5, rho > 0. Returns CT_OK, CT_ERR_ARG (bad argument),
 * CT_ERR_RANGE (node index), CT_ERR_DUPNODE, CT_ERR_DEGENERATE (zero area,
 * or thickness <= 0), CT_ERR_NONFINITE or CT_ERR_NOMEM. Edges shared by
 * more than two triangles carry no hinge.
 */
int ctd_shell_init(ctd_shell *s, ct_idx nnode, const ct_real *x, const ct_real *y,
                   const ct_real *z, ct_idx nelem, const ct_idx *n1, const ct_idx *n2,
                   const ct_idx *n3, const ct_idx *n4, const ct_real *thick, double E,
                   double nu, double rho, double t);
void ctd_shell_destroy(ctd_shell *s);

/*
 * Internal forces at the current positions: ADDED to fx, fy, fz (nodes not
 * in the shell are untouched). *energy (may be NULL) receives the internal
 * energy, membrane + bending (also kept in s->e_membrane, s->e_bending).
 * Returns CT_OK, CT_ERR_ARG or CT_ERR_NONFINITE (a triangle collapsed to
 * zero area or a non-finite force; the forces are then not added).
 */
int ctd_shell_forces(ctd_shell *s, const ct_real *x, const ct_real *y, const ct_real *z,
                     ct_real *fx, ct_real *fy, ct_real *fz, double *energy);

/* Add the lumped masses rho t A / 3 per node and triangle to m (nnode). */
void ctd_shell_masses(const ctd_shell *s, ct_real *m);

/* Stable central-difference time step of the shell alone (no safety
 * factor): 2 / omega_max with omega_max^2 bounded by a block Gershgorin sum
 * of the reference-configuration stiffness (membrane + bending). */
double ctd_shell_dt(const ctd_shell *s);

/* Add the nodal stiffness K_a to k (nnode), the element part of the nodal
 * time step dt = sqrt(2 m / (K_elem + K_contact)) of DESIGN.md section 7. */
void ctd_shell_node_stiffness(const ctd_shell *s, ct_real *k);

/* The rest angles theta0 of the hinges from reference positions, by the
 * same arithmetic as the forces (a shell at rest has theta = theta0 to the
 * bit). For ctd_shell_init; CT_ERR_DEGENERATE when an angle is not finite. */
/* The blocks of the forces' loops: of triangles, of hinge groups, of
 * the other hinges. */
static inline void ctd_shell_blocks(const ctd_shell *s, ct_idx *nbt, ct_idx *nbg, ct_idx *nbr)
{
    const ct_idx B = CTD_SHELL_BLOCK, nr = s->nhinge - 4 * s->ngroup;
    *nbt = (s->ntri + B - 1) / B;
    *nbg = (s->ngroup + B - 1) / B;
    *nbr = (nr + B - 1) / B;
}

int ctd_shell_rest_angles(ctd_shell *s, const ct_real *x, const ct_real *y, const ct_real *z);

/* The vectorisable atan2 of the forces (shell_forces.c); exposed for tests. */
ct_real ctd_shell_atan2(ct_real y, ct_real x);

/* Signed dihedral angle of the hinge with edge p[0]-p[1] and opposite
 * vertices p[2] (triangle A) and p[3] (triangle B), and its gradient g
 * (d theta / d p[a], 4 x 3). Zero for a flat pair; exposed for tests. */
ct_real ctd_shell_dihedral(const ct_real p[4][3], ct_real g[4][3]);

#endif /* CTD_SHELL_H */
