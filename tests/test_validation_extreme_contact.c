/*
 * test_validation_extreme_contact.c -- validation extremes (issue 6) of the
 * contact logic, end to end through the interface object:
 *  g. a node exactly on a vertex shared by many segments (a fan of 6 quads,
 *     a fan of 8 triangles, a cone of 8 triangles): exactly one pair
 *     carries it (driver/interfaces/pair_select.c), the force is the law
 *     of the penetration once (not 6 or 8 times), and it follows a
 *     brute-force closest-point truth, continuously, as the node moves off
 *     the vertex across the segments;
 *  h. initial penetrations (TYPE24 Inacti, Ipen0, Ipen_max): with Inacti
 *     the penetration is subtracted and nothing moves; with Ipen_max the
 *     deeper pairs are deactivated and only the shallow nodes are pushed
 *     out; without either the full force acts and the energy stored at
 *     the start is what the nodes carry away.
 */
#include "test_util.h"
#include "test_validation.h"

#include <stdint.h>
#include <string.h>

#include "test_validation_extreme.h"

/* ---- g. A node on a vertex shared by many segments ------------------------------- */

/* Distance from p to the triangle abc (brute force: the plane when the
 * projection is inside, else the closest of the three edges). */
static double seg_dist(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], t = 0, l2 = 0, d2 = 0;
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ap[k] = p[k] - a[k];
        t += ab[k] * ap[k];
        l2 += ab[k] * ab[k];
    }
    t = fmin(1, fmax(0, t / l2));
    for (int k = 0; k < 3; k++) {
        double e = ap[k] - t * ab[k];
        d2 += e * e;
    }
    return sqrt(d2);
}

