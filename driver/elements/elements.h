/*
 * elements.h -- the structural elements of the explicit driver (prefix
 * ctd_): truss and spring (linear axial), the 8-node elastic brick (total
 * Lagrangian St Venant-Kirchhoff), and the rigid body. DESIGN.md section 9.
 *
 * Conventions shared by every element set:
 *  - Nodal data are the solver's structure-of-arrays (x, y, z, fx, ...)
 *    indexed by global node number; an element set copies its connectivity.
 *  - The force functions ADD the forces the elements exert on the nodes
 *    (minus the internal force vector) into fx, fy, fz, so element sets,
 *    contact and external loads accumulate into one array; the solver then
 *    takes a = f / m.
 *  - Determinism: each element writes its nodal forces into private slots
 *    (slot a of element e at a * nelem + e); a node-parallel pass then sums
 *    each node's slots through a node->slot CSR map in increasing slot
 *    order (ctd_gather). No atomics, no per-thread buffers: results are
 *    bit-identical for any OMP_NUM_THREADS. Energies are summed serially in
 *    element order.
 *  - Nothing is allocated by the per-cycle functions (forces, time steps,
 *    rigid-body accumulation and advance); every scratch array is sized at
 *    init.
 *  - Errors are negative CT_ERR_* codes; the element's index goes into the
 *    optional ct_diag.
 */
#ifndef CTD_ELEMENTS_H
#define CTD_ELEMENTS_H

#include <stdint.h>

#include "contact.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Deterministic gather of per-element slots ------------------------- */

/*
 * Element e has nper local nodes; local node a is conn[a][e * estride]
 * (so an interleaved hex8 array is conn[a] = hex8 + a with estride 8, and
 * separate n1, n2 arrays are conn = {n1, n2} with estride 1). Slot a of
 * element e is a * nelem + e. The touched nodes are listed in increasing
 * order, node[t] owning slots slot[off[t] .. off[t+1]-1] in increasing
 * order.
 */
typedef struct ctd_gather {
    ct_idx nelem, nnode, ntouched;
    int nper;
    ct_idx *node;  /* ntouched touched nodes, increasing */
    int64_t *off;  /* ntouched + 1 */
    int64_t *slot; /* nper * nelem slot indices */
} ctd_gather;

/* Build the map (once per connectivity). CT_ERR_RANGE for a node outside
 * [0, nnode) (diag->index: the element). */
int ctd_gather_build(ctd_gather *g, ct_idx nelem, int nper, const ct_idx *const conn[],
                     int64_t estride, ct_idx nnode, ct_diag *diag);
void ctd_gather_destroy(ctd_gather *g);

/* f[node] += sum of its slots s[slot], for each component whose arrays are
 * not NULL (sy, sz / fy, fz may be NULL for a scalar gather). In parallel
 * over nodes; must be called outside a parallel region. */
void ctd_gather_add(const ctd_gather *g, const ct_real *CT_RESTRICT sx,
                    const ct_real *CT_RESTRICT sy, const ct_real *CT_RESTRICT sz,
                    ct_real *CT_RESTRICT fx, ct_real *CT_RESTRICT fy,
                    ct_real *CT_RESTRICT fz);

/* Loops over fewer items than this (elements or nodes; a brick counts as
 * 32, a brick's step as 8) run on one thread: a parallel region costs more
 * than they do. The result is the same either way. */
#define CTD_PAR_MIN 2048

/* The step returned by the time-step functions of an empty set. */
#define CTD_DT_NONE ((ct_real)1e30)

/* ---- Truss and spring (linear axial) ----------------------------------- */

/*
 * Two-node axial elements. A truss has section A, modulus E and density
 * rho: stiffness k = E A / L0, mass rho A L0 (half on each node), wave
 * speed c = sqrt(E / rho), stable step L / c with L the current length. A
 * spring has a stiffness k and no mass; its stable step is sqrt(m_min / k)
 * with m_min the smaller of its two (assembled, lumped) nodal masses --
 * exact for a uniform chain of springs, conservative for two masses
 * (whose limit is sqrt(2 m / k)). Both carry the axial force
 * N = k (L - L0) (tension positive) along the current axis, and the
 * energy k (L - L0)^2 / 2; large rotations are exact.
 */
typedef struct ctd_truss {
    ct_idx n, nnode;
    ct_idx *n1, *n2;
    ct_real *L0;      /* reference lengths */
    ct_real *k;       /* axial stiffness */
    ct_real *mass;    /* element mass (0 for springs) */
    ct_real *c;       /* wave speed (0 for springs) */
    ct_real *eint;    /* internal energy of each element, last force call */
    ct_real *s[3];    /* private force slots, 2 n each */
    ctd_gather g;
} ctd_truss;

