/*
 * iface.h -- the contact interfaces of the driver (TYPE3, TYPE5, TYPE6,
 * TYPE7, TYPE11, TYPE24), prefix ctd_iface, each composed from the kernels
 * of contact.h (DESIGN.md sections 4 to 8, seeds 000, 001, 002 and 004).
 *
 * One object serves every type. The solver resolves the scene's selections
 * into raw arrays (ctd_iface_data: global node indices, per-segment and
 * per-node stiffness inputs, per-node gaps) and the card into a
 * ctd_iface_cfg; ctd_iface_init copies what it needs, so the caller's
 * arrays may be freed afterwards. Every cycle ctd_iface_step reads the
 * positions, velocities and masses (length nnode), ADDS the contact forces
 * into fx, fy, fz, and fills a report (energies, time-step limits, counts,
 * timers).
 *
 * What each type does:
 *  - TYPE3: surface to surface between two oriented solid surfaces, in two
 *    passes: the secondary surface's nodes against the main segments, and
 *    the main surface's nodes against the secondary segments. Linear law
 *    with the stiffness of two springs in series, K = Stfac Km Ks/(Km + Ks)
 *    (Km the segment stiffness, Ks the node stiffness; seed 000), VisS
 *    damping, friction. Topological search and the closed-form quad
 *    projection by default, as in Radioss.
 *  - TYPE5: secondary nodes against the main surface, one pass, one-sided
 *    unless two_sided; otherwise as TYPE3 (seed 000). The reaction goes to
 *    the main nodes with the shape functions, F_i = N_i(s_c, t_c) F.
 *  - TYPE6: two rigid bodies (seed 004): secondary nodes (sec, and the
 *    nodes of the secondary segments) against the main segments, one pass.
 *    The total normal force is F = f(p_max), a user curve (piecewise-linear
 *    table) of the largest penetration, spread over the penetrating nodes in
 *    proportion to their penetration; the stored energy is the integral of
 *    f from 0 to p_max; the time step is 0.1 sqrt(M_min / K) with
 *    K = max(f'(p_max), f(p_max)/p_max), at the curve's first point
 *    beyond zero before anything penetrates (report field dt_curve).
 *  - TYPE24: node-to-surface penalty with a constant stiffness. Passes:
 *    secondary nodes (plus grnd_IDs) against the main segments; with
 *    `symmetric` (surface to surface) also the main surface's nodes against
 *    the secondary segments; a single surface (self) is one pass of its own
 *    nodes against its own segments. Linear law with stiffness blending
 *    (ct_penalty_linear), initial penetration by Inacti / Ipen0 / Ipen_max,
 *    VisS damping, friction Ifric 0..4 with the Ifiltr / Xfreq filter.
 *  - TYPE7: one surface against itself, both sides, gap from the shell
 *    thickness (at least cfg.gap), the nonlinear TYPE7 law, damping,
 *    friction, the kinematic time step.
 *  - TYPE11: edges against edges (the edges of a surface against
 *    themselves, or set A against set B), TYPE7 law, forces on the four edge
 *    nodes (force and moment balanced); no friction.
 * The node-to-segment types (3, 5, 6, 7, 24) share one pass engine: the
 * narrow phase, one carrying pair per node side, the normal law, damping,
 * friction and the race-free assembly. A linear pass (3, 5, 24) blends the
 * stiffness when a penetration jumps (ct_penalty_linear), so a node found
 * deep inside does not release energy no motion put in. In TYPE3, TYPE5
 * and TYPE6 a node never pairs with a segment it belongs to (the seed
 * forbids a node on both sides; this makes one harmless).
 * Every type searches with the algorithm of cfg.algo (TYPE11: direct, or its
 * own bucket grid over edge boxes for the other three names) and repeats the
 * search only when the re-sort criterion fires (ct_resort_needed).
 *
 * Results are bit-identical for any OMP_NUM_THREADS. Nothing is allocated
 * per cycle once the pair arrays have grown to size.
 */
