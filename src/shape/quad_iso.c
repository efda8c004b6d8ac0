/*
 * Bilinear isoparametric quad4 on unstructured grids: x(xi, eta) = sum N_k(xi, eta) x_k with
 * N_k = (1 + xi_k xi)(1 + eta_k eta) / 4, written as x = a + b xi + c eta + d xi eta. The inverse map
 * starts from the solution without the d term (exact for parallelograms, which a transfinite Gmsh
 * mesh is made of, so these need no iteration) and is refined by Newton's method; the gradients are
 * dN/dx = J^-T dN/dxi with J = [b + d eta, c + d xi].
 */
#include "pmech/approx.h"

#include "shape_internal.h"

#include <float.h>
#include <math.h>

static const double XI[4] = {-1, 1, 1, -1}, ETA[4] = {-1, -1, 1, 1};

/* The inverse map of the cell with corners X at xp and the Jacobian J there: the Newton iteration
 * count, or -1 without convergence (as pm_quad4_inverse_map). */
static int inverse(const double X[4][2], const double xp[2], double xi[2], double J[2][2])
{
    double a[2], b[2], c[2], d[2], scale = 0, mag = fabs(xp[0]) + fabs(xp[1]);
    for (int i = 0; i < 2; i++) {
        a[i] = 0.25 * (X[0][i] + X[1][i] + X[2][i] + X[3][i]);
        b[i] = 0.25 * (-X[0][i] + X[1][i] + X[2][i] - X[3][i]);
        c[i] = 0.25 * (-X[0][i] - X[1][i] + X[2][i] + X[3][i]);
        d[i] = 0.25 * (X[0][i] - X[1][i] + X[2][i] - X[3][i]);
    }
    for (int k = 0; k < 4; k++) {
        const double e = fabs(X[k][0] - X[0][0]) + fabs(X[k][1] - X[0][1]), m = fabs(X[k][0]) + fabs(X[k][1]);
        scale = e > scale ? e : scale;
        mag = m > mag ? m : mag;
    }
    /* the residual sums products of coordinates: it cannot fall below their rounding, which for a
     * small cell far from the origin (a 20 mm cell 3 m up) is larger than any fraction of the cell */
    const double tol = 1e-14 * scale + 8 * DBL_EPSILON * mag;
    xi[0] = xi[1] = 0;
    for (int it = 0; it < 50; it++) {
        J[0][0] = b[0] + d[0] * xi[1];
        J[0][1] = c[0] + d[0] * xi[0];
        J[1][0] = b[1] + d[1] * xi[1];
        J[1][1] = c[1] + d[1] * xi[0];
        const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (!(fabs(det) > 0))
            return -1;
        double r[2];
        for (int i = 0; i < 2; i++)
            r[i] = a[i] + b[i] * xi[0] + c[i] * xi[1] + d[i] * xi[0] * xi[1] - xp[i];
        if (fabs(r[0]) + fabs(r[1]) <= tol)
            return it;
        xi[0] -= (J[1][1] * r[0] - J[0][1] * r[1]) / det;
        xi[1] -= (J[0][0] * r[1] - J[1][0] * r[0]) / det;
    }
    return -1;
}

static void corners(const pm_grid *g, int32_t cell, double X[4][2])
{
    const int32_t *v = g->conn + 4 * (size_t)cell;
    for (int k = 0; k < 4; k++) {
        X[k][0] = g->x[2 * v[k]];
        X[k][1] = g->x[2 * v[k] + 1];
    }
}

int pm_quad4_inverse_map(const pm_grid *g, int32_t cell, const double xp[2], double xi[2])
{
    double X[4][2], J[2][2];
    corners(g, cell, X);
    return inverse(X, xp, xi, J);
}

int pm_quad4_iso_eval(const pm_grid *g, int32_t cell, const double xp[2], pm_stencil *s)
{
    double X[4][2], xi[2], J[2][2];
    corners(g, cell, X);
    if (inverse(X, xp, xi, J) < 0)
        return -1;
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    /* [dN/dx, dN/dy] = [dN/dxi, dN/deta] J^-1 */
    const double i00 = J[1][1] / det, i01 = -J[0][1] / det, i10 = -J[1][0] / det, i11 = J[0][0] / det;
    const int32_t *v = g->conn + 4 * (size_t)cell;
    s->n = 4;
    for (int k = 0; k < 4; k++) {
        const double dxi = 0.25 * XI[k] * (1 + ETA[k] * xi[1]), deta = 0.25 * ETA[k] * (1 + XI[k] * xi[0]);
        s->node[k] = v[k];
        s->N[k] = 0.25 * (1 + XI[k] * xi[0]) * (1 + ETA[k] * xi[1]);
        s->dN[k][0] = dxi * i00 + deta * i10;
        s->dN[k][1] = dxi * i01 + deta * i11;
    }
    return 0;
}
