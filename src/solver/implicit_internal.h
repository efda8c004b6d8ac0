/* Workspace and per-point kernel of the implicit solver (src/solver/implicit*.c). */
#ifndef PMECH_IMPLICIT_INTERNAL_H
#define PMECH_IMPLICIT_INTERNAL_H

#include "solver/implicit.h"
#include "solver/sim_internal.h"
#include "linalg/sparse.h"

#include <stdint.h>

/* Everything the implicit steps need besides the simulation; sized on the first step and grown only
 * when the particle stencils need more room, so steps do not allocate once running. */
typedef struct pm_implicit_ws {
    size_t n;                 /* particles */
    size_t n_rows;            /* packed stencils: the particles', then meshfree constraint rows */
    size_t nn;                /* grid nodes */
    double dt;                /* the step being attempted */
    int quasi_static;         /* 1: no inertia */
    /* particle state at the start of the step: every Newton iteration starts from it */
    double *stress_n, *F_n, *state_n, *vol_n, *x_n, *eps_n;
    /* stencils at the start-of-step positions, packed: particle i uses [st_off[i], st_off[i+1]) */
    int32_t *st_off;
    int32_t *st_node;
    double *st_N, *st_dN;
    size_t st_cap;
    /* nodes */
    int32_t *dof;             /* 2 per node: unknown index, or -1 (prescribed or no material) */
    double *support;          /* sum of V_p N_I(x_p): the nodal volume the particles give */
    double *du;               /* displacement increment of the step, 2 per node */
    double *vn, *an;          /* nodal velocity and acceleration at the start of the step */
    double *fint, *fext;      /* internal and external force, 2 per node */
    double *fscale;           /* sum of the magnitudes of every nodal force term: the residual's scale */
    double *react;            /* reaction of the prescribed components after the last step */
    double *spring;           /* stabilisation stiffness scale per node: M touch / h^2 */
    double *touch;            /* volume of the particles whose stencil holds the node */
    double *smax;             /* largest stress magnitude among those particles */
    double *anchor;           /* quasi-static weak-node spring stiffness (weak_springs()), 0 elsewhere */
    double *K_base, *res_base;/* tangent values and residual of the iterate a correction starts from */
    size_t K_base_cap;
    /* node -> particles, for the pattern */
    int32_t *np_off, *np_idx, *mark, *nbr;
    /* unknowns */
    int n_dof;
    double *res, *sol, *du_try;
    pm_csr K;
    pm_sparse_solver *solver;
    int symmetric;            /* 1: every material gave a symmetric tangent so far this step */
    long failed_particle;     /* particle whose update failed in the last evaluation, or -1 */
} pm_implicit_ws;

/* What a point contributes to the residual and tangent, in the current configuration. */
typedef struct pm_point_contrib {
    int n;                            /* nodes of the stencil */
    double g[PM_STENCIL_MAX][2];      /* dN/dx in the current configuration */
    double hoop[PM_STENCIL_MAX];      /* N / r (axisymmetric), else 0 */
    double V;                         /* current volume (per radian in axisymmetric runs) */
    double sig[4];                    /* Cauchy stress xx, yy, zz, xy */
    double D[16];                     /* tangent on (xx, yy, zz, xy), engineering shear */
} pm_point_contrib;

/* A node carries material, and has unknowns, when its mass exceeds this. */
double pm_implicit_mass_floor(const pm_sim *s);

/* Allocate the workspace for s (first step). */
int pm_implicit_ws_alloc(pm_sim *s);

/* Start of a step: stencils at the current positions, nodal mass, velocity and acceleration, active
 * nodes and unknowns, the quasi-static stabilisation, the sparse pattern. */
int pm_implicit_setup_step(pm_sim *s, pm_implicit_ws *w);

/* Particle updates from w->du and the residual f_ext - f_int - M a on the unknowns (into w->res), and
 * the tangent (into w->K) when want_K. Returns 0, or 1 naming the failed particle in w->failed_particle. */
int pm_implicit_evaluate(pm_sim *s, pm_implicit_ws *w, int want_K);

/* Add lambda * spring to the diagonal of the tangent (a Levenberg-Marquardt-like damping of the
 * Newton correction). */
void pm_implicit_regularise(pm_implicit_ws *w, double lambda);

/*
 * Update particle i from the start-of-step state with the nodal displacement increments du: F, stress,
 * state, volume and plastic strain are written to the particle arrays. Fills c (the tangent only when
 * want_tangent). Returns 0, or 1 if the point failed (inverted, NaN, model failure).
 */
int pm_implicit_point(pm_sim *s, pm_implicit_ws *w, size_t i, const double *du, int want_tangent,
                      pm_point_contrib *c);

#endif
