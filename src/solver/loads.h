/*
 * Loads on the material (the case's loads[]): a force given in time on a set of particles, found at
 * t = 0 (the particle nearest a point, or the particles in a box) and followed by their ids across
 * sorts. Each particle of a set carries the set's force times its share of the set's initial volume,
 * added to the nodal forces as N_I(x_p) f_p wherever a step assembles its external forces.
 *
 * A load on a grid line (MPM, rectangle grid) is a force per unit length on the part [from, to] of the
 * line, lumped onto the line's nodes as a linear element along the line would: each node takes the
 * integral of its hat function over the loaded part, so the nodal forces sum to the force per length
 * times the loaded length, wherever from and to fall between nodes. A node that carries no material
 * in a step loses its share then (the grid update skips nodes without mass).
 */
#ifndef PMECH_LOADS_H
#define PMECH_LOADS_H

#include "solver/sim_internal.h"

/** The particle sets of a simulation's loads. */
typedef struct pm_loads {
    size_t n_ids;        /**< entries of load_of_id: ids below it may carry a load */
    int32_t *load_of_id; /**< the load a particle id belongs to (-1: none) */
    double *volume;      /**< per load: its particles' initial volume */
    size_t n_line;       /**< grid-line loads' node entries */
    int32_t *line_node;  /**< each entry's node */
    int32_t *line_load;  /**< each entry's load */
    double *line_length; /**< each entry's share of its load's line: the integral of the node's linear
                            shape function along the line over the loaded part (m) */
} pm_loads;

/** Find the loads' particle sets and grid-line nodes of @p s (NULL when the case has none).
 *  @return PM_OK, PM_EINPUT naming a load whose box holds no particle or whose line is no grid line,
 *  PM_ENOMEM */
int pm_loads_create(const pm_sim *s, pm_loads **out);

/** Add the loads at time @p t to the nodal forces of @p s (after a step assembled them). */
int pm_loads_apply(pm_sim *s, double t);

/** Free (NULL is fine). */
void pm_loads_destroy(pm_loads *l);

#endif
