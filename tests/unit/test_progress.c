/* Progress lines: format, cadence on a terminal and in a log, the time loop's speed, an ETA that
 * follows the recent pace, silence when quiet. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/progress.h"

/* Everything written to f so far, as a string. */
static char *contents(FILE *f)
{
    fflush(f);
    long n = ftell(f);
    char *buf = calloc((size_t)n + 1, 1);
    rewind(f);
    size_t got = fread(buf, 1, (size_t)n, f);
    buf[got] = '\0';
    fseek(f, 0, SEEK_END);
    return buf;
}

static int matches(const char *s, const char *pattern)
{
    regex_t re;
    if (regcomp(&re, pattern, REG_EXTENDED | REG_NOSUB) != 0)
        return 0;
    int ok = regexec(&re, s, 0, NULL, 0) == 0;
    regfree(&re);
    return ok;
}

/* A progress log on a temporary file, begun for a run to t_end. */
static FILE *begin_log(pm_progress *pg, double t_end, int quiet)
{
    FILE *f = tmpfile();
    assert_non_null(f);
    pm_progress_begin(pg, f, t_end, quiet);
    return f;
}

/* Fails unless what f holds so far contains want. */
static void assert_log_has(FILE *f, const char *want)
{
    char *t = contents(f);
    if (strstr(t, want) == NULL)
        fail_msg("the log lacks \"%s\":\n%s", want, t);
    free(t);
}

#define LINE_RE "step [0-9]+  t = [0-9]\\.[0-9]{3}e[-+][0-9]{2} s  [0-9]+\\.[0-9] %  "
#define RATE_RE "  [0-9.e+-]+ M particle-steps/s"

static void wall_clock_is_monotonic(void **state)
{
    (void)state;
    double a = pm_wall_seconds(), b = pm_wall_seconds();
    assert_true(a > 0);
    assert_true(b >= a);
}

/* A log line every 10 s. The speed counts the time loop only: 1000 steps of 1000 particles in 1 s of
 * loop time are 1 M particle-steps/s, though 10 s of wall time passed (the rest went to output). Half
 * way after 10 s of wall time: 10 s left. */
static void log_lines_every_ten_seconds(void **state)
{
    (void)state;
    pm_progress pg;
    FILE *f = begin_log(&pg, 2.0, 0);
    assert_int_equal(pg.tty, 0); /* a regular file is not a terminal */
    const double w0 = pg.wall_start;
    /* straight after begin: nothing */
    for (long s = 1; s <= 1000; s++)
        pm_progress_update_at(&pg, s, 1e-3 * (double)s, 1e-3 * (double)s, 1e3 * (double)s, w0 + 1e-3 * (double)s);
    char *t = contents(f);
    assert_string_equal(t, "");
    free(t);
    pm_progress_update_at(&pg, 1000, 1.0, 1.0, 1e6, w0 + 10.0);
    t = contents(f);
    assert_true(matches(t, "^" LINE_RE "ETA [0-9]+:[0-9]{2}:[0-9]{2}" RATE_RE "\n$"));
    assert_non_null(strstr(t, "step 1000  t = 1.000e+00 s  50.0 %  ETA 0:00:10  1 M particle-steps/s\n"));
    assert_null(strchr(t, '\r'));
    free(t);
    /* right after a line: quiet again */
    pm_progress_update_at(&pg, 1001, 1.001, 1.001, 1.001e6, w0 + 10.5);
    t = contents(f);
    assert_int_equal(strchr(t, '\n') - t + 1, (long)strlen(t));
    free(t);
    /* the end: the whole wall time, and the loop's speed over the run (2000 steps in 4 s: 0.5 M) */
    pm_progress_end_at(&pg, 2000, 2.0, 4.0, 2e6, w0 + 20.0);
    t = contents(f);
    const char *last = strchr(t, '\n') + 1;
    assert_true(matches(last, "^" LINE_RE "wall [0-9]+:[0-9]{2}:[0-9]{2}" RATE_RE "\n$"));
    assert_non_null(strstr(last, "step 2000  t = 2.000e+00 s  100.0 %  wall 0:00:20  0.5 M particle-steps/s\n"));
    free(t);
    fclose(f);
}

/* The ETA of a run whose step shrinks: 1 simulated second in the first 10 s, then 1e-3 s per 10 s. After
 * two minutes of the slow pace the ETA must be within 15 % of what that pace needs for the rest (the
 * average is over logarithms of the pace with a 30 s memory: the fast start keeps exp(-4) of the weight,
 * a factor 1000^0.018 = 1.13). An ETA from the whole run's average would say 2 minutes instead of 2.7 h. */
