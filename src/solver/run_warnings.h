/**
 * @file run_warnings.h (internal to src/, not installed)
 * @brief The warnings of a run: the case's (pm_case_warnings) at the start and a time step that falls
 *        below 1/100 of the first as it happens; printed on stderr unless quiet, listed in run.json.
 */
#ifndef PMECH_SOLVER_RUN_WARNINGS_H
#define PMECH_SOLVER_RUN_WARNINGS_H

#include <stddef.h>

#include "pmech/case.h"

/** Warnings kept for run.json (more are counted, not kept). */
#define PM_RUN_WARNINGS_MAX 16

/** A run's warnings (plain struct: no allocation). */
typedef struct pm_run_warnings {
    char msg[PM_RUN_WARNINGS_MAX][PM_WARNING_LEN];
    size_t n;         /**< messages kept */
    size_t total;     /**< warnings raised */
    int quiet;        /**< 1: do not print */
    double dt_first;  /**< the first step's size (0 before it) */
    int dt_warned;    /**< the step-size warning was given */
} pm_run_warnings;

/** @brief Start: take the case's warnings and print them unless @p quiet. */
void pm_run_warnings_begin(pm_run_warnings *w, const pm_case *c, int quiet);

/** @brief After a completed step of size @p dt ending at time @p t: warn once if dt < dt_first / 100. */
void pm_run_warnings_step(pm_run_warnings *w, long step, double t, double dt);

#endif
