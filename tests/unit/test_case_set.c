/* Changing a case by key path (pm_case_set and friends): a value set from C is the value a case file
 * with that value gives (the same material parameters, derived constants included), a refused value
 * gives the case file's message and leaves the case as it was, and paths that name nothing say so. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"

static const char *base =
    "{\n"
    "  \"title\": \"slope\", \"dimension\": 2,\n"
    "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 0.5, \"gravity\": [0.0, -9.81] },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0.0, 0.0], \"size\": [4.0, 2.0], \"cells\": [8, 4] },\n"
    "  \"materials\": [ { \"name\": \"soil\", \"model\": \"mohr_coulomb\", \"density\": 2000,\n"
    "                   \"youngs_modulus\": 1.0e7, \"poisson_ratio\": 0.3, \"friction_angle\": 20,\n"
    "                   \"cohesion\": 1000 } ],\n"
    "  \"bodies\": [ { \"name\": \"soil\", \"material\": \"soil\",\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [0.0, 0.0], \"max\": [2.0, 1.0] } } ],\n"
    "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"x\", \"y\"] } ]\n"
    "}\n";

static void load(pm_case *c, const char *from, const char *to)
{
    char buf[4096];
    const char *at = from ? strstr(base, from) : NULL;
    if (from)
        assert_non_null(at);
    if (at)
        snprintf(buf, sizeof buf, "%.*s%s%s", (int)(at - base), base, to, at + strlen(from));
    else
        snprintf(buf, sizeof buf, "%s", base);
    if (pm_case_load_buffer(buf, strlen(buf), "dir/case.json", c) != PM_OK)
        fail_msg("%s", pm_error_message());
}

static void expect_message(int rc, const char *const *parts)
{
    assert_int_equal(rc, PM_EINPUT);
    for (size_t k = 0; parts[k]; k++)
        if (!strstr(pm_error_message(), parts[k]))
            fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), parts[k]);
}

/* Setting friction_angle to 30 gives exactly the material of a file that says 30: every parameter and
 * every derived constant the model's init computes from it. */
static void a_set_value_is_the_file_value(void **state)
{
    (void)state;
    pm_case c, ref;
    load(&c, NULL, NULL);
    load(&ref, "\"friction_angle\": 20", "\"friction_angle\": 30");
    assert_int_equal(pm_case_set(&c, "materials[0].friction_angle", 30), PM_OK);
    assert_memory_equal(c.materials[0].param, ref.materials[0].param, sizeof c.materials[0].param);
    assert_memory_equal(c.materials[0].derived, ref.materials[0].derived, sizeof c.materials[0].derived);
    double phi = 0;
    assert_int_equal(pm_case_get(&c, "materials[0].friction_angle", &phi), PM_OK);
    assert_true(phi == 30);
    /* a list entry, a string and a JSON value */
    assert_int_equal(pm_case_set(&c, "analysis.gravity[1]", -5), PM_OK);
    assert_true(c.analysis.gravity[1] == -5 && c.analysis.gravity[0] == 0);
    assert_int_equal(pm_case_set_string(&c, "analysis.scheme", "usl"), PM_OK);
    assert_int_equal(c.analysis.scheme, PM_SCHEME_USL);
    assert_int_equal(pm_case_set_json(&c, "grid.cells", "[16, 8]"), PM_OK);
    assert_int_equal(c.grid.cells[0], 16);
    assert_int_equal(c.grid.cells[1], 8);
    /* a key the file did not have, in an object it did not have */
    assert_int_equal(pm_case_set(&c, "output.interval", 0.05), PM_OK);
    assert_true(c.output.interval == 0.05);
    pm_case_free(&c);
    pm_case_free(&ref);
}

