#include "verify_util.h"

#include "io/plot.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

const char *vu_dir = ".";

void vu_init(int argc, char **argv)
{
    if (argc > 1)
        vu_dir = argv[1];
}

int vu_small(void)
{
    static int said;
    const char *e = getenv("PMECH_VERIFY_SMALL");
    const int small = e && *e && strcmp(e, "0") != 0;
    if (small && !said) {
        said = 1;
        printf("PMECH_VERIFY_SMALL: the small variant of this test runs\n");
    }
    return small;
}

void vu_load(const char *rel, pm_case *c)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/../../%s", vu_dir, rel);
    if (pm_case_load(path, c) != PM_OK) {
        fprintf(stderr, "cannot load %s: %s\n", path, pm_error_message());
        exit(2);
    }
}

pm_sim *vu_sim(const pm_case *c, int threads)
{
    pm_sim *s = NULL;
    if (pm_sim_create(c, &s, threads) != PM_OK) {
        fprintf(stderr, "setup failed: %s\n", pm_error_message());
        exit(2);
    }
    return s;
}

double vu_dt(const pm_sim *s)
{
    if (s->c->analysis.dt > 0)
        return s->c->analysis.dt;
    if (s->step == 0 || !(s->max_wave > 0))
        return pm_sim_stable_dt(s);
    return s->c->analysis.cfl * s->grid.h_min / s->max_wave;
}

int vu_advance(pm_sim *s, double end)
{
    if (!(s->t < end - 1e-12))
        return 0;
    double dt = vu_dt(s);
    if (s->t + dt > end)
        dt = end - s->t;
    if (pm_explicit_step(s, dt) != 0) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(1);
    }
    return 1;
}

void vu_run_to(pm_sim *s, double end)
{
    while (vu_advance(s, end))
        ;
}

size_t vu_nearest(const pm_sim *s, double x, double y)
{
    size_t best = 0;
    double bd = INFINITY;
    for (size_t i = 0; i < s->p.n; i++) {
        double dx = s->p.x0[2 * i] - x, dy = s->p.x0[2 * i + 1] - y, d = dx * dx + dy * dy;
        if (d < bd) {
            bd = d;
            best = i;
        }
    }
    return best;
}

size_t vu_track(const pm_sim *s, size_t ip, const double key[2])
{
    if (ip < s->p.n && s->p.x0[2 * ip] == key[0] && s->p.x0[2 * ip + 1] == key[1])
        return ip;
    for (size_t i = 0; i < s->p.n; i++)
        if (s->p.x0[2 * i] == key[0] && s->p.x0[2 * i + 1] == key[1])
            return i;
    fprintf(stderr, "lost the particle that started at (%g, %g)\n", key[0], key[1]);
    exit(1);
}

void vu_body_mean(const pm_sim *s, int b, double v[2], double x[2])
{
    double m = 0;
    v[0] = v[1] = x[0] = x[1] = 0;
    for (size_t i = 0; i < s->p.n; i++) {
        if (s->p.body[i] != b)
            continue;
        double mi = s->p.mass[i];
        m += mi;
        for (int d = 0; d < 2; d++) {
            v[d] += mi * s->p.v[2 * i + d];
            x[d] += mi * s->p.x[2 * i + d];
        }
    }
    for (int d = 0; d < 2; d++) {
        v[d] /= m;
        x[d] /= m;
    }
}

int vu_report(const char *bench, const char *quantity, double value, double ref, double err, double tol,
              double seconds)
{
    int ok = tol < 0 || fabs(err) <= tol;
    char tol_text[32] = "reported";
    if (tol >= 0)
        snprintf(tol_text, sizeof tol_text, "%.3g", tol);
    printf("VERIFY|%s|%s|%.6g|%.6g|%.3g|%s|%.2f|%s\n", bench, quantity, value, ref, err, tol_text, seconds,
           ok ? (tol < 0 ? "REPORT" : "PASS") : "FAIL");
    if (tol >= 0)
        printf("  %s: %s = %.6g, reference %.6g, error %.3g, tolerance %.3g: %s\n", bench, quantity, value, ref,
               err, tol, ok ? "ok" : "FAILED");
    fflush(stdout);
    return ok;
}

double vu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void vu_write_csv(const char *path, const char *header, const double *data, size_t nrow, int ncol)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return;
    fprintf(f, "%s\n", header);
    for (size_t r = 0; r < nrow; r++)
        for (int c = 0; c < ncol; c++)
            fprintf(f, "%.12g%c", data[r * ncol + c], c + 1 < ncol ? ',' : '\n');
    fclose(f);
}

void vu_plot_history(const char *png, const char *title, const char *ylabel, const double *t, const double *v,
                     size_t n, const char *label, const double *ref, const char *ref_label)
{
    pm_plot_series s[2];
    memset(s, 0, sizeof s);
    s[0].x = t;
    s[0].y = v;
    s[0].n = n;
    s[0].label = label;
    size_t ns = 1;
    if (ref) {
        s[1].x = t;
        s[1].y = ref;
        s[1].n = n;
        s[1].label = ref_label;
        s[1].dashed = 1;
        s[1].rgb[0] = 0.2;
        s[1].rgb[1] = 0.2;
        s[1].rgb[2] = 0.2;
        ns = 2;
    }
    pm_plot_opts o;
    memset(&o, 0, sizeof o);
    o.title = title;
    o.xlabel = "time (s)";
    o.ylabel = ylabel;
    o.legend = 1;
    if (pm_plot_lines(png, s, ns, &o) != 0)
        fprintf(stderr, "plot %s: %s\n", png, pm_error_message());
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double vu_deposit_front(const pm_sim *s, double gap, double *xmax)
{
    const size_t n = s->p.n;
    double *xs = malloc(n * sizeof *xs);
    if (!xs || n == 0) {
        free(xs);
        return NAN;
    }
    for (size_t i = 0; i < n; i++)
        xs[i] = s->p.x[2 * i];
    qsort(xs, n, sizeof *xs, by_value);
    double front = xs[0];
    for (size_t i = 1; i < n && xs[i] - front <= gap; i++)
        front = xs[i];
    *xmax = xs[n - 1];
    free(xs);
    return front;
}
