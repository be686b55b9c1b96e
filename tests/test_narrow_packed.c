/*
 * test_narrow_packed.c -- packed node coordinates (suite "narrow_packed"):
 * ct_coords_pack writes (x, y, z, 0) per node, and the _packed entry points
 * of the node-segment narrow phase give every output array, byte for byte,
 * as the unpacked ones on the same coordinates: plates of quadrangles and
 * of triangles, a crumpled and a folded sheet, every quadrangle method,
 * one- and two-sided, per-node and per-segment gaps, 1 and 2 threads, a
 * NaN and an infinite coordinate among them; the selection form
 * (ct_narrow_node_slots_packed) likewise. Bad arguments give CT_ERR_ARG.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "test_geo.h"
#include "test_util.h"

#include "meshgen.h"

/* Different bytes before each call, so a field left unwritten shows. */
static void pk_scribble(ctt_geo *o, ct_idx n, unsigned char c)
{
    for (int i = 0; i < CTT_GEO_NF; i++)
        memset(o->f[i], c, (size_t)n * sizeof(ct_real));
    memset(o->g.flag, c, (size_t)n);
}

static void pk_same(const ctt_geo *a, const ctt_geo *b, ct_idx n, const char *what)
{
    for (int i = 0; i < CTT_GEO_NF; i++)
        for (ct_idx k = 0; k < n; k++)
            cr_assert(memcmp(&a->f[i][k], &b->f[i][k], sizeof(ct_real)) == 0,
                      "%s: pair %d field %d: packed %a, unpacked %a", what, (int)k, i,
                      (double)b->f[i][k], (double)a->f[i][k]);
    cr_assert(memcmp(a->g.flag, b->g.flag, (size_t)n) == 0, "%s: flags differ", what);
}

/* One case: the family's pairs (bucket search, gap 0.35 h, margin 0.15 h),
 * unpacked against packed. Returns the active pairs seen. */
