/*
 * test_assemble_balance.c -- race-free force assembly (suite "assemble"),
 * continued: a triangle's weights, Newton's third law and the moment
 * balance of edge-edge pairs, one workspace through growing and shrinking
 * pair counts, bad input and segment slots. Helpers: test_assemble.h.
 */
#include "test_assemble.h"

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
        assemble_zeroed(&ws, v, &map, w, g.f[0], g.f[1], g.f[2], &f);
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
        assemble_zeroed(&ws, v, &map, weights(&g, wb), g.f[0], g.f[1], g.f[2], &f);
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

/* A node outside [0, nnode) in any slot: every variant answers
 * CT_ERR_RANGE and writes nothing outside [0, nnode); all but the serial
 * one write nothing at all (the serial one skips the bad slots as it meets
 * them, ct_assemble.h). The force arrays are longer than nnode, so a
 * variant that wrote through the bad slot unchecked (the atomic and serial
 * variants and the serial scalar sum did, before 2026-12-02) leaves a
 * nonzero value past nnode, where the test looks. */
Test(assemble, out_of_range_node_every_variant)
{
    enum { NN = 5, LEN = 16 };
    const ct_idx bad_nodes[3] = {NN, LEN - 1, -1};
    for (int c = 0; c < 3; c++)
        for (int s = 0; s < 5; s++) {
            ct_idx slot[5][3] = {{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 0}, {4, 0, 1}};
            slot[s][1] = bad_nodes[c];
            ct_asm_map map = ct_asm_map_nodeseg(3, slot[0], slot[1], slot[2], slot[3], slot[4]);
            ct_real h[3] = {0.25, 0.5, 0.125}, f[3] = {1, -2, 3};
            const ct_real *w[5] = {NULL, h, h, h, h};
            ct_assemble_ws ws;
            cr_assert_eq(ct_assemble_ws_init(&ws), CT_OK);
            ct_real X[LEN] = {0}, Y[LEN] = {0}, Z[LEN] = {0}, S[LEN] = {0};
            for (int v = 0; v < CT_ASM_NVARIANT; v++) {
                if (v == CT_ASM_SERIAL)
                    continue; /* below */
                int rp = ct_assemble_prepare(&ws, (ct_assemble_variant)v, &map, NN);
                int ra = ct_assemble(&ws, (ct_assemble_variant)v, &map, w, f, f, f, NN, X, Y, Z);
                /* The variants that prepare refuse there (then the call
                 * refuses an unprepared workspace); the others at the call. */
                cr_assert(rp == CT_ERR_RANGE || ra == CT_ERR_RANGE,
                          "variant %s, slot %d, node %ld: prepare %d, assemble %d",
                          ct_assemble_variant_name((ct_assemble_variant)v), s,
                          (long)bad_nodes[c], rp, ra);
                cr_assert_neq(ra, CT_OK);
                if (v != CT_ASM_COLOUR)
                    cr_assert_eq(ct_assemble_scalar(&ws, (ct_assemble_variant)v, &map, w, f,
                                                    NN, S),
                                 CT_ERR_RANGE, "scalar sum, variant %s",
                                 ct_assemble_variant_name((ct_assemble_variant)v));
            }
            cr_assert_eq(ct_assemble_atomic(&map, w, f, f, f, NN, X, Y, Z), CT_ERR_RANGE);
            cr_assert_eq(ct_assemble_threadbuf(&ws, &map, w, f, f, f, NN, X, Y, Z),
                         CT_ERR_RANGE);
            for (int i = 0; i < LEN; i++)
                cr_assert(X[i] == 0 && Y[i] == 0 && Z[i] == 0 && S[i] == 0,
                          "slot %d, node %ld: force written at %d", s, (long)bad_nodes[c], i);
            /* The serial variant, directly and through ct_assemble: the
             * pairs whose nodes are all in range add, the bad pair adds
             * nothing (to none of its nodes), nothing lands beyond nnode. */
            for (int r = 0; r < 2; r++) {
                int rc = r ? ct_assemble(&ws, CT_ASM_SERIAL, &map, w, f, f, f, NN, X, Y, Z)
                           : ct_assemble_serial(&map, w, f, f, f, NN, X, Y, Z);
                cr_assert_eq(rc, CT_ERR_RANGE);
            }
            /* The bad pair with a zero force: refused all the same. */
            ct_real fz0[3] = {f[0], 0, f[2]}, T[3][LEN] = {{0}};
            cr_assert_eq(ct_assemble_serial(&map, w, fz0, fz0, fz0, NN, T[0], T[1], T[2]),
                         CT_ERR_RANGE);
            cr_assert_eq(ct_assemble_atomic(&map, w, fz0, fz0, fz0, NN, T[0], T[1], T[2]),
                         CT_ERR_RANGE);
            double want[LEN] = {0};
            for (int k = 0; k < 3; k++) {
                if (k == 1)
                    continue; /* the bad pair */
                for (int q = 0; q < 5; q++)
                    want[slot[q][k]] += 2 * (q == 0 ? 1.0 : -(double)h[k]) * (double)f[k];
            }
            for (int i = 0; i < LEN; i++)
                cr_assert(fabs((double)X[i] - want[i]) <= 1e-6 && X[i] == Y[i] && X[i] == Z[i],
                          "serial, slot %d, node %ld: node %d has %g, want %g", s,
                          (long)bad_nodes[c], i, (double)X[i], want[i]);
            ct_assemble_ws_destroy(&ws);
        }
}

/* ct_colour_degree on a map whose slots changed since the colouring (same
 * sizes): its per-node counters are indexed by the map's nodes, so a node
 * out of range is refused (-1) rather than read and written past them. */
Test(assemble, colour_degree_refuses_a_changed_map)
{
    ct_idx slot[5][3] = {{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 0}, {4, 0, 1}};
    ct_asm_map map = ct_asm_map_nodeseg(3, slot[0], slot[1], slot[2], slot[3], slot[4]);
    ct_assemble_ws ws;
    cr_assert_eq(ct_assemble_ws_init(&ws), CT_OK);
    cr_assert_eq(ct_colour_pairs(&ws, &map, 5, 1), CT_OK);
    /* Every pair shares nodes with both others: degree 2 per shared node
     * counted with repetition, at least 2. */
    const ct_idx d = ct_colour_degree(&ws, &map, 5);
    cr_assert_geq(d, 2);
    cr_assert_leq(ws.ncolour, d + 1);
    const ct_idx bad[3] = {5, 40, -1};
    for (int c = 0; c < 3; c++) {
        slot[3][2] = bad[c];
        cr_assert_eq(ct_colour_degree(&ws, &map, 5), -1, "node %ld", (long)bad[c]);
    }
    slot[3][2] = 0;
    cr_assert_eq(ct_colour_degree(&ws, &map, 5), d);
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
