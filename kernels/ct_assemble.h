/*
 * ct_assemble.h -- race-free assembly of contact forces into nodal force
 * arrays, part of contact.h. The design note is docs/RACES.md.
 *
 * One mechanism serves node-segment and edge-edge pairs: pair k touches
 * nslot nodes (its "slots"), node slot[s][k] receiving the force
 *
 *     sign[s] * w[s][k] * (fx[k], fy[k], fz[k])      (w[s] == NULL: weight 1)
 *
 * added into (fxn, fyn, fzn). A node-segment pair has 5 slots: the
 * secondary node (+f) and the segment's nodes n1..n4 (-h_i f); a triangle
 * has n4 == n3 and h4 = 0, the repeated slot simply adds a zero. An
 * edge-edge pair has 4 slots: edge A's nodes (+w f) and edge B's (-w f).
 * With weights summing to 1 on each side, the total force of every pair is
 * zero (and, with the weights of the contact points, so is its moment).
 *
 * A pair whose force is exactly zero (a candidate out of contact: most of a
 * contact cycle's list) is skipped by the serial loop and the coloured
 * blocks (block > 1, the default; the one-pair colouring's vector loop adds
 * them): its contributions are zeros, and x + 0 == x for every x but -0,
 * which sums that start from +0 never produce. So the skip changes no bit of
 * the result, unless the output arrays already hold -0 or a weight is NaN or
 * infinite (0 * inf would have made a NaN); the other variants add the
 * zeros.
 *
 * The slot map depends only on the pair list, so it is analysed once per
 * pair list (after each search): ct_assemble_prepare() colours the pairs or
 * builds the node->slot map the chosen variant needs, and ct_assemble() then
 * runs every cycle without allocating. The caller must prepare again
 * whenever the pair list changes; a stale colouring is a data race that no
 * cheap check can detect (counts are checked, contents are not).
 *
 * Variants (one entry point, ct_assemble(ws, variant, ...)):
 *  - CT_ASM_COLOUR (default): blocks of consecutive pairs are coloured so
 *    that no two blocks of one colour share a node; each colour is a parallel
 *    loop without atomics. Bit-identical for any thread count.
 *  - CT_ASM_ATOMIC: OpenMP atomic adds. NOT deterministic: the order in
 *    which a node receives its contributions varies from run to run.
 *  - CT_ASM_THREADBUF: per-thread force buffers, then a node-parallel sum in
 *    thread order. Deterministic for a fixed thread count only.
 *  - CT_ASM_GATHER: each pair writes private slots, then a node-parallel pass
 *    sums each node's slots through a node->slot CSR map in pair order.
 *    Bit-identical for any thread count (and to the serial loop).
 *  - CT_ASM_SERIAL: the plain sequential loop over pairs (the reference).
 */
#ifndef CT_ASSEMBLE_H
#define CT_ASSEMBLE_H

