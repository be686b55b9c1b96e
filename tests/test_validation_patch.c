/*
 * test_validation_patch.c -- validation case 6 (issue 6, suite
 * validation_patch): the contact patch test. Two elastic blocks with
 * non-matching meshes (4 x 4 x 2 bricks below, 3 x 3 x 2 above) pressed by
 * a uniform pressure sigma, supported so that the exact solution is a
 * uniform uniaxial stress -sigma (scene tests/data/validation/
 * patch_blocks.yaml). A contact discretisation passes the patch test when
 * it transmits that state exactly: every contact node carries sigma times
 * its tributary area and every brick has the stress -sigma.
 *
 * The classic result (Taylor & Papadopoulos, "On a patch test for contact
 * problems in two dimensions", in Wriggers & Wagner (eds.), Nonlinear
 * Computational Mechanics, Springer 1991; Zavarise & De Lorenzis, Comput.
 * Methods Appl. Mech. Eng. 198 (2009) 3428): one-pass node-to-segment
 * contact fails the patch test on non-matching meshes; two passes can pass
 * it for some meshes, not all, and over-constrain others. We measure four interfaces on the same blocks:
 * TYPE5 and TYPE24 nodes to surface (one pass: the upper block's bottom
 * nodes against the lower block's top face) and TYPE3 and TYPE24 surface to
 * surface (two passes). Quasi-static: the pressure is ramped smoothly over
 * ten periods of the lowest mode and held; the figures are means over the
 * last 100 us of the hold, and the spread of the total contact force over
 * that window is the dynamic error left.
 *
 * Figures: the nodal contact pressure (the z contact force of a node over
 * its tributary area, on each contact face) against sigma: the largest
 * deviation and the standard deviation; the brick stress s_zz (from the
 * mean displacement gradient of each brick, Hooke's law) against -sigma,
 * per block. The assertions bound what we measured (a limit of the method
 * where it fails), so a change in the interfaces that moves them shows.
 */
#include "test_validation_bars.h"

#define Q_E 2.1e11
#define Q_NU 0.3
#define Q_SIGMA 2.1e8
#define Q_SIDE 0.02
#define Q_T_AVG 2.0e-4

/* The window sums of one run. */
typedef struct patch_obs {
    vb_nodes up, lo;       /* the contact faces: upper block bottom, lower block top */
    int n;
    double *fz, *ux, *uy, *uz; /* [nnode] sums of the contact force and displacements */
    const ct_real *X, *Y, *Z;
    double ftot_min, ftot_max;
} patch_obs;

static void patch_observe(void *ctx, const ctd_solver *s)
{
    patch_obs *o = ctx;
    if (s->time < Q_T_AVG)
        return;
    o->n++;
    double ftot = 0;
    for (ct_idx i = 0; i < s->nnode; i++) {
        o->fz[i] += s->w->fcz[i];
        o->ux[i] += s->x[i] - o->X[i];
        o->uy[i] += s->y[i] - o->Y[i];
        o->uz[i] += s->z[i] - o->Z[i];
    }
    for (int k = 0; k < o->up.n; k++)
        ftot += s->w->fcz[o->up.i[k]];
    o->ftot_min = fmin(o->ftot_min, ftot);
    o->ftot_max = fmax(o->ftot_max, ftot);
}

static int z_between(double x, double y, double z, const void *arg)
{
    (void)x, (void)y;
    const double *b = arg;
    return z > b[0] && z < b[1];
}

/* Pressure on a face of an n x n grid over the block's side: the mean
 * contact force of each node over its tributary area, against sigma
 * (sign: the upper face is pushed up, the lower face down). */
typedef struct stat {
    double dev_max, sd, mean;
} stat;

