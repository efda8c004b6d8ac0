/*
 * Constitutive models: returns land on the yield surface (|f| <= 1e-10 relative), plastic flow
 * follows the potential, consistent tangents equal central finite differences of the stress update
 * (relative error <= 1e-6) on elastic, plane, edge and apex returns, viscoplastic overstress obeys
 * the flow law, N = 1 Newton equals the closed form, and rigid rotations rotate the stress exactly.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "material/material_internal.h"
#include "material/principal.h"
#include "pmech/error.h"
#include "pmech/material.h"

/* ---- helpers ---------------------------------------------------------------------------- */

typedef struct {
    const char *key;
    double value;
} kv;

/* A complete material: defaults, overrides, elastic pair (E, nu) and init. */
static pm_material make(const char *model, double E, double nu, const kv *kvs)
{
    pm_material m;
    memset(&m, 0, sizeof m);
    m.ops = pm_material_find(model);
    assert_non_null(m.ops);
    snprintf(m.name, sizeof m.name, "%s", model);
    m.density = 2000;
    for (size_t i = 0; i < m.ops->n_params; i++)
        m.param[i] = m.ops->params[i].def;
    for (; kvs && kvs->key; kvs++) {
        int i = pm_material_param_index(m.ops, kvs->key);
        assert_true(i >= 0);
        m.param[i] = kvs->value;
    }
    if (m.ops->elastic_pair)
        assert_int_equal(pm_material_set_elastic(&m, E, nu, NAN, NAN), PM_OK);
    if (m.ops->init) {
        int rc = m.ops->init(&m);
        if (rc)
            fprintf(stderr, "init: %s\n", pm_error_message());
        assert_int_equal(rc, PM_OK);
    }
    return m;
}

/* F_incr whose Hughes-Winget strain is exactly deps (no spin): (I + A)(I - A)^-1, A = deps/2. */
static void f_of(const double de[6], double F[9])
{
    const double A[9] = {0.5 * de[0], 0.25 * de[3], 0.25 * de[5], 0.25 * de[3], 0.5 * de[1],
                         0.25 * de[4], 0.25 * de[5], 0.25 * de[4], 0.5 * de[2]};
    double P[9], M[9];
    for (int i = 0; i < 9; i++) {
        P[i] = (i % 4 == 0) + A[i];
        M[i] = (i % 4 == 0) - A[i];
    }
    /* inverse of M by cofactors */
    double Mi[9];
    const double c0 = M[4] * M[8] - M[5] * M[7], c1 = M[5] * M[6] - M[3] * M[8], c2 = M[3] * M[7] - M[4] * M[6];
    const double r = 1.0 / (M[0] * c0 + M[1] * c1 + M[2] * c2);
    Mi[0] = c0 * r; Mi[1] = (M[2] * M[7] - M[1] * M[8]) * r; Mi[2] = (M[1] * M[5] - M[2] * M[4]) * r;
    Mi[3] = c1 * r; Mi[4] = (M[0] * M[8] - M[2] * M[6]) * r; Mi[5] = (M[2] * M[3] - M[0] * M[5]) * r;
    Mi[6] = c2 * r; Mi[7] = (M[1] * M[6] - M[0] * M[7]) * r; Mi[8] = (M[0] * M[4] - M[1] * M[3]) * r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            F[3 * i + j] = P[3 * i] * Mi[j] + P[3 * i + 1] * Mi[3 + j] + P[3 * i + 2] * Mi[6 + j];
}

