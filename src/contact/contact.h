/*
 * Contact: where the material meets a boundary or an obstacle, and the law that acts there. The
 * explicit and implicit solvers and the meshfree methods (GMM, RKPM) see contact only through this
 * interface; none of them holds a contact list of its own.
 *
 * Life of a contact object (one per simulation, pm_sim::contact, destroyed with it):
 *   pm_contact_create   from the case: every `friction` condition becomes a surface (on a Gmsh group
 *                       on the mesh's boundary, a wall of its edges with a normal per node: edges.c); with gmm and
 *                       rkpm a `fixed` grid side that holds its normal component becomes a guard wall
 *                       as well (nodes that reach the side later are stopped there: it sticks when the
 *                       tangent is held too, slides freely otherwise); every obstacles[] entry
 *                       becomes a polyline, polygon or circle surface (geometry.c) with its law.
 *   pm_contact_detect   at the start of every step (pm_sim_update_constraints): the obstacles are
 *                       moved to their place at time t (displacement = the exact integral of their
 *                       velocity functions), and the candidate nodes found. A node-set surface (an
 *                       MPM grid side or line, or a Gmsh wall) keeps the nodes it had at t = 0; the other surfaces
 *                       take the nodes within pm_contact::reach of them, so that moving meshfree
 *                       nodes and moving obstacles meet as they move. Each entry holds the normal
 *                       into the surface at the node. A box around each surface (its points, disk
 *                       or nodes, widened by the reach) lets this pass and the gaps' skip the far
 *                       nodes and particles without a distance: the distances to a polyline of
 *                       every particle and node took 17 % of an elastic block's step.
 *   pm_contact_gaps     explicit steps, right after: every entry's gap from the material's actual
 *                       surface (detect.c), so a law acts when the material reaches the surface, not
 *                       when a node's cell holds material; and, for the nodal law of a node set (an
 *                       MPM `friction` side or line) once pm_contact_points_reserve() has been called,
 *                       the touching points: the foot on the surface of every particle within half a
 *                       cell of it, between two neighbouring nodes of the set, with its own gap; for
 *                       the nodal law of an obstacle (polyline, polygon, circle) that acts at the
 *                       particles (acts_at), and of a GMM `friction` wall (a grid side or line, a
 *                       Gmsh group), every particle whose gap is within half a cell, acting through
 *                       its stencil's candidate nodes.
 *   pm_contact_apply    explicit steps, after the end-of-step velocity: the law on every contact node
 *                       that carries mass, on its velocity relative to the surface, then the node's
 *                       prescribed components, then the node's acceleration again as (v - v0) /
 *                       dt_acc. The nodal law lets a node approach by its gap in the step and removes
 *                       the rest of its approaching velocity (Bardenhagen et al. 2000), the penalty
 *                       law pushes by stiffness x penetration x dt; both cut the slip by up to mu
 *                       times their normal change. A node set or obstacle with touching points takes
 *                       the nodal law at the points instead (friction.c): the velocity interpolated at
 *                       each point, not each node's, may approach by the point's gap and no more, so
 *                       the reaction acts where the material touches, between the nodes; on an
 *                       obstacle or GMM wall acting at the particles, a node is held only as
 *                       far as the touching particles' own velocities need. The resultant
 *                       force of every surface (m dv / dt, summed over its nodes) is kept for
 *                       pm_contact_force_of().
 *   pm_contact_particle_velocities
 *                       explicit FLIP steps, right after: the particles an obstacle acting at the
 *                       particles pushed take the velocity the law let them move with (touching.c).
 *   pm_contact_project_normal
 *                       explicit steps, velocities re-projected within a step (MUSL, USF start,
 *                       predictor): at the entries of nodal-law surfaces that the law held in
 *                       this step, the normal velocity the law left them (approaching or
 *                       separating: the particles moved with it, and the strain must agree; a node
 *                       lighter than the particles touching there, whose end velocity is not the
 *                       material's, only its mass's share of it, pm_contact_node::hold); at the
 *                       other entries in touch (gap <= 0), the approaching normal velocity only (none
 *                       at the entries of a node set acting at touching points: the law left them
 *                       free); no
 *                       friction impulse (that one has been applied to the end-of-step velocity),
 *                       then the prescribed components.
 *   pm_contact_implicit_begin
 *                       implicit and quasi-static steps, at the start of every attempt: detection at
 *                       the step's start time, the gaps from the material's surface, and each
 *                       obstacle's displacement over the step (implicit_terms.c).
 *   pm_contact_implicit every residual evaluation of the attempt: the penalty terms of the residual and
 *                       tangent at every contact node with unknowns (whatever the surface's law: a
 *                       Newton solve needs forces that are functions of the displacement), built on
 *                       the node's force of the last step: normal, its normal force plus stiffness x
 *                       the step's approach (past the gap when it was apart); tangential, Coulomb
 *                       regularised by a tangential penalty of the same stiffness, returned to mu N
 *                       when larger (stick/slip return map); the tangent is the consistent one
 *                       (unsymmetric while slipping). Guard walls add nothing (the fixed condition
 *                       holds them).
 *   pm_contact_implicit_accept
 *                       after a converged attempt: every node's force is kept for the next step (a
 *                       body at rest on a surface neither sinks nor creeps), the surfaces' resultants
 *                       and impulses are those of the converged state.
 *
 * The nodal arrays a law works on are passed in (pm_contact_field), not taken from the simulation:
 * today that is the one field of pm_sim::nd, and a multi-body run will call the same functions once
 * per body field (an obstacle acts on every body; body-body contact will take two fields and the
 * common normal of their mass gradients).
 *
 * State: everything is plain arrays in the object, and an obstacle's place is a function of time
 * alone. Across steps, explicit runs keep the touching points' impulses (the next step's sweeps start
 * from them, friction.c), following their particles through sorts (pm_contact_renumber), and implicit
 * runs the force of
 * every node touching a surface (held; a node held by both faces of a Gmsh wall's inward corner keeps
 * one per face, pm_contact_implicit_history); checkpoints store both.
 *
 * Force output: every apply starts every surface's resultant from zero and adds m dv / dt of the
 * law (not the prescribed components that follow it) at each of its nodes: the force the surface
 * exerts on the material, its normal part (positive when it pushes the material away) and its
 * tangential part; pm_contact_force_of() reads it.
 *
 * Vectors are PM_DIM per node (v[PM_DIM * n + d]).
 */
