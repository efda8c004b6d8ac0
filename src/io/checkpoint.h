/**
 * @file checkpoint.h (internal to src/, not installed)
 * @brief Checkpoint and restart of a run: DIR/checkpoint.h5 (HDF5, layout in docs/checkpoint.md) holds
 *        everything the next step reads that is not set up again from the case, so that a run continued
 *        from it (`pmech run CASE --restart DIR`) writes the same bytes into every output file as the
 *        run that was never stopped (same thread count).
 *
 * What is not stored is rebuilt by pm_sim_create() from the case exactly as the first run built it:
 * the grid, the approximation, the conditions, the seeded portions of the sources, the load sets. What
 * is stored: every particle array, time, step and the time-step controller, the nodal arrays (the
 * prescribed components switch in time), the colour blocks of the parallel scatter, the flow counters,
 * the contact impulses not yet logged, the output schedule, the probes, the picture ranges, the state
 * of forces.csv, and the byte length of every log file, which a restart cuts back to before appending.
 *
 * Covered: methods mpm (with lme, each particle's kept stencil and Lagrange multipliers: checkpoint_lme.h),
 * gmm (mls, lme) and rkpm, whose node cloud is stored with what rebuilds its cell list exactly
 * (checkpoint_meshfree.h); analysis explicit, implicit and quasi_static, with or without contact_pairs,
 * but not a strength reduction. pm_checkpoint_covers() says why.
 */
#ifndef PMECH_IO_CHECKPOINT_H
#define PMECH_IO_CHECKPOINT_H

#include <stdint.h>
#include <stdio.h>

#include "io/output.h"
#include "solver/forces_log.h"
#include "solver/sim_internal.h"

/** The file's name in the output directory. */
#define PM_CHECKPOINT_NAME "checkpoint.h5"

/** The layout's version (attribute `format_version`): 2 added /meshfree and /lme, 3 /particles/C (APIC's
 *  affine matrix), 4 numbers a Gmsh lattice's nodes as the structured grid's and keeps its straight
 *  friction groups as node sets (the contact impulses of a version 3 file index the mesh's own numbering
 *  and edge walls); a restart reads only its own. */
#define PM_CHECKPOINT_FORMAT 4

/** What the time loop of pm_run() carries from step to step besides the simulation. */
typedef struct pm_run_loop {
    double next_frame;       /**< time of the next frame */
    double next_energy;      /**< time of the next energy.csv row */
    double next_checkpoint;  /**< time of the next checkpoint (INFINITY: at the end only) */
    double dt_min, dt_max;   /**< smallest and largest step so far */
    double last_frame_t;     /**< time of the last frame written */
    double loop_seconds;     /**< wall time spent in steps so far (run.json) */
    double particle_steps;   /**< particles summed over the steps (run.json) */
    long newton_iterations;  /**< implicit: totals so far (run.json) */
    long step_cuts;
    double assemble_seconds, solve_seconds;
} pm_run_loop;

/** Most log files a run writes besides probes.csv and energy.csv. */
#define PM_CK_LOGS_MAX 8

/** The log files (stdio streams) of a run, by their names in the output directory. */
typedef struct pm_ck_logs {
    size_t n;
    const char *name[PM_CK_LOGS_MAX];
    FILE **file[PM_CK_LOGS_MAX];
} pm_ck_logs;

/** @brief Add the log @p name whose stream is *@p f (ignored when *f is NULL or stderr). */
void pm_ck_logs_add(pm_ck_logs *l, const char *name, FILE **f);

/** Everything a checkpoint is written from. */
typedef struct pm_ck_run {
    const pm_sim *s;
    pm_output *out;                 /**< NULL: the run writes no files (no checkpoint either) */
    const pm_forces_log *forces;
    const double *walls_t_last;     /**< the wall profiles' last frame time (NULL: no wall profiles) */
    const pm_ck_logs *logs;
    const pm_run_loop *loop;
    int threads;                    /**< threads of the run (a restart with others is not bitwise) */
    uint64_t case_hash;             /**< pm_checkpoint_case_hash() of the case file when the run began */
    int enabled;                    /**< 0: no checkpoint (the case has no readable file) */
} pm_ck_run;

/** @brief FNV-1a hash (64 bits) of the bytes of file @p path. @return PM_OK, PM_EIO */
int pm_checkpoint_case_hash(const char *path, uint64_t *hash);

/**
 * @brief Whether runs of @p s can be checkpointed and continued.
 * @return PM_OK, or PM_EINPUT naming what is not covered and why
 */
int pm_checkpoint_covers(const pm_sim *s);

/**
 * @brief Whether @p s runs the grid kind lme, whose per-particle stencils a checkpoint stores (/lme).
 * @return 1 or 0
 */
int pm_checkpoint_grid_lme(const pm_sim *s);

/**
 * @brief Write @p dir/checkpoint.h5 atomically (checkpoint.h5.tmp, synced, renamed); the logs are
 *        flushed first so the lengths it records are on disk.
 * @return PM_OK, PM_EIO naming the file and the dataset that could not be written
 */
int pm_checkpoint_write(const char *dir, const pm_ck_run *r);

typedef struct pm_checkpoint pm_checkpoint;

/**
 * @brief Open @p dir/checkpoint.h5 for the simulation @p s just created from its case: refuse it
 *        (PM_EINPUT) when it is missing, unreadable, of another pmech version, another case file
 *        (FNV-1a hash of its bytes), another PM_DIM, or when the case is not covered.
 */
int pm_checkpoint_open(pm_checkpoint **ck, const char *dir, const pm_sim *s);

/**
 * @brief Put the stored state into @p s and @p loop (particles, time, step, controller, nodal arrays,
 *        scatter blocks, flow, contact impulses). @p threads: the run's; another count than the stored
 *        one gives a warning in @p warning ("" when none).
 */
int pm_checkpoint_restore_state(pm_checkpoint *ck, pm_sim *s, pm_run_loop *loop, int threads, char *warning,
                                size_t warning_len);

/**
 * @brief Move the stored logs aside (NAME.resume) before the outputs are opened again, which
 *        starts every log afresh; pm_checkpoint_restore_outputs() puts them back.
 */
int pm_checkpoint_logs_aside(pm_checkpoint *ck);

/**
 * @brief After the outputs were opened (pm_output_open_resume and the logs' own opens): the frame
 *        list, the probes, the picture ranges, forces.csv's schedule, the surfaces' impulses since the
 *        last forces.csv row and the last wall profile (into @p walls_t_last, its time, when not NULL),
 *        and the body fields' impulses (contact_forces.csv) as stored; every log back in place, cut to
 *        its stored length, and its stream appending to it.
 */
int pm_checkpoint_restore_outputs(pm_checkpoint *ck, pm_sim *s, pm_output *out, pm_forces_log *forces,
                                  double *walls_t_last, pm_ck_logs *logs);

/** @brief Close (NULL is fine); logs still aside are put back. */
void pm_checkpoint_close(pm_checkpoint *ck);

#endif
