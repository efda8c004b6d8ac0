/* The loader's checks of sources and sinks: each bad value is refused with the key path and what is
 * allowed, and the same case with the value corrected loads, so the refusal is the check's own. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"

/* %s: method, analysis type, the bodies list, then the sources and the sinks (each a JSON list). */
static const char *tmpl =
    "{ \"dimension\": 2, \"method\": \"%s\",\n"
    "  \"analysis\": { \"type\": \"%s\", \"end_time\": 1.0 },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 2], \"cells\": [4, 8] },\n"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
    "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
    "  %s\n"
    "  \"sources\": %s, \"sinks\": %s }\n";

static const char *one_body = "\"bodies\": [ { \"name\": \"fill\", \"material\": \"m\", \"shape\": { \"type\": "
                              "\"rectangle\", \"min\": [0, 0], \"max\": [1, 0.5] } } ],";

#define SRC(extra) "[ { \"name\": \"hopper\", \"material\": \"m\", \"shape\": { \"type\": \"rectangle\", " \
                   "\"min\": [0, 1.5], \"max\": [1, 2] }, " extra " } ]"

static int load_full(const char *method, const char *type, const char *bodies, const char *sources,
                     const char *sinks, pm_case *keep)
{
    char buf[8192];
    snprintf(buf, sizeof buf, tmpl, method, type, bodies, sources, sinks);
    pm_case c;
    int rc = pm_case_load_buffer(buf, strlen(buf), "case.json", &c);
    if (keep)
        *keep = c;
    else
        pm_case_free(&c);
    return rc;
}

static int load(const char *sources, const char *sinks)
{
    return load_full("mpm", "explicit", one_body, sources, sinks, NULL);
}

static void expect_refused(const char *sources, const char *sinks, const char *part)
{
    int rc = load(sources, sinks);
    if (rc != PM_EINPUT)
        fail_msg("sources %s, sinks %s: expected an input error, got %d", sources, sinks, rc);
    if (!strstr(pm_error_message(), part))
        fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), part);
}

static void schedules_load(void **state)
{
    (void)state;
    pm_case c;
    assert_int_equal(load_full("mpm", "explicit", one_body, SRC("\"period\": 0.25, \"start\": 0.1"), "[]", &c), PM_OK);
    assert_int_equal(c.n_sources, 1);
    assert_int_equal(c.n_bodies, 1);
    /* 0.1, 0.35, 0.6, 0.85: the fifth (1.1) is after end_time */
    assert_int_equal(pm_case_source_releases(&c, 0), 4);
    assert_true(fabs(pm_case_source_release_time(&c, 0, 3) - 0.85) < 1e-12);
    assert_true(c.sources[0].until == 1.0);
    pm_case_free(&c);
    assert_int_equal(load_full("mpm", "explicit", one_body, SRC("\"times\": [0, 0.5, 2]"), "[]", &c), PM_OK);
    assert_int_equal(pm_case_source_releases(&c, 0), 2);
    pm_case_free(&c);
    /* a bin filled only by a source needs no body */
    assert_int_equal(load_full("mpm", "explicit", "", SRC("\"period\": 0.5"), "[]", &c), PM_OK);
    assert_int_equal(c.n_bodies, 0);
    assert_int_equal(pm_case_source_releases(&c, 0), 3);
    pm_case_free(&c);
    assert_int_equal(load_full("mpm", "explicit", "\"bodies\": [],", SRC("\"period\": 0.5"), "[]", NULL), PM_OK);
    assert_int_equal(load_full("mpm", "explicit", "", "[]", "[]", NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "case.json: bodies: required key is missing"));
    assert_int_equal(load_full("mpm", "explicit", "\"bodies\": [],", "[]", "[]", NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "case.json: bodies: expected a non-empty list"));
}