static double tri_dist(const double p[3], const double a[3], const double b[3],
                       const double c[3])
{
    double u[3], v[3], w[3], n[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = p[k] - a[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    /* Barycentric coordinates of the projection. */
    double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2], wv = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
    double den = uu * vv - uv * uv, s = (vv * wu - uv * wv) / den, t = (uu * wv - uv * wu) / den;
    if (s >= 0 && t >= 0 && s + t <= 1)
        return fabs(w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) / sqrt(nn);
    return fmin(seg_dist(p, a, b), fmin(seg_dist(p, b, c), seg_dist(p, c, a)));
}

/* A fan around node 0 at (0, 0, apex): nfan triangles (quads = 0) or quads
 * (quads = 1, nfan quads with a mid-rim node each, 2 nfan rim nodes) to the
 * rim of radius 1 at z = 0; segments counter-clockwise seen from +z. The
 * secondary node is the last one. Returns the node count. */
static ct_idx fan(nodes *p, ct_idx *q[4], int nfan, int quads, double apex)
{
    int nrim = quads ? 2 * nfan : nfan;
    nodes_init(p, (ct_idx)(nrim + 2));
    p->z[0] = (ct_real)apex;
    for (int k = 0; k < nrim; k++) {
        double a = 2 * 3.141592653589793 * k / nrim, r = quads && (k % 2) ? 1.2 : 1.0;
        p->x[1 + k] = (ct_real)(r * cos(a));
        p->y[1 + k] = (ct_real)(r * sin(a));
    }
    for (int s = 0; s < nfan; s++) {
        q[0][s] = 0;
        if (quads) {
            q[1][s] = (ct_idx)(1 + 2 * s);
            q[2][s] = (ct_idx)(1 + 2 * s + 1);
            q[3][s] = (ct_idx)(1 + (2 * s + 2) % nrim);
        } else {
            q[1][s] = (ct_idx)(1 + s);
            q[2][s] = (ct_idx)(1 + (s + 1) % nrim);
            q[3][s] = q[2][s];
        }
    }
    return (ct_idx)(nrim + 2);
}

/* The truth: the distance from node `nd` to the fan (every triangle; a
 * planar quad as its two triangles 0-1-2, 0-2-3). */
static double fan_dist(const nodes *p, ct_idx *q[4], int nseg, ct_idx nd)
{
    double P[3] = {p->x[nd], p->y[nd], p->z[nd]}, best = INFINITY;
    for (int s = 0; s < nseg; s++) {
        double X[4][3];
        for (int a = 0; a < 4; a++) {
            X[a][0] = p->x[q[a][s]];
            X[a][1] = p->y[q[a][s]];
            X[a][2] = p->z[q[a][s]];
        }
        best = fmin(best, tri_dist(P, X[0], X[1], X[2]));
        if (q[3][s] != q[2][s])
            best = fmin(best, tri_dist(P, X[0], X[2], X[3]));
    }
    return best;
}

/* The law of a carried penetration: linear K q or TYPE7's K0 g x/(1 - x). */
static double law(int type, double K, double g, double q)
{
    if (q <= 0)
        return 0;
    return type == 7 ? K * q / (1 - q / g) : K * q;
}

typedef struct fan_case {
    const char *name;
    int type, quads, nfan;
    double apex;
} fan_case;

/*
 * The node starts exactly over the shared vertex, q = 0.3 g inside the
 * gap g = 0.1 (two-sided; for the one-sided quad fan, 0.03 behind the
 * face with gap 0), then moves 0.9 off it in 300 steps along a direction
 * that crosses several segments and edges, keeping its height. At every
 * position one pair is active and the force is law(g - D_true) (one-sided:
 * law(-z)) with D_true from the brute-force truth. Returns the largest
 * relative force error; the curve goes to f.
 */
static double fan_run(const fan_case *fc, FILE *f, int col)
{
    const double K = 1e3, g = 0.1;
    const int one_sided = fc->quads; /* the quad fan: TYPE24 on a solid face, gap 0 */
    ct_idx *q[4];
    for (int a = 0; a < 4; a++)
        cr_assert((q[a] = ct_calloc(16, sizeof(ct_idx))) != NULL);
    nodes p;
    ct_idx nn = fan(&p, q, fc->nfan, fc->quads, fc->apex);
    ct_idx nd = nn - 1, secl[1] = {nd};
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = nn;
    d.nseg = fc->nfan;
    d.n1 = q[0];
    d.n2 = q[1];
    d.n3 = q[2];
    d.n4 = q[3];
    d.nsec = 1;
    d.sec = secl;
    ctd_iface_cfg c = ctd_iface_default_cfg(fc->type);
    c.VisS = 0;
    c.algo = CT_SEARCH_DIRECT;
    c.gap = one_sided ? 0 : (ct_real)g;
    c.two_sided = !one_sided;
    if (fc->type == 7) {
        c.Istf = 1;
        c.Stfac = (ct_real)K;
    } else {
        d.K = (ct_real)K;
    }
    ctd_iface *it = make(&c, &d);
    /* Over a cone the node descends with the surface (height apex (1 - r)
     * plus 0.7 g), so that it stays in the gap. */
    const double dir = 0.3, len = 0.9;
    const int N = 300;
    double worst = 0, dt = 1e-3;
    for (int k = 0; k <= N; k++) {
        double r = len * k / N;
        double z = one_sided ? -0.03 : fc->apex * (1 - r) + 0.7 * g;
        p.x[nd] = (ct_real)(r * cos(dir));
        p.y[nd] = (ct_real)(r * sin(dir));
        p.z[nd] = (ct_real)z;
        p.vx[nd] = (ct_real)(len / N / dt * cos(dir));
        p.vy[nd] = (ct_real)(len / N / dt * sin(dir));
        p.vz[nd] = (ct_real)(-fc->apex * len / N / dt);
        ctd_iface_report rep;
        nodes_step(it, &p, k * dt, dt, &rep);
        double qt = one_sided ? -(double)p.z[nd] : g - fan_dist(&p, q, fc->nfan, nd);
        double Ft = law(fc->type, K, g, qt);
        double F = sqrt((double)p.fx[nd] * p.fx[nd] + (double)p.fy[nd] * p.fy[nd] +
                        (double)p.fz[nd] * p.fz[nd]);
        cr_assert_eq(rep.nactive, 1, "%s at r = %g: %d active pairs", fc->name, r,
                     (int)rep.nactive);
        cr_assert_eq(p.nact[nd], 1);
        double e = fabs(F - Ft) / Ft;
        cr_assert(e <= CTT_TOL(1e-9, 1e-4), "%s at r = %g: force %.12g, law(q_true) %.12g",
                  fc->name, r, F, Ft);
        worst = fmax(worst, e);
        double c[5] = {NAN, NAN, NAN, NAN, NAN};
        c[col - 1] = F / K;
        ctv_row(f, 6, r, c[0], c[1], c[2], c[3], c[4]);
    }
    ctd_iface_destroy(it);
    nodes_free(&p);
    for (int a = 0; a < 4; a++)
        ct_free(q[a]);
    return worst;
}

Test(validation_extreme, vertex_shared_by_many_segments)
{
    const fan_case cases[] = {
        {"TYPE24 one-sided, 6 quads", 24, 1, 6, 0},
        {"TYPE24 two-sided, 8 triangles", 24, 0, 8, 0},
        {"TYPE24 two-sided, cone of 8 triangles", 24, 0, 8, 0.2},
        {"TYPE7, 8 triangles", 7, 0, 8, 0},
        {"TYPE7, cone of 8 triangles", 7, 0, 8, 0.2},
    };
    const int nc = (int)(sizeof cases / sizeof cases[0]);
    FILE *f = ctv_csv("extreme_vertex_fan", "r,quads6_24,tri8_24,cone8_24,tri8_7,cone8_7");
    for (int i = 0; i < nc; i++) {
        double e = fan_run(&cases[i], f, i + 1);
        char qn[128];
        snprintf(qn, sizeof qn, "%s: force vs law(q_true), worst rel. error", cases[i].name);
        ctv_result("g. vertex fan", qn, e, 0, CTT_TOL(1e-9, 1e-4),
                   "node starts on the shared vertex, moves 0.9 off it in 300 steps; one "
                   "active pair asserted at every step (not 6x or 8x the force)");
    }
    if (f)
        fclose(f);
    ctv_plot("extreme_vertex_fan",
             "Force / K of a node moving off a vertex shared by 6-8 segments",
             "distance from the vertex", "force / K",
             "1,2,points,TYPE24 one-sided 6 quads;1,3,points,TYPE24 two-sided 8 triangles;"
             "1,4,points,TYPE24 two-sided cone;1,5,points,TYPE7 8 triangles;"
             "1,6,points,TYPE7 cone",
             "logy");
}

/* ---- h. Initial penetrations ----------------------------------------------------- */

/*
 * Five free nodes (mass 1) start behind a fixed 4 x 4-quad oriented face
 * (TYPE24, one-sided, gap 0, K = 1e4) at depths 2, 4, 6, 8 and 10 mm, at
 * rest. Run 0.2 s (ten times the contact period) with a constant step of
 * 1e-3 (omega dt = 0.1). Returns the stored energy at the start, the
 * kinetic energy at the end, the count of deactivated pairs and the
 * largest speed of each node.
 */
typedef struct init_out {
    double e0, kin_end, ec_end;
    int64_t deactivated;
    double vmax[5];
} init_out;

static init_out initial_run(int Ipen0, int Inacti, double Ipen_max)
{
    const double K = 1e4, dt = 1e-3;
    const int ns = 16, nplate = 25;
    ct_idx *q[4];
    for (int a = 0; a < 4; a++)
        cr_assert((q[a] = ct_calloc((size_t)ns, sizeof(ct_idx))) != NULL);
    nodes p;
    nodes_init(&p, nplate + 5);
    for (int j = 0; j <= 4; j++)
        for (int i = 0; i <= 4; i++) {
            p.x[j * 5 + i] = (ct_real)i;
            p.y[j * 5 + i] = (ct_real)j;
        }
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            int s = j * 4 + i, a = j * 5 + i;
            q[0][s] = a;
            q[1][s] = a + 1;
            q[2][s] = a + 6;
            q[3][s] = a + 5;
        }
    ct_idx sec[5];
    for (int k = 0; k < 5; k++) {
        ct_idx nd = (ct_idx)(nplate + k);
        sec[k] = nd;
        p.x[nd] = (ct_real)(0.35 + 0.7 * k);
        p.y[nd] = (ct_real)(0.45 + 0.6 * k);
        p.z[nd] = (ct_real)(-0.002 * (k + 1));
    }
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = p.n;
    d.nseg = ns;
    d.n1 = q[0];
    d.n2 = q[1];
    d.n3 = q[2];
    d.n4 = q[3];
    d.nsec = 5;
    d.sec = sec;
    d.K = (ct_real)K;
    ctd_iface_cfg c = ctd_iface_default_cfg(24);
    c.two_sided = 0;
    c.gap = 0;
    c.VisS = 0;
    c.Ipen0 = Ipen0;
    c.Inacti = Inacti;
    c.Ipen_max = (ct_real)Ipen_max;
    ctd_iface *it = make(&c, &d);
    init_out o;
    memset(&o, 0, sizeof o);
    const int N = 200;
    for (int k = 0; k <= N; k++) {
        ctd_iface_report rep;
        nodes_step(it, &p, k * dt, k ? dt : 0, &rep);
        if (k == 0)
            o.e0 = rep.e_contact;
        o.ec_end = rep.e_contact;
        o.deactivated = rep.deactivated;
        if (k == N)
            break;
        for (int j = 0; j < 5; j++) {
            ct_idx nd = sec[j];
            double h = k ? dt : 0.5 * dt;
            p.vz[nd] += (ct_real)(h * p.fz[nd]);
            p.vx[nd] += (ct_real)(h * p.fx[nd]);
            p.vy[nd] += (ct_real)(h * p.fy[nd]);
            p.x[nd] += (ct_real)(dt * p.vx[nd]);
            p.y[nd] += (ct_real)(dt * p.vy[nd]);
            p.z[nd] += (ct_real)(dt * p.vz[nd]);
            o.vmax[j] = fmax(o.vmax[j], fabs((double)p.vz[nd]));
        }
    }
    for (int j = 0; j < 5; j++) {
        ct_idx nd = sec[j];
        o.kin_end += 0.5 * ((double)p.vx[nd] * p.vx[nd] + (double)p.vy[nd] * p.vy[nd] +
                            (double)p.vz[nd] * p.vz[nd]);
    }
    ctd_iface_destroy(it);
    nodes_free(&p);
    for (int a = 0; a < 4; a++)
        ct_free(q[a]);
    return o;
}

