/*
 * Material-point driver: applies a deformation path to one point and reports its response.
 * Strain increments are fed through F_incr = (I + A)(I - A)^-1, A = deps/2, whose Hughes-Winget
 * mid-step strain is exactly deps and whose spin is zero; simple shear uses the true F (with spin).
 */
#include "pmech/driver.h"

#include "material/material_internal.h"
#include "material/principal.h"
#include "pmech/error.h"

#include <math.h>
#include <string.h>

/*
 * A step the model could not take, or took to a stress or state that is not finite: the driver stops
 * (exit 1) rather than write inf/NaN rows, and says what it fed the model: the stress at the start,
 * the strain increment (engineering shear) and the elastic trial stress from them.
 */
static int step_failed(const pm_material *m, int k, const double e[4], const double s[6], const double *s1,
                       int update_failed)
{
    const double lam = m->K - 2.0 * m->G / 3.0, tr = e[0] + e[1] + e[2];
    double trial[4];
    for (int i = 0; i < 3; i++)
        trial[i] = s[i] + lam * tr + 2.0 * m->G * e[i];
    trial[3] = s[3] + m->G * e[3];
    char what[256];
    if (update_failed)
        snprintf(what, sizeof what, "model '%s' could not update the stress (its update found no admissible stress)",
                 m->ops->name);
    else
        snprintf(what, sizeof what, "model '%s' returned a stress that is not finite (%g, %g, %g, %g) or a "
                 "non-finite state", m->ops->name, s1[0], s1[1], s1[2], s1[3]);
    return pm_error_set(PM_ESIM,
                        "driver step %d: %s; start stress (sxx, syy, szz, sxy) = (%g, %g, %g, %g), strain increment "
                        "(exx, eyy, ezz, gxy) = (%g, %g, %g, %g), elastic trial stress = (%g, %g, %g, %g)",
                        k, what, s[0], s[1], s[2], s[3], e[0], e[1], e[2], e[3], trial[0], trial[1], trial[2],
                        trial[3]);
}

