/*
 * Strength reduction at unit level: the models' reduce_strength hook divides cohesion and
 * tan(phi) by F (Mohr-Coulomb also its tension cut-off; psi follows phi and stays below it), the
 * reduced material's derived constants are those of a material given the reduced values, models
 * without a Coulomb strength have no hook and are copied untouched; the trial criterion; and the
 * bisection on a coarse slope, whose bracket must end narrower than the tolerance with its lower
 * end standing and its upper end failing.
 */
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
#include "pmech/material.h"
#include "pmech/strength_reduction.h"
#include "solver/sim_internal.h"

static void set_param(pm_material *m, const char *key, double v)
{
    const int i = pm_material_param_index(m->ops, key);
    assert_true(i >= 0);
    m->param[i] = v;
}

/* A material of @p model with every parameter at its default, elastic constants set. */
static pm_material make(const char *model)
{
    pm_material m;
    memset(&m, 0, sizeof m);
    m.ops = pm_material_find(model);
    assert_non_null(m.ops);
    snprintf(m.name, sizeof m.name, "%s", model);
    m.density = 2000;
    for (size_t i = 0; i < m.ops->n_params; i++)
        m.param[i] = m.ops->params[i].def;
    if (m.ops->elastic_pair)
        assert_int_equal(pm_material_set_elastic(&m, 1e8, 0.3, NAN, NAN), PM_OK);
    return m;
}

static pm_material make_coulomb(const char *model, double c, double phi, double psi)
{
    pm_material m = make(model);
    set_param(&m, "cohesion", c);
    set_param(&m, "friction_angle", phi);
    set_param(&m, "dilatancy_angle", psi);
    return m;
}

static double deg_atan_reduced(double deg, double F)
{
    return atan(tan(deg * M_PI / 180.0) / F) * 180.0 / M_PI;
}

static void coulomb_models_reduced(void **unused)
{
    (void)unused;
    const char *models[] = {"mohr_coulomb", "drucker_prager"};
    const double F = 1.7;
    for (int k = 0; k < 2; k++) {
        pm_material m = make_coulomb(models[k], 1.2e4, 32.0, 8.0);
        if (k == 0)
            set_param(&m, "tension_cutoff", 3e3);
        assert_int_equal(m.ops->init(&m), PM_OK);
        assert_non_null(m.ops->reduce_strength);
        pm_material r;
        assert_int_equal(pm_srf_reduce_material(&m, F, &r), PM_OK);
        const double phi_r = pm_material_param(&r, "friction_angle");
        assert_true(fabs(pm_material_param(&r, "cohesion") - 1.2e4 / F) < 1e-9);
        assert_true(fabs(phi_r - deg_atan_reduced(32.0, F)) < 1e-12);
        assert_true(fabs(tan(phi_r * M_PI / 180) - tan(32.0 * M_PI / 180) / F) < 1e-14);
        assert_true(fabs(pm_material_param(&r, "dilatancy_angle") - deg_atan_reduced(8.0, F)) < 1e-12);
        if (k == 0)
            assert_true(fabs(pm_material_param(&r, "tension_cutoff") - 3e3 / F) < 1e-9);
        /* elasticity, density and the model stay */
        assert_ptr_equal(r.ops, m.ops);
        assert_true(r.E == m.E && r.nu == m.nu && r.density == m.density);
        assert_string_equal(r.name, m.name);
        /* derived constants are recomputed: those of the same model given the reduced values */
        pm_material g = m;
        memcpy(g.param, r.param, sizeof g.param);
        memset(g.derived, 0, sizeof g.derived);
        assert_int_equal(g.ops->init(&g), PM_OK);
        assert_memory_equal(g.derived, r.derived, sizeof g.derived);
        /* in place gives the same */
        pm_material p = m;
        assert_int_equal(pm_srf_reduce_material(&p, F, &p), PM_OK);
        assert_memory_equal(p.param, r.param, sizeof p.param);
        /* the hook alone divides the parameters and leaves derived to init */
        pm_material h = m;
        assert_int_equal(h.ops->reduce_strength(&h, F), PM_OK);
        assert_memory_equal(h.param, r.param, sizeof h.param);
        assert_memory_equal(h.derived, m.derived, sizeof h.derived);
    }
}

/* psi = phi: reducing both by the same factor must keep psi <= phi. */
static void dilatancy_stays_below_friction(void **unused)
{
    (void)unused;
    for (double F = 0.6; F < 3.0; F += 0.0937) {
        pm_material m = make_coulomb("mohr_coulomb", 1e4, 27.3, 27.3), r;
        assert_int_equal(m.ops->init(&m), PM_OK);
        assert_int_equal(pm_srf_reduce_material(&m, F, &r), PM_OK);
        assert_true(pm_material_param(&r, "dilatancy_angle") <= pm_material_param(&r, "friction_angle"));
    }
}

static void bad_factor(void **unused)
{
    (void)unused;
    pm_material m = make_coulomb("drucker_prager", 1e4, 30, 0), r;
    assert_int_equal(m.ops->init(&m), PM_OK);
    const double bad[] = {0.0, -1.0, NAN, INFINITY};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(pm_srf_reduce_material(&m, bad[k], &r), PM_EINPUT);
        assert_non_null(strstr(pm_error_message(), "strength reduction factor"));
    }
}

