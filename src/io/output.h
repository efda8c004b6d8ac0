/**
 * @file output.h (internal to src/, not installed)
 * @brief Everything a run writes: ParaView VTU/PVD frames, grid.vtu, probes.csv, energy.csv and
 *        run.json. Every file is written under a temporary name and renamed, so what is on disk
 *        is always complete, even when a run stops on an error.
 */
#ifndef PMECH_OUTPUT_H
#define PMECH_OUTPUT_H

#include "pmech/case.h"
#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pm_output pm_output;

/** What run.json records about a run. */
typedef struct pm_run_summary {
    const char *version;            /**< pmech version */
    const char *case_file;          /**< the case file as given */
    const char *title;              /**< the case's title (pictures redrawn later show it) */
    const char *formulation;        /**< plane_strain, plane_stress or axisymmetric */
    const char *grid;               /**< structured (a rectangle, or a Gmsh lattice run as one) or unstructured */
    long steps;                     /**< time steps taken */
    double dt_min, dt_max;          /**< smallest and largest step */
    double end_time;                /**< simulated time reached */
    double wall_seconds;            /**< whole run */
    double loop_seconds;            /**< time loop only (no setup, no file output) */
    double particle_steps_per_second; /**< particles summed over the steps / loop_seconds */
    size_t particles;               /**< particle count at the end */
    int exit_status;                /**< 0, 1 or 2 as the program exits */
    const char *message;            /**< error message ("" on success) */
    int threads;                    /**< OpenMP threads used */
    int implicit;                   /**< 1: implicit or quasi-static (the fields below are written) */
    long newton_iterations;         /**< implicit: Newton iterations of all steps */
    long step_cuts;                 /**< implicit: halvings of steps that did not converge */
    double assemble_seconds;        /**< implicit: particle updates and assembly */
    double solve_seconds;           /**< implicit: sparse factorisations and solves */
    const char (*warnings)[PM_WARNING_LEN]; /**< warnings of the run (pm_case_warnings and the run's own) */
    size_t n_warnings;              /**< their count */
    int flow;                       /**< 1: the case has sources or sinks (the fields below are written) */
    size_t particles_max;           /**< most particles held at once */
    size_t particles_released;      /**< particles the sources released (at t = 0 too) */
    size_t particles_removed;       /**< particles the sinks removed */
    double mass_released;           /**< their mass */
    double mass_removed;
    const char *interrupted;        /**< "SIGINT" or "SIGTERM" when a signal stopped the run, else NULL */
} pm_run_summary;

/**
 * @brief Create the output directory (and parents), write grid.vtu, open probes.csv and
 *        energy.csv with their headers, and resolve probes (nearest particle at t = 0, ties to the
 *        lowest index; or a body's mass-weighted mean).
 * @return PM_OK, PM_EIO naming the path that could not be written
 */
int pm_output_open(pm_output **o, const char *dir, const pm_case *c, const pm_grid *g,
                   const pm_particles *p);

/**
 * @brief As pm_output_open(), for a run that continues from a checkpoint in @p dir: the frames and logs
 *        already there are kept (the checkpoint then puts back the frame list, the probes and the CSV
 *        files as they were when it was written).
 */
int pm_output_open_resume(pm_output **o, const char *dir, const pm_case *c, const pm_grid *g,
                          const pm_particles *p);

/** @brief Write particles_NNNNNN.vtu for time @p t and rewrite particles.pvd listing all frames. */
int pm_output_frame(pm_output *o, double t, const pm_particles *p);

struct pm_vtu_grid_fields;

/**
 * @brief Write grid_NNNNNN.vtu beside the particle frame just written (same number and time): the nodes the
 *        simulation interpolates from with their nodal fields, and rewrite grid.pvd listing all of them.
 */
int pm_output_grid_frame(pm_output *o, const pm_grid *g, const struct pm_vtu_grid_fields *gf);

/** @brief Append one row of probe values at time @p t to probes.csv (no-op without probes). */
int pm_output_probes(pm_output *o, double t, const pm_particles *p);

/** @brief Append `time,kinetic,strain,gravity,total` to energy.csv (nothing when the last row has this time). */
int pm_output_energy(pm_output *o, double t, double kinetic, double strain, double gravity);

/** @brief Particle index followed by probe @p k (-1 for a body probe). */
long pm_output_probe_particle(const pm_output *o, size_t k);

/**
 * @brief Flush and close the CSV files, write run.json, free @p o. Safe with NULL.
 * @return PM_OK or PM_EIO
 */
int pm_output_close(pm_output *o, const pm_run_summary *s);

/**
 * @brief Write @p len bytes to @p path atomically (temporary file in the same directory, then rename).
 */
int pm_write_file_atomic(const char *path, const void *data, size_t len);

/**
 * @brief Create a directory and its parents (like mkdir -p).
 */
int pm_mkdir_p(const char *path);

#ifdef __cplusplus
}
#endif
#endif
