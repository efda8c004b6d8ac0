/*
 * Case files (shared/design/INPUT.md) to pm_case. Every key is checked: unknown keys, wrong types,
 * out-of-range values and physical nonsense are errors naming the key path, the value and what is
 * allowed; JSON syntax errors name file:line:column. Counts that cannot fit in memory are refused
 * before anything is allocated.
 */
#include "pmech/case.h"

#include "io/json_read.h"
#include "io/material_read.h"
#include "pmech/approx.h"
#include "pmech/error.h"
#include "pmech/grid.h"

#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *const top_keys[] = {"title", "dimension", "formulation", "method", "shape_function", "lme_gamma",
                                       "support_radius", "max_condition", "analysis", "grid", "materials", "bodies",
                                       "boundary_conditions", "output", "probes", NULL};
static const char *const formulations[] = {"plane_strain", "plane_stress", "axisymmetric", NULL};
static const char *const methods[] = {"mpm", "gmm", "rkpm", NULL};
static const char *const analysis_keys[] = {"type", "scheme", "end_time", "dt", "cfl", "gravity",
                                            "gravity_ramp_time", "damping", "newton", "load_steps",
                                            "density_update", "strength_reduction", NULL};
static const char *const srf_keys[] = {"min", "max", "tolerance", "criterion", "displacement_ratio", NULL};
static const char *const srf_criteria[] = {"convergence", "displacement", NULL};
static const char *const density_updates[] = {"deformation", "positions", NULL};
static const char *const analysis_types[] = {"explicit", "implicit", "quasi_static", NULL};
static const char *const schemes[] = {"musl", "usl", "usf", "newmark_pc", NULL};
static const char *const newton_keys[] = {"tolerance", "displacement_tolerance", "max_iterations", "line_search",
                                          "max_step_cuts", NULL};
static const char *const grid_types[] = {"rectangle", "gmsh", NULL};
static const char *const rect_keys[] = {"type", "origin", "size", "cells", "element", NULL};
static const char *const gmsh_keys[] = {"type", "file", NULL};
static const char *const elements[] = {"quad4", "tri3", NULL};
static const char *const body_keys[] = {"name", "material", "shape", "particles_per_cell", "velocity",
                                        "initial_stress", "k0", "surface_y", NULL};
static const char *const shape_types[] = {"rectangle", "polygon", "circle", "gmsh_group", NULL};
static const char *const bc_keys[] = {"type", "boundary", "directions", "value", "coefficient", "until", NULL};
static const char *const bc_types[] = {"fixed", "velocity", "friction", NULL};
static const char *const probe_keys[] = {"name", "quantity", "point", "body", NULL};
static const char *const quantities[] = {"position", "displacement", "velocity", "stress", "plastic_strain", NULL};
static const char *const output_keys[] = {"directory", "interval", "probe_interval", "pictures", NULL};
static const char *const picture_fields[] = {"body", "speed", "pressure", "plastic_strain", "syy", "displacement",
                                             NULL};

static int fail(const char *file, const char *path, const char *fmt, const char *detail)
{
    return pm_error_set(PM_EINPUT, "%s: %s: %s%s", file, path, fmt, detail ? detail : "");
}

/* Grid kinds for `mpm`, cloud kinds for `gmm` (mls, lme) and `rkpm` (rk_cubic); the default follows
 * the method: linear, mls, rk_cubic. */
static int parse_shape_function(pm_case *c, const jr_ctx *cx, json_t *root)
{
    static const char *const cloud_kinds[] = {"mls", "rk_cubic", NULL};
    static const char *const gmm_kinds[] = {"mls", "lme", NULL};
    static const char *const rkpm_kinds[] = {"rk_cubic", NULL};
    const char *all[16];
    int n = 0;
    for (const char *const *k = pm_approx_names(); *k && n < 12; k++)
        all[n++] = *k;
    for (const char *const *k = cloud_kinds; *k; k++)
        all[n++] = *k;
    all[n] = NULL;
    const char *def = c->method == PM_METHOD_GMM ? "mls" : c->method == PM_METHOD_RKPM ? "rk_cubic" : "linear";
    int v, d = 0;
    while (all[d] && strcmp(all[d], def) != 0)
        d++;
    pm_check(jr_enum(cx, root, "shape_function", 0, all, d, &v));
    snprintf(c->shape_function, sizeof c->shape_function, "%s", all[v]);
    const char *const *ok = c->method == PM_METHOD_GMM ? gmm_kinds : c->method == PM_METHOD_RKPM ? rkpm_kinds
                                                                                                 : pm_approx_names();
    for (const char *const *k = ok; *k; k++)
        if (strcmp(*k, c->shape_function) == 0)
            return PM_OK;
    char list[256] = "";
    for (const char *const *k = ok; *k; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k == ok ? "" : ", ", *k);
    return pm_error_set(PM_EINPUT, "%s: shape_function: \"%s\" does not go with method '%s' (allowed: %s)", c->file,
                        c->shape_function, c->method == PM_METHOD_GMM ? "gmm" : c->method == PM_METHOD_RKPM ? "rkpm" : "mpm",
                        list);
}

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
    pm_check(jr_only_keys(&cx, sr, srf_keys));
    const int explicit = c->analysis.type == PM_ANALYSIS_EXPLICIT;
    if (c->analysis.type == PM_ANALYSIS_IMPLICIT)
        return fail(c->file, "analysis.strength_reduction",
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
        return fail(c->file, "analysis.strength_reduction.criterion",
                    "got \"convergence\", but an explicit run has no Newton iterations to converge; use "
                    "\"displacement\", or analysis.type \"quasi_static\"",
                    NULL);
    if (json_object_get(sr, "displacement_ratio") && o->criterion != PM_SRF_DISPLACEMENT)
        return fail(c->file, "analysis.strength_reduction.displacement_ratio",
                    "applies to criterion \"displacement\" only; remove it or set the criterion", NULL);
    pm_check(jr_number(&cx, sr, "displacement_ratio", 0, 10.0, &o->displacement_ratio));
    pm_check(jr_range(&cx, "displacement_ratio", o->displacement_ratio, 1, 1, INFINITY, 0));
    return PM_OK;
}