#ifndef CTD_IFACE_H
#define CTD_IFACE_H

#include <stdint.h>

#include "contact.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The parameters, named as in the Radioss cards. */
typedef struct ctd_iface_cfg {
    int type;       /* 3, 5, 6, 7, 11 or 24 */
    int self;       /* 24: single surface (no secondary set); 7 and 11: always
                       self unless data has a second edge set (11); not
                       used by 3, 5, 6 */
    int symmetric;  /* 24: surface to surface, both passes (3 always has
                       both) */
    int two_sided;  /* 3, 5, 6, 24: 1 for shell surfaces (gap on both sides,
                       needs gap > 0), 0 for oriented solid faces (the
                       default); 7 is always two-sided */
    ct_search_algo algo;             /* broad phase (bucket by default) */
    ct_search_filter filter;         /* shared predicate (hull by default) */
    ct_quad_method quad;             /* node-quad projection (4tri) */
    ct_assemble_variant asm_variant; /* assembly (colour) */
    /* Stiffness. TYPE24 Istf: 0 or 2 mean, 3 max, 4 min, 5 series, 1 or
     * 1000 main only. TYPE7/11: 1 -> K0 = Stfac (the stiffness itself),
     * otherwise K0 = Stfac * Kseg / 2 (Radioss halves it in this law).
     * TYPE3/5 (Istf not read): springs in series, K = Stfac Km Ks/(Km + Ks);
     * with no node stiffness inputs, or for a node whose stiffness is 0 (a
     * beam or spring node), K = Stfac Km; with data.K > 0, K = Stfac K.
     * TYPE6 ignores them (the curve is the law). The result is clamped to
     * [Stmin, Stmax] (Stmax 0: no upper bound). */
    int Istf;
    ct_real Stfac, Stmin, Stmax;
    /* Gap: `gap` is the constant gap (3, 5, 6, and 24 with Igap0 = 0) or
     * the minimum gap (24 with Igap0 = 1, 7, 11). Igap0 = 1 (and always for 7 and 11): the
     * gap of a pair is max(gap, g_s + g_m) with the per-node gaps of the
     * data capped by Gap_max_s and Gap_max_m (0: no cap). */
    ct_real gap;
    int Igap0;
    ct_real Gap_max_s, Gap_max_m;
    /* Initial penetration (24, at the first active cycle): Ipen0 = 1 gives
     * every initial penetration the full force (nothing recorded); with
     * Ipen0 = 0, Inacti != 0 subtracts it (CT_INACTI_SUBTRACT) and
     * Ipen_max > 0 deactivates the pairs penetrated deeper than it. */
    int Ipen0, Inacti;
    ct_real Ipen_max;
    ct_real VisS; /* normal damping ratio */
    /* Friction: Ifric 0 Coulomb (mu = Fric; off when Fric = 0), 1 poly,
     * 2 Darmstad, 3 Renard, 4 exponential decay (ct_fric_law), C[0..5] =
     * C1..C6; the filter Ifiltr 0..3 with Xfreq (ct_filter_alpha). The
     * tangential stiffness is kt_scale times the pair's stiffness (0 ->
     * 1). */
    int Ifric;
    ct_real Fric, C[6];
    int Ifiltr;
    ct_real Xfreq, kt_scale;
    /* The area the contact pressure of the pressure-dependent laws (Ifric
     * 1 and 2) divides a pair's normal force by: CTD_PAREA_MAIN, the main
     * segment's (the Radioss definition, the default), or
     * CTD_PAREA_SECONDARY, the secondary node's share of the surface that
     * faces the contact (iface_area.c), which needs the model's segments
     * in the data (nmseg, m1..m4) and every secondary node on one. */
    int pressure_area;
    /* Active for Tstart <= time <= Tstop (Tstop 0: never stops). */
    double Tstart, Tstop;
    /* 7, 11 and 24 on one surface (Radioss's TYPE25 Igap 2 there): Irem_gap
     * 2 takes each node's (each edge's) surface neighbours within the gap
     * out of its contact (ct_exclusion, ct_search.h): the segments (edges)
     * within the interface's largest contact gap at the first search (the
     * start, or Tstart) and joined to the node (edge) through segments
     * (edges) all within it. 0 or 1: no exclusion. */
    int Irem_gap;
    /* Re-sort margin (search distance gap + margin); 0 -> 0.2 times the
     * mean edge length of the main segments (or edges). */
    ct_real margin;
    /* Bytes the pair arrays of one pass may take (0: the machine's
     * physical memory). A search that finds more pairs than fit fails the
     * step with CT_ERR_NOMEM and says so in the report's msg, instead of
     * allocating what the system cannot hold (where Linux kills the
     * process rather than fail the allocation). */
    double mem_limit;
    /* TYPE6: the force curve f(p), ncurve points (curve_p strictly
     * ascending, every value finite: ct_curve_check), total normal force
     * against the largest penetration; between and beyond the points f is
     * linear (extrapolated from the end intervals), and a negative f counts
     * as 0. Borrowed here: ctd_iface_init copies the table. */
    ct_idx ncurve;
    const ct_real *curve_p, *curve_f;
} ctd_iface_cfg;

