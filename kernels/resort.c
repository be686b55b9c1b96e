/*
 * resort.c -- the re-sort criterion (DESIGN.md section 5): a bound on how
 * much any node-segment distance can have shrunk since a reference
 * configuration, from the displacements of the listed nodes.
 * ct_resort_needed takes one reference (the positions at the last sort);
 * ct_resort_track takes two in one pass over the nodes (the last sort's and
 * the previous cycle's) and keeps the current positions for the next one.
 */
#include "ct_internal.h"

/* The displacements of a node list against one reference: the largest
 * squared length (infinite if one is NaN) and the per-axis extremes. */
typedef struct {
    ct_real m2, lo[3], hi[3];
} cti_disp;

/* Fold displacement (dx, dy, dz) into the running largest squared length m
 * and per-axis extremes l*, h*. NaN compares false: a NaN displacement
 * makes m infinite, which forces a re-sort. Both kernels below use this
 * one sequence, so their bounds agree to the bit. */
#define CTI_DISP_FOLD(dx, dy, dz, m, lx, ly, lz, hx, hy, hz)                                  \
    do {                                                                                       \
        const ct_real d2_ = (dx) * (dx) + (dy) * (dy) + (dz) * (dz);                           \
        const ct_real v_ = d2_ != d2_ ? (ct_real)INFINITY : d2_;                               \
        m = v_ > m ? v_ : m;                                                                   \
        lx = (dx) < lx ? (dx) : lx;                                                            \
        ly = (dy) < ly ? (dy) : ly;                                                            \
        lz = (dz) < lz ? (dz) : lz;                                                            \
        hx = (dx) > hx ? (dx) : hx;                                                            \
        hy = (dy) > hy ? (dy) : hy;                                                            \
        hz = (dz) > hz ? (dz) : hz;                                                            \
    } while (0)

#define CTI_DISP_START(m, lx, ly, lz, hx, hy, hz)                                             \
    ct_real m = 0, lx = (ct_real)INFINITY, ly = (ct_real)INFINITY, lz = (ct_real)INFINITY;    \
    ct_real hx = -(ct_real)INFINITY, hy = -(ct_real)INFINITY, hz = -(ct_real)INFINITY

static void disp_store(cti_disp *d, ct_real m, ct_real lx, ct_real ly, ct_real lz, ct_real hx,
                       ct_real hy, ct_real hz)
{
    d->m2 = m;
    d->lo[0] = lx, d->lo[1] = ly, d->lo[2] = lz;
    d->hi[0] = hx, d->hi[1] = hy, d->hi[2] = hz;
}

/* A list this short runs without a thread team (an interface of a small
 * model, every cycle; see CTI_PAR_FOR). */
#define CTI_RESORT_PAR 8192

/* The loop of a kernel over its list, with the reduction clauses given;
 * BODY(k) handles node k. A list that is 0, 1, ..., n - 1 (a surface over
 * every node in order: list NULL here) is read contiguously in an
 * `omp simd` loop, which gcc vectorises (on the crumpled sheet of the cycle
 * benchmark, the pass of ct_resort_track took 2.2 ns per node so against
 * 5.4 as a scalar loop); any other list in a plain loop (vectorised, its
 * loads become gathers, which made the pass twice as slow as the scalar
 * loop). Every reduction is an exact min or max, so the results depend
 * neither on the loop nor on the team or the lanes: a NaN never enters one
 * (it becomes an infinity first or loses every comparison), and a min or
 * max of zeros may keep either sign, which no bound can see (their
 * differences and squares are +0). clang 14 cannot vectorise these
 * reductions and would warn (an error under -Werror): it gets the plain
 * loop for both. */
#define CTI_RESORT_PLAIN(n, K, clauses, BODY)                                                 \
    CTI_PAR_FOR((n) > CTI_RESORT_PAR, (schedule(static) CTI_UNPAREN clauses),                  \
                for (ct_idx i = 0; i < (n); i++) BODY(K);)
#ifdef __clang__
#define CTI_RESORT_CONTIGUOUS(n, clauses, BODY) CTI_RESORT_PLAIN(n, i, clauses, BODY)
#else
#define CTI_RESORT_CONTIGUOUS(n, clauses, BODY)                                               \
    do {                                                                                       \
        if ((n) > CTI_RESORT_PAR) {                                                            \
            CTI_PRAGMA(omp parallel for simd schedule(static) CTI_UNPAREN clauses)            \
            for (ct_idx i = 0; i < (n); i++)                                                   \
                BODY(i);                                                                       \
        } else {                                                                               \
            CTI_PRAGMA(omp simd CTI_UNPAREN clauses)                                           \
            for (ct_idx i = 0; i < (n); i++)                                                   \
                BODY(i);                                                                       \
        }                                                                                      \
    } while (0)