/* The search lowers the strength of Mohr-Coulomb and Drucker-Prager materials; without one it has
 * nothing to do. */
static int check_strength_reduction(const pm_case *c)
{
    if (!c->analysis.strength_reduction.enabled)
        return PM_OK;
    char list[512] = "";
    size_t used = 0;
    for (size_t k = 0; k < c->n_materials; k++) {
        const char *model = c->materials[k].ops->name;
        if (!strcmp(model, "mohr_coulomb") || !strcmp(model, "drucker_prager"))
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

static int parse_analysis(pm_case *c, json_t *a)
{
    jr_ctx cx = {c->file, "analysis"};
    pm_check(jr_expect_object(&cx, "", a));
    pm_check(jr_only_keys(&cx, a, analysis_keys));
    int v;
    pm_check(jr_enum(&cx, a, "type", JR_REQUIRED, analysis_types, 0, &v));
    c->analysis.type = (pm_analysis_type)v;
    if (json_object_get(a, "scheme") && c->analysis.type != PM_ANALYSIS_EXPLICIT)
        return fail(c->file, "analysis.scheme", "applies to explicit analyses only; remove it or set type to explicit",
                    NULL);
    pm_check(jr_enum(&cx, a, "scheme", 0, schemes, PM_SCHEME_MUSL, &v));
    c->analysis.scheme = (pm_scheme)v;
    pm_check(jr_number(&cx, a, "end_time", JR_REQUIRED, 0, &c->analysis.end_time));
    pm_check(jr_range(&cx, "end_time", c->analysis.end_time, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, a, "dt", 0, 0, &c->analysis.dt));
    if (json_object_get(a, "dt"))
        pm_check(jr_range(&cx, "dt", c->analysis.dt, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, a, "cfl", 0, 0.2, &c->analysis.cfl));
    pm_check(jr_range(&cx, "cfl", c->analysis.cfl, 0, 1, 1, 0));
    const double zero[2] = {0, 0};
    pm_check(jr_vec2(&cx, a, "gravity", 0, zero, c->analysis.gravity));
    pm_check(jr_number(&cx, a, "gravity_ramp_time", 0, 0, &c->analysis.gravity_ramp_time));
    pm_check(jr_range(&cx, "gravity_ramp_time", c->analysis.gravity_ramp_time, 0, 0, INFINITY, 0));
    pm_check(jr_number(&cx, a, "damping", 0, 0, &c->analysis.damping));
    pm_check(jr_range(&cx, "damping", c->analysis.damping, 0, 0, 1, 0));
    pm_check(jr_enum(&cx, a, "density_update", 0, density_updates, 0, &v));
    c->analysis.density_from_positions = v;
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
        pm_check(jr_only_keys(&nc, jn, newton_keys));
        pm_check(jr_number(&nc, jn, "tolerance", 0, 1e-8, &nw->tolerance));
        pm_check(jr_range(&nc, "tolerance", nw->tolerance, 0, 1, 1, 1));
        pm_check(jr_number(&nc, jn, "displacement_tolerance", 0, 1e-8, &nw->displacement_tolerance));
        pm_check(jr_range(&nc, "displacement_tolerance", nw->displacement_tolerance, 0, 1, 1, 1));
        pm_check(jr_int(&nc, jn, "max_iterations", 0, 25, 1, 10000, &n));
        nw->max_iterations = (int)n;
        pm_check(jr_bool(&nc, jn, "line_search", 0, 1, &nw->line_search));
        pm_check(jr_int(&nc, jn, "max_step_cuts", 0, 8, 0, 60, &n));
        nw->max_step_cuts = (int)n;
    }
    return parse_strength_reduction(c, json_object_get(a, "strength_reduction"));
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

static int parse_grid(pm_case *c, json_t *g)
{
    jr_ctx cx = {c->file, "grid"};
    pm_check(jr_expect_object(&cx, "", g));
    int v;
    pm_check(jr_enum(&cx, g, "type", JR_REQUIRED, grid_types, 0, &v));
    c->grid.type = (pm_grid_type)v;
    if (c->grid.type == PM_GRID_GMSH) {
        pm_check(jr_only_keys(&cx, g, gmsh_keys));
        char rel[PM_PATH_MAX];
        pm_check(jr_string(&cx, g, "file", JR_REQUIRED, NULL, rel, sizeof rel));
        if (rel[0] == '/')
            snprintf(c->grid.file, sizeof c->grid.file, "%s", rel);
        else if ((size_t)snprintf(c->grid.file, sizeof c->grid.file, "%s/%s", c->dir, rel) >= sizeof c->grid.file)
            return fail(c->file, "grid.file", "path too long", NULL);
        if (!file_exists(c->grid.file))
            return pm_error_set(PM_EINPUT, "%s: grid.file: mesh file \"%s\" not found (resolved against the case's "
                                "directory)", c->file, c->grid.file);
        return PM_OK;
    }
    pm_check(jr_only_keys(&cx, g, rect_keys));
    const double zero[2] = {0, 0};
    pm_check(jr_vec2(&cx, g, "origin", 0, zero, c->grid.origin));
    pm_check(jr_vec2(&cx, g, "size", JR_REQUIRED, NULL, c->grid.size));
    for (int d = 0; d < 2; d++)
        if (!(c->grid.size[d] > 0))
            return pm_error_set(PM_EINPUT, "%s: grid.size: got [%g, %g]; allowed: two lengths > 0", c->file,
                                c->grid.size[0], c->grid.size[1]);
    json_t *cells = json_object_get(g, "cells");
    if (!cells)
        return fail(c->file, "grid.cells", "required key is missing", NULL);
    if (!json_is_array(cells) || json_array_size(cells) != 2 || !json_is_integer(json_array_get(cells, 0)) ||
        !json_is_integer(json_array_get(cells, 1)))
        return pm_error_set(PM_EINPUT, "%s: grid.cells: expected a list of two whole numbers, got %s", c->file,
                            jr_text(cells));
    for (int d = 0; d < 2; d++) {
        json_int_t n = json_integer_value(json_array_get(cells, d));
        if (n < 1 || n > 100000000)
            return pm_error_set(PM_EINPUT, "%s: grid.cells[%d]: got %lld; allowed: 1 to 100000000", c->file, d,
                                (long long)n);
        c->grid.cells[d] = (int)n;
    }
    pm_check(jr_enum(&cx, g, "element", 0, elements, PM_QUAD4, &v));
    c->grid.element = v;
    return PM_OK;
}

static int parse_materials(pm_case *c, json_t *ms)
{
    if (!ms)
        return fail(c->file, "materials", "required key is missing", NULL);
    if (!json_is_array(ms))
        return pm_error_set(PM_EINPUT, "%s: materials: expected a list of materials, got %s", c->file, jr_type(ms));
    if (json_array_size(ms) == 0)
        return fail(c->file, "materials", "the list is empty; give at least one material", NULL);
    c->n_materials = json_array_size(ms);
    c->materials = calloc(c->n_materials, sizeof *c->materials);
    if (!c->materials)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < c->n_materials; i++) {
        char path[64];
        jr_index(path, sizeof path, "materials", i);
        pm_check(pm_read_material(c->file, path, json_array_get(ms, i), 1, &c->materials[i]));
        for (size_t j = 0; j < i; j++)
            if (!strcmp(c->materials[j].name, c->materials[i].name))
                return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" is already the name of materials[%zu]", c->file,
                                    path, c->materials[i].name, j);
    }
    return PM_OK;
}

