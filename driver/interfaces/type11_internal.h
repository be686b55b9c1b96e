/*
 * type11_internal.h -- what the two files of TYPE11 share: the edge pass
 * (its pairs and per-pair arrays) of type11.c and the edge search of
 * type11_search.c.
 */
#ifndef CTD_TYPE11_INTERNAL_H
#define CTD_TYPE11_INTERNAL_H

#include "iface_internal.h"

/* Per-pair reals (no closest points: the step needs sa and sb only). */
enum { E_DIST = 0, E_PEN, E_NX, E_NY, E_NZ, E_SA, E_SB, E_GAP, E_K0, E_FEL, E_KTAN, E_EN, E_VN, E_MS, E_MM, E_FN, E_FX, E_FY, E_FZ, E_DD,
       E_W1, E_W2, E_W3, E_W4, E_VR2, E_N };

/* The bytes of one pair in the edge pass's arrays (ctdi_epass_grow and
 * its ids), and of one pair the search lists before the filter keeps it
 * (ctdi_epass_grow_ids). */
#define CTDI_EPAIR_BYTES (6 * sizeof(ct_idx) + 5 + E_N * sizeof(ct_real))
#define CTDI_EPAIR_ID_BYTES (2 * sizeof(ct_idx))

/* The filter measures the search's pairs in chunks of this many, into
 * arrays of its own (an edge-edge geometry without the closest points: 8
 * reals and a flag). */
#define CTDI_FCHUNK 16384
#define CTDI_FGEO_N 8

struct ctdi_epass {
    ct_idx na, nb, ne;     /* edges of A, of B (0: self), total */
    ct_idx *e1, *e2;       /* ne edges */
    ct_real *gedge;        /* per-edge gap */
    ct_real sgap;          /* largest pair gap */
    ct_idx nan, nbn;
    ct_idx *an, *bn;       /* unique nodes of A and of B */
    int self, bucket, need_sort;
    ct_real k0;
    ct_real *x0, *y0, *z0;
    /* Pairs (pa, pb: grown for the search's list, cap_ids) and per-pair
     * arrays (grown for the pairs the filter keeps, cap). */
    ct_idx n;
    size_t cap, cap_ids;
    ct_idx *pa, *pb, *sl[4];
    ct_real *fr[CTDI_FGEO_N];
    uint8_t *fflag;
    ct_edge_geo fgeo;
    ct_real *r[E_N];
    uint8_t *flag;
    int32_t *iflag;
    ct_edge_geo geo;
    /* With damping: each pair's damping force at its last step
     * (ct_damping_work) in fd[fcur], carried across re-sorts by the pair
     * key (pa, pb): kpa, kpb hold the nkey keys of the list fd[fcur] is
     * for; o2n matches the next list against them. */
    ct_real *fd[2];
    size_t cap_fd[2];
    int fcur;
    ct_idx nkey;
    ct_idx *kpa, *kpb, *o2n;
    size_t cap_kpa, cap_kpb, cap_o2n;
    /* Search scratch. */
    ct_real *box;          /* 6 per edge: lo xyz, hi xyz */
    ct_idx *cnt;           /* per A edge: pair counts, then offsets (na + 1) */
    ct_idx *cell_off, *cell_edge;
    size_t cap_cell, cap_ce;
    ct_idx *tmp_a;
    size_t cap_tmp;
    int32_t *cellr;        /* 6 per edge: its box's first and last cell per axis */
    size_t cap_cellr;
    int64_t *qoff;         /* per A edge: where its candidates go in qbuf (na + 1) */
    ct_idx *qbuf;          /* the bucket query's candidates, one pass (type11_search.c) */
    size_t cap_qoff, cap_qbuf;
    ct_assemble_ws ws;
    int ws_ok;
    /* Irem_gap 2 (type11_filter.c): 1 to build at the next search, 2
     * built, 0 none; queries and items are the edges. */
    int excl_state;
    ct_exclusion excl;
};

/* An array with room for n items of size bytes: a itself when its
 * capacity *cap holds them, else a new zeroed one (a freed, the contents
 * not kept; NULL and *cap 0 when out of memory). type11.c. */
void *ctdi_grow_fresh(void *a, size_t *cap, size_t n, size_t size);

/* Per-pair arrays for n pairs, and the pair ids for n pairs (contents not
 * kept; type11.c). */
int ctdi_epass_grow(ctdi_epass *e, size_t n);
int ctdi_epass_grow_ids(ctdi_epass *e, size_t n);

/* The search when the re-sort criterion asks for it (or a re-sort was
 * forced), then the pairs' node slots, the assembly preparation and the
 * per-pair stiffness (type11_search.c). *did is 1 when it searched. */
int ctdi_type11_search(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                       const ct_real *z, int *did);

/* After a search (type11_filter.c): keep the pairs within their gap and
 * the margin by the narrow phase's distance; with Irem_gap 2, build the
 * neighbour exclusion at the first search and remove the pairs that either
 * edge excludes. The order stays canonical. */
int ctdi_type11_filter(ctd_iface *it, ctdi_epass *e, const ct_real *x, const ct_real *y,
                       const ct_real *z);

/* After a search, with damping: the damping force of each pair of the new
 * list (pa, pb, n) taken from the old list's, 0 for a new pair; the new
 * keys kept (type11.c). */
int ctdi_type11_carry_damping(ctdi_epass *e);

#endif /* CTD_TYPE11_INTERNAL_H */
