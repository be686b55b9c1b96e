/*
 * test_assemble.h -- what the assembly tests (test_assemble.c: the variants
 * and the colouring; test_assemble_balance.c: balance laws, weights, reuse
 * and bad input) share: pair sets, the plain-loop reference written here
 * independently of the library, nodal force sets and the variant runner.
 */
#ifndef TEST_ASSEMBLE_H
#define TEST_ASSEMBLE_H

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
static inline double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

static inline void tp_alloc(tpairs *g, ct_idx cap, int nslot)
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

static inline void tp_free(tpairs *g)
{
    for (int i = 0; i < 5; i++) {
        ct_free(g->s[i]);
        ct_free(g->w[i]);
    }
    for (int i = 0; i < 3; i++)
        ct_free(g->f[i]);
}

/* A random pair force. One pair in four has none (as a contact list's
 * candidates out of contact; some with negative zeros), which the serial
 * and coloured loops skip; one in ten has a zero x component only, which
 * they must not skip. */
static inline void random_force(tpairs *g, ct_idx k)
{
    double u = urand();
    g->f[0][k] = (ct_real)(urand() - 0.5);
    g->f[1][k] = (ct_real)(urand() - 0.5);
    g->f[2][k] = (ct_real)(-urand());
    if (u < 0.25) {
        g->f[0][k] = u < 0.1 ? (ct_real)-0.0 : 0;
        g->f[1][k] = 0;
        g->f[2][k] = u < 0.05 ? (ct_real)-0.0 : 0;
    } else if (u < 0.35) {
        g->f[0][k] = 0;
    }
}

/* Node-segment pairs of a secondary grid (ns x ns, spacing ratio) over a main
 * plate of nm x nm unit quads (every 7th a triangle, n4 == n3, h4 = 0), in
 * node order: each secondary node pairs with the cells within 0.3 of it.
 * Main nodes are 0 .. (nm+1)^2 - 1, secondary nodes follow. Bilinear or
 * barycentric weights at a random point, summing to 1. */
static inline void tp_plate(tpairs *g, int nm, int ns, double ratio)
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
static inline void tp_hub(tpairs *g, ct_idx npair, ct_idx nnode)
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

static inline ct_asm_map tp_map(const tpairs *g)
{
    return ct_asm_map_nodeseg(g->npair, g->s[0], g->s[1], g->s[2], g->s[3], g->s[4]);
}

/* The brute-force colouring check of test_assemble.c (no two blocks of a
 * colour share a node); bstart: the blocks' starts when ws->block is 0. */
void check_colouring_at(const ct_assemble_ws *ws, const tpairs *g, const ct_idx *bstart);

/* ---- The independent reference ------------------------------------------ */

/* Plain loop: node-segment signs (+, -, -, -, -), slot 0 weight 1. scale[n]
 * receives the sum of |initial| and |contributions| over the components. */
static inline void reference(const tpairs *g, const ct_real *x0, const ct_real *y0,
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

static inline void nf_init(nodef *f, ct_idx n, const ct_real *x0, const ct_real *y0,
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

static inline void nf_free(nodef *f)
{
    ct_free(f->x);
    ct_free(f->y);
    ct_free(f->z);
}

static inline int nf_same_bits(const nodef *a, const nodef *b)
{
    size_t sz = (size_t)a->n * sizeof(ct_real);
    return memcmp(a->x, b->x, sz) == 0 && memcmp(a->y, b->y, sz) == 0 &&
           memcmp(a->z, b->z, sz) == 0;
}

/* Largest per-node error relative to the node's force scale. */
static inline double worst_rel(const nodef *f, const double *rx, const double *ry,
                               const double *rz, const double *scale)
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

static inline const ct_real *const *weights(const tpairs *g, const ct_real *wbuf[5])
{
    wbuf[0] = NULL;
    for (int s = 1; s < 5; s++)
        wbuf[s] = g->w[s];
    return wbuf;
}

/* Run one variant (prepared in ws) from the initial forces into f. */
static inline int run_variant(ct_assemble_ws *ws, ct_assemble_variant v, const tpairs *g,
                              nodef *f, const ct_real *x0, const ct_real *y0, const ct_real *z0)
{
    memcpy(f->x, x0, (size_t)g->nnode * sizeof(ct_real));
    memcpy(f->y, y0, (size_t)g->nnode * sizeof(ct_real));
    memcpy(f->z, z0, (size_t)g->nnode * sizeof(ct_real));
    ct_asm_map map = tp_map(g);
    const ct_real *wb[5];
    return ct_assemble(ws, v, &map, weights(g, wb), g->f[0], g->f[1], g->f[2], g->nnode, f->x,
                       f->y, f->z);
}

/* Prepare variant v for map, zero f, and assemble the pair forces (fx, fy,
 * fz with weights w) into it; both calls must succeed. */
static inline void assemble_zeroed(ct_assemble_ws *ws, int v, const ct_asm_map *map,
                                   const ct_real *const w[], const ct_real *fx,
                                   const ct_real *fy, const ct_real *fz, nodef *f)
{
    memset(f->x, 0, (size_t)f->n * sizeof(ct_real));
    memset(f->y, 0, (size_t)f->n * sizeof(ct_real));
    memset(f->z, 0, (size_t)f->n * sizeof(ct_real));
    cr_assert_eq(ct_assemble_prepare(ws, (ct_assemble_variant)v, map, f->n), CT_OK);
    cr_assert_eq(ct_assemble(ws, (ct_assemble_variant)v, map, w, fx, fy, fz, f->n, f->x, f->y,
                             f->z),
                 CT_OK);
}

static inline void random_init(ct_idx n, ct_real **x0, ct_real **y0, ct_real **z0)
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
static inline void check_all_variants(const tpairs *g, const char *what)
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

#endif
