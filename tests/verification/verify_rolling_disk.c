/*
 * Rolling disk (seed 000 §5.2, Table 1): a hyperelastic disk rolls without slipping down a plane
 * inclined at theta. The plane is the grid side y_min with Coulomb friction (coefficient 1.0, far above
 * the tan(theta)/3 = 0.19 rolling needs) and gravity is tilted, g = |g| (sin(theta), -cos(theta)), so
 * the centre moves along x with a = (2/3) |g| sin(theta) and u(t) = a t^2 / 2.
 *
 * The case (tests/verification/cases/rolling_disk.json) is a coarse copy of examples/rolling_disk:
 * h = R/8 instead of R/25 and 0.3 s instead of 1 s, so that the three runs of a row take about 2 s.
 * For every row of ROWS (method, shape function) and every step dt1 = 2 dt2 = 4 dt3 (dt1 = the case's
 * analysis.dt) it reports, as seed 000 Table 1 does,
 *   - the error of eq. 67, sqrt(sum_i (u(t_i) - u_num(t_i))^2) over t_i = 0.01, 0.02, ... s, in mm,
 *     u_num the displacement along the plane of the disk's centre of mass (mass-weighted mean of the
 *     particle positions);
 *   - the wall time of the run;
 * and judges, on the finest step of each row,
 *   - the centre acceleration a_num, the least-squares fit of u(t) = a t^2 / 2 to the samples, against
 *     (2/3) |g| sin(theta);
 *   - rolling, not sliding: the spin omega (angular momentum about the centre of mass over its polar
 *     moment of inertia) against v / R, as the least-squares ratio of -omega R to v over the samples;
 *   - the centre's largest displacement normal to the plane over the samples (rise or sink) within 1 %
 *     of R, as the benchmark asks;
 *   - no particle leaving the disk: the farthest particle from the centre of mass stays within 2 % of
 *     R (TOL_REACH),
 * and reports the centre's rise off the plane at the end. The tolerances are in ROWS, with their reasons.
 *
 * What the coarse mesh affords. Two things cost the disk its acceleration before (0.857 of the exact
 * one here, 0.48 before that), both measured with an energy and angular-momentum budget of this case:
 *   - the seeded disk was not round as contact sees it (centre distance minus half-size): the outermost
 *     points' seeding half-sizes overshot the rim by different amounts, 0.502 m below the centre at the
 *     start and up to 0.512 m in other directions, so the disk climbed 8 mm onto its own corners in
 *     0.3 s (9 % of the energy it released). Half-sizes now end at the rim (src/core/seed.c);
 *   - the friction side's node-by-node law held the boundary node ahead of the contact point, whose
 *     velocity is that of the material still descending ahead of it: the normal force sat 40 mm (0.6
 *     of a cell) ahead of the centre, a rolling resistance, and at h = R/16 and R/32 the runs gained
 *     energy after 0.2 s and threw particles off. The law now acts at the touching points, on the
 *     velocity interpolated there (src/contact/friction.c): the normal force sits within 2 mm of the
 *     centre, and over 1 s at h = R/8 the disk loses 3 % of the released energy by 0.1 s and 0.3 % by
 *     1 s, where the node-by-node law, with the same round disk, had gained 3.5 times it by 1 s.
 * At h = R/8 the acceleration is now within 2 % over 0.3 s (0.5 % over 1 s), so the benchmark's 5 %
 * is judged on this mesh.
 *
 * Small variant (PMECH_VERIFY_SMALL, for sanitizer builds): the step dt1 only, a seventh of the work,
 * judged as the finest step is, and the MPM and GMM-MLS rows only. The step hardly matters here
 * (measured, dt1 / dt3: acceleration 1.0185 / 1.0175 of the exact one for MPM, 0.978 / 0.976 GMM-MLS;
 * spin 0.976 / 0.977, 1.022 / 1.024), so the same tolerances hold.
 * The GMM-LME row is left out because under ASan on a loaded machine it alone outlasts the test's 15
 * minutes (MPM took 99 s, GMM-MLS 260 s); verify_gmm_column_collapse's small variant runs LME instead.
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One row of the table: a method / shape-function pair and how closely it is expected to roll. */
typedef struct rd_row {
    const char *label;          /* as in the paper's table */
    pm_method method;
    const char *shape_function;
    double lme_gamma;           /* NAN: the approximation's default */
    double tol_acc;             /* relative tolerance of the fitted acceleration */
    double tol_spin;            /* relative tolerance of -omega R / v against 1 */
} rd_row;

