/*
 * test_search_bucket_auto.c -- the bucket grid's cell size chosen per input
 * (kernels/search_bucket_auto.c): its counts against brute force, its
 * choice against pricing every candidate, the pairs it gives, when it
 * chooses again, what ct_search_get_info reports, and `contact search
 * --cells`.
 */
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_search_scene.h"

#include "meshgen.h"
#include "search_bucket_internal.h"

/* A case's search input, its float boxes and the grid's region and caps as
 * the search computes them. */
typedef struct auto_case {
    ctd_case c;
    ct_search_input in;
    float *fbox;
    ct_real lo[3], hi[3];
    int64_t maxc, limit;
} auto_case;

static void auto_case_make(auto_case *a, const char *family, int64_t n)
{
    ct_diag d = {0};
    cr_assert_eq(ctd_case_make(&a->c, family, n, CTD_NUM_NATURAL, 7, &d), CT_OK, "%s", d.msg);
    ctd_case_input(&a->c, (ct_real)(0.3 * a->c.h_mean), (ct_real)(0.2 * a->c.h_mean), &a->in);
    a->fbox = ct_calloc((size_t)8 * (size_t)a->in.nseg, sizeof(float));
    cr_assert_not_null(a->fbox);
    ct_real mb[6];
    cr_assert_eq(cti_bucket_boxes(&a->in, NULL, NULL, a->fbox, NULL, mb), CT_OK);
    const ct_real dd = a->in.gap + a->in.margin;
    for (int k = 0; k < 3; k++) {
        a->lo[k] = mb[k] - dd;
        a->hi[k] = mb[3 + k] + dd;
    }
    a->maxc = 2 * ((int64_t)a->in.nsec + a->in.nseg) + 1024;
    a->limit = 32 * ((int64_t)a->in.nsec + a->in.nseg) + (1 << 20);
}

static void auto_case_free(auto_case *a)
{
    ct_free(a->fbox);
    ctd_case_destroy(&a->c);
}

/* Cell of v along one axis, written here from the definition (floor of the
 * distance from lo in cells, clamped to the grid). */
static int64_t cell_of(double v, double lo, double inv, int64_t n)
{
    double t = floor((v - lo) * inv);
    return t < 0 ? 0 : (t > (double)(n - 1) ? n - 1 : (int64_t)t);
}

/* Exact counts on the grid of factor f: cells, entries (cells covered by
 * each segment's float box) and tests (couples of a secondary node in the
 * region and a segment whose range holds the node's cell, counted couple
 * by couple: no histogram). Returns 0 when the entries pass the limit. */
static int exact_counts(const auto_case *a, double f, double *cells, double *ent, double *tests)
{
    ct_idx n[3];
    ct_real inv[3];
    cti_bucket_size(a->lo, a->hi, a->in.nseg, f, a->maxc, n, inv);
    *cells = (double)n[0] * n[1] * n[2];
    const ct_search_input *in = &a->in;
    int64_t *r = malloc(sizeof(int64_t) * 6 * (size_t)in->nseg);
    char *hit = calloc((size_t)in->nseg, 1);
    cr_assert(r && hit);
    double e = 0;
    for (ct_idx j = 0; j < in->nseg; j++) {
        const float *b = a->fbox + (size_t)8 * j;
        int inside = 1;
        for (int k = 0; k < 3; k++) {
            double l = b[k], h = -(double)b[4 + k];
            inside &= !(h < a->lo[k] || l > a->hi[k]);
            r[6 * j + k] = cell_of(l, a->lo[k], inv[k], n[k]);
            r[6 * j + 3 + k] = cell_of(h, a->lo[k], inv[k], n[k]);
        }
        hit[j] = (char)inside;
        if (inside)
            e += (double)(r[6 * j + 3] - r[6 * j] + 1) * (double)(r[6 * j + 4] - r[6 * j + 1] + 1) *
                 (double)(r[6 * j + 5] - r[6 * j + 2] + 1);
    }
    double t = 0;
    const ct_real *xyz[3] = {in->x, in->y, in->z};
    for (ct_idx i = 0; i < in->nsec; i++) {
        ct_idx p = in->sec[i];
        int64_t c[3];
        int inside = 1;
        for (int k = 0; k < 3; k++) {
            inside &= xyz[k][p] >= a->lo[k] && xyz[k][p] <= a->hi[k];
            c[k] = cell_of(xyz[k][p], a->lo[k], inv[k], n[k]);
        }
        if (!inside)
            continue;
        for (ct_idx j = 0; j < in->nseg; j++)
            t += hit[j] && c[0] >= r[6 * j] && c[0] <= r[6 * j + 3] && c[1] >= r[6 * j + 1] &&
                 c[1] <= r[6 * j + 4] && c[2] >= r[6 * j + 2] && c[2] <= r[6 * j + 5];
    }
    free(r);
    free(hit);
    *ent = e;
    *tests = t;
    return e <= (double)a->limit;
}

