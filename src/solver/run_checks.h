/* Checks a run makes before its first step (solver/run_checks.c). */
#ifndef PM_RUN_CHECKS_H
#define PM_RUN_CHECKS_H

#include "sim_internal.h"

/** Default of analysis.max_steps when a case built in code leaves it 0. */
#define PM_MAX_STEPS_DEFAULT 1e8

/**
 * @brief Refuse, before any step, a run that would be unbounded or silently wrong: an estimated step
 *        count above analysis.max_steps, an explicit fixed dt above the stable step, a point probe
 *        farther than a cell from every particle.
 * @param s a freshly created simulation
 * @return PM_OK, or PM_EINPUT with a message naming the key, the value and the limit
 */
int pm_run_check_start(const pm_sim *s);

#endif
