/*
 * meshgen_shapes.c -- the low-level generators of meshgen.h: plates, hex
 * blocks, cube-spheres, extrusions (tubes, folded sheets), crumpled sheets,
 * soups of small plates, and mesh concatenation.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Counts must fit a ct_idx. */
static int fits(int64_t nnode, int64_t nseg)
{
    return nnode >= 0 && nseg >= 0 && nnode <= INT32_MAX - 64 && nseg <= INT32_MAX - 64;
}

/* m made for nnode nodes and nseg segments, or CT_ERR_TOOBIG when the
 * counts do not fit the index type. */
static int mesh_make(ct_mesh *m, int64_t nnode, int64_t nseg)
{
    if (!fits(nnode, nseg))
        return CT_ERR_TOOBIG;
    return ct_mesh_init(m, (ct_idx)nnode, (ct_idx)nseg);
}

static inline void set_quad(ct_mesh *m, int64_t s, ct_idx a, ct_idx b, ct_idx c, ct_idx d)
{
    m->n1[s] = a;
    m->n2[s] = b;
    m->n3[s] = c;
    m->n4[s] = d;
}

/* ---- Plates ------------------------------------------------------------ */

int ctd_plate_coords(ct_mesh *m, int nx, int ny, const double *xs, const double *ys,
                     double z, int tri)
{
    if (!m || nx < 1 || ny < 1 || !xs || !ys)
        return CT_ERR_ARG;
    int64_t nn = (int64_t)(nx + 1) * (ny + 1), ns = (int64_t)nx * ny * (tri ? 2 : 1);
    int rc = mesh_make(m, nn, ns);
    if (rc != CT_OK)
        return rc;
#pragma omp parallel for schedule(static)
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            int64_t p = i + (int64_t)(nx + 1) * j;
            m->nodes.x[p] = (ct_real)xs[i];
            m->nodes.y[p] = (ct_real)ys[j];
            m->nodes.z[p] = (ct_real)z;
        }
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            ct_idx a = (ct_idx)(i + (int64_t)(nx + 1) * j), b = a + 1, d = a + nx + 1,
                   c = d + 1;
            int64_t cell = i + (int64_t)nx * j;
            if (tri) {
                set_quad(m, 2 * cell, a, b, c, c);
                set_quad(m, 2 * cell + 1, a, c, d, d);
            } else {
                set_quad(m, cell, a, b, c, d);
            }
        }
    return CT_OK;
}

int ctd_plate(ct_mesh *m, int nx, int ny, double hx, double hy, const double origin[3],
              int tri)
{
    if (!m || nx < 1 || ny < 1 || !(hx > 0) || !(hy > 0))
        return CT_ERR_ARG;
    double o[3] = {0, 0, 0};
    if (origin)
        memcpy(o, origin, sizeof o);
    double *xs = malloc(sizeof(double) * ((size_t)nx + 1));
    double *ys = malloc(sizeof(double) * ((size_t)ny + 1));
    int rc = CT_ERR_NOMEM;
    if (xs && ys) {
        for (int i = 0; i <= nx; i++)
            xs[i] = o[0] + i * hx;
        for (int j = 0; j <= ny; j++)
            ys[j] = o[1] + j * hy;
        rc = ctd_plate_coords(m, nx, ny, xs, ys, o[2], tri);
    }
    free(xs);
    free(ys);
    return rc;
}

/* ---- Faces of a lattice box -------------------------------------------- */

/* Node numbering of the lattice points (i, j, k) of [0, N]^3 used by the
 * faces: a full block, or the cube surface only (for the sphere). */
typedef struct lattice {
    int N[3];
    int surface; /* 0: block numbering; 1: surface numbering (N equal) */
} lattice;

static inline ct_idx lattice_id(const lattice *L, int i, int j, int k)
{
    if (!L->surface)
        return (ct_idx)(i + (int64_t)(L->N[0] + 1) * (j + (int64_t)(L->N[1] + 1) * k));
    int n = L->N[0];
    int64_t face = (int64_t)(n + 1) * (n + 1);
    if (k == 0)
        return (ct_idx)(i + (int64_t)(n + 1) * j);
    if (k == n)
        return (ct_idx)(face + (int64_t)(n - 1) * 4 * n + i + (int64_t)(n + 1) * j);
    int64_t r;
    if (j == 0 && i < n)
        r = i;
    else if (i == n && j < n)
        r = n + j;
    else if (j == n && i > 0)
        r = 2 * n + (n - i);
    else
        r = 3 * n + (n - j);
    return (ct_idx)(face + (int64_t)(k - 1) * 4 * n + r);
}

