/*
 * test_assemble.c -- race-free force assembly (suite "assemble").
 *
 * The truths: a plain sequential loop written here (independent of the
 * library, test_assemble.h), brute-force checks of the colouring (no two
 * blocks of a colour share a node; greedy minimality), and bit-for-bit
 * comparisons across thread counts for the deterministic variants. Balance
 * laws, weights, workspace reuse and bad input: test_assemble_balance.c.
 */
#include "test_assemble.h"

/* ---- Colouring checks (brute force, independent of the library) ----------- */

/* No two blocks of one colour share a node. stamp[n] holds (colour, block)
 * of the last block of that colour to touch n, per colour pass. Blocks of
 * ws->block pairs, or (block 0) the given starts bstart. */
void check_colouring_at(const ct_assemble_ws *ws, const tpairs *g, const ct_idx *bstart)
{
    ct_idx B = ws->block, nb = ws->nblock;
    if (B > 0)
        cr_assert_eq(nb, (g->npair + B - 1) / B);
    else
        cr_assert(bstart && bstart[0] == 0 && bstart[nb] == g->npair);
    cr_assert_eq(ws->col_off[0], 0);
    cr_assert_eq(ws->col_off[ws->ncolour], nb);
    int64_t *owner = malloc((size_t)g->nnode * sizeof *owner);
    char *seen = calloc((size_t)nb, 1);
    cr_assert(owner && seen);
    for (ct_idx n = 0; n < g->nnode; n++)
        owner[n] = -1;
    int64_t conflicts = 0;
    for (ct_idx c = 0; c < ws->ncolour; c++) {
        cr_assert(ws->col_off[c + 1] > ws->col_off[c], "colour %d is empty", (int)c);
        for (ct_idx j = ws->col_off[c]; j < ws->col_off[c + 1]; j++) {
            ct_idx b = ws->bperm[j];
            cr_assert(b >= 0 && b < nb && !seen[b]);
            seen[b] = 1;
            cr_assert_eq(ws->colour[b], c);
            if (j > ws->col_off[c])
                cr_assert(b > ws->bperm[j - 1], "blocks not increasing inside a colour");
            int64_t tag = (int64_t)c * nb + b;
            const ct_idx lo = B > 0 ? b * B : bstart[b];
            const ct_idx hi = B > 0 ? (g->npair - lo > B ? lo + B : g->npair) : bstart[b + 1];
            for (ct_idx k = lo; k < hi; k++)
                for (int s = 0; s < 5; s++) {
                    ct_idx n = g->s[s][k];
                    if (owner[n] >= (int64_t)c * nb && owner[n] != tag)
                        conflicts++;
                    owner[n] = tag;
                }
        }
    }
    cr_assert_eq(conflicts, 0, "%lld node conflicts inside colours", (long long)conflicts);
    free(owner);
    free(seen);
}

static void check_colouring(const ct_assemble_ws *ws, const tpairs *g)
{
    check_colouring_at(ws, g, NULL);
}

/* Pair colouring (block 1): greedy bound ncolour <= max degree + 1 and
 * greedy minimality (each colour c' below a pair's colour is held by an
 * earlier pair sharing a node), with node->pair lists built here. Returns
 * the max degree. */
