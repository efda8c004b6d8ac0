/*
 * The material-point driver: drained triaxial compression reaches the Mohr-Coulomb deviator
 * q_f = 2 (c cos phi + s3 sin phi) / (1 - sin phi) within 0.5 % (Cauchy stresses, lateral stress
 * held at the confining pressure); Drucker-Prager with A = -1 / +1 matches it on the compression /
 * extension meridian; elastic oedometer and simple shear agree with closed forms; CSV header.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/driver.h"
#include "pmech/error.h"
#include "pmech/material.h"

typedef struct {
    double qmax, lat_err, last[11];
    int rows;
} rec_t;

static void record(void *ctx, int step, const double v[11])
{
    rec_t *r = ctx;
    (void)step;
    r->qmax = fmax(r->qmax, v[9]);
    memcpy(r->last, v, sizeof r->last);
    r->rows++;
}

static void setup(pm_driver *d, const char *model, const char *const *keys, const double *vals)
{
    memset(d, 0, sizeof *d);
    pm_material *m = &d->material;
    m->ops = pm_material_find(model);
    assert_non_null(m->ops);
    m->density = 2000;
    for (size_t i = 0; i < m->ops->n_params; i++)
        m->param[i] = m->ops->params[i].def;
    for (int i = 0; keys && keys[i]; i++) {
        int k = pm_material_param_index(m->ops, keys[i]);
        assert_true(k >= 0);
        m->param[k] = vals[i];
    }
    assert_int_equal(pm_material_set_elastic(m, 2e7, 0.3, NAN, NAN), PM_OK);
    if (m->ops->init)
        assert_int_equal(m->ops->init(m), PM_OK);
    d->steps = 400;
    d->dt = 1e-3;
}

/* Lateral stress check as a row callback. */
typedef struct {
    rec_t r;
    double pc;
} tri_t;

static void tri_row(void *ctx, int step, const double v[11])
{
    tri_t *t = ctx;
    record(&t->r, step, v);
    t->r.lat_err = fmax(t->r.lat_err, fmax(fabs(v[4] + t->pc), fabs(v[6] + t->pc)) / t->pc);
}

static double triaxial_peak(pm_driver *d, double pc, double axial)
{
    d->path = PM_PATH_TRIAXIAL;
    d->confining_pressure = pc;
    d->axial_strain = axial;
    for (int i = 0; i < 3; i++)
        d->stress0[i] = -pc;
    d->stress0[3] = 0;
    tri_t t;
    memset(&t, 0, sizeof t);
    t.pc = pc;
    int rc = pm_driver_run_cb(d, NULL, tri_row, &t);
    if (rc)
        fail_msg("driver: %s", pm_error_message());
    assert_int_equal(t.r.rows, d->steps + 1);
    assert_true(t.r.lat_err <= 1e-9);
    return t.r.qmax;
}

static void triaxial_mohr_coulomb(void **unused)
{
    (void)unused;
    const double c = 1e4, pc = 1e5;
    const double phis[3] = {20, 30, 40}, psis[3] = {0, 10, 5};
    for (int i = 0; i < 3; i++) {
        const char *keys[] = {"cohesion", "friction_angle", "dilatancy_angle", NULL};
        const double vals[] = {c, phis[i], psis[i]};
        pm_driver d;
        setup(&d, "mohr_coulomb", keys, vals);
        const double s = sin(phis[i] * M_PI / 180), co = cos(phis[i] * M_PI / 180);
        const double qf = 2 * (c * co + pc * s) / (1 - s);
        const double q = triaxial_peak(&d, pc, 0.05);
        if (!(fabs(q - qf) <= 0.005 * qf))
            fail_msg("phi %g: q_peak %g, q_f %g", phis[i], q, qf);
        /* extension (axial_strain < 0): q_f = 2 (c cos phi + s3 sin phi) / (1 + sin phi) */
        const double qe = triaxial_peak(&d, pc, -0.05);
        const double qfe = 2 * (c * co + pc * s) / (1 + s);
        if (!(fabs(qe - qfe) <= 0.005 * qfe))
            fail_msg("phi %g extension: q_peak %g, q_f %g", phis[i], qe, qfe);
    }
}

