/* Unstructured background grids (triangles or quads from a mesh generator) and named sets. */
#include "pmech/error.h"
#include "pmech/grid.h"

#include "mesh_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int pm_grid_add_node_set(pm_grid *g, const char *name, size_t n, const int32_t *nodes, const double normal[2])
{
    pm_node_set *sets = realloc(g->sets, (g->n_sets + 1) * sizeof *sets);
    if (!sets)
        return pm_error_set(PM_ENOMEM, "out of memory for node set '%s'", name);
    g->sets = sets;
    pm_node_set *s = &g->sets[g->n_sets];
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", name);
    s->nodes = malloc((n ? n : 1) * sizeof(int32_t));
    if (!s->nodes)
        return pm_error_set(PM_ENOMEM, "out of memory for node set '%s'", name);
    if (n)
        memcpy(s->nodes, nodes, n * sizeof(int32_t));
    s->n = n;
    if (normal) {
        s->normal[0] = normal[0];
        s->normal[1] = normal[1];
    }
    return (int)g->n_sets++;
}

const pm_cell_set *pm_grid_find_cell_set(const pm_grid *g, const char *name)
{
    for (size_t i = 0; i < g->n_cell_sets; i++)
        if (strcmp(g->cell_sets[i].name, name) == 0)
            return &g->cell_sets[i];
    return NULL;
}

static double cell_area2(const pm_grid *g, const int32_t *v)
{
    double s = 0;
    const int npc = g->nodes_per_cell;
    for (int k = 0; k < npc; k++) {
        const double *p = g->x + 2 * v[k], *q = g->x + 2 * v[(k + 1) % npc];
        s += p[0] * q[1] - q[0] * p[1];
    }
    return s;
}

int pm_grid_unstructured(pm_grid *g, size_t n_nodes, const double *x, size_t n_cells, const int32_t *conn,
                         pm_element element)
{
    memset(g, 0, sizeof *g);
    if (n_nodes < 3 || n_cells < 1)
        return pm_error_set(PM_EINPUT, "an unstructured grid needs at least 3 nodes and one cell");
    if (n_nodes > INT32_MAX || n_cells > INT32_MAX / 4)
        return pm_error_set(PM_EINPUT, "grid too large: %zu nodes, %zu cells", n_nodes, n_cells);
    g->element = element;
    g->nodes_per_cell = element == PM_QUAD4 ? 4 : 3;
    const int npc = g->nodes_per_cell;
    g->n_nodes = n_nodes;
    g->n_cells = n_cells;
    g->x = malloc(2 * n_nodes * sizeof(double));
    g->conn = malloc(n_cells * (size_t)npc * sizeof(int32_t));
    if (!g->x || !g->conn) {
        pm_grid_free(g);
        return pm_error_set(PM_ENOMEM, "cannot allocate a grid of %zu nodes and %zu cells", n_nodes, n_cells);
    }
    memcpy(g->x, x, 2 * n_nodes * sizeof(double));
    memcpy(g->conn, conn, n_cells * (size_t)npc * sizeof(int32_t));
    g->lo[0] = g->hi[0] = x[0];
    g->lo[1] = g->hi[1] = x[1];
    for (size_t i = 0; i < n_nodes; i++)
        for (int d = 0; d < 2; d++) {
            double v = x[2 * i + d];
            if (!isfinite(v)) {
                pm_grid_free(g);
                return pm_error_set(PM_EINPUT, "node %zu has a non-finite coordinate", i);
            }
            g->lo[d] = fmin(g->lo[d], v);
            g->hi[d] = fmax(g->hi[d], v);
        }
    g->h_min = INFINITY;
    for (size_t c = 0; c < n_cells; c++) {
        int32_t *v = g->conn + (size_t)npc * c;
        for (int k = 0; k < npc; k++)
            if (v[k] < 0 || (size_t)v[k] >= n_nodes) {
                pm_grid_free(g);
                return pm_error_set(PM_EINPUT, "cell %zu refers to node %d of %zu", c, (int)v[k], n_nodes);
            }
        double a2 = cell_area2(g, v);
        if (a2 < 0) { /* make it counter-clockwise */
            for (int k = 1; k < npc - k; k++) {
                int32_t t = v[k];
                v[k] = v[npc - k];
                v[npc - k] = t;
            }
            a2 = -a2;
        }
        double emax = 0;
        for (int k = 0; k < npc; k++) {
            const double *p = g->x + 2 * v[k], *q = g->x + 2 * v[(k + 1) % npc];
            emax = fmax(emax, hypot(q[0] - p[0], q[1] - p[1]));
        }
        if (!(a2 > 1e-14 * emax * emax)) {
            pm_grid_free(g);
            return pm_error_set(PM_EINPUT, "cell %zu is degenerate (zero area)", c);
        }
        /* triangles: smallest altitude; quads: area over the longest side */
        double hc = (npc == 3 ? a2 : 0.5 * a2) / emax;
        g->h_min = fmin(g->h_min, hc);
    }
    const double far = fmax(fmax(fabs(g->lo[0]), fabs(g->hi[0])), fmax(fabs(g->lo[1]), fabs(g->hi[1])));
    if (!(far / g->h_min <= PM_COORD_PER_CELL_MAX)) {
        const double h = g->h_min;
        pm_grid_free(g);
        return pm_error_set(PM_EINPUT,
                            "node coordinates up to %g with cells %g m across: a double resolves %.2g of a cell there, "
                            "too coarse for shape functions (allowed: |coordinate| / cell below %g); move the mesh "
                            "near 0",
                            far, h, far * 2.2e-16 / h, PM_COORD_PER_CELL_MAX);
    }
    int rc = pm_grid_locator_build(g);
    if (rc) {
        pm_grid_free(g);
        return rc;
    }
    static const double nxm[2] = {-1, 0}, nxp[2] = {1, 0}, nym[2] = {0, -1}, nyp[2] = {0, 1};
    const double *nrm[4] = {nxm, nxp, nym, nyp};
    const char *nm[4] = {"x_min", "x_max", "y_min", "y_max"};
    for (int k = 0; k < 4; k++) {
        int axis = k / 2;
        double value = (k % 2) ? g->hi[axis] : g->lo[axis];
        rc = pm_grid_add_line_set(g, nm[k], axis, value, nrm[k]);
        if (rc == PM_ENOMEM) {
            pm_grid_free(g);
            return rc;
        }
    }
    pm_error_clear();
    return PM_OK;
}