#ifndef PMECH_CONTACT_H
#define PMECH_CONTACT_H

#include "pmech/case.h"
#include "pmech/grid.h"
#include "pmech/particles.h"
#include "pmech/timefn.h"
#include "pmech/approx.h"
#include "solver/sim_internal.h"

#include <stddef.h>
#include <stdint.h>

struct pm_implicit_ws;

/** How a surface acts on the nodes touching it. */
typedef enum pm_contact_law {
    /** Bardenhagen et al. (2000): the approaching normal velocity is removed and the tangential
     *  speed reduced by mu times that change, never reversed. */
    PM_CONTACT_LAW_NODAL_COULOMB = 0,
    /** Penalty-regularised Coulomb: normal force stiffness x penetration, friction up to mu times it. */
    PM_CONTACT_LAW_PENALTY_COULOMB = 1
} pm_contact_law;

/** What a surface is and how its contact nodes are found. */
typedef enum pm_contact_kind {
    /** A fixed set of nodes with one outward normal (MPM grid side or line); they act while they
     *  carry mass. Its geometry is the plane through its first node with that normal. */
    PM_CONTACT_NODE_SET = 0,
    /** A straight rigid wall axis = value (gmm, rkpm): the nodes near it, found again by every
     *  pm_contact_detect(). */
    PM_CONTACT_WALL = 1,
    /** A rigid chain of segments with the material on one side (obstacles[] of type polyline). */
    PM_CONTACT_POLYLINE = 2,
    /** A rigid closed polygon with the material outside. */
    PM_CONTACT_POLYGON = 3,
    /** A rigid disk with the material outside. */
    PM_CONTACT_CIRCLE = 4,
    /** A Gmsh 1-D group on the mesh's boundary (edges.c): a fixed set of nodes as PM_CONTACT_NODE_SET,
     *  each with the normal of its edges (gmm, rkpm: the nodes near it, found again by every
     *  pm_contact_detect(), pm_contact_surface::detected); its geometry is its edges, 2 points each in
     *  pm_contact::points, the material on their left. */
    PM_CONTACT_EDGES = 5
} pm_contact_kind;

