/*
 * provenance.c -- build provenance and the hwloc machine summary.
 */
#include "provenance.h"

#include <hwloc.h>
#include <string.h>

#include "contact.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static void fmt_bytes(char *b, size_t n, unsigned long long v)
{
    if (v >= (1ull << 20) && v % (1ull << 20) == 0)
        snprintf(b, n, "%lluMiB", v >> 20);
    else
        snprintf(b, n, "%lluKiB", v >> 10);
}

const char *ctd_machine_summary(char *buf, size_t len)
{
    hwloc_topology_t topo;
    if (hwloc_topology_init(&topo) != 0 || hwloc_topology_load(topo) != 0) {
        snprintf(buf, len, "hwloc unavailable");
        return buf;
    }
    int np = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PACKAGE);
    int nc = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_CORE);
    int npu = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PU);
    int nn = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_NUMANODE);
    size_t off = (size_t)snprintf(buf, len, "packages=%d cores=%d pus=%d numa=%d", np, nc, npu, nn);
    const hwloc_obj_type_t caches[] = {HWLOC_OBJ_L1CACHE, HWLOC_OBJ_L2CACHE, HWLOC_OBJ_L3CACHE};
    const char *names[] = {"L1d", "L2", "L3"};
    for (int k = 0; k < 3 && off < len; k++) {
        hwloc_obj_t o = hwloc_get_obj_by_type(topo, caches[k], 0);
        if (!o || !o->attr)
            continue;
        char b[32];
        fmt_bytes(b, sizeof b, (unsigned long long)o->attr->cache.size);
        off += (size_t)snprintf(buf + off, len - off, " %s=%s", names[k], b);
    }
    hwloc_obj_t root = hwloc_get_root_obj(topo);
    const char *cpu = root ? hwloc_obj_get_info_by_name(root, "CPUModel") : NULL;
    if (!cpu) {
        hwloc_obj_t p = hwloc_get_obj_by_type(topo, HWLOC_OBJ_PACKAGE, 0);
        cpu = p ? hwloc_obj_get_info_by_name(p, "CPUModel") : NULL;
    }
    if (cpu && off < len)
        snprintf(buf + off, len - off, " cpu=\"%s\"", cpu);
    hwloc_topology_destroy(topo);
    return buf;
}

void ctd_print_provenance(FILE *f, const char *prefix)
{
    char m[512];
    int nt = 1;
#ifdef _OPENMP
    nt = omp_get_max_threads();
#endif
    fprintf(f, "%sbuild: %s\n", prefix, ct_build_info());
    fprintf(f, "%smachine: %s\n", prefix, ctd_machine_summary(m, sizeof m));
    fprintf(f, "%sthreads: %d\n", prefix, nt);
}
