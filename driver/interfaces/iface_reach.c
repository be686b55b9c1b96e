/*
 * iface_reach.c -- what an interface's gaps let the search find, against
 * the model and the machine.
 *
 * A gap as large as the model makes every node a contact of every segment:
 * the candidates grow as nsec x nseg (a 10^4-node sheet with a 10 m gap
 * exhausted 24 GiB and was killed) and the penalty pushes across the whole
 * model. ctd_iface_check_reach tells it before the run starts. A smaller
 * gap can still find more pairs than the machine holds on a large model:
 * the node-segment search stops at ctdi_pair_limit pairs (its max_pairs),
 * TYPE11's counted pairs go through ctdi_pair_budget, and either failure
 * writes the message (ctdi_pairs_too_many) before the pair arrays are
 * allocated (Linux grants large allocations and kills the process when
 * their pages are touched, so the allocation failing cannot be relied on).
 */
#include <math.h>
#include <stdio.h>
#include <unistd.h>

#include "type11_internal.h"

/* The box around the listed nodes of two lists, grown into lo, hi. */
static void box_of(ct_idx n, const ct_idx *v, const ct_real *x, const ct_real *y,
                   const ct_real *z, double lo[3], double hi[3])
{
    for (ct_idx i = 0; i < n; i++) {
        double c[3] = {x[v[i]], y[v[i]], z[v[i]]};
        for (int d = 0; d < 3; d++) {
            lo[d] = c[d] < lo[d] ? c[d] : lo[d];
            hi[d] = c[d] > hi[d] ? c[d] : hi[d];
        }
    }
}

/* The diagonal of the box around the nodes of lists a and b. */
static double extent(ct_idx na, const ct_idx *a, ct_idx nb, const ct_idx *b, const ct_real *x,
                     const ct_real *y, const ct_real *z)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    box_of(na, a, x, y, z, lo, hi);
    box_of(nb, b, x, y, z, lo, hi);
    if (!(hi[0] >= lo[0]))
        return INFINITY; /* no node: nothing to span */
    double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

static int too_far(char *msg, size_t len, const char *what, double gap, double diag, double h)
{
    if (!(gap >= diag))
        return CT_OK;
    char hs[64] = "";
    if (h > 0)
        snprintf(hs, sizeof hs, ", %.3g here", h);
    snprintf(msg, len,
             "its %s gap %g reaches the diagonal %g of the box around its nodes, so every "
             "node would be in contact with every %s (expected a gap below the element "
             "size%s)",
             what, gap, diag, what[0] == 'e' ? "edge" : "segment", hs);
    return CT_ERR_ARG;
}

int ctd_iface_check_reach(const ctd_iface *it, const ct_real *x, const ct_real *y,
                          const ct_real *z, char *msg, size_t len)
{
    if (!it || !x || !y || !z)
        return CT_ERR_ARG;
    for (int i = 0; i < it->npass; i++) {
        const ctdi_pass *p = &it->pass[i];
        if (p->nsec == 0 || p->nseg == 0)
            continue;
        double d = extent(p->nsec, p->sec, p->nmain, p->mainn, x, y, z);
        double h = ctdi_mean_seg_edge(p->nseg, p->n1, p->n2, p->n3, p->n4, x, y, z);
        int rc = too_far(msg, len, "node-segment", p->reach, d, h);
        if (rc != CT_OK)
            return rc;
    }
    const ctdi_epass *e = it->ep;
    if (e && e->ne > 0) {
        /* sgap is the sum of two edge gaps: the distance of two edges' axes
         * in contact. */
        double d = extent(e->nan, e->an, e->nbn, e->bn, x, y, z);
        return too_far(msg, len, "edge-edge", e->sgap, d, 0);
    }
    return CT_OK;
}

/* The squared distance of nodes p and q. */
static double dist2(const ct_real *x, const ct_real *y, const ct_real *z, ct_idx p, ct_idx q)
{
    const double dx = (double)x[p] - (double)x[q], dy = (double)y[p] - (double)y[q],
                 dz = (double)z[p] - (double)z[q];
    return dx * dx + dy * dy + dz * dz;
}

/* The shortest edge of the segments (INFINITY when none). */
static double shortest_seg_edge(const ctdi_pass *p, const ct_real *x, const ct_real *y,
                                const ct_real *z)
{
    double h2 = INFINITY;
    for (ct_idx j = 0; j < p->nseg; j++) {
        const ct_idx v[4] = {p->n1[j], p->n2[j], p->n3[j], p->n4[j]};
        const int nv = v[3] == v[2] ? 3 : 4;
        for (int a = 0; a < nv; a++)
            h2 = fmin(h2, dist2(x, y, z, v[a], v[(a + 1) % nv]));
    }
    return sqrt(h2);
}

