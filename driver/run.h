/*
 * run.h -- the `contact run` command (prefix ctd_).
 *
 *   contact run SCENE [--out DIR] [--threads N] [--search ALGO] [--end T]
 *                     [--dt-scale S] [--refine N] [--cycle-limit N] [--quiet]
 *
 * Loads the scene, builds the model and its interfaces, runs the solver
 * and prints the report. Exit codes: 0 success, 1 bad usage, 2 bad input
 * (scene, model or interfaces), 4 the run went unstable, 5 an output file
 * could not be written (or the output directory is unusable, or memory ran
 * out).
 */
#ifndef CTD_RUN_H
#define CTD_RUN_H

/* argv[0] is SCENE or an option (the words after `run`). */
int ctd_run_main(int argc, char **argv);

/*
 * `contact check SCENE`: everything `run` does before its time loop (the
 * scene, the model, the interfaces, the loads) and its first cycle's
 * forces and stable step, with every check of a run (finite forces, the
 * contact stiffness, the cycle limit), writing nothing. Prints on stdout
 * "SCENE: ok: ..." (ctd_scene_print_summary), a line with the first
 * time step and the cycles the run would need, one line per interface
 * (its pairs in contact at t = 0 and its stable step) and the initial
 * penetrations (the nodes within their gap at t = 0, the deepest one);
 * on failure, the errors on stderr. Returns the exit code a run would return: 0 valid, 2 bad
 * input, 4 the first cycle is not finite, 5 an output directory the run
 * could not create or write (out, or else the scene's output.dir; checked
 * with nothing created) or no memory. file_only: read and validate the
 * file only (seconds for a scene of 10^9 nodes, whose counts come from
 * formulas) and print the first line.
 */
int ctd_check_main(const char *scene, int file_only, const char *out);

/* `contact check` from its command line (the words after `check`): the
 * options of ctd_check_main and those of `run` that change what the check
 * computes (--search, --end, --dt-scale, --refine, --cycle-limit), so that
 * it answers for the run those options would make. Returns the exit code. */
int ctd_check_cli(int argc, char **argv);

#endif
