/*
 * test_predicate_batch.c -- the batch hull predicate (kernels/predicate_batch.c)
 * against the one-pair predicate, ct_pair_may_touch, pair by pair.
 *
 * The searches that use the batch must return the direct search's pair set
 * bit for bit, and the direct search asks ct_pair_may_touch; so every lane's
 * answer must be the one-pair answer exactly, on ordinary pairs and above
 * all on the awkward ones: points at the decision distance, on edges and
 * corners, in the segment's plane, behind it; warped, reflex, needle and
 * collapsed quads; triangles; coordinates that are not finite. The test
 * also checks that the vector lanes decide most pairs by themselves, so a
 * batch that silently sent everything to the one-pair predicate would fail.
 */
#include <float.h>

#include "test_util.h"

#include "ct_internal.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15u;

static double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * 0x1.0p-53;
}

/* One random segment of a kind chosen by `kind` (0..7), in c[4][3]. */
static void make_segment(int kind, double c[4][3])
{
    double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 4; k++) {
        c[k][0] = sq[k][0] + 0.1 * (urand() - 0.5);
        c[k][1] = sq[k][1] + 0.1 * (urand() - 0.5);
        c[k][2] = 0;
    }
    switch (kind) {
    case 0: /* flat, axis-aligned unit square (exact corners) */
        for (int k = 0; k < 4; k++)
            c[k][0] = sq[k][0], c[k][1] = sq[k][1];
        break;
    case 1: /* warped */
        for (int k = 0; k < 4; k++)
            c[k][2] = 0.3 * (urand() - 0.5);
        break;
    case 2: /* triangle: n4 == n3 */
        for (int a = 0; a < 3; a++)
            c[3][a] = c[2][a];
        break;
    case 3: /* dart (reflex corner) */
        c[2][0] = 0.3, c[2][1] = 0.3;
        break;
    case 4: /* needle: all corners on a line */
        for (int k = 0; k < 4; k++)
            c[k][0] = 0.5 * k, c[k][1] = 0, c[k][2] = 0;
        break;
    case 5: /* collapsed: two corners coincide */
        for (int a = 0; a < 3; a++)
            c[1][a] = c[0][a];
        break;
    case 6: /* strongly warped, large */
        for (int k = 0; k < 4; k++) {
            c[k][0] *= 10;
            c[k][1] *= 10;
            c[k][2] = 4 * (urand() - 0.5);
        }
        break;
    default: /* all four corners the same point */
        for (int k = 1; k < 4; k++)
            for (int a = 0; a < 3; a++)
                c[k][a] = c[0][a];
        break;
    }
}

/* A point near the segment: over it, beside an edge, at a corner, in its
 * plane, or exactly at the decision distance d along an axis. */
static void make_point(int where, const double c[4][3], double d, double p[3])
{
    int k = (int)(4 * urand()) & 3, k1 = (k + 1) & 3;
    double t = urand();
    double e[3];
    for (int a = 0; a < 3; a++)
        e[a] = c[k][a] + t * (c[k1][a] - c[k][a]);
    switch (where) {
    case 0: /* over the middle, at a height around d */
        for (int a = 0; a < 3; a++)
            p[a] = 0.25 * (c[0][a] + c[1][a] + c[2][a] + c[3][a]);
        p[2] += d * (0.8 + 0.4 * urand()) * (urand() < 0.5 ? -1 : 1);
        break;
    case 1: /* beside an edge, at a distance around d */
        for (int a = 0; a < 3; a++)
            p[a] = e[a] + d * (1.2 * urand() - 0.1) * (a == 2 ? 0.5 : 1) * (urand() - 0.5) * 2;
        break;
    case 2: /* exactly on an edge */
        for (int a = 0; a < 3; a++)
            p[a] = e[a];
        break;
    case 3: /* exactly a corner, or d above it */
        for (int a = 0; a < 3; a++)
            p[a] = c[k][a];
        p[2] += urand() < 0.5 ? d : 0;
        break;
    case 4: /* in the plane z = 0, around the outline */
        p[0] = 1.6 * urand() - 0.3;
        p[1] = 1.6 * urand() - 0.3;
        p[2] = 0;
        break;
    default: /* anywhere in a box around the segment */
        for (int a = 0; a < 3; a++)
            p[a] = 3 * urand() - 1;
        break;
    }
}