static void mul3(const double A[9], const double B[9], double C[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

/* One update with strain increment de from (s0, st0); returns status. */
static int upd(const pm_material *m, const double s0[6], const double *st0, const double de[6],
               double dt, double s[6], double *st, double *D)
{
    pm_material_step in;
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    f_of(de, in.F_incr);
    memcpy(in.F_old, I, sizeof I);
    mul3(in.F_incr, in.F_old, in.F_new);
    in.dt = dt;
    memcpy(s, s0, 6 * sizeof(double));
    memcpy(st, st0, PM_MAT_MAX_STATE * sizeof(double));
    return m->ops->update(m, &in, st, s, D);
}

/* Max-norm relative error between the tangent and central differences of the update. */
static double fd_error(const pm_material *m, const double s0[6], const double *st0, const double de[6],
                       double dt)
{
    double D[36], s[6], st[PM_MAT_MAX_STATE];
    assert_int_equal(upd(m, s0, st0, de, dt, s, st, D), PM_OK);
    double Dfd[36], dmax = 0, emax = 0;
    for (int j = 0; j < 6; j++) {
        const double h = 1e-7; /* balances round-off (1e-16/h) and truncation */
        double dp[6], dm[6], sp[6], sm[6];
        memcpy(dp, de, sizeof dp);
        memcpy(dm, de, sizeof dm);
        dp[j] += h;
        dm[j] -= h;
        assert_int_equal(upd(m, s0, st0, dp, dt, sp, st, NULL), PM_OK);
        assert_int_equal(upd(m, s0, st0, dm, dt, sm, st, NULL), PM_OK);
        for (int i = 0; i < 6; i++)
            Dfd[6 * i + j] = (sp[i] - sm[i]) / (2 * h);
    }
    for (int i = 0; i < 36; i++) {
        dmax = fmax(dmax, fabs(Dfd[i]));
        emax = fmax(emax, fabs(Dfd[i] - D[i]));
    }
    double dnorm = 0;
    for (int i = 0; i < 36; i++)
        dnorm = fmax(dnorm, fabs(D[i]));
    if (dnorm == 0) /* zero tangent (perfectly plastic apex): relative to the elastic stiffness */
        dmax = m->K + 4.0 * m->G / 3.0;
    dmax = fmax(dmax, dnorm);
    if (getenv("PM_TEST_VERBOSE"))
        fprintf(stderr, "  %s: tangent relative error %.2e\n", m->ops->name, emax / dmax);
    if (emax > 1e-6 * dmax && getenv("PM_TEST_VERBOSE"))
        for (int i = 0; i < 6; i++) {
            for (int j = 0; j < 6; j++)
                fprintf(stderr, " %11.4g/%-11.4g", D[6 * i + j], Dfd[6 * i + j]);
            fprintf(stderr, "\n");
        }
    return emax / dmax;
}

/* Rotate a diagonal strain increment into general axes (rotation by angles a, b about z and x). */
static void rotated_increment(double e1, double e2, double e3, double a, double b, double de[6])
{
    const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b);
    const double Rz[9] = {ca, -sa, 0, sa, ca, 0, 0, 0, 1}, Rx[9] = {1, 0, 0, 0, cb, -sb, 0, sb, cb};
    double R[9], E[9] = {e1, 0, 0, 0, e2, 0, 0, 0, e3}, RE[9], RER[9], Rt[9];
    mul3(Rz, Rx, R);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Rt[3 * i + j] = R[3 * j + i];
    mul3(R, E, RE);
    mul3(RE, Rt, RER);
    de[0] = RER[0]; de[1] = RER[4]; de[2] = RER[8];
    de[3] = 2 * RER[1]; de[4] = 2 * RER[5]; de[5] = 2 * RER[2];
}

static const double zero_state[PM_MAT_MAX_STATE] = {0};

/* ---- Mohr-Coulomb ------------------------------------------------------------------------- */

static pm_material mc_material(double T)
{
    const kv p[] = {{"cohesion", 1e4}, {"friction_angle", 30}, {"dilatancy_angle", 10},
                    {"tension_cutoff", T}, {NULL, 0}};
    return make("mohr_coulomb", 2e7, 0.3, p);
}

/* f1 = k s1 - s3 - sc at the principal stresses of s, relative to the stress scale. */
static double mc_f_rel(const pm_material *m, const double s[6])
{
    double l[3], V[9];
    pm_eig_sym3(s, l, V);
    const double sp = sin(30 * M_PI / 180), k = (1 + sp) / (1 - sp);
    const double sc = 2 * 1e4 * cos(30 * M_PI / 180) / (1 - sp);
    (void)m;
    return (k * l[0] - l[2] - sc) / (fabs(l[0]) + fabs(l[2]) + sc);
}

typedef enum { R_ELASTIC, R_PLANE, R_EDGE_C, R_EDGE_E, R_APEX } mc_region;

/* Classify a returned principal state by which principal stresses coincide. */
static mc_region classify(const double s[6], const double str[6])
{
    double l[3], V[9], lt[3];
    pm_eig_sym3(s, l, V);
    pm_eig_sym3(str, lt, V);
    const double sc = fabs(l[0]) + fabs(l[1]) + fabs(l[2]) + 1;
    if (fabs(l[0] - lt[0]) + fabs(l[1] - lt[1]) + fabs(l[2] - lt[2]) < 1e-12 * sc)
        return R_ELASTIC;
    const int e12 = fabs(l[0] - l[1]) < 1e-9 * sc, e23 = fabs(l[1] - l[2]) < 1e-9 * sc;
    if (e12 && e23)
        return R_APEX;
    if (e12)
        return R_EDGE_C;
    if (e23)
        return R_EDGE_E;
    return R_PLANE;
}

static void mc_returns(void **unused)
{
    (void)unused;
    pm_material m = mc_material(NAN);
    pm_material le = make("linear_elastic", 2e7, 0.3, NULL);
    const double s0[6] = {-1e5, -1e5, -1e5, 0, 0, 0};
    /* principal strain increments chosen to land in each region (checked by classify) */
    const struct {
        double e[3];
        mc_region r;
    } cases[] = {
        {{-1e-4, 0, 1e-4}, R_ELASTIC},
        {{4e-3, 0, -5e-3}, R_PLANE},
        {{5e-3, 4.9e-3, -9.9e-3}, R_EDGE_C},
        {{9.9e-3, -4.9e-3, -5e-3}, R_EDGE_E},
        {{2e-2, 2e-2, 2e-2}, R_APEX},
    };
    const double sp = sin(M_PI / 6), k = (1 + sp) / (1 - sp), sps = sin(M_PI / 18);
    const double mm = (1 + sps) / (1 - sps);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double de[6], s[6], str[6], st[PM_MAT_MAX_STATE];
        rotated_increment(cases[c].e[0], cases[c].e[1], cases[c].e[2], 0.3, 0.7, de);
        assert_int_equal(upd(&le, s0, zero_state, de, 0, str, st, NULL), PM_OK);
        assert_int_equal(upd(&m, s0, zero_state, de, 0, s, st, NULL), PM_OK);
        const mc_region r = classify(s, str);
        if (r != cases[c].r)
            fail_msg("case %zu: region %d, expected %d", c, (int)r, (int)cases[c].r);
        if (r == R_ELASTIC) {
            assert_true(mc_f_rel(&m, s) < 0);
            assert_true(st[0] == 0.0);
        } else {
            assert_true(fabs(mc_f_rel(&m, s)) <= 1e-10);
            assert_true(st[0] > 0);
        }
        if (r == R_EDGE_C || r == R_EDGE_E) {
            /* plastic strain in the cone of the two potential gradients meeting on the edge:
             * compression edge (m, 0, -1), (0, m, -1); extension edge (m, 0, -1), (m, -1, 0) */
            double lt[3], V[9], ds[6], dp[3], ep[3];
            pm_eig_sym3(str, lt, V);
            for (int i = 0; i < 6; i++)
                ds[i] = str[i] - s[i];
            for (int a = 0; a < 3; a++) {
                const double v[3] = {V[a], V[3 + a], V[6 + a]};
                dp[a] = v[0] * (ds[0] * v[0] + ds[3] * v[1] + ds[5] * v[2]) +
                        v[1] * (ds[3] * v[0] + ds[1] * v[1] + ds[4] * v[2]) +
                        v[2] * (ds[5] * v[0] + ds[4] * v[1] + ds[2] * v[2]);
            }
            const double tr = dp[0] + dp[1] + dp[2];
            for (int a = 0; a < 3; a++)
                ep[a] = (dp[a] - tr / 3) / (2 * m.G) + tr / 3 / (3 * m.K);
            const double g1[3] = {mm, 0, -1};
            const double g2c[3] = {0, mm, -1}, g2e[3] = {mm, -1, 0};
            const double *g2 = r == R_EDGE_C ? g2c : g2e;
            /* least squares ep = a g1 + b g2 */
            const double A11 = g1[0] * g1[0] + g1[1] * g1[1] + g1[2] * g1[2];
            const double A12 = g1[0] * g2[0] + g1[1] * g2[1] + g1[2] * g2[2];
            const double A22 = g2[0] * g2[0] + g2[1] * g2[1] + g2[2] * g2[2];
            const double b1 = g1[0] * ep[0] + g1[1] * ep[1] + g1[2] * ep[2];
            const double b2 = g2[0] * ep[0] + g2[1] * ep[1] + g2[2] * ep[2];
            const double det = A11 * A22 - A12 * A12;
            const double ca = (A22 * b1 - A12 * b2) / det, cb = (A11 * b2 - A12 * b1) / det;
            const double en = sqrt(ep[0] * ep[0] + ep[1] * ep[1] + ep[2] * ep[2]);
            double res = 0;
            for (int a = 0; a < 3; a++)
                res += pow(ep[a] - ca * g1[a] - cb * g2[a], 2);
            assert_true(sqrt(res) <= 1e-8 * en);
            assert_true(ca >= -1e-10 * en && cb >= -1e-10 * en);
        }
        if (r == R_PLANE) {
            /* plastic strain De^-1 (str - s) along the potential gradient (m, 0, -1) in the trial
             * principal axes */
            double lt[3], V[9], ds[6];
            pm_eig_sym3(str, lt, V);
            for (int i = 0; i < 6; i++)
                ds[i] = str[i] - s[i];
            double dp[3];
            for (int a = 0; a < 3; a++) {
                const double v[3] = {V[a], V[3 + a], V[6 + a]};
                dp[a] = v[0] * (ds[0] * v[0] + ds[3] * v[1] + ds[5] * v[2]) +
                        v[1] * (ds[3] * v[0] + ds[1] * v[1] + ds[4] * v[2]) +
                        v[2] * (ds[5] * v[0] + ds[4] * v[1] + ds[2] * v[2]);
            }
            /* invert the isotropic De in principal space */
            const double tr = dp[0] + dp[1] + dp[2];
            double ep[3];
            for (int a = 0; a < 3; a++)
                ep[a] = (dp[a] - tr / 3) / (2 * m.G) + tr / 3 / (3 * m.K);
            const double n = sqrt(ep[0] * ep[0] + ep[1] * ep[1] + ep[2] * ep[2]);
            const double bn = sqrt(mm * mm + 1);
            assert_true(fabs(ep[0] / n - mm / bn) < 1e-8);
            assert_true(fabs(ep[1] / n) < 1e-8);
            assert_true(fabs(ep[2] / n + 1 / bn) < 1e-8);
        }
        if (r == R_APEX) {
            double l[3], V[9];
            pm_eig_sym3(s, l, V);
            assert_true(fabs(l[0] - 1e4 * sqrt(3.0)) < 1e-8 * 1e4); /* c cot 30 */
        }
        const double err = fd_error(&m, s0, zero_state, de, 0);
        if (!(err <= 1e-6))
            fail_msg("MC case %zu: tangent error %g", c, err);
    }
    (void)k;
}

