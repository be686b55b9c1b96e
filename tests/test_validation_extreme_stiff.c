/*
 * test_validation_extreme_stiff.c -- validation extremes (issue 6) of the
 * stiffness, the time step and the gap, driven end to end through the
 * interface object (driver/interfaces/iface.h) with a leapfrog of our own
 * that steps as the driver does (dt = dt_scale x the interface's limit):
 *  a. the stiffness ratio of the two sides from 1e-6 to 1e6 (TYPE5, the
 *     seed's springs in series, K = s Km Ks/(Km + Ks), s = 0.2);
 *  b. a thin shell hit fast enough to tunnel: with the step limits of the
 *     interface (tunnelling 0.9 g/|v|, nodal, TYPE7 kinematic) the node
 *     bounces back; stepping with larger steps ourselves it goes through;
 *  f. gap zero: one-sided contact with gap 0 (penetration = -signed
 *     distance), no division by zero, two-sided gap 0 refused cleanly.
 */
#include "test_util.h"
#include "test_validation.h"

#include <stdint.h>
#include <string.h>

#include "interfaces/build.h"
#include "interfaces/iface.h"

/* ---- Point masses driven through one interface ----------------------------- */

typedef struct pm {
    ct_idx n;
    ct_real *x, *y, *z, *vx, *vy, *vz, *m, *fx, *fy, *fz, *pen;
    int32_t *nact;
    uint8_t *free; /* 1: integrated; 0: held in place */
} pm;

static void pm_init(pm *p, ct_idx n)
{
    memset(p, 0, sizeof *p);
    p->n = n;
    ct_real **a[11] = {&p->x,  &p->y,  &p->z,  &p->vx, &p->vy, &p->vz,
                       &p->m,  &p->fx, &p->fy, &p->fz, &p->pen};
    for (int i = 0; i < 11; i++)
        cr_assert((*a[i] = ct_calloc((size_t)n, sizeof(ct_real))) != NULL);
    cr_assert((p->nact = ct_calloc((size_t)n, sizeof(int32_t))) != NULL);
    cr_assert((p->free = calloc((size_t)n, 1)) != NULL);
    for (ct_idx i = 0; i < n; i++)
        p->m[i] = 1;
}

static void pm_free(pm *p)
{
    ct_real *a[11] = {p->x, p->y, p->z, p->vx, p->vy, p->vz, p->m, p->fx, p->fy, p->fz, p->pen};
    for (int i = 0; i < 11; i++)
        ct_free(a[i]);
    ct_free(p->nact);
    free(p->free);
}

static void pm_set(pm *p, ct_idx i, double x, double y, double z)
{
    p->x[i] = (ct_real)x;
    p->y[i] = (ct_real)y;
    p->z[i] = (ct_real)z;
}

/* Forces of one interface step at x(n) with v(n-1/2) (zeroed first), the
 * per-node penetrations of the interface, every value checked finite. */
static void pm_force(ctd_iface *it, pm *p, double time, double dt, ctd_iface_report *rep)
{
    size_t b = sizeof(ct_real) * (size_t)p->n;
    memset(p->fx, 0, b);
    memset(p->fy, 0, b);
    memset(p->fz, 0, b);
    memset(p->pen, 0, b);
    memset(p->nact, 0, sizeof(int32_t) * (size_t)p->n);
    int rc = ctd_iface_step(it, time, (ct_real)dt, p->x, p->y, p->z, p->vx, p->vy, p->vz, p->m,
                            p->fx, p->fy, p->fz, rep);
    cr_assert_eq(rc, CT_OK, "step at t = %g: %s", time, ct_strerror(rc));
    ctd_iface_fields(it, p->pen, p->nact);
    for (ct_idx i = 0; i < p->n; i++)
        cr_assert(isfinite(p->fx[i]) && isfinite(p->fy[i]) && isfinite(p->fz[i]) &&
                      isfinite(p->pen[i]),
                  "node %d: a non-finite force or penetration at t = %g", (int)i, time);
    cr_assert(isfinite(rep->e_contact) && isfinite(rep->e_damp) && !isnan(rep->dt));
}

/* Kick (dtk) and drift (dt) of the free nodes: the driver's central
 * difference, v(n+1/2) = v(n-1/2) + dtk f/m, x(n+1) = x(n) + dt v(n+1/2). */
