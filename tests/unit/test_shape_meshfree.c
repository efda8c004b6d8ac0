/* Meshfree shape functions on node clouds (mls, lme, rk_cubic radial and tensor-product): partition
 * of unity, linear reproduction and gradient consistency (sum dN_I = 0, sum dN_I x_I^T = I) to
 * 1e-10 on regular, jittered and random clouds, at random points and at points on or next to the
 * cloud boundary and corners; gradients against central differences of N; the low-level moment
 * solve against finite differences with its node set fixed; the adaptive rules of seed 000
 * section 5.3 (minimum node count, LME convex-hull safeguard and Hessian condition); and refusals.
 *
 * Tolerances: the consistency conditions hold exactly in exact arithmetic, so 1e-10 (relative to
 * h for lengths, to 1/h for gradients) leaves round-off of a conditioned 3 x 3 solve (cond <= 1e6
 * by default; LME to |r| <= 1e-14 h) plenty of room. Central differences with step eps = 1e-6 h
 * carry a truncation error ~ eps^2 |N'''| ~ 1e-12 / h^2 and a round-off error ~ 1e-16 / eps, so
 * FD errors are checked to 1e-6 in units of 1/h. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "meshfree_check.h"

#define TOL 1e-10
#define FD_TOL 1e-6

/* Points: random in [lo, hi], then the four corners, points on each edge and points 1e-9 h, 1e-3 h
 * and 0.3 h inside each edge (nedge per edge and offset). */
static double *make_points(size_t nrand, const double lo[2], const double hi[2], double h, double edge_in,
                           unsigned seed, size_t *np)
{
    const int nedge = 20;
    const double offs[4] = {0, 1e-9, 1e-3, 0.3};
    const size_t n = nrand + 4 + 4 * 4 * nedge;
    double *p = malloc(2 * n * sizeof *p);
    if (!p)
        abort();
    size_t k = 0;
    for (size_t i = 0; i < nrand; i++, k++) {
        p[2 * k] = lo[0] + (hi[0] - lo[0]) * mc_rnd(&seed);
        p[2 * k + 1] = lo[1] + (hi[1] - lo[1]) * mc_rnd(&seed);
    }
    /* edge_in > 0 keeps every boundary point that far inside (LME: lambda diverges on the hull) */
    for (int c = 0; c < 4; c++, k++) {
        p[2 * k] = (c & 1) ? hi[0] - edge_in : lo[0] + edge_in;
        p[2 * k + 1] = (c & 2) ? hi[1] - edge_in : lo[1] + edge_in;
    }
    for (int o = 0; o < 4; o++) {
        const double in = fmax(offs[o] * h, edge_in);
        for (int i = 0; i < nedge; i++) {
            const double tx = lo[0] + (hi[0] - lo[0]) * mc_rnd(&seed), ty = lo[1] + (hi[1] - lo[1]) * mc_rnd(&seed);
            const double e[4][2] = {{tx, lo[1] + in}, {tx, hi[1] - in}, {lo[0] + in, ty}, {hi[0] - in, ty}};
            for (int s = 0; s < 4; s++, k++) {
                p[2 * k] = e[s][0];
                p[2 * k + 1] = e[s][1];
            }
        }
    }
    *np = k;
    return p;
}

static void check_kind(const char *kind, pm_cloud *c, const pm_meshfree_opts *o, const char *what, double edge_in,
                       unsigned seed)
{
    pm_approx *a;
    assert_int_equal(pm_approx_create_cloud(kind, c, o, &a), PM_OK);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < c->n; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], c->x[2 * i + k]);
            hi[k] = fmax(hi[k], c->x[2 * i + k]);
        }
    size_t np;
    double *pts = make_points(1500, lo, hi, c->h, edge_in, seed, &np);
    mc_errors e = mc_check(a, np, pts, 1e-6 * c->h);
    char label[96];
    snprintf(label, sizeof label, "%s, %s", kind, what);
    mc_print(label, &e);
    assert_true(e.pu < TOL && e.xrep < TOL && e.grad_sum < TOL && e.grad_x < TOL);
    assert_true(e.fd < FD_TOL);
    /* FD compared at most points: the node set changes between x +- eps only near a support edge
     * (where the weight and its slope vanish for MLS/RK) or where the adaptive radius grows */
    assert_true(e.fd_points > 0.8 * e.points);
    assert_true(e.max_nodes <= PM_STENCIL_MAX);
    if (strcmp(kind, "lme") == 0)
        assert_true(e.min_n >= 0); /* max-ent weights are positive */
    else
        assert_true(e.min_nodes >= 6); /* seed 000 section 5.3: at least six nodes */
    free(pts);
    pm_approx_destroy(a);
}

