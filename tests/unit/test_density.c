/* Density from particle positions (seed 004 eqs. 12-13): a uniformly filled region gives the
 * material density (exactly with Gauss-point seeding; within 1 % with a lattice of points that
 * ignores the cells, away from the region's edge), in plane and axisymmetric (per radian) form,
 * and a compressed filling reads proportionally denser; the average over each point's neighbourhood
 * keeps an exact field exact and narrows the scatter of bunched points; counting only the occupied
 * quarters of the cells is exact where all are filled, undoes most of a free surface's dilution and
 * still reads spray as loose. */
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
        assert_int_equal(pm_density_from_positions(&g, &p, axi, -1, rn, rp, w, NULL, NULL), 0);
        double worst = 0;
        for (size_t i = 0; i < g.n_nodes; i++)
            worst = fmax(worst, fabs(rn[i] / RHO - 1));
        for (size_t i = 0; i < p.n; i++)
            worst = fmax(worst, fabs(rp[i] / RHO - 1));
        printf("Gauss-point filling, %s: max relative density error %.2e\n", axi ? "axisymmetric" : "plane", worst);
        /* the quadrature of N_i (and N_i r) is exact for these rules */
        assert_true(worst < 1e-12);
        /* averaged over the neighbourhood, a field that is exact everywhere stays exact (the shape
         * functions sum to one and each node's weights to its own denominator) */
        int32_t *sn = malloc(4 * p.n * sizeof(int32_t));
        double *sN = malloc(4 * p.n * sizeof(double)), *rs = malloc(p.n * sizeof(double));
        double *w2 = malloc((2 * g.n_nodes + g.n_cells) * sizeof(double));
        assert_int_equal(pm_density_from_positions(&g, &p, axi, -1, rn, rp, w2, sn, sN), 0);
        pm_density_smooth(&g, &p, -1, 2, sn, sN, rp, rs, w2);
        worst = 0;
        for (size_t i = 0; i < p.n; i++)
            worst = fmax(worst, fabs(rs[i] / RHO - 1));
        printf("  averaged twice over the neighbourhood: max relative error %.2e\n", worst);
        assert_true(worst < 1e-12);
        free(sn);
        free(sN);
        free(rs);
        free(w2);
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
    assert_int_equal(pm_density_from_positions(g, &p, axi, -1, rn, rp, w, NULL, NULL), 0);
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

/* Points of a square block bunched into rows and columns a cell or two apart (3 x 3 points per cell
 * as in examples/silo_filling, the density 30 % above and below its mean in waves of 2 and 3 cells,
 * each point then moved at random by up to a quarter of the spacing): each point's own density scatters
 * about the material's by 0.11 in ln rho, as inside the silo filling's deposit. Averaged twice over
 * the neighbourhood the scatter must fall to under half (it falls to 0.025: each pass averages over
 * about four cells, and the waves are one to three cells long); the points' mean must move by under
 * 1 % (the average is mass-weighted and moves no mass; an unnormalised one would move it by far
 * more); and the block's edge, whose cells are partly empty, must not read looser than each point's
 * own value does there (only points count in the average, not the cells' empty parts). */
