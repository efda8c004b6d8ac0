/* Node clouds and consistency checks shared by the meshfree tests (tests/unit/test_*meshfree*.c,
 * test_kronecker.c). */
#ifndef PMECH_TEST_MESHFREE_CHECK_H
#define PMECH_TEST_MESHFREE_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shape/cloud.h"
#include "pmech/error.h"
#include "shape/meshfree.h"
#include "shape/approx_internal.h"

static inline double mc_rnd(unsigned *seed) { return (double)rand_r(seed) / RAND_MAX; }

/* Nodes of an nx x ny grid of spacing h from origin o; interior nodes moved by up to jitter * h in
 * each direction (the boundary nodes stay on the rectangle, so its hull is the rectangle). Volumes
 * h^2, or random in [0.5, 1.5] h^2 when vary_vol. */
static inline pm_cloud *mc_grid_cloud(int nx, int ny, double h, const double o[2], double jitter, int vary_vol,
                                      unsigned seed)
{
    const size_t n = (size_t)nx * (size_t)ny;
    double *x = malloc(2 * n * sizeof *x), *v = malloc(n * sizeof *v);
    if (!x || !v)
        abort();
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const size_t k = (size_t)j * nx + i;
            const int edge = i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
            x[2 * k] = o[0] + h * (i + (edge ? 0 : jitter * (2 * mc_rnd(&seed) - 1)));
            x[2 * k + 1] = o[1] + h * (j + (edge ? 0 : jitter * (2 * mc_rnd(&seed) - 1)));
            v[k] = h * h * (vary_vol ? 0.5 + mc_rnd(&seed) : 1.0);
        }
    pm_cloud_opts co = {.h = h, .cell_size = NAN, .skin = NAN};
    pm_cloud *c;
    if (pm_cloud_create(n, x, v, &co, &c) != 0)
        abort();
    free(x);
    free(v);
    return c;
}

/* Uniformly random nodes in the rectangle [o, o + size] plus nodes at spacing h along its edges
 * (the way a GMM cloud keeps its boundary), volume = area / n. */
static inline pm_cloud *mc_random_cloud(size_t n_in, const double o[2], const double size[2], double h,
                                        unsigned seed)
{
    const int ex = (int)ceil(size[0] / h), ey = (int)ceil(size[1] / h);
    const size_t n = n_in + 2 * (size_t)(ex + ey);
    double *x = malloc(2 * n * sizeof *x);
    if (!x)
        abort();
    size_t k = 0;
    for (size_t i = 0; i < n_in; i++, k++) {
        x[2 * k] = o[0] + size[0] * mc_rnd(&seed);
        x[2 * k + 1] = o[1] + size[1] * mc_rnd(&seed);
    }
    for (int i = 0; i < ex; i++, k += 2) { /* bottom and top, corners once each */
        x[2 * k] = o[0] + size[0] * i / ex;
        x[2 * k + 1] = o[1];
        x[2 * k + 2] = o[0] + size[0] * (i + 1) / ex;
        x[2 * k + 3] = o[1] + size[1];
    }
    for (int j = 0; j < ey; j++, k += 2) { /* right and left */
        x[2 * k] = o[0] + size[0];
        x[2 * k + 1] = o[1] + size[1] * j / ey;
        x[2 * k + 2] = o[0];
        x[2 * k + 3] = o[1] + size[1] * (j + 1) / ey;
    }
    pm_cloud_opts co = {.h = h, .cell_size = NAN, .skin = NAN};
    pm_cloud *c;
    if (k != n || pm_cloud_create(n, x, NULL, &co, &c) != 0)
        abort();
    free(x);
    return c;
}

/* Worst errors of the consistency conditions over a set of points. */
typedef struct mc_errors {
    double pu, xrep, grad_sum, grad_x, fd, min_n;
    int max_nodes, min_nodes, fd_points, points;
} mc_errors;

static inline int mc_same_nodes(const pm_stencil *a, const pm_stencil *b)
{
    if (a->n != b->n)
        return 0;
    for (int k = 0; k < a->n; k++)
        if (a->node[k] != b->node[k])
            return 0;
    return 1;
}

