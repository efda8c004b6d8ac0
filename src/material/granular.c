/*
 * granular: the pressure-dependent granular model of seed 004 eq. 24 (Wieckowski 2004, silo
 * filling), hypo-elastic deviator with the Hughes-Winget rotation.
 *
 * Soil-mechanics pressure p = -tr(sigma)/3 from the logarithmic volumetric strain eps_v measured
 * from the reference state (p0, e0), plus a bulk viscosity acting in compression only:
 *   p   = p_e + p_v,   p_e = p0 exp[(1 + e0)/kappa (1 - exp eps_v)],   p_v = (-mu d eps_v/dt)^+
 * (p_e follows from e - e0 = -kappa ln(p/p0) with e = (1 + e0) J - 1.) The shear modulus follows p_e:
 *   G = 3/2 (1 - 2 nu)/(1 + nu) (1 + e0)/kappa p_e exp(eps_v)
 * (the tangent bulk modulus K_t = dp_e/d(-eps_v) = (1 + e0)/kappa p_e exp(eps_v) with Poisson's
 * ratio nu). The deviator is elastic-viscoplastic exactly as viscoplastic_drucker_prager (f = q - m p,
 * eqs. 16-22) with this G and the total pressure p. Always p > 0: there is no tension; a strongly
 * dilated (loose) point has p -> 0 and no shear strength.
 * eps_v is accumulated as the trace of the mid-step (Hughes-Winget) strain increments.
 *
 * The loosest state: a grain skeleton cannot be looser than e_max (`max_void_ratio`). Material that
 * separates (a portion falling freely, spray thrown up on impact) is no longer a skeleton; the log
 * law alone would let its eps_v grow without bound, so that on landing it would have to be compressed
 * back through all that expansion before it carried any pressure, and would pile up at a fraction of
 * its density. eps_v is therefore held at eps_v,max = ln[(1 + e_max)/(1 + e0)]: expansion beyond it is
 * stress-free, and a point landing from flight compacts from e_max. The default e_max is unbounded.
 * State: [0] equivalent viscoplastic strain, [1] eps_v.
 */
#include "material/material_internal.h"

#include "pmech/error.h"

#include <string.h>

enum { P_KAPPA, P_E0, P_P0, P_MU, P_NU, P_PHI, P_GAMMA, P_N, P_EMAX };
enum { D_M, D_A, D_GF, D_EVMAX };

static const pm_param_spec gr_params[] = {
    {"kappa", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN, 0.0, INFINITY,
     "elastic (swelling) coefficient kappa of e - e0 = -kappa ln(p/p0)"},
    {"void_ratio", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN, 0.0, INFINITY,
     "void ratio e0 at the reference pressure"},
    {"reference_pressure", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN, 0.0, INFINITY,
     "reference pressure p0 (Pa) of the undeformed state"},
    {"bulk_viscosity", 0.0, 0, 0.0, INFINITY, "bulk viscosity mu (Pa s), acts in compression"},
    {"poisson_ratio", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN | PM_PARAM_HI_OPEN, -1.0, 0.5,
     "Poisson's ratio nu linking G to the tangent bulk modulus"},
    {"friction_angle", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN | PM_PARAM_HI_OPEN | PM_PARAM_ANGLE,
     0.0, 90.0, "friction angle phi (degrees)"},
    {"viscosity", NAN, PM_PARAM_REQUIRED | PM_PARAM_LO_OPEN, 0.0, INFINITY,
     "viscosity parameter gamma (1/s) of the Perzyna flow function"},
    {"exponent", 1.0, PM_PARAM_LO_OPEN, 0.0, INFINITY, "exponent N > 0 of the flow function"},
    {"max_void_ratio", INFINITY, PM_PARAM_LO_OPEN, 0.0, INFINITY,
     "loosest void ratio e_max > void_ratio: expansion beyond it is stress-free"},
};

