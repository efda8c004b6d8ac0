/* A quad mesh of equal axis-aligned cells filling its bounding box becomes the structured grid of those
 * cells (pm_grid_adopt_lattice): nodes, cells and sets renumbered, the same coordinates as the
 * `rectangle` grid; anything else is left unstructured. End to end, a case on the silo example's Gmsh
 * mesh, its floor and wall named by the mesh's groups, steps to the same bytes as the same case on its
 * 50 x 160 rectangle with the sides named. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/grid.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"

#include "sim_case.h"

enum { NX = 4, NY = 3 };
static const double ORIGIN[2] = {-0.5, 1.0}, SIZE[2] = {2.0, 0.75};

/* The NX x NY rectangle's nodes numbered backwards and each cell's corners starting at a different
 * one, as a mesher may number them; interior node `moved` (if >= 0) shifted by `shift` cells in x. */
static void scrambled(pm_grid *g, long moved, double shift, int drop_last_cell)
{
    pm_grid r;
    const int cells[2] = {NX, NY};
    assert_int_equal(pm_grid_rectangle(&r, ORIGIN, SIZE, cells, PM_QUAD4), 0);
    const size_t nn = r.n_nodes, nc = r.n_cells - (drop_last_cell ? 1 : 0);
    double *x = malloc(2 * nn * sizeof *x);
    int32_t *conn = malloc(4 * nc * sizeof *conn);
    for (size_t k = 0; k < nn; k++) {
        x[2 * (nn - 1 - k)] = r.x[2 * k] + (k == (size_t)moved ? shift * r.h[0] : 0);
        x[2 * (nn - 1 - k) + 1] = r.x[2 * k + 1];
    }
    for (size_t c = 0; c < nc; c++)
        for (int k = 0; k < 4; k++)
            conn[4 * c + k] = (int32_t)(nn - 1) - r.conn[4 * c + (k + c) % 4];
    assert_int_equal(pm_grid_unstructured(g, nn, x, nc, conn, PM_QUAD4), 0);
    /* a boundary group along the top (nodes and edges) and a cell group: the top row */
    int32_t top[NX + 1], edges[2 * NX], row[NX];
    for (int i = 0; i <= NX; i++)
        top[i] = (int32_t)(nn - 1) - (NY * (NX + 1) + i);
    for (int i = 0; i < NX; i++)
        edges[2 * i] = top[i + 1], edges[2 * i + 1] = top[i];
    const double up[2] = {0, 1};
    const int s = pm_grid_add_node_set(g, "lid", NX + 1, top, up);
    assert_true(s >= 0);
    g->sets[s].edges = malloc(sizeof edges);
    memcpy(g->sets[s].edges, edges, sizeof edges);
    g->sets[s].n_edges = NX;
    for (int i = 0; i < NX; i++)
        row[i] = (NY - 1) * NX + i;
    g->cell_sets = calloc(1, sizeof *g->cell_sets);
    g->n_cell_sets = 1;
    snprintf(g->cell_sets[0].name, sizeof g->cell_sets[0].name, "top_row");
    g->cell_sets[0].cells = malloc(sizeof row);
    memcpy(g->cell_sets[0].cells, row, sizeof row);
    g->cell_sets[0].n = NX;
    free(x), free(conn);
    pm_grid_free(&r);
}

