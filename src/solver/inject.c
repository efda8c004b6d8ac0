/* Sources: a portion seeded once at set-up, copied into the particle arrays at each release (flow.h). */
#include "solver/flow.h"

#include "core/seed.h"
#include "pmech/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* c + |v| of a portion's material at its density as released, in cells of size h. */
static double portion_wave(const pm_case *c, const pm_particles *q, double h)
{
    double w = 0;
    for (size_t i = 0; i < q->n; i++) {
        const pm_material *m = &c->materials[q->material[i]];
        const double rho = q->mass[i] / q->vol[i];
        const double cw = pm_material_signal_speed(m, q->state + q->n_state * i, rho, h);
        double v2 = 0;
        for (int d = 0; d < PM_DIM; d++)
            v2 += q->v[PM_DIM * i + d] * q->v[PM_DIM * i + d];
        w = fmax(w, cw + sqrt(v2));
    }
    return w;
}

/* Whether point x (in cell `cell`) lies in what source k fills: its shape, or for a gmsh group the
 * cells its portion was seeded in (in_cells, NULL otherwise). */
static int in_source(const pm_case_source *src, const uint8_t *in_cells, const double *x, int32_t cell)
{
    if (src->body.shape.type == PM_SHAPE_GMSH_GROUP)
        return cell >= 0 && in_cells[cell];
    return pm_shape_contains(&src->body.shape, x);
}

/* Two sources must not fill one place: a point of either portion inside the other's shape. */
static int check_overlaps(const pm_case *c, const pm_grid *g, const pm_flow *f)
{
    uint8_t *cells = calloc(g->n_cells ? g->n_cells : 1, 1);
    if (!cells)
        return pm_error_set(PM_ENOMEM, "out of memory");
    int rc = PM_OK;
    for (size_t i = 0; i < f->n_sources && !rc; i++) {
        const pm_particles *a = &f->src[i].portion;
        memset(cells, 0, g->n_cells);
        for (size_t q = 0; q < a->n; q++)
            cells[a->cell[q]] = 1;
        for (size_t j = 0; j < f->n_sources && !rc; j++) {
            if (j == i)
                continue;
            const pm_particles *b = &f->src[j].portion;
            for (size_t q = 0; q < b->n; q++) {
                const double *x = b->x + PM_DIM * q;
                if (!in_source(&c->sources[i], cells, x, b->cell[q]))
                    continue;
                const size_t lo = i < j ? i : j, hi = i < j ? j : i;
                rc = pm_error_set(PM_EINPUT,
                                  "%s: sources[%zu].shape: overlaps sources[%zu].shape (the point (%g, %g) lies in "
                                  "both); two sources must not fill the same place",
                                  c->file, hi, lo, x[0], x[1]);
                break;
            }
        }
    }
    free(cells);
    return rc;
}

static int setup_source(const pm_case *c, const pm_grid *g, size_t n_state, size_t k, pm_source_run *r)
{
    const pm_case_source *src = &c->sources[k];
    const size_t n = pm_seed_body_count(c, &src->body, g);
    if (n == 0 && src->body.shape.type == PM_SHAPE_GMSH_GROUP)
        return pm_error_set(PM_EINPUT, "%s: sources[%zu].shape.name: the mesh has no 2-D physical group '%s'",
                            c->file, k, src->body.shape.group);
    if (n == 0)
        return pm_error_set(PM_EINPUT,
                            "%s: sources[%zu] ('%s') yields no particle: no quadrature point of the grid lies "
                            "inside its shape; refine the grid, raise particles_per_cell, or check the shape's "
                            "coordinates",
                            c->file, k, src->body.name);
    pm_check(pm_particles_alloc(&r->portion, n, n_state));
    pm_seed_body_fill(c, &src->body, (int32_t)(c->n_bodies + k), g, &r->portion, 0);
    r->n_releases = pm_case_source_releases(c, k);
    r->wave = portion_wave(c, &r->portion, g->h_min);
    for (int d = 0; d < PM_DIM; d++) {
        r->lo[d] = INFINITY;
        r->hi[d] = -INFINITY;
    }
    for (size_t i = 0; i < n; i++) {
        r->portion_mass += r->portion.mass[i];
        for (int d = 0; d < PM_DIM; d++) {
            const double x = r->portion.x[PM_DIM * i + d], h = r->portion.hsize[PM_DIM * i + d];
            r->lo[d] = fmin(r->lo[d], x - h);
            r->hi[d] = fmax(r->hi[d], x + h);
        }
    }
    return PM_OK;
}

