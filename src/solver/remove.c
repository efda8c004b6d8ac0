/* Sinks: particles that cross an outlet during a step, lie in a region or left the grid are taken out
 * of the arrays at the end of the step (flow.h). */
#include "solver/flow.h"

#include "core/seed.h"

#include <math.h>
#include <string.h>

void pm_flow_before_step(pm_sim *s)
{
    const pm_flow *f = s->flow;
    if (f && f->has_outlet)
        memcpy(f->x_prev, s->p.x, s->p.n * PM_DIM * sizeof(double));
}

/* Whether the path from a to b crosses outlet r (in its removing direction when it has one). */
static int crosses(const pm_sink_run *r, const double *a, const double *b)
{
    const int ax = r->axis, o = 1 - ax;
    const double s0 = a[ax] - r->value, s1 = b[ax] - r->value, n = r->normal[ax];
    int across;
    if (n != 0)
        across = s0 * n <= 0 && s1 * n > 0;
    else
        across = (s0 <= 0 && s1 > 0) || (s0 >= 0 && s1 < 0);
    if (!across)
        return 0;
    const double t = s0 / (s0 - s1), at = a[o] + t * (b[o] - a[o]);
    return at >= r->range[0] && at <= r->range[1];
}

/* 1 + the index of the first sink that takes particle i, 0 when none does. */
static uint8_t sink_of(const pm_sim *s, size_t i)
{
    const pm_flow *f = s->flow;
    pm_particles *p = (pm_particles *)&s->p;
    const double *x = p->x + PM_DIM * i;
    if (!isfinite(x[0]) || !isfinite(x[1]))
        return 0; /* a diverged particle stops the run at the next location, it is not quietly removed */
    for (size_t k = 0; k < f->n_sinks; k++) {
        const pm_case_sink *cs = &s->c->sinks[k];
        int take = 0;
        if (cs->type == PM_SINK_OUTLET) {
            take = crosses(&f->snk[k], f->x_prev + PM_DIM * i, x);
        } else if (cs->type == PM_SINK_REGION) {
            take = pm_shape_contains(&cs->shape, x);
        } else {
            const int32_t cell = pm_grid_locate_from(&s->grid, x, p->cell[i]);
            take = cell < 0;
            if (!take) /* a good hint for the next step's location */
                p->cell[i] = cell;
        }
        if (take)
            return (uint8_t)(k + 1);
    }
    return 0;
}

void pm_flow_remove_marked(pm_sim *s)
{
    pm_flow *f = s->flow;
    pm_particles *p = &s->p;
    uint8_t *drop = f->drop;
    long any = 0;
#pragma omp parallel for schedule(static) reduction(+ : any) num_threads(s->nd.n_threads)
    for (long i = 0; i < (long)p->n; i++) {
        drop[i] = sink_of(s, (size_t)i);
        any += drop[i] != 0;
    }
    if (!any)
        return;
    for (size_t i = 0; i < p->n; i++)
        if (drop[i]) {
            pm_sink_run *r = &f->snk[drop[i] - 1];
            r->step_particles++;
            r->step_mass += p->mass[i];
        }
    for (size_t k = 0; k < f->n_sinks; k++) {
        f->snk[k].removed += f->snk[k].step_particles;
        f->snk[k].removed_mass += f->snk[k].step_mass;
    }
    pm_particles_remove(p, drop); /* in order: particles sorted by cell stay sorted, no re-sort is needed */
}