static int gr_init(pm_material *m)
{
    const double phi = m->param[P_PHI], nu = m->param[P_NU];
    static const int pos[] = {P_KAPPA, P_E0, P_P0, P_GAMMA, P_N};
    for (size_t i = 0; i < sizeof pos / sizeof pos[0]; i++)
        if (!(m->param[pos[i]] > 0))
            return pm_error_set(PM_EINPUT, "%s = %g: must be > 0", m->ops->params[pos[i]].key,
                                m->param[pos[i]]);
    if (!(m->param[P_MU] >= 0))
        return pm_error_set(PM_EINPUT, "bulk_viscosity = %g: must be >= 0", m->param[P_MU]);
    if (!(nu > -1 && nu < 0.5))
        return pm_error_set(PM_EINPUT, "poisson_ratio = %g: must be in (-1, 0.5)", nu);
    if (!(phi > 0 && phi < 90))
        return pm_error_set(PM_EINPUT, "friction_angle = %g: must be in (0, 90)", phi);
    const double e0 = m->param[P_E0], emax = m->param[P_EMAX];
    if (!(emax > e0))
        return pm_error_set(PM_EINPUT, "max_void_ratio = %g: must be > void_ratio = %g", emax, e0);
    const double s = sin(pm_deg2rad(phi));
    m->derived[D_M] = 18.0 * s / (9.0 - s * s);
    m->derived[D_A] = (1.0 + m->param[P_E0]) / m->param[P_KAPPA];
    m->derived[D_GF] = 1.5 * (1.0 - 2.0 * nu) / (1.0 + nu);
    m->derived[D_EVMAX] = isfinite(emax) ? log((1.0 + emax) / (1.0 + e0)) : INFINITY;
    return PM_OK;
}

/* eps_v whose elastic pressure equals the initial pressure (0 when there is none). */
static void gr_init_state(const pm_material *m, const double stress[6], double *state)
{
    state[0] = 0.0;
    state[1] = 0.0;
    if (!stress)
        return;
    const double p = -(stress[0] + stress[1] + stress[2]) / 3.0;
    if (!(p > 0))
        return;
    const double J = 1.0 - log(p / m->param[P_P0]) / m->derived[D_A];
    state[1] = fmin(J > 1e-3 ? log(J) : log(1e-3), m->derived[D_EVMAX]);
}

static int gr_update(const pm_material *m, const pm_material_step *in, double *state,
                     double stress[6], double *tangent)
{
    const double A = m->derived[D_A], p0 = m->param[P_P0], mu = m->param[P_MU];
    const double mm = m->derived[D_M], gf = m->derived[D_GF];
    double srot[6], de[6];
    memcpy(srot, stress, sizeof srot);
    pm_hughes_winget(in->F_incr, srot, de);
    const double dev_v = de[0] + de[1] + de[2];
    if (!isfinite(dev_v))
        return PM_ESIM;
    const double ev_max = m->derived[D_EVMAX], ev = state[1] + dev_v, J = exp(ev);
    const double pe = p0 * exp(A * (1.0 - J));
    /* grains still apart at the step's end are not a skeleton: no viscous resistance */
    const int visc = in->dt > 0 && mu > 0 && dev_v < 0 && ev < ev_max;
    const double pv = visc ? -mu * dev_v / in->dt : 0.0;
    const double p = pe + pv, Kt = A * pe * J, G = gf * Kt;
    state[1] = fmin(ev, ev_max);
    /* trial deviator s_e = s_rot + 2G dev(de) */
    double sdev[6], mrot, se[6], e[6];
    pm_voigt_split(srot, sdev, &mrot);
    const double em = dev_v / 3.0;
    for (int i = 0; i < 6; i++) {
        e[i] = i < 3 ? de[i] - em : 0.5 * de[i]; /* tensor deviatoric strain increment */
        se[i] = sdev[i] + 2.0 * G * e[i];
    }
    const double qe = sqrt(1.5 * (se[0] * se[0] + se[1] * se[1] + se[2] * se[2] +
                                  2.0 * (se[3] * se[3] + se[4] * se[4] + se[5] * se[5])));
    const double mp = mm * p, gdt = m->param[P_GAMMA] * in->dt;
    double x = 0.0, dx[3] = {0, 0, 0};
    if (qe > mp && gdt > 0 && p > 0)
        x = pm_vp_solve(qe, p, mm, G, gdt, m->param[P_N], 0, dx);
    else if (!(p > 0))
        x = qe / (3.0 * G > 0 ? 3.0 * G : 1.0);
    const double ratio = qe > 0 && p > 0 ? 1.0 - 3.0 * G * x / qe : (p > 0 ? 1.0 : 0.0);
    for (int i = 0; i < 6; i++)
        stress[i] = (i < 3 ? -p : 0.0) + ratio * se[i];
    state[0] += x;
    if (tangent) {
        /* d mean = (K_t + mu/dt [compressing]) tr(d eps); dG = G (1 - A J) tr(d eps) */
        const double km = Kt + (visc ? mu / in->dt : 0.0);
        const double dGv = G * (1.0 - A * J);
        const double sde = se[0] * e[0] + se[1] * e[1] + se[2] * e[2] +
                           2.0 * (se[3] * e[3] + se[4] * e[4] + se[5] * e[5]);
        double a[6], g[6], c[6];
        pm_dq_deps(G, se, qe, g);
        for (int i = 0; i < 6; i++) {
            const double vol = i < 3 ? 1.0 : 0.0;
            a[i] = km * vol;
            if (qe > 0)
                g[i] += 3.0 / qe * sde * dGv * vol; /* dq_e/d eps including dG */
        }
        for (int i = 0; i < 6; i++) {
            const double vol = i < 3 ? 1.0 : 0.0;
            if (x > 0 && qe > 0) {
                const double dxi = dx[0] * g[i] - dx[1] * km * vol + dx[2] * dGv * vol;
                c[i] = -3.0 * (G * dxi + x * dGv * vol) / qe + 3.0 * G * x * g[i] / (qe * qe);
            } else
                c[i] = 0.0;
        }
        pm_tangent_invariant(a, ratio, G, se, c, tangent);
        /* ratio * 2 e (x) dG/d eps: the pressure dependence of the shear modulus */
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 3; j++)
                tangent[6 * i + j] += ratio * 2.0 * e[i] * dGv;
    }
    return isfinite(stress[0] + stress[3]) ? PM_OK : PM_ESIM;
}