/* One run of the batch on n pairs, starting with `skip` batches' worth of
 * the corner step left out; compares every answer with ct_pair_may_touch. */
static int64_t check_batch_mode(int n, const double (*p)[3], const double (*c)[4][3],
                                double d, int *accepted, int skip, int *skip_after)
{
    /* The coordinates live in node arrays, as in a search: node 5k is the
     * point, nodes 5k+1..5k+4 the corners of segment k. */
    static ct_real x[5 * CTI_PAIR_BATCH], y[5 * CTI_PAIR_BATCH], z[5 * CTI_PAIR_BATCH];
    static ct_idx n1[CTI_PAIR_BATCH], n2[CTI_PAIR_BATCH], n3[CTI_PAIR_BATCH],
        n4[CTI_PAIR_BATCH];
    cti_pair_batch b;
    cti_pair_batch_init(&b);
    b.skip = skip;
    b.n = n;
    for (int k = 0; k < n; k++) {
        x[5 * k] = (ct_real)p[k][0], y[5 * k] = (ct_real)p[k][1], z[5 * k] = (ct_real)p[k][2];
        for (int v = 0; v < 4; v++) {
            x[5 * k + 1 + v] = (ct_real)c[k][v][0];
            y[5 * k + 1 + v] = (ct_real)c[k][v][1];
            z[5 * k + 1 + v] = (ct_real)c[k][v][2];
        }
        n1[k] = 5 * k + 1, n2[k] = 5 * k + 2, n3[k] = 5 * k + 3, n4[k] = 5 * k + 4;
        b.node[k] = 5 * k;
        b.seg[k] = k;
    }
    cti_pair_batch_load(&b, x, y, z, n1, n2, n3, n4);
    cti_pair_batch_test(&b, (ct_real)d);
    for (int k = 0; k < n; k++) {
        ct_real P[3] = {x[5 * k], y[5 * k], z[5 * k]}, A[4][3];
        for (int v = 0; v < 4; v++)
            A[v][0] = x[5 * k + 1 + v], A[v][1] = y[5 * k + 1 + v], A[v][2] = z[5 * k + 1 + v];
        int one = ct_pair_may_touch(P, A[0], A[1], A[2], A[3], (ct_real)d);
        cr_assert(b.ok[k] == 0 || b.ok[k] == 1, "pair %d: batch answer %lld is not 0 or 1", k,
                  (long long)b.ok[k]);
        cr_assert_eq((int)b.ok[k], one,
                     "pair %d: batch says %d, ct_pair_may_touch says %d (p = %a %a %a, d = %a)",
                     k, (int)b.ok[k], one, (double)P[0], (double)P[1], (double)P[2], d);
        *accepted += one;
    }
    *skip_after = b.skip;
    return b.nscalar;
}

/* Runs n pairs (points p[k], segments c[k]) through the batch and compares
 * each answer with ct_pair_may_touch; returns the pairs the batch left to
 * the one-pair predicate (the larger count of two runs). The batch runs
 * twice: with the corner step (as a fresh batch does) and without it (as
 * after a batch where it left most lanes open, one stage); both must give
 * the one-pair answers. *skip_after gets the
 * first run's skip count (0: the corner step stays on). */
static int64_t check_batch_skip(int n, const double (*p)[3], const double (*c)[4][3],
                                double d, int *accepted, int *skip_after)
{
    int64_t first = 0;
    for (int mode = 0; mode < 2; mode++) {
        int acc = 0, skip;
        int64_t sc = check_batch_mode(n, p, c, d, &acc, mode ? 3 : 0, &skip);
        first = sc > first ? sc : first;
        if (mode == 0) {
            *accepted += acc;
            if (skip_after)
                *skip_after = skip;
        }
    }
    return first;
}

