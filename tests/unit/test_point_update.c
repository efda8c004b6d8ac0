/*
 * The shared point update (src/solver/point_update.h): the plane-stress condition holds and gives
 * the plane-stress moduli for an elastic point, plane strain keeps the out-of-plane stretch, the
 * hoop stretch follows u_r / r, and volumes come from det F. The plane-stress iteration stops once
 * sigma_zz is at its round-off: counted through a von Mises material whose update counts its calls,
 * a yielding point and twenty points at a fraction of a pascal each take at most 6 updates (Newton
 * converges in 2-4; a tolerance of 1e-13 of the in-plane stress, or one without the stretch's ulp,
 * ran the small ones to the limit of 20).
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

static int n_updates;
static const pm_material_ops *vm_ops;

static int counting_update(const pm_material *m, const pm_material_step *in, double *state, double *stress,
                           double *T)
{
    n_updates++;
    return vm_ops->update(m, in, state, stress, T);
}

/* Updates one plane-stress step of the von Mises point m takes, from stress s0 with gradient H. */
static int updates_of_step(const pm_material *m, const double s0[PM_NS], const double H[4])
{
    const double F0[PM_NF] = {1, 0, 0, 1, 1};
    double state[PM_MAT_MAX_STATE] = {0}, eps_p = 0, F[PM_NF], sg[PM_NS], vol, T[36];
    const pm_point_from from = {F0, s0, state, 1.0, 0};
    n_updates = 0;
    assert_int_equal(pm_point_update(m, PM_PLANE_STRESS, &from, H, 0, 1, 1e-3, m->ops->n_state, F, sg, state, &vol,
                                     &eps_p, T),
                     0);
    return n_updates;
}

static void plane_stress_stops_at_round_off(void **unused)
{
    (void)unused;
    vm_ops = pm_material_find("von_mises");
    assert_non_null(vm_ops);
    pm_material_ops counting = *vm_ops;
    counting.update = counting_update;
    pm_material m;
    memset(&m, 0, sizeof m);
    m.ops = vm_ops;
    m.density = 2700;
    const double sy = 5e7;
    m.param[pm_material_param_index(vm_ops, "yield_stress")] = sy;
    assert_int_equal(pm_material_set_elastic(&m, 7.3e10, 0.2, NAN, NAN), PM_OK);
    if (vm_ops->init)
        assert_int_equal(vm_ops->init(&m), PM_OK);
    m.ops = &counting;
    /* on the yield surface (plane stress: sxx^2 - sxx syy + syy^2 + 3 sxy^2 = sy^2), strained further: the
     * step yields and sigma_zz of the trial is not zero */
    const double s_yield[PM_NS] = {0.5 * sy, -0.2 * sy, 0, sqrt(0.61 / 3.0) * sy};
    const double H_yield[4] = {1e-4, 2e-4, 0, -0.5e-4};
    const int worst_yield = updates_of_step(&m, s_yield, H_yield);
    /* stresses of 0.1-0.2 Pa and strains of 1e-11-1e-10: sigma_zz's round-off floor is the stress of one ulp
     * of the stretch times T_zz (about 1e-5 Pa), far above 1e-10 of the in-plane stress; twenty points
     * (one of them ran to the limit without the floor in the tolerance) */
    int worst_tiny = 0;
    for (int k = 0; k < 20; k++) {
        const double sc = pow(10.0, -1.0 + 0.03 * k), e = 1e-11 * (1 + 0.37 * k);
        const double s_tiny[PM_NS] = {sc, -0.5 * sc, 0, 0.3 * sc}, H_tiny[4] = {e, 0.3 * e, 0, -2 * e};
        const int nk = updates_of_step(&m, s_tiny, H_tiny);
        worst_tiny = nk > worst_tiny ? nk : worst_tiny;
    }
    if (worst_yield > 6 || worst_tiny > 6)
        fail_msg("plane-stress updates per step: %d yielding, %d at a fraction of a pascal (at most 6 expected)",
                 worst_yield, worst_tiny);
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
        cmocka_unit_test(plane_stress_stops_at_round_off),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
