/* Prescribed boundary conditions: fixed and velocity node sets, timed velocity conditions and fixed
 * conditions released at a time (boundary.h). */
#include "boundary.h"

#include "contact/contact.h"
#include "contact/multibody.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* A line boundary keeps the nodes between its `from` and `to` and takes its given normal. */
static int restrict_line(const pm_case *c, size_t b, const pm_grid *g, pm_node_set *set)
{
    const pm_case_bc *bc = &c->bcs[b];
    const int other = 1 - bc->line_axis;
    const double tol = 1e-9 * g->h_min;
    size_t kept = 0;
    for (size_t i = 0; i < set->n; i++) {
        const double q = g->x[PM_DIM * set->nodes[i] + other];
        if (q >= bc->line_range[0] - tol && q <= bc->line_range[1] + tol)
            set->nodes[kept++] = set->nodes[i];
    }
    if (kept == 0)
        return pm_error_set(PM_EINPUT, "%s: boundary_conditions[%zu].boundary: no grid node on %c = %g between %g and %g",
                            c->file, b, bc->line_axis ? 'y' : 'x', bc->line_value, bc->line_range[0],
                            bc->line_range[1]);
    set->n = kept;
    for (int d = 0; d < PM_DIM; d++)
        set->normal[d] = bc->line_normal[d];
    return PM_OK;
}

int pm_bc_node_set(const pm_case *c, size_t b, pm_grid *g, const pm_node_set **out)
{
    const pm_case_bc *bc = &c->bcs[b];
    const pm_node_set *set;
    if (bc->line_axis >= 0) {
        char name[64];
        snprintf(name, sizeof name, "%c=%g", bc->line_axis ? 'y' : 'x', bc->line_value);
        int k = pm_grid_add_line_set(g, name, bc->line_axis, bc->line_value, NULL);
        if (k < 0)
            return pm_error_prefix(k, "%s: boundary_conditions[%zu].boundary: ", c->file, b);
        pm_check(restrict_line(c, b, g, &g->sets[k]));
        set = &g->sets[k];
    } else {
        set = pm_grid_find_set(g, bc->boundary);
        if (!set && c->method == PM_METHOD_RKPM)
            return pm_error_set(PM_EINPUT,
                                "%s: boundary_conditions[%zu].boundary: '%s': with method rkpm the nodes are the "
                                "particles, so only the grid sides x_min, x_max, y_min, y_max name boundaries",
                                c->file, b, bc->boundary);
        if (!set && pm_grid_find_cell_set(g, bc->boundary))
            return pm_error_set(PM_EINPUT,
                                "%s: boundary_conditions[%zu].boundary: '%s' is a 2-D physical group of the mesh "
                                "(its cells); a boundary is a 1-D group (its lines), a 0-D one or a grid side",
                                c->file, b, bc->boundary);
        if (!set) {
            char names[512] = "";
            size_t used = 0;
            for (size_t k = 0; k < g->n_sets && used + 1 < sizeof names; k++) {
                const int w = snprintf(names + used, sizeof names - used, "%s%s", k ? ", " : "", g->sets[k].name);
                used += w > 0 ? (size_t)w : 0;
            }
            return pm_error_set(PM_EINPUT, "%s: boundary_conditions[%zu].boundary: no boundary '%s' in the grid "
                                "(it has: %s)", c->file, b, bc->boundary, names);
        }
    }
    if (set->n == 0)
        return pm_error_set(PM_EINPUT, "%s: boundary_conditions[%zu].boundary: no node lies on '%s' at t = 0",
                            c->file, b, set->name);
    *out = set;
    return PM_OK;
}

