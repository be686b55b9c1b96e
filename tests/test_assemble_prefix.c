/*
 * test_assemble_prefix.c -- ct_assemble_coloured_prefix (suite "assemble"):
 * the colouring over a prefix of each block adds exactly the pairs of
 * those prefixes, bit for bit as ct_assemble_coloured adds the same forces
 * with every other pair's force set to zero (the zeros it skips), on 1 and
 * 2 threads, on a small list (no thread team) and a large one.
 */
#include "test_assemble.h"

static void nf_zero(nodef *f)
{
    memset(f->x, 0, (size_t)f->n * sizeof(ct_real));
    memset(f->y, 0, (size_t)f->n * sizeof(ct_real));
    memset(f->z, 0, (size_t)f->n * sizeof(ct_real));
}

static void prefix_case(int nm, int ns, ct_idx block)
{
    tpairs g;
    tp_alloc(&g, (ct_idx)4 * ns * ns, 5);
    tp_plate(&g, nm, ns, 0.9);
    const ct_asm_map map = tp_map(&g);
    ct_assemble_ws ws;
    cr_assert_eq(ct_assemble_ws_init(&ws), CT_OK);
    cr_assert_eq(ct_colour_pairs(&ws, &map, g.nnode, block), CT_OK);
    cr_assert_eq(ws.block, block);
    /* Prefix lengths: empty, whole, beyond the block (taken as whole) and
     * random in between. */
    const ct_idx nb = ws.nblock;
    ct_idx *count = ct_calloc((size_t)nb, sizeof(ct_idx));
    cr_assert(count);
    for (ct_idx b = 0; b < nb; b++)
        count[b] = b % 5 == 0 ? 0 : b % 5 == 1 ? block : b % 5 == 2 ? block + 7
                                                        : (ct_idx)(urand() * block);
    /* The reference: every force outside the prefixes set to zero. */
    tpairs z = g;
    for (int a = 0; a < 3; a++) {
        z.f[a] = ct_calloc((size_t)g.npair, sizeof(ct_real));
        cr_assert(z.f[a]);
    }
    int64_t kept = 0, left = 0;
    for (ct_idx k = 0; k < g.npair; k++) {
        const ct_idx b = k / block;
        const int in = k - b * block < count[b];
        for (int a = 0; a < 3; a++)
            z.f[a][k] = in ? g.f[a][k] : 0;
        kept += in;
        left += !in;
    }
    cr_assert_gt(kept, 0);
    cr_assert_gt(left, 0);
    const ct_real *wb[5];
    nodef ref, full, got;
    nf_init(&ref, g.nnode, NULL, NULL, NULL);
    nf_init(&full, g.nnode, NULL, NULL, NULL);
    nf_init(&got, g.nnode, NULL, NULL, NULL);
    ctt_threads(1);
    cr_assert_eq(ct_assemble_coloured(&ws, &map, weights(&g, wb), z.f[0], z.f[1], z.f[2],
                                      g.nnode, ref.x, ref.y, ref.z),
                 CT_OK);
    cr_assert_eq(ct_assemble_coloured(&ws, &map, weights(&g, wb), g.f[0], g.f[1], g.f[2],
                                      g.nnode, full.x, full.y, full.z),
                 CT_OK);
    /* The prefixes matter: the whole list gives other forces. */
    cr_assert(!nf_same_bits(&ref, &full));
    for (int thr = 1; thr <= 2; thr++) {
        ctt_threads(thr);
        nf_zero(&got);
        cr_assert_eq(ct_assemble_coloured_prefix(&ws, &map, count, weights(&g, wb), g.f[0],
                                                 g.f[1], g.f[2], g.nnode, got.x, got.y, got.z),
                     CT_OK);
        cr_assert(nf_same_bits(&ref, &got), "%d pairs, %d threads: the prefixes' forces differ",
                  (int)g.npair, thr);
        /* No count: the whole blocks, as ct_assemble_coloured. */
        nf_zero(&got);
        cr_assert_eq(ct_assemble_coloured_prefix(&ws, &map, NULL, weights(&g, wb), g.f[0],
                                                 g.f[1], g.f[2], g.nnode, got.x, got.y, got.z),
                     CT_OK);
        cr_assert(nf_same_bits(&full, &got));
    }
    nf_free(&ref);
    nf_free(&full);
    nf_free(&got);
    for (int a = 0; a < 3; a++)
        ct_free(z.f[a]);
    ct_free(count);
    ct_assemble_ws_destroy(&ws);
    tp_free(&g);
}

Test(assemble, coloured_prefix_small_list)
{
    prefix_case(20, 24, 64); /* about 1300 pairs: no thread team */
}

Test(assemble, coloured_prefix_large_list)
{
    prefix_case(60, 70, 256); /* about 11000 pairs */
}
