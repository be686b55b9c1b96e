/*
 * test_output.c -- the output files: a small mesh written to VTU is parsed
 * back (counts, coordinates, fields, cells); the PVD lists the steps; the
 * CSV header and rows read back exactly; the JSON summary is well-formed
 * (checked by a small JSON grammar parser) and holds the provenance; bad
 * output directories give errors naming the path.
 */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "test_output_util.h"

/* The numbers of DataArray `name` (the k-th one with that name, k >= 0)
 * in a VTU text, into out (at most max); returns the count. */
static int data_array(const char *text, const char *name, int k, double *out, int max)
{
    char key[96];
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    const char *p = text;
    for (int i = 0; i <= k; i++) {
        p = strstr(p, key);
        if (!p)
            return -1;
        p += strlen(key);
    }
    p = strchr(p, '>') + 1;
    int n = 0;
    for (;;) {
        char *end;
        double v = strtod(p, &end);
        if (end == p)
            break;
        if (n < max)
            out[n] = v;
        n++;
        p = end;
    }
    return n;
}

static long attr(const char *text, const char *name)
{
    char key[64];
    snprintf(key, sizeof key, "%s=\"", name);
    const char *p = strstr(text, key);
    cr_assert_not_null(p, "attribute %s missing", name);
    return strtol(p + strlen(key), NULL, 10);
}

static ctd_output *open_out(const char *dir)
{
    ctd_output *o = NULL;
    char err[512];
    ctd_output_opts opts = {.dir = dir, .base = "state", .vtu = 1, .csv = 1};
    int rc = ctd_output_open(&o, &opts, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "%s", err);
    return o;
}

/* ---- VTU / PVD ------------------------------------------------------------ */

Test(output, vtu_parse_back)
{
    char *d = tmpdir();
    ctd_output *o = open_out(d);
    ctd_out_mesh m = small_mesh();
    cr_assert_eq(ctd_output_vtu(o, 0.0, &m), CT_OK, "%s", ctd_output_error(o));
    char p[256];
    snprintf(p, sizeof p, "%s/state_000000.vtu", d);
    char *t = slurp(p);
    cr_assert_eq(attr(t, "NumberOfPoints"), NN);
    cr_assert_eq(attr(t, "NumberOfCells"), 5);
    double v[64];
    /* Points: current positions; node 13 is at (1 + 3.25, 4.5, 0). */
    cr_assert_eq(data_array(t, "Points", 0, v, 64), 3 * NN);
    cr_assert_eq(v[3 * 13 + 0], 1 + 0.25 * 13);
    cr_assert_eq(v[3 * 13 + 1], 4.5);
    /* Displacement = (0.25 i, -0.5, 0). */
    cr_assert_eq(data_array(t, "displacement", 0, v, 64), 3 * NN);
    for (int i = 0; i < NN; i++) {
        cr_assert_float_eq(v[3 * i], 0.25 * i, 1e-6, "node %d", i);
        cr_assert_eq(v[3 * i + 1], -0.5, "node %d", i);
        cr_assert_eq(v[3 * i + 2], 0.0, "node %d", i);
    }
    cr_assert_eq(data_array(t, "velocity", 0, v, 64), 3 * NN);
    cr_assert(v[3 * 5] == 5 && v[3 * 5 + 1] == -10 && v[3 * 5 + 2] == 0.125);
    cr_assert_eq(data_array(t, "contact_force", 0, v, 64), 3 * NN);
    cr_assert_eq(v[3 * 9 + 2], 90.0);
    cr_assert_eq(data_array(t, "penetration", 0, v, 64), NN);
    cr_assert(v[7] == 0.0625 && v[6] == 0);
    cr_assert_eq(data_array(t, "active_pairs", 0, v, 64), NN);
    cr_assert(v[7] == 2 && v[8] == 0);
    /* part_id: first the point array, then the cell array. */
    cr_assert_eq(data_array(t, "part_id", 0, v, 64), NN);
    cr_assert(v[11] == 1 && v[12] == 3);
    cr_assert_eq(data_array(t, "part_id", 1, v, 64), 5);
    cr_assert(v[0] == 1 && v[2] == 2 && v[4] == 3);
    cr_assert_eq(data_array(t, "connectivity", 0, v, 64), 25);
    for (int k = 0; k < 25; k++)
        cr_assert_eq(v[k], CONN[k]);
    cr_assert_eq(data_array(t, "offsets", 0, v, 64), 5);
    cr_assert(v[0] == 8 && v[1] == 16 && v[2] == 20 && v[3] == 23 && v[4] == 25);
    cr_assert_eq(data_array(t, "types", 0, v, 64), 5);
    cr_assert(v[0] == 12 && v[1] == 12 && v[2] == 9 && v[3] == 5 && v[4] == 3);
    cr_assert_not_null(strstr(t, "</VTKFile>"));
    free(t);
    ctd_output_close(o);
    rmtree(d);
}

