/*
 * race_kernels.c -- the per-pair kernels of one contact cycle (narrow phase,
 * penalty and damping, friction, TYPE7 law, time step, coloured assembly)
 * run with 1 and with 2 threads on the same input: under ThreadSanitizer
 * any race is reported, and the two runs must give the same bytes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "meshgen.h"

#ifdef _OPENMP
#include <omp.h>
#define SET_THREADS(n) omp_set_num_threads(n)
#else
#define SET_THREADS(n) ((void)(n))
#endif

enum { NR = 24 }; /* per-pair real arrays of one cycle's output */

typedef struct cycle_out {
    ct_real *r[NR];
    uint8_t *flag;
    ct_real *fxn, *fyn, *fzn;
    double dtmin, dissip;
} cycle_out;

static void cycle(const ctd_case *c, const ct_pairs *pr, ct_quad_method m, cycle_out *o,
                  int *failures)
{
    ct_idx np = pr->n, nn = c->mesh.nodes.n;
    ct_real **r = o->r;
    ct_contact_geo g = {r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7],
                        r[8], r[9], r[10], r[11], r[12], o->flag};
    ct_narrow_stats st;
    const ct_mesh *me = &c->mesh;
    int rc = ct_narrow_node_segment(np, pr->node, pr->seg, c->mn1, c->mn2, c->mn3, c->mn4,
                                    me->nodes.x, me->nodes.y, me->nodes.z, NULL, NULL,
                                    (ct_real)(0.5 * c->h_mean), 0, 0, m, 1, &g, &st);
    if (rc) {
        printf("FAIL narrow phase: %s\n", ct_strerror(rc));
        (*failures)++;
        return;
    }
    /* Relative velocity: a fixed field, normal component from the normal. */
    ct_real *vx = r[13], *vy = r[14], *vz = r[15], *vn = r[16], *ms = r[17];
    for (ct_idx k = 0; k < np; k++) {
        vx[k] = (ct_real)(0.1 * sin(0.01 * k));
        vy[k] = (ct_real)(0.1 * cos(0.013 * k));
        vz[k] = (ct_real)-0.05;
        vn[k] = vx[k] * r[2][k] + vy[k] * r[3][k] + vz[k] * r[4][k];
        ms[k] = (ct_real)1.0;
    }
    ct_real *fx = r[18], *fy = r[19], *fz = r[20], *fn = r[21], *en = r[22], *dis = r[23];
    rc = ct_normal_force(np, r[1], r[2], r[3], r[4], vn, NULL, (ct_real)1e3, ms, NULL,
                         (ct_real)0.05, (ct_real)1e-3, fx, fy, fz, fn, en, dis);
    /* Friction history starts at zero and is advanced twice. */
    ct_real *ftx = calloc((size_t)np + 1, sizeof *ftx), *fty = calloc((size_t)np + 1, sizeof *fty),
            *ftz = calloc((size_t)np + 1, sizeof *ftz);
    for (int step = 0; step < 2 && rc == CT_OK; step++)
        rc = ct_friction_step(np, r[2], r[3], r[4], vx, vy, vz, fn, NULL, (ct_real)0.3, NULL,
                              (ct_real)1e3, (ct_real)1e-3, (ct_real)0.8, ftx, fty, ftz, dis);
    o->dissip = rc == CT_OK ? ct_friction_dissipation(np, dis) : 0;
    for (ct_idx k = 0; k < np; k++) {
        fx[k] += ftx[k];
        fy[k] += fty[k];
        fz[k] += ftz[k];
    }
    free(ftx);
    free(fty);
    free(ftz);
    /* TYPE7 law on the same penetrations, and the kinematic step. */
    ct_real *kt = r[13], *e7 = r[14], *gp = r[15];
    int32_t *f7 = calloc((size_t)np + 1, sizeof *f7);
    for (ct_idx k = 0; k < np; k++)
        gp[k] = (ct_real)(0.5 * c->h_mean);
    if (rc == CT_OK)
        rc = ct_penalty_type7(np, r[1], gp, ms, en, kt, e7, f7); /* K0 = 1 (ms) */
    ct_real dt = 0;
    ct_idx imin = 0;
    if (rc == CT_OK)
        rc = ct_dt_type7_kinematic(np, r[1], gp, vn, NULL, &dt, &imin);
    o->dtmin = (double)dt;
    free(f7);
    if (rc) {
        printf("FAIL force kernels: %s\n", ct_strerror(rc));
        (*failures)++;
        return;
    }
    /* Coloured assembly into the nodes. */
    ct_idx *s[4];
    for (int k = 0; k < 4; k++)
        s[k] = ct_calloc((size_t)np, sizeof(ct_idx));
    rc = ct_asm_seg_slots(np, pr->seg, c->main.n, c->mn1, c->mn2, c->mn3, c->mn4, s[0], s[1],
                          s[2], s[3]);
    ct_asm_map map = ct_asm_map_nodeseg(np, pr->node, s[0], s[1], s[2], s[3]);
    const ct_real *w[5] = {NULL, r[9], r[10], r[11], r[12]};
    ct_assemble_ws ws;
    ct_assemble_ws_init(&ws);
    memset(o->fxn, 0, sizeof(ct_real) * (size_t)nn);
    memset(o->fyn, 0, sizeof(ct_real) * (size_t)nn);
    memset(o->fzn, 0, sizeof(ct_real) * (size_t)nn);
    if (rc == CT_OK)
        rc = ct_assemble_prepare(&ws, CT_ASM_COLOUR, &map, nn);
    if (rc == CT_OK)
        rc = ct_assemble(&ws, CT_ASM_COLOUR, &map, w, fx, fy, fz, nn, o->fxn, o->fyn, o->fzn);
    if (rc == CT_OK) {
        /* The contract of the coloured assembly: every node receives its
         * contributions in the order (colour, block, pair, slot) of the
         * colouring, whatever the thread count. A serial sum in that order,
         * with the kernel's expressions, must give the same bytes. (Pair
         * order, the gather's, is another order: the sums agree only to
         * round-off, and bytewise only by chance.) */
        ct_real *rx = ct_calloc((size_t)nn, sizeof(ct_real));
        ct_real *ry = ct_calloc((size_t)nn, sizeof(ct_real));
        ct_real *rz = ct_calloc((size_t)nn, sizeof(ct_real));
        for (ct_idx c = 0; c < ws.ncolour; c++)
            for (ct_idx j = ws.col_off[c]; j < ws.col_off[c + 1]; j++) {
                ct_idx lo = ws.bperm[j] * ws.block;
                ct_idx hi = np - lo > ws.block ? lo + ws.block : np;
                for (ct_idx k = lo; k < hi; k++)
                    for (int sl = 0; sl < map.nslot; sl++) {
                        ct_idx n = map.slot[sl][k];
                        ct_real ww = w[sl] ? w[sl][k] * map.sign[sl] : map.sign[sl];
                        ct_real cx = ww * fx[k], cy = ww * fy[k], cz = ww * fz[k];
                        rx[n] += cx;
                        ry[n] += cy;
                        rz[n] += cz;
                    }
            }
        size_t bytes = sizeof(ct_real) * (size_t)nn;
        if (memcmp(rx, o->fxn, bytes) != 0 || memcmp(ry, o->fyn, bytes) != 0 ||
            memcmp(rz, o->fzn, bytes) != 0) {
            printf("FAIL coloured assembly differs from the serial sum in colour order\n");
            (*failures)++;
        }
        ct_free(rx);
        ct_free(ry);
        ct_free(rz);
    }
    if (rc) {
        printf("FAIL assembly: %s\n", ct_strerror(rc));
        (*failures)++;
    }
    ct_assemble_ws_destroy(&ws);
    for (int k = 0; k < 4; k++)
        ct_free(s[k]);
}

