/*
 * Body-body contact (contact_pairs, src/contact/multibody*.c): the loader refuses bad pairs with the
 * key path and what is allowed (and loads the corrected case, so the refusal is the check's own);
 * bodies of one contact_group share a field; a no_slip pair moves the particles as a single field
 * does, to round-off, in every explicit scheme; frictionless contact between two free bodies keeps
 * the total momentum to round-off.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/multibody.h"
#include "pmech/case.h"
#include "pmech/error.h"
#include "solver/sim_internal.h"

/* %s: method, analysis type, analysis extras, the bodies' extra keys (block, disk), contact_pairs. */
static const char *tmpl =
    "{ \"dimension\": 2, \"method\": \"%s\",\n"
    "  \"analysis\": { \"type\": \"%s\", \"end_time\": 0.01, \"gravity\": [0, 0] %s },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [10, 10] },\n"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
    "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
    "  \"bodies\": [ { \"name\": \"block\", \"material\": \"m\", \"velocity\": [2, 1], %s\n"
    "                  \"shape\": { \"type\": \"rectangle\", \"min\": [0.2, 0.2], \"max\": [0.5, 0.5] } },\n"
    "                { \"name\": \"disk\", \"material\": \"m\", \"velocity\": [-2, 0], %s\n"
    "                  \"shape\": { \"type\": \"circle\", \"center\": [0.7, 0.45], \"radius\": 0.15 } },\n"
    "                { \"name\": \"rest\", \"material\": \"m\",\n"
    "                  \"shape\": { \"type\": \"rectangle\", \"min\": [0.0, 0.8], \"max\": [0.2, 1.0] } } ],\n"
    "  \"contact_pairs\": %s }\n";

static int load_full(const char *method, const char *type, const char *extra, const char *block, const char *disk,
                     const char *pairs, pm_case *keep)
{
    char buf[8192];
    snprintf(buf, sizeof buf, tmpl, method, type, extra, block, disk, pairs);
    pm_case c;
    const int rc = pm_case_load_buffer(buf, strlen(buf), "case.json", &c);
    if (keep && rc == PM_OK)
        *keep = c;
    else
        pm_case_free(&c);
    return rc;
}

static int load(const char *pairs)
{
    return load_full("mpm", "explicit", "", "", "", pairs, NULL);
}

static void expect_refused_full(const char *method, const char *type, const char *extra, const char *block,
                                const char *pairs, const char *part)
{
    const int rc = load_full(method, type, extra, block, "", pairs, NULL);
    if (rc != PM_EINPUT)
        fail_msg("%s: expected an input error, got %d", pairs, rc);
    if (!strstr(pm_error_message(), part))
        fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), part);
}

static void expect_refused(const char *pairs, const char *part)
{
    expect_refused_full("mpm", "explicit", "", "", pairs, part);
}

#define PAIR(extra) "[ { \"bodies\": [\"block\", \"disk\"], " extra " } ]"

static void pairs_load(void **state)
{
    (void)state;
    pm_case c;
    assert_int_equal(load_full("mpm", "explicit", "", "", "", PAIR("\"law\": \"coulomb\", \"friction\": 0.3"), &c),
                     PM_OK);
    assert_int_equal(c.n_contact_pairs, 1);
    assert_int_equal(c.contact_pairs[0].law, PM_PAIR_COULOMB);
    assert_true(c.contact_pairs[0].friction == 0.3);
    assert_int_equal(c.contact_pairs[0].extent_check, 1);
    assert_string_equal(c.bodies[2].contact_group, "rest");
    pm_case_free(&c);
    assert_int_equal(load(PAIR("\"law\": \"frictionless\", \"separation\": \"none\"")), PM_OK);
    assert_int_equal(load(PAIR("\"law\": \"no_slip\"")), PM_OK);
    assert_int_equal(load("[]"), PM_OK);
    /* two bodies in one group, paired with a third */
    assert_int_equal(load_full("mpm", "explicit", "", "\"contact_group\": \"g\",", "\"contact_group\": \"g\",",
                               "[ { \"bodies\": [\"g\", \"rest\"], \"law\": \"frictionless\" } ]", &c),
                     PM_OK);
    pm_multibody *mb;
    assert_int_equal(pm_multibody_create(&c, 121, &mb), PM_OK);
    assert_int_equal(mb->n_fields, 2);
    assert_int_equal(mb->field_of_body[0], mb->field_of_body[1]);
    assert_int_not_equal(mb->field_of_body[0], mb->field_of_body[2]);
    assert_int_equal(mb->offset_of_body[2], 121);
    pm_multibody_destroy(mb);
    pm_case_free(&c);
}

