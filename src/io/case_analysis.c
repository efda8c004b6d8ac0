/*
 * analysis of a case: the time integration, Newton's options and the strength-reduction search,
 * with the checks that tie them to the method and the materials.
 */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const srf_criteria[] = {"convergence", "displacement", NULL};
static const char *const density_updates[] = {"deformation", "positions", NULL};
static const char *const analysis_types[] = {"explicit", "implicit", "quasi_static", NULL};
static const char *const schemes[] = {"musl", "usl", "usf", "newmark_pc", NULL};
static const char *const fbar_modes[] = {"none", "cell", NULL};
static const char *const apart_measures[] = {"point", "cell", NULL};
static const char *const transfers[] = {"flip", "apic", "xpic", NULL};

/*
 * analysis.strength_reduction. A trial is judged by whether its load steps converge, so the analysis
 * must come to rest under gravity: quasi-static, or explicit with damping (dynamic relaxation), where
 * only the displacement can tell a sliding slope from one at rest.
 */
static int parse_strength_reduction(pm_case *c, json_t *sr)
{
    pm_srf_opts *o = &c->analysis.strength_reduction;
    if (!sr)
        return PM_OK;
    const jr_ctx ac = {c->file, "analysis"};
    jr_ctx cx = {c->file, "analysis.strength_reduction"};
    pm_check(jr_expect_object(&ac, "strength_reduction", sr));
    pm_check(jr_only_keys(&cx, sr, pm_case_keys(PM_KEYS_STRENGTH_REDUCTION)));
    const int explicit = c->analysis.type == PM_ANALYSIS_EXPLICIT;
    if (c->analysis.type == PM_ANALYSIS_IMPLICIT)
        return pm_case_fail(c->file, "analysis.strength_reduction",
                            "needs analysis.type \"quasi_static\" (or \"explicit\" with damping > 0 as dynamic "
                            "relaxation); got \"implicit\", whose inertia keeps a failing slope from showing as "
                            "non-convergence",
                            NULL);
    if (explicit && !(c->analysis.damping > 0))
        return pm_error_set(PM_EINPUT,
                            "%s: analysis.strength_reduction: with analysis.type \"explicit\" the search needs "
                            "analysis.damping > 0 (dynamic relaxation to rest); got damping = %g",
                            c->file, c->analysis.damping);
    o->enabled = 1;
    pm_check(jr_number(&cx, sr, "min", 0, 0.5, &o->min));
    pm_check(jr_range(&cx, "min", o->min, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, sr, "max", 0, 3.0, &o->max));
    pm_check(jr_range(&cx, "max", o->max, 0, 1, INFINITY, 0));
    if (!(o->min < o->max))
        return pm_error_set(PM_EINPUT, "%s: analysis.strength_reduction: min = %g must be below max = %g", c->file,
                            o->min, o->max);
    pm_check(jr_number(&cx, sr, "tolerance", 0, 0.01, &o->tolerance));
    /* factors name their output directories to four decimals */
    pm_check(jr_range(&cx, "tolerance", o->tolerance, 1e-3, 0, o->max - o->min, 0));
    int v;
    pm_check(jr_enum(&cx, sr, "criterion", 0, srf_criteria, explicit ? PM_SRF_DISPLACEMENT : PM_SRF_CONVERGENCE,
                     &v));
    o->criterion = (pm_srf_criterion)v;
    if (explicit && o->criterion == PM_SRF_CONVERGENCE)
        return pm_case_fail(c->file, "analysis.strength_reduction.criterion",
                            "got \"convergence\", but an explicit run has no Newton iterations to converge; use "
                            "\"displacement\", or analysis.type \"quasi_static\"",
                            NULL);
    if (json_object_get(sr, "displacement_ratio") && o->criterion != PM_SRF_DISPLACEMENT)
        return pm_case_fail(c->file, "analysis.strength_reduction.displacement_ratio",
                            "applies to criterion \"displacement\" only; remove it or set the criterion", NULL);
    pm_check(jr_number(&cx, sr, "displacement_ratio", 0, 10.0, &o->displacement_ratio));
    pm_check(jr_range(&cx, "displacement_ratio", o->displacement_ratio, 1, 1, INFINITY, 0));
    return PM_OK;
}

/* The search lowers the strength of Mohr-Coulomb and Drucker-Prager materials; without one it has
 * nothing to do. */
