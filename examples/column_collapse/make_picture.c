/*
 * Run the column-collapse case and draw the particles at the end time coloured by the equivalent
 * plastic strain with the colour scale clipped at EPS_MAX, so that the shear bands stay visible
 * next to the few points sheared along the rough base (whose strain reaches ~10):
 *   make_picture CASE.json OUT.png EPS_MAX
 * Prints the run-out (largest x of any particle) and the height left at the wall.
 */
#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/render.h"
#include "pmech/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: make_picture CASE.json OUT.png EPS_MAX\n");
        return 2;
    }
    pm_case c;
    int rc = pm_case_load(argv[1], &c);
    if (rc) {
        fprintf(stderr, "make_picture: %s\n", pm_error_message());
        pm_case_free(&c);
        return pm_exit_code(rc);
    }
    pm_run_opts o = {.out_dir = NULL, .quiet = 1, .threads = 0, .write_output = 0};
    pm_sim *s = NULL;
    rc = pm_run(&c, &o, &s);
    if (rc)
        fprintf(stderr, "make_picture: %s\n", pm_error_message());
    if (s) {
        const double cap = atof(argv[3]);
        const pm_particles *p = pm_sim_particles(s);
        double xmax = 0, hwall = 0, epmax = 0;
        /* the picture shows a copy of the particles whose plastic strain is clipped at cap */
        pm_particles shown = *p;
        shown.eps_p = malloc((p->n ? p->n : 1) * sizeof *shown.eps_p);
        if (!shown.eps_p) {
            fprintf(stderr, "make_picture: out of memory\n");
            pm_sim_destroy(s);
            pm_case_free(&c);
            return 2;
        }
        for (size_t i = 0; i < p->n; i++) {
            const double x = p->x[2 * i], y = p->x[2 * i + 1];
            xmax = fmax(xmax, x);
            if (x < 0.1)
                hwall = fmax(hwall, y);
            epmax = fmax(epmax, p->eps_p[i]);
            shown.eps_p[i] = fmin(p->eps_p[i], cap);
        }
        printf("t = %g s: run-out (largest x) %.3f m, height at the wall %.3f m, largest plastic strain %.2f\n",
               pm_sim_time(s), xmax, hwall, epmax);
        char title[256];
        snprintf(title, sizeof title, "column collapse, t = %.2f s, plastic strain (scale clipped at %g)",
                 pm_sim_time(s), cap);
        if (!rc)
            rc = pm_render_particles(argv[2], pm_sim_grid(s), &shown, PM_FIELD_PLASTIC_STRAIN, 900, title);
        if (rc)
            fprintf(stderr, "make_picture: %s\n", pm_error_message());
        free(shown.eps_p);
        pm_sim_destroy(s);
    }
    pm_case_free(&c);
    return pm_exit_code(rc);
}
