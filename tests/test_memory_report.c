/*
 * test_memory_report.c -- the bytes an interface and a contact cycle say
 * they hold (ctd_iface_memory through the solver's hooks, shown in a run's
 * report and summary.json; ctd_cycle_memory, for the benchmark) against
 * what the C library's allocator measured while they were built and run
 * (glibc's mallinfo2: bytes in use in the main arena plus mmapped blocks).
 *
 * Between the two readings of the allocator only the interfaces (or the
 * cycle) allocate, so the heap's growth is their memory plus the
 * allocator's own overhead per block (a header, and up to 63 bytes of
 * alignment padding per 64-byte-aligned array) plus the few small blocks
 * the memory functions do not count (names, the hook's context). The
 * functions count array capacities, so a figure above the growth means
 * they counted something that was never allocated, and a figure far
 * below it means they missed arrays: both fail here. Not under the
 * sanitizers, whose allocators mallinfo2 does not see.
 */
#include <criterion/criterion.h>
#include <malloc.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_cycle.h"
#include "meshgen.h"
#include "model.h"
#include "scene.h"
#include "solver.h"
#include "test_util.h"

static double heap_bytes(void)
{
    struct mallinfo2 mi = mallinfo2();
    return (double)mi.uordblks + (double)mi.hblkhd;
}

static void scene_file(char *p, size_t n, const char *name)
{
    const char *f = __FILE__, *slash = strrchr(f, '/');
    snprintf(p, n, "%.*s/../data/scenes/%s", slash ? (int)(slash - f) : 1, slash ? f : ".", name);
}

/* The interfaces of a scene, built and stepped `cycles` times on the
 * model's reference state: (counted, grown). */
static void iface_memory(const char *name, int refine, int cycles, double *counted,
                         double *grown, int *nhook_out)
{
    char p[1024], err[1024] = "";
    scene_file(p, sizeof p, name);
    static ctd_scene_err se;
    ctd_scene *sc = NULL;
    cr_assert_eq(ctd_scene_load_refined(p, refine, &sc, &se), CT_OK, "%s",
                 se.count ? se.msg[0].text : "?");
    ctd_model m;
    cr_assert_eq(ctd_model_build(&m, sc, err, sizeof err), CT_OK, "%s", err);
    const ct_idx n = m.mesh.nodes.n;
    ct_real *f[3], *v = ct_calloc((size_t)n, sizeof(ct_real));
    cr_assert(v);
    for (int a = 0; a < 3; a++) {
        f[a] = ct_calloc((size_t)n, sizeof(ct_real));
        cr_assert(f[a]);
    }
    ctd_state st = {0, 1e-7, 0, n, m.mesh.nodes.x, m.mesh.nodes.y, m.mesh.nodes.z,
                    v, v, v, m.mesh.nodes.m, m.node_part, 0};
    const double h0 = heap_bytes();
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    cr_assert_eq(ctd_interfaces_build(&m, sc, &hooks, &nhook, err, sizeof err), CT_OK, "%s",
                 err);
    for (int c = 0; c < cycles; c++) {
        st.step = c;
        st.time = c * st.dt;
        for (int i = 0; i < nhook; i++) {
            ctd_contact_report rep;
            memset(&rep, 0, sizeof rep);
            cr_assert_eq(hooks[i].contact_step(hooks[i].ctx, &st, f[0], f[1], f[2], &rep),
                         CT_OK);
        }
    }
    double c = 0;
    for (int i = 0; i < nhook; i++) {
        cr_assert_not_null(hooks[i].memory, "interface %d has no memory function", i);
        c += (double)hooks[i].memory(hooks[i].ctx);
    }
    *grown = heap_bytes() - h0;
    *counted = c;
    *nhook_out = nhook;
    for (int i = 0; i < nhook; i++)
        hooks[i].destroy(hooks[i].ctx);
    free(hooks);
    for (int a = 0; a < 3; a++)
        ct_free(f[a]);
    ct_free(v);
    ctd_model_destroy(&m);
    ctd_scene_free(sc);
}

/* The figure never exceeds the growth, and falls short of it by the
 * allocator's overhead and the small uncounted blocks alone: at most about
 * 200 bytes per array (a 16-byte header, the 64-byte alignment, ct_calloc's
 * rounding of the count) over 100-150 arrays, 32 KiB, or 3 % of the growth
 * on the larger models (measured 0.2-1 % there). The allowance is a size
 * in bytes, not a fraction: it was once 3 % alone, which the smallest
 * models met only while every bucket search held a 460 KB sampling scratch
 * whatever its input (now sized by the input: those models grow by 170 KB
 * and fall 10-21 KB short). Before this test, the interfaces
 * missed their node lists' spare capacity (4.5 % of the showcase's
 * growth), the element stiffness and a pass's hand-over array, and counted
 * an edge search array never allocated (2 % over on the folding sheet);
 * an array missed in proportion to the mesh exceeds the allowance at
 * refine 4. */
