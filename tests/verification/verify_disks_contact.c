/*
 * Sulsky's two elastic disks (examples/elastic_disks, MUSL) with frictionless body-body contact
 * (contact_pairs): the disks must separate after the impact with no particle of one left attached
 * to the other, and the total energy (kinetic + strain) must stay within 2 % of its initial value at
 * all times (the contact law removes only approaching normal velocity relative to the centre of
 * mass, which conserves momentum and dissipates at most what a perfectly plastic normal impact of
 * the nodal masses would; 2 % is the bound, MUSL's own dissipation in the single-field run
 * is about 1 %).
 *
 * Judged: the energy bound; at the end the smallest distance between a particle of one disk and a
 * particle of the other exceeds 4 cells (0.1 m: an attached particle would be within one particle
 * spacing, 0.0125 m, of its disk, and the disks recede at about 0.25 m/s for more than a second);
 * contact begins (the kinetic energy first drops by 1e-4 of its value) within half a cell's closing
 * time (h / 0.2 sqrt(2)) of the moment the disks' rims touch, (sqrt(2)/2 - 0.4) / (0.2 sqrt(2)) =
 * 1.0858 s: with 2 x 2 particles per cell a rim particle's domain (half-size h/4) may reach up to a
 * quarter cell past the circle on each disk, so the discretised disks may touch up to half a cell's
 * closing time early; single-field contact starts about 1.5 of them early.
 * Reported beside them: the same figures for the single-field run, whose contact begins early (the
 * disks share nodes a cell before they touch).
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct result {
    double worst, onset, min_gap, vdiag, secs;
} result;

/* Smallest distance between a particle of body 0 and one of body 1. */
static double min_distance(const pm_sim *s)
{
    const pm_particles *p = &s->p;
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        if (p->body[i] != 0)
            continue;
        for (size_t j = 0; j < p->n; j++) {
            if (p->body[j] != 1)
                continue;
            const double d = hypot(p->x[PM_DIM * i] - p->x[PM_DIM * j], p->x[PM_DIM * i + 1] - p->x[PM_DIM * j + 1]);
            best = d < best ? d : best;
        }
    }
    return best;
}

static result run(int with_contact)
{
    pm_case c;
    vu_load("examples/elastic_disks/case.json", &c);
    if (with_contact &&
        pm_case_set_json(&c, "contact_pairs", "[{\"bodies\": [\"lower\", \"upper\"], \"law\": \"frictionless\"}]")) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(1);
    }
    result r = {0, NAN, 0, 0, 0};
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    double ke, se, ge;
    pm_sim_energy(s, &ke, &se, &ge);
    const double e0 = ke + se, ke0 = ke;
    while (vu_advance(s, c.analysis.end_time)) {
        pm_sim_energy(s, &ke, &se, &ge);
        const double dev = (ke + se - e0) / e0;
        if (fabs(dev) > fabs(r.worst))
            r.worst = dev;
        if (isnan(r.onset) && ke < ke0 * (1 - 1e-4))
            r.onset = s->t;
    }
    r.secs = vu_now() - t0;
    r.min_gap = min_distance(s);
    double v[2], x[2];
    vu_body_mean(s, 0, v, x);
    r.vdiag = (v[0] + v[1]) / sqrt(2.0);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return r;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    const double touch = (sqrt(2.0) / 2 - 0.4) / (0.2 * sqrt(2.0)), h = 1.0 / 40, closing = 0.2 * sqrt(2.0);
    const result fr = run(1), one = run(0);
    int ok = 1;
    ok &= vu_report("disks, frictionless contact", "max abs(E(t) - E0) / E0, musl", fr.worst, 0.0, fr.worst, 0.02,
                    fr.secs);
    ok &= vu_report("disks, frictionless contact", "smallest distance between the disks' particles at 3.5 s (m)",
                    fr.min_gap, 4 * h, fmax(0.0, (4 * h - fr.min_gap) / (4 * h)), 0.0, fr.secs);
    ok &= vu_report("disks, frictionless contact", "contact onset (s) vs rims touching", fr.onset, touch,
                    (fr.onset - touch) / (h / closing), 0.5, fr.secs);
    vu_report("disks, frictionless contact", "lower disk diagonal velocity at 3.5 s (m/s)", fr.vdiag, -0.1 * sqrt(2.0),
              (fr.vdiag + 0.1 * sqrt(2.0)) / (0.1 * sqrt(2.0)), -1, fr.secs);
    vu_report("disks, single field", "max abs(E(t) - E0) / E0, musl", one.worst, 0.0, one.worst, -1, one.secs);
    vu_report("disks, single field", "smallest distance between the disks' particles at 3.5 s (m)", one.min_gap,
              4 * h, one.min_gap - 4 * h, -1, one.secs);
    vu_report("disks, single field", "contact onset (s) vs rims touching", one.onset, touch,
              (one.onset - touch) / (h / closing), -1, one.secs);
    vu_report("disks, single field", "lower disk diagonal velocity at 3.5 s (m/s)", one.vdiag, -0.1 * sqrt(2.0),
              (one.vdiag + 0.1 * sqrt(2.0)) / (0.1 * sqrt(2.0)), -1, one.secs);
    return ok ? 0 : 1;
}
