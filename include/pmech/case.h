/**
 * @file case.h
 * @brief A case file (docs/input.md) parsed and validated into plain C structs, changed key by key
 *        with the same checks (pm_case_set), and the material-point driver file of `pmech material`.
 *
 * Loading never crashes on bad input: it returns PM_EINPUT with one message naming
 * file:line:column (syntax) or the key path (e.g. `materials[0].poisson_ratio`), the value found
 * and what is allowed, with a "did you mean" for unknown keys.
 */
#ifndef PMECH_CASE_H
#define PMECH_CASE_H

#include <stddef.h>
#include "pmech/material.h"
#include "pmech/timefn.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PM_NAME_MAX 64
#define PM_PATH_MAX 1024

typedef enum { PM_PLANE_STRAIN = 0, PM_PLANE_STRESS = 1, PM_AXISYMMETRIC = 2 } pm_formulation;
typedef enum { PM_METHOD_MPM = 0, PM_METHOD_GMM = 1, PM_METHOD_RKPM = 2 } pm_method;
typedef enum { PM_ANALYSIS_EXPLICIT = 0, PM_ANALYSIS_IMPLICIT = 1, PM_ANALYSIS_QUASI_STATIC = 2 } pm_analysis_type;
typedef enum { PM_SCHEME_MUSL = 0, PM_SCHEME_USL = 1, PM_SCHEME_USF = 2, PM_SCHEME_NEWMARK_PC = 3 } pm_scheme;
typedef enum { PM_SHAPE_RECTANGLE = 0, PM_SHAPE_POLYGON = 1, PM_SHAPE_CIRCLE = 2, PM_SHAPE_GMSH_GROUP = 3 } pm_shape_type;
typedef enum { PM_BC_FIXED = 0, PM_BC_VELOCITY = 1, PM_BC_FRICTION = 2 } pm_bc_type;
typedef enum { PM_STRESS0_NONE = 0, PM_STRESS0_GEOSTATIC = 1, PM_STRESS0_CONSTANT = 2 } pm_stress0_type;
typedef enum {
    PM_Q_POSITION = 0, PM_Q_DISPLACEMENT = 1, PM_Q_VELOCITY = 2, PM_Q_STRESS = 3, PM_Q_PLASTIC_STRAIN = 4
} pm_quantity;
typedef enum { PM_GRID_RECTANGLE = 0, PM_GRID_GMSH = 1 } pm_grid_type;
/** Volumetric averaging of a step's deformation (analysis.fbar). */
typedef enum {
    PM_FBAR_NONE = 0,  /**< every particle keeps its own volume change */
    PM_FBAR_CELL = 1   /**< F-bar: the volume change averaged over each background cell (Coombs et al. 2018) */
} pm_fbar_mode;
/** How particle velocities go to the grid and back in explicit MPM (analysis.transfer). */
typedef enum {
    PM_TRANSFER_FLIP = 0, /**< FLIP with an optional PIC share (analysis.flip) */
    PM_TRANSFER_APIC = 1, /**< affine particle-in-cell: velocity plus a per-particle velocity gradient */
    PM_TRANSFER_XPIC = 2  /**< extended particle-in-cell of order analysis.xpic_order (Hammerquist and Nairn 2017) */
} pm_transfer;
/** When a trial factor of a strength reduction counts as failed (analysis.strength_reduction.criterion). */
typedef enum {
    PM_SRF_CONVERGENCE = 0,  /**< the run cannot apply the full gravity: Newton fails after every step cut */
    PM_SRF_DISPLACEMENT = 1  /**< that, or the largest displacement exceeds a multiple of the elastic one */
} pm_srf_criterion;

/** The region a body fills. */
typedef struct pm_shape {
    pm_shape_type type;
    double min[2], max[2];        /**< rectangle */
    size_t n_points;              /**< polygon: vertex count (>= 3) */
    double *points;               /**< polygon: 2 * n_points coordinates */
    double center[2], radius;     /**< circle */
    char group[PM_NAME_MAX];      /**< gmsh_group: physical group name */
} pm_shape;

/** bodies[] */
typedef struct pm_case_body {
    char name[PM_NAME_MAX];
    int material;                 /**< index into pm_case::materials */
    pm_shape shape;
    int particles_per_cell;       /**< 0 = default for the element (2 quad, 3 tri) */
    double velocity[2];
    pm_stress0_type stress0;
    double k0, surface_y;         /**< geostatic */
    double stress0_value[4];      /**< constant [sxx, syy, szz, sxy] */
    char contact_group[PM_NAME_MAX]; /**< the body field it joins where bodies meet (default: its name) */
} pm_case_body;

