/*
 * narrow_internal.h -- helpers shared by the narrow-phase kernels
 * (project.c and its block kernels project_tri.c, project_quad.c,
 * project_newton.c; edge.c and its block kernel edge_block.c).
 *
 * Structure of every pair loop: for a block of at most CTI_NR_BLOCK pairs,
 * a scalar loop (cti_nr_fetch) first copies the coordinates of each pair,
 * loaded through the indices, into contiguous per-block arrays; then one
 * `#pragma omp simd` loop reads them with unit stride and computes every
 * output of the block with plain scalar locals and selects only (no small
 * arrays, no data-dependent branch, no mixed-width integer), so that the
 * compiler if-converts it and vectorises it. The copy costs two scalar
 * loads and stores a value, which is cheaper than the vector gathers it
 * replaces (microcoded on AMD Zen 4, several times the scalar loads), and
 * the vector loop, free of 32-bit indices, runs 8 double lanes instead of
 * 16 and spills less. Flags are computed as cti_nr_int,
 * the integer type of the width of ct_real, and narrowed to uint8_t by a
 * separate loop afterwards.
 * Only +, -, *, /, sqrt and selects are used (no libm call whose vector
 * variant could differ), so a pair gives bit-identical results whether it
 * lands in a vector lane or in a scalar remainder loop.
 */
#ifndef NARROW_INTERNAL_H
#define NARROW_INTERNAL_H

#include "ct_internal.h"

/* Pairs per block: the unit of work of the parallel loops (so the split of
 * the work among threads never changes which code path a pair takes).
 * Node-segment: 64 (its copy of the coordinates, 7.5 KB in double, and the
 * vector loop alternate more finely than with 128, which measured 5-15%
 * faster at 10^6 pairs, from memory, and the same in cache). Edge-edge
 * keeps 128 (64 was no better). */
#define CTI_NR_BLOCK 64
#define CTI_EE_BLOCK 128

#ifdef CT_SINGLE
typedef int32_t cti_nr_int;
#define CTI_NR_AREA_TOL 1.0e-6f  /* degenerate: area <= tol * longest edge^2 */
#define CTI_NR_IN_TOL 1.0e-5f    /* footprint tolerance in parameter space */
#define CTI_NR_ON_TOL 1.0e-6f    /* on the surface: D <= tol * segment size */
#define CTI_NR_NEWTON_TOL 1.0e-5f
#define CTI_NR_NEWTON_OFF_TOL 1.0e-4f
#define CTI_NR_EDGE_TOL 1.0e-6f  /* edge-edge: degenerate edge length ratio */
#else
typedef int64_t cti_nr_int;
#define CTI_NR_AREA_TOL 1.0e-12
#define CTI_NR_IN_TOL 1.0e-10
#define CTI_NR_ON_TOL 1.0e-14
#define CTI_NR_NEWTON_TOL 1.0e-12
#define CTI_NR_NEWTON_OFF_TOL 1.0e-9
#define CTI_NR_EDGE_TOL 1.0e-12
#endif

/* A CT_NARROW_* flag as cti_nr_int. The flags of the pair loops are built
 * in that type: an int in the loop (the type of the enum constants) makes
 * gcc vectorise it 16 lanes wide in double precision, two vectors per
 * double, which spills registers. */
#define CTI_NR_F(name) ((cti_nr_int)CT_NARROW_##name)

/* `#pragma omp simd` on the pair loops. Neither compiler vectorises sqrt
 * while it may set errno: the loops vectorise only in a build with
 * -fno-math-errno (same, correctly rounded results). gcc 12 and clang 14
 * both vectorise every pair loop (see `make vecreport`).
 *
 * One vector of pairs per iteration. Their time is set in good part by one
 * pair's chain of dependent operations (a division, a square root and
 * another division, 13-20 cycles each; perf puts the node-triangle loop's
 * samples on the instructions waiting for them). Two vectors per
 * iteration do not help: `simdlen(16)` (77a392c to this change) left gcc
 * 12's vector loop at one vector of 8 doubles (only its remainder became
 * scalar; plain `omp simd` measured 0.95-1.01x against it), and the loop
 * written by hand as two independent halves per iteration, which gcc does
 * vectorise as two chains, ran node-triangle 0.70-0.84x (it needs twice the
 * 32 vector registers). */
#define CTI_NR_SIMD _Pragma("omp simd")