static int64_t pk_case(const char *family, int64_t nodes)
{
    ctd_case c;
    ct_diag diag;
    memset(&c, 0, sizeof c);
    cr_assert_eq(ctd_case_make(&c, family, nodes, CTD_NUM_NATURAL, 3, &diag), CT_OK, "%s",
                 family);
    const double h = c.h_mean;
    ct_search_input in;
    ctd_case_input(&c, (ct_real)(0.35 * h), (ct_real)(0.15 * h), &in);
    ct_search_params sp = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *s = NULL;
    ct_pairs pr;
    cr_assert_eq(ct_search_init(&s, &sp), CT_OK);
    cr_assert_eq(ct_pairs_init(&pr, 0), CT_OK);
    cr_assert_eq(ct_search_run(s, &in, &pr), CT_OK);
    ct_search_destroy(s);
    const ct_idx np = pr.n, nn = in.nnode, ns = in.nseg;
    cr_assert_gt(np, 200, "%s: %d pairs", family, (int)np);
    /* Own copies of the coordinates: a NaN and an Inf node among them. */
    ct_real *x = ct_calloc((size_t)nn, sizeof(ct_real));
    ct_real *y = ct_calloc((size_t)nn, sizeof(ct_real));
    ct_real *z = ct_calloc((size_t)nn, sizeof(ct_real));
    ct_real *w = ct_calloc(4 * (size_t)nn, sizeof(ct_real));
    ct_real *gn = ct_calloc((size_t)nn, sizeof(ct_real));
    ct_real *gs = ct_calloc((size_t)ns, sizeof(ct_real));
    cr_assert(x && y && z && w && gn && gs);
    memcpy(x, in.x, (size_t)nn * sizeof(ct_real));
    memcpy(y, in.y, (size_t)nn * sizeof(ct_real));
    memcpy(z, in.z, (size_t)nn * sizeof(ct_real));
    x[pr.node[np / 3]] = (ct_real)NAN;
    z[in.n2[pr.seg[np / 2]]] = (ct_real)INFINITY;
    for (ct_idx i = 0; i < nn; i++)
        gn[i] = (ct_real)(h * (0.1 + 0.3 * (double)(i % 7) / 7));
    for (ct_idx i = 0; i < ns; i++)
        gs[i] = (ct_real)(h * 0.05 * (double)(i % 5));
    /* Poison the fourth value: it must not be read. */
    for (ct_idx i = 0; i < nn; i++)
        w[4 * i + 3] = (ct_real)NAN;
    cr_assert_eq(ct_coords_pack(nn, x, y, z, w), CT_OK);
    for (ct_idx i = 0; i < nn; i++)
        cr_assert(memcmp(&w[4 * i], &x[i], sizeof(ct_real)) == 0 &&
                      memcmp(&w[4 * i + 1], &y[i], sizeof(ct_real)) == 0 &&
                      memcmp(&w[4 * i + 2], &z[i], sizeof(ct_real)) == 0 && w[4 * i + 3] == 0,
                  "%s: node %d packed wrong", family, (int)i);
    for (ct_idx i = 0; i < nn; i++) /* again: the kernels ignore it */
        w[4 * i + 3] = (ct_real)NAN;
    /* The selection form: every other pair, backwards, slots per pair. */
    const ct_idx nsel = np / 2;
    ct_idx *sel = ct_calloc((size_t)nsel + 1, sizeof(ct_idx)), *sl[4];
    cr_assert_not_null(sel);
    for (int d = 0; d < 4; d++) {
        sl[d] = ct_calloc((size_t)np, sizeof(ct_idx));
        cr_assert_not_null(sl[d]);
    }
    const ct_idx *nd[4] = {in.n1, in.n2, in.n3, in.n4};
    for (ct_idx k = 0; k < np; k++)
        for (int d = 0; d < 4; d++)
            sl[d][k] = nd[d][pr.seg[k]];
    for (ct_idx j = 0; j < nsel; j++)
        sel[j] = np - 1 - 2 * j;
    ctt_geo a, b;
    ctt_geo_init(&a, np);
    ctt_geo_init(&b, np);
    int64_t active = 0;
    char what[160];
    for (int m = 0; m < CT_QUAD_NMETHOD; m++)
        for (int two = 0; two < 2; two++)
            for (int gaps = 0; gaps < 2; gaps++)
                for (int thr = 1; thr <= 2; thr++) {
                    ctt_threads(thr);
                    snprintf(what, sizeof what, "%s %s two %d gaps %d threads %d", family,
                             ct_quad_method_name((ct_quad_method)m), two, gaps, thr);
                    const ct_real *g1 = gaps ? gn : NULL, *g2 = gaps ? gs : NULL;
                    const ct_real gap = (ct_real)(0.35 * h), cs = (ct_real)(gaps ? 0.3 * h : 0);
                    ct_narrow_stats sa, sb;
                    pk_scribble(&a, np, 0x5a);
                    pk_scribble(&b, np, 0xa5);
                    cr_assert_eq(ct_narrow_node_segment(np, pr.node, pr.seg, in.n1, in.n2, in.n3,
                                                        in.n4, x, y, z, g1, g2, gap, cs, 0,
                                                        (ct_quad_method)m, two, &a.g, &sa),
                                 CT_OK);
                    cr_assert_eq(ct_narrow_node_segment_packed(
                                     np, pr.node, pr.seg, in.n1, in.n2, in.n3, in.n4, w, g1, g2,
                                     gap, cs, 0, (ct_quad_method)m, two, &b.g, &sb),
                                 CT_OK);
                    pk_same(&a, &b, np, what);
                    cr_assert(memcmp(&sa, &sb, sizeof sa) == 0, "%s: stats differ", what);
                    cr_assert_gt(sa.nonfinite, 0, "%s: no non-finite pair", what);
                    active += sa.active;
                    if (gaps)
                        continue;
                    snprintf(what, sizeof what, "%s slots %s two %d threads %d", family,
                             ct_quad_method_name((ct_quad_method)m), two, thr);
                    pk_scribble(&a, nsel, 0x5a);
                    pk_scribble(&b, nsel, 0xa5);
                    cr_assert_eq(ct_narrow_node_slots(nsel, sel, pr.node, sl[0], sl[1], sl[2],
                                                      sl[3], x, y, z, gap, (ct_quad_method)m,
                                                      two, &a.g, &sa),
                                 CT_OK);
                    cr_assert_eq(ct_narrow_node_slots_packed(nsel, sel, pr.node, sl[0], sl[1],
                                                             sl[2], sl[3], w, gap,
                                                             (ct_quad_method)m, two, &b.g, &sb),
                                 CT_OK);
                    pk_same(&a, &b, nsel, what);
                    cr_assert(memcmp(&sa, &sb, sizeof sa) == 0, "%s: stats differ", what);
                }
    ctt_geo_free(&a);
    ctt_geo_free(&b);
    for (int d = 0; d < 4; d++)
        ct_free(sl[d]);
    ct_free(sel);
    ct_free(x);
    ct_free(y);
    ct_free(z);
    ct_free(w);
    ct_free(gn);
    ct_free(gs);
    ct_pairs_destroy(&pr);
    ctd_case_destroy(&c);
    return active;
}

Test(narrow_packed, plates_quads)
{
    cr_assert_gt(pk_case("plates", ctt_checking() ? 1500 : 6000), 0);
}

Test(narrow_packed, plates_triangles)
{
    cr_assert_gt(pk_case("plates-tri", ctt_checking() ? 1500 : 6000), 0);
}

Test(narrow_packed, crumpled_sheet)
{
    cr_assert_gt(pk_case("crumpled", ctt_checking() ? 1500 : 6000), 0);
}

Test(narrow_packed, folded_sheet)
{
    cr_assert_gt(pk_case("folded", ctt_checking() ? 1500 : 6000), 0);
}

