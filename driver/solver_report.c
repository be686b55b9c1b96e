/*
 * solver_report.c -- what the solver computes and writes besides the time
 * integration: the energy balance (solver.h), the output steps (CSV row,
 * VTU), the last good state of an unstable run, the progress line, and at
 * the end the summary, the energy plot and the printed report.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "solver.h"
#include "solver_internal.h"

#include "ct_internal.h"

#include "wtime.h"

/* Sum m v- . v+ / 2 over the free nodes (at cycle 0, v- is the virtual
 * 2 v(0) - v(1/2)), in fixed chunks. */
double cti_solver_kinetic(ctd_solver *s)
{
    cti_solver_work *w = s->w;
    const ct_real *mass = s->model->mesh.nodes.m;
    const ct_idx nn = s->nnode;
    const int first = s->cycle == 0;
    CTI_PAR_FOR(w->nchunk > 1, (schedule(static)),
    for (int c = 0; c < w->nchunk; c++) {
        ct_idx lo = (ct_idx)c * CTI_CHUNK, hi = lo + CTI_CHUNK < nn ? lo + CTI_CHUNK : nn;
        double sum = 0;
        for (ct_idx i = lo; i < hi; i++) {
            if (!w->free_node[i])
                continue;
            double ax = w->vox[i], ay = w->voy[i], az = w->voz[i];
            if (first) {
                ax = 2 * ax - s->vx[i];
                ay = 2 * ay - s->vy[i];
                az = 2 * az - s->vz[i];
            }
            sum += 0.5 * mass[i] * (ax * s->vx[i] + ay * s->vy[i] + az * s->vz[i]);
        }
        w->part_sum[c] = sum;
    });
    double k = 0;
    for (int c = 0; c < w->nchunk; c++)
        k += w->part_sum[c];
    const ctd_model *m = s->model;
    for (int b = 0; b < m->nbody; b++) {
        const ctd_rigid *r = &m->body[b].rigid;
        double vo[3], dot = 0;
        for (int d = 0; d < 3; d++) {
            vo[d] = first ? 2 * w->vc_old[b][d] - r->vc[d] : w->vc_old[b][d];
            dot += vo[d] * r->vc[d];
        }
        /* Rotation in the same product form, pi- . I^-1 pi+ / 2 with pi =
         * R^T L in the body frame at x(n): the energy of the kick's torque
         * enters with the work of the step that follows it, as for the
         * translation (a body spun up from rest by a load raised from zero
         * then shows no kinetic energy before the load has done work). */
        double R[9], Lo[3];
        ctd_rigid_rotation(r, R);
        for (int d = 0; d < 3; d++)
            Lo[d] = first ? 2 * w->L_old[b][d] - r->L[d] : w->L_old[b][d];
        double rot = 0;
        for (int i = 0; i < 3; i++) {
            double po = R[i] * Lo[0] + R[3 + i] * Lo[1] + R[6 + i] * Lo[2];
            double pn = R[i] * r->L[0] + R[3 + i] * r->L[1] + R[6 + i] * r->L[2];
            rot += po * pn * r->Iinv[i];
        }
        k += 0.5 * r->mass * dot + 0.5 * rot;
    }
    return k;
}

