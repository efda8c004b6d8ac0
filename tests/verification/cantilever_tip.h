/* The cantilever's tip deflection as the verification programs measure it (verify_cantilever.c,
 * verify_meshfree_cantilever.c). */
#ifndef PMECH_CANTILEVER_TIP_H
#define PMECH_CANTILEVER_TIP_H

#include "pmech/sim.h"
#include "solver/sim_internal.h"

#define L_BEAM 8.0

/* Deflection at (L, 0.5) from a plane fitted through the last cell column's points. */
static inline double tip_deflection(const pm_sim *s, double h)
{
    double A[3][3] = {{0}}, b[3] = {0};
    for (size_t i = 0; i < s->p.n; i++) {
        const double x = s->p.x0[2 * i], y = s->p.x0[2 * i + 1];
        if (x < L_BEAM - h)
            continue;
        const double phi[3] = {1, x - L_BEAM, y - 0.5}, u = s->p.x[2 * i + 1] - y;
        for (int r = 0; r < 3; r++) {
            b[r] += phi[r] * u;
            for (int c = 0; c < 3; c++)
                A[r][c] += phi[r] * phi[c];
        }
    }
    /* Cramer's rule for the constant term */
    double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    double d0 = b[0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (b[1] * A[2][2] - A[1][2] * b[2]) +
                A[0][2] * (b[1] * A[2][1] - A[1][1] * b[2]);
    return -d0 / det;
}

#endif
