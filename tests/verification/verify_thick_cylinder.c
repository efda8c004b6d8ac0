/*
 * Thick elastic cylinder (Lame), axisymmetric: a ring a = 1 m < r < b = 2 m between rollers on its
 * flat faces (no axial strain), its inner face r = a on the grid boundary pushed out by u_a = 1 mm
 * (velocity 5 mm/s for 0.2 s, twenty wave transits, then held), outer face free; local damping brings
 * it to rest by 0.6 s. Exact: sigma_rr = A - B/r^2, sigma_tt = A + B/r^2, sigma_zz = 2 nu A with
 * B = E u_a / ((1 + nu) ((1 - 2 nu) a / b^2 + 1 / a)), A = B / b^2.
 * Every particle with 1.1 < r0 < 1.9 (away from the faces, where the cell next to a boundary carries
 * a one-sided stress) is compared; the worst error relative to the stress scale B / a^2 must be
 * below 2 % (the benchmark's tolerance; linear quads resolve the 1/r^2 variation to about 1 % with
 * 50 cells over the wall).
 */
#include "verify_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    pm_case c;
    vu_load("tests/verification/cases/thick_cylinder.json", &c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    while (s->t < c.analysis.end_time - 1e-12) {
        double dt = vu_dt(s);
        if (s->t + dt > c.analysis.end_time)
            dt = c.analysis.end_time - s->t;
        if (pm_explicit_step(s, dt) != 0)
            return 1;
    }
    const double secs = vu_now() - t0;
    const pm_material *m = &c.materials[0];
    const double a = 1.0, b = 2.0, ua = 0.005 * 0.2, E = m->E, nu = m->nu;
    const double B = E * ua / ((1 + nu) * ((1 - 2 * nu) * a / (b * b) + 1 / a)), A = B / (b * b);
    const double scale = B / (a * a);
    double worst[3] = {0, 0, 0}, at[3] = {0, 0, 0};
    for (size_t i = 0; i < s->p.n; i++) {
        const double r0 = s->p.x0[2 * i], r = s->p.x[2 * i];
        if (r0 < 1.1 || r0 > 1.9)
            continue;
        const double *sg = s->p.stress + PM_NS * i;
        const double ex[3] = {A - B / (r * r), A + B / (r * r), 2 * nu * A};
        const double got[3] = {sg[PM_SXX], sg[PM_SZZ], sg[PM_SYY]};
        for (int k = 0; k < 3; k++) {
            const double e = (got[k] - ex[k]) / scale;
            if (fabs(e) > fabs(worst[k])) {
                worst[k] = e;
                at[k] = r0;
            }
        }
    }
    size_t inner = vu_nearest(s, 1.0, 0.05);
    const double u_in = s->p.x[2 * inner] - s->p.x0[2 * inner];
    int ok = 1;
    const char *names[3] = {"sigma_rr", "sigma_tt (hoop)", "sigma_zz"};
    for (int k = 0; k < 3; k++) {
        char q[96];
        snprintf(q, sizeof q, "worst %s error / (B/a^2), at r0 = %.3f m", names[k], at[k]);
        ok &= vu_report("thick cylinder", q, worst[k], 0.0, worst[k], 0.02, secs);
    }
    vu_report("thick cylinder", "radial displacement of the innermost particle (m)", u_in, ua, (u_in - ua) / ua, -1,
              secs);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
