/*
 * output_vtu.c -- the VTU + PVD series for ParaView (the directory:
 * output_dir.c).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "output_internal.h"

/* ---- VTU ------------------------------------------------------------------ */

/* A buffered writer: numbers formatted into a block, written in one go.
 * The data arrays are formatted in parallel: chunks of CTI_VTU_CHUNK items
 * into the pool, CTI_VTU_GROUP chunks at a time by the threads of the
 * run, each chunk into its own slot, then written in order. The file's
 * bytes do not depend on the thread count. */
#define CTI_VTU_CHUNK 512
#define CTI_VTU_GROUP 64
#define CTI_VTU_ITEM 64 /* bytes an item can take: 3 x "%.9g" (16) + 3 */

typedef struct wbuf {
    FILE *f;
    char b[1 << 16];
    size_t n;
    int bad;
    char *pool; /* up to CTI_VTU_GROUP chunks of CTI_VTU_CHUNK x CTI_VTU_ITEM bytes */
    size_t len[CTI_VTU_GROUP];      /* bytes in each chunk's slot */
} wbuf;

static void wflush(wbuf *w)
{
    if (w->n && fwrite(w->b, 1, w->n, w->f) != w->n)
        w->bad = 1;
    w->n = 0;
}

static void wmem(wbuf *w, const char *s, size_t len)
{
    if (w->n + len >= sizeof w->b)
        wflush(w);
    if (len >= sizeof w->b) {
        if (fwrite(s, 1, len, w->f) != len)
            w->bad = 1;
        return;
    }
    memcpy(w->b + w->n, s, len);
    w->n += len;
}

static void wstr(wbuf *w, const char *s) { wmem(w, s, strlen(s)); }

/* One data array: 3-component reals (a - b, b may be NULL), scalar reals
 * (8 to a line) or integers (16 to a line, from one of i32, iidx, u8). */
typedef struct varr {
    int kind; /* 0: vec3, 1: real, 2: integer */
    ct_idx n;
    const ct_real *a[3], *b[3];
    const int32_t *i32;
    const ct_idx *iidx;
    const uint8_t *u8;
} varr;

/* The text of item i into d (at most CTI_VTU_ITEM bytes); its length. */
static size_t item_text(const varr *v, ct_idx i, char *d)
{
    if (v->kind == 0) {
        double c[3] = {v->a[0][i], v->a[1][i], v->a[2][i]};
        if (v->b[0])
            for (int k = 0; k < 3; k++)
                c[k] -= v->b[k][i];
        int k = snprintf(d, CTI_VTU_ITEM, "%.9g %.9g %.9g\n", c[0], c[1], c[2]);
        return (size_t)k;
    }
    if (v->kind == 1) {
        char sep = (i % 8 == 7 || i == v->n - 1) ? '\n' : ' ';
        return (size_t)snprintf(d, CTI_VTU_ITEM, "%.9g%c", (double)v->a[0][i], sep);
    }
    long long x = v->i32 ? v->i32[i] : v->iidx ? v->iidx[i] : v->u8[i];
    char sep = (i % 16 == 15 || i == v->n - 1) ? '\n' : ' ';
    return (size_t)snprintf(d, CTI_VTU_ITEM, "%lld%c", x, sep);
}

static void items(wbuf *w, const varr *v)
{
    const ct_idx n = v->n, per = (ct_idx)CTI_VTU_CHUNK * CTI_VTU_GROUP;
    for (ct_idx g0 = 0; g0 < n; g0 += per) {
        const ct_idx left = n - g0;
        const int nch = (int)((left < per ? left : per) + CTI_VTU_CHUNK - 1) / CTI_VTU_CHUNK;
        char *pool = w->pool;
        size_t *len = w->len;
#pragma omp parallel for schedule(dynamic, 1) if (nch > 1)
        for (int c = 0; c < nch; c++) {
            char *d = pool + (size_t)c * CTI_VTU_CHUNK * CTI_VTU_ITEM;
            ct_idx i0 = g0 + (ct_idx)c * CTI_VTU_CHUNK;
            ct_idx i1 = n - i0 < CTI_VTU_CHUNK ? n : i0 + CTI_VTU_CHUNK;
            size_t l = 0;
            for (ct_idx i = i0; i < i1; i++)
                l += item_text(v, i, d + l);
            len[c] = l;
        }
        for (int c = 0; c < nch; c++)
            wmem(w, pool + (size_t)c * CTI_VTU_CHUNK * CTI_VTU_ITEM, len[c]);
    }
}

/* A 3-component point array; b may be NULL for "a - b" (displacement). */
static void vec3(wbuf *w, const char *name, ct_idx n, const ct_real *ax, const ct_real *ay,
                 const ct_real *az, const ct_real *bx, const ct_real *by, const ct_real *bz)
{
    char h[160];
    snprintf(h, sizeof h,
             "        <DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"3\" "
             "format=\"ascii\">\n",
             name);
    wstr(w, h);
    varr v = {0, n, {ax, ay, az}, {bx, by, bz}, NULL, NULL, NULL};
    items(w, &v);
    wstr(w, "        </DataArray>\n");
}

