/*
 * assemble_body.h -- the per-pair scatter shared by the assembly variants
 * (private to kernels/assemble*.c).
 *
 * Every variant computes one slot's contribution the same way: the weight
 * times the sign (exact, the sign is +1 or -1), then that product times each
 * force component, in separate statements so that no compiler fuses the add
 * into a multiply-add in one variant and not in another.
 */
#ifndef CT_ASSEMBLE_BODY_H
#define CT_ASSEMBLE_BODY_H

#include "ct_internal.h"

/*
 * Weight modes the inner loops are specialised for (the arithmetic is the
 * same in every mode; only the NULL tests are skipped):
 *  0: generic, any w[s] may be NULL;
 *  1: w[0] == NULL, the others given (node-segment pairs);
 *  2: every w[s] given (edge-edge pairs).
 */
static inline int cti_asm_mode(int nslot, const ct_real *const w[])
{
    int given = 0;
    for (int s = 0; s < nslot; s++)
        given += w[s] != NULL;
    if (given == nslot)
        return 2;
    if (!w[0] && given == nslot - 1)
        return 1;
    return 0;
}

/* The weight of slot s of pair k, sign included (exact: sign is +-1). */
static inline __attribute__((always_inline)) ct_real
cti_asm_weight(const ct_real *const w[], const ct_real *sign, int s, ct_idx k, const int mode)
{
    if (mode == 2 || (mode == 1 && s > 0))
        return w[s][k] * sign[s];
    if (mode == 1)
        return sign[0];
    return w[s] ? w[s][k] * sign[s] : sign[s];
}

/* Add pair k's contributions to its nodes, slot by slot in slot order. */
static inline __attribute__((always_inline)) void
cti_asm_pair(ct_idx k, const int nslot, const int mode, const ct_idx *const slot[],
             const ct_real *const w[], const ct_real *sign, const ct_real *restrict fx,
             const ct_real *restrict fy, const ct_real *restrict fz, ct_real *restrict fxn,
             ct_real *restrict fyn, ct_real *restrict fzn)
{
    ct_real f0 = fx[k], f1 = fy[k], f2 = fz[k];
    for (int s = 0; s < nslot; s++) {
        ct_idx n = slot[s][k];
        ct_real ww = cti_asm_weight(w, sign, s, k, mode);
        ct_real cx = ww * f0, cy = ww * f1, cz = ww * f2;
        fxn[n] += cx;
        fyn[n] += cy;
        fzn[n] += cz;
    }
}

/* Whether f0, f1 and f2 all compare equal to 0 (+0 or -0): the bits of
 * the three or-ed, the sign bit shifted out. Fewer instructions than three
 * comparisons, each with its unordered case. */
static inline __attribute__((always_inline)) int cti_asm_zero3(ct_real f0, ct_real f1,
                                                               ct_real f2)
{
#ifdef CT_SINGLE
    uint32_t a, b, c;
#else
    uint64_t a, b, c;
#endif
    memcpy(&a, &f0, sizeof a);
    memcpy(&b, &f1, sizeof b);
    memcpy(&c, &f2, sizeof c);
    return ((a | b | c) << 1) == 0;
}

/* Whether a node-segment map's signs are the usual +1, -1, -1, -1, -1
 * (ct_asm_map_nodeseg): mode 3 of cti_asm_range_k, which adds the force to
 * slot 0 and subtracts the weighted force from the others. */
static inline int cti_asm_signs_nodeseg(int nslot, const ct_real *sign)
{
    if (nslot != 5 || sign[0] != 1)
        return 0;
    for (int s = 1; s < 5; s++)
        if (sign[s] != -1)
            return 0;
    return 1;
}

/* Pairs lo..hi-1 in order, specialised on (nslot, mode); mode 3 is mode 1
 * with the signs of cti_asm_signs_nodeseg; ahead > 0 (mode 3 only: slots 1
 * and 3 are corners) prefetches the nodal forces ahead pairs on
 * (cti_asm_range with sparse).
 *
 * The pairs come sorted by their first slot's node (the secondary node of
 * a node-segment list): that node's force is held in registers over its
 * run of pairs, loaded at the run's first pair and stored after its last,
 * which saves three loads and three stores per pair. It receives the same
 * additions in the same order (a later slot naming it adds to the
 * registers too), so every bit is the memory loop's. */
