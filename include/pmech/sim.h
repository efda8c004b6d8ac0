/**
 * @file sim.h
 * @brief A simulation of a loaded case: create it, advance it step by step or run it to the end,
 *        and read its particles, grid, time and energies. The state itself is opaque.
 */
#ifndef PMECH_SIM_H
#define PMECH_SIM_H

#include <signal.h>
#include <stddef.h>

#include "pmech/case.h"
#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The whole simulation state (opaque: read it through the accessors below). */
typedef struct pm_sim pm_sim;

/**
 * @brief Build the grid, approximation, particles (seeded from the bodies) and nodal arrays.
 * @param c a loaded case (must outlive the simulation)
 * @param s receives the new simulation; free with pm_sim_destroy()
 * @param n_threads OpenMP threads the steps will use (>= 1)
 * @return PM_OK; PM_EINPUT for a case that cannot be set up (a body with no particle, ...)
 */
int pm_sim_create(const pm_case *c, pm_sim **s, int n_threads);

/**
 * @brief Free a simulation.
 * @param s the simulation (NULL is fine)
 */
void pm_sim_destroy(pm_sim *s);

/**
 * @brief The grid that frames output and pictures: the case's grid (GMM/RKPM keep it after their
 *        nodes replaced it as the simulation's grid, pm_sim_grid()).
 * @param s the simulation
 * @return the grid
 */
const pm_grid *pm_sim_frame_grid(const pm_sim *s);

/**
 * @brief The material points in their current state (positions, velocities, stresses, ...).
 * @param s the simulation
 * @return the particles, valid until the next step or pm_sim_destroy()
 */
const pm_particles *pm_sim_particles(const pm_sim *s);

/**
 * @brief The nodes the simulation interpolates from: the background grid for MPM, the node cloud
 *        (nodes without cells) for GMM and RKPM.
 * @param s the simulation
 * @return the grid, valid until pm_sim_destroy()
 */
const pm_grid *pm_sim_grid(const pm_sim *s);

/**
 * @brief Simulated time reached (pseudo-time for quasi-static analyses).
 * @param s the simulation
 * @return the time in seconds
 */
double pm_sim_time(const pm_sim *s);

/**
 * @brief Steps taken so far.
 * @param s the simulation
 * @return the number of completed steps
 */
long pm_sim_steps(const pm_sim *s);

/**
 * @brief Advance one step of the case's analysis: an explicit step for `explicit`, an implicit
 *        (Newton) step, with its step cuts, for `implicit` and `quasi_static`. Writes no files.
 * @param s the simulation
 * @param dt step size (> 0); pm_sim_stable_dt() gives the explicit stable step
 * @return PM_OK, or PM_ESIM naming the step (and the particle when one failed)
 */
int pm_sim_advance(pm_sim *s, double dt);

/**
 * @brief The stable step cfl * h_min / (c + v_max) for the current state.
 * @param s the simulation
 * @return the step in seconds
 */
double pm_sim_stable_dt(const pm_sim *s);

/**
 * @brief Gravity vector at time @p t (with the case's ramp).
 * @param s the simulation
 * @param t time
 * @param g receives (gx, gy)
 */
void pm_sim_gravity(const pm_sim *s, double t, double g[2]);

/**
 * @brief Kinetic, stored (strain) and gravitational potential energy of the particles.
 * @param s the simulation
 * @param kinetic receives the kinetic energy
 * @param strain receives the stored (strain) energy
 * @param gravity receives the gravitational potential energy
 */
void pm_sim_energy(const pm_sim *s, double *kinetic, double *strain, double *gravity);

/** What a run reached, also when it stopped on an error (for callers that judge runs, such as the
 *  strength reduction). */
typedef struct pm_run_stats {
    double t;                /**< time reached: the end time, or the last completed step's */
    long steps;              /**< steps completed */
    long newton_iterations;  /**< implicit: Newton iterations of all steps */
    long step_cuts;          /**< implicit: halvings of steps that did not converge */
    double max_displacement; /**< largest particle displacement |x - x0| at time t */
    double wall_seconds;     /**< the whole run */
} pm_run_stats;

/** Options of a whole run. */
typedef struct pm_run_opts {
    const char *out_dir;   /**< output directory (NULL: the case's) */
    int quiet;             /**< no progress line */
    int threads;           /**< OpenMP threads (0: OMP_NUM_THREADS or all cores) */
    int write_output;      /**< 0: write no files (tests) */
    int verbose;           /**< implicit runs: Newton iterations also on stderr when no files are written */
    pm_run_stats *stats;   /**< if not NULL, receives what the run reached (also when it fails) */
    /** if not NULL: a signal number (SIGINT, SIGTERM) stored here, e.g. by a signal handler, stops the run
     *  after the step in progress with PM_EINTR; outputs are closed and run.json says so */
    const volatile sig_atomic_t *interrupt;
    /** if not NULL: continue the run whose checkpoint.h5 is in this directory (outputs go there too; the
     *  frames and logs after the checkpoint's time are replaced); see docs/checkpoint.md */
    const char *restart;
} pm_run_opts;

/**
 * @brief Run a case to its end time, writing all outputs. An implicit or quasi-static run that stops
 *        because Newton does not converge writes its last converged state as a final frame, so the
 *        mechanism that stopped it can be seen.
 * @param c loaded case
 * @param o options
 * @param out_sim if not NULL, receives the final simulation (caller destroys), for tests
 * @return PM_OK, PM_EINPUT (setup), PM_ESIM (diverged: outputs so far stay valid), PM_EIO
 */
int pm_run(const pm_case *c, const pm_run_opts *o, pm_sim **out_sim);

/**
 * @brief pm_run() with every option at its default but these, writing all outputs; for bindings from
 *        other languages, which cannot follow new fields of pm_run_opts.
 * @param c loaded case
 * @param out_dir output directory (NULL: the case's output.directory)
 * @param threads OpenMP threads (0: the default)
 * @param quiet 1: no progress line or warnings on stderr
 * @param stats if not NULL, receives what the run reached
 * @return as pm_run()
 */
int pm_run_to(const pm_case *c, const char *out_dir, int threads, int quiet, pm_run_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
