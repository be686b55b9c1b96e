/*
 * ct_friction.h -- friction laws, the tangential force with return to the
 * Coulomb cone, the tangential filter, and per-pair history carried across
 * re-sorts; part of contact.h (DESIGN.md section 7, seeds TYPE5, TYPE24).
 *
 * Conventions: v = (vx, vy, vz) is the velocity of the secondary node
 * relative to the contact point on the main segment; the tangential force
 * computed here acts on the secondary node (the reaction goes to the segment
 * nodes through assembly) and opposes the slip. fn is the magnitude of the
 * normal force (>= 0).
 */
#ifndef CT_FRICTION_H
#define CT_FRICTION_H

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Friction laws mu(p, v), p the contact pressure, v the tangential slip
 * speed (>= 0). The coefficients are coef[0] = Fric, coef[1..6] = C1..C6
 * (the TYPE24 card). The result is clamped to mu >= 0 (NaN gives 0).
 */
typedef enum ct_fric_law {
    /* mu = Fric */
    CT_FRIC_COULOMB = 0,
    /* Ifric 1, polynomial in pressure and speed:
     * mu = Fric + C1 p + C2 v + C3 p v + C4 p^2 + C5 v^2 */
    CT_FRIC_POLY = 1,
    /* Ifric 2, Darmstad:
     * mu = C1 e^(C2 v) p^2 + C3 e^(C4 v) p + C5 e^(C6 v) */
    CT_FRIC_DARMSTAD = 2,
    /* Ifric 3, Renard, C1 = mu_s, C2 = mu_d, C3 = mu_max, C4 = mu_min,
     * C5 = Vcr1, C6 = Vcr2 (0 < C5 < C6), xi = (v - C5)/(C6 - C5):
     *   v <= C5:      mu = C1 + (C3 - C1) (v/C5) (2 - v/C5)
     *   C5 < v < C6:  mu = C3 + (C4 - C3) xi^2 (3 - 2 xi)
     *   v >= C6:      mu = C2 - (C2 - C4) / (1 + (C2 - C4) (v - C6)^2)
     * continuous: mu(C5) = C3 from both sides (v/C5 = 1, xi = 0) and
     * mu(C6) = C4 from both sides (xi = 1; 1/(1 + 0)). */
    CT_FRIC_RENARD = 3,
    /* Ifric 4, exponential decay from static to dynamic friction:
     * mu = C1 + (Fric - C1) e^(-C2 v), Fric = mu_s, C1 = mu_d, C2 = decay
     * rate c >= 0 (per unit speed). */
    CT_FRIC_EXPDECAY = 4,
    CT_FRIC_NLAW
} ct_fric_law;

/* Check a law's coefficients: all finite; Renard needs 0 < C5 < C6;
 * exponential decay needs C2 >= 0. CT_ERR_ARG (diag index: the coefficient,
 * 0 = Fric) otherwise. */
int ct_friction_check(int law, const ct_real coef[7], ct_diag *diag);

/* mu for one (pressure, speed); negative speed is taken as its magnitude. */
ct_real ct_friction_mu1(int law, const ct_real coef[7], ct_real pressure, ct_real speed);

/* mu[k] for every pair; pressure may be NULL for laws that do not use it
 * (Coulomb, Renard, exponential decay; taken as 0). CT_ERR_ARG for a NaN or
 * infinite coefficient (ct_friction_check's other rules are not applied);
 * CT_ERR_NONFINITE for a NaN or infinite speed (every law but Coulomb) or
 * pressure (the polynomial and Darmstad laws), or a law whose value
 * overflows (to +-inf, or NaN through an exponential; ct_friction_mu1 gives
 * 0 or +inf there): mu is then unspecified. The speed and the pressure are
 * the kernel's only per-pair inputs; no index is reported. */
int ct_friction_mu(ct_idx npair, int law, const ct_real coef[7], const ct_real *pressure,
                   const ct_real *speed, ct_real *mu);

/*
 * Filter coefficient alpha of F_t = alpha F_new + (1 - alpha) F_old:
 * Ifiltr 0: 1 (no filter); 1: Xfreq; 2: 2 pi / Xfreq; 3: 2 pi Xfreq dt.
 * alpha is kept in (0, 1]: values above 1 become 1; a value that is not
 * positive (Xfreq <= 0, NaN) disables the filter (alpha = 1); an unknown
 * ifiltr gives 1 too.
 */
