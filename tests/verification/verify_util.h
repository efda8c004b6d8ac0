/* Shared helpers of the verification tests: load a case, run it step by step, report results in a
 * form tools/verify.sh collects into docs/verification.md. */
#ifndef PMECH_VERIFY_UTIL_H
#define PMECH_VERIFY_UTIL_H

#include "contact/contact.h"
#include "pmech/case.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"

/** Directory of the verification sources (argv[1]); examples are at <dir>/../../examples. */
extern const char *vu_dir;

/** Parse argv; call first. */
void vu_init(int argc, char **argv);

/**
 * 1 when the environment asks for the small variant (PMECH_VERIFY_SMALL set and not "0"): the tests
 * that take minutes in a release build then run a smaller case they document, judged with tolerances
 * measured for it, so that sanitizer builds (make asan, 10-30 times slower) still check their paths.
 * The first call prints a line saying the small variant runs.
 */
int vu_small(void);

/** Load a case relative to the repository root (e.g. "examples/dyka_bar/case.json"); aborts on error. */
void vu_load(const char *rel, pm_case *c);

/** Create a simulation of @p c with @p threads threads; aborts on error. */
pm_sim *vu_sim(const pm_case *c, int threads);

/** Step size the run loop would take next (fixed or CFL). */
double vu_dt(const pm_sim *s);

/** One explicit step towards @p end (clipped to it); exits 1 with the error if the step fails.
 *  Returns 0 without stepping once @p end is reached, else 1. */
int vu_advance(pm_sim *s, double end);

/** Explicit steps until @p end (vu_advance until it returns 0). */
void vu_run_to(pm_sim *s, double end);

/**
 * Explicit steps towards @p end (vu_dt, the last one clipped to @p end) while the time is below
 * @p mark as well. Unlike vu_run_to(s, mark), the mark clips no step: the steps are those of one run to
 * @p end, so a test can act at the first step boundary at or after the mark (clear a resultant, take a
 * measure) and call it again with mark = end to finish the same run. Returns PM_OK, or the failed
 * step's error code (its message in pm_error_message()) without exiting, so that the test can still
 * report the run as stopped.
 */
int vu_steps_until(pm_sim *s, double end, double mark);

/**
 * Explicit steps to @p end (vu_dt, the last one clipped to it), with @p each (unless NULL) called with
 * @p ctx after every step. Returns 1 once @p end is reached; 0 as soon as a step fails (after printing
 * "step failed: <error>" on stderr, without exiting, so that the test can still report the run) or
 * @p each returns 0.
 */
int vu_run_each(pm_sim *s, double end, int (*each)(pm_sim *s, void *ctx), void *ctx);

/**
 * The corners of a @p width x @p height block resting on a slope that runs down to the right from
 * (0, @p y0) at @p theta_deg degrees: its bottom lies on the slope from @p s0 to s0 + width along it.
 * Counter-clockwise from the bottom's upper end.
 */
void vu_slope_block(double theta_deg, double y0, double s0, double width, double height, double q[4][PM_DIM]);

/**
 * The block of the Gmsh incline tests loaded into @p c: 0.2 m x 0.06 m, density 1000, linear elastic
 * (E = 1e7, nu = 0.3), its bottom on the slope of @p dir/gmsh_incline<deg>.msh (the 1-D group "slope",
 * running down to the right from (0, 0.4)) from s = 0.1 to 0.3 along it, Coulomb friction @p mu there,
 * gravity -@p g, explicit MUSL at CFL 0.3 to @p t_end. @p method NULL: MPM (the default); otherwise
 * that method ("gmm" with MLS, "rkpm" with rk_cubic). Exits 2 if the case does not load.
 */
void vu_gmsh_incline_case(const char *dir, int deg, const char *method, double t_end, double g, double mu,
                          pm_case *c);

/** What a block sliding down a slope did over a run (vu_slope_run). */
typedef struct vu_slope {
    double v_along;  /**< body 0's mean velocity along the slope at the end */
    double travel;   /**< its centre of mass's travel along the slope */
    double force[2]; /**< the slope's mean normal force, and the magnitude of its mean tangential one */
    double secs;     /**< seconds taken, set-up and run */
    int ok;          /**< 0 if a step failed: the figures are then those at the failure */
} vu_slope;

/**
 * Run case @p c, a block on a slope at @p theta_deg degrees down to the right that is its one contact
 * surface (surface 0, of kind @p kind: a set-up that made another kind exits 1), on one thread to its end
 * time with the explicit steps of vu_steps_until. The surface's summed impulse is cleared at the first
 * step boundary at or after half the end time, so its mean force over the second half (as forces.csv
 * reports it) is that impulse over the time since. A failed step stops the run and prints
 * "<label>: <error>".
 */
vu_slope vu_slope_run(const pm_case *c, double theta_deg, pm_contact_kind kind, const char *label);

/**
 * Load case @p rel into @p c (vu_load) and run it on one thread to its end time, the contact surfaces'
 * traction profiles (pm_contact_profile) gathered over the last @p window seconds only: the run stops
 * exactly at end - window, clears them, and goes on. Gives the time they were cleared at in *t_from and
 * the seconds taken (set-up and run) in *secs; returns the simulation, for the caller to destroy.
 */