/* Outlets on a grid side take the side's line and outward normal. */
static int setup_sink(const pm_case *c, const pm_grid *g, size_t k, pm_sink_run *r)
{
    const pm_case_sink *s = &c->sinks[k];
    r->axis = s->axis;
    r->value = s->value;
    r->range[0] = s->range[0];
    r->range[1] = s->range[1];
    for (int d = 0; d < PM_DIM; d++)
        r->normal[d] = s->normal[d];
    if (s->type != PM_SINK_OUTLET || !s->side[0])
        return PM_OK;
    int axis, hi;
    if (!pm_grid_side_of(s->side, &axis, &hi))
        return pm_error_set(PM_EINPUT, "%s: sinks[%zu].boundary: unknown side \"%s\"", c->file, k, s->side);
    r->axis = axis;
    r->value = hi ? g->hi[axis] : g->lo[axis];
    r->normal[axis] = hi ? 1 : -1;
    return PM_OK;
}

int pm_flow_create(const pm_case *c, const pm_grid *g, size_t n_state, pm_flow **out, size_t *room)
{
    *out = NULL;
    *room = 0;
    if (!c->n_sources && !c->n_sinks)
        return PM_OK;
    pm_flow *f = calloc(1, sizeof *f);
    if (!f)
        return pm_error_set(PM_ENOMEM, "out of memory");
    f->n_sources = c->n_sources;
    f->n_sinks = c->n_sinks;
    f->src = calloc(c->n_sources ? c->n_sources : 1, sizeof *f->src);
    f->snk = calloc(c->n_sinks ? c->n_sinks : 1, sizeof *f->snk);
    int rc = !f->src || !f->snk ? pm_error_set(PM_ENOMEM, "out of memory") : PM_OK;
    for (size_t k = 0; !rc && k < c->n_sources; k++) {
        rc = setup_source(c, g, n_state, k, &f->src[k]);
        if (!rc)
            *room += f->src[k].portion.n * f->src[k].n_releases;
    }
    for (size_t k = 0; !rc && k < c->n_sinks; k++) {
        rc = setup_sink(c, g, k, &f->snk[k]);
        f->has_outlet |= c->sinks[k].type == PM_SINK_OUTLET;
        f->has_outside |= c->sinks[k].type == PM_SINK_OUTSIDE_GRID;
    }
    if (!rc)
        rc = check_overlaps(c, g, f);
    if (rc) {
        pm_flow_destroy(f);
        return rc;
    }
    *out = f;
    return PM_OK;
}

void pm_flow_destroy(pm_flow *f)
{
    if (!f)
        return;
    for (size_t k = 0; k < f->n_sources && f->src; k++)
        pm_particles_free(&f->src[k].portion);
    free(f->src);
    free(f->snk);
    free(f->x_prev);
    free(f->drop);
    free(f);
}

/* Whether any particle centre lies in the box a portion will fill. */
static int region_free(const pm_particles *p, const pm_source_run *r)
{
    for (size_t i = 0; i < p->n; i++) {
        const double *x = p->x + PM_DIM * i;
        int in = 1;
        for (int d = 0; d < PM_DIM; d++)
            in &= x[d] >= r->lo[d] && x[d] <= r->hi[d];
        if (in)
            return 0;
    }
    return 1;
}

static int release(pm_sim *s, pm_source_run *r)
{
    pm_particles *p = &s->p;
    pm_flow *f = s->flow;
    const size_t n = r->portion.n;
    if (p->n + n > p->cap) /* the capacity counts every release: reaching this is a bug */
        return pm_error_set(PM_EINTERNAL, "a release of %zu particles does not fit (%zu of %zu in use)", n, p->n,
                            p->cap);
    pm_particles_copy(p, p->n, &r->portion, 0, n);
    for (size_t i = 0; i < n; i++)
        p->id[p->n + i] = f->next_id++;
    p->n += n;
    r->released += n;
    r->released_mass += r->portion_mass;
    f->changed = 1;
    f->max_n = p->n > f->max_n ? p->n : f->max_n;
    /* the next step's size comes from the last stress update, which has not seen this material */
    s->max_wave = fmax(s->max_wave, r->wave);
    return PM_OK;
}

