/*
 * test_iface.c -- the driver's contact interfaces (driver/interfaces/) on
 * meshes under prescribed motions, no solver: TYPE7 self contact on a
 * folded sheet (energy against the quadrature of the force), TYPE11 crossed
 * rods (direction, force and moment balance), the search algorithms
 * agreeing, and 1 and 2 threads agreeing to the bit. One node against a
 * rigid plate (TYPE24, friction, Tstart/Tstop, bad input) is in
 * test_iface_plate.c.
 */
#include "test_util.h"

#include <stdio.h>
#include <string.h>

#include "interfaces/iface.h"
#include "test_iface_util.h"
#include "interfaces/iface_internal.h"

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

/* The pair budget (iface_reach.c): the folded pair finds N candidates
 * with no limit; a limit of exactly their arrays' bytes (1.5 N
 * CTDI_PAIR_BYTES) passes and one byte less fails the step (the search's
 * max_pairs is then N - 1), with a message naming the count; the forces of
 * the passing step are those of the step without a limit. */
Test(iface, pair_budget_stops_the_step)
{
    fold f;
    fold_make(&f, 4, 3, 0.15, 0.1, 0.3);
    fold_place(&f, 0.15);
    ctd_iface_data d = fold_data(&f);
    double fz_free = 0, need = 0;
    for (int k = 0; k < 3; k++) {
        ctd_iface_cfg cfg = ctd_iface_default_cfg(7);
        cfg.Istf = 1;
        cfg.Stfac = 100;
        cfg.mem_limit = k == 0 ? 0 : k == 1 ? need : need - 1;
        ctd_iface *it = NULL;
        ct_diag diag;
        cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
        ctd_iface_report rep;
        memset(f.t.fz, 0, sizeof(ct_real) * (size_t)f.t.n);
        int rc = ctd_iface_step(it, 0, 1e-4, f.t.x, f.t.y, f.t.z, f.t.vx, f.t.vy, f.t.vz, f.t.m,
                                f.t.fx, f.t.fy, f.t.fz, &rep);
        if (k == 0) {
            cr_assert_eq(rc, CT_OK, "%s", rep.msg);
            cr_assert_gt(rep.ncand, 0);
            cr_assert_gt(rep.nactive, 0);
            need = 1.5 * (double)rep.ncand * (double)CTDI_PAIR_BYTES;
            fz_free = fold_top_fz(&f);
        } else if (k == 1) {
            cr_assert_eq(rc, CT_OK, "%s", rep.msg);
            cr_assert_eq(fold_top_fz(&f), fz_free);
        } else {
            /* The search stops at the limit's count, one pair short. */
            char count[64];
            snprintf(count, sizeof count, "found more than %lld candidate pairs",
                     (long long)(need / 1.5 / (double)CTDI_PAIR_BYTES + 0.5) - 1);
            cr_assert_eq(rc, CT_ERR_NOMEM);
            cr_assert(strstr(rep.msg, count) && strstr(rep.msg, "the interface's memory limit"),
                      "%s", rep.msg);
        }
        ctd_iface_destroy(it);
    }
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
        ctd_iface_data d = edge_pair_data(g);
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

/* ---- The secondary nodes' area (pressure_area secondary) ---------------- */

/* The areas ctdi_area_of_pairs gives every node of the surface for one
 * contact normal n (pen > 0 for all), and their sum. */
static double areas_for_normal(const ctd_iface *it, const tnodes *t, double nx, double ny,
                               double nz, ct_real *area)
{
    const ct_idx n = t->n;
    ct_idx *node = ct_calloc((size_t)n, sizeof(ct_idx));
    ct_real *pen = ct_calloc((size_t)n, sizeof(ct_real));
    ct_real *vx = ct_calloc((size_t)n, sizeof(ct_real));
    ct_real *vy = ct_calloc((size_t)n, sizeof(ct_real));
    ct_real *vz = ct_calloc((size_t)n, sizeof(ct_real));
    cr_assert(node && pen && vx && vy && vz);
    for (ct_idx i = 0; i < n; i++) {
        node[i] = i;
        pen[i] = (ct_real)0.01;
        vx[i] = (ct_real)nx;
        vy[i] = (ct_real)ny;
        vz[i] = (ct_real)nz;
    }
    ctdi_area_of_pairs(it, n, node, pen, vx, vy, vz, t->x, t->y, t->z, area);
    double sum = 0;
    for (ct_idx i = 0; i < n; i++)
        sum += (double)area[i];
    ct_free(node);
    ct_free(pen);
    ct_free(vx);
    ct_free(vy);
    ct_free(vz);
    return sum;
}

/*
 * The area a secondary node stands for (driver/interfaces/iface_area.c),
 * against sums worked by hand on the folded sheet of unit quads (two 4 x 3
 * layers 0.19 apart joined by a strip of 0.19 x 1 quads at x = 4) and on
 * a triangulated unit square. Facing the layers (n = z): an inner node
 * stands for 1, a node of the fold's edge for 0.5 (its two layer quads;
 * the strip meets it edge-on: with it, 0.595), and the areas sum to the
 * layers' 24. Facing the strip (n = x): a fold node for the strip's
 * 2 x 0.19 / 4 = 0.095, a node far from it (none of its quads faces x)
 * for all of its quads, 1. A pair out of contact gets 0. Triangles: each
 * of a node's triangles gives a third of its area, the areas sum to the
 * square's.
 */
Test(iface, secondary_node_area)
{
    fold f;
    fold_make(&f, 4, 3, 0.19, 0.1, 0);
    ctd_iface_cfg cfg = ctd_iface_default_cfg(7);
    cfg.Istf = 1;
    cfg.Stfac = 100;
    cfg.Ifric = CT_FRIC_POLY;
    cfg.Fric = (ct_real)0.1;
    cfg.pressure_area = CTD_PAREA_SECONDARY;
    ctd_iface_data d = fold_data(&f);
    ct_diag diag;
    ctd_iface *it = NULL;
    /* Without the model's segments there is no area to take. */
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_ERR_ARG);
    d.nmseg = f.nseg;
    d.m1 = f.n1;
    d.m2 = f.n2;
    d.m3 = f.n3;
    d.m4 = f.n4;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
    cr_assert_not_null(it->area_off);
    ct_real *area = ct_calloc((size_t)f.t.n, sizeof(ct_real));
    cr_assert(area);
    const double tol = CTT_TOL(1e-14, 1e-6);
    double sum = areas_for_normal(it, &f.t, 0, 0, 1, area);
    cr_expect(ctt_rel(sum, 24) <= tol, "sum %.17g", sum);
    cr_expect(ctt_rel(area[fid(&f, 0, 2, 1)], 1) <= tol, "inner %.17g", area[fid(&f, 0, 2, 1)]);
    cr_expect(ctt_rel(area[fid(&f, 1, 4, 1)], 0.5) <= tol, "fold %.17g", area[fid(&f, 1, 4, 1)]);
    cr_expect(ctt_rel(area[fid(&f, 0, 0, 0)], 0.25) <= tol, "corner %.17g",
              area[fid(&f, 0, 0, 0)]);
    areas_for_normal(it, &f.t, 1, 0, 0, area);
    cr_expect(ctt_rel(area[fid(&f, 0, 4, 1)], 0.095) <= tol, "strip %.17g",
              area[fid(&f, 0, 4, 1)]);
    cr_expect(ctt_rel(area[fid(&f, 1, 1, 1)], 1) <= tol, "edge-on %.17g",
              area[fid(&f, 1, 1, 1)]);
    /* Out of contact: 0. */
    ct_idx one = fid(&f, 0, 2, 1);
    ct_real zero = 0, nz = 1, z0 = 0;
    area[0] = 7;
    ctdi_area_of_pairs(it, 1, &one, &zero, &z0, &z0, &nz, f.t.x, f.t.y, f.t.z, area);
    cr_expect_eq(area[0], 0);
    ctd_iface_destroy(it);
    ct_free(area);
    fold_free(&f);

    /* A unit square of 2 x 2 cells, each cut into two triangles. */
    tnodes t;
    tn_init(&t, 9);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++)
            tn_set(&t, 3 * j + i, 0.5 * i, 0.5 * j, 0);
    ct_idx q[4][8];
    int s = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            const ct_idx a = 3 * j + i, b = a + 1, c = a + 4, e = a + 3;
            const ct_idx tr[2][3] = {{a, b, c}, {a, c, e}};
            for (int h = 0; h < 2; h++, s++) {
                q[0][s] = tr[h][0];
                q[1][s] = tr[h][1];
                q[2][s] = q[3][s] = tr[h][2];
            }
        }
    memset(&d, 0, sizeof d);
    d.nnode = 9;
    d.nseg = d.nmseg = 8;
    d.n1 = d.m1 = q[0];
    d.n2 = d.m2 = q[1];
    d.n3 = d.m3 = q[2];
    d.n4 = d.m4 = q[3];
    cfg.gap = (ct_real)0.05;
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
    ct_real a9[9];
    sum = areas_for_normal(it, &t, 0, 0, -1, a9);
    cr_expect(ctt_rel(sum, 1) <= tol, "triangles: sum %.17g", sum);
    /* The centre is a corner of 6 triangles of 1/8: 6 x (1/8) / 3. */
    cr_expect(ctt_rel(a9[4], 0.25) <= tol, "triangles: centre %.17g", a9[4]);
    /* Corner (0, 0): two triangles; corner (1, 0): one. */
    cr_expect(ctt_rel(a9[0], 2.0 / 24) <= tol, "triangles: corner %.17g", a9[0]);
    cr_expect(ctt_rel(a9[2], 1.0 / 24) <= tol, "triangles: corner %.17g", a9[2]);
    ctd_iface_destroy(it);
    /* The model's surface holding every triangle twice, the copy turned
     * the other way (a shell glued on a brick's face on the same nodes):
     * the same areas, a node stands for its surface once. */
    ct_idx q2[4][16];
    for (int k = 0; k < 8; k++)
        for (int c = 0; c < 4; c++) {
            q2[c][k] = q[c][k];
            q2[c][8 + k] = q[c == 1 ? 2 : c == 2 || c == 3 ? 1 : 0][k];
        }
    for (int k = 0; k < 8; k++)
        q2[3][8 + k] = q2[2][8 + k];
    d.nmseg = 16;
    d.m1 = q2[0];
    d.m2 = q2[1];
    d.m3 = q2[2];
    d.m4 = q2[3];
    cr_assert_eq(ctd_iface_init(&it, &cfg, &d, &diag), CT_OK, "%s", diag.msg);
    cr_expect_eq(it->narea_seg, 8);
    ct_real b9[9];
    sum = areas_for_normal(it, &t, 0, 0, -1, b9);
    cr_expect(ctt_rel(sum, 1) <= tol, "repeated triangles: sum %.17g", sum);
    for (int i = 0; i < 9; i++)
        cr_expect_eq(b9[i], a9[i], "node %d: %.17g against %.17g", i, b9[i], a9[i]);
    ctd_iface_destroy(it);
    tn_free(&t);
}

