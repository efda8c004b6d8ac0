/*
 * Cantilever under self-weight (seed 000 section 5.1, Fig. 7) with the meshfree methods: the same
 * case as verify_cantilever.c (implicit quasi-static, 10 load steps, neo-Hookean, 4 points per cell)
 * with method gmm and shape functions mls and lme (nodes: the nodes of the occupied cells of the
 * grid, h = 0.5 ... 0.0625), and rkpm with rk_cubic (nodes: the particles).
 *
 * Judged, for GMM-MLS and GMM-LME:
 *  - finest mesh within 1 % of the paper's 0.67433 m (the requirement; measured -0.23 %);
 *  - the error against the finest mesh falls at a mean rate of at least 1.5 (seed 000 Fig. 7 reports
 *    rate 2 for both; MLS measures 3.1 here, LME 2.5: faster than h^2 is no failure, so only the lower
 *    side is judged, with the same half-unit band verify_cantilever.c allows for the finest-mesh
 *    reference);
 *  - Newton needs at most 6 iterations per load step on average (quadratic convergence with the
 *    consistent tangent; 4 are measured).
 * RKPM is reported, not judged: with nodal integration at the particles it does not converge on this
 * bending problem (see docs/meshfree.md).
 */
#include "verify_util.h"
#include "cantilever_tip.h"

#include "pmech/error.h"
#include "pmech/implicit.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define REF_PAPER 0.67433

/* One run: the tip deflection, seconds and mean Newton iterations per load step. */
static int run(const char *method, const char *shape, double h, double *delta, double *secs, double *its)
{
    pm_case c;
    vu_load("examples/cantilever/case.json", &c);
    c.method = strcmp(method, "gmm") == 0 ? PM_METHOD_GMM : PM_METHOD_RKPM;
    snprintf(c.shape_function, sizeof c.shape_function, "%s", shape);
    c.grid.cells[0] = (int)lround(9.0 / h);
    c.grid.cells[1] = (int)lround(2.5 / h);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    const double dt = c.analysis.end_time / c.analysis.load_steps;
    long total = 0;
    for (int step = 0; step < c.analysis.load_steps; step++) {
        pm_implicit_report rep;
        if (pm_implicit_step(s, dt, NULL, &rep) != 0) {
            fprintf(stderr, "%s/%s h = %g: %s\n", method, shape, h, pm_error_message());
            pm_sim_destroy(s);
            pm_case_free(&c);
            return 0;
        }
        total += rep.iterations;
    }
    *delta = tip_deflection(s, h);
    *secs = vu_now() - t0;
    *its = (double)total / c.analysis.load_steps;
    printf("%s/%s h = %-7g tip deflection %.5f m  %.1f Newton iterations per step  (%.2f s)\n", method, shape, h,
           *delta, *its, *secs);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return 1;
}

static int judged(const char *shape, double rows[4][4])
{
    const double hs[4] = {0.5, 0.25, 0.125, 0.0625};
    char bench[64], q[64];
    snprintf(bench, sizeof bench, "cantilever GMM-%s (quasi-static)", strcmp(shape, "mls") ? "LME" : "MLS");
    double delta[4], secs[4], its = 0;
    for (int k = 0; k < 4; k++) {
        double it = NAN;
        if (!run("gmm", shape, hs[k], &delta[k], &secs[k], &it))
            return 0;
        its = fmax(its, it);
        rows[k][0] = hs[k];
        rows[k][strcmp(shape, "mls") ? 2 : 1] = delta[k];
    }
    int ok = vu_report(bench, "tip deflection h=0.0625 [m]", delta[3], REF_PAPER, (delta[3] - REF_PAPER) / REF_PAPER,
                       0.01, secs[3]);
    for (int k = 0; k < 3; k++) {
        snprintf(q, sizeof q, "tip deflection h=%g [m]", hs[k]);
        vu_report(bench, q, delta[k], REF_PAPER, (delta[k] - REF_PAPER) / REF_PAPER, -1, secs[k]);
    }
    const double e0 = fabs(delta[0] - delta[3]), e1 = fabs(delta[1] - delta[3]), e2 = fabs(delta[2] - delta[3]);
    const double rate = 0.5 * (log2(e0 / e1) + log2(e1 / e2));
    ok &= vu_report(bench, "convergence rate (error vs finest), judged >= 1.5", rate, 2.0, fmin(0.0, rate - 2.0), 0.5,
                    0);
    ok &= vu_report(bench, "Newton iterations per load step (largest mean)", its, 4.0, its - 4.0, 2.0, 0);
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    double rows[4][4] = {{0}};
    int ok = judged("mls", rows);
    ok &= judged("lme", rows);
    const double hk[2] = {0.5, 0.25};
    for (int k = 0; k < 2; k++) {
        double d = NAN, secs = 0, its = 0;
        char q[64];
        snprintf(q, sizeof q, "tip deflection h=%g [m]", hk[k]);
        if (run("rkpm", "rk_cubic", hk[k], &d, &secs, &its))
            vu_report("cantilever RKPM (quasi-static)", q, d, REF_PAPER, (d - REF_PAPER) / REF_PAPER, -1, secs);
        rows[k][3] = d;
    }
    vu_write_csv("meshfree_cantilever.csv", "h,gmm_mls,gmm_lme,rkpm", &rows[0][0], 4, 4);
    return ok ? 0 : 1;
}