Test(validation_extreme, initial_penetration)
{
    const double K = 1e4, tol = CTT_TOL(0.01, 0.01);
    double eall = 0, eshallow = 0;
    for (int k = 0; k < 5; k++) {
        double pk = 0.002 * (k + 1);
        eall += 0.5 * K * pk * pk;
        if (pk <= 0.005)
            eshallow += 0.5 * K * pk * pk;
    }
    /* Without Inacti or Ipen_max: the full force; the energy stored at the
     * start (K p^2/2 per node) is carried away as kinetic energy, and each
     * node leaves at p sqrt(K/m). */
    init_out full = initial_run(0, 0, 0);
    cr_assert(fabs(full.e0 - eall) <= CTT_TOL(1e-12, 1e-6) * eall, "stored %g, K p^2/2 %g",
              full.e0, eall);
    cr_assert(full.ec_end == 0, "still in contact at the end: %g", full.ec_end);
    double e_full = fabs(full.kin_end - eall) / eall;
    cr_assert(e_full <= tol, "kinetic %g against the stored %g", full.kin_end, eall);
    for (int k = 0; k < 5; k++)
        cr_assert(fabs(full.vmax[k] - 0.002 * (k + 1) * sqrt(K)) <= tol * 0.002 * (k + 1) * sqrt(K),
                  "node %d leaves at %g", k, full.vmax[k]);
    /* Inacti: subtracted, nothing stored, nothing moves. */
    init_out sub = initial_run(0, 5, 0);
    cr_assert(sub.e0 == 0 && sub.ec_end == 0 && sub.kin_end == 0, "Inacti: e0 %g kin %g",
              sub.e0, sub.kin_end);
    for (int k = 0; k < 5; k++)
        cr_assert(sub.vmax[k] == 0);
    /* Ipen_max 5 mm: the three deeper pairs are deactivated and stay put;
     * the two shallow nodes are pushed out with the full force. */
    init_out cut = initial_run(0, 0, 0.005);
    cr_assert_eq(cut.deactivated, 3);
    cr_assert(fabs(cut.e0 - eshallow) <= CTT_TOL(1e-12, 1e-6) * eshallow);
    double e_cut = fabs(cut.kin_end - eshallow) / eshallow;
    cr_assert(e_cut <= tol, "kinetic %g against %g", cut.kin_end, eshallow);
    for (int k = 2; k < 5; k++)
        cr_assert(cut.vmax[k] == 0, "deactivated node %d moved", k);
    /* Ipen0 = 1: every initial penetration gets the full force, Inacti and
     * Ipen_max are not applied. */
    init_out ip0 = initial_run(1, 5, 0.005);
    cr_assert(ip0.deactivated == 0 && fabs(ip0.e0 - eall) <= CTT_TOL(1e-12, 1e-6) * eall);
    cr_assert(fabs(ip0.kin_end - eall) <= tol * eall);
    const char *note = "TYPE24 one-sided gap 0, K 1e4, 5 nodes of mass 1 at depths 2..10 mm "
                       "at rest, dt 1e-3 constant, 0.2 s";
    ctv_result("h. initial penetration", "full force: kinetic at end / stored at start - 1",
               e_full, 0, tol, note);
    ctv_result("h. initial penetration", "Inacti: kinetic energy at end (J)", sub.kin_end, 0,
               1e-300, "nothing stored, nothing released");
    ctv_result("h. initial penetration", "Ipen_max 5 mm: pairs deactivated",
               (double)cut.deactivated, 3, 1e-12, note);
    ctv_result("h. initial penetration", "Ipen_max 5 mm: kinetic at end / stored - 1", e_cut,
               0, tol, note);
}
