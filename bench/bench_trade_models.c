/*
 * bench_trade_models.c -- the knobs of the speed/accuracy trade measured on
 * 1-D models (see bench_trade.c): the contact stiffness scale (an elastic bar
 * pressed on a penalty wall) and the time-step safety factor (a mass and the
 * bar bouncing on the wall).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_trade_internal.h"

/* ---- Knob: contact stiffness scale (1-D bar on a penalty wall) ------------ */

/*
 * An elastic bar of nel elements (E = rho = A = h = 1, so the wave speed
 * c = 1 and the time unit is h / c), node 0 on a penalty wall at x = 0 (the
 * linear law of ct_normal_force, K = Stfac E A / h, no contact damping),
 * the top node pushed down by sigma A. Lumped masses (rho A h, halved at
 * the ends), central difference at 0.9 x the stable step of ct_dt_nodal
 * (element stiffness: 2 E A / h inside, E A / h at the ends; K added at node
 * 0), mass-proportional damping c = 2 omega_1 (omega_1 = pi c / (2 L), the
 * first mode of the bar on a rigid wall), from rest at zero strain until
 * every speed is below 1e-9 sigma / (rho c). Returns CT_OK and the
 * penetration at rest, the stable step and the step count.
 */
static int bar_rest(double stfac, int nel, double sigma, double *pen, double *dtst,
                    int64_t *steps)
{
    int nn = nel + 1;
    ct_real m[64], ke[64], kc[64], u[64], v[64], f[64];
    if (nn > 64)
        return CT_ERR_ARG;
    for (int i = 0; i < nn; i++) {
        int ends = i == 0 || i == nel;
        m[i] = (ct_real)(ends ? 0.5 : 1.0);
        ke[i] = (ct_real)(ends ? 1.0 : 2.0);
        kc[i] = 0;
        u[i] = v[i] = f[i] = 0;
    }
    kc[0] = (ct_real)stfac;
    ct_real dtmin;
    ct_idx imin;
    int rc = ct_dt_nodal(nn, NULL, m, ke, kc, NULL, &dtmin, &imin);
    if (rc != CT_OK)
        return rc;
    *dtst = dtmin;
    double dt = 0.9 * dtmin, damp = 2.0 * TR_PI / (2.0 * nel);
    int64_t k = 0, kmax = 10000000;
    ct_real one = 1, zero = 0, Kc = (ct_real)stfac;
    for (; k < kmax; k++) {
        for (int i = 0; i < nn; i++)
            f[i] = 0;
        for (int e = 0; e < nel; e++) {
            ct_real nf = u[e + 1] - u[e]; /* E A strain */
            f[e] += nf;
            f[e + 1] -= nf;
        }
        f[nel] -= (ct_real)sigma;
        ct_real p = -u[0], vn = v[0], fx, fy, fz, fn;
        rc = ct_normal_force(1, &p, &one, &zero, &zero, &vn, &Kc, 0, &m[0], NULL, 0,
                             (ct_real)dt, &fx, &fy, &fz, &fn, NULL, NULL);
        if (rc != CT_OK)
            return rc;
        f[0] += fx;
        double vmax = 0;
        for (int i = 0; i < nn; i++) {
            v[i] = (ct_real)((double)v[i] + dt * ((double)f[i] / (double)m[i] - damp * v[i]));
            u[i] = (ct_real)((double)u[i] + dt * (double)v[i]);
            vmax = fabs((double)v[i]) > vmax ? fabs((double)v[i]) : vmax;
        }
        if (k > 100 && vmax < 1e-9 * sigma)
            break;
    }
    *pen = -(double)u[0];
    *steps = k;
    return k < kmax ? CT_OK : CT_ERR_NOCONV;
}