/* Work of gravity: sum m g . (x - x0), in fixed chunks. */
double cti_solver_gravity_work(ctd_solver *s)
{
    const ctd_model *m = s->model;
    cti_solver_work *w = s->w;
    w->grav_res = 0;
    if (!m->has_gravity)
        return 0;
    const ct_nodes *nd = &m->mesh.nodes;
    const ct_idx nn = s->nnode;
    const double g0 = m->gravity[0], g1 = m->gravity[1], g2 = m->gravity[2];
    const double a0 = fabs(g0), a1 = fabs(g1), a2 = fabs(g2);
    double *res = w->part_sum + w->nchunk + 1;
    CTI_PAR_FOR(w->nchunk > 1, (schedule(static)),
    for (int c = 0; c < w->nchunk; c++) {
        ct_idx lo = (ct_idx)c * CTI_CHUNK, hi = lo + CTI_CHUNK < nn ? lo + CTI_CHUNK : nn;
        double sum = 0, r = 0;
        for (ct_idx i = lo; i < hi; i++) {
            const double X = s->x[i], Y = s->y[i], Z = s->z[i];
            sum += nd->m[i] * (g0 * (X - nd->x[i]) + g1 * (Y - nd->y[i]) + g2 * (Z - nd->z[i]));
            r += nd->m[i] * (a0 * fabs(X) + a1 * fabs(Y) + a2 * fabs(Z));
        }
        w->part_sum[c] = sum;
        res[c] = r;
    });
    double sum = 0, r = 0;
    for (int c = 0; c < w->nchunk; c++) {
        sum += w->part_sum[c];
        r += res[c];
    }
    /* One rounding step of a coordinate is at most 2 eps |x|. */
    w->grav_res = 2 * (double)CTI_EPS * r;
    return sum;
}

void ctd_solver_penetration(const ctd_solver *s, int64_t *count, double *pmax, ct_idx *node)
{
    const ct_real *pen = s->w->pen;
    int64_t c = 0;
    double best = 0;
    ct_idx at = -1;
    for (ct_idx i = 0; i < s->nnode; i++) {
        c += pen[i] > 0;
        if (pen[i] > best) { /* the first deepest: any thread count */
            best = pen[i];
            at = i;
        }
    }
    *count = c;
    *pmax = best;
    *node = at;
}

void ctd_solver_print_penetration(FILE *f, const char *prefix, const ctd_solver *s)
{
    const ctd_model *m = s->model;
    if (!s->nhook)
        return;
    if (s->pen0_count == 0 || s->pen0_node < 0)
        fprintf(f, "%sinitial penetration: none (no node within its gap at t = 0)\n", prefix);
    else
        fprintf(f, "%sinitial penetration: %lld node%s within the gap at t = 0, the deepest %.4g "
                   "at node %lld (part %d)\n", prefix, (long long)s->pen0_count,
                s->pen0_count == 1 ? "" : "s", s->pen0_max,
                (long long)m->node_id[s->pen0_node], m->node_part[s->pen0_node]);
}

void cti_solver_energies(ctd_solver *s)
{
    cti_solver_work *w = s->w;
    ctd_energies *e = &s->e;
    e->kinetic = cti_solver_kinetic(s);
    e->internal = w->internal;
    e->contact = w->contact;
    e->damping = w->damping;
    e->friction = w->friction;
    e->external = cti_solver_gravity_work(s) + w->w_bc + w->w_bc_back + w->loads.work;
    e->total = e->kinetic + e->internal + e->contact + e->damping + e->friction;
    if (s->cycle == 0) {
        s->e0 = *e;
        s->e_max = 0;
    }
    double mx = fmax(fabs(e->total), fmax(fabs(e->external), fabs(s->e0.total)));
    if (mx > s->e_max)
        s->e_max = mx;
    e->error = s->e_max > 0 ? (e->total - s->e0.total - e->external) / s->e_max : 0;
    if (fabs(e->error) > s->error_max)
        s->error_max = fabs(e->error);
    /* The contact's part, from cycle 0 on as the error (an initial
     * penetration's stored energy is E_0's). */
    const double books = e->contact + e->damping + e->friction, work = w->w_c + w->w_c_back;
    if (s->cycle == 0) {
        w->books0 = books;
        w->work0 = work;
    }
    e->contact_error = s->e_max > 0 ? (books - w->books0 + work - w->work0) / s->e_max : 0;
}

