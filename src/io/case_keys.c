/*
 * The keys every object of a case accepts, in one table: the parsers check objects against it
 * through pm_case_keys(), and tests/unit/test_case_keys.c compares it with docs/input.md, so the
 * loader and the reference cannot drift apart unnoticed.
 */
#include "io/case_internal.h"

static const char *const top_keys[] = {"title", "dimension", "formulation", "method", "shape_function", "lme_gamma",
                                       "support_radius", "max_condition", "analysis", "grid", "materials", "bodies",
                                       "boundary_conditions", "output", "probes", "sources", "sinks", "contact_pairs",
                                       "obstacles", "loads", NULL};
static const char *const analysis_keys[] = {"type", "scheme", "end_time", "dt", "cfl", "gravity",
                                            "gravity_ramp_time", "damping", "flip", "newton", "load_steps",
                                            "density_update", "apart_measure", "strength_reduction", "fbar",
                                            "fbar_own_share", "transfer", "xpic_order", "max_steps", NULL};
static const char *const srf_keys[] = {"min", "max", "tolerance", "criterion", "displacement_ratio", NULL};
static const char *const newton_keys[] = {"tolerance", "displacement_tolerance", "max_iterations", "line_search",
                                          "max_step_cuts", "absolute_tolerance", NULL};
static const char *const rect_keys[] = {"type", "origin", "size", "cells", "element", NULL};
static const char *const gmsh_keys[] = {"type", "file", "lattice", NULL};
static const char *const body_keys[] = {"name", "material", "shape", "particles_per_cell", "velocity",
                                        "initial_stress", "k0", "surface_y", "contact_group", NULL};
static const char *const shape_rect[] = {"type", "min", "max", NULL}, *const shape_poly[] = {"type", "points", NULL},
                         *const shape_circ[] = {"type", "center", "radius", NULL},
                         *const shape_grp[] = {"type", "name", NULL};
/* every key of any condition; each type then allows its own */
static const char *const bc_keys[] = {"type", "boundary", "directions", "value", "coefficient", "until", NULL};
static const char *const bc_fixed[] = {"type", "boundary", "directions", "until", NULL};
static const char *const bc_velocity[] = {"type", "boundary", "value", "until", NULL};
static const char *const bc_friction[] = {"type", "boundary", "coefficient", NULL};
static const char *const line_keys[] = {"x", "y", "from", "to", "normal", NULL};
static const char *const probe_keys[] = {"name", "quantity", "point", "body", NULL};
static const char *const output_keys[] = {"directory", "interval", "probe_interval", "pictures", "picture_range",
                                          "picture_width", "checkpoint_interval", NULL};
static const char *const source_keys[] = {"name", "material", "shape", "particles_per_cell", "velocity",
                                          "initial_stress", "k0", "surface_y", "times", "start", "period",
                                          "until", "only_when_free", "contact_group", NULL};
static const char *const sink_outlet[] = {"type", "name", "boundary", NULL},
                         *const sink_region[] = {"type", "name", "shape", NULL},
                         *const sink_outside[] = {"type", "name", NULL};
static const char *const sink_line[] = {"x", "y", "from", "to", "normal", NULL};
static const char *const pair_keys[] = {"bodies", "law", "friction", "separation", NULL};
static const char *const obstacle_keys[] = {"name", "type", "points", "center", "radius", "material_side", "law",
                                            "friction", "penalty_factor", "velocity", "corners", "acts_at", NULL};
static const char *const timefn_keys[] = {"value", "ramp_time", "table", NULL};
static const char *const load_keys[] = {"name", "nearest", "min", "max", "force", "grid_line", "force_per_length", NULL};
static const char *const load_line[] = {"x", "y", "from", "to", NULL};

static const pm_case_keyset table[PM_KEYS_COUNT] = {
    [PM_KEYS_TOP] = {"", NULL, top_keys},
    [PM_KEYS_ANALYSIS] = {"analysis", NULL, analysis_keys},
    [PM_KEYS_NEWTON] = {"analysis.newton", NULL, newton_keys},
    [PM_KEYS_STRENGTH_REDUCTION] = {"analysis.strength_reduction", NULL, srf_keys},
    [PM_KEYS_GRID_RECTANGLE] = {"grid", "rectangle", rect_keys},
    [PM_KEYS_GRID_GMSH] = {"grid", "gmsh", gmsh_keys},
    [PM_KEYS_BODY] = {"bodies[]", NULL, body_keys},
    [PM_KEYS_SHAPE_RECTANGLE] = {"bodies[].shape", "rectangle", shape_rect},
    [PM_KEYS_SHAPE_POLYGON] = {"bodies[].shape", "polygon", shape_poly},
    [PM_KEYS_SHAPE_CIRCLE] = {"bodies[].shape", "circle", shape_circ},
    [PM_KEYS_SHAPE_GMSH_GROUP] = {"bodies[].shape", "gmsh_group", shape_grp},
    [PM_KEYS_BC] = {"boundary_conditions[]", NULL, bc_keys},
    [PM_KEYS_BC_FIXED] = {"boundary_conditions[]", "fixed", bc_fixed},
    [PM_KEYS_BC_VELOCITY] = {"boundary_conditions[]", "velocity", bc_velocity},
    [PM_KEYS_BC_FRICTION] = {"boundary_conditions[]", "friction", bc_friction},
    [PM_KEYS_BC_LINE] = {"boundary_conditions[].boundary", NULL, line_keys},
    [PM_KEYS_PROBE] = {"probes[]", NULL, probe_keys},
    [PM_KEYS_OUTPUT] = {"output", NULL, output_keys},
    [PM_KEYS_SOURCE] = {"sources[]", NULL, source_keys},
    [PM_KEYS_SINK_OUTLET] = {"sinks[]", "outlet", sink_outlet},
    [PM_KEYS_SINK_REGION] = {"sinks[]", "region", sink_region},
    [PM_KEYS_SINK_OUTSIDE_GRID] = {"sinks[]", "outside_grid", sink_outside},
    [PM_KEYS_SINK_LINE] = {"sinks[].boundary", NULL, sink_line},
    [PM_KEYS_CONTACT_PAIR] = {"contact_pairs[]", NULL, pair_keys},
    [PM_KEYS_OBSTACLE] = {"obstacles[]", NULL, obstacle_keys},
    [PM_KEYS_TIMEFN] = {"obstacles[].velocity[]", NULL, timefn_keys},
    [PM_KEYS_LOAD] = {"loads[]", NULL, load_keys},
    [PM_KEYS_LOAD_LINE] = {"loads[].grid_line", NULL, load_line},
};

const char *const *pm_case_keys(pm_case_keyset_id id) { return table[id].keys; }

const pm_case_keyset *pm_case_keysets(size_t *n)
{
    *n = PM_KEYS_COUNT;
    return table;
}