/* The inverse of lattice_id for the surface numbering. */
static void surface_ijk(int n, int64_t id, int p[3])
{
    int64_t face = (int64_t)(n + 1) * (n + 1), mid = (int64_t)(n - 1) * 4 * n;
    if (id < face || id >= face + mid) {
        int64_t q = id < face ? id : id - face - mid;
        p[0] = (int)(q % (n + 1));
        p[1] = (int)(q / (n + 1));
        p[2] = id < face ? 0 : n;
        return;
    }
    int64_t q = id - face, r = q % (4 * n);
    p[2] = 1 + (int)(q / (4 * n));
    if (r < n) {
        p[0] = (int)r; p[1] = 0;
    } else if (r < 2 * n) {
        p[0] = n; p[1] = (int)(r - n);
    } else if (r < 3 * n) {
        p[0] = (int)(n - (r - 2 * n)); p[1] = n;
    } else {
        p[0] = 0; p[1] = (int)(n - (r - 3 * n));
    }
}

/* Write the 2 (N0 N1 + N1 N2 + N2 N0) outer quads, outward, from s0. Face
 * order: -x, +x, -y, +y, -z, +z; on the face of axis a the tangent axes are
 * u = a+1, v = a+2 (cyclic), so e_u x e_v = +e_a. */
static void lattice_faces(ct_mesh *m, const lattice *L, int64_t s0)
{
    int64_t s = s0;
    for (int a = 0; a < 3; a++) {
        int u = (a + 1) % 3, v = (a + 2) % 3, nu = L->N[u], nv = L->N[v];
        for (int side = 0; side < 2; side++) {
            int64_t base = s;
#pragma omp parallel for schedule(static)
            for (int jv = 0; jv < nv; jv++)
                for (int iu = 0; iu < nu; iu++) {
                    int p[4][3];
                    for (int c = 0; c < 4; c++) {
                        int du = (c == 1 || c == 2), dv = (c >= 2);
                        p[c][a] = side ? L->N[a] : 0;
                        p[c][u] = iu + du;
                        p[c][v] = jv + dv;
                    }
                    ct_idx id[4];
                    for (int c = 0; c < 4; c++)
                        id[c] = lattice_id(L, p[c][0], p[c][1], p[c][2]);
                    int64_t t = base + iu + (int64_t)nu * jv;
                    if (side)
                        set_quad(m, t, id[0], id[1], id[2], id[3]);
                    else
                        set_quad(m, t, id[0], id[3], id[2], id[1]);
                }
            s += (int64_t)nu * nv;
        }
    }
}

int ctd_block(ct_mesh *m, int nx, int ny, int nz, const double h[3], const double origin[3],
              ct_idx **hex8)
{
    if (hex8)
        *hex8 = NULL;
    if (!m || nx < 1 || ny < 1 || nz < 1 || !h || !(h[0] > 0) || !(h[1] > 0) || !(h[2] > 0))
        return CT_ERR_ARG;
    double o[3] = {0, 0, 0};
    if (origin)
        memcpy(o, origin, sizeof o);
    int64_t nn = (int64_t)(nx + 1) * (ny + 1) * (nz + 1);
    int64_t ns = 2 * ((int64_t)nx * ny + (int64_t)ny * nz + (int64_t)nz * nx);
    int64_t ne = (int64_t)nx * ny * nz;
    if (!fits(nn, ns) || (hex8 && ne > (INT32_MAX - 64) / 8))
        return CT_ERR_TOOBIG;
    int rc = ct_mesh_init(m, (ct_idx)nn, (ct_idx)ns);
    if (rc != CT_OK)
        return rc;
#pragma omp parallel for schedule(static)
    for (int k = 0; k <= nz; k++)
        for (int j = 0; j <= ny; j++)
            for (int i = 0; i <= nx; i++) {
                int64_t p = i + (int64_t)(nx + 1) * (j + (int64_t)(ny + 1) * k);
                m->nodes.x[p] = (ct_real)(o[0] + i * h[0]);
                m->nodes.y[p] = (ct_real)(o[1] + j * h[1]);
                m->nodes.z[p] = (ct_real)(o[2] + k * h[2]);
            }
    lattice L = {{nx, ny, nz}, 0};
    lattice_faces(m, &L, 0);
    if (hex8) {
        ct_idx *e = ct_calloc((size_t)(8 * ne), sizeof(ct_idx));
        if (!e) {
            ct_mesh_destroy(m);
            return CT_ERR_NOMEM;
        }
#pragma omp parallel for schedule(static)
        for (int k = 0; k < nz; k++)
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < nx; i++) {
                    ct_idx *q = e + 8 * (i + (int64_t)nx * (j + (int64_t)ny * k));
                    for (int c = 0; c < 8; c++) {
                        int di = (c & 3) == 1 || (c & 3) == 2, dj = (c & 3) >= 2, dk = c >= 4;
                        q[c] = lattice_id(&L, i + di, j + dj, k + dk);
                    }
                }
        *hex8 = e;
    }
    return CT_OK;
}

