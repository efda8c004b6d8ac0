/* Progress of a run: one line redrawn in place on a terminal (at most 5 times a second), a plain
 * line every 10 s of wall time in a log, nothing when quiet. Called every step, so the common
 * path is one monotonic clock read and a comparison. */
#include "io/progress.h"

#include <math.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#define TTY_PERIOD 0.2  /* seconds between redraws on a terminal */
#define LOG_PERIOD 10.0 /* seconds between lines otherwise */
#define PACE_MEMORY 30.0 /* wall seconds over which the rate of simulated time is averaged */

double pm_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void pm_progress_begin(pm_progress *pg, FILE *out, double end_time, int quiet)
{
    pg->out = out;
    pg->quiet = quiet || !out;
    int fd = out ? fileno(out) : -1;
    pg->tty = !pg->quiet && fd >= 0 && isatty(fd);
    pg->end_time = end_time;
    pg->wall_start = pm_wall_seconds();
    pg->last_print = pg->last_wall = pg->wall_start;
    pg->last_loop = pg->last_t = pg->last_psteps = 0;
    pg->log_pace = 0;
    pg->have_pace = 0;
}

/* h:mm:ss, or "-:--:--" when unknown */
static void fmt_hms(char *buf, size_t n, double s)
{
    if (!(s >= 0) || s > 3.6e9) {
        snprintf(buf, n, "-:--:--");
        return;
    }
    long v = lround(s);
    snprintf(buf, n, "%ld:%02ld:%02ld", v / 3600, (v / 60) % 60, v % 60);
}

/* The status line (no '\r' or newline). label is "ETA" with the estimated time left, or "wall"
 * with the time so far; rate in particle-steps per second. */
static void print_line(const pm_progress *pg, long step, double t, const char *label, double secs,
                       double rate)
{
    char hms[32];
    fmt_hms(hms, sizeof hms, secs);
    double pct = pg->end_time > 0 ? 100.0 * t / pg->end_time : 0.0;
    if (!isfinite(rate) || rate < 0)
        rate = 0;
    fprintf(pg->out, "step %ld  t = %.3e s  %.1f %%  %s %s  %.3g M particle-steps/s", step, t, pct, label, hms,
            rate * 1e-6);
}

/* Fold the interval since the last sample into the average pace (wall seconds per simulated second). */
static void sample_pace(pm_progress *pg, double t, double now)
{
    const double dw = now - pg->last_wall, dt = t - pg->last_t;
    if (!(dw > 0) || !(dt > 0))
        return;
    const double lp = log(dw / dt);
    if (!pg->have_pace) {
        pg->log_pace = lp;
        pg->have_pace = 1;
    } else {
        pg->log_pace += (1 - exp(-dw / PACE_MEMORY)) * (lp - pg->log_pace);
    }
    pg->last_wall = now;
    pg->last_t = t;
}

void pm_progress_update_at(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps,
                           double now)
{
    if (pg->quiet || now - pg->last_print < (pg->tty ? TTY_PERIOD : LOG_PERIOD))
        return;
    sample_pace(pg, t, now);
    const double left = pg->end_time - t;
    const double eta = !pg->have_pace ? -1.0 : left > 0 ? left * exp(pg->log_pace) : 0.0;
    const double dl = loop_seconds - pg->last_loop;
    const double rate = dl > 0 ? (particle_steps - pg->last_psteps) / dl : 0.0;
    if (pg->tty)
        fputc('\r', pg->out);
    print_line(pg, step, t, "ETA", eta, rate);
    /* a terminal: clear what is left of a longer previous line */
    fputs(pg->tty ? "\033[K" : "\n", pg->out);
    fflush(pg->out);
    pg->last_print = now;
    pg->last_loop = loop_seconds;
    pg->last_psteps = particle_steps;
}

void pm_progress_update(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps)
{
    if (pg->quiet)
        return;
    pm_progress_update_at(pg, step, t, loop_seconds, particle_steps, pm_wall_seconds());
}

void pm_progress_end_at(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps,
                        double now)
{
    if (pg->quiet)
        return;
    const double rate = loop_seconds > 0 ? particle_steps / loop_seconds : 0.0;
    if (pg->tty)
        fputc('\r', pg->out);
    print_line(pg, step, t, "wall", now - pg->wall_start, rate);
    fputs(pg->tty ? "\033[K\n" : "\n", pg->out);
    fflush(pg->out);
    pg->last_print = now;
    pg->last_loop = loop_seconds;
    pg->last_psteps = particle_steps;
}

void pm_progress_end(pm_progress *pg, long step, double t, double loop_seconds, double particle_steps)
{
    pm_progress_end_at(pg, step, t, loop_seconds, particle_steps, pm_wall_seconds());
}
