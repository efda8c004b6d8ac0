/*
 * F-bar volumetric averaging for MPM (Coombs, Charlton, Cortis, Augarde 2018, "Overcoming volumetric
 * locking in material point methods", CMAME 333): the volume change of a step is made uniform over
 * each background cell. Every particle's incremental deformation gradient f keeps its shape but takes
 * the cell's volume ratio,
 *     f_bar = (J_cell / det f)^(1/k) f,   J_cell = sum_c V_p det f_p / sum_c V_p,
 * k = 2 in plane strain (the in-plane block; the out-of-plane stretch stays 1) and 3 in axisymmetric
 * runs (the in-plane block and the hoop stretch). Isochoric flow (von Mises, Mohr-Coulomb or
 * Drucker-Prager with zero dilatancy) then needs one volume constraint per cell instead of one per
 * particle, which linear quads with several particles per cell cannot satisfy without locking.
 *
 * With analysis.fbar_own_share s > 0 a particle keeps the share s of its own volume change,
 * J_bar = J_cell^(1 - s) J_p^s. Full averaging leaves a perfectly plastic flow (no deviatoric
 * stiffness once yielding) one volume constraint per cell and so without resistance to modes that
 * change volume in opposite senses at a cell's particles; with FLIP particle velocities such a mode
 * grows without bound (examples/extrusion at 0.5 mm cells). A small share gives it the bulk stiffness
 * again at the cost of a little of the locking F-bar removes.
 */
#ifndef PMECH_FBAR_H
#define PMECH_FBAR_H

#include "solver/sim_internal.h"

/* The averaging's workspace, sized once: the scale of every particle and the sums of every cell. */
typedef struct pm_fbar {
    double *alpha;  /* per particle: (J_cell / det f_p)^((1 - s)/k), applied by pm_fbar_scale_rate */
    double *det;    /* per particle: det f_p of the step */
    double *sum;    /* per cell: sum V_p det f_p, then sum V_p */
} pm_fbar;

/* Allocate the workspace when the case asks for F-bar (s->fbar stays NULL otherwise). */
int pm_fbar_create(pm_sim *s);

/* Free it; safe when absent. */
void pm_fbar_destroy(pm_sim *s);

/*
 * The scales of a step: every particle's f = I + dt L from the nodal velocities nv (and its hoop
 * stretch 1 + dt v_r / r in axisymmetric runs) over its stencil, averaged per cell with the
 * start-of-step volumes as weights. Needs located particles (connect). Returns the first particle
 * whose f is inverted (det f <= 0), or LONG_MAX.
 */
long pm_fbar_prepare(pm_sim *s, const double *nv, double dt);

/* Scale a step's velocity gradient L (xx, xy, yx, yy) and radial velocity v_r at radius r over dt so
 * that its incremental deformation becomes alpha f: f = I + dt L -> alpha f in plane and, in
 * axisymmetric runs, the hoop stretch 1 + dt v_r / r likewise. Written on the rates so that the
 * point update of the unaveraged path stays as it is. */
static inline void pm_fbar_scale_rate(double alpha, int axisymmetric, double r, double dt, double L[4], double *v_r)
{
    L[0] = (alpha * (1 + dt * L[0]) - 1) / dt;
    L[1] *= alpha;
    L[2] *= alpha;
    L[3] = (alpha * (1 + dt * L[3]) - 1) / dt;
    if (axisymmetric)
        *v_r = (alpha * (1 + dt * *v_r / r) - 1) * r / dt;
}

#endif