#endif
#define CTI_RESORT_LOOP(n, list, clauses, BODY)                                               \
    do {                                                                                       \
        if (list)                                                                              \
            CTI_RESORT_PLAIN(n, (list)[i], clauses, BODY);                                     \
        else                                                                                   \
            CTI_RESORT_CONTIGUOUS(n, clauses, BODY);                                           \
    } while (0)

/* NULL when list is 0, 1, ..., n - 1, else list. */
static const ct_idx *list_or_null(ct_idx n, const ct_idx *restrict list)
{
    /* Its ends decide most lists without the pass (and its team). */
    if (n > 0 && (list[0] != 0 || list[n - 1] != n - 1))
        return list;
    int other = 0;
    CTI_PAR_FOR(n > CTI_RESORT_PAR, (schedule(static) reduction(| : other)),
    for (ct_idx i = 0; i < n; i++)
        other |= list[i] != i;);
    return other ? list : NULL;
}

/* The displacements of the nodes of list (NULL: 0 .. n - 1) since (x0, y0,
 * z0). */
static void resort_list(ct_idx n, const ct_idx *restrict list, const ct_real *restrict x0,
                        const ct_real *restrict y0, const ct_real *restrict z0,
                        const ct_real *restrict x, const ct_real *restrict y,
                        const ct_real *restrict z, cti_disp *out)
{
    CTI_DISP_START(m, lx, ly, lz, hx, hy, hz);
#define CTI_RESORT_NODE(K)                                                                     \
    {                                                                                          \
        const ct_idx k = (K);                                                                  \
        const ct_real dx = x[k] - x0[k], dy = y[k] - y0[k], dz = z[k] - z0[k];                 \
        CTI_DISP_FOLD(dx, dy, dz, m, lx, ly, lz, hx, hy, hz);                                  \
    }
    CTI_RESORT_LOOP(n, list, (reduction(max : m, hx, hy, hz) reduction(min : lx, ly, lz)),
                    CTI_RESORT_NODE);
#undef CTI_RESORT_NODE
    disp_store(out, m, lx, ly, lz, hx, hy, hz);
}

/* The displacements of the nodes of list (NULL: 0 .. n - 1) since (x0, y0,
 * z0) into *a and since (xp, yp, zp) into *b, the largest coordinate
 * magnitude into *amax (infinite if one is NaN), and, when keep, the
 * positions copied to (xk, yk, zk). xk never aliases x or xp: a node
 * listed twice is read the same way by both of its iterations. */
static inline __attribute__((always_inline)) void
track_list(ct_idx n, const ct_idx *restrict list, const ct_real *restrict x0,
           const ct_real *restrict y0, const ct_real *restrict z0, const ct_real *restrict xp,
           const ct_real *restrict yp, const ct_real *restrict zp, const ct_real *restrict x,
           const ct_real *restrict y, const ct_real *restrict z, const int keep,
           ct_real *restrict xk, ct_real *restrict yk, ct_real *restrict zk, cti_disp *a,
           cti_disp *b, double *amax)
{
    CTI_DISP_START(m, lx, ly, lz, hx, hy, hz);
    CTI_DISP_START(pm, plx, ply, plz, phx, phy, phz);
    double L = 0;
    /* The magnitude by selects, not fmax: fmax drops a NaN, where the
     * magnitude must be infinite (and gcc calls libm for it). */
#define CTI_TRACK_NODE(K)                                                                      \
    {                                                                                          \
        const ct_idx k = (K);                                                                  \
        const ct_real cx = x[k], cy = y[k], cz = z[k];                                         \
        const ct_real dx = cx - x0[k], dy = cy - y0[k], dz = cz - z0[k];                       \
        CTI_DISP_FOLD(dx, dy, dz, m, lx, ly, lz, hx, hy, hz);                                  \
        const ct_real ex = cx - xp[k], ey = cy - yp[k], ez = cz - zp[k];                       \
        CTI_DISP_FOLD(ex, ey, ez, pm, plx, ply, plz, phx, phy, phz);                           \
        const double ax = fabs((double)cx), ay = fabs((double)cy), az = fabs((double)cz);      \
        double am = ax > ay ? ax : ay;                                                         \
        am = az > am ? az : am;                                                                \
        am = ((ax != ax) | (ay != ay) | (az != az)) ? INFINITY : am;                           \
        L = am > L ? am : L;                                                                   \
        if (keep) {                                                                            \
            xk[k] = cx;                                                                        \
            yk[k] = cy;                                                                        \
            zk[k] = cz;                                                                        \
        }                                                                                      \
    }
    CTI_RESORT_LOOP(n, list,
                    (reduction(max : m, hx, hy, hz, pm, phx, phy, phz, L)
                         reduction(min : lx, ly, lz, plx, ply, plz)),
                    CTI_TRACK_NODE);
#undef CTI_TRACK_NODE
    disp_store(a, m, lx, ly, lz, hx, hy, hz);
    disp_store(b, pm, plx, ply, plz, phx, phy, phz);
    *amax = L;
}

