/* Point location on unstructured grids: agreement with brute force (also in a hole and outside),
 * the walk from a hint cell, 1e6 random points all found, the linear kind on unstructured
 * quads (isoparametric inverse map) and triangles, and the inverse map of small quads far from the
 * origin. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "shape_check.h"
#include "mesh/mesh_internal.h"
#include "shape/shape_internal.h"

static int32_t brute(const pm_grid *g, const double x[2])
{
    for (size_t c = 0; c < g->n_cells; c++)
        if (pm_grid_cell_contains(g, (int32_t)c, x))
            return (int32_t)c;
    return -1;
}

static void agrees_with_brute_force(void **state)
{
    (void)state;
    for (int el = 0; el < 2; el++) {
        pm_grid g;
        assert_int_equal(sc_jittered_grid(&g, 40, el ? PM_TRI3 : PM_QUAD4, 0.5, 0.2, 5), 0);
        unsigned seed = 9;
        int same = 0, inside = 0;
        const int npts = 20000;
        for (int t = 0; t < npts; t++) {
            /* points also outside the unit square and in the hole */
            double x[2] = {-0.1 + 1.2 * sc_rnd(&seed), -0.1 + 1.2 * sc_rnd(&seed)};
            int32_t c = pm_grid_locate(&g, x), b = brute(&g, x);
            assert_int_equal(c < 0, b < 0);
            if (c >= 0) {
                assert_true(pm_grid_cell_contains(&g, c, x));
                inside++;
            }
            same += c == b;
        }
        printf("%s: %d of %d points agree with brute force exactly (%d inside)\n", el ? "tri3" : "quad4", same, npts,
               inside);
        /* on a shared edge either cell is right; random points essentially never land there */
        assert_int_equal(same, npts);
        pm_grid_free(&g);
    }
}

static void walk_from_hint(void **state)
{
    (void)state;
    pm_grid g;
    assert_int_equal(sc_jittered_grid(&g, 50, PM_TRI3, 0.5, 0.0, 11), 0);
    unsigned seed = 3;
    for (int t = 0; t < 5000; t++) {
        double x[2] = {0.05 + 0.9 * sc_rnd(&seed), 0.05 + 0.9 * sc_rnd(&seed)};
        int32_t c = pm_grid_locate(&g, x);
        double y[2] = {x[0] + 0.03 * (sc_rnd(&seed) - 0.5), x[1] + 0.03 * (sc_rnd(&seed) - 0.5)};
        int32_t d = pm_grid_locate_from(&g, y, c);
        assert_int_equal(d, brute(&g, y));
    }
    double out[2] = {1.5, 0.5};
    assert_int_equal(pm_grid_locate_from(&g, out, 0), -1);
    pm_grid_free(&g);
}

/* A million random points of the unit square all land in a cell (the mesh has no hole here), and a
 * sample of them in the one brute force finds. How fast this goes is bench/'s concern, not a test's. */
static void million_points_all_found(void **state)
{
    (void)state;
    pm_grid g;
    assert_int_equal(sc_jittered_grid(&g, 300, PM_TRI3, 0.5, 0.0, 17), 0);
    const size_t n = 1000000;
    double *x = malloc(PM_DIM * n * sizeof(double));
    unsigned seed = 23;
    for (size_t i = 0; i < PM_DIM * n; i++)
        x[i] = sc_rnd(&seed);
    long found = 0;
    for (size_t i = 0; i < n; i++) {
        const int32_t c = pm_grid_locate(&g, x + PM_DIM * i);
        found += c >= 0;
        if (i % 10000 == 0)
            assert_int_equal(c, brute(&g, x + PM_DIM * i));
    }
    assert_int_equal(found, (long)n);
    free(x);
    pm_grid_free(&g);
}

