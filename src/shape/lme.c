/*
 * Local maximum-entropy (LME) approximants on the grid nodes (Arroyo & Ortiz 2006; seed 003
 * section 2.3, eqs. 33-39). For a point x the shape functions are
 *     N_I = exp(-beta |x - x_I|^2 + lambda* . (x - x_I)) / Z,   gamma = beta h^2,
 * where lambda* minimises log Z (Newton's method with a backtracking line search; converged when
 * |sum N_I (x - x_I)| <= 1e-14 h, i.e. linear fields are reproduced to round-off), and
 *     grad N_I = -N_I J^-1 (x - x_I),   J = sum N_I (x - x_I)(x - x_I)^T     (eq. 39 form).
 *
 * Support: the nodes within R of the point, R = h sqrt(-ln(1e-6) / gamma) (the radius where the
 * Gaussian prior falls to 1e-6), but at least 1.5 h so that the corners of the point's own cell
 * are always in (needed when gamma is large). The case key `support_radius` (metres) replaces R.
 * If more than PM_STENCIL_MAX (64) nodes are within R, the 64 nearest are used.
 *
 * gamma comes from the case key `lme_gamma` (default 1.8, Arroyo & Ortiz's usual choice; seed 003
 * uses 3 for the soil block, 0.8 for GMM). Large gamma tends to the linear finite-element
 * functions (bilinear Q4 on a square grid: max-entropy among the four cocircular corners), small
 * gamma widens the support. h is the cell size of a structured grid; on an unstructured grid the
 * mean cell size sqrt(mean area) (sqrt(4 A / sqrt 3) for triangles, the side of an equilateral
 * triangle of that area).
 *
 * Neighbour search: nodes are binned once into squares of side R / 2, with their coordinates
 * copied in bin order; a point visits the bins that overlap the square [x - R, x + R]^2 (5 x 5,
 * about 6 R^2 of nodes tested against 9 R^2 for 3 x 3 bins of side R).
 *
 * Cost: a solver evaluates the stencil of a point several times per step (every particle pass of
 * MUSL reads the shape functions at the start-of-step positions), and from one step to the next a
 * point moves a small fraction of h. So each particle slot keeps the last stencil with the position
 * it belongs to, and the lambda found there. A stencil is a function of the position alone, so an
 * evaluation at a bit-identical position returns the kept one; any other position is solved afresh,
 * Newton starting, when that position is within h of the kept one, from the first-order prediction
 *     lambda(x + dx) = lambda(x) + (2 beta I - J^-1) dx
 * (differentiate sum N_I d_I = 0; the same algebra gives eq. 39), with J from the kept values.
 * A point that moved 1e-4 h then converges in one Newton step, 1e-2 h in two, against three from
 * lambda = 0. A slot whose particle changed (the periodic sort permutes particles)
 * only misses: the position test decides, never the index. The slots are allocated by connect()
 * for the particle count it sees, sized for the most nodes any particle has then plus a margin; a
 * particle that later has more is solved every time (correct, only slower).
 */
#include "pmech/approx.h"
#include "pmech/error.h"
#include "shape/lme_state.h"

#include "shape_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LME_MAX_IT 100
#define LME_TAYLOR_MAX 1e-2 /* largest exponent change of a Newton step taken without exp() */

/* Per particle slot: the last stencil and where it was evaluated (see the header comment). */
typedef struct lme_cache {
    size_t cap;            /* slots */
    int width;             /* nodes a slot can hold */
    double *xs;            /* 2 per slot: position of the kept lambda (NaN: none) */
    double *lam;           /* 2 per slot: lambda at xs */
    int *n;                /* nodes of the kept stencil at xs; 0: lambda only */
    int32_t *node;         /* width per slot */
    double *N;             /* width per slot */
    double (*dN)[2];       /* width per slot */
} lme_cache;