static void bad_pairs_refused(void **state)
{
    (void)state;
    expect_refused("[ { \"bodies\": [\"block\", \"wall\"], \"law\": \"frictionless\" } ]",
                   "contact_pairs[0].bodies[1]: no body or source is named or grouped \"wall\"");
    expect_refused("[ { \"bodies\": [\"block\", \"block\"], \"law\": \"frictionless\" } ]", "both entries are");
    expect_refused("[ { \"bodies\": [\"block\"], \"law\": \"frictionless\" } ]", "a list of two contact group names");
    expect_refused("[ { \"bodies\": [\"block\", 3], \"law\": \"frictionless\" } ]", "contact_pairs[0].bodies[1]");
    expect_refused(PAIR("\"law\": \"coulomb\", \"friction\": -0.1"), "contact_pairs[0].friction");
    expect_refused(PAIR("\"law\": \"coulomb\""), "contact_pairs[0].friction");
    expect_refused(PAIR("\"law\": \"frictionless\", \"friction\": 0.2"), "goes with law \"coulomb\"");
    expect_refused(PAIR("\"law\": \"sticky\""), "contact_pairs[0].law");
    expect_refused(PAIR("\"friction\": 0.2"), "contact_pairs[0].law");
    expect_refused(PAIR("\"law\": \"frictionless\", \"separation\": \"gap\""), "contact_pairs[0].separation");
    expect_refused(PAIR("\"law\": \"frictionless\", \"frction\": 0.2"), "frction");
    expect_refused("[ { \"bodies\": [\"block\", \"disk\"], \"law\": \"frictionless\" }, "
                   "{ \"bodies\": [\"disk\", \"block\"], \"law\": \"no_slip\" } ]",
                   "is already contact_pairs[0]");
    expect_refused("{}", "contact_pairs: expected a list");
    expect_refused_full("mpm", "quasi_static", "", "", PAIR("\"law\": \"frictionless\""), "analysis.type 'explicit'");
    expect_refused_full("mpm", "implicit", "", "", PAIR("\"law\": \"frictionless\""), "analysis.type 'explicit'");
    expect_refused_full("gmm", "explicit", "", "", PAIR("\"law\": \"frictionless\""), "method 'mpm'");
    expect_refused_full("mpm", "explicit", ", \"fbar\": \"cell\"", "", PAIR("\"law\": \"frictionless\""),
                        "analysis.fbar");
    expect_refused_full("mpm", "explicit", "", "\"contact_group\": 7,", PAIR("\"law\": \"frictionless\""),
                        "bodies[0].contact_group");
}

/* Run the case with a scheme for `steps` steps; positions and velocities into x, v (room for n). */
static size_t run_case(const char *scheme, const char *pairs, int steps, double *x, double *v, size_t cap)
{
    char extra[64];
    snprintf(extra, sizeof extra, ", \"scheme\": \"%s\", \"dt\": 2e-4", scheme);
    pm_case c;
    assert_int_equal(load_full("mpm", "explicit", extra, "", "", pairs, &c), PM_OK);
    pm_sim *s;
    assert_int_equal(pm_sim_create(&c, &s, 1), PM_OK);
    for (int k = 0; k < steps; k++)
        if (pm_explicit_step(s, 2e-4) != PM_OK)
            fail_msg("%s, %s: step %d: %s", scheme, pairs, k, pm_error_message());
    assert_true(s->p.n <= cap);
    const size_t n = s->p.n;
    /* ids survive the periodic sorts: store by id */
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < PM_DIM; d++) {
            x[PM_DIM * (size_t)s->p.id[i] + d] = s->p.x[PM_DIM * i + d];
            v[PM_DIM * (size_t)s->p.id[i] + d] = s->p.v[PM_DIM * i + d];
        }
    pm_sim_destroy(s);
    pm_case_free(&c);
    return n;
}

