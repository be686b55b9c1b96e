/*
 * loads.c -- nodal forces and pressures with their time functions, and the
 * work they do (loads.h).
 */
#include "loads.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One entry of the scene: a force on nodes or a pressure on segments. */
typedef struct ctd_load {
    int kind;                /* CTD_BC_FORCE or CTD_BC_PRESSURE */
    ct_idx n;                /* nodes or segments */
    ct_idx *idx;             /* slots of the nodes (force), or */
    ct_idx *q[4];            /* slots of the segment corners (pressure) */
    double value[3];         /* force per node, or the pressure in value[0] */
    const double (*curve)[2];
    unsigned ncurve;
} ctd_load;

double ctd_loads_factor(const double (*curve)[2], unsigned n, double t)
{
    if (n == 0)
        return 1.0;
    if (t <= curve[0][0])
        return curve[0][1];
    for (unsigned k = 1; k < n; k++)
        if (t < curve[k][0]) {
            double a = (t - curve[k - 1][0]) / (curve[k][0] - curve[k - 1][0]);
            return curve[k - 1][1] + a * (curve[k][1] - curve[k - 1][1]);
        }
    return curve[n - 1][1];
}

void ctd_loads_destroy(ctd_loads *L)
{
    if (!L)
        return;
    for (int i = 0; i < L->nload; i++) {
        free(L->load[i].idx);
        for (int a = 0; a < 4; a++)
            free(L->load[i].q[a]);
    }
    free(L->load);
    free(L->node);
    free(L->slot);
    for (int d = 0; d < 3; d++) {
        ct_free(L->f[d]);
        ct_free(L->fprev[d]);
        ct_free(L->xprev[d]);
    }
    memset(L, 0, sizeof *L);
}

static int fail(ctd_loads *L, char *err, size_t len, int code, const ctd_scene *sc,
                const ctd_scene_bc *bc, unsigned i, const char *what)
{
    if (err && len)
        snprintf(err, len, "%s:%d: boundary[%u] (%s): %s", sc->path, bc->line, i, bc->kind_name,
                 what);
    ctd_loads_destroy(L);
    return code;
}

/* A selection that selects nothing: the field's path, as the scene's
 * errors name it (model.c says the same of the other conditions). */
static int fail_empty(ctd_loads *L, char *err, size_t len, const ctd_scene *sc,
                      const ctd_scene_bc *bc, unsigned i, const char *field, const char *what)
{
    if (err && len)
        snprintf(err, len, "%s:%d: boundary[%u].%s: selects no %s (kind %s)", sc->path, bc->line,
                 i, field, what, bc->kind_name);
    ctd_loads_destroy(L);
    return CT_ERR_ARG;
}

/* Give node i a slot (the order of first appearance). */
static ct_idx slot_of(ctd_loads *L, ct_idx i)
{
    if (L->slot[i] < 0) {
        L->slot[i] = L->nnode;
        L->node[L->nnode++] = i;
    }
    return L->slot[i];
}

int ctd_loads_init(ctd_loads *L, const ctd_model *m, char *err, size_t errlen)
{
    memset(L, 0, sizeof *L);
    const ctd_scene *sc = m->scene;
    unsigned nl = 0;
    for (unsigned i = 0; i < sc->boundary_count; i++)
        nl += sc->boundary[i].kind == CTD_BC_FORCE || sc->boundary[i].kind == CTD_BC_PRESSURE;
    if (nl == 0)
        return CT_OK;
    const ct_idx nn = m->mesh.nodes.n;
    L->load = calloc(nl, sizeof *L->load);
    L->slot = malloc(sizeof(ct_idx) * ((size_t)nn + 1));
    L->node = malloc(sizeof(ct_idx) * ((size_t)nn + 1));
    if (!L->load || !L->slot || !L->node) {
        ctd_loads_destroy(L);
        return CT_ERR_NOMEM;
    }
    for (ct_idx i = 0; i < nn; i++)
        L->slot[i] = -1;
    for (unsigned i = 0; i < sc->boundary_count; i++) {
        const ctd_scene_bc *bc = &sc->boundary[i];
        if (bc->kind != CTD_BC_FORCE && bc->kind != CTD_BC_PRESSURE)
            continue;
        ctd_load *ld = &L->load[L->nload++];
        ld->kind = bc->kind;
        ld->curve = (const double(*)[2])bc->curve;
        ld->ncurve = bc->curve ? bc->curve_count : 0;
        char msg[512];
        int rc;
        if (bc->kind == CTD_BC_FORCE) {
            ct_nodeset ns = {0, NULL};
            if ((rc = ctd_model_select_nodes(m, bc->nodes, &ns, msg, sizeof msg)) != CT_OK)
                return fail(L, err, errlen, rc, sc, bc, i, msg);
            ld->n = ns.n;
            ld->idx = malloc(sizeof(ct_idx) * ((size_t)ns.n + 1));
            if (!ld->idx) {
                ct_nodeset_destroy(&ns);
                return fail(L, err, errlen, CT_ERR_NOMEM, sc, bc, i, "out of memory");
            }
            for (ct_idx k = 0; k < ns.n; k++)
                ld->idx[k] = slot_of(L, ns.node[k]);
            ct_nodeset_destroy(&ns);
            for (int d = 0; d < 3; d++)
                ld->value[d] = bc->value[d];
            if (ld->n == 0)
                return fail_empty(L, err, errlen, sc, bc, i, "nodes", "node");
        } else {
            ct_surface su = {0, NULL};
            if ((rc = ctd_model_select_surface(m, bc->surface, &su, msg, sizeof msg)) != CT_OK)
                return fail(L, err, errlen, rc, sc, bc, i, msg);
            ld->n = su.n;
            const ct_idx *src[4] = {m->mesh.n1, m->mesh.n2, m->mesh.n3, m->mesh.n4};
            int ok = 1;
            for (int a = 0; a < 4; a++)
                ok &= (ld->q[a] = malloc(sizeof(ct_idx) * ((size_t)su.n + 1))) != NULL;
            for (ct_idx k = 0; ok && k < su.n; k++)
                for (int a = 0; a < 4; a++)
                    ld->q[a][k] = slot_of(L, src[a][su.seg[k]]);
            ct_free(su.seg);
            if (!ok)
                return fail(L, err, errlen, CT_ERR_NOMEM, sc, bc, i, "out of memory");
            ld->value[0] = bc->pressure;
            if (ld->n == 0)
                return fail_empty(L, err, errlen, sc, bc, i, "surface", "segment");
        }
    }
    size_t n1 = (size_t)L->nnode + 1;
    for (int d = 0; d < 3; d++) {
        L->f[d] = ct_calloc(n1, sizeof(ct_real));
        L->fprev[d] = ct_calloc(n1, sizeof(ct_real));
        L->xprev[d] = ct_calloc(n1, sizeof(ct_real));
        if (!L->f[d] || !L->fprev[d] || !L->xprev[d]) {
            ctd_loads_destroy(L);
            return CT_ERR_NOMEM;
        }
    }
    return CT_OK;
}