/* track_list with and without the copy (the loops specialised on it). */
static void track_lists(ct_idx n, const ct_idx *list, const ct_real *x0, const ct_real *y0,
                        const ct_real *z0, const ct_real *xp, const ct_real *yp,
                        const ct_real *zp, const ct_real *x, const ct_real *y, const ct_real *z,
                        ct_real *xk, ct_real *yk, ct_real *zk, cti_disp *a, cti_disp *b,
                        double *amax)
{
    if (xk)
        track_list(n, list, x0, y0, z0, xp, yp, zp, x, y, z, 1, xk, yk, zk, a, b, amax);
    else
        track_list(n, list, x0, y0, z0, xp, yp, zp, x, y, z, 0, NULL, NULL, NULL, a, b, amax);
}

/* The bound from both sides' displacements: the smaller of the sum of the
 * two largest and the relative bound per axis (ct_search.h). */
static ct_real resort_bound(ct_idx nsec, ct_idx nmain, const cti_disp *s, const cti_disp *m)
{
    ct_real b = CTI_SQRT(s->m2) + CTI_SQRT(m->m2);
    if (nsec > 0 && nmain > 0 && b <= (ct_real)CTI_HUGE) {
        /* Per axis, the secondary-minus-main displacement lies in
         * [min_s - max_m, max_s - min_m] (a point of a segment moves by a
         * convex combination of its corners' displacements). */
        ct_real r2 = 0;
        for (int a = 0; a < 3; a++) {
            ct_real u = s->hi[a] - m->lo[a], v = m->hi[a] - s->lo[a];
            ct_real r = u > v ? u : v;
            r2 += r * r;
        }
        ct_real rel = CTI_SQRT(r2);
        b = rel < b ? rel : b;
    }
    return b;
}

/* One list for both sides (self contact): its nodes are read once. */
static int one_list(ct_idx nsec, const ct_idx *sec, ct_idx nmain, const ct_idx *main_nodes)
{
    return main_nodes == sec && nmain == nsec;
}

int ct_resort_needed(ct_idx nsec, const ct_idx *sec, ct_idx nmain, const ct_idx *main_nodes,
                     const ct_real *x0, const ct_real *y0, const ct_real *z0, const ct_real *x,
                     const ct_real *y, const ct_real *z, ct_real margin, ct_real *bound)
{
    cti_disp s, m;
    resort_list(nsec, list_or_null(nsec, sec), x0, y0, z0, x, y, z, &s);
    if (one_list(nsec, sec, nmain, main_nodes))
        m = s;
    else
        resort_list(nmain, list_or_null(nmain, main_nodes), x0, y0, z0, x, y, z, &m);
    const ct_real b = resort_bound(nsec, nmain, &s, &m);
    if (bound)
        *bound = b;
    return !(b <= margin);
}

int ct_resort_track(ct_idx nsec, const ct_idx *sec, ct_idx nmain, const ct_idx *main_nodes,
                    const ct_real *x0, const ct_real *y0, const ct_real *z0, const ct_real *xp,
                    const ct_real *yp, const ct_real *zp, const ct_real *x, const ct_real *y,
                    const ct_real *z, ct_real *xk, ct_real *yk, ct_real *zk, ct_real margin,
                    ct_real *bound, ct_real *step, double *amax)
{
    cti_disp s0, sp, m0, mp;
    double Ls, Lm;
    track_lists(nsec, list_or_null(nsec, sec), x0, y0, z0, xp, yp, zp, x, y, z, xk, yk, zk, &s0,
                &sp, &Ls);
    if (one_list(nsec, sec, nmain, main_nodes)) {
        m0 = s0;
        mp = sp;
        Lm = Ls;
    } else {
        track_lists(nmain, list_or_null(nmain, main_nodes), x0, y0, z0, xp, yp, zp, x, y, z, xk,
                    yk, zk, &m0, &mp, &Lm);
    }
    const ct_real b = resort_bound(nsec, nmain, &s0, &m0);
    if (bound)
        *bound = b;
    if (step)
        *step = resort_bound(nsec, nmain, &sp, &mp);
    if (amax)
        *amax = Lm > Ls ? Lm : Ls; /* neither is NaN */
    return !(b <= margin);
}