static void mc_tension_cutoff(void **unused)
{
    (void)unused;
    pm_material m = mc_material(5e3);
    const double s0[6] = {0, 0, 0, 0, 0, 0};
    /* uniaxial tension beyond the cut-off: the largest principal stress is held at T */
    double de[6], s[6], st[PM_MAT_MAX_STATE];
    rotated_increment(2e-3, 0, 0, 0.2, 0.1, de);
    assert_int_equal(upd(&m, s0, zero_state, de, 0, s, st, NULL), PM_OK);
    double l[3], V[9];
    pm_eig_sym3(s, l, V);
    assert_true(fabs(l[0] - 5e3) <= 1e-10 * 5e3);
    assert_true(st[0] > 0);
    double err = fd_error(&m, s0, zero_state, de, 0);
    if (!(err <= 1e-6))
        fail_msg("cut-off plane tangent error %g", err);
    /* equibiaxial / triaxial tension: to the tension apex */
    rotated_increment(2e-3, 2e-3, 2e-3, 0.2, 0.1, de);
    assert_int_equal(upd(&m, s0, zero_state, de, 0, s, st, NULL), PM_OK);
    pm_eig_sym3(s, l, V);
    for (int a = 0; a < 3; a++)
        assert_true(fabs(l[a] - 5e3) <= 1e-10 * 5e3);
}

/*
 * Mohr-Coulomb's loose volume (stress_free_dilation = 1), c = 0, phi = 30, psi = 0, from zero stress
 * (strain increments given exactly through f_of). An isotropic extension ev = 3e-3 goes beyond the
 * apex: the stress stays zero and state[1] holds ev. A compression of ev / 2 takes half of it back,
 * still without stress (the option off: the same step gives p = -K ev / 2 at once). A further
 * compression of ev takes the other half, and the rest, ev / 2, is elastic: p = -K ev / 2, state[1]
 * back to zero. Judged to 1e-10 relative (the sums are exact up to a few roundings). A shear step on
 * a loose point stays at zero stress and leaves the loose volume as it was.
 */
