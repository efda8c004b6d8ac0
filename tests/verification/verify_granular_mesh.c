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
 *
 * Second part, judged: the setting that met both of the criteria in the run-out study
 * (docs/verification-notes.md, "Rate dependence against localisation"): a = 1 (H = L0 = 1 m;
 * cases/granular_column_a1_vp.json, the study's case for a = 1) with Perzyna Drucker-Prager
 * (`viscoplastic_drucker_prager`) matched to phi = 30 deg in plane strain (friction_angle 25.11 deg:
 * m = sqrt(3) sin 30 deg, the deviatoric flow's psi = 0) and gamma = 10 / s, on L0/8 and L0/16, to
 * t = 2.168 s. The same run, end, stray and rest checks as above, and:
 *  - the two run-outs within 5 % of each other (the criterion; measured 1.020 and 1.058,
 *    3.6 %; the Mohr-Coulomb defaults give 1.132 and 1.492 here, 24 %, and fail it);
 *  - each run-out within 20 % of the law 1.2 a (the experiments' scatter and range of materials, as
 *    in verify_granular_column; measured -15 % and -12 %);
 *  - each height at the wall (highest particle within a cell of it) within 20 % of the law H_f = a
 *    below a = 1.15 (measured 0.970 and 0.983 L0).
 * gamma = 10 / s is a regularisation, not the sand's rate dependence (mu(I) with Jop et al.'s
 * parameters and 0.5 mm grains gives gamma of about 800 / s, which behaves as Mohr-Coulomb here); at
 * a = 0.5 the same setting moves 39 % from L0/8 to L0/16 and 3.1 % from L0/16 to L0/32. It is
 * not shown to converge: at a = 1, L0/32 and L0/64 give 1.091 and 1.152 (5.3 %, just outside the
 * criterion); the check pins the setting's behaviour on the meshes it runs, against the defaults' 24 %.
 * Small variant (PMECH_VERIFY_SMALL, for sanitizer builds; the whole test is about 9 s of CPU in a
 * release build, over 3 minutes under ASan): the second part only, unchanged, so every judged
 * criterion of the recommended setting is still judged; the first part's judged figures (end, strays,
 * rest) are of the kind verify_granular_column judges.
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

#define VP_ASPECT 1.0
#define LAW_TOL 0.2

typedef struct mesh_run {
    double runout, stray, creep, volume_ratio, height, seconds;
    int finished;
} mesh_run;

/* The case run on its grid refined @p scale times (the case is changed). */
static mesh_run run_mesh(pm_case *c, int scale)
{
    c->grid.cells[0] *= scale;
    c->grid.cells[1] *= scale;
    const double h = c->grid.size[0] / c->grid.cells[0];
    mesh_run r = {NAN, NAN, NAN, NAN, NAN, 0, 1};
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
    double vol = 0, top = 0;
    for (size_t i = 0; i < s->p.n; i++) {
        vol += s->p.vol[i];
        if (s->p.x[PM_DIM * i] < h)
            top = fmax(top, s->p.x[PM_DIM * i + 1]);
    }
    r.height = top / L0;
    r.runout = (front - L0) / L0;
    r.stray = xmax / front;
    r.creep = (front - front_before) / L0;
    r.volume_ratio = vol / vol0;
    printf("h = L0/%d: front %.4f m, farthest particle %.4f m, deposit volume / column volume %.4f, %.1f s\n",
           (int)(L0 / h + 0.5), front, xmax, r.volume_ratio, r.seconds);
    pm_sim_destroy(s);
    return r;
}

/* The second part of the header: the rate-dependent setting at a = 1 on L0/8 and L0/16, judged. */
static int judge_viscoplastic(void)
{
    const char *B = "granular column run-out under refinement, a = 1, Perzyna Drucker-Prager gamma = 10 / s";
    pm_case c;
    vu_load("tests/verification/cases/granular_column_a1_vp.json", &c);
    const double law = 1.2 * VP_ASPECT, law_h = VP_ASPECT;
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
        ok &= vu_report(B, q, r[k].runout, law, (r[k].runout - law) / law, LAW_TOL, 0);
        snprintf(q, sizeof q, "h = L0/%d: H_f / L0 vs a", n);
        ok &= vu_report(B, q, r[k].height, law_h, (r[k].height - law_h) / law_h, LAW_TOL, 0);
        snprintf(q, sizeof q, "h = L0/%d: deposit volume / column volume", n);
        vu_report(B, q, r[k].volume_ratio, 1, r[k].volume_ratio - 1, -1, 0);
    }
    const double change = (r[1].runout - r[0].runout) / r[1].runout;
    ok &= vu_report(B, "run-out L0/8 vs L0/16 (the 5 % convergence criterion)", r[0].runout, r[1].runout, change,
                    MESH_TOL, r[0].seconds + r[1].seconds);
    pm_case_free(&c);
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    if (vu_small())
        return judge_viscoplastic() ? 0 : 1;
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
    ok &= judge_viscoplastic();
    return ok ? 0 : 1;
}