static void scalar_real(wbuf *w, const char *name, ct_idx n, const ct_real *a)
{
    char h[160];
    snprintf(h, sizeof h, "        <DataArray type=\"Float64\" Name=\"%s\" format=\"ascii\">\n",
             name);
    wstr(w, h);
    varr v = {1, n, {a, NULL, NULL}, {NULL, NULL, NULL}, NULL, NULL, NULL};
    items(w, &v);
    wstr(w, "        </DataArray>\n");
}

static void scalar_int(wbuf *w, const char *type, const char *name, ct_idx n, const int32_t *a,
                       const ct_idx *ai, const uint8_t *au)
{
    char h[160];
    snprintf(h, sizeof h, "        <DataArray type=\"%s\" Name=\"%s\" format=\"ascii\">\n", type,
             name);
    wstr(w, h);
    varr v = {2, n, {NULL, NULL, NULL}, {NULL, NULL, NULL}, a, ai, au};
    items(w, &v);
    wstr(w, "        </DataArray>\n");
}

static int cell_nodes_ok(uint8_t type, ct_idx count)
{
    switch (type) {
    case CTD_VTK_LINE: return count == 2;
    case CTD_VTK_TRIANGLE: return count == 3;
    case CTD_VTK_QUAD: return count == 4;
    case CTD_VTK_HEXAHEDRON: return count == 8;
    default: return 0;
    }
}

/* The raw form: the file opened, written and closed here. */
static int vtu_write_raw(const char *path, const ctd_out_mesh *m, char *err, size_t errlen)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return cti_out_fail(err, errlen, "cannot create VTU file", path, errno);
    errno = 0;
    int bad = cti_vtu_write_raw(f, m) != 0;
    int e = errno;
    if (fclose(f) != 0) {
        bad = 1;
        e = errno;
    }
    return bad ? cti_out_fail(err, errlen, "cannot write VTU file", path, e ? e : EIO) : CT_OK;
}

int ctd_vtu_write(const char *path, const ctd_out_mesh *m, char *err, size_t errlen)
{
    return ctd_vtu_write_as(path, m, CTD_VTU_ASCII, err, errlen);
}

