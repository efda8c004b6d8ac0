/*
 * Failure of a retaining wall (seed 004 §5.2; examples/retaining_wall at 0.25 m cells instead of
 * 0.125 m, 1 s after the release instead of 2 s): cases/retaining_wall.json.
 *
 * Set-up (plane strain): a concrete wall 0.5 m thick and 3 m high (elastic, E = 1 GPa, nu = 0.17,
 * rho = 2500 kg/m^3) whose lowest 0.25 m has cracked and carries no tension (viscoplastic
 * Drucker-Prager, phi = 40 degrees, gamma = 100 /s) stands on 1 m of soil (phi = 40 degrees, E = 5 MPa)
 * and retains 3 m of stored material behind it (phi = 30 degrees, E = 1 MPa, rho = 1500 kg/m^3). One
 * field: wall, base, soil and stored material stick where they meet (a rough wall). The wall is held
 * at its outer face while gravity grows over the first second; then it is released.
 *
 * Judged, 1 s after the release:
 * - the wall is still upright at the release (its rotation below 0.05 degrees) and has rotated outward
 *   (its top towards the open side) by more than 5 degrees after it: a cohesionless base cannot hold
 *   the overturning moment of the active thrust (Coulomb's horizontal thrust 0.5 K_a rho g H^2 cos delta
 *   = 17 kN per metre at H/3 = 1 m above the toe, 17 kN m, against 9 kN m of the wall's weight). Measured 0.0001 and 7.8 degrees;
 * - a shear band from the wall's heel to the top of the stored material: in each cell row of the stored
 *   material (by initial height), the farthest point from the wall that has moved at least half as far
 *   as the material next to the wall; a line through the heel fitted to those points makes the band's
 *   angle with the horizontal. Coulomb's active wedge behind a vertical rough wall (wall friction delta
 *   = phi = 30 degrees, one field) is at 54.3 degrees, Rankine's (smooth wall) at 45 + phi/2 = 60
 *   degrees; judged within 5 degrees of Coulomb's (49.3-59.3). Wrong answers it rejects: no wedge (the
 *   whole fill following the wall, or only the column next to it: angles far below 45 or near 90),
 *   the wedges of a friction angle 10 degrees off (phi = 20: 48.1 degrees, phi = 40: 60.4, both behind
 *   a rough wall) and Rankine's smooth-wall wedge, which the one-field model does not have. The band's
 *   scatter about its line is reported as the rms distance of the row points. Measured 51.8 degrees,
 *   rms 0.24 m (a cell); the example at 0.125 m cells: see its README.
 */
#include "verify_util.h"

#include <math.h>
#include <stdio.h>

#define T_RELEASE 1.0
#define T_END 2.0
#define H_CELL 0.25
#define WALL_BACK 3.5
#define BASE_Y 1.0
#define TOP_Y 4.0
#define STORED 3 /* bodies: soil, wall_base, wall, stored */

static const char *bench = "retaining wall failure (seed 004)";

/* Outward rotation (degrees) of the wall's line from foot to top: positive when the top has moved
 * towards -x, the open side. */
static double rotation(const pm_sim *s, size_t top, size_t foot)
{
    const double *a = s->p.x + PM_DIM * top, *b = s->p.x + PM_DIM * foot;
    return atan2(-(a[0] - b[0]), a[1] - b[1]) * 180 / M_PI;
}

/* The band's angle (degrees from the horizontal) and the rms horizontal distance of the row points
 * from the fitted line; 0 rows found gives NAN. */
static double band_angle(const pm_sim *s, double *rms)
{
    enum { ROWS = 12 };
    const pm_particles *p = &s->p;
    double near[ROWS] = {0}, far[ROWS];
    int n_near[ROWS] = {0};
    for (size_t i = 0; i < p->n; i++) {
        if (p->body[i] != STORED)
            continue;
        const int k = (int)((p->x0[PM_DIM * i + 1] - BASE_Y) / H_CELL);
        if (k < 0 || k >= ROWS || p->x0[PM_DIM * i] > WALL_BACK + 1.5 * H_CELL)
            continue;
        near[k] += hypot(p->x[PM_DIM * i] - p->x0[PM_DIM * i], p->x[PM_DIM * i + 1] - p->x0[PM_DIM * i + 1]);
        n_near[k]++;
    }
    for (int k = 0; k < ROWS; k++) {
        near[k] = n_near[k] ? near[k] / n_near[k] : 0;
        far[k] = -INFINITY;
    }
    for (size_t i = 0; i < p->n; i++) {
        if (p->body[i] != STORED)
            continue;
        const double *x0 = p->x0 + PM_DIM * i, *x = p->x + PM_DIM * i;
        const int k = (int)((x0[1] - BASE_Y) / H_CELL);
        if (k >= 0 && k < ROWS && hypot(x[0] - x0[0], x[1] - x0[1]) >= 0.5 * near[k])
            far[k] = fmax(far[k], x0[0]);
    }
    /* rows below the top row whose wall-side material has moved 5 cm or more */
    double num = 0, den = 0;
    int n = 0;
    for (int k = 0; k < ROWS - 1; k++)
        if (near[k] >= 0.05) {
            const double y = (k + 0.5) * H_CELL;
            num += (far[k] - WALL_BACK) * y;
            den += y * y;
            n++;
        }
    if (n < 3) {
        *rms = NAN;
        return NAN;
    }
    const double cot = num / den;
    double e2 = 0;
    for (int k = 0; k < ROWS - 1; k++)
        if (near[k] >= 0.05) {
            const double y = (k + 0.5) * H_CELL, e = far[k] - WALL_BACK - cot * y;
            e2 += e * e;
        }
    *rms = sqrt(e2 / n);
    return atan2(1.0, cot) * 180 / M_PI;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    pm_case c;
    vu_load("tests/verification/cases/retaining_wall.json", &c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    size_t top = vu_nearest(s, 3.25, 3.875), foot = vu_nearest(s, 3.25, 1.375);
    const double ktop[2] = {s->p.x[PM_DIM * top], s->p.x[PM_DIM * top + 1]};
    const double kfoot[2] = {s->p.x[PM_DIM * foot], s->p.x[PM_DIM * foot + 1]};
    vu_run_to(s, T_RELEASE);
    top = vu_track(s, top, ktop);
    foot = vu_track(s, foot, kfoot);
    double secs = vu_now() - t0;
    const double r0 = rotation(s, top, foot);
    int ok = vu_report(bench, "wall rotation at the release (degrees)", r0, 0, r0, 0.05, secs);
    vu_run_to(s, T_END);
    top = vu_track(s, top, ktop);
    foot = vu_track(s, foot, kfoot);
    secs = vu_now() - t0;
    const double r1 = rotation(s, top, foot);
    ok &= vu_report(bench, "outward wall rotation 1 s after the release (degrees, > 5)", r1, 5, r1 > 5 ? 0 : 1, 0,
                    secs);
    double rms;
    const double ang = band_angle(s, &rms);
    const double coulomb = 54.3;
    ok &= vu_report(bench, "shear band angle from the heel (degrees) vs Coulomb's rough-wall wedge", ang, coulomb,
                    isfinite(ang) ? ang - coulomb : INFINITY, 5.0, secs);
    vu_report(bench, "shear band: rms distance of the row points from the line (m)", rms, 0, rms, -1, secs);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
