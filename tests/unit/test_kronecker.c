/* Kronecker-delta transformation on the essential-boundary nodes (seed 002 eqs. 15-21) for rk_cubic
 * (radial and tensor kernel) and mls: without it N_I(x_J) != delta_IJ at boundary nodes (checked,
 * so the test is not vacuous); after it, every transformed function N'_K (K boundary: unknown is
 * the nodal value; K interior: unknown stays a coefficient) satisfies N'_K(x_J) = delta_KJ for
 * every boundary node J to 1e-10, evaluated afresh at x_J (not from the stored rows); linear
 * fields are still reproduced everywhere; prescribed boundary values of a non-linear function are
 * met exactly; the rows follow moved nodes; bad input is refused.
 *
 * Tolerance 1e-10: the solve for the boundary coefficients stops at a relative residual of
 * 1e-12 (and the matrix Psi_I(x_J) on the boundary is well conditioned, its diagonal dominating
 * a row of a few neighbours), so 1e-10 leaves room for the round-off of the evaluation. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "meshfree_check.h"

#define TOL 1e-10

/* Boundary nodes: those on the edges of the cloud's bounding box. */
static size_t box_boundary(const pm_cloud *c, int32_t *b)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < c->n; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], c->x[2 * i + k]);
            hi[k] = fmax(hi[k], c->x[2 * i + k]);
        }
    size_t nb = 0;
    for (size_t i = 0; i < c->n; i++) {
        const double *x = c->x + 2 * i;
        if (x[0] == lo[0] || x[0] == hi[0] || x[1] == lo[1] || x[1] == hi[1])
            b[nb++] = (int32_t)i;
    }
    return nb;
}

/* u^h(x) = sum_I N_I(x) c_I (component comp of stride) */
static double interp(const pm_approx *a, const double x[2], const double *coef, int stride, int comp)
{
    pm_stencil s;
    assert_int_equal(pm_meshfree_eval(a, x, &s), PM_OK);
    double u = 0;
    for (int k = 0; k < s.n; k++)
        u += s.N[k] * coef[(size_t)stride * s.node[k] + comp];
    return u;
}

