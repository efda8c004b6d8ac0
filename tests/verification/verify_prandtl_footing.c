/*
 * Prandtl's strip footing (cases/prandtl_footing.json, the mesh of examples/rigid_footing): a smooth
 * rigid footing of half width B/2 = 0.25 m (half model, symmetry plane x_min) pushed at 0.05 m/s
 * (ramped over 0.1 s) into a weightless clay, von Mises with yield stress sqrt(3) c_u (plane strain:
 * it yields in shear at c_u = 10 kPa, Tresca-like), E = 10 MPa, nu = 0.45; explicit MUSL with F-bar
 * (linear quads with 4 points per cell lock in isochoric flow) and local damping 0.05 so the slow
 * loading stays near quasi-static; h = 0.05 m (5 cells under the half footing).
 *
 * Judged:
 * - the limit pressure, the footing's own force output (the impulse the obstacle gave the clay,
 *   averaged over the settlement window WINDOW_FROM..WINDOW_TO, 12.5-20 mm) over B/2, within 5 % of
 *   Prandtl's (2 + pi) c_u = 51.42 kPa. 5 %: the tolerance; the locking answer of this mesh
 *   without F-bar (reported below, 41 % high) fails it;
 * - that the force does not carry the local damping: the same case with damping 0.10 within 2 % of it.
 *   Local damping's force, alpha |f| against the velocity, once entered the impulse of every node the
 *   footing drives, so the force rose by about alpha (damping 0, 0.05, 0.10: 0.95, 1.01, 1.07 times
 *   Prandtl, 6 % between the two judged here); with the damping kept out of those nodes 0.963 and
 *   0.971. The footing's speed halved and doubled moved it by 0.7 % each (docs/verification-notes.md),
 *   so 2 % leaves room for the rate and fails a force that takes the damping's share;
 * - the same force with the explicit Newmark predictor-corrector within 2 % of MUSL's (measured 1.004).
 *   That scheme applies the contact law over gamma dt = dt / 2; counted as a momentum change over dt,
 *   its footing once reported half its force (0.483 times Prandtl).
 *
 * Reported (not judged): the same case without F-bar, which must come out well above Prandtl; with the
 * footing acting at the particles that touch it (acts_at "particles"), which holds the node on its
 * edge line from the start; and on the 0.025 m mesh, where the footing starts to drive that edge node,
 * and with it the clay beside the footing, after half a cell of settlement, inside this window (the
 * mesh study in docs/verification-notes.md: the force is then up to h / (B/2) higher and falls back).
 */
#include "verify_util.h"

#include "contact/contact.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Settlement window of the plateau: after the ramp and the elastic-plastic transition, before the heave
 * beside the footing reaches its vertical side (see examples/rigid_footing/README.md). */
#define WINDOW_FROM 0.3
#define WINDOW_TO 0.45

static double limit_pressure(pm_scheme scheme, int fbar, int at_particles, double damping, int cells_x, double *secs)
{
    pm_case c;
    vu_load("tests/verification/cases/prandtl_footing.json", &c);
    c.analysis.scheme = scheme;
    if (!fbar)
        c.analysis.fbar = PM_FBAR_NONE;
    c.analysis.damping = damping;
    /* the same domain on a finer grid: cells_x across 2 m, the height's cells in proportion */
    c.grid.cells[1] = c.grid.cells[1] * cells_x / c.grid.cells[0];
    c.grid.cells[0] = cells_x;
    c.obstacles[0].at_particles = at_particles;
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    vu_run_to(s, WINDOW_FROM);
    pm_contact_surface *sf = &s->contact->surface[0];
    memset(&sf->impulse, 0, sizeof sf->impulse);
    vu_run_to(s, WINDOW_TO);
    const double force = sf->impulse.normal / (WINDOW_TO - WINDOW_FROM);
    *secs = vu_now() - t0;
    pm_sim_destroy(s);
    pm_case_free(&c);
    return force / 0.25;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    const double cu = 10e3, prandtl = (2.0 + M_PI) * cu;
    const char *bench = "Prandtl footing (explicit, F-bar)";
    double secs;
    const double q = limit_pressure(PM_SCHEME_MUSL, 1, 0, 0.05, 40, &secs);
    int ok = vu_report(bench, "limit pressure / (2 + pi) c_u, h = B/10", q / prandtl, 1.0, q / prandtl - 1.0, 0.05,
                       secs);
    const double q_damp = limit_pressure(PM_SCHEME_MUSL, 1, 0, 0.10, 40, &secs);
    ok &= vu_report(bench, "damping 0.10 / damping 0.05 (the force must not carry the damping)", q_damp / q, 1.0,
                    q_damp / q - 1.0, 0.02, secs);
    const double q_newmark = limit_pressure(PM_SCHEME_NEWMARK_PC, 1, 0, 0.05, 40, &secs);
    ok &= vu_report(bench, "newmark_pc / MUSL (the force over the step the law's acceleration acts)", q_newmark / q,
                    1.0, q_newmark / q - 1.0, 0.02, secs);
    const double q_lock = limit_pressure(PM_SCHEME_MUSL, 0, 0, 0.05, 40, &secs);
    vu_report(bench, "without F-bar (locking: must fail the 5 % check)", q_lock / prandtl, 1.0, q_lock / prandtl - 1.0,
              -1, secs);
    const double q_points = limit_pressure(PM_SCHEME_MUSL, 1, 1, 0.05, 40, &secs);
    vu_report(bench, "footing acting at the particles (acts_at, not judged)", q_points / prandtl, 1.0,
              q_points / prandtl - 1.0, -1, secs);
    if (!vu_small()) {
        const double q_fine = limit_pressure(PM_SCHEME_MUSL, 1, 0, 0.05, 80, &secs);
        vu_report(bench, "h = B/20 (its edge node held from 12.5 mm on, not judged)", q_fine / prandtl, 1.0,
                  q_fine / prandtl - 1.0, -1, secs);
    }
    return ok ? 0 : 1;
}
