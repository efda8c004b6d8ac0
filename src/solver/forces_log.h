/*
 * forces.csv: the force every contact surface (friction condition, obstacle) exerts on the material,
 * averaged over the interval since the row before (the impulses of the laws summed and divided by the
 * time), so that the row does not depend on which step happened to fall on its time.
 */
#ifndef PMECH_FORCES_LOG_H
#define PMECH_FORCES_LOG_H

#include "solver/sim_internal.h"

#include <stdio.h>

/** The open forces.csv of a run (NULL file: the case has no contact surface to report). */
typedef struct pm_forces_log {
    FILE *f;
    char csv[PM_PATH_MAX + 32]; /**< its path */
    char png[PM_PATH_MAX + 32]; /**< forces.png beside it: the normal forces over time, drawn at the close */
    size_t n_plot;              /**< surfaces drawn (the first 8) */
    char column[8][PM_NAME_MAX + 48]; /**< their <name>_normal columns */
    long rows;                  /**< rows written */
    double t_last;  /**< time of the row before (0 at the start) */
    double every;   /**< interval between rows */
    double next;    /**< time of the next row */
} pm_forces_log;

/** Open <dir>/forces.csv with its header when @p s has surfaces to report. */
int pm_forces_log_open(pm_forces_log *log, const pm_sim *s, const char *dir);

/** After a step: a row when its time has come (or @p force is set: the run's last step). */
int pm_forces_log_step(pm_forces_log *log, pm_sim *s, int force);

/** Close (a zeroed log is fine); with two rows or more, draw forces.png (cairo): every surface's normal
 *  force against time. */
int pm_forces_log_close(pm_forces_log *log);

#endif
