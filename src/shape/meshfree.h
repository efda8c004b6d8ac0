/**
 * @file meshfree.h (internal to src/, not installed)
 * @brief Meshfree shape functions on a node cloud (GMM: `mls`, `lme`; RKPM: `rk_cubic`) and the
 *        Kronecker-delta transformation that makes them interpolate at essential-boundary nodes.
 *
 * These kinds work on a pm_cloud, not on a pm_grid, so pm_approx_create() does not make them (they
 * are the registry's node-cloud table, see pm_approx_names_for_method()): create them with
 * pm_approx_create_cloud(). The result is an ordinary pm_approx (its
 * grid is NULL): connect() refreshes the cloud's cell list (pm_cloud_update()) and evaluates every
 * material point once (eval() then returns the kept stencil), keeping per point a list of nearby
 * nodes for the next neighbour search and, for lme, the last lambda as the next Newton start.
 * pm_meshfree_eval() is stateless: it searches the cell list and allocates nothing, so evaluations
 * may run in parallel while the cloud does not change.
 *
 * All three use a linear basis. Formulas, defaults and their sources: docs/meshfree.md.
 */
#ifndef PMECH_MESHFREE_H
#define PMECH_MESHFREE_H

#include "pmech/approx.h"
#include "shape/cloud.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Tuning of a meshfree approximation; NAN (or 0 for the integers) picks the kind's default. */
typedef struct pm_meshfree_opts {
    double support_radius; /**< case key `support_radius` (m): MLS weight radius, RK kernel support a
                                (half-side of the square for the tensor kernel), LME search radius;
                                default: MLS/RK f sqrt(2 h^2), LME where exp(-beta r^2) = 1e-6 */
    double dilation;       /**< f in r = f sqrt(2 h^2) (seed 000); default 1.5 */
    double lme_gamma;      /**< case key `lme_gamma`: gamma = beta h^2; default 1.8 */
    double cond_tol;       /**< case key `max_condition`: largest 1-norm condition number of the moment
                                matrix before the support grows (default MLS 1e2, RK 1e6); LME: of the
                                Hessian J (default 1e4) */
    double growth;         /**< adaptive search: radius factor per step; default 1.25 */
    int min_nodes;         /**< adaptive search: fewest nodes; default 6 (MLS, RK), 3 (LME) */
    int lme_max_extra;     /**< LME: most nodes added one by one while cond(J) > cond_tol; default 8 */
    int rk_tensor;         /**< RK: 1 tensor-product kernel (seed 002 eq. 11), 0 radial; default 0 */
    int smoothing;         /**< gradients at the solver's points: 1 smoothed over each point's cell (stabilised
                                conforming nodal integration), -1 point gradients; 0 = default: smoothed for
                                rk_cubic (its nodes are its integration points), point gradients otherwise */
    int axisymmetric;      /**< 1: point volumes are per radian (x = radius), so a smoothing cell's area is V / x */
} pm_meshfree_opts;

/**
 * @brief Options with every field at "default" (NAN / 0), to be overridden field by field.
 * @return the options
 */
pm_meshfree_opts pm_meshfree_opts_default(void);

/**
 * @brief Create the meshfree approximation @p name ("mls", "lme" or "rk_cubic") on a node cloud.
 * @param name the `shape_function` value
 * @param cloud nodes (must outlive the approximation; connect() calls pm_cloud_update() on it)
 * @param opts tuning (NULL: all defaults)
 * @param out receives the approximation; free with pm_approx_destroy()
 * @return PM_OK, PM_EINPUT for an unknown name or a bad option, PM_ENOMEM
 */
int pm_approx_create_cloud(const char *name, pm_cloud *cloud, const pm_meshfree_opts *opts, pm_approx **out);

/**
 * @brief Whether @p a was made by pm_approx_create_cloud().
 * @param a an approximation
 * @return 1 or 0
 */
int pm_approx_is_meshfree(const pm_approx *a);

/**
 * @brief The cloud of a meshfree approximation.
 * @param a an approximation from pm_approx_create_cloud()
 * @return the cloud, or NULL for another kind
 */
pm_cloud *pm_meshfree_cloud(const pm_approx *a);

/**
 * @brief The initial (non-adapted) support or search radius in use, after defaults.
 * @param a an approximation from pm_approx_create_cloud()
 * @return the radius (m), or NAN for another kind
 */
double pm_meshfree_radius(const pm_approx *a);

