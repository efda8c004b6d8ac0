/*
 * Internal helpers shared by the constitutive models (not part of the public interface).
 * Voigt order everywhere: xx, yy, zz, xy, yz, xz; strains carry engineering shears.
 */
#ifndef PMECH_MATERIAL_INTERNAL_H
#define PMECH_MATERIAL_INTERNAL_H

#include "pmech/material.h"

#include <math.h>

/* Operation tables of the models (one per file), collected by material_registry.c. */
extern const pm_material_ops pm_linear_elastic_ops;
extern const pm_material_ops pm_neo_hookean_ops;
extern const pm_material_ops pm_von_mises_ops;
extern const pm_material_ops pm_mohr_coulomb_ops;
extern const pm_material_ops pm_drucker_prager_ops;
extern const pm_material_ops pm_viscoplastic_dp_ops;
extern const pm_material_ops pm_granular_ops;

/*
 * The Coulomb strength parameters of mohr_coulomb and drucker_prager, the first three entries of their
 * parameter tables (in this order: cohesion, friction_angle, dilatancy_angle), so that both models
 * take the same keys with the same ranges, the keys pm_reduce_coulomb_strength divides.
 */
#define PM_COULOMB_PARAM_SPECS                                                                  \
    {"cohesion", NAN, PM_PARAM_REQUIRED, 0.0, INFINITY, "cohesion c (Pa)"},                     \
    {"friction_angle", NAN, PM_PARAM_REQUIRED | PM_PARAM_HI_OPEN | PM_PARAM_ANGLE, 0.0, 90.0,   \
     "friction angle phi (degrees)"},                                                           \
    {"dilatancy_angle", 0.0, PM_PARAM_HI_OPEN | PM_PARAM_ANGLE, 0.0, 90.0,                      \
     "dilatancy angle psi (degrees, <= friction_angle)"}

/*
 * Checks of the Coulomb strength parameters (PM_COULOMB_PARAM_SPECS) the ranges of the table do not
 * say: c >= 0, 0 <= phi < 90 and 0 <= psi <= phi degrees. PM_OK, or PM_EINPUT naming the key.
 */
int pm_check_coulomb_strength(double c, double phi, double psi);

/*
 * pm_material_ops::reduce_strength of the Coulomb-type models (mohr_coulomb, drucker_prager):
 * c -> c / F, phi -> atan(tan(phi) / F), psi -> atan(tan(psi) / F) capped at the reduced phi,
 * a tension_cutoff T (where the model has one and it is set) -> T / F.
 */
int pm_reduce_coulomb_strength(pm_material *m, double factor);

/*
 * pm_material_ops::plastic_strain of the models that keep the accumulated equivalent plastic strain
 * as their first history variable (von_mises, mohr_coulomb, drucker_prager, viscoplastic_dp,
 * granular): state[0].
 */
double pm_plastic_strain_state0(const pm_material *m, const double *state);

/* Degrees to radians. */
static inline double pm_deg2rad(double deg) { return deg * (M_PI / 180.0); }

/* Mean (tension-positive) stress tr(s)/3 of a Voigt stress. */
static inline double pm_voigt_mean(const double s[6]) { return (s[0] + s[1] + s[2]) / 3.0; }

/* sqrt(3 J2) of a Voigt stress (shears are tensor components). */
static inline double pm_voigt_q(const double s[6])
{
    const double m = pm_voigt_mean(s);
    const double a = s[0] - m, b = s[1] - m, c = s[2] - m;
    const double j2 = 0.5 * (a * a + b * b + c * c) + s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
    return sqrt(3.0 * j2);
}

/*
 * Elastic trial state of a hypo-elastic model: rotate sigma_n by Hughes-Winget, add D : deps.
 * Fills deps (Voigt, engineering shears), the trial stress, its mean (tension positive), the
 * deviator (tensor components) and q = sqrt(3 J2).
 */
typedef struct pm_trial {
    double deps[6];  /* mid-step strain increment */
    double sig[6];   /* trial stress */
    double mean;     /* tr(sig)/3 */
    double dev[6];   /* deviator of sig */
    double q;        /* sqrt(3/2 dev:dev) */
} pm_trial;

/* Compute the trial state with bulk modulus K and shear modulus G. */
void pm_trial_state(const double F_incr[9], const double stress[6], double K, double G, pm_trial *t);

/* Deviator (tensor components) and mean of a Voigt stress; returns q = sqrt(3 J2). */
double pm_voigt_split(const double s[6], double dev[6], double *mean);

/*
 * Tangent of an update sigma = mean 1 + ratio * s_e with s_e = s_rot + 2G dev(deps):
 *   D = 1 (x) a + ratio 2G I_dev + s_e (x) c,
 * where a = d mean / d eps and c = d ratio / d eps (6-vectors acting on engineering strains).
 */
void pm_tangent_invariant(const double a[6], double ratio, double G, const double se[6],
                          const double c[6], double D[36]);

/* d q_e / d eps = 3G s_e / q_e for s_e = s_rot + 2G dev(deps) (zero when q_e = 0). */
void pm_dq_deps(double G, const double se[6], double qe, double out[6]);

/* Deviatoric equivalent strain sqrt(2/3 e:e) of a Voigt strain with engineering shears. */
double pm_equiv_dev_strain(const double e[6]);

/*
 * Backward-Euler Perzyna flow of seed 004 eq. 22: the de >= 0 solving
 *   de = gdt ((q_e - m p - 3G de) / (m p))^N      (q_e > m p > 0, gdt = gamma dt > 0),
 * closed form for N = 1 (unless @p newton), safeguarded Newton otherwise. d receives d de / d q_e,
 * d de / d p and d de / d G.
 */
double pm_vp_solve(double qe, double p, double m, double G, double gdt, double N, int newton,
                   double d[3]);

#endif
