/*
 * viscoplastic_drucker_prager: the elastic-viscoplastic Drucker-Prager model of seed 004
 * (Wieckowski 2004, eqs. 15-23), Perzyna type, hypo-elastic with the Hughes-Winget rotation.
 *
 * Soil-mechanics invariants: p = -tr(sigma)/3 (compression positive), q = sqrt(3 J2).
 *   f = q - m p,   m = 18 sin(phi) / (9 - sin^2 phi)
 *   p_{n+1} = p_n - K tr(deps)                                   (eqs. 15, 23)
 *   s_e = Q s_n Q^T + 2G dev(deps)                               (eq. 20)
 *   s_{n+1} = s_e q / q_e,   q = q_e - 3G de                     (eqs. 19, 21)
 *   de = gamma dt <((q_e - m p - 3G de) / (m p))^N>              (eq. 22, backward Euler)
 * N = 1: de = (q_e - m p) / (3G + m p / (gamma dt)); otherwise a safeguarded Newton iteration on
 * eq. 22 within the bracket [0, (q_e - m p)/3G].
 * No cohesion: when p_{n+1} <= 0 the point carries no stress (a loose, unconfined granular
 * element): sigma = 0, the whole trial deviator flows (de = q_e / 3G), tangent 0.
 * State: [0] equivalent viscoplastic strain (sum of de).
 */
#include "material/material_internal.h"

#include "pmech/error.h"

#include <string.h>

enum { P_PHI, P_GAMMA, P_N };
enum { D_M };

static const pm_param_spec vp_params[] = {
    {"friction_angle", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN | PM_PARAM_HI_OPEN | PM_PARAM_ANGLE,
     0.0, 90.0, "friction angle phi (degrees); m = 18 sin(phi)/(9 - sin^2 phi)"},
    {"viscosity", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN, 0.0, INFINITY,
     "viscosity parameter gamma (1/s) of the Perzyna flow function"},
    {"exponent", 1.0, PM_PARAM_LO_OPEN, 0.0, INFINITY, "exponent N > 0 of the flow function"},
};

static int vp_init(pm_material *m)
{
    const double phi = m->param[P_PHI];
    if (!(phi > 0 && phi < 90))
        return pm_error_set(PM_EINPUT, "friction_angle = %g: must be in (0, 90)", phi);
    if (!(m->param[P_GAMMA] > 0))
        return pm_error_set(PM_EINPUT, "viscosity = %g: must be > 0", m->param[P_GAMMA]);
    if (!(m->param[P_N] > 0))
        return pm_error_set(PM_EINPUT, "exponent = %g: must be > 0", m->param[P_N]);
    const double s = sin(pm_deg2rad(phi));
    m->derived[D_M] = 18.0 * s / (9.0 - s * s);
    return PM_OK;
}

double pm_vp_solve(double qe, double p, double m, double G, double gdt, double N, int newton,
                   double d[3])
{
    const double mp = m * p;
    const double xmax = (qe - mp) / (3.0 * G);
    double x;
    if (N == 1.0 && !newton) {
        x = (qe - mp) / (3.0 * G + mp / gdt);
    } else {
        double lo = 0.0, hi = xmax;
        x = (qe - mp) / (3.0 * G + mp / gdt); /* the N = 1 solution as first guess */
        if (!(x > lo && x < hi))
            x = 0.5 * (lo + hi);
        for (int it = 0; it < 200; it++) {
            const double z = (qe - mp - 3.0 * G * x) / mp;
            const double zn = z > 0 ? pow(z, N) : 0.0;
            const double r = x - gdt * zn;
            if (r > 0)
                hi = x;
            else
                lo = x;
            const double dr = 1.0 + (z > 0 ? gdt * N * pow(z, N - 1.0) * 3.0 * G / mp : 0.0);
            double xn = x - r / dr;
            if (!(xn > lo && xn < hi))
                xn = 0.5 * (lo + hi);
            if (fabs(xn - x) <= 1e-15 * xmax || hi - lo <= 1e-15 * xmax) {
                x = xn;
                break;
            }
            x = xn;
        }
    }
    const double q = qe - 3.0 * G * x;
    const double z = (q - mp) / mp;
    /* a = gamma dt N z^(N-1); the factor a / (1 + 3G a / (m p)) tends to m p / 3G as a -> inf */
    double fac;
    if (N == 1.0)
        fac = gdt / (1.0 + 3.0 * G * gdt / mp);
    else if (z > 0) {
        const double a = gdt * N * pow(z, N - 1.0);
        fac = isfinite(a) ? a / (1.0 + 3.0 * G * a / mp) : mp / (3.0 * G);
    } else
        fac = N < 1.0 ? mp / (3.0 * G) : 0.0;
    d[0] = fac / mp;
    d[1] = -fac * q / (mp * p);
    d[2] = -3.0 * x * fac / mp;
    return x;
}

static int vp_update(const pm_material *m, const pm_material_step *in, double *state,
                     double stress[6], double *tangent)
{
    const double K = m->K, G = m->G, mm = m->derived[D_M];
    pm_trial t;
    pm_trial_state(in->F_incr, stress, K, G, &t);
    if (!isfinite(t.q + t.mean))
        return PM_ESIM;
    const double p = -t.mean;
    if (!(p > 0)) { /* no cohesion, no tension: stress-free */
        memset(stress, 0, 6 * sizeof(double));
        state[0] += t.q / (3.0 * G);
        if (tangent)
            memset(tangent, 0, 36 * sizeof(double));
        return PM_OK;
    }
    const double mp = mm * p, gdt = m->param[P_GAMMA] * in->dt;
    if (!(t.q - mp > 0) || !(gdt > 0)) {
        memcpy(stress, t.sig, 6 * sizeof(double));
        if (tangent)
            pm_elastic_stiffness(K, G, tangent);
        return PM_OK;
    }
    double dx[3];
    const double x = pm_vp_solve(t.q, p, mm, G, gdt, m->param[P_N], 0, dx);
    const double ratio = 1.0 - 3.0 * G * x / t.q;
    for (int i = 0; i < 6; i++)
        stress[i] = (i < 3 ? t.mean : 0.0) + ratio * t.dev[i];
    state[0] += x;
    if (tangent) {
        double a[6] = {K, K, K, 0, 0, 0}, g[6], c[6];
        pm_dq_deps(G, t.dev, t.q, g);
        for (int i = 0; i < 6; i++) {
            /* dp = -K tr(deps) */
            const double dxi = dx[0] * g[i] + dx[1] * (i < 3 ? -K : 0.0);
            c[i] = -3.0 * G * dxi / t.q + 3.0 * G * x * g[i] / (t.q * t.q);
        }
        pm_tangent_invariant(a, ratio, G, t.dev, c, tangent);
    }
    return isfinite(stress[0]) ? PM_OK : PM_ESIM;
}

const pm_material_ops pm_viscoplastic_dp_ops = {
    .name = "viscoplastic_drucker_prager",
    .elastic_pair = 1,
    .n_params = sizeof vp_params / sizeof vp_params[0],
    .params = vp_params,
    .n_state = 1,
    .init = vp_init,
    .init_state = NULL,
    .update = vp_update,
    .wave_speed = pm_material_elastic_wave_speed,
    .plastic_strain = pm_plastic_strain_state0,
    .strain_energy = pm_material_elastic_energy,
    .reduce_strength = NULL, /* no Coulomb strength for the search to lower */
};
