/*
 * test_validation_type7.c -- validation case 9 (issue 6): TYPE7 auto
 * contact on a steel sheet folded onto itself, run whole through the scene
 * reader, the model, the interfaces and the solver, watched every cycle
 * through the solver's observer (ctd_solver_opts.observe):
 *  - no node of a flat layer ever crosses the mid-surface of the facing
 *    layer, checked by a brute-force height-field test of our own (each
 *    node against the triangles of the other layer, in projection),
 *    independent of the interface's search;
 *  - the impact speed is swept until TYPE7's kinematic step
 *    (g - p)/(2 (-vn)) becomes the controlling step, and the step is shown
 *    shrinking;
 *  - a middle layer pinched from above and below (contact on both faces);
 *  - the fold opens again when the load is removed.
 * The scenes are in tests/data/validation/type7_*.yaml.
 */
#include "test_util.h"
#include "test_validation.h"

#include <stdio.h>
#include <string.h>

#include "model.h"
#include "scene.h"
#include "solver.h"

/* ---- The run and its observer ---------------------------------------------------- */

#define MAXLAYER 3

typedef struct watch {
    const ctd_model *m;
    double spacing, gap;
    int nlayer;
    int8_t *layer;   /* flat layer of each node, -1 for the bends */
    ct_idx *tri[MAXLAYER]; /* flat triangles (3 nodes each) of each layer */
    int ntri[MAXLAYER];
    ct_real *vprev;  /* y velocities seen at the previous cycle: v(n-1/2) now */
    /* Over the run. */
    double sep_min[MAXLAYER]; /* smallest separation of layer l+1 over layer l */
    double both_min;          /* smallest max(sep01, sep12): both faces in contact */
    int crossed;
    int64_t cycles, kin_cycles;
    double dt_first, dt_min, dt_kin_min, ratio_kin_est, e7_max, e7_end, t_sep;
    double sep_last[MAXLAYER]; /* at the last cycle */
    /* Release (the squeeze): the time the pushing contact stops, the TYPE7
     * energy and separation there, the first time after it with no TYPE7
     * energy. */
    double t_release, e7_release, sep_release, t_open, sep_max_after;
    FILE *csv;
    int col; /* the column group of this run in csv (3 runs side by side) */
} watch;

static void scene_file(char *buf, size_t n, const char *name)
{
    const char *f = __FILE__, *slash = strrchr(f, '/');
    int len = slash ? (int)(slash - f) : 1;
    snprintf(buf, n, "%.*s/data/validation/%s", len, slash ? f : ".", name);
}

/* The height of layer l's mid-surface over (x, z), by the flat triangles
 * of that layer in projection on the xz plane; 0 when no triangle covers
 * the point. */
static int layer_height(const watch *w, const ctd_solver *s, int l, double px, double pz,
                        double *h)
{
    for (int t = 0; t < w->ntri[l]; t++) {
        const ct_idx *v = &w->tri[l][3 * t];
        double ax = s->x[v[0]], az = s->z[v[0]], bx = s->x[v[1]] - ax, bz = s->z[v[1]] - az;
        double cx = s->x[v[2]] - ax, cz = s->z[v[2]] - az, qx = px - ax, qz = pz - az;
        double det = bx * cz - bz * cx;
        if (det == 0)
            continue;
        double u = (qx * cz - qz * cx) / det, vv = (bx * qz - bz * qx) / det;
        if (u < -1e-6 || vv < -1e-6 || u + vv > 1 + 1e-6)
            continue;
        *h = s->y[v[0]] + u * (s->y[v[1]] - s->y[v[0]]) + vv * (s->y[v[2]] - s->y[v[0]]);
        return 1;
    }
    return 0;
}

