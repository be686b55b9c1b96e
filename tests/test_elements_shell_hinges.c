/*
 * test_elements_shell_hinges.c -- the hinge forces as the shell computes
 * them (driver/elements/shell_forces.c): each hinge's force folded onto its
 * two triangles along their normals, signed by the triangles' orientation,
 * with the shell's own vectorisable atan2. Checked against libm's atan2,
 * against finite differences of the energy on a mesh that mixes triangles
 * and quads, reversed elements and thicknesses, and against the same mesh
 * with every element in one orientation (the physics does not know the
 * node order of an element).
 */
#include "test_elements_shell.h"

#include <float.h>
#include <stdint.h>

/* ---- atan2 -------------------------------------------------------------- */

Test(elements_shell_hinges, atan2_matches_libm)
{
    /* Every octant, ratios from 1e-30 to 1e30, the boundaries between the
     * series' two ranges (tan(pi/8)) and between octants (|y| = |x|). */
    const double mags[] = {0,     1e-30, 1e-8, 0.1,    0.41421356237309503,
                           0.4142135623730951, 0.41421356237309515, 0.5, 0.999999, 1,
                           1.000001, 2, 2.414213562373095, 7, 1e8, 1e30};
    const int nm = (int)(sizeof mags / sizeof mags[0]);
    double worst = 0;
    for (int i = 0; i < nm; i++)
        for (int sy = -1; sy <= 1; sy += 2)
            for (int sx = -1; sx <= 1; sx += 2) {
                double y = sy * mags[i], x = sx * 1.0;
                double a = (double)ctd_shell_atan2((ct_real)y, (ct_real)x);
                double b = atan2((double)(ct_real)y, (double)(ct_real)x);
                worst = fmax(worst, fabs(a - b));
                /* The same ratio the other way round. */
                a = (double)ctd_shell_atan2((ct_real)x, (ct_real)y);
                b = atan2((double)(ct_real)x, (double)(ct_real)y);
                worst = fmax(worst, fabs(a - b));
            }
    /* Pseudo-random points on a circle and beyond (a fixed generator). */
    uint64_t r = 0x9E3779B97F4A7C15ull;
    for (int k = 0; k < 200000; k++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        double u = (double)(r >> 11) / 9007199254740992.0;
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        double v = (double)(r >> 11) / 9007199254740992.0;
        ct_real y = (ct_real)((2 * u - 1) * pow(10, 6 * v - 3));
        ct_real x = (ct_real)(2 * v - 1);
        double a = (double)ctd_shell_atan2(y, x), b = atan2((double)y, (double)x);
        worst = fmax(worst, fabs(a - b));
    }
    /* A few units in the last place of pi (the result's largest value). */
    cr_expect_lt(worst, CTT_TOL(8 * DBL_EPSILON, 8 * FLT_EPSILON), "largest difference %g",
                 worst);
    /* Signed zeros and NaN, as atan2. */
    cr_expect_eq(ctd_shell_atan2(0, 1), 0);
    cr_expect(signbit(ctd_shell_atan2(-(ct_real)0, 1)));
    cr_expect_eq(ctd_shell_atan2(0, 0), 0);
    cr_expect(fabs((double)ctd_shell_atan2(0, -(ct_real)0) - M_PI) < CTT_TOL(1e-15, 1e-6));
    cr_expect(fabs((double)ctd_shell_atan2(-(ct_real)0, -1) + M_PI) < CTT_TOL(1e-15, 1e-6));
    cr_expect(fabs((double)ctd_shell_atan2(1, 0) - M_PI / 2) < CTT_TOL(1e-15, 1e-6));
    cr_expect(isnan(ctd_shell_atan2((ct_real)NAN, 1)));
    cr_expect(isnan(ctd_shell_atan2(1, (ct_real)NAN)));
}

/* ---- A mixed mesh ----------------------------------------------------- */

/* Elements of an nx x ny curved plate: every third cell as two triangle
 * elements, and (with flip) every other remaining cell and every second
 * triangle in reversed node order; thickness by element (0.2 to 0.75). */
typedef struct mixed {
    ct_mesh m;
    ct_idx ne;
    ct_idx e1[128], e2[128], e3[128], e4[128];
    ct_real th[128];
} mixed;

