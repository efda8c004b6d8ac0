/* wall_<name>.csv and wall_<name>.png (walls_log.h). */
#include "solver/walls_log.h"

#include "solver/implicit_internal.h"

#include "io/plot.h"
#include "pmech/error.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* As forces.csv: friction conditions and obstacles, not the guard walls a fixed side implies. */
static int reported(const pm_contact_surface *sf)
{
    return !sf->guard;
}

int pm_walls_log_open(pm_walls_log *log, pm_sim *s, const char *dir)
{
    memset(log, 0, sizeof *log);
    pm_contact *ct = s->contact;
    size_t n = 0;
    for (size_t k = 0; ct && k < ct->n_surfaces; k++)
        n += reported(&ct->surface[k]);
    if (!n)
        return PM_OK;
    log->wall = calloc(n, sizeof *log->wall);
    if (!log->wall)
        return pm_error_set(PM_ENOMEM, "out of memory for the wall profiles");
    log->n = n;
    size_t w = 0;
    for (size_t k = 0; k < ct->n_surfaces; k++) {
        const pm_contact_surface *sf = &ct->surface[k];
        if (!reported(sf))
            continue;
        pm_walls_entry *e = &log->wall[w++];
        e->surface = k;
        if (sf->obstacle >= 0)
            snprintf(e->name, sizeof e->name, "%s", s->c->obstacles[sf->obstacle].name);
        else
            snprintf(e->name, sizeof e->name, "boundary_conditions%ld", sf->bc);
        snprintf(e->csv, sizeof e->csv, "%s/wall_%s.csv", dir, e->name);
        snprintf(e->png, sizeof e->png, "%s/wall_%s.png", dir, e->name);
        e->n = pm_contact_profile_stations(ct, k, &s->grid);
        e->st = calloc(e->n, sizeof *e->st);
        e->plot = calloc(3 * e->n, sizeof *e->plot);
        if (!e->st || !e->plot)
            return pm_error_set(PM_ENOMEM, "out of memory for the wall profiles");
        e->f = fopen(e->csv, "w");
        if (!e->f)
            return pm_error_set(PM_EIO, "cannot write '%s': %s", e->csv, strerror(errno));
        fputs("time,s,x,y,normal,tangent\n", e->f);
        if (fflush(e->f) != 0)
            return pm_error_set(PM_EIO, "%s: write failed", e->csv);
    }
    pm_contact_profile_reset(ct);
    log->t_last = s->t;
    return PM_OK;
}

int pm_walls_log_frame(pm_walls_log *log, pm_sim *s)
{
    /* quasi-static: the impulses are those of the last accepted substep alone, of that length */
    const int last_step_only = s->c->analysis.type == PM_ANALYSIS_QUASI_STATIC && s->implicit;
    const double span = last_step_only ? s->implicit->dt : s->t - log->t_last;
    if (!log->n || !(span > 0))
        return PM_OK;
    for (size_t w = 0; w < log->n; w++) {
        pm_walls_entry *e = &log->wall[w];
        pm_check(pm_contact_profile(s->contact, e->surface, &s->grid, span, e->st, e->n));
        for (size_t j = 0; j < e->n; j++) {
            const pm_contact_station *q = &e->st[j];
            fprintf(e->f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", s->t, q->s, q->x[0], q->x[1], q->normal, q->tangent);
        }
        if (fflush(e->f) != 0 || ferror(e->f))
            return pm_error_set(PM_EIO, "%s: write failed", e->csv);
    }
    pm_contact_profile_reset(s->contact);
    log->t_last = s->t;
    log->frames++;
    return PM_OK;
}

int pm_walls_log_close(pm_walls_log *log)
{
    int rc = PM_OK;
    for (size_t w = 0; w < log->n; w++) {
        pm_walls_entry *e = &log->wall[w];
        if (e->f && fclose(e->f) != 0 && !rc)
            rc = pm_error_set(PM_EIO, "%s: write failed", e->csv);
        if (!rc && log->frames > 0 && e->n > 1) {
            double *s = e->plot, *sn = s + e->n, *st = sn + e->n;
            for (size_t j = 0; j < e->n; j++) {
                s[j] = e->st[j].s;
                sn[j] = e->st[j].normal;
                st[j] = e->st[j].tangent;
            }
            const pm_plot_series series[2] = {{s, sn, e->n, "normal", {0, 0, 0}, 0, 1},
                                              {s, st, e->n, "tangential", {0, 0, 0}, 0, 1}};
            char title[PM_NAME_MAX + 96];
            snprintf(title, sizeof title, "Traction of %s on the material (last frame)", e->name);
            const pm_plot_opts o = {title, "position along the wall (m)", "traction (Pa)", 0, 0, 1, 1};
            rc = pm_plot_lines(e->png, series, 2, &o);
        }
        free(e->st);
        free(e->plot);
    }
    free(log->wall);
    memset(log, 0, sizeof *log);
    return rc;
}