/* n elements (n1[e], n2[e]) between nnode nodes at reference positions
 * x, y, z (L0 from them; CT_ERR_DEGENERATE for a zero length, CT_ERR_RANGE
 * for a bad node, CT_ERR_DUPNODE for n1 == n2). Properties are zero until
 * set below. */
int ctd_truss_init(ctd_truss *t, ct_idx n, const ct_idx *n1, const ct_idx *n2, ct_idx nnode,
                   const ct_real *x, const ct_real *y, const ct_real *z, ct_diag *diag);
void ctd_truss_destroy(ctd_truss *t);

/* Elements [first, first + count) become trusses (A, E, rho > 0) or
 * springs (k > 0). CT_ERR_ARG for a bad range or value. */
int ctd_truss_set_truss(ctd_truss *t, ct_idx first, ct_idx count, ct_real A, ct_real E,
                        ct_real rho);
int ctd_truss_set_spring(ctd_truss *t, ct_idx first, ct_idx count, ct_real k);

/* m[node] += half the element mass (serial, element order). */
void ctd_truss_mass(const ctd_truss *t, ct_real *m);

/* Add the element forces at positions x, y, z into fx, fy, fz; store each
 * element's energy in t->eint. CT_ERR_DEGENERATE when an element's current
 * length is zero (diag->index: the element; forces then untouched),
 * CT_ERR_NONFINITE for a NaN/Inf length. */
int ctd_truss_forces(ctd_truss *t, const ct_real *CT_RESTRICT x, const ct_real *CT_RESTRICT y,
                     const ct_real *CT_RESTRICT z, ct_real *CT_RESTRICT fx,
                     ct_real *CT_RESTRICT fy, ct_real *CT_RESTRICT fz, ct_diag *diag);

/* Sum of t->eint (serial, element order). */
double ctd_truss_energy(const ctd_truss *t);

/* Smallest stable step over the elements (m: assembled nodal masses, used
 * by springs); *imin (may be NULL) receives the element (-1 when empty). */
ct_real ctd_truss_dt(const ctd_truss *t, const ct_real *x, const ct_real *y, const ct_real *z,
                     const ct_real *m, ct_idx *imin);

/* ---- 8-node brick, total Lagrangian St Venant-Kirchhoff ----------------- */

/*
 * Node order as ctd_block's hex8: the bottom face counter-clockwise seen
 * from +z, then the top face in the same order (nodes 4-7 above 0-3).
 * Reference coordinates are copied at init. Per Gauss point (full 2 x 2 x 2
 * integration: no hourglass modes, no hourglass control):
 *   H = du/dX (u = x - X), F = I + H, E = (H + H^T + H^T H) / 2,
 *   S = lambda tr(E) I + 2 mu E, P = F S,
 *   f_int[a] = sum_g P grad0 N_a det J0_g,  W = lambda/2 tr(E)^2 + mu E:E.
 * Objective (exactly zero strain under any rigid rotation) and valid for
 * large rotations; the material is linear in Green strain, so only
 * moderate strains are meaningful (it softens in strong compression).
 *
 * Stable step: L / c_b with L = V / A_max (current volume over the largest
 * current face area, the face area being half the norm of the diagonals'
 * cross product) and c_b = sqrt(max(lambda + 2 mu, 3 lambda + 2 mu) / rho).
 * The usual dilatational speed c = sqrt((lambda + 2 mu) / rho) is NOT safe
 * for this fully integrated element: a free cube of side h has
 * omega_max^2 = 4 max(lambda + 2 mu, 3 lambda + 2 mu) / (rho h^2) (its
 * uniform-dilatation mode, measured by power iteration in the tests), so
 * h / c exceeds the limit by 1 / 0.775 at nu = 0.25 and 1 / 0.616 at
 * nu = 0.45; in a 4 x 4 x 4 block the limit is 0.976 h / c (nu = 0.25)
 * and 0.865 h / c (nu = 0.45), below a 0.9 safety factor. With c_b the
 * step of a cube is exactly its limit 2 / omega_max; for nu = 0 the two
 * speeds agree. The solver still applies its safety factor.
 */
/* Elements per block of the brick forces' vector loops (the lanes of two
 * 256-bit vectors in double precision, one in single). */
#define CTD_BRICK_LANES 8