/* One fixed or velocity condition into nd->fixed / nd->vfix, and into nd->timed if it changes at a time. */
static int apply_condition(const pm_case *c, size_t b, pm_grid *g, pm_nodal *nd)
{
    const pm_case_bc *bc = &c->bcs[b];
    const int released = bc->type == PM_BC_FIXED && isfinite(bc->until) && bc->until > 0;
    const pm_node_set *set;
    pm_check(pm_bc_node_set(c, b, g, &set));
    for (size_t i = 0; i < set->n; i++) {
        int32_t n = set->nodes[i];
        for (int d = 0; d < PM_DIM; d++) {
            if (!(bc->dirs & (1u << d)))
                continue;
            if (released && (nd->fixed[n] & (1u << d)))
                return pm_error_set(PM_EINPUT,
                                    "%s: boundary_conditions[%zu]: the node at (%g, %g) is also held in %c by another "
                                    "condition (or the axis); a condition with 'until' must not share nodes with "
                                    "another, as releasing it would free them",
                                    c->file, b, g->x[PM_DIM * n], g->x[PM_DIM * n + 1], "xy"[d]);
            nd->fixed[n] |= (uint8_t)(1u << d);
            nd->vfix[PM_DIM * n + d] = bc->type == PM_BC_VELOCITY ? bc->value[d] : 0.0;
        }
    }
    if ((bc->type == PM_BC_VELOCITY && isfinite(bc->until) && bc->until > 0) || released) {
        struct pm_timed_bc *t = realloc(nd->timed, (nd->n_timed + 1) * sizeof *t);
        if (!t)
            return pm_error_set(PM_ENOMEM, "out of memory");
        nd->timed = t;
        t[nd->n_timed].set = (int)(set - g->sets);
        t[nd->n_timed].dirs = bc->dirs;
        t[nd->n_timed].until = bc->until;
        t[nd->n_timed].release = released;
        t[nd->n_timed].done = 0;
        nd->n_timed++;
    }
    return PM_OK;
}

int pm_bc_setup(const pm_case *c, pm_grid *g, pm_nodal *nd)
{
    if (c->formulation == PM_AXISYMMETRIC) {
        /* nodes on the axis r = 0 cannot move radially */
        for (size_t n = 0; n < g->n_nodes; n++)
            if (fabs(g->x[PM_DIM * n]) <= 1e-9 * g->h_min) {
                nd->fixed[n] |= 1u;
                nd->vfix[PM_DIM * n] = 0.0;
            }
    }
    /* Conditions that are released later come second and must not share a held component with any
     * other: releasing it would otherwise free a node that another condition still holds. */
    for (int pass = 0; pass < 2; pass++)
        for (size_t b = 0; b < c->n_bcs; b++) {
            const pm_case_bc *bc = &c->bcs[b];
            const int released = bc->type == PM_BC_FIXED && isfinite(bc->until) && bc->until > 0;
            if (bc->type == PM_BC_FRICTION || released != pass)
                continue; /* friction: a contact surface (pm_contact_create) */
            pm_check(apply_condition(c, b, g, nd));
        }
    return PM_OK;
}

void pm_sim_update_constraints(pm_sim *s)
{
    pm_nodal *nd = &s->nd;
    for (size_t k = 0; k < nd->n_timed; k++) {
        struct pm_timed_bc *t = &nd->timed[k];
        if (t->done || s->t < t->until * (1 - 1e-12))
            continue;
        const pm_node_set *set = &s->grid.sets[t->set];
        for (size_t i = 0; i < set->n; i++)
            for (int d = 0; d < PM_DIM; d++) {
                if (!(t->dirs & (1u << d)))
                    continue;
                if (t->release)
                    nd->fixed[set->nodes[i]] &= (uint8_t) ~(1u << d);
                else
                    nd->vfix[PM_DIM * set->nodes[i] + d] = 0.0;
            }
        t->done = 1;
        if (s->mb) /* every body field holds the switched nodes */
            pm_multibody_copy_conditions(s->mb, nd);
    }
    /* the contact set of this step: meshfree nodes moved onto or past walls since the last one */
    pm_contact_detect(s->contact, &s->grid, s->t);
}