static int find_material(const pm_case *c, const char *path, const char *name, int *out)
{
    for (size_t k = 0; k < c->n_materials; k++)
        if (!strcmp(c->materials[k].name, name)) {
            *out = (int)k;
            return PM_OK;
        }
    char list[1024] = "";
    size_t used = 0;
    for (size_t k = 0; k < c->n_materials && used + 70 < sizeof list; k++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", k ? ", " : "", c->materials[k].name);
    return pm_error_set(PM_EINPUT, "%s: %s.material: no material is named \"%s\" (materials: %s)", c->file, path, name,
                        list);
}

static int parse_shape(pm_case *c, const char *path, json_t *sh, pm_shape *s)
{
    jr_ctx cx = {c->file, path};
    if (!json_is_object(sh))
        return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(sh));
    int v;
    pm_check(jr_enum(&cx, sh, "type", JR_REQUIRED, shape_types, 0, &v));
    s->type = (pm_shape_type)v;
    static const char *const rect[] = {"type", "min", "max", NULL}, *const poly[] = {"type", "points", NULL},
                             *const circ[] = {"type", "center", "radius", NULL}, *const grp[] = {"type", "name", NULL};
    switch (s->type) {
    case PM_SHAPE_RECTANGLE:
        pm_check(jr_only_keys(&cx, sh, rect));
        pm_check(jr_vec2(&cx, sh, "min", JR_REQUIRED, NULL, s->min));
        pm_check(jr_vec2(&cx, sh, "max", JR_REQUIRED, NULL, s->max));
        if (!(s->min[0] < s->max[0] && s->min[1] < s->max[1]))
            return pm_error_set(PM_EINPUT, "%s: %s: min [%g, %g] must be below and left of max [%g, %g]", c->file, path,
                                s->min[0], s->min[1], s->max[0], s->max[1]);
        break;
    case PM_SHAPE_CIRCLE:
        pm_check(jr_only_keys(&cx, sh, circ));
        pm_check(jr_vec2(&cx, sh, "center", JR_REQUIRED, NULL, s->center));
        pm_check(jr_number(&cx, sh, "radius", JR_REQUIRED, 0, &s->radius));
        pm_check(jr_range(&cx, "radius", s->radius, 0, 1, INFINITY, 0));
        break;
    case PM_SHAPE_POLYGON: {
        pm_check(jr_only_keys(&cx, sh, poly));
        json_t *pts = json_object_get(sh, "points");
        char pp[256];
        jr_join(pp, sizeof pp, path, "points");
        if (!pts)
            return fail(c->file, pp, "required key is missing", NULL);
        if (!json_is_array(pts) || json_array_size(pts) < 3 || json_array_size(pts) > 1000000)
            return pm_error_set(PM_EINPUT, "%s: %s: expected a list of at least 3 points [x, y], got %s", c->file, pp,
                                jr_text(pts));
        s->n_points = json_array_size(pts);
        s->points = malloc(2 * s->n_points * sizeof(double));
        if (!s->points)
            return pm_error_set(PM_ENOMEM, "out of memory");
        for (size_t k = 0; k < s->n_points; k++) {
            json_t *p = json_array_get(pts, k);
            json_t *x = json_array_get(p, 0), *y = json_array_get(p, 1);
            if (!json_is_array(p) || json_array_size(p) != 2 || !json_is_number(x) || !json_is_number(y) ||
                !isfinite(json_number_value(x)) || !isfinite(json_number_value(y)))
                return pm_error_set(PM_EINPUT, "%s: %s[%zu]: expected a point [x, y], got %s", c->file, pp, k,
                                    jr_text(p));
            s->points[2 * k] = json_number_value(x);
            s->points[2 * k + 1] = json_number_value(y);
        }
        break;
    }
    default:
        pm_check(jr_only_keys(&cx, sh, grp));
        pm_check(jr_string(&cx, sh, "name", JR_REQUIRED, NULL, s->group, sizeof s->group));
        if (c->grid.type != PM_GRID_GMSH)
            return fail(c->file, path, "type gmsh_group needs a grid of type gmsh", NULL);
        break;
    }
    return PM_OK;
}

