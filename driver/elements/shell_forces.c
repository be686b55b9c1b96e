/*
 * shell_forces.c -- the per-cycle part of the thin shell (shell.h): the
 * membrane and bending forces, written to private slots and gathered per
 * node in a fixed order; the dihedral angle with its gradient; and the
 * vectorisable atan2 the forces use.
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
 *
 * How the forces compute it. The part of the gradient with nA moves only
 * triangle A's nodes, along A's normal: with 1 / hA = |e| / (2 A_A),
 *   F_c = -K nA,  F_a = (1 - sA) K nA,  F_b = sA K nA,
 *   K = c |e| / (2 A_A),  c = -2 k_h (theta - theta0),
 * and likewise for B. nA is triangle A's own unit normal n_A times a sign
 * sigma_A (+1 when b follows a in A's node order, else -1; for B, -1 when
 * b follows a in B), so the hinge hands triangle A the number c sigma_A
 * and each triangle adds, over its three edges, the numbers of the hinges
 * on that edge (at most two) times |e| / (2 A) times the weights above,
 * all along n_A. Three passes, each a vector loop: every triangle's unit
 * normal; every hinge's angle (from the two normals and the edge, with
 * cti_atan2; the four hinges of an edge between two quads together, the
 * edge and the normals read once), energy and signed numbers; every
 * triangle's membrane force
 * plus its bending force into its three slots. A hinge costs no slots
 * and no scatter: a node sums only its triangles' corners (12 on a quad
 * mesh, not 44 with the hinges' own slots). The energy is summed per
 * block of CTD_SHELL_BLOCK elements, and the blocks in their order.
 */
#include <math.h>
#include <string.h>

#include "ct_internal.h"
#include "shell.h"

/* Triangles + hinges below which the forces are computed serially. */
#define CTI_SHELL_PAR_MIN 2048

#ifdef CT_SINGLE
#define CTI_SHELL_ATAN2 atan2f
#define CTI_SHELL_COPYSIGN copysignf
#else
#define CTI_SHELL_ATAN2 atan2
#define CTI_SHELL_COPYSIGN copysign
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

/* atan2 as a branch-free sequence the compiler can vectorise: t = the
 * smaller of |x|, |y| over the larger, in [0, 1]; above tan(pi/8) it is
 * moved to u = (t - 1) / (t + 1) and atan t = pi/4 + atan u, so |u| <=
 * tan(pi/8) = 0.4142; atan u = u + u z Q(z) with z = u^2, where 1 + z Q(z)
 * is the polynomial of smallest relative error on [0, tan^2(pi/8)] of
 * degree 11 (double: 1.2e-18) or 5 (float: 6e-10), whose leading
 * coefficient rounds to 1 (the script shell_atan_poly.py computes them).
 * Q is evaluated by Estrin's scheme, in pairs and powers z^2, z^4, z^8:
 * a chain of 4 multiplications and 3 additions instead of Horner's 11 of
 * each. Then the octant is restored. Both zero gives 0; a NaN gives NaN. */
