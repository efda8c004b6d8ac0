/*
 * Shape functions compared (seed 003 Fig. 6): the Dyka bar (examples/dyka_bar, v0 = -5 m/s where
 * the free end crosses cells, and v0 = -0.1 m/s where nothing crosses) and the colliding elastic
 * disks (examples/elastic_disks) run with each approximation: linear, gimp, bspline2, lme (default
 * gamma 1.8). Reported per shape function:
 *   Dyka: RMS over two periods (to 8 L/c) of the free end's velocity minus the exact square wave,
 *         divided by |v0|. The Gibbs ringing after each jump dominates it for every scheme (about
 *         0.2 even without cell crossing), so the RMS over the plateaus only (0.25 L/c away from
 *         each jump) is reported as well: that one shows the cell-crossing noise.
 *   Disks: max over the run of |E(t) - E0| / E0 with E = kinetic + strain energy.
 * Bounds are loose (a missing reflection or wrong wave speed gives an RMS of 1 or more, a blow-up
 * an energy error far above 10 %): they catch broken approximations, not rank them. The ranking is
 * the reported numbers.
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const shapes[] = {"linear", "gimp", "bspline2", "lme"};
#define N_SHAPES 4

static double exact(double t, double v0, double T1)
{
    double ph = fmod(t / T1 + 1.0, 4.0);
    return ph < 2.0 ? v0 : -v0;
}

static void set_shape(pm_case *c, const char *shape)
{
    snprintf(c->shape_function, sizeof c->shape_function, "%s", shape);
}

/* Away from the jumps at T1, 3 T1, 5 T1, 7 T1 (0.25 T1 margins), where every scheme rings. */
static int on_plateau(double t, double T1)
{
    double u = t / T1;
    for (int k = 1; k <= 7; k += 2)
        if (fabs(u - k) < 0.25)
            return 0;
    return 1;
}

/* RMS of (v - exact) / |v0| over [0, 8 T1] (and over the plateaus into *plateau); also writes the
 * history. */
static double dyka(const char *shape, double v0, double *plateau, double *seconds)
{
    pm_case c;
    vu_load("examples/dyka_bar/case.json", &c);
    set_shape(&c, shape);
    c.bodies[0].velocity[0] = v0;
    const double cw = sqrt(c.materials[0].E / c.materials[0].density), T1 = 1.0 / cw;
    c.analysis.end_time = 8 * T1;
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    size_t ip = vu_nearest(s, 0.0, 0.005);
    size_t cap = 1 << 14, n = 0;
    double *tv = malloc(2 * cap * sizeof(double));
    double se = 0, st = 0, t_prev = 0, e_prev = 0, pe = 0, pt = 0;
    *plateau = INFINITY;
    tv[0] = 0;
    tv[1] = s->p.v[2 * ip];
    n = 1;
    while (s->t < c.analysis.end_time) {
        if (pm_explicit_step(s, vu_dt(s)) != 0) {
            fprintf(stderr, "%s: Dyka step failed at t = %g: %s\n", shape, s->t, pm_error_message());
            *seconds = vu_now() - t0;
            pm_sim_destroy(s);
            pm_case_free(&c);
            free(tv);
            return INFINITY;
        }
        double e = s->p.v[2 * ip] - exact(s->t, v0, T1);
        se += 0.5 * (e * e + e_prev * e_prev) * (s->t - t_prev);
        st += s->t - t_prev;
        if (on_plateau(s->t, T1) && on_plateau(t_prev, T1)) {
            pe += 0.5 * (e * e + e_prev * e_prev) * (s->t - t_prev);
            pt += s->t - t_prev;
        }
        t_prev = s->t;
        e_prev = e;
        if (n == cap) {
            cap *= 2;
            double *grown = realloc(tv, 2 * cap * sizeof(double));
            if (!grown)
                abort();
            tv = grown;
        }
        tv[2 * n] = s->t;
        tv[2 * n + 1] = s->p.v[2 * ip];
        n++;
    }
    *seconds = vu_now() - t0;
    char name[96], title[128];
    snprintf(name, sizeof name, "shape_compare_dyka_%s_v%g.csv", shape, fabs(v0));
    vu_write_csv(name, "time,velocity", tv, n, 2);
    double *t = malloc(n * sizeof(double)), *v = malloc(n * sizeof(double)), *ex = malloc(n * sizeof(double));
    for (size_t i = 0; i < n; i++) {
        t[i] = tv[2 * i];
        v[i] = tv[2 * i + 1];
        ex[i] = exact(t[i], v0, T1);
    }
    snprintf(name, sizeof name, "shape_compare_dyka_%s_v%g.png", shape, fabs(v0));
    snprintf(title, sizeof title, "Dyka bar, v0 = %g m/s, h = 0.01 m, musl, %s", v0, shape);
    vu_plot_history(name, title, "free-end velocity (m/s)", t, v, n, shape, ex, "exact");
    free(t);
    free(v);
    free(ex);
    free(tv);
    pm_sim_destroy(s);
    pm_case_free(&c);
    *plateau = sqrt(pe / pt) / fabs(v0);
    return sqrt(se / st) / fabs(v0);
}