/* The topological search finds no self contact (a node's closest main node
 * is itself): TYPE7, and TYPE24 on one surface, refuse it. */
Test(iface, topological_search_refused_for_self_contact)
{
    fold f;
    fold_make(&f, 4, 3, 0.19, 0.1, 0);
    ctd_iface_data d = fold_data(&f);
    const int type[3] = {7, 24, 7}, algo[3] = {CT_SEARCH_TOPO, CT_SEARCH_TOPO, CT_SEARCH_BSP};
    const int want[3] = {CT_ERR_ARG, CT_ERR_ARG, CT_OK};
    for (int k = 0; k < 3; k++) {
        ctd_iface_cfg cfg = ctd_iface_default_cfg(type[k]);
        cfg.Istf = 1;
        cfg.Stfac = 100;
        cfg.self = 1;
        cfg.two_sided = 1;
        cfg.algo = (ct_search_algo)algo[k];
        ct_diag diag;
        ctd_iface *it = NULL;
        cr_expect_eq(ctd_iface_init(&it, &cfg, &d, &diag), want[k], "type %d: %s", type[k],
                     diag.msg);
        if (want[k] != CT_OK)
            cr_expect(strstr(diag.msg, "topological search cannot find self contact") != NULL,
                      "%s", diag.msg);
        ctd_iface_destroy(it);
    }
    fold_free(&f);
}