/* The pack itself on a team (above its threshold) and alone. */
Test(narrow_packed, pack_values)
{
    const ct_idx n = 100003;
    ct_real *x = ct_calloc((size_t)n, sizeof(ct_real)), *y = ct_calloc((size_t)n, sizeof(ct_real));
    ct_real *z = ct_calloc((size_t)n, sizeof(ct_real));
    ct_real *w = ct_calloc(4 * (size_t)n, sizeof(ct_real));
    cr_assert(x && y && z && w);
    for (ct_idx i = 0; i < n; i++) {
        x[i] = (ct_real)i;
        y[i] = (ct_real)(-0.5 * (double)i);
        z[i] = (ct_real)(1 + i % 11);
    }
    for (int thr = 1; thr <= 2; thr++) {
        ctt_threads(thr);
        memset(w, 0xff, 4 * (size_t)n * sizeof(ct_real));
        cr_assert_eq(ct_coords_pack(n, x, y, z, w), CT_OK);
        for (ct_idx i = 0; i < n; i++)
            cr_assert(w[4 * i] == x[i] && w[4 * i + 1] == y[i] && w[4 * i + 2] == z[i] &&
                          w[4 * i + 3] == 0,
                      "threads %d node %d", thr, (int)i);
    }
    ct_free(x);
    ct_free(y);
    ct_free(z);
    ct_free(w);
}

Test(narrow_packed, bad_arguments)
{
    ctt_geo o;
    ctt_geo_init(&o, 2);
    ct_real *w = ct_calloc(16, sizeof(ct_real));
    cr_assert_not_null(w);
    ct_real v[4] = {0, 0, 0, 0};
    ct_idx i = 0;
    /* The pack. */
    cr_assert_eq(ct_coords_pack(-1, v, v, v, w), CT_ERR_ARG);
    cr_assert_eq(ct_coords_pack(1, NULL, v, v, w), CT_ERR_ARG);
    cr_assert_eq(ct_coords_pack(1, v, NULL, v, w), CT_ERR_ARG);
    cr_assert_eq(ct_coords_pack(1, v, v, NULL, w), CT_ERR_ARG);
    cr_assert_eq(ct_coords_pack(1, v, v, v, NULL), CT_ERR_ARG);
    cr_assert_eq(ct_coords_pack(1, v, v, v, w + 1), CT_ERR_ARG); /* misaligned */
    cr_assert_eq(ct_coords_pack(1, v, v, v, w + 2), CT_ERR_ARG);
    cr_assert_eq(ct_coords_pack(0, NULL, NULL, NULL, NULL), CT_OK);
    cr_assert_eq(ct_coords_pack(1, v, v, v, w), CT_OK);
    /* The narrow phase: one pair of node 0 and the segment (0, 0, 0, 0). */
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, &i, &i, &i, &i, &i, w, NULL, NULL, 0, 0,
                                               0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_OK);
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, &i, &i, &i, &i, &i, NULL, NULL, NULL, 0, 0,
                                               0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, &i, &i, &i, &i, &i, w + 1, NULL, NULL, 0,
                                               0, 0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, &i, &i, &i, &i, &i, w + 2, NULL, NULL, 0,
                                               0, 0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(-1, &i, &i, &i, &i, &i, &i, w, NULL, NULL, 0, 0,
                                               0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, NULL, &i, &i, &i, &i, w, NULL, NULL, 0, 0,
                                               0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, &i, &i, &i, &i, &i, w, NULL, NULL, -1, 0,
                                               0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, &i, &i, &i, &i, &i, w, NULL, NULL, 0, 0,
                                               0, CT_QUAD_NMETHOD, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(1, &i, &i, &i, &i, &i, &i, w, NULL, NULL, 0, 0,
                                               0, CT_QUAD_4TRI, 0, NULL, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_segment_packed(0, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                                               NULL, 0, 0, 0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_OK);
    cr_assert_eq(ct_narrow_node_slots_packed(1, &i, &i, &i, &i, &i, &i, w, 0, CT_QUAD_4TRI, 0,
                                             &o.g, NULL),
                 CT_OK);
    cr_assert_eq(ct_narrow_node_slots_packed(1, &i, &i, &i, &i, &i, &i, NULL, 0, CT_QUAD_4TRI, 0,
                                             &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_slots_packed(1, &i, &i, &i, &i, &i, &i, w + 1, 0, CT_QUAD_4TRI,
                                             0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_slots_packed(1, NULL, &i, &i, &i, &i, &i, w, 0, CT_QUAD_4TRI, 0,
                                             &o.g, NULL),
                 CT_ERR_ARG);
    /* The unpacked entry points still ask for x, y and z. */
    cr_assert_eq(ct_narrow_node_segment(1, &i, &i, &i, &i, &i, &i, v, v, NULL, NULL, NULL, 0, 0,
                                        0, CT_QUAD_4TRI, 0, &o.g, NULL),
                 CT_ERR_ARG);
    cr_assert_eq(ct_narrow_node_slots(1, &i, &i, &i, &i, &i, &i, v, NULL, v, 0, CT_QUAD_4TRI, 0,
                                      &o.g, NULL),
                 CT_ERR_ARG);
    ct_free(w);
    ctt_geo_free(&o);
}