static void mc_loose_volume(void **unused)
{
    (void)unused;
    const kv on[] = {{"cohesion", 0}, {"friction_angle", 30}, {"dilatancy_angle", 0}, {"stress_free_dilation", 1},
                     {NULL, 0}};
    const kv off[] = {{"cohesion", 0}, {"friction_angle", 30}, {"dilatancy_angle", 0}, {NULL, 0}};
    pm_material m = make("mohr_coulomb", 1e7, 0.3, on), m0 = make("mohr_coulomb", 1e7, 0.3, off);
    const double K = m.K, ev = 3e-3, s0[6] = {0, 0, 0, 0, 0, 0};
    double s[6], st[PM_MAT_MAX_STATE], s1[6], st1[PM_MAT_MAX_STATE];
    const double ext[6] = {ev / 3, ev / 3, ev / 3, 0, 0, 0}, half[6] = {-ev / 6, -ev / 6, -ev / 6, 0, 0, 0};
    const double full[6] = {-ev / 3, -ev / 3, -ev / 3, 0, 0, 0}, shear[6] = {0, 0, 0, 2e-3, 0, 0};
    assert_int_equal(upd(&m, s0, zero_state, ext, 0, s, st, NULL), PM_OK);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(s[i]) <= 1e-10 * K * ev);
    assert_true(fabs(st[1] - ev) <= 1e-10 * ev);
    assert_int_equal(upd(&m, s, st, shear, 0, s1, st1, NULL), PM_OK);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(s1[i]) <= 1e-10 * K * ev);
    assert_true(fabs(st1[1] - ev) <= 1e-10 * ev);
    assert_int_equal(upd(&m, s, st, half, 0, s1, st1, NULL), PM_OK);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(s1[i]) <= 1e-10 * K * ev);
    assert_true(fabs(st1[1] - ev / 2) <= 1e-10 * ev);
    memcpy(s, s1, sizeof s);
    memcpy(st, st1, sizeof st);
    assert_int_equal(upd(&m, s, st, full, 0, s1, st1, NULL), PM_OK);
    for (int i = 0; i < 3; i++)
        assert_true(fabs(s1[i] + K * ev / 2) <= 1e-10 * K * ev);
    assert_true(fabs(st1[1]) <= 1e-10 * ev);
    /* without the option the dilated point is stressed by the first compression */
    assert_int_equal(upd(&m0, s0, zero_state, ext, 0, s, st, NULL), PM_OK);
    assert_int_equal(upd(&m0, s, st, half, 0, s1, st1, NULL), PM_OK);
    for (int i = 0; i < 3; i++)
        assert_true(fabs(s1[i] + K * ev / 2) <= 1e-10 * K * ev);
}

/* Random trial states (with and without a tension cut-off): every return is admissible and lies
 * on the surface, and returning the returned stress again changes nothing. */
static void mc_random_returns(void **unused)
{
    (void)unused;
    unsigned seed = 12345;
    for (int cut = 0; cut < 2; cut++) {
        pm_material m = mc_material(cut ? 3e3 : NAN);
        const double sp = sin(M_PI / 6), k = (1 + sp) / (1 - sp);
        const double sc = 2 * 1e4 * cos(M_PI / 6) / (1 - sp), T = cut ? 3e3 : INFINITY;
        int plastic = 0;
        for (int it = 0; it < 4000; it++) {
            double e[3], de[6], s[6], st[PM_MAT_MAX_STATE], s2[6], st2[PM_MAT_MAX_STATE];
            for (int i = 0; i < 3; i++) {
                seed = seed * 1103515245u + 12345u;
                e[i] = ((seed >> 8) / 16777216.0 - 0.5) * 2e-2;
            }
            seed = seed * 1103515245u + 12345u;
            const double a = (seed >> 8) / 16777216.0 * 6.3;
            rotated_increment(e[0], e[1], e[2], a, 0.5 * a, de);
            const double s0[6] = {-5e4, -8e4, -6e4, 1e4, 0, 0};
            assert_int_equal(upd(&m, s0, zero_state, de, 0, s, st, NULL), PM_OK);
            double l[3], V[9];
            pm_eig_sym3(s, l, V);
            const double scale = fabs(l[0]) + fabs(l[2]) + sc;
            const double f = k * l[0] - l[2] - sc;
            if (!(f <= 1e-10 * scale) || !(l[0] - T <= 1e-10 * scale))
                fail_msg("cut %d it %d: f = %g, s1 - T = %g", cut, it, f / scale, (l[0] - T) / scale);
            if (st[0] > 0) {
                plastic++;
                assert_true(fabs(f) <= 1e-10 * scale || fabs(l[0] - T) <= 1e-10 * scale);
            }
            const double z[6] = {0};
            assert_int_equal(upd(&m, s, st, z, 0, s2, st2, NULL), PM_OK);
            for (int i = 0; i < 6; i++)
                assert_true(fabs(s2[i] - s[i]) <= 1e-9 * scale);
        }
        assert_true(plastic > 1000);
    }
}

/* ---- Drucker-Prager ------------------------------------------------------------------------ */

static double dp_f_rel(const pm_material *m, const double s[6], const double *st)
{
    double dev[6], mean;
    const double q = pm_voigt_split(s, dev, &mean);
    const double s3 = sqrt(3.0);
    const double alpha = m->derived[0], beta = m->derived[1];
    const double k = fmax(0, s3 * alpha + s3 * beta * m->param[4] * st[1] + m->param[5] * st[0]);
    return (q + s3 * beta * mean - k) / (q + fabs(mean) + k + 1);
}

