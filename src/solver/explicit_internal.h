/*
 * The pieces of the explicit MPM step (src/solver/explicit*.c): the particle passes
 * (explicit_passes.c), the grid updates (explicit_grid.c) and the schemes that chain them
 * (explicit.c). Every particle pass evaluates shape functions at the positions of the start of the
 * step (the grid is the undeformed one during the step), so positions are moved in the last pass.
 */
#ifndef PMECH_EXPLICIT_INTERNAL_H
#define PMECH_EXPLICIT_INTERNAL_H

#include "solver/sim_internal.h"
#include "scatter.h"

/* Shape functions of particle i through the approximation's interface; with body fields its nodes
 * are those of the particle's own field (contact/multibody.h). */
int pm_xp_stencil(const pm_sim *s, size_t i, pm_stencil *st);

/* Smallest nodal mass treated as carrying material: guards divisions by round-off masses. */
double pm_xp_mass_floor(const pm_sim *s);

/* Mass, momentum (of v + mom_shift * a) and, with with_force, internal force plus weight (gravity g)
 * of every particle to the grid. Returns the first particle outside the grid, or LONG_MAX. */
long pm_xp_p2g(pm_sim *s, double mom_shift, int with_force, const double g[PM_DIM]);

/* MUSL: particle velocities from the nodal accelerations over dt, then their momentum back to the
 * grid (nodal momentum only). */
void pm_xp_musl_project(pm_sim *s, double dt);

/* USL and MUSL, last pass: strain rate from the nodal velocity vs, stress, velocity (USL only: from
 * the nodal acceleration) and position from the end-of-step nodal velocity. Sets s->max_wave;
 * returns the first failed particle, or LONG_MAX. */
long pm_xp_usl_finish(pm_sim *s, double dt, int musl, const double *vs);

/* USF and predictor-corrector: strain rate from the nodal velocity nv, stress, then its internal
 * force plus weight (gravity g) to the nodal forces. Sets s->max_wave; returns the first failed
 * particle, or LONG_MAX. */
long pm_xp_stress_and_force(pm_sim *s, double dt, const double *nv, const double g[PM_DIM]);

/* USF, last pass: velocity from the nodal acceleration, position from the end-of-step nodal
 * velocity. */
void pm_xp_g2p_usf(pm_sim *s, double dt);

/* Predictor-corrector, last pass: a_p = N a, v_p += dt ((1 - gamma) a_p_old + gamma a_p), x_p += dt
 * N v_pred. */
void pm_xp_g2p_newmark(pm_sim *s, double dt, double gamma);

/* Stress of every particle from the nodal velocity nodal_v over dt, nothing scattered. Sets
 * s->max_wave; returns the first failed particle (or one outside the grid), or LONG_MAX. */
long pm_xp_stress_only(pm_sim *s, const double *nodal_v, double dt);

/* Nodal velocities from momentum, end-of-step velocities from forces with local damping, constraints
 * on the end-of-step velocity (meshfree: on the start velocity too) and friction; acc = (v_new - v) / dt.
 * In MPM a prescribed component's acceleration is therefore the change from the projected to the
 * prescribed velocity: the particles' velocity update (FLIP) receives the reaction's impulse, as the
 * grid does. */
void pm_xp_grid_update(pm_sim *s, double dt);

/* Nodal velocities from momentum into out, with constraints and the contact normal. */
void pm_xp_grid_velocity_from_momentum(pm_sim *s, double *out);

/* Predictor-corrector nodal update: acc from forces with local damping, v_new = vel + gamma dt acc,
 * constraints and friction. */
void pm_xp_grid_newmark(pm_sim *s, double dt, double gamma);

/* USL, after pm_xp_grid_update: the end-of-step nodal velocity the strain rate takes, into
 * nd.vel_strain (returned): v_new, except at nodes lighter than 2 C^2 times the heaviest particle's mass
 * (C the step's Courant number), which add only their mass over that to their start velocity (the
 * reasons in explicit_grid.c). GMM and RKPM: v_new itself. */
const double *pm_xp_grid_usl_strain_velocity(pm_sim *s, double dt);

#endif
