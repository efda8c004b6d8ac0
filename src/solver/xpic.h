/*
 * Extended particle-in-cell update XPIC(m) (Hammerquist and Nairn 2017, "A new method for material
 * point method particle updates that reduces noise and enhances stability", CMAME 318) for the
 * explicit MUSL step.
 *
 * Let S take nodal values to the particles (v_p = sum_i N_i(x_p) v_i) and S+ take particle velocities
 * to the nodes by mass (v_i = sum_p N_i(x_p) m_p v_p / m_i), so that v = S+ V is the step's start grid
 * velocity and v+ its end velocity. FLIP updates V + S (v+ - v) and keeps the part of V that the grid
 * cannot carry (the null space of S+, seen as noise); PIC takes S v+ and loses, besides that, every
 * part of the field that S S+ smooths. XPIC(m) removes the first only, to order m:
 *     V_new = V + S (v+ - v) - (I - S S+)^m V.
 * The eigenvalues of S S+ lie in [0, 1]: a mode it keeps nearly (a long wave, eigenvalue 1 - e) loses
 * e^m instead of PIC's e, a mode it annihilates (eigenvalue 0) is removed entirely. With
 * (S S+)^r V = S P^(r-1) v, P = S+ S, the binomial expansion puts the update on the grid:
 *     V_new = S (v+ + d),   d = v* - v = (m - 1) v + sum_{r=2..m} (-1)^(r+1) C(m, r) P^(r-1) v,
 * m - 1 passes that each take a nodal field to the particles and back by mass, then one pass like
 * PIC's. m = 1 is PIC exactly (d = 0); a uniform field passes unchanged for every m (P keeps it).
 * The recursion uses the unconstrained v = momentum / mass: the constraints reach the particles
 * through v+, as in FLIP's acceleration, so a fixed node's reaction is the same as with FLIP and PIC.
 * Positions move with v+ as with the other transfers. The particles carry nothing beyond their
 * velocity, so checkpoints need no field of their own.
 */
#ifndef PMECH_XPIC_H
#define PMECH_XPIC_H

#include "solver/sim_internal.h"

/* With transfer "xpic": the two nodal work vectors (s->xpic), sized once for the run. Otherwise
 * nothing. Returns PM_OK or PM_ENOMEM. */
int pm_xpic_create(pm_sim *s);

/* MUSL with XPIC(m), m = analysis.xpic_order: every particle's velocity from the start (nd.vel) and
 * end-of-step (nd.vel_new) nodal velocities as above, then its momentum back to the grid (nodal
 * momentum only). Uses nd.mom as the recursion's scatter target. */
void pm_xpic_musl_project(pm_sim *s);

#endif