static void dp_returns(void **unused)
{
    (void)unused;
    const kv p[] = {{"cohesion", 1e4}, {"friction_angle", 30}, {"dilatancy_angle", 10},
                    {"cone_fit", 0.3}, {"bulk_hardening", 2e5}, {"shear_hardening", 5e5}, {NULL, 0}};
    pm_material m = make("drucker_prager", 2e7, 0.3, p);
    pm_material le = make("linear_elastic", 2e7, 0.3, NULL);
    const double s0[6] = {-1e5, -1.2e5, -0.9e5, 1e4, 0, 0};
    const double st0[PM_MAT_MAX_STATE] = {0.01, 0.002};
    const double es[3][3] = {{-1e-4, 0, 1e-4}, {8e-3, 0, -1e-2}, {2e-2, 2e-2, 2e-2}};
    for (int c = 0; c < 3; c++) {
        double de[6], s[6], str[6], st[PM_MAT_MAX_STATE];
        rotated_increment(es[c][0], es[c][1], es[c][2], 0.4, 0.2, de);
        assert_int_equal(upd(&le, s0, st0, de, 0, str, st, NULL), PM_OK);
        assert_int_equal(upd(&m, s0, st0, de, 0, s, st, NULL), PM_OK);
        const double q = pm_voigt_q(s);
        if (c == 0) {
            assert_true(st[0] == st0[0]);
            assert_true(dp_f_rel(&m, s, st) < 0);
        } else {
            assert_true(st[0] > st0[0]);
            if (!(fabs(dp_f_rel(&m, s, st)) <= 1e-10))
                fail_msg("DP case %d: f = %g relative, q %g mean %g ep %g vp %g", c,
                         dp_f_rel(&m, s, st), pm_voigt_q(s), pm_voigt_mean(s), st[0], st[1]);
            /* flow rule: dv_p = sqrt3 b de_p (eq. 38) */
            assert_true(fabs((st[1] - st0[1]) - sqrt(3.0) * m.derived[2] * (st[0] - st0[0])) <=
                        1e-12 * (st[0] - st0[0]) || c == 2);
            if (c == 1) {
                /* deviatoric plastic flow along the trial deviator (radial return) */
                double ds[6], dt[6], mean;
                pm_voigt_split(str, dt, &mean);
                pm_voigt_split(s, ds, &mean);
                const double qt = pm_voigt_q(str);
                for (int i = 0; i < 6; i++)
                    assert_true(fabs(ds[i] / q - dt[i] / qt) < 1e-10);
            }
        }
        if (c == 2)
            assert_true(q < 1e-9 * fabs(pm_voigt_mean(s)) + 1e-6); /* apex */
        const double err = fd_error(&m, s0, st0, de, 0);
        if (!(err <= 1e-6))
            fail_msg("DP case %d: tangent error %g", c, err);
    }
}

/* ---- von Mises ------------------------------------------------------------------------------ */

static void vm_returns(void **unused)
{
    (void)unused;
    const kv p[] = {{"yield_stress", 2e5}, {"hardening_modulus", 1e6}, {NULL, 0}};
    pm_material m = make("von_mises", 2e8, 0.3, p);
    const double s0[6] = {1e4, -2e4, 0, 3e4, 0, 0};
    const double st0[PM_MAT_MAX_STATE] = {0.01};
    const double es[2][3] = {{-1e-4, 0, 1e-4}, {4e-3, 0, -5e-3}};
    for (int c = 0; c < 2; c++) {
        double de[6], s[6], st[PM_MAT_MAX_STATE];
        rotated_increment(es[c][0], es[c][1], es[c][2], 0.4, 0.2, de);
        assert_int_equal(upd(&m, s0, st0, de, 0, s, st, NULL), PM_OK);
        const double f = pm_voigt_q(s) - (2e5 + 1e6 * st[0]);
        if (c == 0)
            assert_true(f < 0 && st[0] == st0[0]);
        else
            assert_true(fabs(f) <= 1e-10 * 2e5 && st[0] > st0[0]);
        const double err = fd_error(&m, s0, st0, de, 0);
        if (!(err <= 1e-6))
            fail_msg("VM case %d: tangent error %g", c, err);
    }
}

/* ---- viscoplastic Drucker-Prager ------------------------------------------------------------- */

static void vp_flow_law(void **unused)
{
    (void)unused;
    const double Ns[3] = {1.0, 2.5, 0.6};
    for (int in = 0; in < 3; in++) {
        const kv p[] = {{"friction_angle", 25}, {"viscosity", 50}, {"exponent", Ns[in]}, {NULL, 0}};
        pm_material m = make("viscoplastic_drucker_prager", 1e6, 0.3, p);
        const double s0[6] = {-1e3, -1.5e3, -1e3, 2e2, 0, 0};
        const double dt = 1e-3;
        const double es[2][3] = {{-1e-5, 0, 1e-5}, {4e-3, 0, -6e-3}};
        for (int c = 0; c < 2; c++) {
            double de[6], s[6], st[PM_MAT_MAX_STATE];
            rotated_increment(es[c][0], es[c][1], es[c][2], 0.4, 0.2, de);
            assert_int_equal(upd(&m, s0, zero_state, de, dt, s, st, NULL), PM_OK);
            const double pr = -pm_voigt_mean(s), q = pm_voigt_q(s), mm = m.derived[0];
            if (c == 0) {
                assert_true(st[0] == 0 && q < mm * pr);
            } else {
                /* backward Euler: de = gamma dt ((q - m p)/(m p))^N at the end of the step */
                const double law = 50 * dt * pow((q - mm * pr) / (mm * pr), Ns[in]);
                if (!(fabs(st[0] - law) <= 1e-10 * st[0]))
                    fail_msg("N = %g: de = %.15g, flow law %.15g", Ns[in], st[0], law);
                assert_true(q > mm * pr); /* overstress is positive */
            }
            const double err = fd_error(&m, s0, zero_state, de, dt);
            if (!(err <= 1e-6))
                fail_msg("VP N=%g case %d: tangent error %g", Ns[in], c, err);
        }
    }
}

