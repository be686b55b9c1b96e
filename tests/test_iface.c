/*
 * test_iface.c -- the driver's contact interfaces (driver/interfaces/) under
 * prescribed motions, no solver: TYPE24 penalty force and its distribution,
 * the stiffness combinations, initial penetration, Coulomb friction and its
 * dissipation, TYPE7 self contact on a folded sheet (energy against the
 * quadrature of the force), TYPE11 crossed rods (direction, force and
 * moment balance), the search algorithms agreeing, 1 and 2 threads agreeing
 * to the bit, and Tstart/Tstop.
 */
#include "test_util.h"

#include <string.h>

#include "interfaces/iface.h"
#include "test_iface_util.h"

static double fsum(const ct_real *f, ct_idx n)
{
    double s = 0;
    for (ct_idx i = 0; i < n; i++)
        s += (double)f[i];
    return s;
}

/* ---- A node against a rigid plate (TYPE24) -------------------------------- */

/* Plate [-L, L]^2 at z = 0 (nodes 0..3, normal +z), node 4 secondary. */
static const ct_idx P1[1] = {0}, P2[1] = {1}, P3[1] = {2}, P4[1] = {3}, SEC4[1] = {4};

static void plate_nodes(tnodes *t, double L)
{
    tn_init(t, 5);
    tn_set(t, 0, -L, -L, 0);
    tn_set(t, 1, L, -L, 0);
    tn_set(t, 2, L, L, 0);
    tn_set(t, 3, -L, L, 0);
}

static ctd_iface *plate_iface(ctd_iface_cfg *c, ct_real K)
{
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 5;
    d.nseg = 1;
    d.n1 = P1;
    d.n2 = P2;
    d.n3 = P3;
    d.n4 = P4;
    d.nsec = 1;
    d.sec = SEC4;
    d.K = K;
    ctd_iface *it = NULL;
    ct_diag diag;
    int rc = ctd_iface_init(&it, c, &d, &diag);
    cr_assert_eq(rc, CT_OK, "init: %s", diag.msg);
    return it;
}

static ctd_iface_cfg plate_cfg(void)
{
    ctd_iface_cfg c = ctd_iface_default_cfg(24);
    c.two_sided = 0; /* an oriented solid face, gap 0 */
    c.gap = 0;
    c.quad = CT_QUAD_NEWTON; /* bilinear shape functions */
    c.VisS = 0;
    c.margin = (ct_real)0.1;
    return c;
}

Test(iface, type24_penalty_force_and_distribution)
{
    const double K = 1000, s = 0.3, tt = -0.4, tol = CTT_TOL(1e-12, 2e-5);
    const double H[4] = {(1 - s) * (1 - tt) / 4, (1 + s) * (1 - tt) / 4, (1 + s) * (1 + tt) / 4,
                         (1 - s) * (1 + tt) / 4};
    const double pens[3] = {1e-3, 0.01, 0.05};
    for (int c = 0; c < 3; c++) {
        tnodes t;
        plate_nodes(&t, 1);
        double p = pens[c];
        tn_set(&t, 4, s, tt, -p);
        ctd_iface_cfg cfg = plate_cfg();
        ctd_iface *it = plate_iface(&cfg, (ct_real)K);
        ctd_iface_report rep;
        tstep(it, &t, 0, 1e-3, &rep);
        double F = K * p;
        cr_assert_eq(rep.nactive, 1);
        cr_assert(fabs(t.fz[4] - F) <= tol * F, "fz %g expected %g", (double)t.fz[4], F);
        cr_assert(fabs(t.fx[4]) <= tol * F && fabs(t.fy[4]) <= tol * F);
        for (int i = 0; i < 4; i++)
            cr_assert(fabs(t.fz[i] + H[i] * F) <= tol * F, "node %d: %g expected %g", i,
                      (double)t.fz[i], -H[i] * F);
        cr_assert(fabs(fsum(t.fz, 5)) <= tol * F && fabs(fsum(t.fx, 5)) <= tol * F);
        cr_assert(fabs(rep.force[2] - F) <= tol * F);
        cr_assert(fabs(rep.e_contact - 0.5 * K * p * p) <= tol * 0.5 * K * p * p);
        /* Constant stiffness: the nodal step sqrt(2 m / K) (m = 1). */
        cr_assert(fabs(rep.dt_nodal - sqrt(2.0 / K)) <= tol * sqrt(2.0 / K));
        ctd_iface_destroy(it);
        tn_free(&t);
    }
}

