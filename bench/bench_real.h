/*
 * bench_real.h -- registration of the real-mesh search benchmarks
 * (bench_real.c): the four searches on Radioss decks read through the
 * driver's importer.
 */
#ifndef BENCH_REAL_H
#define BENCH_REAL_H

#include "bench_search.h"

/*
 * Register the benchmarks on the decks $CT_SHARED/data/radioss/ *.rad
 * (CT_SHARED unset: ../shared) and on the deck named by CT_BENCH_MESH, when
 * set. Prints one line per deck found (or why there is none). Returns how
 * many benchmarks were registered, or -1 on allocation failure. The
 * configuration is copied.
 */
int ctb_real_register(const ctb_search_config *c);

/* Free the cached deck and the registrations (after gb_run). */
void ctb_real_cleanup(void);

#endif /* BENCH_REAL_H */
