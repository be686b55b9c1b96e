/*
 * run.h -- the `contact run` command (prefix ctd_).
 *
 *   contact run SCENE [--out DIR] [--threads N] [--search ALGO] [--end T]
 *                     [--dt-scale S] [--quiet]
 *
 * Loads the scene, builds the model and its interfaces, runs the solver
 * and prints the report. Exit codes: 0 success, 1 bad usage, 2 bad input
 * (scene, model or interfaces), 4 the run went unstable, 5 an output file
 * could not be written (or the output directory is unusable).
 */
#ifndef CTD_RUN_H
#define CTD_RUN_H

/* argv[0] is SCENE or an option (the words after `run`). */
int ctd_run_main(int argc, char **argv);

#endif
