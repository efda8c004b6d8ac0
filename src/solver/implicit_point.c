/*
 * One material point of the implicit solver: the kinematics of the step from the nodal displacement
 * increments, the material's stress update and consistent tangent, and the current-configuration
 * gradients the updated-Lagrangian residual and tangent are built from (seed 000 section 3).
 *
 * Gradients are evaluated once per step at the start-of-step positions (the grid's own shape
 * functions) and pushed forward with the inverse of the incremental deformation gradient, which is
 * the same as letting the grid nodes move with the iteration's displacements (seed 000: "nodes are
 * allowed to move during the iterative procedure").
 */
#include "implicit_internal.h"

#include "pmech/error.h"

#include <math.h>
#include <string.h>

/* The material update with sigma_zz = 0 (plane stress): Newton on the out-of-plane stretch with the
 * model's own d sigma_zz / d eps_zz; every retry starts from the start-of-step stress and state. */
static int update_plane_stress(const pm_material *m, pm_material_step *in, double *state, const double *state0,
                               size_t n_state, double s6[6], const double s0[6], double T[36])
{
    double dz = 1.0;
    const double Fzz_old = in->F_old[8];
    for (int it = 0; it < 20; it++) {
        memcpy(state, state0, n_state * sizeof(double));
        memcpy(s6, s0, 6 * sizeof(double));
        in->F_incr[8] = dz;
        in->F_new[8] = dz * Fzz_old;
        if (m->ops->update(m, in, state, s6, T) != PM_OK)
            return 1;
        const double scale = fabs(s6[0]) + fabs(s6[1]) + fabs(s6[3]) + 1e-300;
        if (fabs(s6[2]) <= 1e-13 * scale || !(T[14] > 0))
            break;
        dz *= 1.0 - s6[2] / T[14];
        if (!(dz > 0))
            return 1;
    }
    s6[2] = 0.0;
    return 0;
}

/* Tangent on (xx, yy, zz, xy) from the model's 6x6; plane stress condenses sigma_zz = 0 out. */
static void reduce_tangent(const double T[36], pm_formulation form, double D[16])
{
    static const int idx[4] = {0, 1, 2, 3};
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            D[4 * a + b] = T[6 * idx[a] + idx[b]];
    if (form != PM_PLANE_STRESS)
        return;
    const double dzz = D[10];
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            if (a != 2 && b != 2)
                D[4 * a + b] -= dzz != 0 ? D[4 * a + 2] * D[8 + b] / dzz : 0.0;
    for (int k = 0; k < 4; k++)
        D[4 * k + 2] = D[8 + k] = 0.0;
}

int pm_implicit_point(pm_sim *s, pm_implicit_ws *w, size_t i, const double *du, int want_tangent,
                      pm_point_contrib *c)
{
    pm_particles *p = &s->p;
    const pm_formulation form = s->c->formulation;
    const int32_t o0 = w->st_off[i], n = w->st_off[i + 1] - o0;
    const int32_t *node = w->st_node + o0;
    const double *N = w->st_N + o0, *dN = w->st_dN + 2 * (size_t)o0;
    double H[4] = {0, 0, 0, 0}, ur = 0;
    for (int k = 0; k < n; k++) {
        const double *u = du + 2 * node[k];
        H[0] += u[0] * dN[2 * k];
        H[1] += u[0] * dN[2 * k + 1];
        H[2] += u[1] * dN[2 * k];
        H[3] += u[1] * dN[2 * k + 1];
        ur += u[0] * N[k];
    }
    const double a = 1 + H[0], b = H[1], cc = H[2], d = 1 + H[3];
    const double detf = a * d - b * cc;
    const double r_n = w->x_n[2 * i];
    const double fz = form == PM_AXISYMMETRIC ? 1 + ur / r_n : 1.0;
    if (!(detf > 0) || !(fz > 0))
        return 1;
    const double *Fn = w->F_n + PM_NF * i;
    pm_material_step in;
    memset(&in, 0, sizeof in);
    in.F_incr[0] = a; in.F_incr[1] = b; in.F_incr[3] = cc; in.F_incr[4] = d; in.F_incr[8] = fz;
    in.F_old[0] = Fn[PM_FXX]; in.F_old[1] = Fn[PM_FXY];
    in.F_old[3] = Fn[PM_FYX]; in.F_old[4] = Fn[PM_FYY]; in.F_old[8] = Fn[PM_FZZ];
    in.F_new[0] = a * Fn[PM_FXX] + b * Fn[PM_FYX];
    in.F_new[1] = a * Fn[PM_FXY] + b * Fn[PM_FYY];
    in.F_new[3] = cc * Fn[PM_FXX] + d * Fn[PM_FYX];
    in.F_new[4] = cc * Fn[PM_FXY] + d * Fn[PM_FYY];
    in.F_new[8] = fz * Fn[PM_FZZ];
    in.dt = w->dt;
    const pm_material *m = &s->c->materials[p->material[i]];
    const size_t ns = p->n_state;
    double *state = p->state + ns * i;
    const double *state0 = w->state_n + ns * i, *sg0 = w->stress_n + PM_NS * i;
    const double s0[6] = {sg0[PM_SXX], sg0[PM_SYY], sg0[PM_SZZ], sg0[PM_SXY], 0, 0};
    double s6[6], T[36] = {0};
    if (form == PM_PLANE_STRESS) {
        if (update_plane_stress(m, &in, state, state0, ns, s6, s0, T))
            return 1;
    } else {
        memcpy(state, state0, ns * sizeof(double));
        memcpy(s6, s0, sizeof s6);
        if (m->ops->update(m, &in, state, s6, want_tangent ? T : NULL) != PM_OK)
            return 1;
    }
    if (!isfinite(s6[0] + s6[1] + s6[2] + s6[3]))
        return 1;
    double *F = p->F + PM_NF * i, *sg = p->stress + PM_NS * i;
    F[PM_FXX] = in.F_new[0]; F[PM_FXY] = in.F_new[1]; F[PM_FYX] = in.F_new[3]; F[PM_FYY] = in.F_new[4];
    F[PM_FZZ] = in.F_new[8];
    sg[PM_SXX] = s6[0]; sg[PM_SYY] = s6[1]; sg[PM_SZZ] = s6[2]; sg[PM_SXY] = s6[3];
    const double Jf = detf * in.F_incr[8];
    p->vol[i] = w->vol_n[i] * Jf;
    if (m->ops->plastic_strain)
        p->eps_p[i] = m->ops->plastic_strain(m, state);
    /* dN/dx_{n+1} = dN/dx_n f^{-1} */
    const double id = 1.0 / detf;
    const double fi[4] = {d * id, -b * id, -cc * id, a * id};
    const double r = r_n + ur;
    c->n = n;
    c->V = p->vol[i];
    for (int k = 0; k < n; k++) {
        const double gx = dN[2 * k], gy = dN[2 * k + 1];
        c->g[k][0] = gx * fi[0] + gy * fi[2];
        c->g[k][1] = gx * fi[1] + gy * fi[3];
        c->hoop[k] = form == PM_AXISYMMETRIC ? N[k] / r : 0.0;
    }
    memcpy(c->sig, s6, 4 * sizeof(double));
    if (want_tangent)
        reduce_tangent(T, form, c->D);
    return 0;
}
