/* Warnings for values a case file accepts but that are almost surely mistakes: the usual ones are
 * units (a modulus in MPa or kPa written as a number of pascals, an angle in radians). Each names the
 * key path, the value and the likely intent; none is an error, since each value can be meant. */
#include "pmech/case.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#define STIFFNESS_MIN 1e3 /* Pa: softer than any soil or rock in the problems pmech is for */
#define ANGLE_MAX 2.0     /* degrees: below this a friction or dilatancy angle is likely in radians */

typedef struct sink {
    char (*out)[PM_WARNING_LEN];
    size_t cap, n;
} sink;

static void add(sink *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void add(sink *s, const char *fmt, ...)
{
    if (s->n < s->cap) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(s->out[s->n], PM_WARNING_LEN, fmt, ap);
        va_end(ap);
    }
    s->n++;
}

/* Young's modulus below 1 kPa, named by the key the case gave it with (E itself, or the bulk and shear
 * pair it was computed from). */
static void stiffness(sink *s, const pm_case *c, size_t k)
{
    const pm_material *m = &c->materials[k];
    if (!m->ops || !m->ops->elastic_pair || !(m->E > 0 && m->E < STIFFNESS_MIN))
        return;
    json_t *jm = c->doc ? json_array_get(json_object_get(c->doc, "materials"), k) : NULL;
    if (jm && !json_object_get(jm, "youngs_modulus") && json_object_get(jm, "shear_modulus"))
        add(s, "%s: materials[%zu] '%s': bulk_modulus %g Pa and shear_modulus %g Pa give a Young's modulus of %g Pa, "
            "below 1 kPa: moduli are in pascals", c->file, k, m->name, m->K, m->G, m->E);
    else
        add(s, "%s: materials[%zu].youngs_modulus of '%s' is %g Pa, below 1 kPa: moduli are in pascals (%g MPa is %g)",
            c->file, k, m->name, m->E, m->E, m->E * 1e6);
}

static void angles(sink *s, const pm_case *c, size_t k)
{
    const pm_material *m = &c->materials[k];
    for (size_t j = 0; m->ops && j < m->ops->n_params; j++) {
        const pm_param_spec *ps = &m->ops->params[j];
        const double a = m->param[j];
        if ((ps->flags & PM_PARAM_ANGLE) && a > 0 && a < ANGLE_MAX)
            add(s, "%s: materials[%zu].%s of '%s' is %g degrees: angles are in degrees; in radians %g would be "
                "%.4g degrees", c->file, k, ps->key, m->name, a, a, a * 180.0 / M_PI);
    }
}

/* apart_measure "cell" acts through a material's density_state (granular), and that only where a point
 * reads looser than the material's max_void_ratio: without one of those the key does nothing */
static void apart_measure(sink *s, const pm_case *c)
{
    if (!c->analysis.apart_from_cell)
        return;
    int granular = 0;
    for (size_t k = 0; k < c->n_materials && c->materials; k++) {
        const pm_material *m = &c->materials[k];
        if (!m->ops || !m->ops->density_state)
            continue;
        granular = 1;
        if (pm_material_param_index(m->ops, "max_void_ratio") < 0 || isfinite(pm_material_param(m, "max_void_ratio")))
            return;
    }
    if (!granular)
        add(s, "%s: analysis.apart_measure is \"cell\", but no material takes its state from the positions' "
            "density (only 'granular' does): the key changes nothing", c->file);
    else
        add(s, "%s: analysis.apart_measure is \"cell\", but no granular material sets max_void_ratio: the "
            "positions loosen a granular state only where it reads looser than that, so the key changes nothing",
            c->file);
}

size_t pm_case_warnings(const pm_case *c, char (*out)[PM_WARNING_LEN], size_t cap)
{
    sink s = {out, cap, 0};
    apart_measure(&s, c);
    for (size_t k = 0; k < c->n_materials && c->materials; k++) {
        stiffness(&s, c, k);
        angles(&s, c, k);
    }
    for (size_t b = 0; b < c->n_bodies && c->bodies; b++)
        if (c->bodies[b].stress0 == PM_STRESS0_GEOSTATIC && c->analysis.gravity[1] > 0)
            add(&s, "%s: analysis.gravity [%g, %g] points up (+y), but bodies[%zu] ('%s') starts from a "
                "geostatic stress, which assumes gravity pointing down", c->file, c->analysis.gravity[0],
                c->analysis.gravity[1], b, c->bodies[b].name);
    return s.n;
}
