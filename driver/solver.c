/*
 * solver.c -- the central-difference time loop (solver.h): forces,
 * time step, kick with boundary conditions, rigid bodies, drift, and the
 * checks that stop an unstable run. The passes over the nodes are in
 * solver_nodes.c; setting up and tearing down in solver_init.c; energies,
 * output and the report in solver_report.c.
 */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "solver.h"
#include "solver_internal.h"

#include "ct_internal.h"

#include "wtime.h"

/* ---- One cycle's pieces ------------------------------------------------------ */

static void fail(ctd_solver *s, const char *status, int code, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void fail(ctd_solver *s, const char *status, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->message, sizeof s->message, fmt, ap);
    va_end(ap);
    s->status = status;
    s->exit_code = code;
}

/* Element forces into w->fx.. and the internal energy; 0 or -1 (failed). */
static int element_forces(ctd_solver *s)
{
    ctd_model *m = s->model;
    cti_solver_work *w = s->w;
    double u = 0;
    for (int k = 0; k < m->nset; k++) {
        ctd_model_set *st = &m->set[k];
        ct_diag d = {0, -1, ""};
        int rc;
        double e = 0;
        if (st->element == CTD_ELEM_BRICK) {
            rc = ctd_brick_forces(&st->brick, s->x, s->y, s->z, w->fx, w->fy, w->fz, &d);
            e = rc ? 0 : ctd_brick_energy(&st->brick);
        } else if (st->element == CTD_ELEM_SHELL) {
            rc = ctd_shell_forces(&st->shell, s->x, s->y, s->z, w->fx, w->fy, w->fz, &e);
        } else {
            rc = ctd_truss_forces(&st->truss, s->x, s->y, s->z, w->fx, w->fy, w->fz, &d);
            e = rc ? 0 : ctd_truss_energy(&st->truss);
        }
        if (rc) {
            char where[96] = "an element";
            if (d.index >= 0)
                snprintf(where, sizeof where, "element %lld", (long long)d.index);
            fail(s, "unstable", CTD_EXIT_UNSTABLE,
                 "cycle %lld (t = %.6g): %s of part %lld (%s) failed: %s%s%s",
                 (long long)s->cycle, s->time, where, (long long)st->part,
                 ctd_element_name(st->element), ct_strerror(rc), d.msg[0] ? ": " : "", d.msg);
            return -1;
        }
        u += e;
    }
    w->internal = u;
    return 0;
}

/* The interfaces: contact forces into w->fc.. (zeroed by
 * cti_solver_forces_begin, added to w->f.. by cti_solver_forces_end);
 * dt_bodies is stable_dt_bodies at x(n). */
static int contact_forces(ctd_solver *s, int want_fields, double dt_bodies)
{
    cti_solver_work *w = s->w;
    ct_idx nn = s->nnode;
    if (!s->nhook)
        return 0;
    /* The largest step that can follow (stable_dt's other limits, the
     * output interval): the interfaces' open pairs count in their step
     * when they can close their clearance in two such steps. */
    double dt_max = s->dt_scale * dt_bodies;
    if (s->every > 0 && s->every < dt_max)
        dt_max = s->every;
    ctd_state st = {s->time, w->dt_prev, s->cycle, nn, s->x, s->y, s->z, s->vx, s->vy, s->vz,
                    s->model->mesh.nodes.m, s->model->node_part,
                    dt_max < CTD_DT_NONE ? dt_max : 0};
    double ec = 0;
    for (int i = 0; i < s->nhook; i++) {
        ctd_contact_report *r = &s->rep[i];
        memset(r, 0, sizeof *r);
        r->want_fields = want_fields;
        r->pen = w->pen;
        r->node_active = w->nact;
        r->bad_node = -1;
        int rc = s->hooks[i].contact_step(s->hooks[i].ctx, &st, w->fcx, w->fcy, w->fcz, r);
        if (rc) {
            int unstable = rc == CT_ERR_NONFINITE || rc == CT_ERR_DEGENERATE || rc == CT_ERR_NOCONV;
            /* Out of memory (an interface's workspaces grow at its first
             * search and whenever its pairs outgrow them) exits as an
             * output failure does: the input is not at fault. Anything
             * else is a search that found more pairs than an index holds
             * (a gap far above the element size: the input), or an
             * interface given bad arrays. */
            int nomem = rc == CT_ERR_NOMEM;
            char node[64] = "";
            if (r->bad_node >= 0 && r->bad_node < nn)
                snprintf(node, sizeof node, " at node %lld",
                         (long long)s->model->node_id[r->bad_node]);
            fail(s, unstable ? "unstable" : (nomem ? "out of memory" : "error"),
                 unstable ? CTD_EXIT_UNSTABLE : (nomem ? CTD_EXIT_OUTPUT : CTD_EXIT_BADINPUT),
                 "cycle %lld (t = %.6g): interface %s (type %d) failed%s: %s%s%s",
                 (long long)s->cycle, s->time, w->if_names[i], s->hooks[i].type, node,
                 ct_strerror(rc), r->msg[0] ? ": " : "", r->msg);
            return -1;
        }
        ec += r->energy;
        w->damping += r->damping;
        w->friction += r->friction;
        s->timers.search += r->t_search;
        s->timers.narrow += r->t_narrow;
        s->timers.force += r->t_force;
        s->timers.assembly += r->t_assembly;
        w->if_force[i] = r->force;
        w->if_active[i] = r->active;
        w->if_resorts[i] = r->resorts;
        w->if_margin[i] = r->margin;
        if (r->force > s->if_force_max[i])
            s->if_force_max[i] = r->force;
        if (r->active > s->if_active_max[i])
            s->if_active_max[i] = r->active;
    }
    w->contact = ec;
    return 0;
}

