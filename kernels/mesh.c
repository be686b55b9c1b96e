/*
 * mesh.c -- node arrays, segment meshes, their validation, and the derived
 * topology (unique edges with their segments, node->segment adjacency).
 *
 * The topology is built with counting sorts keyed by node: every entry
 * (an edge's low node, or a segment's node) is counted, the counts are
 * prefix-summed, the entries scattered (integer atomics only), and each
 * node's short list is then sorted, so the result is the same for any
 * thread count. Everything is O(N) plus the sort of a few entries per node.
 */
#include <stdlib.h>

#include "ct_internal.h"

/* ---- Nodes ------------------------------------------------------------- */

int ct_nodes_init(ct_nodes *nd, ct_idx n)
{
    if (!nd || n < 0)
        return CT_ERR_ARG;
    memset(nd, 0, sizeof *nd);
    ct_real **f[10] = {&nd->x, &nd->y, &nd->z, &nd->vx, &nd->vy,
                       &nd->vz, &nd->fx, &nd->fy, &nd->fz, &nd->m};
    for (int k = 0; k < 10; k++) {
        *f[k] = ct_calloc((size_t)n, sizeof(ct_real));
        if (!*f[k]) {
            ct_nodes_destroy(nd);
            return CT_ERR_NOMEM;
        }
    }
    nd->n = n;
    return CT_OK;
}

void ct_nodes_destroy(ct_nodes *nd)
{
    if (!nd)
        return;
    ct_free(nd->x); ct_free(nd->y); ct_free(nd->z);
    ct_free(nd->vx); ct_free(nd->vy); ct_free(nd->vz);
    ct_free(nd->fx); ct_free(nd->fy); ct_free(nd->fz);
    ct_free(nd->m);
    memset(nd, 0, sizeof *nd);
}

/* ---- Mesh -------------------------------------------------------------- */

static void free_topology(ct_mesh *m)
{
    ct_free(m->e1); ct_free(m->e2);
    ct_free(m->edge_seg_off); ct_free(m->edge_seg);
    ct_free(m->node_seg_off); ct_free(m->node_seg);
    m->e1 = m->e2 = m->edge_seg_off = m->edge_seg = NULL;
    m->node_seg_off = m->node_seg = NULL;
    m->nedge = 0;
}

int ct_mesh_init(ct_mesh *m, ct_idx nnode, ct_idx nseg)
{
    if (!m || nnode < 0 || nseg < 0)
        return CT_ERR_ARG;
    memset(m, 0, sizeof *m);
    int rc = ct_nodes_init(&m->nodes, nnode);
    if (rc != CT_OK)
        return rc;
    m->n1 = ct_calloc((size_t)nseg, sizeof(ct_idx));
    m->n2 = ct_calloc((size_t)nseg, sizeof(ct_idx));
    m->n3 = ct_calloc((size_t)nseg, sizeof(ct_idx));
    m->n4 = ct_calloc((size_t)nseg, sizeof(ct_idx));
    if (!m->n1 || !m->n2 || !m->n3 || !m->n4) {
        ct_mesh_destroy(m);
        return CT_ERR_NOMEM;
    }
    m->nseg = nseg;
    return CT_OK;
}

void ct_mesh_destroy(ct_mesh *m)
{
    if (!m)
        return;
    ct_nodes_destroy(&m->nodes);
    ct_free(m->n1); ct_free(m->n2); ct_free(m->n3); ct_free(m->n4);
    free_topology(m);
    memset(m, 0, sizeof *m);
}

/* ---- Validation -------------------------------------------------------- */

#ifdef CT_SINGLE
#define CTI_AREA_TOL 1e-6
#else
#define CTI_AREA_TOL 1e-12
#endif

static const char *const corner_name[4] = {"n1", "n2", "n3", "n4"};