/** Two edges of a Gmsh wall meeting at a node whose normals differ by more than this many degrees make a
 *  corner there: each edge keeps its own normal (edges.c). Curves meshed finer than this (a circle in 13
 *  edges or more) have a smooth normal at every node. */
#define PM_CONTACT_CORNER_DEG 30.0

/** Resultant force of one surface on the material over the last pm_contact_apply(). */
typedef struct pm_contact_force {
    double force[PM_DIM];   /**< sum of m dv / dt over the surface's nodes */
    double normal;          /**< sum of -m (dv . n) / dt: positive when the surface pushes the material */
    double tangent[PM_DIM]; /**< sum of the tangential parts m (dv - (dv . n) n) / dt */
} pm_contact_force;

/** One boundary or obstacle. */
typedef struct pm_contact_surface {
    pm_contact_kind kind;
    pm_contact_law law;
    double mu;               /**< Coulomb coefficient (INFINITY: sticks; 0: slides freely) */
    long bc;                 /**< the case's boundary_conditions[] index it comes from (-1: none) */
    long obstacle;           /**< the case's obstacles[] index it comes from (-1: none) */
    int guard;               /**< 1: a gmm/rkpm guard wall implied by a fixed side (no implicit terms) */
    size_t first, n;         /**< node set: its entries in pm_contact::node */
    int axis;                /**< wall: 0 for x = value, 1 for y = value */
    double value;            /**< wall: position */
    double normal[PM_DIM];   /**< node set, wall: outward normal of the body's domain (into the surface) */
    double origin[PM_DIM];   /**< node set, wall: a point of its plane; circle: centre at t = 0 */
    double radius;           /**< circle */
    size_t first_point, n_points; /**< polyline, polygon: its points in pm_contact::points (at t = 0) */
    double side;             /**< polyline: +1 material left of its direction, -1 right; polygon: -1 when
                                  counter-clockwise (the material, outside, is right of every segment) */
    int sharp;               /**< polyline, polygon: a node nearest a corner takes the normal of the face
                                  it lies squarely off instead of the direction to the corner */
    int detected;            /**< Gmsh wall (PM_CONTACT_EDGES) of a gmm or rkpm run: no entries of its own;
                                  every detection takes the nodes within reach of its edges */
    const pm_timefn *motion; /**< velocity per component (PM_DIM functions of time; NULL: at rest) */
    double shift[PM_DIM];    /**< displacement of the obstacle at the time of the last detection */
    double box_lo[PM_DIM], box_hi[PM_DIM]; /**< at the last detection: a box holding every point within
                                  pm_contact::reach of the surface (and the inside of a polygon or circle),
                                  so that the node and particle passes skip the rest without a distance */
    double vel[PM_DIM];      /**< its velocity then */
    double stiffness;        /**< penalty law: (c / h)^2 times the penalty factor: force per node mass and
                                  penetration */
    pm_contact_force f;      /**< over the last apply */
    pm_contact_force impulse;/**< the same terms times dt, summed over the applies since a reader reset it */
    double *node_impulse;    /**< per node of the field, 1 + PM_DIM values: the normal and the tangential
                                  impulse (as in impulse) the law gave that node since a reader reset
                                  them: the wall's traction profile (pm_contact_profile) */
    double step[PM_DIM];     /**< implicit steps: the obstacle's displacement over the step being solved */
    int at_particles;        /**< obstacle with the nodal law: acts at the particles that touch it (the case's
                                  acts_at "particles") once points are reserved */
    int points_lost;         /**< 1: the last pm_contact_gaps() found more touching points than there was
                                  room for, so its law acts node by node in this step */
} pm_contact_surface;

