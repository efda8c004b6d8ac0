/*
 * Particle seeding (src/core/seed.c): n x n Gauss points per quad cell (n = 1..6) or the 1-, 3- and
 * 6-point triangle rules, kept when inside the body's shape.
 *
 * - A rectangle or polygon made of whole cells holds every point of those cells and no other:
 *   the count is cells * points per cell, and the volumes (Gauss weights, which sum to the cell
 *   area) add up to the shape's area. Tolerance 1e-12 relative: sums of a few thousand doubles.
 * - Axisymmetric volumes are weights times the radius; Gauss rules integrate r exactly, so the
 *   total is the exact (b^2 - a^2) / 2 (d - c) per radian.
 * - A circle (and a slanted triangle) cut cells: every kept point's weight is the area of a
 *   sub-square of side h / n around it (n = 2: equal weights h^2 / 4), so the seeded area differs
 *   from the shape's by at most the area of the band of half-width d = h sqrt(2) / n (a sub-square's
 *   diagonal) along the boundary: a sub-square that holds points inside and outside lies wholly in
 *   it. For a circle the band is 4 pi r d, for a convex polygon at most 2 P d + pi d^2 (P its
 *   perimeter). That bound is the tolerance; the count is compared with a brute-force count.
 * - Every point lies inside its shape (own inside tests here), mass = density * volume exactly
 *   (the same product), and a body no point falls in is an input error naming it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/seed.h"
#include "pmech/error.h"

#define RHO 2000.0

/* Grid [0, 2] x [0, 1] of nx x ny cells, one body of density RHO with the given shape. */
static const char *tmpl =
    "{ \"dimension\": 2, \"formulation\": \"%s\",\n"
    "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 0.01 },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"size\": [2, 1], \"cells\": [%d, %d], \"element\": \"%s\" },\n"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 2000,\n"
    "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
    "  \"bodies\": [ { \"material\": \"m\", \"particles_per_cell\": %d, \"shape\": %s } ] }\n";

typedef struct seeded {
    pm_case c;
    pm_grid g;
    pm_particles p;
} seeded;

static int seed(seeded *s, const char *formulation, int nx, int ny, const char *element, int ppc, const char *shape)
{
    char buf[4096];
    snprintf(buf, sizeof buf, tmpl, formulation, nx, ny, element, ppc, shape);
    memset(s, 0, sizeof *s);
    assert_int_equal(pm_case_load_buffer(buf, strlen(buf), "case.json", &s->c), PM_OK);
    assert_int_equal(pm_grid_rectangle(&s->g, s->c.grid.origin, s->c.grid.size, s->c.grid.cells, s->c.grid.element),
                     PM_OK);
    size_t per_body[1], total;
    int rc = pm_seed_count(&s->c, &s->g, per_body, &total);
    if (rc)
        return rc;
    assert_int_equal(per_body[0], total);
    assert_int_equal(pm_particles_alloc(&s->p, total, s->c.materials[0].ops->n_state), PM_OK);
    assert_int_equal(pm_seed_fill(&s->c, &s->g, &s->p), PM_OK);
    return PM_OK;
}

static void release(seeded *s)
{
    pm_particles_free(&s->p);
    pm_grid_free(&s->g);
    pm_case_free(&s->c);
}

static double total_volume(const pm_particles *p)
{
    double v = 0;
    for (size_t i = 0; i < p->n; i++)
        v += p->vol[i];
    return v;
}

static void masses_are_density_times_volume(const pm_particles *p)
{
    for (size_t i = 0; i < p->n; i++) {
        assert_true(p->vol[i] > 0);
        assert_true(p->mass[i] == RHO * p->vol[i]);
        assert_int_equal(p->body[i], 0);
    }
}

/* [0.25, 1.75] x [0.25, 0.75] on h = 0.25: 6 x 2 whole cells, area 0.75. */
static const char *rect = "{ \"type\": \"rectangle\", \"min\": [0.25, 0.25], \"max\": [1.75, 0.75] }";