static void vp_newton_equals_closed_form(void **unused)
{
    (void)unused;
    const double qe = 3e4, p = 2e4, mm = 0.9, G = 4e5, gdt = 0.05;
    double d1[3], d2[3];
    const double x1 = pm_vp_solve(qe, p, mm, G, gdt, 1.0, 0, d1);
    const double x2 = pm_vp_solve(qe, p, mm, G, gdt, 1.0, 1, d2);
    assert_true(fabs(x1 - (qe - mm * p) / (3 * G + mm * p / gdt)) <= 1e-15 * x1);
    assert_true(fabs(x1 - x2) <= 1e-12 * x1);
    for (int i = 0; i < 3; i++)
        assert_true(fabs(d1[i] - d2[i]) <= 1e-10 * fabs(d1[i]));
}

static void vp_no_tension(void **unused)
{
    (void)unused;
    const kv p[] = {{"friction_angle", 25}, {"viscosity", 50}, {NULL, 0}};
    pm_material m = make("viscoplastic_drucker_prager", 1e6, 0.3, p);
    /* a stress-free point pulled apart stays stress-free; its deviatoric strain is all plastic */
    const double s0[6] = {0, 0, 0, 0, 0, 0};
    double de[6], s[6], st[PM_MAT_MAX_STATE], D[36];
    rotated_increment(1e-3, -2e-4, 5e-4, 0.3, 0.1, de);
    assert_int_equal(upd(&m, s0, zero_state, de, 1e-3, s, st, D), PM_OK);
    for (int i = 0; i < 6; i++)
        assert_true(s[i] == 0.0);
    for (int i = 0; i < 36; i++)
        assert_true(D[i] == 0.0);
    assert_true(fabs(st[0] - pm_equiv_dev_strain(de)) <= 1e-12 * st[0]);
    /* p = 0 exactly (no confinement, pure shear): stress-free too */
    rotated_increment(1e-3, -1e-3, 0, 0.3, 0.1, de);
    assert_int_equal(upd(&m, s0, zero_state, de, 1e-3, s, st, NULL), PM_OK);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(s[i]) <= 1e-9);
    /* confined and compressed: a regular stress */
    rotated_increment(-1e-3, -1e-3, -1e-3, 0.3, 0.1, de);
    assert_int_equal(upd(&m, s0, zero_state, de, 1e-3, s, st, NULL), PM_OK);
    assert_true(-pm_voigt_mean(s) > 0);
}

/* ---- granular -------------------------------------------------------------------------------- */

static pm_material granular(void)
{
    const kv p[] = {{"kappa", 0.02}, {"void_ratio", 0.9}, {"reference_pressure", 600},
                    {"bulk_viscosity", 1e4}, {"poisson_ratio", 0.3}, {"friction_angle", 30},
                    {"viscosity", 1e4}, {"exponent", 1}, {NULL, 0}};
    return make("granular", NAN, NAN, p);
}

/* The step bound of the granular model adds the bulk viscosity's explicit limit to its wave speed: at
 * seed 004's mu = 1e4 Pa s, rho = 1500 and 50 mm cells, 4 mu / (rho h) = 533 m/s against a P-wave of a
 * few m/s at p0, so a step from the wave speed alone would be 60 times too long. */
static void granular_step_speed(void **unused)
{
    (void)unused;
    pm_material m = granular();
    double st[PM_MAT_MAX_STATE] = {0};
    const double c = m.ops->wave_speed(&m, st, 1500), h = 0.05;
    assert_true(c > 1 && c < 20);
    const double s = pm_material_signal_speed(&m, st, 1500, h);
    assert_true(fabs(s - (c + 4 * 1e4 / (1500 * h))) <= 1e-12 * s);
    /* halving the cell doubles the viscous part */
    assert_true(fabs(pm_material_signal_speed(&m, st, 1500, h / 2) - (c + 8 * 1e4 / (1500 * h))) <= 1e-12 * s);
    /* models without a rate viscosity: the wave speed alone */
    pm_material e = make("linear_elastic", 1e7, 0.3, NULL);
    assert_true(pm_material_signal_speed(&e, NULL, 1000, h) == pm_material_elastic_wave_speed(&e, NULL, 1000));
}

static void granular_law(void **unused)
{
    (void)unused;
    pm_material m = granular();
    const double s0[6] = {-2e3, -3e3, -2e3, 300, 0, 0};
    double st0[PM_MAT_MAX_STATE] = {0};
    m.ops->init_state(&m, s0, st0);
    const double dt = 1e-4;
    /* the initial state's elastic pressure equals the given pressure */
    const double A = 1.9 / 0.02;
    assert_true(fabs(600 * exp(A * (1 - exp(st0[1]))) - 7e3 / 3) <= 1e-10 * 7e3 / 3);
    const double es[3][3] = {{-1e-6, -1e-6, 1e-6}, {4e-4, 1e-5, -6e-4}, {1e-5, -2e-5, 3e-6}};
    for (int c = 0; c < 3; c++) {
        double de[6], s[6], st[PM_MAT_MAX_STATE];
        rotated_increment(es[c][0], es[c][1], es[c][2], 0.4, 0.2, de);
        assert_int_equal(upd(&m, s0, st0, de, dt, s, st, NULL), PM_OK);
        const double ev = st0[1] + de[0] + de[1] + de[2];
        const double dv = de[0] + de[1] + de[2];
        const double pexp = 600 * exp(A * (1 - exp(ev))) + (dv < 0 ? -1e4 * dv / dt : 0);
        const double pr = -pm_voigt_mean(s), q = pm_voigt_q(s);
        assert_true(fabs(pr - pexp) <= 1e-10 * pexp); /* eq. 24 (exp amplifies round-off) */
        assert_true(pr > 0);
        const double mm = m.derived[0];
        if (st[0] > 0) {
            const double law = 1e4 * dt * (q - mm * pr) / (mm * pr);
            if (!(fabs(st[0] - law) <= 1e-10 * st[0]))
                fail_msg("granular case %d: de %.15g law %.15g", c, st[0], law);
        } else {
            assert_true(q <= mm * pr);
        }
        const double err = fd_error(&m, s0, st0, de, dt);
        if (!(err <= 1e-6))
            fail_msg("granular case %d: tangent error %g", c, err);
    }
}

