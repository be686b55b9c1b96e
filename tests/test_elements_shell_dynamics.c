/*
 * test_elements_shell_dynamics.c -- the thin elastic shell in explicit
 * dynamics: energy conservation of central differences at 0.9 dt, the
 * stable step against the spectrum, a 180-degree fold and release,
 * bit-identical forces for 1 and 2 threads, and bad arguments.
 */
#include "test_elements_shell.h"

/* ---- Dynamics ---------------------------------------------------------- */

Test(elements_shell, energy_conservation_free_plate)
{
    /* A free 1 x 1 plate (12 x 12 cells; 8 x 8 under sanitizers), t = 0.02,
     * given vz = v0 cos(pi x) cos(pi y) (a bending field), central
     * differences at 0.9 dt_stable for 2000 steps: kinetic + internal
     * energy constant within 1 %, linear momentum to round-off. */
    const int nc = ctt_checking() ? 8 : 12;
    const double E = 1e4, nu = 0.3, rho = 1.0, t = 0.02, v0 = 0.6;
    ct_mesh m;
    ctd_shell s;
    work w;
    plate_at_rest(&m, &s, &w, nc, nc, 1.0 / nc, 1.0 / nc, E, nu, rho, t);
    const ct_idx n = m.nodes.n;
    for (ct_idx i = 0; i < n; i++)
        w.vz[i] = (ct_real)(v0 * cos(M_PI * m.nodes.x[i]) * cos(M_PI * m.nodes.y[i]));
    double p0[3] = {0, 0, 0}, e0 = 0;
    for (ct_idx i = 0; i < n; i++) {
        p0[2] += w.m[i] * w.vz[i];
        e0 += 0.5 * w.m[i] * w.vz[i] * w.vz[i];
    }
    double dt = 0.9 * ctd_shell_dt(&s);
    /* Half-step start: v(1/2) = v(0) + dt/2 a(0). */
    double u = forces(&s, w.x, w.y, w.z, w.fx, w.fy, w.fz);
    e0 += u;
    for (ct_idx i = 0; i < n; i++) {
        w.vx[i] += (ct_real)(0.5 * dt * w.fx[i] / w.m[i]);
        w.vy[i] += (ct_real)(0.5 * dt * w.fy[i] / w.m[i]);
        w.vz[i] += (ct_real)(0.5 * dt * w.fz[i] / w.m[i]);
    }
    double dev = 0, umax = 0, pscale = 0;
    for (ct_idx i = 0; i < n; i++)
        pscale += w.m[i] * v0;
    for (int st = 1; st <= 2000; st++) {
        for (ct_idx i = 0; i < n; i++) {
            w.x[i] += (ct_real)(dt * w.vx[i]);
            w.y[i] += (ct_real)(dt * w.vy[i]);
            w.z[i] += (ct_real)(dt * w.vz[i]);
        }
        u = forces(&s, w.x, w.y, w.z, w.fx, w.fy, w.fz);
        double ke = 0;
        for (ct_idx i = 0; i < n; i++) {
            double ax = dt * w.fx[i] / w.m[i], ay = dt * w.fy[i] / w.m[i],
                   az = dt * w.fz[i] / w.m[i];
            /* v(n) = v(n - 1/2) + dt/2 a(n); then v(n + 1/2). */
            double vx = w.vx[i] + 0.5 * ax, vy = w.vy[i] + 0.5 * ay, vz = w.vz[i] + 0.5 * az;
            ke += 0.5 * w.m[i] * (vx * vx + vy * vy + vz * vz);
            w.vx[i] += (ct_real)ax;
            w.vy[i] += (ct_real)ay;
            w.vz[i] += (ct_real)az;
        }
        cr_assert(isfinite(ke + u), "step %d: non-finite energy", st);
        dev = fmax(dev, fabs(ke + u - e0));
        umax = fmax(umax, u);
    }
    double p[3] = {0, 0, 0};
    for (ct_idx i = 0; i < n; i++) {
        p[0] += w.m[i] * w.vx[i];
        p[1] += w.m[i] * w.vy[i];
        p[2] += w.m[i] * w.vz[i];
    }
    cr_log_info("free plate %dx%d: dt %.4g, max |E - E0| / E0 = %.3g, max U / E0 = %.3f", nc,
                nc, dt, dev / e0, umax / e0);
    cr_expect_gt(umax, 0.3 * e0, "the plate should bend (max U %g, E0 %g)", umax, e0);
    cr_expect_lt(dev, 0.01 * e0, "energy drift %g of %g", dev, e0);
    for (int k = 0; k < 3; k++)
        cr_expect_lt(fabs(p[k] - p0[k]), CTT_TOL(1e-12, 1e-5) * pscale, "momentum[%d] %g -> %g",
                     k, p0[k], p[k]);
    work_free(&w);
    ctd_shell_destroy(&s);
    ct_mesh_destroy(&m);
}