/** How two contact groups act on each other where they meet on the grid (contact_pairs[].law). */
typedef enum pm_pair_law {
    PM_PAIR_NO_SLIP = 0,      /**< one velocity for both, as if a single field (the default) */
    PM_PAIR_FRICTIONLESS = 1, /**< the approaching normal velocity is removed, sliding is free */
    PM_PAIR_COULOMB = 2       /**< as frictionless, and the sliding speed is reduced by mu times that change */
} pm_pair_law;

/** contact_pairs[]: the law between two contact groups (docs/input.md). */
typedef struct pm_case_contact_pair {
    char group[2][PM_NAME_MAX];   /**< the two contact groups (a body's contact_group or name) */
    pm_pair_law law;
    double friction;              /**< Coulomb coefficient (coulomb only) */
    int extent_check;             /**< 1: contact only where the particles' domains meet (the default);
                                       0: wherever the fields approach each other within a cell */
} pm_case_contact_pair;

/** sources[]: material released during a run, a body's worth at a time (docs/input.md, `sources[]`). */
typedef struct pm_case_source {
    pm_case_body body;            /**< what one release fills: name, material, shape, particles, velocity, stress */
    size_t n_times;               /**< releases at the listed times (0: periodic) */
    double *times;                /**< ascending release times */
    double start, period, until;  /**< periodic releases at start, start + period, ... while <= until */
    int only_when_free;           /**< 1: a release is skipped while a particle lies in its region */
} pm_case_source;

/** What a sink removes: particles that cross a grid line segment, that lie in a region, or that
 *  leave the grid anywhere. */
typedef enum { PM_SINK_OUTLET = 0, PM_SINK_REGION = 1, PM_SINK_OUTSIDE_GRID = 2 } pm_sink_type;

/** sinks[]: where particles leave the model. */
typedef struct pm_case_sink {
    char name[PM_NAME_MAX];
    pm_sink_type type;
    pm_shape shape;               /**< region */
    char side[PM_NAME_MAX];       /**< outlet on a grid side (x_min, x_max, y_min, y_max); "" for a line */
    int axis;                     /**< outlet line: 0 for x = value, 1 for y = value */
    double value;
    double range[2];              /**< outlet: its part from..to along the other axis */
    double normal[2];             /**< outlet: the crossing direction that removes (zero: either) */
} pm_case_sink;

/** boundary_conditions[] */
typedef struct pm_case_bc {
    pm_bc_type type;
    char boundary[PM_NAME_MAX];   /**< side or physical name; "" when given as a line */
    int line_axis;                /**< -1: named; 0: { "x": value }; 1: { "y": value } */
    double line_value;
    double line_range[2];         /**< line: the part from..to along the other axis (default all) */
    double line_normal[2];        /**< line: outward normal for friction (zero: none given) */
    unsigned dirs;                /**< fixed: bit 0 = x, bit 1 = y; velocity: components given */
    double value[2];              /**< velocity values (for the components in dirs) */
    double coefficient;           /**< friction coefficient (>= 0) */
    double until;                 /**< velocity: prescribed until this time, then held; fixed: released at this time (INFINITY or <= 0: never) */
} pm_case_bc;

/** obstacles[].type */
typedef enum pm_obstacle_type {
    PM_OBSTACLE_POLYLINE = 0,     /**< an open chain of segments; the material on one side of it */
    PM_OBSTACLE_POLYGON = 1,      /**< a closed polygon; the material outside it */
    PM_OBSTACLE_CIRCLE = 2        /**< a disk; the material outside it */
} pm_obstacle_type;

/** obstacles[].law */
typedef enum pm_obstacle_law {
    PM_OBSTACLE_NODAL = 0,        /**< Bardenhagen's nodal Coulomb law (velocity projection) */
    PM_OBSTACLE_PENALTY = 1       /**< penalty-regularised Coulomb law (force from the penetration) */
} pm_obstacle_law;