void ctbt_bm_stiff(gb_state *st, const tdesc *d)
{
    double stfac = ctbt_stfacs[d->sub], sigma = 1e-3, pen = 0, dtst = 0;
    int64_t steps = 0;
    int rc = CT_OK;
    while (rc == CT_OK && gb_keep_running(st))
        rc = bar_rest(stfac, 10, sigma, &pen, &dtst, &steps);
    char name[32];
    snprintf(name, sizeof name, "%g", stfac);
    if (rc != CT_OK) {
        ctbt_set_skip(st, name, rc);
        return;
    }
    double u = sigma; /* sigma h / E */
    gb_set_counter(st, "cost", 1.0 / dtst, GB_PLAIN);
    gb_set_counter(st, "accuracy", pen / u, GB_PLAIN);
    gb_set_counter(st, "x_analytic", 1.0 / stfac, GB_PLAIN);
    gb_set_counter(st, "x_dt_stable", dtst, GB_PLAIN);
    gb_set_counter(st, "x_steps_to_rest", (double)steps, GB_PLAIN);
    ctbt_label(st, "stiffness", name, "steps per unit time h/c (1 / dt_stable, ct_dt_nodal)",
               "penetration at rest / element deformation sigma h / E (x_analytic: 1/Stfac)",
               "elastic bar, 10 elements, on a linear penalty wall K = Stfac E A / h, sigma = "
               "1e-3 E, central difference at 0.9 dt_stable, damped to rest");
}

/* ---- Knob: time-step safety factor ---------------------------------------- */

/*
 * Scene "mass": a mass m = 1 moving at v = -1 towards a linear penalty wall
 * K = 1 at x = 0 (ct_normal_force, no damping), central difference with
 * dt = factor x 2 sqrt(m / K) (the stability limit of the central
 * difference for a mass on a spring, omega dt <= 2). The mass starts at
 * x = (1 + phase) |v| dt, phase = j / SAFETY_PHASES, so the contact starts
 * at every point of a step. The restitution e = v_out / |v_in| after
 * release; the exact answer is e = 1, and e^2 - 1 is the relative energy
 * error. (At factor 0.5, omega dt = 1: the discrete half period is exactly
 * 3 steps, cos(Omega dt) = 1 - (omega dt)^2 / 2 = 1/2, and e = 1 for every
 * phase: a coincidence of this scene.)
 */
static int bounce_mass(double factor, double phase, double *err)
{
    ct_real one = 1, zero = 0, K = 1, ms = 1;
    double dt = factor * 2.0, x = (1.0 + phase) * dt, v = -1.0;
    for (int k = 0; k < 100000; k++) {
        ct_real p = (ct_real)(-x), vn = (ct_real)v, fx, fy, fz, fn;
        int rc = ct_normal_force(1, &p, &one, &zero, &zero, &vn, &K, 0, &ms, NULL, 0,
                                 (ct_real)dt, &fx, &fy, &fz, &fn, NULL, NULL);
        if (rc != CT_OK)
            return rc;
        v += dt * (double)fx;
        x += dt * v;
        if (x > 0 && v > 0 && k > 0) {
            *err = v * v - 1.0;
            return CT_OK;
        }
    }
    return CT_ERR_NOCONV;
}

/*
 * Scene "bar": the elastic bar of bar_rest (10 elements, E = rho = A = h =
 * 1), undamped, flying at v0 = -1e-3 c onto the penalty wall K = 10 E A / h,
 * dt = factor x the stable step of ct_dt_nodal (sqrt(2 m / (K_elem +
 * K_contact)), the minimum over nodes), node 0 starting (1 + phase) |v0| dt
 * above the wall. Out of contact the central difference conserves exactly
 * E_n = sum 1/2 m_i v_i(n - 1/2) v_i(n + 1/2) + sum_e 1/2 (E A / h) (u_e+1 -
 * u_e)^2 (positions at n); before contact E = 1/2 M v0^2. The error is
 * E / E0 - 1 at the first step out of contact after t = 200 h / c (about
 * ten contact durations 2 L / c).
 */