static double choose(const auto_case *a, int nb, cti_bucket_auto_info *info)
{
    void *scr = ct_calloc(cti_bucket_auto_scratch(a->in.nsec, a->in.nseg), 1);
    cr_assert_not_null(scr);
    double f =
        cti_bucket_auto_factor(&a->in, a->fbox, a->lo, a->hi, a->maxc, a->limit, nb, scr, info);
    ct_free(scr);
    return f;
}

/* On inputs small enough to be sampled whole, the chooser's counts are
 * exact, and its choice is the cheapest of all the candidates priced by
 * brute force (the pruning of finer grids never drops the best). */
Test(search_bucket_auto, whole_sample_exact_and_cheapest)
{
    const char *fams[] = {"plates", "crumpled", "soup", "graded", "sphere", "block"};
    for (int q = 0; q < 6; q++) {
        auto_case a;
        auto_case_make(&a, fams[q], 1500);
        cr_assert(a.in.nseg <= BK_AUTO_SEGS && a.in.nsec <= BK_AUTO_NODES);
        for (int nb = 1; nb <= 2; nb++) {
            cti_bucket_auto_info info;
            double f = choose(&a, nb, &info);
            double best = -1, best_f = 0, cells, ent, tests;
            for (int c = 0; c < BK_AUTO_NF; c++) {
                if (!exact_counts(&a, cti_bucket_auto_factors[c], &cells, &ent, &tests))
                    break;
                double cost = BK_AUTO_E * ent + tests + BK_AUTO_C * nb * cells;
                if (best < 0 || cost < best - 1e-9 * best) {
                    best = cost;
                    best_f = cti_bucket_auto_factors[c];
                }
            }
            cr_assert_eq(f, best_f, "%s, %d blocks: chose %g, the cheapest is %g", fams[q], nb, f,
                         best_f);
            exact_counts(&a, f, &cells, &ent, &tests);
            cr_assert_eq(info.cells, cells, "%s: cells", fams[q]);
            cr_assert_eq(info.entries, ent, "%s: entries %g, exact %g", fams[q], info.entries, ent);
            cr_assert_eq(info.tests, tests, "%s: tests %g, exact %g", fams[q], info.tests, tests);
        }
        auto_case_free(&a);
    }
}

/* Sampled (10^5 nodes: about 1 segment in 24 and 1 node in 12), the
 * estimates stay within 10 % of the exact counts on regular meshes, where
 * a sample that aliases with the numbering would not (two plates numbered
 * alike doubled the tests in a first version). */