/** obstacles[]: a rigid body placed independently of the grid, fixed or moving. */
typedef struct pm_case_obstacle {
    char name[PM_NAME_MAX];
    pm_obstacle_type type;
    size_t n_points;              /**< polyline (>= 2), polygon (>= 3): points at t = 0 */
    double *points;               /**< 2 per point */
    double center[2], radius;     /**< circle at t = 0 */
    int material_right;           /**< polyline: the material lies right of its direction (default left) */
    int sharp_corners;            /**< polyline, polygon: 1 when a node nearest a corner takes the normal of
                                       the face it lies squarely off (one normal per face, seed 004's two
                                       coincident tool-tip nodes); 0 (default): the normal points at the
                                       corner, as around a rounded edge */
    pm_timefn velocity[2];        /**< rigid translation velocity per component */
    pm_obstacle_law law;
    double friction;              /**< Coulomb coefficient >= 0; INFINITY for "no_slip" */
    double penalty_factor;        /**< penalty law: multiplies the default stiffness (default 1) */
    int at_particles;             /**< nodal law of an MPM run without contact_pairs: 1 to act at the
                                       particles that touch it (acts_at "particles"), 0 (default) node by node */
} pm_case_obstacle;

/** loads[]: a force on a set of particles, shared by their initial volumes. */
typedef struct pm_case_particle_load {
    char name[PM_NAME_MAX];
    int nearest;                  /**< 1: the particle nearest to point; 0: the particles in [min, max] */
    double point[2];
    double min[2], max[2];
    pm_timefn force[2];           /**< total force per component (N per unit thickness; per radian axisymmetric);
                                       a grid line's: force per unit length of the line */
    int line_axis;                /**< -1: a particle set; 0: the grid line x = line_value; 1: y = line_value */
    double line_value;
    double line_range[2];         /**< the loaded part of the line, along the other axis (from, to) */
} pm_case_particle_load;

/** probes[] */
typedef struct pm_case_probe {
    char name[PM_NAME_MAX];
    pm_quantity quantity;
    int body;                     /**< -1: follows the particle nearest to point */
    double point[2];
} pm_case_probe;

/** analysis.newton */
typedef struct pm_newton_opts {
    double tolerance;             /**< relative residual (default 1e-8) */
    double displacement_tolerance;/**< relative displacement increment (default 1e-8) */
    int max_iterations;           /**< default 25 */
    int line_search;              /**< default 1 */
    int max_step_cuts;            /**< halvings of dt or the load increment before giving up (default 8) */
    double absolute_tolerance;    /**< residual norm that counts as converged whatever its scale; 0 = tolerance
                                       x the case's characteristic force (pm_implicit_characteristic_force) */
} pm_newton_opts;

/** analysis.strength_reduction: search for the factor of safety (pmech/strength_reduction.h). */
typedef struct pm_srf_opts {
    int enabled;                  /**< 1 when the key is given */
    double min, max;              /**< the bracket searched: min must hold, max must fail (defaults 0.5, 3) */
    double tolerance;             /**< stop when the bracket is this narrow (default 0.01) */
    pm_srf_criterion criterion;   /**< default PM_SRF_CONVERGENCE (quasi_static), PM_SRF_DISPLACEMENT (explicit) */
    double displacement_ratio;    /**< PM_SRF_DISPLACEMENT: failed above this many elastic displacements (10) */
} pm_srf_opts;

