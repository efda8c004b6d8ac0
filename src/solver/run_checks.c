/*
 * What a run refuses before its first step. Each check stands for a run that would otherwise go on for
 * ever or end with exit 0 and a wrong answer: a step count no machine finishes, an explicit step the
 * material cannot follow (energy grows without bound, yet nothing fails), a probe that follows a particle
 * far from the point the user meant.
 */
#include "run_checks.h"

#include "flow.h"
#include "pmech/error.h"

#include <math.h>

/* The largest P-wave speed plus particle speed: the explicit step is stable below h_min over this. */
static double fastest_wave(const pm_sim *s)
{
    const pm_particles *p = &s->p;
    double w = 0;
    for (size_t i = 0; i < p->n; i++) {
        const pm_material *m = &s->c->materials[p->material[i]];
        const double rho = p->mass[i] / p->vol[i];
        const double c = pm_material_signal_speed(m, p->state + p->n_state * i, rho, s->grid.h_min);
        double v2 = 0;
        for (int d = 0; d < PM_DIM; d++)
            v2 += p->v[PM_DIM * i + d] * p->v[PM_DIM * i + d];
        w = fmax(w, c + sqrt(v2));
    }
    if (s->flow)
        w = fmax(w, pm_flow_wave(s));
    return w;
}

static int check_fixed_dt(const pm_sim *s, double wave)
{
    const pm_case *c = s->c;
    if (c->analysis.type != PM_ANALYSIS_EXPLICIT || !(c->analysis.dt > 0) || !(wave > 0))
        return PM_OK;
    const double limit = s->grid.h_min / wave;
    if (c->analysis.dt <= limit)
        return PM_OK;
    return pm_error_set(PM_EINPUT,
                        "%s: analysis.dt: %g s is above the stable explicit step h_min / (c + v) = %g / %g = %g s "
                        "(%.3g times larger): the energy would grow without bound; use a dt below %g or leave "
                        "dt out and set cfl",
                        c->file, c->analysis.dt, s->grid.h_min, wave, limit, c->analysis.dt / limit, limit);
}

static int check_step_count(const pm_sim *s, double wave)
{
    const pm_case *c = s->c;
    const double max_steps = c->analysis.max_steps > 0 ? c->analysis.max_steps : PM_MAX_STEPS_DEFAULT;
    double steps, dt = 0;
    if (c->analysis.type == PM_ANALYSIS_QUASI_STATIC) {
        steps = c->analysis.load_steps;
    } else {
        dt = c->analysis.dt > 0 ? c->analysis.dt : wave > 0 ? c->analysis.cfl * s->grid.h_min / wave : INFINITY;
        steps = ceil(c->analysis.end_time / dt);
    }
    if (steps <= max_steps || isnan(steps))
        return PM_OK;
    return pm_error_set(PM_EINPUT,
                        "%s: analysis: about %.3g steps (end_time %g s / dt %g s) exceed analysis.max_steps = %.3g; "
                        "check end_time, dt and the materials' stiffness and density, or raise max_steps",
                        c->file, steps, c->analysis.end_time, dt, max_steps);
}

/* The largest cell extent along any axis: "a cell away" for an unstructured grid too. The case's
 * rectangle, not the simulation's grid, since gmm and rkpm keep their own node cloud there. */
static double cell_size(const pm_case *c, const pm_grid *g)
{
    double h = 0;
    if (c->grid.type == PM_GRID_RECTANGLE) {
        for (int d = 0; d < PM_DIM; d++)
            h = fmax(h, c->grid.size[d] / c->grid.cells[d]);
        return h;
    }
    for (size_t e = 0; e < g->n_cells; e++) {
        const int32_t *cn = g->conn + (size_t)g->nodes_per_cell * e;
        for (int d = 0; d < PM_DIM; d++) {
            double lo = INFINITY, hi = -INFINITY;
            for (int k = 0; k < g->nodes_per_cell; k++) {
                lo = fmin(lo, g->x[PM_DIM * (size_t)cn[k] + d]);
                hi = fmax(hi, g->x[PM_DIM * (size_t)cn[k] + d]);
            }
            h = fmax(h, hi - lo);
        }
    }
    return h;
}

static int check_probes(const pm_sim *s)
{
    const pm_case *c = s->c;
    const pm_particles *p = &s->p;
    if (p->n == 0)
        return PM_OK; /* the output names a point probe with nothing to follow */
    double reach = -1;
    for (size_t k = 0; k < c->n_probes; k++) {
        const pm_case_probe *pr = &c->probes[k];
        if (pr->body >= 0)
            continue;
        if (reach < 0)
            reach = cell_size(c, &s->grid);
        double best = INFINITY;
        size_t at = 0;
        for (size_t i = 0; i < p->n; i++) {
            double d2 = 0;
            for (int d = 0; d < PM_DIM; d++) {
                const double dx = p->x[PM_DIM * i + d] - pr->point[d];
                d2 += dx * dx;
            }
            if (d2 < best) {
                best = d2;
                at = i;
            }
        }
        if (sqrt(best) > reach)
            return pm_error_set(PM_EINPUT,
                                "%s: probes[%zu].point: (%g, %g) is %g m from the nearest particle (%g, %g), farther "
                                "than a cell (%g m); a probe follows the particle nearest its point, so put the point "
                                "inside the material",
                                c->file, k, pr->point[0], pr->point[1], sqrt(best), p->x[PM_DIM * at],
                                p->x[PM_DIM * at + 1], reach);
    }
    return PM_OK;
}

int pm_run_check_start(const pm_sim *s)
{
    const double wave = fastest_wave(s);
    pm_check(check_fixed_dt(s, wave));
    pm_check(check_step_count(s, wave));
    return check_probes(s);
}