static int bad_index(const ct_mesh *m, ct_idx s)
{
    ct_idx v[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
    for (int k = 0; k < 4; k++)
        if (v[k] < 0 || v[k] >= m->nodes.n)
            return k;
    return -1;
}

/* The first corner (k > j) repeating an earlier corner j, apart from the
 * triangle convention n4 == n3; -1 when none. */
static int repeated(const ct_idx v[4], int *first)
{
    for (int k = 1; k < 4; k++)
        for (int j = 0; j < k; j++)
            if (v[k] == v[j] && !(k == 3 && j == 2)) {
                *first = j;
                return k;
            }
    return -1;
}

static int finite3(const ct_mesh *m, ct_idx i)
{
    return isfinite(m->nodes.x[i]) && isfinite(m->nodes.y[i]) && isfinite(m->nodes.z[i]);
}

/* Area (sum of the triangles n1n2n3 and n1n3n4) and longest edge squared,
 * in double whatever ct_real is. */
static void seg_area(const ct_mesh *m, ct_idx s, double *area, double *l2max)
{
    ct_idx v[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
    double p[4][3];
    for (int k = 0; k < 4; k++) {
        p[k][0] = m->nodes.x[v[k]];
        p[k][1] = m->nodes.y[v[k]];
        p[k][2] = m->nodes.z[v[k]];
    }
    double l2 = 0;
    for (int k = 0; k < 4; k++) {
        const double *a = p[k], *b = p[(k + 1) & 3];
        double d = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                   (b[2] - a[2]) * (b[2] - a[2]);
        l2 = d > l2 ? d : l2;
    }
    double A = 0;
    for (int t = 0; t < 2; t++) {
        const double *a = p[0], *b = p[1 + t], *c = p[2 + t];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2],
               cz = u[0] * w[1] - u[1] * w[0];
        A += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    }
    *area = A;
    *l2max = l2;
}

/* Check segment s; fill diag and return the code when it is bad. Zero area
 * is only judged when the segment's coordinates are finite (non-finite ones
 * are reported by the node pass). */
static int check_seg(const ct_mesh *m, ct_idx s, ct_diag *diag)
{
    ct_idx v[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
    int k = bad_index(m, s);
    if (k >= 0)
        return cti_fail(diag, CT_ERR_RANGE, s,
                        "segment %ld: node %s = %ld is out of range [0, %ld).", (long)s,
                        corner_name[k], (long)v[k], (long)m->nodes.n);
    int j = 0;
    k = repeated(v, &j);
    if (k >= 0)
        return cti_fail(diag, CT_ERR_DUPNODE, s,
                        "segment %ld: node %s = %ld repeats node %s (only n4 == n3 is "
                        "allowed, for a triangle).",
                        (long)s, corner_name[k], (long)v[k], corner_name[j]);
    for (k = 0; k < 4; k++)
        if (!finite3(m, v[k]))
            return CT_OK;
    double area, l2;
    seg_area(m, s, &area, &l2);
    /* The kernels square squared lengths (a normal's length from a cross
     * product): beyond this the arithmetic overflows, and the area test
     * below would read inf <= inf as zero area. */
    if (!(l2 * l2 < (double)CTI_HUGE))
        return cti_fail(diag, CT_ERR_NONFINITE, s,
                        "segment %ld is too large for %s precision: its longest edge squared "
                        "is %g, and the kernels need its square below %g (scale the model's "
                        "length unit).",
                        (long)s, CT_PRECISION_NAME, l2, (double)CTI_HUGE);
    if (area <= CTI_AREA_TOL * l2)
        return cti_fail(diag, CT_ERR_DEGENERATE, s,
                        "segment %ld has zero area: its area %g is at most %g times its "
                        "longest edge squared (%g).",
                        (long)s, area, CTI_AREA_TOL, l2);
    return CT_OK;
}

static int check_node(const ct_mesh *m, ct_idx i, ct_diag *diag)
{
    const ct_real *c[3] = {m->nodes.x, m->nodes.y, m->nodes.z};
    static const char *const name[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; k++)
        if (!isfinite(c[k][i]))
            return cti_fail(diag, CT_ERR_NONFINITE, i, "node %ld: coordinate %s is %s.",
                            (long)i, name[k], isnan(c[k][i]) ? "NaN" : "infinite");
    return CT_OK;
}

int ct_mesh_validate(const ct_mesh *m, ct_diag *diag)
{
    if (!m || m->nseg < 0 || m->nodes.n < 0 ||
        (m->nseg > 0 && (!m->n1 || !m->n2 || !m->n3 || !m->n4)) ||
        (m->nodes.n > 0 && (!m->nodes.x || !m->nodes.y || !m->nodes.z)))
        return cti_fail(diag, CT_ERR_ARG, -1, "The mesh is NULL or incompletely allocated.");
    /* Find the first bad segment, then the first bad node, in parallel: a
     * min-reduction over indices, then the message for that one. */
    ct_idx nseg = m->nseg, nn = m->nodes.n, first = nseg;
#pragma omp parallel for schedule(static) reduction(min : first)
    for (ct_idx s = 0; s < nseg; s++)
        if (s < first && check_seg(m, s, NULL) != CT_OK)
            first = s;
    if (first < nseg)
        return check_seg(m, first, diag);
    first = nn;
#pragma omp parallel for schedule(static) reduction(min : first)
    for (ct_idx i = 0; i < nn; i++)
        if (i < first && check_node(m, i, NULL) != CT_OK)
            first = i;
    if (first < nn)
        return check_node(m, first, diag);
    return CT_OK;
}

/* ---- Topology ---------------------------------------------------------- */

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static void sort_u64(uint64_t *v, int64_t n)
{
    if (n > 32) {
        qsort(v, (size_t)n, sizeof *v, cmp_u64);
        return;
    }
    for (int64_t i = 1; i < n; i++) {
        uint64_t t = v[i];
        int64_t j = i - 1;
        while (j >= 0 && v[j] > t) {
            v[j + 1] = v[j];
            j--;
        }
        v[j + 1] = t;
    }
}

static void sort_idx(ct_idx *v, ct_idx n)
{
    for (ct_idx i = 1; i < n; i++) {
        ct_idx t = v[i], j = i - 1;
        while (j >= 0 && v[j] > t) {
            v[j + 1] = v[j];
            j--;
        }
        v[j + 1] = t;
    }
}

static int cmp_idx(const void *a, const void *b)
{
    ct_idx x = *(const ct_idx *)a, y = *(const ct_idx *)b;
    return (x > y) - (x < y);
}

/* The distinct corners of segment s (a triangle's n4 == n3 counted once;
 * any other repeat is skipped as well). Returns how many. */
static inline int seg_nodes(const ct_mesh *m, ct_idx s, ct_idx v[4])
{
    ct_idx c[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
    int n = 0;
    for (int k = 0; k < 4; k++) {
        int dup = 0;
        for (int j = 0; j < n; j++)
            dup |= (v[j] == c[k]);
        if (!dup)
            v[n++] = c[k];
    }
    return n;
}

/* The edges of segment s as (low, high) pairs, consecutive corners in the
 * cycle n1 n2 n3 n4 with zero-length ones (n4 == n3) skipped. */
static inline int seg_edges(const ct_mesh *m, ct_idx s, ct_idx lo[4], ct_idx hi[4])
{
    ct_idx c[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
    int n = 0;
    for (int k = 0; k < 4; k++) {
        ct_idx a = c[k], b = c[(k + 1) & 3];
        if (a == b)
            continue;
        lo[n] = a < b ? a : b;
        hi[n] = a < b ? b : a;
        n++;
    }
    return n;
}

int ct_mesh_build_topology(ct_mesh *m, ct_diag *diag)
{
    if (!m || m->nseg < 0 || m->nodes.n < 0 ||
        (m->nseg > 0 && (!m->n1 || !m->n2 || !m->n3 || !m->n4)))
        return cti_fail(diag, CT_ERR_ARG, -1, "The mesh is NULL or incompletely allocated.");
    ct_idx nseg = m->nseg, nn = m->nodes.n;
    if ((int64_t)nseg * 4 > INT32_MAX - 1)
        return cti_fail(diag, CT_ERR_TOOBIG, -1,
                        "The mesh has %ld segments: 4 entries per segment overflow a 32-bit "
                        "index.",
                        (long)nseg);
    ct_idx first = nseg;
#pragma omp parallel for schedule(static) reduction(min : first)
    for (ct_idx s = 0; s < nseg; s++)
        if (s < first && bad_index(m, s) >= 0)
            first = s;
    if (first < nseg)
        return check_seg(m, first, diag);
    free_topology(m);

    int rc = CT_ERR_NOMEM;
    ct_idx *cnt = ct_calloc((size_t)nn + 1, sizeof(ct_idx));
    ct_idx *off = ct_calloc((size_t)nn + 1, sizeof(ct_idx));
    ct_idx *ecnt = ct_calloc((size_t)nn + 1, sizeof(ct_idx));
    ct_idx *eoff = ct_calloc((size_t)nn + 1, sizeof(ct_idx));
    uint64_t *ent = NULL;
    m->node_seg_off = ct_calloc((size_t)nn + 1, sizeof(ct_idx));
    if (!cnt || !off || !ecnt || !eoff || !m->node_seg_off)
        goto done;

    /* Node -> segment: count, prefix sum, scatter, sort each node's list. */
#pragma omp parallel for schedule(static)
    for (ct_idx s = 0; s < nseg; s++) {
        ct_idx v[4];
        int k = seg_nodes(m, s, v);
        for (int j = 0; j < k; j++) {
#pragma omp atomic update
            cnt[v[j]]++;
        }
    }
    ct_idx total = cti_prefix_sum_idx(cnt, m->node_seg_off, nn);
    m->node_seg = ct_calloc((size_t)total, sizeof(ct_idx));
    if (!m->node_seg)
        goto done;
    memcpy(off, m->node_seg_off, (size_t)nn * sizeof(ct_idx));
#pragma omp parallel for schedule(static)
    for (ct_idx s = 0; s < nseg; s++) {
        ct_idx v[4];
        int k = seg_nodes(m, s, v);
        for (int j = 0; j < k; j++) {
            ct_idx p;
#pragma omp atomic capture
            p = off[v[j]]++;
            m->node_seg[p] = s;
        }
    }
#pragma omp parallel for schedule(dynamic, 4096)
    for (ct_idx i = 0; i < nn; i++) {
        ct_idx *l = m->node_seg + m->node_seg_off[i];
        ct_idx len = m->node_seg_off[i + 1] - m->node_seg_off[i];
        if (len > 32)
            qsort(l, (size_t)len, sizeof *l, cmp_idx);
        else
            sort_idx(l, len);
    }

    /* Edges: entries (high << 32 | segment) bucketed by the low node, each
     * bucket sorted, so the whole array is ordered by (low, high, segment). */
    memset(cnt, 0, ((size_t)nn + 1) * sizeof(ct_idx));
#pragma omp parallel for schedule(static)
    for (ct_idx s = 0; s < nseg; s++) {
        ct_idx lo[4], hi[4];
        int k = seg_edges(m, s, lo, hi);
        for (int j = 0; j < k; j++) {
#pragma omp atomic update
            cnt[lo[j]]++;
        }
    }
    ct_idx nent = cti_prefix_sum_idx(cnt, off, nn);
    ent = ct_calloc((size_t)nent, sizeof(uint64_t));
    m->edge_seg = ct_calloc((size_t)nent, sizeof(ct_idx));
    if (!ent || !m->edge_seg)
        goto done;
    memcpy(cnt, off, ((size_t)nn + 1) * sizeof(ct_idx));
#pragma omp parallel for schedule(static)
    for (ct_idx s = 0; s < nseg; s++) {
        ct_idx lo[4], hi[4];
        int k = seg_edges(m, s, lo, hi);
        for (int j = 0; j < k; j++) {
            ct_idx p;
#pragma omp atomic capture
            p = cnt[lo[j]]++;
            ent[p] = (uint64_t)(uint32_t)hi[j] << 32 | (uint32_t)s;
        }
    }
#pragma omp parallel for schedule(dynamic, 4096)
    for (ct_idx i = 0; i < nn; i++) {
        uint64_t *l = ent + off[i];
        ct_idx len = off[i + 1] - off[i];
        sort_u64(l, len);
        ct_idx u = 0;
        for (ct_idx j = 0; j < len; j++)
            u += (j == 0 || (l[j] >> 32) != (l[j - 1] >> 32));
        ecnt[i] = u;
    }
    ct_idx nedge = cti_prefix_sum_idx(ecnt, eoff, nn);
    m->e1 = ct_calloc((size_t)nedge, sizeof(ct_idx));
    m->e2 = ct_calloc((size_t)nedge, sizeof(ct_idx));
    m->edge_seg_off = ct_calloc((size_t)nedge + 1, sizeof(ct_idx));
    if (!m->e1 || !m->e2 || !m->edge_seg_off)
        goto done;
#pragma omp parallel for schedule(dynamic, 4096)
    for (ct_idx i = 0; i < nn; i++) {
        const uint64_t *l = ent + off[i];
        ct_idx len = off[i + 1] - off[i], e = eoff[i] - 1;
        for (ct_idx j = 0; j < len; j++) {
            if (j == 0 || (l[j] >> 32) != (l[j - 1] >> 32)) {
                e++;
                m->e1[e] = i;
                m->e2[e] = (ct_idx)(l[j] >> 32);
                m->edge_seg_off[e] = off[i] + j;
            }
            m->edge_seg[off[i] + j] = (ct_idx)(uint32_t)l[j];
        }
    }
    m->edge_seg_off[nedge] = nent;
    m->nedge = nedge;
    rc = CT_OK;

done:
    ct_free(cnt);
    ct_free(off);
    ct_free(ecnt);
    ct_free(eoff);
    ct_free(ent);
    if (rc != CT_OK) {
        free_topology(m);
        return cti_fail(diag, rc, -1, "Out of memory while building the mesh topology.");
    }
    return CT_OK;
}

/* ---- Surfaces and node sets -------------------------------------------- */

int ct_surface_nodes(const ct_mesh *m, const ct_surface *s, ct_nodeset *out)
{
    if (!m || !s || !out || s->n < 0 || (s->n > 0 && !s->seg))
        return CT_ERR_ARG;
    out->n = 0;
    out->node = NULL;
    ct_idx n = s->n, nn = m->nodes.n, nseg = m->nseg;
    int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad)
    for (ct_idx k = 0; k < n; k++) {
        ct_idx t = s->seg[k];
        if (t < 0 || t >= nseg || bad_index(m, t) >= 0)
            bad = 1;
    }
    if (bad)
        return CT_ERR_RANGE;
    unsigned char *mark = ct_calloc((size_t)nn, 1);
    if (!mark)
        return CT_ERR_NOMEM;
#pragma omp parallel for schedule(static)
    for (ct_idx k = 0; k < n; k++) {
        ct_idx t = s->seg[k];
        ct_idx v[4] = {m->n1[t], m->n2[t], m->n3[t], m->n4[t]};
        for (int j = 0; j < 4; j++) {
#pragma omp atomic write
            mark[v[j]] = 1;
        }
    }
    ct_idx cnt = 0;
    for (ct_idx i = 0; i < nn; i++)
        cnt += mark[i];
    out->node = ct_calloc((size_t)cnt, sizeof(ct_idx));
    if (!out->node) {
        ct_free(mark);
        return CT_ERR_NOMEM;
    }
    ct_idx p = 0;
    for (ct_idx i = 0; i < nn; i++)
        if (mark[i])
            out->node[p++] = i;
    out->n = cnt;
    ct_free(mark);
    return CT_OK;
}

void ct_nodeset_destroy(ct_nodeset *s)
{
    if (!s)
        return;
    ct_free(s->node);
    s->node = NULL;
    s->n = 0;
}
