/*
 * Axial vibration of an elastic bar fixed at one end (x = 0) and free at x = L, started with a
 * uniform velocity: every mode present has a period 4L/(c (2k-1)), so the motion repeats with the
 * fundamental period 4 L / c, c = sqrt(E / rho) (nu = 0, rollers on the long sides: 1-D).
 * The period is measured from successive downward zero crossings of the free-end velocity over
 * three periods; tolerance 1 % (linear MPM with 100 cells has a dispersion error far below that).
 */
#include "verify_util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static double measure(pm_case *c, double *secs)
{
    const double L = 1.0;
    const double cw = sqrt(c->materials[0].E / c->materials[0].density), T = 4 * L / cw;
    c->analysis.end_time = 3.3 * T;
    const double t0 = vu_now();
    pm_sim *s = vu_sim(c, 1);
    size_t ip = vu_nearest(s, L, 0.005);
    const double key[2] = {s->p.x0[2 * ip], s->p.x0[2 * ip + 1]};
    double crossings[16];
    int nc = 0;
    double tp = 0, vp = s->p.v[2 * ip];
    while (s->t < c->analysis.end_time) {
        if (pm_explicit_step(s, vu_dt(s)) != 0)
            return NAN;
        ip = vu_track(s, ip, key);
        double v = s->p.v[2 * ip];
        if (vp > 0 && v <= 0 && nc < 16)
            crossings[nc++] = tp + (s->t - tp) * vp / (vp - v);
        tp = s->t;
        vp = v;
    }
    *secs = vu_now() - t0;
    pm_sim_destroy(s);
    if (nc < 2)
        return NAN;
    return (crossings[nc - 1] - crossings[0]) / (nc - 1);
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = 1;
    const char *scheme_names[] = {"musl", "usl", "usf", "newmark_pc"};
    const pm_scheme schemes[] = {PM_SCHEME_MUSL, PM_SCHEME_USL, PM_SCHEME_USF, PM_SCHEME_NEWMARK_PC};
    for (int k = 0; k < 4; k++) {
        pm_case c;
        vu_load("tests/verification/cases/vibrating_bar.json", &c);
        c.analysis.scheme = schemes[k];
        const double T = 4.0 / sqrt(c.materials[0].E / c.materials[0].density);
        double secs = 0;
        const double P = measure(&c, &secs);
        char q[64];
        snprintf(q, sizeof q, "period (s), %s", scheme_names[k]);
        ok &= vu_report("vibrating bar", q, P, T, (P - T) / T, 0.01, secs);
        pm_case_free(&c);
    }
    return ok ? 0 : 1;
}
