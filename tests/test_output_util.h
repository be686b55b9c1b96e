/*
 * test_output_util.h -- what the output tests share: a temporary directory,
 * a file read whole, and a small mesh of every cell type with every field.
 */
#ifndef TEST_OUTPUT_UTIL_H
#define TEST_OUTPUT_UTIL_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "output.h"
#include "test_util.h"

/* ---- Helpers ------------------------------------------------------------- */

static inline char *tmpdir(void)
{
    static char d[64];
    snprintf(d, sizeof d, "/tmp/ctd_out_XXXXXX");
    cr_assert_not_null(mkdtemp(d), "mkdtemp");
    return d;
}

/* Remove a flat directory and its files. */
static inline void rmtree(const char *d)
{
    DIR *dp = opendir(d);
    if (!dp)
        return;
    struct dirent *e;
    char p[512];
    while ((e = readdir(dp)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(p, sizeof p, "%s/%s", d, e->d_name);
        remove(p);
    }
    closedir(dp);
    rmdir(d);
}

/* A whole file, NUL-terminated, and its length. */
static inline char *slurp_n(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    cr_assert_not_null(b);
    cr_assert_eq(fread(b, 1, (size_t)n, f), (size_t)n);
    b[n] = '\0';
    fclose(f);
    *len = (size_t)n;
    return b;
}

static inline char *slurp(const char *path)
{
    size_t n;
    return slurp_n(path, &n);
}

/* ---- A small mesh: 2 hexahedra side by side, a quad on top, a triangle
 * and a line ------------------------------------------------------------- */

#define NN 14
static ct_real X0[NN], Y0[NN], Z0[NN], X[NN], Y[NN], Z[NN], VX[NN], VY[NN], VZ[NN];
static ct_real FX[NN], FY[NN], FZ[NN], PEN[NN];
static int32_t NPART[NN], NACT[NN];
static const uint8_t TYPES[5] = {CTD_VTK_HEXAHEDRON, CTD_VTK_HEXAHEDRON, CTD_VTK_QUAD,
                                 CTD_VTK_TRIANGLE, CTD_VTK_LINE};
static const ct_idx OFF[6] = {0, 8, 16, 20, 23, 25};
/* Nodes 0-11: a 2x1x1 brick grid (i + 3 j + 6 k); 12, 13 extra points. */
static const ct_idx CONN[25] = {0, 1, 4, 3, 6, 7, 10, 9,  1, 2, 5, 4, 7, 8, 11, 10,
                                6, 7, 10, 9, 7, 8, 11, 12, 13};
static const int32_t CPART[5] = {1, 1, 2, 2, 3};

static inline ctd_out_mesh small_mesh(void)
{
    for (int i = 0; i < NN; i++) {
        int a = i % 3, j = (i / 3) % 2, k = i / 6;
        X0[i] = (ct_real)a;
        Y0[i] = (ct_real)j;
        Z0[i] = (ct_real)k;
        if (i >= 12) {
            X0[i] = (ct_real)(i - 12);
            Y0[i] = 5;
            Z0[i] = 0;
        }
        X[i] = X0[i] + (ct_real)(0.25 * i);
        Y[i] = Y0[i] - (ct_real)0.5;
        Z[i] = Z0[i];
        VX[i] = (ct_real)i;
        VY[i] = (ct_real)(-2 * i);
        VZ[i] = (ct_real)0.125;
        FX[i] = FY[i] = 0;
        FZ[i] = (ct_real)(10 * i);
        PEN[i] = (ct_real)(i == 7 ? 0.0625 : 0.0);
        NPART[i] = i < 12 ? 1 : 3;
        NACT[i] = i == 7 ? 2 : 0;
    }
    ctd_out_mesh m = {.nnode = NN, .x = X, .y = Y, .z = Z, .x0 = X0, .y0 = Y0, .z0 = Z0,
                      .vx = VX, .vy = VY, .vz = VZ, .fcx = FX, .fcy = FY, .fcz = FZ,
                      .pen = PEN, .node_part = NPART, .node_active = NACT, .ncell = 5,
                      .cell_type = TYPES, .cell_off = OFF, .cell_node = CONN,
                      .cell_part = CPART};
    return m;
}

#endif