static void observe(void *ctx, const ctd_solver *s)
{
    watch *w = ctx;
    const ctd_contact_report *r = &s->rep[0];
    /* Separation of each flat node from the facing layers (signed: positive
     * on the side it started on). */
    double sep[MAXLAYER] = {INFINITY, INFINITY, INFINITY};
    double est = INFINITY;
    for (ct_idx i = 0; i < s->nnode; i++) {
        int l = w->layer[i];
        if (l < 0)
            continue;
        for (int o = l - 1; o <= l + 1; o += 2) {
            double h;
            if (o < 0 || o >= w->nlayer || !layer_height(w, s, o, s->x[i], s->z[i], &h))
                continue;
            double d = o < l ? s->y[i] - h : h - s->y[i];
            int lo = o < l ? o : l;
            if (d < sep[lo])
                sep[lo] = d;
            /* The kinematic step of a node of the top layer over the
             * clamped bottom one, from v(n-1/2) (the velocity the interface
             * saw): distance over twice the approach speed. */
            if (w->nlayer == 2 && l == 1 && d < w->gap && w->vprev[i] < 0)
                est = fmin(est, d / (2 * -(double)w->vprev[i]));
        }
    }
    for (int l = 0; l + 1 < w->nlayer; l++) {
        if (sep[l] < w->sep_min[l])
            w->sep_min[l] = sep[l];
        if (sep[l] <= 0)
            w->crossed = 1;
    }
    if (w->nlayer == 3 && fmax(sep[0], sep[1]) < w->both_min)
        w->both_min = fmax(sep[0], sep[1]);
    /* The step: s->dt led to x(n); the limits of x(n) set the next one. */
    if (s->cycle == 1)
        w->dt_first = s->dt;
    if (s->cycle > 0 && s->dt < w->dt_min)
        w->dt_min = s->dt;
    int kin = r->dt_kin > 0 && r->dt_kin <= r->dt_limit * (1 + 1e-9);
    if (kin) {
        w->kin_cycles++;
        if (r->dt_kin < w->dt_kin_min) {
            w->dt_kin_min = r->dt_kin;
            w->ratio_kin_est = isfinite(est) ? r->dt_kin / est : 0;
        }
    }
    w->e7_max = fmax(w->e7_max, r->energy);
    w->e7_end = r->energy;
    if (w->t_sep < 0 && w->e7_max > 0 && r->energy == 0)
        w->t_sep = s->time;
    if (w->t_release > 0 && s->time <= w->t_release) {
        w->e7_release = r->energy;
        w->sep_release = sep[0];
    }
    if (w->t_release > 0 && s->time > w->t_release && w->t_open < 0 && r->energy == 0)
        w->t_open = s->time;
    if (w->t_release > 0 && s->time > w->t_release && sep[0] < INFINITY)
        w->sep_max_after = fmax(w->sep_max_after, sep[0]);
    for (int l = 0; l < MAXLAYER; l++)
        w->sep_last[l] = sep[l];
    if (w->csv && w->col < 0) {
        /* A history: time, the separations over the gap, TYPE7's energy. */
        ctv_row(w->csv, 4, s->time * 1e6, fmin(sep[0], 20 * w->gap) / w->gap,
                w->nlayer > 2 ? fmin(sep[1], 20 * w->gap) / w->gap : NAN, r->energy);
    } else if (w->csv && s->time <= 45e-6) { /* the impacts up to 100 m/s */
        /* Time, then per column group the step and the separations. */
        double v[7] = {s->time * 1e6, NAN, NAN, NAN, NAN, NAN, NAN};
        v[1 + w->col] = s->cycle > 0 ? s->dt * 1e9 : NAN;
        v[4 + w->col] = (w->nlayer > 2 ? fmin(sep[0], sep[1]) : sep[0]) / w->gap;
        ctv_row(w->csv, 7, v[0], v[1], v[2], v[3], v[4], v[5], v[6]);
    }
    memcpy(w->vprev, s->vy, sizeof(ct_real) * (size_t)s->nnode);
    w->cycles++;
}

typedef struct t7run {
    ctd_scene *sc;
    ctd_model m;
    ctd_solver s;
    watch w;
} t7run;

/* Load a scene, set the thrown layer's speed (v > 0: every node with an
 * initial velocity gets (0, -v, 0)), classify the flat layers, run to
 * end_time with the observer. */
