/* Particle pictures of a field (pmech/render.h): the field's values from particles in memory or from a
 * frame read back, handed to the one drawing routine (io/picture.c). */
#include "pmech/render.h"

#include "io/particle_fields.h"
#include "io/picture.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const struct field_info {
    const char *name, *unit;
} fields[] = {
    [PM_FIELD_BODY] = {"body", ""},
    [PM_FIELD_SPEED] = {"speed", "m/s"},
    [PM_FIELD_PRESSURE] = {"pressure", "Pa"},
    [PM_FIELD_PLASTIC_STRAIN] = {"plastic_strain", "-"},
    [PM_FIELD_SYY] = {"syy", "Pa"},
    [PM_FIELD_DISPLACEMENT] = {"displacement", "m"},
    [PM_FIELD_Q] = {"q", "Pa"},
    [PM_FIELD_VOLUMETRIC_STRAIN] = {"volumetric_strain", "-"},
    [PM_FIELD_DEVIATORIC_STRAIN] = {"deviatoric_strain", "-"},
    [PM_FIELD_SXX] = {"sxx", "Pa"},
    [PM_FIELD_SZZ] = {"szz", "Pa"},
    [PM_FIELD_SXY] = {"sxy", "Pa"},
    [PM_FIELD_MATERIAL] = {"material", ""},
    [PM_FIELD_GRID_SPEED] = {"grid_speed", "m/s"},
};
#define N_FIELDS ((int)(sizeof fields / sizeof fields[0]))

int pm_field_from_name(const char *name)
{
    for (int k = 0; name && k < N_FIELDS; k++)
        if (!strcmp(name, fields[k].name))
            return k;
    return -1;
}

const char *pm_field_name(pm_field f) { return (int)f >= 0 && (int)f < N_FIELDS ? fields[f].name : "?"; }

const char *pm_field_unit(pm_field f) { return (int)f >= 0 && (int)f < N_FIELDS ? fields[f].unit : ""; }

const char *const *pm_field_names(void)
{
    static const char *names[N_FIELDS + 1];
    if (!names[0])
        for (int k = 0; k < N_FIELDS; k++)
            names[k] = fields[k].name;
    return names;
}

static int is_category(pm_field f) { return f == PM_FIELD_BODY || f == PM_FIELD_MATERIAL; }

/* Length of one particle's vector (PM_DIM entries). */
static double norm_of(const double *a)
{
    double s = 0;
    for (int d = 0; d < PM_DIM; d++)
        s += a[d] * a[d];
    return sqrt(s);
}

/* The field's value at particle i. */
static double particle_value(const pm_particles *p, size_t i, pm_field f)
{
    const double *s = p->stress + PM_NS * i;
    double vol, dev;
    switch (f) {
    case PM_FIELD_BODY: return p->body[i];
    case PM_FIELD_MATERIAL: return p->material[i];
    case PM_FIELD_SPEED: return norm_of(p->v + PM_DIM * i);
    case PM_FIELD_GRID_SPEED: return norm_of(p->v_grid + PM_DIM * i);
    case PM_FIELD_PRESSURE: return pm_pf_pressure(s);
    case PM_FIELD_PLASTIC_STRAIN: return p->eps_p[i];
    case PM_FIELD_SYY: return s[PM_SYY];
    case PM_FIELD_SXX: return s[PM_SXX];
    case PM_FIELD_SZZ: return s[PM_SZZ];
    case PM_FIELD_SXY: return s[PM_SXY];
    case PM_FIELD_Q: return pm_pf_q(s);
    case PM_FIELD_VOLUMETRIC_STRAIN:
    case PM_FIELD_DEVIATORIC_STRAIN:
        pm_pf_log_strain(p->F + PM_NF * i, &vol, &dev);
        return f == PM_FIELD_VOLUMETRIC_STRAIN ? vol : dev;
    default: return hypot(p->x[PM_DIM * i] - p->x0[PM_DIM * i], p->x[PM_DIM * i + 1] - p->x0[PM_DIM * i + 1]);
    }
}

/* Smallest and largest finite entry; 0 when there is none. */
static int finite_range(const double *v, size_t n, double r[2])
{
    r[0] = INFINITY;
    r[1] = -INFINITY;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i])) {
            r[0] = fmin(r[0], v[i]);
            r[1] = fmax(r[1], v[i]);
        }
    return r[0] <= r[1];
}

/* A range a colour bar can show: a single value is widened around itself. */
static void widen(double r[2])
{
    if (r[1] > r[0])
        return;
    const double d = r[0] != 0 ? 0.01 * fabs(r[0]) : 1.0;
    r[0] -= d;
    r[1] += d;
}

