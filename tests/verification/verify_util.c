#include "verify_util.h"

#include "contact/contact.h"
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

/* One explicit step of vu_dt towards @p end, clipped to it; the step's status. */
static int step_towards(pm_sim *s, double end)
{
    double dt = vu_dt(s);
    if (s->t + dt > end)
        dt = end - s->t;
    return pm_explicit_step(s, dt);
}

int vu_advance(pm_sim *s, double end)
{
    if (!(s->t < end - 1e-12))
        return 0;
    if (step_towards(s, end) != PM_OK) {
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

int vu_steps_until(pm_sim *s, double end, double mark)
{
    while (s->t < end - 1e-12 && s->t < mark) {
        const int rc = step_towards(s, end);
        if (rc != PM_OK)
            return rc;
    }
    return PM_OK;
}

int vu_run_each(pm_sim *s, double end, int (*each)(pm_sim *s, void *ctx), void *ctx)
{
    while (s->t < end - 1e-12) {
        if (step_towards(s, end) != PM_OK) {
            fprintf(stderr, "step failed: %s\n", pm_error_message());
            return 0;
        }
        if (each && !each(s, ctx))
            return 0;
    }
    return 1;
}

void vu_slope_block(double theta_deg, double y0, double s0, double width, double height, double q[4][PM_DIM])
{
    const double th = theta_deg * M_PI / 180.0;
    const double e[PM_DIM] = {cos(th), -sin(th)}, n[PM_DIM] = {sin(th), cos(th)};
    for (int k = 0; k < 4; k++) {
        const double a = (k == 1 || k == 2) ? width : 0.0, b = k >= 2 ? height : 0.0;
        for (int d = 0; d < PM_DIM; d++)
            q[k][d] = (d ? y0 : 0.0) + s0 * e[d] + a * e[d] + b * n[d];
    }
}

void vu_gmsh_incline_case(const char *dir, int deg, const char *method, double t_end, double g, double mu,
                          pm_case *c)
{
    double q[4][PM_DIM];
    vu_slope_block(deg, 0.4, 0.1, 0.2, 0.06, q);
    char how[96] = "", text[4096], path[1024];
    if (method)
        snprintf(how, sizeof how, "\"method\": \"%s\", \"shape_function\": \"%s\",", method,
                 strcmp(method, "rkpm") ? "mls" : "rk_cubic");
    snprintf(text, sizeof text,
             "{ \"dimension\": 2, %s \"analysis\": { \"type\": \"explicit\", \"scheme\": \"musl\","
             "  \"end_time\": %g, \"cfl\": 0.3, \"gravity\": [0, %g] },"
             "  \"grid\": { \"type\": \"gmsh\", \"file\": \"gmsh_incline%d.msh\" },"
             "  \"materials\": [ { \"name\": \"block\", \"model\": \"linear_elastic\", \"density\": 1000,"
             "                   \"youngs_modulus\": 1.0e7, \"poisson_ratio\": 0.3 } ],"
             "  \"bodies\": [ { \"name\": \"block\", \"material\": \"block\", \"particles_per_cell\": 2,"
             "    \"shape\": { \"type\": \"polygon\", \"points\": [[%.9g, %.9g], [%.9g, %.9g], [%.9g, %.9g], [%.9g, %.9g]] } } ],"
             "  \"boundary_conditions\": [ { \"type\": \"friction\", \"boundary\": \"slope\", \"coefficient\": %g } ] }",
             how, t_end, -g, deg, q[0][0], q[0][1], q[1][0], q[1][1], q[2][0], q[2][1], q[3][0], q[3][1], mu);
    snprintf(path, sizeof path, "%s/cases/gmsh_incline.json", dir);
    if (pm_case_load_buffer(text, strlen(text), path, c) != PM_OK) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(2);
    }
}

vu_slope vu_slope_run(const pm_case *c, double theta_deg, pm_contact_kind kind, const char *label)
{
    const double th = theta_deg * M_PI / 180.0, e[PM_DIM] = {cos(th), -sin(th)}, end = c->analysis.end_time;
    const double t0 = vu_now();
    pm_sim *s = vu_sim(c, 1);
    if (s->contact->n_surfaces != 1 || s->contact->surface[0].kind != kind) {
        fprintf(stderr, "%s: the slope is not the case's one contact surface of kind %d\n", label, (int)kind);
        exit(1);
    }
    pm_contact_force *J = &s->contact->surface[0].impulse;
    double v[PM_DIM], x0[PM_DIM], x[PM_DIM], t_reset = 0;
    vu_body_mean(s, 0, v, x0);
    vu_slope r = {.ok = vu_steps_until(s, end, 0.5 * end) == PM_OK};
    if (r.ok && s->t < end - 1e-12) {
        memset(J, 0, sizeof *J);
        t_reset = s->t;
        r.ok = vu_steps_until(s, end, end) == PM_OK;
    }
    if (!r.ok)
        fprintf(stderr, "%s: %s\n", label, pm_error_message());
    vu_body_mean(s, 0, v, x);
    double tangent2 = 0;
    for (int d = 0; d < PM_DIM; d++) {
        r.v_along += v[d] * e[d];
        r.travel += (x[d] - x0[d]) * e[d];
        tangent2 += J->tangent[d] * J->tangent[d];
    }
    r.force[0] = J->normal / (s->t - t_reset);
    r.force[1] = sqrt(tangent2) / (s->t - t_reset);
    r.secs = vu_now() - t0;
    pm_sim_destroy(s);
    return r;
}

pm_sim *vu_run_profiled(const char *rel, pm_case *c, double window, double *t_from, double *secs)
{
    vu_load(rel, c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(c, 1);
    vu_run_to(s, c->analysis.end_time - window);
    pm_contact_profile_reset(s->contact);
    *t_from = s->t;
    vu_run_to(s, c->analysis.end_time);
    *secs = vu_now() - t0;
    return s;
}

/* One run of the sliding block: body 0's mean velocity at the end and its centre of mass's travel. */
static void slide(const char *rel, double mu, double ramp, vu_runner run, double v[PM_DIM], double dx[PM_DIM],
                  double *secs)
{
    pm_case c;
    vu_load(rel, &c);
    c.bcs[0].coefficient = mu;
    c.analysis.gravity_ramp_time = ramp;
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    double x0[PM_DIM], x[PM_DIM];
    vu_body_mean(s, 0, v, x0);
    run(s, c.analysis.end_time);
    vu_body_mean(s, 0, v, x);
    for (int d = 0; d < PM_DIM; d++)
        dx[d] = x[d] - x0[d];
    *secs = vu_now() - t0;
    pm_sim_destroy(s);
    pm_case_free(&c);
}

int vu_sliding_block(const char *bench, const char *rel, const char *what, vu_runner run, double stick_tol)
{
    const double g = 9.81, th = 30.0 * M_PI / 180.0, t = 0.1;
    const double mus[2] = {0.0, 0.1};
    int ok = 1;
    for (int k = 0; k < 2; k++) {
        double v[PM_DIM], dx[PM_DIM], secs = 0;
        slide(rel, mus[k], 0.0, run, v, dx, &secs);
        const double ref = g * (sin(th) - mus[k] * cos(th)) * t;
        char q[96];
        snprintf(q, sizeof q, "mean velocity at 0.1 s (m/s)%s, mu = %.1f", what, mus[k]);
        ok &= vu_report(bench, q, v[0], ref, (v[0] - ref) / ref, 0.02, secs);
    }
    double v[PM_DIM], dx[PM_DIM], secs = 0;
    slide(rel, 1.5 * tan(th), 0.02, run, v, dx, &secs);
    const double free_dist = 0.5 * g * sin(th) * t * t;
    ok &= vu_report(bench, "centre-of-mass travel / frictionless, mu = 1.5 tan(theta)", dx[0] / free_dist, 0.0,
                    dx[0] / free_dist, stick_tol, secs);
    return ok;
}

long vu_collapse_run(pm_sim *s, const double *at, int n, vu_step_fn step, void *ctx, const char *label,
                     double *runout, double *height)
{
    long steps = 0;
    int k = 0;
    while (k < n) {
        double dt = vu_dt(s);
        if (s->t + dt > at[k])
            dt = at[k] - s->t;
        if ((step ? step(s, dt, ctx) : pm_explicit_step(s, dt)) != PM_OK) {
            fprintf(stderr, "%s: stopped at t = %g: %s\n", label, s->t, pm_error_message());
            break;
        }
        steps++;
        if (s->t >= at[k] - 1e-9) {
            double xm = -INFINITY, ym = -INFINITY;
            for (size_t i = 0; i < s->p.n; i++) {
                xm = fmax(xm, s->p.x[PM_DIM * i]);
                if (s->p.x[PM_DIM * i] < 0.1)
                    ym = fmax(ym, s->p.x[PM_DIM * i + 1]);
            }
            runout[k] = xm;
            height[k] = ym;
            k++;
        }
    }
    return steps;
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

vu_band vu_silo_band(size_t n, const double *r, const double *height, size_t stride, const double *vol,
                     const double *down, double z, double half, double r_wall)
{
    vu_band b = {0, 0, 0, 0};
    int na = 0, nw = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(fabs(height[stride * i] - z) < half))
            continue;
        b.all += vol[i];
        if (r[stride * i] < 0.1) {
            b.axis += down[i];
            na++;
        } else if (r[stride * i] > r_wall - 0.1) {
            b.wall += down[i];
            nw++;
        }
    }
    b.axis = na ? b.axis / na : 0;
    b.wall = nw ? b.wall / nw : 0;
    for (size_t i = 0; i < n; i++)
        if (fabs(height[stride * i] - z) < half && down[i] > 0.1 * b.axis)
            b.moving += vol[i];
    return b;
}
