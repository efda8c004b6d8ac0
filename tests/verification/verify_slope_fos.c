/*
 * Factor of safety of a slope by strength reduction, against Griffiths & Lane (1999), Geotechnique
 * 49(3), example 1: a homogeneous 2:1 slope with no foundation layer (depth factor D = 1), H = 10 m,
 * c' / (gamma H) = 0.05 (c' = 10 kPa with gamma = 20 kN/m^3), phi' = 20 deg, psi = 0, E = 1e5 kPa,
 * nu = 0.3; the crest runs 1.2 H behind the top of the face, the base under the whole body is fixed
 * and the back face is on rollers (cases/slope_fos.json). Their finite elements give FoS = 1.4, as do
 * Bishop & Morgenstern's charts (Bishop's method of slices); that is the reference.
 *
 * Gravity is applied in one quasi-static load step; a factor fails when that step does not converge
 * after Newton's 8 halvings (pmech/strength_reduction.h); bisection between 1.2 and 1.8 to 0.02, so the
 * factor found is within 0.01 of the search's own limit. A step is converged at a relative residual of
 * 1e-8, or when the correction is below 1e-4 of the increment with the residual below 1e-4: RKPM's
 * Newton stalls between 1e-6 and 4e-5 on this slope (its plastic tangent is not exactly consistent),
 * while a slope that flows keeps corrections of about 0.1 of its increment. A force test alone at 1e-4
 * would pass such a flowing slope (MPM h = H/20 then gives 1.56).
 *
 * Rows (one thread):
 *  - MPM, linear quads, 2 x 2 points per cell, h = H/20 = 0.5 m: judged within 5 % of 1.4. Linear
 *    quads with 4 points lock in isochoric plastic flow (psi = 0) and make a coarse slope too strong
 *    (the next row); at H/20 the factor is within 2 % (examples/slope_fos has the study). 5 % covers
 *    the bisection's 0.01, the spread over the Newton settings (1.378 to 1.403 at H/20 over 6 to 12
 *    step cuts, 1 to 10 load steps, 25 or 50 iterations, force tolerance 1e-6 or 1e-8) and the
 *    reference's own scatter (charts and finite elements, 1.38 to 1.40).
 *  - MPM at h = H/10: reported, not judged (8 % high from the locking above).
 *  Not converged, and not claimed to be: under refinement the MPM factor keeps falling, 1.509, 1.378,
 *  1.341 at H/10, H/20, H/40 (examples/slope_fos, study.sh), so at H/40 it is 4.2 % below 1.4 and
 *  the trend points further down (part of it may be Newton's difficulty on the finer grid: F = 1.2
 *  already needs step cuts there). The H/20 row is judged as the answer of that mesh, which is what
 *  users run. H/40 is judged within the same 5 % by examples/slope_fos/study.sh (it exits 1 when
 *  H/20 or H/40 is outside), not here: even the two trials that decide "within 5 %" at H/40, F = 1.33
 *  must hold and F = 1.47 must fail, took 158 s of one core's CPU on the loaded machine (F = 1.33
 *  holds after 196 Newton iterations and 5 step cuts; F = 1.47 fails at 78 % of gravity after 354
 *  iterations and 8 cuts), beyond the suite's budget of a minute per test. Its margin is small (bracket 1.331-1.350
 *  against the band's lower end 1.33): a finer mesh would likely fall out of the band.
 *  - RKPM (rk_cubic, one node per cell: node spacing H/10, 220 nodes): judged within 10 %, the
 *    over-estimate to be expected of a discretisation this coarse (MPM at the same spacing is 8 %
 *    high). It lands within 2 %; likely because one smoothed integration point per node constrains
 *    isochoric flow far less than four points per linear quad (not isolated further).
 *
 * Small variant (PMECH_VERIFY_SMALL, for sanitizer builds): the MPM H/10 row alone, judged within 10 %,
 * with Newton allowed 4 step cuts instead of 8. A failing trial spends nearly all the run time in its
 * cuts (at H/10: 580-670 Newton iterations with 8 cuts, 137-143 with 4, against 5-25 for a trial that
 * holds); fewer cuts can only make a trial fail sooner, and every trial of this search that holds does
 * so with no cut, so the factor found is the same (measured: 1.509 with 4 cuts as with 8, 8 % high from
 * the locking above). A slope that keeps no strength (the search's floor, 1.2) or far too much (its
 * ceiling, 1.8) is outside 10 %.
 */
#include "verify_util.h"

#include "pmech/error.h"
#include "pmech/strength_reduction.h"
#include "solver/sim_internal.h"

#include <stdio.h>
#include <stdlib.h>

#define FOS_REF 1.4
#define H 10.0

static int row(pm_case *c, const char *label, pm_method method, const char *shape, double h, int ppc, double tol)
{
    c->method = method;
    c->bodies[0].particles_per_cell = ppc;
    snprintf(c->shape_function, sizeof c->shape_function, "%s", shape);
    c->grid.cells[0] = (int)(c->grid.size[0] / h + 0.5);
    c->grid.cells[1] = (int)(c->grid.size[1] / h + 0.5);
    pm_srf_result *r = malloc(sizeof *r);
    if (!r)
        return 0;
    pm_run_opts o = {.out_dir = NULL, .quiet = 1, .threads = 1, .write_output = 0};
    const double t0 = vu_now();
    const int rc = pm_strength_reduction(c, &o, r);
    const double secs = vu_now() - t0;
    char q[160];
    snprintf(q, sizeof q, "%s, h = H/%.0f: factor of safety (%d trials)", label, H / h, r->n_trials);
    for (int k = 0; k < r->n_trials; k++)
        printf("%s h = %g: F = %.4f %s, max displacement %.4g m, gravity reached %.3f, %ld Newton iterations, "
               "%ld step cuts, %.2f s\n",
               label, h, r->trial[k].factor, r->trial[k].failed ? "fails" : "holds", r->trial[k].max_displacement,
               r->trial[k].t, r->trial[k].newton_iterations, r->trial[k].step_cuts, r->trial[k].wall_seconds);
    int ok;
    if (rc) {
        fprintf(stderr, "%s: %s\n", q, pm_error_message());
        ok = vu_report("slope factor of safety (Griffiths & Lane 1999)", q, 0, FOS_REF, 1, tol, secs);
    } else {
        ok = vu_report("slope factor of safety (Griffiths & Lane 1999)", q, r->fos, FOS_REF,
                       (r->fos - FOS_REF) / FOS_REF, tol, secs);
    }
    free(r);
    return tol < 0 || ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    pm_case c;
    vu_load("tests/verification/cases/slope_fos.json", &c);
    int ok = 1;
    if (vu_small()) {
        c.analysis.newton.max_step_cuts = 4;
        ok &= row(&c, "MPM linear, 2 x 2 points per cell, 4 step cuts", PM_METHOD_MPM, "linear", 1.0, 2, 0.10);
        pm_case_free(&c);
        return ok ? 0 : 1;
    }
    ok &= row(&c, "MPM linear, 2 x 2 points per cell", PM_METHOD_MPM, "linear", 0.5, 2, 0.05);
    ok &= row(&c, "MPM linear, 2 x 2 points per cell", PM_METHOD_MPM, "linear", 1.0, 2, -1);
    ok &= row(&c, "RKPM rk_cubic, a node per cell", PM_METHOD_RKPM, "rk_cubic", 1.0, 1, 0.10);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