static void expect_close(const char *what, double counted, double grown)
{
    cr_log_info("%s: counted %.0f bytes, the heap grew by %.0f (%.3f)", what, counted, grown,
                counted / grown);
    cr_assert_gt(counted, 0, "%s: nothing counted", what);
    cr_assert_leq(counted, grown, "%s: counted %.0f bytes, but the heap grew by %.0f only", what,
                  counted, grown);
    const double allow = fmax(0.03 * grown, 32768.0);
    cr_assert_geq(counted, grown - allow, "%s: counted %.0f bytes of the %.0f the heap grew by",
                  what, counted, grown);
}

Test(memory_report, interface_memory_is_the_heap_it_grew)
{
    if (ctt_checking())
        cr_skip_test("mallinfo2 does not see the sanitizers' allocators");
    const char *scenes[3] = {"folding-sheet.yaml", "showcase.yaml", "sliding-block.yaml"};
    for (int k = 0; k < 3; k++)
        for (int refine = 1; refine <= 4; refine += 3) {
            double counted, grown;
            int nhook;
            iface_memory(scenes[k], refine, 5, &counted, &grown, &nhook);
            char what[256];
            snprintf(what, sizeof what, "%s refine %d (%d interfaces)", scenes[k], refine,
                     nhook);
            expect_close(what, counted, grown);
        }
}

/* The contact cycle of the benchmark on a folded sheet (2500 nodes),
 * built and run 40 cycles of its prescribed motion (re-sorts included):
 * ctd_cycle_memory against the heap's growth. */
Test(memory_report, cycle_memory_is_the_heap_it_grew)
{
    if (ctt_checking())
        cr_skip_test("mallinfo2 does not see the sanitizers' allocators");
    ctd_case c;
    ct_diag diag;
    cr_assert_eq(ctd_case_make(&c, "folded", 2500, CTD_NUM_NATURAL, 1, &diag), CT_OK, "%s",
                 diag.msg);
    const ct_idx n = c.mesh.nodes.n;
    const double h = c.h_mean;
    ct_real *ref[3] = {c.mesh.nodes.x, c.mesh.nodes.y, c.mesh.nodes.z}, *pos[3], *vel[3], *f[3];
    ct_real *m = ct_calloc((size_t)n, sizeof(ct_real));
    cr_assert(m);
    for (ct_idx i = 0; i < n; i++)
        m[i] = 1;
    double lo = 1e300, hi = -1e300;
    for (int a = 0; a < 3; a++) {
        pos[a] = ct_calloc((size_t)n, sizeof(ct_real));
        vel[a] = ct_calloc((size_t)n, sizeof(ct_real));
        f[a] = ct_calloc((size_t)n, sizeof(ct_real));
        cr_assert(pos[a] && vel[a] && f[a]);
    }
    for (ct_idx i = 0; i < n; i++) {
        lo = fmin(lo, (double)ref[1][i]);
        hi = fmax(hi, (double)ref[1][i]);
    }
    /* The layers pressed into contact and sliding (the motion of
     * tests/test_cycle.c), 0.05 h per cycle at most. */
    ctd_motion mo = {1, 2, 0.5 * (lo + hi), 0.72, 0.1, 0.5 * h, 0.8 * h, 1};
    mo.period = ctd_motion_max_step(&mo, 0.5 * (hi - lo)) / (0.05 * h);
    ctd_cycle_params p = ctd_cycle_default_params(h);
    const double h0 = heap_bytes();
    ctd_cycle *cy = NULL;
    cr_assert_eq(ctd_cycle_init(&cy, &p, n, m, c.sec.n, c.sec.node, c.sec.n, c.sec.node,
                                c.main.n, c.mn1, c.mn2, c.mn3, c.mn4, 1),
                 CT_OK);
    const double dt = 1e-3;
    int64_t active = 0;
    for (int k = 0; k < 40; k++) {
        ctd_motion_eval(&mo, n, (const ct_real *const *)ref, k, dt, pos, vel);
        cr_assert_eq(ctd_cycle_step(cy, pos[0], pos[1], pos[2], vel[0], vel[1], vel[2],
                                    (ct_real)dt, f[0], f[1], f[2]),
                     CT_OK);
        active += ctd_cycle_get_stats(cy)->nactive;
    }
    const double counted = (double)ctd_cycle_memory(cy), grown = heap_bytes() - h0;
    cr_assert_gt(active, 0, "the motion never brought the layers into contact");
    expect_close("the folded sheet's cycle", counted, grown);
    ctd_cycle_destroy(cy);
    for (int a = 0; a < 3; a++) {
        ct_free(pos[a]);
        ct_free(vel[a]);
        ct_free(f[a]);
    }
    ct_free(m);
    ctd_case_destroy(&c);
}
