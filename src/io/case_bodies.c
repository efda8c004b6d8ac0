/* materials and bodies of a case: names, shapes, seeding options and initial stress. */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "io/material_read.h"
#include "pmech/error.h"
#include "pmech/grid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const shape_types[] = {"rectangle", "polygon", "circle", "gmsh_group", NULL};

int pm_case_parse_materials(pm_case *c, json_t *ms)
{
    if (!ms)
        return pm_case_fail(c->file, "materials", "required key is missing", NULL);
    if (!json_is_array(ms))
        return pm_error_set(PM_EINPUT, "%s: materials: expected a list of materials, got %s", c->file, jr_type(ms));
    if (json_array_size(ms) == 0)
        return pm_case_fail(c->file, "materials", "the list is empty; give at least one material", NULL);
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

int pm_case_parse_shape(pm_case *c, const char *path, json_t *sh, pm_shape *s)
{
    jr_ctx cx = {c->file, path};
    if (!json_is_object(sh))
        return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(sh));
    int v;
    pm_check(jr_enum(&cx, sh, "type", JR_REQUIRED, shape_types, 0, &v));
    s->type = (pm_shape_type)v;
    switch (s->type) {
    case PM_SHAPE_RECTANGLE:
        pm_check(jr_only_keys(&cx, sh, pm_case_keys(PM_KEYS_SHAPE_RECTANGLE)));
        pm_check(jr_vec2(&cx, sh, "min", JR_REQUIRED, NULL, s->min));
        pm_check(jr_vec2(&cx, sh, "max", JR_REQUIRED, NULL, s->max));
        if (!(s->min[0] < s->max[0] && s->min[1] < s->max[1]))
            return pm_error_set(PM_EINPUT, "%s: %s: min [%g, %g] must be below and left of max [%g, %g]", c->file, path,
                                s->min[0], s->min[1], s->max[0], s->max[1]);
        break;
    case PM_SHAPE_CIRCLE:
        pm_check(jr_only_keys(&cx, sh, pm_case_keys(PM_KEYS_SHAPE_CIRCLE)));
        pm_check(jr_vec2(&cx, sh, "center", JR_REQUIRED, NULL, s->center));
        pm_check(jr_number(&cx, sh, "radius", JR_REQUIRED, 0, &s->radius));
        pm_check(jr_range(&cx, "radius", s->radius, 0, 1, INFINITY, 0));
        break;
    case PM_SHAPE_POLYGON: {
        pm_check(jr_only_keys(&cx, sh, pm_case_keys(PM_KEYS_SHAPE_POLYGON)));
        json_t *pts = json_object_get(sh, "points");
        char pp[256];
        jr_join(pp, sizeof pp, path, "points");
        if (!pts)
            return pm_case_fail(c->file, pp, "required key is missing", NULL);
        if (!json_is_array(pts) || json_array_size(pts) < 3 || json_array_size(pts) > 1000000)
            return pm_error_set(PM_EINPUT, "%s: %s: expected a list of at least 3 points [x, y], got %s", c->file, pp,
                                jr_text(pts));
        s->n_points = json_array_size(pts);
        s->points = malloc(PM_DIM * s->n_points * sizeof(double));
        if (!s->points)
            return pm_error_set(PM_ENOMEM, "out of memory");
        for (size_t k = 0; k < s->n_points; k++) {
            json_t *p = json_array_get(pts, k);
            json_t *x = json_array_get(p, 0), *y = json_array_get(p, 1);
            if (!json_is_array(p) || json_array_size(p) != PM_DIM || !json_is_number(x) || !json_is_number(y) ||
                !isfinite(json_number_value(x)) || !isfinite(json_number_value(y)))
                return pm_error_set(PM_EINPUT, "%s: %s[%zu]: expected a point [x, y], got %s", c->file, pp, k,
                                    jr_text(p));
            s->points[PM_DIM * k] = json_number_value(x);
            s->points[PM_DIM * k + 1] = json_number_value(y);
        }
        pm_check(pm_case_check_polygon(c, pp, s));
        break;
    }
    default:
        pm_check(jr_only_keys(&cx, sh, pm_case_keys(PM_KEYS_SHAPE_GMSH_GROUP)));
        pm_check(jr_string(&cx, sh, "name", JR_REQUIRED, NULL, s->group, sizeof s->group));
        if (c->grid.type != PM_GRID_GMSH)
            return pm_case_fail(c->file, path, "type gmsh_group needs a grid of type gmsh", NULL);
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
            return pm_case_fail(c->file, path, "k0 and surface_y go with \"initial_stress\": \"geostatic\"", NULL);
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
        return pm_case_fail(c->file, path, "k0 and surface_y go with \"initial_stress\": \"geostatic\"", NULL);
    body->stress0 = PM_STRESS0_CONSTANT;
    return jr_vecn(&cx, b, "initial_stress", 0, 4, body->stress0_value);
}

void pm_case_shape_box(const pm_shape *s, double lo[PM_DIM], double hi[PM_DIM])
{
    if (s->type == PM_SHAPE_RECTANGLE) {
        memcpy(lo, s->min, PM_DIM * sizeof(double));
        memcpy(hi, s->max, PM_DIM * sizeof(double));
    } else if (s->type == PM_SHAPE_CIRCLE) {
        for (int d = 0; d < PM_DIM; d++) {
            lo[d] = s->center[d] - s->radius;
            hi[d] = s->center[d] + s->radius;
        }
    } else if (s->type == PM_SHAPE_POLYGON) {
        for (int d = 0; d < PM_DIM; d++)
            lo[d] = hi[d] = s->points[d];
        for (size_t k = 1; k < s->n_points; k++)
            for (int d = 0; d < PM_DIM; d++) {
                lo[d] = fmin(lo[d], s->points[PM_DIM * k + d]);
                hi[d] = fmax(hi[d], s->points[PM_DIM * k + d]);
            }
    } else {
        for (int d = 0; d < PM_DIM; d++)
            lo[d] = hi[d] = NAN;
    }
}

/* A name must not repeat among the bodies and sources before it: output, probes and pictures tell
 * bodies and sources apart by it. */
static int check_unique_name(const pm_case *c, const char *path, const char *name, size_t n_bodies)
{
    for (size_t j = 0; j < n_bodies; j++)
        if (!strcmp(c->bodies[j].name, name))
            return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" is already the name of bodies[%zu]", c->file, path,
                                name, j);
    for (size_t j = 0; j < c->n_sources; j++)
        if (!strcmp(c->sources[j].body.name, name))
            return pm_error_set(PM_EINPUT, "%s: %s.name: \"%s\" is already the name of sources[%zu]", c->file, path,
                                name, j);
    return PM_OK;
}

