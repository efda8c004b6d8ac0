/* boundary_conditions, probes and output of a case. */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/render.h"
#include "pmech/error.h"
#include "pmech/grid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const bc_types[] = {"fixed", "velocity", "friction", NULL};
static const char *const quantities[] = {"position", "displacement", "velocity", "stress", "plastic_strain", NULL};

int pm_case_parse_bcs(pm_case *c, json_t *bcs)
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
        pm_check(jr_only_keys(&cx, b, pm_case_keys(PM_KEYS_BC)));
        int t;
        pm_check(jr_enum(&cx, b, "type", JR_REQUIRED, bc_types, 0, &t));
        bc->type = (pm_bc_type)t;
        json_t *bd = json_object_get(b, "boundary");
        jr_join(bp, sizeof bp, path, "boundary");
        bc->line_axis = -1;
        bc->until = INFINITY;
        if (!bd)
            return pm_case_fail(c->file, bp, "required key is missing", NULL);
        if (json_is_object(bd)) {
            jr_ctx lc = {c->file, bp};
            pm_check(jr_only_keys(&lc, bd, pm_case_keys(PM_KEYS_BC_LINE)));
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
                return pm_case_fail(c->file, bp, "name too long", NULL);
            snprintf(bc->boundary, sizeof bc->boundary, "%s", name);
        } else {
            return pm_error_set(PM_EINPUT, "%s: %s: expected a side name or {\"x\": value} / {\"y\": value}, got %s",
                                c->file, bp, jr_text(bd));
        }
        if (bc->type == PM_BC_FIXED) {
            pm_check(jr_only_keys(&cx, b, pm_case_keys(PM_KEYS_BC_FIXED)));
            json_t *d = json_object_get(b, "directions");
            jr_join(bp, sizeof bp, path, "directions");
            if (!d)
                return pm_case_fail(c->file, bp, "required key is missing", NULL);
            if (!json_is_array(d) || json_array_size(d) == 0 || json_array_size(d) > PM_DIM)
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
                if (bc->dirs & (1u << which)) /* a repeated direction is a typo for the other one, most likely */
                    return pm_error_set(PM_EINPUT, "%s: %s[%zu]: \"%s\" is listed twice; each direction at most once",
                                        c->file, bp, k2, dirs[which]);
                bc->dirs |= 1u << which;
            }
            if (json_object_get(b, "until")) {
                /* a gate that opens (a silo outlet closed while the fill settles); the implicit solvers
                 * and the meshfree node clouds number or rebuild their constraints once */
                if (c->analysis.type != PM_ANALYSIS_EXPLICIT || c->method != PM_METHOD_MPM)
                    return pm_error_set(PM_EINPUT,
                                        "%s: %s.until: a fixed condition can be released only in an 'explicit' "
                                        "analysis with method 'mpm'; remove 'until'",
                                        c->file, path);
                pm_check(jr_number(&cx, b, "until", 0, INFINITY, &bc->until));
                pm_check(jr_range(&cx, "until", bc->until, 0, 1, INFINITY, 0));
            }
        } else if (bc->type == PM_BC_VELOCITY) {
            pm_check(jr_only_keys(&cx, b, pm_case_keys(PM_KEYS_BC_VELOCITY)));
            pm_check(jr_number(&cx, b, "until", 0, INFINITY, &bc->until));
            if (json_object_get(b, "until"))
                pm_check(jr_range(&cx, "until", bc->until, 0, 1, INFINITY, 0));
            json_t *v = json_object_get(b, "value");
            jr_join(bp, sizeof bp, path, "value");
            if (!v)
                return pm_case_fail(c->file, bp, "required key is missing", NULL);
            if (!json_is_array(v) || json_array_size(v) != PM_DIM)
                return pm_error_set(PM_EINPUT, "%s: %s: expected [vx, vy] (null leaves a component free), got %s",
                                    c->file, bp, jr_text(v));
            for (int d = 0; d < PM_DIM; d++) {
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
                return pm_case_fail(c->file, bp, "both components are null: give at least one velocity", NULL);
        } else {
            pm_check(jr_only_keys(&cx, b, pm_case_keys(PM_KEYS_BC_FRICTION)));
            json_t *mu = json_object_get(b, "coefficient");
            if (json_is_string(mu) && !strcmp(json_string_value(mu), "no_slip")) {
                bc->coefficient = INFINITY; /* the laws then keep no slip at all, as for obstacles */
            } else {
                pm_check(jr_number(&cx, b, "coefficient", JR_REQUIRED, 0, &bc->coefficient));
                pm_check(jr_range(&cx, "coefficient", bc->coefficient, 0, 0, INFINITY, 0));
            }
        }
    }
    return PM_OK;
}

int pm_case_parse_probes(pm_case *c, json_t *ps)
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
        pm_check(jr_only_keys(&cx, p, pm_case_keys(PM_KEYS_PROBE)));
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
            return pm_case_fail(c->file, path, "give exactly one of \"point\" ([x, y]) or \"body\" (a body's name)",
                                NULL);
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

int pm_case_parse_output(pm_case *c, json_t *o)
{
    jr_ctx cx = {c->file, "output"};
    char def[PM_PATH_MAX + 8];
    snprintf(def, sizeof def, "%.*s.out", (int)(sizeof c->stem - 1), c->stem);
    c->output.interval = c->analysis.end_time / 100;
    c->output.picture_range[0] = c->output.picture_range[1] = NAN;
    c->output.picture_width = 800;
    if (!o) {
        snprintf(c->output.directory, sizeof c->output.directory, "%.*s", (int)(sizeof c->output.directory - 1), def);
        return PM_OK;
    }
    pm_check(jr_expect_object(&cx, "", o));
    pm_check(jr_only_keys(&cx, o, pm_case_keys(PM_KEYS_OUTPUT)));
    pm_check(jr_string(&cx, o, "directory", 0, def, c->output.directory, sizeof c->output.directory));
    if (!c->output.directory[0])
        return pm_case_fail(c->file, "output.directory", "is empty; give a directory (\".\" for the current one)",
                            NULL);
    pm_check(jr_number(&cx, o, "interval", 0, c->analysis.end_time / 100, &c->output.interval));
    pm_check(jr_range(&cx, "interval", c->output.interval, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, o, "probe_interval", 0, 0, &c->output.probe_interval));
    pm_check(jr_range(&cx, "probe_interval", c->output.probe_interval, 0, 0, INFINITY, 0));
    pm_check(jr_number(&cx, o, "checkpoint_interval", 0, 0, &c->output.checkpoint_interval));
    pm_check(jr_range(&cx, "checkpoint_interval", c->output.checkpoint_interval, 0, 0, INFINITY, 0));
    json_t *pic = json_object_get(o, "pictures");
    if (pic && !json_is_false(pic)) {
        int f;
        pm_check(jr_enum(&cx, o, "pictures", 0, pm_field_names(), 0, &f));
        snprintf(c->output.pictures, sizeof c->output.pictures, "%s", pm_field_names()[f]);
    }
    return pm_case_parse_picture_options(c, &cx, o);
}
