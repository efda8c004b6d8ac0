/*
 * Implicit MPM (Newmark, beta = 1/4, gamma = 1/2; analysis.type "implicit") with steps far above the
 * explicit stability limit dt_crit = h / c (linear elements, lumped mass, c = sqrt(E / rho)) on two
 * elastic bars (nu = 0, rollers on the long sides: 1-D):
 *
 * Vibrating bar (tests/verification/cases/implicit_vibrating_bar.json; steel, L = 1 m, h = 0.01 m,
 * fixed at x = 0, free at x = L, started with v0 = 0.01 m/s): every mode has a period 4L/(c (2k-1)),
 * so the free end's displacement is a triangle wave of period T = 4L/c. Run at dt = 5, 10 and 20 x
 * dt_crit (T / dt = 80, 40, 20) for 3.3 T. Judged:
 *  - the period, from the zero crossings of the free-end displacement over three periods, within 2 %
 *    of 4L/c (the tolerance; the trapezoidal rule lengthens the fundamental period by
 *    (w dt)^2 / 12 = 0.05 / 0.2 / 0.8 %);
 *  - energy does not grow: max over the run of (E(t) - E0) / E0 <= 1e-3, E = kinetic + strain
 *    energy of the particles, E0 = m v0^2 / 2 (Newmark's trapezoidal rule conserves the energy of a
 *    linear system exactly; 1e-3 leaves room for the particle quadrature of the strain energy and the
 *    Newton tolerance). The drift at the end is reported.
 * The displacement is used rather than the velocity (as in verify_vibration.c) because the velocity is
 * a square wave whose jumps the trapezoidal rule cannot resolve at these steps (its highest modes
 * ring without damping), so its zero crossings are ragged; the displacement's mode amplitudes fall as
 * 1/(2k-1)^2 and its crossings are clean.
 *
 * Dyka bar (cases/implicit_dyka_bar.json; L = 1 m, E = 100 MPa, rho = 1000, h = 0.01 m, fixed at
 * x = L, free at x = 0, v0 = -5 m/s, so the free end crosses cells) at dt = 10 x dt_crit
 * (10 steps per L/c), to 9 L/c. A wave problem: a step of L/(10 c) smears the velocity jumps over
 * several steps, so the free-end velocity is not judged (it is plotted). What the large step must keep,
 * and is judged:
 *  - the momentum: the bar's mean velocity (the reaction's impulse) is the triangle wave
 *    v0 (1 - ph) for ph in [0, 2], v0 (ph - 3) for ph in [2, 4], ph = t c / L mod 4. Its RMS error
 *    over 9 L/c is judged only against a loose bound, 25 % of |v0|: a bar that loses a reflection or
 *    comes to rest gives 58 % or more (the RMS of the unit triangle wave is 1/sqrt(3)). It is not small:
 *    at 10 steps per L/c the trapezoidal rule puts the high modes of the kinks out of phase (5 % on
 *    the v0 = -0.1 m/s bar, where nothing crosses a cell), and the cell crossings dissipate energy,
 *    which rounds the peaks (measured by a scan over dt: 3.5 % at dt_crit, 8 % at 10 dt_crit, 13 %
 *    at 20 dt_crit; explicit MUSL 3.3 %);
 *  - its period, from the zero crossings of the mean velocity (at L/c, 3L/c, ...), within 2 % of 4L/c;
 *  - stability and energy: every particle speed stays below 2 |v0| (the exact solution never exceeds
 *    |v0|; an unstable scheme grows without bound), and the total energy does not grow by more than
 *    1e-3 of E0. Its loss is reported: the cell crossings dissipate (E/E0 = 0.87 at 9 L/c already
 *    at dt = dt_crit, 0.74 at 10 dt_crit; explicit MUSL 0.98); on the same bar at v0 = -0.1 m/s,
 *    where no point crosses, 2.5 %.
 */
#include "verify_util.h"

#include "pmech/error.h"
#include "solver/implicit.h"
#include "solver/sim_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct series {
    size_t n, cap;
    double *row; /* t, tip displacement, tip velocity, mean velocity, energy / E0 */
} series;

#define NCOL 5

static void push(series *h, const double r[NCOL])
{
    if (h->n == h->cap) {
        h->cap = h->cap ? 2 * h->cap : 1024;
        h->row = realloc(h->row, NCOL * h->cap * sizeof(double));
    }
    for (int k = 0; k < NCOL; k++)
        h->row[NCOL * h->n + k] = r[k];
    h->n++;
}

typedef struct outcome {
    series h;
    double secs, vmax, e0;
    long steps;
    int iterations, cuts;
    double assemble, solve;
} outcome;