pm_sim *vu_run_profiled(const char *rel, pm_case *c, double window, double *t_from, double *secs);

/** A way to run a simulation to time @p end (vu_run_to, or a test's implicit steps). */
typedef void (*vu_runner)(pm_sim *s, double end);

/**
 * The sliding-block benchmark shared by the explicit and the implicit solver: the case @p rel is a
 * block on a friction boundary (its first boundary condition) under gravity tilted by 30 degrees, run
 * to 0.1 s by @p run. The rigid-body answer while it slides is the mean velocity
 * g (sin(theta) - mu cos(theta)) t: with mu = 0 and 0.1 each within 2 %. With mu = 1.5 tan(theta) it
 * sticks, gravity ramped over 20 ms (a sudden load makes the elastic block bounce on its base, and a
 * node lifted off carries no friction; the answer, no travel, is unchanged): its centre of mass's travel
 * over the frictionless g sin(theta) t^2 / 2 within @p stick_tol. Reports the three rows under @p bench,
 * @p what put into the velocity rows' names after the unit (e.g. ", implicit", or ""). Returns 1 if all
 * three pass.
 */
int vu_sliding_block(const char *bench, const char *rel, const char *what, vu_runner run, double stick_tol);

/** One step of @p dt by a test's solver (e.g. implicit, its report kept in @p ctx); PM_OK or the error. */
typedef int (*vu_step_fn)(pm_sim *s, double dt, void *ctx);

/**
 * A soil column collapsing away from a smooth wall at x = 0, run through the ascending times
 * @p at[0..n-1] with steps of vu_dt (the step before each time clipped to reach it) taken by @p step
 * (NULL: pm_explicit_step). At each time the run-out, the largest x of all points, in runout[k], and the
 * height at the wall, the largest y of the points within 0.1 m of it, in height[k]. A failed step stops
 * the run with "<label>: stopped at t = ...: <error>" on stderr, the times not reached left unset.
 * Returns the number of steps taken; the time reached is s->t.
 */
long vu_collapse_run(pm_sim *s, const double *at, int n, vu_step_fn step, void *ctx, const char *label,
                     double *runout, double *height);

/** Index of the particle nearest to @p x at the start (ties: lowest index). */
size_t vu_nearest(const pm_sim *s, double x, double y);

/**
 * Follow a particle across the periodic sorts that reorder the arrays: @p ip is its index, @p key
 * its initial position (p->x0 identifies a particle). Returns the current index.
 */
size_t vu_track(const pm_sim *s, size_t ip, const double key[2]);

/** Mass-weighted mean velocity and centre of mass of body @p b. */
void vu_body_mean(const pm_sim *s, int b, double v[2], double x[2]);

/**
 * Record one verified figure: prints a `VERIFY|benchmark|quantity|pmech|reference|error|tolerance|
 * seconds|PASS/FAIL` line and returns 1 if within tolerance (|error| <= tol). Use tol < 0 for a
 * figure that is reported but not judged.
 */
int vu_report(const char *bench, const char *quantity, double value, double ref, double err, double tol,
              double seconds);

/** Monotonic seconds. */
double vu_now(void);

/** Write a CSV file of @p ncol columns (header comma separated) next to the test's working dir. */
void vu_write_csv(const char *path, const char *header, const double *data, size_t nrow, int ncol);

/**
 * Plot a time history against a reference curve into PNG @p png (in the working directory;
 * tools/verify.sh copies *.png into docs/img/verification).
 */
void vu_plot_history(const char *png, const char *title, const char *ylabel, const double *t, const double *v,
                     size_t n, const char *label, const double *ref, const char *ref_label);

/**
 * The front of a granular deposit along x: the particles' x sorted, up to the first gap wider than
 * @p gap (a particle beyond such a gap has left the deposit); the farthest particle's x in *xmax.
 * Returns NAN when out of memory.
 */
double vu_deposit_front(const pm_sim *s, double gap, double *xmax);

/** How the fill of an axisymmetric silo moves down at one height (vu_silo_band). */
typedef struct vu_band {
    double axis;   /**< mean downward motion of the points on the axis, r < 0.1 m (0 if none) */
    double wall;   /**< that of the points next to the wall, r > r_wall - 0.1 m (0 if none) */
    double all;    /**< summed volume of the points in the band */
    double moving; /**< that of the points moving down by more than a tenth of the axis's mean */
} vu_band;

/**
 * The points of a silo of radius @p r_wall within @p half of height @p z (|height - z| < half; a NaN
 * height, a point not there, is outside): point i at radius r[stride * i] and height
 * height[stride * i], of volume vol[i], moving down by down[i] (a speed, or a drop over a time).
 * The means and sums of vu_band, each summed in the order of the points; the funnel and mass flow
 * classes of the silo tests are made from them.
 */
vu_band vu_silo_band(size_t n, const double *r, const double *height, size_t stride, const double *vol,
                     const double *down, double z, double half, double r_wall);

#endif
