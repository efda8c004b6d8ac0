/*
 * Meshfree shape functions on a node cloud, all with a linear basis:
 *
 *   mls       seed 000 eqs. 50-58: N_I = p(x)^T M^-1(x) p(x_I) w_I(x), M = sum w_I p(x_I) p(x_I)^T,
 *             w_I the cubic spline (seed 002 eq. 40) of |x - x_I| / r.
 *   rk_cubic  seed 002 eqs. 1-14: Psi_I = C(x; x - x_I) Phi_a(x - x_I) Delta V_I with the correction
 *             C = H^T(x - x_I) M^-1 H(0), Phi_a the same cubic spline, radial or tensor product (eq. 11).
 *   lme       seed 000 eq. 61 / seed 003 eqs. 33-39: N_I = exp(-beta |d_I|^2 + lambda . d_I) / Z,
 *             Newton on lambda shared with the grid kind (pm_lme_solve in lme.c).
 *
 * MLS and RK are the same construction with a linear basis (shifting the basis to be centred at x
 * multiplies M by a constant invertible matrix, which cancels), so both go through
 * pm_linear_moment_shape(); they differ in the weight: MLS uses w_I, RK uses Phi_a Delta V_I.
 *
 * The neighbours of a point are found afresh at each evaluation with the adaptive rule of seed 000
 * section 5.3: MLS/RK grow the radius until at least min_nodes nodes are inside and the moment
 * matrix is well conditioned; LME grows it until the nodes enclose the point (convex-hull
 * safeguard: outside the hull lambda diverges), then adds the next-nearest nodes one at a time
 * while cond(J) exceeds its tolerance.
 */
#include "pmech/meshfree.h"
#include "pmech/error.h"

#include "shape_internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* candidates of one query; more than this many nodes in a support is a mis-set radius anyway */
#define MF_CAND_MAX 1024
#define MF_MAX_GROWTH 60
#define MF_PRIOR_TOL 1e-6
#define MF_DEFAULT_DILATION 1.5
#define MF_DEFAULT_GAMMA 1.8
#define MF_DEFAULT_GROWTH 1.25
/* MLS: nodes that move with a flow are stretched apart along it and pressed together across it, so a
 * circular support can hold only one or two rows of nodes across the stretch; its moment matrix is
 * then nearly singular (gradients ten times their size, N down to -0.6) and the support must grow.
 * A regular or 0.3 h-jittered cloud gives 9-33. RK keeps the round-off bound: its volume-weighted
 * moments next to the edge of a particle cloud exceed 100 without being degenerate, and growing
 * them there changes the solution (the RKPM cantilever moves by 0.8 %). */
#define MF_DEFAULT_MLS_COND 1e2
#define MF_DEFAULT_MOMENT_COND 1e6
#define MF_DEFAULT_HESSIAN_COND 1e4
#define MF_DEFAULT_MIN_NODES 6
#define MF_DEFAULT_LME_MIN_NODES 3
#define MF_DEFAULT_LME_EXTRA 8

typedef enum mf_kind { MF_MLS, MF_LME, MF_RK } mf_kind;

/* Stencils of the points as of the last connect(), so that the several passes of a step evaluate
 * each point once: slot entries per point, the position they were computed at as the key. */
typedef struct mf_cache {
    size_t n, slot;    /* points, entries per point */
    int *len;          /* nodes per point; -1: not cached (evaluate afresh) */
    double *key;       /* 2 per point */
    int32_t *node;     /* slot per point */
    double *N, *dN;    /* slot, 2 slot per point */
} mf_cache;

typedef struct mf_data {
    mf_kind kind;
    pm_cloud *cloud;
    double r0, growth, cond_tol, gamma, beta;
    int min_nodes, max_extra, tensor, smooth, axisym;
    mf_cache cache;
} mf_data;

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

/* w'(z) / z, finite at z = 0 (where the radial gradient d w / d x = w'(z)/z * d / a^2 is needed) */
static double spline_dw_over_z(double z)
{
    if (z < 0.5)
        return -8.0 + 12.0 * z;
    if (z < 1.0)
        return (-4.0 + 8.0 * z - 4.0 * z * z) / z;
    return 0;
}

static double norm1_3(const double A[3][3])
{
    double m = 0;
    for (int j = 0; j < 3; j++)
        m = fmax(m, fabs(A[0][j]) + fabs(A[1][j]) + fabs(A[2][j]));
    return m;
}