#ifdef CT_SINGLE
#define CTI_ATAN_C1 -3.3333307625842715e-1f
#define CTI_ATAN_C2 1.9998216947649524e-1f
#define CTI_ATAN_C3 -1.4240083009892624e-1f
#define CTI_ATAN_C4 1.0573479821952973e-1f
#define CTI_ATAN_C5 -6.0347904037902214e-2f
#else
#define CTI_ATAN_C1 -3.3333333333333129e-1
#define CTI_ATAN_C2 1.9999999999942732e-1
#define CTI_ATAN_C3 -1.4285714279416961e-1
#define CTI_ATAN_C4 1.1111110752666387e-1
#define CTI_ATAN_C5 -9.0908970191424086e-2
#define CTI_ATAN_C6 7.6920488836134403e-2
#define CTI_ATAN_C7 -6.6629904080136297e-2
#define CTI_ATAN_C8 5.8471476830363597e-2
#define CTI_ATAN_C9 -5.0362702112626711e-2
#define CTI_ATAN_C10 3.7993868366624396e-2
#define CTI_ATAN_C11 -1.7835672000221571e-2
#endif
static inline ct_real cti_atan2(ct_real y, ct_real x)
{
    const ct_real pi = (ct_real)3.14159265358979323846;
    const ct_real tan_pi_8 = (ct_real)0.41421356237309504880;
    ct_real ax = CTI_FABS(x), ay = CTI_FABS(y);
    ct_real mx = ax > ay ? ax : ay, mn = ax > ay ? ay : ax;
    /* One division: u = t, or (t - 1) / (t + 1) = (mn - mx) / (mn + mx).
     * Both zero give u = 0; a NaN fails every comparison and reaches u. */
    int big = mn > tan_pi_8 * mx;
    ct_real num = big ? mn - mx : mn, den = big ? mn + mx : mx;
    ct_real u = den == 0 ? 0 : num / den;
    ct_real z = u * u, z2 = z * z, z4 = z2 * z2;
#ifdef CT_SINGLE
    ct_real q = ((CTI_ATAN_C1 + CTI_ATAN_C2 * z) + (CTI_ATAN_C3 + CTI_ATAN_C4 * z) * z2) +
                CTI_ATAN_C5 * z4;
#else
    ct_real z8 = z4 * z4;
    ct_real r0 = (CTI_ATAN_C1 + CTI_ATAN_C2 * z) + (CTI_ATAN_C3 + CTI_ATAN_C4 * z) * z2;
    ct_real r1 = (CTI_ATAN_C5 + CTI_ATAN_C6 * z) + (CTI_ATAN_C7 + CTI_ATAN_C8 * z) * z2;
    ct_real r2 = (CTI_ATAN_C9 + CTI_ATAN_C10 * z) + CTI_ATAN_C11 * z2;
    ct_real q = (r0 + r1 * z4) + r2 * z8;
#endif
    ct_real r = (big ? pi / 4 : 0) + (u + (u * z) * q);
    r = ay > ax ? pi / 2 - r : r;
    /* The signs by copysign (signbit does not vectorise): -0 counts as
     * negative, as in atan2. */
    r = CTI_SHELL_COPYSIGN(1, x) < 0 ? pi - r : r;
    return CTI_SHELL_COPYSIGN(r, y);
}

ct_real ctd_shell_atan2(ct_real y, ct_real x) { return cti_atan2(y, x); }

/* The edge vectors d1 = x2 - x1 and d2 = x3 - x1 of triangles [t0, t1)
 * into the force slots of their first two corners (sx[t], sy[t], sz[t] and
 * sx[ntri + t], ...), where the triangle loop of ctd_shell_forces reads them
 * before it writes its forces there. Scalar loads on purpose: vectorised,
 * the nine indexed loads a triangle are vector gathers, and the scalar
 * copy with unit-stride vector loops over it measured faster (as the
 * contact kernels' copies, CTI_NOVEC in ct_internal.h). */
CTI_NOVEC static void cti_shell_edges(const ctd_shell *s, ct_idx t0, ct_idx t1,
                                      const ct_real *restrict x, const ct_real *restrict y,
                                      const ct_real *restrict z)
{
    const ct_idx *restrict c1 = s->t1, *restrict c2 = s->t2, *restrict c3 = s->t3;
    const size_t nt = (size_t)s->ntri;
    ct_real *restrict sx = s->sx, *restrict sy = s->sy, *restrict sz = s->sz;
    CTI_NOVEC_LOOP
    for (ct_idx t = t0; t < t1; t++) {
        const ct_idx i1 = c1[t], i2 = c2[t], i3 = c3[t];
        const ct_real x1 = x[i1], y1 = y[i1], z1 = z[i1];
        sx[t] = x[i2] - x1;
        sy[t] = y[i2] - y1;
        sz[t] = z[i2] - z1;
        sx[nt + t] = x[i3] - x1;
        sy[nt + t] = y[i3] - y1;
        sz[nt + t] = z[i3] - z1;
    }
}