int pm_field_range(const pm_particles *p, pm_field field, double range[2])
{
    if ((int)field < 0 || (int)field >= N_FIELDS || is_category(field))
        return pm_error_set(PM_EINPUT, "field %d has no range (a category or unknown)", (int)field);
    range[0] = INFINITY;
    range[1] = -INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        const double v = particle_value(p, i, field);
        if (isfinite(v)) {
            range[0] = fmin(range[0], v);
            range[1] = fmax(range[1], v);
        }
    }
    if (!(range[0] <= range[1]))
        return pm_error_set(PM_EINPUT, "field %s: no finite value over %zu particles", fields[field].name, p->n);
    return PM_OK;
}

/* The options' range, or the values' own (widened when single). */
static int pick_range(const pm_render_opts *o, const double *v, size_t n, const char *name, double r[2])
{
    if (o && o->range) {
        r[0] = o->range[0];
        r[1] = o->range[1];
        if (!(r[1] > r[0]) || !isfinite(r[0]) || !isfinite(r[1]))
            return pm_error_set(PM_EINPUT, "picture of %s: range [%g, %g]; allowed: finite lo < hi", name, r[0], r[1]);
        return PM_OK;
    }
    if (!finite_range(v, n, r))
        r[0] = r[1] = 0;
    widen(r);
    return PM_OK;
}

static void fill_common(pm_picture *pic, const pm_render_opts *o, const char *name, const char *unit)
{
    pic->width = o && o->width > 0 ? o->width : 800;
    pic->title = o ? o->title : NULL;
    pic->time = o && o->show_time ? o->time : NAN;
    pic->field = name;
    pic->unit = unit;
    pic->axisymmetric = o ? o->axisymmetric : 0;
}

int pm_render_field(const char *png, const pm_grid *g, const pm_particles *p, pm_field field,
                    const pm_render_opts *o)
{
    if ((int)field < 0 || (int)field >= N_FIELDS)
        return pm_error_set(PM_EINPUT, "picture %s: unknown field %d", png, (int)field);
    double *v = malloc((p->n ? p->n : 1) * sizeof *v);
    if (!v)
        return pm_error_set(PM_ENOMEM, "out of memory drawing %s", png);
    for (size_t i = 0; i < p->n; i++)
        v[i] = particle_value(p, i, field);
    pm_picture pic;
    memset(&pic, 0, sizeof pic);
    pic.n = p->n;
    pic.x = p->x;
    pic.x_stride = PM_DIM;
    pic.F = p->F;
    pic.hsize = p->hsize;
    const int cat = is_category(field);
    pic.value = cat ? NULL : v;
    pic.category = cat ? v : NULL;
    memcpy(pic.lo, g->lo, sizeof pic.lo);
    memcpy(pic.hi, g->hi, sizeof pic.hi);
    fill_common(&pic, o, fields[field].name, fields[field].unit);
    int rc = cat ? PM_OK : pick_range(o, v, p->n, fields[field].name, pic.range);
    if (!rc)
        rc = pm_picture_write(png, &pic);
    free(v);
    return rc;
}

int pm_render_particles(const char *path, const pm_grid *g, const pm_particles *p, pm_field field, int width,
                        const char *title)
{
    const pm_render_opts o = {.width = width, .title = title};
    return pm_render_field(path, g, p, field, &o);
}

/* ---- frames read back ----------------------------------------------------------------------- */

static const char *array_unit(const char *array)
{
    static const struct {
        const char *array, *unit;
    } units[] = {{"displacement", "m"},         {"velocity", "m/s"},          {"grid_velocity", "m/s"},
                 {"stress", "Pa"},              {"pressure", "Pa"},           {"q", "Pa"},
                 {"plastic_strain", "-"},       {"volumetric_strain", "-"},   {"deviatoric_strain", "-"},
                 {"half_size", "m"},            {"deformation_gradient", "-"}};
    for (size_t k = 0; k < sizeof units / sizeof units[0]; k++)
        if (!strcmp(array, units[k].array))
            return units[k].unit;
    return "";
}

/* Index of component @p name of an array of @p nc components, or -1. */
static int component_index(const char *array, int nc, const char *name)
{
    static const char *const vec[] = {"x", "y", "z"}, *const sig[] = {"xx", "yy", "zz", "xy"},
                             *const def[] = {"xx", "xy", "yx", "yy", "zz"};
    const char *const *names = vec;
    int n = nc <= 3 ? nc : 0;
    if (!strcmp(array, "stress")) {
        names = sig;
        n = nc == 4 ? 4 : 0;
    } else if (!strcmp(array, "deformation_gradient")) {
        names = def;
        n = nc == 5 ? 5 : 0;
    }
    for (int k = 0; k < n; k++)
        if (!strcmp(name, names[k]))
            return k;
    return -1;
}