Test(iface, type24_approach_no_blending)
{
    /* The node comes down at a speed consistent with its motion: every step
     * the force is K p (no blending, no damping with VisS = 0). */
    const double K = 500, v = 0.1, dt = 1e-3, tol = CTT_TOL(1e-9, 1e-3);
    tnodes t;
    plate_nodes(&t, 1);
    ctd_iface_cfg cfg = plate_cfg();
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    double z = 0.002;
    int seen = 0;
    for (int k = 0; k < 100; k++) {
        tn_set(&t, 4, 0.1, 0.2, z);
        t.vz[4] = (ct_real)-v;
        ctd_iface_report rep;
        tstep(it, &t, k * dt, dt, &rep);
        double p = z < 0 ? -z : 0;
        cr_assert(fabs(t.fz[4] - K * p) <= tol * K * 0.01, "step %d: fz %g expected %g", k,
                  (double)t.fz[4], K * p);
        seen += p > 0;
        z -= v * dt;
    }
    cr_assert(seen > 50);
    ctd_iface_destroy(it);
    tn_free(&t);
}

Test(iface, type24_step_kept_while_the_pair_is_open)
{
    /* A node just above the plate (a candidate, not in contact), then in
     * contact, then just above again (contact chatter): the nodal step stays
     * sqrt(2 m / K) throughout. It must not jump back to the element step
     * (no limit) while the pair is open, since the spring can act again at
     * the next cycle with that longer step (the two-bar impact of
     * validation_bars ran away that way). */
    const double K = 500, tol = CTT_TOL(1e-12, 2e-6);
    const double zs[3] = {1e-4, -1e-4, 2e-4};
    tnodes t;
    plate_nodes(&t, 1);
    ctd_iface_cfg cfg = plate_cfg();
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    for (int k = 0; k < 3; k++) {
        tn_set(&t, 4, 0.1, 0.2, zs[k]);
        ctd_iface_report rep;
        tstep(it, &t, k * 1e-3, 1e-3, &rep);
        cr_assert_eq(rep.nactive, zs[k] < 0, "step %d", k);
        cr_assert(fabs(rep.dt_nodal - sqrt(2.0 / K)) <= tol * sqrt(2.0 / K),
                  "step %d: dt_nodal %g expected %g", k, (double)rep.dt_nodal, sqrt(2.0 / K));
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}

Test(iface, type24_stiffness_modes)
{
    /* Km = Stfac E t = 2 * 100 * 1 = 200, Ks = Stfac * et = 2 * 40 = 80. */
    const ct_real E[1] = {100}, th[1] = {1};
    ct_real et[5] = {0, 0, 0, 0, 40};
    const int istf[6] = {2, 3, 4, 5, 1000, 0};
    const double Kexp[6] = {140, 200, 80, 200.0 * 80 / 280, 200, 140};
    const double p = 0.01, tol = CTT_TOL(1e-12, 2e-5);
    for (int c = 0; c < 6; c++) {
        tnodes t;
        plate_nodes(&t, 1);
        tn_set(&t, 4, 0, 0, -p);
        ctd_iface_cfg cfg = plate_cfg();
        cfg.Istf = istf[c];
        cfg.Stfac = 2;
        ctd_iface_data d;
        memset(&d, 0, sizeof d);
        d.nnode = 5;
        d.nseg = 1;
        d.n1 = P1;
        d.n2 = P2;
        d.n3 = P3;
        d.n4 = P4;
        d.nsec = 1;
        d.sec = SEC4;
        d.seg_E = E;
        d.seg_t = th;
        d.node_et = et;
        ctd_iface *it = NULL;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, NULL), CT_OK);
        ctd_iface_report rep;
        tstep(it, &t, 0, 1e-3, &rep);
        cr_assert(fabs(t.fz[4] - Kexp[c] * p) <= tol * Kexp[c] * p, "Istf %d: %g expected %g",
                  istf[c], (double)t.fz[4], Kexp[c] * p);
        ctd_iface_destroy(it);
        /* Stmax clamps. */
        cfg.Stmax = 50;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, NULL), CT_OK);
        tstep(it, &t, 0, 1e-3, &rep);
        cr_assert(fabs(t.fz[4] - 50 * p) <= tol * 50 * p);
        ctd_iface_destroy(it);
        tn_free(&t);
    }
}