static void t7_run(t7run *r, const char *name, double v, double end_time, FILE *csv, int col)
{
    char p[1024], err[1024] = "";
    scene_file(p, sizeof p, name);
    static ctd_scene_err se;
    int rc = ctd_scene_load(p, &r->sc, &se);
    cr_assert_eq(rc, CT_OK, "%s: %s", p, se.count ? se.msg[0].text : "?");
    rc = ctd_model_build(&r->m, r->sc, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "model: %s", err);
    ct_nodes *nd = &r->m.mesh.nodes;
    if (v > 0)
        for (ct_idx i = 0; i < nd->n; i++)
            if (nd->vy[i] != 0)
                nd->vy[i] = (ct_real)-v;
    watch *w = &r->w;
    memset(w, 0, sizeof *w);
    w->m = &r->m;
    w->spacing = r->sc->mesh[0].generate->spacing;
    w->gap = r->sc->interfaces[0].gap;
    w->nlayer = (int)r->sc->mesh[0].generate->layers;
    cr_assert(w->nlayer >= 2 && w->nlayer <= MAXLAYER);
    w->layer = malloc((size_t)nd->n);
    w->vprev = calloc((size_t)nd->n, sizeof(ct_real));
    cr_assert(w->layer && w->vprev);
    const double lf = r->sc->mesh[0].generate->cells[0] * r->sc->mesh[0].generate->size[0];
    for (ct_idx i = 0; i < nd->n; i++) {
        double fl = nd->y[i] / w->spacing;
        int l = (int)lround(fl);
        /* Coordinates as stored (single precision: 1e-5 relative). */
        w->layer[i] = (fabs(fl - l) < 1e-5 && nd->x[i] >= -1e-5 * lf && nd->x[i] <= lf * (1 + 1e-5) &&
                       r->m.node_part[i] == 1)
                          ? (int8_t)l
                          : -1;
        w->vprev[i] = nd->vy[i];
    }
    for (int l = 0; l < w->nlayer; l++) {
        w->tri[l] = malloc(sizeof(ct_idx) * 6 * (size_t)r->m.mesh.nseg);
        cr_assert(w->tri[l]);
    }
    for (ct_idx k = 0; k < r->m.mesh.nseg; k++) {
        ct_idx q[4] = {r->m.mesh.n1[k], r->m.mesh.n2[k], r->m.mesh.n3[k], r->m.mesh.n4[k]};
        int l = w->layer[q[0]];
        if (l < 0 || r->m.seg_part[k] != 1 || w->layer[q[1]] != l || w->layer[q[2]] != l ||
            w->layer[q[3]] != l)
            continue;
        ct_idx *t = &w->tri[l][3 * w->ntri[l]];
        t[0] = q[0], t[1] = q[1], t[2] = q[2], t[3] = q[0], t[4] = q[2], t[5] = q[3];
        w->ntri[l] += 2;
    }
    for (int l = 0; l < MAXLAYER; l++)
        w->sep_min[l] = INFINITY;
    w->both_min = INFINITY;
    w->dt_min = w->dt_kin_min = INFINITY;
    w->t_sep = -1;
    w->t_open = -1;
    w->t_release = r->sc->interfaces_count > 1 ? r->sc->interfaces[1].Tstop : 0;
    w->csv = csv;
    w->col = col;
    ctd_contact_hook *hooks = NULL;
    int nhook = 0;
    rc = ctd_interfaces_build(&r->m, r->sc, &hooks, &nhook, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "interfaces: %s", err);
    ctd_solver_opts o = ctd_solver_default_opts();
    o.no_output = 1;
    o.quiet = 1;
    o.threads = 1;
    o.end_time = end_time;
    o.observe = observe;
    o.observe_ctx = w;
    rc = ctd_solver_init(&r->s, &r->m, &o, hooks, nhook, err, sizeof err);
    cr_assert_eq(rc, CT_OK, "solver: %s", err);
    ctd_solver_run(&r->s);
    cr_assert_str_eq(r->s.status, "ok", "%s at %g m/s: %s", name, v, r->s.message);
}