static void lattice_becomes_the_rectangle(void **state)
{
    (void)state;
    pm_grid g, r;
    scrambled(&g, -1, 0, 0);
    const int cells[2] = {NX, NY};
    assert_int_equal(pm_grid_rectangle(&r, ORIGIN, SIZE, cells, PM_QUAD4), 0);
    assert_int_equal(pm_grid_adopt_lattice(&g), 1);
    assert_true(g.structured);
    assert_null(g.locator);
    assert_int_equal(g.cells[0], NX);
    assert_int_equal(g.cells[1], NY);
    for (int d = 0; d < 2; d++) {
        assert_true(g.origin[d] == r.origin[d]);
        assert_true(fabs(g.h[d] - r.h[d]) <= 1e-15 * r.h[d]);
    }
    assert_true(g.h_min == r.h_min);
    for (size_t k = 0; k < 2 * r.n_nodes; k++)
        assert_true(fabs(g.x[k] - r.x[k]) <= 1e-15);
    assert_memory_equal(g.conn, r.conn, 4 * r.n_cells * sizeof(int32_t));
    /* sets: the same places as before, in the new numbers */
    const pm_node_set *lid = pm_grid_find_set(&g, "lid");
    assert_non_null(lid);
    for (size_t k = 0; k < lid->n; k++) {
        assert_int_equal(lid->nodes[k], NY * (NX + 1) + (int)k); /* ascending along the top */
        assert_true(fabs(g.x[2 * lid->nodes[k] + 1] - (ORIGIN[1] + SIZE[1])) < 1e-15);
    }
    for (int i = 0; i < NX; i++) { /* each edge from right to left, as given */
        assert_int_equal(lid->edges[2 * i], NY * (NX + 1) + i + 1);
        assert_int_equal(lid->edges[2 * i + 1], NY * (NX + 1) + i);
    }
    const pm_node_set *xmax = pm_grid_find_set(&g, "x_max");
    assert_non_null(xmax);
    assert_int_equal(xmax->n, NY + 1);
    for (size_t k = 0; k < xmax->n; k++)
        assert_int_equal(xmax->nodes[k], (int)k * (NX + 1) + NX);
    /* the top row of cells, given in the scrambled numbering, is the top row */
    for (int i = 0; i < NX; i++) {
        const int32_t c = g.cell_sets[0].cells[i];
        assert_int_equal(c / NX, NY - 1);
    }
    const double p[2] = {0.3, 1.6};
    assert_int_equal(pm_grid_locate(&g, p), pm_grid_locate(&r, p));
    pm_grid_free(&g);
    pm_grid_free(&r);
}

/* A node off its place by a tenth of a cell, a missing cell, or a graded spacing: not a lattice. */
static void other_meshes_stay_unstructured(void **state)
{
    (void)state;
    pm_grid g;
    scrambled(&g, 6, 0.1, 0); /* node 6 is interior (row 1, column 1) */
    assert_int_equal(pm_grid_adopt_lattice(&g), 0);
    assert_false(g.structured);
    assert_non_null(g.locator);
    pm_grid_free(&g);

    scrambled(&g, 6, 1e-12, 0); /* round-off only: still the lattice */
    assert_int_equal(pm_grid_adopt_lattice(&g), 1);
    pm_grid_free(&g);

    scrambled(&g, -1, 0, 1);
    assert_int_equal(pm_grid_adopt_lattice(&g), 0);
    assert_false(g.structured);
    pm_grid_free(&g);

    /* two columns of widths 1 and 2: equal counts, unequal cells */
    const double x[] = {0, 0, 1, 0, 3, 0, 0, 1, 1, 1, 3, 1};
    const int32_t conn[] = {0, 1, 4, 3, 1, 2, 5, 4};
    assert_int_equal(pm_grid_unstructured(&g, 6, x, 2, conn, PM_QUAD4), 0);
    assert_int_equal(pm_grid_adopt_lattice(&g), 0);
    pm_grid_free(&g);

    const int cells[2] = {2, 2};
    pm_grid r;
    assert_int_equal(pm_grid_rectangle(&r, ORIGIN, SIZE, cells, PM_TRI3), 0);
    assert_int_equal(pm_grid_unstructured(&g, r.n_nodes, r.x, r.n_cells, r.conn, PM_TRI3), 0);
    assert_int_equal(pm_grid_adopt_lattice(&g), 0);
    pm_grid_free(&g);
    pm_grid_free(&r);
}

/* A block dropped 5 mm onto the silo's floor against its friction wall, 300 steps: grid given by
 * `grid`, the floor's and the wall's names by `floor` and `wall`. The case is kept for as long as the
 * run (`c`). */