Test(search_bucket_auto, sampled_estimates_close, .timeout = 120)
{
    const char *fams[] = {"plates", "soup"};
    for (int q = 0; q < 2; q++) {
        auto_case a;
        auto_case_make(&a, fams[q], ctt_checking() ? 30000 : 100000);
        cti_bucket_auto_info info;
        double f = choose(&a, 1, &info);
        /* Exact counts by histogram (the couple-by-couple count is
         * quadratic): cells, entries, then each node's cell's count. */
        ct_idx n[3];
        ct_real inv[3];
        cti_bucket_size(a.lo, a.hi, a.in.nseg, f, a.maxc, n, inv);
        int64_t ncell = (int64_t)n[0] * n[1] * n[2];
        double *cnt = calloc((size_t)ncell, sizeof *cnt);
        double ent = 0, tests = 0;
        for (ct_idx j = 0; j < a.in.nseg; j++) {
            const float *b = a.fbox + (size_t)8 * j;
            int64_t lo[3], hi[3];
            for (int k = 0; k < 3; k++) {
                lo[k] = cell_of(b[k], a.lo[k], inv[k], n[k]);
                hi[k] = cell_of(-(double)b[4 + k], a.lo[k], inv[k], n[k]);
            }
            for (int64_t z = lo[2]; z <= hi[2]; z++)
                for (int64_t y = lo[1]; y <= hi[1]; y++)
                    for (int64_t x = lo[0]; x <= hi[0]; x++) {
                        cnt[(z * n[1] + y) * n[0] + x] += 1;
                        ent += 1;
                    }
        }
        const ct_real *xyz[3] = {a.in.x, a.in.y, a.in.z};
        for (ct_idx i = 0; i < a.in.nsec; i++) {
            ct_idx p = a.in.sec[i];
            int64_t c[3];
            for (int k = 0; k < 3; k++)
                c[k] = cell_of(xyz[k][p], a.lo[k], inv[k], n[k]);
            tests += cnt[(c[2] * n[1] + c[1]) * n[0] + c[0]];
        }
        free(cnt);
        cr_assert_lt(fabs(info.entries / ent - 1), 0.1, "%s: entries %g, exact %g", fams[q],
                     info.entries, ent);
        cr_assert_lt(fabs(info.tests / tests - 1), 0.1, "%s: tests %g, exact %g", fams[q],
                     info.tests, tests);
        auto_case_free(&a);
    }
}

/* What the weights were fitted to show: a volume filled with small plates
 * gets cells coarser than the Radioss sizing (its segments' boxes cover
 * tens of its cells), a mesh whose elements grow 100x gets finer ones (its
 * coarse cells hold hundreds of small segments). */
Test(search_bucket_auto, soup_coarser_graded_finer)
{
    auto_case a;
    cti_bucket_auto_info info;
    auto_case_make(&a, "soup", 20000);
    cr_assert_lt(choose(&a, 1, &info), 1.0, "soup: factor %g", info.factor);
    auto_case_free(&a);
    auto_case_make(&a, "graded", 20000);
    cr_assert_gt(choose(&a, 1, &info), 1.0, "graded: factor %g", info.factor);
    auto_case_free(&a);
}

/* The chosen grid changes the cost, never the pairs: the default (chosen)
 * and every candidate factor give direct's pairs. */
Test(search_bucket_auto, same_pairs_as_direct)
{
    const char *fams[] = {"soup", "graded"};
    for (int q = 0; q < 2; q++) {
        auto_case a;
        auto_case_make(&a, fams[q], 4000);
        ct_pairs ref, got;
        ct_pairs_init(&ref, 0);
        ct_pairs_init(&got, 0);
        ctt_search(CT_SEARCH_DIRECT, &a.in, &ref);
        cr_assert_gt(ref.n, 0);
        for (int c = -1; c < BK_AUTO_NF; c++) {
            ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
            cr_assert_eq(p.cell_factor, 0.0, "the default is the chosen grid");
            if (c >= 0)
                p.cell_factor = cti_bucket_auto_factors[c];
            ctt_search_with(&p, &a.in, &got);
            cr_assert(ctt_same_pairs(&ref, &got), "%s, factor %g: pairs differ from direct",
                      fams[q], p.cell_factor);
        }
        ct_pairs_destroy(&ref);
        ct_pairs_destroy(&got);
        auto_case_free(&a);
    }
}

/* The chooser's scratch follows the input up to the sample caps: a search
 * of a few hundred nodes held 460 KB for it whatever its size (7.1 KB per
 * node of an 81-node plate; the memsets of its 131 KB table made that
 * search 6 times slower). Its bytes, and a small search's memory against
 * the same search on a fixed grid (which never chooses). */
