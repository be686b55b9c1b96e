/*
 * test_resort_track.c -- ct_resort_track (suite "resort"): its two bounds
 * are ct_resort_needed's against each reference, bit for bit, it copies
 * exactly the listed nodes' positions, and its largest magnitude is a hand
 * loop's, and both bounds are the criterion's computed by hand; on one
 * list (self contact) and two overlapping lists, every node in order (read
 * contiguously) or not, small (no thread team) and large, 1 and 2 threads;
 * a NaN position makes both bounds and the magnitude infinite.
 */
#include "test_util.h"

#include <string.h>

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct {
    ct_idx n;
    ct_real *p[3][3]; /* [reference: 0 sort, 1 previous, 2 now][axis] */
    ct_real *k[3];    /* the copy's destination */
} tstate;

static void ts_make(tstate *t, ct_idx n)
{
    t->n = n;
    for (int r = 0; r < 3; r++)
        for (int a = 0; a < 3; a++) {
            t->p[r][a] = ct_calloc((size_t)n, sizeof(ct_real));
            cr_assert(t->p[r][a]);
        }
    for (int a = 0; a < 3; a++) {
        t->k[a] = ct_calloc((size_t)n, sizeof(ct_real));
        cr_assert(t->k[a]);
    }
    /* Positions around 100 (so the magnitude is not the displacement's),
     * the previous ones within 0.01 of now, the sort's within 0.3; some
     * nodes carry a negative coordinate of larger magnitude. */
    for (ct_idx i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) {
            double now = 100 + 10 * urand() - (i % 97 == 0 ? 300 * urand() : 0);
            t->p[2][a][i] = (ct_real)now;
            t->p[1][a][i] = (ct_real)(now - 0.01 * (2 * urand() - 1));
            t->p[0][a][i] = (ct_real)(now - 0.3 * (2 * urand() - 1));
        }
}

static void ts_free(tstate *t)
{
    for (int r = 0; r < 3; r++)
        for (int a = 0; a < 3; a++)
            ct_free(t->p[r][a]);
    for (int a = 0; a < 3; a++)
        ct_free(t->k[a]);
}