/* The loosest state e_max = 1 (seed 004's e0 = 0.9, kappa = 0.02): eps_v,max = ln(2 / 1.9). Grains pulled
 * apart beyond it are stress-free and keep eps_v,max; compression from there carries the log law's
 * pressure and the bulk viscosity; a point still looser than e_max at the step's end (the density from
 * positions put it there) has no viscous pressure. Exact values: the law is evaluated in closed form. */
static void granular_loosest_state(void **unused)
{
    (void)unused;
    const kv p[] = {{"kappa", 0.02}, {"void_ratio", 0.9}, {"reference_pressure", 600},
                    {"bulk_viscosity", 1e4}, {"poisson_ratio", 0.3}, {"friction_angle", 30},
                    {"viscosity", 1e4}, {"exponent", 1}, {"max_void_ratio", 1.0}, {NULL, 0}};
    pm_material m = make("granular", NAN, NAN, p);
    const double A = 1.9 / 0.02, evmax = log(2.0 / 1.9), dt = 1e-4;
    const double s0[6] = {-600, -600, -600, 0, 0, 0};
    double st0[PM_MAT_MAX_STATE] = {0}, de[6] = {0}, s[6], st[PM_MAT_MAX_STATE];
    /* expansion from e0 by 10 % (e = 1.1): the log law's pressure at e = 1.1 (0.4 Pa, below the 4 Pa
     * of e_max), and the state held at e_max */
    st0[1] = 0;
    de[0] = de[1] = de[2] = 0.1 / 3;
    assert_int_equal(upd(&m, s0, st0, de, dt, s, st, NULL), PM_OK);
    assert_true(st[1] == evmax);
    const double pexp = 600 * exp(A * (1 - exp(0.1)));
    assert_true(fabs(-pm_voigt_mean(s) - pexp) <= 1e-10 * pexp);
    assert_true(-pm_voigt_mean(s) < 600 * exp(A * (1 - 2.0 / 1.9)));
    /* compression from e_max: log law plus mu times the rate */
    st0[1] = evmax;
    de[0] = de[1] = de[2] = -1e-3 / 3;
    assert_int_equal(upd(&m, s0, st0, de, dt, s, st, NULL), PM_OK);
    const double pc = 600 * exp(A * (1 - exp(evmax - 1e-3))) + 1e4 * 1e-3 / dt;
    assert_true(fabs(st[1] - (evmax - 1e-3)) <= 1e-14);
    assert_true(fabs(-pm_voigt_mean(s) - pc) <= 1e-12 * pc);
    /* compression of a point still looser than e_max at the step's end: no viscous part */
    st0[1] = 0.5;
    assert_int_equal(upd(&m, s0, st0, de, dt, s, st, NULL), PM_OK);
    const double pl = 600 * exp(A * (1 - exp(0.5 - 1e-3)));
    assert_true(fabs(-pm_voigt_mean(s) - pl) <= 1e-12 * pl + 1e-300);
    assert_true(-pm_voigt_mean(s) < 1e-6);
    assert_true(st[1] == evmax);
    /* the density from positions loosens a point it shows apart, looser than e_max (rho / rho_ref =
     * 0.5: eps_v = ln 2); it neither loosens a point inside the skeleton (0.97: eps_v = 0.030, under
     * eps_v,max = 0.051, against a point at -0.02) nor densifies one (1.05) */
    assert_non_null(m.ops->density_state);
    st0[1] = -0.02;
    m.ops->density_state(&m, 0.5, st0);
    assert_true(fabs(st0[1] - log(2.0)) <= 1e-15);
    st0[1] = -0.02;
    m.ops->density_state(&m, 0.97, st0);
    assert_true(st0[1] == -0.02);
    st0[1] = -0.02;
    m.ops->density_state(&m, 1.05, st0);
    assert_true(st0[1] == -0.02);
    /* without max_void_ratio expansion is unbounded as before */
    pm_material u = granular();
    st0[1] = 0;
    de[0] = de[1] = de[2] = 0.1 / 3;
    assert_int_equal(upd(&u, s0, st0, de, dt, s, st, NULL), PM_OK);
    assert_true(fabs(st[1] - 0.1) <= 1e-12);
}

/* ---- elastic models --------------------------------------------------------------------------- */

static void linear_elastic_tangent(void **unused)
{
    (void)unused;
    pm_material m = make("linear_elastic", 2e7, 0.3, NULL);
    const double s0[6] = {-1e5, 2e4, -3e4, 1e4, 2e3, -5e3};
    double de[6];
    rotated_increment(1e-3, -2e-3, 5e-4, 0.3, 0.9, de);
    const double err = fd_error(&m, s0, zero_state, de, 0);
    assert_true(err <= 1e-6);
}

