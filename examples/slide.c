/*
 * slide.c -- libcontact in an explicit code of your own: the whole contact
 * cycle (search, narrow phase, carrying pairs, forces with friction,
 * race-free assembly, contact time step) around a central-difference
 * update, through the public header alone.
 *
 * The case has an answer: nine point masses resting on a rigid floor of
 * 30 x 20 quads, launched along x at v0 = 1 m/s, slide with Coulomb
 * friction (mu = 0.3) and stop after v0^2 / (2 mu g) = 0.1699 m, having
 * dissipated their kinetic energy m v0^2 / 2 in friction, at the height
 * where K p = m g. They slide along the edges shared by two rows of quads
 * and over their vertices, where two or four pairs see the same
 * penetration and one must carry it (four would hold the mass at a
 * quarter of its penetration); each crosses 17 segments (its contact and
 * its friction history move from pair to pair) and the candidates are
 * searched again whenever the re-sort criterion asks. The program checks
 * the distance, the work, the height and that the masses stopped, and
 * exits 1 when one is off.
 *
 * Build against an installed library (make install):
 *     cc -O2 slide.c $(pkg-config --cflags --libs contact) -o slide
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"

enum { NX = 30, NY = 20, NS = 3 };                   /* floor quads, 3 x 3 masses */
enum { NFLOOR = (NX + 1) * (NY + 1), NNODE = NFLOOR + NS * NS, NSEG = NX * NY };

static const double H = 0.01;      /* floor quad size, m */
static const double MASS = 0.01;   /* each sliding mass, kg */
static const double K = 1.0e4;     /* penalty stiffness, N/m */
static const double KT = 1.0e4;    /* tangential (stick) stiffness, N/m */
static const double GAP = 0.002;   /* contact thickness, m */
static const double MARGIN = 0.003;
static const double MU = 0.3, VISS = 0.05, G = 9.81, V0 = 1.0, T_END = 0.45;

/* Per-pair arrays, grown at a re-sort when the list outgrows them. */
enum { PR_DIST, PR_PEN, PR_NX, PR_NY, PR_NZ, PR_CX, PR_CY, PR_CZ, PR_H1, PR_H2, PR_H3, PR_H4,
       PR_GAP, PR_RX, PR_RY, PR_RZ, PR_VN, PR_MS, PR_FX, PR_FY, PR_FZ, PR_FN, PR_FDIS,
       PR_PX, PR_PY, PR_PZ, PR_NREAL };
typedef struct pair_arrays {
    ct_idx cap;
    ct_real *r[PR_NREAL];
    ct_real *ft[2][3], *pprev[2]; /* states, on the old and the new list */
    ct_idx *s[4], *old_of_new, *handoff;
    uint8_t *flag, *carry;
} pair_arrays;

static void pair_arrays_free(pair_arrays *a)
{
    for (int i = 0; i < PR_NREAL; i++)
        ct_free(a->r[i]);
    for (int l = 0; l < 2; l++) {
        for (int d = 0; d < 3; d++)
            ct_free(a->ft[l][d]);
        ct_free(a->pprev[l]);
    }
    for (int i = 0; i < 4; i++)
        ct_free(a->s[i]);
    ct_free(a->old_of_new);
    ct_free(a->handoff);
    ct_free(a->flag);
    ct_free(a->carry);
    memset(a, 0, sizeof *a);
}

/* Room for n pairs; the states of both lists are kept. */
static int grow(pair_arrays *a, ct_idx n)
{
    if (n <= a->cap)
        return CT_OK;
    const size_t cap = (size_t)n + (size_t)n / 2 + 64;
    pair_arrays b = {.cap = (ct_idx)cap};
    int ok = 1;
    for (int i = 0; i < PR_NREAL; i++)
        ok &= (b.r[i] = ct_calloc(cap, sizeof(ct_real))) != NULL;
    for (int l = 0; l < 2; l++) {
        for (int d = 0; d < 3; d++)
            ok &= (b.ft[l][d] = ct_calloc(cap, sizeof(ct_real))) != NULL;
        ok &= (b.pprev[l] = ct_calloc(cap, sizeof(ct_real))) != NULL;
    }
    for (int i = 0; i < 4; i++)
        ok &= (b.s[i] = ct_calloc(cap, sizeof(ct_idx))) != NULL;
    ok &= (b.old_of_new = ct_calloc(cap, sizeof(ct_idx))) != NULL;
    ok &= (b.handoff = ct_calloc(cap, sizeof(ct_idx))) != NULL;
    ok &= (b.flag = ct_calloc(cap, 1)) != NULL;
    ok &= (b.carry = ct_calloc(cap, 1)) != NULL;
    if (!ok) {
        pair_arrays_free(&b);
        return CT_ERR_NOMEM;
    }
    for (int l = 0; l < 2 && a->cap > 0; l++) {
        for (int d = 0; d < 3; d++)
            memcpy(b.ft[l][d], a->ft[l][d], sizeof(ct_real) * (size_t)a->cap);
        memcpy(b.pprev[l], a->pprev[l], sizeof(ct_real) * (size_t)a->cap);
    }
    pair_arrays_free(a);
    *a = b;
    return CT_OK;
}

