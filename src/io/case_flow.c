/* sources and sinks of a case: material released during a run, and where it leaves the model. */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const sink_types[] = {"outlet", "region", "outside_grid", NULL};

/* Names become values of the release and removal logs (CSV). */
static int csv_safe_name(const pm_case *c, const char *path, const char *name)
{
    for (const char *ch = name; *ch; ch++)
        if (*ch == ',' || *ch == '"' || *ch == '\n')
            return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" has a comma, quote or newline; it is written in a "
                                "CSV log", c->file, path, name);
    return PM_OK;
}

/* Only explicit MPM appends and removes particles: the implicit workspace and the GMM/RKPM node clouds
 * are built once for the particles of the start. */
static int check_method(const pm_case *c, const char *section)
{
    if (c->method != PM_METHOD_MPM)
        return pm_error_set(PM_EINPUT, "%s: %s: particles can be added and removed only with method 'mpm' (GMM and "
                            "RKPM build their node clouds from the particles of the start); remove '%s' or use "
                            "method 'mpm'", c->file, section, section);
    if (c->analysis.type != PM_ANALYSIS_EXPLICIT)
        return pm_error_set(PM_EINPUT, "%s: %s: particles can be added and removed only in 'explicit' analyses (the "
                            "implicit solvers number their unknowns once); remove '%s' or use analysis.type "
                            "'explicit'", c->file, section, section);
    return PM_OK;
}

static int parse_times(pm_case *c, const char *path, json_t *t, pm_case_source *src)
{
    char tp[96];
    jr_join(tp, sizeof tp, path, "times");
    if (!json_is_array(t) || json_array_size(t) == 0 || json_array_size(t) > 10000000)
        return pm_error_set(PM_EINPUT, "%s: %s: expected a non-empty list of release times, got %s", c->file, tp,
                            jr_text(t));
    src->n_times = json_array_size(t);
    src->times = malloc(src->n_times * sizeof(double));
    if (!src->times)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t k = 0; k < src->n_times; k++) {
        json_t *e = json_array_get(t, k);
        const double v = json_is_number(e) ? json_number_value(e) : NAN;
        if (!isfinite(v) || v < 0)
            return pm_error_set(PM_EINPUT, "%s: %s[%zu]: got %s; allowed: a time >= 0 (s)", c->file, tp, k,
                                jr_text(e));
        if (k > 0 && !(v > src->times[k - 1]))
            return pm_error_set(PM_EINPUT, "%s: %s[%zu] = %g: the times must increase (the one before is %g)", c->file,
                                tp, k, v, src->times[k - 1]);
        src->times[k] = v;
    }
    return PM_OK;
}

static int parse_schedule(pm_case *c, const char *path, json_t *s, pm_case_source *src)
{
    jr_ctx cx = {c->file, path};
    json_t *t = json_object_get(s, "times"), *per = json_object_get(s, "period");
    if (!!t == !!per)
        return pm_case_fail(c->file, path, "give exactly one of \"times\" (a list of release times) or \"period\" "
                            "(with optional \"start\" and \"until\")", NULL);
    if (t) {
        if (json_object_get(s, "start") || json_object_get(s, "until"))
            return pm_case_fail(c->file, path, "\"start\" and \"until\" go with \"period\", not with \"times\"", NULL);
        pm_check(parse_times(c, path, t, src));
    } else {
        pm_check(jr_number(&cx, s, "period", JR_REQUIRED, 0, &src->period));
        pm_check(jr_range(&cx, "period", src->period, 0, 1, INFINITY, 0));
        pm_check(jr_number(&cx, s, "start", 0, 0, &src->start));
        pm_check(jr_range(&cx, "start", src->start, 0, 0, INFINITY, 0));
    }
    const double first = t ? src->times[0] : src->start;
    if (first > c->analysis.end_time)
        return pm_error_set(PM_EINPUT, "%s: %s: the first release, at t = %g s, comes after analysis.end_time = %g s",
                            c->file, path, first, c->analysis.end_time);
    if (!t) {
        pm_check(jr_number(&cx, s, "until", 0, c->analysis.end_time, &src->until));
        pm_check(jr_range(&cx, "until", src->until, src->start, 0, INFINITY, 0));
    }
    return jr_bool(&cx, s, "only_when_free", 0, 0, &src->only_when_free);
}

