/*
 * Contact in implicit and quasi-static runs (penalty terms in the Newton residual and tangent,
 * src/contact/implicit_terms.c).
 *
 * Block on an obstacle (cases/implicit_block_on_obstacle.json): an elastic block 0.2 x 0.1 m
 * (rho = 1000, E = 1 MPa, nu = 0.3; a roller on its left side, the symmetry plane) rests on a rigid
 * frictionless polyline obstacle and is loaded by gravity 10 m/s^2 over 4 quasi-static steps. Judged:
 *  - the obstacle's normal force equals the weight, 200 N/m, to 1e-6 relative: static equilibrium,
 *    which a converged Newton solve (relative tolerance 1e-8) must meet whatever the penalty;
 *  - the penetration, the material's base (its displacement extrapolated from the two lowest particle
 *    rows to y = 0) below the obstacle, within 5 % of W / (k sum m_I), the weight over the penalty
 *    stiffness of the base nodes (k = (c / h)^2 per node mass): the penalty springs carry the weight
 *    and nothing else does (the block is seeded on the obstacle: its Gauss points' extent overlaps
 *    it by 4 % of a cell, which counts as touching with no force). A body that sank freely, or a
 *    penalty that forgot its force between the 4 load steps (sinking by 1 + 2 + 3 + 4 increments), is
 *    off by a factor of 2 or more.
 *
 * Block on an incline (cases/implicit_sliding_block.json): the same block, E = 10 MPa, on a friction
 * boundary (grid side y_min) with gravity tilted by theta = 30 degrees, Newmark steps of 2 ms (23
 * times the explicit limit h / c). Rigid-body answer while sliding: mean velocity
 * g (sin(theta) - mu cos(theta)) t, 0.4905 m/s (mu = 0) and 0.40554 m/s (mu = 0.1) at t = 0.1 s,
 * within 2 %. With mu = 1.5 tan(theta) (gravity ramped over 20 ms) it sticks: its centre of mass must
 * move less than 1 % of the frictionless distance g sin(theta) t^2 / 2 (the tangential penalty keeps
 * each node's force from step to step, so a sticking block does not creep).
 */
#include "verify_util.h"

#include "contact/contact.h"
#include "pmech/error.h"
#include "solver/implicit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static void run_implicit(pm_sim *s, double end)
{
    const int qs = s->c->analysis.type == PM_ANALYSIS_QUASI_STATIC;
    const double dt = qs ? end / s->c->analysis.load_steps : s->c->analysis.dt;
    while (s->t < end - 1e-9 * end) {
        const double h = fmin(dt, end - s->t);
        if (pm_implicit_step(s, h, NULL, NULL) != PM_OK) {
            fprintf(stderr, "implicit step failed: %s\n", pm_error_message());
            exit(1);
        }
    }
}

static int block_on_obstacle(void)
{
    pm_case c;
    vu_load("tests/verification/cases/implicit_block_on_obstacle.json", &c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    run_implicit(s, c.analysis.end_time);
    const double secs = vu_now() - t0;
    pm_contact_force f;
    if (pm_contact_force_of(s->contact, 0, &f) != PM_OK)
        return 0;
    const double W = 1000 * 0.2 * 0.1 * 10.0;
    int ok = vu_report("implicit block on obstacle", "obstacle's normal force / weight", f.normal / W, 1.0,
                       f.normal / W - 1.0, 1e-6, secs);
    /* the base nodes (y = 0) and their mass */
    double base_mass = 0.0;
    for (size_t I = 0; I < s->grid.n_nodes; I++)
        if (fabs(s->grid.x[2 * I + 1]) < 1e-9)
            base_mass += s->nd.mass[I];
    const double h = s->grid.h_min, expect = W / (s->contact->penalty * base_mass);
    /* the material's base: the displacement of the two lowest particle rows (Gauss points at
     * 0.2113 h and 0.7887 h) extrapolated to y = 0 */
    const double y1 = 0.2113249 * h, y2 = 0.7886751 * h;
    double u1 = 0, u2 = 0;
    int n1 = 0, n2 = 0;
    for (size_t i = 0; i < s->p.n; i++) {
        const double y0 = s->p.x0[2 * i + 1], uy = s->p.x[2 * i + 1] - y0;
        if (fabs(y0 - y1) < 1e-6 * h)
            u1 += uy, n1++;
        else if (fabs(y0 - y2) < 1e-6 * h)
            u2 += uy, n2++;
    }
    if (!n1 || !n2)
        return 0;
    u1 /= n1, u2 /= n2;
    const double pen = -(u1 - (u2 - u1) * y1 / (y2 - y1));
    ok &= vu_report("implicit block on obstacle", "penetration / (W / (k sum m_base))", pen / expect, 1.0,
                    pen / expect - 1.0, 0.05, secs);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = block_on_obstacle();
    ok &= vu_sliding_block("implicit sliding block", "tests/verification/cases/implicit_sliding_block.json",
                           ", implicit", run_implicit, 0.01);
    return ok ? 0 : 1;
}
