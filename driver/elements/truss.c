/*
 * truss.c -- two-node linear axial elements: trusses (k = E A / L0) and
 * springs (stiffness k). See elements.h.
 */
#include <stdlib.h>

#include "ct_internal.h"
#include "elements.h"

void ctd_truss_destroy(ctd_truss *t)
{
    if (!t)
        return;
    ct_free(t->n1);
    ct_free(t->n2);
    ct_free(t->L0);
    ct_free(t->k);
    ct_free(t->mass);
    ct_free(t->c);
    ct_free(t->eint);
    for (int d = 0; d < 3; d++)
        ct_free(t->s[d]);
    ctd_gather_destroy(&t->g);
    memset(t, 0, sizeof *t);
}

int ctd_truss_init(ctd_truss *t, ct_idx n, const ct_idx *n1, const ct_idx *n2, ct_idx nnode,
                   const ct_real *x, const ct_real *y, const ct_real *z, ct_diag *diag)
{
    if (!t || n < 0 || nnode < 0 || (n > 0 && (!n1 || !n2 || !x || !y || !z)))
        return cti_fail(diag, CT_ERR_ARG, -1, "Bad arguments to ctd_truss_init.");
    memset(t, 0, sizeof *t);
    const size_t ne = (size_t)n + 1;
    t->n1 = ct_calloc(ne, sizeof *t->n1);
    t->n2 = ct_calloc(ne, sizeof *t->n2);
    t->L0 = ct_calloc(ne, sizeof *t->L0);
    t->k = ct_calloc(ne, sizeof *t->k);
    t->mass = ct_calloc(ne, sizeof *t->mass);
    t->c = ct_calloc(ne, sizeof *t->c);
    t->eint = ct_calloc(ne, sizeof *t->eint);
    int ok = t->n1 && t->n2 && t->L0 && t->k && t->mass && t->c && t->eint;
    for (int d = 0; d < 3; d++) {
        t->s[d] = ct_calloc(2 * ne, sizeof *t->s[d]);
        ok = ok && t->s[d];
    }
    if (!ok) {
        ctd_truss_destroy(t);
        return cti_fail(diag, CT_ERR_NOMEM, -1, "Out of memory for %d truss elements.", (int)n);
    }
    t->n = n;
    t->nnode = nnode;
    for (ct_idx e = 0; e < n; e++) {
        ct_idx a = n1[e], b = n2[e];
        if (a < 0 || a >= nnode || b < 0 || b >= nnode) {
            ctd_truss_destroy(t);
            return cti_fail(diag, CT_ERR_RANGE, e,
                            "Truss element %d refers to a node outside [0, %d).", (int)e,
                            (int)nnode);
        }
        if (a == b) {
            ctd_truss_destroy(t);
            return cti_fail(diag, CT_ERR_DUPNODE, e, "Truss element %d joins node %d to itself.",
                            (int)e, (int)a);
        }
        ct_real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
        ct_real L = CTI_SQRT(dx * dx + dy * dy + dz * dz);
        if (!(L > 0)) {
            ctd_truss_destroy(t);
            return cti_fail(diag, CT_ERR_DEGENERATE, e, "Truss element %d has zero length.",
                            (int)e);
        }
        t->n1[e] = a;
        t->n2[e] = b;
        t->L0[e] = L;
    }
    const ct_idx *conn[2] = {t->n1, t->n2};
    int rc = ctd_gather_build(&t->g, n, 2, conn, 1, nnode, diag);
    if (rc != CT_OK)
        ctd_truss_destroy(t);
    return rc;
}

int ctd_truss_set_truss(ctd_truss *t, ct_idx first, ct_idx count, ct_real A, ct_real E,
                        ct_real rho)
{
    if (!t || first < 0 || count < 0 || first > t->n - count || !(A > 0) || !(E > 0) ||
        !(rho > 0))
        return CT_ERR_ARG;
    for (ct_idx e = first; e < first + count; e++) {
        t->k[e] = E * A / t->L0[e];
        t->mass[e] = rho * A * t->L0[e];
        t->c[e] = CTI_SQRT(E / rho);
    }
    return CT_OK;
}

int ctd_truss_set_spring(ctd_truss *t, ct_idx first, ct_idx count, ct_real k)
{
    if (!t || first < 0 || count < 0 || first > t->n - count || !(k > 0))
        return CT_ERR_ARG;
    for (ct_idx e = first; e < first + count; e++) {
        t->k[e] = k;
        t->mass[e] = 0;
        t->c[e] = 0;
    }
    return CT_OK;
}

void ctd_truss_mass(const ctd_truss *t, ct_real *m)
{
    for (ct_idx e = 0; e < t->n; e++) {
        m[t->n1[e]] += t->mass[e] / 2;
        m[t->n2[e]] += t->mass[e] / 2;
    }
}

