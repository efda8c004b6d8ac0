/*
 * Linear-moment shape functions on a node cloud (seed 000 eqs. 50-58 for mls, seed 002 eqs. 1-14
 * for rk_cubic): N_I = w_I H^T(x - x_I) M^-1 H(0), M = sum w_I H H^T, with a linear basis H. MLS
 * weighs by the cubic spline w_I of |x - x_I| / r, RK by Phi_a(x - x_I) Delta V_I (the same spline,
 * radial or tensor product, eq. 11); shifting the basis to be centred at x multiplies M by a
 * constant invertible matrix, which cancels, so both are pm_linear_moment_shape().
 */
#include "pmech/error.h"

#include "meshfree_shape.h"

#include <math.h>
#include <string.h>

/* The spline and w'(z) / z (finite at z = 0, where the radial gradient d w / d x = w'(z)/z * d / a^2
 * is needed), inline for the weight loops; pm_cubic_spline() is the same polynomial. */
static inline double spline_w(double z, double *dw_over_z)
{
    if (z < 0.5) {
        *dw_over_z = -8.0 + 12.0 * z;
        return 2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z;
    }
    if (z < 1.0) {
        *dw_over_z = (-4.0 + 8.0 * z - 4.0 * z * z) / z;
        return 4.0 / 3.0 - 4.0 * z + 4.0 * z * z - 4.0 / 3.0 * z * z * z;
    }
    *dw_over_z = 0;
    return 0;
}

double pm_cubic_spline(double z, double *dw)
{
    if (z < 0.5) {
        if (dw)
            *dw = z * (-8.0 + 12.0 * z);
        return 2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z;
    }
    if (z < 1.0) {
        if (dw)
            *dw = -4.0 + 8.0 * z - 4.0 * z * z;
        return 4.0 / 3.0 - 4.0 * z + 4.0 * z * z - 4.0 / 3.0 * z * z * z;
    }
    if (dw)
        *dw = 0;
    return 0;
}

static double norm1_3(const double A[3][3])
{
    double m = 0;
    for (int j = 0; j < 3; j++) {
        const double c = fabs(A[0][j]) + fabs(A[1][j]) + fabs(A[2][j]);
        m = c > m ? c : m; /* not fmax(), a call here; a NaN column is caught by the det test */
    }
    return m;
}

