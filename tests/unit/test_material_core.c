/*
 * Material interface basics: the registry, elastic constants, parameter look-up, the messages of
 * invalid parameters (naming key, value and range), wave speeds and the Hughes-Winget rotation.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pmech/error.h"
#include "pmech/material.h"

static void registry_consistent(void **unused)
{
    (void)unused;
    const char *const *names = pm_material_names();
    int n = 0;
    for (; names[n]; n++) {
        const pm_material_ops *ops = pm_material_find(names[n]);
        assert_non_null(ops);
        assert_string_equal(ops->name, names[n]);
        assert_true(ops->update != NULL);
        assert_true(ops->n_state <= PM_MAT_MAX_STATE);
        assert_true(ops->n_params <= PM_MAT_MAX_PARAMS);
        for (size_t i = 0; i < ops->n_params; i++) {
            assert_non_null(ops->params[i].key);
            assert_non_null(ops->params[i].help);
            assert_int_equal(pm_material_param_index(ops, ops->params[i].key), (int)i);
        }
    }
    assert_int_equal(n, 7);
    assert_null(pm_material_find("mohr_coulom"));
    assert_null(pm_material_find(NULL));
    assert_int_equal(pm_material_param_index(pm_material_find("von_mises"), "cohesion"), -1);
}

static void elastic_constants(void **unused)
{
    (void)unused;
    pm_material m;
    memset(&m, 0, sizeof m);
    assert_int_equal(pm_material_set_elastic(&m, 2e7, 0.25, NAN, NAN), PM_OK);
    assert_true(fabs(m.K - 2e7 / 1.5) < 1e-6 && fabs(m.G - 8e6) < 1e-6);
    assert_true(fabs(m.lambda - (m.K - 2 * m.G / 3)) < 1e-6);
    pm_material k;
    memset(&k, 0, sizeof k);
    assert_int_equal(pm_material_set_elastic(&k, NAN, NAN, m.K, m.G), PM_OK);
    assert_true(fabs(k.E - 2e7) < 1e-6 && fabs(k.nu - 0.25) < 1e-12);
    assert_int_equal(pm_material_set_elastic(&m, -1, 0.3, NAN, NAN), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "youngs_modulus"));
    assert_int_equal(pm_material_set_elastic(&m, 1e7, 0.5, NAN, NAN), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "poisson_ratio"));
    assert_int_equal(pm_material_set_elastic(&m, NAN, NAN, 1e7, 0), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "shear_modulus"));
    assert_int_equal(pm_material_set_elastic(&m, 1e7, 0.3, 1e7, NAN), PM_EINPUT);
    assert_int_equal(pm_material_set_elastic(&m, NAN, NAN, NAN, NAN), PM_EINPUT);
    assert_int_equal(pm_material_set_elastic(&m, 1e7, NAN, NAN, NAN), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "poisson_ratio"));
}

/* Fill defaults, set one parameter, run the range checks of the table and init like a loader. */
static int try_param(const char *model, const char *key, double value)
{
    pm_material m;
    memset(&m, 0, sizeof m);
    m.ops = pm_material_find(model);
    m.density = 2000;
    for (size_t i = 0; i < m.ops->n_params; i++) {
        const pm_param_spec *s = &m.ops->params[i];
        m.param[i] = s->def;
        if (isnan(m.param[i]) && (s->flags & PM_PARAM_REQUIRED)) /* a valid required value */
            m.param[i] = !strcmp(s->key, "poisson_ratio") ? 0.3 : !strcmp(s->key, "friction_angle") ? 30 : 1e4;
        if (!strcmp(s->key, "kappa"))
            m.param[i] = 0.02;
        if (!strcmp(s->key, "void_ratio"))
            m.param[i] = 0.9;
    }
    int k = pm_material_param_index(m.ops, key);
    assert_true(k >= 0);
    m.param[k] = value;
    const pm_param_spec *s = &m.ops->params[k];
    /* what the loader does with simple bounds */
    const int lo_ok = (s->flags & PM_PARAM_LO_OPEN) ? value > s->lo : value >= s->lo;
    const int hi_ok = (s->flags & PM_PARAM_HI_OPEN) ? value < s->hi : value <= s->hi;
    const int table_ok = isnan(value) || (lo_ok && hi_ok);
    if (m.ops->elastic_pair)
        assert_int_equal(pm_material_set_elastic(&m, 2e7, 0.3, NAN, NAN), PM_OK);
    const int rc = m.ops->init ? m.ops->init(&m) : PM_OK;
    if (rc)
        assert_non_null(strstr(pm_error_message(), key)); /* the message names the key */
    /* init must reject at least what the table rejects (callers may skip the table) */
    if (!table_ok && rc != PM_EINPUT)
        fail_msg("%s.%s = %g accepted by init", model, key, value);
    return rc;
}

