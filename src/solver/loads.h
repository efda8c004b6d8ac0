/*
 * Loads on the material (the case's loads[]): a force given in time on a set of particles, found at
 * t = 0 (the particle nearest a point, or the particles in a box) and followed by their ids across
 * sorts. Each particle of a set carries the set's force times its share of the set's initial volume,
 * added to the nodal forces as N_I(x_p) f_p wherever a step assembles its external forces.
 */
#ifndef PMECH_LOADS_H
#define PMECH_LOADS_H

#include "solver/sim_internal.h"

/** The particle sets of a simulation's loads. */
typedef struct pm_loads {
    size_t n_ids;        /**< entries of load_of_id: ids below it may carry a load */
    int32_t *load_of_id; /**< the load a particle id belongs to (-1: none) */
    double *volume;      /**< per load: its particles' initial volume */
} pm_loads;

/** Find the loads' particle sets of @p s (NULL when the case has none). @return PM_OK, PM_EINPUT
 *  naming a load whose box holds no particle, PM_ENOMEM */
int pm_loads_create(const pm_sim *s, pm_loads **out);

/** Add the loads at time @p t to the nodal forces of @p s (after a step assembled them). */
int pm_loads_apply(pm_sim *s, double t);

/** Free (NULL is fine). */
void pm_loads_destroy(pm_loads *l);

#endif