Test(iface, type24_initial_penetration)
{
    const double K = 1000, p0 = 0.02, tol = CTT_TOL(1e-10, 1e-4);
    /* Inacti: the initial penetration is subtracted; going 0.005 deeper
     * gives K * 0.005. */
    tnodes t;
    plate_nodes(&t, 1);
    tn_set(&t, 4, 0.2, 0.1, -p0);
    ctd_iface_cfg cfg = plate_cfg();
    cfg.Inacti = 5;
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    ctd_iface_report rep;
    tstep(it, &t, 0, 1e-3, &rep);
    cr_assert(fabs(t.fz[4]) <= tol * K * p0, "initial force %g", (double)t.fz[4]);
    for (int k = 1; k <= 5; k++) {
        tn_set(&t, 4, 0.2, 0.1, -p0 - 0.001 * k);
        t.vz[4] = -1; /* 1 per step of 1e-3: consistent, no blending */
        tstep(it, &t, k * 1e-3, 1e-3, &rep);
        cr_assert(fabs(t.fz[4] - K * 0.001 * k) <= tol * K * p0, "step %d: %g", k,
                  (double)t.fz[4]);
    }
    ctd_iface_destroy(it);
    /* Ipen_max: a pair deeper than it is deactivated for good. */
    tn_set(&t, 4, 0.2, 0.1, -p0);
    t.vz[4] = 0;
    cfg = plate_cfg();
    cfg.Ipen_max = (ct_real)0.01;
    it = plate_iface(&cfg, (ct_real)K);
    tstep(it, &t, 0, 1e-3, &rep);
    cr_assert_eq(rep.deactivated, 1);
    cr_assert(t.fz[4] == 0);
    tstep(it, &t, 1e-3, 1e-3, &rep);
    cr_assert(t.fz[4] == 0);
    ctd_iface_destroy(it);
    /* Default (Inacti 0): the full force on the initial penetration. */
    cfg = plate_cfg();
    it = plate_iface(&cfg, (ct_real)K);
    tstep(it, &t, 0, 1e-3, &rep);
    cr_assert(fabs(t.fz[4] - K * p0) <= tol * K * p0);
    ctd_iface_destroy(it);
    tn_free(&t);
}

/* ---- Friction (TYPE24, Coulomb) ------------------------------------------ */

