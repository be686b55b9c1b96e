/*
 * solver.h -- the explicit central-difference solver of the driver (prefix
 * ctd_), and the hook through which contact interfaces act on it.
 *
 * Time integration (lumped masses m, velocities at half steps):
 *   f(n)      = element forces at x(n) + contact forces + m g
 *   v(n+1/2)  = v(n-1/2) + dt_k f(n) / m,  dt_k = (dt(n-1/2) + dt(n+1/2)) / 2
 *               (the first step: v(1/2) = v(0) + dt(1/2)/2 f(0)/m)
 *   x(n+1)    = x(n) + dt(n+1/2) v(n+1/2)
 * Imposed components (fixed, velocity) are set after the kick; their
 * reaction R(n) = m (v_imposed - v_kicked) / dt_k. Rigid bodies are kicked
 * with the force and moment of their nodes' forces (ctd_rigid_accumulate),
 * then drifted by ctd_rigid_advance; a driven body (model.h) has its
 * constrained centre components imposed and does not rotate.
 *
 * Time step: dt(n+1/2) = dt_scale x min(brick, shell, truss/spring steps at
 * x(n), every interface's dt_limit, 0.25 / |omega| of each rigid body), at
 * most the output interval, then shortened to (end_time - t) / k with k
 * the fewest steps that reach end_time (so a constant stable step stays
 * constant and the run lands on end_time without a short last step).
 *
 * Energy balance, evaluated at output steps and every 100 cycles:
 *   kinetic   K(n) = sum m v(n-1/2) . v(n+1/2) / 2 (rigid bodies: M v_c- .
 *             v_c+ / 2 plus pi- . I^-1 pi+ / 2, pi = R^T L the angular
 *             momentum in the body frame at x(n)): the product of the two
 *             half-step velocities, the kinetic energy the central difference
 *             conserves exactly with the internal energy of a linear system
 *             (it differs from m |(v- + v+)/2|^2 / 2 by m |v+ - v-|^2 / 8);
 *   internal  U(n): the elements' energies at x(n);
 *   contact   the interfaces' stored energy; damping and friction: their
 *             dissipation summed over the steps;
 *   external  gravity: sum m g . (x(n) - x(0)) (exact); imposed components:
 *             the trapezoidal rule sum over steps of dx . (R(k) + R(k+1)) / 2,
 *             dx = dt(k+1/2) v(k+1/2), the work the scheme actually does;
 *   error     (E_total - E_0 - W_ext) / max(E), E_total = K + U + contact +
 *             damping + friction, max(E) the largest of |E_total|, |W_ext|
 *             and E_0 seen so far.
 *
 * Robustness: a NaN or infinite force or position, an inverted element,
 * an interface returning an error, or a runaway energy (K + U + contact >
 * 100 max(E_0, |W_ext|, R) + 1e-30, R = 2 eps sum m |g| . |x| the gravity
 * work's resolution: steps whose displacement is below the coordinates'
 * rounding leave W_ext at 0) stops the run: s->status is "unstable",
 * s->message names the node (scene id and part), element (index in its
 * part) or interface and the cycle, and the last state that passed the
 * checks is written to OUT/last_good.vtu. Nothing is allocated inside the
 * time loop; the final state is bit-identical for any OMP_NUM_THREADS
 * (element sets are deterministic, energy sums use fixed chunks).
 */
#ifndef CTD_SOLVER_H
#define CTD_SOLVER_H

#include <stdint.h>
#include <stdio.h>

#include "contact.h"
#include "model.h"
#include "output.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Exit codes of `contact run` (CTD_EXIT_OK 0 and CTD_EXIT_BADINPUT 2 are in
 * scene.h). */
enum { CTD_EXIT_USAGE = 1, CTD_EXIT_UNSTABLE = 4, CTD_EXIT_OUTPUT = 5 };

/* The state an interface sees at cycle `step`: positions x(n) at `time`,
 * velocities v(n-1/2), lumped masses, the part id of each node. dt is the
 * step that led to x(n) (0 at the first cycle). */
typedef struct ctd_state {
    double time, dt;
    int64_t step;
    ct_idx nnode;
    const ct_real *x, *y, *z;
    const ct_real *vx, *vy, *vz;
    const ct_real *m;
    const int32_t *part;
    /* The largest step the solver can take after this cycle: dt_scale
     * times the elements' and rigid bodies' limits at x(n) (contact only
     * lowers it); 0: unknown. */
    double dt_max;
} ctd_state;

/* What one interface reports for one cycle. The solver zeroes the report
 * before each call, except the fields marked (in). */