static void models_without_strength(void **unused)
{
    (void)unused;
    const char *const *names = pm_material_names();
    int without = 0;
    for (int k = 0; names[k]; k++) {
        pm_material m = make(names[k]);
        const int coulomb = !strcmp(names[k], "mohr_coulomb") || !strcmp(names[k], "drucker_prager");
        assert_int_equal(m.ops->reduce_strength != NULL, coulomb);
        if (coulomb)
            continue;
        without++;
        /* copied unchanged, whatever the factor */
        pm_material r;
        memset(&r, 0x5a, sizeof r);
        assert_int_equal(pm_srf_reduce_material(&m, 2.0, &r), PM_OK);
        assert_memory_equal(&r, &m, sizeof m);
        assert_int_equal(pm_srf_reduce_material(&m, 0.0, &r), PM_OK);
    }
    assert_int_equal(without, 5);
}

static void criterion(void **unused)
{
    (void)unused;
    pm_srf_opts so = {.enabled = 1, .min = 0.5, .max = 3, .tolerance = 0.01, .criterion = PM_SRF_DISPLACEMENT,
                      .displacement_ratio = 10};
    pm_srf_trial t = {.factor = 1.2, .converged = 1, .max_displacement = 0.5};
    assert_false(pm_srf_judge(&so, &t, 0.1));  /* 5 x elastic */
    t.max_displacement = 1.0;
    assert_false(pm_srf_judge(&so, &t, 0.1));  /* 10 x: not above */
    t.max_displacement = 1.0001;
    assert_true(pm_srf_judge(&so, &t, 0.1));
    assert_false(pm_srf_judge(&so, &t, 0.0)); /* no reference yet: nothing to compare with */
    so.criterion = PM_SRF_CONVERGENCE;        /* converged is standing, however far it moved */
    t.max_displacement = 1e6;
    assert_false(pm_srf_judge(&so, &t, 0.1));
}

/* Griffiths & Lane's 2:1 slope (tests/verification/cases/slope_fos.json) on cells of 2 m: a few
 * seconds for the whole search. */
static const char slope[] =
    "{ \"dimension\": 2, \"formulation\": \"plane_strain\", \"method\": \"mpm\", \"shape_function\": \"linear\",\n"
    "  \"analysis\": { \"type\": \"quasi_static\", \"end_time\": 1.0, \"load_steps\": 1, \"gravity\": [0.0, -9.81],\n"
    "    \"newton\": { \"tolerance\": 1e-8, \"displacement_tolerance\": 1e-4, \"max_step_cuts\": 8 },\n"
    "    \"strength_reduction\": { \"min\": 0.5, \"max\": 4.0, \"tolerance\": 0.25 } },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [34, 12], \"cells\": [17, 6], \"element\": "
    "\"quad4\" },\n"
    "  \"materials\": [ { \"name\": \"soil\", \"model\": \"mohr_coulomb\", \"density\": 2038.7359837,\n"
    "    \"youngs_modulus\": 1.0e8, \"poisson_ratio\": 0.3, \"cohesion\": 1.0e4, \"friction_angle\": 20,\n"
    "    \"dilatancy_angle\": 0 } ],\n"
    "  \"bodies\": [ { \"name\": \"slope\", \"material\": \"soil\", \"particles_per_cell\": 2,\n"
    "    \"shape\": { \"type\": \"polygon\", \"points\": [[0, 0], [32, 0], [12, 10], [0, 10]] } } ],\n"
    "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"x\", \"y\"] },\n"
    "    { \"type\": \"fixed\", \"boundary\": \"x_min\", \"directions\": [\"x\"] } ] }\n";

static void bisection_bracket(void **unused)
{
    (void)unused;
    pm_case c;
    if (pm_case_load_buffer(slope, strlen(slope), "slope.json", &c) != PM_OK)
        fail_msg("%s", pm_error_message());
    pm_run_opts o;
    memset(&o, 0, sizeof o);
    o.threads = 1;
    o.quiet = 1;
    o.write_output = 0;
    pm_srf_result r;
    if (pm_strength_reduction(&c, &o, &r) != PM_OK)
        fail_msg("%s", pm_error_message());
    const pm_srf_opts *so = &c.analysis.strength_reduction;
    /* the two ends first, then one trial per halving of [0.5, 4] down to 0.25: 14 -> 4 halvings */
    assert_int_equal(r.n_trials, 6);
    assert_true(r.trial[0].factor == so->min && !r.trial[0].failed);
    assert_true(r.trial[1].factor == so->max && r.trial[1].failed);
    assert_true(r.hi - r.lo <= so->tolerance && r.lo < r.hi);
    assert_true(r.fos == 0.5 * (r.lo + r.hi));
    /* every trial agrees with the bracket: those at or below lo held, those at or above hi failed */
    for (int k = 0; k < r.n_trials; k++) {
        if (r.trial[k].factor <= r.lo)
            assert_false(r.trial[k].failed);
        if (r.trial[k].factor >= r.hi)
            assert_true(r.trial[k].failed);
    }
    /* coarse, but a factor of safety near Griffiths & Lane's 1.4 */
    assert_true(r.fos > 1.0 && r.fos < 2.0);
    c.analysis.strength_reduction.enabled = 0;
    assert_int_equal(pm_strength_reduction(&c, &o, &r), PM_EINPUT);
    pm_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(coulomb_models_reduced),
        cmocka_unit_test(dilatancy_stays_below_friction),
        cmocka_unit_test(bad_factor),
        cmocka_unit_test(models_without_strength),
        cmocka_unit_test(criterion),
        cmocka_unit_test(bisection_bracket),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