static void regular_and_jittered_clouds(void **state)
{
    (void)state;
    const double o[2] = {-1.5, 2.0};
    const char *kinds[3] = {"mls", "rk_cubic", "lme"};
    for (int k = 0; k < 3; k++) {
        const int lme = k == 2;
        /* LME on the hull itself has no solution (lambda diverges): its points stay 1e-9 h inside */
        const double in = lme ? 1e-9 * 0.25 : 0;
        pm_cloud *c = mc_grid_cloud(17, 11, 0.25, o, 0, 0, 3);
        check_kind(kinds[k], c, NULL, "regular 17 x 11", in, 5);
        pm_cloud_destroy(c);
        c = mc_grid_cloud(17, 11, 0.25, o, 0.3, 1, 7);
        check_kind(kinds[k], c, NULL, "jittered 0.3 h, volumes 0.5-1.5 h^2", in, 9);
        pm_cloud_destroy(c);
    }
}

static void random_clouds(void **state)
{
    (void)state;
    const double o[2] = {10.0, -3.0}, size[2] = {3.0, 2.0};
    pm_cloud *c = mc_random_cloud(600, o, size, 0.1, 13);
    check_kind("mls", c, NULL, "random 600 + edges", 0, 15);
    check_kind("rk_cubic", c, NULL, "random 600 + edges", 0, 17);
    pm_meshfree_opts t = pm_meshfree_opts_default();
    t.rk_tensor = 1;
    check_kind("rk_cubic", c, &t, "tensor kernel, random 600 + edges", 0, 19);
    check_kind("lme", c, NULL, "random 600 + edges", 1e-9 * 0.1, 21);
    pm_meshfree_opts g = pm_meshfree_opts_default();
    g.lme_gamma = 0.8;
    check_kind("lme", c, &g, "gamma 0.8, random 600 + edges", 1e-9 * 0.1, 23);
    g.lme_gamma = 4.0;
    check_kind("lme", c, &g, "gamma 4, random 600 + edges", 1e-9 * 0.1, 25);
    pm_cloud_destroy(c);
}

/* The moment solve with its node set and weights fixed: dN equals central differences of N where
 * the weights follow x (so the adaptive search plays no part). */
static void moment_gradients_match_differences(void **state)
{
    (void)state;
    unsigned seed = 31;
    const double a = 0.35;
    double worst = 0, worst_cond = 0;
    for (int trial = 0; trial < 200; trial++) {
        double xn[20][2];
        for (int i = 0; i < 20; i++) {
            xn[i][0] = 0.5 * mc_rnd(&seed) - 0.25;
            xn[i][1] = 0.5 * mc_rnd(&seed) - 0.25;
        }
        const double x[2] = {0.1 * mc_rnd(&seed) - 0.05, 0.1 * mc_rnd(&seed) - 0.05};
        double N[3][20], dN[3][20][2];
        const double eps = 1e-6 * a;
        for (int dir = 0; dir < 2; dir++) {
            for (int s = 0; s < 3; s++) { /* s = 0: at x; 1: +eps; 2: -eps along dir */
                double xp[2] = {x[0], x[1]};
                xp[dir] += s == 1 ? eps : (s == 2 ? -eps : 0);
                double d[20][2], w[20], dw[20][2], cond;
                for (int i = 0; i < 20; i++) {
                    d[i][0] = xp[0] - xn[i][0];
                    d[i][1] = xp[1] - xn[i][1];
                    const double r = sqrt(d[i][0] * d[i][0] + d[i][1] * d[i][1]);
                    double dwz;
                    w[i] = pm_cubic_spline(r / a, &dwz);
                    dw[i][0] = r > 0 ? dwz * d[i][0] / (r * a) : 0;
                    dw[i][1] = r > 0 ? dwz * d[i][1] / (r * a) : 0;
                }
                assert_int_equal(pm_linear_moment_shape(20, (const double (*)[2])d, w, (const double (*)[2])dw, a,
                                                        N[s], dN[s], &cond),
                                 PM_OK);
                worst_cond = fmax(worst_cond, cond);
            }
            for (int i = 0; i < 20; i++)
                worst = fmax(worst, fabs((N[1][i] - N[2][i]) / (2 * eps) - dN[0][i][dir]) * a);
        }
    }
    printf("moment solve: dN vs central differences %.1e (units 1/a), condition <= %.3g\n", worst, worst_cond);
    assert_true(worst < FD_TOL);
    /* the spline of seed 002 eq. 40: values and slopes at the joins */
    double dw0, dw1, dw2;
    assert_true(fabs(pm_cubic_spline(0, &dw0) - 2.0 / 3.0) < 1e-15 && dw0 == 0);
    assert_true(fabs(pm_cubic_spline(0.5 - 1e-12, &dw1) - pm_cubic_spline(0.5, &dw2)) < 1e-11);
    assert_true(fabs(dw1 + 1) < 1e-10 && fabs(dw2 + 1) < 1e-10);
    assert_true(fabs(pm_cubic_spline(1 - 1e-9, &dw1)) < 1e-20 && fabs(dw1) < 1e-15);
    assert_true(pm_cubic_spline(1.0, NULL) == 0 && pm_cubic_spline(2.0, NULL) == 0);
    /* nodes on one line: the moment matrix is singular and the solve says so */
    double d[4][2] = {{0, -0.1}, {0, 0}, {0, 0.1}, {0, 0.2}}, w[4] = {1, 1, 1, 1}, dw[4][2] = {{0}}, N[4], dN[4][2], cond;
    assert_int_equal(pm_linear_moment_shape(4, (const double (*)[2])d, w, (const double (*)[2])dw, 1, N, dN, &cond),
                     PM_ESIM);
    assert_true(isinf(cond));
}

