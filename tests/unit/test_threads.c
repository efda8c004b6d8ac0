/* Results do not depend on the thread count or the scatter strategy beyond round-off: a short run
 * of a deforming block with gravity and a frictional base, on 1 thread and on 2 and 4 threads with
 * per-thread buffers and with coloured row blocks, agrees to 1e-12 relative in positions,
 * velocities and stresses (the nodal sums are added in another order, nothing else differs). A
 * layer two cells thin has too few rows for four blocks: the colour scatter then runs on one
 * thread and still agrees. */
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

typedef struct setup {
    int threads;
    const char *scatter; /* PMECH_SCATTER */
    double height;       /* of the block */
} setup;

static pm_sim *run(setup u, pm_scheme scheme, pm_case *c, pm_material *m, pm_case_body *b, pm_case_bc *bc)
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
    b->shape.max[1] = u.height;
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
    assert_int_equal(setenv("PMECH_SCATTER", u.scatter, 1), 0);
    assert_int_equal(pm_sim_create(c, &s, u.threads), 0);
    assert_int_equal(s->scatter, strcmp(u.scatter, "buffers") == 0 ? PM_SCATTER_BUFFERS : PM_SCATTER_COLOUR);
    const double dt = 0.5 * pm_sim_stable_dt(s);
    for (int k = 0; k < 40; k++)
        assert_int_equal(pm_explicit_step(s, dt), 0);
    return s;
}

static double rel(double a, double b, double scale) { return fabs(a - b) / scale; }

/* Run `u` and compare it with one thread; returns whether the last step's colour blocks were disjoint. */
static int check(pm_scheme scheme, setup u)
{
    pm_case c1, c2;
    pm_material m1, m2;
    pm_case_body b1, b2;
    pm_case_bc bc1, bc2;
    setup one = {1, "buffers", u.height};
    pm_sim *s1 = run(one, scheme, &c1, &m1, &b1, &bc1), *s2 = run(u, scheme, &c2, &m2, &b2, &bc2);
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
    const int ok = s2->blocks_ok;
    pm_sim_destroy(s1);
    pm_sim_destroy(s2);
    return ok;
}

static void all_strategies(pm_scheme scheme)
{
    const setup two_buf = {2, "buffers", 0.6}, two_col = {2, "colour", 0.6}, four_col = {4, "colour", 0.6};
    check(scheme, two_buf);
    assert_true(check(scheme, two_col));
    assert_true(check(scheme, four_col));
}

static void musl_1_vs_2_threads(void **st) { (void)st; all_strategies(PM_SCHEME_MUSL); }
static void usl_1_vs_2_threads(void **st) { (void)st; all_strategies(PM_SCHEME_USL); }
static void usf_1_vs_2_threads(void **st) { (void)st; all_strategies(PM_SCHEME_USF); }
static void newmark_1_vs_2_threads(void **st) { (void)st; all_strategies(PM_SCHEME_NEWMARK_PC); }

static void colour_too_few_rows_runs_serially(void **st)
{
    (void)st;
    const setup thin = {2, "colour", 0.05};
    assert_false(check(PM_SCHEME_MUSL, thin));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(musl_1_vs_2_threads),
        cmocka_unit_test(usl_1_vs_2_threads),
        cmocka_unit_test(usf_1_vs_2_threads),
        cmocka_unit_test(newmark_1_vs_2_threads),
        cmocka_unit_test(colour_too_few_rows_runs_serially),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
