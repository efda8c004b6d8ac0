/**
 * @file particle_fields.h (internal to src/, not installed)
 * @brief Scalar fields derived from a particle's stress and deformation gradient, written into every
 *        frame and drawn in pictures: pressure, von Mises q, volumetric and deviatoric logarithmic strain.
 */
#ifndef PMECH_IO_PARTICLE_FIELDS_H
#define PMECH_IO_PARTICLE_FIELDS_H

#include "pmech/particles.h"

/** @brief Pressure p = -(sxx + syy + szz) / 3 of a stress block (PM_NS entries, tension positive): compression positive. */
double pm_pf_pressure(const double *stress);

/** @brief Von Mises equivalent stress q = sqrt(3 J2) of a stress block (PM_NS entries). */
double pm_pf_q(const double *stress);

/**
 * @brief Invariants of the logarithmic (Hencky) strain eps = ln(V) = ln(F F^T) / 2 of a deformation gradient
 *        (PM_NF entries, the out-of-plane or hoop stretch included).
 * @param F the deformation gradient
 * @param vol receives the volumetric strain tr(eps) = ln(det F)
 * @param dev receives the equivalent deviatoric strain sqrt(2/3 e:e), e = eps - tr(eps) / 3 I
 */
void pm_pf_log_strain(const double *F, double *vol, double *dev);

#endif