static void invalid_parameters(void **unused)
{
    (void)unused;
    const char *frictional[] = {"mohr_coulomb", "drucker_prager"};
    for (int i = 0; i < 2; i++) {
        assert_int_equal(try_param(frictional[i], "friction_angle", 90), PM_EINPUT);
        assert_int_equal(try_param(frictional[i], "friction_angle", -1), PM_EINPUT);
        assert_int_equal(try_param(frictional[i], "cohesion", -1), PM_EINPUT);
        assert_int_equal(try_param(frictional[i], "dilatancy_angle", 31), PM_EINPUT); /* > phi = 30 */
        assert_int_equal(try_param(frictional[i], "dilatancy_angle", 30), PM_OK);
        assert_int_equal(try_param(frictional[i], "friction_angle", 0), PM_OK);
    }
    assert_int_equal(try_param("drucker_prager", "cone_fit", 1.5), PM_EINPUT);
    assert_int_equal(try_param("drucker_prager", "cone_fit", -1.01), PM_EINPUT);
    assert_int_equal(try_param("drucker_prager", "cone_fit", 1), PM_OK);
    assert_int_equal(try_param("drucker_prager", "shear_hardening", -1e12), PM_EINPUT);
    assert_int_equal(try_param("mohr_coulomb", "tension_cutoff", -5), PM_EINPUT);
    assert_int_equal(try_param("von_mises", "yield_stress", 0), PM_EINPUT);
    assert_int_equal(try_param("von_mises", "hardening_modulus", -1e12), PM_EINPUT);
    assert_int_equal(try_param("viscoplastic_drucker_prager", "friction_angle", 0), PM_EINPUT);
    assert_int_equal(try_param("viscoplastic_drucker_prager", "viscosity", 0), PM_EINPUT);
    assert_int_equal(try_param("viscoplastic_drucker_prager", "exponent", -1), PM_EINPUT);
    assert_int_equal(try_param("granular", "kappa", 0), PM_EINPUT);
    assert_int_equal(try_param("granular", "poisson_ratio", 0.5), PM_EINPUT);
    assert_int_equal(try_param("granular", "bulk_viscosity", -1), PM_EINPUT);
    assert_int_equal(try_param("granular", "friction_angle", 95), PM_EINPUT);
    /* the loosest state must be looser than the reference void ratio 0.9 */
    assert_int_equal(try_param("granular", "max_void_ratio", 0.9), PM_EINPUT);
    assert_int_equal(try_param("granular", "max_void_ratio", 1.0), PM_OK);
    /* the message gives value and allowed range */
    try_param("drucker_prager", "cone_fit", 2);
    assert_non_null(strstr(pm_error_message(), "cone_fit = 2"));
    assert_non_null(strstr(pm_error_message(), "[-1, 1]"));
}

