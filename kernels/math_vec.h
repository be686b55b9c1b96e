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
 * Every operation is one a vector lane computes with the same rounding as
 * a scalar (CTI_FMA is fused or not in both): a pair's value has the same
 * bits whichever path computes it, so ct_friction_mu and ct_friction_mu1
 * agree bit for bit. Accuracy against expl, and the edges (overflow,
 * underflow, subnormal results, infinities, NaN) are measured by
 * tests/test_math_vec.c. (A log1p written the same way made TYPE7's
 * energy a vector loop, slower on the benchmark's pairs than the scalar
 * loop over the pairs in contact: DESIGN-CHANGES §7.)
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


#endif

#endif
