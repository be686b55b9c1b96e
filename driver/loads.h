/*
 * loads.h -- the external loads of a scene (prefix ctd_loads): nodal
 * forces and pressures on surfaces, each scaled by a piecewise-linear
 * function of time (scene.h, boundary kinds force and pressure).
 *
 * A force entry adds value x factor(t) to each of its nodes. A pressure
 * entry gives each of its segments the force -p factor(t) A, A the vector
 * area of the segment in its current geometry (a quad: (x3 - x1) x
 * (x4 - x2) / 2; a triangle: (x2 - x1) x (x3 - x1) / 2), shared equally by
 * its corners: a follower load, pushing against the segment's normal.
 *
 * The work of the loads is summed over the steps with the trapezoidal rule,
 * W += (F(n-1) + F(n)) . (x(n) - x(n-1)) / 2 on each loaded node: exact
 * for a constant load, and the work the central difference does with a
 * load that varies linearly within a step. Everything is serial and in a
 * fixed order (loads are few), so the result does not depend on the number
 * of threads; nothing is allocated after ctd_loads_init.
 */
#ifndef CTD_LOADS_H
#define CTD_LOADS_H

#include "contact.h"
#include "model.h"

#ifdef __cplusplus
extern "C" {
#endif

struct ctd_load;

typedef struct ctd_loads {
    int nload;
    struct ctd_load *load;
    /* The loaded nodes (sorted, unique) and, for each, the load at the last
     * call, the one before it and the position at the last call. */
    ct_idx nnode;
    ct_idx *node;
    ct_real *f[3], *fprev[3], *xprev[3];
    ct_idx *slot;  /* [model nodes] index into node[], or -1 */
    double work;   /* external work of the loads so far */
    int started;
} ctd_loads;

/* Resolve the scene's force and pressure entries on model m. CT_OK (also
 * with no load: nload 0), or a negative code with err naming the scene
 * file, line and boundary entry (e.g. a selection with nothing in it). */
int ctd_loads_init(ctd_loads *L, const ctd_model *m, char *err, size_t errlen);
void ctd_loads_destroy(ctd_loads *L);

/* The loads at time t on positions x, y, z (model node arrays), ADDED
 * into fx, fy, fz; the work of the step since the last call is added to
 * L->work. Call once per cycle. */
void ctd_loads_apply(ctd_loads *L, double t, const ct_real *x, const ct_real *y,
                     const ct_real *z, ct_real *fx, ct_real *fy, ct_real *fz);

/* The factor of a [time, factor] table of n points at time t (n 0: 1;
 * linear between points, constant outside them). */
double ctd_loads_factor(const double (*curve)[2], unsigned n, double t);

#ifdef __cplusplus
}
#endif

#endif /* CTD_LOADS_H */
