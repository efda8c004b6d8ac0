/*
 * mohr_coulomb: Mohr-Coulomb with non-associated flow and a tension cut-off, returned in principal
 * stress space (Clausen, Damkilde & Andersen 2006, 2007), hypo-elastic (Hughes-Winget) frame.
 *
 * Principal stresses sorted s1 >= s2 >= s3 (tension positive). With
 *   k = (1 + sin phi)/(1 - sin phi),  m = (1 + sin psi)/(1 - sin psi),  sc = 2 c cos phi/(1 - sin phi)
 * the yield planes of the sextant and their flow directions are
 *   f1 = k s1 - s3 - sc   (flow (m, 0, -1))          main plane
 *   f2 = k s2 - s3 - sc   (flow (0, m, -1))          meets f1 on the compression edge s1 = s2
 *   f3 = k s1 - s2 - sc   (flow (m, -1, 0))          meets f1 on the extension edge s2 = s3
 *   t_i = s_i - T         (flow e_i, Rankine)        tension cut-off, when T < apex = c cot phi
 * Because all surfaces are planes and the elasticity is linear, every return onto an active set J
 * is closed form: dlambda = (A_J R_J)^-1 (A_J s_tr - c_J) with R_J = De b_J. The active set is the
 * first of {f1}, {t1}, {f1,f2}, {f1,f3}, {f1,t1}, {t1,t2} whose multipliers are >= 0, whose result
 * keeps s1 >= s2 >= s3 and violates no plane; otherwise the stress returns to a point (apex or the
 * corners of the cut-off), which is equivalent to Clausen's geometric region tests. The principal
 * tangent is (I - R (A R)^-1 A) De (zero at points) and the full tangent is its spectral form.
 * State: [0] equivalent plastic strain sqrt(2/3 |dev eps_p|^2), accumulated; [1] the loose volumetric
 * strain (below).
 *
 * Loose volume (stress_free_dilation = 1). A trial stress beyond the apex returns to the apex point,
 * whatever the dilatancy: the volume the step gained there is not a flow the model describes (psi = 0
 * allows none) but a point that has lost contact, and without this option it keeps that volume and
 * takes elastic stress from the first compression on, so loosened material never packs back. With it,
 * the volumetric strain beyond the apex, (p_trial - p_apex) / K, is kept in state[1] and carried
 * without stress: while it is positive the point stays at the apex, further extension adds to it, and
 * compression first takes it back; only the compression beyond it reaches the elastic trial. The option
 * needs the apex (no tension cut-off below it) and changes nothing while the stress stays inside the
 * cone.
 */
#include "material/material_internal.h"
#include "material/principal.h"

#include "pmech/error.h"

#include <string.h>

enum { P_C, P_PHI, P_PSI, P_T, P_LOOSE };
enum { D_K, D_M, D_SC, D_T, D_APEX, D_CUT };

static const pm_param_spec mc_params[] = {
    PM_COULOMB_PARAM_SPECS,
    {"tension_cutoff", NAN, 0, 0.0, INFINITY,
     "largest principal (tensile) stress T (Pa); absent: the apex c cot(phi), i.e. no cut-off"},
    {"stress_free_dilation", 0.0, 0, 0.0, 1.0,
     "1: volume gained at the apex is carried without stress until compacted back; 0: elastic at once"},
};

static int mc_init(pm_material *m)
{
    const double c = m->param[P_C], phi = m->param[P_PHI], psi = m->param[P_PSI];
    const double T = m->param[P_T];
    pm_check(pm_check_coulomb_strength(c, phi, psi));
    if (!isnan(T) && !(T >= 0))
        return pm_error_set(PM_EINPUT, "tension_cutoff = %g: must be >= 0", T);
    const double loose = m->param[P_LOOSE];
    if (loose != 0 && loose != 1)
        return pm_error_set(PM_EINPUT, "stress_free_dilation = %g: must be 0 or 1", loose);
    const double sp = sin(pm_deg2rad(phi)), ss = sin(pm_deg2rad(psi));
    const double k = (1 + sp) / (1 - sp);
    m->derived[D_K] = k;
    m->derived[D_M] = (1 + ss) / (1 - ss);
    m->derived[D_SC] = 2.0 * c * cos(pm_deg2rad(phi)) / (1 - sp);
    m->derived[D_APEX] = sp > 0 ? m->derived[D_SC] / (k - 1) : INFINITY;
    m->derived[D_CUT] = !isnan(T) && T < m->derived[D_APEX];
    m->derived[D_T] = m->derived[D_CUT] ? T : INFINITY;
    if (loose == 1 && (m->derived[D_CUT] || !isfinite(m->derived[D_APEX])))
        return pm_error_set(PM_EINPUT, "stress_free_dilation = 1 needs the apex: a friction_angle above 0 and no "
                                       "tension_cutoff below c cot(phi)");
    return PM_OK;
}

