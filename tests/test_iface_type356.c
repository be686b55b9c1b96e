/*
 * test_iface_type356.c -- the interfaces of the seed 000 family (TYPE3,
 * TYPE5, TYPE6) under prescribed positions, no solver, against truths
 * computed here by hand: the TYPE5 series stiffness from the element
 * inputs and the shape-function distribution of the reaction (force and
 * moment balance), the topological search against the direct one on a
 * sliding node, TYPE3's two passes (action and reaction, energy), the
 * defaults, bad cards, and 1 against 2 threads to the bit. TYPE6's curve
 * law is in test_iface_type6.c.
 */
#include "test_iface_type356.h"

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Rotation by angle w about the unit axis u (Rodrigues), applied to v. */
static void rotate(const double u[3], double w, const double v[3], double out[3])
{
    double c = cos(w), s = sin(w), uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2], uxv[3];
    cross(u, v, uxv);
    for (int i = 0; i < 3; i++)
        out[i] = v[i] * c + uxv[i] * s + u[i] * uv * (1 - c);
}

/* ---- TYPE5: one node into one quad ------------------------------------- */

Test(iface_type356, type5_series_stiffness_and_shape_functions)
{
    /* A parallelogram (closed-form (s, t) is exact on it) of area 2 x 1.5,
     * rotated out of the axes; node 4 sits at depth p behind the point
     * (s, t). */
    const double X[4][3] = {{0, 0, 0}, {2, 0, 0}, {2.6, 1.5, 0}, {0.6, 1.5, 0}};
    const double area = 3.0, s = 0.35, t = -0.55, p = 0.01;
    const double ax0[3] = {1, 2, 3}, al = sqrt(14.0);
    const double ax[3] = {ax0[0] / al, ax0[1] / al, ax0[2] / al}, ang = 0.7;
    const double N[4] = {(1 - s) * (1 - t) / 4, (1 + s) * (1 - t) / 4, (1 + s) * (1 + t) / 4,
                         (1 - s) * (1 + t) / 4};
    const double ez[3] = {0, 0, 1};
    double Xr[4][3], n[3], C[3] = {0, 0, 0}, P[3];
    rotate(ax, ang, ez, n);
    for (int i = 0; i < 4; i++) {
        rotate(ax, ang, X[i], Xr[i]);
        for (int a = 0; a < 3; a++)
            C[a] += N[i] * Xr[i][a];
    }
    for (int a = 0; a < 3; a++)
        P[a] = C[a] - p * n[a]; /* behind the oriented face */
    /* Inputs: brick face B A^2 / V against the node's B (2 Vnode)^(1/3);
     * shell E t against the node's mean E t; and the fallbacks. */
    const ct_real sB[1] = {1000}, sA[1] = {(ct_real)area}, sV[1] = {6}, sE[1] = {200},
                  sT[1] = {2};
    ct_real nB[5] = {0, 0, 0, 0, 2000}, nV[5] = {0, 0, 0, 0, 0.5}, nEt[5] = {0, 0, 0, 0, 100};
    ct_real nEt0[5] = {50, 50, 50, 50, 0}; /* the secondary node has none */
    const double KmB = 1000 * area * area / 6, KsB = 2000 * cbrt(2 * 0.5);
    const double KmE = 200 * 2, KsE = 100;
    const double Kexp[5] = {0.2 * KmB * KsB / (KmB + KsB), 0.2 * KmE * KsE / (KmE + KsE),
                            0.2 * KmE, 0.2 * KmE, 0.2 * 700};
    const ct_idx q1[1] = {0}, q2[1] = {1}, q3[1] = {2}, q4[1] = {3}, sec[1] = {4};
    const double tol = CTT_TOL(1e-10, 1e-3);
    for (int c = 0; c < 5; c++) {
        tnodes tn;
        tn_init(&tn, 5);
        for (int i = 0; i < 4; i++)
            tn_set(&tn, i, Xr[i][0], Xr[i][1], Xr[i][2]);
        tn_set(&tn, 4, P[0], P[1], P[2]);
        ctd_iface_cfg cfg = ctd_iface_default_cfg(5);
        ctd_iface_data d;
        memset(&d, 0, sizeof d);
        d.nnode = 5;
        d.nseg = 1;
        d.n1 = q1;
        d.n2 = q2;
        d.n3 = q3;
        d.n4 = q4;
        d.nsec = 1;
        d.sec = sec;
        if (c == 0) {
            d.seg_B = sB;
            d.seg_A = sA;
            d.seg_V = sV;
            d.node_B = nB;
            d.node_vnode = nV;
        } else {
            d.seg_E = sE;
            d.seg_t = sT;
        }
        if (c == 1)
            d.node_et = nEt; /* series */
        if (c == 3)
            d.node_et = nEt0; /* Ks = 0 at the node: the main spring alone */
        if (c == 4)
            d.K = 700; /* constant (c == 2: no node inputs, main alone) */
        ctd_iface *it = make_iface(&cfg, &d);
        ctd_iface_report rep;
        tstep(it, &tn, 0, 1e-3, &rep);
        const double K = Kexp[c], F = K * p;
        cr_assert_eq(rep.nactive, 1, "case %d", c);
        /* The node is pushed out along the face normal with K p. */
        const double fn[3] = {tn.fx[4], tn.fy[4], tn.fz[4]};
        for (int a = 0; a < 3; a++)
            cr_assert(fabs(fn[a] - F * n[a]) <= tol * F, "case %d axis %d: %g expected %g", c,
                      a, fn[a], F * n[a]);
        /* Main node i gets -N_i(s, t) F. */
        for (int i = 0; i < 4; i++) {
            const double fi[3] = {tn.fx[i], tn.fy[i], tn.fz[i]};
            for (int a = 0; a < 3; a++)
                cr_assert(fabs(fi[a] + N[i] * F * n[a]) <= tol * F,
                          "case %d node %d axis %d: %g expected %g", c, i, a, fi[a],
                          -N[i] * F * n[a]);
        }
        /* Momentum and the moment about the contact point. */
        double sum[3] = {0, 0, 0}, M[3] = {0, 0, 0};
        for (int k = 0; k < 5; k++) {
            const double f[3] = {tn.fx[k], tn.fy[k], tn.fz[k]};
            const double r[3] = {tn.x[k] - C[0], tn.y[k] - C[1], tn.z[k] - C[2]};
            double m[3];
            cross(r, f, m);
            for (int a = 0; a < 3; a++) {
                sum[a] += f[a];
                M[a] += m[a];
            }
        }
        for (int a = 0; a < 3; a++) {
            cr_assert(fabs(sum[a]) <= tol * F, "case %d: force sum %g", c, sum[a]);
            cr_assert(fabs(M[a]) <= tol * F * 2, "case %d: moment %g", c, M[a]);
        }
        cr_assert(fabs(rep.e_contact - 0.5 * K * p * p) <= tol * 0.5 * K * p * p,
                  "case %d: energy %g expected %g", c, rep.e_contact, 0.5 * K * p * p);
        cr_assert(fabs((double)rep.kmax - K) <= tol * K);
        cr_assert(fabs((double)rep.dt - sqrt(2.0 / K)) <= tol * sqrt(2.0 / K));
        for (int a = 0; a < 3; a++)
            cr_assert(fabs(rep.force[a] - F * n[a]) <= tol * F);
        ctd_iface_destroy(it);
        tn_free(&tn);
    }
}