Test(iface, type24_coulomb_sliding)
{
    const double K = 1000, p = 0.01, mu = 0.3, v = 1, dt = 1e-3;
    const double Fn = K * p, tol = CTT_TOL(1e-9, 1e-3);
    tnodes t;
    plate_nodes(&t, 10);
    ctd_iface_cfg cfg = plate_cfg();
    cfg.Fric = (ct_real)mu;
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    double x = -1;
    for (int k = 0; k < 30; k++) {
        tn_set(&t, 4, x, 0.5, -p);
        t.vx[4] = (ct_real)v;
        ctd_iface_report rep;
        tstep(it, &t, k * dt, dt, &rep);
        cr_assert(fabs(t.fz[4] - Fn) <= tol * Fn);
        if (k >= 5) { /* steady sliding (the stick phase lasts 3 steps) */
            cr_assert(fabs(t.fx[4] + mu * Fn) <= tol * mu * Fn, "step %d: ft %g expected %g",
                      k, (double)t.fx[4], -mu * Fn);
            cr_assert(fabs(t.fy[4]) <= tol * mu * Fn);
            double w = mu * Fn * v * dt;
            cr_assert(fabs(rep.e_fric - w) <= tol * w, "step %d: dissipation %g expected %g",
                      k, rep.e_fric, w);
        }
        cr_assert(fabs(fsum(t.fx, 5)) <= tol * Fn && fabs(fsum(t.fz, 5)) <= tol * Fn);
        x += v * dt;
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}

/* ---- TYPE7 on a folded sheet --------------------------------------------- */

/* Two layers nx by ny quads of size 1, the bottom at z = 0, the top at z = h,
 * joined by a strip of quads at x = nx (the fold). Top-layer nodes are
 * flagged. */
typedef struct fold {
    tnodes t;
    ct_idx nseg;
    ct_idx *n1, *n2, *n3, *n4;
    int *top;
    ct_real *gap;
    int nx, ny;
} fold;

static ct_idx fid(const fold *f, int layer, int i, int j)
{
    return (ct_idx)(layer * (f->nx + 1) * (f->ny + 1) + j * (f->nx + 1) + i);
}

static void fold_make(fold *f, int nx, int ny, double h, double half_t, double jitter)
{
    memset(f, 0, sizeof *f);
    f->nx = nx;
    f->ny = ny;
    ct_idx nn = (ct_idx)(2 * (nx + 1) * (ny + 1));
    tn_init(&f->t, nn);
    f->top = calloc((size_t)nn, sizeof(int));
    f->gap = ct_calloc((size_t)nn, sizeof(ct_real));
    ct_idx ns = (ct_idx)(2 * nx * ny + ny);
    f->n1 = ct_calloc((size_t)ns, sizeof(ct_idx));
    f->n2 = ct_calloc((size_t)ns, sizeof(ct_idx));
    f->n3 = ct_calloc((size_t)ns, sizeof(ct_idx));
    f->n4 = ct_calloc((size_t)ns, sizeof(ct_idx));
    cr_assert(f->top && f->gap && f->n1 && f->n2 && f->n3 && f->n4);
    unsigned seed = 12345;
    for (int l = 0; l < 2; l++)
        for (int j = 0; j <= ny; j++)
            for (int i = 0; i <= nx; i++) {
                ct_idx k = fid(f, l, i, j);
                seed = seed * 1103515245u + 12345u;
                double jx = jitter * ((double)((seed >> 8) % 1000) / 1000.0 - 0.5);
                seed = seed * 1103515245u + 12345u;
                double jy = jitter * ((double)((seed >> 8) % 1000) / 1000.0 - 0.5);
                if (i == nx)
                    jx = 0;
                tn_set(&f->t, k, i + jx, j + jy, l ? h : 0);
                f->top[k] = l;
                f->gap[k] = (ct_real)half_t;
            }
    ct_idx s = 0;
    for (int l = 0; l < 2; l++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                f->n1[s] = fid(f, l, i, j);
                f->n2[s] = fid(f, l, i + 1, j);
                f->n3[s] = fid(f, l, i + 1, j + 1);
                f->n4[s] = fid(f, l, i, j + 1);
                s++;
            }
    for (int j = 0; j < ny; j++) {
        f->n1[s] = fid(f, 0, nx, j);
        f->n2[s] = fid(f, 0, nx, j + 1);
        f->n3[s] = fid(f, 1, nx, j + 1);
        f->n4[s] = fid(f, 1, nx, j);
        s++;
    }
    f->nseg = s;
}

static void fold_free(fold *f)
{
    tn_free(&f->t);
    free(f->top);
    ct_free(f->gap);
    ct_free(f->n1);
    ct_free(f->n2);
    ct_free(f->n3);
    ct_free(f->n4);
}

static ctd_iface_data fold_data(const fold *f)
{
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = f->t.n;
    d.nseg = f->nseg;
    d.n1 = f->n1;
    d.n2 = f->n2;
    d.n3 = f->n3;
    d.n4 = f->n4;
    d.gap_node = f->gap;
    return d;
}

/* Top layer at height h (velocity -1). */
static void fold_place(fold *f, double h)
{
    for (ct_idx i = 0; i < f->t.n; i++)
        if (f->top[i]) {
            f->t.z[i] = (ct_real)h;
            f->t.vz[i] = -1;
        }
}

static double fold_top_fz(const fold *f)
{
    double s = 0;
    for (ct_idx i = 0; i < f->t.n; i++)
        if (f->top[i])
            s += (double)f->t.fz[i];
    return s;
}

Test(iface, type7_folded_energy_is_force_integral)
{
    /* Thickness 0.2 (pair gap 0.2); the layers go from 0.19 to 0.08 apart. */
    const double K0 = 100, h0 = 0.19, h1 = 0.08;
    const int N = 2000; /* Simpson intervals (even) */
    fold f;
    fold_make(&f, 4, 3, h0, 0.1, 0.3);
    ctd_iface_cfg cfg = ctd_iface_default_cfg(7);
    cfg.Istf = 1;
    cfg.Stfac = (ct_real)K0;
    cfg.VisS = 0;
    ctd_iface_data d = fold_data(&f);
    ctd_iface *it = NULL;
    ct_diag diag;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
    double e0 = 0, e1 = 0, simpson = 0, prev = -1;
    const double hstep = (h0 - h1) / N;
    for (int k = 0; k <= N; k++) {
        double h = h0 - k * hstep;
        fold_place(&f, h);
        ctd_iface_report rep;
        tstep(it, &f.t, k * 1e-4, 1e-4, &rep);
        double F = fold_top_fz(&f);
        for (ct_idx i = 0; i < f.t.n; i++)
            cr_assert(isfinite(f.t.fx[i]) && isfinite(f.t.fy[i]) && isfinite(f.t.fz[i]));
        cr_assert(isfinite(rep.e_contact));
        cr_assert(F > 0, "step %d: no contact force", k);
        cr_assert(F >= prev, "step %d: force %g fell from %g", k, F, prev);
        prev = F;
        simpson += F * (k == 0 || k == N ? 1 : (k % 2 ? 4 : 2));
        if (k == 0)
            e0 = rep.e_contact;
        if (k == N)
            e1 = rep.e_contact;
        cr_assert(fabs(fsum(f.t.fz, f.t.n)) <= CTT_TOL(1e-9, 1e-3) * F);
    }
    simpson *= hstep / 3;
    cr_assert(e1 > e0);
    cr_assert(fabs((e1 - e0) - simpson) <= CTT_TOL(1e-6, 1e-3) * (e1 - e0),
              "stored %.12g, integral %.12g", e1 - e0, simpson);
    ctd_iface_destroy(it);
    fold_free(&f);
}

/* ---- TYPE11 crossed rods ----------------------------------------------- */

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

Test(iface, type11_crossed_rods)
{
    const double r = 0.15, K0 = 50, tol = CTT_TOL(1e-10, 1e-4);
    tnodes t;
    tn_init(&t, 4);
    tn_set(&t, 0, -0.6, 0, 0);
    tn_set(&t, 1, 1.4, 0.1, 0);
    tn_set(&t, 2, 0.2, -0.8, 0.12);
    tn_set(&t, 3, -0.3, 1.2, 0.32);
    ct_real g[4] = {(ct_real)r, (ct_real)r, (ct_real)r, (ct_real)r};
    const ct_idx a1[1] = {0}, a2[1] = {1}, b1[1] = {2}, b2[1] = {3};
    /* Independent geometry: the common normal and distance of the lines. */
    double A1[3] = {-0.6, 0, 0}, eA[3] = {2.0, 0.1, 0}, B1[3] = {0.2, -0.8, 0.12},
           eB[3] = {-0.5, 2.0, 0.2}, n[3];
    cross(eA, eB, n);
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; i++)
        n[i] /= nl;
    double dist = (A1[0] - B1[0]) * n[0] + (A1[1] - B1[1]) * n[1] + (A1[2] - B1[2]) * n[2];
    if (dist < 0) { /* n from B towards A */
        dist = -dist;
        for (int i = 0; i < 3; i++)
            n[i] = -n[i];
    }
    double gp = 2 * r, x = (gp - dist) / gp, F = K0 * gp * x / (1 - x);
    cr_assert(dist < gp);
    for (int algo = 0; algo < 2; algo++) {
        ctd_iface_cfg cfg = ctd_iface_default_cfg(11);
        cfg.Istf = 1;
        cfg.Stfac = (ct_real)K0;
        cfg.VisS = 0;
        cfg.algo = algo ? CT_SEARCH_BUCKET : CT_SEARCH_DIRECT;
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
        ctd_iface *it = NULL;
        ct_diag diag;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
        ctd_iface_report rep;
        tstep(it, &t, 0, 1e-3, &rep);
        cr_assert_eq(rep.nactive, 1);
        double fa[3] = {(double)t.fx[0] + t.fx[1], (double)t.fy[0] + t.fy[1],
                        (double)t.fz[0] + t.fz[1]};
        double fb[3] = {(double)t.fx[2] + t.fx[3], (double)t.fy[2] + t.fy[3],
                        (double)t.fz[2] + t.fz[3]};
        for (int i = 0; i < 3; i++) {
            cr_assert(fabs(fa[i] - F * n[i]) <= tol * F, "axis %d: %g expected %g", i, fa[i],
                      F * n[i]);
            cr_assert(fabs(fa[i] + fb[i]) <= tol * F);
        }
        /* Moment about the origin. */
        double M[3] = {0, 0, 0};
        for (ct_idx k = 0; k < 4; k++) {
            double p[3] = {t.x[k], t.y[k], t.z[k]}, f[3] = {t.fx[k], t.fy[k], t.fz[k]}, c[3];
            cross(p, f, c);
            for (int i = 0; i < 3; i++)
                M[i] += c[i];
        }
        for (int i = 0; i < 3; i++)
            cr_assert(fabs(M[i]) <= tol * F * 2, "moment %d: %g", i, M[i]);
        double e = K0 * gp * gp * ((1 - x) - 1 - log(1 - x));
        cr_assert(fabs(rep.e_contact - e) <= CTT_TOL(1e-9, 1e-3) * e);
        ctd_iface_destroy(it);
    }
    tn_free(&t);
}