/* Newton (project_newton.c): one or two steps from the linear start for
 * every pair of a block (cti_nr_block_newton); up to CTI_NR_NEWTON_VEC_IT
 * steps for the whole block when more than 1 / CTI_NR_NEWTON_MORE_DEN of it
 * has not converged (a converged pair keeps its values); then the cap for
 * the pairs still not converged (further vector rounds of
 * CTI_NR_NEWTON_VEC_IT steps over those pairs alone). A flat parallelogram
 * converges in 1 step, a flat or smooth plate in 2; 3
 * (single) or 4 (double) steps converge all but a few in 1e5 pairs of
 * plates warped by 5% of the element size, but about half of a crumpled
 * sheet's candidates need more (nodes off the quadrangle); a step costs
 * about 35 instructions per pair in double with AVX2, 15 in single. */
#ifdef CT_SINGLE
#define CTI_NR_NEWTON_VEC_IT 3
#else
#define CTI_NR_NEWTON_VEC_IT 4
#endif
#define CTI_NR_NEWTON_MAX_IT 30
/* From step CTI_NR_NEWTON_VEC_IT on, the iterations of a pair end when |s|
 * or |t| exceeds CTI_NR_NEWTON_FAR and no point inside the quadrangle is
 * nearer the node than its boundary, by the bound of cti_quad_hull_q
 * (within a relative CTI_NR_NEWTON_OFF_TOL of the squared distance): its
 * answer is then the boundary's, as it would be at the cap. */
#define CTI_NR_NEWTON_FAR 1.5
/* 3 and 24 measured the same as 8 on warped and crumpled quadrangles. */
#define CTI_NR_NEWTON_MORE_DEN 8

/* Everything a node-segment block kernel needs (internal; the public API
 * takes the arrays one by one). */
typedef struct cti_nr_args {
    const ct_idx *node, *seg, *n1, *n2, *n3, *n4;
    /* ct_narrow_node_slots: seg is the selection and the node of pair j is
     * node_sel[seg[j]] (node is then NULL); NULL otherwise. */
    const ct_idx *node_sel;
    const ct_real *x, *y, *z;
    /* The packed entry points (ct_coords_pack): (x, y, z, w) of node i at
     * xyzw[4 i..4 i + 3], x, y and z then NULL; NULL otherwise. */
    const ct_real *xyzw;
    const ct_real *gap_node, *gap_seg;
    ct_real gap, gap_max_s, gap_max_m;
    int two_sided;
    const ct_contact_geo *out;
} cti_nr_args;

/* Per-block scratch: the pair gaps (computed by cti_nr_gather, a plain loop
 * with the optional per-node and per-segment gaps), the coordinates of the
 * pairs (cti_nr_fetch: the node p and the corners X1..X4, as stored in
 * x, y, z) and the integer flags of the block before they are narrowed to
 * bytes.
 *
 * The coordinates are stored two to an entry (CTI_PUT2), pair j's at
 * [2 j] and [2 j + 1]: (x, y) of p and of each corner, then (pz, z1),
 * (z2, z3); z4 alone. The copy stores two values at a time (6 stores a
 * triangle pair instead of 12, 8 a quadrangle pair instead of 15), and
 * the vector loops separate them with permutes. */
typedef struct cti_nr_blk {
    _Alignas(64) ct_real g[CTI_NR_BLOCK];
    _Alignas(64) ct_real pxy[2 * CTI_NR_BLOCK];
    _Alignas(64) ct_real xy1[2 * CTI_NR_BLOCK], xy2[2 * CTI_NR_BLOCK];
    _Alignas(64) ct_real xy3[2 * CTI_NR_BLOCK], xy4[2 * CTI_NR_BLOCK];
    _Alignas(64) ct_real z01[2 * CTI_NR_BLOCK], z23[2 * CTI_NR_BLOCK];
    _Alignas(64) ct_real z4[CTI_NR_BLOCK];
    _Alignas(64) cti_nr_int flag[CTI_NR_BLOCK];
    /* Newton: whether the last block ran its second fixed loop (a guess
     * for the next one, see cti_nr_block_newton; 0 at the start). */
    int newton_more;
} cti_nr_blk;

void cti_nr_gather(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b);

/* The coordinates of the pairs from k0 on into b->px.. b->z4, from x, y, z
 * or from the packed xyzw (the same values), up to n pairs or to the first
 * pair whose segment is not of the kind `quad` says (a triangle: n3 ==
 * n4); returns how many it copied (at least 1 when the pair at k0 is of
 * that kind). The fourth corner only when quad != 0 (a triangle kernel
 * does not read it). */