static void fail_node(ctd_solver *s, ct_idx i, const char *what)
{
    /* Before the first step no time step is to blame: the input is (loads
     * or gravity past the range of the numbers, an interface's force). */
    if (s->cycle == 0)
        fail(s, "unstable", CTD_EXIT_UNSTABLE,
             "cycle 0 (t = %.6g): node %lld (part %d) has a non-finite %s before the first "
             "step: expected loads, gravity and initial state whose forces are finite (two "
             "loads of 1e308 on one node add up to infinity)", s->time,
             (long long)s->model->node_id[i], s->model->node_part[i], what);
    else
        fail(s, "unstable", CTD_EXIT_UNSTABLE,
             "cycle %lld (t = %.6g): node %lld (part %d) has a non-finite %s; the time step "
             "(dt = %.3g) is likely above the stable limit", (long long)s->cycle, s->time,
             (long long)s->model->node_id[i], s->model->node_part[i], what, s->dt);
}

/* The stable step at x(n), before the safety factor, from its part
 * stable_dt_bodies (dt_bodies) and the interfaces' reports. */
static double stable_dt(const ctd_solver *s, double dt_bodies)
{
    double dt = dt_bodies;
    for (int i = 0; i < s->nhook; i++)
        if (s->rep[i].dt_limit > 0 && s->rep[i].dt_limit < dt)
            dt = s->rep[i].dt_limit;
    return dt;
}

/* Its part from the elements (at x(n), after element_forces) and the
 * rigid bodies' rotation: all but the interfaces. */
static double stable_dt_bodies(ctd_solver *s)
{
    ctd_model *m = s->model;
    double dt = CTD_DT_NONE;
    for (int k = 0; k < m->nset; k++) {
        ctd_model_set *st = &m->set[k];
        double d;
        if (st->element == CTD_ELEM_BRICK)
            d = ctd_brick_dt_last(&st->brick); /* from element_forces at x(n) */
        else if (st->element == CTD_ELEM_SHELL)
            d = ctd_shell_dt(&st->shell);
        else
            d = ctd_truss_dt(&st->truss, s->x, s->y, s->z, m->mesh.nodes.m, NULL);
        if (d < dt)
            dt = d;
    }
    for (int b = 0; b < m->nbody; b++) {
        const double *om = m->body[b].rigid.omega;
        double wn = sqrt(om[0] * om[0] + om[1] * om[1] + om[2] * om[2]);
        /* The angular velocity at the start comes from L (omega is set by a step). */
        if (s->cycle == 0) {
            const ctd_rigid *r = &m->body[b].rigid;
            double R[9], pi[3], wb[3];
            ctd_rigid_rotation(r, R);
            for (int a = 0; a < 3; a++) {
                pi[a] = R[a] * r->L[0] + R[3 + a] * r->L[1] + R[6 + a] * r->L[2];
                wb[a] = r->Iinv[a] * pi[a];
            }
            wn = sqrt(wb[0] * wb[0] + wb[1] * wb[1] + wb[2] * wb[2]);
        }
        if (wn > 0 && 0.25 / wn < dt)
            dt = 0.25 / wn;
    }
    return dt;
}

