/*
 * The grid side of the explicit step: nodal velocities from momentum, accelerations from forces with
 * local damping, constraints, then contact (src/contact): its law acts on the end-of-step velocity
 * only, node by node after the parallel loops, and the acceleration is then taken from the velocity
 * change so that the particles receive the reaction impulses too. The nodes a nodal-law surface may
 * hold meet its law undamped (contact_undamp), so that its reported force is the material's. Last,
 * USL's strain velocity, in which nodes a particle has only just reached take part of their increment.
 */
#include "explicit_internal.h"
#include "meshfree_internal.h"
#include "contact/contact.h"
#include "contact/multibody.h"

#include <math.h>
#include <string.h>

static void constrain(const pm_nodal *nd, int32_t n, double v[PM_DIM])
{
    for (int d = 0; d < PM_DIM; d++)
        if (nd->fixed[n] & (1u << d))
            v[d] = nd->vfix[PM_DIM * n + d];
}

double pm_xp_mass_floor(const pm_sim *s)
{
    return s->p.n ? 1e-12 * s->p.mass[0] : 0.0;
}

/* Local (Cundall) damping: the force reduced by alpha times its magnitude against the velocity. */
static inline double damped(double f, double v, double alpha)
{
    return f - alpha * fabs(f) * (v > 0 ? 1.0 : v < 0 ? -1.0 : 0.0);
}

/* End velocity of node n from its forces over dt_acc, damped by alpha (0: not), with its prescribed
 * components: as the two grid updates below compute it (newmark: acceleration zero on prescribed
 * components, the contact imposes them), so that a node's damped value here is bit for bit theirs. */
static inline void end_velocity(const pm_nodal *nd, size_t n, double dt_acc, double alpha, int newmark,
                                double vn[PM_DIM])
{
    const double m = nd->mass[n], *v = nd->vel + PM_DIM * n;
    for (int d = 0; d < PM_DIM; d++) {
        const double f = alpha > 0 ? damped(nd->force[PM_DIM * n + d], v[d], alpha) : nd->force[PM_DIM * n + d];
        if (newmark)
            vn[d] = v[d] + dt_acc * ((nd->fixed[n] & (1u << d)) ? 0.0 : f / m);
        else
            vn[d] = v[d] + dt_acc * f / m;
    }
    constrain(nd, (int32_t)n, vn);
}

/* Whether contact entry cn is one whose law holds its node's velocity (the nodal law) on a node with
 * material. */
static inline int nodal_entry(const pm_sim *s, const pm_contact_node *cn, double mfloor)
{
    return s->contact->surface[cn->surface].law == PM_CONTACT_LAW_NODAL_COULOMB && s->nd.mass[cn->node] > mfloor;
}

/*
 * Local damping stays out of the nodes a nodal-law surface holds. Its force, alpha |f| against the
 * velocity, is no force of the material: at a node a moving footing drives, it points against the
 * footing's motion, so the law's impulse, which replaces the node's end velocity by the footing's,
 * had to overcome it as well and the footing's reported force was (1 + alpha) times the clay's
 * resistance (Prandtl's footing, damping 0, 0.05 and 0.10: 0.95, 1.01 and 1.07 times Prandtl, see
 * docs/verification-notes.md). So these nodes enter the law with their undamped velocity, and those
 * it left alone get their damping back after it (contact_damp_free).
 */
static void contact_undamp(pm_sim *s, double dt_acc, int newmark, double mfloor)
{
    const pm_contact *ct = s->contact;
    for (size_t k = 0; ct && k < ct->n_node; k++)
        if (nodal_entry(s, &ct->node[k], mfloor))
            end_velocity(&s->nd, (size_t)ct->node[k].node, dt_acc, 0.0, newmark,
                         s->nd.vel_new + PM_DIM * (size_t)ct->node[k].node);
}

/* After the law: a node whose velocity it did not change (still its undamped one) takes its damped
 * velocity, and the acceleration from it as pm_contact_apply() gives it; one the law changed keeps the
 * law's. Comparing with the undamped value, rather than reading the entry's flag, also leaves alone a
 * node that one surface held and another, also touching it, did not. */
static void contact_damp_free(pm_sim *s, double dt_acc, int newmark, double mfloor)
{
    const pm_contact *ct = s->contact;
    pm_nodal *nd = &s->nd;
    const double alpha = s->c->analysis.damping;
    for (size_t k = 0; ct && k < ct->n_node; k++) {
        if (!nodal_entry(s, &ct->node[k], mfloor))
            continue;
        const size_t n = (size_t)ct->node[k].node;
        double *vn = nd->vel_new + PM_DIM * n, u[PM_DIM];
        end_velocity(nd, n, dt_acc, 0.0, newmark, u);
        if (memcmp(u, vn, sizeof u) != 0)
            continue;
        end_velocity(nd, n, dt_acc, alpha, newmark, vn);
        for (int d = 0; d < PM_DIM; d++)
            nd->acc[PM_DIM * n + d] = (vn[d] - nd->vel[PM_DIM * n + d]) / dt_acc;
    }
}

