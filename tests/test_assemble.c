/*
 * test_assemble.c -- race-free force assembly (suite "assemble").
 *
 * The truths: a plain sequential loop written here (independent of the
 * library), brute-force checks of the colouring (no two blocks of a colour
 * share a node; greedy minimality), Newton's third law and the moment
 * balance of edge-edge pairs, and bit-for-bit comparisons across thread
 * counts for the deterministic variants.
 */
#include <stdint.h>
#include <string.h>

#include "test_util.h"

/* ---- Pair sets ------------------------------------------------------------ */

typedef struct tpairs {
    ct_idx npair, nnode, cap;
    int nslot;
    ct_idx *s[5];
    ct_real *w[5];
    ct_real *f[3];
} tpairs;

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

static void tp_alloc(tpairs *g, ct_idx cap, int nslot)
{
    memset(g, 0, sizeof *g);
    g->cap = cap;
    g->nslot = nslot;
    for (int i = 0; i < 5; i++) {
        g->s[i] = ct_calloc((size_t)cap, sizeof(ct_idx));
        g->w[i] = ct_calloc((size_t)cap, sizeof(ct_real));
        cr_assert(g->s[i] && g->w[i]);
    }
    for (int i = 0; i < 3; i++) {
        g->f[i] = ct_calloc((size_t)cap, sizeof(ct_real));
        cr_assert(g->f[i]);
    }
}

static void tp_free(tpairs *g)
{
    for (int i = 0; i < 5; i++) {
        ct_free(g->s[i]);
        ct_free(g->w[i]);
    }
    for (int i = 0; i < 3; i++)
        ct_free(g->f[i]);
}

static void random_force(tpairs *g, ct_idx k)
{
    g->f[0][k] = (ct_real)(urand() - 0.5);
    g->f[1][k] = (ct_real)(urand() - 0.5);
    g->f[2][k] = (ct_real)(-urand());
}

/* Node-segment pairs of a secondary grid (ns x ns, spacing ratio) over a main
 * plate of nm x nm unit quads (every 7th a triangle, n4 == n3, h4 = 0), in
 * node order: each secondary node pairs with the cells within 0.3 of it.
 * Main nodes are 0 .. (nm+1)^2 - 1, secondary nodes follow. Bilinear or
 * barycentric weights at a random point, summing to 1. */
static void tp_plate(tpairs *g, int nm, int ns, double ratio)
{
    ct_idx nmain = (ct_idx)(nm + 1) * (nm + 1), k = 0;
    const double r = 0.3;
    for (int j = 0; j < ns; j++)
        for (int i = 0; i < ns; i++) {
            double x = (i + 0.5) * ratio, y = (j + 0.5) * ratio;
            int i0 = (int)floor(x - r), i1 = (int)floor(x + r);
            int j0 = (int)floor(y - r), j1 = (int)floor(y + r);
            for (int b = j0; b <= j1; b++)
                for (int a = i0; a <= i1; a++) {
                    if (a < 0 || b < 0 || a >= nm || b >= nm)
                        continue;
                    cr_assert(k < g->cap);
                    ct_idx seg = (ct_idx)b * nm + a, n1 = (ct_idx)b * (nm + 1) + a;
                    int tri = seg % 7 == 3;
                    g->s[0][k] = nmain + (ct_idx)j * ns + i;
                    g->s[1][k] = n1;
                    g->s[2][k] = n1 + 1;
                    g->s[3][k] = n1 + nm + 2;
                    g->s[4][k] = tri ? n1 + nm + 2 : n1 + nm + 1;
                    double u = urand(), v = urand();
                    if (tri) {
                        if (u + v > 1) {
                            u = 1 - u;
                            v = 1 - v;
                        }
                        g->w[1][k] = (ct_real)(1 - u - v);
                        g->w[2][k] = (ct_real)u;
                        g->w[3][k] = (ct_real)v;
                        g->w[4][k] = 0;
                    } else {
                        double s = 2 * u - 1, t = 2 * v - 1;
                        g->w[1][k] = (ct_real)((1 - s) * (1 - t) / 4);
                        g->w[2][k] = (ct_real)((1 + s) * (1 - t) / 4);
                        g->w[3][k] = (ct_real)((1 + s) * (1 + t) / 4);
                        g->w[4][k] = (ct_real)((1 - s) * (1 + t) / 4);
                    }
                    random_force(g, k);
                    k++;
                }
        }
    g->npair = k;
    g->nnode = nmain + (ct_idx)ns * ns;
}

