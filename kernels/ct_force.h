/*
 * ct_force.h -- contact stiffness, normal force laws and normal damping,
 * part of contact.h (DESIGN.md section 7).
 *
 * Conventions shared by every kernel here:
 *  - Per-pair arrays are structure of arrays of length npair; inputs are
 *    const, outputs are written for every pair (0 when out of contact).
 *  - p is the penetration (p > 0 in contact; p <= 0 or NaN: no contact).
 *  - n = (nx, ny, nz) is the unit normal pointing from the main segment
 *    towards the secondary node; the normal force on the secondary node is
 *    +fn * n (fn >= 0: compressive only). It must be finite for every pair,
 *    in contact or not (the narrow phase gives (0, 0, 1) to pairs it
 *    skips): the force vector is fn * n, and 0 times a NaN normal is NaN
 *    (a select to zero there cost the linear kernel 0.81x at 10^6 pairs). Assembly applies the reaction to
 *    the segment nodes with the shape weights.
 *  - vn is the relative normal velocity (secondary minus contact point) . n:
 *    negative while the node approaches the segment.
 *  - Stored energy is the elastic energy held by the contact spring in its
 *    current state (a state function, not an increment: the increment over a
 *    step is the difference of two totals). Damping dissipation is the
 *    energy removed by the damper over one step (>= 0).
 *  - Kernels run in parallel (OpenMP, static schedule) and give bit-identical
 *    results for any thread count: every pair is computed independently, and
 *    sums use ct_sum_ordered().
 *  - Non-finite values (docs/fuzz F15): the force kernels answer
 *    CT_ERR_NONFINITE when a value they read for a pair, in contact or not,
 *    is NaN or infinite, or when a force (or a state they write) overflows
 *    to a NaN or infinite value. Energies and dissipations are diagnostics
 *    and are not checked: from finite inputs they are finite, or +inf
 *    where their value exceeds the largest ct_real, never NaN. The values
 *    these conventions give a meaning keep it: a penetration that is
 *    NaN or <= 0, -inf included, is no contact (only p = +inf is an error),
 *    and so are the values a kernel's description names so. Stiffnesses,
 *    masses, velocities, normals and states must be finite (a stiffness
 *    <= 0 gives no force, a NaN or infinite one is an error). A NaN or
 *    infinite step dt or damping ratio viss is CT_ERR_ARG; a scalar standing
 *    for a per-pair array (K0 for K) is checked as the array. The check runs
 *    in the loop that computes the pairs, at the cost of an operation or
 *    two per checked value. These kernels take no ct_diag and report no
 *    pair (ct_penalty_type6 does). After CT_ERR_NONFINITE their outputs,
 *    and the states they update, are unspecified: the step is to be
 *    discarded.
 */
#ifndef CT_FORCE_H
#define CT_FORCE_H

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Stiffness ---------------------------------------------------------- */

/* Bulk modulus B = E / (3 (1 - 2 nu)); nu >= 0.5 or invalid input gives
 * 0 when E is 0 and a huge value (1e300, or 3e38 in single) otherwise. */
ct_real ct_bulk_modulus(ct_real E, ct_real nu);

/* Main segment stiffness of a shell, Stfac * E * t. */
ct_real ct_seg_stiffness_shell(ct_real stfac, ct_real E, ct_real t);

/* Main segment stiffness of a brick face, Stfac * B * A^2 / V (0 when
 * V <= 0). */
ct_real ct_seg_stiffness_brick(ct_real stfac, ct_real B, ct_real A, ct_real V);

/* Secondary node stiffness B * (2 Vnode)^(1/3) + Et_mean, with Vnode the
 * sum of V/8 over the bricks attached to the node and Et_mean the mean of
 * E * t over the attached shells (both 0 when there are none). */
ct_real ct_node_stiffness1(ct_real B, ct_real vnode, ct_real et_mean);

/*
 * Segment stiffness for nseg segments. A segment with t[i] > 0 is a shell
 * (Stfac * E[i] * t[i]); otherwise one with V[i] > 0 is a brick face
 * (Stfac * B[i] * A[i]^2 / V[i]); a segment that is both uses the shell
 * value (seed TYPE5); a segment that is neither gets 0. E and t may both be
 * NULL (no shells), B, A and V may all be NULL (no bricks). A NaN input that
 * would be used gives CT_ERR_NONFINITE, a negative E, B, A or a negative
 * stfac CT_ERR_ARG, with the smallest offending index in diag.
 */
int ct_seg_stiffness(ct_idx nseg, ct_real stfac, const ct_real *E, const ct_real *t,
                     const ct_real *B, const ct_real *A, const ct_real *V, ct_real *K,
                     ct_diag *diag);