/* The element loop: slot 0 (node n1) receives +N u, slot 1 (node n2) -N u,
 * u the unit vector from n1 to n2, N = k (L - L0). Returns the number of
 * elements whose length is zero or not finite (their slots are zero, their
 * energy -1). */
static ct_idx truss_slots(ct_idx n, const ct_idx *CT_RESTRICT n1, const ct_idx *CT_RESTRICT n2,
                          const ct_real *CT_RESTRICT L0, const ct_real *CT_RESTRICT k,
                          const ct_real *CT_RESTRICT x, const ct_real *CT_RESTRICT y,
                          const ct_real *CT_RESTRICT z, ct_real *CT_RESTRICT sx,
                          ct_real *CT_RESTRICT sy, ct_real *CT_RESTRICT sz,
                          ct_real *CT_RESTRICT eint)
{
    CTI_PAR_FOR_SIMD(n > CTD_PAR_MIN, (schedule(static)),
    for (ct_idx e = 0; e < n; e++) {
        ct_idx a = n1[e], b = n2[e];
        ct_real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
        ct_real L = CTI_SQRT(dx * dx + dy * dy + dz * dz);
        /* Branch-free: a bad length gives zero slots and is counted. */
        int ok = (L > 0) & (L < CTI_HUGE);
        ct_real d = ok ? L - L0[e] : 0;
        ct_real s = k[e] * d / (ok ? L : 1);
        sx[e] = s * dx;
        sy[e] = s * dy;
        sz[e] = s * dz;
        sx[n + e] = -s * dx;
        sy[n + e] = -s * dy;
        sz[n + e] = -s * dz;
        eint[e] = ok ? k[e] * d * d / 2 : -1;
    });
    /* A negative energy marks a bad element. */
    ct_idx nbad = 0;
    CTI_PAR_FOR(n > CTD_PAR_MIN, (schedule(static) reduction(+ : nbad)),
    for (ct_idx e = 0; e < n; e++)
        nbad += eint[e] < 0;
    );
    return nbad;
}

int ctd_truss_forces(ctd_truss *t, const ct_real *CT_RESTRICT x, const ct_real *CT_RESTRICT y,
                     const ct_real *CT_RESTRICT z, ct_real *CT_RESTRICT fx,
                     ct_real *CT_RESTRICT fy, ct_real *CT_RESTRICT fz, ct_diag *diag)
{
    if (!t || (t->n > 0 && (!x || !y || !z || !fx || !fy || !fz)))
        return CT_ERR_ARG;
    ct_idx nbad = truss_slots(t->n, t->n1, t->n2, t->L0, t->k, x, y, z, t->s[0], t->s[1],
                              t->s[2], t->eint);
    if (nbad > 0) {
        /* Report the first bad element (serial scan, rare path). */
        ct_idx e = 0;
        for (; e < t->n; e++) {
            ct_idx a = t->n1[e], b = t->n2[e];
            ct_real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
            ct_real L = CTI_SQRT(dx * dx + dy * dy + dz * dz);
            if (!(L > 0 && L < CTI_HUGE))
                break;
        }
        ct_idx a = t->n1[e], b = t->n2[e];
        ct_real l2 = (x[b] - x[a]) * (x[b] - x[a]) + (y[b] - y[a]) * (y[b] - y[a]) +
                     (z[b] - z[a]) * (z[b] - z[a]);
        int nonfinite = !(l2 == l2) || l2 >= CTI_HUGE;
        return cti_fail(diag, nonfinite ? CT_ERR_NONFINITE : CT_ERR_DEGENERATE, e,
                        "Truss element %d has a %s length.", (int)e,
                        nonfinite ? "non-finite" : "zero");
    }
    ctd_gather_add(&t->g, t->s[0], t->s[1], t->s[2], fx, fy, fz);
    return CT_OK;
}

double ctd_truss_energy(const ctd_truss *t)
{
    double s = 0;
    for (ct_idx e = 0; e < t->n; e++)
        s += t->eint[e];
    return s;
}

ct_real ctd_truss_dt(const ctd_truss *t, const ct_real *x, const ct_real *y, const ct_real *z,
                     const ct_real *m, ct_idx *imin)
{
    ct_real best = CTD_DT_NONE;
    ct_idx arg = -1;
    /* Serial scan: the first element reaching the minimum is reported,
     * whatever the thread count. */
    for (ct_idx e = 0; e < t->n; e++) {
        ct_idx a = t->n1[e], b = t->n2[e];
        ct_real dt;
        if (t->c[e] > 0) {
            ct_real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
            dt = CTI_SQRT(dx * dx + dy * dy + dz * dz) / t->c[e];
        } else if (t->k[e] > 0) {
            dt = CTI_SQRT(CTI_MIN(m[a], m[b]) / t->k[e]);
        } else {
            continue;
        }
        if (dt < best || arg < 0) {
            best = dt;
            arg = e;
        }
    }
    if (imin)
        *imin = arg;
    return best;
}
