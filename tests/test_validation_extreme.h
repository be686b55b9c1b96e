/*
 * test_validation_extreme.h -- what the extreme cases share (suites
 * validation_extreme): node arrays with the output fields, one interface
 * step with every result checked finite, and an interface made or the test
 * fails.
 */
#ifndef TEST_VALIDATION_EXTREME_H
#define TEST_VALIDATION_EXTREME_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "interfaces/build.h"
#include "interfaces/iface.h"
#include "test_util.h"

typedef struct nodes {
    ct_idx n;
    ct_real *x, *y, *z, *vx, *vy, *vz, *m, *fx, *fy, *fz, *pen;
    int32_t *nact;
} nodes;

/* n nodes at the origin, at rest, of mass 1. */
static inline void nodes_init(nodes *p, ct_idx n)
{
    memset(p, 0, sizeof *p);
    p->n = n;
    ct_real **a[11] = {&p->x,  &p->y,  &p->z,  &p->vx, &p->vy, &p->vz,
                       &p->m,  &p->fx, &p->fy, &p->fz, &p->pen};
    for (int i = 0; i < 11; i++)
        cr_assert((*a[i] = ct_calloc((size_t)n, sizeof(ct_real))) != NULL);
    cr_assert((p->nact = ct_calloc((size_t)n, sizeof(int32_t))) != NULL);
    for (ct_idx i = 0; i < n; i++)
        p->m[i] = 1;
}

static inline void nodes_free(nodes *p)
{
    ct_real *a[11] = {p->x, p->y, p->z, p->vx, p->vy, p->vz, p->m, p->fx, p->fy, p->fz, p->pen};
    for (int i = 0; i < 11; i++)
        ct_free(a[i]);
    ct_free(p->nact);
}

static inline void nodes_set(nodes *p, ct_idx i, double x, double y, double z)
{
    p->x[i] = (ct_real)x;
    p->y[i] = (ct_real)y;
    p->z[i] = (ct_real)z;
}

/* One step at `time` with step dt (forces and fields zeroed first), the
 * output fields filled, every force and penetration checked finite. */
static inline void nodes_step(ctd_iface *it, nodes *p, double time, double dt,
                              ctd_iface_report *rep)
{
    size_t b = sizeof(ct_real) * (size_t)p->n;
    memset(p->fx, 0, b);
    memset(p->fy, 0, b);
    memset(p->fz, 0, b);
    memset(p->pen, 0, b);
    memset(p->nact, 0, sizeof(int32_t) * (size_t)p->n);
    int rc = ctd_iface_step(it, time, (ct_real)dt, p->x, p->y, p->z, p->vx, p->vy, p->vz, p->m,
                            p->fx, p->fy, p->fz, rep);
    cr_assert_eq(rc, CT_OK, "step: %s", ct_strerror(rc));
    ctd_iface_fields(it, p->pen, p->nact);
    for (ct_idx i = 0; i < p->n; i++)
        cr_assert(isfinite(p->fx[i]) && isfinite(p->fy[i]) && isfinite(p->fz[i]) &&
                      isfinite(p->pen[i]),
                  "node %d: a non-finite force or penetration", (int)i);
    cr_assert(isfinite(rep->e_contact));
}

static inline ctd_iface *make(const ctd_iface_cfg *c, const ctd_iface_data *d)
{
    ctd_iface *it = NULL;
    ct_diag dg = {0, -1, ""};
    int rc = ctd_iface_init(&it, c, d, &dg);
    cr_assert_eq(rc, CT_OK, "init: %s: %s", ct_strerror(rc), dg.msg);
    return it;
}

#endif /* TEST_VALIDATION_EXTREME_H */