int ctd_vtu_write_as(const char *path, const ctd_out_mesh *m, int format, char *err,
                     size_t errlen)
{
    if (format != CTD_VTU_ASCII && format != CTD_VTU_RAW) {
        if (err && errlen)
            snprintf(err, errlen, "VTU '%s': unknown format %d (expected ascii 0 or raw 1)",
                     path, format);
        return CT_ERR_ARG;
    }
    if (!m || !m->x || !m->y || !m->z || m->nnode < 0 || m->ncell < 0 ||
        (m->ncell > 0 && (!m->cell_type || !m->cell_off || !m->cell_node))) {
        if (err && errlen)
            snprintf(err, errlen, "VTU '%s': incomplete mesh (positions or cells missing)", path);
        return CT_ERR_ARG;
    }
    for (ct_idx c = 0; c < m->ncell; c++) {
        ct_idx a = m->cell_off[c], b = m->cell_off[c + 1];
        int bad = !cell_nodes_ok(m->cell_type[c], b - a);
        for (ct_idx k = a; k < b && !bad; k++)
            bad = m->cell_node[k] < 0 || m->cell_node[k] >= m->nnode;
        if (bad) {
            if (err && errlen)
                snprintf(err, errlen,
                         "VTU '%s': cell %lld has type %d with %lld nodes, or a node out of "
                         "range (expected line 2, triangle 3, quad 4, hexahedron 8 nodes < %lld)",
                         path, (long long)c, m->cell_type[c], (long long)(b - a),
                         (long long)m->nnode);
            return CT_ERR_RANGE;
        }
    }
    if (format == CTD_VTU_RAW)
        return vtu_write_raw(path, m, err, errlen);
    /* The pool holds the chunks of the longest array, at most a group. */
    ct_idx most = m->nnode > m->ncell ? m->nnode : m->ncell;
    if (m->ncell > 0 && m->cell_off[m->ncell] > most)
        most = m->cell_off[m->ncell];
    size_t nch = ((size_t)most + CTI_VTU_CHUNK - 1) / CTI_VTU_CHUNK;
    nch = nch < 1 ? 1 : nch > CTI_VTU_GROUP ? CTI_VTU_GROUP : nch;
    wbuf *w = malloc(sizeof *w);
    char *pool = malloc(nch * CTI_VTU_CHUNK * CTI_VTU_ITEM);
    if (!w || !pool) {
        free(w);
        free(pool);
        return cti_out_nomem(err, errlen);
    }
    w->n = 0;
    w->bad = 0;
    w->pool = pool;
    w->f = fopen(path, "wb");
    if (!w->f) {
        free(pool);
        free(w);
        return cti_out_fail(err, errlen, "cannot create VTU file", path, errno);
    }
    const ct_idx n = m->nnode, nc = m->ncell;
    char h[256];
    wstr(w, "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
            "header_type=\"UInt64\">\n  <UnstructuredGrid>\n");
    snprintf(h, sizeof h, "    <Piece NumberOfPoints=\"%lld\" NumberOfCells=\"%lld\">\n",
             (long long)n, (long long)nc);
    wstr(w, h);
    wstr(w, "      <Points>\n");
    vec3(w, "Points", n, m->x, m->y, m->z, NULL, NULL, NULL);
    wstr(w, "      </Points>\n      <PointData>\n");
    if (m->x0 && m->y0 && m->z0)
        vec3(w, "displacement", n, m->x, m->y, m->z, m->x0, m->y0, m->z0);
    if (m->vx && m->vy && m->vz)
        vec3(w, "velocity", n, m->vx, m->vy, m->vz, NULL, NULL, NULL);
    if (m->fcx && m->fcy && m->fcz)
        vec3(w, "contact_force", n, m->fcx, m->fcy, m->fcz, NULL, NULL, NULL);
    if (m->pen)
        scalar_real(w, "penetration", n, m->pen);
    if (m->node_part)
        scalar_int(w, "Int32", "part_id", n, m->node_part, NULL, NULL);
    if (m->node_active)
        scalar_int(w, "Int32", "active_pairs", n, m->node_active, NULL, NULL);
    wstr(w, "      </PointData>\n      <CellData>\n");
    if (m->cell_part)
        scalar_int(w, "Int32", "part_id", nc, m->cell_part, NULL, NULL);
    wstr(w, "      </CellData>\n      <Cells>\n");
    scalar_int(w, "Int64", "connectivity", nc ? m->cell_off[nc] : 0, NULL, m->cell_node, NULL);
    scalar_int(w, "Int64", "offsets", nc, NULL, m->cell_off + 1, NULL);
    scalar_int(w, "UInt8", "types", nc, NULL, NULL, m->cell_type);
    wstr(w, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    wflush(w);
    int e = errno;
    int bad = w->bad;
    if (fclose(w->f) != 0) {
        bad = 1;
        e = errno;
    }
    free(w->pool);
    free(w);
    if (bad)
        return cti_out_fail(err, errlen, "cannot write VTU file", path, e ? e : EIO);
    return CT_OK;
}

/* ---- PVD series ------------------------------------------------------------- */

static void step_name(const ctd_output *o, int k, char *buf, size_t len)
{
    snprintf(buf, len, "%s_%06d.vtu", o->base, k);
}

/* Rewrite the collection through a temporary file and rename (atomic). */
static int write_pvd(ctd_output *o)
{
    char name[300];
    snprintf(name, sizeof name, "%s.pvd", o->base);
    char *path = cti_out_path(o->dir, name);
    snprintf(name, sizeof name, "%s.pvd.tmp", o->base);
    char *tmp = cti_out_path(o->dir, name);
    if (!path || !tmp) {
        free(path);
        free(tmp);
        return cti_out_nomem(o->err, sizeof o->err);
    }
    int rc = CT_OK;
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        rc = cti_out_fail(o->err, sizeof o->err, "cannot create PVD file", tmp, errno);
    } else {
        int bad = fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
                             "version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n") < 0;
        for (int k = 0; k < o->nstep && !bad; k++) {
            char fn[300];
            step_name(o, k, fn, sizeof fn);
            bad = fprintf(f, "    <DataSet timestep=\"%.15g\" group=\"\" part=\"0\" file=\"%s\"/>\n",
                          o->step_time[k], fn) < 0;
        }
        bad |= fprintf(f, "  </Collection>\n</VTKFile>\n") < 0;
        int e = errno;
        if (fclose(f) != 0) {
            bad = 1;
            e = errno;
        }
        if (bad)
            rc = cti_out_fail(o->err, sizeof o->err, "cannot write PVD file", tmp, e ? e : EIO);
        else if (rename(tmp, path) != 0)
            rc = cti_out_fail(o->err, sizeof o->err, "cannot rename PVD file to", path, errno);
    }
    free(path);
    free(tmp);
    return rc;
}

int ctd_output_vtu(ctd_output *o, double time, const ctd_out_mesh *m)
{
    if (!o)
        return CT_ERR_ARG;
    if (!o->vtu)
        return CT_OK;
    if (o->nstep == o->capstep) {
        int cap = o->capstep ? 2 * o->capstep : 64;
        double *t = realloc(o->step_time, (size_t)cap * sizeof *t);
        if (!t)
            return cti_out_nomem(o->err, sizeof o->err);
        o->step_time = t;
        o->capstep = cap;
    }
    char fn[300];
    step_name(o, o->nstep, fn, sizeof fn);
    char *path = cti_out_path(o->dir, fn);
    if (!path)
        return cti_out_nomem(o->err, sizeof o->err);
    int rc = ctd_vtu_write_as(path, m, o->vtu_format, o->err, sizeof o->err);
    free(path);
    if (rc != CT_OK)
        return rc;
    o->step_time[o->nstep++] = time;
    return write_pvd(o);
}
