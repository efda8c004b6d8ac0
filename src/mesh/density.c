/* Mass density from particle positions (seed 004 section 3.3, eqs. 12-13). */
#include "pmech/approx.h"
#include "mesh/density.h"
#include "pmech/error.h"

#include "shape/shape_internal.h"

#include <math.h>
#include <string.h>

/* Linear shape functions of cell c at x: 3 or 4 values and node indices. */
static int cell_shape(const pm_grid *g, int32_t c, const double x[2], int32_t node[4], double N[4])
{
    if (g->element == PM_TRI3) {
        const int32_t *t = g->conn + 3 * (size_t)c;
        const double *p0 = g->x + 2 * t[0], *p1 = g->x + 2 * t[1], *p2 = g->x + 2 * t[2];
        double det = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
        for (int k = 0; k < 3; k++) {
            const double *a = g->x + 2 * t[(k + 1) % 3], *b = g->x + 2 * t[(k + 2) % 3];
            N[k] = ((a[0] - x[0]) * (b[1] - x[1]) - (b[0] - x[0]) * (a[1] - x[1])) / det;
            node[k] = t[k];
        }
        return 3;
    }
    if (g->structured) {
        double dN[8];
        pm_linear_quad_eval(g, x, c, node, N, dN);
        return 4;
    }
    pm_stencil s;
    if (pm_quad4_iso_eval(g, c, x, &s) != 0)
        return -1;
    for (int k = 0; k < 4; k++) {
        node[k] = s.node[k];
        N[k] = s.N[k];
    }
    return 4;
}

/* Add integral over cell c of N_i (times r when axisymmetric) to den[i]. */
static void cell_weights(const pm_grid *g, size_t c, int axi, double *den)
{
    const int npc = g->nodes_per_cell;
    const int32_t *v = g->conn + (size_t)npc * c;
    if (npc == 3) {
        const double *p0 = g->x + 2 * v[0], *p1 = g->x + 2 * v[1], *p2 = g->x + 2 * v[2];
        double A = 0.5 * fabs((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]));
        double rs = p0[0] + p1[0] + p2[0];
        for (int k = 0; k < 3; k++)
            den[v[k]] += axi ? A * (rs + g->x[2 * v[k]]) / 12.0 : A / 3.0;
        return;
    }
    static const double XI[4] = {-1, 1, 1, -1}, ETA[4] = {-1, -1, 1, 1};
    const double gp = 0.5773502691896257645;
    for (int q = 0; q < 4; q++) {
        const double xi = XI[q] * gp, eta = ETA[q] * gp;
        double N[4], J[4] = {0, 0, 0, 0}, r = 0;
        for (int k = 0; k < 4; k++) {
            const double *x = g->x + 2 * v[k];
            N[k] = 0.25 * (1 + XI[k] * xi) * (1 + ETA[k] * eta);
            double dxi = 0.25 * XI[k] * (1 + ETA[k] * eta), deta = 0.25 * ETA[k] * (1 + XI[k] * xi);
            J[0] += dxi * x[0];
            J[1] += deta * x[0];
            J[2] += dxi * x[1];
            J[3] += deta * x[1];
            r += N[k] * x[0];
        }
        double w = fabs(J[0] * J[3] - J[1] * J[2]) * (axi ? r : 1.0);
        for (int k = 0; k < 4; k++)
            den[v[k]] += N[k] * w;
    }
}

int pm_density_from_positions(const pm_grid *g, const pm_particles *p, int axisymmetric, int32_t material,
                              double *rho_node, double *rho_p, double *work)
{
    double *den = work, *occupied = work + g->n_nodes;
    memset(rho_node, 0, g->n_nodes * sizeof(double));
    memset(work, 0, (g->n_nodes + g->n_cells) * sizeof(double));
    int32_t node[4];
    double N[4];
    for (size_t i = 0; i < p->n; i++) {
        if (material >= 0 && p->material[i] != material)
            continue;
        int32_t c = p->cell[i];
        if (c < 0 || (size_t)c >= g->n_cells)
            return pm_error_set(PM_ESIM, "density from positions: particle %zu has no cell", i);
        int n = cell_shape(g, c, p->x + 2 * i, node, N);
        if (n < 0)
            return pm_error_set(PM_ESIM, "density from positions: particle %zu: degenerate cell %d", i, (int)c);
        for (int k = 0; k < n; k++)
            rho_node[node[k]] += N[k] * p->mass[i];
        occupied[c] = 1.0;
    }
    for (size_t c = 0; c < g->n_cells; c++)
        if (occupied[c] != 0)
            cell_weights(g, c, axisymmetric, den);
    for (size_t i = 0; i < g->n_nodes; i++)
        rho_node[i] = den[i] > 0 ? rho_node[i] / den[i] : 0.0;
    if (rho_p) {
        for (size_t i = 0; i < p->n; i++) {
            rho_p[i] = 0;
            if (material >= 0 && p->material[i] != material)
                continue;
            int n = cell_shape(g, p->cell[i], p->x + 2 * i, node, N);
            for (int k = 0; k < n; k++)
                rho_p[i] += N[k] * rho_node[node[k]];
        }
    }
    return PM_OK;
}