/* ctd_iface_cfg.pressure_area. */
enum { CTD_PAREA_MAIN = 0, CTD_PAREA_SECONDARY = 1 };

/* Defaults for a type:
 *  - 24, 7, 11: bucket search, 4tri, Stfac 1, VisS 1.0 (24) or 0.05 (7,
 *    11), two-sided and self for 7 and 11;
 *  - 3, 5: topological search, closed-form quad projection, Stfac 0.2 (the
 *    seed's series scale), VisS 0, one-sided;
 *  - 6: bucket search, closed-form quad projection, Stfac 0.2 (unused),
 *    VisS 0, one-sided, gap 0, no curve (the caller must give one);
 * and for all: hull filter, colour assembly, kt_scale 1, everything else 0
 * as in the scene defaults. */
ctd_iface_cfg ctd_iface_default_cfg(int type);

/*
 * The resolved data. Node indices are global (0 .. nnode-1); per-node
 * arrays are indexed by the global node index and have nnode entries.
 * Only the arrays a type needs are read; NULL means "none".
 *  - main segments n1..n4 (n4 == n3 for a triangle): the surface of 7, the
 *    main surface of 3, 5, 6 and 24, the surface whose edges 11 uses when
 *    it has no explicit edges;
 *  - secondary nodes sec (5, 6, 24 nodes to surface; any order, duplicates
 *    allowed) and secondary segments s1..s4 (3, and 24 surface to surface:
 *    their nodes are secondary nodes too, and the second pass uses them;
 *    6: their nodes are secondary nodes, nothing more);
 *  - grnd (24): extra secondary nodes;
 *  - edges (11): ea1/ea2 (set A) and eb1/eb2 (set B, nb = 0: A against
 *    itself); without edges, A is the unique edges of the main segments;
 *  - stiffness: K > 0 is a given stiffness for every pair (scaled by Stfac,
 *    clamped); otherwise segment inputs seg_E, seg_t (shells), seg_B, seg_A,
 *    seg_V (brick faces), see ct_seg_stiffness, for the main segments, and
 *    ssg_* the same for the secondary segments, and node inputs node_B,
 *    node_vnode, node_et (ct_node_stiffness) for the nodes;
 *  - gap_node: per-node gap (half the shell thickness; 0 for solids; read
 *    by 7, 11, and 24 with Igap0 = 1);
 *  - mass_min (6): the smaller of the two rigid bodies' masses for the
 *    time step; 0 -> the smaller of the sums of the nodal masses m of each
 *    side's nodes (secondary nodes, main segment nodes) at the first
 *    active step;
 *  - m1..m4 (nmseg): the model's surface segments, read only with
 *    pressure_area CTD_PAREA_SECONDARY and a pressure-dependent law.
 */
