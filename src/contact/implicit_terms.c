/*
 * Contact in implicit and quasi-static steps (contact.h): penalty-regularised Coulomb contact at the
 * nodes touching a surface, as terms of the Newton residual and its tangent.
 *
 * At a contact node of nodal mass m with normal n (into the surface), the relative increment of the
 * step is r = du - du_obstacle, and the force on the material f = -N n + t is built on the node's
 * force of the last accepted step, f_old (zero for a node that did not push then):
 *   N = max(0, N_old + k m (r . n - g)),  N_old = -f_old . n, g = 0 when N_old > 0, else the gap of
 *       the material's surface at the start of the step (0 when it overlaps already),
 *   trial tangential force t* = P (f_old - k m r),  P = I - n n^T,
 *   t = t* when |t*| <= mu N (stick), else mu N t* / |t*| (slip),
 * with k the stiffness per node mass. Keeping f_old (pm_contact_implicit_accept) makes the penalty
 * incremental: a body resting on a surface keeps its force from step to step, so it neither sinks
 * nor creeps, and a body seeded overlapping a surface by part of a particle (Gauss points) starts
 * touching with no force instead of being kicked off. The tangent of -f (the residual's sign
 * convention for internal forces) is
 *   stick: k m (n n^T + P),
 *   slip:  k m n n^T - mu k m e n^T + (mu N k m / |t*|) (I - e e^T) P,   e = t* / |t*|,
 * the consistent one: Newton converges quadratically through stick and slip alike. The slip tangent
 * is unsymmetric; the solver sees that and factors with UMFPACK.
 */
#include "contact/contact.h"

