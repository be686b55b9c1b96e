/*
 * shell_forces.c -- the per-cycle part of the thin shell (shell.h): the
 * membrane and bending forces, written to private slots and gathered per
 * node in a fixed order; and the dihedral angle with its gradient.
 *
 * Membrane (constant-strain triangle, total Lagrangian). In a local
 * orthonormal frame of the reference triangle, Dm = [X2 - X1, X3 - X1] is
 * the 2 x 2 reference edge matrix and Bm = Dm^-1 (upper triangular: b11,
 * b12, b22). With the current edges d1 = x2 - x1 and d2 = x3 - x1, the
 * deformation gradient F = [d1 d2] Bm (3 x 2) has the columns
 * f0 = b11 d1 and f1 = b12 d1 + b22 d2. The Green strain is
 * Eg = (F^T F - I) / 2 and the plane-stress St Venant-Kirchhoff law gives
 * S = lambda' tr(Eg) I + 2 mu Eg, lambda' = E nu / (1 - nu^2),
 * mu = E / (2 (1 + nu)); energy W = V (mu Eg:Eg + lambda'/2 tr(Eg)^2)
 * with V = A0 t. The first Piola stress is P = F S, and the nodal forces
 * are -dW/dx: [f2 f3] = -V P Bm^T, f1 = -(f2 + f3). Rigid motions leave F^T F
 * = I, so they give neither energy nor force.
 *
 * Bending (hinge on an interior edge). Edge nodes a = p0, b = p1, opposite
 * vertices c = p2 (triangle A) and d = p3 (triangle B); e = b - a. The
 * normals nA = e x (c - a) / |.| and nB = (d - a) x e / |.| agree for a flat
 * consistently oriented pair (they do not depend on the triangles' own node
 * order). The signed dihedral angle is
 *   theta = atan2((nA x nB) . e / |e|, nA . nB).
 * With the heights hA = |e x (c - a)| / |e|, hB = |(d - a) x e| / |e| and
 * the positions of the feet of c and d on the edge, sA = (c - a).e / |e|^2,
 * sB = (d - a).e / |e|^2, the gradient is (only the normal motion of c
 * relative to its foot on the edge turns triangle A about the edge):
 *   d theta / d c = -nA / hA,            d theta / d d = -nB / hB,
 *   d theta / d a = (1 - sA) nA / hA + (1 - sB) nB / hB,
 *   d theta / d b = sA nA / hA + sB nB / hB.
 * The four sum to zero (translations) and are checked against central
 * finite differences in tests/test_elements_shell.c. The hinge energy is
 * E_h = k_h (theta - theta0)^2, its forces -2 k_h (theta - theta0) grad.
 * theta lives in (-pi, pi]: one hinge folded flat on itself (the two
 * triangles coincident) is left to the contact to prevent.
 */
#include <math.h>
#include <string.h>

#include "ct_internal.h"
#include "shell.h"

/* Triangles + hinges below which the forces are computed serially. */
#define CTI_SHELL_PAR_MIN 2048

#ifdef CT_SINGLE
#define CTI_SHELL_ATAN2 atan2f
#else
#define CTI_SHELL_ATAN2 atan2
#endif

static inline void cti_shell_cross(const ct_real u[3], const ct_real v[3], ct_real w[3])
{
    w[0] = u[1] * v[2] - u[2] * v[1];
    w[1] = u[2] * v[0] - u[0] * v[2];
    w[2] = u[0] * v[1] - u[1] * v[0];
}

