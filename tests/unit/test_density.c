/* Density from particle positions (seed 004 eqs. 12-13): a uniformly filled region gives the
 * material density (exactly with Gauss-point seeding; within 1 % with a lattice of points that
 * ignores the cells, away from the region's edge), in plane and axisymmetric (per radian) form,
 * and a compressed filling reads proportionally denser. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "shape_check.h"
#include "mesh/density.h"

static const double RHO = 1850.0;

/* 3 points per triangle at the order-2 Gauss points, mass = rho * volume. */
static void gauss_fill(const pm_grid *g, pm_particles *p, int axi, double rho)
{
    assert_int_equal(pm_particles_alloc(p, 3 * g->n_cells, 0), 0);
    for (size_t c = 0; c < g->n_cells; c++) {
        const int32_t *t = g->conn + 3 * c;
        const double *p0 = g->x + 2 * t[0], *p1 = g->x + 2 * t[1], *p2 = g->x + 2 * t[2];
        double A = 0.5 * fabs((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]));
        for (int k = 0; k < 3; k++) {
            size_t i = 3 * c + k;
            double b[3] = {1.0 / 6, 1.0 / 6, 1.0 / 6};
            b[k] = 2.0 / 3;
            p->x[2 * i] = b[0] * p0[0] + b[1] * p1[0] + b[2] * p2[0];
            p->x[2 * i + 1] = b[0] * p0[1] + b[1] * p1[1] + b[2] * p2[1];
            p->mass[i] = rho * A / 3 * (axi ? p->x[2 * i] : 1.0);
            p->cell[i] = (int32_t)c;
        }
    }
}

static void gauss_seeding_is_exact(void **state)
{
    (void)state;
    pm_grid g;
    assert_int_equal(sc_jittered_grid(&g, 20, PM_TRI3, 0.4, 0.0, 3), 0);
    for (int axi = 0; axi < 2; axi++) {
        pm_particles p;
        gauss_fill(&g, &p, axi, RHO);
        double *rn = malloc(g.n_nodes * sizeof(double)), *rp = malloc(p.n * sizeof(double));
        double *w = malloc((g.n_nodes + g.n_cells) * sizeof(double));
        assert_int_equal(pm_density_from_positions(&g, &p, axi, -1, rn, rp, w), 0);
        double worst = 0;
        for (size_t i = 0; i < g.n_nodes; i++)
            worst = fmax(worst, fabs(rn[i] / RHO - 1));
        for (size_t i = 0; i < p.n; i++)
            worst = fmax(worst, fabs(rp[i] / RHO - 1));
        printf("Gauss-point filling, %s: max relative density error %.2e\n", axi ? "axisymmetric" : "plane", worst);
        /* the quadrature of N_i (and N_i r) is exact for these rules */
        assert_true(worst < 1e-12);
        free(rn);
        free(rp);
        free(w);
        pm_particles_free(&p);
    }
    pm_grid_free(&g);
}

/* A disk filled with a square lattice of points unrelated to the cells; particles further than
 * 2 h inside the disk's edge must read the material density within 1 %. */
static void lattice_in_a_disk(pm_grid *g, const char *what, int axi, double squeeze)
{
    const double cx = 0.5, cy = 0.5, R = 0.35, s = 1.0 / 160; /* 6 to 8 points across a cell */
    size_t cap = (size_t)(4 * R * R / (s * s)) + 16, n = 0;
    pm_particles p;
    assert_int_equal(pm_particles_alloc(&p, cap, 0), 0);
    for (double y = cy - R + s / 2; y < cy + R; y += s)
        for (double x = cx - R + s / 2; x < cx + R; x += s) {
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > R * R)
                continue;
            /* squeeze: the same points and masses pushed together towards the centre along y */
            double yy = cy + (y - cy) * squeeze;
            p.x[2 * n] = x;
            p.x[2 * n + 1] = yy;
            p.mass[n] = RHO * s * s * (axi ? x : 1.0);
            n++;
        }
    p.n = n;
    for (size_t i = 0; i < n; i++)
        p.cell[i] = pm_grid_locate(g, p.x + 2 * i);
    double *rn = malloc(g->n_nodes * sizeof(double)), *rp = malloc(n * sizeof(double));
    double *w = malloc((g->n_nodes + g->n_cells) * sizeof(double));
    assert_int_equal(pm_density_from_positions(g, &p, axi, -1, rn, rp, w), 0);
    const double h = 1.0 / 20, expect = RHO / squeeze;
    double worst = 0, edge_min = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double dx = p.x[2 * i] - cx, dy = (p.x[2 * i + 1] - cy) / squeeze;
        double depth = R - sqrt(dx * dx + dy * dy); /* in the unsqueezed disk */
        if (depth > 2 * h / squeeze)
            worst = fmax(worst, fabs(rp[i] / expect - 1));
        else
            edge_min = fmin(edge_min, rp[i] / expect);
    }
    printf("%-40s interior max error %.3f %%, lowest edge value %.2f of rho\n", what, 100 * worst, edge_min);
    assert_true(worst < 0.01);
    free(rn);
    free(rp);
    free(w);
    pm_particles_free(&p);
}

static void uniform_region_within_one_percent(void **state)
{
    (void)state;
    pm_grid g;
    assert_int_equal(sc_jittered_grid(&g, 20, PM_TRI3, 0.4, 0.0, 7), 0);
    lattice_in_a_disk(&g, "lattice disk, jittered triangles", 0, 1.0);
    lattice_in_a_disk(&g, "lattice disk, axisymmetric", 1, 1.0);
    lattice_in_a_disk(&g, "lattice disk squeezed to 0.8 in y", 0, 0.8);
    pm_grid_free(&g);
    const double origin[2] = {0, 0}, size[2] = {1, 1};
    const int cells[2] = {20, 20};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    lattice_in_a_disk(&g, "lattice disk, structured quads", 0, 1.0);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gauss_seeding_is_exact),
        cmocka_unit_test(uniform_region_within_one_percent),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
