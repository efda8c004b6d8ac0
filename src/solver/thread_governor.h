/**
 * @file thread_governor.h (internal to src/, not installed)
 * @brief The thread count of an explicit run chosen by measurement, so that a run is never slower than
 *        on one thread when other programs hold the cores.
 *
 * A run whose thread count the user did not fix starts on all the threads it was given. Now and then it
 * takes a few steps on the other count (one thread if it runs on several, and back) and compares the
 * median step times; it moves to the other count when that is at least 5 % faster. A trial that loses
 * makes the next one twice as far away (64 steps at first, at most 4096), and one that is twice as slow
 * after three steps is cut short, so the trials cost little once the choice is made. Steps that write
 * frames are not timed here (the caller times the step alone).
 */
#ifndef PMECH_SOLVER_THREAD_GOVERNOR_H
#define PMECH_SOLVER_THREAD_GOVERNOR_H

#include "solver/sim_internal.h"

/** Samples for one median. */
#define PM_GOV_SAMPLES 9

/** Governor state (plain struct: no allocation). */
typedef struct pm_thread_gov {
    int active;                        /**< 0: the count stays as it is */
    int n_max;                         /**< the count the run was given */
    int cur;                           /**< the count chosen */
    int in_trial;                      /**< 1: the steps run on the other count */
    double steady[PM_GOV_SAMPLES];     /**< the last step times on the chosen count (ring) */
    int n_steady, next_steady;
    double trial[PM_GOV_SAMPLES];      /**< step times of the running trial */
    int n_trial;
    long interval;                     /**< steps between trials */
    long until_trial;                  /**< steps left before the next trial */
    long steps_one, steps_many;        /**< steps run on one thread and on n_max */
    int switches;                      /**< times the chosen count changed */
} pm_thread_gov;

/** @brief Start; @p active 0 keeps the simulation's thread count for the whole run. */
void pm_thread_gov_init(pm_thread_gov *g, const pm_sim *s, int active);

/** @brief Before a step: set the simulation's thread count for it. */
void pm_thread_gov_before(pm_thread_gov *g, pm_sim *s);

/** @brief After a step that took @p seconds. */
void pm_thread_gov_after(pm_thread_gov *g, double seconds);

/** @brief The thread count most steps ran with. */
int pm_thread_gov_main_count(const pm_thread_gov *g);

#endif
