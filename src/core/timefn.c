/* Scalar functions of time: values and exact integrals (timefn.h). */
#include "pmech/timefn.h"

#include <stdlib.h>
#include <string.h>

/* Table segment holding t: the last i with t[i] <= t (t inside [t[0], t[n-1]]). */
static size_t segment(const pm_timefn *f, double t)
{
    size_t lo = 0, hi = f->n - 1;
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        if (f->t[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

double pm_timefn_value(const pm_timefn *f, double t)
{
    switch (f->kind) {
    case PM_TIMEFN_RAMP: return t >= f->ramp_time ? f->value : t > 0 ? f->value * t / f->ramp_time : 0.0;
    case PM_TIMEFN_TABLE: {
        if (t <= f->t[0])
            return f->v[0];
        if (t >= f->t[f->n - 1])
            return f->v[f->n - 1];
        const size_t i = segment(f, t);
        const double s = (t - f->t[i]) / (f->t[i + 1] - f->t[i]);
        return f->v[i] + s * (f->v[i + 1] - f->v[i]);
    }
    default: return f->value;
    }
}

/* Integral of a table from a to b, both inside one segment or beyond the ends (trapezoid, exact). */
static double table_piece(const pm_timefn *f, double a, double b)
{
    return 0.5 * (pm_timefn_value(f, a) + pm_timefn_value(f, b)) * (b - a);
}

double pm_timefn_integral(const pm_timefn *f, double t)
{
    if (!(t > 0))
        return 0.0;
    switch (f->kind) {
    case PM_TIMEFN_RAMP:
        if (t <= f->ramp_time)
            return 0.5 * f->value * t * t / f->ramp_time;
        return 0.5 * f->value * f->ramp_time + f->value * (t - f->ramp_time);
    case PM_TIMEFN_TABLE: {
        /* the pieces: [0, t0] constant, the segments, beyond the end constant */
        double sum = 0.0, a = 0.0;
        for (size_t i = 0; i < f->n && a < t; i++) {
            const double b = f->t[i] < t ? f->t[i] : t;
            if (b > a) {
                sum += table_piece(f, a, b);
                a = b;
            }
        }
        if (t > a)
            sum += table_piece(f, a, t);
        return sum;
    }
    default: return f->value * t;
    }
}

void pm_timefn_free(pm_timefn *f)
{
    if (f->kind == PM_TIMEFN_TABLE) {
        free(f->t);
        free(f->v);
    }
    memset(f, 0, sizeof *f);
}
