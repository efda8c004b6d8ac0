/*
 * Implicit MPM step (seed 000 Algorithm 1): initial phase (projection, Newmark predictor with the
 * displacement increment starting at zero), UL-FEM phase (Newton iterations on the nodal
 * displacement increments with a sparse direct solve each), convection phase (displacement,
 * acceleration and velocity to the particles, positions moved, the grid reset by simply not keeping
 * anything nodal). Quasi-static steps are the same without inertia.
 *
 * A step that does not converge is halved and retried from the saved start-of-step particle state.
 */
#include "implicit_internal.h"
#include "meshfree_internal.h"

#include "contact/contact.h"

#include "pmech/error.h"
#include "pmech/grid.h"
#include "io/progress.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A relative residual above this is divergence, not slow convergence. */
#define PM_NEWTON_DIVERGED 1e8
/* A first correction of a step is accepted without damping while its relative residual is below this. */
#define PM_FIRST_ACCEPT 0.1

static double norm2(const double *v, int n)
{
    double s = 0;
    for (int k = 0; k < n; k++)
        s += v[k] * v[k];
    return sqrt(s);
}

/* Norm of a nodal vector over the unknowns. */
static double free_norm(const pm_implicit_ws *w, const double *nodal)
{
    double s = 0;
    for (size_t k = 0; k < 2 * w->nn; k++)
        if (w->dof[k] >= 0)
            s += nodal[k] * nodal[k];
    return sqrt(s);
}

static void set_du(pm_implicit_ws *w, const double *base, const double *delta, double step)
{
    for (size_t k = 0; k < 2 * w->nn; k++) {
        const int d = w->dof[k];
        if (d >= 0)
            w->du[k] = base[k] + step * delta[d];
    }
}

/*
 * The residual relative to the scale of the forces that balance in it: the norm over the unknowns
 * of the summed magnitudes of every nodal term (each particle's internal force, inertia, load). A
 * bending beam's internal forces are far larger than its load, so relative to the load alone a
 * residual would look large while Newton is converging quadratically.
 */
static double relative_residual(const pm_implicit_ws *w)
{
    const double scale = free_norm(w, w->fscale);
    const double r = norm2(w->res, w->n_dof) / (scale > 0 ? scale : 1.0);
    return isfinite(r) ? r : INFINITY;
}

/* The strain whose nodal force sets the absolute tolerance: far below any strain a result depends on,
 * so that the absolute test never judges a loaded step (the relative one does), only steps whose
 * forces are all round-off. */
#define PM_CHARACTERISTIC_STRAIN 1e-6

double pm_implicit_characteristic_force(const pm_sim *s)
{
    double modulus = 0;
    for (size_t k = 0; k < s->c->n_materials; k++) {
        const pm_material *m = &s->c->materials[k];
        const double c = pm_material_elastic_wave_speed(m, NULL, m->density);
        modulus = fmax(modulus, m->density * c * c);
    }
    return PM_CHARACTERISTIC_STRAIN * modulus * s->grid.h_min;
}

/* Converged by the relative test, or by the absolute one: a body moving freely has no force at all,
 * so its residual is round-off over round-off and the relative test alone never passes. */
static int converged(const pm_implicit_ws *w, double r, double tolerance, double abs_tol)
{
    return r <= tolerance || norm2(w->res, w->n_dof) <= abs_tol;
}

/* Evaluate at the current increments; a failed point counts as an infinite residual. */
static double evaluate_rel(pm_sim *s, pm_implicit_ws *w)
{
    if (pm_implicit_evaluate(s, w, 1))
        return INFINITY;
    return relative_residual(w);
}

static int solve(pm_implicit_ws *w, pm_implicit_report *rep, FILE *log)
{
    pm_solve_info info;
    const int sym = pm_csr_asymmetry(&w->K) <= 1e-10;
    int rc = pm_sparse_solve(w->solver, &w->K, sym, w->res, w->sol, &info);
    rep->solve_seconds += info.seconds;
    if (rc == PM_OK) {
        if (info.used == PM_SOLVER_UMFPACK)
            rep->used_umfpack = 1;
        if (info.fell_back) {
            rep->solver_fallbacks++;
            if (log)
                fprintf(log, "  CHOLMOD: the tangent is not positive definite; solved with UMFPACK\n");
        }
    }
    return rc;
}

