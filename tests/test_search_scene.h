/*
 * test_search_scene.h -- a hand-built search scene for the search tests
 * (test_search_bsp.c, test_search_bucket*.c, test_search_topo.c,
 * test_search_families.c): nodes, main segments and secondary nodes added
 * one by one into fixed-capacity arrays, grids and plates of them, the
 * search input over them, and running and comparing searches.
 */
#ifndef TEST_SCENE_H
#define TEST_SCENE_H

#include <string.h>

#include "test_util.h"

typedef struct ctt_scene {
    ct_idx nn, ns, nsec, capn, caps;
    ct_real *x, *y, *z;
    ct_idx *n1, *n2, *n3, *n4, *sec;
} ctt_scene;

/* An empty scene with room for capn nodes (and secondary nodes) and caps
 * segments. */
static inline void ctt_scene_init(ctt_scene *s, ct_idx capn, ct_idx caps)
{
    memset(s, 0, sizeof *s);
    s->capn = capn;
    s->caps = caps;
    s->x = calloc((size_t)capn + 1, sizeof(ct_real));
    s->y = calloc((size_t)capn + 1, sizeof(ct_real));
    s->z = calloc((size_t)capn + 1, sizeof(ct_real));
    s->sec = calloc((size_t)capn + 1, sizeof(ct_idx));
    s->n1 = calloc((size_t)caps + 1, sizeof(ct_idx));
    s->n2 = calloc((size_t)caps + 1, sizeof(ct_idx));
    s->n3 = calloc((size_t)caps + 1, sizeof(ct_idx));
    s->n4 = calloc((size_t)caps + 1, sizeof(ct_idx));
}

static inline void ctt_scene_free(ctt_scene *s)
{
    free(s->x), free(s->y), free(s->z), free(s->sec);
    free(s->n1), free(s->n2), free(s->n3), free(s->n4);
}

/* A node at (x, y, z); returns its number. */
static inline ct_idx ctt_scene_node(ctt_scene *s, double x, double y, double z)
{
    cr_assert_lt(s->nn, s->capn);
    s->x[s->nn] = (ct_real)x, s->y[s->nn] = (ct_real)y, s->z[s->nn] = (ct_real)z;
    return s->nn++;
}

/* A main segment (a triangle repeats its third node: c == d). */
static inline void ctt_scene_seg(ctt_scene *s, ct_idx a, ct_idx b, ct_idx c, ct_idx d)
{
    cr_assert_lt(s->ns, s->caps);
    s->n1[s->ns] = a, s->n2[s->ns] = b, s->n3[s->ns] = c, s->n4[s->ns] = d;
    s->ns++;
}

/* Node `node` becomes the next secondary node. */
static inline void ctt_scene_sec(ctt_scene *s, ct_idx node) { s->sec[s->nsec++] = node; }

/* Grid of nodes x = xs[i], y = ys[j] at height z; segments (quads, or two
 * triangles per cell) when segs. Returns the first node. */
static inline ct_idx ctt_scene_grid(ctt_scene *s, int nx, int ny, const double *xs,
                                    const double *ys, double z, int segs, int tri)
{
    ct_idx base = s->nn;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            ctt_scene_node(s, xs[i], ys[j], z);
    for (int j = 0; segs && j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            ct_idx a = base + j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
            if (tri) {
                ctt_scene_seg(s, a, b, c, c);
                ctt_scene_seg(s, a, c, d, d);
            } else {
                ctt_scene_seg(s, a, b, c, d);
            }
        }
    return base;
}

/* A plate: the grid at spacing h from (ox, oy). */
static inline ct_idx ctt_scene_plate(ctt_scene *s, int nx, int ny, double ox, double oy,
                                     double z, double h, int segs, int tri)
{
    double *xs = malloc(sizeof(double) * (size_t)nx), *ys = malloc(sizeof(double) * (size_t)ny);
    for (int i = 0; i < nx; i++)
        xs[i] = ox + h * i;
    for (int j = 0; j < ny; j++)
        ys[j] = oy + h * j;
    ct_idx b = ctt_scene_grid(s, nx, ny, xs, ys, z, segs, tri);
    free(xs);
    free(ys);
    return b;
}

/* The search input over the scene (hull filter). */
static inline ct_search_input ctt_scene_input(const ctt_scene *s, double gap, double margin,
                                              int self)
{
    ct_search_input in;
    memset(&in, 0, sizeof in);
    in.nnode = s->nn;
    in.x = s->x, in.y = s->y, in.z = s->z;
    in.nsec = s->nsec, in.sec = s->sec;
    in.nseg = s->ns;
    in.n1 = s->n1, in.n2 = s->n2, in.n3 = s->n3, in.n4 = s->n4;
    in.gap = (ct_real)gap, in.margin = (ct_real)margin;
    in.self = self;
    in.filter = CT_FILTER_HULL;
    return in;
}

/* One search with parameters p on in into out; asserts that it succeeds. */
static inline void ctt_search_with(const ct_search_params *p, const ct_search_input *in,
                                   ct_pairs *out)
{
    ct_search *s;
    cr_assert_eq(ct_search_init(&s, p), CT_OK);
    int rc = ct_search_run(s, in, out);
    cr_assert_eq(rc, CT_OK, "%s search failed: %s", ct_search_algo_name(p->algo),
                 ct_strerror(rc));
    ct_search_destroy(s);
}

/* Search `a` with its default parameters. */
static inline void ctt_search(ct_search_algo a, const ct_search_input *in, ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(a);
    ctt_search_with(&p, in, out);
}

/* Search `a` with leaf size `leaf` and box threshold `minbox` (the bsp
 * search's parameters). */
static inline void ctt_search_tuned(ct_search_algo a, int leaf, double minbox,
                                    const ct_search_input *in, ct_pairs *out)
{
    ct_search_params p = ct_search_default_params(a);
    p.leaf_size = leaf;
    p.min_box = minbox;
    ctt_search_with(&p, in, out);
}

/* 1 when both pair lists are the same, byte for byte. */
static inline int ctt_same_pairs(const ct_pairs *a, const ct_pairs *b)
{
    return a->n == b->n && memcmp(a->node, b->node, sizeof(ct_idx) * (size_t)a->n) == 0 &&
           memcmp(a->seg, b->seg, sizeof(ct_idx) * (size_t)a->n) == 0;
}

#endif /* TEST_SCENE_H */
