/* The case loader: a full valid case gives the right values and defaults; every class of bad input
 * gives PM_EINPUT and one message naming the key path (or file:line:column), the value found and what
 * is allowed. Messages are matched by exact substrings, so a vaguer message fails the test. */
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

static const char *base =
    "{\n"
    "  \"title\": \"Dyka bar\",\n"
    "  \"dimension\": 2,\n"
    "  \"formulation\": \"plane_strain\",\n"
    "  \"method\": \"mpm\",\n"
    "  \"shape_function\": \"linear\",\n"
    "  \"analysis\": { \"type\": \"explicit\", \"scheme\": \"musl\", \"end_time\": 0.01, \"dt\": 1e-6, \"cfl\": 0.2,\n"
    "                \"gravity\": [0.0, -9.81], \"gravity_ramp_time\": 0.0, \"damping\": 0.0 },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0.0, 0.0], \"size\": [1.0, 0.1], \"cells\": [100, 10],\n"
    "            \"element\": \"quad4\" },\n"
    "  \"materials\": [ { \"name\": \"steel\", \"model\": \"linear_elastic\", \"density\": 7800,\n"
    "                   \"youngs_modulus\": 2.0e11, \"poisson_ratio\": 0.0 } ],\n"
    "  \"bodies\": [ { \"name\": \"bar\", \"material\": \"steel\",\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [0.0, 0.0], \"max\": [1.0, 0.1] },\n"
    "                \"particles_per_cell\": 2, \"velocity\": [-5.0, 0.0] } ],\n"
    "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"x_max\", \"directions\": [\"x\"] },\n"
    "                             { \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"y\"] } ],\n"
    "  \"output\": { \"directory\": \"out\", \"interval\": 1e-4 },\n"
    "  \"probes\": [ { \"name\": \"A\", \"point\": [0.0, 0.05], \"quantity\": \"velocity\" } ]\n"
    "}\n";

/* base with the first occurrence of `from` replaced by `to` */
static int load_edit(const char *from, const char *to, pm_case *c)
{
    char buf[8192];
    const char *at = strstr(base, from);
    assert_non_null(at);
    snprintf(buf, sizeof buf, "%.*s%s%s", (int)(at - base), base, to, at + strlen(from));
    return pm_case_load_buffer(buf, strlen(buf), "dir/case.json", c);
}

static void expect_error(const char *from, const char *to, const char *const *parts)
{
    pm_case c;
    int rc = load_edit(from, to, &c);
    const char *msg = pm_error_message();
    if (rc != PM_EINPUT)
        fail_msg("expected an input error for %s -> %s, got %d", from, to, rc);
    for (size_t k = 0; parts[k]; k++)
        if (!strstr(msg, parts[k]))
            fail_msg("message \"%s\" lacks \"%s\"", msg, parts[k]);
    pm_case_free(&c);
}

#define EXPECT(from, to, ...)                                  \
    do {                                                       \
        const char *const parts_[] = {__VA_ARGS__, NULL};      \
        expect_error(from, to, parts_);                        \
    } while (0)

static void valid_case_loads(void **st)
{
    (void)st;
    pm_case c;
    assert_int_equal(pm_case_load_buffer(base, strlen(base), "dir/case.json", &c), PM_OK);
    assert_string_equal(c.title, "Dyka bar");
    assert_string_equal(c.stem, "case");
    assert_string_equal(c.dir, "dir");
    assert_int_equal(c.analysis.type, PM_ANALYSIS_EXPLICIT);
    assert_int_equal(c.analysis.scheme, PM_SCHEME_MUSL);
    assert_true(c.analysis.dt == 1e-6 && c.analysis.gravity[1] == -9.81);
    assert_int_equal(c.grid.cells[0], 100);
    assert_int_equal(c.n_materials, 1);
    assert_true(c.materials[0].E == 2e11 && c.materials[0].density == 7800);
    assert_true(fabs(c.materials[0].G - 1e11) < 1);
    assert_int_equal(c.n_bodies, 1);
    assert_int_equal(c.bodies[0].material, 0);
    assert_true(c.bodies[0].velocity[0] == -5.0);
    assert_int_equal(c.n_bcs, 2);
    assert_int_equal(c.bcs[0].dirs, 1);
    assert_string_equal(c.bcs[1].boundary, "y_min");
    assert_int_equal(c.n_probes, 1);
    assert_int_equal(c.probes[0].body, -1);
    assert_string_equal(c.output.directory, "out");
    assert_true(c.analysis.newton.max_iterations == 25 && c.analysis.load_steps == 10);
    pm_case_free(&c);
}

