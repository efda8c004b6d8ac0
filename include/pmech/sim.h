/**
 * @file sim.h
 * @brief A simulation: the case, its grid, approximation, particles and nodal arrays, and the
 *        time integrators that advance it. The integrators see shape functions only through
 *        pm_approx and constitutive models only through pm_material.
 */
#ifndef PMECH_SIM_H
#define PMECH_SIM_H

#include <stdint.h>

#include "pmech/approx.h"
#include "pmech/case.h"
#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Nodal arrays of the background grid; all sized once (no allocation inside steps). */
typedef struct pm_nodal {
    double *mass;        /**< lumped mass */
    double *mom;         /**< momentum, 2 per node */
    double *vel;         /**< velocity at the start of the step (after constraints), 2 per node */
    double *vel_new;     /**< velocity at the end of the step, 2 per node */
    double *force;       /**< total force (internal + external), 2 per node */
    double *acc;         /**< acceleration, 2 per node */
    uint8_t *fixed;      /**< bit 0: x prescribed, bit 1: y prescribed */
    double *vfix;        /**< prescribed velocity, 2 per node */
    int n_threads;       /**< scatter buffers for OpenMP threads beyond the first */
    double *scratch;     /**< (n_threads - 1) * 5 * n_nodes doubles: mass, mom/force */
    size_t n_timed;      /**< velocity conditions that end at a given time */
    struct pm_timed_bc {
        int set;         /**< grid node set */
        unsigned dirs;   /**< components */
        double until;    /**< time after which the nodes are held (velocity zero) */
        int done;        /**< 1 once switched */
    } *timed;
} pm_nodal;

/**
 * How the parallel particle-to-grid scatters of the explicit steps keep two threads from writing one
 * node. Chosen when the simulation is created, from the environment variable PMECH_SCATTER
 * ("colour" or "buffers"; unset or empty: colour; anything else: pm_sim_create() fails with PM_EINPUT).
 */
typedef enum pm_scatter {
    /** Particles sorted by cell are cut into 2 x threads blocks of whole cell rows; the even blocks
     *  scatter at once straight into the nodal arrays, then the odd ones. Linear quad4 on a
     *  structured grid only; other approximations use buffers. */
    PM_SCATTER_COLOUR = 0,
    /** Every thread scatters into its own copy of the nodal arrays; the copies are summed after. */
    PM_SCATTER_BUFFERS = 1
} pm_scatter;

/** Statistics a step reports. */
typedef struct pm_step_info {
    double dt;           /**< step taken */
    double dt_next;      /**< stable step for the next step (automatic mode) */
} pm_step_info;

/** The whole simulation state. */
typedef struct pm_sim {
    const pm_case *c;    /**< the case (not owned) */
    pm_grid grid;        /**< background grid */
    pm_approx *approx;   /**< shape functions */
    pm_particles p;      /**< material points */
    pm_nodal nd;         /**< nodal arrays */
    double t;            /**< simulated time */
    long step;           /**< steps taken */
    double dt_next;      /**< step to take next */
    double max_wave;     /**< largest c + |v| over particles at the last stress update */
    int sort_interval;   /**< steps between sorts of the particles by cell (0: never) */
    uint32_t *perm;      /**< sort workspace: permutation, n */
    uint32_t *bucket;    /**< sort workspace: particles per cell, n_cells + 1 */
    double *scratch;     /**< sort workspace: n doubles */
    int32_t *iscratch;   /**< sort workspace: n ints */
    double *rho_node;    /**< density from positions: nodal densities (NULL when not used) */
    double *rho_p;       /**< density from positions: particle densities */
    double *rho_work;    /**< density from positions: n_nodes + n_cells doubles */
    double energy_gravity_work; /**< reserved for ramped-gravity bookkeeping */
    struct pm_implicit_ws *implicit; /**< implicit/quasi-static workspace (NULL until the first implicit step) */
    struct pm_contact *contact; /**< contact surfaces (friction conditions) and the nodes touching them */
    struct pm_mf *mf;    /**< GMM/RKPM: node cloud, moving nodes, boundary rows (NULL for MPM); grid then
                              holds the cloud's nodes without cells */
    pm_scatter scatter;  /**< scatter strategy of the explicit steps (set at creation only) */
    size_t *blocks;      /**< colour scatter: first particle of each of the 2 x threads row blocks, then n */
    int n_blocks;        /**< colour scatter: blocks in use (0: not cut yet) */
    int blocks_ok;       /**< colour scatter: no two same-colour blocks share a node at this step */
} pm_sim;

/**
 * @brief Build the grid, approximation, particles (seeded from the bodies) and nodal arrays.
 * @param c a loaded case (must outlive the simulation)
 * @param s receives the new simulation; free with pm_sim_destroy()
 * @param n_threads OpenMP threads the steps will use (>= 1)
 * @return PM_OK; PM_EINPUT for a case that cannot be set up (a body with no particle, ...)
 */
int pm_sim_create(const pm_case *c, pm_sim **s, int n_threads);

/** @brief Free a simulation (NULL is fine). */
void pm_sim_destroy(pm_sim *s);

/**
 * @brief Set every particle's volume to mass / density, the density interpolated from nodal densities
 *        of the particle positions (seed 004 eqs. 12-13); the case's `density_update: positions`.
 *        Needs located particles (connect).
 */
/**
 * @brief The grid that frames output and pictures: the case's grid (GMM/RKPM keep it after their
 *        nodes replaced it in pm_sim::grid).
 * @param s the simulation
 * @return the grid
 */
const pm_grid *pm_sim_frame_grid(const pm_sim *s);

int pm_sim_volumes_from_positions(pm_sim *s);

/**
 * @brief Switch velocity conditions whose `until` time has come to holding their nodes still, and
 *        find the nodes touching the contact surfaces at this time. Called at the start of every step.
 */
void pm_sim_update_constraints(pm_sim *s);

/**
 * @brief Advance one explicit step with the case's scheme (usf, usl, musl, newmark_pc).
 * @param s simulation
 * @param dt step size (> 0)
 * @return PM_OK, or PM_ESIM naming the step and the particle that failed
 */
int pm_explicit_step(pm_sim *s, double dt);

/**
 * @brief Update every particle's F, stress, volume and plastic strain from nodal velocities
 *        @p nodal_v (2 per node) over @p dt, as a step's stress pass does (with the case's
 *        formulation). Used by the steps and by patch tests that prescribe nodal velocities.
 * @return PM_OK, or PM_ESIM naming the particle that failed
 */
int pm_sim_update_stresses(pm_sim *s, const double *nodal_v, double dt);

/**
 * @brief Reorder the particles by background cell (counting sort on p->cell, stable), so that
 *        particles that share nodes are neighbours in memory. Needs current cells (connect).
 */
void pm_sim_sort_particles(pm_sim *s);

/**
 * @brief The stable step cfl * h_min / (c + v_max) for the current state.
 */
double pm_sim_stable_dt(const pm_sim *s);

/** @brief Gravity vector at time @p t (with the case's ramp). */
void pm_sim_gravity(const pm_sim *s, double t, double g[2]);

/**
 * @brief Kinetic, stored (strain) and gravitational potential energy of the particles.
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

#ifdef __cplusplus
}
#endif
#endif