/* Node stiffness for n nodes (ct_node_stiffness1 per node). B and vnode may
 * both be NULL (no solids), et_mean may be NULL (no shells). Errors as for
 * ct_seg_stiffness. */
int ct_node_stiffness(ct_idx n, const ct_real *B, const ct_real *vnode,
                      const ct_real *et_mean, ct_real *K, ct_diag *diag);

/* How the main (segment) and secondary (node) stiffnesses are combined.
 * TYPE24's Istf selects one of the first five (the driver maps the card
 * value); TYPE3/TYPE5 use the scaled series law with s = 0.2 by default. */
typedef enum ct_stiff_combine {
    CT_STIFF_MAIN = 0,      /* K = Km */
    CT_STIFF_MEAN,          /* K = (Km + Ks) / 2 */
    CT_STIFF_MAX,           /* K = max(Km, Ks) */
    CT_STIFF_MIN,           /* K = min(Km, Ks) */
    CT_STIFF_SERIES,        /* K = Km Ks / (Km + Ks) */
    CT_STIFF_SCALED_SERIES, /* K = s Km Ks / (Km + Ks) */
    CT_STIFF_NCOMBINE
} ct_stiff_combine;

/* Default scale of the TYPE3/TYPE5 series law (seed TYPE5). */
#define CT_STIFF_SCALE_DEFAULT 0.2

/*
 * One combination, then clamped to [stmin, stmax] (stmax <= 0 means no upper
 * bound). Km, Ks >= 0. The series law is evaluated as lo / (1 + lo/hi)
 * (lo, hi the smaller and larger stiffness): finite and within a few ulps
 * for any ratio, 0 when either is 0, the other one when one is infinite.
 * An unknown mode gives 0.
 */
ct_real ct_stiffness_combine1(int mode, ct_real Km, ct_real Ks, ct_real s, ct_real stmin,
                              ct_real stmax);

/* Per-pair stiffness K[k] = combine(Kseg[seg[k]], Knode[node[k]]). Indices
 * are not range-checked (they come from the search). A NaN or negative
 * stiffness gives CT_ERR_NONFINITE / CT_ERR_ARG (smallest pair index in
 * diag), an unknown mode CT_ERR_ARG. */
int ct_stiffness_pairs(ct_idx npair, int mode, const ct_idx *node, const ct_idx *seg,
                       const ct_real *Knode, const ct_real *Kseg, ct_real s, ct_real stmin,
                       ct_real stmax, ct_real *K, ct_diag *diag);

/* ---- Linear penalty (TYPE3, TYPE5, TYPE24) ------------------------------ */

/* fcap value meaning "not blended". */
#define CT_BLEND_NONE (-1)

/* A jump is an increase of the penetration beyond CT_BLEND_SLACK |vn| dt:
 * the slack keeps rounding, and a velocity sampled at another instant of the
 * step than the displacement, from being taken for a jump (each false jump
 * would reshape the law and, through the time integration error, feed
 * energy in). */
#define CT_BLEND_SLACK 1.5

/*
 * Linear penalty F = K q with q the effective penetration, with optional
 * per-pair states the caller keeps across steps (and carries across
 * re-sorts with ct_pair_match / ct_pair_remap):
 *
 * Initial penetration (p0 != NULL; TYPE24 Inacti "subtract"): p0 = min(p0, p)
 * then q = p - p0, so the initial penetration is not pushed out and is
 * forgotten as the node moves out; p0 never grows. p0 == NULL: q = p (the
 * "ignore" mode, full force). p0 is set at the start by
 * ct_initial_penetration().
 *
 * Stiffness blending (p_prev, fcap, qjump all given, or all NULL; TYPE24).
 * When q grows by more than the motion explains, q - p_prev >
 * CT_BLEND_SLACK |vn| dt (a node found deep inside after a re-sort, say),
 * the full force K q would release energy no motion put in. The pair then switches to a blended law, still a
 * function of q alone (so conservative: F = dE/dq, no energy is created
 * while it holds), with a force plateau Fc from qc = Fc/K to the jump
 * penetration qj, and the full stiffness again beyond qj:
 *     F = K q (q <= qc),  Fc (qc < q <= qj),  Fc + K (q - qj) (q > qj);
 *     E = K q^2/2,  Fc q - Fc^2/(2K),  E(qj) + Fc (q - qj) + K (q - qj)^2/2.
 * Fc is chosen so that the stored energy at the jump equals what the law
 * stored at the motion-explained penetration q_e = p_prev + |vn| dt:
 *     E_a = E_old(q_e),  Fc = 2 E_a / (q + sqrt(q^2 - 2 E_a/K))
 * (the root of Fc q - Fc^2/(2K) = E_a written without cancellation); no
 * plateau when E_a >= K q^2/2. For a fresh jump from 0 to q with
 * dq = |vn| dt << q this is Fc ~ K q (dq/q)^2 / 2: the secant stiffness is
 * scaled by half the square of the fraction of the jump the motion
 * explains. Further loading meets the full stiffness K (the node is still
 * stopped), unloading pushes the node out along the plateau, and the secant
 * stiffness F/q grows back to K as the penetration recovers; the blending
 * ends (fcap = CT_BLEND_NONE) once K q <= Fc or the pair separates. The
 * tangent stiffness is K or 0: the time step is unaffected. New pairs start
 * with p_prev = 0, fcap = CT_BLEND_NONE, qjump = 0; p_prev receives q.
 *
 * Outputs: fel[k] the elastic normal force magnitude (>= 0), energy[k] the
 * stored energy (may be NULL). K <= 0 gives no force. Returns CT_ERR_ARG for
 * a negative count, NULL required arrays (vn is required with blending),
 * dt < 0 or not finite, or a partial blending state; CT_ERR_NONFINITE (see
 * the conventions) for a NaN or infinite K, p0, blending state or (with
 * blending) vn, p = +inf, or a force or state that overflows.
 */