/* ---- Determinism, search algorithms, Tstart/Tstop ------------------------- */

/* Two jittered plates nx by nx, z = 0 and z = 0.15 (shells, gap 0.1 each
 * side), the top one sliding; TYPE24 surface to surface with friction. */
typedef struct plates {
    tnodes t;
    ct_idx ns;
    ct_idx *m1, *m2, *m3, *m4, *s1, *s2, *s3, *s4;
    ct_real *gap;
} plates;

static void plates_make(plates *P, int nx)
{
    fold f;
    fold_make(&f, nx, nx, 0.15, 0.1, 0.4);
    /* Reuse the fold's layers as the two plates (drop the strip). */
    P->t = f.t;
    P->gap = f.gap;
    P->ns = (ct_idx)(nx * nx);
    P->m1 = f.n1;
    P->m2 = f.n2;
    P->m3 = f.n3;
    P->m4 = f.n4;
    P->s1 = f.n1 + P->ns;
    P->s2 = f.n2 + P->ns;
    P->s3 = f.n3 + P->ns;
    P->s4 = f.n4 + P->ns;
    for (ct_idx i = 0; i < P->t.n; i++)
        if (f.top[i])
            P->t.vx[i] = (ct_real)0.5;
    free(f.top);
}

static void plates_free(plates *P)
{
    tn_free(&P->t);
    ct_free(P->gap);
    ct_free(P->m1);
    ct_free(P->m2);
    ct_free(P->m3);
    ct_free(P->m4);
}