static int parse_initial_stress(pm_case *c, const char *path, json_t *b, pm_case_body *body)
{
    jr_ctx cx = {c->file, path};
    json_t *is = json_object_get(b, "initial_stress");
    char ip[256];
    jr_join(ip, sizeof ip, path, "initial_stress");
    if (!is) {
        if (json_object_get(b, "k0") || json_object_get(b, "surface_y"))
            return fail(c->file, path, "k0 and surface_y go with \"initial_stress\": \"geostatic\"", NULL);
        return PM_OK;
    }
    if (json_is_string(is)) {
        if (strcmp(json_string_value(is), "geostatic") != 0)
            return pm_error_set(PM_EINPUT, "%s: %s: got \"%s\"; allowed: \"geostatic\" or a list [sxx, syy, szz, sxy]",
                                c->file, ip, json_string_value(is));
        body->stress0 = PM_STRESS0_GEOSTATIC;
        pm_check(jr_number(&cx, b, "k0", JR_REQUIRED, 0, &body->k0));
        pm_check(jr_range(&cx, "k0", body->k0, 0, 0, INFINITY, 0));
        pm_check(jr_number(&cx, b, "surface_y", JR_REQUIRED, 0, &body->surface_y));
        return PM_OK;
    }
    if (json_object_get(b, "k0") || json_object_get(b, "surface_y"))
        return fail(c->file, path, "k0 and surface_y go with \"initial_stress\": \"geostatic\"", NULL);
    body->stress0 = PM_STRESS0_CONSTANT;
    return jr_vecn(&cx, b, "initial_stress", 0, 4, body->stress0_value);
}

static void shape_box(const pm_shape *s, double lo[2], double hi[2])
{
    if (s->type == PM_SHAPE_RECTANGLE) {
        memcpy(lo, s->min, 2 * sizeof(double));
        memcpy(hi, s->max, 2 * sizeof(double));
    } else if (s->type == PM_SHAPE_CIRCLE) {
        for (int d = 0; d < 2; d++) {
            lo[d] = s->center[d] - s->radius;
            hi[d] = s->center[d] + s->radius;
        }
    } else if (s->type == PM_SHAPE_POLYGON) {
        lo[0] = hi[0] = s->points[0];
        lo[1] = hi[1] = s->points[1];
        for (size_t k = 1; k < s->n_points; k++)
            for (int d = 0; d < 2; d++) {
                lo[d] = fmin(lo[d], s->points[2 * k + d]);
                hi[d] = fmax(hi[d], s->points[2 * k + d]);
            }
    } else {
        lo[0] = lo[1] = hi[0] = hi[1] = NAN;
    }
}