/** A node touching a surface. */
typedef struct pm_contact_node {
    int32_t node;            /**< node index of the field */
    int32_t surface;         /**< index in pm_contact::surface */
    double normal[PM_DIM];   /**< outward unit normal at the node */
    double mu;               /**< friction coefficient */
    double gap;              /**< distance from the material's surface to the obstacle (< 0: penetration) */
    int held;                /**< 1: the nodal law acted on it in this step's pm_contact_apply() (reset by
                                  pm_contact_detect()) */
    double vn_held;          /**< then: its normal velocity relative to the surface after the law */
    double hold;             /**< the share of vn_held the re-projected velocity takes (1; a node of a node set
                                  lighter than a particle touching there: its mass over the particle's) */
    int corner;              /**< 1: the node is a Gmsh wall's re-entrant corner (a tool's tip), whose normal
                                  is that of the face the nearest material lies squarely off, chosen by
                                  every pm_contact_gaps() */
    int32_t own_row;         /**< Gmsh walls (PM_CONTACT_EDGES) only: 0, or for the second face of an inward
                                  corner 1 + its index among those faces: its implicit force history is then
                                  a row of its own after the (surface, node) rows, so that the two faces of
                                  one node keep their forces apart */
} pm_contact_node;

/** Nodes a touching point acts through at most: a node set's two either side of it; an obstacle's, the
 *  stencil nodes of the touching particle that are its candidates (linear 4, uGIMP and B-spline up to 9;
 *  of a wider stencil, the largest shape functions). */
#define PM_CONTACT_POINT_NODES 16

/** Where the material's surface touches a surface (explicit steps, pm_contact_points_reserve): the
 *  nodal law then acts on the velocity interpolated there. On a node set the point is a particle's foot
 *  between two of its nodes; on an obstacle or a GMM wall it is the touching particle itself, the
 *  law acting on the velocity its stencil gives it, i.e. on the motion that would carry it into the
 *  obstacle. */
typedef struct pm_contact_point {
    int32_t surface;         /**< index in pm_contact::surface */
    int32_t n;               /**< nodes in node[], entry[], w[] */
    int32_t node[PM_CONTACT_POINT_NODES];  /**< the nodes it acts through (-1: none) */
    int32_t entry[PM_CONTACT_POINT_NODES]; /**< their entries in pm_contact::node (-1: none) */
    double w[PM_CONTACT_POINT_NODES];      /**< their shape functions at the point (summing to 1) */
    double normal[PM_DIM];   /**< into the surface at the point */
    double allow;            /**< normal velocity towards the surface it may have: its gap / dt, >= 0 */
    double mass;             /**< obstacle: the touching particle's mass, the least a node answers its
                                  impulse with (node set: 0, every node with its own) */
    double pmass;            /**< node set: the touching particle's mass; a node lighter than it takes a share
                                  of the point in proportion (obstacle: 0) */
    double lam_n;            /**< normal impulse per unit velocity weight the law gave it in this step */
    double lam_t[PM_DIM];    /**< tangential impulse, the same way, |lam_t| <= mu lam_n */
    size_t particle;         /**< the particle whose foot it is (its index after a sort that follows the
                                  points' detection: pm_contact_renumber) */
} pm_contact_point;

/** Values per entry in pm_contact::pt_impulse. */
#define PM_CONTACT_PT_ROW (1 + 2 * PM_DIM)