static void sample(const pm_sim *s, size_t ip, double e0, series *h)
{
    double ke, se, ge, v[2], x[2];
    pm_sim_energy(s, &ke, &se, &ge);
    vu_body_mean(s, 0, v, x);
    const double r[NCOL] = {s->t, s->p.x[2 * ip] - s->p.x0[2 * ip], s->p.v[2 * ip], v[0], (ke + se) / e0};
    push(h, r);
}

/* Run @p c with fixed steps dt, sampling the particle nearest to (xt, 0.005). */
static outcome run(pm_case *c, double dt, double xt)
{
    outcome o = {0};
    c->analysis.dt = dt;
    const double t0 = vu_now();
    pm_sim *s = vu_sim(c, 1);
    size_t ip = vu_nearest(s, xt, 0.005);
    const double key[2] = {s->p.x0[2 * ip], s->p.x0[2 * ip + 1]};
    double ke, se, ge;
    pm_sim_energy(s, &ke, &se, &ge);
    o.e0 = ke + se;
    sample(s, ip, o.e0, &o.h);
    while (s->t < c->analysis.end_time - 1e-9 * dt) {
        pm_implicit_report rep;
        if (pm_implicit_step(s, dt, NULL, &rep) != 0) {
            fprintf(stderr, "implicit step failed: %s\n", pm_error_message());
            exit(1);
        }
        o.steps++;
        o.iterations += rep.iterations;
        o.cuts += rep.step_cuts;
        o.assemble += rep.assemble_seconds;
        o.solve += rep.solve_seconds;
        ip = vu_track(s, ip, key);
        sample(s, ip, o.e0, &o.h);
        for (size_t i = 0; i < s->p.n; i++)
            o.vmax = fmax(o.vmax, hypot(s->p.v[2 * i], s->p.v[2 * i + 1]));
    }
    o.secs = vu_now() - t0;
    pm_sim_destroy(s);
    return o;
}

/* Mean spacing of same-direction zero crossings of column col (after t > tmin): the period. */
static double period_from_crossings(const series *h, int col, double tmin)
{
    double first = NAN, last = NAN;
    int n = 0;
    for (size_t i = 1; i < h->n; i++) {
        const double *a = h->row + NCOL * (i - 1), *b = h->row + NCOL * i;
        if (a[0] < tmin || !((a[col] > 0 && b[col] <= 0) || (a[col] < 0 && b[col] >= 0)))
            continue;
        const double tc = a[0] + (b[0] - a[0]) * a[col] / (a[col] - b[col]);
        if (n == 0)
            first = tc;
        last = tc;
        n++;
    }
    return n >= 3 ? 2 * (last - first) / (n - 1) : NAN; /* crossings alternate: half a period apart */
}

static double max_energy_growth(const series *h)
{
    double g = -INFINITY;
    for (size_t i = 0; i < h->n; i++)
        g = fmax(g, h->row[NCOL * i + 4] - 1.0);
    return g;
}

static void perf_line(const char *name, const outcome *o, size_t particles)
{
    printf("PERF|%s|%zu|%ld|%.4g|%.2f|%.4g|%.4g|%d\n", name, particles, o->steps, o->secs / o->steps,
           (double)o->iterations / o->steps, o->assemble / o->steps, o->solve / o->steps, o->cuts);
}

static double tri(double t, double T1)
{
    const double ph = fmod(t / T1, 4.0);
    return ph <= 2.0 ? 1.0 - ph : ph - 3.0;
}