/* The world angular velocity R diag(Iinv) R^T L of body r for the angular
 * momentum L, at its present orientation. */
static void body_omega(const ctd_rigid *r, const double L[3], double om[3])
{
    double R[9], a[3];
    ctd_rigid_rotation(r, R);
    for (int i = 0; i < 3; i++)
        a[i] = (R[i] * L[0] + R[3 + i] * L[1] + R[6 + i] * L[2]) * r->Iinv[i];
    for (int i = 0; i < 3; i++)
        om[i] = R[3 * i] * a[0] + R[3 * i + 1] * a[1] + R[3 * i + 2] * a[2];
}

/* Rigid bodies: force and moment of their nodes' forces, kick (imposed
 * components of driven bodies, with their reaction work). */
static void rigid_kick(ctd_solver *s, double dtk, double dt_new)
{
    ctd_model *m = s->model;
    cti_solver_work *w = s->w;
    for (int b = 0; b < m->nbody; b++) {
        ctd_model_body *bd = &m->body[b];
        ctd_rigid *r = &bd->rigid;
        /* The contact forces' resultant and moment on the body, for their
         * work (contact_work): with the centre's velocity before and after
         * the kick, and the angular velocity of the angular momentum before
         * and after it at the present orientation (the kinetic energy's
         * product form is taken in that frame too; exact for the
         * translation, for the rotation to second order in the step). */
        double Fc[3] = {0, 0, 0}, Tc[3] = {0, 0, 0};
        if (s->nhook) {
            ctd_rigid_clear(r);
            ctd_rigid_accumulate(r, s->x, s->y, s->z, w->fcx, w->fcy, w->fcz);
            for (int d = 0; d < 3; d++) {
                Fc[d] = r->F[d];
                Tc[d] = r->tau[d];
            }
        }
        ctd_rigid_clear(r);
        ctd_rigid_accumulate(r, s->x, s->y, s->z, w->fx, w->fy, w->fz);
        for (int d = 0; d < 3; d++) {
            w->vc_old[b][d] = r->vc[d];
            w->L_old[b][d] = r->L[d];
            r->vc[d] += dtk * r->F[d] / r->mass;
            r->L[d] += dtk * r->tau[d];
        }
        if (bd->driven) {
            for (int d = 0; d < 3; d++) {
                r->L[d] = 0;
                if (!bd->dof[d])
                    continue;
                double R = r->mass * (bd->v[d] - r->vc[d]) / dtk;
                w->w_bc_back += 0.5 * R * w->dt_prev * w->vc_old[b][d];
                w->w_bc_fwd += 0.5 * R * dt_new * bd->v[d];
                r->vc[d] = bd->v[d];
            }
        }
        if (s->nhook) {
            double om0[3], om1[3];
            body_omega(r, w->L_old[b], om0);
            body_omega(r, r->L, om1);
            for (int d = 0; d < 3; d++) {
                w->w_c_back += 0.5 * dtk * (Fc[d] * w->vc_old[b][d] + Tc[d] * om0[d]);
                w->w_c_fwd += 0.5 * dtk * (Fc[d] * r->vc[d] + Tc[d] * om1[d]);
            }
        }
        ctd_rigid_clear(r);
    }
}

/* Drift: the rigid bodies (advance and place their nodes), then the other
 * nodes, in one pass that also finds whether a position is not finite
 * (*bad: the first such node, or -1). Returns -1 when a body failed. */
static int drift(ctd_solver *s, double dt, ct_idx *bad)
{
    ctd_model *m = s->model;
    *bad = -1;
    for (int b = 0; b < m->nbody; b++) {
        ctd_rigid *r = &m->body[b].rigid;
        int rc = ctd_rigid_advance(r, dt);
        if (rc) {
            fail(s, "unstable", CTD_EXIT_UNSTABLE,
                 "cycle %lld (t = %.6g): rigid body %lld (part %lld) failed to advance: %s; "
                 "the time step (dt = %.3g) is likely above the stable limit of its rotation",
                 (long long)s->cycle, s->time, (long long)m->body[b].id,
                 (long long)m->body[b].part, ct_strerror(rc), dt);
            return -1;
        }
        ctd_rigid_set_nodes(r, s->x, s->y, s->z, s->vx, s->vy, s->vz);
    }
    /* Body nodes are placed above and only read there. */
    *bad = cti_solver_drift_nodes(s, dt);
    return 0;
}

