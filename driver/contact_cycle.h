/*
 * contact_cycle.h -- one node-to-segment contact interface run cycle after
 * cycle with the library's kernels (DESIGN.md section 4), prefix ctd_.
 *
 * A cycle is:
 *  1. search: the re-sort criterion (ct_resort_needed, positions at the last
 *     sort kept; with the skip, ct_resort_track, which bounds the step
 *     since the last cycle in the same pass over the nodes); when it fires
 *     (and at the first cycle), the candidate search (ct_search_run), the
 *     assembly preparation (ct_asm_seg_slots, ct_assemble_prepare) and the
 *     friction history carried from the old pair list to the new one
 *     (ct_friction_remap);
 *  2. narrow phase (ct_narrow_node_segment) of every candidate that may be
 *     in contact: with the skip on (the default, see below), a candidate
 *     whose last computed distance exceeds the gap by more than the motion
 *     since then cannot be in contact and keeps its last results; then the
 *     pairs that carry each node (ct_select_pairs, one per side: over a
 *     vertex shared by four segments one pair applies the force, not
 *     four), the others' penetration set to 0. A node's pairs cut by a
 *     block boundary are decided whole: each block evaluates the other
 *     block's pairs of that node again, for the decision only;
 *  3. force, for the pairs in contact (p > 0; the others get zero force and
 *     zero friction history): the relative velocity at the contact point, the normal law
 *     (TYPE7, ct_penalty_type7, or linear), damping and the normal force
 *     vector (ct_normal_finish / ct_normal_force), Coulomb friction
 *     (ct_friction_step), and the total pair force;
 *  4. assembly into the nodal force arrays: by default the colouring, of
 *     blocks of the pass itself, each block adding its own pairs in contact
 *     from a compact list the pass leaves (a fraction of the candidates:
 *     the others' zero forces are never stored nor read); the other
 *     variants with ct_assemble on every candidate's pair force;
 *  5. time step, for the pairs in contact: TYPE7 kinematic
 *     (ct_dt_type7_kinematic) and nodal (ct_dt_nodal with the contact
 *     tangent stiffness).
 * Each phase is timed (omp_get_wtime) and the times accumulate in the
 * interface's statistics.
 *
 * Memory: per-pair arrays are allocated at a re-sort when the pair count
 * exceeds their capacity (grown with 50% headroom) and kept; a cycle
 * without a re-sort allocates nothing, and neither does a re-sort whose
 * pairs fit. The per-thread scratch of the force pass is allocated at
 * creation for omp_get_max_threads() threads, and again only by a cycle
 * run with more threads than any before. Results are bit-identical for any OMP_NUM_THREADS.
 */
#ifndef CTD_CONTACT_CYCLE_H
#define CTD_CONTACT_CYCLE_H

#include <stdint.h>

#include "contact.h"

/* Normal force law of the interface. */
typedef enum ctd_cycle_law {
    CTD_LAW_TYPE7 = 0, /* K = K0 g / (g - p) (ct_penalty_type7) */
    CTD_LAW_LINEAR = 1 /* F = K0 p (ct_normal_force) */
} ctd_cycle_law;

typedef struct ctd_cycle_params {
    ct_search_algo algo;        /* broad phase (bucket by default) */
    ct_search_filter filter;    /* shared predicate (hull by default) */
    ct_quad_method quad;        /* node-quad projection (4tri by default) */
    ct_assemble_variant asm_variant; /* assembly (colour by default) */
    ctd_cycle_law law;          /* TYPE7 by default */
    int two_sided;              /* 1: shells (default), 0: oriented solids */
    ct_real gap;                /* contact distance of a pair */
    ct_real margin;             /* re-sort margin; search distance gap + margin */
    ct_real K0;                 /* penalty stiffness (per pair, uniform) */
    ct_real viss;               /* normal damping ratio */
    ct_real mu;                 /* Coulomb coefficient (0: no friction) */
    ct_real kt;                 /* tangential (stick) stiffness */
    int skip;                   /* 1 (default): skip the narrow phase of the
                                   candidates that provably are out of contact */
    int select;                 /* 1 (default): the pairs that carry each node,
                                   one per side (ct_select_pairs); 0: every
                                   pair in contact applies its force */
} ctd_cycle_params;

