/*
 * scene_validate_iface.c -- the checks of a scene's contact interfaces:
 * type, sides, gaps, stiffness, friction and their ranges (scene_validate.c
 * has the rest).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ct_internal.h"
#include "errf.h"
#include "meshgen.h"
#include "scene_validate_internal.h"

/* ---- Interfaces ------------------------------------------------------------ */

void cti_vcheck_interface(vctx *v, unsigned i, ctd_scene_interface *f)
{
    char b[64];
    snprintf(b, sizeof b, "interfaces[%u]", i);
    f->line = cti_path_line(v->e->root, b);
    snprintf(f->label, sizeof f->label, "%s", f->name ? f->name : "");
    if (!f->name)
        snprintf(f->label, sizeof f->label, "if%u", i);
    const int64_t t = f->type;
    if (t != 3 && t != 5 && t != 6 && t != 7 && t != 11 && t != 24) {
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.type", b),
                "expected one of 3, 5, 6, 7, 11, 24, got %lld", (long long)t);
        return;
    }
    /* Selections: main is a surface; secondary per type. */
    cti_vsel(v, cti_vpath(v, "%s.main", b), f->main, SEL_SURF);
    f->self = f->secondary == NULL;
    if (f->self && (t == 3 || t == 5 || t == 6))
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.secondary", b),
                "required field missing for type %lld (expected a %s selection)", (long long)t,
                t == 5 ? "node" : "surface");
    else if (f->secondary)
        cti_vsel(v, cti_vpath(v, "%s.secondary", b), f->secondary,
                 (t == 3 || t == 6 || t == 11) ? SEL_SURF
                 : (t == 5 || t == 7)          ? SEL_NODES
                                               : SEL_NODES | SEL_SURF);
    if (f->grnd_IDs && t != 24)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.grnd_IDs", b), "only used by type 24");
    else if (f->grnd_IDs)
        cti_vsel(v, cti_vpath(v, "%s.grnd_IDs", b), f->grnd_IDs, SEL_NODES);
    /* TYPE6: both sides on rigid parts, and the force curve. */
    if (t == 6) {
        ctd_scene_sel *side[2] = {f->main, f->secondary};
        for (int s = 0; s < 2; s++) {
            if (!side[s])
                continue;
            int64_t pid = side[s]->part          ? side[s]->part
                          : side[s]->parts_count ? side[s]->parts[0]
                                                 : 0;
            const ctd_scene_part *p = pid ? ctd_scene_part_by_id(v->sc, pid) : NULL;
            if (p && p->element != CTD_ELEM_RIGID)
                cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.%s", b, s ? "secondary" : "main"),
                        "part %lld has element %s; type 6 expects a part with element rigid",
                        (long long)pid, p->element_name);
        }
        if (!f->curve)
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.curve", b),
                    "required field missing for type 6 (expected [[p0, F0], [p1, F1], ...])");
    } else if (f->curve) {
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.curve", b), "only used by type 6");
    }
    if (f->curve && f->curve_count < 2)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.curve", b),
                "expected at least 2 points, got %u", f->curve_count);
    for (unsigned k = 0; f->curve && k < f->curve_count; k++) {
        cti_vnum(v, cti_vpath(v, "%s.curve[%u][0]", b, k), f->curve[k][0], 0, 0, INFINITY, 0,
                 "a penetration >= 0");
        cti_vnum(v, cti_vpath(v, "%s.curve[%u][1]", b, k), f->curve[k][1], 0, 0, INFINITY, 0,
                 "a force >= 0");
        if (k > 0 && !(f->curve[k][0] > f->curve[k - 1][0]))
            cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.curve[%u][0]", b, k),
                    "expected penetrations in strictly ascending order, got %s after %s",
                    ctd_num(f->curve[k][0]).s, ctd_num(f->curve[k - 1][0]).s);
    }
    /* Search. */
    static const char *const search_names[] = {"direct", "topological", "bucket", "bsp"};
    if (f->search_name)
        f->search = cti_venum(v, cti_vpath(v, "%s.search", b), f->search_name, search_names, 4);
    else
        f->search = (t == 3 || t == 5) ? CT_SEARCH_TOPO : CT_SEARCH_BUCKET;
    if (f->search_name && f->search == CT_SEARCH_TOPO && (t == 7 || (t == 24 && f->self)))
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.search", b),
                "topological cannot find self contact (a node's closest main node is itself): "
                "expected direct, bucket or bsp for type %lld%s",
                (long long)t, t == 24 ? " on one surface" : "");
    else if (f->search_name && t == 11 && f->search != CT_SEARCH_DIRECT &&
             f->search != CT_SEARCH_BUCKET)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.search", b),
                "type 11's edge search is direct or bucket, got %s", f->search_name);
    /* The pressure's area (the secondary nodes' areas are checked with the
     * model, ctd_interfaces_build). */
    static const char *const parea_names[] = {"main", "secondary"};
    f->pressure_area = 0;
    if (f->pressure_area_name) {
        const char *pa = cti_vpath(v, "%s.pressure_area", b);
        f->pressure_area = cti_venum(v, pa, f->pressure_area_name, parea_names, 2);
        if (t == 11 && f->pressure_area == 1)
            cti_err(v->e, CT_ERR_ARG, 0, pa,
                    "expected main for type 11 (edge to edge: its nodes have no area), got "
                    "secondary");
    }
    /* Defaults of the card fields that are not zero. */
    if (!cti_vhas(v, cti_vpath(v, "%s.Stfac", b)))
        f->Stfac = (t == 3 || t == 5 || t == 6) ? 0.2 : 1.0;
    if (!cti_vhas(v, cti_vpath(v, "%s.VisS", b)))
        f->VisS = (t == 7 || t == 11) ? 0.05 : t == 24 ? 1.0 : 0.0;
    /* Integer flags. */
    if (!(f->Istf >= 0 && f->Istf <= 5) && f->Istf != 1000)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Istf", b),
                "expected one of 0, 1, 2, 3, 4, 5, 1000, got %lld", (long long)f->Istf);
    if (f->Igap0 < 0 || f->Igap0 > 1)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Igap0", b), "expected 0 or 1, got %lld",
                (long long)f->Igap0);
    if (f->Ipen0 < 0 || f->Ipen0 > 1)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Ipen0", b), "expected 0 or 1, got %lld",
                (long long)f->Ipen0);
    if (f->Inacti < -1 || (f->Inacti > 6 && f->Inacti != 1000) || f->Inacti == 4)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Inacti", b),
                "expected one of -1, 0, 1, 2, 3, 5, 6, 1000, got %lld", (long long)f->Inacti);
    if (f->Ifric < 0 || f->Ifric > 4)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Ifric", b),
                "expected an integer in 0..4, got %lld", (long long)f->Ifric);
    if (f->Irem_gap < 0 || f->Irem_gap > 2)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Irem_gap", b),
                "expected an integer in 0..2, got %lld", (long long)f->Irem_gap);
    else if (f->Irem_gap == 2 && t != 7 && t != 11 && !(t == 24 && f->self))
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Irem_gap", b),
                "2 is only used by self contact: types 7, 11, and 24 without secondary, got "
                "type %lld%s",
                (long long)t, t == 24 ? " with a secondary side" : "");
    if (f->Ifiltr < 0 || f->Ifiltr > 3)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Ifiltr", b),
                "expected an integer in 0..3, got %lld", (long long)f->Ifiltr);
    /* Numbers. */
    cti_vnum(v, cti_vpath(v, "%s.Stfac", b), f->Stfac, 0, 1, INFINITY, 0, "a number > 0");
    cti_vnum(v, cti_vpath(v, "%s.Stmin", b), f->Stmin, 0, 0, INFINITY, 0, "a number >= 0");
    if (cti_vnum(v, cti_vpath(v, "%s.Stmax", b), f->Stmax, 0, 0, INFINITY, 0,
                 "a number >= 0 (0: no limit)") &&
        f->Stmax > 0 && f->Stmax < f->Stmin)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Stmax", b),
                "expected a number >= Stmin (%s), got %s", ctd_num(f->Stmin).s,
                ctd_num(f->Stmax).s);
    cti_vnum(v, cti_vpath(v, "%s.gap", b), f->gap, 0, 0, INFINITY, 0,
             "a number >= 0 (0: automatic)");
    cti_vnum(v, cti_vpath(v, "%s.Gap_max_s", b), f->Gap_max_s, 0, 0, INFINITY, 0, "a number >= 0");
    cti_vnum(v, cti_vpath(v, "%s.Gap_max_m", b), f->Gap_max_m, 0, 0, INFINITY, 0, "a number >= 0");
    cti_vnum(v, cti_vpath(v, "%s.Ipen_max", b), f->Ipen_max, 0, 0, INFINITY, 0, "a number >= 0");
    cti_vnum(v, cti_vpath(v, "%s.VisS", b), f->VisS, 0, 0, INFINITY, 0, "a number >= 0");
    /* The friction kernels refuse coefficients above CTI_HUGE
     * (ct_friction_check): bound them here so that `contact check` agrees
     * with `contact run` and the message names the field. */
    const double huge = (double)CTI_HUGE;
    char ex[2][64];
    snprintf(ex[0], sizeof ex[0], "a number in [0, %g]", huge);
    snprintf(ex[1], sizeof ex[1], "a number in [%g, %g]", -huge, huge);
    cti_vnum(v, cti_vpath(v, "%s.Fric", b), f->Fric, 0, 0, huge, 0, ex[0]);
    const double C[6] = {f->C1, f->C2, f->C3, f->C4, f->C5, f->C6};
    for (int k = 0; k < 6; k++)
        cti_vnum(v, cti_vpath(v, "%s.C%d", b, k + 1), C[k], -huge, 0, huge, 0, ex[1]);
    if (f->Ifric == 3 && !(f->C4 <= f->C2))
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.C4", b),
                "Renard friction (Ifric 3) expects C4 = mu_min <= C2 = mu_d, got C4 = %s, "
                "C2 = %s", ctd_num(f->C4).s, ctd_num(f->C2).s);
    if (f->Ifric == 3 && !(f->C5 > 0 && f->C6 > f->C5))
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.C5", b),
                "Renard friction (Ifric 3) expects 0 < C5 < C6, got C5 = %s, C6 = %s",
                ctd_num(f->C5).s, ctd_num(f->C6).s);
    if (f->Ifric == 4 && f->C2 < 0)
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.C2", b),
                "Ifric 4 expects a decay rate C2 >= 0, got %s", ctd_num(f->C2).s);
    const char *px = cti_vpath(v, "%s.Xfreq", b);
    char pxs[96];
    snprintf(pxs, sizeof pxs, "%s", px);
    if (f->Ifiltr == 1)
        cti_vnum(v, pxs, f->Xfreq, 0, 1, 1, 0, "a number in (0, 1] for Ifiltr 1");
    else if (f->Ifiltr == 2)
        cti_vnum(v, pxs, f->Xfreq, 6.283185307179586, 0, INFINITY, 0,
                 "a number >= 2 pi for Ifiltr 2");
    else if (f->Ifiltr == 3)
        cti_vnum(v, pxs, f->Xfreq, 0, 1, INFINITY, 0, "a number > 0 for Ifiltr 3");
    else
        cti_vnum(v, pxs, f->Xfreq, -INFINITY, 0, INFINITY, 0, "a finite number");
    cti_vnum(v, cti_vpath(v, "%s.Tstart", b), f->Tstart, 0, 0, INFINITY, 0, "a time >= 0");
    cti_vnum(v, cti_vpath(v, "%s.margin", b), f->margin, 0, 0, INFINITY, 1,
             "a length >= 0 (0: 0.2 times the mean main edge length)");
    if (cti_vnum(v, cti_vpath(v, "%s.Tstop", b), f->Tstop, 0, 0, INFINITY, 0,
                 "a time >= 0 (0: never)") &&
        f->Tstop > 0 && !(f->Tstop > f->Tstart))
        cti_err(v->e, CT_ERR_ARG, 0, cti_vpath(v, "%s.Tstop", b),
                "expected a time > Tstart (%s), got %s", ctd_num(f->Tstart).s,
                ctd_num(f->Tstop).s);
}
