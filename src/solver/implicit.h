/**
 * @file implicit.h (internal to src/, not installed)
 * @brief Implicit MPM (seed 000 Algorithm 1, after Guilkey & Weiss 2003): per step an
 *        updated-Lagrangian Newton solve for the nodal displacement increments on the background
 *        grid, Newmark (beta = 1/4, gamma = 1/2) in time or no inertia (quasi-static), then the
 *        convection to the particles and the grid reset. Uses only the pm_approx and pm_material
 *        interfaces, so any shape function and any model runs implicitly.
 */
#ifndef PMECH_IMPLICIT_H
#define PMECH_IMPLICIT_H

#include <stdio.h>

#include "pmech/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of Newton iterations whose residuals a step report keeps. */
#define PM_NEWTON_HISTORY 64

/** What one implicit step (with all its cuts) did. */
typedef struct pm_implicit_report {
    int iterations;                        /**< Newton iterations of the accepted attempt(s) */
    int step_cuts;                         /**< halvings of the step before it converged */
    int substeps;                          /**< attempts that converged and were accepted */
    int n_history;                         /**< entries in residual[] (last accepted substep) */
    double residual[PM_NEWTON_HISTORY];    /**< relative residual before each solve and at the end */
    int damped;                            /**< corrections recomputed with a damped (regularised) tangent */
    int solver_fallbacks;                  /**< CHOLMOD found the tangent indefinite; UMFPACK solved */
    int used_umfpack;                      /**< 1 if any solve of the step used UMFPACK */
    int dofs;                              /**< unknowns of the last system */
    double assemble_seconds;               /**< particle updates + assembly */
    double solve_seconds;                  /**< factorisations and solves */
} pm_implicit_report;

/**
 * @brief Advance an implicit or quasi-static simulation from s->t to s->t + @p dt.
 *
 * Quasi-static runs have no inertia; gravity is applied in proportion to t / end_time (so the
 * load grows over `analysis.load_steps` increments) and prescribed velocities are displacement
 * rates per unit of this pseudo-time. When Newton diverges (or a material update fails) the step
 * is halved and retried from the start-of-step state, up to `analysis.newton.max_step_cuts` times.
 * Each Newton iteration is written to @p log when it is not NULL.
 * @param s simulation created for an implicit or quasi-static case
 * @param dt step (or load increment in pseudo-time)
 * @param log where iteration lines go (may be NULL)
 * @param rep receives what the step did (may be NULL)
 * @return PM_OK, or PM_ESIM naming the step (and the particle when one failed)
 */
int pm_implicit_step(pm_sim *s, double dt, FILE *log, pm_implicit_report *rep);

/**
 * @brief Reaction forces (per radian in axisymmetric runs) of the case's `fixed` and `velocity`
 *        boundary conditions at the end of the last implicit step: the nodal internal force minus
 *        external and inertial forces summed over each condition's nodes.
 * @param s simulation after at least one pm_implicit_step()
 * @param bc index into the case's boundary_conditions
 * @param R receives (Rx, Ry); zero for friction conditions
 */
void pm_implicit_reaction(const pm_sim *s, size_t bc, double R[2]);

/** @brief Free the implicit solver's workspace of @p s (called by pm_sim_destroy()). */
void pm_implicit_free(pm_sim *s);

/**
 * @brief The force that sets the default absolute Newton tolerance: 1e-6 times the largest P-wave
 *        modulus (density c^2) of the case's materials times the smallest cell size, i.e. the nodal force
 *        of a strain of 1e-6 across a cell (per unit thickness in plane analyses).
 */
double pm_implicit_characteristic_force(const pm_sim *s);

#ifdef __cplusplus
}
#endif
#endif
