/*
 * The cohesive soil column collapse (examples/column_collapse: Mohr-Coulomb c = 5 kPa, phi = 25 deg,
 * psi = 0, E = 1.8 MPa, nu = 0.3, rho = 1850, 2 m x 4 m beside a smooth wall on a rough base) run
 * implicitly (Newmark, Newton with the consistent Mohr-Coulomb tangent, UMFPACK for the unsymmetric
 * non-associated tangent) to t = 2 s, on the coarse grid h = 0.1 m (2 x 2 points per cell, 3200
 * points; the example uses h = 0.05 m) so the test stays short.
 *
 * There is no analytic run-out, and no published number for this column: seed 000 shows pictures
 * only, Bui et al. 2008 (SPH) likewise. The reference is therefore the explicit MUSL run of the same
 * coarse case (same grid, points, material and initial geostatic stress; CFL 0.2), an independent
 * time integrator on the same discretisation: this test checks the implicit integrator against the
 * explicit one, not the model against the physics (verify_granular_column does that for a
 * cohesionless column against experiments). Judged:
 *  - the implicit run reaches t = 2 s (the requirement);
 *  - run-out (largest x of the soil's points at t = 2 s, measured from the wall) within 5 % of the
 *    explicit one. Why 5 %: the collapse is a failure process whose shear bands are chosen by the
 *    cell-crossing noise; the example's two meshes (h = 0.05 and 0.025) give run-outs 0.9 % apart
 *    and, at t = 0.88 s, 2.3 % apart, and a time integrator with 20 x larger steps is a bigger
 *    perturbation than that; a column that does not collapse (run-out 2 m) or spreads without
 *    strength (more than 6 m, the grid) is 60 % or more away;
 *  - height of the soil at the wall (largest y of the points within 0.1 m of it) within 5 %, for the
 *    same reasons.
 * Reported: the run-out at t = 0.6 s and 1.28 s, Newton iterations per step, step cuts, seconds.
 *
 * Small variant (PMECH_VERIFY_SMALL, for sanitizer builds): h = 0.2 m (800 points) to t = 0.6 s, the
 * same comparison judged at 0.6 s within 5 % (SMALL_TOL). Measured: run-out -0.9 %, height at the wall
 * +0.7 % of the explicit run's (2.558 m, 3.297 m); a column that has not started to fall (run-out 2 m,
 * height 4 m) is 21 % or more away.
 */
#include "verify_util.h"

#include "pmech/error.h"
#include "solver/implicit.h"
#include "solver/sim_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define NSNAP 3
static const double snap_t[NSNAP] = {0.6, 1.28, 2.0};
static int n_snap = NSNAP; /* 1 in the small variant */
#define SMALL_TOL 0.05

typedef struct result {
    double runout[NSNAP], height[NSNAP], secs, t_end, assemble, solve;
    long steps, iterations, cuts;
} result;

/* One implicit step, its Newton iterations, cuts and times added to the run's result. */
static int implicit_step(pm_sim *s, double dt, void *ctx)
{
    result *r = ctx;
    pm_implicit_report rep;
    const int rc = pm_implicit_step(s, dt, NULL, &rep);
    r->iterations += rep.iterations;
    r->cuts += rep.step_cuts;
    r->assemble += rep.assemble_seconds;
    r->solve += rep.solve_seconds;
    return rc;
}

static result run(pm_case *c, int implicit)
{
    result r = {0};
    if (!implicit) {
        c->analysis.type = PM_ANALYSIS_EXPLICIT;
        c->analysis.scheme = PM_SCHEME_MUSL;
        c->analysis.dt = 0;
        c->analysis.cfl = 0.2;
    }
    const double t0 = vu_now();
    pm_sim *s = vu_sim(c, 1);
    r.steps = vu_collapse_run(s, snap_t, n_snap, implicit ? implicit_step : NULL, &r,
                              implicit ? "implicit" : "explicit", r.runout, r.height);
    r.t_end = s->t;
    r.secs = vu_now() - t0;
    pm_sim_destroy(s);
    return r;
}

/* The coarse case, or for the small variant the same column on cells twice as large. */
static void load(pm_case *c, int small)
{
    vu_load("tests/verification/cases/implicit_column_collapse.json", c);
    if (small)
        for (int d = 0; d < PM_DIM; d++)
            c->grid.cells[d] /= 2;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = 1;
    const int small = vu_small();
    if (small)
        n_snap = 1;
    pm_case c;
    load(&c, small);
    const double dt = c.analysis.dt;
    result im = run(&c, 1);
    pm_case_free(&c);
    load(&c, small);
    result ex = run(&c, 0);
    printf("explicit: %ld steps, %.1f s; implicit: %ld steps of %g s, %.2f Newton iterations per step, %ld cuts, "
           "%.1f s (assembly %.1f s, solves %.1f s)\n",
           ex.steps, ex.secs, im.steps, dt, (double)im.iterations / im.steps, im.cuts, im.secs, im.assemble, im.solve);
    printf("PERF|column collapse h = 0.1, implicit, dt = %g|%zu|%ld|%.4g|%.2f|%.4g|%.4g|%ld\n", dt, (size_t)3200,
           im.steps, im.secs / im.steps, (double)im.iterations / im.steps, im.assemble / im.steps,
           im.solve / im.steps, im.cuts);
    const double t_end = snap_t[n_snap - 1];
    ok &= vu_report("column collapse (implicit)", "end time reached (s)", im.t_end, t_end, im.t_end - t_end, 1e-9,
                    im.secs);
    for (int k = 0; k < n_snap; k++) {
        char q[96];
        const double tol = k < n_snap - 1 ? -1 : small ? SMALL_TOL : 0.05;
        snprintf(q, sizeof q, "run-out at t = %.2f s (m), implicit vs explicit MUSL, h = %.1f", snap_t[k],
                 small ? 0.2 : 0.1);
        ok &= vu_report("column collapse (implicit)", q, im.runout[k], ex.runout[k],
                        (im.runout[k] - ex.runout[k]) / ex.runout[k], tol, im.secs);
        snprintf(q, sizeof q, "height at the wall at t = %.2f s (m), implicit vs explicit", snap_t[k]);
        ok &= vu_report("column collapse (implicit)", q, im.height[k], ex.height[k],
                        (im.height[k] - ex.height[k]) / ex.height[k], tol, im.secs);
    }
    char q[96];
    snprintf(q, sizeof q, "Newton iterations per step (dt = %g s)", dt);
    vu_report("column collapse (implicit)", q, (double)im.iterations / im.steps, 0, 0, -1, im.secs);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
