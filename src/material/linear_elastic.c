/*
 * linear_elastic: isotropic hypo-elasticity, sigma_{n+1} = Q sigma_n Q^T + D : deps, with the
 * Hughes-Winget rotation Q and mid-step strain increment deps (exact for rigid rotations).
 * No history variables; the tangent is D. Allocation-free and without eigen-decompositions:
 * this is the explicit solver's hot path.
 */
#include "material/material_internal.h"

#include "pmech/error.h"

static int le_update(const pm_material *m, const pm_material_step *in, double *state,
                     double stress[6], double *tangent)
{
    (void)state;
    double de[6];
    pm_hughes_winget(in->F_incr, stress, de);
    const double K = m->K, G = m->G;
    const double ev = de[0] + de[1] + de[2];
    const double lam = (K - 2.0 * G / 3.0) * ev, g2 = 2.0 * G;
    stress[0] += lam + g2 * de[0];
    stress[1] += lam + g2 * de[1];
    stress[2] += lam + g2 * de[2];
    stress[3] += G * de[3];
    stress[4] += G * de[4];
    stress[5] += G * de[5];
    if (tangent)
        pm_elastic_stiffness(K, G, tangent);
    if (!(stress[0] == stress[0]) || !(stress[3] == stress[3]))
        return PM_ESIM;
    return PM_OK;
}

const pm_material_ops pm_linear_elastic_ops = {
    .name = "linear_elastic",
    .elastic_pair = 1,
    .n_params = 0,
    .params = NULL,
    .n_state = 0,
    .init = NULL,
    .init_state = NULL,
    .update = le_update,
    .wave_speed = pm_material_elastic_wave_speed,
    .plastic_strain = NULL,
    .strain_energy = pm_material_elastic_energy,
    .reduce_strength = NULL,
};
