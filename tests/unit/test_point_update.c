/*
 * The shared point update (src/solver/point_update.h): the plane-stress condition holds and gives
 * the plane-stress moduli for an elastic point, plane strain keeps the out-of-plane stretch, the
 * hoop stretch follows u_r / r, and volumes come from det F.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "solver/point_update.h"

static const double E = 2e7, NU = 0.25;

static pm_material elastic(void)
{
    pm_material m;
    memset(&m, 0, sizeof m);
    m.ops = pm_material_find("linear_elastic");
    assert_non_null(m.ops);
    m.density = 1000;
    assert_int_equal(pm_material_set_elastic(&m, E, NU, NAN, NAN), PM_OK);
    if (m.ops->init)
        assert_int_equal(m.ops->init(&m), PM_OK);
    return m;
}

/* One step from the undeformed, unstressed state with displacement gradient H (and u_r at r). */
static int step(const pm_material *m, pm_formulation form, const double H[4], double u_r, double r, double F[PM_NF],
                double sg[PM_NS], double *vol, double T[36])
{
    const double F0[PM_NF] = {1, 0, 0, 1, 1}, s0[PM_NS] = {0, 0, 0, 0};
    double state[PM_MAT_MAX_STATE] = {0}, eps_p = 0;
    const pm_point_from from = {F0, s0, state, 2.0, 0};
    return pm_point_update(m, form, &from, H, u_r, r, 1e-3, m->ops->n_state, F, sg, state, vol, &eps_p, T);
}

static void plane_stress_condition(void **unused)
{
    (void)unused;
    const pm_material m = elastic();
    const double e = 1e-6;
    double F[PM_NF], sg[PM_NS], vol, T[36];
    /* yy held: sigma_xx = E / (1 - nu^2) e, sigma_yy = nu sigma_xx */
    const double Hx[4] = {e, 0, 0, 0};
    assert_int_equal(step(&m, PM_PLANE_STRESS, Hx, 0, 1, F, sg, &vol, T), 0);
    assert_true(fabs(sg[PM_SZZ]) <= 1e-13 * fabs(sg[PM_SXX]));
    assert_true(fabs(sg[PM_SXX] / e - E / (1 - NU * NU)) < 1e-4 * E);
    assert_true(fabs(sg[PM_SYY] - NU * sg[PM_SXX]) < 1e-4 * fabs(sg[PM_SXX]));
    /* the out-of-plane contraction of plane stress, and the volume from det F */
    assert_true(fabs((F[PM_FZZ] - 1) / e + NU / (1 - NU)) < 1e-4);
    assert_true(fabs(vol - 2.0 * (1 + e) * F[PM_FZZ]) < 1e-15);
    /* uniaxial stress: the lateral contraction nu e leaves sigma_yy ~ 0 and sigma_xx = E e */
    const double Hu[4] = {e, 0, 0, -NU * e};
    assert_int_equal(step(&m, PM_PLANE_STRESS, Hu, 0, 1, F, sg, &vol, T), 0);
    assert_true(fabs(sg[PM_SZZ]) <= 1e-13 * fabs(sg[PM_SXX]));
    assert_true(fabs(sg[PM_SYY]) < 1e-4 * fabs(sg[PM_SXX]));
    assert_true(fabs(sg[PM_SXX] / e - E) < 1e-4 * E);
    assert_true(fabs((F[PM_FZZ] - 1) / e + NU) < 1e-4);
}

static void plane_strain_and_hoop(void **unused)
{
    (void)unused;
    const pm_material m = elastic();
    const double e = 1e-6;
    double F[PM_NF], sg[PM_NS], vol;
    const double Hx[4] = {e, 0, 0, 0};
    assert_int_equal(step(&m, PM_PLANE_STRAIN, Hx, 0, 1, F, sg, &vol, NULL), 0);
    assert_true(F[PM_FZZ] == 1.0);
    assert_true(fabs(sg[PM_SZZ] - NU * (sg[PM_SXX] + sg[PM_SYY])) < 1e-4 * fabs(sg[PM_SXX]));
    /* axisymmetric: hoop stretch 1 + u_r / r */
    const double H0[4] = {0, 0, 0, 0};
    assert_int_equal(step(&m, PM_AXISYMMETRIC, H0, 2e-6, 2.0, F, sg, &vol, NULL), 0);
    assert_true(F[PM_FZZ] == 1 + 2e-6 / 2.0);
    assert_true(sg[PM_SZZ] > 0);
    /* an inverted step fails */
    const double Hinv[4] = {-2, 0, 0, 0};
    assert_int_equal(step(&m, PM_PLANE_STRAIN, Hinv, 0, 1, F, sg, &vol, NULL), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plane_stress_condition),
        cmocka_unit_test(plane_strain_and_hoop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