ct_real ct_filter_alpha(int ifiltr, ct_real xfreq, ct_real dt);

/*
 * Tangential force with an elastic predictor and return to the cone, per
 * pair, on the history arrays ft (in: last step's force; out: the new one):
 *   1. the old force loses its normal component (the tangent plane turns):
 *      F_o = F_old - (F_old . n) n;
 *   2. tangential slip velocity v_t = v - (v . n) n and the elastic trial
 *      F* = F_o - K_t v_t dt (the brief's F_old + K_t v_t dt with v_t the
 *      main-relative-to-secondary velocity);
 *   3. return: |F*| <= mu fn: stick, F = F*; else slip, F = mu fn F* / |F*|;
 *   4. filter (alpha < 1): F = alpha F + (1 - alpha) F_o, then scaled back
 *      into the cone if it left it (so |F| <= mu fn always).
 * dissip[k] = |F| s with s = max(0, |F*| - mu fn) / K_t the slip of the
 * step: the work of the slipping part (>= 0; mu fn |v_t| dt in steady
 * sliding), with the slip taken from v alone: a one-step estimate, first
 * order in the step; an energy balance takes ct_friction_work's books
 * instead. Pairs with fn <= 0 (out of contact) get F = 0, dissip 0.
 * mu (per pair) may be NULL to use mu0; kt may be NULL to use kt0; dissip
 * may be NULL. fn, mu, kt NaN or negative (-inf too) count as 0 (fn or mu:
 * no friction force; kt: no elastic increment, the old force is kept
 * within the cone).
 * CT_ERR_ARG for a negative count, NULL required arrays, dt NaN, infinite
 * or negative, or alpha outside (0, 1]. CT_ERR_NONFINITE (docs/fuzz F15)
 * for +inf in fn, mu, kt (or mu0, kt0 standing for them), a NaN or
 * infinite normal, velocity or old force, or an overflow (the trial
 * force's square, the cone mu fn, the filtered force's square): checked
 * for every pair, in the loop that computes them; no index is reported,
 * and the forces (the history) are then unspecified: the step is to be
 * discarded. The dissipation is not checked (ct_force.h: finite or +inf).
 */
int ct_friction_step(ct_idx npair, const ct_real *nx, const ct_real *ny, const ct_real *nz,
                     const ct_real *vx, const ct_real *vy, const ct_real *vz,
                     const ct_real *fn, const ct_real *mu, ct_real mu0, const ct_real *kt,
                     ct_real kt0, ct_real dt, ct_real alpha, ct_real *ftx, ct_real *fty,
                     ct_real *ftz, ct_real *dissip);

/*
 * The fused fast path: the linear penalty force with normal damping
 * (exactly ct_normal_force) and the Coulomb friction step (exactly
 * ct_friction_step with fn the normal force just computed), in one pass
 * that reads each input once and writes each output once. The results are
 * bit-identical to calling ct_normal_force(npair, p, nx, ny, nz, vn, K, K0,
 * ms, mm, viss, dt, fx, fy, fz, fn, energy, dissip) and then
 * ct_friction_step(npair, nx, ny, nz, vx, vy, vz, fn, mu, mu0, kt, kt0, dt,
 * alpha, ftx, fty, ftz, fdissip), for any thread count.
 *
 * v = (vx, vy, vz) is the velocity of the secondary node relative to the
 * contact point (ct_friction_step); vn may be NULL to use its normal
 * component v . n (computed as v0 n0 + v1 n1 + v2 n2), which saves a stream
 * when the caller has no separate normal velocity. K, mm, mu, kt may be
 * NULL (scalar K0, secondary mass only, mu0, kt0). fn, energy, dissip
 * (normal damping work) and fdissip (friction work) may be NULL; fx, fy, fz
 * receive the normal force vector and ftx, fty, ftz (in: last step's
 * tangential force, out: the new one) the tangential force, both on the
 * secondary node. CT_ERR_ARG and CT_ERR_NONFINITE as in the two kernels,
 * with one difference: the normal must be the unit vector the conventions
 * ask for, since the check takes the first component of the normal force
 * vector only (it covers fn; the friction trial covers the normal); a
 * component fn n_i that overflows only because |n_i| > 1 is not detected.
 */
