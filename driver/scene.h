/*
 * scene.h -- scene files (prefix ctd_): a YAML description of one run, read
 * through libcyaml with a schema, then checked. This comment is the users'
 * reference for the format.
 *
 * ---- Example --------------------------------------------------------------
 *
 *   title: ball on plate
 *   end_time: 0.01                  # required, > 0 (seconds)
 *   refine: 1                       # optional, >= 1: multiplies every `cells`
 *   output: {dir: out/ball, every: 1.0e-4, vtu: true, csv: true}
 *   solver: {dt_scale: 0.9, threads: 0}
 *   mesh:
 *     - generate: {kind: block, part: 1, cells: [20, 20, 2], size: [0.2, 0.2, 0.02]}
 *     - generate: {kind: ball, part: 2, cells: [6], radius: 0.03, origin: [0.1, 0.1, 0.06]}
 *     - import: {file: decks/bolster.rad}
 *   parts:
 *     - {id: 1, name: plate, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}
 *     - {id: 2, name: ball, element: brick, material: {E: 2.1e11, nu: 0.3, rho: 7800}}
 *   rigid_bodies: [{id: 1, part: 3}]
 *   boundary:
 *     - {kind: fixed, nodes: {part: 1, where: "z < 0.001"}}
 *     - {kind: initial_velocity, nodes: {part: 2}, value: [0, 0, -5]}
 *     - {kind: gravity, value: [0, 0, -9.81]}
 *   interfaces:
 *     - {type: 24, name: ball-plate, main: {part: 1}, secondary: {part: 2},
 *        Istf: 2, Stfac: 1.0, gap: 0.001, Fric: 0.2, search: bucket}
 *     - {type: 6, main: {part: 3}, secondary: {part: 4}, curve: [[0, 0], [0.01, 1000]]}
 *
 * Keys are case-sensitive; an unknown key is an error (typos are caught).
 * Flow {..} and block style may be mixed freely. A file holds one YAML
 * document. Anchors and aliases repeat a value:
 *   parts:
 *     - {id: 1, element: brick, material: &steel {E: 2.1e11, nu: 0.3, rho: 7800}}
 *     - {id: 2, element: brick, material: *steel}
 * An alias names an anchor on a node that ends before it (so no cycles),
 * and the aliases of a file copy at most 100000 YAML nodes in all. Merge
 * keys (`<<: *a`) are not supported. An error inside an aliased value
 * names the line where the value is written (the anchor's).
 *
 * ---- Top level --------------------------------------------------------------
 *   title       string, optional.
 *   end_time    number > 0, required.
 *   refine      integer >= 1, optional (1): every generated mesh's `cells`
 *               are multiplied by it, its extent kept (the folded sheet's
 *               cell size `size` divided by it): the scene's size parameter.
 *   output      optional mapping:
 *                 dir    string (default "out/<scene file name without .yaml>",
 *                        relative to the working directory; created with
 *                        its missing parents);
 *                 every  number > 0, the output interval (default end_time/100);
 *                 vtu    bool (true): VTU + PVD series (a bool is true or
 *                        false, or yes/no, on/off, in any case);
 *                 format "binary" (default) or "ascii": the VTU arrays as
 *                        raw bytes in an appended block (exact, fast to
 *                        write) or as "%.9g" text;
 *                 csv    bool (true): CSV time history.
 *   solver      optional mapping:
 *                 dt_scale  number in (0, 1] (0.9): safety factor on the
 *                           stable time step;
 *                 threads   integer >= 0 (0: OpenMP's default, OMP_NUM_THREADS
 *                           or every core, but when OMP_NUM_THREADS is not
 *                           set at most one thread per 2000 nodes: a smaller
 *                           model runs faster on fewer; `--threads N`
 *                           overrides both);
 *                 cycle_limit integer in 1 .. 1e15 (1e8): a run whose stable
 *                           step would need more cycles than this to reach
 *                           end_time stops at once with an error (exit 2)
 *                           naming the step, instead of running for days.
 *   mesh        list, required, at least one entry, each exactly one of:
 *     generate: {kind, part, cells, size, origin, radius, length, to, layers,
 *                spacing, tri}
 *       kind     required, one of (N counts nodes, "cells" before refine):
 *         plate   cells [nx, ny], size [Lx, Ly]: quads (tri: true -> two
 *                 triangles each) in the plane z = origin z; N = (nx+1)(ny+1).
 *         block   cells [nx, ny, nz], size [Lx, Ly, Lz]: bricks;
 *                 N = (nx+1)(ny+1)(nz+1).
 *         sphere  cells [n], radius: cube-sphere surface of quads centred at
 *                 origin; N = 6 n^2 + 2.
 *         ball    cells [n], radius: a block of n^3 bricks mapped onto the
 *                 ball centred at origin; N = (n+1)^3.
 *         tube    cells [nr, nl], radius, length: quads of a tube along z from
 *                 origin; N = nr (nl+1).
 *         folded  cells [nflat, nw], size [h], layers, spacing: accordion
 *                 sheet (meshgen.h ctd_folded) of cells of size h / refine;
 *                 N as ctd_folded makes it.
 *         net     cells [nx, ny], size [Lx, Ly]: trusses along the grid lines
 *                 of a plate in z = origin z; N = (nx+1)(ny+1).
 *         rod     cells [n], to [x, y, z]: n trusses from origin to `to`;
 *                 N = n + 1.
 *       part     required integer: the part its elements belong to (must be
 *                listed in `parts`, with an element kind that fits: shell or
 *                rigid for plate/sphere/tube/folded, brick or rigid for
 *                block/ball, truss, spring or rigid for net/rod).
 *       origin   [x, y, z], optional ([0, 0, 0]); sizes > 0; cells >= 1.
 *     import: {file}
 *       file     a Radioss block-format deck (import_radioss.h), relative to
 *                the scene file's directory. It is read while the scene is
 *                loaded; each /PART with elements must be listed in `parts`.
 *   Node ids: an imported node keeps its deck id; a generated mesh's nodes are
 *   numbered from (largest id so far) + 1 in the generator's order. Ids must
 *   not repeat across meshes (list imports first).
 *   parts       list, required: {id (integer > 0, unique), name (string,
 *               optional), element, material: {E, nu, rho}, thickness, area,
 *               stiffness}
 *                 element    one of brick, shell, truss, spring, rigid;
 *                 E > 0, -1 < nu < 0.5, rho > 0 (all required, finite);
 *                 thickness  > 0, required for shell;
 *                 area       > 0, required for truss (cross-section);
 *                 stiffness  > 0, required for spring (axial, N/m).
 *   rigid_bodies  list, optional: {id (> 0, unique), part}: part must have
 *               element rigid. A rigid part listed in no body is a body of
 *               its own.
 *   boundary    list, optional: {kind, nodes, value, dofs}
 *                 kind   fixed | velocity | initial_velocity | gravity |
 *                        force | pressure;
 *                 nodes  a node selection (below); required except for
 *                        gravity (which acts on every node) and pressure;
 *                 value  [vx, vy, vz] (or [gx, gy, gz], or the force
 *                        [Fx, Fy, Fz] in N on EACH selected node), required
 *                        for velocity, initial_velocity, gravity, force;
 *                 dofs   fixed and velocity only: which components, a string
 *                        of x, y, z (default "xyz");
 *                 surface   pressure only, required: a surface selection
 *                        (below); each segment gets the force -pressure x its
 *                        vector area, shared equally by its corners, from the
 *                        current geometry (a follower load): a positive
 *                        pressure pushes against the segment's normal, into a
 *                        solid's outer face;
 *                 pressure  pressure only, required: a finite number (Pa);
 *                 curve  force and pressure only, optional: the load's
 *                        factor against time, [[t0, s0], [t1, s1], ...], t
 *                        strictly ascending, linear in between, constant before
 *                        the first and after the last point (default: 1 at all
 *                        times). The loads' work enters the energy balance as
 *                        external work.
 *   interfaces  list, optional, each a mapping:
 *     type       required: 3, 5, 6, 7, 11 or 24.
 *     name       string, optional (default "if<index>").
 *     main       a surface selection, required.
 *     secondary  a selection: required for 3, 5, 6; absent for 7, 11, 24
 *                means self contact on `main`.
 *     margin     number >= 0 [0: 0.2 times the mean main edge length]: the
 *                re-sort margin, in length units (not a Radioss field).
 *                The search collects the pairs within gap + margin and
 *                runs again when the nodes have moved by the margin since
 *                (ct_resort_needed): a larger margin searches less often
 *                and keeps more candidates. The contacts and the step do
 *                not change with it: every pair in contact is found with
 *                any margin, and the interface's stable step counts an
 *                open pair within 0.2 mean edges of contact plus what it
 *                can close in two steps, not every candidate (so a margin
 *                below the default counts fewer). TYPE6 searches its
 *                largest penetration plus two margins deep: there a larger
 *                margin costs more than it saves. The run's report prints
 *                the margin used.
 *     search     direct | topological | bucket | bsp (default: topological
 *                for 3 and 5, bucket otherwise). Not topological for self
 *                contact (7, and 24 without secondary): a node's closest
 *                main node is itself, it would find nothing. Type 11's
 *                edge search is direct or bucket.
 *     Radioss card fields, all optional (defaults in brackets):
 *       Istf      0, 1, 2, 3, 4, 5 or 1000 [0]: stiffness choice (TYPE24:
 *                 0 -> 2; 2 mean, 3 max, 4 min, 5 series, 1000 main only;
 *                 TYPE7/11: 1 -> Stfac is the stiffness itself).
 *       Stfac     > 0 [0.2 for 3, 5, 6; 1.0 otherwise]: stiffness scale.
 *       Stmin, Stmax  >= 0 [0, 0 = no limit]; Stmax >= Stmin when set.
 *       gap       >= 0 [0: automatic]; Gap_max_s, Gap_max_m >= 0 [0: none].
 *       Igap0, Ipen0, Ipen_max, Inacti  [0]; Ipen_max >= 0.
 *       Irem_gap  0, 1 or 2 [0, as 1]; 2 (self contact: types 7, 11, and 24
 *                 without secondary, as Radioss's TYPE25 Igap 2): each node's
 *                 (edge's) neighbours on the surface within the gap at the
 *                 start leave its contact (for a gap above half the
 *                 shortest edge; ct_exclusion in ct_search.h).
 *       VisS      >= 0 [0.05 for 7, 11; 1.0 for 24; 0 otherwise].
 *       Ifric     0..4 [0]; Fric >= 0 [0]; C1..C6 [0] (Renard, Ifric 3,
 *                 needs 0 < C5 < C6; Ifric 4 needs C2 >= 0).
 *       Ifiltr    0..3 [0]; Xfreq: Ifiltr 1 needs 0 < Xfreq <= 1, 2 needs
 *                 Xfreq >= 2 pi, 3 needs Xfreq > 0.
 *     pressure_area  main | secondary (default main; not a Radioss field):
 *                 the area the pressure of Ifric 1 and 2 divides a pair's
 *                 normal force by: the main segment's (Radioss), or the
 *                 secondary node's share of its surface segments facing the
 *                 contact (every secondary node must be on a surface
 *                 segment; not for type 11).
 *       Tstart, Tstop  >= 0 [0, 0 = never stops]; Tstop > Tstart when set.
 *       grnd_IDs  a node selection: extra secondary nodes (TYPE24).
 *       curve     TYPE6, required there: [[p0, F0], [p1, F1], ...], at least
 *                 2 points, p >= 0 strictly ascending, F >= 0.
 *   Selections (nodes, main, secondary, grnd_IDs), a mapping of:
 *     part: id | parts: [ids]   elements (surfaces) or nodes of these parts;
 *     surf: id                  a /SURF of an imported deck (surfaces only);
 *     group: id                 a /GRNOD of an imported deck (nodes only);
 *     ids: [node ids]           nodes (nodes only);
 *     where: "z < 0.001 and x >= 0"   optional filter on the initial node
 *                 positions (clauses `x|y|z <|<=|>|>= number` joined by
 *                 `and`); alone it selects among all nodes; on a surface
 *                 it keeps the segments whose nodes all satisfy it.
 *   A node selection needs at least one of these; a surface one exactly one
 *   of part, parts, surf.
 *
 * ---- Errors -----------------------------------------------------------------
 * Every message reads "FILE:LINE: FIELD: what, expected ..." with FIELD a
 * path such as interfaces[0].type, e.g.
 *   scenes/ball.yaml:12: interfaces[0].type: expected one of 3, 5, 6, 7, 11, 24, got 9
 */