static int parse_bodies(pm_case *c, json_t *bs)
{
    if (!bs)
        return fail(c->file, "bodies", "required key is missing", NULL);
    if (!json_is_array(bs) || json_array_size(bs) == 0)
        return pm_error_set(PM_EINPUT, "%s: bodies: expected a non-empty list of bodies, got %s", c->file,
                            jr_text(bs));
    c->n_bodies = json_array_size(bs);
    c->bodies = calloc(c->n_bodies, sizeof *c->bodies);
    if (!c->bodies)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < c->n_bodies; i++) {
        char path[64], def[PM_NAME_MAX];
        jr_index(path, sizeof path, "bodies", i);
        jr_ctx cx = {c->file, path};
        json_t *b = json_array_get(bs, i);
        pm_case_body *body = &c->bodies[i];
        if (!json_is_object(b))
            return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(b));
        pm_check(jr_only_keys(&cx, b, body_keys));
        snprintf(def, sizeof def, "body%zu", i);
        pm_check(jr_string(&cx, b, "name", 0, def, body->name, sizeof body->name));
        for (size_t j = 0; j < i; j++)
            if (!strcmp(c->bodies[j].name, body->name))
                return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" is already the name of bodies[%zu]", c->file, path,
                                    body->name, j);
        char mat[PM_NAME_MAX];
        pm_check(jr_string(&cx, b, "material", JR_REQUIRED, NULL, mat, sizeof mat));
        pm_check(find_material(c, path, mat, &body->material));
        json_t *sh = json_object_get(b, "shape");
        char sp[96];
        jr_join(sp, sizeof sp, path, "shape");
        if (!sh)
            return fail(c->file, sp, "required key is missing", NULL);
        pm_check(parse_shape(c, sp, sh, &body->shape));
        long ppc;
        pm_check(jr_int(&cx, b, "particles_per_cell", 0, 0, 1, 6, &ppc));
        if (c->grid.element == PM_TRI3 && ppc != 0 && ppc != 1 && ppc != 3 && ppc != 6)
            return pm_error_set(PM_EINPUT, "%s: %s.particles_per_cell: got %ld; allowed on tri3 grids: 1, 3 or 6",
                                c->file, path, ppc);
        body->particles_per_cell = (int)ppc;
        const double zero[2] = {0, 0};
        pm_check(jr_vec2(&cx, b, "velocity", 0, zero, body->velocity));
        pm_check(parse_initial_stress(c, path, b, body));
        if (c->grid.type == PM_GRID_RECTANGLE) {
            double lo[2], hi[2], glo[2], ghi[2];
            shape_box(&body->shape, lo, hi);
            const double tol = 1e-9 * fmax(c->grid.size[0], c->grid.size[1]);
            for (int d = 0; d < 2; d++) {
                glo[d] = c->grid.origin[d];
                ghi[d] = c->grid.origin[d] + c->grid.size[d];
            }
            if (lo[0] < glo[0] - tol || lo[1] < glo[1] - tol || hi[0] > ghi[0] + tol || hi[1] > ghi[1] + tol)
                return pm_error_set(PM_EINPUT,
                                    "%s: %s.shape: the body spans [%g, %g] x [%g, %g], outside the grid [%g, %g] x "
                                    "[%g, %g]; enlarge the grid or move the body",
                                    c->file, path, lo[0], hi[0], lo[1], hi[1], glo[0], ghi[0], glo[1], ghi[1]);
        }
    }
    return PM_OK;
}