ct_idx cti_nr_fetch(const cti_nr_args *a, ct_idx k0, ct_idx n, int quad, cti_nr_blk *b);

/* Block kernels: pairs [k0, k0 + n), n <= CTI_NR_BLOCK, all triangles or all
 * quadrangles, gaps in b->g (b->flag is their scratch). */
void cti_nr_block_tri(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b);
void cti_nr_block_4tri(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b);
void cti_nr_block_newton(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b);
void cti_nr_block_closed(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b);

/* Edge-edge: the nb <= CTI_EE_BLOCK pairs of the block at k0, their end
 * points in C (as cti_ee_fetch in edge.c stores them) and gaps in G, into
 * out at k0 and their integer flags into F. */
void cti_ee_block(ct_idx nb, const ct_real *restrict G,
                  const ct_real (*restrict C)[2 * CTI_EE_BLOCK], const ct_edge_geo *out,
                  ct_idx k0, cti_nr_int *restrict F);

/* The output arrays of a block as restrict locals o_*, offset by k0. */
#define CTI_NR_OUTPTRS(a, k0)                                                             \
    const ct_contact_geo *o_ = (a)->out;                                                  \
    ct_real *restrict o_dist = o_->dist + (k0), *restrict o_pen = o_->pen + (k0);         \
    ct_real *restrict o_nx = o_->nx + (k0), *restrict o_ny = o_->ny + (k0);               \
    ct_real *restrict o_nz = o_->nz + (k0), *restrict o_cx = o_->cx + (k0);               \
    ct_real *restrict o_cy = o_->cy + (k0), *restrict o_cz = o_->cz + (k0);               \
    ct_real *restrict o_h1 = o_->h1 + (k0), *restrict o_h2 = o_->h2 + (k0);               \
    ct_real *restrict o_h3 = o_->h3 + (k0), *restrict o_h4 = o_->h4 + (k0);               \
    ct_real *restrict o_gap = o_->gap + (k0);                                             \
    cti_nr_int *restrict o_iflag = b->flag

/* Write pair j of the block, or the documented skip values when bad != 0
 * or when cti_nr_finish found the distance overflowed (flag NONFINITE);
 * the contact point (cx, cy, cz) is relative to (ox, oy, oz) (see
 * CTI_NR_LOAD). */
#define CTI_NR_STORE(j, bad, dist, pen, nx, ny, nz, cx, cy, cz, h1, h2, h3, h4, g, flag)  \
    do {                                                                                  \
        const cti_nr_int b_ = (bad) ? (bad) : ((flag) & CTI_NR_F(NONFINITE));             \
        o_dist[j] = b_ ? CT_NARROW_FAR : (dist);                                          \
        o_pen[j] = b_ ? 0 : (pen);                                                        \
        o_nx[j] = b_ ? 0 : (nx);                                                          \
        o_ny[j] = b_ ? 0 : (ny);                                                          \
        o_nz[j] = b_ ? 1 : (nz);                                                          \
        o_cx[j] = b_ ? 0 : (cx) + ox;                                                     \
        o_cy[j] = b_ ? 0 : (cy) + oy;                                                     \
        o_cz[j] = b_ ? 0 : (cz) + oz;                                                     \
        o_h1[j] = b_ ? 0 : (h1);                                                          \
        o_h2[j] = b_ ? 0 : (h2);                                                          \
        o_h3[j] = b_ ? 0 : (h3);                                                          \
        o_h4[j] = b_ ? 0 : (h4);                                                          \
        o_gap[j] = (b_ & CTI_NR_F(NONFINITE)) ? 0 : (g);                                  \
        o_iflag[j] = b_ ? b_ : (flag);                                                    \
    } while (0)

/* Narrow the block's integer flags to the output bytes. */
static inline void cti_nr_flags_out(const cti_nr_int *restrict f, uint8_t *restrict o,
                                    ct_idx n)
{
    for (ct_idx j = 0; j < n; j++)
        o[j] = (uint8_t)f[j];
}

/* The block's coordinates and gaps (fetched, see cti_nr_fetch) as restrict
 * locals i_*. */
#define CTI_NR_INPTRS(a, k0)                                                              \
    const ct_real *restrict i_pxy = b->pxy, *restrict i_xy1 = b->xy1;                     \
    const ct_real *restrict i_xy2 = b->xy2, *restrict i_xy3 = b->xy3;                     \
    const ct_real *restrict i_xy4 = b->xy4, *restrict i_z01 = b->z01;                     \
    const ct_real *restrict i_z23 = b->z23, *restrict i_z4 = b->z4;                       \
    const ct_real *restrict i_g = b->g;                                                   \
    (void)(a), (void)(k0)

