/**
 * @file progress.h (internal to src/, not installed)
 * @brief Progress of a long run: one updating line on a terminal (step, simulated time, percent,
 *        ETA, particle-steps per second), plain periodic lines otherwise, nothing when quiet.
 */
#ifndef PMECH_PROGRESS_H
#define PMECH_PROGRESS_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Progress reporter state (plain struct: no allocation). */
typedef struct pm_progress {
    FILE *out;            /**< where to write (stderr) */
    int tty;              /**< 1: redraw one line with '\r' */
    int quiet;            /**< 1: print nothing */
    double end_time;      /**< simulated time at 100 % */
    size_t particles;     /**< for particle-steps per second */
    double wall_start;    /**< monotonic seconds at begin */
    double last_print;    /**< monotonic seconds of the last line */
    long last_step;       /**< step at the last line */
    double last_wall;     /**< wall at the last speed sample */
} pm_progress;

/** @brief Start reporting. @p out is usually stderr; tty is detected with isatty(). */
void pm_progress_begin(pm_progress *pg, FILE *out, double end_time, size_t particles, int quiet);

/** @brief Report step @p step at simulated time @p t (prints at most a few times per second). */
void pm_progress_update(pm_progress *pg, long step, double t);

/** @brief Final line (end the updating line with a newline). */
void pm_progress_end(pm_progress *pg, long step, double t);

/** @brief Monotonic wall clock in seconds. */
double pm_wall_seconds(void);

#ifdef __cplusplus
}
#endif
#endif