/* ---- Cube-sphere ------------------------------------------------------- */

int ctd_sphere(ct_mesh *m, int n, double radius, const double centre[3])
{
    if (!m || n < 1 || !(radius > 0))
        return CT_ERR_ARG;
    double o[3] = {0, 0, 0};
    if (centre)
        memcpy(o, centre, sizeof o);
    int64_t nn = 6 * (int64_t)n * n + 2, ns = 6 * (int64_t)n * n;
    int rc = mesh_make(m, nn, ns);
    if (rc != CT_OK)
        return rc;
#pragma omp parallel for schedule(static)
    for (int64_t id = 0; id < nn; id++) {
        int p[3];
        surface_ijk(n, id, p);
        double c[3], r2 = 0;
        for (int a = 0; a < 3; a++) {
            c[a] = (p[a] == 0) ? -1.0 : (p[a] == n) ? 1.0 : tan(M_PI / 4 * (2.0 * p[a] / n - 1));
            r2 += c[a] * c[a];
        }
        double s = radius / sqrt(r2);
        m->nodes.x[id] = (ct_real)(o[0] + c[0] * s);
        m->nodes.y[id] = (ct_real)(o[1] + c[1] * s);
        m->nodes.z[id] = (ct_real)(o[2] + c[2] * s);
    }
    lattice L = {{n, n, n}, 1};
    lattice_faces(m, &L, 0);
    return CT_OK;
}

/* ---- Extrusions -------------------------------------------------------- */

int ctd_extrude(ct_mesh *m, int np, const double *px, const double *py, int closed, int nl,
                double length, double z0)
{
    if (!m || !px || !py || nl < 1 || np < (closed ? 3 : 2) || !(length > 0))
        return CT_ERR_ARG;
    int nq = closed ? np : np - 1;
    int64_t nn = (int64_t)np * (nl + 1), ns = (int64_t)nq * nl;
    int rc = mesh_make(m, nn, ns);
    if (rc != CT_OK)
        return rc;
#pragma omp parallel for schedule(static)
    for (int l = 0; l <= nl; l++)
        for (int i = 0; i < np; i++) {
            int64_t p = i + (int64_t)np * l;
            m->nodes.x[p] = (ct_real)px[i];
            m->nodes.y[p] = (ct_real)py[i];
            m->nodes.z[p] = (ct_real)(z0 + length * l / nl);
        }
#pragma omp parallel for schedule(static)
    for (int l = 0; l < nl; l++)
        for (int i = 0; i < nq; i++) {
            ct_idx a = (ct_idx)(i + (int64_t)np * l);
            ct_idx b = (ct_idx)((i + 1) % np + (int64_t)np * l);
            set_quad(m, i + (int64_t)nq * l, a, b, b + np, a + np);
        }
    return CT_OK;
}

int ctd_tube(ct_mesh *m, int nr, int nl, double radius, double length)
{
    if (!m || nr < 3 || !(radius > 0))
        return CT_ERR_ARG;
    double *px = malloc(sizeof(double) * (size_t)nr), *py = malloc(sizeof(double) * (size_t)nr);
    int rc = CT_ERR_NOMEM;
    if (px && py) {
        for (int i = 0; i < nr; i++) {
            px[i] = radius * cos(2 * M_PI * i / nr);
            py[i] = radius * sin(2 * M_PI * i / nr);
        }
        rc = ctd_extrude(m, nr, px, py, 1, nl, length, 0.0);
    }
    free(px);
    free(py);
    return rc;
}

/* The points along the folded sheet's section, in double (it can exceed
 * any integer type for absurd parameters). */