static int bounce_bar(double factor, double phase, double *err, double *dtst)
{
    enum { NEL = 10, NN = NEL + 1 };
    ct_real m[NN], ke[NN], kc[NN];
    double u[NN], v[NN], f[NN], vold[NN];
    for (int i = 0; i < NN; i++) {
        int ends = i == 0 || i == NEL;
        m[i] = (ct_real)(ends ? 0.5 : 1.0);
        ke[i] = (ct_real)(ends ? 1.0 : 2.0);
        kc[i] = 0;
    }
    kc[0] = 10;
    ct_real dtmin;
    ct_idx imin;
    int rc = ct_dt_nodal(NN, NULL, m, ke, kc, NULL, &dtmin, &imin);
    if (rc != CT_OK)
        return rc;
    *dtst = dtmin;
    double dt = factor * (double)dtmin, v0 = -1e-3, mtot = 0;
    for (int i = 0; i < NN; i++) {
        u[i] = (1.0 + phase) * (-v0) * dt; /* node 0's height above the wall */
        v[i] = v0;
        mtot += m[i];
    }
    double e0 = 0.5 * mtot * v0 * v0, t = 0;
    ct_real one = 1, zero = 0, Kc = kc[0];
    for (int64_t k = 0; k < 10000000; k++, t += dt) {
        for (int i = 0; i < NN; i++)
            f[i] = 0;
        double se = 0;
        for (int e = 0; e < NEL; e++) {
            double nf = u[e + 1] - u[e];
            f[e] += nf;
            f[e + 1] -= nf;
            se += 0.5 * nf * nf;
        }
        ct_real p = (ct_real)(-u[0]), vn = (ct_real)v[0], fx, fy, fz, fn;
        rc = ct_normal_force(1, &p, &one, &zero, &zero, &vn, &Kc, 0, &m[0], NULL, 0,
                             (ct_real)dt, &fx, &fy, &fz, &fn, NULL, NULL);
        if (rc != CT_OK)
            return rc;
        f[0] += (double)fx;
        double ke2 = 0;
        for (int i = 0; i < NN; i++) {
            vold[i] = v[i];
            v[i] += dt * f[i] / (double)m[i];
            ke2 += 0.5 * (double)m[i] * vold[i] * v[i];
        }
        if (t >= 200.0 && fx == 0) {
            *err = (ke2 + se) / e0 - 1.0;
            return CT_OK;
        }
        for (int i = 0; i < NN; i++)
            u[i] += dt * v[i];
    }
    return CT_ERR_NOCONV;
}

void ctbt_bm_safety(gb_state *st, const tdesc *d)
{
    double factor = ctbt_factors[d->sub], emax = 0, esum = 0, dtst = 2.0;
    int rc = CT_OK;
    while (rc == CT_OK && gb_keep_running(st)) {
        emax = esum = 0;
        for (int j = 0; j < SAFETY_PHASES && rc == CT_OK; j++) {
            double err = 0, ph = (double)j / SAFETY_PHASES;
            rc = d->variant ? bounce_bar(factor, ph, &err, &dtst) : bounce_mass(factor, ph, &err);
            emax = fabs(err) > emax ? fabs(err) : emax;
            esum += err;
        }
    }
    char name[32];
    snprintf(name, sizeof name, "%g@%s", factor, d->variant ? "bar" : "mass");
    if (rc != CT_OK) {
        ctbt_set_skip(st, name, rc);
        return;
    }
    gb_set_counter(st, "cost", 1.0 / (factor * dtst), GB_PLAIN);
    gb_set_counter(st, "accuracy", emax, GB_PLAIN);
    gb_set_counter(st, "x_mean_energy_err", esum / SAFETY_PHASES, GB_PLAIN);
    if (d->variant)
        ctbt_label(st, "safety", name,
                   "steps per unit time h/c (dt = factor x ct_dt_nodal's sqrt(2m/(K_elem+K)))",
                   "max |E_after / E_before - 1| over 32 contact phases (x_mean_energy_err: mean)",
                   "undamped elastic bar, 10 elements, v0 = -1e-3 c onto a linear penalty wall "
                   "K = 10 E A / h, central difference, ct_normal_force");
    else
        ctbt_label(st, "safety", name, "steps per unit time sqrt(m/K) (dt = factor x 2 sqrt(m/K))",
                   "max |e^2 - 1| over 32 contact phases, e the restitution (x_mean_energy_err: "
                   "mean)",
                   "mass m on a linear penalty wall K, central difference, ct_normal_force; "
                   "factor 0.5 is exact by coincidence (discrete half period = 3 steps)");
}
