/*
 * drucker_prager: the cone of seed 002 (eqs. 29-39, Borja-type), hypo-elastic (Hughes-Winget).
 * With tension-positive mean stress p = tr(sigma)/3 and q = sqrt(3 J2):
 *   yield      F = q + sqrt3 beta p - k,   k = sqrt3 alpha + sqrt3 beta K' v_p + H' e_p  (>= 0)
 *   potential  G = q + sqrt3 b p
 *   alpha = 6 c cos(phi) / (sqrt3 (3 + A sin(phi))),  beta = 6 sin(phi) / (sqrt3 (3 + A sin(phi)))
 *   b     = 6 sin(psi) / (sqrt3 (3 + A sin(psi)))
 *   flow  deps_p = dlambda (sqrt(3/2) n + b/sqrt3 1):  de_p = dlambda, dv_p = sqrt3 b dlambda.
 * So q <= M (c cot(phi) - p) with M = 6 sin(phi)/(3 + A sin(phi)): A = -1 fits Mohr-Coulomb at the
 * compression meridian (outer apexes), A = +1 at the extension meridian (inner apexes).
 * Cone return: dlambda = F_trial / (3G + 3 K beta b + 3 beta b K' + H'); apex return when the
 * cone return would give q < 0: s = 0, de_p = q_trial / (3G), p from F = 0 with q = 0.
 * State: [0] e_p (deviatoric equivalent plastic strain), [1] v_p (plastic volumetric strain).
 */
#include "material/material_internal.h"

#include "pmech/error.h"

#include <string.h>

enum { P_C, P_PHI, P_PSI, P_A, P_KH, P_HH };
enum { D_ALPHA, D_BETA, D_B };

static const pm_param_spec dp_params[] = {
    PM_COULOMB_PARAM_SPECS,
    {"cone_fit", -1.0, 0, -1.0, 1.0,
     "A of seed 002 eq. 35: -1 cone through the outer (compression) apexes, +1 inner"},
    {"bulk_hardening", 0.0, 0, -INFINITY, INFINITY,
     "bulk hardening/softening modulus K' (Pa) acting on the plastic volumetric strain"},
    {"shear_hardening", 0.0, 0, -INFINITY, INFINITY,
     "shear hardening/softening modulus H' (Pa) acting on the deviatoric plastic strain"},
};

static int dp_init(pm_material *m)
{
    const double phi = m->param[P_PHI], psi = m->param[P_PSI], A = m->param[P_A];
    const double c = m->param[P_C];
    pm_check(pm_check_coulomb_strength(c, phi, psi));
    if (!(A >= -1 && A <= 1))
        return pm_error_set(PM_EINPUT, "cone_fit = %g: must be in [-1, 1]", A);
    const double sp = sin(pm_deg2rad(phi)), cp = cos(pm_deg2rad(phi)), ss = sin(pm_deg2rad(psi));
    const double s3 = sqrt(3.0);
    m->derived[D_ALPHA] = 6.0 * c * cp / (s3 * (3.0 + A * sp));
    m->derived[D_BETA] = 6.0 * sp / (s3 * (3.0 + A * sp));
    m->derived[D_B] = 6.0 * ss / (s3 * (3.0 + A * ss));
    const double beta = m->derived[D_BETA], b = m->derived[D_B];
    const double Kh = m->param[P_KH], Hh = m->param[P_HH];
    if (!(3.0 * m->G + 3.0 * beta * b * (m->K + Kh) + Hh > 0))
        return pm_error_set(PM_EINPUT,
                            "shear_hardening = %g: softening too strong, need 3 G + 3 beta b (K + K') + "
                            "H' > 0 (H' > %g)",
                            Hh, -(3.0 * m->G + 3.0 * beta * b * (m->K + Kh)));
    if (beta > 0 && !(m->K + Kh > 0))
        return pm_error_set(PM_EINPUT, "bulk_hardening = %g: must be > -K = %g", Kh, -m->K);
    return PM_OK;
}

