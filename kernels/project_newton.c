/*
 * project_newton.c -- node-quadrangle projection by Newton on the bilinear
 * (s, t) (DESIGN.md section 6; ct_quad_method in ct_narrow.h): a linear
 * start, two steps in one vector loop for every pair, two more for the whole
 * block when enough of it has not converged, further vector rounds for the
 * pairs still not converged (except those far off the quadrangle, whose
 * answer is the boundary's), and the boundary rule of narrow_quad.h.
 */
#include "narrow_quad.h"

/* ---- Newton ---------------------------------------------------------------- */

/* One Newton step on f(s,t) = |x(s,t) - p|^2 / 2: the full Hessian when it
 * is safely positive definite, Gauss-Newton otherwise. Iterates are kept in
 * [-3, 3]^2 so a wandering iteration stays finite. *step = |ds| + |dt|.
 * With hold != 0 the step leaves *s, *t and *step as they were, bit for
 * bit (ds and dt become -0, which added to any value gives that value, and
 * a value the last step clamped is inside the clamp): a lane's step held
 * so keeps fewer values live than a step taken and then undone by
 * selects, which in single precision cost a loop with it 12 %. */
CTI_NR_INLINE void cti_newton_step_held(CTI_QPARAMS, ct_real *s, ct_real *t, ct_real *step,
                                        cti_nr_int hold)
{
    CTI_QUNUSED;
    ct_real S = *s, T = *t;
    cti_v3 xs = v3_add(a1, v3_scale(T, a3));
    cti_v3 xt = v3_add(a2, v3_scale(S, a3));
    cti_v3 r = v3_sub(cti_quad_x(x0, a1, a2, a3, S, T), P);
    ct_real g1 = v3_dot(r, xs), g2 = v3_dot(r, xt);
    ct_real h11 = v3_dot(xs, xs), h22 = v3_dot(xt, xt), h12 = v3_dot(xs, xt);
    ct_real hf = h12 + v3_dot(r, a3);
    ct_real detf = h11 * h22 - hf * hf;
    ct_real detg = h11 * h22 - h12 * h12;
    cti_nr_int full = detf > (ct_real)1e-6 * h11 * h22;
    ct_real m12 = full ? hf : h12;
    ct_real det = full ? detf : detg;
    ct_real inv = 1 / (det > 0 ? det : 1);
    ct_real ds = -(h22 * g1 - m12 * g2) * inv;
    ct_real dt = -(h11 * g2 - m12 * g1) * inv;
    const ct_real st = CTI_FABS(ds) + CTI_FABS(dt);
    ds = hold ? (ct_real)-0.0 : ds;
    dt = hold ? (ct_real)-0.0 : dt;
    S += ds;
    T += dt;
    S = S < -3 ? -3 : (S > 3 ? 3 : S);
    T = T < -3 ? -3 : (T > 3 ? 3 : T);
    *s = S;
    *t = T;
    *step = hold ? *step : st;
}

/* cti_newton_step_held, never held. */
CTI_NR_INLINE void cti_newton_step(CTI_QPARAMS, ct_real *s, ct_real *t, ct_real *step)
{
    cti_newton_step_held(CTI_QARGS, s, t, step, 0);
}

/* Start of Newton: the least-squares (s, t) of the quadrangle's affine part
 * x0 + s a1 + t a2 (exact for a parallelogram), kept in [-3, 3]^2. */
static inline void cti_newton_start(CTI_QPARAMS, ct_real *s, ct_real *t)
{
    CTI_QUNUSED;
    cti_v3 r = v3_sub(P, x0);
    ct_real h11 = v3_dot(a1, a1), h22 = v3_dot(a2, a2), h12 = v3_dot(a1, a2);
    ct_real g1 = v3_dot(r, a1), g2 = v3_dot(r, a2);
    cti_v3 c = v3_cross(a1, a2);
    ct_real det = v3_dot(c, c);
    ct_real inv = 1 / (det > 0 ? det : 1);
    ct_real S = (h22 * g1 - h12 * g2) * inv, T = (h11 * g2 - h12 * g1) * inv;
    *s = S < -3 ? -3 : (S > 3 ? 3 : S);
    *t = T < -3 ? -3 : (T > 3 ? 3 : T);
}

