/*
 * contact_cycle_internal.h -- what the two files of the contact cycle share:
 * contact_cycle.c (set-up, search, assembly, the cycle) and
 * contact_cycle_pairs.c (the fused pass over the candidate pairs: narrow
 * phase, force, time step).
 */
#ifndef CTD_CONTACT_CYCLE_INTERNAL_H
#define CTD_CONTACT_CYCLE_INTERNAL_H

#include "contact_cycle.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wtime.h"

#ifdef _OPENMP
#include <omp.h>
static inline int cti_cycle_max_threads(void) { return omp_get_max_threads(); }
static inline int cti_cycle_thread(void) { return omp_get_thread_num(); }
#else
static inline int cti_cycle_max_threads(void) { return 1; }
static inline int cti_cycle_thread(void) { return 0; }
#endif

/* Pairs per block of the fused narrow/force/step pass (phase_pairs), at
 * least: a block ends at the end of its last node's run of pairs
 * (ct_pair_node_blocks), so that which of a node's pairs carry it, and the
 * hand-over of their states, are decided inside one block. Measured on the
 * folded sheet, 10^6 nodes: 2048, 4096 and 8192 within 5 % of each other
 * (4096 best by a little); 512 and 256 slower, by the kernels' fixed cost
 * per call. */
#define CY_BLOCK 4096

/* Narrow-phase results kept per pair: p and the four weights. */
#define CY_NGEO 5

/* One block's results of the fused pass. */
typedef struct cy_block {
    int rc, rc_kin, rc_nod;  /* the first failing kernel; the step kernels' codes */
    int64_t active;          /* pairs with p > 0 */
    ct_real dt_kin, dt_nod;  /* the block's smallest limits */
    ct_idx i_kin, i_nod;     /* their pairs (global indices; -1: none) */
    ct_idx neval;            /* pairs through the narrow phase */
    double t[3];             /* seconds in narrow phase, force, step */
} cy_block;

/*
 * The fused pass runs the force and the step only on the block's pairs in
 * contact (p > 0): the others have zero force, zero friction history and no
 * step limit, which is what the kernels give them, so they are skipped
 * (about two thirds of the candidates of the folded sheet). The block's
 * active pairs are packed into a per-thread scratch of as many entries as
 * the longest block (len): their local indices (act), the gathered inputs
 * and the kernels' outputs; CS_PPREV and CS_HO hold the evaluated pairs'
 * last penetrations and hand-overs (ct_select_pairs).
 */
enum { CS_H1, CS_H2, CS_H3, CS_H4, CS_NX, CS_NY, CS_NZ, CS_PEN, CS_GAP, CS_MS, CS_K0,
       CS_T0, CS_T1, CS_T2, CS_VRX, CS_VRY, CS_VRZ, CS_VN, CS_FEL, CS_KTAN, CS_FN,
       CS_FX, CS_FY, CS_FZ, CS_PPREV, CS_NREAL };
enum { CS_ACT, CS_NODE, CS_S1, CS_S2, CS_S3, CS_S4, CS_HO, CS_NIDX };
typedef struct cy_scratch {
    ct_real *v[CS_NREAL];
    ct_idx *i[CS_NIDX];
    int32_t *flag7;
    uint8_t *carry; /* the selection's carry flags */
    void *mem; /* the one allocation the arrays live in */
} cy_scratch;