#ifndef CTD_SCENE_H
#define CTD_SCENE_H

#include <stdio.h>
#include <stdbool.h>
#include <stdint.h>

#include "import_radioss.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Exit codes of `contact check` and `contact run` (solver.h has the others). */
enum { CTD_EXIT_OK = 0, CTD_EXIT_BADINPUT = 2 };

/* The default of solver.cycle_limit: the most cycles a run may need. */
#define CTD_CYCLE_LIMIT ((int64_t)100000000)

/* A parsed `where` filter: every clause must hold (axis 0..2, op one of
 * CTD_WHERE_*). */
enum { CTD_WHERE_LT = 0, CTD_WHERE_LE, CTD_WHERE_GT, CTD_WHERE_GE };
#define CTD_WHERE_MAX 6
typedef struct ctd_where {
    int n;
    int axis[CTD_WHERE_MAX];
    int op[CTD_WHERE_MAX];
    double value[CTD_WHERE_MAX];
} ctd_where;

/* 1 when the point satisfies every clause (an empty filter holds). */
int ctd_where_eval(const ctd_where *w, double x, double y, double z);

/* A selection of nodes or of surface segments. */
typedef struct ctd_scene_sel {
    int64_t part;               /* 0: none */
    int64_t *parts;             /* list of part ids */
    unsigned parts_count;
    int64_t surf, group;        /* 0: none */
    int64_t *ids;               /* node ids */
    unsigned ids_count;
    char *where_text;           /* NULL when absent */
    /* Filled by the loader. */
    ctd_where where;
    int line;
} ctd_scene_sel;