Test(search_bucket_auto, scratch_follows_the_input)
{
    const size_t big = (size_t)3 * BK_AUTO_NODES * sizeof(ct_real) +
                       (size_t)8 * BK_AUTO_SEGS * sizeof(float) + (size_t)2 * BK_AUTO_NODES * 8;
    cr_expect_eq(cti_bucket_auto_scratch(1000000, 1000000), big);
    cr_expect_eq(cti_bucket_auto_scratch(BK_AUTO_NODES, BK_AUTO_SEGS), big);
    /* 100 nodes and 80 segments: 2400 + 2560 bytes of samples, a table of
     * 256 slots of 8 bytes. */
    cr_expect_eq(cti_bucket_auto_scratch(100, 80),
                 100 * 3 * sizeof(ct_real) + 80 * 8 * sizeof(float) + 256 * 8);
    cr_expect_eq(cti_bucket_auto_scratch(0, 0), (size_t)16 * 8);
    auto_case a;
    auto_case_make(&a, "plates", 200);
    ct_pairs got;
    ct_pairs_init(&got, 0);
    size_t mem[2];
    double chosen = 0;
    for (int q = 0; q < 2; q++) {
        /* First the chooser, then a fixed grid of the factor it chose. */
        ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
        p.cell_factor = q ? chosen : 0.0;
        ct_search *s;
        cr_assert_eq(ct_search_init(&s, &p), CT_OK);
        cr_assert_eq(ct_search_run(s, &a.in, &got), CT_OK);
        mem[q] = ct_search_memory(s);
        ct_search_info si;
        cr_assert_eq(ct_search_get_info(s, &si), CT_OK);
        chosen = si.cell_factor;
        cr_assert_gt(chosen, 0);
        ct_search_destroy(s);
    }
    const size_t scr = cti_bucket_auto_scratch(a.in.nsec, a.in.nseg);
    cr_expect_leq(scr, 16384, "%zu bytes for %d nodes", scr, a.in.nsec);
    cr_expect_geq(mem[0], mem[1] + scr, "auto %zu, fixed %zu", mem[0], mem[1]);
    /* The scratch array grows by half again plus 64 entries at a time. */
    cr_expect_leq(mem[0], mem[1] + scr + scr / 2 + 64 * sizeof(ct_real),
                  "auto %zu, fixed %zu, scratch %zu", mem[0], mem[1], scr);
    ct_pairs_destroy(&got);
    auto_case_free(&a);
}

/* The choice is kept for BK_AUTO_EVERY searches of an input whose counts
 * and extent stay, and made again when the extent grows by more than
 * BK_AUTO_DRIFT or the counts change. */
Test(search_bucket_auto, chosen_again_when_the_input_changes)
{
    auto_case a;
    auto_case_make(&a, "soup", 3000);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
    ct_search *s;
    cr_assert_eq(ct_search_init(&s, &p), CT_OK);
    ct_pairs out;
    ct_pairs_init(&out, 0);
    cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
    const bk_state *st = s->algo_state;
    cr_assert_gt(st->auto_f, 0);
    cr_assert_eq(st->auto_age, 1);
    for (int k = 2; k <= BK_AUTO_EVERY; k++) {
        cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
        cr_assert_eq(st->auto_age, k, "kept while the input stays");
    }
    cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
    cr_assert_eq(st->auto_age, 1, "chosen again after BK_AUTO_EVERY searches");
    cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
    cr_assert_eq(st->auto_age, 2);
    /* Stretch the x extent by 1.25: chosen again. */
    ct_real *x = a.c.mesh.nodes.x;
    for (ct_idx i = 0; i < a.c.mesh.nodes.n; i++)
        x[i] *= 1.25;
    cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
    cr_assert_eq(st->auto_age, 1, "chosen again when the extent changes");
    cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
    cr_assert_eq(st->auto_age, 2);
    /* One secondary fewer: chosen again. */
    a.in.nsec -= 1;
    cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
    cr_assert_eq(st->auto_age, 1, "chosen again when the counts change");
    ct_pairs_destroy(&out);
    ct_search_destroy(s);
    auto_case_free(&a);
}

/* ct_search_get_info reports the grid's factor the last bucket search used
 * (the chosen one, or the one set) and whether it ran on a renumbered copy;
 * 0 for the other algorithms. */