static void pm_leap(pm *p, double dtk, double dt)
{
    for (ct_idx i = 0; i < p->n; i++) {
        if (!p->free[i])
            continue;
        p->vx[i] += (ct_real)(dtk * p->fx[i] / p->m[i]);
        p->vy[i] += (ct_real)(dtk * p->fy[i] / p->m[i]);
        p->vz[i] += (ct_real)(dtk * p->fz[i] / p->m[i]);
        p->x[i] += (ct_real)(dt * p->vx[i]);
        p->y[i] += (ct_real)(dt * p->vy[i]);
        p->z[i] += (ct_real)(dt * p->vz[i]);
    }
}

/* The plate [-1, 1]^2 at z = 0 (nodes 0..3, normal +z) and secondary node 4. */
static const ct_idx Q1[1] = {0}, Q2[1] = {1}, Q3[1] = {2}, Q4[1] = {3}, S4[1] = {4};

static void plate(pm *p)
{
    pm_init(p, 5);
    pm_set(p, 0, -1, -1, 0);
    pm_set(p, 1, 1, -1, 0);
    pm_set(p, 2, 1, 1, 0);
    pm_set(p, 3, -1, 1, 0);
    p->free[4] = 1;
}

static ctd_iface_data plate_data(void)
{
    ctd_iface_data d;
    memset(&d, 0, sizeof d);
    d.nnode = 5;
    d.nseg = 1;
    d.n1 = Q1;
    d.n2 = Q2;
    d.n3 = Q3;
    d.n4 = Q4;
    d.nsec = 1;
    d.sec = S4;
    return d;
}

static ctd_iface *make(const ctd_iface_cfg *c, const ctd_iface_data *d)
{
    ctd_iface *it = NULL;
    ct_diag dg = {0, -1, ""};
    int rc = ctd_iface_init(&it, c, d, &dg);
    cr_assert_eq(rc, CT_OK, "init: %s: %s", ct_strerror(rc), dg.msg);
    return it;
}

/* ---- a. Stiffness ratio 1e-6 .. 1e6 ----------------------------------------- */

/* The series stiffness in long double, s lo / (1 + lo/hi) computed the
 * plain way (hand value, independent of the kernel's formula). */
static double series_ref(double s, double km, double ks)
{
    long double a = km, b = ks;
    return (double)((long double)s * a * b / (a + b));
}

/* One bounce of a node of mass 1 at 1 m/s on the plate (TYPE5, one-sided,
 * gap 1e-3) with main stiffness km and node stiffness ks. const_dt > 0:
 * that constant step; otherwise the driver's rule, 0.9 x the interface's
 * limit (the tunnelling limit 0.9 g/|v| while the node approaches, growing
 * as it slows, up to 0.9 sqrt(2m/K)). Outputs: the largest penetration, the
 * pair stiffness and nodal step the interface reported in contact, the
 * exit speed. */
typedef struct bounce_out {
    double pmax, k, dt_nodal, vout;
} bounce_out;

static bounce_out bounce(double km, double ks, double const_dt)
{
    const double gap = 1e-3, v = 1;
    bounce_out o = {0, 0, 0, 0};
    pm p;
    plate(&p);
    pm_set(&p, 4, 0.13, -0.21, 3 * gap);
    p.vz[4] = (ct_real)-v;
    ct_real segE[1] = {(ct_real)km}, segt[1] = {1}, net[5] = {0, 0, 0, 0, (ct_real)ks};
    ctd_iface_cfg c = ctd_iface_default_cfg(5);
    c.gap = (ct_real)gap;
    c.algo = CT_SEARCH_DIRECT;
    ctd_iface_data d = plate_data();
    d.seg_E = segE;
    d.seg_t = segt;
    d.node_et = net;
    ctd_iface *it = make(&c, &d);
    double t = 0, dt_prev = 0;
    int steps = 0;
    for (; steps < 20000; steps++) {
        ctd_iface_report rep;
        pm_force(it, &p, t, dt_prev, &rep);
        o.pmax = fmax(o.pmax, (double)p.pen[4]);
        if (rep.nactive > 0) {
            o.k = rep.kmax;
            o.dt_nodal = rep.dt_nodal;
        }
        if (p.z[4] > 3 * gap && p.vz[4] > 0)
            break;
        double dt = const_dt > 0 ? const_dt : 0.9 * (rep.dt < 1e-2 ? rep.dt : 1e-2);
        pm_leap(&p, steps ? 0.5 * (dt_prev + dt) : 0.5 * dt, dt);
        dt_prev = dt;
        t += dt;
    }
    cr_assert(steps < 20000, "km %g ks %g: the node never left", km, ks);
    o.vout = p.vz[4] / v;
    ctd_iface_destroy(it);
    pm_free(&p);
    return o;
}