/* Bilinear projection by Newton: fixed vector loops over the block
 * (cti_nr_block_newton) write the outputs; pairs not converged then (last
 * step above the tolerance, NaN included) continue to the cap in further
 * vector rounds over those pairs alone (newton_redo). Which steps a pair
 * takes depends on the pair only, so the results do not depend on lanes,
 * blocks or threads. */

/* The two SIMD loops of the redo stay functions of their own: inlined into
 * newton_redo, whose compact scratch is a local aggregate, gcc 12 does not
 * vectorise them. */
#if defined(__GNUC__)
#define CTI_NR_NOINLINE __attribute__((noinline))
#else
#define CTI_NR_NOINLINE
#endif

/* The coordinates and gaps of block pairs idx[0..m-1] into c (the layout
 * of the block scratch, compacted). */
static void newton_pick(const cti_nr_blk *b, const ct_idx *idx, ct_idx m, cti_nr_blk *c)
{
    for (ct_idx q = 0; q < m; q++) {
        const ct_idx j = idx[q];
        for (int e = 0; e < 2; e++) {
            c->pxy[2 * q + e] = b->pxy[2 * j + e];
            c->xy1[2 * q + e] = b->xy1[2 * j + e];
            c->xy2[2 * q + e] = b->xy2[2 * j + e];
            c->xy3[2 * q + e] = b->xy3[2 * j + e];
            c->xy4[2 * q + e] = b->xy4[2 * j + e];
            c->z01[2 * q + e] = b->z01[2 * j + e];
            c->z23[2 * q + e] = b->z23[2 * j + e];
        }
        c->z4[q] = b->z4[j];
        c->g[q] = b->g[j];
    }
}

/* Whether a and b have the same bits (not ==, which takes 0 for -0 and
 * no NaN for itself). */
static inline cti_nr_int cti_same_bits(ct_real a, ct_real b)
{
    union {
        ct_real r;
        cti_nr_int i;
    } ua = {a}, ub = {b};
    _Static_assert(sizeof(ct_real) == sizeof(cti_nr_int), "cti_nr_int is ct_real's width");
    return ua.i == ub.i;
}

/* A Newton step of a lane that is not done; a lane that is done keeps s,
 * t and its last step size st. done becomes 1 when the step converges, or
 * when the step left the bits of s and t as they were: a step is a function
 * of those bits, so every later step would be that same step, and the cap
 * would end there too, with this step's size (whether the lane was done
 * already does not matter: done stays 1). done is a real rather than a
 * mask: gcc 12 does not vectorise a select between masks. */
CTI_NR_INLINE void cti_newton_step_unless_done(CTI_QPARAMS, ct_real *s, ct_real *t,
                                               ct_real *st, ct_real *done)
{
    ct_real s2 = *s, t2 = *t, st2;
    cti_newton_step(CTI_QARGS, &s2, &t2, &st2);
    ct_real same = cti_same_bits(s2, *s) & cti_same_bits(t2, *t) ? 1 : 0;
    cti_nr_int keep = *done != 0;
    *s = keep ? *s : s2;
    *t = keep ? *t : t2;
    *st = keep ? *st : st2;
    *done = *st <= CTI_NR_NEWTON_TOL ? 1 : *done;
    *done = same != 0 ? 1 : *done;
}

/* A round of further steps of the m compacted pairs of b (see
 * newton_redo): the first `left` of NSTEP steps (a constant: both compilers
 * vectorise only a constant inner count); s, t and the last step size st
 * updated in place, fin set to 1 for the pairs done (converged, or at a
 * fixed point), not for those that only ran out of steps. A lane whose step
 * converged keeps its values from then on; so does every lane past `left`. */
