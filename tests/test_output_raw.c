/*
 * test_output_raw.c -- the VTU file with raw appended arrays, read back by
 * its own parser of the format (VTK's XML file formats: every
 * DataArray with format="appended" names an offset from the byte after the
 * underscore that opens the AppendedData block; there an 8-byte count of
 * the array's bytes (header_type UInt64) precedes the values). Every array
 * must hold the mesh's values bit for bit, and the file must be the same
 * bytes for any thread count.
 */
#include <math.h>
#include <stdint.h>

#include "test_output_util.h"

/* The value of attribute `key` in the tag that starts at tag (which ends at
 * the next '>'), copied into out; 0 when absent. */
static int tag_attr(const char *tag, const char *key, char *out, size_t cap)
{
    const char *end = strchr(tag, '>');
    char k[64];
    snprintf(k, sizeof k, " %s=\"", key);
    const char *p = strstr(tag, k);
    if (!p || !end || p > end)
        return 0;
    p += strlen(k);
    size_t n = (size_t)(strchr(p, '"') - p);
    cr_assert_lt(n, cap);
    memcpy(out, p, n);
    out[n] = '\0';
    return 1;
}

/* The k-th array named `name`: checks its type and components, and returns
 * a pointer to its values in the appended block and their byte count. */
static const char *raw_array(const char *file, size_t flen, const char *name, int k,
                             const char *type, int ncomp, uint64_t *nbytes)
{
    const char *app = strstr(file, "<AppendedData encoding=\"raw\">");
    cr_assert_not_null(app, "no raw AppendedData block");
    const char *base = strchr(app, '_');
    cr_assert_not_null(base);
    base++;
    char key[96], v[64];
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    const char *p = file;
    for (int i = 0; i <= k; i++) {
        p = strstr(p + 1, key);
        cr_assert(p && p < app, "array %s (%d) missing", name, k);
    }
    while (p > file && *p != '<')
        p--;
    cr_assert(tag_attr(p, "type", v, sizeof v));
    cr_assert_str_eq(v, type, "type of %s", name);
    cr_assert(tag_attr(p, "format", v, sizeof v));
    cr_assert_str_eq(v, "appended", "format of %s", name);
    if (ncomp > 1) {
        cr_assert(tag_attr(p, "NumberOfComponents", v, sizeof v));
        cr_assert_eq(atoi(v), ncomp, "components of %s", name);
    }
    cr_assert(tag_attr(p, "offset", v, sizeof v), "offset of %s", name);
    size_t off = (size_t)strtoull(v, NULL, 10);
    cr_assert_leq((size_t)(base - file) + off + 8, flen, "%s beyond the file", name);
    memcpy(nbytes, base + off, 8);
    cr_assert_leq((size_t)(base - file) + off + 8 + *nbytes, flen, "%s beyond the file", name);
    return base + off + 8;
}

static const char *real_type(void) { return sizeof(ct_real) == 8 ? "Float64" : "Float32"; }
static const char *idx_type(void) { return sizeof(ct_idx) == 8 ? "Int64" : "Int32"; }

/* Array `name` must be the n values of `want`, of `size` bytes each. */
static void expect_raw(const char *f, size_t len, const char *name, int k, const char *type,
                       int ncomp, const void *want, size_t n, size_t size)
{
    uint64_t nb = 0;
    const char *d = raw_array(f, len, name, k, type, ncomp, &nb);
    cr_assert_eq(nb, (uint64_t)(n * size), "%s: %llu bytes, expected %zu", name,
                 (unsigned long long)nb, n * size);
    cr_assert_eq(memcmp(d, want, n * size), 0, "%s differs from the mesh", name);
}

/* The 3-component values (a - b when b) interleaved, as the file must
 * hold them. */
static ct_real *vec3_of(ct_idx n, const ct_real *ax, const ct_real *ay, const ct_real *az,
                        const ct_real *bx, const ct_real *by, const ct_real *bz)
{
    ct_real *t = malloc(3 * (size_t)n * sizeof *t);
    cr_assert_not_null(t);
    for (ct_idx i = 0; i < n; i++) {
        t[3 * i] = bx ? ax[i] - bx[i] : ax[i];
        t[3 * i + 1] = by ? ay[i] - by[i] : ay[i];
        t[3 * i + 2] = bz ? az[i] - bz[i] : az[i];
    }
    return t;
}

