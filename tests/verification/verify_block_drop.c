/*
 * A stiff block dropped on a soft elastic layer (tests/verification/cases/block_drop.json): a 1-D
 * column between rollers, no gravity, the block (M = 20 kg per m, E = 100 MPa) approaching at
 * v0 = 1 m/s a layer (H = 0.1 m, E = 1 MPa, nu = 0, m = 1 kg per m) held at its base, frictionless
 * body-body contact. The layer is a spring k = E W / H = 1e6 N/m per m; its waves cross it in 1 ms,
 * far less than the contact, and the block's in 0.3 ms, so the block is a mass on a light spring:
 * Rayleigh's estimate gives the contact time T = pi sqrt((M + m/3) / k) = 14.17 ms and an elastic
 * bounce gives the momentum exchanged J = 2 M v0 = 40 N s per m and a rebound at v0. What the layer
 * keeps when the block leaves is at most its kinetic energy then, about m v0^2 / 6, 1.7 % of the
 * energy: the rebound speed may be up to 0.9 % below v0 and J 0.4 % below 2 M v0.
 *
 * Judged: J (the contact force of contact_forces integrated over the impact) within 5 % of 2 M v0;
 * the block's speed after the impact within 5 % of v0; the contact time within 5 % of T; the impulses
 * on the two bodies opposite to 1e-9 (the two fields get opposite normals). Reported: the total
 * energy after the impact over the initial one.
 *
 * The same contact seen from the other side (tests/verification/cases/soft_drop.json): a soft block
 * (E = 1 MPa, 10 kg per m) dropped at 1 m/s on a stiff base body (E = 100 MPa, held at its foot)
 * through body-body contact, against the soft block dropped on a rigid obstacle (obstacles[], a
 * frictionless polyline) at the base's top. The stiff base is rigid-like (its P-wave is ten times
 * faster and it is four times denser than the block's), so both must give the block the same
 * rebound: judged within 5 % (the bound), rebound speed and momentum exchanged.
 */
#include "verify_util.h"

#include "contact/multibody.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static void set(pm_case *c, const char *path, const char *json)
{
    if (pm_case_set_json(c, path, json) != PM_OK) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(1);
    }
}

/* The soft block's mean vertical velocity at the end of soft_drop.json, on the stiff base body or
 * (obstacle) on a rigid floor at the base's top. */
static double soft_drop(int obstacle, double *secs)
{
    pm_case c;
    vu_load("tests/verification/cases/soft_drop.json", &c);
    if (obstacle) {
        set(&c, "contact_pairs", "[]");
        set(&c, "bodies", "[{\"name\": \"block\", \"material\": \"soft\", \"particles_per_cell\": 2, "
                          "\"velocity\": [0, -1.0], \"shape\": {\"type\": \"rectangle\", \"min\": [0.0, 0.06], "
                          "\"max\": [0.1, 0.16]}}]");
        set(&c, "obstacles", "[{\"name\": \"floor\", \"type\": \"polyline\", \"points\": [[-0.1, 0.05], [0.2, "
                             "0.05]], \"material_side\": \"left\"}]");
    }
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    vu_run_to(s, c.analysis.end_time);
    double v[2], x[2];
    vu_body_mean(s, obstacle ? 0 : 1, v, x);
    *secs = vu_now() - t0;
    pm_sim_destroy(s);
    pm_case_free(&c);
    return v[1];
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    pm_case c;
    vu_load("tests/verification/cases/block_drop.json", &c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    const pm_multibody *mb = s->mb;
    const size_t nf = (size_t)mb->n_fields, layer = (size_t)mb->field_of_body[0], block = (size_t)mb->field_of_body[1];
    double ke, se, ge;
    pm_sim_energy(s, &ke, &se, &ge);
    const double e0 = ke + se;
    double j_block = 0, j_layer = 0, first = NAN, last = NAN;
    while (s->t < c.analysis.end_time - 1e-12) {
        double dt = vu_dt(s);
        if (s->t + dt > c.analysis.end_time)
            dt = c.analysis.end_time - s->t;
        if (pm_explicit_step(s, dt) != 0) {
            fprintf(stderr, "%s\n", pm_error_message());
            return 1;
        }
        const double fb = mb->pair_force[PM_DIM * (block * nf + layer) + 1];
        const double fl = mb->pair_force[PM_DIM * (layer * nf + block) + 1];
        j_block += fb * dt;
        j_layer += fl * dt;
        if (fb != 0) {
            if (isnan(first))
                first = s->t - dt;
            last = s->t;
        }
    }
    const double secs = vu_now() - t0;
    double v[2], x[2];
    vu_body_mean(s, 1, v, x);
    pm_sim_energy(s, &ke, &se, &ge);
    const double M = 20.0, m = 1.0, k = 1e6, v0 = 1.0, T = M_PI * sqrt((M + m / 3) / k), J = 2 * M * v0;
    int ok = 1;
    ok &= vu_report("block dropped on a soft layer", "momentum exchanged (N s per m) vs 2 M v0", j_block, J,
                    (j_block - J) / J, 0.05, secs);
    ok &= vu_report("block dropped on a soft layer", "rebound speed (m/s) vs v0", v[1], v0, (v[1] - v0) / v0, 0.05,
                    secs);
    const double dur = last - first;
    ok &= vu_report("block dropped on a soft layer", "contact time (s) vs pi sqrt((M + m/3) / k)", dur, T,
                    (dur - T) / T, 0.05, secs);
    ok &= vu_report("block dropped on a soft layer", "impulse on the layer + on the block, relative", j_layer + j_block,
                    0.0, (j_layer + j_block) / j_block, 1e-9, secs);
    vu_report("block dropped on a soft layer", "total energy after / before", (ke + se) / e0, 1.0, (ke + se) / e0 - 1,
              -1, secs);
    pm_sim_destroy(s);
    pm_case_free(&c);
    double s_body, s_obst;
    const double vb = soft_drop(0, &s_body), vo = soft_drop(1, &s_obst), m_soft = 10.0;
    ok &= vu_report("soft block dropped on a stiff base", "rebound speed (m/s): on the base body vs on an obstacle", vb,
                    vo, (vb - vo) / vo, 0.05, s_body + s_obst);
    const double jb = m_soft * (vb + 1.0), jo = m_soft * (vo + 1.0);
    ok &= vu_report("soft block dropped on a stiff base", "momentum exchanged (N s per m): base body vs obstacle", jb, jo,
                    (jb - jo) / jo, 0.05, s_body + s_obst);
    vu_report("soft block dropped on a stiff base", "rebound speed on the base body / v0", vb, 1.0, vb - 1.0, -1,
              s_body);
    return ok ? 0 : 1;
}
