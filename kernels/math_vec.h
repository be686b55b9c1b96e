/*
 * math_vec.h -- the exponential as arithmetic a vector loop can hold
 * (internal).
 *
 * libm's exp has no vector form unless the build allows -ffast-math, so a
 * loop that calls it runs one element at a time: the Darmstad and Ifric 4
 * friction laws spent 11.5 and 4.4 ns per pair at 10^6 pairs in it, where
 * the laws without an exponential run as vector loops at 0.1-0.8.
 *
 * cti_exp is the textbook method, with no branch, table or call:
 *  - x = n ln2 + r, n the nearest integer to x / ln2, |r| <= ln2 / 2 (about;
 *    n rounds the rounded quotient). ln 2 is split in two, its high part
 *    with enough trailing zero bits that n ln2_hi is exact for every n
 *    that occurs (Cody and Waite), so r is exact but for n ln2_lo's
 *    rounding;
 *  - exp(r) by its Taylor series in Horner form, to the degree whose first
 *    omitted term is below the precision's rounding at |r| = ln2 / 2:
 *    degree 13 in double (the next term 4e-18), 7 in single (5e-9);
 *  - 2^n from its exponent bits. n is read from the bits of x / ln2 + 1.5
 *    2^52 (2^23 in single), where a unit is the last bit: no conversion
 *    to an integer type, so no conversion that would be undefined for a
 *    NaN. Where 2^n itself is not a normal number (results near the
 *    overflow and in the subnormal range) it is applied as two factors,
 *    2^(n - k) 2^k, so the one rounding is that of the final product.
 * The arguments are clamped first to the interval past whose ends the
 * result is +inf or 0 anyway, a NaN computed as 0 and returned as itself.
 *
 * cti_log1p(y) = log(1 + y), the same way: u = 1 + y = 2^e m with m in
 * [sqrt(2)/2, sqrt(2)) read from u's bits (e made a floating-point number
 * by the bits of 1.5 2^52 + e, again no conversion), f = m - 1 (exact),
 * s = f / (2 + f), log(1 + f) = f - (f^2/2 - s (f^2/2 + R)), R = 2 s^2/3 +
 * 2 s^4/5 + ... (the series of 2 atanh s, whose terms past the first are
 * R; to s^22 in double, s^12 in single, where the next is below the
 * rounding at |s| = 0.1716): f enters exactly and the rest is a small
 * correction. The rounding of u = 1 + y is corrected to first order by
 * (y - (u - 1)) / u. e ln2 is added in two parts as in cti_exp.
 *
 * Every operation is one a vector lane computes with the same rounding as
 * a scalar (CTI_FMA is fused or not in both): a pair's value has the same
 * bits whichever path computes it, so ct_friction_mu and ct_friction_mu1,
 * ct_penalty_type7's energies and ct_type7_energy, agree bit for bit.
 * Accuracy against the long double functions, and the edges (overflow,
 * underflow, subnormal results, infinities, NaN, -1) are measured by
 * tests/test_math_vec.c.
 */
#ifndef CT_MATH_VEC_H
#define CT_MATH_VEC_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "ct_internal.h"

#ifdef CT_SINGLE

static inline float cti_exp(float x)
{
    const float shift = 0x1.8p23f; /* 1.5 2^23: its last bit is a unit */
    float xc = x > 89.0f ? 89.0f : x; /* expf overflows from 88.73 */
    xc = xc < -104.0f ? -104.0f : xc; /* and is 0 below -103.98 */
    xc = x == x ? xc : 0.0f;
    float t = xc * 0x1.715476p+0f + shift;
    float n = t - shift;
    float r = (xc - n * 0x1.62ep-1f) - n * 0x1.0bfbe8p-15f;
    float p = 1.0f / 5040;
    p = CTI_FMA(p, r, 1.0f / 720);
    p = CTI_FMA(p, r, 1.0f / 120);
    p = CTI_FMA(p, r, 1.0f / 24);
    p = CTI_FMA(p, r, 1.0f / 6);
    p = CTI_FMA(p, r, 0.5f);
    p = CTI_FMA(p, r, 1.0f);
    p = CTI_FMA(p, r, 1.0f);
    /* 2^n = 2^n1 2^k, n1 = n - k within the normal exponents. */
    float k = n < -100.0f ? -30.0f : (n > 100.0f ? 30.0f : 0.0f);
    float s2 = n < -100.0f ? 0x1p-30f : (n > 100.0f ? 0x1p30f : 1.0f);
    float t1 = (n - k) + shift, s1;
    uint32_t u;
    memcpy(&u, &t1, sizeof u);
    u = (u - UINT32_C(0x4B400000) + 127u) << 23; /* 0x4B400000: shift's bits */
    memcpy(&s1, &u, sizeof s1);
    float y = (p * s1) * s2;
    return x == x ? y : x;
}