/** A whole case. */
typedef struct pm_case {
    char file[PM_PATH_MAX];       /**< the case file as given */
    char dir[PM_PATH_MAX];        /**< its directory (for relative paths such as a gmsh file) */
    char stem[PM_PATH_MAX];       /**< file name without directory and extension */
    char title[256];
    int dimension;
    pm_formulation formulation;
    pm_method method;
    char shape_function[PM_NAME_MAX];
    double lme_gamma;             /**< NAN = the approximation's default */
    double support_radius;        /**< NAN = default */
    double max_condition;         /**< meshfree: condition number above which a support grows; NAN = default */
    struct {
        pm_analysis_type type;
        pm_scheme scheme;
        double end_time;
        double dt;                /**< 0 = automatic from cfl */
        double cfl;
        double gravity[2];
        double gravity_ramp_time;
        double damping;
        double pic;               /**< MUSL: PIC share of the particle velocity update, 1 - the key flip (0: FLIP) */
        pm_transfer transfer;     /**< MUSL: FLIP/PIC, APIC or XPIC particle-grid transfer */
        int xpic_order;           /**< XPIC's order m (analysis.xpic_order; 1 is PIC) */
        pm_newton_opts newton;
        int load_steps;
        int density_from_positions;  /**< 1: volumes from the density of particle positions (seed 004 eq. 13) */
        int apart_from_cell;      /**< 1: a point is apart where the densest node of its cell reads so (apart_measure) */
        pm_fbar_mode fbar;        /**< volumetric averaging against locking (MPM only) */
        double fbar_own_share;    /**< share s of each particle's own volume change F-bar keeps: J_cell^(1-s) J_p^s */
        pm_srf_opts strength_reduction;
        double max_steps;         /**< a run whose estimated step count exceeds this is refused (default 1e8) */
    } analysis;
    struct {
        pm_grid_type type;
        double origin[2], size[2];
        int cells[2];
        int element;              /**< pm_element */
        char file[PM_PATH_MAX];   /**< gmsh: resolved against dir */
        int lattice;              /**< gmsh: 1 (default) runs a mesh of equal axis-aligned quads filling its
                                       bounding box as the structured grid of those cells */
    } grid;
    size_t n_materials;
    pm_material *materials;
    size_t n_bodies;
    pm_case_body *bodies;
    size_t n_bcs;
    pm_case_bc *bcs;
    size_t n_probes;
    pm_case_probe *probes;
    struct {
        char directory[PM_PATH_MAX]; /**< default "<stem>.out" */
        double interval;             /**< default end_time / 100 */
        double probe_interval;       /**< 0 = every step */
        double checkpoint_interval;  /**< simulated seconds between checkpoints; 0 = at the end (and on a signal) only */
        char pictures[PM_NAME_MAX];  /**< field of a PNG picture per frame (pm_field_from_name), "" = none */
        double picture_range[2];     /**< fixed colour range of the pictures; NaN: one range over the run */
        int picture_width;           /**< picture width in pixels (default 800) */
    } output;
    size_t n_sources;
    pm_case_source *sources;      /**< particles of source k carry body index n_bodies + k */
    size_t n_sinks;
    pm_case_sink *sinks;
    size_t n_contact_pairs;
    pm_case_contact_pair *contact_pairs; /**< body-body contact laws; none: one field, bodies stick */
    size_t n_obstacles;
    pm_case_obstacle *obstacles;
    size_t n_loads;
    pm_case_particle_load *loads;
    void *doc;                    /**< the JSON document the case was read from (private; pm_case_set edits it) */
} pm_case;

/**
 * @brief Load and validate a case file.
 * @param path file to read
 * @param c receives the case (free with pm_case_free, also after a failure)
 * @return PM_OK, PM_EINPUT (message names file:line:column or key path), PM_EIO, PM_ENOMEM
 */
int pm_case_load(const char *path, pm_case *c);

/**
 * @brief Load a case from text in memory (for tests and the fuzz target).
 * @param text JSON text
 * @param len its length in bytes
 * @param name file name used in messages (its directory resolves relative paths)
 * @param c receives the case (free with pm_case_free)
 */
int pm_case_load_buffer(const char *text, size_t len, const char *name, pm_case *c);

/** @brief Free what a case owns and zero it. Safe on a zeroed struct. */
void pm_case_free(pm_case *c);

/**
 * @brief Load a case into a case allocated here (for bindings from other languages, which cannot
 *        allocate the struct themselves).
 * @param path the case file, or NULL to load @p text instead
 * @param text JSON text when @p path is NULL (its name in messages: @p name)
 * @param name file name of @p text for messages and relative paths (NULL: "case.json")
 * @param out receives the case (NULL after a failure); free with pm_case_destroy()
 * @return as pm_case_load()
 */
int pm_case_new(const char *path, const char *text, const char *name, pm_case **out);

/** @brief Free a case from pm_case_new() (NULL is fine). */
void pm_case_destroy(pm_case *c);

/** @brief The case's output directory (output.directory, or its default "<stem>.out"). */
const char *pm_case_output_dir(const pm_case *c);

/** Longest warning message, with its terminating zero. */
#define PM_WARNING_LEN 320

/**
 * @brief Values of a case that are valid but almost surely mistakes: a stiffness below 1 kPa (moduli are
 *        in pascals), an angle between 0 and 2 degrees (given in radians?), gravity pointing up with a
 *        geostatic initial stress. `pmech run` prints them and run.json lists them; none stops a run.
 * @param c the case
 * @param out receives up to @p cap messages, each naming the key path and the value
 * @param cap room in @p out (0 to count only)
 * @return the number of warnings (may exceed @p cap)
 */