typedef struct {
    double a[6][3], r[6][3], b[6][3], c[6];
    int n; /* planes in use: 3 (no cut-off) or 6 */
} mc_planes;

static void mc_setup(const pm_material *m, mc_planes *P)
{
    const double k = m->derived[D_K], mm = m->derived[D_M], sc = m->derived[D_SC];
    const double T = m->derived[D_T];
    const double A[6][3] = {{k, 0, -1}, {0, k, -1}, {k, -1, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const double B[6][3] = {{mm, 0, -1}, {0, mm, -1}, {mm, -1, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const double lam = m->K - 2.0 * m->G / 3.0, g2 = 2.0 * m->G;
    P->n = m->derived[D_CUT] ? 6 : 3;
    for (int j = 0; j < 6; j++) {
        const double tr = B[j][0] + B[j][1] + B[j][2];
        for (int i = 0; i < 3; i++) {
            P->a[j][i] = A[j][i];
            P->b[j][i] = B[j][i];
            P->r[j][i] = lam * tr + g2 * B[j][i];
        }
        P->c[j] = j < 3 ? sc : T;
    }
}

/* Solve the n x n system M x = y (n <= 3) by Gaussian elimination with partial pivoting. */
static int solve_small(int n, double M[3][3], double y[3], double x[3])
{
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(M[r][c]) > fabs(M[p][c]))
                p = r;
        if (fabs(M[p][c]) < 1e-300)
            return -1;
        if (p != c) {
            for (int j = 0; j < n; j++) {
                double t = M[c][j];
                M[c][j] = M[p][j];
                M[p][j] = t;
            }
            double t = y[c];
            y[c] = y[p];
            y[p] = t;
        }
        for (int r = c + 1; r < n; r++) {
            const double f = M[r][c] / M[c][c];
            for (int j = c; j < n; j++)
                M[r][j] -= f * M[c][j];
            y[r] -= f * y[c];
        }
    }
    for (int r = n - 1; r >= 0; r--) {
        double s = y[r];
        for (int j = r + 1; j < n; j++)
            s -= M[r][j] * x[j];
        x[r] = s / M[r][r];
    }
    return 0;
}

/*
 * Return onto the active set J (planes or lines). On success fills sig and, when Dp is not NULL,
 * the principal tangent. Returns 1 if the return is admissible, 0 otherwise.
 */
static int try_active(const mc_planes *P, const pm_material *m, const int *J, int n,
                      const double str[3], double tol, double sig[3], double *Dp)
{
    double M[3][3], y[3], x[3];
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++)
            M[i][j] = P->a[J[i]][0] * P->r[J[j]][0] + P->a[J[i]][1] * P->r[J[j]][1] +
                      P->a[J[i]][2] * P->r[J[j]][2];
        y[i] = P->a[J[i]][0] * str[0] + P->a[J[i]][1] * str[1] + P->a[J[i]][2] * str[2] - P->c[J[i]];
    }
    double Mc[3][3];
    memcpy(Mc, M, sizeof M);
    if (solve_small(n, Mc, y, x))
        return 0;
    for (int i = 0; i < n; i++)
        if (x[i] < -tol * 1e-3 / (2.0 * m->G)) /* multipliers are strains */
            return 0;
    for (int d = 0; d < 3; d++) {
        sig[d] = str[d];
        for (int j = 0; j < n; j++)
            sig[d] -= x[j] * P->r[J[j]][d];
    }
    if (sig[1] > sig[0] + tol || sig[2] > sig[1] + tol)
        return 0;
    for (int j = 0; j < P->n; j++)
        if (P->a[j][0] * sig[0] + P->a[j][1] * sig[1] + P->a[j][2] * sig[2] - P->c[j] > tol)
            return 0;
    if (Dp) {
        /* dsig/dstr = I - R (A R)^-1 A, then times De */
        double X[3][3]; /* (A R)^-1 A, n x 3 */
        for (int col = 0; col < 3; col++) {
            double rhs[3], sol[3];
            for (int i = 0; i < n; i++)
                rhs[i] = P->a[J[i]][col];
            memcpy(Mc, M, sizeof M);
            if (solve_small(n, Mc, rhs, sol))
                return 0;
            for (int i = 0; i < n; i++)
                X[i][col] = sol[i];
        }
        double Adr[3][3];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) {
                double s = r == c ? 1.0 : 0.0;
                for (int j = 0; j < n; j++)
                    s -= P->r[J[j]][r] * X[j][c];
                Adr[r][c] = s;
            }
        const double lam = m->K - 2.0 * m->G / 3.0, g2 = 2.0 * m->G;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                Dp[3 * r + c] = lam * (Adr[r][0] + Adr[r][1] + Adr[r][2]) + g2 * Adr[r][c];
    }
    return 1;
}