static stat face_pressure(const patch_obs *o, const vb_nodes *f, int ncell, double sign,
                          FILE *csv, int col, int ncol)
{
    double a = Q_SIDE / ncell, sum = 0, sum2 = 0, dmax = 0;
    for (int k = 0; k < f->n; k++) {
        ct_idx i = f->i[k];
        int ix = (int)lround(o->X[i] / a), iy = (int)lround(o->Y[i] / a);
        double wx = (ix == 0 || ix == ncell) ? 0.5 : 1, wy = (iy == 0 || iy == ncell) ? 0.5 : 1;
        double p = sign * o->fz[i] / o->n / (a * a * wx * wy) / Q_SIGMA;
        sum += p;
        sum2 += (p - 1) * (p - 1);
        dmax = fmax(dmax, fabs(p - 1));
        if (csv) {
            /* One row per node: x (mm, each run shifted by 0.25 mm so that
             * the runs' points stand side by side), y (mm), then this
             * run's column. */
            fprintf(csv, "%.6g,%.6g", o->X[i] * 1e3 + 0.25 * (col - 0.5 * (ncol - 1)),
                    o->Y[i] * 1e3);
            for (int c = 0; c < ncol; c++)
                fprintf(csv, c == col ? ",%.6g" : ",nan", p);
            fputc('\n', csv);
        }
    }
    stat st = {dmax, sqrt(sum2 / f->n), sum / f->n};
    return st;
}

/* The stress s_zz of each brick of element set `set` from its mean
 * displacement gradient (a box: the gradient at the centre), against
 * -sigma. */
static stat block_stress(const patch_obs *o, const ctd_model *m, int set, FILE *csv, int col,
                         int ncol)
{
    const ctd_brick *b = &m->set[set].brick;
    double lam = Q_E * Q_NU / ((1 + Q_NU) * (1 - 2 * Q_NU)), mu = Q_E / (2 * (1 + Q_NU));
    double sum = 0, sum2 = 0, dmax = 0;
    for (ct_idx e = 0; e < b->n; e++) {
        const ct_idx *q = b->conn + 8 * (int64_t)e;
        double c[3] = {0, 0, 0}, L[3];
        for (int a = 0; a < 8; a++) {
            c[0] += o->X[q[a]] / 8;
            c[1] += o->Y[q[a]] / 8;
            c[2] += o->Z[q[a]] / 8;
        }
        L[0] = 2 * fabs(o->X[q[0]] - c[0]);
        L[1] = 2 * fabs(o->Y[q[0]] - c[1]);
        L[2] = 2 * fabs(o->Z[q[0]] - c[2]);
        double g[3] = {0, 0, 0}; /* du/dx, dv/dy, dw/dz */
        for (int a = 0; a < 8; a++) {
            double sx = o->X[q[a]] > c[0] ? 1 : -1, sy = o->Y[q[a]] > c[1] ? 1 : -1,
                   sz = o->Z[q[a]] > c[2] ? 1 : -1;
            g[0] += o->ux[q[a]] / o->n * sx / (4 * L[0]);
            g[1] += o->uy[q[a]] / o->n * sy / (4 * L[1]);
            g[2] += o->uz[q[a]] / o->n * sz / (4 * L[2]);
        }
        double szz = lam * (g[0] + g[1] + g[2]) + 2 * mu * g[2];
        double r = -szz / Q_SIGMA;
        if (csv) {
            /* One row per brick: its centre's z (mm, shifted by 0.2 mm per
             * run as above) and x (mm), this run's column. */
            fprintf(csv, "%.6g,%.6g", c[2] * 1e3 + 0.2 * (col - 0.5 * (ncol - 1)), c[0] * 1e3);
            for (int k = 0; k < ncol; k++)
                fprintf(csv, k == col ? ",%.6g" : ",nan", r);
            fputc('\n', csv);
        }
        sum += r;
        sum2 += (r - 1) * (r - 1);
        dmax = fmax(dmax, fabs(r - 1));
    }
    stat st = {dmax, sqrt(sum2 / b->n), sum / b->n};
    return st;
}

/* The interfaces measured: the file's TYPE5 card (Stfac 0.2, the series
 * law, VisS 0.3) and TYPE3 with the same card, both also at Stfac 1;
 * TYPE24 with its default stiffness (Istf 0: the mean of the face and node
 * stiffnesses, Stfac 1) and the same damping VisS 0.3 (not its default
 * 1.0: see the section text), nodes to surface (the secondary selection
 * without its part: nodes by position only) and surface to surface. */
typedef struct variant {
    const char *name, *col;
    int type, nts;
    double stfac;
    /* Upper bounds asserted on the standard deviations (relative to sigma)
     * of the nodal pressure on the upper and lower contact faces and of the
     * brick stress in the upper and lower blocks: the values measured when
     * the case was written (double precision; section text), plus 25 %. */
    double bound[4];
} variant;

