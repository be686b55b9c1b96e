/*
 * bench_topology.c -- hwloc topology report, OpenMP thread binding and
 * first-touch allocation (see bench_topology.h).
 */
#include "bench_topology.h"

#include <hwloc.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

static hwloc_topology_t topo;
static int topo_loaded;

int ctb_topology_open(void)
{
    if (topo_loaded)
        return 0;
    if (hwloc_topology_init(&topo) != 0)
        return -1;
    if (hwloc_topology_load(topo) != 0) {
        hwloc_topology_destroy(topo);
        return -1;
    }
    topo_loaded = 1;
    return 0;
}

void ctb_topology_close(void)
{
    if (topo_loaded)
        hwloc_topology_destroy(topo);
    topo_loaded = 0;
}

static const char *const bind_names[] = {"none", "compact", "spread"};

const char *ctb_bind_name(ctb_bind_policy p)
{
    return (p >= CTB_BIND_NONE && p <= CTB_BIND_SPREAD) ? bind_names[p] : "unknown";
}

int ctb_bind_from_name(const char *name)
{
    for (int k = 0; name && k < 3; k++)
        if (strcmp(name, bind_names[k]) == 0)
            return k;
    return -1;
}

int ctb_bind_from_env(void)
{
    const char *e = getenv("CT_BENCH_BIND");
    if (!e || !*e)
        return CTB_BIND_SPREAD;
    return ctb_bind_from_name(e);
}

/* Bytes as "48KiB" or "2MiB" (exact multiples only get the larger unit). */
static void fmt_size(char *b, size_t n, unsigned long long v)
{
    if (v >= (1ull << 30) && v % (1ull << 30) == 0)
        snprintf(b, n, "%lluGiB", v >> 30);
    else if (v >= (1ull << 20) && v % (1ull << 20) == 0)
        snprintf(b, n, "%lluMiB", v >> 20);
    else if (v >= (1ull << 10))
        snprintf(b, n, "%lluKiB", v >> 10);
    else
        snprintf(b, n, "%lluB", v);
}

static const hwloc_obj_type_t cache_types[] = {HWLOC_OBJ_L1CACHE, HWLOC_OBJ_L2CACHE,
                                               HWLOC_OBJ_L3CACHE, HWLOC_OBJ_L4CACHE};
static const char *const cache_names[] = {"L1d", "L2", "L3", "L4"};

const char *ctb_topology_line(char *buf, size_t len)
{
    if (len == 0)
        return buf;
    buf[0] = '\0';
    if (ctb_topology_open() != 0) {
        snprintf(buf, len, "hwloc unavailable");
        return buf;
    }
    size_t off = (size_t)snprintf(
        buf, len, "packages=%d numa=%d cores=%d pus=%d",
        hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PACKAGE),
        hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_NUMANODE),
        hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_CORE), hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PU));
    for (int k = 0; k < 4 && off < len; k++) {
        int n = hwloc_get_nbobjs_by_type(topo, cache_types[k]);
        hwloc_obj_t o = hwloc_get_obj_by_type(topo, cache_types[k], 0);
        if (n <= 0 || !o || !o->attr)
            continue;
        char b[32];
        fmt_size(b, sizeof b, (unsigned long long)o->attr->cache.size);
        off += (size_t)snprintf(buf + off, len - off, " %s=%sx%d", cache_names[k], b, n);
    }
    return buf;
}

void ctb_topology_print(FILE *f, const char *prefix)
{
    if (ctb_topology_open() != 0) {
        fprintf(f, "%stopology: hwloc unavailable\n", prefix);
        return;
    }
    int npu = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PU);
    fprintf(f, "%stopology: packages=%d numa=%d cores=%d pus=%d\n", prefix,
            hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PACKAGE),
            hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_NUMANODE),
            hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_CORE), npu);
    for (int k = 0; k < 4; k++) {
        int n = hwloc_get_nbobjs_by_type(topo, cache_types[k]);
        hwloc_obj_t o = hwloc_get_obj_by_type(topo, cache_types[k], 0);
        if (n <= 0 || !o || !o->attr)
            continue;
        char b[32];
        fmt_size(b, sizeof b, (unsigned long long)o->attr->cache.size);
        int share = o->cpuset ? hwloc_bitmap_weight(o->cpuset) : 0;
        fprintf(f, "%scache: %s %s x%d, line %uB, shared by %d PU%s\n", prefix, cache_names[k], b, n,
                o->attr->cache.linesize, share, share == 1 ? "" : "s");
    }
    int nn = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_NUMANODE);
    for (int k = 0; k < nn; k++) {
        hwloc_obj_t o = hwloc_get_obj_by_type(topo, HWLOC_OBJ_NUMANODE, (unsigned)k);
        char b[32], cpus[128] = "";
        fmt_size(b, sizeof b, (unsigned long long)o->attr->numanode.local_memory);
        if (o->cpuset)
            hwloc_bitmap_list_snprintf(cpus, sizeof cpus, o->cpuset);
        fprintf(f, "%snuma: node %u, %s, PUs (OS) %s\n", prefix, o->os_index, b, cpus);
    }
}

