/*
 * iface_pass_force.c -- the per-pair stages of a node-segment pass
 * (iface_pass.c runs them in order): the relative velocity at the contact
 * point, the initial-penetration state, the normal law with damping,
 * friction, and the time-step limits, with the nodal contact step over the
 * interface's passes.
 */
#include "iface_internal.h"

#include "ct_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Relative velocity at the contact point, its normal part, the main mass
 * at the contact point (sum h_i m_i) and, for pressure-dependent friction,
 * the segment area. */
int ctdi_pass_kinematics(ctdi_pass *p, ct_idx n, const ct_idx *restrict node,
                         const ct_real *restrict x, const ct_real *restrict y,
                         const ct_real *restrict z, const ct_real *restrict vx,
                         const ct_real *restrict vy, const ct_real *restrict vz,
                         const ct_real *restrict m, int want_area)
{
    const ct_idx *restrict s1 = p->s[0], *restrict s2 = p->s[1], *restrict s3 = p->s[2],
                           *restrict s4 = p->s[3];
    const ct_contact_geo *g = &p->geo;
    ct_real *restrict area = p->r[CTDI_R_PRS];
    int rc = ct_relative_velocity(n, node, s1, s2, s3, s4, g->h1, g->h2, g->h3, g->h4, g->nx,
                                  g->ny, g->nz, vx, vy, vz, m, p->r[CTDI_R_VRX],
                                  p->r[CTDI_R_VRY], p->r[CTDI_R_VRZ], p->r[CTDI_R_VN],
                                  p->r[CTDI_R_MM]);
    if (rc != CT_OK || !want_area)
        return rc;
    CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++) {
        ct_idx i1 = s1[k], i2 = s2[k], i3 = s3[k], i4 = s4[k];
        ct_real ax = x[i3] - x[i1], ay = y[i3] - y[i1], az = z[i3] - z[i1];
        ct_real bx = x[i4] - x[i2], by = y[i4] - y[i2], bz = z[i4] - z[i2];
        if (i4 == i3) {
            bx = x[i3] - x[i2];
            by = y[i3] - y[i2];
            bz = z[i3] - z[i2];
            ax = x[i2] - x[i1];
            ay = y[i2] - y[i1];
            az = z[i2] - z[i1];
        }
        ct_real cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
        area[k] = (ct_real)0.5 * CTI_SQRT(cx * cx + cy * cy + cz * cz);
    });
    return CT_OK;
}

/* Friction: mu per pair when the law needs it, the step, the total force. */
int ctdi_pass_friction(ctd_iface *it, ctdi_pass *p, ct_idx n, ct_real dt)
{
    ct_real **r = p->r;
    ct_real **ft = p->st[p->cur];
    const ct_contact_geo *g = &p->geo;
    const ct_real *mu = NULL;
    int law = it->fric_law;
    if (law != CT_FRIC_COULOMB) {
        ct_real *restrict spd = r[CTDI_R_SPD], *restrict prs = r[CTDI_R_PRS];
        const ct_real *restrict rx = r[CTDI_R_VRX], *restrict ry = r[CTDI_R_VRY],
                                *restrict rz = r[CTDI_R_VRZ], *restrict vn = r[CTDI_R_VN],
                                *restrict nx = g->nx, *restrict ny = g->ny,
                                *restrict nz = g->nz, *restrict fn = r[CTDI_R_FN];
        const int usep = law == CT_FRIC_POLY || law == CT_FRIC_DARMSTAD;
        CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < n; k++) {
            ct_real tx = rx[k] - vn[k] * nx[k], ty = ry[k] - vn[k] * ny[k],
                    tz = rz[k] - vn[k] * nz[k];
            spd[k] = CTI_SQRT(tx * tx + ty * ty + tz * tz);
            prs[k] = usep && prs[k] > 0 ? fn[k] / prs[k] : 0;
        });
        int rc = ct_friction_mu(n, law, it->coef, prs, spd, r[CTDI_R_MU]);
        if (rc != CT_OK)
            return rc;
        mu = r[CTDI_R_MU];
    }
    {
        ct_real *restrict kt = r[CTDI_R_KT];
        const ct_real *restrict K = r[CTDI_R_K];
        const ct_real s = it->cfg.kt_scale;
        CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < n; k++)
            kt[k] = s * K[k];
        );
    }
    ct_real alpha = ct_filter_alpha(it->cfg.Ifiltr, it->cfg.Xfreq, dt);
    /* The books (ct_friction_work): the last step's force's half first. */
    int rc = ct_friction_work(n, r[CTDI_R_VRX], r[CTDI_R_VRY], r[CTDI_R_VRZ], ft[CTDI_ST_FTX],
                              ft[CTDI_ST_FTY], ft[CTDI_ST_FTZ], r[CTDI_R_KT], 0, dt, 0,
                              r[CTDI_R_FD], NULL);
    if (rc != CT_OK)
        return rc;
    rc = ct_friction_step(n, g->nx, g->ny, g->nz, r[CTDI_R_VRX], r[CTDI_R_VRY], r[CTDI_R_VRZ],
                          r[CTDI_R_FN], mu, it->coef[0], r[CTDI_R_KT], 0, dt, alpha,
                          ft[CTDI_ST_FTX], ft[CTDI_ST_FTY], ft[CTDI_ST_FTZ], NULL);
    if (rc != CT_OK)
        return rc;
    rc = ct_friction_work(n, r[CTDI_R_VRX], r[CTDI_R_VRY], r[CTDI_R_VRZ], ft[CTDI_ST_FTX],
                          ft[CTDI_ST_FTY], ft[CTDI_ST_FTZ], r[CTDI_R_KT], 0, dt, 1,
                          r[CTDI_R_FD], r[CTDI_R_EN]);
    if (rc != CT_OK)
        return rc;
    ct_real *restrict fx = r[CTDI_R_FX], *restrict fy = r[CTDI_R_FY], *restrict fz = r[CTDI_R_FZ];
    const ct_real *restrict tx = ft[CTDI_ST_FTX], *restrict ty = ft[CTDI_ST_FTY],
                            *restrict tz = ft[CTDI_ST_FTZ];
    CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
    for (ct_idx k = 0; k < n; k++) {
        fx[k] += tx[k];
        fy[k] += ty[k];
        fz[k] += tz[k];
    });
    return CT_OK;
}

