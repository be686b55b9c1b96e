/*
 * search_bsp_partition.c -- the quick-sort search's partition of a box's
 * nodes about a pivot (private to kernels/search_bsp*.c).
 *
 * A split moves the nodes of [n0, n1) of the tree order (coordinates nx,
 * ny, nz and numbers nid, four arrays) so that those whose coordinate on
 * the split axis is below the pivot come first. Hoare's partition, which
 * swaps pairs from both ends, takes a branch per node on its coordinate:
 * on a mesh deeper in the tree, where a box's nodes lie in no useful
 * order, half of those branches are mispredicted, and the swaps scramble
 * the order further. Here the partition is stable and branch-free:
 *  - a node below the pivot is written back in place at the next free
 *    position of the left part (never past the node being read, so no
 *    node is overwritten before it is read), a node above it to a scratch
 *    array, and the scratch is copied behind the left part at the end;
 *  - with AVX-512, sixteen nodes at a time: one compare gives the mask,
 *    and each array's sixteen values are compressed in registers to the
 *    left ones and to the right ones, each stored as a whole vector at its
 *    part's next free position (the lanes past the part's new end are
 *    garbage that later stores or the final copy overwrite; they never
 *    reach past the sixteen just read);
 *  - without it, one node at a time, stored to both places with the
 *    positions advanced by the comparison.
 * Both orders are the one stable partition, so the tree (and every
 * answer) is the same whichever path ran. A NaN coordinate compares false
 * and goes right, as in the partition it replaces.
 */
#include "search_bsp_internal.h"

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

ct_idx cti_bsp_partition(bsp_f *restrict nx, bsp_f *restrict ny, bsp_f *restrict nz,
                         ct_idx *restrict nid, ct_idx n0, ct_idx n1, int ax, bsp_f mid,
                         bsp_f *restrict scratch)
{
    /* The scratch holds the right part's four arrays, w apart. */
    const size_t w = (size_t)(n1 - n0);
    bsp_f *restrict sx = scratch, *restrict sy = scratch + w, *restrict sz = scratch + 2 * w;
    ct_idx *restrict sid = (ct_idx *)(void *)(scratch + 3 * w);
    ct_idx i = n0, l = n0;
    size_t r = 0;
#if defined(__AVX512F__)
    const __m512 vm = _mm512_set1_ps(mid);
    for (; i + 16 <= n1; i += 16) {
        const __m512 vx = _mm512_loadu_ps(nx + i), vy = _mm512_loadu_ps(ny + i);
        const __m512 vz = _mm512_loadu_ps(nz + i);
        const __m512i vi = _mm512_loadu_si512((const void *)(nid + i));
        const __m512 va = ax == 0 ? vx : (ax == 1 ? vy : vz);
        const __mmask16 kl = _mm512_cmp_ps_mask(va, vm, _CMP_LT_OQ);
        const __mmask16 kr = (__mmask16)~kl;
        _mm512_storeu_ps(nx + l, _mm512_maskz_compress_ps(kl, vx));
        _mm512_storeu_ps(ny + l, _mm512_maskz_compress_ps(kl, vy));
        _mm512_storeu_ps(nz + l, _mm512_maskz_compress_ps(kl, vz));
        _mm512_storeu_si512((void *)(nid + l), _mm512_maskz_compress_epi32(kl, vi));
        _mm512_storeu_ps(sx + r, _mm512_maskz_compress_ps(kr, vx));
        _mm512_storeu_ps(sy + r, _mm512_maskz_compress_ps(kr, vy));
        _mm512_storeu_ps(sz + r, _mm512_maskz_compress_ps(kr, vz));
        _mm512_storeu_si512((void *)(sid + r), _mm512_maskz_compress_epi32(kr, vi));
        const int c = __builtin_popcount((unsigned)kl);
        l += c;
        r += (size_t)(16 - c);
    }
#endif
    for (; i < n1; i++) {
        const bsp_f x = nx[i], y = ny[i], z = nz[i];
        const ct_idx id = nid[i];
        const bsp_f a = ax == 0 ? x : (ax == 1 ? y : z);
        const int left = a < mid;
        nx[l] = x, ny[l] = y, nz[l] = z, nid[l] = id;
        sx[r] = x, sy[r] = y, sz[r] = z, sid[r] = id;
        l += left;
        r += (size_t)(1 - left);
    }
    memcpy(nx + l, sx, r * sizeof *nx);
    memcpy(ny + l, sy, r * sizeof *ny);
    memcpy(nz + l, sz, r * sizeof *nz);
    memcpy(nid + l, sid, r * sizeof *nid);
    return l;
}
