/* releases.csv and removals.csv: one row per release (or skipped release) and per sink and step that
 * removed particles; each row is written whole and flushed, so the files stay valid if a run stops. */
#include "solver/flow.h"

#include "pmech/error.h"

#include <errno.h>
#include <string.h>

static int open_csv(FILE **f, const char *dir, const char *name, const char *header)
{
    char path[PM_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    *f = fopen(path, "w");
    if (!*f)
        return pm_error_set(PM_EIO, "cannot write '%s': %s", path, strerror(errno));
    if (fputs(header, *f) < 0 || fflush(*f) != 0)
        return pm_error_set(PM_EIO, "cannot write '%s'", path);
    return PM_OK;
}

static int end_row(FILE *f, const char *name)
{
    return fflush(f) == 0 && !ferror(f) ? PM_OK : pm_error_set(PM_EIO, "%s: write failed", name);
}

static int log_releases(FILE *f, const pm_sim *s)
{
    const pm_flow *fl = s->flow;
    for (size_t k = 0; k < fl->n_sources; k++) {
        const pm_source_run *r = &fl->src[k];
        if (r->event == PM_RELEASE_NONE)
            continue;
        const int done = r->event == PM_RELEASE_DONE;
        fprintf(f, "%.17g,%s,%zu,%.17g,%.17g\n", r->event_time, s->c->sources[k].body.name,
                done ? r->portion.n : 0, done ? r->portion_mass : 0.0, r->released_mass);
        pm_check(end_row(f, "releases.csv"));
    }
    return PM_OK;
}

static int log_removals(FILE *f, const pm_sim *s)
{
    const pm_flow *fl = s->flow;
    for (size_t k = 0; k < fl->n_sinks; k++) {
        const pm_sink_run *r = &fl->snk[k];
        if (r->step_particles == 0)
            continue;
        fprintf(f, "%.17g,%s,%zu,%.17g,%.17g\n", s->t, s->c->sinks[k].name, r->step_particles, r->step_mass,
                r->removed_mass);
        pm_check(end_row(f, "removals.csv"));
    }
    return PM_OK;
}

int pm_flow_log_open(pm_flow_log *log, const pm_sim *s, const char *dir)
{
    memset(log, 0, sizeof *log);
    if (!s->flow)
        return PM_OK;
    if (s->flow->n_sources) {
        pm_check(open_csv(&log->releases, dir, "releases.csv", "time,source,particles,mass,cumulative_mass\n"));
        pm_check(log_releases(log->releases, s));
    }
    if (s->flow->n_sinks)
        pm_check(open_csv(&log->removals, dir, "removals.csv", "time,sink,particles,mass,cumulative_mass\n"));
    return PM_OK;
}

int pm_flow_log_step(pm_flow_log *log, const pm_sim *s)
{
    if (log->releases)
        pm_check(log_releases(log->releases, s));
    if (log->removals)
        pm_check(log_removals(log->removals, s));
    return PM_OK;
}

int pm_flow_log_close(pm_flow_log *log)
{
    int rc = PM_OK;
    if (log->releases && fclose(log->releases) != 0)
        rc = pm_error_set(PM_EIO, "releases.csv: write failed");
    if (log->removals && fclose(log->removals) != 0 && !rc)
        rc = pm_error_set(PM_EIO, "removals.csv: write failed");
    memset(log, 0, sizeof *log);
    return rc;
}