static void defaults_apply(void **st)
{
    (void)st;
    pm_case c;
    assert_int_equal(load_edit("  \"output\": { \"directory\": \"out\", \"interval\": 1e-4 },\n", "", &c), PM_OK);
    assert_string_equal(c.output.directory, "case.out");
    assert_true(fabs(c.output.interval - 1e-4) < 1e-18);
    pm_case_free(&c);
    assert_int_equal(load_edit("\"dt\": 1e-6, \"cfl\": 0.2,", "", &c), PM_OK);
    assert_true(c.analysis.dt == 0 && c.analysis.cfl == 0.2);
    pm_case_free(&c);
}

static void syntax_error_names_line_and_column(void **st)
{
    (void)st;
    EXPECT("\"dimension\": 2,", "\"dimension\": 2", "dir/case.json:4:");
}

static void unknown_keys_suggest(void **st)
{
    (void)st;
    EXPECT("\"particles_per_cell\"", "\"particles_per_cel\"", "bodies[0].particles_per_cel", "unknown key",
           "did you mean 'particles_per_cell'");
    EXPECT("\"gravity\":", "\"gravty\":", "analysis.gravty", "did you mean 'gravity'");
    EXPECT("\"model\": \"linear_elastic\"", "\"model\": \"linear_elastc\"", "materials[0].model", "linear_elastc",
           "did you mean 'linear_elastic'", "mohr_coulomb");
    EXPECT("\"scheme\": \"musl\"", "\"scheme\": \"mulsl\"", "analysis.scheme", "did you mean 'musl'");
    EXPECT("\"boundary\": \"x_max\"", "\"boundary\": \"x_mx\"", "boundary_conditions[0].boundary", "x_mx",
           "did you mean 'x_max'");
}

static void missing_and_mistyped_keys_name_their_path(void **st)
{
    (void)st;
    EXPECT("\"end_time\": 0.01,", "", "analysis.end_time", "required key is missing");
    EXPECT("\"end_time\": 0.01", "\"end_time\": \"soon\"", "analysis.end_time", "expected a number", "\"soon\"");
    EXPECT("\"cells\": [100, 10]", "\"cells\": [100.5, 10]", "grid.cells", "two whole numbers");
    EXPECT("\"velocity\": [-5.0, 0.0]", "\"velocity\": [-5.0]", "bodies[0].velocity", "a list of 2 numbers");
}

static void physical_nonsense_is_refused(void **st)
{
    (void)st;
    EXPECT("\"youngs_modulus\": 2.0e11", "\"youngs_modulus\": -1", "materials[0].youngs_modulus", "-1", "> 0");
    EXPECT("\"poisson_ratio\": 0.0", "\"poisson_ratio\": 0.5", "materials[0].poisson_ratio", "0.5", "(-1, 0.5)");
    EXPECT("\"density\": 7800", "\"density\": 0", "materials[0].density", "got 0", "> 0");
    EXPECT("\"end_time\": 0.01", "\"end_time\": -2", "analysis.end_time", "got -2", "> 0");
    EXPECT("\"cfl\": 0.2", "\"cfl\": 1.5", "analysis.cfl", "got 1.5", "(0, 1]");
    EXPECT("\"damping\": 0.0", "\"damping\": 2", "analysis.damping", "[0, 1]");
    EXPECT("\"max\": [1.0, 0.1]", "\"max\": [1.5, 0.1]", "bodies[0].shape", "outside the grid");
    EXPECT("\"material\": \"steel\"", "\"material\": \"stel\"", "bodies[0].material", "\"stel\"", "steel");
    EXPECT("[ { \"name\": \"steel\", \"model\": \"linear_elastic\", \"density\": 7800,\n"
           "                   \"youngs_modulus\": 2.0e11, \"poisson_ratio\": 0.0 } ]",
           "[]", "materials", "empty");
    EXPECT("\"cells\": [100, 10]", "\"cells\": [100000000, 100000000]", "grid.cells", "particles", "GB");
    EXPECT("\"dimension\": 2", "\"dimension\": 3", "dimension", "3-D");
}