static int64_t check_batch(int n, const double (*p)[3], const double (*c)[4][3], double d,
                           int *accepted)
{
    return check_batch_skip(n, p, c, d, accepted, NULL);
}

Test(predicate_batch, matches_one_pair_predicate_on_awkward_pairs)
{
    enum { NB = 400 };
    static double p[CTI_PAIR_BATCH][3], c[CTI_PAIR_BATCH][4][3];
    int64_t total = 0, scalar = 0;
    int accepted = 0;
    for (int b = 0; b < NB; b++) {
        /* Batch sizes that are not multiples of the vector width too. */
        int n = b % 7 == 0 ? 1 + (int)(urand() * (CTI_PAIR_BATCH - 1)) : CTI_PAIR_BATCH;
        double d = (b % 3 == 0) ? 0.5 : 0.05 + urand();
        for (int k = 0; k < n; k++) {
            make_segment((int)(8 * urand()), c[k]);
            make_point((int)(6 * urand()), c[k], d, p[k]);
        }
        scalar += check_batch(n, (const double(*)[3])p, (const double(*)[4][3])c, d, &accepted);
        total += n;
    }
    cr_assert_gt(accepted, total / 5, "too few accepted pairs (%d of %lld) to test anything",
                 accepted, (long long)total);
    cr_assert_lt(accepted, total * 4 / 5, "too few rejected pairs (%lld of %lld)",
                 (long long)(total - accepted), (long long)total);
    /* The segments above include many degenerate ones that the vector
     * steps may not decide; still, most pairs are decided in the lanes. */
    cr_assert_lt(scalar, total / 2, "%lld of %lld pairs left to the one-pair predicate",
                 (long long)scalar, (long long)total);
}

/* Smooth, well-shaped quads (a flat grid): the vector steps decide every
 * pair, and the answers are the one-pair ones. */
Test(predicate_batch, smooth_pairs_decided_in_lanes)
{
    static double p[CTI_PAIR_BATCH][3], c[CTI_PAIR_BATCH][4][3];
    int64_t total = 0, scalar = 0;
    int accepted = 0;
    for (int b = 0; b < 100; b++) {
        for (int k = 0; k < CTI_PAIR_BATCH; k++) {
            double ox = (double)(k % 4) - 1, oy = (double)((k / 4) % 4) - 1;
            double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, h = 0.02 * urand();
            for (int v = 0; v < 4; v++) {
                c[k][v][0] = ox + sq[v][0];
                c[k][v][1] = oy + sq[v][1];
                c[k][v][2] = h;
            }
            p[k][0] = urand();
            p[k][1] = urand();
            p[k][2] = 0.3;
        }
        scalar += check_batch(CTI_PAIR_BATCH, (const double(*)[3])p,
                              (const double(*)[4][3])c, 0.5, &accepted);
        total += CTI_PAIR_BATCH;
    }
    cr_assert_gt(accepted, 0);
    cr_assert_lt(accepted, total);
    cr_assert_eq(scalar, 0, "%lld smooth pairs left to the one-pair predicate", (long long)scalar);
}

/* The corner step's switch. Segments small against d (a graded mesh's fine
 * region): most pairs have a corner within d, the costly steps run on the
 * few left, packed, and the step stays on. Segments large against d (the
 * plates): no corner is within d, and the next batches leave the step out.
 * Either way every answer is the one-pair answer (check_batch_skip runs
 * both ways), and the smooth pairs never reach the one-pair predicate. */
