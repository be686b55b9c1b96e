/*
 * brick.c -- the 8-node elastic brick: total Lagrangian St Venant-Kirchhoff
 * with full 2 x 2 x 2 Gauss integration. See elements.h.
 */
#include <stdlib.h>

#include "ct_internal.h"
#include "elements.h"

/* Entry j (of per) of element e in the lane layout: blocks of
 * CTD_BRICK_LANES elements, each holding entry j of its elements side by
 * side. */
#define CTI_LANE(e, per, j)                                                                     \
    (((size_t)(e) / CTD_BRICK_LANES * (size_t)(per) + (size_t)(j)) * CTD_BRICK_LANES +         \
     (size_t)(e) % CTD_BRICK_LANES)

/* Natural coordinates of the nodes (hex8 order of ctd_block). */
static const int XI[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
static const int ETA[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
static const int ZETA[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

/* The six faces, each counter-clockwise seen from outside. */
static const int FACE[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                               {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

/* The shape derivatives at the Gauss points by edges. Along natural axis
 * k, the eight nodes pair into four edges EDGE[k][m] = {minus end, plus
 * end}; both ends share the other two signs (s1, s2): m & 1 gives s1 (+
 * when set), m & 2 gives s2. The derivative along k of node a's shape
 * function at Gauss point g (at the signs of node g times G = 1 / sqrt 3)
 * is the end's sign times W[k][g][m] = (1 + G s1 t1) (1 + G s2 t2) / 8,
 * t1, t2 the point's signs on the other two axes. So a gradient along k is
 * sum_m (u_plus - u_minus) W[k][g][m] (4 terms, not 8), and the nodal
 * forces sum over the points per edge first. The table holds constant
 * expressions (the unrolled loop folds them). */
#define CTI_GP 0.57735026918962576451
#define CTI_SX(a) ((a) == 1 || (a) == 2 || (a) == 5 || (a) == 6 ? 1 : -1)
#define CTI_SY(a) ((a) == 2 || (a) == 3 || (a) == 6 || (a) == 7 ? 1 : -1)
#define CTI_SZ(a) ((a) >= 4 ? 1 : -1)
#define CTI_MS1(m) ((m)&1 ? 1 : -1)
#define CTI_MS2(m) ((m)&2 ? 1 : -1)
#define CTI_W(t1, t2, m)                                                                        \
    ((ct_real)((1 + CTI_GP * CTI_MS1(m) * (t1)) * (1 + CTI_GP * CTI_MS2(m) * (t2)) / 8))
#define CTI_W4(t1, t2) {CTI_W(t1, t2, 0), CTI_W(t1, t2, 1), CTI_W(t1, t2, 2), CTI_W(t1, t2, 3)}
#define CTI_WX(g) CTI_W4(CTI_SY(g), CTI_SZ(g))
#define CTI_WY(g) CTI_W4(CTI_SX(g), CTI_SZ(g))
#define CTI_WZ(g) CTI_W4(CTI_SX(g), CTI_SY(g))
#define CTI_W8(F) {F(0), F(1), F(2), F(3), F(4), F(5), F(6), F(7)}
static const ct_real CTI_EW[3][8][4] = {CTI_W8(CTI_WX), CTI_W8(CTI_WY), CTI_W8(CTI_WZ)};
static const int CTI_EDGE[3][4][2] = {{{0, 1}, {3, 2}, {4, 5}, {7, 6}},
                                      {{0, 3}, {1, 2}, {4, 7}, {5, 6}},
                                      {{0, 4}, {1, 5}, {3, 7}, {2, 6}}};

/* dN[g][a][k]: derivative of shape function a along natural axis k at
 * Gauss point g (points at +-1/sqrt(3), weights 1). */
typedef ct_real cti_hex_dn[8][8][3];

static void hex_dn(cti_hex_dn dN)
{
    const double gp = 1.0 / sqrt(3.0);
    for (int g = 0; g < 8; g++) {
        double xi = gp * XI[g], eta = gp * ETA[g], zeta = gp * ZETA[g];
        for (int a = 0; a < 8; a++) {
            double p = 1 + xi * XI[a], q = 1 + eta * ETA[a], r = 1 + zeta * ZETA[a];
            dN[g][a][0] = (ct_real)(XI[a] * q * r / 8);
            dN[g][a][1] = (ct_real)(ETA[a] * p * r / 8);
            dN[g][a][2] = (ct_real)(ZETA[a] * p * q / 8);
        }
    }
}

/* J[i][k] = sum_a X[a][i] dN[a][k]; returns det J, inv = J^-1. */
static inline ct_real jac_inv(const ct_real X[8][3], const ct_real dN[8][3], ct_real inv[3][3])
{
    ct_real J[3][3] = {{0}};
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                J[i][k] += X[a][i] * dN[a][k];
    ct_real c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1];
    ct_real c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2];
    ct_real c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
    ct_real det = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
    if (inv) {
        ct_real id = det != 0 ? 1 / det : 0;
        inv[0][0] = c00 * id;
        inv[1][0] = c01 * id;
        inv[2][0] = c02 * id;
        inv[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * id;
        inv[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * id;
        inv[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * id;
        inv[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * id;
        inv[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * id;
        inv[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * id;
    }
    return det;
}


static void load(const ct_idx *conn, const ct_real *x, const ct_real *y, const ct_real *z,
                 ct_real P[8][3])
{
    for (int a = 0; a < 8; a++) {
        ct_idx v = conn[a];
        P[a][0] = x[v];
        P[a][1] = y[v];
        P[a][2] = z[v];
    }
}

void ctd_lame(ct_real E, ct_real nu, ct_real *lambda, ct_real *mu)
{
    *lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    *mu = E / (2 * (1 + nu));
}

void ctd_brick_destroy(ctd_brick *b)
{
    if (!b)
        return;
    ct_free(b->conn);
    ct_free(b->ref);
    ct_free(b->vol0);
    ct_free(b->eint);
    ct_free(b->dte);
    ct_free(b->jinv);
    ct_free(b->jdet);
    ct_free(b->lconn);
    for (int d = 0; d < 3; d++)
        ct_free(b->s[d]);
    ctd_gather_destroy(&b->g);
    memset(b, 0, sizeof *b);
}

static int brick_init(ctd_brick *b, ct_idx n, const ct_idx *conn, ct_idx nnode,
                      const ct_real *x, const ct_real *y, const ct_real *z, ct_real E,
                      ct_real nu, ct_real rho, int shared, ct_diag *diag)
{
    if (!b || n < 0 || nnode < 0 || (n > 0 && (!conn || !x || !y || !z)))
        return cti_fail(diag, CT_ERR_ARG, -1, "Bad arguments to ctd_brick_init.");
    if (!(E > 0) || !(nu > -1 && nu < 0.5) || !(rho > 0))
        return cti_fail(diag, CT_ERR_ARG, -1,
                        "Brick material needs E > 0, -1 < nu < 0.5 and rho > 0.");
    if (n > (INT32_MAX - 64) / 8)
        return cti_fail(diag, CT_ERR_TOOBIG, -1, "Too many bricks (%d).", (int)n);
    memset(b, 0, sizeof *b);
    const size_t ne = (size_t)n + 1, nn = (size_t)nnode + 1;
    b->conn = ct_calloc(8 * ne, sizeof *b->conn);
    if (!shared)
        b->ref = ct_calloc(3 * nn, sizeof *b->ref);
    b->vol0 = ct_calloc(ne, sizeof *b->vol0);
    b->eint = ct_calloc(ne, sizeof *b->eint);
    b->dte = ct_calloc(ne, sizeof *b->dte);
    /* The lane copies, padded to whole blocks. */
    const size_t nl = ((size_t)n + CTD_BRICK_LANES - 1) / CTD_BRICK_LANES * CTD_BRICK_LANES + 1;
    b->jinv = ct_calloc(72 * nl, sizeof *b->jinv);
    b->jdet = ct_calloc(8 * nl, sizeof *b->jdet);
    b->lconn = ct_calloc(8 * nl, sizeof *b->lconn);
    int ok = b->conn && (shared || b->ref) && b->vol0 && b->eint && b->dte && b->jinv &&
             b->jdet && b->lconn;
    for (int d = 0; d < 3; d++) {
        b->s[d] = ct_calloc(8 * ne, sizeof *b->s[d]);
        ok = ok && b->s[d];
    }
    if (!ok) {
        ctd_brick_destroy(b);
        return cti_fail(diag, CT_ERR_NOMEM, -1, "Out of memory for %d bricks.", (int)n);
    }
    b->n = n;
    b->nnode = nnode;
    b->dt_last = CTD_DT_NONE;
    ctd_lame(E, nu, &b->lambda, &b->mu);
    b->rho = rho;
    if (shared) {
        b->X0 = x;
        b->Y0 = y;
        b->Z0 = z;
    } else {
        ct_real *X0 = b->ref, *Y0 = b->ref + nn, *Z0 = b->ref + 2 * nn;
        if (nnode > 0) {
            memcpy(X0, x, (size_t)nnode * sizeof *x);
            memcpy(Y0, y, (size_t)nnode * sizeof *y);
            memcpy(Z0, z, (size_t)nnode * sizeof *z);
        }
        b->X0 = X0;
        b->Y0 = Y0;
        b->Z0 = Z0;
    }
    memcpy(b->conn, conn, (size_t)n * 8 * sizeof *conn);
    /* The lane copy of the nodes; the lanes past the last element keep
     * node 0 and a unit Jacobian (their results are not stored). */
    for (size_t e = 0; e + 1 < nl; e++)
        for (int a = 0; a < 8; a++) {
            b->lconn[CTI_LANE(e, 8, a)] = e < (size_t)n ? conn[8 * e + (size_t)a] : 0;
            b->jdet[CTI_LANE(e, 8, a)] = 1; /* a = g here: replaced below */
            for (int k = 0; k < 3; k++)
                b->jinv[CTI_LANE(e, 72, 9 * a + 4 * k)] = 1;
        }
    const ct_idx *cs[8];
    for (int a = 0; a < 8; a++)
        cs[a] = b->conn + a;
    int rc = ctd_gather_build(&b->g, n, 8, cs, 8, nnode, diag);
    if (rc != CT_OK) {
        ctd_brick_destroy(b);
        return rc;
    }
    cti_hex_dn dN;
    hex_dn(dN);
    for (ct_idx e = 0; e < n; e++) {
        ct_real X[8][3];
        load(b->conn + 8 * (int64_t)e, x, y, z, X);
        ct_real v = 0;
        for (int g = 0; g < 8; g++) {
            ct_real inv[3][3];
            ct_real det = jac_inv(X, dN[g], inv);
            b->jdet[CTI_LANE(e, 8, g)] = det;
            for (int k = 0; k < 9; k++)
                b->jinv[CTI_LANE(e, 72, 9 * g + k)] = inv[k / 3][k % 3];
            if (!(det > 0)) {
                ctd_brick_destroy(b);
                return cti_fail(diag, CT_ERR_DEGENERATE, e,
                                "Brick %d has a non-positive Jacobian at Gauss point %d "
                                "(tangled, inverted or misnumbered).",
                                (int)e, g);
            }
            v += det;
        }
        b->vol0[e] = v;
    }
    return CT_OK;
}

int ctd_brick_init(ctd_brick *b, ct_idx n, const ct_idx *conn, ct_idx nnode, const ct_real *x,
                   const ct_real *y, const ct_real *z, ct_real E, ct_real nu, ct_real rho,
                   ct_diag *diag)
{
    return brick_init(b, n, conn, nnode, x, y, z, E, nu, rho, 0, diag);
}

int ctd_brick_init_shared(ctd_brick *b, ct_idx n, const ct_idx *conn, ct_idx nnode,
                          const ct_real *x, const ct_real *y, const ct_real *z, ct_real E,
                          ct_real nu, ct_real rho, ct_diag *diag)
{
    return brick_init(b, n, conn, nnode, x, y, z, E, nu, rho, 1, diag);
}

void ctd_brick_mass(const ctd_brick *b, ct_real *m)
{
    for (ct_idx e = 0; e < b->n; e++)
        for (int a = 0; a < 8; a++)
            m[b->conn[8 * (int64_t)e + a]] += b->rho * b->vol0[e] / 8;
}

/* Gauss point g of the CTD_BRICK_LANES elements of a block, in vector
 * lanes: from the edge differences D, the reference Jacobian's inverse jb
 * and determinant db (the block's lane layout), add the point's edge sums
 * to R, its energy to W, its volume det0 det F to V, and clear ok where
 * det F <= 0. */
static inline void cti_brick_gauss_point(int g, const ct_real *CT_RESTRICT jb,
                                         const ct_real *CT_RESTRICT db,
                                         ct_real (*CT_RESTRICT D)[4][3][CTD_BRICK_LANES],
                                         ct_real (*CT_RESTRICT R)[4][3][CTD_BRICK_LANES],
                                         ct_real *CT_RESTRICT W, ct_real *CT_RESTRICT V,
                                         ct_real *CT_RESTRICT ok, ct_real lambda, ct_real mu)
{
    enum { L = CTD_BRICK_LANES };
#pragma omp simd
    for (int l = 0; l < L; l++) {
        const ct_real d0 = db[g * L + l];
        ct_real iv[3][3], Hn[3][3], H[3][3], F[3][3], Es[3][3], S[3][3], P[3][3], Q[3][3];
#pragma GCC unroll 16
        for (int k = 0; k < 9; k++)
            iv[k / 3][k % 3] = jb[(9 * g + k) * L + l];
#pragma GCC unroll 16
        for (int i = 0; i < 3; i++)
#pragma GCC unroll 16
            for (int k = 0; k < 3; k++)
                Hn[i][k] = D[k][0][i][l] * CTI_EW[k][g][0] + D[k][1][i][l] * CTI_EW[k][g][1] +
                           D[k][2][i][l] * CTI_EW[k][g][2] + D[k][3][i][l] * CTI_EW[k][g][3];
#pragma GCC unroll 16
        for (int i = 0; i < 3; i++)
#pragma GCC unroll 16
            for (int j = 0; j < 3; j++) {
                H[i][j] = Hn[i][0] * iv[0][j] + Hn[i][1] * iv[1][j] + Hn[i][2] * iv[2][j];
                F[i][j] = H[i][j] + (i == j);
            }
        ct_real dF = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
                     F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                     F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
        ok[l] = dF > 0 ? ok[l] : 0;
        V[l] += d0 * dF;
#pragma GCC unroll 16
        for (int i = 0; i < 3; i++)
#pragma GCC unroll 16
            for (int j = 0; j < 3; j++)
                Es[i][j] = (H[i][j] + H[j][i] + H[0][i] * H[0][j] + H[1][i] * H[1][j] +
                            H[2][i] * H[2][j]) / 2;
        ct_real tr = Es[0][0] + Es[1][1] + Es[2][2];
        ct_real ee = 0;
#pragma GCC unroll 16
        for (int i = 0; i < 3; i++)
#pragma GCC unroll 16
            for (int j = 0; j < 3; j++) {
                S[i][j] = 2 * mu * Es[i][j] + (i == j ? lambda * tr : 0);
                ee += Es[i][j] * Es[i][j];
            }
#pragma GCC unroll 16
        for (int i = 0; i < 3; i++)
#pragma GCC unroll 16
            for (int j = 0; j < 3; j++)
                P[i][j] = F[i][0] * S[0][j] + F[i][1] * S[1][j] + F[i][2] * S[2][j];
#pragma GCC unroll 16
        for (int i = 0; i < 3; i++)
#pragma GCC unroll 16
            for (int k = 0; k < 3; k++)
                Q[i][k] = d0 * (P[i][0] * iv[k][0] + P[i][1] * iv[k][1] + P[i][2] * iv[k][2]);
#pragma GCC unroll 16
        for (int k = 0; k < 3; k++)
#pragma GCC unroll 16
            for (int m = 0; m < 4; m++)
#pragma GCC unroll 16
                for (int i = 0; i < 3; i++)
                    R[k][m][i][l] += Q[i][k] * CTI_EW[k][g][m];
        W[l] += d0 * (lambda / 2 * tr * tr + mu * ee);
    }
}

/*
 * Per element and Gauss point g, with the reference Jacobian's inverse
 * J0^-1 and determinant det0 kept from the set-up (b->jinv, b->jdet): the
 * displacement gradient H = (sum_a u_a dN_a^T) J0^-1, its natural-axis
 * part from the edge differences (CTI_EW; the shape gradients
 * G_a = J0^-T dN_a are never formed), F = I + H, the Green strain
 * E = (H + H^T + H^T H) / 2, S = lambda tr(E) I + 2 mu E, P = F S, and the
 * nodal forces -det0 P G_a = -Q dN_a with Q = det0 P J0^-T. The element's
 * current volume sum_g det0 det F and its largest face area give its
 * stable step (ctd_brick_dt's, at no extra pass over the elements).
 */
int ctd_brick_forces(ctd_brick *b, const ct_real *CT_RESTRICT x, const ct_real *CT_RESTRICT y,
                     const ct_real *CT_RESTRICT z, ct_real *CT_RESTRICT fx,
                     ct_real *CT_RESTRICT fy, ct_real *CT_RESTRICT fz, ct_diag *diag)
{
    if (!b || (b->n > 0 && (!x || !y || !z || !fx || !fy || !fz)))
        return CT_ERR_ARG;
    const ct_idx n = b->n;
    const size_t nz = (size_t)n;
    const ct_real *CT_RESTRICT X0 = b->X0, *CT_RESTRICT Y0 = b->Y0, *CT_RESTRICT Z0 = b->Z0;
    const ct_real *CT_RESTRICT jinv = b->jinv, *CT_RESTRICT jdet = b->jdet;
    const ct_real lambda = b->lambda, mu = b->mu;
    const ct_real mod = CTI_MAX(lambda + 2 * mu, 3 * lambda + 2 * mu);
    const ct_real cw = CTI_SQRT(mod / b->rho);
    ct_real *CT_RESTRICT sx = b->s[0], *CT_RESTRICT sy = b->s[1], *CT_RESTRICT sz = b->s[2];
    ct_real *CT_RESTRICT eint = b->eint, *CT_RESTRICT dte = b->dte;
    const ct_idx nblk = (n + CTD_BRICK_LANES - 1) / CTD_BRICK_LANES;
    ct_idx bad = 0;
    ct_real best = CTD_DT_NONE;
#pragma omp parallel for schedule(static) reduction(max : bad) reduction(min : best) \
    if (n > CTD_PAR_MIN / 32)
    for (ct_idx bk = 0; bk < nblk; bk++) {
        enum { L = CTD_BRICK_LANES };
        const ct_idx *CT_RESTRICT lc = b->lconn + (size_t)bk * 8 * L;
        const ct_real *CT_RESTRICT jb = jinv + (size_t)bk * 72 * L;
        const ct_real *CT_RESTRICT db = jdet + (size_t)bk * 8 * L;
        _Alignas(64) ct_real p[8][3][L], u[8][3][L], D[3][4][3][L], R[3][4][3][L], W[L], V[L];
        _Alignas(64) ct_real ok[L];
        /* The corners' positions and displacements, each node's read once
         * (not once per edge it ends). */
        for (int a = 0; a < 8; a++)
            for (int l = 0; l < L; l++) {
                ct_idx v = lc[a * L + l];
                p[a][0][l] = x[v];
                p[a][1][l] = y[v];
                p[a][2][l] = z[v];
                u[a][0][l] = p[a][0][l] - X0[v];
                u[a][1][l] = p[a][1][l] - Y0[v];
                u[a][2][l] = p[a][2][l] - Z0[v];
            }
        /* The displacement differences along the edges of each axis. */
        for (int k = 0; k < 3; k++)
            for (int m = 0; m < 4; m++) {
                const int a1 = CTI_EDGE[k][m][1], a0 = CTI_EDGE[k][m][0];
                for (int i = 0; i < 3; i++)
                    for (int l = 0; l < L; l++) {
                        D[k][m][i][l] = u[a1][i][l] - u[a0][i][l];
                        R[k][m][i][l] = 0;
                    }
            }
        for (int l = 0; l < L; l++) {
            W[l] = V[l] = 0;
            ok[l] = 1;
        }
        for (int g = 0; g < 8; g++)
            cti_brick_gauss_point(g, jb, db, D, R, W, V, ok, lambda, mu);
        for (int l = 0; l < L; l++) {
            const ct_idx e = bk * L + l;
            if (e >= n)
                break;
            /* f_a = -sum_g Q dN_a: each edge's sum R goes to its plus end
             * with a minus sign and to its minus end with a plus sign. */
            ct_real f[8][3] = {{0}};
            for (int k = 0; k < 3; k++)
                for (int m = 0; m < 4; m++)
                    for (int i = 0; i < 3; i++) {
                        f[CTI_EDGE[k][m][1]][i] -= R[k][m][i][l];
                        f[CTI_EDGE[k][m][0]][i] += R[k][m][i][l];
                    }
            /* The stable step (elements.h): volume over the largest face
             * area over the wave speed; an inverted element gives 0. */
            ct_real a2max = 0;
            for (int q = 0; q < 6; q++) {
                const int i0 = FACE[q][0], i1 = FACE[q][1], i2 = FACE[q][2], i3 = FACE[q][3];
                ct_real d1x = p[i2][0][l] - p[i0][0][l], d1y = p[i2][1][l] - p[i0][1][l],
                        d1z = p[i2][2][l] - p[i0][2][l];
                ct_real d2x = p[i3][0][l] - p[i1][0][l], d2y = p[i3][1][l] - p[i1][1][l],
                        d2z = p[i3][2][l] - p[i1][2][l];
                ct_real cx = d1y * d2z - d1z * d2y, cy = d1z * d2x - d1x * d2z,
                        cz = d1x * d2y - d1y * d2x;
                const ct_real a2 = cx * cx + cy * cy + cz * cz;
                a2max = a2 > a2max ? a2 : a2max; /* fmax's answer: never NaN */
            }
            /* One root for the largest face: the rounded root is monotone,
             * so this is the largest of the six roots, bit for bit. */
            const ct_real amax = CTI_SQRT(a2max) / 2;
            ct_real dt = (V[l] > 0 && amax > 0) ? V[l] / amax / cw : 0;
            dte[e] = dt;
            best = CTI_MIN(best, dt);
            if (!(ok[l] && W[l] == W[l]))
                bad = CTI_MAX(bad, e + 1);
            for (int a = 0; a < 8; a++) {
                sx[(size_t)a * nz + (size_t)e] = f[a][0];
                sy[(size_t)a * nz + (size_t)e] = f[a][1];
                sz[(size_t)a * nz + (size_t)e] = f[a][2];
            }
            eint[e] = W[l];
        }
    }
    b->dt_last = best;
    if (bad > 0) {
        ct_idx e = bad - 1;
        int nonfinite = !(eint[e] == eint[e]) || CTI_FABS(eint[e]) >= CTI_HUGE;
        return cti_fail(diag, nonfinite ? CT_ERR_NONFINITE : CT_ERR_DEGENERATE, e,
                        "Brick %d is %s.", (int)e,
                        nonfinite ? "not finite" : "inverted (det F <= 0 at a Gauss point)");
    }
    ctd_gather_add(&b->g, sx, sy, sz, fx, fy, fz);
    return CT_OK;
}

ct_real ctd_brick_dt_last(const ctd_brick *b) { return b->dt_last; }

double ctd_brick_energy(const ctd_brick *b)
{
    double s = 0;
    for (ct_idx e = 0; e < b->n; e++)
        s += b->eint[e];
    return s;
}

static ct_real volume_of(const ct_real P[8][3], const cti_hex_dn dN)
{
    ct_real v = 0;
    for (int g = 0; g < 8; g++)
        v += jac_inv(P, dN[g], NULL);
    return v;
}

ct_real ctd_brick_volume(const ctd_brick *b, ct_idx e, const ct_real *x, const ct_real *y,
                         const ct_real *z)
{
    cti_hex_dn dN;
    hex_dn(dN);
    ct_real P[8][3];
    load(b->conn + 8 * (int64_t)e, x, y, z, P);
    return volume_of(P, dN);
}

ct_real ctd_brick_dt(const ctd_brick *b, const ct_real *x, const ct_real *y, const ct_real *z,
                     ct_idx *imin)
{
    cti_hex_dn dN;
    hex_dn(dN);
    const ct_idx n = b->n;
    /* The bulk-mode wave speed of the fully integrated element (elements.h). */
    const ct_real mod = CTI_MAX(b->lambda + 2 * b->mu, 3 * b->lambda + 2 * b->mu);
    const ct_real c = CTI_SQRT(mod / b->rho);
    ct_real *dte = b->dte;
    ct_real best = CTD_DT_NONE;
    CTI_PAR_FOR(n > CTD_PAR_MIN / 8, (schedule(static) reduction(min : best)),
    for (ct_idx e = 0; e < n; e++) {
        ct_real P[8][3];
        load(b->conn + 8 * (int64_t)e, x, y, z, P);
        ct_real amax = 0;
        for (int f = 0; f < 6; f++) {
            const ct_real *p0 = P[FACE[f][0]], *p1 = P[FACE[f][1]], *p2 = P[FACE[f][2]],
                          *p3 = P[FACE[f][3]];
            ct_real d1[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            ct_real d2[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
            ct_real cx = d1[1] * d2[2] - d1[2] * d2[1], cy = d1[2] * d2[0] - d1[0] * d2[2],
                    cz = d1[0] * d2[1] - d1[1] * d2[0];
            const ct_real a = CTI_SQRT(cx * cx + cy * cy + cz * cz) / 2;
            amax = a > amax ? a : amax; /* fmax's answer: amax is never NaN */
        }
        ct_real v = volume_of(P, dN);
        /* An inverted or collapsed element gives 0 (the solver stops). */
        ct_real dt = (v > 0 && amax > 0) ? v / amax / c : 0;
        dte[e] = dt;
        best = CTI_MIN(best, dt);
    });
    if (imin) {
        ct_idx arg = -1;
        for (ct_idx e = 0; e < n && arg < 0; e++)
            if (dte[e] == best)
                arg = e;
        *imin = arg;
    }
    return best;
}
