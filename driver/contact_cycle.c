/*
 * contact_cycle.c -- the contact cycle of one node-to-segment interface
 * (see contact_cycle.h): search with the re-sort criterion, narrow phase,
 * force, assembly, time step, each phase timed.
 */
#include "contact_cycle.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
static double wtime(void) { return omp_get_wtime(); }
#else
#include <time.h>
static double wtime(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
#endif

/* Pairs per block of the fused narrow/force/step pass (phase_pairs): a
 * multiple of the kernels' own blocks (64 for the narrow phase, 2048 for
 * the normal force and friction), so each kernel sees the block boundaries
 * a whole-list call would. Measured on the folded sheet, 10^6 nodes: 2048,
 * 4096 and 8192 within 5 % of each other (4096 best by a little); 512 and
 * 256 slower, by the kernels' fixed cost per call. */
#define CY_BLOCK 4096

/* One block's results of the fused pass. */
typedef struct cy_block {
    int rc, rc_kin, rc_nod;  /* the first failing kernel; the step kernels' codes */
    int64_t active;          /* pairs with p > 0 */
    ct_real dt_kin, dt_nod;  /* the block's smallest limits */
    ct_idx i_kin, i_nod;     /* their pairs (global indices; -1: none) */
    double t[3];             /* seconds in narrow phase, force, step */
} cy_block;

/* Per-pair real arrays of the force phase. */
enum { R_VRX, R_VRY, R_VRZ, R_VN, R_FEL, R_KTAN, R_FN, R_FX, R_FY, R_FZ, R_MS, R_K0, R_N };

struct ctd_cycle {
    ctd_cycle_params p;
    /* The interface (borrowed arrays). */
    ct_idx nnode, nsec, nmain, nseg;
    const ct_real *m;
    const ct_idx *sec, *mainn, *n1, *n2, *n3, *n4;
    int self;
    /* Search. */
    ct_search *search;
    int need_sort;
    ct_real *x0, *y0, *z0; /* positions at the last sort */
    /* Pair lists and friction histories, double-buffered: `cur` is the
     * current one, 1 - cur the previous one (the source of the remap). */
    int cur;
    ct_pairs pairs[2];
    ct_real *ft[2][3];
    size_t capft[2];
    /* Single-buffered per-pair arrays (capacity cap). */
    size_t cap;
    ct_idx *s[4], *old_of_new;
    ct_real *g[13];
    uint8_t *flag;
    int32_t *flag7;
    ct_real *r[R_N];
    ct_contact_geo geo;
    cy_block *blk; /* (cap + CY_BLOCK - 1) / CY_BLOCK records */
    /* Assembly. */
    ct_assemble_ws ws;
    int ws_ready;
    ctd_cycle_stats st;
};

ctd_cycle_params ctd_cycle_default_params(double h)
{
    ctd_cycle_params p;
    memset(&p, 0, sizeof p);
    p.algo = CT_SEARCH_BUCKET;
    p.filter = CT_FILTER_HULL;
    p.quad = CT_QUAD_4TRI;
    p.asm_variant = CT_ASM_COLOUR;
    p.law = CTD_LAW_TYPE7;
    p.two_sided = 1;
    p.gap = (ct_real)(0.3 * h);
    p.margin = (ct_real)(0.2 * h);
    p.K0 = 1;
    p.viss = (ct_real)0.05;
    p.mu = (ct_real)0.2;
    p.kt = 1;
    return p;
}

static void free_pair_arrays(ctd_cycle *cy)
{
    for (int i = 0; i < 4; i++)
        ct_free(cy->s[i]);
    ct_free(cy->old_of_new);
    for (int i = 0; i < 13; i++)
        ct_free(cy->g[i]);
    ct_free(cy->flag);
    ct_free(cy->flag7);
    for (int i = 0; i < R_N; i++)
        ct_free(cy->r[i]);
    free(cy->blk);
    cy->blk = NULL;
    memset(cy->s, 0, sizeof cy->s);
    cy->old_of_new = NULL;
    memset(cy->g, 0, sizeof cy->g);
    cy->flag = NULL;
    cy->flag7 = NULL;
    memset(cy->r, 0, sizeof cy->r);
    cy->cap = 0;
}

/* Make the single-buffered arrays hold n pairs (contents not kept: they are
 * all rewritten after each search). */
static int grow_pair_arrays(ctd_cycle *cy, size_t n, int exact)
{
    if (n <= cy->cap && cy->flag)
        return CT_OK;
    free_pair_arrays(cy);
    size_t c = exact ? n + 64 : n + n / 2 + 64;
    int ok = 1;
    for (int i = 0; i < 4; i++)
        ok &= (cy->s[i] = ct_calloc(c, sizeof(ct_idx))) != NULL;
    ok &= (cy->old_of_new = ct_calloc(c, sizeof(ct_idx))) != NULL;
    for (int i = 0; i < 13; i++)
        ok &= (cy->g[i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    ok &= (cy->flag = ct_calloc(c, 1)) != NULL;
    ok &= (cy->flag7 = ct_calloc(c, sizeof(int32_t))) != NULL;
    for (int i = 0; i < R_N; i++)
        ok &= (cy->r[i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    ok &= (cy->blk = calloc((c + CY_BLOCK - 1) / CY_BLOCK, sizeof *cy->blk)) != NULL;
    if (!ok) {
        free_pair_arrays(cy);
        return CT_ERR_NOMEM;
    }
    cy->cap = c;
    ct_contact_geo g = {cy->g[0], cy->g[1], cy->g[2],  cy->g[3],  cy->g[4],
                        cy->g[5], cy->g[6], cy->g[7],  cy->g[8],  cy->g[9],
                        cy->g[10], cy->g[11], cy->g[12], cy->flag};
    cy->geo = g;
    return CT_OK;
}

/* Make friction history side b hold n pairs (contents not kept). */
static int grow_ft(ctd_cycle *cy, int b, size_t n, int exact)
{
    if (n <= cy->capft[b] && cy->ft[b][0])
        return CT_OK;
    for (int i = 0; i < 3; i++) {
        ct_free(cy->ft[b][i]);
        cy->ft[b][i] = NULL;
    }
    size_t c = exact ? n + 64 : n + n / 2 + 64;
    int ok = 1;
    for (int i = 0; i < 3; i++)
        ok &= (cy->ft[b][i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    cy->capft[b] = ok ? c : 0;
    return ok ? CT_OK : CT_ERR_NOMEM;
}

int ctd_cycle_init(ctd_cycle **out, const ctd_cycle_params *p, ct_idx nnode, const ct_real *m,
                   ct_idx nsec, const ct_idx *sec, ct_idx nmain, const ct_idx *mainn,
                   ct_idx nseg, const ct_idx *n1, const ct_idx *n2, const ct_idx *n3,
                   const ct_idx *n4, int self)
{
    if (!out)
        return CT_ERR_ARG;
    *out = NULL;
    if (!p || nnode < 0 || nsec < 0 || nmain < 0 || nseg < 0 || !m || (nsec && !sec) ||
        (nmain && !mainn) || (nseg && (!n1 || !n2 || !n3 || !n4)) || !(p->gap > 0) ||
        !(p->margin >= 0) || p->quad < 0 || p->quad >= CT_QUAD_NMETHOD ||
        p->asm_variant < 0 || p->asm_variant >= CT_ASM_NVARIANT ||
        (p->law != CTD_LAW_TYPE7 && p->law != CTD_LAW_LINEAR))
        return CT_ERR_ARG;
    ctd_cycle *cy = calloc(1, sizeof *cy);
    if (!cy)
        return CT_ERR_NOMEM;
    cy->p = *p;
    cy->nnode = nnode;
    cy->nsec = nsec;
    cy->nmain = nmain;
    cy->nseg = nseg;
    cy->m = m;
    cy->sec = sec;
    cy->mainn = mainn;
    cy->n1 = n1;
    cy->n2 = n2;
    cy->n3 = n3;
    cy->n4 = n4;
    cy->self = self;
    cy->need_sort = 1;
    ct_search_params sp = ct_search_default_params(p->algo);
    int rc = ct_search_init(&cy->search, &sp);
    if (rc == CT_OK)
        rc = ct_pairs_init(&cy->pairs[0], 0);
    if (rc == CT_OK)
        rc = ct_pairs_init(&cy->pairs[1], 0);
    if (rc == CT_OK) {
        cy->x0 = ct_calloc((size_t)nnode, sizeof(ct_real));
        cy->y0 = ct_calloc((size_t)nnode, sizeof(ct_real));
        cy->z0 = ct_calloc((size_t)nnode, sizeof(ct_real));
        if (!cy->x0 || !cy->y0 || !cy->z0)
            rc = CT_ERR_NOMEM;
    }
    if (rc == CT_OK)
        rc = grow_ft(cy, 0, 0, 1);
    if (rc == CT_OK)
        rc = grow_ft(cy, 1, 0, 1);
    if (rc == CT_OK)
        rc = grow_pair_arrays(cy, 0, 1);
    if (rc == CT_OK) {
        rc = ct_assemble_ws_init(&cy->ws);
        cy->ws_ready = rc == CT_OK;
    }
    if (rc != CT_OK) {
        ctd_cycle_destroy(cy);
        return rc;
    }
    cy->st.dt_kin = cy->st.dt_nodal = CT_DT_NONE;
    *out = cy;
    return CT_OK;
}

void ctd_cycle_destroy(ctd_cycle *cy)
{
    if (!cy)
        return;
    ct_search_destroy(cy->search);
    ct_pairs_destroy(&cy->pairs[0]);
    ct_pairs_destroy(&cy->pairs[1]);
    for (int b = 0; b < 2; b++)
        for (int i = 0; i < 3; i++)
            ct_free(cy->ft[b][i]);
    ct_free(cy->x0);
    ct_free(cy->y0);
    ct_free(cy->z0);
    free_pair_arrays(cy);
    if (cy->ws_ready)
        ct_assemble_ws_destroy(&cy->ws);
    free(cy);
}

void ctd_cycle_force_resort(ctd_cycle *cy)
{
    if (cy)
        cy->need_sort = 1;
}

const ctd_cycle_stats *ctd_cycle_get_stats(const ctd_cycle *cy) { return &cy->st; }

void ctd_cycle_stats_reset(ctd_cycle *cy)
{
    cy->st.cycles = cy->st.resorts = cy->st.cand_sum = cy->st.active_sum = 0;
    for (int i = 0; i < CTD_PH_N; i++)
        cy->st.t[i] = 0;
    cy->st.t_sort = 0;
}

int ctd_cycle_reserve(ctd_cycle *cy, ct_idx npair)
{
    if (!cy || npair < 0)
        return CT_ERR_ARG;
    int rc = grow_pair_arrays(cy, (size_t)npair, 1);
    for (int b = 0; b < 2 && rc == CT_OK; b++) {
        rc = grow_ft(cy, b, (size_t)npair, 1);
        if (rc == CT_OK)
            rc = ct_pairs_reserve(&cy->pairs[b], npair);
    }
    return rc;
}

const ct_pairs *ctd_cycle_pairs(const ctd_cycle *cy) { return &cy->pairs[cy->cur]; }

const ct_contact_geo *ctd_cycle_geo(const ctd_cycle *cy) { return &cy->geo; }

size_t ctd_cycle_memory(const ctd_cycle *cy)
{
    size_t per = 5 * sizeof(ct_idx) + 13 * sizeof(ct_real) + 1 + sizeof(int32_t) +
                 R_N * sizeof(ct_real);
    size_t b = cy->cap * per + (cy->capft[0] + cy->capft[1]) * 3 * sizeof(ct_real);
    b += (cy->cap + CY_BLOCK - 1) / CY_BLOCK * sizeof(cy_block);
    b += ((size_t)cy->pairs[0].cap + (size_t)cy->pairs[1].cap) * 2 * sizeof(ct_idx);
    b += 3 * (size_t)cy->nnode * sizeof(ct_real);
    b += ct_search_memory(cy->search) + ct_assemble_ws_memory(&cy->ws);
    return b;
}

/* ---- Phases ---------------------------------------------------------------- */

/* The search and everything that depends on the pair list. */
static int phase_search(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z)
{
    int rc;
    if (!cy->need_sort) {
        int need = ct_resort_needed(cy->nsec, cy->sec, cy->nmain, cy->mainn, cy->x0, cy->y0,
                                    cy->z0, x, y, z, cy->p.margin, &cy->st.bound);
        if (!need)
            return CT_OK;
    } else {
        cy->st.bound = 0;
    }
    int old = cy->cur, now = 1 - cy->cur;
    ct_search_input in;
    memset(&in, 0, sizeof in);
    in.nnode = cy->nnode;
    in.x = x;
    in.y = y;
    in.z = z;
    in.nsec = cy->nsec;
    in.sec = cy->sec;
    in.nseg = cy->nseg;
    in.n1 = cy->n1;
    in.n2 = cy->n2;
    in.n3 = cy->n3;
    in.n4 = cy->n4;
    in.gap = cy->p.gap;
    in.margin = cy->p.margin;
    in.self = cy->self;
    in.filter = cy->p.filter;
    ct_pairs *np = &cy->pairs[now];
    const ct_pairs *op = &cy->pairs[old];
    rc = ct_search_run(cy->search, &in, np);
    if (rc != CT_OK)
        return rc;
    ct_idx n = np->n;
    if ((rc = grow_pair_arrays(cy, (size_t)n, 0)) != CT_OK ||
        (rc = grow_ft(cy, now, (size_t)n, 0)) != CT_OK)
        return rc;
    rc = ct_asm_seg_slots(n, np->seg, cy->nseg, cy->n1, cy->n2, cy->n3, cy->n4, cy->s[0],
                          cy->s[1], cy->s[2], cy->s[3]);
    if (rc != CT_OK)
        return rc;
    ct_asm_map map = ct_asm_map_nodeseg(n, np->node, cy->s[0], cy->s[1], cy->s[2], cy->s[3]);
    rc = ct_assemble_prepare(&cy->ws, cy->p.asm_variant, &map, cy->nnode);
    if (rc != CT_OK)
        return rc;
    rc = ct_friction_remap(op->n, op->node, op->seg, cy->ft[old][0], cy->ft[old][1],
                           cy->ft[old][2], n, np->node, np->seg, cy->ft[now][0],
                           cy->ft[now][1], cy->ft[now][2], cy->old_of_new, NULL);
    if (rc != CT_OK)
        return rc;
    /* Per-pair constants: the secondary mass and the stiffness. */
    const ct_idx *restrict nd = np->node;
    const ct_real *restrict mass = cy->m;
    ct_real *restrict ms = cy->r[R_MS], *restrict k0 = cy->r[R_K0];
    const ct_real K0 = cy->p.K0;
#pragma omp parallel for simd schedule(static)
    for (ct_idx k = 0; k < n; k++) {
        ms[k] = mass[nd[k]];
        k0[k] = K0;
    }
    /* Positions at this sort. */
    ct_real *restrict a = cy->x0, *restrict b = cy->y0, *restrict c = cy->z0;
    const ct_idx nn = cy->nnode;
#pragma omp parallel for simd schedule(static)
    for (ct_idx i = 0; i < nn; i++) {
        a[i] = x[i];
        b[i] = y[i];
        c[i] = z[i];
    }
    cy->cur = now;
    if (!cy->need_sort) { /* fired by the criterion */
        cy->st.natural_sorts++;
        cy->st.interval_sum += cy->st.life_cycles - cy->st.life_last_sort;
    }
    cy->st.life_last_sort = cy->st.life_cycles;
    cy->need_sort = 0;
    cy->st.resorts++;
    return CT_OK;
}

/* The force of pairs [k0, k1): relative velocity, normal law, damping,
 * Coulomb friction and the total pair force. Every kernel is called on the
 * block alone (below their thread-team thresholds: no team). */
static int block_force(ctd_cycle *cy, ct_idx k0, ct_idx k1, const ct_real *vx,
                       const ct_real *vy, const ct_real *vz, ct_real dt)
{
    const ct_contact_geo *g = &cy->geo;
    ct_real *const *r = cy->r;
    const ct_idx n = k1 - k0;
    int rc = ct_relative_velocity(
        n, cy->pairs[cy->cur].node + k0, cy->s[0] + k0, cy->s[1] + k0, cy->s[2] + k0,
        cy->s[3] + k0, g->h1 + k0, g->h2 + k0, g->h3 + k0, g->h4 + k0, g->nx + k0, g->ny + k0,
        g->nz + k0, vx, vy, vz, NULL, r[R_VRX] + k0, r[R_VRY] + k0, r[R_VRZ] + k0, r[R_VN] + k0,
        NULL);
    if (rc != CT_OK)
        return rc;
    if (cy->p.law == CTD_LAW_TYPE7) {
        rc = ct_penalty_type7(n, g->pen + k0, g->gap + k0, r[R_K0] + k0, r[R_FEL] + k0,
                              r[R_KTAN] + k0, NULL, cy->flag7 + k0);
        if (rc == CT_OK)
            rc = ct_normal_finish(n, g->pen + k0, r[R_FEL] + k0, r[R_KTAN] + k0, r[R_VN] + k0,
                                  r[R_MS] + k0, NULL, cy->p.viss, dt, g->nx + k0, g->ny + k0,
                                  g->nz + k0, r[R_FN] + k0, r[R_FX] + k0, r[R_FY] + k0,
                                  r[R_FZ] + k0, NULL);
    } else {
        rc = ct_normal_force(n, g->pen + k0, g->nx + k0, g->ny + k0, g->nz + k0, r[R_VN] + k0,
                             NULL, cy->p.K0, r[R_MS] + k0, NULL, cy->p.viss, dt, r[R_FX] + k0,
                             r[R_FY] + k0, r[R_FZ] + k0, r[R_FN] + k0, NULL, NULL);
        /* The tangent stiffness for the nodal step: K0 in contact. */
        const ct_real *restrict pen = g->pen;
        ct_real *restrict kt = r[R_KTAN];
        const ct_real K0 = cy->p.K0;
#pragma omp simd
        for (ct_idx k = k0; k < k1; k++)
            kt[k] = pen[k] > 0 ? K0 : 0;
    }
    if (rc != CT_OK || !(cy->p.mu > 0))
        return rc;
    ct_real *const *ft = cy->ft[cy->cur];
    rc = ct_friction_step(n, g->nx + k0, g->ny + k0, g->nz + k0, r[R_VRX] + k0, r[R_VRY] + k0,
                          r[R_VRZ] + k0, r[R_FN] + k0, NULL, cy->p.mu, NULL, cy->p.kt, dt, 1,
                          ft[0] + k0, ft[1] + k0, ft[2] + k0, NULL);
    if (rc != CT_OK)
        return rc;
    /* The pair force on the secondary node: normal plus tangential. */
    ct_real *restrict fx = r[R_FX], *restrict fy = r[R_FY], *restrict fz = r[R_FZ];
    const ct_real *restrict tx = ft[0], *restrict ty = ft[1], *restrict tz = ft[2];
#pragma omp simd
    for (ct_idx k = k0; k < k1; k++) {
        fx[k] += tx[k];
        fy[k] += ty[k];
        fz[k] += tz[k];
    }
    return CT_OK;
}

/* The two step limits of pairs [k0, k1) into the block's record. */
static void block_timestep(const ctd_cycle *cy, ct_idx k0, ct_idx k1, cy_block *b)
{
    const ct_idx n = k1 - k0;
    b->rc_kin = ct_dt_type7_kinematic(n, cy->geo.pen + k0, cy->geo.gap + k0,
                                      cy->r[R_VN] + k0, NULL, &b->dt_kin, &b->i_kin);
    b->rc_nod = ct_dt_nodal(n, cy->pairs[cy->cur].node + k0, cy->m, NULL, cy->r[R_KTAN] + k0,
                            NULL, &b->dt_nod, &b->i_nod);
    b->i_kin += b->i_kin >= 0 ? k0 : 0;
    b->i_nod += b->i_nod >= 0 ? k0 : 0;
}

/* Fold block b's limit into the running one (blocks in increasing order:
 * the first smallest wins, as in one scan). A NaN item is reported by its
 * kernel as CT_ERR_NONFINITE with its index; the first one wins. */
static void fold_limit(int rc, ct_real d, ct_idx i, int *best_rc, ct_real *best, ct_idx *bi)
{
    if (*best_rc != CT_OK)
        return;
    if (rc != CT_OK) {
        *best_rc = rc;
        *best = CT_DT_NONE;
        *bi = i;
    } else if (i >= 0 && d < *best) {
        *best = d;
        *bi = i;
    }
}

/* Narrow phase, force and time step of every pair, fused in blocks of
 * CY_BLOCK pairs so that the block's per-pair arrays stay in cache from one
 * kernel to the next (separate passes streamed about 30 arrays of the size
 * of the pair list through memory). Each kernel computes every pair alone,
 * and CY_BLOCK is a multiple of the kernels' own blocks, so the results are
 * those of whole-list calls, bit for bit. The phases are timed per block;
 * the caller shares the pass's wall time among them in proportion to the
 * sums of those times (tph: narrow, force, step). */
static int phase_pairs(ctd_cycle *cy, ct_idx n, const ct_real *x, const ct_real *y,
                       const ct_real *z, const ct_real *vx, const ct_real *vy,
                       const ct_real *vz, ct_real dt, int64_t *active, double tph[3])
{
    const ct_pairs *pp = &cy->pairs[cy->cur];
    const ct_idx nblk = (n + CY_BLOCK - 1) / CY_BLOCK;
    cy_block *blk = cy->blk;
#pragma omp parallel for schedule(static)
    for (ct_idx bi = 0; bi < nblk; bi++) {
        const ct_idx k0 = bi * CY_BLOCK, k1 = n - k0 < CY_BLOCK ? n : k0 + CY_BLOCK;
        cy_block *b = &blk[bi];
        ct_narrow_stats ns;
        double t0 = wtime();
        b->rc = ct_narrow_node_segment(
            k1 - k0, pp->node + k0, pp->seg + k0, cy->n1, cy->n2, cy->n3, cy->n4, x, y, z, NULL,
            NULL, cy->p.gap, 0, 0, cy->p.quad, cy->p.two_sided,
            &(ct_contact_geo){cy->geo.dist + k0, cy->geo.pen + k0, cy->geo.nx + k0,
                              cy->geo.ny + k0, cy->geo.nz + k0, cy->geo.cx + k0,
                              cy->geo.cy + k0, cy->geo.cz + k0, cy->geo.h1 + k0,
                              cy->geo.h2 + k0, cy->geo.h3 + k0, cy->geo.h4 + k0,
                              cy->geo.gap + k0, cy->geo.flag + k0},
            &ns);
        b->active = ns.active;
        double t1 = wtime();
        if (b->rc == CT_OK)
            b->rc = block_force(cy, k0, k1, vx, vy, vz, dt);
        double t2 = wtime();
        if (b->rc == CT_OK)
            block_timestep(cy, k0, k1, b);
        double t3 = wtime();
        b->t[0] = t1 - t0;
        b->t[1] = t2 - t1;
        b->t[2] = t3 - t2;
    }
    /* In block order: the first failing kernel, the active count, the
     * limits, and the share of each phase. */
    int rc_kin = CT_OK, rc_nod = CT_OK;
    ct_real dkin = CT_DT_NONE, dnod = CT_DT_NONE;
    ct_idx ikin = -1, inod = -1;
    double sum[3] = {0, 0, 0};
    *active = 0;
    for (ct_idx bi = 0; bi < nblk; bi++) {
        const cy_block *b = &blk[bi];
        if (b->rc != CT_OK)
            return b->rc;
        *active += b->active;
        fold_limit(b->rc_kin, b->dt_kin, b->i_kin, &rc_kin, &dkin, &ikin);
        fold_limit(b->rc_nod, b->dt_nod, b->i_nod, &rc_nod, &dnod, &inod);
        for (int i = 0; i < 3; i++)
            sum[i] += b->t[i];
    }
    for (int i = 0; i < 3; i++)
        tph[i] = sum[i];
    if (rc_kin != CT_OK)
        return rc_kin;
    cy->st.dt_kin = dkin;
    if (rc_nod != CT_OK)
        return rc_nod;
    cy->st.dt_nodal = dnod;
    return CT_OK;
}

static int phase_assemble(ctd_cycle *cy, ct_idx n, ct_real *fxn, ct_real *fyn, ct_real *fzn)
{
    const ct_idx nn = cy->nnode;
    ct_real *restrict a = fxn, *restrict b = fyn, *restrict c = fzn;
#pragma omp parallel for simd schedule(static)
    for (ct_idx i = 0; i < nn; i++) {
        a[i] = 0;
        b[i] = 0;
        c[i] = 0;
    }
    const ct_pairs *pp = &cy->pairs[cy->cur];
    ct_asm_map map = ct_asm_map_nodeseg(n, pp->node, cy->s[0], cy->s[1], cy->s[2], cy->s[3]);
    const ct_real *const w[5] = {NULL, cy->geo.h1, cy->geo.h2, cy->geo.h3, cy->geo.h4};
    return ct_assemble(&cy->ws, cy->p.asm_variant, &map, w, cy->r[R_FX], cy->r[R_FY],
                       cy->r[R_FZ], nn, fxn, fyn, fzn);
}

int ctd_cycle_step(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z,
                   const ct_real *vx, const ct_real *vy, const ct_real *vz, ct_real dt,
                   ct_real *fxn, ct_real *fyn, ct_real *fzn)
{
    if (!cy || !x || !y || !z || !vx || !vy || !vz || !fxn || !fyn || !fzn || !(dt >= 0))
        return CT_ERR_ARG;
    double t0 = wtime();
    int64_t nsort = cy->st.resorts;
    int rc = phase_search(cy, x, y, z);
    double t1 = wtime();
    if (cy->st.resorts != nsort)
        cy->st.t_sort += t1 - t0;
    if (rc != CT_OK) {
        cy->need_sort = 1;
        return rc;
    }
    ct_idx n = cy->pairs[cy->cur].n;
    int64_t active = 0;
    double tph[3] = {0, 0, 0};
    rc = phase_pairs(cy, n, x, y, z, vx, vy, vz, dt, &active, tph);
    double t2 = wtime();
    /* The pass's wall time, shared among narrow phase, force and step. */
    if (rc == CT_OK) {
        double all = tph[0] + tph[1] + tph[2], w = t2 - t1;
        for (int i = 0; i < 3; i++)
            tph[i] = all > 0 ? w * tph[i] / all : w / 3;
    }
    if (rc == CT_OK)
        rc = phase_assemble(cy, n, fxn, fyn, fzn);
    double t3 = wtime();
    if (rc != CT_OK)
        return rc;
    ctd_cycle_stats *s = &cy->st;
    s->t[CTD_PH_SEARCH] += t1 - t0;
    s->t[CTD_PH_NARROW] += tph[0];
    s->t[CTD_PH_FORCE] += tph[1];
    s->t[CTD_PH_ASSEMBLE] += t3 - t2;
    s->t[CTD_PH_TIMESTEP] += tph[2];
    s->cycles++;
    s->life_cycles++;
    s->ncand = n;
    s->nactive = (ct_idx)active;
    s->cand_sum += n;
    s->active_sum += active;
    return CT_OK;
}

/* ---- Prescribed motion --------------------------------------------------- */

double ctd_motion_max_step(const ctd_motion *mo, double rc)
{
    double w = 2 * 3.141592653589793 / mo->period;
    double a = rc * mo->s1 / 2 * w, b = mo->slide * w;
    return sqrt(a * a + b * b);
}

void ctd_motion_eval(const ctd_motion *mo, ct_idx n, const ct_real *const ref[3],
                     double cycle, double dt, ct_real *const pos[3], ct_real *const vel[3])
{
    const double pi2 = 2 * 3.141592653589793;
    double phi = pi2 * cycle / mo->period, w = dt > 0 ? pi2 / (mo->period * dt) : 0;
    double f = mo->s0 - mo->s1 * (1 - cos(phi)) / 2, fdot = -mo->s1 / 2 * sin(phi) * w;
    double sl = mo->slide * sin(phi), sldot = mo->slide * cos(phi) * w;
    double kw = pi2 / mo->wavelength, cen = mo->centre;
    int c = mo->axis_c, s = mo->axis_s, o = 3 - c - s;
    const ct_real *restrict rc = ref[c], *restrict rs = ref[s], *restrict ro = ref[o];
    ct_real *restrict pc = pos[c], *restrict ps = pos[s], *restrict po = pos[o];
    ct_real *restrict vc = vel[c], *restrict vs = vel[s], *restrict vo = vel[o];
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < n; i++) {
        double d = (double)rc[i] - cen, cw = cos(kw * (double)rc[i]);
        pc[i] = (ct_real)(cen + d * f);
        vc[i] = (ct_real)(d * fdot);
        ps[i] = (ct_real)((double)rs[i] + sl * cw);
        vs[i] = (ct_real)(sldot * cw);
        po[i] = ro[i];
        vo[i] = 0;
    }
}
