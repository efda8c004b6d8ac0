/*
 * Kronecker-delta transformation (seed 002 eqs. 15-21) restricted to the essential-boundary nodes.
 *
 * Seed 002 transforms every unknown, d = A^-1 u with A_KI = Psi_I(x_K) over all nodes; A^-1 is dense
 * and the transformed functions lose their compact support. Only the nodes where a value is
 * prescribed need it: with B the boundary nodes, the rows Lambda_JI = Psi_I(x_J), J in B, map the
 * coefficients to the nodal values there, and the unknowns become (u_B, d_rest). Imposing u_B = g
 * is then solving A_BB d_B = g - A_B,rest d_rest, where A_BB is the |B| x |B| block of Lambda on the
 * boundary columns: sparse (a boundary node sees only the boundary nodes in its support), so it is
 * solved iteratively and the work and memory stay O(|B| x stencil). Equivalently the transformed
 * shape functions are Psi' = Psi Lambda^-1 with Lambda = [A_BB A_B,rest; 0 I], which satisfy
 * Psi'_K(x_J) = delta_KJ for J in B (eq. 18) and, since Lambda u = u for linear u, still reproduce
 * linear fields.
 */
#include "pmech/error.h"
#include "shape/meshfree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KD_MAX_PASSES 4
#define KD_REL_TOL 1e-14  /* BiCGStab stop, relative to |g| + |Lambda c| */
#define KD_ACCEPT_TOL 1e-12 /* the final true residual must be below this, relative */

struct pm_kd {
    size_t nb, n_nodes;
    int32_t *node;   /* nb boundary nodes */
    int32_t *bidx;   /* n_nodes: boundary index of a node, -1 elsewhere */
    int32_t *rowlen; /* nb */
    int32_t *col;    /* nb * PM_STENCIL_MAX */
    double *val;     /* nb * PM_STENCIL_MAX */
    double *diag;    /* nb: Psi_J(x_J), the Jacobi preconditioner */
    double *work;    /* 10 nb: BiCGStab's 8 vectors, the correction, the right-hand side */
    double *offset;  /* 2 nb or NULL: rows evaluated at x_J + offset_J instead of x_J */
};

void pm_kd_destroy(pm_kd *kd)
{
    if (!kd)
        return;
    free(kd->node);
    free(kd->bidx);
    free(kd->rowlen);
    free(kd->col);
    free(kd->val);
    free(kd->diag);
    free(kd->work);
    free(kd->offset);
    free(kd);
}

int pm_kd_update(pm_kd *kd, const pm_approx *a)
{
    const pm_cloud *c = pm_meshfree_cloud(a);
    if (!c || c->n != kd->n_nodes)
        return pm_error_set(PM_EINPUT, "Kronecker transformation: not the cloud it was created on");
    for (size_t j = 0; j < kd->nb; j++) {
        pm_stencil s;
        const int32_t J = kd->node[j];
        int rc;
        if (kd->offset) {
            const double x[2] = {c->x[2 * (size_t)J] + kd->offset[2 * j],
                                 c->x[2 * (size_t)J + 1] + kd->offset[2 * j + 1]};
            rc = pm_meshfree_eval(a, x, &s);
        } else /* rows are re-evaluated every step at the same nodes: the node's own search state pays */
            rc = pm_meshfree_eval_node(a, (size_t)J, &s);
        if (rc)
            return pm_error_prefix(rc, "Kronecker transformation at boundary node %d: ", (int)J);
        kd->rowlen[j] = s.n;
        kd->diag[j] = 0;
        for (int k = 0; k < s.n; k++) {
            kd->col[j * PM_STENCIL_MAX + k] = s.node[k];
            kd->val[j * PM_STENCIL_MAX + k] = s.N[k];
            if (s.node[k] == J)
                kd->diag[j] = s.N[k];
        }
    }
    return PM_OK;
}

