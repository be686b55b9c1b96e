/*
 * test_search_topo_renumber.c -- the topological search on a spatially
 * renumbered copy of a scattered input (kernels/search_renumber.c) gives
 * the pairs of the plain topological search, bit for bit, over a sequence
 * of searches whose motion makes both its tie-breaks and its history
 * matter: ties between main nodes are broken by the original numbers, and
 * the history is carried to every new numbering. Also: a topology rewritten
 * in place, in the same arrays, is noticed (the history is keyed on the
 * contents, not on the pointers), with and without renumbering.
 */
#include <stdint.h>
#include <string.h>

#include "test_search_scene.h"

#include "ct_internal.h"

/* Main surface: an (nx+1) x (ny+1) grid of unit quads at z = 0, and an
 * m x m sheet of secondary nodes; every number then shuffled (nodes and
 * segments, by a fixed random permutation). main_node[j][i] is the number
 * of grid node (i, j), sec_node[k] that of secondary k. */
enum { NX = 40, NY = 40, M = 12 };

typedef struct tr_scene {
    ctt_scene s;
    ct_idx grid[(NY + 1) * (NX + 1)];
    ct_idx secn[M * M];
} tr_scene;

static uint64_t rng = 88172645463325252ull;
static ct_idx irnd(ct_idx n)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (ct_idx)(rng % (uint64_t)n);
}

static void shuffle(ct_idx *v, ct_idx n)
{
    for (ct_idx i = n - 1; i > 0; i--) {
        ct_idx j = irnd(i + 1), t = v[i];
        v[i] = v[j];
        v[j] = t;
    }
}

static void tr_make(tr_scene *t)
{
    const ct_idx ng = (NY + 1) * (NX + 1), nn = ng + M * M, nq = NX * NY;
    ctt_scene *s = &t->s;
    ctt_scene_init(s, nn, nq);
    ct_idx *perm = malloc(sizeof(ct_idx) * (size_t)nn);
    ct_idx *sp = malloc(sizeof(ct_idx) * (size_t)nq);
    cr_assert(perm && sp);
    for (ct_idx i = 0; i < nn; i++)
        perm[i] = i;
    for (ct_idx i = 0; i < nq; i++)
        sp[i] = i;
    shuffle(perm, nn);
    shuffle(sp, nq);
    for (ct_idx k = 0; k < ng; k++)
        t->grid[k] = perm[k];
    for (ct_idx k = 0; k < M * M; k++)
        t->secn[k] = perm[ng + k];
    s->nn = nn;
    for (int j = 0; j <= NY; j++)
        for (int i = 0; i <= NX; i++) {
            ct_idx v = t->grid[j * (NX + 1) + i];
            s->x[v] = (ct_real)i, s->y[v] = (ct_real)j, s->z[v] = 0;
        }
    s->ns = nq;
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            const ct_idx a = j * (NX + 1) + i, q = sp[j * NX + i];
            s->n1[q] = t->grid[a], s->n2[q] = t->grid[a + 1];
            s->n3[q] = t->grid[a + NX + 2], s->n4[q] = t->grid[a + NX + 1];
        }
    /* Secondaries listed in increasing number (any order would do). */
    ct_idx *sn = malloc(sizeof(ct_idx) * M * M);
    cr_assert(sn);
    memcpy(sn, t->secn, sizeof(ct_idx) * M * M);
    for (ct_idx a = 1; a < M * M; a++)
        for (ct_idx b = a; b > 0 && sn[b - 1] > sn[b]; b--) {
            ct_idx u = sn[b];
            sn[b] = sn[b - 1];
            sn[b - 1] = u;
        }
    for (ct_idx k = 0; k < M * M; k++)
        ctt_scene_sec(s, sn[k]);
    free(sn);
    free(perm);
    free(sp);
}

/* The sheet at offset dx along x: secondary (i, j) at (4.5 + i + dx, 5 + j,
 * 0.3). Every coordinate is exact; where dx is a whole number the node is
 * exactly halfway between two main nodes of its row (a tie). */
static void tr_place(tr_scene *t, double dx)
{
    for (int j = 0; j < M; j++)
        for (int i = 0; i < M; i++) {
            ct_idx v = t->secn[j * M + i];
            t->s.x[v] = (ct_real)(4.5 + i + dx);
            t->s.y[v] = (ct_real)(5 + j);
            t->s.z[v] = (ct_real)0.3;
        }
}

/*
 * Five workspaces search the same sequence: the plain search (renumber -1,
 * the reference), and on a renumbered copy with the kept numbering (renumber
 * 1, default keep; 1 and 2 threads alternating), made anew every search
 * (keep -1: the history is carried over every time), and every third
 * search (keep 3). Steps along x of 1.25 elements let the closest main
 * node run ahead of the one hop a call allows, so the history decides the
 * pairs; steps of 0.25 let it catch up. Gap + margin 1.2 reaches beyond the
 * segments of one node, so the tied node chosen decides the pairs too.
 */