int pm_case_check_strength_reduction(const pm_case *c)
{
    if (!c->analysis.strength_reduction.enabled)
        return PM_OK;
    char list[512] = "";
    size_t used = 0;
    for (size_t k = 0; k < c->n_materials; k++) {
        const char *model = c->materials[k].ops->name;
        if (c->materials[k].ops->reduce_strength)
            return PM_OK;
        if (used + 100 < sizeof list)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s\"%s\" is %s", k ? ", " : "",
                                     c->materials[k].name, model);
    }
    return pm_error_set(PM_EINPUT,
                        "%s: analysis.strength_reduction: no material has a strength to reduce (%s); the search "
                        "lowers the cohesion and friction of mohr_coulomb and drucker_prager materials",
                        c->file, list);
}

int pm_case_parse_analysis(pm_case *c, json_t *a)
{
    jr_ctx cx = {c->file, "analysis"};
    pm_check(jr_expect_object(&cx, "", a));
    pm_check(jr_only_keys(&cx, a, pm_case_keys(PM_KEYS_ANALYSIS)));
    int v;
    pm_check(jr_enum(&cx, a, "type", JR_REQUIRED, analysis_types, 0, &v));
    c->analysis.type = (pm_analysis_type)v;
    if (json_object_get(a, "scheme") && c->analysis.type != PM_ANALYSIS_EXPLICIT)
        return pm_case_fail(c->file, "analysis.scheme",
                            "applies to explicit analyses only; remove it or set type to explicit", NULL);
    pm_check(jr_enum(&cx, a, "scheme", 0, schemes, PM_SCHEME_MUSL, &v));
    c->analysis.scheme = (pm_scheme)v;
    pm_check(jr_number(&cx, a, "end_time", JR_REQUIRED, 0, &c->analysis.end_time));
    pm_check(jr_range(&cx, "end_time", c->analysis.end_time, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, a, "dt", 0, 0, &c->analysis.dt));
    if (json_object_get(a, "dt"))
        pm_check(jr_range(&cx, "dt", c->analysis.dt, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, a, "cfl", 0, 0.2, &c->analysis.cfl));
    pm_check(jr_range(&cx, "cfl", c->analysis.cfl, 0, 1, 1, 0));
    const double zero[PM_DIM] = {0, 0};
    pm_check(jr_vec2(&cx, a, "gravity", 0, zero, c->analysis.gravity));
    pm_check(jr_number(&cx, a, "gravity_ramp_time", 0, 0, &c->analysis.gravity_ramp_time));
    pm_check(jr_range(&cx, "gravity_ramp_time", c->analysis.gravity_ramp_time, 0, 0, INFINITY, 0));
    pm_check(jr_number(&cx, a, "damping", 0, 0, &c->analysis.damping));
    pm_check(jr_range(&cx, "damping", c->analysis.damping, 0, 0, 1, 0));
    double flip;
    pm_check(jr_number(&cx, a, "flip", 0, 1.0, &flip));
    pm_check(jr_range(&cx, "flip", flip, 0, 0, 1, 0));
    c->analysis.pic = 1.0 - flip;
    pm_check(jr_enum(&cx, a, "density_update", 0, density_updates, 0, &v));
    c->analysis.density_from_positions = v;
    if (c->method != PM_METHOD_MPM && c->analysis.density_from_positions)
        return pm_error_set(PM_EINPUT,
                            "%s: analysis.density_update: \"positions\" needs the cells of method 'mpm'; with gmm "
                            "and rkpm use \"deformation\" (volume from det F)",
                            c->file);
    pm_check(jr_enum(&cx, a, "apart_measure", 0, apart_measures, 0, &c->analysis.apart_from_cell));
    if (json_object_get(a, "apart_measure") && !c->analysis.density_from_positions)
        return pm_case_fail(c->file, "analysis.apart_measure", "judges points apart by the density of the positions; "
                            "set density_update to \"positions\" or remove it", NULL);
    pm_check(jr_enum(&cx, a, "fbar", 0, fbar_modes, PM_FBAR_NONE, &v));
    c->analysis.fbar = (pm_fbar_mode)v;
    if (c->analysis.fbar != PM_FBAR_NONE && c->method != PM_METHOD_MPM)
        return pm_case_fail(c->file, "analysis.fbar",
                            "averages the volume change over background cells, which only method 'mpm' has; "
                            "use \"none\" with gmm and rkpm",
                            NULL);
    if (c->analysis.fbar != PM_FBAR_NONE && c->formulation == PM_PLANE_STRESS)
        return pm_case_fail(c->file, "analysis.fbar",
                            "plane stress leaves the thickness free, so nothing locks; use \"none\"", NULL);
    if (c->analysis.fbar != PM_FBAR_NONE && c->analysis.type != PM_ANALYSIS_EXPLICIT)
        return pm_case_fail(c->file, "analysis.fbar",
                            "is available in explicit analyses only so far; use \"none\" with implicit and "
                            "quasi_static",
                            NULL);
    /* below 1: a share of 1 would be no averaging at all, which "none" says */
    pm_check(jr_number(&cx, a, "fbar_own_share", 0, 0, &c->analysis.fbar_own_share));
    pm_check(jr_range(&cx, "fbar_own_share", c->analysis.fbar_own_share, 0, 0, 1, 1));
    if (json_object_get(a, "fbar_own_share") && c->analysis.fbar == PM_FBAR_NONE)
        return pm_case_fail(c->file, "analysis.fbar_own_share", "is a share of F-bar's averaging; set fbar to "
                            "\"cell\" or remove it", NULL);
    pm_check(jr_enum(&cx, a, "transfer", 0, transfers, PM_TRANSFER_FLIP, &v));
    c->analysis.transfer = (pm_transfer)v;
    if (c->analysis.transfer != PM_TRANSFER_FLIP) {
        const char *name = c->analysis.transfer == PM_TRANSFER_APIC ? "apic" : "xpic";
        /* both update the particles in MUSL's re-projection, on the fixed grid's nodes */
        if (c->analysis.type != PM_ANALYSIS_EXPLICIT || c->analysis.scheme != PM_SCHEME_MUSL ||
            c->method != PM_METHOD_MPM)
            return pm_error_set(PM_EINPUT,
                                "%s: analysis.transfer: \"%s\" needs method 'mpm', an explicit analysis and scheme "
                                "musl; use \"flip\"",
                                c->file, name);
        if (c->analysis.pic > 0)
            return pm_error_set(PM_EINPUT,
                                "%s: analysis.flip: blends FLIP with PIC; with transfer \"%s\" the update is its "
                                "own, so remove flip or set it to 1",
                                c->file, name);
    }
    long order;
    /* the series' alternating binomial sums lose round-off in proportion to 2^m: 2e-11 of a uniform
     * velocity at m = 20 (test_xpic), twice that for every order above */
    pm_check(jr_int(&cx, a, "xpic_order", 0, 5, 1, 20, &order));
    c->analysis.xpic_order = (int)order;
    if (json_object_get(a, "xpic_order") && c->analysis.transfer != PM_TRANSFER_XPIC)
        return pm_case_fail(c->file, "analysis.xpic_order", "is the order of transfer \"xpic\"; set transfer "
                            "to \"xpic\" or remove it", NULL);
    pm_check(jr_number(&cx, a, "max_steps", 0, 1e8, &c->analysis.max_steps));
    pm_check(jr_range(&cx, "max_steps", c->analysis.max_steps, 1, 0, 1e15, 0));
    long n;
    pm_check(jr_int(&cx, a, "load_steps", 0, 10, 1, 100000000, &n));
    c->analysis.load_steps = (int)n;
    pm_newton_opts *nw = &c->analysis.newton;
    nw->tolerance = 1e-8;
    nw->displacement_tolerance = 1e-8;
    nw->max_iterations = 25;
    nw->line_search = 1;
    nw->max_step_cuts = 8;
    json_t *jn = json_object_get(a, "newton");
    if (jn) {
        jr_ctx nc = {c->file, "analysis.newton"};
        pm_check(jr_expect_object(&cx, "newton", jn));
        pm_check(jr_only_keys(&nc, jn, pm_case_keys(PM_KEYS_NEWTON)));
        pm_check(jr_number(&nc, jn, "tolerance", 0, 1e-8, &nw->tolerance));
        pm_check(jr_range(&nc, "tolerance", nw->tolerance, 0, 1, 1, 1));
        pm_check(jr_number(&nc, jn, "displacement_tolerance", 0, 1e-8, &nw->displacement_tolerance));
        pm_check(jr_range(&nc, "displacement_tolerance", nw->displacement_tolerance, 0, 1, 1, 1));
        pm_check(jr_int(&nc, jn, "max_iterations", 0, 25, 1, 10000, &n));
        nw->max_iterations = (int)n;
        pm_check(jr_bool(&nc, jn, "line_search", 0, 1, &nw->line_search));
        pm_check(jr_int(&nc, jn, "max_step_cuts", 0, 8, 0, 60, &n));
        nw->max_step_cuts = (int)n;
        pm_check(jr_number(&nc, jn, "absolute_tolerance", 0, 0, &nw->absolute_tolerance));
        if (json_object_get(jn, "absolute_tolerance"))
            pm_check(jr_range(&nc, "absolute_tolerance", nw->absolute_tolerance, 0, 1, INFINITY, 0));
    }
    return parse_strength_reduction(c, json_object_get(a, "strength_reduction"));
}
