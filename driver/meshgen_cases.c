/*
 * meshgen_cases.c -- the search-case families of meshgen.h: each builds
 * its bodies with the low-level generators, names the main segments and
 * the secondary nodes, then ctd_case_make renumbers, gathers the main
 * segments' nodes and measures their mean edge length.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- Helpers ----------------------------------------------------------- */

static int64_t iround(double v) { return (int64_t)llround(v); }
static int64_t imax(int64_t a, int64_t b) { return a > b ? a : b; }

static int main_range(ctd_case *c, ct_idx s0, ct_idx n)
{
    c->main.seg = ct_calloc((size_t)n, sizeof(ct_idx));
    if (!c->main.seg)
        return CT_ERR_NOMEM;
    for (ct_idx k = 0; k < n; k++)
        c->main.seg[k] = s0 + k;
    c->main.n = n;
    return CT_OK;
}

static int sec_range(ctd_case *c, ct_idx i0, ct_idx n)
{
    c->sec.node = ct_calloc((size_t)n, sizeof(ct_idx));
    if (!c->sec.node)
        return CT_ERR_NOMEM;
    for (ct_idx k = 0; k < n; k++)
        c->sec.node[k] = i0 + k;
    c->sec.n = n;
    return CT_OK;
}

/* Main body first, then the secondary body: main = the main body's
 * segments; sec = the secondary body's nodes (all, or those on its
 * segments). Both bodies are consumed. */
static int two_bodies(ctd_case *c, ct_mesh *mb, ct_mesh *sb, int surface_only)
{
    int rc = ctd_mesh_concat(&c->mesh, mb, sb);
    ct_idx nmain_nodes = mb->nodes.n, nmain_seg = mb->nseg;
    if (rc == CT_OK)
        rc = main_range(c, 0, nmain_seg);
    if (rc == CT_OK && !surface_only)
        rc = sec_range(c, nmain_nodes, sb->nodes.n);
    if (rc == CT_OK && surface_only) {
        ct_surface s = {sb->nseg, NULL};
        s.seg = ct_calloc((size_t)sb->nseg, sizeof(ct_idx));
        rc = s.seg ? CT_OK : CT_ERR_NOMEM;
        for (ct_idx k = 0; rc == CT_OK && k < sb->nseg; k++)
            s.seg[k] = nmain_seg + k;
        if (rc == CT_OK)
            rc = ct_surface_nodes(&c->mesh, &s, &c->sec);
        ct_free(s.seg);
    }
    ct_mesh_destroy(mb);
    ct_mesh_destroy(sb);
    c->self = 0;
    return rc;
}

/* One body against itself: main = all its segments, sec = their nodes. */
static int self_body(ctd_case *c, ct_mesh *b)
{
    c->mesh = *b;
    memset(b, 0, sizeof *b);
    c->self = 1;
    int rc = main_range(c, 0, c->mesh.nseg);
    if (rc == CT_OK)
        rc = ct_surface_nodes(&c->mesh, &c->main, &c->sec);
    return rc;
}

/* ---- Families ---------------------------------------------------------- */

static int fam_plates(ctd_case *c, int64_t t, int tri)
{
    int s = (int)imax(2, iround(sqrt((double)t)));
    ct_mesh a, b;
    double ob[3] = {0, 0, 0}, oa[3] = {0.25, 0.35, 0.3};
    int rc = ctd_plate(&b, s, s, 1, 1, ob, tri);
    if (rc != CT_OK)
        return rc;
    rc = ctd_plate(&a, s - 1, s - 1, 1, 1, oa, tri);
    if (rc != CT_OK) {
        ct_mesh_destroy(&b);
        return rc;
    }
    return two_bodies(c, &b, &a, 0);
}

static int fam_block(ctd_case *c, int64_t t)
{
    int nz = (int)imax(1, iround(cbrt((double)t / 16)));
    int nx = (int)imax(1, iround(sqrt((double)t / (nz + 1))) - 1);
    double h[3] = {1, 1, 1}, ob[3] = {0, 0, -nz}, oa[3] = {0.25, 0.35, 0.3};
    ct_mesh a, b;
    int rc = ctd_block(&b, nx + 1, nx + 1, nz, h, ob, NULL);
    if (rc != CT_OK)
        return rc;
    rc = ctd_block(&a, nx, nx, nz, h, oa, NULL);
    if (rc != CT_OK) {
        ct_mesh_destroy(&b);
        return rc;
    }
    return two_bodies(c, &b, &a, 1);
}

static int fam_sphere(ctd_case *c, int64_t t)
{
    int n = (int)imax(1, iround(sqrt((double)(t - 2) / 6)));
    double r = 2.0 * n / M_PI; /* quads about 1 wide */
    ct_mesh in, out;
    int rc = ctd_sphere(&out, n + 1, r + 0.3, NULL);
    if (rc != CT_OK)
        return rc;
    rc = ctd_sphere(&in, n, r, NULL);
    if (rc != CT_OK) {
        ct_mesh_destroy(&out);
        return rc;
    }
    return two_bodies(c, &out, &in, 0);
}