typedef struct lme_data {
    double gamma, beta, h, R;
    double lo[2], bin;     /* bins: origin and side */
    int nb[2];             /* bins per direction */
    int32_t *start;        /* nb[0] * nb[1] + 1 */
    int32_t *nodes;        /* node indices sorted by bin */
    double *xb;            /* their coordinates, 2 per entry of nodes (read in bin order) */
    lme_cache cache;
} lme_data;

static void cache_free(lme_cache *c)
{
    free(c->xs);
    free(c->lam);
    free(c->n);
    free(c->node);
    free(c->N);
    free(c->dN);
    memset(c, 0, sizeof *c);
}

static void lme_destroy(pm_approx *a)
{
    lme_data *d = a->data;
    if (d) {
        free(d->start);
        free(d->nodes);
        free(d->xb);
        cache_free(&d->cache);
        free(d);
    }
    a->data = NULL;
}

static double grid_spacing(const pm_grid *g)
{
    if (g->structured)
        return sqrt(g->h[0] * g->h[1]);
    double area = 0;
    const int npc = g->nodes_per_cell;
    for (size_t c = 0; c < g->n_cells; c++) {
        const int32_t *v = g->conn + (size_t)npc * c;
        double s = 0;
        for (int k = 0; k < npc; k++) {
            const double *p = g->x + 2 * v[k], *q = g->x + 2 * v[(k + 1) % npc];
            s += p[0] * q[1] - q[0] * p[1];
        }
        area += 0.5 * fabs(s);
    }
    double mean = area / (double)g->n_cells;
    return g->element == PM_TRI3 ? sqrt(4.0 * mean / sqrt(3.0)) : sqrt(mean);
}

static int lme_init(pm_approx *a)
{
    const pm_grid *g = a->grid;
    lme_data *d = calloc(1, sizeof *d);
    if (!d)
        return pm_error_set(PM_ENOMEM, "out of memory");
    a->data = d;
    d->gamma = a->opts.lme_gamma > 0 ? a->opts.lme_gamma : PM_LME_DEFAULT_GAMMA;
    d->h = grid_spacing(g);
    d->beta = d->gamma / (d->h * d->h);
    d->R = a->opts.support_radius > 0 ? a->opts.support_radius
                                      : fmax(d->h * sqrt(-log(PM_LME_PRIOR_TOL) / d->gamma), 1.5 * d->h);
    d->bin = 0.5 * d->R;
    for (int k = 0; k < 2; k++) {
        d->lo[k] = g->lo[k];
        double nb = floor((g->hi[k] - g->lo[k]) / d->bin) + 1;
        if (nb > 1e6)
            return pm_error_set(PM_EINPUT, "lme: support radius %g is too small for the grid", d->R);
        d->nb[k] = (int)nb;
    }
    size_t nbins = (size_t)d->nb[0] * (size_t)d->nb[1];
    d->start = calloc(nbins + 1, sizeof(int32_t));
    d->nodes = malloc((g->n_nodes ? g->n_nodes : 1) * sizeof(int32_t));
    if (!d->start || !d->nodes)
        return pm_error_set(PM_ENOMEM, "out of memory for the LME node bins");
    for (size_t i = 0; i < g->n_nodes; i++) {
        int bx = (int)((g->x[2 * i] - d->lo[0]) / d->bin), by = (int)((g->x[2 * i + 1] - d->lo[1]) / d->bin);
        bx = bx < 0 ? 0 : (bx >= d->nb[0] ? d->nb[0] - 1 : bx);
        by = by < 0 ? 0 : (by >= d->nb[1] ? d->nb[1] - 1 : by);
        d->start[(size_t)by * d->nb[0] + bx + 1]++;
    }
    for (size_t b = 0; b < nbins; b++)
        d->start[b + 1] += d->start[b];
    int32_t *fill = malloc(nbins * sizeof(int32_t));
    if (!fill)
        return pm_error_set(PM_ENOMEM, "out of memory for the LME node bins");
    memcpy(fill, d->start, nbins * sizeof(int32_t));
    for (size_t i = 0; i < g->n_nodes; i++) {
        int bx = (int)((g->x[2 * i] - d->lo[0]) / d->bin), by = (int)((g->x[2 * i + 1] - d->lo[1]) / d->bin);
        bx = bx < 0 ? 0 : (bx >= d->nb[0] ? d->nb[0] - 1 : bx);
        by = by < 0 ? 0 : (by >= d->nb[1] ? d->nb[1] - 1 : by);
        d->nodes[fill[(size_t)by * d->nb[0] + bx]++] = (int32_t)i;
    }
    free(fill);
    d->xb = malloc((g->n_nodes ? g->n_nodes : 1) * 2 * sizeof(double));
    if (!d->xb)
        return pm_error_set(PM_ENOMEM, "out of memory for the LME node bins");
    for (size_t k = 0; k < g->n_nodes; k++) {
        d->xb[2 * k] = g->x[2 * d->nodes[k]];
        d->xb[2 * k + 1] = g->x[2 * d->nodes[k] + 1];
    }
    return PM_OK;
}