Test(predicate_batch, corner_step_on_fine_segments_off_on_coarse)
{
    static double p[CTI_PAIR_BATCH][3], c[CTI_PAIR_BATCH][4][3];
    for (int fine = 0; fine < 2; fine++) {
        int64_t scalar = 0;
        int accepted = 0, total = 0, on = 0;
        for (int b = 0; b < 50; b++) {
            const double h = fine ? 0.05 : 1.0, d = 0.5;
            for (int k = 0; k < CTI_PAIR_BATCH; k++) {
                double ox = h * (double)(k % 8) - 4 * h, oy = h * (double)((k / 8) % 8) - 4 * h;
                double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                for (int v = 0; v < 4; v++) {
                    c[k][v][0] = ox + h * sq[v][0];
                    c[k][v][1] = oy + h * sq[v][1];
                    c[k][v][2] = 0;
                }
                /* Fine: within about d of the patch; coarse: over the
                 * segment's middle at 0.3, as the plates' nodes are (every
                 * corner then farther than d). */
                p[k][0] = fine ? d * (2 * urand() - 1) : ox + h * (0.3 + 0.4 * urand());
                p[k][1] = fine ? d * (2 * urand() - 1) : oy + h * (0.3 + 0.4 * urand());
                p[k][2] = fine ? 0.6 * d * (2 * urand() - 1) : 0.3;
            }
            int skip = -1;
            scalar += check_batch_skip(CTI_PAIR_BATCH, (const double(*)[3])p,
                                       (const double(*)[4][3])c, 0.5, &accepted, &skip);
            on += skip == 0;
            total += CTI_PAIR_BATCH;
        }
        cr_assert_gt(accepted, total / 4, "fine %d: %d of %d accepted", fine, accepted, total);
        cr_assert_eq(scalar, 0, "fine %d: %lld pairs left to the one-pair predicate", fine,
                     (long long)scalar);
        if (fine)
            cr_assert_eq(on, 50, "fine segments: the corner step was dropped %d times", 50 - on);
        else
            cr_assert_eq(on, 0, "coarse segments: the corner step was kept %d times", on);
    }
}

/* Self contact on a crumpled sheet: segments of a node's neighbourhood
 * that lie just farther than d, turned every way. Their boxes, inflated by
 * d, keep such pairs (a turned segment's box is larger than the segment):
 * step 4b must reject them in the lanes, in both stage orders, with the
 * one-pair answers. (Before step 4b ran in the lanes, such pairs were
 * about 2 per node of the crumpled sheet, all sent to the one-pair
 * predicate.) */
static int box_but_not_hull(const double p[3], const double c[4][3], double d)
{
    ct_real P[3], A[4][3];
    for (int a = 0; a < 3; a++) {
        P[a] = (ct_real)p[a];
        for (int v = 0; v < 4; v++)
            A[v][a] = (ct_real)c[v][a];
    }
    return ct_pair_box_near(P, A[0], A[1], A[2], A[3], (ct_real)d) &&
           !ct_pair_may_touch(P, A[0], A[1], A[2], A[3], (ct_real)d);
}