/*
 * The skip. Every point of a segment (the 4-triangle surface of a quad, or
 * a triangle) is a convex combination of its corners, so the node-segment
 * distance shrinks by no more than the bound of the re-sort criterion
 * (ct_resort_needed: the smaller of the largest secondary step plus the
 * largest main step and the relative bound per axis, 0 for a rigid
 * motion). The cycle sums that bound from one cycle to the next (positions
 * of the previous cycle kept; ct_resort_track evaluates it with the re-sort
 * criterion, in one pass); a candidate whose distance D was
 * computed when that sum was M_c needs no narrow phase while the sum stays
 * below M_c + (D - gap - slack): its distance is still above the gap, so
 * its penetration, force, friction history and step limit are the zeros a
 * narrow phase would give. The slack, 1024 machine epsilons times the
 * largest coordinate plus the gap, covers the rounding of D; the sum is
 * scaled by 1 + 1e-6 for its own. Forces, histories and steps are
 * therefore those of the full evaluation, bit for bit (tests/test_cycle.c
 * checks it). A skipped candidate's penetration (ctd_cycle_geo) reads 0
 * and its flag is left over. The bound is carried
 * across a re-sort for the pairs that survive it (new pairs are evaluated).
 * It holds for the exact distances the skip uses: two-sided contact with
 * triangles and the 4-triangle quad method. With one-sided contact (a node
 * behind a segment is in contact without crossing it) or the Newton and
 * closed-form methods (their distance to the patch is not a bound) every
 * candidate is evaluated, whatever `skip` says.
 */

/* The defaults: bucket, hull filter, 4tri, colour, TYPE7, two-sided,
 * gap 0.3 h, margin 0.2 h, K0 = 1, viss 0.05, Coulomb 0.2, kt = K0, skip
 * on (h the mean main edge length the caller passes). */
ctd_cycle_params ctd_cycle_default_params(double h);

/* Phases, the index into the time array of the statistics. */
enum { CTD_PH_SEARCH = 0, CTD_PH_NARROW, CTD_PH_FORCE, CTD_PH_ASSEMBLE, CTD_PH_TIMESTEP,
       CTD_PH_N };

/* Accumulated over the cycles since the last ctd_cycle_stats_reset. */
typedef struct ctd_cycle_stats {
    int64_t cycles;            /* cycles run */
    int64_t resorts;           /* searches run (the first one included) */
    int64_t cand_sum;          /* candidate pairs, summed over cycles */
    int64_t active_sum;        /* active pairs (p > 0), summed over cycles */
    int64_t eval_sum;          /* pairs through the narrow phase, summed */
    double t[CTD_PH_N];        /* seconds spent in each phase */
    double t_sort;             /* of t[CTD_PH_SEARCH]: seconds in the searches
                                  (with their preparation and remap); the rest
                                  is the re-sort check */
    /* Of the last cycle: */
    ct_idx ncand, nactive, neval;
    ct_real bound;             /* displacement bound of the re-sort check */
    ct_real dt_kin, dt_nodal;  /* smallest step of each kind (CT_DT_NONE: none) */
    /* Over the interface's life (not reset): cycles, searches fired by the
     * criterion and the sum of the intervals (in cycles) that ended with
     * them, so interval_sum / natural_sorts is the mean re-sort interval. */
    int64_t life_cycles, life_last_sort, natural_sorts, interval_sum;
} ctd_cycle_stats;

typedef struct ctd_cycle ctd_cycle;

/*
 * Create an interface over the node arrays (nnode nodes, masses m), the
 * secondary nodes sec[0..nsec-1] (sorted ascending: the friction history
 * matches pairs by (node, segment)), the main nodes mainn[0..nmain-1] (for
 * the re-sort criterion; for self contact pass sec again) and the main
 * segments n1..n4[0..nseg-1]. The arrays are not copied and must outlive
 * the interface. self: 1 for one surface against itself. Returns CT_OK,
 * CT_ERR_ARG (also for a NaN or infinite K0, viss, mu or kt, which the
 * force kernels would refuse every cycle) or CT_ERR_NOMEM.
 */
int ctd_cycle_init(ctd_cycle **cy, const ctd_cycle_params *p, ct_idx nnode, const ct_real *m,
                   ct_idx nsec, const ct_idx *sec, ct_idx nmain, const ct_idx *mainn,
                   ct_idx nseg, const ct_idx *n1, const ct_idx *n2, const ct_idx *n3,
                   const ct_idx *n4, int self);