/* log Z and the normalised weights at lambda; q_max (may be NULL) receives the largest |d_I|^2. */
static double log_z(int n, const double (*d)[2], double beta, const double lam[2], double *p, double *q_max)
{
    double fmax = -INFINITY, qm = 0;
    for (int i = 0; i < n; i++) {
        const double q = d[i][0] * d[i][0] + d[i][1] * d[i][1];
        p[i] = -beta * q + lam[0] * d[i][0] + lam[1] * d[i][1];
        fmax = fmax > p[i] ? fmax : p[i];
        qm = q > qm ? q : qm;
    }
    if (q_max)
        *q_max = qm;
    double z = 0;
    for (int i = 0; i < n; i++) {
        p[i] = exp(p[i] - fmax); /* the largest term is 1, so z >= 1 */
        z += p[i];
    }
    for (int i = 0; i < n; i++)
        p[i] /= z;
    return fmax + log(z > 1 ? z : 1.0);
}

/* e^a for |a| <= LME_TAYLOR_MAX: the Taylor polynomial of degree 6, remainder below a^7 / 7! */
static inline double exp_small(double a)
{
    return 1 + a * (1 + a * (1.0 / 2 + a * (1.0 / 6 + a * (1.0 / 24 + a * (1.0 / 120 + a * (1.0 / 720))))));
}

/* Formed as sum p (d - r)(d - r)^T: the difference form sum p d d^T - r r^T loses all digits when
 * the weights concentrate on one node (large gamma). */
void pm_lme_resid_hess(int n, const double (*d)[2], const double *p, double r[2], double J[3])
{
    r[0] = r[1] = J[0] = J[1] = J[2] = 0;
    for (int i = 0; i < n; i++) {
        r[0] += p[i] * d[i][0];
        r[1] += p[i] * d[i][1];
    }
    for (int i = 0; i < n; i++) {
        const double a = d[i][0] - r[0], b = d[i][1] - r[1];
        J[0] += p[i] * a * a;
        J[1] += p[i] * a * b;
        J[2] += p[i] * b * b;
    }
}

