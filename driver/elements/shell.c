/*
 * shell.c -- set-up of the thin shell (shell.h): triangles from the input
 * elements, reference geometry, interior-edge hinges, the node->slot map,
 * lumped masses and the stable time step. The forces are in shell_forces.c.
 *
 * Bending calibration. The hinge stiffness is k_h = k_b |e0| / h_e with
 * h_e = (A_A + A_B) / |e0| (the mean height of the two triangles over the
 * edge) and k_b = D / 2. Take a mesh of square cells of side h and the
 * deflection w = (a x^2 + 2 b x y + c y^2) / 2 (curvatures a, c, twist b).
 * The linear interpolant on each triangle has a constant slope; the
 * dihedral angle across an edge is the jump of the slope normal to it.
 * With one split (diagonal (0,0)-(h,h)) the edges parallel to y have
 * theta = (a + b) h, those parallel to x (c + b) h, the diagonals
 * sqrt(2) b h, so the energy density is (D/2) ((a+b)^2 + (c+b)^2 + 4 b^2):
 * bending couples to twist, and a cantilever strip (b, c free) comes out
 * 1/0.8 too soft, more on narrow strips (measured 1.55 on 40 x 2 cells).
 * With both splits averaged (quads; no hinge on the diagonals) the four
 * triangle pairs across an edge parallel to y have slope jumps a + b, a,
 * a, a - b, mean square a^2 + b^2 / 2, and the density is
 *   W = (D / 2) (a^2 + c^2 + b^2),
 * against the plate's (D / 2) (a^2 + c^2 + 2 nu a c + 2 (1 - nu) b^2):
 * exact for cylindrical bending about either mesh axis (any nu), no
 * Poisson coupling between the two curvatures (a strip bends as the wide
 * plate, with D), and a twist stiffness 1 / (2 (1 - nu)) of the plate's
 * (0.71 for nu = 0.3). Meshes of triangles keep the one-split behaviour.
 *
 * Stable time step. For central differences dt <= 2 / omega_max, with
 * omega_max^2 = lambda_max(M^-1 K). By the block Gershgorin theorem
 * lambda_max <= max_a r_a / m_a with r_a = sum_b ||K_ab||_2 over the 3 x 3
 * nodal blocks, and r_a is bounded by the sum of the elements' own block
 * norms. Both stiffnesses are taken at the reference configuration:
 *  - membrane (linear plane stress, local frame, shape gradients g_a):
 *    K_ab[i][k] = V (lambda' g_ai g_bk + mu (g_a . g_b) delta_ik + mu g_ak g_bi);
 *  - hinge: K = 2 k_h grad(theta) grad(theta)^T, ||K_ab|| = 2 k_h |g_a| |g_b|.
 * For a 1-D bar of lumped masses this gives exactly L / c. For a uniform
 * mesh it amounts to dt ~ h_min / c for the membrane and, for the bending
 * alone, to dt ~ h^2 / (C sqrt(D / (rho t))) with C between 4 (1-D) and
 * the 2-D value the sum produces; membrane and bending add in omega^2.
 * The node stiffness reported for DESIGN.md's dt = sqrt(2 m / K) is
 * K_a = r_a / 2 (then sqrt(2 m_a / K_a) = 2 / sqrt(r_a / m_a)).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ct_internal.h"
#include "shell.h"

/* A triangle is degenerate when twice its area is at most this times the
 * square of its longest edge (as ct_mesh_validate). */
#ifdef CT_SINGLE
#define CTI_SHELL_AREA_TOL 1e-6
#else
#define CTI_SHELL_AREA_TOL 1e-12
#endif

/* One triangle edge, for pairing elements across edges. */
typedef struct cti_shell_edge {
    int64_t key; /* min(a, b) * nnode + max(a, b) */
    ct_idx elem; /* input element of the triangle */
    ct_idx tri;
} cti_shell_edge;

static int cti_shell_edge_cmp(const void *pa, const void *pb)
{
    const cti_shell_edge *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    if (a->elem != b->elem)
        return a->elem < b->elem ? -1 : 1;
    return (a->tri > b->tri) - (a->tri < b->tri);
}