size_t pm_case_warnings(const pm_case *c, char (*out)[PM_WARNING_LEN], size_t cap);

/**
 * @brief How many releases source @p k makes up to analysis.end_time (its listed times, or start,
 *        start + period, ... up to until; a time within 1e-9 periods of a limit counts as inside).
 */
size_t pm_case_source_releases(const pm_case *c, size_t k);

/** @brief The time of release @p j (0-based, below pm_case_source_releases()) of source @p k. */
double pm_case_source_release_time(const pm_case *c, size_t k, size_t j);

/*
 * Changing a loaded case by key path. A path names a key as docs/input.md does, with [i] for the
 * i-th entry of a list: "materials[0].friction_angle", "analysis.gravity[1]", "bodies[0].shape.max".
 * Each call edits the case's JSON document and reloads all of it, so a value passes exactly the
 * checks it would in a case file (ranges, types, unknown keys with "did you mean", cross-checks
 * between sections); on failure the case is left as it was and the message names the key path.
 * Objects missing on the way are created ("output.picture_range" on a case without "output"); an
 * index equal to a list's length appends to it. A simulation made from the case must be destroyed
 * before the case changes (it points into the case's arrays).
 */

/**
 * @brief Set a number (a whole number is written as a JSON integer, so keys that take counts accept it).
 * @param c a case from pm_case_load() or pm_case_load_buffer()
 * @param path key path, e.g. "materials[0].friction_angle"
 * @param value the number (finite)
 * @return PM_OK, or PM_EINPUT naming the key path (the case unchanged)
 */
int pm_case_set(pm_case *c, const char *path, double value);

/**
 * @brief Set a string, e.g. pm_case_set_string(c, "analysis.scheme", "usl").
 * @return PM_OK, or PM_EINPUT naming the key path (the case unchanged)
 */
int pm_case_set_string(pm_case *c, const char *path, const char *value);

/**
 * @brief Set any JSON value given as text: a list "[0, -9.81]", an object, true or false.
 * @param json the value as JSON text
 * @return PM_OK, or PM_EINPUT for text that is not JSON or a value the case refuses (case unchanged)
 */
int pm_case_set_json(pm_case *c, const char *path, const char *json);

/**
 * @brief Remove an optional key so that its default applies (e.g. "analysis.dt").
 * @return PM_OK; PM_EINPUT when the key is not there or the case needs it (the case unchanged)
 */
int pm_case_remove(pm_case *c, const char *path);

/**
 * @brief Read a number given in the case (defaults that the file leaves out are not in the document:
 *        read those from the struct).
 * @param value receives the number
 * @return PM_OK; PM_EINPUT when the path does not name a number of the document
 */
int pm_case_get(const pm_case *c, const char *path, double *value);

/**
 * @brief The JSON text of a key's value, or of the whole case for path "" (to save a changed case).
 * @return a string to release with free(), or NULL (message set) when the path names nothing
 */
char *pm_case_get_json(const pm_case *c, const char *path);

/** Material-point driver path types. */
typedef enum { PM_PATH_TRIAXIAL = 0, PM_PATH_OEDOMETER = 1, PM_PATH_SIMPLE_SHEAR = 2, PM_PATH_INCREMENTS = 3 } pm_path_type;

/** A `pmech material` driver file. */
typedef struct pm_driver {
    pm_material material;
    double stress0[4];            /**< initial [sxx, syy, szz, sxy], tension positive */
    pm_path_type path;
    double confining_pressure;    /**< triaxial, compression positive */
    double axial_strain;          /**< triaxial/oedometer, compression positive */
    double shear_strain;          /**< simple_shear, engineering gamma_xy */
    int steps;                    /**< increments of the path (default 100) */
    double dt;                    /**< time per step for rate-dependent models (default 1e-3) */
    size_t n_increments;          /**< strain_increments */
    double *increments;           /**< 4 per increment: dexx, deyy, dezz, dgxy */
} pm_driver;

/**
 * @brief Load a driver file (docs/input.md, "Material-point driver files").
 * @return PM_OK or PM_EINPUT/PM_EIO with a message as for case files
 */
int pm_driver_load(const char *path, pm_driver *d);

/** @brief Free what a driver owns. */
void pm_driver_free(pm_driver *d);

#ifdef __cplusplus
}
#endif
#endif