int pm_lme_newton(int n, const double (*d)[2], double beta, double tol, double lambda[2], double *N, double r[2],
                  double J[3])
{
    double q_max;
    double lz = log_z(n, d, beta, lambda, N, &q_max), rprev = INFINITY;
    const double dmax = sqrt(q_max);
    const double cap = 4 * beta * dmax + 1 / dmax;
    /* log Z = lz + lz_slope + log(lz_prod): what the steps without exp() added, resolved when a
     * line search needs it */
    double lz_slope = 0, lz_prod = 1;
    int have_rj = 0; /* r and J already formed at N by the last step */
    for (int it = 0;; it++) {
        if (!have_rj)
            pm_lme_resid_hess(n, d, N, r, J);
        have_rj = 0;
        const double rnow = sqrt(r[0] * r[0] + r[1] * r[1]);
        /* converged; or within 100 tol and no longer falling (round-off floor: with large gamma the
         * exponents reach ~ gamma and carry absolute errors ~ 1e-16 gamma) */
        if (rnow <= tol || (rnow <= 100 * tol && rnow > 0.5 * rprev))
            return it;
        rprev = rnow;
        if (it == LME_MAX_IT)
            return -1;
        double det = J[0] * J[2] - J[1] * J[1];
        double step[2];
        if (det > 1e-300 && isfinite(det)) {
            step[0] = -(J[2] * r[0] - J[1] * r[1]) / det;
            step[1] = -(J[0] * r[1] - J[1] * r[0]) / det;
        } else { /* degenerate Hessian: steepest descent */
            step[0] = -r[0] * beta;
            step[1] = -r[1] * beta;
        }
        const double sn = sqrt(step[0] * step[0] + step[1] * step[1]);
        /*
         * A step that changes no exponent by more than LME_TAYLOR_MAX (the last one or two of a
         * solve, and all of one that starts from a nearby point's lambda) updates the weights
         * without exponentials: N_I(lambda + s) = N_I e^(a_I) / sum_J N_J e^(a_J) with
         * a_I = s . (d_I - r), |a_I| <= |s| (|d_I| + |r|), and e^a by its Taylor polynomial of
         * degree 6, whose remainder a^7 / 7! stays below 1e-17 there. The step must pass the same
         * sufficient-decrease test as below, log Z moving by s . r + log sum_J N_J e^(a_J). The same
         * pass sums the new residual and Hessian about the old residual c = r,
         * r' = c + m, J' = sum N'_I (d_I - c)(d_I - c)^T - m m^T with m = sum N'_I (d_I - c): m is
         * as small as r, so the shift loses none of the digits of J that the difference form about
         * 0 would (pm_lme_resid_hess()).
         */
        if (det > 1e-300 && isfinite(det) && sn * (dmax + rnow) <= LME_TAYLOR_MAX) {
            const double slope = r[0] * step[0] + r[1] * step[1], c0 = r[0], c1 = r[1];
            double zs = 0, s0 = 0, s1 = 0, j0 = 0, j1 = 0, j2 = 0;
            for (int i = 0; i < n; i++) {
                const double u = d[i][0] - c0, v = d[i][1] - c1, a = step[0] * u + step[1] * v;
                const double p = N[i] * exp_small(a);
                N[i] = p;
                zs += p;
                s0 += p * u;
                s1 += p * v;
                j0 += p * u * u;
                j1 += p * u * v;
                j2 += p * v * v;
            }
            if (zs > 0 && (-slope < 1e-10 * (1 + fabs(lz)) || slope + log(zs) <= 1e-4 * slope)) {
                const double iz = 1 / zs, m0 = s0 * iz, m1 = s1 * iz;
                for (int i = 0; i < n; i++)
                    N[i] *= iz;
                r[0] = c0 + m0;
                r[1] = c1 + m1;
                J[0] = j0 * iz - m0 * m0;
                J[1] = j1 * iz - m0 * m1;
                J[2] = j2 * iz - m1 * m1;
                have_rj = 1;
                lz_slope += slope;
                lz_prod *= zs;
                lambda[0] += step[0];
                lambda[1] += step[1];
                continue;
            }
            lz = log_z(n, d, beta, lambda, N, NULL); /* not accepted: back to the weights at lambda */
            lz_slope = 0;
            lz_prod = 1;
        }
        lz += lz_slope + log(lz_prod);
        lz_slope = 0;
        lz_prod = 1;
        /* a step longer than a few beta * (node distance) only happens where J is tiny (the weight
         * sits on one node, large gamma); cap it so that the line search starts at a useful scale */
        if (sn > cap) {
            step[0] *= cap / sn;
            step[1] *= cap / sn;
        }
        /* backtracking on log Z (convex); the gradient of log Z is r */
        const double slope = r[0] * step[0] + r[1] * step[1];
        double t = 1.0, lam[2];
        int accepted = 0;
        for (int ls = 0; ls < 60; ls++) {
            lam[0] = lambda[0] + t * step[0];
            lam[1] = lambda[1] + t * step[1];
            double lz_new = log_z(n, d, beta, lam, N, NULL);
            /* near the solution the predicted decrease of log Z (the Newton decrement) drowns in its
             * round-off: take the full Newton step there */
            if (lz_new <= lz + 1e-4 * t * slope || -slope < 1e-10 * (1 + fabs(lz))) {
                lz = lz_new;
                accepted = 1;
                break;
            }
            t *= 0.5;
        }
        if (!accepted) {
            log_z(n, d, beta, lambda, N, NULL);
            return -1;
        }
        lambda[0] = lam[0];
        lambda[1] = lam[1];
    }
}