/* Initial penetration at the first active cycle (TYPE24). */
void ctdi_pass_initial_state(ctd_iface *it, ctdi_pass *p, ct_idx n)
{
    ct_real **st = p->st[p->cur];
    const ct_real *restrict pen = p->geo.pen;
    ct_real *restrict pp = st[CTDI_ST_PPREV];
    /* Start without blending: the initial state is Inacti's business. */
    for (ct_idx k = 0; k < n; k++)
        pp[k] = pen[k] > 0 ? pen[k] : 0;
    if (it->cfg.Ipen0 != 0)
        return;
    int mode = it->cfg.Inacti != 0 ? CT_INACTI_SUBTRACT : CT_INACTI_IGNORE;
    int nd = ct_initial_penetration(n, mode, pen, it->cfg.Ipen_max, st[CTDI_ST_P0], p->iflag);
    if (nd > 0)
        it->deactivated += nd;
    ct_real *restrict act = st[CTDI_ST_ACT];
    for (ct_idx k = 0; k < n; k++) {
        act[k] = (ct_real)p->iflag[k];
        if (mode == CT_INACTI_SUBTRACT && pp[k] > 0)
            pp[k] = 0; /* q = p - p0 = 0 at the start */
    }
}

int ctdi_pass_normal_force(ctd_iface *it, ctdi_pass *p, ct_idx n, ct_real dt)
{
    ct_real **r = p->r, **st = p->st[p->cur];
    const ct_contact_geo *g = &p->geo;
    int rc;
    if (p->law == CTDI_LAW_TYPE7) {
        rc = ct_penalty_type7(n, g->pen, g->gap, r[CTDI_R_K], r[CTDI_R_FEL], r[CTDI_R_KTAN],
                              r[CTDI_R_EN], p->iflag);
        /* The law keeps no history, but p_prev marks the pairs that carried
         * their node this step, so that the friction force follows the
         * contact to the next segment (pair_select.c). */
        const ct_real *restrict pen = g->pen;
        ct_real *restrict pp = st[CTDI_ST_PPREV];
        CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < n; k++)
            pp[k] = pen[k] > 0 ? pen[k] : 0;
        );
    } else if (p->law == CTDI_LAW_TYPE6) {
        rc = ctdi_type6_normal(it, p, n);
    } else {
        /* The blending tells a jump of the penetration from motion by
         * |v| dt (ct_penalty_linear reads only the magnitude): the relative
         * speed, not its normal part, bounds how fast a penetration can
         * grow (the distance to a surface changes at most as fast as the
         * node moves against it). The normal part alone misses the motion
         * of a node sliding past a convex vertex or edge, where the normal
         * turns within a step: it took that motion for a jump and cut the
         * force (validation case g). The speed goes in the friction
         * speed scratch, which ctdi_pass_friction() fills later. */
        ct_real *restrict spd = r[CTDI_R_SPD];
        const ct_real *restrict ux = r[CTDI_R_VRX], *restrict uy = r[CTDI_R_VRY],
                                *restrict uz = r[CTDI_R_VRZ];
        CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < n; k++)
            spd[k] = CTI_SQRT(ux[k] * ux[k] + uy[k] * uy[k] + uz[k] * uz[k]);
        );
        ct_real *p0 = it->cfg.Inacti != 0 && it->cfg.Ipen0 == 0 ? st[CTDI_ST_P0] : NULL;
        rc = ct_penalty_linear(n, g->pen, spd, r[CTDI_R_K], dt, p0, st[CTDI_ST_PPREV],
                               st[CTDI_ST_FCAP], st[CTDI_ST_QJUMP], r[CTDI_R_FEL],
                               r[CTDI_R_EN]);
        const ct_real *restrict pen = g->pen, *restrict K = r[CTDI_R_K];
        ct_real *restrict kt = r[CTDI_R_KTAN];
        CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < n; k++)
            kt[k] = pen[k] > 0 ? K[k] : 0;
        );
    }
    if (rc != CT_OK)
        return rc;
    rc = ct_normal_finish(n, g->pen, r[CTDI_R_FEL], r[CTDI_R_KTAN], r[CTDI_R_VN], r[CTDI_R_MS],
                          r[CTDI_R_MM], it->cfg.VisS, dt, g->nx, g->ny, g->nz, r[CTDI_R_FN],
                          r[CTDI_R_FX], r[CTDI_R_FY], r[CTDI_R_FZ], r[CTDI_R_DD]);
    if (rc != CT_OK || !(it->cfg.VisS > 0))
        return rc;
    /* The damper's books: its work by the trapezoidal rule. */
    return ct_damping_work(n, g->pen, r[CTDI_R_FN], r[CTDI_R_FEL], r[CTDI_R_VN], dt,
                           st[CTDI_ST_FDAMP], r[CTDI_R_DD]);
}