typedef struct ctd_contact_report {
    double energy;      /* stored (penalty) contact energy at x(n) */
    double damping;     /* energy dissipated by normal damping in this step (>= 0) */
    double friction;    /* energy dissipated by friction in this step (>= 0) */
    double dt_limit;    /* the interface's stable step (no safety factor);
                           0 or CTD_DT_NONE: no limit */
    double dt_kin;      /* the TYPE7/11 kinematic step (g - p)/(2 (-vn)) among
                           the limits behind dt_limit (0: none), so that an
                           observer can tell which limit controls */
    double force;       /* magnitude of the total contact force on the
                           secondary side (the main side gets the opposite) */
    double fvec[3];     /* that force as a vector */
    int64_t active;     /* active pairs */
    int64_t resorts;    /* re-sorts (searches) so far */
    double margin;      /* the re-sort margin in use (0: not chosen yet) */
    int64_t excluded;   /* Irem_gap 2: candidate pairs the neighbour
                           exclusion took out of the first search */
    double t_search, t_narrow, t_force, t_assembly; /* seconds in this cycle */
    /* (in) 1 at output cycles: the hook may then fill the per-node fields
     * below (zeroed by the solver; each hook keeps the larger penetration
     * and adds its active pair count). */
    int want_fields;
    ct_real *pen;          /* (in) [nnode] penetration per node */
    int32_t *node_active;  /* (in) [nnode] active pairs per node */
    /* On failure (a negative return): the entity and a full sentence. */
    int64_t bad_node;      /* node index or -1 */
    char msg[512];
} ctd_contact_report;

/*
 * One interface. contact_step is called once per cycle after the element
 * forces, with the state at x(n); it ADDS its nodal forces into fx, fy, fz
 * (the solver's contact-force arrays, zeroed before the first interface),
 * fills rep and returns CT_OK or a negative CT_ERR_* code (the run then
 * stops as unstable for CT_ERR_NONFINITE, CT_ERR_DEGENERATE and
 * CT_ERR_NOCONV, as an error otherwise). It must not allocate once its
 * workspaces have grown (re-sorts aside), and must be deterministic.
 * destroy (may be NULL) releases ctx when the solver is destroyed.
 */
typedef int (*ctd_contact_step_fn)(void *ctx, const ctd_state *s, ct_real *fx, ct_real *fy,
                                   ct_real *fz, ctd_contact_report *rep);

typedef struct ctd_contact_hook {
    const char *name;    /* label (the scene's name or "if<index>") */
    int type;            /* 3, 5, 6, 7, 11, 24 */
    const char *search;  /* search algorithm name */
    void *ctx;
    ctd_contact_step_fn contact_step;
    void (*destroy)(void *ctx);
    /* Bytes the interface holds (its arrays, search and assembly
     * workspaces); may be NULL. They only grow, so at the end of a run
     * this is the run's peak. */
    size_t (*memory)(const void *ctx);
    /* A remark on the interface's set-up for the reports of `check` and
     * `run` ("" when none): ctd_iface_self_gap_note's. */
    char note[400];
} ctd_contact_hook;

/*
 * The interfaces of a scene, built on a model (driver/interfaces/build.c).
 * *hooks receives a malloc'd
 * array of *nhook hooks (the solver takes ownership of it and of each
 * ctx). Returns CT_OK or a negative code with err naming the interface.
 */
int ctd_interfaces_build(const ctd_model *m, const ctd_scene *sc, ctd_contact_hook **hooks,
                         int *nhook, char *err, size_t errlen);

struct ctd_solver;

/* With no thread count given (opts.threads, solver.threads, nor
 * OMP_NUM_THREADS), a run takes at most one thread per this many nodes.
 * Measured with LLVM's OpenMP runtime (docs/DESIGN-CHANGES.md §9), medians
 * of three runs, 1 against 2 threads: the folding sheet at refine 2 (531
 * nodes) 0.48 s and 0.48, at refine 3 (1144 nodes) 1.60 and 1.40; the
 * showcase (730 nodes) 0.78 and 0.92. */
#define CTD_NODES_PER_THREAD 1000

typedef struct ctd_solver_opts {
    double end_time;     /* > 0: overrides the scene's */
    double dt_scale;     /* > 0: overrides solver.dt_scale (any value: for experiments) */
    double every;        /* > 0: overrides output.every */
    int threads;         /* > 0: overrides solver.threads */
    const char *out_dir; /* NULL: the scene's output directory */
    int no_output;       /* 1: write no file at all (tests) */
    int quiet;           /* 1: no progress line and no report */
    int progress;        /* -1: on a terminal (stderr) only; 0 off; 1 on */
    FILE *report;        /* the report's stream (NULL: stdout) */
    int64_t max_cycles;  /* > 0: stop (status "ok") after this many cycles */
    int64_t cycle_limit; /* > 0: overrides solver.cycle_limit (ignored with max_cycles) */
    int dry;             /* 1: cycle 0 only (forces, contact, stable step and the
                            cycle-limit estimate, with every check of a run), then
                            stop with s->dt the stable step found (contact check) */
    /* Called once per cycle (NULL: never), after the kick: s->time, the
     * positions x(n), the velocities v(n+1/2) (rigid bodies' nodes
     * included), s->dt (the step that led to x(n)) and each interface's
     * report of x(n) in s->rep[i]. Energies in s->e are those of the last
     * evaluation (every 100 cycles and at output steps). It records; it
     * must not change the solver. Histories for validation and embedding
     * codes come from here. */
    void (*observe)(void *ctx, const struct ctd_solver *s);
    void *observe_ctx;
} ctd_solver_opts;