int pm_kd_create(const pm_approx *a, size_t nb, const int32_t *nodes, pm_kd **out)
{
    *out = NULL;
    const pm_cloud *c = pm_meshfree_cloud(a);
    if (!c)
        return pm_error_set(PM_EINPUT, "Kronecker transformation needs a meshfree approximation");
    pm_kd *kd = calloc(1, sizeof *kd);
    if (!kd)
        return pm_error_set(PM_ENOMEM, "out of memory");
    kd->nb = nb;
    kd->n_nodes = c->n;
    const size_t nb1 = nb ? nb : 1;
    kd->node = malloc(nb1 * sizeof *kd->node);
    kd->bidx = malloc(c->n * sizeof *kd->bidx);
    kd->rowlen = malloc(nb1 * sizeof *kd->rowlen);
    kd->col = malloc(nb1 * PM_STENCIL_MAX * sizeof *kd->col);
    kd->val = malloc(nb1 * PM_STENCIL_MAX * sizeof *kd->val);
    kd->diag = malloc(nb1 * sizeof *kd->diag);
    kd->work = malloc(10 * nb1 * sizeof *kd->work);
    if (!kd->node || !kd->bidx || !kd->rowlen || !kd->col || !kd->val || !kd->diag || !kd->work) {
        pm_kd_destroy(kd);
        return pm_error_set(PM_ENOMEM, "out of memory for the Kronecker transformation of %zu nodes", nb);
    }
    for (size_t i = 0; i < c->n; i++)
        kd->bidx[i] = -1;
    for (size_t j = 0; j < nb; j++) {
        const int32_t J = nodes[j];
        if (J < 0 || (size_t)J >= c->n || kd->bidx[J] >= 0) {
            pm_kd_destroy(kd);
            return pm_error_set(PM_EINPUT, "Kronecker transformation: boundary node %d is %s", (int)J,
                                J < 0 || (size_t)J >= c->n ? "not in the cloud" : "listed twice");
        }
        kd->bidx[J] = (int32_t)j;
        kd->node[j] = J;
    }
    int rc = pm_kd_update(kd, a);
    if (rc) {
        pm_kd_destroy(kd);
        return rc;
    }
    *out = kd;
    return PM_OK;
}

size_t pm_kd_size(const pm_kd *kd) { return kd->nb; }

int pm_kd_row(const pm_kd *kd, size_t j, int32_t *node, const int32_t **cols, const double **vals)
{
    *node = kd->node[j];
    *cols = kd->col + j * PM_STENCIL_MAX;
    *vals = kd->val + j * PM_STENCIL_MAX;
    return kd->rowlen[j];
}

void pm_kd_values(const pm_kd *kd, const double *coef, int stride, int comp, double *val)
{
    for (size_t j = 0; j < kd->nb; j++) {
        const int32_t *cj = kd->col + j * PM_STENCIL_MAX;
        const double *vj = kd->val + j * PM_STENCIL_MAX;
        double s = 0;
        for (int k = 0; k < kd->rowlen[j]; k++)
            s += vj[k] * coef[(size_t)stride * cj[k] + comp];
        val[j] = s;
    }
}

/* y = A_BB x: the entries of Lambda whose column is a boundary node */
static void abb_mult(const pm_kd *kd, const double *x, double *y)
{
    for (size_t j = 0; j < kd->nb; j++) {
        const int32_t *cj = kd->col + j * PM_STENCIL_MAX;
        const double *vj = kd->val + j * PM_STENCIL_MAX;
        double s = 0;
        for (int k = 0; k < kd->rowlen[j]; k++) {
            const int32_t b = kd->bidx[cj[k]];
            if (b >= 0)
                s += vj[k] * x[b];
        }
        y[j] = s;
    }
}

static double dot(size_t n, const double *a, const double *b)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

static void precond(const pm_kd *kd, const double *x, double *y)
{
    for (size_t j = 0; j < kd->nb; j++)
        y[j] = kd->diag[j] != 0 ? x[j] / kd->diag[j] : x[j];
}

/* BiCGStab with Jacobi preconditioning (the updates use the preconditioned directions, so x is
 * the solution itself) for A_BB x = b from x = 0. Returns the final recursive residual norm. */
