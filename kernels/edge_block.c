/*
 * edge_block.c -- the edge-edge block kernel: closest points of the
 * pairs of one block, one `#pragma omp simd` loop (the method is in the
 * head of edge.c, which fetches the block's end points and gaps and runs
 * the blocks in parallel). Like the other block kernels it uses no OpenMP
 * construct but simd, so the build may compile it with another compiler
 * than the rest (see NARROW_CC in the Makefile).
 */
#include "narrow_internal.h"

#define CTI_EE_PAR_TOL (16 * CTI_EPS)

/* |w + s u - t v|^2, the squared distance of Pa(s) and Pb(t). */
static inline ct_real cti_ee_q(ct_real ux, ct_real uy, ct_real uz, ct_real vx, ct_real vy,
                               ct_real vz, ct_real wx, ct_real wy, ct_real wz, ct_real s,
                               ct_real t)
{
    ct_real rx = wx + s * ux - t * vx;
    ct_real ry = wy + s * uy - t * vy;
    ct_real rz = wz + s * uz - t * vz;
    return rx * rx + ry * ry + rz * rz;
}

/* Keep (s, t) when it is strictly closer than the best so far. */
#define CTI_EE_CAND(s_, t_)                                                               \
    do {                                                                                  \
        ct_real cs_ = (s_), ct_ = (t_);                                                   \
        ct_real q_ = cti_ee_q(ux, uy, uz, vx, vy, vz, wx, wy, wz, cs_, ct_);              \
        cti_nr_int take_ = q_ < bq;                                                       \
        bs = take_ ? cs_ : bs;                                                            \
        bt = take_ ? ct_ : bt;                                                            \
        bq = take_ ? q_ : bq;                                                             \
    } while (0)

/* The block's loop; pts (a constant where it is inlined): whether the
 * closest points are written (out->pax and the five others not NULL). */