/* Plot column col of the history against the exact triangle wave scale * tri(t + shift, T1). */
static void plot_against_wave(const char *png, const char *title, const char *ylabel, const series *h, int col,
                              double scale, double shift, double T1)
{
    double *t = malloc(h->n * sizeof(double)), *y = malloc(h->n * sizeof(double)), *e = malloc(h->n * sizeof(double));
    if (t && y && e) {
        for (size_t i = 0; i < h->n; i++) {
            t[i] = h->row[NCOL * i];
            y[i] = h->row[NCOL * i + col];
            e[i] = scale * tri(t[i] + shift, T1);
        }
        vu_plot_history(png, title, ylabel, t, y, h->n, "pmech", e, "exact");
    }
    free(t);
    free(y);
    free(e);
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = 1;
    /* vibrating bar */
    const double factors[3] = {5, 10, 20};
    for (int k = 0; k < 3; k++) {
        pm_case c;
        vu_load("tests/verification/cases/implicit_vibrating_bar.json", &c);
        const double cw = sqrt(c.materials[0].E / c.materials[0].density), T = 4.0 / cw;
        const double h = c.grid.size[0] / c.grid.cells[0], dt = factors[k] * h / cw;
        c.analysis.end_time = 3.3 * T;
        outcome o = run(&c, dt, 1.0);
        const double P = period_from_crossings(&o.h, 1, 0.25 * T);
        char q[96];
        snprintf(q, sizeof q, "period (s), implicit, dt = %g dt_crit (T/dt = %.0f)", factors[k], T / dt);
        ok &= vu_report("vibrating bar", q, P, T, (P - T) / T, 0.02, o.secs);
        const double g = max_energy_growth(&o.h), drift = o.h.row[NCOL * (o.h.n - 1) + 4] - 1.0;
        snprintf(q, sizeof q, "energy growth max (E-E0)/E0, dt = %g dt_crit", factors[k]);
        ok &= vu_report("vibrating bar", q, g, 0.0, g, 1e-3, o.secs);
        snprintf(q, sizeof q, "energy drift at 3.3 T (E-E0)/E0, dt = %g dt_crit", factors[k]);
        vu_report("vibrating bar", q, drift, 0.0, drift, -1, o.secs);
        printf("vibrating bar dt = %g dt_crit: %ld steps, %.2f Newton iterations per step, %d cuts\n", factors[k],
               o.steps, (double)o.iterations / o.steps, o.cuts);
        if (k == 1) {
            perf_line("vibrating bar, implicit, dt = 10 dt_crit", &o, 400);
            vu_write_csv("implicit_vibration_dt10.csv", "time,tip_displacement,tip_velocity,mean_velocity,energy_ratio",
                         o.h.row, o.h.n, NCOL);
            const double amp = c.bodies[0].velocity[0] * T / 4; /* triangle wave 0 -> amp at T/4 */
            plot_against_wave("implicit_vibration_dt10.png", "Vibrating bar, implicit, dt = 10 dt_crit",
                              "free-end displacement (m)", &o.h, 1, -amp, T / 4, T / 4);
        }
        free(o.h.row);
        pm_case_free(&c);
    }
    /* Dyka bar */
    {
        pm_case c;
        vu_load("tests/verification/cases/implicit_dyka_bar.json", &c);
        const double cw = sqrt(c.materials[0].E / c.materials[0].density), T1 = 1.0 / cw;
        const double h = c.grid.size[0] / c.grid.cells[0], dt = 10 * h / cw, v0 = c.bodies[0].velocity[0];
        c.analysis.end_time = 9 * T1;
        outcome o = run(&c, dt, 0.0);
        double se = 0, st = 0;
        for (size_t i = 1; i < o.h.n; i++) {
            const double *a = o.h.row + NCOL * (i - 1), *b = o.h.row + NCOL * i;
            const double ea = a[3] - v0 * tri(a[0], T1), eb = b[3] - v0 * tri(b[0], T1);
            se += 0.5 * (ea * ea + eb * eb) * (b[0] - a[0]);
            st += b[0] - a[0];
        }
        const double rms = sqrt(se / st) / fabs(v0);
        ok &= vu_report("Dyka bar", "mean velocity RMS error / abs(v0), implicit, v0=-5, dt = 10 dt_crit", rms, 0.0,
                        rms, 0.25, o.secs);
        const double P = period_from_crossings(&o.h, 3, 0.5 * T1);
        ok &= vu_report("Dyka bar", "mean-velocity period (s), implicit, dt = 10 dt_crit", P, 4 * T1,
                        (P - 4 * T1) / (4 * T1), 0.02, o.secs);
        const double vr = o.vmax / fabs(v0);
        ok &= vu_report("Dyka bar", "largest particle speed / abs(v0), implicit, dt = 10 dt_crit", vr, 1.0, vr - 1.0,
                        1.0, o.secs);
        const double g = max_energy_growth(&o.h), drift = o.h.row[NCOL * (o.h.n - 1) + 4] - 1.0;
        ok &= vu_report("Dyka bar", "energy growth max (E-E0)/E0, implicit, dt = 10 dt_crit", g, 0.0, g, 1e-3, o.secs);
        vu_report("Dyka bar", "energy drift at 9 L/c (E-E0)/E0, implicit, dt = 10 dt_crit", drift, 0.0, drift, -1,
                  o.secs);
        printf("Dyka bar dt = 10 dt_crit: %ld steps, %.2f Newton iterations per step, %d cuts\n", o.steps,
               (double)o.iterations / o.steps, o.cuts);
        perf_line("Dyka bar v0 = -5, implicit, dt = 10 dt_crit", &o, 400);
        vu_write_csv("implicit_dyka.csv", "time,free_end_displacement,free_end_velocity,mean_velocity,energy_ratio",
                     o.h.row, o.h.n, NCOL);
        plot_against_wave("implicit_dyka_mean_velocity.png", "Dyka bar, v0 = -5 m/s, implicit, dt = 10 dt_crit",
                          "mean velocity (m/s)", &o.h, 3, v0, 0.0, T1);
        free(o.h.row);
        pm_case_free(&c);
    }
    return ok ? 0 : 1;
}