Test(output, pvd_lists_steps)
{
    char *d = tmpdir();
    ctd_output *o = open_out(d);
    ctd_out_mesh m = small_mesh();
    const double times[3] = {0.0, 0.5e-3, 1.25e-3};
    for (int s = 0; s < 3; s++)
        cr_assert_eq(ctd_output_vtu(o, times[s], &m), CT_OK, "%s", ctd_output_error(o));
    char p[256];
    snprintf(p, sizeof p, "%s/state.pvd", d);
    char *t = slurp(p);
    int n = 0;
    for (const char *q = strstr(t, "<DataSet"); q; q = strstr(q + 1, "<DataSet"))
        n++;
    cr_assert_eq(n, 3);
    cr_assert_not_null(strstr(t, "timestep=\"0.00125\" group=\"\" part=\"0\" file=\"state_000002.vtu\""), "%s", t);
    cr_assert_not_null(strstr(t, "timestep=\"0.0005\" group=\"\" part=\"0\" file=\"state_000001.vtu\""));
    cr_assert_not_null(strstr(t, "</Collection>\n</VTKFile>"));
    for (int s = 0; s < 3; s++) {
        snprintf(p, sizeof p, "%s/state_%06d.vtu", d, s);
        cr_assert_eq(access(p, R_OK), 0, "%s missing", p);
    }
    free(t);
    ctd_output_close(o);
    rmtree(d);
}

Test(output, vtu_rejects_bad_cell)
{
    ctd_out_mesh m = small_mesh();
    static const ct_idx bad[25] = {0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10,
                                   6, 7, 10, 9, 7, 8, 11, 12, 14};
    m.cell_node = bad;
    char err[512];
    cr_assert_eq(ctd_vtu_write("/tmp/ctd_never_written.vtu", &m, err, sizeof err), CT_ERR_RANGE);
    cr_assert_not_null(strstr(err, "cell 4"), "%s", err);
    cr_assert_neq(access("/tmp/ctd_never_written.vtu", F_OK), 0);
}