/** The surfaces of a simulation and the nodes touching them. */
typedef struct pm_contact {
    size_t n_surfaces;
    pm_contact_surface *surface;
    size_t n_fixed;          /**< entries of node[] that belong to node-set surfaces (set at creation) */
    size_t n_node;           /**< entries in use: node sets first, then the walls' contacts */
    size_t cap;              /**< entries allocated: node sets plus walls x nodes, never grown in a step */
    size_t n_nodes;          /**< nodes of the field */
    pm_contact_node *node;
    size_t n_points;         /**< polyline and polygon points of every obstacle, PM_DIM each */
    double *points;
    int32_t *slot;           /**< n_nodes: -1, or during the gap pass the node's entry for one surface */
    double reach;            /**< nodes and particles within this distance of a surface are considered */
    double penalty;          /**< implicit steps: penalty stiffness per node mass of the surfaces that have
                                  none of their own (friction conditions): (c / h)^2 */
    int surface_gaps;        /**< 1: every gap from the material's surface, whatever the law (implicit) */
    double *held;            /**< implicit steps: each node's force on the material at the last accepted
                                  step, PM_DIM per (surface, node), then one row per own_row entry */
    double *held_next;       /**< the same, being written by pm_contact_implicit_accept() */
    size_t n_own_rows;       /**< entries with an own_row (second faces of Gmsh walls' inward corners) */
    size_t n_pt, pt_cap;     /**< touching points in use and allocated (0: node sets act node by node) */
    pm_contact_point *pt;    /**< explicit steps: where the material touches node-set surfaces */
    int32_t *side_nbr;       /**< per node-set entry: the entries before and after it along its surface
                                  (-1 at an end), 2 per entry */
    double *pt_impulse;      /**< per entry, PM_CONTACT_PT_ROW values: the normal push (sum of w lam_n), the
                                  impulse and its tangential part (PM_DIM each) its surface's points gave
                                  its node (a node two surfaces share gets each surface's own) */
    const double *node_x;    /**< the node positions the points are placed between (the grid's) */
    size_t pt_old, n_pt_old; /**< while the points are found: where the last step's points were moved
                                  (the end of pt[]) and how many, their impulses to start the sweeps from */
    size_t pt_cursor;        /**< the next of them to match (pm_contact_gaps) */
    double pt_dt;            /**< the step the points' impulses were found for (0: none yet) */
    size_t *pt_renum;        /**< pt_cap: scratch of pm_contact_renumber() */
    size_t pt_solves;        /**< explicit applications that had touching points, since creation */
    size_t pt_sweeps;        /**< the Gauss-Seidel sweeps those took, summed */
} pm_contact;

/**
 * Whether surface @p sf can act at touching points (pm_contact_points_reserve): the nodal law of a node
 * set, of a meshfree `friction` wall (a grid side or line, not a guard wall, or a Gmsh group), or of an
 * obstacle that asks for it (pm_contact_surface::at_particles). A GMM wall's nodes hold shape-function
 * coefficients, not the material's velocity: a particle on the floor takes 0.79 of its velocity from the
 * bottom row and 0.21 from the row above on a quad grid's cloud, so the law held node by node left the
 * touching particles approaching, and took stick, slip and lift-off for each coefficient; the bottom row
 * then carried a wave along the floor faster than the sliding (verify_incline_fine), the friction fell to
 * 0.27 of the normal force, and a block slid 6 % fast. At the particles, the law acts on the velocity the
 * material moves with (docs/verification-notes.md); on a Gmsh slope meshed twice as fine as the incline
 * tests' the block was +3.2 % at 0.1 s node by node and +0.7 % at the particles. RKPM runs reserve no
 * points, so their walls act node by node: on h = 0.01 m that block was +1.5 % at 0.1 s node by node and
 * +2.0 % at the particles, whose normal impulse over 0.01 s ranged over 0.93-1.09 of W cos (0.96-1.03
 * node by node).
 */
static inline int pm_contact_takes_points(const pm_contact_surface *sf)
{
    if (sf->law != PM_CONTACT_LAW_NODAL_COULOMB)
        return 0;
    return sf->kind == PM_CONTACT_NODE_SET || (sf->kind == PM_CONTACT_WALL && !sf->guard) ||
           (sf->kind == PM_CONTACT_EDGES && sf->detected) ||
           (sf->at_particles &&
            (sf->kind == PM_CONTACT_POLYLINE || sf->kind == PM_CONTACT_POLYGON || sf->kind == PM_CONTACT_CIRCLE));
}

/** Whether surface @p sf acts at touching points in this step: it can, points are reserved, and the last
 *  pm_contact_gaps() had room for all of its points. */
static inline int pm_contact_at_points(const pm_contact *ct, const pm_contact_surface *sf)
{
    return ct->pt_cap > 0 && !sf->points_lost && pm_contact_takes_points(sf);
}

