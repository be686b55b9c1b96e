/*
 * solver_init.c -- setting the solver up and tearing it down (solver.h):
 * its options, the arrays of the time loop, the interfaces' hooks and the
 * output writers, and the momentum of the state. The time loop itself is
 * solver.c.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "errf.h"
#include "solver.h"
#include "solver_internal.h"

#include "ct_internal.h"

ctd_solver_opts ctd_solver_default_opts(void)
{
    ctd_solver_opts o;
    memset(&o, 0, sizeof o);
    o.progress = -1;
    return o;
}

void ctd_solver_destroy(ctd_solver *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->nhook; i++)
        if (s->hooks[i].destroy)
            s->hooks[i].destroy(s->hooks[i].ctx);
    free(s->hooks);
    free(s->rep);
    free(s->if_force_max);
    free(s->if_active_max);
    ct_real **arr[] = {&s->x, &s->y, &s->z, &s->vx, &s->vy, &s->vz};
    for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++)
        ct_free(*arr[k]);
    cti_solver_work *w = s->w;
    if (w) {
        ct_real **wa[] = {&w->vox, &w->voy, &w->voz, &w->fx, &w->fy, &w->fz, &w->fcx, &w->fcy,
                          &w->fcz, &w->pen, &w->vmx, &w->vmy, &w->vmz, &w->gx, &w->gy,
                          &w->gz, &w->gvx, &w->gvy, &w->gvz};
        for (size_t k = 0; k < sizeof wa / sizeof wa[0]; k++)
            ct_free(*wa[k]);
        ct_free(w->nact);
        free(w->free_node);
        free(w->part_sum);
        free(w->vc_old);
        free(w->L_old);
        ctd_loads_destroy(&w->loads);
        free(w->if_force);
        free(w->if_active);
        free(w->if_resorts);
        free(w->if_margin);
        free(w->if_names);
        ctd_output_close(w->out);
        free(w);
    }
    memset(s, 0, sizeof *s);
}

int ctd_solver_init(ctd_solver *s, ctd_model *m, const ctd_solver_opts *opts,
                    ctd_contact_hook *hooks, int nhook, char *err, size_t errlen)
{
    if (!s)
        return CT_ERR_ARG;
    memset(s, 0, sizeof *s);
    s->hooks = hooks;
    s->nhook = hooks ? nhook : 0;
    if (!m || !m->scene || nhook < 0)
        return ctd_errf(err, errlen, CT_ERR_ARG, "no model to run");
    const ctd_scene *sc = m->scene;
    s->model = m;
    s->opts = opts ? *opts : ctd_solver_default_opts();
    s->end_time = s->opts.end_time > 0 ? s->opts.end_time : sc->end_time;
    s->dt_scale = s->opts.dt_scale > 0 ? s->opts.dt_scale : sc->solver->dt_scale;
    s->cycle_limit = s->opts.cycle_limit > 0           ? s->opts.cycle_limit
                     : sc->solver->cycle_limit > 0 ? sc->solver->cycle_limit
                                                    : CTD_CYCLE_LIMIT;
    s->every = s->opts.every > 0 ? s->opts.every
               : sc->output->every > 0 ? sc->output->every
                                      : s->end_time / 100;
    s->threads = s->opts.threads > 0 ? s->opts.threads : (int)sc->solver->threads;
#ifdef _OPENMP
    if (s->threads == 0 && !getenv("OMP_NUM_THREADS")) {
        /* Nobody chose: at most one thread per CTD_NODES_PER_THREAD nodes.
         * A smaller model's loops are too short to share (the showcase's
         * 730 nodes: 0.78 s on 1 thread, 0.92 on 2, and, measured with
         * libgomp, 3.3 times slower on 2 than on 1 while another process
         * held a core; solver.h has the figures of the threshold). */
        const ct_idx cap = 1 + m->mesh.nodes.n / CTD_NODES_PER_THREAD;
        if (cap < omp_get_max_threads())
            s->threads = (int)cap;
    }
    if (s->threads > 0)
        omp_set_num_threads(s->threads);
    s->threads = omp_get_max_threads();
#else
    s->threads = 1;
