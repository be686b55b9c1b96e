/*
 * test_math_vec.c -- the kernels' vector exp (kernels/math_vec.h) against
 * the long double expl: within one unit in the last place of the result
 * everywhere (faithful rounding: the result is one of the two
 * floating-point numbers around the true value), subnormal results
 * included; the edges (overflow, underflow, infinities, NaN, -0); the
 * friction laws that use it, whose array form (a vector loop) must give
 * the same bits as the one-pair form for every pair.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>

#include "../kernels/math_vec.h"
#include "test_util.h"

#ifdef CT_SINGLE
#define EXP_LO (-104.0)
#define EXP_HI 89.0
#define EXP_TINY 0x1p-149L /* the smallest subnormal */
#define EXP_MIN FLT_MIN
#else
#define EXP_LO (-746.0)
#define EXP_HI 710.0
#define EXP_TINY 0x1p-1074L
#define EXP_MIN DBL_MIN
#endif

/* |y - ref| in units of the last place of ct_real at ref (the spacing
 * above |ref|, the smallest subnormal below the normal range). ref is
 * finite and its ct_real rounding too. */
static long double ulps(ct_real y, long double ref)
{
    ct_real r = (ct_real)ref;
    long double u = fabsl(ref) < (long double)EXP_MIN
                        ? EXP_TINY
                        : fabsl((long double)nextafter((double)r, INFINITY) - (long double)r);
#ifdef CT_SINGLE
    if (fabsl(ref) >= (long double)EXP_MIN)
        u = fabsl((long double)nextafterf(r, INFINITY) - (long double)r);
#endif
    return fabsl((long double)y - ref) / u;
}