static void wave_speed_and_energy(void **unused)
{
    (void)unused;
    pm_material m;
    memset(&m, 0, sizeof m);
    m.ops = pm_material_find("linear_elastic");
    m.density = 1000;
    assert_int_equal(pm_material_set_elastic(&m, 1e7, 0.3, NAN, NAN), PM_OK);
    const double c = pm_material_elastic_wave_speed(&m, NULL, 1000);
    assert_true(fabs(c - sqrt((m.K + 4 * m.G / 3) / 1000)) < 1e-9);
    const double s[6] = {-3e4, -3e4, -3e4, 0, 0, 0};
    assert_true(fabs(pm_material_elastic_energy(&m, NULL, NULL, s) - 0.5 * 9e8 / m.K) < 1e-9);
    /* neo-Hookean energy at F = I is zero and its stress vanishes */
    m.ops = pm_material_find("neo_hookean");
    pm_material_step in;
    memset(&in, 0, sizeof in);
    in.F_new[0] = in.F_new[4] = in.F_new[8] = 1;
    double st[6];
    assert_int_equal(m.ops->update(&m, &in, NULL, st, NULL), PM_OK);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(st[i]) < 1e-9);
    assert_true(fabs(m.ops->strain_energy(&m, &in, NULL, st)) < 1e-12);
    assert_true(fabs(m.ops->wave_speed(&m, NULL, 1000) - c) < 1e-9);
}

static void hughes_winget_finite_rotation(void **unused)
{
    (void)unused;
    /* one step of 60 degrees about an oblique axis: the stress is rotated exactly, no strain */
    const double n[3] = {1 / sqrt(3.0), 1 / sqrt(3.0), 1 / sqrt(3.0)}, th = M_PI / 3;
    const double c = cos(th), s = sin(th), C = 1 - c;
    const double R[9] = {c + n[0] * n[0] * C, n[0] * n[1] * C - n[2] * s, n[0] * n[2] * C + n[1] * s,
                         n[1] * n[0] * C + n[2] * s, c + n[1] * n[1] * C, n[1] * n[2] * C - n[0] * s,
                         n[2] * n[0] * C - n[1] * s, n[2] * n[1] * C + n[0] * s, c + n[2] * n[2] * C};
    double sig[6] = {1, 2, 3, 0.5, -0.4, 0.3}, de[6];
    const double S[9] = {1, 0.5, 0.3, 0.5, 2, -0.4, 0.3, -0.4, 3};
    pm_hughes_winget(R, sig, de);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(de[i]) < 1e-14);
    double RS[9], E[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            RS[3 * i + j] = 0;
            for (int k = 0; k < 3; k++)
                RS[3 * i + j] += R[3 * i + k] * S[3 * k + j];
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            E[3 * i + j] = 0;
            for (int k = 0; k < 3; k++)
                E[3 * i + j] += RS[3 * i + k] * R[3 * j + k];
        }
    const double expect[6] = {E[0], E[4], E[8], E[1], E[5], E[2]};
    for (int i = 0; i < 6; i++)
        assert_true(fabs(sig[i] - expect[i]) < 1e-13);
    /* uniaxial stretch f: the mid-step strain is 2 (f - 1)/(f + 1) */
    const double f = 1.1, F[9] = {f, 0, 0, 0, 1, 0, 0, 0, 1};
    double z[6] = {0};
    pm_hughes_winget(F, z, de);
    assert_true(fabs(de[0] - 2 * (f - 1) / (f + 1)) < 1e-15);
}

static void elastic_stiffness_matrix(void **unused)
{
    (void)unused;
    double D[36];
    pm_elastic_stiffness(10, 3, D);
    assert_true(fabs(D[0] - 14) < 1e-12 && fabs(D[1] - 8) < 1e-12 && fabs(D[21] - 3) < 1e-12);
    assert_true(D[3] == 0 && D[18] == 0 && D[35] == 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(registry_consistent),
        cmocka_unit_test(elastic_constants),
        cmocka_unit_test(invalid_parameters),
        cmocka_unit_test(wave_speed_and_energy),
        cmocka_unit_test(hughes_winget_finite_rotation),
        cmocka_unit_test(elastic_stiffness_matrix),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