static inline float cti_log1p(float y)
{
    float ys = y > -1.0f ? y : 0.0f; /* y <= -1, NaN, +inf: computed on 0 */
    ys = ys <= FLT_MAX ? ys : 0.0f;
    float u = 1.0f + ys;
    float c = (ys - (u - 1.0f)) / u; /* u's rounding, to first order */
    uint32_t b, mb, eb;
    memcpy(&b, &u, sizeof b);
    mb = (b & UINT32_C(0x007FFFFF)) | UINT32_C(0x3F800000);
    eb = UINT32_C(0x4B400000) + (b >> 23); /* 1.5 2^23 + the biased exponent */
    float m, e;
    memcpy(&m, &mb, sizeof m);
    memcpy(&e, &eb, sizeof e);
    e = (e - 0x1.8p23f) - 127.0f;
    e = m > 0x1.6a09e6p+0f ? e + 1.0f : e; /* m above sqrt(2): m / 2 */
    m = m > 0x1.6a09e6p+0f ? 0.5f * m : m;
    float f = m - 1.0f, s = f / (2.0f + f), z = s * s, hf = 0.5f * f * f;
    float r = 2.0f / 13;
    r = CTI_FMA(r, z, 2.0f / 11);
    r = CTI_FMA(r, z, 2.0f / 9);
    r = CTI_FMA(r, z, 2.0f / 7);
    r = CTI_FMA(r, z, 2.0f / 5);
    r = CTI_FMA(r, z, 2.0f / 3);
    r *= z;
    float lo = CTI_FMA(e, 0x1.0bfbe8p-15f, c);
    float res = CTI_FMA(e, 0x1.62ep-1f, -((hf - CTI_FMA(s, hf + r, lo)) - f));
    res = y > -1.0f ? res : (y == -1.0f ? -INFINITY : NAN);
    res = y == 0.0f ? y : res; /* -0 stays -0 */
    return y <= FLT_MAX ? res : y; /* +inf, and NaN as itself */
}

#else

static inline double cti_exp(double x)
{
    const double shift = 0x1.8p52; /* 1.5 2^52: its last bit is a unit */
    double xc = x > 710.0 ? 710.0 : x; /* exp overflows from 709.79 */
    xc = xc < -746.0 ? -746.0 : xc;    /* and is 0 below -745.14 */
    xc = x == x ? xc : 0.0;
    double t = xc * 0x1.71547652b82fep+0 + shift;
    double n = t - shift;
    double r = (xc - n * 0x1.62e42fee00000p-1) - n * 0x1.a39ef35793c76p-33;
    double p = 1.0 / 6227020800.0; /* 1 / 13! */
    p = CTI_FMA(p, r, 1.0 / 479001600.0);
    p = CTI_FMA(p, r, 1.0 / 39916800.0);
    p = CTI_FMA(p, r, 1.0 / 3628800.0);
    p = CTI_FMA(p, r, 1.0 / 362880.0);
    p = CTI_FMA(p, r, 1.0 / 40320.0);
    p = CTI_FMA(p, r, 1.0 / 5040.0);
    p = CTI_FMA(p, r, 1.0 / 720.0);
    p = CTI_FMA(p, r, 1.0 / 120.0);
    p = CTI_FMA(p, r, 1.0 / 24.0);
    p = CTI_FMA(p, r, 1.0 / 6.0);
    p = CTI_FMA(p, r, 0.5);
    p = CTI_FMA(p, r, 1.0);
    p = CTI_FMA(p, r, 1.0);
    /* 2^n = 2^n1 2^k, n1 = n - k within the normal exponents. */
    double k = n < -1000.0 ? -60.0 : (n > 1000.0 ? 60.0 : 0.0);
    double s2 = n < -1000.0 ? 0x1p-60 : (n > 1000.0 ? 0x1p60 : 1.0);
    double t1 = (n - k) + shift, s1;
    uint64_t u;
    memcpy(&u, &t1, sizeof u);
    u = (u - UINT64_C(0x4338000000000000) + 1023u) << 52; /* shift's bits */
    memcpy(&s1, &u, sizeof s1);
    double y = (p * s1) * s2;
    return x == x ? y : x;
}

static inline double cti_log1p(double y)
{
    double ys = y > -1.0 ? y : 0.0; /* y <= -1, NaN, +inf: computed on 0 */
    ys = ys <= DBL_MAX ? ys : 0.0;
    double u = 1.0 + ys;
    double c = (ys - (u - 1.0)) / u; /* u's rounding, to first order */
    uint64_t b, mb, eb;
    memcpy(&b, &u, sizeof b);
    mb = (b & UINT64_C(0x000FFFFFFFFFFFFF)) | UINT64_C(0x3FF0000000000000);
    eb = UINT64_C(0x4338000000000000) + (b >> 52); /* 1.5 2^52 + the biased exponent */
    double m, e;
    memcpy(&m, &mb, sizeof m);
    memcpy(&e, &eb, sizeof e);
    e = (e - 0x1.8p52) - 1023.0;
    e = m > 0x1.6a09e667f3bcdp+0 ? e + 1.0 : e; /* m above sqrt(2): m / 2 */
    m = m > 0x1.6a09e667f3bcdp+0 ? 0.5 * m : m;
    double f = m - 1.0, s = f / (2.0 + f), z = s * s, hf = 0.5 * f * f;
    double r = 2.0 / 23;
    r = CTI_FMA(r, z, 2.0 / 21);
    r = CTI_FMA(r, z, 2.0 / 19);
    r = CTI_FMA(r, z, 2.0 / 17);
    r = CTI_FMA(r, z, 2.0 / 15);
    r = CTI_FMA(r, z, 2.0 / 13);
    r = CTI_FMA(r, z, 2.0 / 11);
    r = CTI_FMA(r, z, 2.0 / 9);
    r = CTI_FMA(r, z, 2.0 / 7);
    r = CTI_FMA(r, z, 2.0 / 5);
    r = CTI_FMA(r, z, 2.0 / 3);
    r *= z;
    double lo = CTI_FMA(e, 0x1.a39ef35793c76p-33, c);
    double res = CTI_FMA(e, 0x1.62e42fee00000p-1, -((hf - CTI_FMA(s, hf + r, lo)) - f));
    res = y > -1.0 ? res : (y == -1.0 ? -INFINITY : NAN);
    res = y == 0.0 ? y : res; /* -0 stays -0 */
    return y <= DBL_MAX ? res : y; /* +inf, and NaN as itself */
}

#endif

#endif