void ctd_shell_destroy(ctd_shell *s)
{
    if (!s)
        return;
    void *arrs[] = {s->t1, s->t2, s->t3, s->tri_elem, s->tri_vol, s->b11, s->b12,
                    s->b22, s->tri_w, s->elem_t, s->h1, s->h2, s->h3, s->h4, s->theta0, s->hk,
                    s->sx, s->sy, s->sz, s->slot_off, s->slot, s->e_blk, s->node_k,
                    s->node_m, s->snode, s->hta, s->htb, s->hsa, s->hsb, s->nx, s->ny,
                    s->nz, s->il, s->hc, s->te};
    for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++)
        ct_free(arrs[i]);
    memset(s, 0, sizeof *s);
}

/* Largest singular value of a 2 x 2 matrix. */
static double cti_shell_norm2(double a, double b, double c, double d)
{
    double f = a * a + b * b + c * c + d * d, det = a * d - b * c;
    double disc = f * f - 4 * det * det;
    return sqrt(0.5 * (f + sqrt(disc > 0 ? disc : 0)));
}

/* Reference data of triangle t; CT_ERR_DEGENERATE for a zero area. */
static int cti_shell_tri_ref(ctd_shell *s, ct_idx t, const ct_real *x, const ct_real *y,
                             const ct_real *z, double lam, double mu, double *r)
{
    ct_idx i1 = s->t1[t], i2 = s->t2[t], i3 = s->t3[t];
    double d1[3] = {(double)x[i2] - x[i1], (double)y[i2] - y[i1], (double)z[i2] - z[i1]};
    double d2[3] = {(double)x[i3] - x[i1], (double)y[i3] - y[i1], (double)z[i3] - z[i1]};
    double d3[3] = {d2[0] - d1[0], d2[1] - d1[1], d2[2] - d1[2]};
    double n[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                   d1[0] * d2[1] - d1[1] * d2[0]};
    double l1 = sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]);
    double l2 = sqrt(d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]);
    double l3 = sqrt(d3[0] * d3[0] + d3[1] * d3[1] + d3[2] * d3[2]);
    double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double lmax = fmax(l1, fmax(l2, l3));
    double tol = CTI_SHELL_AREA_TOL * lmax * lmax;
    if (!(ln > tol))
        return CT_ERR_DEGENERATE;
    /* Local frame: e1 along d1, e2 = n x e1 / |n|. */
    double e1[3] = {d1[0] / l1, d1[1] / l1, d1[2] / l1};
    double e2[3] = {(n[1] * e1[2] - n[2] * e1[1]) / ln, (n[2] * e1[0] - n[0] * e1[2]) / ln,
                    (n[0] * e1[1] - n[1] * e1[0]) / ln};
    double D11 = l1, D12 = d2[0] * e1[0] + d2[1] * e1[1] + d2[2] * e1[2];
    double D22 = d2[0] * e2[0] + d2[1] * e2[1] + d2[2] * e2[2];
    double b11 = 1 / D11, b12 = -D12 / (D11 * D22), b22 = 1 / D22;
    double th = s->elem_t[s->tri_elem[t]];
    double V = 0.5 * ln * th * s->tri_w[t];
    s->b11[t] = (ct_real)b11;
    s->b12[t] = (ct_real)b12;
    s->b22[t] = (ct_real)b22;
    s->tri_vol[t] = (ct_real)V;
    /* Lumped mass and the membrane Gershgorin sums. */
    double mm = s->rho * V / 3;
    double g[3][2] = {{-b11, -(b12 + b22)}, {b11, b12}, {0, b22}};
    const ct_idx nd[3] = {i1, i2, i3};
    for (int a = 0; a < 3; a++) {
        s->node_m[nd[a]] += (ct_real)mm;
        for (int b = 0; b < 3; b++) {
            double gab = g[a][0] * g[b][0] + g[a][1] * g[b][1];
            double k[2][2];
            for (int i = 0; i < 2; i++)
                for (int kk = 0; kk < 2; kk++)
                    k[i][kk] = V * (lam * g[a][i] * g[b][kk] + (i == kk ? mu * gab : 0) +
                                    mu * g[a][kk] * g[b][i]);
            r[nd[a]] += cti_shell_norm2(k[0][0], k[0][1], k[1][0], k[1][1]);
        }
    }
    return CT_OK;
}

