/*
 * Plot q against the axial strain for the driver outputs of this example, with the analytic
 * Mohr-Coulomb peak q_f as a dashed line:
 *   make_plot OUT.png Q_F LABEL1 FILE1.csv [LABEL2 FILE2.csv ...]
 * The axial strain is the compression-positive logarithmic strain -eyy, in percent.
 */
#include "io/plot.h"
#include "pmech/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXN 100000

static int read_csv(const char *file, double *x, double *y, size_t *n)
{
    FILE *f = fopen(file, "r");
    char line[4096];
    if (!f || !fgets(line, sizeof line, f))
        return -1;
    *n = 0;
    while (*n < MAXN && fgets(line, sizeof line, f)) {
        double v[12];
        if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3],
                   &v[4], &v[5], &v[6], &v[7], &v[8], &v[9], &v[10], &v[11]) != 12)
            continue;
        x[*n] = -100.0 * v[2];  /* -eyy in percent */
        y[*n] = 1e-3 * v[10];   /* q in kPa */
        (*n)++;
    }
    fclose(f);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 5 || (argc - 3) % 2) {
        fprintf(stderr, "usage: make_plot OUT.png Q_F LABEL1 FILE1.csv [LABEL2 FILE2.csv ...]\n");
        return 2;
    }
    const double qf = atof(argv[2]) * 1e-3;
    const size_t nc = (size_t)(argc - 3) / 2;
    pm_plot_series s[8];
    memset(s, 0, sizeof s);
    static double xs[7][MAXN], ys[7][MAXN];
    double xmax = 0;
    for (size_t k = 0; k < nc && k < 7; k++) {
        if (read_csv(argv[4 + 2 * k], xs[k], ys[k], &s[k].n)) {
            fprintf(stderr, "make_plot: cannot read %s\n", argv[4 + 2 * k]);
            return 1;
        }
        s[k].x = xs[k];
        s[k].y = ys[k];
        s[k].label = argv[3 + 2 * k];
        if (s[k].n)
            xmax = xs[k][s[k].n - 1] > xmax ? xs[k][s[k].n - 1] : xmax;
    }
    double rx[2] = {0, xmax}, ry[2] = {qf, qf};
    char lab[128];
    snprintf(lab, sizeof lab, "q_f = 2 (c cos phi + s3 sin phi)/(1 - sin phi) = %.1f kPa", qf);
    s[nc] = (pm_plot_series){rx, ry, 2, lab, {0.3, 0.3, 0.3}, 1, 0};
    const pm_plot_opts o = {"Drained triaxial compression, s3 = 100 kPa, c = 10 kPa, phi = 30 deg",
                            "axial strain -e_yy (%, logarithmic)", "deviator q (kPa)", 900, 600, 1, 2};
    int rc = pm_plot_lines(argv[1], s, nc + 1, &o);
    if (rc)
        fprintf(stderr, "make_plot: %s\n", pm_error_message());
    return rc ? 1 : 0;
}