static void out_mesh(const ctd_solver *s, ctd_out_mesh *om, const ct_real *x, const ct_real *y,
                     const ct_real *z, const ct_real *vx, const ct_real *vy, const ct_real *vz)
{
    const ctd_model *m = s->model;
    const cti_solver_work *w = s->w;
    memset(om, 0, sizeof *om);
    om->nnode = s->nnode;
    om->x = x;
    om->y = y;
    om->z = z;
    om->x0 = m->mesh.nodes.x;
    om->y0 = m->mesh.nodes.y;
    om->z0 = m->mesh.nodes.z;
    om->vx = vx;
    om->vy = vy;
    om->vz = vz;
    if (s->nhook) {
        om->fcx = w->fcx;
        om->fcy = w->fcy;
        om->fcz = w->fcz;
        om->pen = w->pen;
        om->node_active = w->nact;
    }
    om->node_part = m->node_part;
    om->ncell = m->ncell;
    om->cell_type = m->cell_type;
    om->cell_off = m->cell_off;
    om->cell_node = m->cell_node;
    om->cell_part = m->cell_part;
}

int cti_solver_output(ctd_solver *s)
{
    cti_solver_work *w = s->w;
    s->output_steps++;
    if (!w->out)
        return CT_OK;
    const ctd_scene *sc = s->model->scene;
    int rc = CT_OK;
    if (sc->output->csv) {
        ctd_history_row r = {s->cycle, s->time, w->dt_prev, s->e.kinetic, s->e.internal,
                             s->e.contact, s->e.damping, s->e.friction, s->e.external,
                             s->e.error, w->if_force, w->if_active, w->if_resorts};
        rc = ctd_output_csv_row(w->out, &r);
        w->wrote_csv |= rc == CT_OK;
    }
    if (!rc && sc->output->vtu) {
        const ct_idx nn = s->nnode;
        const int first = s->cycle == 0;
        CTI_PAR_FOR(nn > CTD_PAR_MIN, (schedule(static)),
        for (ct_idx i = 0; i < nn; i++) {
            if (w->free_node[i]) {
                /* v(n) = (v- + v+) / 2; at cycle 0 this is v(0), kept in vo. */
                w->vmx[i] = first ? w->vox[i] : (ct_real)0.5 * (w->vox[i] + s->vx[i]);
                w->vmy[i] = first ? w->voy[i] : (ct_real)0.5 * (w->voy[i] + s->vy[i]);
                w->vmz[i] = first ? w->voz[i] : (ct_real)0.5 * (w->voz[i] + s->vz[i]);
            } else {
                w->vmx[i] = s->vx[i];
                w->vmy[i] = s->vy[i];
                w->vmz[i] = s->vz[i];
            }
        });
        ctd_out_mesh om;
        out_mesh(s, &om, s->x, s->y, s->z, w->vmx, w->vmy, w->vmz);
        rc = ctd_output_vtu(w->out, s->time, &om);
        w->wrote_vtu |= rc == CT_OK;
    }
    return rc;
}

void cti_solver_last_good(ctd_solver *s)
{
    cti_solver_work *w = s->w;
    size_t len = strlen(s->message);
    if (!w->have_good) {
        snprintf(s->message + len, sizeof s->message - len, "; no state passed the checks");
        return;
    }
    if (!s->out_dir[0])
        return;
    char path[1200], err[512];
    snprintf(path, sizeof path, "%s/last_good.vtu", s->out_dir);
    ctd_out_mesh om;
    out_mesh(s, &om, w->gx, w->gy, w->gz, w->gvx, w->gvy, w->gvz);
    om.fcx = om.fcy = om.fcz = om.pen = NULL;
    om.node_active = NULL;
    int rc = ctd_vtu_write(path, &om, err, sizeof err);
    if (rc)
        snprintf(s->message + len, sizeof s->message - len,
                 "; the last good state could not be written: %s", err);
    else
        snprintf(s->message + len, sizeof s->message - len,
                 "; last good state (cycle %lld, t = %.6g) written to %s",
                 (long long)w->good_cycle, w->good_time, path);
}

