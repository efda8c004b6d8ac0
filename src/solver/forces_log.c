/* forces.csv (forces_log.h): one row per output interval / 20, written whole and flushed. */
#include "solver/forces_log.h"

#include "contact/contact.h"
#include "io/plot.h"
#include "pmech/error.h"

#include <errno.h>
#include <math.h>
#include <string.h>

/* The surfaces reported: friction conditions and obstacles (not the walls a fixed side implies). */
static int reported(const pm_contact_surface *sf)
{
    return !sf->guard;
}

static void surface_name(const pm_sim *s, const pm_contact_surface *sf, char *out, size_t cap)
{
    if (sf->obstacle >= 0)
        snprintf(out, cap, "%s", s->c->obstacles[sf->obstacle].name);
    else
        snprintf(out, cap, "boundary_conditions%ld", sf->bc);
}

int pm_forces_log_open(pm_forces_log *log, const pm_sim *s, const char *dir)
{
    memset(log, 0, sizeof *log);
    const pm_contact *ct = s->contact;
    size_t n = 0;
    for (size_t k = 0; ct && k < ct->n_surfaces; k++)
        n += reported(&ct->surface[k]);
    if (!n)
        return PM_OK;
    snprintf(log->csv, sizeof log->csv, "%s/forces.csv", dir);
    snprintf(log->png, sizeof log->png, "%s/forces.png", dir);
    log->f = fopen(log->csv, "w");
    if (!log->f)
        return pm_error_set(PM_EIO, "cannot write '%s': %s", log->csv, strerror(errno));
    fputs("time", log->f);
    for (size_t k = 0; k < ct->n_surfaces; k++) {
        if (!reported(&ct->surface[k]))
            continue;
        char name[PM_NAME_MAX + 32];
        surface_name(s, &ct->surface[k], name, sizeof name);
        fprintf(log->f, ",%s_normal,%s_tangent_x,%s_tangent_y,%s_x,%s_y", name, name, name, name, name);
        if (log->n_plot < sizeof log->column / sizeof log->column[0])
            snprintf(log->column[log->n_plot++], sizeof log->column[0], "%s_normal", name);
    }
    fputc('\n', log->f);
    log->every = s->c->output.interval / 20;
    log->next = log->every;
    for (size_t k = 0; k < ct->n_surfaces; k++)
        memset(&s->contact->surface[k].impulse, 0, sizeof s->contact->surface[k].impulse);
    return fflush(log->f) == 0 ? PM_OK : pm_error_set(PM_EIO, "forces.csv: write failed");
}

int pm_forces_log_step(pm_forces_log *log, pm_sim *s, int force)
{
    if (!log->f)
        return PM_OK;
    const double eps = 1e-12 * s->c->analysis.end_time, span = s->t - log->t_last;
    if ((!force && s->t < log->next - eps) || !(span > 0))
        return PM_OK;
    fprintf(log->f, "%.17g", s->t);
    pm_contact *ct = s->contact;
    for (size_t k = 0; k < ct->n_surfaces; k++) {
        pm_contact_surface *sf = &ct->surface[k];
        if (!reported(sf))
            continue;
        const pm_contact_force *J = &sf->impulse;
        fprintf(log->f, ",%.9g,%.9g,%.9g,%.9g,%.9g", J->normal / span, J->tangent[0] / span, J->tangent[1] / span,
                J->force[0] / span, J->force[1] / span);
        memset(&sf->impulse, 0, sizeof sf->impulse);
    }
    fputc('\n', log->f);
    log->rows++;
    log->t_last = s->t;
    while (log->next <= s->t + eps)
        log->next += log->every;
    return fflush(log->f) == 0 && !ferror(log->f) ? PM_OK : pm_error_set(PM_EIO, "forces.csv: write failed");
}

int pm_forces_log_close(pm_forces_log *log)
{
    int rc = log->f && fclose(log->f) != 0 ? pm_error_set(PM_EIO, "forces.csv: write failed") : PM_OK;
    if (!rc && log->f && log->rows >= 2) {
        const char *cols[sizeof log->column / sizeof log->column[0]];
        for (size_t k = 0; k < log->n_plot; k++)
            cols[k] = log->column[k];
        const pm_plot_opts o = {"Normal force of each surface on the material", "time (s)",
                                "force (N per unit thickness)", 0, 0, 1, 1};
        rc = pm_plot_csv(log->csv, "time", 1.0, cols, 1.0, log->n_plot, log->png, &o);
    }
    memset(log, 0, sizeof *log);
    return rc;
}