/* The shortest of TYPE11's edges (INFINITY when none). */
static double shortest_edge(const ctdi_epass *e, const ct_real *x, const ct_real *y,
                            const ct_real *z)
{
    double h2 = INFINITY;
    for (ct_idx k = 0; k < e->ne; k++)
        h2 = fmin(h2, dist2(x, y, z, e->e1[k], e->e2[k]));
    return sqrt(h2);
}

/* The note for a self-contact gap against the shortest edge h: 1 with the
 * note in msg when the gap is more than half of h. With Irem_gap 2 the
 * neighbours within the gap at the start are out of contact; those beyond
 * it still come within it when the segments between are compressed. */
static int gap_note(char *msg, size_t len, const char *what, const char *who, double gap,
                    double h, int irem)
{
    if (!(gap > 0.5 * h))
        return 0;
    if (irem)
        snprintf(msg, len,
                 "self contact%s with a gap of %g, more than half the shortest edge (%g): "
                 "Irem_gap 2 takes the neighbours within the gap at the start out of contact; "
                 "%s still comes within the gap of its farther neighbours when the segments "
                 "between are compressed",
                 what, gap, h, who);
    else
        snprintf(msg, len,
                 "self contact%s with a gap of %g, more than half the shortest edge (%g): %s "
                 "comes within the gap of its neighbours %s (expected a gap of at most half the "
                 "shortest edge, as Radioss recommends, or Irem_gap: 2)",
                 what, gap, h, who,
                 gap >= h ? "from the start" : "when the segments between are compressed");
    return 1;
}

int ctd_iface_self_gap_note(const ctd_iface *it, const ct_real *x, const ct_real *y,
                            const ct_real *z, char *msg, size_t len)
{
    if (len > 0)
        msg[0] = 0;
    if (!it || !x || !y || !z)
        return 0;
    for (int i = 0; i < it->npass; i++) {
        const ctdi_pass *p = &it->pass[i];
        if (p->self && p->nseg > 0 &&
            gap_note(msg, len, "", "a node", (double)p->reach, shortest_seg_edge(p, x, y, z),
                     p->excl_state != 0))
            return 1;
    }
    /* TYPE11's sgap: the distance of two edges' axes in contact. */
    const ctdi_epass *e = it->ep;
    return e && e->self && e->ne > 0 &&
           gap_note(msg, len, " of edges", "an edge", (double)e->sgap, shortest_edge(e, x, y, z),
                    e->excl_state != 0);
}

/* The machine's physical memory in bytes (INFINITY when unknown). */
static double physical_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    return pages > 0 && size > 0 ? (double)pages * (double)size : INFINITY;
}

/* The bytes the pair arrays may take: the interface's limit, or the
 * machine's memory. */
static double pair_memory(const ctd_iface *it)
{
    return it->cfg.mem_limit > 0 ? it->cfg.mem_limit : physical_memory();
}

int64_t ctdi_pair_limit(const ctd_iface *it, size_t bytes_per_pair)
{
    double n = floor(pair_memory(it) / (1.5 * (double)bytes_per_pair));
    return n < (double)INT32_MAX ? (int64_t)n : INT32_MAX;
}

int ctdi_pairs_too_many(ctd_iface *it, int64_t npair, int more, ct_idx nsec,
                        size_t bytes_per_pair, double gap)
{
    const double gib = 1024.0 * 1024.0 * 1024.0;
    const double need = 1.5 * (double)npair * (double)bytes_per_pair, have = pair_memory(it);
    char what[96], room[64] = "";
    /* The count's limit, not the memory's: more than the index counts, or
     * a count the memory holds. */
    if (more ? ctdi_pair_limit(it, bytes_per_pair) == INT32_MAX : need <= have) {
        snprintf(what, sizeof what, "a 32-bit index");
    } else {
        snprintf(what, sizeof what, "the %.3g GiB %s", have / gib,
                 it->cfg.mem_limit > 0 ? "of the interface's memory limit"
                                       : "of this machine's memory");
        snprintf(room, sizeof room, " at %zu bytes a pair", (size_t)(1.5 * bytes_per_pair));
    }
    snprintf(it->msg, sizeof it->msg,
             "the search found %s%lld candidate pairs (%.3g per secondary) within the search "
             "gap %g, more than %s holds%s (expected a gap below the element size)",
             more ? "more than " : "", (long long)npair,
             nsec > 0 ? (double)npair / (double)nsec : 0.0, gap, what, room);
    return CT_ERR_NOMEM;
}

int ctdi_pair_budget(ctd_iface *it, int64_t npair, ct_idx nsec, size_t bytes_per_pair,
                     double gap)
{
    if (npair <= ctdi_pair_limit(it, bytes_per_pair))
        return CT_OK;
    return ctdi_pairs_too_many(it, npair, 0, nsec, bytes_per_pair, gap);
}
