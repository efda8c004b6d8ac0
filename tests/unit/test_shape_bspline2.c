/* Quadratic B-splines: partition of unity, linear reproduction and gradient consistency to 1e-10
 * everywhere in the grid (the ghost nodes outside the edges are folded in by linear extrapolation),
 * gradients equal to finite differences, the uniform B-spline in the interior, the linear hat
 * functions in the half cell next to an edge, non-negative values. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "shape_check.h"

static void check_grid(const int cells[2], unsigned seed)
{
    pm_grid g;
    const double origin[2] = {-1.5, 2.0}, size[2] = {7.0, 3.0};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    pm_approx *a;
    assert_int_equal(pm_approx_create("bspline2", &g, &a), 0);
    pm_particles p;
    const double lo[2] = {g.lo[0], g.lo[1]}, hi[2] = {g.hi[0], g.hi[1]};
    sc_random_particles(&p, 3000, lo, hi, 0, seed);
    assert_int_equal(a->ops->connect(a, &p), 0);
    sc_errors e = sc_check(a, &p, 1e-7);
    char what[64];
    snprintf(what, sizeof what, "bspline2, %d x %d cells, whole grid", cells[0], cells[1]);
    sc_print(what, &e);
    assert_true(e.pu < 1e-10 && e.grad_sum < 1e-10 && e.xrep < 1e-10 && e.urep < 1e-10 && e.grep < 1e-10);
    assert_true(e.fd < 1e-5);
    assert_true(e.min_n >= -1e-15);
    assert_true(e.max_nodes <= 9);
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

static void reproduces_linear_fields(void **state)
{
    (void)state;
    const int c1[2] = {7, 6}, c2[2] = {1, 2}, c3[2] = {3, 1};
    check_grid(c1, 3);
    check_grid(c2, 5);
    check_grid(c3, 7);
}

static double bspline_1d(double d)
{
    d = fabs(d);
    if (d <= 0.5)
        return 0.75 - d * d;
    if (d <= 1.5)
        return 0.5 * (1.5 - d) * (1.5 - d);
    return 0;
}

static void interior_and_edge_values(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {6, 6};
    const int cells[2] = {6, 6};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    pm_approx *a;
    assert_int_equal(pm_approx_create("bspline2", &g, &a), 0);
    pm_particles p;
    const double lo[2] = {0, 0}, hi[2] = {6, 6};
    sc_random_particles(&p, 2000, lo, hi, 0, 17);
    assert_int_equal(a->ops->connect(a, &p), 0);
    double w_int = 0, w_edge = 0;
    for (size_t i = 0; i < p.n; i++) {
        pm_stencil st;
        assert_int_equal(a->ops->eval(a, &p, i, &st), 0);
        const double x = p.x[2 * i], y = p.x[2 * i + 1];
        int interior = x > 1.5 && x < 4.5 && y > 1.5 && y < 4.5;
        int edge_half = x < 0.5 && y > 1.5 && y < 4.5;
        for (int k = 0; k < st.n; k++) {
            const double *xn = g.x + 2 * st.node[k];
            if (interior)
                w_int = fmax(w_int, fabs(st.N[k] - bspline_1d(x - xn[0]) * bspline_1d(y - xn[1])));
            if (edge_half) {
                double hx = fmax(0.0, 1 - fabs(x - xn[0]));
                w_edge = fmax(w_edge, fabs(st.N[k] - hx * bspline_1d(y - xn[1])));
            }
        }
    }
    printf("bspline2: interior vs uniform B-spline %.2e, edge half-cell vs hat x B-spline %.2e\n", w_int, w_edge);
    assert_true(w_int < 1e-13 && w_edge < 1e-13);
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reproduces_linear_fields),
        cmocka_unit_test(interior_and_edge_values),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