static int unknown_field(const pm_frame *f, const char *field)
{
    char list[1024] = "";
    const char *const *names = pm_field_names();
    for (size_t k = 0; names[k]; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", names[k]);
    for (size_t k = 0; k < pm_frame_n_arrays(f); k++) {
        const char *a = pm_frame_array_name(f, k, NULL);
        if (pm_field_from_name(a) < 0)
            snprintf(list + strlen(list), sizeof list - strlen(list), ", %s", a);
    }
    return pm_error_set(PM_EINPUT, "field '%s': not in this frame; allowed: %s, or ARRAY.COMPONENT (velocity.y, "
                        "stress.xy)", field, list);
}

int pm_frame_field(const pm_frame *f, const char *field, double *out, const char **unit, int *category)
{
    static const struct {
        pm_field f;
        const char *array;
        int comp; /* -1: magnitude, -2: the scalar itself */
    } map[] = {{PM_FIELD_BODY, "body", -2},       {PM_FIELD_MATERIAL, "material", -2}, {PM_FIELD_SPEED, "velocity", -1},
               {PM_FIELD_GRID_SPEED, "grid_velocity", -1},
               {PM_FIELD_DISPLACEMENT, "displacement", -1}, {PM_FIELD_SXX, "stress", 0}, {PM_FIELD_SYY, "stress", 1},
               {PM_FIELD_SZZ, "stress", 2},       {PM_FIELD_SXY, "stress", 3}};
    const size_t n = pm_frame_n_points(f);
    const int fid = pm_field_from_name(field);
    char array[128];
    int comp = -2;
    snprintf(array, sizeof array, "%s", field);
    for (size_t k = 0; fid >= 0 && k < sizeof map / sizeof map[0]; k++)
        if ((int)map[k].f == fid) {
            snprintf(array, sizeof array, "%s", map[k].array);
            comp = map[k].comp;
        }
    char *dot = fid < 0 ? strchr(array, '.') : NULL;
    if (dot)
        *dot = '\0';
    int nc = 0;
    const double *a = pm_frame_array(f, array, &nc);
    if (!a)
        return unknown_field(f, field);
    if (dot) {
        comp = component_index(array, nc, dot + 1);
        if (comp < 0)
            return unknown_field(f, field);
    }
    if (comp == -2 && nc > 1)
        comp = -1;
    for (size_t i = 0; i < n; i++) {
        const double *ai = a + (size_t)nc * i;
        if (comp >= 0) {
            out[i] = ai[comp];
        } else if (comp == -1) {
            double s = 0;
            for (int k = 0; k < nc; k++)
                s += ai[k] * ai[k];
            out[i] = sqrt(s);
        } else {
            out[i] = ai[0];
        }
    }
    if (unit)
        *unit = fid >= 0 ? fields[fid].unit : array_unit(array);
    if (category)
        *category = fid >= 0 && is_category((pm_field)fid);
    return PM_OK;
}

int pm_render_frame(const char *png, const pm_frame *f, const double lo[2], const double hi[2], const char *field,
                    const pm_render_opts *o)
{
    const size_t n = pm_frame_n_points(f);
    double *v = malloc((n ? n : 1) * sizeof *v);
    if (!v)
        return pm_error_set(PM_ENOMEM, "out of memory drawing %s", png);
    const char *unit = "";
    int cat = 0;
    int rc = pm_frame_field(f, field, v, &unit, &cat);
    pm_picture pic;
    memset(&pic, 0, sizeof pic);
    int nc = 0;
    pic.n = n;
    pic.x = pm_frame_points(f);
    pic.x_stride = 3;
    pic.F = pm_frame_array(f, "deformation_gradient", &nc);
    if (nc != PM_NF)
        pic.F = NULL;
    pic.hsize = pm_frame_array(f, "half_size", &nc);
    if (nc != PM_DIM)
        pic.hsize = NULL;
    pic.value = cat ? NULL : v;
    pic.category = cat ? v : NULL;
    memcpy(pic.lo, lo, sizeof pic.lo);
    memcpy(pic.hi, hi, sizeof pic.hi);
    fill_common(&pic, o, field, unit);
    if (!rc && !cat)
        rc = pick_range(o, v, n, field, pic.range);
    if (!rc)
        rc = pm_picture_write(png, &pic);
    free(v);
    return rc;
}
