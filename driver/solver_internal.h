/*
 * solver_internal.h -- the solver's work arrays, shared by solver.c (time
 * loop) and solver_report.c (energies, output, report). Not an API.
 */
#ifndef CTD_SOLVER_INTERNAL_H
#define CTD_SOLVER_INTERNAL_H

#include "loads.h"
#include "solver.h"

/* Energy sums go through fixed chunks of nodes (bit-identical for any
 * thread count). */
#define CTI_CHUNK 1024

typedef struct cti_solver_work {
    /* What the run wrote, for the report's list of files. */
    int wrote_csv, wrote_vtu, wrote_summary, wrote_plot;
    ct_real *vox, *voy, *voz;     /* v(n-1/2), kept at energy cycles */
    ct_real *fx, *fy, *fz;        /* total nodal force */
    ct_real *fcx, *fcy, *fcz;     /* contact force */
    ct_real *pen;                 /* per node, from the interfaces */
    int32_t *nact;
    ct_real *vmx, *vmy, *vmz;     /* output velocity (v- + v+) / 2 */
    ct_real *gx, *gy, *gz, *gvx, *gvy, *gvz; /* last good state */
    double good_time;
    int64_t good_cycle;
    int have_good;
    uint8_t *free_node;           /* 1: integrated by the kick (not rigid, m > 0) */
    double *part_sum;             /* chunk partial sums (four per chunk) */
    int nchunk;
    double (*vc_old)[3];          /* rigid bodies' centre velocity before the kick */
    double (*L_old)[3];           /* and their angular momentum before the kick */
    /* Energy accumulators. */
    double w_bc;                  /* imposed-velocity work up to the last step (both halves) */
    double w_bc_back;             /* this step's backward half */
    double w_bc_fwd;              /* this step's forward half */
    double w_c;                   /* contact forces' work up to the last step (both halves) */
    double w_c_back, w_c_fwd;     /* this step's halves (contact_work in solver.c) */
    double books0, work0;         /* the interfaces' books and w_c at cycle 0 */
    ctd_loads loads;              /* nodal forces and pressures, and their work */
    double damping, friction;     /* dissipation so far */
    double internal;              /* elements' energy at x(n) */
    double contact;               /* interfaces' stored energy at x(n) */
    double grav_res;              /* the gravity work's resolution (cti_solver_gravity_work) */
    double dt_prev;
    ctd_output *out;
    double *if_force;             /* per-interface values for the CSV row */
    int64_t *if_active, *if_resorts;
    double *if_margin;
    const char **if_names;
    double t_start, last_progress;
    int progress_shown;
} cti_solver_work;

/* solver_nodes.c: the passes over the nodes of a cycle (see there). */
/* The total force (and with interfaces their force, and on an output cycle
 * the fields they fill) zeroed. */
void cti_solver_forces_begin(ctd_solver *s, int want_fields);
/* Contact force and gravity added to the total force; the first node whose
 * total is not finite, or -1. */
ct_idx cti_solver_forces_end(ctd_solver *s);
/* The kick by dtk (dt_new: the step that follows), with the contact forces'
 * work and the imposed velocities and their reactions' work; keep_old:
 * v(n-1/2) kept in vo first. */
void cti_solver_kick(ctd_solver *s, double dtk, double dt_new, int keep_old);
/* The drift by dt of the nodes not in a rigid body; the first node whose
 * position is not finite, or -1. */
ct_idx cti_solver_drift_nodes(ctd_solver *s, double dt);

/* solver_report.c */
double cti_solver_kinetic(ctd_solver *s);
/* The gravity work sum m g . (x - x(0)), and in w->grav_res the work
 * gravity does over one rounding step of every coordinate: a displacement
 * below it is lost in the positions, so the work computed from them can
 * stay 0 while the velocities (and the kinetic energy) already grow. */
double cti_solver_gravity_work(ctd_solver *s);
/* Energies at the current cycle into s->e (x(n), v- in vo, v+ in v). */
void cti_solver_energies(ctd_solver *s);
/* Write one output step (CSV row and VTU). CT_OK or an output error. */
int cti_solver_output(ctd_solver *s);
/* Write the last good state as OUT/last_good.vtu (when there is an output
 * directory); appends where it went to s->message. */
void cti_solver_last_good(ctd_solver *s);
void cti_solver_progress(ctd_solver *s, int final);
/* Summary, plot and the printed report at the end of a run. */
int cti_solver_finish(ctd_solver *s);

#endif
