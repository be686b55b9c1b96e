/*
 * contact_cycle.c -- the contact cycle of one node-to-segment interface
 * (see contact_cycle.h): search with the re-sort criterion, narrow phase,
 * force, assembly, time step, each phase timed.
 */
#include "contact_cycle_internal.h"

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
    p.skip = 1;
    p.select = 1;
    return p;
}

static void free_pair_arrays(ctd_cycle *cy)
{
    for (int i = 0; i < 4; i++)
        ct_free(cy->s[i]);
    ct_free(cy->old_of_new);
    for (int i = 0; i < CY_NGEO; i++)
        ct_free(cy->g[i]);
    ct_free(cy->flag);
    ct_free(cy->evald);
    for (int i = 0; i < 3; i++)
        ct_free(cy->fp[i]);
    for (int i = 0; i < 5; i++)
        ct_free(cy->cn[i]);
    free(cy->blk);
    cy->blk = NULL;
    free(cy->nact);
    cy->nact = NULL;
    free(cy->bst);
    cy->bst = NULL;
    memset(cy->s, 0, sizeof cy->s);
    cy->old_of_new = NULL;
    memset(cy->g, 0, sizeof cy->g);
    cy->flag = NULL;
    cy->evald = NULL;
    memset(cy->fp, 0, sizeof cy->fp);
    memset(cy->cn, 0, sizeof cy->cn);
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
    for (int i = 1; i < CY_NGEO; i++)
        ok &= (cy->g[i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    ok &= (cy->flag = ct_calloc(c, 1)) != NULL;
    ok &= (cy->evald = ct_calloc(c, 1)) != NULL;
    for (int i = 0; i < 3; i++)
        ok &= (cy->fp[i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    for (int i = 0; i < 5 && cti_cycle_fused(cy); i++)
        ok &= (cy->cn[i] = ct_calloc(c, sizeof(ct_idx))) != NULL;
    /* At most c / CY_BLOCK + 1 blocks (all but the last hold CY_BLOCK pairs
     * or more), and their final start. */
    const size_t nb = c / CY_BLOCK + 2;
    ok &= (cy->blk = calloc(nb, sizeof *cy->blk)) != NULL;
    ok &= (cy->nact = calloc(nb, sizeof *cy->nact)) != NULL;
    ok &= (cy->bst = calloc(nb, sizeof *cy->bst)) != NULL;
    if (!ok) {
        free_pair_arrays(cy);
        return CT_ERR_NOMEM;
    }
    cy->cap = c;
    /* The results the cycle keeps per pair (ctd_cycle_geo): p (pp[cur],
     * double-buffered with the friction history), the weights and the
     * flag. */
    memset(&cy->geo, 0, sizeof cy->geo);
    cy->geo.pen = cy->pp[cy->cur];
    if (!cti_cycle_fused(cy)) { /* fused: g[1..4] hold the compact lists */
        cy->geo.h1 = cy->g[1];
        cy->geo.h2 = cy->g[2];
        cy->geo.h3 = cy->g[3];
        cy->geo.h4 = cy->g[4];
    }
    cy->geo.flag = cy->flag;
    return CT_OK;
}

/* Make friction history, skip expiry and last penetration side b hold n
 * pairs (contents not kept). */
static int grow_ft(ctd_cycle *cy, int b, size_t n, int exact)
{
    if (n <= cy->capft[b] && cy->ft[b][0])
        return CT_OK;
    for (int i = 0; i < 3; i++) {
        ct_free(cy->ft[b][i]);
        cy->ft[b][i] = NULL;
    }
    ct_free(cy->ex[b]);
    cy->ex[b] = NULL;
    ct_free(cy->pp[b]);
    cy->pp[b] = NULL;
    size_t c = exact ? n + 64 : n + n / 2 + 64;
    int ok = 1;
    for (int i = 0; i < 3; i++)
        ok &= (cy->ft[b][i] = ct_calloc(c, sizeof(ct_real))) != NULL;
    ok &= (cy->ex[b] = ct_calloc(c, sizeof(ct_real))) != NULL;
    ok &= (cy->pp[b] = ct_calloc(c, sizeof(ct_real))) != NULL;
    cy->capft[b] = ok ? c : 0;
    cy->geo.pen = cy->pp[cy->cur];
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
        (p->law != CTD_LAW_TYPE7 && p->law != CTD_LAW_LINEAR) || (p->skip != 0 && p->skip != 1) ||
        !isfinite(p->K0) || !isfinite(p->viss) || !isfinite(p->mu) || !isfinite(p->kt))
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
    cy->skip_on = p->skip && p->two_sided && p->quad == CT_QUAD_4TRI;
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
    for (int b = 0; rc == CT_OK && cy->skip_on && b < 2; b++) {
        cy->xp[b] = ct_calloc((size_t)nnode, sizeof(ct_real));
        cy->yp[b] = ct_calloc((size_t)nnode, sizeof(ct_real));
        cy->zp[b] = ct_calloc((size_t)nnode, sizeof(ct_real));
        if (!cy->xp[b] || !cy->yp[b] || !cy->zp[b])
            rc = CT_ERR_NOMEM;
    }
    if (rc == CT_OK)
        rc = grow_ft(cy, 0, 0, 1);
    if (rc == CT_OK)
        rc = grow_ft(cy, 1, 0, 1);
    if (rc == CT_OK)
        rc = grow_pair_arrays(cy, 0, 1);
    if (rc == CT_OK)
        rc = cti_cycle_scratch_grow(cy, cti_cycle_max_threads(), CY_BLOCK + CY_BLOCK / 8);
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
    for (int b = 0; b < 2; b++) {
        for (int i = 0; i < 3; i++)
            ct_free(cy->ft[b][i]);
        ct_free(cy->ex[b]);
        ct_free(cy->pp[b]);
    }
    ct_free(cy->x0);
    for (int b = 0; b < 2; b++) {
        ct_free(cy->xp[b]);
        ct_free(cy->yp[b]);
        ct_free(cy->zp[b]);
    }
    ct_free(cy->y0);
    ct_free(cy->z0);
    free_pair_arrays(cy);
    cti_cycle_scratch_free(cy);
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
    cy->st.eval_sum = 0;
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

const uint8_t *ctd_cycle_evaluated(const ctd_cycle *cy)
{
    return cy->skip_on ? cy->evald : NULL;
}

const ct_real *ctd_cycle_friction(const ctd_cycle *cy, int axis)
{
    return axis >= 0 && axis < 3 ? cy->ft[cy->cur][axis] : NULL;
}

size_t ctd_cycle_memory(const ctd_cycle *cy)
{
    size_t per = (cti_cycle_fused(cy) ? 10 : 5) * sizeof(ct_idx) +
                 (CY_NGEO - 1) * sizeof(ct_real) + 2 + 3 * sizeof(ct_real);
    size_t b = cy->cap * per + (cy->capft[0] + cy->capft[1]) * 5 * sizeof(ct_real);
    b += (size_t)cy->nscr * (size_t)cy->scrlen *
         (CS_NREAL * sizeof(ct_real) + CS_NIDX * sizeof(ct_idx) + sizeof(int32_t) + 1);
    b += (cy->cap / CY_BLOCK + 2) * (sizeof(cy_block) + 2 * sizeof(ct_idx));
    b += ((size_t)cy->pairs[0].cap + (size_t)cy->pairs[1].cap) * 2 * sizeof(ct_idx);
    b += (cy->skip_on ? 9 : 3) * (size_t)cy->nnode * sizeof(ct_real);
    b += ct_search_memory(cy->search) + ct_assemble_ws_memory(&cy->ws);
    return b;
}

/* ---- Phases ---------------------------------------------------------------- */

/* The search and everything that depends on the pair list. need: the
 * re-sort criterion when the skip's pass evaluated it (bound: its bound),
 * -1 when not. */
static int phase_search(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z,
                        int need, ct_real bound)
{
    int rc;
    if (!cy->need_sort) {
        if (need < 0)
            need = ct_resort_needed(cy->nsec, cy->sec, cy->nmain, cy->mainn, cy->x0, cy->y0,
                                    cy->z0, x, y, z, cy->p.margin, &bound);
        cy->st.bound = bound;
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
    /* The pass's blocks: a node's pairs in one block. */
    const ct_idx nblk = ct_pair_node_blocks(n, np->node, CY_BLOCK, cy->bst);
    if (nblk < 0)
        return nblk;
    ct_idx mb = 0;
    for (ct_idx b = 0; b < nblk; b++)
        mb = cy->bst[b + 1] - cy->bst[b] > mb ? cy->bst[b + 1] - cy->bst[b] : mb;
    cy->nblk = nblk;
    cy->maxblk = mb;
    if ((rc = cti_cycle_scratch_grow(cy, cti_cycle_max_threads(), mb)) != CT_OK)
        return rc;
    ct_asm_map map = ct_asm_map_nodeseg(n, np->node, cy->s[0], cy->s[1], cy->s[2], cy->s[3]);
    /* Fused: the colouring's blocks are the pass's (cti_cycle_fused). */
    rc = cti_cycle_fused(cy)
             ? ct_colour_pair_blocks(&cy->ws, &map, cy->nnode, nblk, cy->bst)
             : ct_assemble_prepare(&cy->ws, cy->p.asm_variant, &map, cy->nnode);
    if (rc != CT_OK)
        return rc;
    rc = ct_friction_remap(op->n, op->node, op->seg, cy->ft[old][0], cy->ft[old][1],
                           cy->ft[old][2], n, np->node, np->seg, cy->ft[now][0],
                           cy->ft[now][1], cy->ft[now][2], cy->old_of_new, NULL);
    if (rc != CT_OK)
        return rc;
    /* The last penetration follows its pair (the carrier choice hands a
     * node's states over when its contact moves to another pair). A pair
     * the skip leaves out reads 0 here: it was out of contact when last
     * evaluated, or it is new. */
    if ((rc = ct_pair_remap(n, cy->old_of_new, cy->pp[old], 0, cy->pp[now])) != CT_OK)
        return rc;
    if (cy->skip_on)
        cti_skip_remap(cy, n, old, now);
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
    cy->geo.pen = cy->pp[now];
    if (!cy->need_sort) { /* fired by the criterion */
        cy->st.natural_sorts++;
        cy->st.interval_sum += cy->st.life_cycles - cy->st.life_last_sort;
    }
    cy->st.life_last_sort = cy->st.life_cycles;
    cy->need_sort = 0;
    cy->st.resorts++;
    return CT_OK;
}

/* The assembly: the nodal forces zeroed, then, with the colouring, the
 * compact lists the pass left (cti_cycle_fused), otherwise every
 * candidate's pair force with the chosen variant. */
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
    const ct_real *const *g = (const ct_real *const *)cy->g;
    if (cti_cycle_fused(cy)) {
        ct_asm_map map = ct_asm_map_nodeseg(n, cy->cn[0], cy->cn[1], cy->cn[2], cy->cn[3],
                                            cy->cn[4]);
        const ct_real *const w[5] = {NULL, g[1], g[2], g[3], g[4]};
        return ct_assemble_coloured_prefix(&cy->ws, &map, cy->nact, w, cy->fp[0], cy->fp[1],
                                           cy->fp[2], nn, fxn, fyn, fzn);
    }
    const ct_pairs *pp = &cy->pairs[cy->cur];
    ct_asm_map map = ct_asm_map_nodeseg(n, pp->node, cy->s[0], cy->s[1], cy->s[2], cy->s[3]);
    const ct_real *const w[5] = {NULL, g[1], g[2], g[3], g[4]};
    return ct_assemble(&cy->ws, cy->p.asm_variant, &map, w, cy->fp[0], cy->fp[1],
                       cy->fp[2], nn, fxn, fyn, fzn);
}

int ctd_cycle_step(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z,
                   const ct_real *vx, const ct_real *vy, const ct_real *vz, ct_real dt,
                   ct_real *fxn, ct_real *fyn, ct_real *fzn)
{
    if (!cy || !x || !y || !z || !vx || !vy || !vz || !fxn || !fyn || !fzn || !(dt >= 0))
        return CT_ERR_ARG;
    /* With the skip, its motion bound and the re-sort criterion in one
     * pass over the nodes: the search phase's time (its check). */
    double tm = ctd_wtime();
    ct_real bound = 0;
    int need = cy->skip_on ? cti_skip_motion(cy, x, y, z, &bound) : -1;
    double t0 = ctd_wtime();
    int64_t nsort = cy->st.resorts;
    int rc = phase_search(cy, x, y, z, need, bound);
    double t1 = ctd_wtime();
    if (cy->st.resorts != nsort)
        cy->st.t_sort += t1 - t0;
    if (rc != CT_OK) {
        cy->need_sort = 1;
        return rc;
    }
    ct_idx n = cy->pairs[cy->cur].n;
    int64_t active = 0, neval = 0;
    double tph[3] = {0, 0, 0};
    rc = cti_cycle_pairs(cy, n, x, y, z, vx, vy, vz, dt, &active, &neval, tph);
    double t2 = ctd_wtime();
    /* The pass's wall time, shared among narrow phase, force and step. */
    if (rc == CT_OK) {
        double all = tph[0] + tph[1] + tph[2], w = t2 - t1;
        for (int i = 0; i < 3; i++)
            tph[i] = all > 0 ? w * tph[i] / all : w / 3;
    }
    if (rc == CT_OK)
        rc = phase_assemble(cy, n, fxn, fyn, fzn);
    double t3 = ctd_wtime();
    if (rc != CT_OK)
        return rc;
    ctd_cycle_stats *s = &cy->st;
    s->t[CTD_PH_SEARCH] += t1 - tm;
    s->t[CTD_PH_NARROW] += tph[0];
    s->t[CTD_PH_FORCE] += tph[1];
    s->t[CTD_PH_ASSEMBLE] += t3 - t2;
    s->t[CTD_PH_TIMESTEP] += tph[2];
    s->cycles++;
    s->life_cycles++;
    s->ncand = n;
    s->nactive = (ct_idx)active;
    s->neval = (ct_idx)neval;
    s->eval_sum += neval;
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
