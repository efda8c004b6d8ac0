/* Structured grids: node/cell counts, boundary sets, and point location against brute force. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/grid.h"

/* Brute force: the cell whose element contains the point (barycentric / box test). */
static int inside_cell(const pm_grid *g, size_t c, const double x[2])
{
    const int32_t *n = g->conn + (size_t)g->nodes_per_cell * c;
    if (g->element == PM_QUAD4) {
        const double *a = g->x + 2 * n[0], *b = g->x + 2 * n[2];
        return x[0] >= a[0] - 1e-12 && x[0] <= b[0] + 1e-12 && x[1] >= a[1] - 1e-12 && x[1] <= b[1] + 1e-12;
    }
    for (int k = 0; k < 3; k++) {
        const double *p = g->x + 2 * n[k], *q = g->x + 2 * n[(k + 1) % 3];
        if ((q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0]) < -1e-12)
            return 0;
    }
    return 1;
}

static void locate_agrees_with_brute_force(void **state)
{
    (void)state;
    for (int el = 0; el < 2; el++) {
        pm_grid g;
        const double origin[2] = {1, -2}, size[2] = {3, 2};
        const int cells[2] = {6, 5};
        assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, (pm_element)el), 0);
        assert_int_equal(g.n_nodes, 7 * 6);
        assert_int_equal(g.n_cells, el == PM_QUAD4 ? 30 : 60);
        unsigned seed = 3;
        for (int i = 0; i < 5000; i++) {
            double x[2] = {origin[0] + size[0] * rand_r(&seed) / RAND_MAX,
                           origin[1] + size[1] * rand_r(&seed) / RAND_MAX};
            int32_t c = pm_grid_locate(&g, x);
            assert_true(c >= 0);
            assert_true(inside_cell(&g, (size_t)c, x));
        }
        double out[2] = {origin[0] - 0.01, 0};
        assert_int_equal(pm_grid_locate(&g, out), -1);
        double nan_pt[2] = {NAN, 0};
        assert_int_equal(pm_grid_locate(&g, nan_pt), -1);
        double corner[2] = {origin[0] + size[0], origin[1] + size[1]};
        assert_true(pm_grid_locate(&g, corner) >= 0);
        pm_grid_free(&g);
    }
}

static void sides_hold_their_nodes(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {2, 1};
    const int cells[2] = {4, 3};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    const pm_node_set *s = pm_grid_find_set(&g, "y_min");
    assert_non_null(s);
    assert_int_equal(s->n, 5);
    assert_true(s->normal[1] == -1.0);
    s = pm_grid_find_set(&g, "x_max");
    assert_non_null(s);
    assert_int_equal(s->n, 4);
    for (size_t i = 0; i < s->n; i++)
        assert_true(g.x[2 * s->nodes[i]] == 2.0);
    assert_null(pm_grid_find_set(&g, "z_min"));
    assert_true(pm_grid_add_line_set(&g, "mid", 0, 1.0, NULL) >= 0);
    assert_int_equal(pm_grid_find_set(&g, "mid")->n, 4);
    assert_true(pm_grid_add_line_set(&g, "none", 0, 0.3, NULL) < 0);
    pm_grid_free(&g);
}

static void nonsense_sizes_are_rejected(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {-1, 1};
    const int cells[2] = {4, 3};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(locate_agrees_with_brute_force),
        cmocka_unit_test(sides_hold_their_nodes),
        cmocka_unit_test(nonsense_sizes_are_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
