/**
 * @file density.h (internal to src/, not installed)
 * @brief Mass density from the current particle positions (Wieckowski, seed 004 section 3.3).
 */
#ifndef PMECH_DENSITY_H
#define PMECH_DENSITY_H

#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Density field from particle positions and masses, seed 004 eqs. 12-13.
 *
 * Nodal densities (eq. 13, generalised from tri3 to quad4 cells):
 *     rho_i = sum_P N_i(X_P) M_P / sum_j integral over cell j of N_i dV,
 * the first sum over the selected particles in the cells around node i, the second over those
 * cells around node i that hold at least one selected particle (integral of N_i = A_j / 3 for a
 * triangle in plane problems; quads and axisymmetric volumes, integral of N_i r dA per radian, by
 * 2 x 2 Gauss points or exactly for triangles). Particle densities (eq. 12):
 *     rho_P = sum_i N_i(X_P) rho_i,
 * with N_i the linear shape functions of the particle's cell (whatever approximation the solver
 * runs). A region filled uniformly gives the material density at every node whose surrounding
 * occupied cells are filled; nodes on the region's edge see partly filled cells and read low.
 *
 * @param g grid
 * @param p particles; p->cell must be located (connect) and p->mass set (per radian when
 *          @p axisymmetric)
 * @param axisymmetric 1 for axisymmetric runs (x = radius, volumes per radian), else 0
 * @param material only particles of this material index count (-1: all); a granular material's
 *          density is that of its own points
 * @param rho_node receives g->n_nodes nodal densities (0 where no occupied cell touches the node)
 * @param rho_p receives p->n particle densities (may be NULL; particles of other materials get 0)
 * @param work workspace of g->n_nodes + g->n_cells doubles
 * @return PM_OK, or PM_ESIM if a selected particle has no cell
 */
int pm_density_from_positions(const pm_grid *g, const pm_particles *p, int axisymmetric, int32_t material,
                              double *rho_node, double *rho_p, double *work);

#ifdef __cplusplus
}
#endif
#endif
