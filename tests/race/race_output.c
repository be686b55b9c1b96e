/*
 * race_output.c -- the race check of the VTU writer (race_check.c runs
 * it): its data arrays are formatted by the threads in chunks. A file of
 * 70001 nodes (three rounds of chunks) written with 2 threads, watched by
 * ThreadSanitizer, must be the bytes of the same file written with 1; and
 * so must its raw binary form, whose 3-component arrays the threads
 * interleave (above 65536 nodes).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "output.h"

#ifdef _OPENMP
#include <omp.h>
#define SET_THREADS(n) omp_set_num_threads(n)
#else
#define SET_THREADS(n) ((void)(n))
#endif

/* The whole file (free it), or NULL; *len its size. */
static char *slurp(const char *path, long *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    *len = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = malloc((size_t)*len + 1);
    if (t && fread(t, 1, (size_t)*len, f) != (size_t)*len) {
        free(t);
        t = NULL;
    }
    fclose(f);
    return t;
}

void race_check_output(int *failures)
{
    const ct_idx n = 70001, nc = n - 1;
    ct_real *c = calloc(4 * (size_t)n, sizeof *c);
    ct_idx *off = calloc((size_t)nc + 1, sizeof *off), *conn = calloc(2 * (size_t)nc, sizeof *conn);
    uint8_t *ty = calloc((size_t)nc, 1);
    if (!c || !off || !conn || !ty) {
        printf("FAIL race_output: out of memory\n");
        (*failures)++;
        free(c), free(off), free(conn), free(ty);
        return;
    }
    for (ct_idx i = 0; i < n; i++) {
        c[i] = (ct_real)(0.001 * i);
        c[n + i] = (ct_real)(1.0 / (i + 1));
        c[2 * n + i] = (ct_real)(i % 3);
        c[3 * n + i] = (ct_real)(i % 5 ? 0 : 1e-3 * i);
    }
    for (ct_idx k = 0; k < nc; k++) {
        conn[2 * k] = k;
        conn[2 * k + 1] = k + 1;
        ty[k] = CTD_VTK_LINE;
        off[k + 1] = 2 * (k + 1);
    }
    ctd_out_mesh m = {.nnode = n, .x = c, .y = c + n, .z = c + 2 * n, .x0 = c + n,
                      .y0 = c + 2 * n, .z0 = c, .pen = c + 3 * n, .ncell = nc,
                      .cell_type = ty, .cell_off = off, .cell_node = conn};
    for (int fmt = CTD_VTU_ASCII; fmt <= CTD_VTU_RAW; fmt++) {
        char p[2][64], err[512];
        long len[2] = {0, 0};
        char *t[2] = {NULL, NULL};
        for (int k = 0; k < 2; k++) {
            snprintf(p[k], sizeof p[k], "/tmp/race_output_%d_%d.vtu", (int)getpid(), k);
            SET_THREADS(2 - k);
            if (ctd_vtu_write_as(p[k], &m, fmt, err, sizeof err) != CT_OK) {
                printf("FAIL race_output: %s\n", err);
                (*failures)++;
            }
            t[k] = slurp(p[k], &len[k]);
            remove(p[k]);
        }
        SET_THREADS(2);
        if (!t[0] || !t[1] || len[0] != len[1] || memcmp(t[0], t[1], (size_t)len[0]) != 0) {
            printf("FAIL race_output: the %s VTU file differs between 2 threads and 1\n",
                   fmt == CTD_VTU_RAW ? "raw" : "ASCII");
            (*failures)++;
        }
        free(t[0]), free(t[1]);
    }
    free(c), free(off), free(conn), free(ty);
}
