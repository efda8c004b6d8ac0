/*
 * One material point's update, shared by the explicit schemes, the implicit residual and tangent and
 * the energy sums: the 3x3 kinematics built from the in-plane F and a displacement gradient, the
 * out-of-plane stretch (1, from sigma_zz = 0, or the hoop stretch 1 + u_r / r), the material's
 * update, volume from det F, plastic strain and wave speed.
 *
 * The update itself is inline: the explicit passes call it once per particle and step, and a call
 * across files would cost a measurable share of an elastic point's update.
 */
#ifndef PMECH_POINT_UPDATE_H
#define PMECH_POINT_UPDATE_H

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/material.h"
#include "pmech/particles.h"
#include "shape/approx_internal.h"

#include <math.h>
#include <string.h>

#if PM_DIM != 2
#error "point_update.h builds the 3x3 kinematics of a 2-D point only"
#endif

/* The start of the step a point is updated from. */
typedef struct pm_point_from {
    const double *F;      /* deformation gradient, PM_NF entries */
    const double *stress; /* Cauchy stress, PM_NS entries */
    const double *state;  /* history, n_state entries; may be the particle's own (updated in place) */
    double vol;           /* the volume det F scales: the initial one, or the step's start (see incr_vol) */
    int incr_vol;         /* 1: vol is the start-of-step volume, scaled by det F_incr; 0: the initial
                             volume, scaled by det F_new */
} pm_point_from;

/*
 * Fill the 3x3 F_incr, F_old and F_new of a step (row-major) from the in-plane F (PM_NF entries),
 * the in-plane displacement gradient of the step H = d(du)/dx (xx, xy, yx, yy) and the out-of-plane
 * stretch fz of the step. F_new = F_incr F_old. in->dt is left alone.
 */
static inline void pm_point_kinematics(const double *F, const double H[4], double fz, pm_material_step *in)
{
    const double a = 1 + H[0], b = H[1], c = H[2], d = 1 + H[3];
    in->F_incr[0] = a; in->F_incr[1] = b; in->F_incr[2] = 0;
    in->F_incr[3] = c; in->F_incr[4] = d; in->F_incr[5] = 0;
    in->F_incr[6] = 0; in->F_incr[7] = 0; in->F_incr[8] = fz;
    in->F_old[0] = F[PM_FXX]; in->F_old[1] = F[PM_FXY]; in->F_old[2] = 0;
    in->F_old[3] = F[PM_FYX]; in->F_old[4] = F[PM_FYY]; in->F_old[5] = 0;
    in->F_old[6] = 0; in->F_old[7] = 0; in->F_old[8] = F[PM_FZZ];
    in->F_new[0] = a * F[PM_FXX] + b * F[PM_FYX]; in->F_new[1] = a * F[PM_FXY] + b * F[PM_FYY]; in->F_new[2] = 0;
    in->F_new[3] = c * F[PM_FXX] + d * F[PM_FYX]; in->F_new[4] = c * F[PM_FXY] + d * F[PM_FYY]; in->F_new[5] = 0;
    in->F_new[6] = 0; in->F_new[7] = 0; in->F_new[8] = fz * F[PM_FZZ];
}

/*
 * The material's update with sigma_zz = 0: Newton on the out-of-plane stretch of the step, with the
 * model's own d sigma_zz / d eps_zz as slope. Every try starts again from state0 and s0 (either may
 * alias state and s6), so the accepted update is a single step of the model. T (36 entries) receives
 * the tangent of the last try. Returns 0, or 1 if the model failed or the stretch left (0, inf).
 */
int pm_point_plane_stress(const pm_material *m, pm_material_step *in, double *state, const double *state0,
                          size_t n_state, double s6[6], const double s0[6], double T[36]);

/*
 * Update a point over one step: kinematics from `from`, the in-plane displacement gradient H of the
 * step and, in axisymmetric runs, the radial displacement u_r at radius r (hoop stretch 1 + u_r / r);
 * then the material, F, stress, state, volume and plastic strain written to F, stress, state, vol,
 * eps_p. T, when not NULL, receives the model's 6x6 consistent tangent (always filled in plane
 * stress). Returns 0, or 1 if the point failed (inverted, not finite, model failure); F and stress
 * may be written before a failure is found, for the caller's message.
 */
static inline int pm_point_update(const pm_material *m, pm_formulation form, const pm_point_from *from,
                                  const double H[4], double u_r, double r, double dt, size_t n_state, double *F,
                                  double *stress, double *state, double *vol, double *eps_p, double *T)
{
    pm_material_step in;
    const double fz = form == PM_AXISYMMETRIC ? 1 + u_r / r : 1.0;
    pm_point_kinematics(from->F, H, fz, &in);
    in.dt = dt;
    const double J2 = in.F_new[0] * in.F_new[4] - in.F_new[1] * in.F_new[3];
    /* det F_incr > 0 follows from det F_new > 0 but for round-off; it is tested where it scales the
     * volume (the implicit caller also divides by it) */
    const double j2 = from->incr_vol ? in.F_incr[0] * in.F_incr[4] - in.F_incr[1] * in.F_incr[3] : 1.0;
    if (!(J2 > 0) || !(j2 > 0) || !(fz > 0))
        return 1;
    const double *sg0 = from->stress;
    double s6[6] = {sg0[PM_SXX], sg0[PM_SYY], sg0[PM_SZZ], sg0[PM_SXY], 0, 0};
    if (form == PM_PLANE_STRESS) {
        double Tl[36] = {0}; /* the iteration needs the tangent even when the caller does not */
        if (pm_point_plane_stress(m, &in, state, from->state, n_state, s6, s6, T ? T : Tl))
            return 1;
    } else {
        if (from->state != state)
            memcpy(state, from->state, n_state * sizeof(double));
        if (m->ops->update(m, &in, state, s6, T) != PM_OK)
            return 1;
    }
    const double Fzz = in.F_new[8], J = J2 * Fzz;
    F[PM_FXX] = in.F_new[0]; F[PM_FXY] = in.F_new[1]; F[PM_FYX] = in.F_new[3]; F[PM_FYY] = in.F_new[4];
    F[PM_FZZ] = Fzz;
    stress[PM_SXX] = s6[0]; stress[PM_SYY] = s6[1]; stress[PM_SZZ] = s6[2]; stress[PM_SXY] = s6[3];
    if (!isfinite(s6[0] + s6[1] + s6[2] + s6[3]) || !(J > 0))
        return 1;
    *vol = from->incr_vol ? from->vol * (j2 * in.F_incr[8]) : from->vol * J;
    if (m->ops->plastic_strain)
        *eps_p = m->ops->plastic_strain(m, state);
    return 0;
}

/* Speed of the fastest signal at a point for the CFL condition: the material's signal speed at the
 * current density in cells of size h (waves and any explicit viscosity) plus the particle's own speed
 * (velocity v, PM_DIM entries). */
static inline double pm_point_wave_speed(const pm_material *m, const double *state, double mass, double vol,
                                         double h, const double *v)
{
    const double cw = pm_material_signal_speed(m, state, mass / vol, h);
    double v2 = v[0] * v[0];
    for (int d = 1; d < PM_DIM; d++)
        v2 += v[d] * v[d];
    return cw + sqrt(v2);
}

/* Stored energy per unit reference volume of a point at rest in its current state (F, PM_NF entries;
 * stress, PM_NS entries): the kinematics of a step without increment, so models see F_old = F_new. */
double pm_point_strain_energy(const pm_material *m, const double *F, const double *stress, const double *state);

#endif