#define CTI_NEWTON_ROUND(NAME, NSTEP)                                                      \
    CTI_NR_NOINLINE static void NAME(const cti_nr_args *a, ct_idx m, const cti_nr_blk *b,  \
                                     int left, ct_real *restrict sv, ct_real *restrict tv, \
                                     ct_real *restrict stv, ct_real *restrict fin)         \
    {                                                                                     \
        CTI_NR_INPTRS(a, 0);                                                              \
        CTI_NR_SIMD                                                                       \
        for (ct_idx q = 0; q < m; q++) {                                                  \
            CTI_QUAD_LOAD(q);                                                             \
            (void)g, (void)nonfin;                                                        \
            ct_real s = sv[q], t = tv[q], st = stv[q];                                    \
            ct_real done = 0;                                                             \
            _Pragma("GCC unroll 8")                                                       \
            for (int i = 0; i < (NSTEP); i++) {                                           \
                const ct_real held = i >= left ? 1 : done;                                \
                ct_real d = held;                                                         \
                cti_newton_step_unless_done(CTI_QARGS, &s, &t, &st, &d);                  \
                done = held != 0 ? done : d;                                              \
            }                                                                             \
            sv[q] = s;                                                                    \
            tv[q] = t;                                                                    \
            stv[q] = st;                                                                  \
            fin[q] = done;                                                                \
        }                                                                                 \
    }
/* done: 1 once a step converged or the steps ran out
 * (cti_newton_step_unless_done). The first round is one step when the block
 * took CTI_NR_NEWTON_VEC_IT steps already (most pairs of a crumpled sheet
 * converge at the fifth), the others CTI_NR_NEWTON_VEC_IT. */
CTI_NEWTON_ROUND(newton_round1, 1)
CTI_NEWTON_ROUND(newton_round, CTI_NR_NEWTON_VEC_IT)

/* Whether (s, t) is farther than CTI_NR_NEWTON_FAR outside the square. */
static inline int cti_newton_far(ct_real s, ct_real t)
{
    const ct_real f2 = (ct_real)(CTI_NR_NEWTON_FAR * CTI_NR_NEWTON_FAR);
    return (s * s > f2) | (t * t > f2);
}

/* off[q] = 1 when no point inside the quadrangle of compacted pair q of b
 * is nearer its node than the boundary's nearest (cti_quad_hull_q, up to a
 * relative CTI_NR_NEWTON_OFF_TOL of the squared distance), else 0. */
CTI_NR_NOINLINE static void newton_off(const cti_nr_args *a, ct_idx m, const cti_nr_blk *b,
                                       ct_real *restrict off)
{
    CTI_NR_INPTRS(a, 0);
    CTI_NR_SIMD
    for (ct_idx q = 0; q < m; q++) {
        CTI_QUAD_LOAD(q);
        (void)g, (void)nonfin;
        ct_real bs, bt, bq;
        cti_quad_boundary(CTI_QARGS, &bs, &bt, &bq);
        ct_real hq = cti_quad_hull_q(CTI_QARGS);
        off[q] = hq >= bq * (1 - CTI_NR_NEWTON_OFF_TOL) ? 1 : 0;
    }
}

/* The end of Newton for the m compacted pairs of b whose iterations ended
 * at (s, t) with last step st: into a's outputs, offset 0 (the caller's
 * compact arrays), and b->flag. */
CTI_NR_NOINLINE static void newton_finish(const cti_nr_args *a, ct_idx m, cti_nr_blk *b,
                          const ct_real *restrict sv, const ct_real *restrict tv,
                          const ct_real *restrict stv)
{
    CTI_NR_OUTPTRS(a, 0);
    CTI_NR_INPTRS(a, 0);
    int two = a->two_sided;
    CTI_NR_SIMD
    for (ct_idx q = 0; q < m; q++) {
        CTI_QUAD_LOAD(q);
        ct_real s = sv[q], t = tv[q];
        cti_nr_int conv = stv[q] <= CTI_NR_NEWTON_TOL;
        /* Not converged inside the square: keep the best of the iterate and
         * the boundary, and say so. Not converged outside: the boundary.
         * (|s| <= 1 as s^2 <= 1, the same answer, NaN included: written
         * like quad_end's test, gcc 12 merges the two into a select of
         * masks it cannot vectorise.) */
        cti_nr_int fb = (!conv) & (s * s <= 1) & (t * t <= 1);
        CTI_QUAD_STORE(q, s, t, conv | fb, fb ? CTI_NR_F(FALLBACK) : 0);
    }
}