/* Max |E(t) - E0| / E0 of the colliding disks; *rebound receives the lower disk's final diagonal
 * velocity over its initial one (about -1 after a clean bounce). */
static double disks(const char *shape, double *rebound, double *seconds)
{
    pm_case c;
    vu_load("examples/elastic_disks/case.json", &c);
    set_shape(&c, shape);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    double ke, se, ge;
    pm_sim_energy(s, &ke, &se, &ge);
    const double e0 = ke + se;
    double worst = 0;
    while (s->t < c.analysis.end_time - 1e-12) {
        double dt = vu_dt(s);
        if (s->t + dt > c.analysis.end_time)
            dt = c.analysis.end_time - s->t;
        if (pm_explicit_step(s, dt) != 0) {
            fprintf(stderr, "%s: disks step failed at t = %g: %s\n", shape, s->t, pm_error_message());
            worst = INFINITY;
            break;
        }
        pm_sim_energy(s, &ke, &se, &ge);
        double dev = (ke + se - e0) / e0;
        if (fabs(dev) > fabs(worst))
            worst = dev;
    }
    double v[2], x[2];
    vu_body_mean(s, 0, v, x);
    *rebound = (v[0] + v[1]) / (0.2);
    *seconds = vu_now() - t0;
    pm_sim_destroy(s);
    pm_case_free(&c);
    return worst;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = 1;
    const double v0s[2] = {-5.0, -0.1};
    for (int k = 0; k < N_SHAPES; k++)
        for (int m = 0; m < 2; m++) {
            double secs, plat;
            double rms = dyka(shapes[k], v0s[m], &plat, &secs);
            char q[128];
            snprintf(q, sizeof q, "RMS error / abs(v0), v0=%g, h=0.01 m, musl, %s", v0s[m], shapes[k]);
            ok &= vu_report("Dyka bar (shape functions)", q, rms, 0.0, rms, 0.5, secs);
            snprintf(q, sizeof q, "plateau RMS error / abs(v0) (0.25 L/c from jumps), v0=%g, %s", v0s[m], shapes[k]);
            ok &= vu_report("Dyka bar (shape functions)", q, plat, 0.0, plat, 0.5, secs);
        }
    for (int k = 0; k < N_SHAPES; k++) {
        double secs, rebound;
        double err = disks(shapes[k], &rebound, &secs);
        char q[128];
        snprintf(q, sizeof q, "max abs(E(t) - E0) / E0, musl, %s", shapes[k]);
        ok &= vu_report("elastic disks (shape functions)", q, err, 0.0, err, 0.10, secs);
        snprintf(q, sizeof q, "lower disk rebound velocity / initial, %s", shapes[k]);
        vu_report("elastic disks (shape functions)", q, rebound, -1.0, rebound + 1.0, -1, secs);
    }
    return ok ? 0 : 1;
}
