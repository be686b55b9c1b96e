/*
 * contact_cycle_pairs.c -- the fused pass of the contact cycle over the
 * candidate pairs (see contact_cycle.h): the narrow phase of every
 * candidate (with the skip, of those whose expiry has passed), then the
 * force and the time step of the pairs in contact, leaving, with the
 * default colouring, compact lists of their forces for the assembly.
 *
 * The pass runs in blocks of about CY_BLOCK pairs, each holding all the
 * pairs of its nodes (ct_pair_node_blocks), so that a block's per-pair
 * arrays stay in cache from one kernel to the next (separate whole-list
 * passes streamed about 30 arrays of the size of the pair list through
 * memory) and a node's carrying pairs and the hand-over of its pair states
 * are decided inside its block. The narrow phase writes into the thread's scratch; p and the
 * flag go back to the per-pair arrays, and the pairs in contact (p > 0)
 * are packed in place; the force and step kernels run on them alone. A
 * pair out of contact gets from those kernels a zero force, a zero
 * friction force and no step limit, so the pass writes exactly that for it
 * without calling them: on the folded sheet about two candidates in three
 * are out of contact. With the colouring, the pair forces of a block stay
 * packed (a compact list: force, weights, nodes of its pairs in contact, at
 * the block's first positions; block_pack writes the weights and nodes
 * there directly, and the force kernels read them in place), and the
 * assembly reads those lists alone:
 * before, the pass scattered weights and forces into arrays over every
 * candidate (zero out of contact) and the assembly read them all, and the
 * cycle took 1.05-1.16 times its time now on the folded and crumpled
 * sheets. The narrow phase reads the selected pairs in place, their corners
 * through the per-pair slots (ct_narrow_node_slots). Every kernel computes
 * each pair alone, so the packing changes no pair's result, and the blocks
 * are fixed by the pair list: the results are those of whole-list calls,
 * bit for bit, for any thread count (tests/test_cycle.c checks both).
 */
#include "contact_cycle_internal.h"

void cti_cycle_scratch_free(ctd_cycle *cy)
{
    for (int t = 0; t < cy->nscr; t++)
        ct_free(cy->scr[t].mem);
    free(cy->scr);
    cy->scr = NULL;
    cy->nscr = 0;
    cy->scrlen = 0;
}

int cti_cycle_scratch_grow(ctd_cycle *cy, int nthr, ct_idx len)
{
    if (nthr <= cy->nscr && len <= cy->scrlen)
        return CT_OK;
    /* Longer arrays: every thread's scratch made again (at a re-sort, and
     * only when a block is longer than any before). */
    if (len > cy->scrlen) {
        const int keep = cy->nscr;
        cti_cycle_scratch_free(cy);
        nthr = nthr > keep ? nthr : keep;
        cy->scrlen = len;
    }
    len = cy->scrlen;
    cy_scratch *s = realloc(cy->scr, (size_t)nthr * sizeof *s);
    if (!s)
        return CT_ERR_NOMEM;
    cy->scr = s;
    /* Each array a multiple of 64 bytes long, so all stay aligned. */
    const size_t L = ((size_t)len + 63) & ~(size_t)63;
    const size_t nr = L * sizeof(ct_real), ni = L * sizeof(ct_idx);
    for (int t = cy->nscr; t < nthr; t++) {
        char *m = ct_calloc(CS_NREAL * nr + CS_NIDX * ni + L * sizeof(int32_t) + L, 1);
        if (!m)
            return CT_ERR_NOMEM;
        s[t].mem = m;
        for (int a = 0; a < CS_NREAL; a++)
            s[t].v[a] = (ct_real *)(void *)(m + (size_t)a * nr);
        m += CS_NREAL * nr;
        for (int a = 0; a < CS_NIDX; a++)
            s[t].i[a] = (ct_idx *)(void *)(m + (size_t)a * ni);
        m += CS_NIDX * ni;
        s[t].flag7 = (int32_t *)(void *)m;
        s[t].carry = (uint8_t *)(m + L * sizeof(int32_t));
        /* The stiffness is uniform: the TYPE7 kernel reads it per pair. */
        for (size_t k = 0; k < L; k++)
            s[t].v[CS_K0][k] = cy->p.K0;
        cy->nscr = t + 1;
    }
    return CT_OK;
}