static pm_sim *silo_block(const char *grid, const char *floor, const char *wall, pm_case *c)
{
    char dir[1024], text[4096];
    sc_repo_path("examples/silo_discharge/x.json", dir, sizeof dir);
    snprintf(text, sizeof text,
             "{\"dimension\": 2, \"analysis\": {\"type\": \"explicit\", \"end_time\": 0.1, \"cfl\": 0.3,"
             " \"gravity\": [0, -9.81]}, \"grid\": %s,"
             " \"materials\": [{\"name\": \"m\", \"model\": \"mohr_coulomb\", \"density\": 1500,"
             " \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3, \"friction_angle\": 30, \"cohesion\": 100}],"
             " \"bodies\": [{\"name\": \"b\", \"material\": \"m\", \"shape\": {\"type\": \"rectangle\","
             " \"min\": [0.6, 0.005], \"max\": [1.0, 0.3]}}],"
             " \"boundary_conditions\": [{\"type\": \"fixed\", \"boundary\": \"%s\", \"directions\": [\"y\"]},"
             " {\"type\": \"friction\", \"boundary\": \"%s\", \"coefficient\": 0.3}]}",
             grid, floor, wall);
    pm_sim *s = sc_sim_of(text, dir, c);
    for (int k = 0; k < 300; k++)
        assert_int_equal(pm_sim_advance(s, 2e-4), 0);
    return s;
}

static void gmsh_lattice_steps_as_the_rectangle(void **state)
{
    (void)state;
    pm_case ca, cb, cu;
    /* the mesh's groups "floor" (x > 0.2) and "wall" (a straight 1-D group: the law of a grid side) */
    pm_sim *a = silo_block("{\"type\": \"gmsh\", \"file\": \"silo.msh\"}", "floor", "wall", &ca);
    pm_sim *b = silo_block("{\"type\": \"rectangle\", \"size\": [1.0, 3.2], \"cells\": [50, 160]}", "y_min",
                           "x_max", &cb);
    pm_sim *u =
        silo_block("{\"type\": \"gmsh\", \"file\": \"silo.msh\", \"lattice\": false}", "floor", "wall", &cu);
    assert_true(a->grid.structured);
    assert_false(u->grid.structured);
    assert_int_equal(a->p.n, b->p.n);
    assert_int_equal(a->p.n, u->p.n);
    assert_memory_equal(a->p.x, b->p.x, 2 * a->p.n * sizeof(double));
    assert_memory_equal(a->p.v, b->p.v, 2 * a->p.n * sizeof(double));
    /* the isoparametric path computes the same cells another way: equal to round-off, not to the bit */
    double dmax = 0, vmax = 0;
    for (size_t i = 0; i < a->p.n; i++) {
        size_t j = 0; /* the isoparametric path seeds the cells in the mesh's order: match by x0 */
        while (j < u->p.n && (fabs(u->p.x0[2 * j] - a->p.x0[2 * i]) > 1e-9 ||
                              fabs(u->p.x0[2 * j + 1] - a->p.x0[2 * i + 1]) > 1e-9))
            j++;
        assert_true(j < u->p.n);
        for (int d = 0; d < 2; d++) {
            dmax = fmax(dmax, fabs(a->p.x[2 * i + d] - u->p.x[2 * j + d]));
            vmax = fmax(vmax, fabs(a->p.v[2 * i + d]));
        }
    }
    fprintf(stderr, "lattice against isoparametric: largest position difference %.3g m, speeds up to %.3g m/s\n",
            dmax, vmax);
    assert_true(vmax > 0.05); /* the block has fallen and is moving: the comparison sees a motion */
    assert_true(dmax < 1e-9); /* measured 3e-11 m: the round-off of 300 steps, not a different path */
    pm_sim_destroy(a);
    pm_sim_destroy(b);
    pm_sim_destroy(u);
    pm_case_free(&ca);
    pm_case_free(&cb);
    pm_case_free(&cu);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(lattice_becomes_the_rectangle),
        cmocka_unit_test(other_meshes_stay_unstructured),
        cmocka_unit_test(gmsh_lattice_steps_as_the_rectangle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