static void rectangle_of_whole_cells(void **state)
{
    (void)state;
    for (int n = 1; n <= 6; n++) {
        seeded s;
        assert_int_equal(seed(&s, "plane_strain", 8, 4, "quad4", n, rect), PM_OK);
        assert_int_equal(s.p.n, (size_t)(12 * n * n));
        assert_true(fabs(total_volume(&s.p) - 0.75) < 1e-12 * 0.75);
        for (size_t i = 0; i < s.p.n; i++) {
            const double *x = s.p.x + PM_DIM * i;
            assert_true(x[0] > 0.25 && x[0] < 1.75 && x[1] > 0.25 && x[1] < 0.75);
        }
        masses_are_density_times_volume(&s.p);
        release(&s);
    }
    static const int tri_rules[3] = {1, 3, 6};
    for (int k = 0; k < 3; k++) {
        seeded s;
        assert_int_equal(seed(&s, "plane_strain", 8, 4, "tri3", tri_rules[k], rect), PM_OK);
        assert_int_equal(s.p.n, (size_t)(12 * 2 * tri_rules[k]));
        /* the 6-point weights are given to 15 digits: they sum to 1 within 1e-15 */
        assert_true(fabs(total_volume(&s.p) - 0.75) < 1e-12 * 0.75);
        masses_are_density_times_volume(&s.p);
        release(&s);
    }
}

/* An L of whole cells: 6 cells along y in [0.25, 0.5], 2 more above on x in [0.25, 0.75]; area 0.5. */
static void polygon_of_whole_cells(void **state)
{
    (void)state;
    const char *l_shape = "{ \"type\": \"polygon\", \"points\": [[0.25, 0.25], [1.75, 0.25], [1.75, 0.5], [0.75, 0.5], "
                          "[0.75, 0.75], [0.25, 0.75]] }";
    for (int n = 1; n <= 4; n++) {
        seeded s;
        assert_int_equal(seed(&s, "plane_strain", 8, 4, "quad4", n, l_shape), PM_OK);
        assert_int_equal(s.p.n, (size_t)(8 * n * n));
        assert_true(fabs(total_volume(&s.p) - 0.5) < 1e-12 * 0.5);
        for (size_t i = 0; i < s.p.n; i++) {
            const double *x = s.p.x + PM_DIM * i;
            const int low = x[0] > 0.25 && x[0] < 1.75 && x[1] > 0.25 && x[1] < 0.5;
            const int high = x[0] > 0.25 && x[0] < 0.75 && x[1] > 0.5 && x[1] < 0.75;
            assert_true(low || high);
        }
        masses_are_density_times_volume(&s.p);
        release(&s);
    }
}

/* Points of the n x n Gauss rule of every cell that a test keeps: the count seeding must give. */
static size_t brute_count(int nx, int ny, int n, int (*inside)(const double x[PM_DIM]))
{
    static const double g2 = 0.5773502691896257645; /* n = 2: +-1/sqrt(3) */
    assert_int_equal(n, 2);
    const double hx = 2.0 / nx, hy = 1.0 / ny;
    size_t k = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            for (int b = 0; b < 2; b++)
                for (int a = 0; a < 2; a++) {
                    const double x[PM_DIM] = {(i + 0.5 * (1 + (a ? g2 : -g2))) * hx,
                                              (j + 0.5 * (1 + (b ? g2 : -g2))) * hy};
                    k += (size_t)inside(x);
                }
    return k;
}

static int in_circle(const double x[PM_DIM])
{
    return (x[0] - 1) * (x[0] - 1) + (x[1] - 0.5) * (x[1] - 0.5) <= 0.4 * 0.4;
}

/* Strictly inside the triangle (0.1, 0.1), (1.9, 0.2), (0.6, 0.9) by the signs of its edge functions. */
static const double tri[3][PM_DIM] = {{0.1, 0.1}, {1.9, 0.2}, {0.6, 0.9}};
static int in_triangle(const double x[PM_DIM])
{
    for (int k = 0; k < 3; k++) {
        const double *a = tri[k], *b = tri[(k + 1) % 3];
        if ((b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]) < 0)
            return 0;
    }
    return 1;
}