int pm_linear_moment_shape(int n, const double (*d)[2], const double *w, const double (*dw)[2], double L,
                           double *N, double (*dN)[2], double *cond)
{
    const double iL = 1.0 / L;
    /*
     * M = sum w H H^T and, for its derivative, A_k = sum dw_k H H^T: six distinct entries each, as M
     * is symmetric. H depends on x through d = x - x_I (dH/dx_k = e_(k+1) / L), so
     * dM/dx_k = A_k + (e_(k+1) m^T + m e_(k+1)^T) / L with m = sum w H, the first column of M: the
     * loop over the nodes needs only these 18 sums.
     */
    double s[3][6]; /* rows: w, dw_x, dw_y; columns: 00, 01, 02, 11, 12, 22 */
    /* one pass per weight: 18 running sums in one loop do not fit the registers */
    for (int r = 0; r < 3; r++) {
        double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0;
        for (int i = 0; i < n; i++) {
            const double h1 = d[i][0] * iL, h2 = d[i][1] * iL, f = r ? dw[i][r - 1] : w[i];
            const double f1 = f * h1, f2 = f * h2;
            s0 += f;
            s1 += f1;
            s2 += f2;
            s3 += f1 * h1;
            s4 += f1 * h2;
            s5 += f2 * h2;
        }
        s[r][0] = s0; s[r][1] = s1; s[r][2] = s2; s[r][3] = s3; s[r][4] = s4; s[r][5] = s5;
    }
    const double M[3][3] = {{s[0][0], s[0][1], s[0][2]}, {s[0][1], s[0][3], s[0][4]}, {s[0][2], s[0][4], s[0][5]}};
    double Mk[2][3][3];
    for (int k = 0; k < 2; k++) {
        const double *a = s[k + 1];
        const double A[3][3] = {{a[0], a[1], a[2]}, {a[1], a[3], a[4]}, {a[2], a[4], a[5]}};
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                Mk[k][r][c] = A[r][c] + iL * ((r == k + 1 ? M[c][0] : 0.0) + (c == k + 1 ? M[r][0] : 0.0));
    }
    /* symmetric 3 x 3 inverse by cofactors: M is small and its condition is checked below */
    double Mi[3][3];
    Mi[0][0] = M[1][1] * M[2][2] - M[1][2] * M[2][1];
    Mi[0][1] = M[0][2] * M[2][1] - M[0][1] * M[2][2];
    Mi[0][2] = M[0][1] * M[1][2] - M[0][2] * M[1][1];
    Mi[1][1] = M[0][0] * M[2][2] - M[0][2] * M[2][0];
    Mi[1][2] = M[0][2] * M[1][0] - M[0][0] * M[1][2];
    Mi[2][2] = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    const double det = M[0][0] * Mi[0][0] + M[0][1] * (M[1][2] * M[2][0] - M[1][0] * M[2][2]) +
                       M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    const double nM = norm1_3(M);
    if (!(det > 1e-300 * nM * nM * nM) || !isfinite(det)) {
        *cond = INFINITY;
        return pm_error_set(PM_ESIM, "moment matrix is singular (%d nodes, all on a line?)", n);
    }
    const double id = 1.0 / det;
    Mi[0][0] *= id; Mi[0][1] *= id; Mi[0][2] *= id;
    Mi[1][1] *= id; Mi[1][2] *= id; Mi[2][2] *= id;
    Mi[1][0] = Mi[0][1]; Mi[2][0] = Mi[0][2]; Mi[2][1] = Mi[1][2];
    *cond = nM * norm1_3(Mi);
    /* b = M^-1 H(0), H(0) = e_0; db_k = -M^-1 (dM/dx_k) b */
    const double b[3] = {Mi[0][0], Mi[1][0], Mi[2][0]};
    double db[2][3];
    for (int k = 0; k < 2; k++) {
        double t[3];
        for (int a = 0; a < 3; a++)
            t[a] = Mk[k][a][0] * b[0] + Mk[k][a][1] * b[1] + Mk[k][a][2] * b[2];
        for (int a = 0; a < 3; a++)
            db[k][a] = -(Mi[a][0] * t[0] + Mi[a][1] * t[1] + Mi[a][2] * t[2]);
    }
    /* the basis terms over L folded into the coefficients: one multiply-add chain per output */
    const double b1 = b[1] * iL, b2 = b[2] * iL;
    const double e0[3] = {db[0][0] + b1, db[0][1] * iL, db[0][2] * iL};
    const double e1[3] = {db[1][0] + b2, db[1][1] * iL, db[1][2] * iL};
    for (int i = 0; i < n; i++) {
        const double dx = d[i][0], dy = d[i][1];
        const double bh = b[0] + b1 * dx + b2 * dy;
        N[i] = w[i] * bh;
        dN[i][0] = dw[i][0] * bh + w[i] * (e0[0] + e0[1] * dx + e0[2] * dy);
        dN[i][1] = dw[i][1] * bh + w[i] * (e1[0] + e1[1] * dx + e1[2] * dy);
    }
    return PM_OK;
}

/* ---- MLS and RK ---------------------------------------------------------------------------- */

/*
 * Radial weights w_I = W(|d_I| / a) and their gradients W'(z) / z d_I / a^2 for all n candidates,
 * which the query found strictly inside the support. Both pieces of the spline (pm_cubic_spline()'s
 * expressions) are evaluated for every node and blended with factors 0 and 1, t a + (1 - t) b,
 * which is exactly a or b: a select (?:) would be kept a branch, as IEEE traps forbid computing both
 * sides of it, while this loop vectorises; the square root and the division per node are most of
 * its cost.
 */
static void radial_weights(int n, const double (*restrict d)[2], const double *restrict q, double a,
                           double *restrict w, double (*restrict dw)[2])
{
    const double ia = 1.0 / a, ia2 = ia * ia;
    double zs[PM_STENCIL_MAX];
    for (int i = 0; i < n; i++) /* apart: sqrt() may set errno, which keeps a loop scalar */
        zs[i] = sqrt(q[i]) * ia;
    for (int i = 0; i < n; i++) {
        const double z = zs[i];
        const double t = z < 0.5, u = z < 1.0; /* inner piece; inside the support */
        const double w_in = 2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z;
        const double w_out = 4.0 / 3.0 - 4.0 * z + 4.0 * z * z - 4.0 / 3.0 * z * z * z;
        const double g_in = -8.0 + 12.0 * z;
        const double g_out = (-4.0 + 8.0 * z - 4.0 * z * z) / (z + t * (1 - z)); /* no 1 / 0 at z = 0 */
        const double g = (t * g_in + (u - t) * g_out) * ia2;
        w[i] = t * w_in + (u - t) * w_out;
        dw[i][0] = g * d[i][0];
        dw[i][1] = g * d[i][1];
    }
}

/*
 * Weights of the candidates (offsets d, squared distances q, from the query) within the support of
 * radius (half-side) a, compacted in place into idx and d (with w and dw); drops the nodes of a
 * tensor query outside the square and nodes of zero weight (zero volume, or a distance that rounds
 * to a). Returns the number kept.
 */
