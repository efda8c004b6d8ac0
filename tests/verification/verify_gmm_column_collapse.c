/*
 * The cohesive soil column collapse of seed 000 §5.3 (examples/column_collapse: Mohr-Coulomb
 * c = 5 kPa, phi = 25 deg, psi = 0, E = 1.8 MPa, nu = 0.3, rho = 1850, 2 m x 4 m beside a smooth
 * wall on a rough base) with the Galerkin meshfree method, explicit MUSL to t = 2 s, on the coarse
 * grid h = 0.1 m (2 x 2 points per cell, 3200 points) so the test stays short.
 *
 * Seed 000 reports that at t = 2 s "the final configurations of MPM, GMM-LME and GMM-MLS almost
 * coincide", and that GMM survives this test only with an adaptive cloud: the support grows until
 * it holds enough nodes and its moment matrix (MLS) or Hessian (LME) is well conditioned. As the
 * column spreads, the nodes, which move with the material, are stretched apart along the flow and
 * pressed together across it; a circular support then holds one or two rows of nodes across the
 * stretch and the MLS moment matrix becomes nearly singular (gradients ten times their normal size,
 * shape functions of -0.6), which blows a run up in a few steps.
 *
 * There is no analytic run-out and no published number (seed 000 and Bui et al. 2008 give pictures
 * only); the reference is the MPM run of the same case (same points, material, initial stress, CFL),
 * so this is a comparison of methods, not a verification against the physics. Judged:
 *  - GMM-MLS and GMM-LME reach t = 2 s with pmech's default adaptive cloud;
 *  - their run-out (largest x of the points) and the height of the soil at the wall (largest y of
 *    the points within 0.1 m of it) at t = 2 s within 10 % of MPM's. Why 10 %: the methods differ in
 *    the approximation and in how the rough base acts (MPM holds every base node of the fixed grid;
 *    GMM holds the nodes on the base at t = 0 and stops the others where they reach it), the
 *    collapse is a failure process whose shear bands follow discretisation noise (the MPM example's
 *    two meshes give run-outs 0.9 % apart at t = 2 s but 2.3 % at 0.88 s), and a column that does
 *    not fall (run-out 2 m) or flows without strength (beyond the 6 m grid) is 60 % or more away.
 * Reported, not judged: the same figures at t = 0.6 and 1.28 s, and the time a GMM-MLS run without
 * the conditioning rule (moment matrices admitted up to condition number 1e6) stops.
 *
 * Small variant (PMECH_VERIFY_SMALL, for sanitizer builds): h = 0.2 m (800 points) to t = 0.6 s, the
 * same comparison judged at 0.6 s within 5 %, and the run without the conditioning rule left out.
 * Measured: run-out +1.7 % (MLS) and +1.1 % (LME), height at the wall -1.6 % and -1.4 % of MPM's
 * (2.558 m and 3.297 m); early in the collapse the methods have had less time to part. A column that
 * has not started to fall (run-out 2 m, height 4 m) is 21 % or more away.
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define NSNAP 3
static const double snap_t[NSNAP] = {0.6, 1.28, 2.0};
static int n_snap = NSNAP; /* 1 in the small variant */
#define SMALL_TOL 0.05

typedef struct result {
    double runout[NSNAP], height[NSNAP], secs, t_end;
    long steps;
} result;

/* One explicit MUSL run of the coarse column with the given method and approximation; cond_tol
 * NAN keeps the approximation's default. */
static result run(pm_method method, const char *shape, double cond_tol)
{
    pm_case c;
    vu_load("tests/verification/cases/implicit_column_collapse.json", &c);
    c.analysis.type = PM_ANALYSIS_EXPLICIT;
    c.analysis.scheme = PM_SCHEME_MUSL;
    c.analysis.dt = 0;
    c.analysis.cfl = 0.2;
    c.method = method;
    snprintf(c.shape_function, sizeof c.shape_function, "%s", shape);
    c.max_condition = cond_tol;
    if (n_snap < NSNAP) /* the small variant's cells twice as large */
        for (int d = 0; d < PM_DIM; d++)
            c.grid.cells[d] /= 2;
    result r = {0};
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    char label[32];
    snprintf(label, sizeof label, "%s/%s", method == PM_METHOD_GMM ? "gmm" : "mpm", shape);
    r.steps = vu_collapse_run(s, snap_t, n_snap, NULL, NULL, label, r.runout, r.height);
    r.t_end = s->t;
    r.secs = vu_now() - t0;
    printf("%s/%s: %ld steps to t = %.4g s, %.1f s, %.3g M particle-steps/s\n",
           method == PM_METHOD_GMM ? "gmm" : "mpm", shape, r.steps, r.t_end, r.secs,
           1e-6 * (double)r.steps * (double)s->p.n / r.secs);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return r;
}

static int judge(const char *label, const result *g, const result *ref)
{
    char bench[64], q[128];
    snprintf(bench, sizeof bench, "column collapse (%s)", label);
    const double t_end = snap_t[n_snap - 1];
    int ok = vu_report(bench, "end time reached (s)", g->t_end, t_end, g->t_end - t_end, 1e-9, g->secs);
    for (int k = 0; k < n_snap && g->t_end >= snap_t[k] - 1e-9; k++) {
        const double tol = k < n_snap - 1 ? -1 : n_snap < NSNAP ? SMALL_TOL : 0.10;
        snprintf(q, sizeof q, "run-out at t = %.2f s (m), vs MPM, h = %.1f", snap_t[k], n_snap < NSNAP ? 0.2 : 0.1);
        ok &= vu_report(bench, q, g->runout[k], ref->runout[k], (g->runout[k] - ref->runout[k]) / ref->runout[k],
                        tol, g->secs);
        snprintf(q, sizeof q, "height at the wall at t = %.2f s (m), vs MPM", snap_t[k]);
        ok &= vu_report(bench, q, g->height[k], ref->height[k], (g->height[k] - ref->height[k]) / ref->height[k],
                        tol, g->secs);
    }
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    if (vu_small())
        n_snap = 1;
    const result mpm = run(PM_METHOD_MPM, "linear", NAN);
    const result mls = run(PM_METHOD_GMM, "mls", NAN);
    const result lme = run(PM_METHOD_GMM, "lme", NAN);
    int ok = judge("GMM-MLS", &mls, &mpm);
    ok &= judge("GMM-LME", &lme, &mpm);
    if (n_snap == NSNAP) {
        const result bare = run(PM_METHOD_GMM, "mls", 1e6);
        vu_report("column collapse (GMM-MLS)", "time reached without the conditioning rule (s)", bare.t_end, 2.0,
                  bare.t_end - 2.0, -1, bare.secs);
    }
    return ok ? 0 : 1;
}