#include "pmech/error.h"
#include "solver/implicit_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The row of entry cn's force history: its (surface, node) row, or for the second face of a Gmsh wall's
 * inward corner a row of its own, as the node's two faces push along different normals and each face
 * must go on from its own force (the first face's row would give the second a tangential force that is
 * the first's normal one, and leave the first without its normal force). */
static size_t history_row(const pm_contact *ct, const pm_contact_node *cn)
{
    if (ct->surface[cn->surface].kind == PM_CONTACT_EDGES && cn->own_row > 0)
        return ct->n_surfaces * ct->n_nodes + (size_t)(cn->own_row - 1);
    return (size_t)cn->surface * ct->n_nodes + (size_t)cn->node;
}

int pm_contact_implicit_history(pm_contact *ct, double **held, size_t *rows)
{
    *rows = ct->n_surfaces * ct->n_nodes + ct->n_own_rows;
    if (!ct->held) {
        ct->held = calloc(*rows * PM_DIM + 1, sizeof *ct->held);
        ct->held_next = calloc(*rows * PM_DIM + 1, sizeof *ct->held_next);
        if (!ct->held || !ct->held_next)
            return pm_error_set(PM_ENOMEM, "out of memory for the contact forces of %zu nodes", ct->n_nodes);
    }
    *held = ct->held;
    return PM_OK;
}

int pm_contact_implicit_begin(pm_contact *ct, const pm_grid *g, const pm_approx *a, const pm_particles *p,
                              double t0, double t1)
{
    if (!ct)
        return PM_OK;
    double *held;
    size_t rows;
    pm_check(pm_contact_implicit_history(ct, &held, &rows));
    ct->surface_gaps = 1; /* the incremental penalty needs no head start (see the top) */
    pm_contact_detect(ct, g, t0);
    pm_contact_gaps(ct, a, p);
    for (size_t k = 0; k < ct->n_surfaces; k++) {
        pm_contact_surface *sf = &ct->surface[k];
        for (int d = 0; d < PM_DIM; d++)
            sf->step[d] = sf->motion ? pm_timefn_integral(&sf->motion[d], t1) - sf->shift[d] : 0.0;
    }
    return PM_OK;
}

/* What the law gives at one contact entry for the increments du. */
typedef struct entry_force {
    double f[PM_DIM];      /* force on the material */
    double t[PM_DIM];      /* its tangential part */
    double normal;         /* N >= 0 */
    double K[PM_DIM][PM_DIM]; /* tangent of -f with respect to the node's increment */
} entry_force;

static inline double dotd(const double *a, const double *b)
{
    double s = 0.0;
    for (int d = 0; d < PM_DIM; d++)
        s += a[d] * b[d];
    return s;
}

/* Returns 1 when the entry touches (a force acts), 0 when it is apart. */
static int entry_law(const pm_contact *ct, const pm_contact_node *cn, double m, const double *du, entry_force *out)
{
    const pm_contact_surface *sf = &ct->surface[cn->surface];
    const double *n = cn->normal;
    const double km = m * (sf->stiffness > 0 ? sf->stiffness : ct->penalty);
    const double *held = ct->held + PM_DIM * history_row(ct, cn);
    double r[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        r[d] = du[PM_DIM * (size_t)cn->node + d] - sf->step[d];
    /* a node that pushed at the end of the last step goes on from its force; one that did not
     * starts touching when its material reaches the surface (an overlap at the start of the step,
     * as a Gauss-seeded body has on its side, counts as touching with no force yet) */
    const double held_normal = -dotd(held, n);
    const double closing = held_normal > 0 ? 0.0 : fmax(cn->gap, 0.0);
    const double N = fmax(held_normal, 0.0) + km * (dotd(r, n) - closing);
    memset(out, 0, sizeof *out);
    if (!(N > 0))
        return 0;
    double tt[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        tt[d] = held[d] - km * r[d];
    const double tn = dotd(tt, n);
    for (int d = 0; d < PM_DIM; d++)
        tt[d] -= tn * n[d];
    const double tlen = sqrt(dotd(tt, tt)), limit = cn->mu * N;
    const int slip = tlen > limit;
    double e[PM_DIM] = {0};
    for (int d = 0; d < PM_DIM; d++) {
        e[d] = tlen > 0 ? tt[d] / tlen : 0.0;
        out->t[d] = slip ? limit * e[d] : tt[d];
        out->f[d] = -N * n[d] + out->t[d];
    }
    out->normal = N;
    for (int i = 0; i < PM_DIM; i++)
        for (int j = 0; j < PM_DIM; j++) {
            const double nn = n[i] * n[j], P = (i == j) - nn;
            if (!slip) {
                out->K[i][j] = km * (nn + P);
                continue;
            }
            /* (I - e e^T) P = P - e e^T, as e lies in the tangent plane */
            const double turn = tlen > 0 ? limit * km / tlen * (P - e[i] * e[j]) : 0.0;
            out->K[i][j] = km * nn - cn->mu * km * e[i] * n[j] + turn;
        }
    return 1;
}

/* The node's mass when it has unknowns and material, else 0. */
static double active_mass(const pm_implicit_ws *w, const double *mass, double mass_floor, int32_t I)
{
    int any = 0;
    for (int d = 0; d < PM_DIM; d++)
        any |= w->dof[PM_DIM * (size_t)I + d] >= 0;
    return any && mass[I] > mass_floor ? mass[I] : 0.0;
}

void pm_contact_implicit(const pm_contact *ct, const double *mass, double mass_floor, pm_implicit_ws *w, int want_K)
{
    for (size_t e = 0; ct && e < ct->n_node; e++) {
        const pm_contact_node *cn = &ct->node[e];
        const double m = active_mass(w, mass, mass_floor, cn->node);
        entry_force ef;
        if (ct->surface[cn->surface].guard || !(m > 0) || !isfinite(cn->gap) || !entry_law(ct, cn, m, w->du, &ef))
            continue;
        const size_t I = (size_t)cn->node;
        for (int d = 0; d < PM_DIM; d++) {
            w->fint[PM_DIM * I + d] -= ef.f[d];
            w->fscale[PM_DIM * I + d] += fabs(ef.f[d]);
        }
        if (!want_K)
            continue;
        for (int i = 0; i < PM_DIM; i++) {
            const int row = w->dof[PM_DIM * I + i];
            for (int j = 0; row >= 0 && j < PM_DIM; j++) {
                const int col = w->dof[PM_DIM * I + j];
                const int at = col >= 0 ? pm_csr_find(&w->K, row, col) : -1;
                if (at >= 0)
                    w->K.val[at] += ef.K[i][j];
            }
        }
    }
}

void pm_contact_implicit_accept(pm_contact *ct, const double *mass, double mass_floor, const pm_implicit_ws *w,
                                double dt)
{
    if (!ct || !ct->held)
        return;
    for (size_t k = 0; k < ct->n_surfaces; k++)
        memset(&ct->surface[k].f, 0, sizeof ct->surface[k].f);
    /* a node that no longer touches starts from zero force when it touches again */
    memset(ct->held_next, 0, (ct->n_surfaces * ct->n_nodes + ct->n_own_rows) * PM_DIM * sizeof *ct->held_next);
    for (size_t e = 0; e < ct->n_node; e++) {
        const pm_contact_node *cn = &ct->node[e];
        pm_contact_surface *sf = &ct->surface[cn->surface];
        const double m = active_mass(w, mass, mass_floor, cn->node);
        entry_force ef;
        if (sf->guard || !(m > 0) || !isfinite(cn->gap) || !entry_law(ct, cn, m, w->du, &ef))
            continue;
        double *keep = ct->held_next + PM_DIM * history_row(ct, cn);
        /* the wall profiles (profile.c) read the node's impulse, as explicit steps leave it */
        double *J = sf->node_impulse + (size_t)(1 + PM_DIM) * (size_t)cn->node;
        for (int d = 0; d < PM_DIM; d++) {
            keep[d] = ef.f[d];
            sf->f.force[d] += ef.f[d];
            sf->f.tangent[d] += ef.t[d];
            J[1 + d] += ef.t[d] * dt;
        }
        sf->f.normal += ef.normal;
        J[0] += ef.normal * dt;
    }
    double *swap = ct->held;
    ct->held = ct->held_next;
    ct->held_next = swap;
    for (size_t k = 0; k < ct->n_surfaces; k++) {
        pm_contact_surface *sf = &ct->surface[k];
        for (int d = 0; d < PM_DIM; d++) {
            sf->impulse.force[d] += sf->f.force[d] * dt;
            sf->impulse.tangent[d] += sf->f.tangent[d] * dt;
        }
        sf->impulse.normal += sf->f.normal * dt;
    }
}