/* Keep the tangent and residual of the current iterate, for corrections that must be recomputed. */
static int save_base(pm_implicit_ws *w)
{
    if ((size_t)w->K.nnz > w->K_base_cap) {
        double *b = realloc(w->K_base, (size_t)w->K.nnz * sizeof(double));
        if (!b)
            return pm_error_set(PM_ENOMEM, "out of memory for the implicit tangent");
        w->K_base = b;
        w->K_base_cap = (size_t)w->K.nnz;
    }
    memcpy(w->K_base, w->K.val, (size_t)w->K.nnz * sizeof(double));
    memcpy(w->res_base, w->res, (size_t)w->n_dof * sizeof(double));
    return PM_OK;
}

static void restore_base(pm_implicit_ws *w)
{
    memcpy(w->K.val, w->K_base, (size_t)w->K.nnz * sizeof(double));
    memcpy(w->res, w->res_base, (size_t)w->n_dof * sizeof(double));
}

/* One attempt at a step of size w->dt. Returns 0 converged, 1 not converged (cut the step), < 0 error. */
static int attempt(pm_sim *s, pm_implicit_ws *w, FILE *log, pm_implicit_report *rep)
{
    const pm_newton_opts *o = &s->c->analysis.newton;
    const double abs_tol =
        o->absolute_tolerance > 0 ? o->absolute_tolerance : o->tolerance * pm_implicit_characteristic_force(s);
    const double w0 = pm_wall_seconds();
    int rc = s->approx->ops->connect(s->approx, &s->p);
    if (rc)
        return pm_error_prefix(rc, "step %ld (t = %.6g s): ", s->step + 1, s->t);
    pm_check(pm_contact_implicit_begin(s->contact, &s->grid, s->approx, &s->p, s->t, s->t + w->dt));
    pm_check(pm_implicit_setup_step(s, w));
    rep->dofs = w->n_dof;
    if (pm_implicit_evaluate(s, w, 1)) {
        rep->assemble_seconds += pm_wall_seconds() - w0;
        return 1;
    }
    rep->assemble_seconds += pm_wall_seconds() - w0;
    if (w->n_dof == 0)
        return 0;
    double r = relative_residual(w);
    rep->n_history = 0;
    rep->residual[rep->n_history++] = r;
    if (log)
        fprintf(log, "step %ld t %.6g dt %.4g: %d unknowns, %d entries\n  iter 0 residual %.3e\n", s->step + 1,
                s->t, w->dt, w->n_dof, w->K.nnz, r);
    for (int it = 1; it <= o->max_iterations; it++) {
        if (converged(w, r, o->tolerance, abs_tol))
            return 0;
        int src = solve(w, rep, log);
        if (src == PM_ESIM)
            return 1;
        if (src)
            return src;
        memcpy(w->du_try, w->du, 2 * w->nn * sizeof(double));
        pm_check(save_base(w));
        const double t0 = pm_wall_seconds(), solve0 = rep->solve_seconds;
        double step = 1.0;
        set_du(w, w->du_try, w->sol, step);
        double r_new = evaluate_rel(s, w);
        /* The first correction of a step starts from the last step's equilibrium, where the residual
         * is only the load increment; one full correction can leave a larger residual than that (the
         * linearisation error of a whole load step in a stiff bending body) and still be the way into
         * the quadratic region. Such a correction is taken as it is while it stays small. */
        const int first_ok = it == 1 && r_new < PM_FIRST_ACCEPT;
        if (first_ok)
            r = fmax(r, r_new) * (1 + 1e-12);
        /* A correction that makes things worse comes from a mode the tangent gets wrong (nearly
         * singular or indefinite: a node with a sliver of support, compressed material's geometric
         * stiffness). Damp it with a growing nodal spring on the tangent's diagonal (the residual is
         * unchanged, so the solution is not), then fall back to backtracking along the direction. */
        for (int lm = 0; lm < 5 && !(r_new < r); lm++) {
            restore_base(w);
            pm_implicit_regularise(w, pow(10.0, 2 * lm - 6));
            src = solve(w, rep, log);
            if (src && src != PM_ESIM)
                return src;
            if (src)
                continue;
            set_du(w, w->du_try, w->sol, step);
            r_new = evaluate_rel(s, w);
            rep->damped++;
        }
        for (int ls = 0; o->line_search && ls < 4 && !(r_new < r); ls++) {
            step *= 0.5;
            set_du(w, w->du_try, w->sol, step);
            r_new = evaluate_rel(s, w);
        }
        rep->assemble_seconds += pm_wall_seconds() - t0 - (rep->solve_seconds - solve0);
        rep->iterations++;
        const double du_norm = free_norm(w, w->du);
        const double rel_du = du_norm > 0 ? step * norm2(w->sol, w->n_dof) / du_norm : 0.0;
        if (rep->n_history < PM_NEWTON_HISTORY)
            rep->residual[rep->n_history++] = r_new;
        if (log)
            fprintf(log, "  iter %d residual %.3e  du %.3e%s\n", it, r_new, rel_du,
                    step < 1 ? "  (line search)" : "");
        if (isfinite(r_new) && converged(w, INFINITY, 0, abs_tol))
            return 0;
        if (!isfinite(r_new) || r_new > PM_NEWTON_DIVERGED || !(r_new < r))
            return 1; /* diverging, or no correction helps: cut the step */
        r = r_new;
        if (r <= o->tolerance || (rel_du <= o->displacement_tolerance && r <= sqrt(o->tolerance)))
            return 0;
    }
    return 1;
}

