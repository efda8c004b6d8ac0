/*
 * obstacles[]: rigid polylines, polygons and circles, fixed or moving with a velocity given per
 * component as a function of time; and the reader of such functions of time (a number, a ramp, a
 * table), which other prescribed quantities share.
 */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const obstacle_types[] = {"polyline", "polygon", "circle", NULL};
static const char *const laws[] = {"nodal", "penalty", NULL};
static const char *const sides[] = {"left", "right", NULL};
static const char *const corners[] = {"round", "sharp", NULL};
static const char *const acts_at[] = {"nodes", "particles", NULL};

int pm_case_parse_timefn(const char *file, const char *path, json_t *v, pm_timefn *f)
{
    memset(f, 0, sizeof *f);
    if (json_is_number(v) && isfinite(json_number_value(v))) {
        f->value = json_number_value(v);
        return PM_OK;
    }
    if (!json_is_object(v))
        return pm_error_set(PM_EINPUT,
                            "%s: %s: expected a number, {\"value\": v, \"ramp_time\": T} or {\"table\": [[t, v], "
                            "...]}, got %s",
                            file, path, jr_text(v));
    jr_ctx cx = {file, path};
    pm_check(jr_only_keys(&cx, v, pm_case_keys(PM_KEYS_TIMEFN)));
    json_t *table = json_object_get(v, "table");
    if (!table) {
        pm_check(jr_number(&cx, v, "value", JR_REQUIRED, 0, &f->value));
        pm_check(jr_number(&cx, v, "ramp_time", JR_REQUIRED, 0, &f->ramp_time));
        pm_check(jr_range(&cx, "ramp_time", f->ramp_time, 0, 1, INFINITY, 1));
        f->kind = PM_TIMEFN_RAMP;
        return PM_OK;
    }
    char tp[256];
    jr_join(tp, sizeof tp, path, "table");
    if (json_object_get(v, "value") || json_object_get(v, "ramp_time"))
        return pm_case_fail(file, path, "give either \"table\" or \"value\" with \"ramp_time\", not both", NULL);
    if (!json_is_array(table) || json_array_size(table) == 0 || json_array_size(table) > 1000000)
        return pm_error_set(PM_EINPUT, "%s: %s: expected a list of [t, value] pairs, got %s", file, tp,
                            jr_text(table));
    const size_t n = json_array_size(table);
    f->t = malloc(n * sizeof *f->t);
    f->v = malloc(n * sizeof *f->v);
    f->kind = PM_TIMEFN_TABLE; /* from here on pm_timefn_free() releases the arrays */
    if (!f->t || !f->v)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) {
        json_t *e = json_array_get(table, i), *t = json_array_get(e, 0), *x = json_array_get(e, 1);
        if (!json_is_array(e) || json_array_size(e) != 2 || !json_is_number(t) || !json_is_number(x) ||
            !isfinite(json_number_value(t)) || !isfinite(json_number_value(x)))
            return pm_error_set(PM_EINPUT, "%s: %s[%zu]: expected a pair [t, value], got %s", file, tp, i, jr_text(e));
        f->t[i] = json_number_value(t);
        f->v[i] = json_number_value(x);
        f->n = i + 1;
        if (i > 0 && !(f->t[i] > f->t[i - 1]))
            return pm_error_set(PM_EINPUT, "%s: %s[%zu]: time %g is not after the previous one, %g (the times must "
                                "increase)", file, tp, i, f->t[i], f->t[i - 1]);
    }
    return PM_OK;
}

static int read_points(pm_case *c, const char *path, json_t *o, size_t min, pm_case_obstacle *ob)
{
    char pp[256];
    jr_join(pp, sizeof pp, path, "points");
    json_t *pts = json_object_get(o, "points");
    if (!pts)
        return pm_case_fail(c->file, pp, "required key is missing", NULL);
    if (!json_is_array(pts) || json_array_size(pts) < min || json_array_size(pts) > 1000000)
        return pm_error_set(PM_EINPUT, "%s: %s: expected a list of at least %zu points [x, y], got %s", c->file, pp,
                            min, jr_text(pts));
    ob->n_points = json_array_size(pts);
    ob->points = malloc(PM_DIM * ob->n_points * sizeof(double));
    if (!ob->points)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t k = 0; k < ob->n_points; k++) {
        json_t *p = json_array_get(pts, k), *x = json_array_get(p, 0), *y = json_array_get(p, 1);
        if (!json_is_array(p) || json_array_size(p) != PM_DIM || !json_is_number(x) || !json_is_number(y) ||
            !isfinite(json_number_value(x)) || !isfinite(json_number_value(y)))
            return pm_error_set(PM_EINPUT, "%s: %s[%zu]: expected a point [x, y], got %s", c->file, pp, k, jr_text(p));
        ob->points[PM_DIM * k] = json_number_value(x);
        ob->points[PM_DIM * k + 1] = json_number_value(y);
        if (k > 0 && ob->points[PM_DIM * k] == ob->points[PM_DIM * (k - 1)] &&
            ob->points[PM_DIM * k + 1] == ob->points[PM_DIM * (k - 1) + 1])
            return pm_error_set(PM_EINPUT, "%s: %s[%zu]: the same point as the one before it (a segment of zero "
                                "length)", c->file, pp, k);
    }
    return PM_OK;
}