typedef struct ctd_brick {
    ct_idx n, nnode;
    ct_idx *conn;          /* 8 n, interleaved (element-major) */
    /* Reference positions of all nodes (nnode): the set's copy (in ref),
     * or the caller's arrays (ctd_brick_init_shared; ref NULL). */
    const ct_real *X0, *Y0, *Z0;
    ct_real *ref;
    ct_real lambda, mu, rho;
    ct_real *vol0;         /* reference volumes */
    ct_real *eint;         /* strain energy of each element, last force call */
    ct_real *dte;          /* scratch: each element's stable step */
    /* In blocks of L = CTD_BRICK_LANES elements, entry j of element e at
     * ((e / L) per + j) L + e % L (per: the entries of an element): the
     * reference Jacobian's inverse at Gauss point g (per 72, entry (i, k)
     * at j = 9 g + 3 i + k) and its determinant (per 8, j = g), kept so
     * that the forces need not rebuild them, and the element's nodes (per
     * 8). The forces run the elements of a block in vector lanes. */
    ct_real *jinv, *jdet;
    ct_idx *lconn;
    ct_real dt_last;       /* the set's stable step at the last force call */
    ct_real *s[3];         /* private force slots, 8 n each */
    ctd_gather g;
} ctd_brick;

/* Lame constants from Young's modulus and Poisson's ratio. */
void ctd_lame(ct_real E, ct_real nu, ct_real *lambda, ct_real *mu);

/* n bricks conn[8 e + a] over nnode nodes at reference x, y, z, material
 * (E, nu, rho). CT_ERR_RANGE for a bad node, CT_ERR_DEGENERATE for a
 * non-positive Jacobian at a Gauss point (a tangled or inverted element),
 * CT_ERR_ARG for E <= 0, nu outside (-1, 0.5) or rho <= 0. */
int ctd_brick_init(ctd_brick *b, ct_idx n, const ct_idx *conn, ct_idx nnode, const ct_real *x,
                   const ct_real *y, const ct_real *z, ct_real E, ct_real nu, ct_real rho,
                   ct_diag *diag);

/* The same, borrowing x, y, z as the reference positions instead of
 * copying them: they must stay unchanged while b lives. A model of many
 * brick parts then holds one copy of the nodes, not one per part. */
int ctd_brick_init_shared(ctd_brick *b, ct_idx n, const ct_idx *conn, ct_idx nnode,
                          const ct_real *x, const ct_real *y, const ct_real *z, ct_real E,
                          ct_real nu, ct_real rho, ct_diag *diag);
void ctd_brick_destroy(ctd_brick *b);

/* m[node] += rho V0 / 8 (serial, element order). */
void ctd_brick_mass(const ctd_brick *b, ct_real *m);

/* Add the element forces at positions x, y, z into fx, fy, fz; store each
 * element's strain energy in b->eint. CT_ERR_DEGENERATE when an element is
 * inverted (det F <= 0 at a Gauss point; diag->index: the element; forces
 * then untouched), CT_ERR_NONFINITE for NaN/Inf. */
int ctd_brick_forces(ctd_brick *b, const ct_real *CT_RESTRICT x, const ct_real *CT_RESTRICT y,
                     const ct_real *CT_RESTRICT z, ct_real *CT_RESTRICT fx,
                     ct_real *CT_RESTRICT fy, ct_real *CT_RESTRICT fz, ct_diag *diag);

/* Sum of b->eint (serial, element order). */
double ctd_brick_energy(const ctd_brick *b);

/* The stable step of ctd_brick_dt at the positions of the last
 * ctd_brick_forces call, which computes it on the way (the solver's: forces
 * and step at the same positions); CTD_DT_NONE before any call. */
ct_real ctd_brick_dt_last(const ctd_brick *b);

/* Current volume of element e (exact for the trilinear map: 2 x 2 x 2
 * Gauss of det J). For the contact stiffness B A^2 / V. */
ct_real ctd_brick_volume(const ctd_brick *b, ct_idx e, const ct_real *x, const ct_real *y,
                         const ct_real *z);

/* Smallest stable step over the elements (see above); *imin (may be NULL)
 * receives the element. */
ct_real ctd_brick_dt(const ctd_brick *b, const ct_real *x, const ct_real *y, const ct_real *z,
                     ct_idx *imin);

/* ---- Rigid body ---------------------------------------------------------- */

