/*
 * Internal to src/io: the parts of case loading. case_file.c reads the file and the top level and
 * calls one parser per section (case_analysis.c, case_grid.c, case_bodies.c, case_conditions.c);
 * case_keys.c holds the one table of the keys every object of a case accepts, which the parsers
 * check against and the documentation test compares with docs/input.md.
 */
#ifndef PMECH_IO_CASE_INTERNAL_H
#define PMECH_IO_CASE_INTERNAL_H

#include <jansson.h>
#include <stddef.h>

#include "pmech/case.h"
#include "pmech/particles.h"

/** The objects of a case that take keys (materials excepted: their keys come from each model). */
typedef enum pm_case_keyset_id {
    PM_KEYS_TOP,
    PM_KEYS_ANALYSIS,
    PM_KEYS_NEWTON,
    PM_KEYS_STRENGTH_REDUCTION,
    PM_KEYS_GRID_RECTANGLE,
    PM_KEYS_GRID_GMSH,
    PM_KEYS_BODY,
    PM_KEYS_SHAPE_RECTANGLE,
    PM_KEYS_SHAPE_POLYGON,
    PM_KEYS_SHAPE_CIRCLE,
    PM_KEYS_SHAPE_GMSH_GROUP,
    PM_KEYS_BC,
    PM_KEYS_BC_FIXED,
    PM_KEYS_BC_VELOCITY,
    PM_KEYS_BC_FRICTION,
    PM_KEYS_BC_LINE,
    PM_KEYS_PROBE,
    PM_KEYS_OUTPUT,
    PM_KEYS_SOURCE,
    PM_KEYS_SINK_OUTLET,
    PM_KEYS_SINK_REGION,
    PM_KEYS_SINK_OUTSIDE_GRID,
    PM_KEYS_SINK_LINE,
    PM_KEYS_CONTACT_PAIR,
    PM_KEYS_OBSTACLE,
    PM_KEYS_TIMEFN,
    PM_KEYS_LOAD,
    PM_KEYS_LOAD_LINE,
    PM_KEYS_COUNT
} pm_case_keyset_id;

/** The keys one object of a case accepts. */
typedef struct pm_case_keyset {
    const char *path;        /**< the object's key path, [] for any index: "bodies[].shape"; "" the root */
    const char *variant;     /**< the value of the object's "type" that selects this list, or NULL */
    const char *const *keys; /**< NULL-terminated, as jr_only_keys() takes them */
} pm_case_keyset;

/** The allowed keys of object @p id, for jr_only_keys(). */
const char *const *pm_case_keys(pm_case_keyset_id id);

/** The whole key table, PM_KEYS_COUNT entries in pm_case_keyset_id order; @p n receives the count. */
const pm_case_keyset *pm_case_keysets(size_t *n);

/**
 * Load a case from a parsed document, which the case then owns (pm_case_free releases it, also after a
 * failure); @p name is the file name used in messages and for relative paths.
 */
int pm_case_from_json(json_t *root, const char *name, pm_case *c);

/** Set PM_EINPUT "<file>: <path>: <what><detail>" (detail may be NULL) and return it. */
int pm_case_fail(const char *file, const char *path, const char *what, const char *detail);

/**
 * `analysis` with its `newton` and `strength_reduction` objects. Needs c->method (read before it)
 * for the checks that tie the analysis to the method.
 */
int pm_case_parse_analysis(pm_case *c, json_t *a);

/** After the materials: a strength-reduction search needs a material whose strength it can reduce. */
int pm_case_check_strength_reduction(const pm_case *c);

/** `grid`: a rectangle's origin, size, cells and element, or a gmsh file resolved against c->dir. */
int pm_case_parse_grid(pm_case *c, json_t *g);

/**
 * Upper estimates of the particles (bodies and every release of the sources, each shape as full as its
 * bounding box) and grid nodes of a rectangle grid; both 0 for a Gmsh grid, which the mesh file bounds.
 */
void pm_case_estimate_sizes(const pm_case *c, double *particles, double *nodes);

/** Refuse particle and node counts that cannot be allocated, before anything is (after the bodies). */
int pm_case_check_sizes(const pm_case *c);

/** `materials`: a non-empty list of uniquely named materials. */
int pm_case_parse_materials(pm_case *c, json_t *ms);

/** `bodies`: after the grid, the materials and the sources (a case with sources may have no body). */
int pm_case_parse_bodies(pm_case *c, json_t *bs);

/**
 * The keys a body and a source share (all of a body's): name (default @p def_name, unique among the
 * first @p n_before bodies and the sources parsed so far), material, shape, particles_per_cell,
 * velocity, initial stress; the shape must lie inside a rectangle grid. The caller checks which keys
 * the object may have.
 */
int pm_case_parse_body(pm_case *c, const char *path, json_t *b, const char *def_name, size_t n_before,
                       pm_case_body *body);

/** `sources`: after the grid, the materials and the analysis (explicit MPM only). */
int pm_case_parse_sources(pm_case *c, json_t *ss);

/** `sinks`: after the grid and the analysis (explicit MPM only). */
int pm_case_parse_sinks(pm_case *c, json_t *ss);

/** A shape object (rectangle, polygon, circle, gmsh_group) at key path @p path. */
int pm_case_parse_shape(pm_case *c, const char *path, json_t *sh, pm_shape *s);

/** Refuse a polygon that encloses no area or whose outline crosses itself (case_polygon.c); @p path
 *  names its points in messages. */
int pm_case_check_polygon(const pm_case *c, const char *path, const pm_shape *s);

/** The bounding box of a shape; NaN for a gmsh group, whose extent only the mesh knows. */
void pm_case_shape_box(const pm_shape *s, double lo[PM_DIM], double hi[PM_DIM]);

/**
 * `contact_pairs`: after the bodies, the sources and the analysis; names the contact groups of the
 * bodies and sources (case_contact_pairs.c).
 */
int pm_case_parse_contact_pairs(pm_case *c, json_t *cp);

/** `boundary_conditions`: after the analysis and the grid, which decide what a condition may be. */
int pm_case_parse_bcs(pm_case *c, json_t *bcs);

/** `obstacles` (after `analysis` and `grid`, whose type and box it checks against). */
int pm_case_parse_obstacles(pm_case *c, json_t *obs);

/** Free the obstacles a case holds (pm_case_free calls it). */
void pm_case_free_obstacles(pm_case *c);

/** `loads` (after `analysis`). */
int pm_case_parse_loads(pm_case *c, json_t *ls);

/** Free the loads a case holds (pm_case_free calls it). */
void pm_case_free_loads(pm_case *c);

/**
 * A function of time at key path @p path: a number (constant), {"value": v, "ramp_time": T} or
 * {"table": [[t, v], ...]} with increasing times. @p f owns a table afterwards, also after a failure
 * (pm_timefn_free).
 */
int pm_case_parse_timefn(const char *file, const char *path, json_t *v, pm_timefn *f);

/** `probes`: after the bodies, which a probe may name. */
int pm_case_parse_probes(pm_case *c, json_t *ps);

/** `output`: after the analysis, whose end time sets the default interval. */
int pm_case_parse_output(pm_case *c, json_t *o);

struct jr_ctx;

/** `output.picture_range` and `output.picture_width` (case_pictures.c), called by pm_case_parse_output. */
int pm_case_parse_picture_options(pm_case *c, const struct jr_ctx *cx, json_t *o);

#endif
