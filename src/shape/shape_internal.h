/* Helpers shared by the approximations in src/shape (not public). */
#ifndef PMECH_SHAPE_INTERNAL_H
#define PMECH_SHAPE_INTERNAL_H

#include "approx_internal.h"
#include "shape/cloud.h"
#include "shape/meshfree.h"

/* Defaults of the LME kinds, on the grid (lme.c) and on a node cloud (lme_cloud.c) alike. */
#define PM_LME_DEFAULT_GAMMA 1.8 /* gamma = beta h^2 (Arroyo & Ortiz's usual choice) */
#define PM_LME_PRIOR_TOL 1e-6    /* the default support ends where the Gaussian prior falls to this */
/* Candidates of one neighbour query; more nodes than this in a support is a mis-set radius anyway. */
#define PM_SHAPE_CAND_MAX 1024

/**
 * A kind that works on a node cloud (pm_approx_create_cloud()): its ops and the set-up of its
 * private data. init(a, cloud, opts) gets @p a with ops set and fills data and opts, or returns
 * PM_EINPUT (a bad option) / PM_ENOMEM leaving a->data NULL.
 */
typedef struct pm_cloud_kind {
    const pm_approx_ops *ops;
    int (*init)(pm_approx *a, pm_cloud *cloud, const pm_meshfree_opts *opts);
} pm_cloud_kind;

/** The registry entry of a node-cloud kind, or NULL for a grid kind. */
const pm_cloud_kind *pm_cloud_kind_of(const pm_approx_ops *ops);

/* The node-cloud kinds (meshfree.c), collected by the registry in approx.c. */
extern const pm_approx_ops pm_approx_mls_ops;
extern const pm_approx_ops pm_approx_lme_cloud_ops;
extern const pm_approx_ops pm_approx_rk_cubic_ops;
/** Set up mls on @p cloud (pm_cloud_kind::init). */
int pm_mf_init_mls(pm_approx *a, pm_cloud *cloud, const pm_meshfree_opts *opts);
/** Set up lme on @p cloud (pm_cloud_kind::init). */
int pm_mf_init_lme(pm_approx *a, pm_cloud *cloud, const pm_meshfree_opts *opts);
/** Set up rk_cubic on @p cloud (pm_cloud_kind::init). */
int pm_mf_init_rk(pm_approx *a, pm_cloud *cloud, const pm_meshfree_opts *opts);

/**
 * Locate the background cell of every particle into p->cell (in parallel with a->n_threads),
 * starting each search from the particle's previous cell. Returns PM_OK or PM_ESIM naming the
 * highest-numbered particle outside the grid.
 */
int pm_shape_connect_cells(pm_approx *a, pm_particles *p);

/**
 * Tensor-product stencil on a structured grid from 1-D weights: node (ix[i], iy[j]) gets
 * N = wx[i] wy[j] and gradient (dwx[i] wy[j] / hx, wx[i] dwy[j] / hy), where dw are derivatives with
 * respect to the coordinate in cell units. Nodes whose value and gradient all vanish are left out.
 */
void pm_shape_tensor_stencil(const pm_grid *g, int nx, const int *ix, const double *wx, const double *dwx,
                             int ny, const int *iy, const double *wy, const double *dwy, pm_stencil *s);

/**
 * Linear (isoparametric bilinear) shape functions of an arbitrary convex quad4 cell at xp: the
 * inverse map (xi, eta) is found by Newton's method from the cell centre.
 * @return 0, or -1 when the Newton iteration does not converge (degenerate cell)
 */
int pm_quad4_iso_eval(const pm_grid *g, int32_t cell, const double xp[2], pm_stencil *s);

/**
 * Inverse isoparametric map of quad4 cell @p cell: (xi, eta) in [-1, 1]^2 for points inside.
 * @return number of Newton iterations (>= 0), or -1 without convergence
 */
int pm_quad4_inverse_map(const pm_grid *g, int32_t cell, const double xp[2], double xi[2]);

/**
 * @brief pm_cloud_query() for the meshfree kinds: no argument checks (x and r finite, r >= 0), and
 *        the offsets d_I = x - x_I come with the nodes, so the caller need not read the positions
 *        again.
 * @param c the cloud
 * @param x query point
 * @param r radius
 * @param cap capacity of @p idx, @p d and @p d2
 * @param idx receives node indices
 * @param d receives x - x_I (may be NULL)
 * @param d2 receives |x - x_I|^2 (may be NULL)
 * @return the number of nodes with |x - x_I| < r (only the first @p cap are written)
 */
int pm_cloud_gather(const pm_cloud *c, const double x[2], double r, int cap, int32_t *idx, double (*d)[2],
                    double *d2);

/** Newton tolerance of the LME solve, relative to the node spacing h: |sum N_I (x - x_I)| <= tol h. */
#define PM_LME_TOL 1e-14

/**
 * @brief LME residual r = sum p_I d_I and Hessian J = sum p_I (d_I - r)(d_I - r)^T.
 * @param n number of nodes
 * @param d offsets x - x_I
 * @param p weights (shape function values)
 * @param r receives the residual
 * @param J receives xx, xy, yy of the Hessian
 */
void pm_lme_resid_hess(int n, const double (*d)[2], const double *p, double r[2], double J[3]);

/**
 * Local max-ent shape functions (seed 003 section 2.3) of a point at offsets d_I = x - x_I from
 * @p n nodes: N_I = exp(-beta |d_I|^2 + lambda . d_I) / Z with lambda from Newton's method on
 * log Z (residual r = sum N_I d_I, Hessian J = sum N_I d_I d_I^T - r r^T, backtracking line
 * search), gradients from eq. 39, grad N_I = -N_I J^-1 d_I.
 * @param n number of nodes (>= 3, not all on one line)
 * @param d offsets x - x_I
 * @param beta beta > 0
 * @param tol absolute tolerance on |r|
 * @param lambda in: starting guess (0, 0 is fine); out: the solution
 * @param N receives the n values
 * @param dN receives the n gradients
 * @return Newton iterations taken (>= 0), or -1 if the solve did not converge in 100 iterations
 */
int pm_lme_solve(int n, const double (*d)[2], double beta, double tol, double lambda[2], double *N,
                 double (*dN)[2]);

/**
 * pm_lme_solve() without the gradients: the Newton iteration alone, which also hands back the
 * residual and Hessian it last formed (at the returned lambda and N), so that a caller computing
 * its own gradients need not form them again.
 * @param n number of nodes (>= 3, not all on one line)
 * @param d offsets x - x_I
 * @param beta beta > 0
 * @param tol absolute tolerance on |r|
 * @param lambda in: starting guess; out: the solution
 * @param N receives the n values
 * @param r receives the final residual sum N_I d_I
 * @param J receives the final Hessian (xx, xy, yy), sum N_I (d_I - r)(d_I - r)^T
 * @return Newton iterations taken (>= 0), or -1 if the solve did not converge
 */
int pm_lme_newton(int n, const double (*d)[2], double beta, double tol, double lambda[2], double *N, double r[2],
                  double J[3]);

#endif