static int all_finite(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* F_incr with mid-step strain deps (Voigt, engineering shears) and no spin. */
static void f_from_strain(const double deps[6], double F[9])
{
    const double A[9] = {0.5 * deps[0], 0.25 * deps[3], 0.25 * deps[5],
                         0.25 * deps[3], 0.5 * deps[1], 0.25 * deps[4],
                         0.25 * deps[5], 0.25 * deps[4], 0.5 * deps[2]};
    double P[9], M[9], Mi[9];
    for (int i = 0; i < 9; i++) {
        const double I = (i % 4 == 0) ? 1.0 : 0.0;
        P[i] = I + A[i];
        M[i] = I - A[i];
    }
    const double c0 = M[4] * M[8] - M[5] * M[7], c1 = M[5] * M[6] - M[3] * M[8], c2 = M[3] * M[7] - M[4] * M[6];
    const double r = 1.0 / (M[0] * c0 + M[1] * c1 + M[2] * c2);
    Mi[0] = c0 * r;
    Mi[1] = (M[2] * M[7] - M[1] * M[8]) * r;
    Mi[2] = (M[1] * M[5] - M[2] * M[4]) * r;
    Mi[3] = c1 * r;
    Mi[4] = (M[0] * M[8] - M[2] * M[6]) * r;
    Mi[5] = (M[2] * M[3] - M[0] * M[5]) * r;
    Mi[6] = c2 * r;
    Mi[7] = (M[1] * M[6] - M[0] * M[7]) * r;
    Mi[8] = (M[0] * M[4] - M[1] * M[3]) * r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            F[3 * i + j] = P[3 * i] * Mi[j] + P[3 * i + 1] * Mi[3 + j] + P[3 * i + 2] * Mi[6 + j];
}

static void matmul3(const double A[9], const double B[9], double C[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

/* Logarithmic (Hencky) strain 1/2 ln(F F^T), Voigt with tensor shears. */
static void log_strain(const double F[9], double e[6])
{
    double b[6], lam[3], V[9];
    b[0] = F[0] * F[0] + F[1] * F[1] + F[2] * F[2];
    b[1] = F[3] * F[3] + F[4] * F[4] + F[5] * F[5];
    b[2] = F[6] * F[6] + F[7] * F[7] + F[8] * F[8];
    b[3] = F[0] * F[3] + F[1] * F[4] + F[2] * F[5];
    b[4] = F[3] * F[6] + F[4] * F[7] + F[5] * F[8];
    b[5] = F[0] * F[6] + F[1] * F[7] + F[2] * F[8];
    pm_eig_sym3(b, lam, V);
    for (int a = 0; a < 3; a++)
        lam[a] = 0.5 * log(lam[a]);
    pm_spectral_compose(lam, V, e);
}

typedef struct {
    const pm_material *m;
    FILE *csv;
    void (*row)(void *, int, const double[11]);
    void *ctx;
} out_t;

static void emit(const out_t *o, int step, const double F[9], const double s[6], const double *state)
{
    double e[6], v[11];
    log_strain(F, e);
    const double p = -(s[0] + s[1] + s[2]) / 3.0;
    const double q = pm_voigt_q(s);
    const double ep = o->m->ops->plastic_strain ? o->m->ops->plastic_strain(o->m, state) : 0.0;
    v[0] = e[0]; v[1] = e[1]; v[2] = e[2]; v[3] = e[3];
    v[4] = s[0]; v[5] = s[1]; v[6] = s[2]; v[7] = s[3];
    v[8] = p; v[9] = q; v[10] = ep;
    if (o->csv) {
        fprintf(o->csv, "%d", step);
        for (int i = 0; i < 11; i++)
            fprintf(o->csv, ",%.12g", v[i]);
        fputc('\n', o->csv);
    }
    if (o->row)
        o->row(o->ctx, step, v);
}

/* One update from (s0, st0) with F_incr; results in s, st (and tangent D when not NULL). */
static int step_update(const pm_material *m, const double Fi[9], const double Fold[9], double dt,
                       const double s0[6], const double *st0, double s[6], double *st, double *D)
{
    pm_material_step in;
    memcpy(in.F_incr, Fi, sizeof in.F_incr);
    memcpy(in.F_old, Fold, sizeof in.F_old);
    matmul3(Fi, Fold, in.F_new);
    in.dt = dt;
    memcpy(s, s0, 6 * sizeof(double));
    memcpy(st, st0, PM_MAT_MAX_STATE * sizeof(double));
    return m->ops->update(m, &in, st, s, D);
}

int pm_driver_run_cb(const pm_driver *d, FILE *csv,
                     void (*row)(void *ctx, int step, const double values[11]), void *ctx)
{
    const pm_material *m = &d->material;
    if (!m->ops)
        return pm_error_set(PM_EINPUT, "driver: material has no model");
    const int n = d->path == PM_PATH_INCREMENTS ? (int)d->n_increments : d->steps;
    if (n < 1)
        return pm_error_set(PM_EINPUT, d->path == PM_PATH_INCREMENTS
                                           ? "path.increments: at least one increment is needed"
                                           : "path.steps = %d: must be >= 1",
                            n);
    double s[6] = {d->stress0[0], d->stress0[1], d->stress0[2], d->stress0[3], 0, 0};
    double state[PM_MAT_MAX_STATE] = {0};
    if (m->ops->init_state)
        m->ops->init_state(m, s, state);
    double F[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const out_t o = {m, csv, row, ctx};
    if (csv)
        fprintf(csv, "%s\n", PM_DRIVER_CSV_HEADER);
    emit(&o, 0, F, s, state);
    const double dt = d->dt;
    for (int k = 1; k <= n; k++) {
        double Fi[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, s1[6], st1[PM_MAT_MAX_STATE], D[36];
        int rc = PM_OK;
        double de_k[6] = {0}; /* this step's strain increment, for a message */
        switch (d->path) {
        case PM_PATH_OEDOMETER:
        case PM_PATH_TRIAXIAL: {
            const double ly0 = 1.0 - d->axial_strain * (k - 1) / n, ly1 = 1.0 - d->axial_strain * k / n;
            if (!(ly1 > 0))
                return pm_error_set(PM_EINPUT, "path.axial_strain = %g: must be < 1", d->axial_strain);
            const double fy = ly1 / ly0;
            double de[6] = {0, 2.0 * (fy - 1.0) / (fy + 1.0), 0, 0, 0, 0};
            if (d->path == PM_PATH_OEDOMETER) {
                memcpy(de_k, de, sizeof de);
                f_from_strain(de, Fi);
                rc = step_update(m, Fi, F, dt, s, state, s1, st1, NULL);
                break;
            }
            /* triaxial: Newton on the lateral strain increments for sxx = szz = -pc */
            const double pc = d->confining_pressure;
            const double scale = fabs(pc) + fabs(s[0]) + fabs(s[1]) + fabs(s[2]) + m->E + m->K;
            int conv = 0;
            for (int it = 0; it < 60 && rc == PM_OK; it++) {
                memcpy(de_k, de, sizeof de);
                f_from_strain(de, Fi);
                rc = step_update(m, Fi, F, dt, s, state, s1, st1, D);
                if (rc)
                    break;
                const double r0 = s1[0] + pc, r2 = s1[2] + pc;
                if (fabs(r0) <= 1e-12 * scale && fabs(r2) <= 1e-12 * scale) {
                    conv = 1;
                    break;
                }
                double a = D[0], b = D[2], c = D[12], e = D[14];
                double det = a * e - b * c;
                if (!(fabs(det) > 1e-12 * (a * a + e * e + 1e-300))) {
                    /* no lateral stiffness (perfectly plastic apex): fall back to elasticity */
                    pm_elastic_stiffness(m->K > 0 ? m->K : 1.0, m->G > 0 ? m->G : 1.0, D);
                    a = D[0]; b = D[2]; c = D[12]; e = D[14];
                    det = a * e - b * c;
                }
                de[0] -= (e * r0 - b * r2) / det;
                de[2] -= (a * r2 - c * r0) / det;
            }
            if (rc == PM_OK && !conv)
                return pm_error_set(PM_ESIM,
                                    "driver step %d: lateral stress did not converge to the confining "
                                    "pressure (the material cannot carry it)",
                                    k);
            break;
        }
        case PM_PATH_SIMPLE_SHEAR: {
            const double dg = d->shear_strain / n;
            Fi[1] = dg; /* F = [[1, g], [0, 1]]: F_incr = F_k F_{k-1}^-1 */
            de_k[3] = dg;
            rc = step_update(m, Fi, F, dt, s, state, s1, st1, NULL);
            break;
        }
        case PM_PATH_INCREMENTS: {
            const double *inc = d->increments + 4 * (size_t)(k - 1);
            const double de[6] = {inc[0], inc[1], inc[2], inc[3], 0, 0};
            memcpy(de_k, de, sizeof de);
            f_from_strain(de, Fi);
            rc = step_update(m, Fi, F, dt, s, state, s1, st1, NULL);
            break;
        }
        default:
            return pm_error_set(PM_EINPUT, "path.type: unknown path %d", (int)d->path);
        }
        if (rc == PM_ESIM)
            return step_failed(m, k, de_k, s, s1, 1);
        if (rc != PM_OK)
            return rc;
        if (!all_finite(s1, 6) || !all_finite(st1, (int)m->ops->n_state))
            return step_failed(m, k, de_k, s, s1, 0);
        double Fn[9];
        matmul3(Fi, F, Fn);
        memcpy(F, Fn, sizeof F);
        memcpy(s, s1, sizeof s);
        memcpy(state, st1, sizeof state);
        emit(&o, k, F, s, state);
    }
    return PM_OK;
}

int pm_driver_run(const pm_driver *d, FILE *csv) { return pm_driver_run_cb(d, csv, NULL, NULL); }