int pm_linear_moment_shape(int n, const double (*d)[2], const double *w, const double (*dw)[2], double L,
                           double *N, double (*dN)[2], double *cond)
{
    const double iL = 1.0 / L;
    double M[3][3] = {{0}}, Mk[2][3][3] = {{{0}}};
    for (int i = 0; i < n; i++) {
        const double h[3] = {1.0, d[i][0] * iL, d[i][1] * iL};
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                M[a][b] += w[i] * h[a] * h[b];
                /* d(H H^T)/dx_k: H depends on x through d = x - x_I, dH/dx_k = e_(k+1) / L */
                for (int k = 0; k < 2; k++)
                    Mk[k][a][b] += dw[i][k] * h[a] * h[b] +
                                   w[i] * iL * ((a == k + 1 ? h[b] : 0.0) + (b == k + 1 ? h[a] : 0.0));
            }
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
    for (int i = 0; i < n; i++) {
        const double h[3] = {1.0, d[i][0] * iL, d[i][1] * iL};
        const double bh = b[0] + b[1] * h[1] + b[2] * h[2];
        N[i] = w[i] * bh;
        for (int k = 0; k < 2; k++) {
            const double dbh = db[k][0] + db[k][1] * h[1] + db[k][2] * h[2];
            dN[i][k] = dw[i][k] * bh + w[i] * (dbh + b[k + 1] * iL);
        }
    }
    return PM_OK;
}

/* ---- MLS and RK ---------------------------------------------------------------------------- */

/* Weights of the nodes within the support of radius (half-side) a; drops the nodes of a tensor
 * query outside the square. Returns the number kept (compacted in idx). */
static int moment_weights(const mf_data *md, const double x[2], double a, int nf, int32_t *idx, double (*d)[2],
                          double *w, double (*dw)[2])
{
    const pm_cloud *c = md->cloud;
    const double ia = 1.0 / a, ia2 = ia * ia;
    int m = 0;
    for (int i = 0; i < nf; i++) {
        const int32_t j = idx[i];
        const double dx = x[0] - c->x[2 * j], dy = x[1] - c->x[2 * j + 1];
        const double v = md->kind == MF_RK ? c->vol[j] : 1.0;
        if (md->tensor) {
            const double zx = fabs(dx) * ia, zy = fabs(dy) * ia;
            if (zx >= 1 || zy >= 1)
                continue;
            const double wx = pm_cubic_spline(zx, NULL), wy = pm_cubic_spline(zy, NULL);
            w[m] = wx * wy * v;
            dw[m][0] = spline_dw_over_z(zx) * dx * ia2 * wy * v;
            dw[m][1] = spline_dw_over_z(zy) * dy * ia2 * wx * v;
        } else {
            const double z = sqrt(dx * dx + dy * dy) * ia;
            w[m] = pm_cubic_spline(z, NULL) * v;
            const double g = spline_dw_over_z(z) * ia2 * v;
            dw[m][0] = g * dx;
            dw[m][1] = g * dy;
        }
        if (!(w[m] > 0)) /* zero-volume node: no contribution */
            continue;
        d[m][0] = dx;
        d[m][1] = dy;
        idx[m++] = j;
    }
    return m;
}