void cti_solver_progress(ctd_solver *s, int final)
{
    cti_solver_work *w = s->w;
    int on = s->opts.progress > 0 || (s->opts.progress < 0 && !s->opts.quiet && isatty(2));
    if (!on)
        return;
    if (final) {
        if (w->progress_shown)
            fprintf(stderr, "\n");
        return;
    }
    double t = ctd_wtime();
    if (t - w->t_start < 1.0 || t - w->last_progress < 0.25)
        return;
    w->last_progress = t;
    w->progress_shown = 1;
    fprintf(stderr, "\r  cycle %lld  t = %.4g / %.4g (%3.0f%%)  dt = %.3g  energy error %+.2e   ",
            (long long)s->cycle, s->time, s->end_time, 100 * s->time / s->end_time, s->dt,
            s->e.error);
    fflush(stderr);
}

static void print_report(ctd_solver *s, FILE *f)
{
    const ctd_model *m = s->model;
    const ctd_scene *sc = m->scene;
    const ctd_energies *e = &s->e;
    fprintf(f, "%s: %s after %lld cycles, t = %.6g of %.6g s (%.2f s wall, %d thread%s)\n",
            sc->path, s->status, (long long)s->cycle, s->time, s->end_time, s->wall, s->threads,
            s->threads == 1 ? "" : "s");
    if (s->message[0])
        fprintf(f, "  %s\n", s->message);
    fprintf(f, "  model: %d nodes, %lld elements, %d segments, %d rigid bod%s, %d interface%s\n",
            s->nnode, (long long)m->nelem, m->mesh.nseg, m->nbody, m->nbody == 1 ? "y" : "ies",
            s->nhook, s->nhook == 1 ? "" : "s");
    fprintf(f, "  energy: kinetic %.6g, internal %.6g, contact %.6g, damping %.6g, "
               "friction %.6g, external work %.6g, initial %.6g\n",
            e->kinetic, e->internal, e->contact, e->damping, e->friction, e->external,
            s->e0.total);
    fprintf(f, "  energy error (E - E0 - W_ext) / max(E): final %+.3e, largest %.3e\n", e->error,
            s->error_max);
    if (s->nhook)
        fprintf(f, "  of which contact: %+.3e (the interfaces' stored energy, damping and friction "
                   "against the work their forces did on the nodes)\n", e->contact_error);
    for (int i = 0; i < s->nhook; i++) {
        fprintf(f, "  interface %s (type %d, %s search): max force %.4g, max active pairs %lld, "
                   "re-sorts %lld", s->w->if_names[i], s->hooks[i].type,
                s->hooks[i].search ? s->hooks[i].search : "?", s->if_force_max[i],
                (long long)s->if_active_max[i], (long long)s->w->if_resorts[i]);
        if (s->w->if_margin[i] > 0)
            fprintf(f, " (margin %.3g)", s->w->if_margin[i]);
        const int64_t mem = ctd_solver_if_memory(s, i);
        if (mem >= 0)
            fprintf(f, ", memory %.3g MB", (double)mem / 1e6);
        if (s->rep[i].excluded > 0)
            fprintf(f, ", neighbour pairs excluded %lld", (long long)s->rep[i].excluded);
        fputc('\n', f);
        if (s->hooks[i].note[0])
            fprintf(f, "    note: %s\n", s->hooks[i].note);
    }
    ctd_solver_print_penetration(f, "  ", s);
    const ctd_timers *t = &s->timers;
    double tot = t->total > 0 ? t->total : 1;
    fprintf(f, "  time split: search %.1f%%, narrow %.1f%%, force %.1f%%, assembly %.1f%%, "
               "elements %.1f%%, other %.1f%% of %.3f s\n", 100 * t->search / tot,
            100 * t->narrow / tot, 100 * t->force / tot, 100 * t->assembly / tot,
            100 * t->elements / tot, 100 * t->other / tot, t->total);
    /* The files this run wrote (an earlier run's may lie beside them). */
    const cti_solver_work *w = s->w;
    const char *name[4] = {"state.pvd + state_*.vtu for ParaView", "history.csv",
                           "summary.json", "energies.png"};
    const int wrote[4] = {w->wrote_vtu, w->wrote_csv, w->wrote_summary, w->wrote_plot};
    int any = 0;
    for (int k = 0; k < 4; k++) {
        if (!wrote[k])
            continue;
        if (any++)
            fprintf(f, ", %s", name[k]);
        else
            fprintf(f, "  files: %s/ (%s", s->out_dir, name[k]);
    }
    if (any)
        fprintf(f, ")\n");
}