/*
 * A set of nodes moving rigidly. Mass, centre and inertia tensor come from
 * the nodes' lumped masses and positions; the body frame is the principal
 * frame (Jacobi eigen-decomposition), with principal moments I[0..2] and
 * the nodes' body-frame offsets rb. A principal moment below 1e-12 times
 * the largest (nodes on a line, or one node) gets no rotation about that
 * axis (its inverse is taken as zero).
 *
 * Time integration, matching the solver's central difference (velocities
 * at half steps):
 *   kick:   v_c += dt F / M,  L += dt tau       (L: world angular momentum
 *                                                about the centre)
 *   drift:  x_c += dt v_c; the rotation is advanced torque-free with L
 *           fixed: in the body frame pi = R^T L, the implicit midpoint rule
 *           pi_1 - pi_0 = dt pi_m x (I^-1 pi_m), pi_m = (pi_0 + pi_1) / 2,
 *           solved by fixed-point iteration to round-off, and the body
 *           turns by the Cayley rotation Q = cay(dt w), w = I^-1 pi_m,
 *           for which pi_1 = Q^T pi_0 exactly. The midpoint rule conserves
 *           the quadratic invariants |pi|^2 and the kinetic energy
 *           pi . I^-1 pi / 2 exactly, and Q orthogonal keeps L = R pi: a
 *           torque-free body conserves energy and angular momentum to
 *           round-off. The orientation is a unit quaternion, multiplied by
 *           Cayley's (1, w/2) and normalised every step.
 * ctd_rigid_set_nodes then places the nodes at x_c + R rb and gives them
 * the velocity v_c + omega x (x_i - x_c), omega = R w / dt, the body's
 * angular velocity over the step (the Cayley axis is fixed by Q, so it is
 * the same seen from the start and the end of the step).
 */
typedef struct ctd_rigid {
    ct_idx n;
    ct_idx *node;          /* the nodes (copied) */
    ct_real *rb[3];        /* body-frame offsets of the nodes */
    double mass;
    double I[3];           /* principal moments */
    double Iinv[3];        /* their inverses (0 for a degenerate axis) */
    double xc[3], vc[3];   /* centre (time n) and its velocity (half step) */
    double q[4];           /* orientation: body -> world, (w, x, y, z) */
    double L[3];           /* world angular momentum about the centre */
    double omega[3];       /* world angular velocity of the last step */
    double F[3], tau[3];   /* accumulated force and moment about the centre */
    int iters;             /* fixed-point iterations of the last step */
} ctd_rigid;

/* From nnode-node arrays: the body of the n nodes node[] with masses m and
 * positions x, y, z; its initial velocity and angular momentum from the
 * nodes' velocities vx, vy, vz (may all be NULL: at rest). CT_ERR_ARG for a
 * zero total mass, CT_ERR_RANGE for a bad node. */
int ctd_rigid_init(ctd_rigid *r, ct_idx n, const ct_idx *node, ct_idx nnode, const ct_real *m,
                   const ct_real *x, const ct_real *y, const ct_real *z, const ct_real *vx,
                   const ct_real *vy, const ct_real *vz);
void ctd_rigid_destroy(ctd_rigid *r);

/* Give the body the centre velocity v and the world angular velocity w
 * (L = R I R^T w). */
void ctd_rigid_set_velocity(ctd_rigid *r, const double v[3], const double w[3]);

/* World inertia tensor R diag(I) R^T (row-major 3 x 3) and rotation matrix. */
void ctd_rigid_rotation(const ctd_rigid *r, double R[9]);
void ctd_rigid_inertia_world(const ctd_rigid *r, double J[9]);

/* Zero the accumulated force and moment. */
void ctd_rigid_clear(ctd_rigid *r);

/* Add the nodal forces fx, fy, fz of the body's nodes to F, and their
 * moments about the centre, (x_i - x_c) x f_i, to tau (serial, node
 * order). */
void ctd_rigid_accumulate(ctd_rigid *r, const ct_real *x, const ct_real *y, const ct_real *z,
                          const ct_real *fx, const ct_real *fy, const ct_real *fz);

/* One step: kick with F and tau, then drift (see above). CT_ERR_NOCONV if
 * the midpoint iteration does not converge (|omega| dt far above 1),
 * CT_ERR_NONFINITE for NaN/Inf. */
int ctd_rigid_advance(ctd_rigid *r, double dt);

/* Place the body's nodes and set their velocities (see above). */
void ctd_rigid_set_nodes(const ctd_rigid *r, ct_real *x, ct_real *y, ct_real *z, ct_real *vx,
                         ct_real *vy, ct_real *vz);

/* Kinetic energy M |v_c|^2 / 2 + L . omega_body / 2 with omega from L at the
 * current orientation, and the world linear and angular momentum (about the
 * world origin; either pointer may be NULL). */
double ctd_rigid_kinetic(const ctd_rigid *r);
void ctd_rigid_momentum(const ctd_rigid *r, double p[3], double Lo[3]);

#ifdef __cplusplus
}
#endif

#endif /* CTD_ELEMENTS_H */
