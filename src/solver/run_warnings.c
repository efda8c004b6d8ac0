/* Warnings of a run (run_warnings.h). A collapsing step size is the usual sign of particles flying off or
 * a body turning inside out; the run goes on, but the user should know why it has slowed down. */
#include "solver/run_warnings.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static void keep(pm_run_warnings *w, const char *msg)
{
    if (w->n < PM_RUN_WARNINGS_MAX) {
        const size_t len = strnlen(msg, PM_WARNING_LEN - 1);
        memcpy(w->msg[w->n], msg, len);
        w->msg[w->n++][len] = '\0';
    }
    w->total++;
    if (!w->quiet)
        fprintf(stderr, "pmech: warning: %s\n", msg);
}

void pm_run_warnings_begin(pm_run_warnings *w, const pm_case *c, int quiet)
{
    memset(w, 0, sizeof *w);
    w->quiet = quiet;
    char found[PM_RUN_WARNINGS_MAX][PM_WARNING_LEN];
    const size_t n = pm_case_warnings(c, found, PM_RUN_WARNINGS_MAX);
    for (size_t k = 0; k < n && k < PM_RUN_WARNINGS_MAX; k++)
        keep(w, found[k]);
    w->total += n > PM_RUN_WARNINGS_MAX ? n - PM_RUN_WARNINGS_MAX : 0;
}

void pm_run_warnings_step(pm_run_warnings *w, long step, double t, double dt)
{
    if (w->dt_first <= 0) {
        w->dt_first = dt;
        return;
    }
    if (w->dt_warned || !(dt < 0.01 * w->dt_first))
        return;
    char msg[PM_WARNING_LEN];
    snprintf(msg, sizeof msg, "step %ld (t = %.6g s): the time step %.3g s fell below 1/100 of the first (%.3g s): "
             "particles moving fast or a body collapsing; the run goes on, slowly", step, t, dt, w->dt_first);
    w->dt_warned = 1;
    keep(w, msg);
}