/* Every pair touches the hub node 0 and four random others (repeats
 * allowed, so some pairs name a node twice). */
static void tp_hub(tpairs *g, ct_idx npair, ct_idx nnode)
{
    for (ct_idx k = 0; k < npair; k++) {
        g->s[0][k] = 0;
        double left = 1;
        for (int s = 1; s < 5; s++) {
            g->s[s][k] = 1 + (ct_idx)(urand() * (nnode - 1));
            g->w[s][k] = (ct_real)(s < 4 ? left * urand() : left);
            left -= g->w[s][k];
        }
        random_force(g, k);
    }
    g->npair = npair;
    g->nnode = nnode;
}

static ct_asm_map tp_map(const tpairs *g)
{
    return ct_asm_map_nodeseg(g->npair, g->s[0], g->s[1], g->s[2], g->s[3], g->s[4]);
}

/* ---- The independent reference ------------------------------------------ */

/* Plain loop: node-segment signs (+, -, -, -, -), slot 0 weight 1. scale[n]
 * receives the sum of |initial| and |contributions| over the components. */
static void reference(const tpairs *g, const ct_real *x0, const ct_real *y0,
                      const ct_real *z0, double *rx, double *ry, double *rz, double *scale)
{
    for (ct_idx n = 0; n < g->nnode; n++) {
        rx[n] = x0[n];
        ry[n] = y0[n];
        rz[n] = z0[n];
        scale[n] = fabs(x0[n]) + fabs(y0[n]) + fabs(z0[n]);
    }
    for (ct_idx k = 0; k < g->npair; k++)
        for (int s = 0; s < 5; s++) {
            double w = s == 0 ? 1.0 : -(double)g->w[s][k];
            ct_idx n = g->s[s][k];
            double cx = w * g->f[0][k], cy = w * g->f[1][k], cz = w * g->f[2][k];
            rx[n] += cx;
            ry[n] += cy;
            rz[n] += cz;
            scale[n] += fabs(cx) + fabs(cy) + fabs(cz);
        }
}

typedef struct nodef {
    ct_idx n;
    ct_real *x, *y, *z;
} nodef;

static void nf_init(nodef *f, ct_idx n, const ct_real *x0, const ct_real *y0,
                    const ct_real *z0)
{
    f->n = n;
    f->x = ct_calloc((size_t)n, sizeof(ct_real));
    f->y = ct_calloc((size_t)n, sizeof(ct_real));
    f->z = ct_calloc((size_t)n, sizeof(ct_real));
    cr_assert(f->x && f->y && f->z);
    if (x0) {
        memcpy(f->x, x0, (size_t)n * sizeof(ct_real));
        memcpy(f->y, y0, (size_t)n * sizeof(ct_real));
        memcpy(f->z, z0, (size_t)n * sizeof(ct_real));
    }
}

static void nf_free(nodef *f)
{
    ct_free(f->x);
    ct_free(f->y);
    ct_free(f->z);
}

static int nf_same_bits(const nodef *a, const nodef *b)
{
    size_t sz = (size_t)a->n * sizeof(ct_real);
    return memcmp(a->x, b->x, sz) == 0 && memcmp(a->y, b->y, sz) == 0 &&
           memcmp(a->z, b->z, sz) == 0;
}