/* The narrow phase of block [k0, k1): of every pair, or with the skip of
 * those whose expiry has passed, into the scratch (act: their indices in
 * the block). The slots are chosen so that the force kernels' inputs (h,
 * n, p, gap) land where the force pass reads them; the distance and the
 * contact point borrow four slots the force pass only writes. */
static int block_narrow(ctd_cycle *cy, ct_idx k0, ct_idx k1, cy_scratch *s, const ct_real *x,
                        const ct_real *y, const ct_real *z, ct_idx *neval)
{
    const ct_pairs *pp = &cy->pairs[cy->cur];
    const ct_idx nb = k1 - k0;
    ct_idx *restrict act = s->i[CS_ACT];
    ct_idx ne = nb;
    if (cy->skip_on) {
        ne = cti_skip_select(cy, k0, k1, act);
    } else {
        for (ct_idx k = 0; k < nb; k++)
            act[k] = k;
    }
    *neval = ne;
    if (ne == 0)
        return CT_OK;
    /* The selected pairs through the per-pair slots (s1..s4, one index per
     * pair, no copy) rather than n1..n4 through the segment numbers. */
    ct_real *const *v = s->v;
    uint8_t *fl = (uint8_t *)(void *)s->flag7;
    const ct_contact_geo out = {v[CS_VRX], v[CS_PEN], v[CS_NX], v[CS_NY], v[CS_NZ],
                                v[CS_VRY], v[CS_VRZ], v[CS_VN], v[CS_H1], v[CS_H2],
                                v[CS_H3],  v[CS_H4],  v[CS_GAP], fl};
    int rc = ct_narrow_node_slots(ne, act, pp->node + k0, cy->s[0] + k0, cy->s[1] + k0,
                                  cy->s[2] + k0, cy->s[3] + k0, x, y, z, cy->p.gap,
                                  cy->p.quad, cy->p.two_sided, &out, NULL);
    if (rc == CT_OK && cy->skip_on)
        cti_skip_expiry(cy, k0, ne, act, out.dist, out.gap, fl);
    return rc;
}

/* After block_narrow: the pairs that carry each node (ct_select_pairs, one
 * per side) among the block's ne evaluated pairs, the others' penetration
 * set to 0 (they then get no force, as out of contact), and the hand-overs
 * (s->i[CS_HO], evaluated indices): a node's new carrier on a side takes
 * the friction history of the pair that carried it there last step. The
 * block holds all its nodes' pairs, and a pair the skip leaves out was out
 * of contact at its last evaluation (last penetration 0): the evaluated
 * pairs decide each node whole. */
static int block_select(const ctd_cycle *cy, ct_idx k0, ct_idx ne, cy_scratch *s,
                        const ct_real *x, const ct_real *y, const ct_real *z)
{
    if (ne == 0)
        return CT_OK;
    const ct_idx *restrict node = cy->pairs[cy->cur].node + k0;
    const ct_real *restrict pen = cy->geo.pen + k0;
    const ct_idx *restrict act = s->i[CS_ACT];
    ct_real *const *v = s->v;
    const ct_contact_geo g = {v[CS_VRX], v[CS_PEN], v[CS_NX], v[CS_NY], v[CS_NZ],
                              v[CS_VRY], v[CS_VRZ], v[CS_VN], v[CS_H1], v[CS_H2],
                              v[CS_H3],  v[CS_H4],  v[CS_GAP], (uint8_t *)(void *)s->flag7};
    /* The evaluated pairs' nodes and last penetrations (this step's are
     * written back after the selection, by block_pack). */
    ct_idx *restrict nd = s->i[CS_NODE];
    ct_real *restrict pv = v[CS_PPREV];
    for (ct_idx j = 0; j < ne; j++) {
        nd[j] = node[act[j]];
        pv[j] = pen[act[j]];
    }
    return ct_select_pairs(ne, nd, x, y, z, cy->p.two_sided, &g, pv, s->carry, s->i[CS_HO],
                           NULL);
}