static void out_alloc(cycle_out *o, ct_idx np, ct_idx nn)
{
    for (int k = 0; k < NR; k++)
        o->r[k] = ct_calloc((size_t)np, sizeof(ct_real));
    o->flag = ct_calloc((size_t)np, 1);
    o->fxn = ct_calloc((size_t)nn, sizeof(ct_real));
    o->fyn = ct_calloc((size_t)nn, sizeof(ct_real));
    o->fzn = ct_calloc((size_t)nn, sizeof(ct_real));
}

static void out_free(cycle_out *o)
{
    for (int k = 0; k < NR; k++)
        ct_free(o->r[k]);
    ct_free(o->flag);
    ct_free(o->fxn);
    ct_free(o->fyn);
    ct_free(o->fzn);
}

void race_check_kernels(int *failures)
{
    const char *fams[] = {"folded", "plates-tri"};
    for (int f = 0; f < 2; f++) {
        ctd_case c;
        ct_diag d = {0};
        if (ctd_case_make(&c, fams[f], 3000, CTD_NUM_SHUFFLED, 9, &d) != CT_OK) {
            printf("FAIL case %s: %s\n", fams[f], d.msg);
            (*failures)++;
            continue;
        }
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.5 * c.h_mean), 0, &in);
        ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
        ct_search *s;
        ct_pairs pr;
        ct_pairs_init(&pr, 0);
        if (ct_search_init(&s, &p) != CT_OK || ct_search_run(s, &in, &pr) != CT_OK) {
            printf("FAIL search for the kernel cycle on %s\n", fams[f]);
            (*failures)++;
        }
        ct_search_destroy(s);
        for (int m = 0; m < CT_QUAD_NMETHOD; m++) {
            cycle_out o1, o2;
            out_alloc(&o1, pr.n, c.mesh.nodes.n);
            out_alloc(&o2, pr.n, c.mesh.nodes.n);
            SET_THREADS(1);
            cycle(&c, &pr, (ct_quad_method)m, &o1, failures);
            SET_THREADS(2);
            cycle(&c, &pr, (ct_quad_method)m, &o2, failures);
            int same = o1.dtmin == o2.dtmin && o1.dissip == o2.dissip &&
                       memcmp(o1.flag, o2.flag, (size_t)pr.n) == 0 &&
                       memcmp(o1.fxn, o2.fxn, sizeof(ct_real) * (size_t)c.mesh.nodes.n) == 0 &&
                       memcmp(o1.fyn, o2.fyn, sizeof(ct_real) * (size_t)c.mesh.nodes.n) == 0 &&
                       memcmp(o1.fzn, o2.fzn, sizeof(ct_real) * (size_t)c.mesh.nodes.n) == 0;
            for (int k = 0; k < NR; k++)
                same = same && memcmp(o1.r[k], o2.r[k], sizeof(ct_real) * (size_t)pr.n) == 0;
            if (!same) {
                printf("FAIL %s, %s: 1 and 2 threads give different bytes\n", fams[f],
                       ct_quad_method_name((ct_quad_method)m));
                (*failures)++;
            }
            out_free(&o1);
            out_free(&o2);
        }
        ct_pairs_destroy(&pr);
        ctd_case_destroy(&c);
    }
}