static inline ct_real cti_shell_dot(const ct_real u[3], const ct_real v[3])
{
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

/* The dihedral angle and its gradient; returns -1 when a triangle or the
 * edge has collapsed (nothing is written to g then), else 0. */
static int cti_shell_hinge(const ct_real p[4][3], ct_real *theta, ct_real g[4][3])
{
    ct_real e[3], ca[3], da[3], na[3], nb[3];
    for (int k = 0; k < 3; k++) {
        e[k] = p[1][k] - p[0][k];
        ca[k] = p[2][k] - p[0][k];
        da[k] = p[3][k] - p[0][k];
    }
    cti_shell_cross(e, ca, na);
    cti_shell_cross(da, e, nb);
    ct_real ee = cti_shell_dot(e, e);
    ct_real la = CTI_SQRT(cti_shell_dot(na, na)); /* 2 A_A = |e| hA */
    ct_real lb = CTI_SQRT(cti_shell_dot(nb, nb)); /* 2 A_B = |e| hB */
    if (!(ee > 0) || !(la > 0) || !(lb > 0))
        return -1;
    ct_real le = CTI_SQRT(ee);
    for (int k = 0; k < 3; k++) {
        na[k] /= la;
        nb[k] /= lb;
    }
    ct_real w[3];
    cti_shell_cross(na, nb, w);
    *theta = CTI_SHELL_ATAN2(cti_shell_dot(w, e) / le, cti_shell_dot(na, nb));
    ct_real ia = le / la, ib = le / lb; /* 1 / hA, 1 / hB */
    ct_real sa = cti_shell_dot(ca, e) / ee, sb = cti_shell_dot(da, e) / ee;
    for (int k = 0; k < 3; k++) {
        ct_real ua = na[k] * ia, ub = nb[k] * ib;
        g[2][k] = -ua;
        g[3][k] = -ub;
        g[0][k] = (1 - sa) * ua + (1 - sb) * ub;
        g[1][k] = sa * ua + sb * ub;
    }
    return 0;
}

ct_real ctd_shell_dihedral(const ct_real p[4][3], ct_real g[4][3])
{
    ct_real theta = 0;
    if (cti_shell_hinge(p, &theta, g) != 0) {
        memset(g, 0, 12 * sizeof(ct_real));
        return 0;
    }
    return theta;
}

int ctd_shell_forces(ctd_shell *s, const ct_real *x, const ct_real *y, const ct_real *z,
                     ct_real *fx, ct_real *fy, ct_real *fz, double *energy)
{
    if (!s || !x || !y || !z || !fx || !fy || !fz)
        return CT_ERR_ARG;
    const ct_real E = (ct_real)s->E, nu = (ct_real)s->nu;
    const ct_real lam = E * nu / (1 - nu * nu); /* plane-stress lambda' */
    const ct_real mu = E / (2 * (1 + nu));
    const ct_idx ntri = s->ntri, nhinge = s->nhinge;
    ct_real *restrict sx = s->sx, *restrict sy = s->sy, *restrict sz = s->sz;
    double *restrict e_el = s->e_el;
    int bad = 0;
    /* Small shells run serially (a parallel region costs more than them). */
    const int par = (int64_t)ntri + nhinge >= CTI_SHELL_PAR_MIN;

#pragma omp parallel reduction(| : bad) if (par)
    {
#pragma omp for schedule(static)
        for (ct_idx t = 0; t < ntri; t++) {
            ct_idx i1 = s->t1[t], i2 = s->t2[t], i3 = s->t3[t];
            ct_real d1[3] = {x[i2] - x[i1], y[i2] - y[i1], z[i2] - z[i1]};
            ct_real d2[3] = {x[i3] - x[i1], y[i3] - y[i1], z[i3] - z[i1]};
            ct_real b11 = s->b11[t], b12 = s->b12[t], b22 = s->b22[t], V = s->tri_vol[t];
            ct_real f0[3], f1[3];
            for (int k = 0; k < 3; k++) {
                f0[k] = b11 * d1[k];
                f1[k] = b12 * d1[k] + b22 * d2[k];
            }
            /* Green strain and the second Piola-Kirchhoff stress. */
            ct_real e00 = (cti_shell_dot(f0, f0) - 1) / 2;
            ct_real e11 = (cti_shell_dot(f1, f1) - 1) / 2;
            ct_real e01 = cti_shell_dot(f0, f1) / 2;
            ct_real tr = e00 + e11;
            ct_real s00 = lam * tr + 2 * mu * e00, s11 = lam * tr + 2 * mu * e11;
            ct_real s01 = 2 * mu * e01;
            e_el[t] = (double)V * ((double)mu * (e00 * e00 + e11 * e11 + 2 * e01 * e01) +
                                   (double)lam / 2 * tr * tr);
            ct_real h2[3], h3[3];
            for (int k = 0; k < 3; k++) {
                ct_real p0 = f0[k] * s00 + f1[k] * s01; /* P = F S, column 0 */
                ct_real p1 = f0[k] * s01 + f1[k] * s11; /* column 1 */
                h2[k] = -V * (p0 * b11 + p1 * b12);
                h3[k] = -V * (p1 * b22);
            }
            if (!isfinite(e_el[t] + h2[0] + h2[1] + h2[2] + h3[0] + h3[1] + h3[2]))
                bad = 1;
            ct_idx q = 3 * t;
            sx[q] = -(h2[0] + h3[0]);
            sy[q] = -(h2[1] + h3[1]);
            sz[q] = -(h2[2] + h3[2]);
            sx[q + 1] = h2[0];
            sy[q + 1] = h2[1];
            sz[q + 1] = h2[2];
            sx[q + 2] = h3[0];
            sy[q + 2] = h3[1];
            sz[q + 2] = h3[2];
        }

#pragma omp for schedule(static)
        for (ct_idx h = 0; h < nhinge; h++) {
            const ct_idx nd[4] = {s->h1[h], s->h2[h], s->h3[h], s->h4[h]};
            ct_real p[4][3], g[4][3], theta;
            for (int a = 0; a < 4; a++) {
                p[a][0] = x[nd[a]];
                p[a][1] = y[nd[a]];
                p[a][2] = z[nd[a]];
            }
            ct_idx q = 3 * ntri + 4 * h;
            if (cti_shell_hinge(p, &theta, g) != 0) {
                bad = 1;
                e_el[ntri + h] = 0;
                for (int a = 0; a < 4; a++)
                    sx[q + a] = sy[q + a] = sz[q + a] = 0;
                continue;
            }
            ct_real dth = theta - s->theta0[h];
            e_el[ntri + h] = (double)s->hk[h] * dth * dth;
            ct_real c = -2 * s->hk[h] * dth;
            if (!isfinite(e_el[ntri + h] + c))
                bad = 1;
            for (int a = 0; a < 4; a++) {
                sx[q + a] = c * g[a][0];
                sy[q + a] = c * g[a][1];
                sz[q + a] = c * g[a][2];
            }
        }
    }
    if (bad)
        return CT_ERR_NONFINITE;

    /* Gather: each node sums its slots in increasing slot order, so the
     * result does not depend on the thread count. */
#pragma omp parallel for schedule(static) if (par)
    for (ct_idx j = 0; j < s->nsnode; j++) {
        const ct_idx i = s->snode[j];
        ct_idx a0 = s->slot_off[j], a1 = s->slot_off[j + 1];
        if (a0 == a1)
            continue;
        ct_real gx = 0, gy = 0, gz = 0;
        for (ct_idx a = a0; a < a1; a++) {
            ct_idx q = s->slot[a];
            gx += sx[q];
            gy += sy[q];
            gz += sz[q];
        }
        fx[i] += gx;
        fy[i] += gy;
        fz[i] += gz;
    }

    /* Energies summed serially in element order (deterministic). */
    double em = 0, eb = 0;
    for (ct_idx t = 0; t < ntri; t++)
        em += e_el[t];
    for (ct_idx h = 0; h < nhinge; h++)
        eb += e_el[ntri + h];
    s->e_membrane = em;
    s->e_bending = eb;
    if (energy)
        *energy = em + eb;
    return CT_OK;
}
