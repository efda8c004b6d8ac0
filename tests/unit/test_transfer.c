/* Particle-grid transfers conserve mass and momentum to 1e-12 relative (round-off of sums over a
 * few thousand terms), for every explicit scheme, on quad4 and tri3, with a spinning, deforming
 * body and no boundary conditions or gravity. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/material.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"
#include "transfer_case.h"

static void sums(const pm_sim *s, double pm[3], double gm[3])
{
    memset(pm, 0, 3 * sizeof(double));
    memset(gm, 0, 3 * sizeof(double));
    for (size_t i = 0; i < s->p.n; i++) {
        pm[0] += s->p.mass[i];
        pm[1] += s->p.mass[i] * s->p.v[2 * i];
        pm[2] += s->p.mass[i] * s->p.v[2 * i + 1];
    }
    for (size_t n = 0; n < s->grid.n_nodes; n++) {
        gm[0] += s->nd.mass[n];
        gm[1] += s->nd.mass[n] * s->nd.vel_new[2 * n];
        gm[2] += s->nd.mass[n] * s->nd.vel_new[2 * n + 1];
    }
}

static void check(pm_scheme scheme, pm_element el)
{
    pm_case c;
    pm_material mat;
    pm_case_body body;
    tc_disk_case(&c, &mat, &body, "transfer.json", scheme, el, 10, 1e6, 0.25);
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(&c, &s, 1), 0);
    /* rigid spin plus a stretching field, so that stresses and internal forces are non-zero */
    double p0[3] = {0, 0, 0};
    for (size_t i = 0; i < s->p.n; i++) {
        double dx = s->p.x[2 * i] - 0.5, dy = s->p.x[2 * i + 1] - 0.5;
        s->p.v[2 * i] = 1.0 - 3.0 * dy + 0.5 * dx;
        s->p.v[2 * i + 1] = -0.5 + 3.0 * dx;
        p0[0] += s->p.mass[i];
        p0[1] += s->p.mass[i] * s->p.v[2 * i];
        p0[2] += s->p.mass[i] * s->p.v[2 * i + 1];
    }
    for (int step = 0; step < 20; step++) {
        assert_int_equal(pm_explicit_step(s, 1e-4), 0);
        double pm[3], gm[3];
        sums(s, pm, gm);
        const double pref = fabs(p0[1]) + fabs(p0[2]);
        assert_true(fabs(gm[0] - p0[0]) <= 1e-12 * p0[0]);
        assert_true(fabs(pm[0] - p0[0]) <= 1e-12 * p0[0]);
        for (int d = 1; d < 3; d++) {
            /* grid momentum at the end of the step equals the particles' momentum */
            assert_true(fabs(gm[d] - p0[d]) <= 1e-12 * pref);
            assert_true(fabs(pm[d] - p0[d]) <= 1e-12 * pref);
        }
    }
    pm_sim_destroy(s);
}

static void musl_quad4(void **st) { (void)st; check(PM_SCHEME_MUSL, PM_QUAD4); }
static void usl_quad4(void **st) { (void)st; check(PM_SCHEME_USL, PM_QUAD4); }
static void usf_tri3(void **st) { (void)st; check(PM_SCHEME_USF, PM_TRI3); }
static void musl_tri3(void **st) { (void)st; check(PM_SCHEME_MUSL, PM_TRI3); }
static void newmark_quad4(void **st) { (void)st; check(PM_SCHEME_NEWMARK_PC, PM_QUAD4); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(musl_quad4), cmocka_unit_test(usl_quad4), cmocka_unit_test(usf_tri3),
        cmocka_unit_test(musl_tri3), cmocka_unit_test(newmark_quad4),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
