/**
 * @file strength_reduction.h
 * @brief Factor of safety of a slope by strength reduction (Griffiths & Lane 1999): the case is run
 *        again and again from its initial state with the strength of every Mohr-Coulomb and
 *        Drucker-Prager material divided by a trial factor F, and bisection finds the factor at which
 *        the slope stops standing under gravity.
 *
 * Reduction: c -> c / F, phi -> atan(tan(phi) / F), psi -> atan(tan(psi) / F) capped at the reduced
 * phi, a Mohr-Coulomb tension cut-off T -> T / F. Elastic constants, density and Drucker-Prager
 * hardening moduli stay. Other models are not changed.
 *
 * A trial fails (pm_srf_criterion):
 *  - PM_SRF_CONVERGENCE: the run stops before the end time because a load step does not converge
 *    after `newton.max_step_cuts` halvings (each attempt ends after `newton.max_iterations`
 *    iterations or as soon as the residual grows): gravity cannot be carried;
 *  - PM_SRF_DISPLACEMENT: that (or any stop of an explicit run), or the largest particle
 *    displacement at the end exceeds `displacement_ratio` times that of the same case with the
 *    reduced materials made linear elastic (one extra run, done first).
 */
#ifndef PMECH_STRENGTH_REDUCTION_H
#define PMECH_STRENGTH_REDUCTION_H

#include "pmech/case.h"
#include "pmech/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most trials one search runs: the two ends and the bisections (50 halve any bracket to nothing). */
#define PM_SRF_MAX_TRIALS 64

/** One trial factor and what its run did. */
typedef struct pm_srf_trial {
    double factor;            /**< F */
    int converged;            /**< 1: the run reached its end time */
    int failed;               /**< 1: the slope does not stand at F (not converged, or moved too far) */
    double max_displacement;  /**< largest particle displacement at the end (or the last converged state) */
    double t;                 /**< time reached (end_time unless the run stopped) */
    long newton_iterations;   /**< quasi-static: all Newton iterations of the run */
    long step_cuts;           /**< quasi-static: halvings of load steps */
    double wall_seconds;      /**< the trial's run */
} pm_srf_trial;

/** The outcome of a search. */
typedef struct pm_srf_result {
    double fos;               /**< factor of safety: the middle of [lo, hi] */
    double lo;                /**< largest factor that held */
    double hi;                /**< smallest factor that failed */
    double elastic_displacement; /**< PM_SRF_DISPLACEMENT: the elastic run's largest displacement (else 0) */
    int n_trials;             /**< entries of trial[], in the order run */
    pm_srf_trial trial[PM_SRF_MAX_TRIALS];
} pm_srf_result;

/**
 * @brief Divide the strength of @p m by @p factor (through its model's
 *        pm_material_ops::reduce_strength: Mohr-Coulomb and Drucker-Prager; models without one are
 *        copied unchanged) and recompute the model's derived constants.
 * @param m the material as given
 * @param factor F > 0
 * @param out receives the reduced material (may be @p m itself)
 * @return PM_OK, or PM_EINPUT when the model rejects the reduced parameters
 */
int pm_srf_reduce_material(const pm_material *m, double factor, pm_material *out);

/**
 * @brief Judge a trial that ran to its end time: does the slope stand? Only PM_SRF_DISPLACEMENT
 *        can fail such a trial, when its largest displacement exceeds displacement_ratio times
 *        @p elastic_displacement (> 0); a trial that stopped early has failed without asking.
 * @param so the search's options (criterion, displacement_ratio)
 * @param t the trial (max_displacement is read)
 * @param elastic_displacement the elastic reference run's largest displacement (0: none yet)
 * @return 1 failed, 0 stands
 */
int pm_srf_judge(const pm_srf_opts *so, const pm_srf_trial *t, double elastic_displacement);

/**
 * @brief Run @p c once with every strength divided by @p factor and judge the run.
 * @param c case with analysis.strength_reduction set
 * @param factor F > 0
 * @param elastic_displacement the reference of PM_SRF_DISPLACEMENT (ignored otherwise)
 * @param o run options: output directory (NULL: none written), threads, quiet
 * @param t receives the trial
 * @return PM_OK whether the slope stood or not (t->failed says which); PM_EINPUT, PM_EIO, PM_ENOMEM
 *         for errors that are not the slope failing
 */
int pm_srf_trial_run(const pm_case *c, double factor, double elastic_displacement, const pm_run_opts *o,
                     pm_srf_trial *t);

/**
 * @brief Search for the factor of safety of @p c between analysis.strength_reduction.min and max.
 *
 * Runs min (must hold) and max (must fail), then bisects until the bracket is narrower than the
 * tolerance. With an output directory DIR each trial writes a whole run into DIR/srf_<F> (F to four
 * decimals; the elastic reference into DIR/srf_elastic), and DIR/strength_reduction.csv gets a row
 * per trial: `factor,converged,fails,max_displacement,displacement_ratio,time_reached,newton_iterations,
 * step_cuts,seconds` (converged and fails are yes/no; displacement_ratio is empty without an elastic
 * reference).
 * One line per trial goes to stderr unless @p o->quiet.
 * @param c case with analysis.strength_reduction set
 * @param o run options (out_dir: NULL means the case's directory; write_output 0: no files)
 * @param r receives the trials and, on success, the factor of safety
 * @return PM_OK; PM_ESIM when min already fails or max still holds (the message says which and
 *         r->n_trials holds what ran); PM_EINPUT, PM_EIO, PM_ENOMEM for other errors
 */
int pm_strength_reduction(const pm_case *c, const pm_run_opts *o, pm_srf_result *r);

/**
 * @brief pm_strength_reduction() with default options but these (for bindings from other languages).
 * @param c case with analysis.strength_reduction set
 * @param out_dir where the trials go (NULL: the case's output.directory; "" for no files)
 * @param threads OpenMP threads (0: the default)
 * @param quiet 1: no line per trial
 * @param fos receives the factor of safety
 * @param lo receives the largest factor that held
 * @param hi receives the smallest factor that failed
 * @return as pm_strength_reduction()
 */
int pm_strength_reduction_to(const pm_case *c, const char *out_dir, int threads, int quiet, double *fos, double *lo,
                             double *hi);

#ifdef __cplusplus
}
#endif
#endif