Test(output_raw, parse_back_bit_for_bit)
{
    char *d = tmpdir(), err[512];
    ctd_output *o = NULL;
    ctd_output_opts opts = {.dir = d, .base = "state", .vtu = 1, .vtu_format = CTD_VTU_RAW};
    cr_assert_eq(ctd_output_open(&o, &opts, err, sizeof err), CT_OK, "%s", err);
    ctd_out_mesh m = small_mesh();
    cr_assert_eq(ctd_output_vtu(o, 0.0, &m), CT_OK, "%s", ctd_output_error(o));
    char p[256];
    snprintf(p, sizeof p, "%s/state_000000.vtu", d);
    size_t len;
    char *f = slurp_n(p, &len);
    cr_assert_not_null(strstr(f, "NumberOfPoints=\"14\" NumberOfCells=\"5\""));
    cr_assert_not_null(strstr(f, "header_type=\"UInt64\""));
    cr_assert_null(strstr(f, "format=\"ascii\""));
    ct_real *pts = vec3_of(NN, X, Y, Z, NULL, NULL, NULL);
    ct_real *dis = vec3_of(NN, X, Y, Z, X0, Y0, Z0);
    ct_real *vel = vec3_of(NN, VX, VY, VZ, NULL, NULL, NULL);
    ct_real *fc = vec3_of(NN, FX, FY, FZ, NULL, NULL, NULL);
    const size_t rs = sizeof(ct_real), is = sizeof(ct_idx);
    expect_raw(f, len, "Points", 0, real_type(), 3, pts, 3 * NN, rs);
    expect_raw(f, len, "displacement", 0, real_type(), 3, dis, 3 * NN, rs);
    expect_raw(f, len, "velocity", 0, real_type(), 3, vel, 3 * NN, rs);
    expect_raw(f, len, "contact_force", 0, real_type(), 3, fc, 3 * NN, rs);
    expect_raw(f, len, "penetration", 0, real_type(), 1, PEN, NN, rs);
    expect_raw(f, len, "part_id", 0, "Int32", 1, NPART, NN, 4);
    expect_raw(f, len, "active_pairs", 0, "Int32", 1, NACT, NN, 4);
    expect_raw(f, len, "part_id", 1, "Int32", 1, CPART, 5, 4);
    expect_raw(f, len, "connectivity", 0, idx_type(), 1, CONN, 25, is);
    expect_raw(f, len, "offsets", 0, idx_type(), 1, OFF + 1, 5, is);
    expect_raw(f, len, "types", 0, "UInt8", 1, TYPES, 5, 1);
    /* The point data between <PointData> and </PointData>, the cell part
     * between <CellData> and </CellData>. */
    const char *pd = strstr(f, "<PointData>"), *pe = strstr(f, "</PointData>");
    const char *cd = strstr(f, "<CellData>"), *ce = strstr(f, "</CellData>");
    cr_assert(pd && pe && cd && ce);
    const char *vt = strstr(f, "Name=\"velocity\""), *cp = strstr(pe, "Name=\"part_id\"");
    cr_assert(vt && cp);
    cr_expect(pd < vt && vt < pe, "velocity outside <PointData>");
    cr_expect(cd < cp && cp < ce, "the cells' part_id outside <CellData>");
    /* The block closes after the last array's values. */
    uint64_t nb;
    const char *last = raw_array(f, len, "types", 0, "UInt8", 1, &nb);
    const char *tail = "\n  </AppendedData>\n</VTKFile>\n";
    cr_assert_eq((size_t)(last - f) + nb + strlen(tail), len);
    cr_assert_eq(memcmp(last + nb, tail, strlen(tail)), 0);
    free(pts);
    free(dis);
    free(vel);
    free(fc);
    free(f);
    ctd_output_close(o);
    rmtree(d);
}

/* Above 65536 nodes the interleaving is shared by the threads: the bytes
 * must not change, and they must be the mesh's (an empty mesh too). */
Test(output_raw, same_bytes_for_any_threads)
{
    const ct_idx n = 100003, nc = 0;
    ct_real *x = malloc((size_t)n * sizeof *x), *y = malloc((size_t)n * sizeof *y),
            *z = malloc((size_t)n * sizeof *z);
    cr_assert(x && y && z);
    for (ct_idx i = 0; i < n; i++) {
        x[i] = (ct_real)(sin(0.37 * i) * 1e3);
        y[i] = (ct_real)(1e-7 * i - 3e-3);
        z[i] = (ct_real)(1.0 / (i + 1));
    }
    ctd_out_mesh m = {.nnode = n, .x = x, .y = y, .z = z, .x0 = z, .y0 = x, .z0 = y,
                      .ncell = nc};
    char *d = tmpdir(), p1[256], p2[256], err[512];
    snprintf(p1, sizeof p1, "%s/t1.vtu", d);
    snprintf(p2, sizeof p2, "%s/t2.vtu", d);
    ctt_threads(1);
    cr_assert_eq(ctd_vtu_write_as(p1, &m, CTD_VTU_RAW, err, sizeof err), CT_OK, "%s", err);
    ctt_threads(2);
    cr_assert_eq(ctd_vtu_write_as(p2, &m, CTD_VTU_RAW, err, sizeof err), CT_OK, "%s", err);
    size_t la, lb;
    char *a = slurp_n(p1, &la), *b = slurp_n(p2, &lb);
    cr_assert_eq(la, lb);
    cr_assert_eq(memcmp(a, b, la), 0, "the files differ between 1 and 2 threads");
    ct_real *dis = vec3_of(n, x, y, z, z, x, y);
    expect_raw(a, la, "displacement", 0, real_type(), 3, dis, 3 * (size_t)n, sizeof(ct_real));
    uint64_t nb = 1;
    raw_array(a, la, "connectivity", 0, idx_type(), 1, &nb);
    cr_assert_eq(nb, 0);
    free(dis);
    free(a);
    free(b);
    free(x);
    free(y);
    free(z);
    rmtree(d);
}

Test(output_raw, unknown_format_is_refused)
{
    ctd_out_mesh m = small_mesh();
    char err[512];
    cr_assert_eq(ctd_vtu_write_as("/tmp/ctd_never_written_raw.vtu", &m, 7, err, sizeof err),
                 CT_ERR_ARG);
    cr_assert_not_null(strstr(err, "unknown format 7"), "%s", err);
    cr_assert_neq(access("/tmp/ctd_never_written_raw.vtu", F_OK), 0);
    ctd_output *o = (ctd_output *)1;
    ctd_output_opts opts = {.dir = "/tmp", .vtu = 1, .vtu_format = -1};
    cr_assert_eq(ctd_output_open(&o, &opts, err, sizeof err), CT_ERR_ARG);
    cr_assert_null(o);
    cr_assert_not_null(strstr(err, "unknown VTU format -1"), "%s", err);
}
