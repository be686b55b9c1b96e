/*
 * contact.h -- the public API of libcontact, penalty contact kernels for
 * explicit finite-element dynamics.
 *
 * This is the one header a user includes. It defines the core types (the
 * floating-point type, indices, error codes, node and segment arrays) and
 * pulls in one sub-header per concept (search, narrow phase, force laws,
 * friction, assembly, time step), each of which is documented on its own.
 *
 * Conventions (see DESIGN.md section 3):
 *  - Structure of arrays: every per-node or per-segment field is its own
 *    64-byte-aligned array, padded to a multiple of CT_PAD elements.
 *  - Every function that can fail returns an int status: CT_OK (0) or a
 *    negative CT_ERR_* code; ct_strerror() names the code, and a ct_diag
 *    (when the function takes one) says what and where.
 *  - The library never prints, never exits and never allocates inside a
 *    time-step loop once its workspaces have grown to size.
 *  - Results are bit-identical for any OMP_NUM_THREADS.
 */
#ifndef CONTACT_H
#define CONTACT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* `restrict` in the public headers, spelled so C++ can include them. */
#ifdef __cplusplus
#define CT_RESTRICT __restrict__
#else
#define CT_RESTRICT restrict
#endif

/* ---- Scalar types ------------------------------------------------------ */

#ifdef CT_SINGLE
typedef float ct_real;
#define CT_PRECISION_NAME "single"
#define CT_PRECISION_GUARD ct_library_is_single_precision
#else
typedef double ct_real;
#define CT_PRECISION_NAME "double"
#define CT_PRECISION_GUARD ct_library_is_double_precision
#endif

/* The library defines the one of these that names its precision, and every
 * file that includes this header refers to the one that names the file's:
 * a program compiled with -DCT_SINGLE against the double-precision library
 * (which would read its float arrays as doubles), or the other way round,
 * fails to link with "undefined reference to ct_library_is_..._precision"
 * (pkg-config --cflags contact gives the library's flag). */
extern const int CT_PRECISION_GUARD;
#if defined(__GNUC__) || defined(__clang__)
__attribute__((used))
#endif
static const int *const ct_precision_guard_ = &CT_PRECISION_GUARD;

/* Indices inside one shared-memory domain. */
typedef int32_t ct_idx;

/* Alignment in bytes of every array the library allocates, and the element
 * count every array is padded to (a 64-byte line of floats). */
#define CT_ALIGN 64
#define CT_PAD 16

/* ---- Errors ------------------------------------------------------------ */

enum ct_status {
    CT_OK = 0,
    CT_ERR_NOMEM = -1,      /* an allocation failed */
    CT_ERR_ARG = -2,        /* an impossible argument (NULL, negative count) */
    CT_ERR_RANGE = -3,      /* an index out of range */
    CT_ERR_DUPNODE = -4,    /* a node repeated within one segment */
    CT_ERR_NONFINITE = -5,  /* a NaN or infinite value */
    CT_ERR_DEGENERATE = -6, /* a zero-area segment or zero-length edge */
    CT_ERR_NOCONV = -7,     /* an iteration did not converge */
    CT_ERR_TOOBIG = -8      /* a count would overflow ct_idx */
};

/* A short, constant English name for a status code. */
const char *ct_strerror(int code);

/* Details of a failure: the code, the offending entity's index (node,
 * segment, pair... or -1) and a full-sentence message. Functions that take
 * a ct_diag fill it on failure only; it may be NULL. */
typedef struct ct_diag {
    int code;
    int64_t index;
    char msg[256];
} ct_diag;

/* ---- Memory ------------------------------------------------------------ */

/* Allocate `count` elements of `size` bytes, 64-byte aligned, zero-filled,
 * rounded up to a multiple of CT_PAD elements. NULL on failure or overflow. */
void *ct_calloc(size_t count, size_t size);
void ct_free(void *p);

/* ---- Build provenance -------------------------------------------------- */

/* "compiler=... flags=... precision=... commit=...", fixed at build time. */
const char *ct_build_info(void);

/* ---- Nodes (structure of arrays) --------------------------------------- */

typedef struct ct_nodes {
    ct_idx n;
    ct_real *x, *y, *z;    /* positions */
    ct_real *vx, *vy, *vz; /* velocities */
    ct_real *fx, *fy, *fz; /* forces */
    ct_real *m;            /* lumped masses */
} ct_nodes;

int ct_nodes_init(ct_nodes *nd, ct_idx n);
void ct_nodes_destroy(ct_nodes *nd);

/* ---- Mesh: segments, edges, adjacency ---------------------------------- */

/*
 * A segment is a quadrangle n1 n2 n3 n4 or a triangle with n4 == n3 (the
 * Radioss convention). Node numbers are 0-based indices into the nodes.
 * Edges and adjacency are derived by ct_mesh_build_topology():
 *  - edges e1[k] < e2[k], unique, sorted by (e1, e2); the segments adjacent
 *    to edge k are edge_seg[edge_seg_off[k] .. edge_seg_off[k+1]-1];
 *  - the segments attached to node i are
 *    node_seg[node_seg_off[i] .. node_seg_off[i+1]-1], in increasing order.
 */
typedef struct ct_mesh {
    ct_nodes nodes;
    ct_idx nseg;
    ct_idx *n1, *n2, *n3, *n4;
    ct_idx nedge;
    ct_idx *e1, *e2;
    ct_idx *edge_seg_off, *edge_seg;
    ct_idx *node_seg_off, *node_seg;
} ct_mesh;

/* Allocate a mesh of nnode nodes and nseg segments (all fields zero). */
int ct_mesh_init(ct_mesh *m, ct_idx nnode, ct_idx nseg);
void ct_mesh_destroy(ct_mesh *m);

/* Check the mesh: node index out of range, a node repeated in a segment
 * (other than the n3 == n4 triangle convention), NaN/Inf coordinates, and
 * zero-area segments are all rejected. Reported in diag: the first bad
 * segment (index, repeated node, area; in segment order), else the first
 * node with a NaN/Inf coordinate (in node order), so a segment of valid
 * indices with a NaN corner is reported by its node after every other
 * segment's problem. Zero area means area <= 1e-12 (double)
 * or 1e-6 (single) times the square of the segment's longest edge. */
int ct_mesh_validate(const ct_mesh *m, ct_diag *diag);

/* Derive edges and node->segment adjacency (replaces earlier ones).
 * CT_ERR_RANGE (segment in diag) for a segment node outside [0, nnode). */
int ct_mesh_build_topology(ct_mesh *m, ct_diag *diag);

/* A surface is a list of segments; a node set is a list of nodes. */
typedef struct ct_surface {
    ct_idx n;
    ct_idx *seg;
} ct_surface;

typedef struct ct_nodeset {
    ct_idx n;
    ct_idx *node;
} ct_nodeset;

/* The nodes used by a surface's segments, sorted and unique. CT_ERR_RANGE
 * for a segment index outside [0, nseg) or a segment node outside
 * [0, nnode). */
int ct_surface_nodes(const ct_mesh *m, const ct_surface *s, ct_nodeset *out);
void ct_nodeset_destroy(ct_nodeset *s);

#ifdef __cplusplus
}
#endif

/* One sub-header per concept. */
#include "ct_search.h"
#include "ct_narrow.h"
#include "ct_force.h"
#include "ct_friction.h"
#include "ct_assemble.h"
#include "ct_timestep.h"

#endif /* CONTACT_H */