static void linear_on_unstructured(void **state)
{
    (void)state;
    for (int el = 0; el < 2; el++) {
        pm_grid g;
        assert_int_equal(sc_jittered_grid(&g, 12, el ? PM_TRI3 : PM_QUAD4, 0.5, 0.25, 29), 0);
        pm_approx *a;
        assert_int_equal(pm_approx_create("linear", &g, &a), 0);
        pm_particles p;
        const double lo[2] = {0, 0}, hi[2] = {1, 1};
        sc_random_particles(&p, 3000, lo, hi, 0, 31);
        /* drop the points in the hole */
        size_t k = 0;
        for (size_t i = 0; i < p.n; i++)
            if (pm_grid_locate(&g, p.x + 2 * i) >= 0) {
                p.x[2 * k] = p.x[2 * i];
                p.x[2 * k + 1] = p.x[2 * i + 1];
                k++;
            }
        p.n = k;
        assert_int_equal(a->ops->connect(a, &p), 0);
        sc_errors e = sc_check(a, &p, 0);
        sc_print(el ? "linear, unstructured tri3" : "linear, unstructured quad4 (isoparametric)", &e);
        assert_true(e.pu < 1e-10 && e.grad_sum < 1e-10 && e.xrep < 1e-10 && e.urep < 1e-10 && e.grep < 1e-10);
        assert_true(e.min_n > -1e-10);
        pm_particles_free(&p);
        pm_approx_destroy(a);
        pm_grid_free(&g);
    }
}

/* Cells of 20 mm 3 m from the origin (a silo's wall near its top): the coordinates' rounding is
 * then larger than 1e-14 of a cell, which a convergence test on the cell's size alone never reached.
 * Points mapped forward from known (xi, eta) must come back to them, to 1e-9 (rounding of the
 * coordinates, 5e-16, over the cell's 0.02 m half-width is 2e-14; a wrong root or an unconverged
 * iteration is off by far more). */
static void inverse_map_far_from_origin(void **state)
{
    (void)state;
    for (int jit = 0; jit < 2; jit++) {
        pm_grid g;
        const int n = 12;
        assert_int_equal(sc_jittered_grid(&g, n, PM_QUAD4, jit ? 0.4 : 0.0, 0.0, 41), 0);
        for (size_t k = 0; k < g.n_nodes; k++) {
            g.x[2 * k] = 0.7 + 0.02 * n * g.x[2 * k];
            g.x[2 * k + 1] = 3.0 + 0.02 * n * g.x[2 * k + 1];
        }
        unsigned seed = 43;
        for (size_t c = 0; c < g.n_cells; c++) {
            const int32_t *v = g.conn + 4 * c;
            for (int t = 0; t < 20; t++) {
                const double xi0[2] = {-0.95 + 1.9 * sc_rnd(&seed), -0.95 + 1.9 * sc_rnd(&seed)};
                static const double XI[4] = {-1, 1, 1, -1}, ETA[4] = {-1, -1, 1, 1};
                double x[2] = {0, 0}, xi[2];
                for (int q = 0; q < 4; q++) {
                    const double w = 0.25 * (1 + XI[q] * xi0[0]) * (1 + ETA[q] * xi0[1]);
                    x[0] += w * g.x[2 * v[q]];
                    x[1] += w * g.x[2 * v[q] + 1];
                }
                assert_true(pm_quad4_inverse_map(&g, (int32_t)c, x, xi) >= 0);
                assert_true(fabs(xi[0] - xi0[0]) < 1e-9 && fabs(xi[1] - xi0[1]) < 1e-9);
                pm_stencil s;
                assert_int_equal(pm_quad4_iso_eval(&g, (int32_t)c, x, &s), 0);
                double pu = 0, gx = 0, gy = 0;
                for (int q = 0; q < 4; q++) {
                    pu += s.N[q];
                    gx += s.dN[q][0];
                    gy += s.dN[q][1];
                }
                /* partition of unity and its zero gradient, to rounding of N (1e-16) and dN (1e-14 / m) */
                assert_true(fabs(pu - 1) < 1e-12 && fabs(gx) < 1e-9 && fabs(gy) < 1e-9);
            }
        }
        pm_grid_free(&g);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(agrees_with_brute_force),
        cmocka_unit_test(walk_from_hint),
        cmocka_unit_test(million_points_all_found),
        cmocka_unit_test(linear_on_unstructured),
        cmocka_unit_test(inverse_map_far_from_origin),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
