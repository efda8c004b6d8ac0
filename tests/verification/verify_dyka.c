/*
 * Dyka bar (seed 003 section 3.1): elastic bar fixed at x = L, free at
 * x = 0, uniform initial velocity v0. The free end's velocity is a square wave: v0 for t < L/c,
 * -v0 for L/c < t < 3L/c, period 4L/c, c = sqrt(E/rho).
 *
 * v0 = -0.1 m/s: no particle crosses a cell boundary, so linear MPM is a finite-element solution with
 * particle quadrature; Gibbs ringing follows each jump, so plateau means are taken away from the
 * jumps (0.25 L/c margins) and must be within 2 % of +-v0 for two periods (five plateaus, to 9 L/c).
 * The pointwise deviation inside the same windows is reported per plateau and its largest value is
 * judged within 50 % of |v0|: measured 21, 28, 34, 42 % (MUSL) on plateaus 2 to 5, the ringing of the
 * linear grid's dispersion, which spreads every jump further the longer the wave has travelled (the
 * plateau means stay within 0.5 %). 50 % is not a bound the discretisation has to meet by theory but
 * the line a wrong answer crosses: a jump that arrives 0.25 L/c early or late (wave speed 3 % off at
 * 9 L/c), a reflection of the wrong sign or a lost one puts a deviation of 2 |v0| inside a window.
 * v0 = -5 m/s: the free end crosses cells and linear MPM is noisy (seed 003 Fig. 6). The RMS error
 * over two periods is reported for three grid sizes; it does not fall with h (the noise comes from
 * every crossing, and finer grids have more of them). It is judged only against a loose bound (50 %
 * of |v0|; a missing reflection or a wrong wave speed gives 100 % or more).
 */
#include "verify_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Largest pointwise deviation from the square wave allowed inside the plateau windows (see the top). */
#define RINGING_TOL 0.5

static double exact(double t, double v0, double T1)
{
    double ph = fmod(t / T1 + 1.0, 4.0); /* the square wave starts at -T1 in phase units */
    return ph < 2.0 ? v0 : -v0;
}

typedef struct history {
    size_t n, cap;
    double *tv; /* t, v pairs */
} history;

static void push(history *h, double t, double v)
{
    if (h->n == h->cap) {
        h->cap = h->cap ? 2 * h->cap : 4096;
        h->tv = realloc(h->tv, 2 * h->cap * sizeof(double));
    }
    h->tv[2 * h->n] = t;
    h->tv[2 * h->n + 1] = v;
    h->n++;
}

static void plot(const history *h, double v0, double T1, const char *png, const char *title)
{
    double *t = malloc(h->n * sizeof(double)), *v = malloc(h->n * sizeof(double)), *e = malloc(h->n * sizeof(double));
    for (size_t i = 0; i < h->n; i++) {
        t[i] = h->tv[2 * i];
        v[i] = h->tv[2 * i + 1];
        e[i] = exact(t[i], v0, T1);
    }
    vu_plot_history(png, title, "free-end velocity (m/s)", t, v, h->n, "pmech", e, "exact");
    free(t);
    free(v);
    free(e);
}