/* Of the nl pairs still iterating (block positions live[], their iterates
 * at s[pos[q]], t[pos[q]]), those far outside the square whose answer is
 * the boundary's (newton_off) end: they leave live[] and pos[], which keep
 * their order; returns how many are left. c is scratch. */
static ct_idx newton_end_off(const cti_nr_args *a, const cti_nr_blk *b, cti_nr_blk *c,
                             ct_idx nl, ct_idx *live, ct_idx *pos, const ct_real *s,
                             const ct_real *t)
{
    ct_idx far[CTI_NR_BLOCK], fl[CTI_NR_BLOCK], nf = 0;
    for (ct_idx q = 0; q < nl; q++) {
        far[nf] = q;
        nf += cti_newton_far(s[pos[q]], t[pos[q]]);
    }
    if (nf == 0)
        return nl;
    for (ct_idx f = 0; f < nf; f++)
        fl[f] = live[far[f]];
    ct_real off[CTI_NR_BLOCK];
    newton_pick(b, fl, nf, c);
    newton_off(a, nf, c, off);
    ct_idx m = 0, f = 0;
    for (ct_idx q = 0; q < nl; q++) {
        const int is_far = f < nf && far[f] == q;
        const int end = is_far && off[f] != 0;
        f += is_far;
        live[m] = live[q];
        pos[m] = pos[q];
        m += !end;
    }
    return m;
}

/*
 * The pairs of block k0 that the fixed loops left unconverged (redo[j];
 * their iterates in sv, tv, their last step sizes in stv, after `steps`
 * steps) take further steps in SIMD lanes: rounds over those still
 * iterating, the first to step CTI_NR_NEWTON_VEC_IT when the block stopped
 * before it, then one step, then CTI_NR_NEWTON_VEC_IT at a
 * time, up to CTI_NR_NEWTON_MAX_IT steps in all; then their outputs are
 * computed. A lane keeps its values from the step that converged, or from
 * the step that returned its (s, t) unchanged, so each pair gets the values
 * of a scalar loop that stops at convergence or at the cap (and the same
 * bytes: a pair's arithmetic does not depend on its lane). Each round and
 * the end work on the pairs' inputs copied into a compact scratch, as the
 * block's own copy does (vector gathers cost more).
 *
 * On a crumpled sheet about half of the candidates come here: nodes off
 * the quadrangle, where Newton on the bilinear extension converges slowly
 * (to a point outside the square) or not at all, and the answer is the
 * boundary's. So at step CTI_NR_NEWTON_VEC_IT, which every pair reaches
 * whichever path its block took, a pair whose iterate is more than
 * CTI_NR_NEWTON_FAR outside the square ends when no point inside the
 * quadrangle can be nearer than the boundary (newton_off): continued, it
 * would end at the boundary too, or at an interior point no nearer, up to
 * the relative CTI_NR_NEWTON_OFF_TOL of the squared distance, which a tie
 * within rounding needs. Otherwise only the flags can differ: FALLBACK or
 * OUTSIDE, where the iterations would have stopped inside the square
 * unconverged, or within the footprint tolerance of its edge. On the
 * crumpled sheet this ends 87 % of the pairs that come here and the kernel
 * runs 1.7 times faster, every output the same bytes.
 */