/* Time-step limits over the pairs that enter the step (ctdi_dt_counts:
 * in contact, or open within the band and two steps' approach of it). The
 * nodal step: each such carrying pair's stiffness (the linear law's K even
 * while the pair is open, so that the step does not jump back to the
 * element step in a cycle of chatter; TYPE7's tangent stiffness, K0 when
 * open) is spread onto its nodes with the weights |w| (1 on the secondary
 * node, h_i on the segment's), summed
 * per node over the pairs and passes, and ctdi_nodal_finish takes
 * sqrt(2 m / (kelem + kc)) per node: the Gershgorin bound of the contact
 * springs on the lumped masses. A node pressed by several pairs, or loaded
 * both as a secondary node and as a segment's node (surface to surface,
 * self contact), gets the sum of its springs. */
int ctdi_pass_timestep(ctd_iface *it, ctdi_pass *p, ct_idx n, const ct_real *m,
                       ctd_iface_report *rep)
{
    const ct_real dt = it->dt_max, band = it->band;
    const ct_real *restrict gap = p->geo.gap, *restrict rx = p->r[CTDI_R_VRX],
                            *restrict ry = p->r[CTDI_R_VRY], *restrict rz = p->r[CTDI_R_VRZ],
                            *restrict kt = p->r[CTDI_R_KTAN], *restrict pen = p->geo.pen,
                            *restrict dist = p->geo.dist;
    ct_real dmin;
    ct_idx imin;
    int rc = CT_OK;
    if (p->law == CTDI_LAW_TYPE6) {
        /* Rigid bodies: the curve's step on the smaller body mass. */
        dmin = ctdi_type6_dt(it, p, m);
        if (dmin < rep->dt_curve)
            rep->dt_curve = dmin;
    } else {
        const ct_real *restrict ks =
            p->law == CTDI_LAW_LINEAR ? p->r[CTDI_R_K] : p->r[CTDI_R_KTAN];
        const uint8_t *restrict carry = p->carry;
        ct_real *restrict kdt = p->r[CTDI_R_KDT];
        CTI_PAR_FOR_SIMD(n > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < n; k++) {
            const ct_real v2 = rx[k] * rx[k] + ry[k] * ry[k] + rz[k] * rz[k];
            const int counts = ctdi_dt_counts(pen[k], dist[k], gap[k], v2, dt, band);
            kdt[k] = carry[k] && counts ? ks[k] : 0;
        });
        ct_asm_map map = ct_asm_map_nodeseg(n, p->pairs[p->cur].node, p->s[0], p->s[1],
                                            p->s[2], p->s[3]);
        for (int s = 0; s < map.nslot; s++)
            map.sign[s] = 1;
        const ct_real *const w[5] = {NULL, p->geo.h1, p->geo.h2, p->geo.h3, p->geo.h4};
        rc = ct_assemble_scalar(&p->ws, it->cfg.asm_variant, &map, w, kdt, it->nnode, it->kc);
        if (rc != CT_OK)
            return rc;
    }
    if (p->law == CTDI_LAW_TYPE7) {
        rc = ct_dt_type7_kinematic(n, p->geo.pen, p->geo.gap, p->r[CTDI_R_VN], NULL, &dmin,
                                   &imin);
        if (rc != CT_OK)
            return rc;
        if (dmin < rep->dt_kin)
            rep->dt_kin = dmin;
    }
    ct_real gmin = CT_DT_NONE, v2max = 0, kmax = 0;
    CTI_PAR_FOR(n > CTDI_PAR_MIN,
                (schedule(static) reduction(min : gmin) reduction(max : v2max, kmax)),
    for (ct_idx k = 0; k < n; k++) {
        ct_real v2 = rx[k] * rx[k] + ry[k] * ry[k] + rz[k] * rz[k];
        if (!ctdi_dt_counts(pen[k], dist[k], gap[k], v2, dt, band))
            continue;
        if (gap[k] > 0 && gap[k] < gmin)
            gmin = gap[k];
        if (v2 > v2max)
            v2max = v2;
        if (kt[k] > kmax)
            kmax = kt[k];
    });
    ctdi_report_limits(rep, kmax, gmin, v2max);
    return CT_OK;
}

