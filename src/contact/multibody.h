/*
 * Body-body contact on the background grid (the case's contact_pairs): every contact group of bodies
 * and sources has a field of its own, a full copy of the nodal arrays. Field f of grid node n is
 * entry f * n_nodes + n of every pm_nodal array, and a particle's stencil names the nodes of its
 * own field (pm_multibody::offset_of_body), so the particle passes and the grid updates of the
 * explicit step run unchanged over all fields as if they were one larger grid; without
 * contact_pairs there is one field and nothing here runs.
 *
 * Where two fields carry mass at one node the bodies may meet. Per step:
 *   pm_multibody_prepare  after the particle-to-grid pass: the nodes shared by two fields or more;
 *                         at those only, every field's volume gradient (a particle pass), its outward
 *                         normal, and, for the pairs that ask for it, its front: how far its
 *                         particles' own domains reach along that normal (a second particle pass).
 *   pm_multibody_apply    after the end-of-step velocities: the pair's law at every shared node
 *                         (no_slip: the centre-of-mass velocity, exactly the single-field result;
 *                         frictionless and coulomb: the nodal Coulomb law of contact.h on the
 *                         velocity relative to the centre of mass, when the fields approach and, with
 *                         the extent check, their particles' domains touch), then every field's
 *                         boundary contact surfaces (contact.h), then acc = (v - v0) / dt_acc there.
 *   pm_multibody_project  re-projected velocities (MUSL, USF start, predictor): the approaching
 *                         normal velocity only, as pm_contact_project_normal does for surfaces.
 *
 * The normal. At a node shared by fields a and b the outward normal of a is the unit volume gradient
 * (sum of V_p grad N_I(x_p) over a field's particles, which points from the particles to the node:
 * out of the body) of whichever of the two fills more of the node's support (the larger nodal
 * volume sum V_p N_I), a's own or b's reversed. The two fields thus get exactly opposite normals, so
 * the impulses they exchange cancel and momentum is kept to round-off. Taking the fuller body's
 * gradient rather than the difference of both matters at a body's corners: where a block's corner
 * rests on a flat slope, the block covers the node with one cell and its gradient leans out along
 * the slope, which would make a frictionless block plough; the slope's gradient there is the true
 * normal. Volumes rather than masses keep a dense body from dictating the normal of a light one.
 *
 * The contact test. Approaching (v_a - v_cm) . n_a > 0 alone fires as soon as two bodies share a
 * node, up to a cell before they touch. The extent check also asks that the particles' domains
 * meet: a particle fills the parallelogram F [-h, h] about its position (h its initial half-size),
 * whose reach along n is x_p . n + sum_j |(F^T n)_j| h_j; field a's front is the largest reach of its
 * particles in the node's support, and two fields touch when front_a + front_b >= 0 (b's rear along
 * n_a is -front_b). With three fields or more at a node, each field acts against the centre of mass
 * of all, with the law and front of the heaviest other field there.
 *
 * Boundary surfaces and obstacles (contact.h) act on every field: pm_contact_apply runs once per field
 * on that field's part of the arrays, and the surfaces' forces are summed over the fields. Their gaps
 * (pm_contact_gaps) come from the particles of all bodies, so at a node where two fields carry mass
 * next to an obstacle that one of them touches, the other is held back there as well.
 *
 * The force between a pair is m (v_after - v_before) / dt summed over the shared nodes of the
 * heavier-partner field a (on a, from b), over the last apply; pm_multibody_log_* average it over
 * the rows of contact_forces.csv.
 */
#ifndef PMECH_CONTACT_MULTIBODY_H
#define PMECH_CONTACT_MULTIBODY_H