/* ---- TYPE5: topological against direct search --------------------------- */

Test(iface_type356, type5_topological_finds_what_direct_finds)
{
    /* One node per row of quads (so a main node sums at most two nonzero
     * reactions, in an order that cannot change the result), each at its
     * own depth, sliding 4.5 elements along x. */
    enum { NX = 8, NY = 4, NS = 4, NSEG = NX * NY, NG = (NX + 1) * (NY + 1) };
    const double K = 100, v = 1.0, dt = 0.01;
    const double pen[NS] = {0.01, 0.02, 0.005, 0.03};
    const double y0[NS] = {0.5, 1.5, 2.5, 3.5}, x0[NS] = {0, 0.37, 0.71, 0.13};
    ct_idx m1[NSEG], m2[NSEG], m3[NSEG], m4[NSEG], sec[NS];
    ct_idx *q[4] = {m1, m2, m3, m4};
    grid_segments(NX, NY, 0, 0, q);
    tnodes tn;
    tn_init(&tn, NG + NS);
    for (int j = 0; j <= NY; j++)
        for (int i = 0; i <= NX; i++)
            tn_set(&tn, j * (NX + 1) + i, i + 0.3 * j, j, 0);
    for (int k = 0; k < NS; k++) {
        sec[k] = NG + k;
        tn.vx[NG + k] = (ct_real)v;
    }
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = NG + NS;
    d.nseg = NSEG;
    d.n1 = m1;
    d.n2 = m2;
    d.n3 = m3;
    d.n4 = m4;
    d.nsec = NS;
    d.sec = sec;
    d.K = (ct_real)(K / 0.2); /* K = Stfac K_data */
    ctd_iface *it[2];
    for (int a = 0; a < 2; a++) {
        ctd_iface_cfg cfg = ctd_iface_default_cfg(5);
        if (a == 1)
            cfg.algo = CT_SEARCH_DIRECT;
        it[a] = make_iface(&cfg, &d);
    }
    ct_real *f[2];
    for (int a = 0; a < 2; a++) {
        f[a] = ct_calloc(3 * (size_t)tn.n, sizeof(ct_real));
        cr_assert(f[a]);
    }
    const double tol = CTT_TOL(1e-9, 1e-3);
    int resorts = 0;
    for (int step = 0; step < 450; step++) {
        const double x = 0.6 + v * dt * step;
        for (int k = 0; k < NS; k++)
            tn_set(&tn, NG + k, x + x0[k] + 0.3 * y0[k], y0[k], -pen[k]);
        for (int a = 0; a < 2; a++) {
            ctd_iface_report rep;
            tstep(it[a], &tn, step * dt, dt, &rep);
            cr_assert_eq(rep.nactive, NS, "%s, step %d: %d active",
                         a ? "direct" : "topological", step, (int)rep.nactive);
            resorts += a == 0 ? rep.resorted : 0;
            memcpy(f[a], tn.fx, sizeof(ct_real) * (size_t)tn.n);
            memcpy(f[a] + tn.n, tn.fy, sizeof(ct_real) * (size_t)tn.n);
            memcpy(f[a] + 2 * tn.n, tn.fz, sizeof(ct_real) * (size_t)tn.n);
            for (int k = 0; k < NS; k++)
                cr_assert(fabs(tn.fz[NG + k] - K * pen[k]) <= tol * K * pen[k],
                          "step %d node %d: %g expected %g", step, k, (double)tn.fz[NG + k],
                          K * pen[k]);
        }
        for (ct_idx i = 0; i < 3 * tn.n; i++)
            cr_assert(f[0][i] == f[1][i], "step %d: force %d differs: %.17g against %.17g",
                      step, (int)i, (double)f[0][i], (double)f[1][i]);
    }
    /* The nodes crossed 4.5 elements: the topological search hopped. */
    cr_assert(resorts >= 10, "only %d searches", resorts);
    for (int a = 0; a < 2; a++) {
        ctd_iface_destroy(it[a]);
        ct_free(f[a]);
    }
    tn_free(&tn);
}

