/*
 * bench_trade_internal.h -- private declarations shared by the files of the
 * speed/accuracy trade benchmarks (bench_trade.c: scenes, buffers, dispatch
 * and registration; bench_trade_search.c, bench_trade_kernels.c,
 * bench_trade_models.c: the knobs). Not part of the bench API.
 */
#ifndef BENCH_TRADE_INTERNAL_H
#define BENCH_TRADE_INTERNAL_H

#include <stdint.h>

#include "bench_trade.h"
#include "contact.h"
#include "gbench.h"
#include "meshgen.h"

#define TR_PI 3.14159265358979323846
#define MV_STEPS 30
#define MV_TARGET 10000
#define MV_TARGET_PLATES 4000
#define ST_TARGET 20000
#define ST_SEED 12345u
#define TR_GAP 0.3    /* gap / h */
#define TR_MARGIN 0.2 /* margin / h */
#define WQ_PAIRS 100000
#define RN_TARGET 1000000 /* secondaries of the renumbering knob's shuffled plates */
#define DN_TARGET 100000  /* secondaries of the dense-leaf knob's graded mesh */
#define CL_TARGET 100000  /* secondaries of the cell-size knob's meshes */
/* The cell-size knob: the bucket grid's cell_factor settings, and the
 * families it is measured on (bench_trade_search.c). */
#define CL_NFACTOR 7
#define CL_NFAMILY 4
extern const double ctbt_cell_factors[CL_NFACTOR];
/* Row name of cell factor v: "auto" (0, the chosen grid) or the factor. */
const char *ctbt_cell_name(int v);
extern const char *const ctbt_cell_families[CL_NFAMILY];
#define SAFETY_PHASES 32

enum { K_SEARCH, K_FILTER, K_MARGIN, K_RENUM, K_DENSE, K_CELL, K_QUAD, K_PREC, K_ASM, K_STIFF,
       K_SAFETY };
enum { ASM_COLOUR, ASM_COLOUR_B1, ASM_ATOMIC, ASM_THREADBUF, ASM_GATHER, ASM_SERIAL, ASM_N };

/* MV_SHEET: the crumpled sheet in self contact (every knob of the moving
 * scenes); MV_PLATES: two plates sliding (the search knob only: a scene
 * without self contact, where the topological search's history means what
 * it was made for). */
enum { MV_SHEET, MV_PLATES, MV_NSCENE };

extern const char *const ctbt_asm_name[ASM_N];
extern const double ctbt_margins[4];
extern const double ctbt_stfacs[4];
extern const double ctbt_factors[4];
extern const char *const ctbt_mv_name[MV_NSCENE];
extern ctb_search_config ctbt_cfg;

typedef struct tdesc {
    int knob, sub, variant; /* variant: quad case 0 crumpled, 1 warped */
    struct tdesc *next;
} tdesc;

typedef struct geobuf {
    ct_idx cap;
    ct_real *r[13];
    uint8_t *flag;
    ct_contact_geo g;
} geobuf;

typedef struct movecase {
    int state; /* 0: not built, 1: ready, -1: failed */
    int scene;
    char err[256];
    ctd_case c;
    ct_idx nnode;
    double h, maxstep;
    ct_real *xs, *ys, *zs; /* MV_STEPS * nnode positions */
    ct_pairs ref[MV_STEPS];
    ct_idx *pos;
    double ref_s;
} movecase;

typedef struct statcase {
    int state;
    char err[256];
    ctd_case c;
    ct_search_input in;
    ct_pairs pairs;
    double h;
    geobuf ref; /* Newton */
} statcase;

double ctbt_now_s(void);
const char *ctbt_prec_name(void);
void ctbt_geo_free(geobuf *b);
int ctbt_geo_reserve(geobuf *b, ct_idx n);
int ctbt_narrow(const ct_search_input *in, const ct_pairs *p, ct_quad_method m, ct_real gap,
                geobuf *b, ct_narrow_stats *st);
int64_t ctbt_count_missing(const ct_idx *pos, ct_idx rn, const ct_idx *rnode,
                           const ct_idx *rseg, const ct_pairs *got, int64_t *extra);
void ctbt_mv_input(const movecase *m, int k, ct_search_input *in);
int ctbt_pingpong(int64_t it);
movecase *ctbt_mv_get(int scene);
double ctbt_mv_ref_pairs(const movecase *m);
statcase *ctbt_sc_get(void);
void ctbt_set_skip(gb_state *st, const char *what, int rc);
/* The two counters of every trade row: cost, ns per item over `it` timed
 * repetitions of `dt` seconds in all (n items each), and the accuracy
 * figure. */
void ctbt_cost_accuracy(gb_state *st, double dt, int64_t it, double n, double accuracy);
void ctbt_label(gb_state *st, const char *knob, const char *setting, const char *cost,
                const char *acc, const char *note);
void ctbt_wq_free(void);
void ctbt_as_free(void);
void ctbt_bm_search(gb_state *st, const tdesc *d);
void ctbt_bm_filter(gb_state *st, const tdesc *d);
void ctbt_bm_margin(gb_state *st, const tdesc *d);
void ctbt_bm_static_search(gb_state *st, const tdesc *d);
const char *ctbt_dense_name(int dense);
const char *ctbt_renum_name(int variant); /* 0 off, 1 auto, 2 fresh */
void ctbt_rn_free(void);
void ctbt_bm_quad(gb_state *st, const tdesc *d);
void ctbt_bm_prec(gb_state *st, const tdesc *d);
void ctbt_bm_asm(gb_state *st, const tdesc *d);
void ctbt_bm_stiff(gb_state *st, const tdesc *d);
void ctbt_bm_safety(gb_state *st, const tdesc *d);

#endif
