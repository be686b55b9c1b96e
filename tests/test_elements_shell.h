/*
 * test_elements_shell.h -- helpers shared by the shell tests
 * (test_elements_shell.c: membrane and bending; test_elements_shell_dynamics.c:
 * dynamics, threads, errors): plate meshes, the shell on them, forces, and
 * the node arrays of a run.
 */
#ifndef TEST_ELEMENTS_SHELL_H
#define TEST_ELEMENTS_SHELL_H

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#include "elements/shell.h"
#include "meshgen.h"
#include "test_util.h"

/* A plate mesh of nx x ny quads of size hx x hy from the origin. */
static inline void plate(ct_mesh *m, int nx, int ny, double hx, double hy)
{
    const double o[3] = {0, 0, 0};
    cr_assert_eq(ctd_plate(m, nx, ny, hx, hy, o, 0), CT_OK);
}

static inline void shell_on(ctd_shell *s, const ct_mesh *m, double E, double nu, double rho,
                     double t)
{
    cr_assert_eq(ctd_shell_init(s, m->nodes.n, m->nodes.x, m->nodes.y, m->nodes.z, m->nseg,
                                m->n1, m->n2, m->n3, m->n4, NULL, E, nu, rho, t),
                 CT_OK);
}

/* Forces at (x, y, z), zeroed first. */
static inline double forces(ctd_shell *s, const ct_real *x, const ct_real *y, const ct_real *z,
                     ct_real *fx, ct_real *fy, ct_real *fz)
{
    double e = 0;
    memset(fx, 0, sizeof(ct_real) * (size_t)s->nnode);
    memset(fy, 0, sizeof(ct_real) * (size_t)s->nnode);
    memset(fz, 0, sizeof(ct_real) * (size_t)s->nnode);
    cr_assert_eq(ctd_shell_forces(s, x, y, z, fx, fy, fz, &e), CT_OK);
    return e;
}

typedef struct work {
    ct_real *x, *y, *z, *fx, *fy, *fz, *vx, *vy, *vz, *m;
} work;

static inline void work_init(work *w, ct_idx n)
{
    ct_real **a[] = {&w->x, &w->y, &w->z, &w->fx, &w->fy, &w->fz, &w->vx, &w->vy, &w->vz, &w->m};
    for (int k = 0; k < 10; k++) {
        *a[k] = ct_calloc((size_t)n, sizeof(ct_real));
        cr_assert_not_null(*a[k]);
    }
}

static inline void work_free(work *w)
{
    ct_real *a[] = {w->x, w->y, w->z, w->fx, w->fy, w->fz, w->vx, w->vy, w->vz, w->m};
    for (int k = 0; k < 10; k++)
        ct_free(a[k]);
}

/* The flat nx x ny plate of cells hx x hy as shells, with its work arrays:
 * lumped masses in w->m, positions at the reference, velocities zero. */
static inline void plate_at_rest(ct_mesh *m, ctd_shell *s, work *w, int nx, int ny, double hx,
                                 double hy, double E, double nu, double rho, double t)
{
    plate(m, nx, ny, hx, hy);
    shell_on(s, m, E, nu, rho, t);
    work_init(w, m->nodes.n);
    ctd_shell_masses(s, w->m);
    for (ct_idx i = 0; i < m->nodes.n; i++) {
        w->x[i] = m->nodes.x[i];
        w->y[i] = m->nodes.y[i];
        w->z[i] = m->nodes.z[i];
    }
}

/* A curved reference (part of a cylinder), so hinges have theta0 != 0. */
static inline void curved(ct_mesh *m, int nx, int ny, double h, double R)
{
    plate(m, nx, ny, h, h);
    for (ct_idx i = 0; i < m->nodes.n; i++) {
        double s = m->nodes.x[i];
        m->nodes.x[i] = (ct_real)(R * sin(s / R));
        m->nodes.z[i] = (ct_real)(R * (1 - cos(s / R)));
    }
}

/* The forces at w's positions against central differences of the energy,
 * node by node and component by component (tolerance relative to the
 * largest force). */
static inline void expect_forces_are_energy_gradient(ctd_shell *s, work *w)
{
    const ct_idx n = s->nnode;
    forces(s, w->x, w->y, w->z, w->fx, w->fy, w->fz);
    ct_real *f0[3];
    for (int k = 0; k < 3; k++) {
        f0[k] = ct_calloc((size_t)n, sizeof(ct_real));
        cr_assert_not_null(f0[k]);
        memcpy(f0[k], k == 0 ? w->fx : k == 1 ? w->fy : w->fz, sizeof(ct_real) * (size_t)n);
    }
    double fmx = 0;
    for (ct_idx i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            fmx = fmax(fmx, fabs(f0[k][i]));
    cr_assert_gt(fmx, 0);
    const double h = CTT_TOL(1e-6, 1e-3), tol = CTT_TOL(1e-6, 3e-2);
    ct_real *xs[3] = {w->x, w->y, w->z};
    for (ct_idx i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            ct_real keep = xs[k][i];
            xs[k][i] = (ct_real)(keep + h);
            double ep = forces(s, w->x, w->y, w->z, w->fx, w->fy, w->fz);
            xs[k][i] = (ct_real)(keep - h);
            double em = forces(s, w->x, w->y, w->z, w->fx, w->fy, w->fz);
            xs[k][i] = keep;
            double fd = -(ep - em) / (2 * h);
            cr_expect_lt(fabs(fd - f0[k][i]), tol * fmx, "node %d comp %d: fd %g force %g",
                         (int)i, k, fd, (double)f0[k][i]);
        }
    for (int k = 0; k < 3; k++)
        ct_free(f0[k]);
}

#endif /* TEST_ELEMENTS_SHELL_H */
