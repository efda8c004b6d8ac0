/* Cases the solver cannot run are refused by the loader, with the key path, before any run starts:
 * a friction condition in an implicit or quasi-static analysis, and density_update "positions" with a
 * meshfree method. The same cases with the setting that makes them valid load, so the refusal is
 * the check's and not another error's. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"

/* A small valid case; %s are the method, the analysis type, density_update and the second condition. */
static const char *tmpl =
    "{ \"dimension\": 2, \"method\": \"%s\",\n"
    "  \"analysis\": { \"type\": \"%s\", \"end_time\": 0.01, \"density_update\": \"%s\" },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [4, 4] },\n"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
    "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
    "  \"bodies\": [ { \"material\": \"m\",\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [0, 0], \"max\": [1, 0.5] } } ],\n"
    "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"x_min\", \"directions\": [\"x\"] }, %s ] }\n";

static const char *friction = "{ \"type\": \"friction\", \"boundary\": \"y_min\", \"coefficient\": 0.3 }";
static const char *fixed = "{ \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"y\"] }";

static int load(const char *method, const char *type, const char *density, const char *bc)
{
    char buf[4096];
    snprintf(buf, sizeof buf, tmpl, method, type, density, bc);
    pm_case c;
    int rc = pm_case_load_buffer(buf, strlen(buf), "case.json", &c);
    pm_case_free(&c);
    return rc;
}

static void expect_refused(const char *method, const char *type, const char *density, const char *bc,
                           const char *part)
{
    int rc = load(method, type, density, bc);
    if (rc != PM_EINPUT)
        fail_msg("%s/%s/%s: expected an input error, got %d", method, type, density, rc);
    if (!strstr(pm_error_message(), part))
        fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), part);
}

static void friction_in_every_analysis(void **state)
{
    (void)state;
    assert_int_equal(load("mpm", "implicit", "deformation", friction), PM_OK);
    assert_int_equal(load("mpm", "quasi_static", "deformation", friction), PM_OK);
    assert_int_equal(load("mpm", "explicit", "deformation", friction), PM_OK);
    assert_int_equal(load("mpm", "implicit", "deformation", fixed), PM_OK);
}

static void positions_need_mpm(void **state)
{
    (void)state;
    const char *msg = "case.json: analysis.density_update: \"positions\" needs the cells of method 'mpm'";
    expect_refused("gmm", "explicit", "positions", fixed, msg);
    expect_refused("rkpm", "explicit", "positions", fixed, msg);
    assert_int_equal(load("mpm", "explicit", "positions", fixed), PM_OK);
    assert_int_equal(load("gmm", "explicit", "deformation", fixed), PM_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(friction_in_every_analysis),
        cmocka_unit_test(positions_need_mpm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
