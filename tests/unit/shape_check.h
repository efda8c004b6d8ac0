/* Checks shared by the shape-function tests (included by tests/unit/test_shape_*.c). */
#ifndef PMECH_TEST_SHAPE_CHECK_H
#define PMECH_TEST_SHAPE_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shape/approx_internal.h"
#include "pmech/grid.h"
#include "pmech/particles.h"

static inline double sc_rnd(unsigned *seed) { return (double)rand_r(seed) / RAND_MAX; }

/* Worst errors over a set of points. */
typedef struct sc_errors {
    double pu, grad_sum, xrep, urep, grep, fd, min_n;
    int max_nodes;
} sc_errors;

/*
 * Partition of unity, reproduction of x and of an arbitrary linear field with its gradient, and
 * a central finite-difference check of every dN (step eps) for the particles of p (cells located).
 */
static inline sc_errors sc_check(const pm_approx *a, pm_particles *p, double eps)
{
    const pm_grid *g = a->grid;
    sc_errors e;
    memset(&e, 0, sizeof e);
    e.min_n = INFINITY;
    const double c0 = 0.3, c1 = -1.7, c2 = 2.9;
    for (size_t i = 0; i < p->n; i++) {
        pm_stencil st;
        if (a->ops->eval(a, p, i, &st) != 0) {
            fprintf(stderr, "eval failed at particle %zu (%g, %g)\n", i, p->x[2 * i], p->x[2 * i + 1]);
            e.pu = INFINITY;
            return e;
        }
        double sum = 0, u = 0, gx = 0, gy = 0, sx = 0, sy = 0, xr = 0, yr = 0;
        for (int k = 0; k < st.n; k++) {
            const double *xn = g->x + 2 * st.node[k];
            double un = c0 + c1 * xn[0] + c2 * xn[1];
            sum += st.N[k];
            u += st.N[k] * un;
            xr += st.N[k] * xn[0];
            yr += st.N[k] * xn[1];
            gx += st.dN[k][0] * un;
            gy += st.dN[k][1] * un;
            sx += st.dN[k][0];
            sy += st.dN[k][1];
            e.min_n = fmin(e.min_n, st.N[k]);
        }
        const double *x = p->x + 2 * i;
        e.max_nodes = st.n > e.max_nodes ? st.n : e.max_nodes;
        e.pu = fmax(e.pu, fabs(sum - 1));
        e.grad_sum = fmax(e.grad_sum, fmax(fabs(sx), fabs(sy)));
        e.xrep = fmax(e.xrep, fmax(fabs(xr - x[0]), fabs(yr - x[1])));
        e.urep = fmax(e.urep, fabs(u - (c0 + c1 * x[0] + c2 * x[1])));
        e.grep = fmax(e.grep, fmax(fabs(gx - c1), fabs(gy - c2)));
        if (eps > 0) {
            /* finite differences of N_I along x and y, looked up by node */
            for (int d = 0; d < 2; d++) {
                pm_stencil sp, sm;
                const double x0 = p->x[2 * i + d];
                p->x[2 * i + d] = x0 + eps;
                int r1 = a->ops->eval(a, p, i, &sp);
                p->x[2 * i + d] = x0 - eps;
                int r2 = a->ops->eval(a, p, i, &sm);
                p->x[2 * i + d] = x0;
                if (r1 || r2)
                    continue;
                for (int k = 0; k < st.n; k++) {
                    double np = 0, nm = 0;
                    for (int q = 0; q < sp.n; q++)
                        if (sp.node[q] == st.node[k])
                            np = sp.N[q];
                    for (int q = 0; q < sm.n; q++)
                        if (sm.node[q] == st.node[k])
                            nm = sm.N[q];
                    e.fd = fmax(e.fd, fabs((np - nm) / (2 * eps) - st.dN[k][d]));
                }
            }
        }
    }
    return e;
}

static inline void sc_print(const char *what, const sc_errors *e)
{
    printf("%-44s PU %.1e  sum dN %.1e  x %.1e  u %.1e  grad u %.1e  FD %.1e  min N %.3g  nodes <= %d\n", what, e->pu,
           e->grad_sum, e->xrep, e->urep, e->grep, e->fd, e->min_n, e->max_nodes);
}

/* Random particles in [lo, hi] (cells located by connect). */
static inline void sc_random_particles(pm_particles *p, size_t n, const double lo[2], const double hi[2],
                                       double hs, unsigned seed)
{
    if (pm_particles_alloc(p, n, 0) != 0)
        abort();
    for (size_t i = 0; i < n; i++) {
        p->x[2 * i] = lo[0] + (hi[0] - lo[0]) * sc_rnd(&seed);
        p->x[2 * i + 1] = lo[1] + (hi[1] - lo[1]) * sc_rnd(&seed);
        p->hsize[2 * i] = p->hsize[2 * i + 1] = hs;
        p->cell[i] = -1;
    }
}


/* A jittered n x n grid on [0, 1]^2 as triangles (diagonals alternating) or quads: interior nodes move
 * by up to amp/2 of the spacing in each direction; cells whose centre lies within @p hole of
 * (0.5, 0.5) are left out. Returns pm_grid_unstructured's status. */
static inline int sc_jittered_grid(pm_grid *g, int n, pm_element el, double amp, double hole, unsigned seed)
{
    const size_t nn = (size_t)(n + 1) * (n + 1);
    double *x = malloc(2 * nn * sizeof(double));
    int32_t *conn = malloc((size_t)n * n * 6 * sizeof(int32_t));
    if (!x || !conn) {
        free(x);
        free(conn);
        return -1;
    }
    const double h = 1.0 / n;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            size_t k = (size_t)j * (n + 1) + i;
            x[2 * k] = i * h + ((i > 0 && i < n) ? (sc_rnd(&seed) - 0.5) * amp * h : 0);
            x[2 * k + 1] = j * h + ((j > 0 && j < n) ? (sc_rnd(&seed) - 0.5) * amp * h : 0);
        }
    size_t nc = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double cx = (i + 0.5) * h - 0.5, cy = (j + 0.5) * h - 0.5;
            if (cx * cx + cy * cy < hole * hole)
                continue;
            int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            if (el == PM_QUAD4) {
                int32_t q[4] = {a, b, c, d};
                memcpy(conn + 4 * nc++, q, sizeof q);
            } else {
                int32_t t[6] = {a, b, c, a, c, d};
                if ((i + j) % 2) {
                    t[2] = d; t[3] = b; t[4] = c; t[5] = d;
                }
                memcpy(conn + 3 * nc, t, sizeof t);
                nc += 2;
            }
        }
    int rc = pm_grid_unstructured(g, nn, x, nc, conn, el);
    free(x);
    free(conn);
    return rc;
}

#endif
