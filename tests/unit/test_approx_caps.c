/*
 * What the approximation registry says about its kinds without comparing names: which methods a
 * kind serves (and so the name lists a case file is checked against, with each method's default
 * first), whether it interpolates at the nodes, whether the linear-quad fast path applies; and
 * that the tables it answers from are the ones the created approximations carry.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "shape/approx_internal.h"
#include "pmech/case.h"
#include "pmech/error.h"
#include "shape/meshfree.h"

/* out[] equals the NULL-terminated want[]. */
static void names_equal(const char *const *out, size_t n, const char *const *want)
{
    size_t k = 0;
    for (; want[k]; k++) {
        assert_true(k < n);
        assert_string_equal(out[k], want[k]);
    }
    assert_int_equal(n, k);
    assert_null(out[k]);
}

static void names_per_method(void **unused)
{
    (void)unused;
    const char *out[16];
    names_equal(out, pm_approx_all_names(out, 16),
                (const char *const[]){"linear", "gimp", "bspline2", "lme", "mls", "rk_cubic", NULL});
    names_equal(out, pm_approx_names_for_method(PM_METHOD_MPM, out, 16),
                (const char *const[]){"linear", "gimp", "bspline2", "lme", NULL});
    names_equal(out, pm_approx_names_for_method(PM_METHOD_GMM, out, 16), (const char *const[]){"mls", "lme", NULL});
    names_equal(out, pm_approx_names_for_method(PM_METHOD_RKPM, out, 16), (const char *const[]){"rk_cubic", NULL});
    /* the grid kinds' own list is the mpm one */
    const char *const *grid = pm_approx_names();
    names_equal(grid, pm_approx_names_for_method(PM_METHOD_MPM, out, 16), (const char *const[]){"linear", "gimp",
                                                                                                "bspline2", "lme", NULL});
    /* unknown methods serve nothing; a short buffer is cut and still terminated */
    assert_int_equal(pm_approx_names_for_method(-1, out, 16), 0);
    assert_null(out[0]);
    assert_int_equal(pm_approx_names_for_method(7, out, 16), 0);
    assert_int_equal(pm_approx_names_for_method(PM_METHOD_MPM, out, 3), 2);
    assert_string_equal(out[1], "gimp");
    assert_null(out[2]);
    assert_int_equal(pm_approx_all_names(out, 1), 0);
    assert_null(out[0]);
    assert_int_equal(pm_approx_all_names(out, 0), 0);
}

static void serves(void **unused)
{
    (void)unused;
    assert_true(pm_approx_serves("linear", PM_METHOD_MPM));
    assert_true(pm_approx_serves("lme", PM_METHOD_MPM));
    assert_true(pm_approx_serves("lme", PM_METHOD_GMM));
    assert_false(pm_approx_serves("lme", PM_METHOD_RKPM));
    assert_true(pm_approx_serves("rk_cubic", PM_METHOD_RKPM));
    assert_false(pm_approx_serves("rk_cubic", PM_METHOD_GMM));
    assert_false(pm_approx_serves("mls", PM_METHOD_MPM));
    assert_false(pm_approx_serves("linear", PM_METHOD_GMM));
    assert_false(pm_approx_serves("bogus", PM_METHOD_MPM));
    assert_false(pm_approx_serves("linear", 5));
    assert_null(pm_approx_find(NULL, PM_METHOD_MPM));
    /* lme is two kinds, one per place its nodes live */
    assert_ptr_not_equal(pm_approx_find("lme", PM_METHOD_MPM), pm_approx_find("lme", PM_METHOD_GMM));
}

static void capability_flags(void **unused)
{
    (void)unused;
    struct { const char *name; int method, interpolating, fast; } want[] = {
        {"linear", PM_METHOD_MPM, 1, 1},  {"gimp", PM_METHOD_MPM, 0, 0}, {"bspline2", PM_METHOD_MPM, 0, 0},
        {"lme", PM_METHOD_MPM, 1, 0},     {"mls", PM_METHOD_GMM, 0, 0},  {"lme", PM_METHOD_GMM, 1, 0},
        {"rk_cubic", PM_METHOD_RKPM, 0, 0},
    };
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        const pm_approx_ops *ops = pm_approx_find(want[k].name, want[k].method);
        assert_non_null(ops);
        assert_string_equal(ops->name, want[k].name);
        assert_int_equal(ops->methods, 1u << want[k].method);
        assert_int_equal(ops->interpolating, want[k].interpolating);
        assert_int_equal(ops->linear_quad_fast, want[k].fast);
    }
}

/* The created approximations carry the tables the registry answers from. */
static void created_kinds_match(void **unused)
{
    (void)unused;
    pm_grid g;
    memset(&g, 0, sizeof g);
    assert_int_equal(pm_grid_rectangle(&g, (const double[]){0, 0}, (const double[]){4, 4}, (const int[]){4, 4},
                                       PM_QUAD4),
                     PM_OK);
    const char *grid[8];
    for (size_t k = 0, n = pm_approx_names_for_method(PM_METHOD_MPM, grid, 8); k < n; k++) {
        pm_approx *a;
        assert_int_equal(pm_approx_create(grid[k], &g, &a), PM_OK);
        assert_ptr_equal(a->ops, pm_approx_find(grid[k], PM_METHOD_MPM));
        assert_false(pm_approx_is_meshfree(a));
        pm_approx_destroy(a);
    }
    double x[2 * 25];
    for (int i = 0; i < 25; i++) {
        x[2 * i] = i % 5;
        x[2 * i + 1] = i / 5;
    }
    pm_cloud *cl;
    assert_int_equal(pm_cloud_create(25, x, NULL, NULL, &cl), PM_OK);
    const char *cloud[8];
    const int methods[] = {PM_METHOD_GMM, PM_METHOD_RKPM};
    for (int m = 0; m < 2; m++)
        for (size_t k = 0, n = pm_approx_names_for_method(methods[m], cloud, 8); k < n; k++) {
            pm_approx *a;
            assert_int_equal(pm_approx_create_cloud(cloud[k], cl, NULL, &a), PM_OK);
            assert_ptr_equal(a->ops, pm_approx_find(cloud[k], methods[m]));
            assert_true(pm_approx_is_meshfree(a));
            pm_approx_destroy(a);
        }
    pm_approx *a = NULL;
    assert_int_equal(pm_approx_create_cloud("linear", cl, NULL, &a), PM_EINPUT);
    assert_null(a);
    assert_non_null(strstr(pm_error_message(), "available: mls, lme, rk_cubic"));
    assert_int_equal(pm_approx_create("mls", &g, &a), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "available: linear, gimp, bspline2, lme"));
    pm_cloud_destroy(cl);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(names_per_method),
        cmocka_unit_test(serves),
        cmocka_unit_test(capability_flags),
        cmocka_unit_test(created_kinds_match),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