/* Largest per-node error relative to the node's force scale. */
static double worst_rel(const nodef *f, const double *rx, const double *ry, const double *rz,
                        const double *scale)
{
    double worst = 0;
    for (ct_idx n = 0; n < f->n; n++) {
        double e = fabs(f->x[n] - rx[n]) + fabs(f->y[n] - ry[n]) + fabs(f->z[n] - rz[n]);
        double r = scale[n] > 0 ? e / scale[n] : e;
        if (!(r <= worst))
            worst = r; /* also catches NaN */
    }
    return worst;
}

static const ct_real *const *weights(const tpairs *g, const ct_real *wbuf[5])
{
    wbuf[0] = NULL;
    for (int s = 1; s < 5; s++)
        wbuf[s] = g->w[s];
    return wbuf;
}

/* Run one variant (prepared in ws) from the initial forces into f. */
static int run_variant(ct_assemble_ws *ws, ct_assemble_variant v, const tpairs *g, nodef *f,
                       const ct_real *x0, const ct_real *y0, const ct_real *z0)
{
    memcpy(f->x, x0, (size_t)g->nnode * sizeof(ct_real));
    memcpy(f->y, y0, (size_t)g->nnode * sizeof(ct_real));
    memcpy(f->z, z0, (size_t)g->nnode * sizeof(ct_real));
    ct_asm_map map = tp_map(g);
    const ct_real *wb[5];
    return ct_assemble(ws, v, &map, weights(g, wb), g->f[0], g->f[1], g->f[2], g->nnode, f->x,
                       f->y, f->z);
}

static void random_init(ct_idx n, ct_real **x0, ct_real **y0, ct_real **z0)
{
    *x0 = ct_calloc((size_t)n, sizeof(ct_real));
    *y0 = ct_calloc((size_t)n, sizeof(ct_real));
    *z0 = ct_calloc((size_t)n, sizeof(ct_real));
    cr_assert(*x0 && *y0 && *z0);
    for (ct_idx i = 0; i < n; i++) {
        (*x0)[i] = (ct_real)(urand() - 0.5);
        (*y0)[i] = (ct_real)(urand() - 0.5);
        (*z0)[i] = (ct_real)(urand() - 0.5);
    }
}

/* Check every variant against the reference with 1 and 2 threads. */
static void check_all_variants(const tpairs *g, const char *what)
{
    ct_real *x0, *y0, *z0;
    random_init(g->nnode, &x0, &y0, &z0);
    double *rx = malloc(4 * (size_t)g->nnode * sizeof(double));
    cr_assert(rx);
    double *ry = rx + g->nnode, *rz = ry + g->nnode, *scale = rz + g->nnode;
    reference(g, x0, y0, z0, rx, ry, rz, scale);
    const double tol = CTT_TOL(1e-12, 1e-5);
    ct_asm_map map = tp_map(g);
    nodef f;
    nf_init(&f, g->nnode, NULL, NULL, NULL);
    ct_assemble_ws ws;
    cr_assert_eq(ct_assemble_ws_init(&ws), CT_OK);
    const ct_idx blocks[3] = {0, 1, 37};
    for (int threads = 1; threads <= 2; threads++) {
        ctt_threads(threads);
        for (int v = 0; v < CT_ASM_NVARIANT; v++) {
            int nb = v == CT_ASM_COLOUR ? 3 : 1;
            for (int b = 0; b < nb; b++) {
                if (v == CT_ASM_COLOUR)
                    cr_assert_eq(ct_colour_pairs(&ws, &map, g->nnode, blocks[b]), CT_OK);
                else
                    cr_assert_eq(ct_assemble_prepare(&ws, v, &map, g->nnode), CT_OK);
                cr_assert_eq(run_variant(&ws, v, g, &f, x0, y0, z0), CT_OK);
                double e = worst_rel(&f, rx, ry, rz, scale);
                cr_expect(e <= tol, "%s: variant %s (block %d), %d threads: error %.3g > %.3g",
                          what, ct_assemble_variant_name(v), (int)blocks[b], threads, e, tol);
            }
        }
    }
    ct_assemble_ws_destroy(&ws);
    nf_free(&f);
    free(rx);
    ct_free(x0);
    ct_free(y0);
    ct_free(z0);
}