int pm_lme_solve(int n, const double (*d)[2], double beta, double tol, double lambda[2], double *N,
                 double (*dN)[2])
{
    double r[2], J[3];
    const int it = pm_lme_newton(n, d, beta, tol, lambda, N, r, J);
    if (it < 0)
        return -1;
    /* gradients, eq. 39: grad N_I = -N_I J^-1 d_I */
    double det = J[0] * J[2] - J[1] * J[1];
    if (!(det > 0))
        return -1;
    const double i0 = J[2] / det, i1 = -J[1] / det, i2 = J[0] / det;
    for (int i = 0; i < n; i++) {
        dN[i][0] = -N[i] * (i0 * d[i][0] + i1 * d[i][1]);
        dN[i][1] = -N[i] * (i1 * d[i][0] + i2 * d[i][1]);
    }
    return it;
}

/*
 * The nodes within R of x (the PM_STENCIL_MAX nearest when more), their indices into cand and
 * squared distances into dist2; returns their count.
 */
static int neighbours(const lme_data *ld, const double x[2], int32_t cand[PM_SHAPE_CAND_MAX],
                      double dist2[PM_SHAPE_CAND_MAX])
{
    int nc = 0;
    const double R2 = ld->R * ld->R;
    int b0[2], b1[2];
    for (int k = 0; k < 2; k++) {
        /* floor of the clamped value: a huge or NaN coordinate must not overflow the int */
        const double u0 = (x[k] - ld->R - ld->lo[k]) / ld->bin, u1 = (x[k] + ld->R - ld->lo[k]) / ld->bin;
        const double top = ld->nb[k] - 1;
        b0[k] = (int)floor(u0 > 0 ? (u0 < top ? u0 : top) : 0);
        b1[k] = (int)floor(u1 > 0 ? (u1 < top ? u1 : top) : 0);
    }
    for (int jy = b0[1]; jy <= b1[1]; jy++)
        for (int jx = b0[0]; jx <= b1[0]; jx++) {
            const size_t b = (size_t)jy * ld->nb[0] + jx;
            for (int32_t k = ld->start[b]; k < ld->start[b + 1]; k++) {
                const double dx = x[0] - ld->xb[2 * k], dy = x[1] - ld->xb[2 * k + 1], r2 = dx * dx + dy * dy;
                if (r2 > R2 || nc == PM_SHAPE_CAND_MAX)
                    continue;
                cand[nc] = ld->nodes[k];
                dist2[nc++] = r2;
            }
        }
    if (nc > PM_STENCIL_MAX) { /* keep the nearest PM_STENCIL_MAX (partial selection) */
        for (int i = 0; i < PM_STENCIL_MAX; i++) {
            int m = i;
            for (int j = i + 1; j < nc; j++)
                if (dist2[j] < dist2[m] || (dist2[j] == dist2[m] && cand[j] < cand[m]))
                    m = j;
            int32_t tc = cand[i]; cand[i] = cand[m]; cand[m] = tc;
            double td = dist2[i]; dist2[i] = dist2[m]; dist2[m] = td;
        }
        nc = PM_STENCIL_MAX;
    }
    return nc;
}