int ct_penalty_linear(ct_idx npair, const ct_real *p, const ct_real *vn, const ct_real *K,
                      ct_real dt, ct_real *p0, ct_real *p_prev, ct_real *fcap,
                      ct_real *qjump, ct_real *fel, ct_real *energy);

/* TYPE24 Inacti modes the kernels support. */
typedef enum ct_inacti {
    CT_INACTI_IGNORE = 0,  /* full force on the whole penetration */
    CT_INACTI_SUBTRACT = 1 /* force on max(0, p - p0), p0 = min(p0, p) */
} ct_inacti;

/*
 * Initial penetration at the first cycle (p_init from the narrow phase):
 * p0[k] = p_init[k] (mode SUBTRACT) or 0 (IGNORE); a pair with p_init >
 * pen_max (pen_max > 0; TYPE24 Ipen_max) is deactivated, active[k] = 0
 * (else 1). The caller decides from Ipen0 whether initial penetrations are
 * recorded at all. Returns the number of deactivated pairs, or CT_ERR_ARG.
 */
int ct_initial_penetration(ct_idx npair, int mode, const ct_real *p_init, ct_real pen_max,
                           ct_real *p0, int32_t *active);

/* ---- TYPE7 nonlinear law ------------------------------------------------- */

/* Deactivation threshold: a node with p >= g (1 - CT_TYPE7_RMIN) has
 * reached the mid-surface; its force is capped at the value there,
 * F_max = K0 g (1 - RMIN) / RMIN (about 999 K0 g). */
#define CT_TYPE7_RMIN 1e-3

/* The TYPE7 stored energy K0 g^2 (r - 1 - ln r), r = 1 - p/g, for
 * 0 <= p < g (series in p/g below 1/32, else -x - log1p(-x)). Other
 * inputs: see ct_penalty_type7; this scalar function has no error code,
 * and an infinite input gives a finite value (0 for an infinite K0 or g,
 * the capped law's for p = +inf). */
ct_real ct_type7_energy(ct_real K0, ct_real g, ct_real p);

/*
 * TYPE7 law K = K0 g/(g - p), F = K p = K0 g x/(1 - x) with x = p/g, stored
 * energy E = K0 g^2 (r - 1 - ln r), tangent dF/dp = K0 g^2/(g - p)^2.
 * For x >= 1 - RMIN the pair is deactivated (flag[k] = 1, else 0): F stays
 * at F_max, the energy continues as E(p_c) + F_max (min(p, g) - p_c) and the
 * tangent is the one at p_c: a penetration reaching or passing the gap is
 * not an error. p <= 0, NaN p, g <= 0 or NaN g (-inf too), K0 <= 0 give
 * zero force, energy and tangent. CT_ERR_NONFINITE (see the conventions)
 * for p or g = +inf, a NaN or infinite K0, or a force or tangent whose
 * value exceeds the largest ct_real (F_max = 999 K0 g); the energy is
 * +inf where it does (a gap above 1e154 alone does not make it overflow),
 * and no output is NaN otherwise. ktan, energy and flag may be NULL. (Radioss halves K0 in this law unless
 * Istf = 1: the caller passes the K0 it wants.)
 */
