/**
 * @file driver.h
 * @brief The material-point driver behind `pmech material`: one point of a material is driven
 *        along a strain (or mixed strain/stress) path and its response written as CSV.
 *
 * The driver file format (pm_driver, loaded by pm_driver_load in case.h) is described in
 * docs/input.md and docs/materials.md.
 */
#ifndef PMECH_DRIVER_H
#define PMECH_DRIVER_H

#include <stdio.h>

#include "pmech/case.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Header line of the driver's CSV output (without the newline). */
#define PM_DRIVER_CSV_HEADER "step,exx,eyy,ezz,exy,sxx,syy,szz,sxy,p,q,eps_p"

/**
 * @brief Drive one material point along the path of @p d and write one CSV row per step.
 *
 * The material in @p d must be complete (elastic constants set, parameters filled, ops->init
 * called), as pm_driver_load leaves it. Rows: step 0 (the initial state) to d->steps (or the number
 * of increments), columns PM_DRIVER_CSV_HEADER: logarithmic strains 1/2 ln(F F^T) (tension
 * positive, exy the tensor component), Cauchy stresses (tension positive), p = -tr(sigma)/3,
 * q = sqrt(3 J2) and the equivalent plastic strain.
 * Triaxial paths hold both lateral Cauchy stresses at -confining_pressure by a Newton iteration
 * on the lateral strain increments using the consistent tangent.
 *
 * @param d the driver (path and material)
 * @param csv stream receiving the header and rows (may be NULL: nothing is written)
 * @return PM_OK; PM_ESIM if a stress update fails or the lateral-stress iteration does not
 *         converge (message names the step); PM_EINPUT for an invalid path (e.g. steps < 1)
 */
int pm_driver_run(const pm_driver *d, FILE *csv);

/**
 * @brief Like pm_driver_run, and also hand every row to @p row (for tests and plots).
 * @param d the driver
 * @param csv stream for CSV text (may be NULL)
 * @param row called with the step and the 11 values after `step` of each row (may be NULL)
 * @param ctx passed to @p row
 * @return as pm_driver_run
 */
int pm_driver_run_cb(const pm_driver *d, FILE *csv,
                     void (*row)(void *ctx, int step, const double values[11]), void *ctx);

#ifdef __cplusplus
}
#endif
#endif