/*
 * Locate the cells; on the first call also size the per-particle slots for every particle the arrays
 * can hold (set-up time: the solvers connect once before the first step, and sources append
 * particles only up to the capacity, so no step allocates).
 */
static int lme_connect(pm_approx *a, pm_particles *p)
{
    int rc = pm_shape_connect_cells(a, p);
    if (rc)
        return rc;
    lme_data *ld = a->data;
    lme_cache *c = &ld->cache;
    const size_t want = p->cap > p->n ? p->cap : p->n;
    if (c->cap >= want)
        return PM_OK;
    int widest = 0;
    for (size_t i = 0; i < p->n; i++) {
        int32_t cand[PM_SHAPE_CAND_MAX];
        double dist2[PM_SHAPE_CAND_MAX];
        int nc = neighbours(ld, p->x + 2 * i, cand, dist2);
        widest = nc > widest ? nc : widest;
    }
    if (p->n == 0) { /* all particles are still to be released: size for a point inside the grid */
        const pm_grid *g = a->grid;
        const double mid[2] = {0.5 * (g->lo[0] + g->hi[0]), 0.5 * (g->lo[1] + g->hi[1])};
        int32_t cand[PM_SHAPE_CAND_MAX];
        double dist2[PM_SHAPE_CAND_MAX];
        widest = neighbours(ld, mid, cand, dist2);
    }
    cache_free(c);
    /* particles move: leave room for a few more nodes than any has now */
    int width = widest + widest / 4 + 4;
    width = width > PM_STENCIL_MAX ? PM_STENCIL_MAX : width;
    const size_t n = want ? want : 1, w = (size_t)width;
    c->xs = malloc(2 * n * sizeof(double));
    c->lam = malloc(2 * n * sizeof(double));
    c->n = calloc(n, sizeof(int));
    c->node = malloc(n * w * sizeof(int32_t));
    c->N = malloc(n * w * sizeof(double));
    c->dN = malloc(n * w * sizeof *c->dN);
    if (!c->xs || !c->lam || !c->n || !c->node || !c->N || !c->dN) {
        cache_free(c);
        return pm_error_set(PM_ENOMEM, "lme: out of memory for the stencils of %zu particles", want);
    }
    for (size_t i = 0; i < 2 * n; i++)
        c->xs[i] = NAN;
    c->cap = want;
    c->width = width;
    return PM_OK;
}

/*
 * Starting lambda at x for slot ip from the lambda kept at xs: first-order prediction with J
 * formed from the kept values when the slot has them, the kept lambda itself otherwise.
 */
static void predict_lambda(const pm_grid *g, double beta, const lme_cache *c, size_t ip, const double x[2],
                           double lam[2])
{
    const double *xs = c->xs + 2 * ip;
    lam[0] = c->lam[2 * ip];
    lam[1] = c->lam[2 * ip + 1];
    const int n = c->n[ip];
    if (n == 0)
        return;
    const size_t o = ip * (size_t)c->width;
    double J[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        const double *xn = g->x + 2 * c->node[o + i], Ni = c->N[o + i];
        const double a = xs[0] - xn[0], b = xs[1] - xn[1];
        J[0] += Ni * a * a;
        J[1] += Ni * a * b;
        J[2] += Ni * b * b;
    }
    const double det = J[0] * J[2] - J[1] * J[1];
    if (!(det > 0))
        return;
    const double i0 = J[2] / det, i1 = -J[1] / det, i2 = J[0] / det;
    const double dx = x[0] - xs[0], dy = x[1] - xs[1];
    lam[0] += (2 * beta - i0) * dx - i1 * dy;
    lam[1] += -i1 * dx + (2 * beta - i2) * dy;
}