/* Where a block's packed pairs live for the force and step kernels: the
 * weights and the nodes (secondary node, then the corners' slots). With
 * the fused assembly (cti_cycle_fused) they are the block's compact list
 * itself (g[1..4] and cn at the block's first positions), which block_pack
 * fills directly: the assembly reads them there, so the pass no longer
 * copies them out of the scratch after the force; otherwise the scratch. */
typedef struct cy_packed {
    ct_real *h[4];
    ct_idx *c[5];
} cy_packed;

static cy_packed block_packed(const ctd_cycle *cy, ct_idx k0, const cy_scratch *s)
{
    cy_packed pk;
    const int fused = cti_cycle_fused(cy);
    for (int a = 0; a < 4; a++)
        pk.h[a] = fused ? cy->g[1 + a] + k0 : s->v[CS_H1 + a];
    for (int a = 0; a < 5; a++)
        pk.c[a] = fused ? cy->cn[a] + k0 : s->i[CS_NODE + a];
    return pk;
}

/* After block_narrow: write the results back into the interface's arrays
 * (p and the flag of every evaluated pair, the weights of the pairs in
 * contact), then pack the pairs in contact for the force and step kernels:
 * their indices in the block (act), their geometry (compacted in place, the
 * weights into dst's), nodes (dst's), mass and friction history. Returns
 * their count. */
