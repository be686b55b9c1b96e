/*
 * test_nonfinite.h -- a harness for the non-finite checks of the force and
 * friction kernels (docs/fuzz F15): each input array of a kernel receives
 * +inf, -inf and NaN, one entry at a time, at non-first indices, on a list
 * short enough for the serial path and on one long enough for the thread
 * team, with 1 and 2 threads. The kernel must answer CT_ERR_NONFINITE (and
 * name the pair, where it takes a ct_diag), except for a NaN or -inf in an
 * input whose header gives NaN and negative values a meaning (a penetration:
 * no contact), where it must answer CT_OK, with no force at that pair when
 * that is the meaning.
 */
#ifndef TEST_NONFINITE_H
#define TEST_NONFINITE_H

#include <stdint.h>
#include <string.h>

#include "test_util.h"

/* Above every force kernel's parallel threshold (CTI_PAR_MIN = 8192 pairs;
 * the edge-edge forces: more than one block of 128), and below it. */
#define NTF_LONG 9001
#define NTF_SHORT 37
#define NTF_MAXARR 16

/* The fills put pair i in contact unless i % 4 == 3 (ntf_contact). The bad
 * entry goes at index 1 (in contact, the first block: the first thread's),
 * n - 3 (in contact) and n - 2 (out of contact; both in the last block: the
 * second thread's share with 2 threads). */
static inline int ntf_contact(ct_idx i) { return i % 4 != 3; }

/* One kernel under test. fill() writes valid values into the input arrays
 * (the states a kernel updates among them: it is called before
 * every call); call() runs the kernel on them and returns its status (diag
 * may be filled); zero_at() says whether the kernel's results of pair k
 * are all zero (in out, or in the states of in it writes). Bit a of
 * relaxed: a NaN or -inf in input a has a meaning (CT_OK); bit a of
 * relaxed_zero: that meaning is no force at all at that pair (checked).
 * out_len: each output array's length in units of n (4 for the edge-edge
 * nodal forces). */
typedef struct ntf_case {
    const char *name;
    int nin, nout, out_len; /* inputs perturbed, outputs checked */
    const char *in_name[NTF_MAXARR];
    uint32_t relaxed, relaxed_zero;
    int has_index; /* the kernel reports the pair in its ct_diag */
    void (*fill)(ct_real **in, ct_idx n);
    int (*call)(ct_real **in, ct_real **out, ct_idx n, ct_diag *d);
    int (*zero_at)(ct_real **in, ct_real **out, ct_idx k);
} ntf_case;

/* Every output of pair k (out_len w) is zero. */
static inline int ntf_all_zero(ct_real **out, int nout, int w, ct_idx k)
{
    for (int j = 0; j < nout; j++)
        for (int s = 0; s < w; s++)
            if (out[j][(size_t)w * (size_t)k + (size_t)s] != 0)
                return 0;
    return 1;
}

/* Run the case: the valid inputs give CT_OK, then every (input, value,
 * position, size, thread count). */
static inline void ntf_run(const ntf_case *c)
{
    const ct_idx sizes[2] = {NTF_SHORT, NTF_LONG};
    const ct_real vals[3] = {(ct_real)INFINITY, -(ct_real)INFINITY, (ct_real)NAN};
    const char *vname[3] = {"+inf", "-inf", "NaN"};
    for (int si = 0; si < 2; si++) {
        const ct_idx n = sizes[si];
        /* Every array a fill or a call may use (a case may perturb fewer
         * inputs than its fill writes, and check fewer outputs). */
        ct_real *in[NTF_MAXARR], *out[NTF_MAXARR];
        for (int a = 0; a < NTF_MAXARR; a++)
            in[a] = ct_calloc((size_t)n, sizeof(ct_real));
        for (int j = 0; j < NTF_MAXARR; j++)
            out[j] = ct_calloc((size_t)n * (size_t)c->out_len, sizeof(ct_real));
        ct_diag d;
        for (int t = 1; t <= 2; t++) {
            ctt_threads(t);
            c->fill(in, n);
            cr_assert_eq(c->call(in, out, n, &d), CT_OK, "%s: valid inputs, n=%ld", c->name,
                         (long)n);
        }
        const ct_idx pos[3] = {1, n - 3, n - 2};
        for (int a = 0; a < c->nin; a++)
            for (int v = 0; v < 3; v++)
                for (int pi = 0; pi < 3; pi++)
                    for (int t = 1; t <= 2; t++) {
                        ctt_threads(t);
                        c->fill(in, n);
                        in[a][pos[pi]] = vals[v];
                        memset(&d, 0, sizeof d);
                        d.index = -99;
                        int rc = c->call(in, out, n, &d);
                        int ok = v > 0 && (c->relaxed >> a & 1);
                        cr_assert_eq(rc, ok ? CT_OK : CT_ERR_NONFINITE,
                                     "%s: %s = %s at %ld of %ld, %d thread(s): status %d",
                                     c->name, c->in_name[a], vname[v], (long)pos[pi], (long)n,
                                     t, rc);
                        if (ok && (c->relaxed_zero >> a & 1))
                            cr_assert(c->zero_at(in, out, pos[pi]),
                                      "%s: %s = %s at %ld: a force", c->name, c->in_name[a],
                                      vname[v], (long)pos[pi]);
                        else if (!ok && c->has_index)
                            cr_assert_eq(d.index, pos[pi], "%s: %s = %s: index %ld, not %ld",
                                         c->name, c->in_name[a], vname[v], (long)d.index,
                                         (long)pos[pi]);
                    }
        for (int a = 0; a < NTF_MAXARR; a++) {
            ct_free(in[a]);
            ct_free(out[a]);
        }
    }
}

/* Deterministic values in [lo, hi) for entry i of stream s (a hash). */
static inline ct_real ntf_val(ct_idx i, int s, double lo, double hi)
{
    uint64_t z = (uint64_t)i * UINT64_C(0x9e3779b97f4a7c15) + (uint64_t)s * 7919u + 1;
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    z ^= z >> 31;
    return (ct_real)(lo + (hi - lo) * (double)(z >> 11) * (1.0 / 9007199254740992.0));
}

/* A unit normal for entry i, streams s..s+2. */
static inline void ntf_normal(ct_idx i, int s, ct_real *nx, ct_real *ny, ct_real *nz)
{
    double x = ntf_val(i, s, -1, 1), y = ntf_val(i, s + 1, -1, 1), z = ntf_val(i, s + 2, 0.1, 1);
    double l = sqrt(x * x + y * y + z * z);
    *nx = (ct_real)(x / l);
    *ny = (ct_real)(y / l);
    *nz = (ct_real)(z / l);
}

/* A penetration: in contact (0.5e-3 .. 1.5e-3) or not (-1e-3 .. 0). */
static inline ct_real ntf_pen(ct_idx i)
{
    return ntf_contact(i) ? ntf_val(i, 90, 0.5e-3, 1.5e-3) : ntf_val(i, 90, -1e-3, 0);
}

#endif /* TEST_NONFINITE_H */
