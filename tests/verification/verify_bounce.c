/*
 * An elastic disk bouncing off a rigid inclined wall (an obstacles[] polyline at 20 degrees, not
 * aligned with the grid), frictionless, no gravity. The disk (R = 0.1 m, E = 100 MPa, rho = 1000) flies
 * at 1 m/s straight down onto the wall, 2 cm away along the wall's normal. A stiff elastic disk at an
 * impact speed far below its wave speed (1 m/s against 367 m/s) rebounds with its normal velocity
 * reversed (restitution 1, a little of the energy stays in the disk's ringing) and its tangential
 * velocity unchanged. (A ten times softer disk, 116 m/s, measured 0.91 with the nodal law and 0.93
 * with the penalty law: more of the energy stays in its ringing.) Checked for both laws, 0.04 s after the impact:
 *   - restitution -v_n,after / v_n,before within 5 % of 1 (a nodal law that stopped the contact
 *     nodes dead would lose the kinetic energy of the contact layer each step it acts, which is the
 *     error this bounds);
 *   - tangential velocity within 2 % of its value before (frictionless wall: a wall that dragged or a
 *     normal tilted by a degree would show);
 *   - translational kinetic energy after / before within 10 % of 1 (reported and judged: it is the
 *     restitution squared, blended with the unchanged tangential part);
 *   - the wall's force output: its impulse (forces.csv's normal force times time) against the disk's
 *     change of normal momentum m (v_n,after - v_n,before), within 2 %.
 */
#include "verify_util.h"

#include "contact/contact.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double TH = 20.0 * M_PI / 180.0, R = 0.1, GAP = 0.02, V0 = 1.0, T_END = 0.06;

static void make_case(const char *law, pm_case *c)
{
    const double y_line = 0.3 - 0.5 * tan(TH), yc = y_line + (R + GAP) / cos(TH);
    char text[2048];
    snprintf(text, sizeof text,
             "{ \"dimension\": 2, \"analysis\": { \"type\": \"explicit\", \"scheme\": \"musl\", \"end_time\": %g,"
             "  \"cfl\": 0.3, \"gravity\": [0, 0] },"
             "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1.0, 0.5], \"cells\": [100, 50],"
             "             \"element\": \"quad4\" },"
             "  \"materials\": [ { \"name\": \"disk\", \"model\": \"linear_elastic\", \"density\": 1000,"
             "                   \"youngs_modulus\": 1.0e8, \"poisson_ratio\": 0.3 } ],"
             "  \"bodies\": [ { \"name\": \"disk\", \"material\": \"disk\", \"particles_per_cell\": 2,"
             "    \"velocity\": [0, %g], \"shape\": { \"type\": \"circle\", \"center\": [0.5, %.12g], \"radius\": %g } } ],"
             "  \"obstacles\": [ { \"name\": \"wall\", \"type\": \"polyline\", \"points\": [[0, 0.3], [1, %.12g]],"
             "                     \"law\": \"%s\" } ] }",
             T_END, -V0, yc, R, 0.3 - tan(TH), law);
    if (pm_case_load_buffer(text, strlen(text), "bounce.json", c) != PM_OK) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(2);
    }
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = 1;
    const double n[2] = {sin(TH), cos(TH)}, e[2] = {cos(TH), -sin(TH)}; /* wall normal (material side), tangent */
    const char *const laws[] = {"nodal", "penalty"};
    for (int k = 0; k < 2; k++) {
        pm_case c;
        make_case(laws[k], &c);
        const double t0 = vu_now();
        pm_sim *s = vu_sim(&c, 1);
        double v[2], x[2], mass = 0;
        for (size_t i = 0; i < s->p.n; i++)
            mass += s->p.mass[i];
        vu_body_mean(s, 0, v, x);
        const double vn0 = v[0] * n[0] + v[1] * n[1], vt0 = v[0] * e[0] + v[1] * e[1];
        int run_ok = 1;
        while (run_ok && s->t < T_END - 1e-12) {
            double dt = vu_dt(s);
            if (s->t + dt > T_END)
                dt = T_END - s->t;
            if (pm_explicit_step(s, dt) != PM_OK) {
                fprintf(stderr, "%s law: %s\n", laws[k], pm_error_message());
                run_ok = 0;
            }
        }
        ok &= run_ok;
        vu_body_mean(s, 0, v, x);
        const double secs = vu_now() - t0;
        const double vn = v[0] * n[0] + v[1] * n[1], vt = v[0] * e[0] + v[1] * e[1];
        const double rest = -vn / vn0, ke = (vn * vn + vt * vt) / (vn0 * vn0 + vt0 * vt0);
        const double impulse = s->contact->surface[0].impulse.normal, dp = mass * (vn - vn0);
        char q[96];
        snprintf(q, sizeof q, "%s law: restitution -v_n after / v_n before", laws[k]);
        ok &= vu_report("bounce", q, rest, 1.0, rest - 1.0, 0.05, secs);
        snprintf(q, sizeof q, "%s law: tangential velocity after (m/s)", laws[k]);
        ok &= vu_report("bounce", q, vt, vt0, (vt - vt0) / vt0, 0.02, secs);
        snprintf(q, sizeof q, "%s law: translational kinetic energy after / before", laws[k]);
        ok &= vu_report("bounce", q, ke, 1.0, ke - 1.0, 0.10, secs);
        snprintf(q, sizeof q, "%s law: wall's normal impulse (N s/m) against m dv_n", laws[k]);
        ok &= vu_report("bounce", q, impulse, dp, (impulse - dp) / dp, 0.02, secs);
        pm_sim_destroy(s);
        pm_case_free(&c);
    }
    return ok ? 0 : 1;
}
