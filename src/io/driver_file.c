/* `pmech material` driver files (docs/input.md, "Material-point driver files") to pm_driver. */
#include "pmech/case.h"

#include "io/json_read.h"
#include "io/material_read.h"
#include "pmech/error.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const driver_keys[] = {"material", "initial_stress", "path", NULL};
static const char *const path_types[] = {"triaxial", "oedometer", "simple_shear", "strain_increments", NULL};

static int parse_path(const char *file, json_t *p, pm_driver *d)
{
    jr_ctx cx = {file, "path"};
    if (!json_is_object(p))
        return pm_error_set(PM_EINPUT, "%s: path: expected an object, got %s", file, jr_type(p));
    int t;
    pm_check(jr_enum(&cx, p, "type", JR_REQUIRED, path_types, 0, &t));
    d->path = (pm_path_type)t;
    static const char *const tri[] = {"type", "confining_pressure", "axial_strain", "steps", "dt", NULL};
    static const char *const oed[] = {"type", "axial_strain", "steps", "dt", NULL};
    static const char *const shr[] = {"type", "shear_strain", "steps", "dt", NULL};
    static const char *const inc[] = {"type", "increments", "dt", NULL};
    const char *const *keys = t == 0 ? tri : t == 1 ? oed : t == 2 ? shr : inc;
    pm_check(jr_only_keys(&cx, p, keys));
    long steps;
    pm_check(jr_int(&cx, p, "steps", 0, 100, 1, 100000000, &steps));
    d->steps = (int)steps;
    pm_check(jr_number(&cx, p, "dt", 0, 1e-3, &d->dt));
    pm_check(jr_range(&cx, "dt", d->dt, 0, 1, INFINITY, 0));
    switch (d->path) {
    case PM_PATH_TRIAXIAL:
        pm_check(jr_number(&cx, p, "confining_pressure", JR_REQUIRED, 0, &d->confining_pressure));
        pm_check(jr_range(&cx, "confining_pressure", d->confining_pressure, 0, 1, INFINITY, 0));
        pm_check(jr_number(&cx, p, "axial_strain", JR_REQUIRED, 0, &d->axial_strain));
        pm_check(jr_range(&cx, "axial_strain", d->axial_strain, -1, 1, 1, 1));
        break;
    case PM_PATH_OEDOMETER:
        pm_check(jr_number(&cx, p, "axial_strain", JR_REQUIRED, 0, &d->axial_strain));
        pm_check(jr_range(&cx, "axial_strain", d->axial_strain, -1, 1, 1, 1));
        break;
    case PM_PATH_SIMPLE_SHEAR:
        pm_check(jr_number(&cx, p, "shear_strain", JR_REQUIRED, 0, &d->shear_strain));
        break;
    default: {
        json_t *inc_list = json_object_get(p, "increments");
        if (!inc_list)
            return pm_error_set(PM_EINPUT, "%s: path.increments: required key is missing", file);
        if (!json_is_array(inc_list) || json_array_size(inc_list) == 0 || json_array_size(inc_list) > 100000000)
            return pm_error_set(PM_EINPUT, "%s: path.increments: expected a non-empty list of [dexx, deyy, dezz, dgxy], "
                                "got %s", file, jr_text(inc_list));
        d->n_increments = json_array_size(inc_list);
        d->increments = malloc(4 * d->n_increments * sizeof(double));
        if (!d->increments)
            return pm_error_set(PM_ENOMEM, "out of memory");
        for (size_t k = 0; k < d->n_increments; k++) {
            json_t *e = json_array_get(inc_list, k);
            int ok = json_is_array(e) && json_array_size(e) == 4;
            for (size_t q = 0; ok && q < 4; q++) {
                json_t *x = json_array_get(e, q);
                ok = json_is_number(x) && isfinite(json_number_value(x));
                if (ok)
                    d->increments[4 * k + q] = json_number_value(x);
            }
            if (!ok)
                return pm_error_set(PM_EINPUT, "%s: path.increments[%zu]: expected [dexx, deyy, dezz, dgxy], got %s",
                                    file, k, jr_text(e));
        }
        d->steps = (int)d->n_increments;
    }
    }
    return PM_OK;
}

static int parse_driver(const char *file, json_t *root, pm_driver *d)
{
    jr_ctx cx = {file, ""};
    if (!json_is_object(root))
        return pm_error_set(PM_EINPUT, "%s: a driver file must be a JSON object, got %s", file, jr_type(root));
    pm_check(jr_only_keys(&cx, root, driver_keys));
    json_t *m = json_object_get(root, "material");
    if (!m)
        return pm_error_set(PM_EINPUT, "%s: material: required key is missing", file);
    pm_check(pm_read_material(file, "material", m, 0, &d->material));
    json_t *p = json_object_get(root, "path");
    if (!p)
        return pm_error_set(PM_EINPUT, "%s: path: required key is missing", file);
    pm_check(parse_path(file, p, d));
    if (json_object_get(root, "initial_stress")) {
        pm_check(jr_vecn(&cx, root, "initial_stress", 0, 4, d->stress0));
    } else if (d->path == PM_PATH_TRIAXIAL) {
        d->stress0[0] = d->stress0[1] = d->stress0[2] = -d->confining_pressure;
    }
    return PM_OK;
}

int pm_driver_load(const char *path, pm_driver *d)
{
    memset(d, 0, sizeof *d);
    json_error_t err;
    json_t *root = json_load_file(path, JSON_REJECT_DUPLICATES, &err);
    if (!root) {
        if (err.line < 0)
            return pm_error_set(PM_EINPUT, "%s: cannot read the driver file: %s", path, err.text);
        return pm_error_set(PM_EINPUT, "%s:%d:%d: %s", path, err.line, err.column, err.text);
    }
    int rc = parse_driver(path, root, d);
    json_decref(root);
    return rc;
}

void pm_driver_free(pm_driver *d)
{
    free(d->increments);
    memset(d, 0, sizeof *d);
}