Test(search_bucket_auto, info_reports_the_choice)
{
    auto_case a;
    auto_case_make(&a, "soup", 70000); /* pieces, above 2^16 nodes: renumbered */
    cr_assert_geq(a.in.nnode, 1 << 16);
    ct_pairs out;
    ct_pairs_init(&out, 0);
    for (int c = -1; c < 2; c++) {
        ct_search_params p = ct_search_default_params(CT_SEARCH_BUCKET);
        if (c >= 0)
            p.cell_factor = c ? 1.4 : 0.5;
        p.renumber = c == 1 ? -1 : 0;
        ct_search *s;
        cr_assert_eq(ct_search_init(&s, &p), CT_OK);
        cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
        ct_search_info info;
        cr_assert_eq(ct_search_get_info(s, &info), CT_OK);
        if (c < 0) {
            /* The factor the workspace chose (on the renumbered copy). */
            cr_assert_gt(info.cell_factor, 0);
            cr_assert_eq(info.cell_factor, ((const bk_state *)s->algo_state)->auto_f);
        } else {
            cr_assert_eq(info.cell_factor, p.cell_factor);
        }
        cr_assert_eq(info.renumbered, c != 1, "renumber %d", p.renumber);
        cr_assert_eq(ct_search_get_info(s, NULL), CT_ERR_ARG);
        ct_search_destroy(s);
    }
    ct_search_info info;
    cr_assert_eq(ct_search_get_info(NULL, &info), CT_ERR_ARG);
    ct_search_params p = ct_search_default_params(CT_SEARCH_BSP);
    ct_search *s;
    cr_assert_eq(ct_search_init(&s, &p), CT_OK);
    cr_assert_eq(ct_search_run(s, &a.in, &out), CT_OK);
    cr_assert_eq(ct_search_get_info(s, &info), CT_OK);
    cr_assert_eq(info.cell_factor, 0);
    cr_assert_eq(info.renumbered, 0);
    ct_search_destroy(s);
    ct_pairs_destroy(&out);
    auto_case_free(&a);
}

/* `contact search --cells`: a factor is used and printed, auto prints the
 * chosen one, and a factor out of (0, 100] is refused naming the option. */
Test(search_bucket_auto, cli_cells_option)
{
    char self[1024], cmd[1400], line[512];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    cr_assert(len > 0);
    self[len] = '\0';
    const char *dir = dirname(self);
    const char *vals[] = {"0.5", "auto"};
    for (int k = 0; k < 2; k++) {
        snprintf(cmd, sizeof cmd,
                 "OMP_NUM_THREADS=2 '%s/contact' search --family soup --n 3000 --algo bucket "
                 "--repeat 1 --cells %s",
                 dir, vals[k]);
        FILE *f = popen(cmd, "r");
        cr_assert_not_null(f);
        int seen = 0;
        while (fgets(line, sizeof line, f)) {
            if (strncmp(line, "  bucket", 8))
                continue;
            const char *c = strstr(line, "cells x");
            cr_assert_not_null(c, "no factor in: %s", line);
            double fct = atof(c + 7);
            if (k == 0)
                cr_assert_eq(fct, 0.5, "%s", line);
            else
                cr_assert_gt(fct, 0, "%s", line);
            cr_assert_not_null(strstr(line, "identical to direct"), "%s", line);
            seen++;
        }
        int st = pclose(f);
        cr_assert(WIFEXITED(st) && WEXITSTATUS(st) == 0, "status %d for --cells %s", st, vals[k]);
        cr_assert_eq(seen, 1);
    }
    const char *bad[] = {"0", "-1", "nan", "101", "x"};
    for (int k = 0; k < 5; k++) {
        snprintf(cmd, sizeof cmd, "'%s/contact' search --cells %s 2>&1", dir, bad[k]);
        FILE *f = popen(cmd, "r");
        cr_assert_not_null(f);
        int named = 0;
        while (fgets(line, sizeof line, f))
            named |= strstr(line, "--cells expects auto or a factor") != NULL;
        int st = pclose(f);
        cr_assert(WIFEXITED(st) && WEXITSTATUS(st) == 1, "--cells %s: status %d", bad[k], st);
        cr_assert(named, "--cells %s: no message naming the option", bad[k]);
    }
}