static ctd_iface *plates_iface(const plates *P, ct_search_algo algo)
{
    ctd_iface_cfg cfg = ctd_iface_default_cfg(24);
    cfg.symmetric = 1;
    cfg.two_sided = 1;
    cfg.Igap0 = 1;
    cfg.Fric = (ct_real)0.2;
    cfg.Ifiltr = 1;
    cfg.Xfreq = (ct_real)0.5;
    cfg.algo = algo;
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = P->t.n;
    d.nseg = P->ns;
    d.n1 = P->m1;
    d.n2 = P->m2;
    d.n3 = P->m3;
    d.n4 = P->m4;
    d.nsseg = P->ns;
    d.s1 = P->s1;
    d.s2 = P->s2;
    d.s3 = P->s3;
    d.s4 = P->s4;
    d.K = 100;
    d.gap_node = P->gap;
    ctd_iface *it = NULL;
    ct_diag diag;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
    return it;
}

/* Run `steps` steps of the sliding plates, top plate moving; returns the
 * forces of the last step in out (3 n) and the energies in en[3]. */
static void plates_run(plates *P, ctd_iface *it, int steps, ct_real *out, double en[3])
{
    const double dt = 1e-2;
    en[0] = en[1] = en[2] = 0;
    for (int k = 0; k < steps; k++) {
        ctd_iface_report rep;
        tstep(it, &P->t, k * dt, dt, &rep);
        en[0] = rep.e_contact;
        en[1] += rep.e_damp;
        en[2] += rep.e_fric;
        cr_assert(rep.nactive > 0);
        double tot[3] = {fsum(P->t.fx, P->t.n), fsum(P->t.fy, P->t.n), fsum(P->t.fz, P->t.n)};
        for (int a = 0; a < 3; a++)
            cr_assert(fabs(tot[a]) <= CTT_TOL(1e-10, 1e-3) * (fabs(rep.force[2]) + 1));
        for (ct_idx i = 0; i < P->t.n; i++)
            P->t.x[i] += P->t.vx[i] * (ct_real)dt;
    }
    memcpy(out, P->t.fx, sizeof(ct_real) * (size_t)P->t.n);
    memcpy(out + P->t.n, P->t.fy, sizeof(ct_real) * (size_t)P->t.n);
    memcpy(out + 2 * P->t.n, P->t.fz, sizeof(ct_real) * (size_t)P->t.n);
}

