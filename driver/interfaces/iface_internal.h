/*
 * iface_internal.h -- what the interface files share (not for the solver):
 * the interface object, the node-segment pass engine (iface_pass.c), the
 * pass builder of the node-to-surface types (iface.c), the TYPE6 curve law
 * (type6.c) and the edge pass of TYPE11 (type11.c). Internal names use the
 * prefix ctdi_.
 */
#ifndef CTD_IFACE_INTERNAL_H
#define CTD_IFACE_INTERNAL_H

#include "iface.h"
#include "wtime.h"

#include <math.h>
#include <stdint.h>

/* Loops of the interface code run in parallel only above this many
 * entries: below it the fork/join costs more than the loop (and much more
 * when the cores are shared). Every such loop is element-wise or an exact
 * min/max reduction, so the results do not depend on it. */
#define CTDI_PAR_MIN 2048

/* Normal law of a pass: linear with blending (3, 5, 24), TYPE7's
 * nonlinear law (7), or TYPE6's user curve of the largest penetration. */
enum { CTDI_LAW_LINEAR = 0, CTDI_LAW_TYPE7 = 1, CTDI_LAW_TYPE6 = 2 };

/* Per-pair states carried across re-sorts (double-buffered, remapped). */
enum { CTDI_ST_FTX = 0, CTDI_ST_FTY, CTDI_ST_FTZ, CTDI_ST_P0, CTDI_ST_PPREV, CTDI_ST_FCAP,
       CTDI_ST_QJUMP, CTDI_ST_ACT, CTDI_ST_FDAMP, CTDI_ST_N };

/* Per-pair scratch of one cycle. */
enum { CTDI_R_VRX = 0, CTDI_R_VRY, CTDI_R_VRZ, CTDI_R_VN, CTDI_R_FEL, CTDI_R_KTAN, CTDI_R_FN,
       CTDI_R_FX, CTDI_R_FY, CTDI_R_FZ, CTDI_R_MS, CTDI_R_MM, CTDI_R_K, CTDI_R_EN, CTDI_R_DD,
       CTDI_R_FD, CTDI_R_MU, CTDI_R_PRS, CTDI_R_SPD, CTDI_R_KT, CTDI_R_KDT, CTDI_R_N };

/* One node-segment pass: secondary nodes against main segments. */
typedef struct ctdi_pass {
    /* Geometry (owned copies). */
    ct_idx nsec, nmain, nseg;
    ct_idx *sec, *mainn; /* sorted, unique global node indices */
    /* mainn, or sec when both hold the same nodes (self contact): the
     * re-sort check then reads them once. */
    const ct_idx *mainn_rs;
    ct_idx *n1, *n2, *n3, *n4;
    ct_real *kseg; /* per-segment stiffness with Stfac (NULL: constant K) */
    ct_real *gseg; /* per-segment gap (NULL: none) */
    ct_real sgap;  /* search gap: the largest pair gap */
    ct_real reach; /* sgap without TYPE6's curve: the largest contact gap */
    int self, two_sided, law;
    /* 1 for the second pass of a surface-to-surface interface (its nodes
     * are the interface's main side): its forces count negative in the
     * report's force. */
    int reverse;
    /* The law's totals of the last step: TYPE6's largest penetration,
     * curve stiffness and stored energy (the energy is not held per pair). */
    ct_real pmax, kcurve;
    /* TYPE6: the largest penetration the last search's pairs hold for
     * certain (iface_pass.c, search_gap); beyond it the law asks for a
     * re-sort. The prune's per-pair distances (2 per pair, grown as the
     * search's lists grow, kept). */
    ct_real plimit;
    double *prune;
    size_t prune_cap;
    double e_law;
    /* Search and the re-sort criterion. */
    ct_search *search;
    ct_pairs pairs[2];
    /* Irem_gap 2: 1 to build the neighbour exclusion at the next search,
     * 2 built (applied to every search's pairs), 0 none. */
    int excl_state;
    ct_exclusion excl;
    int cur, need_sort, first;
    ct_real *x0, *y0, *z0;
    /* States, double-buffered. */
    ct_real *st[2][CTDI_ST_N];
    size_t capst[2];
    /* Scratch, single-buffered. */
    size_t cap;
    ct_idx *s[4], *o2n;
    ct_real *g[13];
    uint8_t *flag;
    int32_t *iflag;
    ct_real *r[CTDI_R_N];
    uint8_t *carry; /* 1: the pair carries its node this step (pair_select.c) */
    ct_idx *handoff; /* the pair whose states move to this carrier, or -1 */
    ct_contact_geo geo;
    ct_assemble_ws ws;
    int ws_ok;
} ctdi_pass;