static uint64_t xorshift(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

Test(math_vec, exp_within_one_ulp_of_expl)
{
    /* Half the arguments over the whole range whose result is neither 0
     * nor +inf (subnormal results included), half in [-1, 1] where most
     * of a friction law's arguments fall; plus the integers and the
     * multiples of ln 2 / 2, where the reduction changes n. */
    uint64_t s = 0x9e3779b97f4a7c15u;
    long double worst = 0;
    double wx = 0;
    long checked = 0;
    for (long i = 0; i < 2000000; i++) {
        double f = (double)(xorshift(&s) >> 11) * 0x1p-53;
        ct_real x = (ct_real)(i % 2 ? EXP_LO + (EXP_HI - EXP_LO) * f : 2 * f - 1);
        if (i % 1000 == 0)
            x = (ct_real)((double)(i / 1000 % 1400) - 700) * (ct_real)0.34657359027997264;
        long double ref = expl((long double)x);
        if (!isfinite((double)(ct_real)ref) || (ct_real)ref == 0)
            continue; /* the edges: below */
        long double e = ulps(cti_exp(x), ref);
        checked++;
        if (e > worst) {
            worst = e;
            wx = (double)x;
        }
    }
    cr_log_info("cti_exp: worst %.3Lf ulp at x = %.17g over %ld arguments", worst, wx, checked);
    cr_assert_gt(checked, 1900000);
    cr_assert_lt(worst, 1.0L, "%.3Lf ulp at x = %.17g", worst, wx);
}

Test(math_vec, exp_edges)
{
    cr_assert_eq(cti_exp(0), 1);
    cr_assert_eq(cti_exp(-(ct_real)0), 1);
    cr_assert_eq(cti_exp((ct_real)INFINITY), (ct_real)INFINITY);
    cr_assert_eq(cti_exp(-(ct_real)INFINITY), 0);
    cr_assert(isnan(cti_exp((ct_real)NAN)));
    cr_assert(isnan(cti_exp(-(ct_real)NAN)));
    cr_assert_eq(cti_exp((ct_real)1e30), (ct_real)INFINITY);
    cr_assert_eq(cti_exp((ct_real)-1e30), 0);
#ifdef CT_SINGLE
    /* expf: the largest finite result at 88.72 (FLT_MAX's log is 88.7228),
     * +inf at 88.73; the smallest subnormal 2^-149 at -103.9, 0 at -104
     * (2^-150's log is -103.972). */
    cr_assert(isfinite(cti_exp(88.72f)));
    cr_assert_eq(cti_exp(88.73f), INFINITY);
    cr_assert_eq(cti_exp(-103.9f), 0x1p-149f);
    cr_assert_eq(cti_exp(-104.0f), 0);
#else
    /* exp: finite at 709.78 (DBL_MAX's log is 709.7827), +inf at 709.79;
     * the smallest subnormal at -745.1, 0 at -745.2 (2^-1075's log is
     * -745.1332). */
    cr_assert(isfinite(cti_exp(709.78)));
    cr_assert_eq(cti_exp(709.79), INFINITY);
    cr_assert_eq(cti_exp(-745.1), 0x1p-1074);
    cr_assert_eq(cti_exp(-745.2), 0);
#endif
    /* Exact where the true value is a power of two: exp(n ln2) is not one
     * (ln 2 is not a ct_real), but exp(0) is, and the results of exp of
     * opposite arguments multiply to 1 within two ulps. */
    for (int i = 1; i < 200; i++) {
        ct_real x = (ct_real)i * (ct_real)0.37;
        ct_real q = cti_exp(x) * cti_exp(-x);
        cr_assert_leq(CTI_FABS(q - 1), 3 * CTI_EPS, "x = %g: %g", (double)x, (double)q);
    }
}

Test(math_vec, friction_laws_array_equals_one_pair)
{
    /* 1037 pairs: whole vector iterations, a remainder and blocks of the
     * array form; speeds and pressures over decades, both signs of the
     * exponents' coefficients. The array form runs cti_exp in vector
     * lanes, the one-pair form as a scalar: the same bits. */
    enum { N = 1037 };
    static ct_real p[N], v[N], mu[N];
    uint64_t s = 12345;
    for (int i = 0; i < N; i++) {
        p[i] = (ct_real)ldexp((double)(xorshift(&s) % 1000) / 1000.0, (int)(xorshift(&s) % 40) - 10);
        v[i] = (ct_real)ldexp((double)(xorshift(&s) % 1000) / 1000.0, (int)(xorshift(&s) % 20) - 10);
        if (i % 7 == 0)
            v[i] = -v[i];
    }
    const ct_real cd[7] = {0, 1e-4, -0.5, 0.01, -3, 0.2, 0.05};
    const ct_real ce[7] = {0.5, 0.2, 2.5, 0, 0, 0, 0};
    for (int law = CT_FRIC_DARMSTAD; law <= CT_FRIC_EXPDECAY; law++) {
        if (law == CT_FRIC_RENARD)
            continue;
        const ct_real *c = law == CT_FRIC_DARMSTAD ? cd : ce;
        for (int t = 1; t <= 2; t++) {
            omp_set_num_threads(t);
            cr_assert_eq(ct_friction_mu(N, law, c, p, v, mu), CT_OK);
            for (int i = 0; i < N; i++) {
                cr_assert_eq(mu[i], ct_friction_mu1(law, c, p[i], v[i]), "law %d pair %d", law,
                             i);
                /* And the law against libm's exp in double, within the
                 * roundings of its few operations (the exponents as the
                 * law rounds them: an exponent's rounding error e is a
                 * relative error e of the result). */
                ct_real a = CTI_FABS(v[i]);
                double w;
                if (law == CT_FRIC_DARMSTAD)
                    w = cd[1] * exp((double)(cd[2] * a)) * p[i] * p[i] +
                        cd[3] * exp((double)(cd[4] * a)) * p[i] + cd[5] * exp((double)(cd[6] * a));
                else
                    w = ce[1] + (ce[0] - ce[1]) * exp((double)(-ce[2] * a));
                cr_assert_leq(fabs((double)mu[i] - w), 8 * CTI_EPS * fabs(w) + 1e-300,
                              "law %d pair %d: %.17g against %.17g", law, i, (double)mu[i], w);
            }
        }
    }
}
