/*
 * neo_hookean: compressible neo-Hookean hyperelasticity (Simo & Hughes / Bonet & Wood form),
 *   W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
 *   sigma = mu/J (b - I) + lambda ln(J)/J I,      b = F F^T, J = det F,
 * evaluated from the total deformation gradient F_new (the incoming stress is ignored: the
 * model is path-independent, and an initial stress cannot be represented by it).
 * Tangent: the spatial elasticity tensor (Truesdell / Lie rate of the Kirchhoff stress over J)
 *   c = lambda/J 1(x)1 + 2 (mu - lambda ln J)/J I_sym.
 * mu and lambda are the small-strain Lame constants (m->G, m->lambda).
 */
#include "material/material_internal.h"

#include "pmech/error.h"

#include <string.h>

static double det3(const double F[9])
{
    return F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
           F[2] * (F[3] * F[7] - F[4] * F[6]);
}

static int nh_update(const pm_material *m, const pm_material_step *in, double *state,
                     double stress[6], double *tangent)
{
    (void)state;
    const double *F = in->F_new;
    const double J = det3(F);
    if (!(J > 0))
        return PM_ESIM;
    const double mu = m->G, lam = m->lambda, lnJ = log(J), iJ = 1.0 / J;
#define BB(i, j) (F[3 * (i)] * F[3 * (j)] + F[3 * (i) + 1] * F[3 * (j) + 1] + F[3 * (i) + 2] * F[3 * (j) + 2])
    const double pv = (lam * lnJ - mu) * iJ;
    stress[0] = mu * iJ * BB(0, 0) + pv;
    stress[1] = mu * iJ * BB(1, 1) + pv;
    stress[2] = mu * iJ * BB(2, 2) + pv;
    stress[3] = mu * iJ * BB(0, 1);
    stress[4] = mu * iJ * BB(1, 2);
    stress[5] = mu * iJ * BB(0, 2);
#undef BB
    if (tangent) {
        const double a = lam * iJ, g = (mu - lam * lnJ) * iJ;
        memset(tangent, 0, 36 * sizeof(double));
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                tangent[6 * i + j] = a + (i == j ? 2.0 * g : 0.0);
        tangent[21] = tangent[28] = tangent[35] = g;
    }
    return PM_OK;
}

/* P-wave speed of the current tangent: rho c^2 = c_1111 with rho = rho0 / J, i.e.
 * c^2 = (lambda + 2 (mu - lambda ln J)) / rho0, never below the small-strain value. */
static double nh_wave_speed(const pm_material *m, const double *state, double density)
{
    (void)state;
    const double J = m->density > 0 && density > 0 ? m->density / density : 1.0;
    const double lnJ = log(J);
    double c11 = m->lambda + 2.0 * (m->G - m->lambda * lnJ);
    const double c0 = m->lambda + 2.0 * m->G;
    if (c11 < c0)
        c11 = c0;
    const double rho0 = m->density > 0 ? m->density : density;
    return sqrt(c11 / rho0);
}

static double nh_energy(const pm_material *m, const pm_material_step *in, const double *state,
                        const double stress[6])
{
    (void)state;
    (void)stress;
    const double *F = in->F_new;
    const double J = det3(F);
    if (!(J > 0))
        return NAN;
    double I1 = 0;
    for (int i = 0; i < 9; i++)
        I1 += F[i] * F[i];
    const double lnJ = log(J);
    return 0.5 * m->G * (I1 - 3.0) - m->G * lnJ + 0.5 * m->lambda * lnJ * lnJ;
}

const pm_material_ops pm_neo_hookean_ops = {
    .name = "neo_hookean",
    .elastic_pair = 1,
    .n_params = 0,
    .params = NULL,
    .n_state = 0,
    .init = NULL,
    .init_state = NULL,
    .update = nh_update,
    .wave_speed = nh_wave_speed,
    .plastic_strain = NULL,
    .strain_energy = nh_energy,
    .reduce_strength = NULL,
};