/* ---- Colouring checks (brute force, independent of the library) ----------- */

/* No two blocks of one colour share a node. stamp[n] holds (colour, block)
 * of the last block of that colour to touch n, per colour pass. */
static void check_colouring(const ct_assemble_ws *ws, const tpairs *g)
{
    ct_idx B = ws->block, nb = ws->nblock;
    cr_assert_eq(nb, (g->npair + B - 1) / B);
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
            for (ct_idx k = b * B; k < g->npair && k < (b + 1) * B; k++)
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

/* A triangle (n4 == n3, h4 = 0): each node gets exactly its weight times
 * the force, the repeated node n3 exactly -h3 f. */
Test(assemble, triangle_weights)
{
    ct_idx node[1] = {4}, s1[1] = {0}, s2[1] = {1}, s3[1] = {2}, s4[1] = {2};
    ct_real h1[1] = {0.25}, h2[1] = {0.125}, h3[1] = {0.625}, h4[1] = {0};
    ct_real fx[1] = {2}, fy[1] = {-4}, fz[1] = {8};
    ct_asm_map map = ct_asm_map_nodeseg(1, node, s1, s2, s3, s4);
    const ct_real *w[5] = {NULL, h1, h2, h3, h4};
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    const ct_real ex[5][3] = {{-0.5, 1, -2}, {-0.25, 0.5, -1}, {-1.25, 2.5, -5}, {0, 0, 0},
                              {2, -4, 8}};
    for (int v = 0; v < CT_ASM_NVARIANT; v++)
        for (ct_idx blk = 0; blk <= 1; blk++) {
            ct_real X[5] = {0}, Y[5] = {0}, Z[5] = {0};
            if (v == CT_ASM_COLOUR)
                cr_assert_eq(ct_colour_pairs(&ws, &map, 5, blk), CT_OK);
            else
                cr_assert_eq(ct_assemble_prepare(&ws, v, &map, 5), CT_OK);
            cr_assert_eq(ct_assemble(&ws, v, &map, w, fx, fy, fz, 5, X, Y, Z), CT_OK);
            for (int n = 0; n < 5; n++)
                cr_assert(X[n] == ex[n][0] && Y[n] == ex[n][1] && Z[n] == ex[n][2],
                          "variant %s node %d: (%g %g %g)", ct_assemble_variant_name(v), n,
                          (double)X[n], (double)Y[n], (double)Z[n]);
        }
    ct_assemble_ws_destroy(&ws);
}

/* Edge-edge pairs with the force along the line between the contact points:
 * the assembled nodal forces have zero resultant and zero moment. */
Test(assemble, edge_edge_balance)
{
    ct_idx nn = 400, np = ctt_checking() ? 2000 : 20000;
    ct_real *px = ct_calloc((size_t)nn, sizeof(ct_real)), *py = ct_calloc((size_t)nn, sizeof(ct_real)),
            *pz = ct_calloc((size_t)nn, sizeof(ct_real));
    cr_assert(px && py && pz);
    for (ct_idx i = 0; i < nn; i++) {
        px[i] = (ct_real)urand();
        py[i] = (ct_real)urand();
        pz[i] = (ct_real)urand();
    }
    tpairs g;
    tp_alloc(&g, np, 4);
    double fsum = 0;
    for (ct_idx k = 0; k < np; k++) {
        for (int s = 0; s < 4; s++)
            g.s[s][k] = (ct_idx)(urand() * nn);
        double a = urand(), b = urand();
        g.w[0][k] = (ct_real)(1 - a);
        g.w[1][k] = (ct_real)a;
        g.w[2][k] = (ct_real)(1 - b);
        g.w[3][k] = (ct_real)b;
        double pa[3], pb[3];
        const ct_real *P[3] = {px, py, pz};
        for (int d = 0; d < 3; d++) {
            pa[d] = g.w[0][k] * P[d][g.s[0][k]] + g.w[1][k] * P[d][g.s[1][k]];
            pb[d] = g.w[2][k] * P[d][g.s[2][k]] + g.w[3][k] * P[d][g.s[3][k]];
        }
        double mag = urand();
        for (int d = 0; d < 3; d++) {
            g.f[d][k] = (ct_real)(mag * (pb[d] - pa[d]));
            fsum += fabs(g.f[d][k]);
        }
    }
    g.npair = np;
    ct_asm_map map = ct_asm_map_edge(np, g.s[0], g.s[1], g.s[2], g.s[3]);
    const ct_real *w[4] = {g.w[0], g.w[1], g.w[2], g.w[3]};
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    nodef f;
    nf_init(&f, nn, NULL, NULL, NULL);
    ctt_threads(2);
    for (int v = 0; v < CT_ASM_NVARIANT; v++) {
        memset(f.x, 0, (size_t)nn * sizeof(ct_real));
        memset(f.y, 0, (size_t)nn * sizeof(ct_real));
        memset(f.z, 0, (size_t)nn * sizeof(ct_real));
        cr_assert_eq(ct_assemble_prepare(&ws, v, &map, nn), CT_OK);
        cr_assert_eq(ct_assemble(&ws, v, &map, w, g.f[0], g.f[1], g.f[2], nn, f.x, f.y, f.z),
                     CT_OK);
        double F[3] = {0, 0, 0}, M[3] = {0, 0, 0};
        for (ct_idx i = 0; i < nn; i++) {
            F[0] += f.x[i];
            F[1] += f.y[i];
            F[2] += f.z[i];
            M[0] += (double)py[i] * f.z[i] - (double)pz[i] * f.y[i];
            M[1] += (double)pz[i] * f.x[i] - (double)px[i] * f.z[i];
            M[2] += (double)px[i] * f.y[i] - (double)py[i] * f.x[i];
        }
        /* Single precision: the weights and forces are rounded once each, so
         * the moment balance holds to about eps per pair (relative). */
        double tol = CTT_TOL(1e-13, 2e-6) * fsum;
        for (int d = 0; d < 3; d++) {
            cr_expect(fabs(F[d]) <= tol, "%s: force %d = %g", ct_assemble_variant_name(v), d,
                      F[d]);
            cr_expect(fabs(M[d]) <= tol, "%s: moment %d = %g", ct_assemble_variant_name(v), d,
                      M[d]);
        }
    }
    ct_assemble_ws_destroy(&ws);
    nf_free(&f);
    tp_free(&g);
    ct_free(px);
    ct_free(py);
    ct_free(pz);
}

/* Random node-segment pairs over random nodes: the total force over all
 * nodes is zero to round-off (Newton's third law), for every variant. */
Test(assemble, newton_third_law)
{
    ct_idx nn = 5000, np = ctt_checking() ? 5000 : 50000;
    tpairs g;
    tp_alloc(&g, np, 5);
    double fsum = 0;
    for (ct_idx k = 0; k < np; k++) {
        double left = 1;
        for (int s = 0; s < 5; s++)
            g.s[s][k] = (ct_idx)(urand() * nn);
        for (int s = 1; s < 5; s++) {
            g.w[s][k] = (ct_real)(s < 4 ? left * urand() : left);
            left -= g.w[s][k];
        }
        random_force(&g, k);
        fsum += fabs(g.f[0][k]) + fabs(g.f[1][k]) + fabs(g.f[2][k]);
    }
    g.npair = np;
    g.nnode = nn;
    ct_asm_map map = tp_map(&g);
    const ct_real *wb[5];
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    nodef f;
    nf_init(&f, nn, NULL, NULL, NULL);
    ctt_threads(2);
    for (int v = 0; v < CT_ASM_NVARIANT; v++) {
        memset(f.x, 0, (size_t)nn * sizeof(ct_real));
        memset(f.y, 0, (size_t)nn * sizeof(ct_real));
        memset(f.z, 0, (size_t)nn * sizeof(ct_real));
        cr_assert_eq(ct_assemble_prepare(&ws, v, &map, nn), CT_OK);
        cr_assert_eq(ct_assemble(&ws, v, &map, weights(&g, wb), g.f[0], g.f[1], g.f[2], nn,
                                 f.x, f.y, f.z),
                     CT_OK);
        double F[3] = {0, 0, 0};
        for (ct_idx i = 0; i < nn; i++) {
            F[0] += f.x[i];
            F[1] += f.y[i];
            F[2] += f.z[i];
        }
        /* The weights were rounded so that they sum to 1 up to one rounding
         * per weight; single precision stores them to 6e-8 relative. */
        double tol = CTT_TOL(1e-13, 1e-6) * fsum;
        for (int d = 0; d < 3; d++)
            cr_expect(fabs(F[d]) <= tol, "%s: total force %d = %g (tol %g)",
                      ct_assemble_variant_name(v), d, F[d], tol);
    }
    ct_assemble_ws_destroy(&ws);
    nf_free(&f);
    tp_free(&g);
}

/* One workspace through growing and shrinking pair counts: results stay
 * right, and once it has held the largest case no call makes it grow. */
Test(assemble, workspace_reuse)
{
    const int sizes[6] = {30, 120, 20, 80, 120, 50};
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    size_t mem_after_largest = 0;
    ctt_threads(2);
    for (int i = 0; i < 6; i++) {
        int ns = ctt_checking() ? sizes[i] / 2 : sizes[i];
        tpairs g;
        tp_alloc(&g, (ct_idx)ns * ns * 4 + 16, 5);
        tp_plate(&g, (int)(ns * 0.8) + 1, ns, 0.8);
        ct_real *x0, *y0, *z0;
        random_init(g.nnode, &x0, &y0, &z0);
        double *rx = malloc(4 * (size_t)g.nnode * sizeof(double));
        cr_assert(rx);
        double *ry = rx + g.nnode, *rz = ry + g.nnode, *scale = rz + g.nnode;
        reference(&g, x0, y0, z0, rx, ry, rz, scale);
        ct_asm_map map = tp_map(&g);
        nodef f;
        nf_init(&f, g.nnode, NULL, NULL, NULL);
        for (int v = 0; v < CT_ASM_NVARIANT; v++) {
            cr_assert_eq(ct_assemble_prepare(&ws, v, &map, g.nnode), CT_OK);
            for (int rep = 0; rep < 2; rep++) {
                cr_assert_eq(run_variant(&ws, v, &g, &f, x0, y0, z0), CT_OK);
                double e = worst_rel(&f, rx, ry, rz, scale);
                cr_expect(e <= CTT_TOL(1e-12, 1e-5), "size %d variant %s: error %g", ns,
                          ct_assemble_variant_name(v), e);
            }
        }
        if (i == 1)
            mem_after_largest = ct_assemble_ws_memory(&ws);
        if (i > 1)
            cr_assert_eq(ct_assemble_ws_memory(&ws), mem_after_largest,
                         "the workspace grew at size %d", ns);
        nf_free(&f);
        free(rx);
        ct_free(x0);
        ct_free(y0);
        ct_free(z0);
        tp_free(&g);
    }
    cr_assert(mem_after_largest > 0);
    ct_assemble_ws_destroy(&ws);
}

/* Bad input: clear error codes, nothing written. */
Test(assemble, errors)
{
    ct_idx node[2] = {0, 1}, a[2] = {2, 3}, b[2] = {3, 9};
    ct_real h[2] = {1, 1}, f[2] = {1, 1};
    ct_asm_map map = ct_asm_map_nodeseg(2, node, a, b, b, b);
    const ct_real *w[5] = {NULL, h, h, h, h};
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    ct_real X[10] = {0}, Y[10] = {0}, Z[10] = {0};
    /* Node 9 is outside 5 nodes. */
    cr_assert_eq(ct_colour_pairs(&ws, &map, 5, 0), CT_ERR_RANGE);
    cr_assert_eq(ct_gather_prepare(&ws, &map, 5), CT_ERR_RANGE);
    /* Not prepared: refused. */
    cr_assert_eq(ct_assemble(&ws, CT_ASM_COLOUR, &map, w, f, f, f, 10, X, Y, Z), CT_ERR_ARG);
    cr_assert_eq(ct_assemble(&ws, CT_ASM_GATHER, &map, w, f, f, f, 10, X, Y, Z), CT_ERR_ARG);
    /* Prepared for 10 nodes, called with another count: refused. */
    cr_assert_eq(ct_colour_pairs(&ws, &map, 10, 0), CT_OK);
    cr_assert_eq(ct_assemble(&ws, CT_ASM_COLOUR, &map, w, f, f, f, 9, X, Y, Z), CT_ERR_ARG);
    for (int i = 0; i < 10; i++)
        cr_assert(X[i] == 0 && Y[i] == 0 && Z[i] == 0);
    /* Impossible maps. */
    ct_asm_map bad = map;
    bad.nslot = 6;
    cr_assert_eq(ct_colour_pairs(&ws, &bad, 10, 0), CT_ERR_ARG);
    bad = map;
    bad.slot[2] = NULL;
    cr_assert_eq(ct_assemble_serial(&bad, w, f, f, f, 10, X, Y, Z), CT_ERR_ARG);
    bad = map;
    bad.npair = -1;
    cr_assert_eq(ct_assemble_atomic(&bad, w, f, f, f, 10, X, Y, Z), CT_ERR_ARG);
    cr_assert_eq(ct_assemble(&ws, (ct_assemble_variant)17, &map, w, f, f, f, 10, X, Y, Z),
                 CT_ERR_ARG);
    /* Names round-trip. */
    for (int v = 0; v < CT_ASM_NVARIANT; v++)
        cr_assert_eq(ct_assemble_variant_from_name(ct_assemble_variant_name(v)), v);
    cr_assert_eq(ct_assemble_variant_from_name("nope"), -1);
    ct_assemble_ws_destroy(&ws);
}

/* Segment slots are the segment's nodes; a bad segment index is reported. */
Test(assemble, seg_slots)
{
    ct_idx n1[3] = {0, 4, 8}, n2[3] = {1, 5, 9}, n3[3] = {2, 6, 10}, n4[3] = {3, 6, 11};
    ct_idx seg[4] = {2, 0, 1, 2}, s1[4], s2[4], s3[4], s4[4];
    cr_assert_eq(ct_asm_seg_slots(4, seg, 3, n1, n2, n3, n4, s1, s2, s3, s4), CT_OK);
    for (int k = 0; k < 4; k++)
        cr_assert(s1[k] == n1[seg[k]] && s2[k] == n2[seg[k]] && s3[k] == n3[seg[k]] &&
                  s4[k] == n4[seg[k]]);
    seg[3] = 3;
    cr_assert_eq(ct_asm_seg_slots(4, seg, 3, n1, n2, n3, n4, s1, s2, s3, s4), CT_ERR_RANGE);
}

/* The fixed-order sum agrees with a compensated sum. */
Test(assemble, sum_fixed)
{
    int64_t n = 1000003;
    ct_real *v = ct_calloc((size_t)n, sizeof(ct_real));
    cr_assert(v);
    double s = 0, c = 0, sa = 0;
    for (int64_t i = 0; i < n; i++) {
        v[i] = (ct_real)(urand() - 0.3);
        double y = (double)v[i] - c, t = s + y;
        c = (t - s) - y;
        s = t;
        sa += fabs((double)v[i]);
    }
    double got = ct_sum_fixed(n, v);
    cr_assert(fabs(got - s) <= 1e-12 * sa, "sum %.17g vs %.17g", got, s);
    cr_assert(ct_sum_fixed(0, v) == 0.0);
    ct_free(v);
}
