/* Write a sample output directory through the output API, for VTK's reader to check.
 * usage: write_sample DIR N_PARTICLES [quad4|tri3]
 * N particles in two bodies on a 10 x 10 grid, three frames of made-up motion and stress,
 * probes, energy rows and run.json. */
#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/grid.h"
#include "io/output.h"
#include "pmech/particles.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void move(pm_particles *p, double t)
{
    for (size_t i = 0; i < p->n; i++) {
        double s = sin(10.0 * t + 0.01 * (double)i);
        p->v[2 * i] = s;
        p->v[2 * i + 1] = -0.5 * s;
        p->x[2 * i] = p->x0[2 * i] + 0.01 * t * s;
        p->x[2 * i + 1] = p->x0[2 * i + 1] - 0.005 * t * s;
        for (int k = 0; k < PM_NS; k++)
            p->stress[PM_NS * i + (size_t)k] = -1e5 * t * (k + 1);
        p->eps_p[i] = 1e-3 * t;
        p->vol[i] = p->vol0[i] * (1 + 1e-3 * t);
    }
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 4) {
        fprintf(stderr, "usage: write_sample DIR N_PARTICLES [quad4|tri3]\n");
        return 2;
    }
    const char *dir = argv[1];
    long n = strtol(argv[2], NULL, 10);
    pm_element el = argc == 4 && strcmp(argv[3], "tri3") == 0 ? PM_TRI3 : PM_QUAD4;
    if (n < 1) {
        fprintf(stderr, "write_sample: N_PARTICLES must be >= 1\n");
        return 2;
    }
    static pm_case c; /* large: keep it off the stack */
    pm_case_body bodies[2];
    pm_case_probe probes[3];
    memset(bodies, 0, sizeof bodies);
    memset(probes, 0, sizeof probes);
    snprintf(c.file, sizeof c.file, "write_sample.json");
    snprintf(bodies[0].name, PM_NAME_MAX, "lower");
    snprintf(bodies[1].name, PM_NAME_MAX, "upper");
    c.n_bodies = 2;
    c.bodies = bodies;
    snprintf(probes[0].name, PM_NAME_MAX, "corner");
    probes[0].quantity = PM_Q_VELOCITY;
    probes[0].body = -1;
    snprintf(probes[1].name, PM_NAME_MAX, "centre");
    probes[1].quantity = PM_Q_STRESS;
    probes[1].body = -1;
    probes[1].point[0] = probes[1].point[1] = 0.5;
    snprintf(probes[2].name, PM_NAME_MAX, "top");
    probes[2].quantity = PM_Q_POSITION;
    probes[2].body = 1;
    c.n_probes = 3;
    c.probes = probes;

    pm_grid g;
    const double origin[2] = { 0, 0 }, size[2] = { 1, 1 };
    const int cells[2] = { 10, 10 };
    pm_particles p;
    if (pm_grid_rectangle(&g, origin, size, cells, el) || pm_particles_alloc(&p, (size_t)n, 0)) {
        fprintf(stderr, "write_sample: %s\n", pm_error_message());
        return 1;
    }
    /* particles on a square lattice inside the unit square, lower half body 0, upper body 1 */
    size_t side = (size_t)ceil(sqrt((double)n));
    for (size_t i = 0; i < p.n; i++) {
        p.x[2 * i] = p.x0[2 * i] = ((double)(i % side) + 0.5) / (double)side;
        p.x[2 * i + 1] = p.x0[2 * i + 1] = ((double)(i / side) + 0.5) / (double)side;
        p.body[i] = p.material[i] = p.x[2 * i + 1] < 0.5 ? 0 : 1;
        p.vol[i] = p.vol0[i] = 1.0 / (double)(side * side);
        p.mass[i] = 2000.0 * p.vol[i];
    }
    pm_output *o = NULL;
    int rc = pm_output_open(&o, dir, &c, &g, &p);
    for (int f = 0; !rc && f < 3; f++) {
        double t = 0.05 * f;
        move(&p, t);
        rc = pm_output_frame(o, t, &p);
        if (!rc)
            rc = pm_output_probes(o, t, &p);
        if (!rc)
            rc = pm_output_energy(o, t, 1.0 + t, 2.0 - t, -0.5);
    }
    pm_run_summary s = {
        .version = PMECH_VERSION, .case_file = c.file, .steps = 2, .dt_min = 0.05, .dt_max = 0.05,
        .end_time = 0.1, .wall_seconds = 0, .loop_seconds = 0, .particle_steps_per_second = 0,
        .particles = p.n, .exit_status = rc ? 1 : 0, .message = "", .threads = 1,
    };
    int rc2 = pm_output_close(o, &s);
    if (rc || rc2)
        fprintf(stderr, "write_sample: %s\n", pm_error_message());
    pm_particles_free(&p);
    pm_grid_free(&g);
    return rc || rc2 ? 1 : 0;
}