static inline __attribute__((always_inline)) int
cti_asm_range_k(ct_idx lo, ct_idx hi, const int nslot, const int mode,
                const ct_idx *const slot[], const ct_real *const w[], const ct_real *sign,
                const ct_real *restrict fx, const ct_real *restrict fy,
                const ct_real *restrict fz, ct_real *restrict fxn, ct_real *restrict fyn,
                ct_real *restrict fzn, const int check, const ct_idx nnode, const int ahead)
{
    /* The slot and weight arrays and the signs as locals: read through the
     * caller's arrays of pointers, they were loaded again for every pair
     * (the stores to the nodal forces could have changed them, for all
     * the compiler knew), three loads a slot. */
    const ct_idx *restrict sl[CT_ASM_MAXSLOT];
    const ct_real *wl[CT_ASM_MAXSLOT];
    ct_real sg[CT_ASM_MAXSLOT];
    for (int s = 0; s < nslot; s++) {
        sl[s] = slot[s];
        wl[s] = w[s];
        sg[s] = sign[s];
    }
    const ct_idx *restrict s0 = sl[0];
    ct_idx cur = -1; /* the node held in (ax, ay, az), -1: none */
    ct_real ax = 0, ay = 0, az = 0;
    int bad = 0;
    for (ct_idx k = lo; k < hi; k++) {
        /* check: a pair with a node outside [0, nnode) adds nothing (a
         * predictable branch; the caller answers CT_ERR_RANGE), whatever
         * its force. */
        if (check) {
            /* A negative node becomes a large unsigned one. */
            uint64_t out = 0;
            for (int s = 0; s < nslot; s++)
                out |= (uint64_t)((uint64_t)(int64_t)sl[s][k] >= (uint64_t)nnode);
            if (out) {
                bad = 1;
                continue;
            }
        }
        /* ahead > 0: the first and third corners' forces of pair k + ahead
         * prefetched (a quadrangle's other two share their cache lines). */
        if (ahead > 0 && k + ahead < hi) {
            const ct_idx a1 = sl[1][k + ahead], a3 = sl[3][k + ahead];
            __builtin_prefetch(&fxn[a1], 1);
            __builtin_prefetch(&fyn[a1], 1);
            __builtin_prefetch(&fzn[a1], 1);
            __builtin_prefetch(&fxn[a3], 1);
            __builtin_prefetch(&fyn[a3], 1);
            __builtin_prefetch(&fzn[a3], 1);
        }
        /* A zero force adds nothing (ct_assemble.h): skipped. In a contact
         * cycle's list the pairs in contact come in runs, so the branch is
         * well predicted. */
        const ct_real f0 = fx[k], f1 = fy[k], f2 = fz[k];
        if (cti_asm_zero3(f0, f1, f2))
            continue;
        const ct_idx n0 = s0[k];
        if (n0 != cur) {
            if (cur >= 0) {
                fxn[cur] = ax;
                fyn[cur] = ay;
                fzn[cur] = az;
            }
            cur = n0;
            ax = fxn[cur];
            ay = fyn[cur];
            az = fzn[cur];
        }
        for (int s = 0; s < nslot; s++) {
            const ct_idx n = s == 0 ? n0 : sl[s][k];
            if (mode == 3) {
                /* Signs +1, -1, -1, -1, -1: slot 0 adds the force (1 * f
                 * is f), the others subtract w * f (x + (-w) * f is
                 * x - w * f, bit for bit: negation is exact and the
                 * rounding symmetric). */
                const ct_real ww = s == 0 ? 1 : wl[s][k];
                const ct_real cx = s == 0 ? f0 : ww * f0, cy = s == 0 ? f1 : ww * f1,
                              cz = s == 0 ? f2 : ww * f2;
                if (n == cur) {
                    ax = s == 0 ? ax + cx : ax - cx;
                    ay = s == 0 ? ay + cy : ay - cy;
                    az = s == 0 ? az + cz : az - cz;
                } else {
                    fxn[n] = s == 0 ? fxn[n] + cx : fxn[n] - cx;
                    fyn[n] = s == 0 ? fyn[n] + cy : fyn[n] - cy;
                    fzn[n] = s == 0 ? fzn[n] + cz : fzn[n] - cz;
                }
                continue;
            }
            const ct_real ww = cti_asm_weight(wl, sg, s, k, mode);
            const ct_real cx = ww * f0, cy = ww * f1, cz = ww * f2;
            if (n == cur) {
                ax += cx;
                ay += cy;
                az += cz;
            } else {
                fxn[n] += cx;
                fyn[n] += cy;
                fzn[n] += cz;
            }
        }
    }
    if (cur >= 0) {
        fxn[cur] = ax;
        fyn[cur] = ay;
        fzn[cur] = az;
    }
    return bad;
}

/* The specialisations of cti_asm_range_k for the common (nslot, mode);
 * check and nnode as there. */