static void bad_schedules_refused(void **state)
{
    (void)state;
    expect_refused(SRC("\"period\": 0"), "[]", "case.json: sources[0].period: got 0; allowed: > 0");
    expect_refused(SRC("\"period\": -1"), "[]", "sources[0].period: got -1");
    expect_refused(SRC("\"velocity\": [0, -1]"), "[]", "sources[0]: give exactly one of \"times\"");
    expect_refused(SRC("\"period\": 0.1, \"times\": [0]"), "[]", "sources[0]: give exactly one of");
    expect_refused(SRC("\"times\": [0, 0.5, 0.5]"), "[]", "sources[0].times[2] = 0.5: the times must increase");
    expect_refused(SRC("\"times\": [-0.1]"), "[]", "sources[0].times[0]: got -0.1");
    expect_refused(SRC("\"times\": []"), "[]", "sources[0].times: expected a non-empty list");
    expect_refused(SRC("\"times\": [0], \"start\": 0"), "[]", "\"start\" and \"until\" go with \"period\"");
    expect_refused(SRC("\"period\": 0.1, \"start\": 0.5, \"until\": 0.2"), "[]", "sources[0].until: got 0.2");
    expect_refused(SRC("\"period\": 0.1, \"start\": 3"), "[]", "the first release, at t = 3 s, comes after");
    expect_refused(SRC("\"period\": 0.1, \"only_when_free\": 1"), "[]", "sources[0].only_when_free");
    expect_refused(SRC("\"period\": 0.1, \"perod\": 1"), "[]", "did you mean 'period'");
    assert_int_equal(load(SRC("\"period\": 0.1, \"only_when_free\": true"), "[]"), PM_OK);
}

static void bad_sources_refused(void **state)
{
    (void)state;
    const char *outside = "[ { \"material\": \"m\", \"period\": 0.5, \"shape\": { \"type\": \"rectangle\", "
                          "\"min\": [0.5, 1.5], \"max\": [1.5, 2] } } ]";
    expect_refused(outside, "[]", "case.json: sources[0].shape: the source spans [0.5, 1.5] x [1.5, 2], outside the "
                   "grid");
    const char *unknown = "[ { \"material\": \"sand\", \"period\": 0.5, \"shape\": { \"type\": \"rectangle\", "
                          "\"min\": [0, 1.5], \"max\": [1, 2] } } ]";
    expect_refused(unknown, "[]", "sources[0].material: no material is named \"sand\"");
    const char *named_as_body = "[ { \"name\": \"fill\", \"material\": \"m\", \"period\": 0.5, \"shape\": { \"type\": "
                                "\"rectangle\", \"min\": [0, 1.5], \"max\": [1, 2] } } ]";
    expect_refused(named_as_body, "[]", "bodies[0].name: \"fill\" is already the name of sources[0]");
    const char *comma = "[ { \"name\": \"a,b\", \"material\": \"m\", \"period\": 0.5, \"shape\": { \"type\": "
                        "\"rectangle\", \"min\": [0, 1.5], \"max\": [1, 2] } } ]";
    expect_refused(comma, "[]", "sources[0].name: \"a,b\" has a comma");
    expect_refused("{}", "[]", "sources: expected a list");
}

static void methods_refused(void **state)
{
    (void)state;
    const char *src = SRC("\"period\": 0.5");
    const char *out = "[ { \"type\": \"outlet\", \"boundary\": \"y_min\" } ]";
    assert_int_equal(load_full("gmm", "explicit", one_body, src, "[]", NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "sources: particles can be added and removed only with method 'mpm'"));
    assert_int_equal(load_full("rkpm", "explicit", one_body, "[]", out, NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "sinks: particles can be added and removed only with method 'mpm'"));
    assert_int_equal(load_full("mpm", "implicit", one_body, src, "[]", NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "only in 'explicit' analyses"));
    assert_int_equal(load_full("mpm", "quasi_static", one_body, "[]", out, NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "only in 'explicit' analyses"));
    /* empty lists ask for nothing */
    assert_int_equal(load_full("gmm", "implicit", one_body, "[]", "[]", NULL), PM_OK);
}