static void t7_free(t7run *r)
{
    free(r->w.layer);
    free(r->w.vprev);
    for (int l = 0; l < r->w.nlayer; l++)
        free(r->w.tri[l]);
    ctd_solver_destroy(&r->s);
    ctd_model_destroy(&r->m);
    ctd_scene_free(r->sc);
}

/* ---- 9a. No crossing at any speed, and the kinematic step ---------------------------- */

/*
 * The two-layer fold (type7_fold.yaml), top layer thrown at 5 to 300 m/s
 * onto the clamped bottom layer. At every cycle of every run no flat node
 * of one layer is at or beyond the other layer's mid-surface (height
 * field, our own test). The interface's kinematic step takes over from the
 * shell's step above an impact speed we find (the lowest swept speed at
 * which it is the smallest limit at some cycle); beyond it the step
 * shrinks with the speed, and the kinematic step equals our own
 * distance / (2 x approach speed) of the top layer over the clamped
 * bottom. After each impact the top layer springs back: TYPE7's stored
 * energy returns to 0.
 */
Test(validation_type7, fold_speed_sweep)
{
    const double speeds[] = {5, 10, 20, 50, 100, 110, 120, 130, 140, 150, 200, 250, 300};
    const int ns = (int)(sizeof speeds / sizeof speeds[0]);
    FILE *f = ctv_csv("extreme_type7_fold_sweep", "v,sep_min_over_g,dt_min_over_dt_first,"
                                          "kinematic_cycles,e7_max,energy_error");
    FILE *fd = ctv_csv("extreme_type7_fold_dt", "t_us,dt_100,dt_200,dt_300,sep_100,sep_200,sep_300");
    double onset = -1, dtr_prev = 2, worst_ratio = 0, worst_err = 0;
    double dt_first = 0, dt_min300 = 0, sep300 = 0;
    for (int k = 0; k < ns; k++) {
        t7run r;
        double v = speeds[k];
        int col = v == 100 ? 0 : v == 200 ? 1 : v == 300 ? 2 : -1;
        t7_run(&r, "type7_fold.yaml", v, 2.5e-3 / v + 1.5e-4, col >= 0 ? fd : NULL, col);
        watch *w = &r.w;
        cr_assert(!w->crossed && w->sep_min[0] > 0,
                  "%g m/s: a node crossed the facing layer (separation %g)", v, w->sep_min[0]);
        cr_assert(w->e7_max > 0, "%g m/s: no contact", v);
        cr_assert(w->e7_end == 0, "%g m/s: the fold did not open (%g J stored)", v, w->e7_end);
        double err = fabs(r.s.e.error);
        cr_assert(err <= 0.02, "%g m/s: energy error %g", v, err);
        double dtr = w->dt_min / w->dt_first;
        if (w->kin_cycles > 0) {
            if (onset < 0)
                onset = v;
            /* Our own kinematic step of the top layer: the same number. */
            worst_ratio = fmax(worst_ratio, fabs(w->ratio_kin_est - 1));
            cr_assert(fabs(w->ratio_kin_est - 1) <= CTT_TOL(1e-9, 1e-3),
                      "%g m/s: dt_kin %g against our %g", v, w->dt_kin_min,
                      w->dt_kin_min / w->ratio_kin_est);
        }
        if (onset > 0 && v >= 150) {
            /* Beyond the onset the step shrinks with the speed. */
            cr_assert(dtr < dtr_prev, "%g m/s: dt_min / dt_first %g after %g", v, dtr,
                      dtr_prev);
            dtr_prev = dtr;
        }
        worst_err = fmax(worst_err, err);
        if (v == 300) {
            dt_first = w->dt_first;
            dt_min300 = w->dt_min;
            sep300 = w->sep_min[0] / w->gap;
        }
        ctv_row(f, 6, v, w->sep_min[0] / w->gap, dtr, (double)w->kin_cycles, w->e7_max, err);
        t7_free(&r);
    }
    if (f)
        fclose(f);
    if (fd)
        fclose(fd);
    /* The kinematic step does not bite at 50 m/s and does by 200 m/s. */
    cr_assert(onset > 50 && onset <= 200, "kinematic onset at %g m/s", onset);
    cr_assert(dt_min300 < 0.1 * dt_first, "at 300 m/s the step only fell to %g of %g",
              dt_min300, dt_first);
    ctv_plot("extreme_type7_fold_sweep", "TYPE7 fold: closest approach and smallest step against speed",
             "impact speed (m/s)", "ratio",
             "1,2,linespoints,smallest separation / gap (> 0: never crossed);"
             "1,3,linespoints,smallest step / step before impact",
             "logy");
    ctv_plot("extreme_type7_fold_dt", "TYPE7 fold: the time step through the impact",
             "time (us)", "time step (ns)",
             "1,2,points,100 m/s;1,3,points,200 m/s;1,4,points,300 m/s", "logy");
    const char *note = "2-layer steel fold (8x4 shells of 5 mm, t = 1 mm, 4 mm apart), "
                       "bottom clamped, Stfac 0.01, VisS 0, dt_scale 0.9, 13 speeds 5..300 m/s";
    ctv_result("9. TYPE7 fold", "nodes crossing the facing mid-surface (all speeds, cycles)",
               0, 0, 0, note);
    ctv_result("9. TYPE7 fold", "smallest separation / gap at 300 m/s (> 0)", sep300, 0, 0,
               note);
    ctv_result("9. TYPE7 fold", "speed at which the kinematic step controls (m/s)", onset, 0,
               0, "lowest swept speed with dt_kin the smallest limit at some cycle");
    ctv_result("9. TYPE7 fold", "dt_kin vs our D/(2 |v|), worst rel. error", worst_ratio, 0,
               CTT_TOL(1e-9, 1e-3), note);
    ctv_result("9. TYPE7 fold", "smallest step / step before impact at 300 m/s",
               dt_min300 / dt_first, 0, 0, note);
    ctv_result("9. TYPE7 fold", "largest final energy error over the sweep", worst_err, 0,
               0.02, note);
}