int ct_penalty_type7(ct_idx npair, const ct_real *p, const ct_real *g, const ct_real *K0,
                     ct_real *fel, ct_real *ktan, ct_real *energy, int32_t *flag);

/* ---- TYPE6 user curve ---------------------------------------------------- */

/* Check a piecewise-linear table: n >= 2, every value finite, x strictly
 * ascending. CT_ERR_ARG with the offending index in diag (the first point
 * that breaks a rule; -1 for the count). */
int ct_curve_check(ct_idx n, const ct_real *x, const ct_real *y, ct_diag *diag);

/* f(p) by linear interpolation; beyond the table, linear extrapolation of
 * the first (p < x[0]) or last (p > x[n-1]) interval. *slope (may be NULL)
 * receives f'(p) (the right interval at a breakpoint). The table must have
 * passed ct_curve_check; a NaN p gives 0 and slope 0. */
ct_real ct_curve_eval(ct_idx n, const ct_real *x, const ct_real *y, ct_real p,
                      ct_real *slope);

/*
 * TYPE6: the total force F = max(0, f(p_max)) of the largest penetration is
 * spread over the penetrating pairs in proportion to their penetration,
 * fel[k] = F q_k / sum(q), q_k = max(0, p_k) (NaN counts as 0), so the
 * forces sum to F (to round-off). *pmax, *ftotal and *kcurve (the stiffness
 * for damping and time step, max(f'(p_max), f(p_max)/p_max)) may be NULL.
 * The table is checked first (CT_ERR_ARG via diag). CT_ERR_NONFINITE with
 * diag's index at the first pair of p = +inf (-inf, like NaN, counts as
 * 0), or at the first pair of the largest penetration when F, the largest
 * force or (asked for) kcurve overflows there (a steep extrapolation), or
 * -1 when the sum of the penetrations does; the outputs are then
 * unspecified.
 */
int ct_penalty_type6(ct_idx npair, const ct_real *p, ct_idx ncurve, const ct_real *cx,
                     const ct_real *cy, ct_real *fel, ct_real *pmax, ct_real *ftotal,
                     ct_real *kcurve, ct_diag *diag);

/* ---- Damping and the normal force vector -------------------------------- */

/* Damping coefficient C = viss sqrt(2 K m), m = ms mm/(ms + mm) when mm > 0
 * (reduced mass with the segment), else ms. Invalid input gives 0. */
ct_real ct_damping_coef(ct_real viss, ct_real K, ct_real ms, ct_real mm);

/*
 * Normal damping and the force vector. A pair is in contact when p > 0
 * (fel comes from one of the laws above; kd is the stiffness the damper is
 * tuned to: K for the linear law, the tangent for TYPE7, kcurve for TYPE6):
 *     C = viss sqrt(2 kd m),  fn = max(0, fel - C vn).
 * The total normal force is clamped to be compressive (as Radioss does): the
 * damper may reduce the spring force to zero while the node separates but
 * never pulls. dissip[k] = -(fn - fel) vn dt >= 0 is the work the clamped
 * damper removes over the step, if the force and vn held through it: a
 * one-step estimate, which near the damped stability limit (omega dt of
 * order 1, vn swings within a step) books dissipation the central
 * difference does not do; an energy balance takes ct_damping_work's books
 * instead. (fx, fy, fz) = fn n. Pairs out of contact
 * get zeros. mm may be NULL (secondary mass only); fn and dissip may be NULL.
 * CT_ERR_ARG for a negative count, NULL required arrays, or dt or viss
 * NaN, infinite or (dt) negative; CT_ERR_NONFINITE (see the conventions)
 * for a NaN or infinite fel, kd, vn, ms, mm or normal, p = +inf, or a
 * force that overflows.
 */
int ct_normal_finish(ct_idx npair, const ct_real *p, const ct_real *fel, const ct_real *kd,
                     const ct_real *vn, const ct_real *ms, const ct_real *mm, ct_real viss,
                     ct_real dt, const ct_real *nx, const ct_real *ny, const ct_real *nz,
                     ct_real *fn, ct_real *fx, ct_real *fy, ct_real *fz, ct_real *dissip);

/*
 * The fused fast path for the linear law without blending or initial
 * penetration: F = K p, damping as in ct_normal_finish, in one pass.
 * Outputs the force vector on the secondary node, fn (its magnitude), the
 * stored energy K p^2/2 and the damping dissipation; energy and dissip may
 * be NULL. K may be NULL to use the scalar K0 for every pair. Errors as for
 * ct_normal_finish, with K (or K0) in place of fel and kd.
 */
