/*
 * bench_topology.h -- hwloc topology report, OpenMP thread binding and
 * first-touch allocation for the benchmarks.
 *
 * Binding policies (CT_BENCH_BIND=compact|spread|none, or --bind=...):
 *  - compact: thread i on the i-th processing unit in hwloc's logical
 *    order, so threads fill the hardware threads of one core, then the next
 *    core, then the next package (shares caches, halves bandwidth per core);
 *  - spread: the threads are distributed evenly over the tree (hwloc_distrib:
 *    packages first, then cores), one processing unit each (most cache and
 *    bandwidth per thread);
 *  - none: the threads are left where the OpenMP runtime puts them
 *    (OMP_PROC_BIND / OMP_PLACES then apply).
 * The default is spread.
 */
#ifndef BENCH_TOPOLOGY_H
#define BENCH_TOPOLOGY_H

#include <stddef.h>
#include <stdio.h>

#include "contact.h"

typedef enum ctb_bind_policy {
    CTB_BIND_NONE = 0,
    CTB_BIND_COMPACT,
    CTB_BIND_SPREAD
} ctb_bind_policy;

/* Load the machine topology (once; later calls do nothing). 0 on success,
 * -1 when hwloc cannot load it (binding then does nothing). */
int ctb_topology_open(void);
void ctb_topology_close(void);

/* "none", "compact", "spread", and the inverse (-1 when unknown). */
const char *ctb_bind_name(ctb_bind_policy p);
int ctb_bind_from_name(const char *name);

/* The policy named by CT_BENCH_BIND, or spread when it is unset; -1 when
 * it names no policy. */
int ctb_bind_from_env(void);

/* Counts (packages, NUMA nodes, cores, processing units), each cache level
 * (size, count, processing units sharing one) and each NUMA node's memory,
 * one line per item, each prefixed with `prefix`. */
void ctb_topology_print(FILE *f, const char *prefix);

/* The same as one line ("packages=1 numa=1 cores=2 pus=2 L1d=48KiBx2 ...")
 * in buf; returns buf. */
const char *ctb_topology_line(char *buf, size_t len);

/*
 * Set the OpenMP thread count to nthreads and bind the threads of a team
 * of that size by policy p (each thread to one processing unit). Describes
 * the placement as "t0:PU0 t1:PU1" (the PUs the threads run on afterwards,
 * logical indices) in desc when desc != NULL. Returns 0, or -1 when a
 * binding failed (desc then says which). With CTB_BIND_NONE only the
 * thread count is set.
 */
int ctb_bind_threads(ctb_bind_policy p, int nthreads, char *desc, size_t len);

/* Allocate count elements of size bytes, 64-byte aligned and padded like
 * ct_calloc, and touch (zero) the pages from the OpenMP threads of the
 * current team size with a static schedule, so each page lands on the NUMA
 * node of the thread whose static block of a parallel loop uses it. Free
 * with ctb_free. NULL on failure. */
void *ctb_first_touch_alloc(size_t count, size_t size);
void ctb_free(void *p);

/* First-touch copies (the copy loop is the static parallel loop). */
ct_real *ctb_first_touch_copy_real(const ct_real *src, size_t n);
ct_idx *ctb_first_touch_copy_idx(const ct_idx *src, size_t n);

#endif /* BENCH_TOPOLOGY_H */