typedef struct ctd_iface_data {
    ct_idx nnode;
    ct_idx nseg;
    const ct_idx *n1, *n2, *n3, *n4;
    ct_idx nsec;
    const ct_idx *sec;
    ct_idx nsseg;
    const ct_idx *s1, *s2, *s3, *s4;
    ct_idx ngrnd;
    const ct_idx *grnd;
    ct_idx nea, neb;
    const ct_idx *ea1, *ea2, *eb1, *eb2;
    ct_real K;
    const ct_real *seg_E, *seg_t, *seg_B, *seg_A, *seg_V;
    const ct_real *ssg_E, *ssg_t, *ssg_B, *ssg_A, *ssg_V;
    const ct_real *node_B, *node_vnode, *node_et;
    const ct_real *gap_node;
    ct_real mass_min;
    /* Every surface segment of the model (shells, faces of bricks and of
     * rigid bodies), for pressure_area CTD_PAREA_SECONDARY: the secondary
     * nodes' areas come from those they are corners of. */
    ct_idx nmseg;
    const ct_idx *m1, *m2, *m3, *m4;
} ctd_iface_data;

/* Timer slots of the report (seconds). */
enum { CTD_IT_SEARCH = 0, CTD_IT_NARROW, CTD_IT_FORCE, CTD_IT_ASSEMBLE, CTD_IT_N };

/* What one step reports. Energies in double; time steps CT_DT_NONE when the
 * interface sets no limit. */
typedef struct ctd_iface_report {
    int on;                /* 1 when Tstart <= time <= Tstop */
    double e_contact;      /* elastic energy stored in the contact springs now,
                              normal and (friction's elastic predictor)
                              tangential (TYPE6: the integral of the curve
                              from 0 to p_max) */
    double e_damp;         /* normal damping dissipation of this step: the
                              damping force's work over the step by the
                              trapezoidal rule (ct_damping_work; may be
                              negative near the damped stability limit,
                              where the scheme itself feeds energy in) */
    double e_fric;         /* friction dissipation of this step: minus the
                              friction force's work over the step by the
                              trapezoidal rule, less the change of its
                              tangential springs' energy (which e_contact
                              holds); may be negative in a step where a
                              spring gives back what it stored */
    double force[3];       /* total force on the secondary side (sum over
                              pairs of the force on the secondary node or
                              edge A; TYPE3's second pass counts minus the
                              force on its node, a main node); the main side
                              gets the opposite */
    ct_real kmax;          /* largest pair stiffness (tangent) this step
                              (TYPE6: the curve's K) */
    ct_real dt_nodal;      /* min over pairs of sqrt(2 m / (kelem + k)) at the
                              secondary node (kelem from ctd_iface_set_kelem) */
    ct_idx dt_node;        /* the node that sets dt_nodal (-1: none) */
    ct_real dt_kin;        /* TYPE7/11 kinematic step (g - p) / (2 (-vn)) */
    ct_real dt_tunnel;     /* 0.9 gap_min / |v_rel,max| over the candidates */
    ct_real dt_curve;      /* TYPE6 0.1 sqrt(M_min / K), K = max(f'(p_max),
                              f(p_max)/p_max), p_max the first curve point
                              beyond 0 while nothing penetrates (TYPE6 sets
                              no dt_nodal: its nodes move with their rigid
                              bodies) */
    ct_real dt;            /* min of the four */
    ct_idx ncand, nactive; /* candidate and active pairs (all passes) */
    int resorted;          /* searches run in this step */
    int64_t resorts;       /* searches over the interface's life */
    ct_real margin;        /* the re-sort margin in use (cfg.margin, or the
                              default chosen at the first step; 0 before) */
    int64_t deactivated;   /* pairs deactivated by Ipen_max so far */
    int64_t excluded;      /* Irem_gap 2: the candidate pairs the neighbour
                              exclusion took out of the first search */
    double t[CTD_IT_N];    /* seconds in each phase this step */
    char msg[512];         /* when the step fails: what the code alone
                              cannot say (empty otherwise) */
} ctd_iface_report;