/* Plate bending stiffness of the element triangle t comes from. */
static double cti_shell_D(const ctd_shell *s, ct_idx t)
{
    double th = s->elem_t[s->tri_elem[t]];
    return s->E * th * th * th / (12 * (1 - s->nu * s->nu));
}

/* The node of triangle t that is neither a nor b. */
static ct_idx cti_shell_third(const ctd_shell *s, ct_idx t, ct_idx a, ct_idx b)
{
    ct_idx c[3] = {s->t1[t], s->t2[t], s->t3[t]};
    for (int k = 0; k < 3; k++)
        if (c[k] != a && c[k] != b)
            return c[k];
    return -1;
}

/* Whether b follows a in triangle t's cyclic order (a and b corners). */
static int cti_shell_follows(const ctd_shell *s, ct_idx t, ct_idx a, ct_idx b)
{
    ct_idx c[3] = {s->t1[t], s->t2[t], s->t3[t]};
    for (int k = 0; k < 3; k++)
        if (c[k] == a)
            return c[(k + 1) % 3] == b;
    return 0;
}

/* Each triangle edge's hinge sides (te, shell.h): side A of hinge h is
 * entry h of hc, side B nhinge + h. An edge of a triangle has at most two
 * hinges (one per triangle of the other element holding it). */
static int cti_shell_edge_hinges(ctd_shell *s)
{
    const ct_idx none = 2 * s->nhinge;
    s->te = ct_calloc(6 * (size_t)s->ntri + 1, sizeof(ct_idx));
    if (!s->te)
        return CT_ERR_NOMEM;
    for (size_t k = 0; k < 6 * (size_t)s->ntri; k++)
        s->te[k] = none;
    for (ct_idx h = 0; h < s->nhinge; h++)
        for (int side = 0; side < 2; side++) {
            ct_idx t = side ? s->htb[h] : s->hta[h];
            ct_idx c[3] = {s->t1[t], s->t2[t], s->t3[t]};
            int k = 0;
            while (k < 3 && !((c[k] == s->h1[h] && c[(k + 1) % 3] == s->h2[h]) ||
                              (c[k] == s->h2[h] && c[(k + 1) % 3] == s->h1[h])))
                k++;
            if (k == 3)
                return CT_ERR_ARG; /* cannot happen: the hinge's edge is t's */
            size_t j0 = (size_t)(2 * k) * (size_t)s->ntri + (size_t)t;
            size_t j1 = j0 + (size_t)s->ntri;
            if (s->te[j1] != none)
                return CT_ERR_ARG; /* cannot happen: see above */
            s->te[s->te[j0] != none ? j1 : j0] = side ? s->nhinge + h : h;
        }
    return CT_OK;
}

/* Rest angle, stiffness and bending Gershgorin sums of hinge h between
 * triangles ta and tb: k_h = wa wb (D / 2) |e|^2 / (A_A + A_B), D the mean
 * of the two elements' plate stiffnesses, wa and wb the triangles' weights
 * (1, or 1/2 for the two splits of a quad). */