/* Declare the scalars of pair j of a block, read from the fetched arrays,
 * translated so that X1 is at the origin: (ox, oy, oz) = X1, p = (px, py,
 * pz), X2..X4 = (x2, y2, z2).., the gap g, and nonfin = 1 when a coordinate
 * or the gap is NaN/Inf (a sum of all of them is then NaN or Inf; finite
 * values cannot overflow it short of 1e37). Working relative to X1 keeps
 * differences of nearby coordinates accurate far from the origin, which
 * single precision needs. */
#define CTI_NR_LOAD(j)                                                                     \
    const ct_real ox = i_xy1[2 * (j)], oy = i_xy1[2 * (j) + 1], oz = i_z01[2 * (j) + 1];   \
    const ct_real px = i_pxy[2 * (j)] - ox, py = i_pxy[2 * (j) + 1] - oy;                  \
    const ct_real pz = i_z01[2 * (j)] - oz;                                                \
    const ct_real x2 = i_xy2[2 * (j)] - ox, y2 = i_xy2[2 * (j) + 1] - oy;                  \
    const ct_real z2 = i_z23[2 * (j)] - oz;                                                \
    const ct_real x3 = i_xy3[2 * (j)] - ox, y3 = i_xy3[2 * (j) + 1] - oy;                  \
    const ct_real z3 = i_z23[2 * (j) + 1] - oz;                                            \
    const ct_real x4 = i_xy4[2 * (j)] - ox, y4 = i_xy4[2 * (j) + 1] - oy;                  \
    const ct_real z4 = i_z4[j] - oz;                                                       \
    const ct_real g = i_g[j];                                                              \
    const ct_real zsum_ = (((px + py) + (pz + x2)) + ((y2 + z2) + (x3 + y3))) +            \
                          (((z3 + x4) + (y4 + z4)) + g);                                   \
    const cti_nr_int nonfin = !(zsum_ - zsum_ == 0);                                       \
    (void)x4; (void)y4; (void)z4

/* Force inlining of the larger helpers: a call left in a simd loop stops
 * its vectorisation. */
#if defined(__GNUC__)
#define CTI_NR_INLINE static inline __attribute__((always_inline))
#else
#define CTI_NR_INLINE static inline
#endif

static inline ct_real cti_nr_clamp01(ct_real u)
{
    u = u > 0 ? u : 0;
    return u < 1 ? u : 1;
}

/* The three components of the cross product V x P of the vectors named by
 * the scalars Vx, Vy, Vz and Px, Py, Pz, as a list of arguments. */
#define CTI_NR_KROSS(V, P)                                                                \
    V##y * P##z - V##z * P##y, V##z * P##x - V##x * P##z, V##x * P##y - V##y * P##x

/*
 * Closest point of triangle (a, a + ab, a + ac) to a + ap, branch-free with
 * one division: the Voronoi region of the point (vertex, edge or face) is
 * found from dot products, the numerators and the denominator of its
 * parameters are selected, and divided once. Then the residual is formed
 * explicitly, so the squared distance *q is accurate near the surface (the
 * 4-triangle method compares it). Outputs: *q, the weights of a, b and c
 * (*u, *v, *w, each in [0, 1], their sum 1 up to rounding), the unnormalised normal ab x ac and
 * its squared length *nn, the squared longest edge *l2, and *in = 1 when
 * the unclamped projection lies inside within CTI_NR_IN_TOL.
 *
 * kb = ab x ap and kc = ac x ap (CTI_NR_KROSS) are inputs. In a fan of
 * triangles around one vertex (the 4-triangle quad, vertex a at the
 * centroid) a corner's product is kc of one triangle and kb of the next:
 * written the same way for both, the compiler forms it once, where the
 * former ap x ac and ab x ap, the same products subtracted in the other
 * order, were formed twice. cti_nr_tri computes them for a lone triangle.
 */