/* Is v in the cone spanned by the correctors of planes J (n <= 4)? Tries every subset of 3 or
 * fewer generators (a small non-negative least-squares). */
static int in_cone(const mc_planes *P, const int *J, int n, const double v[3], double tol)
{
    const double vn = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (vn <= tol)
        return 1;
    for (int mask = 1; mask < (1 << n); mask++) {
        int S[3], ns = 0;
        for (int j = 0; j < n; j++)
            if (mask & (1 << j)) {
                if (ns == 3)
                    goto next;
                S[ns++] = J[j];
            }
        {
            /* least squares R_S x = v via the normal equations */
            double M[3][3], y[3], x[3];
            for (int i = 0; i < ns; i++) {
                for (int j = 0; j < ns; j++)
                    M[i][j] = P->r[S[i]][0] * P->r[S[j]][0] + P->r[S[i]][1] * P->r[S[j]][1] +
                              P->r[S[i]][2] * P->r[S[j]][2];
                y[i] = P->r[S[i]][0] * v[0] + P->r[S[i]][1] * v[1] + P->r[S[i]][2] * v[2];
            }
            if (solve_small(ns, M, y, x))
                goto next;
            double res[3] = {v[0], v[1], v[2]};
            int ok = 1;
            for (int j = 0; j < ns; j++) {
                if (x[j] < 0)
                    ok = 0;
                for (int d = 0; d < 3; d++)
                    res[d] -= x[j] * P->r[S[j]][d];
            }
            if (ok && sqrt(res[0] * res[0] + res[1] * res[1] + res[2] * res[2]) <= 1e-9 * vn)
                return 1;
        }
    next:;
    }
    return 0;
}