static void triaxial_drucker_prager_meridians(void **unused)
{
    (void)unused;
    const double c = 1e4, pc = 1e5, phi = 30;
    const double s = sin(phi * M_PI / 180), co = cos(phi * M_PI / 180);
    const char *keys[] = {"cohesion", "friction_angle", "cone_fit", NULL};
    /* A = -1: outer apexes, the compression meridian */
    const double v1[] = {c, phi, -1};
    pm_driver d;
    setup(&d, "drucker_prager", keys, v1);
    const double qc = triaxial_peak(&d, pc, 0.05), qfc = 2 * (c * co + pc * s) / (1 - s);
    if (!(fabs(qc - qfc) <= 0.005 * qfc))
        fail_msg("DP A=-1 compression: %g vs MC %g", qc, qfc);
    /* A = +1: inner apexes, the extension meridian */
    const double v2[] = {c, phi, 1};
    setup(&d, "drucker_prager", keys, v2);
    const double qe = triaxial_peak(&d, pc, -0.05), qfe = 2 * (c * co + pc * s) / (1 + s);
    if (!(fabs(qe - qfe) <= 0.005 * qfe))
        fail_msg("DP A=+1 extension: %g vs MC %g", qe, qfe);
}

static void oedometer_and_shear_elastic(void **unused)
{
    (void)unused;
    pm_driver d;
    setup(&d, "linear_elastic", NULL, NULL);
    const pm_material *m = &d.material;
    d.path = PM_PATH_OEDOMETER;
    d.axial_strain = 1e-4;
    d.steps = 10;
    rec_t r;
    memset(&r, 0, sizeof r);
    assert_int_equal(pm_driver_run_cb(&d, NULL, record, &r), PM_OK);
    const double eyy = log(1 - 1e-4);
    assert_true(fabs(r.last[1] - eyy) <= 1e-12);
    assert_true(fabs(r.last[5] - (m->K + 4 * m->G / 3) * eyy) <= 1e-6 * fabs(r.last[5]));
    assert_true(fabs(r.last[4] - (m->K - 2 * m->G / 3) * eyy) <= 1e-6 * fabs(r.last[4]));
    d.path = PM_PATH_SIMPLE_SHEAR;
    d.shear_strain = 1e-4;
    memset(&r, 0, sizeof r);
    assert_int_equal(pm_driver_run_cb(&d, NULL, record, &r), PM_OK);
    assert_true(fabs(r.last[7] - m->G * 1e-4) <= 1e-6 * m->G * 1e-4);
    assert_true(fabs(r.last[3] - 0.5e-4) <= 1e-8); /* tensor shear strain */
}

static void csv_output(void **unused)
{
    (void)unused;
    pm_driver d;
    setup(&d, "linear_elastic", NULL, NULL);
    double inc[8] = {1e-4, 0, 0, 0, 0, 0, 0, 2e-4};
    d.path = PM_PATH_INCREMENTS;
    d.n_increments = 2;
    d.increments = inc;
    FILE *f = tmpfile();
    assert_non_null(f);
    assert_int_equal(pm_driver_run(&d, f), PM_OK);
    rewind(f);
    char line[1024];
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "step,exx,eyy,ezz,exy,sxx,syy,szz,sxy,p,q,eps_p\n");
    int rows = 0;
    while (fgets(line, sizeof line, f))
        rows++;
    assert_int_equal(rows, 3);
    fclose(f);
    d.n_increments = 0;
    assert_int_equal(pm_driver_run(&d, NULL), PM_EINPUT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(triaxial_mohr_coulomb),
        cmocka_unit_test(triaxial_drucker_prager_meridians),
        cmocka_unit_test(oedometer_and_shear_elastic),
        cmocka_unit_test(csv_output),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