/**
 * @brief Shape functions and gradients at an arbitrary point (a material point, a node, a probe).
 * @param a an approximation from pm_approx_create_cloud()
 * @param x the point
 * @param s receives nodes, N and dN/dx
 * @return PM_OK; PM_ESIM when the point has too few nodes around it, more than PM_STENCIL_MAX in
 *         the support (MLS, RK: reduce support_radius), lies outside the cloud's convex hull
 *         (LME), or the moment matrix stays ill-conditioned; PM_EINPUT for another kind
 */
int pm_meshfree_eval(const pm_approx *a, const double x[2], pm_stencil *s);

/**
 * @brief pm_meshfree_eval() at the current position of cloud node @p node, cheaper when called for
 *        the same nodes step after step (a solver moving its nodes with the interpolated field): each
 *        node keeps a list of the nodes around it for the neighbour search and, for lme, the lambda
 *        of its last solve as the start of the next. Same functions as pm_meshfree_eval() to
 *        round-off. Calls for distinct nodes may run in parallel; after moving nodes, call
 *        pm_cloud_update() (or connect()) first, as for any query.
 * @param a an approximation from pm_approx_create_cloud()
 * @param node a node index of its cloud
 * @param s receives nodes, N and dN/dx
 * @return as pm_meshfree_eval(); PM_EINPUT also for a node index out of range
 */
int pm_meshfree_eval_node(const pm_approx *a, size_t node, pm_stencil *s);

/**
 * What a meshfree approximation keeps from one connect() to the next that its shape functions depend
 * on, besides the cloud itself (pm_cloud_restore()): a checkpoint stores it. The candidate lists are
 * not part of it: a list only answers a query the cell list would answer with the same nodes in the
 * same order.
 */
typedef struct pm_meshfree_state {
    size_t n_points;  /**< points of the stencil cache (0: none made yet) */
    size_t slot;      /**< stencil entries per point: a connect() that meets a longer stencil widens the
                           cache, and a widened cache starts every point's lambda afresh */
    double *key;      /**< lme: PM_DIM per point, where it was last evaluated (NAN: never); else NULL */
    double *lam;      /**< lme: PM_DIM per point, the lambda found there, the start of its next solve;
                           else NULL */
    size_t n_nodes;   /**< nodes of the cloud */
    double *node_lam; /**< lme: PM_DIM per node, the lambda of its last pm_meshfree_eval_node(); else NULL */
} pm_meshfree_state;

/**
 * @brief The state of @p a, as pointers into it (valid until the next connect() or resize).
 * @param a an approximation from pm_approx_create_cloud()
 * @param st receives the state
 * @return PM_OK, or PM_EINPUT for another kind
 */
int pm_meshfree_state_get(const pm_approx *a, pm_meshfree_state *st);

/**
 * @brief Make the stencil cache of @p a hold @p n_points points of @p slot entries, every point not
 *        yet evaluated (lambda 0), to be filled with a stored state through pm_meshfree_state_get().
 * @param a an approximation from pm_approx_create_cloud()
 * @param n_points points (0: no cache)
 * @param slot entries per point, 1 to PM_STENCIL_MAX + 4 (the most a connect() gives)
 * @return PM_OK, PM_EINPUT for another kind or a slot out of range, PM_ENOMEM
 */
int pm_meshfree_state_resize(pm_approx *a, size_t n_points, size_t slot);

/**
 * @brief The cubic spline of seed 002 eq. 40: 2/3 - 4z^2 + 4z^3 on [0, 1/2],
 *        4/3 - 4z + 4z^2 - 4z^3/3 on [1/2, 1], 0 beyond (z >= 0).
 * @param z normalised distance |d| / a
 * @param dw receives dw/dz (may be NULL)
 * @return w(z)
 */
double pm_cubic_spline(double z, double *dw);

/**
 * @brief Linear-basis reproducing-kernel / MLS shape functions from given weights: with
 *        H_I = [1, d_I / L] (d_I = x - x_I) and M = sum w_I H_I H_I^T,
 *        N_I = w_I H(0)^T M^-1 H_I (seed 002 eq. 8-14, the same functions as seed 000 eq. 54),
 *        and dN_I from differentiating through M^-1 (dM^-1 = -M^-1 dM M^-1).
 * @param n number of nodes
 * @param d offsets x - x_I
 * @param w weights w_I(x) (> 0 for the nodes given)
 * @param dw gradients of w_I with respect to x
 * @param L length that scales the basis (the support radius), for a well-scaled M
 * @param N receives the n values
 * @param dN receives the n gradients
 * @param cond receives the 1-norm condition number of M (INFINITY when singular)
 * @return PM_OK, or PM_ESIM when M is singular (then N and dN are not set)
 */