static void keep_good(ctd_solver *s)
{
    cti_solver_work *w = s->w;
    size_t b = sizeof(ct_real) * (size_t)s->nnode;
    memcpy(w->gx, s->x, b);
    memcpy(w->gy, s->y, b);
    memcpy(w->gz, s->z, b);
    memcpy(w->gvx, s->vx, b);
    memcpy(w->gvy, s->vy, b);
    memcpy(w->gvz, s->vz, b);
    w->good_time = s->time;
    w->good_cycle = s->cycle;
    w->have_good = 1;
}

/* The node with the largest speed (for a runaway message). */
static ct_idx fastest_node(const ctd_solver *s)
{
    ct_idx best = -1;
    double vmax = -1;
    for (ct_idx i = 0; i < s->nnode; i++) {
        double v2 = (double)s->vx[i] * s->vx[i] + (double)s->vy[i] * s->vy[i] +
                    (double)s->vz[i] * s->vz[i];
        if (v2 > vmax) {
            vmax = v2;
            best = i;
        }
    }
    return best;
}

/* ---- The loop -------------------------------------------------------------------- */

int ctd_solver_run(ctd_solver *s)
{
    ctd_model *m = s->model;
    cti_solver_work *w = s->w;
    const double end = s->end_time, tol = 1e-12 * end;
    double next_out = 0;
    w->t_start = ctd_wtime();
    w->last_progress = w->t_start;
    s->exit_code = CTD_EXIT_OK;
    for (;;) {
        double t0 = ctd_wtime();
        int final = s->time >= end - tol || s->opts.dry ||
                     (s->opts.max_cycles > 0 && s->cycle >= s->opts.max_cycles);
        int out_step = s->time >= next_out - tol || final;
        int check = out_step || s->cycle % 100 == 0;
        /* Forces at x(n). */
        cti_solver_forces_begin(s, out_step);
        if (element_forces(s))
            break;
        double t1 = ctd_wtime();
        s->timers.elements += t1 - t0;
        /* The elements' and bodies' step at x(n), once: the interfaces
         * take the largest step that can follow from it, then stable_dt. */
        const double dt_bodies = stable_dt_bodies(s);
        if (contact_forces(s, out_step, dt_bodies))
            break;
        if (s->cycle == 0 && s->nhook) /* an output cycle: the fields hold them */
            ctd_solver_penetration(s, &s->pen0_count, &s->pen0_max, &s->pen0_node);
        ctd_loads_apply(&w->loads, s->time, s->x, s->y, s->z, w->fx, w->fy, w->fz);
        ct_idx bad = cti_solver_forces_end(s);
        if (bad >= 0) {
            fail_node(s, bad, "force");
            break;
        }
        /* Step, kick, energies. */
        double dt_new = s->dt_scale * stable_dt(s, dt_bodies);
        const int by_output = dt_new > s->every;
        if (by_output)
            dt_new = s->every;
        const double dt_cap = dt_new;
        if (final && s->cycle > 0) {
            /* No step follows: v+ only serves the energies; the same step as
             * before keeps them free of a step-size jump. */
            dt_new = w->dt_prev;
        } else if ((!final || s->opts.dry) && dt_new > 0 && isfinite(dt_new)) {
            /* Land on end_time in equal steps: a constant stable step stays
             * constant to the end (no short last step). A dry cycle
             * (`contact check`) takes the step the run would start with, so
             * that its cycle count and the cycle limit's verdict are the
             * run's. */
            double nrem = ceil((end - s->time) / dt_new * (1 - 1e-12));
            dt_new = (end - s->time) / (nrem > 1 ? nrem : 1);
        }
        if (!(dt_new > 0) || !isfinite(dt_new)) {
            fail(s, "unstable", CTD_EXIT_UNSTABLE, "cycle %lld (t = %.6g): the stable time step "
                 "is %g", (long long)s->cycle, s->time, dt_new);
            break;
        }
        /* A run that cannot end: end_time 9e18 s, or a step made tiny by a
         * huge Stfac or E/rho, ran on with no message (hours to years). The
         * estimate is checked at every step, as the step changes. */
        if ((!final || s->opts.dry) && s->opts.max_cycles <= 0 &&
            (double)s->cycle + (end - s->time) / dt_new > (double)s->cycle_limit) {
            fail(s, "error", CTD_EXIT_BADINPUT,
                 "cycle %lld (t = %.6g): the stable time step %.3g would need %.3g more cycles "
                 "to reach end_time %g, more than solver.cycle_limit (%lld) allows: expected a "
                 "shorter end_time, a larger step (check the interfaces' Stfac and the "
                 "materials' E/rho) or a larger cycle_limit", (long long)s->cycle, s->time,
                 dt_new, (end - s->time) / dt_new, end, (long long)s->cycle_limit);
            break;
        }
        double dtk = s->cycle == 0 ? 0.5 * dt_new : 0.5 * (w->dt_prev + dt_new);
        cti_solver_kick(s, dtk, dt_new, check);
        rigid_kick(s, dtk, dt_new);
        if (check) {
            cti_solver_energies(s);
            /* The gravity work's resolution too: a body at rest has E0 = 0,
             * and its first displacements can be below the coordinates'
             * rounding (a work of 0 against a kinetic energy > 0). */
            double ref = fmax(fmax(s->e0.total, fabs(s->e.external)), w->grav_res);
            double live = s->e.kinetic + s->e.internal + s->e.contact;
            if (!isfinite(live) || !isfinite(ref) || !isfinite(s->e.external)) {
                /* A NaN compares false below: without this a NaN contact
                 * energy went to history.csv with status "ok" and exit 0. */
                fail(s, "unstable", CTD_EXIT_UNSTABLE,
                     "cycle %lld (t = %.6g): non-finite energy: kinetic %g, internal %g, "
                     "contact %g, external work %g, initial total %g", (long long)s->cycle,
                     s->time, s->e.kinetic, s->e.internal, s->e.contact, s->e.external,
                     s->e0.total);
                break;
            }
            if (s->cycle > 0 && live > 100 * ref + 1e-30) {
                ct_idx f = fastest_node(s);
                fail(s, "unstable", CTD_EXIT_UNSTABLE,
                     "cycle %lld (t = %.6g): runaway energy: kinetic + internal + contact = %.4g "
                     "exceeds 100 x max(E0, |W_ext|, the gravity work's resolution) = %.4g; "
                     "fastest node %lld (part %d); the time step (dt = %.3g) is likely above "
                     "the stable limit",
                     (long long)s->cycle, s->time, live, 100 * ref,
                     f >= 0 ? (long long)m->node_id[f] : -1LL, f >= 0 ? m->node_part[f] : 0,
                     w->dt_prev);
                break;
            }
        }
        if (s->opts.observe)
            s->opts.observe(s->opts.observe_ctx, s);
        if (out_step) {
            int rc = cti_solver_output(s);
            if (rc) {
                fail(s, "error", CTD_EXIT_OUTPUT, "cycle %lld (t = %.6g): %s", (long long)s->cycle,
                     s->time, ctd_output_error(w->out));
                break;
            }
            while (next_out <= s->time + tol)
                next_out += s->every;
        }
        w->w_bc += w->w_bc_back + w->w_bc_fwd;
        w->w_c += w->w_c_back + w->w_c_fwd;
        if (s->opts.dry) {
            s->dt = dt_new; /* the step the run would start with */
            s->dt_max = dt_cap;
            s->dt_by_output = by_output;
        }
        if (final) {
            s->timers.total += ctd_wtime() - t0;
            break;
        }
        if (check)
            keep_good(s);
        /* Drift to x(n+1). */
        if (drift(s, dt_new, &bad))
            break;
        if (bad >= 0) {
            s->cycle++;
            s->time += dt_new;
            fail_node(s, bad, "position");
            break;
        }
        s->dt = dt_new;
        s->dt_max = dt_cap;
        s->dt_by_output = by_output;
        w->dt_prev = dt_new;
        s->time = s->time + dt_new >= end - tol ? end : s->time + dt_new;
        s->cycle++;
        s->timers.total += ctd_wtime() - t0;
        cti_solver_progress(s, 0);
    }
    cti_solver_progress(s, 1);
    if (s->exit_code == CTD_EXIT_UNSTABLE)
        cti_solver_last_good(s);
    s->wall = ctd_wtime() - w->t_start;
    int rc = cti_solver_finish(s);
    if (rc && s->exit_code == CTD_EXIT_OK)
        s->exit_code = CTD_EXIT_OUTPUT;
    return s->exit_code;
}
