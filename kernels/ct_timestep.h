/*
 * ct_timestep.h -- the stable time step contribution of contact, part of
 * contact.h (DESIGN.md section 7).
 *
 * Every array kernel returns the minimum step through *dtmin and the index
 * where it occurs through *imin (ties: the smallest index, so the answer is
 * the same for any thread count). An entry that sets no limit counts as
 * CT_DT_NONE; when no entry sets a limit, *dtmin = CT_DT_NONE and
 * *imin = -1. A NaN or infinite input of an entry (for ct_dt_nodal its
 * mass or its total stiffness, for the TYPE7 step p, g or vn, whether or not
 * the entry sets a limit) gives CT_ERR_NONFINITE with *imin the smallest
 * such index: an infinite stiffness or approach speed would otherwise give
 * a zero step, on which a solver cannot advance. dt (per entry, may be NULL) receives
 * every entry's step.
 */
#ifndef CT_TIMESTEP_H
#define CT_TIMESTEP_H

#ifdef __cplusplus
extern "C" {
#endif

/* "No limit" (1e30 in both precisions). */
#define CT_DT_NONE ((ct_real)1e30)

/*
 * Nodal step dt_i = sqrt(2 m / (K_elem + K_contact)) for n entries. With
 * idx == NULL entry i uses m[i] and kelem[i]; with idx given (a per-pair
 * call), entry i uses m[idx[i]] and kelem[idx[i]] (idx not range-checked).
 * kelem may be NULL (0). kcont[i] is the contact tangent stiffness of entry
 * i (K for the linear law, K0 g^2/(g - p)^2 for TYPE7: ct_type7_tangent).
 * A total stiffness <= 0 or a mass <= 0 sets no limit.
 */
int ct_dt_nodal(ct_idx n, const ct_idx *idx, const ct_real *m, const ct_real *kelem,
                const ct_real *kcont, ct_real *dt, ct_real *dtmin, ct_idx *imin);

/* TYPE7 tangent dF/dp = K0 g^2/(g - p)^2 = K0 / r^2, r = 1 - p/g, with p
 * limited to the deactivation point g (1 - CT_TYPE7_RMIN) (the largest
 * tangent the law reaches); K0 for p <= 0; 0 for invalid g or K0. */
ct_real ct_type7_tangent(ct_real K0, ct_real g, ct_real p);

/*
 * TYPE7 kinematic step dt = (g - p) / (2 (-vn)) per pair: the time for an
 * approaching node (vn < 0) to cover half its remaining distance to the
 * mid-surface. Separating or still nodes (vn >= 0), pairs out of contact
 * (p <= 0) and deactivated pairs (p >= g (1 - CT_TYPE7_RMIN)) set no limit.
 */
int ct_dt_type7_kinematic(ct_idx npair, const ct_real *p, const ct_real *g,
                          const ct_real *vn, ct_real *dt, ct_real *dtmin, ct_idx *imin);

/* TYPE6 step 0.1 sqrt(M_min / K) with K = max(f'(p), f(p)/p) from the curve
 * at the largest penetration p (> 0); CT_DT_NONE when K <= 0 or p <= 0.
 * M_min = min of the two rigid-body masses. */
ct_real ct_dt_type6(ct_real mmin, ct_real p, ct_idx ncurve, const ct_real *cx,
                    const ct_real *cy);

/* Tunnelling limit 0.9 gap_min / |v_rel,max| (CT_DT_NONE when the speed is
 * 0 or NaN or the gap is not positive or NaN; 0 for an infinite speed: the
 * caller checks the scalars it passes). */
ct_real ct_dt_tunnel(ct_real gap_min, ct_real vrel_max);

#ifdef __cplusplus
}
#endif

#endif /* CT_TIMESTEP_H */