/* On a rectangle grid the obstacle's box must overlap the grid (at t = 0). */
static int check_inside(const pm_case *c, const char *path, const pm_case_obstacle *ob)
{
    if (c->grid.type != PM_GRID_RECTANGLE)
        return PM_OK;
    double lo[2], hi[2];
    if (ob->type == PM_OBSTACLE_CIRCLE) {
        for (int d = 0; d < PM_DIM; d++)
            lo[d] = ob->center[d] - ob->radius, hi[d] = ob->center[d] + ob->radius;
    } else {
        for (int d = 0; d < PM_DIM; d++)
            lo[d] = hi[d] = ob->points[d];
        for (size_t k = 1; k < ob->n_points; k++)
            for (int d = 0; d < PM_DIM; d++) {
                lo[d] = fmin(lo[d], ob->points[PM_DIM * k + d]);
                hi[d] = fmax(hi[d], ob->points[PM_DIM * k + d]);
            }
    }
    for (int d = 0; d < PM_DIM; d++) {
        const double g0 = c->grid.origin[d], g1 = c->grid.origin[d] + c->grid.size[d];
        if (hi[d] < g0 || lo[d] > g1)
            return pm_error_set(PM_EINPUT,
                                "%s: %s: the obstacle spans %c from %g to %g, outside the grid's %g to %g: it would "
                                "never touch the material",
                                c->file, path, "xy"[d], lo[d], hi[d], g0, g1);
    }
    return PM_OK;
}

static int parse_friction(pm_case *c, const char *path, json_t *o, pm_case_obstacle *ob)
{
    char fp[256];
    jr_join(fp, sizeof fp, path, "friction");
    json_t *f = json_object_get(o, "friction");
    ob->friction = 0.0;
    if (!f)
        return PM_OK;
    if (json_is_string(f) && !strcmp(json_string_value(f), "no_slip")) {
        ob->friction = INFINITY;
        return PM_OK;
    }
    if (!json_is_number(f) || !(json_number_value(f) >= 0) || !isfinite(json_number_value(f)))
        return pm_error_set(PM_EINPUT, "%s: %s: got %s; allowed: a coefficient >= 0 or \"no_slip\"", c->file, fp,
                            jr_text(f));
    ob->friction = json_number_value(f);
    return PM_OK;
}

static int parse_velocity(pm_case *c, const char *path, json_t *o, pm_case_obstacle *ob)
{
    char vp[256], ep[288];
    jr_join(vp, sizeof vp, path, "velocity");
    json_t *v = json_object_get(o, "velocity");
    if (!v)
        return PM_OK;
    if (!json_is_array(v) || json_array_size(v) != PM_DIM)
        return pm_error_set(PM_EINPUT, "%s: %s: expected [vx, vy], each a number or a function of time, got %s",
                            c->file, vp, jr_text(v));
    for (int d = 0; d < PM_DIM; d++) {
        jr_index(ep, sizeof ep, vp, (size_t)d);
        pm_check(pm_case_parse_timefn(c->file, ep, json_array_get(v, (size_t)d), &ob->velocity[d]));
    }
    return PM_OK;
}