static void plastic_parameters_are_checked(void **st)
{
    (void)st;
    EXPECT("\"model\": \"linear_elastic\", \"density\": 7800,",
           "\"model\": \"mohr_coulomb\", \"cohesion\": 1e4, \"friction_angle\": 95, \"density\": 7800,",
           "materials[0].friction_angle", "95");
    EXPECT("\"model\": \"linear_elastic\", \"density\": 7800,",
           "\"model\": \"mohr_coulomb\", \"cohesion\": -1, \"friction_angle\": 30, \"density\": 7800,",
           "materials[0].cohesion", "-1");
    EXPECT("\"model\": \"linear_elastic\", \"density\": 7800,",
           "\"model\": \"mohr_coulomb\", \"cohesion\": 1, \"friction_angle\": 30, \"dilatancy_angle\": 40, "
           "\"density\": 7800,",
           "materials[0].dilatancy_angle", "40");
    EXPECT("\"model\": \"linear_elastic\", \"density\": 7800,",
           "\"model\": \"drucker_prager\", \"cohesion\": 1, \"friction_angle\": 30, \"cone_fit\": 2, "
           "\"density\": 7800,",
           "materials[0].cone_fit", "2");
}

static void line_boundaries_take_a_range_and_normal(void **st)
{
    (void)st;
    pm_case c;
    assert_int_equal(load_edit("{ \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"y\"] }",
                               "{ \"type\": \"friction\", \"boundary\": { \"y\": 0.0, \"from\": 0.2, \"normal\": [0, -2] },"
                               " \"coefficient\": 0.3 }",
                               &c),
                     PM_OK);
    assert_int_equal(c.bcs[1].line_axis, 1);
    assert_true(c.bcs[1].line_range[0] == 0.2 && isinf(c.bcs[1].line_range[1]));
    assert_true(c.bcs[1].line_normal[0] == 0.0 && c.bcs[1].line_normal[1] == -1.0);
    pm_case_free(&c);
    EXPECT("\"boundary\": \"y_min\"", "\"boundary\": { \"y\": 0, \"form\": 1 }", "boundary_conditions[1].boundary.form",
           "did you mean 'from'");
    EXPECT("\"boundary\": \"y_min\"", "\"boundary\": { \"y\": 0, \"from\": 1, \"to\": 0.5 }", "from = 1 must be below");
}

/* method and shape_function go together: gmm takes mls or lme, rkpm rk_cubic, mpm the grid kinds;
 * the default follows the method */