void ctd_cycle_destroy(ctd_cycle *cy);

/*
 * One cycle at positions x, y, z and velocities vx, vy, vz (length nnode),
 * time step dt (damping dissipation and the friction predictor). The
 * contact forces are written into fxn, fyn, fzn (length nnode; zeroed
 * first, inside the assembly phase). The statistics accumulate. A failing
 * kernel's code is returned (the interface then must be destroyed).
 */
int ctd_cycle_step(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z,
                   const ct_real *vx, const ct_real *vy, const ct_real *vz, ct_real dt,
                   ct_real *fxn, ct_real *fyn, ct_real *fzn);

/* Size the per-pair arrays and pair lists for npair pairs now (exactly;
 * the pair lists get ct_pairs_reserve's 25% on top), so that later
 * re-sorts up to that count allocate nothing. */
int ctd_cycle_reserve(ctd_cycle *cy, ct_idx npair);

/* Force the next cycle to search (e.g. after a jump of the positions). */
void ctd_cycle_force_resort(ctd_cycle *cy);

/* The statistics, and their reset (the per-cycle "last" fields stay). */
const ctd_cycle_stats *ctd_cycle_get_stats(const ctd_cycle *cy);
void ctd_cycle_stats_reset(ctd_cycle *cy);

/* The current candidate pairs (valid until the next step). */
const ct_pairs *ctd_cycle_pairs(const ctd_cycle *cy);

/* The narrow-phase results the cycle keeps, one element per candidate:
 * pen (0 out of contact), the flag of every candidate evaluated in the
 * last cycle, and, with an assembly variant other than the colouring, the
 * weights h1..h4 of the candidates in contact (the others hold left-over
 * values; with the colouring, the weights go to the compact lists the
 * assembly reads, and h1..h4 are NULL). The other fields are NULL: the
 * force pass takes them from its block scratch, and storing them for
 * every pair cost more than the narrow phase the skip saves. */
const ct_contact_geo *ctd_cycle_geo(const ctd_cycle *cy);
/* 1 for each candidate whose narrow phase ran in the last cycle, 0 for one
 * the skip left alone; NULL when the skip is off. */
const uint8_t *ctd_cycle_evaluated(const ctd_cycle *cy);
/* Component axis (0, 1, 2) of the tangential friction force of each
 * candidate after the last cycle: the history the next cycle's predictor
 * starts from (zero for a pair out of contact). NULL for a bad axis. */
const ct_real *ctd_cycle_friction(const ctd_cycle *cy, int axis);

/* Bytes held by the interface (per-pair arrays, search and assembly
 * workspaces, positions at the last sort). */
size_t ctd_cycle_memory(const ctd_cycle *cy);


/* ---- A prescribed motion for benchmarks and tests -------------------------
 *
 * Positions from reference positions X (axis index 0, 1, 2 for x, y, z):
 * along the compression axis c the nodes are scaled about `centre` by
 *     f(phi) = s0 - s1 (1 - cos phi) / 2,   phi = 2 pi cycle / period,
 * so the layers stacked along c approach each other (s0 < 1 compresses
 * from the start), and along the slide axis s they move by
 *     slide sin(phi) cos(2 pi X_c / wavelength),
 * so neighbouring layers (half a wavelength apart along c) slide in
 * opposite directions. Velocities are the time derivatives with
 * dphi/dt = 2 pi / (period dt). The motion is periodic, so any number of
 * cycles stays bounded. */
typedef struct ctd_motion {
    int axis_c, axis_s;
    double centre, s0, s1, slide, wavelength;
    double period; /* cycles per period */
} ctd_motion;

/* Largest displacement of a node over one cycle for reference coordinates
 * along c within [centre - rc, centre + rc] (an upper bound). */
double ctd_motion_max_step(const ctd_motion *mo, double rc);

/* Positions and velocities of n nodes at cycle `cycle` (time cycle * dt). */
void ctd_motion_eval(const ctd_motion *mo, ct_idx n, const ct_real *const ref[3],
                     double cycle, double dt, ct_real *const pos[3], ct_real *const vel[3]);

#endif /* CTD_CONTACT_CYCLE_H */
