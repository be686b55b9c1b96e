/*
 * meshgen.c -- the search-case object: names, destruction, the search
 * input, and renumbering (shuffled, space-filling curve) with the radix
 * sort it uses. The families themselves are built in meshgen_cases.c.
 */
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"

static const char *const families[] = {"plates", "plates-tri", "block",    "sphere", "tube",
                                       "folded", "crumpled",   "soup",     "graded",
                                       "ball-plate"};

const char *const *ctd_case_families(int *count)
{
    if (count)
        *count = (int)(sizeof families / sizeof families[0]);
    return families;
}

static const char *const num_names[3] = {"natural", "shuffled", "sfc"};

const char *ctd_numbering_name(ctd_numbering n)
{
    return (n >= CTD_NUM_NATURAL && n <= CTD_NUM_SFC) ? num_names[n] : "unknown";
}

int ctd_numbering_from_name(const char *name)
{
    for (int k = 0; name && k < 3; k++)
        if (strcmp(name, num_names[k]) == 0)
            return k;
    return -1;
}

void ctd_case_destroy(ctd_case *c)
{
    if (!c)
        return;
    ct_mesh_destroy(&c->mesh);
    ct_free(c->main.seg);
    ct_nodeset_destroy(&c->sec);
    ct_free(c->mn1);
    ct_free(c->mn2);
    ct_free(c->mn3);
    ct_free(c->mn4);
    memset(c, 0, sizeof *c);
}

void ctd_case_input(const ctd_case *c, ct_real gap, ct_real margin, ct_search_input *in)
{
    memset(in, 0, sizeof *in);
    in->nnode = c->mesh.nodes.n;
    in->x = c->mesh.nodes.x;
    in->y = c->mesh.nodes.y;
    in->z = c->mesh.nodes.z;
    in->nsec = c->sec.n;
    in->sec = c->sec.node;
    in->nseg = c->main.n;
    in->n1 = c->mn1;
    in->n2 = c->mn2;
    in->n3 = c->mn3;
    in->n4 = c->mn4;
    in->gap = gap;
    in->margin = margin;
    in->self = c->self;
}

/* ---- Radix sort -------------------------------------------------------- */

int ctd_radix_sort(uint64_t *key, ct_idx *val, int64_t n)
{
    if (n < 2)
        return CT_OK;
    uint64_t *k2 = malloc(sizeof(uint64_t) * (size_t)n);
    ct_idx *v2 = malloc(sizeof(ct_idx) * (size_t)n);
    if (!k2 || !v2) {
        free(k2);
        free(v2);
        return CT_ERR_NOMEM;
    }
    uint64_t *ka = key, *kb = k2;
    ct_idx *va = val, *vb = v2;
    for (int shift = 0; shift < 64; shift += 8) {
        int64_t cnt[256] = {0};
        for (int64_t i = 0; i < n; i++)
            cnt[(ka[i] >> shift) & 255]++;
        if (cnt[(ka[0] >> shift) & 255] == n)
            continue; /* every key has the same digit: nothing to do */
        int64_t run = 0;
        for (int d = 0; d < 256; d++) {
            int64_t t = cnt[d];
            cnt[d] = run;
            run += t;
        }
        for (int64_t i = 0; i < n; i++) {
            int64_t p = cnt[(ka[i] >> shift) & 255]++;
            kb[p] = ka[i];
            vb[p] = va[i];
        }
        uint64_t *tk = ka; ka = kb; kb = tk;
        ct_idx *tv = va; va = vb; vb = tv;
    }
    if (ka != key) {
        memcpy(key, ka, sizeof(uint64_t) * (size_t)n);
        memcpy(val, va, sizeof(ct_idx) * (size_t)n);
    }
    free(k2);
    free(v2);
    return CT_OK;
}

/* ---- Renumbering ------------------------------------------------------- */