static int cti_shell_hinge_ref(ctd_shell *s, ct_idx h, ct_idx ta, ct_idx tb,
                               const ct_real *x, const ct_real *y, const ct_real *z,
                               double *r)
{
    const ct_idx nd[4] = {s->h1[h], s->h2[h], s->h3[h], s->h4[h]};
    if (nd[2] < 0 || nd[3] < 0 || nd[2] == nd[3])
        return CT_ERR_DEGENERATE; /* two triangles on the same three nodes */
    ct_real p[4][3], g[4][3];
    for (int a = 0; a < 4; a++) {
        p[a][0] = x[nd[a]];
        p[a][1] = y[nd[a]];
        p[a][2] = z[nd[a]];
    }
    ctd_shell_dihedral(p, g); /* the gradient; theta0 from ctd_shell_rest_angles */
    double ee = 0;
    for (int k = 0; k < 3; k++)
        ee += ((double)p[1][k] - p[0][k]) * ((double)p[1][k] - p[0][k]);
    /* Areas from the volumes (V = w A t). */
    double wa = s->tri_w[ta], wb = s->tri_w[tb];
    double areas = (double)s->tri_vol[ta] / (wa * s->elem_t[s->tri_elem[ta]]) +
                   (double)s->tri_vol[tb] / (wb * s->elem_t[s->tri_elem[tb]]);
    double D = 0.5 * (cti_shell_D(s, ta) + cti_shell_D(s, tb));
    double hk = wa * wb * 0.5 * D * ee / areas;
    s->hk[h] = (ct_real)hk;
    double gn[4], gsum = 0;
    for (int a = 0; a < 4; a++) {
        gn[a] = sqrt((double)g[a][0] * g[a][0] + (double)g[a][1] * g[a][1] +
                     (double)g[a][2] * g[a][2]);
        gsum += gn[a];
    }
    for (int a = 0; a < 4; a++)
        r[nd[a]] += 2 * hk * gn[a] * gsum;
    return CT_OK;
}

/* Pair the elements across edges and fill the hinges: an edge shared by
 * exactly two elements A and B gets one hinge per pair (triangle of A
 * holding the edge, triangle of B holding it): 1 for two triangles, 2 for
 * a triangle and a quad, 4 for two quads. The diagonals inside a quad
 * carry no hinge. */
static int cti_shell_hinges(ctd_shell *s, const ct_real *x, const ct_real *y,
                            const ct_real *z, double *r)
{
    ct_idx ntri = s->ntri;
    size_t ne = (size_t)3 * (size_t)ntri;
    cti_shell_edge *ed = malloc(ne * sizeof *ed + 1);
    if (!ed)
        return CT_ERR_NOMEM;
    for (ct_idx t = 0; t < ntri; t++) {
        ct_idx c[3] = {s->t1[t], s->t2[t], s->t3[t]};
        for (int k = 0; k < 3; k++) {
            int64_t a = c[k], b = c[(k + 1) % 3];
            ed[3 * t + k].key = (a < b ? a : b) * (int64_t)s->nnode + (a < b ? b : a);
            ed[3 * t + k].elem = s->tri_elem[t];
            ed[3 * t + k].tri = t;
        }
    }
    qsort(ed, ne, sizeof *ed, cti_shell_edge_cmp);
    int err = CT_OK;
    int64_t ng = 0; /* the groups of four hinges (shell.h), from pass 0 */
    for (int pass = 0; pass < 2 && err == CT_OK; pass++) {
        int64_t nh = 0, ig = 0;
        for (size_t i = 0; i < ne && err == CT_OK;) {
            size_t j = i + 1, mid = 0; /* mid: first record of the second element */
            int nel = 1;
            while (j < ne && ed[j].key == ed[i].key) {
                if (ed[j].elem != ed[j - 1].elem) {
                    nel++;
                    mid = j;
                }
                j++;
            }
            const int group = nel == 2 && mid - i == 2 && j - mid == 2;
            if (nel == 2) {
                for (size_t ia = i; ia < mid; ia++)
                    for (size_t ib = mid; ib < j; ib++) {
                        /* The hinge's number: in its group, or after them. */
                        const int64_t h =
                            group ? (int64_t)(2 * (ia - i) + (ib - mid)) * ng + ig
                                  : 4 * ng + (nh - 4 * ig);
                        if (pass == 1) {
                            ct_idx a = (ct_idx)(ed[ia].key / s->nnode);
                            ct_idx b = (ct_idx)(ed[ia].key % s->nnode);
                            s->h1[h] = a;
                            s->h2[h] = b;
                            s->h3[h] = cti_shell_third(s, ed[ia].tri, a, b);
                            s->h4[h] = cti_shell_third(s, ed[ib].tri, a, b);
                            s->hta[h] = ed[ia].tri;
                            s->htb[h] = ed[ib].tri;
                            s->hsa[h] = cti_shell_follows(s, ed[ia].tri, a, b) ? 1 : -1;
                            s->hsb[h] = cti_shell_follows(s, ed[ib].tri, a, b) ? -1 : 1;
                            err = cti_shell_hinge_ref(s, (ct_idx)h, ed[ia].tri, ed[ib].tri,
                                                      x, y, z, r);
                        }
                        nh++;
                    }
                ig += group;
            }
            i = j;
        }
        if (pass == 0) {
            if (nh > INT32_MAX / 4) {
                err = CT_ERR_TOOBIG;
                break;
            }
            s->nhinge = (ct_idx)nh;
            s->ngroup = (ct_idx)ig;
            ng = ig;
            ct_idx **ids[4] = {&s->h1, &s->h2, &s->h3, &s->h4};
            for (int k = 0; k < 4; k++)
                if (!(*ids[k] = ct_calloc((size_t)nh + 1, sizeof(ct_idx))))
                    err = CT_ERR_NOMEM;
            s->theta0 = ct_calloc((size_t)nh + 1, sizeof(ct_real));
            s->hk = ct_calloc((size_t)nh + 1, sizeof(ct_real));
            s->hta = ct_calloc((size_t)nh + 1, sizeof(ct_idx));
            s->htb = ct_calloc((size_t)nh + 1, sizeof(ct_idx));
            s->hsa = ct_calloc((size_t)nh + 1, sizeof(ct_real));
            s->hsb = ct_calloc((size_t)nh + 1, sizeof(ct_real));
            s->hc = ct_calloc(2 * (size_t)nh + 1, sizeof(ct_real));
            if (!s->theta0 || !s->hk || !s->hta || !s->htb || !s->hsa || !s->hsb || !s->hc)
                err = CT_ERR_NOMEM;
        }
    }
    free(ed);
    return err;
}