int pm_case_parse_body(pm_case *c, const char *path, json_t *b, const char *def_name, size_t n_before,
                       pm_case_body *body)
{
    jr_ctx cx = {c->file, path};
    pm_check(jr_string(&cx, b, "name", 0, def_name, body->name, sizeof body->name));
    pm_check(check_unique_name(c, path, body->name, n_before));
    char mat[PM_NAME_MAX];
    pm_check(jr_string(&cx, b, "material", JR_REQUIRED, NULL, mat, sizeof mat));
    pm_check(find_material(c, path, mat, &body->material));
    json_t *sh = json_object_get(b, "shape");
    char sp[96];
    jr_join(sp, sizeof sp, path, "shape");
    if (!sh)
        return pm_case_fail(c->file, sp, "required key is missing", NULL);
    pm_check(pm_case_parse_shape(c, sp, sh, &body->shape));
    long ppc;
    pm_check(jr_int(&cx, b, "particles_per_cell", 0, 0, 1, 6, &ppc));
    if (c->grid.element == PM_TRI3 && ppc != 0 && ppc != 1 && ppc != 3 && ppc != 6)
        return pm_error_set(PM_EINPUT, "%s: %s.particles_per_cell: got %ld; allowed on tri3 grids: 1, 3 or 6",
                            c->file, path, ppc);
    body->particles_per_cell = (int)ppc;
    const double zero[PM_DIM] = {0, 0};
    pm_check(jr_vec2(&cx, b, "velocity", 0, zero, body->velocity));
    pm_check(parse_initial_stress(c, path, b, body));
    pm_check(jr_string(&cx, b, "contact_group", 0, body->name, body->contact_group, sizeof body->contact_group));
    if (c->grid.type == PM_GRID_RECTANGLE) {
        double lo[PM_DIM], hi[PM_DIM], glo[PM_DIM], ghi[PM_DIM];
        pm_case_shape_box(&body->shape, lo, hi);
        const double tol = 1e-9 * fmax(c->grid.size[0], c->grid.size[1]);
        for (int d = 0; d < PM_DIM; d++) {
            glo[d] = c->grid.origin[d];
            ghi[d] = c->grid.origin[d] + c->grid.size[d];
        }
        if (lo[0] < glo[0] - tol || lo[1] < glo[1] - tol || hi[0] > ghi[0] + tol || hi[1] > ghi[1] + tol)
            return pm_error_set(PM_EINPUT,
                                "%s: %s.shape: the %s spans [%g, %g] x [%g, %g], outside the grid [%g, %g] x "
                                "[%g, %g]; enlarge the grid or move the %s",
                                c->file, path, strncmp(path, "sources", 7) ? "body" : "source", lo[0], hi[0], lo[1],
                                hi[1], glo[0], ghi[0], glo[1], ghi[1],
                                strncmp(path, "sources", 7) ? "body" : "source");
    }
    return PM_OK;
}

int pm_case_parse_bodies(pm_case *c, json_t *bs)
{
    /* a case whose material all comes from sources (a bin filled by portions) may start empty */
    if (!bs && c->n_sources)
        return PM_OK;
    if (!bs)
        return pm_case_fail(c->file, "bodies", "required key is missing", NULL);
    if (!json_is_array(bs) || (json_array_size(bs) == 0 && !c->n_sources))
        return pm_error_set(PM_EINPUT, "%s: bodies: expected a non-empty list of bodies, got %s", c->file,
                            jr_text(bs));
    c->n_bodies = json_array_size(bs);
    c->bodies = calloc(c->n_bodies ? c->n_bodies : 1, sizeof *c->bodies);
    if (!c->bodies)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t i = 0; i < c->n_bodies; i++) {
        char path[64], def[PM_NAME_MAX];
        jr_index(path, sizeof path, "bodies", i);
        jr_ctx cx = {c->file, path};
        json_t *b = json_array_get(bs, i);
        if (!json_is_object(b))
            return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(b));
        pm_check(jr_only_keys(&cx, b, pm_case_keys(PM_KEYS_BODY)));
        snprintf(def, sizeof def, "body%zu", i);
        pm_check(pm_case_parse_body(c, path, b, def, i, &c->bodies[i]));
    }
    return PM_OK;
}
