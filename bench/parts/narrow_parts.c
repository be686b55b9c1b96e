/*
 * narrow_parts.c -- the node-segment narrow phase taken apart (`make
 * bench-parts`): on one block of 64 pairs whose data stay in L1, repeated,
 * the time per pair of each part of a block's work alone (the block kernel
 * reading its block scratch, the copy of the coordinates into it through
 * the indices, the gaps), and of the three in sequence as the library runs
 * them. No memory traffic beyond L1 is in these figures: they say what the
 * instructions themselves cost with every datum in L1, the best case of the
 * same code at any number of pairs (docs/TARGETS.md uses them). It reads the library's internal
 * header (kernels/narrow_internal.h), so it is built against the library
 * of the same build and is not part of `make bench`.
 *
 * Pairs: those of the kernel benchmark (bench_kernels.c), on a smaller
 * mesh: the plates case of meshgen.h ("plates-tri" for the node-triangle
 * kernel, "plates" for the 4-triangle one), searched by the bucket search
 * with gap 0.35 h and margin 0.15 h, in node order; the block is the list's
 * middle 64 pairs. The kernels' arithmetic is branch-free, but its time
 * still depends on the data (in a first version, triangles of three random
 * nodes ran the node-triangle kernel 1.2 times faster than triangles of
 * three neighbouring random nodes), so the pairs are the benchmark's own.
 */
#include "narrow_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "meshgen.h"

enum { NPAIR = CTI_NR_BLOCK, NREP = 5 };

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The parts of one kind (quad: the 4-triangle kernel on quadrangles). */
enum { P_KERNEL, P_COPY, P_GAP, P_ALL, P_N };
static const char *const part_name[P_N] = {"block kernel", "copy", "gaps", "all three"};

/* The time per pair of part `part`, median of NREP runs of `reps` blocks. */
static double time_part(const cti_nr_args *a, int quad, int part, long reps, cti_nr_blk *b)
{
    double t[NREP];
    for (int r = 0; r < NREP; r++) {
        const double t0 = now();
        for (long i = 0; i < reps; i++) {
            ct_idx m = NPAIR;
            if (part == P_COPY || part == P_ALL)
                m = cti_nr_fetch(a, 0, NPAIR, quad, b);
            if (part == P_GAP || part == P_ALL)
                cti_nr_gather(a, 0, m, b);
            if (part == P_KERNEL || part == P_ALL)
                (quad ? cti_nr_block_4tri : cti_nr_block_tri)(a, 0, m, b);
            /* Keep every repetition: the outputs and the scratch are read
             * by "something" the compiler cannot see. */
            __asm__ volatile("" : : "r"(b), "r"(a->out->dist) : "memory");
        }
        t[r] = (now() - t0) / (double)reps / NPAIR * 1e9;
    }
    qsort(t, NREP, sizeof t[0], cmp_double);
    return t[NREP / 2];
}

int main(int argc, char **argv)
{
    const long reps = argc > 1 ? atol(argv[1]) : 1000000;
    if (reps <= 0) {
        fprintf(stderr, "usage: narrow_parts [blocks per run, > 0]\n");
        return 1;
    }
    static ct_real o[13][NPAIR];
    static uint8_t flag[NPAIR];
    const ct_contact_geo g = {o[0], o[1], o[2], o[3], o[4],  o[5],  o[6],
                              o[7], o[8], o[9], o[10], o[11], o[12], flag};
    static cti_nr_blk b;
    printf("narrow_parts: %s\n", ct_build_info());
    printf("one block of %d pairs in L1, ns per pair, median of %d runs of %ld blocks\n",
           NPAIR, NREP, reps);
    printf("%-14s", "kernel");
    for (int p = 0; p < P_N; p++)
        printf(" %13s", part_name[p]);
    printf("\n");
    for (int quad = 0; quad < 2; quad++) {
        /* The benchmark's pairs (bench_kernels_data.c), on about 4000
         * secondary nodes. */
        ctd_case c;
        ct_diag diag;
        ct_pairs pairs;
        memset(&pairs, 0, sizeof pairs);
        ct_search *srch = NULL;
        int rc = ctd_case_make(&c, quad ? "plates" : "plates-tri", 4000, CTD_NUM_NATURAL, 1,
                               &diag);
        if (rc != CT_OK) {
            fprintf(stderr, "narrow_parts: the plates case: %s\n", ct_strerror(rc));
            return 1;
        }
        ct_search_input in;
        ctd_case_input(&c, (ct_real)(0.35 * c.h_mean), (ct_real)(0.15 * c.h_mean), &in);
        ct_search_params sp = ct_search_default_params(CT_SEARCH_BUCKET);
        rc = ct_search_init(&srch, &sp);
        if (rc == CT_OK)
            rc = ct_pairs_init(&pairs, 0);
        if (rc == CT_OK)
            rc = ct_search_run(srch, &in, &pairs);
        ct_search_destroy(srch);
        if (rc != CT_OK || pairs.n < 3 * NPAIR) {
            fprintf(stderr, "narrow_parts: the search: %s\n", ct_strerror(rc));
            return 1;
        }
        const ct_idx k0 = pairs.n / 2;
        cti_nr_args a;
        memset(&a, 0, sizeof a);
        a.node = pairs.node + k0;
        a.seg = pairs.seg + k0;
        a.n1 = in.n1;
        a.n2 = in.n2;
        a.n3 = in.n3;
        a.n4 = in.n4;
        a.x = in.x;
        a.y = in.y;
        a.z = in.z;
        a.gap = (ct_real)(0.35 * c.h_mean);
        a.out = &g;
        b.newton_more = 0;
        /* The block scratch filled once, for the kernel alone. */
        if (cti_nr_fetch(&a, 0, NPAIR, quad, &b) != NPAIR) {
            fprintf(stderr, "narrow_parts: the block mixes segment kinds\n");
            return 1;
        }
        cti_nr_gather(&a, 0, NPAIR, &b);
        printf("%-14s", quad ? "4 triangles" : "node-triangle");
        for (int p = 0; p < P_N; p++)
            printf(" %13.2f", time_part(&a, quad, p, reps, &b));
        printf("\n");
        ct_pairs_destroy(&pairs);
        ctd_case_destroy(&c);
    }
    return 0;
}
