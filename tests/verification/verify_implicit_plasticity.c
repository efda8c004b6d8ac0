/*
 * Mohr-Coulomb and Drucker-Prager run implicitly with their consistent tangents: plane-strain
 * unconfined compression of a block (0.5 m wide, 1 m high; E = 100 MPa, nu = 0.3, c = 10 kPa,
 * phi = 30 deg, psi = 0) between smooth platens (rollers at the base, a prescribed downward velocity
 * on the top grid line, symmetry at x = 0, the side x = 0.5 free), quasi-static in 20 load steps to
 * 2 % axial strain, some 60 times the strain at failure. The stress is homogeneous, so the axial
 * stress of every point is judged against the analytic limit stress (compression positive):
 *  - Mohr-Coulomb: sigma_3 = sigma_xx = 0, and with psi = 0 the plastic flow (1, 0, -1) leaves the
 *    out-of-plane stress at its elastic value nu sigma_yy, which stays the intermediate one; so the
 *    limit is the unconfined strength q_u = 2 c cos(phi) / (1 - sin(phi)) = 34.64 kPa from the
 *    first yield on (cases/implicit_compression_mc.json);
 *  - Drucker-Prager (outer cone, A = -1, cases/implicit_compression_dp.json): in steady plastic
 *    flow the stress no longer changes, so the plastic out-of-plane strain rate vanishes, which with
 *    psi = 0 (b = 0) means s_zz = 0, sigma_zz = sigma_yy / 2; then q = sqrt(3) sigma_a / 2,
 *    p = -sigma_a / 2 and F = 0 gives sigma_a = 2 alpha / (1 - beta) = 78.13 kPa. The out-of-plane
 *    stress relaxes to it over a plastic strain of order sigma / E = 0.1 %, which is why E is large.
 * Tolerances: the mean axial stress at 2 % strain within 1 % of the analytic value, and every
 * point's axial stress within 2 % of the mean (homogeneity). Both are loose against what perfect
 * plasticity allows (the yield condition holds at every converged point), and leave room for the
 * stabilisation springs of weakly supported nodes; 2 % strain keeps every point inside its starting
 * cell (the top row of points, a quarter cell below the platen's grid line, would cross at 2.6 %),
 * so the homogeneous field is exactly representable.
 * Newton iterations per step are reported, and one plastic step's residuals: the tangent is
 * unsymmetric (non-associated flow, so UMFPACK solves it). Convergence is linear, not quadratic:
 * these models are hypo-elastic (Hughes-Winget) and their tangent is d sigma / d eps of the return
 * mapping without the objective-rate terms of order sigma / E.
 */
#include "verify_util.h"

#include "pmech/error.h"
#include "solver/implicit.h"
#include "solver/sim_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int run(const char *file, const char *name, double ref, double tol)
{
    pm_case c;
    vu_load(file, &c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    const double dt = c.analysis.end_time / c.analysis.load_steps;
    int iters = 0, cuts = 0, umf = 0, worst_it = 0;
    double assemble = 0, solve = 0;
    double hist[64][2];
    int nh = 0;
    for (int step = 0; step < c.analysis.load_steps; step++) {
        pm_implicit_report rep;
        if (pm_implicit_step(s, dt, NULL, &rep) != 0) {
            fprintf(stderr, "%s: %s\n", name, pm_error_message());
            return 0;
        }
        iters += rep.iterations;
        cuts += rep.step_cuts;
        umf |= rep.used_umfpack;
        assemble += rep.assemble_seconds;
        solve += rep.solve_seconds;
        worst_it = rep.iterations > worst_it ? rep.iterations : worst_it;
        double sv = 0, vv = 0;
        for (size_t i = 0; i < s->p.n; i++) {
            sv += -s->p.stress[PM_NS * i + PM_SYY] * s->p.vol[i];
            vv += s->p.vol[i];
        }
        if (nh < 64) {
            hist[nh][0] = 0.02 * s->t / c.analysis.end_time;
            hist[nh][1] = sv / vv;
            nh++;
        }
        printf("%s step %d: %d Newton iterations, mean axial stress %.6g Pa\n", name, step + 1, rep.iterations,
               sv / vv);
        if (step == 9) {
            printf("%s step 10 relative residuals:", name);
            for (int k = 0; k < rep.n_history; k++)
                printf(" %.2e", rep.residual[k]);
            printf("\n");
        }
    }
    const double secs = vu_now() - t0;
    double sv = 0, vv = 0;
    for (size_t i = 0; i < s->p.n; i++) {
        sv += -s->p.stress[PM_NS * i + PM_SYY] * s->p.vol[i];
        vv += s->p.vol[i];
    }
    const double mean = sv / vv;
    double spread = 0;
    for (size_t i = 0; i < s->p.n; i++)
        spread = fmax(spread, fabs(-s->p.stress[PM_NS * i + PM_SYY] - mean) / mean);
    int ok = 1;
    char q[128];
    snprintf(q, sizeof q, "%s: mean axial stress at 2 %% strain (Pa)", name);
    ok &= vu_report("plane-strain compression (implicit)", q, mean, ref, (mean - ref) / ref, tol, secs);
    snprintf(q, sizeof q, "%s: largest deviation of a point's axial stress from the mean", name);
    ok &= vu_report("plane-strain compression (implicit)", q, spread, 0, spread, 0.02, secs);
    snprintf(q, sizeof q, "%s: Newton iterations per load step (most %d)%s", name, worst_it,
             umf ? ", UMFPACK" : "");
    vu_report("plane-strain compression (implicit)", q, (double)iters / c.analysis.load_steps, 0, 0, -1, secs);
    printf("PERF|compression %s, quasi-static|%zu|%d|%.4g|%.2f|%.4g|%.4g|%d\n", name, s->p.n, c.analysis.load_steps,
           secs / c.analysis.load_steps, (double)iters / c.analysis.load_steps, assemble / c.analysis.load_steps,
           solve / c.analysis.load_steps, cuts);
    char csv[64];
    snprintf(csv, sizeof csv, "implicit_compression_%s.csv", name);
    vu_write_csv(csv, "axial_strain,mean_axial_stress", &hist[0][0], (size_t)nh, 2);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    const double c = 1e4, phi = 30.0 * M_PI / 180.0;
    const double q_mc = 2 * c * cos(phi) / (1 - sin(phi));
    const double alpha = 6 * c * cos(phi) / (sqrt(3.0) * (3 - sin(phi)));
    const double beta = 6 * sin(phi) / (sqrt(3.0) * (3 - sin(phi)));
    const double q_dp = 2 * alpha / (1 - beta);
    int ok = 1;
    ok &= run("tests/verification/cases/implicit_compression_mc.json", "mohr_coulomb", q_mc, 0.01);
    ok &= run("tests/verification/cases/implicit_compression_dp.json", "drucker_prager", q_dp, 0.01);
    return ok ? 0 : 1;
}