/* Seed 004 §3.3: the volume change of the granular pressure from the density of the points'
 * positions, J = rho_ref / rho, acting only where it shows the point apart, looser than the loosest
 * skeleton. Inside a skeleton the positions' density of a point scatters by 0.11-0.16 in ln rho
 * (points bunch within cells), against 0.05 from e0 to e_max, and raising eps_v to it wherever it was
 * looser ratcheted the state loose step after step: 30 portions of the silo filling then crowded 6 %
 * closer than their pressure allows (examples/silo_filling, "Where the over-compaction comes from").
 * Without e_max no density is looser than the loosest skeleton, and the positions do not act. */
static void gr_density_state(const pm_material *m, double rho_ratio, double *state)
{
    if (!(rho_ratio > 0))
        return;
    const double ev = -log(rho_ratio);
    if (ev > m->derived[D_EVMAX])
        state[1] = fmax(state[1], ev);
}

/* Tangent moduli at the state's volumetric strain. */
static void gr_moduli(const pm_material *m, const double *state, double *Kt, double *G)
{
    const double A = m->derived[D_A], J = exp(state ? state[1] : 0.0);
    const double pe = m->param[P_P0] * exp(A * (1.0 - J));
    *Kt = A * pe * J;
    *G = m->derived[D_GF] * *Kt;
}

static double gr_wave_speed(const pm_material *m, const double *state, double density)
{
    double Kt, G;
    gr_moduli(m, state, &Kt, &G);
    return sqrt((Kt + 4.0 * G / 3.0) / density);
}

/* The bulk viscosity mu acts on this step's volumetric rate: explicit in time. */
static double gr_rate_viscosity(const pm_material *m)
{
    return m->param[P_MU];
}

static double gr_energy(const pm_material *m, const pm_material_step *in, const double *state,
                        const double stress[6])
{
    (void)in;
    double Kt, G, dev[6], mean;
    gr_moduli(m, state, &Kt, &G);
    const double q = pm_voigt_split(stress, dev, &mean);
    (void)mean;
    /* deviatoric elastic energy s:s/(4G) = q^2/(6G); the pressure part is not stored energy of a
     * linear spring and is left out */
    return G > 0 ? q * q / (6.0 * G) : 0.0;
}

const pm_material_ops pm_granular_ops = {
    .name = "granular",
    .elastic_pair = 0,
    .n_params = sizeof gr_params / sizeof gr_params[0],
    .params = gr_params,
    .n_state = 2,
    .init = gr_init,
    .init_state = gr_init_state,
    .update = gr_update,
    .wave_speed = gr_wave_speed,
    .rate_viscosity = gr_rate_viscosity,
    .density_state = gr_density_state,
    .plastic_strain = pm_plastic_strain_state0,
    .strain_energy = gr_energy,
    .reduce_strength = NULL, /* no Coulomb strength for the search to lower */
};