/* ---- 9b. Both faces of a pinched layer ------------------------------------------------- */

/*
 * Three layers (type7_pinch.yaml): the middle and top ones thrown at
 * 30 m/s; the middle one lands on the clamped bottom one and the top one
 * lands on it. At some cycle the middle layer must be within the gap of
 * both neighbours at once (the TYPE7 law pushing on both of its faces),
 * at no cycle may a flat node reach a facing mid-surface, and afterwards
 * the layers spring apart (no stored energy, every separation above the
 * gap).
 */
Test(validation_type7, pinched_both_faces)
{
    FILE *f = ctv_csv("extreme_type7_pinch", "t_us,sep_mid_bottom,sep_top_mid,e7");
    t7run r;
    t7_run(&r, "type7_pinch.yaml", 0, 0, f, -1);
    if (f)
        fclose(f);
    watch *w = &r.w;
    cr_assert(!w->crossed && w->sep_min[0] > 0 && w->sep_min[1] > 0,
              "a node crossed: separations %g %g", w->sep_min[0], w->sep_min[1]);
    cr_assert(w->both_min < w->gap, "never in contact on both faces at once (%g)",
              w->both_min / w->gap);
    cr_assert(w->e7_end == 0 && w->sep_last[0] > w->gap && w->sep_last[1] > w->gap,
              "the layers did not come apart: %g J, %g, %g", w->e7_end, w->sep_last[0],
              w->sep_last[1]);
    cr_assert(fabs(r.s.e.error) <= 0.01, "energy error %g", r.s.e.error);
    ctv_plot("extreme_type7_pinch", "TYPE7: a middle layer pinched between two others",
             "time (us)", "separation / gap; TYPE7 energy (J)",
             "1,2,lines,middle over bottom;1,3,lines,top over middle;1,4,dashed,TYPE7 energy (J)",
             "");
    const char *note = "3-layer steel fold, bottom clamped, middle and top at 30 m/s, "
                       "Stfac 0.01, VisS 0";
    ctv_result("9. TYPE7 pinch", "smallest separation / gap, middle over bottom (> 0)",
               w->sep_min[0] / w->gap, 0, 0, note);
    ctv_result("9. TYPE7 pinch", "smallest separation / gap, top over middle (> 0)",
               w->sep_min[1] / w->gap, 0, 0, note);
    ctv_result("9. TYPE7 pinch", "both faces at once: max of the two, smallest (< 1)",
               w->both_min / w->gap, 0, 0, note);
    ctv_result("9. TYPE7 pinch", "final energy error", fabs(r.s.e.error), 0, 0.01, note);
    t7_free(&r);
}