/* Convection phase: nodal solution to the particles, positions moved (GMM/RKPM: the nodes too,
 * keeping their velocity and acceleration for the next predictor). */
static int convect(pm_sim *s, pm_implicit_ws *w)
{
    pm_particles *p = &s->p;
    const double dt = w->dt, c0 = 4.0 / (dt * dt);
    for (size_t i = 0; i < w->n; i++) {
        double u[2] = {0, 0}, a[2] = {0, 0};
        for (int32_t k = w->st_off[i]; k < w->st_off[i + 1]; k++) {
            const int32_t I = w->st_node[k];
            const double N = w->st_N[k];
            for (int d = 0; d < 2; d++) {
                const size_t q = 2 * (size_t)I + d;
                u[d] += N * w->du[q];
                a[d] += N * (c0 * (w->du[q] - dt * w->vn[q]) - w->an[q]);
            }
        }
        double *x = p->x + 2 * i, *v = p->v + 2 * i, *ap = p->a + 2 * i, *vg = p->v_grid + PM_DIM * i;
        for (int d = 0; d < 2; d++) {
            x[d] += u[d];
            vg[d] = u[d] / dt; /* quasi-static: per unit of the pseudo-time */
            if (w->quasi_static) {
                v[d] = ap[d] = 0.0;
            } else {
                v[d] += 0.5 * dt * (ap[d] + a[d]); /* seed 000 eq. 48 */
                ap[d] = a[d];
            }
        }
    }
    if (!s->mf)
        return PM_OK;
    /* the nodal Newmark update; w->fint is free until the next evaluation, so it holds the new v */
    for (size_t k = 0; k < 2 * w->nn; k++) {
        if (w->dof[k] < 0) { /* prescribed (moving with vfix) or without material: no inertia of its own */
            w->fint[k] = (s->nd.fixed[k / 2] >> (k % 2)) & 1u ? s->nd.vfix[k] : 0.0;
            w->an[k] = 0.0;
            continue;
        }
        const double a_new = w->quasi_static ? 0.0 : c0 * (w->du[k] - dt * w->vn[k]) - w->an[k];
        w->fint[k] = w->quasi_static ? 0.0 : w->vn[k] + 0.5 * dt * (w->an[k] + a_new);
        w->an[k] = a_new;
    }
    return pm_mf_after_implicit(s, w->du, w->fint, w->an);
}

