/**
 * @file timefn.h
 * @brief A scalar function of time for prescribed quantities that change during a run (an obstacle's
 *        velocity component, a load's magnitude): a constant, a linear ramp from zero to a value, or a
 *        piecewise-linear table held constant beyond its ends. Plain data, so a run's state stays a
 *        function of time alone (checkpoints need nothing from it).
 */
#ifndef PMECH_TIMEFN_H
#define PMECH_TIMEFN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#ifdef __cplusplus
}
#endif

#endif

/** How a pm_timefn is given. */
typedef enum pm_timefn_kind {
    PM_TIMEFN_CONSTANT = 0, /**< value at every time */
    PM_TIMEFN_RAMP = 1,     /**< 0 at t = 0, value at ramp_time and after, linear between */
    PM_TIMEFN_TABLE = 2     /**< linear between (t[i], v[i]); v[0] before t[0], v[n-1] after t[n-1] */
} pm_timefn_kind;

/** One scalar function of time (the table arrays are owned: pm_timefn_free). */
typedef struct pm_timefn {
    pm_timefn_kind kind;
    double value;      /**< constant and ramp: the value */
    double ramp_time;  /**< ramp: time at which value is reached (> 0) */
    size_t n;          /**< table: points (>= 1), times strictly increasing */
    double *t, *v;     /**< table: times and values */
} pm_timefn;

/** The function's value at time @p t. */
double pm_timefn_value(const pm_timefn *f, double t);

/** The integral of the function from 0 to @p t (t >= 0): exact for every kind. */
double pm_timefn_integral(const pm_timefn *f, double t);

/** Free a table's arrays and make @p f the constant 0 (a zeroed struct is fine). */
void pm_timefn_free(pm_timefn *f);

#ifdef __cplusplus
}
#endif

#endif
