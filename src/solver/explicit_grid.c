/*
 * The grid side of the explicit step: nodal velocities from momentum, accelerations from forces with
 * local damping, constraints and boundary friction. Friction (Bardenhagen et al. 2000) is applied to
 * the end-of-step velocity only, node by node after the parallel loops, and the acceleration is then
 * taken from the velocity change so that the particles receive the reaction impulses too.
 */
#include "explicit_internal.h"
#include "meshfree_internal.h"

#include <math.h>

/* Coulomb friction on a grid boundary (Bardenhagen et al. 2000): the approaching normal velocity is
 * removed and the tangential speed reduced by mu times that change, never reversed. */
static void apply_friction(const pm_friction_node *fn, double v[2])
{
    const double *nrm = fn->normal;
    const double vn = v[0] * nrm[0] + v[1] * nrm[1];
    if (vn <= 0)
        return; /* separating or sliding along: free */
    double vt[2] = {v[0] - vn * nrm[0], v[1] - vn * nrm[1]};
    const double speed = hypot(vt[0], vt[1]), cut = fn->mu * vn;
    const double keep = speed > cut ? 1.0 - cut / speed : 0.0;
    v[0] = keep * vt[0];
    v[1] = keep * vt[1];
}

/* Remove only the approaching normal velocity (no friction impulse): for velocities that are
 * re-projected within a step, where the frictional impulse has already been applied. */
static void apply_contact_normal(const pm_friction_node *fn, double v[2])
{
    const double vn = v[0] * fn->normal[0] + v[1] * fn->normal[1];
    if (vn > 0) {
        v[0] -= vn * fn->normal[0];
        v[1] -= vn * fn->normal[1];
    }
}

static void constrain(const pm_nodal *nd, int32_t n, double v[PM_DIM])
{
    for (int d = 0; d < PM_DIM; d++)
        if (nd->fixed[n] & (1u << d))
            v[d] = nd->vfix[PM_DIM * n + d];
}

/* Smallest nodal mass treated as carrying material: guards divisions by round-off masses. */
static double mass_floor(const pm_sim *s)
{
    return s->p.n ? 1e-12 * s->p.mass[0] : 0.0;
}

/* Local (Cundall) damping: the force reduced by alpha times its magnitude against the velocity. */
static inline double damped(double f, double v, double alpha)
{
    return f - alpha * fabs(f) * (v > 0 ? 1.0 : v < 0 ? -1.0 : 0.0);
}

void pm_xp_grid_update(pm_sim *s, double dt, int constrain_start)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = s->grid.n_nodes;
    const double alpha = s->c->analysis.damping, mfloor = mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        double *v = nd->vel + PM_DIM * n, *vn = nd->vel_new + PM_DIM * n, *a = nd->acc + PM_DIM * n;
        const double m = nd->mass[n];
        if (!(m > mfloor)) {
            for (int d = 0; d < PM_DIM; d++)
                v[d] = vn[d] = a[d] = 0;
            continue;
        }
        for (int d = 0; d < PM_DIM; d++) {
            v[d] = nd->mom[PM_DIM * n + d] / m;
            const double f = alpha > 0 ? damped(nd->force[PM_DIM * n + d], v[d], alpha) : nd->force[PM_DIM * n + d];
            vn[d] = v[d] + dt * f / m;
        }
        if (constrain_start)
            constrain(nd, (int32_t)n, v);
        constrain(nd, (int32_t)n, vn);
        /* here rather than in a loop of its own: the velocities are still in registers */
        for (int d = 0; d < PM_DIM; d++)
            a[d] = (vn[d] - v[d]) / dt;
    }
    for (size_t k = 0; k < nd->n_friction; k++) {
        const pm_friction_node *fn = &nd->friction[k];
        const int32_t n = fn->node;
        if (nd->mass[n] > mfloor) {
            apply_friction(fn, nd->vel_new + 2 * n);
            constrain(nd, n, nd->vel_new + 2 * n);
            for (int d = 0; d < 2; d++)
                nd->acc[2 * n + d] = (nd->vel_new[2 * n + d] - nd->vel[2 * n + d]) / dt;
        }
    }
    if (s->mf && s->mf->transform)
        pm_mf_impose_update(s, dt, constrain_start);
}

void pm_xp_grid_velocity_from_momentum(pm_sim *s, double *out)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = s->grid.n_nodes;
    const double mfloor = mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        double *v = out + PM_DIM * n;
        const double m = nd->mass[n];
        for (int d = 0; d < PM_DIM; d++)
            v[d] = m > mfloor ? nd->mom[PM_DIM * n + d] / m : 0.0;
        if (m > mfloor)
            constrain(nd, (int32_t)n, v);
    }
    for (size_t k = 0; k < nd->n_friction; k++) {
        const pm_friction_node *fn = &nd->friction[k];
        apply_contact_normal(fn, out + 2 * fn->node);
        constrain(nd, fn->node, out + 2 * fn->node);
    }
    if (s->mf && s->mf->transform)
        pm_mf_impose(s, out, 0);
}

void pm_xp_grid_newmark(pm_sim *s, double dt, double gamma)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = s->grid.n_nodes;
    const double alpha = s->c->analysis.damping, mfloor = mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        const double m = nd->mass[n];
        double *a = nd->acc + PM_DIM * n, *v = nd->vel + PM_DIM * n, *vn = nd->vel_new + PM_DIM * n;
        for (int d = 0; d < PM_DIM; d++) {
            if (!(m > mfloor)) {
                a[d] = vn[d] = 0;
                continue;
            }
            const double f = alpha > 0 ? damped(nd->force[PM_DIM * n + d], v[d], alpha) : nd->force[PM_DIM * n + d];
            /* prescribed components: acceleration zero, the force is the reaction */
            a[d] = (nd->fixed[n] & (1u << d)) ? 0.0 : f / m;
            vn[d] = v[d] + gamma * dt * a[d];
        }
    }
    for (size_t k = 0; k < nd->n_friction; k++) {
        const pm_friction_node *fn = &nd->friction[k];
        const int32_t n = fn->node;
        if (!(nd->mass[n] > mfloor))
            continue;
        apply_friction(fn, nd->vel_new + 2 * n);
        constrain(nd, n, nd->vel_new + 2 * n);
        for (int d = 0; d < 2; d++)
            nd->acc[2 * n + d] = (nd->vel_new[2 * n + d] - nd->vel[2 * n + d]) / (gamma * dt);
    }
    if (s->mf && s->mf->transform)
        pm_mf_impose(s, nd->acc, 1);
}
