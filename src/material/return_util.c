/* Small helpers shared by the invariant-based (p, q) return mappings. */
#include "material/material_internal.h"

#include <string.h>

double pm_voigt_split(const double s[6], double dev[6], double *mean)
{
    const double m = (s[0] + s[1] + s[2]) / 3.0;
    dev[0] = s[0] - m;
    dev[1] = s[1] - m;
    dev[2] = s[2] - m;
    dev[3] = s[3];
    dev[4] = s[4];
    dev[5] = s[5];
    *mean = m;
    const double j2 = 0.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) + dev[3] * dev[3] +
                      dev[4] * dev[4] + dev[5] * dev[5];
    return sqrt(3.0 * j2);
}

void pm_trial_state(const double F_incr[9], const double stress[6], double K, double G, pm_trial *t)
{
    memcpy(t->sig, stress, 6 * sizeof(double));
    pm_hughes_winget(F_incr, t->sig, t->deps);
    const double *de = t->deps;
    const double ev = de[0] + de[1] + de[2];
    const double lam = (K - 2.0 * G / 3.0) * ev, g2 = 2.0 * G;
    t->sig[0] += lam + g2 * de[0];
    t->sig[1] += lam + g2 * de[1];
    t->sig[2] += lam + g2 * de[2];
    t->sig[3] += G * de[3];
    t->sig[4] += G * de[4];
    t->sig[5] += G * de[5];
    t->q = pm_voigt_split(t->sig, t->dev, &t->mean);
}

void pm_tangent_invariant(const double a[6], double ratio, double G, const double se[6],
                          const double c[6], double D[36])
{
    const double g = 2.0 * G * ratio;
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            double v = (i < 3 ? a[j] : 0.0) + se[i] * c[j];
            if (i < 3 && j < 3)
                v += g * ((i == j ? 1.0 : 0.0) - 1.0 / 3.0);
            else if (i == j)
                v += 0.5 * g;
            D[6 * i + j] = v;
        }
}

void pm_dq_deps(double G, const double se[6], double qe, double out[6])
{
    if (!(qe > 0)) {
        memset(out, 0, 6 * sizeof(double));
        return;
    }
    const double f = 3.0 * G / qe;
    for (int i = 0; i < 6; i++)
        out[i] = f * se[i];
}

double pm_equiv_dev_strain(const double e[6])
{
    const double m = (e[0] + e[1] + e[2]) / 3.0;
    const double a = e[0] - m, b = e[1] - m, c = e[2] - m;
    /* tensor shears are half the engineering ones */
    const double ee = a * a + b * b + c * c + 0.5 * (e[3] * e[3] + e[4] * e[4] + e[5] * e[5]);
    return sqrt(2.0 / 3.0 * ee);
}
