/*
 * test_cycle_handover.c -- the contact cycle (driver/contact_cycle.c) hands
 * a node's friction history to the pair that carries it next when its
 * contact moves from one segment to the next (suite "cycle").
 *
 * The truth is Coulomb's sticking predictor: a node pressed into a flat
 * surface and sliding at speed v below the friction limit carries the
 * tangential force -kt v dt after one step and -2 kt v dt after two,
 * whichever segment it is over. Without the hand-over the second segment's
 * pair would start from zero and read -kt v dt.
 */
#include "test_util.h"

#include <string.h>

#include "contact_cycle.h"

/* Two unit quads side by side at z = 0, A = [0, 1] x [0, 1] and
 * B = [1, 2] x [0, 1]; node 6 the secondary, 0.25 above them (gap 0.3),
 * sliding along x at 1. Steps at x = 0.95 (over A) and 1.05 (over B); with
 * resort, a search between the two (the pair list made again: the last
 * penetration and the history must follow their pairs through it). */
static void slide_across(int resort)
{
    ct_real x[7] = {0, 1, 2, 0, 1, 2, (ct_real)0.95}, y[7] = {0, 0, 0, 1, 1, 1, 0.5};
    ct_real z[7] = {0, 0, 0, 0, 0, 0, 0.25};
    ct_real vx[7] = {0, 0, 0, 0, 0, 0, 1}, vy[7] = {0}, vz[7] = {0};
    ct_real m[7] = {1, 1, 1, 1, 1, 1, 1};
    ct_idx sec[1] = {6}, mainn[6] = {0, 1, 2, 3, 4, 5};
    ct_idx n1[2] = {0, 1}, n2[2] = {1, 2}, n3[2] = {4, 5}, n4[2] = {3, 4};
    ctd_cycle_params p = ctd_cycle_default_params(1);
    cr_assert(p.select && p.mu > 0 && p.kt > 0);
    ctd_cycle *cy;
    cr_assert_eq(ctd_cycle_init(&cy, &p, 7, m, 1, sec, 6, mainn, 2, n1, n2, n3, n4, 0), CT_OK);
    ct_real f[3][7];
    const ct_real dt = (ct_real)1e-3;
    const double step = (double)p.kt * 1.0 * (double)dt; /* kt v dt */

    /* Over A: A carries, B (also within the gap) does not. */
    cr_assert_eq(ctd_cycle_step(cy, x, y, z, vx, vy, vz, dt, f[0], f[1], f[2]), CT_OK);
    const ct_pairs *P = ctd_cycle_pairs(cy);
    cr_assert_eq(P->n, 2, "both segments are candidates");
    ct_idx ka = P->seg[0] == 0 ? 0 : 1, kb = 1 - ka;
    const ct_real *pen = ctd_cycle_geo(cy)->pen;
    cr_assert(pen[ka] > 0 && pen[kb] == 0, "over A: p %g on A, %g on B", (double)pen[ka],
              (double)pen[kb]);
    const double h1 = (double)ctd_cycle_friction(cy, 0)[ka];
    cr_assert_float_eq(h1, -step, 1e-12 * step, "one step of sticking: %g, expected %g", h1,
                       -step);
    /* Below the friction limit (the predictor sticks on both steps). */
    const double fn = (double)f[2][6];
    cr_assert_gt((double)p.mu * fn, 2 * step, "the case must stick: mu Fn %g", (double)p.mu * fn);

    /* Over B: B carries, with A's history. */
    x[6] = (ct_real)1.05;
    if (resort)
        ctd_cycle_force_resort(cy);
    cr_assert_eq(ctd_cycle_step(cy, x, y, z, vx, vy, vz, dt, f[0], f[1], f[2]), CT_OK);
    cr_assert_eq(ctd_cycle_get_stats(cy)->resorts, resort ? 2 : 1);
    P = ctd_cycle_pairs(cy);
    cr_assert_eq(P->n, 2);
    ka = P->seg[0] == 0 ? 0 : 1;
    kb = 1 - ka;
    pen = ctd_cycle_geo(cy)->pen;
    cr_assert(pen[kb] > 0 && pen[ka] == 0, "over B: p %g on A, %g on B", (double)pen[ka],
              (double)pen[kb]);
    const double h2 = (double)ctd_cycle_friction(cy, 0)[kb];
    cr_assert_float_eq(h2, -2 * step, 1e-12 * step,
                       "two steps of sticking: %g, expected %g (one step: %g)", h2, -2 * step,
                       -step);
    for (int a = 0; a < 3; a++)
        cr_assert_eq(ctd_cycle_friction(cy, a)[ka], 0, "axis %d: A kept its history", a);
    /* The node feels it: its tangential force is the history. */
    cr_assert_float_eq((double)f[0][6], -2 * step, 1e-12 * step);
    ctd_cycle_destroy(cy);
}

Test(cycle, friction_history_follows_the_node_to_the_next_segment)
{
    slide_across(0);
}

Test(cycle, friction_history_follows_the_node_through_a_search)
{
    slide_across(1);
}