/* For triangles [t0, t1): the sum of the coefficients of the hinges on
 * each edge k (hc[te[2 k ntri + t]] + hc[te[(2 k + 1) ntri + t]]) into the
 * force slot of the third corner (sx, sy, sz[2 ntri + t] for edges 0, 1,
 * 2), which the triangle loop reads before it writes its forces there.
 * Scalar loads on purpose (cti_shell_edges). */
CTI_NOVEC static void cti_shell_hinge_sums(const ctd_shell *s, ct_idx t0, ct_idx t1)
{
    const ct_idx *restrict te = s->te;
    const ct_real *restrict hc = s->hc;
    const size_t nt = (size_t)s->ntri;
    ct_real *restrict sx = s->sx + 2 * nt, *restrict sy = s->sy + 2 * nt,
                      *restrict sz = s->sz + 2 * nt;
    CTI_NOVEC_LOOP
    for (ct_idx t = t0; t < t1; t++) {
        sx[t] = hc[te[t]] + hc[te[nt + t]];
        sy[t] = hc[te[2 * nt + t]] + hc[te[3 * nt + t]];
        sz[t] = hc[te[4 * nt + t]] + hc[te[5 * nt + t]];
    }
}

/* The edge vectors (cti_shell_edges), the unit normal and 1 / |normal|
 * (1 / (2 A)) of every triangle, by blocks of CTD_SHELL_BLOCK. A collapsed
 * triangle gets NaN or infinite values, which make its forces and its
 * hinges' NaN (reported there). An orphaned work-sharing loop: called
 * inside the forces' parallel region, or serially. */
static void cti_shell_normals(ctd_shell *s, const ct_real *restrict x, const ct_real *restrict y,
                              const ct_real *restrict z)
{
    const ct_idx ntri = s->ntri, nb = (ntri + CTD_SHELL_BLOCK - 1) / CTD_SHELL_BLOCK;
    const ct_real *restrict sx = s->sx, *restrict sy = s->sy, *restrict sz = s->sz;
    ct_real *restrict nx = s->nx, *restrict ny = s->ny, *restrict nz = s->nz;
    ct_real *restrict il = s->il;
#pragma omp for schedule(static)
    for (ct_idx b = 0; b < nb; b++) {
        const ct_idx k0 = b * CTD_SHELL_BLOCK,
                     k1 = ntri - k0 < CTD_SHELL_BLOCK ? ntri : k0 + CTD_SHELL_BLOCK;
        cti_shell_edges(s, k0, k1, x, y, z);
#pragma omp simd
        for (ct_idx t = k0; t < k1; t++) {
            ct_real ax = sx[t], ay = sy[t], az = sz[t];
            ct_real bx = sx[ntri + t], by = sy[ntri + t], bz = sz[ntri + t];
            ct_real cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
            ct_real inv = 1 / CTI_SQRT(cx * cx + cy * cy + cz * cz);
            nx[t] = cx * inv;
            ny[t] = cy * inv;
            nz[t] = cz * inv;
            il[t] = inv;
        }
    }
}

/* theta = the dihedral angle of hinge h from the triangles' unit normals:
 * nA and nB are the normals of triangles hta[h] and htb[h] signed by hsa[h]
 * and hsb[h] to the hinge's orientation (shell.h). A macro over the arrays
 * h1, h2, hta, htb, hsa, hsb, nx, ny, nz, x, y, z of the caller, not a
 * function: clang vectorises an omp simd loop only when every memory
 * access is written inside it (an inlined function's are not marked).
 * atan2 is invariant under a positive common scale of its arguments, so
 * (nA x nB) . e / |e| against nA . nB is taken as (nA x nB) . e against
 * |e| (nA . nB): one division a hinge fewer. */
