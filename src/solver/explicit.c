/*
 * Explicit MPM time step: USF, USL, MUSL (Sulsky et al.; seed 004 section 3.5) and the explicit
 * Newmark predictor-corrector (seed 003 section 2.2, gamma = 1/2), each a chain of the particle
 * passes (explicit_passes.c) and grid updates (explicit_grid.c).
 */
#include "explicit_internal.h"
#include "apic.h"
#include "xpic.h"
#include "fbar.h"
#include "flow.h"
#include "meshfree_internal.h"
#include "contact/contact.h"
#include "solver/loads.h"

#include "pmech/error.h"

#include <limits.h>
#include <math.h>

static int fail_particle(const pm_sim *s, long i, const char *what)
{
    const double *x = s->p.x + PM_DIM * i;
    return pm_error_set(PM_ESIM, "step %ld (t = %.6g s): particle %ld at (%.6g, %.6g) %s", s->step + 1, s->t, i,
                        x[0], x[1], what);
}

static const char *failure_text(const pm_sim *s, long i)
{
    const double *F = s->p.F + PM_NF * i;
    double J = (F[PM_FXX] * F[PM_FYY] - F[PM_FXY] * F[PM_FYX]) * F[PM_FZZ];
    return J > 0 && isfinite(J) ? "failed: its stress or velocity is not finite (the run diverged; try a "
                                  "smaller dt or cfl)"
                                : "inverted (det F <= 0): the run diverged; try a smaller dt or cfl";
}

/* The particles an obstacle holds at its touching points take the velocity they move with
 * (touching.c); XPIC and APIC build the particles' velocities from the grid's and need it not. */
static void contact_particles(pm_sim *s, double shift)
{
    if (s->c->analysis.transfer == PM_TRANSFER_FLIP)
        pm_contact_particle_velocities(s->contact, s->approx, &s->p, s->nd.vel, shift);
}