static int moment_eval(const mf_data *md, const double x[2], pm_stencil *s)
{
    int32_t idx[MF_CAND_MAX];
    double d[PM_STENCIL_MAX][2], w[PM_STENCIL_MAX], dw[PM_STENCIL_MAX][2];
    double a = md->r0, cond = INFINITY;
    int m = 0;
    for (int step = 0; step < MF_MAX_GROWTH; step++, a *= md->growth) {
        int nf;
        /* the square of half-side a lies within the circle of radius a sqrt 2 */
        pm_check(pm_cloud_query(md->cloud, x, md->tensor ? a * sqrt(2.0) : a, MF_CAND_MAX, idx, NULL, &nf));
        if (nf > MF_CAND_MAX)
            return pm_error_set(PM_ESIM, "%d nodes within %g of (%g, %g): support_radius is far too large", nf, a,
                                x[0], x[1]);
        if (md->tensor) { /* count those in the square before weighing (the buffers hold 64) */
            int in = 0;
            for (int i = 0; i < nf; i++) {
                const int32_t j = idx[i];
                if (fabs(x[0] - md->cloud->x[2 * j]) < a && fabs(x[1] - md->cloud->x[2 * j + 1]) < a)
                    idx[in++] = j;
            }
            nf = in;
        }
        if (nf > PM_STENCIL_MAX)
            return pm_error_set(PM_ESIM,
                                "%d nodes within the support %g of (%g, %g), at most %d fit a stencil: "
                                "reduce support_radius",
                                nf, a, x[0], x[1], PM_STENCIL_MAX);
        const int all_in = (size_t)nf == md->cloud->n;
        if (nf >= md->min_nodes) {
            m = moment_weights(md, x, a, nf, idx, d, w, dw);
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

/* ---- LME ----------------------------------------------------------------------------------- */

/* Is x strictly inside the convex hull of the nodes at offsets d = x - x_I? Fast sufficient test:
 * a node in each open quadrant around x (then every direction has a node strictly ahead). Exact
 * test otherwise: the largest angular gap between node directions is below pi. */
static int inside_hull(int n, const double (*d)[2])
{
    int q = 0;
    for (int i = 0; i < n; i++) {
        const double u = -d[i][0], v = -d[i][1];
        if (u > 0 && v > 0)
            q |= 1;
        else if (u < 0 && v > 0)
            q |= 2;
        else if (u < 0 && v < 0)
            q |= 4;
        else if (u > 0 && v < 0)
            q |= 8;
    }
    if (q == 15)
        return 1;
    double ang[PM_STENCIL_MAX];
    int k = 0;
    for (int i = 0; i < n; i++)
        if (d[i][0] != 0 || d[i][1] != 0) {
            const double t = atan2(-d[i][1], -d[i][0]);
            int j = k++;
            while (j > 0 && ang[j - 1] > t) {
                ang[j] = ang[j - 1];
                j--;
            }
            ang[j] = t;
        }
    if (k < 3)
        return 0;
    double gap = ang[0] + 2 * M_PI - ang[k - 1];
    for (int i = 1; i < k; i++)
        gap = fmax(gap, ang[i] - ang[i - 1]);
    /* a gap of pi within round-off means x is on an edge of the hull: lambda diverges there */
    return gap < M_PI * (1 - 1e-12);
}

/*
 * Gradients of eq. 39, grad N_I = -N_I J^-1 d_I, with d_I replaced by d_I - r, r = sum N_I d_I the
 * final Newton residual (|r| <= 1e-14 h), and J = sum N_I (d_I - r)(d_I - r)^T. Identical at
 * convergence; but then sum grad N_I = -J^-1 sum N_I (d_I - r) = 0 and
 * sum grad N_I x_I^T = J^-1 sum N_I (d_I - r) d_I^T = I hold to round-off even next to the hull,
 * where J is nearly singular and the eq. 39 form would amplify r by 1 / lambda_min(J).
 * Returns the condition number of J (seed 000 section 5.3), INFINITY when J is singular.
 */
static double lme_gradients(int n, const double (*d)[2], const double *N, double (*dN)[2])
{
    double r[2], J[3];
    pm_lme_resid_hess(n, d, N, r, J);
    const double det = J[0] * J[2] - J[1] * J[1];
    if (!(det > 0))
        return INFINITY;
    const double i0 = J[2] / det, i1 = -J[1] / det, i2 = J[0] / det;
    for (int i = 0; i < n; i++) {
        const double a = d[i][0] - r[0], b = d[i][1] - r[1];
        dN[i][0] = -N[i] * (i0 * a + i1 * b);
        dN[i][1] = -N[i] * (i1 * a + i2 * b);
    }
    const double m = 0.5 * (J[0] + J[2]), q = sqrt(0.25 * (J[0] - J[2]) * (J[0] - J[2]) + J[1] * J[1]);
    const double lo = m - q, hi = m + q;
    return lo > 0 ? hi / lo : INFINITY;
}

static int lme_cloud_eval(const mf_data *md, const double x[2], pm_stencil *s)
{
    const pm_cloud *c = md->cloud;
    int32_t idx[MF_CAND_MAX];
    double d2[MF_CAND_MAX], d[PM_STENCIL_MAX][2];
    double R = md->r0;
    int nf = 0, m = 0, found = 0;
    /* grow the search until the nearest (at most 64) nodes enclose x */
    for (int step = 0; step < MF_MAX_GROWTH && !found; step++) {
        pm_check(pm_cloud_query(c, x, R, MF_CAND_MAX, idx, d2, &nf));
        if (nf > MF_CAND_MAX)
            return pm_error_set(PM_ESIM, "lme: %d nodes within %g of (%g, %g): support_radius is far too large", nf,
                                R, x[0], x[1]);
        pm_cloud_sort_by_distance(nf, idx, d2);
        m = nf < PM_STENCIL_MAX ? nf : PM_STENCIL_MAX;
        for (int i = 0; i < m; i++) {
            d[i][0] = x[0] - c->x[2 * idx[i]];
            d[i][1] = x[1] - c->x[2 * idx[i] + 1];
        }
        if (m >= md->min_nodes && inside_hull(m, (const double (*)[2])d)) {
            found = 1;
            break;
        }
        if ((size_t)nf == c->n || nf >= PM_STENCIL_MAX)
            break;
        R *= md->growth;
    }
    if (!found)
        return pm_error_set(PM_ESIM,
                            "lme: (%g, %g) is not inside the convex hull of its %d nearest nodes (outside the "
                            "node cloud?)",
                            x[0], x[1], m);
    const double tol = PM_LME_TOL * c->h;
    double lam[2] = {0, 0};
    if (pm_lme_solve(m, (const double (*)[2])d, md->beta, tol, lam, s->N, s->dN) < 0)
        return pm_error_set(PM_ESIM, "lme: the Newton solve for lambda did not converge at (%g, %g)", x[0], x[1]);
    double kappa = lme_gradients(m, (const double (*)[2])d, s->N, s->dN);
    /* seed 000 section 5.3: while J is ill-conditioned, add the next-nearest node */
    for (int extra = 0; kappa > md->cond_tol && extra < md->max_extra && m < PM_STENCIL_MAX; extra++) {
        while (m == nf && (size_t)nf < c->n) { /* every node within R is in: look further */
            R *= md->growth;
            pm_check(pm_cloud_query(c, x, R, MF_CAND_MAX, idx, d2, &nf));
            if (nf > MF_CAND_MAX) { /* an unordered subset: stop adding rather than add a wrong node */
                nf = m;
                break;
            }
            pm_cloud_sort_by_distance(nf, idx, d2);
        }
        if (m == nf)
            break;
        d[m][0] = x[0] - c->x[2 * idx[m]];
        d[m][1] = x[1] - c->x[2 * idx[m] + 1];
        double N2[PM_STENCIL_MAX], dN2[PM_STENCIL_MAX][2], lam2[2] = {lam[0], lam[1]};
        /* warm start from the m-node lambda; next to the hull that lambda is large and can put the
         * new node's weight far off, so a failure retries from lambda = 0 */
        if (pm_lme_solve(m + 1, (const double (*)[2])d, md->beta, tol, lam2, N2, dN2) < 0) {
            lam2[0] = lam2[1] = 0;
            if (pm_lme_solve(m + 1, (const double (*)[2])d, md->beta, tol, lam2, N2, dN2) < 0)
                break; /* keep the converged solution with m nodes */
        }
        m++;
        lam[0] = lam2[0];
        lam[1] = lam2[1];
        memcpy(s->N, N2, (size_t)m * sizeof *N2);
        kappa = lme_gradients(m, (const double (*)[2])d, s->N, s->dN);
    }
    if (isinf(kappa))
        return pm_error_set(PM_ESIM, "lme: singular Hessian at (%g, %g) with %d nodes", x[0], x[1], m);
    s->n = m;
    memcpy(s->node, idx, (size_t)m * sizeof *idx);
    return PM_OK;
}

/* ---- the approximation --------------------------------------------------------------------- */

static void cache_free(mf_cache *c)
{
    free(c->len);
    free(c->key);
    free(c->node);
    free(c->N);
    free(c->dN);
    memset(c, 0, sizeof *c);
}

static int cache_alloc(mf_cache *c, size_t n, size_t slot)
{
    cache_free(c);
    c->len = malloc((n ? n : 1) * sizeof *c->len);
    c->key = malloc(2 * (n ? n : 1) * sizeof *c->key);
    c->node = malloc((n ? n : 1) * slot * sizeof *c->node);
    c->N = malloc((n ? n : 1) * slot * sizeof *c->N);
    c->dN = malloc(2 * (n ? n : 1) * slot * sizeof *c->dN);
    if (!c->len || !c->key || !c->node || !c->N || !c->dN) {
        cache_free(c);
        return pm_error_set(PM_ENOMEM, "out of memory for %zu meshfree stencils", n);
    }
    c->n = n;
    c->slot = slot;
    return PM_OK;
}

/*
 * Stabilised conforming nodal integration (Chen et al. 2001): when the integration points are the
 * nodes themselves (RKPM), point gradients leave spurious zero-energy modes and fail the linear
 * patch test. The gradient at a point is instead the average over its cell, a square of the
 * point's area centred on it: grad N_I = 1/A * boundary integral of N_I n, by two Gauss points on
 * each side. The cells of seeded particles tile the body, so the smoothed gradients integrate a
 * linear field exactly (the integration constraint that makes the patch test pass). Values N stay
 * those at the point.
 */
static int smoothed_eval(const pm_approx *a, const double x[2], double half, pm_stencil *s)
{
    pm_check(pm_meshfree_eval(a, x, s));
    for (int k = 0; k < s->n; k++)
        s->dN[k][0] = s->dN[k][1] = 0.0;
    static const double g = 0.57735026918962576; /* 1 / sqrt 3 */
    static const double nrm[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (int e = 0; e < 4; e++) {
        for (int q = 0; q < 2; q++) {
            const double t = (q ? g : -g) * half;
            const double xq[2] = {x[0] + nrm[e][0] * half - nrm[e][1] * t, x[1] + nrm[e][1] * half + nrm[e][0] * t};
            pm_stencil sq;
            pm_check(pm_meshfree_eval(a, xq, &sq));
            for (int k = 0; k < sq.n; k++) {
                int at = 0;
                while (at < s->n && s->node[at] != sq.node[k])
                    at++;
                if (at == s->n) {
                    if (s->n == PM_STENCIL_MAX)
                        return pm_error_set(PM_ESIM, "the smoothing cell at (%g, %g) touches more than %d nodes: "
                                            "reduce support_radius", x[0], x[1], PM_STENCIL_MAX);
                    s->node[at] = sq.node[k];
                    s->N[at] = 0.0;
                    s->dN[at][0] = s->dN[at][1] = 0.0;
                    s->n++;
                }
                /* each Gauss point weighs half a side: half; the area is (2 half)^2 */
                const double w = sq.N[k] * half / (4 * half * half);
                s->dN[at][0] += w * nrm[e][0];
                s->dN[at][1] += w * nrm[e][1];
            }
        }
    }
    return PM_OK;
}

/* Evaluate every point once into the cache. A stencil longer than the slot leaves the point
 * uncached and reports its length, so that the caller can widen the slot and try again. */
static int cache_fill(pm_approx *a, const pm_particles *p, long *bad, int *longest)
{
    const mf_data *md = a->data;
    const mf_cache *c = &md->cache;
    const int axisym = md->axisym;
    long first_bad = LONG_MAX;
    int most = 0;
#pragma omp parallel for schedule(dynamic, 256) num_threads(a->n_threads) reduction(min : first_bad) \
    reduction(max : most)
    for (size_t i = 0; i < p->n; i++) {
        pm_stencil st;
        const double *x = p->x + 2 * i;
        c->len[i] = -1;
        c->key[2 * i] = x[0];
        c->key[2 * i + 1] = x[1];
        /* the cell of a point: its area (per radian in axisymmetric runs the volume is r times it) */
        const double area = p->vol && p->vol[i] > 0 ? p->vol[i] / (axisym && x[0] > 0 ? x[0] : 1.0) : 0.0;
        const int rc = md->smooth && area > 0 ? smoothed_eval(a, x, 0.5 * sqrt(area), &st)
                                              : pm_meshfree_eval(a, x, &st);
        if (rc != PM_OK) {
            first_bad = (long)i < first_bad ? (long)i : first_bad;
            continue;
        }
        most = st.n > most ? st.n : most;
        if ((size_t)st.n > c->slot)
            continue;
        const size_t o = i * c->slot;
        memcpy(c->node + o, st.node, (size_t)st.n * sizeof *st.node);
        memcpy(c->N + o, st.N, (size_t)st.n * sizeof *st.N);
        memcpy(c->dN + 2 * o, st.dN, 2 * (size_t)st.n * sizeof(double));
        c->len[i] = st.n;
    }
    *bad = first_bad;
    *longest = most;
    return PM_OK;
}

/* Refresh the cell list, then the shape functions of every point at its current position. The
 * cache is sized on the first call and widened only when a stencil outgrows it. */
static int mf_connect(pm_approx *a, pm_particles *p)
{
    mf_data *md = a->data;
    pm_check(pm_cloud_update(md->cloud, NULL));
    if (!p || p->n == 0)
        return PM_OK;
    if (md->cache.n != p->n || md->cache.slot == 0)
        pm_check(cache_alloc(&md->cache, p->n, md->cache.slot ? md->cache.slot : 24));
    long bad;
    int longest;
    pm_check(cache_fill(a, p, &bad, &longest));
    if (bad == LONG_MAX && (size_t)longest > md->cache.slot) {
        pm_check(cache_alloc(&md->cache, p->n, (size_t)longest + 4));
        pm_check(cache_fill(a, p, &bad, &longest));
    }
    if (bad != LONG_MAX) {
        pm_stencil st;
        int rc = pm_meshfree_eval(a, p->x + 2 * bad, &st);
        return pm_error_prefix(rc ? rc : PM_ESIM, "particle %ld at (%g, %g): ", bad, p->x[2 * bad],
                               p->x[2 * bad + 1]);
    }
    return PM_OK;
}

static int mf_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s)
{
    const mf_cache *c = &((const mf_data *)a->data)->cache;
    const double *x = p->x + 2 * ip;
    if (ip < c->n && c->len[ip] >= 0 && c->key[2 * ip] == x[0] && c->key[2 * ip + 1] == x[1]) {
        const size_t o = ip * c->slot;
        s->n = c->len[ip];
        memcpy(s->node, c->node + o, (size_t)s->n * sizeof *s->node);
        memcpy(s->N, c->N + o, (size_t)s->n * sizeof *s->N);
        memcpy(s->dN, c->dN + 2 * o, 2 * (size_t)s->n * sizeof(double));
        return PM_OK;
    }
    int rc = pm_meshfree_eval(a, x, s);
    return rc ? pm_error_prefix(rc, "particle %zu: ", ip) : PM_OK;
}

static void mf_destroy(pm_approx *a)
{
    mf_data *md = a->data;
    if (md)
        cache_free(&md->cache);
    free(a->data);
    a->data = NULL;
}

static const pm_approx_ops mls_ops = {.name = "mls", .connect = mf_connect, .eval = mf_eval, .destroy = mf_destroy};
static const pm_approx_ops lme_ops = {.name = "lme", .connect = mf_connect, .eval = mf_eval, .destroy = mf_destroy};
static const pm_approx_ops rk_ops = {.name = "rk_cubic", .connect = mf_connect, .eval = mf_eval,
                                     .destroy = mf_destroy};

int pm_approx_is_meshfree(const pm_approx *a)
{
    return a && (a->ops == &mls_ops || a->ops == &lme_ops || a->ops == &rk_ops);
}

pm_cloud *pm_meshfree_cloud(const pm_approx *a)
{
    return pm_approx_is_meshfree(a) ? ((const mf_data *)a->data)->cloud : NULL;
}

double pm_meshfree_radius(const pm_approx *a)
{
    return pm_approx_is_meshfree(a) ? ((const mf_data *)a->data)->r0 : NAN;
}

int pm_meshfree_eval(const pm_approx *a, const double x[2], pm_stencil *s)
{
    if (!pm_approx_is_meshfree(a))
        return pm_error_set(PM_EINPUT, "pm_meshfree_eval: '%s' is not a meshfree approximation",
                            a ? a->ops->name : "(null)");
    const mf_data *md = a->data;
    s->n = 0;
    if (!isfinite(x[0]) || !isfinite(x[1]))
        return pm_error_set(PM_ESIM, "%s: non-finite point (%g, %g)", a->ops->name, x[0], x[1]);
    return md->kind == MF_LME ? lme_cloud_eval(md, x, s) : moment_eval(md, x, s);
}

pm_meshfree_opts pm_meshfree_opts_default(void)
{
    return (pm_meshfree_opts){.support_radius = NAN, .dilation = NAN, .lme_gamma = NAN, .cond_tol = NAN,
                              .growth = NAN, .min_nodes = 0, .lme_max_extra = 0, .rk_tensor = 0,
                              .smoothing = 0, .axisymmetric = 0};
}

/* A set option must be a positive finite number; NAN means "default". */
static int opt_value(double v, double def, const char *what, double *out)
{
    if (isnan(v)) {
        *out = def;
        return PM_OK;
    }
    if (!(v > 0) || !isfinite(v))
        return pm_error_set(PM_EINPUT, "%s must be a positive number, not %g", what, v);
    *out = v;
    return PM_OK;
}

int pm_approx_create_cloud(const char *name, pm_cloud *cloud, const pm_meshfree_opts *opts, pm_approx **out)
{
    *out = NULL;
    const pm_approx_ops *ops = NULL;
    mf_kind kind = MF_MLS;
    if (strcmp(name, "mls") == 0)
        ops = &mls_ops;
    else if (strcmp(name, "lme") == 0) {
        ops = &lme_ops;
        kind = MF_LME;
    } else if (strcmp(name, "rk_cubic") == 0) {
        ops = &rk_ops;
        kind = MF_RK;
    } else
        return pm_error_set(PM_EINPUT, "shape_function '%s' is not available on a node cloud; available: mls, lme, "
                            "rk_cubic", name);
    if (!cloud)
        return pm_error_set(PM_EINPUT, "%s: no node cloud", name);
    const pm_meshfree_opts o = opts ? *opts : pm_meshfree_opts_default();
    mf_data *md = calloc(1, sizeof *md);
    if (!md)
        return pm_error_set(PM_ENOMEM, "out of memory");
    md->kind = kind;
    md->cloud = cloud;
    const double h = cloud->h;
    double f = MF_DEFAULT_DILATION;
    int rc = opt_value(o.dilation, MF_DEFAULT_DILATION, "dilation", &f);
    if (!rc)
        rc = opt_value(o.lme_gamma, MF_DEFAULT_GAMMA, "lme_gamma", &md->gamma);
    if (!rc)
        rc = opt_value(o.growth, MF_DEFAULT_GROWTH, "growth", &md->growth);
    if (!rc)
        rc = opt_value(o.cond_tol, kind == MF_LME ? MF_DEFAULT_HESSIAN_COND
                                       : kind == MF_MLS ? MF_DEFAULT_MLS_COND : MF_DEFAULT_MOMENT_COND,
                       "cond_tol",
                       &md->cond_tol);
    md->beta = md->gamma / (h * h);
    const double r_def = kind == MF_LME ? fmax(h * sqrt(-log(MF_PRIOR_TOL) / md->gamma), sqrt(2.0) * h)
                                        : f * sqrt(2.0 * h * h);
    if (!rc)
        rc = opt_value(o.support_radius, r_def, "support_radius", &md->r0);
    md->min_nodes = o.min_nodes > 0 ? o.min_nodes : kind == MF_LME ? MF_DEFAULT_LME_MIN_NODES : MF_DEFAULT_MIN_NODES;
    md->max_extra = o.lme_max_extra > 0 ? o.lme_max_extra : MF_DEFAULT_LME_EXTRA;
    md->tensor = kind == MF_RK && o.rk_tensor;
    md->smooth = o.smoothing > 0 || (o.smoothing == 0 && kind == MF_RK);
    md->axisym = o.axisymmetric != 0;
    if (!rc && !(md->growth > 1))
        rc = pm_error_set(PM_EINPUT, "%s: growth must exceed 1, not %g", name, md->growth);
    if (!rc && (md->min_nodes < 3 || md->min_nodes > PM_STENCIL_MAX || o.min_nodes < 0))
        rc = pm_error_set(PM_EINPUT, "%s: min_nodes must be 3 to %d, not %d", name, PM_STENCIL_MAX, o.min_nodes);
    if (!rc && o.lme_max_extra < 0)
        rc = pm_error_set(PM_EINPUT, "%s: lme_max_extra must not be negative", name);
    if (rc) {
        free(md);
        return rc;
    }
    pm_approx *a = calloc(1, sizeof *a);
    if (!a) {
        free(md);
        return pm_error_set(PM_ENOMEM, "out of memory");
    }
    a->ops = ops;
    a->grid = NULL;
    a->n_threads = 1;
    a->data = md;
    a->opts.lme_gamma = md->gamma;
    a->opts.support_radius = md->r0;
    *out = a;
    return PM_OK;
}
