/* Derived particle fields. The strain is logarithmic so that it stays meaningful at the large
 * deformations pmech is for: ln(det F) adds over steps and is -ln 2 for a halving of volume, where
 * the small-strain trace would say -0.5. */
#include "io/particle_fields.h"

#include <math.h>

#if PM_DIM != 2
#error "the strain invariants below use the 2-D layout of F (in-plane block plus the out-of-plane stretch)"
#endif

double pm_pf_pressure(const double *s) { return -(s[PM_SXX] + s[PM_SYY] + s[PM_SZZ]) / 3.0; }

double pm_pf_q(const double *s)
{
    const double dxy = s[PM_SXX] - s[PM_SYY], dyz = s[PM_SYY] - s[PM_SZZ], dzx = s[PM_SZZ] - s[PM_SXX];
    return sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) + 3.0 * s[PM_SXY] * s[PM_SXY]);
}

void pm_pf_log_strain(const double *F, double *vol, double *dev)
{
    /* B = F F^T is block diagonal: the in-plane 2 x 2 block and Fzz^2; its eigenvalues are the squared
     * principal stretches */
    const double b11 = F[PM_FXX] * F[PM_FXX] + F[PM_FXY] * F[PM_FXY];
    const double b22 = F[PM_FYX] * F[PM_FYX] + F[PM_FYY] * F[PM_FYY];
    const double b12 = F[PM_FXX] * F[PM_FYX] + F[PM_FXY] * F[PM_FYY];
    const double mean = 0.5 * (b11 + b22), half = 0.5 * (b11 - b22);
    const double r = sqrt(half * half + b12 * b12);
    /* lambda1 * lambda2 = det(B) exactly, so the smaller root comes from the product (no cancellation) */
    const double det = b11 * b22 - b12 * b12, l1 = mean + r;
    if (!(l1 > 0) || !(det > 0) || F[PM_FZZ] == 0) { /* a particle squashed flat: no logarithmic strain */
        *vol = *dev = NAN;
        return;
    }
    const double e[3] = {0.5 * log(l1), 0.5 * log(det / l1), log(fabs(F[PM_FZZ]))};
    const double v = e[0] + e[1] + e[2];
    double s = 0;
    for (int k = 0; k < 3; k++)
        s += (e[k] - v / 3) * (e[k] - v / 3);
    *vol = v;
    *dev = sqrt(2.0 / 3.0 * s);
}