/* ---- TYPE3: two faces pressed into each other ---------------------------- */

/* Main face 3 x 3 unit quads on [0,3]^2 at z = 0 facing +z (nodes 0..15);
 * secondary face 2 x 2 unit quads on [0.5,2.5]^2 at z = zs facing -z
 * (nodes 16..24). */
typedef struct faces {
    tnodes t;
    ct_idx m[4][9], s[4][4];
    ct_real mB[1], sB[1];
    ct_real segB[9], segA[9], segV[9], ssgB[4], ssgA[4], ssgV[4], nodeB[25], nodeV[25];
} faces;

static void faces_make(faces *F, double zs)
{
    memset(F, 0, sizeof *F);
    tn_init(&F->t, 25);
    for (int j = 0; j <= 3; j++)
        for (int i = 0; i <= 3; i++)
            tn_set(&F->t, j * 4 + i, i, j, 0);
    for (int j = 0; j <= 2; j++)
        for (int i = 0; i <= 2; i++)
            tn_set(&F->t, 16 + j * 3 + i, 0.5 + i, 0.5 + j, zs);
    ct_idx *qm[4] = {F->m[0], F->m[1], F->m[2], F->m[3]};
    ct_idx *qs[4] = {F->s[0], F->s[1], F->s[2], F->s[3]};
    grid_segments(3, 3, 0, 0, qm);
    grid_segments(2, 2, 16, 1, qs);
    /* Main bricks B 1000, A 1, V 1 (Km 1000); secondary B 3000, A 1, V 2
     * (Km 1500); node stiffness B (2 * 0.5)^(1/3) = B: 500 on the main
     * nodes, 800 on the secondary ones. */
    for (int k = 0; k < 9; k++) {
        F->segB[k] = 1000;
        F->segA[k] = 1;
        F->segV[k] = 1;
    }
    for (int k = 0; k < 4; k++) {
        F->ssgB[k] = 3000;
        F->ssgA[k] = 1;
        F->ssgV[k] = 2;
    }
    for (int k = 0; k < 25; k++) {
        F->nodeB[k] = k < 16 ? 500 : 800;
        F->nodeV[k] = (ct_real)0.5;
    }
    for (ct_idx k = 16; k < 25; k++)
        F->t.m[k] = 2;
}