/** The nodal arrays one application works on (one body's field). */
typedef struct pm_contact_field {
    const double *mass;      /**< lumped nodal mass */
    const double *v0;        /**< start-of-step velocity, PM_DIM per node: acc = (v - v0) / dt_acc */
    double *v;               /**< the velocity the law acts on, PM_DIM per node */
    double *acc;             /**< acceleration, PM_DIM per node (rewritten at contact nodes by apply) */
    const uint8_t *fixed;    /**< bit d: component d prescribed */
    const double *vfix;      /**< prescribed velocity, PM_DIM per node */
    double mass_floor;       /**< a node carries material when its mass exceeds this */
} pm_contact_field;

/** The simulation's one field, with @p v as the velocity to act on. */
static inline pm_contact_field pm_contact_field_of(const pm_nodal *nd, double *v, double mass_floor)
{
    pm_contact_field f = {nd->mass, nd->vel, v, nd->acc, nd->fixed, nd->vfix, mass_floor};
    return f;
}

/**
 * Surfaces of the case's conditions (see the top). MPM node sets are taken from @p g (a line
 * condition adds its set to it); walls take a grid side's position from @p frame (the case's grid,
 * which frames the meshfree nodes). The first detection (t = 0) is done.
 * @return PM_OK, PM_EINPUT naming the condition, PM_ENOMEM
 */
int pm_contact_create(const pm_case *c, pm_grid *g, const pm_grid *frame, pm_contact **out);

/** An empty contact object for a field of @p n_nodes nodes (surfaces are added to it). */
int pm_contact_new(size_t n_nodes, pm_contact **out);

/** A new surface (zeroed, no bc or obstacle) with room for @p more_nodes more entries in
 *  pm_contact::node. @return its index, or a negative status */
int pm_contact_add_surface(pm_contact *ct, size_t more_nodes, pm_contact_surface **out);

/** Add a node-set surface; its nodes touch it from now on. @return its index, or a negative status */
int pm_contact_add_node_set(pm_contact *ct, size_t n, const int32_t *nodes, const double normal[PM_DIM], double mu,
                            pm_contact_law law, long bc);

/**
 * Add the wall of a Gmsh 1-D group @p set of @p g (its pm_node_set::edges, not empty): its nodes touch it
 * from now on, each with the outward normal of its edges, the two edges' normals weighted by the
 * inverse of their lengths (exact on a circle) where they turn by less than PM_CONTACT_CORNER_DEG. At a
 * sharper corner where the material's domain turns inwards (a corner of a bin), the node has two
 * entries, one per edge's normal; where it turns outwards (a tool's tip in the material), one entry
 * whose normal pm_contact_gaps() takes from the face the nearest material lies off. A node of one edge
 * only (the group's end, or one of two coincident nodes at a tip) has that edge's normal.
 * @return its index, or a negative status
 */
int pm_contact_add_edge_set(pm_contact *ct, const pm_grid *g, const pm_node_set *set, double mu,
                            pm_contact_law law, long bc);

/**
 * Add the wall of a Gmsh 1-D group @p set of the case's mesh @p frame for a gmm or rkpm run, whose nodes
 * move: its edges make a fixed rigid wall (the material on each edge's left) whose contact nodes every
 * pm_contact_detect() finds within pm_contact::reach of it, each with the normal of the face it lies off
 * (a node nearest a corner: the face it lies squarely off). @return its index, or a negative status
 */
int pm_contact_add_edge_wall(pm_contact *ct, const pm_grid *frame, const pm_node_set *set, double mu,
                             pm_contact_law law, long bc);

/** Add a wall axis = value; detection finds its nodes. @return its index, or a negative status */
int pm_contact_add_wall(pm_contact *ct, int axis, double value, const double normal[PM_DIM], double mu,
                        pm_contact_law law, long bc, int guard);

/**
 * Add a rigid obstacle of the case (obstacles[@p k]): a polyline, polygon or circle moving with its
 * velocity functions; @p wave is the P-wave speed and @p h the cell size that set the penalty
 * stiffness. @return its index, or a negative status
 */
int pm_contact_add_obstacle(pm_contact *ct, const pm_case *c, size_t k, double wave, double h);

