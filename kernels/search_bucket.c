/* search_bucket.c -- placeholder until the bucket search lands; always fails. */
#include "ct_internal.h"

int cti_search_bucket(ct_search *s, const ct_search_input *in, ct_pairs *out)
{
    (void)s;
    (void)in;
    (void)out;
    return CT_ERR_ARG;
}