static int parse_one(pm_case *c, size_t i, json_t *o)
{
    char path[64];
    jr_index(path, sizeof path, "obstacles", i);
    jr_ctx cx = {c->file, path};
    pm_case_obstacle *ob = &c->obstacles[i];
    if (!json_is_object(o))
        return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(o));
    pm_check(jr_only_keys(&cx, o, pm_case_keys(PM_KEYS_OBSTACLE)));
    char def[PM_NAME_MAX];
    snprintf(def, sizeof def, "obstacle%zu", i);
    pm_check(jr_string(&cx, o, "name", 0, def, ob->name, sizeof ob->name));
    for (const char *ch = ob->name; *ch; ch++)
        if (*ch == ',' || *ch == '"' || *ch == '\n' || *ch == '/')
            return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" has a comma, quote, slash or newline; it names CSV "
                                "columns and files", c->file, path, ob->name);
    for (size_t j = 0; j < i; j++)
        if (!strcmp(c->obstacles[j].name, ob->name))
            return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" is already the name of obstacles[%zu]", c->file, path,
                                ob->name, j);
    int t;
    pm_check(jr_enum(&cx, o, "type", JR_REQUIRED, obstacle_types, 0, &t));
    ob->type = (pm_obstacle_type)t;
    const char *wrong = NULL;
    if (ob->type == PM_OBSTACLE_CIRCLE) {
        pm_check(jr_vec2(&cx, o, "center", JR_REQUIRED, NULL, ob->center));
        pm_check(jr_number(&cx, o, "radius", JR_REQUIRED, 0, &ob->radius));
        pm_check(jr_range(&cx, "radius", ob->radius, 0, 1, INFINITY, 0));
        wrong = json_object_get(o, "points")          ? "points"
                : json_object_get(o, "material_side") ? "material_side"
                : json_object_get(o, "corners")       ? "corners"
                                                      : NULL;
    } else {
        pm_check(read_points(c, path, o, ob->type == PM_OBSTACLE_POLYLINE ? 2 : 3, ob));
        wrong = json_object_get(o, "center") ? "center" : json_object_get(o, "radius") ? "radius" : NULL;
        if (ob->type == PM_OBSTACLE_POLYGON && json_object_get(o, "material_side"))
            wrong = "material_side";
    }
    if (wrong) {
        char wp[256];
        jr_join(wp, sizeof wp, path, wrong);
        return pm_error_set(PM_EINPUT, "%s: %s: not a key of a %s obstacle", c->file, wp, obstacle_types[t]);
    }
    int side;
    pm_check(jr_enum(&cx, o, "material_side", 0, sides, 0, &side));
    ob->material_right = side;
    int corner;
    pm_check(jr_enum(&cx, o, "corners", 0, corners, 0, &corner));
    ob->sharp_corners = corner;
    int law;
    pm_check(jr_enum(&cx, o, "law", 0, laws, 0, &law));
    ob->law = (pm_obstacle_law)law;
    pm_check(parse_friction(c, path, o, ob));
    pm_check(jr_enum(&cx, o, "acts_at", 0, acts_at, 0, &ob->at_particles));
    /* the touching points are the explicit MPM nodal law's, on the one field of a run without body pairs */
    if (ob->at_particles && (ob->law != PM_OBSTACLE_NODAL || c->method != PM_METHOD_MPM || c->n_contact_pairs))
        return pm_error_set(PM_EINPUT,
                            "%s: %s.acts_at: \"particles\" needs law \"nodal\", method \"mpm\" and no contact_pairs; "
                            "allowed otherwise: \"nodes\"",
                            c->file, path);
    pm_check(jr_number(&cx, o, "penalty_factor", 0, 1.0, &ob->penalty_factor));
    pm_check(jr_range(&cx, "penalty_factor", ob->penalty_factor, 0, 1, 100, 0));
    pm_check(parse_velocity(c, path, o, ob));
    return check_inside(c, path, ob);
}

int pm_case_parse_obstacles(pm_case *c, json_t *obs)
{
    if (!obs)
        return PM_OK;
    if (!json_is_array(obs))
        return pm_error_set(PM_EINPUT, "%s: obstacles: expected a list, got %s", c->file, jr_type(obs));
    const size_t n = json_array_size(obs);
    c->obstacles = calloc(n ? n : 1, sizeof *c->obstacles);
    if (!c->obstacles)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) {
        c->n_obstacles = i + 1; /* so that pm_case_free() frees what this one owns */
        pm_check(parse_one(c, i, json_array_get(obs, i)));
    }
    return PM_OK;
}

void pm_case_free_obstacles(pm_case *c)
{
    for (size_t k = 0; k < c->n_obstacles && c->obstacles; k++) {
        free(c->obstacles[k].points);
        for (int d = 0; d < PM_DIM; d++)
            pm_timefn_free(&c->obstacles[k].velocity[d]);
    }
    free(c->obstacles);
    c->obstacles = NULL;
    c->n_obstacles = 0;
}