static int fam_tube(ctd_case *c, int64_t t)
{
    int nr = (int)imax(8, iround(sqrt((double)t)));
    int nl = (int)imax(1, iround((double)t / nr) - 1);
    /* Stadium: flat walls of length w at y = -+d/2 joined by half circles
     * of radius d/2, perimeter nr (unit spacing), counter-clockwise. */
    double d = 0.3, rr = d / 2, w = (nr - M_PI * d) / 2;
    double *px = malloc(sizeof(double) * (size_t)nr), *py = malloc(sizeof(double) * (size_t)nr);
    int rc = CT_ERR_NOMEM;
    if (px && py) {
        for (int i = 0; i < nr; i++) {
            double u = (double)i, arc = M_PI * rr;
            if (u < w) {
                px[i] = u; py[i] = -rr;
            } else if (u < w + arc) {
                double a = (u - w) / rr - M_PI / 2;
                px[i] = w + rr * cos(a); py[i] = rr * sin(a);
            } else if (u < 2 * w + arc) {
                px[i] = w - (u - w - arc); py[i] = rr;
            } else {
                double a = (u - 2 * w - arc) / rr + M_PI / 2;
                px[i] = rr * cos(a); py[i] = rr * sin(a);
            }
        }
        ct_mesh b;
        rc = ctd_extrude(&b, nr, px, py, 1, nl, nl, 0.0);
        if (rc == CT_OK)
            rc = self_body(c, &b);
    }
    free(px);
    free(py);
    return rc;
}

static int fam_folded(ctd_case *c, int64_t t)
{
    double spacing = 0.4;
    int nlayer = (int)imax(2, iround(cbrt((double)t) / 2));
    int k = (int)imax(1, iround(sqrt((double)t / nlayer)));
    int64_t np = iround(nlayer * (double)k + (nlayer - 1) * M_PI * spacing / 2) + 1;
    int nw = (int)imax(1, iround((double)t / (double)np) - 1);
    ct_mesh b;
    int rc = ctd_folded(&b, nlayer, k, nw, 1.0, spacing);
    return rc == CT_OK ? self_body(c, &b) : rc;
}

static int fam_crumpled(ctd_case *c, int64_t t, uint64_t seed)
{
    int s = (int)imax(2, iround(sqrt((double)t)) - 1);
    ct_mesh b;
    int rc = ctd_crumpled(&b, s, s, 1.0, 5.0, seed);
    return rc == CT_OK ? self_body(c, &b) : rc;
}

static int fam_soup(ctd_case *c, int64_t t, uint64_t seed)
{
    int np = (int)imax(1, iround((double)t / 16));
    double box = cbrt(np * 9 * 1.5);
    ct_mesh b;
    int rc = ctd_soup(&b, np, 3, 1.0, box, seed);
    return rc == CT_OK ? self_body(c, &b) : rc;
}

static int fam_graded(ctd_case *c, int64_t t)
{
    int n = (int)imax(3, iround(sqrt((double)t)));
    double r = pow(100.0, 1.0 / (n - 1)); /* cell sizes 1 .. 100 */
    double *xs = malloc(sizeof(double) * ((size_t)n + 1));
    double *xa = malloc(sizeof(double) * ((size_t)n + 1));
    double *ya = malloc(sizeof(double) * ((size_t)n + 1));
    int rc = CT_ERR_NOMEM;
    if (xs && xa && ya) {
        xs[0] = 0;
        for (int i = 0; i < n; i++)
            xs[i + 1] = xs[i] + pow(r, i);
        /* The secondary plate's nodes sit a quarter (x) and 0.35 (y) of the
         * way into the main plate's cells: not aligned at any grading. */
        for (int i = 0; i < n; i++) {
            xa[i] = xs[i] + 0.25 * (xs[i + 1] - xs[i]);
            ya[i] = xs[i] + 0.35 * (xs[i + 1] - xs[i]);
        }
        ct_mesh a, b;
        rc = ctd_plate_coords(&b, n, n, xs, xs, 0.0, 0);
        if (rc == CT_OK) {
            rc = ctd_plate_coords(&a, n - 1, n - 1, xa, ya, 0.3, 0);
            if (rc == CT_OK)
                rc = two_bodies(c, &b, &a, 0);
            else
                ct_mesh_destroy(&b);
        }
    }
    free(xs);
    free(xa);
    free(ya);
    return rc;
}

static int fam_ball_plate(ctd_case *c, int64_t t)
{
    int n = (int)imax(1, iround(sqrt((double)(t - 2) / 6)));
    double r = 2.0 * n / M_PI, ctr[3] = {0, 0, r + 0.3};
    int np = (int)ceil(2.4 * r) + 2;
    double o[3] = {-0.5 * np + 0.25, -0.5 * np + 0.35, 0};
    ct_mesh s, p;
    int rc = ctd_plate(&p, np, np, 1, 1, o, 0);
    if (rc != CT_OK)
        return rc;
    rc = ctd_sphere(&s, n, r, ctr);
    if (rc != CT_OK) {
        ct_mesh_destroy(&p);
        return rc;
    }
    return two_bodies(c, &p, &s, 0);
}