static ct_idx check_greedy(const ct_assemble_ws *ws, const tpairs *g, int minimality)
{
    cr_assert_eq(ws->block, 1);
    ct_idx nn = g->nnode, np = g->npair;
    ct_idx *cnt = calloc((size_t)nn + 1, sizeof *cnt);
    ct_idx *lst = malloc(5 * (size_t)np * sizeof *lst);
    cr_assert(cnt && lst);
    for (ct_idx k = 0; k < np; k++)
        for (int s = 0; s < 5; s++) {
            int dup = 0;
            for (int r = 0; r < s; r++)
                dup |= g->s[r][k] == g->s[s][k];
            if (!dup)
                cnt[g->s[s][k] + 1]++;
        }
    for (ct_idx n = 0; n < nn; n++)
        cnt[n + 1] += cnt[n];
    ct_idx *cur = malloc((size_t)nn * sizeof *cur);
    cr_assert(cur);
    memcpy(cur, cnt, (size_t)nn * sizeof *cur);
    for (ct_idx k = 0; k < np; k++)
        for (int s = 0; s < 5; s++) {
            int dup = 0;
            for (int r = 0; r < s; r++)
                dup |= g->s[r][k] == g->s[s][k];
            if (!dup)
                lst[cur[g->s[s][k]]++] = k;
        }
    ct_idx maxdeg = 0, maxcol = 0;
    char *have = NULL;
    for (ct_idx k = 0; k < np; k++) {
        ct_idx deg = 0, ck = ws->colour[k];
        if (ck > maxcol)
            maxcol = ck;
        for (int s = 0; s < 5; s++) {
            int dup = 0;
            for (int r = 0; r < s; r++)
                dup |= g->s[r][k] == g->s[s][k];
            if (!dup)
                deg += cnt[g->s[s][k] + 1] - cnt[g->s[s][k]] - 1;
        }
        if (deg > maxdeg)
            maxdeg = deg;
        if (minimality && ck > 0) {
            have = realloc(have, (size_t)ck);
            cr_assert(have);
            memset(have, 0, (size_t)ck);
            for (int s = 0; s < 5; s++) {
                ct_idx n = g->s[s][k];
                for (ct_idx j = cnt[n]; j < cnt[n + 1]; j++)
                    if (lst[j] < k && ws->colour[lst[j]] < ck)
                        have[ws->colour[lst[j]]] = 1;
            }
            for (ct_idx c = 0; c < ck; c++)
                cr_assert(have[c], "pair %d has colour %d but colour %d was free", (int)k,
                          (int)ck, (int)c);
        }
    }
    cr_assert_eq(ws->ncolour, maxcol + 1);
    cr_assert(ws->ncolour <= maxdeg + 1, "%d colours > greedy bound %d + 1", (int)ws->ncolour,
              (int)maxdeg);
    free(have);
    free(cur);
    free(lst);
    free(cnt);
    return maxdeg;
}

/* ---- Tests ---------------------------------------------------------------- */

TestSuite(assemble);

/* Every variant adds the same nodal forces as the plain loop (1 and 2
 * threads; blocks 1, 37 and the default for colouring). */
Test(assemble, variants_match_plain_loop)
{
    tpairs g;
    int ns = ctt_checking() ? 60 : 200;
    tp_alloc(&g, (ct_idx)ns * ns * 4 + 16, 5);
    tp_plate(&g, (int)(ns * 0.8) + 1, ns, 0.8);
    cr_assert(g.npair > 2 * ns * ns);
    check_all_variants(&g, "plate");
    tp_free(&g);
}

/* Same with heavy sharing: a fine secondary grid over a coarse plate (each
 * main node in ~100 pairs, more than 64 colours) and a hub node in every
 * pair, with repeated nodes inside pairs. */
Test(assemble, variants_match_heavy_sharing)
{
    tpairs g;
    int ns = ctt_checking() ? 60 : 160;
    tp_alloc(&g, (ct_idx)ns * ns * 4 + 16, 5);
    tp_plate(&g, (int)(ns * 0.25) + 1, ns, 0.25);
    check_all_variants(&g, "fine-over-coarse plate");
    tp_free(&g);
    ct_idx np = ctt_checking() ? 500 : 3000;
    tp_alloc(&g, np, 5);
    tp_hub(&g, np, 2000);
    check_all_variants(&g, "hub");
    tp_free(&g);
}

/* The default (coloured) and gather variants give the same bits with 1 and
 * 2 threads; so does the pair colouring; threadbuf repeats itself for a
 * fixed thread count. */