Test(iface, threads_bit_identical)
{
    int nx = ctt_checking() ? 8 : 24;
    ct_real *f[2];
    double en[2][3];
    for (int th = 0; th < 2; th++) {
        ctt_threads(th + 1);
        plates P;
        plates_make(&P, nx);
        ctd_iface *it = plates_iface(&P, CT_SEARCH_BUCKET);
        f[th] = ct_calloc(3 * (size_t)P.t.n, sizeof(ct_real));
        cr_assert(f[th]);
        plates_run(&P, it, 12, f[th], en[th]);
        ctd_iface_destroy(it);
        /* TYPE7 and TYPE11 on the same mesh with the fold, added on top. */
        ct_idx nn = P.t.n;
        plates_free(&P);
        fold F;
        fold_make(&F, nx, 4, 0.15, 0.1, 0.4);
        ctd_iface_data d = fold_data(&F);
        for (int type = 7; type <= 11; type += 4) {
            ctd_iface_cfg cfg = ctd_iface_default_cfg(type);
            cfg.Istf = 1;
            cfg.Stfac = 10;
            cfg.Fric = (ct_real)0.1;
            ctd_iface *it2 = NULL;
            cr_assert_eq(ctd_iface_init(&it2, &cfg, &d, NULL), CT_OK);
            for (ct_idx i = 0; i < F.t.n; i++)
                F.t.vx[i] = F.top[i] ? (ct_real)0.3 : 0;
            ctd_iface_report rep;
            for (int k = 0; k < 3; k++) {
                memset(F.t.fx, 0, sizeof(ct_real) * (size_t)F.t.n);
                memset(F.t.fy, 0, sizeof(ct_real) * (size_t)F.t.n);
                memset(F.t.fz, 0, sizeof(ct_real) * (size_t)F.t.n);
                cr_assert_eq(ctd_iface_step(it2, k * 0.01, (ct_real)0.01, F.t.x, F.t.y, F.t.z,
                                            F.t.vx, F.t.vy, F.t.vz, F.t.m, F.t.fx, F.t.fy,
                                            F.t.fz, &rep),
                             CT_OK);
            }
            cr_assert(rep.nactive > 0, "type %d: no contact", type);
            for (ct_idx i = 0; i < F.t.n && i < nn; i++) {
                f[th][i] += F.t.fx[i];
                f[th][nn + i] += F.t.fy[i];
                f[th][2 * nn + i] += F.t.fz[i];
            }
            en[th][0] += rep.e_contact;
            ctd_iface_destroy(it2);
        }
        fold_free(&F);
        if (th == 1)
            cr_assert_eq(memcmp(f[0], f[1], 3 * sizeof(ct_real) * (size_t)nn), 0,
                         "forces differ between 1 and 2 threads");
    }
    ctt_threads(2);
    cr_assert(memcmp(en[0], en[1], sizeof en[0]) == 0, "energies differ");
    cr_assert(en[0][2] > 0, "no friction dissipation");
    ct_free(f[0]);
    ct_free(f[1]);
}