enum ctd_gen_kind {
    CTD_GEN_PLATE = 0, CTD_GEN_BLOCK, CTD_GEN_SPHERE, CTD_GEN_BALL, CTD_GEN_TUBE,
    CTD_GEN_FOLDED, CTD_GEN_NET, CTD_GEN_ROD, CTD_GEN_NKIND
};

typedef struct ctd_scene_generate {
    char *kind_name;
    int64_t part;
    int64_t *cells;            /* before refine; see `cells_eff` */
    unsigned cells_count;
    double *size;
    unsigned size_count;
    double origin[3];
    double to[3];
    double radius, length, spacing;
    int64_t layers;
    bool tri;
    /* Filled by the loader. */
    int kind;                  /* enum ctd_gen_kind */
    int64_t cells_eff[3];      /* cells times refine (unused entries 0) */
    double h_eff;              /* folded: the cell size, size[0] / refine */
} ctd_scene_generate;

typedef struct ctd_scene_import {
    char *file;                /* as written */
    /* Filled by the loader. */
    char *path;                /* resolved against the scene's directory */
    ctd_deck *deck;            /* the deck, read */
} ctd_scene_import;

typedef struct ctd_scene_mesh {
    ctd_scene_generate *generate; /* exactly one of these is non-NULL */
    ctd_scene_import *import;
    /* Filled by the loader: node ids first_id .. first_id + nnode - 1 for a
     * generated mesh (nnode -1 when the loader cannot tell), the deck's ids
     * for an import. */
    int64_t first_id, nnode;
    int line;
} ctd_scene_mesh;