static void shape_function_follows_the_method(void **st)
{
    (void)st;
    EXPECT("\"method\": \"mpm\"", "\"method\": \"gmm\"", "shape_function", "\"linear\"", "'gmm'", "mls, lme");
    EXPECT("\"shape_function\": \"linear\"", "\"shape_function\": \"mls\"", "shape_function", "'mpm'", "linear");
    EXPECT("\"method\": \"mpm\",\n  \"shape_function\": \"linear\"",
           "\"method\": \"rkpm\",\n  \"shape_function\": \"lme\"", "'rkpm'", "rk_cubic");
    pm_case c;
    assert_int_equal(load_edit("\"method\": \"mpm\",\n  \"shape_function\": \"linear\",\n",
                               "\"method\": \"gmm\",\n", &c), PM_OK);
    assert_string_equal(c.shape_function, "mls");
    pm_case_free(&c);
    assert_int_equal(load_edit("\"method\": \"mpm\",\n  \"shape_function\": \"linear\",\n",
                               "\"method\": \"rkpm\",\n", &c), PM_OK);
    assert_string_equal(c.shape_function, "rk_cubic");
    pm_case_free(&c);
    /* the conditioning limit of the adaptive supports: absent means the approximation's default */
    assert_int_equal(load_edit("\"method\": \"mpm\",\n  \"shape_function\": \"linear\",\n",
                               "\"method\": \"gmm\",\n  \"max_condition\": 1e3,\n", &c), PM_OK);
    assert_true(c.max_condition == 1e3);
    pm_case_free(&c);
    assert_int_equal(load_edit("\"method\": \"mpm\",\n  \"shape_function\": \"linear\",\n",
                               "\"method\": \"gmm\",\n", &c), PM_OK);
    assert_true(isnan(c.max_condition));
    pm_case_free(&c);
    EXPECT("\"method\": \"mpm\",\n  \"shape_function\": \"linear\",\n",
           "\"method\": \"gmm\",\n  \"max_condition\": 0.5,\n", "max_condition", "0.5");
}

/* base with each pair {from, to} of @p edits replaced in turn (first occurrence) */
static int load_edits(const char *const *edits, pm_case *c)
{
    static char a[8192], b[8192];
    char *cur = a, *next = b;
    snprintf(cur, sizeof a, "%s", base);
    for (size_t k = 0; edits[k]; k += 2) {
        const char *at = strstr(cur, edits[k]);
        assert_non_null(at);
        snprintf(next, sizeof a, "%.*s%s%s", (int)(at - cur), cur, edits[k + 1], at + strlen(edits[k]));
        char *t = cur;
        cur = next;
        next = t;
    }
    return pm_case_load_buffer(cur, strlen(cur), "dir/case.json", c);
}

static const char *const explicit_head = "\"type\": \"explicit\", \"scheme\": \"musl\", \"end_time\": 0.01,";
static const char *const elastic_steel = "\"model\": \"linear_elastic\", \"density\": 7800,";
static const char *const mc_steel = "\"model\": \"mohr_coulomb\", \"cohesion\": 1e4, \"friction_angle\": 30, "
                                    "\"density\": 7800,";

/* a strength-reduction case: `head` replaces the analysis' type, scheme and end time, `material` the
 * steel's model; the message must hold every one of `parts` (none: the case must load) */
static void srf_case(const char *head, const char *material, const char *const *parts)
{
    const char *const edits[] = {explicit_head, head, elastic_steel, material, NULL};
    pm_case c;
    int rc = load_edits(edits, &c);
    if (!parts[0]) {
        if (rc != PM_OK)
            fail_msg("expected %s to load, got: %s", head, pm_error_message());
    } else {
        if (rc != PM_EINPUT)
            fail_msg("expected an input error for %s, got %d", head, rc);
        for (size_t k = 0; parts[k]; k++)
            if (!strstr(pm_error_message(), parts[k]))
                fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), parts[k]);
    }
    pm_case_free(&c);
}

#define SRF(head, material, ...)                               \
    do {                                                       \
        const char *const parts_[] = {__VA_ARGS__, NULL};      \
        srf_case(head, material, parts_);                      \
    } while (0)