typedef struct ctd_iface ctd_iface;

/* Create an interface. Returns CT_OK, CT_ERR_ARG (a bad parameter or
 * missing array; diag says which), CT_ERR_RANGE (a node index outside
 * [0, nnode)) or CT_ERR_NOMEM. diag may be NULL. */
int ctd_iface_init(ctd_iface **it, const ctd_iface_cfg *cfg, const ctd_iface_data *data,
                   ct_diag *diag);
void ctd_iface_destroy(ctd_iface *it);

/*
 * One cycle at time `time` with step dt (damping, friction predictor,
 * blending): x, y, z, vx, vy, vz, m have nnode entries; the contact forces
 * are ADDED into fx, fy, fz. rep may be NULL. Outside [Tstart, Tstop]
 * nothing is added and the report is zero (on = 0); the next active cycle
 * searches anew. A failing kernel's code is returned.
 */
int ctd_iface_step(ctd_iface *it, double time, ct_real dt, const ct_real *x, const ct_real *y,
                   const ct_real *z, const ct_real *vx, const ct_real *vy, const ct_real *vz,
                   const ct_real *m, ct_real *fx, ct_real *fy, ct_real *fz,
                   ctd_iface_report *rep);

/* The element stiffness per node (nnode entries, borrowed, may be NULL)
 * used by the nodal time step of the report. */
void ctd_iface_set_kelem(ctd_iface *it, const ct_real *kelem);

/* The largest step the caller can take after the next ctd_iface_step (its
 * other limits: elements, bodies, safety factor; contact only lowers it).
 * With it, an open pair enters the interface's stable step only when it
 * can close its clearance in two such steps at its present relative speed
 * (and always when in contact); without it (0, the default) every pair
 * that carries its node does, and the step then depends on the search
 * margin that made the pair a candidate. */
void ctd_iface_set_dt_max(ctd_iface *it, ct_real dt_max);

/* Force a search at the next cycle. */
void ctd_iface_force_resort(ctd_iface *it);

/* The type (3, 5, 6, 7, 11, 24), and the number of secondary nodes of the first
 * pass (after merging grnd_IDs) or of edges in set A (11). */
int ctd_iface_type(const ctd_iface *it);
ct_idx ctd_iface_nsec(const ctd_iface *it);

/* Check the interface's gaps against the extent of its nodes at x, y, z:
 * CT_ERR_ARG, with a message in msg, when a pair gap (node-segment, or
 * edge-edge for TYPE11; not TYPE6's curve) reaches the diagonal of the box
 * around the nodes of its pass. Every node would then be in contact with
 * every segment: the candidates grow as nsec x nseg and the penalty forces
 * act across the whole model. */
int ctd_iface_check_reach(const ctd_iface *it, const ct_real *x, const ct_real *y,
                          const ct_real *z, char *msg, size_t len);

/* A remark on a self-contact interface whose gap is more than half its
 * surface's shortest edge (node-segment: a pass's largest contact gap
 * against its segments' shortest edge; edge-edge: the pair gap against the
 * shortest edge): a node then comes within the gap of its neighbours'
 * segments when the mesh between is compressed by half, or from the start
 * when the gap exceeds the edge, and the penalty pushes neighbours apart on
 * a flat sheet (Radioss's warning 94 says the same). Returns 1 with the
 * remark in msg, 0 with msg empty otherwise. Not an error: a few small
 * elements may be acceptable. */
int ctd_iface_self_gap_note(const ctd_iface *it, const ct_real *x, const ct_real *y,
                            const ct_real *z, char *msg, size_t len);

/* Bytes held by the interface. */
size_t ctd_iface_memory(const ctd_iface *it);

#ifdef __cplusplus
}
#endif

#endif /* CTD_IFACE_H */
