/* Shared helpers of the verification tests: load a case, run it step by step, report results in a
 * form tools/verify.sh collects into docs/verification.md. */
#ifndef PMECH_VERIFY_UTIL_H
#define PMECH_VERIFY_UTIL_H

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

#endif
