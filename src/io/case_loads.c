/* loads[]: forces on sets of particles (the one nearest a point, or those in a box), each component a
 * function of time. */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int parse_one(pm_case *c, size_t i, json_t *o)
{
    char path[64], fp[96], ep[128];
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
    if (near == box)
        return pm_case_fail(c->file, path,
                            "give either \"nearest\": [x, y] (one particle) or \"min\" and \"max\" (the particles in "
                            "that box)",
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
    json_t *f = json_object_get(o, "force");
    jr_join(fp, sizeof fp, path, "force");
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