#define CTI_SHELL_ANGLE(h, theta)                                                               \
    do {                                                                                        \
        ct_idx a_ = h1[h], b_ = h2[h], ta_ = hta[h], tb_ = htb[h];                              \
        ct_real ex_ = x[b_] - x[a_], ey_ = y[b_] - y[a_], ez_ = z[b_] - z[a_];                  \
        ct_real le_ = CTI_SQRT(ex_ * ex_ + ey_ * ey_ + ez_ * ez_);                              \
        CTI_SHELL_THETA(hsa[h], hsb[h], ta_, tb_, theta);                                       \
    } while (0)

/* theta of a hinge from the edge vector ex_, ey_, ez_ and its length le_
 * (locals of the caller) and the unit normals of its triangles ta and tb
 * with their signs sa and sb; the arithmetic of CTI_SHELL_ANGLE, to the
 * bit (the rest angles and the groups' angles agree). */
#define CTI_SHELL_THETA(sa, sb, ta, tb, theta)                                                  \
    do {                                                                                        \
        ct_real sa_ = (sa), sb_ = (sb);                                                         \
        ct_real ax_ = sa_ * nx[ta], ay_ = sa_ * ny[ta], az_ = sa_ * nz[ta];                     \
        ct_real bx_ = sb_ * nx[tb], by_ = sb_ * ny[tb], bz_ = sb_ * nz[tb];                     \
        ct_real wx_ = ay_ * bz_ - az_ * by_, wy_ = az_ * bx_ - ax_ * bz_;                       \
        ct_real wz_ = ax_ * by_ - ay_ * bx_;                                                    \
        (theta) = cti_atan2(wx_ * ex_ + wy_ * ey_ + wz_ * ez_,                                  \
                            le_ * (ax_ * bx_ + ay_ * by_ + az_ * bz_));                         \
    } while (0)

/* Hinge h's energy (into eb), its coefficient c = -2 k_h (theta - theta0)
 * signed for each side's triangle (sa, sb; into hc), and whether c is
 * finite (into bad), from its angle theta; over the caller's hk, th0, hc,
 * nhinge. */
#define CTI_SHELL_HINGE_OUT(h, sa, sb, theta)                                                   \
    do {                                                                                        \
        ct_real dth_ = (theta)-th0[h];                                                          \
        ct_real c_ = -2 * hk[h] * dth_;                                                         \
        eb += (double)hk[h] * dth_ * dth_;                                                      \
        bad |= !(CTI_FABS(c_) < (ct_real)HUGE_VAL);                                             \
        hc[h] = c_ * (sa);                                                                      \
        hc[nhinge + h] = c_ * (sb);                                                             \
    } while (0)

/* The hinge arrays CTI_SHELL_ANGLE reads, as restrict locals. */
#define CTI_SHELL_ANGLE_ARRAYS(s)                                                               \
    const ct_idx *restrict h1 = (s)->h1, *restrict h2 = (s)->h2, *restrict hta = (s)->hta;      \
    const ct_idx *restrict htb = (s)->htb;                                                      \
    const ct_real *restrict hsa = (s)->hsa, *restrict hsb = (s)->hsb;                           \
    const ct_real *restrict nx = (s)->nx, *restrict ny = (s)->ny, *restrict nz = (s)->nz

int ctd_shell_rest_angles(ctd_shell *s, const ct_real *x, const ct_real *y, const ct_real *z)
{
    cti_shell_normals(s, x, y, z);
    CTI_SHELL_ANGLE_ARRAYS(s);
    ct_real *restrict th0 = s->theta0;
    int bad = 0;
    for (ct_idx h = 0; h < s->nhinge; h++) {
        CTI_SHELL_ANGLE(h, th0[h]);
        bad |= !(CTI_FABS(th0[h]) < 4);
    }
    return bad ? CT_ERR_DEGENERATE : CT_OK;
}