static void sinks_load(void **state)
{
    (void)state;
    pm_case c;
    const char *sinks = "[ { \"type\": \"outlet\", \"name\": \"hole\", \"boundary\": { \"y\": 0, \"from\": 0.4, \"to\": "
                        "0.6, \"normal\": [0, -3] } }, { \"type\": \"region\", \"shape\": { \"type\": \"circle\", "
                        "\"center\": [0.5, 1], \"radius\": 0.1 } }, { \"type\": \"outside_grid\" }, "
                        "{ \"type\": \"outlet\", \"boundary\": \"x_max\" } ]";
    assert_int_equal(load_full("mpm", "explicit", one_body, "[]", sinks, &c), PM_OK);
    assert_int_equal(c.n_sinks, 4);
    assert_int_equal(c.sinks[0].type, PM_SINK_OUTLET);
    assert_string_equal(c.sinks[0].name, "hole");
    assert_int_equal(c.sinks[0].axis, 1);
    assert_true(c.sinks[0].range[0] == 0.4 && c.sinks[0].range[1] == 0.6);
    assert_true(c.sinks[0].normal[0] == 0 && c.sinks[0].normal[1] == -1);
    assert_int_equal(c.sinks[1].type, PM_SINK_REGION);
    assert_string_equal(c.sinks[1].name, "sink1");
    assert_int_equal(c.sinks[2].type, PM_SINK_OUTSIDE_GRID);
    assert_string_equal(c.sinks[3].side, "x_max");
    pm_case_free(&c);
}

static void bad_sinks_refused(void **state)
{
    (void)state;
    expect_refused("[]", "[ { \"type\": \"drain\" } ]", "sinks[0].type");
    expect_refused("[]", "[ { \"type\": \"outlet\" } ]", "case.json: sinks[0].boundary: required key is missing");
    expect_refused("[]", "[ { \"type\": \"outlet\", \"boundary\": \"y_mni\" } ]", "did you mean 'y_min'");
    expect_refused("[]", "[ { \"type\": \"outlet\", \"boundary\": { \"y\": -1 } } ]",
                   "sinks[0].boundary: the outlet y = -1 from -inf to inf misses the grid");
    expect_refused("[]", "[ { \"type\": \"outlet\", \"boundary\": { \"y\": 0, \"from\": 2, \"to\": 3 } } ]",
                   "misses the grid");
    expect_refused("[]", "[ { \"type\": \"outlet\", \"boundary\": { \"y\": 0, \"from\": 0.6, \"to\": 0.4 } } ]",
                   "from = 0.6 must be below to = 0.4");
    expect_refused("[]", "[ { \"type\": \"outlet\", \"boundary\": { \"y\": 0, \"normal\": [1, 0] } } ]",
                   "sinks[0].boundary.normal: [1, 0]: must be along the y axis");
    expect_refused("[]", "[ { \"type\": \"outlet\", \"boundary\": { \"x\": 0, \"y\": 0 } } ]",
                   "expected exactly one of \"x\" or \"y\"");
    expect_refused("[]", "[ { \"type\": \"region\" } ]", "sinks[0].shape: required key is missing");
    expect_refused("[]", "[ { \"type\": \"region\", \"boundary\": \"y_min\", \"shape\": { \"type\": \"circle\", "
                   "\"center\": [0, 0], \"radius\": 1 } } ]", "sinks[0].boundary: unknown key (allowed here: type, name, shape)");
    expect_refused("[]", "[ { \"type\": \"outside_grid\" }, { \"type\": \"outside_grid\" } ]",
                   "sinks[1].type: sinks[0] is already of type 'outside_grid'");
    expect_refused("[]", "[ { \"type\": \"outside_grid\", \"name\": \"a\" }, { \"type\": \"region\", \"name\": \"a\", "
                   "\"shape\": { \"type\": \"circle\", \"center\": [0, 0], \"radius\": 1 } } ]",
                   "sinks[1].name: \"a\" is already the name of sinks[0]");
    expect_refused("[]", "5", "sinks: expected a list");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(schedules_load),       cmocka_unit_test(bad_schedules_refused),
        cmocka_unit_test(bad_sources_refused),  cmocka_unit_test(methods_refused),
        cmocka_unit_test(sinks_load),           cmocka_unit_test(bad_sinks_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