static double folded_points(int nlayer, int nflat, double h, double spacing)
{
    double lf = nflat * h, lb = M_PI * spacing / 2;
    double total = nlayer * lf + (nlayer - 1) * lb;
    return round(total / h) + 1;
}

int64_t ctd_folded_nodes(int nlayer, int nflat, int nw, double h, double spacing)
{
    if (nlayer < 1 || nflat < 1 || nw < 1 || !(h > 0) || !(spacing > 0))
        return -1;
    double np = folded_points(nlayer, nflat, h, spacing);
    if (!(np * (nw + 1.0) < 9e18))
        return INT64_MAX;
    return (int64_t)np * (nw + 1);
}

int ctd_folded(ct_mesh *m, int nlayer, int nflat, int nw, double h, double spacing)
{
    if (!m || nlayer < 1 || nflat < 1 || nw < 1 || !(h > 0) || !(spacing > 0))
        return CT_ERR_ARG;
    double lf = nflat * h, r = spacing / 2, lb = M_PI * r, period = lf + lb;
    double total = nlayer * lf + (nlayer - 1) * lb;
    double npd = folded_points(nlayer, nflat, h, spacing);
    if (!(npd <= INT32_MAX / 2))
        return CT_ERR_TOOBIG;
    int64_t np = (int64_t)npd;
    double *px = malloc(sizeof(double) * (size_t)np), *py = malloc(sizeof(double) * (size_t)np);
    int rc = CT_ERR_NOMEM;
    if (px && py) {
        double du = total / (double)(np - 1);
        for (int64_t i = 0; i < np; i++) {
            double u = du * (double)i;
            int64_t L = (int64_t)floor(u / period);
            double w = u - (double)L * period;
            if (L >= nlayer || i == np - 1) {
                L = nlayer - 1;
                w = lf;
            }
            int fwd = (L % 2 == 0);
            if (w <= lf) {
                px[i] = fwd ? w : lf - w;
                py[i] = (double)L * spacing;
            } else {
                double t = (w - lf) / r; /* bend angle in [0, pi] */
                px[i] = fwd ? lf + r * sin(t) : -r * sin(t);
                py[i] = (double)L * spacing + r - r * cos(t);
            }
        }
        rc = ctd_extrude(m, (int)np, px, py, 0, nw, nw * h, 0.0);
    }
    free(px);
    free(py);
    return rc;
}

/* ---- Random shapes ----------------------------------------------------- */

uint64_t ctd_splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

#define CRUMPLE_MODES 8

int ctd_crumpled(ct_mesh *m, int nx, int ny, double h, double amplitude, uint64_t seed)
{
    if (!m || !(amplitude >= 0))
        return CT_ERR_ARG;
    int rc = ctd_plate(m, nx, ny, h, h, NULL, 0);
    if (rc != CT_OK)
        return rc;
    /* Per component c and mode q: wave vector, phase and weight; weights sum
     * to one so each displacement component is at most `amplitude`. */
    double kx[3][CRUMPLE_MODES], ky[3][CRUMPLE_MODES], ph[3][CRUMPLE_MODES],
        wt[3][CRUMPLE_MODES];
    uint64_t st = seed ^ 0x6372756d706c6564ULL;
    for (int c = 0; c < 3; c++) {
        double sum = 0;
        for (int q = 0; q < CRUMPLE_MODES; q++) {
            double ang = 2 * M_PI * ctd_u01(ctd_splitmix64(&st));
            double lam = 12 * h * (0.7 + 0.7 * ctd_u01(ctd_splitmix64(&st)));
            kx[c][q] = 2 * M_PI / lam * cos(ang);
            ky[c][q] = 2 * M_PI / lam * sin(ang);
            ph[c][q] = 2 * M_PI * ctd_u01(ctd_splitmix64(&st));
            wt[c][q] = 0.5 + ctd_u01(ctd_splitmix64(&st));
            sum += wt[c][q];
        }
        for (int q = 0; q < CRUMPLE_MODES; q++)
            wt[c][q] *= amplitude / sum;
    }
    ct_idx nn = m->nodes.n;
#pragma omp parallel for schedule(static)
    for (ct_idx p = 0; p < nn; p++) {
        double x = m->nodes.x[p], y = m->nodes.y[p], d[3];
        for (int c = 0; c < 3; c++) {
            double s = 0;
            for (int q = 0; q < CRUMPLE_MODES; q++)
                s += wt[c][q] * sin(kx[c][q] * x + ky[c][q] * y + ph[c][q]);
            d[c] = s;
        }
        m->nodes.x[p] = (ct_real)(x + d[0]);
        m->nodes.y[p] = (ct_real)(y + d[1]);
        m->nodes.z[p] = (ct_real)d[2];
    }
    return CT_OK;
}