void pm_xp_grid_update(pm_sim *s, double dt)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = nd->n_all;
    const double alpha = s->c->analysis.damping, mfloor = pm_xp_mass_floor(s);
    const int meshfree = s->mf != NULL;
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
        /* MPM constrains only the end velocity: a start velocity set to the prescribed one makes the
         * acceleration of a fixed node zero, and the particles beside a rough floor or a wall keep
         * their velocity from step to step (the FLIP update never learns of the constraint) and pump
         * it back into the free nodes: a granular column ran out 60-70 % too far. GMM and RKPM keep
         * the start constraint: their values are imposed on transformed coefficients, and giving the
         * impulse to the particles there made the GMM vibrating bar lose 1.6 % of its energy in 3.8
         * periods instead of 0.3 % (verify_meshfree_patch) */
        if (meshfree)
            constrain(nd, (int32_t)n, v);
        constrain(nd, (int32_t)n, vn);
        /* here rather than in a loop of its own: the velocities are still in registers */
        for (int d = 0; d < PM_DIM; d++)
            a[d] = (vn[d] - v[d]) / dt;
    }
    /* body fields keep the damping at contact nodes: their entries name each field's nodes in turn */
    const int undamp = alpha > 0 && !s->mb;
    if (undamp)
        contact_undamp(s, dt, 0, mfloor);
    if (s->mb)
        pm_multibody_apply(s, nd->vel_new, dt, dt);
    else
        pm_contact_apply(s->contact, pm_contact_field_of(nd, nd->vel_new, mfloor), dt, dt);
    if (undamp)
        contact_damp_free(s, dt, 0, mfloor);
    if (s->mf && s->mf->transform)
        pm_mf_impose_update(s, dt);
}

void pm_xp_grid_velocity_from_momentum(pm_sim *s, double *out)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = nd->n_all;
    const double mfloor = pm_xp_mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        double *v = out + PM_DIM * n;
        const double m = nd->mass[n];
        for (int d = 0; d < PM_DIM; d++)
            v[d] = m > mfloor ? nd->mom[PM_DIM * n + d] / m : 0.0;
        if (m > mfloor)
            constrain(nd, (int32_t)n, v);
    }
    if (s->mb)
        pm_multibody_project(s, out);
    else
        pm_contact_project_normal(s->contact, pm_contact_field_of(nd, out, mfloor));
    if (s->mf && s->mf->transform)
        pm_mf_impose(s, out, 0);
}

void pm_xp_grid_newmark(pm_sim *s, double dt, double gamma)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = nd->n_all;
    const double alpha = s->c->analysis.damping, mfloor = pm_xp_mass_floor(s);
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
    const int undamp = alpha > 0 && !s->mb;
    if (undamp)
        contact_undamp(s, gamma * dt, 1, mfloor);
    if (s->mb)
        pm_multibody_apply(s, nd->vel_new, dt, gamma * dt);
    else
        pm_contact_apply(s->contact, pm_contact_field_of(nd, nd->vel_new, mfloor), dt, gamma * dt);
    if (undamp)
        contact_damp_free(s, gamma * dt, 1, mfloor);
    if (s->mf && s->mf->transform)
        pm_mf_impose(s, nd->acc, 1);
}

/*
 * USL takes the strain rate from the end-of-step nodal velocity v + dt f / m. At a node that a particle
 * has only just reached, m is a sliver of the particle's mass while f, from the stress and the gradient
 * of a shape function that is small there but steep, is not: the increment grows as 1 / m. Such a node
 * and the particles beside it form a mode that the step integrates like forward Euler: each step the
 * stress changes by -alpha times itself, alpha = C^2 / s with C = (c + |v|) dt / h the step's Courant
 * number and s the fraction of a cell the particles have crossed into, so the mode grows once alpha > 2
 * (a block's front face crossing a grid line: a node of 2e-5 particle masses gave the front particles
 * a strain of 0.27 in one step and the sliding block diverged at 0.029 s; on the incline at 25 degrees
 * a node of 0.026 particle masses grew by 1.5 per step). With n x n points per cell the node carries
 * s n particle masses (2 x 2 points), so alpha = C^2 n m_p / m. Here a node lighter than M = 2 C^2 m_p
 * (m_p the heaviest particle's mass) adds only the share m / M of its increment to its start-of-step
 * velocity, which is USF's: alpha then stays at most n / 2 for uniform points (1 for 2 x 2) and 1.5 for
 * the Gauss points of 3 x 3 to 6 x 6, whatever C, where a face crosses a grid line; a node of fuller
 * mass keeps USL's velocity exactly (and USL's own limit at high C, at a body's corner, stays).
 * Momentum is untouched: the particles' velocities and positions take the full increments.
 */
const double *pm_xp_grid_usl_strain_velocity(pm_sim *s, double dt)
{
    pm_nodal *nd = &s->nd;
    if (s->mf) /* GMM and RKPM: the nodal values are transformed coefficients, not velocities */
        return nd->vel_new;
    double m_p = 0.0;
    const double *pmass = s->p.mass;
    const size_t np = s->p.n;
#pragma omp parallel for schedule(static) reduction(max : m_p) num_threads(nd->n_threads)
    for (size_t i = 0; i < np; i++)
        m_p = fmax(m_p, pmass[i]);
    /* the first step has no wave speed yet; its step is the case's cfl */
    const double courant = s->max_wave > 0 ? s->max_wave * dt / s->grid.h_min : s->c->analysis.cfl;
    const double m_c = 2.0 * courant * courant * m_p, mfloor = pm_xp_mass_floor(s);
    const size_t nn = nd->n_all;
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        const double m = s->mb ? pm_multibody_strain_mass(s, n) : nd->mass[n];
        const double *vn = nd->vel_new + PM_DIM * n, *a = nd->acc + PM_DIM * n;
        double *out = nd->vel_strain + PM_DIM * n;
        const double keep = nd->mass[n] > mfloor && m < m_c ? 1.0 - m / m_c : 0.0;
        /* the increment is dt a, as the particles take it: from the start velocity the laws left the
         * node (a no_slip pair's, its centre of mass's); prescribed components keep their value */
        for (int d = 0; d < PM_DIM; d++)
            out[d] = (nd->fixed[n] & (1u << d)) ? vn[d] : vn[d] - keep * dt * a[d];
    }
    return nd->vel_strain;
}