static ct_idx block_pack(const ctd_cycle *cy, ct_idx k0, ct_idx ne, cy_scratch *s,
                         const cy_packed *dst)
{
    const ct_contact_geo *g = &cy->geo;
    ct_real *const *v = s->v;
    ct_idx *act = s->i[CS_ACT];
    const uint8_t *restrict fl = (const uint8_t *)(const void *)s->flag7;
    const ct_real *restrict pen = v[CS_PEN];
    {
        ct_real *restrict gp = g->pen + k0;
        uint8_t *restrict gf = g->flag + k0;
        const ct_idx *restrict a = act;
        for (ct_idx j = 0; j < ne; j++) {
            gp[a[j]] = pen[j];
            gf[a[j]] = fl[j];
        }
    }
    /* The evaluated pairs in contact (positions in the scratch, pk). Every
     * index is written, the count advances by the test: no branch. */
    ct_idx na = 0;
    {
        ct_idx *restrict w = s->i[CS_S4];
        for (ct_idx j = 0; j < ne; j++) {
            w[na] = j;
            na += pen[j] > 0;
        }
    }
    /* pk's uses end before the gathers below, which may write its array
     * (dst's fourth corner without the fused assembly). */
    {
        const ct_idx *restrict pk = s->i[CS_S4];
        /* Their weights, which the assembly reads (the per-pair arrays of
         * ctd_cycle_geo; with the fused assembly, the compact lists instead).
         * (The other results are not kept: stored for every pair, they cost
         * more than the narrow phase saved by the skip, every store a cache
         * miss.) */
        {
            const int slot[4] = {CS_H1, CS_H2, CS_H3, CS_H4};
            ct_real *const gw[4] = {g->h1, g->h2, g->h3, g->h4};
            for (int a = 0; a < 4 && gw[0]; a++) {
                const ct_real *restrict f = v[slot[a]];
                ct_real *restrict t = gw[a] + k0;
                for (ct_idx i = 0; i < na; i++)
                    t[act[pk[i]]] = f[pk[i]];
            }
        }
        /* The pair (index in the block) whose friction history each pair in
         * contact takes: its own, or the one its node's contact moved from
         * (block_select's hand-over, an evaluated index), which then loses it
         * (block_unpack: it is out of contact). In place: pk[i] >= i. Before
         * act is compacted: from may be below i. */
        {
            ct_idx *restrict hs = s->i[CS_HO];
            const int handover = cy->p.select;
            for (ct_idx i = 0; i < na; i++) {
                const ct_idx j = pk[i], from = handover ? hs[j] : -1;
                hs[i] = act[from >= 0 ? from : j];
            }
        }
        /* Compact the geometry and the indices, in one pass: the normal, p
         * and the gap in place (pk[i] >= i: a slot is read before it is
         * overwritten), the weights into dst (in place when dst is the
         * scratch), act in place. */
        {
            ct_real *nx = v[CS_NX], *ny = v[CS_NY], *nz = v[CS_NZ], *pp = v[CS_PEN];
            ct_real *gap = v[CS_GAP];
            const ct_real *h1 = v[CS_H1], *h2 = v[CS_H2], *h3 = v[CS_H3], *h4 = v[CS_H4];
            ct_real *d1 = dst->h[0], *d2 = dst->h[1], *d3 = dst->h[2], *d4 = dst->h[3];
            for (ct_idx i = 0; i < na; i++) {
                const ct_idx j = pk[i];
                nx[i] = nx[j];
                ny[i] = ny[j];
                nz[i] = nz[j];
                pp[i] = pp[j];
                gap[i] = gap[j];
                d1[i] = h1[j];
                d2[i] = h2[j];
                d3[i] = h3[j];
                d4[i] = h4[j];
                act[i] = act[j];
            }
        }
    }
    {
        /* Nodes, mass and history of the pairs in contact (dst's nodes;
         * pk's array may be the fourth corner's: pk is not read below). */
        const ct_idx *restrict nd = cy->pairs[cy->cur].node + k0;
        const ct_idx *restrict s1 = cy->s[0] + k0, *restrict s2 = cy->s[1] + k0;
        const ct_idx *restrict s3 = cy->s[2] + k0, *restrict s4 = cy->s[3] + k0;
        const ct_real *restrict mass = cy->m;
        ct_idx *restrict cn = dst->c[0], *restrict c1 = dst->c[1];
        ct_idx *restrict c2 = dst->c[2], *restrict c3 = dst->c[3];
        ct_idx *restrict c4 = dst->c[4];
        ct_real *restrict ms = v[CS_MS];
        const ct_idx *restrict ac = act;
        for (ct_idx i = 0; i < na; i++) {
            const ct_idx k = ac[i];
            cn[i] = nd[k];
            c1[i] = s1[k];
            c2[i] = s2[k];
            c3[i] = s3[k];
            c4[i] = s4[k];
            ms[i] = mass[nd[k]];
        }
        if (cy->p.mu > 0) {
            /* The three components in one pass: three streams of loads in
             * flight per pair, not one array after another. */
            ct_real *const *ft = cy->ft[cy->cur];
            const ct_real *restrict f0 = ft[0] + k0, *restrict f1 = ft[1] + k0;
            const ct_real *restrict f2 = ft[2] + k0;
            ct_real *restrict t0 = v[CS_T0], *restrict t1 = v[CS_T0 + 1];
            ct_real *restrict t2 = v[CS_T0 + 2];
            const ct_idx *restrict hs = s->i[CS_HO];
            for (ct_idx i = 0; i < na; i++) {
                const ct_idx k = hs[i];
                t0[i] = f0[k];
                t1[i] = f1[k];
                t2[i] = f2[k];
            }
        }
    }
    return na;
}

/* The force of the na packed pairs of s (weights and nodes in pk):
 * relative velocity, normal law, damping, Coulomb friction. Every kernel
 * is called on the packed pairs alone (below their thread-team thresholds:
 * no team). */
