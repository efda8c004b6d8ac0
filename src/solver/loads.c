/* Loads on particle sets (loads.h). */
#include "solver/loads.h"

#include "pmech/error.h"

#include <math.h>
#include <stdlib.h>

void pm_loads_destroy(pm_loads *l)
{
    if (!l)
        return;
    free(l->load_of_id);
    free(l->volume);
    free(l->line_node);
    free(l->line_load);
    free(l->line_length);
    free(l);
}

static int inside(const pm_case_particle_load *ld, const double *x)
{
    for (int d = 0; d < PM_DIM; d++)
        if (!(x[d] >= ld->min[d] && x[d] <= ld->max[d]))
            return 0;
    return 1;
}

/* The integral over [a, b] of the hat function that is 1 at sc and 0 at sl and sr (a side is absent when
 * its neighbour is NAN: the node ends the line). */
static double hat_integral(double sl, double sc, double sr, double a, double b)
{
    double sum = 0;
    if (!isnan(sl)) {
        const double lo = fmax(a, sl), hi = fmin(b, sc);
        if (hi > lo)
            sum += ((hi - sl) * (hi - sl) - (lo - sl) * (lo - sl)) / (2 * (sc - sl));
    }
    if (!isnan(sr)) {
        const double lo = fmax(a, sc), hi = fmin(b, sr);
        if (hi > lo)
            sum += ((sr - lo) * (sr - lo) - (sr - hi) * (sr - hi)) / (2 * (sr - sc));
    }
    return sum;
}

/* A rectangle grid's nodes on a line lie in increasing order along it (numbering row by row). */
static int line_entries(const pm_sim *s, size_t k, pm_loads *l, int count_only)
{
    const pm_case *c = s->c;
    const pm_case_particle_load *ld = &c->loads[k];
    const pm_grid *g = &s->grid;
    const int axis = ld->line_axis, along = 1 - axis;
    const double tol = 1e-6 * g->h[axis];
    size_t first = l->n_line, n = 0;
    for (size_t I = 0; I < g->n_nodes; I++) {
        const double *x = g->x + PM_DIM * I;
        if (!(fabs(x[axis] - ld->line_value) <= tol))
            continue;
        if (!count_only) {
            l->line_node[first + n] = (int32_t)I;
            l->line_load[first + n] = (int32_t)k;
        }
        n++;
    }
    if (!n)
        return pm_error_set(PM_EINPUT, "%s: loads[%zu].grid_line: %c = %g is no line of the grid (its lines along %c "
                            "are at %g + i x %g, up to %g)", c->file, k, "xy"[axis], ld->line_value, "xy"[axis],
                            g->origin[axis], g->h[axis], g->hi[axis]);
    l->n_line += n;
    if (count_only)
        return PM_OK;
    double total = 0;
    for (size_t j = 0; j < n; j++) {
        const double sc = g->x[PM_DIM * l->line_node[first + j] + along];
        const double sl = j > 0 ? g->x[PM_DIM * l->line_node[first + j - 1] + along] : NAN;
        const double sr = j + 1 < n ? g->x[PM_DIM * l->line_node[first + j + 1] + along] : NAN;
        l->line_length[first + j] = hat_integral(sl, sc, sr, ld->line_range[0], ld->line_range[1]);
        total += l->line_length[first + j];
    }
    if (!(total > 0))
        return pm_error_set(PM_EINPUT, "%s: loads[%zu].grid_line: from = %g to = %g misses the grid (%g to %g)",
                            c->file, k, ld->line_range[0], ld->line_range[1], g->lo[along], g->hi[along]);
    return PM_OK;
}

static int line_loads(const pm_sim *s, pm_loads *l)
{
    const pm_case *c = s->c;
    for (size_t k = 0; k < c->n_loads; k++)
        if (c->loads[k].line_axis >= 0)
            pm_check(line_entries(s, k, l, 1));
    if (!l->n_line)
        return PM_OK;
    l->line_node = malloc(l->n_line * sizeof *l->line_node);
    l->line_load = malloc(l->n_line * sizeof *l->line_load);
    l->line_length = malloc(l->n_line * sizeof *l->line_length);
    if (!l->line_node || !l->line_load || !l->line_length)
        return pm_error_set(PM_ENOMEM, "out of memory for the loads");
    l->n_line = 0;
    for (size_t k = 0; k < c->n_loads; k++)
        if (c->loads[k].line_axis >= 0)
            pm_check(line_entries(s, k, l, 0));
    return PM_OK;
}