/* USL and MUSL: forces from the stress at the start, then (MUSL) velocities re-projected. */
static int step_usl_musl(pm_sim *s, double dt, int musl)
{
    double g[PM_DIM];
    pm_sim_gravity(s, s->t, g);
    long bad = pm_xp_p2g(s, 0.0, 1, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, "is outside the grid");
    const int apic = s->c->analysis.transfer == PM_TRANSFER_APIC; /* MUSL only (case_analysis.c) */
    if (apic)
        pm_apic_p2g_momentum(s);
    pm_check(pm_loads_apply(s, s->t));
    pm_xp_grid_update(s, dt);
    contact_particles(s, 0.0);
    pm_nodal *nd = &s->nd;
    if (musl) {
        if (apic)
            pm_apic_musl_project(s);
        else if (s->xpic) /* transfer "xpic", MUSL only (case_analysis.c) */
            pm_xpic_musl_project(s);
        else
            pm_xp_musl_project(s, dt);
        /* nd->vel now holds the re-projected velocity used for the strain rate */
        pm_xp_grid_velocity_from_momentum(s, nd->vel);
    }
    const double *vs = musl ? nd->vel : pm_xp_grid_usl_strain_velocity(s, dt);
    if (s->fbar && (bad = pm_fbar_prepare(s, vs, dt)) != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    const long failed = pm_xp_usl_finish(s, dt, musl, vs);
    if (failed != LONG_MAX)
        return fail_particle(s, failed, failure_text(s, failed));
    return PM_OK;
}

/* USF: stress first from the projected velocity, then forces from the new stress. */
static int step_usf(pm_sim *s, double dt)
{
    double g[PM_DIM];
    pm_sim_gravity(s, s->t, g);
    long bad = pm_xp_p2g(s, 0.0, 0, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, "is outside the grid");
    pm_xp_grid_velocity_from_momentum(s, s->nd.vel);
    if (s->fbar && (bad = pm_fbar_prepare(s, s->nd.vel, dt)) != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    bad = pm_xp_stress_and_force(s, dt, s->nd.vel, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    pm_check(pm_loads_apply(s, s->t));
    pm_xp_grid_update(s, dt);
    contact_particles(s, 0.0);
    pm_xp_g2p_usf(s, dt);
    return PM_OK;
}

/*
 * Explicit Newmark predictor-corrector (seed 003, Algorithm of section 2.2, gamma = 1/2):
 * predicted nodal velocity from v_p + (1 - gamma) dt a_p, strain from it, forces from the new
 * stress, corrector v = v_pred + gamma dt a; particles: a_p = N a, v_p += dt ((1-gamma) a_p_old +
 * gamma a_p), x_p += dt N v_pred (= dt v + dt^2/2 a, the central-difference position).
 */
static int step_newmark_pc(pm_sim *s, double dt)
{
    const double gamma = 0.5;
    double g[PM_DIM];
    pm_sim_gravity(s, s->t + dt, g);
    long bad = pm_xp_p2g(s, (1 - gamma) * dt, 0, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, "is outside the grid");
    pm_xp_grid_velocity_from_momentum(s, s->nd.vel);
    if (s->fbar && (bad = pm_fbar_prepare(s, s->nd.vel, dt)) != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    bad = pm_xp_stress_and_force(s, dt, s->nd.vel, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    pm_check(pm_loads_apply(s, s->t + dt));
    pm_xp_grid_newmark(s, dt, gamma);
    contact_particles(s, (1 - gamma) * dt);
    pm_xp_g2p_newmark(s, dt, gamma);
    return PM_OK;
}

int pm_sim_update_stresses(pm_sim *s, const double *nodal_v, double dt)
{
    pm_check(s->approx->ops->connect(s->approx, &s->p));
    long bad = s->fbar ? pm_fbar_prepare(s, nodal_v, dt) : LONG_MAX;
    if (bad == LONG_MAX)
        bad = pm_xp_stress_only(s, nodal_v, dt);
    return bad == LONG_MAX ? PM_OK : fail_particle(s, bad, failure_text(s, bad));
}

int pm_explicit_step(pm_sim *s, double dt)
{
    int rc = s->approx->ops->connect(s->approx, &s->p);
    if (rc)
        return pm_error_prefix(PM_ESIM, "step %ld (t = %.6g s): ", s->step + 1, s->t);
    pm_sim_update_constraints(s);
    pm_contact_gaps(s->contact, s->approx, &s->p); /* from where the material is at the step's start */
    if (s->rho_p && (rc = pm_sim_volumes_from_positions(s)) != PM_OK)
        return pm_error_prefix(PM_ESIM, "step %ld (t = %.6g s): ", s->step + 1, s->t);
    /* particles drift apart in memory as they move; a periodic sort keeps the scatters local (and
     * puts particles a source appended among their neighbours); the contact's touching
     * points, found before, follow their particles */
    const int appended = pm_flow_take_changed(s);
    const int sort = s->sort_interval > 0 && (s->step % s->sort_interval == 0 || appended) &&
                     s->grid.n_cells < UINT32_MAX;
    if (sort) {
        pm_sim_sort_particles(s);
        pm_contact_renumber(s->contact, s->perm, s->p.n);
    }
    pm_scatter_prepare(s, sort);
    pm_flow_before_step(s);
    switch (s->c->analysis.scheme) {
    case PM_SCHEME_USF: rc = step_usf(s, dt); break;
    case PM_SCHEME_USL: rc = step_usl_musl(s, dt, 0); break;
    case PM_SCHEME_NEWMARK_PC: rc = step_newmark_pc(s, dt); break;
    default: rc = step_usl_musl(s, dt, 1); break;
    }
    if (rc)
        return rc;
    s->t += dt;
    s->step++;
    if (s->flow && (rc = pm_flow_after_step(s)) != PM_OK)
        return rc;
    if (s->mf) /* the particles moved with the predicted velocity in the predictor-corrector */
        return pm_mf_after_explicit(s, dt, s->c->analysis.scheme == PM_SCHEME_NEWMARK_PC ? s->nd.vel : s->nd.vel_new);
    return PM_OK;
}