static int parse_bcs(pm_case *c, json_t *bcs)
{
    if (!bcs)
        return PM_OK;
    if (!json_is_array(bcs))
        return pm_error_set(PM_EINPUT, "%s: boundary_conditions: expected a list, got %s", c->file, jr_type(bcs));
    c->n_bcs = json_array_size(bcs);
    c->bcs = calloc(c->n_bcs ? c->n_bcs : 1, sizeof *c->bcs);
    if (!c->bcs)
        return pm_error_set(PM_ENOMEM, "out of memory");
    static const char *const sides[] = {"x_min", "x_max", "y_min", "y_max", NULL};
    static const char *const dirs[] = {"x", "y", NULL};
    for (size_t i = 0; i < c->n_bcs; i++) {
        char path[64], bp[96];
        jr_index(path, sizeof path, "boundary_conditions", i);
        jr_ctx cx = {c->file, path};
        json_t *b = json_array_get(bcs, i);
        pm_case_bc *bc = &c->bcs[i];
        if (!json_is_object(b))
            return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(b));
        pm_check(jr_only_keys(&cx, b, bc_keys));
        int t;
        pm_check(jr_enum(&cx, b, "type", JR_REQUIRED, bc_types, 0, &t));
        bc->type = (pm_bc_type)t;
        json_t *bd = json_object_get(b, "boundary");
        jr_join(bp, sizeof bp, path, "boundary");
        bc->line_axis = -1;
        bc->until = INFINITY;
        if (!bd)
            return fail(c->file, bp, "required key is missing", NULL);
        if (json_is_object(bd)) {
            static const char *const line_keys[] = {"x", "y", "from", "to", "normal", NULL};
            jr_ctx lc = {c->file, bp};
            pm_check(jr_only_keys(&lc, bd, line_keys));
            json_t *x = json_object_get(bd, "x"), *y = json_object_get(bd, "y");
            if (!!x == !!y || !json_is_number(x ? x : y))
                return pm_error_set(PM_EINPUT, "%s: %s: expected a side name or {\"x\": value} / {\"y\": value}, got %s",
                                    c->file, bp, jr_text(bd));
            bc->line_axis = x ? 0 : 1;
            bc->line_value = json_number_value(x ? x : y);
            pm_check(jr_number(&lc, bd, "from", 0, -INFINITY, &bc->line_range[0]));
            pm_check(jr_number(&lc, bd, "to", 0, INFINITY, &bc->line_range[1]));
            if (!(bc->line_range[0] < bc->line_range[1]))
                return pm_error_set(PM_EINPUT, "%s: %s: from = %g must be below to = %g", c->file, bp,
                                    bc->line_range[0], bc->line_range[1]);
            if (json_object_get(bd, "normal")) {
                pm_check(jr_vec2(&lc, bd, "normal", 0, NULL, bc->line_normal));
                const double len = hypot(bc->line_normal[0], bc->line_normal[1]);
                if (!(len > 0))
                    return pm_error_set(PM_EINPUT, "%s: %s.normal: must not be zero", c->file, bp);
                bc->line_normal[0] /= len;
                bc->line_normal[1] /= len;
            }
        } else if (json_is_string(bd)) {
            const char *name = json_string_value(bd);
            int known = 0;
            for (int k = 0; sides[k]; k++)
                known |= !strcmp(name, sides[k]);
            if (!known && c->grid.type == PM_GRID_RECTANGLE) {
                const char *s = jr_suggest(name, sides);
                char hint[96] = "";
                if (s)
                    snprintf(hint, sizeof hint, "did you mean '%s'? ", s);
                return pm_error_set(PM_EINPUT, "%s: %s: unknown boundary \"%s\"; %s(allowed: x_min, x_max, y_min, y_max, "
                                    "or {\"x\": value} / {\"y\": value})", c->file, bp, name, hint);
            }
            if (strlen(name) >= sizeof bc->boundary)
                return fail(c->file, bp, "name too long", NULL);
            snprintf(bc->boundary, sizeof bc->boundary, "%s", name);
        } else {
            return pm_error_set(PM_EINPUT, "%s: %s: expected a side name or {\"x\": value} / {\"y\": value}, got %s",
                                c->file, bp, jr_text(bd));
        }
        if (bc->type == PM_BC_FIXED) {
            static const char *const k[] = {"type", "boundary", "directions", NULL};
            pm_check(jr_only_keys(&cx, b, k));
            json_t *d = json_object_get(b, "directions");
            jr_join(bp, sizeof bp, path, "directions");
            if (!d)
                return fail(c->file, bp, "required key is missing", NULL);
            if (!json_is_array(d) || json_array_size(d) == 0 || json_array_size(d) > 2)
                return pm_error_set(PM_EINPUT, "%s: %s: expected [\"x\"], [\"y\"] or [\"x\", \"y\"], got %s", c->file, bp,
                                    jr_text(d));
            for (size_t k2 = 0; k2 < json_array_size(d); k2++) {
                json_t *e = json_array_get(d, k2);
                int which = -1;
                for (int q = 0; dirs[q] && json_is_string(e); q++)
                    if (!strcmp(json_string_value(e), dirs[q]))
                        which = q;
                if (which < 0)
                    return pm_error_set(PM_EINPUT, "%s: %s[%zu]: got %s; allowed: \"x\" or \"y\"", c->file, bp, k2,
                                        jr_text(e));
                bc->dirs |= 1u << which;
            }
        } else if (bc->type == PM_BC_VELOCITY) {
            static const char *const k[] = {"type", "boundary", "value", "until", NULL};
            pm_check(jr_only_keys(&cx, b, k));
            pm_check(jr_number(&cx, b, "until", 0, INFINITY, &bc->until));
            if (json_object_get(b, "until"))
                pm_check(jr_range(&cx, "until", bc->until, 0, 1, INFINITY, 0));
            json_t *v = json_object_get(b, "value");
            jr_join(bp, sizeof bp, path, "value");
            if (!v)
                return fail(c->file, bp, "required key is missing", NULL);
            if (!json_is_array(v) || json_array_size(v) != 2)
                return pm_error_set(PM_EINPUT, "%s: %s: expected [vx, vy] (null leaves a component free), got %s",
                                    c->file, bp, jr_text(v));
            for (int d = 0; d < 2; d++) {
                json_t *e = json_array_get(v, (size_t)d);
                if (json_is_null(e))
                    continue;
                if (!json_is_number(e) || !isfinite(json_number_value(e)))
                    return pm_error_set(PM_EINPUT, "%s: %s[%d]: expected a number or null, got %s", c->file, bp, d,
                                        jr_text(e));
                bc->dirs |= 1u << d;
                bc->value[d] = json_number_value(e);
            }
            if (!bc->dirs)
                return fail(c->file, bp, "both components are null: give at least one velocity", NULL);
        } else {
            static const char *const k[] = {"type", "boundary", "coefficient", NULL};
            pm_check(jr_only_keys(&cx, b, k));
            pm_check(jr_number(&cx, b, "coefficient", JR_REQUIRED, 0, &bc->coefficient));
            pm_check(jr_range(&cx, "coefficient", bc->coefficient, 0, 0, INFINITY, 0));
        }
    }
    return PM_OK;
}

