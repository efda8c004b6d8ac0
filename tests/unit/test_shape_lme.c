/* Local max-ent shape functions on grid nodes (seed 003 section 2.3): partition of unity, linear
 * reproduction and gradient consistency to 1e-10 for points inside the grid, gradients (eq. 39)
 * equal to finite differences, the limit of large gamma (bilinear Q4 on a square grid), Newton
 * iteration counts, and the support cap. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "shape_check.h"
#include "shape/shape_internal.h"

static void check_gamma(double gamma, pm_element el, unsigned seed)
{
    pm_grid g;
    const double origin[2] = {-1.5, 2.0}, size[2] = {7.0, 3.0};
    const int cells[2] = {14, 6};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, el), 0);
    pm_approx *a;
    pm_approx_opts o = {.lme_gamma = gamma, .support_radius = NAN};
    assert_int_equal(pm_approx_create_opts("lme", &g, &o, &a), 0);
    pm_particles p;
    /* strictly inside: on the hull of the nodes lambda diverges */
    const double lo[2] = {g.lo[0] + 1e-3, g.lo[1] + 1e-3}, hi[2] = {g.hi[0] - 1e-3, g.hi[1] - 1e-3};
    sc_random_particles(&p, 2000, lo, hi, 0, seed);
    assert_int_equal(a->ops->connect(a, &p), 0);
    sc_errors e = sc_check(a, &p, 1e-7);
    char what[64];
    snprintf(what, sizeof what, "lme, gamma %.3g, %s grid", gamma, el == PM_QUAD4 ? "quad4" : "tri3");
    sc_print(what, &e);
    assert_true(e.pu < 1e-10 && e.grad_sum < 1e-10 && e.xrep < 1e-10 && e.urep < 1e-10 && e.grep < 1e-10);
    assert_true(e.fd < 1e-5 * gamma);
    assert_true(e.min_n >= 0);
    assert_true(e.max_nodes <= PM_STENCIL_MAX);
    pm_particles_free(&p);
    pm_approx_destroy(a);
    pm_grid_free(&g);
}

static void reproduces_linear_fields(void **state)
{
    (void)state;
    check_gamma(1.8, PM_QUAD4, 3);
    check_gamma(0.8, PM_QUAD4, 5); /* wide support: capped at 64 nodes */
    check_gamma(4.0, PM_QUAD4, 7);
    check_gamma(1.8, PM_TRI3, 9);
}

/* Large gamma: the maximum-entropy choice among the four cocircular corners of a square cell is
 * the bilinear Q4 function (independent xi and eta). */
static void large_gamma_tends_to_q4(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {5, 5};
    const int cells[2] = {5, 5};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    pm_particles p;
    const double lo[2] = {1, 1}, hi[2] = {4, 4};
    sc_random_particles(&p, 400, lo, hi, 0, 21);
    const double gammas[4] = {4, 10, 30, 100};
    double prev = INFINITY;
    for (int k = 0; k < 4; k++) {
        pm_approx *a, *lin;
        pm_approx_opts o = {.lme_gamma = gammas[k], .support_radius = NAN};
        assert_int_equal(pm_approx_create_opts("lme", &g, &o, &a), 0);
        assert_int_equal(pm_approx_create("linear", &g, &lin), 0);
        assert_int_equal(a->ops->connect(a, &p), 0);
        double worst = 0, worst_g = 0;
        for (size_t i = 0; i < p.n; i++) {
            pm_stencil s, l;
            assert_int_equal(a->ops->eval(a, &p, i, &s), 0);
            assert_int_equal(lin->ops->eval(lin, &p, i, &l), 0);
            for (int q = 0; q < s.n; q++) {
                double ref = 0, rg[2] = {0, 0};
                for (int m = 0; m < l.n; m++)
                    if (l.node[m] == s.node[q]) {
                        ref = l.N[m];
                        rg[0] = l.dN[m][0];
                        rg[1] = l.dN[m][1];
                    }
                worst = fmax(worst, fabs(s.N[q] - ref));
                /* gradients converge away from the cell edges, where Q4's gradient jumps */
                const double fx = fmod(p.x[2 * i], 1.0), fy = fmod(p.x[2 * i + 1], 1.0);
                if (fx > 0.2 && fx < 0.8 && fy > 0.2 && fy < 0.8)
                    worst_g = fmax(worst_g, fmax(fabs(s.dN[q][0] - rg[0]), fabs(s.dN[q][1] - rg[1])));
            }
        }
        printf("lme gamma %5.1f: max |N - N_Q4| = %.2e, max |dN - dN_Q4| (cell interiors) = %.2e\n", gammas[k], worst,
               worst_g);
        assert_true(worst < prev || worst < 1e-12);
        prev = worst;
        pm_approx_destroy(a);
        pm_approx_destroy(lin);
    }
    assert_true(prev < 1e-3);
    pm_particles_free(&p);
    pm_grid_free(&g);
}

/* Newton iterations of the lambda solve, reported over random points for several gammas. */
static void newton_converges(void **state)
{
    (void)state;
    const double gammas[5] = {0.8, 1.8, 4, 10, 100};
    unsigned seed = 33;
    for (int k = 0; k < 5; k++) {
        int it_max = 0;
        long it_sum = 0;
        const int npts = 2000;
        for (int t = 0; t < npts; t++) {
            /* nodes of a unit grid around a point inside the centre cell (5 x 5 nodes) */
            double d[25][2], N[25], dN[25][2], lam[2] = {0, 0};
            double x = 2 + sc_rnd(&seed), y = 2 + sc_rnd(&seed);
            int n = 0;
            for (int j = 0; j < 5; j++)
                for (int i = 0; i < 5; i++) {
                    d[n][0] = x - i;
                    d[n][1] = y - j;
                    n++;
                }
            int it = pm_lme_solve(n, (const double (*)[2])d, gammas[k], PM_LME_TOL, lam, N, dN);
            assert_true(it >= 0);
            it_max = it > it_max ? it : it_max;
            it_sum += it;
        }
        printf("lme Newton, gamma %5.1f: mean %.2f, max %d iterations (|r| <= 1e-14 h)\n", gammas[k],
               (double)it_sum / npts, it_max);
        assert_true(it_max <= 30);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reproduces_linear_fields),
        cmocka_unit_test(large_gamma_tends_to_q4),
        cmocka_unit_test(newton_converges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