static void strength_reduction_is_checked(void **st)
{
    (void)st;
    pm_case c;
    const char *const ok[] = {explicit_head,
                              "\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {},",
                              elastic_steel, mc_steel, NULL};
    assert_int_equal(load_edits(ok, &c), PM_OK);
    const pm_srf_opts *o = &c.analysis.strength_reduction;
    assert_true(o->enabled && o->min == 0.5 && o->max == 3.0 && o->tolerance == 0.01);
    assert_int_equal(o->criterion, PM_SRF_CONVERGENCE);
    pm_case_free(&c);
    const char *const dyn[] = {explicit_head, "\"type\": \"explicit\", \"end_time\": 1, \"strength_reduction\": {},",
                               "\"damping\": 0.0", "\"damping\": 0.1", elastic_steel, mc_steel, NULL};
    assert_int_equal(load_edits(dyn, &c), PM_OK);
    assert_int_equal(c.analysis.strength_reduction.criterion, PM_SRF_DISPLACEMENT);
    assert_true(c.analysis.strength_reduction.displacement_ratio == 10.0);
    pm_case_free(&c);
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {\"min\": 0.8, \"max\": 2.5, "
        "\"tolerance\": 0.005, \"criterion\": \"displacement\", \"displacement_ratio\": 4},",
        mc_steel, NULL);
    SRF("\"type\": \"implicit\", \"end_time\": 1, \"strength_reduction\": {},", mc_steel,
        "dir/case.json: analysis.strength_reduction:", "\"quasi_static\"", "got \"implicit\"");
    SRF("\"type\": \"explicit\", \"end_time\": 1, \"strength_reduction\": {},", mc_steel,
        "analysis.strength_reduction:", "damping > 0", "got damping = 0");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {\"min\": 2, \"max\": 1.5},",
        mc_steel, "analysis.strength_reduction: min = 2 must be below max = 1.5");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {\"min\": -1},", mc_steel,
        "analysis.strength_reduction.min: got -1", "> 0");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {\"tolerance\": 0},", mc_steel,
        "analysis.strength_reduction.tolerance: got 0", "[0.001, 2.5]");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {\"tolerence\": 0.1},", mc_steel,
        "analysis.strength_reduction.tolerence", "did you mean 'tolerance'");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {\"criterion\": \"newton\"},",
        mc_steel, "analysis.strength_reduction.criterion", "\"newton\"", "convergence, displacement");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {\"displacement_ratio\": 5},",
        mc_steel, "analysis.strength_reduction.displacement_ratio", "criterion \"displacement\" only");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": 3,", mc_steel,
        "analysis.strength_reduction: expected an object");
    SRF("\"type\": \"quasi_static\", \"end_time\": 1, \"strength_reduction\": {},", elastic_steel,
        "analysis.strength_reduction: no material has a strength to reduce", "\"steel\" is linear_elastic");
    const char *const conv[] = {explicit_head,
                                "\"type\": \"explicit\", \"end_time\": 1, \"strength_reduction\": "
                                "{\"criterion\": \"convergence\"},",
                                "\"damping\": 0.0", "\"damping\": 0.1", elastic_steel, mc_steel, NULL};
    assert_int_equal(load_edits(conv, &c), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "analysis.strength_reduction.criterion: got \"convergence\""));
    pm_case_free(&c);
}

static void never_crashes_on_truncations(void **st)
{
    (void)st;
    /* every prefix of a valid case is invalid input, never a crash */
    for (size_t n = 0; n + 2 < strlen(base); n += 7) {
        pm_case c;
        int rc = pm_case_load_buffer(base, n, "t.json", &c);
        assert_int_equal(rc, PM_EINPUT);
        pm_case_free(&c);
    }
}