Test(search_topo_renumber, same_pairs_as_plain_search, .timeout = 60)
{
    tr_scene t;
    tr_make(&t);
    static const double step[] = {0,    1.25, 1.25, 1.25, 0.25, 0.25, 0.25, 0.25,
                                  1.25, 1.25, 0.25, 1.25, 0.25, 0.25, 1.25, 0.25};
    enum { NW = 4, NSTEP = sizeof step / sizeof step[0] };
    const int renum[NW] = {-1, 1, 1, 1}, keep[NW] = {0, 0, -1, 3};
    ct_search *w[NW];
    ct_pairs got[NW];
    for (int k = 0; k < NW; k++) {
        ct_search_params p = ct_search_default_params(CT_SEARCH_TOPO);
        p.renumber = renum[k];
        p.renumber_keep = keep[k];
        cr_assert_eq(ct_search_init(&w[k], &p), CT_OK);
        ct_pairs_init(&got[k], 0);
    }
    ct_search_input in = ctt_scene_input(&t.s, 0.3, 0.9, 0);
    double dx = 0;
    int64_t total = 0, ties = 0;
    for (int q = 0; q < NSTEP; q++) {
        dx += step[q];
        tr_place(&t, dx);
        ties += dx == (double)(int64_t)dx;
        for (int k = 0; k < NW; k++) {
            ctt_threads(k == 1 ? 1 + (q & 1) : 2);
            cr_assert_eq(ct_search_run(w[k], &in, &got[k]), CT_OK, "step %d, workspace %d", q,
                         k);
        }
        for (int k = 1; k < NW; k++)
            cr_assert(ctt_same_pairs(&got[0], &got[k]),
                      "step %d (dx %g): renumbered workspace %d gives %d pairs, the plain "
                      "search %d (or they differ)",
                      q, dx, k, got[k].n, got[0].n);
        total += got[0].n;
    }
    cr_assert_geq(ties, 4, "not vacuous: steps with ties");
    cr_assert_gt(total, (int64_t)NSTEP * M * M * 3, "not vacuous: %lld pairs", (long long)total);
    /* The renumbered workspaces did run on a copy. */
    for (int k = 1; k < NW; k++)
        cr_assert(w[k]->rn != NULL, "workspace %d: no renumbering", k);
    for (int k = 0; k < NW; k++) {
        ct_search_destroy(w[k]);
        ct_pairs_destroy(&got[k]);
    }
    ctt_scene_free(&t.s);
}

/*
 * The history belongs to the topology's contents: after a search, every
 * node is renumbered in place (coordinates, corners and secondaries
 * rewritten in the same arrays, which keep their addresses), and the next
 * search must be a full one. On the flat sheet with gap + margin 0.5 the
 * topological search equals the direct search exactly (test_search_topo.c),
 * before and after; a history kept across the rewrite would hop from the
 * old numbers' nodes and miss pairs. With and without renumbering.
 */
static void rewrite_case(int renumber)
{
    tr_scene t;
    tr_make(&t);
    ctt_scene *s = &t.s;
    tr_place(&t, 0.13);
    for (ct_idx k = 0; k < M * M; k++)
        s->y[t.secn[k]] += (ct_real)0.21;
    ct_search_params p = ct_search_default_params(CT_SEARCH_TOPO);
    p.renumber = renumber;
    ct_search *w;
    cr_assert_eq(ct_search_init(&w, &p), CT_OK);
    ct_pairs got, ref;
    ct_pairs_init(&got, 0);
    ct_pairs_init(&ref, 0);
    ct_search_input in = ctt_scene_input(s, 0.3, 0.2, 0);
    for (int round = 0; round < 3; round++) {
        cr_assert_eq(ct_search_run(w, &in, &got), CT_OK);
        ctt_search(CT_SEARCH_DIRECT, &in, &ref);
        cr_assert_gt(ref.n, M * M / 2, "not vacuous");
        cr_assert(ctt_same_pairs(&got, &ref), "round %d: topological %d pairs, direct %d",
                  round, got.n, ref.n);
        /* Renumber every node in place: new number = a random permutation. */
        const ct_idx nn = s->nn;
        ct_idx *perm = malloc(sizeof(ct_idx) * (size_t)nn);
        ct_real *c = malloc(sizeof(ct_real) * 3 * (size_t)nn);
        cr_assert(perm && c);
        for (ct_idx i = 0; i < nn; i++)
            perm[i] = i;
        shuffle(perm, nn);
        for (ct_idx i = 0; i < nn; i++)
            c[3 * i] = s->x[i], c[3 * i + 1] = s->y[i], c[3 * i + 2] = s->z[i];
        for (ct_idx i = 0; i < nn; i++)
            s->x[perm[i]] = c[3 * i], s->y[perm[i]] = c[3 * i + 1],
            s->z[perm[i]] = c[3 * i + 2];
        for (ct_idx j = 0; j < s->ns; j++) {
            s->n1[j] = perm[s->n1[j]], s->n2[j] = perm[s->n2[j]];
            s->n3[j] = perm[s->n3[j]], s->n4[j] = perm[s->n4[j]];
        }
        for (ct_idx i = 0; i < s->nsec; i++)
            s->sec[i] = perm[s->sec[i]];
        for (ct_idx k = 0; k < M * M; k++)
            t.secn[k] = perm[t.secn[k]];
        free(perm);
        free(c);
    }
    ct_search_destroy(w);
    ct_pairs_destroy(&got);
    ct_pairs_destroy(&ref);
    ctt_scene_free(s);
}

Test(search_topo_renumber, in_place_rewrite_plain) { rewrite_case(-1); }

Test(search_topo_renumber, in_place_rewrite_renumbered) { rewrite_case(1); }