enum ctd_element { CTD_ELEM_BRICK = 0, CTD_ELEM_SHELL, CTD_ELEM_TRUSS, CTD_ELEM_SPRING,
                   CTD_ELEM_RIGID, CTD_ELEM_NKIND };

typedef struct ctd_scene_material {
    double E, nu, rho;
} ctd_scene_material;

typedef struct ctd_scene_part {
    int64_t id;
    char *name;                /* NULL when absent */
    char *element_name;
    ctd_scene_material material;
    double thickness, area, stiffness;
    /* Filled by the loader. */
    int element;               /* enum ctd_element */
    int line;
} ctd_scene_part;

typedef struct ctd_scene_rigid {
    int64_t id, part;
    int line;
} ctd_scene_rigid;

enum ctd_bc_kind { CTD_BC_FIXED = 0, CTD_BC_VELOCITY, CTD_BC_INITIAL_VELOCITY,
                   CTD_BC_GRAVITY, CTD_BC_FORCE, CTD_BC_PRESSURE, CTD_BC_NKIND };

typedef struct ctd_scene_bc {
    char *kind_name;
    ctd_scene_sel *nodes;      /* NULL for gravity */
    double *value;
    unsigned value_count;      /* 0 or 3 */
    char *dofs;                /* NULL: "xyz" */
    ctd_scene_sel *surface;    /* pressure: the loaded segments */
    double pressure;           /* pressure: its value (Pa) */
    double (*curve)[2];        /* force, pressure: [time, factor] points */
    unsigned curve_count;      /* 0: factor 1 at all times */
    /* Filled by the loader. */
    int kind;                  /* enum ctd_bc_kind */
    int dof[3];                /* 1 for each constrained component */
    int line;
} ctd_scene_bc;

typedef struct ctd_scene_interface {
    int64_t type;
    char *name;
    ctd_scene_sel *main, *secondary, *grnd_IDs;
    char *search_name;
    char *pressure_area_name;
    int64_t Istf, Igap0, Ipen0, Inacti, Ifric, Ifiltr, Irem_gap;
    double Stfac, Stmin, Stmax, gap, Gap_max_s, Gap_max_m, Ipen_max, VisS;
    double Fric, C1, C2, C3, C4, C5, C6, Xfreq, Tstart, Tstop;
    double margin;             /* re-sort margin; 0: 0.2 x mean main edge */
    double (*curve)[2];
    unsigned curve_count;
    /* Filled by the loader. */
    int search;                /* enum ct_search_algo value (ct_search.h) */
    int pressure_area;         /* 0 main, 1 secondary (CTD_PAREA_*, iface.h) */
    int self;                  /* 1: no secondary, self contact on main */
    char label[64];            /* name, or "if<index>" */
    int line;
} ctd_scene_interface;

