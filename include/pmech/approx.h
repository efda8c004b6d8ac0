/**
 * @file approx.h
 * @brief How a material point sees the nodes: connectivity and shape functions N_I(x_p) with
 *        gradients. MPM, GMM and RKPM differ only in the approximation plugged in here.
 */
#ifndef PMECH_APPROX_H
#define PMECH_APPROX_H

#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of nodes one point may be connected to. */
#define PM_STENCIL_MAX 64

/** The nodes a point talks to, their shape function values and gradients. */
typedef struct pm_stencil {
    int n;                           /**< number of nodes */
    int32_t node[PM_STENCIL_MAX];    /**< node indices */
    double N[PM_STENCIL_MAX];        /**< shape function values */
    double dN[PM_STENCIL_MAX][2];    /**< shape function gradients (d/dx, d/dy) */
} pm_stencil;

typedef struct pm_approx pm_approx;

/**
 * Methods an approximation serves, the bits of pm_approx_ops::methods: bit m stands for the
 * pm_method m of case.h (PM_METHOD_MPM = 0, GMM = 1, RKPM = 2), so `1u << c->method` tests a case.
 */
enum {
    PM_APPROX_MPM = 1u << 0,   /**< grid kinds, for `method: mpm` */
    PM_APPROX_GMM = 1u << 1,   /**< node-cloud kinds of the generalized meshfree method */
    PM_APPROX_RKPM = 1u << 2   /**< node-cloud kinds of the reproducing kernel particle method */
};

/** Operations of an approximation; one static table per kind. */
typedef struct pm_approx_ops {
    const char *name;  /**< the `shape_function` value, e.g. "linear" */
    unsigned methods;  /**< PM_APPROX_* bits of the methods that may use this kind */
    /**
     * 1: the functions take the nodal values at the nodes where essential conditions are imposed
     * (Kronecker delta there: linear; lme on the boundary of its hull), so those values can be set
     * directly; 0: they only approximate them (mls, rk_cubic, gimp, bspline2), and a meshfree
     * solver must transform the nodal unknowns to impose them.
     */
    int interpolating;
    /** 1: on a structured quad4 grid pm_linear_quad_eval() gives exactly this kind's functions. */
    int linear_quad_fast;
    /**
     * Rebuild connectivity for all points (MPM: locate the cell of each point into p->cell;
     * meshfree: neighbour search). Returns PM_OK or PM_ESIM naming a particle that left the grid.
     */
    int (*connect)(pm_approx *a, pm_particles *p);
    /** Fill N and dN/dx for point @p ip. Returns PM_OK or PM_ESIM. */
    int (*eval)(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s);
    /** Free private data (may be NULL). */
    void (*destroy)(pm_approx *a);
    /**
     * Check that the kind fits the grid and set up private data from the creation options (may be
     * NULL). Called once by pm_approx_create_opts(); returns PM_OK or PM_EINPUT/PM_ENOMEM.
     */
    int (*init)(pm_approx *a);
} pm_approx_ops;

/** Tuning keys of the case file that approximations read (docs/input.md: `lme_gamma`, `support_radius`). */
typedef struct pm_approx_opts {
    double lme_gamma;       /**< LME: gamma = beta h^2; NAN = the default (1.8) */
    double support_radius;  /**< meshfree/LME support radius in metres; NAN = from the kind's tolerance */
} pm_approx_opts;

/**
 * @brief Create the approximation called @p name on grid @p g.
 * @param name a `shape_function` value
 * @param g grid (must outlive the approximation)
 * @param out receives a new approximation; free with pm_approx_destroy()
 * @return PM_OK, PM_EINPUT for an unknown name or one that does not fit the grid
 */
int pm_approx_create(const char *name, const pm_grid *g, pm_approx **out);

/**
 * @brief Create the approximation called @p name on grid @p g with the case's tuning keys.
 * @param name a `shape_function` value
 * @param g grid (must outlive the approximation)
 * @param opts tuning keys (NULL: all defaults)
 * @param out receives a new approximation; free with pm_approx_destroy()
 * @return PM_OK, PM_EINPUT for an unknown name or one that does not fit the grid, PM_ENOMEM
 */
int pm_approx_create_opts(const char *name, const pm_grid *g, const pm_approx_opts *opts, pm_approx **out);

/** @brief Destroy an approximation (NULL is fine). */
void pm_approx_destroy(pm_approx *a);

/** @brief Names of the grid approximations (pm_approx_create()), NULL-terminated (for messages and "did you mean"). */
const char *const *pm_approx_names(void);

/**
 * @brief Every `shape_function` name, the grid kinds then the node-cloud kinds, each name once
 *        (lme is both): the values a case file may give.
 * @param out receives at most @p cap - 1 names and a terminating NULL
 * @param cap entries of @p out (>= 1)
 * @return the number of names written (without the NULL)
 */
size_t pm_approx_all_names(const char **out, size_t cap);

/**
 * @brief The `shape_function` names that method @p method serves, the method's default first
 *        (mpm: linear, gimp, bspline2, lme; gmm: mls, lme; rkpm: rk_cubic).
 * @param method a pm_method value (case.h)
 * @param out receives at most @p cap - 1 names and a terminating NULL
 * @param cap entries of @p out (>= 1)
 * @return the number of names written (without the NULL); 0 for an unknown method
 */
size_t pm_approx_names_for_method(int method, const char **out, size_t cap);

/**
 * @brief Whether the kind called @p name serves method @p method (on a grid for mpm, on a node
 *        cloud for gmm and rkpm).
 * @param name a `shape_function` value
 * @param method a pm_method value (case.h)
 * @return 1 or 0 (0 also for an unknown name or method)
 */
int pm_approx_serves(const char *name, int method);

/**
 * @brief The ops table of kind @p name as used by method @p method (the grid lme for mpm, the
 *        cloud lme for gmm), for asking its capabilities before anything is created.
 * @param name a `shape_function` value
 * @param method a pm_method value (case.h)
 * @return the table, or NULL when the method has no kind of that name
 */
const pm_approx_ops *pm_approx_find(const char *name, int method);

/**
 * @brief Rebuild the connectivity of all points (MPM: the cell of each point; meshfree: the
 *        neighbour search). Needed after points move and before pm_approx_eval().
 * @param a the approximation
 * @param p the points
 * @return PM_OK, or PM_ESIM naming a particle that left the grid
 */
int pm_approx_connect(pm_approx *a, pm_particles *p);

/**
 * @brief The nodes point @p ip talks to, with shape function values and gradients.
 * @param a the approximation (connected to @p p)
 * @param p the points
 * @param ip index of the point
 * @param s receives the stencil
 * @return PM_OK or PM_ESIM
 */
int pm_approx_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s);

/**
 * @brief The kind of an approximation, to ask its name and capabilities.
 * @param a the approximation
 * @return its ops table
 */
const pm_approx_ops *pm_approx_kind(const pm_approx *a);

#ifdef __cplusplus
}
#endif
#endif
