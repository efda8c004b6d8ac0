/* loads[]: forces on sets of particles (the one nearest a point, or those in a box), each component a
 * function of time. */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The force components, each a number or a function of time, under @p key. */
static int parse_force(pm_case *c, const char *path, json_t *o, const char *key, pm_case_particle_load *ld)
{
    char fp[96], ep[128];
    json_t *f = json_object_get(o, key);
    jr_join(fp, sizeof fp, path, key);
    if (!f)
        return pm_case_fail(c->file, fp, "required key is missing", NULL);
    if (!json_is_array(f) || json_array_size(f) != PM_DIM)
        return pm_error_set(PM_EINPUT, "%s: %s: expected [fx, fy], each a number or a function of time, got %s",
                            c->file, fp, jr_text(f));
    for (int d = 0; d < PM_DIM; d++) {
        jr_index(ep, sizeof ep, fp, (size_t)d);
        pm_check(pm_case_parse_timefn(c->file, ep, json_array_get(f, (size_t)d), &ld->force[d]));
    }
    return PM_OK;
}

/* A force per length on the nodes of a grid line: an MPM rectangle grid's nodes stay where they are. */
static int parse_line(pm_case *c, const char *path, json_t *o, json_t *line, pm_case_particle_load *ld)
{
    char lp[96];
    jr_join(lp, sizeof lp, path, "grid_line");
    jr_ctx lc = {c->file, lp};
    for (const char *k = "nearest\0min\0max\0force\0"; *k; k += strlen(k) + 1)
        if (json_object_get(o, k))
            return pm_error_set(PM_EINPUT, "%s: %s: \"%s\" does not go with \"grid_line\" (its force is "
                                "\"force_per_length\")", c->file, path, k);
    if (!json_is_object(line))
        return pm_error_set(PM_EINPUT, "%s: %s: expected {\"x\": value} or {\"y\": value} with optional \"from\" "
                            "and \"to\", got %s", c->file, lp, jr_text(line));
    pm_check(jr_only_keys(&lc, line, pm_case_keys(PM_KEYS_LOAD_LINE)));
    json_t *x = json_object_get(line, "x"), *y = json_object_get(line, "y");
    if (!!x == !!y || !json_is_number(x ? x : y))
        return pm_error_set(PM_EINPUT, "%s: %s: expected exactly one of \"x\" and \"y\", a number, got %s", c->file,
                            lp, jr_text(line));
    ld->line_axis = x ? 0 : 1;
    ld->line_value = json_number_value(x ? x : y);
    pm_check(jr_number(&lc, line, "from", 0, -INFINITY, &ld->line_range[0]));
    pm_check(jr_number(&lc, line, "to", 0, INFINITY, &ld->line_range[1]));
    if (!(ld->line_range[0] < ld->line_range[1]))
        return pm_error_set(PM_EINPUT, "%s: %s: from = %g must be below to = %g", c->file, lp, ld->line_range[0],
                            ld->line_range[1]);
    if (c->method != PM_METHOD_MPM || c->grid.type != PM_GRID_RECTANGLE)
        return pm_error_set(PM_EINPUT, "%s: %s: a load on a grid line needs method 'mpm' and a 'rectangle' grid (its "
                            "nodes stay on the line)", c->file, lp);
    return parse_force(c, path, o, "force_per_length", ld);
}

static int parse_one(pm_case *c, size_t i, json_t *o)
{
    char path[64];
    jr_index(path, sizeof path, "loads", i);
    jr_ctx cx = {c->file, path};
    pm_case_particle_load *ld = &c->loads[i];
    if (!json_is_object(o))
        return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(o));
    pm_check(jr_only_keys(&cx, o, pm_case_keys(PM_KEYS_LOAD)));
    char def[PM_NAME_MAX];
    snprintf(def, sizeof def, "load%zu", i);
    pm_check(jr_string(&cx, o, "name", 0, def, ld->name, sizeof ld->name));
    const int near = json_object_get(o, "nearest") != NULL;
    const int box = json_object_get(o, "min") || json_object_get(o, "max");
    ld->line_axis = -1;
    json_t *line = json_object_get(o, "grid_line");
    if (line)
        return parse_line(c, path, o, line, ld);
    if (json_object_get(o, "force_per_length"))
        return pm_case_fail(c->file, path, "\"force_per_length\" goes with \"grid_line\"; a particle set takes \"force\"",
                            NULL);
    if (near == box)
        return pm_case_fail(c->file, path,
                            "give either \"nearest\": [x, y] (one particle), \"min\" and \"max\" (the particles in "
                            "that box) or \"grid_line\" (the grid nodes of a line)",
                            NULL);
    ld->nearest = near;
    if (near) {
        pm_check(jr_vec2(&cx, o, "nearest", JR_REQUIRED, NULL, ld->point));
    } else {
        pm_check(jr_vec2(&cx, o, "min", JR_REQUIRED, NULL, ld->min));
        pm_check(jr_vec2(&cx, o, "max", JR_REQUIRED, NULL, ld->max));
        if (!(ld->min[0] < ld->max[0] && ld->min[1] < ld->max[1]))
            return pm_error_set(PM_EINPUT, "%s: %s: min [%g, %g] must lie below and left of max [%g, %g]", c->file,
                                path, ld->min[0], ld->min[1], ld->max[0], ld->max[1]);
    }
    return parse_force(c, path, o, "force", ld);
}

int pm_case_parse_loads(pm_case *c, json_t *ls)
{
    if (!ls)
        return PM_OK;
    if (!json_is_array(ls))
        return pm_error_set(PM_EINPUT, "%s: loads: expected a list, got %s", c->file, jr_type(ls));
    const size_t n = json_array_size(ls);
    c->loads = calloc(n ? n : 1, sizeof *c->loads);
    if (!c->loads)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) {
        c->n_loads = i + 1; /* so that pm_case_free() frees what this one owns */
        pm_check(parse_one(c, i, json_array_get(ls, i)));
    }
    if (n && c->analysis.type != PM_ANALYSIS_EXPLICIT)
        return pm_error_set(PM_EINPUT, "%s: loads: need analysis.type 'explicit' (loads in implicit runs are not "
                            "available in this version)", c->file);
    return PM_OK;
}

void pm_case_free_loads(pm_case *c)
{
    for (size_t k = 0; k < c->n_loads && c->loads; k++)
        for (int d = 0; d < PM_DIM; d++)
            pm_timefn_free(&c->loads[k].force[d]);
    free(c->loads);
    c->loads = NULL;
    c->n_loads = 0;
}