static int packed_force(const ctd_cycle *cy, ct_idx na, cy_scratch *s, const cy_packed *pk,
                        const ct_real *vx, const ct_real *vy, const ct_real *vz, ct_real dt)
{
    ct_real *const *v = s->v;
    int rc = ct_relative_velocity(na, pk->c[0], pk->c[1], pk->c[2], pk->c[3], pk->c[4],
                                  pk->h[0], pk->h[1], pk->h[2], pk->h[3], v[CS_NX], v[CS_NY],
                                  v[CS_NZ], vx, vy, vz, NULL, v[CS_VRX], v[CS_VRY], v[CS_VRZ],
                                  v[CS_VN], NULL);
    if (rc != CT_OK)
        return rc;
    if (cy->p.law == CTD_LAW_TYPE7) {
        rc = ct_penalty_type7(na, v[CS_PEN], v[CS_GAP], v[CS_K0], v[CS_FEL], v[CS_KTAN], NULL,
                              s->flag7);
        if (rc == CT_OK)
            rc = ct_normal_finish(na, v[CS_PEN], v[CS_FEL], v[CS_KTAN], v[CS_VN], v[CS_MS],
                                  NULL, cy->p.viss, dt, v[CS_NX], v[CS_NY], v[CS_NZ], v[CS_FN],
                                  v[CS_FX], v[CS_FY], v[CS_FZ], NULL);
    } else {
        rc = ct_normal_force(na, v[CS_PEN], v[CS_NX], v[CS_NY], v[CS_NZ], v[CS_VN], NULL,
                             cy->p.K0, v[CS_MS], NULL, cy->p.viss, dt, v[CS_FX], v[CS_FY],
                             v[CS_FZ], v[CS_FN], NULL, NULL);
        /* The tangent stiffness for the nodal step: K0, every pair is in
         * contact. */
        ct_real *restrict kt = v[CS_KTAN];
        const ct_real K0 = cy->p.K0;
        for (ct_idx i = 0; i < na; i++)
            kt[i] = K0;
    }
    if (rc != CT_OK || !(cy->p.mu > 0))
        return rc;
    return ct_friction_step(na, v[CS_NX], v[CS_NY], v[CS_NZ], v[CS_VRX], v[CS_VRY], v[CS_VRZ],
                            v[CS_FN], NULL, cy->p.mu, NULL, cy->p.kt, dt, 1, v[CS_T0], v[CS_T1],
                            v[CS_T2], NULL);
}

/* Write block [k0, k1)'s friction histories (the packed pairs' results,
 * zero for the others) and its pair forces (normal plus tangential). With
 * the fused assembly (cti_cycle_fused), the forces go to the block's
 * compact list: its pairs in contact at [k0, k0 + na) of the per-pair
 * arrays, in order, beside their nodes and weights, which block_pack put
 * there; the assembly then reads those lists alone. Otherwise into the
 * per-pair arrays fp, zero for the pairs out of contact. */
static void block_unpack(const ctd_cycle *cy, ct_idx k0, ct_idx k1, ct_idx na,
                         const cy_scratch *s)
{
    const int fric = cy->p.mu > 0, fused = cti_cycle_fused(cy);
    ct_real *const *ft = cy->ft[cy->cur];
    const ct_idx *restrict act = s->i[CS_ACT];
    for (int d = 0; d < 3; d++) {
        ct_real *restrict f = cy->fp[d] + k0, *restrict h = ft[d] + k0;
        const ct_real *restrict fn = s->v[CS_FX + d], *restrict fh = s->v[CS_T0 + d];
        if (fused) {
            for (ct_idx i = 0; !fric && i < na; i++)
                f[i] = fn[i];
            for (ct_idx i = 0; fric && i < na; i++)
                f[i] = fn[i] + fh[i];
        } else {
            memset(f, 0, sizeof(ct_real) * (size_t)(k1 - k0));
            for (ct_idx i = 0; !fric && i < na; i++)
                f[act[i]] = fn[i];
            for (ct_idx i = 0; fric && i < na; i++)
                f[act[i]] = fn[i] + fh[i];
        }
        if (fric)
            memset(h, 0, sizeof(ct_real) * (size_t)(k1 - k0));
    }
    if (fric) {
        /* The histories of the pairs in contact, the three components in
         * one pass (as block_pack reads them). */
        ct_real *restrict h0 = ft[0] + k0, *restrict h1 = ft[1] + k0, *restrict h2 = ft[2] + k0;
        const ct_real *restrict g0 = s->v[CS_T0], *restrict g1 = s->v[CS_T0 + 1];
        const ct_real *restrict g2 = s->v[CS_T0 + 2];
        for (ct_idx i = 0; i < na; i++) {
            const ct_idx k = act[i];
            h0[k] = g0[i];
            h1[k] = g1[i];
            h2[k] = g2[i];
        }
    }
}

