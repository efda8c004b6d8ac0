/*
 * Cost per point of the meshfree shape functions, on the cloud of tests/unit/test_meshfree_cost.c
 * (200 x 200 nodes, h = 0.01, interior nodes jittered by 0.3 h; 158,404 points, 2 x 2 per node
 * cell), three ways:
 *   eval     pm_meshfree_eval(): stateless, the cell list searched and LME solved from lambda = 0;
 *   connect  what a solver's step pays per material point: connect() after nodes and points moved
 *            a little (1e-3 h per step, a smooth field plus a smaller relative motion), so that the
 *            candidate lists hold and LME starts from the point's last lambda;
 *   node     pm_meshfree_eval_node() at every node after the same motion (a GMM step moves its
 *            nodes with the interpolated field).
 * Each figure is the fastest of several repetitions, in ns per point; connect and node on 1 and 2
 * threads. It also checks that connect(), pm_meshfree_eval_node() and pm_meshfree_eval() give the
 * same functions (to 1e-12; a failed check exits with status 1).
 *
 * build and run (from the top directory, after building libpmech.a in build/):
 *   cc -O3 -std=c11 -fopenmp -Iinclude -Isrc bench/meshfree_eval.c build/libpmech.a -lm -o meshfree_eval
 *   OMP_NUM_THREADS=2 ./meshfree_eval [repetitions]
 */
#define _POSIX_C_SOURCE 199309L /* clock_gettime() */

