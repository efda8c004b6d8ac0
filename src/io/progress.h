/**
 * @file progress.h (internal to src/, not installed)
 * @brief Progress of a long run: one updating line on a terminal (step, simulated time, percent,
 *        ETA, particle-steps per second), plain periodic lines otherwise, nothing when quiet.
 *
 * The speed counts the time loop only (the seconds the caller spent in steps, not in writing
 * frames) and the particles each step actually stepped (the caller's running sum, which follows
 * sources and sinks), as run.json does. The ETA divides the simulated time left by the recent rate
 * of simulated time: a time-weighted moving average of the logarithm of wall seconds per simulated
 * second, with a 30-second memory, so that it follows a shrinking (or growing) step within a minute
 * or two instead of averaging over the whole run.
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
    double wall_start;    /**< monotonic seconds at begin */
    double last_print;    /**< monotonic seconds of the last line */
    double last_loop;     /**< time-loop seconds at the last line */
    double last_psteps;   /**< particle-steps at the last line */
    double last_wall;     /**< wall at the last sample of the simulated-time rate */
    double last_t;        /**< simulated time at that sample */
    double log_pace;      /**< moving average of ln(wall seconds per simulated second) */
    int have_pace;        /**< 1 once log_pace holds a sample */
} pm_progress;

/** @brief Start reporting. @p out is usually stderr; tty is detected with isatty(). */
void pm_progress_begin(pm_progress *pg, FILE *out, double end_time, int quiet);

/**
 * @brief Report step @p step at simulated time @p t (prints at most 5 times a second on a terminal, every
 *        10 s otherwise).
 * @param loop_seconds   the seconds spent in the time loop's steps so far
 * @param particle_steps the particles stepped so far, summed over those steps (each step counts the
 *                       particles it moved, so a run that injects or removes particles is measured
 *                       by what it did, not by its count at the start)
 */
void pm_progress_update(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps);

/** @brief pm_progress_update() at wall time @p now (monotonic seconds), for tests. */
void pm_progress_update_at(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps,
                           double now);

/** @brief Final line (end the updating line with a newline): the whole wall time, the loop's speed
 *         (@p particle_steps over @p loop_seconds, as run.json's particle_steps_per_second). */
void pm_progress_end(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps);

/** @brief pm_progress_end() at wall time @p now, for tests. */
void pm_progress_end_at(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps,
                        double now);

/** @brief Monotonic wall clock in seconds. */
double pm_wall_seconds(void);

#ifdef __cplusplus
}
#endif
#endif
