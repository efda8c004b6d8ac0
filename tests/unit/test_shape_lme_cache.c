/* LME stencils kept per particle between evaluations: an evaluation at an unchanged position returns
 * the kept stencil bit for bit; after a move (1e-6 h to 0.9 h, warm-started Newton) or a permutation
 * of the particles (slots now hold other particles) the values and gradients equal a cold solve
 * from lambda = 0. Both solves stop at |sum N_I d_I| <= 1e-14 h, which moves N by about 1e-13:
 * tolerance 1e-10 on N and on h dN. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "shape_check.h"

/* Largest difference of N and h dN between two stencils, matched by node; -1 if the node sets differ. */
static double stencil_diff(const pm_stencil *a, const pm_stencil *b, double h)
{
    if (a->n != b->n)
        return -1;
    double worst = 0;
    for (int k = 0; k < a->n; k++) {
        int m = 0;
        while (m < b->n && b->node[m] != a->node[k])
            m++;
        if (m == b->n)
            return -1;
        worst = fmax(worst, fabs(a->N[k] - b->N[m]));
        worst = fmax(worst, h * fmax(fabs(a->dN[k][0] - b->dN[m][0]), fabs(a->dN[k][1] - b->dN[m][1])));
    }
    return worst;
}

/* Evaluate every particle with the kept-stencil approximation `a` and a fresh one (cold start). */
static double compare_cold(const pm_grid *g, pm_approx *a, pm_particles *p, double h)
{
    pm_approx *cold = NULL;
    assert_int_equal(pm_approx_create("lme", g, &cold), 0);
    assert_int_equal(a->ops->connect(a, p), 0);
    double worst = 0;
    for (size_t i = 0; i < p->n; i++) {
        pm_stencil s, c;
        assert_int_equal(a->ops->eval(a, p, i, &s), 0);
        assert_int_equal(cold->ops->eval(cold, p, i, &c), 0); /* never connected: no slots, cold */
        double d = stencil_diff(&s, &c, h);
        assert_true(d >= 0);
        worst = fmax(worst, d);
    }
    pm_approx_destroy(cold);
    return worst;
}

static void check_grid(pm_element el)
{
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {4, 3};
    const int cells[2] = {16, 12};
    const double h = 0.25;
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, el), 0);
    pm_approx *a = NULL;
    assert_int_equal(pm_approx_create("lme", &g, &a), 0);
    pm_particles p;
    const double lo[2] = {1, 1}, hi[2] = {3, 2};
    sc_random_particles(&p, 500, lo, hi, 0, 17);
    assert_int_equal(a->ops->connect(a, &p), 0);
    /* unchanged position: the kept stencil, bit for bit */
    for (size_t i = 0; i < p.n; i++) {
        pm_stencil s1, s2;
        assert_int_equal(a->ops->eval(a, &p, i, &s1), 0);
        assert_int_equal(a->ops->eval(a, &p, i, &s2), 0);
        assert_int_equal(s1.n, s2.n);
        assert_memory_equal(s1.node, s2.node, (size_t)s1.n * sizeof(int32_t));
        assert_memory_equal(s1.N, s2.N, (size_t)s1.n * sizeof(double));
        assert_memory_equal(s1.dN, s2.dN, (size_t)s1.n * sizeof s1.dN[0]);
    }
    /* moves of growing size, each warm-started from the previous position */
    unsigned seed = 23;
    const double moves[5] = {1e-6, 1e-4, 1e-2, 0.3, 0.9};
    for (int m = 0; m < 5; m++) {
        for (size_t i = 0; i < p.n; i++) {
            const double ang = 6.283185307179586 * sc_rnd(&seed);
            p.x[2 * i] += moves[m] * h * cos(ang);
            p.x[2 * i + 1] += moves[m] * h * sin(ang);
        }
        double worst = compare_cold(&g, a, &p, h);
        printf("lme %s, move %.0e h: warm against cold %.1e\n", el == PM_QUAD4 ? "quad4" : "tri3", moves[m], worst);
        assert_true(worst < 1e-10);
    }
    /* reverse the particles: every slot now holds another particle's stencil */
    for (size_t i = 0; i < p.n / 2; i++) {
        size_t j = p.n - 1 - i;
        for (int d = 0; d < 2; d++) {
            double t = p.x[2 * i + d];
            p.x[2 * i + d] = p.x[2 * j + d];
            p.x[2 * j + d] = t;
        }
        int32_t c = p.cell[i];
        p.cell[i] = p.cell[j];
        p.cell[j] = c;
    }
    double worst = compare_cold(&g, a, &p, h);
    printf("lme %s, permuted particles: warm against cold %.1e\n", el == PM_QUAD4 ? "quad4" : "tri3", worst);
    assert_true(worst < 1e-10);
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

static void kept_stencils_equal_cold_solves(void **state)
{
    (void)state;
    check_grid(PM_QUAD4);
    check_grid(PM_TRI3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(kept_stencils_equal_cold_solves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