static int same_bits(ct_real a, ct_real b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* The criterion's bound by hand (DESIGN.md section 5), from reference r
 * to now: the same operations per node, whose min and max are exact, so
 * the kernels' bits are expected. */
static ct_real hand_bound(const tstate *t, int r, ct_idx ns, const ct_idx *sec, ct_idx nm,
                          const ct_idx *mainn)
{
    ct_real m2[2] = {0, 0}, lo[2][3], hi[2][3];
    for (int side = 0; side < 2; side++) {
        const ct_idx n = side ? nm : ns, *l = side ? mainn : sec;
        for (int a = 0; a < 3; a++)
            lo[side][a] = (ct_real)INFINITY, hi[side][a] = -(ct_real)INFINITY;
        for (ct_idx i = 0; i < n; i++) {
            ct_real d[3];
            for (int a = 0; a < 3; a++) {
                d[a] = t->p[2][a][l[i]] - t->p[r][a][l[i]];
                lo[side][a] = d[a] < lo[side][a] ? d[a] : lo[side][a];
                hi[side][a] = d[a] > hi[side][a] ? d[a] : hi[side][a];
            }
            ct_real d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            m2[side] = d2 > m2[side] ? d2 : m2[side];
        }
    }
    ct_real b = (ct_real)sqrt((double)m2[0]) + (ct_real)sqrt((double)m2[1]);
    ct_real r2 = 0;
    for (int a = 0; a < 3; a++) {
        ct_real u = hi[0][a] - lo[1][a], v = hi[1][a] - lo[0][a];
        ct_real w = u > v ? u : v;
        r2 += w * w;
    }
    ct_real rel = (ct_real)sqrt((double)r2);
    return rel < b ? rel : b;
}

/* One call against the reference calls, on lists (sec, main). */
static void check_case(tstate *t, ct_idx ns, const ct_idx *sec, ct_idx nm, const ct_idx *mainn,
                       int threads)
{
    ctt_threads(threads);
    ct_real *const *q = t->p[0], *const *pv = t->p[1], *const *x = t->p[2];
    const ct_real margin = (ct_real)0.25;
    ct_real b_ref, s_ref;
    int need_ref = ct_resort_needed(ns, sec, nm, mainn, q[0], q[1], q[2], x[0], x[1], x[2],
                                    margin, &b_ref);
    ct_resort_needed(ns, sec, nm, mainn, pv[0], pv[1], pv[2], x[0], x[1], x[2], 0, &s_ref);
    /* The magnitude and the copy by hand; unlisted nodes keep a sentinel. */
    double L_ref = 0;
    for (int pass = 0; pass < 2; pass++) {
        const ct_idx n = pass ? nm : ns, *l = pass ? mainn : sec;
        for (ct_idx i = 0; i < n; i++)
            for (int a = 0; a < 3; a++) {
                double v = fabs((double)x[a][l[i]]);
                L_ref = v > L_ref ? v : L_ref;
            }
    }
    for (int a = 0; a < 3; a++)
        for (ct_idx i = 0; i < t->n; i++)
            t->k[a][i] = (ct_real)-7;
    ct_real b, s;
    double L;
    int need = ct_resort_track(ns, sec, nm, mainn, q[0], q[1], q[2], pv[0], pv[1], pv[2], x[0],
                               x[1], x[2], t->k[0], t->k[1], t->k[2], margin, &b, &s, &L);
    cr_assert_eq(need, need_ref);
    const ct_real b_hand = hand_bound(t, 0, ns, sec, nm, mainn);
    const ct_real s_hand = hand_bound(t, 1, ns, sec, nm, mainn);
    cr_assert(same_bits(b_ref, b_hand), "ct_resort_needed %.17g, by hand %.17g", (double)b_ref,
              (double)b_hand);
    cr_assert(same_bits(s_ref, s_hand), "ct_resort_needed %.17g, by hand %.17g", (double)s_ref,
              (double)s_hand);
    cr_assert(same_bits(b, b_ref), "bound %.17g, ct_resort_needed's %.17g", (double)b,
              (double)b_ref);
    cr_assert(same_bits(s, s_ref), "step %.17g, ct_resort_needed's %.17g", (double)s,
              (double)s_ref);
    cr_assert_gt(s, 0);
    cr_assert_lt(s, b, "the step's bound (moves of 0.01) is below the sort's (0.3)");
    cr_assert_eq(L, L_ref, "magnitude %.17g, by hand %.17g", L, L_ref);
    char *listed = calloc((size_t)t->n, 1);
    cr_assert(listed);
    for (ct_idx i = 0; i < ns; i++)
        listed[sec[i]] = 1;
    for (ct_idx i = 0; i < nm; i++)
        listed[mainn[i]] = 1;
    for (int a = 0; a < 3; a++)
        for (ct_idx i = 0; i < t->n; i++) {
            ct_real want = listed[i] ? x[a][i] : (ct_real)-7;
            cr_assert(same_bits(t->k[a][i], want), "node %d axis %d: copied %g, expected %g",
                      (int)i, a, (double)t->k[a][i], (double)want);
        }
    /* Without the copy and the optional outputs: the same criterion. */
    cr_assert_eq(ct_resort_track(ns, sec, nm, mainn, q[0], q[1], q[2], pv[0], pv[1], pv[2],
                                 x[0], x[1], x[2], NULL, NULL, NULL, margin, NULL, NULL, NULL),
                 need_ref);
    free(listed);
    ctt_threads(2);
}

/* Lists over n nodes: every other node in a scrambled order (sec), the
 * last two thirds (main, overlapping sec) and every node in order (all,
 * which the kernels read contiguously). */
static void lists(ct_idx n, ct_idx **sec, ct_idx *ns, ct_idx **mainn, ct_idx *nm, ct_idx **all)
{
    *ns = n / 2;
    *nm = n - n / 3;
    *sec = malloc((size_t)*ns * sizeof **sec);
    *mainn = malloc((size_t)*nm * sizeof **mainn);
    *all = malloc((size_t)n * sizeof **all);
    cr_assert(*sec && *mainn && *all);
    for (ct_idx i = 0; i < *ns; i++)
        (*sec)[i] = (ct_idx)(((int64_t)i * 7919 % *ns) * 2);
    for (ct_idx i = 0; i < *nm; i++)
        (*mainn)[i] = n / 3 + i;
    for (ct_idx i = 0; i < n; i++)
        (*all)[i] = i;
}

Test(resort, track_equals_two_criteria_and_a_copy)
{
    const ct_idx sizes[2] = {1000, 40000}; /* below and above the team threshold */
    for (int z = 0; z < 2; z++) {
        tstate t;
        ts_make(&t, sizes[z]);
        ct_idx *sec, *mainn, *all, ns, nm;
        lists(t.n, &sec, &ns, &mainn, &nm, &all);
        for (int threads = 1; threads <= 2; threads++) {
            check_case(&t, ns, sec, nm, mainn, threads);   /* two lists */
            check_case(&t, nm, mainn, nm, mainn, threads); /* one list: self contact */
            check_case(&t, t.n, all, t.n, all, threads);   /* the same, every node */
            check_case(&t, t.n, all, ns, sec, threads);    /* every node against a list */
        }
        free(sec);
        free(mainn);
        free(all);
        ts_free(&t);
    }
}

Test(resort, track_nan_position_is_infinite)
{
    tstate t;
    ts_make(&t, 20000);
    ct_idx *sec, *mainn, *all, ns, nm;
    lists(t.n, &sec, &ns, &mainn, &nm, &all);
    t.p[2][1][mainn[nm / 2]] = (ct_real)NAN;
    for (int c = 0; c < 2; c++) { /* a list, then every node */
        const ct_idx n = c ? t.n : nm, *l = c ? all : mainn;
        ct_real b, s;
        double L;
        int need = ct_resort_track(n, l, n, l, t.p[0][0], t.p[0][1], t.p[0][2], t.p[1][0],
                                   t.p[1][1], t.p[1][2], t.p[2][0], t.p[2][1], t.p[2][2],
                                   t.k[0], t.k[1], t.k[2], (ct_real)1e30, &b, &s, &L);
        cr_assert_eq(need, 1, "a NaN position must force a re-sort");
        cr_assert(isinf(b) && b > 0, "bound %g", (double)b);
        cr_assert(isinf(s) && s > 0, "step %g", (double)s);
        cr_assert(isinf(L) && L > 0, "magnitude %g", L);
        ct_real b1;
        cr_assert_eq(ct_resort_needed(n, l, n, l, t.p[0][0], t.p[0][1], t.p[0][2], t.p[2][0],
                                      t.p[2][1], t.p[2][2], (ct_real)1e30, &b1),
                     1);
        cr_assert(isinf(b1) && b1 > 0, "ct_resort_needed's bound %g", (double)b1);
    }
    free(sec);
    free(mainn);
    free(all);
    ts_free(&t);
}