static void newton_redo(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b,
                        const cti_nr_int *redo, const ct_real *sv, const ct_real *tv,
                        const ct_real *stv, int steps)
{
    ct_idx rq[CTI_NR_BLOCK], live[CTI_NR_BLOCK], pos[CTI_NR_BLOCK];
    ct_real s[CTI_NR_BLOCK], t[CTI_NR_BLOCK], st[CTI_NR_BLOCK];
    ct_idx nr = 0;
    for (ct_idx j = 0; j < n; j++) {
        rq[nr] = j;
        nr += redo[j] != 0;
    }
    if (nr == 0)
        return;
    cti_nr_blk c;
    /* Rounds: live[] the block positions of the pairs still iterating, pos[]
     * their places in rq (where s, t, st are kept). */
    for (ct_idx q = 0; q < nr; q++) {
        live[q] = rq[q];
        pos[q] = q;
        s[q] = sv[rq[q]];
        t[q] = tv[rq[q]];
        st[q] = stv[rq[q]];
    }
    ct_idx nl = nr;
    ct_real ls[CTI_NR_BLOCK], lt[CTI_NR_BLOCK], lst[CTI_NR_BLOCK], lfin[CTI_NR_BLOCK];
    /* Rounds of steps; at step CTI_NR_NEWTON_VEC_IT, the end of the pairs
     * far off the quadrangle (newton_end_off). */
    int it0 = steps, checked = 0;
    while (nl > 0 && it0 < CTI_NR_NEWTON_MAX_IT) {
        if (!checked && it0 >= CTI_NR_NEWTON_VEC_IT) {
            checked = 1;
            nl = newton_end_off(a, b, &c, nl, live, pos, s, t);
            if (nl == 0)
                break;
        }
        const int n_it = it0 < CTI_NR_NEWTON_VEC_IT   ? CTI_NR_NEWTON_VEC_IT - it0
                         : it0 == CTI_NR_NEWTON_VEC_IT ? 1
                                                       : CTI_NR_NEWTON_VEC_IT;
        newton_pick(b, live, nl, &c);
        for (ct_idx q = 0; q < nl; q++) {
            ls[q] = s[pos[q]];
            lt[q] = t[pos[q]];
            lst[q] = st[pos[q]];
        }
        const int left = CTI_MIN(n_it, CTI_NR_NEWTON_MAX_IT - it0);
        (n_it == 1 ? newton_round1 : newton_round)(a, nl, &c, left, ls, lt, lst, lfin);
        it0 += n_it;
        ct_idx m = 0;
        for (ct_idx q = 0; q < nl; q++) {
            const ct_idx p = pos[q];
            s[p] = ls[q];
            t[p] = lt[q];
            st[p] = lst[q];
            live[m] = live[q];
            pos[m] = p;
            m += lfin[q] == 0;
        }
        nl = m;
    }
    /* The outputs, into compact arrays, then to the pairs' places. */
    ct_real o[13][CTI_NR_BLOCK];
    uint8_t of[CTI_NR_BLOCK];
    const ct_contact_geo cg = {o[0], o[1], o[2], o[3], o[4],  o[5],  o[6],
                               o[7], o[8], o[9], o[10], o[11], o[12], of};
    cti_nr_args ca = *a;
    ca.out = &cg;
    newton_pick(b, rq, nr, &c);
    newton_finish(&ca, nr, &c, s, t, st);
    const ct_contact_geo *out = a->out;
    ct_real *const dst[13] = {out->dist, out->pen, out->nx, out->ny, out->nz,
                              out->cx,   out->cy,  out->cz, out->h1, out->h2,
                              out->h3,   out->h4,  out->gap};
    for (int f = 0; f < 13; f++)
        for (ct_idx q = 0; q < nr; q++)
            dst[f][k0 + rq[q]] = o[f][q];
    for (ct_idx q = 0; q < nr; q++)
        b->flag[rq[q]] = c.flag[q];
}

/* Left to itself, clang 14 interleaves one of the first loop's two forms 4
 * vectors deep in single (64 pairs at a time; see CTI_NR_SIMD), and the
 * plates ran 0.74-0.86x of the one-vector loop at 10^6 pairs. */
#if defined(__clang__)
#define CTI_NR_ONE_VECTOR _Pragma("clang loop interleave_count(1)")
#else
#define CTI_NR_ONE_VECTOR
#endif

/* The first fixed loop of cti_nr_block_newton: the start and nstep steps
 * (1 or 2, a constant) of block pairs [k0, k0 + n) into sv, tv and stv, and
 * their outputs when store (a constant: the forms are separate loops); the
 * first step for every pair, the second for those the first did not
 * converge (as cti_newton_step_unless_done). Returns the number of pairs not
 * converged; *nun1, those the first step did not converge. */
