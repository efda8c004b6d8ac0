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
    free(l);
}

static int inside(const pm_case_particle_load *ld, const double *x)
{
    for (int d = 0; d < PM_DIM; d++)
        if (!(x[d] >= ld->min[d] && x[d] <= ld->max[d]))
            return 0;
    return 1;
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
        if (!(l->volume[k] > 0)) {
            pm_loads_destroy(l);
            return pm_error_set(PM_EINPUT, "%s: loads[%zu]: no particle lies in the box [%g, %g] x [%g, %g] at t = 0",
                                c->file, k, c->loads[k].min[0], c->loads[k].max[0], c->loads[k].min[1],
                                c->loads[k].max[1]);
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
    return PM_OK;
}