/* The two step limits of the na packed pairs of block k0 into the block's
 * record (indices of the whole list; packing keeps the order, so the
 * smallest index still wins a tie). */
static void packed_timestep(const ctd_cycle *cy, ct_idx k0, ct_idx na, const cy_scratch *s,
                            const cy_packed *pk, cy_block *b)
{
    const ct_idx *act = s->i[CS_ACT];
    b->rc_kin = ct_dt_type7_kinematic(na, s->v[CS_PEN], s->v[CS_GAP], s->v[CS_VN], NULL,
                                      &b->dt_kin, &b->i_kin);
    b->rc_nod = ct_dt_nodal(na, pk->c[0], cy->m, NULL, s->v[CS_KTAN], NULL, &b->dt_nod,
                            &b->i_nod);
    b->i_kin = b->i_kin >= 0 ? k0 + act[b->i_kin] : -1;
    b->i_nod = b->i_nod >= 0 ? k0 + act[b->i_nod] : -1;
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

/* The narrow phase, force and time step of every pair, fused in blocks
 * (see the head of the file). The phases are timed per block; the caller
 * shares the pass's wall time among them in proportion to the sums of
 * those times (tph: narrow, force with its packing, step). */
int cti_cycle_pairs(ctd_cycle *cy, ct_idx n, const ct_real *x, const ct_real *y,
                    const ct_real *z, const ct_real *vx, const ct_real *vy, const ct_real *vz,
                    ct_real dt, int64_t *active, int64_t *neval, double tph[3])
{
    /* A team larger than any before gets its scratch here, once. */
    int rc = cti_cycle_scratch_grow(cy, cti_cycle_max_threads(), cy->maxblk);
    if (rc != CT_OK)
        return rc;
    const ct_idx nblk = n > 0 ? cy->nblk : 0;
    const ct_idx *bst = cy->bst;
    cy_block *blk = cy->blk;
#pragma omp parallel for schedule(static)
    for (ct_idx bi = 0; bi < nblk; bi++) {
        const ct_idx k0 = bst[bi], k1 = bst[bi + 1];
        cy_block *b = &blk[bi];
        cy_scratch *s = &cy->scr[cti_cycle_thread()];
        double t0 = ctd_wtime();
        ct_idx ne = 0;
        b->rc = block_narrow(cy, k0, k1, s, x, y, z, &ne);
        if (b->rc == CT_OK && cy->p.select)
            b->rc = block_select(cy, k0, ne, s, x, y, z);
        b->neval = ne;
        double t1 = ctd_wtime();
        ct_idx na = 0;
        const cy_packed pk = block_packed(cy, k0, s);
        if (b->rc == CT_OK) {
            na = block_pack(cy, k0, ne, s, &pk);
            b->rc = packed_force(cy, na, s, &pk, vx, vy, vz, dt);
            if (b->rc == CT_OK)
                block_unpack(cy, k0, k1, na, s);
        }
        b->active = na;
        cy->nact[bi] = na;
        double t2 = ctd_wtime();
        if (b->rc == CT_OK)
            packed_timestep(cy, k0, na, s, &pk, b);
        double t3 = ctd_wtime();
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
    *neval = 0;
    for (ct_idx bi = 0; bi < nblk; bi++) {
        const cy_block *b = &blk[bi];
        if (b->rc != CT_OK)
            return b->rc;
        *active += b->active;
        *neval += b->neval;
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