static void neighbourhood_average_narrows_the_scatter(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {1, 1};
    const int cells[2] = {20, 20};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    /* the block's sides lie inside cells (partly filled cells at its edge), as a deposit's do */
    const double h = 1.0 / 20, s = h / 3, lo = 0.21, hi = lo + 36 * s;
    const size_t side = (size_t)((hi - lo) / s + 0.5), n = side * side;
    pm_particles p;
    assert_int_equal(pm_particles_alloc(&p, n, 0), 0);
    unsigned seed = 2026u;
    for (size_t a = 0; a < side; a++)
        for (size_t b = 0; b < side; b++) {
            const size_t i = a * side + b;
            /* waves of 2 h in x and 3 h in y draw the points into rows and columns that are 30 %
             * denser and looser than the mean, then each point moves at random */
            for (int d = 0; d < 2; d++) {
                seed = seed * 1103515245u + 12345u;
                const double u = (double)((seed >> 8) & 0xffff) / 65535.0 - 0.5;
                const double lambda = (d == 0 ? 2 : 3) * h, at = lo + ((d == 0 ? b : a) + 0.5) * s;
                p.x[2 * i + d] = at - 0.3 * lambda / (2 * M_PI) * sin(2 * M_PI * (at - lo) / lambda) + 0.5 * s * u;
            }
            p.mass[i] = RHO * s * s;
            p.cell[i] = pm_grid_locate(&g, p.x + 2 * i);
        }
    p.n = n;
    double *rn = malloc(g.n_nodes * sizeof(double)), *rp = malloc(n * sizeof(double));
    double *rs = malloc(n * sizeof(double)), *sN = malloc(4 * n * sizeof(double));
    double *w = malloc((2 * g.n_nodes + g.n_cells) * sizeof(double));
    int32_t *sn = malloc(4 * n * sizeof(int32_t));
    assert_int_equal(pm_density_from_positions(&g, &p, 0, -1, rn, rp, w, sn, sN), 0);
    pm_density_smooth(&g, &p, -1, 2, sn, sN, rp, rs, w);
    double m[2] = {0, 0}, m2[2] = {0, 0}, edge[2] = {0, 0};
    size_t k = 0, ke = 0;
    for (size_t i = 0; i < n; i++) {
        const double x = p.x[2 * i], y = p.x[2 * i + 1];
        const double depth = fmin(fmin(x - lo, hi - x), fmin(y - lo, hi - y));
        const double v[2] = {log(rp[i] / RHO), log(rs[i] / RHO)};
        if (depth > 3 * h) {
            for (int j = 0; j < 2; j++) {
                m[j] += v[j];
                m2[j] += v[j] * v[j];
            }
            k++;
        } else if (depth < s) {
            for (int j = 0; j < 2; j++)
                edge[j] += v[j];
            ke++;
        }
    }
    double sd[2];
    for (int j = 0; j < 2; j++) {
        m[j] /= (double)k;
        sd[j] = sqrt(fmax(m2[j] / (double)k - m[j] * m[j], 0.0));
        edge[j] /= (double)ke;
    }
    printf("bunched block: inside, ln(rho / rho_ref) mean %+.4f sd %.4f (own) and %+.4f sd %.4f (averaged); "
           "edge mean %+.3f and %+.3f\n", m[0], sd[0], m[1], sd[1], edge[0], edge[1]);
    assert_true(sd[0] > 0.08); /* the bunching this test is about is there */
    assert_true(sd[1] < 0.5 * sd[0]);
    assert_true(fabs(m[1] - m[0]) < 0.01);
    assert_true(edge[1] >= edge[0]);
    free(rn);
    free(rp);
    free(rs);
    free(sN);
    free(w);
    free(sn);
    pm_particles_free(&p);
    pm_grid_free(&g);
}

/* Every part of every cell holding points (3 x 3 Gauss points per quad, the 6-point Gauss rule per
 * triangle): counting only the occupied quarters of the cells changes nothing, so a uniformly filled
 * region reads the material density exactly at every point, plane and axisymmetric, on jittered quads
 * and triangles (the parts' integrals of N_i, and of N_i r, sum to the cell's). */