#define CHECK(call)                                                                            \
    do {                                                                                       \
        int rc_ = (call);                                                                      \
        if (rc_ != CT_OK) {                                                                    \
            fprintf(stderr, "slide: %s failed: %s\n", #call, ct_strerror(rc_));                \
            return 2;                                                                          \
        }                                                                                      \
    } while (0)

int main(void)
{
    printf("slide: libcontact %s\n", ct_build_info());
    /* The mesh: floor nodes, then the masses (secondary nodes). */
    ct_mesh mesh;
    CHECK(ct_mesh_init(&mesh, NNODE, NSEG));
    ct_nodes *nd = &mesh.nodes;
    for (int j = 0; j <= NY; j++)
        for (int i = 0; i <= NX; i++) {
            int k = j * (NX + 1) + i;
            nd->x[k] = (ct_real)(i * H), nd->y[k] = (ct_real)(j * H), nd->z[k] = 0;
        }
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) { /* counter-clockwise from +z: normal up */
            int s = j * NX + i, a = j * (NX + 1) + i;
            mesh.n1[s] = a, mesh.n2[s] = a + 1, mesh.n3[s] = a + NX + 2, mesh.n4[s] = a + NX + 1;
        }
    ct_idx sec[NS * NS], floor_nodes[NFLOOR];
    double x_start[NS * NS];
    const double z_rest = GAP - MASS * G / K; /* where K p = m g */
    for (int k = 0; k < NFLOOR; k++)
        floor_nodes[k] = k;
    for (int j = 0; j < NS; j++)
        for (int i = 0; i < NS; i++) {
            int q = j * NS + i, k = NFLOOR + q;
            sec[q] = k;
            nd->x[k] = (ct_real)(0.0253 + 0.0101 * i), x_start[q] = nd->x[k];
            nd->y[k] = (ct_real)((8 + j) * H); /* on the edges between rows of quads */
            nd->z[k] = (ct_real)z_rest;
            nd->vx[k] = (ct_real)V0;
            nd->m[k] = (ct_real)MASS;
        }
    ct_diag diag;
    if (ct_mesh_validate(&mesh, &diag) != CT_OK) {
        fprintf(stderr, "slide: bad mesh: %s\n", diag.msg);
        return 2;
    }

    /* The library's objects: a search (kept: it reuses its numbering), two
     * pair lists (old and new, for the history's remap), the assembly's
     * workspace, and the positions at the last search. */
    ct_search_params sp = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *search;
    CHECK(ct_search_init(&search, &sp));
    ct_pairs pairs[2];
    CHECK(ct_pairs_init(&pairs[0], 0));
    CHECK(ct_pairs_init(&pairs[1], 0));
    ct_assemble_ws ws;
    CHECK(ct_assemble_ws_init(&ws));
    pair_arrays pa = {0};
    ct_real *x0 = ct_calloc(NNODE, sizeof(ct_real)), *y0 = ct_calloc(NNODE, sizeof(ct_real));
    ct_real *z0 = ct_calloc(NNODE, sizeof(ct_real));
    if (!x0 || !y0 || !z0)
        return 2;
    ct_asm_map map;
    int cur = 0, first = 1, nsearch = 0;
    double friction_work = 0, t = 0, dt = 1e-3;
    long cycles = 0;

    while (t < T_END) {
        /* 1. The candidates: searched again when motion since the last
         *    search may have brought a pair within the gap unseen. */
        ct_real bound;
        if (first || ct_resort_needed(NS * NS, sec, NFLOOR, floor_nodes, x0, y0, z0, nd->x,
                                      nd->y, nd->z, (ct_real)MARGIN, &bound)) {
            int now = first ? 0 : 1 - cur;
            ct_search_input in = {NNODE, nd->x, nd->y, nd->z, NS * NS, sec, NSEG,
                                  mesh.n1, mesh.n2, mesh.n3, mesh.n4, (ct_real)GAP,
                                  (ct_real)MARGIN, 0, CT_FILTER_HULL};
            CHECK(ct_search_run(search, &in, &pairs[now]));
            const ct_pairs *np = &pairs[now], *op = &pairs[cur];
            CHECK(grow(&pa, np->n));
            CHECK(ct_asm_seg_slots(np->n, np->seg, NSEG, mesh.n1, mesh.n2, mesh.n3, mesh.n4,
                                   pa.s[0], pa.s[1], pa.s[2], pa.s[3]));
            if (!first) { /* the pair states follow their (node, segment) */
                CHECK(ct_friction_remap(op->n, op->node, op->seg, pa.ft[cur][0], pa.ft[cur][1],
                                        pa.ft[cur][2], np->n, np->node, np->seg,
                                        pa.ft[now][0], pa.ft[now][1], pa.ft[now][2],
                                        pa.old_of_new, NULL));
                CHECK(ct_pair_remap(np->n, pa.old_of_new, pa.pprev[cur], 0, pa.pprev[now]));
            }
            for (ct_idx k = 0; k < np->n; k++)
                pa.r[PR_MS][k] = nd->m[np->node[k]];
            map = ct_asm_map_nodeseg(np->n, np->node, pa.s[0], pa.s[1], pa.s[2], pa.s[3]);
            CHECK(ct_assemble_prepare(&ws, CT_ASM_COLOUR, &map, NNODE));
            memcpy(x0, nd->x, sizeof(ct_real) * NNODE);
            memcpy(y0, nd->y, sizeof(ct_real) * NNODE);
            memcpy(z0, nd->z, sizeof(ct_real) * NNODE);
            cur = now;
            first = 0;
            nsearch++;
        }
        const ct_pairs *pp = &pairs[cur];
        const ct_idx n = pp->n;
        ct_real **r = pa.r, **ft = pa.ft[cur], *pprev = pa.pprev[cur];

        /* 2. Narrow phase: distance, penetration, normal, weights. */
        ct_contact_geo geo = {r[PR_DIST], r[PR_PEN], r[PR_NX], r[PR_NY],  r[PR_NZ],
                              r[PR_CX],   r[PR_CY],  r[PR_CZ], r[PR_H1],  r[PR_H2],
                              r[PR_H3],   r[PR_H4],  r[PR_GAP], pa.flag};
        CHECK(ct_narrow_node_segment(n, pp->node, pp->seg, mesh.n1, mesh.n2, mesh.n3, mesh.n4,
                                     nd->x, nd->y, nd->z, NULL, NULL, (ct_real)GAP, 0, 0,
                                     CT_QUAD_4TRI, 0, &geo, NULL));
        /* 3. One pair carries each node (not one per segment it is near);
         *    when its contact moved to the next segment, so do its states. */
        CHECK(ct_select_pairs(n, pp->node, nd->x, nd->y, nd->z, 0, &geo, pprev, pa.carry,
                              pa.handoff, NULL));
        for (ct_idx k = 0; k < n; k++) {
            ct_idx from = pa.handoff[k];
            if (from < 0)
                continue;
            for (int d = 0; d < 3; d++)
                ft[d][k] = ft[d][from], ft[d][from] = 0;
            pprev[k] = pprev[from], pprev[from] = 0;
        }
        /* 4. Forces: relative velocity at the contact point, then the
         *    penalty with damping and Coulomb friction (history in ft). */
        CHECK(ct_relative_velocity(n, pp->node, pa.s[0], pa.s[1], pa.s[2], pa.s[3], r[PR_H1],
                                   r[PR_H2], r[PR_H3], r[PR_H4], r[PR_NX], r[PR_NY], r[PR_NZ],
                                   nd->vx, nd->vy, nd->vz, NULL, r[PR_RX], r[PR_RY], r[PR_RZ],
                                   r[PR_VN], NULL));
        CHECK(ct_pair_force_linear_coulomb(
            n, r[PR_PEN], r[PR_NX], r[PR_NY], r[PR_NZ], r[PR_RX], r[PR_RY], r[PR_RZ], r[PR_VN],
            NULL, (ct_real)K, r[PR_MS], NULL, (ct_real)VISS, NULL, (ct_real)MU, NULL,
            (ct_real)KT, (ct_real)dt, 1, r[PR_FX], r[PR_FY], r[PR_FZ], r[PR_FN], NULL, NULL,
            ft[0], ft[1], ft[2], r[PR_FDIS]));
        friction_work += ct_friction_dissipation(n, r[PR_FDIS]);
        for (ct_idx k = 0; k < n; k++) {
            r[PR_PX][k] = r[PR_FX][k] + ft[0][k];
            r[PR_PY][k] = r[PR_FY][k] + ft[1][k];
            r[PR_PZ][k] = r[PR_FZ][k] + ft[2][k];
            pprev[k] = r[PR_PEN][k];
        }
        /* 5. Assembly: colours of pairs sharing no node, no atomics. */
        memset(nd->fx, 0, sizeof(ct_real) * NNODE);
        memset(nd->fy, 0, sizeof(ct_real) * NNODE);
        memset(nd->fz, 0, sizeof(ct_real) * NNODE);
        const ct_real *const w[5] = {NULL, r[PR_H1], r[PR_H2], r[PR_H3], r[PR_H4]};
        CHECK(ct_assemble(&ws, CT_ASM_COLOUR, &map, w, r[PR_PX], r[PR_PY], r[PR_PZ], NNODE,
                          nd->fx, nd->fy, nd->fz));
        /* 6. The next step: the nodal step of the carrying pairs' springs
         *    (normal and tangential), with a safety factor. */
        for (ct_idx k = 0; k < n; k++)
            r[PR_GAP][k] = pa.carry[k] ? (ct_real)(K + KT) : 0; /* GAP reused as scratch */
        ct_real dtmin = CT_DT_NONE;
        ct_idx imin;
        CHECK(ct_dt_nodal(n, pp->node, nd->m, NULL, r[PR_GAP], NULL, &dtmin, &imin));
        double dt_new = dtmin < CT_DT_NONE ? 0.5 * dtmin : 1e-3;
        /* 7. Central difference: the masses move, the floor is fixed. */
        for (int q = 0; q < NS * NS; q++) {
            ct_idx k = sec[q];
            double im = 1.0 / nd->m[k];
            nd->vx[k] += (ct_real)(dt * nd->fx[k] * im);
            nd->vy[k] += (ct_real)(dt * nd->fy[k] * im);
            nd->vz[k] += (ct_real)(dt * (nd->fz[k] * im - G));
            nd->x[k] += (ct_real)(dt_new * nd->vx[k]);
            nd->y[k] += (ct_real)(dt_new * nd->vy[k]);
            nd->z[k] += (ct_real)(dt_new * nd->vz[k]);
        }
        t += dt_new;
        dt = dt_new;
        cycles++;
    }

    /* The answers: every mass stopped after v0^2 / (2 mu g); the friction
     * work is their kinetic energy at the start. */
    const double s_exact = V0 * V0 / (2 * MU * G), w_exact = NS * NS * 0.5 * MASS * V0 * V0;
    double s_err = 0, v_max = 0, z_err = 0;
    for (int q = 0; q < NS * NS; q++) {
        ct_idx k = sec[q];
        double s = nd->x[k] - x_start[q];
        printf("slide: mass %d: slid %.9f m, speed %.3e m/s, height %.9e m\n", q, s,
               sqrt((double)nd->vx[k] * nd->vx[k] + (double)nd->vy[k] * nd->vy[k]),
               (double)nd->z[k]);
        s_err = fmax(s_err, fabs(s - s_exact) / s_exact);
        v_max = fmax(v_max, sqrt((double)nd->vx[k] * nd->vx[k] + (double)nd->vy[k] * nd->vy[k]));
        z_err = fmax(z_err, fabs(nd->z[k] - z_rest) / (MASS * G / K));
    }
    /* Stopped, the masses still swing on the stick spring, loaded to
     * mu m g when they stopped: speeds up to mu g sqrt(m / kt). */
    const double v_stick = MU * G * sqrt(MASS / KT);
    double w_err = fabs(friction_work - w_exact) / w_exact;
    printf("slide: %ld cycles, %d searches, t = %.4f s\n", cycles, nsearch, t);
    printf("slide: sliding distance: largest relative error %.2e against v0^2/(2 mu g) = "
           "%.6f m\n", s_err, s_exact);
    printf("slide: friction work %.6e J against m v0^2/2 = %.6e J (relative error %.2e)\n",
           friction_work, w_exact, w_err);
    printf("slide: largest speed at the end %.2e m/s (the stick spring's swing: up to %.2e)\n",
           v_max, v_stick);
    printf("slide: height: largest departure from rest %.2e of the static penetration m g/K\n",
           z_err);
    int ok = s_err < 0.01 && w_err < 0.01 && v_max < 1.5 * v_stick && z_err < 0.01;
    printf("slide: verification %s\n", ok ? "passed" : "FAILED");

    ct_free(x0), ct_free(y0), ct_free(z0);
    pair_arrays_free(&pa);
    ct_assemble_ws_destroy(&ws);
    ct_pairs_destroy(&pairs[0]);
    ct_pairs_destroy(&pairs[1]);
    ct_search_destroy(search);
    ct_mesh_destroy(&mesh);
    return ok ? 0 : 1;
}