int ctd_soup(ct_mesh *m, int nplate, int k, double h, double box, uint64_t seed)
{
    if (!m || nplate < 1 || k < 1 || !(h > 0) || !(box > 0))
        return CT_ERR_ARG;
    int64_t npp = (int64_t)(k + 1) * (k + 1), spp = (int64_t)k * k;
    int64_t nn = npp * nplate, ns = spp * nplate;
    int rc = mesh_make(m, nn, ns);
    if (rc != CT_OK)
        return rc;
#pragma omp parallel for schedule(static)
    for (int pl = 0; pl < nplate; pl++) {
        /* Each plate draws from its own stream: independent of threads. */
        uint64_t st = seed ^ ((uint64_t)pl * 0xd1b54a32d192ed03ULL);
        double c[3];
        for (int a = 0; a < 3; a++)
            c[a] = box * ctd_u01(ctd_splitmix64(&st));
        /* Uniform random rotation from a unit quaternion (Shoemake). */
        double u1 = ctd_u01(ctd_splitmix64(&st)), u2 = ctd_u01(ctd_splitmix64(&st)),
               u3 = ctd_u01(ctd_splitmix64(&st));
        double qw = sqrt(1 - u1) * sin(2 * M_PI * u2), qx = sqrt(1 - u1) * cos(2 * M_PI * u2),
               qy = sqrt(u1) * sin(2 * M_PI * u3), qz = sqrt(u1) * cos(2 * M_PI * u3);
        double R[3][3] = {
            {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)},
            {2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)},
            {2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)}};
        int64_t n0 = npp * pl, s0 = spp * pl;
        for (int b = 0; b <= k; b++)
            for (int a = 0; a <= k; a++) {
                double l[2] = {(a - 0.5 * k) * h, (b - 0.5 * k) * h};
                int64_t p = n0 + a + (int64_t)(k + 1) * b;
                m->nodes.x[p] = (ct_real)(c[0] + R[0][0] * l[0] + R[0][1] * l[1]);
                m->nodes.y[p] = (ct_real)(c[1] + R[1][0] * l[0] + R[1][1] * l[1]);
                m->nodes.z[p] = (ct_real)(c[2] + R[2][0] * l[0] + R[2][1] * l[1]);
            }
        for (int b = 0; b < k; b++)
            for (int a = 0; a < k; a++) {
                ct_idx p = (ct_idx)(n0 + a + (int64_t)(k + 1) * b);
                set_quad(m, s0 + a + (int64_t)k * b, p, p + 1, p + k + 2, p + k + 1);
            }
    }
    return CT_OK;
}

/* ---- Concatenation ----------------------------------------------------- */

int ctd_mesh_concat(ct_mesh *out, const ct_mesh *a, const ct_mesh *b)
{
    if (!out || !a || !b)
        return CT_ERR_ARG;
    int64_t nn = (int64_t)a->nodes.n + b->nodes.n, ns = (int64_t)a->nseg + b->nseg;
    int rc = mesh_make(out, nn, ns);
    if (rc != CT_OK)
        return rc;
    const ct_mesh *src[2] = {a, b};
    ct_idx noff = 0, soff = 0;
    for (int q = 0; q < 2; q++) {
        const ct_mesh *s = src[q];
        size_t nb = (size_t)s->nodes.n * sizeof(ct_real);
        memcpy(out->nodes.x + noff, s->nodes.x, nb);
        memcpy(out->nodes.y + noff, s->nodes.y, nb);
        memcpy(out->nodes.z + noff, s->nodes.z, nb);
        memcpy(out->nodes.vx + noff, s->nodes.vx, nb);
        memcpy(out->nodes.vy + noff, s->nodes.vy, nb);
        memcpy(out->nodes.vz + noff, s->nodes.vz, nb);
        memcpy(out->nodes.m + noff, s->nodes.m, nb);
        ct_idx ns_q = s->nseg;
#pragma omp parallel for schedule(static)
        for (ct_idx t = 0; t < ns_q; t++)
            set_quad(out, soff + t, s->n1[t] + noff, s->n2[t] + noff, s->n3[t] + noff,
                     s->n4[t] + noff);
        noff += s->nodes.n;
        soff += s->nseg;
    }
    return CT_OK;
}
