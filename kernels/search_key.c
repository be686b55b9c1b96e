/*
 * search_key.c -- a copy of a search input's topology (the secondaries and
 * the four corner arrays, with the counts), kept by the parts of a search
 * workspace whose state belongs to one topology: the kept renumbering
 * (search_renumber.c) and the topological search's history
 * (search_topo.c).
 *
 * Why a copy and not the pointers: a caller may rewrite its arrays in place
 * (a remeshed or eroded interface), and state built for the old contents
 * would then be silently stale. A full comparison is one streaming pass
 * over 4 numbers per segment and 1 per secondary, about 2 ns per secondary
 * on two plates, small against any search.
 *
 * The loops carry no simd pragma: clang turns the copies into memcpy calls
 * and does not vectorise the comparisons, and -Werror then rejects a pragma
 * it could not honour.
 */
#include "ct_internal.h"

void cti_topo_key_free(cti_topo_key *k)
{
    ct_free(k->sec);
    ct_free(k->n1);
    ct_free(k->n2);
    ct_free(k->n3);
    ct_free(k->n4);
    memset(k, 0, sizeof *k);
}

size_t cti_topo_key_memory(const cti_topo_key *k)
{
    return (k->cap_sec + 4 * k->cap_seg) * sizeof(ct_idx);
}

int cti_topo_key_same(const cti_topo_key *k, const ct_search_input *in)
{
    if (!k->valid || in->nnode != k->nnode || in->nsec != k->nsec || in->nseg != k->nseg)
        return 0;
    const ct_idx *restrict a1 = in->n1, *restrict a2 = in->n2, *restrict a3 = in->n3,
                           *restrict a4 = in->n4, *restrict as = in->sec;
    const ct_idx *restrict b1 = k->n1, *restrict b2 = k->n2, *restrict b3 = k->n3,
                           *restrict b4 = k->n4, *restrict bs = k->sec;
    int diff = 0;
#pragma omp parallel for schedule(static) reduction(| : diff) if (in->nseg > 16384)
    for (ct_idx j = 0; j < in->nseg; j++)
        diff |= (a1[j] != b1[j]) | (a2[j] != b2[j]) | (a3[j] != b3[j]) | (a4[j] != b4[j]);
#pragma omp parallel for schedule(static) reduction(| : diff) if (in->nsec > 65536)
    for (ct_idx i = 0; i < in->nsec; i++)
        diff |= as[i] != bs[i];
    return !diff;
}

int cti_topo_key_store(cti_topo_key *k, const ct_search_input *in)
{
    const size_t ns = (size_t)in->nsec, ng = (size_t)in->nseg;
    int ok = 1;
    k->valid = 0;
    if (ns > k->cap_sec) {
        ct_free(k->sec);
        ok &= (k->sec = ct_calloc(ns, sizeof(ct_idx))) != NULL;
        k->cap_sec = ok ? ns : 0;
    }
    if (ok && ng > k->cap_seg) {
        ct_idx **ip[] = {&k->n1, &k->n2, &k->n3, &k->n4};
        for (int i = 0; i < 4; i++) {
            ct_free(*ip[i]);
            ok &= (*ip[i] = ct_calloc(ng, sizeof(ct_idx))) != NULL;
        }
        k->cap_seg = ok ? ng : 0;
    }
    if (!ok)
        return CT_ERR_NOMEM;
    const ct_idx *restrict a1 = in->n1, *restrict a2 = in->n2, *restrict a3 = in->n3,
                           *restrict a4 = in->n4, *restrict as = in->sec;
    ct_idx *restrict b1 = k->n1, *restrict b2 = k->n2, *restrict b3 = k->n3, *restrict b4 = k->n4,
                     *restrict bs = k->sec;
#pragma omp parallel for schedule(static) if (in->nseg > 16384)
    for (ct_idx j = 0; j < in->nseg; j++) {
        b1[j] = a1[j];
        b2[j] = a2[j];
        b3[j] = a3[j];
        b4[j] = a4[j];
    }
#pragma omp parallel for schedule(static) if (in->nsec > 65536)
    for (ct_idx i = 0; i < in->nsec; i++)
        bs[i] = as[i];
    k->nnode = in->nnode;
    k->nsec = in->nsec;
    k->nseg = in->nseg;
    k->valid = 1;
    return CT_OK;
}
