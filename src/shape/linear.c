/* Linear finite-element shape functions of the cell containing the point (classic MPM). */
#include "pmech/approx.h"
#include "pmech/error.h"

#include "shape_internal.h"

#include <math.h>

int pm_shape_connect_cells(pm_approx *a, pm_particles *p)
{
    const pm_grid *g = a->grid;
    long bad = -1;
#pragma omp parallel for schedule(static) reduction(max : bad) num_threads(a->n_threads)
    for (long i = 0; i < (long)p->n; i++) {
        int32_t c = pm_grid_locate_from(g, p->x + 2 * i, p->cell[i]);
        p->cell[i] = c;
        if (c < 0 && i > bad)
            bad = i;
    }
    if (bad >= 0)
        return pm_error_set(PM_ESIM, "particle %ld left the grid at (%g, %g)", bad, p->x[2 * bad],
                            p->x[2 * bad + 1]);
    return PM_OK;
}

/* Barycentric coordinates of a triangle: valid for any (also unstructured) tri3 mesh. */
static void tri3_eval(const pm_grid *g, int32_t cell, const double xp[2], pm_stencil *s)
{
    const int32_t *t = g->conn + 3 * (size_t)cell;
    const double *p0 = g->x + 2 * t[0], *p1 = g->x + 2 * t[1], *p2 = g->x + 2 * t[2];
    double det = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
    double id = 1.0 / det;
    /* gradient of each barycentric coordinate is constant over the triangle */
    double b[3][2] = {{(p1[1] - p2[1]) * id, (p2[0] - p1[0]) * id},
                      {(p2[1] - p0[1]) * id, (p0[0] - p2[0]) * id},
                      {(p0[1] - p1[1]) * id, (p1[0] - p0[0]) * id}};
    s->n = 3;
    for (int k = 0; k < 3; k++) {
        const double *pk = g->x + 2 * t[(k + 1) % 3], *pl = g->x + 2 * t[(k + 2) % 3];
        double area2 = (pk[0] - xp[0]) * (pl[1] - xp[1]) - (pl[0] - xp[0]) * (pk[1] - xp[1]);
        s->node[k] = t[k];
        s->N[k] = area2 * id;
        s->dN[k][0] = b[k][0];
        s->dN[k][1] = b[k][1];
    }
}

static void quad4_eval(const pm_grid *g, int32_t cell, const double xp[2], pm_stencil *s)
{
    double dN[8];
    s->n = 4;
    pm_linear_quad_eval(g, xp, cell, s->node, s->N, dN);
    for (int k = 0; k < 4; k++) {
        s->dN[k][0] = dN[2 * k];
        s->dN[k][1] = dN[2 * k + 1];
    }
}

static int linear_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s)
{
    const pm_grid *g = a->grid;
    int32_t c = p->cell[ip];
    if (c < 0)
        return pm_error_set(PM_ESIM, "particle %zu is outside the grid", ip);
    if (g->element == PM_TRI3)
        tri3_eval(g, c, p->x + 2 * ip, s);
    else if (g->structured)
        quad4_eval(g, c, p->x + 2 * ip, s);
    else if (pm_quad4_iso_eval(g, c, p->x + 2 * ip, s) != 0)
        return pm_error_set(PM_ESIM, "particle %zu: no inverse isoparametric map in cell %d (degenerate quad?)", ip,
                            (int)c);
    return PM_OK;
}

const pm_approx_ops pm_approx_linear_ops = {
    .name = "linear",
    .methods = PM_APPROX_MPM,
    .interpolating = 1,
    .linear_quad_fast = 1,
    .connect = pm_shape_connect_cells,
    .eval = linear_eval,
    .destroy = NULL,
};

void pm_shape_tensor_stencil(const pm_grid *g, int nx, const int *ix, const double *wx, const double *dwx,
                             int ny, const int *iy, const double *wy, const double *dwy, pm_stencil *s)
{
    const double ihx = 1.0 / g->h[0], ihy = 1.0 / g->h[1];
    const int stride = g->cells[0] + 1;
    int n = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const double N = wx[i] * wy[j];
            const double gx = dwx[i] * ihx * wy[j], gy = wx[i] * dwy[j] * ihy;
            if (N == 0 && gx == 0 && gy == 0)
                continue;
            s->node[n] = iy[j] * stride + ix[i];
            s->N[n] = N;
            s->dN[n][0] = gx;
            s->dN[n][1] = gy;
            n++;
        }
    s->n = n;
}