/* Seed 000 section 5.3. MLS: a radius too small for six nodes grows until six are in. LME: a search
 * radius holding too few nodes, or nodes not around the point, grows until they enclose it; a
 * strict Hessian tolerance adds next-nearest nodes. */
static void adaptive_rules(void **state)
{
    (void)state;
    const double o[2] = {0, 0};
    pm_cloud *c = mc_grid_cloud(11, 11, 0.1, o, 0.2, 0, 41);
    pm_meshfree_opts m = pm_meshfree_opts_default();
    m.support_radius = 0.12; /* about 4 nodes around an interior point, 1-2 at a corner */
    pm_approx *a;
    assert_int_equal(pm_approx_create_cloud("mls", c, &m, &a), PM_OK);
    assert_true(pm_meshfree_radius(a) == 0.12);
    size_t np;
    const double lo[2] = {0, 0}, hi[2] = {1, 1};
    double *pts = make_points(500, lo, hi, 0.1, 0, 43, &np);
    mc_errors e = mc_check(a, np, pts, 0);
    mc_print("mls, support 1.2 h (grows to >= 6 nodes)", &e);
    assert_true(e.pu < TOL && e.xrep < TOL && e.grad_sum < TOL && e.grad_x < TOL);
    assert_true(e.min_nodes >= 6);
    pm_approx_destroy(a);
    m.min_nodes = 12;
    assert_int_equal(pm_approx_create_cloud("rk_cubic", c, &m, &a), PM_OK);
    e = mc_check(a, np, pts, 0);
    mc_print("rk_cubic, support 1.2 h, min 12 nodes", &e);
    assert_true(e.pu < TOL && e.xrep < TOL && e.grad_sum < TOL && e.grad_x < TOL);
    assert_true(e.min_nodes >= 12);
    pm_approx_destroy(a);
    free(pts);

    /* LME with seed 000's search radius sqrt(2 h^2) = 1.41 h and a small one, 0.8 h */
    const double lo2[2] = {1e-6, 1e-6}, hi2[2] = {1 - 1e-6, 1 - 1e-6};
    pts = make_points(500, lo2, hi2, 0.1, 1e-9, 47, &np);
    const double radii[2] = {sqrt(2.0) * 0.1, 0.08};
    int nodes_default = 0;
    for (int k = 0; k < 2; k++) {
        pm_meshfree_opts l = pm_meshfree_opts_default();
        l.support_radius = radii[k];
        assert_int_equal(pm_approx_create_cloud("lme", c, &l, &a), PM_OK);
        e = mc_check(a, np, pts, 0);
        char what[80];
        snprintf(what, sizeof what, "lme, search radius %.2f h (hull safeguard)", radii[k] / 0.1);
        mc_print(what, &e);
        assert_true(e.pu < TOL && e.xrep < TOL && e.grad_sum < TOL && e.grad_x < TOL && e.min_n >= 0);
        if (k == 0)
            nodes_default = e.max_nodes;
        pm_approx_destroy(a);
    }
    /* an impossible Hessian tolerance: every point takes lme_max_extra more nodes */
    pm_meshfree_opts l = pm_meshfree_opts_default();
    l.support_radius = sqrt(2.0) * 0.1;
    l.cond_tol = 1.0;
    l.lme_max_extra = 5;
    assert_int_equal(pm_approx_create_cloud("lme", c, &l, &a), PM_OK);
    pm_approx *b;
    l.cond_tol = 1e300; /* never adds */
    assert_int_equal(pm_approx_create_cloud("lme", c, &l, &b), PM_OK);
    int added = 0;
    for (size_t i = 0; i < np; i++) {
        pm_stencil sa, sb;
        assert_int_equal(pm_meshfree_eval(a, pts + 2 * i, &sa), PM_OK);
        assert_int_equal(pm_meshfree_eval(b, pts + 2 * i, &sb), PM_OK);
        assert_true(sa.n == sb.n + 5 || sa.n == PM_STENCIL_MAX);
        /* the old connectivity plus the next-nearest nodes */
        for (int q = 0; q < sb.n; q++)
            assert_int_equal(sa.node[q], sb.node[q]);
        added += sa.n - sb.n;
    }
    e = mc_check(a, np, pts, 0);
    mc_print("lme, radius 1.41 h, cond(J) tolerance 1 (+5 nodes)", &e);
    assert_true(e.pu < TOL && e.xrep < TOL && e.grad_sum < TOL && e.grad_x < TOL);
    printf("lme: %d nodes added over %zu points; default tolerance: stencils of up to %d nodes\n", added, np,
           nodes_default);
    pm_approx_destroy(a);
    pm_approx_destroy(b);
    free(pts);

    /* outside the cloud's hull LME has no solution: refused with the point named */
    assert_int_equal(pm_approx_create_cloud("lme", c, NULL, &a), PM_OK);
    pm_stencil s;
    const double out[2] = {-0.01, 0.5}, on[2] = {0.0, 0.5};
    assert_int_equal(pm_meshfree_eval(a, out, &s), PM_ESIM);
    assert_non_null(strstr(pm_error_message(), "convex hull"));
    assert_int_equal(pm_meshfree_eval(a, on, &s), PM_ESIM);
    pm_approx_destroy(a);
    pm_cloud_destroy(c);
}