/* neo-Hookean: J c : deps = d tau - deps tau - tau deps for a spin-free perturbation of F_new. */
static void neo_hookean_tangent(void **unused)
{
    (void)unused;
    pm_material m = make("neo_hookean", 1e6, 0.35, NULL);
    const double F[9] = {1.2, 0.3, 0.05, -0.1, 0.8, 0.02, 0.04, -0.03, 1.1};
    const double J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
                     F[2] * (F[3] * F[7] - F[4] * F[6]);
    pm_material_step in;
    memset(&in, 0, sizeof in);
    memcpy(in.F_new, F, sizeof F);
    double s[6], D[36];
    assert_int_equal(m.ops->update(&m, &in, NULL, s, D), PM_OK);
    double emax = 0, dmax = 0;
    for (int j = 0; j < 6; j++) {
        const double h = 1e-6;
        double tau[2][6];
        for (int sgn = 0; sgn < 2; sgn++) {
            double e[6] = {0}, Fi[9];
            e[j] = sgn ? -h : h;
            f_of(e, Fi);
            mul3(Fi, F, in.F_new);
            double sp[6];
            assert_int_equal(m.ops->update(&m, &in, NULL, sp, NULL), PM_OK);
            const double Jp = J * (Fi[0] * (Fi[4] * Fi[8] - Fi[5] * Fi[7]) - Fi[1] * (Fi[3] * Fi[8] - Fi[5] * Fi[6]) +
                                   Fi[2] * (Fi[3] * Fi[7] - Fi[4] * Fi[6]));
            for (int i = 0; i < 6; i++)
                tau[sgn][i] = Jp * sp[i];
        }
        /* unit perturbation E_j (tensor), with tau from s */
        double E[9] = {0};
        const int map[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
        if (j < 3)
            E[4 * j] = 1;
        else {
            E[3 * map[j][0] + map[j][1]] = 0.5;
            E[3 * map[j][1] + map[j][0]] = 0.5;
        }
        const double T[9] = {J * s[0], J * s[3], J * s[5], J * s[3], J * s[1], J * s[4], J * s[5], J * s[4], J * s[2]};
        double ET[9], TE[9];
        mul3(E, T, ET);
        mul3(T, E, TE);
        for (int i = 0; i < 6; i++) {
            const int a = map[i][0], b = map[i][1];
            const double dtau = (tau[0][i] - tau[1][i]) / (2 * h);
            const double c = (dtau - ET[3 * a + b] - TE[3 * a + b]) / J;
            emax = fmax(emax, fabs(c - D[6 * i + j]));
            dmax = fmax(dmax, fabs(D[6 * i + j]));
        }
    }
    if (!(emax <= 1e-6 * dmax))
        fail_msg("neo-Hookean tangent error %g", emax / dmax);
}

/* ---- rigid rotation ----------------------------------------------------------------------- */

static void rigid_rotation_all_models(void **unused)
{
    (void)unused;
    const kv vm[] = {{"yield_stress", 1e5}, {NULL, 0}};
    const kv mc[] = {{"cohesion", 1e4}, {"friction_angle", 30}, {NULL, 0}};
    const kv dp[] = {{"cohesion", 1e4}, {"friction_angle", 30}, {NULL, 0}};
    const kv vp[] = {{"friction_angle", 30}, {"viscosity", 50}, {NULL, 0}};
    pm_material mats[6] = {
        make("linear_elastic", 2e7, 0.3, NULL), make("von_mises", 2e7, 0.3, vm),
        make("mohr_coulomb", 2e7, 0.3, mc),     make("drucker_prager", 2e7, 0.3, dp),
        make("viscoplastic_drucker_prager", 2e7, 0.3, vp), granular(),
    };
    for (int k = 0; k < 6; k++) {
        pm_material *m = &mats[k];
        /* a stressed point on (or near) its yield surface */
        double s[6] = {-1.0e5, -2.5e5, -1.5e5, 4e4, 0, 0};
        if (k == 1) {
            const double sc = 0.999 * 1e5 / pm_voigt_q(s);
            for (int i = 0; i < 6; i++)
                s[i] *= sc;
        }
        if (k == 5)
            for (int i = 0; i < 6; i++)
                s[i] *= 0.01;
        double st[PM_MAT_MAX_STATE] = {0};
        if (m->ops->init_state)
            m->ops->init_state(m, s, st);
        const double s0[6] = {s[0], s[1], s[2], s[3], s[4], s[5]};
        const double ep0 = m->ops->plastic_strain ? m->ops->plastic_strain(m, st) : 0;
        const int n = 100;
        const double th = 0.5 * M_PI / n;
        pm_material_step in;
        memset(&in, 0, sizeof in);
        const double R[9] = {cos(th), -sin(th), 0, sin(th), cos(th), 0, 0, 0, 1};
        double F[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        for (int i = 0; i < n; i++) {
            memcpy(in.F_incr, R, sizeof R);
            memcpy(in.F_old, F, sizeof F);
            mul3(R, F, in.F_new);
            memcpy(F, in.F_new, sizeof F);
            in.dt = 1e-3;
            assert_int_equal(m->ops->update(m, &in, st, s, NULL), PM_OK);
        }
        /* rotation by 90 degrees about z: xx <-> yy, xy -> -xy */
        const double expect[6] = {s0[1], s0[0], s0[2], -s0[3], 0, 0};
        const double sc = fabs(s0[0]) + fabs(s0[1]) + fabs(s0[2]);
        for (int i = 0; i < 6; i++)
            if (!(fabs(s[i] - expect[i]) <= 1e-8 * sc))
                fail_msg("%s: component %d = %.12g, expected %.12g", m->ops->name, i, s[i], expect[i]);
        const double p0 = pm_voigt_mean(s0), p1 = pm_voigt_mean(s);
        const double q0 = pm_voigt_q(s0), q1 = pm_voigt_q(s);
        assert_true(fabs(p1 - p0) <= 1e-8 * fabs(p0));
        assert_true(fabs(q1 - q0) <= 1e-8 * q0);
        const double ep1 = m->ops->plastic_strain ? m->ops->plastic_strain(m, st) : 0;
        if (!(ep1 == ep0))
            fail_msg("%s: plastic strain %g after a rigid rotation", m->ops->name, ep1 - ep0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mc_returns),
        cmocka_unit_test(mc_tension_cutoff),
        cmocka_unit_test(mc_loose_volume),
        cmocka_unit_test(mc_random_returns),
        cmocka_unit_test(dp_returns),
        cmocka_unit_test(vm_returns),
        cmocka_unit_test(vp_flow_law),
        cmocka_unit_test(vp_newton_equals_closed_form),
        cmocka_unit_test(vp_no_tension),
        cmocka_unit_test(granular_law),
        cmocka_unit_test(granular_step_speed),
        cmocka_unit_test(granular_loosest_state),
        cmocka_unit_test(linear_elastic_tangent),
        cmocka_unit_test(neo_hookean_tangent),
        cmocka_unit_test(rigid_rotation_all_models),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