static void eta_follows_a_shrinking_step(void **state)
{
    (void)state;
    pm_progress pg;
    FILE *f = begin_log(&pg, 2.0, 0);
    const double w0 = pg.wall_start;
    double t = 1.0, w = w0 + 10.0;
    pm_progress_update_at(&pg, 100, t, 1.0, 1e3, w);
    for (int k = 0; k < 12; k++) {
        t += 1e-3;
        w += 10.0;
        pm_progress_update_at(&pg, 101 + k, t, 1.0, 10.0 * (101 + k), w);
    }
    const double want = (2.0 - t) * 1e4; /* seconds left at 10 s per 1e-3 s */
    const double eta = (2.0 - t) * exp(pg.log_pace);
    if (fabs(eta / want - 1) > 0.15)
        fail_msg("ETA %.0f s, the slow pace needs %.0f s", eta, want);
    fclose(f);
}

static void terminal_redraws_one_line(void **state)
{
    (void)state;
    pm_progress pg;
    FILE *f = begin_log(&pg, 1.0, 0);
    pg.tty = 1; /* as if stderr were a terminal */
    pm_progress_update_at(&pg, 1, 0.1, 0.01, 10, pg.wall_start + 0.1); /* within 0.2 s of begin: nothing */
    char *t = contents(f);
    assert_string_equal(t, "");
    free(t);
    const double w0 = pg.wall_start;
    pm_progress_update_at(&pg, 2, 0.2, 0.1, 20, w0 + 0.25);
    pm_progress_update_at(&pg, 3, 0.3, 0.2, 30, w0 + 0.5);
    pm_progress_end_at(&pg, 10, 1.0, 0.5, 100, w0 + 1.0);
    t = contents(f);
    /* three redraws of the same line, each clearing the rest of it; a newline only at the end */
    assert_true(matches(t, "^\r" LINE_RE "ETA [^\r\n]*" RATE_RE "\033\\[K"
                           "\r" LINE_RE "ETA [^\r\n]*" RATE_RE "\033\\[K"
                           "\r" LINE_RE "wall [^\r\n]*" RATE_RE "\033\\[K\n$"));
    assert_non_null(strstr(t, "\rstep 3  t = 3.000e-01 s  30.0 %  ETA "));
    free(t);
    fclose(f);
}

static void quiet_prints_nothing(void **state)
{
    (void)state;
    pm_progress pg;
    FILE *f = begin_log(&pg, 1.0, 1);
    pm_progress_update_at(&pg, 5, 0.5, 1.0, 50, pg.wall_start + 100);
    pm_progress_end(&pg, 10, 1.0, 2.0, 100);
    char *t = contents(f);
    assert_string_equal(t, "");
    free(t);
    fclose(f);
}

static void unknown_eta_before_time_advances(void **state)
{
    (void)state;
    pm_progress pg;
    FILE *f = begin_log(&pg, 1.0, 0);
    pm_progress_update_at(&pg, 0, 0.0, 0.0, 0.0, pg.wall_start + 11);
    assert_log_has(f, "0.0 %  ETA -:--:--  ");
    fclose(f);
}

/* A run whose particle count grows (sources) or shrinks (sinks): the speed is the particles actually
 * stepped, the caller's running sum, per second of loop time. Here a filling that adds 10 particles
 * every step from 10: after 1000 steps it has stepped sum(10 k, k = 1..1000) = 5.005e6 particle-steps;
 * in 1 s of loop time that is 5.005 M/s, not the 0.01 M/s its 10 particles at the start would give
 * (what the line said before it took the sum). The next line covers steps 1001-2000 alone (15.005e6
 * particle-steps in 1 s), and the last one the whole run (20.01e6 in 2 s). */
static void rate_follows_a_growing_count(void **state)
{
    (void)state;
    pm_progress pg;
    FILE *f = begin_log(&pg, 2.0, 0);
    const double w0 = pg.wall_start;
    double sum = 0;
    for (long k = 1; k <= 2000; k++) {
        sum += 10.0 * (double)k;
        if (k == 1000)
            pm_progress_update_at(&pg, k, 1e-3 * (double)k, 1.0, sum, w0 + 10.0);
        else if (k == 2000)
            pm_progress_update_at(&pg, k, 1e-3 * (double)k, 2.0, sum, w0 + 20.0);
    }
    pm_progress_end_at(&pg, 2000, 2.0, 2.0, sum, w0 + 20.0);
    assert_log_has(f, "step 1000  t = 1.000e+00 s  50.0 %  ETA 0:00:10  5 M particle-steps/s\n");
    assert_log_has(f, "step 2000  t = 2.000e+00 s  100.0 %  ETA 0:00:00  15 M particle-steps/s\n");
    assert_log_has(f, "step 2000  t = 2.000e+00 s  100.0 %  wall 0:00:20  10 M particle-steps/s\n");
    fclose(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(wall_clock_is_monotonic),
        cmocka_unit_test(log_lines_every_ten_seconds),
        cmocka_unit_test(eta_follows_a_shrinking_step),
        cmocka_unit_test(terminal_redraws_one_line),
        cmocka_unit_test(quiet_prints_nothing),
        cmocka_unit_test(unknown_eta_before_time_advances),
        cmocka_unit_test(rate_follows_a_growing_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