#define CTI_ASM_RANGE_DISPATCH(check, nnode)                                                   \
    do {                                                                                       \
        if (mode == 1 && cti_asm_signs_nodeseg(nslot, sign))                                   \
            return cti_asm_range_k(lo, hi, 5, 3, slot, w, sign, fx, fy, fz, fxn, fyn, fzn,     \
                                   check, nnode, 0);                                           \
        if (nslot == 5 && mode == 1)                                                           \
            return cti_asm_range_k(lo, hi, 5, 1, slot, w, sign, fx, fy, fz, fxn, fyn, fzn,     \
                                   check, nnode, 0);                                           \
        if (nslot == 4 && mode == 2)                                                           \
            return cti_asm_range_k(lo, hi, 4, 2, slot, w, sign, fx, fy, fz, fxn, fyn, fzn,     \
                                   check, nnode, 0);                                           \
        if (nslot == 5 && mode == 2)                                                           \
            return cti_asm_range_k(lo, hi, 5, 2, slot, w, sign, fx, fy, fz, fxn, fyn, fzn,     \
                                   check, nnode, 0);                                           \
        return cti_asm_range_k(lo, hi, nslot, 0, slot, w, sign, fx, fy, fz, fxn, fyn, fzn,     \
                               check, nnode, 0);                                               \
    } while (0)

/* Pairs lo..hi-1 whose nodes are known to be in range (a prepared
 * colouring checked them); returns 0. sparse: a list of pairs in contact (a
 * contact cycle's compact lists, ct_assemble_coloured_prefix), whose
 * corners' forces, with the usual node-segment signs, are prefetched
 * CTI_ASM_AHEAD pairs ahead. Such a list touches few pairs a node, in short
 * runs of nodes the hardware prefetcher barely locks on, and its time is
 * the misses on the nodal forces' lines (DESIGN-CHANGES §7); on a whole
 * list in node order the prefetches cost more than they save. The same
 * additions in the same order either way. */
#define CTI_ASM_AHEAD 32
static inline int cti_asm_range(ct_idx lo, ct_idx hi, int nslot, int mode,
                                const ct_idx *const slot[], const ct_real *const w[],
                                const ct_real *sign, const ct_real *restrict fx,
                                const ct_real *restrict fy, const ct_real *restrict fz,
                                ct_real *restrict fxn, ct_real *restrict fyn,
                                ct_real *restrict fzn, int sparse)
{
    if (sparse && mode == 1 && cti_asm_signs_nodeseg(nslot, sign))
        return cti_asm_range_k(lo, hi, 5, 3, slot, w, sign, fx, fy, fz, fxn, fyn, fzn, 0, 0,
                               CTI_ASM_AHEAD);
    CTI_ASM_RANGE_DISPATCH(0, 0);
}

/* Pairs lo..hi-1, each pair's nodes checked against [0, nnode) as it
 * comes: a pair with one out of range adds nothing (to none of its nodes,
 * so the forces added still sum to zero) and the answer is 1.
 * The serial variant's own check: 1.1x its time on 10^4 pairs, none
 * measurable on 10^6, where a vector pass over the slots before the loop
 * cost 1.1x and 1.25x. */
static inline int cti_asm_range_checked(ct_idx lo, ct_idx hi, int nslot, int mode,
                                        const ct_idx *const slot[], const ct_real *const w[],
                                        const ct_real *sign, const ct_real *restrict fx,
                                        const ct_real *restrict fy, const ct_real *restrict fz,
                                        ct_real *restrict fxn, ct_real *restrict fyn,
                                        ct_real *restrict fzn, ct_idx nnode)
{
    CTI_ASM_RANGE_DISPATCH(1, nnode);
}

/* Worksharing loops whose iterations never write the same node: SIMD is
 * legal. gcc vectorises them (gathers and scatters); clang 14 cannot and
 * would warn (an error under -Werror), so it gets the plain loop. */
#ifdef __clang__
#define CTI_ASM_FOR_SIMD _Pragma("omp for schedule(static)")
#else
#define CTI_ASM_FOR_SIMD _Pragma("omp for simd schedule(static)")
#endif

/* The size of the current team (1 outside OpenMP). */
static inline int cti_asm_team(void)
{
#ifdef _OPENMP
    return omp_get_num_threads();
#else
    return 1;
#endif
}

/* Check a map's shape (not its node indices). */
static inline int cti_asm_map_ok(const ct_asm_map *map)
{
    if (!map || map->npair < 0 || map->nslot < 1 || map->nslot > CT_ASM_MAXSLOT)
        return 0;
    for (int s = 0; s < map->nslot; s++)
        if (map->npair > 0 && !map->slot[s])
            return 0;
    return 1;
}

/* CT_ERR_RANGE when a slot of the map holds a node outside [0, nnode): a
 * pass over the slots, made by every entry that would otherwise write
 * through them unchecked (the colouring and the gather map once per pair
 * list; the atomic variant and the serial scalar sum, which have no
 * preparation, at every call). */
static inline int cti_asm_nodes_in_range(const ct_asm_map *map, ct_idx nnode)
{
    int bad = 0;
    for (int s = 0; s < map->nslot; s++) {
        const ct_idx *restrict sl = map->slot[s];
#pragma omp parallel for schedule(static) reduction(| : bad)
        for (ct_idx k = 0; k < map->npair; k++)
            bad |= (sl[k] < 0) | (sl[k] >= nnode);
    }
    return bad ? CT_ERR_RANGE : CT_OK;
}

#endif /* CT_ASSEMBLE_BODY_H */
