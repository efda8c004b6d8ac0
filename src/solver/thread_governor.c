/* Thread count by measurement (thread_governor.h). */
#include "solver/thread_governor.h"

#include <string.h>

#define INTERVAL_FIRST 64
#define INTERVAL_MAX 4096
#define BETTER 0.95    /* the other count must take at most 95 % of the time per step */
#define HOPELESS 2.0   /* a trial twice as slow after three steps is cut short */

static double median(const double *v, int n)
{
    double a[PM_GOV_SAMPLES];
    memcpy(a, v, (size_t)n * sizeof *a);
    for (int i = 1; i < n; i++) /* insertion sort: nine numbers */
        for (int j = i; j > 0 && a[j - 1] > a[j]; j--) {
            const double t = a[j];
            a[j] = a[j - 1];
            a[j - 1] = t;
        }
    return n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
}

void pm_thread_gov_init(pm_thread_gov *g, const pm_sim *s, int active)
{
    memset(g, 0, sizeof *g);
    g->n_max = s->nd.n_threads;
    g->cur = g->n_max;
    g->active = active && g->n_max > 1;
    g->interval = g->until_trial = INTERVAL_FIRST;
}

static int other(const pm_thread_gov *g) { return g->cur == 1 ? g->n_max : 1; }

void pm_thread_gov_before(pm_thread_gov *g, pm_sim *s)
{
    if (!g->active)
        return;
    const int n = g->in_trial ? other(g) : g->cur;
    s->nd.n_threads = n;
    if (s->approx)
        s->approx->n_threads = n;
}

static void end_trial(pm_thread_gov *g)
{
    const double mine = median(g->steady, g->n_steady), theirs = median(g->trial, g->n_trial);
    g->in_trial = 0;
    if (theirs < BETTER * mine) {
        g->cur = other(g);
        g->switches++;
        /* the trial's steps are the new count's baseline */
        memcpy(g->steady, g->trial, (size_t)g->n_trial * sizeof *g->trial);
        g->n_steady = g->n_trial;
        g->next_steady = g->n_trial % PM_GOV_SAMPLES;
        g->interval = INTERVAL_FIRST;
    } else if (g->interval < INTERVAL_MAX) {
        g->interval *= 2;
    }
    g->until_trial = g->interval;
}

void pm_thread_gov_after(pm_thread_gov *g, double seconds)
{
    if (!g->active) {
        g->steps_many++;
        return;
    }
    const int n = g->in_trial ? other(g) : g->cur;
    if (n == 1)
        g->steps_one++;
    else
        g->steps_many++;
    if (g->in_trial) {
        g->trial[g->n_trial++] = seconds;
        const int hopeless = g->n_trial >= 3 && median(g->trial, g->n_trial) > HOPELESS * median(g->steady, g->n_steady);
        if (g->n_trial == PM_GOV_SAMPLES || hopeless)
            end_trial(g);
        return;
    }
    g->steady[g->next_steady] = seconds;
    g->next_steady = (g->next_steady + 1) % PM_GOV_SAMPLES;
    if (g->n_steady < PM_GOV_SAMPLES)
        g->n_steady++;
    if (--g->until_trial <= 0 && g->n_steady == PM_GOV_SAMPLES) {
        g->in_trial = 1;
        g->n_trial = 0;
    }
}

int pm_thread_gov_main_count(const pm_thread_gov *g)
{
    if (!g->active)
        return g->n_max;
    return g->steps_one > g->steps_many ? 1 : g->n_max;
}
