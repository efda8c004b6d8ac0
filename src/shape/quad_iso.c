/*
 * Bilinear isoparametric quad4 on unstructured grids: x(xi, eta) = sum N_k(xi, eta) x_k with
 * N_k = (1 + xi_k xi)(1 + eta_k eta) / 4. The inverse map is found by Newton's method from the
 * centre (exact in one step for parallelograms); the gradients are dN/dx = J^-T dN/dxi.
 */
#include "pmech/approx.h"

#include "shape_internal.h"

#include <math.h>

static const double XI[4] = {-1, 1, 1, -1}, ETA[4] = {-1, -1, 1, 1};

static void shape(const double xi[2], double N[4], double dxi[4], double deta[4])
{
    for (int k = 0; k < 4; k++) {
        N[k] = 0.25 * (1 + XI[k] * xi[0]) * (1 + ETA[k] * xi[1]);
        dxi[k] = 0.25 * XI[k] * (1 + ETA[k] * xi[1]);
        deta[k] = 0.25 * ETA[k] * (1 + XI[k] * xi[0]);
    }
}

int pm_quad4_inverse_map(const pm_grid *g, int32_t cell, const double xp[2], double xi[2])
{
    const int32_t *v = g->conn + 4 * (size_t)cell;
    double X[4][2], scale = 0;
    for (int k = 0; k < 4; k++) {
        X[k][0] = g->x[2 * v[k]];
        X[k][1] = g->x[2 * v[k] + 1];
        scale = fmax(scale, fabs(X[k][0] - X[0][0]) + fabs(X[k][1] - X[0][1]));
    }
    xi[0] = xi[1] = 0;
    for (int it = 0; it < 50; it++) {
        double N[4], dxi[4], deta[4], r[2] = {-xp[0], -xp[1]}, J[2][2] = {{0, 0}, {0, 0}};
        shape(xi, N, dxi, deta);
        for (int k = 0; k < 4; k++) {
            r[0] += N[k] * X[k][0];
            r[1] += N[k] * X[k][1];
            J[0][0] += dxi[k] * X[k][0];
            J[0][1] += deta[k] * X[k][0];
            J[1][0] += dxi[k] * X[k][1];
            J[1][1] += deta[k] * X[k][1];
        }
        if (fabs(r[0]) + fabs(r[1]) <= 1e-14 * scale)
            return it;
        double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (!(fabs(det) > 0))
            return -1;
        xi[0] -= (J[1][1] * r[0] - J[0][1] * r[1]) / det;
        xi[1] -= (J[0][0] * r[1] - J[1][0] * r[0]) / det;
    }
    return -1;
}

int pm_quad4_iso_eval(const pm_grid *g, int32_t cell, const double xp[2], pm_stencil *s)
{
    double xi[2];
    if (pm_quad4_inverse_map(g, cell, xp, xi) < 0)
        return -1;
    const int32_t *v = g->conn + 4 * (size_t)cell;
    double N[4], dxi[4], deta[4], J[2][2] = {{0, 0}, {0, 0}};
    shape(xi, N, dxi, deta);
    for (int k = 0; k < 4; k++) {
        const double *x = g->x + 2 * v[k];
        J[0][0] += dxi[k] * x[0];
        J[0][1] += deta[k] * x[0];
        J[1][0] += dxi[k] * x[1];
        J[1][1] += deta[k] * x[1];
    }
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    if (!(fabs(det) > 0))
        return -1;
    /* [dN/dx, dN/dy] = [dN/dxi, dN/deta] J^-1 */
    const double i00 = J[1][1] / det, i01 = -J[0][1] / det, i10 = -J[1][0] / det, i11 = J[0][0] / det;
    s->n = 4;
    for (int k = 0; k < 4; k++) {
        s->node[k] = v[k];
        s->N[k] = N[k];
        s->dN[k][0] = dxi[k] * i00 + deta[k] * i10;
        s->dN[k][1] = dxi[k] * i01 + deta[k] * i11;
    }
    return 0;
}
