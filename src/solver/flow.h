/*
 * Material that enters and leaves a run (explicit MPM): sources release a body's worth of particles
 * at given times (inject.c), sinks remove particles that cross an outlet, lie in a region or leave the
 * grid (remove.c), and two CSV logs record both (flow_log.c).
 *
 * Particles are added and removed only between steps, at the end of a step (after the particles
 * moved and the time advanced): first the sinks, then the sources, so that a frame written at time t
 * shows neither a particle removed at t nor misses one released at t. The particle arrays are
 * allocated once with room for every release the sources can make before the end time; a release
 * copies a portion seeded once at set-up, so no step allocates. Removal compacts the arrays in order.
 * Every particle carries an id (pm_particles::id) that no other particle of the run ever takes.
 */
#ifndef PMECH_SOLVER_FLOW_H
#define PMECH_SOLVER_FLOW_H

#include <stdint.h>
#include <stdio.h>

#include "solver/sim_internal.h"

/** What happened at a source during the last step (or at set-up). */
typedef enum { PM_RELEASE_NONE = 0, PM_RELEASE_DONE = 1, PM_RELEASE_SKIPPED = 2 } pm_release_event;

/** One source during a run. */
typedef struct pm_source_run {
    pm_particles portion;      /**< one release, seeded once (ids unset) */
    size_t next;               /**< the next release to make */
    size_t n_releases;         /**< releases up to the end time */
    double lo[PM_DIM], hi[PM_DIM]; /**< only_when_free: no particle centre may lie in this box */
    double wave;               /**< c + |v| of the released material, for the stable step */
    double portion_mass;       /**< mass of one release */
    pm_release_event event;    /**< the last step's */
    double event_time;         /**< when (the time the step reached) */
    size_t released;           /**< particles released so far */
    double released_mass;      /**< their mass */
} pm_source_run;

/** One sink during a run. */
typedef struct pm_sink_run {
    int axis;                  /**< outlet: 0 the line x = value, 1 y = value */
    double value;
    double range[2];           /**< outlet: from..to along the other axis */
    double normal[PM_DIM];     /**< outlet: removing direction (zero: either) */
    size_t step_particles;     /**< removed in the last step */
    double step_mass;
    size_t removed;            /**< removed so far */
    double removed_mass;
} pm_sink_run;

/** Sources and sinks of a simulation. */
typedef struct pm_flow {
    size_t n_sources;
    pm_source_run *src;
    size_t n_sinks;
    pm_sink_run *snk;
    int has_outlet;            /**< x_prev is kept */
    int has_outside;           /**< a sink removes particles that leave the grid */
    double *x_prev;            /**< positions at the start of the step, PM_DIM per particle slot */
    uint8_t *drop;             /**< removal flags, one per particle slot */
    int32_t next_id;           /**< id of the next particle released */
    int changed;               /**< particles were appended since the last sort */
    size_t max_n;              /**< most particles held at once */
} pm_flow;

/**
 * @brief Set up the sources and sinks of case @p c on grid @p g: seed one portion per source, check
 *        that no two sources overlap and that each yields particles, resolve outlets on grid sides.
 * @param n_state history variables per particle (as the simulation's particles)
 * @param out receives the state (NULL when the case has neither sources nor sinks)
 * @param room receives the particles every release up to the end time adds
 * @return PM_OK; PM_EINPUT naming the key path of a source or sink that cannot work
 */
int pm_flow_create(const pm_case *c, const pm_grid *g, size_t n_state, pm_flow **out, size_t *room);

/**
 * @brief Once the particles of the bodies are seeded and located (and the work arrays sized to
 *        s->p.cap): make the releases due at t = 0.
 */
int pm_flow_start(pm_sim *s);

/** @brief Free the state (NULL is fine). */
void pm_flow_destroy(pm_flow *f);

/** @brief At the start of an explicit step: keep the positions the outlets test crossings from. */
void pm_flow_before_step(pm_sim *s);

/**
 * @brief At the end of an explicit step (time advanced): remove what the sinks take, then make the
 *        releases that fell due.
 * @return PM_OK; PM_ESIM when a source has two releases due within one step (its period is shorter
 *         than the step)
 */
int pm_flow_after_step(pm_sim *s);

/** @brief Whether particles were appended since the last call (the caller then sorts: appended
 *         particles are out of cell order; removal keeps the order). */
int pm_flow_take_changed(pm_sim *s);

/**
 * @brief The largest c + |v| of material still to be released, 0 when no release is left: the stable
 *        step must hold for a portion before it arrives.
 */
double pm_flow_wave(const pm_sim *s);

/** @brief Time of the next release of any source (INFINITY when none is left). */
double pm_flow_next_release(const pm_sim *s);

/**
 * @brief The stable step with sources and sinks, given the largest c + |v| of the particles:
 *        cfl h / max(that, pm_flow_wave()); with no particle at all, the time to the next release
 *        (or to the end): an empty grid has nothing to keep stable.
 */
double pm_flow_stable_dt(const pm_sim *s, double particle_wave);

/**
 * @brief Remove the particles the sinks take at the time reached (each goes to the first sink in the
 *        case's order that takes it), keeping the order of the others, and add them to the sinks'
 *        counts. Part of pm_flow_after_step().
 */
void pm_flow_remove_marked(pm_sim *s);

/** Totals for run.json. */
typedef struct pm_flow_totals {
    size_t released, removed, max_n;
    double released_mass, removed_mass;
} pm_flow_totals;

/** @brief Particles and mass released and removed so far, and the most held at once. */
void pm_flow_totals_of(const pm_sim *s, pm_flow_totals *t);

/** The release and removal logs of a run (CSV, whole lines only). */
typedef struct pm_flow_log {
    FILE *releases;            /**< releases.csv: time,source,particles,mass,cumulative_mass */
    FILE *removals;            /**< removals.csv: time,sink,particles,mass,cumulative_mass */
} pm_flow_log;

/**
 * @brief Open releases.csv (when the case has sources) and removals.csv (when it has sinks) in @p dir,
 *        and write the rows of the releases made at set-up.
 */
int pm_flow_log_open(pm_flow_log *log, const pm_sim *s, const char *dir);

/** @brief Append the rows of the last step's releases and removals. */
int pm_flow_log_step(pm_flow_log *log, const pm_sim *s);

/** @brief Close both files (safe on a zeroed log). */
int pm_flow_log_close(pm_flow_log *log);

#endif
