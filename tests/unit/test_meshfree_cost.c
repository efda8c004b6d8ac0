/* Cost per point of the meshfree building blocks, printed for docs/meshfree.md (not a timed test:
 * nothing is asserted about the times, which depend on the machine and its load). What is
 * asserted is that the timed loops computed what they should: each query found exactly the nodes
 * a brute-force count finds for the sampled points, and the sum of all N equals the number of
 * points (partition of unity, 1e-9 relative over the sum of many values each exact to ~1e-15).
 *
 * Set-up: a 200 x 200 node cloud of spacing h = 0.01 with interior nodes jittered by 0.3 h
 * (40,000 nodes, 4 material points per node's cell as in seed 000's GMM runs -> 160,000 points,
 * all inside the cloud). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <time.h>

#include "meshfree_check.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

#define NX 200
#define H 0.01

static double *points(size_t *np)
{
    const size_t n = (size_t)4 * (NX - 1) * (NX - 1);
    double *p = malloc(2 * n * sizeof *p);
    if (!p)
        abort();
    const double g = 0.5 / sqrt(3.0);
    size_t k = 0;
    for (int j = 0; j < NX - 1; j++)
        for (int i = 0; i < NX - 1; i++)
            for (int q = 0; q < 4; q++, k++) {
                p[2 * k] = H * (i + 0.5 + ((q & 1) ? g : -g));
                p[2 * k + 1] = H * (j + 0.5 + ((q & 2) ? g : -g));
            }
    *np = k;
    return p;
}

static void neighbour_search(void **state)
{
    (void)state;
    const double o[2] = {0, 0};
    pm_cloud *c = mc_grid_cloud(NX, NX, H, o, 0.3, 0, 5);
    size_t np;
    double *p = points(&np);
    const double radii[3] = {sqrt(2.0) * H, 1.5 * sqrt(2.0) * H, 2.77 * H};
    int32_t idx[256];
    for (int k = 0; k < 3; k++) {
        long found = 0;
        const double t0 = now();
        for (size_t i = 0; i < np; i++) {
            int nf;
            pm_cloud_query(c, p + 2 * i, radii[k], 256, idx, NULL, &nf);
            found += nf;
        }
        const double t = now() - t0;
        printf("cost: query r = %.2f h: %6.1f ns/point (%.1f nodes found per point)\n", radii[k] / H, 1e9 * t / np,
               (double)found / np);
        /* brute-force count at every 997th point */
        for (size_t i = 0; i < np; i += 997) {
            int nf, nb = 0;
            pm_cloud_query(c, p + 2 * i, radii[k], 256, idx, NULL, &nf);
            for (size_t j = 0; j < c->n; j++) {
                const double dx = c->x[2 * j] - p[2 * i], dy = c->x[2 * j + 1] - p[2 * i + 1];
                nb += dx * dx + dy * dy < radii[k] * radii[k];
            }
            assert_int_equal(nf, nb);
        }
    }
    /* the skin check and a rebuild, per node */
    int rebuilt;
    double t0 = now();
    for (int r = 0; r < 20; r++)
        assert_int_equal(pm_cloud_update(c, &rebuilt), PM_OK);
    const double t_update = (now() - t0) / 20;
    assert_int_equal(rebuilt, 0);
    t0 = now();
    for (int r = 0; r < 20; r++)
        assert_int_equal(pm_cloud_rebuild(c), PM_OK);
    const double t_build = (now() - t0) / 20;
    printf("cost: skin check %.1f ns/node, rebuild %.1f ns/node (%zu nodes)\n", 1e9 * t_update / c->n,
           1e9 * t_build / c->n, c->n);
    free(p);
    pm_cloud_destroy(c);
}

static void shape_functions(void **state)
{
    (void)state;
    const double o[2] = {0, 0};
    pm_cloud *c = mc_grid_cloud(NX, NX, H, o, 0.3, 0, 5);
    size_t np;
    double *p = points(&np);
    const char *kinds[5] = {"mls", "rk_cubic", "rk_cubic", "lme", "lme"};
    const char *labels[5] = {"mls (r = 1.5 sqrt2 h)", "rk_cubic radial (a = 1.5 sqrt2 h)",
                             "rk_cubic tensor (a = 1.5 sqrt2 h)", "lme gamma 1.8 (R = 2.77 h)",
                             "lme gamma 1.8, R = sqrt2 h"};
    for (int k = 0; k < 5; k++) {
        pm_meshfree_opts mo = pm_meshfree_opts_default();
        mo.rk_tensor = k == 2;
        if (k == 4)
            mo.support_radius = sqrt(2.0) * H;
        pm_approx *a;
        assert_int_equal(pm_approx_create_cloud(kinds[k], c, &mo, &a), PM_OK);
        double sum = 0;
        long nodes = 0;
        const double t0 = now();
        for (size_t i = 0; i < np; i++) {
            pm_stencil s;
            assert_int_equal(pm_meshfree_eval(a, p + 2 * i, &s), PM_OK);
            for (int q = 0; q < s.n; q++)
                sum += s.N[q];
            nodes += s.n;
        }
        const double t = now() - t0;
        printf("cost: %-36s %6.0f ns/point (%.1f nodes per point)\n", labels[k], 1e9 * t / np, (double)nodes / np);
        assert_true(fabs(sum - (double)np) < 1e-9 * (double)np);
        pm_approx_destroy(a);
    }
    free(p);
    pm_cloud_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(neighbour_search),
        cmocka_unit_test(shape_functions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
