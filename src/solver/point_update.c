/* The parts of the point update that are not on the hot path of every step (see point_update.h). */
#include "point_update.h"

#include "pmech/error.h"

#include <float.h>

int pm_point_plane_stress(const pm_material *m, pm_material_step *in, double *state, const double *state0,
                          size_t n_state, double s6[6], const double s0[6], double T[36])
{
    /* copies: the caller may hand the point's own state and stress as the start values */
    double st0[PM_MAT_MAX_STATE], sg0[6];
    memcpy(st0, state0, n_state * sizeof(double));
    memcpy(sg0, s0, sizeof sg0);
    const double Fzz_old = in->F_old[8];
    double dz = 1.0;
    for (int it = 0; it < 20; it++) {
        memcpy(state, st0, n_state * sizeof(double));
        memcpy(s6, sg0, sizeof sg0);
        in->F_incr[8] = dz;
        in->F_new[8] = dz * Fzz_old;
        if (m->ops->update(m, in, state, s6, T) != PM_OK)
            return 1;
        /* 1e-10 of the in-plane stress: round-off in the stress update leaves about 1e-12 to 1e-13,
         * and a tolerance below that ran every one of half the cutting case's points to the
         * iteration limit, 4 times the cost of the whole step (examples/cutting). Plus the stress of
         * the smallest change of the stretch a double resolves near 1 (a few ulps times T_zz): points
         * at stresses of a pascal cannot get closer than that and alternated about it */
        const double scale = fabs(s6[0]) + fabs(s6[1]) + fabs(s6[3]) + 1e-300;
        if (!(T[14] > 0) || fabs(s6[2]) <= 1e-10 * scale + 8 * DBL_EPSILON * T[14])
            break;
        /* The tangent relates stress to the step's strain in the current configuration, d eps_zz =
         * d dz / dz, so Newton's correction of the stretch is relative: dz *= 1 - s_zz / T_zz. The
         * additive form would use the slope at dz = 1 for every iterate and converge only linearly
         * once the stretch of the step is large. */
        dz *= 1.0 - s6[2] / T[14];
        if (!(dz > 0))
            return 1;
    }
    s6[2] = 0.0;
    return 0;
}

double pm_point_strain_energy(const pm_material *m, const double *F, const double *stress, const double *state)
{
    double s6[6] = {stress[PM_SXX], stress[PM_SYY], stress[PM_SZZ], stress[PM_SXY], 0, 0};
    pm_material_step in;
    memset(&in, 0, sizeof in);
    const double H[4] = {0, 0, 0, 0};
    pm_point_kinematics(F, H, 1.0, &in);
    return m->ops->strain_energy ? m->ops->strain_energy(m, &in, state, s6) : pm_material_elastic_energy(m, &in, NULL, s6);
}
