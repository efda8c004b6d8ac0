/*
 * F-bar volumetric averaging (src/solver/fbar.c, analysis.fbar "cell"). A prescribed nodal velocity
 * field that changes volume unevenly inside each cell (v = (x^2, x y) away from the origin: div v =
 * 3x varies across a cell) is applied for one step to a plane-strain block of 2 x 2 particles per
 * cell, with and without averaging:
 *  - with it, every particle's det F equals its cell's volume-weighted mean of the unaveraged det F
 *    (to 1e-12: the average is exact arithmetic on the same step), and F / sqrt(det F) equals the
 *    unaveraged F / sqrt(det F) (the shape of the step is kept, only its volume change is shared);
 *  - without it the det F inside a cell differ by about 3 h dt relative, i.e. 1e-4 here, so the
 *    averaging has something to remove (checked: the spread is at least 1e-5);
 *  - with fbar_own_share s = 0.25 every det F is J_cell^0.75 J_p^0.25 (to 1e-12), with the shape kept;
 *    full averaging misses that by s |ln(J_p / J_cell)|, about 2e-5 here (checked: at least 1e-6);
 *  - the loader refuses fbar_own_share without fbar "cell" and outside [0, 1).
 *  - the loader refuses fbar with gmm, with plane stress and with implicit analyses, naming the key.
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

#include "pmech/case.h"
#include "pmech/error.h"
#include "solver/sim_internal.h"

static const char *tmpl =
    "{ \"dimension\": 2, \"method\": \"%s\", \"formulation\": \"%s\",\n"
    "  \"analysis\": { \"type\": \"%s\", \"end_time\": 0.01, \"fbar\": \"%s\"%s },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"origin\": [1, 1], \"size\": [1, 1], \"cells\": [4, 4] },\n"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
    "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
    "  \"bodies\": [ { \"material\": \"m\",\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [1, 1], \"max\": [2, 2] } } ] }\n";

static int load_with(pm_case *c, const char *method, const char *form, const char *type, const char *fbar,
                     const char *extra)
{
    char buf[2048];
    snprintf(buf, sizeof buf, tmpl, method, form, type, fbar, extra);
    return pm_case_load_buffer(buf, strlen(buf), "case.json", c);
}

static int load(pm_case *c, const char *method, const char *form, const char *type, const char *fbar)
{
    return load_with(c, method, form, type, fbar, "");
}

/* One step of the prescribed field; F of every particle into F (PM_NF each). extra: more analysis keys. */
static void step_F(const char *fbar, const char *extra, double *F, size_t *n, int32_t *cell, double *vol)
{
    pm_case c;
    assert_int_equal(load_with(&c, "mpm", "plane_strain", "explicit", fbar, extra), PM_OK);
    pm_sim *s;
    assert_int_equal(pm_sim_create(&c, &s, 1), PM_OK);
    double *v = malloc(PM_DIM * s->grid.n_nodes * sizeof(double));
    assert_non_null(v);
    for (size_t I = 0; I < s->grid.n_nodes; I++) {
        const double x = s->grid.x[PM_DIM * I], y = s->grid.x[PM_DIM * I + 1];
        v[PM_DIM * I] = x * x;
        v[PM_DIM * I + 1] = x * y;
    }
    assert_int_equal(pm_sim_update_stresses(s, v, 1e-3), PM_OK);
    *n = s->p.n;
    memcpy(F, s->p.F, PM_NF * s->p.n * sizeof(double));
    memcpy(cell, s->p.cell, s->p.n * sizeof(int32_t));
    memcpy(vol, s->p.vol0, s->p.n * sizeof(double));
    free(v);
    pm_sim_destroy(s);
    pm_case_free(&c);
}

static double det2(const double *F) { return F[PM_FXX] * F[PM_FYY] - F[PM_FXY] * F[PM_FYX]; }

/* Each cell's volume-weighted mean of the unaveraged det F: sum[c] = {sum V det F, sum V}. */
static void cell_sums(const double *F0, const int32_t *cell, const double *vol, size_t n, double sum[16][2])
{
    memset(sum, 0, 16 * sizeof sum[0]);
    for (size_t i = 0; i < n; i++) {
        sum[cell[i]][0] += vol[i] * det2(F0 + PM_NF * i);
        sum[cell[i]][1] += vol[i];
    }
}

