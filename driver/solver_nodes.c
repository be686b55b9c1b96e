/*
 * solver_nodes.c -- the time loop's passes over the nodes (solver.c):
 * forces zeroed at a cycle's start; contact force and gravity added, with
 * the finiteness check; the kick with the contact forces' work and the
 * imposed velocities; the drift with its check.
 *
 * Each pass is one parallel region: a region costs 1.6 us on two threads
 * of this project's hosts, more on more threads, and on a model of 10^4
 * nodes the eight passes that were here, and a serial loop over the held
 * nodes, took a sixth of a cycle on two threads (docs/DESIGN-CHANGES.md
 * §9). The kick and the drift run over fixed chunks of CTI_CHUNK nodes,
 * whose sums (the works) are added in chunk order: the same bits for any
 * thread count. A node's arithmetic is the same in every pass whatever
 * the chunk or the thread.
 */
#include <math.h>

#include "solver.h"
#include "solver_internal.h"

#include "ct_internal.h"

/* The first node (in index order) with a non-finite value in a, b or c, or
 * -1: the serial scan after a pass (forces, drift) found one. */
static ct_idx first_nonfinite(ct_idx n, const ct_real *a, const ct_real *b, const ct_real *c)
{
    for (ct_idx i = 0; i < n; i++)
        if (!isfinite(a[i]) || !isfinite(b[i]) || !isfinite(c[i]))
            return i;
    return -1;
}

/* The start of a cycle's forces: the total force, and with interfaces their
 * force (and, on an output cycle, the fields they fill), zeroed. */
void cti_solver_forces_begin(ctd_solver *s, int want_fields)
{
    cti_solver_work *w = s->w;
    const ct_idx nn = s->nnode;
    const int hooks = s->nhook > 0, fields = hooks && want_fields;
    ct_real *restrict fx = w->fx, *restrict fy = w->fy, *restrict fz = w->fz;
    ct_real *restrict cx = w->fcx, *restrict cy = w->fcy, *restrict cz = w->fcz;
    ct_real *restrict pen = w->pen;
    int32_t *restrict nact = w->nact;
    CTI_PAR_FOR(nn > CTD_PAR_MIN, (schedule(static)),
    for (ct_idx i = 0; i < nn; i++) {
        fx[i] = 0;
        fy[i] = 0;
        fz[i] = 0;
        if (hooks) {
            cx[i] = 0;
            cy[i] = 0;
            cz[i] = 0;
        }
        if (fields) {
            pen[i] = 0;
            nact[i] = 0;
        }
    });
}

/* The nodes [lo, hi) of a chunk: lo = c CTI_CHUNK. */
static inline void chunk_range(int c, ct_idx nn, ct_idx *lo, ct_idx *hi)
{
    *lo = (ct_idx)c * CTI_CHUNK;
    *hi = nn - *lo > CTI_CHUNK ? *lo + CTI_CHUNK : nn;
}

/* forces_end on the nodes of chunk c; returns whether a total is not finite. */
static int forces_end_chunk(ctd_solver *s, int c)
{
    cti_solver_work *w = s->w;
    const ctd_model *m = s->model;
    const ct_real *restrict mass = m->mesh.nodes.m;
    const int hooks = s->nhook > 0, grav = m->has_gravity;
    const ct_real gx = (ct_real)m->gravity[0], gy = (ct_real)m->gravity[1],
                  gz = (ct_real)m->gravity[2];
    ct_real *restrict fx = w->fx, *restrict fy = w->fy, *restrict fz = w->fz;
    const ct_real *restrict cx = w->fcx, *restrict cy = w->fcy, *restrict cz = w->fcz;
    ct_idx lo, hi;
    chunk_range(c, s->nnode, &lo, &hi);
    int bad = 0;
#pragma omp simd reduction(| : bad)
    for (ct_idx i = lo; i < hi; i++) {
        ct_real ux = fx[i], uy = fy[i], uz = fz[i];
        if (hooks) {
            ux += cx[i];
            uy += cy[i];
            uz += cz[i];
        }
        if (grav) {
            ux += mass[i] * gx;
            uy += mass[i] * gy;
            uz += mass[i] * gz;
        }
        fx[i] = ux;
        fy[i] = uy;
        fz[i] = uz;
        bad |= CTI_NONFINITE(ux) | CTI_NONFINITE(uy) | CTI_NONFINITE(uz);
    }
    return bad;
}

/* The end of a cycle's forces: the contact force and gravity added to the
 * elements' forces and the loads; returns the first node whose total force
 * is not finite, or -1. */
ct_idx cti_solver_forces_end(ctd_solver *s)
{
    cti_solver_work *w = s->w;
    int bad = 0;
    CTI_PAR_FOR(s->nnode > CTD_PAR_MIN, (schedule(static) reduction(| : bad)),
    for (int c = 0; c < w->nchunk; c++)
        bad |= forces_end_chunk(s, c););
    return bad ? first_nonfinite(s->nnode, w->fx, w->fy, w->fz) : -1;
}