static ctd_iface_data faces_data(const faces *F)
{
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 25;
    d.nseg = 9;
    d.n1 = F->m[0];
    d.n2 = F->m[1];
    d.n3 = F->m[2];
    d.n4 = F->m[3];
    d.nsseg = 4;
    d.s1 = F->s[0];
    d.s2 = F->s[1];
    d.s3 = F->s[2];
    d.s4 = F->s[3];
    d.seg_B = F->segB;
    d.seg_A = F->segA;
    d.seg_V = F->segV;
    d.ssg_B = F->ssgB;
    d.ssg_A = F->ssgA;
    d.ssg_V = F->ssgV;
    d.node_B = F->nodeB;
    d.node_vnode = F->nodeV;
    return d;
}

Test(iface_type356, type3_both_passes_action_reaction_energy)
{
    const double delta = 0.01;
    /* Pass 1: 9 secondary nodes into the main face, K1 = 0.2 series(1000,
     * 800); pass 2: the 4 inner main nodes into the secondary face,
     * K2 = 0.2 series(1500, 500). */
    const double K1 = 0.2 * 1000 * 800 / 1800.0, K2 = 0.2 * 1500 * 500 / 2000.0;
    const double Fs = (9 * K1 + 4 * K2) * delta, E = (9 * K1 + 4 * K2) * delta * delta / 2;
    const double tol = CTT_TOL(1e-10, 1e-3);
    for (int algo = 0; algo < 2; algo++) {
        faces F;
        faces_make(&F, -delta);
        ctd_iface_cfg cfg = ctd_iface_default_cfg(3);
        if (algo)
            cfg.algo = CT_SEARCH_DIRECT;
        ctd_iface_data d = faces_data(&F);
        ctd_iface *it = make_iface(&cfg, &d);
        ctd_iface_report rep;
        tstep(it, &F.t, 0, 1e-3, &rep);
        cr_assert_eq(rep.nactive, 13, "%d active pairs", (int)rep.nactive);
        double fm[3] = {0, 0, 0}, fsec[3] = {0, 0, 0};
        for (ct_idx k = 0; k < 25; k++) {
            double *acc = k < 16 ? fm : fsec;
            acc[0] += F.t.fx[k];
            acc[1] += F.t.fy[k];
            acc[2] += F.t.fz[k];
        }
        cr_assert(fabs(fsec[2] - Fs) <= tol * Fs, "secondary side %g expected %g", fsec[2], Fs);
        for (int a = 0; a < 3; a++) {
            cr_assert(fabs(fsec[a] + fm[a]) <= tol * Fs, "axis %d: %g against %g", a, fsec[a],
                      fm[a]);
            cr_assert(fabs(rep.force[a] - fsec[a]) <= tol * Fs, "report axis %d: %g, nodes %g",
                      a, rep.force[a], fsec[a]);
        }
        /* Each pass pushes its own nodes out: secondary nodes up by K1 d,
         * inner main nodes down by K2 d (plus pass-1 reactions). */
        for (ct_idx k = 16; k < 25; k++)
            cr_assert(F.t.fz[k] > (ct_real)(K1 * delta * 0.999));
        cr_assert(fabs(rep.e_contact - E) <= tol * E, "energy %.12g expected %.12g",
                  rep.e_contact, E);
        cr_assert(fabs((double)rep.kmax - K1) <= tol * K1);
        ctd_iface_destroy(it);
        tn_free(&F.t);
    }
}

/* ---- Defaults and bad cards ----------------------------------------------- */