typedef struct ctd_scene_output {
    char *dir;
    double every;
    bool vtu, csv;
    char *format_name; /* VTU arrays: "binary" (default) or "ascii" */
    int format;        /* filled by the loader: CTD_VTU_RAW or CTD_VTU_ASCII */
} ctd_scene_output;

typedef struct ctd_scene_solver {
    double dt_scale;
    int64_t threads;
    int64_t cycle_limit; /* filled by the loader: 1e8 when absent */
} ctd_scene_solver;

/* A loaded scene. The lists hold `*_count` entries. */
typedef struct ctd_scene {
    char *title;
    double end_time;
    int64_t refine;
    ctd_scene_output *output;  /* never NULL after a successful load */
    ctd_scene_solver *solver;  /* never NULL after a successful load */
    ctd_scene_mesh *mesh;
    unsigned mesh_count;
    ctd_scene_part *parts;
    unsigned parts_count;
    ctd_scene_rigid *rigid_bodies;
    unsigned rigid_bodies_count;
    ctd_scene_bc *boundary;
    unsigned boundary_count;
    ctd_scene_interface *interfaces;
    unsigned interfaces_count;
    /* Filled by the loader. */
    char *path;                /* the scene file as given */
    char *dir;                 /* its directory */
    char *out_dir;             /* output.dir or the default */
    void *internal;            /* the YAML tree (line lookups) */
} ctd_scene;

/* The errors of one load: the first CTD_SCENE_MAXERR messages (count may be
 * larger), each "FILE:LINE: FIELD: what". */
#define CTD_SCENE_MAXERR 16
typedef struct ctd_scene_msg {
    int line;                  /* 1-based; 0 when the file could not be read */
    char field[128];           /* "interfaces[0].type", or "" */
    char text[640];
} ctd_scene_msg;

typedef struct ctd_scene_err {
    int code;                  /* CT_OK or the first error's CT_ERR_* code */
    int count;
    ctd_scene_msg msg[CTD_SCENE_MAXERR];
} ctd_scene_err;

/*
 * Load and check a scene. On success returns CT_OK and *out is a scene to
 * release with ctd_scene_free. On failure returns a negative CT_ERR_* code
 * (CT_ERR_ARG: unreadable file, malformed YAML, a field of the wrong type,
 * missing or unknown; CT_ERR_RANGE: a reference to a part, node, group,
 * surface or body that does not exist; CT_ERR_NONFINITE: a NaN or infinite
 * number; CT_ERR_NOMEM: out of memory, `contact` exits 5; other codes
 * from the deck reader), *out is NULL and err (may be
 * NULL) lists the errors. Imported decks are read here. Nothing is printed.
 */
int ctd_scene_load(const char *path, ctd_scene **out, ctd_scene_err *err);

/* The same with the scene's `refine` replaced by refine (1..1000; 0 keeps
 * the file's): `contact run --refine N`, and tests that need a scene
 * larger than its CI size. An out-of-range value is an error on the field
 * "refine". */
int ctd_scene_load_refined(const char *path, int64_t refine, ctd_scene **out,
                           ctd_scene_err *err);
void ctd_scene_free(ctd_scene *sc);

/* The part with this id, or NULL. */
const ctd_scene_part *ctd_scene_part_by_id(const ctd_scene *sc, int64_t id);

/* The names used in the file for enum values ("brick", "bucket", ...). */
const char *ctd_element_name(int element);
const char *ctd_gen_kind_name(int kind);
const char *ctd_bc_kind_name(int kind);

/* Print a failed load's messages ("FILE:LINE: FIELD: what", at most
 * CTD_SCENE_MAXERR of them, then how many more were not shown) and a last
 * line counting them, or saying the scene was not loaded for want of
 * memory when that was the first error. */
void ctd_scene_print_errors(FILE *f, const char *path, const ctd_scene_err *err);

/* Print "PATH: ok: ..." (title, end time, meshes, node count, parts,
 * rigid bodies, boundary conditions, interfaces, output directory) and
 * each imported deck's warning: the first lines of `contact check`
 * (driver/run.c). */
void ctd_scene_print_summary(FILE *f, const char *path, const ctd_scene *sc);

#ifdef __cplusplus
}
#endif

#endif /* CTD_SCENE_H */