/*
 * The work of this step's contact forces on the free nodes (rigid bodies:
 * rigid_kick in solver.c), in the two halves the kinetic energy m v- . v+ / 2 counts:
 * the velocity increment of the step, dtk f / m, makes that product grow by
 * dtk f . v- / 2 now and dtk f . v+ / 2 at the next cycle, so a force's work
 * is dtk f . (v- + v+) / 2. v+ of a constrained direction is its imposed
 * velocity. The nodes of chunk c, before their kick; *back and *fwd get the
 * chunk's sums of fc . v- and fc . v+.
 */
static void contact_work_chunk(const ctd_solver *s, double dtk, int c, double *back,
                               double *fwd)
{
    const cti_solver_work *w = s->w;
    const ctd_model *m = s->model;
    const ct_real *restrict mass = m->mesh.nodes.m;
    const uint8_t *restrict fr = w->free_node, *restrict mask = m->bc_mask;
    const ct_real *restrict cx = w->fcx, *restrict cy = w->fcy, *restrict cz = w->fcz;
    const ct_real *restrict fx = w->fx, *restrict fy = w->fy, *restrict fz = w->fz;
    const ct_real *restrict vx = s->vx, *restrict vy = s->vy, *restrict vz = s->vz;
    const ct_real *restrict bx = m->bc_v[0], *restrict by = m->bc_v[1], *restrict bz = m->bc_v[2];
    ct_idx lo, hi;
    chunk_range(c, s->nnode, &lo, &hi);
    double b = 0, f = 0;
    /* Selects, not branches, so that the loop vectorises (a node that is
     * not free adds nothing; its mass may be 0, the quotient's lane is not
     * used). The sums are in a fixed order within the chunk. */
#pragma omp simd reduction(+ : b, f)
    for (ct_idx i = lo; i < hi; i++) {
        const int free_ = fr[i] != 0;
        const unsigned mk = mask[i];
        const double im = dtk / (free_ ? (double)mass[i] : 1.0);
        const double vmx = vx[i], vmy = vy[i], vmz = vz[i];
        const double px = mk & 1u ? (double)bx[i] : vmx + im * (double)fx[i];
        const double py = mk & 2u ? (double)by[i] : vmy + im * (double)fy[i];
        const double pz = mk & 4u ? (double)bz[i] : vmz + im * (double)fz[i];
        const double ux = cx[i], uy = cy[i], uz = cz[i];
        const double tb = (ux * vmx + uy * vmy) + uz * vmz;
        const double tf = (ux * px + uy * py) + uz * pz;
        b += free_ ? tb : 0;
        f += free_ ? tf : 0;
    }
    *back = b;
    *fwd = f;
}

/* One imposed component of a node after its kick (vk): the imposed
 * velocity vimp replaces it, and the reaction R = m (vimp - vk) / dtk does
 * the work R dt_prev v- / 2 (backward half; v- = vk - dtk f / m for a node
 * with mass) and R dt_new vimp / 2 (forward half), added to *wb and *wf
 * when on. Returns the component's velocity. */
static inline __attribute__((always_inline)) ct_real
imposed(int on, double m, double vimp, double vk, double f, double dtk, double dtp,
        double dt_new, double *wb, double *wf)
{
    const double R = m * (vimp - vk) / dtk;
    const double vold = m > 0 ? vk - dtk * f / m : vimp;
    *wb += on ? 0.5 * R * dtp * vold : 0;
    *wf += on ? 0.5 * R * dt_new * vimp : 0;
    return on ? (ct_real)vimp : (ct_real)vk;
}

/* The kick of chunk c (see cti_solver_kick); its reactions' work into *wb_out
 * and *wf_out. */
static void kick_chunk(ctd_solver *s, int c, ct_real dk, double dtk, double dt_new,
                       int keep_old, double *wb_out, double *wf_out)
{
    const ctd_model *m = s->model;
    cti_solver_work *w = s->w;
    const double dtp = w->dt_prev;
    ct_idx lo, hi;
    chunk_range(c, s->nnode, &lo, &hi);
    const uint8_t *restrict fr = w->free_node, *restrict mask = m->bc_mask;
    const int32_t *restrict body = m->node_body;
    const ct_real *restrict ms = m->mesh.nodes.m, *restrict fx = w->fx, *restrict fy = w->fy,
                            *restrict fz = w->fz;
    const ct_real *restrict bx = m->bc_v[0], *restrict by = m->bc_v[1], *restrict bz = m->bc_v[2];
    ct_real *restrict vx = s->vx, *restrict vy = s->vy, *restrict vz = s->vz;
    if (keep_old) {
        ct_real *restrict ox = w->vox, *restrict oy = w->voy, *restrict oz = w->voz;
#pragma omp simd
        for (ct_idx i = lo; i < hi; i++) {
            ox[i] = vx[i];
            oy[i] = vy[i];
            oz[i] = vz[i];
        }
    }
    /* Selects, not branches, so that the loop vectorises: a node not free
     * keeps its velocity (its mass may be 0: the quotient's lane is not
     * used); a rigid body's nodes have no imposed component here
     * (rigid_kick). */
    double wb = 0, wf = 0;
#pragma omp simd reduction(+ : wb, wf)
    for (ct_idx i = lo; i < hi; i++) {
        const int f = fr[i] != 0;
        const ct_real im = dk / (f ? ms[i] : 1);
        const ct_real kx = vx[i] + im * fx[i], ky = vy[i] + im * fy[i],
                      kz = vz[i] + im * fz[i];
        const ct_real ux = f ? kx : vx[i], uy = f ? ky : vy[i], uz = f ? kz : vz[i];
        const unsigned mk = body[i] < 0 ? mask[i] : 0u;
        const double mi = ms[i];
        vx[i] = imposed(mk & 1u, mi, bx[i], ux, fx[i], dtk, dtp, dt_new, &wb, &wf);
        vy[i] = imposed(mk & 2u, mi, by[i], uy, fy[i], dtk, dtp, dt_new, &wb, &wf);
        vz[i] = imposed(mk & 4u, mi, bz[i], uz, fz[i], dtk, dtp, dt_new, &wb, &wf);
    }
    *wb_out = wb;
    *wf_out = wf;
}

