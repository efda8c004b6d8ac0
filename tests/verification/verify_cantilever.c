/*
 * Cantilever under self-weight (seed 000 section 5.1; BENCHMARKS.md): L = 8, b = h = 1, rho = 1000,
 * E = 90 MPa, nu = 0, plane strain, neo-Hookean, clamped at x = 0, implicit quasi-static, 4 points per
 * cell. The example runs MPM with quadratic B-splines (examples/cantilever/case.json).
 *
 * Reference, computed here and not taken from pmech: the inextensible elastica of a cantilever under
 * its distributed dead load q = rho g b h (theta'' = (q / EI)(L - s) cos theta, theta(0) = 0,
 * theta'(L) = 0, RK4 with shooting on theta'(0)) plus the shear deflection q L^2 / (2 kappa G A),
 * kappa = 5/6. It gives 0.67435 m for the paper's beam (the paper's nonlinear FEM value is 0.67433);
 * linear Timoshenko gives 0.67806. Letting the shear strain follow the section's rotation in the same
 * ODE (Reissner's inextensible beam) moves the reference by -1.5e-4 relative: that is the beam-model
 * uncertainty of the reference, 20 times below the tightest tolerance below.
 *
 * Tip deflection: a least-squares plane through the displacements of the points of the last cell
 * column (reference x0 > L - h), evaluated at (L, 0.5) (cantilever_tip.h).
 *
 * Judged, with why:
 *  - the ODE reproduces 0.67435 to 2e-5 (the five digits quoted for it);
 *  - MPM bspline2 and GMM-MLS at h = 0.0625 within 0.3 % of the elastica. The linear answer is 0.55 %
 *    off, so a solver converging to it fails (checked: the linear value must fall outside 0.3 %);
 *  - MPM bspline2 at h = 0.5 ... 0.0625: the error against the elastica is reported per mesh; it falls
 *    from -0.06 % at h = 0.5 to below 1e-4 at h <= 0.25, which is the reference's own uncertainty, so
 *    no rate can be measured below that and none is judged; every mesh h <= 0.25 is judged within
 *    0.03 %, ten times tighter than the finest-mesh tolerance;
 *  - path independence: MPM bspline2 at h = 0.125 in 5 and 20 load steps agree within 3e-4 (a tenth
 *    of the accuracy tolerance, so the step count cannot decide the accuracy verdict; measured 1.1e-4,
 *    the re-gridding error of the particles moving through the grid; the former start-of-step spring
 *    on weak nodes made bspline2 depend on the step count by 0.7 % and failed this);
 *  - a slender case where geometric nonlinearity matters: the same beam with E = 40 MPa (tip
 *    deflection 18.6 % of L, linear Timoshenko 2.7 % above the elastica), h = 0.0625, 10 load steps:
 *    MPM bspline2 and GMM-MLS within 1 % of the elastica (a linear answer fails it);
 *  - the clamp reaction equals the weight 78,480 N to 1e-5 (no stabilisation force remains at
 *    convergence but the weak-node spring's, which vanishes for affine motion);
 *  - Newton converges quadratically on the first load step: the last residual is at most 10 times
 *    the square of the one before.
 * Reported, not judged: MPM with linear shape functions. Its answer grows with the number of load
 * steps (h = 0.0625: 0.6755 / 0.6797 / 0.6919 m in 1 / 10 / 40 steps), the cell-crossing error of C0
 * shape functions: every step starts with an out-of-balance force of about 3e-2 of the internal
 * forces (5e-4 with bspline2, which is the load increment) that the step then absorbs into the
 * deformation. That is a known limitation, not a tolerance to widen.
 */
#include "verify_util.h"
#include "cantilever_tip.h"

#include "pmech/error.h"
#include "solver/implicit.h"
#include "solver/sim_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define RHO_G (1000.0 * 9.81)
#define WEIGHT (8.0 * RHO_G)
#define E_PAPER 9.0e7
#define E_SLENDER 4.0e7
#define TOL_FINE 0.003
#define TOL_SLENDER 0.01
#define TOL_PATH 3e-4

/* The beam of unit depth and height: load per length, bending and shear stiffness (nu = 0). */
typedef struct {
    double q, EI, kGA;
    int coupled; /* 1: shear strain along the section normal inside the ODE (Reissner) */
} beam;

static beam make_beam(double E, int coupled)
{
    const beam b = {RHO_G * 1.0, E / 12.0, 5.0 / 6.0 * 0.5 * E, coupled};
    return b;
}

/* y = (theta, theta', x, w); s the arc length. */
static void rhs(const beam *b, double s, const double y[4], double f[4])
{
    const double th = y[0];
    const double gam = b->coupled ? -b->q * (L_BEAM - s) * cos(th) / b->kGA : 0.0;
    const double xs = cos(th) - gam * sin(th);
    f[0] = y[1];
    f[1] = b->q / b->EI * (L_BEAM - s) * xs;
    f[2] = xs;
    f[3] = sin(th) + gam * cos(th);
}