static void check_transformation(const char *kind, pm_cloud *c, const pm_meshfree_opts *o, const char *what)
{
    pm_approx *a;
    assert_int_equal(pm_approx_create_cloud(kind, c, o, &a), PM_OK);
    const size_t n = c->n;
    int32_t *b = malloc(n * sizeof *b), *bidx = malloc(n * sizeof *bidx);
    double *coef = calloc(2 * n, sizeof *coef), *g = calloc(n, sizeof *g), *orig = calloc(2 * n, sizeof *orig);
    assert_true(b && bidx && coef && g && orig);
    const size_t nb = box_boundary(c, b);
    for (size_t i = 0; i < n; i++)
        bidx[i] = -1;
    for (size_t j = 0; j < nb; j++)
        bidx[b[j]] = (int32_t)j;

    /* without the transformation the functions do not interpolate at the boundary nodes */
    double before = 0;
    for (size_t j = 0; j < nb; j++) {
        pm_stencil s;
        assert_int_equal(pm_meshfree_eval(a, c->x + 2 * b[j], &s), PM_OK);
        for (int k = 0; k < s.n; k++)
            before = fmax(before, fabs(s.N[k] - (s.node[k] == b[j])));
    }
    assert_true(before > 0.1);

    pm_kd *kd;
    assert_int_equal(pm_kd_create(a, nb, b, &kd), PM_OK);
    assert_int_equal((int)pm_kd_size(kd), (int)nb);
    size_t entries = 0;
    for (size_t j = 0; j < nb; j++) {
        int32_t node;
        const int32_t *cols;
        const double *vals;
        const int len = pm_kd_row(kd, j, &node, &cols, &vals);
        assert_int_equal(node, b[j]);
        double sum = 0;
        for (int k = 0; k < len; k++)
            sum += vals[k];
        assert_true(fabs(sum - 1) < TOL); /* a row is the partition of unity at x_J */
        entries += (size_t)len;
    }

    /* every transformed function N'_K at every boundary node x_J; component 1 of stride 2, with
     * component 0 holding a marker that must stay untouched */
    double after = 0, untouched = 0;
    for (size_t K = 0; K < n; K++) {
        for (size_t i = 0; i < n; i++) {
            coef[2 * i] = orig[2 * i] = 1000.0 + (double)i;
            coef[2 * i + 1] = 0;
        }
        memset(g, 0, nb * sizeof *g);
        if (bidx[K] >= 0)
            g[bidx[K]] = 1;
        else
            coef[2 * K + 1] = 1;
        assert_int_equal(pm_kd_impose(kd, g, 2, 1, coef), PM_OK);
        for (size_t i = 0; i < n; i++) {
            untouched = fmax(untouched, fabs(coef[2 * i] - orig[2 * i]));
            if (bidx[i] < 0) /* the interior unknowns are not changed */
                untouched = fmax(untouched, fabs(coef[2 * i + 1] - (i == K ? 1.0 : 0.0)));
        }
        for (size_t j = 0; j < nb; j++)
            after = fmax(after, fabs(interp(a, c->x + 2 * b[j], coef, 2, 1) - (b[j] == (int32_t)K)));
    }
    assert_true(untouched == 0);

    /* linear fields: nodal values in, the same values out as coefficients, exact everywhere */
    unsigned seed = 77;
    double lin = 0, lin_coef = 0;
    for (int t = 0; t < 3; t++) {
        const double c0 = mc_rnd(&seed) - 0.5, c1 = 3 * mc_rnd(&seed) - 1.5, c2 = 3 * mc_rnd(&seed) - 1.5;
        for (size_t i = 0; i < n; i++)
            coef[i] = bidx[i] >= 0 ? 0.0 : c0 + c1 * c->x[2 * i] + c2 * c->x[2 * i + 1];
        for (size_t j = 0; j < nb; j++)
            g[j] = c0 + c1 * c->x[2 * b[j]] + c2 * c->x[2 * b[j] + 1];
        assert_int_equal(pm_kd_impose(kd, g, 1, 0, coef), PM_OK);
        for (size_t i = 0; i < n; i++)
            lin_coef = fmax(lin_coef, fabs(coef[i] - (c0 + c1 * c->x[2 * i] + c2 * c->x[2 * i + 1])));
        for (int q = 0; q < 200; q++) {
            const double x[2] = {c->x[2 * b[0]] + (mc_rnd(&seed) - 0.5) * 4 * c->h,
                                 c->x[2 * b[0] + 1] + (mc_rnd(&seed) - 0.5) * 4 * c->h};
            const double y[2] = {c->x[2 * (q % n)] + 0.3 * c->h * (mc_rnd(&seed) - 0.5),
                                 c->x[2 * (q % n) + 1] + 0.3 * c->h * (mc_rnd(&seed) - 0.5)};
            const double *p[2] = {x, y};
            for (int k = 0; k < 2; k++) {
                pm_stencil s;
                if (pm_meshfree_eval(a, p[k], &s) != 0)
                    continue; /* a point beyond the cloud with too few nodes */
                lin = fmax(lin, fabs(interp(a, p[k], coef, 1, 0) - (c0 + c1 * p[k][0] + c2 * p[k][1])));
            }
        }
    }

    /* a non-linear boundary function: met exactly with the transformation, not without it */
    double met = 0, naive = 0;
    for (size_t i = 0; i < n; i++)
        coef[i] = sin(3 * c->x[2 * i]) * cos(2 * c->x[2 * i + 1]);
    for (size_t j = 0; j < nb; j++) {
        g[j] = coef[b[j]];
        naive = fmax(naive, fabs(interp(a, c->x + 2 * b[j], coef, 1, 0) - g[j]));
    }
    assert_int_equal(pm_kd_impose(kd, g, 1, 0, coef), PM_OK);
    for (size_t j = 0; j < nb; j++)
        met = fmax(met, fabs(interp(a, c->x + 2 * b[j], coef, 1, 0) - g[j]));

    printf("%-9s %-34s |B| %3zu of %3zu, %5.1f entries/row: |N(x_J) - delta| %.2f before, %.1e after; "
           "linear %.1e (coef %.1e); sin*cos at B: %.1e naive, %.1e transformed\n",
           kind, what, nb, n, (double)entries / nb, before, after, lin, lin_coef, naive, met);
    assert_true(after < TOL);
    assert_true(lin < TOL && lin_coef < TOL);
    assert_true(met < TOL && naive > 1e-4);

    /* nodes move (interior ones, by up to 0.2 h): the rows are re-evaluated in place */
    for (size_t i = 0; i < n; i++)
        if (bidx[i] < 0) {
            c->x[2 * i] += 0.2 * c->h * (2 * mc_rnd(&seed) - 1);
            c->x[2 * i + 1] += 0.2 * c->h * (2 * mc_rnd(&seed) - 1);
        }
    assert_int_equal(a->ops->connect(a, NULL), PM_OK);
    assert_int_equal(pm_kd_update(kd, a), PM_OK);
    for (size_t i = 0; i < n; i++)
        coef[i] = 0;
    for (size_t j = 0; j < nb; j++)
        g[j] = 1.0 + c->x[2 * b[j]];
    assert_int_equal(pm_kd_impose(kd, g, 1, 0, coef), PM_OK);
    for (size_t j = 0; j < nb; j++)
        assert_true(fabs(interp(a, c->x + 2 * b[j], coef, 1, 0) - g[j]) < TOL);

    pm_kd_destroy(kd);
    free(b);
    free(bidx);
    free(coef);
    free(g);
    free(orig);
    pm_approx_destroy(a);
}

