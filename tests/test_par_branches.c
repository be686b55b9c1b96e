/*
 * test_par_branches.c -- a kernel's loops run in a thread team above their
 * size threshold and as plain loops below it (CTI_PAR_FOR, ct_internal.h).
 * Each kernel here is called on N pairs (the team, 2 threads) and on the
 * first M of them (no team): the M results must be the same bits. The
 * step scan must also find the same minimum and index over the prefix.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "test_util.h"

#define N 20000 /* above every kernel's team threshold (8192) */
#define M 1500  /* below it */

static ct_real rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (ct_real)((double)(*s >> 11) / 9007199254740992.0);
}

/* Pair data: penetrations around 0 (half in contact), unit normals,
 * velocities, masses, gaps, stiffnesses. */
typedef struct pairs {
    ct_real p[N], g[N], K[N], vn[N], ms[N], mm[N], nx[N], ny[N], nz[N], vx[N], vy[N], vz[N];
    ct_real fn[N];
    ct_idx idx[N];
} pairs;

static pairs *make_pairs(void)
{
    pairs *d = calloc(1, sizeof *d);
    cr_assert_not_null(d);
    uint64_t s = 12345;
    for (int i = 0; i < N; i++) {
        d->g[i] = (ct_real)0.01 + (ct_real)0.01 * rnd(&s);
        d->p[i] = d->g[i] * (rnd(&s) - (ct_real)0.4);
        d->K[i] = (ct_real)1e6 * ((ct_real)0.5 + rnd(&s));
        d->vn[i] = rnd(&s) - (ct_real)0.5;
        d->ms[i] = (ct_real)0.1 + rnd(&s);
        d->mm[i] = (ct_real)0.1 + rnd(&s);
        ct_real a = (ct_real)6.2831853 * rnd(&s), c = (ct_real)2 * rnd(&s) - 1;
        ct_real r = (ct_real)sqrt(1 - (double)(c * c));
        d->nx[i] = r * (ct_real)cos((double)a);
        d->ny[i] = r * (ct_real)sin((double)a);
        d->nz[i] = c;
        d->vx[i] = rnd(&s) - (ct_real)0.5;
        d->vy[i] = rnd(&s) - (ct_real)0.5;
        d->vz[i] = rnd(&s) - (ct_real)0.5;
        d->fn[i] = (ct_real)10 * rnd(&s);
        d->idx[i] = (ct_idx)((i * 7919) % N);
    }
    return d;
}

static void expect_same(const ct_real *a, const ct_real *b, const char *what)
{
    cr_expect_eq(memcmp(a, b, M * sizeof *a), 0, "%s: the plain loop's results differ", what);
}

Test(par_branches, force_kernels_same_bits_with_and_without_team)
{
    ctt_threads(2);
    pairs *d = make_pairs();
    ct_real *o = calloc(16 * (size_t)N, sizeof *o);
    cr_assert_not_null(o);
    ct_real *fel = o, *kt = o + N, *en = o + 2 * N, *fn = o + 3 * N, *fx = o + 4 * N,
            *fy = o + 5 * N, *fz = o + 6 * N, *dd = o + 7 * N;
    ct_real *fel2 = o + 8 * N, *kt2 = o + 9 * N, *en2 = o + 10 * N, *fn2 = o + 11 * N,
            *fx2 = o + 12 * N, *fy2 = o + 13 * N, *fz2 = o + 14 * N, *dd2 = o + 15 * N;
    int32_t fl[N], fl2[N];
    for (int pass = 0; pass < 2; pass++) {
        const ct_idx n = pass ? M : N;
        ct_real *F = pass ? fel2 : fel, *T = pass ? kt2 : kt, *E = pass ? en2 : en;
        cr_assert_eq(ct_penalty_type7(n, d->p, d->g, d->K, F, T, E, pass ? fl2 : fl), CT_OK);
        cr_assert_eq(ct_normal_finish(n, d->p, F, T, d->vn, d->ms, d->mm, (ct_real)0.1,
                                      (ct_real)1e-6, d->nx, d->ny, d->nz, pass ? fn2 : fn,
                                      pass ? fx2 : fx, pass ? fy2 : fy, pass ? fz2 : fz,
                                      pass ? dd2 : dd),
                     CT_OK);
    }
    expect_same(fel, fel2, "TYPE7 force");
    expect_same(kt, kt2, "TYPE7 tangent");
    expect_same(en, en2, "TYPE7 energy");
    cr_expect_eq(memcmp(fl, fl2, M * sizeof fl[0]), 0, "TYPE7 flags");
    expect_same(fn, fn2, "normal force");
    expect_same(fx, fx2, "force x");
    expect_same(fz, fz2, "force z");
    expect_same(dd, dd2, "damping dissipation");
    /* Friction: a history per call, from the same start. */
    ct_real *h = calloc(8 * (size_t)N, sizeof *h);
    cr_assert_not_null(h);
    for (int i = 0; i < N; i++)
        h[i] = h[4 * N + i] = (ct_real)0.01 * d->vx[i];
    for (int pass = 0; pass < 2; pass++) {
        ct_real *b = h + 4 * pass * N;
        cr_assert_eq(ct_friction_step(pass ? M : N, d->nx, d->ny, d->nz, d->vx, d->vy, d->vz,
                                      d->fn, NULL, (ct_real)0.3, NULL, (ct_real)1e5,
                                      (ct_real)1e-6, (ct_real)0.5, b, b + N, b + 2 * N,
                                      b + 3 * N),
                     CT_OK);
    }
    for (int a = 0; a < 4; a++)
        expect_same(h + a * N, h + 4 * N + a * N, "friction force and dissipation");
    free(h);
    free(o);
    free(d);
}

Test(par_branches, step_scan_same_minimum_with_and_without_team)
{
    ctt_threads(2);
    pairs *d = make_pairs();
    ct_real *dt1 = calloc(N, sizeof *dt1), *dt2 = calloc(N, sizeof *dt2);
    cr_assert(dt1 && dt2);
    ct_real m1, m2;
    ct_idx i1, i2;
    cr_assert_eq(ct_dt_nodal(N, d->idx, d->ms, NULL, d->K, dt1, &m1, &i1), CT_OK);
    cr_assert_eq(ct_dt_nodal(M, d->idx, d->ms, NULL, d->K, dt2, &m2, &i2), CT_OK);
    expect_same(dt1, dt2, "nodal steps");
    /* The prefix's minimum by a plain scan of the team's steps. */
    ct_real best = dt1[0];
    ct_idx bi = 0;
    for (ct_idx k = 1; k < M; k++)
        if (dt1[k] < best) {
            best = dt1[k];
            bi = k;
        }
    cr_expect_eq(m2, best);
    cr_expect_eq(i2, bi);
    free(dt1);
    free(dt2);
    free(d);
}