int64_t ctd_solver_if_memory(const ctd_solver *s, int i)
{
    if (!s || i < 0 || i >= s->nhook || !s->hooks[i].memory)
        return -1;
    return (int64_t)s->hooks[i].memory(s->hooks[i].ctx);
}

/* The run's outcome says that its final files failed: a run that went
 * well until then is an output error (status "error", exit 5, the message
 * why; it had ended with status "ok" and an empty message); a failed one
 * keeps its own status and adds this. */
static void end_output_failed(ctd_solver *s, const char *why)
{
    if (s->exit_code == CTD_EXIT_OK) {
        s->status = "error";
        s->exit_code = CTD_EXIT_OUTPUT;
        snprintf(s->message, sizeof s->message, "%s", why);
    } else {
        size_t len = strlen(s->message);
        snprintf(s->message + len, sizeof s->message - len, "; %s", why);
    }
}

int cti_solver_finish(ctd_solver *s)
{
    cti_solver_work *w = s->w;
    ctd_timers *t = &s->timers;
    t->other = t->total - t->elements - t->search - t->narrow - t->force - t->assembly;
    if (t->other < 0)
        t->other = 0;
    int rc = CT_OK;
    if (w->out) {
        const ctd_model *m = s->model;
        ctd_if_summary *ifs = calloc((size_t)s->nhook + 1, sizeof *ifs);
        if (!ifs) {
            end_output_failed(s, "out of memory writing the summary");
            return CT_ERR_NOMEM;
        }
        for (int i = 0; i < s->nhook; i++) {
            ifs[i].name = w->if_names[i];
            ifs[i].type = s->hooks[i].type;
            ifs[i].search = s->hooks[i].search ? s->hooks[i].search : "";
            ifs[i].max_active = s->if_active_max[i];
            ifs[i].resorts = w->if_resorts[i];
            ifs[i].margin = w->if_margin[i];
            ifs[i].max_force = s->if_force_max[i];
            ifs[i].memory = ctd_solver_if_memory(s, i);
        }
        ctd_run_summary sum = {m->scene->path, m->scene->title ? m->scene->title : "",
                               s->status, s->exit_code, s->message[0] ? s->message : NULL,
                               s->threads, s->cycle, s->nnode, m->nelem, m->mesh.nseg,
                               s->output_steps, s->end_time, s->time, s->wall, s->e.error,
                               s->error_max, s->e.contact_error, t->search, t->narrow, t->force, t->assembly,
                               t->elements, t->other, s->nhook, ifs};
        rc = ctd_output_summary(w->out, &sum);
        w->wrote_summary = rc == CT_OK;
        free(ifs);
        if (rc)
            end_output_failed(s, ctd_output_error(w->out));
        /* A run stopped in its first cycle has no history to plot (gnuplot
         * fails on it). */
        if (!rc && m->scene->output->csv && (s->cycle > 0 || s->exit_code == CTD_EXIT_OK)) {
            char msg[512];
            int prc = ctd_output_plot_energies(s->out_dir, msg, sizeof msg);
            w->wrote_plot = prc == 0;
            if (prc < 0 && !s->opts.quiet)
                fprintf(stderr, "contact: energy plot: %s\n", msg);
        }
    }
    if (!s->opts.quiet)
        print_report(s, s->opts.report ? s->opts.report : stdout);
    return rc;
}