static void interpolates_at_boundary_nodes(void **state)
{
    (void)state;
    const double o[2] = {-1.0, 0.5};
    pm_cloud *c = mc_grid_cloud(13, 9, 0.25, o, 0.25, 1, 61);
    check_transformation("rk_cubic", c, NULL, "jittered 13 x 9");
    pm_cloud_destroy(c);
    c = mc_grid_cloud(13, 9, 0.25, o, 0.25, 1, 61);
    pm_meshfree_opts t = pm_meshfree_opts_default();
    t.rk_tensor = 1;
    check_transformation("rk_cubic", c, &t, "tensor kernel, jittered 13 x 9");
    pm_cloud_destroy(c);
    c = mc_grid_cloud(13, 9, 0.25, o, 0.25, 1, 61);
    check_transformation("mls", c, NULL, "jittered 13 x 9");
    pm_cloud_destroy(c);
    const double size[2] = {2.0, 1.0};
    c = mc_random_cloud(300, o, size, 0.1, 63);
    check_transformation("mls", c, NULL, "random 300 + edges");
    pm_cloud_destroy(c);
    c = mc_random_cloud(300, o, size, 0.1, 63);
    pm_meshfree_opts w = pm_meshfree_opts_default();
    w.dilation = 2.0; /* wider support: more coupling along the boundary */
    check_transformation("rk_cubic", c, &w, "random 300 + edges, f = 2");
    pm_cloud_destroy(c);
}

static void refusals(void **state)
{
    (void)state;
    const double o[2] = {0, 0};
    pm_cloud *c = mc_grid_cloud(6, 6, 0.1, o, 0, 0, 71);
    pm_approx *a;
    assert_int_equal(pm_approx_create_cloud("rk_cubic", c, NULL, &a), PM_OK);
    pm_kd *kd;
    const int32_t twice[3] = {0, 1, 0}, outside[2] = {0, 36};
    assert_int_equal(pm_kd_create(a, 3, twice, &kd), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "listed twice"));
    assert_null(kd);
    assert_int_equal(pm_kd_create(a, 2, outside, &kd), PM_EINPUT);
    assert_int_equal(pm_kd_create(NULL, 2, twice, &kd), PM_EINPUT);
    /* no boundary nodes: imposing nothing is a no-op */
    assert_int_equal(pm_kd_create(a, 0, twice, &kd), PM_OK);
    double coef[36] = {0};
    assert_int_equal(pm_kd_impose(kd, NULL, 1, 0, coef), PM_OK);
    pm_kd_destroy(kd);
    pm_kd_destroy(NULL);
    pm_approx_destroy(a);
    pm_cloud_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(interpolates_at_boundary_nodes),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