/* Keep the per-node arrays for the set's nodes only (built per model node
 * above): the nodes with a slot (the triangles' corners; a hinge's nodes
 * are corners too), their slot ranges, masses and stiffnesses, the same
 * values in the same order. */
static int compact_nodes(ctd_shell *s)
{
    const ct_idx nnode = s->nnode;
    ct_idx n = 0;
    for (ct_idx i = 0; i < nnode; i++)
        n += s->slot_off[i + 1] > s->slot_off[i];
    ct_idx *sn = ct_calloc((size_t)n + 1, sizeof *sn), *so = ct_calloc((size_t)n + 2, sizeof *so);
    ct_real *nk = ct_calloc((size_t)n + 1, sizeof *nk), *nm = ct_calloc((size_t)n + 1, sizeof *nm);
    if (!sn || !so || !nk || !nm) {
        ct_free(sn);
        ct_free(so);
        ct_free(nk);
        ct_free(nm);
        ctd_shell_destroy(s);
        return CT_ERR_NOMEM;
    }
    ct_idx j = 0;
    for (ct_idx i = 0; i < nnode; i++) {
        if (s->slot_off[i + 1] == s->slot_off[i])
            continue;
        sn[j] = i;
        so[j + 1] = s->slot_off[i + 1];
        nk[j] = s->node_k[i];
        nm[j] = s->node_m[i];
        j++;
    }
    ct_free(s->slot_off);
    ct_free(s->node_k);
    ct_free(s->node_m);
    s->nsnode = n;
    s->snode = sn;
    s->slot_off = so;
    s->node_k = nk;
    s->node_m = nm;
    return CT_OK;
}