/*
 * A node of mass 1 hits the plate at 1 m/s. The softer side has the
 * stiffness Ksoft = 5e4 N/m, the stiffer one ratio x Ksoft (main segment
 * Km = E t, secondary node Ks = its shell's E t). The seed's law
 * K = 0.2 Km Ks/(Km + Ks) must come out to a few ulps for every ratio, the
 * largest penetration must be the linear spring's v sqrt(m/K) (energy:
 * K p^2/2 = m v^2/2), and the nodal step the interface reports must be
 * sqrt(2 m/K): the softer side sets both, however stiff the other. The
 * exit speed is measured three times: with a small constant step (the law
 * conserves energy: the node leaves at its impact speed), with the largest
 * constant step the nodal limit allows (reported), and with the driver's
 * step rule, whose step grows inside the contact (the tunnelling limit
 * 0.9 g/|v| grows as the node slows, up to 0.9 sqrt(2m/K)): resolved in a
 * few steps, the contact loses energy (a known limit, asserted and
 * reported).
 */
Test(validation_extreme, stiffness_ratio_series)
{
    const double ksoft = 5e4, m = 1, v = 1, s = 0.2;
    const double tol_k = CTT_TOL(1e-13, 1e-6), tol_p = 0.02; /* measured 0.95 % */
    const double tol_v = CTT_TOL(1e-3, 2e-3), tol_vdrv = 0.10;
    FILE *f = ctv_csv("extreme_stiffness_ratio",
                      "ratio,K_over_Ksoft,K_ref_over_Ksoft,pmax_over_ref,dt_over_ref,"
                      "vout_const_dt,vout_driver_dt");
    double worst_k = 0, worst_p = 0, worst_dt = 0, worst_v = 0, worst_vdrv = 0, vbig = 0;
    for (int e = -6; e <= 6; e++) {
        double ratio = pow(10.0, e);
        double km = ratio >= 1 ? ratio * ksoft : ksoft, ks = ratio >= 1 ? ksoft : ksoft / ratio;
        const double kref = series_ref(s, km, ks);
        const double pref = v * sqrt(m / kref), dtref = sqrt(2 * m / kref);
        bounce_out a = bounce(km, ks, 0), b = bounce(km, ks, 0.9 * 0.9e-3);
        /* The largest constant step the driver could take in contact,
         * 0.9 sqrt(2m/K): the contact lasts about 2.5 steps. */
        bounce_out c = bounce(km, ks, 0.9 * dtref);
        vbig = fmax(vbig, fabs(c.vout - 1));
        double ek = ctt_rel(a.k, kref), ep = ctt_rel(a.pmax, pref);
        double edt = ctt_rel(a.dt_nodal, dtref), ev = fabs(b.vout - 1);
        double evd = fabs(a.vout - 1);
        cr_assert(ek <= tol_k, "ratio %g: K %.17g, series %.17g", ratio, a.k, kref);
        cr_assert(ep <= tol_p, "ratio %g: pmax %g, v sqrt(m/K) %g", ratio, a.pmax, pref);
        cr_assert(ctt_rel(b.pmax, pref) <= tol_p, "ratio %g: pmax %g (constant step)", ratio,
                  b.pmax);
        cr_assert(edt <= tol_k, "ratio %g: dt_nodal %g, sqrt(2m/K) %g", ratio, a.dt_nodal,
                  dtref);
        cr_assert(ev <= tol_v, "ratio %g: leaves at %g of the impact speed", ratio, b.vout);
        cr_assert(evd <= tol_vdrv, "ratio %g: leaves at %g of the impact speed (driver step)",
                  ratio, a.vout);
        /* The softer side dictates: K between 0.1 and 0.2 Ksoft. */
        cr_assert(a.k <= s * ksoft * (1 + tol_k) && a.k >= 0.5 * s * ksoft * (1 - tol_k));
        worst_k = fmax(worst_k, ek);
        worst_p = fmax(worst_p, ep);
        worst_dt = fmax(worst_dt, edt);
        worst_v = fmax(worst_v, ev);
        worst_vdrv = fmax(worst_vdrv, evd);
        ctv_row(f, 7, ratio, a.k / ksoft, kref / ksoft, a.pmax / pref, a.dt_nodal / dtref,
                b.vout, a.vout);
    }
    if (f)
        fclose(f);
    ctv_plot("extreme_stiffness_ratio",
             "TYPE5 springs in series: stiffness ratio Km/Ks from 1e-6 to 1e6",
             "stiffness ratio Km/Ks", "normalised value",
             "1,2,points,K / Ksoft (interface);1,3,dashed,0.2 Km Ks/(Km+Ks) / Ksoft (seed 000);"
             "1,4,linespoints,pmax / v sqrt(m/K);1,5,linespoints,nodal step / sqrt(2m/K);"
             "1,6,linespoints,exit / impact speed (constant step);"
             "1,7,linespoints,exit / impact speed (driver's step)",
             "logx");
    const char *note = "TYPE5 one-sided, node m=1 at 1 m/s on a fixed quad, gap 1e-3, "
                       "softer side 5e4 N/m, ratios 1e-6..1e6, dt = 0.9 x interface limit";
    ctv_result("a. stiffness ratio", "series K rel. error (worst ratio)", worst_k, 0, tol_k,
               note);
    ctv_result("a. stiffness ratio", "pmax vs v sqrt(m/K) rel. error (worst)", worst_p, 0,
               tol_p, note);
    ctv_result("a. stiffness ratio", "dt_nodal vs sqrt(2m/K) rel. error (worst)", worst_dt, 0,
               tol_k, note);
    ctv_result("a. stiffness ratio", "exit speed error, constant step 8.1e-4 (worst)", worst_v,
               0, tol_v, note);
    ctv_result("a. stiffness ratio", "exit speed error, constant step 0.9 sqrt(2m/K) (worst)",
               vbig, 0, 0, "the contact force switches on and off between steps");
    ctv_result("a. stiffness ratio", "exit speed error, driver's step rule (worst)",
               worst_vdrv, 0, tol_vdrv,
               "known limit: the step grows from 0.9 x 0.9 g/v to 0.9 sqrt(2m/K) inside the "
               "contact; the variable-step central difference loses this much speed");
}