static int parse_probes(pm_case *c, json_t *ps)
{
    if (!ps)
        return PM_OK;
    if (!json_is_array(ps))
        return pm_error_set(PM_EINPUT, "%s: probes: expected a list, got %s", c->file, jr_type(ps));
    c->n_probes = json_array_size(ps);
    c->probes = calloc(c->n_probes ? c->n_probes : 1, sizeof *c->probes);
    if (!c->probes)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < c->n_probes; i++) {
        char path[64], def[PM_NAME_MAX];
        jr_index(path, sizeof path, "probes", i);
        jr_ctx cx = {c->file, path};
        json_t *p = json_array_get(ps, i);
        pm_case_probe *pr = &c->probes[i];
        if (!json_is_object(p))
            return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(p));
        pm_check(jr_only_keys(&cx, p, probe_keys));
        snprintf(def, sizeof def, "probe%zu", i);
        pm_check(jr_string(&cx, p, "name", 0, def, pr->name, sizeof pr->name));
        for (const char *ch = pr->name; *ch; ch++)
            if (*ch == ',' || *ch == '"' || *ch == '\n')
                return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" has a comma, quote or newline; it becomes a CSV "
                                    "column name", c->file, path, pr->name);
        for (size_t j = 0; j < i; j++)
            if (!strcmp(c->probes[j].name, pr->name))
                return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" is already the name of probes[%zu]", c->file, path,
                                    pr->name, j);
        int q;
        pm_check(jr_enum(&cx, p, "quantity", JR_REQUIRED, quantities, 0, &q));
        pr->quantity = (pm_quantity)q;
        json_t *pt = json_object_get(p, "point"), *bd = json_object_get(p, "body");
        if (!!pt == !!bd)
            return fail(c->file, path, "give exactly one of \"point\" ([x, y]) or \"body\" (a body's name)", NULL);
        pr->body = -1;
        if (pt) {
            pm_check(jr_vec2(&cx, p, "point", JR_REQUIRED, NULL, pr->point));
        } else {
            char bname[PM_NAME_MAX];
            pm_check(jr_string(&cx, p, "body", JR_REQUIRED, NULL, bname, sizeof bname));
            for (size_t k = 0; k < c->n_bodies; k++)
                if (!strcmp(c->bodies[k].name, bname))
                    pr->body = (int)k;
            if (pr->body < 0)
                return pm_error_set(PM_EINPUT, "%s: %s.body: no body is named \"%s\"", c->file, path, bname);
        }
    }
    return PM_OK;
}

static int parse_output(pm_case *c, json_t *o)
{
    jr_ctx cx = {c->file, "output"};
    char def[PM_PATH_MAX + 8];
    snprintf(def, sizeof def, "%.*s.out", (int)(sizeof c->stem - 1), c->stem);
    c->output.interval = c->analysis.end_time / 100;
    if (!o) {
        snprintf(c->output.directory, sizeof c->output.directory, "%.*s", (int)(sizeof c->output.directory - 1), def);
        return PM_OK;
    }
    pm_check(jr_expect_object(&cx, "", o));
    pm_check(jr_only_keys(&cx, o, output_keys));
    pm_check(jr_string(&cx, o, "directory", 0, def, c->output.directory, sizeof c->output.directory));
    if (!c->output.directory[0])
        return fail(c->file, "output.directory", "must not be empty", NULL);
    pm_check(jr_number(&cx, o, "interval", 0, c->analysis.end_time / 100, &c->output.interval));
    pm_check(jr_range(&cx, "interval", c->output.interval, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, o, "probe_interval", 0, 0, &c->output.probe_interval));
    pm_check(jr_range(&cx, "probe_interval", c->output.probe_interval, 0, 0, INFINITY, 0));
    json_t *pic = json_object_get(o, "pictures");
    if (pic && !json_is_false(pic)) {
        int f;
        pm_check(jr_enum(&cx, o, "pictures", 0, picture_fields, 0, &f));
        snprintf(c->output.pictures, sizeof c->output.pictures, "%s", picture_fields[f]);
    }
    return PM_OK;
}

/* Refuse counts that cannot be allocated, before anything is allocated. */
static int check_sizes(pm_case *c)
{
    if (c->grid.type != PM_GRID_RECTANGLE)
        return PM_OK;
    const double cells = (double)c->grid.cells[0] * (double)c->grid.cells[1];
    const double cell_area = c->grid.size[0] * c->grid.size[1] / cells;
    double particles = 0;
    for (size_t b = 0; b < c->n_bodies; b++) {
        double lo[2], hi[2];
        shape_box(&c->bodies[b].shape, lo, hi);
        int n = c->bodies[b].particles_per_cell;
        double per_cell = c->grid.element == PM_QUAD4 ? (double)(n ? n : 2) * (n ? n : 2) : 2.0 * (n ? n : 3);
        particles += (hi[0] - lo[0]) * (hi[1] - lo[1]) / cell_area * per_cell;
    }
    const double nodes = (double)(c->grid.cells[0] + 1) * (double)(c->grid.cells[1] + 1);
    const double bytes = particles * 220.0 + nodes * 120.0;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const double mem = pages > 0 && page > 0 ? (double)pages * (double)page : 1e12;
    if (particles > (double)INT32_MAX || nodes > (double)INT32_MAX || bytes > mem)
        return pm_error_set(PM_EINPUT,
                            "%s: grid.cells: about %.3g particles and %.3g grid nodes would need %.3g GB of memory; "
                            "this machine has %.3g GB (and at most %d of each fit); use fewer cells or particles",
                            c->file, particles, nodes, bytes / 1e9, mem / 1e9, INT32_MAX);
    return PM_OK;
}