/*
 * MPM, linear shape functions on tri3 cells.
 * Acceleration, 5 %: the benchmark's figure, met here (measured +1.8 %: the disk first settles 1.1 mm
 * into the plane, elastic and contact compression, and the 2 % of slip measured below lets it run
 * slightly ahead). A stuck disk (-100 %), a frictionless one sliding at g sin(theta) (+50 %), the
 * old pivoting one (-48 %) and the one that climbed its corners (-14 %) all fail.
 * Spin, 5 %: the spin of a disk that rolls without slipping is exactly v / R; MPM particle velocities
 * carry the disk's elastic ringing and the friction acts at a few points only, hence a few per cent
 * (measured -2.3 %); a disk that slides even partly spins measurably slower (a frictionless one not at all).
 *
 * GMM-MLS and GMM-LME (gamma 0.8 as in the paper's best row): the plane is a wall that acts at the
 * particles touching it, on the velocity their stencils give them (src/contact/contact.h,
 * pm_contact_takes_points). GMM's nodes are the corners of the cells the disk occupied at t = 0 and their
 * supports span 1.5 sqrt(2) cells, so a node's velocity mixes more of the material on both sides of the
 * contact. Acceleration 5 %, the benchmark's figure (measured -2.4 % MLS, -3.7 % LME, the same at every
 * step to 0.2 %; -5.4 % and -5.2 % while the wall acted node by node on the cloud's nodes, which held
 * the nodes' coefficients rather than the material's velocity at the contact, and the disk slipped:
 * spin 0.959 MLS; -28 % and -25 % before the disk was round, about -50 % before the gaps came from the
 * material). Spin 8 % (measured +2.4 % MLS, +4.5 % LME: the disk turns slightly faster than it rolls;
 * node by node -4.1 % and +0.7 %): a sliding or stuck disk fails both.
 */
static const rd_row ROWS[] = {
    {"MPM", PM_METHOD_MPM, "linear", NAN, 0.05, 0.05},
    {"GMM-MLS", PM_METHOD_GMM, "mls", NAN, 0.05, 0.08},
    {"GMM-LME (gamma 0.8)", PM_METHOD_GMM, "lme", 0.8, 0.05, 0.08},
};

enum { N_DT = 3, N_ROWS = sizeof ROWS / sizeof ROWS[0] };
static const char *const COARSE_CASE = "tests/verification/cases/rolling_disk.json";
/* No particle leaves the disk: the farthest one stays within 2 % of R of the centre of mass. The disk's
 * elastic strain is a few tenths of a per cent; a particle thrown off at the contact (as one was at
 * 10.8 m/s before) is centimetres away at the next sample. */
static const double TOL_REACH = 0.02;
/* The benchmark's bound on the centre's rise off the plane, applied to any normal displacement. */
static const double TOL_RISE = 0.01;
static const double SAMPLE_DT = 0.01; /* t_i of eq. 67 */

typedef struct rd_result {
    double err_mm;     /* eq. 67 in mm */
    double secs;       /* wall time of the run (set-up and steps) */
    double acc;        /* fitted centre acceleration */
    double spin;       /* least-squares ratio of -omega R to v over the samples */
    double rise;       /* centre's normal displacement at the end (m) */
    double rise_max;   /* its largest size at the samples, rise or sink (m) */
    double reach;      /* largest distance of a particle from the centre of mass at the samples (m) */
    int ok;            /* the run finished */
} rd_result;