#endif
    s->status = "ok";
    ct_idx nn = m->mesh.nodes.n;
    s->nnode = nn;
    size_t n1 = (size_t)nn + 1;
    cti_solver_work *w = s->w = calloc(1, sizeof *w);
    if (!w)
        return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    ct_real **arr[] = {&s->x, &s->y, &s->z, &s->vx, &s->vy, &s->vz, &w->vox, &w->voy,
                       &w->voz, &w->fx, &w->fy, &w->fz, &w->fcx, &w->fcy, &w->fcz, &w->pen,
                       &w->vmx, &w->vmy, &w->vmz, &w->gx, &w->gy, &w->gz, &w->gvx, &w->gvy,
                       &w->gvz};
    for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++)
        if (!(*arr[k] = ct_calloc(n1, sizeof(ct_real))))
            return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    w->nact = ct_calloc(n1, sizeof(int32_t));
    w->free_node = calloc(n1, 1);
    w->nchunk = (int)((nn + CTI_CHUNK - 1) / CTI_CHUNK);
    w->part_sum = calloc(4 * ((size_t)w->nchunk + 1), sizeof(double));
    w->vc_old = calloc((size_t)m->nbody + 1, sizeof *w->vc_old);
    w->L_old = calloc((size_t)m->nbody + 1, sizeof *w->L_old);
    int nh = s->nhook;
    s->rep = calloc((size_t)nh + 1, sizeof *s->rep);
    s->if_force_max = calloc((size_t)nh + 1, sizeof(double));
    s->if_active_max = calloc((size_t)nh + 1, sizeof(int64_t));
    w->if_force = calloc((size_t)nh + 1, sizeof(double));
    w->if_active = calloc((size_t)nh + 1, sizeof(int64_t));
    w->if_resorts = calloc((size_t)nh + 1, sizeof(int64_t));
    w->if_margin = calloc((size_t)nh + 1, sizeof(double));
    w->if_names = calloc((size_t)nh + 1, sizeof(char *));
    if (!w->nact || !w->free_node || !w->part_sum || !w->vc_old || !w->L_old ||
        !s->rep ||
        !s->if_force_max || !s->if_active_max || !w->if_force || !w->if_active ||
        !w->if_resorts || !w->if_margin || !w->if_names)
        return ctd_errf(err, errlen, CT_ERR_NOMEM, "out of memory");
    for (int i = 0; i < nh; i++) {
        if (!s->hooks[i].contact_step)
            return ctd_errf(err, errlen, CT_ERR_ARG, "interface %d has no contact_step", i);
        w->if_names[i] = s->hooks[i].name ? s->hooks[i].name : "interface";
    }
    const ct_nodes *nd = &m->mesh.nodes;
    memcpy(s->x, nd->x, sizeof(ct_real) * (size_t)nn);
    memcpy(s->y, nd->y, sizeof(ct_real) * (size_t)nn);
    memcpy(s->z, nd->z, sizeof(ct_real) * (size_t)nn);
    memcpy(s->vx, nd->vx, sizeof(ct_real) * (size_t)nn);
    memcpy(s->vy, nd->vy, sizeof(ct_real) * (size_t)nn);
    memcpy(s->vz, nd->vz, sizeof(ct_real) * (size_t)nn);
    for (ct_idx i = 0; i < nn; i++)
        w->free_node[i] = m->node_body[i] < 0 && nd->m[i] > 0;
    int lrc = ctd_loads_init(&w->loads, m, err, errlen);
    if (lrc != CT_OK) {
        /* A selection that selects nothing is the input's fault: tell the
         * caller (run.c reported every init failure as exit 5, "an output
         * file could not be written"). */
        s->exit_code = lrc == CT_ERR_NOMEM ? CTD_EXIT_OUTPUT : CTD_EXIT_BADINPUT;
        return lrc == CT_ERR_NOMEM ? ctd_errf(err, errlen, lrc, "out of memory") : lrc;
    }
    /* Driven bodies start with their imposed velocity and no spin. */
    for (int b = 0; b < m->nbody; b++) {
        ctd_model_body *bd = &m->body[b];
        if (!bd->driven)
            continue;
        double v[3], zero[3] = {0, 0, 0};
        for (int d = 0; d < 3; d++)
            v[d] = bd->dof[d] ? bd->v[d] : bd->rigid.vc[d];
        ctd_rigid_set_velocity(&bd->rigid, v, zero);
    }
    /* Output directory: checked now, so a bad one fails before the run. */
    if (!s->opts.no_output) {
        const char *dir = s->opts.out_dir ? s->opts.out_dir : sc->out_dir;
        ctd_output_opts oo = {dir, "state", sc->output->vtu, sc->output->csv,
                              sc->output->format};
        char msg[512];
        int rc = ctd_output_open(&w->out, &oo, msg, sizeof msg);
        if (rc)
            return ctd_errf(err, errlen, rc, "%s", msg);
        snprintf(s->out_dir, sizeof s->out_dir, "%s", ctd_output_dir(w->out));
        if (sc->output->csv && (rc = ctd_output_csv_begin(w->out, nh, w->if_names)))
            return ctd_errf(err, errlen, rc, "%s", ctd_output_error(w->out));
    }
    return CT_OK;
}

void ctd_solver_momentum(const ctd_solver *s, double p[3])
{
    const ctd_model *m = s->model;
    const ct_real *mass = m->mesh.nodes.m;
    p[0] = p[1] = p[2] = 0;
    for (ct_idx i = 0; i < s->nnode; i++)
        if (m->node_body[i] < 0) {
            p[0] += mass[i] * s->vx[i];
            p[1] += mass[i] * s->vy[i];
            p[2] += mass[i] * s->vz[i];
        }
    for (int b = 0; b < m->nbody; b++)
        for (int d = 0; d < 3; d++)
            p[d] += m->body[b].rigid.mass * m->body[b].rigid.vc[d];
}