static const variant var[] = {
    {"TYPE5 one pass, Stfac 0.2", "TYPE5", 5, 1, 0.2, {0.37, 0.93, 0.15, 0.37}},
    {"TYPE5 one pass, Stfac 1", "TYPE5_Stfac1", 5, 1, 1.0, {0.092, 0.54, 0.044, 0.23}},
    {"TYPE24 nodes to surface", "TYPE24_nts", 24, 1, 1.0, {0.053, 0.45, 0.017, 0.19}},
    {"TYPE3 two passes, Stfac 0.2", "TYPE3", 3, 0, 0.2, {0.30, 0.39, 0.12, 0.165}},
    /* The two-pass bounds were re-measured when the stiffness blending
     * began to judge a penetration jump against |v_rel| dt instead of
     * |v_n| dt: a quasi-static contact then no longer blends on noise, and
     * TYPE24 surface to surface stopped moving with the step (0.057 to
     * 0.092 on the lower face over dt_scale 0.8 .. 0.95 before, three
     * digits steady now). */
    {"TYPE3 two passes, Stfac 1", "TYPE3_Stfac1", 3, 0, 1.0, {0.106, 0.136, 0.045, 0.055}},
    {"TYPE24 surface to surface", "TYPE24_s2s", 24, 0, 1.0, {0.084, 0.078, 0.029, 0.028}},
};
#define V_N ((int)(sizeof var / sizeof var[0]))

typedef struct patch_res {
    stat up, lo, s_up, s_lo;
    double total, dyn;
} patch_res;

static patch_res run_patch(int v, FILE *csv_up, FILE *csv_lo, FILE *csv_s)
{
    vb_run r;
    vb_load(&r, "patch_blocks.yaml");
    ctd_scene_interface *f = &r.sc->interfaces[0];
    f->type = var[v].type;
    f->Stfac = var[v].stfac;
    if (var[v].type == 24) {
        f->Istf = 0;
        f->VisS = 0.3;
        if (var[v].nts)
            f->secondary->part = 0;
    }
    patch_obs o;
    memset(&o, 0, sizeof o);
    o.ftot_min = INFINITY;
    o.ftot_max = -INFINITY;
    vb_start(&r, patch_observe, &o);
    ct_idx nn = r.m.mesh.nodes.n;
    o.fz = calloc((size_t)nn, sizeof(double));
    o.ux = calloc((size_t)nn, sizeof(double));
    o.uy = calloc((size_t)nn, sizeof(double));
    o.uz = calloc((size_t)nn, sizeof(double));
    cr_assert(o.fz && o.ux && o.uy && o.uz);
    o.X = r.m.mesh.nodes.x;
    o.Y = r.m.mesh.nodes.y;
    o.Z = r.m.mesh.nodes.z;
    const double bu[2] = {5e-8, 1e-5}, bl[2] = {-1e-5, 1e-8};
    o.up = vb_mesh_nodes(&r.m, 1, z_between, bu);
    o.lo = vb_mesh_nodes(&r.m, 0, z_between, bl);
    cr_assert(o.up.n == 16 && o.lo.n == 25);
    vb_go(&r);
    cr_assert(o.n > 100);
    patch_res x;
    x.up = face_pressure(&o, &o.up, 3, 1.0, csv_up, v, V_N);
    x.lo = face_pressure(&o, &o.lo, 4, -1.0, csv_lo, v, V_N);
    x.s_lo = block_stress(&o, &r.m, 0, csv_s, v, V_N);
    x.s_up = block_stress(&o, &r.m, 1, csv_s, v, V_N);
    double ftot = 0;
    for (int k = 0; k < o.up.n; k++)
        ftot += o.fz[o.up.i[k]] / o.n;
    x.total = ftot / (Q_SIGMA * Q_SIDE * Q_SIDE);
    x.dyn = (o.ftot_max - o.ftot_min) / 2 / ftot;
    free(o.fz);
    free(o.ux);
    free(o.uy);
    free(o.uz);
    free(o.up.i);
    free(o.lo.i);
    vb_free(&r);
    return x;
}

