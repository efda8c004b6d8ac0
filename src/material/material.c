/*
 * Model-independent parts of the material interface: parameter look-up, elastic constants,
 * the objective (Hughes-Winget) stress rotation shared by every hypo-elastic model, and the
 * isotropic elastic stiffness.
 */
#include "material/material_internal.h"

#include "pmech/error.h"

#include <math.h>
#include <string.h>

int pm_material_param_index(const pm_material_ops *ops, const char *key)
{
    if (!ops || !key)
        return -1;
    for (size_t i = 0; i < ops->n_params; i++)
        if (!strcmp(ops->params[i].key, key))
            return (int)i;
    return -1;
}

double pm_material_param(const pm_material *m, const char *key)
{
    int i = pm_material_param_index(m ? m->ops : NULL, key);
    return i < 0 ? NAN : m->param[i];
}

int pm_material_set_elastic(pm_material *m, double E, double nu, double K, double G)
{
    const int have_en = !isnan(E) || !isnan(nu), have_kg = !isnan(K) || !isnan(G);
    if (have_en && have_kg)
        return pm_error_set(PM_EINPUT,
                            "give either youngs_modulus and poisson_ratio or bulk_modulus and "
                            "shear_modulus, not both pairs");
    if (have_en) {
        if (isnan(E))
            return pm_error_set(PM_EINPUT, "youngs_modulus is missing (poisson_ratio given)");
        if (isnan(nu))
            return pm_error_set(PM_EINPUT, "poisson_ratio is missing (youngs_modulus given)");
        if (!(E > 0) || !isfinite(E))
            return pm_error_set(PM_EINPUT, "youngs_modulus = %g: must be > 0", E);
        if (!(nu > -1.0 && nu < 0.5))
            return pm_error_set(PM_EINPUT, "poisson_ratio = %g: must be in (-1, 0.5)", nu);
        K = E / (3.0 * (1.0 - 2.0 * nu));
        G = E / (2.0 * (1.0 + nu));
    } else if (have_kg) {
        if (isnan(K))
            return pm_error_set(PM_EINPUT, "bulk_modulus is missing (shear_modulus given)");
        if (isnan(G))
            return pm_error_set(PM_EINPUT, "shear_modulus is missing (bulk_modulus given)");
        if (!(K > 0) || !isfinite(K))
            return pm_error_set(PM_EINPUT, "bulk_modulus = %g: must be > 0", K);
        if (!(G > 0) || !isfinite(G))
            return pm_error_set(PM_EINPUT, "shear_modulus = %g: must be > 0", G);
        E = 9.0 * K * G / (3.0 * K + G);
        nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
    } else {
        return pm_error_set(PM_EINPUT,
                            "elastic constants missing: give youngs_modulus and poisson_ratio, or "
                            "bulk_modulus and shear_modulus");
    }
    m->E = E;
    m->nu = nu;
    m->K = K;
    m->G = G;
    m->lambda = K - 2.0 * G / 3.0;
    return PM_OK;
}

double pm_material_elastic_wave_speed(const pm_material *m, const double *state, double density)
{
    (void)state;
    return sqrt((m->K + 4.0 * m->G / 3.0) / density);
}

double pm_material_signal_speed(const pm_material *m, const double *state, double density, double h)
{
    const double c = m->ops->wave_speed ? m->ops->wave_speed(m, state, density)
                                        : pm_material_elastic_wave_speed(m, state, density);
    const double eta = m->ops->rate_viscosity ? m->ops->rate_viscosity(m) : 0.0;
    return c + 4.0 * eta / (density * h);
}

double pm_material_elastic_energy(const pm_material *m, const pm_material_step *in,
                                  const double *state, const double stress[6])
{
    (void)in;
    (void)state;
    if (!(m->K > 0) || !(m->G > 0))
        return 0.0;
    const double p = pm_voigt_mean(stress);
    const double a = stress[0] - p, b = stress[1] - p, c = stress[2] - p;
    const double ss = a * a + b * b + c * c +
                      2.0 * (stress[3] * stress[3] + stress[4] * stress[4] + stress[5] * stress[5]);
    /* 1/2 sigma : C^-1 : sigma = p^2 / (2K) + s:s / (4G) */
    return 0.5 * p * p / m->K + 0.25 * ss / m->G;
}

double pm_plastic_strain_state0(const pm_material *m, const double *state)
{
    (void)m;
    return state[0];
}

/* Inverse of a general 3x3 row-major matrix; returns the determinant (0: singular, B untouched). */
static double inv3(const double A[9], double B[9])
{
    const double c0 = A[4] * A[8] - A[5] * A[7];
    const double c1 = A[5] * A[6] - A[3] * A[8];
    const double c2 = A[3] * A[7] - A[4] * A[6];
    const double det = A[0] * c0 + A[1] * c1 + A[2] * c2;
    if (det == 0.0)
        return 0.0;
    const double r = 1.0 / det;
    B[0] = c0 * r;
    B[1] = (A[2] * A[7] - A[1] * A[8]) * r;
    B[2] = (A[1] * A[5] - A[2] * A[4]) * r;
    B[3] = c1 * r;
    B[4] = (A[0] * A[8] - A[2] * A[6]) * r;
    B[5] = (A[2] * A[3] - A[0] * A[5]) * r;
    B[6] = c2 * r;
    B[7] = (A[1] * A[6] - A[0] * A[7]) * r;
    B[8] = (A[0] * A[4] - A[1] * A[3]) * r;
    return det;
}

/* The in-plane case (plane strain/stress, axisymmetric: no out-of-plane shear) is the explicit
 * solver's hot path; the same formulas reduce to a 2x2 inverse and one rotation about z. */