static void driver_files_load(void **st)
{
    (void)st;
    const char *good = "{ \"material\": { \"model\": \"mohr_coulomb\", \"density\": 2000, \"youngs_modulus\": 2e7,"
                       " \"poisson_ratio\": 0.3, \"cohesion\": 1e4, \"friction_angle\": 30 },"
                       " \"path\": { \"type\": \"triaxial\", \"confining_pressure\": 1e5, \"axial_strain\": 0.05,"
                       " \"steps\": 500 } }";
    FILE *f = fopen("driver_test.json", "w");
    assert_non_null(f);
    fputs(good, f);
    fclose(f);
    pm_driver d;
    assert_int_equal(pm_driver_load("driver_test.json", &d), PM_OK);
    assert_int_equal(d.path, PM_PATH_TRIAXIAL);
    assert_int_equal(d.steps, 500);
    assert_true(d.stress0[0] == -1e5 && d.stress0[2] == -1e5);
    pm_driver_free(&d);
    f = fopen("driver_test.json", "w");
    fputs("{ \"material\": { \"model\": \"von_mises\", \"density\": 1, \"youngs_modulus\": 1, \"poisson_ratio\": 0.3,"
          " \"yield_stress\": 1 }, \"path\": { \"type\": \"triaxal\" } }", f);
    fclose(f);
    assert_int_equal(pm_driver_load("driver_test.json", &d), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "path.type"));
    assert_non_null(strstr(pm_error_message(), "did you mean 'triaxial'"));
    pm_driver_free(&d);
    remove("driver_test.json");
}