#include "contact/contact.h"
#include "pmech/case.h"
#include "solver/sim_internal.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/** The fields, their pair laws and the per-step work arrays (all sized at creation). */
typedef struct pm_multibody {
    int n_fields;
    size_t n_nodes;            /**< grid nodes per field */
    size_t n_bodies;           /**< body indices: the case's bodies, then its sources */
    int32_t *field_of_body;    /**< body index -> field */
    int32_t *offset_of_body;   /**< body index -> field * n_nodes */
    const char **name;         /**< contact group of each field */
    uint8_t *law;              /**< pm_pair_law of fields a, b at [a * n_fields + b] */
    double *mu;                /**< Coulomb coefficient of a pair (0 frictionless) */
    uint8_t *extent;           /**< 1: the pair's contact test asks the particles' domains to meet */
    int any_extent;            /**< some pair uses the extent check */
    uint8_t *shared;           /**< per grid node: 1 when two fields or more carry mass there */
    int32_t *list;             /**< the shared nodes of this step */
    size_t n_list;
    double *vol;               /**< nodal volume sum V_p N_I, per field node (shared nodes only) */
    double *grad;              /**< volume gradient, PM_DIM per field node (shared nodes only) */
    double *normal;            /**< outward unit normal, PM_DIM per field node (0: none) */
    double *front;             /**< reach of the field's particles along its normal, per field node */
    double *pair_force;        /**< force on a from b over the last apply, PM_DIM at [a * n_fields + b] */
    double *pair_impulse;      /**< sum of pair_force dt since the last log row */
    double impulse_time;       /**< time those impulses cover */
    pm_contact_force *surface_sum; /**< boundary surfaces' forces summed over the fields */
    size_t n_surfaces;
    FILE *log;                 /**< contact_forces.csv (NULL: not written) */
} pm_multibody;

/**
 * The fields of @p c (one per distinct contact group of its bodies and sources, in order of first
 * appearance) and the laws of their pairs (no_slip for pairs not listed), for a grid of @p n_nodes.
 * *out is NULL when the case has no contact_pairs.
 * @return PM_OK, PM_EINPUT (too many fields x nodes for 32-bit node numbers), PM_ENOMEM
 */
int pm_multibody_create(const pm_case *c, size_t n_nodes, pm_multibody **out);

/** Free (NULL is fine); closes the log. */
void pm_multibody_destroy(pm_multibody *mb);

/** Copy field 0's prescribed components (fixed, vfix: where the conditions were set up) to every
 *  other field. */
void pm_multibody_copy_conditions(const pm_multibody *mb, pm_nodal *nd);

/** After the contact surfaces exist: room for their per-field force sums. @return PM_OK, PM_ENOMEM */
int pm_multibody_attach_surfaces(pm_multibody *mb, size_t n_surfaces);

/** The field of particle @p i's body. */
static inline int pm_multibody_field_of(const pm_multibody *mb, const pm_particles *p, size_t i)
{
    return mb->field_of_body[p->body[i]];
}

/** After the particle-to-grid pass: shared nodes, normals and fronts (see the top). */
void pm_multibody_prepare(pm_sim *s);

/** End-of-step velocities @p v (start-of-step s->nd.vel): the pair laws, the boundary surfaces of
 *  every field, and acc = (v - v0) / dt_acc at the nodes they touched. */
void pm_multibody_apply(pm_sim *s, double *v, double dt, double dt_acc);

/** The mass of entry @p e (field e / n_nodes at grid node e % n_nodes) that measures how light it is
 *  in USL's strain rate (pm_xp_grid_usl_strain_velocity): the fields' summed mass at the node when the
 *  field's heaviest partner there holds it by a no_slip pair (they move as one field would, and a
 *  single field has that mass), else the entry's own. */
double pm_multibody_strain_mass(const pm_sim *s, size_t e);

/** Re-projected velocities @p v: approaching normal velocities removed between fields and at the
 *  boundary surfaces, no_slip pairs at their centre of mass. */
void pm_multibody_project(pm_sim *s, double *v);

/** Open @p dir/contact_forces.csv (header: time, then per listed pair its force components, normal
 *  and tangential parts) and write the row of t = 0. */
int pm_multibody_log_open(pm_multibody *mb, const pm_case *c, const char *dir);

/** Add the last step's pair forces over @p dt to the running impulses. */
void pm_multibody_log_step(pm_multibody *mb, double dt);

/** A row at time @p t: each listed pair's mean force since the last row, on its first group from
 *  its second. @return PM_OK, PM_EIO */
int pm_multibody_log_row(pm_multibody *mb, const pm_case *c, double t);

/** Close the log. @return PM_OK, PM_EIO */
int pm_multibody_log_close(pm_multibody *mb);

#endif
