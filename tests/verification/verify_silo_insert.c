/*
 * Axisymmetric silo discharge with a conical insert (seed 004 §5.1.1, second case;
 * examples/silo_discharge_insert at 50 mm cells instead of 20 mm, 0.8 s of discharge instead of 2 s):
 * cases/silo_discharge_insert.json.
 *
 * Set-up: the silo of verify_silo_discharge (radius 1 m, fill 3 m, outlet radius 0.2 m, viscoplastic
 * Drucker-Prager phi = 25 degrees, gamma = 50 /s, rho = 1500 kg/m^3, wall and floor mu_w = tan 20
 * degrees) with a rigid cone on the axis: base radius 0.4 m at z = 1 m, apex at z = 1.69 m (sides at
 * 60 degrees to the horizontal), an `obstacles[]` polygon with the same Coulomb friction. The fill
 * settles on the closed outlet while gravity grows over the first second, then the outlet opens.
 *
 * Judged: mass flow in the upper part, the seed's finding. The flow class is measured from how far each
 * point sinks between 0.25 and 0.8 s after the opening (a time average: the instantaneous velocities
 * of a viscoplastic continuum in MPM are noisy), for the points at z = 2.0 m and 2.5 m (0.3 and 0.8 m
 * above the apex) at 0.25 s:
 * - the mean drop next to the wall (r > 0.9 m) over that on the axis (r < 0.1 m) above 0.5, and
 * - the share of the cross-section (the points' volumes, which are per radian and so weigh the section
 *   by area) that sinks by more than a tenth of the axis's drop above 0.8.
 * Mass flow has the whole section sinking together (ratio near 1, share 1); funnel flow, the same silo
 * without the insert at the same resolution, gives ratios 0.05 (z = 2.0 m) and 0.07 (z = 2.5 m) and
 * shares 0.23 and 0.46 over the same window, and fails both. Measured here: ratios 1.01 and 0.90,
 * shares 1.00.
 * Reported: the discharge rate 0.25-0.8 s after the opening against Beverloo's 276 kg/s (C = 0.58,
 * D = 0.4 m, d = 0; see verify_silo_discharge), and the same class figures at z = 1.0 m, below the insert,
 * where the flow funnels into the outlet.
 */
#include "verify_util.h"

#include "solver/flow.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define T_OPEN 1.0
#define T_FROM (T_OPEN + 0.25)
#define T_TO (T_OPEN + 0.8)
#define R_SILO 1.0
#define H_CELL 0.05
#define RHO 1500.0
#define G 9.81

static const char *bench = "silo discharge with insert (seed 004)";

/* Whole-silo mass removed so far (the sink counts per radian). */
static double removed(const pm_sim *s)
{
    return 2 * M_PI * s->flow->snk[0].removed_mass;
}

/* The points' heights and volumes at the window's start, indexed by particle id. */
typedef struct {
    double *r, *z, *vol;
    int32_t n;
} snapshot;

static snapshot take(const pm_sim *s)
{
    const pm_particles *p = &s->p;
    snapshot a = {0};
    for (size_t i = 0; i < p->n; i++)
        a.n = p->id[i] + 1 > a.n ? p->id[i] + 1 : a.n;
    a.r = calloc((size_t)a.n, sizeof *a.r);
    a.z = calloc((size_t)a.n, sizeof *a.z);
    a.vol = calloc((size_t)a.n, sizeof *a.vol);
    if (!a.r || !a.z || !a.vol) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    for (int32_t k = 0; k < a.n; k++)
        a.z[k] = NAN;
    for (size_t i = 0; i < p->n; i++) {
        a.r[p->id[i]] = p->x[PM_DIM * i];
        a.z[p->id[i]] = p->x[PM_DIM * i + 1];
        a.vol[p->id[i]] = p->vol[i];
    }
    return a;
}

/* Drop of the points that stood within a cell of height z at the snapshot: a point removed by the outlet
 * since then has dropped all the way, by z. Judged or only reported. */
static int check_class(const pm_sim *s, const snapshot *a, double z, int judged, double secs)
{
    const pm_particles *p = &s->p;
    double *drop = malloc((size_t)a->n * sizeof *drop);
    if (!drop) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    for (int32_t k = 0; k < a->n; k++)
        drop[k] = a->z[k]; /* removed unless found below */
    for (size_t i = 0; i < p->n; i++)
        drop[p->id[i]] = a->z[p->id[i]] - p->x[PM_DIM * i + 1];
    const vu_band b = vu_silo_band((size_t)a->n, a->r, a->z, 1, a->vol, drop, z, H_CELL, R_SILO);
    free(drop);
    const double da = b.axis;
    const double ratio = da > 0 ? b.wall / da : 0, share = b.all > 0 ? b.moving / b.all : 0;
    char q[128];
    snprintf(q, sizeof q, "mass flow: wall / axis drop over 0.25-0.8 s at z = %.1f m (> 0.5)", z);
    int ok = vu_report(bench, q, ratio, 1, ratio - 1, judged ? 0.5 : -1, secs);
    snprintf(q, sizeof q, "mass flow: share of the section sinking at z = %.1f m (> 0.8)", z);
    ok &= vu_report(bench, q, share, 1, share - 1, judged ? 0.2 : -1, secs);
    snprintf(q, sizeof q, "axis drop over 0.25-0.8 s at z = %.1f m (m)", z);
    vu_report(bench, q, da, 0, da, -1, secs);
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    pm_case c;
    vu_load("tests/verification/cases/silo_discharge_insert.json", &c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    vu_run_to(s, T_FROM);
    const double m0 = removed(s);
    snapshot a = take(s);
    vu_run_to(s, T_TO);
    const double secs = vu_now() - t0;
    int ok = 1;
    ok &= check_class(s, &a, 2.0, 1, secs);
    ok &= check_class(s, &a, 2.5, 1, secs);
    check_class(s, &a, 1.0, 0, secs);
    const double W = (removed(s) - m0) / (T_TO - T_FROM), Wb = 0.58 * RHO * sqrt(G) * pow(0.4, 2.5);
    char q[96];
    snprintf(q, sizeof q, "discharge rate (kg/s) / Beverloo (C = 0.58, k d = 0): %.0f / %.0f", W, Wb);
    vu_report(bench, q, W / Wb, 1, W / Wb - 1, -1, secs);
    free(a.r);
    free(a.z);
    free(a.vol);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
