/*
 * Local max-ent shape functions on a node cloud (seed 000 eq. 61, seed 003 eqs. 33-39):
 * N_I = exp(-beta |d_I|^2 + lambda . d_I) / Z, Newton on lambda shared with the grid kind
 * (pm_lme_newton() in lme.c). The support grows until its nodes enclose the point (convex-hull
 * safeguard: outside the hull lambda diverges), then takes the next-nearest nodes one at a time
 * while cond(J) exceeds its tolerance (seed 000 section 5.3).
 */
#include "pmech/error.h"

#include "meshfree_shape.h"

#include <math.h>
#include <string.h>

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
int pm_mf_lme_eval(const mf_data *md, const double x[2], double lam[2], const mf_list *L, pm_stencil *s)
{
    const pm_cloud *c = md->cloud;
    int32_t idx[PM_SHAPE_CAND_MAX];
    double d2[PM_SHAPE_CAND_MAX], d[PM_SHAPE_CAND_MAX][2];
    double R = md->r0;
    int nf = 0, m = 0, found = 0;
    /* grow the search until the nearest (at most 64) nodes enclose x */
    for (int step = 0; step < MF_MAX_GROWTH && !found; step++) {
        nf = step == 0 && L ? list_gather(c, L, x, R, idx, d, d2) : pm_cloud_gather(c, x, R, PM_SHAPE_CAND_MAX, idx, d, d2);
        if (nf > PM_SHAPE_CAND_MAX)
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
            const int got = pm_cloud_gather(c, x, R, PM_SHAPE_CAND_MAX - m, idx + m, d + m, d2 + m);
            if (got > PM_SHAPE_CAND_MAX - m) { /* an unordered subset: stop adding rather than add a wrong node */
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
