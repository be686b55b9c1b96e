/*
 * test_assemble_scalar.c -- ct_assemble_scalar (suite assemble_scalar): one
 * value per pair spread onto the pair's nodes, against a plain loop in
 * double, with the colouring and serially, bit-identical for 1 and 2
 * threads.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "test_util.h"

/* A node-segment map of np pairs on nn nodes with heavy sharing: slot
 * arrays sl[0..4] of random nodes and weights w[0..4] in [0, 1), from an
 * LCG seeded with seed (ct_calloc'ed; random_map_free frees them). */
static void random_map(ct_idx np, ct_idx nn, uint64_t seed, ct_idx *sl[5], ct_real *w[5])
{
    for (int a = 0; a < 5; a++) {
        sl[a] = ct_calloc((size_t)np, sizeof(ct_idx));
        w[a] = ct_calloc((size_t)np, sizeof(ct_real));
        cr_assert(sl[a] && w[a]);
    }
    uint64_t s = seed;
    for (ct_idx k = 0; k < np; k++)
        for (int a = 0; a < 5; a++) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            sl[a][k] = (ct_idx)((s >> 33) % (uint64_t)nn);
            w[a][k] = (ct_real)((double)((s >> 11) & 0xFFFF) / 65536.0);
        }
}

static void random_map_free(ct_idx *sl[5], ct_real *w[5])
{
    for (int a = 0; a < 5; a++) {
        ct_free(sl[a]);
        ct_free(w[a]);
    }
}

Test(assemble_scalar, matches_plain_loop_and_threads)
{
    /* Pairs of a node-segment map with heavy sharing: 20000 pairs on 3000
     * nodes, weights in [0, 1), signs (+, -, -, -, -). */
    const ct_idx np = 20000, nn = 3000;
    ct_idx *sl[5];
    ct_real *w[5], *f = ct_calloc((size_t)np, sizeof(ct_real));
    cr_assert(f);
    random_map(np, nn, 12345, sl, w);
    for (ct_idx k = 0; k < np; k++)
        f[k] = (ct_real)(1.0 + (double)(k % 97));
    ct_asm_map map = ct_asm_map_nodeseg(np, sl[0], sl[1], sl[2], sl[3], sl[4]);
    const ct_real *const wt[5] = {NULL, w[1], w[2], w[3], w[4]};
    double *ref = calloc((size_t)nn, sizeof(double));
    cr_assert(ref);
    for (ct_idx k = 0; k < np; k++) {
        ref[sl[0][k]] += (double)f[k];
        for (int a = 1; a < 5; a++)
            ref[sl[a][k]] -= (double)w[a][k] * (double)f[k];
    }
    ct_assemble_ws ws;
    cr_assert_eq(ct_assemble_ws_init(&ws), CT_OK);
    cr_assert_eq(ct_assemble_prepare(&ws, CT_ASM_COLOUR, &map, nn), CT_OK);
    ct_real *out[3];
    for (int r = 0; r < 3; r++) {
        out[r] = ct_calloc((size_t)nn, sizeof(ct_real));
        cr_assert(out[r]);
    }
    ctt_threads(1);
    cr_assert_eq(ct_assemble_scalar(&ws, CT_ASM_COLOUR, &map, wt, f, nn, out[0]), CT_OK);
    ctt_threads(2);
    cr_assert_eq(ct_assemble_scalar(&ws, CT_ASM_COLOUR, &map, wt, f, nn, out[1]), CT_OK);
    cr_assert_eq(ct_assemble_scalar(&ws, CT_ASM_SERIAL, &map, wt, f, nn, out[2]), CT_OK);
    cr_expect(memcmp(out[0], out[1], sizeof(ct_real) * (size_t)nn) == 0,
              "colour: 1 and 2 threads differ");
    double scale = 0;
    for (ct_idx i = 0; i < nn; i++)
        scale = fmax(scale, fabs(ref[i]));
    for (int r = 0; r < 3; r += 2)
        for (ct_idx i = 0; i < nn; i++)
            cr_assert(fabs((double)out[r][i] - ref[i]) <= CTT_TOL(1e-12, 1e-4) * scale,
                      "run %d node %d: %.17g, expected %.17g", r, (int)i, (double)out[r][i],
                      ref[i]);
    /* A workspace prepared for another map is refused. */
    ct_asm_map other = ct_asm_map_nodeseg(np - 1, sl[0], sl[1], sl[2], sl[3], sl[4]);
    cr_expect_eq(ct_assemble_scalar(&ws, CT_ASM_COLOUR, &other, wt, f, nn, out[0]), CT_ERR_ARG);
    ct_assemble_ws_destroy(&ws);
    for (int r = 0; r < 3; r++)
        ct_free(out[r]);
    random_map_free(sl, w);
    ct_free(f);
    free(ref);
}