int pm_linear_moment_shape(int n, const double (*d)[2], const double *w, const double (*dw)[2], double L,
                           double *N, double (*dN)[2], double *cond);

/**
 * Kronecker-delta transformation (seed 002 eqs. 15-21), restricted to the essential-boundary
 * nodes B (the "mixed" form): the unknowns of the nodes in B become nodal values
 * u(x_J) = sum_I N_I(x_J) d_I, J in B, the others stay coefficients. Stored are only the rows
 * Lambda_JI = N_I(x_J) for J in B, so memory is O(|B| x stencil). The transformed shape functions
 * interpolate at every J in B (N'_K(x_J) = delta_KJ) and still reproduce linear fields.
 */
typedef struct pm_kd pm_kd;

/**
 * @brief Evaluate the rows Lambda_JI = N_I(x_J) for the boundary nodes @p nodes.
 * @param a a meshfree approximation (`mls` or `rk_cubic`; `lme` already interpolates on the hull)
 * @param nb number of boundary nodes
 * @param nodes their cloud indices (distinct)
 * @param out receives the transformation; free with pm_kd_destroy()
 * @return PM_OK, PM_EINPUT (bad or repeated index, not a meshfree kind), PM_ESIM from the shape
 *         functions, PM_ENOMEM
 */
int pm_kd_create(const pm_approx *a, size_t nb, const int32_t *nodes, pm_kd **out);

/**
 * @brief Re-evaluate the rows after the nodes moved (same boundary set; no allocation).
 * @param kd the transformation
 * @param a the approximation it was created with
 * @return PM_OK or the status of pm_meshfree_eval()
 */
int pm_kd_update(pm_kd *kd, const pm_approx *a);

/**
 * @brief Evaluate row j at x_J + offsets[2 j] instead of at x_J, here and in later updates: the
 *        value is then prescribed there (RKPM: on the side a boundary node lies next to, not at the
 *        node a fraction of a spacing inside it).
 * @param kd the transformation
 * @param a the approximation it was created with
 * @param offsets 2 per row
 * @return PM_OK, PM_ENOMEM, or the status of pm_meshfree_eval()
 */
int pm_kd_set_offsets(pm_kd *kd, const pm_approx *a, const double *offsets);

/** @brief Free a transformation (NULL is fine). @param kd the transformation */
void pm_kd_destroy(pm_kd *kd);

/**
 * @brief Number of boundary nodes.
 * @param kd the transformation
 * @return |B|
 */
size_t pm_kd_size(const pm_kd *kd);

/**
 * @brief Row j of Lambda (for assembling constraints in an implicit solver).
 * @param kd the transformation
 * @param j row, 0 <= j < pm_kd_size()
 * @param node receives the boundary node index x_J of the row
 * @param cols receives the node indices I of the row
 * @param vals receives N_I(x_J)
 * @return the number of entries in the row
 */
int pm_kd_row(const pm_kd *kd, size_t j, int32_t *node, const int32_t **cols, const double **vals);

/**
 * @brief Nodal values at the boundary nodes from coefficients: val_j = sum_I N_I(x_J) c_I.
 * @param kd the transformation
 * @param coef coefficients, component @p comp of node I at coef[stride * I + comp]
 * @param stride components per node in @p coef (1 or 2)
 * @param comp component
 * @param val receives pm_kd_size() values
 */
void pm_kd_values(const pm_kd *kd, const double *coef, int stride, int comp, double *val);

/**
 * @brief Impose nodal values @p g at the boundary nodes: change only their coefficients so that
 *        sum_I N_I(x_J) c_I = g_J for every J in B (a sparse |B| x |B| solve, BiCGStab with a
 *        Jacobi preconditioner, in the transformation's own workspace: not thread-safe per kd).
 * @param kd the transformation
 * @param g prescribed values, pm_kd_size() of them
 * @param stride components per node in @p coef
 * @param comp component
 * @param coef coefficients, updated in place at the boundary nodes
 * @return PM_OK, or PM_ESIM when the solve does not reach 1e-12 relative accuracy
 */
int pm_kd_impose(pm_kd *kd, const double *g, int stride, int comp, double *coef);

#ifdef __cplusplus
}
#endif
#endif