/*
 * The damper's books for an energy balance of the central difference: its
 * work over the last step by the trapezoidal rule, as the scheme's kinetic
 * energy m v- . v+ / 2 counts every force's work (a force of step n works
 * over the half steps before and after x(n)). Per pair k, after
 * ct_normal_finish (fn, fel, vn its inputs and output; p the penetration):
 * the damping part of the normal force fd = fn - fel (0 when p <= 0) goes
 * to fprev[k], and dissip[k] = -(fprev_old[k] + fd) vn dt / 2, vn the
 * velocity that led to x(n), dt that step. fprev is the caller's per-pair
 * state, 0 for a new pair, carried with its pair across re-sorts (e.g.
 * ct_pair_match, ct_pair_remap) and to the pair a contact moves to. A
 * step's value may be negative near the stability limit: the scheme does
 * that. On a damped edge contact of the driver the one-step figure booked
 * 13 % more than the damping forces did, this within 0.3 % of their nodal
 * work (the force's second half step taken at this step's contact point).
 * CT_ERR_ARG for a negative count, NULL arrays or dt NaN, infinite or
 * negative.
 */
int ct_damping_work(ct_idx npair, const ct_real *p, const ct_real *fn, const ct_real *fel,
                    const ct_real *vn, ct_real dt, ct_real *fprev, ct_real *dissip);

int ct_normal_force(ct_idx npair, const ct_real *p, const ct_real *nx, const ct_real *ny,
                    const ct_real *nz, const ct_real *vn, const ct_real *K, ct_real K0,
                    const ct_real *ms, const ct_real *mm, ct_real viss, ct_real dt,
                    ct_real *fx, ct_real *fy, ct_real *fz, ct_real *fn, ct_real *energy,
                    ct_real *dissip);

/* ---- Kinematics at the contact point ----------------------------------- */

/*
 * Relative velocity of each pair: the secondary node's velocity minus the
 * contact point's, u = v(node) - sum_i h_i v(s_i), written to (rx, ry, rz),
 * and its normal part vn = u . n. s1..s4 are the segment's nodes per pair
 * and h1..h4 their weights (ct_contact_geo; a triangle has h4 = 0). When m
 * is given, mm gets the main mass at the contact point, sum_i h_i m(s_i)
 * (the reduced mass of the damper); m and mm are both NULL or both given.
 * node and s1..s4 are not range-checked (no node count is passed; they come
 * from the search and ct_asm_seg_slots, which check them).
 */
int ct_relative_velocity(ct_idx npair, const ct_idx *node, const ct_idx *s1, const ct_idx *s2,
                         const ct_idx *s3, const ct_idx *s4, const ct_real *h1,
                         const ct_real *h2, const ct_real *h3, const ct_real *h4,
                         const ct_real *nx, const ct_real *ny, const ct_real *nz,
                         const ct_real *vx, const ct_real *vy, const ct_real *vz,
                         const ct_real *m, ct_real *rx, ct_real *ry, ct_real *rz, ct_real *vn,
                         ct_real *mm);

/*
 * Relative velocity of each edge pair at its closest points (ct_narrow_edge_edge):
 * u = v(Pa) - v(Pb), with Pa = (1 - sa) a1 + sa a2 on the first edge and
 * Pb = (1 - sb) b1 + sb b2 on the second; vn = u . n (n the pair's normal,
 * from the second edge towards the first). Optional outputs: (rx, ry, rz) = u
 * (all three or none), u2 = u . u (NULL: not formed), and with m the masses
 * at the two points, ma = (1 - sa) m(a1) + sa m(a2) and mb the same on the
 * second edge (m, ma and mb all given or all NULL). The node indices are not
 * range-checked. Returns CT_ERR_ARG for a negative count, a missing required
 * array or a mismatched optional group.
 */
int ct_relative_velocity_edge(ct_idx npair, const ct_idx *a1, const ct_idx *a2,
                              const ct_idx *b1, const ct_idx *b2, const ct_real *sa,
                              const ct_real *sb, const ct_real *nx, const ct_real *ny,
                              const ct_real *nz, const ct_real *vx, const ct_real *vy,
                              const ct_real *vz, const ct_real *m, ct_real *rx, ct_real *ry,
                              ct_real *rz, ct_real *vn, ct_real *u2, ct_real *ma, ct_real *mb);

/* ---- Deterministic sum --------------------------------------------------- */

/* Sum of a[0..n-1] in an order fixed by n alone (64 fixed blocks, each
 * summed in double, then the block sums in order): bit-identical for any
 * thread count. Used for energy totals. */
double ct_sum_ordered(ct_idx n, const ct_real *a);

#ifdef __cplusplus
}
#endif

#endif /* CT_FORCE_H */
