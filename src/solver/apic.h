/*
 * Affine particle-in-cell transfer (APIC; Jiang, Schroeder, Selle, Teran, Stomakhin 2015, "The affine
 * particle-in-cell method", ACM TOG 34) for the explicit MUSL step. Every particle carries, besides
 * its velocity v_p, an affine velocity matrix C_p (pm_particles::C); its momentum reaches node i as
 *     m_p N_i(x_p) (v_p + C_p (x_i - x_p)),
 * and the grid-to-particle transfer rebuilds both from the end-of-step nodal velocities,
 *     v_p = sum_i N_i v_i,   C_p = sum_i v_i (x) grad N_i(x_p).
 * With shape functions that reproduce linear fields (sum N_i (x_i - x_p) = 0 and sum (x_i - x_p) (x)
 * grad N_i = I), a velocity field that is affine over a particle's stencil goes to the grid and back
 * unchanged: PIC's loss of rotation and shear at the grid scale disappears, without FLIP's noise.
 */
#ifndef PMECH_APIC_H
#define PMECH_APIC_H

#include "solver/sim_internal.h"

/* The nodal momentum of every particle's velocity and affine matrix, replacing the momentum of the
 * particle-to-grid pass (pm_xp_p2g, which has located the particles and scattered their mass). */
void pm_apic_p2g_momentum(pm_sim *s);

/* MUSL with APIC: every particle's velocity and affine matrix from the end-of-step nodal velocities
 * (nd.vel_new), then their momentum back to the grid (nodal momentum only). */
void pm_apic_musl_project(pm_sim *s);

#endif