typedef struct ctdi_epass ctdi_epass; /* TYPE11 (type11.c) */

struct ctd_iface {
    ctd_iface_cfg cfg;
    ct_idx nnode;
    ct_real *knode;  /* per-node stiffness with Stfac (NULL: none) */
    ct_real *gnode;  /* per-node gap (NULL: none) */
    ct_real kconst;  /* > 0: the given stiffness (before Stfac) */
    int stiff_mode;  /* ct_stiff_combine */
    int ks_fallback; /* 3, 5: a node of stiffness 0 takes the main one alone */
    /* TYPE6: the curve (owned copies) and the smaller rigid-body mass
     * (mass_set 0: still to be summed from the nodal masses). */
    ct_idx ncurve;
    ct_real *curve_p, *curve_f;
    ct_real mass_min;
    int mass_set;
    ct_real margin;
    ct_real dt_max; /* ctd_iface_set_dt_max (0: unknown) */
    /* The clearance within which an open pair enters the stable step
     * (ctdi_dt_counts): 0.2 times the mean main edge length (the default
     * margin), set with the margin at the first step. */
    ct_real band;
    int npass;
    ctdi_pass pass[2];
    ctdi_epass *ep;
    const ct_real *kelem;
    /* Per node (nnode entries, node-segment types but TYPE6): the contact
     * stiffness of this step spread onto the nodes for the nodal step. */
    ct_real *kc;
    ct_real coef[7];
    int fric_law, fric_on;
    /* pressure_area CTD_PAREA_SECONDARY (iface_area.c): the model
     * segments the secondary nodes of the passes are corners of (their
     * corners copied, 4 per segment), and per node its segments (CSR over
     * the nnode nodes; NULL when the main area is used). */
    ct_idx narea_seg, narea_ent;
    ct_idx *area_q, *area_off, *area_seg;
    int was_on;
    int64_t resorts, deactivated, excluded;
    char msg[512]; /* the failing step's explanation (ctd_iface_report.msg) */
};

/* pressure_area CTD_PAREA_SECONDARY (iface_area.c): build the node ->
 * segment map of the passes' secondary nodes from the model's segments of
 * d (after the passes are set up; nothing when the law reads no pressure);
 * a secondary node on no segment is an error (its index in diag). */
int ctdi_area_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag);
void ctdi_area_free(ctd_iface *it);
size_t ctdi_area_memory(const ctd_iface *it);
/* The area of the secondary node of each pair in contact (pen > 0) that
 * faces its contact normal, into area[k] (see iface_area.c); pairs out of
 * contact get 0. */
void ctdi_area_of_pairs(const ctd_iface *it, ct_idx n, const ct_idx *restrict node,
                        const ct_real *restrict pen, const ct_real *restrict nx,
                        const ct_real *restrict ny, const ct_real *restrict nz,
                        const ct_real *restrict x, const ct_real *restrict y,
                        const ct_real *restrict z, ct_real *restrict area);

/* The factor on the nodal contact step for normal damping VisS: the
 * damping C = VisS sqrt(2 K m) is the ratio zeta = VisS / sqrt(2) of the
 * contact spring, and the central difference is stable for a damped
 * oscillator only up to (2 / omega)(sqrt(1 + zeta^2) - zeta) (0.52 at the
 * TYPE24 default VisS = 1; without it a damped contact slowly gains
 * energy). */
static inline double ctdi_damped_dt_factor(double viss)
{
    double zeta = viss / 1.4142135623730951;
    return sqrt(1.0 + zeta * zeta) - zeta;
}

/* Whether the pairs' gaps come from the per-node gaps (7, 11, and 24 with
 * Igap0 = 1) or are the constant cfg.gap (3, 5, 6, 24 with Igap0 = 0). */
static inline int ctdi_var_gap(const ctd_iface_cfg *c)
{
    return c->type == 7 || c->type == 11 || (c->type == 24 && c->Igap0 != 0);
}

/* The bytes of one pair in a node-segment pass's arrays (grow_scratch,
 * grow_states for both sides, the two pair lists; the assembly's
 * workspace comes on top). */
#define CTDI_PAIR_BYTES                                                                       \
    (9 * sizeof(ct_idx) + 6 + (13 + CTDI_R_N + 2 * CTDI_ST_N) * sizeof(ct_real))