/* A refused value: the case file's message, and the case keeps its old value. */
static void a_refused_value_leaves_the_case(void **state)
{
    (void)state;
    pm_case c;
    load(&c, NULL, NULL);
    const double before = c.materials[0].param[pm_material_param_index(c.materials[0].ops, "friction_angle")];
    expect_message(pm_case_set(&c, "materials[0].friction_angle", 95),
                   (const char *const[]){"dir/case.json", "materials[0].friction_angle", "95", NULL});
    assert_true(c.materials[0].param[pm_material_param_index(c.materials[0].ops, "friction_angle")] == before);
    expect_message(pm_case_set(&c, "materials[0].friction_angel", 30),
                   (const char *const[]){"materials[0]", "friction_angel", "friction_angle", NULL});
    expect_message(pm_case_set_string(&c, "analysis.scheme", "usx"),
                   (const char *const[]){"analysis.scheme", "usx", NULL});
    expect_message(pm_case_set(&c, "grid.cells[0]", 2.5), (const char *const[]){"grid.cells", NULL});
    /* a cross-check between sections: the body must lie in the grid */
    expect_message(pm_case_set(&c, "bodies[0].shape.max[0]", 9), (const char *const[]){"bodies[0]", NULL});
    assert_true(c.bodies[0].shape.max[0] == 2.0);
    expect_message(pm_case_set(&c, "analysis.end_time", NAN), (const char *const[]){"finite", NULL});
    expect_message(pm_case_set_json(&c, "analysis.gravity", "[0, "), (const char *const[]){"not JSON", NULL});
    pm_case_free(&c);
}

/* Paths that name nothing, or are not paths. */
static void paths_that_name_nothing(void **state)
{
    (void)state;
    pm_case c;
    load(&c, NULL, NULL);
    expect_message(pm_case_set(&c, "materials[3].cohesion", 1), (const char *const[]){"materials[3]", "has 1 entry", NULL});
    expect_message(pm_case_set(&c, "analysis.end_time.x", 1), (const char *const[]){"analysis.end_time", "not an object", NULL});
    expect_message(pm_case_set(&c, "materials..x", 1), (const char *const[]){"not a key path", NULL});
    expect_message(pm_case_set(&c, "materials[x]", 1), (const char *const[]){"not a key path", NULL});
    expect_message(pm_case_set(&c, "", 1), (const char *const[]){"empty key path", NULL});
    double v;
    expect_message(pm_case_get(&c, "analysis.dt", &v), (const char *const[]){"analysis.dt", "no such key", NULL});
    expect_message(pm_case_get(&c, "title", &v), (const char *const[]){"not a number", NULL});
    /* a case built by hand has no document */
    pm_case hand;
    memset(&hand, 0, sizeof hand);
    expect_message(pm_case_set(&hand, "analysis.dt", 1), (const char *const[]){"not loaded from a file", NULL});
    pm_case_free(&c);
}

/* Removing an optional key restores its default; a list entry can be appended and removed; the whole
 * document reads back as JSON that loads to the same case. */
static void remove_append_and_save(void **state)
{
    (void)state;
    pm_case c;
    load(&c, "\"end_time\": 0.5", "\"end_time\": 0.5, \"dt\": 1e-4");
    assert_true(c.analysis.dt == 1e-4);
    assert_int_equal(pm_case_remove(&c, "analysis.dt"), PM_OK);
    assert_true(c.analysis.dt == 0);
    expect_message(pm_case_remove(&c, "analysis.end_time"), (const char *const[]){"analysis.end_time", NULL});
    assert_true(c.analysis.end_time == 0.5);
    assert_int_equal(pm_case_set_json(&c, "boundary_conditions[1]",
                                      "{\"type\": \"fixed\", \"boundary\": \"x_min\", \"directions\": [\"x\"]}"),
                     PM_OK);
    assert_int_equal(c.n_bcs, 2);
    assert_int_equal(pm_case_remove(&c, "boundary_conditions[1]"), PM_OK);
    assert_int_equal(c.n_bcs, 1);
    assert_int_equal(pm_case_set(&c, "materials[0].cohesion", 2500), PM_OK);
    char *text = pm_case_get_json(&c, "");
    assert_non_null(text);
    pm_case again;
    assert_int_equal(pm_case_load_buffer(text, strlen(text), "dir/case.json", &again), PM_OK);
    assert_memory_equal(again.materials[0].param, c.materials[0].param, sizeof c.materials[0].param);
    free(text);
    text = pm_case_get_json(&c, "analysis.gravity");
    assert_non_null(text);
    assert_non_null(strstr(text, "-9.81"));
    free(text);
    pm_case_free(&again);
    pm_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_set_value_is_the_file_value),
        cmocka_unit_test(a_refused_value_leaves_the_case),
        cmocka_unit_test(paths_that_name_nothing),
        cmocka_unit_test(remove_append_and_save),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