static inline __attribute__((always_inline)) void
cti_ee_block_loop(ct_idx nb, const ct_real *restrict G,
                  const ct_real (*restrict C)[2 * CTI_EE_BLOCK], const ct_edge_geo *out,
                  ct_idx k0, cti_nr_int *restrict F, const int pts)
{
    ct_real *restrict odist = out->dist, *restrict open = out->pen;
    ct_real *restrict onx = out->nx, *restrict ony = out->ny, *restrict onz = out->nz;
    ct_real *restrict osa = out->sa, *restrict osb = out->sb;
    ct_real *restrict opax = out->pax, *restrict opay = out->pay, *restrict opaz = out->paz;
    ct_real *restrict opbx = out->pbx, *restrict opby = out->pby, *restrict opbz = out->pbz;
    ct_real *restrict ogap = out->gap;
    const ct_real *restrict A1 = C[0], *restrict A2 = C[1], *restrict B1 = C[2];
    const ct_real *restrict B2 = C[3], *restrict ZA = C[4], *restrict ZB = C[5];
    CTI_NR_SIMD
    for (ct_idx j = 0; j < nb; j++) {
        ct_idx k = k0 + j;
        /* Relative to A1 (accuracy far from the origin). */
        const ct_real ox = A1[2 * j], oy = A1[2 * j + 1], oz = ZA[2 * j];
        const ct_real ux = A2[2 * j] - ox, uy = A2[2 * j + 1] - oy, uz = ZA[2 * j + 1] - oz;
        const ct_real b1x = B1[2 * j] - ox, b1y = B1[2 * j + 1] - oy, b1z = ZB[2 * j] - oz;
        const ct_real b2x = B2[2 * j] - ox, b2y = B2[2 * j + 1] - oy;
        const ct_real b2z = ZB[2 * j + 1] - oz;
        const ct_real g = G[j];
        /* NaN or Inf anywhere makes the sum NaN or Inf. */
        ct_real zs = ((ux + uy) + (uz + b1x)) + ((b1y + b1z) + (b2x + b2y)) + (b2z + g);
        cti_nr_int nonfin = !(zs - zs == 0);
        ct_real vx = b2x - b1x, vy = b2y - b1y, vz = b2z - b1z;
        ct_real wx = -b1x, wy = -b1y, wz = -b1z;
        ct_real a = ux * ux + uy * uy + uz * uz;
        ct_real bb = ux * vx + uy * vy + uz * vz;
        ct_real c = vx * vx + vy * vy + vz * vz;
        ct_real d = ux * wx + uy * wy + uz * wz;
        ct_real e = vx * wx + vy * wy + vz * wz;
        ct_real cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
        ct_real den = cx * cx + cy * cy + cz * cz;
        cti_nr_int par = !(den > CTI_EE_PAR_TOL * a * c);
        /* 1/a and 1/c from one division. */
        ct_real ag = a > 0 ? a : 1, cg = c > 0 ? c : 1;
        ct_real iac = 1 / (ag * cg);
        ct_real ai = cg * iac, ci = ag * iac;
        /* General case. */
        ct_real sg = (bb * e - c * d) / (par ? 1 : den);
        /* Parallel: B1 and B2 on A's line are at -d/a and (b - d)/a. */
        ct_real q1 = -d * ai, q2 = (bb - d) * ai;
        ct_real lo = q1 < q2 ? q1 : q2, hi = q1 < q2 ? q2 : q1;
        ct_real olo = lo > 0 ? lo : 0, ohi = hi < 1 ? hi : 1;
        ct_real sp = olo <= ohi ? (ct_real)0.5 * (olo + ohi) : (hi < 0 ? 0 : 1);
        ct_real s = cti_nr_clamp01(par ? sp : sg);
        ct_real t = cti_nr_clamp01((bb * s + e) * ci);
        s = cti_nr_clamp01((bb * t - d) * ai);
        /* The minimum is interior to both edges (found above) or has an
         * end point: the four end-point projections are candidates too,
         * which makes nearly parallel edges exact. Ties keep the
         * earlier one. */
        ct_real bs = s, bt = t, bq = cti_ee_q(ux, uy, uz, vx, vy, vz, wx, wy, wz, s, t);
        CTI_EE_CAND(0, cti_nr_clamp01(e * ci));
        CTI_EE_CAND(1, cti_nr_clamp01((e + bb) * ci));
        CTI_EE_CAND(cti_nr_clamp01(-d * ai), 0);
        CTI_EE_CAND(cti_nr_clamp01((bb - d) * ai), 1);
        s = bs;
        t = bt;
        ct_real lm = a > c ? a : c, ls = a < c ? a : c;
        cti_nr_int degen = !(ls > CTI_NR_EDGE_TOL * CTI_NR_EDGE_TOL * lm);
        cti_nr_int bad = nonfin ? CTI_NR_F(NONFINITE) : (degen ? CTI_NR_F(DEGENERATE) : 0);
        ct_real pax = s * ux, pay = s * uy, paz = s * uz;
        ct_real pbx = b1x + t * vx, pby = b1y + t * vy, pbz = b1z + t * vz;
        ct_real rx = pax - pbx, ry = pay - pby, rz = paz - pbz;
        ct_real r2 = rx * rx + ry * ry + rz * rz;
        ct_real dist = CTI_SQRT(r2);
        /* dist <= tol * sqrt(lm), squared. */
        cti_nr_int touch = r2 <= (CTI_NR_ON_TOL * CTI_NR_ON_TOL) * lm;
        /* Touching: u x v, or for parallel edges u x (the axis along
         * which u is smallest), then oriented from B's midpoint towards
         * A's. */
        ct_real max_ = (ct_real)0.5 * (ux - (b1x + b2x));
        ct_real may_ = (ct_real)0.5 * (uy - (b1y + b2y));
        ct_real maz_ = (ct_real)0.5 * (uz - (b1z + b2z));
        ct_real aux = CTI_FABS(ux), auy = CTI_FABS(uy), auz = CTI_FABS(uz);
        /* Selects of reals and single comparisons: combined boolean
         * masks stop gcc's vectoriser here. */
        cti_nr_int kx = aux <= (auy < auz ? auy : auz), ky = auy <= auz;
        ct_real pcx = kx ? 0 : (ky ? -uz : uy);
        ct_real pcy = kx ? uz : (ky ? 0 : -ux);
        ct_real pcz = kx ? -uy : (ky ? ux : 0);
        ct_real tx = par ? pcx : cx, ty = par ? pcy : cy, tz = par ? pcz : cz;
        ct_real om = tx * max_ + ty * may_ + tz * maz_;
        ct_real atx = CTI_FABS(tx), aty = CTI_FABS(ty), atz = CTI_FABS(tz);
        ct_real big = atx >= (aty > atz ? aty : atz) ? tx : (aty >= atz ? ty : tz);
        ct_real fl = om < 0 ? -1 : (om > 0 ? 1 : (big < 0 ? -1 : 1));
        /* One square root and one division normalise the normal. */
        ct_real nx = touch ? fl * tx : rx, ny = touch ? fl * ty : ry;
        ct_real nz = touch ? fl * tz : rz;
        ct_real n2 = touch ? tx * tx + ty * ty + tz * tz : r2;
        ct_real ni = 1 / CTI_SQRT(n2 > 0 ? n2 : 1);
        ct_real pen = g - dist;
        ct_real smin = s < t ? s : t, smax = s < t ? t : s;
        cti_nr_int clamped = (smin <= 0) | (smax >= 1);
        odist[k] = bad ? CT_NARROW_FAR : dist;
        open[k] = bad ? 0 : (pen > 0 ? pen : 0);
        onx[k] = bad ? 0 : nx * ni;
        ony[k] = bad ? 0 : ny * ni;
        onz[k] = bad ? 1 : nz * ni;
        osa[k] = bad ? 0 : s;
        osb[k] = bad ? 0 : t;
        if (pts) {
            opax[k] = bad ? 0 : pax + ox;
            opay[k] = bad ? 0 : pay + oy;
            opaz[k] = bad ? 0 : paz + oz;
            opbx[k] = bad ? 0 : pbx + ox;
            opby[k] = bad ? 0 : pby + oy;
            opbz[k] = bad ? 0 : pbz + oz;
        }
        ogap[k] = nonfin ? 0 : g;
        F[j] = bad ? bad
                   : ((clamped ? CTI_NR_F(OUTSIDE) : 0) | (par ? CTI_NR_F(PARALLEL) : 0));
    }
}

void cti_ee_block(ct_idx nb, const ct_real *restrict G,
                  const ct_real (*restrict C)[2 * CTI_EE_BLOCK], const ct_edge_geo *out,
                  ct_idx k0, cti_nr_int *restrict F)
{
    if (out->pax)
        cti_ee_block_loop(nb, G, C, out, k0, F, 1);
    else
        cti_ee_block_loop(nb, G, C, out, k0, F, 0);
}