/* CT_OK when npair pairs of bytes_per_pair each (times the arrays' growth
 * factor 1.5) fit in the interface's memory limit; otherwise
 * CT_ERR_NOMEM, with it->msg saying how many pairs, per secondary (nsec),
 * for which search gap (iface_reach.c). */
int ctdi_pair_budget(ctd_iface *it, int64_t npair, ct_idx nsec, size_t bytes_per_pair,
                     double gap);

/* The most pairs of bytes_per_pair the limit holds (at most 2^31 - 1): the
 * search's max_pairs. */
int64_t ctdi_pair_limit(const ctd_iface *it, size_t bytes_per_pair);

/* Write it->msg for npair pairs found (more: more than npair, the search
 * stopped at its limit) and return CT_ERR_NOMEM. */
int ctdi_pairs_too_many(ctd_iface *it, int64_t npair, int more, ct_idx nsec,
                        size_t bytes_per_pair, double gap);


/* A pass's times into the report, from the clock read at its start (t[0])
 * and after its search, narrow phase, force, assembly and time step
 * (t[1..5]; the step counts as force), and its candidate and active pair
 * counts. */
static inline void ctdi_report_pass(ctd_iface_report *rep, const double t[6], ct_idx ncand,
                                    int64_t nactive)
{
    rep->t[CTD_IT_SEARCH] += t[1] - t[0];
    rep->t[CTD_IT_NARROW] += t[2] - t[1];
    rep->t[CTD_IT_FORCE] += (t[3] - t[2]) + (t[5] - t[4]);
    rep->t[CTD_IT_ASSEMBLE] += t[4] - t[3];
    rep->ncand += ncand;
    rep->nactive += (ct_idx)nactive;
}

/* Set the band of ctdi_dt_counts at the first step: 0.2 times the mean
 * main edge length h (fallback when h is 0), and the margin to it when the
 * card gave none (the default margin). */
static inline void ctdi_choose_band(ctd_iface *it, double h, ct_real fallback)
{
    it->band = (ct_real)(h > 0 ? 0.2 * h : fallback);
    if (!(it->margin > 0))
        it->margin = it->band;
}

/* Whether a pair enters the interface's stable step (its nodal spring and
 * the tunnelling limit): in contact (pen > 0), or open by no more than
 * band + 2 |v| dtmax (clearance |dist| - gap; band = it->band, 0.2 times
 * the mean main edge length, the default margin; |v| = sqrt(v2) the
 * relative speed at the contact point; dtmax the largest step the solver
 * may take next, ctd_iface_set_dt_max). The band keeps the step down
 * through the separations of chatter (a pair that opens for a few cycles
 * would otherwise let the step jump to the elements' and meet its spring
 * again with it); the speed term counts a fast pair at least a cycle
 * before it can touch. A pair farther off does not count, however wide the
 * search margin that made it a candidate: for any margin at least the
 * band, the step does not depend on the margin. With dtmax unknown (<= 0)
 * every pair counts (every candidate within the margin), as does a NaN
 * distance. */
static inline int ctdi_dt_counts(ct_real pen, ct_real dist, ct_real gap, ct_real v2, ct_real dt,
                                 ct_real band)
{
    if (pen > 0 || !(dt > 0))
        return 1;
    const ct_real c = (dist < 0 ? -dist : dist) - gap - band;
    return !(c > 0) || c * c <= 4 * v2 * dt * dt;
}

/* Fold a pass's largest contact stiffness, smallest gap (CT_DT_NONE: no
 * pair) and largest squared relative speed into the report: rep->kmax and
 * the tunnelling limit rep->dt_tunnel (ct_dt_tunnel). */
static inline void ctdi_report_limits(ctd_iface_report *rep, ct_real kmax, ct_real gmin,
                                      ct_real v2max)
{
    if (kmax > rep->kmax)
        rep->kmax = kmax;
    if (gmin < CT_DT_NONE) {
        ct_real d = ct_dt_tunnel(gmin, (ct_real)sqrt((double)v2max));
        if (d < rep->dt_tunnel)
            rep->dt_tunnel = d;
    }
}

/* Sorted unique copy of the concatenation of up to 6 index lists (NULL
 * lists skipped); *out is ct_calloc'ed (at least one element). Returns the
 * count, or a negative CT_ERR_*; indices outside [0, nnode) give
 * CT_ERR_RANGE. */
int64_t ctdi_unique_nodes(ct_idx nnode, const ct_idx *const lists[6], const ct_idx counts[6],
                          ct_idx **out);

/* Copy n indices (ct_calloc'ed; NULL on failure). */
ct_idx *ctdi_copy_idx(ct_idx n, const ct_idx *a);