static void circle_and_triangle_within_the_boundary_band(void **state)
{
    (void)state;
    const int nx = 200, ny = 100, n = 2;
    const double h = 0.01, d = h * sqrt(2.0) / n;
    seeded s;
    assert_int_equal(seed(&s, "plane_strain", nx, ny, "quad4", n,
                          "{ \"type\": \"circle\", \"center\": [1, 0.5], \"radius\": 0.4 }"),
                     PM_OK);
    const double r = 0.4, area = M_PI * r * r, band = 2 * M_PI * r * 2 * d;
    printf("circle: seeded area %.6f, exact %.6f, error %.2e, bound %.2e\n", total_volume(&s.p), area,
           fabs(total_volume(&s.p) - area), band);
    assert_true(fabs(total_volume(&s.p) - area) <= band);
    assert_int_equal(s.p.n, brute_count(nx, ny, n, in_circle));
    /* the particles' extents end at the rim (contact measures the body's surface from them), and the
     * outermost reach it to within the rim's sagitta over a point spacing: the disk stays round */
    double reach = 0.0;
    for (size_t i = 0; i < s.p.n; i++) {
        assert_true(in_circle(s.p.x + PM_DIM * i));
        const double *x = s.p.x + PM_DIM * i, *hs = s.p.hsize + PM_DIM * i;
        const double depth = r - hypot(x[0] - 1, x[1] - 0.5);
        assert_true(hs[0] <= depth && hs[1] <= depth && fmax(hs[0], hs[1]) <= 0.5 * h / n * (1 + 1e-12));
        reach = fmax(reach, r - depth + fmin(hs[0], hs[1]));
    }
    assert_true(reach <= r + 1e-12 && reach >= r - 1e-3 * h);
    masses_are_density_times_volume(&s.p);
    release(&s);

    assert_int_equal(seed(&s, "plane_strain", nx, ny, "quad4", n,
                          "{ \"type\": \"polygon\", \"points\": [[0.1, 0.1], [1.9, 0.2], [0.6, 0.9]] }"),
                     PM_OK);
    double t_area = 0, perimeter = 0;
    for (int k = 0; k < 3; k++) {
        const double *a = tri[k], *b = tri[(k + 1) % 3];
        t_area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
        perimeter += hypot(b[0] - a[0], b[1] - a[1]);
    }
    printf("triangle: seeded area %.6f, exact %.6f, error %.2e, bound %.2e\n", total_volume(&s.p), t_area,
           fabs(total_volume(&s.p) - t_area), 2 * perimeter * d + M_PI * d * d);
    assert_true(fabs(total_volume(&s.p) - t_area) <= 2 * perimeter * d + M_PI * d * d);
    /* no Gauss point of this grid lies on an edge of the triangle, so strict and inclusive agree */
    assert_int_equal(s.p.n, brute_count(nx, ny, n, in_triangle));
    for (size_t i = 0; i < s.p.n; i++)
        assert_true(in_triangle(s.p.x + PM_DIM * i));
    masses_are_density_times_volume(&s.p);
    release(&s);
}

/* Per radian, the rectangle [0.25, 1.75] x [0.25, 0.75] has volume (1.75^2 - 0.25^2) / 2 * 0.5 = 0.75. */
static void axisymmetric_volume_is_exact(void **state)
{
    (void)state;
    for (int n = 1; n <= 3; n++) {
        seeded s;
        assert_int_equal(seed(&s, "axisymmetric", 8, 4, "quad4", n, rect), PM_OK);
        const double exact = (1.75 * 1.75 - 0.25 * 0.25) / 2 * 0.5;
        assert_true(fabs(total_volume(&s.p) - exact) < 1e-12 * exact);
        masses_are_density_times_volume(&s.p);
        release(&s);
    }
}

/* A circle of radius 0.01 around a grid node holds no cell centre (the only point with n = 1). */
static void a_body_without_points_is_an_input_error(void **state)
{
    (void)state;
    seeded s;
    int rc = seed(&s, "plane_strain", 8, 4, "quad4", 1,
                  "{ \"type\": \"circle\", \"center\": [0.5, 0.5], \"radius\": 0.01 }");
    assert_int_equal(rc, PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "case.json: bodies[0] ('body0') yields no particle"));
    release(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rectangle_of_whole_cells),
        cmocka_unit_test(polygon_of_whole_cells),
        cmocka_unit_test(circle_and_triangle_within_the_boundary_band),
        cmocka_unit_test(axisymmetric_volume_is_exact),
        cmocka_unit_test(a_body_without_points_is_an_input_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
