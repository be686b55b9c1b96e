/*
 * bench_peers.h -- the peer benchmarks (bench_peers.c): nanoflann, CGAL and
 * Bullet answering our search's query on the same meshes, in the same run,
 * their pair sets checked against ours.
 */
#ifndef BENCH_PEERS_H
#define BENCH_PEERS_H

#include "bench_search.h"

/* Register the peer benchmarks (names peer/<family>/<peer>/t<threads>/
 * <nodes>; tuning variants peer/<family>/<peer>@<setting>/t<threads>/
 * <nodes> with CT_BENCH_FULL or CT_BENCH_PEER_TUNE=1). Returns how many, or
 * -1 on allocation failure. The configuration is copied. */
int ctb_peers_register(const ctb_search_config *c);

/* Free the cached mesh and the registrations (after gb_run). Returns the
 * number of peer runs whose pair set differed from our search's or that
 * failed (0: all agreed); the program's exit status must then be non-zero. */
int ctb_peers_cleanup(void);

/* The verification mode: when argv holds --verify-peers, run every peer
 * (each setting, 1 and all threads) on small meshes of several families
 * (plates, self contact, graded...) with both filters, compare each pair
 * set with the direct search's, print one line per run and return the
 * exit status (0: all equal, 1: a mismatch or a failure). Returns -1 when
 * the flag is absent. */
int ctb_peers_verify_main(int argc, char **argv);

#endif /* BENCH_PEERS_H */
