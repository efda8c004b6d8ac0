/* uGIMP shape functions: partition of unity, linear reproduction and gradient consistency to 1e-10
 * for every particle inside the grid (the boundary cells' hat functions are continued linearly,
 * so this holds at the edges too), gradients equal to finite differences, the classic closed form
 * in the interior, and refusal of grids it does not support. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "shape_check.h"

static void check_grid(double hs_cells, unsigned seed)
{
    pm_grid g;
    const double origin[2] = {-1.5, 2.0}, size[2] = {7.0, 3.0};
    const int cells[2] = {7, 6};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    pm_approx *a;
    assert_int_equal(pm_approx_create("gimp", &g, &a), 0);
    pm_particles p;
    const double lo[2] = {g.lo[0], g.lo[1]}, hi[2] = {g.hi[0], g.hi[1]};
    sc_random_particles(&p, 3000, lo, hi, hs_cells * g.h[1], seed);
    assert_int_equal(a->ops->connect(a, &p), 0);
    sc_errors e = sc_check(a, &p, 1e-7);
    char what[64];
    snprintf(what, sizeof what, "gimp, half-size %.3g h, whole grid", hs_cells);
    sc_print(what, &e);
    assert_true(e.pu < 1e-10 && e.grad_sum < 1e-10 && e.xrep < 1e-10 && e.urep < 1e-10 && e.grep < 1e-10);
    assert_true(e.fd < 1e-5);
    assert_true(e.max_nodes <= 16);
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

static void reproduces_linear_fields(void **state)
{
    (void)state;
    check_grid(0.25, 3); /* 2 particles per cell */
    check_grid(1.0 / 6, 5); /* 3 per cell */
    check_grid(0.5, 7);  /* 1 per cell: the domain fills the cell */
    check_grid(0.8, 9);  /* larger than half a cell still works */
    check_grid(0.0, 11); /* zero size: the linear hat functions */
}

/* Interior values against the closed form of Bardenhagen & Kober (l <= h/2). */
static double gimp_1d(double d, double h, double l)
{
    d = fabs(d);
    if (d < l)
        return 1 - (d * d + l * l) / (2 * h * l);
    if (d < h - l)
        return 1 - d / h;
    if (d < h + l)
        return (h + l - d) * (h + l - d) / (4 * h * l);
    return 0;
}

static void matches_closed_form(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {4, 4};
    const int cells[2] = {4, 4};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    pm_approx *a;
    assert_int_equal(pm_approx_create("gimp", &g, &a), 0);
    pm_particles p;
    const double lo[2] = {1.3, 1.3}, hi[2] = {2.7, 2.7};
    sc_random_particles(&p, 500, lo, hi, 0.3, 13);
    assert_int_equal(a->ops->connect(a, &p), 0);
    double worst = 0;
    for (size_t i = 0; i < p.n; i++) {
        pm_stencil st;
        assert_int_equal(a->ops->eval(a, &p, i, &st), 0);
        for (int k = 0; k < st.n; k++) {
            const double *xn = g.x + 2 * st.node[k];
            double ref = gimp_1d(p.x[2 * i] - xn[0], 1.0, 0.3) * gimp_1d(p.x[2 * i + 1] - xn[1], 1.0, 0.3);
            worst = fmax(worst, fabs(st.N[k] - ref));
        }
    }
    printf("gimp vs closed form, interior: %.2e\n", worst);
    assert_true(worst < 1e-13);
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

static void refuses_tri_grids(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {1, 1};
    const int cells[2] = {2, 2};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_TRI3), 0);
    pm_approx *a = NULL;
    assert_int_equal(pm_approx_create("gimp", &g, &a), -1);
    assert_null(a);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reproduces_linear_fields),
        cmocka_unit_test(matches_closed_form),
        cmocka_unit_test(refuses_tri_grids),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
