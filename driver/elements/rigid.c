/*
 * rigid.c -- rigid bodies made of nodes: mass properties, force and moment
 * assembly, and a kick-drift step whose rotation part is the implicit
 * midpoint rule of Euler's equations with a Cayley rotation update. See
 * elements.h for the scheme and its conservation properties.
 *
 * The body state is kept in double precision whatever ct_real is.
 */
#include <stdlib.h>

#include "ct_internal.h"
#include "elements.h"

/* ---- Small 3 x 3 helpers ------------------------------------------------ */

static void cross(const double a[3], const double b[3], double c[3])
{
    double t0 = a[1] * b[2] - a[2] * b[1];
    double t1 = a[2] * b[0] - a[0] * b[2];
    double t2 = a[0] * b[1] - a[1] * b[0];
    c[0] = t0;
    c[1] = t1;
    c[2] = t2;
}

/* y = R x, y = R^T x (R row-major). */
static void mulv(const double R[9], const double x[3], double y[3])
{
    double t[3];
    for (int i = 0; i < 3; i++)
        t[i] = R[3 * i] * x[0] + R[3 * i + 1] * x[1] + R[3 * i + 2] * x[2];
    y[0] = t[0];
    y[1] = t[1];
    y[2] = t[2];
}

static void mulvt(const double R[9], const double x[3], double y[3])
{
    double t[3];
    for (int i = 0; i < 3; i++)
        t[i] = R[i] * x[0] + R[3 + i] * x[1] + R[6 + i] * x[2];
    y[0] = t[0];
    y[1] = t[1];
    y[2] = t[2];
}

static void quat_to_matrix(const double q[4], double R[9])
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    R[0] = 1 - 2 * (y * y + z * z);
    R[1] = 2 * (x * y - w * z);
    R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z);
    R[4] = 1 - 2 * (x * x + z * z);
    R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y);
    R[7] = 2 * (y * z + w * x);
    R[8] = 1 - 2 * (x * x + y * y);
}

/* Shepperd's method: the largest of the four candidates is the pivot. */
static void matrix_to_quat(const double R[9], double q[4])
{
    double tr = R[0] + R[4] + R[8];
    if (tr >= R[0] && tr >= R[4] && tr >= R[8]) {
        double s = 2 * sqrt(1 + tr);
        q[0] = s / 4;
        q[1] = (R[7] - R[5]) / s;
        q[2] = (R[2] - R[6]) / s;
        q[3] = (R[3] - R[1]) / s;
    } else if (R[0] >= R[4] && R[0] >= R[8]) {
        double s = 2 * sqrt(1 + R[0] - R[4] - R[8]);
        q[0] = (R[7] - R[5]) / s;
        q[1] = s / 4;
        q[2] = (R[1] + R[3]) / s;
        q[3] = (R[2] + R[6]) / s;
    } else if (R[4] >= R[8]) {
        double s = 2 * sqrt(1 + R[4] - R[0] - R[8]);
        q[0] = (R[2] - R[6]) / s;
        q[1] = (R[1] + R[3]) / s;
        q[2] = s / 4;
        q[3] = (R[5] + R[7]) / s;
    } else {
        double s = 2 * sqrt(1 + R[8] - R[0] - R[4]);
        q[0] = (R[3] - R[1]) / s;
        q[1] = (R[2] + R[6]) / s;
        q[2] = (R[5] + R[7]) / s;
        q[3] = s / 4;
    }
    double nq = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int i = 0; i < 4; i++)
        q[i] /= nq;
}

/* Cyclic Jacobi for a symmetric 3 x 3 matrix A (destroyed): eigenvalues in
 * d, eigenvectors in the columns of V (row-major), det V = +1. */