/* The defaults: nothing overridden, progress -1. */
ctd_solver_opts ctd_solver_default_opts(void);

typedef struct ctd_energies {
    double kinetic, internal, contact, damping, friction, external;
    double total;  /* kinetic + internal + contact + damping + friction */
    double error;  /* (total - E_0 - external) / max(E) */
    /* The contact's part of error: (contact + damping + friction + W_c) /
     * max(E), W_c the work the contact forces have done on the nodes (and
     * rigid bodies), as the kinetic energy m v- . v+ / 2 counts it. 0 when
     * the interfaces' books are the work their forces do; the rest of
     * error is the elements', loads' and constraints'. */
    double contact_error;
} ctd_energies;

typedef struct ctd_timers {
    double search, narrow, force, assembly, elements, other, total;
} ctd_timers;

struct cti_solver_work;

typedef struct ctd_solver {
    ctd_model *model;
    ctd_solver_opts opts;
    double end_time, dt_scale, every;
    int64_t cycle_limit; /* a run needing more cycles fails (exit 2) */
    int threads;
    /* The state: x(n), the latest velocities (half step), forces. */
    ct_idx nnode;
    ct_real *x, *y, *z, *vx, *vy, *vz;
    double time, dt;
    /* The largest step allowed at the last step (the stable step x
     * dt_scale, or the output interval when that is smaller: then
     * dt_by_output), which dt evens out to land on end_time in equal steps. */
    double dt_max;
    int dt_by_output;
    int64_t cycle;
    /* Energies at the last evaluation, at the start, and the extremes. */
    ctd_energies e, e0;
    double e_max, error_max;
    int64_t output_steps;
    ctd_timers timers;
    /* Interfaces. */
    int nhook;
    ctd_contact_hook *hooks;
    ctd_contact_report *rep;
    double *if_force_max;
    int64_t *if_active_max;
    /* The nodes within their gap at cycle 0 (initial penetrations): how
     * many, the deepest p = gap - distance and its node (-1 when none). */
    int64_t pen0_count;
    double pen0_max;
    ct_idx pen0_node;
    /* Outcome of ctd_solver_run. */
    const char *status;  /* "ok", "unstable", "error", "out of memory" */
    int exit_code;
    char message[512];
    char out_dir[1024];  /* "" when nothing is written */
    double wall;
    struct cti_solver_work *w;
} ctd_solver;

/*
 * Prepare a run of model m with the given interfaces (hooks may be NULL
 * when nhook is 0; the solver takes ownership of the hooks array, which
 * must be malloc'd, and of each ctx). Opens the output directory (unless
 * no_output): an unwritable directory fails here. Returns CT_OK or a
 * negative CT_ERR_* code with err saying what failed.
 */
int ctd_solver_init(ctd_solver *s, ctd_model *m, const ctd_solver_opts *opts,
                    ctd_contact_hook *hooks, int nhook, char *err, size_t errlen);

/* Run to the end time. Returns the exit code: CTD_EXIT_OK, CTD_EXIT_UNSTABLE
 * (s->message says where and when), CTD_EXIT_BADINPUT (an interface's
 * search found more pairs than the machine holds: its gap is far above the
 * element size), or CTD_EXIT_OUTPUT (a file could not be written). Writes the series, history, summary and plot, and prints the
 * report (unless quiet). */
int ctd_solver_run(ctd_solver *s);

void ctd_solver_destroy(ctd_solver *s);

/* Total linear momentum (sum m v over the nodes not in rigid bodies, plus
 * M v_c of each body) from the latest velocities. */
void ctd_solver_momentum(const ctd_solver *s, double p[3]);

/* The nodes in contact at the last cycle that filled the output fields
 * (every output cycle, cycle 0 among them): how many have a positive
 * penetration p = gap - distance on some interface, the deepest p and its
 * node (index; -1 and 0 when none). */
void ctd_solver_penetration(const ctd_solver *s, int64_t *count, double *pmax, ct_idx *node);

/* "PREFIXinitial penetration: ..." from pen0_*: none, or how many nodes
 * start within their gap and the deepest (its depth, node id and part);
 * nothing without interfaces. In the run's report and `contact check`. */
void ctd_solver_print_penetration(FILE *f, const char *prefix, const ctd_solver *s);

/* Bytes held by interface i (its hook's memory), -1 when its hook does not
 * say or i is out of range. */
int64_t ctd_solver_if_memory(const ctd_solver *s, int i);

#ifdef __cplusplus
}
#endif

#endif /* CTD_SOLVER_H */