Test(output, vtu_1e5_nodes)
{
    /* A 316 x 316 quad grid (~10^5 nodes; 100 x 100 under sanitizers). */
    int s = ctt_checking() ? 100 : 316;
    ct_idx n = (ct_idx)(s + 1) * (s + 1), nc = (ct_idx)s * s;
    ct_real *x = calloc((size_t)n, sizeof *x), *y = calloc((size_t)n, sizeof *y),
            *z = calloc((size_t)n, sizeof *z);
    ct_idx *off = malloc(((size_t)nc + 1) * sizeof *off), *conn = malloc(4 * (size_t)nc * sizeof *conn);
    uint8_t *ty = malloc((size_t)nc);
    for (ct_idx i = 0; i < n; i++) {
        x[i] = (ct_real)(i % (s + 1));
        y[i] = (ct_real)(i / (s + 1));
    }
    for (ct_idx c = 0; c < nc; c++) {
        ct_idx i = c % s, j = c / s, a = i + (s + 1) * j;
        conn[4 * c] = a;
        conn[4 * c + 1] = a + 1;
        conn[4 * c + 2] = a + s + 2;
        conn[4 * c + 3] = a + s + 1;
        ty[c] = CTD_VTK_QUAD;
        off[c] = 4 * c;
    }
    off[nc] = 4 * nc;
    ctd_out_mesh m = {.nnode = n, .x = x, .y = y, .z = z, .x0 = x, .y0 = y, .z0 = z, .vx = x,
                      .vy = y, .vz = z, .ncell = nc, .cell_type = ty, .cell_off = off,
                      .cell_node = conn};
    char *d = tmpdir(), p[256], err[512];
    snprintf(p, sizeof p, "%s/big.vtu", d);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    cr_assert_eq(ctd_vtu_write(p, &m, err, sizeof err), CT_OK, "%s", err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    cr_log_info("VTU of %d nodes, %d quads: %.3f s", (int)n, (int)nc, secs);
    char *t = slurp(p);
    cr_assert_eq(attr(t, "NumberOfPoints"), n);
    cr_assert_eq(attr(t, "NumberOfCells"), nc);
    double v[4];
    cr_assert_eq(data_array(t, "offsets", 0, v, 4), nc);
    free(t);
    free(x), free(y), free(z), free(off), free(conn), free(ty);
    rmtree(d);
}

/* The data arrays are formatted by the threads in chunks: the file must be
 * the same bytes for 1 and 2 threads, and its numbers those of a plain
 * serial printf, across several rounds of chunks (70001 nodes: 3 rounds of
 * 32768 items; 70000 segments of 2 nodes). */
Test(output, vtu_same_bytes_for_any_threads)
{
    const ct_idx n = 70001, nc = n - 1;
    ct_real *x = calloc((size_t)n, sizeof *x), *y = calloc((size_t)n, sizeof *y),
            *z = calloc((size_t)n, sizeof *z), *pen = calloc((size_t)n, sizeof *pen);
    ct_idx *off = malloc(((size_t)nc + 1) * sizeof *off);
    ct_idx *conn = malloc(2 * (size_t)nc * sizeof *conn);
    uint8_t *ty = malloc((size_t)nc);
    int32_t *part = malloc((size_t)n * sizeof *part);
    cr_assert(x && y && z && pen && off && conn && ty && part);
    for (ct_idx i = 0; i < n; i++) {
        x[i] = (ct_real)(sin(0.37 * i) * 1e3);
        y[i] = (ct_real)(1e-7 * i - 3e-3);
        z[i] = (ct_real)(i % 7 == 0 ? 0 : 1.0 / (i + 1));
        pen[i] = (ct_real)(i % 5 == 0 ? 2.5e-4 * i : 0);
        part[i] = (int32_t)(i % 13);
    }
    for (ct_idx c = 0; c < nc; c++) {
        conn[2 * c] = c;
        conn[2 * c + 1] = c + 1;
        ty[c] = CTD_VTK_LINE;
        off[c] = 2 * c;
    }
    off[nc] = 2 * nc;
    ctd_out_mesh m = {.nnode = n, .x = x, .y = y, .z = z, .x0 = y, .y0 = z, .z0 = x,
                      .pen = pen, .node_part = part, .ncell = nc, .cell_type = ty,
                      .cell_off = off, .cell_node = conn};
    char *d = tmpdir(), p1[256], p2[256], err[512];
    snprintf(p1, sizeof p1, "%s/t1.vtu", d);
    snprintf(p2, sizeof p2, "%s/t2.vtu", d);
    ctt_threads(1);
    cr_assert_eq(ctd_vtu_write(p1, &m, err, sizeof err), CT_OK, "%s", err);
    ctt_threads(2);
    cr_assert_eq(ctd_vtu_write(p2, &m, err, sizeof err), CT_OK, "%s", err);
    char *a = slurp(p1), *b = slurp(p2);
    cr_assert(a && b);
    cr_expect_str_eq(a, b, "the files differ between 1 and 2 threads");
    /* The positions and the displacement as a serial printf writes them. */
    size_t cap = (size_t)n * 3 * 20 + 256, len = 0;
    char *want = malloc(cap), *wd = malloc(cap);
    cr_assert(want && wd);
    want[0] = wd[0] = 0;
    for (ct_idx i = 0; i < n; i++)
        len += (size_t)snprintf(want + len, cap - len, "%.9g %.9g %.9g\n", (double)x[i],
                                (double)y[i], (double)z[i]);
    len = 0;
    for (ct_idx i = 0; i < n; i++)
        len += (size_t)snprintf(wd + len, cap - len, "%.9g %.9g %.9g\n",
                                (double)x[i] - (double)y[i], (double)y[i] - (double)z[i],
                                (double)z[i] - (double)x[i]);
    cr_expect(strstr(a, want) != NULL, "the Points array is not the serial text");
    cr_expect(strstr(a, wd) != NULL, "the displacement array is not the serial text");
    double v[4];
    cr_expect_eq(data_array(a, "connectivity", 0, v, 4), 2 * nc);
    cr_expect_eq(data_array(a, "penetration", 0, v, 4), n);
    free(want), free(wd), free(a), free(b);
    free(x), free(y), free(z), free(pen), free(off), free(conn), free(ty), free(part);
    rmtree(d);
}

/* ---- CSV ------------------------------------------------------------------ */

Test(output, csv_header_and_rows)
{
    char *d = tmpdir();
    ctd_output *o = open_out(d);
    const char *names[2] = {"ball-plate", "self contact"};
    cr_assert_eq(ctd_output_csv_begin(o, 2, names), CT_OK, "%s", ctd_output_error(o));
    for (int k = 0; k < 3; k++) {
        double f[2] = {1000.5 * k, 0.1 / 3};
        int64_t act[2] = {k, 7}, rs[2] = {k * 2, 0};
        ctd_history_row r = {.cycle = 10 * k, .time = 1e-4 * k / 3, .dt = 1.0 / 3e7,
                             .kinetic = 0.1 * k, .internal = 2.0 / 3, .contact = 1e-9,
                             .damping = 0, .friction = 0.5, .external_work = -1.5,
                             .energy_error = 1e-5 * k, .if_force = f, .if_active = act,
                             .if_resorts = rs};
        cr_assert_eq(ctd_output_csv_row(o, &r), CT_OK, "%s", ctd_output_error(o));
    }
    char p[256];
    snprintf(p, sizeof p, "%s/history.csv", d);
    char *t = slurp(p);
    const char *hdr = "cycle,time,dt,kinetic,internal,contact,damping,friction,external_work,"
                      "energy_error,ball-plate_force,ball-plate_active,ball-plate_resorts,"
                      "self_contact_force,self_contact_active,self_contact_resorts\n";
    cr_assert_eq(strncmp(t, hdr, strlen(hdr)), 0, "%s", t);
    int lines = 0;
    for (const char *q = t; *q; q++)
        lines += *q == '\n';
    cr_assert_eq(lines, 4);
    /* Row 2 (k = 2) read back: every number exact (printed with 17 digits). */
    const char *row = t;
    for (int i = 0; i < 3; i++)
        row = strchr(row, '\n') + 1;
    double v[16];
    int nv = 0;
    for (const char *q = row; nv < 16;) {
        char *end;
        v[nv++] = strtod(q, &end);
        if (*end != ',')
            break;
        q = end + 1;
    }
    cr_assert_eq(nv, 16);
    cr_assert_eq(v[0], 20);
    cr_assert_eq(v[1], 1e-4 * 2 / 3);
    cr_assert_eq(v[2], 1.0 / 3e7);
    cr_assert_eq(v[4], 2.0 / 3);
    cr_assert_eq(v[9], 2e-5);
    cr_assert_eq(v[10], 2001.0);
    cr_assert(v[11] == 2 && v[12] == 4 && v[13] == 0.1 / 3 && v[14] == 7 && v[15] == 0);
    free(t);
    ctd_output_close(o);
    rmtree(d);
}

/* ---- JSON ----------------------------------------------------------------- */

/* A JSON grammar check (RFC 8259 values); returns the end or NULL. */
static const char *jvalue(const char *p);
static const char *jws(const char *p)
{
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r')
        p++;
    return p;
}
static const char *jstring(const char *p)
{
    if (*p != '"')
        return NULL;
    for (p++; *p != '"'; p++) {
        if ((unsigned char)*p < 0x20)
            return NULL;
        if (*p == '\\') {
            p++;
            if (*p == 'u') {
                for (int k = 1; k <= 4; k++)
                    if (!strchr("0123456789abcdefABCDEF", p[k]) || !p[k])
                        return NULL;
                p += 4;
            } else if (!*p || !strchr("\"\\/bfnrt", *p)) {
                return NULL;
            }
        }
    }
    return p + 1;
}
static const char *jvalue(const char *p)
{
    p = jws(p);
    if (*p == '{' || *p == '[') {
        char close = *p == '{' ? '}' : ']';
        p = jws(p + 1);
        if (*p == close)
            return p + 1;
        for (;;) {
            if (close == '}') {
                p = jstring(jws(p));
                if (!p || *(p = jws(p)) != ':')
                    return NULL;
                p++;
            }
            p = jvalue(p);
            if (!p)
                return NULL;
            p = jws(p);
            if (*p == close)
                return p + 1;
            if (*p != ',')
                return NULL;
            p++;
        }
    }
    if (*p == '"')
        return jstring(p);
    if (strncmp(p, "true", 4) == 0 || strncmp(p, "null", 4) == 0)
        return p + 4;
    if (strncmp(p, "false", 5) == 0)
        return p + 5;
    char *end;
    strtod(p, &end);
    return end == p ? NULL : end;
}

Test(output, json_summary)
{
    cr_assert_null(jvalue("{\"a\": [1, 2,]}"), "the checker itself rejects bad JSON");
    cr_assert_null(jvalue("{\"a\" 1}"));
    cr_assert_not_null(jvalue("{\"a\": [1, {\"b\": null}], \"c\": \"x\\n\"}"));
    char *d = tmpdir();
    ctd_output *o = open_out(d);
    ctd_if_summary ifs[2] = {{.name = "ball \"plate\"", .type = 24, .search = "bucket",
                              .max_active = 120, .resorts = 3, .max_force = 1.5e3},
                             {.name = "self", .type = 7, .search = "bsp"}};
    ctd_run_summary s = {.scene = "scenes/ball.yaml", .title = "ball\non plate",
                         .status = "unstable", .exit_code = 3,
                         .message = "NaN at node 12, cycle 400", .threads = 2, .cycles = 400,
                         .nodes = 1000, .elements = 800, .segments = 600, .output_steps = 4,
                         .end_time = 0.01, .time_reached = 0.004, .wall_time = 1.5,
                         .energy_error = 0.5 / 0.0, .energy_error_max = 0.015,
                         .t_search = 0.25, .t_narrow = 0.125, .t_force = 0.0625,
                         .t_assembly = 0.03125, .t_elements = 1.0, .t_other = 0.03125,
                         .ninterface = 2, .interfaces = ifs};
    cr_assert_eq(ctd_output_summary(o, &s), CT_OK, "%s", ctd_output_error(o));
    char p[256];
    snprintf(p, sizeof p, "%s/summary.json", d);
    char *t = slurp(p);
    const char *end = jvalue(t);
    cr_assert_not_null(end, "summary.json is not valid JSON:\n%s", t);
    cr_assert_eq(*jws(end), '\0', "trailing text after the JSON value");
    const char *keys[] = {"\"scene\": \"scenes/ball.yaml\"", "\"title\": \"ball\\non plate\"",
                          "\"status\": \"unstable\"", "\"exit_code\": 3", "\"cycles\": 400",
                          "\"energy_error\": null", "\"energy_error_max\": 0.014999999999999999",
                          "\"search\": 0.25", "\"elements\": 1", "\"timers\"",
                          "\"name\": \"ball \\\"plate\\\"\"", "\"type\": 24", "\"max_active\": 120",
                          "\"provenance\"", "\"build\": \"compiler=", "\"machine\": \"", "\"date\": \"20"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        cr_assert_not_null(strstr(t, keys[k]), "%s missing in\n%s", keys[k], t);
    cr_assert_not_null(strstr(t, "precision=" CT_PRECISION_NAME));
    free(t);
    ctd_output_close(o);
    rmtree(d);
}

/* ---- Directories ------------------------------------------------------------ */

static int open_fails(const char *dir, char *err, size_t len)
{
    ctd_output *o = (ctd_output *)1;
    ctd_output_opts opts = {.dir = dir, .vtu = 1, .csv = 1};
    int rc = ctd_output_open(&o, &opts, err, len);
    cr_assert_null(o);
    return rc;
}

Test(output, bad_directories)
{
    char err[512];
    /* Under /proc nothing can be created, not even by root. */
    cr_assert_neq(open_fails("/proc/x", err, sizeof err), CT_OK);
    cr_assert_not_null(strstr(err, "cannot create output directory '/proc/x': "), "%s", err);
    cr_assert_neq(open_fails("/proc", err, sizeof err), CT_OK);
    cr_assert_not_null(strstr(err, "cannot write to output directory '/proc': "), "%s", err);
    /* The check (contact check) creates nothing and refuses both too, even
     * as root, to whom access() grants /proc: proc has no blocks. */
    cr_assert_neq(ctd_output_check_dir("/proc/x/out", err, sizeof err), CT_OK);
    if (geteuid() == 0) /* otherwise access() refuses first */
        cr_assert_str_eq(err, "output directory is on a filesystem that stores no files "
                              "'/proc/x/out': No space left on device");
    cr_assert_neq(ctd_output_check_dir("/proc", err, sizeof err), CT_OK);
    cr_assert_not_null(strstr(err, "'/proc': "), "%s", err);
    char *d = tmpdir(), p[256];
    snprintf(p, sizeof p, "%s/file", d);
    FILE *f = fopen(p, "w");
    fclose(f);
    cr_assert_neq(open_fails(p, err, sizeof err), CT_OK);
    cr_assert_not_null(strstr(err, "is not a directory"), "%s", err);
    /* Under a file: no level can be made. */
    char want[400];
    snprintf(p, sizeof p, "%s/file/sub/run", d);
    cr_assert_neq(open_fails(p, err, sizeof err), CT_OK);
    snprintf(want, sizeof want, "cannot use output directory '%s': Not a directory", p);
    cr_assert_str_eq(err, want);
    /* Missing parents are created (as mkdir -p; a run's default
     * out/<scene> in a fresh directory needs out/ too). */
    snprintf(p, sizeof p, "%s/no/such/", d);
    ctd_output *o2 = open_out(p);
    struct stat st2;
    cr_assert(stat(p, &st2) == 0 && S_ISDIR(st2.st_mode));
    ctd_output_close(o2);
    snprintf(p, sizeof p, "%s/no/such", d);
    rmdir(p);
    snprintf(p, sizeof p, "%s/no", d);
    rmdir(p);
    /* A new leaf under an existing parent is created, and no probe is left. */
    snprintf(p, sizeof p, "%s/run", d);
    ctd_output *o = open_out(p);
    struct stat st;
    cr_assert(stat(p, &st) == 0 && S_ISDIR(st.st_mode));
    char probe[300];
    snprintf(probe, sizeof probe, "%s/.contact-probe", p);
    cr_assert_neq(access(probe, F_OK), 0);
    cr_assert_str_eq(ctd_output_dir(o), p);
    ctd_output_close(o);
    rmtree(p);
    remove(d);
    rmtree(d);
}

/* ---- Plot -------------------------------------------------------------------- */

static void history(ctd_output *o)
{
    const char *names[1] = {"a"};
    cr_assert_eq(ctd_output_csv_begin(o, 1, names), CT_OK);
    for (int k = 0; k <= 10; k++) {
        double f[1] = {k};
        int64_t a[1] = {k}, r[1] = {0};
        ctd_history_row row = {.cycle = k, .time = 1e-3 * k, .dt = 1e-4, .kinetic = 10.0 - k,
                               .internal = k, .if_force = f, .if_active = a, .if_resorts = r};
        cr_assert_eq(ctd_output_csv_row(o, &row), CT_OK);
    }
}

Test(output, plot_energies)
{
    char *d = tmpdir(), msg[512], p[256];
    ctd_output *o = open_out(d);
    history(o);
    ctd_output_close(o);
    int rc = ctd_output_plot_energies(d, msg, sizeof msg);
    snprintf(p, sizeof p, "%s/energies.gp", d);
    cr_assert_eq(access(p, R_OK), 0);
    if (rc == 1) {
        cr_assert_not_null(strstr(msg, "gnuplot is not installed"), "%s", msg);
    } else {
        cr_assert_eq(rc, 0, "%s", msg);
        snprintf(p, sizeof p, "%s/energies.png", d);
        FILE *f = fopen(p, "rb");
        cr_assert_not_null(f, "no PNG");
        unsigned char sig[8] = {0};
        cr_assert_eq(fread(sig, 1, 8, f), 8);
        fclose(f);
        cr_assert(sig[0] == 0x89 && sig[1] == 'P' && sig[2] == 'N' && sig[3] == 'G');
    }
    rmtree(d);
}

Test(output, plot_without_gnuplot)
{
    char *d = tmpdir(), msg[512], p[256];
    ctd_output *o = open_out(d);
    history(o);
    ctd_output_close(o);
    setenv("PATH", "/nonexistent", 1); /* this test runs in its own process */
    cr_assert_eq(ctd_output_plot_energies(d, msg, sizeof msg), 1);
    cr_assert_not_null(strstr(msg, "gnuplot is not installed"), "%s", msg);
    snprintf(p, sizeof p, "%s/energies.png", d);
    cr_assert_neq(access(p, F_OK), 0);
    rmtree(d);
}