/*
 * Partition of unity sum N_I = 1, linear reproduction sum N_I x_I = x, gradient consistency
 * sum dN_I = 0 and sum dN_I x_I^T = I (errors in units of 1/h), and differences of N (step eps,
 * extrapolated) against dN where the node set is the same at x, x +- eps and x +- eps/2 (the
 * adaptive radius may change it, and N with it, between two points), relative to the largest
 * |dN| of the stencil or 1/h, whichever is larger. Returns errors; pu = INFINITY when an
 * evaluation failed.
 */
static inline mc_errors mc_check(const pm_approx *a, size_t np, const double *pts, double eps)
{
    const pm_cloud *c = pm_meshfree_cloud(a);
    mc_errors e;
    memset(&e, 0, sizeof e);
    e.min_n = INFINITY;
    e.min_nodes = PM_STENCIL_MAX;
    for (size_t i = 0; i < np; i++) {
        const double *x = pts + 2 * i;
        pm_stencil s;
        if (pm_meshfree_eval(a, x, &s) != 0) {
            fprintf(stderr, "eval failed at (%.17g, %.17g): %s\n", x[0], x[1], pm_error_message());
            e.pu = INFINITY;
            return e;
        }
        e.points++;
        double sum = 0, xr[2] = {0, 0}, gs[2] = {0, 0}, gx[2][2] = {{0, 0}, {0, 0}};
        for (int k = 0; k < s.n; k++) {
            const double *xn = c->x + 2 * s.node[k];
            sum += s.N[k];
            for (int p = 0; p < 2; p++) {
                /* offsets from x keep the sums at the scale of h, not of the coordinates */
                xr[p] += s.N[k] * (xn[p] - x[p]);
                gs[p] += s.dN[k][p];
                for (int q = 0; q < 2; q++)
                    gx[p][q] += s.dN[k][p] * (xn[q] - x[q]);
            }
            e.min_n = fmin(e.min_n, s.N[k]);
        }
        e.max_nodes = s.n > e.max_nodes ? s.n : e.max_nodes;
        e.min_nodes = s.n < e.min_nodes ? s.n : e.min_nodes;
        e.pu = fmax(e.pu, fabs(sum - 1));
        e.xrep = fmax(e.xrep, fmax(fabs(xr[0]), fabs(xr[1])) / c->h);
        e.grad_sum = fmax(e.grad_sum, fmax(fabs(gs[0]), fabs(gs[1])) * c->h);
        e.grad_x = fmax(e.grad_x, fmax(fmax(fabs(gx[0][0] - 1), fabs(gx[1][1] - 1)), fmax(fabs(gx[0][1]), fabs(gx[1][0]))));
        if (eps <= 0)
            continue;
        int ok = 1;
        double fd = 0;
        for (int d = 0; d < 2 && ok; d++) {
            /* Richardson: (4 D(eps/2) - D(eps)) / 3 of central differences D cancels the eps^2 term,
             * so steep functions (close nodes, points next to the LME hull) are checked too */
            pm_stencil st[4];
            const double step[4] = {eps, -eps, 0.5 * eps, -0.5 * eps};
            for (int q = 0; q < 4 && ok; q++) {
                double xq[2] = {x[0], x[1]};
                xq[d] += step[q];
                ok = pm_meshfree_eval(a, xq, &st[q]) == 0 && mc_same_nodes(&s, &st[q]);
            }
            if (!ok)
                break;
            /* relative to the steepest function of the stencil (at least 1/h): round-off in N
             * is amplified by 1/eps and truncation by the steepness, both scale with it */
            double gmax = 1.0 / c->h;
            for (int k = 0; k < s.n; k++)
                gmax = fmax(gmax, fabs(s.dN[k][d]));
            for (int k = 0; k < s.n; k++) {
                const double d1 = (st[0].N[k] - st[1].N[k]) / (2 * eps), d2 = (st[2].N[k] - st[3].N[k]) / eps;
                fd = fmax(fd, fabs((4 * d2 - d1) / 3 - s.dN[k][d]) / gmax);
            }
        }
        if (ok) {
            e.fd_points++;
            e.fd = fmax(e.fd, fd);
        }
    }
    return e;
}

static inline void mc_print(const char *what, const mc_errors *e)
{
    printf("%-46s PU %.1e  x %.1e  sum dN %.1e  dN x %.1e  FD %.1e (%d/%d pts)  min N %+.2g  nodes %d-%d\n", what,
           e->pu, e->xrep, e->grad_sum, e->grad_x, e->fd, e->fd_points, e->points, e->min_n, e->min_nodes,
           e->max_nodes);
}

#endif
