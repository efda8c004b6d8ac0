/* Linear shape functions on quad4 and tri3: partition of unity, linear reproduction and
 * gradient consistency to 1e-12 (exact in exact arithmetic; 1e-12 leaves room for round-off on
 * coordinates of order 10). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "shape/approx_internal.h"
#include "pmech/grid.h"
#include "pmech/particles.h"
#include "shape_check.h"


static void check_reproduction(pm_element el)
{
    pm_grid g;
    const double origin[2] = {-1.5, 2.0}, size[2] = {7.0, 3.0};
    const int cells[2] = {7, 5};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, el), 0);
    pm_approx *a;
    assert_int_equal(pm_approx_create("linear", &g, &a), 0);
    pm_particles p;
    const size_t n = 2000;
    assert_int_equal(pm_particles_alloc(&p, n, 0), 0);
    unsigned seed = 7;
    for (size_t i = 0; i < n; i++) {
        p.x[2 * i] = origin[0] + size[0] * sc_rnd(&seed);
        p.x[2 * i + 1] = origin[1] + size[1] * sc_rnd(&seed);
    }
    assert_int_equal(a->ops->connect(a, &p), 0);
    /* partition of unity, linear reproduction and gradient consistency to 1e-12 (round-off of
     * bilinear and linear functions on cells of size 0.6 to 1) */
    const sc_errors e = sc_check(a, &p, 0.0);
    assert_true(e.min_n >= -1e-12);
    assert_true(e.pu < 1e-12 && e.grad_sum < 1e-12 && e.xrep < 1e-12);
    assert_true(e.urep < 1e-12 && e.grep < 1e-12);
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

static void quad4_reproduces_linear_fields(void **state)
{
    (void)state;
    check_reproduction(PM_QUAD4);
}

static void tri3_reproduces_linear_fields(void **state)
{
    (void)state;
    check_reproduction(PM_TRI3);
}

/* The inlined quad4 path of the solvers must equal the generic one bit for bit. */
static void inline_quad_matches_generic(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {1, 2};
    const int cells[2] = {4, 8};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    pm_approx *a;
    assert_int_equal(pm_approx_create("linear", &g, &a), 0);
    pm_particles p;
    assert_int_equal(pm_particles_alloc(&p, 1, 0), 0);
    p.x[0] = 0.61;
    p.x[1] = 1.37;
    assert_int_equal(a->ops->connect(a, &p), 0);
    pm_stencil st;
    assert_int_equal(a->ops->eval(a, &p, 0, &st), 0);
    int32_t node[4];
    double N[4], dN[8];
    pm_linear_quad_eval(&g, p.x, p.cell[0], node, N, dN);
    for (int k = 0; k < 4; k++) {
        assert_int_equal(node[k], st.node[k]);
        assert_true(N[k] == st.N[k] && dN[2 * k] == st.dN[k][0] && dN[2 * k + 1] == st.dN[k][1]);
    }
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

static void unknown_shape_function_is_input_error(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {1, 1};
    const int cells[2] = {1, 1};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    pm_approx *a = NULL;
    assert_int_equal(pm_approx_create("cubic_hermite", &g, &a), -1);
    assert_null(a);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(quad4_reproduces_linear_fields),
        cmocka_unit_test(tri3_reproduces_linear_fields),
        cmocka_unit_test(inline_quad_matches_generic),
        cmocka_unit_test(unknown_shape_function_is_input_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