/* Spin of body 0 about its centre of mass: angular momentum over polar moment of inertia. */
static double body_spin(const pm_sim *s, const double xc[2], const double vc[2])
{
    double L = 0, I = 0;
    for (size_t i = 0; i < s->p.n; i++) {
        if (s->p.body[i] != 0)
            continue;
        const double m = s->p.mass[i];
        const double rx = s->p.x[2 * i] - xc[0], ry = s->p.x[2 * i + 1] - xc[1];
        const double ux = s->p.v[2 * i] - vc[0], uy = s->p.v[2 * i + 1] - vc[1];
        L += m * (rx * uy - ry * ux);
        I += m * (rx * rx + ry * ry);
    }
    return L / I;
}

/* Largest distance of a particle of body 0 from the centre of mass @p xc. */
static double body_reach(const pm_sim *s, const double xc[2])
{
    double r = 0;
    for (size_t i = 0; i < s->p.n; i++)
        if (s->p.body[i] == 0)
            r = fmax(r, hypot(s->p.x[2 * i] - xc[0], s->p.x[2 * i + 1] - xc[1]));
    return r;
}

static void run(const char *case_file, double end_time, const rd_row *row, double dt, const char *csv, rd_result *r)
{
    pm_case c;
    vu_load(case_file, &c);
    c.analysis.end_time = end_time;
    c.method = row->method;
    snprintf(c.shape_function, sizeof c.shape_function, "%s", row->shape_function);
    c.lme_gamma = row->lme_gamma;
    c.analysis.dt = dt;
    const double g = hypot(c.analysis.gravity[0], c.analysis.gravity[1]);
    const double sin_th = c.analysis.gravity[0] / g, R = c.bodies[0].shape.radius;
    const double a = 2.0 / 3.0 * g * sin_th, T = c.analysis.end_time;
    const long per_sample = lround(SAMPLE_DT / dt), n_samples = lround(T / SAMPLE_DT);
    if (fabs(per_sample * dt - SAMPLE_DT) > 1e-9 * SAMPLE_DT) {
        fprintf(stderr, "dt = %g does not divide the sample interval %g\n", dt, SAMPLE_DT);
        exit(2);
    }
    /* columns: t, u_num, u_exact, normal displacement, v, -omega R */
    double *hist = calloc((size_t)(n_samples + 1) * 6, sizeof *hist);
    if (!hist)
        exit(2);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    double x0[2], v[2], x[2];
    vu_body_mean(s, 0, v, x0);
    double sum_e2 = 0, fit_num = 0, fit_den = 0, spin_num = 0, spin_den = 0, rise = 0;
    r->ok = 1;
    r->rise_max = 0;
    r->reach = body_reach(s, x0);
    for (long k = 1; k <= n_samples && r->ok; k++) {
        for (long j = 0; j < per_sample; j++)
            if (pm_explicit_step(s, dt) != PM_OK) {
                r->ok = 0;
                break;
            }
        const double t = k * SAMPLE_DT;
        vu_body_mean(s, 0, v, x);
        const double u = x[0] - x0[0], ue = 0.5 * a * t * t, w = body_spin(s, x, v);
        sum_e2 += (ue - u) * (ue - u);
        fit_num += u * 0.5 * t * t;
        fit_den += 0.25 * t * t * t * t;
        spin_num += -w * R * v[0];
        spin_den += v[0] * v[0];
        rise = x[1] - x0[1];
        r->rise_max = fmax(r->rise_max, fabs(rise));
        r->reach = fmax(r->reach, body_reach(s, x));
        double *h = hist + 6 * k;
        h[0] = t, h[1] = u, h[2] = ue, h[3] = rise, h[4] = v[0], h[5] = -w * R;
    }
    r->secs = vu_now() - t0;
    r->err_mm = 1e3 * sqrt(sum_e2);
    r->acc = fit_num / fit_den;
    r->spin = spin_num / spin_den;
    r->rise = rise;
    vu_write_csv(csv, "time,u,u_exact,rise,v,minus_omega_R", hist, (size_t)n_samples + 1, 6);
    free(hist);
    pm_sim_destroy(s);
    pm_case_free(&c);
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    pm_case c;
    vu_load(COARSE_CASE, &c);
    const double dt1 = c.analysis.dt, g = hypot(c.analysis.gravity[0], c.analysis.gravity[1]);
    const double a_ref = 2.0 / 3.0 * g * c.analysis.gravity[0] / g, T = c.analysis.end_time;
    const double R = c.bodies[0].shape.radius;
    pm_case_free(&c);
    if (!(dt1 > 0)) {
        fprintf(stderr, "the rolling-disk case needs a fixed analysis.dt\n");
        return 2;
    }
    int ok = 1;
    const int small = vu_small(), n_dt = small ? 1 : N_DT, n_rows = small ? 2 : N_ROWS;
    for (int ir = 0; ir < n_rows; ir++) {
        const rd_row *row = &ROWS[ir];
        rd_result res[N_DT];
        for (int k = 0; k < n_dt; k++) {
            const double dt = dt1 / (1 << k);
            char csv[96], q[128];
            snprintf(csv, sizeof csv, "rolling_disk_%s_%s_dt%d.csv", row->label, row->shape_function, k + 1);
            for (char *p = csv; *p; p++)
                if (*p == ' ')
                    *p = '_';
            run(COARSE_CASE, T, row, dt, csv, &res[k]);
            if (!res[k].ok) {
                fprintf(stderr, "%s, dt = %g: the run stopped early\n", row->label, dt);
                ok = 0;
                continue;
            }
            snprintf(q, sizeof q, "%s, dt%d = %.3g s: error eq. 67 (mm), wall time", row->label, k + 1, dt);
            vu_report("rolling disk", q, res[k].err_mm, 0.0, res[k].err_mm, -1, res[k].secs);
            snprintf(q, sizeof q, "%s, dt%d: fitted acceleration (m/s^2); -omega R / v; rise (mm)", row->label, k + 1);
            printf("  %s: a = %.4f (%.4f of %.4f), spin %.4f, rise %.3f mm\n", q, res[k].acc, res[k].acc / a_ref,
                   a_ref, res[k].spin, 1e3 * res[k].rise);
        }
        const rd_result *f = &res[n_dt - 1];
        if (!f->ok)
            continue;
        char q[128];
        snprintf(q, sizeof q, "%s, dt%d: centre acceleration (m/s^2), fit of u = a t^2/2", row->label, n_dt);
        ok &= vu_report("rolling disk", q, f->acc, a_ref, (f->acc - a_ref) / a_ref, row->tol_acc, f->secs);
        snprintf(q, sizeof q, "%s, dt%d: spin -omega R / v (least squares over the samples)", row->label, n_dt);
        ok &= vu_report("rolling disk", q, f->spin, 1.0, f->spin - 1.0, row->tol_spin, f->secs);
        snprintf(q, sizeof q, "%s, dt%d: rise of the centre off the plane at the end (mm)", row->label, n_dt);
        vu_report("rolling disk", q, 1e3 * f->rise, 0.0, 1e3 * f->rise, -1, f->secs);
        snprintf(q, sizeof q, "%s, dt%d: largest normal displacement of the centre / R", row->label, n_dt);
        ok &= vu_report("rolling disk", q, f->rise_max / R, 0.0, f->rise_max / R, TOL_RISE, f->secs);
        snprintf(q, sizeof q, "%s, dt%d: farthest particle from the centre of mass / R", row->label, n_dt);
        ok &= vu_report("rolling disk", q, f->reach / R, 1.0, f->reach / R - 1.0, TOL_REACH, f->secs);
    }
    return ok ? 0 : 1;
}
