/* Symmetric 3x3 eigen-decomposition (cyclic Jacobi) and the spectral consistent tangent. */
#include "material/principal.h"

#include <math.h>
#include <string.h>

void pm_eig_sym3(const double s[6], double lam[3], double V[9])
{
    double A[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
    double Q[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int sweep = 0; sweep < 50; sweep++) {
        const double off = A[0][1] * A[0][1] + A[0][2] * A[0][2] + A[1][2] * A[1][2];
        const double diag = A[0][0] * A[0][0] + A[1][1] * A[1][1] + A[2][2] * A[2][2];
        if (off == 0.0 || off <= 1e-36 * diag)
            break;
        for (int p = 0; p < 2; p++) {
            for (int q = p + 1; q < 3; q++) {
                const double apq = A[p][q];
                if (apq == 0.0)
                    continue;
                /* rotation that annihilates A[p][q] (Golub & Van Loan, sym.schur2) */
                const double theta = (A[q][q] - A[p][p]) / (2.0 * apq);
                const double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(1.0 + theta * theta));
                const double c = 1.0 / sqrt(1.0 + t * t), sn = t * c;
                for (int k = 0; k < 3; k++) {
                    const double akp = A[k][p], akq = A[k][q];
                    A[k][p] = c * akp - sn * akq;
                    A[k][q] = sn * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {
                    const double apk = A[p][k], aqk = A[q][k];
                    A[p][k] = c * apk - sn * aqk;
                    A[q][k] = sn * apk + c * aqk;
                }
                A[p][q] = A[q][p] = 0.0;
                for (int k = 0; k < 3; k++) {
                    const double qkp = Q[k][p], qkq = Q[k][q];
                    Q[k][p] = c * qkp - sn * qkq;
                    Q[k][q] = sn * qkp + c * qkq;
                }
            }
        }
    }
    int idx[3] = {0, 1, 2};
    const double d[3] = {A[0][0], A[1][1], A[2][2]};
    for (int i = 0; i < 2; i++)
        for (int j = i + 1; j < 3; j++)
            if (d[idx[j]] > d[idx[i]]) {
                int t = idx[i];
                idx[i] = idx[j];
                idx[j] = t;
            }
    for (int a = 0; a < 3; a++) {
        lam[a] = d[idx[a]];
        for (int i = 0; i < 3; i++)
            V[3 * i + a] = Q[i][idx[a]];
    }
}

void pm_spectral_compose(const double lam[3], const double V[9], double s[6])
{
    memset(s, 0, 6 * sizeof(double));
    for (int a = 0; a < 3; a++) {
        const double x = V[a], y = V[3 + a], z = V[6 + a], l = lam[a];
        s[0] += l * x * x;
        s[1] += l * y * y;
        s[2] += l * z * z;
        s[3] += l * x * y;
        s[4] += l * y * z;
        s[5] += l * x * z;
    }
}

/* Voigt (tensor components) of the symmetric dyad (u (x) w + w (x) u) / 2. */
static void sym_dyad(const double u[3], const double w[3], double out[6])
{
    out[0] = u[0] * w[0];
    out[1] = u[1] * w[1];
    out[2] = u[2] * w[2];
    out[3] = 0.5 * (u[0] * w[1] + u[1] * w[0]);
    out[4] = 0.5 * (u[1] * w[2] + u[2] * w[1]);
    out[5] = 0.5 * (u[0] * w[2] + u[2] * w[0]);
}

void pm_spectral_tangent(const double V[9], const double str[3], const double sig[3],
                         const double Dp[9], double G, double D[36])
{
    double v[3][3], m[3][6];
    for (int a = 0; a < 3; a++) {
        for (int i = 0; i < 3; i++)
            v[a][i] = V[3 * i + a];
        sym_dyad(v[a], v[a], m[a]);
    }
    memset(D, 0, 36 * sizeof(double));
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            const double d = Dp[3 * a + b];
            if (d == 0.0)
                continue;
            for (int i = 0; i < 6; i++)
                for (int j = 0; j < 6; j++)
                    D[6 * i + j] += d * m[a][i] * m[b][j];
        }
    const double scale = fabs(str[0]) + fabs(str[1]) + fabs(str[2]) + 2.0 * G * 1e-300;
    for (int a = 0; a < 2; a++)
        for (int b = a + 1; b < 3; b++) {
            const double dt = str[a] - str[b];
            double c;
            if (fabs(dt) > 1e-9 * scale)
                c = 2.0 * G * (sig[a] - sig[b]) / dt;
            else
                c = 0.5 * (Dp[3 * a + a] - Dp[3 * a + b] - Dp[3 * b + a] + Dp[3 * b + b]);
            if (c == 0.0)
                continue;
            double M[6];
            sym_dyad(v[a], v[b], M);
            for (int i = 0; i < 6; i++)
                for (int j = 0; j < 6; j++)
                    D[6 * i + j] += 2.0 * c * M[i] * M[j];
        }
}