enum { CAP = 4096 };
static double xa[PM_DIM * CAP], va[PM_DIM * CAP], xb[PM_DIM * CAP], vb[PM_DIM * CAP];

static void no_slip_is_single_field(void **state)
{
    (void)state;
    const char *schemes[] = {"usf", "usl", "musl", "newmark_pc"};
    for (int k = 0; k < 4; k++) {
        /* 120 steps at 2 m/s relative: the bodies meet (0.05 m apart) and push into each other */
        const size_t n = run_case(schemes[k], "[]", 120, xa, va, CAP);
        assert_int_equal(run_case(schemes[k], PAIR("\"law\": \"no_slip\""), 120, xb, vb, CAP), n);
        double dx = 0, dv = 0;
        for (size_t i = 0; i < PM_DIM * n; i++) {
            dx = fmax(dx, fabs(xa[i] - xb[i]));
            dv = fmax(dv, fabs(va[i] - vb[i]));
        }
        if (dx > 1e-12 || dv > 1e-9)
            fail_msg("%s: no_slip pair vs single field: positions differ by %g m, velocities by %g m/s", schemes[k],
                     dx, dv);
    }
}

static void frictionless_keeps_momentum(void **state)
{
    (void)state;
    const char *schemes[] = {"usf", "musl", "newmark_pc"};
    for (int k = 0; k < 3; k++) {
        char extra[64];
        snprintf(extra, sizeof extra, ", \"scheme\": \"%s\", \"dt\": 2e-4", schemes[k]);
        pm_case c;
        assert_int_equal(load_full("mpm", "explicit", extra, "", "", PAIR("\"law\": \"coulomb\", \"friction\": 0.4"),
                                   &c),
                         PM_OK);
        pm_sim *s;
        assert_int_equal(pm_sim_create(&c, &s, 1), PM_OK);
        double p0[PM_DIM] = {0}, p1[PM_DIM] = {0}, scale = 0;
        for (size_t i = 0; i < s->p.n; i++)
            for (int d = 0; d < PM_DIM; d++) {
                p0[d] += s->p.mass[i] * s->p.v[PM_DIM * i + d];
                scale += s->p.mass[i] * fabs(s->p.v[PM_DIM * i + d]);
            }
        int acted = 0;
        for (int step = 0; step < 150; step++) {
            assert_int_equal(pm_explicit_step(s, 2e-4), PM_OK);
            for (size_t e = 0; e < PM_DIM * (size_t)s->mb->n_fields * (size_t)s->mb->n_fields; e++)
                acted |= s->mb->pair_force[e] != 0;
        }
        for (size_t i = 0; i < s->p.n; i++)
            for (int d = 0; d < PM_DIM; d++)
                p1[d] += s->p.mass[i] * s->p.v[PM_DIM * i + d];
        if (!acted)
            fail_msg("%s: the bodies never met", schemes[k]);
        for (int d = 0; d < PM_DIM; d++)
            if (fabs(p1[d] - p0[d]) > 1e-12 * scale)
                fail_msg("%s: momentum %d changed from %.17g to %.17g", schemes[k], d, p0[d], p1[d]);
        pm_sim_destroy(s);
        pm_case_free(&c);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(pairs_load),
        cmocka_unit_test(bad_pairs_refused),
        cmocka_unit_test(no_slip_is_single_field),
        cmocka_unit_test(frictionless_keeps_momentum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
