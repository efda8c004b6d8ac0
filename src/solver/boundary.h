/* Boundary conditions of a simulation: prescribed (fixed, velocity) node sets, velocity conditions
 * that end at a given time, and the node set a condition names. Friction conditions are contact
 * surfaces (src/contact). */
#ifndef PMECH_BOUNDARY_H
#define PMECH_BOUNDARY_H

#include "pmech/case.h"
#include "pmech/grid.h"
#include "solver/sim_internal.h"

/* The grid nodes of boundary_conditions[b] at t = 0: a named side or group, or a line (whose set is
 * added to g, restricted to its from..to and given its normal). PM_EINPUT naming the condition when
 * the boundary does not exist or holds no node. */
int pm_bc_node_set(const pm_case *c, size_t b, pm_grid *g, const pm_node_set **out);

/* The prescribed components of every fixed and velocity condition into nd->fixed / nd->vfix (with
 * the axis r = 0 of an axisymmetric run held radially), and the conditions with an `until` time into
 * nd->timed (pm_sim_update_constraints switches them: velocity conditions are then held, fixed ones
 * released). PM_EINPUT when a fixed condition to be released shares a held component with another. */
int pm_bc_setup(const pm_case *c, pm_grid *g, pm_nodal *nd);

#endif