#ifdef __cplusplus
extern "C" {
#endif

/* Largest number of node slots per pair. */
#define CT_ASM_MAXSLOT 5

/* The pair -> node map: slot[s][k] is the node of slot s of pair k (global
 * node index), sign[s] is +1 or -1. A small descriptor of the caller's
 * arrays (nothing is copied). */
typedef struct ct_asm_map {
    ct_idx npair;
    int nslot;                           /* 1 .. CT_ASM_MAXSLOT */
    const ct_idx *slot[CT_ASM_MAXSLOT];
    ct_real sign[CT_ASM_MAXSLOT];
} ct_asm_map;

/* Node-segment map: slots (node, s1, s2, s3, s4), signs (+, -, -, -, -).
 * s1..s4 hold the segment's nodes per pair (see ct_asm_seg_slots); weights
 * are then (NULL, h1, h2, h3, h4). */
ct_asm_map ct_asm_map_nodeseg(ct_idx npair, const ct_idx *node, const ct_idx *s1,
                              const ct_idx *s2, const ct_idx *s3, const ct_idx *s4);

/* Edge-edge map: slots (a1, a2, b1, b2), signs (+, +, -, -); weights
 * (wa1, wa2, wb1, wb2), e.g. (1 - s, s, 1 - t, t) for contact points at
 * parameters s on edge A and t on edge B. */
ct_asm_map ct_asm_map_edge(ct_idx npair, const ct_idx *a1, const ct_idx *a2,
                           const ct_idx *b1, const ct_idx *b2);

/* Materialise the segment nodes of each pair, s_i[k] = n_i[seg[k]] (once per
 * pair list), in parallel. Returns CT_ERR_RANGE when a seg[k] is outside
 * [0, nseg). */
int ct_asm_seg_slots(ct_idx npair, const ct_idx *CT_RESTRICT seg, ct_idx nseg,
                     const ct_idx *CT_RESTRICT n1, const ct_idx *CT_RESTRICT n2,
                     const ct_idx *CT_RESTRICT n3, const ct_idx *CT_RESTRICT n4,
                     ct_idx *CT_RESTRICT s1, ct_idx *CT_RESTRICT s2, ct_idx *CT_RESTRICT s3,
                     ct_idx *CT_RESTRICT s4);

typedef enum ct_assemble_variant {
    CT_ASM_COLOUR = 0, /* the default: coloured blocks, no atomics */
    CT_ASM_ATOMIC,     /* omp atomic adds; not deterministic */
    CT_ASM_THREADBUF,  /* per-thread buffers + reduction; fixed thread count */
    CT_ASM_GATHER,     /* private slots + node->slot CSR sum */
    CT_ASM_SERIAL,     /* sequential reference */
    CT_ASM_NVARIANT
} ct_assemble_variant;

/* "colour", "atomic", "threadbuf", "gather", "serial"; inverse (-1 when
 * unknown). */
const char *ct_assemble_variant_name(ct_assemble_variant v);
int ct_assemble_variant_from_name(const char *name);

/*
 * The workspace. Fields are read-only for the caller; they describe the
 * last colouring and the gather map. Everything is grown on demand and
 * kept, so nothing is allocated per cycle once sizes are stable.
 *
 * Colouring: pairs are cut into nblock blocks of `block` consecutive pairs
 * (block b holds pairs [b*block, min((b+1)*block, npair))). colour[b] is
 * block b's colour; bperm lists the blocks grouped by colour, in increasing
 * order inside a colour, colour c at bperm[col_off[c] .. col_off[c+1]-1].
 * No two blocks of one colour share a node. With block == 1 this is the
 * plain pair colouring (colour[k] is pair k's colour).
 */
typedef struct ct_assemble_ws {
    /* Colouring (ct_colour_pairs). */
    ct_idx col_npair, col_nnode; /* the map it was made for (-1: none) */
    int col_nslot;
    ct_idx block, nblock; /* block: 0 when the blocks were given
                             (ct_colour_pair_blocks) */
    ct_idx *bstart;       /* nblock + 1 block starts, when block == 0 */
    ct_idx ncolour;
    ct_idx *colour;  /* nblock */
    ct_idx *col_off; /* ncolour + 1 */
    ct_idx *bperm;   /* nblock */
    ct_idx max_degree; /* largest number of other blocks sharing a node with
                          one block, counted with repetition (greedy bound:
                          ncolour <= max_degree + 1); computed only when
                          asked, see ct_colour_degree */
    /* Gather (ct_gather_prepare): touched nodes, their slots in pair order. */
    ct_idx g_npair, g_nnode;
    int g_nslot;
    ct_idx g_ntouched;
    ct_idx *g_node;    /* g_ntouched touched nodes, increasing */
    int64_t *g_off;    /* g_ntouched + 1 */
    int64_t *g_slot;   /* npair * nslot slot indices k * nslot + s */
    ct_real *g_cx, *g_cy, *g_cz; /* private slot contributions */
    /* Per-thread buffers (ct_assemble_threadbuf). */
    int tb_nthr;
    ct_idx tb_npair, tb_nnode;
    ct_idx *tb_lo, *tb_hi; /* node range touched by each thread's block */
    ct_real **tb_buf;      /* per thread: 3 * (hi - lo) values (x, y, z) */
    size_t *tb_cap;
    /* Scratch and capacities (elements). */
    uint64_t *mask;        /* per node colour mask */
    ct_idx *todo, *next;   /* deferred blocks of the colouring passes */
    ct_idx *full;          /* leading full mask words per node (passes > 0) */
    size_t cap_full;
    size_t cap_colour, cap_off, cap_bperm, cap_mask, cap_todo, cap_next, cap_bstart;
    size_t cap_gnode, cap_goff, cap_gslot, cap_gc[3], cap_cnt;
    int64_t *cnt;          /* per node counts and cursors (gather build) */
    int tb_maxthr;
} ct_assemble_ws;

int ct_assemble_ws_init(ct_assemble_ws *ws);
void ct_assemble_ws_destroy(ct_assemble_ws *ws);
/* Bytes held by the workspace. */
size_t ct_assemble_ws_memory(const ct_assemble_ws *ws);

/*
 * Greedy, deterministic colouring: blocks in increasing order, each takes
 * the smallest colour not used by an earlier block that shares a node.
 * A first pass gives colours 0..63 with one 64-bit mask per node; blocks
 * that found all 64 taken go to further passes with wider masks over their
 * nodes only, which gives exactly the one-by-one greedy result. block <= 0
 * selects ct_asm_default_block(npair); block == 1 colours single pairs. The
 * result depends on the map only, never on the thread count. Node indices
 * must lie in [0, nnode) (else CT_ERR_RANGE).
 */
int ct_colour_pairs(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode,
                    ct_idx block);

/*
 * The same colouring on blocks the caller chooses: block b holds pairs
 * [bstart[b], bstart[b + 1]), b < nblock, with bstart[0] == 0,
 * bstart[nblock] == npair and the starts strictly increasing (nblock == 0
 * for no pair); CT_ERR_ARG otherwise. The starts are copied (ws->bstart;
 * ws->block is 0 after it), and every coloured assembly then works on
 * these blocks. For a caller whose per-block work needs all the pairs of a
 * node in one block (which pairs carry the node, the hand-over of their
 * states): ct_pair_node_blocks gives such starts.
 */
int ct_colour_pair_blocks(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode,
                          ct_idx nblock, const ct_idx *bstart);

/*
 * Blocks of consecutive pairs that never split a node's run: pairs in
 * ascending node order (node[k], a search's canonical order), each block
 * at least `block` pairs (block >= 1; the last may be shorter), extended to
 * the end of the run of its last pair's node. Writes the starts and the
 * final npair to bstart, which has room for npair / block + 2 entries, and
 * returns the number of blocks (0 for no pair), or CT_ERR_ARG for a NULL
 * array, block < 1, a negative count or nodes out of ascending order.
 */
ct_idx ct_pair_node_blocks(ct_idx npair, const ct_idx *node, ct_idx block, ct_idx *bstart);

/*
 * The default block of the colouring: npair / 32 pairs, at least
 * CT_ASM_BLOCK_MIN and at most CT_ASM_BLOCK_MAX. A colour's blocks lie
 * apart in the pair arrays; each block is a dozen short streams (forces,
 * slots, weights), and blocks of 256 pairs left the hardware prefetcher too
 * little to lock on: at 10^6 pairs the coloured loop was 2-3x slower than
 * the serial one. Blocks of 4096 stream like the serial loop and need fewer
 * colours (2 instead of 6 on the plates). The size depends on npair only,
 * so the colouring, and with it every node's order of contributions, stays
 * independent of the thread count; npair / 32 keeps 16 or more blocks per
 * colour for the threads to share.
 */
#define CT_ASM_BLOCK_MIN 256
#define CT_ASM_BLOCK_MAX 4096
ct_idx ct_asm_default_block(ct_idx npair);

/* The greedy bound of the last colouring: the largest, over blocks, number
 * of (other block, shared node) incidences; ncolour <= it + 1. Costs a pass
 * over the map (for tests and reports). Stores it in ws->max_degree too.
 * -1 when ws holds no colouring of a map of these sizes, or a node of the
 * map is outside [0, nnode). */
ct_idx ct_colour_degree(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode);

/* Build the node->slot CSR map of the gather variant (once per pair list). */
int ct_gather_prepare(ct_assemble_ws *ws, const ct_asm_map *map, ct_idx nnode);

/* Prepare what `variant` needs (colouring with the default block, gather
 * map, thread-buffer ranges; nothing for atomic and serial). */
int ct_assemble_prepare(ct_assemble_ws *ws, ct_assemble_variant variant,
                        const ct_asm_map *map, ct_idx nnode);

/*
 * Add the pairs' forces into fxn, fyn, fzn (length nnode). w[s] are the
 * per-pair weights of slot s (NULL: 1); fx, fy, fz the pair forces.
 * Returns CT_ERR_ARG when the workspace was not prepared for a map of this
 * size (npair, nslot, nnode), for COLOUR and GATHER; THREADBUF prepares its
 * ranges itself when sizes or the thread count change.
 *
 * Node indices: ATOMIC and SERIAL (and ct_assemble_scalar with any variant
 * but COLOUR) check every slot at each call and answer CT_ERR_RANGE for a
 * node outside [0, nnode): ATOMIC and the scalar sum with nothing written,
 * SERIAL (which checks each pair as it comes, at no measurable cost on
 * 10^6 pairs, 1.1x on 10^4) with the pairs whose nodes are all in range
 * added and the others not (no write outside [0, nnode)). COLOUR, GATHER and
 * THREADBUF check them when they prepare (CT_ERR_RANGE from
 * ct_assemble_prepare or the first THREADBUF call) and trust the prepared
 * map afterwards: a map whose slots change while its sizes stay (a new
 * pair list of the same length) must be prepared again, as it must anyway
 * for the colouring to be right.
 */
int ct_assemble(ct_assemble_ws *ws, ct_assemble_variant variant, const ct_asm_map *map,
                const ct_real *const w[], const ct_real *CT_RESTRICT fx,
                const ct_real *CT_RESTRICT fy, const ct_real *CT_RESTRICT fz, ct_idx nnode,
                ct_real *CT_RESTRICT fxn, ct_real *CT_RESTRICT fyn, ct_real *CT_RESTRICT fzn);

/*
 * One value per pair instead of a vector: fn[slot s of pair k] +=
 * w[s][k] sign[s] f[k] (w[s] NULL: 1), e.g. a contact stiffness spread
 * onto the pair's nodes for the nodal time step. CT_ASM_COLOUR uses the
 * colouring ws was prepared with for this map (CT_ERR_ARG otherwise) and
 * runs each colour in parallel; every other variant sums serially in pair
 * order. Either way the result does not depend on the thread count. Every
 * variant skips a pair whose value is exactly zero (the nodal step's
 * stiffness of a pair that does not count), with the same exception as the
 * force assembly's skip above: fn holding -0, or a NaN or infinite weight.
 */
int ct_assemble_scalar(const ct_assemble_ws *ws, ct_assemble_variant variant,
                       const ct_asm_map *map, const ct_real *const w[],
                       const ct_real *CT_RESTRICT f, ct_idx nnode, ct_real *CT_RESTRICT fn);

/* The variants, explicitly (same arguments). */
int ct_assemble_coloured(const ct_assemble_ws *ws, const ct_asm_map *map,
                         const ct_real *const w[], const ct_real *CT_RESTRICT fx,
                         const ct_real *CT_RESTRICT fy, const ct_real *CT_RESTRICT fz,
                         ct_idx nnode, ct_real *CT_RESTRICT fxn, ct_real *CT_RESTRICT fyn,
                         ct_real *CT_RESTRICT fzn);

/*
 * The colouring over a prefix of each block: block b adds only its first
 * count[b] pairs (count NULL: all, as ct_assemble_coloured). For a caller
 * that keeps, at the start of each block, a compact list of the block's
 * pairs that carry a force (a subset of the block's pairs, whose nodes the
 * colouring already covers): the lists are added colour by colour, each
 * block in order, with no atomics, in the order ct_assemble_coloured adds
 * the same forces spread over the whole blocks (it skips zero forces), so
 * the result is the same, bit for bit, for any thread count.
 */
int ct_assemble_coloured_prefix(const ct_assemble_ws *ws, const ct_asm_map *map,
                                const ct_idx *count, const ct_real *const w[],
                                const ct_real *CT_RESTRICT fx, const ct_real *CT_RESTRICT fy,
                                const ct_real *CT_RESTRICT fz, ct_idx nnode,
                                ct_real *CT_RESTRICT fxn, ct_real *CT_RESTRICT fyn,
                                ct_real *CT_RESTRICT fzn);
int ct_assemble_atomic(const ct_asm_map *map, const ct_real *const w[],
                       const ct_real *CT_RESTRICT fx, const ct_real *CT_RESTRICT fy,
                       const ct_real *CT_RESTRICT fz, ct_idx nnode, ct_real *CT_RESTRICT fxn,
                       ct_real *CT_RESTRICT fyn, ct_real *CT_RESTRICT fzn);
int ct_assemble_threadbuf(ct_assemble_ws *ws, const ct_asm_map *map,
                          const ct_real *const w[], const ct_real *CT_RESTRICT fx,
                          const ct_real *CT_RESTRICT fy, const ct_real *CT_RESTRICT fz,
                          ct_idx nnode, ct_real *CT_RESTRICT fxn, ct_real *CT_RESTRICT fyn,
                          ct_real *CT_RESTRICT fzn);
int ct_assemble_gather(ct_assemble_ws *ws, const ct_asm_map *map,
                       const ct_real *const w[], const ct_real *CT_RESTRICT fx,
                       const ct_real *CT_RESTRICT fy, const ct_real *CT_RESTRICT fz,
                       ct_idx nnode, ct_real *CT_RESTRICT fxn, ct_real *CT_RESTRICT fyn,
                       ct_real *CT_RESTRICT fzn);
int ct_assemble_serial(const ct_asm_map *map, const ct_real *const w[],
                       const ct_real *CT_RESTRICT fx, const ct_real *CT_RESTRICT fy,
                       const ct_real *CT_RESTRICT fz, ct_idx nnode, ct_real *CT_RESTRICT fxn,
                       ct_real *CT_RESTRICT fyn, ct_real *CT_RESTRICT fzn);

/*
 * Deterministic sum of v[0..n-1] (e.g. contact or friction energies): at
 * most 256 blocks whose bounds depend on n alone (never on the thread count)
 * are summed in parallel, each in index order and in double, then the block
 * sums are added in block order. Bit-identical for any thread count; call it
 * outside a parallel region.
 */
double ct_sum_fixed(int64_t n, const ct_real *CT_RESTRICT v);

#ifdef __cplusplus
}
#endif

#endif /* CT_ASSEMBLE_H */
