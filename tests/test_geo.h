/*
 * test_geo.h -- the narrow phase's output arrays (ct_contact_geo) for n
 * pairs, allocated and freed by the narrow-phase tests (test_project*.c,
 * test_narrow_packed.c).
 */
#ifndef TEST_GEO_H
#define TEST_GEO_H

#include "test_util.h"

enum { CTT_GEO_NF = 13 }; /* real fields of ct_contact_geo */

typedef struct ctt_geo {
    ct_contact_geo g;
    ct_real *f[CTT_GEO_NF]; /* the same arrays, in the order of the struct */
} ctt_geo;

static inline void ctt_geo_init(ctt_geo *o, ct_idx n)
{
    ct_real **p[CTT_GEO_NF] = {&o->g.dist, &o->g.pen, &o->g.nx, &o->g.ny, &o->g.nz,
                               &o->g.cx,   &o->g.cy,  &o->g.cz, &o->g.h1, &o->g.h2,
                               &o->g.h3,   &o->g.h4,  &o->g.gap};
    for (int i = 0; i < CTT_GEO_NF; i++) {
        *p[i] = o->f[i] = ct_calloc((size_t)n + 1, sizeof(ct_real));
        cr_assert_not_null(o->f[i]);
    }
    o->g.flag = ct_calloc((size_t)n + 1, 1);
    cr_assert_not_null(o->g.flag);
}

static inline void ctt_geo_free(ctt_geo *o)
{
    for (int i = 0; i < CTT_GEO_NF; i++)
        ct_free(o->f[i]);
    ct_free(o->g.flag);
}

#endif
