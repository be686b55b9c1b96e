/*
 * bench_trade.h -- the speed/accuracy trade benchmarks (bench_trade.c,
 * issue 5 item 7, DESIGN.md section 10): for each knob, one benchmark per
 * setting with a cost counter and an accuracy counter.
 *
 * Names: trade/<knob>/<setting> (Google Benchmark appends "/real_time").
 * Knobs: search, filter, margin, quad, precision, assembly, stiffness,
 * safety. Every run sets the counters
 *   cost      the knob's cost figure (its unit is in the label),
 *   accuracy  the knob's accuracy figure (its meaning is in the label),
 *   x_<name>  further figures of the same run,
 * and the label "knob=<knob> setting=<value>; cost: <what>; accuracy:
 * <what>; <case>". bench/report.py turns them into the "Speed/accuracy
 * trade" table.
 */
#ifndef BENCH_TRADE_H
#define BENCH_TRADE_H

#include "bench_search.h"

/* Register the trade benchmarks (the configuration is copied); returns how
 * many, or -1 on allocation failure. */
int ctb_trade_register(const ctb_search_config *c);

/* Free the cached cases and the registrations (after gb_run). */
void ctb_trade_cleanup(void);

/*
 * `bench --dump-narrow FILE`: when argv holds --dump-narrow FILE (or
 * --dump-narrow=FILE), write the narrow-phase results of the fixed
 * precision case (crumpled sheet, ~20000 nodes, seed 12345, bucket search
 * with gap 0.3 h + margin 0.2 h, Newton projection, two-sided) to FILE, one
 * line per candidate pair, and return the exit status (0 on success).
 * Returns -1 when the option is absent. bench/trade_precision.py compares
 * the dumps of a double and a single build.
 */
int ctb_trade_dump_main(int argc, char **argv);

#endif /* BENCH_TRADE_H */