static void fill_parts(const pm_grid *g, pm_particles *p, int axi)
{
    const int tri = g->element == PM_TRI3, per = tri ? 6 : 9;
    assert_int_equal(pm_particles_alloc(p, (size_t)per * g->n_cells, 0), 0);
    static const double A6 = 0.445948490915965, W6A = 0.223381589678011;
    static const double B6 = 0.091576213509771, W6B = 0.109951743655322;
    static const double G3[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, W3[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    size_t n = 0;
    for (size_t c = 0; c < g->n_cells; c++)
        for (int q = 0; q < per; q++) {
            double x[2] = {0, 0}, w;
            if (tri) {
                const int32_t *t = g->conn + 3 * c;
                const double a = q < 3 ? A6 : B6, b[3] = {q % 3 == 0 ? 1 - 2 * a : a, q % 3 == 1 ? 1 - 2 * a : a,
                                                         q % 3 == 2 ? 1 - 2 * a : a};
                const double *p0 = g->x + 2 * t[0], *p1 = g->x + 2 * t[1], *p2 = g->x + 2 * t[2];
                for (int d = 0; d < 2; d++)
                    x[d] = b[0] * p0[d] + b[1] * p1[d] + b[2] * p2[d];
                w = (q < 3 ? W6A : W6B) * 0.5 *
                    fabs((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]));
            } else {
                static const double XI[4] = {-1, 1, 1, -1}, ETA[4] = {-1, -1, 1, 1};
                const int32_t *v = g->conn + 4 * c;
                const double xi = G3[q % 3], eta = G3[q / 3];
                double J[4] = {0, 0, 0, 0};
                for (int k = 0; k < 4; k++) {
                    const double *xk = g->x + 2 * v[k];
                    const double N = 0.25 * (1 + XI[k] * xi) * (1 + ETA[k] * eta);
                    const double dxi = 0.25 * XI[k] * (1 + ETA[k] * eta), deta = 0.25 * ETA[k] * (1 + XI[k] * xi);
                    x[0] += N * xk[0];
                    x[1] += N * xk[1];
                    J[0] += dxi * xk[0];
                    J[1] += deta * xk[0];
                    J[2] += dxi * xk[1];
                    J[3] += deta * xk[1];
                }
                w = W3[q % 3] * W3[q / 3] * fabs(J[0] * J[3] - J[1] * J[2]);
            }
            p->x[2 * n] = x[0];
            p->x[2 * n + 1] = x[1];
            p->mass[n] = RHO * w * (axi ? x[0] : 1.0);
            p->cell[n] = (int32_t)c;
            n++;
        }
    p->n = n;
}

static void occupied_parts_of_a_filled_region_are_exact(void **state)
{
    (void)state;
    for (int tri = 0; tri < 2; tri++) {
        pm_grid g;
        assert_int_equal(sc_jittered_grid(&g, 12, tri ? PM_TRI3 : PM_QUAD4, 0.4, 0.0, 5), 0);
        for (int axi = 0; axi < 2; axi++) {
            pm_particles p;
            fill_parts(&g, &p, axi);
            double *rn = malloc(g.n_nodes * sizeof(double)), *rp = malloc(p.n * sizeof(double));
            double *rs = malloc(p.n * sizeof(double)), *sN = malloc(4 * p.n * sizeof(double));
            double *w = malloc((2 * g.n_nodes + 4 * g.n_cells) * sizeof(double));
            int32_t *sn = malloc(4 * p.n * sizeof(int32_t));
            assert_int_equal(pm_density_from_positions(&g, &p, axi, -1, rn, rp, w, sn, sN), 0);
            pm_density_parts(&g, &p, axi, -1, sn, sN, rs, w);
            double worst = 0;
            for (size_t i = 0; i < p.n; i++)
                worst = fmax(worst, fmax(fabs(rp[i] / RHO - 1), fabs(rs[i] / RHO - 1)));
            printf("occupied parts, jittered %s, %s: max relative density error %.2e\n", tri ? "triangles" : "quads",
                   axi ? "axisymmetric" : "plane", worst);
            assert_true(worst < 1e-12);
            free(rn);
            free(rp);
            free(rs);
            free(sN);
            free(w);
            free(sn);
            pm_particles_free(&p);
        }
        pm_grid_free(&g);
    }
}

/* A lattice of 3 x 3 points per cell whose top row of cells holds one row of points (a third of its
 * points, in its lower quarters, which that row fills to two thirds), and a spray of the same points
 * three spacings apart (one in a cell of nine). Each point's own density dilutes the top row by the
 * cells' empty part: it reads 0.67 of the material's at the lowest. Counting occupied quarters only,
 * the lowest must be over 0.78 (measured 0.82, the two-thirds-filled quarters' own dilution; the whole
 * cells' 0.67 fails). The spray must still read looser than the loosest packing with margin: under
 * 0.8 of the material's (measured 0.73 at most; e_max = 1.0 with e0 = 0.9 is 0.95). */
static void occupied_parts_at_a_surface_and_in_spray(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[2] = {0, 0}, size[2] = {1, 1};
    const int cells[2] = {20, 20};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), 0);
    const double h = 1.0 / 20, s = h / 3, lo = 0.2, top = lo + 7.5 * h;
    pm_particles p;
    assert_int_equal(pm_particles_alloc(&p, 4000, 0), 0);
    size_t n = 0;
    for (double y = lo + s / 2; y < top; y += s)
        for (double x = lo + s / 2; x < 0.8; x += s) {
            p.x[2 * n] = x;
            p.x[2 * n + 1] = y;
            p.mass[n] = RHO * s * s;
            n++;
        }
    const size_t n_block = n;
    for (double y = 0.7 + 1.5 * s; y < 0.95; y += 3 * s)
        for (double x = 0.1 + 0.5 * s; x < 0.9; x += 3 * s) {
            p.x[2 * n] = x;
            p.x[2 * n + 1] = y;
            p.mass[n] = RHO * s * s;
            n++;
        }
    p.n = n;
    for (size_t i = 0; i < n; i++)
        p.cell[i] = pm_grid_locate(&g, p.x + 2 * i);
    double *rn = malloc(g.n_nodes * sizeof(double)), *rp = malloc(n * sizeof(double));
    double *rs = malloc(n * sizeof(double)), *sN = malloc(4 * n * sizeof(double));
    double *w = malloc((2 * g.n_nodes + 4 * g.n_cells) * sizeof(double));
    int32_t *sn = malloc(4 * n * sizeof(int32_t));
    assert_int_equal(pm_density_from_positions(&g, &p, 0, -1, rn, rp, w, sn, sN), 0);
    pm_density_parts(&g, &p, 0, -1, sn, sN, rs, w);
    double own_lo = INFINITY, parts_lo = INFINITY, spray_hi = 0, x_lo = 0.2 + h, x_hi = 0.8 - h;
    for (size_t i = 0; i < n; i++) {
        const double x = p.x[2 * i], y = p.x[2 * i + 1];
        if (i >= n_block)
            spray_hi = fmax(spray_hi, rs[i] / RHO);
        else if (y > lo + 7 * h && x > x_lo && x < x_hi) {
            own_lo = fmin(own_lo, rp[i] / RHO);
            parts_lo = fmin(parts_lo, rs[i] / RHO);
        }
    }
    printf("top row of cells a third filled: lowest density %.3f of the material's (own), %.3f (occupied "
           "quarters); spray a ninth as dense: highest %.3f\n", own_lo, parts_lo, spray_hi);
    assert_true(own_lo < 0.75); /* the dilution this test is about is there */
    assert_true(parts_lo > 0.78);
    assert_true(spray_hi < 0.8);
    free(rn);
    free(rp);
    free(rs);
    free(sN);
    free(w);
    free(sn);
    pm_particles_free(&p);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gauss_seeding_is_exact),
        cmocka_unit_test(uniform_region_within_one_percent),
        cmocka_unit_test(neighbourhood_average_narrows_the_scatter),
        cmocka_unit_test(occupied_parts_of_a_filled_region_are_exact),
        cmocka_unit_test(occupied_parts_at_a_surface_and_in_spray),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