int pm_case_parse_sources(pm_case *c, json_t *ss)
{
    if (!ss)
        return PM_OK;
    if (!json_is_array(ss))
        return pm_error_set(PM_EINPUT, "%s: sources: expected a list, got %s", c->file, jr_type(ss));
    if (json_array_size(ss) == 0)
        return PM_OK;
    pm_check(check_method(c, "sources"));
    const size_t n = json_array_size(ss);
    c->sources = calloc(n, sizeof *c->sources);
    if (!c->sources)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) {
        char path[64], def[PM_NAME_MAX];
        jr_index(path, sizeof path, "sources", i);
        jr_ctx cx = {c->file, path};
        json_t *s = json_array_get(ss, i);
        pm_case_source *src = &c->sources[i];
        c->n_sources = i + 1; /* so that pm_case_free() frees what this one owns */
        if (!json_is_object(s))
            return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(s));
        pm_check(jr_only_keys(&cx, s, pm_case_keys(PM_KEYS_SOURCE)));
        snprintf(def, sizeof def, "source%zu", i);
        c->n_sources = i; /* the names before this one */
        int rc = pm_case_parse_body(c, path, s, def, 0, &src->body);
        c->n_sources = i + 1;
        pm_check(rc);
        pm_check(csv_safe_name(c, path, src->body.name));
        pm_check(parse_schedule(c, path, s, src));
    }
    return PM_OK;
}

/* An outlet's line: a grid side (resolved against the grid when the run starts), or x = value /
 * y = value with an optional part from..to and crossing direction. */
static int parse_outlet(pm_case *c, const char *path, json_t *s, pm_case_sink *k)
{
    char bp[96];
    jr_join(bp, sizeof bp, path, "boundary");
    json_t *bd = json_object_get(s, "boundary");
    k->range[0] = -INFINITY;
    k->range[1] = INFINITY;
    if (!bd)
        return pm_case_fail(c->file, bp, "required key is missing", NULL);
    if (json_is_string(bd)) {
        static const char *const sides[] = {"x_min", "x_max", "y_min", "y_max", NULL};
        const char *name = json_string_value(bd);
        for (int q = 0; sides[q]; q++)
            if (!strcmp(name, sides[q])) {
                snprintf(k->side, sizeof k->side, "%s", name);
                return PM_OK;
            }
        const char *sug = jr_suggest(name, sides);
        return pm_error_set(PM_EINPUT, "%s: %s: unknown side \"%s\"; %s%s%sallowed: x_min, x_max, y_min, y_max (the "
                            "sides of the grid's bounding box), or a line {\"x\": value} / {\"y\": value} with "
                            "optional \"from\", \"to\", \"normal\"", c->file, bp, name, sug ? "did you mean '" : "",
                            sug ? sug : "", sug ? "'? " : "");
    }
    if (!json_is_object(bd))
        return pm_error_set(PM_EINPUT, "%s: %s: expected a side name or {\"x\": value} / {\"y\": value}, got %s",
                            c->file, bp, jr_text(bd));
    jr_ctx lc = {c->file, bp};
    pm_check(jr_only_keys(&lc, bd, pm_case_keys(PM_KEYS_SINK_LINE)));
    json_t *x = json_object_get(bd, "x"), *y = json_object_get(bd, "y");
    if (!!x == !!y || !json_is_number(x ? x : y) || !isfinite(json_number_value(x ? x : y)))
        return pm_error_set(PM_EINPUT, "%s: %s: expected exactly one of \"x\" or \"y\" with a number, got %s", c->file,
                            bp, jr_text(bd));
    k->axis = x ? 0 : 1;
    k->value = json_number_value(x ? x : y);
    pm_check(jr_number(&lc, bd, "from", 0, -INFINITY, &k->range[0]));
    pm_check(jr_number(&lc, bd, "to", 0, INFINITY, &k->range[1]));
    if (!(k->range[0] < k->range[1]))
        return pm_error_set(PM_EINPUT, "%s: %s: from = %g must be below to = %g", c->file, bp, k->range[0],
                            k->range[1]);
    if (json_object_get(bd, "normal")) {
        pm_check(jr_vec2(&lc, bd, "normal", 0, NULL, k->normal));
        const double len = hypot(k->normal[0], k->normal[1]);
        if (!(len > 0) || fabs(k->normal[1 - k->axis]) > 1e-12 * len)
            return pm_error_set(PM_EINPUT, "%s: %s.normal: [%g, %g]: must be along the %c axis, across the line",
                                c->file, bp, k->normal[0], k->normal[1], k->axis ? 'y' : 'x');
        k->normal[0] /= len;
        k->normal[1] /= len;
    }
    if (c->grid.type == PM_GRID_RECTANGLE) {
        const int a = k->axis, o = 1 - a;
        const double lo = c->grid.origin[a], hi = lo + c->grid.size[a], tol = 1e-9 * (hi - lo);
        const double olo = c->grid.origin[o], ohi = olo + c->grid.size[o];
        if (k->value < lo - tol || k->value > hi + tol || k->range[1] <= olo || k->range[0] >= ohi)
            return pm_error_set(PM_EINPUT, "%s: %s: the outlet %c = %g from %g to %g misses the grid [%g, %g] x "
                                "[%g, %g]", c->file, bp, a ? 'y' : 'x', k->value, k->range[0], k->range[1],
                                c->grid.origin[0], c->grid.origin[0] + c->grid.size[0], c->grid.origin[1],
                                c->grid.origin[1] + c->grid.size[1]);
    }
    return PM_OK;
}