/* obstacles[]: kinds, velocity functions, and every bad value named by its key path */
static void obstacles_are_read_and_checked(void **st)
{
    (void)st;
    const char *at = "  \"output\": {";
    pm_case c;
    assert_int_equal(load_edit(at,
                               "  \"obstacles\": [ { \"type\": \"polyline\", \"points\": [[0, 0.1], [1, 0]],"
                               " \"friction\": 0.3, \"velocity\": [1, { \"table\": [[0, 0], [1, 2]] }] },"
                               " { \"name\": \"roller\", \"type\": \"circle\", \"center\": [0.5, 0.2], \"radius\": 0.1,"
                               " \"law\": \"penalty\", \"friction\": \"no_slip\" } ],\n  \"output\": {",
                               &c),
                     PM_OK);
    assert_int_equal(c.n_obstacles, 2);
    assert_string_equal(c.obstacles[0].name, "obstacle0");
    assert_true(c.obstacles[0].type == PM_OBSTACLE_POLYLINE && c.obstacles[0].n_points == 2);
    assert_true(c.obstacles[0].friction == 0.3 && c.obstacles[0].law == PM_OBSTACLE_NODAL);
    assert_true(c.obstacles[0].velocity[1].kind == PM_TIMEFN_TABLE && c.obstacles[0].velocity[1].n == 2);
    assert_true(isinf(c.obstacles[1].friction) && c.obstacles[1].law == PM_OBSTACLE_PENALTY);
    pm_case_free(&c);
    EXPECT(at, "  \"obstacles\": [ { \"type\": \"polyline\", \"points\": [[0, 0.1]] } ],\n  \"output\": {",
           "obstacles[0].points", "at least 2 points");
    EXPECT(at, "  \"obstacles\": [ { \"type\": \"circle\", \"center\": [5, 5], \"radius\": 0.1 } ],\n  \"output\": {",
           "obstacles[0]", "outside the grid");
    EXPECT(at,
           "  \"obstacles\": [ { \"type\": \"polyline\", \"points\": [[0, 0], [1, 0]], \"friction\": -0.1 } ],\n"
           "  \"output\": {",
           "obstacles[0].friction", "-0.1", "\"no_slip\"");
    EXPECT(at,
           "  \"obstacles\": [ { \"type\": \"polyline\", \"points\": [[0, 0], [1, 0]],"
           " \"velocity\": [0, { \"table\": [[0, 0], [2, 1], [1, 3]] }] } ],\n  \"output\": {",
           "obstacles[0].velocity[1].table[2]", "not after");
    EXPECT(at, "  \"obstacles\": [ { \"type\": \"square\" } ],\n  \"output\": {", "obstacles[0].type", "square");
    /* acting at the particles: the nodal law's; read, and refused with the penalty law */
    assert_int_equal(load_edit(at,
                               "  \"obstacles\": [ { \"type\": \"polyline\", \"points\": [[0, 0.1], [1, 0]],"
                               " \"acts_at\": \"particles\" } ],\n  \"output\": {",
                               &c),
                     PM_OK);
    assert_true(c.obstacles[0].at_particles == 1);
    pm_case_free(&c);
    EXPECT(at,
           "  \"obstacles\": [ { \"type\": \"polyline\", \"points\": [[0, 0], [1, 0]], \"law\": \"penalty\","
           " \"acts_at\": \"particles\" } ],\n  \"output\": {",
           "obstacles[0].acts_at", "needs law \"nodal\"");
    EXPECT(at,
           "  \"obstacles\": [ { \"type\": \"polyline\", \"points\": [[0, 0], [1, 0]], \"acts_at\": \"edges\" } ],\n"
           "  \"output\": {",
           "obstacles[0].acts_at", "edges");
    /* loads[]: one set, a force per component */
    EXPECT(at, "  \"loads\": [ { \"nearest\": [0, 0], \"min\": [0, 0], \"max\": [1, 1], \"force\": [0, 1] } ],\n"
           "  \"output\": {", "loads[0]", "either \"nearest\"");
    EXPECT(at, "  \"loads\": [ { \"nearest\": [0, 0], \"force\": [0, { \"value\": 1 }] } ],\n  \"output\": {",
           "loads[0].force[1].ramp_time", "missing");
    /* loads[] on a grid line: a force per length, the line's keys */
    assert_int_equal(load_edit(at,
                                 "  \"loads\": [ { \"grid_line\": { \"y\": 0.5, \"from\": 0.1 },"
                                 " \"force_per_length\": [0, -1000] } ],\n  \"output\": {",
                                 &c),
                     PM_OK);
    assert_true(c.loads[0].line_axis == 1 && c.loads[0].line_value == 0.5 && c.loads[0].line_range[0] == 0.1 &&
                isinf(c.loads[0].line_range[1]));
    pm_case_free(&c);
    EXPECT(at, "  \"loads\": [ { \"grid_line\": { \"y\": 0.5 }, \"force\": [0, 1] } ],\n  \"output\": {",
           "loads[0]", "\"force\" does not go with \"grid_line\"");
    EXPECT(at, "  \"loads\": [ { \"nearest\": [0, 0], \"force_per_length\": [0, 1] } ],\n  \"output\": {",
           "loads[0]", "goes with \"grid_line\"");
    EXPECT(at,
           "  \"loads\": [ { \"grid_line\": { \"x\": 0.5, \"y\": 0.5 }, \"force_per_length\": [0, 1] } ],\n"
           "  \"output\": {",
           "loads[0].grid_line", "exactly one");
    EXPECT(at,
           "  \"loads\": [ { \"grid_line\": { \"y\": 0.5, \"from\": 2, \"to\": 1 }, \"force_per_length\": [0, 1] } ],\n"
           "  \"output\": {",
           "loads[0].grid_line", "from = 2");
    EXPECT(at,
           "  \"loads\": [ { \"grid_line\": { \"y\": 0.5, \"normal\": [0, 1] }, \"force_per_length\": [0, 1] } ],\n"
           "  \"output\": {",
           "loads[0].grid_line", "normal");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(valid_case_loads),
        cmocka_unit_test(defaults_apply),
        cmocka_unit_test(syntax_error_names_line_and_column),
        cmocka_unit_test(unknown_keys_suggest),
        cmocka_unit_test(missing_and_mistyped_keys_name_their_path),
        cmocka_unit_test(physical_nonsense_is_refused),
        cmocka_unit_test(plastic_parameters_are_checked),
        cmocka_unit_test(line_boundaries_take_a_range_and_normal),
        cmocka_unit_test(shape_function_follows_the_method),
        cmocka_unit_test(strength_reduction_is_checked),
        cmocka_unit_test(never_crashes_on_truncations),
        cmocka_unit_test(driver_files_load),
        cmocka_unit_test(obstacles_are_read_and_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