/* Pairs whose value is exactly zero (two in three here, as in a contact
 * list where most candidates do not count) are skipped: the result is bit
 * for bit that of a plain loop adding every pair, zeros included, in pair
 * order (the serial sum; the coloured one, on 1 and 2 threads, adds in
 * colour order, so to round-off). A NaN weight on a zero pair stays out, as
 * ct_assemble.h says: the check that the skip is there. */
Test(assemble_scalar, zero_values_add_nothing)
{
    const ct_idx np = 30000, nn = 4000;
    ct_idx *sl[5];
    ct_real *w[5], *f = ct_calloc((size_t)np, sizeof(ct_real));
    cr_assert(f);
    random_map(np, nn, 777, sl, w);
    for (ct_idx k = 0; k < np; k++)
        f[k] = k % 3 == 0 ? (ct_real)(0.1 + (double)(k % 89)) : (k % 3 == 1 ? 0 : -(ct_real)0);
    ct_asm_map map = ct_asm_map_nodeseg(np, sl[0], sl[1], sl[2], sl[3], sl[4]);
    for (int a = 0; a < 5; a++)
        map.sign[a] = 1;
    const ct_real *const wt[5] = {NULL, w[1], w[2], w[3], w[4]};
    ct_real *ref = ct_calloc((size_t)nn, sizeof(ct_real));
    cr_assert(ref);
    for (ct_idx k = 0; k < np; k++)
        for (int a = 0; a < 5; a++)
            ref[sl[a][k]] += (a == 0 ? (ct_real)1 : w[a][k]) * f[k];
    ct_assemble_ws ws;
    cr_assert_eq(ct_assemble_ws_init(&ws), CT_OK);
    cr_assert_eq(ct_assemble_prepare(&ws, CT_ASM_COLOUR, &map, nn), CT_OK);
    ct_real *out = ct_calloc((size_t)nn, sizeof(ct_real));
    cr_assert(out);
    for (int r = 0; r < 3; r++) {
        memset(out, 0, sizeof(ct_real) * (size_t)nn);
        ctt_threads(r == 2 ? 2 : 1);
        cr_assert_eq(ct_assemble_scalar(&ws, r == 0 ? CT_ASM_SERIAL : CT_ASM_COLOUR, &map, wt, f,
                                        nn, out),
                     CT_OK);
        if (r == 0)
            cr_assert(memcmp(out, ref, sizeof(ct_real) * (size_t)nn) == 0,
                      "serial: not the plain loop's bits");
        else
            for (ct_idx i = 0; i < nn; i++)
                cr_assert(fabs((double)out[i] - (double)ref[i]) <=
                              CTT_TOL(1e-12, 1e-4) * (1 + fabs((double)ref[i])),
                          "colour run %d node %d", r, (int)i);
    }
    /* A NaN weight on a pair of value zero adds nothing. */
    w[2][1] = (ct_real)NAN;
    memset(out, 0, sizeof(ct_real) * (size_t)nn);
    cr_assert_eq(ct_assemble_scalar(&ws, CT_ASM_SERIAL, &map, wt, f, nn, out), CT_OK);
    for (ct_idx i = 0; i < nn; i++)
        cr_assert(!isnan((double)out[i]), "node %d got the NaN of a zero pair", (int)i);
    ct_assemble_ws_destroy(&ws);
    ct_free(out);
    ct_free(ref);
    random_map_free(sl, w);
    ct_free(f);
}
