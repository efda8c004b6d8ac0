/* Particle generation from the bodies of a case (internal to the solver setup). */
#ifndef PMECH_SEED_H
#define PMECH_SEED_H

#include "pmech/case.h"
#include "pmech/grid.h"
#include "pmech/particles.h"

/**
 * Count the particles every body yields on grid @p g (Gauss points of each cell that lie inside
 * the body's shape). @p per_body receives one count per body. Returns PM_EINPUT naming a body
 * that yields no particle.
 */
int pm_seed_count(const pm_case *c, const pm_grid *g, size_t *per_body, size_t *total);

/**
 * Fill particles (already allocated for the total count) with positions, volumes, masses,
 * initial velocity, F = I, initial stress and material state.
 */
int pm_seed_fill(const pm_case *c, const pm_grid *g, pm_particles *p);

/** Particles @p b yields on grid @p g (0 for a shape no quadrature point lies in). */
size_t pm_seed_body_count(const pm_case *c, const pm_case_body *b, const pm_grid *g);

/**
 * Fill the particles of @p b (any body-like description: a body or what a source releases) from index
 * @p first, with body index @p index, as pm_seed_fill() does; @p p must have room. Returns the count.
 */
size_t pm_seed_body_fill(const pm_case *c, const pm_case_body *b, int32_t index, const pm_grid *g, pm_particles *p,
                         size_t first);

/** 1 if @p x lies inside @p shape (boundary included for rectangles and circles). */
int pm_shape_contains(const pm_shape *shape, const double x[2]);

#endif