/* ---- b. Tunnelling through a thin shell -------------------------------------- */

/*
 * One node of mass 1 thrown at the plate (a shell of thickness g = 0.01,
 * mid-surface z = 0, both sides) from z = 3.3 g at speed v. step_factor
 * <= 0: the driver's step, 0.9 x the interface's limit (tunnelling
 * 0.9 g/|v|, nodal, kinematic); > 0: a fixed step step_factor g / v of our
 * own (the limits ignored). Returns the final z of the node (below 0: it
 * went through) after 3 g / v beyond the time a free flight would need to
 * cross; *vmax receives the largest speed seen (energy created shows here).
 */
static double tunnel_run(int type, double K, double v, double step_factor, double *vmax)
{
    const double g = 0.01, z0 = 3.3 * g;
    pm p;
    plate(&p);
    pm_set(&p, 4, 0.1, 0.2, z0);
    p.vz[4] = (ct_real)-v;
    ctd_iface_cfg c = ctd_iface_default_cfg(type);
    c.gap = (ct_real)g;
    c.VisS = 0;
    c.algo = CT_SEARCH_DIRECT;
    c.two_sided = 1;
    if (type == 7) {
        c.Istf = 1;
        c.Stfac = (ct_real)K;
    }
    ctd_iface_data d = plate_data();
    if (type == 24)
        d.K = (ct_real)K;
    ctd_iface *it = make(&c, &d);
    double t = 0, dt_prev = 0, tend = (z0 + 3 * g) / v + 4 * 3.141592653589793 * sqrt(1 / K);
    *vmax = v;
    for (int k = 0; k < 200000 && t < tend; k++) {
        ctd_iface_report rep;
        pm_force(it, &p, t, dt_prev, &rep);
        double dt = step_factor > 0 ? step_factor * g / v : 0.9 * fmin(rep.dt, 0.1 * g / v);
        pm_leap(&p, k ? 0.5 * (dt_prev + dt) : 0.5 * dt, dt);
        dt_prev = dt;
        t += dt;
        *vmax = fmax(*vmax, fabs((double)p.vz[4]));
    }
    double z = p.z[4];
    ctd_iface_destroy(it);
    pm_free(&p);
    return z;
}