static void refusals(void **state)
{
    (void)state;
    const double o[2] = {0, 0};
    pm_cloud *c = mc_grid_cloud(20, 20, 0.1, o, 0, 0, 51);
    pm_approx *a;
    assert_int_equal(pm_approx_create_cloud("linear", c, NULL, &a), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "mls, lme, rk_cubic"));
    assert_int_equal(pm_approx_create_cloud("mls", NULL, NULL, &a), PM_EINPUT);
    pm_meshfree_opts m = pm_meshfree_opts_default();
    m.support_radius = -1;
    assert_int_equal(pm_approx_create_cloud("mls", c, &m, &a), PM_EINPUT);
    m = pm_meshfree_opts_default();
    m.growth = 1.0;
    assert_int_equal(pm_approx_create_cloud("mls", c, &m, &a), PM_EINPUT);
    m = pm_meshfree_opts_default();
    m.min_nodes = 65;
    assert_int_equal(pm_approx_create_cloud("rk_cubic", c, &m, &a), PM_EINPUT);
    /* a support holding more than 64 nodes cannot fill a stencil: an error naming the fix */
    m = pm_meshfree_opts_default();
    m.support_radius = 0.5;
    assert_int_equal(pm_approx_create_cloud("mls", c, &m, &a), PM_OK);
    pm_stencil s;
    const double x[2] = {1.0, 1.0};
    assert_int_equal(pm_meshfree_eval(a, x, &s), PM_ESIM);
    assert_non_null(strstr(pm_error_message(), "reduce support_radius"));
    /* the pm_approx view: eval by particle, error naming it; connect refreshes the cloud */
    pm_particles p;
    memset(&p, 0, sizeof p);
    double px[4] = {1.0, 1.0, 0.55, 0.45};
    p.n = 2;
    p.x = px;
    /* connect evaluates every point once (the solvers' passes then reuse it) and names the first
     * that fails; eval of that point fails the same way */
    assert_int_equal(a->ops->connect(a, &p), PM_ESIM);
    assert_non_null(strstr(pm_error_message(), "particle 0"));
    assert_int_equal(a->ops->eval(a, &p, 0, &s), PM_ESIM);
    assert_non_null(strstr(pm_error_message(), "particle 0"));
    pm_approx_destroy(a);
    assert_int_equal(pm_approx_create_cloud("mls", c, NULL, &a), PM_OK);
    assert_string_equal(a->ops->name, "mls");
    assert_int_equal(a->ops->eval(a, &p, 1, &s), PM_OK);
    assert_true(pm_approx_is_meshfree(a) && pm_meshfree_cloud(a) == c);
    /* default MLS radius: f sqrt(2 h^2) with f = 1.5 */
    assert_true(fabs(pm_meshfree_radius(a) - 1.5 * sqrt(2.0) * 0.1) < 1e-15);
    pm_approx_destroy(a);
    /* grid kinds are not meshfree */
    assert_false(pm_approx_is_meshfree(NULL));
    assert_int_equal(pm_meshfree_eval(NULL, x, &s), PM_EINPUT);
    pm_cloud_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(regular_and_jittered_clouds),
        cmocka_unit_test(random_clouds),
        cmocka_unit_test(moment_gradients_match_differences),
        cmocka_unit_test(adaptive_rules),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
