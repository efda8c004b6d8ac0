/*
 * The Coulomb strength, friction and cohesion, of the models that have one: the checks of its
 * parameters, and what strength reduction divides (Griffiths & Lane 1999). Friction is reduced
 * through its tangent, the coefficient that multiplies the normal stress, so that c and tan(phi)
 * fall by the same factor.
 */
#include "material/material_internal.h"

#include "pmech/error.h"

int pm_check_coulomb_strength(double c, double phi, double psi)
{
    if (!(c >= 0))
        return pm_error_set(PM_EINPUT, "cohesion = %g: must be >= 0", c);
    if (!(phi >= 0 && phi < 90))
        return pm_error_set(PM_EINPUT, "friction_angle = %g: must be in [0, 90)", phi);
    if (!(psi >= 0 && psi <= phi))
        return pm_error_set(PM_EINPUT, "dilatancy_angle = %g: must be in [0, friction_angle = %g]", psi, phi);
    return PM_OK;
}

static double reduce_angle(double deg, double factor)
{
    return atan(tan(deg * M_PI / 180.0) / factor) * 180.0 / M_PI;
}

int pm_reduce_coulomb_strength(pm_material *m, double factor)
{
    const int ic = pm_material_param_index(m->ops, "cohesion");
    const int iphi = pm_material_param_index(m->ops, "friction_angle");
    const int ipsi = pm_material_param_index(m->ops, "dilatancy_angle");
    const int it = pm_material_param_index(m->ops, "tension_cutoff");
    if (ic < 0 || iphi < 0 || ipsi < 0)
        return pm_error_set(PM_EINTERNAL, "material model %s lacks cohesion, friction_angle or dilatancy_angle",
                            m->ops->name);
    const double psi = reduce_angle(m->param[ipsi], factor);
    m->param[ic] = m->param[ic] / factor;
    m->param[iphi] = reduce_angle(m->param[iphi], factor);
    /* the models require psi <= phi; reducing both tangents by F keeps that, rounding aside */
    m->param[ipsi] = fmin(psi, m->param[iphi]);
    if (it >= 0 && !isnan(m->param[it]))
        m->param[it] = m->param[it] / factor;
    return PM_OK;
}