static void jacobi3(double A[9], double d[3], double V[9])
{
    for (int i = 0; i < 9; i++)
        V[i] = (i % 4 == 0);
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
        double diag = A[0] * A[0] + A[4] * A[4] + A[8] * A[8];
        if (off <= 1e-36 * diag || off == 0)
            break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                double apq = A[3 * p + q];
                if (apq == 0)
                    continue;
                double theta = (A[3 * q + q] - A[3 * p + p]) / (2 * apq);
                double t = (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
                double c = 1 / sqrt(t * t + 1), s = t * c;
                /* A <- G^T A G with G the rotation in the (p, q) plane. */
                for (int k = 0; k < 3; k++) {
                    double akp = A[3 * k + p], akq = A[3 * k + q];
                    A[3 * k + p] = c * akp - s * akq;
                    A[3 * k + q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {
                    double apk = A[3 * p + k], aqk = A[3 * q + k];
                    A[3 * p + k] = c * apk - s * aqk;
                    A[3 * q + k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    double vkp = V[3 * k + p], vkq = V[3 * k + q];
                    V[3 * k + p] = c * vkp - s * vkq;
                    V[3 * k + q] = s * vkp + c * vkq;
                }
            }
    }
    d[0] = A[0];
    d[1] = A[4];
    d[2] = A[8];
    double det = V[0] * (V[4] * V[8] - V[5] * V[7]) - V[1] * (V[3] * V[8] - V[5] * V[6]) +
                 V[2] * (V[3] * V[7] - V[4] * V[6]);
    if (det < 0)
        for (int k = 0; k < 3; k++)
            V[3 * k + 2] = -V[3 * k + 2];
}

/* ---- Body -------------------------------------------------------------- */

void ctd_rigid_destroy(ctd_rigid *r)
{
    if (!r)
        return;
    ct_free(r->node);
    for (int d = 0; d < 3; d++)
        ct_free(r->rb[d]);
    memset(r, 0, sizeof *r);
}

void ctd_rigid_rotation(const ctd_rigid *r, double R[9]) { quat_to_matrix(r->q, R); }

void ctd_rigid_inertia_world(const ctd_rigid *r, double J[9])
{
    double R[9];
    quat_to_matrix(r->q, R);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            J[3 * i + j] = R[3 * i] * r->I[0] * R[3 * j] + R[3 * i + 1] * r->I[1] * R[3 * j + 1] +
                           R[3 * i + 2] * r->I[2] * R[3 * j + 2];
}

/* World angular velocity from L at the current orientation. */
static void omega_of(const ctd_rigid *r, const double R[9], double w[3])
{
    double pi[3];
    mulvt(R, r->L, pi);
    for (int k = 0; k < 3; k++)
        pi[k] *= r->Iinv[k];
    mulv(R, pi, w);
}

int ctd_rigid_init(ctd_rigid *r, ct_idx n, const ct_idx *node, ct_idx nnode, const ct_real *m,
                   const ct_real *x, const ct_real *y, const ct_real *z, const ct_real *vx,
                   const ct_real *vy, const ct_real *vz)
{
    if (!r || n < 1 || !node || !m || !x || !y || !z)
        return CT_ERR_ARG;
    memset(r, 0, sizeof *r);
    double M = 0, s[3] = {0, 0, 0}, p[3] = {0, 0, 0};
    for (ct_idx i = 0; i < n; i++) {
        ct_idx v = node[i];
        if (v < 0 || v >= nnode)
            return CT_ERR_RANGE;
        M += m[v];
        s[0] += m[v] * (double)x[v];
        s[1] += m[v] * (double)y[v];
        s[2] += m[v] * (double)z[v];
        if (vx && vy && vz) {
            p[0] += m[v] * (double)vx[v];
            p[1] += m[v] * (double)vy[v];
            p[2] += m[v] * (double)vz[v];
        }
    }
    if (!(M > 0))
        return CT_ERR_ARG;
    r->node = ct_calloc((size_t)n, sizeof *r->node);
    for (int d = 0; d < 3; d++)
        r->rb[d] = ct_calloc((size_t)n, sizeof *r->rb[d]);
    if (!r->node || !r->rb[0] || !r->rb[1] || !r->rb[2]) {
        ctd_rigid_destroy(r);
        return CT_ERR_NOMEM;
    }
    r->n = n;
    memcpy(r->node, node, (size_t)n * sizeof *node);
    r->mass = M;
    for (int d = 0; d < 3; d++) {
        r->xc[d] = s[d] / M;
        r->vc[d] = p[d] / M;
    }
    /* Inertia tensor and angular momentum about the centre. */
    double J[9] = {0};
    for (ct_idx i = 0; i < n; i++) {
        ct_idx v = node[i];
        double rr[3] = {x[v] - r->xc[0], y[v] - r->xc[1], z[v] - r->xc[2]};
        double r2 = rr[0] * rr[0] + rr[1] * rr[1] + rr[2] * rr[2];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                J[3 * a + b] += m[v] * ((a == b) * r2 - rr[a] * rr[b]);
        if (vx && vy && vz) {
            double dv[3] = {vx[v] - r->vc[0], vy[v] - r->vc[1], vz[v] - r->vc[2]}, l[3];
            cross(rr, dv, l);
            for (int d = 0; d < 3; d++)
                r->L[d] += m[v] * l[d];
        }
    }
    double V[9];
    jacobi3(J, r->I, V);
    double imax = fmax(r->I[0], fmax(r->I[1], r->I[2]));
    for (int k = 0; k < 3; k++)
        r->Iinv[k] = r->I[k] > 1e-12 * imax && r->I[k] > 0 ? 1 / r->I[k] : 0;
    matrix_to_quat(V, r->q);
    double R[9];
    quat_to_matrix(r->q, R);
    for (ct_idx i = 0; i < n; i++) {
        ct_idx v = node[i];
        double rr[3] = {x[v] - r->xc[0], y[v] - r->xc[1], z[v] - r->xc[2]}, b[3];
        mulvt(R, rr, b);
        for (int d = 0; d < 3; d++)
            r->rb[d][i] = (ct_real)b[d];
    }
    omega_of(r, R, r->omega);
    return CT_OK;
}

void ctd_rigid_set_velocity(ctd_rigid *r, const double v[3], const double w[3])
{
    double R[9], b[3];
    quat_to_matrix(r->q, R);
    mulvt(R, w, b);
    for (int k = 0; k < 3; k++)
        b[k] *= r->I[k];
    mulv(R, b, r->L);
    for (int d = 0; d < 3; d++)
        r->vc[d] = v[d];
    omega_of(r, R, r->omega);
}

void ctd_rigid_clear(ctd_rigid *r)
{
    for (int d = 0; d < 3; d++)
        r->F[d] = r->tau[d] = 0;
}

void ctd_rigid_accumulate(ctd_rigid *r, const ct_real *x, const ct_real *y, const ct_real *z,
                          const ct_real *fx, const ct_real *fy, const ct_real *fz)
{
    double F[3] = {0, 0, 0}, T[3] = {0, 0, 0};
    for (ct_idx i = 0; i < r->n; i++) {
        ct_idx v = r->node[i];
        double f[3] = {fx[v], fy[v], fz[v]};
        double rr[3] = {x[v] - r->xc[0], y[v] - r->xc[1], z[v] - r->xc[2]}, t[3];
        cross(rr, f, t);
        for (int d = 0; d < 3; d++) {
            F[d] += f[d];
            T[d] += t[d];
        }
    }
    for (int d = 0; d < 3; d++) {
        r->F[d] += F[d];
        r->tau[d] += T[d];
    }
}

int ctd_rigid_advance(ctd_rigid *r, double dt)
{
    if (!(dt >= 0))
        return CT_ERR_ARG;
    /* Kick. */
    for (int d = 0; d < 3; d++) {
        r->vc[d] += dt * r->F[d] / r->mass;
        r->L[d] += dt * r->tau[d];
        r->xc[d] += dt * r->vc[d];
    }
    /* Torque-free rotation: implicit midpoint in the body frame. */
    double R[9], pi0[3], pm[3], w[3];
    quat_to_matrix(r->q, R);
    mulvt(R, r->L, pi0);
    double scale = sqrt(pi0[0] * pi0[0] + pi0[1] * pi0[1] + pi0[2] * pi0[2]);
    pm[0] = pi0[0];
    pm[1] = pi0[1];
    pm[2] = pi0[2];
    /* The iteration contracts by about |omega| dt per pass; it stops at
     * round-off, or when the change stops decreasing at round-off level. */
    int it = 0, conv = scale == 0;
    double prev = HUGE_VAL;
    while (!conv && it < 100) {
        double om[3] = {pm[0] * r->Iinv[0], pm[1] * r->Iinv[1], pm[2] * r->Iinv[2]}, c[3];
        cross(pm, om, c);
        double diff = 0;
        for (int d = 0; d < 3; d++) {
            double nv = pi0[d] + dt / 2 * c[d];
            diff = fmax(diff, fabs(nv - pm[d]));
            pm[d] = nv;
        }
        it++;
        conv = diff <= 1e-15 * scale || (diff >= prev && diff <= 1e-13 * scale);
        prev = diff;
    }
    r->iters = it;
    if (!conv)
        return CT_ERR_NOCONV;
    for (int d = 0; d < 3; d++)
        w[d] = dt * pm[d] * r->Iinv[d];
    /* q <- q (1, w/2), normalised: the Cayley rotation. */
    double h[4] = {1, w[0] / 2, w[1] / 2, w[2] / 2};
    const double *q = r->q;
    double nq[4] = {q[0] * h[0] - q[1] * h[1] - q[2] * h[2] - q[3] * h[3],
                    q[0] * h[1] + q[1] * h[0] + q[2] * h[3] - q[3] * h[2],
                    q[0] * h[2] - q[1] * h[3] + q[2] * h[0] + q[3] * h[1],
                    q[0] * h[3] + q[1] * h[2] - q[2] * h[1] + q[3] * h[0]};
    double norm = sqrt(nq[0] * nq[0] + nq[1] * nq[1] + nq[2] * nq[2] + nq[3] * nq[3]);
    if (!(norm > 0 && norm < 1e300))
        return CT_ERR_NONFINITE;
    for (int k = 0; k < 4; k++)
        r->q[k] = nq[k] / norm;
    /* The step's angular velocity (w is on Q's axis: R_n w = R_n+1 w). */
    if (dt > 0) {
        double wb[3] = {w[0] / dt, w[1] / dt, w[2] / dt};
        mulv(R, wb, r->omega);
    }
    for (int d = 0; d < 3; d++)
        if (!isfinite(r->xc[d]) || !isfinite(r->vc[d]) || !isfinite(r->L[d]))
            return CT_ERR_NONFINITE;
    return CT_OK;
}

void ctd_rigid_set_nodes(const ctd_rigid *r, ct_real *x, ct_real *y, ct_real *z, ct_real *vx,
                         ct_real *vy, ct_real *vz)
{
    double R[9];
    quat_to_matrix(r->q, R);
    for (ct_idx i = 0; i < r->n; i++) {
        ct_idx v = r->node[i];
        double b[3] = {r->rb[0][i], r->rb[1][i], r->rb[2][i]}, rr[3], wr[3];
        mulv(R, b, rr);
        x[v] = (ct_real)(r->xc[0] + rr[0]);
        y[v] = (ct_real)(r->xc[1] + rr[1]);
        z[v] = (ct_real)(r->xc[2] + rr[2]);
        if (vx && vy && vz) {
            cross(r->omega, rr, wr);
            vx[v] = (ct_real)(r->vc[0] + wr[0]);
            vy[v] = (ct_real)(r->vc[1] + wr[1]);
            vz[v] = (ct_real)(r->vc[2] + wr[2]);
        }
    }
}

double ctd_rigid_kinetic(const ctd_rigid *r)
{
    double R[9], pi[3];
    quat_to_matrix(r->q, R);
    mulvt(R, r->L, pi);
    double t = r->mass * (r->vc[0] * r->vc[0] + r->vc[1] * r->vc[1] + r->vc[2] * r->vc[2]);
    for (int k = 0; k < 3; k++)
        t += pi[k] * pi[k] * r->Iinv[k];
    return t / 2;
}

void ctd_rigid_momentum(const ctd_rigid *r, double p[3], double Lo[3])
{
    double pp[3] = {r->mass * r->vc[0], r->mass * r->vc[1], r->mass * r->vc[2]};
    if (p)
        for (int d = 0; d < 3; d++)
            p[d] = pp[d];
    if (Lo) {
        double c[3];
        cross(r->xc, pp, c);
        for (int d = 0; d < 3; d++)
            Lo[d] = c[d] + r->L[d];
    }
}
