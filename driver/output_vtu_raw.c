/*
 * output_vtu_raw.c -- a VTU file whose arrays are raw binary in one
 * appended block (VTK XML format, encoding "raw", header_type UInt64).
 *
 * The XML part names every array with format="appended" and its offset;
 * after "<AppendedData encoding="raw">" and an underscore come the arrays
 * in the same order, each as an 8-byte count of its bytes and its values.
 * Reals are written as the build holds them (Float64, or Float32 in single
 * precision), indices as ct_idx (Int32 or Int64), so nothing is rounded or
 * formatted: the file holds the state bit for bit. The 3-component arrays
 * are interleaved (x y z per point) into a scratch array first, in
 * parallel; the bytes do not depend on the thread count.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "output_internal.h"

#ifdef CT_SINGLE
#define CTI_VTU_REAL "Float32"
#else
#define CTI_VTU_REAL "Float64"
#endif

/* One array of the file: name, VTK type, components, and where its values
 * are (a 3-component array is built from a - b, b may be NULL). */
typedef struct rarr {
    const char *name, *type;
    int ncomp, point; /* point: 1 point data, 0 cell data or cells */
    uint64_t count;   /* values (components included) */
    size_t size;      /* bytes of a value */
    const void *data; /* contiguous values, or NULL for a 3-component array */
    const ct_real *a[3], *b[3];
} rarr;

static int little_endian(void)
{
    const uint16_t one = 1;
    unsigned char c;
    memcpy(&c, &one, 1);
    return c == 1;
}

static uint64_t bytes_of(const rarr *r) { return r->count * (uint64_t)r->size; }

static void header_line(FILE *f, const rarr *r, uint64_t off)
{
    fprintf(f, "        <DataArray type=\"%s\" Name=\"%s\"", r->type, r->name);
    if (r->ncomp > 1)
        fprintf(f, " NumberOfComponents=\"%d\"", r->ncomp);
    fprintf(f, " format=\"appended\" offset=\"%llu\"/>\n", (unsigned long long)off);
}

/* The interleaved values of a 3-component array into t (3 n reals). */
static void interleave(const rarr *r, ct_idx n, ct_real *restrict t)
{
    const ct_real *restrict ax = r->a[0], *restrict ay = r->a[1], *restrict az = r->a[2];
    const ct_real *restrict bx = r->b[0], *restrict by = r->b[1], *restrict bz = r->b[2];
    const int diff = bx != NULL;
#pragma omp parallel for schedule(static) if (n > 65536)
    for (ct_idx i = 0; i < n; i++) {
        t[3 * i] = diff ? ax[i] - bx[i] : ax[i];
        t[3 * i + 1] = diff ? ay[i] - by[i] : ay[i];
        t[3 * i + 2] = diff ? az[i] - bz[i] : az[i];
    }
}

int cti_vtu_write_raw(FILE *f, const ctd_out_mesh *m)
{
    const ct_idx n = m->nnode, nc = m->ncell;
    const uint64_t un = (uint64_t)n, uc = (uint64_t)nc;
    const size_t rs = sizeof(ct_real), is = sizeof(ct_idx);
    const char *itype = is == 8 ? "Int64" : "Int32";
    rarr r[12];
    int k = 0;
#define CTI_VEC(nm, X, Y, Z, BX, BY, BZ)                                                        \
    r[k++] = (rarr){nm, CTI_VTU_REAL, 3, 1, 3 * un, rs, NULL, {X, Y, Z}, {BX, BY, BZ}}
#define CTI_ARR(nm, ty, pt, cnt, sz, d)                                                         \
    r[k++] = (rarr){nm, ty, 1, pt, cnt, sz, d, {NULL, NULL, NULL}, {NULL, NULL, NULL}}
    CTI_VEC("Points", m->x, m->y, m->z, NULL, NULL, NULL);
    const int npoints = k;
    if (m->x0 && m->y0 && m->z0)
        CTI_VEC("displacement", m->x, m->y, m->z, m->x0, m->y0, m->z0);
    if (m->vx && m->vy && m->vz)
        CTI_VEC("velocity", m->vx, m->vy, m->vz, NULL, NULL, NULL);
    if (m->fcx && m->fcy && m->fcz)
        CTI_VEC("contact_force", m->fcx, m->fcy, m->fcz, NULL, NULL, NULL);
    if (m->pen)
        CTI_ARR("penetration", CTI_VTU_REAL, 1, un, rs, m->pen);
    if (m->node_part)
        CTI_ARR("part_id", "Int32", 1, un, 4, m->node_part);
    if (m->node_active)
        CTI_ARR("active_pairs", "Int32", 1, un, 4, m->node_active);
    const int npoint_data = k;
    if (m->cell_part)
        CTI_ARR("part_id", "Int32", 0, uc, 4, m->cell_part);
    const int ncell_data = k;
    CTI_ARR("connectivity", itype, 0, nc ? (uint64_t)m->cell_off[nc] : 0, is, m->cell_node);
    CTI_ARR("offsets", itype, 0, uc, is, nc ? m->cell_off + 1 : NULL);
    CTI_ARR("types", "UInt8", 0, uc, 1, m->cell_type);
#undef CTI_VEC
#undef CTI_ARR
    /* The XML part, each array's offset the sum of the blocks before it. */
    uint64_t off[12], o = 0;
    for (int i = 0; i < k; i++) {
        off[i] = o;
        o += 8 + bytes_of(&r[i]);
    }
    fprintf(f,
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
            "byte_order=\"%s\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n"
            "    <Piece NumberOfPoints=\"%lld\" NumberOfCells=\"%lld\">\n      <Points>\n",
            little_endian() ? "LittleEndian" : "BigEndian", (long long)n, (long long)nc);
    for (int i = 0; i < k; i++) {
        if (i == npoints)
            fputs("      </Points>\n      <PointData>\n", f);
        if (i == npoint_data)
            fputs("      </PointData>\n      <CellData>\n", f);
        if (i == ncell_data)
            fputs("      </CellData>\n      <Cells>\n", f);
        header_line(f, &r[i], off[i]);
    }
    fputs("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
          "  <AppendedData encoding=\"raw\">\n_",
          f);
    /* The blocks. */
    ct_real *t = n > 0 ? malloc(3 * (size_t)n * rs) : NULL;
    int bad = n > 0 && !t;
    for (int i = 0; i < k && !bad; i++) {
        uint64_t nb = bytes_of(&r[i]);
        bad |= fwrite(&nb, 8, 1, f) != 1;
        if (nb == 0 || bad)
            continue;
        const void *d = r[i].data;
        if (!d) {
            interleave(&r[i], n, t);
            d = t;
        }
        bad |= fwrite(d, 1, (size_t)nb, f) != (size_t)nb;
    }
    free(t);
    fputs("\n  </AppendedData>\n</VTKFile>\n", f);
    return bad || ferror(f) ? -1 : 0;
}