/* ---- Finishing --------------------------------------------------------- */

/* Gather the main segments' nodes; mean edge length over the main
 * segments' edges, summed in fixed blocks (same result for any thread
 * count). */
#define CASE_BLOCKS 64

static int finish(ctd_case *c)
{
    ct_idx n = c->main.n;
    c->mn1 = ct_calloc((size_t)n, sizeof(ct_idx));
    c->mn2 = ct_calloc((size_t)n, sizeof(ct_idx));
    c->mn3 = ct_calloc((size_t)n, sizeof(ct_idx));
    c->mn4 = ct_calloc((size_t)n, sizeof(ct_idx));
    if (!c->mn1 || !c->mn2 || !c->mn3 || !c->mn4)
        return CT_ERR_NOMEM;
    const ct_mesh *m = &c->mesh;
    const ct_real *x = m->nodes.x, *y = m->nodes.y, *z = m->nodes.z;
    double bsum[CASE_BLOCKS];
    int64_t bcnt[CASE_BLOCKS];
    int64_t bl = ((int64_t)n + CASE_BLOCKS - 1) / CASE_BLOCKS;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < CASE_BLOCKS; b++) {
        int64_t lo = b * bl, hi = lo + bl < n ? lo + bl : n, cnt = 0;
        double sum = 0;
        for (int64_t k = lo; k < hi; k++) {
            ct_idx s = c->main.seg[k];
            ct_idx v[4] = {m->n1[s], m->n2[s], m->n3[s], m->n4[s]};
            c->mn1[k] = v[0];
            c->mn2[k] = v[1];
            c->mn3[k] = v[2];
            c->mn4[k] = v[3];
            for (int e = 0; e < 4; e++) {
                ct_idx p = v[e], q = v[(e + 1) & 3];
                if (p == q)
                    continue;
                double dx = (double)x[q] - x[p], dy = (double)y[q] - y[p],
                       dz = (double)z[q] - z[p];
                sum += sqrt(dx * dx + dy * dy + dz * dz);
                cnt++;
            }
        }
        bsum[b] = sum;
        bcnt[b] = cnt;
    }
    double sum = 0;
    int64_t cnt = 0;
    for (int b = 0; b < CASE_BLOCKS; b++) {
        sum += bsum[b];
        cnt += bcnt[b];
    }
    c->h_mean = cnt > 0 ? sum / (double)cnt : 0.0;
    return CT_OK;
}

int ctd_case_make(ctd_case *c, const char *family, int64_t target_nodes, ctd_numbering num,
                  uint64_t seed, ct_diag *diag)
{
    if (!c)
        return CT_ERR_ARG;
    memset(c, 0, sizeof *c);
    if (!family || target_nodes < 4 || num < CTD_NUM_NATURAL || num > CTD_NUM_SFC) {
        if (diag) {
            diag->code = CT_ERR_ARG;
            diag->index = -1;
            snprintf(diag->msg, sizeof diag->msg,
                     "Bad case request: family %s, target %lld nodes (at least 4), "
                     "numbering %d.",
                     family ? family : "(null)", (long long)target_nodes, (int)num);
        }
        return CT_ERR_ARG;
    }
    int rc;
    if (!strcmp(family, "plates"))
        rc = fam_plates(c, target_nodes, 0);
    else if (!strcmp(family, "plates-tri"))
        rc = fam_plates(c, target_nodes, 1);
    else if (!strcmp(family, "block"))
        rc = fam_block(c, target_nodes);
    else if (!strcmp(family, "sphere"))
        rc = fam_sphere(c, target_nodes);
    else if (!strcmp(family, "tube"))
        rc = fam_tube(c, target_nodes);
    else if (!strcmp(family, "folded"))
        rc = fam_folded(c, target_nodes);
    else if (!strcmp(family, "crumpled"))
        rc = fam_crumpled(c, target_nodes, seed);
    else if (!strcmp(family, "soup"))
        rc = fam_soup(c, target_nodes, seed);
    else if (!strcmp(family, "graded"))
        rc = fam_graded(c, target_nodes);
    else if (!strcmp(family, "ball-plate"))
        rc = fam_ball_plate(c, target_nodes);
    else {
        if (diag) {
            diag->code = CT_ERR_ARG;
            diag->index = -1;
            snprintf(diag->msg, sizeof diag->msg, "Unknown mesh family \"%s\".", family);
        }
        return CT_ERR_ARG;
    }
    snprintf(c->name, sizeof c->name, "%s", family);
    if (rc == CT_OK)
        rc = ctd_case_renumber(c, num, seed);
    if (rc == CT_OK)
        rc = finish(c);
    if (rc != CT_OK) {
        ctd_case_destroy(c);
        if (diag) {
            diag->code = rc;
            diag->index = -1;
            snprintf(diag->msg, sizeof diag->msg,
                     "Could not build the %s case of %lld nodes: %s.", family,
                     (long long)target_nodes, ct_strerror(rc));
        }
    }
    return rc;
}
