/*
 * Wall traction profiles: for every friction condition and obstacle, wall_<name>.csv holds, at every
 * frame after the first, the traction along the wall averaged over the time since the frame before
 * (pm_contact_profile), and at the end wall_<name>.png draws the last one. Quasi-static runs, whose
 * time only orders the load steps, write the traction of the frame's last (sub)step instead: an
 * average over load steps would mix states under different loads (pm_implicit_step keeps only that
 * step's impulses).
 */
#ifndef PMECH_WALLS_LOG_H
#define PMECH_WALLS_LOG_H

#include "contact/contact.h"
#include "solver/sim_internal.h"

#include <stdio.h>

/** One reported wall: its CSV and its stations. */
typedef struct pm_walls_entry {
    size_t surface;               /**< index in pm_contact::surface */
    FILE *f;                      /**< wall_<name>.csv */
    char csv[PM_PATH_MAX + 96];
    char png[PM_PATH_MAX + 96];
    char name[PM_NAME_MAX + 32];
    size_t n;                     /**< stations */
    pm_contact_station *st;       /**< the last profile written */
    double *plot;                 /**< 3 n: s, normal, tangent of the last profile (kPa-free SI) */
} pm_walls_entry;

/** The open wall profiles of a run (n = 0: nothing to report). */
typedef struct pm_walls_log {
    size_t n;
    pm_walls_entry *wall;
    double t_last;                /**< time of the last profile (the impulses are gathered from then on) */
    long frames;                  /**< profiles written */
} pm_walls_log;

/** Open a wall_<name>.csv in @p dir for every reported surface of @p s. */
int pm_walls_log_open(pm_walls_log *log, pm_sim *s, const char *dir);

/** At a frame: every wall's profile since the last one appended to its CSV (nothing when no time
 *  passed), then the impulses gathered afresh. */
int pm_walls_log_frame(pm_walls_log *log, pm_sim *s);

/** Close (a zeroed log is fine); draw wall_<name>.png from the last profile of each wall. */
int pm_walls_log_close(pm_walls_log *log);

#endif