CTI_NR_INLINE ct_idx newton_block_first(const cti_nr_args *a, ct_idx k0, ct_idx n,
                                        cti_nr_blk *b, ct_real *restrict sv,
                                        ct_real *restrict tv, ct_real *restrict stv,
                                        ct_idx *nun1, const int store, const int nstep)
{
    CTI_NR_OUTPTRS(a, k0);
    CTI_NR_INPTRS(a, k0);
    int two = a->two_sided;
    ct_idx nun = 0, n1 = 0;
    _Pragma("omp simd reduction(+ : nun, n1)") CTI_NR_ONE_VECTOR
    for (ct_idx j = 0; j < n; j++) {
        CTI_QUAD_LOAD(j);
        ct_real s, t, st = 0;
        cti_newton_start(CTI_QARGS, &s, &t);
        cti_newton_step(CTI_QARGS, &s, &t, &st);
        n1 += !(st <= CTI_NR_NEWTON_TOL);
        /* The second step as cti_newton_step_unless_done, without its
         * fixed-point test, which matters only to the steps after this one
         * (clang 14 does not vectorise this loop with it). */
        if (nstep > 1)
            cti_newton_step_held(CTI_QARGS, &s, &t, &st, st <= CTI_NR_NEWTON_TOL);
        sv[j] = s;
        tv[j] = t;
        stv[j] = st;
        nun += !(st <= CTI_NR_NEWTON_TOL);
        if (store)
            CTI_QUAD_STORE(j, s, t, 1, 0);
    }
    *nun1 = n1;
    return nun;
}

/* The forms of the two fixed loops, each a function of its own: with the
 * forms' calls side by side in one function, clang 14 merged them into one
 * call with its constant arguments selected at run time, and then could
 * not vectorise the loop (it writes the outputs only when `store`). The
 * names say the steps of the first loop, s when it stores the outputs. */
#define CTI_NEWTON_FIRST(NAME, STORE, NSTEP)                                                  \
    CTI_NR_NOINLINE static ct_idx NAME(const cti_nr_args *a, ct_idx k0, ct_idx n,             \
                                       cti_nr_blk *b, ct_real *restrict sv,                   \
                                       ct_real *restrict tv, ct_real *restrict stv,           \
                                       ct_idx *nun1)                                          \
    {                                                                                         \
        return newton_block_first(a, k0, n, b, sv, tv, stv, nun1, STORE, NSTEP);              \
    }
CTI_NEWTON_FIRST(newton_first_1, 0, 1)
CTI_NEWTON_FIRST(newton_first_1s, 1, 1)
CTI_NEWTON_FIRST(newton_first_2, 0, 2)
CTI_NEWTON_FIRST(newton_first_2s, 1, 2)
/* The second fixed loop: steps FROM + 1 to CTI_NR_NEWTON_VEC_IT of block
 * pairs [k0, k0 + n) (FROM: the first loop's steps), for every pair of the
 * block; a pair that had converged keeps its values, as in the rounds. The
 * outputs of every pair are written again (a converged pair's are the same
 * bytes), fin[j] says whether pair j is done. A constant FROM in each form
 * (the inner loop is vectorised only with a constant count). */
#define CTI_NEWTON_MORE(NAME, FROM)                                                           \
    CTI_NR_NOINLINE static void NAME(const cti_nr_args *a, ct_idx k0, ct_idx n,               \
                                     cti_nr_blk *b, ct_real *restrict sv,                     \
                                     ct_real *restrict tv, ct_real *restrict stv,             \
                                     ct_real *restrict fin)                                   \
    {                                                                                         \
        CTI_NR_OUTPTRS(a, k0);                                                                \
        CTI_NR_INPTRS(a, k0);                                                                 \
        int two = a->two_sided;                                                               \
        CTI_NR_SIMD                                                                           \
        for (ct_idx j = 0; j < n; j++) {                                                      \
            CTI_QUAD_LOAD(j);                                                                 \
            ct_real s = sv[j], t = tv[j], st = stv[j];                                        \
            ct_real done = st <= CTI_NR_NEWTON_TOL ? 1 : 0;                                   \
            _Pragma("GCC unroll 8")                                                           \
            for (int i = (FROM); i < CTI_NR_NEWTON_VEC_IT; i++) {                             \
                cti_newton_step_unless_done(CTI_QARGS, &s, &t, &st, &done);                   \
            }                                                                                 \
            sv[j] = s;                                                                        \
            tv[j] = t;                                                                        \
            stv[j] = st;                                                                      \
            fin[j] = done;                                                                    \
            CTI_QUAD_STORE(j, s, t, 1, 0);                                                    \
        }                                                                                     \
    }