static void split_name(pm_case *c, const char *name)
{
    snprintf(c->file, sizeof c->file, "%s", name);
    const char *slash = strrchr(name, '/');
    if (slash)
        snprintf(c->dir, sizeof c->dir, "%.*s", (int)(slash - name), name);
    else
        snprintf(c->dir, sizeof c->dir, ".");
    if (!c->dir[0])
        snprintf(c->dir, sizeof c->dir, "/");
    const char *base = slash ? slash + 1 : name;
    snprintf(c->stem, sizeof c->stem, "%s", base);
    char *dot = strrchr(c->stem, '.');
    if (dot && dot != c->stem)
        *dot = '\0';
}

static int parse_root(pm_case *c, json_t *root)
{
    jr_ctx cx = {c->file, ""};
    if (!json_is_object(root))
        return pm_error_set(PM_EINPUT, "%s: the case must be a JSON object, got %s", c->file, jr_type(root));
    pm_check(jr_only_keys(&cx, root, top_keys));
    pm_check(jr_string(&cx, root, "title", 0, c->stem, c->title, sizeof c->title));
    long dim;
    json_t *jd = json_object_get(root, "dimension");
    if (jd && json_is_integer(jd) && json_integer_value(jd) == 3)
        return fail(c->file, "dimension", "got 3: 3-D is not supported yet; allowed: 2", NULL);
    pm_check(jr_int(&cx, root, "dimension", JR_REQUIRED, 2, 2, 2, &dim));
    c->dimension = (int)dim;
    int v;
    pm_check(jr_enum(&cx, root, "formulation", 0, formulations, PM_PLANE_STRAIN, &v));
    c->formulation = (pm_formulation)v;
    pm_check(jr_enum(&cx, root, "method", 0, methods, PM_METHOD_MPM, &v));
    c->method = (pm_method)v;
    pm_check(parse_shape_function(c, &cx, root));
    pm_check(jr_number(&cx, root, "lme_gamma", 0, NAN, &c->lme_gamma));
    if (!isnan(c->lme_gamma))
        pm_check(jr_range(&cx, "lme_gamma", c->lme_gamma, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, root, "support_radius", 0, NAN, &c->support_radius));
    if (!isnan(c->support_radius))
        pm_check(jr_range(&cx, "support_radius", c->support_radius, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, root, "max_condition", 0, NAN, &c->max_condition));
    if (!isnan(c->max_condition))
        pm_check(jr_range(&cx, "max_condition", c->max_condition, 1, 0, INFINITY, 0));
    json_t *a = json_object_get(root, "analysis");
    if (!a)
        return fail(c->file, "analysis", "required key is missing", NULL);
    pm_check(parse_analysis(c, a));
    json_t *g = json_object_get(root, "grid");
    if (!g)
        return fail(c->file, "grid", "required key is missing", NULL);
    pm_check(parse_grid(c, g));
    pm_check(parse_materials(c, json_object_get(root, "materials")));
    pm_check(check_strength_reduction(c));
    pm_check(parse_bodies(c, json_object_get(root, "bodies")));
    pm_check(parse_bcs(c, json_object_get(root, "boundary_conditions")));
    pm_check(parse_probes(c, json_object_get(root, "probes")));
    pm_check(parse_output(c, json_object_get(root, "output")));
    return check_sizes(c);
}

int pm_case_load_buffer(const char *text, size_t len, const char *name, pm_case *c)
{
    memset(c, 0, sizeof *c);
    split_name(c, name);
    json_error_t err;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &err);
    if (!root)
        return pm_error_set(PM_EINPUT, "%s:%d:%d: %s", c->file, err.line, err.column, err.text);
    int rc = parse_root(c, root);
    json_decref(root);
    return rc;
}

int pm_case_load(const char *path, pm_case *c)
{
    memset(c, 0, sizeof *c);
    FILE *f = fopen(path, "rb");
    if (!f) {
        split_name(c, path);
        return pm_error_set(PM_EINPUT, "%s: cannot open the case file (does it exist?)", path);
    }
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 65536 > cap) {
            cap = cap ? 2 * cap : 131072;
            if (cap > ((size_t)1 << 30)) {
                free(buf);
                fclose(f);
                return pm_error_set(PM_EINPUT, "%s: the case file is larger than 1 GiB", path);
            }
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(f);
                return pm_error_set(PM_ENOMEM, "out of memory reading %s", path);
            }
            buf = nb;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0)
            break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return pm_error_set(PM_EIO, "%s: read error", path);
    }
    int rc = pm_case_load_buffer(buf, len, path, c);
    free(buf);
    return rc;
}

void pm_case_free(pm_case *c)
{
    for (size_t b = 0; b < c->n_bodies && c->bodies; b++)
        free(c->bodies[b].shape.points);
    free(c->bodies);
    free(c->materials);
    free(c->bcs);
    free(c->probes);
    memset(c, 0, sizeof *c);
}
