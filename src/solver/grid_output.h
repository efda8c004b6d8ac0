/**
 * @file grid_output.h (internal to src/, not installed)
 * @brief The nodal side of a frame: the nodes a simulation interpolates from (the MPM grid, or the
 *        GMM/RKPM node cloud) with their lumped mass, velocity, prescribed components and contact.
 */
#ifndef PMECH_SOLVER_GRID_OUTPUT_H
#define PMECH_SOLVER_GRID_OUTPUT_H

#include "io/output.h"
#include "solver/sim_internal.h"

/**
 * @brief Write the grid frame that goes with the particle frame just written (pm_output_grid_frame()):
 *        mass and flags always; the velocity of the last explicit step (implicit runs keep theirs in
 *        the Newton workspace and write none).
 * @return PM_OK, PM_ENOMEM, PM_EIO
 */
int pm_sim_grid_frame(pm_output *out, const pm_sim *s);

#endif