CTI_NR_INLINE void cti_nr_tri_k(ct_real abx, ct_real aby, ct_real abz, ct_real acx,
                                ct_real acy, ct_real acz, ct_real apx, ct_real apy,
                                ct_real apz, ct_real kbx, ct_real kby, ct_real kbz,
                                ct_real kcx, ct_real kcy, ct_real kcz, ct_real *q, ct_real *u,
                                ct_real *v, ct_real *w, ct_real *nx, ct_real *ny,
                                ct_real *nz, ct_real *nn, ct_real *l2, cti_nr_int *in)
{
    ct_real cx = aby * acz - abz * acy;
    ct_real cy = abz * acx - abx * acz;
    ct_real cz = abx * acy - aby * acx;
    ct_real n2 = cx * cx + cy * cy + cz * cz;
    ct_real aa = abx * abx + aby * aby + abz * abz;
    ct_real cc = acx * acx + acy * acy + acz * acz;
    ct_real d1 = abx * apx + aby * apy + abz * apz;
    ct_real d2 = acx * apx + acy * apy + acz * apz;
    ct_real bcx = acx - abx, bcy = acy - aby, bcz = acz - abz;
    ct_real bpx = apx - abx, bpy = apy - aby, bpz = apz - abz;
    ct_real bb = bcx * bcx + bcy * bcy + bcz * bcz;
    ct_real e3 = bcx * bpx + bcy * bpy + bcz * bpz; /* (b->c).(b->p) */
    ct_real lm = aa > cc ? aa : cc;
    lm = lm > bb ? lm : bb;
    /* ab.(p - b) and ac.(p - c). */
    ct_real d3 = d1 - aa, d6 = d2 - cc;
    /* Face: barycentric numerators over the determinant |ab x ac|^2, as
     * (ap x ac).n and (ab x ap).n: equal to cc d1 - ac d2 and aa d2 - ac d1
     * (Lagrange's identity) but without their cancellation, which on a
     * needle (a long edge L over a height h) costs eps L^2/h^2 of the
     * weights: 0.3 of the height in single precision at L/h = 2000
     * (validation case c). */
    /* (ap x ac).n = -(kc.n) exactly: ap x ac and ac x ap have the same
     * products, subtracted in the other order. */
    ct_real fv = -(kcx * cx + kcy * cy + kcz * cz);
    ct_real fw = kbx * cx + kby * cy + kbz * cz;
    /* (bc x bp).n, not n2 - fv - fw: on a needle whose far corner is a,
     * those three are of the order of the long edge squared and their
     * difference can lose the sign that picks the edge b-c's region. */
    ct_real fu = (bcy * bpz - bcz * bpy) * cx + (bcz * bpx - bcx * bpz) * cy +
                 (bcx * bpy - bcy * bpx) * cz;
    ct_real lim = -CTI_NR_IN_TOL * n2;
    *in = (fv >= lim) & (fw >= lim) & (fu >= lim);
    /* Regions in increasing priority; the last true test wins. */
    ct_real un = fu, vn = fv, wn = fw, den = n2;
    cti_nr_int r = (fu <= 0) & (e3 >= 0) & (e3 <= bb); /* edge b-c */
    un = r ? 0 : un;
    vn = r ? bb - e3 : vn;
    wn = r ? e3 : wn;
    den = r ? bb : den;
    r = (fv <= 0) & (d2 >= 0) & (d6 <= 0);             /* edge a-c */
    un = r ? -d6 : un;
    vn = r ? 0 : vn;
    wn = r ? d2 : wn;
    den = r ? cc : den;
    /* The vertex tests ab.(p - c) <= ac.(p - c) and ac.(p - b) <= ab.(p - b)
     * are (b - c).(p - c) <= 0 and (c - b).(p - b) <= 0, i.e. e3 >= bb and
     * e3 <= 0, formed from the short vectors b->c and b->p; not as the
     * differences of dot products with the edges from a, which on a needle
     * whose far corner is a are of the order of its length squared and lost
     * their sign (a point near the edge b-c went to vertex c, 0.88 away
     * instead of 0.51). */
    r = (d6 >= 0) & (e3 >= bb);                        /* vertex c */
    un = r ? 0 : un;
    vn = r ? 0 : vn;
    wn = r ? 1 : wn;
    den = r ? 1 : den;
    r = (fw <= 0) & (d1 >= 0) & (d3 <= 0);             /* edge a-b */
    un = r ? -d3 : un;
    vn = r ? d1 : vn;
    wn = r ? 0 : wn;
    den = r ? aa : den;
    r = (d3 >= 0) & (e3 <= 0);                         /* vertex b */
    un = r ? 0 : un;
    vn = r ? 1 : vn;
    wn = r ? 0 : wn;
    den = r ? 1 : den;
    r = (d1 <= 0) & (d2 <= 0);                         /* vertex a */
    un = r ? 1 : un;
    vn = r ? 0 : vn;
    wn = r ? 0 : wn;
    den = r ? 1 : den;
    ct_real inv = 1 / (den > 0 ? den : 1);
    ct_real vv = cti_nr_clamp01(vn * inv), ww = cti_nr_clamp01(wn * inv);
    *u = cti_nr_clamp01(un * inv);
    ct_real rx = apx - vv * abx - ww * acx;
    ct_real ry = apy - vv * aby - ww * acy;
    ct_real rz = apz - vv * abz - ww * acz;
    *q = rx * rx + ry * ry + rz * rz;
    *v = vv;
    *w = ww;
    *nx = cx; *ny = cy; *nz = cz;
    *nn = n2;
    *l2 = lm;
}

