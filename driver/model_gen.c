/*
 * model_gen.c -- one generated mesh entry of a scene (scene.h kinds): the
 * meshgen.h generators, and the kinds that exist only for scenes (ball,
 * net, rod; numbering in model.h).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"
#include "model_internal.h"

void cti_gen_destroy(cti_gen *g)
{
    ct_mesh_destroy(&g->mesh);
    ct_free(g->hex8);
    free(g->l1);
    free(g->l2);
    memset(g, 0, sizeof *g);
}

static void translate(ct_mesh *m, const double o[3])
{
    for (ct_idx i = 0; i < m->nodes.n; i++) {
        m->nodes.x[i] += (ct_real)o[0];
        m->nodes.y[i] += (ct_real)o[1];
        m->nodes.z[i] += (ct_real)o[2];
    }
}

/* The cube [-1, 1]^3 onto the unit ball, shell by shell: the cube's
 * surface of half-side s = max(|x|, |y|, |z|) onto the sphere of radius s.
 * On its shell a point's coordinates c become s tan(pi c / (4 s)) (the
 * equi-angular cubed sphere: its cells span nearly equal angles; the
 * coordinate equal to +-s stays), then the point is scaled radially onto
 * the sphere. The map's Jacobian is bounded away from zero everywhere, so
 * the bricks keep their shape as the mesh is refined (the smooth map used
 * before, x sqrt(1 - y^2/2 - z^2/2 + y^2 z^2/3), is singular at the cube's
 * corners: its corner bricks flattened as h^2 and the stable step with
 * them). */
static void cube_to_ball(double *x, double *y, double *z)
{
    double p[3] = {*x, *y, *z};
    const double s = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
    if (!(s > 0))
        return;
    for (int k = 0; k < 3; k++)
        if (fabs(p[k]) < s)
            p[k] = s * tan(0.78539816339744830962 * p[k] / s);
    const double f = s / sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    *x = p[0] * f;
    *y = p[1] * f;
    *z = p[2] * f;
}

static int alloc_lines(cti_gen *g, int64_t n)
{
    if (n > INT32_MAX / 2)
        return CT_ERR_TOOBIG;
    g->l1 = malloc(sizeof(ct_idx) * (size_t)(n + 1));
    g->l2 = malloc(sizeof(ct_idx) * (size_t)(n + 1));
    if (!g->l1 || !g->l2)
        return CT_ERR_NOMEM;
    g->nline = (ct_idx)n;
    return CT_OK;
}

int cti_generate(cti_gen *g, const ctd_scene_generate *sg)
{
    memset(g, 0, sizeof *g);
    const int64_t *c = sg->cells_eff;
    const double *o = sg->origin;
    for (int k = 0; k < 3; k++)
        if (c[k] > INT32_MAX / 4)
            return CT_ERR_TOOBIG;
    int rc;
    switch (sg->kind) {
    case CTD_GEN_PLATE:
    case CTD_GEN_NET: {
        int nx = (int)c[0], ny = (int)c[1];
        rc = ctd_plate(&g->mesh, nx, ny, sg->size[0] / nx, sg->size[1] / ny, o,
                       sg->kind == CTD_GEN_PLATE && sg->tri);
        if (rc || sg->kind == CTD_GEN_PLATE)
            break;
        g->mesh.nseg = 0; /* the net keeps the nodes only */
        if ((rc = alloc_lines(g, (int64_t)nx * (ny + 1) + (int64_t)(nx + 1) * ny)))
            break;
        ct_idx k = 0;
        for (int j = 0; j <= ny; j++)
            for (int i = 0; i < nx; i++, k++) {
                g->l1[k] = i + (nx + 1) * j;
                g->l2[k] = i + 1 + (nx + 1) * j;
            }
        for (int j = 0; j < ny; j++)
            for (int i = 0; i <= nx; i++, k++) {
                g->l1[k] = i + (nx + 1) * j;
                g->l2[k] = i + (nx + 1) * (j + 1);
            }
        break;
    }
    case CTD_GEN_BLOCK: {
        double h[3] = {sg->size[0] / c[0], sg->size[1] / c[1], sg->size[2] / c[2]};
        rc = ctd_block(&g->mesh, (int)c[0], (int)c[1], (int)c[2], h, o, &g->hex8);
        break;
    }
    case CTD_GEN_BALL: {
        int n = (int)c[0];
        double h[3] = {2.0 / n, 2.0 / n, 2.0 / n}, o0[3] = {-1, -1, -1};
        rc = ctd_block(&g->mesh, n, n, n, h, o0, &g->hex8);
        if (rc)
            break;
        ct_nodes *nd = &g->mesh.nodes;
        for (ct_idx i = 0; i < nd->n; i++) {
            /* Exact grid coordinates (no accumulated round-off) before mapping. */
            ct_idx ii = i % (n + 1), jj = (i / (n + 1)) % (n + 1), kk = i / ((n + 1) * (n + 1));
            double x = -1 + 2.0 * ii / n, y = -1 + 2.0 * jj / n, z = -1 + 2.0 * kk / n;
            cube_to_ball(&x, &y, &z);
            nd->x[i] = (ct_real)(o[0] + sg->radius * x);
            nd->y[i] = (ct_real)(o[1] + sg->radius * y);
            nd->z[i] = (ct_real)(o[2] + sg->radius * z);
        }
        break;
    }
    case CTD_GEN_SPHERE:
        rc = ctd_sphere(&g->mesh, (int)c[0], sg->radius, o);
        break;
    case CTD_GEN_TUBE:
        rc = ctd_tube(&g->mesh, (int)c[0], (int)c[1], sg->radius, sg->length);
        if (!rc)
            translate(&g->mesh, o);
        break;
    case CTD_GEN_FOLDED:
        rc = ctd_folded(&g->mesh, (int)sg->layers, (int)c[0], (int)c[1], sg->h_eff,
                        sg->spacing);
        if (!rc)
            translate(&g->mesh, o);
        break;
    case CTD_GEN_ROD: {
        int n = (int)c[0];
        if ((rc = ct_mesh_init(&g->mesh, n + 1, 0)) || (rc = alloc_lines(g, n)))
            break;
        for (int k = 0; k <= n; k++) {
            double t = (double)k / n;
            g->mesh.nodes.x[k] = (ct_real)(o[0] + t * (sg->to[0] - o[0]));
            g->mesh.nodes.y[k] = (ct_real)(o[1] + t * (sg->to[1] - o[1]));
            g->mesh.nodes.z[k] = (ct_real)(o[2] + t * (sg->to[2] - o[2]));
        }
        for (int k = 0; k < n; k++) {
            g->l1[k] = k;
            g->l2[k] = k + 1;
        }
        break;
    }
    default:
        rc = CT_ERR_ARG;
    }
    if (rc)
        cti_gen_destroy(g);
    return rc;
}