/* Integrate from the clamp with theta'(0) = k0; returns theta'(L), the tip's w in *w. */
static double shoot(const beam *b, double k0, double *w)
{
    enum { STEPS = 4000 };
    const double ds = L_BEAM / STEPS;
    double y[4] = {0, k0, 0, 0};
    for (int n = 0; n < STEPS; n++) {
        const double s = n * ds;
        double k1[4], k2[4], k3[4], k4[4], t[4];
        rhs(b, s, y, k1);
        for (int i = 0; i < 4; i++)
            t[i] = y[i] + 0.5 * ds * k1[i];
        rhs(b, s + 0.5 * ds, t, k2);
        for (int i = 0; i < 4; i++)
            t[i] = y[i] + 0.5 * ds * k2[i];
        rhs(b, s + 0.5 * ds, t, k3);
        for (int i = 0; i < 4; i++)
            t[i] = y[i] + ds * k3[i];
        rhs(b, s + ds, t, k4);
        for (int i = 0; i < 4; i++)
            y[i] += ds / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
    *w = y[3];
    return y[1];
}

/* Tip deflection (positive down) of the elastica; the coupled form carries its shear inside. */
static double elastica(double E, int coupled)
{
    const beam b = make_beam(E, coupled);
    double w, k0 = -b.q * L_BEAM * L_BEAM / (2 * b.EI), k1 = 0.99 * k0; /* linear root curvature */
    double f0 = shoot(&b, k0, &w), f1 = shoot(&b, k1, &w);
    for (int it = 0; it < 50 && fabs(f1) > 1e-14 * fabs(k1) && f1 != f0; it++) {
        const double k2 = k1 - f1 * (k1 - k0) / (f1 - f0);
        k0 = k1;
        f0 = f1;
        k1 = k2;
        f1 = shoot(&b, k1, &w);
    }
    shoot(&b, k1, &w);
    const double shear = coupled ? 0.0 : b.q * L_BEAM * L_BEAM / (2 * b.kGA);
    return -w + shear;
}

static double timoshenko(double E)
{
    const beam b = make_beam(E, 0);
    return b.q * pow(L_BEAM, 4) / (8 * b.EI) + b.q * L_BEAM * L_BEAM / (2 * b.kGA);
}

typedef struct {
    double delta, secs, reaction;
    double r_last, r_prev; /* the last two residuals of the first load step */
} result;

/* One run of the case: method/shape, cell size h, load steps, Young's modulus. */
static int run(const char *method, const char *shape, double h, int steps, double E, result *out)
{
    pm_case c;
    vu_load("examples/cantilever/case.json", &c);
    c.method = strcmp(method, "gmm") == 0 ? PM_METHOD_GMM : PM_METHOD_MPM;
    snprintf(c.shape_function, sizeof c.shape_function, "%s", shape);
    if (E != c.materials[0].E && pm_material_set_elastic(&c.materials[0], E, c.materials[0].nu, NAN, NAN)) {
        fprintf(stderr, "%s\n", pm_error_message());
        return 0;
    }
    if (E < E_PAPER) { /* the slender beam sags further: room below */
        c.grid.origin[1] = -2.0;
        c.grid.size[1] = 3.5;
    }
    c.grid.cells[0] = (int)lround(c.grid.size[0] / h);
    c.grid.cells[1] = (int)lround(c.grid.size[1] / h);
    c.analysis.load_steps = steps;
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    const double dt = c.analysis.end_time / steps;
    out->r_last = out->r_prev = NAN;
    int ok = 1;
    for (int step = 0; step < steps && ok; step++) {
        pm_implicit_report rep;
        if (pm_implicit_step(s, dt, NULL, &rep) != 0) {
            fprintf(stderr, "%s/%s h = %g, %d steps: %s\n", method, shape, h, steps, pm_error_message());
            ok = 0;
        } else if (step == 0 && rep.n_history >= 3) {
            out->r_last = rep.residual[rep.n_history - 1];
            out->r_prev = rep.residual[rep.n_history - 2];
        }
    }
    if (ok) {
        double R[2];
        pm_implicit_reaction(s, 0, R);
        out->reaction = R[1];
        out->delta = tip_deflection(s, h);
        out->secs = vu_now() - t0;
        printf("%s/%s E = %g MPa, h = %-7g %2d steps: tip deflection %.6f m  (%.2f s)\n", method, shape, E / 1e6, h,
               steps, out->delta, out->secs);
    }
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    const char *B = "cantilever (implicit quasi-static)";
    char q[96];
    int ok = 1;

    const double ref = elastica(E_PAPER, 0), ref_coupled = elastica(E_PAPER, 1), lin = timoshenko(E_PAPER);
    const double ref_sl = elastica(E_SLENDER, 0), lin_sl = timoshenko(E_SLENDER);
    printf("elastica + shear %.6f m (Reissner %.6f), linear Timoshenko %.6f; slender (E = 40 MPa): %.6f, linear "
           "%.6f\n",
           ref, ref_coupled, lin, ref_sl, lin_sl);
    ok &= vu_report(B, "elastica + shear, ODE here [m]", ref, 0.67435, (ref - 0.67435) / 0.67435, 2e-5, 0);
    vu_report(B, "Reissner elastica (beam-model spread) [m]", ref_coupled, ref, (ref_coupled - ref) / ref, -1, 0);
    const double lin_err = (lin - ref) / ref, lin_sl_err = (lin_sl - ref_sl) / ref_sl;
    vu_report(B, "linear Timoshenko (must fail the 0.3 % check) [m]", lin, ref, lin_err, -1, 0);
    vu_report(B, "slender: linear Timoshenko (must fail the 1 % check) [m]", lin_sl, ref_sl, lin_sl_err, -1, 0);
    if (!(fabs(lin_err) > TOL_FINE) || !(fabs(lin_sl_err) > TOL_SLENDER)) {
        printf("the tolerances would let a linear answer pass\n");
        ok = 0;
    }

    /* MPM bspline2, mesh study in 10 load steps */
    const double hs[4] = {0.5, 0.25, 0.125, 0.0625};
    result r[4];
    double rows[4][3];
    for (int k = 0; k < 4; k++) {
        if (!run("mpm", "bspline2", hs[k], 10, E_PAPER, &r[k]))
            return 1;
        rows[k][0] = hs[k];
        rows[k][1] = r[k].delta;
        rows[k][2] = r[k].secs;
    }
    for (int k = 0; k < 4; k++) {
        snprintf(q, sizeof q, "MPM bspline2 tip deflection h=%g [m]", hs[k]);
        const double e = (r[k].delta - ref) / ref;
        ok &= vu_report(B, q, r[k].delta, ref, e, k == 3 ? TOL_FINE : k ? 0.1 * TOL_FINE : -1, r[k].secs);
    }
    ok &= vu_report(B, "clamp reaction / weight (MPM, h=0.0625)", r[3].reaction / WEIGHT, 1.0,
                    r[3].reaction / WEIGHT - 1.0, 1e-5, 0);
    printf("Newton, first load step h=0.125: last residual %.3e, previous %.3e\n", r[2].r_last, r[2].r_prev);
    const double qratio = r[2].r_last / (r[2].r_prev * r[2].r_prev);
    ok &= vu_report(B, "quadratic Newton: r_k / r_{k-1}^2", qratio, 0, isfinite(qratio) ? qratio : INFINITY, 10, 0);

    /* GMM-MLS at the finest mesh */
    result g;
    if (!run("gmm", "mls", 0.0625, 10, E_PAPER, &g))
        return 1;
    ok &= vu_report(B, "GMM-MLS tip deflection h=0.0625 [m]", g.delta, ref, (g.delta - ref) / ref, TOL_FINE, g.secs);

    /* path independence */
    result p5, p20;
    if (!run("mpm", "bspline2", 0.125, 5, E_PAPER, &p5) || !run("mpm", "bspline2", 0.125, 20, E_PAPER, &p20))
        return 1;
    ok &= vu_report(B, "MPM bspline2 h=0.125: 20 vs 5 load steps", p20.delta, p5.delta, (p20.delta - p5.delta) / p5.delta,
                    TOL_PATH, p5.secs + p20.secs);

    /* slender beam */
    result sm, sg;
    if (!run("mpm", "bspline2", 0.0625, 10, E_SLENDER, &sm) || !run("gmm", "mls", 0.0625, 10, E_SLENDER, &sg))
        return 1;
    ok &= vu_report(B, "slender E=40MPa: MPM bspline2 h=0.0625 [m]", sm.delta, ref_sl, (sm.delta - ref_sl) / ref_sl,
                    TOL_SLENDER, sm.secs);
    ok &= vu_report(B, "slender E=40MPa: GMM-MLS h=0.0625 [m]", sg.delta, ref_sl, (sg.delta - ref_sl) / ref_sl,
                    TOL_SLENDER, sg.secs);

    /* linear shape functions: the known cell-crossing drift, reported */
    result l5, l20, l10;
    if (run("mpm", "linear", 0.0625, 10, E_PAPER, &l10))
        vu_report(B, "MPM linear tip deflection h=0.0625 (known limitation) [m]", l10.delta, ref,
                  (l10.delta - ref) / ref, -1, l10.secs);
    if (run("mpm", "linear", 0.125, 5, E_PAPER, &l5) && run("mpm", "linear", 0.125, 20, E_PAPER, &l20))
        vu_report(B, "MPM linear h=0.125: 20 vs 5 load steps (known limitation)", l20.delta, l5.delta,
                  (l20.delta - l5.delta) / l5.delta, -1, l5.secs + l20.secs);

    vu_write_csv("cantilever_convergence.csv", "h,tip_deflection,seconds", &rows[0][0], 4, 3);
    return ok ? 0 : 1;
}