/* The end of block b of n items. */
static inline ct_idx cti_block_end(ct_idx b, ct_idx n)
{
    return n - b * CTD_SHELL_BLOCK < CTD_SHELL_BLOCK ? n : (b + 1) * CTD_SHELL_BLOCK;
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
    const ct_real *restrict b11v = s->b11, *restrict b12v = s->b12, *restrict b22v = s->b22;
    const ct_real *restrict vol = s->tri_vol, *restrict hk = s->hk, *restrict th0 = s->theta0;
    const ct_real *restrict il = s->il;
    ct_real *restrict hc = s->hc;
    CTI_SHELL_ANGLE_ARRAYS(s);
    ct_real *restrict sx = s->sx, *restrict sy = s->sy, *restrict sz = s->sz;
    double *restrict e_blk = s->e_blk;
    const ct_idx ng = s->ngroup;
    ct_idx nbt, nbg, nbr;
    ctd_shell_blocks(s, &nbt, &nbg, &nbr);
    int bad_g = 0, bad_h = 0, bad_t = 0; /* shared: the loops' reductions */
    /* Small shells run serially (a parallel region costs more than them). */
    const int par = (int64_t)ntri + nhinge >= CTI_SHELL_PAR_MIN;

#pragma omp parallel if (par)
    {
        cti_shell_normals(s, x, y, z);

        /* Hinges: the angle, the energy, and the coefficient
         * c = -2 k_h (theta - theta0) signed for each side's triangle. The
         * groups of four first (shell.h): one edge vector and four normals
         * read for four hinges, 4.5 gathers a hinge where a hinge alone
         * takes 12 (the gathers are most of this loop's time). No barrier
         * between the two loops: they write different hinges. */
#pragma omp for schedule(static) reduction(| : bad_g) nowait
        for (ct_idx b = 0; b < nbg; b++) {
            const ct_idx g0 = b * CTD_SHELL_BLOCK, g1 = cti_block_end(b, ng);
            double eb = 0;
            int bad = 0;
#pragma omp simd reduction(+ : eb) reduction(| : bad)
            for (ct_idx g = g0; g < g1; g++) {
                ct_idx a_ = h1[g], b_ = h2[g];
                ct_idx A1 = hta[g], A2 = hta[2 * ng + g], B1 = htb[g], B2 = htb[ng + g];
                ct_real ex_ = x[b_] - x[a_], ey_ = y[b_] - y[a_], ez_ = z[b_] - z[a_];
                ct_real le_ = CTI_SQRT(ex_ * ex_ + ey_ * ey_ + ez_ * ez_);
                /* The signs are the triangles' (hsa[ng + g] = hsa[g], ...). */
                ct_real sA1 = hsa[g], sA2 = hsa[2 * ng + g], sB1 = hsb[g], sB2 = hsb[ng + g];
                ct_real th_0, th_1, th_2, th_3;
                CTI_SHELL_THETA(sA1, sB1, A1, B1, th_0);
                CTI_SHELL_THETA(sA1, sB2, A1, B2, th_1);
                CTI_SHELL_THETA(sA2, sB1, A2, B1, th_2);
                CTI_SHELL_THETA(sA2, sB2, A2, B2, th_3);
                CTI_SHELL_HINGE_OUT(g, sA1, sB1, th_0);
                CTI_SHELL_HINGE_OUT(ng + g, sA1, sB2, th_1);
                CTI_SHELL_HINGE_OUT(2 * ng + g, sA2, sB1, th_2);
                CTI_SHELL_HINGE_OUT(3 * ng + g, sA2, sB2, th_3);
            }
            e_blk[nbt + b] = eb;
            bad_g |= bad;
        }
#pragma omp for schedule(static) reduction(| : bad_h)
        for (ct_idx b = 0; b < nbr; b++) {
            const ct_idx j0 = 4 * ng + b * CTD_SHELL_BLOCK,
                         j1 = 4 * ng + cti_block_end(b, nhinge - 4 * ng);
            double eb = 0;
            int bad = 0;
#pragma omp simd reduction(+ : eb) reduction(| : bad)
            for (ct_idx h = j0; h < j1; h++) {
                ct_real theta;
                CTI_SHELL_ANGLE(h, theta);
                CTI_SHELL_HINGE_OUT(h, hsa[h], hsb[h], theta);
            }
            e_blk[nbt + nbg + b] = eb;
            bad_h |= bad;
        }

        /* Triangles: membrane, plus the hinges' forces on the triangle's
         * side, which are along its normal. */
#pragma omp for schedule(static) reduction(| : bad_t)
        for (ct_idx b = 0; b < nbt; b++) {
            const ct_idx k0 = b * CTD_SHELL_BLOCK, k1 = cti_block_end(b, ntri);
            double eb = 0;
            int bad = 0;
            cti_shell_hinge_sums(s, k0, k1);
#pragma omp simd reduction(+ : eb) reduction(| : bad)
            for (ct_idx t = k0; t < k1; t++) {
                /* The edge vectors cti_shell_normals left in the slots. */
                ct_real d1x = sx[t], d1y = sy[t], d1z = sz[t];
                ct_real d2x = sx[ntri + t], d2y = sy[ntri + t], d2z = sz[ntri + t];
                ct_real b11 = b11v[t], b12 = b12v[t], b22 = b22v[t], V = vol[t];
                ct_real f0x = b11 * d1x, f0y = b11 * d1y, f0z = b11 * d1z;
                ct_real f1x = b12 * d1x + b22 * d2x, f1y = b12 * d1y + b22 * d2y,
                        f1z = b12 * d1z + b22 * d2z;
                /* Green strain and the second Piola-Kirchhoff stress. */
                ct_real e00 = (f0x * f0x + f0y * f0y + f0z * f0z - 1) / 2;
                ct_real e11 = (f1x * f1x + f1y * f1y + f1z * f1z - 1) / 2;
                ct_real e01 = (f0x * f1x + f0y * f1y + f0z * f1z) / 2;
                ct_real tr = e00 + e11;
                ct_real s00 = lam * tr + 2 * mu * e00, s11 = lam * tr + 2 * mu * e11;
                ct_real s01 = 2 * mu * e01;
                double em = (double)V * ((double)mu * (e00 * e00 + e11 * e11 + 2 * e01 * e01) +
                                         (double)lam / 2 * tr * tr);
                eb += em;
                /* P = F S; forces on nodes 2 and 3: -V P Bm^T. */
                ct_real p0x = f0x * s00 + f1x * s01, p1x = f0x * s01 + f1x * s11;
                ct_real p0y = f0y * s00 + f1y * s01, p1y = f0y * s01 + f1y * s11;
                ct_real p0z = f0z * s00 + f1z * s01, p1z = f0z * s01 + f1z * s11;
                ct_real h2x = -V * (p0x * b11 + p1x * b12), h3x = -V * (p1x * b22);
                ct_real h2y = -V * (p0y * b11 + p1y * b12), h3y = -V * (p1y * b22);
                ct_real h2z = -V * (p0z * b11 + p1z * b12), h3z = -V * (p1z * b22);
                /* Edge k runs from corner k to corner k + 1, opposite corner
                 * k + 2: e0 = d1, e1 = d2 - d1, e2 = -d2; r_k = corner k + 2
                 * minus corner k: r0 = d2, r1 = -d1, r2 = d1 - d2. s_k is the
                 * foot of the opposite corner on the edge, (r_k . e_k) / |e_k|^2,
                 * and kap_k = (sum of the edge's hinge coefficients) |e_k| /
                 * (2 A). The edge's hinges push the opposite corner by -kap_k n,
                 * its start by kap_k (1 - s_k) n and its end by kap_k s_k n. */
                ct_real e1x = d2x - d1x, e1y = d2y - d1y, e1z = d2z - d1z;
                ct_real q0 = d1x * d1x + d1y * d1y + d1z * d1z;
                ct_real q1 = e1x * e1x + e1y * e1y + e1z * e1z;
                ct_real q2 = d2x * d2x + d2y * d2y + d2z * d2z;
                ct_real r0 = (d2x * d1x + d2y * d1y + d2z * d1z) / q0;
                ct_real r1 = -(d1x * e1x + d1y * e1y + d1z * e1z) / q1;
                ct_real r2 = ((d2x - d1x) * d2x + (d2y - d1y) * d2y + (d2z - d1z) * d2z) / q2;
                ct_real inv = il[t];
                /* The edges' hinge sums cti_shell_hinge_sums left. */
                ct_real k0 = sx[2 * ntri + t] * CTI_SQRT(q0) * inv;
                ct_real k1 = sy[2 * ntri + t] * CTI_SQRT(q1) * inv;
                ct_real k2 = sz[2 * ntri + t] * CTI_SQRT(q2) * inv;
                ct_real w1 = k0 * (1 - r0) + k2 * r2 - k1;
                ct_real w2 = k1 * (1 - r1) + k0 * r0 - k2;
                ct_real w3 = k2 * (1 - r2) + k1 * r1 - k0;
                ct_real ux = nx[t], uy = ny[t], uz = nz[t];
                ct_real g2x = h2x + w2 * ux, g2y = h2y + w2 * uy, g2z = h2z + w2 * uz;
                ct_real g3x = h3x + w3 * ux, g3y = h3y + w3 * uy, g3z = h3z + w3 * uz;
                ct_real g1x = w1 * ux - (h2x + h3x), g1y = w1 * uy - (h2y + h3y),
                        g1z = w1 * uz - (h2z + h3z);
                bad |= !(CTI_FABS(g1x + g1y + g1z + g2x + g2y + g2z + g3x + g3y + g3z) <
                         (ct_real)HUGE_VAL) |
                       !(em < HUGE_VAL);
                sx[t] = g1x;
                sy[t] = g1y;
                sz[t] = g1z;
                sx[ntri + t] = g2x;
                sy[ntri + t] = g2y;
                sz[ntri + t] = g2z;
                sx[2 * ntri + t] = g3x;
                sy[2 * ntri + t] = g3y;
                sz[2 * ntri + t] = g3z;
            }
            e_blk[b] = eb;
            bad_t |= bad;
        }
    }
    if (bad_g | bad_h | bad_t)
        return CT_ERR_NONFINITE;

    /* Gather: each node sums its slots in increasing slot order, so the
     * result does not depend on the thread count. */
    const ct_idx *restrict snode = s->snode, *restrict off = s->slot_off, *restrict slot = s->slot;
#pragma omp parallel for schedule(static) if (par)
    for (ct_idx j = 0; j < s->nsnode; j++) {
        const ct_idx i = snode[j];
        ct_real gx = 0, gy = 0, gz = 0;
        for (ct_idx a = off[j]; a < off[j + 1]; a++) {
            ct_idx q = slot[a];
            gx += sx[q];
            gy += sy[q];
            gz += sz[q];
        }
        fx[i] += gx;
        fy[i] += gy;
        fz[i] += gz;
    }

    /* Energies: the blocks' sums added serially in block order (the
     * blocks do not depend on the thread count). */
    double em = 0, eb = 0;
    for (ct_idx b = 0; b < nbt; b++)
        em += e_blk[b];
    for (ct_idx b = 0; b < nbg + nbr; b++)
        eb += e_blk[nbt + b];
    s->e_membrane = em;
    s->e_bending = eb;
    if (energy)
        *energy = em + eb;
    return CT_OK;
}
