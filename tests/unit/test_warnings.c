/* Warnings for valid values that are almost surely mistakes (src/io/case_warnings.c,
 * src/solver/run_warnings.c): each rule fires on its value and names the key path and the value, a
 * sound case has none, and values just past each threshold do not warn. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "solver/run_warnings.h"

static const char *base =
    "{ \"dimension\": 2,\n"
    "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 1, \"gravity\": [0, -9.81] },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"size\": [2, 2], \"cells\": [4, 4] },\n"
    "  \"materials\": [ { \"name\": \"sand\", \"model\": \"mohr_coulomb\", \"density\": 1800,\n"
    "                   \"youngs_modulus\": 2e7, \"poisson_ratio\": 0.3, \"friction_angle\": 30,\n"
    "                   \"dilatancy_angle\": 0, \"cohesion\": 0 } ],\n"
    "  \"bodies\": [ { \"name\": \"layer\", \"material\": \"sand\", \"initial_stress\": \"geostatic\",\n"
    "                \"k0\": 0.5, \"surface_y\": 1,\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [0, 0], \"max\": [2, 1] } } ] }\n";

/* The warnings of base with one setting changed; *n receives their count. */
static void warnings_of(const char *path, const char *json, char (*w)[PM_WARNING_LEN], size_t *n)
{
    pm_case c;
    if (pm_case_load_buffer(base, strlen(base), "w.json", &c) != PM_OK)
        fail_msg("%s", pm_error_message());
    if (path && pm_case_set_json(&c, path, json) != PM_OK)
        fail_msg("%s", pm_error_message());
    *n = pm_case_warnings(&c, w, 8);
    pm_case_free(&c);
}

static void expect_one(const char *path, const char *json, const char *const *parts)
{
    char w[8][PM_WARNING_LEN];
    size_t n;
    warnings_of(path, json, w, &n);
    if (n != 1)
        fail_msg("%s = %s: %zu warnings, want 1", path, json, n);
    for (size_t k = 0; parts[k]; k++)
        if (!strstr(w[0], parts[k]))
            fail_msg("warning \"%s\" lacks \"%s\"", w[0], parts[k]);
}

static void expect_none(const char *path, const char *json)
{
    char w[8][PM_WARNING_LEN];
    size_t n;
    warnings_of(path, json, w, &n);
    if (n != 0)
        fail_msg("%s = %s: %zu warnings (%s), want none", path ? path : "base", json ? json : "", n, w[0]);
}

static void a_sound_case_has_none(void **state)
{
    (void)state;
    expect_none(NULL, NULL);
    expect_none("materials[0].youngs_modulus", "1000");  /* 1 kPa itself is allowed */
    expect_none("materials[0].friction_angle", "2");     /* 2 degrees */
    expect_none("materials[0].friction_angle", "0");     /* frictionless is a real choice */
    expect_none("analysis.gravity", "[9.81, 0]");        /* sideways gravity (a tilted frame) */
}

static void each_rule_fires(void **state)
{
    (void)state;
    expect_one("materials[0].youngs_modulus", "5",
               (const char *const[]){"materials[0].youngs_modulus", "5 Pa", "below 1 kPa", NULL});
    expect_one("materials[0].friction_angle", "0.5236",
               (const char *const[]){"materials[0].friction_angle", "0.5236", "radians", "30", NULL});
    expect_one("analysis.gravity", "[0, 9.81]", (const char *const[]){"analysis.gravity", "up", "bodies[0]", NULL});
    expect_one("analysis",
               "{\"type\": \"explicit\", \"end_time\": 1, \"gravity\": [0, -9.81], "
               "\"density_update\": \"positions\", \"apart_measure\": \"cell\"}",
               (const char *const[]){"analysis.apart_measure", "cell", "changes nothing", NULL});
    expect_one("materials[0]",
               "{\"name\": \"sand\", \"model\": \"mohr_coulomb\", \"density\": 1800, \"bulk_modulus\": 500, "
               "\"shear_modulus\": 300, \"friction_angle\": 30, \"cohesion\": 0}",
               (const char *const[]){"materials[0]", "bulk_modulus 500", "shear_modulus 300", "below 1 kPa", NULL});
}

/* apart_measure "cell" with a granular material: nothing to warn of when it sets max_void_ratio, one
 * warning naming that parameter when it does not (the positions then never loosen its state). */
static size_t granular_cell_warnings(const char *max_void_ratio, char (*w)[PM_WARNING_LEN])
{
    pm_case c;
    char mat[512];
    snprintf(mat, sizeof mat,
             "{\"name\": \"sand\", \"model\": \"granular\", \"density\": 1500, \"kappa\": 0.02, "
             "\"void_ratio\": 0.9, \"reference_pressure\": 600, \"poisson_ratio\": 0.3, \"friction_angle\": 30, "
             "\"viscosity\": 1e4, \"exponent\": 1%s%s}",
             max_void_ratio ? ", \"max_void_ratio\": " : "", max_void_ratio ? max_void_ratio : "");
    if (pm_case_load_buffer(base, strlen(base), "w.json", &c) != PM_OK ||
        pm_case_set_json(&c, "analysis",
                         "{\"type\": \"explicit\", \"end_time\": 1, \"gravity\": [0, -9.81], "
                         "\"density_update\": \"positions\", \"apart_measure\": \"cell\"}") != PM_OK ||
        pm_case_set_json(&c, "materials[0]", mat) != PM_OK)
        fail_msg("%s", pm_error_message());
    const size_t n = pm_case_warnings(&c, w, 8);
    pm_case_free(&c);
    return n;
}

static void cell_measure_needs_max_void_ratio(void **state)
{
    (void)state;
    char w[8][PM_WARNING_LEN];
    assert_int_equal(granular_cell_warnings("1.0", w), 0);
    assert_int_equal(granular_cell_warnings(NULL, w), 1);
    assert_non_null(strstr(w[0], "max_void_ratio"));
    assert_non_null(strstr(w[0], "changes nothing"));
}

/* The step-size warning: once, when a step falls below 1/100 of the first. */
static void a_collapsing_step_warns_once(void **state)
{
    (void)state;
    pm_case c;
    assert_int_equal(pm_case_load_buffer(base, strlen(base), "w.json", &c), PM_OK);
    pm_run_warnings w;
    pm_run_warnings_begin(&w, &c, 1);
    assert_int_equal(w.n, 0);
    pm_run_warnings_step(&w, 1, 1e-3, 1e-3);
    pm_run_warnings_step(&w, 2, 1.1e-3, 1e-4);
    pm_run_warnings_step(&w, 3, 1.10001e-3, 1.0001e-5); /* just above 1/100 */
    assert_int_equal(w.n, 0);
    pm_run_warnings_step(&w, 4, 1.10002e-3, 9e-6);
    pm_run_warnings_step(&w, 5, 1.10003e-3, 1e-7);
    assert_int_equal(w.n, 1);
    assert_non_null(strstr(w.msg[0], "step 4"));
    assert_non_null(strstr(w.msg[0], "1/100 of the first"));
    pm_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_sound_case_has_none),
        cmocka_unit_test(each_rule_fires),
        cmocka_unit_test(cell_measure_needs_max_void_ratio),
        cmocka_unit_test(a_collapsing_step_warns_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