static int dp_update(const pm_material *m, const pm_material_step *in, double *state,
                     double stress[6], double *tangent)
{
    const double K = m->K, G = m->G, s3 = sqrt(3.0);
    const double alpha = m->derived[D_ALPHA], beta = m->derived[D_BETA], b = m->derived[D_B];
    const double Kh = m->param[P_KH], Hh = m->param[P_HH];
    pm_trial t;
    pm_trial_state(in->F_incr, stress, K, G, &t);
    const double ep = state[0], vp = state[1];
    /* strength k as a linear function of dlambda along the cone: k0 + hk dlambda (>= 0) */
    const double k0 = s3 * alpha + s3 * beta * Kh * vp + Hh * ep;
    const double hk = 3.0 * beta * Kh * b + Hh;
    const double F = t.q + s3 * beta * t.mean - fmax(k0, 0.0);
    if (!(F > 0)) {
        memcpy(stress, t.sig, 6 * sizeof(double));
        if (tangent)
            pm_elastic_stiffness(K, G, tangent);
        return isfinite(t.q + t.mean) ? PM_OK : PM_ESIM;
    }
    double a[6], c[6], g[6];
    pm_dq_deps(G, t.dev, t.q, g);
    /* cone return */
    double hkk = k0 > 0 || hk > 0 ? hk : 0.0;
    double h = 3.0 * G + 3.0 * K * beta * b + hkk;
    double dl = (t.q + s3 * beta * t.mean - k0 * (hkk != 0.0 || k0 > 0)) / h;
    if (hkk != 0.0 && k0 + hk * dl < 0) { /* strength softened to zero within the step */
        h = 3.0 * G + 3.0 * K * beta * b;
        dl = (t.q + s3 * beta * t.mean) / h;
    }
    if (t.q - 3.0 * G * dl >= 0) {
        const double ratio = 1.0 - 3.0 * G * dl / t.q;
        const double mean = t.mean - s3 * K * b * dl;
        for (int i = 0; i < 6; i++)
            stress[i] = (i < 3 ? mean : 0.0) + ratio * t.dev[i];
        state[0] = ep + dl;
        state[1] = vp + s3 * b * dl;
        if (tangent) {
            /* d dl = (g + sqrt3 beta K 1) / h */
            double ddl[6];
            for (int i = 0; i < 6; i++)
                ddl[i] = (g[i] + (i < 3 ? s3 * beta * K : 0.0)) / h;
            for (int i = 0; i < 6; i++) {
                a[i] = (i < 3 ? K : 0.0) - s3 * K * b * ddl[i];
                c[i] = -3.0 * G * ddl[i] / t.q + 3.0 * G * dl * g[i] / (t.q * t.q);
            }
            pm_tangent_invariant(a, ratio, G, t.dev, c, tangent);
        }
        return isfinite(stress[0]) ? PM_OK : PM_ESIM;
    }
    /* apex return: s = 0, de_p = q_tr / 3G, dv_p = (mean_tr - mean) / K and
     * sqrt3 beta mean = k0' + sqrt3 beta K' dv_p + H' de_p with k0' the strength before the step.
     * (beta > 0 here: with beta = 0 the cone return always succeeds.) */
    const double dep = t.q / (3.0 * G);
    if (!(beta > 0)) { /* cylinder softened to zero shear strength: deviator vanishes */
        for (int i = 0; i < 6; i++)
            stress[i] = i < 3 ? t.mean : 0.0;
        state[0] = ep + dep;
        if (tangent) {
            for (int i = 0; i < 6; i++)
                a[i] = i < 3 ? K : 0.0;
            memset(c, 0, sizeof c);
            pm_tangent_invariant(a, 0.0, G, t.dev, c, tangent);
        }
        return isfinite(t.mean) ? PM_OK : PM_ESIM;
    }
    const double kk = s3 * beta * (1.0 + Kh / K);
    double mean = (k0 + s3 * beta * Kh * t.mean / K + Hh * dep) / kk;
    int soft0 = 0;
    if (k0 + s3 * beta * Kh * (t.mean - mean) / K + Hh * dep < 0) {
        mean = 0.0; /* no strength left: the apex is at zero stress */
        soft0 = 1;
    }
    for (int i = 0; i < 6; i++)
        stress[i] = i < 3 ? mean : 0.0;
    state[0] = ep + dep;
    state[1] = vp + (t.mean - mean) / K;
    if (tangent) {
        for (int i = 0; i < 6; i++) {
            a[i] = soft0 ? 0.0
                         : (s3 * beta * Kh * (i < 3 ? 1.0 : 0.0) + Hh * g[i] / (3.0 * G)) / kk;
            c[i] = 0.0;
        }
        pm_tangent_invariant(a, 0.0, G, t.dev, c, tangent);
    }
    return isfinite(mean) ? PM_OK : PM_ESIM;
}

const pm_material_ops pm_drucker_prager_ops = {
    .name = "drucker_prager",
    .elastic_pair = 1,
    .n_params = sizeof dp_params / sizeof dp_params[0],
    .params = dp_params,
    .n_state = 2,
    .init = dp_init,
    .init_state = NULL,
    .update = dp_update,
    .wave_speed = pm_material_elastic_wave_speed,
    .plastic_strain = pm_plastic_strain_state0,
    .strain_energy = pm_material_elastic_energy,
    .reduce_strength = pm_reduce_coulomb_strength,
};
