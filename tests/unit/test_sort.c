/* Sorting particles by cell changes only their order: a run that sorts every step and one that never
 * sorts agree particle by particle (matched by initial position) to 1e-12 relative (round-off of the
 * summation order), and after a sort the cells are in non-decreasing order. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "pmech/material.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"

static pm_case c;
static pm_material m;
static pm_case_body b;

static pm_sim *make(void)
{
    memset(&c, 0, sizeof c);
    strcpy(c.file, "sort.json");
    strcpy(c.shape_function, "linear");
    c.dimension = 2;
    c.analysis.scheme = PM_SCHEME_MUSL;
    c.analysis.cfl = 0.3;
    c.analysis.end_time = 1;
    c.analysis.gravity[1] = -9.81;
    c.grid.size[0] = c.grid.size[1] = 1.0;
    c.grid.cells[0] = c.grid.cells[1] = 20;
    memset(&m, 0, sizeof m);
    m.ops = pm_material_find("linear_elastic");
    m.density = 1000;
    pm_material_set_elastic(&m, 1e4, 0.3, NAN, NAN);
    c.materials = &m;
    c.n_materials = 1;
    memset(&b, 0, sizeof b);
    b.shape.type = PM_SHAPE_CIRCLE;
    b.shape.center[0] = b.shape.center[1] = 0.5;
    b.shape.radius = 0.3;
    b.velocity[0] = 0.8;
    b.velocity[1] = 0.5;
    c.bodies = &b;
    c.n_bodies = 1;
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(&c, &s, 1), 0);
    return s;
}

static void sorting_changes_only_the_order(void **st)
{
    (void)st;
    pm_sim *a = make(), *z = make();
    a->sort_interval = 1;
    z->sort_interval = 0;
    const double dt = 0.5 * pm_sim_stable_dt(a);
    for (int k = 0; k < 60; k++) {
        assert_int_equal(pm_explicit_step(a, dt), 0);
        assert_int_equal(pm_explicit_step(z, dt), 0);
    }
    /* after a sort the cells are ordered */
    assert_int_equal(a->approx->ops->connect(a->approx, &a->p), 0);
    pm_sim_sort_particles(a);
    for (size_t i = 1; i < a->p.n; i++)
        assert_true(a->p.cell[i - 1] <= a->p.cell[i]);
    int moved = 0;
    for (size_t i = 0; i < z->p.n; i++) {
        size_t j = 0;
        while (j < a->p.n && !(a->p.x0[2 * j] == z->p.x0[2 * i] && a->p.x0[2 * j + 1] == z->p.x0[2 * i + 1]))
            j++;
        assert_true(j < a->p.n);
        moved |= j != i;
        for (int d = 0; d < 2; d++) {
            assert_true(fabs(a->p.x[2 * j + d] - z->p.x[2 * i + d]) <= 1e-12);
            assert_true(fabs(a->p.v[2 * j + d] - z->p.v[2 * i + d]) <= 1e-12);
        }
        for (int k = 0; k < PM_NS; k++)
            assert_true(fabs(a->p.stress[PM_NS * j + k] - z->p.stress[PM_NS * i + k]) <=
                        1e-12 * (1 + fabs(z->p.stress[PM_NS * i + k])));
    }
    assert_true(moved); /* the body crossed cells, so the sort did reorder */
    pm_sim_destroy(a);
    pm_sim_destroy(z);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(sorting_changes_only_the_order)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