/*
 * The kick, chunk by chunk in one pass: per chunk, the contact forces' work
 * (contact_work_chunk, before the kick), v- kept when keep_old, the kick of
 * the free nodes, then the imposed components with their reaction work
 * (backward and forward halves, solver.h). Every sum is per chunk and the
 * chunks' sums are added in chunk order: the same bits for any thread
 * count. (The imposed components were a serial loop after the kick; on the
 * wide folding sheet a third of the nodes are held, and that loop was a
 * thirtieth of a cycle on one thread, which a second thread did not share.)
 */
void cti_solver_kick(ctd_solver *s, double dtk, double dt_new, int keep_old)
{
    cti_solver_work *w = s->w;
    const ct_real dk = (ct_real)dtk;
    const int hooks = s->nhook > 0, nc = w->nchunk;
    double *back = w->part_sum, *fwd = back + nc + 1, *rb = fwd + nc + 1, *rf = rb + nc + 1;
    CTI_PAR_FOR(s->nnode > CTD_PAR_MIN, (schedule(static)),
    for (int c = 0; c < nc; c++) {
        if (hooks)
            contact_work_chunk(s, dtk, c, &back[c], &fwd[c]);
        kick_chunk(s, c, dk, dtk, dt_new, keep_old, &rb[c], &rf[c]);
    });
    double b = 0, f = 0, wb = 0, wf = 0;
    for (int c = 0; c < nc; c++) {
        b += back[c];
        f += fwd[c];
        wb += rb[c];
        wf += rf[c];
    }
    if (hooks) {
        w->w_c_back = 0.5 * dtk * b;
        w->w_c_fwd = 0.5 * dtk * f;
    }
    w->w_bc_back = wb;
    w->w_bc_fwd = wf;
}

/* The drift of the nodes of chunk c not in a rigid body (see
 * cti_solver_drift_nodes); returns whether a position of the chunk is not
 * finite. */
static int drift_chunk(ctd_solver *s, int c, ct_real d)
{
    const int32_t *restrict body = s->model->node_body;
    ct_real *restrict x = s->x, *restrict y = s->y, *restrict z = s->z;
    const ct_real *restrict vx = s->vx, *restrict vy = s->vy, *restrict vz = s->vz;
    ct_idx lo, hi;
    chunk_range(c, s->nnode, &lo, &hi);
    int bad = 0;
#pragma omp simd reduction(| : bad)
    for (ct_idx i = lo; i < hi; i++) {
        /* Every load unconditional, so that both compilers vectorise. */
        const int free_ = body[i] < 0;
        const ct_real dx = d * vx[i], dy = d * vy[i], dz = d * vz[i];
        const ct_real xi = free_ ? x[i] + dx : x[i];
        const ct_real yi = free_ ? y[i] + dy : y[i];
        const ct_real zi = free_ ? z[i] + dz : z[i];
        x[i] = xi;
        y[i] = yi;
        z[i] = zi;
        bad |= CTI_NONFINITE(xi) | CTI_NONFINITE(yi) | CTI_NONFINITE(zi);
    }
    return bad;
}

/* The drift of the nodes not in a rigid body (those were placed by their
 * body before); returns the first node whose position is not finite, or
 * -1. */
ct_idx cti_solver_drift_nodes(ctd_solver *s, double dt)
{
    const ct_real d = (ct_real)dt;
    int nonfin = 0;
    CTI_PAR_FOR(s->nnode > CTD_PAR_MIN, (schedule(static) reduction(| : nonfin)),
    for (int c = 0; c < s->w->nchunk; c++)
        nonfin |= drift_chunk(s, c, d););
    return nonfin ? first_nonfinite(s->nnode, s->x, s->y, s->z) : -1;
}
