/*
 * provenance.h -- build provenance and machine summary printed by every
 * program that prints results (driver, benchmarks).
 */
#ifndef CTD_PROVENANCE_H
#define CTD_PROVENANCE_H

#include <stddef.h>
#include <stdio.h>

/* One line: "packages=1 cores=2 pus=2 numa=1 L1d=48KiB L2=2MiB L3=32MiB"
 * (from hwloc), written into buf. Returns buf. */
const char *ctd_machine_summary(char *buf, size_t len);

/* Print "# build: <ct_build_info()>", "# machine: <summary>" and
 * "# threads: N" lines, each prefixed with `prefix`. */
void ctd_print_provenance(FILE *f, const char *prefix);

#endif