/* Logical index of the PU a thread's single-PU cpuset names, or -1. */
static int pu_logical(hwloc_const_cpuset_t set)
{
    int os = hwloc_bitmap_first(set);
    if (os < 0)
        return -1;
    hwloc_obj_t pu = hwloc_get_pu_obj_by_os_index(topo, (unsigned)os);
    return pu ? (int)pu->logical_index : -1;
}

int ctb_bind_threads(ctb_bind_policy p, int nthreads, char *desc, size_t len)
{
    if (desc && len)
        desc[0] = '\0';
    if (nthreads < 1)
        nthreads = 1;
#ifdef _OPENMP
    omp_set_num_threads(nthreads);
#endif
    if (p == CTB_BIND_NONE)
        return 0;
    if (ctb_topology_open() != 0) {
        if (desc && len)
            snprintf(desc, len, "hwloc unavailable: not bound");
        return -1;
    }
    int npu = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PU);
    if (npu < 1)
        return -1;
    hwloc_cpuset_t *sets = calloc((size_t)nthreads, sizeof *sets);
    int *where = calloc((size_t)nthreads, sizeof *where);
    if (!sets || !where) {
        free(sets);
        free(where);
        return -1;
    }
    int fail = 0;
    for (int t = 0; t < nthreads; t++) {
        if (p == CTB_BIND_COMPACT) {
            hwloc_obj_t pu = hwloc_get_obj_by_type(topo, HWLOC_OBJ_PU, (unsigned)(t % npu));
            sets[t] = pu ? hwloc_bitmap_dup(pu->cpuset) : NULL;
        } else {
            sets[t] = hwloc_bitmap_alloc();
        }
        if (!sets[t])
            fail = 1;
    }
    if (!fail && p == CTB_BIND_SPREAD) {
        hwloc_obj_t root = hwloc_get_root_obj(topo);
        if (hwloc_distrib(topo, &root, 1, sets, (unsigned)nthreads, INT_MAX, 0) != 0)
            fail = 1;
        for (int t = 0; !fail && t < nthreads; t++)
            hwloc_bitmap_singlify(sets[t]);
    }
    if (!fail) {
#ifdef _OPENMP
#pragma omp parallel num_threads(nthreads) reduction(+ : fail)
        {
            int t = omp_get_thread_num();
#else
        {
            int t = 0;
#endif
            hwloc_cpuset_t now = hwloc_bitmap_alloc();
            if (hwloc_set_cpubind(topo, sets[t], HWLOC_CPUBIND_THREAD) != 0 || !now ||
                hwloc_get_cpubind(topo, now, HWLOC_CPUBIND_THREAD) != 0)
                fail += 1;
            where[t] = now ? pu_logical(now) : -1;
            hwloc_bitmap_free(now);
        }
    }
    if (desc && len) {
        size_t off = 0;
        for (int t = 0; t < nthreads && off < len; t++)
            off += (size_t)snprintf(desc + off, len - off, "%st%d:PU%d", t ? " " : "", t,
                                    where[t]);
        if (fail && off < len)
            snprintf(desc + off, len - off, " (binding failed)");
    }
    for (int t = 0; t < nthreads; t++)
        hwloc_bitmap_free(sets[t]);
    free(sets);
    free(where);
    return fail ? -1 : 0;
}

void *ctb_first_touch_alloc(size_t count, size_t size)
{
    if (size == 0 || count > (SIZE_MAX - CT_PAD) / size)
        return NULL;
    size_t padded = (count + CT_PAD - 1) / CT_PAD * CT_PAD;
    size_t bytes = padded * size;
    if (bytes == 0)
        bytes = CT_ALIGN;
    bytes = (bytes + CT_ALIGN - 1) / CT_ALIGN * CT_ALIGN;
    void *p = NULL;
    if (posix_memalign(&p, CT_ALIGN, bytes) != 0)
        return NULL;
    /* Touch in 64-byte lines so each page is first written by the thread
     * whose static block holds it. */
    unsigned char *b = p;
    int64_t nline = (int64_t)(bytes / CT_ALIGN);
#pragma omp parallel for schedule(static)
    for (int64_t k = 0; k < nline; k++)
        memset(b + k * CT_ALIGN, 0, CT_ALIGN);
    return p;
}

void ctb_free(void *p) { free(p); }

ct_real *ctb_first_touch_copy_real(const ct_real *src, size_t n)
{
    ct_real *d = ctb_first_touch_alloc(n, sizeof *d);
    if (!d)
        return NULL;
    int64_t m = (int64_t)n;
#pragma omp parallel for schedule(static)
    for (int64_t k = 0; k < m; k++)
        d[k] = src[k];
    return d;
}

ct_idx *ctb_first_touch_copy_idx(const ct_idx *src, size_t n)
{
    ct_idx *d = ctb_first_touch_alloc(n, sizeof *d);
    if (!d)
        return NULL;
    int64_t m = (int64_t)n;
#pragma omp parallel for schedule(static)
    for (int64_t k = 0; k < m; k++)
        d[k] = src[k];
    return d;
}