Test(iface_type356, defaults)
{
    for (int type = 3; type <= 6; type++) {
        if (type == 4)
            continue;
        ctd_iface_cfg c = ctd_iface_default_cfg(type);
        cr_assert_eq(c.type, type);
        cr_assert(fabs((double)c.Stfac - 0.2) < 1e-7);
        cr_assert(c.VisS == 0 && c.two_sided == 0 && c.self == 0 && c.gap == 0);
        cr_assert_eq(c.quad, CT_QUAD_CLOSED);
        cr_assert_eq(c.algo, type == 6 ? CT_SEARCH_BUCKET : CT_SEARCH_TOPO);
        cr_assert(c.ncurve == 0 && !c.curve_p && !c.curve_f);
    }
}

Test(iface_type356, bad_cards)
{
    const ct_idx q1[1] = {0}, q2[1] = {1}, q3[1] = {2}, q4[1] = {3}, sec[1] = {4};
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 5;
    d.nseg = 1;
    d.n1 = q1;
    d.n2 = q2;
    d.n3 = q3;
    d.n4 = q4;
    d.nsec = 1;
    d.sec = sec;
    d.K = 10;
    ctd_iface *it = NULL;
    ct_diag diag;
    /* TYPE6 without a curve, and with abscissae that go down. */
    ctd_iface_cfg c = ctd_iface_default_cfg(6);
    memset(&diag, 0, sizeof diag);
    cr_assert_eq(ctd_iface_init(&it, &c, &d, &diag), CT_ERR_ARG);
    cr_assert_null(it);
    cr_assert(strstr(diag.msg, "TYPE6") && strstr(diag.msg, "curve"), "message: %s", diag.msg);
    const ct_real dp[3] = {0, 0.02, 0.01}, df[3] = {0, 10, 20};
    c.ncurve = 3;
    c.curve_p = dp;
    c.curve_f = df;
    memset(&diag, 0, sizeof diag);
    cr_assert_eq(ctd_iface_init(&it, &c, &d, &diag), CT_ERR_ARG);
    cr_assert_null(it);
    cr_assert_eq(diag.index, 2, "index %lld: %s", (long long)diag.index, diag.msg);
    cr_assert(strstr(diag.msg, "TYPE6") && strstr(diag.msg, "abscissa"), "message: %s",
              diag.msg);
    /* TYPE5 without secondary nodes; without a stiffness. */
    c = ctd_iface_default_cfg(5);
    ctd_iface_data e = d;
    e.nsec = 0;
    e.sec = NULL;
    memset(&diag, 0, sizeof diag);
    cr_assert_eq(ctd_iface_init(&it, &c, &e, &diag), CT_ERR_ARG);
    cr_assert_null(it);
    cr_assert(strstr(diag.msg, "TYPE5") && strstr(diag.msg, "secondary"), "message: %s",
              diag.msg);
    e = d;
    e.K = 0;
    memset(&diag, 0, sizeof diag);
    cr_assert_eq(ctd_iface_init(&it, &c, &e, &diag), CT_ERR_ARG);
    cr_assert(strstr(diag.msg, "stiffness"), "message: %s", diag.msg);
    /* Two-sided without a gap. */
    c.two_sided = 1;
    cr_assert_eq(ctd_iface_init(&it, &c, &d, &diag), CT_ERR_ARG);
    cr_assert(strstr(diag.msg, "gap"), "message: %s", diag.msg);
    /* TYPE3 without secondary segments; a bad index. */
    c = ctd_iface_default_cfg(3);
    cr_assert_eq(ctd_iface_init(&it, &c, &d, &diag), CT_ERR_ARG);
    cr_assert(strstr(diag.msg, "TYPE3"), "message: %s", diag.msg);
    c = ctd_iface_default_cfg(5);
    const ct_idx bad[1] = {9};
    e = d;
    e.sec = bad;
    cr_assert_eq(ctd_iface_init(&it, &c, &e, &diag), CT_ERR_RANGE);
    cr_assert_null(it);
    /* The good card passes. */
    cr_assert_eq(ctd_iface_init(&it, &c, &d, &diag), CT_OK, "%s", diag.msg);
    cr_assert_eq(ctd_iface_type(it), 5);
    cr_assert_eq(ctd_iface_nsec(it), 1);
    ctd_iface_destroy(it);
}

/* ---- Determinism ------------------------------------------------------------ */