/**
 * Let the nodal law of every surface that can (pm_contact_takes_points) act where the material touches
 * it instead of node by node, for up to @p cap particles (explicit steps of a single-field run; see
 * pm_contact_gaps). @p g gives the node positions and the cell size. Call once after pm_contact_create().
 * @return PM_OK, PM_ENOMEM
 */
int pm_contact_points_reserve(pm_contact *ct, const pm_grid *g, size_t cap);

/**
 * The particles were renumbered (@p perm[j]: the old index of the particle now at j, for @p n
 * particles): the touching points follow them, so that the next pm_contact_gaps() starts each particle's
 * point from its own impulses again.
 */
void pm_contact_renumber(pm_contact *ct, const uint32_t *perm, size_t n);

/** Free (NULL is fine). */
void pm_contact_destroy(pm_contact *ct);

/**
 * Find the nodes near every surface at time @p t, from the node positions of @p g: node sets keep
 * their nodes, the other surfaces take the nodes within pm_contact::reach of them (or inside). Each
 * entry's gap is first the node's own signed distance (node sets: 0), which
 * pm_contact_gaps() replaces by the material's.
 */
void pm_contact_detect(pm_contact *ct, const pm_grid *g, double t);

/**
 * The gap of every contact entry from the material's actual surface: the smallest, over the
 * particles whose stencil holds the node, of the particle's signed distance to the surface minus
 * its half-size along the normal. Contact then starts when the material reaches the surface, not
 * when its cell does. With points reserved, also the touching points of the node sets' nodal law
 * (pm_contact_point; see the top). Needs connected particles (pm_approx::connect at their positions).
 */
void pm_contact_gaps(pm_contact *ct, const pm_approx *a, const pm_particles *p);

/**
 * Signed distance of @p x to surface @p sf as placed at the last detection (positive on the
 * material's side); @p n receives the unit normal pointing into the surface.
 */
double pm_contact_distance(const pm_contact *ct, const pm_contact_surface *sf, const double x[PM_DIM],
                           double n[PM_DIM]);

/**
 * Explicit steps: the law at every contact node of @p f that carries mass (node sets with touching
 * points: at the points, all at once), then its prescribed components, then acc = (v - v0) / dt_acc
 * there; the surfaces' forces are m dv / dt.
 */
void pm_contact_apply(pm_contact *ct, pm_contact_field f, double dt, double dt_acc);

/**
 * Explicit steps with the FLIP transfer, after pm_contact_apply() and before the particles' velocity update:
 * every particle touching an obstacle that acts at the particles (pm_contact_surface::at_particles) and
 * whose point the law pushed in this step (normal impulse > 0) takes as its own velocity the one its
 * stencil gives it from the nodal start velocity @p v0, less @p shift times its acceleration p->a (the
 * predictor-corrector's momentum shift; 0: none). The update, which adds the interpolated change, then
 * leaves it the velocity the law let it move with, not the one it had before the law held it (touching.c
 * says why). Needs the particles connected where they were at pm_contact_gaps().
 */
void pm_contact_particle_velocities(const pm_contact *ct, const pm_approx *a, pm_particles *p, const double *v0,
                                    double shift);

/** Explicit steps, re-projected velocities: at every contact node of @p f that the nodal law held in
 *  this step's apply, the normal velocity (relative to the surface) the law left it, whether the mapped
 *  one approaches or separates; at the other nodes in touch, the approaching normal velocity removed;
 *  then the prescribed components (no mass test, no impulse, no force). */
void pm_contact_project_normal(const pm_contact *ct, pm_contact_field f);

/**
 * Implicit steps, at the start of every attempt from @p t0 to @p t1: the contact nodes at t0 (nodes of
 * @p g), their gaps from the material's surface (particles @p p connected in @p a), and each
 * obstacle's displacement over the step. The first call allocates the nodal force history.
 * @return PM_OK, PM_ENOMEM
 */
int pm_contact_implicit_begin(pm_contact *ct, const pm_grid *g, const pm_approx *a, const pm_particles *p,
                              double t0, double t1);