/* Back to the start-of-step particle state after an attempt that did not converge. */
static void restore(pm_sim *s, const pm_implicit_ws *w)
{
    pm_particles *p = &s->p;
    memcpy(p->stress, w->stress_n, PM_NS * w->n * sizeof(double));
    memcpy(p->F, w->F_n, PM_NF * w->n * sizeof(double));
    memcpy(p->state, w->state_n, p->n_state * w->n * sizeof(double));
    memcpy(p->vol, w->vol_n, w->n * sizeof(double));
    memcpy(p->eps_p, w->eps_n, w->n * sizeof(double));
}

int pm_implicit_step(pm_sim *s, double dt, FILE *log, pm_implicit_report *rep)
{
    pm_implicit_report local;
    if (!rep)
        rep = &local;
    memset(rep, 0, sizeof *rep);
    if (!s->implicit)
        pm_check(pm_implicit_ws_alloc(s));
    pm_implicit_ws *w = s->implicit;
    w->quasi_static = s->c->analysis.type == PM_ANALYSIS_QUASI_STATIC;
    pm_sim_update_constraints(s);
    const int max_cuts = s->c->analysis.newton.max_step_cuts;
    double remaining = dt, h = dt;
    while (remaining > 1e-12 * dt) {
        if (h > remaining)
            h = remaining;
        w->dt = h;
        const int rc = attempt(s, w, log, rep);
        if (rc < 0)
            return rc;
        if (rc == 1) {
            const long bad = w->failed_particle;
            restore(s, w);
            if (rep->step_cuts >= max_cuts) {
                char who[160] = "";
                if (bad >= 0)
                    snprintf(who, sizeof who, "; particle %ld at (%.6g, %.6g) could not be updated", bad,
                             w->x_n[2 * bad], w->x_n[2 * bad + 1]);
                return pm_error_set(PM_ESIM,
                                    "step %ld (t = %.6g s): Newton did not converge after %d halvings of the "
                                    "step (last try dt = %.4g)%s",
                                    s->step + 1, s->t, rep->step_cuts, h, who);
            }
            rep->step_cuts++;
            if (log)
                fprintf(log, "  not converged: step halved to %.4g\n", 0.5 * h);
            h *= 0.5;
            continue;
        }
        if (w->quasi_static) /* its wall profiles are of the last load step alone (walls_log.h) */
            pm_contact_profile_reset(s->contact);
        pm_contact_implicit_accept(s->contact, s->nd.mass, pm_implicit_mass_floor(s), w, h);
        const int crc = convect(s, w);
        s->t += h;
        if (crc)
            return crc;
        remaining -= h;
        rep->substeps++;
    }
    s->step++;
    if (log)
        fflush(log);
    return PM_OK;
}

void pm_implicit_reaction(const pm_sim *s, size_t bc, double R[2])
{
    R[0] = R[1] = 0;
    const pm_implicit_ws *w = s->implicit;
    if (!w || bc >= s->c->n_bcs)
        return;
    const pm_case_bc *b = &s->c->bcs[bc];
    if (b->type == PM_BC_FRICTION)
        return;
    char name[64];
    if (b->line_axis >= 0)
        snprintf(name, sizeof name, "%c=%g", b->line_axis ? 'y' : 'x', b->line_value);
    else
        snprintf(name, sizeof name, "%s", b->boundary);
    const pm_node_set *set = pm_grid_find_set(&s->grid, name);
    if (!set)
        return;
    for (size_t k = 0; k < set->n; k++)
        for (int d = 0; d < 2; d++)
            if (b->dirs & (1u << d))
                R[d] += w->react[2 * (size_t)set->nodes[k] + d];
}