void ctd_loads_apply(ctd_loads *L, double t, const ct_real *x, const ct_real *y,
                     const ct_real *z, ct_real *fx, ct_real *fy, ct_real *fz)
{
    if (L->nload == 0)
        return;
    const ct_idx nl = L->nnode;
    ct_real *f0 = L->f[0], *f1 = L->f[1], *f2 = L->f[2];
    for (ct_idx k = 0; k < nl; k++)
        f0[k] = f1[k] = f2[k] = 0;
    for (int i = 0; i < L->nload; i++) {
        const ctd_load *ld = &L->load[i];
        const double s = ctd_loads_factor(ld->curve, ld->ncurve, t);
        if (ld->kind == CTD_BC_FORCE) {
            const ct_real a = (ct_real)(s * ld->value[0]), b = (ct_real)(s * ld->value[1]),
                          c = (ct_real)(s * ld->value[2]);
            for (ct_idx k = 0; k < ld->n; k++) {
                f0[ld->idx[k]] += a;
                f1[ld->idx[k]] += b;
                f2[ld->idx[k]] += c;
            }
            continue;
        }
        const double p = s * ld->value[0];
        for (ct_idx k = 0; k < ld->n; k++) {
            const ct_idx q1 = ld->q[0][k], q2 = ld->q[1][k], q3 = ld->q[2][k],
                         q4 = ld->q[3][k];
            const ct_idx i1 = L->node[q1], i2 = L->node[q2], i3 = L->node[q3],
                         i4 = L->node[q4];
            const int tri = q4 == q3;
            /* Vector area: the two diagonals (quad) or two edges (triangle). */
            double ax = x[i3] - x[i1], ay = y[i3] - y[i1], az = z[i3] - z[i1];
            double bx = x[i4] - x[i2], by = y[i4] - y[i2], bz = z[i4] - z[i2];
            if (tri) {
                ax = x[i2] - x[i1], ay = y[i2] - y[i1], az = z[i2] - z[i1];
                bx = x[i3] - x[i1], by = y[i3] - y[i1], bz = z[i3] - z[i1];
            }
            const double share = -p * 0.5 / (tri ? 3.0 : 4.0);
            const ct_real gx = (ct_real)(share * (ay * bz - az * by)),
                          gy = (ct_real)(share * (az * bx - ax * bz)),
                          gz = (ct_real)(share * (ax * by - ay * bx));
            const ct_idx c[4] = {q1, q2, q3, q4};
            for (int a = 0; a < (tri ? 3 : 4); a++) {
                f0[c[a]] += gx;
                f1[c[a]] += gy;
                f2[c[a]] += gz;
            }
        }
    }
    double w = 0;
    for (ct_idx k = 0; k < nl; k++) {
        const ct_idx i = L->node[k];
        if (L->started)
            w += 0.5 * ((double)(L->fprev[0][k] + f0[k]) * (double)(x[i] - L->xprev[0][k]) +
                        (double)(L->fprev[1][k] + f1[k]) * (double)(y[i] - L->xprev[1][k]) +
                        (double)(L->fprev[2][k] + f2[k]) * (double)(z[i] - L->xprev[2][k]));
        L->fprev[0][k] = f0[k];
        L->fprev[1][k] = f1[k];
        L->fprev[2][k] = f2[k];
        L->xprev[0][k] = x[i];
        L->xprev[1][k] = y[i];
        L->xprev[2][k] = z[i];
        fx[i] += f0[k];
        fy[i] += f1[k];
        fz[i] += f2[k];
    }
    L->work += w;
    L->started = 1;
}