Test(validation_extreme, tunnelling_thin_shell)
{
    /* TYPE24 K = 4e4 stores K g^2/2 = 2 J in the band: a 1 m/s node (0.5 J)
     * stops at g/2. TYPE7 (K0 = 1e4) stores up to K0 g^2 (r - 1 - ln r)
     * = 5.9 J before its deactivation point. */
    const double K24 = 4e4, K7 = 1e4, v = 1;
    const double factors[] = {0.5, 0, 0.9, 1.5, 2.5, 4.0, 8.0}; /* 0: the driver's step */
    const int nf = (int)(sizeof factors / sizeof factors[0]);
    FILE *f = ctv_csv("extreme_tunnelling",
                      "step_over_g_per_v,z_end_type24_over_g,z_end_type7_over_g,"
                      "vmax_type24_over_v,vmax_type7_over_v");
    int first_tunnel24 = -1, first_tunnel7 = -1;
    for (int i = 0; i < nf; i++) {
        double vm24, vm7;
        double z24 = tunnel_run(24, K24, v, factors[i], &vm24);
        double z7 = tunnel_run(7, K7, v, factors[i], &vm7);
        cr_assert(isfinite(z24) && isfinite(z7));
        if (factors[i] == 0) {
            /* The driver's step: both bounce back at the impact speed. */
            cr_assert(z24 > 0.01 && z7 > 0.01, "driver's step: z %g %g", z24, z7);
            cr_assert(vm24 <= v * 1.01 && vm7 <= v * 1.01, "speed grew: %g %g", vm24, vm7);
        }
        if (z24 < 0 && first_tunnel24 < 0)
            first_tunnel24 = i;
        if (z7 < 0 && first_tunnel7 < 0)
            first_tunnel7 = i;
        double x = factors[i] > 0 ? factors[i] : 0.9 * 0.9;
        ctv_row(f, 5, x, z24 / 0.01, z7 / 0.01, vm24 / v, vm7 / v);
    }
    if (f)
        fclose(f);
    /* Ignoring the limit: stepping 4 g / v and 8 g / v both go through. */
    cr_assert(first_tunnel24 >= 0 && factors[first_tunnel24] <= 4.0,
              "TYPE24 never tunnelled with large steps");
    cr_assert(first_tunnel7 >= 0 && factors[first_tunnel7] <= 4.0,
              "TYPE7 never tunnelled with large steps");
    /* Steps within the tunnelling limit never tunnel. */
    cr_assert(factors[first_tunnel24] > 0.9 && factors[first_tunnel7] > 0.9);
    /* The linear law's own limit: a node carrying more than K g^2/2 is
     * pushed through the band even with the driver's step (v = 3: 4.5 J
     * against 2 J), while TYPE7's growing stiffness still stops it. */
    double vm24, vm7;
    double z24 = tunnel_run(24, K24, 3, 0, &vm24), z7 = tunnel_run(7, K7, 3, 0, &vm7);
    cr_assert(z24 < 0, "linear penalty at 4.5 J against 2 J: z_end %g", z24);
    cr_assert(z7 > 0, "TYPE7 at 4.5 J: z_end %g", z7);
    ctv_plot("extreme_tunnelling",
             "Node at 1 m/s on a shell of thickness g: final height against the step",
             "step x v / g (0.81: the driver's step)", "final z / g (below 0: went through)",
             "1,2,linespoints,TYPE24 linear K = 4e4;1,3,linespoints,TYPE7 K0 = 1e4", "");
    const char *note = "one node m=1 at 1 m/s on a fixed two-sided quad, g = 0.01, VisS 0";
    ctv_result("b. tunnelling", "smallest step (x g/v) that tunnels, TYPE24",
               factors[first_tunnel24], 0, 0, note);
    ctv_result("b. tunnelling", "smallest step (x g/v) that tunnels, TYPE7",
               factors[first_tunnel7], 0, 0, note);
    ctv_result("b. tunnelling", "driver's step: final z / g, TYPE24 (> 0: bounced)",
               tunnel_run(24, K24, v, 0, &vm24) / 0.01, 0, 0, note);
    ctv_result("b. tunnelling", "linear law at 3 m/s (4.5 J > K g^2/2): final z / g",
               z24 / 0.01, 0, 0, "the step limit cannot help: the band is too soft");
}

/* ---- f. Gap zero ------------------------------------------------------------------ */

/*
 * One-sided contact with gap 0 (TYPE24 and TYPE5 on an oriented face):
 * the node at height z over the face has penetration max(0, -z) and force
 * K max(0, -z) along +z, at z = +-1e-3 ... +-1e-300 and exactly 0, inside
 * the face, on its edge and on its corner; no step limit divides by the
 * gap (the tunnelling limit is off); a two-sided surface or a TYPE7 sheet
 * without a gap is refused with CT_ERR_ARG, not a crash.
 */