static history run(double v0, int cells_x, const char *scheme, double *seconds)
{
    pm_case c;
    vu_load("examples/dyka_bar/case.json", &c);
    c.bodies[0].velocity[0] = v0;
    c.grid.cells[0] = cells_x;
    if (scheme && scheme[0] == 'n')
        c.analysis.scheme = PM_SCHEME_NEWMARK_PC;
    const double cw = sqrt(c.materials[0].E / c.materials[0].density), T1 = 1.0 / cw;
    c.analysis.end_time = 9 * T1;
    double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    size_t ip = vu_nearest(s, 0.0, 0.005);
    const double key[2] = {s->p.x0[2 * ip], s->p.x0[2 * ip + 1]};
    history h = {0};
    push(&h, 0, s->p.v[2 * ip]);
    while (s->t < c.analysis.end_time) {
        if (pm_explicit_step(s, vu_dt(s)) != 0) {
            fprintf(stderr, "step failed\n");
            exit(1);
        }
        ip = vu_track(s, ip, key);
        push(&h, s->t, s->p.v[2 * ip]);
    }
    *seconds = vu_now() - t0;
    pm_sim_destroy(s);
    pm_case_free(&c);
    return h;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = 1;
    const double T1 = 1.0 / sqrt(1e8 / 1000.0);
    const char *schemes[] = {"musl", "newmark_pc"};
    for (int sc = 0; sc < 2; sc++) {
        double secs;
        const double v0 = -0.1;
        history h = run(v0, 110, schemes[sc], &secs);
        char name[64];
        snprintf(name, sizeof name, "dyka_slow_%s.csv", schemes[sc]);
        vu_write_csv(name, "time,velocity", h.tv, h.n, 2);
        snprintf(name, sizeof name, "dyka_slow_%s.png", schemes[sc]);
        char title[96];
        snprintf(title, sizeof title, "Dyka bar, v0 = -0.1 m/s, h = 0.01 m, %s", schemes[sc]);
        plot(&h, v0, T1, name, title);
        /* plateaus [k T1 + margin, (k + 2) T1 - margin], the first one starting at 0 */
        const double lo[5] = {0.0, 1.0, 3.0, 5.0, 7.0}, hi[5] = {1.0, 3.0, 5.0, 7.0, 9.0};
        double worst = 0, late = 0;
        for (int k = 0; k < 5; k++) {
            double sum = 0, dev = 0;
            int cnt = 0;
            for (size_t i = 0; i < h.n; i++) {
                double t = h.tv[2 * i] / T1;
                if (t > lo[k] + (k ? 0.25 : 0.05) && t < hi[k] - 0.25) {
                    sum += h.tv[2 * i + 1];
                    dev = fmax(dev, fabs(h.tv[2 * i + 1] - exact(h.tv[2 * i], v0, T1)) / fabs(v0));
                    cnt++;
                }
            }
            double mean = sum / cnt, ref = (k % 2 == 0) ? v0 : -v0;
            char q[96];
            snprintf(q, sizeof q, "%s plateau %d mean v (m/s), v0=-0.1", schemes[sc], k + 1);
            ok &= vu_report("Dyka bar", q, mean, ref, (mean - ref) / fabs(v0), 0.02, secs);
            snprintf(q, sizeof q, "%s plateau %d largest pointwise abs(v - exact) / abs(v0)", schemes[sc], k + 1);
            vu_report("Dyka bar", q, dev, 0, dev, -1, 0);
            worst = fmax(worst, dev);
            if (k >= 3)
                late = fmax(late, dev);
        }
        char q[112];
        snprintf(q, sizeof q, "%s largest pointwise ringing / abs(v0), plateaus 1-5", schemes[sc]);
        ok &= vu_report("Dyka bar", q, worst, 0, worst, RINGING_TOL, 0);
        snprintf(q, sizeof q, "%s largest pointwise ringing / abs(v0), plateaus 4-5", schemes[sc]);
        vu_report("Dyka bar", q, late, 0, late, -1, 0);
        free(h.tv);
    }
    const int cells[3] = {55, 110, 220};
    for (int g = 0; g < 3; g++) {
        double secs;
        const double v0 = -5.0;
        history h = run(v0, cells[g], "musl", &secs);
        char name[64];
        snprintf(name, sizeof name, "dyka_fast_h%d.csv", cells[g]);
        vu_write_csv(name, "time,velocity", h.tv, h.n, 2);
        snprintf(name, sizeof name, "dyka_fast_h%d.png", cells[g]);
        char title[96];
        snprintf(title, sizeof title, "Dyka bar, v0 = -5 m/s, h = %.3g m, musl, linear", 1.1 / cells[g]);
        plot(&h, v0, T1, name, title);
        double se = 0, st = 0;
        for (size_t i = 1; i < h.n && h.tv[2 * i] <= 8 * T1; i++) {
            double dt = h.tv[2 * i] - h.tv[2 * i - 2];
            double e = h.tv[2 * i + 1] - exact(h.tv[2 * i], v0, T1);
            se += e * e * dt;
            st += dt;
        }
        double rms = sqrt(se / st) / fabs(v0);
        char q[96];
        snprintf(q, sizeof q, "RMS error / abs(v0), v0=-5, h=%.4g m, musl", 1.1 / cells[g]);
        ok &= vu_report("Dyka bar", q, rms, 0.0, rms, 0.5, secs);
        free(h.tv);
    }
    return ok ? 0 : 1;
}