int ctd_shell_init(ctd_shell *s, ct_idx nnode, const ct_real *x, const ct_real *y,
                   const ct_real *z, ct_idx nelem, const ct_idx *n1, const ct_idx *n2,
                   const ct_idx *n3, const ct_idx *n4, const ct_real *thick, double E,
                   double nu, double rho, double t)
{
    if (!s)
        return CT_ERR_ARG;
    memset(s, 0, sizeof *s);
    if (nnode < 0 || nelem < 0 || (nnode > 0 && (!x || !y || !z)) ||
        (nelem > 0 && (!n1 || !n2 || !n3)) || !(E > 0) || !(nu >= 0 && nu < 0.5) ||
        !(rho > 0) || !isfinite(E) || !isfinite(rho) || (!thick && !(t > 0 && isfinite(t))))
        return CT_ERR_ARG;
    s->nnode = nnode;
    s->nelem = nelem;
    s->E = E;
    s->nu = nu;
    s->rho = rho;

    /* Check the elements and count the triangles. */
    int64_t ntri = 0;
    for (ct_idx e = 0; e < nelem; e++) {
        ct_idx c[4] = {n1[e], n2[e], n3[e], n4 ? n4[e] : n3[e]};
        for (int k = 0; k < 4; k++)
            if (c[k] < 0 || c[k] >= nnode)
                return CT_ERR_RANGE;
        int quad = c[3] != c[2];
        if (c[0] == c[1] || c[0] == c[2] || c[1] == c[2] ||
            (quad && (c[3] == c[0] || c[3] == c[1])))
            return CT_ERR_DUPNODE;
        if (thick && !(thick[e] > 0 && isfinite(thick[e])))
            return CT_ERR_DEGENERATE;
        ntri += quad ? 4 : 1;
    }
    for (ct_idx i = 0; i < nnode; i++)
        if (!isfinite(x[i]) || !isfinite(y[i]) || !isfinite(z[i]))
            return CT_ERR_NONFINITE;
    if (ntri > INT32_MAX / 4 || (int64_t)nnode * nnode < 0)
        return CT_ERR_TOOBIG;
    s->ntri = (ct_idx)ntri;

    size_t nt = (size_t)ntri + 1, nn = (size_t)nnode + 1;
    s->t1 = ct_calloc(nt, sizeof(ct_idx));
    s->t2 = ct_calloc(nt, sizeof(ct_idx));
    s->t3 = ct_calloc(nt, sizeof(ct_idx));
    s->tri_elem = ct_calloc(nt, sizeof(ct_idx));
    s->tri_vol = ct_calloc(nt, sizeof(ct_real));
    s->b11 = ct_calloc(nt, sizeof(ct_real));
    s->b12 = ct_calloc(nt, sizeof(ct_real));
    s->b22 = ct_calloc(nt, sizeof(ct_real));
    s->tri_w = ct_calloc(nt, sizeof(ct_real));
    s->elem_t = ct_calloc((size_t)nelem + 1, sizeof(ct_real));
    s->node_k = ct_calloc(nn, sizeof(ct_real));
    s->node_m = ct_calloc(nn, sizeof(ct_real));
    double *r = calloc(nn, sizeof(double));
    if (!s->t1 || !s->t2 || !s->t3 || !s->tri_elem || !s->tri_vol || !s->b11 || !s->b12 ||
        !s->b22 || !s->tri_w || !s->elem_t || !s->node_k || !s->node_m || !r) {
        free(r);
        ctd_shell_destroy(s);
        return CT_ERR_NOMEM;
    }
    ct_idx q = 0;
    for (ct_idx e = 0; e < nelem; e++) {
        s->elem_t[e] = thick ? thick[e] : (ct_real)t;
        ct_idx c[4] = {n1[e], n2[e], n3[e], n4 ? n4[e] : n3[e]};
        if (c[3] == c[2]) {
            s->t1[q] = c[0];
            s->t2[q] = c[1];
            s->t3[q] = c[2];
            s->tri_w[q] = 1;
            s->tri_elem[q++] = e;
            continue;
        }
        /* A quad: both splits, (1 2 3) (1 3 4) and (1 2 4) (2 3 4), each
         * triangle with weight 1/2. */
        static const int split[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}};
        for (int k = 0; k < 4; k++) {
            s->t1[q] = c[split[k][0]];
            s->t2[q] = c[split[k][1]];
            s->t3[q] = c[split[k][2]];
            s->tri_w[q] = (ct_real)0.5;
            s->tri_elem[q++] = e;
        }
    }

    /* Reference geometry, masses, membrane stiffness sums; hinges. */
    double nu2 = nu * nu, lam = E * nu / (1 - nu2), mu = E / (2 * (1 + nu));
    int err = CT_OK;
    for (ct_idx k = 0; k < s->ntri && err == CT_OK; k++)
        err = cti_shell_tri_ref(s, k, x, y, z, lam, mu, r);
    if (err == CT_OK)
        err = cti_shell_hinges(s, x, y, z, r);
    if (err == CT_OK)
        err = cti_shell_edge_hinges(s);
    if (err == CT_OK) {
        s->nx = ct_calloc(nt, sizeof(ct_real));
        s->ny = ct_calloc(nt, sizeof(ct_real));
        s->nz = ct_calloc(nt, sizeof(ct_real));
        s->il = ct_calloc(nt, sizeof(ct_real));
        err = s->nx && s->ny && s->nz && s->il ? CT_OK : CT_ERR_NOMEM;
    }
    if (err != CT_OK) {
        free(r);
        ctd_shell_destroy(s);
        return err;
    }

    /* Slots and the node -> slot map (slots in increasing order). */
    int64_t nslot = 3 * (int64_t)s->ntri;
    if (nslot > INT32_MAX) {
        free(r);
        ctd_shell_destroy(s);
        return CT_ERR_TOOBIG;
    }
    s->nslot = (ct_idx)nslot;
    s->sx = ct_calloc((size_t)nslot + 1, sizeof(ct_real));
    s->sy = ct_calloc((size_t)nslot + 1, sizeof(ct_real));
    s->sz = ct_calloc((size_t)nslot + 1, sizeof(ct_real));
    s->slot = ct_calloc((size_t)nslot + 1, sizeof(ct_idx));
    s->slot_off = ct_calloc(nn + 1, sizeof(ct_idx));
    ct_idx nbt, nbg, nbr;
    ctd_shell_blocks(s, &nbt, &nbg, &nbr);
    size_t nblk = (size_t)nbt + (size_t)nbg + (size_t)nbr;
    s->e_blk = ct_calloc(nblk + 1, sizeof(double));
    if (!s->sx || !s->sy || !s->sz || !s->slot || !s->slot_off || !s->e_blk) {
        free(r);
        ctd_shell_destroy(s);
        return CT_ERR_NOMEM;
    }
    /* The rest angles, by the forces' own normals (which pass the edge
     * vectors through the slots). */
    if ((err = ctd_shell_rest_angles(s, x, y, z)) != CT_OK) {
        free(r);
        ctd_shell_destroy(s);
        return err;
    }
    for (int pass = 0; pass < 2; pass++) {
        /* Pass 0 counts, pass 1 fills (slot_off[i + 1] used as a cursor). */
        for (ct_idx k = 0; k < s->nslot; k++) {
            ct_idx tt = k % s->ntri;
            int c = (int)(k / s->ntri);
            ct_idx node = c == 0 ? s->t1[tt] : c == 1 ? s->t2[tt] : s->t3[tt];
            if (pass == 0)
                s->slot_off[node + 1]++;
            else
                s->slot[s->slot_off[node + 1]++] = k;
        }
        if (pass == 0) {
            /* Exclusive prefix sum shifted by one: slot_off[i + 1] = start of i. */
            ct_idx run = 0;
            for (ct_idx i = 0; i < nnode; i++) {
                ct_idx c = s->slot_off[i + 1];
                s->slot_off[i + 1] = run;
                run += c;
            }
        }
    }
    /* After the fill slot_off[i + 1] is the end of node i, slot_off[0] = 0. */

    /* Nodal stiffness and the stable step. */
    double w2max = 0;
    for (ct_idx i = 0; i < nnode; i++) {
        s->node_k[i] = (ct_real)(0.5 * r[i]);
        if (r[i] > 0 && s->node_m[i] > 0)
            w2max = fmax(w2max, r[i] / s->node_m[i]);
    }
    s->dt_stable = w2max > 0 ? 2 / sqrt(w2max) : HUGE_VAL;
    free(r);
    return compact_nodes(s);
}

void ctd_shell_masses(const ctd_shell *s, ct_real *m)
{
    for (ct_idx j = 0; j < s->nsnode; j++)
        m[s->snode[j]] += s->node_m[j];
}

double ctd_shell_dt(const ctd_shell *s) { return s->dt_stable; }

void ctd_shell_node_stiffness(const ctd_shell *s, ct_real *k)
{
    for (ct_idx j = 0; j < s->nsnode; j++)
        k[s->snode[j]] += s->node_k[j];
}