Test(predicate_batch, turned_neighbours_rejected_in_lanes)
{
    static double p[CTI_PAIR_BATCH][3], c[CTI_PAIR_BATCH][4][3];
    int64_t total = 0, scalar = 0, box_only = 0;
    int accepted = 0;
    const double d = 0.5;
    for (int b = 0; b < 100; b++) {
        for (int k = 0; k < CTI_PAIR_BATCH; k++) {
            /* A slightly warped quad of side 1.3 about the origin, turned
             * about z, then about x. */
            double sq[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            double t = 6.283185307179586 * urand(), f = 3.141592653589793 * (urand() - 0.5);
            double ct = cos(t), st = sin(t), cf = cos(f), sf = sin(f);
            double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
            for (int v = 0; v < 4; v++) {
                double x = 0.65 * sq[v][0] + 0.1 * (urand() - 0.5);
                double y = 0.65 * sq[v][1] + 0.1 * (urand() - 0.5), z = 0.1 * (urand() - 0.5);
                double xr = ct * x - st * y, yr = st * x + ct * y;
                c[k][v][0] = xr;
                c[k][v][1] = cf * yr - sf * z;
                c[k][v][2] = sf * yr + cf * z;
                for (int a = 0; a < 3; a++) {
                    lo[a] = fmin(lo[a], c[k][v][a]);
                    hi[a] = fmax(hi[a], c[k][v][a]);
                }
            }
            /* The node somewhere in the inflated box, preferably where the
             * box keeps it and the hull does not. */
            for (int tries = 0; tries < 64; tries++) {
                for (int a = 0; a < 3; a++)
                    p[k][a] = lo[a] - d + (hi[a] - lo[a] + 2 * d) * urand();
                if (box_but_not_hull(p[k], (const double(*)[3])c[k], d))
                    break;
            }
            box_only += box_but_not_hull(p[k], (const double(*)[3])c[k], d);
        }
        scalar += check_batch(CTI_PAIR_BATCH, (const double(*)[3])p,
                              (const double(*)[4][3])c, d, &accepted);
        total += CTI_PAIR_BATCH;
    }
    cr_assert_gt(box_only, total * 9 / 10,
                 "only %lld of %lld pairs pass the box but not the hull: nothing to test",
                 (long long)box_only, (long long)total);
    /* Step 4b's bound takes the larger lateral term, not both: beyond a
     * corner it can fall short of d, and step 5 decides (about 4 %). */
    cr_assert_lt(scalar, total / 10, "%lld of %lld pairs left to the one-pair predicate",
                 (long long)scalar, (long long)total);
}

/* Coordinates that are not finite: the lane defers to the one-pair
 * predicate, whatever it answers, and the answers agree. */
Test(predicate_batch, non_finite_coordinates)
{
    static double p[CTI_PAIR_BATCH][3], c[CTI_PAIR_BATCH][4][3];
    int accepted = 0;
    for (int k = 0; k < 16; k++) {
        make_segment(0, c[k]);
        make_point(0, c[k], 0.5, p[k]);
    }
    p[0][0] = NAN;
    p[1][2] = INFINITY;
    c[2][1][1] = NAN;
    c[3][3][2] = -INFINITY;
    int64_t scalar =
        check_batch(16, (const double(*)[3])p, (const double(*)[4][3])c, 0.5, &accepted);
    cr_assert_geq(scalar, 4, "the four non-finite pairs must go to the one-pair predicate");
}

/* The searches round box bounds outward to float with cti_next_down_f and
 * cti_next_up_f; they must be libm's nextafterf toward -inf and +inf, on
 * zeros, subnormals, the largest float, infinities and random bit
 * patterns. */
static void check_next(float f)
{
    float d = cti_next_down_f(f), u = cti_next_up_f(f);
    float wd = nextafterf(f, -INFINITY), wu = nextafterf(f, INFINITY);
    cr_assert(memcmp(&d, &wd, sizeof d) == 0, "next down of %a: %a, libm %a", (double)f,
              (double)d, (double)wd);
    cr_assert(memcmp(&u, &wu, sizeof u) == 0, "next up of %a: %a, libm %a", (double)f,
              (double)u, (double)wu);
}

Test(predicate_batch, float_rounding_steps_match_nextafterf)
{
    const float special[] = {0.0f,       -0.0f,     0x1p-149f,  -0x1p-149f, 0x1p-126f,
                             -0x1p-126f, 1.0f,      -1.0f,      FLT_MAX,    -FLT_MAX,
                             INFINITY,   -INFINITY, 0x1.fffffep-127f, -0x1.fffffep-127f};
    for (size_t k = 0; k < sizeof special / sizeof special[0]; k++)
        check_next(special[k]);
    for (int k = 0; k < 100000; k++) {
        uint32_t b = (uint32_t)(urand() * 4294967296.0);
        float f;
        memcpy(&f, &b, sizeof f);
        if (f == f)
            check_next(f);
    }
}