CTI_NEWTON_MORE(newton_more_from_1, 1)
CTI_NEWTON_MORE(newton_more_from_2, 2)

/*
 * Newton for block pairs [k0, k0 + n): the start and one or two steps for
 * every pair (the second for the pairs the first did not converge); when
 * more than 1 / CTI_NR_NEWTON_MORE_DEN of the block has not converged then,
 * the steps up to CTI_NR_NEWTON_VEC_IT for the whole block
 * (newton_block_more); the pairs still not converged then go on in the
 * compacted rounds of newton_redo. Every pair takes steps until one
 * converges (the first always), so its result does not depend on which of
 * these paths it took, nor on the block's other pairs. A flat
 * parallelogram's start is exact and its first step converges; smooth
 * meshes converge in two steps and take the first loop alone; warped or
 * crumpled ones take both loops, as compacting half a block costs more
 * than two more steps for all of it.
 *
 * The block before gives two guesses (b->newton_more), which change the
 * time only, never a byte:
 *  - bit 1: whether its first step left more than 1 / CTI_NR_NEWTON_MORE_DEN
 *    of it unconverged; if so the first loop takes two steps, else one (a
 *    second step in the same loop costs less than a second loop, and on a
 *    flat parallelogram it is a step for nothing: 1.2 times the time);
 *  - bit 0: whether it ran the second loop: the first loop writes the
 *    outputs when the second is not expected, the second rewrites them for
 *    every pair when it runs, and a plain loop writes them when the guess
 *    was wrong the other way.
 */
void cti_nr_block_newton(const cti_nr_args *a, ct_idx k0, ct_idx n, cti_nr_blk *b)
{
    CTI_NR_OUTPTRS(a, k0);
    CTI_NR_INPTRS(a, k0);
    int two = a->two_sided;
    ct_real sv[CTI_NR_BLOCK], tv[CTI_NR_BLOCK], stv[CTI_NR_BLOCK], fin[CTI_NR_BLOCK];
    cti_nr_int redo[CTI_NR_BLOCK];
    const int guess = b->newton_more & 1, nf = b->newton_more & 2 ? 2 : 1;
    ct_idx nun1;
    const ct_idx nun = (nf == 2 ? (guess ? newton_first_2 : newton_first_2s)
                                : (guess ? newton_first_1 : newton_first_1s))(
        a, k0, n, b, sv, tv, stv, &nun1);
    const int more = nun * CTI_NR_NEWTON_MORE_DEN > n;
    int steps = nf;
    if (more) {
        (nf == 2 ? newton_more_from_2 : newton_more_from_1)(a, k0, n, b, sv, tv, stv, fin);
        steps = CTI_NR_NEWTON_VEC_IT;
        for (ct_idx j = 0; j < n; j++)
            redo[j] = fin[j] == 0;
    } else {
        if (guess) {
            CTI_NR_SIMD
            for (ct_idx j = 0; j < n; j++) {
                CTI_QUAD_LOAD(j);
                CTI_QUAD_STORE(j, sv[j], tv[j], 1, 0);
            }
        }
        for (ct_idx j = 0; j < n; j++)
            redo[j] = !(stv[j] <= CTI_NR_NEWTON_TOL);
    }
    b->newton_more = more | (nun1 * CTI_NR_NEWTON_MORE_DEN > n ? 2 : 0);
    newton_redo(a, k0, n, b, redo, sv, tv, stv, steps);
    cti_nr_flags_out(b->flag, a->out->flag + k0, n);
}
