/*
 * Loads on particle sets (loads[]) against two answers that need no mesh to be right:
 *  - a point load (the particle nearest a point) of 100 N/m on a free block in space: its momentum
 *    grows by exactly F t, so the mean velocity is F t / M; compared within 0.1 % (round-off and the
 *    explicit steps carry no error in the total momentum; a load applied to the wrong set or not
 *    summed to the nodes would be off by its share);
 *  - a distributed load on the top row of particles of an elastic column resting on a fixed base
 *    (statics: sigma_yy = -P / W everywhere): P = 1000 N/m, ramped over 20 ms, held, with local damping;
 *    the mean vertical stress of the lower half at 1 s within 2 % of -5000 Pa (measured 0.24 %; at
 *    0.3 s the damped column still swings, -11 %; a load spread over the wrong area or missing a row
 *    of particles is off by far more);
 *  - the same column loaded instead through the nodes of the grid line y = 0.4 (its top) by 5000 N/m^2
 *    per length over x = 0 to 0.1125 m, a part that ends between two nodes (h = 0.025 m): the nodal
 *    forces must sum to 5000 x 0.1125 = 562.5 N/m, so the mean vertical stress of the lower half is
 *    -562.5 / 0.2 Pa, within 2 % (a lumping that gave every node inside the part a whole spacing would
 *    load 0.125 m, 11 % too much; one that dropped the partly loaded node, 0.1 m, 11 % too little).
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static pm_sim *load_run(const char *text, pm_case *c, double t_end)
{
    if (pm_case_load_buffer(text, strlen(text), "loads.json", c) != PM_OK) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(2);
    }
    pm_sim *s = vu_sim(c, 1);
    while (s->t < t_end - 1e-12) {
        double dt = vu_dt(s);
        if (s->t + dt > t_end)
            dt = t_end - s->t;
        if (pm_explicit_step(s, dt) != PM_OK) {
            fprintf(stderr, "%s\n", pm_error_message());
            exit(1);
        }
    }
    return s;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = 1;
    const char *free_block =
        "{ \"dimension\": 2, \"analysis\": { \"type\": \"explicit\", \"scheme\": \"musl\", \"end_time\": 0.05,"
        "  \"cfl\": 0.3, \"gravity\": [0, 0] },"
        "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1], \"cells\": [20, 20] },"
        "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,"
        "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],"
        "  \"bodies\": [ { \"name\": \"b\", \"material\": \"m\","
        "               \"shape\": { \"type\": \"rectangle\", \"min\": [0.4, 0.4], \"max\": [0.6, 0.6] } } ],"
        "  \"loads\": [ { \"name\": \"push\", \"nearest\": [0.4, 0.5], \"force\": [100, 0] } ] }";
    pm_case c;
    double t0 = vu_now();
    pm_sim *s = load_run(free_block, &c, 0.05);
    double v[2], x[2], M = 0;
    vu_body_mean(s, 0, v, x);
    for (size_t i = 0; i < s->p.n; i++)
        M += s->p.mass[i];
    const double ref = 100 * 0.05 / M;
    ok &= vu_report("loads", "point load 100 N/m on a free block: mean velocity at 0.05 s (m/s)", v[0], ref,
                    (v[0] - ref) / ref, 1e-3, vu_now() - t0);
    pm_sim_destroy(s);
    pm_case_free(&c);

    const char *column =
        "{ \"dimension\": 2, \"analysis\": { \"type\": \"explicit\", \"scheme\": \"musl\", \"end_time\": 1.0,"
        "  \"cfl\": 0.3, \"gravity\": [0, 0], \"damping\": 0.1 },"
        "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [0.4, 0.5], \"cells\": [16, 20] },"
        "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,"
        "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],"
        "  \"bodies\": [ { \"name\": \"b\", \"material\": \"m\","
        "               \"shape\": { \"type\": \"rectangle\", \"min\": [0, 0], \"max\": [0.2, 0.4] } } ],"
        "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"y\"] },"
        "                             { \"type\": \"fixed\", \"boundary\": \"x_min\", \"directions\": [\"x\"] } ],"
        "  \"loads\": [ { \"name\": \"top\", \"min\": [0, 0.39], \"max\": [0.2, 0.4],"
        "                \"force\": [0, { \"value\": -1000, \"ramp_time\": 0.02 }] } ] }";
    t0 = vu_now();
    s = load_run(column, &c, 1.0);
    double sum = 0, vol = 0;
    for (size_t i = 0; i < s->p.n; i++)
        if (s->p.x[PM_DIM * i + 1] < 0.2) {
            sum += s->p.stress[PM_NS * i + 1] * s->p.vol[i];
            vol += s->p.vol[i];
        }
    const double syy = sum / vol, sref = -1000 / 0.2;
    ok &= vu_report("loads", "1000 N/m on a column's top row: mean sigma_yy of the lower half (Pa)", syy, sref,
                    (syy - sref) / sref, 0.02, vu_now() - t0);
    pm_sim_destroy(s);
    pm_case_free(&c);

    char line_column[2048];
    snprintf(line_column, sizeof line_column, "%.*s%s", (int)(strstr(column, "\"loads\"") - column), column,
             "\"loads\": [ { \"name\": \"strip\", \"grid_line\": { \"y\": 0.4, \"from\": 0, \"to\": 0.1125 },"
             "  \"force_per_length\": [0, { \"value\": -5000, \"ramp_time\": 0.02 }] } ] }");
    t0 = vu_now();
    s = load_run(line_column, &c, 1.0);
    sum = vol = 0;
    for (size_t i = 0; i < s->p.n; i++)
        if (s->p.x[PM_DIM * i + 1] < 0.2) {
            sum += s->p.stress[PM_NS * i + 1] * s->p.vol[i];
            vol += s->p.vol[i];
        }
    const double syy_line = sum / vol, sref_line = -5000 * 0.1125 / 0.2;
    ok &= vu_report("loads", "5000 N/m/m on the grid line y = 0.4, x = 0-0.1125: mean sigma_yy of the lower half (Pa)",
                    syy_line, sref_line, (syy_line - sref_line) / sref_line, 0.02, vu_now() - t0);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