static int lme_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s)
{
    const pm_grid *g = a->grid;
    lme_data *ld = a->data;
    const double *x = p->x + 2 * ip;
    if (p->cell[ip] < 0)
        return pm_error_set(PM_ESIM, "particle %zu is outside the grid", ip);
    lme_cache *c = ip < ld->cache.cap ? &ld->cache : NULL;
    double *xs = c ? c->xs + 2 * ip : NULL;
    if (c && c->n[ip] > 0 && xs[0] == x[0] && xs[1] == x[1]) {
        const size_t o = ip * (size_t)c->width;
        const int n = c->n[ip];
        s->n = n;
        memcpy(s->node, c->node + o, (size_t)n * sizeof(int32_t));
        memcpy(s->N, c->N + o, (size_t)n * sizeof(double));
        memcpy(s->dN, c->dN + o, (size_t)n * sizeof *s->dN);
        return PM_OK;
    }
    int32_t cand[PM_SHAPE_CAND_MAX];
    double dist2[PM_SHAPE_CAND_MAX];
    const int nc = neighbours(ld, x, cand, dist2);
    if (nc < 3)
        return pm_error_set(PM_ESIM, "lme: particle %zu at (%g, %g) has only %d nodes within the support radius %g",
                            ip, x[0], x[1], nc, ld->R);
    double d[PM_STENCIL_MAX][2];
    for (int i = 0; i < nc; i++) {
        d[i][0] = x[0] - g->x[2 * cand[i]];
        d[i][1] = x[1] - g->x[2 * cand[i] + 1];
    }
    double lam[2] = {0, 0};
    const int warm = c && hypot(x[0] - xs[0], x[1] - xs[1]) < ld->h;
    if (warm)
        predict_lambda(g, ld->beta, c, ip, x, lam);
    int it = pm_lme_solve(nc, (const double (*)[2])d, ld->beta, PM_LME_TOL * ld->h, lam, s->N, s->dN);
    if (it < 0 && warm) { /* a start the line search cannot recover from: the cold start as before */
        lam[0] = lam[1] = 0;
        it = pm_lme_solve(nc, (const double (*)[2])d, ld->beta, PM_LME_TOL * ld->h, lam, s->N, s->dN);
    }
    if (it < 0)
        return pm_error_set(PM_ESIM,
                            "lme: the Newton solve for lambda did not converge for particle %zu at (%g, %g) "
                            "(on the edge of the grid's node cloud?)",
                            ip, x[0], x[1]);
    s->n = nc;
    memcpy(s->node, cand, (size_t)nc * sizeof(int32_t));
    if (c) {
        /* this slot belongs to particle ip alone during a particle loop, so threads never share it */
        xs[0] = x[0];
        xs[1] = x[1];
        c->lam[2 * ip] = lam[0];
        c->lam[2 * ip + 1] = lam[1];
        c->n[ip] = nc <= c->width ? nc : 0;
        if (c->n[ip]) {
            const size_t o = ip * (size_t)c->width;
            memcpy(c->node + o, cand, (size_t)nc * sizeof(int32_t));
            memcpy(c->N + o, s->N, (size_t)nc * sizeof(double));
            memcpy(c->dN + o, s->dN, (size_t)nc * sizeof *s->dN);
        }
    }
    return PM_OK;
}

const pm_approx_ops pm_approx_lme_ops = {
    .name = "lme",
    .methods = PM_APPROX_MPM,
    .interpolating = 1,
    .linear_quad_fast = 0,
    .connect = lme_connect,
    .eval = lme_eval,
    .destroy = lme_destroy,
    .init = lme_init,
};

int pm_lme_state_get(const pm_approx *a, pm_lme_state *st)
{
    if (!a || a->ops != &pm_approx_lme_ops || !a->data)
        return pm_error_set(PM_EINPUT, "pm_lme_state_get: '%s' is not the grid kind lme",
                            a ? a->ops->name : "(null)");
    lme_cache *c = &((lme_data *)a->data)->cache;
    *st = (pm_lme_state){.cap = c->cap, .n_nodes = a->grid->n_nodes, .width = c->width, .xs = c->xs,
                         .lam = c->lam, .n = c->n, .node = c->node, .N = c->N, .dN = c->dN};
    return PM_OK;
}
