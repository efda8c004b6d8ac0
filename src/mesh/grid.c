#include "pmech/grid.h"
#include "pmech/error.h"

#include "mesh_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int pm_mesh_cmp_i32(const void *a, const void *b)
{
    const int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

void pm_grid_free(pm_grid *g)
{
    pm_grid_locator_free(g->locator);
    for (size_t i = 0; i < g->n_cell_sets; i++)
        free(g->cell_sets[i].cells);
    free(g->cell_sets);
    free(g->x);
    free(g->conn);
    for (size_t i = 0; i < g->n_sets; i++) {
        free(g->sets[i].nodes);
        free(g->sets[i].edges);
    }
    free(g->sets);
    memset(g, 0, sizeof *g);
}

int pm_grid_add_line_set(pm_grid *g, const char *name, int axis, double value, const double normal[2])
{
    double tol = 1e-9 * (g->h_min > 0 ? g->h_min : 1.0);
    size_t cnt = 0;
    for (size_t i = 0; i < g->n_nodes; i++)
        if (fabs(g->x[2 * i + axis] - value) <= tol)
            cnt++;
    if (cnt == 0)
        return pm_error_set(PM_EINPUT, "no grid node lies on the line %c = %g", axis ? 'y' : 'x', value);
    int32_t *nodes = malloc(cnt * sizeof *nodes);
    if (!nodes)
        return pm_error_set(PM_ENOMEM, "out of memory for node set '%s'", name);
    size_t k = 0;
    for (size_t i = 0; i < g->n_nodes; i++)
        if (fabs(g->x[2 * i + axis] - value) <= tol)
            nodes[k++] = (int32_t)i;
    const int rc = pm_grid_add_node_set(g, name, k, nodes, normal);
    free(nodes);
    return rc;
}

const pm_node_set *pm_grid_find_set(const pm_grid *g, const char *name)
{
    for (size_t i = 0; i < g->n_sets; i++)
        if (strcmp(g->sets[i].name, name) == 0)
            return &g->sets[i];
    return NULL;
}

int pm_grid_rectangle(pm_grid *g, const double origin[2], const double size[2], const int cells[2],
                      pm_element element)
{
    memset(g, 0, sizeof *g);
    if (!(size[0] > 0 && size[1] > 0) || cells[0] < 1 || cells[1] < 1)
        return pm_error_set(PM_EINPUT, "grid size and cell counts must be positive");
    const int nx = cells[0], ny = cells[1];
    g->element = element;
    g->nodes_per_cell = element == PM_QUAD4 ? 4 : 3;
    g->n_nodes = (size_t)(nx + 1) * (size_t)(ny + 1);
    g->n_cells = (size_t)nx * (size_t)ny * (element == PM_QUAD4 ? 1 : 2);
    g->structured = 1;
    for (int d = 0; d < 2; d++) {
        g->origin[d] = origin[d];
        g->h[d] = size[d] / cells[d];
        g->cells[d] = cells[d];
        g->lo[d] = origin[d];
        g->hi[d] = origin[d] + size[d];
    }
    g->h_min = fmin(g->h[0], g->h[1]);
    g->x = malloc(2 * g->n_nodes * sizeof(double));
    g->conn = malloc(g->n_cells * (size_t)g->nodes_per_cell * sizeof(int32_t));
    if (!g->x || !g->conn) {
        pm_grid_free(g);
        return pm_error_set(PM_ENOMEM, "cannot allocate a grid of %d x %d cells", nx, ny);
    }
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            size_t k = (size_t)j * (nx + 1) + i;
            /* i == nx uses the exact far edge so that boundary sets match to round-off */
            g->x[2 * k] = i == nx ? g->hi[0] : origin[0] + i * g->h[0];
            g->x[2 * k + 1] = j == ny ? g->hi[1] : origin[1] + j * g->h[1];
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int32_t n0 = j * (nx + 1) + i;
            int32_t q[4] = {n0, n0 + 1, n0 + nx + 2, n0 + nx + 1};
            size_t c = (size_t)j * nx + i;
            if (element == PM_QUAD4) {
                memcpy(g->conn + 4 * c, q, sizeof q);
            } else {
                int32_t *t = g->conn + 6 * c;
                t[0] = q[0]; t[1] = q[1]; t[2] = q[2];
                t[3] = q[0]; t[4] = q[2]; t[5] = q[3];
            }
        }
    static const double nxm[2] = {-1, 0}, nxp[2] = {1, 0}, nym[2] = {0, -1}, nyp[2] = {0, 1};
    int rc;
    if ((rc = pm_grid_add_line_set(g, "x_min", 0, g->lo[0], nxm)) < 0 ||
        (rc = pm_grid_add_line_set(g, "x_max", 0, g->hi[0], nxp)) < 0 ||
        (rc = pm_grid_add_line_set(g, "y_min", 1, g->lo[1], nym)) < 0 ||
        (rc = pm_grid_add_line_set(g, "y_max", 1, g->hi[1], nyp)) < 0) {
        pm_grid_free(g);
        return rc;
    }
    return PM_OK;
}

int32_t pm_grid_locate(const pm_grid *g, const double xp[2])
{
    return pm_grid_locate_from(g, xp, -1);
}

int32_t pm_grid_locate_from(const pm_grid *g, const double xp[2], int32_t hint)
{
    if (!g->structured)
        return g->locator ? pm_grid_locator_find(g, xp, hint) : -1;
    double fx = (xp[0] - g->origin[0]) / g->h[0];
    double fy = (xp[1] - g->origin[1]) / g->h[1];
    if (!(fx >= 0 && fy >= 0 && fx <= g->cells[0] && fy <= g->cells[1]))
        return -1; /* also rejects NaN */
    int cx = (int)fx, cy = (int)fy;
    if (cx == g->cells[0])
        cx--; /* a point on the far edge belongs to the last cell */
    if (cy == g->cells[1])
        cy--;
    int32_t c = cy * g->cells[0] + cx;
    if (g->element == PM_QUAD4)
        return c;
    /* tri3: lower triangle when below the lower-left to upper-right diagonal */
    return (fx - cx >= fy - cy) ? 2 * c : 2 * c + 1;
}

int pm_grid_side_of(const char *name, int *axis, int *hi)
{
    static const char *const sides[] = {"x_min", "x_max", "y_min", "y_max"};
    for (int k = 0; k < (int)(sizeof sides / sizeof sides[0]); k++)
        if (strcmp(name, sides[k]) == 0) {
            *axis = k / 2;
            *hi = k % 2;
            return 1;
        }
    return 0;
}