Test(assemble, deterministic_bits)
{
    tpairs g;
    int ns = ctt_checking() ? 60 : 200;
    tp_alloc(&g, (ct_idx)ns * ns * 4 + 16, 5);
    tp_plate(&g, (int)(ns * 0.5) + 1, ns, 0.5);
    ct_real *x0, *y0, *z0;
    random_init(g.nnode, &x0, &y0, &z0);
    ct_asm_map map = tp_map(&g);
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    nodef a, b;
    nf_init(&a, g.nnode, NULL, NULL, NULL);
    nf_init(&b, g.nnode, NULL, NULL, NULL);
    const ct_idx blocks[2] = {0, 1};
    for (int i = 0; i < 2; i++) {
        cr_assert_eq(ct_colour_pairs(&ws, &map, g.nnode, blocks[i]), CT_OK);
        ctt_threads(1);
        cr_assert_eq(run_variant(&ws, CT_ASM_COLOUR, &g, &a, x0, y0, z0), CT_OK);
        ctt_threads(2);
        cr_assert_eq(run_variant(&ws, CT_ASM_COLOUR, &g, &b, x0, y0, z0), CT_OK);
        cr_assert(nf_same_bits(&a, &b), "coloured (block %d): 1 and 2 threads differ",
                  (int)blocks[i]);
    }
    cr_assert_eq(ct_gather_prepare(&ws, &map, g.nnode), CT_OK);
    ctt_threads(1);
    cr_assert_eq(run_variant(&ws, CT_ASM_GATHER, &g, &a, x0, y0, z0), CT_OK);
    ctt_threads(2);
    cr_assert_eq(run_variant(&ws, CT_ASM_GATHER, &g, &b, x0, y0, z0), CT_OK);
    cr_assert(nf_same_bits(&a, &b), "gather: 1 and 2 threads differ");
    cr_assert_eq(run_variant(&ws, CT_ASM_THREADBUF, &g, &a, x0, y0, z0), CT_OK);
    cr_assert_eq(run_variant(&ws, CT_ASM_THREADBUF, &g, &b, x0, y0, z0), CT_OK);
    cr_assert(nf_same_bits(&a, &b), "threadbuf: two runs with 2 threads differ");
    /* The fixed-order energy sum. */
    ctt_threads(1);
    double s1 = ct_sum_fixed(g.nnode, x0);
    ctt_threads(2);
    double s2 = ct_sum_fixed(g.nnode, x0);
    cr_assert(memcmp(&s1, &s2, sizeof s1) == 0, "ct_sum_fixed: 1 and 2 threads differ");
    ct_assemble_ws_destroy(&ws);
    nf_free(&a);
    nf_free(&b);
    ct_free(x0);
    ct_free(y0);
    ct_free(z0);
    tp_free(&g);
}

/* 10^5 pairs that all share a hub node: every pair needs its own colour
 * (so the greedy colouring uses exactly npair colours), none conflicts. */
Test(assemble, colouring_hub)
{
    ct_idx np = ctt_checking() ? 5000 : 100000;
    tpairs g;
    tp_alloc(&g, np, 5);
    tp_hub(&g, np, np / 2);
    ct_asm_map map = tp_map(&g);
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    cr_assert_eq(ct_colour_pairs(&ws, &map, g.nnode, 1), CT_OK);
    cr_assert_eq(ws.ncolour, np);
    check_colouring(&ws, &g);
    check_greedy(&ws, &g, 0);
    cr_assert_eq(ct_colour_pairs(&ws, &map, g.nnode, 0), CT_OK);
    cr_assert_eq(ws.ncolour, ws.nblock);
    check_colouring(&ws, &g);
    cr_log_info("hub: %d pairs -> %d pair colours", (int)np, (int)np);
    ct_assemble_ws_destroy(&ws);
    tp_free(&g);
}

/* 10^5 pairs of a fine grid over a coarse plate (each main node in about
 * 100 pairs): valid colouring, greedy minimal, within the greedy bound;
 * blocks valid too. */
Test(assemble, colouring_plate)
{
    int ns = ctt_checking() ? 64 : 215;
    tpairs g;
    tp_alloc(&g, (ct_idx)ns * ns * 4 + 16, 5);
    tp_plate(&g, (int)(ns * 0.25) + 1, ns, 0.25);
    cr_assert(g.npair >= (ctt_checking() ? 9000 : 100000));
    ct_asm_map map = tp_map(&g);
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    cr_assert_eq(ct_colour_pairs(&ws, &map, g.nnode, 1), CT_OK);
    check_colouring(&ws, &g);
    ct_idx deg = check_greedy(&ws, &g, 1);
    cr_assert_eq(ct_colour_degree(&ws, &map, g.nnode), deg);
    cr_assert(ws.ncolour > 64, "the case should need the passes beyond 64 colours");
    ct_idx pc = ws.ncolour;
    cr_assert_eq(ct_colour_pairs(&ws, &map, g.nnode, 0), CT_OK);
    check_colouring(&ws, &g);
    ct_idx bdeg = ct_colour_degree(&ws, &map, g.nnode);
    cr_assert(ws.ncolour <= bdeg + 1);
    cr_log_info("fine-over-coarse plate: %d pairs, %d pair colours (max degree %d), "
                "%d block colours (block %d, max degree %d)",
                (int)g.npair, (int)pc, (int)deg, (int)ws.ncolour, (int)ws.block, (int)bdeg);
    ct_assemble_ws_destroy(&ws);
    tp_free(&g);
}