int pm_case_parse_sinks(pm_case *c, json_t *ss)
{
    if (!ss)
        return PM_OK;
    if (!json_is_array(ss))
        return pm_error_set(PM_EINPUT, "%s: sinks: expected a list, got %s", c->file, jr_type(ss));
    if (json_array_size(ss) == 0)
        return PM_OK;
    pm_check(check_method(c, "sinks"));
    const size_t n = json_array_size(ss);
    if (n > 255) /* a removed particle's sink is kept in one byte */
        return pm_error_set(PM_EINPUT, "%s: sinks: %zu sinks; at most 255 are allowed", c->file, n);
    c->sinks = calloc(n, sizeof *c->sinks);
    if (!c->sinks)
        return pm_error_set(PM_ENOMEM, "out of memory");
    c->n_sinks = n;
    static const pm_case_keyset_id keys[] = {PM_KEYS_SINK_OUTLET, PM_KEYS_SINK_REGION, PM_KEYS_SINK_OUTSIDE_GRID};
    for (size_t i = 0; i < n; i++) {
        char path[64], def[PM_NAME_MAX];
        jr_index(path, sizeof path, "sinks", i);
        jr_ctx cx = {c->file, path};
        json_t *s = json_array_get(ss, i);
        pm_case_sink *k = &c->sinks[i];
        if (!json_is_object(s))
            return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(s));
        int t;
        pm_check(jr_enum(&cx, s, "type", JR_REQUIRED, sink_types, 0, &t));
        k->type = (pm_sink_type)t;
        pm_check(jr_only_keys(&cx, s, pm_case_keys(keys[t])));
        snprintf(def, sizeof def, "sink%zu", i);
        pm_check(jr_string(&cx, s, "name", 0, def, k->name, sizeof k->name));
        pm_check(csv_safe_name(c, path, k->name));
        for (size_t j = 0; j < i; j++) {
            if (!strcmp(c->sinks[j].name, k->name))
                return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" is already the name of sinks[%zu]", c->file, path,
                                    k->name, j);
            if (k->type == PM_SINK_OUTSIDE_GRID && c->sinks[j].type == PM_SINK_OUTSIDE_GRID)
                return pm_error_set(PM_EINPUT, "%s: %s.type: sinks[%zu] is already of type 'outside_grid'", c->file,
                                    path, j);
        }
        if (k->type == PM_SINK_OUTLET) {
            pm_check(parse_outlet(c, path, s, k));
        } else if (k->type == PM_SINK_REGION) {
            char sp[96];
            jr_join(sp, sizeof sp, path, "shape");
            json_t *sh = json_object_get(s, "shape");
            if (!sh)
                return pm_case_fail(c->file, sp, "required key is missing", NULL);
            pm_check(pm_case_parse_shape(c, sp, sh, &k->shape));
            if (k->shape.type == PM_SHAPE_GMSH_GROUP)
                return pm_case_fail(c->file, sp, "a sink's region is a rectangle, polygon or circle, not a "
                                    "gmsh_group", NULL);
        }
    }
    return PM_OK;
}

size_t pm_case_source_releases(const pm_case *c, size_t k)
{
    const pm_case_source *s = &c->sources[k];
    const double end = c->analysis.end_time;
    if (s->n_times) {
        size_t n = 0;
        while (n < s->n_times && s->times[n] <= end * (1 + 1e-12))
            n++;
        return n;
    }
    const double last = fmin(s->until, end);
    if (s->start > last * (1 + 1e-12))
        return 0;
    return (size_t)floor((last - s->start) / s->period + 1e-9) + 1;
}

double pm_case_source_release_time(const pm_case *c, size_t k, size_t j)
{
    const pm_case_source *s = &c->sources[k];
    return s->n_times ? s->times[j] : s->start + (double)j * s->period;
}
