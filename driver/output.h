/*
 * output.h -- what a run writes for a user to look at (prefix ctd_):
 *
 *   DIR/<base>_NNNNNN.vtu   VTK XML UnstructuredGrid per output step, its
 *                           arrays raw binary in an appended block (the
 *                           default of a scene) or ASCII text
 *   DIR/<base>.pvd          the ParaView collection indexing them by time
 *                           (rewritten after every step, so it is valid
 *                           whenever the run stops)
 *   DIR/history.csv         one row per output step (ctd_history_row)
 *   DIR/summary.json        the run summary with provenance and timers
 *   DIR/energies.gp, .png   gnuplot script and plot of the energies
 *
 * Every function returns CT_OK or a negative CT_ERR_* code (CT_ERR_ARG for
 * an I/O failure) and then ctd_output_error() says what failed, with the
 * path and strerror(errno). Nothing is printed.
 */
#ifndef CTD_OUTPUT_H
#define CTD_OUTPUT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "contact.h"

#ifdef __cplusplus
extern "C" {
#endif

/* VTK cell types used. */
enum { CTD_VTK_LINE = 3, CTD_VTK_TRIANGLE = 5, CTD_VTK_QUAD = 9, CTD_VTK_HEXAHEDRON = 12 };

/*
 * The state one VTU file shows. Cells are in VTK's layout: cell c has type
 * cell_type[c] and nodes cell_node[cell_off[c] .. cell_off[c+1]-1] (0-based).
 * Optional arrays may be NULL (the field is then not written).
 */
typedef struct ctd_out_mesh {
    ct_idx nnode;
    const ct_real *x, *y, *z;          /* current positions (required) */
    const ct_real *x0, *y0, *z0;       /* initial positions: "displacement" */
    const ct_real *vx, *vy, *vz;       /* "velocity" */
    const ct_real *fcx, *fcy, *fcz;    /* "contact_force" */
    const ct_real *pen;                /* "penetration" (per node) */
    const int32_t *node_part;          /* "part_id" (point data) */
    const int32_t *node_active;        /* "active_pairs" (per node) */
    ct_idx ncell;
    const uint8_t *cell_type;          /* CTD_VTK_* */
    const ct_idx *cell_off;            /* [ncell + 1] */
    const ct_idx *cell_node;
    const int32_t *cell_part;          /* "part_id" (cell data) */
} ctd_out_mesh;

/* How a VTU file holds its arrays: as text ("%.9g" reals), or as the
 * machine's own bytes in one appended block (encoding "raw": every array is
 * an 8-byte byte count and its values, reals exactly as computed, in the
 * precision of the build). ParaView and VTK read both; the raw form is
 * several times smaller and faster to write. */
enum { CTD_VTU_ASCII = 0, CTD_VTU_RAW = 1 };

/* Write one VTU file (no output directory needed: the "last good state"),
 * in ASCII (ctd_vtu_write) or in the given format. */
int ctd_vtu_write(const char *path, const ctd_out_mesh *m, char *err, size_t errlen);
int ctd_vtu_write_as(const char *path, const ctd_out_mesh *m, int format, char *err,
                     size_t errlen);

typedef struct ctd_output ctd_output;

typedef struct ctd_output_opts {
    const char *dir;   /* created if missing, with its missing parents */
    const char *base;  /* file name stem of the VTU series (NULL: "state") */
    int vtu, csv;      /* which series to write */
    int vtu_format;    /* CTD_VTU_ASCII (0) or CTD_VTU_RAW */
} ctd_output_opts;

/*
 * Open an output directory: create it when missing, with its missing
 * parents (as mkdir -p), then prove it writable by writing and removing a
 * probe file, and check that at least 1 MiB is free. On failure *out is
 * NULL and err holds e.g. "cannot create output directory 'res/run1':
 * Not a directory" (res is a file).
 */
int ctd_output_open(ctd_output **out, const ctd_output_opts *opts, char *err, size_t errlen);

/*
 * What ctd_output_open would find, creating and writing nothing (for
 * `contact check`): dir exists and is a writable directory, or is missing
 * and its nearest existing ancestor is one; and the disk has 1 MiB free.
 * CT_OK, or an error with the messages of ctd_output_open (CT_ERR_NOMEM:
 * no memory).
 */
int ctd_output_check_dir(const char *dir, char *err, size_t errlen);
void ctd_output_close(ctd_output *o);
const char *ctd_output_error(const ctd_output *o);
const char *ctd_output_dir(const ctd_output *o);

/* Write step `time` as the next VTU file and update the PVD collection
 * (nothing when vtu is off). */
int ctd_output_vtu(ctd_output *o, double time, const ctd_out_mesh *m);

/* ---- Time history (CSV) ---------------------------------------------------- */

/* One row; the per-interface arrays hold `ninterface` values (from
 * ctd_output_csv_begin). */
typedef struct ctd_history_row {
    int64_t cycle;
    double time, dt;
    double kinetic, internal, contact, damping, friction, external_work;
    double energy_error;       /* (E_total - E_0 - W_ext) / max(E) */
    const double *if_force;    /* total normal contact force magnitude */
    const int64_t *if_active;  /* active pairs */
    const int64_t *if_resorts; /* re-sorts so far */
} ctd_history_row;

/* Write the header: cycle,time,dt,kinetic,internal,contact,damping,friction,
 * external_work,energy_error, then <name>_force,<name>_active,<name>_resorts
 * per interface (names sanitised to [A-Za-z0-9_-]). */
int ctd_output_csv_begin(ctd_output *o, int ninterface, const char *const *names);
int ctd_output_csv_row(ctd_output *o, const ctd_history_row *r);

/* ---- Run summary (JSON) ------------------------------------------------------ */

typedef struct ctd_if_summary {
    const char *name;
    int type;
    const char *search;
    int64_t max_active, resorts;
    double margin;  /* the re-sort margin in use (0: none chosen) */
    double max_force;
    int64_t memory; /* bytes held at the end (the peak), -1: unknown */
} ctd_if_summary;

typedef struct ctd_run_summary {
    const char *scene, *title;
    const char *status;        /* "ok", "unstable", "error", "out of memory" */
    int exit_code;
    const char *message;       /* may be NULL */
    int threads;
    int64_t cycles, nodes, elements, segments, output_steps;
    double end_time, time_reached, wall_time;
    double energy_error, energy_error_max;
    double energy_error_contact; /* its contact part (ctd_energies.contact_error) */
    /* Timer split, seconds. */
    double t_search, t_narrow, t_force, t_assembly, t_elements, t_other;
    int ninterface;
    const ctd_if_summary *interfaces;
} ctd_run_summary;

/* Write DIR/summary.json: the fields above plus "provenance": {"build":
 * ct_build_info(), "machine": ctd_machine_summary(), "host", "date"}. */
int ctd_output_summary(ctd_output *o, const ctd_run_summary *s);

/* JSON string escaping into f (quotes included). */
void ctd_json_string(FILE *f, const char *s);

/* ---- Plot ------------------------------------------------------------------- */

/* Write DIR/energies.gp (energies of DIR/history.csv against time) and run
 * gnuplot on it to make DIR/energies.png. Returns 0 when the PNG was made,
 * 1 when gnuplot is not installed (msg says so; the script is still
 * written), a negative CT_ERR_* code on failure (msg says why). */
int ctd_output_plot_energies(const char *dir, char *msg, size_t msglen);

#ifdef __cplusplus
}
#endif

#endif /* CTD_OUTPUT_H */
