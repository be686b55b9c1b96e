/*
 * contact_cycle_skip.c -- the skip of the contact cycle's narrow phase (see
 * contact_cycle.h for why it is exact): the motion bound (the re-sort
 * criterion's, from one cycle to the next) summed cycle after cycle, each
 * pair's expiry (the value of that sum up to which its last distance
 * proves it out of contact), carried across a re-sort, and the selection
 * of the pairs whose expiry has passed.
 *
 * The expiry of a pair evaluated when the sum was M, at distance D with gap
 * g, is M + (D - g - slack) / (1 + 1e-6); the pair is skipped while the sum
 * is below it. A pair whose segment was skipped by the kernel (degenerate,
 * or a NaN/Inf coordinate) gets -1: it is evaluated every cycle, as is every
 * pair when the sum or the expiry is NaN (the comparison is false).
 */
#include "contact_cycle_internal.h"

#include <float.h>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#ifdef CT_SINGLE
#define CY_EPS FLT_EPSILON
#else
#define CY_EPS DBL_EPSILON
#endif

int cti_skip_motion(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z,
                    ct_real *bound)
{
    /* One pass over the nodes (ct_resort_track): the re-sort criterion
     * against the positions at the last sort, returned with its bound for
     * the search phase; this step's bound, the criterion's against the last
     * cycle's positions (buffer pc; 0 for a rigid motion), added to the
     * sum; this cycle's positions into the other buffer. The first cycle
     * has no previous positions: its pairs are all new (expiry -1), so the
     * sum does not matter; it stays 0. */
    const int p = cy->pc, q = 1 - p;
    ct_real step = 0;
    double L = 0;
    int need = ct_resort_track(cy->nsec, cy->sec, cy->nmain, cy->mainn, cy->x0, cy->y0, cy->z0,
                               cy->xp[p], cy->yp[p], cy->zp[p], x, y, z, cy->xp[q], cy->yp[q],
                               cy->zp[q], cy->p.margin, bound, &step, &L);
    if (cy->have_prev)
        cy->motion += step == step ? (double)step : INFINITY;
    cy->pc = q;
    cy->have_prev = 1;
    cy->slack = 1024 * CY_EPS * (L + (double)cy->p.gap);
    return need;
}

void cti_skip_remap(ctd_cycle *cy, ct_idx n, int old, int now)
{
    const ct_idx *restrict o = cy->old_of_new;
    const ct_real *restrict src = cy->ex[old];
    ct_real *restrict dst = cy->ex[now];
    const double M = cy->motion;
    /* (The penetrations were remapped before: a pair the skip leaves out
     * reads 0, as the force pass needs.) */
#pragma omp parallel for schedule(static)
    for (ct_idx k = 0; k < n; k++)
        dst[k] = o[k] >= 0 ? (ct_real)((double)src[o[k]] - M) : (ct_real)-1;
    cy->motion = 0;
}

ct_idx cti_skip_select(ctd_cycle *cy, ct_idx k0, ct_idx k1, ct_idx *restrict act)
{
    const ct_real *restrict ex = cy->ex[cy->cur] + k0;
    uint8_t *restrict ev = cy->evald + k0;
    const double M = cy->motion;
    const ct_idx n = k1 - k0;
    ct_idx ne = 0, k = 0;
#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)
    /* 16 pairs a step: the test in two vectors of 8 doubles (NaN selects,
     * as !(M < ex) does), the selected indices stored compressed. */
    const __m512d vm = _mm512_set1_pd(M);
    const __m512i step = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    for (; k + 16 <= n; k += 16) {
#ifdef CT_SINGLE
        const __m512d e0 = _mm512_cvtps_pd(_mm256_loadu_ps(ex + k));
        const __m512d e1 = _mm512_cvtps_pd(_mm256_loadu_ps(ex + k + 8));
#else
        const __m512d e0 = _mm512_loadu_pd(ex + k), e1 = _mm512_loadu_pd(ex + k + 8);
#endif
        const __mmask16 m = (__mmask16)(_mm512_cmp_pd_mask(vm, e0, _CMP_NLT_UQ) |
                                        (_mm512_cmp_pd_mask(vm, e1, _CMP_NLT_UQ) << 8));
        _mm512_mask_compressstoreu_epi32(act + ne, m,
                                         _mm512_add_epi32(_mm512_set1_epi32((int)k), step));
        _mm_storeu_si128((__m128i *)(void *)(ev + k), _mm_maskz_set1_epi8(m, 1));
        ne += (ct_idx)__builtin_popcount((unsigned)m);
    }
#endif
    /* Every index is written, the count advances by the test: no branch. */
    for (; k < n; k++) {
        const int need = !(M < (double)ex[k]);
        act[ne] = k;
        ne += need;
        ev[k] = (uint8_t)need;
    }
    return ne;
}

void cti_skip_expiry(ctd_cycle *cy, ct_idx k0, ct_idx ne, const ct_idx *restrict act,
                     const ct_real *restrict dist, const ct_real *restrict gap,
                     const uint8_t *restrict flag)
{
    ct_real *restrict ex = cy->ex[cy->cur] + k0;
    const double M = cy->motion, slack = cy->slack, inv = 1 / (1 + 1e-6);
    const uint8_t bad = CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE;
    for (ct_idx j = 0; j < ne; j++) {
        double e = (flag[j] & bad) ? -1 : M + ((double)dist[j] - (double)gap[j] - slack) * inv;
        ex[act[j]] = (ct_real)e;
    }
}