/**
 * The nodal force history of implicit steps (pm_contact::held), allocated on the first call: @p rows
 * rows of PM_DIM, one per (surface, node), then one per second face of an inward corner of a Gmsh wall
 * (pm_contact_node::own_row). For checkpoints. @return PM_OK, PM_ENOMEM
 */
int pm_contact_implicit_history(pm_contact *ct, double **held, size_t *rows);

/**
 * Implicit steps: add the penalty contact terms at the increments w->du to the internal force
 * (w->fint, w->fscale) and, when @p want_K, to the tangent w->K, at every contact node whose nodal
 * mass (@p mass) exceeds @p mass_floor. NULL @p ct adds nothing.
 */
void pm_contact_implicit(const pm_contact *ct, const double *mass, double mass_floor, struct pm_implicit_ws *w,
                         int want_K);

/**
 * Implicit steps, after a converged attempt of length @p dt: keep every node's force for the next
 * step; each surface's resultant (pm_contact_force_of), impulse and per-node impulses (the wall
 * profiles) are the converged ones.
 */
void pm_contact_implicit_accept(pm_contact *ct, const double *mass, double mass_floor,
                                const struct pm_implicit_ws *w, double dt);

/** Surfaces (boundaries and obstacles) of @p ct (0 for NULL). */
size_t pm_contact_n_surfaces(const pm_contact *ct);

/** One station of a wall's traction profile. */
typedef struct pm_contact_station {
    double s;            /**< position along the wall: arc length from its start (see pm_contact_profile) */
    double x[PM_DIM];    /**< the wall's point there (at the last detection's place) */
    double normal;       /**< normal traction on the material, positive when the wall pushes it away */
    double tangent;      /**< tangential traction on the material along the direction of increasing s */
} pm_contact_station;

/** Length of surface @p k: a polyline's or polygon's perimeter, a circle's circumference, the span of a
 *  node set's nodes, a meshfree wall's side of the frame @p g. */
double pm_contact_length(const pm_contact *ct, size_t k, const pm_grid *g);

/** Stations of surface @p k's profile: about one per cell of @p g along it (at least one), evenly
 *  spaced, both ends included on an open wall. */
size_t pm_contact_profile_stations(const pm_contact *ct, size_t k, const pm_grid *g);

/**
 * The traction profile of surface @p k (force per unit length of wall, per unit thickness in plane
 * runs): the per-node impulses since pm_contact_profile_reset(), each shared between the two stations
 * either side of the node's position along the wall by nearness, divided by @p span (the time they were
 * gathered over) and by each station's share of the wall (a spacing; half of one at an open wall's
 * ends). Position along the wall: from the first point of a polyline or polygon along its points; on a
 * circle counter-clockwise from its +x point; on a straight grid side or line from its lowest node (or
 * the frame's side), upwards or rightwards. @p out holds pm_contact_profile_stations() entries.
 * @return PM_OK, PM_EINPUT for a bad request
 */
int pm_contact_profile(const pm_contact *ct, size_t k, const pm_grid *g, double span, pm_contact_station *out,
                       size_t n_out);

/** Start gathering the per-node impulses of every surface afresh. */
void pm_contact_profile_reset(pm_contact *ct);

/** Resultant force of surface @p k over the last apply. @return PM_OK, PM_EINPUT for no such surface */
int pm_contact_force_of(const pm_contact *ct, size_t k, pm_contact_force *out);

/** The laws on one node's velocity @p v (normal: outward unit normal). Return 1 when they acted. */
int pm_contact_nodal_coulomb(const double normal[PM_DIM], double mu, double v[PM_DIM]);
/** Nodal Coulomb law that lets the node approach at up to @p allowed (gap / dt) before it acts. */
int pm_contact_nodal_coulomb_gap(const double normal[PM_DIM], double mu, double allowed, double v[PM_DIM]);
/** Penalty law: the normal velocity change @p push (stiffness x penetration x dt) away from the surface,
 *  and a tangential change up to mu times it, never reversing the slip. */
int pm_contact_penalty_coulomb(const double normal[PM_DIM], double mu, double push, double v[PM_DIM]);
int pm_contact_normal_only(const double normal[PM_DIM], double v[PM_DIM]);

#endif
