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
#include "point_update.h"

#include "pmech/error.h"

#include <math.h>
#include <string.h>

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
    const double *N = w->st_N + o0, *dN = w->st_dN + PM_DIM * (size_t)o0;
    double H[4] = {0, 0, 0, 0}, ur = 0;
    for (int k = 0; k < n; k++) {
        const double *u = du + PM_DIM * node[k];
        for (int e = 0; e < PM_DIM; e++)
            for (int f = 0; f < PM_DIM; f++)
                H[PM_DIM * e + f] += u[e] * dN[PM_DIM * k + f];
        ur += u[0] * N[k];
    }
    const pm_material *m = &s->c->materials[p->material[i]];
    const size_t ns = p->n_state;
    const pm_point_from from = {w->F_n + PM_NF * i, w->stress_n + PM_NS * i, w->state_n + ns * i, w->vol_n[i], 1};
    const double r_n = w->x_n[PM_DIM * i];
    double T[36] = {0};
    if (pm_point_update(m, form, &from, H, ur, r_n, w->dt, ns, p->F + PM_NF * i, p->stress + PM_NS * i,
                        p->state + ns * i, &p->vol[i], &p->eps_p[i], want_tangent ? T : NULL))
        return 1;
    const double a = 1 + H[0], b = H[1], cc = H[2], d = 1 + H[3];
    const double detf = a * d - b * cc;
    /* dN/dx_{n+1} = dN/dx_n f^{-1} */
    const double id = 1.0 / detf;
    const double fi[4] = {d * id, -b * id, -cc * id, a * id};
    const double r = r_n + ur;
    c->n = n;
    c->V = p->vol[i];
    for (int k = 0; k < n; k++) {
        const double gx = dN[PM_DIM * k], gy = dN[PM_DIM * k + 1];
        c->g[k][0] = gx * fi[0] + gy * fi[2];
        c->g[k][1] = gx * fi[1] + gy * fi[3];
        c->hoop[k] = form == PM_AXISYMMETRIC ? N[k] / r : 0.0;
    }
    memcpy(c->sig, p->stress + PM_NS * i, 4 * sizeof(double));
    if (want_tangent)
        reduce_tangent(T, form, c->D);
    return 0;
}