void ctdi_nodal_begin(ctd_iface *it)
{
    if (!it->kc)
        return;
    for (int i = 0; i < it->npass; i++) {
        const ctdi_pass *p = &it->pass[i];
        ct_real *restrict kc = it->kc;
        const ct_idx *restrict sec = p->sec, *restrict mn = p->mainn;
        CTI_PAR_FOR_SIMD(p->nsec > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < p->nsec; k++)
            kc[sec[k]] = 0;
        );
        if (p->mainn_rs == p->sec) /* self contact: the same nodes */
            continue;
        CTI_PAR_FOR_SIMD(p->nmain > CTDI_PAR_MIN, (schedule(static)),
        for (ct_idx k = 0; k < p->nmain; k++)
            kc[mn[k]] = 0;
        );
    }
}

/* The nodal step of node i (CT_DT_NONE without contact stiffness or mass). */
static inline double node_dt(const ct_real *kc, const ct_real *kelem, const ct_real *m, ct_idx i)
{
    double k = (double)kc[i] + (kelem ? (double)kelem[i] : 0);
    return kc[i] > 0 && m[i] > 0 ? sqrt(2.0 * (double)m[i] / k) : (double)CT_DT_NONE;
}

void ctdi_nodal_finish(ctd_iface *it, const ct_real *m, ctd_iface_report *rep)
{
    if (!it->kc)
        return;
    const ct_real *kc = it->kc, *ke = it->kelem;
    double dmin = CT_DT_NONE;
    for (int i = 0; i < it->npass; i++) {
        const ctdi_pass *p = &it->pass[i];
        /* Self contact: one side, its nodes are the other's. */
        const int nside = p->mainn_rs == p->sec ? 1 : 2;
        for (int side = 0; side < nside; side++) {
            const ct_idx n = side ? p->nmain : p->nsec, *restrict l = side ? p->mainn : p->sec;
            double d = CT_DT_NONE;
            CTI_PAR_FOR(n > CTDI_PAR_MIN, (schedule(static) reduction(min : d)),
            for (ct_idx k = 0; k < n; k++) {
                double v = node_dt(kc, ke, m, l[k]);
                d = v < d ? v : d;
            });
            if (d < dmin) {
                /* The first node (in this list's order) that reaches it. */
                dmin = d;
                for (ct_idx k = 0; k < n; k++)
                    if (node_dt(kc, ke, m, l[k]) == d) {
                        rep->dt_node = l[k];
                        break;
                    }
            }
        }
    }
    if (dmin < CT_DT_NONE) {
        ct_real d = (ct_real)(dmin * ctdi_damped_dt_factor((double)it->cfg.VisS));
        if (d < rep->dt_nodal)
            rep->dt_nodal = d;
    }
}
