/*
 * A quad mesh that fills its bounding box with equal axis-aligned cells (a transfinite rectangle from
 * Gmsh, as most silo and forming meshes are) is a structured grid numbered differently. Renumbered to
 * the structured order it takes the structured grid's O(1) point location and inline linear-quad
 * passes, which run the same cells 1.5 to 2 times as fast as the isoparametric path, and it gives the
 * same numbers as the `rectangle` grid of those cells.
 */
#include "pmech/grid.h"
#include "pmech/error.h"
#include "pmech/particles.h"

#include "mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* How far (in cells) a node may lie from its lattice place: Gmsh writes coordinates to 16 digits,
 * so a transfinite node is off by round-off only; anything more is a different mesh. */
#define LATTICE_TOL 1e-8

/* The lattice index of coordinate v along axis d, or -1 when v is not on a lattice line. */
static long lattice_index(double v, double lo, double h, long n)
{
    const double f = (v - lo) / h;
    const long i = lround(f);
    if (i < 0 || i > n || fabs(f - (double)i) > LATTICE_TOL)
        return -1;
    return i;
}

/* New node index of every node (by its lattice place), or 0 when some node is off the lattice or
 * two share a place. */
static int number_nodes(const pm_grid *g, const long n[PM_DIM], const double h[PM_DIM], int32_t *new_of,
                        uint8_t *taken)
{
    for (size_t k = 0; k < g->n_nodes; k++) {
        const long i = lattice_index(g->x[PM_DIM * k], g->lo[0], h[0], n[0]);
        const long j = lattice_index(g->x[PM_DIM * k + 1], g->lo[1], h[1], n[1]);
        if (i < 0 || j < 0)
            return 0;
        const long m = j * (n[0] + 1) + i;
        if (taken[m])
            return 0;
        taken[m] = 1;
        new_of[k] = (int32_t)m;
    }
    return 1;
}

/* New cell index of every cell, or 0 when some cell is not one lattice square. */
static int number_cells(const pm_grid *g, const long n[PM_DIM], const int32_t *new_of, int32_t *cell_of,
                        uint8_t *taken)
{
    const long row = n[0] + 1;
    for (size_t c = 0; c < g->n_cells; c++) {
        int32_t v[4];
        for (int k = 0; k < 4; k++)
            v[k] = new_of[g->conn[4 * c + k]];
        int32_t n0 = v[0];
        for (int k = 1; k < 4; k++)
            n0 = v[k] < n0 ? v[k] : n0;
        const long i = n0 % row, j = n0 / row;
        if (i >= n[0] || j >= n[1])
            return 0;
        /* the four corners of the lattice square at n0, each once */
        const int32_t want[4] = {n0, n0 + 1, (int32_t)(n0 + row), (int32_t)(n0 + row + 1)};
        unsigned seen = 0;
        for (int k = 0; k < 4; k++)
            for (int w = 0; w < 4; w++)
                if (v[k] == want[w])
                    seen |= 1u << w;
        if (seen != 0xFu)
            return 0;
        const long m = j * n[0] + i;
        if (taken[m])
            return 0;
        taken[m] = 1;
        cell_of[c] = (int32_t)m;
    }
    return 1;
}

