/* Results do not depend on the thread count beyond round-off: a short run of a deforming block
 * with gravity and a fixed base, on 1 and 2 threads, agrees to 1e-12 relative in positions,
 * velocities and stresses (the per-thread scatter buffers are summed in another order, nothing
 * else differs). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "pmech/material.h"
#include "pmech/sim.h"

static pm_sim *run(int threads, pm_scheme scheme, pm_case *c, pm_material *m, pm_case_body *b, pm_case_bc *bc)
{
    memset(c, 0, sizeof *c);
    strcpy(c->file, "threads.json");
    strcpy(c->shape_function, "linear");
    c->dimension = 2;
    c->analysis.scheme = scheme;
    c->analysis.cfl = 0.3;
    c->analysis.end_time = 1;
    c->analysis.gravity[1] = -9.81;
    c->grid.size[0] = 1.2;
    c->grid.size[1] = 1.1;
    c->grid.origin[0] = -0.1;
    c->grid.cells[0] = 48;
    c->grid.cells[1] = 44;
    memset(m, 0, sizeof *m);
    m->ops = pm_material_find("linear_elastic");
    m->density = 1000;
    pm_material_set_elastic(m, 1e5, 0.3, NAN, NAN);
    c->materials = m;
    c->n_materials = 1;
    memset(b, 0, sizeof *b);
    b->shape.type = PM_SHAPE_RECTANGLE;
    b->shape.max[0] = 1.0;
    b->shape.max[1] = 0.6;
    b->velocity[0] = 0.3;
    c->bodies = b;
    c->n_bodies = 1;
    memset(bc, 0, sizeof *bc);
    bc->type = PM_BC_FRICTION;
    bc->line_axis = -1;
    strcpy(bc->boundary, "y_min");
    bc->coefficient = 0.3;
    c->bcs = bc;
    c->n_bcs = 1;
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(c, &s, threads), 0);
    const double dt = 0.5 * pm_sim_stable_dt(s);
    for (int k = 0; k < 40; k++)
        assert_int_equal(pm_explicit_step(s, dt), 0);
    return s;
}

static double rel(double a, double b, double scale) { return fabs(a - b) / scale; }

static void check(pm_scheme scheme)
{
    pm_case c1, c2;
    pm_material m1, m2;
    pm_case_body b1, b2;
    pm_case_bc bc1, bc2;
    pm_sim *s1 = run(1, scheme, &c1, &m1, &b1, &bc1), *s2 = run(2, scheme, &c2, &m2, &b2, &bc2);
    assert_int_equal(s1->p.n, s2->p.n);
    double smax = 0, vmax = 0;
    for (size_t i = 0; i < s1->p.n; i++) {
        for (int k = 0; k < PM_NS; k++)
            smax = fmax(smax, fabs(s1->p.stress[PM_NS * i + k]));
        vmax = fmax(vmax, hypot(s1->p.v[2 * i], s1->p.v[2 * i + 1]));
    }
    assert_true(smax > 0 && vmax > 0);
    for (size_t i = 0; i < s1->p.n; i++) {
        for (int d = 0; d < 2; d++) {
            assert_true(rel(s1->p.x[2 * i + d], s2->p.x[2 * i + d], 1.0) <= 1e-12);
            assert_true(rel(s1->p.v[2 * i + d], s2->p.v[2 * i + d], vmax) <= 1e-12);
        }
        for (int k = 0; k < PM_NS; k++)
            assert_true(rel(s1->p.stress[PM_NS * i + k], s2->p.stress[PM_NS * i + k], smax) <= 1e-12);
    }
    pm_sim_destroy(s1);
    pm_sim_destroy(s2);
}

static void musl_1_vs_2_threads(void **st) { (void)st; check(PM_SCHEME_MUSL); }
static void usf_1_vs_2_threads(void **st) { (void)st; check(PM_SCHEME_USF); }
static void newmark_1_vs_2_threads(void **st) { (void)st; check(PM_SCHEME_NEWMARK_PC); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(musl_1_vs_2_threads),
        cmocka_unit_test(usf_1_vs_2_threads),
        cmocka_unit_test(newmark_1_vs_2_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