Test(validation_patch, nonmatching_blocks)
{
    char head[256];
    int len = snprintf(head, sizeof head, "x_mm,y_mm");
    for (int v = 0; v < V_N; v++)
        len += snprintf(head + len, sizeof head - (size_t)len, ",%s", var[v].col);
    FILE *cu = ctv_csv("patch_pressure_upper", head);
    FILE *cl = ctv_csv("patch_pressure_lower", head);
    memcpy(head, "z_mm,x_mm", 9);
    FILE *cs = ctv_csv("patch_stress", head);
    const char *cn = "6 patch test";
    patch_res res[V_N];
    for (int v = 0; v < V_N; v++) {
        patch_res x = res[v] = run_patch(v, cu, cl, cs);
        char q[160], note[256];
        /* Equilibrium: the contact carries the load (the window's mean). */
        snprintf(q, sizeof q, "%s: contact force / (sigma A)", var[v].name);
        snprintf(note, sizeof note, "mean over 200-300 us; dynamic spread +-%.2g", x.dyn);
        double e_tot = ctv_result(cn, q, x.total, 1.0, 2e-3, note);
        cr_expect(e_tot < 2e-3, "%s: contact force %.6f sigma A", var[v].name, x.total);
        cr_expect(x.dyn < 0.01, "%s: the contact force still swings by %.3g", var[v].name,
                  x.dyn);
        const stat *st[4] = {&x.up, &x.lo, &x.s_up, &x.s_lo};
        const char *what[4] = {"upper face pressure", "lower face pressure",
                               "upper block stress s_zz", "lower block stress s_zz"};
        for (int k = 0; k < 4; k++) {
            snprintf(q, sizeof q, "%s: %s, std dev / sigma", var[v].name, what[k]);
            snprintf(note, sizeof note, "largest deviation %.3g; asserted below %.3g "
                     "(uniform in the exact solution)", st[k]->dev_max, var[v].bound[k]);
            ctv_result(cn, q, st[k]->sd, 0.0, 0, note);
            cr_expect(st[k]->sd < var[v].bound[k], "%s: %s std dev %.4f, bound %.4f",
                      var[v].name, what[k], st[k]->sd, var[v].bound[k]);
        }
        /* One pass fails the patch test (Taylor & Papadopoulos): the main
         * face's pressure is far from uniform. */
        if (var[v].nts)
            cr_expect(x.lo.sd > 0.1, "%s: the main face is uniform to %.3g", var[v].name,
                      x.lo.sd);
    }
    /* Two passes do better than one with the same stiffness, on the main
     * face and in the main block. */
    cr_expect(res[5].lo.sd < res[2].lo.sd / 3 && res[5].s_lo.sd < res[2].s_lo.sd / 3,
              "TYPE24 surface to surface: %.4f, %.4f; nodes to surface %.4f, %.4f",
              res[5].lo.sd, res[5].s_lo.sd, res[2].lo.sd, res[2].s_lo.sd);
    cr_expect(res[4].lo.sd < res[1].lo.sd / 3 && res[4].s_lo.sd < res[1].s_lo.sd / 3,
              "TYPE3 Stfac 1: %.4f, %.4f; TYPE5 Stfac 1: %.4f, %.4f", res[4].lo.sd,
              res[4].s_lo.sd, res[1].lo.sd, res[1].s_lo.sd);
    char series[1024];
    for (int f = 0; f < 2; f++) {
        int n = 0;
        for (int v = 0; v < V_N; v++)
            n += snprintf(series + n, sizeof series - (size_t)n, "%s1,%d,points,%s",
                          v ? ";" : "", v + 3, var[v].name);
        ctv_plot(f ? "patch_pressure_lower" : "patch_pressure_upper",
                 f ? "Patch test: nodal contact pressure on the lower (main) face"
                   : "Patch test: nodal contact pressure on the upper (secondary) face",
                 "node x (mm; the runs side by side, 0.25 mm apart)",
                 "contact force / (tributary area x sigma); exact 1", series, "");
    }
    {
        int n = 0;
        for (int v = 0; v < V_N; v++)
            n += snprintf(series + n, sizeof series - (size_t)n, "%s1,%d,points,%s",
                          v ? ";" : "", v + 3, var[v].name);
        ctv_plot("patch_stress", "Patch test: brick stress (zz) against the applied pressure",
                 "brick centre z (mm; contact plane at 0; the runs 0.2 mm apart)",
                 "-(stress zz) / sigma; exact 1", series, "");
    }
    if (cu)
        fclose(cu);
    if (cl)
        fclose(cl);
    if (cs)
        fclose(cs);
}