int ct_pair_force_linear_coulomb(
    ct_idx npair, const ct_real *p, const ct_real *nx, const ct_real *ny, const ct_real *nz,
    const ct_real *vx, const ct_real *vy, const ct_real *vz, const ct_real *vn,
    const ct_real *K, ct_real K0, const ct_real *ms, const ct_real *mm, ct_real viss,
    const ct_real *mu, ct_real mu0, const ct_real *kt, ct_real kt0, ct_real dt,
    ct_real alpha, ct_real *fx, ct_real *fy, ct_real *fz, ct_real *fn, ct_real *energy,
    ct_real *dissip, ct_real *ftx, ct_real *fty, ct_real *ftz, ct_real *fdissip);

/*
 * Friction's books for an energy balance of the central difference (as
 * ct_damping_work): a step's dissipation is minus the friction force's work
 * by the trapezoidal rule, -(F_old + F) . v dt / 2 (F the pair's tangential
 * force, the history ct_friction_step updates; v the relative velocity that
 * led to x(n), dt that step), less the change of the elastic predictor's
 * spring energy |F|^2 / (2 K_t), which is stored energy. Called twice per
 * step: before ct_friction_step (after = 0: F the history it starts from;
 * dissip[k] gets that half and the spring energy given back) and after it
 * (after = 1: F the new force; dissip[k] gets the rest, energy[k] (may be
 * NULL) the spring energy added to it). kt per pair, or NULL for kt0; a
 * spring of stiffness <= 0 holds nothing. On the driver's sliding block the
 * slip figure's energy error was first order in the step (-2.19e-3 at
 * dt_scale 0.9), these books' second order (-3.6e-4). A step's value may
 * be negative (a spring giving back what it stored). CT_ERR_ARG for a
 * negative count, NULL arrays (energy and kt excepted) or dt NaN, infinite
 * or negative.
 */
int ct_friction_work(ct_idx npair, const ct_real *vx, const ct_real *vy, const ct_real *vz,
                     const ct_real *ftx, const ct_real *fty, const ct_real *ftz,
                     const ct_real *kt, ct_real kt0, ct_real dt, int after, ct_real *dissip,
                     ct_real *energy);

/* Total friction dissipation of a step: ct_sum_ordered(npair, dissip)
 * (bit-identical for any thread count). */
double ct_friction_dissipation(ct_idx npair, const ct_real *dissip);

/*
 * Match a new pair list against an old one by the key (node, seg): both
 * lists strictly ascending by node then seg (the canonical order of the
 * search when the secondary list is sorted; any key with that order works,
 * e.g. the secondary position instead of the node). old_of_new[k] receives
 * the old index of new pair k, or -1. The new list is split into blocks
 * (one per thread); each block finds its start in the old list by binary
 * search and merge-walks from there. CT_ERR_ARG when a list is not strictly
 * ascending (index of the first offender in diag: new list index, or
 * -1 - old index).
 */
int ct_pair_match(ct_idx nold, const ct_idx *old_node, const ct_idx *old_seg, ct_idx nnew,
                  const ct_idx *new_node, const ct_idx *new_seg, ct_idx *old_of_new,
                  ct_diag *diag);

/* dst[k] = src[old_of_new[k]], or fill when old_of_new[k] < 0: the gather
 * that carries any per-pair state (friction history, p_prev, fcap, p0) to
 * the new list. src and dst must not overlap. old_of_new is not checked
 * against src's length (not passed): it must come from ct_pair_match or
 * ct_friction_remap on the list src belongs to. */
int ct_pair_remap(ct_idx nnew, const ct_idx *old_of_new, const ct_real *src, ct_real fill,
                  ct_real *dst);

/* Friction history across a re-sort: match, then remap the three force
 * components (pairs not found start at zero). */
int ct_friction_remap(ct_idx nold, const ct_idx *old_node, const ct_idx *old_seg,
                      const ct_real *old_fx, const ct_real *old_fy, const ct_real *old_fz,
                      ct_idx nnew, const ct_idx *new_node, const ct_idx *new_seg,
                      ct_real *new_fx, ct_real *new_fy, ct_real *new_fz,
                      ct_idx *old_of_new, ct_diag *diag);

#ifdef __cplusplus
}
#endif

#endif /* CT_FRICTION_H */