/* cti_nr_tri_k for one triangle. */
CTI_NR_INLINE void cti_nr_tri(ct_real abx, ct_real aby, ct_real abz, ct_real acx,
                              ct_real acy, ct_real acz, ct_real apx, ct_real apy,
                              ct_real apz, ct_real *q, ct_real *u, ct_real *v, ct_real *w,
                              ct_real *nx, ct_real *ny, ct_real *nz, ct_real *nn,
                              ct_real *l2, cti_nr_int *in)
{
    cti_nr_tri_k(abx, aby, abz, acx, acy, acz, apx, apy, apz, CTI_NR_KROSS(ab, ap),
                 CTI_NR_KROSS(ac, ap), q, u, v, w, nx, ny, nz, nn, l2, in);
}

/*
 * The sidedness rule and the outputs common to every node-segment method
 * (see ct_narrow.h): p and the contact point c, the segment normal at c
 * (Nx, Ny, Nz), unnormalised, of squared length nn, the squared segment
 * size l2, in the footprint test, g the pair's gap. A square root and a
 * division normalise whichever vector becomes the normal; one square
 * root gives the distance.
 */
CTI_NR_INLINE void cti_nr_finish(ct_real px, ct_real py, ct_real pz, ct_real cx, ct_real cy,
                                 ct_real cz, ct_real Nx, ct_real Ny, ct_real Nz, ct_real nn,
                                 ct_real l2, cti_nr_int in, ct_real g, int two_sided,
                                 ct_real *dist, ct_real *pen, ct_real *nx, ct_real *ny,
                                 ct_real *nz, cti_nr_int *flag)
{
    ct_real rx = px - cx, ry = py - cy, rz = pz - cz;
    ct_real r2 = rx * rx + ry * ry + rz * rz;
    /* Finite coordinates whose squares overflow (near 1e154, single 1e19)
     * give an infinite or NaN r2: the pair is then skipped as non-finite
     * (CTI_NR_STORE), not given an infinite distance and a zero normal. */
    const cti_nr_int ovf = !(r2 - r2 == 0);
    ct_real r = CTI_SQRT(r2);
    /* r <= tol * sqrt(l2), squared. */
    cti_nr_int on = r2 <= (CTI_NR_ON_TOL * CTI_NR_ON_TOL) * l2;
    ct_real side = rx * Nx + ry * Ny + rz * Nz;
    cti_nr_int behind = (!two_sided) & (!on) & (side < 0);
    cti_nr_int usen = behind | on;
    ct_real vx = usen ? Nx : rx, vy = usen ? Ny : ry, vz = usen ? Nz : rz;
    /* 1 / sqrt of the chosen squared length (1 when it is not positive),
     * formed per candidate and then selected: the segment normal's, from
     * nn, which is known long before r, starts early, and the residual's
     * reuses r, so only one division follows the square root of r2 on the
     * pair's longest chain of dependent operations (which bounds this
     * loop: a division or square root takes 13-20 cycles to deliver). The
     * same values as selecting the length first: r > 0 exactly when
     * r2 > 0. */
    ct_real inn = 1 / CTI_SQRT(nn > 0 ? nn : 1);
    ct_real inr = 1 / (r > 0 ? r : 1);
    ct_real inv = usen ? inn : inr;
    ct_real gr = g - r;
    *dist = behind ? -r : r;
    *pen = behind ? (in ? g + r : 0) : (gr > 0 ? gr : 0);
    *nx = vx * inv;
    *ny = vy * inv;
    *nz = vz * inv;
    *flag = (behind ? CTI_NR_F(BEHIND) : 0) | (in ? 0 : CTI_NR_F(OUTSIDE)) |
            (ovf ? CTI_NR_F(NONFINITE) : 0);
}

#endif /* NARROW_INTERNAL_H */
