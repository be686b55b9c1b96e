/*
 * test_iface_type356.h -- helpers shared by the TYPE3/5 tests
 * (test_iface_type356.c) and the TYPE6 tests (test_iface_type6.c).
 */
#ifndef TEST_IFACE_TYPE356_H
#define TEST_IFACE_TYPE356_H

#include <string.h>

#include "interfaces/iface.h"
#include "test_iface_util.h"
#include "test_util.h"

/* An interface from its card and data; asserts that it builds. */
static inline ctd_iface *make_iface(const ctd_iface_cfg *c, const ctd_iface_data *d)
{
    ctd_iface *it = NULL;
    ct_diag diag;
    memset(&diag, 0, sizeof diag);
    int rc = ctd_iface_init(&it, c, d, &diag);
    cr_assert_eq(rc, CT_OK, "init: %s (%s)", ct_strerror(rc), diag.msg);
    return it;
}

/* A sheared grid nx by ny at z = 0 (parallelograms, normal +z): node (i, j)
 * at (i + 0.3 j, j, 0). */
static inline void grid_segments(int nx, int ny, ct_idx off, int flip, ct_idx *q[4])
{
    ct_idx s = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            ct_idx a = off + (ct_idx)(j * (nx + 1) + i), b = a + 1;
            ct_idx c = b + (ct_idx)(nx + 1), e = a + (ct_idx)(nx + 1);
            q[0][s] = a;
            q[1][s] = flip ? e : b;
            q[2][s] = c;
            q[3][s] = flip ? b : e;
            s++;
        }
}

#endif /* TEST_IFACE_TYPE356_H */