/* Spread the low 21 bits of v to every third bit. */
static inline uint64_t spread3(uint64_t v)
{
    v &= 0x1fffffULL;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

typedef struct box3 {
    double lo[3], scale[3];
} box3;

static inline uint64_t morton(const box3 *b, double x, double y, double z)
{
    double p[3] = {x, y, z};
    uint64_t q[3];
    for (int a = 0; a < 3; a++) {
        double t = (p[a] - b->lo[a]) * b->scale[a];
        t = t < 0 ? 0 : t > 2097151.0 ? 2097151.0 : t;
        q[a] = (uint64_t)t;
    }
    return spread3(q[0]) | spread3(q[1]) << 1 | spread3(q[2]) << 2;
}

/* A random permutation of 0..n-1 (Fisher-Yates). */
static void shuffle(ct_idx *p, ct_idx n, uint64_t seed)
{
    uint64_t st = seed;
    for (ct_idx i = 0; i < n; i++)
        p[i] = i;
    for (ct_idx i = n - 1; i > 0; i--) {
        ct_idx j = (ct_idx)(ctd_u01(ctd_splitmix64(&st)) * (double)(i + 1));
        j = j > i ? i : j;
        ct_idx t = p[i];
        p[i] = p[j];
        p[j] = t;
    }
}

/* The permutations (new -> old) of nodes and segments along the Morton
 * curve of the coordinates (segments by their corners' mean). */
static int sfc_order(const ct_mesh *m, ct_idx *node_old, ct_idx *seg_old)
{
    ct_idx nn = m->nodes.n, ns = m->nseg;
    const ct_real *x = m->nodes.x, *y = m->nodes.y, *z = m->nodes.z;
    double lo0 = 1e300, lo1 = 1e300, lo2 = 1e300, hi0 = -1e300, hi1 = -1e300, hi2 = -1e300;
#pragma omp parallel for schedule(static) reduction(min : lo0, lo1, lo2) \
    reduction(max : hi0, hi1, hi2)
    for (ct_idx i = 0; i < nn; i++) {
        lo0 = lo0 < x[i] ? lo0 : x[i]; hi0 = hi0 > x[i] ? hi0 : x[i];
        lo1 = lo1 < y[i] ? lo1 : y[i]; hi1 = hi1 > y[i] ? hi1 : y[i];
        lo2 = lo2 < z[i] ? lo2 : z[i]; hi2 = hi2 > z[i] ? hi2 : z[i];
    }
    box3 b = {{lo0, lo1, lo2}, {0, 0, 0}};
    double hi[3] = {hi0, hi1, hi2};
    for (int a = 0; a < 3; a++)
        b.scale[a] = hi[a] > b.lo[a] ? 2097151.0 / (hi[a] - b.lo[a]) : 0.0;
    int64_t nmax = nn > ns ? nn : ns;
    uint64_t *key = malloc(sizeof(uint64_t) * (size_t)(nmax > 0 ? nmax : 1));
    if (!key)
        return CT_ERR_NOMEM;
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < nn; i++) {
        key[i] = morton(&b, x[i], y[i], z[i]);
        node_old[i] = i;
    }
    int rc = ctd_radix_sort(key, node_old, nn);
#pragma omp parallel for schedule(static)
    for (ct_idx s = 0; s < ns; s++) {
        ct_idx v[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
        double c[3] = {0, 0, 0};
        for (int k = 0; k < 4; k++) {
            c[0] += 0.25 * x[v[k]];
            c[1] += 0.25 * y[v[k]];
            c[2] += 0.25 * z[v[k]];
        }
        key[s] = morton(&b, c[0], c[1], c[2]);
        seg_old[s] = s;
    }
    if (rc == CT_OK)
        rc = ctd_radix_sort(key, seg_old, ns);
    free(key);
    return rc;
}

/* The sorted list of new[old[k]] over a list of k (via marks). */
static int remap_sorted(ct_idx *list, ct_idx n, const ct_idx *new_of_old, ct_idx range)
{
    unsigned char *mark = calloc((size_t)range + 1, 1);
    if (!mark)
        return CT_ERR_NOMEM;
    for (ct_idx k = 0; k < n; k++)
        mark[new_of_old[list[k]]] = 1;
    ct_idx p = 0;
    for (ct_idx i = 0; i < range; i++)
        if (mark[i])
            list[p++] = i;
    free(mark);
    return CT_OK;
}

int ctd_case_renumber(ctd_case *c, ctd_numbering num, uint64_t seed)
{
    if (!c || num < CTD_NUM_NATURAL || num > CTD_NUM_SFC)
        return CT_ERR_ARG;
    if (num == CTD_NUM_NATURAL)
        return CT_OK;
    ct_mesh *m = &c->mesh;
    ct_idx nn = m->nodes.n, ns = m->nseg;
    int64_t big = nn > ns ? nn : ns;
    ct_idx *node_old = malloc(sizeof(ct_idx) * ((size_t)nn + 1));
    ct_idx *node_new = malloc(sizeof(ct_idx) * ((size_t)nn + 1));
    ct_idx *seg_old = malloc(sizeof(ct_idx) * ((size_t)ns + 1));
    ct_idx *seg_new = malloc(sizeof(ct_idx) * ((size_t)ns + 1));
    ct_real *tmp = malloc(sizeof(ct_real) * ((size_t)big + 1));
    ct_idx *itmp = malloc(sizeof(ct_idx) * ((size_t)big + 1));
    int rc = CT_ERR_NOMEM;
    if (!node_old || !node_new || !seg_old || !seg_new || !tmp || !itmp)
        goto done;
    if (num == CTD_NUM_SHUFFLED) {
        shuffle(node_old, nn, seed ^ 0x6e6f646573ULL);
        shuffle(seg_old, ns, seed ^ 0x7365676d656e7473ULL);
        rc = CT_OK;
    } else {
        rc = sfc_order(m, node_old, seg_old);
    }
    if (rc != CT_OK)
        goto done;
#pragma omp parallel for schedule(static)
    for (ct_idx i = 0; i < nn; i++)
        node_new[node_old[i]] = i;
#pragma omp parallel for schedule(static)
    for (ct_idx s = 0; s < ns; s++)
        seg_new[seg_old[s]] = s;
    /* Gather every node field into its new place. */
    ct_real *field[10] = {m->nodes.x,  m->nodes.y,  m->nodes.z,  m->nodes.vx, m->nodes.vy,
                          m->nodes.vz, m->nodes.fx, m->nodes.fy, m->nodes.fz, m->nodes.m};
    for (int f = 0; f < 10; f++) {
        ct_real *a = field[f];
#pragma omp parallel for schedule(static)
        for (ct_idx i = 0; i < nn; i++)
            tmp[i] = a[node_old[i]];
        memcpy(a, tmp, sizeof(ct_real) * (size_t)nn);
    }
    ct_idx *conn[4] = {m->n1, m->n2, m->n3, m->n4};
    for (int f = 0; f < 4; f++) {
        ct_idx *a = conn[f];
#pragma omp parallel for schedule(static)
        for (ct_idx s = 0; s < ns; s++)
            itmp[s] = node_new[a[seg_old[s]]];
        memcpy(a, itmp, sizeof(ct_idx) * (size_t)ns);
    }
    rc = remap_sorted(c->main.seg, c->main.n, seg_new, ns);
    if (rc == CT_OK)
        rc = remap_sorted(c->sec.node, c->sec.n, node_new, nn);
    /* The topology, if any, is stale. */
    if (rc == CT_OK && m->node_seg_off)
        rc = ct_mesh_build_topology(m, NULL);
done:
    free(node_old);
    free(node_new);
    free(seg_old);
    free(seg_new);
    free(tmp);
    free(itmp);
    return rc;
}