static void averages_volume_keeps_shape(void **state)
{
    (void)state;
    enum { MAXP = 64 };
    double F0[PM_NF * MAXP], F1[PM_NF * MAXP], vol[MAXP], sum[16][2];
    int32_t cell[MAXP], cell1[MAXP];
    size_t n0, n1;
    step_F("none", "", F0, &n0, cell, vol);
    step_F("cell", "", F1, &n1, cell1, vol);
    assert_int_equal(n0, 64);
    assert_int_equal(n1, n0);
    cell_sums(F0, cell, vol, n0, sum);
    double spread = 0;
    for (size_t i = 0; i < n0; i++) {
        const double Jc = sum[cell[i]][0] / sum[cell[i]][1], J0 = det2(F0 + PM_NF * i), J1 = det2(F1 + PM_NF * i);
        spread = fmax(spread, fabs(J0 - Jc));
        assert_true(fabs(J1 - Jc) < 1e-12);
        assert_true(fabs(F1[PM_FZZ + PM_NF * i] - 1.0) < 1e-15); /* plane strain: no thickness change */
        for (int k = 0; k < 4; k++)
            assert_true(fabs(F1[PM_NF * i + k] / sqrt(J1) - F0[PM_NF * i + k] / sqrt(J0)) < 1e-12);
    }
    assert_true(spread > 1e-5);
}

static void own_share_keeps_part_of_own_volume_change(void **state)
{
    (void)state;
    enum { MAXP = 64 };
    const double share = 0.25;
    double F0[PM_NF * MAXP], F1[PM_NF * MAXP], F2[PM_NF * MAXP], vol[MAXP], sum[16][2];
    int32_t cell[MAXP], cell1[MAXP];
    size_t n0, n1;
    step_F("none", "", F0, &n0, cell, vol);
    step_F("cell", "", F1, &n1, cell1, vol);
    step_F("cell", ", \"fbar_own_share\": 0.25", F2, &n1, cell1, vol);
    assert_int_equal(n1, n0);
    cell_sums(F0, cell, vol, n0, sum);
    double missed = 0;
    for (size_t i = 0; i < n0; i++) {
        const double Jc = sum[cell[i]][0] / sum[cell[i]][1], J0 = det2(F0 + PM_NF * i), J2 = det2(F2 + PM_NF * i);
        const double want = pow(Jc, 1 - share) * pow(J0, share);
        assert_true(fabs(J2 - want) < 1e-12);
        missed = fmax(missed, fabs(det2(F1 + PM_NF * i) - want));
        for (int k = 0; k < 4; k++)
            assert_true(fabs(F2[PM_NF * i + k] / sqrt(J2) - F0[PM_NF * i + k] / sqrt(J0)) < 1e-12);
    }
    assert_true(missed > 1e-6);
}

static void expect_refused_share(const char *fbar, const char *extra, const char *part)
{
    pm_case c;
    const int rc = load_with(&c, "mpm", "plane_strain", "explicit", fbar, extra);
    pm_case_free(&c);
    if (rc != PM_EINPUT)
        fail_msg("%s%s: expected an input error, got %d", fbar, extra, rc);
    if (!strstr(pm_error_message(), part))
        fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), part);
}

static void own_share_refused_where_it_cannot_apply(void **state)
{
    (void)state;
    expect_refused_share("none", ", \"fbar_own_share\": 0.1", "case.json: analysis.fbar_own_share: is a share");
    expect_refused_share("cell", ", \"fbar_own_share\": 1", "analysis.fbar_own_share");
    expect_refused_share("cell", ", \"fbar_own_share\": -0.1", "analysis.fbar_own_share");
}

static void expect_refused(const char *method, const char *form, const char *type, const char *part)
{
    pm_case c;
    const int rc = load(&c, method, form, type, "cell");
    pm_case_free(&c);
    if (rc != PM_EINPUT)
        fail_msg("%s/%s/%s: expected an input error, got %d", method, form, type, rc);
    if (!strstr(pm_error_message(), part))
        fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), part);
}

static void refused_where_it_cannot_apply(void **state)
{
    (void)state;
    expect_refused("gmm", "plane_strain", "explicit", "case.json: analysis.fbar: averages the volume change");
    expect_refused("mpm", "plane_stress", "explicit", "case.json: analysis.fbar: plane stress");
    expect_refused("mpm", "plane_strain", "implicit", "case.json: analysis.fbar: is available in explicit");
    pm_case c;
    assert_int_equal(load(&c, "mpm", "axisymmetric", "explicit", "cell"), PM_OK);
    pm_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(averages_volume_keeps_shape),
        cmocka_unit_test(refused_where_it_cannot_apply),
        cmocka_unit_test(own_share_keeps_part_of_own_volume_change),
        cmocka_unit_test(own_share_refused_where_it_cannot_apply),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
