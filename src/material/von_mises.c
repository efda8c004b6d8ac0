/*
 * von_mises: J2 plasticity with linear isotropic hardening, hypo-elastic (Hughes-Winget) frame.
 *   f = q - (sigma_y + H alpha),  q = sqrt(3 J2),  associated (radial) return:
 *   dlambda = f_trial / (3G + H),  s = s_trial (1 - 3G dlambda / q_trial),  alpha += dlambda.
 * State: [0] alpha = equivalent plastic strain.
 */
#include "material/material_internal.h"

#include "pmech/error.h"

#include <string.h>

enum { P_YIELD, P_HARD };

static const pm_param_spec vm_params[] = {
    {"yield_stress", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN, 0.0, INFINITY,
     "initial uniaxial yield stress sigma_y (Pa)"},
    {"hardening_modulus", 0.0, 0, -INFINITY, INFINITY,
     "linear isotropic hardening modulus H = d sigma_y / d eps_p (Pa; negative softens)"},
};

static int vm_init(pm_material *m)
{
    const double H = m->param[P_HARD], sy = m->param[P_YIELD];
    if (!(sy > 0) || !isfinite(sy))
        return pm_error_set(PM_EINPUT, "yield_stress = %g: must be > 0", sy);
    if (!isfinite(H) || !(3.0 * m->G + H > 0))
        return pm_error_set(PM_EINPUT,
                            "hardening_modulus = %g: softening must satisfy 3 G + H > 0 (H > %g)", H,
                            -3.0 * m->G);
    return PM_OK;
}

static int vm_update(const pm_material *m, const pm_material_step *in, double *state,
                     double stress[6], double *tangent)
{
    const double K = m->K, G = m->G, sy = m->param[P_YIELD], H = m->param[P_HARD];
    pm_trial t;
    pm_trial_state(in->F_incr, stress, K, G, &t);
    double alpha = state[0];
    /* the yield stress never softens below zero */
    const double syn = fmax(sy + H * alpha, 0.0);
    const double f = t.q - syn;
    if (!(f > 0)) {
        memcpy(stress, t.sig, 6 * sizeof(double));
        if (tangent)
            pm_elastic_stiffness(K, G, tangent);
        return isfinite(t.q) ? PM_OK : PM_ESIM;
    }
    double Heff = syn > 0 || H > 0 ? H : 0.0;
    double dl = f / (3.0 * G + Heff);
    if (Heff < 0 && sy + H * (alpha + dl) < 0) { /* softened to zero strength within the step */
        Heff = 0.0;
        dl = t.q / (3.0 * G);
    }
    const double ratio = 1.0 - 3.0 * G * dl / t.q;
    for (int i = 0; i < 6; i++)
        stress[i] = (i < 3 ? t.mean : 0.0) + ratio * t.dev[i];
    state[0] = alpha + dl;
    if (tangent) {
        double a[6] = {K, K, K, 0, 0, 0}, g[6], c[6];
        pm_dq_deps(G, t.dev, t.q, g);
        /* ratio = 1 - 3G dl / q, dl = (q - syn) / (3G + Heff) */
        const double k = -3.0 * G / (t.q * (3.0 * G + Heff)) + 3.0 * G * dl / (t.q * t.q);
        for (int i = 0; i < 6; i++)
            c[i] = k * g[i];
        pm_tangent_invariant(a, ratio, G, t.dev, c, tangent);
    }
    return isfinite(stress[0]) ? PM_OK : PM_ESIM;
}

const pm_material_ops pm_von_mises_ops = {
    .name = "von_mises",
    .elastic_pair = 1,
    .n_params = sizeof vm_params / sizeof vm_params[0],
    .params = vm_params,
    .n_state = 1,
    .init = vm_init,
    .init_state = NULL,
    .update = vm_update,
    .wave_speed = pm_material_elastic_wave_speed,
    .plastic_strain = pm_plastic_strain_state0,
    .strain_energy = pm_material_elastic_energy,
    .reduce_strength = NULL, /* no Coulomb strength for the search to lower */
};