/* Mean edge length of segments (triangles: 3 edges) or of edges. */
double ctdi_mean_seg_edge(ct_idx nseg, const ct_idx *n1, const ct_idx *n2, const ct_idx *n3,
                          const ct_idx *n4, const ct_real *x, const ct_real *y,
                          const ct_real *z);

/* Fail (ctdi_fail) with "WHAT: why." for a ctdi_pass_setup that returned
 * rc: a gap of 0 on a two-sided surface, memory, a node out of range. */
int ctdi_pass_setup_fail(ct_diag *diag, int rc, const char *what);

/* Node-segment pass (iface_pass.c). ctdi_pass_setup copies the segments
 * and the secondary list (already unique and sorted) and allocates the
 * workspaces; ctdi_pass_step runs one cycle and accumulates into rep;
 * ctdi_pass_free releases everything. */
int ctdi_pass_setup(ctd_iface *it, ctdi_pass *p, ct_idx nsec, ct_idx *sec_owned, ct_idx nseg,
                    const ct_idx *n1, const ct_idx *n2, const ct_idx *n3, const ct_idx *n4,
                    ct_real *kseg_owned, int self, int two_sided, int law);
int ctdi_pass_step(ctd_iface *it, ctdi_pass *p, ct_real dt, const ct_real *x,
                   const ct_real *y, const ct_real *z, const ct_real *vx, const ct_real *vy,
                   const ct_real *vz, const ct_real *m, ct_real *fx, ct_real *fy,
                   ct_real *fz, ctd_iface_report *rep);
void ctdi_pass_free(ctdi_pass *p);
/* The per-pair stages ctdi_pass_step runs, in this order (iface_pass_force.c):
 * the initial-penetration state (first cycle), the relative velocity at the
 * contact point (and the segment area when want_area), the normal law with
 * damping, friction, and the time-step limits into rep. */
void ctdi_pass_initial_state(ctd_iface *it, ctdi_pass *p, ct_idx n);
int ctdi_pass_kinematics(ctdi_pass *p, ct_idx n, const ct_idx *node, const ct_real *x,
                         const ct_real *y, const ct_real *z, const ct_real *vx,
                         const ct_real *vy, const ct_real *vz, const ct_real *m, int want_area);
int ctdi_pass_normal_force(ctd_iface *it, ctdi_pass *p, ct_idx n, ct_real dt);
int ctdi_pass_friction(ctd_iface *it, ctdi_pass *p, ct_idx n, ct_real dt);
int ctdi_pass_timestep(ctd_iface *it, ctdi_pass *p, ct_idx n, const ct_real *m,
                       ctd_iface_report *rep);
/* The nodal contact step of the interface's node-segment passes (after
 * every pass has run; iface_pass_force.c): zero it->kc on the passes' nodes
 * (ctdi_nodal_begin, before the passes), then the minimum over those nodes
 * of sqrt(2 m / (kelem + kc)) times the damping factor into rep. */
void ctdi_nodal_begin(ctd_iface *it);
void ctdi_nodal_finish(ctd_iface *it, const ct_real *m, ctd_iface_report *rep);

/* One pair per node side carries the contact (pair_select.c): called after
 * the narrow phase; zeroes the other pairs' penetrations, moves the pair
 * states with the contact, and returns the active pairs. */
int64_t ctdi_pass_select(ctdi_pass *p, const ct_real *x, const ct_real *y, const ct_real *z);
size_t ctdi_pass_memory(const ctdi_pass *p, ct_idx nnode);

/* One surface of a node-to-surface pass: its segments and their
 * stiffness inputs (as ct_seg_stiffness; all NULL: none). */
typedef struct ctdi_surf {
    ct_idx nseg;
    const ct_idx *q1, *q2, *q3, *q4;
    const ct_real *E, *t, *B, *A, *V;
} ctdi_surf;

/* The main (n1..n4, seg_*) and the secondary (s1..s4, ssg_*) surface of
 * the data. */
static inline ctdi_surf ctdi_main_surf(const ctd_iface_data *d)
{
    ctdi_surf s = {d->nseg,  d->n1,    d->n2,    d->n3,    d->n4,
                   d->seg_E, d->seg_t, d->seg_B, d->seg_A, d->seg_V};
    return s;
}
static inline ctdi_surf ctdi_sec_surf(const ctd_iface_data *d)
{
    ctdi_surf s = {d->nsseg, d->s1,    d->s2,    d->s3,    d->s4,
                   d->ssg_E, d->ssg_t, d->ssg_B, d->ssg_A, d->ssg_V};
    return s;
}

