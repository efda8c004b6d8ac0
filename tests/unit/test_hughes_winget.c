/* The planar fast path of pm_hughes_winget agrees with the general 3x3 path (to 1e-13 relative:
 * the same formulas in another order), and a rigid rotation rotates the stress exactly. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "pmech/material.h"

static void planar_matches_general(void **state)
{
    (void)state;
    const double f[9] = {1.013, 0.021, 0, -0.034, 0.991, 0, 0, 0, 1.002};
    double g[9];
    for (int i = 0; i < 9; i++)
        g[i] = f[i];
    g[2] = 1e-300; /* not exactly planar: takes the general path, same result to round-off */
    double s1[6] = {-1e5, -2e5, -1.5e5, 3e4, 0, 0}, s2[6] = {-1e5, -2e5, -1.5e5, 3e4, 0, 0};
    double d1[6], d2[6];
    pm_hughes_winget(f, s1, d1);
    pm_hughes_winget(g, s2, d2);
    for (int i = 0; i < 6; i++) {
        assert_true(fabs(s1[i] - s2[i]) <= 1e-13 * 2e5);
        assert_true(fabs(d1[i] - d2[i]) <= 1e-13);
    }
}

static void rigid_rotation_is_exact(void **state)
{
    (void)state;
    const double th = 0.3;
    const double f[9] = {cos(th), -sin(th), 0, sin(th), cos(th), 0, 0, 0, 1};
    double s[6] = {-1e5, 2e4, -3e4, 5e4, 0, 0}, d[6];
    const double sxx = s[0], syy = s[1], sxy = s[3];
    pm_hughes_winget(f, s, d);
    const double c = cos(th), sn = sin(th);
    /* sigma' = R sigma R^T with R = f */
    const double exx = c * c * sxx - 2 * c * sn * sxy + sn * sn * syy;
    const double eyy = sn * sn * sxx + 2 * c * sn * sxy + c * c * syy;
    const double exy = c * sn * (sxx - syy) + (c * c - sn * sn) * sxy;
    assert_true(fabs(s[0] - exx) < 1e-9 && fabs(s[1] - eyy) < 1e-9 && fabs(s[3] - exy) < 1e-9);
    assert_true(fabs(s[2] + 3e4) < 1e-9);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(d[i]) < 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(planar_matches_general),
        cmocka_unit_test(rigid_rotation_is_exact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