/* Rewrite the grid in the structured numbering (new_of: nodes, cell_of: cells). */
static int renumber(pm_grid *g, const long n[PM_DIM], const double h[PM_DIM], const int32_t *new_of,
                    const int32_t *cell_of)
{
    double *x = malloc(PM_DIM * g->n_nodes * sizeof *x);
    int32_t *conn = malloc(4 * g->n_cells * sizeof *conn);
    if (!x || !conn) {
        free(x);
        free(conn);
        return pm_error_set(PM_ENOMEM, "out of memory renumbering a %ld x %ld grid", n[0], n[1]);
    }
    /* the coordinates the `rectangle` grid of these cells has, far sides exact */
    for (long j = 0; j <= n[1]; j++)
        for (long i = 0; i <= n[0]; i++) {
            const size_t k = (size_t)(j * (n[0] + 1) + i);
            x[PM_DIM * k] = i == n[0] ? g->hi[0] : g->lo[0] + (double)i * h[0];
            x[PM_DIM * k + 1] = j == n[1] ? g->hi[1] : g->lo[1] + (double)j * h[1];
        }
    for (long j = 0; j < n[1]; j++)
        for (long i = 0; i < n[0]; i++) {
            const int32_t n0 = (int32_t)(j * (n[0] + 1) + i);
            int32_t *q = conn + 4 * (j * n[0] + i);
            q[0] = n0;
            q[1] = n0 + 1;
            q[2] = (int32_t)(n0 + n[0] + 2);
            q[3] = (int32_t)(n0 + n[0] + 1);
        }
    free(g->x);
    free(g->conn);
    g->x = x;
    g->conn = conn;
    for (size_t s = 0; s < g->n_sets; s++) {
        pm_node_set *set = &g->sets[s];
        for (size_t k = 0; k < set->n; k++)
            set->nodes[k] = new_of[set->nodes[k]];
        qsort(set->nodes, set->n, sizeof set->nodes[0], pm_mesh_cmp_i32);
        for (size_t k = 0; k < 2 * set->n_edges; k++)
            set->edges[k] = new_of[set->edges[k]];
    }
    for (size_t s = 0; s < g->n_cell_sets; s++) {
        pm_cell_set *set = &g->cell_sets[s];
        for (size_t k = 0; k < set->n; k++)
            set->cells[k] = cell_of[set->cells[k]];
        qsort(set->cells, set->n, sizeof set->cells[0], pm_mesh_cmp_i32);
    }
    pm_grid_locator_free(g->locator);
    g->locator = NULL;
    g->structured = 1;
    for (int d = 0; d < PM_DIM; d++) {
        g->origin[d] = g->lo[d];
        g->h[d] = h[d];
        g->cells[d] = (int)n[d];
    }
    g->h_min = fmin(h[0], h[1]);
    return PM_OK;
}

int pm_grid_adopt_lattice(pm_grid *g)
{
    if (g->structured || g->element != PM_QUAD4 || g->n_cells == 0)
        return 0;
    /* the first cell gives the spacing; the counts must then fill the bounding box exactly */
    double lo[PM_DIM], hi[PM_DIM];
    for (int d = 0; d < PM_DIM; d++) {
        lo[d] = hi[d] = g->x[PM_DIM * g->conn[0] + d];
        for (int k = 1; k < 4; k++) {
            const double v = g->x[PM_DIM * g->conn[k] + d];
            lo[d] = fmin(lo[d], v);
            hi[d] = fmax(hi[d], v);
        }
    }
    long n[PM_DIM];
    double h[PM_DIM];
    for (int d = 0; d < PM_DIM; d++) {
        const double extent = g->hi[d] - g->lo[d], cell = hi[d] - lo[d];
        if (!(cell > 0) || !(extent > 0) || extent / cell > 1e7)
            return 0;
        n[d] = lround(extent / cell);
        if (n[d] < 1 || fabs(extent / cell - (double)n[d]) > 1e-6)
            return 0;
        h[d] = extent / (double)n[d];
    }
    if ((size_t)n[0] * (size_t)n[1] != g->n_cells || (size_t)(n[0] + 1) * (size_t)(n[1] + 1) != g->n_nodes ||
        g->n_nodes > (size_t)INT32_MAX)
        return 0;
    int32_t *new_of = malloc(g->n_nodes * sizeof *new_of);
    int32_t *cell_of = malloc(g->n_cells * sizeof *cell_of);
    uint8_t *taken = calloc(g->n_nodes, 1); /* n_nodes > n_cells: serves both passes */
    int rc = 0;
    if (!new_of || !cell_of || !taken) {
        rc = pm_error_set(PM_ENOMEM, "out of memory checking a %ld x %ld grid", n[0], n[1]);
    } else if (number_nodes(g, n, h, new_of, taken)) {
        memset(taken, 0, g->n_nodes);
        if (number_cells(g, n, new_of, cell_of, taken)) {
            rc = renumber(g, n, h, new_of, cell_of);
            rc = rc < 0 ? rc : 1;
        }
    }
    free(new_of);
    free(cell_of);
    free(taken);
    return rc;
}