Test(elements_shell, stable_step_vs_spectrum)
{
    /* dt_stable (block Gershgorin) against 2 / omega_max, omega_max from a
     * power iteration on M^-1/2 K M^-1/2 (K v by central differences of
     * the forces at the reference): never above, and not wastefully below. */
    const double E = 1e4, nu = 0.3, rho = 1.0;
    const double ts[2] = {0.02, 0.6}; /* membrane-bound and bending-bound */
    for (int c = 0; c < 2; c++) {
        ct_mesh m;
        plate(&m, 6, 5, 1.0 / 6, 1.0 / 6);
        ctd_shell s;
        shell_on(&s, &m, E, nu, rho, ts[c]);
        const ct_idx n = m.nodes.n;
        work w;
        work_init(&w, n);
        ctd_shell_masses(&s, w.m);
        double *v = calloc(3 * (size_t)n, sizeof(double)), *kv = calloc(3 * (size_t)n, sizeof(double));
        cr_assert(v && kv);
        for (ct_idx i = 0; i < 3 * n; i++)
            v[i] = sin(1.3 * i + 0.7) + 0.1 * cos(7.1 * i);
        double lam = 0, eps = CTT_TOL(1e-7, 1e-3);
        for (int it = 0; it < 400; it++) {
            double nv = 0;
            for (ct_idx i = 0; i < 3 * n; i++)
                nv += v[i] * v[i];
            nv = sqrt(nv);
            for (ct_idx i = 0; i < 3 * n; i++)
                v[i] /= nv;
            for (int sg = 0; sg < 2; sg++) {
                double d = sg ? -eps : eps;
                for (ct_idx i = 0; i < n; i++) {
                    double is = 1 / sqrt(w.m[i]);
                    w.x[i] = (ct_real)(m.nodes.x[i] + d * is * v[3 * i]);
                    w.y[i] = (ct_real)(m.nodes.y[i] + d * is * v[3 * i + 1]);
                    w.z[i] = (ct_real)(m.nodes.z[i] + d * is * v[3 * i + 2]);
                }
                forces(&s, w.x, w.y, w.z, w.fx, w.fy, w.fz);
                for (ct_idx i = 0; i < n; i++) {
                    double is = 1 / sqrt(w.m[i]);
                    double f[3] = {w.fx[i], w.fy[i], w.fz[i]};
                    for (int k = 0; k < 3; k++)
                        kv[3 * i + k] = (sg ? kv[3 * i + k] : 0) + (sg ? 1 : -1) * f[k] * is / (2 * eps);
                }
            }
            lam = 0;
            for (ct_idx i = 0; i < 3 * n; i++)
                lam += v[i] * kv[i];
            memcpy(v, kv, sizeof(double) * 3 * (size_t)n);
        }
        double dt_true = 2 / sqrt(lam), dt = ctd_shell_dt(&s);
        cr_log_info("t = %g: dt_stable %.5g, 2/omega_max %.5g, ratio %.3f", ts[c], dt, dt_true,
                    dt / dt_true);
        cr_expect_leq(dt, dt_true * (1 + CTT_TOL(1e-6, 1e-2)), "dt %g above 2/omega %g", dt, dt_true);
        cr_expect_gt(dt, 0.5 * dt_true, "dt %g too conservative (2/omega %g)", dt, dt_true);
        free(v);
        free(kv);
        work_free(&w);
        ctd_shell_destroy(&s);
        ct_mesh_destroy(&m);
    }
}

