/* Functions of time (pmech/timefn.h): values and exact integrals of a constant, a ramp and a table. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "pmech/timefn.h"

#define NEAR(a, b) assert_true(fabs((a) - (b)) <= 1e-12 * (1 + fabs(b)))

static void constant_and_ramp(void **st)
{
    (void)st;
    pm_timefn c = {PM_TIMEFN_CONSTANT, 2.5, 0, 0, NULL, NULL};
    NEAR(pm_timefn_value(&c, 7.0), 2.5);
    NEAR(pm_timefn_integral(&c, 4.0), 10.0);
    NEAR(pm_timefn_integral(&c, -1.0), 0.0);
    pm_timefn r = {PM_TIMEFN_RAMP, 3.0, 2.0, 0, NULL, NULL};
    NEAR(pm_timefn_value(&r, 0.0), 0.0);
    NEAR(pm_timefn_value(&r, 1.0), 1.5);
    NEAR(pm_timefn_value(&r, 5.0), 3.0);
    NEAR(pm_timefn_integral(&r, 1.0), 0.75);      /* 1/2 * 1 * 1.5 */
    NEAR(pm_timefn_integral(&r, 4.0), 3.0 + 6.0); /* the ramp's triangle, then 3 for 2 s */
}

static void table_values_and_integral(void **st)
{
    (void)st;
    double t[] = {1.0, 2.0, 4.0}, v[] = {0.0, 2.0, -2.0};
    pm_timefn f = {PM_TIMEFN_TABLE, 0, 0, 3, t, v};
    NEAR(pm_timefn_value(&f, 0.5), 0.0); /* held before the first point */
    NEAR(pm_timefn_value(&f, 1.5), 1.0);
    NEAR(pm_timefn_value(&f, 3.0), 0.0);
    NEAR(pm_timefn_value(&f, 9.0), -2.0); /* held after the last */
    /* areas: [0, 1] 0; [1, 2] 1; [2, 4] 0; [4, 5] -2 */
    NEAR(pm_timefn_integral(&f, 1.5), 0.25);
    NEAR(pm_timefn_integral(&f, 2.0), 1.0);
    NEAR(pm_timefn_integral(&f, 3.0), 1.0 + 0.5 * (2.0 + 0.0));
    NEAR(pm_timefn_integral(&f, 5.0), 1.0 + 0.0 - 2.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(constant_and_ramp),
        cmocka_unit_test(table_values_and_integral),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
