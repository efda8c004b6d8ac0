/*
 * Which granular points the density of the positions reads apart (analysis.apart_measure, the granular
 * model's loosest state e_max; src/solver/sim.c). A bed of 4 x 4 points per cell (at the Gauss
 * points) fills one row of 0.1 m cells and three of the four rows of points of the next (its free
 * surface crosses those cells), and one point lies alone in a far cell. With e_max = 1.0 and e0 = 0.9 a point is apart where its density reads below
 * 1.9 / 2.0 of the material's: its granular eps_v is then raised to -ln(rho / rho_ref).
 *  - "point" (the default) reads the upper two of the three rows of points in those cells apart by
 *    their own density (0.89 and 0.78 of the material's, diluted by the cells' nodes on the free
 *    surface; the lowest row reads 0.97), 32 points, and raises their eps_v to exactly
 *    -ln(rho / rho_ref);
 *  - "cell" reads them by the densest node of their cell, on the row below (0.97 of the material's),
 *    and leaves every point of the bed as it was;
 *  - the lone point is apart by either measure, with "cell" by its cell's densest node exactly;
 *  - the loader refuses apart_measure without density_update "positions", and values other than
 *    "point" and "cell", naming the key.
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
    "{ \"dimension\": 2, \"method\": \"mpm\", \"formulation\": \"plane_strain\",\n"
    "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 0.01, \"dt\": 1e-5%s },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [0.4, 0.4], \"cells\": [4, 4] },\n"
    "  \"materials\": [ { \"name\": \"g\", \"model\": \"granular\", \"density\": 1500, \"kappa\": 0.02,\n"
    "                   \"void_ratio\": 0.9, \"reference_pressure\": 600, \"poisson_ratio\": 0.3,\n"
    "                   \"friction_angle\": 30, \"viscosity\": 1e4, \"max_void_ratio\": 1.0 } ],\n"
    "  \"bodies\": [ { \"name\": \"bed\", \"material\": \"g\", \"particles_per_cell\": 4,\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [0, 0], \"max\": [0.4, 0.175] } },\n"
    "              { \"name\": \"lone\", \"material\": \"g\", \"particles_per_cell\": 2,\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [0.3, 0.3], \"max\": [0.35, 0.35] } } ] }\n";

static int load(pm_case *c, const char *analysis_extra)
{
    char buf[2048];
    snprintf(buf, sizeof buf, tmpl, analysis_extra);
    return pm_case_load_buffer(buf, strlen(buf), "case.json", c);
}

typedef struct judged {
    size_t n_bed, bed_raised, bed_changed; /* bed points; those raised past e_max; those changed at all */
    size_t lone;                           /* the lone point's index */
    double lone_ev, lone_expected;         /* its eps_v after the pass, and -ln(rho / rho_ref) of the measure */
    double worst_raise_error;              /* bed points raised: |eps_v + ln(rho_p / rho_ref)|, largest */
} judged;

static judged judge(const char *measure_key)
{
    pm_case c;
    assert_int_equal(load(&c, measure_key), PM_OK);
    pm_sim *s;
    assert_int_equal(pm_sim_create(&c, &s, 1), PM_OK);
    pm_particles *p = &s->p;
    assert_int_equal(s->approx->ops->connect(s->approx, p), PM_OK);
    double *before = malloc(p->n * sizeof(double));
    assert_non_null(before);
    for (size_t i = 0; i < p->n; i++)
        before[i] = p->state[p->n_state * i + 1];
    assert_int_equal(pm_sim_volumes_from_positions(s), PM_OK);
    const double ev_max = log(2.0 / 1.9), rho_ref = 1500;
    judged j = {0};
    size_t n_lone = 0;
    for (size_t i = 0; i < p->n; i++) {
        const double ev = p->state[p->n_state * i + 1];
        if (p->x[PM_DIM * i + 1] > 0.3) {
            j.lone = i;
            j.lone_ev = ev;
            n_lone++;
            continue;
        }
        j.n_bed++;
        j.bed_changed += ev != before[i];
        if (ev > ev_max) {
            j.bed_raised++;
            const double e = fabs(ev + log(s->rho_p[i] / rho_ref));
            j.worst_raise_error = e > j.worst_raise_error ? e : j.worst_raise_error;
        }
    }
    assert_int_equal(n_lone, 1);
    const pm_grid *g = &s->grid;
    double densest = 0;
    for (int k = 0; k < g->nodes_per_cell; k++)
        densest = fmax(densest, s->rho_node[g->conn[(size_t)g->nodes_per_cell * (size_t)p->cell[j.lone] + k]]);
    j.lone_expected = -log((c.analysis.apart_from_cell ? densest : s->rho_p[j.lone]) / rho_ref);
    free(before);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return j;
}

static void point_reads_the_free_surface_apart(void **state)
{
    (void)state;
    const judged j = judge(", \"density_update\": \"positions\"");
    assert_int_equal(j.n_bed, 112); /* 64 in the full row of cells, 48 in the one the surface crosses */
    assert_int_equal(j.bed_raised, 32);
    assert_true(j.worst_raise_error < 1e-12);
    assert_true(j.lone_ev > log(2.0 / 1.9));
    assert_true(fabs(j.lone_ev - j.lone_expected) < 1e-12);
}

static void cell_reads_them_by_the_packed_node(void **state)
{
    (void)state;
    const judged j = judge(", \"density_update\": \"positions\", \"apart_measure\": \"cell\"");
    assert_int_equal(j.n_bed, 112);
    assert_int_equal(j.bed_changed, 0);
    assert_true(j.lone_ev > log(2.0 / 1.9));
    assert_true(fabs(j.lone_ev - j.lone_expected) < 1e-12);
}

static void expect_refused(const char *extra, const char *part)
{
    pm_case c;
    assert_int_equal(load(&c, extra), PM_EINPUT);
    if (!strstr(pm_error_message(), part))
        fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), part);
    pm_case_free(&c);
}

static void refused_where_it_cannot_apply(void **state)
{
    (void)state;
    expect_refused(", \"apart_measure\": \"cell\"", "case.json: analysis.apart_measure: judges points apart");
    expect_refused(", \"density_update\": \"positions\", \"apart_measure\": \"cells\"", "apart_measure");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(point_reads_the_free_surface_apart),
        cmocka_unit_test(cell_reads_them_by_the_packed_node),
        cmocka_unit_test(refused_where_it_cannot_apply),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