/* Two jittered faces nx by nx pressed into each other by 0.005 .. 0.02, the
 * upper one sliding; TYPE3 with friction and damping. Returns the forces of
 * the last step (3 n) and the energies. */
static void type3_run(int nx, ct_real *out, double en[3])
{
    const ct_idx ng = (ct_idx)((nx + 1) * (nx + 1)), ns = (ct_idx)(nx * nx);
    tnodes tn;
    tn_init(&tn, 2 * ng);
    unsigned seed = 2024;
    for (int l = 0; l < 2; l++)
        for (int j = 0; j <= nx; j++)
            for (int i = 0; i <= nx; i++) {
                double r[3];
                for (int a = 0; a < 3; a++) {
                    seed = seed * 1103515245u + 12345u;
                    r[a] = (double)((seed >> 8) % 1000) / 1000.0;
                }
                ct_idx k = (ct_idx)(l * ng + j * (nx + 1) + i);
                tn_set(&tn, k, i + 0.3 * (r[0] - 0.5), j + 0.3 * (r[1] - 0.5),
                       l ? -0.005 - 0.015 * r[2] : 0.002 * r[2]);
                tn.vx[k] = l ? (ct_real)0.4 : 0;
                tn.vz[k] = l ? (ct_real)-0.1 : 0;
                tn.m[k] = (ct_real)(1 + r[2]);
            }
    ct_idx *q[8];
    for (int a = 0; a < 8; a++) {
        q[a] = ct_calloc((size_t)ns, sizeof(ct_idx));
        cr_assert(q[a]);
    }
    grid_segments(nx, nx, 0, 0, q);
    grid_segments(nx, nx, ng, 1, q + 4);
    ctd_iface_cfg cfg = ctd_iface_default_cfg(3);
    cfg.Fric = (ct_real)0.2;
    cfg.VisS = (ct_real)0.1;
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 2 * ng;
    d.nseg = ns;
    d.n1 = q[0];
    d.n2 = q[1];
    d.n3 = q[2];
    d.n4 = q[3];
    d.nsseg = ns;
    d.s1 = q[4];
    d.s2 = q[5];
    d.s3 = q[6];
    d.s4 = q[7];
    d.K = 500;
    ctd_iface *it = make_iface(&cfg, &d);
    const double dt = 0.01;
    en[0] = en[1] = en[2] = 0;
    for (int step = 0; step < 8; step++) {
        ctd_iface_report rep;
        tstep(it, &tn, step * dt, dt, &rep);
        cr_assert(rep.nactive > ns, "step %d: %d active", step, (int)rep.nactive);
        en[0] = rep.e_contact;
        en[1] += rep.e_damp;
        en[2] += rep.e_fric;
        for (ct_idx k = ng; k < 2 * ng; k++)
            tn.x[k] += tn.vx[k] * (ct_real)dt;
    }
    memcpy(out, tn.fx, sizeof(ct_real) * (size_t)tn.n);
    memcpy(out + tn.n, tn.fy, sizeof(ct_real) * (size_t)tn.n);
    memcpy(out + 2 * tn.n, tn.fz, sizeof(ct_real) * (size_t)tn.n);
    ctd_iface_destroy(it);
    for (int a = 0; a < 8; a++)
        ct_free(q[a]);
    tn_free(&tn);
}

Test(iface_type356, type3_threads_bit_identical)
{
    const int nx = ctt_checking() ? 12 : 40;
    const size_t n = 3 * 2 * (size_t)((nx + 1) * (nx + 1));
    ct_real *f[2];
    double en[2][3];
    for (int th = 0; th < 2; th++) {
        ctt_threads(th + 1);
        f[th] = ct_calloc(n, sizeof(ct_real));
        cr_assert(f[th]);
        type3_run(nx, f[th], en[th]);
    }
    ctt_threads(2);
    cr_assert_eq(memcmp(f[0], f[1], n * sizeof(ct_real)), 0,
                 "forces differ between 1 and 2 threads");
    cr_assert(memcmp(en[0], en[1], sizeof en[0]) == 0, "energies differ");
    cr_assert(en[0][0] > 0 && en[0][1] > 0 && en[0][2] > 0, "energies %g %g %g", en[0][0],
              en[0][1], en[0][2]);
    ct_free(f[0]);
    ct_free(f[1]);
}
