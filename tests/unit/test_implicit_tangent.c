/* The implicit solver's assembled tangent is the derivative of its residual: K = -d r / d du,
 * checked column by column against central finite differences of the residual at a deformed,
 * stressed iterate, for plane strain, plane stress and axisymmetric neo-Hookean bodies (a
 * hyperelastic model, whose spatial tangent makes the linearisation exact) with and without
 * inertia. Tolerance 1e-6 of the column's largest entry: the differences use a step of 1e-7 of the
 * cell size, whose truncation and round-off errors are both well below that. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"
#include "solver/implicit_internal.h"
#include "solver/meshfree_internal.h"

static const char *CASE_FMT =
    "{ \"dimension\": 2, \"formulation\": \"%s\", \"method\": \"%s\", \"shape_function\": \"%s\","
    "  \"analysis\": { \"type\": \"%s\", \"end_time\": 1.0, \"dt\": 0.01, \"gravity\": [0, -9.81] },"
    "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [2, 1], \"cells\": [8, 4], \"element\": \"quad4\" },"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"neo_hookean\", \"density\": 1000,"
    "                     \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],"
    "  \"bodies\": [ { \"name\": \"b\", \"material\": \"m\", \"velocity\": [0.1, -0.2],"
    "                  \"shape\": { \"type\": \"rectangle\", \"min\": [0.25, 0], \"max\": [1.55, 0.6] } } ],"
    "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"y\"] } ] }";

static void check_tangent_of(const char *formulation, const char *type, const char *method, const char *shape)
{
    char text[2048];
    snprintf(text, sizeof text, CASE_FMT, formulation, method, shape, type);
    pm_case c;
    assert_int_equal(pm_case_load_buffer(text, strlen(text), "tangent.json", &c), 0);
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(&c, &s, 1), 0);
    assert_int_equal(pm_implicit_ws_alloc(s), 0);
    pm_implicit_ws *w = s->implicit;
    w->quasi_static = !strcmp(type, "quasi_static");
    w->dt = 0.01;
    assert_int_equal(pm_implicit_setup_step(s, w), 0);
    /* a smooth, finite displacement increment: stretch, shear and rotation of a few percent */
    for (size_t I = 0; I < w->nn; I++) {
        const double x = s->grid.x[2 * I], y = s->grid.x[2 * I + 1];
        if (w->dof[2 * I] >= 0)
            w->du[2 * I] = 0.03 * x + 0.02 * y * y + 0.01 * sin(3 * y);
        if (w->dof[2 * I + 1] >= 0)
            w->du[2 * I + 1] = -0.02 * x * y + 0.015 * x * x;
    }
    /* meshfree boundary rows: an increment that meets them, so that the residual does not carry the
     * penalty force of a violated constraint, whose size would drown the differences in round-off */
    for (int comp = 0; s->mf && comp < 2; comp++)
        if (s->mf->kd[comp]) {
            double zero[256] = {0};
            assert_true(pm_kd_size(s->mf->kd[comp]) <= 256);
            assert_int_equal(pm_kd_impose(s->mf->kd[comp], zero, 2, comp, w->du), 0);
        }
    assert_int_equal(pm_implicit_evaluate(s, w, 1), 0);
    const int n = w->n_dof, nnz = w->K.nnz;
    assert_true(n > 20);
    double *K = malloc((size_t)nnz * sizeof *K), *rp = malloc((size_t)n * sizeof *rp);
    double *rm = malloc((size_t)n * sizeof *rm);
    memcpy(K, w->K.val, (size_t)nnz * sizeof *K);
    const double eps = 1e-7 * s->grid.h_min;
    double worst = 0;
    for (size_t k = 0; k < 2 * w->nn; k++) {
        const int j = w->dof[k];
        if (j < 0)
            continue;
        const double u0 = w->du[k];
        w->du[k] = u0 + eps;
        assert_int_equal(pm_implicit_evaluate(s, w, 0), 0);
        memcpy(rp, w->res, (size_t)n * sizeof *rp);
        w->du[k] = u0 - eps;
        assert_int_equal(pm_implicit_evaluate(s, w, 0), 0);
        memcpy(rm, w->res, (size_t)n * sizeof *rm);
        w->du[k] = u0;
        double colmax = 0, err = 0;
        for (int i = 0; i < n; i++) {
            const int at = pm_csr_find(&w->K, i, j);
            const double kij = at >= 0 ? K[at] : 0.0;
            const double fd = -(rp[i] - rm[i]) / (2 * eps);
            /* entries outside the pattern must vanish too */
            colmax = fmax(colmax, fabs(fd));
            err = fmax(err, fabs(kij - fd));
        }
        worst = fmax(worst, err / colmax);
    }
    printf("%s %s %s %s: %d unknowns, largest relative column error %.2e\n", method, shape, formulation, type, n,
           worst);
    assert_true(worst < 1e-6);
    free(K);
    free(rp);
    free(rm);
    pm_sim_destroy(s);
    pm_case_free(&c);
}

static void check_tangent(const char *formulation, const char *type)
{
    check_tangent_of(formulation, type, "mpm", "linear");
}

/* GMM and RKPM: the same solver on node clouds, with the penalty rows of the Kronecker-delta
 * transformation (mls, rk_cubic) on the fixed side */
static void gmm_mls_static(void **st) { (void)st; check_tangent_of("plane_strain", "quasi_static", "gmm", "mls"); }
static void gmm_mls_dynamic(void **st) { (void)st; check_tangent_of("plane_strain", "implicit", "gmm", "mls"); }
static void gmm_lme_static(void **st) { (void)st; check_tangent_of("plane_strain", "quasi_static", "gmm", "lme"); }
static void rkpm_static(void **st) { (void)st; check_tangent_of("plane_strain", "quasi_static", "rkpm", "rk_cubic"); }

static void plane_strain_static(void **st) { (void)st; check_tangent("plane_strain", "quasi_static"); }
static void plane_strain_dynamic(void **st) { (void)st; check_tangent("plane_strain", "implicit"); }
static void plane_stress_static(void **st) { (void)st; check_tangent("plane_stress", "quasi_static"); }
static void axisymmetric_static(void **st) { (void)st; check_tangent("axisymmetric", "quasi_static"); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plane_strain_static),
        cmocka_unit_test(plane_strain_dynamic),
        cmocka_unit_test(plane_stress_static),
        cmocka_unit_test(axisymmetric_static),
        cmocka_unit_test(gmm_mls_static),
        cmocka_unit_test(gmm_mls_dynamic),
        cmocka_unit_test(gmm_lme_static),
        cmocka_unit_test(rkpm_static),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
