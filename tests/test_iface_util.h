/*
 * test_iface_util.h -- what the interface tests share: node arrays of a
 * test (positions, velocities, unit masses, forces) and one step of an
 * interface with the forces zeroed first.
 */
#ifndef TEST_IFACE_UTIL_H
#define TEST_IFACE_UTIL_H

#include <string.h>

#include "test_util.h"
#include "interfaces/iface.h"

typedef struct tnodes {
    ct_idx n;
    ct_real *x, *y, *z, *vx, *vy, *vz, *m, *fx, *fy, *fz;
} tnodes;

static inline void tn_init(tnodes *t, ct_idx n)
{
    t->n = n;
    ct_real **a[10] = {&t->x, &t->y, &t->z, &t->vx, &t->vy, &t->vz, &t->m, &t->fx, &t->fy, &t->fz};
    for (int i = 0; i < 10; i++) {
        *a[i] = ct_calloc((size_t)n, sizeof(ct_real));
        cr_assert(*a[i]);
    }
    for (ct_idx i = 0; i < n; i++)
        t->m[i] = 1;
}

static inline void tn_free(tnodes *t)
{
    ct_real *a[10] = {t->x, t->y, t->z, t->vx, t->vy, t->vz, t->m, t->fx, t->fy, t->fz};
    for (int i = 0; i < 10; i++)
        ct_free(a[i]);
}

static inline void tn_set(tnodes *t, ct_idx i, double x, double y, double z)
{
    t->x[i] = (ct_real)x;
    t->y[i] = (ct_real)y;
    t->z[i] = (ct_real)z;
}

/* Zero the forces, run one step, check the status. */
static inline void tstep(ctd_iface *it, tnodes *t, double time, double dt, ctd_iface_report *rep)
{
    memset(t->fx, 0, sizeof(ct_real) * (size_t)t->n);
    memset(t->fy, 0, sizeof(ct_real) * (size_t)t->n);
    memset(t->fz, 0, sizeof(ct_real) * (size_t)t->n);
    int rc = ctd_iface_step(it, time, (ct_real)dt, t->x, t->y, t->z, t->vx, t->vy, t->vz, t->m,
                            t->fx, t->fy, t->fz, rep);
    cr_assert_eq(rc, CT_OK, "step: %s", ct_strerror(rc));
}

/* Sum of a nodal force component over n nodes. */
static inline double fsum(const ct_real *f, ct_idx n)
{
    double s = 0;
    for (ct_idx i = 0; i < n; i++)
        s += (double)f[i];
    return s;
}

/* The interface data of one edge pair over four nodes: edge A from node 0
 * to node 1, edge B from node 2 to node 3, node gaps g (4). */
static inline ctd_iface_data edge_pair_data(const ct_real g[4])
{
    static const ct_idx a1[1] = {0}, a2[1] = {1}, b1[1] = {2}, b2[1] = {3};
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 4;
    d.nea = 1;
    d.ea1 = a1;
    d.ea2 = a2;
    d.neb = 1;
    d.eb1 = b1;
    d.eb2 = b2;
    d.gap_node = g;
    return d;
}

#endif /* TEST_IFACE_UTIL_H */
