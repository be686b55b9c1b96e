/*
 * test_assemble_blocks.c -- the colouring on blocks the caller chooses
 * (ct_colour_pair_blocks) and the blocks that never split a node's pairs
 * (ct_pair_node_blocks), suite "assemble".
 *
 * The truths: starts computed by hand on a short list; on a plate, the
 * defining properties checked pair by pair (a block's first pair starts a
 * node's run, every block but the last holds at least `block` pairs and
 * stops at the first run end after them); the brute-force colouring check
 * of test_assemble.c; the plain loop of test_assemble.h for the forces
 * (within check_all_variants' tolerance: the colouring sums in another
 * order).
 */
#include "test_assemble.h"

Test(assemble, node_blocks_by_hand)
{
    /* Runs: 0 x2, 1 x3, 2 x1, 3 x4, 4 x1. */
    const ct_idx node[] = {0, 0, 1, 1, 1, 2, 3, 3, 3, 3, 4};
    ct_idx bs[16];
    /* Block 2: [0, 2) ends a run; [2, 4) cuts node 1: to 5; [5, 7) cuts
     * node 3: to 10; [10, 11) the last. */
    cr_assert_eq(ct_pair_node_blocks(11, node, 2, bs), 4);
    const ct_idx want2[] = {0, 2, 5, 10, 11};
    for (int b = 0; b <= 4; b++)
        cr_assert_eq(bs[b], want2[b], "block 2: start %d is %d, expected %d", b, (int)bs[b],
                     (int)want2[b]);
    /* Block 1: one run per block. */
    cr_assert_eq(ct_pair_node_blocks(11, node, 1, bs), 5);
    const ct_idx want1[] = {0, 2, 5, 6, 10, 11};
    for (int b = 0; b <= 5; b++)
        cr_assert_eq(bs[b], want1[b]);
    /* A block past the list: one block. */
    cr_assert_eq(ct_pair_node_blocks(11, node, 100, bs), 1);
    cr_assert(bs[0] == 0 && bs[1] == 11);
    /* No pair: no block, and the final start. */
    bs[0] = -7;
    cr_assert_eq(ct_pair_node_blocks(0, NULL, 4, bs), 0);
    cr_assert_eq(bs[0], 0);
    /* Bad arguments. */
    const ct_idx down[] = {0, 2, 1};
    cr_assert_eq(ct_pair_node_blocks(3, down, 2, bs), CT_ERR_ARG);
    cr_assert_eq(ct_pair_node_blocks(11, node, 0, bs), CT_ERR_ARG);
    cr_assert_eq(ct_pair_node_blocks(11, node, 2, NULL), CT_ERR_ARG);
    cr_assert_eq(ct_pair_node_blocks(-1, node, 2, bs), CT_ERR_ARG);
}

/* The colouring on node blocks of a plate: no two blocks of a colour share
 * a node; the coloured assembly, whole and over block prefixes, adds the
 * plain loop's forces, bit for bit alike on 1 and 2 threads. */