Test(elements_shell, fold_180_and_release)
{
    /* Strip 1 x 1/12 (24 x 2 cells), t = 0.05, clamped at x = 0 (node
     * columns 0 and 1); the last two node columns are driven rigidly along
     * the pure-bending arc of angle phi(t) = pi s(t / T) (smoothstep, T =
     * two periods of the first mode), folding the strip into a half circle
     * over itself; then released for one period. No NaN; after release the
     * total energy stays within 2 % of its value at release (nothing does
     * work then); at the fold the internal energy is within a factor 2 of
     * the pure-bending D pi^2 / (2 L^2) L w. */
    const int nx = ctt_checking() ? 12 : 24, ny = 2;
    const double L = 1.0, wdt = L / 12, t = 0.05, E = 1e4, nu = 0.3, rho = 1.0;
    const double D = E * t * t * t / (12 * (1 - nu * nu));
    ct_mesh m;
    ctd_shell s;
    work w;
    plate_at_rest(&m, &s, &w, nx, ny, L / nx, wdt / ny, E, nu, rho, t);
    const ct_idx n = m.nodes.n;
    double dt = 0.9 * ctd_shell_dt(&s);
    double w1 = 1.875104 * 1.875104 * sqrt(D / (rho * t)) / (L * L), T1 = 2 * M_PI / w1;
    long nramp = (long)(2 * T1 / dt), nrel = (long)(T1 / dt);
    double erel = 0, dev = 0, ufold = 0;
    for (long st = 1; st <= nramp + nrel; st++) {
        double u = forces(&s, w.x, w.y, w.z, w.fx, w.fy, w.fz);
        double ke = 0;
        double q = st < nramp ? (double)st / nramp : 1, phi = M_PI * q * q * (3 - 2 * q);
        double kap = phi / L;
        for (ct_idx i = 0; i < n; i++) {
            int col = (int)(i % (nx + 1));
            if (col <= 1)
                continue;
            if (st <= nramp && col >= nx - 1) {
                /* Driven: the arc position at arc length x. */
                double a = m.nodes.x[i];
                double px = kap > 1e-12 ? sin(kap * a) / kap : a;
                double pz = kap > 1e-12 ? (1 - cos(kap * a)) / kap : 0;
                w.vx[i] = (ct_real)((px - w.x[i]) / dt);
                w.vz[i] = (ct_real)((pz - w.z[i]) / dt);
                w.vy[i] = 0;
                w.x[i] = (ct_real)px;
                w.z[i] = (ct_real)pz;
                continue;
            }
            double vx = w.vx[i] + dt * w.fx[i] / w.m[i], vy = w.vy[i] + dt * w.fy[i] / w.m[i],
                   vz = w.vz[i] + dt * w.fz[i] / w.m[i];
            /* Kinetic energy at the full step (mean of the half steps). */
            double ax = 0.5 * (vx + w.vx[i]), ay = 0.5 * (vy + w.vy[i]), az = 0.5 * (vz + w.vz[i]);
            ke += 0.5 * w.m[i] * (ax * ax + ay * ay + az * az);
            w.vx[i] = (ct_real)vx;
            w.vy[i] = (ct_real)vy;
            w.vz[i] = (ct_real)vz;
            w.x[i] += (ct_real)(dt * vx);
            w.y[i] += (ct_real)(dt * vy);
            w.z[i] += (ct_real)(dt * vz);
        }
        cr_assert(isfinite(u + ke), "step %ld: non-finite energy", st);
        if (st == nramp)
            ufold = u;
        if (st == nramp + 1)
            erel = u + ke;
        if (st > nramp + 1)
            dev = fmax(dev, fabs(u + ke - erel));
    }
    double ub = D * M_PI * M_PI / (2 * L * L) * L * wdt;
    cr_log_info("fold: %ld + %ld steps, U at fold / pure bending %.3f, drift after release "
                "%.3g", nramp, nrel, ufold / ub, dev / erel);
    cr_expect_gt(ufold, 0.5 * ub, "fold energy %g, pure bending %g", ufold, ub);
    cr_expect_lt(ufold, 2.0 * ub, "fold energy %g, pure bending %g", ufold, ub);
    cr_expect_lt(dev, 0.02 * erel, "energy after release drifts by %g of %g", dev, erel);
    for (ct_idx i = 0; i < n; i++)
        cr_expect(fabs(w.x[i]) < 2 * L && fabs(w.z[i]) < 2 * L, "node %d escaped", (int)i);
    work_free(&w);
    ctd_shell_destroy(&s);
    ct_mesh_destroy(&m);
}