struct ctd_cycle {
    ctd_cycle_params p;
    /* The interface (borrowed arrays). */
    ct_idx nnode, nsec, nmain, nseg;
    const ct_real *m;
    const ct_idx *sec, *mainn, *n1, *n2, *n3, *n4;
    int self;
    /* Search. */
    ct_search *search;
    int need_sort;
    ct_real *x0, *y0, *z0; /* positions at the last sort */
    /* Pair lists and friction histories, double-buffered: `cur` is the
     * current one, 1 - cur the previous one (the source of the remap). */
    int cur;
    ct_pairs pairs[2];
    ct_real *ft[2][3];
    ct_real *ex[2]; /* the skip's expiry of each pair (contact_cycle_skip.c) */
    ct_real *pp[2]; /* each pair's penetration of the last step (0 when not a
                       carrier, or skipped); geo.pen is pp[cur] */
    size_t capft[2];
    /* Single-buffered per-pair arrays (capacity cap). */
    size_t cap;
    ct_idx *s[4], *old_of_new;
    ct_real *g[CY_NGEO]; /* g[0] unused (p is pp[cur]), h1..h4 */
    uint8_t *flag;
    uint8_t *evald; /* 1: the pair's narrow phase ran this cycle */
    ct_real *fp[3]; /* the pair force on the secondary node (assembled) */
    ct_idx *cn[5];  /* fused assembly: the compact lists' nodes (node, s1..s4) */
    ct_idx *nact;   /* fused assembly: each block's list length (pairs in contact) */
    ct_contact_geo geo;
    /* The pass's blocks of the current list (ct_pair_node_blocks): nblk,
     * starting at bst[0..nblk], the longest maxblk pairs. */
    ct_idx *bst, nblk, maxblk;
    cy_block *blk; /* nblk records (room: cap / CY_BLOCK + 1) */
    cy_scratch *scr; /* per thread (nscr), of scrlen entries per array */
    int nscr;
    ct_idx scrlen;
    /* The skip (contact_cycle_skip.c): on, the previous cycle's positions
     * (valid when have_prev) in buffer pc, the other receiving this
     * cycle's, the motion sum since the last re-sort, the rounding slack
     * of this cycle. */
    int skip_on, have_prev, pc;
    ct_real *xp[2], *yp[2], *zp[2];
    double motion, slack;
    /* Assembly. */
    ct_assemble_ws ws;
    int ws_ready;
    ctd_cycle_stats st;
};

/* The fused pass over the n candidate pairs (contact_cycle_pairs.c): the
 * active count, the count of pairs through the narrow phase and the seconds
 * spent in narrow phase, force and step. */
int cti_cycle_pairs(ctd_cycle *cy, ct_idx n, const ct_real *x, const ct_real *y,
                    const ct_real *z, const ct_real *vx, const ct_real *vy, const ct_real *vz,
                    ct_real dt, int64_t *active, int64_t *neval, double tph[3]);

/* 1 when the assembly is fused with the pass (the colouring variant): the
 * pass leaves each block's pairs in contact in a compact list (forces in
 * fp, weights in g[1..4], nodes in cn, at the block's first positions, in
 * order; nact[b] of them), and ct_assemble_coloured_prefix assembles those
 * lists alone, colour by colour, with the colouring made at the search on
 * the pass's blocks.
 * The per-pair weights are then not kept (ctd_cycle_geo gives no h1..h4).
 * The other variants assemble the per-pair forces fp, zero out of
 * contact, with ct_assemble. */
static inline int cti_cycle_fused(const ctd_cycle *cy)
{
    return cy->p.asm_variant == CT_ASM_COLOUR;
}

/* The skip (contact_cycle_skip.c). cti_skip_motion adds this cycle's
 * motion bound to the sum and keeps the positions, and returns the re-sort
 * criterion (its bound in *bound), evaluated in the same pass;
 * cti_skip_remap carries the expiries of the pairs that survive a re-sort (after the friction
 * remap filled old_of_new) and restarts the sum; cti_skip_select lists in
 * act the pairs of block [k0, k1) (indices in the block) whose expiry has
 * passed and returns their count; cti_skip_expiry sets the expiries of the
 * ne evaluated pairs act[j] from their narrow-phase results (packed). */
int cti_skip_motion(ctd_cycle *cy, const ct_real *x, const ct_real *y, const ct_real *z,
                    ct_real *bound);
void cti_skip_remap(ctd_cycle *cy, ct_idx n, int old, int now);
ct_idx cti_skip_select(ctd_cycle *cy, ct_idx k0, ct_idx k1, ct_idx *act);
void cti_skip_expiry(ctd_cycle *cy, ct_idx k0, ct_idx ne, const ct_idx *act, const ct_real *dist,
                     const ct_real *gap, const uint8_t *flag);

/* The per-thread scratch of the pass, for nthr threads (outside a parallel
 * region), each array with room for len pairs (the longest block), and its
 * release. */
int cti_cycle_scratch_grow(ctd_cycle *cy, int nthr, ct_idx len);
void cti_cycle_scratch_free(ctd_cycle *cy);

#endif /* CTD_CONTACT_CYCLE_INTERNAL_H */
