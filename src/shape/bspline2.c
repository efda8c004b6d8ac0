/*
 * Quadratic B-spline shape functions on structured quad4 grids (Steffen, Kirby & Berzins 2008):
 * one uniform C1 quadratic B-spline per grid node, centred on it, support 3h, N = S(x) S(y) with
 *     S(d) = 3/4 - (d/h)^2             for |d| <= h/2,
 *     S(d) = (3/2 - |d|/h)^2 / 2       for h/2 <= |d| <= 3h/2.
 *
 * Boundary treatment: the B-spline of the missing ghost node just outside a grid edge (node -1 or
 * n+1 in that direction) is folded onto the two nodes inside by linear extrapolation,
 * u_{-1} = 2 u_0 - u_1, i.e. N_0 += 2 N_{-1}, N_1 -= N_{-1} (likewise at the far edge). Partition of
 * unity and exact reproduction of linear fields (values and gradients) then hold everywhere in
 * the grid, edges included. In the half cell next to an edge the folded functions are exactly the
 * linear hat functions (1 - t and t), so they stay non-negative and interpolate at the boundary
 * node, which keeps nodal boundary conditions as sharp as with linear shape functions. A grid
 * needs at least one cell per direction; with one cell the functions are the linear ones.
 */
#include "pmech/approx.h"
#include "pmech/error.h"

#include "shape_internal.h"

#include <math.h>

static int bspline2_init(pm_approx *a)
{
    if (!a->grid->structured || a->grid->element != PM_QUAD4)
        return pm_error_set(PM_EINPUT, "'bspline2' needs a structured quad4 grid (grid.type 'rectangle', element "
                                       "'quad4')");
    return PM_OK;
}

/* 1-D weights at u (cell units) on n cells: up to 3 distinct nodes. */
static int weights_1d(double u, int n, int idx[3], double w[3], double dw[3])
{
    int i = (int)floor(u + 0.5);
    if (i < 0)
        i = 0;
    if (i > n)
        i = n;
    const double r = u - i; /* in [-1/2, 1/2] inside the grid */
    const double ww[3] = {0.5 * (0.5 - r) * (0.5 - r), 0.75 - r * r, 0.5 * (0.5 + r) * (0.5 + r)};
    const double dd[3] = {-(0.5 - r), -2 * r, 0.5 + r};
    const int k0 = i - 1;
    /* real nodes lo..hi (at most 3); ghosts -1 and n+1 fold onto 0, 1 and n, n-1, which lie in it */
    const int base = k0 < 0 ? 0 : k0, hi = i + 1 > n ? n : i + 1;
    double W[3] = {0, 0, 0}, D[3] = {0, 0, 0};
    for (int m = 0; m < 3; m++) {
        int k = k0 + m;
        if (k < 0) {
            W[0 - base] += 2 * ww[m]; D[0 - base] += 2 * dd[m];
            W[1 - base] -= ww[m];     D[1 - base] -= dd[m];
        } else if (k > n) {
            W[n - base] += 2 * ww[m];     D[n - base] += 2 * dd[m];
            W[n - 1 - base] -= ww[m];     D[n - 1 - base] -= dd[m];
        } else {
            W[k - base] += ww[m]; D[k - base] += dd[m];
        }
    }
    const int cnt = hi - base + 1;
    for (int m = 0; m < cnt; m++) {
        idx[m] = base + m;
        w[m] = W[m];
        dw[m] = D[m];
    }
    return cnt;
}

static int bspline2_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s)
{
    const pm_grid *g = a->grid;
    if (p->cell[ip] < 0)
        return pm_error_set(PM_ESIM, "particle %zu is outside the grid", ip);
    int ix[3], iy[3];
    double wx[3], wy[3], dwx[3], dwy[3];
    const double ihx = 1.0 / g->h[0], ihy = 1.0 / g->h[1];
    int nx = weights_1d((p->x[2 * ip] - g->origin[0]) * ihx, g->cells[0], ix, wx, dwx);
    int ny = weights_1d((p->x[2 * ip + 1] - g->origin[1]) * ihy, g->cells[1], iy, wy, dwy);
    pm_shape_tensor_stencil(g, nx, ix, wx, dwx, ny, iy, wy, dwy, s);
    return PM_OK;
}

const pm_approx_ops pm_approx_bspline2_ops = {
    .name = "bspline2",
    .methods = PM_APPROX_MPM,
    .interpolating = 0,
    .linear_quad_fast = 0,
    .connect = pm_shape_connect_cells,
    .eval = bspline2_eval,
    .destroy = NULL,
    .init = bspline2_init,
};