Test(elements_shell, threads_bit_identical)
{
    const int nc = ctt_checking() ? 12 : 40;
    ct_mesh m;
    curved(&m, nc, nc, 1.0 / nc, 0.8);
    ctd_shell s;
    shell_on(&s, &m, 1e4, 0.3, 1.0, 0.02);
    const ct_idx n = m.nodes.n;
    work a, b;
    work_init(&a, n);
    work_init(&b, n);
    for (ct_idx i = 0; i < n; i++) {
        double p = m.nodes.x[i], q = m.nodes.y[i];
        a.x[i] = (ct_real)(p + 0.01 * sin(5 * q));
        a.y[i] = (ct_real)(q + 0.01 * cos(3 * p));
        a.z[i] = (ct_real)(m.nodes.z[i] + 0.05 * sin(7 * p + 4 * q));
    }
    ctt_threads(1);
    double e1 = forces(&s, a.x, a.y, a.z, a.fx, a.fy, a.fz);
    ctt_threads(2);
    double e2 = forces(&s, a.x, a.y, a.z, b.fx, b.fy, b.fz);
    size_t bytes = sizeof(ct_real) * (size_t)n;
    cr_expect_eq(memcmp(a.fx, b.fx, bytes), 0);
    cr_expect_eq(memcmp(a.fy, b.fy, bytes), 0);
    cr_expect_eq(memcmp(a.fz, b.fz, bytes), 0);
    cr_expect_eq(memcmp(&e1, &e2, sizeof e1), 0);
    double fmx = 0;
    for (ct_idx i = 0; i < n; i++)
        fmx = fmax(fmx, fabs(a.fz[i]));
    cr_expect_gt(fmx, 0);
    work_free(&a);
    work_free(&b);
    ctd_shell_destroy(&s);
    ct_mesh_destroy(&m);
}

Test(elements_shell, errors)
{
    ct_real x[4] = {0, 1, 1, 0}, y[4] = {0, 0, 1, 1}, z[4] = {0, 0, 0, 0};
    ct_idx a[1] = {0}, b[1] = {1}, c[1] = {2}, d[1] = {3}, big[1] = {4};
    ctd_shell s;
    /* One quad: four half-weight triangles, no interior edge. */
    cr_expect_eq(ctd_shell_init(&s, 4, x, y, z, 1, a, b, c, d, NULL, 1, 0.3, 1, 0.1), CT_OK);
    cr_expect_eq(s.ntri, 4);
    cr_expect_eq(s.nhinge, 0);
    ctd_shell_destroy(&s);
    cr_expect_eq(ctd_shell_init(&s, 4, x, y, z, 1, a, b, c, big, NULL, 1, 0.3, 1, 0.1),
                 CT_ERR_RANGE);
    cr_expect_eq(ctd_shell_init(&s, 4, x, y, z, 1, a, b, b, d, NULL, 1, 0.3, 1, 0.1),
                 CT_ERR_DUPNODE);
    cr_expect_eq(ctd_shell_init(&s, 4, x, y, z, 1, a, b, c, d, NULL, 1, 0.5, 1, 0.1),
                 CT_ERR_ARG);
    cr_expect_eq(ctd_shell_init(&s, 4, x, y, z, 1, a, b, c, d, NULL, 1, 0.3, 1, 0.0),
                 CT_ERR_ARG);
    ct_real th[1] = {-1};
    cr_expect_eq(ctd_shell_init(&s, 4, x, y, z, 1, a, b, c, d, th, 1, 0.3, 1, 0.1),
                 CT_ERR_DEGENERATE);
    ct_real xc[4] = {0, 1, 2, 0}, yc[4] = {0, 1, 2, 1};
    cr_expect_eq(ctd_shell_init(&s, 4, xc, yc, z, 1, a, b, c, c, NULL, 1, 0.3, 1, 0.1),
                 CT_ERR_DEGENERATE);
    /* Two triangles (n4 NULL): one hinge. A triangle collapsed during a run
     * is reported, and the forces are left alone. */
    ct_idx t1[2] = {0, 0}, t2[2] = {1, 2}, t3[2] = {2, 3};
    cr_assert_eq(ctd_shell_init(&s, 4, x, y, z, 2, t1, t2, t3, NULL, NULL, 1, 0.3, 1, 0.1),
                 CT_OK);
    cr_expect_eq(s.ntri, 2);
    cr_expect_eq(s.nhinge, 1);
    ct_real f[3][4] = {{0}};
    ct_real xx[4] = {0, 1, 2, 0}, yy[4] = {0, 1, 2, 1};
    cr_expect_eq(ctd_shell_forces(&s, xx, yy, z, f[0], f[1], f[2], NULL), CT_ERR_NONFINITE);
    for (int i = 0; i < 4; i++)
        cr_expect_eq(f[0][i] + f[1][i] + f[2][i], 0);
    ctd_shell_destroy(&s);
}