#include "pmech/error.h"
#include "shape/meshfree.h"
#include "shape/approx_internal.h" /* the benchmark sets an approximation's thread count */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define NX 200
#define H 0.01

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double rnd(unsigned long long *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* the displacement of one step at x: a smooth field, plus a smaller one on the scale of h for the
 * points (relative motion of points and nodes) */
static void step_motion(const double *x, double *u, int point, int step)
{
    const double t = 0.1 * step, L = NX * H;
    u[0] = 1e-3 * H * sin(6.0 * x[1] / L + t);
    u[1] = 1e-3 * H * cos(5.0 * x[0] / L + t);
    if (point) {
        u[0] += 2e-4 * H * sin(x[0] / H + t);
        u[1] += 2e-4 * H * cos(x[1] / H + t);
    }
}

static pm_cloud *make_cloud(void)
{
    const size_t n = (size_t)NX * NX;
    double *x = malloc(2 * n * sizeof *x);
    unsigned long long seed = 5;
    for (int j = 0; j < NX; j++)
        for (int i = 0; i < NX; i++) {
            const size_t k = (size_t)j * NX + i;
            const int inner = i > 0 && j > 0 && i < NX - 1 && j < NX - 1;
            x[2 * k] = H * (i + (inner ? 0.3 * (2 * rnd(&seed) - 1) : 0.0));
            x[2 * k + 1] = H * (j + (inner ? 0.3 * (2 * rnd(&seed) - 1) : 0.0));
        }
    pm_cloud *c;
    const pm_cloud_opts o = {.h = H, .cell_size = NAN, .skin = NAN};
    if (pm_cloud_create(n, x, NULL, &o, &c) != PM_OK)
        exit(2);
    free(x);
    return c;
}

static double *make_points(size_t *np)
{
    const size_t n = (size_t)4 * (NX - 1) * (NX - 1);
    double *p = malloc(2 * n * sizeof *p);
    const double g = 0.5 / sqrt(3.0);
    size_t k = 0;
    for (int j = 0; j < NX - 1; j++)
        for (int i = 0; i < NX - 1; i++)
            for (int q = 0; q < 4; q++, k++) {
                p[2 * k] = H * (i + 0.5 + ((q & 1) ? g : -g));
                p[2 * k + 1] = H * (j + 0.5 + ((q & 2) ? g : -g));
            }
    *np = k;
    return p;
}

/* largest difference of N (and of dN times h) between two stencils of the same point */
static double stencil_diff(const pm_stencil *a, const pm_stencil *b)
{
    if (a->n != b->n)
        return INFINITY;
    double worst = 0;
    for (int k = 0; k < a->n; k++) {
        int at = -1;
        for (int q = 0; q < b->n; q++)
            if (b->node[q] == a->node[k])
                at = q;
        if (at < 0)
            return INFINITY;
        worst = fmax(worst, fabs(a->N[k] - b->N[at]));
        worst = fmax(worst, H * fmax(fabs(a->dN[k][0] - b->dN[at][0]), fabs(a->dN[k][1] - b->dN[at][1])));
    }
    return worst;
}

int main(int argc, char **argv)
{
    const int reps = argc > 1 ? atoi(argv[1]) : 5;
    const char *kinds[4] = {"mls", "rk_cubic", "rk_cubic", "lme"};
    const char *labels[4] = {"mls", "rk_cubic radial", "rk_cubic tensor", "lme gamma 1.8"};
    int failed = 0;
    printf("| shape functions | eval, ns | connect 1 thread | connect 2 threads | node 1 thread | node 2 threads |"
           " nodes per point |\n|---|---:|---:|---:|---:|---:|---:|\n");
    for (int kk = 0; kk < 4; kk++) {
        pm_cloud *c = make_cloud();
        size_t np;
        double *x0 = make_points(&np);
        pm_particles p;
        memset(&p, 0, sizeof p);
        p.n = np;
        p.x = malloc(2 * np * sizeof *p.x);
        memcpy(p.x, x0, 2 * np * sizeof *p.x);
        pm_meshfree_opts mo = pm_meshfree_opts_default();
        mo.rk_tensor = kk == 2;
        mo.smoothing = -1; /* point gradients: the cost of one evaluation */
        pm_approx *a;
        if (pm_approx_create_cloud(kinds[kk], c, &mo, &a) != PM_OK)
            return 2;
        /* stateless evaluation */
        double t_eval = INFINITY;
        long nodes = 0;
        for (int r = 0; r < reps; r++) {
            nodes = 0;
            const double t0 = now();
            for (size_t i = 0; i < np; i++) {
                pm_stencil s;
                if (pm_meshfree_eval(a, p.x + 2 * i, &s) != PM_OK)
                    return 2;
                nodes += s.n;
            }
            t_eval = fmin(t_eval, now() - t0);
        }
        /* steps: move, then connect (the points) and the node evaluations, on 1 and 2 threads */
        double t_conn[2] = {INFINITY, INFINITY}, t_node[2] = {INFINITY, INFINITY};
        int step = 0;
        for (int th = 1; th <= 2; th++) {
            a->n_threads = th;
            for (int r = 0; r < reps + 1; r++, step++) {
                for (size_t I = 0; I < c->n; I++) {
                    double u[2];
                    step_motion(c->x + 2 * I, u, 0, step);
                    c->x[2 * I] += u[0];
                    c->x[2 * I + 1] += u[1];
                }
                for (size_t i = 0; i < np; i++) {
                    double u[2];
                    step_motion(p.x + 2 * i, u, 1, step);
                    p.x[2 * i] += u[0];
                    p.x[2 * i + 1] += u[1];
                }
                double t0 = now();
                if (pm_approx_connect(a, &p) != PM_OK)
                    return 2;
                const double tc = now() - t0;
                t0 = now();
                long bad = 0;
#pragma omp parallel for schedule(dynamic, 256) num_threads(th) reduction(+ : bad)
                for (size_t I = 0; I < c->n; I++) {
                    pm_stencil s;
                    bad += pm_meshfree_eval_node(a, I, &s) != PM_OK;
                }
                const double tn = now() - t0;
                if (r > 0) { /* the first step of each thread count makes the candidate lists */
                    t_conn[th - 1] = fmin(t_conn[th - 1], tc);
                    t_node[th - 1] = fmin(t_node[th - 1], tn);
                }
                (void)bad; /* lme fails at the cloud's hull vertices, as it should */
            }
        }
        /* the three ways agree */
        double worst = 0;
        for (size_t i = 0; i < np; i += 97) {
            pm_stencil s1, s2;
            if (pm_approx_eval(a, &p, i, &s1) != PM_OK || pm_meshfree_eval(a, p.x + 2 * i, &s2) != PM_OK)
                return 2;
            worst = fmax(worst, stencil_diff(&s1, &s2));
        }
        for (size_t I = 0; I < c->n; I += 13) {
            pm_stencil s1, s2;
            const int r1 = pm_meshfree_eval_node(a, I, &s1), r2 = pm_meshfree_eval(a, c->x + 2 * I, &s2);
            if (r1 != r2)
                worst = INFINITY;
            else if (r1 == PM_OK)
                worst = fmax(worst, stencil_diff(&s1, &s2));
        }
        printf("| %s | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f |\n", labels[kk], 1e9 * t_eval / (double)np,
               1e9 * t_conn[0] / (double)np, 1e9 * t_conn[1] / (double)np, 1e9 * t_node[0] / (double)c->n,
               1e9 * t_node[1] / (double)c->n, (double)nodes / (double)np);
        if (!(worst < 1e-12)) {
            fprintf(stderr, "%s: connect / node / eval differ by %g\n", labels[kk], worst);
            failed = 1;
        }
        pm_approx_destroy(a);
        pm_cloud_destroy(c);
        free(p.x);
        free(x0);
    }
    return failed;
}
