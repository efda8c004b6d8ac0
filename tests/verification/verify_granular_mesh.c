/*
 * Mesh convergence of the granular column's run-out: the cohesionless column of verify_granular_column
 * at aspect ratio a = 0.5 (L0 = 1 m, H = 0.5 m; cases/granular_column_a05.json: Mohr-Coulomb c = 0,
 * phi = 30 deg, psi = 0, rough floor, smooth wall, pmech's defaults: MUSL, pure FLIP, linear shape
 * functions, 2 x 2 points per cell, CFL 0.2) on h = L0/8 and h = L0/16, to t = 1.8 s. a = 0.5 is the
 * cheapest column that shows the trend of the run-out study (examples/granular_column).
 *
 * Judged, with why:
 *  - both runs reach 1.8 s (a run that stops, e.g. a particle leaving the grid, fails);
 *  - no particle beyond 1.1 times the deposit's front (isolated points racing ahead);
 *  - at rest: the front advances less than 0.05 L0 over the last 0.4 s (measured below 0.01 L0).
 * Expected to fail, and marked so instead of being given a tolerance it would pass:
 *  - the two meshes' run-outs (L_f - L0) / L0 within 5 % of each other (the convergence
 *    criterion, the difference over the finer mesh's run-out). Measured 0.314 and 0.544, a difference
 *    of 42 % of 0.544, and L0/32 gives 0.690: the run-out is not converged in h. The cells' height
 *    decides it (docs/verification.md has the study: a tail one or two cells thick keeps lengthening
 *    as the cells get flatter). The test exits 1 when the two meshes DO agree within 5 %: the defect
 *    is then gone and this check must become a judged one.
 * Reported: each mesh's run-out against the law 1.2 a of Lube et al. (2005) (-48 % and -9 %), the
 * deposit's volume over the column's (the cohesionless model's apex return lets points expand at
 * zero stress: 1.085 and 1.12 here, where psi = 0 allows no plastic dilation), seconds.
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>

#define ASPECT 0.5
#define L0 1.0
#define STRAY 1.1
#define REST_WINDOW 0.4
#define MESH_TOL 0.05

typedef struct mesh_run {
    double runout, stray, creep, volume_ratio, seconds;
    int finished;
} mesh_run;

/* The case run on its grid refined @p scale times (the case is changed). */
static mesh_run run_mesh(pm_case *c, int scale)
{
    c->grid.cells[0] *= scale;
    c->grid.cells[1] *= scale;
    const double h = c->grid.size[0] / c->grid.cells[0];
    mesh_run r = {NAN, NAN, NAN, NAN, 0, 1};
    const double t0 = vu_now(), end = c->analysis.end_time;
    pm_sim *s = vu_sim(c, 1);
    double vol0 = 0, front_before = NAN, xmax;
    for (size_t i = 0; i < s->p.n; i++)
        vol0 += s->p.vol[i];
    int rc = vu_steps_until(s, end, end - REST_WINDOW);
    if (rc == PM_OK) {
        front_before = vu_deposit_front(s, 2 * h, &xmax);
        rc = vu_steps_until(s, end, end);
    }
    if (rc != PM_OK) {
        fprintf(stderr, "h = L0/%d: stopped at t = %g s: %s\n", (int)(L0 / h + 0.5), s->t, pm_error_message());
        r.finished = 0;
    }
    r.seconds = vu_now() - t0;
    const double front = vu_deposit_front(s, 2 * h, &xmax);
    double vol = 0;
    for (size_t i = 0; i < s->p.n; i++)
        vol += s->p.vol[i];
    r.runout = (front - L0) / L0;
    r.stray = xmax / front;
    r.creep = (front - front_before) / L0;
    r.volume_ratio = vol / vol0;
    printf("h = L0/%d: front %.4f m, farthest particle %.4f m, deposit volume / column volume %.4f, %.1f s\n",
           (int)(L0 / h + 0.5), front, xmax, r.volume_ratio, r.seconds);
    pm_sim_destroy(s);
    return r;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    const char *B = "granular column run-out under refinement, a = 0.5";
    pm_case c;
    vu_load("tests/verification/cases/granular_column_a05.json", &c);
    const double law = 1.2 * ASPECT;
    int ok = 1;
    mesh_run r[2];
    for (int k = 0; k < 2; k++) {
        const int scale = k ? 2 : 1, n = (int)(c.grid.cells[0] / c.grid.size[0] * L0 + 0.5) * scale;
        r[k] = run_mesh(&c, scale);
        char q[96];
        snprintf(q, sizeof q, "h = L0/%d: end time reached", n);
        ok &= vu_report(B, q, r[k].finished, 1, r[k].finished - 1.0, 0, r[k].seconds);
        snprintf(q, sizeof q, "h = L0/%d: farthest particle / front", n);
        ok &= vu_report(B, q, r[k].stray, 1, r[k].stray - 1, STRAY - 1, 0);
        snprintf(q, sizeof q, "h = L0/%d: front's advance over the last 0.4 s / L0", n);
        ok &= vu_report(B, q, r[k].creep, 0, r[k].creep, 0.05, 0);
        snprintf(q, sizeof q, "h = L0/%d: (L_f - L0) / L0 vs 1.2 a", n);
        vu_report(B, q, r[k].runout, law, (r[k].runout - law) / law, -1, 0);
        snprintf(q, sizeof q, "h = L0/%d: deposit volume / column volume (psi = 0)", n);
        vu_report(B, q, r[k].volume_ratio, 1, r[k].volume_ratio - 1, -1, 0);
    }
    const double change = (r[1].runout - r[0].runout) / r[1].runout;
    vu_report(B, "run-out L0/8 vs L0/16, expected to fail the 5 % convergence criterion (measured 42 %)",
              r[0].runout, r[1].runout, change, -1, r[0].seconds + r[1].seconds);
    if (fabs(change) <= MESH_TOL) {
        printf("the two meshes now agree within %.0f %%: the run-out converges, so judge this check (and update "
               "docs/verification.md) instead of expecting it to fail\n",
               100 * MESH_TOL);
        ok = 0;
    }
    pm_case_free(&c);
    return ok ? 0 : 1;
}
