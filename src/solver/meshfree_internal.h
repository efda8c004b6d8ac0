/* GMM and RKPM inside the MPM solvers (src/solver/meshfree_*.c): the node cloud that replaces the
 * grid, nodes that move with the material, essential conditions through the Kronecker-delta rows
 * (frictional walls are contact surfaces, src/contact). */
#ifndef PMECH_MESHFREE_INTERNAL_H
#define PMECH_MESHFREE_INTERNAL_H

#include "shape/cloud.h"
#include "shape/meshfree.h"
#include "solver/sim_internal.h"

struct pm_implicit_ws;

typedef struct pm_mf {
    pm_grid background;      /* the case's grid: it creates the nodes and frames output and pictures */
    pm_cloud *cloud;         /* the nodes; s->grid.x aliases cloud->x */
    int rkpm;                /* 1: the nodes are the particles */
    int transform;           /* 1 (mls, rk_cubic): essential conditions through Lambda rows */
    pm_kd *kd[2];            /* per component: rows N_I(x_J) of the nodes J whose component is prescribed */
    int32_t *kd_nodes[2];    /* those nodes J */
    double *g;               /* prescribed values, max |B| */
    int history;             /* implicit: vh, ah hold the nodal velocity and acceleration of the last step */
    double *vh, *ah;         /* 2 per node */
    double *g_nodes;         /* 2 per node: the nodes' displacement of the step */
    int failed;              /* an imposition of the essential conditions did not converge */
} pm_mf;

/* Replace the case's grid by the node cloud after the particles are seeded: GMM nodes are the
 * nodes of the cells holding particles, RKPM nodes the particles; named sides become node sets. */
int pm_mf_create(pm_sim *s, int n_threads);

/* After the nodal arrays and the conditions exist: with mls and rk_cubic the prescribed components
 * move from nodal flags to Lambda rows. */
int pm_mf_setup_conditions(pm_sim *s);

void pm_mf_destroy(pm_sim *s);

/* Explicit steps: give the nodes in the Lambda rows coefficients that make the interpolated
 * velocity (what = 0, values from vfix) or acceleration (what = 1, zero) what is prescribed. */
void pm_mf_impose(pm_sim *s, double *nodal, int what);

/* Explicit steps, end of grid_update: impose on the start and end-of-step velocities, then the
 * accelerations of those nodes again as (v_new - v) / dt. */
void pm_mf_impose_update(pm_sim *s, double dt);

/* End of an explicit step: move the nodes with their velocity (RKPM: to the particles), refresh
 * the Lambda rows. */
int pm_mf_after_explicit(pm_sim *s, double dt, const double *vel);

/* End of an implicit step: move the nodes by du and keep v, a at the nodes for the next predictor. */
int pm_mf_after_implicit(pm_sim *s, const double *du, const double *v, const double *a);

/* After a checkpoint put the cloud back (src/io/checkpoint_meshfree.c): the Lambda rows evaluated at the
 * restored nodes, as the end of the step that wrote it left them. */
int pm_mf_restored(pm_sim *s);

/* Implicit predictor: the nodes' own v, a from the last step where they have them. */
void pm_mf_nodal_history(const pm_sim *s, double *vn, double *an);

/* Implicit: number of constraint rows (|B_x| + |B_y|), their packed stencils after the particles',
 * and their penalty terms in the residual and tangent. */
size_t pm_mf_constraint_rows(const pm_sim *s);
int pm_mf_constraint_stencil(const pm_sim *s, size_t row, const int32_t **cols, const double **vals);
void pm_mf_penalty(pm_sim *s, struct pm_implicit_ws *w, int want_K);

#endif
