#include "io/material_read.h"

#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const elastic_keys[] = {"youngs_modulus", "poisson_ratio", "bulk_modulus", "shear_modulus"};

int pm_read_material(const char *file, const char *path, json_t *obj, int need_name, pm_material *m)
{
    jr_ctx cx = {file, path};
    memset(m, 0, sizeof *m);
    if (!json_is_object(obj))
        return pm_error_set(PM_EINPUT, "%s: %s: expected a material object, got %s", file, path, jr_type(obj));
    pm_check(jr_string(&cx, obj, "name", need_name ? JR_REQUIRED : 0, "material", m->name, sizeof m->name));
    int model;
    pm_check(jr_enum(&cx, obj, "model", JR_REQUIRED, pm_material_names(), 0, &model));
    m->ops = pm_material_find(pm_material_names()[model]);
    /* allowed keys: name, model, density, the elastic pair, the model's parameters */
    const char *allowed[8 + PM_MAT_MAX_PARAMS];
    size_t na = 0;
    allowed[na++] = "name";
    allowed[na++] = "model";
    allowed[na++] = "density";
    if (m->ops->elastic_pair)
        for (int k = 0; k < 4; k++)
            allowed[na++] = elastic_keys[k];
    for (size_t k = 0; k < m->ops->n_params && na + 1 < sizeof allowed / sizeof allowed[0]; k++)
        allowed[na++] = m->ops->params[k].key;
    allowed[na] = NULL;
    pm_check(jr_only_keys(&cx, obj, allowed));
    pm_check(jr_number(&cx, obj, "density", JR_REQUIRED, 0, &m->density));
    pm_check(jr_range(&cx, "density", m->density, 0, 1, INFINITY, 0));
    if (m->ops->elastic_pair) {
        double v[4];
        for (int k = 0; k < 4; k++)
            pm_check(jr_number(&cx, obj, elastic_keys[k], 0, NAN, &v[k]));
        if (pm_material_set_elastic(m, v[0], v[1], v[2], v[3]) != PM_OK) {
            /* the model's message names the key; give it its path */
            char msg[1024];
            snprintf(msg, sizeof msg, "%s", pm_error_message());
            const char *key = NULL;
            for (int k = 0; k < 4 && !key; k++)
                if (strstr(msg, elastic_keys[k]) == msg)
                    key = elastic_keys[k];
            if (key)
                return pm_error_set(PM_EINPUT, "%s: %s.%s", file, path, msg);
            return pm_error_set(PM_EINPUT, "%s: %s: %s", file, path, msg);
        }
    }
    for (size_t k = 0; k < m->ops->n_params; k++) {
        const pm_param_spec *ps = &m->ops->params[k];
        unsigned fl = ps->flags & PM_PARAM_REQUIRED ? JR_REQUIRED : 0;
        pm_check(jr_number(&cx, obj, ps->key, fl, ps->def, &m->param[k]));
        if (json_object_get(obj, ps->key))
            pm_check(jr_range(&cx, ps->key, m->param[k], ps->lo, !!(ps->flags & PM_PARAM_LO_OPEN), ps->hi,
                              !!(ps->flags & PM_PARAM_HI_OPEN)));
    }
    if (m->ops->init && m->ops->init(m) != PM_OK) {
        char msg[1024];
        snprintf(msg, sizeof msg, "%s", pm_error_message());
        return pm_error_set(PM_EINPUT, "%s: %s.%s", file, path, msg);
    }
    return PM_OK;
}