/* Principal return; str sorted descending. Returns 0 elastic, 1 plastic, 2 at the apex point. */
static int mc_return(const pm_material *m, const double str[3], double sig[3], double *Dp)
{
    mc_planes P;
    mc_setup(m, &P);
    const double scale = fabs(str[0]) + fabs(str[1]) + fabs(str[2]) + P.c[0] + (P.n > 3 ? fabs(P.c[3]) : 0);
    const double tol = 1e-13 * scale;
    int yielded = 0;
    for (int j = 0; j < P.n; j++)
        if (P.a[j][0] * str[0] + P.a[j][1] * str[1] + P.a[j][2] * str[2] - P.c[j] > tol)
            yielded = 1;
    if (!yielded) {
        memcpy(sig, str, 3 * sizeof(double));
        return 0;
    }
    static const int sets[6][2] = {{0, -1}, {3, -1}, {0, 1}, {0, 2}, {0, 3}, {3, 4}};
    for (int s = 0; s < 6; s++) {
        const int n = sets[s][1] < 0 ? 1 : 2;
        if (P.n == 3 && (sets[s][0] >= 3 || sets[s][1] >= 3))
            continue;
        if (try_active(&P, m, sets[s], n, str, tol, sig, Dp))
            return 1;
    }
    /* point returns: the stress is fixed, the tangent zero */
    if (Dp)
        memset(Dp, 0, 9 * sizeof(double));
    if (P.n == 3) {
        const double apex = m->derived[D_APEX];
        sig[0] = sig[1] = sig[2] = isfinite(apex) ? apex : (str[0] + str[1] + str[2]) / 3.0;
        return isfinite(apex) ? 2 : 1;
    }
    const double T = P.c[3], s3c = m->derived[D_K] * T - P.c[0];
    const double pts[3][3] = {{T, s3c, s3c}, {T, T, s3c}, {T, T, T}};
    static const int pj[3][4] = {{0, 2, 3, -1}, {0, 1, 3, 4}, {3, 4, 5, -1}};
    static const int pn[3] = {3, 4, 3};
    for (int k = 0; k < 3; k++) {
        const double v[3] = {str[0] - pts[k][0], str[1] - pts[k][1], str[2] - pts[k][2]};
        if (in_cone(&P, pj[k], pn[k], v, tol)) {
            memcpy(sig, pts[k], sizeof pts[k]);
            return 1;
        }
    }
    memcpy(sig, pts[2], sizeof pts[2]);
    return 1;
}

static int mc_update(const pm_material *m, const pm_material_step *in, double *state,
                     double stress[6], double *tangent)
{
    const double K = m->K, G = m->G;
    pm_trial t;
    pm_trial_state(in->F_incr, stress, K, G, &t);
    if (!isfinite(t.q + t.mean))
        return PM_ESIM;
    const int loose = m->param[P_LOOSE] == 1;
    if (loose && state[1] > 0) {
        /* the step's volume change first goes to the loose volume: all of an extension, of a
         * compression as much as there is */
        const double ev = t.deps[0] + t.deps[1] + t.deps[2], taken = ev > -state[1] ? ev : -state[1];
        for (int i = 0; i < 3; i++)
            t.sig[i] -= K * taken;
        state[1] += taken;
    }
    double str[3], V[9], sig[3], Dp[9] = {0};
    pm_eig_sym3(t.sig, str, V);
    const int rc = mc_return(m, str, sig, tangent ? Dp : NULL);
    if (loose && rc == 2) {
        const double beyond = ((str[0] + str[1] + str[2]) / 3.0 - sig[0]) / K;
        state[1] += beyond > 0 ? beyond : 0.0;
    }
    if (!rc) {
        memcpy(stress, t.sig, 6 * sizeof(double));
        if (tangent)
            pm_elastic_stiffness(K, G, tangent);
        return PM_OK;
    }
    pm_spectral_compose(sig, V, stress);
    /* plastic strain increment in principal axes: De^-1 (str - sig) */
    const double ds[3] = {str[0] - sig[0], str[1] - sig[1], str[2] - sig[2]};
    const double dm = (ds[0] + ds[1] + ds[2]) / 3.0;
    double dev = 0;
    for (int i = 0; i < 3; i++)
        dev += (ds[i] - dm) * (ds[i] - dm);
    /* |dev deps_p| = |dev dsig| / 2G */
    state[0] += sqrt(2.0 / 3.0 * dev) / (2.0 * G);
    if (tangent)
        pm_spectral_tangent(V, str, sig, Dp, G, tangent);
    return PM_OK;
}

const pm_material_ops pm_mohr_coulomb_ops = {
    .name = "mohr_coulomb",
    .elastic_pair = 1,
    .n_params = sizeof mc_params / sizeof mc_params[0],
    .params = mc_params,
    .n_state = 2,
    .init = mc_init,
    .init_state = NULL,
    .update = mc_update,
    .wave_speed = pm_material_elastic_wave_speed,
    .plastic_strain = pm_plastic_strain_state0,
    .strain_energy = pm_material_elastic_energy,
    .reduce_strength = pm_reduce_coulomb_strength,
};