Test(iface, search_algorithms_agree)
{
    const ct_search_algo algos[4] = {CT_SEARCH_DIRECT, CT_SEARCH_BUCKET, CT_SEARCH_BSP,
                                     CT_SEARCH_TOPO};
    ct_real *f[4];
    double en[4][3];
    ct_idx n = 0;
    for (int a = 0; a < 4; a++) {
        plates P;
        plates_make(&P, 6);
        n = P.t.n;
        ctd_iface *it = plates_iface(&P, algos[a]);
        f[a] = ct_calloc(3 * (size_t)n, sizeof(ct_real));
        cr_assert(f[a]);
        plates_run(&P, it, 3, f[a], en[a]);
        ctd_iface_destroy(it);
        plates_free(&P);
    }
    /* Direct, bucket and bsp find the same candidates: identical forces.
     * The topological search may miss pairs, so it is only required to find
     * a contact. */
    for (int a = 1; a < 3; a++)
        cr_assert_eq(memcmp(f[0], f[a], 3 * sizeof(ct_real) * (size_t)n), 0, "%s differs",
                     ct_search_algo_name(algos[a]));
    cr_assert(en[3][0] > 0);
    for (int a = 0; a < 4; a++)
        ct_free(f[a]);
}

Test(iface, tstart_tstop)
{
    const double K = 1000, p = 0.01;
    tnodes t;
    plate_nodes(&t, 1);
    tn_set(&t, 4, 0.1, 0.1, -p);
    ctd_iface_cfg cfg = plate_cfg();
    cfg.Tstart = 1;
    cfg.Tstop = 2;
    ctd_iface *it = plate_iface(&cfg, (ct_real)K);
    const double times[5] = {0.5, 1.0, 1.5, 2.0, 2.5};
    const int on[5] = {0, 1, 1, 1, 0};
    for (int k = 0; k < 5; k++) {
        ctd_iface_report rep;
        tstep(it, &t, times[k], 1e-3, &rep);
        cr_assert_eq(rep.on, on[k], "time %g", times[k]);
        double want = on[k] ? K * p : 0;
        cr_assert(fabs(t.fz[4] - want) <= CTT_TOL(1e-12, 2e-5) * K * p, "time %g: %g",
                  times[k], (double)t.fz[4]);
        cr_assert(on[k] || (rep.e_contact == 0 && rep.nactive == 0));
    }
    ctd_iface_destroy(it);
    tn_free(&t);
}

Test(iface, bad_input)
{
    ctd_iface_cfg cfg = ctd_iface_default_cfg(24);
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    ctd_iface *it = NULL;
    ct_diag diag;
    cfg.type = 9;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_ERR_ARG);
    cr_assert_null(it);
    cfg = ctd_iface_default_cfg(24);
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_ERR_ARG); /* no segments */
    const ct_idx bad[1] = {7};
    d.nnode = 5;
    d.nseg = 1;
    d.n1 = P1;
    d.n2 = P2;
    d.n3 = P3;
    d.n4 = bad;
    d.nsec = 1;
    d.sec = SEC4;
    d.K = 1;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_ERR_RANGE);
    cr_assert_null(it);
}