Test(assemble, colouring_on_node_blocks)
{
    const int ns = ctt_checking() ? 48 : 120;
    tpairs g;
    tp_alloc(&g, (ct_idx)4 * ns * ns + 16, 5);
    tp_plate(&g, ns / 2, ns, 0.5);
    const ct_idx np = g.npair, block = 37;
    ct_idx *bs = malloc(((size_t)np / block + 2) * sizeof *bs);
    cr_assert(bs);
    const ct_idx nb = ct_pair_node_blocks(np, g.s[0], block, bs);
    cr_assert_gt(nb, 10);
    /* The definition, pair by pair. */
    int64_t cut_runs = 0;
    for (ct_idx b = 0; b < nb; b++) {
        const ct_idx lo = bs[b], hi = bs[b + 1];
        cr_assert(hi > lo);
        if (lo > 0)
            cr_assert_neq(g.s[0][lo], g.s[0][lo - 1], "block %d splits a node's run", (int)b);
        if (b < nb - 1) {
            cr_assert_geq(hi - lo, block);
            /* It stops at the first run end after `block` pairs. */
            for (ct_idx k = lo + block; k < hi; k++)
                cr_assert_eq(g.s[0][k], g.s[0][k - 1]);
            cut_runs += hi - lo > block;
        }
    }
    cr_assert_eq(bs[nb], np);
    cr_assert_gt(cut_runs, 0, "the case should have runs across the nominal block ends");

    ct_asm_map map = tp_map(&g);
    ct_assemble_ws ws;
    cr_assert_eq(ct_assemble_ws_init(&ws), CT_OK);
    cr_assert_eq(ct_colour_pair_blocks(&ws, &map, g.nnode, nb, bs), CT_OK);
    cr_assert_eq(ws.block, 0);
    cr_assert_eq(ws.nblock, nb);
    check_colouring_at(&ws, &g, bs);

    /* Forces: the plain loop, then the colouring on 1 and 2 threads. */
    double *rx = malloc((size_t)g.nnode * sizeof *rx), *ry = malloc((size_t)g.nnode * sizeof *ry);
    double *rz = malloc((size_t)g.nnode * sizeof *rz), *sc = malloc((size_t)g.nnode * sizeof *sc);
    ct_real *zero = ct_calloc((size_t)g.nnode, sizeof(ct_real));
    cr_assert(rx && ry && rz && sc && zero);
    reference(&g, zero, zero, zero, rx, ry, rz, sc);
    const ct_real *wb[5];
    nodef one, two, pre1, pre2;
    nf_init(&one, g.nnode, NULL, NULL, NULL);
    nf_init(&two, g.nnode, NULL, NULL, NULL);
    nf_init(&pre1, g.nnode, NULL, NULL, NULL);
    nf_init(&pre2, g.nnode, NULL, NULL, NULL);
    nodef *whole[2] = {&one, &two}, *pre[2] = {&pre1, &pre2};
    /* Prefixes: every third block empty, the others whole. */
    ct_idx *count = calloc((size_t)nb, sizeof *count);
    cr_assert(count);
    for (ct_idx b = 0; b < nb; b++)
        count[b] = b % 3 == 0 ? 0 : bs[b + 1] - bs[b];
    for (int t = 0; t < 2; t++) {
        ctt_threads(t + 1);
        cr_assert_eq(ct_assemble_coloured(&ws, &map, weights(&g, wb), g.f[0], g.f[1], g.f[2],
                                          g.nnode, whole[t]->x, whole[t]->y, whole[t]->z),
                     CT_OK);
        cr_assert_eq(ct_assemble_coloured_prefix(&ws, &map, count, weights(&g, wb), g.f[0],
                                                 g.f[1], g.f[2], g.nnode, pre[t]->x,
                                                 pre[t]->y, pre[t]->z),
                     CT_OK);
    }
    const double err = worst_rel(&one, rx, ry, rz, sc);
    cr_assert_lt(err, CTT_TOL(1e-12, 1e-5), "coloured on node blocks against the plain loop: %g",
                 err);
    cr_assert(nf_same_bits(&one, &two), "1 and 2 threads differ");
    cr_assert(nf_same_bits(&pre1, &pre2), "prefixes: 1 and 2 threads differ");
    /* The prefixes' forces are those of the blocks kept: the plain loop
     * over their pairs. */
    tpairs kept = g;
    for (int a = 0; a < 3; a++) {
        kept.f[a] = ct_calloc((size_t)np, sizeof(ct_real));
        cr_assert(kept.f[a]);
    }
    for (ct_idx b = 0; b < nb; b++)
        for (ct_idx k = bs[b]; k < bs[b] + count[b]; k++)
            for (int a = 0; a < 3; a++)
                kept.f[a][k] = g.f[a][k];
    reference(&kept, zero, zero, zero, rx, ry, rz, sc);
    const double perr = worst_rel(&pre1, rx, ry, rz, sc);
    cr_assert_lt(perr, CTT_TOL(1e-12, 1e-5), "prefixes against the plain loop: %g", perr);
    cr_assert(!nf_same_bits(&one, &pre1));

    /* Starts that are not blocks of the list: refused, and the workspace
     * then refuses to assemble. */
    const ct_idx saved = bs[1];
    bs[1] = bs[2];
    cr_assert_eq(ct_colour_pair_blocks(&ws, &map, g.nnode, nb, bs), CT_ERR_ARG);
    cr_assert_neq(ct_assemble_coloured(&ws, &map, weights(&g, wb), g.f[0], g.f[1], g.f[2],
                                       g.nnode, one.x, one.y, one.z),
                  CT_OK);
    bs[1] = saved;
    bs[nb] = np - 1;
    cr_assert_eq(ct_colour_pair_blocks(&ws, &map, g.nnode, nb, bs), CT_ERR_ARG);
    bs[nb] = np;
    bs[0] = 1;
    cr_assert_eq(ct_colour_pair_blocks(&ws, &map, g.nnode, nb, bs), CT_ERR_ARG);
    bs[0] = 0;
    cr_assert_eq(ct_colour_pair_blocks(&ws, &map, g.nnode, nb, NULL), CT_ERR_ARG);
    cr_assert_eq(ct_colour_pair_blocks(&ws, &map, g.nnode, nb, bs), CT_OK);

    for (int a = 0; a < 3; a++)
        ct_free(kept.f[a]);
    free(count);
    nf_free(&one);
    nf_free(&two);
    nf_free(&pre1);
    nf_free(&pre2);
    ct_free(zero);
    free(rx);
    free(ry);
    free(rz);
    free(sc);
    free(bs);
    ct_assemble_ws_destroy(&ws);
    tp_free(&g);
}

/* Given the uniform blocks' starts, the colouring is ct_colour_pairs's. */
Test(assemble, given_uniform_blocks_colour_as_the_block_size)
{
    tpairs g;
    tp_alloc(&g, (ct_idx)4 * 40 * 40 + 16, 5);
    tp_plate(&g, 20, 40, 0.5);
    const ct_idx B = 29, nb = (g.npair + B - 1) / B;
    ct_idx *bs = malloc(((size_t)nb + 1) * sizeof *bs);
    cr_assert(bs);
    for (ct_idx b = 0; b < nb; b++)
        bs[b] = b * B;
    bs[nb] = g.npair;
    ct_asm_map map = tp_map(&g);
    ct_assemble_ws a, c;
    cr_assert_eq(ct_assemble_ws_init(&a), CT_OK);
    cr_assert_eq(ct_assemble_ws_init(&c), CT_OK);
    cr_assert_eq(ct_colour_pairs(&a, &map, g.nnode, B), CT_OK);
    cr_assert_eq(ct_colour_pair_blocks(&c, &map, g.nnode, nb, bs), CT_OK);
    cr_assert_eq(a.nblock, c.nblock);
    cr_assert_eq(a.ncolour, c.ncolour);
    cr_assert_gt(a.ncolour, 1);
    for (ct_idx b = 0; b < nb; b++)
        cr_assert_eq(a.colour[b], c.colour[b]);
    free(bs);
    ct_assemble_ws_destroy(&a);
    ct_assemble_ws_destroy(&c);
    tp_free(&g);
}
