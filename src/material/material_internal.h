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

#endif
