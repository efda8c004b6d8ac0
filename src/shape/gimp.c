/*
 * uGIMP: generalized interpolation material point shape functions (Bardenhagen & Kober 2004) with
 * the particle domain kept at its initial size ("undeformed" GIMP; seed 003 Fig. 4c), on structured
 * quad4 grids.
 *
 * In each direction the weight of node I is the mean of its hat function over the particle's
 * domain [x_p - l, x_p + l] (l = p->hsize, the initial half-size from seeding):
 *     S_I(x_p) = 1/(2l) * integral of hat_I over [x_p - l, x_p + l],
 *     dS_I/dx_p = (hat_I(x_p + l) - hat_I(x_p - l)) / (2l),
 * and N_I = S_I(x) S_I(y). For l <= h/2 this is the classic piecewise-quadratic GIMP function.
 *
 * Boundary treatment: where the particle domain reaches past the grid edge, the hat functions of
 * the two nodes of the boundary cell are continued linearly outside the grid (node 0 keeps
 * 1 - xi, node 1 keeps xi for xi < 0). They still sum to one and reproduce x exactly, so partition
 * of unity, linear reproduction and gradient consistency hold for every particle inside the grid,
 * at the edges too; the price is a slightly negative weight (at most -l_out/(2h) for a domain
 * reaching l_out past the edge) on the second node. A zero half-size falls back to the linear
 * hat functions (the limit l -> 0).
 */
#include "pmech/approx.h"
#include "pmech/error.h"

#include "shape_internal.h"

#include <math.h>

/* Most nodes per direction: l up to 2.5 cells reaches 7 nodes. */
#define GIMP_1D_MAX 8

static int gimp_init(pm_approx *a)
{
    if (!a->grid->structured || a->grid->element != PM_QUAD4)
        return pm_error_set(PM_EINPUT, "'gimp' needs a structured quad4 grid (grid.type 'rectangle', element "
                                       "'quad4')");
    return PM_OK;
}

/* Extended hat of node k (0..n) at position u (in cell units from the origin). */
static double hat(int k, int n, double u)
{
    int c = (int)floor(u);
    if (c < 0)
        c = 0;
    if (c > n - 1)
        c = n - 1;
    double t = u - c;
    if (k == c)
        return 1 - t;
    if (k == c + 1)
        return t;
    return 0.0;
}

/*
 * 1-D weights of the nodes touched by [u - l, u + l] (cell units), n cells. Fills idx, w, dw
 * (dw in 1/cell units) and returns the count, or -1 if more than GIMP_1D_MAX nodes are touched.
 */
static int weights_1d(double u, double l, int n, int idx[GIMP_1D_MAX], double w[GIMP_1D_MAX],
                      double dw[GIMP_1D_MAX])
{
    if (l <= 1e-12) {
        int c = (int)floor(u);
        if (c < 0)
            c = 0;
        if (c > n - 1)
            c = n - 1;
        double t = u - c;
        idx[0] = c; w[0] = 1 - t; dw[0] = -1;
        idx[1] = c + 1; w[1] = t; dw[1] = 1;
        return 2;
    }
    const double a = u - l, b = u + l;
    int c0 = (int)floor(a), c1 = (int)floor(b);
    if (c0 < 0)
        c0 = 0;
    if (c1 > n - 1)
        c1 = n - 1;
    if (c1 < c0) /* both ends outside on the same side: one boundary cell */
        c1 = c0 = (a < 0 ? 0 : n - 1);
    const int first = c0, cnt = c1 - c0 + 2;
    if (cnt > GIMP_1D_MAX)
        return -1;
    for (int k = 0; k < cnt; k++) {
        idx[k] = first + k;
        w[k] = 0;
    }
    for (int c = c0; c <= c1; c++) {
        /* part of [a, b] in cell c (cells 0 and n-1 extend to -inf and +inf) */
        double s = c == 0 ? a : fmax(a, (double)c);
        double e = c == n - 1 ? b : fmin(b, (double)(c + 1));
        if (e <= s)
            continue;
        /* integral of t = x - c and of 1 - t over [s, e] */
        double it = 0.5 * ((e - c) * (e - c) - (s - c) * (s - c));
        w[c - first] += (e - s) - it;
        w[c + 1 - first] += it;
    }
    const double inv = 1.0 / (b - a);
    for (int k = 0; k < cnt; k++) {
        w[k] *= inv;
        dw[k] = (hat(idx[k], n, b) - hat(idx[k], n, a)) * inv;
    }
    return cnt;
}

static int gimp_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s)
{
    const pm_grid *g = a->grid;
    if (p->cell[ip] < 0)
        return pm_error_set(PM_ESIM, "particle %zu is outside the grid", ip);
    int ix[GIMP_1D_MAX], iy[GIMP_1D_MAX];
    double wx[GIMP_1D_MAX], wy[GIMP_1D_MAX], dwx[GIMP_1D_MAX], dwy[GIMP_1D_MAX];
    const double ihx = 1.0 / g->h[0], ihy = 1.0 / g->h[1];
    const double ux = (p->x[2 * ip] - g->origin[0]) * ihx, uy = (p->x[2 * ip + 1] - g->origin[1]) * ihy;
    const double lx = p->hsize ? p->hsize[2 * ip] * ihx : 0.0, ly = p->hsize ? p->hsize[2 * ip + 1] * ihy : 0.0;
    int nx = weights_1d(ux, lx, g->cells[0], ix, wx, dwx);
    int ny = weights_1d(uy, ly, g->cells[1], iy, wy, dwy);
    if (nx < 0 || ny < 0)
        return pm_error_set(PM_ESIM, "particle %zu: its GIMP domain (half-size %g x %g) spans more than %d nodes",
                            ip, p->hsize[2 * ip], p->hsize[2 * ip + 1], GIMP_1D_MAX);
    pm_shape_tensor_stencil(g, nx, ix, wx, dwx, ny, iy, wy, dwy, s);
    return PM_OK;
}

const pm_approx_ops pm_approx_gimp_ops = {
    .name = "gimp",
    .methods = PM_APPROX_MPM,
    .interpolating = 0,
    .linear_quad_fast = 0,
    .connect = pm_shape_connect_cells,
    .eval = gimp_eval,
    .destroy = NULL,
    .init = gimp_init,
};