Test(validation_extreme, gap_zero)
{
    const double K = 1000;
    const double zs[] = {1e-3, 1e-9, 1e-300, 0.0, -0.0, -1e-300, -1e-12, -1e-9, -1e-6, -1e-3};
    const double where[3][2] = {{0.3, 0.2}, {1.0, 0.4}, {1.0, 1.0}}; /* inside, edge, corner */
    const int types[2] = {24, 5};
    double worst = 0;
    int checked = 0;
    for (int ty = 0; ty < 2; ty++)
        for (int w = 0; w < 3; w++)
            for (size_t iz = 0; iz < sizeof zs / sizeof zs[0]; iz++) {
                pm p;
                plate(&p);
                pm_set(&p, 4, where[w][0], where[w][1], zs[iz]);
                p.vz[4] = -1;
                ctd_iface_cfg c = ctd_iface_default_cfg(types[ty]);
                c.gap = 0;
                c.two_sided = 0;
                c.VisS = 0;
                c.algo = CT_SEARCH_DIRECT;
                ctd_iface_data d = plate_data();
                d.K = (ct_real)K;
                ctd_iface *it = make(&c, &d);
                ctd_iface_report rep;
                pm_force(it, &p, 0, 1e-3, &rep);
                double zr = (double)p.z[4]; /* as stored (1e-300 is 0 in single) */
                double pen = zr < 0 ? -zr : 0;
                double kk = types[ty] == 5 ? K * CT_STIFF_SCALE_DEFAULT : K, Kp = kk * pen;
                /* Below the narrow phase's on-surface tolerance (1e-14, single
                 * 1e-6, times the segment size) a node counts as on the face. */
                const double on = CTT_TOL(1e-14, 1e-6) * 2 * sqrt(2.0);
                if (pen <= on && p.pen[4] == 0)
                    pen = 0;
                Kp = kk * pen;
                double tolp = CTT_TOL(1e-12, 1e-6) * (pen > 0 ? pen : 1e-300);
                cr_assert(fabs((double)p.pen[4] - pen) <= tolp,
                          "type %d at (%g, %g, %g): penetration %g, expected %g", types[ty],
                          where[w][0], where[w][1], zs[iz], (double)p.pen[4], pen);
                cr_assert(fabs((double)p.fz[4] - Kp) <= CTT_TOL(1e-12, 1e-6) * (Kp > 0 ? Kp : 1e-300),
                          "type %d at z = %g: force %g, expected %g", types[ty], zs[iz],
                          (double)p.fz[4], Kp);
                cr_assert(p.fx[4] == 0 && p.fy[4] == 0);
                cr_assert(rep.dt_tunnel == CT_DT_NONE, "a gap-0 tunnelling limit: %g",
                          (double)rep.dt_tunnel);
                cr_assert(rep.dt > 0);
                if (pen > 1e-12)
                    worst = fmax(worst, fabs((double)p.pen[4] - pen) / pen);
                checked++;
                ctd_iface_destroy(it);
                pm_free(&p);
            }
    cr_assert_eq(checked, 60);
    /* Refused, not crashed: two-sided with gap 0, TYPE7 without thickness. */
    ctd_iface_data d = plate_data();
    d.K = (ct_real)K;
    ctd_iface_cfg c = ctd_iface_default_cfg(24);
    c.gap = 0;
    c.two_sided = 1;
    ctd_iface *it = NULL;
    cr_assert_eq(ctd_iface_init(&it, &c, &d, NULL), CT_ERR_ARG);
    cr_assert(it == NULL);
    c = ctd_iface_default_cfg(7);
    c.gap = 0;
    cr_assert_eq(ctd_iface_init(&it, &c, &d, NULL), CT_ERR_ARG);
    ct_real zero_gap[5] = {0, 0, 0, 0, 0};
    d.gap_node = zero_gap;
    cr_assert_eq(ctd_iface_init(&it, &c, &d, NULL), CT_ERR_ARG);
    ctv_result("f. gap zero", "penetration vs -signed distance, worst rel. error", worst, 0,
               CTT_TOL(1e-12, 1e-6),
               "TYPE24 and TYPE5 one-sided, gap 0, z = +-1e-3..+-1e-300 and 0, inside / edge "
               "/ corner; two-sided gap 0 and TYPE7 without thickness refused (CT_ERR_ARG)");
}