/* ---- 9c. The fold opens again ------------------------------------------------------------ */

/*
 * The two-layer fold squeezed shut by a rigid block driven down at 3 m/s
 * (type7_squeeze.yaml) until its contact stops at Tstop = 1.35 ms: the
 * layers are then well inside the gap with TYPE7 energy stored. Once the
 * load is gone the fold must open: TYPE7's stored energy back to exactly
 * 0 within 100 us, the layers more than two gaps apart afterwards and
 * apart at the end, and no node may cross at any cycle, squeezed or not.
 * (The released top layer vibrates freely and touches the bottom one
 * again briefly near 2.64 ms: a new, elastic impact, shown in the plot.)
 */
Test(validation_type7, squeeze_and_release)
{
    FILE *f = ctv_csv("extreme_type7_squeeze", "t_us,sep,unused,e7");
    t7run r;
    t7_run(&r, "type7_squeeze.yaml", 0, 0, f, -1);
    if (f)
        fclose(f);
    watch *w = &r.w;
    cr_assert(!w->crossed && w->sep_min[0] > 0, "a node crossed: separation %g",
              w->sep_min[0]);
    cr_assert(w->e7_release > 0 && w->sep_release < 0.6 * w->gap,
              "not squeezed at the release: %g J, separation %g g", w->e7_release,
              w->sep_release / w->gap);
    cr_assert(w->t_open > w->t_release && w->t_open - w->t_release < 1e-4,
              "the fold did not open within 100 us of the release (%g)", w->t_open);
    cr_assert(w->sep_max_after > 2 * w->gap, "the layers came apart by only %g g",
              w->sep_max_after / w->gap);
    cr_assert(w->e7_end == 0 && w->sep_last[0] > w->gap,
              "closed at the end: %g J, separation %g g", w->e7_end, w->sep_last[0] / w->gap);
    cr_assert(fabs(r.s.e.error) <= 0.02, "energy error %g", r.s.e.error);
    ctv_plot("extreme_type7_squeeze", "TYPE7 fold squeezed by a driven block, released at 1.35 ms",
             "time (us)", "separation / gap; TYPE7 energy (J)",
             "1,2,lines,layer separation / gap;1,4,dashed,TYPE7 stored energy (J)", "");
    const char *note = "2-layer steel fold, block driven at 3 m/s (TYPE24, VisS 0.5) until "
                       "Tstop 1.35 ms; TYPE7 Stfac 0.01, VisS 0";
    ctv_result("9. TYPE7 squeeze", "separation / gap at the release", w->sep_release / w->gap,
               0, 0, note);
    ctv_result("9. TYPE7 squeeze", "TYPE7 energy at the release (J)", w->e7_release, 0, 0,
               note);
    ctv_result("9. TYPE7 squeeze", "time from release to open (us)",
               (w->t_open - w->t_release) * 1e6, 0, 0, note);
    ctv_result("9. TYPE7 squeeze", "TYPE7 energy at the end (J)", w->e7_end, 0, 1e-300, note);
    ctv_result("9. TYPE7 squeeze", "largest separation / gap after the release",
               w->sep_max_after / w->gap, 0, 0, note);
    ctv_result("9. TYPE7 squeeze", "separation / gap at the end (> 1)", w->sep_last[0] / w->gap,
               0, 0, note);
    ctv_result("9. TYPE7 squeeze", "final energy error", fabs(r.s.e.error), 0, 0.02, note);
    t7_free(&r);
}