/* The releases of every source that fell due by the time reached. */
static int release_due(pm_sim *s)
{
    const pm_case *c = s->c;
    pm_flow *f = s->flow;
    const double eps = 1e-12 * c->analysis.end_time;
    for (size_t k = 0; k < f->n_sources; k++) {
        pm_source_run *r = &f->src[k];
        r->event = PM_RELEASE_NONE;
        size_t due = 0;
        while (r->next + due < r->n_releases && pm_case_source_release_time(c, k, r->next + due) <= s->t + eps)
            due++;
        if (due == 0)
            continue;
        const pm_case_source *src = &c->sources[k];
        if (due > 1 && !src->only_when_free)
            return pm_error_set(PM_ESIM,
                                "step %ld (t = %.6g s): sources[%zu] ('%s'): %zu releases fell due within one step "
                                "(from t = %.6g s); they would fill the same place: lengthen its period or its "
                                "times' spacing beyond the step, or set only_when_free",
                                s->step, s->t, k, src->body.name, due, pm_case_source_release_time(c, k, r->next));
        r->next += due; /* with only_when_free, every release but the first is skipped */
        r->event_time = s->t;
        if (src->only_when_free && !region_free(&s->p, r)) {
            r->event = PM_RELEASE_SKIPPED;
            continue;
        }
        pm_check(release(s, r));
        r->event = PM_RELEASE_DONE;
    }
    return PM_OK;
}

int pm_flow_start(pm_sim *s)
{
    pm_flow *f = s->flow;
    if (!f)
        return PM_OK;
    f->next_id = (int32_t)s->p.n;
    f->max_n = s->p.n;
    f->drop = calloc(s->p.cap ? s->p.cap : 1, 1);
    if (f->has_outlet)
        f->x_prev = malloc((s->p.cap ? s->p.cap : 1) * PM_DIM * sizeof(double));
    if (!f->drop || (f->has_outlet && !f->x_prev))
        return pm_error_set(PM_ENOMEM, "out of memory for %zu particles", s->p.cap);
    return release_due(s);
}

int pm_flow_after_step(pm_sim *s)
{
    pm_flow *f = s->flow;
    if (!f)
        return PM_OK;
    for (size_t k = 0; k < f->n_sinks; k++) {
        f->snk[k].step_particles = 0;
        f->snk[k].step_mass = 0;
    }
    if (f->n_sinks)
        pm_flow_remove_marked(s);
    return release_due(s);
}

int pm_flow_take_changed(pm_sim *s)
{
    if (!s->flow || !s->flow->changed)
        return 0;
    s->flow->changed = 0;
    return 1;
}

double pm_flow_wave(const pm_sim *s)
{
    double w = 0;
    for (size_t k = 0; s->flow && k < s->flow->n_sources; k++)
        if (s->flow->src[k].next < s->flow->src[k].n_releases)
            w = fmax(w, s->flow->src[k].wave);
    return w;
}

double pm_flow_next_release(const pm_sim *s)
{
    double t = INFINITY;
    for (size_t k = 0; s->flow && k < s->flow->n_sources; k++) {
        const pm_source_run *r = &s->flow->src[k];
        if (r->next < r->n_releases)
            t = fmin(t, pm_case_source_release_time(s->c, k, r->next));
    }
    return t;
}

void pm_flow_totals_of(const pm_sim *s, pm_flow_totals *t)
{
    memset(t, 0, sizeof *t);
    const pm_flow *f = s->flow;
    if (!f)
        return;
    for (size_t k = 0; k < f->n_sources; k++) {
        t->released += f->src[k].released;
        t->released_mass += f->src[k].released_mass;
    }
    for (size_t k = 0; k < f->n_sinks; k++) {
        t->removed += f->snk[k].removed;
        t->removed_mass += f->snk[k].removed_mass;
    }
    t->max_n = f->max_n;
}

double pm_flow_stable_dt(const pm_sim *s, double particle_wave)
{
    const double w = fmax(particle_wave, pm_flow_wave(s));
    if (s->p.n == 0) {
        const double wait = fmin(pm_flow_next_release(s), s->c->analysis.end_time) - s->t;
        if (wait > 0)
            return wait;
    }
    return s->c->analysis.cfl * s->grid.h_min / w;
}