/*
 * Append a pass to it->pass (iface.c): the unique nodes of up to six lists
 * (NULL lists skipped) against the segments of surface s, for the types
 * with two distinct sides (3, 5, 6): a node never pairs with a segment it
 * belongs to, and the pass is one-sided unless cfg.two_sided. With
 * need_k, the segment stiffness Stfac Km comes from the surface's inputs
 * unless the interface has a constant K, and its absence is an error.
 * reverse marks the second pass of surface to surface (see ctdi_pass).
 * Errors go to diag, naming the type and `what` (e.g. "main segments").
 */
int ctdi_add_pass(ctd_iface *it, const ct_idx *const lists[6], const ct_idx counts[6],
                  const ctdi_surf *s, int need_k, int reverse, int law, const char *what,
                  ct_diag *diag);

/* TYPE6 (type6.c): copy and check the curve (ctdi_type6_setup, from
 * ctd_iface_init); the normal law of a pass over its n pairs after the
 * narrow phase (force fel, damping stiffness = curve K, friction stiffness
 * = the pair's share of it, p_prev; the stored energy in p->e_law); the
 * step 0.1 sqrt(M_min / K) at the pass's largest penetration (m: the nodal
 * masses, summed once when data.mass_min was 0). */
int ctdi_type6_normal(ctd_iface *it, ctdi_pass *p, ct_idx n);
ct_real ctdi_type6_dt(ctd_iface *it, const ctdi_pass *p, const ct_real *m);
/* TYPE6, after a search: keep a node's pairs whose distance is within two
 * margins of the larger of the contact gap and the node's closest pair's
 * distance, in order (type6.c says why). The search reaches as deep as the
 * bodies are (iface_pass.c): without this a node at the surface pairs
 * with every segment within the crush depth. */
int ctdi_type6_prune(const ctd_iface *it, ctdi_pass *p, ct_pairs *pp, const ct_real *x,
                     const ct_real *y, const ct_real *z);

/* The integral of max(0, f) from a to b (a <= b) for the piecewise-linear
 * curve (x, y) of n >= 2 points with the end intervals extrapolated, as
 * ct_curve_eval; exact up to round-off (double sums). */
double ctdi_curve_integral(ct_idx n, const ct_real *x, const ct_real *y, double a, double b);

/* Per-type setup (type3.c, type5.c, type6.c, type24.c, type7.c,
 * type11.c). */
int ctdi_type3_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag);
int ctdi_type5_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag);
int ctdi_type6_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag);
int ctdi_type24_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag);
int ctdi_type7_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag);
int ctdi_type11_setup(ctd_iface *it, const ctd_iface_data *d, ct_diag *diag);
int ctdi_type11_step(ctd_iface *it, ct_real dt, const ct_real *x, const ct_real *y,
                     const ct_real *z, const ct_real *vx, const ct_real *vy,
                     const ct_real *vz, const ct_real *m, ct_real *fx, ct_real *fy,
                     ct_real *fz, ctd_iface_report *rep);
void ctdi_type11_free(ctdi_epass *e);
size_t ctdi_type11_memory(const ctdi_epass *e, ct_idx nnode);
void ctdi_type11_force_resort(ctdi_epass *e);
/* The unique edges of segments d->n1..n4 (d->nseg of them), lower node
 * first, sorted; *e1 and *e2 are ct_calloc'ed. */
int ctdi_seg_edges(const ctd_iface_data *d, ct_idx **e1, ct_idx **e2, ct_idx *ne);
/* Output fields of the last step (iface_fields.c). */
void ctdi_type11_fields(const ctdi_epass *e, ct_real *pen, int32_t *nact);

/* Segment stiffness with Stfac from the data's inputs for one surface
 * (E, t, B, A, V as ct_seg_stiffness); *out NULL when all inputs are NULL. */
int ctdi_seg_stiffness(ct_real stfac, ct_idx nseg, const ct_real *E, const ct_real *t,
                       const ct_real *B, const ct_real *A, const ct_real *V, ct_real **out,
                       ct_diag *diag);

/* Per-segment gap: the largest per-node gap of its nodes (NULL when gnode
 * is NULL). */
ct_real *ctdi_seg_gap(const ct_real *gnode, ct_idx nseg, const ct_idx *n1, const ct_idx *n2,
                      const ct_idx *n3, const ct_idx *n4);

/* Fill diag (may be NULL) and return code. */
int ctdi_fail(ct_diag *diag, int code, int64_t index, const char *msg);

#endif /* CTD_IFACE_INTERNAL_H */