static void mixed_make(mixed *q, int nx, int ny, int flip)
{
    curved(&q->m, nx, ny, 0.3, 0.7);
    cr_assert_leq(2 * q->m.nseg, 128);
    q->ne = 0;
    for (ct_idx c = 0; c < q->m.nseg; c++) {
        ct_idx a = q->m.n1[c], b = q->m.n2[c], d = q->m.n3[c], e = q->m.n4[c];
        ct_real t = (ct_real)(0.2 + 0.1 * (double)(c % 4));
        ct_idx k = q->ne;
        if (c % 3 == 0) {
            int rev = flip && c % 2 == 0;
            q->e1[k] = a, q->e2[k] = rev ? d : b, q->e3[k] = rev ? b : d, q->e4[k] = q->e3[k];
            q->e1[k + 1] = a, q->e2[k + 1] = d, q->e3[k + 1] = e, q->e4[k + 1] = e;
            q->th[k] = t;
            q->th[k + 1] = (ct_real)(t * 1.5);
            q->ne += 2;
        } else {
            int rev = flip && c % 2 == 1;
            q->e1[k] = a, q->e2[k] = rev ? e : b, q->e3[k] = d, q->e4[k] = rev ? b : e;
            q->th[k] = t;
            q->ne += 1;
        }
    }
}

static void mixed_shell(ctd_shell *s, const mixed *q)
{
    const ct_nodes *nd = &q->m.nodes;
    cr_assert_eq(ctd_shell_init(s, nd->n, nd->x, nd->y, nd->z, q->ne, q->e1, q->e2, q->e3,
                                q->e4, q->th, 1000.0, 0.3, 1.0, 0.0),
                 CT_OK);
}

/* A smooth deformation of the reference. */
static void deform(const ct_mesh *m, work *w)
{
    for (ct_idx i = 0; i < m->nodes.n; i++) {
        double p = m->nodes.x[i], q = m->nodes.y[i];
        w->x[i] = (ct_real)(m->nodes.x[i] + 0.02 * sin(3 * q));
        w->y[i] = (ct_real)(m->nodes.y[i] + 0.01 * cos(2 * p));
        w->z[i] = (ct_real)(m->nodes.z[i] + 0.04 * sin(4 * p + q) + 0.03 * p * q);
    }
}

Test(elements_shell_hinges, orientation_does_not_change_forces)
{
    mixed a, b;
    mixed_make(&a, 5, 4, 0);
    mixed_make(&b, 5, 4, 1);
    ctd_shell sa, sb;
    mixed_shell(&sa, &a);
    mixed_shell(&sb, &b);
    /* Triangles beside quads, triangles beside triangles: hinges of one
     * and of two per triangle edge. */
    cr_assert_eq(sa.nhinge, sb.nhinge);
    cr_assert_gt(sa.nhinge, 0);
    const ct_idx n = a.m.nodes.n;
    work wa, wb;
    work_init(&wa, n);
    work_init(&wb, n);
    deform(&a.m, &wa);
    deform(&b.m, &wb);
    double ea = forces(&sa, wa.x, wa.y, wa.z, wa.fx, wa.fy, wa.fz);
    double eb = forces(&sb, wb.x, wb.y, wb.z, wb.fx, wb.fy, wb.fz);
    cr_expect_gt(sa.e_bending, 0);
    cr_expect_lt(ctt_rel(ea, eb), CTT_TOL(1e-12, 1e-5), "energy %.17g against %.17g", ea, eb);
    double fmx = 0, dmx = 0;
    for (ct_idx i = 0; i < n; i++) {
        const ct_real fa[3] = {wa.fx[i], wa.fy[i], wa.fz[i]}, fb[3] = {wb.fx[i], wb.fy[i],
                                                                         wb.fz[i]};
        for (int k = 0; k < 3; k++) {
            fmx = fmax(fmx, fabs(fa[k]));
            dmx = fmax(dmx, fabs((double)fa[k] - fb[k]));
        }
    }
    cr_assert_gt(fmx, 0);
    cr_expect_lt(dmx, CTT_TOL(1e-11, 1e-4) * fmx, "largest difference %g of %g", dmx, fmx);
    work_free(&wa);
    work_free(&wb);
    ctd_shell_destroy(&sa);
    ctd_shell_destroy(&sb);
    ct_mesh_destroy(&a.m);
    ct_mesh_destroy(&b.m);
}

Test(elements_shell_hinges, mixed_mesh_energy_gradient_fd)
{
    mixed q;
    mixed_make(&q, 4, 3, 1);
    ctd_shell s;
    mixed_shell(&s, &q);
    /* Both hinge loops run: the groups of an edge between two quads, and
     * the hinges of edges with a triangle. */
    cr_assert_gt(s.ngroup, 0);
    cr_assert_gt(s.nhinge, 4 * s.ngroup);
    const ct_idx n = q.m.nodes.n;
    work w;
    work_init(&w, n);
    deform(&q.m, &w);
    forces(&s, w.x, w.y, w.z, w.fx, w.fy, w.fz);
    /* Thick elements (0.2-0.75 on cells of 0.3): the bending forces are
     * not hidden under the membrane's in the tolerance. */
    cr_expect_gt(s.e_bending, 0.1 * s.e_membrane, "bending %g, membrane %g", s.e_bending,
                 s.e_membrane);
    expect_forces_are_energy_gradient(&s, &w);
    work_free(&w);
    ctd_shell_destroy(&s);
    ct_mesh_destroy(&q.m);
}