static double bicgstab(pm_kd *kd, const double *b, double *x, double tol)
{
    const size_t n = kd->nb;
    double *r = kd->work, *rh = r + n, *p = rh + n, *v = p + n, *ph = v + n, *s = ph + n, *sh = s + n, *t = sh + n;
    memcpy(r, b, n * sizeof *r);
    memcpy(rh, b, n * sizeof *r);
    memset(x, 0, n * sizeof *x);
    memset(p, 0, n * sizeof *p);
    memset(v, 0, n * sizeof *v);
    double rho = 1, alpha = 1, omega = 1, rn = sqrt(dot(n, r, r));
    for (size_t it = 0; it < 4 * n + 50 && rn > tol; it++) {
        const double rho1 = dot(n, rh, r);
        if (rho1 == 0 || omega == 0)
            break; /* breakdown: the caller restarts from the true residual */
        const double beta = (rho1 / rho) * (alpha / omega);
        for (size_t i = 0; i < n; i++)
            p[i] = r[i] + beta * (p[i] - omega * v[i]);
        precond(kd, p, ph);
        abb_mult(kd, ph, v);
        const double rv = dot(n, rh, v);
        if (rv == 0)
            break;
        alpha = rho1 / rv;
        for (size_t i = 0; i < n; i++)
            s[i] = r[i] - alpha * v[i];
        if (sqrt(dot(n, s, s)) <= tol) {
            for (size_t i = 0; i < n; i++)
                x[i] += alpha * ph[i];
            return sqrt(dot(n, s, s));
        }
        precond(kd, s, sh);
        abb_mult(kd, sh, t);
        const double tt = dot(n, t, t);
        omega = tt > 0 ? dot(n, t, s) / tt : 0;
        for (size_t i = 0; i < n; i++) {
            x[i] += alpha * ph[i] + omega * sh[i];
            r[i] = s[i] - omega * t[i];
        }
        rho = rho1;
        rn = sqrt(dot(n, r, r));
    }
    return rn;
}

int pm_kd_impose(pm_kd *kd, const double *g, int stride, int comp, double *coef)
{
    const size_t n = kd->nb;
    if (n == 0)
        return PM_OK;
    /* BiCGStab uses work[0, 8n); the correction and the right-hand side follow */
    double *x = kd->work + 8 * n, *b = kd->work + 9 * n;
    double scale = 0, res = INFINITY;
    /* each pass solves for the true residual g - Lambda c, so a pass that stopped early (or broke
     * down) is corrected by the next */
    for (int pass = 0; pass <= KD_MAX_PASSES; pass++) {
        pm_kd_values(kd, coef, stride, comp, b);
        res = 0;
        for (size_t j = 0; j < n; j++) {
            if (pass == 0)
                scale = fmax(scale, fmax(fabs(g[j]), fabs(b[j])));
            b[j] = g[j] - b[j];
            res = fmax(res, fabs(b[j]));
        }
        if (!isfinite(res))
            break;
        if (res <= KD_ACCEPT_TOL * scale || res == 0)
            return PM_OK;
        if (pass == KD_MAX_PASSES)
            break;
        bicgstab(kd, b, x, KD_REL_TOL * sqrt(dot(n, b, b)) + KD_REL_TOL * scale);
        for (size_t j = 0; j < n; j++)
            coef[(size_t)stride * kd->node[j] + comp] += x[j];
    }
    return pm_error_set(PM_ESIM,
                        "Kronecker transformation: the boundary values were not reached (largest error %g, "
                        "values up to %g)",
                        res, scale);
}

int pm_kd_set_offsets(pm_kd *kd, const pm_approx *a, const double *offsets)
{
    if (!kd->offset && !(kd->offset = malloc(2 * (kd->nb ? kd->nb : 1) * sizeof(double))))
        return pm_error_set(PM_ENOMEM, "out of memory");
    memcpy(kd->offset, offsets, 2 * kd->nb * sizeof(double));
    return pm_kd_update(kd, a);
}
