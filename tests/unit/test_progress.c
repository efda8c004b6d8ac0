/* Progress lines: format, cadence on a terminal and in a log, silence when quiet. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

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

#define LINE_RE "step [0-9]+  t = [0-9]\\.[0-9]{3}e[-+][0-9]{2} s  [0-9]+\\.[0-9] %  "
#define RATE_RE "  [0-9.e+-]+ M particle-steps/s"

static void wall_clock_is_monotonic(void **state)
{
    (void)state;
    double a = pm_wall_seconds(), b = pm_wall_seconds();
    assert_true(a > 0);
    assert_true(b >= a);
}

static void log_lines_every_ten_seconds(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    assert_non_null(f);
    pm_progress pg;
    pm_progress_begin(&pg, f, 2.0, 1000000, 0);
    assert_int_equal(pg.tty, 0); /* a regular file is not a terminal */
    /* straight after begin: nothing */
    for (long s = 1; s <= 1000; s++)
        pm_progress_update(&pg, s, 1e-3 * (double)s);
    char *t = contents(f);
    assert_string_equal(t, "");
    free(t);
    /* 10 s later (pretend): one line; half way after 10 s of wall time -> 10 s left; 100 steps of
     * a million particles in those 10 s -> 10 M particle-steps/s */
    double now = pm_wall_seconds();
    pg.wall_start = now - 10.0;
    pg.last_print = now - 10.5;
    pg.last_wall = now - 10.0;
    pg.last_step = 900;
    pm_progress_update(&pg, 1000, 1.0);
    t = contents(f);
    assert_true(matches(t, "^" LINE_RE "ETA [0-9]+:[0-9]{2}:[0-9]{2}" RATE_RE "\n$"));
    assert_non_null(strstr(t, "step 1000  t = 1.000e+00 s  50.0 %  ETA 0:00:10  10 M particle-steps/s\n"));
    assert_null(strchr(t, '\r'));
    free(t);
    /* right after a line: quiet again */
    pm_progress_update(&pg, 1001, 1.001);
    t = contents(f);
    assert_int_equal(strchr(t, '\n') - t + 1, (long)strlen(t));
    free(t);
    pm_progress_end(&pg, 2000, 2.0);
    t = contents(f);
    const char *last = strchr(t, '\n') + 1;
    assert_true(matches(last, "^" LINE_RE "wall [0-9]+:[0-9]{2}:[0-9]{2}" RATE_RE "\n$"));
    assert_non_null(strstr(last, "step 2000  t = 2.000e+00 s  100.0 %  wall 0:00:10  "));
    free(t);
    fclose(f);
}

static void terminal_redraws_one_line(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    assert_non_null(f);
    pm_progress pg;
    pm_progress_begin(&pg, f, 1.0, 10, 0);
    pg.tty = 1; /* as if stderr were a terminal */
    pm_progress_update(&pg, 1, 0.1); /* within 0.2 s of begin: nothing */
    char *t = contents(f);
    assert_string_equal(t, "");
    free(t);
    pg.last_print -= 0.25;
    pm_progress_update(&pg, 2, 0.2);
    pg.last_print -= 0.25;
    pm_progress_update(&pg, 3, 0.3);
    pm_progress_end(&pg, 10, 1.0);
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
    FILE *f = tmpfile();
    assert_non_null(f);
    pm_progress pg;
    pm_progress_begin(&pg, f, 1.0, 10, 1);
    pg.last_print -= 100;
    pm_progress_update(&pg, 5, 0.5);
    pm_progress_end(&pg, 10, 1.0);
    char *t = contents(f);
    assert_string_equal(t, "");
    free(t);
    fclose(f);
}

static void unknown_eta_before_time_advances(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    assert_non_null(f);
    pm_progress pg;
    pm_progress_begin(&pg, f, 1.0, 10, 0);
    pg.last_print -= 11;
    pm_progress_update(&pg, 0, 0.0);
    char *t = contents(f);
    assert_non_null(strstr(t, "0.0 %  ETA -:--:--  "));
    free(t);
    fclose(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(wall_clock_is_monotonic),
        cmocka_unit_test(log_lines_every_ten_seconds),
        cmocka_unit_test(terminal_redraws_one_line),
        cmocka_unit_test(quiet_prints_nothing),
        cmocka_unit_test(unknown_eta_before_time_advances),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