static int hughes_winget_planar(const double f[9], double stress[6], double deps[6])
{
    const double a = f[0] + 1.0, b = f[1], c = f[3], d = f[4] + 1.0;
    const double det = a * d - b * c;
    if (det == 0.0 || f[8] == -1.0)
        return 0;
    const double id = 1.0 / det;
    const double pi00 = d * id, pi01 = -b * id, pi10 = -c * id, pi11 = a * id;
    const double m00 = f[0] - 1.0, m01 = f[1], m10 = f[3], m11 = f[4] - 1.0;
    const double g00 = 2.0 * (m00 * pi00 + m01 * pi10), g01 = 2.0 * (m00 * pi01 + m01 * pi11);
    const double g10 = 2.0 * (m10 * pi00 + m11 * pi10), g11 = 2.0 * (m10 * pi01 + m11 * pi11);
    deps[0] = g00;
    deps[1] = g11;
    deps[2] = 2.0 * (f[8] - 1.0) / (f[8] + 1.0);
    deps[3] = g01 + g10;
    deps[4] = deps[5] = 0.0;
    const double w = 0.25 * (g01 - g10);
    if (w == 0.0)
        return 1;
    /* Q = (I - W)^-1 (I + W) with W = [[0, w], [-w, 0]]: a rotation with these cosine and sine */
    const double iw = 1.0 / (1.0 + w * w), cq = (1.0 - w * w) * iw, sq = 2.0 * w * iw;
    const double sxx = stress[0], syy = stress[1], sxy = stress[3];
    const double cc = cq * cq, ss = sq * sq, cs = cq * sq;
    stress[0] = cc * sxx + 2.0 * cs * sxy + ss * syy;
    stress[1] = ss * sxx - 2.0 * cs * sxy + cc * syy;
    stress[3] = cs * (syy - sxx) + (cc - ss) * sxy;
    return 1;
}

void pm_hughes_winget(const double F_incr[9], double stress[6], double deps[6])
{
    if (F_incr[2] == 0.0 && F_incr[5] == 0.0 && F_incr[6] == 0.0 && F_incr[7] == 0.0 && stress[4] == 0.0 &&
        stress[5] == 0.0 && hughes_winget_planar(F_incr, stress, deps))
        return;
    /* Gradient of the displacement increment with respect to the mid-step configuration
     * x_{n+1/2} = (x_n + x_{n+1}) / 2:  G = 2 (f - I)(f + I)^-1. */
    double fp[9], fpi[9], fm[9], G[9];
    for (int i = 0; i < 9; i++) {
        fp[i] = F_incr[i];
        fm[i] = F_incr[i];
    }
    fp[0] += 1.0; fp[4] += 1.0; fp[8] += 1.0;
    fm[0] -= 1.0; fm[4] -= 1.0; fm[8] -= 1.0;
    if (inv3(fp, fpi) == 0.0) {
        /* f has an eigenvalue -1 (a half turn within one step): no mid-step configuration */
        for (int i = 0; i < 6; i++)
            deps[i] = NAN;
        return;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            G[3 * i + j] = 2.0 * (fm[3 * i] * fpi[j] + fm[3 * i + 1] * fpi[3 + j] + fm[3 * i + 2] * fpi[6 + j]);
    deps[0] = G[0];
    deps[1] = G[4];
    deps[2] = G[8];
    deps[3] = G[1] + G[3];
    deps[4] = G[5] + G[7];
    deps[5] = G[2] + G[6];
    /* Half the spin, w = W/2; rotation Q = (I - w)^-1 (I + w) (Cayley transform). */
    const double wxy = 0.25 * (G[1] - G[3]), wyz = 0.25 * (G[5] - G[7]), wxz = 0.25 * (G[2] - G[6]);
    if (wxy == 0.0 && wyz == 0.0 && wxz == 0.0)
        return;
    const double Ip[9] = {1, wxy, wxz, -wxy, 1, wyz, -wxz, -wyz, 1};
    const double Im[9] = {1, -wxy, -wxz, wxy, 1, -wyz, wxz, wyz, 1};
    double Imi[9], Q[9], S[9], QS[9];
    inv3(Im, Imi); /* det = 1 + |w|^2 > 0 */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Q[3 * i + j] = Imi[3 * i] * Ip[j] + Imi[3 * i + 1] * Ip[3 + j] + Imi[3 * i + 2] * Ip[6 + j];
    S[0] = stress[0]; S[1] = stress[3]; S[2] = stress[5];
    S[3] = stress[3]; S[4] = stress[1]; S[5] = stress[4];
    S[6] = stress[5]; S[7] = stress[4]; S[8] = stress[2];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            QS[3 * i + j] = Q[3 * i] * S[j] + Q[3 * i + 1] * S[3 + j] + Q[3 * i + 2] * S[6 + j];
    /* sigma' = Q S Q^T, upper triangle only */
#define QSQT(i, j) (QS[3 * (i)] * Q[3 * (j)] + QS[3 * (i) + 1] * Q[3 * (j) + 1] + QS[3 * (i) + 2] * Q[3 * (j) + 2])
    stress[0] = QSQT(0, 0);
    stress[1] = QSQT(1, 1);
    stress[2] = QSQT(2, 2);
    stress[3] = QSQT(0, 1);
    stress[4] = QSQT(1, 2);
    stress[5] = QSQT(0, 2);
#undef QSQT
}

void pm_elastic_stiffness(double K, double G, double D[36])
{
    const double a = K + 4.0 * G / 3.0, b = K - 2.0 * G / 3.0;
    memset(D, 0, 36 * sizeof(double));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            D[6 * i + j] = i == j ? a : b;
    D[21] = D[28] = D[35] = G;
}