static int moment_weights(const mf_data *md, double a, int nf, int32_t *idx, double (*d)[2], const double *q,
                          double *w, double (*dw)[2])
{
    const double *vol = md->kind == MF_RK ? md->cloud->vol : NULL;
    int m = 0;
    if (!md->tensor) {
        radial_weights(nf, (const double (*)[2])d, q, a, w, dw);
        if (vol)
            for (int i = 0; i < nf; i++) {
                const double v = vol[idx[i]];
                w[i] *= v;
                dw[i][0] *= v;
                dw[i][1] *= v;
            }
        for (int i = 0; i < nf; i++) {
            if (!(w[i] > 0))
                continue;
            if (m < i) {
                idx[m] = idx[i];
                d[m][0] = d[i][0];
                d[m][1] = d[i][1];
                w[m] = w[i];
                dw[m][0] = dw[i][0];
                dw[m][1] = dw[i][1];
            }
            m++;
        }
        return m;
    }
    const double ia = 1.0 / a, ia2 = ia * ia;
    for (int i = 0; i < nf; i++) {
        const int32_t j = idx[i];
        const double dx = d[i][0], dy = d[i][1];
        const double v = vol ? vol[j] : 1.0;
        const double zx = fabs(dx) * ia, zy = fabs(dy) * ia;
        if (zx >= 1 || zy >= 1)
            continue;
        double gx, gy;
        const double wx = spline_w(zx, &gx), wy = spline_w(zy, &gy);
        const double wi = wx * wy * v;
        if (!(wi > 0)) /* zero-volume node: no contribution */
            continue;
        w[m] = wi;
        dw[m][0] = gx * dx * ia2 * wy * v;
        dw[m][1] = gy * dy * ia2 * wx * v;
        d[m][0] = dx;
        d[m][1] = dy;
        idx[m++] = j;
    }
    return m;
}

int pm_mf_moment_eval(const mf_data *md, const double x[2], const mf_list *L, pm_stencil *s)
{
    int32_t idx[PM_SHAPE_CAND_MAX];
    double d[PM_SHAPE_CAND_MAX][2], q[PM_SHAPE_CAND_MAX], w[PM_STENCIL_MAX], dw[PM_STENCIL_MAX][2];
    double a = md->r0, cond = INFINITY;
    int m = 0;
    for (int step = 0; step < MF_MAX_GROWTH; step++, a *= md->growth) {
        /* the square of half-side a lies within the circle of radius a sqrt 2 */
        int nf = step == 0 && L ? list_gather(md->cloud, L, x, first_radius(md), idx, d, q)
                                : pm_cloud_gather(md->cloud, x, md->tensor ? a * sqrt(2.0) : a, PM_SHAPE_CAND_MAX, idx, d, q);
        if (nf > PM_SHAPE_CAND_MAX)
            return pm_error_set(PM_ESIM, "%d nodes within %g of (%g, %g): support_radius is far too large", nf, a,
                                x[0], x[1]);
        if (md->tensor) { /* count those in the square before weighing (the buffers hold 64) */
            int in = 0;
            for (int i = 0; i < nf; i++)
                if (fabs(d[i][0]) < a && fabs(d[i][1]) < a) {
                    idx[in] = idx[i];
                    d[in][0] = d[i][0];
                    d[in][1] = d[i][1];
                    in++;
                }
            nf = in;
        }
        const int all_in = (size_t)nf == md->cloud->n;
        if (nf > PM_STENCIL_MAX)
            return pm_error_set(PM_ESIM,
                                "%d nodes within the support %g of (%g, %g), at most %d fit a stencil: "
                                "reduce support_radius",
                                nf, a, x[0], x[1], PM_STENCIL_MAX);
        if (nf >= md->min_nodes) {
            m = moment_weights(md, a, nf, idx, d, q, w, dw);
            if (m >= 3 && pm_linear_moment_shape(m, (const double (*)[2])d, w, (const double (*)[2])dw, a, s->N,
                                                 s->dN, &cond) == PM_OK &&
                cond <= md->cond_tol) {
                s->n = m;
                memcpy(s->node, idx, (size_t)m * sizeof *idx);
                return PM_OK;
            }
        }
        if (all_in)
            break;
    }
    return pm_error_set(PM_ESIM,
                        "%s at (%g, %g): no support up to radius %g gives %d nodes and a moment matrix with "
                        "condition number <= %g (last: %d nodes, condition %g)",
                        md->kind == MF_RK ? "rk_cubic" : "mls", x[0], x[1], a, md->min_nodes, md->cond_tol, m,
                        cond);
}
