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

/* Candidate lists, one per point that is evaluated again and again (the solver's material points,
 * the cloud's nodes): the nodes near where the list was made, which answer the point's first query
 * while they are sure to hold every node of its support (lists_get()). */
typedef struct mf_lists {
    size_t n, slot;    /* lists, entries per list */
    int32_t *node;     /* slot per list */
    int *len;          /* -1: none */
    double *x;         /* 2 per list: where it was made */
    size_t *build;     /* the cloud's n_builds when it was made */
} mf_lists;

/* Stencils of the points as of the last connect(), so that the several passes of a step evaluate
 * each point once: slot entries per point, the position they were computed at as the key. LME also
 * keeps each point's lambda, the start of its next Newton solve. */
typedef struct mf_cache {
    size_t n, slot;    /* points, entries per point */
    int *len;          /* nodes per point; -1: not cached (evaluate afresh) */
    double *key;       /* 2 per point (NAN: never evaluated) */
    int32_t *node;     /* slot per point */
    double *N, *dN;    /* slot, 2 slot per point */
    double *lam;       /* LME: 2 per point, lambda at key (0, 0: none) */
    mf_lists lists;    /* one per point */
} mf_cache;

typedef struct mf_data {
    mf_kind kind;
    pm_cloud *cloud;
    double r0, growth, cond_tol, gamma, beta;
    int min_nodes, max_extra, tensor, smooth, axisym;
    mf_cache cache;
    /* pm_meshfree_eval_node(): per cloud node, its candidate list and (LME) last lambda */
    mf_lists node_lists;
    double *node_lam;
} mf_data;

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

/* A point's candidate list: the nodes that were within some radius R_L of a nearby position (see
 * cache_fill()). NULL where the cell list is to be searched instead. */
typedef struct mf_list {
    const int32_t *node;
    int n;
} mf_list;

/* The nodes of a candidate list within r of x, with their offsets x - x_I and squared distances:
 * what pm_cloud_gather() gives, in the same order (the list is a cell-list query of the same build),
 * without visiting cells or testing the nodes outside R_L. */
static int list_gather(const pm_cloud *c, const mf_list *L, const double x[2], double r, int32_t *restrict idx,
                       double (*restrict d)[2], double *restrict q)
{
    const double r2 = r * r, x0 = x[0], x1 = x[1];
    const double *restrict xc = c->x;
    int n = 0;
    for (int k = 0; k < L->n; k++) {
        const int32_t j = L->node[k];
        const double dx = x0 - xc[2 * (size_t)j], dy = x1 - xc[2 * (size_t)j + 1];
        const double qq = dx * dx + dy * dy;
        idx[n] = j;
        d[n][0] = dx;
        d[n][1] = dy;
        q[n] = qq;
        n += qq < r2;
    }
    return n;
}

/* The query radius of the first (not grown) support: the tensor kernel's square of half-side r0
 * lies within the circle of radius r0 sqrt 2. */
static double first_radius(const mf_data *md)
{
    return md->tensor ? md->r0 * sqrt(2.0) : md->r0;
}

