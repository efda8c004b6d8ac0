/**
 * @file sim_internal.h
 * @brief Inside of a simulation (the solver's, not the library user's): the state behind the opaque
 *        pm_sim, the nodal arrays, the scatter strategies and the steps the run loop calls.
 */
#ifndef PMECH_SIM_INTERNAL_H
#define PMECH_SIM_INTERNAL_H

#include <stdint.h>

#include "pmech/sim.h"
#include "shape/approx_internal.h"

/** Nodal arrays of the background grid; all sized once (no allocation inside steps). */
typedef struct pm_nodal {
    double *mass;        /**< lumped mass */
    double *mom;         /**< momentum, 2 per node */
    double *vel;         /**< velocity at the start of the step (after constraints), 2 per node */
    double *vel_new;     /**< velocity at the end of the step, 2 per node */
    double *force;       /**< total force (internal + external), 2 per node */
    double *acc;         /**< acceleration, 2 per node */
    double *vel_strain;  /**< USL: the end-of-step velocity the strain rate takes, 2 per node */
    uint8_t *fixed;      /**< bit 0: x prescribed, bit 1: y prescribed */
    size_t n_all;        /**< entries of each array: grid nodes x body fields (contact/multibody.h) */
    double *vfix;        /**< prescribed velocity, 2 per node */
    int n_threads;       /**< scatter buffers for OpenMP threads beyond the first */
    double *scratch;     /**< (n_threads - 1) * 5 * n_nodes doubles: mass, mom/force */
    size_t n_timed;      /**< velocity conditions that end at a given time */
    struct pm_timed_bc {
        int set;         /**< grid node set */
        unsigned dirs;   /**< components */
        double until;    /**< time after which the nodes are held (velocity zero), or released */
        int release;     /**< 1: a fixed condition whose components become free at `until` */
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
struct pm_sim {
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
    struct pm_fbar *fbar; /**< F-bar volumetric averaging (analysis.fbar; NULL when off) */
    double *xpic;        /**< XPIC's two nodal work vectors, 2 x PM_DIM x nd.n_all (NULL with other transfers) */
    struct pm_mf *mf;    /**< GMM/RKPM: node cloud, moving nodes, boundary rows (NULL for MPM); grid then
                              holds the cloud's nodes without cells */
    pm_scatter scatter;  /**< scatter strategy of the explicit steps (set at creation only) */
    size_t *blocks;      /**< colour scatter: first particle of each of the 2 x threads row blocks, then n */
    int n_blocks;        /**< colour scatter: blocks in use (0: not cut yet) */
    int blocks_ok;       /**< colour scatter: no two same-colour blocks share a node at this step */
    struct pm_flow *flow; /**< sources and sinks (solver/flow.h; NULL when the case has none) */
    struct pm_loads *loads; /**< forces on particle sets (solver/loads.h; NULL when the case has none) */
    struct pm_multibody *mb; /**< body fields of contact_pairs (contact/multibody.h; NULL: one field) */
};

/**
 * @brief Set every particle's volume to mass / density, the density interpolated from nodal densities
 *        of the particle positions (seed 004 eqs. 12-13); the case's `density_update: positions`.
 *        A material with a density_state (granular) also takes that density, or with
 *        `apart_measure: cell` the densest node of the particle's cell, as its volume change where it
 *        shows the particle apart. Needs located particles (connect).
 */
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

#endif