int pm_loads_create(const pm_sim *s, pm_loads **out)
{
    *out = NULL;
    const pm_case *c = s->c;
    const pm_particles *p = &s->p;
    if (!c->n_loads)
        return PM_OK;
    pm_loads *l = calloc(1, sizeof *l);
    if (!l)
        return pm_error_set(PM_ENOMEM, "out of memory for the loads");
    for (size_t i = 0; i < p->n; i++)
        if ((size_t)p->id[i] + 1 > l->n_ids)
            l->n_ids = (size_t)p->id[i] + 1;
    l->load_of_id = malloc((l->n_ids ? l->n_ids : 1) * sizeof *l->load_of_id);
    l->volume = calloc(c->n_loads, sizeof *l->volume);
    if (!l->load_of_id || !l->volume) {
        pm_loads_destroy(l);
        return pm_error_set(PM_ENOMEM, "out of memory for the loads");
    }
    for (size_t k = 0; k < l->n_ids; k++)
        l->load_of_id[k] = -1;
    /* the earlier load wins where two sets share a particle */
    for (size_t k = c->n_loads; k-- > 0;) {
        const pm_case_particle_load *ld = &c->loads[k];
        if (ld->line_axis >= 0)
            continue;
        if (ld->nearest) {
            size_t best = 0;
            double d2 = INFINITY;
            for (size_t i = 0; i < p->n; i++) {
                const double dx = p->x[PM_DIM * i] - ld->point[0], dy = p->x[PM_DIM * i + 1] - ld->point[1];
                if (dx * dx + dy * dy < d2) {
                    d2 = dx * dx + dy * dy;
                    best = i;
                }
            }
            if (p->n)
                l->load_of_id[p->id[best]] = (int32_t)k;
        } else {
            for (size_t i = 0; i < p->n; i++)
                if (inside(ld, p->x + PM_DIM * i))
                    l->load_of_id[p->id[i]] = (int32_t)k;
        }
    }
    for (size_t i = 0; i < p->n; i++) {
        const int32_t k = l->load_of_id[p->id[i]];
        if (k >= 0)
            l->volume[k] += p->vol0[i];
    }
    for (size_t k = 0; k < c->n_loads; k++)
        if (c->loads[k].line_axis < 0 && !(l->volume[k] > 0)) {
            pm_loads_destroy(l);
            return pm_error_set(PM_EINPUT, "%s: loads[%zu]: no particle lies in the box [%g, %g] x [%g, %g] at t = 0",
                                c->file, k, c->loads[k].min[0], c->loads[k].max[0], c->loads[k].min[1],
                                c->loads[k].max[1]);
        }
    const int rc = line_loads(s, l);
    if (rc) {
        pm_loads_destroy(l);
        return rc;
    }
    *out = l;
    return PM_OK;
}

int pm_loads_apply(pm_sim *s, double t)
{
    const pm_loads *l = s->loads;
    if (!l)
        return PM_OK;
    const pm_case *c = s->c;
    const pm_particles *p = &s->p;
    double *force = s->nd.force;
    pm_stencil st;
    for (size_t i = 0; i < p->n; i++) {
        const size_t id = (size_t)p->id[i];
        const int32_t k = id < l->n_ids ? l->load_of_id[id] : -1;
        if (k < 0)
            continue;
        pm_check(pm_approx_eval(s->approx, p, i, &st));
        const double share = p->vol0[i] / l->volume[k];
        for (int d = 0; d < PM_DIM; d++) {
            const double f = share * pm_timefn_value(&c->loads[k].force[d], t);
            for (int j = 0; j < st.n; j++)
                force[PM_DIM * st.node[j] + d] += st.N[j] * f;
        }
    }
    for (size_t e = 0; e < l->n_line; e++) {
        const pm_case_particle_load *ld = &c->loads[l->line_load[e]];
        for (int d = 0; d < PM_DIM; d++)
            force[PM_DIM * l->line_node[e] + d] += l->line_length[e] * pm_timefn_value(&ld->force[d], t);
    }
    return PM_OK;
}