static int moment_eval(const mf_data *md, const double x[2], const mf_list *L, pm_stencil *s)
{
    int32_t idx[MF_CAND_MAX];
    double d[MF_CAND_MAX][2], q[MF_CAND_MAX], w[PM_STENCIL_MAX], dw[PM_STENCIL_MAX][2];
    double a = md->r0, cond = INFINITY;
    int m = 0;
    for (int step = 0; step < MF_MAX_GROWTH; step++, a *= md->growth) {
        /* the square of half-side a lies within the circle of radius a sqrt 2 */
        int nf = step == 0 && L ? list_gather(md->cloud, L, x, first_radius(md), idx, d, q)
                                : pm_cloud_gather(md->cloud, x, md->tensor ? a * sqrt(2.0) : a, MF_CAND_MAX, idx, d, q);
        if (nf > MF_CAND_MAX)
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

/* ---- LME ----------------------------------------------------------------------------------- */

/* Monotone in the angle of (u, v) on [0, 2 pi), with values in [0, 4): sorts directions as atan2
 * would, at the cost of one division. */
static inline double pseudo_angle(double u, double v)
{
    if (v >= 0)
        return u >= 0 ? v / (u + v) : 1 - u / (v - u);
    return u < 0 ? 2 - v / (-u - v) : 3 + u / (u - v);
}

/*
 * Is x strictly inside the convex hull of the nodes at offsets d = x - x_I? Fast sufficient tests
 * first: a node in each open quadrant around x (then every direction has a node strictly ahead)
 * says yes; no node strictly left of x, or right, below or above it (x on or beyond the hull, as
 * at a node on a straight side of the cloud, evaluated there every step) says no. Otherwise the
 * exact test without atan2(): the
 * largest angular gap between successive node directions is below pi, i.e. below pi (1 - 1e-12),
 * since a gap of pi within round-off means x is on an edge of the hull, where lambda diverges.
 * Successive directions a, b (by angle) have a gap below that when a x b > sin(1e-12 pi) |a| |b|,
 * or, for gaps below pi / 2, when a . b > 0; there a x b may come out a hair negative where two
 * directions agree to round-off and their order did not (harmless: a set of directions that spans
 * no more than pi / 2 has an empty axis half-plane, so no true gap near 2 pi gets this far).
 */
static int inside_hull(int n, const double (*d)[2])
{
    int q = 0;
    for (int i = 0; i < n; i++) { /* u = -d_x > 0 etc.; & and | so that only the exit branches */
        const int ur = d[i][0] < 0, ul = d[i][0] > 0, va = d[i][1] < 0, vb = d[i][1] > 0;
        q |= (ur & va) | (ul & va) << 1 | (ul & vb) << 2 | (ur & vb) << 3;
        if (q == 15)
            return 1;
    }
    int h = 0;
    for (int i = 0; i < n; i++)
        h |= (d[i][0] < 0) | (d[i][0] > 0) << 1 | (d[i][1] < 0) << 2 | (d[i][1] > 0) << 3;
    if (h != 15)
        return 0;
    double ang[PM_STENCIL_MAX], dir[PM_STENCIL_MAX][2];
    int k = 0;
    for (int i = 0; i < n && i < PM_STENCIL_MAX; i++)
        if (d[i][0] != 0 || d[i][1] != 0) {
            const double u = -d[i][0], v = -d[i][1], t = pseudo_angle(u, v);
            int j = k++;
            while (j > 0 && ang[j - 1] > t) {
                ang[j] = ang[j - 1];
                dir[j][0] = dir[j - 1][0];
                dir[j][1] = dir[j - 1][1];
                j--;
            }
            ang[j] = t;
            dir[j][0] = u;
            dir[j][1] = v;
        }
    if (k < 3)
        return 0;
    const double s_tol = sin(1e-12 * M_PI);
    for (int i = 0; i < k; i++) {
        const double *a = dir[i == 0 ? k - 1 : i - 1], *b = dir[i];
        const double cr = a[0] * b[1] - a[1] * b[0], dt = a[0] * b[0] + a[1] * b[1];
        const double ab = sqrt((a[0] * a[0] + a[1] * a[1]) * (b[0] * b[0] + b[1] * b[1]));
        if (!(cr > s_tol * ab || (dt > 0 && cr > -s_tol * ab)))
            return 0;
    }
    return 1;
}

/*
 * Gradients of eq. 39, grad N_I = -N_I J^-1 d_I, with d_I replaced by d_I - r, r = sum N_I d_I the
 * final Newton residual (|r| <= 1e-14 h), and J = sum N_I (d_I - r)(d_I - r)^T. Identical at
 * convergence; but then sum grad N_I = -J^-1 sum N_I (d_I - r) = 0 and
 * sum grad N_I x_I^T = J^-1 sum N_I (d_I - r) d_I^T = I hold to round-off even next to the hull,
 * where J is nearly singular and the eq. 39 form would amplify r by 1 / lambda_min(J). r and J are
 * those the Newton solve formed last, at N (pm_lme_newton()).
 * Returns the condition number of J (seed 000 section 5.3), INFINITY when J is singular.
 */
static double lme_gradients(int n, const double (*d)[2], const double *N, const double r[2], const double J[3],
                            double (*dN)[2])
{
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

/* Nearer by distance, ties by node index: the order that picks "the k nearest" uniquely. */
static inline int nearer(const int32_t *idx, const double *d2, int a, int b)
{
    return d2[a] < d2[b] || (d2[a] == d2[b] && idx[a] < idx[b]);
}

static inline void swap_entry(int32_t *idx, double (*d)[2], double *d2, int a, int b)
{
    const int32_t ti = idx[a];
    const double t0 = d[a][0], t1 = d[a][1], tq = d2[a];
    idx[a] = idx[b]; d[a][0] = d[b][0]; d[a][1] = d[b][1]; d2[a] = d2[b];
    idx[b] = ti; d[b][0] = t0; d[b][1] = t1; d2[b] = tq;
}

/* Moves the nearest of entries from..n-1 to position from. */
static void bring_nearest(int from, int n, int32_t *idx, double (*d)[2], double *d2)
{
    int k = from;
    for (int j = from + 1; j < n; j++)
        if (nearer(idx, d2, j, k))
            k = j;
    swap_entry(idx, d, d2, from, k);
}

/* Moves the k nearest of the n entries to the front, in no particular order (quickselect: linear
 * on average, where picking them one by one costs k n). */
static void select_nearest(int k, int n, int32_t *idx, double (*d)[2], double *d2)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        swap_entry(idx, d, d2, (lo + hi) / 2, hi); /* the middle entry as pivot, parked at hi */
        int store = lo;
        for (int i = lo; i < hi; i++)
            if (nearer(idx, d2, i, hi))
                swap_entry(idx, d, d2, i, store++);
        swap_entry(idx, d, d2, store, hi); /* entries before store are nearer than the pivot */
        if (store == k - 1 || store == k)
            return;
        if (store < k)
            lo = store + 1;
        else
            hi = store - 1;
    }
}

/* Newton from lam; a start that fails (warm, next to the hull) is retried from lambda = 0. */
static int lme_newton_retry(int n, const double (*d)[2], double beta, double tol, double lam[2], double *N,
                            double r[2], double J[3])
{
    const int warm = lam[0] != 0 || lam[1] != 0;
    int it = pm_lme_newton(n, d, beta, tol, lam, N, r, J);
    if (it < 0 && warm) {
        lam[0] = lam[1] = 0;
        it = pm_lme_newton(n, d, beta, tol, lam, N, r, J);
    }
    return it;
}

/*
 * LME at x. lam: in, the starting lambda (0, 0 for none; from the lambda of a point that moved
 * little since, the Newton steps are small enough to be taken without exponentials, see
 * pm_lme_newton()); out, the solution. The stencil is the support's nodes in the order the query found them
 * (the 64 nearest, nearest first, when more), then any added ones nearest first: the node set
 * is what decides the functions, its order only the round-off of the sums.
 */
static int lme_cloud_eval(const mf_data *md, const double x[2], double lam[2], const mf_list *L, pm_stencil *s)
{
    const pm_cloud *c = md->cloud;
    int32_t idx[MF_CAND_MAX];
    double d2[MF_CAND_MAX], d[MF_CAND_MAX][2];
    double R = md->r0;
    int nf = 0, m = 0, found = 0;
    /* grow the search until the nearest (at most 64) nodes enclose x */
    for (int step = 0; step < MF_MAX_GROWTH && !found; step++) {
        nf = step == 0 && L ? list_gather(c, L, x, R, idx, d, d2) : pm_cloud_gather(c, x, R, MF_CAND_MAX, idx, d, d2);
        if (nf > MF_CAND_MAX)
            return pm_error_set(PM_ESIM, "lme: %d nodes within %g of (%g, %g): support_radius is far too large", nf,
                                R, x[0], x[1]);
        m = nf < PM_STENCIL_MAX ? nf : PM_STENCIL_MAX;
        if (nf > PM_STENCIL_MAX)
            select_nearest(m, nf, idx, d, d2);
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
    double r[2], J[3];
    const int warm = lam[0] != 0 || lam[1] != 0;
    if (lme_newton_retry(m, (const double (*)[2])d, md->beta, tol, lam, s->N, r, J) < 0)
        return pm_error_set(PM_ESIM, "lme: the Newton solve for lambda did not converge at (%g, %g)", x[0], x[1]);
    double kappa = lme_gradients(m, (const double (*)[2])d, s->N, r, J, s->dN);
    /* Where the start changes lambda beyond round-off: the solve stops at |r| <= tol, which leaves
     * lambda uncertain by about tol / lambda_min(J), so near the hull (J ill-conditioned) a warm and
     * a cold start can end on different sides of cond_tol or of a failure, and the stencil would
     * depend on the history. There the solve is redone from lambda = 0, as without a start. */
    if (warm && kappa > 1e-2 * md->cond_tol) {
        lam[0] = lam[1] = 0;
        if (pm_lme_newton(m, (const double (*)[2])d, md->beta, tol, lam, s->N, r, J) < 0)
            return pm_error_set(PM_ESIM, "lme: the Newton solve for lambda did not converge at (%g, %g)", x[0],
                                x[1]);
        kappa = lme_gradients(m, (const double (*)[2])d, s->N, r, J, s->dN);
    }
    /* seed 000 section 5.3: while J is ill-conditioned, add the next-nearest node */
    for (int extra = 0; kappa > md->cond_tol && extra < md->max_extra && m < PM_STENCIL_MAX; extra++) {
        while (m == nf && (size_t)nf < c->n) {
            /* every node within R is in: look further, and keep only the nodes beyond R (the
             * query computes the same squared distances, so the test is exact) */
            const double r2_in = R * R;
            R *= md->growth;
            const int got = pm_cloud_gather(c, x, R, MF_CAND_MAX - m, idx + m, d + m, d2 + m);
            if (got > MF_CAND_MAX - m) { /* an unordered subset: stop adding rather than add a wrong node */
                nf = m;
                break;
            }
            nf = m;
            for (int i = m; i < m + got; i++)
                if (!(d2[i] < r2_in)) {
                    idx[nf] = idx[i];
                    d[nf][0] = d[i][0];
                    d[nf][1] = d[i][1];
                    d2[nf++] = d2[i];
                }
        }
        if (m == nf)
            break;
        bring_nearest(m, nf, idx, d, d2);
        double N2[PM_STENCIL_MAX], lam2[2] = {lam[0], lam[1]};
        /* warm start from the m-node lambda; next to the hull that lambda is large and can put the
         * new node's weight far off, so a failure retries from lambda = 0 */
        if (lme_newton_retry(m + 1, (const double (*)[2])d, md->beta, tol, lam2, N2, r, J) < 0)
            break; /* keep the converged solution with m nodes */
        m++;
        lam[0] = lam2[0];
        lam[1] = lam2[1];
        memcpy(s->N, N2, (size_t)m * sizeof *N2);
        kappa = lme_gradients(m, (const double (*)[2])d, s->N, r, J, s->dN);
    }
    if (isinf(kappa))
        return pm_error_set(PM_ESIM, "lme: singular Hessian at (%g, %g) with %d nodes", x[0], x[1], m);
    s->n = m;
    memcpy(s->node, idx, (size_t)m * sizeof *idx);
    return PM_OK;
}

/* ---- the approximation --------------------------------------------------------------------- */

/* Margin of the candidate lists: a list made at x_L with radius R_L = r + 2 skin + delta holds every
 * node within r of any x with |x - x_L| <= delta as long as the cell list was not rebuilt, since
 * every node then moved at most 2 skin since the list was made (skin each side of its build). */
static double list_delta(const pm_cloud *c)
{
    return c->skin;
}

static double list_radius(const mf_data *md)
{
    return first_radius(md) + 2 * md->cloud->skin + list_delta(md->cloud);
}

static void lists_free(mf_lists *L)
{
    free(L->node);
    free(L->len);
    free(L->x);
    free(L->build);
    memset(L, 0, sizeof *L);
}

static int lists_alloc(mf_lists *L, const mf_data *md, size_t n)
{
    lists_free(L);
    const size_t n1 = n ? n : 1;
    /* room for 1.5 times the nodes of a list's disc in a cloud of spacing h (a denser spot makes
     * lists that do not fit: those points search the cell list) */
    const double rl = list_radius(md) / md->cloud->h;
    const double want = 1.5 * M_PI * rl * rl + 8;
    L->slot = want < 16 ? 16 : want > MF_CAND_MAX ? MF_CAND_MAX : (size_t)want;
    L->node = malloc(n1 * L->slot * sizeof *L->node);
    L->len = malloc(n1 * sizeof *L->len);
    L->x = malloc(2 * n1 * sizeof *L->x);
    L->build = malloc(n1 * sizeof *L->build);
    if (!L->node || !L->len || !L->x || !L->build) {
        lists_free(L);
        return pm_error_set(PM_ENOMEM, "out of memory for %zu candidate lists", n);
    }
    for (size_t i = 0; i < n; i++)
        L->len[i] = -1;
    L->n = n;
    return PM_OK;
}

/* List i for a point now at x: kept while x is within delta of where it was made and the cell list
 * was not rebuilt since, made anew otherwise (and then kept for the next calls). NULL when the
 * list does not fit its slot: the caller searches the cell list. */
static const mf_list *lists_get(const mf_data *md, const mf_lists *L, size_t i, const double x[2], mf_list *out)
{
    int32_t *node = L->node + i * L->slot;
    double *xl = L->x + 2 * i;
    const double dx = x[0] - xl[0], dy = x[1] - xl[1], delta = list_delta(md->cloud);
    if (L->len[i] < 0 || L->build[i] != md->cloud->n_builds || !(dx * dx + dy * dy <= delta * delta)) {
        if (!isfinite(x[0]) || !isfinite(x[1]))
            return NULL;
        const int n = pm_cloud_gather(md->cloud, x, list_radius(md), (int)L->slot, node, NULL, NULL);
        L->len[i] = n <= (int)L->slot ? n : -1;
        L->build[i] = md->cloud->n_builds;
        xl[0] = x[0];
        xl[1] = x[1];
    }
    if (L->len[i] < 0)
        return NULL;
    out->node = node;
    out->n = L->len[i];
    return out;
}

static void cache_free(mf_cache *c)
{
    free(c->len);
    free(c->key);
    free(c->node);
    free(c->N);
    free(c->dN);
    free(c->lam);
    lists_free(&c->lists);
    memset(c, 0, sizeof *c);
}

static int cache_alloc(mf_cache *c, const mf_data *md, size_t n, size_t slot)
{
    cache_free(c);
    const size_t n1 = n ? n : 1;
    c->len = malloc(n1 * sizeof *c->len);
    c->key = malloc(2 * n1 * sizeof *c->key);
    c->node = malloc(n1 * slot * sizeof *c->node);
    c->N = malloc(n1 * slot * sizeof *c->N);
    c->dN = malloc(2 * n1 * slot * sizeof *c->dN);
    c->lam = calloc(2 * n1, sizeof *c->lam);
    if (!c->len || !c->key || !c->node || !c->N || !c->dN || !c->lam || lists_alloc(&c->lists, md, n)) {
        cache_free(c);
        return pm_error_set(PM_ENOMEM, "out of memory for %zu meshfree stencils", n);
    }
    for (size_t i = 0; i < 2 * n; i++)
        c->key[i] = NAN;
    c->n = n;
    c->slot = slot;
    return PM_OK;
}

/* pm_meshfree_eval() for a known meshfree kind; lam as for lme_cloud_eval() (LME only), L a
 * candidate list for the first support or NULL. */
static int point_eval(const mf_data *md, const char *name, const double x[2], double lam[2], const mf_list *L,
                      pm_stencil *s)
{
    s->n = 0;
    if (!isfinite(x[0]) || !isfinite(x[1]))
        return pm_error_set(PM_ESIM, "%s: non-finite point (%g, %g)", name, x[0], x[1]);
    return md->kind == MF_LME ? lme_cloud_eval(md, x, lam, L, s) : moment_eval(md, x, L, s);
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
    const double h_warm = md->cloud->h;
    long first_bad = LONG_MAX;
    int most = 0;
#pragma omp parallel for schedule(dynamic, 256) num_threads(a->n_threads) reduction(min : first_bad) \
    reduction(max : most)
    for (size_t i = 0; i < p->n; i++) {
        pm_stencil st;
        const double *x = p->x + 2 * i;
        /* LME: start Newton from this slot's last lambda if the point it belongs to was near x (the
         * periodic sort of the particles may have given the slot to another one far away) */
        double *lam = c->lam + 2 * i;
        if (!(fabs(x[0] - c->key[2 * i]) + fabs(x[1] - c->key[2 * i + 1]) < h_warm))
            lam[0] = lam[1] = 0;
        c->len[i] = -1;
        c->key[2 * i] = x[0];
        c->key[2 * i + 1] = x[1];
        /* the cell of a point: its area (per radian in axisymmetric runs the volume is r times it) */
        const double area = p->vol && p->vol[i] > 0 ? p->vol[i] / (axisym && x[0] > 0 ? x[0] : 1.0) : 0.0;
        int rc;
        if (md->smooth && area > 0)
            rc = smoothed_eval(a, x, 0.5 * sqrt(area), &st);
        else {
            mf_list buf;
            rc = point_eval(md, a->ops->name, x, lam, lists_get(md, &c->lists, i, x, &buf), &st);
        }
        if (rc != PM_OK) {
            lam[0] = lam[1] = 0;
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
        pm_check(cache_alloc(&md->cache, md, p->n, md->cache.slot ? md->cache.slot : 24));
    long bad;
    int longest;
    pm_check(cache_fill(a, p, &bad, &longest));
    if (bad == LONG_MAX && (size_t)longest > md->cache.slot) {
        pm_check(cache_alloc(&md->cache, md, p->n, (size_t)longest + 4));
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
    if (md) {
        cache_free(&md->cache);
        lists_free(&md->node_lists);
        free(md->node_lam);
    }
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
    double lam[2] = {0, 0};
    return point_eval(a->data, a->ops->name, x, lam, NULL, s);
}

int pm_meshfree_eval_node(const pm_approx *a, size_t node, pm_stencil *s)
{
    if (!pm_approx_is_meshfree(a))
        return pm_error_set(PM_EINPUT, "pm_meshfree_eval_node: '%s' is not a meshfree approximation",
                            a ? a->ops->name : "(null)");
    const mf_data *md = a->data;
    if (node >= md->cloud->n)
        return pm_error_set(PM_EINPUT, "pm_meshfree_eval_node: node %zu of a cloud of %zu", node, md->cloud->n);
    const double x[2] = {md->cloud->x[2 * node], md->cloud->x[2 * node + 1]};
    double *lam = md->node_lam + 2 * node;
    mf_list buf;
    const int rc = point_eval(md, a->ops->name, x, lam, lists_get(md, &md->node_lists, node, x, &buf), s);
    if (rc != PM_OK)
        lam[0] = lam[1] = 0;
    return rc;
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
    if (!rc) {
        md->node_lam = calloc(2 * cloud->n, sizeof *md->node_lam);
        rc = md->node_lam ? lists_alloc(&md->node_lists, md, cloud->n) : pm_error_set(PM_ENOMEM, "out of memory");
    }
    pm_approx *a = rc ? NULL : calloc(1, sizeof *a);
    if (!rc && !a)
        rc = pm_error_set(PM_ENOMEM, "out of memory");
    if (rc) {
        lists_free(&md->node_lists);
        free(md->node_lam);
        free(md);
        return rc;
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
